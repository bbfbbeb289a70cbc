#!/usr/bin/env python3
"""Without an OpenGL 4.3 context every GPU-tier test is skipped with the reason, never passed.

usage: check_gpu_skips.py CTEST BUILD_DIR GPU_TESTS GPU_TEST_SH GL_PROBE

Hides the EGL vendor libraries (__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json, so there is
no context even on a machine with a GPU) and checks, from what ctest has registered
(ctest --show-only=json-v1, which runs nothing):
  - every gpu-labelled test (gpu, or gpu-slow) is named "gpu:...", has SKIP_RETURN_CODE 77 and
    runs either the Catch GPU binary or tools/gpu_test.sh, and every "gpu:..." test has the label;
  - every one of them, run as ctest runs it, exits 77 and says "skipped: ..." and why;
  - with CLOTHSIM_REQUIRE_GPU=1 one Catch test and one command-level test fail instead (all
    of them would take twice as long for little more);
  - by hand, a Catch run mixing test cases that need no context with skipped ones exits 0
    and says how many skipped, and fails under CLOTHSIM_REQUIRE_GPU=1;
  - gpu_test.sh skips (or fails under CLOTHSIM_REQUIRE_GPU=1) when a --needs tool is missing.
"""
import json
import os
import subprocess
import sys

ctest, build_dir, gpu_tests, gpu_test_sh, probe = sys.argv[1:6]
gpu_tests, gpu_test_sh = os.path.realpath(gpu_tests), os.path.realpath(gpu_test_sh)
failures = []


def check(ok, what):
    print(("ok:   " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def env(require_gpu):
    e = dict(os.environ, __EGL_VENDOR_LIBRARY_FILENAMES="/nonexistent.json")
    e.pop("CLOTHSIM_REQUIRE_GPU", None)
    if require_gpu:
        e["CLOTHSIM_REQUIRE_GPU"] = "1"
    return e


def run(command, require_gpu, cwd=None):
    p = subprocess.run(command, env=env(require_gpu), cwd=cwd, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True, timeout=120)
    return p.returncode, p.stdout


def properties(test):
    return {p["name"]: p["value"] for p in test.get("properties", [])}


listing = json.loads(subprocess.run([ctest, "--test-dir", build_dir, "--show-only=json-v1"],
                                    check=True, stdout=subprocess.PIPE, text=True).stdout)
tests = listing["tests"]
def gpu_labelled(t):
    """A label "gpu", or "gpu-slow" (the [gpu][slow] Catch cases: Catch's discovery takes one
    label, and ctest -L gpu, a regular expression, selects both)."""
    return any(label == "gpu" or label.startswith("gpu-") for label in properties(t).get("LABELS", []))


gpu = [t for t in tests if gpu_labelled(t)]
catch_tests = [t for t in gpu if os.path.realpath(t["command"][0]) == gpu_tests]
command_tests = [t for t in gpu if gpu_test_sh in map(os.path.realpath, t["command"])]
print(f"{len(gpu)} gpu-labelled tests: {len(catch_tests)} Catch test cases, {len(command_tests)} command-level")
if not catch_tests or not command_tests:
    sys.exit("FAIL: expected both Catch and command-level GPU tests")
for t in gpu:
    name, props = t["name"], properties(t)
    check(name.startswith("gpu:"), f"'{name}' is named gpu:...")
    check(props.get("SKIP_RETURN_CODE") == 77, f"'{name}' has SKIP_RETURN_CODE 77")
    check(t in catch_tests or t in command_tests, f"'{name}' runs the Catch GPU binary or gpu_test.sh")
for t in tests:
    if t["name"].startswith("gpu:"):
        check(t in gpu, f"'{t['name']}' has the label gpu (or gpu-slow)")



def as_registered(t):
    """The test's command as ctest runs it; for a command-level test, what gpu_test.sh would
    run after its checks is replaced by a failure, so that nothing of a real test runs here
    (alongside the real one, on its output files) even if the checks wrongly passed."""
    command = t["command"]
    if t in command_tests:
        command = command[:command.index("--") + 1] + ["sh", "-c", "echo 'the command ran'; exit 1"]
    return command


# Every GPU-tier test, as ctest runs it, skips with the reason.
for t in gpu:
    code, out = run(as_registered(t), False, properties(t).get("WORKING_DIRECTORY"))
    ok = code == 77 and "skipped: " in out and ("OpenGL 4.3" in out or "not installed" in out)
    check(ok, f"'{t['name']}' without a context: exit {code}, " + ("says why" if ok else "output:\n" + out))

# Under CLOTHSIM_REQUIRE_GPU=1 the same is a failure naming the reason.
for t in (catch_tests[0], command_tests[0]):
    code, out = run(as_registered(t), True, properties(t).get("WORKING_DIRECTORY"))
    ok = code not in (0, 77) and "CLOTHSIM_REQUIRE_GPU=1" in out and "OpenGL 4.3" in out
    check(ok, f"'{t['name']}' without a context under CLOTHSIM_REQUIRE_GPU=1: exit {code}"
          + ("" if ok else ", output:\n" + out))

# By hand: test cases that need no context ([shaders]) pass next to skipped ones, exit 0.
code, out = run([gpu_tests, "[shaders],[gpu]"], False)
check(code == 0 and "test cases were skipped, no OpenGL 4.3 context" in out,
      f"a mixed run by hand exits {code} and counts the skipped" + ("" if code == 0 else ":\n" + out[-2000:]))
code, out = run([gpu_tests, "[shaders],[gpu]"], True)
check(code not in (0, 77), f"a mixed run by hand under CLOTHSIM_REQUIRE_GPU=1 exits {code}")

# A missing tool (xvfb-run, ffmpeg) is a skip too, and a failure under CLOTHSIM_REQUIRE_GPU=1;
# the command is not run.
missing = ["sh", gpu_test_sh, probe, "--needs", "clothsim-no-such-tool", "--", "sh", "-c", "echo ran"]
code, out = run(missing, False)
check(code == 77 and "skipped: clothsim-no-such-tool is not installed" in out and "ran" not in out,
      f"a missing tool skips: exit {code}, {out.strip()!r}")
code, out = run(missing, True)
check(code == 1 and "clothsim-no-such-tool is not installed" in out and "ran" not in out,
      f"a missing tool under CLOTHSIM_REQUIRE_GPU=1 fails: exit {code}, {out.strip()!r}")

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
print("every GPU-tier test is skipped with the reason without a context")
