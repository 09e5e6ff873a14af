#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The armour layer at 30, 100 and 300 units: cost per body and step as the layer grows.

usage: tools/bench/armour_scaling.py [--units 30,100,300] [--window 0.6,0.7] [--threads 1]
       [--femdem build/femdem] [--out out/armour_scaling]

Each size is scenes/armour_layer.toml made wider: the flume, the packing box and the rows of
fixed cubes on the slope grow with the number of units (30 units fill 8 m of width, so N units
fill 8 N / 30 m), so every unit sees the same neighbourhood on average and the cost per body
should stay flat. The packing generator places the N units (seed 6, as the shipped scene); the
30-unit size is the shipped scene itself, with its cached packing.

Each run goes to the start of the window (units landing since 0.4 s), where femdem writes its
checkpoint, then `femdem resume` runs the window. Measured over the window only: user CPU time
of the resume (GNU time; immune to a loaded machine's descheduling), steps, steps per CPU
second, element updates per CPU second, candidate and touching contact pairs per step, and CPU
time per body per step. Prints a Markdown table for docs/PERFORMANCE.md.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
SCENE = os.path.join(ROOT, "scenes", "armour_layer.toml")
UNITS_PER_WIDTH = 30 / 8.0  # the shipped scene: 30 units across 8 m
CUBE_PITCH = 2.5  # the fixed cubes' spacing across the flume (m)
SIDE_CLEARANCE = 0.6  # side walls 0.6 m outside the packing box, as shipped


def scaled_scene(units, out_dir):
    """The shipped scene's text widened for `units` units (30 units: the scene itself)."""
    text = open(SCENE).read()
    width = units / UNITS_PER_WIDTH
    head, rest = text.split("[[bodies]]", 1)
    bodies = re.findall(r"\[\[bodies\]\]\n(.*?)(?=\n\[\[|\n\[[a-z])", "[[bodies]]" + rest, re.S)
    rows = sorted({re.search(r"position = \[([-\d.]+), [-\d.]+, ([-\d.]+)\]", b).groups()
                   for b in bodies})
    columns = max(1, round(3 * units / 30))
    cubes = []
    for r, (x, z) in enumerate(rows):
        for c in range(columns):
            y = CUBE_PITCH * (c - (columns - 1) / 2.0)
            cubes.append(
                f'[[bodies]]\nname = "base{r}_{c}"\nmaterial = "concrete"\n'
                f'mesh = {{ file = "{ROOT}/scenes/meshes/cube.stl", element_size = 0.7 }}\n'
                f"rotation = [0.0, -33.6901, 0.0]\nposition = [{x}, {y:.4f}, {z}]\n"
                "fixed = true\n")
    tail = "[[packings]]" + rest.split("[[packings]]", 1)[1]
    side = width / 2 + SIDE_CLEARANCE
    for old, new in (
            ('file = "meshes/', f'file = "{ROOT}/scenes/meshes/'),
            ('cache = "packings/armour_layer_30.csv"', f'cache = "{out_dir}/packing_{units}.csv"'),
            ("size = [20.0, 8.0, 12.0], count = 30",
             f"size = [20.0, {width:.4f}, 12.0], count = {units}"),
            ("position = [1.2481, -4.0, 2.6348]", f"position = [1.2481, {-width / 2:.4f}, 2.6348]"),
            ("point = [0.0, -4.6, 0.0]", f"point = [0.0, {-side:.4f}, 0.0]"),
            ("point = [0.0, 4.6, 0.0]", f"point = [0.0, {side:.4f}, 0.0]")):
        if old not in tail:  # the shipped scene changed under this script
            sys.exit(f"armour_scaling: '{old}' is no longer in {SCENE}; update this script")
        tail = tail.replace(old, new)
    return head + "\n".join(cubes) + "\n" + tail


def timed(cmd):
    """Runs cmd under GNU time; returns its user CPU seconds."""
    r = subprocess.run(["/usr/bin/time", "-f", "@user %U"] + cmd, stdout=subprocess.DEVNULL,
                       stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        sys.exit(f"armour_scaling: {' '.join(cmd)} failed ({r.returncode}):\n{r.stderr[-2000:]}")
    return float(re.search(r"@user ([\d.]+)", r.stderr).group(1))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--units", default="30,100,300")
    ap.add_argument("--window", default="0.6,0.7", help="start,end of the measured window (s)")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--femdem", default=os.path.join(ROOT, "build", "femdem"))
    ap.add_argument("--out", default="out/armour_scaling")
    a = ap.parse_args()
    t0, t1 = (float(v) for v in a.window.split(","))
    os.makedirs(a.out, exist_ok=True)
    out = os.path.abspath(a.out)
    rows = []
    for units in (int(u) for u in a.units.split(",")):
        scene = SCENE  # 30 units: the shipped scene itself
        if units != 30:
            scene = f"{out}/armour_{units}.toml"
            open(scene, "w").write(scaled_scene(units, out))
        run = f"{out}/run_{units}"
        shutil.rmtree(run, ignore_errors=True)
        common = ["--threads", str(a.threads), "--quiet", "--no-plot"]
        timed([a.femdem, "run", scene, "--out", run, "--set", f"simulation.end_time={t0}"] + common)
        before = json.load(open(f"{run}/summary.json"))
        cpu = timed([a.femdem, "resume", run, "--set", f"simulation.end_time={t1}"] + common)
        after = json.load(open(f"{run}/summary.json"))
        steps = after["steps"] - before["steps"]
        ex0, ex1 = before["extra"], after["extra"]
        cand = ex1["contact_pair_evaluations"] - ex0["contact_pair_evaluations"]
        touch = ex1["contact_touching_pair_evaluations"] - ex0["contact_touching_pair_evaluations"]
        bodies = len(after["bodies"])
        elements = after["elements"]
        rows.append((units, bodies, elements, steps, cpu, cand / steps, touch / steps,
                     cpu / steps / units * 1e6, steps * elements / cpu))
        print(f"{units} units done: {steps} steps, {cpu:.1f} s CPU, {cand / steps:.0f} candidate "
              f"and {touch / steps:.1f} touching pairs per step, {elements} elements",
              file=sys.stderr, flush=True)
    print(f"| units | bodies | elements | steps in [{t0}, {t1}] s | CPU s | steps per CPU s |"
          " candidate pairs / step | touching pairs / step | candidates / unit / step |"
          " CPU us / unit / step | element updates per CPU s |")
    print("| " + " | ".join(["---"] * 11) + " |")
    for u, b, e, n, cpu, cand, touch, per_unit, rate in rows:
        print(f"| {u} | {b} | {e} | {n} | {cpu:.1f} | {n / cpu:.1f} | {cand:.0f} | {touch:.1f} |"
              f" {cand / u:.1f} | {per_unit:.0f} | {rate / 1e6:.2f} M |")


if __name__ == "__main__":
    main()
