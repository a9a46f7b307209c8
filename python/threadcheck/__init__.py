"""threadcheck: what thread a CNC lathe program will cut, and whether it meets its standard.

Each function runs the same job as the command line, through the same door as the web API
(``threadcheck serve``), and returns a plain dict identical to that command's JSON
(``docs/json.md`` in the repository lists every key and its unit). Errors raise ``ValueError``
with the command line's one-line message (``file:line:column`` for programs).

Pictures and pages: ``svg=`` and ``html=`` take a path to write (all of a call's files are
written together, or none); ``render(command, document, **arguments)`` returns a document as a
string (``"svg"``, ``"html"``, ``"text"``, ``"fix"``: the corrected program).

>>> import threadcheck
>>> threadcheck.limits("M10x1.5-6g")["external"]["pitch_diameter"]["max"]
8.994
"""

from __future__ import annotations

import json as _json
import os as _os
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

from . import _threadcheck
from ._types import (
    CapabilityReport,
    CompareReport,
    CorrectReport,
    FitReport,
    LimitsReport,
    MillReport,
    PassesReport,
    TapReport,
    ThreadMillReport,
    VerifyReport,
)

__all__ = [
    "verify",
    "limits",
    "passes",
    "correct",
    "capability",
    "fit",
    "compare",
    "mill",
    "tap",
    "thread_mill",
    "render",
    "VerifyReport",
    "LimitsReport",
    "PassesReport",
    "CorrectReport",
    "CapabilityReport",
    "FitReport",
    "CompareReport",
    "MillReport",
    "TapReport",
    "ThreadMillReport",
    "__version__",
]
__version__: str = _threadcheck.__version__

PathLike = Union[str, "_os.PathLike[str]"]
Threads = Union[str, Sequence[str]]


def _arguments(values: Dict[str, Any]) -> str:
    """The JSON object of a call's keyword arguments: ``None`` means not given."""
    args: Dict[str, Any] = {}
    for key, value in values.items():
        if value is None:
            continue
        if key == "thread" and not isinstance(value, str):
            value = list(value)
        if isinstance(value, tuple):
            value = list(value)
        args[key] = value
    # allow_nan=False: NaN and infinity are refused here with the key's name, as the CLI does.
    try:
        return _json.dumps(args, allow_nan=False)
    except ValueError:
        bad = [k for k, v in args.items() if isinstance(v, float) and v != v or v in (float("inf"), float("-inf"))]
        raise ValueError(f"{', '.join(bad) or 'an argument'} is not a finite number") from None


def _run(command: str, document: str, values: Dict[str, Any]) -> Tuple[str, bool]:
    text, passed = _threadcheck.run(command, document, _arguments(values))
    return text, passed


def _json_with_files(command: str, values: Dict[str, Any], files: Dict[str, Optional[PathLike]]) -> Any:
    """The command's JSON; each document named in ``files`` rendered and written to its path,
    all of them together once every one rendered (a failure writes none)."""
    rendered: List[Tuple[str, str]] = []
    for document, path in files.items():
        if path is not None:
            rendered.append((_os.fspath(path), _run(command, document, values)[0]))
    text, _passed = _run(command, "json", values)
    # The command line's writer: no input replaced, no two outputs on one file, all or none.
    _threadcheck.write_files(rendered)
    return _json.loads(text)


def render(command: str, document: str, **arguments: Any) -> str:
    """A command's document as a string: ``render("verify", "svg", thread="M10x1.5-6g")``.

    ``command`` is ``verify``, ``passes``, ``limits``, ``compare``, ``fit``, ``correct``,
    ``capability`` or ``mill``; ``document`` is ``json``, ``text`` (what the command prints),
    ``svg``, ``html`` or ``fix`` (the program with its correction written in; ``verify`` and
    ``correct``); the arguments are the command's function's keyword arguments.
    """
    return _run(command, document, arguments)[0]


