#!/bin/sh
# Checkpoints end to end: `simulate --frames 2N --save-state A` and `--frames N --save-state B`,
# then `--load-state B --frames N --save-state C` must give byte-identical A and C (the same
# streams, frame and time, bit for bit). A truncated, foreign or mismatched state file is exit 2
# with a message naming it, never a crash.
# A state is for the scalar it was saved in: loading one saved by the other backend (float on
# the GPU, double with --backend cpu) is exit 2 naming the precision.
# usage: check_checkpoint_cli.sh CLOTHSIM SCENE cpu|gpu|cpu-on-gpu OUTDIR
#   cpu         everything on --backend cpu (needs no GPU); the CPU-tier test
#   gpu         everything on --backend gpu, and a GPU state loaded on --backend cpu
#   cpu-on-gpu  only the cross-precision check the cpu mode cannot make: a CPU state loaded
#               on --backend gpu (a GPU-tier test: add_gpu_command_test)
# Without an OpenGL 4.3 context (exit 3) the modes that need the GPU are skipped (exit 77),
# unless CLOTHSIM_REQUIRE_GPU=1 makes that a failure; they never pass without having run.
set -u
bin=$1 scene=$2 mode=$3 dir=$4
case $mode in
  cpu|gpu) backend=$mode ;;
  cpu-on-gpu) backend=cpu ;;
  *) echo "check_checkpoint_cli.sh: unknown mode $mode"; exit 2 ;;
esac
rm -rf "$dir"
mkdir -p "$dir"
fail() { echo "FAIL: $*"; exit 1; }
no_context() {  # the GPU backend found no OpenGL 4.3 context (exit 3)
  if [ "${CLOTHSIM_REQUIRE_GPU:-}" = 1 ]; then fail "no OpenGL 4.3 context (CLOTHSIM_REQUIRE_GPU=1)"; fi
  echo "skipped: no OpenGL 4.3 context"; exit 77
}
small="--set cloth.num_width_points=33 --set cloth.num_height_points=17 --set cloth.pinned=[[0,0],[32,0]]"
sim() {  # sim NAME ARGS...: runs simulate on the small cloth, output in NAME.out / NAME.err
  name=$1; shift
  # shellcheck disable=SC2086 # the --set words split on purpose
  "$bin" simulate "$scene" --backend "$backend" $small "$@" >"$dir/$name.out" 2>"$dir/$name.err"
  code=$?
  cat "$dir/$name.out" "$dir/$name.err"
  [ $code -eq 3 ] && no_context
  return $code
}
# cross STATE OTHER: loading STATE (saved on $backend) on backend OTHER is exit 2 naming the
# precision. On the GPU without a context that is a skip (or a failure), never a pass.
cross() {
  # shellcheck disable=SC2086 # the --set words split on purpose
  "$bin" simulate "$scene" --backend "$2" $small --frames 1 --load-state "$1" >"$dir/other.out" 2>"$dir/other.err"
  code=$?
  cat "$dir/other.err"
  if [ $code -eq 3 ]; then
    [ "$2" = gpu ] || fail "--backend $2 exited 3"
    no_context
  fi
  [ $code -eq 2 ] || fail "loading a $backend state on $2: exit $code, expected 2"
  grep -q "byte (.*) scalars, saved by backend" "$dir/other.err" || fail "no precision message"
  echo "ok: a $backend state on $2 is exit 2 naming the precision"
}
if [ "$mode" = cpu-on-gpu ]; then
  sim saved --frames 2 --save-state "$dir/A.state" || fail "the CPU run failed"
  cross "$dir/A.state" gpu
  exit 0
fi
sim whole --frames 12 --save-state "$dir/A.state" || fail "the 12-frame run failed"
sim first --frames 6 --save-state "$dir/B.state" || fail "the first 6 frames failed"
sim second --frames 6 --load-state "$dir/B.state" --save-state "$dir/C.state" || fail "the resumed run failed"
grep -q "loaded $dir/B.state: frame 6" "$dir/second.out" || fail "no 'loaded ... frame 6' line"
cmp "$dir/A.state" "$dir/C.state" || fail "12 frames and 6 + 6 frames differ"
echo "ok: 12 frames == 6 frames, saved, loaded, 6 frames (bitwise)"

# refused STATE WHY ARGS...: loading STATE must be exit 2 with a message naming it and WHY.
refused() {
  state=$1 why=$2; shift 2
  sim refused --frames 1 --load-state "$state" "$@"
  code=$?
  [ $code -eq 2 ] || fail "loading $state: exit $code, expected 2"
  grep -q "^error: --load-state $state: .*$why" "$dir/refused.err" || fail "loading $state: no message with '$why'"
}
size=$(wc -c <"$dir/A.state")
head -c $((size / 2)) "$dir/A.state" >"$dir/truncated.state"
refused "$dir/truncated.state" "truncated"
head -c 40 "$dir/A.state" >"$dir/header_only.state"
refused "$dir/header_only.state" "truncated"
head -c 10 "$dir/A.state" >"$dir/ten.state"
refused "$dir/ten.state" "not a clothsim state file"
cp "$scene" "$dir/foreign.state"
refused "$dir/foreign.state" "not a clothsim state file"
refused "$dir/missing.state" "cannot open"
refused "$dir/A.state" "different cloth: .*33x17 cloth with 2 pinned.*but scene .* has a 33x19 cloth" --set cloth.num_height_points=19
refused "$dir/A.state" "different cloth: .*33x17 cloth with 2 pinned.*but scene .* has a 33x17 cloth with 1" --set cloth.pinned=[[0,0]]
# The other backend's scalar: the GPU runs in float, `--backend cpu` in double. A GPU state on
# the CPU needs no context beyond the one this mode has; a CPU state on the GPU is the
# cpu-on-gpu mode, a GPU-tier test of its own, so the CPU tier never needs a GPU.
if [ "$backend" = gpu ]; then
  cross "$dir/A.state" cpu
else
  echo "(a CPU state loaded on the GPU: the cpu-on-gpu mode, a GPU-tier test)"
fi
# What does not change the cloth still loads.
sim stiffer --frames 1 --load-state "$dir/A.state" --set cloth.ks=800 --set cloth.density=200 \
  || fail "a state did not load under a different ks and density"
echo "ok: bad state files are exit 2 with the file and the reason"
