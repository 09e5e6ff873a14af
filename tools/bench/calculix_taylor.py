#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The Taylor bar in femdem and in CalculiX (ccx) on the same TET10 mesh: cost per element per
step, number of steps, final length, mean base radius and maximum equivalent plastic strain.

usage: tools/bench/calculix_taylor.py [--h 1.6e-3] [--out out/calculix_taylor]
       [--femdem build/femdem] [--ccx ccx] [--end-time 80e-6] [--reuse]

One run of the script
  1. meshes the rod with femdem's own cylinder generator (scenes/taylor_bar.toml with
     bodies.rod.mesh.element_size = H, a one-step femdem run, /mesh of its results.h5) and
     writes a CalculiX deck with C3D10 elements, the same material (E 117 GPa, nu 0.35,
     rho 8930, von Mises 400 MPa, linear hardening 100 MPa), v0 = -227 m/s along z,
     NLGEOM, *DYNAMIC, EXPLICIT for 80 us;
  2. runs both codes single-threaded (femdem --threads 1, ccx with OMP_NUM_THREADS=1) and
     measures wall and CPU time; a short run of each (femdem: one step, ccx: one increment of
     1e-12 s) gives the fixed cost (reading, meshing, mass matrix, output), which is subtracted
     before dividing by steps x elements;
  3. reads both final shapes (length = max z - min z, mean base radius = mean radius of the
     impact-face nodes on the outer rim, as tools/taylor_profile.py) and the maximum equivalent
     plastic strain (femdem: element averages over the 4 Gauss points; ccx: PEEQ at the
     integration points, also averaged per element for the same measure) and draws the final
     r-z profiles of both over the initial one;
  4. prints a table and writes OUT/h<H>mm/calculix_taylor.{csv,json,png}.

