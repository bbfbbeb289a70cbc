#!/usr/bin/python3
"""Validates the shape of `clothsim bench --json` output (every field the bench promises).

usage: check_bench_json.py BENCH.json EXPECTED_RESULTS
"""
import json
import math
import sys

FIELDS = {"backend": str, "solver": str, "size": int, "particles": int, "self_collision": bool, "substeps_per_frame": int,
          "ms_per_frame": float, "particle_substeps_per_s": float, "pass_ms": dict, "pass_timing": str,
          "dispatches_per_frame": (int, float), "barriers_per_frame": (int, float), "gpu_memory_bytes": int,
          "springs": int, "colours": int}
# The passes each backend's step runs (the GPU fuses collide_objects into advance or
# resolve_self_contacts, and times the five stages of collide_self one by one).
PASSES = {"gpu": {"advance", "count_cells", "scan_cells", "fill_cells", "sort_cells", "resolve_self_contacts",
                  "solve_length_constraints", "compute_normals", "check_divergence"},
          "cpu": {"advance", "collide_self", "collide_objects", "solve_length_constraints", "compute_normals",
                  "check_divergence"}}
# fabric predicts instead of advancing and runs the multigrid solve's stages instead of Provot's
# (the V-cycle, cycle_levels, only where the cloth has coarse levels).
FABRIC_SOLVE = {"compute_residuals", "prolong_to_cloth", "relax_vertices"}
FABRIC_NAMES = {"advance": "predict"}


def main():
    data = json.load(open(sys.argv[1]))
    expected = int(sys.argv[2])
    assert isinstance(data["gl_renderer"], str) and data["gl_renderer"], "gl_renderer missing"
    results = data["results"]
    assert len(results) + len(data["skipped"]) == expected, f"{len(results)} results, expected {expected}"
    for r in results:
        for key, kind in FIELDS.items():
            assert key in r, f"missing {key} in {r}"
            value = r[key]
            if kind is float:
                assert isinstance(value, (int, float)) and math.isfinite(value) and value > 0, f"{key} = {value}"
            else:
                assert isinstance(value, kind), f"{key} has type {type(value).__name__}"
        assert r["particles"] == r["size"] ** 2
        n = r["size"]
        # The grid's springs and its own twelve colours (docs/model.md, "The cloth model").
        assert r["springs"] == 2 * (n - 1) * n + 2 * (n - 1) ** 2 + 2 * (n - 2) * n, r["springs"]
        assert r["colours"] == 12, r["colours"]
        assert r["solver"] in ("classic", "fabric"), r["solver"]
        passes = PASSES[r["backend"]]
        if r["solver"] == "fabric":
            passes = {FABRIC_NAMES.get(p, p) for p in passes} - {"solve_length_constraints"} | FABRIC_SOLVE
            assert set(r["pass_ms"]) - {"cycle_levels"} == passes, sorted(r["pass_ms"])
        else:
            assert set(r["pass_ms"]) == passes, sorted(r["pass_ms"])
        if r["backend"] == "gpu":
            assert r["dispatches_per_frame"] > 0 and r["barriers_per_frame"] > 0 and r["gpu_memory_bytes"] > 0
            # one dispatch per pass, per colour: classic at least advance + 12 colours per substep,
            # fabric at least predict, compute_residuals, prolong_to_cloth and a colour of the sweep
            floor = 13 if r["solver"] == "classic" else 4
            assert r["dispatches_per_frame"] >= floor * r["substeps_per_frame"], r["dispatches_per_frame"]
    solvers = {r["solver"] for r in results}
    assert solvers == {"classic", "fabric"}, f"solvers {solvers}: the tiny bench runs both"
    print(f"{sys.argv[1]}: {len(results)} results, all fields present")


if __name__ == "__main__":
    main()
