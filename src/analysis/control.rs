//! Before the machine (issue 63): what the control will refuse and what a post got wrong, each
//! at its line, with the control's own message where it publishes one
//! ([`crate::gcode::alarm`]). The reader's events (cutter compensation at a threading move, a
//! tap dragged sideways) join what the operations show: the spindle stopped or at S0 at a
//! threading operation or a tap, a tap's zero feed, a tap's feed written in the other feed
//! mode's convention, and a threading pass that starts too close to the part for the Z axis to
//! reach the synchronised feed (Fanuc's run-in formula, its servo time constant a named
//! default unless the machine file gives it).
//!
//! An error fails the program (the control refuses the block, or the cut breaks the tool); a
//! warning is said and leaves the verdict to the checks.

use crate::analysis::made::Process;
use crate::analysis::tap::{TapFeature, TapReport};
use crate::gcode::{Alarm, ControlRule, Dialect, HoleKind, Level, Operation, Program, SpindleDir};
use serde::Serialize;

/// The Z axis's servo time constant assumed where the machine file gives none, seconds: the
/// value Fanuc's lathe manuals use in their run-in formula's example (a named default).
pub const ASSUMED_SERVO_TIME_CONSTANT_S: f64 = 0.033;

/// The lead error allowed in the first thread, as a fraction (Fanuc's formula's `a`; a named
/// default).
pub const ALLOWED_LEAD_ERROR: f64 = 0.01;

/// One finding: a rule at a place.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ControlFinding {
    /// The rule's id (`control.spindle_stopped`).
    pub rule: &'static str,
    /// Error or warning.
    pub level: Level,
    /// The operation it concerns: a turned thread, a tapped hole or a milled one.
    pub made: Process,
    /// The block's code (`G76`, `G84`, `G33.1`).
    pub code: String,
    /// Its line.
    pub line: usize,
    /// Its column.
    pub column: usize,
    /// The subprogram file the line is in, when not the program's own.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// The control's own message, where it publishes one.
    pub alarm: Option<Alarm>,
    /// What is wrong, with the values.
    pub message: String,
    /// What the check assumed (a machine's figure the machine file did not give).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub assumed: Option<String>,
}

impl ControlFinding {
    fn new(
        dialect: Dialect,
        rule: ControlRule,
        made: Process,
        code: &str,
        at: (usize, usize),
        message: String,
    ) -> Self {
        ControlFinding {
            rule: rule.id(),
            level: rule.level(),
            made,
            code: code.to_string(),
            line: at.0,
            column: at.1,
            file: None,
            alarm: crate::gcode::alarm(dialect, rule, code),
            message,
            assumed: None,
        }
    }
}

/// Whether any finding is an error (the program then fails).
pub fn any_error(findings: &[ControlFinding]) -> bool {
    findings.iter().any(|f| f.level == Level::Error)
}

