"""A sweep's plan and records (used by sweeps.py): the --vary values, the runs' ids, the
manifest as read back, and the checks on the output folder. Plain Python, no Dask."""
import hashlib
import itertools
import json
import os

SEED_KEY = "simulation.seed"


class SweepError(ValueError):
    """Bad sweep input: the message names the option and what was expected."""


def split_values(text):
    """'1,2,[0,-9.8,0],"a,b"' -> [1, 2, [0, -9.8, 0], 'a,b']: commas inside brackets or quotes stay."""
    parts, depth, quoted, start = [], 0, False, 0
    for i, ch in enumerate(text):
        if ch == '"' and (i == 0 or text[i - 1] != "\\"):
            quoted = not quoted
        elif not quoted and ch in "[{":
            depth += 1
        elif not quoted and ch in "]}":
            depth -= 1
        elif not quoted and depth == 0 and ch == ",":
            parts.append(text[start:i])
            start = i + 1
    parts.append(text[start:])
    values = []
    for p in parts:
        p = p.strip()
        if not p:
            raise SweepError(f"--vary: empty value in {text!r}")
        try:
            values.append(json.loads(p))
        except ValueError:
            values.append(p)  # not JSON: a string, as --set takes it
    return values


def parse_vary(vary):
    """{key: [values]} from a dict, or from 'KEY=V1,V2,...' strings (the command line's form)."""
    if isinstance(vary, dict):
        out = {}
        for key, values in vary.items():
            if not isinstance(values, (list, tuple)) or not values:
                raise SweepError(f"vary: {key}: expected a non-empty list of values")
            out[str(key)] = list(values)
        return out
    out = {}
    for item in vary or []:
        key, eq, values = str(item).partition("=")
        if not eq or not key:
            raise SweepError(f"--vary {item}: expected KEY=V1,V2,... (e.g. cloth.ks=500,5000)")
        if key in out:
            raise SweepError(f"--vary {key}: given twice")
        out[key] = split_values(values)
    return out


def run_id(values):
    """A run's name from its varied values alone: the same values are the same run in any sweep order."""
    canonical = json.dumps(values, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(canonical.encode()).hexdigest()[:12]


def plan_runs(vary, seeds):
    keys = list(vary)
    lists = [vary[k] for k in keys]
    if seeds:
        if SEED_KEY in vary:
            raise SweepError(f"--seeds: {SEED_KEY} is already varied by --vary")
        keys.append(SEED_KEY)
        lists.append(list(range(seeds)))
    runs = []
    for combo in itertools.product(*lists):
        values = dict(zip(keys, combo))
        runs.append({"id": run_id(values), "values": values})
    return runs


def read_manifest(path):
    """The manifest's records; a last line cut short by a killed sweep is dropped from the file."""
    if not os.path.exists(path):
        return []
    with open(path, "rb") as f:
        data = f.read()
    keep = data[: data.rfind(b"\n") + 1]
    if len(keep) != len(data):
        with open(path, "r+b") as f:
            f.truncate(len(keep))
    records = []
    for n, line in enumerate(keep.decode("utf-8").splitlines(), 1):
        if line.strip():
            try:
                records.append(json.loads(line))
            except ValueError:
                raise SweepError(f"{path}:{n}: not a manifest line (JSON expected); is OUT another program's folder?")
    return records


def check_out(out):
    if os.path.islink(out):
        raise SweepError(f"--out {out}: is a symbolic link; name the folder itself")
    if os.path.exists(out) and not os.path.isdir(out):
        raise SweepError(f"--out {out}: exists and is not a folder")
    if os.path.isdir(out):
        extra = set(os.listdir(out)) - {"runs", "manifest.jsonl"}
        if extra:
            raise SweepError(f"--out {out}: holds files that are not a sweep's ({', '.join(sorted(extra)[:3])}); "
                             "name a new or empty folder, or an earlier sweep's to resume it")
