#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The deposit of a granular column collapse (scenes/column_collapse.toml) against the run-out
laws of Lajeunesse et al. (2004).

usage: tools/plot_collapse.py OUT [-o PNG] [--start T] [--repose DEG [DEG ...]] [--compare OTHER]

A run of one body (the continuum counterpart, scenes/column_collapse_continuum.toml) is read
from its frames alone: R is the mean over 24 sectors of the outermost node in each, H the
highest node, and the figure's third panel shows the nodes at the end coloured by their initial
height. Its `top undisturbed` line gives the height of the column's centre (the nodes within
R_i / 4 of the axis), which for a < 0.74 must stay at H_i.

A run of many grains reads OUT/history.csv (every grain's centre of mass in time) and OUT/results.h5 (the grains'
nodes, first and last frame), and prints and draws:
- the column at the start (`--start`, default the first history row: the time the tube starts
  to rise is a better start when the grains settle first): R_i, the radius of the outermost
  grain's surface, H_i, the height of the highest grain's surface, and a = H_i / R_i;
- the deposit at the end: H_f, the highest node; R_f, the run-out, taken as the radius that
  holds 98 % of the grains' centres plus a mean grain radius (a few grains that roll or bounce
  off the front are not the deposit's edge); the azimuthally averaged profile h(r), the mean over
  24 sectors of the highest node in each 1/2-grain-wide ring;
- R(t) and H(t) the same way from the grains' centres in history.csv;
- the laws: for a < 0.74, R_f / R_i = a / (2 mu) + sqrt(1 - a^2 / (12 mu^2)) with mu = tan of the
  repose angle (a truncated cone whose top is undisturbed: H_f = H_i); for a > 0.74,
  R_f / R_i = sqrt(3 a / 0.74) with H_f = 0.74 R_i (a cone). Repose angles by default 21 and
  23.5 degrees (the beads' repose angle and the continuum papers' best-fit friction angle);
  and, per law, how far the profile lies from the law's outline where that outline is at least
  one grain diameter high (grains cannot make a thinner layer: beyond that radius they spread as
  one layer, which lengthens the run-out of coarse grains at large a).
With --compare OTHER (another run of grains, read the same way and from the same --start), the
two deposits in units of their own R_i: the run-out, the height and the profile h(r) / R_i
apart (the scale pair: the same a at two sizes).
The figure: the profile against the initial column and the laws' shapes, R and H in time, and
the grains' centres at the end in (r, z), coloured by their height in the initial column (the
layers of the papers' internal-structure test).
"""
import argparse
import math
import os
import sys

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "python"))
import femdem  # noqa: E402  (tools/python/femdem)

SECTORS = 24
KEEP = 0.98  # share of the grains' centres inside the run-out


def grain_columns(history):
    names = [b for b in femdem.body_names(history) if f"{b}.com_x" in history]
    xyz = np.stack([np.stack([history[f"{b}.com_{c}"] for c in "xyz"], axis=-1) for b in names],
                   axis=1)  # (rows, grains, 3)
    return names, xyz


def run_out(centres, grain_radius):
    """R from the centres' radial distances (98 % inside) and H from the highest centre."""
    r = np.hypot(centres[..., 0], centres[..., 1])
    return np.quantile(r, KEEP, axis=-1) + grain_radius, centres[..., 2].max(axis=-1) + grain_radius


def laws(a, repose_degrees):
    """(label, R_f / R_i, the deposit's outline as ([r], [h]) in units of R_i)."""
    out = []
    for deg in repose_degrees:
        mu = math.tan(math.radians(deg))
        if a < 0.74:  # a truncated cone of slope mu whose top stays at H_i
            r_f = a / (2 * mu) + math.sqrt(max(0.0, 1 - a * a / (12 * mu * mu)))
            out.append((f"eq. 60, {deg:g} deg", r_f, ([0, r_f - a / mu, r_f], [a, a, 0])))
        else:  # a cone of height 0.74 R_i
            r_f = math.sqrt(3 * a / 0.74)
            out.append(("eq. 61", r_f, ([0, r_f], [0.74, 0])))
            break
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out")
    ap.add_argument("-o", "--output", help="figure (default OUT/collapse.png)")
    ap.add_argument("--start", type=float, default=None, help="time of the initial column (s)")
    ap.add_argument("--repose", type=float, nargs="+", default=[21.0, 23.5])
    ap.add_argument("--compare", metavar="OTHER",
                    help="another run of grains: its normalised deposit against OUT's")
    a = ap.parse_args()
    run = femdem.Run(a.out)
    names, _ = grain_columns(run.history)
    if not names:
        sys.exit(f"plot_collapse: {a.out}: no bodies in history.csv")
    if len(names) == 1:
        return continuum(a)
    d = grain_deposit(a.out, run.history, a.start)
    print(f"{d['grains']} grains, mean radius {d['rg'] * 1e3:.3f} mm; start t = "
          f"{d['t'][d['i0']]:.4g} s, end t = {d['t'][-1]:.4g} s")
    report(a, d["t"], d["R"], d["H"], d["i0"], d["h_f"], d["deposit"], d["cloud"],
           "grain centres", 8, grain=2 * d["rg"])
    if a.compare:
        compare(d, grain_deposit(a.compare, femdem.Run(a.compare).history, a.start), a.compare)


