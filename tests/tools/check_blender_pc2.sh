#!/bin/sh
# Blender plays clothsim's point cache back: a PC2 of a 33x17 cloth (every 2nd frame) on the OBJ
# beside it, through the Mesh Cache modifier, must match the OBJ of the last frame
# (blender_mesh_cache.py does the checking). Needs Debian's `blender` package
# (scripts/install-deps --blender): without it the test is skipped (exit 77), or fails under
# CLOTHSIM_REQUIRE_BLENDER=1, which CI sets (.ci/run installs it).
# usage: check_blender_pc2.sh CLOTHSIM SCENE blender_mesh_cache.py OUTDIR
set -u
bin=$1 scene=$2 script=$3 dir=$4
. "$(dirname "$0")/blender_playback.sh"
small="--set cloth.num_width_points=33 --set cloth.num_height_points=17 --set cloth.pinned=[[0,0],[32,0]]"
frames=10
# shellcheck disable=SC2086 # the --set words split on purpose
"$bin" simulate "$scene" --backend cpu $small --frames $frames --export "$dir/cloth.pc2" --export-every 2 || fail "simulate .pc2"
# shellcheck disable=SC2086
"$bin" simulate "$scene" --backend cpu $small --frames $frames --export "$dir/frames/" --export-every 2 || fail "simulate DIR/"
last=$(printf '%s/frames/frame_%04d.obj' "$dir" $frames)
[ -f "$last" ] || fail "$last was not written"
play_back "$dir/cloth.obj" "$dir/cloth.pc2" "$last" $frames 2 cloth
