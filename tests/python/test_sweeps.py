"""clothsim sweep on Dask: the product of variations as runs, recorded, deterministic and resumable."""
import json
import os
import signal
import subprocess
import sys
import time

import psutil
import pytest

import clothsim
from conftest import BINARY, SMALL, SPHERE, simulate

VARY = {"cloth.ks": [500, 1000, 2000, 4000], "sphere.friction": [0.2, 0.8]}  # 8 runs


def manifest(out):
    with open(os.path.join(out, "manifest.jsonl")) as f:
        return [json.loads(l) for l in f if l.strip()]


def pc2(out, run_id):
    with open(os.path.join(out, "runs", run_id, "cloth.pc2"), "rb") as f:
        return f.read()


def cli_sweep(*args, **popen):
    """`clothsim sweep ARGS` through the command line's hand-over to Python."""
    return subprocess.Popen([BINARY, "sweep", *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            **popen)


# 8 runs on the CPU; 4 on llvmpipe, whose runs take longer (the same code path either way).
@pytest.mark.parametrize("backend,ks", [("cpu", [500, 1000, 2000, 4000]), ("gpu", [500, 4000])])
def test_runs_on_2_workers_equal_1_worker_and_simulate_bitwise(backend, ks, workdir):
    two, one = str(workdir / "two"), str(workdir / "one")
    n = 2 * len(ks)
    summary = clothsim.sweep(SPHERE, {**{k: [v] for k, v in SMALL.items()}, **VARY, "cloth.ks": ks}, frames=60,
                             out=two, workers=2, backend=backend, progress=False)
    assert summary == {"runs": n, "skipped": 0, "ok": n, "failed": 0, "lost": 0,
                       "manifest": os.path.join(two, "manifest.jsonl")}
    vary = [f"--vary={k}={v}" for k, v in SMALL.items()] + ["--vary=cloth.ks=" + ",".join(map(str, ks)),
                                                              "--vary=sphere.friction=0.2,0.8"]
    p = cli_sweep(SPHERE, *vary, "--frames", "60", "--out", one, "--workers", "1", "--backend", backend)
    stdout, stderr = p.communicate(timeout=300)
    assert p.returncode == 0, stderr
    assert f"{n} runs: {n} ok, 0 failed" in stdout
    runs = manifest(two)
    assert sorted(r["id"] for r in runs) == sorted(r["id"] for r in manifest(one))
    caches = set()
    for r in runs:
        assert r["status"] == "ok" and r["exit_code"] == 0 and r["stats"]["frames"] == 60
        assert set(os.listdir(os.path.join(two, "runs", r["id"]))) == {"scene.json", "stats.json", "cloth.pc2",
                                                                       "cloth.obj", "log.txt"}
        assert pc2(two, r["id"]) == pc2(one, r["id"])
        # The run is its scene: simulate of runs/ID/scene.json writes the same point cache.
        again = workdir / f"{r['id']}.pc2"
        simulate(os.path.join(two, "runs", r["id"], "scene.json"), "--frames", "60", "--backend", backend,
                 "--export", str(again))
        assert again.read_bytes() == pc2(two, r["id"])
        with open(os.path.join(two, "runs", r["id"], "scene.json")) as f:
            scene = json.load(f)
        assert scene["cloth"]["ks"] == r["values"]["cloth.ks"]
        caches.add(pc2(two, r["id"]))
    assert len(caches) == n  # every variation changed the run


def test_a_bad_value_and_a_divergence_are_recorded_and_the_sweep_goes_on(workdir):
    out = str(workdir / "bad")
    vary = {**{k: [v] for k, v in SMALL.items()}, "cloth.ks": [1000, -5],
            "simulation.gravity": [[0, -9.8, 0], [0, -1e9, 0]]}
    summary = clothsim.sweep(SPHERE, vary, frames=5, out=out, workers=2, backend="cpu", progress=False)
    assert (summary["ok"], summary["failed"], summary["lost"]) == (1, 3, 0)
    by = {(r["values"]["cloth.ks"], r["values"]["simulation.gravity"][1]): r for r in manifest(out)}
    assert by[(1000, -9.8)]["status"] == "ok"
    bad = by[(-5, -9.8)]
    assert bad["status"] == "failed" and bad["exit_code"] == 2
    assert "cloth.ks: expected a spring constant >= 0" in bad["message"]
    diverged = by[(1000, -1e9)]
    assert diverged["status"] == "failed" and diverged["exit_code"] == 1
    assert "diverged at frame 1" in diverged["message"]
    # A rerun skips every recorded run, failed ones included; --retry-failed redoes those.
    again = clothsim.sweep(SPHERE, vary, frames=5, out=out, workers=1, backend="cpu", progress=False)
    assert (again["skipped"], again["ok"], again["failed"]) == (4, 0, 0)
    retry = clothsim.sweep(SPHERE, vary, frames=5, out=out, workers=1, backend="cpu", progress=False,
                           retry_failed=True)
    assert (retry["skipped"], retry["failed"]) == (1, 3)


def test_bad_sweep_input_is_exit_2_and_touches_nothing(workdir):
    keep = workdir / "notes.txt"
    keep.write_text("mine")
    for args, says in [(["--vary", "cloth.ks", "--frames", "1", "--out", str(workdir / "a")], "expected KEY=V1,V2"),
                       (["--vary", "cloth.ks=1,2", "--frames", "1", "--out", str(workdir)], "not a sweep's"),
                       (["--frames", "1", "--out", str(workdir / "b")], "nothing to sweep"),
                       (["--vary", "cloth.ks=1", "--frames", "0", "--out", str(workdir / "c")], "--frames 0")]:
        p = cli_sweep(SPHERE, *args)
        _, stderr = p.communicate(timeout=60)
        assert p.returncode == 2 and says in stderr, stderr
    assert sorted(os.listdir(workdir)) == ["notes.txt"] and keep.read_text() == "mine"


def running_simulations(root):
    """The clothsim-headless processes under `root` (the sweep's process tree)."""
    try:
        return [c for c in psutil.Process(root).children(recursive=True) if c.name() == "clothsim-headless"]
    except psutil.NoSuchProcess:
        return []


def test_a_sweep_whose_worker_is_killed_completes_on_rerun_with_nothing_lost_or_duplicated(workdir):
    out = str(workdir / "killed")
    # Runs of about a second each, so the kills land mid-run.
    args = [SPHERE, "--vary=cloth.num_width_points=25", "--vary=cloth.num_height_points=25",
            "--vary=cloth.ks=500,1000,2000,4000", "--vary=sphere.friction=0.2,0.8", "--frames", "120", "--out", out,
            "--workers", "2", "--backend", "cpu"]
    p = cli_sweep(*args, start_new_session=True)
    killed_worker = False
    deadline = time.time() + 120
    while time.time() < deadline and p.poll() is None:
        sims = running_simulations(p.pid)
        done = len(manifest(out)) if os.path.exists(os.path.join(out, "manifest.jsonl")) else 0
        if sims and not killed_worker and done >= 1:
            sims[0].parent().kill()  # the Dask worker running it, mid-run
            killed_worker = True
        elif killed_worker and done >= 3:
            # Then the whole sweep, scheduler and all, as soon as three runs are in, whether or
            # not a simulation is running at that poll (waiting for one let a loaded machine's
            # sweep finish all eight first, once in CI's test on a fresh clone).
            os.killpg(p.pid, signal.SIGKILL)
            break
        time.sleep(0.05)
    p.communicate(timeout=60)
    assert killed_worker
    before = manifest(out)
    assert 3 <= len(before) < 8, "the sweep was to be killed part-way"
    rerun = cli_sweep(*args)
    stdout, stderr = rerun.communicate(timeout=300)
    assert rerun.returncode == 0, stderr
    assert f"{len(before)} already done" in stdout
    after = manifest(out)
    assert after[: len(before)] == before  # nothing redone
    ids = [r["id"] for r in after]
    assert len(ids) == 8 and len(set(ids)) == 8 and all(r["status"] == "ok" for r in after)
    assert sorted(os.listdir(os.path.join(out, "runs"))) == sorted(ids)  # no partial folder left
    for r in after:  # and every run whole: its cache is the one its scene simulates to
        again = workdir / f"{r['id']}.pc2"
        simulate(os.path.join(out, "runs", r["id"], "scene.json"), "--frames", "120", "--backend", "cpu",
                 "--export", str(again))
        assert again.read_bytes() == pc2(out, r["id"])


def test_an_existing_scheduler_runs_the_sweep(workdir):
    """--scheduler: a Dask cluster started by hand (as on many machines), here a scheduler and one worker."""
    info = workdir / "scheduler.json"
    dask = [sys.executable, "-m"]
    scheduler = subprocess.Popen(dask + ["distributed.cli.dask_scheduler", "--host", "127.0.0.1", "--port", "0",
                                         "--no-dashboard", "--scheduler-file", str(info)],
                                 stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    worker = None
    try:
        deadline = time.time() + 60
        while not info.exists() and time.time() < deadline:
            time.sleep(0.1)
        time.sleep(0.2)  # the file is written whole before it is read
        address = json.loads(info.read_text())["address"]
        worker = subprocess.Popen(dask + ["distributed.cli.dask_worker", address, "--nthreads", "1", "--no-dashboard",
                                          "--local-directory", str(workdir / "worker")],
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        out = str(workdir / "remote")
        p = cli_sweep(SPHERE, *[f"--vary={k}={v}" for k, v in SMALL.items()], "--vary=cloth.ks=500,4000",
                      "--frames", "30", "--out", out, "--scheduler", address, "--backend", "cpu")
        stdout, stderr = p.communicate(timeout=120)
        assert p.returncode == 0, stderr
        assert "2 runs: 2 ok" in stdout
        for r in manifest(out):
            again = workdir / f"{r['id']}.pc2"
            simulate(os.path.join(out, "runs", r["id"], "scene.json"), "--frames", "30", "--backend", "cpu",
                     "--export", str(again))
            assert again.read_bytes() == pc2(out, r["id"])
    finally:
        for proc in (worker, scheduler):
            if proc:
                proc.terminate()
                proc.wait(timeout=30)
