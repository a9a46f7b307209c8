//! The `verify` report: JSON as the CLI contract specifies, and the human table.

use crate::check::CheckFeature;
use crate::geometry::rad;
use crate::passes::{Infeed, Schedule};
use crate::standards::{Hand, ThreadKind};
use crate::verify::Verification;
use serde::Serialize;
use serde_json::{json, Value};
use std::fmt::Write as _;

/// The infeed as words (`flank 29.5°`).
pub fn infeed_text(i: &Infeed) -> String {
    match i {
        Infeed::Radial => "radial".into(),
        Infeed::Flank { angle } => format!("flank {angle}°"),
        Infeed::Alternating { angle } => format!("alternating {angle}°"),
    }
}

fn schedule_text(s: &Schedule) -> &'static str {
    match s {
        Schedule::ConstantDepth => "constant-depth",
        Schedule::ConstantArea => "constant-area",
        Schedule::Sandvik => "sandvik",
        Schedule::Explicit(_) => "explicit",
    }
}

/// The `thread` object of the reports.
#[derive(Clone, Debug, Serialize)]
pub struct ThreadReport<'a> {
    /// The designation as written.
    pub designation: &'a str,
    /// The form's name (`iso-metric`, …).
    pub form: &'static str,
    /// `external` or `internal`.
    pub kind: &'static str,
    /// Nominal diameter, mm.
    pub nominal_diameter: f64,
    /// Pitch, mm.
    pub pitch: f64,
    /// Lead, mm.
    pub lead: f64,
    /// Number of starts.
    pub starts: u32,
    /// `right` or `left`.
    pub hand: &'static str,
    /// Tolerance class.
    pub class: &'a str,
}

impl<'a> ThreadReport<'a> {
    /// The thread of a verification.
    pub fn of(v: &'a Verification) -> Self {
        let t = &v.designation.thread;
        ThreadReport {
            designation: &v.designation.text,
            form: t.form.name(),
            kind: v.kind.name(),
            nominal_diameter: t.nominal_diameter,
            pitch: t.pitch,
            lead: t.lead(),
            starts: t.starts,
            hand: if t.hand == Hand::Left { "left" } else { "right" },
            class: &v.limits.class,
        }
    }
}

/// The `thread` object of the reports, as a JSON value.
pub fn thread_json(v: &Verification) -> Value {
    serde_json::to_value(ThreadReport::of(v)).unwrap_or(Value::Null)
}

/// The `insert` object.
#[derive(Clone, Debug, Serialize)]
pub struct InsertReport<'a> {
    /// Full, partial or custom.
    pub kind: crate::insert::InsertKind,
    /// Its name (`partial 60° r0.04`).
    pub name: &'a str,
    /// Included angle, degrees.
    pub angle: f64,
    /// Tip radius, mm.
    pub tip_radius: f64,
}

/// The `plan` object.
#[derive(Clone, Debug, Serialize)]
pub struct PlanReport<'a> {
    /// The program and its dialect, `None` for a generated plan.
    pub program: Option<&'a str>,
    /// The infeed.
    pub infeed: Infeed,
    /// The depth schedule's name.
    pub schedule: &'static str,
    /// Blank (external) or bore (internal) diameter, mm.
    pub blank_diameter: f64,
    /// The last pass's X, mm.
    pub final_x: f64,
    /// The final X was solved for the middle of the d2 tolerance.
    pub final_x_solved: bool,
}

/// The per-pass chip and edge figures (absent when a run skipped them).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct PassMetricsReport {
    /// Chip area, mm².
    pub chip_area: f64,
    /// Cutting edge in contact, mm.
    pub engaged_edge: EngagedEdge,
    /// Largest chip thickness, mm.
    pub max_chip_thickness: f64,
    /// Chip area behind the tip, mm².
    pub trailing_area: f64,
}

/// Lengths of cutting edge in contact, mm.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct EngagedEdge {
    /// Leading flank.
    pub leading: f64,
    /// Trailing flank.
    pub trailing: f64,
    /// Tip radius.
    pub tip: f64,
}

/// One entry of `passes`.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct PassReport {
    /// Pass number, 1 first.
    pub index: usize,
    /// X (diameter), mm.
    pub x: f64,
    /// Axial start, mm.
    pub z: f64,
    /// Radial depth below the blank, mm.
    pub depth: f64,
    /// Start index.
    pub start: u32,
    /// Program line.
    pub source_line: Option<usize>,
    /// Chip and edge figures.
    #[serde(flatten)]
    pub metrics: Option<PassMetricsReport>,
}

