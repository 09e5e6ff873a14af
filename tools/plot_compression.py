#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Unconfined compression of a cylinder between two walls (scenes/mc_cylinder_compression.toml):
axial stress-strain curve against the theoretical peak, and the shear band.

usage: tools/plot_compression.py OUT_DIR [--json] [--figures DIR] [--window EPS]

Reads OUT_DIR/run.log (the resolved scene), history.csv and results.h5. The cylinder is the
body meshed by the "cylinder" generator; the walls are the two whose normals are +z and -z.
Axial stress = mean of the two walls' axial forces over the initial section pi R^2
(compression positive); axial strain = 1 - (wall gap) / L0.

Theory: von Mises: the yield stress; Mohr-Coulomb: 2 c cos(phi) / (1 - sin(phi)), and a slip
plane at 45 + phi/2 degrees to the horizontal (45 for von Mises).

Peak: the largest stress up to the strain EPS (default 1.2e-3, the window of the thesis' zoomed
figure 4.28, ten times the elastic limit): past it the section grows (plastic flow) and the wall
force over the *initial* section keeps rising, although the true stress does not. The largest
stress of the whole run is printed too.

Band: in the last frame of results.h5, the elements with the largest equivalent plastic strain
(the top 5 %, at least 20) define a plane by a least-squares fit (principal axes of their
deformed centroids, weighted by the plastic strain); its angle to the horizontal is the band
angle. The ratio of their spread across the plane to their spread along it is printed as the
thickness ratio: a band gives a small one (below about 0.3), plasticity spread through the
body (barrelling, no band) a large one, and the angle then means nothing. The picture is a cut through the axis, perpendicular to that plane, coloured by
equivalent plastic strain, with the fitted and the theoretical lines.

