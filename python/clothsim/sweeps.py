"""Sweeps: the product of some parameter variations, each a clothsim run, as tasks on Dask.

Layout of OUT (docs/sweeps.md):
    OUT/manifest.jsonl    one line per finished run: id, values, status, exit code, message,
                          stats, wall time; appended by this process only, as runs finish
    OUT/runs/ID/          scene.json (the run's scene, resolved), stats.json, cloth.pc2 and
                          cloth.obj (its point cache and mesh), log.txt (what clothsim printed)

A run is one `clothsim-headless simulate` of its scene.json, in a temporary folder on the
worker; its files come back with the task's result and this process writes them, so workers
need the same clothsim and the scene's input files at the same paths, but no shared disk.
A run is finished once its manifest line is written: a rerun skips those (resuming an
interrupted sweep) and redoes the rest. A run that fails (bad value, divergence) is recorded
with its message and exit code and does not stop the sweep; a run whose worker died is not
recorded (Dask retries it elsewhere first), so a rerun does it.
"""
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

from . import _clothsim
from . import override_strings
from .sweep_plan import SEED_KEY, SweepError, check_out, parse_vary, plan_runs, read_manifest

RUN_FILES = ("scene.json", "stats.json", "cloth.pc2", "cloth.obj", "log.txt")


def default_binary():
    """clothsim-headless beside this package's build folder (build/python/clothsim -> build/)."""
    if os.environ.get("CLOTHSIM_BINARY"):
        return os.environ["CLOTHSIM_BINARY"]
    here = os.path.dirname(os.path.abspath(__file__))
    return os.path.normpath(os.path.join(here, "..", "..", "clothsim-headless"))


def simulate(task):
    """Runs on a worker: one clothsim simulate in a temporary folder; returns its files as bytes."""
    t0 = time.time()
    tmp = tempfile.mkdtemp(prefix="clothsim-run-")
    try:
        scene = os.path.join(tmp, "scene.json")
        with open(scene, "w") as f:
            f.write(task["scene"])
        argv = [task["binary"], "simulate", scene, "--frames", str(task["frames"]), "--backend", task["backend"],
                "--export", os.path.join(tmp, "cloth.pc2"), "--export-every", str(task["export_every"]),
                "--stats-json", os.path.join(tmp, "stats.json")]

        def die_with_worker():  # a killed worker takes its run with it (Linux's parent-death signal)
            try:
                import ctypes
                ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
            except OSError:
                pass

        proc = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, preexec_fn=die_with_worker)
        log = proc.stdout.decode("utf-8", "replace")
        files = {}
        for name in RUN_FILES[1:4]:
            p = os.path.join(tmp, name)
            if os.path.exists(p):
                with open(p, "rb") as f:
                    files[name] = f.read()
        files["log.txt"] = log.encode()
        errors = [l[len("error: "):] for l in log.splitlines() if l.startswith("error: ")]
        if proc.returncode < 0:
            message = f"clothsim ended by signal {-proc.returncode}"
        else:
            message = "\n".join(errors) if errors else ("" if proc.returncode == 0 else log.strip()[-500:])
        return {"id": task["id"], "exit_code": proc.returncode, "message": message, "files": files,
                "wall_time_s": time.time() - t0}
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


class Progress:
    """'sweep 5/8 runs (1 failed)  ETA 12 s' on one refreshed line of a terminal; silent otherwise."""

    def __init__(self, total, enabled):
        self.total, self.enabled, self.t0 = total, enabled and sys.stderr.isatty(), time.time()

    def update(self, done, failed):
        if not self.enabled or self.total == 0:
            return
        elapsed = time.time() - self.t0
        eta = f"  ETA {elapsed / done * (self.total - done):.0f} s" if done else ""
        bar = "#" * int(30 * done / self.total)
        failures = f" ({failed} failed)" if failed else ""
        sys.stderr.write(f"\rsweep [{bar:<30}] {done}/{self.total} runs{failures}{eta}   ")
        sys.stderr.flush()

    def finish(self):
        if self.enabled:
            sys.stderr.write("\n")


