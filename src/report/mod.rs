//! The `verify` report: JSON as the CLI contract specifies, and the human table.

pub mod capability;
pub mod compare;
pub mod correct;
pub mod fit;
pub mod html;
pub mod mill;
pub(crate) mod output;
pub mod svg;
pub mod tapping;
pub mod threadmill;

use crate::analysis::check::{CheckFeature, Verdict};
use crate::analysis::verify::Verification;
pub(crate) use crate::ground::fmt::fmt_num;
use crate::ground::plane::rad;
use crate::standards::{Hand, ThreadKind};
use crate::toolpath::passes::{Infeed, Schedule};
use serde::Serialize;
use std::fmt::Write as _;

fn schedule_text(s: &Schedule) -> &'static str {
    s.name()
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
    /// The diameter the designation names, mm (NPT: the pipe's outside diameter).
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
        ThreadReport::new(&v.designation, v.kind, &v.limits.class)
    }

    /// The thread of a designation, cut as `kind`, in class `class`.
    pub fn new(designation: &'a crate::standards::Designation, kind: ThreadKind, class: &'a str) -> Self {
        let t = &designation.thread;
        ThreadReport {
            designation: &designation.text,
            form: t.form.name(),
            kind: kind.name(),
            nominal_diameter: crate::standards::tolerance::named_diameter(t),
            pitch: t.pitch,
            lead: t.lead(),
            starts: t.starts,
            hand: match t.hand {
                Hand::Left => "left",
                Hand::Right => "right",
            },
            class,
        }
    }
}

/// The `insert` object.
#[derive(Clone, Debug, Serialize)]
pub struct InsertReport<'a> {
    /// Full, partial or custom.
    pub kind: crate::geometry::insert::InsertKind,
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
    pub program: Option<&'a crate::analysis::verify::ProgramLabel>,
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
    /// The highest fin or notch inside the groove, mm (0: the profile falls cleanly from each
    /// crest to the root).
    pub fin_height: f64,
    /// Best wire and the measurement over three wires, mm.
    pub three_wire: Option<crate::geometry::measure::ThreeWire>,
    /// Signed clearance to the maximum-material profile, mm.
    pub max_material_clearance: Option<f64>,
    /// The functional (virtual) pitch diameter, where the program's lead deviates, mm.
    pub functional_pitch_diameter: Option<f64>,
}

impl MeasuredReport {
    /// The `measured` object of a measurement (and the functional d2 where a lead deviates).
    pub fn of(m: &crate::geometry::measure::Measurement, functional_pitch_diameter: Option<f64>) -> Self {
        MeasuredReport {
            major_diameter: m.major_diameter,
            pitch_diameter: m.pitch_diameter,
            minor_diameter: m.minor_diameter,
            root_radius: m.root_radius,
            flank_angles: m.flank_angles,
            thread_depth: m.thread_depth,
            engagement_depth: m.engagement_depth,
            crest_width: m.crest_width,
            fin_height: m.fin_height,
            three_wire: m.three_wire,
            max_material_clearance: m.max_material_clearance,
            functional_pitch_diameter,
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
    pub limits: &'a crate::standards::tolerance::ThreadLimits,
    /// The checks, each with its cells as the text, SVG and HTML tables show them.
    pub checks: Vec<CheckReport<'a>>,
    /// The verdict.
    pub verdict: Verdict,
    /// Form checks left out of the verdict.
    pub gauge_only: bool,
    /// Helix angle at d2, degrees.
    pub helix_angle: f64,
    /// Process figures of a program's operation.
    pub process: Option<&'a crate::analysis::process::ProcessReport>,
    /// The last pass's X for mid-tolerance d2, mm, whether d2 is off or not (null only when no
    /// X helps: a start missing).
    pub suggested_final_x: Option<f64>,
    /// A program lead that matches the designation's only after rounding, and its effect.
    pub lead_deviation: Option<&'a crate::analysis::lead::LeadDeviation>,
    /// The correction in the program's own word, when d2 is off.
    pub correction: Option<CorrectionReport<'a>>,
    /// What failing form checks say about the insert or the infeed.
    pub hints: Vec<HintReport<'a>>,
    /// Stated assumptions.
    pub notes: &'a [crate::ground::note::Note],
    /// The normal deviation from the basic profile along one pitch, as the picture plots it
    /// (when the verification carries its picture).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub deviation: Option<&'a crate::analysis::picture::Deviation>,
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
                program: v.program.as_ref(),
                infeed: v.infeed,
                schedule: schedule_text(&v.schedule),
                blank_diameter: v.blank_diameter,
                final_x: v.final_x,
                final_x_solved: v.final_x_solved,
            },
            passes,
            measured: MeasuredReport::of(m, v.functional_pitch_diameter),
            lead_deviation: v.lead_deviation.as_ref(),
            correction: v
                .correction
                .as_ref()
                .map(|c| CorrectionReport { text: correction_text(c), correction: c }),
            hints: v.hints.iter().map(|h| HintReport { hint: h, text: hint_text(h) }).collect(),
            limits: &v.limits,
            checks: v.checks.iter().map(|c| CheckReport { check: c, shown: check_cells(c) }).collect(),
            verdict: Verdict::of(v.pass),
            gauge_only: v.gauge_only,
            helix_angle: v.helix_angle,
            process: v.process.as_ref(),
            suggested_final_x: v.middle_final_x,
            notes: &v.notes,
            deviation: v.picture.as_ref().map(|p| &p.deviation),
        }
    }
}

