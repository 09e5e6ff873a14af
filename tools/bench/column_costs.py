#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""What each column-collapse run cost, as a row of docs/PERFORMANCE.md's table.

usage: tools/bench/column_costs.py [--cpu LOG]... OUT/NAME [OUT/NAME ...]

Reads each run's summary.json: grains (bodies), TET10, steps, the mean step (the run's end time
over its steps), wall time, and the contact pairs a step: the candidate sub-tet pairs and those
found touching (summary.json's `contact_pair_evaluations` and
`contact_touching_pair_evaluations` over the steps). CPU time comes from the lines
"NAME: user X s" that tools/bench/column_variants.sh prints (its output saved to LOG); without
them the CPU column is empty. Grains per CPU second and steps are what the cost table compares
across sizes.
"""
import argparse
import json
import os
import re
import sys


def cpu_times(logs):
    out = {}
    for path in logs:
        with open(path) as f:
            for line in f:
                m = re.match(r"^(\S+): user ([0-9.]+) s\b", line.strip())
                if m:
                    out[m.group(1)] = float(m.group(2))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--cpu", action="append", default=[], help="a column_variants.sh output (repeatable)")
    a = ap.parse_args()
    cpu = cpu_times(a.cpu)
    print("| run | grains | TET10 | steps | mean step | wall s | CPU s | candidate pairs a step "
          "| touching a step | element updates per CPU s |")
    print("|---|---:|---:|---:|---|---:|---:|---:|---:|---:|")
    for run in a.runs:
        name = os.path.basename(os.path.normpath(run))
        try:
            with open(os.path.join(run, "summary.json")) as f:
                s = json.load(f)
        except (OSError, ValueError) as e:
            sys.exit(f"column_costs: {run}: {e}")
        extra, steps = s["extra"], s["steps"]
        grains = len(s["bodies"])
        c = cpu.get(name)
        rate = f"{s['elements'] * steps / c:.3g}" if c else ""
        print(f"| {name} ({s['status']} at {s['end_time']:.3g} s) | {grains} | {s['elements']:,} "
              f"| {steps:,} | {s['end_time'] / steps:.2g} s | {s['wall_time_s']:.0f} | "
              f"{c if c else ''} | {extra.get('contact_pair_evaluations', 0) / steps:,.0f} | "
              f"{extra.get('contact_touching_pair_evaluations', 0) / steps:,.0f} | {rate} |")


if __name__ == "__main__":
    main()
