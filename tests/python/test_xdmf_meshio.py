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


if __name__ == "__main__":
    sys.exit(unittest.main())