/// The findings of a program read in `dialect`: the reader's events, then each threading
/// operation's, then each tapping cycle's (with its tap's lead where the tapping check found
/// it), in program order within each. `servo_time_constant` is the machine file's (seconds).
pub fn before_machine(
    prog: &Program,
    dialect: Dialect,
    tapped: Option<&TapReport>,
    machine: Option<&crate::analysis::process::MachineProfile>,
) -> Vec<ControlFinding> {
    let axis = Axis {
        servo_time_constant: machine.and_then(|m| m.servo_time_constant_s),
        acceleration: machine.and_then(|m| m.z_acceleration_mm_s2),
    };
    let mut out: Vec<ControlFinding> = prog
        .control
        .iter()
        .map(|e| {
            let tap = matches!(e.code.as_str(), "G33.1" | "G84" | "G74");
            let made = if tap { Process::Tapped } else { Process::Turned };
            let mut f =
                ControlFinding::new(dialect, e.rule, made, &e.code, (e.line, e.column), e.detail.clone());
            f.file.clone_from(&e.file);
            f
        })
        .collect();
    for op in &prog.operations {
        out.extend(turned(op, dialect, axis));
    }
    for h in prog.holes.iter().filter(|h| h.kind == HoleKind::Tap) {
        let at = (h.line, h.column);
        let mut flag = |rule: ControlRule, message: String| {
            let mut f = ControlFinding::new(dialect, rule, Process::Tapped, &h.code, at, message);
            f.file.clone_from(&h.source_file);
            out.push(f);
        };
        // A Haas control turns the spindle itself for its tapping cycles (the tapping check
        // says so); a rigid tap's spindle is the cycle's.
        let starts_itself = dialect == Dialect::Haas || h.rigid;
        if h.spindle_dir == Some(SpindleDir::Stopped) && !starts_itself {
            flag(
                ControlRule::SpindleStopped,
                format!(
                    "{} with the spindle stopped (M5): the tap is pushed into the hole without turning",
                    h.code
                ),
            );
        }
        if h.spindle == Some(0.0) && !h.constant_surface_speed {
            flag(ControlRule::SpindleSpeedZero, format!("{} at S0: the spindle does not turn", h.code));
        }
        // A Haas lathe's live-tool tapping (G95, G186) turns the live tool, not the spindle
        // G96 governs.
        let live_tool = dialect == Dialect::Haas && matches!(h.code.as_str(), "G95" | "G186");
        if h.constant_surface_speed && !live_tool {
            flag(
                ControlRule::CssAtTap,
                format!(
                    "{} under G96 (constant surface speed): S{} is a surface speed, and the spindle turns at what the hole's diameter makes of it{}; {}: give the tap its speed with G97 S… before the cycle",
                    h.code,
                    h.spindle.map_or("?".to_string(), crate::ground::fmt::fmt_num),
                    if h.x.is_some_and(|x| x.abs() < 1e-9) {
                        " (on the centre line, X0, the fastest the clamp allows: G50 S, else the spindle's top speed)"
                    } else {
                        ""
                    },
                    if h.feed_per_rev {
                        "the tap cuts at a speed the program never chose"
                    } else {
                        "a feed per minute no longer matches the spindle's speed, and the tap is torn"
                    }
                ),
            );
        }
        if h.feed == Some(0.0) {
            flag(
                ControlRule::FeedZero,
                format!("{} with {}0: the tap is given no feed", h.code, h.feed_word),
            );
        }
    }
    if let Some(t) = tapped {
        out.extend(t.holes.iter().filter_map(|th| feed_convention(dialect, th)));
        if let Some((m, max)) = machine.and_then(|m| Some((m, m.max_feed_mm_min?))) {
            out.extend(t.holes.iter().filter_map(|th| feed_limit(dialect, th, &m.name, max)));
        }
    }
    out
}

/// A tap whose synchronised feed S × lead the machine's axes cannot follow (LinuxCNC #4391:
/// "the thread is ruined"); `max` the machine file's fastest feed, mm/min.
fn feed_limit(
    dialect: Dialect,
    th: &crate::analysis::tap::TappedHole,
    machine: &str,
    max: f64,
) -> Option<ControlFinding> {
    let h = &th.cycle;
    let s = h.spindle.filter(|s| *s > 0.0 && !h.constant_surface_speed)?;
    let feed = s * th.tap.lead;
    if feed <= max + 1e-9 {
        return None;
    }
    let num = crate::ground::fmt::fmt_num;
    let mut c = ControlFinding::new(
        dialect,
        ControlRule::SyncFeedLimit,
        Process::Tapped,
        &h.code,
        (h.line, h.column),
        format!(
            "{} at S{} × lead {} = {} mm/min, beyond the fastest feed the axes follow, {} mm/min ({machine}): the tap strips its thread or breaks; at most S{} for this lead",
            h.code,
            num(s),
            num(th.tap.lead),
            num((feed * 1000.0).round() / 1000.0),
            num(max),
            num((max / th.tap.lead).floor())
        ),
    );
    c.file.clone_from(&h.source_file);
    Some(c)
}

