# SPDX-License-Identifier: GPL-3.0-or-later
"""Reads the outputs of femdem runs (the files are described in docs/OUTPUTS.md).

    import femdem

    run = femdem.Run("out/taylor_bar")
    run.history["time"], run.history["rod.com_z"]     # history.csv: {column: numpy array}
    run.summary["end_time"]                           # summary.json (None while running)
    run.results.coordinates, run.results.times        # results.h5: mesh and frame times
    run.results.field("equivalent_plastic_strain", -1)   # one frame's field, the last one

or the readers on their own: read_history(), read_summary(), open_results() and, for
`femdem sweep`, read_sweep(); each takes a file or the folder holding it. A run still going, or
killed, reads as what it has written so far: the complete rows of history.csv, the complete
frames of results.h5, no summary.json.

Modules: femdem.history (history.csv), femdem.summary (summary.json), femdem.results
(results.h5, needs h5py), femdem.sweep (sweep.csv). numpy is needed for history.csv and
results.h5 and is imported only when one is read.
"""
import os
from functools import cached_property

from .history import (HISTORY_FILE, body_names, has_compaction, has_penetration, history_path,
                      read_history, wall_names)
from .results import RESULTS_FILE, Results, open_results, results_path
from .summary import SUMMARY_FILE, read_summary, summary_path
from .sweep import SWEEP_FILE, read_sweep, sweep_path, varied_keys

__all__ = ["Run", "read_history", "body_names", "wall_names", "has_compaction",
           "has_penetration", "read_summary", "Results", "open_results", "read_sweep",
           "varied_keys", "history_path", "summary_path", "results_path", "sweep_path",
           "HISTORY_FILE", "SUMMARY_FILE", "RESULTS_FILE", "SWEEP_FILE"]


class Run:
    """The output folder of one `femdem run` (`--out DIR`). Each file is read on first use and
    kept: `history` (dict of numpy arrays), `summary` (dict, or None while the run is going or
    after a kill) and `results` (an open Results; close it with close(), or use the Run as a
    context manager)."""

    def __init__(self, out_dir):
        self.dir = os.fspath(out_dir)
        if not os.path.isdir(self.dir):
            raise FileNotFoundError(f"{self.dir}: no such run folder")

    def __repr__(self):
        return f"femdem.Run({self.dir!r})"

    def path(self, name):
        """The path of a file of the run, e.g. path("run.log")."""
        return os.path.join(self.dir, name)

    @cached_property
    def history(self):
        """history.csv: {column: numpy array} (read_history)."""
        return read_history(self.path(HISTORY_FILE))

    @cached_property
    def summary(self):
        """summary.json as a dict, or None when there is none (the run is going or was
        killed)."""
        try:
            return read_summary(self.path(SUMMARY_FILE))
        except FileNotFoundError:
            return None

    @cached_property
    def results(self):
        """results.h5 opened read-only (a Results)."""
        return open_results(self.path(RESULTS_FILE))

    @property
    def bodies(self):
        """The body names, from the history's columns."""
        return body_names(self.history)

    @property
    def walls(self):
        """The wall names, from the history's columns."""
        return wall_names(self.history)

    def close(self):
        """Closes results.h5 if it was opened."""
        results = self.__dict__.pop("results", None)
        if results is not None:
            results.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False