/// The `measured` object: the as-cut tooth.
#[derive(Clone, Debug, Serialize)]
pub struct MeasuredReport {
    /// mm.
    pub major_diameter: f64,
    /// mm.
    pub pitch_diameter: f64,
    /// mm.
    pub minor_diameter: f64,
    /// Smallest root radius, mm.
    pub root_radius: Option<f64>,
    /// Half angles of the low-z and high-z flank, degrees.
    pub flank_angles: [f64; 2],
    /// Crest to root, mm.
    pub thread_depth: f64,
    /// Radial overlap with the basic mating part, mm.
    pub engagement_depth: f64,
    /// Crest flat, mm.
    pub crest_width: f64,
    /// Best wire and the measurement over three wires, mm.
    pub three_wire: Option<crate::measure::ThreeWire>,
    /// Signed clearance to the maximum-material profile, mm.
    pub max_material_clearance: Option<f64>,
}

/// A verdict.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Verdict {
    /// Every counted check is within its limits.
    Pass,
    /// At least one is not.
    Fail,
}

impl Verdict {
    /// `Pass` when `ok`.
    pub fn of(ok: bool) -> Verdict {
        if ok {
            Verdict::Pass
        } else {
            Verdict::Fail
        }
    }
}

/// The whole `verify --json` object of a plan, and of each program operation (docs/json.md).
#[derive(Clone, Debug, Serialize)]
pub struct VerifyReport<'a> {
    /// The thread.
    pub thread: ThreadReport<'a>,
    /// The insert.
    pub insert: InsertReport<'a>,
    /// The plan.
    pub plan: PlanReport<'a>,
    /// Every pass.
    pub passes: Vec<PassReport>,
    /// The as-cut tooth.
    pub measured: MeasuredReport,
    /// The class's limits.
    pub limits: &'a crate::tolerance::ThreadLimits,
    /// The checks.
    pub checks: &'a [crate::check::Check],
    /// The verdict.
    pub verdict: Verdict,
    /// Form checks left out of the verdict.
    pub gauge_only: bool,
    /// Helix angle at d2, degrees.
    pub helix_angle: f64,
    /// Process figures of a program's operation.
    pub process: Option<&'a crate::process::ProcessReport>,
    /// The X for mid-tolerance d2, mm.
    pub suggested_final_x: Option<f64>,
    /// Stated assumptions.
    pub notes: &'a [String],
}

impl<'a> VerifyReport<'a> {
    /// The report of a verification.
    pub fn of(v: &'a Verification) -> Self {
        let m = &v.measurement;
        let surface = rad(v.blank_diameter);
        let passes = v
            .passes
            .iter()
            .enumerate()
            .map(|(i, p)| PassReport {
                index: p.index,
                x: p.x_end,
                z: p.z_start,
                depth: (rad(p.x_end) - surface).abs(),
                start: p.start,
                source_line: p.source_line,
                metrics: v.metrics.get(i).map(|pm| PassMetricsReport {
                    chip_area: pm.chip_area,
                    engaged_edge: EngagedEdge { leading: pm.leading, trailing: pm.trailing, tip: pm.tip },
                    max_chip_thickness: pm.max_chip_thickness,
                    trailing_area: pm.trailing_area,
                }),
            })
            .collect();
        VerifyReport {
            thread: ThreadReport::of(v),
            insert: InsertReport {
                kind: v.insert.kind.clone(),
                name: &v.insert.name,
                angle: v.insert.angle,
                tip_radius: v.insert.tip_radius,
            },
            plan: PlanReport {
                program: v.program.as_deref(),
                infeed: v.infeed,
                schedule: schedule_text(&v.schedule),
                blank_diameter: v.blank_diameter,
                final_x: v.final_x,
                final_x_solved: v.final_x_solved,
            },
            passes,
            measured: MeasuredReport {
                major_diameter: m.major_diameter,
                pitch_diameter: m.pitch_diameter,
                minor_diameter: m.minor_diameter,
                root_radius: m.root_radius,
                flank_angles: m.flank_angles,
                thread_depth: m.thread_depth,
                engagement_depth: m.engagement_depth,
                crest_width: m.crest_width,
                three_wire: m.three_wire,
                max_material_clearance: m.max_material_clearance,
            },
            limits: &v.limits,
            checks: &v.checks,
            verdict: Verdict::of(v.pass),
            gauge_only: v.gauge_only,
            helix_angle: v.helix_angle,
            process: v.process.as_ref(),
            suggested_final_x: v.suggested_final_x,
            notes: &v.notes,
        }
    }
}

