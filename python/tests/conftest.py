"""Finds the command-line binary the tests compare with, so that ``pytest python/tests`` runs
as it is: ``THREADCHECK_BIN`` when set, else the release build of this repository (the one the
README's first command just made), else ``threadcheck`` on the PATH. A test that needs it and
finds none fails with that message."""

import os
import pathlib
import shutil


def _find_binary():
    built = pathlib.Path(__file__).resolve().parents[2] / "target" / "release" / "threadcheck"
    for candidate in (os.environ.get("THREADCHECK_BIN"), str(built), shutil.which("threadcheck")):
        if candidate and os.path.isfile(candidate) and os.access(candidate, os.X_OK):
            return candidate
    return None


_binary = _find_binary()
if _binary:
    os.environ["THREADCHECK_BIN"] = _binary
