#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Plots a femdem run's history.csv: energies, body centres of mass, contact forces.

usage: tools/plot_history.py OUT_DIR     (writes OUT_DIR/energy.png, com.png, forces.png)

forces.png has the force on each wall that was touched and the total contact force on each
body that was touched (walls and other bodies); it is not written when nothing touched.
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "python"))
import femdem  # noqa: E402  (tools/python/femdem)
from femdem.plotting import draw_flat_flat, legend_outside  # noqa: E402


def nonzero(series):
    return any(v != 0.0 for v in series)


def main():
    args = sys.argv[1:]
    if args in (["-h"], ["--help"]):
        print(__doc__)
        return 0
    if len(args) != 1 or args[0].startswith("-"):
        print(__doc__, file=sys.stderr)
        return 2
    out = args[0]
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    h = femdem.read_history(os.path.join(out, "history.csv"))
    t = h["time"]
    written = []

    fig, ax = plt.subplots(figsize=(9, 5))
    for key, label in [("kinetic_energy", "kinetic"), ("internal_energy", "elastic (stored)"),
                       ("plastic_dissipation", "plastic dissipation"),
                       ("contact_energy", "contact"),
                       ("contact_dissipation", "contact friction dissipation"),
                       ("viscous_dissipation", "damping dissipation"),
                       ("mass_scaling_dissipation", "mass-scaling dissipation"),
                       ("external_work", "external work"),
                       ("total_energy", "balance: kin + el + dissipated + contact - ext")]:
        if key in h and nonzero(h[key]):
            ax.plot(t, h[key], label=label, lw=2 if key == "total_energy" else 1)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("energy [J]")
    ax.set_title("Energies")
    ax.grid(alpha=0.3)
    legend_outside(ax)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "energy.png"), dpi=120)
    written.append("energy.png")
    plt.close(fig)

    # One length scale for the three panels: the extent of the motion and of the positions, so
    # that a component that only carries round-off (1e-19 m) is drawn flat at its value.
    bodies = sorted(femdem.body_names(h))
    coms = {(b, c): h[f"{b}.com_{c}"] for b in bodies for c in "xyz"}
    scale = max((max(abs(float(v)) for v in s) for s in coms.values() if len(s)), default=0.0)
    scale = max(scale, max((float(s.max() - s.min()) for s in coms.values() if len(s)),
                           default=0.0))
    fig, axes = plt.subplots(1, 3, figsize=(14, 4))
    for i, c in enumerate("xyz"):
        for b in bodies:
            axes[i].plot(t, coms[(b, c)], label=b)
        draw_flat_flat(axes[i], [coms[(b, c)] for b in bodies], scale if scale > 0 else None)
        axes[i].set_xlabel("time [s]")
        axes[i].set_ylabel(f"centre of mass {c} [m]")
        axes[i].grid(alpha=0.3)
    legend_outside(axes[2])
    fig.tight_layout()
    fig.savefig(os.path.join(out, "com.png"), dpi=120)
    written.append("com.png")
    plt.close(fig)

    wall_series = [(f"{w} {c}", h[f"{w}.force_{c}"]) for w in sorted(femdem.wall_names(h))
                   for c in "xyz" if nonzero(h[f"{w}.force_{c}"])]
    body_series = [(f"{b} {c}", h[f"{b}.contact_force_{c}"]) for b in bodies for c in "xyz"
                   if f"{b}.contact_force_{c}" in h and nonzero(h[f"{b}.contact_force_{c}"])]
    panels = [(title, series) for title, series in
              [("force on the wall [N]", wall_series),
               ("contact force on the body [N]", body_series)] if series]
    if panels:
        fig, axes = plt.subplots(1, len(panels), figsize=(7 * len(panels) + 2, 4.5),
                                 squeeze=False)
        for ax, (ylabel, series) in zip(axes[0], panels):
            for label, s in series:
                ax.plot(t, s, label=label)
            ax.set_xlabel("time [s]")
            ax.set_ylabel(ylabel)
            ax.grid(alpha=0.3)
            legend_outside(ax)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "forces.png"), dpi=120)
        written.append("forces.png")
        plt.close(fig)
    print("plots: " + ", ".join(os.path.join(out, w) for w in written))
    return 0


if __name__ == "__main__":
    sys.exit(main())
