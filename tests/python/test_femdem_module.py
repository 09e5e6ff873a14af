# SPDX-License-Identifier: GPL-3.0-or-later
"""Tests of tools/python/femdem, the Python reader of femdem's outputs (docs/OUTPUTS.md).

From the repository's root:
    /usr/bin/python3 -m unittest discover -s tests/python
    /usr/bin/python3 tests/python/test_femdem_module.py
With FEMDEM_EXE=/path/to/femdem the tests also run scenes/bar_vibration.toml (shortened) and
check that its history.csv, summary.json and results.h5 read back consistently.

The synthetic files are written as femdem writes them: history.csv row by row, results.h5 with
the groups, datasets, types, chunks and attributes of femdem's results writer (ResultsWriter),
in SWMR mode, the frame's fields before its time.
"""
import json
import math
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "tools", "python"))
import femdem  # noqa: E402  (tools/python/femdem)

try:
    import h5py
    import numpy as np
except ImportError:  # the tests that need them are skipped
    h5py = np = None

needs_h5 = unittest.skipIf(h5py is None, "needs numpy and h5py")


# ---------------------------------------------------------------------------------------------
# history.csv

def history_columns(bodies, walls, contact=False, compaction=False):
    """The column names femdem writes (the standard columns, then the optional ones)."""
    cols = list(femdem.history.GLOBAL_COLUMNS)
    for b in bodies:
        cols += [b + s for s in femdem.history.BODY_SUFFIXES]
    for w in walls:
        cols += [w + s for s in femdem.history.WALL_SUFFIXES]
    if contact:
        cols += ["contact.max_penetration", "contact.max_penetration_per_size"]
    if compaction:
        cols += ["compaction." + s for s in (
            "punch_displacement", "punch_force", "punch_pressure", "bottom_force",
            "die_normal_force", "die_axial_force", "radial_pressure", "height", "solid_volume",
            "relative_density", "volume_ratio", "column_strain")]
    return cols


def write_text(path, text):
    with open(path, "w", newline="") as f:
        f.write(text)


def history_text(cols, rows):
    """history.csv as femdem writes it: shortest round-trip numbers, `nan`, one line per row."""
    def num(v):
        if math.isnan(v):
            return "nan"
        return str(int(v)) if v == int(v) and abs(v) < 1e15 else repr(v)
    lines = [",".join(cols)] + [",".join(num(v) for v in r) for r in rows]
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------------------------------------
# results.h5, as femdem's results writer lays it out

FIELDS = [("displacement", True, 3), ("velocity", True, 3), ("stress", False, 9),
          ("von_mises", False, 1), ("pressure", False, 1), ("equivalent_plastic_strain", False, 1)]


def _string_type(size):
    t = h5py.h5t.C_S1.copy()
    t.set_size(max(1, size))
    t.set_strpad(h5py.h5t.STR_NULLTERM)
    t.set_cset(h5py.h5t.CSET_UTF8)
    return t


def _string_attribute(obj, name, value):
    data = value.encode("utf-8") or b"\0"
    t = _string_type(len(data))
    space = h5py.h5s.create(h5py.h5s.SCALAR)
    attr = h5py.h5a.create(obj.id, name.encode(), t, space)
    attr.write(np.array(data, dtype=f"S{len(data)}"), mtype=t)


