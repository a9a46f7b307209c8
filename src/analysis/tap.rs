//! Tapping cycles checked against their tap and the drill that made the hole (issue 31): a tap
//! forms the flanks, so the tapped thread's pitch and major diameters are the tap's class, but
//! its minor diameter D1 is the drill's, and a hole drilled outside the class's D1 limits fails
//! D1 whatever the tap. Per tapping cycle (Fanuc and Haas `G84`, left-hand `G74`, rigid with
//! `M29`):
//!
//! - **drill diameter** against D1 min and max of the tap's class (compared at the standard's
//!   resolution): the drill is the preceding drilling cycle's (G73, G81–G83, G85–G89) at the same
//!   position, its diameter from the tool table (`5 = "drill:8.5"`);
//! - **feed**: the lead per revolution under G99 (G95 in G17), S × lead per minute under G98
//!   (G94 in G17), within half the program's least increment (0.0005 mm/rev; 0.5 mm/min);
//! - **depth**: the tap's bottom must stay its chamfer length above the drill's bottom (the
//!   chamfer's threads are incomplete and the chips need room): drill bottom − tap bottom ≥
//!   chamfer, the chamfer `tap:M10x1.5-6H:2.5` pitches (default 2.5, form C of ISO 8830 /
//!   DIN 2197, stated);
//! - **spindle**: G84 cuts a right-hand thread with the spindle clockwise (M3), G74 a left-hand
//!   one counter-clockwise (M4); the cycle reverses the spindle itself at the bottom.

use crate::analysis::percent::{thread_percent, ThreadPercent};
use crate::analysis::tools::{Tool, ToolTable};
use crate::gcode::{Dialect, HoleCycle, HoleKind, ReadOptions, SpindleDir};
use crate::standards::tolerance::limits_for;
use crate::standards::{parse_designation, Hand, ParseOptions, ThreadKind};
use crate::Error;
use serde::Serialize;

/// What the tapping check reads.
#[derive(Clone, Debug)]
pub struct TapSpec {
    /// The program's text and the name messages call it.
    pub program: (String, String),
    /// Its dialect.
    pub dialect: Dialect,
    /// How to read it (units, G-code system, …).
    pub reading: ReadOptions,
    /// The tool table naming the taps and drills.
    pub tools: ToolTable,
    /// Accept sizes outside the standard series.
    pub allow_nonstandard: bool,
    /// A tap or drill the tool table does not name is taken from the program (`verify`): the
    /// tap's designation from the nearest comment above its cycle, else the standard size of its
    /// lead over its drill; the drill's diameter from a comment at its cycle. Else such a tool
    /// is refused by name.
    pub from_program: bool,
    /// Z of the stock's bottom face, mm: a drill whose full diameter passes it makes a through
    /// hole, whose tap has no bottom to meet (`None`: not known, every hole blind).
    pub stock_bottom: Option<f64>,
    /// The tap of the tapping cycles whose tool is not known (`--tap`): one that names no tool
    /// (and no `in_spindle` in the table), or a T the tool table does not name; before the
    /// program's comments. A designation such as `M10x1.5-6H`, parsed.
    pub tap: Option<crate::standards::Designation>,
    /// The workpiece's material and the taps' kind, for each hole's torque (`--material`,
    /// `--tap-kind`; the kind's default spiral-fluted, stated); `None`: no torque.
    pub torque: Option<TorqueSpec>,
    /// The machine the program runs on (`--machine`): its spindle's torque and power hold each
    /// hole's torque (a warning when exceeded).
    pub machine: Option<crate::analysis::process::MachineProfile>,
}

/// What a hole's torque is computed for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TorqueSpec {
    /// The workpiece's material (the tap maker's table 1).
    pub material: &'static crate::standards::torque::Material,
    /// The taps' kind.
    pub kind: crate::standards::torque::TapKind,
    /// The kind was given (else the default, stated).
    pub kind_given: bool,
}

/// A cutting tap's torque at a hole (issue 64), by the tap maker's equation.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TapTorque {
    /// Tc, N·m.
    pub newton_metres: f64,
    /// Power at the spindle, kW, at the cycle's S (`None` without an S).
    pub power_kw: Option<f64>,
    /// The material (table 1's name) and its kc, N/mm².
    pub material: &'static str,
    /// kc, N/mm².
    pub kc: f64,
    /// The tap's kind.
    pub tap_kind: crate::standards::torque::TapKind,
    /// Table 2's K.
    pub k: f64,
    /// The pitch is the size's coarse one (else fine).
    pub coarse: bool,
    /// The machine file's spindle torque, N·m, the torque is held against (`None`: not given).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spindle_torque_nm: Option<f64>,
    /// The machine file's spindle power, kW, the power is held against (`None`: not given).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spindle_power_kw: Option<f64>,
    /// The tap asks more torque or power than the machine file's spindle gives: a warning (the
    /// spindle stalls or the tap breaks); the verdict is the thread's.
    pub exceeds_spindle: bool,
}

/// What a tapping check looks at.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum TapFeature {
    /// The drill's diameter against D1.
    DrillDiameter,
    /// F against the lead.
    Feed,
    /// The depth left below the tap for its chamfer.
    Depth,
    /// The spindle's direction against the tap's hand.
    Spindle,
}

impl TapFeature {
    /// The JSON name (`drill_diameter`).
    pub fn name(self) -> &'static str {
        match self {
            TapFeature::DrillDiameter => "drill_diameter",
            TapFeature::Feed => "feed",
            TapFeature::Depth => "depth",
            TapFeature::Spindle => "spindle",
        }
    }
}

/// One check of a tapping cycle.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TapCheck {
    /// What is checked.
    pub feature: TapFeature,
    /// Within its limits.
    pub ok: bool,
    /// The program's value (mm, mm/rev or mm/min; none for the spindle).
    pub value: Option<f64>,
    /// The least allowed value.
    pub min: Option<f64>,
    /// The largest allowed value.
    pub max: Option<f64>,
    /// The unit of value, min and max.
    pub unit: &'static str,
    /// 0 inside, else the signed distance to the nearer limit in µm (mm for a feed per minute).
    pub deviation: f64,
    /// Why, in words.
    pub note: String,
}

/// The drill that made a tapped hole.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DrillInfo {
    /// The drilling cycle.
    pub cycle: HoleCycle,
    /// Its diameter from the tool table, mm (`None`: its tool is not a drill of the table).
    pub diameter: Option<f64>,
    /// Its point's included angle, degrees (the table's, else a twist drill's 118°).
    pub point_angle: f64,
    /// The angle was given in the tool table (else the default).
    pub point_given: bool,
}

/// What a form tap leaves in its hole (issue 64).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct FormedThread {
    /// The minor diameter D1 the tap forms, mm, by volume constancy (`None` when the hole is
    /// overfilled: the nut's teeth close before the displaced metal is placed).
    pub minor_diameter: Option<f64>,
    /// The hole the tap makers' formula gives for the middle of the band, mm:
    /// D − 0.0068·P·% (in inch, D − 0.0068·%/TPI) at 65 %.
    pub hole_for_65_percent: f64,
}

/// The band of percent thread form-tap makers recommend for their hole (a named default, the
/// cutting band's 60–75 %), in their formula hole = D − 0.0068·P·%.
pub const FORM_TAP_BAND: [f64; 2] = [60.0, 75.0];

