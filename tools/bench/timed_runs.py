#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Timed whole runs of femdem at growing sizes: time per element per step and peak memory.

usage: tools/bench/timed_runs.py [--sizes 1e4,1e5,1e6] [--steps 40] [--threads 1,2]
       [--layouts 1x2,2x1] [--frames 1] [--femdem build/femdem] [--out out/bench]

Each run is an elastic steel box (6 TET10 per grid cell) compressed by a moving rigid wall,
fixed at its base, for a fixed number of steps, with one frame at the start and one at the end.
Reported: loop time per element per step (the engine's cost), element updates per second, set-up
time (mesh generation, model build, stable-step factors) and peak resident memory per element
(GNU time). Prints a Markdown table for docs/PERFORMANCE.md.

--frames N writes N frames after the first (evenly spread) instead of one at the end: the loop
time of N frames against one gives a frame's cost (the gather of a distributed run included).

--layouts RxT,... runs each size as R MPI ranks of T threads (mpirun; R = 1 runs without it)
instead of --threads: e.g. 1x2,2x1 compares threads and ranks on a 2-core machine. The peak
memory is then the largest rank's.
"""
import argparse
import os
import platform
import re
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import femdem  # noqa: E402  (tools/python/femdem)

SCENE = """title = "timed run"
[simulation]
end_time = {end_time}
time_step = {dt}
output_interval = {output_interval}
history_interval = {hist}

[[materials]]
name = "steel"
model = "elastic"
density = 7850.0
youngs_modulus = 210e9
poisson_ratio = 0.3

[[bodies]]
name = "box"
material = "steel"
mesh = {{ generator = "box", size = [1.0, 1.0, 1.0], element_size = {h} }}
velocity = [0.0, 0.0, -5.0]

[[walls]]
name = "floor"
point = [0.0, 0.0, -1e-9]
normal = [0.0, 0.0, 1.0]
"""


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sizes", default="1e4,1e5,1e6")
    ap.add_argument("--steps", type=int, default=40)
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--layouts", default="", help="RxT,...: R ranks of T threads (mpirun)")
    ap.add_argument("--frames", type=int, default=1, help="frames after the first")
    ap.add_argument("--femdem", default=os.path.join(os.path.dirname(__file__), "../../build/femdem"))
    ap.add_argument("--out", default="out/bench")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    print(f"machine: {cpu_model()}, {os.cpu_count()} cores")
    layouts = ([tuple(int(x) for x in l.split("x")) for l in a.layouts.split(",")] if a.layouts
               else [(1, int(t)) for t in a.threads.split(",")])
    print("| elements | nodes | ranks x threads | steps | loop s | ns / element / step | element updates/s | set-up s | peak MB | KB / element |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for size in [float(s) for s in a.sizes.split(",")]:
        h = (6.0 / size) ** (1.0 / 3.0)
        # a step below the stable one for this h (c_d = 6000 m/s)
        dt = 0.1 * h / 6000.0
        end_time = dt * a.steps
        for ranks, threads in layouts:
            d = os.path.join(a.out, f"n{int(size)}_r{ranks}_t{threads}")
            os.makedirs(d, exist_ok=True)
            scene = os.path.join(d, "scene.toml")
            with open(scene, "w") as f:
                f.write(SCENE.format(end_time=end_time, dt=dt, hist=end_time / 4, h=h,
                                    output_interval=end_time / a.frames))
            mpi = (["mpirun", "-np", str(ranks), "--oversubscribe", "--allow-run-as-root",
                    "--bind-to", "none"] if ranks > 1 else [])
            cmd = ["/usr/bin/time", "-v"] + mpi + [a.femdem, "run", scene, "--quiet", "--threads",
                                                    str(threads), "--out", d, "--force"]
            p = subprocess.run(cmd, capture_output=True, text=True)
            if p.returncode != 0:
                print(p.stdout, p.stderr)
                raise SystemExit(p.returncode)
            rss_kb = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", p.stderr).group(1))
            s = femdem.read_summary(d)
            ne, nn, steps = s["elements"], s["nodes"], s["steps"]
            loop = s["extra"]["loop_time_s"]
            print(f"| {ne} | {nn} | {ranks} x {threads} | {steps} | {loop:.2f} | {1e9 * loop / (ne * steps):.0f} "
                  f"| {ne * steps / loop:.3g} | {s['extra']['setup_time_s']:.2f} | {rss_kb / 1024:.0f} "
                  f"| {rss_kb / ne:.2f} |", flush=True)


if __name__ == "__main__":
    main()