femdem keeps scenes/taylor_bar.toml as it is (a penalty wall at z = 0); CalculiX gets u_z = 0
on the impact-face nodes instead (see write_deck for why that is the same problem).
"""
import argparse
import csv
import json
import os
import re
import resource
import subprocess
import sys
import time

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools", "python"))
# (by name: run_femdem's argument `femdem` is the program's path)
from femdem import open_results, read_summary  # noqa: E402  (tools/python/femdem)

SCENE = os.path.join(ROOT, "scenes", "taylor_bar.toml")

# Material and load of scenes/taylor_bar.toml (SI units).
E, NU, RHO = 117e9, 0.35, 8930.0
SIGMA_Y, H_LIN = 400e6, 100e6
V0 = -227.0
# Reference (thesis ch. 4, h 0.8 mm): final length 21.48 mm, mean base radius 7.12 mm.
REF_LENGTH_MM, REF_RADIUS_MM = 21.48, 7.12


def child_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def timed(cmd, cwd=None, env=None, log=None):
    """Runs cmd, returns (wall s, CPU s of the child, return code)."""
    c0, t0 = child_cpu(), time.perf_counter()
    with open(log, "w") if log else open(os.devnull, "w") as out:
        rc = subprocess.run(cmd, cwd=cwd, env=env, stdout=out, stderr=subprocess.STDOUT).returncode
    return time.perf_counter() - t0, child_cpu() - c0, rc


# ---------------------------------------------------------------------------------------------
# femdem

def run_femdem(femdem, h, out_dir, end_time=None, reuse=False):
    summary_path = os.path.join(out_dir, "summary.json")
    timing_path = os.path.join(out_dir, "timing.json")
    if reuse and os.path.exists(summary_path) and os.path.exists(timing_path):
        s = read_summary(summary_path)
        if s.get("status") == "completed":
            with open(timing_path) as f:
                return s, json.load(f)
    cmd = [femdem, "run", SCENE, "--out", out_dir, "--threads", "1",
           "--set", f"bodies.rod.mesh.element_size={h!r}"]
    if end_time is not None:
        cmd += ["--set", f"simulation.end_time={end_time!r}"]
    os.makedirs(out_dir, exist_ok=True)
    wall, cpu, rc = timed(cmd, log=os.path.join(out_dir, "stdout.txt"))
    s = read_summary(summary_path)
    t = {"wall_s": wall, "cpu_s": cpu, "returncode": rc}
    with open(timing_path, "w") as f:
        json.dump(t, f)
    return s, t


def femdem_final_state(out_dir):
    with open_results(out_dir) as f:
        X = f.coordinates
        x = f.positions(-1)
        eqps = f.field("equivalent_plastic_strain", -1)
        t = f.times
        lengths = [float(np.ptp(X[:, 2] + f.field("displacement", k)[:, 2])) for k in range(len(t))]
    return x, float(eqps.max()), t, np.array(lengths)


# ---------------------------------------------------------------------------------------------
# CalculiX deck

def rim_nodes(X):
    """Impact-face nodes, and those of them on the outer rim (as tools/taylor_profile.py)."""
    R0 = np.max(np.linalg.norm(X[:, :2], axis=1))
    base = np.where(np.abs(X[:, 2] - X[:, 2].min()) < 1e-9)[0]
    rim = base[np.abs(np.linalg.norm(X[base, :2], axis=1) - R0) < 1e-6 * R0]
    return base, rim


def write_ids(o, ids, per_line=16):
    for k in range(0, len(ids), per_line):
        o.write(",".join(str(int(i)) for i in ids[k:k + per_line]) + "\n")


def write_deck(path, X, conn, end_time, volume_check=False):
    """CalculiX input deck for the Taylor bar on femdem's mesh.

    Node order: femdem writes TET10 in VTK quadratic-tetra order (corners 0-3, then mid-edges
    4:(0,1) 5:(1,2) 6:(2,0) 7:(0,3) 8:(1,3) 9:(2,3)). CalculiX's C3D10 (shape10tet.f: nodes
    5..10 carry 4*xi*a, 4*xi*et, 4*et*a, 4*ze*a, 4*xi*ze, 4*et*ze, i.e. edges 1-2, 2-3, 3-1,
    1-4, 2-4, 3-4) is the same order, and both count a tetrahedron positive when
    (x2-x1) x (x3-x1) . (x4-x1) > 0. So the connectivity is copied as is (1-based); the script
    checks it against the element volumes CalculiX prints (EVOL).

    The wall: femdem has a frictionless penalty wall at z = 0. Here the impact-face nodes get
    u_z = 0 and nothing else. For a Taylor bar that is the same problem: the rod is pushed onto
    the wall from the first instant to the end (it arrives at 227 m/s and never has the speed
    to rebound within 80 us), so the face stays in contact and the contact condition reduces
    to u_z = 0 there; frictionless means no tangential force, so x and y stay free and the foot
    spreads radially. What this cannot do is let a face node lift off (a bilateral constraint
    holds it) or catch a node of the side surface that rolls over onto the wall; the script
    reports min z of the final shape to show whether any node went below the wall.
    The face nodes start with v_z = 0 (they are on the wall); femdem stops them in its first
    step through the penalty.
    """
    base, _ = rim_nodes(X)
    top_z = X[:, 2].max()
    top = int(np.argmin(np.where(np.abs(X[:, 2] - top_z) < 1e-9, np.linalg.norm(X[:, :2], axis=1), np.inf)))
    with open(path, "w") as o:
        o.write("*HEADING\nTaylor bar, femdem mesh (tools/bench/calculix_taylor.py)\n")
        o.write("*NODE, NSET=NALL\n")
        for i, p in enumerate(X):
            # (CalculiX reads at most 20 characters per number: 13 significant digits fit)
            o.write(f"{i + 1},{p[0]:.12e},{p[1]:.12e},{p[2]:.12e}\n")
        o.write("*ELEMENT, TYPE=C3D10, ELSET=EALL\n")
        for e, c in enumerate(conn + 1):
            o.write(f"{e + 1}," + ",".join(str(int(v)) for v in c[:8]) + ",\n"
                    + ",".join(str(int(v)) for v in c[8:]) + "\n")
        o.write("*NSET, NSET=NBASE\n")
        write_ids(o, base + 1)
        o.write(f"*NSET, NSET=NTOP\n{top + 1}\n")
        o.write("*MATERIAL, NAME=COPPER\n")
        o.write(f"*ELASTIC\n{E:.6e},{NU}\n*DENSITY\n{RHO}\n")
        # von Mises, isotropic linear hardening: true stress against equivalent plastic strain;
        # the table runs to 10 (the foot reaches about 3); CalculiX interpolates linearly.
        o.write("*PLASTIC\n")
        for ep in (0.0, 1.0, 3.0, 10.0):
            o.write(f"{SIGMA_Y + H_LIN * ep:.6e},{ep}\n")
        o.write("*SOLID SECTION, ELSET=EALL, MATERIAL=COPPER\n")
        o.write(f"*INITIAL CONDITIONS, TYPE=VELOCITY\nNALL,3,{V0}\nNBASE,3,0.\n")
        o.write("*BOUNDARY\nNBASE,3,3\n")
        # Step 1: the impact. Print requests share one FREQUENCY in CalculiX (the last card's
        # wins), so step 1 prints only the top node every increment (the increment count and the
        # length history), and step 2, a single increment of 1e-12 s, prints the final fields.
        # The *DYNAMIC data line: initial increment, period; with EXPLICIT ccx replaces the
        # increment by its Courant estimate.
        o.write("*STEP, NLGEOM, INC=100000000\n*DYNAMIC, EXPLICIT\n")
        o.write(f"{min(1e-9, end_time)!r},{end_time!r}\n")
        o.write("*NODE PRINT, NSET=NTOP, FREQUENCY=1\nU\n")
        o.write("*END STEP\n")
        o.write("*STEP, NLGEOM, INC=100000000\n*DYNAMIC, EXPLICIT\n1e-12,1e-12\n")
        o.write("*NODE PRINT, NSET=NALL\nU\n*EL PRINT, ELSET=EALL\nPEEQ\n")
        if volume_check:
            o.write("*EL PRINT, ELSET=EALL\nEVOL\n")
        o.write("*NODE FILE\nU\n*EL FILE\nPEEQ\n")
        o.write("*END STEP\n")
    return top


def dat_blocks(path):
    """The blocks of a CalculiX .dat file: list of (title, set, time, rows as lists of str)."""
    blocks = []
    head = re.compile(r"^\s*(.+?)\s*for set\s+(\S+)\s+and time\s+(\S+)")
    with open(path) as f:
        lines = f.read().split("\n")
    i = 0
    while i < len(lines):
        m = head.match(lines[i])
        if not m:
            i += 1
            continue
        i += 1
        while i < len(lines) and not lines[i].strip():
            i += 1
        rows = []
        while i < len(lines) and lines[i].strip() and not head.match(lines[i]):
            rows.append(lines[i].split())
            i += 1
        blocks.append((m.group(1), m.group(2), float(m.group(3)), rows))
    return blocks


def run_ccx(ccx, X, conn, run_dir, end_time, volume_check=False, reuse=False):
    os.makedirs(run_dir, exist_ok=True)
    timing_path = os.path.join(run_dir, "timing.json")
    dat = os.path.join(run_dir, "taylor.dat")
    if reuse and os.path.exists(timing_path) and os.path.exists(dat):
        with open(timing_path) as f:
            t = json.load(f)
        if t["returncode"] == 0:
            return t
    write_deck(os.path.join(run_dir, "taylor.inp"), X, conn, end_time, volume_check)
    for ext in (".dat", ".frd", ".sta", ".cvg"):
        if os.path.exists(os.path.join(run_dir, "taylor" + ext)):
            os.remove(os.path.join(run_dir, "taylor" + ext))
    env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_STIFFNESS="1", CCX_NPROC_RESULTS="1",
               CCX_NPROC_EQUATION_SOLVER="1", NUMBER_OF_CPUS="1")
    wall, cpu, rc = timed([ccx, "-i", "taylor"], cwd=run_dir, env=env,
                          log=os.path.join(run_dir, "stdout.txt"))
    t = {"wall_s": wall, "cpu_s": cpu, "returncode": rc}
    with open(os.path.join(run_dir, "stdout.txt")) as f:
        log = f.read()
    m = re.search(r"initial stable time increment:\s*(\S+)", log)
    t["courant_dt"] = float(m.group(1)) if m else None
    m = re.search(r"Total CalculiX Time:\s*(\S+)", log)
    t["ccx_reported_s"] = float(m.group(1)) if m else None
    t["errors"] = [line.strip() for line in log.split("\n") if "ERROR" in line or "WARNING" in line][:10]
    with open(timing_path, "w") as f:
        json.dump(t, f)
    return t


def ccx_results(run_dir, n_nodes, n_elems):
    blocks = dat_blocks(os.path.join(run_dir, "taylor.dat"))
    top = [(t, float(r[0][3])) for title, s, t, r in blocks if s == "NTOP" and r]
    u = [b for b in blocks if b[1] == "NALL" and b[0].startswith("displacements")]
    pe = [b for b in blocks if b[1] == "EALL" and b[0].startswith("equivalent plastic")]
    vol = [b for b in blocks if b[1] == "EALL" and b[0].startswith("volume")]
    res = {"increments": len(top), "top_history": top}
    if top:
        times = np.array([0.0] + [t for t, _ in top])
        dts = np.diff(times)
        res["dt_first"], res["dt_min"], res["dt_max"] = float(dts[0]), float(dts.min()), float(dts.max())
        res["end_time"] = float(times[-1])
    if u:
        U = np.zeros((n_nodes, 3))
        for r in u[-1][3]:
            U[int(r[0]) - 1] = [float(v) for v in r[1:4]]
        res["U"] = U
    if pe:
        P = np.zeros((n_elems, 4))
        cnt = np.zeros(n_elems, dtype=int)
        for r in pe[-1][3]:
            e = int(r[0]) - 1
            P[e, cnt[e] % 4] = float(r[2])
            cnt[e] += 1
        res["peeq_ip_max"] = float(P.max())
        res["peeq_elem_max"] = float((P.sum(axis=1) / np.maximum(cnt, 1)).max())
        res["ip_per_element"] = int(cnt.max())
    if vol:
        res["evol"] = np.array([float(r[1]) for r in vol[-1][3]])
    return res


def tet10_volumes(X, conn):
    """Element volumes of the TET10 mesh in VTK node order, computed here independently of
    CalculiX: det J of the quadratic map (a cubic) integrated with the 5-point degree-3 rule."""
    pts = [((0.25, 0.25, 0.25), -0.8)] + [(p, 0.45) for p in
                                          ((1 / 6, 1 / 6, 1 / 6), (0.5, 1 / 6, 1 / 6), (1 / 6, 0.5, 1 / 6), (1 / 6, 1 / 6, 0.5))]
    xe = X[conn]  # [E,10,3]
    vol = np.zeros(len(conn))
    for (r, s, t), w in pts:
        L = np.array([1 - r - s - t, r, s, t])
        dL = np.array([[-1, -1, -1], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
        edges = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]
        dN = np.zeros((10, 3))
        for i in range(4):
            dN[i] = (4 * L[i] - 1) * dL[i]
        for k, (i, j) in enumerate(edges):
            dN[4 + k] = 4 * (L[i] * dL[j] + L[j] * dL[i])
        J = np.einsum("eai,aj->eij", xe, dN)
        vol += w * np.linalg.det(J) / 6.0
    return vol


# ---------------------------------------------------------------------------------------------
# shapes and figure

def shape_numbers(X, x):
    _, rim = rim_nodes(X)
    return {"length_mm": 1e3 * float(np.ptp(x[:, 2])),
            "mean_base_radius_mm": 1e3 * float(np.mean(np.linalg.norm(x[rim, :2], axis=1))),
            "min_z_mm": 1e3 * float(x[:, 2].min())}


def outer_profile(X, pts):
    """(z, r) of the outer surface: the nodes that start on the lateral surface (r = R0), in
    rings of equal initial height, each ring's mean deformed height and radius."""
    r0 = np.linalg.norm(X[:, :2], axis=1)
    side = np.where(np.abs(r0 - r0.max()) < 1e-6 * r0.max())[0]
    levels = np.round(X[side, 2] / (1e-6 * r0.max())).astype(np.int64)
    r = np.linalg.norm(pts[side, :2], axis=1) * 1e3
    z = pts[side, 2] * 1e3
    zr = [(z[levels == v].mean(), r[levels == v].mean()) for v in np.unique(levels)]
    return np.array(zr).T