/// The tap makers' hole for a form tap: D − 0.0068·P·% (inch: D − 0.0068·%/TPI, the same), mm.
pub fn form_tap_hole(thread: &crate::standards::BasicThread, percent: f64) -> f64 {
    thread.nominal_diameter - 0.0068 * thread.pitch * percent
}

/// The tap of a tapping cycle.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TapInfo {
    /// The designation with its class.
    pub designation: String,
    /// Where the designation came from: the tool table, a comment, or inferred.
    pub designation_from: crate::analysis::naming::DesignationFrom,
    /// The comment's line (the cycle's, when inferred); `None` from the tool table.
    pub designation_line: Option<usize>,
    /// The lead, mm.
    pub lead: f64,
    /// The chamfer length, pitches.
    pub chamfer_pitches: f64,
    /// The chamfer was given in the tool table (else the default).
    pub chamfer_given: bool,
    /// A form (roll) tap (the tool table's `form-tap:`): the drill is checked against the hole
    /// it needs, and D1 is what it forms.
    pub forming: bool,
    /// The chamfer's length, mm (its pitches times the pitch).
    pub chamfer_length: f64,
    /// Z where the tap's full thread begins: its bottom plus the chamfer, mm (`None` when the
    /// cycle gives no bottom).
    pub full_thread_z: Option<f64>,
    /// D1 limits of the class, mm.
    pub minor_diameter: crate::standards::tolerance::Limit,
    /// D2 limits of the class, mm (the tap's: stated, not computed).
    pub pitch_diameter: crate::standards::tolerance::Limit,
}

/// One tapping cycle and its checks.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TappedHole {
    /// The tapping cycle.
    pub cycle: HoleCycle,
    /// Its tap.
    pub tap: TapInfo,
    /// The drill that made the hole, when a drilling cycle precedes it at its position.
    pub drill: Option<DrillInfo>,
    /// A drill that leaves D1 within the class's limits: the middle of D1 and the nearest
    /// stocked drill (ISO 2306's tap drill, or the metric or inch drill nearest the middle);
    /// `None` for a taper pipe tap.
    pub drill_that_passes: Option<crate::standards::drills::PassingDrill>,
    /// How much thread the drill leaves (a 60° tap's drill of known diameter; `None`
    /// otherwise): reported beside the checks, never failed (D1's limits are the check).
    pub thread_percent: Option<ThreadPercent>,
    /// The torque the tap needs (`--material`; a cutting tap whose drill is known), N·m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub torque: Option<TapTorque>,
    /// A form tap's thread: the minor diameter D1 it forms in the drilled hole, by volume
    /// constancy (`None` for a cutting tap, or when the drill is not known).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub formed: Option<FormedThread>,
    /// The checks.
    pub checks: Vec<TapCheck>,
    /// Within every check.
    pub pass: bool,
    /// What was assumed or could not be checked.
    pub notes: Vec<crate::ground::note::Note>,
    /// The hole's wall in its axial half-section (z, r), mm, from the top (Z0, or six pitches
    /// above the tap's bottom when that lies above Z0) down to the drill's point: the tap's
    /// thread (the basic profile's flanks, cut off at the drill's radius), its chamfer's cone
    /// from the basic minor diameter, the plain bore below and the drill's 118° point. Empty
    /// when the drill's diameter or either bottom is not known.
    #[serde(skip)]
    pub wall: Vec<crate::Point>,
}

/// The drill's point angle: a twist drill's 118° (a named default of the picture and the depth
/// check).
const DRILL_POINT_DEG: f64 = 118.0;

/// The basic minor diameter D1 of `t` (the fundamental triangle's 5H/8 below D), where the
/// picture's tap chamfer starts.
fn t_minor_basic(t: &crate::standards::BasicThread) -> f64 {
    t.nominal_diameter - 2.0 * 5.0 * t.fundamental_height() / 8.0
}

/// The tapped hole's wall, as [`TappedHole::wall`] says: `t` the tap's thread, `chamfer` its
/// length (mm), `drill` the drill's diameter, `tap_z` and `drill_z` the bottoms.
fn hole_wall(
    t: &crate::standards::BasicThread,
    chamfer: f64,
    drill: f64,
    crest: f64,
    tap_z: f64,
    drill_z: f64,
    point_deg: f64,
) -> Vec<crate::Point> {
    let p = t.pitch;
    let half = t.half_angle();
    let h = t.fundamental_height();
    // The thread's crest stands at the drill's wall for a cutting tap, at the D1 it forms,
    // inside the wall, for a form tap.
    let (rd, rc, rmaj) = (0.5 * drill, 0.5 * crest, 0.5 * t.nominal_diameter);
    let rmin = 0.5 * t_minor_basic(t);
    // The tap's tooth: the fundamental triangle's apex H/8 beyond D, flanks at the half angle.
    let apex = rmaj + h / 8.0;
    let top = if tap_z < 0.0 { 0.0 } else { tap_z + 6.0 * p };
    let point_top = drill_z + rd / (0.5 * point_deg).to_radians().tan();
    let mut out = Vec::new();
    let n = (((top - drill_z.min(tap_z)) / p) * 48.0).ceil().clamp(8.0, 20_000.0) as usize;
    let bottom = drill_z.min(tap_z);
    for i in 0..=n {
        let z = top - (top - bottom) * i as f64 / n as f64;
        let r = if z >= tap_z {
            let u = (z / p - (z / p).round()).abs() * p;
            let tooth = apex - u / half.tan();
            let cone = if z < tap_z + chamfer {
                rmin + (apex - rmin) * (z - tap_z) / chamfer
            } else {
                f64::INFINITY
            };
            rc.max(tooth.min(cone).min(rmaj))
        } else if z >= point_top {
            rd
        } else {
            (z - drill_z).max(0.0) * (0.5 * point_deg).to_radians().tan()
        };
        out.push(crate::Point::new(z, r));
    }
    out
}

/// Every tapping cycle of a program, checked.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TapReport {
    /// The program's name.
    pub program: String,
    /// Its dialect.
    pub dialect: Dialect,
    /// Every tapping cycle in program order.
    pub holes: Vec<TappedHole>,
    /// The drilling cycles read.
    pub drills: usize,
    /// Every drilling and boring cycle's hole, in program order.
    pub drilled: Vec<crate::gcode::HoleCycle>,
    /// Every tapping cycle passes.
    pub pass: bool,
    /// The program's notes.
    pub notes: Vec<crate::ground::note::Note>,
    /// The machine the program was read for, and why.
    pub machine: crate::gcode::MachineReading,
    /// Z of the stock's bottom face, mm: the caller's, else the program's own (Klartext's
    /// `BLK FORM 0.1`); `None` when not known.
    pub stock_bottom: Option<f64>,
}

/// The same position (within 1 µm; unknown matches unknown).
fn same(a: Option<f64>, b: Option<f64>) -> bool {
    match (a, b) {
        (Some(a), Some(b)) => (a - b).abs() < 1e-3,
        (None, None) => true,
        _ => false,
    }
}

