#!/bin/sh
# A deliberately unstable run (ks 1e9 on a 7x5 cloth, far too stiff for 30 substeps) must stop
# with the divergence message and exit 1; `simulate --export` must still write a finite OBJ
# (the last frame that passed the check), and `render` must write no frame of the blown-up cloth.
# usage: check_divergence_cli.sh CLOTHSIM SCENE simulate|render cpu|gpu OUTDIR
# Without an OpenGL 4.3 context (exit 3) the GPU variant is skipped (exit 77), unless
# CLOTHSIM_REQUIRE_GPU=1 makes that a failure.
set -u
bin=$1 scene=$2 command=$3 backend=$4 dir=$5
mkdir -p "$dir"
unstable="--set cloth.num_width_points=7 --set cloth.num_height_points=5 --set cloth.ks=1e9 --set simulation.self_collision=false"
case $command in
  simulate) out="$dir/unstable_$backend.obj"; rm -f "$out"
            set -- simulate "$scene" --frames 100 --backend "$backend" --export "$out" ;;
  render)   out="$dir/unstable_render_$backend"; rm -rf "$out"
            set -- render "$scene" --frames 100 --backend "$backend" --size 64x48 --out "$out" ;;
  *) echo "unknown command $command"; exit 2 ;;
esac
# shellcheck disable=SC2086 # the --set words split on purpose
"$bin" "$@" $unstable >"$dir/stdout.txt" 2>"$dir/stderr.txt"
code=$?
cat "$dir/stdout.txt" "$dir/stderr.txt"
if [ $code -eq 3 ]; then
  if [ "${CLOTHSIM_REQUIRE_GPU:-}" = 1 ]; then echo "FAIL: no OpenGL 4.3 context (CLOTHSIM_REQUIRE_GPU=1)"; exit 1; fi
  echo "skipped: no OpenGL 4.3 context"; exit 77
fi
fail() { echo "FAIL: $*"; exit 1; }
[ $code -eq 1 ] || fail "exit code $code, expected 1"
grep -q '^error: the simulation diverged at frame [0-9]*: .*Likely cause: the springs are too stiff for the time step.*--set simulation.simulation_steps=[0-9]*$' "$dir/stderr.txt" \
  || fail "no divergence message on stderr"
frame=$(sed -n 's/^error: the simulation diverged at frame \([0-9]*\):.*/\1/p' "$dir/stderr.txt")
if [ "$command" = simulate ]; then
  grep -qx "wrote $out (frame $((frame - 1)), the last one that passed the divergence check)" "$dir/stdout.txt" \
    || fail "no 'wrote $out (frame $((frame - 1)), ...)' line"
  [ "$(grep -c '^v ' "$out")" -eq 35 ] || fail "$out does not have 35 vertices"
  [ "$(grep -c '^f ' "$out")" -eq 48 ] || fail "$out does not have 48 triangles"
  if grep -qiE 'nan|inf' "$out"; then fail "$out holds NaN or Inf"; fi
  awk '$1 == "v" || $1 == "vn" { for (i = 2; i <= 4; ++i) if ($i + 0 != $i + 0 || ($i + 0) * 0 != 0) exit 1 }' "$out" \
    || fail "$out has a non-numeric coordinate"
else
  # Frames before the failing one are written, none after it.
  written=$(ls "$out" 2>/dev/null | wc -l)
  [ "$written" -eq $((frame - 1)) ] || fail "$written frames written, expected $((frame - 1))"
fi
echo "ok: diverged at frame $frame, exit 1"
