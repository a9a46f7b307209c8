"""threadcheck: what thread a CNC lathe program will cut, and whether it meets its standard.

Each function runs the same job as the command line and returns a plain dict identical to that
command's JSON (``docs/json.md`` in the repository lists every key and its unit). Errors raise
``ValueError`` with the command line's one-line message (``file:line:column`` for programs).

>>> import threadcheck
>>> threadcheck.limits("M10x1.5-6g")["external"]["pitch_diameter"]["max"]
8.994
"""

import json as _json

from . import _threadcheck

__all__ = ["verify", "limits", "passes", "__version__"]
__version__ = _threadcheck.__version__


def verify(thread, program=None, dialect="fanuc", insert=None, final_x=None, internal=False,
           infeed=None, passes=None, blank_diameter=None, gauge_only=False,
           allow_nonstandard=False, program_name="<program>", default_units=None, main=None,
           linuxcnc_release="current"):
    """``threadcheck verify --json -``.

    ``thread`` is a designation with its class (``"M20x1.5-6g"``), or a list of them, one per
    threading operation of ``program``. ``program`` is the program's text (not a path); without
    it a plan is generated and ``final_x`` (or the solved middle of the tolerance) is verified.
    ``insert`` is ``"full"``, ``"partial"``, ``"partial:R"`` or an insert file's path; without
    it a program is verified with a partial insert and the report says so. ``infeed`` takes the
    command line's words: ``"radial"``, ``"flank"``, ``"flank:27"``, ``"modified"`` (the default:
    half the thread angle less 0.5°), ``"alternating"``, ``"alternating:ANGLE"``.
    ``default_units`` (``"mm"``/``"inch"``) reads a program that sets no units as an inch or
    metric control would; ``main`` (``"O3101"``) picks the main program of a text that holds
    several O-programs (else the one no other calls, said in ``notes``).
    ``linuxcnc_release`` (``"current"``/``"before-2.9"``) chooses the comparison rules of a
    ``linuxcnc`` program: EQ, NE, LE, GE within 1e-6 from LinuxCNC 2.9.0 on, EQ and NE within
    1e-4 and LE, GE exact before (Debian 12's package).
    The dict has ``verdict`` (``"pass"``/``"fail"``); a program's report has ``operations``.
    """
    threads = [thread] if isinstance(thread, str) else list(thread)
    text, _passed = _threadcheck.job_json(
        "verify", threads, program=program, dialect=dialect, insert=insert, final_x=final_x,
        internal=internal, infeed=infeed, passes=passes, blank_diameter=blank_diameter,
        gauge_only=gauge_only, allow_nonstandard=allow_nonstandard, program_name=program_name,
        default_units=default_units, main=main, linuxcnc_release=linuxcnc_release)
    return _json.loads(text)


def limits(designation, allow_nonstandard=False):
    """``threadcheck limits DESIGNATION --json``: basic sizes and limits of size, mm."""
    return _json.loads(_threadcheck.limits_json(designation, allow_nonstandard=allow_nonstandard))


def passes(thread=None, program=None, dialect="fanuc", insert=None, final_x=None, internal=False,
           infeed=None, passes=None, blank_diameter=None, allow_nonstandard=False,
           program_name="<program>", default_units=None, main=None, linuxcnc_release="current"):
    """``threadcheck passes --json``: the passes of a generated plan or of a program's text."""
    text, _ok = _threadcheck.job_json(
        "passes", [] if thread is None else [thread], program=program, dialect=dialect,
        insert=insert, final_x=final_x, internal=internal, infeed=infeed, passes=passes,
        blank_diameter=blank_diameter, allow_nonstandard=allow_nonstandard,
        program_name=program_name, default_units=default_units, main=main,
        linuxcnc_release=linuxcnc_release)
    return _json.loads(text)
