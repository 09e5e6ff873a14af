#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Plots a compaction run (a scene with a [compaction] section): the compaction curve
(relative density against mean punch pressure), force against punch displacement, and the
Heckel plot ln(1/(1-D)) against pressure with the fit from summary.json.

usage: tools/plot_compaction.py OUT_DIR
       (writes OUT_DIR/compaction_curve.png, force_displacement.png, heckel.png)
       tools/plot_compaction.py --compare OUT_DIR OUT_DIR ... -o PNG [--labels A,B,...]
       (one figure with the runs' compaction curves and Heckel plots, e.g. a friction sweep,
       and a table of the relative density at given pressures, the peak density, the share of
       the punch force the die wall carries and the Heckel fit)
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "python"))
import femdem  # noqa: E402  (tools/python/femdem)
from femdem.plotting import legend_outside  # noqa: E402
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def loading_part(h):
    """Pressure (MPa) and relative density up to the peak pressure."""
    P = [p / 1e6 for p in h["compaction.punch_pressure"]]
    D = h["compaction.relative_density"]
    peak = max(range(len(P)), key=lambda i: P[i]) if P else 0
    return P[: peak + 1], D[: peak + 1], peak


def density_at(P, D, p):
    """D where the loading curve first reaches pressure p (MPa), or None."""
    for i in range(1, len(P)):
        if P[i - 1] < p <= P[i]:
            w = (p - P[i - 1]) / (P[i] - P[i - 1])
            return D[i - 1] + w * (D[i] - D[i - 1])
    return None


def pressure_at(P, D, d):
    """Pressure (MPa) where the loading curve first reaches relative density d, or None."""
    for i in range(1, len(D)):
        if D[i - 1] < d <= D[i]:
            w = (d - D[i - 1]) / (D[i] - D[i - 1])
            return P[i - 1] + w * (P[i] - P[i - 1])
    return None


def compare(dirs, png, labels):
    pressures = (25.0, 50.0, 100.0)
    densities = (0.6, 0.7, 0.8, 0.85)
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 5))
    print("run | " + " | ".join(f"P (MPa) at D {d:g}" for d in densities) + " | " +
          " | ".join(f"D at {p:g} MPa" for p in pressures) +
          " | peak P (MPa) | D at peak | die wall share of punch force at peak | "
          "Heckel yield pressure (MPa), R² | wall time (min)")
    for out, label in zip(dirs, labels):
        h = femdem.read_history(os.path.join(out, "history.csv"))
        summ = {}
        try:
            summ = femdem.read_summary(out)
        except (OSError, ValueError):
            pass
        P, D, peak = loading_part(h)
        ax1.plot(P, D, lw=1.5, label=label)
        hp = [p for p, d in zip(P, D) if 0.0 < d < 1.0]
        hy = [math.log(1.0 / (1.0 - d)) for d in D if 0.0 < d < 1.0]
        ax2.plot(hp, hy, lw=1.2, label=label)
        share = (h["compaction.die_axial_force"][peak] / h["compaction.punch_force"][peak]
                 if h["compaction.punch_force"][peak] else float("nan"))
        fit = summ.get("compaction", {}).get("heckel", {})
        heckel = (f"{fit['yield_pressure'] / 1e6:.1f}, {fit['r2']:.3f}"
                  if fit.get("yield_pressure") else "-")
        cells = [density_at(P, D, p) for p in pressures]
        at_d = [pressure_at(P, D, d) for d in densities]
        wall = summ.get("wall_time_s")
        print(f"{label} | " + " | ".join(f"{c:.1f}" if c is not None else "-" for c in at_d) +
              " | " + " | ".join(f"{c:.4f}" if c is not None else "-" for c in cells) +
              f" | {P[peak]:.1f} | {D[peak]:.4f} | {share:.3f} | {heckel} | "
              + (f"{wall / 60:.1f}" if wall else "-"))
    ax1.set_xlabel("mean punch pressure [MPa]")
    ax1.set_ylabel("relative density D")
    ax1.set_title("Compaction curves (loading)")
    ax1.grid(alpha=0.3)
    legend_outside(ax1)
    ax2.set_xlabel("mean punch pressure P [MPa]")
    ax2.set_ylabel("ln(1 / (1 − D))")
    ax2.set_title("Heckel plots (loading)")
    ax2.grid(alpha=0.3)
    legend_outside(ax2)
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    print(f"wrote {png}")
    return 0


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--compare":
        args = sys.argv[2:]
        png, labels = None, None
        dirs = []
        i = 0
        while i < len(args):
            if args[i] == "-o" and i + 1 < len(args):
                png, i = args[i + 1], i + 2
            elif args[i] == "--labels" and i + 1 < len(args):
                labels, i = args[i + 1].split(","), i + 2
            else:
                dirs.append(args[i])
                i += 1
        if not dirs or png is None or (labels is not None and len(labels) != len(dirs)):
            print(__doc__)
            return 2
        return compare(dirs, png, labels or [os.path.basename(d.rstrip("/")) for d in dirs])
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    out = sys.argv[1]
    h = femdem.read_history(os.path.join(out, "history.csv"))
    if "compaction.punch_pressure" not in h:
        print(f"{out}/history.csv has no compaction columns (the scene needs [compaction])")
        return 1
    summary = {}
    try:
        summary = femdem.read_summary(out).get("compaction", {})
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
    legend_outside(ax)
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
    legend_outside(ax)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "heckel.png"), dpi=120)
    written.append("heckel.png")
    plt.close(fig)

    print("wrote " + ", ".join(os.path.join(out, w) for w in written))
    return 0


if __name__ == "__main__":
    sys.exit(main())