def figure(path, X, shapes, histories, title):
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(10, 6.5), gridspec_kw={"width_ratios": [1.1, 1]})
    for pts, label, style in [(X, "initial", "k--")] + shapes:
        zz, rr = outer_profile(X, pts)
        ax.plot(rr, zz, style, label=label)
        ax.plot(-rr, zz, style)
    ax.axhline(0, color="gray", lw=3)
    ax.set_aspect("equal")
    ax.set_xlabel("radius [mm]")
    ax.set_ylabel("height [mm]")
    ax.legend(fontsize=8, loc="upper right")
    inset = ax.inset_axes([0.05, 0.42, 0.36, 0.3])
    for pts, style in [(X, "k--")] + [(p, st) for p, _, st in shapes]:
        zz, rr = outer_profile(X, pts)
        inset.plot(rr, zz, style)
    inset.set_xlim(3.0, 7.6)
    inset.set_ylim(-0.2, 3.0)
    inset.set_title("foot", fontsize=7)
    inset.tick_params(labelsize=6)
    ax.set_title("outer surface (rings of side-surface nodes: mean r, z)", fontsize=9)
    for t, L, label, style in histories:
        ax2.plot(1e6 * np.asarray(t), 1e3 * np.asarray(L), style, label=label)
    ax2.axhline(REF_LENGTH_MM, color="k", ls=":", lw=0.8, label=f"thesis {REF_LENGTH_MM} mm")
    ax2.set_xlabel("time [us]")
    ax2.set_ylabel("length [mm]")
    ax2.legend(fontsize=8)
    ax2.set_title("length history", fontsize=9)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ---------------------------------------------------------------------------------------------

