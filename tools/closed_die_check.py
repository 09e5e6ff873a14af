#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Compares a closed-die (uniaxial-strain) run of a von Mises body with the analytic answer.

usage: tools/closed_die_check.py OUT_DIR E NU SIGMA_Y H [FIGURE.png]

In a filled frictionless die every point is in uniaxial strain: principal log strains
(e, 0, 0) with e = ln(h / h0) from the punch-bottom gap. femdem's elasticity is Hencky's
(Kirchhoff stress linear in the log strain) and its von Mises return is the small-strain one in
principal log strains, so the exact answer is the 1-D return mapping below, driven along the
run's own strain path (loading and unloading), with
  tau_a = lambda e + 2 G (e - e_pa),  tau_r = lambda e + G e_pa   (compression positive),
  q = tau_a - tau_r = 2 G e - 3 G e_pa,  yield |q| = sigma_y + H eps_p,
and Cauchy = tau / J, J = h / h0. Elastic slope K + 4G/3 = lambda + 2G; first yield at
e = sigma_y / (2G), axial stress sigma_y (1 - nu) / (1 - 2 nu); then slope
K + (4/3) G H / (3G + H).
Prints the errors at first yield, at the peak, and the residual die-wall pressure after
unloading; writes the figure if asked.
"""
import math
import os
import sys


sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "python"))
import femdem  # noqa: E402  (tools/python/femdem)
from femdem.plotting import legend_outside  # noqa: E402


def analytic(strain, E, nu, sy, H):
    """Axial and radial Cauchy stress (compression positive) along a path of axial log
    strains (compression positive)."""
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    G = E / (2 * (1 + nu))
    e_pa, eps_p = 0.0, 0.0
    axial, radial = [], []
    for e in strain:
        q = 2 * G * e - 3 * G * e_pa
        f = abs(q) - (sy + H * eps_p)
        if f > 0:
            dg = f / (3 * G + H)
            e_pa += math.copysign(dg, q)
            eps_p += dg
        J = math.exp(-e)
        axial.append((lam * e + 2 * G * (e - e_pa)) / J)
        radial.append((lam * e + G * e_pa) / J)
    return axial, radial


def main():
    if len(sys.argv) not in (6, 7):
        print(__doc__)
        return 2
    out = sys.argv[1]
    E, nu, sy, H = (float(a) for a in sys.argv[2:6])
    h = femdem.read_history(out + "/history.csv")
    height = h["compaction.height"]
    strain = [-math.log(x / height[0]) for x in height]
    P = h["compaction.punch_pressure"]
    R = h["compaction.radial_pressure"]
    A, Rr = analytic(strain, E, nu, sy, H)
    G = E / (2 * (1 + nu))
    e_y = sy / (2 * G)
    # first yield, the peak, and after unloading (punch off)
    i_y = min(range(len(strain)), key=lambda i: abs(strain[i] - e_y))
    i_pk = max(range(len(P)), key=lambda i: P[i])
    i_un = next((i for i in range(i_pk, len(P)) if P[i] == 0.0), len(P) - 1)
    K = E / (3 * (1 - 2 * nu))
    print(f"elastic slope K + 4G/3 = {(K + 4 * G / 3) / 1e9:.4g} GPa; yield at e = {e_y:.5g}, "
          f"axial {sy * (1 - nu) / (1 - 2 * nu) / 1e6:.4g} MPa; plastic slope "
          f"{(K + 4 / 3 * G * H / (3 * G + H)) / 1e9:.4g} GPa")
    for name, i in (("first yield", i_y), ("peak", i_pk)):
        print(f"{name}: e = {strain[i]:.5f}; punch pressure {P[i] / 1e6:.4f} MPa, analytic "
              f"{A[i] / 1e6:.4f} MPa ({100 * (P[i] / A[i] - 1):+.2f} %); die-wall pressure "
              f"{R[i] / 1e6:.4f} MPa, analytic {Rr[i] / 1e6:.4f} MPa "
              f"({100 * (R[i] / Rr[i] - 1):+.2f} %)")
    # the elastic slope from the first quarter of the elastic range, the plastic one between
    # twice the yield strain and 90 % of the peak strain
    def slope(lo, hi):
        idx = [i for i in range(i_pk + 1) if lo <= strain[i] <= hi]
        xs = [strain[i] for i in idx]
        ys = [P[i] * math.exp(-strain[i]) for i in idx]  # Kirchhoff: tau = P J
        n = len(xs)
        mx, my = sum(xs) / n, sum(ys) / n
        return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    s_el = slope(0.25 * e_y, 0.75 * e_y)
    s_pl = slope(2 * e_y, 0.9 * strain[i_pk])
    print(f"measured slopes (Kirchhoff): elastic {s_el / 1e9:.4g} GPa "
          f"({100 * (s_el / (K + 4 * G / 3) - 1):+.2f} %), plastic {s_pl / 1e9:.4g} GPa "
          f"({100 * (s_pl / (K + 4 / 3 * G * H / (3 * G + H)) - 1):+.2f} %)")
    print(f"after unloading (t = {h['time'][i_un] * 1e3:.4f} ms, e = {strain[i_un]:.5f}): "
          f"residual die-wall pressure {R[i_un] / 1e6:.4f} MPa, analytic {Rr[i_un] / 1e6:.4f} MPa "
          f"({100 * (R[i_un] / Rr[i_un] - 1):+.2f} %)")
    print(f"solid volume ratio at the peak {h['compaction.volume_ratio'][i_pk]:.6f}, h/h0 "
          f"{height[i_pk] / height[0]:.6f}; relative density {h['compaction.relative_density'][i_pk]:.6f}")
    if len(sys.argv) == 7:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(7, 5))
        ax.plot([100 * e for e in strain], [p / 1e6 for p in P], lw=2.5, alpha=0.6,
                label="femdem: punch pressure")
        ax.plot([100 * e for e in strain], [a / 1e6 for a in A], "k--", lw=1,
                label="analytic: axial stress")
        ax.plot([100 * e for e in strain], [r / 1e6 for r in R], lw=2.5, alpha=0.6,
                label="femdem: die-wall pressure")
        ax.plot([100 * e for e in strain], [r / 1e6 for r in Rr], "k:", lw=1,
                label="analytic: radial stress")
        ax.set_xlabel("axial log strain ln(h0 / h) [%]")
        ax.set_ylabel("stress [MPa]")
        ax.set_title("Closed-die compression of a von Mises cube")
        ax.grid(alpha=0.3)
        legend_outside(ax)
        fig.tight_layout()
        fig.savefig(sys.argv[6], dpi=120)
        print("wrote " + sys.argv[6])
    return 0


if __name__ == "__main__":
    sys.exit(main())
