# SPDX-License-Identifier: GPL-3.0-or-later
"""Reads the sweep.csv of `femdem sweep`: one row per finished run, in sweep order
(docs/OUTPUTS.md, "sweep.csv").

The columns are the varied keys (full dotted names), then `run`, `exit_code`, `status` and
summary.json flattened (`end_time`, ..., `energy.kinetic`, ..., `bodies.NAME.com.x`, ...,
`extra.NAME`). The values are kept as the text of the file: a varied value is as given on the
command line (an array such as `[0,0,-5]`, a quoted string), and the result columns are empty
for a failed run or a null in its summary.

Needs only the standard library.
"""
import csv

from ._paths import file_in

SWEEP_FILE = "sweep.csv"


def sweep_path(path_or_sweep_dir):
    """The path of sweep.csv: `path_or_sweep_dir` itself, or sweep.csv in it if a folder."""
    return file_in(path_or_sweep_dir, SWEEP_FILE)


def read_sweep(path_or_sweep_dir):
    """The rows of a sweep.csv (a file, or the sweep's folder) as a list of {column: text},
    each dict in the column order of the file. Rows with the wrong number of fields are dropped;
    an empty file or one with only its column line gives []."""
    with open(sweep_path(path_or_sweep_dir), newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        return []
    header = rows[0]
    return [dict(zip(header, r)) for r in rows[1:] if len(r) == len(header)]


def varied_keys(row):
    """The varied keys of a sweep: the columns before `run` (of a row, or the column names)."""
    columns = list(row)
    return columns[: columns.index("run")] if "run" in columns else []