class ResultsFile:
    """Writes a results.h5 like femdem: mesh, SWMR, frames (fields first, then the time)."""

    def __init__(self, path, mesh):
        self.path = path
        f = self.file = h5py.File(path, "w", libver=("latest", "latest"))
        f.attrs.create("complete", 0, dtype="<i4")
        f.attrs.create("format_version", 1, dtype="<i4")
        _string_attribute(f, "format", "femdem-results")
        g = f.create_group("mesh")
        g.create_dataset("coordinates", data=mesh["coordinates"], dtype="<f8")
        g.create_dataset("connectivity", data=mesh["connectivity"], dtype="<i4")
        g.create_dataset("node_body", data=mesh["node_body"], dtype="<i4")
        g.create_dataset("element_body", data=mesh["element_body"], dtype="<i4")
        names = [n.encode("utf-8") for n in mesh["body_names"]]
        width = max([1] + [len(n) + 1 for n in names])
        t = _string_type(width)
        space = h5py.h5s.create_simple((len(names),))
        d = h5py.h5d.create(g.id, b"body_names", t, space)
        d.write(h5py.h5s.ALL, h5py.h5s.ALL, np.array(names, dtype=f"S{width}"), mtype=t)
        fr = f.create_group("frames")
        self.time = fr.create_dataset("time", shape=(0,), maxshape=(None,), chunks=(1024,),
                                      dtype="<f8")
        self.nodes, self.elements = len(mesh["coordinates"]), len(mesh["connectivity"])
        self.fields = []
        for name, node, comps in FIELDS:
            rows = self.nodes if node else self.elements
            shape = (0, rows, comps) if comps > 1 else (0, rows)
            chunk_rows = min(max((1 << 20) // (comps * 8), 1), rows)
            chunks = (1, chunk_rows, comps) if comps > 1 else (1, chunk_rows)
            dcpl = h5py.h5p.create(h5py.h5p.DATASET_CREATE)
            dcpl.set_chunk(chunks)
            dcpl.set_fill_time(h5py.h5d.FILL_TIME_NEVER)
            space = h5py.h5s.create_simple(shape, (h5py.h5s.UNLIMITED,) + shape[1:])
            dset = h5py.Dataset(h5py.h5d.create(fr.id, name.encode(), h5py.h5t.IEEE_F64LE, space,
                                                dcpl=dcpl))
            self.fields.append((name, dset))
        _string_attribute(fr["stress"], "components", "xx xy xz yx yy yz zx zy zz")
        f.swmr_mode = True
        self.frames = 0

    def write_fields(self, values):
        """Appends one frame's fields (the frame is not counted until write_time)."""
        for name, dset in self.fields:
            dset.resize(self.frames + 1, axis=0)
            dset[self.frames] = values[name]
        self.file.flush()

    def write_time(self, time):
        self.time.resize((self.frames + 1,))
        self.time[self.frames] = time
        self.file.flush()
        self.frames += 1

    def write_frame(self, time, values):
        self.write_fields(values)
        self.write_time(time)

    def close(self, complete=True):
        self.file.close()
        if complete:
            with h5py.File(self.path, "r+") as f:
                f.attrs.modify("complete", 1)


def two_body_mesh():
    """Two TET10 elements (two bodies) with their 20 nodes (not shared)."""
    corners = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    edges = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]
    tet = np.vstack([corners] + [0.5 * (corners[i] + corners[j]) for i, j in edges])
    coordinates = np.vstack([tet, tet + [2.0, 0.0, 0.0]])
    return {"coordinates": coordinates,
            "connectivity": np.arange(20, dtype=np.int32).reshape(2, 10),
            "node_body": np.repeat(np.arange(2, dtype=np.int32), 10),
            "element_body": np.arange(2, dtype=np.int32),
            "body_names": ["ball", "prism_é"]}


def frame_values(k, nodes=20, elements=2):
    """Distinct values for frame k."""
    return {"displacement": 1e-3 * k + np.arange(3 * nodes).reshape(nodes, 3),
            "velocity": -1.0 * k - np.arange(3 * nodes).reshape(nodes, 3),
            "stress": 1e6 * k + np.arange(9 * elements, dtype=float).reshape(elements, 9),
            "von_mises": 2e6 * k + np.arange(elements, dtype=float),
            "pressure": -3e6 * k + np.arange(elements, dtype=float),
            "equivalent_plastic_strain": 0.01 * k + np.arange(elements, dtype=float)}


def write_killed_results(path, frames):
    """Run in a child process: writes `frames` frames and half of the next (its fields, not its
    time), then kills itself as SIGKILL would kill femdem, the file still open."""
    w = ResultsFile(path, two_body_mesh())
    for k in range(int(frames)):
        w.write_frame(0.5 * k, frame_values(k))
    w.write_fields(frame_values(99))
    os.kill(os.getpid(), signal.SIGKILL)


def write_live_results(path):
    """Run in a child process: a run still going. Writes two frames, says so on stdout, then one
    more frame for every line read from stdin; closes (complete) at end of input."""
    w = ResultsFile(path, two_body_mesh())
    for k in range(2):
        w.write_frame(0.5 * k, frame_values(k))
    print("frames 2", flush=True)
    for _ in sys.stdin:
        k = w.frames
        w.write_frame(0.5 * k, frame_values(k))
        print(f"frames {w.frames}", flush=True)
    w.close(complete=True)


def child(function, *args):
    """The command that runs one of the functions above in a fresh python."""
    code = (f"import sys; sys.path.insert(0, {HERE!r}); import test_femdem_module as t; "
            f"t.{function}(*sys.argv[1:])")
    return [sys.executable, "-c", code] + [str(a) for a in args]


class TempDir(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="femdem_test_")
        self.addCleanup(shutil.rmtree, self.dir, True)

    def path(self, *names):
        return os.path.join(self.dir, *names)


# ---------------------------------------------------------------------------------------------

@unittest.skipIf(np is None, "needs numpy")
class HistoryTest(TempDir):
    COLS = history_columns(["ball", "prism"], ["floor", "punch"], contact=True, compaction=True)

    def rows(self, n):
        return [[0.1 * i + j for j in range(len(self.COLS))] for i in range(n)]

    def test_values_and_order(self):
        rows = self.rows(5)
        rows[2][3] = float("nan")
        rows[3][4] = 1.0000000000000002e-300
        rows[4][5] = -2.5e-7
        write_text(self.path("history.csv"), history_text(self.COLS, rows))
        for source in (self.dir, self.path("history.csv")):
            h = femdem.read_history(source)
            self.assertEqual(list(h), self.COLS)
            for j, name in enumerate(self.COLS):
                self.assertIsInstance(h[name], np.ndarray)
                self.assertEqual(h[name].dtype, np.float64)
                self.assertEqual(len(h[name]), 5)
                for i in range(5):
                    v = rows[i][j]
                    if math.isnan(v):
                        self.assertTrue(math.isnan(h[name][i]))
                    else:
                        self.assertEqual(h[name][i], v, (name, i))
        self.assertEqual(h["time"].tolist(), [0.1 * i for i in range(5)])

    def test_torn_last_line_is_dropped(self):
        text = history_text(self.COLS, self.rows(4))
        torn = text[: text.rfind("\n", 0, len(text) - 1) + 1] + "0.3,0.00"  # row 4 cut short
        write_text(self.path("history.csv"), torn)
        h = femdem.read_history(self.dir)
        self.assertEqual(h["time"].tolist(), [0.0, 0.1, 0.2])
        # cut inside a number of its last field: the row has all its fields but is still dropped
        write_text(self.path("history.csv"), text[:-3])
        h = femdem.read_history(self.dir)
        self.assertEqual(len(h["time"]), 3)
        self.assertEqual(len(h["contact.max_penetration"]), 3)

    def test_rows_with_wrong_field_count_are_dropped(self):
        lines = history_text(self.COLS, self.rows(4)).splitlines()
        lines[2] = lines[2] + ",7"  # one field too many
        lines[3] = lines[3].rsplit(",", 1)[0]  # one too few
        write_text(self.path("history.csv"), "\n".join(lines) + "\n")
        h = femdem.read_history(self.dir)
        self.assertEqual(h["time"].tolist(), [0.0, 0.30000000000000004])

    def test_column_line_only_and_empty_file(self):
        write_text(self.path("history.csv"), ",".join(self.COLS) + "\n")
        h = femdem.read_history(self.dir)
        self.assertEqual(list(h), self.COLS)
        self.assertTrue(all(len(v) == 0 for v in h.values()))
        write_text(self.path("history.csv"), "")
        with self.assertRaises(ValueError):
            femdem.read_history(self.dir)
        with self.assertRaises(FileNotFoundError):
            femdem.read_history(self.path("nothing"))

    def test_column_helpers(self):
        self.assertEqual(femdem.body_names(self.COLS), ["ball", "prism"])
        self.assertEqual(femdem.wall_names(self.COLS), ["floor", "punch"])
        self.assertTrue(femdem.has_compaction(self.COLS))
        self.assertTrue(femdem.has_penetration(self.COLS))
        plain = history_columns(["bar"], [])
        self.assertEqual(femdem.body_names(plain), ["bar"])
        self.assertEqual(femdem.wall_names(plain), [])
        self.assertFalse(femdem.has_compaction(plain))
        self.assertFalse(femdem.has_penetration(plain))
        # names with dots, and a wall named like a body's column
        odd = history_columns(["v.cross", "contact"], ["die.wall_1"])
        self.assertEqual(femdem.body_names(odd), ["v.cross", "contact"])
        self.assertEqual(femdem.wall_names(odd), ["die.wall_1"])
        # the helpers take the history itself too
        write_text(self.path("history.csv"), history_text(self.COLS, self.rows(2)))
        h = femdem.read_history(self.dir)
        self.assertEqual(femdem.body_names(h), ["ball", "prism"])
        self.assertEqual(femdem.wall_names(h), ["floor", "punch"])


class SummaryTest(TempDir):
    def test_read_back(self):
        s = {"scene": "scenes/x.toml", "status": "completed", "end_time": 8e-05, "steps": 2345,
             "nodes": 35, "elements": 2, "energy": {"kinetic": 1.5},
             "bodies": {"ball": {"com": [0, 0, 1.25], "coefficient_of_restitution": None}},
             "extra": {"loop_time_s": 12.0}}
        write_text(self.path("summary.json"), json.dumps(s, indent=2))
        self.assertEqual(femdem.read_summary(self.dir), s)
        self.assertEqual(femdem.read_summary(self.path("summary.json")), s)

    def test_missing(self):
        with self.assertRaises(FileNotFoundError):
            femdem.read_summary(self.dir)


class SweepTest(TempDir):
    def test_read_back(self):
        text = ('bodies.ball.velocity,contact.penalty_factor,run,exit_code,status,end_time,'
                'bodies.ball.coefficient_of_restitution.com\n'
                '"[0,0,-1]",10,"velocity=0,0,-1__penalty_factor=10",0,completed,0.0001,0.75\n'
                '"[0,0,-2]",10,"velocity=0,0,-2__penalty_factor=10",1,failed,,\n'
                '"[0,0,-5]",10,short\n')
        write_text(self.path("sweep.csv"), text)
        rows = femdem.read_sweep(self.dir)
        self.assertEqual(len(rows), 2)  # the short row is dropped
        self.assertEqual(rows[0]["bodies.ball.velocity"], "[0,0,-1]")
        self.assertEqual(rows[0]["run"], "velocity=0,0,-1__penalty_factor=10")
        self.assertEqual(rows[0]["bodies.ball.coefficient_of_restitution.com"], "0.75")
        self.assertEqual(rows[1]["status"], "failed")
        self.assertEqual(rows[1]["end_time"], "")
        self.assertEqual(list(rows[0])[:3], ["bodies.ball.velocity", "contact.penalty_factor",
                                             "run"])
        self.assertEqual(femdem.varied_keys(rows[0]),
                         ["bodies.ball.velocity", "contact.penalty_factor"])
        write_text(self.path("sweep.csv"), text.split("\n")[0] + "\n")
        self.assertEqual(femdem.read_sweep(self.path("sweep.csv")), [])
        write_text(self.path("sweep.csv"), "")
        self.assertEqual(femdem.read_sweep(self.dir), [])


@needs_h5
class ResultsTest(TempDir):
    def write_complete(self, frames=3):
        w = ResultsFile(self.path("results.h5"), two_body_mesh())
        for k in range(frames):
            w.write_frame(0.5 * k, frame_values(k))
        w.close(complete=True)

    def check_frames(self, r, frames):
        self.assertEqual(r.frame_count, frames)
        self.assertEqual(len(r), frames)
        self.assertEqual(r.times.tolist(), [0.5 * k for k in range(frames)])
        for k in range(frames):
            for name, values in frame_values(k).items():
                np.testing.assert_array_equal(r.field(name, k), values)
                np.testing.assert_array_equal(r.field(name, k - frames), values)
        for name, values in frame_values(frames - 1).items():
            np.testing.assert_array_equal(r.field(name), values)

    def test_mesh_and_frames(self):
        self.write_complete()
        mesh = two_body_mesh()
        with femdem.open_results(self.dir) as r:
            self.assertTrue(r.complete)
            self.assertEqual(r.format_version, 1)
            np.testing.assert_array_equal(r.coordinates, mesh["coordinates"])
            np.testing.assert_array_equal(r.connectivity, mesh["connectivity"])
            self.assertEqual(r.connectivity.shape, (2, 10))
            np.testing.assert_array_equal(r.node_body, mesh["node_body"])
            np.testing.assert_array_equal(r.element_body, mesh["element_body"])
            self.assertEqual(r.body_names, ["ball", "prism_é"])
            self.assertEqual((r.node_count, r.element_count), (20, 2))
            self.assertEqual(sorted(r.field_names), sorted(n for n, _, _ in FIELDS))
            self.check_frames(r, 3)
            self.assertEqual(r.field("stress", 1).shape, (2, 9))
            self.assertEqual(r.field("von_mises", 1).shape, (2,))
            self.assertEqual(r.series("displacement").shape, (3, 20, 3))
            np.testing.assert_array_equal(r.series("pressure")[1], frame_values(1)["pressure"])
            fr = r.frame(1)
            self.assertEqual(fr["time"], 0.5)
            self.assertEqual([r.frame_at(t) for t in (-1.0, 0.2, 0.3, 0.5, 0.9, 5.0)],
                             [0, 0, 1, 1, 2, 2])  # frames at t = 0, 0.5, 1
            np.testing.assert_array_equal(fr["velocity"], frame_values(1)["velocity"])
            np.testing.assert_array_equal(r.positions(2), mesh["coordinates"]
                                          + frame_values(2)["displacement"])
            with self.assertRaises(IndexError):
                r.field("pressure", 3)
            with self.assertRaises(IndexError):
                r.field("pressure", -4)
            with self.assertRaises(KeyError):
                r.field("temperature")
            with self.assertRaises(KeyError):
                r.field("time")
        self.assertIsNone(r.file)

    def test_no_frames(self):
        self.write_complete(frames=0)
        with femdem.open_results(self.path("results.h5")) as r:
            self.assertEqual(r.frame_count, 0)
            self.assertEqual(len(r.times), 0)
            self.assertEqual(r.body_names, ["ball", "prism_é"])
            with self.assertRaises(IndexError):
                r.field("displacement")

    def test_killed_run(self):
        path = self.path("results.h5")
        p = subprocess.run(child("write_killed_results", path, 3), capture_output=True)
        self.assertEqual(p.returncode, -signal.SIGKILL, p.stderr.decode())
        # the writer's mark is still on: a plain read-only open is refused ...
        with self.assertRaises(OSError):
            h5py.File(path, "r")
        # ... the reader falls back to SWMR and sees the 3 complete frames, not the cut one
        with femdem.open_results(self.dir) as r:
            self.assertFalse(r.complete)
            with h5py.File(path, "r", swmr=True) as f:
                self.assertEqual(f["/frames/displacement"].shape[0], 4)
            self.check_frames(r, 3)

    def test_run_still_going(self):
        path = self.path("results.h5")
        with subprocess.Popen(child("write_live_results", path), stdin=subprocess.PIPE,
                              stdout=subprocess.PIPE, text=True) as p:
            try:
                self.assertEqual(p.stdout.readline().strip(), "frames 2")
                r = femdem.open_results(self.dir)
                self.assertFalse(r.complete)
                self.check_frames(r, 2)
                p.stdin.write("\n")
                p.stdin.flush()
                self.assertEqual(p.stdout.readline().strip(), "frames 3")
                self.assertEqual(r.frame_count, 2)  # fixed until refresh()
                r.refresh()
                self.check_frames(r, 3)
                r.close()
                p.stdin.close()
                self.assertEqual(p.wait(timeout=60), 0)
            finally:
                if p.poll() is None:
                    p.kill()
        with femdem.open_results(self.dir) as r:
            self.assertTrue(r.complete)
            self.check_frames(r, 3)

    def test_not_a_results_file(self):
        with h5py.File(self.path("other.h5"), "w") as f:
            f.attrs["format"] = "something-else"
            f.create_group("frames").create_dataset("time", data=[0.0])
        with self.assertRaises(ValueError):
            femdem.open_results(self.path("other.h5"))
        with self.assertRaises(OSError):
            femdem.open_results(self.path("missing.h5"))


@needs_h5
class RunTest(TempDir):
    def write_run(self, summary):
        cols = history_columns(["ball", "prism_é"], ["floor"])
        write_text(self.path("history.csv"),
                   history_text(cols, [[float(i)] * len(cols) for i in range(3)]))
        w = ResultsFile(self.path("results.h5"), two_body_mesh())
        for k in range(2):
            w.write_frame(0.5 * k, frame_values(k))
        w.close(complete=summary)
        if summary:
            write_text(self.path("summary.json"), json.dumps({"status": "completed",
                                                              "end_time": 2.0}))

    def test_run_without_summary(self):
        self.write_run(summary=False)
        with femdem.Run(self.dir) as run:
            self.assertIsNone(run.summary)
            self.assertEqual(run.history["time"].tolist(), [0.0, 1.0, 2.0])
            self.assertEqual(run.bodies, ["ball", "prism_é"])
            self.assertEqual(run.walls, ["floor"])
            self.assertEqual(run.results.frame_count, 2)
            self.assertFalse(run.results.complete)
            results = run.results
            self.assertIs(run.results, results)  # opened once
        self.assertIsNone(results.file)  # closed with the run

    def test_run_with_summary(self):
        self.write_run(summary=True)
        run = femdem.Run(self.dir)
        self.assertEqual(run.summary["status"], "completed")
        self.assertTrue(run.results.complete)
        self.assertEqual(run.path("run.log"), os.path.join(self.dir, "run.log"))
        run.close()

    def test_lazy(self):
        write_text(self.path("summary.json"), "{}")
        run = femdem.Run(self.dir)  # nothing read yet: no history.csv is not an error here
        self.assertEqual(run.summary, {})
        with self.assertRaises(FileNotFoundError):
            run.history
        with self.assertRaises(OSError):
            run.results
        with self.assertRaises(FileNotFoundError):
            femdem.Run(self.path("missing"))


@needs_h5
class ScriptTest(TempDir):
    """The scripts find the package from anywhere."""

    def test_plot_history_from_another_folder(self):
        try:
            import matplotlib  # noqa: F401
        except ImportError:
            self.skipTest("needs matplotlib")
        cols = history_columns(["ball"], ["floor"])
        write_text(self.path("history.csv"),
                   history_text(cols, [[float(i)] * len(cols) for i in range(3)]))
        p = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "plot_history.py"),
                            self.dir], cwd=tempfile.gettempdir(), capture_output=True, text=True)
        self.assertEqual(p.returncode, 0, p.stderr)
        for png in ("energy.png", "com.png", "forces.png"):
            self.assertTrue(os.path.getsize(self.path(png)) > 0, png)


