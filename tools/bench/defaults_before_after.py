#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Every shipped scene before and after issue 17's defaults: steps, CPU time and results.

usage: tools/bench/defaults_before_after.py [--scenes a,b,...] [--threads 1]
       [--femdem build/femdem] [--out out/defaults_before_after] [--before-commit cf28dec^]

"Before" is the scene file as it was before issue 17 (git show BEFORE_COMMIT:scenes/NAME.toml:
its hand-set penalties and mass scaling) run with the settings that were then the defaults:
the element bound at safety 0.5 (`simulation.stable_step = "element"`; a scene that set its own
safety keeps it) and the penalty factor 100 on every contact and wall that did not set one.
"After" is the scene as shipped now with today's defaults (the assembled estimate at 0.8, the
automatic contact stiffness where a scene sets none). Both run with the same binary, one after
the other, so the difference is the settings alone, not the code between the commits.

Per scene and side: steps, user CPU seconds (GNU time), the largest |energy balance error| in
history.csv, the deepest contact overlap per element size (bodies and walls), and the scene's
results as summary.json has them (restitution of bodies that rebound, the largest plastic
strain, the final axial length of the Taylor bar's rod, the compaction columns' largest
relative density). Prints a Markdown table for docs/PERFORMANCE.md; each scene's figures are
kept in OUT/NAME.json as soon as it is measured (a rerun with the same --out measures only the
scenes not measured yet, then prints the whole table).

The three multi-body scenes (armour_layer, compaction_64_spheres, powder_compaction) take from
half an hour to hours each way; they are left out of the default list and measured by their long
tests (docs/PERFORMANCE.md gives those figures); `--scenes` can name them.
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
FAST = ("armour_unit_drop ball_on_concrete bar_vibration closed_die_cube compaction_unit_cell "
        "hertz_sphere_plate hertz_sphere_wall hertz_two_spheres mc_cylinder_compression "
        "oblique_impact sphere_drop sphere_impact sphere_impact_pair taylor_bar").split()


def old_scene(name, commit, folder):
    """The scene file at `commit`, written where its relative mesh and packing paths resolve."""
    text = subprocess.run(["git", "-C", ROOT, "show", f"{commit}:scenes/{name}.toml"],
                          check=True, capture_output=True, text=True).stdout
    for sub in ("meshes", "packings"):
        link = os.path.join(folder, sub)
        if not os.path.exists(link):
            os.symlink(os.path.join(ROOT, "scenes", sub), link)
    path = os.path.join(folder, f"{name}.toml")
    open(path, "w").write(text)
    return path, text


def old_default_sets(text):
    """--set options that give a scene file of before issue 17 the defaults it then ran with."""
    sets = ["simulation.stable_step=element"]
    text = re.sub(r"#[^\n]*", "", text)  # (no key's value here holds a '#')
    # the walls and the contact table without a penalty of their own had 100
    for m in re.finditer(r"\[\[walls\]\]\n(.*?)(?=\n\[|\Z)", text, re.S):
        block = m.group(1)
        name = re.search(r'name\s*=\s*"([^"]+)"', block).group(1)
        if "penalty_factor" not in block:
            sets.append(f"walls.{name}.penalty_factor=100")
    contact = re.search(r"\n\[contact\]\n(.*?)(?=\n\[|\Z)", text, re.S)
    if not (contact and "penalty_factor" in contact.group(1)):
        sets.append("contact.penalty_factor=100")
    die = re.search(r"die\s*=\s*\{([^}]*)\}", text)
    if die and "penalty_factor" not in die.group(1):
        sets.append("compaction.die.penalty_factor=100")
    return sets


