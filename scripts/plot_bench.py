#!/usr/bin/python3
"""Plots `clothsim bench --json` output: particle-substeps/s against particles, log-log,
one line per backend x self-collision.

usage: scripts/plot_bench.py BENCH.json OUT.png [--title TEXT]
"""
import argparse
import json

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("bench_json")
    ap.add_argument("out_png")
    ap.add_argument("--title", default=None)
    args = ap.parse_args()
    with open(args.bench_json) as f:
        data = json.load(f)
    lines = {}
    for r in data["results"]:
        key = (r["backend"], r["self_collision"])
        lines.setdefault(key, []).append((r["particles"], r["particle_substeps_per_s"]))
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for (backend, sc), pts in sorted(lines.items()):
        pts.sort()
        style = "-" if backend == "gpu" else "--"
        ax.plot([p for p, _ in pts], [v for _, v in pts], style, marker="o",
                label=f"{backend}, self-collision {'on' if sc else 'off'}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("particles")
    ax.set_ylabel("particle-substeps per second")
    ax.set_title(args.title or f"clothsim bench on {data['gl_renderer']}", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.out_png, dpi=100)
    print(f"wrote {args.out_png}")


if __name__ == "__main__":
    main()
