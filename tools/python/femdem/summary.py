# SPDX-License-Identifier: GPL-3.0-or-later
"""Reads a femdem run's summary.json: the run's scalar results (docs/OUTPUTS.md, "summary.json").

The file is written once, atomically, at the end of the run (also for a run that diverged or was
interrupted), so it is either absent (a run still going, or killed) or whole. Its keys: `scene`,
`status` (`completed`, `unstable` or `interrupted`), `end_time`, `steps`, `time_step`,
`wall_time_s`, `threads`, `nodes`, `elements`, `energy` {...}, `bodies` {NAME: {...}}, `extra`
{...} and, for a scene with `[compaction]`, `compaction` {...}.

Needs only the standard library.
"""
import json

from ._paths import file_in

SUMMARY_FILE = "summary.json"


def summary_path(path_or_run_dir):
    """The path of summary.json: `path_or_run_dir` itself, or summary.json in it if a folder."""
    return file_in(path_or_run_dir, SUMMARY_FILE)


def read_summary(path_or_run_dir):
    """summary.json (a file, or a run's output folder) as a dict.

    Raises FileNotFoundError when there is none (the run is going or was killed) and ValueError
    when the file is not JSON.
    """
    with open(summary_path(path_or_run_dir)) as f:
        return json.load(f)
