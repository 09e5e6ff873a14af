#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Measures and draws the settled armour layer of scenes/armour_layer.toml without ParaView.

usage: tools/armour_layer.py OUT [-o PNG] [--unit-volume V] [--slope 1.5]

Reads OUT/results.h5 (the last frame), OUT/summary.json and OUT/history.csv, and prints:
- when the run came to rest, the peak kinetic energy, the run time; how many units move slower
  than 0.1 m/s at the end and the three fastest with their share of the kinetic energy;
- the deepest overlap between bodies over the run and at the end (summary.json, the contact
  estimate 2E/N of the deepest pair), absolute and relative to the element size;
- the packing density of the layer, measured in a control volume over the slope away from the
  lateral edges (the interior patch):
    * the areal density N D_n^2 / A (units whose centre of mass lies over the patch, per slope
      area, times the nominal diameter squared, D_n = V^(1/3): the coefficient breakwater
      design uses);
    * the solid fraction of the units in the slab from the slope plane to the layer's top (the
      height under which 95 % of the units' volume over the patch lies), the fixed units' volume
      taken out of the slab; and its profile across the layer.
  The volumes are counted on a 5 cm grid of points in slope coordinates, each point tested
  against the corner tetrahedra of the deformed TET10 mesh.
The figure: the final packing seen from the side and from above the slope (boundary faces of
the deformed meshes, one colour per unit, the fixed units grey), the solid-fraction profile and
the kinetic energy against time with the rest threshold.
"""
import argparse
import os
import sys

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "python"))
import femdem  # noqa: E402  (tools/python/femdem)
from femdem.plotting import legend_outside  # noqa: E402

GRID = 0.05  # m, the point spacing of the volume count


def slope_frame(run_over_rise):
    """Unit vectors: up the slope (in x-z), across it (y), and its outward normal."""
    angle = np.arctan(1.0 / run_over_rise)
    up = np.array([np.cos(angle), 0.0, np.sin(angle)])
    across = np.array([0.0, 1.0, 0.0])
    normal = np.array([-np.sin(angle), 0.0, np.cos(angle)])
    return up, across, normal


def load(out):
    with femdem.open_results(out) as r:
        return r.positions(-1), r.connectivity[:, :4], r.element_body, r.body_names, r.times[-1]


def tet_volumes(x, conn):
    a, b, c, d = (x[conn[:, k]] for k in range(4))
    return np.abs(np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a))) / 6.0


def points_inside(x, conn, grid_lo, n_cells, frame):
    """Boolean grid (s, y, n) of points inside any of the tetrahedra conn (slope coordinates)."""
    up, across, normal = frame
    q = np.stack([x @ up, x @ across, x @ normal], axis=1)  # node coordinates in the slope frame
    inside = np.zeros(n_cells, dtype=bool)
    for tet in conn:
        c = q[tet]
        lo = np.maximum(np.ceil((c.min(axis=0) - grid_lo) / GRID).astype(int), 0)
        hi = np.minimum(np.floor((c.max(axis=0) - grid_lo) / GRID).astype(int), np.array(n_cells) - 1)
        if np.any(hi < lo):
            continue
        idx = np.stack(np.meshgrid(*[np.arange(lo[k], hi[k] + 1) for k in range(3)],
                                   indexing="ij"), axis=-1).reshape(-1, 3)
        p = grid_lo + idx * GRID
        T = (c[1:] - c[0]).T
        lam = np.linalg.solve(T, (p - c[0]).T).T
        ok = (lam >= 0).all(axis=1) & (lam.sum(axis=1) <= 1)
        sel = idx[ok]
        inside[sel[:, 0], sel[:, 1], sel[:, 2]] = True
    return inside


def boundary_faces(conn):
    faces = np.concatenate([conn[:, [0, 1, 2]], conn[:, [0, 1, 3]], conn[:, [0, 2, 3]],
                            conn[:, [1, 2, 3]]])
    owner = np.tile(np.arange(len(conn)), 4)
    key = np.sort(faces, axis=1)
    _, first, counts = np.unique(key, axis=0, return_index=True, return_counts=True)
    once = first[counts == 1]
    return faces[once], owner[once]


def draw(ax, x, conn, element_body, fixed, elev, azim, title):
    faces, owner = boundary_faces(conn)
    body = element_body[owner]
    cmap = plt.get_cmap("tab20")
    colours = np.array([(0.6, 0.6, 0.6, 1.0) if fixed[b] else cmap(b % 20) for b in body])
    # light from above: shade by the face normal's z component
    tri = x[faces]
    nrm = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    nrm /= np.linalg.norm(nrm, axis=1)[:, None] + 1e-300
    shade = 0.55 + 0.45 * np.abs(nrm[:, 2])
    colours[:, :3] *= shade[:, None]
    ax.add_collection3d(Poly3DCollection(tri, facecolors=colours, edgecolors="none"))
    lo, hi = x.min(axis=0), x.max(axis=0)
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect(hi - lo)
    ax.view_init(elev=elev, azim=azim)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    ax.set_title(title, fontsize=9)


def read_summary(out):
    """summary.json, or for a run still going (or killed) what history.csv's last row says."""
    run = femdem.Run(out)
    if run.summary is not None:
        return run.summary
    h = run.history
    names = sorted(femdem.body_names(h))
    bodies = {}
    for n in names:
        bodies[n] = {"com": [h[f"{n}.com_{c}"][-1] for c in "xyz"],
                     "vcom": [h[f"{n}.vcom_{c}"][-1] for c in "xyz"],
                     "kinetic_energy": h[f"{n}.kinetic_energy"][-1]}
    ke = np.asarray(h["kinetic_energy"])
    pen = np.asarray(h.get("contact.max_penetration", [0.0]))
    print("(no summary.json: the run is going or was stopped; read from history.csv)")
    return {"bodies": bodies, "steps": len(h["time"]), "wall_time_s": float("nan"), "threads": 0,
            "end_time": h["time"][-1], "status": "running or stopped",
            "extra": {"peak_kinetic_energy": float(ke.max()),
                      "peak_kinetic_energy_time": float(h["time"][int(ke.argmax())]),
                      "contact_max_penetration": float(pen.max()),
                      "contact_max_penetration_time": float(h["time"][int(pen.argmax())]),
                      "contact_final_max_penetration": float(pen[-1])}}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out")
    ap.add_argument("-o", "--png", default=None)
    ap.add_argument("--unit-volume", type=float, default=None,
                    help="volume of one unit (m^3); default: the mean over the moving bodies")
    ap.add_argument("--slope", type=float, default=1.5, help="run over rise of the slope")
    ap.add_argument("--element-size", type=float, default=0.4,
                    help="the units' mesh element size (m), for the relative penetration")
    ap.add_argument("--edge", type=float, default=None,
                    help="margin kept from the layer's lateral and along-slope ends (m); default D_n")
    args = ap.parse_args()
    out = args.out
    summ = read_summary(out)
    x, conn, element_body, names, t_end = load(out)
    bodies = summ["bodies"]
    fixed = np.array([bodies[n]["kinetic_energy"] == 0.0 and bodies[n]["vcom"] == [0, 0, 0]
                      and n.startswith("base") for n in names])
    units = [i for i, n in enumerate(names) if not fixed[i]]
    vol = tet_volumes(x, conn)
    unit_volume = args.unit_volume or float(np.mean([vol[element_body == i].sum() for i in units]))
    dn = unit_volume ** (1.0 / 3.0)
    frame = slope_frame(args.slope)
    up, across, normal = frame

    extra = summ.get("extra", {})
    print(f"run: {summ['steps']} {'history rows' if summ['threads'] == 0 else 'steps'}, "
          f"{summ['wall_time_s'] / 60:.1f} min wall, "
          f"{summ['threads']} thread(s), end time {summ['end_time']:.3f} s, status {summ['status']}")
    if "at_rest_time" in extra:
        ke_end = summ["energy"]["kinetic"]
        print(f"at rest at t = {extra['at_rest_time']:.3f} s (kinetic energy {ke_end:.4g} J, "
              f"{ke_end / extra['peak_kinetic_energy']:.2e} of its peak "
              f"{extra['peak_kinetic_energy']:.4g} J at t = {extra['peak_kinetic_energy_time']:.3f} s)")
    else:
        print("NOT at rest by the end of the run")
    # The rest criterion is on the total: say which units still hold what is left of it.
    speed = {names[i]: float(np.linalg.norm(bodies[names[i]]["vcom"])) for i in units}
    energy = {names[i]: float(bodies[names[i]]["kinetic_energy"]) for i in units}
    total = sum(energy.values())
    slow = sum(v < 0.1 for v in speed.values())
    fastest = sorted(speed, key=speed.get, reverse=True)[:3]
    print(f"units at the end: {slow} of {len(units)} slower than 0.1 m/s; fastest "
          + ", ".join(f"{n} {speed[n]:.2f} m/s ({energy[n] / total:.0%} of the kinetic energy)"
                      if total > 0 else f"{n} {speed[n]:.2f} m/s"
                      for n in fastest))
    pen, pen_end = extra.get("contact_max_penetration", 0.0), extra.get("contact_final_max_penetration", 0.0)
    print(f"deepest overlap between bodies: {pen * 1e3:.2f} mm at t = "
          f"{extra.get('contact_max_penetration_time', 0.0):.3f} s ({pen / args.element_size:.2e} of "
          f"the element size {args.element_size} m); at the end {pen_end * 1e3:.2f} mm "
          f"({pen_end / args.element_size:.2e})")

    # the interior patch: the along-slope and lateral extent of the units' centres, less a margin
    com = np.array([bodies[names[i]]["com"] for i in units])
    s_c, y_c, n_c = com @ up, com @ across, com @ normal
    margin = args.edge if args.edge is not None else dn
    s0, s1 = max(s_c.min(), 0.0) + margin, s_c.max() - margin
    y0, y1 = y_c.min() + margin, y_c.max() - margin
    if s1 <= s0 or y1 <= y0:
        print("the layer is too small for an interior patch")
        return 1
    area = (s1 - s0) * (y1 - y0)
    over = (s_c >= s0) & (s_c <= s1) & (y_c >= y0) & (y_c <= y1)
    n_over = int(over.sum())
    print(f"units: {len(units)}, D_n = {dn:.3f} m (V = {unit_volume:.4f} m^3); interior patch "
          f"s {s0:.2f}..{s1:.2f} m up the slope, y {y0:.2f}..{y1:.2f} m: {area:.2f} m^2 of slope")
    print(f"areal packing density N D_n^2 / A = {n_over} x {dn:.3f}^2 / {area:.2f} = "
          f"{n_over * dn * dn / area:.3f}")

    n_top_all = (x @ normal).max()
    grid_lo = np.array([s0, y0, 0.0])
    n_cells = (int((s1 - s0) / GRID) + 1, int((y1 - y0) / GRID) + 1, int(n_top_all / GRID) + 1)
    unit_tets = np.isin(element_body, units)
    solid = points_inside(x, conn[unit_tets], grid_lo, n_cells, frame)
    base = points_inside(x, conn[~unit_tets], grid_lo, n_cells, frame)
    per_level = solid.sum(axis=(0, 1)).astype(float)
    free_level = (~base).sum(axis=(0, 1)).astype(float)
    cum = np.cumsum(per_level)
    k_top = int(np.searchsorted(cum, 0.95 * cum[-1])) + 1
    thickness = k_top * GRID
    fraction = per_level[:k_top].sum() / free_level[:k_top].sum()
    print(f"layer thickness (95 % of the units' volume over the patch): {thickness:.2f} m = "
          f"{thickness / dn:.2f} D_n")
    print(f"solid fraction of the layer: {fraction:.3f} (porosity {1 - fraction:.3f}); the fixed "
          f"units take {base[:, :, :k_top].mean():.3f} of the slab and are left out")

    fig = plt.figure(figsize=(15, 10))
    ax1 = fig.add_subplot(2, 2, 1, projection="3d")
    draw(ax1, x, conn, element_body, fixed, elev=5, azim=-90,
         title=f"t = {t_end:.2f} s, from the side (along y)")
    ax2 = fig.add_subplot(2, 2, 2, projection="3d")
    draw(ax2, x, conn, element_body, fixed, elev=55, azim=-150, title="from above the slope")
    ax3 = fig.add_subplot(2, 2, 3)
    levels = (np.arange(len(per_level)) + 0.5) * GRID
    with np.errstate(invalid="ignore", divide="ignore"):
        ax3.plot(per_level / np.maximum(free_level, 1), levels, "b-")
    ax3.axhline(thickness, color="k", ls="--", label=f"layer top ({thickness:.2f} m)")
    ax3.set_xlabel("solid fraction of the units (fixed units left out)")
    ax3.set_ylabel("distance from the slope plane (m)")
    ax3.set_title(f"interior patch {area:.1f} m$^2$: solid fraction {fraction:.3f}, "
                  f"N D$_n^2$/A = {n_over * dn * dn / area:.3f}", fontsize=9)
    legend_outside(ax3)
    ax4 = fig.add_subplot(2, 2, 4)
    h = femdem.read_history(out)
    ke = np.asarray(h["kinetic_energy"])
    ax4.semilogy(h["time"], np.maximum(ke, 1e-30), "r-", label="kinetic energy")
    # the rest criterion, and the run's own threshold where it differs
    thresholds = {1e-3, extra.get("rest_kinetic_fraction", 1e-3)}
    for frac, style in zip(sorted(thresholds, reverse=True), ("--", ":")):
        ax4.axhline(frac * ke.max(), color="k", ls=style, label=f"{frac:g} of the peak")
    ax4.set_ylim(max(ke.max() * 1e-6, 1e-30), ke.max() * 3)
    ax4.set_xlabel("time (s)")
    ax4.set_ylabel("J")
    legend_outside(ax4)
    ax4.set_title("kinetic energy", fontsize=9)
    fig.tight_layout()
    png = args.png or os.path.join(out, "armour_layer.png")
    fig.savefig(png, dpi=110)
    print(f"figure: {png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
