# SPDX-License-Identifier: GPL-3.0-or-later
"""The one rule every reader of the package uses to find its file."""
import os


def file_in(path_or_dir, name):
    """`path_or_dir` itself, or the file `name` in it if it is a folder."""
    if os.path.isdir(path_or_dir):
        return os.path.join(path_or_dir, name)
    return os.fspath(path_or_dir)
