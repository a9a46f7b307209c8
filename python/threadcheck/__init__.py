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

__all__ = ["verify", "limits", "passes", "correct", "capability", "fit", "compare", "mill", "__version__"]
__version__ = _threadcheck.__version__


def verify(thread, program=None, dialect="fanuc", insert=None, final_x=None, internal=False,
           infeed=None, passes=None, blank_diameter=None, gauge_only=False,
           allow_nonstandard=False, program_name="<program>", default_units=None, main=None,
           linuxcnc_release="current", coating=0.0):
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
    ``coating`` (mm) checks against the limits before a coat of that thickness.
    The dict has ``verdict`` (``"pass"``/``"fail"``); a program's report has ``operations``.
    """
    threads = [thread] if isinstance(thread, str) else list(thread)
    text, _passed = _threadcheck.job_json(
        "verify", threads, program=program, dialect=dialect, insert=insert, final_x=final_x,
        internal=internal, infeed=infeed, passes=passes, blank_diameter=blank_diameter,
        gauge_only=gauge_only, allow_nonstandard=allow_nonstandard, program_name=program_name,
        default_units=default_units, main=main, linuxcnc_release=linuxcnc_release,
        coating=coating)
    return _json.loads(text)


def limits(designation, allow_nonstandard=False, coating=0.0):
    """``threadcheck limits DESIGNATION --json``: basic sizes and limits of size, mm.

    ``coating`` (mm) gives the limits to cut to before a coat of that thickness.
    """
    return _json.loads(_threadcheck.limits_json(designation, allow_nonstandard=allow_nonstandard,
                                                coating=coating))


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


def correct(thread, program=None, dialect="fanuc", insert=None, final_x=None, internal=False,
            infeed=None, passes=None, blank_diameter=None, allow_nonstandard=False,
            program_name="<program>", default_units=None, main=None, linuxcnc_release="current",
            coating=0.0, measured_m=None, wire=None, measured_d2=None, gauge=None, pickup_z=None):
    """``threadcheck correct --json``: what was measured on the part, turned into the change.

    ``thread`` and the plan or ``program`` arguments are ``verify``'s. Give one measurement:
    ``measured_m`` (mm over three wires) with ``wire`` (their diameter, mm), ``measured_d2``
    (mm), or ``gauge`` (``"go-fails"``, ``"nogo-enters"``, ``"ok"``); ``pickup_z`` (mm from the
    program's Z0) adds a pick-up's start angle and Z shift. The dict has ``verdict``
    (``"pass"`` in tolerance), ``measured``, ``delta_pitch_diameter``, ``suggested_final_x``,
    ``correction`` (the program's word), ``wear_offset`` and ``pickup``.
    """
    text, _ok = _threadcheck.job_json(
        "correct", [thread], program=program, dialect=dialect, insert=insert, final_x=final_x,
        internal=internal, infeed=infeed, passes=passes, blank_diameter=blank_diameter,
        allow_nonstandard=allow_nonstandard, program_name=program_name,
        default_units=default_units, main=main, linuxcnc_release=linuxcnc_release,
        coating=coating, measured_m=measured_m, wire=wire, measured_d2=measured_d2, gauge=gauge,
        pickup_z=pickup_z)
    return _json.loads(text)


def capability(thread, program=None, dialect="fanuc", insert=None, final_x=None, internal=False,
               infeed=None, passes=None, blank_diameter=None, allow_nonstandard=False,
               program_name="<program>", default_units=None, main=None,
               linuxcnc_release="current", coating=0.0, x_sigma=0.0, tip_radius_tol=0.0,
               wear_per_part=0.0, samples=10000, seed=1, gauge_only=False):
    """``threadcheck capability --json``: a seeded Monte Carlo of the parts a program cuts.

    ``x_sigma`` is the X repeatability (one sigma on the diameter, mm), ``tip_radius_tol`` a
    partial insert's tip radius tolerance (± mm, uniform), ``wear_per_part`` the radial wear per
    part (mm); ``gauge_only`` leaves form checks out of each part's verdict. The dict has ``sizes`` (mean, sigma, Cp, Cpk, ppm per checked size),
    ``pass_share``, ``parts_per_edge``, ``best_final_x`` and the d2 ``histogram``.
    """
    text, _ok = _threadcheck.job_json(
        "capability", [thread], program=program, dialect=dialect, insert=insert, final_x=final_x,
        internal=internal, infeed=infeed, passes=passes, blank_diameter=blank_diameter,
        allow_nonstandard=allow_nonstandard, program_name=program_name,
        default_units=default_units, main=main, linuxcnc_release=linuxcnc_release,
        coating=coating, x_sigma=x_sigma, tip_radius_tol=tip_radius_tol,
        wear_per_part=wear_per_part, samples=samples, seed=seed, gauge_only=gauge_only)
    return _json.loads(text)


def fit(thread, bolt_program=None, bolt_dialect="fanuc", bolt_final_x=None, bolt_insert="partial",
        nut_program=None, nut_dialect="fanuc", nut_final_x=None, nut_insert="partial",
        allow_nonstandard=False):
    """``threadcheck fit --json``: a bolt and a nut cut in the computer and assembled.

    ``thread`` is a fit designation (``"M10x1.5-6H/6g"``). Each side is a program's text
    (``bolt_program``, ``nut_program``, with their dialects) or a plan (``bolt_final_x``,
    ``nut_final_x``; default mid-tolerance); inserts as ``verify`` takes them. The dict has
    ``verdict`` (``"fits"``/``"interferes"``), ``clearance_um`` and both sides' reports.
    """
    text, _ok = _threadcheck.fit_json(
        thread, allow_nonstandard=allow_nonstandard, bolt_program=bolt_program,
        bolt_dialect=bolt_dialect, bolt_final_x=bolt_final_x, bolt_insert=bolt_insert,
        nut_program=nut_program, nut_dialect=nut_dialect, nut_final_x=nut_final_x,
        nut_insert=nut_insert)
    return _json.loads(text)


def compare(thread, insert=None, final_x=None, internal=False, allow_nonstandard=False,
            infeed=None, schedule=None, modified=None):
    """``threadcheck compare --json``: the thread with every infeed strategy and schedule.

    ``infeed`` (``"radial"``, ``"flank:27"`` …) and ``schedule`` (``"constant-area"`` …)
    compare that one alone; ``modified`` lists the modified-flank angles (default half the
    thread angle less 0.5° and 3°). The dict has ``strategies`` and ``recommended``.
    """
    return _json.loads(_threadcheck.compare_json(
        thread, insert=insert, final_x=final_x, internal=internal,
        allow_nonstandard=allow_nonstandard, infeed=infeed, schedule=schedule, modified=modified))


def mill(program, target, tool_diameter, dialect="fanuc", tolerance=0.01, n_order=False,
         program_name="<program>"):
    """``threadcheck mill --json``: a milling program's text against a target curve.

    ``target`` is the target's TOML text (``x``, ``y`` in ``t`` and ``z``, ``t``, ``material``,
    optional ``z``), ``tool_diameter`` and ``tolerance`` in mm. The dict has ``verdict``,
    ``gouge_max``, ``leftover_max`` and the levels.
    """
    text, _ok = _threadcheck.mill_json(program, target, tool_diameter, dialect=dialect,
                                       tolerance=tolerance, n_order=n_order,
                                       program_name=program_name)
    return _json.loads(text)