/// Whether a drill and a tap are one hole: the same place in machine coordinates when the
/// program set both work offsets' origins (G10), else the same place in work offsets that do not
/// differ (a cycle before any G54… is in the machine's, which may be either).
fn same_place(d: &crate::gcode::HoleCycle, h: &crate::gcode::HoleCycle) -> bool {
    // Radial holes (a live tool along X) by their Z and C; never one of each kind.
    match (d.radial, h.radial) {
        (Some(a), Some(b)) => return (a.z - b.z).abs() < 1e-3 && (a.c_deg - b.c_deg).abs() < 1e-3,
        (None, None) => {}
        _ => return false,
    }
    match (d.machine_xy, h.machine_xy) {
        (Some(a), Some(b)) => (a.0 - b.0).abs() < 1e-3 && (a.1 - b.1).abs() < 1e-3,
        _ => {
            let offsets_differ = matches!((&d.work_offset, &h.work_offset), (Some(a), Some(b)) if a != b);
            !offsets_differ && same(d.x, h.x) && same(d.y, h.y)
        }
    }
}

/// Reads the program's drilling and tapping cycles and checks each tapping cycle.
///
/// ```
/// use threadcheck::{tap, Dialect, ReadOptions, TapSpec, ToolTable};
/// let program = "T0505\nG99 M3 S800\nG0 X0 Z5\nG83 Z-25 R2 Q5000 F0.1\nT0606\nG84 Z-18 R5 F1.5\nG80\nM30\n";
/// let tools = ToolTable::from_toml("[tools]\n5 = \"drill:8.5\"\n6 = \"tap:M10x1.5-6H\"\n", "tools.toml", std::path::Path::new("."))?;
/// let spec = TapSpec { program: (program.into(), "tap.nc".into()), dialect: Dialect::Fanuc, reading: ReadOptions::default(), tools, allow_nonstandard: false, from_program: false, stock_bottom: None, tap: None, torque: None, machine: None };
/// let r = tap(&spec)?;
/// assert!(r.pass); // Ø8.5 within D1 8.376–8.676; F1.5 = P; 25 − 18 = 7 ≥ 2.5·1.5
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn tap(spec: &TapSpec) -> Result<TapReport, Error> {
    let (text, name) = &spec.program;
    let prog = read_holes(spec)?;
    let comments = if spec.from_program { crate::gcode::comments(text, spec.dialect) } else { Vec::new() };
    let mut tap_by_tool: std::collections::HashMap<u32, TapOf> = std::collections::HashMap::new();
    let mut drill_by_tool: std::collections::HashMap<u32, (f64, usize)> = std::collections::HashMap::new();
    let mut holes = Vec::new();
    for (i, h) in prog.holes.iter().enumerate() {
        if h.kind != HoleKind::Tap {
            continue;
        }
        let (drill, drill_note) = drill_of(spec, &prog, i, &comments, &mut drill_by_tool);
        // A later cycle of the same tap takes what its first one found.
        let tap = match h.tool.and_then(|t| tap_by_tool.get(&t)) {
            Some(first) => first.clone(),
            None => tap_of(spec, &prog, i, &comments, drill.as_ref().and_then(|d| d.diameter))?,
        };
        if let Some(t) = h.tool {
            tap_by_tool.entry(t).or_insert_with(|| tap.clone());
        }
        holes.push(tapped_hole(spec, &prog, h, &tap, drill, drill_note)?);
    }
    let pass = holes.iter().all(|h| h.pass);
    let drilled: Vec<crate::gcode::HoleCycle> =
        prog.holes.iter().filter(|h| h.kind == HoleKind::Drill).cloned().collect();
    Ok(TapReport {
        program: name.clone(),
        dialect: spec.dialect,
        holes,
        drills: drilled.len(),
        drilled,
        pass,
        notes: prog.notes,
        machine: prog.machine,
        stock_bottom: spec.stock_bottom.or(prog.stock_bottom.map(|s| s.0)),
    })
}

/// The program's hole cycles, the cycles that name no tool given the tool in the spindle;
/// refused when it has no tapping cycle.
fn read_holes(spec: &TapSpec) -> Result<crate::gcode::Program, Error> {
    let (text, name) = &spec.program;
    let opts = ReadOptions { allow_no_threading: true, ..spec.reading.clone() };
    let mut prog = crate::gcode::read_program_with(text, name, spec.dialect, opts)?;
    // Cycles before the program calls a tool take the one the tool table says is in the spindle.
    if let Some(t) = spec.tools.in_spindle() {
        let first = prog.holes.iter().find(|h| h.tool.is_none()).map(|h| (h.line, h.column));
        if let Some((line, column)) = first {
            for h in prog.holes.iter_mut().filter(|h| h.tool.is_none()) {
                h.tool = Some(t);
            }
            prog.notes.push(crate::ground::note::Note::at(
                name,
                line,
                column,
                format!(
                    "the cycles that name no tool take T{t}, the tool {} says is in the spindle (in_spindle)",
                    spec.tools.source
                ),
            ));
        }
    }
    let taps: Vec<&HoleCycle> = prog.holes.iter().filter(|h| h.kind == HoleKind::Tap).collect();
    if taps.is_empty() {
        // What in the program explains it, named at its place (a Haas program's M97 read in
        // another dialect).
        let hint = crate::gcode::no_thread_hint(&prog.notes);
        let (line, column) = hint.as_ref().map_or((1, 1), |h| (h.0, h.1));
        return Err(Error::Program {
            file: name.clone(),
            line,
            column,
            message: format!(
                "no tapping cycle in the program (looked for {} in the {} dialect){}",
                match spec.dialect {
                    Dialect::Sinumerik => "CYCLE84 and CYCLE840",
                    Dialect::LinuxCnc => "G33.1",
                    Dialect::Fanuc | Dialect::Haas | Dialect::Mitsubishi | Dialect::Mazak => "G84 and G74",
                    Dialect::Klartext => "the cycles 206, 207 and 209",
                    Dialect::Okuma | Dialect::Dyna | Dialect::Heidenhain => {
                        "a tapping cycle threadcheck reads: none yet"
                    }
                },
                spec.dialect.name(),
                hint.map_or(String::new(), |h| format!("; {}", h.2))
            ),
        });
    }
    Ok(prog)
}

/// The drill of the tapping cycle `prog.holes[i]`: the last drilling cycle before it at its
/// position; its diameter from the tool table, else (a program verified whole) from a comment
/// at its cycle, and the note that says so.
fn drill_of(
    spec: &TapSpec,
    prog: &crate::gcode::Program,
    i: usize,
    comments: &[crate::gcode::Comment],
    drill_by_tool: &mut std::collections::HashMap<u32, (f64, usize)>,
) -> (Option<DrillInfo>, Option<String>) {
    let h = &prog.holes[i];
    let mut drill_note = None;
    let drill =
        prog.holes[..i].iter().rev().find(|d| d.kind == HoleKind::Drill && same_place(d, h)).map(|d| {
            let (mut diameter, point) = match d.tool.and_then(|dt| spec.tools.tool(dt)) {
                Some((Tool::Drill { diameter, point_angle }, _)) => (Some(*diameter), *point_angle),
                Some((Tool::Insert(_) | Tool::Tap { .. }, _)) | None => (None, None),
            };
            if diameter.is_none() && spec.from_program {
                // The comment at its cycle (back to the cycle before), else the one an earlier
                // cycle of the same tool took.
                let after = prog
                    .holes
                    .iter()
                    .take_while(|o| o.main_line < d.main_line)
                    .map(|o| o.main_line)
                    .max()
                    .unwrap_or(0);
                // A CAM system's tool list that names the drill by its number first.
                let listed = d.tool.and_then(|t| {
                    comments.iter().find_map(|c| {
                        match crate::analysis::naming::listed_tool(&c.text, d.units, ParseOptions::default())
                        {
                            Some(crate::analysis::naming::ListedTool {
                                tool,
                                kind: crate::analysis::naming::ListedKind::Drill { diameter },
                            }) if tool == t => Some((diameter, c.line)),
                            _ => None,
                        }
                    })
                });
                let found = listed
                    .or_else(|| {
                        comments.iter().rev().filter(|c| c.line > after && c.line <= d.main_line).find_map(
                            |c| {
                                crate::analysis::naming::drill_in_comment(&c.text, d.units)
                                    .map(|v| (v, c.line))
                            },
                        )
                    })
                    .or_else(|| d.tool.and_then(|t| drill_by_tool.get(&t).copied()));
                if let (Some(found), Some(t)) = (found, d.tool) {
                    drill_by_tool.entry(t).or_insert(found);
                }
                if let Some((dia, line)) = found {
                    diameter = Some(dia);
                    drill_note = Some(format!(
                        "the drill's diameter Ø{} is the comment's at line {line}",
                        crate::ground::fmt::fmt_num(dia)
                    ));
                }
            }
            DrillInfo {
                cycle: d.clone(),
                diameter,
                point_angle: point.unwrap_or(DRILL_POINT_DEG),
                point_given: point.is_some(),
            }
        });
    (drill, drill_note)
}

