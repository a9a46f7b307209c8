"""The reports' shapes as ``TypedDict``s, one per command: the top-level keys of the JSON that
``docs/json.md`` documents (lengths in mm, deviations in µm, angles in degrees). Nested objects
are plain dicts; ``total=False`` where a key belongs to one form of a report only (a plan's
verify report against a program's)."""

from __future__ import annotations

from typing import Any, Dict, List, Optional, TypedDict

Json = Dict[str, Any]


class Check(TypedDict, total=False):
    """One check of a verify report (``checks[]``)."""

    feature: str
    kind: str
    value: Optional[float]
    min: Optional[float]
    max: Optional[float]
    ok: bool
    deviation_um: float
    note: str


class Correction(TypedDict, total=False):
    """The word that sets an operation's final depth and its value for mid-tolerance d2."""

    word: str
    value: float
    was: float
    units: str
    line: int
    column: int
    editable: bool
    written: str
    means: Any
    text: str
    also: List[Json]
    deeper: List[Json]


class _Report(TypedDict, total=False):
    """The keys a verify report of one thread has (a plan's, or a program operation's)."""

    thread: Json
    insert: Json
    plan: Json
    passes: List[Json]
    measured: Json
    limits: Json
    checks: List[Check]
    verdict: str
    gauge_only: bool
    helix_angle: float
    process: Optional[Json]
    suggested_final_x: Optional[float]
    lead_deviation: Optional[Json]
    correction: Optional[Correction]
    hints: List[Json]
    notes: List[Json]
    deviation: Json


class OperationReport(_Report, total=False):
    """One operation of a program's verify report: a full report and its ``operation``, or
    (nothing cut) ``reason`` and ``suggested_final_x``."""

    operation: Json
    reason: str
    designation_from: str
    designation_line: Optional[int]
    made: str


class VerifyReport(_Report, total=False):
    """``verify --json -``: a plan's report (the keys of :class:`OperationReport` but
    ``operation``), or a program's: ``program``, ``dialect``, ``verdict``, ``operations``."""

    program: str
    dialect: str
    operations: List[OperationReport]
    skipped_blocks: int
    read_past_blocks: int
    machine: Json


class _LimitsRequired(TypedDict):
    """``limits D --json``: the keys always there."""

    designation: str
    form: str
    nominal_diameter: float
    pitch: float
    lead: float
    starts: int
    hand: str
    nonstandard: bool
    basic: Json
    external: Optional[Json]
    internal: Optional[Json]


class LimitsReport(_LimitsRequired, total=False):
    """``limits D --json``; ``rolled`` with ``rolled=True`` or a ``blank``."""

    rolled: Json


class PassesReport(TypedDict, total=False):
    """``passes --json``: ``passes`` always; ``operations`` for a program."""

    thread: Optional[Json]
    thread_start: float
    thread_end: float
    passes: List[Json]
    operations: List[Json]
    notes: List[Json]
    read_past_blocks: int
    machine: Json


class CorrectReport(TypedDict):
    """``correct --json``."""

    designation: str
    kind: str
    verdict: str
    pitch_diameter_limits: Json
    target_pitch_diameter: float
    computed: Json
    measured: Json
    delta_pitch_diameter: Optional[float]
    suggested_final_x: Optional[float]
    correction: Optional[Correction]
    wear_offset: Optional[Json]
    pickup: Optional[Json]
    notes: List[Json]


class CapabilityReport(TypedDict):
    """``capability --json``."""

    designation: str
    kind: str
    final_x: float
    x_sigma: float
    tip_radius_tol: float
    wear_per_part: float
    samples: int
    seed: int
    sizes: List[Json]
    pass_share: float
    parts_per_edge: Optional[Json]
    best_final_x: float
    best_parts_per_edge: Optional[Json]
    best_correction: Optional[Correction]
    cpk_uncertainty: Optional[float]
    histogram: Json
    notes: List[Json]


class FitReport(TypedDict):
    """``fit --json``."""

    thread: str
    verdict: str
    clearance_um: float
    engagement_depth: float
    flank_overlap: float
    bolt: Json
    nut: Json


class CompareReport(TypedDict):
    """``compare --json``."""

    final_x: float
    reports: List[Json]
    strategies: List[Json]
    recommended: Json


class TapReport(TypedDict):
    """``tap --json``: every tapping cycle with its tap, its drill and its checks."""

    program: str
    dialect: str
    holes: List[Json]
    drills: int
    notes: List[Json]
    machine: Json


class ThreadMillReport(TypedDict):
    """``thread-mill --json``: the milled thread, measured and checked."""

    program: str
    designation: str
    kind: str
    cutter: Json
    cutter_ratio: float
    helices: List[Json]
    blank_diameter: float
    measured: Json
    tooth_profile: Json
    distortion_pitch_diameter_um: float
    distortion_flank_angles_deg: List[float]
    limits: Json
    checks: List[Check]
    verdict: str
    notes: List[str]


class MillReport(TypedDict):
    """``mill --json``."""

    program: str
    dialect: str
    tool_diameter: float
    tolerance: float
    target: Json
    verdict: str
    gouge_max: float
    gouge_at: Json
    leftover_max: float
    leftover_at: Json
    levels: List[Json]
    worst_level: float
    profile: List[Json]
    notes: List[Json]
