#!/bin/sh
# Checkpoints end to end: `simulate --frames 2N --save-state A` and `--frames N --save-state B`,
# then `--load-state B --frames N --save-state C` must give byte-identical A and C (the same
# streams, frame and time, bit for bit). A truncated, foreign or mismatched state file is exit 2
# with a message naming it, never a crash.
# usage: check_checkpoint_cli.sh CLOTHSIM SCENE cpu|gpu OUTDIR
# Without an OpenGL 4.3 context (exit 3) the GPU variant is skipped (exit 77), unless
# CLOTHSIM_REQUIRE_GPU=1 makes that a failure.
set -u
bin=$1 scene=$2 backend=$3 dir=$4
rm -rf "$dir"
mkdir -p "$dir"
fail() { echo "FAIL: $*"; exit 1; }
small="--set cloth.num_width_points=33 --set cloth.num_height_points=17 --set cloth.pinned=[[0,0],[32,0]]"
sim() {  # sim NAME ARGS...: runs simulate on the small cloth, output in NAME.out / NAME.err
  name=$1; shift
  # shellcheck disable=SC2086 # the --set words split on purpose
  "$bin" simulate "$scene" --backend "$backend" $small "$@" >"$dir/$name.out" 2>"$dir/$name.err"
  code=$?
  cat "$dir/$name.out" "$dir/$name.err"
  if [ $code -eq 3 ]; then
    if [ "${CLOTHSIM_REQUIRE_GPU:-}" = 1 ]; then fail "no OpenGL 4.3 context (CLOTHSIM_REQUIRE_GPU=1)"; fi
    echo "skipped: no OpenGL 4.3 context"; exit 77
  fi
  return $code
}
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
# The other backend's scalar: the GPU and cpu float run in float, `--backend cpu` in double.
other=gpu; [ "$backend" = gpu ] && other=cpu
"$bin" simulate "$scene" --backend "$other" $small --frames 1 --load-state "$dir/A.state" >"$dir/other.out" 2>"$dir/other.err"
code=$?
cat "$dir/other.err"
if [ $code -ne 3 ]; then
  [ $code -eq 2 ] || fail "loading a $backend state on $other: exit $code, expected 2"
  grep -q "byte (.*) scalars, saved by backend" "$dir/other.err" || fail "no precision message"
fi
# What does not change the cloth still loads.
sim stiffer --frames 1 --load-state "$dir/A.state" --set cloth.ks=800 --set cloth.density=200 \
  || fail "a state did not load under a different ks and density"
echo "ok: bad state files are exit 2 with the file and the reason"