/// A hint with its sentence.
#[derive(Clone, Debug, Serialize)]
pub struct HintReport<'a> {
    /// The hint and its figures.
    #[serde(flatten)]
    pub hint: &'a crate::analysis::check::Hint,
    /// What to do, in words.
    pub text: String,
}

/// The correction with its sentence.
#[derive(Clone, Debug, Serialize)]
pub struct CorrectionReport<'a> {
    /// The word, its new value and place.
    #[serde(flatten)]
    pub correction: &'a crate::analysis::correction::Correction,
    /// What to do, in words.
    pub text: String,
}

/// A correction's new value at the program's increment: `0.2948` (inch), `0.930` (mm).
fn correction_number(c: &crate::analysis::correction::Correction) -> String {
    match c.units {
        crate::gcode::ProgramUnits::Mm => format!("{:.3}", c.value),
        crate::gcode::ProgramUnits::Inch => format!("{:.4}", c.value),
    }
}

/// A correction's new word as the program would write it: `X0.2948`, `K0.930`, `TDEP=0.930`,
/// `R24=0.930`.
pub fn correction_word(c: &crate::analysis::correction::Correction) -> String {
    use crate::gcode::WordForm;
    match c.form {
        WordForm::Number | WordForm::Expression => format!("{}{}", c.word, correction_number(c)),
        WordForm::Argument | WordForm::ArgumentExpression | WordForm::Parameter => {
            format!("{}={}", c.word, correction_number(c))
        }
    }
}

/// What replaces the word in place to apply a correction: the whole word (`X19.452`), or a
/// call's argument alone (`1.597`); `None` where it cannot be rewritten in place.
pub fn correction_replacement(c: &crate::analysis::correction::Correction) -> Option<String> {
    use crate::gcode::WordForm;
    match c.form {
        WordForm::Number => Some(correction_word(c)),
        WordForm::Argument => Some(correction_number(c)),
        WordForm::Expression | WordForm::ArgumentExpression | WordForm::Parameter => None,
    }
}

/// A form failure's hint as a sentence: what to change, since no final X fixes it.
pub fn hint_text(h: &crate::analysis::check::Hint) -> String {
    use crate::analysis::check::Hint;
    match *h {
        Hint::TipRadius { tip_radius, root_radius_min } => format!(
            "the insert's tip radius {} mm is under the standard's root radius {} mm, which no final X changes: use a full-profile insert (--insert full) or a tip of {} mm or more; --gauge-only judges the sizes and the GO gauge alone",
            fmt_num(tip_radius),
            fmt_num(root_radius_min),
            fmt_num(root_radius_min)
        ),
        Hint::FlankAngle { half_angle } => format!(
            "a flank stands steeper than {}°: the infeed angle (or the insert's angle) is over the flank's; infeed at {}° or a little less",
            fmt_num(half_angle),
            fmt_num(half_angle)
        ),
        Hint::Groove => "the passes do not follow one groove (a fin, a notch or a second pocket): check the infeed angle against the flank and every pass's start phase".into(),
    }
}

