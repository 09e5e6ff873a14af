#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Fits Thornton's (1997) elastic-perfectly-plastic restitution law to a restitution sweep.

usage: tools/thornton_fit.py SWEEP_CSV [--body NAME] [--out PNG]

SWEEP_CSV is the sweep.csv of `femdem sweep SCENE --vary bodies.NAME.velocity=...` (the impact
speed is the norm of the varied velocity). Thornton, J. Appl. Mech. 64 (1997) 383, for impact
speeds V above the yield speed V_y:
  e = sqrt(6 sqrt(3) / 5) sqrt(1 - (V_y/V)^2 / 6)
      * [ (V_y/V) / ((V_y/V) + 2 sqrt(6/5 - (V_y/V)^2 / 5)) ]^(1/4)
Prints the measured restitutions, the fitted V_y and the fit's residuals, and draws them with
the thesis' values (V_y = 7 m/s: e(20) = 0.87, e(50) = 0.71) into a PNG next to the CSV.
"""
import argparse
import math
import os
import re
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "python"))
import femdem  # noqa: E402  (tools/python/femdem)
from femdem.plotting import legend_outside  # noqa: E402


def thornton(v, vy):
    r = np.minimum(vy / np.asarray(v, dtype=float), 1.0)  # e = 1 below V_y
    e = (math.sqrt(6.0 * math.sqrt(3.0) / 5.0) * np.sqrt(1.0 - r * r / 6.0)
         * (r / (r + 2.0 * np.sqrt(1.2 - r * r / 5.0))) ** 0.25)
    return np.where(r < 1.0, e, 1.0)


def fit_vy(v, e):
    """Least-squares V_y by golden-section search on (0, min(v))."""
    def cost(vy):
        return float(np.sum((thornton(v, vy) - e) ** 2))
    lo, hi = 1e-6, float(np.min(v)) * 0.999
    g = (math.sqrt(5.0) - 1.0) / 2.0
    a, b = hi - g * (hi - lo), lo + g * (hi - lo)
    for _ in range(200):
        if cost(a) < cost(b):
            hi = b
        else:
            lo = a
        a, b = hi - g * (hi - lo), lo + g * (hi - lo)
    return 0.5 * (lo + hi)


def speed_of(text):
    nums = [float(x) for x in re.findall(r"[-+]?\d*\.?\d+(?:[eE][-+]?\d+)?", text)]
    return math.sqrt(sum(x * x for x in nums))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("csv")
    ap.add_argument("--body", default="ball")
    ap.add_argument("--out", default=None)
    args = ap.parse_args()
    rows = femdem.read_sweep(args.csv)
    vkey = next((k for k in rows[0] if k.startswith("bodies.") and k.endswith(".velocity")), None)
    ekey = f"bodies.{args.body}.coefficient_of_restitution.com"
    if vkey is None or ekey not in rows[0]:
        print(f"{args.csv}: needs a varied *.velocity column and {ekey}", file=sys.stderr)
        return 2
    pts = sorted((speed_of(r[vkey]), float(r[ekey])) for r in rows if r.get(ekey, "") != "")
    if len(pts) < 2:
        print("fewer than two runs with a restitution", file=sys.stderr)
        return 2
    v, e = np.array(pts).T
    vy = fit_vy(v, e)
    print(f"fitted V_y = {vy:.3f} m/s (thesis: 7 m/s)")
    print("  V (m/s)   e measured   Thornton(fit)   Thornton(V_y = 7)")
    for vi, ei, ef, e7 in zip(v, e, thornton(v, vy), thornton(v, 7.0)):
        print(f"  {vi:7.2f}   {ei:10.4f}   {ef:13.4f}   {e7:17.4f}")
    vv = np.linspace(max(0.5, 0.8 * vy), 1.1 * v.max(), 200)
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(v, e, "o", label="femdem")
    ax.plot(vv, thornton(vv, vy), "-", label=f"Thornton, fitted V_y = {vy:.2f} m/s")
    ax.plot(vv, thornton(vv, 7.0), "--", color="gray", label="Thornton, V_y = 7 m/s (thesis)")
    ax.plot([20, 50], [0.87, 0.71], "s", color="k", mfc="none", label="thesis")
    ax.set_xlabel("impact speed [m/s]")
    ax.set_ylabel("coefficient of restitution (centre of mass)")
    ax.set_ylim(0.0, 1.05)
    legend_outside(ax)
    fig.tight_layout()
    out = args.out or os.path.join(os.path.dirname(os.path.abspath(args.csv)), "thornton_fit.png")
    fig.savefig(out, dpi=120)
    print(f"figure: {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