/// An error at a tapping cycle's place: its line and column in the file it stands in (a
/// subprogram's, or the program's `name`).
fn at_cycle(h: &HoleCycle, name: &str, message: String) -> Error {
    Error::Program {
        file: h.source_file.clone().unwrap_or_else(|| name.to_string()),
        line: h.line,
        column: h.column,
        message,
    }
}

/// One tapping cycle checked against its tap and its drill.
fn tapped_hole(
    spec: &TapSpec,
    prog: &crate::gcode::Program,
    h: &HoleCycle,
    tap: &TapOf,
    drill: Option<DrillInfo>,
    drill_note: Option<String>,
) -> Result<TappedHole, Error> {
    let name = &spec.program.1;
    let perr = |message: String| at_cycle(h, name, message);
    let (des, chamfer_pitches, chamfer_given) = (&tap.designation, tap.chamfer_pitches, tap.chamfer_given);
    let designation = &des.text;
    let limits = limits_for(des, ThreadKind::Internal)?.ok_or_else(|| {
        perr(format!("tap {designation}: give the internal class the tap cuts, e.g. M10x1.5-6H"))
    })?;
    let lead = des.thread.lead();
    let pitch = des.thread.pitch;
    let res = limits.resolution;
    let mut checks = Vec::new();
    let mut notes: Vec<String> = tap.why.iter().cloned().chain(drill_note).collect();
    let (hole_window, formed) = hole_window(&des.thread, &limits, tap.forming, drill.as_ref(), &mut notes);
    drill_check(drill.as_ref(), hole_window, res, formed, tap.forming, &mut checks, &mut notes);
    feed_check(h, lead, spec.machine.as_ref().and_then(|m| m.tap_holder), &mut checks, &mut notes);
    let chamfer = chamfer_pitches * pitch;
    depth_check(
        spec,
        prog,
        h,
        drill.as_ref(),
        &des.thread,
        chamfer,
        (chamfer_pitches, chamfer_given, designation),
        &mut checks,
        &mut notes,
    );
    spindle_check(spec, h, &des.thread, designation, &mut checks, &mut notes);
    notes.push(format!(
        "the tapped thread's D2 and D are the tap's class {} (not computed); D1 is {}",
        limits.class,
        if tap.forming { "what the form tap forms" } else { "the drill's" }
    ));
    let pass = checks.iter().all(|c| c.ok);
    let thread_percent = percent_of(&des.thread, drill.as_ref(), tap.forming, &mut notes);
    let torque = torque_of(spec, h, &des.thread, drill.as_ref(), tap.forming, &mut notes);
    let wall = match (&drill, h.bottom) {
        (Some(DrillInfo { diameter: Some(dia), cycle, point_angle, .. }), Some(tz)) => {
            cycle.bottom.map_or_else(Vec::new, |dz| {
                let crest = formed.and_then(|f| f.minor_diameter).unwrap_or(*dia);
                hole_wall(&des.thread, chamfer, *dia, crest, tz, dz, *point_angle)
            })
        }
        _ => Vec::new(),
    };
    Ok(TappedHole {
        cycle: h.clone(),
        tap: TapInfo {
            designation: des.text.clone(),
            designation_from: tap.from,
            designation_line: tap.line,
            lead,
            chamfer_pitches,
            chamfer_given,
            forming: tap.forming,
            chamfer_length: chamfer,
            full_thread_z: h.bottom.map(|z| z + chamfer),
            minor_diameter: limits.minor_diameter,
            pitch_diameter: limits.pitch_diameter,
        },
        drill,
        thread_percent,
        drill_that_passes: crate::standards::drills::drill_that_passes(&des.thread, hole_window, res)?,
        formed,
        torque,
        checks,
        pass,
        notes: notes.into_iter().map(crate::ground::note::Note::from).collect(),
        wall,
    })
}

/// A tapped hole's window for the drill: the class's D1, or for a form tap the makers' window for
/// 60–75 % of thread; and what a form tap forms from the drill's hole.
fn hole_window(
    t: &crate::standards::BasicThread,
    limits: &crate::standards::tolerance::ThreadLimits,
    forming: bool,
    drill: Option<&DrillInfo>,
    notes: &mut Vec<String>,
) -> (crate::standards::tolerance::Limit, Option<FormedThread>) {
    let res = limits.resolution;
    // A form tap's hole: the tap makers' window for 60–75 % of thread, not D1 (the tap forms
    // D1 from the wall's metal).
    let hole_window = if forming {
        crate::standards::tolerance::Limit {
            min: Some(res.round(form_tap_hole(t, FORM_TAP_BAND[1]))),
            max: Some(res.round(form_tap_hole(t, FORM_TAP_BAND[0]))),
        }
    } else {
        limits.minor_diameter
    };
    let formed = match (drill, forming) {
        (Some(DrillInfo { diameter: Some(dia), .. }), true) => {
            let profile = crate::geometry::forming::FormProfile {
                p: t.pitch,
                r2: 0.5 * t.pitch_diameter(),
                tan_half: t.half_angle().tan(),
            };
            let minor = match crate::geometry::forming::formed_minor(&profile, t.nominal_diameter, *dia) {
                crate::geometry::forming::Formed::Minor(d1) => Some(d1),
                crate::geometry::forming::Formed::Overfilled => None,
            };
            Some(FormedThread { minor_diameter: minor, hole_for_65_percent: form_tap_hole(t, 65.0) })
        }
        _ => None,
    };
    if forming {
        notes.push(format!(
            "a form tap: its hole is the tap makers' D − 0.0068·P·% for {}–{} % of thread (a named default), {}–{} mm; the tap forms D1 from the wall's metal, computed by volume constancy with a flat crest (a formed crest is cupped); ISO 965's and ASME B1.1's D1 limits are for cut threads, and a formed D1 at the usual 65 % lies over them (DIN 13-50 gives formed threads their own, not in the sources here): D1 is reported, not checked",
            crate::ground::fmt::fmt_num(FORM_TAP_BAND[0]),
            crate::ground::fmt::fmt_num(FORM_TAP_BAND[1]),
            crate::ground::fmt::fmt_num(hole_window.min.unwrap_or(0.0)),
            crate::ground::fmt::fmt_num(hole_window.max.unwrap_or(0.0)),
        ));
    }
    (hole_window, formed)
}