/// The tip radius of an insert whose tip alone fails a verification: every failing check that
/// counts is a form check and the tip-radius hint stands (the first run of a newcomer, with the
/// assumed partial-profile insert). `None` otherwise.
pub(crate) fn form_only_from_tip(v: &Verification) -> Option<f64> {
    let mut failing = v.checks.iter().filter(|c| !c.ok && c.kind.counts(v.gauge_only)).peekable();
    failing.peek()?;
    if !failing.all(|c| c.kind == crate::analysis::check::CheckKind::Form) {
        return None;
    }
    v.hints.iter().find_map(|h| match *h {
        crate::analysis::check::Hint::TipRadius { tip_radius, .. } => Some(tip_radius),
        _ => None,
    })
}

/// The sentence of a correction: `change X19.462 at line 12 to X19.452 (mm, diameter)`.
pub fn correction_text(c: &crate::analysis::correction::Correction) -> String {
    let what = match c.means {
        crate::gcode::WordMeans::Diameter => "diameter",
        crate::gcode::WordMeans::Radius => "radius",
        crate::gcode::WordMeans::Depth { .. } => "thread depth",
    };
    let mut at = format!("line {}:{}", c.line, c.column);
    if !c.also.is_empty() {
        let more: Vec<String> = c.also.iter().map(|p| format!("{}:{}", p.line, p.column)).collect();
        at = format!("lines {}:{} and {} (one cycle per start)", c.line, c.column, more.join(", "));
    }
    let word = &c.word;
    let place = match c.form {
        crate::gcode::WordForm::Number => format!("change {} at {at} to {}", c.written, correction_word(c)),
        // A call's argument: `change TDEP 1.400 at line 3:34 to 1.597`.
        crate::gcode::WordForm::Argument => {
            format!("change {word} {} at {at} to {}", c.written, correction_number(c))
        }
        crate::gcode::WordForm::Expression | crate::gcode::WordForm::ArgumentExpression => {
            format!("make {word} (written {} at {at}) {}", c.written, correction_word(c))
        }
        crate::gcode::WordForm::Parameter => {
            format!("set {word} (read by the call at line {}) to {}", c.line, correction_word(c))
        }
    };
    let mut text = format!("{place} ({}, {what})", c.units.name());
    if !c.deeper.is_empty() {
        let words: Vec<String> =
            c.deeper.iter().map(|d| format!("{} at line {}:{}", d.written, d.line, d.column)).collect();
        let (verb, them) = if words.len() == 1 { ("cuts", "it") } else { ("cut", "them") };
        text.push_str(&format!(
            "; {} {verb} deeper than that: set {them} to {} too",
            words.join(" and "),
            correction_word(c)
        ));
    }
    text
}

/// A value with `prec` decimals, or a dash when there is none.
pub(crate) fn opt(v: Option<f64>, prec: usize) -> String {
    v.map_or_else(|| "—".to_string(), |x| format!("{x:.prec$}"))
}

/// A check's value, limits and deviation as the tables show them, each in the check's own
/// unit: lengths to 0.1 µm with the deviation in µm, angles to 0.001°, speeds and feeds whole,
/// yes/no checks in words; the deviation is empty inside the limits.
#[derive(Clone, Debug, Serialize)]
pub(crate) struct CheckCells {
    pub value: String,
    pub min: String,
    pub max: String,
    pub deviation: String,
    /// The value's and limits' unit (`mm`, `°`, `turn`, `rpm`, `mm/min`; empty for counts,
    /// tapers and yes/no).
    pub unit: &'static str,
}

/// A check as the JSON gives it: its numbers, and (`shown`) its cells as every table shows
/// them, so that the page reads like the SVG's table (yes/no in words, signed deviations in the
/// check's unit).
#[derive(Clone, Debug, Serialize)]
pub struct CheckReport<'a> {
    #[serde(flatten)]
    check: &'a crate::analysis::check::Check,
    shown: CheckCells,
}

