# SPDX-License-Identifier: GPL-3.0-or-later
"""ParaView (Debian paraview, pvbatch under xvfb-run) opens a femdem run: the default reader,
both Xdmf3 readers and the legacy XDMF reader show every field of every frame with the values
of results.h5, walls.xdmf shows the walls, and the last frame renders to PNG (paraview_open_results.py does the ParaView
side). A long test (`tools/test --full`, `ctest -R Readers.ParaView`): it needs FEMDEM_EXE and
FEMDEM_PARAVIEW=1, which CTest sets; skipped otherwise.
"""
import json
import os
import shutil
import subprocess
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


@unittest.skipUnless(os.environ.get("FEMDEM_EXE") and os.environ.get("FEMDEM_PARAVIEW"),
                     "set FEMDEM_EXE and FEMDEM_PARAVIEW=1 (CTest's Readers.ParaView does)")
class ParaViewOpensARun(unittest.TestCase):
    def test_every_reader_shows_every_field(self):
        self.check_run("bar_vibration.toml", ["--set", "simulation.end_time=1.0"], walls=0)

    def test_walls_beside_the_bodies(self):
        self.check_run("closed_die_cube.toml", ["--set", "simulation.end_time=4e-5",
                                                "--set", "simulation.output_interval=1e-5"],
                       walls=6)

    def check_run(self, scene, options, walls):
        import h5py
        import numpy as np

        for tool in ("pvbatch", "xvfb-run"):
            self.assertIsNotNone(shutil.which(tool), f"{tool} missing: run tools/setup")
        with tempfile.TemporaryDirectory(prefix="femdem_paraview_") as tmp:
            out = os.path.join(tmp, "run")
            p = subprocess.run([os.environ["FEMDEM_EXE"], "run",
                                os.path.join(ROOT, "scenes", scene), "--out", out,
                                "--quiet", "--threads", "1"] + options,
                               capture_output=True, text=True, timeout=300)
            self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
            with h5py.File(os.path.join(out, "results.h5"), "r") as h5:
                fr = h5["frames"]

                def span(a):
                    a = a.reshape(a.shape[0], -1)[:, 0]  # first component, as GetRange(0)
                    return [float(a.min()), float(a.max())]

                expected = {
                    "times": [float(t) for t in fr["time"][()]],
                    "elements": int(h5["mesh/connectivity"].shape[0]),
                    "point": {n: span(fr[n][-1]) + [3] for n in ("displacement", "velocity")},
                    "cell": {n: span(fr[n][-1]) + [9 if n == "stress" else 1]
                             for n in ("stress", "von_mises", "pressure",
                                       "equivalent_plastic_strain")},
                }
                body = h5["mesh/element_body"][()].astype(float)
                expected["cell"]["body"] = [float(body.min()), float(body.max()), 1]
            self.assertGreater(np.abs(expected["point"]["displacement"]).max(), 0.0)
            self.assertEqual(os.path.exists(os.path.join(out, "walls.xdmf")), walls > 0)
            exp_path = os.path.join(tmp, "expected.json")
            with open(exp_path, "w") as f:
                json.dump(expected, f)
            png = os.path.join(tmp, "last_frame.png")
            extra = [os.path.join(out, "walls.xdmf"), str(walls)] if walls else []
            p = subprocess.run(["xvfb-run", "-a", "pvbatch",
                                os.path.join(HERE, "paraview_open_results.py"),
                                os.path.join(out, "results.xdmf"), exp_path, png] + extra,
                               capture_output=True, text=True, timeout=600)
            print(p.stdout)
            self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
            self.assertNotIn("FAILED", p.stdout, p.stderr)
            self.assertNotIn("Skipping unrecognized array type", p.stdout + p.stderr)
            self.assertGreater(os.path.getsize(png), 10000)


if __name__ == "__main__":
    unittest.main()