def verify(thread: Optional[Threads] = None, program: Optional[str] = None, dialect: Optional[str] = None,
           insert: Optional[str] = None, final_x: Optional[float] = None, internal: bool = False,
           infeed: Optional[str] = None, passes: Optional[int] = None,
           blank_diameter: Optional[float] = None, gauge_only: bool = False,
           allow_nonstandard: bool = False, program_name: Optional[str] = None,
           default_units: Optional[str] = None, main: Optional[str] = None,
        linuxcnc_release: Optional[str] = None, coating: Optional[float] = None,
        coating_limits: Optional[str] = None,
           engagement: Optional[float] = None,
           insert_toml: Optional[str] = None, tools: Optional[str] = None,
           gcode_system: Optional[str] = None,
           schedule: Optional[str] = None, depths: Optional[Sequence[float]] = None,
           first_depth: Optional[float] = None, min_depth: Optional[float] = None,
           finish: Optional[float] = None, spring: Optional[int] = None,
           taper: Optional[float] = None, chamfer: Optional[float] = None,
           units: Optional[str] = None, machine: Optional[str] = None,
           clearance_angle: Optional[float] = None, no_pass_metrics: bool = False,
           operation: Optional[int] = None,
        machine_type: Optional[str] = None, block_delete: bool = False, stock_bottom: Optional[float] = None,
           svg: Optional[PathLike] = None, html: Optional[PathLike] = None,
           fix: Optional[PathLike] = None) -> VerifyReport:
    """``threadcheck verify --json -``.

    ``thread`` is a designation with its class (``"M20x1.5-6g"``), or a list of them, one per
    threading operation of ``program`` (``operation``, from 1, checks that one alone). With a
    program and no ``thread``, each operation's thread is the one the program names (the nearest
    comment above it), else the standard size it cuts; each operation's ``designation_from``
    (``"given"``, ``"comment"``, ``"inferred"``) and ``designation_line`` say which. A program's
    report has an entry per thread it makes, each with ``made``: ``"turned"``, ``"tapped"`` (a
    tapping cycle, as :func:`tap` reports it) or ``"milled"`` (as :func:`thread_mill` reports it;
    ``tools`` must name the thread mill, else it is not checked and fails).
    ``program`` is the program's **text** (a path is refused
    by name); ``program_name`` is what messages call it and, by its extension, chooses the dialect
    when ``dialect`` is not given (``.ngc`` linuxcnc, ``.mpf``/``.spf`` sinumerik, else fanuc,
    stated in ``notes``). Without a program a plan is generated and ``final_x`` (or the solved
    middle of the tolerance) is verified.
    ``insert`` is ``"full"``, ``"partial"``, ``"partial:R"`` or an insert file's path;
    ``insert_toml`` an insert file's text; ``tools`` a tool table's TOML text (T number to
    insert); without them a program is verified with a partial insert and the report says so.
    ``infeed`` takes the command line's words: ``"radial"``, ``"flank"``, ``"flank:27"``,
    ``"modified"`` (the default: half the thread angle less 0.5°), ``"alternating"``,
    ``"alternating:ANGLE"``; ``schedule`` ``"constant-area"``, ``"constant-depth"``,
    ``"sandvik"``, or ``depths`` the cumulative radial depths, mm.
    ``default_units`` (``"mm"``/``"inch"``) reads a program that sets no units as an inch or
    metric control would; ``main`` (``"O3101"``) picks the main program of a text that holds
    several O-programs. ``linuxcnc_release`` (``"current"``/``"before-2.9"``) chooses the
    comparison rules of a ``linuxcnc`` program; ``gcode_system`` (``"a"``, ``"b"``, ``"c"``) the
    G-code system a Fanuc control is set to (B: G78 the threading cycle; C: G78 the multiple
    one); ``machine_type`` (``"lathe"``/``"mill"``/``"mill-turn"``) the machine the program runs on (default: the
    program's own evidence, else a lathe; the report's ``machine`` says which and why). ``block_delete``
    skips the blocks that begin with ``/`` (the control's switch on; off, the default, runs them,
    stated). ``coating`` (mm) checks against the limits
    before a coat of that thickness; ``coating_limits`` is ``"before"`` (the standards' default:
    the class applies before coating, the coated thread within the basic profile) or ``"after"``. ``machine`` is a machine profile's TOML text (or
    ``"training-lathe"``). ``svg``, ``html`` and ``fix`` write the picture, the page and the
    corrected program to those paths.
    The dict has ``verdict`` (``"pass"``/``"fail"``); a program's report has ``operations``,
    each with ``suggested_final_x`` (the last pass's X for mid-tolerance d2, also when nothing
    is cut) and ``correction`` (the program's own word) when d2 is off.
    """
    values = dict(locals())
    files = {"svg": values.pop("svg"), "html": values.pop("html"), "fix": values.pop("fix")}
    report: VerifyReport = _json_with_files("verify", values, files)
    return report


