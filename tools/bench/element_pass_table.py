#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Markdown tables of a bench_element_pass run (its --benchmark_out JSON) for
docs/PERFORMANCE.md: ns per element update (thread CPU time) and element updates per second
(wall clock) for each model, size and thread count, SIMD beside the scalar kernel.

    build/tools/bench/bench_element_pass --benchmark_out=pass.json --benchmark_out_format=json
    tools/bench/element_pass_table.py pass.json
"""
import json
import sys

MODELS = ["elastic", "von Mises", "von Mises + F-bar (volume average)", "Drucker-Prager",
          "Mohr-Coulomb", "piece-wise Drucker-Prager", "von Mises + nodal F-bar",
          "von Mises + sub-tet F-bar"]
KERNELS = ["simd", "scalar", "simd, table gradients"]


def main():
    runs = json.load(open(sys.argv[1]))["benchmarks"]
    rows = {}
    for r in runs:
        name = r["name"].split("/")
        kind = name[0]
        args = dict(p.split(":") for p in name[1:] if ":" in p)
        key = (kind, int(args["model"]), int(args["elements"]), int(args["threads"]))
        rows.setdefault(key, {})[int(args["kernel"])] = (r["ns_per_element"],
                                                          r["element_updates_per_s"], r["label"])
    for kind in ("Pass", "Step"):
        print(f"\n{kind}:\n")
        print("| model | elements | threads | SIMD ns | scalar ns | speed-up | SIMD table ns | "
              "SIMD updates/s (wall) | 2 threads / 1 (wall) |")
        print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
        for key in sorted(k for k in rows if k[0] == kind):
            _, model, n, threads = key
            k = rows[key]
            simd = k.get(0)
            scalar = k.get(1)
            table = k.get(2)
            one = rows.get((kind, model, n, 1), {}).get(0)
            scaling = f"{simd[1] / one[1]:.2f}" if threads == 2 and simd and one else ""
            print(f"| {MODELS[model]} | {n:,} | {threads} | "
                  f"{simd[0]:.0f} | {scalar[0]:.0f} | {scalar[0] / simd[0]:.2f} | "
                  f"{table[0]:.0f} | " if table else
                  f"| {MODELS[model]} | {n:,} | {threads} | "
                  f"{simd[0]:.0f} | {scalar[0]:.0f} | {scalar[0] / simd[0]:.2f} | | ", end="")
            print(f"{simd[1] / 1e6:.2f} M | {scaling} |")


if __name__ == "__main__":
    main()