/// The findings of a thread-milled thread: each move after its last helix that cuts the
/// finished thread, with how deep, and the moves under compensation that were not judged said
/// once.
pub fn milled(r: &crate::analysis::thread_mill::ThreadMillReport, dialect: Dialect) -> Vec<ControlFinding> {
    let num = crate::ground::fmt::fmt_num;
    let crossings = r.crossings.iter().map(|c| {
        let how = match c.other_hand {
            Some(h) => format!("is a {}-hand helix on a {}-hand thread", h.name(), h.other().name()),
            None => format!(
                "moves {} mm per revolution where the thread's lead is {} mm",
                num((c.lead * 1e4).round() / 1e4),
                num(c.thread_lead)
            ),
        };
        ControlFinding::new(
            dialect,
            ControlRule::MillReturnHelix,
            Process::Milled,
            c.code,
            (c.line, 1),
            format!(
                "the helix at line {} {how}: it drifts {:.3} mm off the groove it starts in, with its teeth {:.3} mm past the thread's crest: it cuts through the flanks; return along the thread's own helix (the same hand and lead) or lift the teeth out of the groove first",
                c.line, c.drift, c.depth
            ),
        )
    });
    let mut out: Vec<ControlFinding> = crossings.collect();
    let gouges = r
        .after_finish
        .gouges
        .iter()
        .map(|g| {
            let what = match (g.rapid, g.along_z) {
                (true, true) => "a rapid along Z",
                (false, true) => "a feed along Z",
                (true, false) => "a rapid in the plane",
                (false, false) => "a move in the plane",
            };
            ControlFinding::new(
                dialect,
                ControlRule::MillGouge,
                Process::Milled,
                g.code,
                (g.line, 1),
                format!(
                    "{what} after the last helix (line {}) with the cutter's teeth {:.3} mm past the finished thread's crest: it cuts the thread just made; leave the groove toward the hole's axis (away from an external thread's) before moving along Z",
                    r.helices.last().map_or(0, |h| h.line),
                    g.depth
                ),
            )
        });
    out.extend(gouges);
    out
}

/// A tap's feed in the other feed mode's convention: under a per-minute mode F is the lead,
/// under a per-revolution mode F is S × lead (FreeCAD's posts, #5714 and #31599).
fn feed_convention(dialect: Dialect, th: &crate::analysis::tap::TappedHole) -> Option<ControlFinding> {
    let h = &th.cycle;
    let k = th.checks.iter().find(|k| k.feature == TapFeature::Feed && !k.ok)?;
    let f = k.value?;
    let lead = th.tap.lead;
    let s = h.spindle.filter(|s| *s > 0.0 && !h.constant_surface_speed)?;
    let num = crate::ground::fmt::fmt_num;
    let message = if !h.feed_per_rev && (f - lead).abs() <= 0.0005 {
        format!(
            "{} F{} is the lead, written as if the feed were per revolution; under the per-minute feed mode in force F must be S × lead = {} × {} = {} mm/min: the tap is fed {} times too slowly",
            h.code,
            num(f),
            num(s),
            num(lead),
            num(s * lead),
            num((s * lead / f).round())
        )
    } else if h.feed_per_rev && (f - s * lead).abs() <= 0.5 {
        format!(
            "{} F{} is S × lead, written as if the feed were per minute; under the per-revolution feed mode in force F must be the lead, {} mm: the tap is fed {} times too fast",
            h.code,
            num(f),
            num(lead),
            num((f / lead).round())
        )
    } else {
        return None;
    };
    let mut c = ControlFinding::new(
        dialect,
        ControlRule::TapFeedConvention,
        Process::Tapped,
        &h.code,
        (h.line, h.column),
        message,
    );
    c.file.clone_from(&h.source_file);
    Some(c)
}