pub(crate) fn check_cells(c: &crate::Check) -> CheckCells {
    use crate::CheckUnit as U;
    let unit = c.feature.unit();
    let prec = match unit {
        U::Mm => 4,
        U::Degree | U::Turn => 3,
        U::DiameterPerLength => 5,
        U::Count | U::Rpm | U::MmPerMin | U::YesNo => 0,
    };
    let lim = |v: Option<f64>| if unit == U::YesNo { String::new() } else { opt(v, prec) };
    let value = match unit {
        U::YesNo => (if c.value != 0.0 { "yes" } else { "no" }).to_string(),
        _ => format!("{:.prec$}", c.value),
    };
    // Outside the limits: by how much, in the check's unit (lengths as the analysis measured
    // them, to the true limit).
    let over = match (c.min, c.max) {
        (_, Some(max)) if c.value > max => c.value - max,
        (Some(min), _) if c.value < min => c.value - min,
        _ => 0.0,
    };
    let deviation = if c.ok {
        String::new()
    } else {
        match unit {
            U::Mm => format!("{:+.1} µm", c.deviation_um),
            U::Degree => format!("{over:+.3}°"),
            U::Turn => format!("{over:+.3} turn"),
            U::DiameterPerLength => format!("{over:+.5}"),
            U::Count => format!("{over:+.0}"),
            U::Rpm => format!("{over:+.0} rpm"),
            U::MmPerMin => format!("{over:+.0} mm/min"),
            U::YesNo => String::new(),
        }
    };
    let unit = match unit {
        U::Mm => "mm",
        U::Degree => "°",
        U::Turn => "turn",
        U::Rpm => "rpm",
        U::MmPerMin => "mm/min",
        U::Count | U::DiameterPerLength | U::YesNo => "",
    };
    CheckCells { value, min: lim(c.min), max: lim(c.max), deviation, unit }
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
            crate::geometry::insert::InsertKind::Full => "full-profile",
            crate::geometry::insert::InsertKind::Partial => "partial-profile",
            crate::geometry::insert::InsertKind::Custom => "custom",
        },
        v.insert.name,
        match &v.program {
            Some(p) => format!("passes from {p}"),
            None => format!("{} infeed, {}", v.infeed, schedule_text(&v.schedule)),
        },
        v.passes.len()
    );
    let inch = v.units == crate::analysis::verify::Units::Inch;
    // With --units inch, a length in inches beside the mm.
    let also = |mm: f64| if inch { format!(" ({:.5} in)", mm / 25.4) } else { String::new() };
    let also_um = |um: f64| if inch { format!(" ({:+.5} in)", um / 25_400.0) } else { String::new() };
    let _ = writeln!(
        s,
        "{} X{:.4}{}, final X{:.4}{}{}",
        if v.kind == ThreadKind::External { "blank" } else { "bore" },
        v.blank_diameter,
        also(v.blank_diameter),
        v.final_x,
        also(v.final_x),
        if v.final_x_solved {
            " (solved for mid-tolerance pitch diameter: use it as the cycle's X)"
        } else {
            ""
        }
    );
    let _ = if inch {
        writeln!(
            s,
            "\n    {:<16}{:>10}{:>10}{:>10}{:>12}  kind  {:>8}{:>8}{:>8} in",
            "check", "value", "min", "max", "deviation", "value", "min", "max"
        )
    } else {
        writeln!(s, "\n    {:<16}{:>10}{:>10}{:>10}{:>12}  kind", "check", "value", "min", "max", "deviation")
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
        let cells = check_cells(c);
        let _ = write!(
            s,
            "  {mark} {:<16}{:>10}{:>10}{:>10}{:>12}  {}",
            c.feature.label(),
            cells.value,
            cells.min,
            cells.max,
            cells.deviation,
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
        "\n  measured: thread depth {:.4}{}, flanks {:.3}°/{:.3}°{}{}",
        m.thread_depth,
        also(m.thread_depth),
        m.flank_angles[0],
        m.flank_angles[1],
        m.three_wire.map_or(String::new(), |w| format!(
            ", M over {:.4}{} wires {:.4}{}",
            w.wire,
            also(w.wire),
            w.m,
            also(w.m)
        )),
        m.max_material_clearance.map_or(String::new(), |c| format!(
            ", GO-gauge clearance {:+.1} µm{}",
            c * 1000.0,
            also_um(c * 1000.0)
        ))
    );
    if let (Some(ld), Some(f)) = (&v.lead_deviation, v.functional_pitch_diameter) {
        let _ = writeln!(
            s,
            "  lead {:.6} mm (the program's, at its {} {} increment) against {:.6} mm: {:+.2} µm over the {:.2} mm the finishing pass threads; functional pitch diameter {f:.4} ({:+.2} µm), what a GO gauge sees",
            ld.program_lead,
            crate::ground::fmt::fmt_num(ld.increment),
            ld.units.name(),
            ld.designation_lead,
            ld.cumulative * 1000.0,
            ld.length,
            (f - m.pitch_diameter) * 1000.0
        );
    }
    let _ = writeln!(s, "  helix angle {:.3}° at d2: incline the insert by it", v.helix_angle);
    if let Some(p) = &v.process {
        if let Some(t) = &p.machining_time {
            let _ = writeln!(
                s,
                "  machining time {:.1} s (cutting {:.1} s, rapid {:.1} s{})",
                t.total,
                t.cutting,
                t.rapid,
                p.machine.as_ref().map_or(
                    format!(", rapid {} mm/min assumed", crate::analysis::process::ASSUMED_RAPID_MM_MIN),
                    |m| format!(", {m}"),
                )
            );
        }
    }
    let failed: Vec<&str> = v
        .checks
        .iter()
        .filter(|c| !c.ok && c.kind.counts(v.gauge_only))
        .map(|c| c.feature.words(v.kind))
        .collect();
    if v.pass {
        let _ = writeln!(s, "\nverdict: PASS");
    } else {
        let form = form_only_from_tip(v).map_or(String::new(), |tip| {
            format!(
                " — form only, from the insert's {} mm tip: --insert full cuts the standard root; --gauge-only judges the sizes and the GO gauge alone",
                fmt_num(tip)
            )
        });
        let _ = writeln!(s, "\nverdict: FAIL ({}){form}", failed.join(", "));
    }
    if let Some(x) = v.suggested_final_x {
        let failed = |f: CheckFeature| v.checks.iter().find(|c| c.feature == f && !c.ok);
        let off = if let Some(gp) = failed(CheckFeature::GaugePlane) {
            format!("the gauge plane is {:+.3} turn from its basic position", gp.value)
        } else if let Some(d2) = failed(CheckFeature::PitchDiameter) {
            format!("pitch diameter is {:+.1} µm{} off", d2.deviation_um, also_um(d2.deviation_um))
        } else if let Some(f) = failed(CheckFeature::FunctionalPitchDiameter) {
            format!(
                "the functional pitch diameter is {:+.1} µm{} off",
                f.deviation_um,
                also_um(f.deviation_um)
            )
        } else {
            "the pitch diameter is off".to_string()
        };
        match &v.correction {
            Some(c) => {
                let _ = writeln!(
                    s,
                    "{off}: {} for mid-tolerance (the last pass at X{x:.4} mm{} on the diameter)",
                    correction_text(c),
                    if inch { format!(", {:.5} in,", x / 25.4) } else { String::new() }
                );
            }
            None => {
                let _ = writeln!(s, "{off}: program the last pass at X{x:.4}{} for mid-tolerance", also(x));
            }
        }
    }
    for h in &v.hints {
        let _ = writeln!(s, "hint: {}", hint_text(h));
    }
    for n in &v.notes {
        let _ = writeln!(s, "note: {n}");
    }
    s
}

