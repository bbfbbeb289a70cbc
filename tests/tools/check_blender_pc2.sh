#!/bin/sh
# Blender plays clothsim's point cache back: a PC2 of a 33x17 cloth (every 2nd frame) on the OBJ
# beside it, through the Mesh Cache modifier, must match the OBJ of the last frame
# (blender_mesh_cache.py does the checking). Needs Debian's `blender` package
# (scripts/install-deps --blender): without it the test is skipped (exit 77), or fails under
# CLOTHSIM_REQUIRE_BLENDER=1, which CI sets (.ci/run installs it).
# usage: check_blender_pc2.sh CLOTHSIM SCENE blender_mesh_cache.py OUTDIR
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
small="--set cloth.num_width_points=33 --set cloth.num_height_points=17 --set cloth.pinned=[[0,0],[32,0]]"
frames=10
# shellcheck disable=SC2086 # the --set words split on purpose
"$bin" simulate "$scene" --backend cpu $small --frames $frames --export "$dir/cloth.pc2" --export-every 2 || fail "simulate .pc2"
# shellcheck disable=SC2086
"$bin" simulate "$scene" --backend cpu $small --frames $frames --export "$dir/frames/" --export-every 2 || fail "simulate DIR/"
last=$(printf '%s/frames/frame_%04d.obj' "$dir" $frames)
[ -f "$last" ] || fail "$last was not written"
blender -b --factory-startup --python-exit-code 1 --python "$script" -- "$dir/cloth.obj" "$dir/cloth.pc2" "$last" $frames 2 \
  >"$dir/blender.log" 2>&1
code=$?
grep -E '^(ok|wm\.|import_scene\.)|Error|assert' "$dir/blender.log"
[ $code -eq 0 ] || { tail -20 "$dir/blender.log"; fail "blender exit $code"; }
grep -q '^ok: Mesh Cache plays the PC2 back' "$dir/blender.log" || fail "blender did not finish the checks"
