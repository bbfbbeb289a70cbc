#!/bin/sh
# Runs one command-level GPU-tier test (add_gpu_command_test in tests/CMakeLists.txt) only
# where it can run, so that a machine without OpenGL 4.3 is told the test was skipped and why,
# never that it passed or failed.
# usage: gpu_test.sh PROBE [--needs TOOL]... -- COMMAND [ARG]...
# Checks that each TOOL is on PATH and that PROBE (clothsim_gl_probe) makes an OpenGL 4.3
# context the way clothsim does. If one is missing it prints "skipped: <reason>" and exits 77,
# which ctest reports as Not Run (SKIP_RETURN_CODE 77); under CLOTHSIM_REQUIRE_GPU=1 (CI, where
# everything is installed) it prints "FAIL: <reason>" and exits 1 instead. Otherwise it runs
# COMMAND, whose exit status is the test's.
set -u
probe=$1
shift
not_run() {  # not_run WHAT [WHY]
  if [ "${CLOTHSIM_REQUIRE_GPU:-}" = 1 ]; then
    echo "FAIL: $1 (CLOTHSIM_REQUIRE_GPU=1)${2:+: $2}"
    exit 1
  fi
  echo "skipped: $1${2:+: $2}"
  exit 77
}
while [ $# -gt 0 ]; do
  case $1 in
    --needs) command -v "$2" >/dev/null 2>&1 || not_run "$2 is not installed"; shift 2 ;;
    --) shift; break ;;
    *) echo "gpu_test.sh: unknown option $1"; exit 2 ;;
  esac
done
[ $# -gt 0 ] || { echo "gpu_test.sh: no command after --"; exit 2; }
why=$("$probe" 2>&1)
code=$?
case $code in
  0) echo "OpenGL: $why" ;;
  3) not_run "no OpenGL 4.3 context" "$why" ;;
  # A probe that crashes (or trips a sanitizer) is a bug to see, not a reason to skip.
  *) echo "FAIL: $probe exited $code: $why"; exit 1 ;;
esac
exec "$@"