/// The drill's diameter against the hole's window (a note when the drill is not known).
fn drill_check(
    drill: Option<&DrillInfo>,
    hole_window: crate::standards::tolerance::Limit,
    res: crate::standards::tolerance::Resolution,
    formed: Option<FormedThread>,
    forming: bool,
    checks: &mut Vec<TapCheck>,
    notes: &mut Vec<String>,
) {
    match drill {
        Some(DrillInfo { diameter: Some(dia), cycle, .. }) => {
            // A cutting tap's hole is D1 (the drill's), a form tap's the makers' window.
            let (lo, hi) = (hole_window.min, hole_window.max);
            let v = res.round(*dia);
            let below = lo.map_or(0.0, |lo| (v - lo).min(0.0));
            let above = hi.map_or(0.0, |hi| (v - hi).max(0.0));
            let dev = if below < 0.0 { below } else { above };
            let at = format!(
                "T{}, {} at line {}",
                cycle.tool.map_or("?".to_string(), |t| t.to_string()),
                cycle.code,
                cycle.line
            );
            let d1 = formed.and_then(|f| f.minor_diameter);
            let (ok, note) = if forming {
                let what = match d1 {
                    Some(d1) => format!("the tap forms D1 {} mm in it", crate::ground::fmt::fmt_num((d1 * 1e4).round() / 1e4)),
                    None => "the hole holds more metal than the thread's teeth take: the tap is overloaded (it breaks)".to_string(),
                };
                (dev == 0.0 && d1.is_some(), format!("a form tap's hole ({at}): {what}"))
            } else {
                (dev == 0.0, format!("the tapped hole's minor diameter D1 is the drill's ({at})"))
            };
            checks.push(TapCheck {
                feature: TapFeature::DrillDiameter,
                ok,
                value: Some(*dia),
                min: lo,
                max: hi,
                unit: "mm",
                deviation: (dev * 10_000.0).round() / 10.0,
                note,
            });
        }
        Some(DrillInfo { diameter: None, cycle, .. }) => notes.push(format!(
            "the hole is drilled by {} at line {} with {}, which the tool table does not give as a drill (write drill:DIAMETER): D1 is not checked",
            cycle.code,
            cycle.line,
            cycle.tool.map_or("no tool".to_string(), |t| format!("T{t}"))
        )),
        None => notes.push(
            "no drilling cycle precedes this tap at its position: D1 (the drill's diameter) and the depth are not checked"
                .to_string(),
        ),
    }
}

/// The under-feed a floating (tension-compression) holder takes up, a fraction of the feed:
/// the 2 to 5 % tap makers allow such holders, at its top (a named default).
pub const FLOATING_UNDERFEED_MAX: f64 = 0.05;

/// The feed against the lead: per revolution, or S × lead per minute; a floating holder
/// (`holder`, the machine file's) takes up an under-feed to [`FLOATING_UNDERFEED_MAX`].
fn feed_check(
    h: &HoleCycle,
    lead: f64,
    holder: Option<crate::analysis::process::TapHolder>,
    checks: &mut Vec<TapCheck>,
    notes: &mut Vec<String>,
) {
    use crate::analysis::process::TapHolder;
    // The feed.
    match h.feed {
        Some(f) => {
            let mode = if h.feed_per_rev { "per revolution" } else { "per minute" };
            if h.feed_mode_assumed {
                notes.push(format!(
                    "the program sets no feed mode before {}: feed {mode} assumed, the control's power-on state ({})",
                    h.code,
                    if h.feed_per_rev { "a lathe's G99" } else { "a machining centre's G94" }
                ));
            }
            // Under G96 S is a surface speed, m/min (ft/min), not the spindle's rpm.
            let rpm = h.spindle.filter(|_| !h.constant_surface_speed);
            if h.constant_surface_speed && !h.feed_per_rev {
                notes.push(format!(
                    "{} runs under G96: its S is a surface speed, not the spindle's rpm, and its feed per minute is not checked against S × lead",
                    h.code
                ));
                return;
            }
            let expected = if h.feed_per_rev { Some(lead) } else { rpm.map(|s| s * lead) };
            match expected {
                Some(e) => {
                    let (tol, unit) = if h.feed_per_rev { (0.0005, "mm/rev") } else { (0.5, "mm/min") };
                    // A floating holder's float takes up an under-feed; a rigid one nothing.
                    let floating = holder == Some(TapHolder::Floating);
                    let min = if floating { e * (1.0 - FLOATING_UNDERFEED_MAX) } else { e };
                    let off = if f < min { f - min } else { (f - e).max(0.0) };
                    let ok = off.abs() <= tol + 1e-9;
                    let under = (e - f) / e;
                    if floating && f < e - tol && ok {
                        notes.push(format!(
                            "{} at line {} feeds {:.1} % under the lead: the floating (tension-compression) holder the machine file gives (tap_holder) takes up an under-feed of up to {} %",
                            h.code,
                            h.line,
                            100.0 * under,
                            100.0 * FLOATING_UNDERFEED_MAX
                        ));
                    } else if holder.is_none() && !ok && under > 0.0 && under <= FLOATING_UNDERFEED_MAX + 1e-9
                    {
                        notes.push(format!(
                            "{} at line {} feeds {:.1} % under the lead: a rigid holder is assumed, which takes up nothing; a floating (tension-compression) holder takes up to {} % (the machine file's tap_holder = \"floating\")",
                            h.code,
                            h.line,
                            100.0 * under,
                            100.0 * FLOATING_UNDERFEED_MAX
                        ));
                    }
                    checks.push(TapCheck {
                        feature: TapFeature::Feed,
                        ok,
                        value: Some(f),
                        min: Some(if floating { (min * 1e6).round() / 1e6 } else { e }),
                        max: Some(e),
                        unit,
                        deviation: if ok {
                            0.0
                        } else if h.feed_per_rev {
                            off * 1000.0
                        } else {
                            off
                        },
                        note: if h.feed_per_rev {
                            format!(
                                "feed per revolution: {} must be the lead, {} mm",
                                match h.feed_word.as_str() {
                                    "MPIT" => "MPIT's coarse pitch",
                                    w => w,
                                },
                                crate::ground::fmt::fmt_num(lead)
                            )
                        } else {
                            format!(
                                "feed per minute: F must be S × lead = {} × {}",
                                crate::ground::fmt::fmt_num(h.spindle.unwrap_or(0.0)),
                                in_units(h.units, lead).0
                            )
                        },
                    });
                }
                None => notes
                    .push(format!("{} feeds per minute with no S in force: the feed is not checked", h.code)),
            }
        }
        None => notes.push(format!("{} has no F: the feed is not checked", h.code)),
    }
}

