#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Plots a femdem sweep's sweep.csv: the main results against the first varied key, one line
per value of the other varied keys (if any). Called by `femdem sweep` at the end.

usage: tools/plot_sweep.py SWEEP_DIR [--quiet]

Writes into SWEEP_DIR, for the runs that completed:
  restitution_<body>.png   coefficient of restitution (com and kinetic energy), bodies that have one
  max_eqps_<body>.png      max equivalent plastic strain, bodies that yielded
  kinetic_energy.png       final kinetic energy of every body
  energy_balance_error.png energy balance error at the end
  wall_time.png            wall-clock time of each run
Exit code 4 when matplotlib is missing (femdem sweep then prints a note).
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "python"))
import femdem  # noqa: E402  (tools/python/femdem; needs neither numpy nor matplotlib)
from femdem.plotting import draw_flat_flat, key_label, key_unit, legend_outside  # noqa: E402


def number(text):
    try:
        v = float(text)
    except ValueError:
        return None
    return v if math.isfinite(v) else None


def parse_array(text):
    t = text.strip()
    if not (t.startswith("[") and t.endswith("]")):
        return None
    parts = [number(p) for p in t[1:-1].split(",")] if t[1:-1].strip() else []
    if not parts or any(p is None for p in parts):
        return None
    return parts


def axis_positions(key, values):
    """x positions and axis label for the values of one varied key: the numbers themselves, the
    varying component of arrays of numbers, or 0, 1, 2, ... with the values as tick labels."""
    distinct = list(dict.fromkeys(values))
    nums = [number(v) for v in distinct]
    if all(n is not None for n in nums):
        return {v: n for v, n in zip(distinct, nums)}, key, None
    arrays = [parse_array(v) for v in distinct]
    if all(a is not None for a in arrays) and len({len(a) for a in arrays}) == 1:
        varying = [i for i in range(len(arrays[0])) if len({a[i] for a in arrays}) > 1]
        if len(varying) == 1:
            i = varying[0]
            return {v: a[i] for v, a in zip(distinct, arrays)}, f"{key}[{i}]", None
    return {v: float(i) for i, v in enumerate(distinct)}, key, distinct


def main():
    args = [a for a in sys.argv[1:] if a != "--quiet"]
    quiet = "--quiet" in sys.argv[1:]
    if len(args) != 1:
        print(__doc__)
        return 2
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("plot_sweep.py: matplotlib is not installed (tools/setup installs it)", file=sys.stderr)
        return 4

    out = args[0]
    rows = femdem.read_sweep(os.path.join(out, "sweep.csv"))
    if not rows:
        print("plot_sweep.py: no finished runs in sweep.csv; no plots")
        return 0
    header = list(rows[0])
    keys = femdem.varied_keys(header)
    data = [r for r in rows if r.get("status") == "completed"]
    if not data:
        print("plot_sweep.py: no completed runs; no plots")
        return 0

    xmap, xlabel, ticks = axis_positions(keys[0], [r[keys[0]] for r in data])
    groups = {}
    for r in data:
        groups.setdefault(tuple(r[k] for k in keys[1:]), []).append(r)
    group_keys = list(groups)

    def group_label(g):
        def unit(k):
            u = key_unit(k)
            return f" {u}" if u and u != "-" else ""
        return ", ".join(f"{k.split('.')[-1]}={v}{unit(k)}" for k, v in zip(keys[1:], g))

    bodies = []
    for name in header:
        if name.startswith("bodies.") and name.endswith(".kinetic_energy") and \
                ".coefficient_of_restitution." not in name:
            bodies.append(name[len("bodies."): -len(".kinetic_energy")])

    def has_values(column, nonzero=False):
        if column not in header:
            return False
        vals = [number(r[column]) for r in data]
        return any(v is not None and (v != 0.0 or not nonzero) for v in vals)

    # (file, title, y label, [(column, line label suffix, style)], log y)
    figures = []
    for b in bodies:
        rc = f"bodies.{b}.coefficient_of_restitution."
        if has_values(rc + "com") or has_values(rc + "kinetic_energy"):
            figures.append((f"restitution_{b}.png", f"{b}: coefficient of restitution",
                            "coefficient of restitution",
                            [(rc + "com", "centre-of-mass speed", "-o"),
                             (rc + "kinetic_energy", "sqrt(KE after / KE before)", "--s")], False))
        eq = f"bodies.{b}.max_equivalent_plastic_strain"
        if has_values(eq, nonzero=True):
            figures.append((f"max_eqps_{b}.png", f"{b}: max equivalent plastic strain",
                            "max equivalent plastic strain", [(eq, "", "-o")], False))
    ke = [(f"bodies.{b}.kinetic_energy", b, "-o") for b in bodies]
    if ke:
        figures.append(("kinetic_energy.png", "final kinetic energy", "kinetic energy [J]", ke,
                        False))
    if has_values("energy.balance_error"):
        figures.append(("energy_balance_error.png", "energy balance error at the end",
                        "balance error [J]", [("energy.balance_error", "", "-o")], False))
    if has_values("wall_time_s"):
        figures.append(("wall_time.png", "wall-clock time per run", "wall time [s]",
                        [("wall_time_s", "", "-o")], False))

    xs_all = sorted(set(xmap.values()))
    log_x = ticks is None and xs_all[0] > 0 and xs_all[-1] / xs_all[0] >= 100.0
    written = []
    for fname, title, ylabel, series, log_y in figures:
        fig, ax = plt.subplots(figsize=(8.5, 4.5))
        plotted = []
        for gi, g in enumerate(group_keys):
            color = f"C{gi % 10}"
            for column, suffix, style in series:
                if column not in header:
                    continue
                pts = sorted((xmap[r[keys[0]]], number(r[column])) for r in groups[g]
                             if number(r[column]) is not None)
                if not pts:
                    continue
                plotted.append([p[1] for p in pts])
                parts = [p for p in (group_label(g), suffix) if p]
                ax.plot([p[0] for p in pts], [p[1] for p in pts], style,
                        color=color if len(group_keys) > 1 else None,
                        label=", ".join(parts) if parts else None, ms=4)
        ax.set_xlabel(key_label(xlabel))
        ax.set_ylabel(ylabel)
        ax.set_title(title)
        if log_x:
            ax.set_xscale("log")
        if log_y:
            ax.set_yscale("log")
        else:
            draw_flat_flat(ax, plotted)
        if ticks is not None:
            ax.set_xticks(range(len(ticks)))
            ax.set_xticklabels(ticks, rotation=30, ha="right")
        ax.grid(True, alpha=0.3)
        legend_outside(ax)
        fig.tight_layout()
        path = os.path.join(out, fname)
        fig.savefig(path, dpi=110)
        plt.close(fig)
        written.append(path)
    if not quiet:
        print("plots: " + ", ".join(written) if written else "plot_sweep.py: nothing to plot")
    return 0


if __name__ == "__main__":
    sys.exit(main())
