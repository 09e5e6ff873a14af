#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Taylor bar results from a femdem run: final length, mean base radius, maximum equivalent
plastic strain, their histories, and a figure of the final profile against the initial one.

usage: tools/taylor_profile.py OUT_DIR [--json]
Writes OUT_DIR/taylor_profile.png and OUT_DIR/taylor_history.png and prints the numbers
(reference, thesis ch. 4: length 21.48 mm, mean base radius 7.12 mm).
"""
import json
import os
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "python"))
import femdem  # noqa: E402  (tools/python/femdem)
from femdem.plotting import legend_outside  # noqa: E402


def main():
    out = sys.argv[1]
    f = femdem.open_results(out)
    X = f.coordinates
    times = f.times
    n = len(times)
    R0 = np.max(np.linalg.norm(X[:, :2], axis=1))
    base = np.where(np.abs(X[:, 2] - X[:, 2].min()) < 1e-9)[0]
    rim = base[np.abs(np.linalg.norm(X[base, :2], axis=1) - R0) < 1e-6 * R0]
    lengths, radii, eqps = [], [], []
    for k in range(n):
        x = f.positions(k)
        lengths.append(x[:, 2].max() - x[:, 2].min())
        radii.append(np.mean(np.linalg.norm(x[rim, :2], axis=1)))
        eqps.append(f.field("equivalent_plastic_strain", k).max())
    x = f.positions(n - 1)
    result = {"time": float(times[-1]), "length_mm": 1e3 * lengths[-1],
              "mean_base_radius_mm": 1e3 * radii[-1], "max_equivalent_plastic_strain": float(eqps[-1]),
              "frames": n, "complete": int(f.complete)}
    f.close()

    fig, ax = plt.subplots(figsize=(5, 7))
    for pts, label, style in [(X, "initial", "k--"), (x, f"t = {1e6 * times[-1]:.0f} us", "b-")]:
        r = np.linalg.norm(pts[:, :2], axis=1) * 1e3
        z = pts[:, 2] * 1e3
        bins = np.linspace(z.min(), z.max(), 60)
        idx = np.digitize(z, bins)
        zr = [(z[idx == i].mean(), r[idx == i].max()) for i in range(1, len(bins)) if np.any(idx == i)]
        zz, rr = np.array(zr).T
        ax.plot(rr, zz, style, label=label)
        ax.plot(-rr, zz, style)
    ax.axhline(0, color="gray", lw=3)
    ax.set_aspect("equal")
    ax.set_xlabel("radius [mm]")
    ax.set_ylabel("height [mm]")
    ax.set_title(f"Taylor bar: L = {result['length_mm']:.2f} mm (21.48), "
                 f"R = {result['mean_base_radius_mm']:.2f} mm (7.12)", fontsize=9)
    legend_outside(ax)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "taylor_profile.png"), dpi=120)
    plt.close(fig)

    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    t_us = 1e6 * times
    axes[0].plot(t_us, 1e3 * np.array(lengths), label="length")
    axes[0].axhline(21.48, color="k", ls="--", lw=0.8, label="thesis 21.48 mm")
    axes[0].set_xlabel("time [us]")
    axes[0].set_ylabel("length [mm]")
    legend_outside(axes[0])
    axes[1].plot(t_us, 1e3 * np.array(radii), label="mean base radius")
    axes[1].axhline(7.12, color="k", ls="--", lw=0.8, label="thesis 7.12 mm")
    axes[1].set_xlabel("time [us]")
    axes[1].set_ylabel("radius [mm]")
    legend_outside(axes[1])
    fig.tight_layout()
    fig.savefig(os.path.join(out, "taylor_history.png"), dpi=120)
    plt.close(fig)
    print(json.dumps(result, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
