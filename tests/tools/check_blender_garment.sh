#!/bin/sh
# Blender plays a garment on a moving body back: scenes/jump_tabard.json (a sewn tabard on the
# skinned, jumping BCN_Epileptic.X) for 12 frames, every 2nd exported, as the cloth's PC2 (on
# the OBJ beside it) and the character's --export-colliders folder (its mesh.pc2 on its first
# frame's OBJ); blender_mesh_cache.py checks each against the OBJ of the last frame, in world
# space. Skipped (exit 77) without Debian's `blender`, a failure under CLOTHSIM_REQUIRE_BLENDER=1
# (as check_blender_pc2.sh).
# usage: check_blender_garment.sh CLOTHSIM SCENE blender_mesh_cache.py OUTDIR
set -u
bin=$1 scene=$2 script=$3 dir=$4
. "$(dirname "$0")/blender_playback.sh"
frames=12
"$bin" simulate "$scene" --backend cpu --frames $frames --export "$dir/cloth.pc2" --export-colliders "$dir/body/" \
  --export-every 2 || fail "simulate .pc2"
"$bin" simulate "$scene" --backend cpu --frames $frames --export "$dir/frames/" --export-every 2 || fail "simulate DIR/"
last=$(printf '%s/frames/frame_%04d.obj' "$dir" $frames)
body_last=$(printf '%s/body/mesh0/frame_%04d.obj' "$dir" $frames)
for f in "$last" "$body_last" "$dir/body/mesh0/mesh.pc2"; do [ -f "$f" ] || fail "$f was not written"; done
play_back "$dir/cloth.obj" "$dir/cloth.pc2" "$last" $frames 2 tabard
play_back "$dir/body/mesh0/frame_0000.obj" "$dir/body/mesh0/mesh.pc2" "$body_last" $frames 2 body