class Writer:
    """The one writer of OUT: a run's folder whole (via a temporary), then its manifest line."""

    def __init__(self, out):
        self.out = out
        self.runs = os.path.join(out, "runs")
        os.makedirs(self.runs, exist_ok=True)
        self.manifest = os.path.join(out, "manifest.jsonl")

    def record(self, run, result, scene_text):
        stats = None
        if "stats.json" in result["files"]:
            try:
                stats = json.loads(result["files"]["stats.json"])
            except ValueError:
                stats = None
        ok = result["exit_code"] == 0 and stats is not None
        files = dict(result["files"])
        if scene_text is not None:
            files["scene.json"] = scene_text.encode()
        final = os.path.join(self.runs, run["id"])
        partial = tempfile.mkdtemp(prefix=f".{run['id']}.", dir=self.runs)
        for name, data in files.items():
            with open(os.path.join(partial, name), "wb") as f:
                f.write(data)
        if os.path.lexists(final):  # a run written by a sweep that died before its manifest line
            shutil.rmtree(final) if os.path.isdir(final) and not os.path.islink(final) else os.remove(final)
        os.rename(partial, final)
        line = {"id": run["id"], "values": run["values"], "status": "ok" if ok else "failed",
                "exit_code": result["exit_code"], "message": result["message"], "stats": stats,
                "wall_time_s": round(result["wall_time_s"], 3)}
        with open(self.manifest, "a") as f:
            f.write(json.dumps(line, sort_keys=True) + "\n")
            f.flush()
            os.fsync(f.fileno())
        return line

    def clean_partials(self):
        for name in os.listdir(self.runs):
            if name.startswith("."):  # a run folder a killed sweep was writing
                shutil.rmtree(os.path.join(self.runs, name), ignore_errors=True)


def sweep(scene, vary, frames, out, seeds=0, workers=None, scheduler=None, backend="gpu", export_every=1,
          retry_failed=False, progress=True, binary=None):
    """Runs the product of `vary` ({key: [values]} or ["KEY=V1,V2", ...]) times `seeds` seeds.

    scene: a scene file or dict; frames: frames per run; out: the sweep's folder (resumed if it
    holds an earlier sweep). workers: a LocalCluster of that many worker processes (default: the
    CPU count); scheduler: "tcp://HOST:PORT" of a running Dask scheduler instead. Returns a
    summary dict {"runs", "skipped", "ok", "failed", "lost", "manifest"}.
    """
    if isinstance(frames, bool) or not isinstance(frames, int) or frames < 1:
        raise SweepError(f"--frames {frames}: expected a positive integer")
    if isinstance(seeds, bool) or not isinstance(seeds, int) or seeds < 0:
        raise SweepError(f"--seeds {seeds}: expected a non-negative integer")
    if backend not in ("gpu", "cpu"):
        raise SweepError(f"--backend {backend}: expected gpu or cpu")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise SweepError(f"--workers {workers}: expected a positive integer")
    if workers is not None and scheduler:
        raise SweepError("--workers and --scheduler: give one (the scheduler's cluster has its own workers)")
    out = os.fspath(out)
    check_out(out)
    binary = binary or default_binary()
    if not os.access(binary, os.X_OK):
        raise SweepError(f"{binary}: no clothsim-headless there; build it, or set CLOTHSIM_BINARY")
    runs = plan_runs(parse_vary(vary), seeds)
    is_text = isinstance(scene, dict)
    scene_arg = json.dumps(scene) if is_text else os.path.abspath(os.fspath(scene))
    _clothsim.resolve_scene(scene_arg, is_text, [])  # the base scene itself: a bad file stops here (ValueError)

    writer = Writer(out)
    writer.clean_partials()
    records = read_manifest(writer.manifest)
    finished = {r["id"] for r in records if r.get("status") == "ok" or (r.get("status") == "failed" and not retry_failed)}
    todo = [r for r in runs if r["id"] not in finished]
    summary = {"runs": len(runs), "skipped": len(runs) - len(todo), "ok": 0, "failed": 0, "lost": 0,
               "manifest": writer.manifest}
    bar = Progress(len(todo), progress)
    tasks = []
    for run in todo:
        sets = override_strings(run["values"])
        try:
            scene_text = _clothsim.resolve_scene(scene_arg, is_text, sets)
        except ValueError as e:  # a bad value: recorded as the command line would end, exit 2
            writer.record(run, {"exit_code": 2, "message": str(e), "files": {"log.txt": f"error: {e}\n".encode()},
                                "wall_time_s": 0.0}, None)
            summary["failed"] += 1
            bar.update(summary["failed"], summary["failed"])
            continue
        tasks.append({"id": run["id"], "scene": scene_text, "frames": frames, "backend": backend,
                      "export_every": export_every, "binary": os.path.abspath(binary)})
    if tasks:
        _run_on_dask(tasks, {r["id"]: r for r in todo}, writer, summary, bar, workers, scheduler)
    bar.finish()
    return summary