def run(femdem, scene, out, threads, sets):
    cmd = [femdem, "run", scene, "--out", out, "--force", "--threads", str(threads), "--quiet",
           "--no-plot"]
    for s in sets:
        cmd += ["--set", s]
    r = subprocess.run(["/usr/bin/time", "-f", "@user %U"] + cmd, stdout=subprocess.DEVNULL,
                       stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        sys.exit(f"defaults_before_after: {' '.join(cmd)} failed ({r.returncode}):\n"
                 f"{r.stderr[-2000:]}")
    cpu = float(re.search(r"@user ([\d.]+)", r.stderr).group(1))
    return cpu, measures(out)


def measures(out):
    s = json.load(open(os.path.join(out, "summary.json")))
    ex = s.get("extra", {})
    worst, dmax = 0.0, None
    with open(os.path.join(out, "history.csv")) as f:
        rows = csv.DictReader(f)
        for row in rows:
            # the first rows' energies are round-off (the balance rule's floor ignores them too)
            if float(row["time"]) > 0.01 * s["end_time"]:
                worst = max(worst, abs(float(row["energy_balance_error"])))
            if "compaction.relative_density" in row:
                d = float(row["compaction.relative_density"])
                dmax = d if dmax is None else max(dmax, d)
    results = []
    for name, b in s["bodies"].items():
        e = b.get("coefficient_of_restitution")
        if e is not None:  # that of the centre of mass (and of the kinetic energy)
            results.append(f"e({name}) {e['com']:.4f}")
    eps = max((b.get("max_equivalent_plastic_strain", 0.0) for b in s["bodies"].values()),
              default=0.0)
    if eps > 0.0:
        results.append(f"max eps_p {eps:.3f}")
    if dmax is not None:
        results.append(f"D max {dmax:.4f}")
    overlap = max(ex.get("contact_max_penetration_per_size", 0.0),
                  ex.get("walls_max_penetration_per_size", 0.0))
    return {"steps": s["steps"], "balance": worst, "overlap": overlap,
            "results": ", ".join(results)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scenes", default=",".join(FAST))
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--femdem", default=os.path.join(ROOT, "build", "femdem"))
    ap.add_argument("--out", default="out/defaults_before_after")
    ap.add_argument("--before-commit", default="cf28dec^")
    a = ap.parse_args()
    out = os.path.abspath(a.out)
    os.makedirs(out, exist_ok=True)
    # each scene's figures are kept in OUT/NAME.json as soon as it is done, so a long sweep
    # that is cut short keeps what it measured and a rerun measures only what is missing
    with tempfile.TemporaryDirectory() as old_dir:
        for name in a.scenes.split(","):
            kept = os.path.join(out, f"{name}.json")
            if os.path.exists(kept):
                continue
            path, text = old_scene(name, a.before_commit, old_dir)
            cb, b = run(a.femdem, path, f"{out}/{name}_before", a.threads, old_default_sets(text))
            ca, af = run(a.femdem, os.path.join(ROOT, "scenes", f"{name}.toml"),
                         f"{out}/{name}_after", a.threads, [])
            print(f"{name}: {b['steps']} -> {af['steps']} steps, {cb:.1f} -> {ca:.1f} s CPU",
                  file=sys.stderr, flush=True)
            with open(kept, "w") as f:
                json.dump({"before": dict(b, cpu=cb), "after": dict(af, cpu=ca)}, f)
    print("| scene | steps before | after | CPU s before | after | max energy balance error "
          "before / after | deepest overlap per element size before / after | results before |"
          " after |")
    print("| " + " | ".join(["---"] * 9) + " |")
    for name in a.scenes.split(","):
        kept = os.path.join(out, f"{name}.json")
        if not os.path.exists(kept):
            continue
        r = json.load(open(kept))
        b, af = r["before"], r["after"]
        print(f"| {name} | {b['steps']:,} | {af['steps']:,} | {b['cpu']:.1f} | {af['cpu']:.1f} | "
              f"{b['balance']:.1e} / {af['balance']:.1e} | {b['overlap']:.1e} / "
              f"{af['overlap']:.1e} | {b['results']} | {af['results']} |")

if __name__ == "__main__":
    main()