/// The room below the tap: its point against the drill's point cone (a through hole passes).
#[allow(clippy::too_many_arguments)]
fn depth_check(
    spec: &TapSpec,
    prog: &crate::gcode::Program,
    h: &HoleCycle,
    drill: Option<&DrillInfo>,
    t: &crate::standards::BasicThread,
    chamfer: f64,
    (chamfer_pitches, chamfer_given, designation): (f64, bool, &str),
    checks: &mut Vec<TapCheck>,
    notes: &mut Vec<String>,
) {
    // The depth.
    if !chamfer_given {
        notes.push(format!(
            "the tap's chamfer is taken as {} pitches = {} mm (form C, ISO 8830; give tap:{designation}:PITCHES)",
            crate::ground::fmt::fmt_num(chamfer_pitches),
            crate::ground::fmt::fmt_num(chamfer)
        ));
    }
    if let (Some(d), Some(tb)) = (drill, h.bottom) {
        if let Some(db) = d.cycle.bottom {
            // The tap's point, where its chamfer starts at the basic minor diameter (or the
            // drill's, when the drill is smaller), meets the drill's point cone that far above
            // the drill's bottom (issue 46: the chamfer's length is not the room it needs).
            let basic_minor = t_minor_basic(t);
            let point = d.diameter.map_or(basic_minor, |dia| dia.min(basic_minor));
            let half = (0.5 * d.point_angle).to_radians().tan();
            let need = 0.5 * point / half;
            let room = tb - db;
            // A through hole: the drill's full diameter passes the stock's bottom, and the tap
            // has nothing below it to meet.
            // The stock's bottom: the caller's, else the one the program declares
            // (Klartext's BLK FORM 0.1).
            // (A Z: a radial hole's axis does not meet it.)
            let stock_bottom =
                spec.stock_bottom.or(prog.stock_bottom.map(|s| s.0)).filter(|_| h.radial.is_none());
            let through = match (stock_bottom, d.diameter) {
                (Some(sb), Some(dia)) => db + 0.5 * dia / half <= sb + 1e-9,
                _ => false,
            };
            let ok = through || room >= need - 1e-9;
            let how = if through {
                format!(
                    "a through hole: the drill's full diameter passes the stock's bottom (Z{}) at Z{}, so nothing lies below the tap",
                    match (spec.stock_bottom, prog.stock_bottom) {
                        (None, Some((z, line))) => format!("{}, BLK FORM at line {line}", crate::ground::fmt::fmt_num(z)),
                        _ => crate::ground::fmt::fmt_num(stock_bottom.unwrap_or(0.0)),
                    },
                    crate::ground::fmt::fmt_num(((db + 0.5 * d.diameter.unwrap_or(0.0) / half) * 1e4).round() / 1e4)
                )
            } else {
                String::new()
            };
            checks.push(TapCheck {
                feature: TapFeature::Depth,
                ok,
                value: Some(room),
                min: Some((need * 1e4).round() / 1e4),
                max: None,
                unit: "mm",
                deviation: if ok { 0.0 } else { ((room - need) * 1e4).round() / 10.0 },
                note: if through {
                    how
                } else {
                    // A radial hole's bottoms are radii: written as the program's X.
                    // In the program's units (an inch program's Z-0.5, not Z-12.7).
                    let at = |v: f64| match h.radial {
                        Some(_) => format!("X{}", in_units(h.units, 2.0 * v).0),
                        None => format!("Z{}", in_units(h.units, v).0),
                    };
                    let len = |v: f64| {
                        let (n, u) = in_units(h.units, v);
                        format!("{n} {u}")
                    };
                    format!(
                        "the drill's bottom ({}) lies {} below the tap's ({}); the tap's point (Ø{}) meets the drill's {}° point {} above its bottom{}",
                        at(db),
                        len(room),
                        at(tb),
                        in_units(h.units, point).0,
                        crate::ground::fmt::fmt_num(d.point_angle),
                        len(need),
                        if ok {
                            String::new()
                        } else {
                            format!(", {} above the tap's bottom", len(need - room))
                        }
                    )
                },
            });
            if !d.point_given {
                notes.push(format!(
                    "the drill's point angle is taken as {}°, a twist drill's (a named default; drill:DIAMETER:ANGLE in the tool table gives it)",
                    crate::ground::fmt::fmt_num(DRILL_POINT_DEG)
                ));
            }
        }
    }
}

/// The spindle's direction against the thread's hand and the cycle's.
fn spindle_check(
    spec: &TapSpec,
    h: &HoleCycle,
    t: &crate::standards::BasicThread,
    designation: &str,
    checks: &mut Vec<TapCheck>,
    notes: &mut Vec<String>,
) {
    // The spindle.
    // G84 taps right-hand, G74 left-hand, CYCLE84 as its pitch's sign says; LinuxCNC's
    // G33.1 and Sinumerik's CYCLE840 tap the way the spindle turns.
    let hand = h.hand.unwrap_or(t.hand);
    let want = match hand {
        Hand::Right => SpindleDir::Cw,
        Hand::Left => SpindleDir::Ccw,
    };
    let hand_ok = t.hand == hand;
    // A Haas control starts the spindle itself for its tapping cycles: clockwise for G84,
    // counter-clockwise for G184 ("It is not necessary to start the spindle CW before this
    // canned cycle", the lathe's G84 page; the mill's G84 the same, a named reading); G95 and
    // G186 turn the live tool, whatever the main spindle does (HAAS-L84).
    let spindle_dir = match (spec.dialect, h.code.as_str(), h.spindle_dir) {
        (Dialect::Haas, "G84" | "G184", Some(SpindleDir::Stopped) | None) => {
            let (dir, turn, code) = if h.code == "G84" {
                (SpindleDir::Cw, "clockwise", "M3")
            } else {
                (SpindleDir::Ccw, "counter-clockwise", "M4")
            };
            notes.push(format!(
                "the Haas control starts the spindle {turn} for {} itself: the spindle is taken as {turn} ({code})",
                h.code
            ));
            Some(dir)
        }
        (Dialect::Haas, "G95" | "G186" | "G195" | "G196", _) => {
            let (dir, words) = if matches!(h.code.as_str(), "G95" | "G195") {
                (SpindleDir::Cw, "clockwise")
            } else {
                (SpindleDir::Ccw, "counter-clockwise")
            };
            notes.push(format!(
                "{} is the Haas lathe's live-tool rigid tapping: the control turns the live tool {words} itself, whatever the main spindle does",
                h.code
            ));
            Some(dir)
        }
        (_, _, d) => d,
    };
    match spindle_dir {
        Some(dir) => checks.push(TapCheck {
            feature: TapFeature::Spindle,
            ok: dir == want && hand_ok,
            value: None,
            min: None,
            max: None,
            unit: "",
            deviation: 0.0,
            note: format!(
                "{}{} taps a {}-hand thread with the spindle {}; the spindle is {}{}",
                h.code,
                if h.code == "CYCLE84" { format!(" (the sign of {})", h.feed_word) } else { String::new() },
                if hand == Hand::Right { "right" } else { "left" },
                if want == SpindleDir::Cw { "clockwise (M3)" } else { "counter-clockwise (M4)" },
                match dir {
                    SpindleDir::Cw => "clockwise (M3)",
                    SpindleDir::Ccw => "counter-clockwise (M4)",
                    SpindleDir::Stopped => "stopped (M5)",
                },
                if hand_ok {
                    String::new()
                } else {
                    format!(", and the tap {designation} is of the other hand")
                }
            ),
        }),
        None => notes.push(format!("no M3 or M4 before {}: the spindle's direction is not checked", h.code)),
    }
}