def limits(designation: Optional[str] = None, allow_nonstandard: bool = False,
           coating: Optional[float] = None, coating_limits: Optional[str] = None,
        thread: Optional[str] = None, rolled: bool = False,
        blank: Optional[float] = None) -> LimitsReport:
    """``threadcheck limits DESIGNATION --json``: basic sizes and limits of size, mm.

    The designation is given as ``designation`` or as ``thread``, as the other functions take it.
    ``coating`` (mm) gives the limits to cut to before a coat of that thickness;
    ``coating_limits`` (``"before"``, the standards' default, or ``"after"``) which limits the
    class applies to. ``rolled`` adds a rolled external thread's blank (``rolled`` in the
    report), ``blank`` (in the designation's units) the major diameter that blank forms.
    """
    report: LimitsReport = _json.loads(_run("limits", "json", dict(locals()))[0])
    return report


def passes(thread: Optional[Threads] = None, program: Optional[str] = None,
           dialect: Optional[str] = None, insert: Optional[str] = None,
           final_x: Optional[float] = None, internal: bool = False, infeed: Optional[str] = None,
           passes: Optional[int] = None, blank_diameter: Optional[float] = None,
           allow_nonstandard: bool = False, program_name: Optional[str] = None,
           default_units: Optional[str] = None, main: Optional[str] = None,
           linuxcnc_release: Optional[str] = None, insert_toml: Optional[str] = None,
           schedule: Optional[str] = None, depths: Optional[Sequence[float]] = None,
           first_depth: Optional[float] = None, min_depth: Optional[float] = None,
           finish: Optional[float] = None, spring: Optional[int] = None,
           taper: Optional[float] = None, chamfer: Optional[float] = None,
        coating: Optional[float] = None, coating_limits: Optional[str] = None,
        engagement: Optional[float] = None, gcode_system: Optional[str] = None,
        clearance_angle: Optional[float] = None, machine: Optional[str] = None,
        units: Optional[str] = None,
        machine_type: Optional[str] = None, block_delete: bool = False) -> PassesReport:
    """``threadcheck passes --json``: the passes of a generated plan or of a program's text.

    The arguments are ``verify``'s; a program needs no thread.
    """
    report: PassesReport = _json.loads(_run("passes", "json", dict(locals()))[0])
    return report


def correct(thread: str, program: Optional[str] = None, dialect: Optional[str] = None,
            insert: Optional[str] = None, final_x: Optional[float] = None,
            internal: bool = False, infeed: Optional[str] = None, passes: Optional[int] = None,
            blank_diameter: Optional[float] = None, allow_nonstandard: bool = False,
            program_name: Optional[str] = None, default_units: Optional[str] = None,
            main: Optional[str] = None, linuxcnc_release: Optional[str] = None,
        coating: Optional[float] = None, coating_limits: Optional[str] = None,
        engagement: Optional[float] = None, measured_m: Optional[float] = None,
            wire: Optional[float] = None, measured_d2: Optional[float] = None,
            gauge: Optional[str] = None, pickup_z: Optional[float] = None,
            insert_toml: Optional[str] = None, gcode_system: Optional[str] = None,
            operation: Optional[int] = None,
        chamfer: Optional[float] = None, clearance_angle: Optional[float] = None,
        depths: Optional[Sequence[float]] = None, finish: Optional[float] = None,
        first_depth: Optional[float] = None, machine: Optional[str] = None,
        min_depth: Optional[float] = None, schedule: Optional[str] = None,
        spring: Optional[int] = None, taper: Optional[float] = None, units: Optional[str] = None,
        machine_type: Optional[str] = None, block_delete: bool = False,
            html: Optional[PathLike] = None, fix: Optional[PathLike] = None) -> CorrectReport:
    """``threadcheck correct --json``: what was measured on the part, turned into the change.

    ``thread`` and the plan or ``program`` arguments are ``verify``'s. Give one measurement:
    ``measured_m`` (mm over three wires) with ``wire`` (their diameter, mm), ``measured_d2``
    (mm), or ``gauge`` (``"go-fails"``, ``"nogo-enters"``, ``"ok"``); ``pickup_z`` (mm from the
    program's Z0) adds a pick-up's start angle and Z shift; ``operation`` (from 1) says which
    thread was measured when the program cuts several. The dict has ``verdict``
    (``"pass"`` in tolerance), ``measured``, ``delta_pitch_diameter``, ``suggested_final_x``,
    ``correction`` (the program's word), ``wear_offset`` and ``pickup``. ``html`` and ``fix``
    write the page and the corrected program.
    """
    values = dict(locals())
    files = {"html": values.pop("html"), "fix": values.pop("fix")}
    report: CorrectReport = _json_with_files("correct", values, files)
    return report