/// The infeed angle a cycle was given.
#[derive(Clone, Debug, Serialize)]
pub struct InfeedAngleReport<'a> {
    /// Degrees from the radial.
    pub degrees: f64,
    /// The word that gave it (`R29`, `IANG`, `Q`, `A/2`).
    pub word: &'a str,
}

/// The `operation` object of a program report.
#[derive(Clone, Debug, Serialize)]
pub struct OperationInfo<'a> {
    /// 1-based, in program order.
    pub index: usize,
    /// The cycle (`G76`, `G33`, `L97`, …).
    pub cycle: &'a str,
    /// First program line.
    pub source_line: usize,
    /// The T number, if named.
    pub tool: Option<u32>,
    /// Spindle state.
    pub spindle: crate::gcode::Spindle,
    /// The infeed angle, when the cycle has one.
    pub infeed_angle: Option<InfeedAngleReport<'a>>,
    /// Number of passes.
    pub passes: usize,
    /// Warnings and assumed defaults.
    pub notes: &'a [crate::ground::note::Note],
}

impl<'a> OperationInfo<'a> {
    /// The object of an operation.
    pub fn of(o: &'a crate::gcode::Operation) -> Self {
        OperationInfo {
            index: o.index,
            cycle: &o.cycle,
            source_line: o.source_line,
            tool: o.tool,
            spindle: o.spindle,
            infeed_angle: o.infeed_angle.as_ref().map(|(a, w)| InfeedAngleReport { degrees: *a, word: w }),
            passes: o.passes.len(),
            notes: &o.notes,
        }
    }
}

