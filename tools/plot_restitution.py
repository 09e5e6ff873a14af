#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Plots the steel-ball-on-concrete restitution sweep against the thesis (ch. 5) and the
experiments, and prints the comparison as a markdown table.

usage: tools/plot_restitution.py SWEEP_CSV [-o PNG] [--body NAME]

SWEEP_CSV is the sweep.csv of
  femdem sweep scenes/ball_on_concrete.toml --vary 'bodies.ball.velocity=[0,0,-4.3],...' \\
               --vary bodies.prism.material=concrete_mc1,...
(the impact speed is the norm of the varied velocity; the restitution is
bodies.NAME.coefficient_of_restitution.com, the ratio of the ball's centre-of-mass speeds, which
is the thesis' "average vertical velocity of all mass points"). One line per value of the varied
*.material key (one line if none is varied): the Mohr-Coulomb cases concrete_mc1..4 with the
thesis' simulated values (Table 5.5) as dashed lines of the same colour, the piece-wise
Drucker-Prager model concrete_pwdp, other materials (stand-ins) by their names; the experiments
(Table 5.2) as black means with their ranges as error bars. The PNG goes next to the CSV
(restitution.png) unless -o names it.
"""
import argparse
import csv
import math
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "python"))
import femdem  # noqa: E402  (tools/python/femdem)
from femdem.plotting import legend_outside  # noqa: E402

REFERENCE_CSV = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes",
                             "ball_on_concrete_reference.csv")


def read_reference(path=REFERENCE_CSV):
    """The thesis' Table 5.5 (simulated, per material: speeds and e) and Table 5.2 (experiments:
    speed, mean, lowest, highest), from the CSV next to the scene."""
    thesis, experiments = {}, []
    with open(path, newline="") as f:
        rows = csv.DictReader(line for line in f if not line.startswith("#"))
        for r in rows:
            speed, e = float(r["speed"]), float(r["e"])
            if r["source"] == "table5.5":
                thesis.setdefault(r["material"], ([], []))
                thesis[r["material"]][0].append(speed)
                thesis[r["material"]][1].append(e)
            else:
                experiments.append((speed, e, float(r["e_lowest"]), float(r["e_highest"])))
    return thesis, experiments


# THESIS[material] = (speeds, e); EXPERIMENTS = [(speed, mean, lowest, highest)]
THESIS, EXPERIMENTS = read_reference()
LABELS = {
    "concrete_mc1": "MC case 1 (c 15 MPa, φ 30°)",
    "concrete_mc2": "MC case 2 (c 45 MPa, φ 10°)",
    "concrete_mc2_phi13": "MC case 2 read as φ 13° (Table 5.3)",
    "concrete_mc3": "MC case 3 (c 70 MPa, φ 5°)",
    "concrete_mc4": "MC case 4 (c 100 MPa, φ 0°)",
    "concrete_pwdp": "piece-wise DP",
}
# Thesis Table 5.2: impact speed, mean, lowest and highest restitution of the drop tests
EXPERIMENTS = [(4.3, 0.379, 0.34, 0.42), (5.4, 0.369, 0.34, 0.39), (6.35, 0.346, 0.32, 0.36)]


def speed_of(text):
    nums = [float(x) for x in re.findall(r"[-+]?\d*\.?\d+(?:[eE][-+]?\d+)?", text)]
    return math.sqrt(sum(x * x for x in nums))


def thesis_value(material, speed):
    if material not in THESIS:
        return None
    for v, e in zip(*THESIS[material]):
        if abs(v - speed) < 1e-6:
            return e
    return None


def experiment_at(speed):
    for v, mean, lo, hi in EXPERIMENTS:
        if abs(v - speed) < 1e-6:
            return mean, lo, hi
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("csv")
    ap.add_argument("-o", "--out", default=None, help="the PNG (default: restitution.png next to the CSV)")
    ap.add_argument("--body", default="ball", help="the impactor (default: ball)")
    args = ap.parse_args()
    rows = femdem.read_sweep(args.csv)
    if not rows:
        print(f"{args.csv}: no finished runs", file=sys.stderr)
        return 2
    keys = list(rows[0].keys())
    vkey = next((k for k in keys[: keys.index("run")] if k.endswith(".velocity")), None)
    mkey = next((k for k in keys[: keys.index("run")] if k.endswith(".material")), None)
    ekey = f"bodies.{args.body}.coefficient_of_restitution.com"
    if vkey is None or ekey not in keys:
        print(f"{args.csv}: needs a varied *.velocity column and {ekey}", file=sys.stderr)
        return 2

    # material -> sorted [(speed, e)], in the order the sweep gives the materials
    results = {}
    skipped = []
    for r in rows:
        material = r[mkey].strip('"') if mkey else "femdem"
        speed = speed_of(r[vkey])
        results.setdefault(material, [])
        if r.get("status") != "completed" or r.get(ekey, "") == "":
            skipped.append(f"{material} at {speed:g} m/s ({r.get('status') or 'no result'})")
            continue
        results[material].append((speed, float(r[ekey])))
    for m in results:
        results[m].sort()

    fig, ax = plt.subplots(figsize=(9.5, 5))
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for i, (material, pts) in enumerate(results.items()):
        color = colors[i % len(colors)]
        label = LABELS.get(material, material)
        if pts:
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "-o", color=color, label=label)
        if material in THESIS:
            ax.plot(*THESIS[material], "--", color=color, alpha=0.8,
                    label=f"{label.split(' (')[0]}, thesis")
    ev = [x[0] for x in EXPERIMENTS]
    em = [x[1] for x in EXPERIMENTS]
    err = [[x[1] - x[2] for x in EXPERIMENTS], [x[3] - x[1] for x in EXPERIMENTS]]
    ax.errorbar(ev, em, yerr=err, fmt="s", color="k", capsize=4, label="experiments (mean, range)")
    ax.set_xlabel("impact speed [m/s]")
    ax.set_ylabel("coefficient of restitution (ball's centre of mass)")
    ax.set_title("Steel ball on a concrete prism (thesis ch. 5)")
    ax.grid(alpha=0.3)
    legend_outside(ax)
    fig.tight_layout()
    out = args.out or os.path.join(os.path.dirname(os.path.abspath(args.csv)), "restitution.png")
    fig.savefig(out, dpi=130)

    print("| material | v (m/s) | e (femdem) | thesis | difference | experiments mean (range) |")
    print("|---|---:|---:|---:|---:|---|")
    for material, pts in results.items():
        for speed, e in pts:
            t = thesis_value(material, speed)
            x = experiment_at(speed)
            ts = f"{t:.3f}" if t is not None else "–"
            ds = f"{e - t:+.3f}" if t is not None else "–"
            xs = f"{x[0]:.3f} ({x[1]:.2f}–{x[2]:.2f})" if x else "–"
            print(f"| {LABELS.get(material, material)} | {speed:g} | {e:.3f} | {ts} | {ds} | {xs} |")
    for s in skipped:
        print(f"not plotted: {s}", file=sys.stderr)
    print(f"figure: {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