/// The whole `verify --json` object, as a JSON value.
pub fn verify_json(v: &Verification) -> Value {
    serde_json::to_value(VerifyReport::of(v)).unwrap_or(Value::Null)
}

fn opt(v: Option<f64>, prec: usize) -> String {
    v.map_or_else(|| "—".to_string(), |x| format!("{x:.prec$}"))
}

/// The human report: a compact table of checks with ✓/✗ and deviations in µm.
pub fn verify_text(v: &Verification) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{} {} ({}), {} insert '{}', {}, {} passes",
        v.designation.text,
        v.kind.name(),
        v.limits.class,
        match v.insert.kind {
            crate::insert::InsertKind::Full => "full-profile",
            crate::insert::InsertKind::Partial => "partial-profile",
            crate::insert::InsertKind::Custom => "custom",
        },
        v.insert.name,
        match &v.program {
            Some(p) => format!("passes from {p}"),
            None => format!("{} infeed, {}", infeed_text(&v.infeed), schedule_text(&v.schedule)),
        },
        v.passes.len()
    );
    let _ = writeln!(
        s,
        "{} X{:.4}, final X{:.4}{}",
        if v.kind == ThreadKind::External { "blank" } else { "bore" },
        v.blank_diameter,
        v.final_x,
        if v.final_x_solved {
            " (solved for mid-tolerance pitch diameter: use it as the cycle's X)"
        } else {
            ""
        }
    );
    let inch = v.units == crate::verify::Units::Inch;
    let _ = if inch {
        writeln!(
            s,
            "\n    {:<16}{:>10}{:>10}{:>10}{:>10}  kind  {:>8}{:>8}{:>8} in",
            "check", "value", "min", "max", "dev µm", "value", "min", "max"
        )
    } else {
        writeln!(s, "\n    {:<16}{:>10}{:>10}{:>10}{:>10}  kind", "check", "value", "min", "max", "dev µm")
    };
    for c in &v.checks {
        let counts = c.kind.counts(v.gauge_only);
        let mark = if c.ok {
            "✓"
        } else if counts {
            "✗"
        } else {
            "·"
        };
        let prec = if c.feature == CheckFeature::FlankAngle { 3 } else { 4 };
        let name = c.feature.label();
        let value = if c.feature == CheckFeature::SingleGroove {
            if c.ok {
                "yes".into()
            } else {
                "no".into()
            }
        } else {
            format!("{:.prec$}", c.value)
        };
        let _ = write!(
            s,
            "  {mark} {:<16}{:>10}{:>10}{:>10}{:>10.1}  {}",
            name,
            value,
            if c.feature == CheckFeature::SingleGroove { String::new() } else { opt(c.min, prec) },
            if c.feature == CheckFeature::SingleGroove { String::new() } else { opt(c.max, prec) },
            c.deviation_um,
            c.kind.name()
        );
        // Lengths in inches beside the mm (not the angles, the counts or the turns).
        let length = c.feature.is_length();
        if inch && length {
            let i = |x: Option<f64>| x.map_or_else(|| "—".to_string(), |x| format!("{:.5}", x / 25.4));
            let _ = write!(s, "  {:>8}{:>8}{:>8} in", i(Some(c.value)), i(c.min), i(c.max));
        }
        if let Some(n) = &c.note {
            let _ = write!(s, "  {n}");
        }
        s.push('\n');
    }
    let m = &v.measurement;
    let _ = writeln!(
        s,
        "\n  measured: thread depth {:.4}, flanks {:.3}°/{:.3}°{}{}",
        m.thread_depth,
        m.flank_angles[0],
        m.flank_angles[1],
        m.three_wire.map_or(String::new(), |w| format!(", M over {:.4} wires {:.4}", w.wire, w.m)),
        m.max_material_clearance
            .map_or(String::new(), |c| format!(", GO-gauge clearance {:+.1} µm", c * 1000.0))
    );
    let _ = writeln!(s, "  helix angle {:.3}° at d2: incline the insert by it", v.helix_angle);
    if let Some(p) = &v.process {
        if let Some(t) = &p.machining_time {
            let _ = writeln!(
                s,
                "  machining time {:.1} s (cutting {:.1} s, rapid {:.1} s{})",
                t.total,
                t.cutting,
                t.rapid,
                p.machine.as_ref().map_or(", rapid 5000 mm/min assumed".to_string(), |m| format!(", {m}"))
            );
        }
    }
    let failed: Vec<&str> =
        v.checks.iter().filter(|c| !c.ok && c.kind.counts(v.gauge_only)).map(|c| c.feature.name()).collect();
    if v.pass {
        let _ = writeln!(s, "\nverdict: PASS");
    } else {
        let _ = writeln!(s, "\nverdict: FAIL ({})", failed.join(", "));
    }
    if let Some(x) = v.suggested_final_x {
        let off = v
            .checks
            .iter()
            .find(|c| c.feature == CheckFeature::PitchDiameter)
            .map_or(0.0, |c| c.deviation_um);
        let _ = writeln!(
            s,
            "pitch diameter is {off:+.1} µm off: program the last pass at X{x:.4} for mid-tolerance"
        );
    }
    for n in &v.notes {
        let _ = writeln!(s, "note: {n}");
    }
    s
}

