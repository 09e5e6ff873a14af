# SPDX-License-Identifier: GPL-3.0-or-later
"""Tests of tools/python/femdem/plotting.py (units of scene keys, legends outside the curves,
flat signals drawn flat) and of the plot scripts' command lines that use it.

    /usr/bin/python3 -m unittest discover -s tests/python
"""
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "tools", "python"))
from femdem import plotting  # noqa: E402

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    plt = None

needs_matplotlib = unittest.skipIf(plt is None, "needs matplotlib")


class KeyUnitTest(unittest.TestCase):
    def test_units_of_scene_keys(self):
        # docs/SCENES.md: velocity m/s, youngs_modulus Pa, friction dimensionless
        self.assertEqual(plotting.key_unit("bodies.ball.velocity"), "m/s")
        self.assertEqual(plotting.key_unit("bodies.ball.velocity[2]"), "m/s")
        self.assertEqual(plotting.key_unit("materials.steel.youngs_modulus"), "Pa")
        self.assertEqual(plotting.key_unit("contact.friction"), "-")
        self.assertIsNone(plotting.key_unit("title"))

    def test_labels(self):
        self.assertEqual(plotting.key_label("simulation.end_time"), "simulation.end_time [s]")
        self.assertEqual(plotting.key_label("contact.friction"), "contact.friction [-]")
        self.assertEqual(plotting.key_label("title"), "title")


@needs_matplotlib
class AxesTest(unittest.TestCase):
    def tearDown(self):
        plt.close("all")

    def test_round_off_is_drawn_flat(self):
        fig, ax = plt.subplots()
        noise = [1e-19, -2e-19, 3e-19, 0.0]
        ax.plot(range(4), noise)
        self.assertTrue(plotting.draw_flat_flat(ax, [noise], scale=0.05))
        lo, hi = ax.get_ylim()
        # the axis spans 1e-3 of the 0.05 m scale: the 5e-19 m of round-off is 1e-14 of it
        self.assertAlmostEqual(hi - lo, 5e-5, delta=1e-12)
        self.assertLess(lo, -2e-19)
        self.assertGreater(hi, 3e-19)

    def test_a_real_signal_keeps_its_limits(self):
        fig, ax = plt.subplots()
        signal = [0.0, 1e-3, 4e-3, 2e-3]
        ax.plot(range(4), signal)
        before = ax.get_ylim()
        self.assertFalse(plotting.draw_flat_flat(ax, [signal], scale=0.05))
        self.assertEqual(ax.get_ylim(), before)

    def test_constant_signal_without_scale(self):
        fig, ax = plt.subplots()
        ax.plot(range(3), [2.0, 2.0, 2.0])
        self.assertTrue(plotting.draw_flat_flat(ax, [[2.0, 2.0, 2.0]]))
        lo, hi = ax.get_ylim()
        self.assertAlmostEqual(0.5 * (lo + hi), 2.0)
        self.assertAlmostEqual(hi - lo, 2e-3)

    def test_legend_is_outside_the_axes(self):
        fig, ax = plt.subplots()
        ax.plot([0, 1], [0, 1], label="a")
        legend = plotting.legend_outside(ax)
        fig.tight_layout()
        fig.canvas.draw()
        box = legend.get_window_extent()
        axes_box = ax.get_window_extent()
        self.assertGreaterEqual(box.x0, axes_box.x1)  # entirely to the right of the plot

    def test_no_legend_without_labels(self):
        fig, ax = plt.subplots()
        ax.plot([0, 1], [0, 1])
        self.assertIsNone(plotting.legend_outside(ax))


class PlotHistoryCommandLineTest(unittest.TestCase):
    SCRIPT = os.path.join(ROOT, "tools", "plot_history.py")

    def run_script(self, *args):
        return subprocess.run([sys.executable, self.SCRIPT, *args], capture_output=True,
                              text=True, cwd=tempfile.gettempdir())

    def test_help_exits_zero_with_usage(self):
        p = self.run_script("--help")
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertIn("usage: tools/plot_history.py OUT_DIR", p.stdout)

    def test_no_folder_is_a_usage_error(self):
        p = self.run_script()
        self.assertEqual(p.returncode, 2)
        self.assertIn("usage:", p.stderr)

    @needs_matplotlib
    def test_body_contact_gets_a_forces_plot(self):
        # two bodies touching each other and no wall: history.csv has their contact forces
        names = ["time", "dt", "kinetic_energy", "internal_energy", "plastic_dissipation",
                 "contact_energy", "contact_dissipation", "viscous_dissipation",
                 "mass_scaling_dissipation", "external_work", "total_energy",
                 "energy_balance_error"]
        for b in ("upper", "lower"):
            names += [b + s for s in (".com_x", ".com_y", ".com_z", ".vcom_x", ".vcom_y",
                                      ".vcom_z", ".kinetic_energy", ".contact_force_x",
                                      ".contact_force_y", ".contact_force_z",
                                      ".max_principal_stress")]
        names += ["contact.max_penetration", "contact.max_penetration_per_size"]
        rows = []
        for i in range(5):
            row = dict.fromkeys(names, 0.0)
            row["time"] = i * 1e-6
            row["upper.com_z"], row["lower.com_z"] = 0.1, -0.1
            row["upper.com_x"] = 1e-19 * (-1) ** i  # round-off
            row["upper.contact_force_z"] = 100.0 * i
            row["lower.contact_force_z"] = -100.0 * i
            rows.append(",".join(repr(row[n]) for n in names))
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(d, "history.csv"), "w") as f:
                f.write(",".join(names) + "\n" + "\n".join(rows) + "\n")
            p = self.run_script(d)
            self.assertEqual(p.returncode, 0, p.stderr)
            self.assertTrue(os.path.getsize(os.path.join(d, "forces.png")) > 0)


if __name__ == "__main__":
    unittest.main()