/// The designation of an operation that cut nothing.
#[derive(Clone, Debug, Serialize)]
pub struct DesignationOnly<'a> {
    /// As written.
    pub designation: &'a str,
}

/// The one check of an operation that cut nothing: `cut`, not ok.
#[derive(Clone, Debug, Serialize)]
pub struct NoCutCheck<'a> {
    /// Always `cut`.
    pub feature: &'static str,
    /// Always `size`.
    pub kind: crate::analysis::check::CheckKind,
    /// Always false.
    pub ok: bool,
    /// Why.
    pub note: &'a str,
}

/// One entry of a program report's `operations`: a full verify report, or the reason nothing
/// was cut; both with the `operation` object.
#[derive(Clone, Debug, Serialize)]
#[serde(untagged)]
pub enum OperationReport<'a> {
    /// Cut and measured.
    Verified {
        /// The verify report's keys.
        #[serde(flatten)]
        report: Box<VerifyReport<'a>>,
        /// The operation.
        operation: OperationInfo<'a>,
    },
    /// Nothing to measure.
    NoCut {
        /// The designation.
        thread: DesignationOnly<'a>,
        /// One failing `cut` check.
        checks: [NoCutCheck<'a>; 1],
        /// Always `fail`.
        verdict: Verdict,
        /// Why.
        reason: &'a str,
        /// The last pass's X that cuts the thread mid-tolerance with this insert from this
        /// blank, mm (null when no plan can).
        suggested_final_x: Option<f64>,
        /// The operation.
        operation: OperationInfo<'a>,
    },
}

/// The next step of an operation that cuts nothing: the final X that would.
pub(crate) fn no_cut_next(suggested_final_x: Option<f64>) -> Option<String> {
    suggested_final_x.map(|x| {
        format!("a last pass at X{x:.4} (diameter, mm) cuts this thread mid-tolerance with this insert")
    })
}

/// `verify --program --json`: the program, its verdict (the worst of its operations) and every
/// operation's full report (docs/json.md).
#[derive(Clone, Debug, Serialize)]
pub struct ProgramReport<'a> {
    /// The program's name and dialect.
    pub program: &'a crate::analysis::verify::ProgramLabel,
    /// The dialect.
    pub dialect: crate::gcode::Dialect,
    /// The worst verdict.
    pub verdict: Verdict,
    /// Every operation.
    pub operations: Vec<OperationReport<'a>>,
    /// Blocks read for position only.
    pub skipped_blocks: usize,
    /// Blocks read past: something in them threadcheck does not model (each named in a note).
    pub read_past_blocks: usize,
    /// Program-wide warnings.
    pub notes: &'a [crate::ground::note::Note],
}

impl<'a> ProgramReport<'a> {
    /// The report of a program's verification.
    pub fn of(pv: &'a crate::analysis::verify::ProgramVerification) -> Self {
        let operations = pv
            .operations
            .iter()
            .map(|o| {
                let operation = OperationInfo::of(&o.operation);
                match &o.result {
                    crate::analysis::verify::OperationResult::Verified(v) => {
                        OperationReport::Verified { report: Box::new(VerifyReport::of(v)), operation }
                    }
                    crate::analysis::verify::OperationResult::NoCut { reason, suggested_final_x } => {
                        OperationReport::NoCut {
                            suggested_final_x: *suggested_final_x,
                            thread: DesignationOnly { designation: &o.designation },
                            checks: [NoCutCheck {
                                feature: "cut",
                                kind: crate::analysis::check::CheckKind::Size,
                                ok: false,
                                note: reason,
                            }],
                            verdict: Verdict::Fail,
                            reason,
                            operation,
                        }
                    }
                }
            })
            .collect();
        ProgramReport {
            program: &pv.program,
            dialect: pv.dialect,
            verdict: Verdict::of(pv.pass()),
            operations,
            skipped_blocks: pv.skipped_blocks,
            read_past_blocks: pv.read_past_blocks,
            notes: &pv.notes,
        }
    }
}