/// The `operation` object of a program report.
fn operation_json(o: &crate::gcode::Operation) -> Value {
    json!({
        "index": o.index,
        "cycle": o.cycle,
        "source_line": o.source_line,
        "tool": o.tool,
        "spindle": o.spindle,
        "infeed_angle": o.infeed_angle.as_ref().map(|(a, w)| json!({"degrees": a, "word": w})),
        "passes": o.passes.len(),
        "notes": o.notes,
    })
}

/// `verify --program --json`: the program, its verdict (the worst of its operations) and every
/// operation's full report.
pub fn program_json(pv: &crate::verify::ProgramVerification) -> Value {
    let ops: Vec<Value> = pv
        .operations
        .iter()
        .map(|o| {
            let mut v = match &o.result {
                crate::verify::OperationResult::Verified(v) => verify_json(v),
                crate::verify::OperationResult::NoCut { reason } => json!({
                    "thread": {"designation": o.designation},
                    "checks": [{"feature": "cut", "kind": "size", "ok": false, "note": reason}],
                    "verdict": "fail",
                    "reason": reason,
                }),
            };
            if let Some(obj) = v.as_object_mut() {
                obj.insert("operation".into(), operation_json(&o.operation));
            }
            v
        })
        .collect();
    json!({
        "program": pv.program,
        "dialect": pv.dialect,
        "verdict": if pv.pass() { "pass" } else { "fail" },
        "operations": ops,
        "skipped_blocks": pv.skipped_blocks,
        "notes": pv.notes,
    })
}

/// The human report of a program: one section per operation, then the program's verdict.
pub fn program_text(pv: &crate::verify::ProgramVerification) -> String {
    let mut s = String::new();
    let n = pv.operations.len();
    let _ = writeln!(s, "{}: {n} threading operation{}\n", pv.program, if n == 1 { "" } else { "s" });
    for o in &pv.operations {
        let op = &o.operation;
        let _ = writeln!(
            s,
            "== operation {} of {n}: {} at line {}{}, {} passes",
            op.index,
            op.cycle,
            op.source_line,
            op.tool.map_or(String::new(), |t| format!(", tool T{t}")),
            op.passes.len()
        );
        match &o.result {
            crate::verify::OperationResult::Verified(v) => s.push_str(&verify_text(v)),
            crate::verify::OperationResult::NoCut { reason } => {
                let _ =
                    writeln!(s, "{}: nothing to measure\n\nverdict: FAIL (no cut: {reason})", o.designation);
                for note in &op.notes {
                    let _ = writeln!(s, "note: {note}");
                }
            }
        }
        s.push('\n');
    }
    for note in &pv.notes {
        let _ = writeln!(s, "note: {note}");
    }
    if n > 1 {
        let failed: Vec<String> = pv
            .operations
            .iter()
            .filter(|o| !o.result.pass())
            .map(|o| o.operation.index.to_string())
            .collect();
        if failed.is_empty() {
            let _ = writeln!(s, "program verdict: PASS (all {n} operations)");
        } else {
            let _ = writeln!(s, "program verdict: FAIL (operation {})", failed.join(", "));
        }
    }
    s
}