/// The drill's % of thread (the tap makers' for a form tap), with a note outside its band.
fn percent_of(
    t: &crate::standards::BasicThread,
    drill: Option<&DrillInfo>,
    forming: bool,
    notes: &mut Vec<String>,
) -> Option<ThreadPercent> {
    // A form tap's percent is the tap makers' (D − hole)/(0.0068·P); a cutting tap's the charts'.
    let percent = drill.and_then(|d| d.diameter).and_then(|dia| {
        let cut = thread_percent(t, dia)?;
        Some(if forming {
            ThreadPercent {
                percent: (t.nominal_diameter - dia) / (0.0068 * t.pitch),
                band: FORM_TAP_BAND,
                ..cut
            }
        } else {
            cut
        })
    });
    if let Some(p) = percent.filter(|p| p.percent < p.band[0] || p.percent > p.band[1]) {
        notes.push(format!(
            "the drill leaves {} % of thread, outside the {}–{} % shop charts give for a {} tap (a named default): {}",
            crate::ground::fmt::fmt_num((p.percent * 10.0).round() / 10.0),
            crate::ground::fmt::fmt_num(p.band[0]),
            crate::ground::fmt::fmt_num(p.band[1]),
            if forming { "form" } else { "cutting" },
            if p.percent > p.band[1] {
                "above it the tap's torque rises steeply for little more strength"
            } else {
                "below it the thread holds less"
            }
        ));
    }
    percent
}

/// The tap maker's torque for a cutting tap, held against the machine's spindle.
fn torque_of(
    spec: &TapSpec,
    h: &HoleCycle,
    t: &crate::standards::BasicThread,
    drill: Option<&DrillInfo>,
    forming: bool,
    notes: &mut Vec<String>,
) -> Option<TapTorque> {
    match (spec.torque, drill.and_then(|d| d.diameter)) {
        (Some(ts), Some(dia)) if !forming => {
            let coarse = is_coarse_pitch(t);
            match ts.kind.k(ts.material.group, coarse) {
                Some(k) => {
                    let nm = crate::standards::torque::tapping_torque(
                        t.half_angle(),
                        ts.material.kc,
                        k,
                        t.nominal_diameter,
                        dia,
                    );
                    if !ts.kind_given {
                        notes.push(format!(
                            "the tap is taken as {} for its torque (a named default; give its kind)",
                            ts.kind.name()
                        ));
                    }
                    let power_kw = h
                        .spindle
                        .filter(|s| *s > 0.0)
                        .map(|s| nm * 2.0 * std::f64::consts::PI * s / 60_000.0);
                    let machine = spec.machine.as_ref();
                    let spindle_torque_nm = machine.and_then(|m| m.spindle_torque_nm);
                    let spindle_power_kw = machine.and_then(|m| m.spindle_power_kw);
                    let over_torque = spindle_torque_nm.filter(|max| nm > *max);
                    let over_power = match (power_kw, spindle_power_kw) {
                        (Some(p), Some(max)) if p > max => Some((p, max)),
                        _ => None,
                    };
                    let name = machine.map_or("", |m| m.name.as_str());
                    if let Some(max) = over_torque {
                        notes.push(format!(
                            "warning: the tap needs {} N·m, more than the spindle's {} N·m (the machine file '{name}'): the spindle stalls or the tap breaks",
                            crate::ground::fmt::fmt_num((nm * 100.0).round() / 100.0),
                            crate::ground::fmt::fmt_num(max)
                        ));
                    }
                    if let Some((p, max)) = over_power {
                        notes.push(format!(
                            "warning: the tap needs {} kW at S{}, more than the spindle's {} kW (the machine file '{name}')",
                            crate::ground::fmt::fmt_num((p * 1000.0).round() / 1000.0),
                            crate::ground::fmt::fmt_num(h.spindle.unwrap_or(0.0)),
                            crate::ground::fmt::fmt_num(max)
                        ));
                    }
                    if machine.is_some() && spindle_torque_nm.is_none() && spindle_power_kw.is_none() {
                        notes.push(format!(
                            "the machine file '{name}' gives no spindle_torque_nm or spindle_power_kw: the torque is not held against the spindle"
                        ));
                    }
                    Some(TapTorque {
                        newton_metres: nm,
                        power_kw,
                        material: ts.material.name,
                        kc: ts.material.kc,
                        tap_kind: ts.kind,
                        k,
                        coarse,
                        spindle_torque_nm,
                        spindle_power_kw,
                        exceeds_spindle: over_torque.is_some() || over_power.is_some(),
                    })
                }
                None => {
                    notes.push(format!(
                        "the tap maker's table gives no K for a {} tap in {} at a {} pitch: no torque",
                        ts.kind.name(),
                        ts.material.name,
                        if coarse { "coarse" } else { "fine" }
                    ));
                    None
                }
            }
        }
        (Some(_), Some(_)) => {
            notes.push("a form tap's torque is not computed: the tap maker's equation is for cutting taps (a form tap's is two to three times as high, by the same maker)".to_string());
            None
        }
        (Some(_), None) => {
            notes.push("the drill is not known: no torque".to_string());
            None
        }
        (None, _) => None,
    }
}

/// A length in a program's units, to their resolution's tenth (0.1 µm, 0.00001 in) without
/// trailing zeros, and the unit: `("12.7", "mm")`, `("0.5", "in")`.
fn in_units(units: crate::gcode::ProgramUnits, mm: f64) -> (String, &'static str) {
    match units {
        crate::gcode::ProgramUnits::Mm => (crate::ground::fmt::fmt_num((mm * 1e4).round() / 1e4), "mm"),
        crate::gcode::ProgramUnits::Inch => {
            (crate::ground::fmt::fmt_num((mm / crate::MM_PER_INCH * 1e5).round() / 1e5), "in")
        }
    }
}

/// Whether a comment naming a tap says it forms the thread: FORM, FORMING, ROLL, FLUTELESS,
/// GEWINDEFORMER or GEWINDEFURCHER among its words (`(FORM TAP M8)`, `(M6 ROLL TAP)`).
fn says_forming(text: &str) -> bool {
    text.to_uppercase()
        .split(|c: char| !c.is_alphanumeric())
        .any(|w| matches!(w, "FORM" | "FORMING" | "ROLL" | "FLUTELESS" | "GEWINDEFORMER" | "GEWINDEFURCHER"))
}

/// Whether the thread's pitch is the coarse one of its size (ISO 261's coarse series, UNC):
/// the tap maker's table 2 has a K for coarse and one for fine.
fn is_coarse_pitch(t: &crate::standards::BasicThread) -> bool {
    use crate::standards::ThreadForm;
    match t.form {
        ThreadForm::IsoMetric => crate::standards::data::catalog().ok().is_some_and(|c| {
            c.iso.series.sizes.iter().any(|s| {
                (s.d - t.nominal_diameter).abs() < 1e-9
                    && s.coarse.is_some_and(|p| (p - t.pitch).abs() < 1e-9)
            })
        }),
        // BSW is BS 84's coarse series (BSF its fine one): the size's BSW pitch.
        ThreadForm::Whitworth => crate::standards::data::catalog().ok().is_some_and(|c| {
            c.bsw.iter().any(|s| {
                crate::standards::designation::inch_value(&s.size)
                    .is_some_and(|d| (d * 25.4 - t.nominal_diameter).abs() < 1e-6)
                    && (25.4 / s.tpi - t.pitch).abs() < 1e-9
            })
        }),
        // UNC is ASME B1.1's coarse series: the size's UNC threads per inch (a 1/4-20 was
        // read as fine, its K 1.25 for 1.35: found on an inch program's torque).
        ThreadForm::Unified => crate::standards::data::catalog().ok().is_some_and(|c| {
            c.unified.iter().any(|s| {
                (s.d * 25.4 - t.nominal_diameter).abs() < 1e-6
                    && s.unc.is_some_and(|tpi| (25.4 / tpi - t.pitch).abs() < 1e-9)
            })
        }),
        _ => false,
    }
}