def capability(thread: str, program: Optional[str] = None, dialect: Optional[str] = None,
               insert: Optional[str] = None, final_x: Optional[float] = None,
               internal: bool = False, infeed: Optional[str] = None,
               passes: Optional[int] = None, blank_diameter: Optional[float] = None,
               allow_nonstandard: bool = False, program_name: Optional[str] = None,
               default_units: Optional[str] = None, main: Optional[str] = None,
        linuxcnc_release: Optional[str] = None, coating: Optional[float] = None,
        coating_limits: Optional[str] = None,
           engagement: Optional[float] = None,
               x_sigma: Optional[float] = None, tip_radius_tol: Optional[float] = None,
               wear_per_part: Optional[float] = None, samples: Optional[int] = None,
               seed: Optional[int] = None, gauge_only: bool = False,
               insert_toml: Optional[str] = None, gcode_system: Optional[str] = None,
               operation: Optional[int] = None,
        chamfer: Optional[float] = None, clearance_angle: Optional[float] = None,
        depths: Optional[Sequence[float]] = None, finish: Optional[float] = None,
        first_depth: Optional[float] = None, machine: Optional[str] = None,
        min_depth: Optional[float] = None, schedule: Optional[str] = None,
        spring: Optional[int] = None, taper: Optional[float] = None, units: Optional[str] = None,
        machine_type: Optional[str] = None, block_delete: bool = False,
               svg: Optional[PathLike] = None, html: Optional[PathLike] = None) -> CapabilityReport:
    """``threadcheck capability --json``: a seeded Monte Carlo of the parts a program cuts.

    The thread, plan and program arguments are ``verify``'s.

    ``x_sigma`` is the X repeatability (one sigma on the diameter, mm), ``tip_radius_tol`` a
    partial insert's tip radius tolerance (± mm, uniform), ``wear_per_part`` the radial wear per
    part (mm), ``samples`` (10 000) and ``seed`` (1) the Monte Carlo's; ``gauge_only`` leaves
    form checks out of each part's verdict; ``operation`` (from 1) picks one thread of a program
    that cuts several. The dict has ``sizes`` (mean, sigma, Cp, Cpk, ppm
    per checked size), ``pass_share``, ``parts_per_edge``, ``best_final_x`` and the d2
    ``histogram``. ``svg`` and ``html`` write the histogram and the page.
    """
    values = dict(locals())
    files = {"svg": values.pop("svg"), "html": values.pop("html")}
    report: CapabilityReport = _json_with_files("capability", values, files)
    return report


def fit(thread: str, bolt_program: Optional[str] = None, bolt_dialect: Optional[str] = None,
        bolt_final_x: Optional[float] = None, bolt_insert: Optional[str] = None,
        nut_program: Optional[str] = None, nut_dialect: Optional[str] = None,
        nut_final_x: Optional[float] = None, nut_insert: Optional[str] = None,
        allow_nonstandard: bool = False, svg: Optional[PathLike] = None) -> FitReport:
    """``threadcheck fit --json``: a bolt and a nut cut in the computer and assembled.

    ``thread`` is a fit designation (``"M10x1.5-6H/6g"``). Each side is a program's text
    (``bolt_program``, ``nut_program``, with their dialects, default fanuc) or a plan
    (``bolt_final_x``, ``nut_final_x``; default mid-tolerance); inserts as ``verify`` takes
    them (default partial). The dict has ``verdict`` (``"fits"``/``"interferes"``),
    ``clearance_um`` and both sides' reports. ``svg`` writes the pair's picture.
    """
    values = dict(locals())
    files = {"svg": values.pop("svg")}
    report: FitReport = _json_with_files("fit", values, files)
    return report


