# SPDX-License-Identifier: GPL-3.0-or-later
"""Reads a femdem run's history.csv: one row per history sample (docs/OUTPUTS.md, "history.csv").

The columns are the global ones (`time`, `dt`, the energies), then for every body `BODY.com_x`,
`BODY.vcom_x`, ..., `BODY.max_principal_stress`, for every wall `WALL.force_x`, ...,
`WALL.max_penetration_per_size`, then `contact.max_penetration` and
`contact.max_penetration_per_size` when bodies can touch each other and the 12 `compaction.*`
columns of a scene with `[compaction]`.

A run that was killed may leave a last line without its line break (a row cut by the kill): it
is dropped, as is any row with the wrong number of fields, so the file of a run still going or
killed reads as the rows written so far.

numpy is needed here (imported when a file is read).
"""

from ._paths import file_in

HISTORY_FILE = "history.csv"

#: The columns every history.csv starts with, in order.
GLOBAL_COLUMNS = ("time", "dt", "kinetic_energy", "internal_energy", "plastic_dissipation",
                  "contact_energy", "contact_dissipation", "viscous_dissipation",
                  "mass_scaling_dissipation", "external_work", "total_energy",
                  "energy_balance_error")
#: The columns of one body, `BODY` + suffix, in order.
BODY_SUFFIXES = (".com_x", ".com_y", ".com_z", ".vcom_x", ".vcom_y", ".vcom_z",
                 ".kinetic_energy", ".contact_force_x", ".contact_force_y", ".contact_force_z",
                 ".max_principal_stress")
#: The columns of one wall, `WALL` + suffix, in order.
WALL_SUFFIXES = (".force_x", ".force_y", ".force_z", ".position_x", ".position_y",
                 ".position_z", ".max_penetration", ".max_penetration_per_size")
#: The column of the deepest overlap between two bodies (scenes where bodies can touch).
PENETRATION_COLUMN = "contact.max_penetration"
#: The prefix of the compaction columns (scenes with `[compaction]`).
COMPACTION_PREFIX = "compaction."


def history_path(path_or_run_dir):
    """The path of history.csv: `path_or_run_dir` itself, or history.csv in it if a folder."""
    return file_in(path_or_run_dir, HISTORY_FILE)


def read_history(path_or_run_dir):
    """The columns of a history.csv (a file, or a run's output folder) as {name: numpy array}.

    The arrays are float64, one value per complete row, in the order of the file; the dict keeps
    the columns' order. A torn last line and rows with the wrong number of fields are dropped.
    Raises OSError when the file cannot be read and ValueError when it has no column line.
    """
    import csv

    import numpy as np

    path = history_path(path_or_run_dir)
    with open(path, newline="") as f:
        text = f.read()
    if not text.endswith("\n"):
        text = text[: text.rfind("\n") + 1]  # a killed run's torn last line
    rows = list(csv.reader(text.splitlines()))
    if not rows:
        raise ValueError(f"{path}: no column line")
    header = rows[0]
    values = [[float(v) for v in row] for row in rows[1:] if len(row) == len(header)]
    table = np.array(values, dtype=float).reshape(len(values), len(header))
    columns = table.T.copy()  # one contiguous array per column
    return {name: columns[i] for i, name in enumerate(header)}


def _names_with(columns, suffix):
    names = []
    for c in columns:
        if c.endswith(suffix) and len(c) > len(suffix):
            name = c[: -len(suffix)]
            if name not in names:
                names.append(name)
    return names


def body_names(columns):
    """The bodies of a history (its dict, or its column names), in column order.

    A body is the NAME of a column `NAME.com_x`.
    """
    return _names_with(columns, ".com_x")


def wall_names(columns):
    """The walls of a history (its dict, or its column names), in column order.

    A wall is the NAME of a column `NAME.force_x` (a body's `.contact_force_x` is not one).
    """
    return _names_with(columns, ".force_x")


def has_compaction(columns):
    """True when the history (its dict, or its column names) has the compaction columns."""
    return any(c.startswith(COMPACTION_PREFIX) for c in columns)


def has_penetration(columns):
    """True when the history (its dict, or its column names) has `contact.max_penetration`."""
    return PENETRATION_COLUMN in columns