def grain_deposit(out, h, start):
    """A run of grains: the column at `start` and the deposit at the end (see the docstring)."""
    names, xyz = grain_columns(h)
    t = h["time"]
    i0 = 0 if start is None else int(np.searchsorted(t, start))
    with femdem.open_results(out) as res:
        x0, x1 = res.positions(0), res.positions(-1)
        node_body = np.asarray(res.node_body)
    # each grain's radius: its nodes' largest distance from their mean, in the first frame
    radius = np.zeros(node_body.max() + 1)
    for b in range(radius.size):
        p = x0[node_body == b]
        if len(p):
            radius[b] = np.linalg.norm(p - p.mean(axis=0), axis=1).max()
    rg = float(radius[radius > 0].mean())
    R, H = run_out(xyz, rg)
    cloud = (np.hypot(xyz[-1, :, 0], xyz[-1, :, 1]), xyz[-1, :, 2], xyz[i0, :, 2])
    # the deposit's profile: the highest node per ring and sector, averaged over the sectors
    return dict(grains=len(names), t=t, i0=i0, rg=rg, R=R, H=H, deposit=profile(x1, rg),
                h_f=float(x1[:, 2].max()), cloud=cloud)


def compare(d, e, other):
    """Two deposits in units of their own R_i (a scale pair: the same a at two sizes; or any
    two variants): the run-out, the height and the profile h(r) / R_i, interpolated on one
    grid of r / R_i out to the shorter run-out; the profile's difference is given as a share
    of the larger deposit's height, so 5 % means the two outlines lie within 5 % of H_f."""
    def normalised(x):
        r_i = x["R"][x["i0"]]
        return r_i, x["R"][-1] / r_i, x["h_f"] / r_i, x["deposit"][0] / r_i, x["deposit"][1] / r_i
    r_i, rf, hf, pr, ph = normalised(d)
    r_j, rf2, hf2, pr2, ph2 = normalised(e)
    print(f"against {other} ({e['grains']} grains, R_i = {r_j * 1e3:.2f} mm, a = "
          f"{e['H'][e['i0']] / r_j:.3f}): R_f / R_i {rf:.3f} against {rf2:.3f} "
          f"({100 * (rf / rf2 - 1):+.1f} %), H_f / R_i {hf:.3f} against {hf2:.3f} "
          f"({100 * (hf / hf2 - 1):+.1f} %)")
    grid = np.linspace(0.0, min(rf, rf2), 101)
    diff = np.abs(np.interp(grid, pr, ph, right=0.0) - np.interp(grid, pr2, ph2, right=0.0))
    top = max(hf, hf2)
    print(f"  profile h(r) / R_i out to r = {grid[-1]:.2f} R_i: apart by {diff.mean():.3f} R_i on "
          f"average ({100 * diff.mean() / top:.1f} % of H_f), {diff.max():.3f} R_i at most")


def thick_part(deposit, r_i, outline, grain):
    """Where the law's deposit is at least one grain thick: the mean and largest |h - h_law| / R_i
    of the profile there, and the radius / R_i out to which that holds. Coarse grains cannot make
    a layer thinner than themselves, so beyond it they spread as one layer (the run-out's excess
    at a large a)."""
    lr, lh = outline
    r = deposit[0] / r_i
    h_law = np.interp(r, lr, lh, right=0.0)
    thick = h_law >= grain / r_i
    if not thick.any():
        return None
    d = np.abs(deposit[1][thick] / r_i - h_law[thick])
    return float(d.mean()), float(d.max()), float(r[thick].max())


