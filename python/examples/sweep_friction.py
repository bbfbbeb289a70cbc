#!/usr/bin/env python3
"""A friction sweep on a slope, against the closed form (docs/sweeps.md shows its plot).

A 0.3 m x 0.2 m cloth lies on a plane tilted by 20 degrees (the gravity is tilted instead, which
is the same thing); the sweep runs it once per Coulomb friction coefficient mu. A block on such a
slope slides a distance 1/2 g (sin theta - mu cos theta) t^2 in time t, and not at all once mu
reaches tan theta = 0.364. Each run's point cache gives the cloth's mean distance down the slope.
The sweep is a product: every mu on each solver. fabric applies Coulomb friction; the
classic solver keeps CS184's rule (the tangential move scaled by 1 - mu), which is not Coulomb's.

    PYTHONPATH=build/python /usr/bin/python3 python/examples/sweep_friction.py OUT_DIR [PLOT.png]
"""
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import clothsim  # noqa: E402

THETA = math.radians(20.0)
G = 9.8
FRAMES, FPS = 45, 90  # half a second
MUS = [round(0.05 * k, 2) for k in range(11)]  # 0 to 0.5
SOLVERS = ["classic", "fabric"]  # a product: 22 runs

SCENE = {
    # A cloth lying flat 0.1 mm above a floor, gravity tilted by THETA along +x.
    "cloth": {"width": 0.3, "height": 0.2, "num_width_points": 13, "num_height_points": 9, "thickness": 0.0095,
              "orientation": 0, "density": 0.15, "damping": 0, "ks": 5000},
    "plane": {"point": [0, 1.0 - 1e-4, 0], "normal": [0, 1, 0], "friction": 0.0},
    "simulation": {"gravity": [G * math.sin(THETA), -G * math.cos(THETA), 0], "frames_per_sec": FPS,
                   "simulation_steps": 30, "self_collision": False},
}


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    plot = sys.argv[2] if len(sys.argv) > 2 else os.path.join(out, "sweep_friction.png")
    summary = clothsim.sweep(SCENE, {"plane.friction": MUS, "simulation.solver": SOLVERS}, frames=FRAMES, out=out,
                             workers=2, backend="cpu")
    print(summary)
    with open(os.path.join(out, "manifest.jsonl")) as f:
        runs = [json.loads(line) for line in f if line.strip()]
    t = np.arange(FRAMES + 1) / FPS
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    measured = {solver: {} for solver in SOLVERS}
    for run in sorted(runs, key=lambda r: r["values"]["plane.friction"]):
        mu, solver = run["values"]["plane.friction"], run["values"]["simulation.solver"]
        if run["status"] != "ok":
            print(f"mu {mu}, {solver}: {run['message']}")
            continue
        x = clothsim.read_pc2(os.path.join(out, "runs", run["id"], "cloth.pc2"))[:, :, 0].mean(axis=1)
        slide = x - x[0]
        measured[solver][mu] = slide[-1]
        if solver == "fabric":
            left.plot(t, 100 * slide, label=f"μ {mu:g}")
    left.set(xlabel="time (s)", ylabel="distance down the slope (cm)", title="fabric: the cloth's mean, per run")
    left.legend(fontsize=7, ncol=2)
    mus = np.linspace(0, max(MUS), 200)
    closed = 0.5 * np.maximum(0, G * (math.sin(THETA) - mus * math.cos(THETA))) * t[-1] ** 2
    right.plot(mus, 100 * closed, "k-", label="closed form ½ g (sin θ − μ cos θ) t²")
    for solver, marker in zip(SOLVERS, "so"):
        right.plot(list(measured[solver]), [100 * v for v in measured[solver].values()], marker, label=solver)
    right.axvline(math.tan(THETA), color="grey", ls=":", label="μ = tan θ: it holds")
    right.set(xlabel="friction coefficient μ", ylabel=f"distance after {t[-1]:g} s (cm)",
              title="a 20° slope: slide against friction")
    right.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(plot, dpi=110)
    print("  mu  closed form " + " ".join(f"{s:>8}" for s in SOLVERS) + "  (cm slid in half a second)")
    for mu in MUS:
        c = 0.5 * max(0.0, G * (math.sin(THETA) - mu * math.cos(THETA))) * t[-1] ** 2
        row = " ".join(f"{100 * measured[s][mu]:8.2f}" if mu in measured[s] else "       -" for s in SOLVERS)
        print(f"{mu:4.2f}  {100 * c:11.2f} {row}")
    print(f"wrote {plot}")


if __name__ == "__main__":
    main()
