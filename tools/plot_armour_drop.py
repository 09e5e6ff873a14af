#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Draws and measures the V-Cross drop (scenes/armour_unit_drop.toml) without ParaView.

usage: tools/plot_armour_drop.py ELASTIC_OUT MC_OUT [-o PNG] [--body unit]

Reads history.csv, summary.json and results.h5 of the two runs (elastic and Mohr-Coulomb) and
prints, for each: the peak largest principal stress and its time (summary.json), the element
where the largest principal stress is highest in the output frames and its position, the
largest equivalent plastic strain, the plastic volume fraction, the energy balance error and
the arm deflection (the thesis' measure, Fig. 6.10: vertical displacement of the arm tips'
lower edge relative to the core corners below them, which start level).

The figure has: the largest principal stress against time; the arm deflection against time;
the unit projected onto the x-z plane (the plane of the cross), each element's centroid coloured
by its largest principal stress at the elastic run's peak frame, and by the equivalent plastic
strain at the end of the Mohr-Coulomb run. Elements are drawn in increasing order of the value,
so each point of the projection shows the largest value behind it.
"""
import argparse
import os
import sys

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "python"))
import femdem  # noqa: E402  (tools/python/femdem)
from femdem.plotting import legend_outside  # noqa: E402

# V-Cross proportions of scenes/meshes/v_cross.stl (span S, arm width a), used to find the arm
# tips and the core corners.
SPAN = 4.67
ARM = 1.26


def read_history(out, body):
    h = femdem.read_history(out)
    return h["time"], h[body + ".max_principal_stress"]


def principal_max(stress):
    """Largest eigenvalue of each 3x3 stress (rows of 9 numbers)."""
    return np.linalg.eigvalsh(stress.reshape(-1, 3, 3))[:, -1]


def arm_deflection(X, disp):
    """Mean vertical displacement of the arm tips' lower edges minus that of the core corners
    under them (x = +-a/2 at the arms' lower face), per frame."""
    z_arm = 0.5 * SPAN - 0.5 * ARM
    tol = 0.02
    on_lower = np.abs(X[:, 2] - z_arm) < tol
    tips = on_lower & (np.abs(np.abs(X[:, 0]) - 0.5 * SPAN) < tol)
    corners = on_lower & (np.abs(np.abs(X[:, 0]) - 0.5 * ARM) < tol)
    if not tips.any() or not corners.any():
        return None
    return disp[:, tips, 2].mean(axis=1) - disp[:, corners, 2].mean(axis=1)


def measure(out, body):
    summ = femdem.read_summary(out)
    b = summ["bodies"][body]
    r = {
        "peak": b["max_principal_stress"],
        "peak_time": b["max_principal_stress_time"],
        "max_eps_p": b["max_equivalent_plastic_strain"],
        "balance": summ["energy"]["balance_error"],
        "energy": summ["energy"],
        "elements": summ["elements"],
        "steps": summ["steps"],
        "wall": summ["wall_time_s"],
    }
    with femdem.open_results(out) as f:
        X = f.coordinates
        conn = f.connectivity
        times = f.times
        s1 = np.array([principal_max(f.field("stress", i)) for i in range(len(times))])
        eps = f.series("equivalent_plastic_strain")
        disp = f.series("displacement")
    cent = X[conn[:, :4]].mean(axis=1)
    fi, ei = np.unravel_index(np.argmax(s1), s1.shape)
    r.update(X=X, cent=cent, times=times, s1=s1, eps=eps, frame_peak=fi,
             frame_peak_value=s1[fi, ei], frame_peak_time=times[fi], frame_peak_where=cent[ei])
    # Plastic volume fraction at the end: element volumes from the corner nodes (straight-sided
    # mesh from a faceted surface, so this is the element's volume).
    p = X[conn[:, :4]]
    vol = np.abs(np.einsum("ij,ij->i", np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]),
                           p[:, 3] - p[:, 0])) / 6.0
    plastic = eps[-1] > 0
    r["plastic_fraction"] = vol[plastic].sum() / vol.sum()
    r["plastic_where"] = (cent[plastic].min(axis=0), cent[plastic].max(axis=0)) if plastic.any() else None
    r["defl"] = arm_deflection(X, disp)
    return r