def compare(thread: str, insert: Optional[str] = None, final_x: Optional[float] = None,
            internal: bool = False, allow_nonstandard: bool = False,
            infeed: Optional[str] = None, schedule: Optional[str] = None,
            modified: Optional[Sequence[float]] = None, insert_toml: Optional[str] = None,
        blank_diameter: Optional[float] = None, chamfer: Optional[float] = None,
        clearance_angle: Optional[float] = None, coating: Optional[float] = None,
        coating_limits: Optional[str] = None, default_units: Optional[str] = None,
        depths: Optional[Sequence[float]] = None, dialect: Optional[str] = None,
        engagement: Optional[float] = None, finish: Optional[float] = None,
        first_depth: Optional[float] = None, gcode_system: Optional[str] = None,
        linuxcnc_release: Optional[str] = None, machine: Optional[str] = None,
        main: Optional[str] = None, min_depth: Optional[float] = None,
        passes: Optional[int] = None, program: Optional[str] = None,
        program_name: Optional[str] = None, spring: Optional[int] = None,
        taper: Optional[float] = None, units: Optional[str] = None,
        machine_type: Optional[str] = None, block_delete: bool = False,
            html: Optional[PathLike] = None) -> CompareReport:
    """``threadcheck compare --json``: the thread with every infeed strategy and schedule.

    The plan's arguments are ``verify``'s (a program is refused: it fixes its own passes).
    ``infeed`` (``"radial"``, ``"flank:27"`` …) and ``schedule`` (``"constant-area"`` …)
    compare that one alone; ``modified`` lists the modified-flank angles (default half the
    thread angle less 0.5° and 3°). The dict has ``strategies`` and ``recommended``. ``html``
    writes the page with every strategy's picture.
    """
    values = dict(locals())
    files = {"html": values.pop("html")}
    report: CompareReport = _json_with_files("compare", values, files)
    return report


def mill(program: str, target: str, tool_diameter: float, dialect: Optional[str] = None,
         tolerance: Optional[float] = None, n_order: bool = False,
         program_name: Optional[str] = None, svg: Optional[PathLike] = None,
         default_units: Optional[str] = None, gcode_system: Optional[str] = None,
         machine_type: Optional[str] = None, main: Optional[str] = None,
         linuxcnc_release: Optional[str] = None, block_delete: bool = False) -> MillReport:
    """``threadcheck mill --json``: a milling program's text against a target curve.

    ``target`` is the target's TOML text (``x``, ``y`` in ``t`` and ``z``, ``t``, ``material``,
    optional ``z``), ``tool_diameter`` and ``tolerance`` (0.01) in mm. The dict has
    ``verdict``, ``gouge_max``, ``leftover_max`` and the levels. ``svg`` writes the worst
    level's picture.
    The program is read as ``verify`` reads it: ``default_units``, ``gcode_system``,
    ``machine_type``, ``main``, ``linuxcnc_release`` and ``block_delete`` mean what they mean
    there.
    """
    values = dict(locals())
    files = {"svg": values.pop("svg")}
    report: MillReport = _json_with_files("mill", values, files)
    return report