/// How many blocks were read past, for a header line: empty when none.
pub fn read_past_text(blocks: usize) -> String {
    match blocks {
        0 => String::new(),
        1 => ", 1 block read past (named in the notes)".into(),
        n => format!(", {n} blocks read past (named in the notes)"),
    }
}

/// The human report of a program: one section per operation, then the program's verdict.
pub fn program_text(pv: &crate::analysis::verify::ProgramVerification) -> String {
    let mut s = String::new();
    let n = pv.operations_in_program;
    let named = match pv.operations.as_slice() {
        [o] if n > 1 => format!(" (operation {} checked)", o.operation.index),
        _ => String::new(),
    };
    let _ = writeln!(
        s,
        "{}: {n} threading operation{}{named}{}\n",
        pv.program,
        if n == 1 { "" } else { "s" },
        read_past_text(pv.read_past_blocks)
    );
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
            crate::analysis::verify::OperationResult::Verified(v) => s.push_str(&verify_text(v)),
            crate::analysis::verify::OperationResult::NoCut { reason, suggested_final_x } => {
                let _ =
                    writeln!(s, "{}: nothing to measure\n\nverdict: FAIL (no cut: {reason})", o.designation);
                if let Some(next) = no_cut_next(*suggested_final_x) {
                    let _ = writeln!(s, "next: {next}");
                }
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

/// One operation of `passes --json`.
#[derive(Clone, Debug, Serialize)]
pub struct PassesOperation<'a> {
    /// 1-based, in program order.
    pub index: usize,
    /// The cycle (`G76`, `G33`, `L97`, …).
    pub cycle: &'a str,
    /// First program line.
    pub source_line: usize,
    /// The T number, if named.
    pub tool: Option<u32>,
    /// Spindle state.
    pub spindle: crate::gcode::Spindle,
    /// Lead, mm.
    pub lead: f64,
    /// Warnings and assumed defaults.
    pub notes: &'a [crate::ground::note::Note],
    /// Its passes.
    pub passes: &'a [crate::toolpath::passes::Pass],
}

/// `passes --json` (docs/json.md).
#[derive(Clone, Debug, Serialize)]
pub struct PassesReport<'a> {
    /// The thread, when one was given.
    pub thread: Option<ThreadReport<'a>>,
    /// Largest Z any pass reaches, mm.
    pub thread_start: f64,
    /// Smallest Z any pass reaches, mm.
    pub thread_end: f64,
    /// Every pass in cutting order.
    pub passes: &'a [crate::toolpath::passes::Pass],
    /// A program's passes by operation.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub operations: Option<Vec<PassesOperation<'a>>>,
    /// A program's notes (assumptions, what was read past).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub notes: Option<&'a [crate::ground::note::Note]>,
    /// A program's blocks read past (each kind named in `notes`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub read_past_blocks: Option<usize>,
}

impl<'a> PassesReport<'a> {
    /// The report of `passes`, grouped by `operations` when they come from a program.
    pub fn new(
        thread: Option<ThreadReport<'a>>,
        passes: &'a [crate::toolpath::passes::Pass],
        operations: Option<&'a [crate::gcode::Operation]>,
        program: Option<(&'a [crate::ground::note::Note], usize)>,
    ) -> Self {
        let (thread_start, thread_end) =
            passes.iter().fold((f64::NEG_INFINITY, f64::INFINITY), |(a, b), p| {
                (a.max(p.z_start.max(p.z_end)), b.min(p.z_start.min(p.z_end)))
            });
        PassesReport {
            thread,
            thread_start,
            thread_end,
            passes,
            notes: program.map(|p| p.0),
            read_past_blocks: program.map(|p| p.1),
            operations: operations.map(|ops| {
                ops.iter()
                    .map(|op| PassesOperation {
                        index: op.index,
                        cycle: &op.cycle,
                        source_line: op.source_line,
                        tool: op.tool,
                        spindle: op.spindle,
                        lead: op.lead(),
                        notes: &op.notes,
                        passes: &op.passes,
                    })
                    .collect()
            }),
        }
    }
}

/// The `basic` object of `limits --json`: the basic sizes, rounded as the tables print them.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct BasicReport {
    /// d = D, mm.
    pub major_diameter: f64,
    /// d2 = D2, mm.
    pub pitch_diameter: f64,
    /// d3, mm.
    pub minor_diameter_external: f64,
    /// D1, mm.
    pub minor_diameter_internal: f64,
    /// H, mm.
    pub fundamental_triangle_height: f64,
}