def report(a, t, R, H, i0, h_f, deposit, cloud, cloud_label, point_size, note=None, grain=None):
    """Print the column, the deposit and the laws; draw the profile against the laws, R and H in
    time, and the cloud (r, z, initial z) at the end coloured by the initial height."""
    r_i, h_i, r_f = R[i0], H[i0], R[-1]
    aspect = h_i / r_i
    print(f"initial column: R_i = {r_i * 1e3:.2f} mm, H_i = {h_i * 1e3:.2f} mm, a = {aspect:.3f}")
    print(f"deposit: R_f = {r_f * 1e3:.2f} mm (R_f / R_i = {r_f / r_i:.3f}), H_f = "
          f"{h_f * 1e3:.2f} mm (H_f / R_i = {h_f / r_i:.3f}, H_f / H_i = {h_f / h_i:.3f})")
    if note:
        print(note)
    for label, value, outline in laws(aspect, a.repose):
        print(f"  {label}: R_f / R_i = {value:.3f} (deposit {100 * (r_f / r_i / value - 1):+.1f} %)")
        fit = thick_part(deposit, r_i, outline, grain) if grain else None
        if fit:
            print(f"    where it is a grain or more thick (r <= {fit[2]:.2f} R_i): profile off "
                  f"it by {fit[0]:.3f} R_i on average, {fit[1]:.3f} R_i at most")
    if aspect > 0.74:
        print(f"  saturation H_f = 0.74 R_i: deposit {100 * (h_f / r_i / 0.74 - 1):+.1f} %")

    fig, ax = plt.subplots(1, 3, figsize=(16, 4.8))
    ax[0].plot(deposit[0] / r_i, deposit[1] / r_i, "k-", label="deposit h(r) (24 sectors)")
    ax[0].plot([0, 1, 1], [h_i / r_i, h_i / r_i, 0], "b--", label="initial column")
    for label, value, (lr, lh) in laws(aspect, a.repose):
        ax[0].plot(lr, lh, ":", label=f"{label}: R_f / R_i = {value:.2f}")
    ax[0].set_xlabel("r / R_i")
    ax[0].set_ylabel("h / R_i")
    ax[0].legend(fontsize=8)
    ax[1].plot(t, R / r_i, label="R(t) / R_i")
    ax[1].plot(t, H / r_i, label="H(t) / R_i")
    ax[1].set_xlabel("t (s)")
    ax[1].legend()
    r, z, z0 = cloud
    sc = ax[2].scatter(r / r_i, z / r_i, c=z0 / h_i, s=point_size, cmap="viridis")
    fig.colorbar(sc, ax=ax[2], label="initial height / H_i")
    ax[2].set_xlabel(f"r / R_i ({cloud_label} at the end)")
    ax[2].set_ylabel("z / R_i")
    fig.tight_layout()
    png = a.output or os.path.join(a.out, "collapse.png")
    fig.savefig(png, dpi=110)
    print(f"figure: {png}")


def sector_front(x):
    """The mean over SECTORS of the outermost node's radius in each sector."""
    rr = np.hypot(x[:, 0], x[:, 1])
    s = ((np.arctan2(x[:, 1], x[:, 0]) + math.pi) / (2 * math.pi) * SECTORS).astype(int) % SECTORS
    front = np.zeros(SECTORS)
    np.maximum.at(front, s, rr)
    return float(front.mean())


def profile(x, ring, empty_is_zero=True):
    """(ring centres, the mean over SECTORS of the highest node in each ring and sector).

    Among grains a sector with no node has no grain there (height 0); a continuum covers every
    sector it reaches, and a cell with no node is one the mesh's nodes happen to miss (near the
    axis, where the cells are small), so with empty_is_zero=False the mean is over the cells
    that hold nodes."""
    rr = np.hypot(x[:, 0], x[:, 1])
    nb = int(rr.max() / ring) + 1
    top = np.zeros((SECTORS, nb))
    hit = np.zeros((SECTORS, nb))
    s = ((np.arctan2(x[:, 1], x[:, 0]) + math.pi) / (2 * math.pi) * SECTORS).astype(int) % SECTORS
    k = (rr / ring).astype(int)
    np.maximum.at(top, (s, k), np.maximum(x[:, 2], 0.0))
    np.add.at(hit, (s, k), 1.0)
    if empty_is_zero:
        return (np.arange(nb) + 0.5) * ring, top.mean(axis=0)
    return (np.arange(nb) + 0.5) * ring, top.sum(axis=0) / np.maximum((hit > 0).sum(axis=0), 1)


def centre_height(x, radius):
    """The highest node within `radius` of the axis."""
    return float(x[np.hypot(x[:, 0], x[:, 1]) < radius, 2].max())


def continuum(a):
    """One deforming body: every measure from its nodes, frame by frame."""
    with femdem.open_results(a.out) as res:
        t = np.asarray(res.times)
        frames = [res.positions(i) for i in range(len(t))]
    i0 = 0 if a.start is None else min(int(np.searchsorted(t, a.start)), len(t) - 1)
    R = np.array([sector_front(x) for x in frames])
    H = np.array([float(x[:, 2].max()) for x in frames])
    r_i, h_f = R[i0], H[-1]
    x0, x1 = frames[i0], frames[-1]
    c0, c1 = centre_height(x0, r_i / 4), centre_height(x1, r_i / 4)
    print(f"one body, {x1.shape[0]} nodes; start t = {t[i0]:.4g} s, end t = {t[-1]:.4g} s")
    ring = r_i / 12  # about the mesh's node spacing at the top
    cloud = (np.hypot(x1[:, 0], x1[:, 1]), x1[:, 2], x0[:, 2])
    report(a, t, R, H, i0, h_f, profile(x1, ring, empty_is_zero=False), cloud, "nodes", 2,
           f"top undisturbed: the centre's height {c0 * 1e3:.3f} -> {c1 * 1e3:.3f} mm "
           f"({100 * (c1 / c0 - 1):+.2f} %)")


if __name__ == "__main__":
    main()