def project(ax, cent, value, title, label, cmap):
    order = np.argsort(value)
    sc = ax.scatter(cent[order, 0], cent[order, 2], c=value[order], s=6, cmap=cmap, marker="s")
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("z (m)")
    ax.set_title(title, fontsize=9)
    plt.colorbar(sc, ax=ax, label=label, shrink=0.8)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("elastic")
    ap.add_argument("mc")
    ap.add_argument("-o", "--output", default=None)
    ap.add_argument("--body", default="unit")
    a = ap.parse_args()
    runs = {"elastic": a.elastic, "Mohr-Coulomb": a.mc}
    res = {}
    for name, out in runs.items():
        r = measure(out, a.body)
        res[name] = r
        print(f"{name}: {out}")
        print(f"  elements {r['elements']}, steps {r['steps']}, wall time {r['wall']:.0f} s")
        print(f"  peak largest principal stress {r['peak'] / 1e6:.3f} MPa at t = {r['peak_time'] * 1e3:.3f} ms")
        # The thesis shows snapshots at 0.5, 1.5 and 2.5 ms (Figs 6.5-6.7): its peaks may be
        # taken from those, so the largest values up to those times are printed too.
        th, sh = read_history(out, a.body)
        for tw in (1.5e-3, 2.5e-3):
            print(f"  largest up to {tw * 1e3:.1f} ms: {sh[th <= tw].max() / 1e6:.3f} MPa")
        w = r["frame_peak_where"]
        print(f"  in the frames: {r['frame_peak_value'] / 1e6:.3f} MPa at t = {r['frame_peak_time'] * 1e3:.3f} ms,"
              f" element centroid ({w[0]:.3f}, {w[1]:.3f}, {w[2]:.3f}) m")
        print(f"  max equivalent plastic strain {r['max_eps_p']:.3e}, plastic volume fraction "
              f"{r['plastic_fraction']:.4f}")
        if r["plastic_where"] is not None:
            lo, hi = r["plastic_where"]
            print(f"  plastic elements' centroids within x [{lo[0]:.2f}, {hi[0]:.2f}], z [{lo[2]:.2f}, {hi[2]:.2f}] m")
        print(f"  energy balance error {r['balance']:.2e}; plastic dissipation "
              f"{r['energy']['plastic_dissipation']:.1f} J, kinetic at the end {r['energy']['kinetic']:.1f} J")
        if r["defl"] is not None:
            d = r["defl"]
            i = np.argmax(np.abs(d))
            print(f"  arm deflection: largest |tip - corner| {abs(d[i]) * 1e3:.4f} mm at t = {r['times'][i] * 1e3:.3f} ms")
    de, dm = res["elastic"]["defl"], res["Mohr-Coulomb"]["defl"]
    if de is not None and dm is not None:
        red = 1 - np.abs(dm).max() / np.abs(de).max()
        print(f"arm deflection reduced by {red * 100:.1f} % (thesis: about 60 %)")
    print(f"peak tension MC / elastic = {res['Mohr-Coulomb']['peak'] / res['elastic']['peak']:.3f}"
          f" (thesis 3.5 / 12 = {3.5 / 12:.3f})")

    fig, axs = plt.subplots(2, 2, figsize=(11, 9))
    for name, out in runs.items():
        t, s1 = read_history(out, a.body)
        axs[0, 0].plot(t * 1e3, s1 / 1e6, label=name)
        r = res[name]
        if r["defl"] is not None:
            axs[0, 1].plot(r["times"] * 1e3, r["defl"] * 1e3, "o-", ms=3, label=name)
    axs[0, 0].axhline(12, color="C0", ls="--", lw=0.8, label="thesis elastic 12 MPa")
    axs[0, 0].axhline(3.5, color="C1", ls="--", lw=0.8, label="thesis M-C 3.5 MPa")
    axs[0, 0].set_xlabel("t (ms)")
    axs[0, 0].set_ylabel("largest principal stress in the unit (MPa)")
    legend_outside(axs[0, 0])
    axs[0, 1].set_xlabel("t (ms)")
    axs[0, 1].set_ylabel("arm deflection, tip - core corner (mm)")
    legend_outside(axs[0, 1])
    re_ = res["elastic"]
    project(axs[1, 0], re_["cent"], re_["s1"][re_["frame_peak"]] / 1e6,
            f"elastic, largest principal stress at t = {re_['frame_peak_time'] * 1e3:.2f} ms",
            "MPa", "coolwarm")
    rm = res["Mohr-Coulomb"]
    project(axs[1, 1], rm["cent"], rm["eps"][-1],
            f"Mohr-Coulomb, equivalent plastic strain at t = {rm['times'][-1] * 1e3:.1f} ms",
            "equivalent plastic strain", "viridis")
    fig.suptitle("V-Cross dropped flat at 2 m/s on a rigid base (scenes/armour_unit_drop.toml)")
    fig.tight_layout()
    png = a.output or os.path.join(a.mc, "armour_unit_drop.png")
    fig.savefig(png, dpi=110)
    print("figure:", png)


if __name__ == "__main__":
    main()