@unittest.skipUnless(os.environ.get("FEMDEM_EXE"), "set FEMDEM_EXE to a femdem program")
@needs_h5
class RealRunTest(TempDir):
    """A short real run: history.csv, summary.json and results.h5 agree with each other."""

    END_TIME = 2.0  # bar_vibration: output_interval 0.25, history_interval 0.02

    def test_bar_vibration(self):
        out = self.path("bar")
        p = subprocess.run([os.environ["FEMDEM_EXE"], "run",
                            os.path.join(ROOT, "scenes", "bar_vibration.toml"), "--out", out,
                            "--quiet", "--threads", "1",
                            "--set", f"simulation.end_time={self.END_TIME}"],
                           capture_output=True, text=True, timeout=300)
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
        with femdem.Run(out) as run:
            s, h, r = run.summary, run.history, run.results
            self.assertEqual(s["status"], "completed")
            self.assertEqual(s["end_time"], self.END_TIME)
            self.assertEqual(h["time"][-1], s["end_time"])
            self.assertEqual(h["time"][0], 0.0)
            self.assertEqual(len(h["time"]), 101)  # t = 0 and every 0.02
            self.assertEqual(list(h)[:12], list(femdem.history.GLOBAL_COLUMNS))
            self.assertEqual(run.bodies, ["bar"])
            self.assertEqual(run.walls, [])
            self.assertEqual(run.bodies, list(s["bodies"]))
            self.assertEqual(h["kinetic_energy"][-1], s["energy"]["kinetic"])
            self.assertEqual([h[f"bar.com_{c}"][-1] for c in "xyz"], s["bodies"]["bar"]["com"])
            self.assertEqual(h["bar.kinetic_energy"][-1], s["bodies"]["bar"]["kinetic_energy"])
            self.assertTrue(r.complete)
            self.assertEqual(r.body_names, list(s["bodies"]))
            self.assertEqual(r.node_count, s["nodes"])
            self.assertEqual(r.element_count, s["elements"])
            self.assertEqual(r.coordinates.shape, (s["nodes"], 3))
            self.assertEqual(r.connectivity.shape, (s["elements"], 10))
            self.assertEqual(set(r.node_body.tolist()), {0})
            self.assertEqual(r.frame_count, 9)  # t = 0 and every 0.25, the last at end_time
            with open(os.path.join(out, "results.xdmf")) as f:
                self.assertEqual(f.read().count('<Grid Name="frame_'), r.frame_count)
            self.assertEqual(r.times[0], 0.0)
            self.assertEqual(r.times[-1], s["end_time"])
            self.assertTrue(np.all(np.diff(r.times) > 0))
            self.assertEqual(r.field("velocity").shape, (s["nodes"], 3))
            self.assertEqual(r.field("stress").shape, (s["elements"], 9))
            self.assertTrue(np.all(r.field("equivalent_plastic_strain") == 0.0))


if __name__ == "__main__":
    unittest.main()