def tap(program: str, tools: Optional[str] = None, dialect: Optional[str] = None, program_name: Optional[str] = None,
        allow_nonstandard: bool = False, default_units: Optional[str] = None,
        gcode_system: Optional[str] = None,
        machine_type: Optional[str] = None, stock_bottom: Optional[float] = None,
        tap: Optional[str] = None, material: Optional[str] = None,
        tap_kind: Optional[str] = None, machine: Optional[str] = None,
        main: Optional[str] = None, linuxcnc_release: Optional[str] = None,
        block_delete: bool = False) -> TapReport:
    """``threadcheck tap --json``: a program's tapping cycles (G84, G74) against their taps and
    the drills that made the holes.

    ``program`` is the program's text, ``tools`` the tool table's TOML text: each tap as
    ``6 = "tap:M10x1.5-6H"`` (``:PITCHES`` adds its chamfer length, default 2.5), each drill as
    ``5 = "drill:8.5"`` (``drill:8.5:135`` with its point's included angle, default 118°); a tap or
    drill the table does not name is taken from the program's comments (``(TAP M10X1.5)``,
    ``(DRILL 8.5)``), else the tap is the standard size of its lead over its drill.
    ``stock_bottom`` (the stock's bottom face's Z) makes a hole whose drill passes it a through
    hole. ``tap`` (``"M10x1.5-6H"``) is the tap of the cycles whose tool is not known (no T, or one the
    table does not name; a table's
    ``in_spindle = T`` names the tool in the spindle at the start instead). Each hole in ``holes`` has its ``cycle``, ``tap``, ``drill`` and
    ``checks`` (``drill_diameter`` against D1 of the tap's class, ``feed`` against the lead,
    ``depth`` left for the chamfer, ``spindle``) and ``drill_that_passes`` (the middle of D1 and
    the nearest stocked drill within it: ISO 2306's tap drill for ISO metric taps); the dict's
    ``pass`` is the verdict. A form tap is ``"form-tap:M10x1.5-6H"``. ``material`` (``"c45"``,
    ``"gg-25"``, …) adds each cutting tap's ``torque`` by the tap maker's equation, for taps of
    ``tap_kind`` (``"hand-plug"``, ``"hand-bottoming"``, ``"spiral-fluted"``, the default, or
    ``"spiral-pointed"``). ``machine`` is a machine file's TOML text: its ``type`` reads the
    program, its ``spindle_torque_nm`` and ``spindle_power_kw`` hold each torque (``exceeds_spindle``
    and a warning note when the tap asks more), its ``tap_holder = "floating"`` lets the ``feed``
    check take an under-feed of up to 5 % (a tension-compression holder), said in the hole's notes.
    The program is read as ``verify`` reads it: ``default_units``, ``gcode_system``,
    ``machine_type``, ``main``, ``linuxcnc_release`` and ``block_delete`` mean what they mean
    there.
    """
    report: TapReport = _json.loads(_run("tap", "json", dict(locals()))[0])
    return report


def thread_mill(program: str, thread: Optional[str] = None, cutter_diameter: Optional[float] = None, cutter_angle: Optional[float] = None,
                cutter_tip_radius: Optional[float] = None, cutter_rows: Optional[int] = None,
                cutter_row_pitch: Optional[float] = None, blank_diameter: Optional[float] = None,
                comp_radius: Optional[float] = None, dialect: Optional[str] = None,
                program_name: Optional[str] = None, allow_nonstandard: bool = False,
        tools: Optional[str] = None, default_units: Optional[str] = None,
        cutter_teeth: Optional[int] = None, gcode_system: Optional[str] = None,
        machine_type: Optional[str] = None, main: Optional[str] = None,
        linuxcnc_release: Optional[str] = None, block_delete: bool = False) -> ThreadMillReport:
    """``threadcheck thread-mill --json``: the thread a thread-milling program leaves.

    ``program`` is the program's text (helical G2/G3 in G17, the cutter centre's path),
    ``thread`` the designation with its class (default: the one the program names in a comment
    above its helices, else the standard size they cut), ``default_units`` (``"mm"``/``"inch"``)
    the units of a program that sets none, ``cutter_diameter`` (mm, over the tooth's tip),
    ``cutter_angle`` (60°) and ``cutter_tip_radius`` (0) the tooth, or ``tools`` a tool table's
    TOML text naming the helices' T as a thread mill, else the thread mill the program's
    comments name for that T (a CAM post's tool list, ``(T5  D=8. CR=0. - thread mill)``; the
    shape options then raise ``ValueError``: they need ``cutter_diameter``); ``cutter_rows`` (1) and
    ``cutter_row_pitch`` (mm) a multi-form cutter's rows; ``blank_diameter`` the bore (default
    the middle of D1); ``comp_radius`` the D register G41/G42 apply (mm); ``cutter_teeth`` the
    cutter's teeth, for each helix's feed per tooth in ``feeds``. The dict has ``measured``,
    ``tooth_profile`` (the cutter's tooth alone), ``distortion_pitch_diameter_um``,
    ``distortion_flank_angles_deg``, ``helices``, ``checks`` (``lead`` among them) and ``pass``.
    The program is read as ``verify`` reads it: ``default_units``, ``gcode_system``,
    ``machine_type``, ``main``, ``linuxcnc_release`` and ``block_delete`` mean what they mean
    there.
    """
    report: ThreadMillReport = _json.loads(_run("thread-mill", "json", dict(locals()))[0])
    return report
