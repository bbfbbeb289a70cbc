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
if ! command -v blender >/dev/null; then
  if [ "${CLOTHSIM_REQUIRE_BLENDER:-0}" = 1 ]; then
    echo "FAIL: blender is not installed and CLOTHSIM_REQUIRE_BLENDER=1 (scripts/install-deps --blender)"
    exit 1
  fi
  echo "skipped: blender is not installed (scripts/install-deps --blender)"
  exit 77
fi
rm -rf "$dir"
mkdir -p "$dir"
fail() { echo "FAIL: $*"; exit 1; }
frames=12
"$bin" simulate "$scene" --backend cpu --frames $frames --export "$dir/cloth.pc2" --export-colliders "$dir/body/" \
  --export-every 2 || fail "simulate .pc2"
"$bin" simulate "$scene" --backend cpu --frames $frames --export "$dir/frames/" --export-every 2 || fail "simulate DIR/"
last=$(printf '%s/frames/frame_%04d.obj' "$dir" $frames)
body_last=$(printf '%s/body/mesh0/frame_%04d.obj' "$dir" $frames)
for f in "$last" "$body_last" "$dir/body/mesh0/mesh.pc2"; do [ -f "$f" ] || fail "$f was not written"; done
play() {  # MESH CACHE LAST NAME
  blender -b --factory-startup --python-exit-code 1 --python "$script" -- "$1" "$2" "$3" $frames 2 \
    >"$dir/blender_$4.log" 2>&1
  code=$?
  grep -E '^(ok|wm\.|import_scene\.)|Error|assert' "$dir/blender_$4.log"
  [ $code -eq 0 ] || { tail -20 "$dir/blender_$4.log"; fail "blender exit $code on the $4"; }
  grep -q '^ok: Mesh Cache plays the PC2 back' "$dir/blender_$4.log" || fail "blender did not finish the $4's checks"
}
play "$dir/cloth.obj" "$dir/cloth.pc2" "$last" tabard
play "$dir/body/mesh0/frame_0000.obj" "$dir/body/mesh0/mesh.pc2" "$body_last" body
