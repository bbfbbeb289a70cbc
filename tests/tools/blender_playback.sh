# Sourced by the Blender playback checks (check_blender_pc2.sh, check_blender_garment.sh), with
# `dir` (their output folder) and `script` (blender_mesh_cache.py) set. Without Debian's
# `blender` a check is skipped (exit 77), or fails under CLOTHSIM_REQUIRE_BLENDER=1, which CI
# sets (.ci/run installs it); with it, `dir` is made empty, `fail` says why and exits 1, and
# `play_back` runs the Mesh Cache check.
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
# play_back MESH.obj CACHE.pc2 LAST.obj FRAME EVERY NAME: Blender plays CACHE on MESH and must
# reach LAST at FRAME (blender_mesh_cache.py); its log is DIR/blender_NAME.log.
play_back() {
  blender -b --factory-startup --python-exit-code 1 --python "$script" -- "$1" "$2" "$3" "$4" "$5" \
    >"$dir/blender_$6.log" 2>&1
  code=$?
  grep -E '^(ok|wm\.|import_scene\.)|Error|assert' "$dir/blender_$6.log"
  [ $code -eq 0 ] || { tail -20 "$dir/blender_$6.log"; fail "blender exit $code on the $6"; }
  grep -q '^ok: Mesh Cache plays the PC2 back' "$dir/blender_$6.log" || fail "blender did not finish the $6's checks"
}
