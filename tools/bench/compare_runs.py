#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Runs shortened shipped scenes with two femdem binaries and says whether their outputs are the
same bits: history.csv (byte for byte), results.h5 (h5diff, exact), summary.json (equal but for
its timings and the checkpoint's paths) and the resolved scene in run.log. For refactorings that
must not change a result.

    tools/bench/compare_runs.py OLD_FEMDEM NEW_FEMDEM [--out DIR]

Exit code 0 when every scene matches, 1 otherwise.
"""
import argparse
import filecmp
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# (scene, end_time, threads, extra options): short enough for minutes in all, and covering
# elastic, von Mises, Mohr-Coulomb, wall and body contact, friction, impact damping, compaction.
SCENES = [
    ("bar_vibration", "4.0", 1, []),
    ("sphere_drop", "30e-6", 1, []),
    ("hertz_two_spheres", "20e-6", 2, []),
    ("compaction_unit_cell", "0.2e-3", 2, ["--no-plot"]),
    ("oblique_impact", "20e-6", 1, []),
    ("mc_cylinder_compression", "2e-5", 1, []),
    ("ball_on_concrete", "2e-5", 1, []),
    ("armour_layer", "0.01", 2, []),
    ("taylor_bar", "2e-6", 1, []),
]
TIMINGS = {"wall_time_s", "setup_time_s", "loop_time_s", "element_updates_per_s",
           "compaction_time_s"}


def run(exe, scene, end, threads, extra, out):
    cmd = [exe, "run", os.path.join(ROOT, "scenes", scene + ".toml"), "--out", out, "--threads",
           str(threads), "--quiet", "--set", "simulation.end_time=" + end] + extra
    env = dict(os.environ, OMP_WAIT_POLICY="passive")
    subprocess.run(cmd, check=True, env=env, cwd=ROOT)


def summary(path):
    with open(os.path.join(path, "summary.json")) as f:
        s = json.load(f)
    for k in TIMINGS:
        s.pop(k, None)
        s.get("extra", {}).pop(k, None)
    # the checkpoint's file and resume command name the run's own folder
    for k in ("file", "resume"):
        s.get("checkpoint", {}).pop(k, None)
    return s


def resolved(path):
    with open(os.path.join(path, "run.log")) as f:
        text = f.read()
    a, b = text.find("# resolved scene"), text.find("# end of resolved scene")
    return text[a:b]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "compare_runs"))
    a = ap.parse_args()
    ok = True
    for scene, end, threads, extra in SCENES:
        dirs = []
        for tag, exe in (("old", a.old), ("new", a.new)):
            d = os.path.join(a.out, tag, scene)
            run(os.path.abspath(exe), scene, end, threads, extra, d)
            dirs.append(d)
        o, n = dirs
        # the mesh and the frames (the root attributes name each binary's version)
        h5 = [subprocess.run(["h5diff", os.path.join(o, "results.h5"),
                              os.path.join(n, "results.h5"), group, group],
                             stdout=subprocess.DEVNULL) for group in ("/mesh", "/frames")]
        checks = {
            "history": filecmp.cmp(os.path.join(o, "history.csv"), os.path.join(n, "history.csv"),
                                   shallow=False),
            "results": all(r.returncode == 0 for r in h5),
            "summary": summary(o) == summary(n),
            "resolved scene": resolved(o) == resolved(n),
        }
        ok &= all(checks.values())
        print(f"{scene:26s} " + "  ".join(f"{k}: {'same' if v else 'DIFFERENT'}"
                                           for k, v in checks.items()), flush=True)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
