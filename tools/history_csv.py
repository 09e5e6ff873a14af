# SPDX-License-Identifier: GPL-3.0-or-later
"""Reads a femdem run's history.csv (docs/OUTPUTS.md) for the plot and check scripts in tools/.

A killed run may leave a last line without its line break (a row cut by the kill): it is
dropped, as is any row with the wrong number of fields.
"""
import csv


def read_history(path):
    """The columns of history.csv at `path`, as {name: [float, ...]}."""
    with open(path, newline="") as f:
        text = f.read()
    if not text.endswith("\n"):
        text = text[: text.rfind("\n") + 1]  # a killed run's torn last line
    rows = list(csv.reader(text.splitlines()))
    header, data = rows[0], rows[1:]
    cols = {name: [] for name in header}
    for row in data:
        if len(row) != len(header):
            continue
        for name, value in zip(header, row):
            cols[name].append(float(value))
    return cols