/// The tap of one tapping cycle, and where it came from.
#[derive(Clone)]
struct TapOf {
    designation: crate::standards::Designation,
    chamfer_pitches: f64,
    chamfer_given: bool,
    /// A form tap (the tool table's `form-tap:`); a tap named otherwise cuts.
    forming: bool,
    from: crate::analysis::naming::DesignationFrom,
    line: Option<usize>,
    why: Option<String>,
}

/// The tap of the tapping cycle `prog.holes[i]`: the tool table's; else, in a program verified
/// whole, the nearest comment above it (back to the tapping cycle before) that names a thread,
/// else the standard size of its lead (F per revolution, or F/S) whose basic minor diameter
/// D1 = D − 1.0825·P is nearest its drill's diameter; else refused at the cycle.
fn tap_of(
    spec: &TapSpec,
    prog: &crate::gcode::Program,
    i: usize,
    comments: &[crate::gcode::Comment],
    drill: Option<f64>,
) -> Result<TapOf, Error> {
    use crate::analysis::naming::{from_comments, infer_designation, DesignationFrom};
    let h = &prog.holes[i];
    let name = &spec.program.1;
    let perr = |message: String| at_cycle(h, name, message);
    let table = h.tool.map(|t| (t, spec.tools.tool(t)));
    // A cycle whose tool is not known (it names none, or one the table does not name): the tap
    // given (`--tap`).
    if let (None | Some((_, None)), Some(designation)) = (table, &spec.tap) {
        return Ok(TapOf {
            designation: designation.clone(),
            chamfer_pitches: crate::analysis::tools::DEFAULT_TAP_CHAMFER_PITCHES,
            chamfer_given: false,
            forming: false,
            from: DesignationFrom::Given,
            line: None,
            why: Some(match h.tool {
                None => format!("{designation}: the tap given (‹tap›) for the cycles that name no tool"),
                Some(t) => {
                    format!("{designation}: the tap given (‹tap›) for T{t}, which {}", not_named(&spec.tools))
                }
            }),
        });
    }
    if let Some((_, Some((Tool::Tap { designation, chamfer_pitches, chamfer_given, forming }, _)))) = table {
        // The tool table's tap enters here: parsed once for its hole.
        let designation =
            parse_designation(designation, ParseOptions { allow_nonstandard: spec.allow_nonstandard })?;
        return Ok(TapOf {
            designation,
            chamfer_pitches: *chamfer_pitches,
            chamfer_given: *chamfer_given,
            forming: *forming,
            from: DesignationFrom::Tool,
            line: None,
            why: None,
        });
    }
    // A tool the table calls something else is a contradiction, not a gap.
    let named_otherwise = matches!(table, Some((_, Some((Tool::Insert(_) | Tool::Drill { .. }, _)))));
    if spec.from_program && !named_otherwise {
        let opts = ParseOptions { allow_nonstandard: spec.allow_nonstandard };
        // Comments are the main program's: a hole of a subprogram file reads them at its call.
        let after = prog.holes[..i]
            .iter()
            .rev()
            .find(|o| o.kind == HoleKind::Tap && o.main_line < h.main_line)
            .map_or(0, |o| o.main_line);
        let default = crate::analysis::tools::DEFAULT_TAP_CHAMFER_PITCHES;
        let lead = match (h.feed, h.feed_per_rev, h.spindle) {
            (Some(f), true, _) => Some(f),
            (Some(f), false, Some(s)) if s > 0.0 => Some(f / s),
            _ => None,
        };
        // A CAM system's tool list that names the tool as a tap, before the nearest comment.
        let listed = h
            .tool
            .and_then(|t| crate::analysis::naming::listed_tap(comments, t, h.units, opts, lead, h.line));
        let listed = match listed {
            Some(Ok(n)) => Some(n),
            Some(Err(Error::Program { message, .. })) => return Err(perr(message)),
            Some(Err(e)) => return Err(e),
            None => None,
        };
        let named = match listed
            .or_else(|| from_comments(comments, after, h.main_line, ThreadKind::Internal, opts))
        {
            Some(n) => Some(n),
            None => match (lead, drill) {
                (Some(lead), Some(d)) => {
                    let major = d + 1.082_531_754_730_548 * lead;
                    infer_designation(
                        lead,
                        1,
                        major,
                        ThreadKind::Internal,
                        crate::gcode::ProgramUnits::Mm,
                        h.line,
                    )
                    .or_else(|e| {
                        infer_designation(
                            lead,
                            1,
                            major,
                            ThreadKind::Internal,
                            crate::gcode::ProgramUnits::Inch,
                            h.line,
                        )
                        .map_err(|_| e)
                    })
                    .ok()
                }
                _ => None,
            },
        };
        if let Some(n) = named {
            // A comment (or tool list line) that says the tap forms: `(FORM TAP M8)`,
            // `(ROLL TAP 1/4-20)`, `GEWINDEFORMER M10`.
            let forming = n.from == DesignationFrom::Comment
                && comments.iter().filter(|c| Some(c.line) == n.line).any(|c| says_forming(&c.text));
            let why = if forming { format!("{}; a form tap, as the comment says", n.why) } else { n.why };
            return Ok(TapOf {
                designation: n.designation,
                chamfer_pitches: default,
                chamfer_given: false,
                forming,
                from: n.from,
                line: n.line,
                why: Some(why),
            });
        }
    }
    // The examples in the program's units (an inch program is offered an inch tap) and its
    // dialect's comment syntax (Klartext and Sinumerik comment after `;`).
    let (example, words) = match h.units {
        crate::gcode::ProgramUnits::Mm => ("M10x1.5-6H", "TAP M10X1.5"),
        crate::gcode::ProgramUnits::Inch => ("1/4-20 UNC-2B", "TAP 1/4-20 UNC"),
    };
    let in_comment = match spec.dialect {
        Dialect::Klartext | Dialect::Sinumerik => format!("; {words}"),
        _ => format!("({words})"),
    };
    Err(match table {
        None => perr(format!(
            "{} names no tool: the tapping check needs the tap (T and the tool table's tap:DESIGNATION, the table's in_spindle, ‹tap›{})",
            h.code,
            if spec.from_program { format!(", or a comment such as {in_comment} above the cycle") } else { String::new() }
        )),
        Some((t, Some((Tool::Insert(_) | Tool::Drill { .. }, written)))) => perr(format!(
            "{} with tool T{t}, which {} calls \"{written}\", not a tap (write {t} = \"tap:{example}\")",
            h.code, spec.tools.source
        )),
        Some((t, _)) => perr(format!(
            "{} with tool T{t}, which {} (write {t} = \"tap:{example}\" in ‹tools›, give ‹tap›{})",
            h.code,
            not_named(&spec.tools),
            if spec.from_program {
                format!(", or name the tap in a comment above the cycle: {in_comment}")
            } else {
                String::new()
            }
        )),
    })
}

/// What the tool table says of a tool it does not name: "no tool table names" when none was
/// given.
fn not_named(tools: &crate::analysis::tools::ToolTable) -> String {
    if tools.is_given() {
        format!("{} does not name", tools.source)
    } else {
        "no tool table names".to_string()
    }
}