def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--h", type=float, default=1.6e-3, help="element size [m] (default 1.6e-3)")
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "calculix_taylor"))
    ap.add_argument("--femdem", default=os.path.join(ROOT, "build", "femdem"))
    ap.add_argument("--ccx", default="ccx")
    ap.add_argument("--end-time", type=float, default=80e-6)
    ap.add_argument("--increment-only", action="store_true",
                    help="run ccx for one increment only and print its Courant increment and the "
                         "increments the whole end time takes (a fixed increment)")
    ap.add_argument("--reuse", action="store_true",
                    help="reuse finished runs found in the output folder instead of running again")
    args = ap.parse_args()

    tag = f"h{1e3 * args.h:g}mm"
    out = os.path.join(args.out, tag)
    os.makedirs(out, exist_ok=True)
    print(f"[calculix_taylor] h = {args.h:g} m, output in {out}", flush=True)

    # 1. Mesh: one femdem step; it also gives femdem's fixed cost (set-up + first/last frame).
    short_dir = os.path.join(out, "femdem_short")
    s_short, t_short = run_femdem(args.femdem, args.h, short_dir, end_time=1e-9, reuse=args.reuse)
    with open_results(short_dir) as f:
        X = f.coordinates
        conn = f.connectivity.astype(np.int64)
    n_nodes, n_elems = len(X), len(conn)
    print(f"[calculix_taylor] mesh: {n_nodes} nodes, {n_elems} TET10", flush=True)

    # 2a. CalculiX: a one-increment run (fixed cost, element-volume check), then the full run.
    ccx_short = os.path.join(out, "ccx_short")
    tc_short = run_ccx(args.ccx, X, conn, ccx_short, 1e-12, volume_check=True, reuse=args.reuse)
    rc_short = ccx_results(ccx_short, n_nodes, n_elems)
    check = {}
    if "evol" in rc_short:
        v_ref = tet10_volumes(X, conn)
        check = {"min_volume_ccx": float(rc_short["evol"].min()),
                 "max_rel_volume_difference": float(np.max(np.abs(rc_short["evol"] - v_ref) / v_ref)),
                 "total_volume_ccx": float(rc_short["evol"].sum()), "total_volume_mesh": float(v_ref.sum())}
        print(f"[calculix_taylor] node order check: ccx EVOL min {check['min_volume_ccx']:.3e} m^3, "
              f"largest relative difference to this script's TET10 volumes {check['max_rel_volume_difference']:.1e}",
              flush=True)
    if args.increment_only:
        dt = tc_short["courant_dt"]
        print(f"[calculix_taylor] ccx Courant increment {dt:.4e} s: {args.end_time / dt:.0f} "
              f"increments for {1e6 * args.end_time:g} us", flush=True)
        return
    print(f"[calculix_taylor] running ccx for {1e6 * args.end_time:g} us ...", flush=True)
    tc = run_ccx(args.ccx, X, conn, os.path.join(out, "ccx"), args.end_time, reuse=args.reuse)
    rc = ccx_results(os.path.join(out, "ccx"), n_nodes, n_elems)
    print(f"[calculix_taylor] ccx: {rc['increments']} increments, {tc['wall_s']:.1f} s wall, "
          f"{tc['cpu_s']:.1f} s CPU, return code {tc['returncode']}", flush=True)

    # 2b. femdem, the scene as it is (penalty wall), one thread.
    print(f"[calculix_taylor] running femdem for {1e6 * args.end_time:g} us ...", flush=True)
    s_full, t_full = run_femdem(args.femdem, args.h, os.path.join(out, "femdem"),
                                end_time=args.end_time, reuse=args.reuse)
    print(f"[calculix_taylor] femdem: {s_full['steps']} steps, {t_full['wall_s']:.1f} s wall, "
          f"{t_full['cpu_s']:.1f} s CPU, status {s_full['status']}", flush=True)

    # 3. Shapes.
    x_f, eqps_f, t_f, L_f = femdem_final_state(os.path.join(out, "femdem"))
    rows = []

    def per_step(full, short, steps, steps_short):
        n = max(steps - steps_short, 1)
        return 1e6 * (full - short) / (n * n_elems)

    fem = {"code": f"femdem ({s_full['status']}, penalty wall)", "element_size_mm": 1e3 * args.h,
           "elements": n_elems, "nodes": n_nodes, "steps": s_full["steps"],
           "end_time_us": 1e6 * s_full["end_time"],
           "first_dt_s": s_short["time_step"], "last_dt_s": s_full["time_step"],
           "wall_s": t_full["wall_s"], "cpu_s": t_full["cpu_s"],
           "fixed_wall_s": t_short["wall_s"], "fixed_cpu_s": t_short["cpu_s"],
           "us_per_element_step_wall": per_step(t_full["wall_s"], t_short["wall_s"], s_full["steps"], s_short["steps"]),
           "us_per_element_step_cpu": per_step(t_full["cpu_s"], t_short["cpu_s"], s_full["steps"], s_short["steps"]),
           "us_per_element_step_loop": 1e6 * s_full["extra"]["loop_time_s"] / (s_full["steps"] * n_elems),
           **shape_numbers(X, x_f), "max_eqps": eqps_f, "max_eqps_ip": None}
    rows.append(fem)
    if "U" in rc:
        x_c = X + rc["U"]
        ccx_row = {"code": "CalculiX ccx 2.20 explicit, C3D10, u_z=0 face", "element_size_mm": 1e3 * args.h,
                   "elements": n_elems, "nodes": n_nodes, "steps": rc["increments"],
                   "end_time_us": 1e6 * rc.get("end_time", float("nan")),
                   "first_dt_s": rc.get("dt_first"), "last_dt_s": rc.get("dt_min"),
                   "wall_s": tc["wall_s"], "cpu_s": tc["cpu_s"],
                   "fixed_wall_s": tc_short["wall_s"], "fixed_cpu_s": tc_short["cpu_s"],
                   "us_per_element_step_wall": per_step(tc["wall_s"], tc_short["wall_s"], rc["increments"], 1),
                   "us_per_element_step_cpu": per_step(tc["cpu_s"], tc_short["cpu_s"], rc["increments"], 1),
                   "us_per_element_step_loop": None,
                   **shape_numbers(X, x_c), "max_eqps": rc.get("peeq_elem_max"),
                   "max_eqps_ip": rc.get("peeq_ip_max")}
        rows.append(ccx_row)
    else:
        x_c = None
        print("[calculix_taylor] ccx gave no final displacements; see", os.path.join(out, "ccx", "stdout.txt"))

    # 4. Table, CSV, JSON, figure.
    cols = ["code", "element_size_mm", "elements", "nodes", "steps", "end_time_us", "first_dt_s", "last_dt_s",
            "wall_s", "cpu_s", "fixed_wall_s", "fixed_cpu_s", "us_per_element_step_wall",
            "us_per_element_step_cpu", "us_per_element_step_loop", "length_mm", "mean_base_radius_mm",
            "min_z_mm", "max_eqps", "max_eqps_ip"]
    with open(os.path.join(out, "calculix_taylor.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols)
        w.writeheader()
        for r in rows:
            w.writerow(r)
    meta = {"element_size_m": args.h, "end_time_s": args.end_time, "rows": rows, "node_order_check": check,
            "ccx_errors": tc.get("errors"), "ccx_courant_dt_s": tc.get("courant_dt"),
            "command": " ".join([os.path.relpath(sys.argv[0], ROOT)] + sys.argv[1:]),
            "reference": {"length_mm": REF_LENGTH_MM, "mean_base_radius_mm": REF_RADIUS_MM}}
    with open(os.path.join(out, "calculix_taylor.json"), "w") as f:
        json.dump(meta, f, indent=2)

    shapes = [(x_f, f"femdem: L {fem['length_mm']:.2f} mm, R {fem['mean_base_radius_mm']:.2f} mm", "b-")]
    histories = [(t_f, L_f, "femdem (max z - min z)", "b-")]
    if x_c is not None:
        shapes.append((x_c, f"CalculiX: L {rows[1]['length_mm']:.2f} mm, R {rows[1]['mean_base_radius_mm']:.2f} mm",
                       "r-"))
        th = np.array([(0.0, 0.0)] + rc["top_history"])
        top = np.argmax(np.where(np.abs(X[:, 2] - X[:, 2].max()) < 1e-9, -np.linalg.norm(X[:, :2], axis=1), -np.inf))
        histories.append((th[:, 0], X[top, 2] + th[:, 1], "CalculiX (top centre node z)", "r-"))
    figure(os.path.join(out, "calculix_taylor.png"), X, shapes, histories,
           f"Taylor bar, h = {1e3 * args.h:g} mm ({n_elems} TET10 / C3D10), t = {1e6 * args.end_time:g} us")

    fmt = "{:<48} {:>7} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>8}"
    print(fmt.format("code", "steps", "wall s", "CPU s", "us/el/st", "(CPU)", "L mm", "R mm", "eqps"))
    for r in rows:
        print(fmt.format(r["code"][:48], r["steps"], f"{r['wall_s']:.1f}", f"{r['cpu_s']:.1f}",
                         f"{r['us_per_element_step_wall']:.2f}", f"{r['us_per_element_step_cpu']:.2f}",
                         f"{r['length_mm']:.2f}", f"{r['mean_base_radius_mm']:.2f}",
                         "-" if r["max_eqps"] is None else f"{r['max_eqps']:.2f}"))
    print(f"reference (thesis, h 0.8 mm): L {REF_LENGTH_MM} mm, R {REF_RADIUS_MM} mm")
    print(f"written: {out}/calculix_taylor.{{csv,json,png}}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
