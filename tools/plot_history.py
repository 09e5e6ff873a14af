#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Plots a femdem run's history.csv: energies, body centres of mass, contact forces.

usage: tools/plot_history.py OUT_DIR     (writes OUT_DIR/energy.png, com.png, forces.png)
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "python"))
import femdem  # noqa: E402  (tools/python/femdem)
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        return 2
    out = sys.argv[1]
    h = femdem.read_history(os.path.join(out, "history.csv"))
    t = h["time"]
    written = []

    fig, ax = plt.subplots(figsize=(8, 5))
    for key, label in [("kinetic_energy", "kinetic"), ("internal_energy", "elastic (stored)"),
                       ("plastic_dissipation", "plastic dissipation"),
                       ("contact_energy", "contact"), ("external_work", "external work"),
                       ("total_energy", "balance: kin + el + pl + contact - ext")]:
        if key in h and any(v != 0.0 for v in h[key]):
            ax.plot(t, h[key], label=label, lw=2 if key == "total_energy" else 1)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("energy [J]")
    ax.set_title("Energies")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "energy.png"), dpi=120)
    written.append("energy.png")
    plt.close(fig)

    bodies = sorted(femdem.body_names(h))
    fig, axes = plt.subplots(1, 3, figsize=(13, 4))
    for i, c in enumerate("xyz"):
        for b in bodies:
            axes[i].plot(t, h[f"{b}.com_{c}"], label=b)
        axes[i].set_xlabel("time [s]")
        axes[i].set_ylabel(f"centre of mass {c} [m]")
        axes[i].grid(alpha=0.3)
    axes[0].legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "com.png"), dpi=120)
    written.append("com.png")
    plt.close(fig)

    walls = sorted(femdem.wall_names(h))
    if walls:
        fig, ax = plt.subplots(figsize=(8, 5))
        for w in walls:
            for c in "xyz":
                series = h[f"{w}.force_{c}"]
                if any(v != 0.0 for v in series):
                    ax.plot(t, series, label=f"{w} {c}")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("force on wall [N]")
        ax.grid(alpha=0.3)
        ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(out, "forces.png"), dpi=120)
        written.append("forces.png")
        plt.close(fig)
    print("plots: " + ", ".join(os.path.join(out, w) for w in written))
    return 0


if __name__ == "__main__":
    sys.exit(main())
