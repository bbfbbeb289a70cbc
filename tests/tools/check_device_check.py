#!/usr/bin/python3
"""Checks the folder `scripts/device-check --quick` wrote (docs/device-check.md): summary.md says the
run passed, names the GL renderer, has every step, a validate row per shipped scene (passed, or
skipped for its size) with its deviation, and the bench table of the quick sizes; the logs and the
bench JSON are beside it, no more than 8 files (what a device machine's $OUT gives back).

usage: check_device_check.py OUT_DIR [--ctest-skipped]
  --ctest-skipped  the run had CLOTHSIM_DEVICE_CHECK_NO_CTEST=1: its ctest step must say skipped
"""
import json
import os
import re
import sys

STEPS = ["build", "context", "ctest", "validate", "bench", "plot"]
FILES = ["summary.md", "build.log", "ctest.log", "validate.log", "bench.log", "bench.json"]
QUICK_SIZES = [32, 64]


def table(lines, header_start):
    """Rows (lists of cells) of the markdown table whose header line starts with header_start."""
    rows, inside = [], False
    for line in lines:
        if line.startswith(header_start):
            inside = True
            continue
        if inside:
            if line.startswith("| ---"):
                continue
            if not line.startswith("|"):
                break
            rows.append([c.strip() for c in line.strip().strip("|").split("|")])
    return rows


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    ctest_skipped = "--ctest-skipped" in sys.argv[2:]
    errors = []
    summary_path = os.path.join(out, "summary.md")
    if not os.path.isfile(summary_path):
        sys.exit(f"FAIL: {summary_path} was not written")
    text = open(summary_path).read()
    print(text)
    lines = text.splitlines()

    def check(ok, what):
        if not ok:
            errors.append(what)

    check(lines and lines[0] == "# clothsim device check (quick)", "the title is not '# clothsim device check (quick)'")
    check("- Result: **PASSED**" in lines, "the summary does not say '- Result: **PASSED**'")
    m = re.search(r"^- GL renderer: (.+)$", text, re.M)
    check(m and not m.group(1).startswith("unknown"), "no GL renderer line")
    m = re.search(r"^- Tests \(ctest -L gpu, CLOTHSIM_REQUIRE_GPU=1\): (.+)$", text, re.M)
    check(m is not None, "no test-count line")
    if m:
        if ctest_skipped:
            check(m.group(1).startswith("skipped (CLOTHSIM_DEVICE_CHECK_NO_CTEST=1"), f"ctest not said skipped: {m.group(1)}")
        else:
            check(re.match(r"\d+ passed, 0 failed, \d+ skipped, of \d+", m.group(1)), f"test counts: {m.group(1)}")
    check(re.search(r"^- Total wall time: [0-9.]+ s", text, re.M), "no total wall time")

    steps = {r[0]: r for r in table(lines, "| step |")}
    for s in STEPS:
        check(s in steps, f"step {s} missing from the steps table")
        if s in steps:
            check(not steps[s][1].startswith("FAIL"), f"step {s}: {steps[s][1]}")
            check(re.fullmatch(r"[0-9]+\.[0-9]", steps[s][2]), f"step {s} has no time: {steps[s][2]}")

    scenes_dir = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scenes")
    shipped = sorted(f"scenes/{f}" for f in os.listdir(scenes_dir) if f.endswith(".json"))
    rows = {r[0]: r for r in table(lines, "| scene |")}
    check(sorted(rows) == shipped, f"validate rows {sorted(rows)} are not the shipped scenes {shipped}")
    passed = 0
    for name, (_, particles, frames, result, deviation, seconds) in rows.items():
        if result == "pass":
            passed += 1
            check(frames == "3", f"{name}: {frames} frames, --quick runs 3")
            check(re.match(r"[0-9.]+e[-+][0-9]+ m", deviation), f"{name}: no deviation ({deviation})")
            check(int(particles) <= 5000, f"{name}: {particles} particles validated in --quick")
        elif result.startswith("skipped"):
            check(int(particles) > 5000, f"{name}: skipped with only {particles} particles")
        else:
            errors.append(f"{name}: {result}")
    check(passed >= 5, f"only {passed} scenes validated")

    bench = table(lines, "| solver |")
    expected = {(s, c, f"{n}²") for s in ("classic", "fabric") for c in ("off", "on") for n in QUICK_SIZES}
    check({(r[0], r[1], r[2]) for r in bench} == expected, f"bench rows {[r[:3] for r in bench]}")
    for r in bench:
        check(float(r[4]) > 0 and float(r[5]) > 0, f"bench row {r}: no timing")

    for f in FILES:
        check(os.path.isfile(os.path.join(out, f)), f"{f} missing")
    names = os.listdir(out)
    check(len(names) <= 8, f"{len(names)} files in {out}, more than a device machine gives back: {names}")
    if os.path.isfile(os.path.join(out, "bench.json")):
        data = json.load(open(os.path.join(out, "bench.json")))
        check(len(data["results"]) == len(expected), f"bench.json has {len(data['results'])} results")
    log = open(os.path.join(out, "validate.log")).read() if os.path.isfile(os.path.join(out, "validate.log")) else ""
    check(log.count("validation passed") == passed, "validate.log does not hold each passing run")

    if errors:
        print("FAIL: " + "\nFAIL: ".join(errors))
        sys.exit(1)
    print(f"ok: summary.md lists {len(steps)} steps, {passed} validated scenes, {len(bench)} bench rows")


if __name__ == "__main__":
    main()
