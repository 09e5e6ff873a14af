# SPDX-License-Identifier: GPL-3.0-or-later
"""meshio (Debian python3-meshio), a reader femdem does not control, reads results.xdmf.

A short real run of scenes/bar_vibration.toml (FEMDEM_EXE, set by CTest) is read with meshio's
xdmf.TimeSeriesReader, the standard way to load an XDMF time series in Python: every frame, with
every field, must come back with the values results.h5 holds in /frames (read with h5py), the
quadratic tetrahedra kept. Run with the fast suite (`ctest -R Python.FemdemModule`).
(meshio.read, meshio's reader of one mesh, takes an XDMF file of one grid only: a time series is
read with TimeSeriesReader.)
"""
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

NODE_FIELDS = ("displacement", "velocity")
CELL_FIELDS = ("stress", "von_mises", "pressure", "equivalent_plastic_strain")


@unittest.skipUnless(os.environ.get("FEMDEM_EXE"), "set FEMDEM_EXE to a femdem program")
class MeshioReadsEveryFrame(unittest.TestCase):
    END_TIME = 1.0  # bar_vibration: output_interval 0.25, so 5 frames

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory(prefix="femdem_meshio_")
        cls.out = os.path.join(cls.tmp.name, "bar")
        p = subprocess.run([os.environ["FEMDEM_EXE"], "run",
                            os.path.join(ROOT, "scenes", "bar_vibration.toml"), "--out", cls.out,
                            "--quiet", "--threads", "1",
                            "--set", f"simulation.end_time={cls.END_TIME}"],
                           capture_output=True, text=True, timeout=300)
        if p.returncode != 0:
            raise RuntimeError(p.stdout + p.stderr)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_every_frame_and_field_equals_results_h5(self):
        import h5py
        import meshio  # a missing meshio fails here: tools/setup installs it
        import numpy as np

        with h5py.File(os.path.join(self.out, "results.h5"), "r") as h5:
            times = h5["frames/time"][()]
            frames = {name: h5["frames"][name][()] for name in NODE_FIELDS + CELL_FIELDS}
            coordinates = h5["mesh/coordinates"][()]
            connectivity = h5["mesh/connectivity"][()]
            element_body = h5["mesh/element_body"][()]
        self.assertEqual(len(times), 5)

        with meshio.xdmf.TimeSeriesReader(os.path.join(self.out, "results.xdmf")) as reader:
            points, cells = reader.read_points_cells()
            self.assertEqual(reader.num_steps, len(times))
            np.testing.assert_array_equal(points, coordinates)
            self.assertEqual(len(cells), 1)
            self.assertEqual(cells[0].type, "tetra10")
            np.testing.assert_array_equal(cells[0].data, connectivity)
            for k in range(reader.num_steps):
                t, point_data, cell_data = reader.read_data(k)
                self.assertEqual(t, times[k])
                self.assertEqual(sorted(point_data), sorted(NODE_FIELDS))
                self.assertEqual(sorted(cell_data), sorted(CELL_FIELDS + ("body",)))
                for name in NODE_FIELDS:
                    np.testing.assert_array_equal(point_data[name], frames[name][k], name)
                for name in CELL_FIELDS:
                    self.assertEqual(len(cell_data[name]), 1)
                    np.testing.assert_array_equal(cell_data[name][0], frames[name][k], name)
                np.testing.assert_array_equal(cell_data["body"][0], element_body)
            # the run moves: the last frame is not the first
            self.assertGreater(np.abs(frames["displacement"][-1]).max(), 0.0)


@unittest.skipUnless(os.environ.get("FEMDEM_EXE"), "set FEMDEM_EXE to a femdem program")
class MeshioReadsTheWalls(unittest.TestCase):
    """walls.xdmf of a short closed-die run (six walls, the punch moving): meshio's reading of
    each wall's quadrilateral and force equals what femdem's Python reader gives from results.h5
    (patch + displacement)."""

    def test_walls_xdmf_equals_results_h5(self):
        import meshio
        import numpy as np

        sys.path.insert(0, os.path.join(ROOT, "tools", "python"))
        import femdem

        with tempfile.TemporaryDirectory(prefix="femdem_meshio_walls_") as tmp:
            out = os.path.join(tmp, "die")
            p = subprocess.run([os.environ["FEMDEM_EXE"], "run",
                                os.path.join(ROOT, "scenes", "closed_die_cube.toml"), "--out",
                                out, "--quiet", "--threads", "1",
                                "--set", "simulation.end_time=4e-5",
                                "--set", "simulation.output_interval=1e-5"],
                               capture_output=True, text=True, timeout=300)
            self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
            with femdem.Results(out) as r, \
                    meshio.xdmf.TimeSeriesReader(os.path.join(out, "walls.xdmf")) as reader:
                self.assertEqual(len(r.wall_names), 6)
                points, cells = reader.read_points_cells()
                self.assertEqual(cells[0].type, "quad")
                self.assertEqual(len(cells[0].data), 6)
                self.assertEqual(reader.num_steps, r.frame_count)
                moved = 0.0
                for k in range(reader.num_steps):
                    t, point_data, cell_data = reader.read_data(k)
                    self.assertEqual(t, r.times[k])
                    np.testing.assert_array_equal(cell_data["force"][0], r.wall_force(k))
                    np.testing.assert_array_equal(cell_data["wall"][0], np.arange(6))
                    moved = max(moved, float(np.abs(r.wall_patch(k) - r.wall_patch(0)).max()))
                # meshio gives the first frame's geometry (its mesh grid): the walls at t = 0
                np.testing.assert_array_equal(points, r.wall_patch(0).reshape(-1, 3))
                self.assertGreater(moved, 0.0)  # the punch moves
                # the punch presses the cube: equal and opposite forces on punch and floor
                self.assertGreater(np.abs(r.wall_force(-1)).max(), 0.0)


