#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Plots a compaction run (a scene with a [compaction] section): the compaction curve
(relative density against mean punch pressure), force against punch displacement, and the
Heckel plot ln(1/(1-D)) against pressure with the fit from summary.json.

usage: tools/plot_compaction.py OUT_DIR
       (writes OUT_DIR/compaction_curve.png, force_displacement.png, heckel.png)
"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from history_csv import read_history  # noqa: E402  (tools/history_csv.py)
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    out = sys.argv[1]
    h = read_history(os.path.join(out, "history.csv"))
    if "compaction.punch_pressure" not in h:
        print(f"{out}/history.csv has no compaction columns (the scene needs [compaction])")
        return 1
    summary = {}
    try:
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f).get("compaction", {})
    except (OSError, ValueError):
        pass  # a run still going: plot the curve without the fit
    P = [p / 1e6 for p in h["compaction.punch_pressure"]]
    D = h["compaction.relative_density"]
    written = []

    fig, ax = plt.subplots(figsize=(7, 5))
    ax.plot(P, D, lw=1.5)
    ax.set_xlabel("mean punch pressure [MPa]")
    ax.set_ylabel("relative density D")
    ax.set_title("Compaction curve")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "compaction_curve.png"), dpi=120)
    written.append("compaction_curve.png")
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(7, 5))
    d_mm = [d * 1e3 for d in h["compaction.punch_displacement"]]
    ax.plot(d_mm, h["compaction.punch_force"], label="punch")
    ax.plot(d_mm, h["compaction.bottom_force"], label="bottom", ls="--")
    if any(v != 0.0 for v in h["compaction.die_axial_force"]):
        ax.plot(d_mm, h["compaction.die_axial_force"], label="die-wall friction", ls=":")
    ax.set_xlabel("punch displacement [mm]")
    ax.set_ylabel("force [N]")
    ax.set_title("Force against punch displacement")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "force_displacement.png"), dpi=120)
    written.append("force_displacement.png")
    plt.close(fig)

    # Heckel: the loading part only (up to the largest pressure), as the fit uses
    peak = max(range(len(P)), key=lambda i: P[i]) if P else 0
    hp, hy = [], []
    for i in range(peak + 1):
        if 0.0 < D[i] < 1.0:
            hp.append(P[i])
            hy.append(math.log(1.0 / (1.0 - D[i])))
    fig, ax = plt.subplots(figsize=(7, 5))
    ax.plot(hp, hy, ".", ms=3, label="run (loading)")
    fit = summary.get("heckel", {})
    if fit.get("K") is not None and fit.get("A") is not None and fit.get("points", 0) >= 2:
        lo, hi = fit["pressure_min"] / 1e6, fit["pressure_max"] / 1e6
        K, A = fit["K"] * 1e6, fit["A"]
        ax.plot([lo, hi], [K * lo + A, K * hi + A], "r-", lw=2,
                label=(f"Heckel fit: K = {fit['K']:.3g} 1/Pa, A = {A:.3f}\n"
                       f"yield pressure {fit['yield_pressure'] / 1e6:.3g} MPa, "
                       f"R² = {fit['r2']:.4f}"))
    ax.set_xlabel("mean punch pressure P [MPa]")
    ax.set_ylabel("ln(1 / (1 − D))")
    ax.set_title("Heckel plot")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "heckel.png"), dpi=120)
    written.append("heckel.png")
    plt.close(fig)

    print("wrote " + ", ".join(os.path.join(out, w) for w in written))
    return 0


if __name__ == "__main__":
    sys.exit(main())