/// `limits --json` (docs/json.md).
#[derive(Clone, Debug, Serialize)]
pub struct LimitsReport<'a> {
    /// As written.
    pub designation: &'a str,
    /// The form's name.
    pub form: &'static str,
    /// mm.
    pub nominal_diameter: f64,
    /// mm.
    pub pitch: f64,
    /// mm.
    pub lead: f64,
    /// Number of starts.
    pub starts: u32,
    /// `right` or `left`.
    pub hand: &'static str,
    /// Outside the standard series.
    pub nonstandard: bool,
    /// Basic sizes.
    pub basic: BasicReport,
    /// The external thread's limits, when the designation has an external class.
    pub external: Option<&'a crate::standards::tolerance::ThreadLimits>,
    /// The internal thread's limits.
    pub internal: Option<&'a crate::standards::tolerance::ThreadLimits>,
}

impl<'a> LimitsReport<'a> {
    /// The report of a designation's limits.
    pub fn new(
        des: &'a crate::standards::Designation,
        external: Option<&'a crate::standards::tolerance::ThreadLimits>,
        internal: Option<&'a crate::standards::tolerance::ThreadLimits>,
    ) -> Self {
        let t = &des.thread;
        let (major_diameter, pitch_diameter, minor_diameter_external, minor_diameter_internal, h) =
            crate::standards::tolerance::basic_rounded(t);
        LimitsReport {
            designation: &des.text,
            form: t.form.name(),
            nominal_diameter: crate::standards::tolerance::named_diameter(t),
            pitch: t.pitch,
            lead: t.lead(),
            starts: t.starts,
            hand: match t.hand {
                Hand::Left => "left",
                Hand::Right => "right",
            },
            nonstandard: des.nonstandard,
            basic: BasicReport {
                major_diameter,
                pitch_diameter,
                minor_diameter_external,
                minor_diameter_internal,
                fundamental_triangle_height: h,
            },
            external,
            internal,
        }
    }
}

/// A case of `sweep --json` that could not be verified.
#[derive(Clone, Debug, Serialize)]
pub struct CaseError<'a> {
    /// The case's label.
    pub case: &'a str,
    /// The one-line error.
    pub error: String,
}

/// One line of `sweep --export-placements`: what an outside baseline needs to redo the cut.
#[derive(Clone, Debug, Serialize)]
pub struct PlacementsLine<'a> {
    /// The case's label.
    pub case: &'a str,
    /// `external` or `internal`.
    pub kind: &'static str,
    /// mm.
    pub pitch: f64,
    /// Axial position of the measured groove, mm.
    pub z_ref: f64,
    /// The blank's outline, (z, r) mm.
    pub blank: Vec<[f64; 2]>,
    /// Every insert placement's outline, (z, r) mm.
    pub placements: Vec<Vec<[f64; 2]>>,
    /// Measured d2, mm.
    pub pitch_diameter: f64,
    /// threadcheck's best time for the same cut (sweep and pitch diameter), s.
    pub threadcheck_seconds: f64,
    /// threadcheck's best time for the case's whole verify, s.
    pub verify_seconds: f64,
}

/// The JSON text of a report: pretty, with a final newline.
pub fn to_json_pretty<T: Serialize>(v: &T) -> Result<String, crate::Error> {
    let mut s = serde_json::to_string_pretty(v).map_err(|e| crate::Error::Data(e.to_string()))?;
    s.push('\n');
    Ok(s)
}

/// The JSON text of a report on one line, with a final newline (JSON Lines).
pub fn to_json_line<T: Serialize>(v: &T) -> Result<String, crate::Error> {
    let mut s = serde_json::to_string(v).map_err(|e| crate::Error::Data(e.to_string()))?;
    s.push('\n');
    Ok(s)
}
