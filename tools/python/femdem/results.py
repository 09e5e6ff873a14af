# SPDX-License-Identifier: GPL-3.0-or-later
"""Reads a femdem run's results.h5: the TET10 mesh once, then one frame of fields per output
interval (docs/OUTPUTS.md, "results.h5 / results.xdmf", which gives the layout).

    /mesh/coordinates [N,3]    reference node positions (float64)
    /mesh/connectivity [E,10]  TET10 node indices, VTK quadratic-tetra order (int32)
    /mesh/node_body [N], /mesh/element_body [E]   body index of each node, element (int32)
    /mesh/body_names [B]       the body names, in body-index order
    /frames/time [F]           the time of each complete frame
    /frames/displacement [F,N,3], /frames/velocity [F,N,3]               node fields
    /frames/stress [F,E,9] (Cauchy, row-major 3x3), /frames/von_mises [F,E],
    /frames/pressure [F,E], /frames/equivalent_plastic_strain [F,E]     element fields
    /walls/names [W], /walls/normal [W,3], /walls/patch [W,4,3]   the rigid walls (if any) and
                               the rectangle drawn for each at t = 0
    /walls/displacement [F,W,3], /walls/force [F,W,3]   each wall's translation and the force
                               the bodies exert on it, per frame
    root attributes: complete (1 for a finished run), format, format_version, femdem_version,
    units, node_order, scene_digest
The frame fields are float64 (float32 from a writer set to single precision) and are returned
as stored.

The writer uses HDF5's single-writer/multiple-reader (SWMR) mode, so the file of a run still
going, or killed, is readable: it is opened read-only, as a SWMR reader when a plain open is
refused (the writer's "open" mark). A frame is counted once its time is in /frames/time; the
field datasets are extended (and written) before that, so they may hold one frame more, still
being written or cut by a kill: it is never read. Frame indices count the complete frames only,
and -1 is the last complete frame.

h5py and numpy are needed here (imported when a file is opened).
"""

from ._paths import file_in

RESULTS_FILE = "results.h5"
#: Fields with one value (or vector) per node.
NODE_FIELDS = ("displacement", "velocity")
#: Fields with one value (or tensor) per element: averages over its 4 Gauss points.
ELEMENT_FIELDS = ("stress", "von_mises", "pressure", "equivalent_plastic_strain")
#: The order of the 9 components of a stress row.
STRESS_COMPONENTS = ("xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz")


def results_path(path_or_run_dir):
    """The path of results.h5: `path_or_run_dir` itself, or results.h5 in it if a folder."""
    return file_in(path_or_run_dir, RESULTS_FILE)


def _text(value):
    """A string of the file (fixed-length strings read as bytes) as str."""
    if isinstance(value, bytes):
        return value.rstrip(b"\0").decode("utf-8")
    return str(value)