def _run_on_dask(tasks, runs, writer, summary, bar, workers, scheduler):
    import logging
    from distributed import Client, LocalCluster, as_completed

    if scheduler:
        client, cluster = Client(scheduler), None
    else:
        cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1, processes=True,
                               dashboard_address=None, silence_logs=logging.ERROR)
        client = Client(cluster)
    try:
        futures = [client.submit(simulate, t, key=f"clothsim-run-{t['id']}", pure=False) for t in tasks]
        scenes = {t["id"]: t["scene"] for t in tasks}
        done = summary["failed"]  # the bad values, recorded before any run
        for future in as_completed(futures):
            try:
                result = future.result()
            except Exception as e:  # the worker died (more often than Dask retries) or was lost
                summary["lost"] += 1
                print(f"sweep: run {future.key[len('clothsim-run-'):]} not finished ({type(e).__name__}: {e}); "
                      "a rerun of the sweep does it", file=sys.stderr)
                continue
            line = writer.record(runs[result["id"]], result, scenes[result["id"]])
            summary["ok" if line["status"] == "ok" else "failed"] += 1
            done += 1
            bar.update(done, summary["failed"])
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def main(argv=None):
    import argparse

    p = argparse.ArgumentParser(prog="clothsim sweep", description=(
        "Runs SCENE once for every combination of the --vary values (times --seeds), as tasks on Dask; "
        "each run writes OUT/runs/ID/ and a line of OUT/manifest.jsonl. Rerunning resumes."))
    p.add_argument("scene", help="the scene file")
    p.add_argument("--vary", action="append", default=[], metavar="KEY=V1,V2,...",
                   help="a scene key and its values, as --set takes them (repeat for a product)")
    p.add_argument("--seeds", type=int, default=0, help=f"also vary {SEED_KEY} over 0..N-1")
    p.add_argument("--frames", type=int, required=True, help="frames per run")
    p.add_argument("--out", required=True, help="the sweep's folder (an earlier sweep's is resumed)")
    p.add_argument("--workers", type=int, default=None, help="a local Dask cluster of N worker processes "
                   "(default: the CPU count)")
    p.add_argument("--scheduler", default=None, help="tcp://HOST:PORT of a running Dask scheduler instead")
    p.add_argument("--backend", default="gpu", choices=["gpu", "cpu"])
    p.add_argument("--export-every", type=int, default=1, help="keep every K-th frame in the point caches")
    p.add_argument("--retry-failed", action="store_true", help="redo the runs recorded as failed")
    a = p.parse_args(argv)
    if not a.vary and not a.seeds:
        p.error("nothing to sweep: give --vary KEY=V1,V2,... or --seeds N")
    if a.export_every < 1:
        p.error(f"--export-every {a.export_every}: expected a positive integer")
    try:
        s = sweep(a.scene, a.vary, a.frames, a.out, seeds=a.seeds, workers=a.workers, scheduler=a.scheduler,
                  backend=a.backend, export_every=a.export_every, retry_failed=a.retry_failed)
    except ValueError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    lost = f", {s['lost']} not finished (rerun the sweep to finish them)" if s["lost"] else ""
    print(f"sweep: {s['runs']} runs: {s['ok']} ok, {s['failed']} failed, {s['skipped']} already done{lost}; "
          f"{s['manifest']}")
    return 1 if s["lost"] else 0


if __name__ == "__main__":
    sys.exit(main())