@unittest.skipUnless(os.environ.get("FEMDEM_EXE"), "set FEMDEM_EXE to a femdem program")
class OptionalFieldsReadAndMeanWhatTheySay(unittest.TestCase):
    """`[output] fields` with every optional field, on the closed die (a cube confined on five
    sides and pressed by a punch: its stress is uniform): meshio reads each field of every frame
    as results.h5 has it, and the contact pressure on the faces equals the stress normal to them
    (the interior nodes of the top and of a side face within 1 % of -sigma_zz and -sigma_xx),
    the nodal stress the element stress, the body velocity the mass-weighted mean velocity."""

    FIELDS = ("log_strain", "nodal_stress", "contact_force", "contact_pressure",
              "body_velocity", "node_body")

    def test_fields(self):
        import h5py
        import meshio
        import numpy as np

        with tempfile.TemporaryDirectory(prefix="femdem_fields_") as tmp:
            out = os.path.join(tmp, "die")
            fields = "[" + ",".join(f'"{f}"' for f in self.FIELDS) + "]"
            p = subprocess.run([os.environ["FEMDEM_EXE"], "run",
                                os.path.join(ROOT, "scenes", "closed_die_cube.toml"), "--out",
                                out, "--quiet", "--threads", "1",
                                "--set", "simulation.end_time=4e-5",
                                "--set", "simulation.output_interval=1e-5",
                                "--set", f"output.fields={fields}"],
                               capture_output=True, text=True, timeout=300)
            self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
            with h5py.File(os.path.join(out, "results.h5"), "r") as h5:
                fr = {n: h5["frames"][n][()] for n in h5["frames"]}
                X = h5["mesh/coordinates"][()]
                node_body = h5["mesh/node_body"][()]
            with meshio.xdmf.TimeSeriesReader(os.path.join(out, "results.xdmf")) as reader:
                reader.read_points_cells()
                for k in range(reader.num_steps):
                    _, point_data, cell_data = reader.read_data(k)
                    np.testing.assert_array_equal(cell_data["log_strain"][0], fr["log_strain"][k])
                    for name in ("nodal_stress", "contact_force", "contact_pressure",
                                 "body_velocity"):
                        np.testing.assert_array_equal(point_data[name], fr[name][k], name)
                    np.testing.assert_array_equal(point_data["node_body"], node_body)
            stress = fr["stress"][-1]
            self.assertLess(np.ptp(stress[:, 8]), 0.02 * abs(stress[:, 8].mean()))  # near uniform
            lo, hi = X.min(0), X.max(0)

            def face_interior(axis, value):
                on = np.abs(X[:, axis] - value) < 1e-9
                for a in range(3):
                    if a != axis:
                        on &= (np.abs(X[:, a] - lo[a]) > 1e-9) & (np.abs(X[:, a] - hi[a]) > 1e-9)
                return on

            p = fr["contact_pressure"][-1]
            for axis, component in ((2, 8), (0, 0)):
                nodes = face_interior(axis, hi[axis])
                expected = -stress[:, component].mean()
                self.assertGreater(expected, 0.0)
                print(f"contact_pressure on the interior of face {'zx'[axis == 0]}+: "
                      f"{p[nodes].min() / 1e6:.2f}-{p[nodes].max() / 1e6:.2f} MPa, "
                      f"-stress: {expected / 1e6:.2f} MPa")
                np.testing.assert_allclose(p[nodes], expected, rtol=0.01)
            np.testing.assert_allclose(fr["nodal_stress"][-1][:, 8], stress[:, 8].mean(),
                                       rtol=0.02)
            # a compressed cube: log strain zz negative, and the punch's force reaches the nodes
            self.assertLess(fr["log_strain"][-1][:, 8].max(), 0.0)
            self.assertGreater(np.abs(fr["contact_force"][-1]).max(), 0.0)
            self.assertEqual(len(np.unique(fr["body_velocity"][-1], axis=0)), 1)  # one body


if __name__ == "__main__":
    sys.exit(unittest.main())