class Results:
    """A results.h5 opened read-only; use it as a context manager, or call close().

    The mesh is read on first use and kept; the frame count is fixed when the file is opened
    and moves on with refresh() for a run still being written.
    """

    def __init__(self, path_or_run_dir):
        import h5py

        self.path = results_path(path_or_run_dir)
        try:
            self.file = h5py.File(self.path, "r")
        except OSError:
            # a run still going, or killed: the file keeps the writer's mark; read it as a
            # SWMR reader (a missing file fails here again, with its own message)
            self.file = h5py.File(self.path, "r", swmr=True)
        fmt = self.file.attrs.get("format")
        if fmt is not None and _text(fmt) != "femdem-results":
            name = self.path
            self.close()
            raise ValueError(f"{name}: not a femdem results file (format '{_text(fmt)}')")
        self._mesh = {}
        self._count()

    def __repr__(self):
        return f"femdem.Results({self.path!r}, {self._frame_count} frames)"

    # --- the file

    def close(self):
        """Closes the file (the arrays already read stay valid)."""
        if self.file is not None:
            self.file.close()
            self.file = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    @property
    def complete(self):
        """True for a finished run; False for one that diverged, was stopped, killed or is
        still going (the root attribute `complete`)."""
        return int(self.file.attrs.get("complete", 0)) == 1

    @property
    def format_version(self):
        """The root attribute `format_version` (None if the file has none)."""
        v = self.file.attrs.get("format_version")
        return None if v is None else int(v)

    # --- the mesh

    def _mesh_array(self, name):
        if name not in self._mesh:
            self._mesh[name] = self.file["mesh"][name][()]
        return self._mesh[name]

    @property
    def coordinates(self):
        """Reference node positions [N,3] (float64)."""
        return self._mesh_array("coordinates")

    @property
    def connectivity(self):
        """TET10 node indices [E,10] (int32, VTK quadratic-tetra order: corners 0-3 first)."""
        return self._mesh_array("connectivity")

    @property
    def node_body(self):
        """Body index of each node [N] (int32)."""
        return self._mesh_array("node_body")

    @property
    def element_body(self):
        """Body index of each element [E] (int32)."""
        return self._mesh_array("element_body")

    @property
    def body_names(self):
        """The body names, as a list of str indexed by body index."""
        if "body_names" not in self._mesh:
            self._mesh["body_names"] = [_text(n) for n in self.file["mesh"]["body_names"][()]]
        return self._mesh["body_names"]

    @property
    def node_count(self):
        """The number of nodes N."""
        return int(self.file["mesh"]["coordinates"].shape[0])

    @property
    def element_count(self):
        """The number of TET10 elements E."""
        return int(self.file["mesh"]["connectivity"].shape[0])

    # --- the frames

    @property
    def field_names(self):
        """The per-frame fields in the file (every dataset of /frames but `time`)."""
        return [n for n in self.file["frames"] if n != "time"]

    def _count(self):
        frames = self.file["frames"]
        datasets = [frames[n] for n in frames]
        if "walls" in self.file:
            datasets += [self.file["walls"][n] for n in ("displacement", "force")]
        if self.file.swmr_mode:
            for d in datasets:
                d.refresh()
        # the time is appended last: it counts the complete frames (the min guards against a
        # reader that sees the datasets at different moments)
        self._frame_count = min(int(d.shape[0]) for d in datasets)
        self._times = frames["time"][: self._frame_count]

    def refresh(self):
        """Sees the frames written since the file was opened (a run still going)."""
        self._count()

    @property
    def frame_count(self):
        """The number of complete frames."""
        return self._frame_count

    def __len__(self):
        return self._frame_count

    @property
    def times(self):
        """The times of the complete frames [F] (float64)."""
        return self._times

    def _index(self, frame):
        n = self._frame_count
        i = int(frame)
        if i < 0:
            i += n
        if not 0 <= i < n:
            raise IndexError(f"{self.path}: frame {frame} out of range ({n} complete frames)")
        return i

    def _dataset(self, name):
        if name == "time" or name not in self.file["frames"]:
            raise KeyError(f"{self.path}: no field '{name}' (fields: "
                           + ", ".join(self.field_names) + ")")
        return self.file["frames"][name]

    def frame_at(self, time):
        """The index of the complete frame nearest to `time` (s)."""
        import numpy as np

        if self._frame_count == 0:
            raise IndexError(f"{self.path}: no complete frames")
        return int(np.argmin(np.abs(np.asarray(self._times) - time)))

    def field(self, name, frame=-1):
        """One frame's field by name: [N,3] for a node vector, [E,9] for the stress, [E] for an
        element scalar. `frame` counts the complete frames (-1: the last one)."""
        d = self._dataset(name)
        return d[self._index(frame)]

    def series(self, name):
        """A field over all complete frames: [F,N,3], [F,E,9] or [F,E]."""
        return self._dataset(name)[: self._frame_count]

    def frame(self, frame=-1):
        """All fields of one frame, as {name: array}, with its `time`."""
        i = self._index(frame)
        fields = {"time": float(self._times[i])}
        for name in self.field_names:
            fields[name] = self.file["frames"][name][i]
        return fields

    def positions(self, frame=-1):
        """Deformed node positions [N,3] of a frame: coordinates + displacement."""
        return self.coordinates + self.field("displacement", frame)


    # --- the walls

    @property
    def wall_names(self):
        """The rigid walls' names ([] for a run without walls)."""
        if "walls" not in self.file:
            return []
        return [_text(n) for n in self.file["walls"]["names"][()]]

    @property
    def wall_normals(self):
        """The walls' unit normals [W,3], pointing towards the bodies."""
        return self.file["walls"]["normal"][()]

    def wall_patch(self, frame=-1):
        """The rectangle drawn for each wall where it is at a frame: corners [W,4,3]."""
        w = self.file["walls"]
        return w["patch"][()] + w["displacement"][self._index(frame)][:, None, :]

    def wall_force(self, frame=-1):
        """The force the bodies exert on each wall at a frame [W,3], N."""
        return self.file["walls"]["force"][self._index(frame)]


def open_results(path_or_run_dir):
    """Opens results.h5 (a file, or a run's output folder) read-only: a Results."""
    return Results(path_or_run_dir)