Writes OUT_DIR/compression_curve.png and OUT_DIR/compression_band.png (or into --figures DIR)
and prints the numbers; --json prints them as one JSON object instead.
"""
import argparse
import json
import math
import os
import sys
import tomllib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "python"))
import femdem  # noqa: E402  (tools/python/femdem)
from femdem.plotting import legend_outside  # noqa: E402
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.tri as mtri  # noqa: E402


def resolved_scene(out):
    text = open(os.path.join(out, "run.log")).read()
    start = text.index("# resolved scene")
    end = text.index("# end of resolved scene")
    return tomllib.loads(text[start:end])


def theory(material):
    model = material["model"]
    if model == "mohr_coulomb":
        c = material["cohesion"]
        phi = math.radians(material["friction_angle"])
        return 2 * c * math.cos(phi) / (1 - math.sin(phi)), 45 + material["friction_angle"] / 2, (
            f"2c cos(phi)/(1 - sin(phi)), c {c / 1e6:g} MPa, phi {material['friction_angle']:g} deg")
    if model == "von_mises":
        return material["yield_stress"], 45.0, "von Mises yield stress"
    raise SystemExit(f"plot_compression.py: no theoretical peak for model '{model}'")


def band_fit(X, conn, u, eqps):
    """Plane through the most strained elements: (unit normal, centre, selected mask)."""
    corners = conn[:, :4]
    x = X + u
    cent = x[corners].mean(axis=1)
    k = max(20, int(0.05 * len(eqps)))
    sel = np.argsort(eqps)[-k:]
    w = eqps[sel]
    if not np.any(w > 0):
        return None, None, sel
    c = (cent[sel] * w[:, None]).sum(axis=0) / w.sum()
    d = cent[sel] - c
    cov = (d * w[:, None]).T @ d / w.sum()
    vals, vecs = np.linalg.eigh(cov)
    n = vecs[:, 0]
    if n[2] < 0:
        n = -n
    return n, c, sel


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out")
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--figures", default=None, help="folder for the PNGs (default OUT)")
    ap.add_argument("--window", type=float, default=1.2e-3, help="strain window of the peak")
    ap.add_argument("--no-plot", action="store_true")
    a = ap.parse_args()
    out = a.out
    scene = resolved_scene(out)
    body = next(b for b in scene["bodies"] if b["mesh"].get("generator") == "cylinder")
    R, L0 = body["mesh"]["radius"], body["mesh"]["length"]
    material = next(m for m in scene["materials"] if m["name"] == body["material"])
    sigma_th, angle_th, formula = theory(material)
    walls = scene.get("walls", [])
    bottom = next(w for w in walls if w["normal"][2] > 0.99)
    top = next(w for w in walls if w["normal"][2] < -0.99)

    h = femdem.read_history(out)
    A0 = math.pi * R * R
    force = 0.5 * (h[top["name"] + ".force_z"] - h[bottom["name"] + ".force_z"])
    stress = force / A0
    gap = h[top["name"] + ".position_z"] - h[bottom["name"] + ".position_z"]
    strain = 1.0 - gap / L0
    early = strain <= a.window
    i_peak = int(np.argmax(np.where(early, stress, -np.inf)))
    peak = float(stress[i_peak])
    res = {
        "model": material["model"], "theory_peak_pa": sigma_th, "peak_pa": peak,
        "peak_ratio": peak / sigma_th, "peak_strain": float(strain[i_peak]),
        "peak_time": float(h["time"][i_peak]), "window": a.window,
        "max_stress_pa": float(stress.max()), "max_stress_strain": float(strain[np.argmax(stress)]),
        "final_strain": float(strain[-1]), "final_stress_pa": float(stress[-1]),
        "wall_friction": [bottom.get("friction", 0.0), top.get("friction", 0.0)],
        "theory_band_angle_deg": angle_th,
    }

    with femdem.open_results(out) as f:
        X = f.coordinates
        conn = f.connectivity
        times = f.times
        last = len(times) - 1
        u = f.field("displacement", last)
        eqps = f.field("equivalent_plastic_strain", last)
    res["frame_time"] = float(times[last])
    res["frame_strain"] = float(np.interp(times[last], h["time"], strain))
    res["max_eqps"] = float(eqps.max())
    n, c, sel = band_fit(X, conn, u, eqps)
    if n is not None:
        res["band_angle_deg"] = float(math.degrees(math.acos(min(1.0, abs(n[2])))))
        res["band_centre"] = [float(v) for v in c]
        # spread of the selected elements about the plane, against their spread in it: a flat
        # band gives a small ratio, a cone or scattered plasticity a large one
        x = X + u
        d = x[conn[sel, :4]].mean(axis=1) - c
        res["band_thickness_ratio"] = float(np.std(d @ n) / np.sqrt(np.mean(
            np.sum((d - np.outer(d @ n, n)) ** 2, axis=1))))

    if not a.no_plot:
        figs = a.figures or out
        os.makedirs(figs, exist_ok=True)
        plot_curve(figs, strain, stress, sigma_th, formula, peak, i_peak, res)
        plot_band(figs, X, conn, u, eqps, n, c, angle_th, res, R)

    if a.json:
        print(json.dumps(res))
    else:
        print(f"theoretical peak {sigma_th / 1e6:.4f} MPa ({formula})")
        print(f"peak (strain <= {a.window:g}): {peak / 1e6:.4f} MPa = {100 * (peak / sigma_th - 1):+.2f} % "
              f"at strain {res['peak_strain']:.3g}")
        print(f"largest stress of the run {res['max_stress_pa'] / 1e6:.4f} MPa at strain "
              f"{res['max_stress_strain']:.4f}; final strain {res['final_strain']:.4f}, stress "
              f"{res['final_stress_pa'] / 1e6:.4f} MPa")
        if "band_angle_deg" in res:
            print(f"band (last frame, t = {1e3 * res['frame_time']:.3f} ms, strain "
                  f"{res['frame_strain']:.4f}, max eqps {res['max_eqps']:.4f}): fitted angle "
                  f"{res['band_angle_deg']:.1f} deg to the horizontal (theory {angle_th:g}), "
                  f"thickness ratio {res['band_thickness_ratio']:.2f}"
                  + (" (not a planar band: the fit means nothing)"
                     if res["band_thickness_ratio"] > 0.3 else ""))
        else:
            print("no plastic strain in the last frame")


def plot_curve(figs, strain, stress, sigma_th, formula, peak, i_peak, res):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, zoom in zip(axes, [False, True]):
        m = strain <= (1.2e-3 if zoom else np.inf)
        ax.plot(100 * strain[m], stress[m] / 1e6, "b-", lw=1.2, label="wall force / $\\pi R^2$")
        ax.axhline(sigma_th / 1e6, color="k", ls="--", lw=0.9,
                   label=f"theory {sigma_th / 1e6:.3f} MPa")
        ax.plot(100 * strain[i_peak], peak / 1e6, "ro", ms=5,
                label=f"peak {peak / 1e6:.3f} MPa ({100 * (peak / sigma_th - 1):+.2f} %)")
        ax.set_xlabel("axial strain [%]")
        ax.set_ylabel("axial stress [MPa]")
        ax.set_ylim(bottom=0)
        ax.grid(alpha=0.3)
        ax.set_title("first 0.12 % (thesis fig. 4.28)" if zoom else "whole run", fontsize=9)
        if zoom:
            legend_outside(ax)
    fr = res["wall_friction"]
    fig.suptitle(f"Unconfined compression, {res['model']} ({formula}), wall friction {fr[0]:g}",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(figs, "compression_curve.png"), dpi=120)
    plt.close(fig)


def plot_band(figs, X, conn, u, eqps, n, c, angle_th, res, R):
    x = X + u
    cent = x[conn[:, :4]].mean(axis=1)
    # the cut: the plane through the axis that contains the band's normal
    if n is not None and math.hypot(n[0], n[1]) > 1e-6:
        az = math.atan2(n[1], n[0])
    else:
        az = 0.0
    e_s = np.array([math.cos(az), math.sin(az), 0.0])
    e_q = np.array([-math.sin(az), math.cos(az), 0.0])
    axis_xy = np.array([x[:, 0].mean(), x[:, 1].mean(), 0.0])
    q = (cent - axis_xy) @ e_q
    # typical element edge: a regular tetrahedron of edge h has |det| = 6 V = h^3 / sqrt(2)
    det = np.linalg.det(np.stack([x[conn[:, i]] - x[conn[:, 0]] for i in (1, 2, 3)], axis=1))
    h = float(np.cbrt(math.sqrt(2) * np.mean(np.abs(det))))
    slab = np.abs(q) < 0.75 * h
    s = (cent[slab] - axis_xy) @ e_s
    z = cent[slab, 2]
    fig, ax = plt.subplots(figsize=(6, 8))
    tri = mtri.Triangulation(1e3 * s, 1e3 * z)
    # drop long triangles spanning outside the body
    pts = np.c_[tri.x, tri.y][tri.triangles]
    edge = np.max(np.linalg.norm(pts - np.roll(pts, 1, axis=1), axis=2), axis=1)
    tri.set_mask(edge > 2.5e3 * h)
    vmax = max(float(eqps.max()), 1e-12)
    cs = ax.tricontourf(tri, eqps[slab], levels=np.linspace(0, vmax, 21), cmap="inferno")
    fig.colorbar(cs, ax=ax, label="equivalent plastic strain", shrink=0.8)
    if n is not None:
        cs_ = (c - axis_xy) @ e_s
        for ang, style, label in [(res["band_angle_deg"], "c-", f"fit {res['band_angle_deg']:.1f}°"),
                                  (angle_th, "w--", f"45 + φ/2 = {angle_th:g}°")]:
            # the band's trace in the cut: it rises along +s when n_s < 0
            sign = -1.0 if (n @ e_s) > 0 else 1.0
            t = np.linspace(-1.2 * R, 1.2 * R, 2)
            ax.plot(1e3 * (cs_ + t), 1e3 * (c[2] + sign * t * math.tan(math.radians(ang))), style,
                    lw=1.5, label=label)
    ax.set_aspect("equal")
    ax.set_xlim(1e3 * s.min() - 2, 1e3 * s.max() + 2)
    ax.set_ylim(1e3 * z.min() - 2, 1e3 * z.max() + 2)
    ax.set_xlabel("distance from the axis in the cut [mm]")
    ax.set_ylabel("height [mm]")
    legend_outside(ax)
    ax.set_title(f"cut through the axis, t = {1e3 * res['frame_time']:.2f} ms, strain "
                 f"{100 * res['frame_strain']:.2f} %", fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(figs, "compression_band.png"), dpi=120)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