/// A threading operation's findings: the spindle stopped or at S0, and a run-in shorter than
/// the Z axis needs to reach the synchronised feed.
fn turned(op: &Operation, dialect: Dialect, axis: Axis) -> Vec<ControlFinding> {
    let at = (op.source_line, op.source_column);
    let mut out = Vec::new();
    let mut push = |rule: ControlRule, message: String, assumed: Option<String>| {
        let mut f = ControlFinding::new(dialect, rule, Process::Turned, &op.cycle, at, message);
        f.file.clone_from(&op.source_file);
        f.assumed = assumed;
        out.push(f);
    };
    if op.spindle.dir == Some(SpindleDir::Stopped) {
        push(
            ControlRule::SpindleStopped,
            format!(
                "{} with the spindle stopped (M5): the threading feed waits for the spindle's one-revolution signal, which never comes",
                op.cycle
            ),
            None,
        );
    }
    if op.spindle.s == Some(0.0) && !op.spindle.constant_surface_speed {
        push(ControlRule::SpindleSpeedZero, format!("{} at S0: the spindle does not turn", op.cycle), None);
    }
    if let Some(RunIn { start, end, run_in, need, rpm, by_acceleration }) = run_in(op, axis) {
        let t1 = axis.servo_time_constant.unwrap_or(ASSUMED_SERVO_TIME_CONSTANT_S);
        let num = crate::ground::fmt::fmt_num;
        let how = match by_acceleration {
            Some(a) => format!(
                "to accelerate to the threading feed at its {} mm/s² (V²/(2a), longer than the servo's lag t1·V·(−1 − ln a))",
                num(a)
            ),
            None => format!(
                "to reach the threading feed within {} % of the lead (Fanuc's run-in δ1 = t1·V·(−1 − ln a))",
                num(ALLOWED_LEAD_ERROR * 100.0)
            ),
        };
        push(
            ControlRule::RunInShort,
            format!(
                "the first pass starts at Z{start:.3}, {:.2} mm before the part's end at Z{end:.3}; at S{} × lead {} the Z axis needs {:.2} mm {how}: the first threads' lead is short; start the passes {:.2} mm or more before the part",
                run_in,
                num(rpm),
                num(op.lead()),
                need,
                need
            ),
            {
                let assumed: Vec<String> = [
                    axis.servo_time_constant.is_none().then(|| format!(
                        "servo time constant t1 = {} s (a named default; the machine file's servo_time_constant_s gives the machine's)",
                        num(t1)
                    )),
                    axis.acceleration.is_none().then(|| {
                        "the Z axis's acceleration not limited (the machine file's z_acceleration_mm_s2 gives it)".to_string()
                    }),
                ]
                .into_iter()
                .flatten()
                .collect();
                (!assumed.is_empty()).then(|| assumed.join("; "))
            },
        );
    }
    out
}

/// A run-in too short: the first pass's start and the part's end (Z, mm), the run-in and what
/// the axis needs (mm), at the spindle speed (rpm).
struct RunIn {
    start: f64,
    end: f64,
    run_in: f64,
    need: f64,
    rpm: f64,
    /// The acceleration (mm/s²) whose V²/(2a) is the need, where longer than the servo's lag.
    by_acceleration: Option<f64>,
}

/// What the machine file says of the Z axis: its servo time constant (s) and its
/// acceleration (mm/s²), each where given.
#[derive(Clone, Copy, Debug)]
struct Axis {
    servo_time_constant: Option<f64>,
    acceleration: Option<f64>,
}

/// The run-in of an operation's first pass against what the Z axis needs, where the program
/// faced or chamfered the part's end before the thread (the contour's X move nearest the
/// passes' start, over the stretch the thread is cut in) and the spindle speed is known;
/// `None` when long enough or not known.
fn run_in(op: &Operation, axis: Axis) -> Option<RunIn> {
    let rpm = op.spindle.s.filter(|s| *s > 0.0 && !op.spindle.constant_surface_speed)?;
    let first = op.passes.first()?;
    let dir = first.feed_direction();
    let lead = first.lead;
    let (lo_x, hi_x) = op.passes.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), p| {
        (lo.min(p.x_end.abs()).min(p.x_start.abs()), hi.max(p.x_end.abs()).max(p.x_start.abs()))
    });
    let external = op.passes.last().is_some_and(|l| l.x_end.abs() <= first.x_end.abs());
    let (z0, z1) = (first.z_start.min(first.z_end), first.z_start.max(first.z_end));
    // The part's end: a facing or chamfering feed move (one that changes X; a move along Z,
    // or a profile's rapid approach, starts in the air as often as not) across the stretch between the root and two pitches beyond
    // the crest, within the thread's Z range.
    let ends = op
        .contour
        .iter()
        .filter(|t| !t.rapid && (t.to[0] - t.from[0]).abs() > 1e-6)
        .filter(|t| {
            let (a, b) = (t.from[0].abs(), t.to[0].abs());
            if external {
                a.max(b) > lo_x + 1e-6 && a.min(b) <= hi_x + 2.0 * lead
            } else {
                a.min(b) < hi_x - 1e-6 && a.max(b) >= lo_x - 2.0 * lead
            }
        })
        .flat_map(|t| [t.from[1], t.to[1]])
        .filter(|z| (z0 - 1e-9..=z1 + 1e-9).contains(z));
    // The part's end the passes enter: the contour's Z nearest the passes' start.
    let end =
        if dir < 0.0 { ends.fold(f64::NEG_INFINITY, f64::max) } else { ends.fold(f64::INFINITY, f64::min) };
    if !end.is_finite() {
        return None;
    }
    let run_in = (first.z_start - end) * -dir;
    let t1 = axis.servo_time_constant.unwrap_or(ASSUMED_SERVO_TIME_CONSTANT_S);
    let v = rpm * lead / 60.0;
    let lag = t1 * v * (-1.0 - ALLOWED_LEAD_ERROR.ln());
    // At a limited acceleration the axis covers V²/(2a) before it runs at the feed.
    let ramp = axis.acceleration.map(|a| (a, v * v / (2.0 * a)));
    let (need, by_acceleration) = match ramp {
        Some((a, d)) if d > lag => (d, Some(a)),
        _ => (lag, None),
    };
    (run_in > 1e-6 && run_in + 1e-9 < need).then_some(RunIn {
        start: first.z_start,
        end,
        run_in,
        need,
        rpm,
        by_acceleration,
    })
}

/// The drilling and boring cycles a tap runs in (a post that wrote a tap's operation as a
/// drilling cycle): the cycle's T is the tool table's tap, or one a CAM tool list names as a
/// tap (a comment line such as `T6 | M8X1.25 TAP`). A drilling cycle leaves the hole at rapid
/// (G73 and G83 between pecks too) or with the spindle stopped (G86–G88): the tap is pulled
/// out without reversing, an error. A boring cycle feeds out with the spindle turning forward
/// (G85, G89): only a self-reversing tapping head survives it, a warning.
pub fn taps_in_drill_cycles(
    prog: &Program,
    dialect: Dialect,
    tools: Option<&crate::analysis::tools::ToolTable>,
    comments: &[crate::gcode::Comment],
    allow_nonstandard: bool,
) -> Vec<ControlFinding> {
    use crate::analysis::naming::{listed_tool, ListedKind};
    use crate::analysis::tools::Tool;
    let opts = crate::standards::ParseOptions { allow_nonstandard };
    let mut out = Vec::new();
    for h in prog.holes.iter().filter(|h| h.kind == HoleKind::Drill) {
        let Some(t) = h.tool else { continue };
        let table = tools.and_then(|tt| tt.tool(t)).map(|x| x.0);
        let why = match table {
            Some(Tool::Tap { designation, .. }) => format!("T{t} is the tool table's tap {designation}"),
            Some(_) => continue,
            None => {
                let listed = comments.iter().find_map(|c| {
                    listed_tool(&c.text, h.units, opts).filter(|l| l.tool == t).map(|l| (l.kind, c.line))
                });
                match listed {
                    Some((ListedKind::Tap { .. }, line)) => {
                        format!("T{t} is a tap in the program's tool list at line {line}")
                    }
                    _ => continue,
                }
            }
        };
        let code = h.code.as_str();
        let (rule, how) = match code {
            "G85" | "G89" => (
                ControlRule::TapInBoringCycle,
                "feeds out of the hole with the spindle still turning forward: a plain tap strips the thread it cut; only a self-reversing tapping head (which reverses as the spindle pulls back) runs so",
            ),
            "G86" | "G87" | "G88" => (
                ControlRule::TapInDrillCycle,
                "stops the spindle at the bottom and leaves the hole without turning it back: the tap is pulled out of its thread and strips it",
            ),
            "G73" | "G83" => (
                ControlRule::TapInDrillCycle,
                "retracts at rapid between its pecks and at the end without reversing the spindle: the tap is pulled out of its thread and strips it or breaks",
            ),
            _ => (
                ControlRule::TapInDrillCycle,
                "leaves the hole at rapid without reversing the spindle: the tap is pulled out of its thread and strips it or breaks",
            ),
        };
        let mut f = ControlFinding::new(
            dialect,
            rule,
            Process::Tapped,
            code,
            (h.line, h.column),
            format!("{why}, and {code} {how}; tap with G84 (G74 for a left-hand tap)"),
        );
        f.file.clone_from(&h.source_file);
        out.push(f);
    }
    out
}
