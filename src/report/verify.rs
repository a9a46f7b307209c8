//! `verify`'s report: the JSON contract's views of a verification and of a program's
//! operations, the text table, the SVG cross-sections (layers are `<g id="…">` groups: `title`,
//! `blank`, `tolerance-zone`, `basic-profile`, `passes`, `as-cut`, `dimensions`, `legend`,
//! `chip-chart`, each view (`tooth`, `window`) holding its own copies; text from user input is
//! escaped by the `svg` crate) and the self-contained HTML page.

use super::kit::*;
use super::*;
use crate::analysis::check::{CheckFeature, Verdict};
use crate::analysis::picture::Picture;
use crate::analysis::program::ProgramVerification;
use crate::analysis::turn::OperationResult;
use crate::analysis::turn::Verification;
use crate::geometry::insert::Insert;
use crate::geometry::measure::{DeviationSample, ProfileRegion};
use crate::ground::plane::{rad, Point};
use crate::standards::ThreadKind;
use crate::toolpath::passes::Infeed;
use serde::Serialize;
use std::fmt::Write as _;
use svg::node::element::{Group, Line, Polygon, Polyline, Rectangle};
use svg::Document;

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
            hand: t.hand.name(),
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
    pub program: Option<&'a crate::analysis::turn::ProgramLabel>,
    /// The infeed: the options' for a generated plan; for a program's passes the one they
    /// follow (`null` when they follow no single one).
    pub infeed: Option<Infeed>,
    /// The depth schedule's name; for a program's passes the law they follow
    /// (`constant-area`, `constant-depth`, else `programmed`).
    pub schedule: &'static str,
    /// Where the infeed and the schedule come from: `options` (a generated plan) or `passes`
    /// (read back from a program's passes).
    pub from: &'static str,
    /// For a program's passes: how many leading passes follow the law (the rest run to the
    /// final depth) and its first depth (mm, radial).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub law_passes: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub first_depth: Option<f64>,
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
    /// An internal 60° thread's percent of thread from its bore (issue 64); absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub thread_percent: Option<crate::analysis::percent::ThreadPercent>,
    /// The last pass's X for mid-tolerance d2, mm, whether d2 is off or not (null only when no
    /// X helps: a start missing).
    pub suggested_final_x: Option<f64>,
    /// A program lead that matches the designation's only after rounding, and its effect.
    pub lead_deviation: Option<&'a crate::analysis::turn::lead::LeadDeviation>,
    /// The correction in the program's own word, when d2 is off.
    pub correction: Option<CorrectionReport<'a>>,
    /// What failing form checks say about the insert or the infeed.
    pub hints: Vec<HintReport<'a>>,
    /// The checks that rest on a tool nobody chose (their `unverified` says what was
    /// assumed): reported, never failed.
    pub unverified: Vec<crate::analysis::check::CheckFeature>,
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
                infeed: v.cut_plan.map_or(Some(v.infeed), |c| c.infeed),
                schedule: v.cut_plan.map_or_else(|| schedule_text(&v.schedule), |c| c.law.name()),
                from: if v.cut_plan.is_some() { "passes" } else { "options" },
                law_passes: v.cut_plan.and_then(|c| (c.law_passes > 0).then_some(c.law_passes)),
                first_depth: v.cut_plan.and_then(|c| c.first_depth),
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
            unverified: v.checks.iter().filter(|c| c.unverified.is_some()).map(|c| c.feature).collect(),
            limits: &v.limits,
            checks: v
                .checks
                .iter()
                .map(|c| CheckReport { check: c, shown: check_cells(c, super::Lengths(v.units)) })
                .collect(),
            verdict: Verdict::of(v.pass),
            gauge_only: v.gauge_only,
            helix_angle: v.helix_angle,
            process: v.process.as_ref(),
            thread_percent: v.thread_percent,
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
    pub correction: &'a crate::analysis::turn::correction::Correction,
    /// What to do, in words.
    pub text: String,
}

/// The tip radius of an insert whose tip alone fails a verification: every failing check that
/// counts is a form check and the tip-radius hint stands (the first run of a newcomer, with the
/// assumed partial-profile insert). `None` otherwise.
pub(crate) fn form_only_from_tip(v: &Verification) -> Option<f64> {
    let mut failing = v.checks.iter().filter(|c| c.fails(v.gauge_only)).peekable();
    failing.peek()?;
    if !failing.all(|c| c.kind == crate::analysis::check::CheckKind::Form) {
        return None;
    }
    v.hints.iter().find_map(|h| match *h {
        crate::analysis::check::Hint::TipRadius { tip_radius, .. } => Some(tip_radius),
        _ => None,
    })
}

/// The text's check table: a row per check in the report's unit; in inch, each length's mm
/// beside it (not the angles, the counts or the turns).
fn check_rows(s: &mut String, v: &Verification, lengths: super::Lengths) {
    let inch = lengths.inch();
    let _ = if inch {
        writeln!(
            s,
            "\n    {:<16}{:>10}{:>10}{:>10}{:>12}  kind  {:>10}{:>10}{:>10} mm",
            "check", "value in", "min", "max", "deviation", "value", "min", "max"
        )
    } else {
        writeln!(s, "\n    {:<16}{:>10}{:>10}{:>10}{:>12}  kind", "check", "value", "min", "max", "deviation")
    };
    for c in &v.checks {
        let counts = c.counts(v.gauge_only);
        let mark = if c.unverified.is_some() {
            "?"
        } else if c.ok {
            "✓"
        } else if counts {
            "✗"
        } else {
            "·"
        };
        let cells = check_cells(c, lengths);
        // A cell wider than its column ("rounds to the limit") keeps two spaces before it.
        let deviation = if cells.deviation.chars().count() > 10 {
            format!("  {}", cells.deviation)
        } else {
            cells.deviation
        };
        let _ = write!(
            s,
            "  {mark} {:<16}{:>10}{:>10}{:>10}{:>12}  {}",
            c.feature.label(),
            cells.value,
            cells.min,
            cells.max,
            deviation,
            c.kind.name()
        );
        if inch && c.feature.is_length() {
            let mm = check_cells(c, super::Lengths(crate::analysis::turn::Units::Mm));
            let _ = write!(s, "  {:>10}{:>10}{:>10} mm", mm.value, mm.min, mm.max);
        }
        if let Some(n) = &c.note {
            let _ = write!(s, "  {n}");
        }
        s.push('\n');
    }
}

/// What a program's passes follow, in words: `flank 30° infeed, constant area √n × 0.4 mm a side
/// for 5 passes`.
fn cut_plan_text(c: &crate::analysis::turn::cut_plan::CutPlan) -> String {
    use crate::analysis::turn::cut_plan::DepthLaw;
    let infeed = match c.infeed {
        Some(i) => format!("{i} infeed"),
        None => "no single infeed".to_string(),
    };
    let law = match (c.law, c.first_depth) {
        (DepthLaw::ConstantArea, Some(a)) => {
            format!(
                "constant area √n × {} mm a side for {} passes",
                crate::ground::fmt::fmt_num((a * 1e4).round() / 1e4),
                c.law_passes
            )
        }
        (DepthLaw::ConstantDepth, Some(a)) => {
            format!(
                "constant depth {} mm a side for {} passes",
                crate::ground::fmt::fmt_num((a * 1e4).round() / 1e4),
                c.law_passes
            )
        }
        _ => "depths as programmed".to_string(),
    };
    format!("{infeed}, {law}")
}

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
            Some(p) => match v.cut_plan {
                Some(c) => format!("passes from {p} ({})", cut_plan_text(&c)),
                None => format!("passes from {p}"),
            },
            None => format!("{} infeed, {}", v.infeed, schedule_text(&v.schedule)),
        },
        v.passes.len()
    );
    // Lengths in the report's unit: in inch, the mm beside them.
    let l = super::Lengths(v.units);
    let _ = writeln!(
        s,
        "{} {}, final {}{}",
        if v.kind == ThreadKind::External { "blank" } else { "bore" },
        l.word("X", v.blank_diameter),
        l.word("X", v.final_x),
        if v.final_x_solved {
            " (solved for mid-tolerance pitch diameter: use it as the cycle's X)"
        } else {
            ""
        }
    );
    check_rows(&mut s, v, l);
    let m = &v.measurement;
    let _ = writeln!(
        s,
        "\n  measured: thread depth {}, flanks {:.3}°/{:.3}°{}{}",
        l.both(m.thread_depth),
        m.flank_angles[0],
        m.flank_angles[1],
        m.three_wire.map_or(String::new(), |w| format!(", M over {} wires {}", l.both(w.wire), l.both(w.m))),
        m.max_material_clearance
            .map_or(String::new(), |c| format!(", GO-gauge clearance {}", l.deviation(c * 1000.0, true)))
    );
    if let (Some(ld), Some(f)) = (&v.lead_deviation, v.functional_pitch_diameter) {
        let _ = writeln!(
            s,
            "  lead {} (the program's, at its {} {} increment) against {}: {} over the {} a gauge engages; functional pitch diameter {} ({}), what a GO gauge sees",
            l.lead(ld.program_lead),
            crate::ground::fmt::fmt_num(ld.increment),
            ld.units.name(),
            l.lead(ld.designation_lead),
            l.deviation(ld.cumulative * 1000.0, true),
            l.both(ld.length),
            l.both(f),
            l.deviation((f - m.pitch_diameter) * 1000.0, true)
        );
    }
    if let Some(t) = &v.thread_percent {
        let _ = writeln!(
            s,
            "  thread from the bore {}: {}",
            l.word("Ø", v.blank_diameter),
            super::thread_percent_words(t)
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
    let failed: Vec<&str> =
        v.checks.iter().filter(|c| c.fails(v.gauge_only)).map(|c| c.feature.words(v.kind)).collect();
    // The checks a tool nobody chose decides: named beside the verdict, never failed.
    let unverified: Vec<&str> =
        v.checks.iter().filter(|c| c.unverified.is_some()).map(|c| c.feature.words(v.kind)).collect();
    let unverified = match v.checks.iter().find_map(|c| c.unverified.as_deref()) {
        Some(why) => format!(" — form unverified ({}): {why}", unverified.join(", ")),
        None => String::new(),
    };
    if v.pass {
        let _ = writeln!(s, "\nverdict: PASS{unverified}");
    } else {
        let form = form_only_from_tip(v).map_or(unverified, |tip| {
            format!(
                " — form only, from the insert's {} mm tip: ‹insert› full cuts the standard root; ‹gauge_only› judges the sizes and the GO gauge alone",
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
            format!("pitch diameter is {} off", l.deviation(d2.deviation_um, true))
        } else if let Some(f) = failed(CheckFeature::FunctionalPitchDiameter) {
            format!("the functional pitch diameter is {} off", l.deviation(f.deviation_um, true))
        } else {
            "the pitch diameter is off".to_string()
        };
        match &v.correction {
            Some(c) => {
                let _ = writeln!(
                    s,
                    "{off}: {} for mid-tolerance (the last pass at X{} on the diameter)",
                    correction_text(c),
                    l.both(x)
                );
            }
            None => {
                let _ = writeln!(s, "{off}: program the last pass at {} for mid-tolerance", l.word("X", x));
            }
        }
    }
    for h in &v.hints {
        let _ = writeln!(s, "hint: {}", hint_text(h));
    }
    for n in &v.notes {
        let _ = writeln!(s, "note: {}", n.marked());
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
        /// Always `turned` (the key `process` is the process checks').
        made: crate::analysis::program::Process,
        /// The verify report's keys.
        #[serde(flatten)]
        report: Box<VerifyReport<'a>>,
        /// The operation.
        operation: OperationInfo<'a>,
        /// Where its designation came from: given, comment, tool or inferred.
        designation_from: crate::analysis::naming::DesignationFrom,
        /// The line of the comment that named it (of the operation, when inferred).
        designation_line: Option<usize>,
    },
    /// Nothing to measure.
    NoCut {
        /// Always `turned` (the key `process` is the process checks').
        made: crate::analysis::program::Process,
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
        /// Where its designation came from: given, comment, tool or inferred.
        designation_from: crate::analysis::naming::DesignationFrom,
        /// The line of the comment that named it (of the operation, when inferred).
        designation_line: Option<usize>,
    },
    /// A tapping cycle and its checks (`tap`'s `holes[]` entry).
    Tapped {
        /// Always `tapped`.
        made: crate::analysis::program::Process,
        /// The hole's keys.
        #[serde(flatten)]
        hole: &'a crate::analysis::tap::TappedHole,
        /// `pass` or `fail`.
        verdict: Verdict,
    },
    /// The thread-milled thread (`thread-mill`'s report).
    Milled {
        /// Always `milled`.
        made: crate::analysis::program::Process,
        /// The report's keys.
        #[serde(flatten)]
        report: Box<crate::report::thread_mill::ThreadMillJson<'a>>,
    },
    /// Helices whose cutter is not known: not checked, failing.
    NotChecked {
        /// Always `milled`.
        made: crate::analysis::program::Process,
        /// The first helix's line.
        line: usize,
        /// Why, and what to give.
        reason: &'a str,
        /// Always `fail`.
        verdict: Verdict,
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
    pub program: &'a crate::analysis::turn::ProgramLabel,
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
    /// The machine the program was read for, and why.
    pub machine: &'a crate::gcode::MachineReading,
    /// What the control will refuse and what the post got wrong, each at its line (an error
    /// fails the program).
    pub control: &'a [crate::analysis::control::ControlFinding],
}

impl<'a> ProgramReport<'a> {
    /// The report of a program's verification.
    pub fn of(pv: &'a crate::analysis::program::ProgramVerification) -> Self {
        let operations = pv
            .operations
            .iter()
            .map(|o| {
                let operation = OperationInfo::of(&o.operation);
                match &o.result {
                    crate::analysis::turn::OperationResult::Verified(v) => OperationReport::Verified {
                        made: crate::analysis::program::Process::Turned,
                        report: Box::new(VerifyReport::of(v)),
                        operation,
                        designation_from: o.named.from,
                        designation_line: o.named.line,
                    },
                    crate::analysis::turn::OperationResult::NoCut { reason, suggested_final_x } => {
                        OperationReport::NoCut {
                            made: crate::analysis::program::Process::Turned,
                            suggested_final_x: *suggested_final_x,
                            thread: DesignationOnly { designation: &o.named.designation.text },
                            checks: [NoCutCheck {
                                feature: "cut",
                                kind: crate::analysis::check::CheckKind::Size,
                                ok: false,
                                note: reason,
                            }],
                            verdict: Verdict::Fail,
                            reason,
                            operation,
                            designation_from: o.named.from,
                            designation_line: o.named.line,
                        }
                    }
                }
            })
            .chain(pv.tapped.iter().flat_map(|t| &t.holes).map(|hole| OperationReport::Tapped {
                made: crate::analysis::program::Process::Tapped,
                hole,
                verdict: Verdict::of(hole.pass),
            }))
            .chain(pv.milled.iter().map(|m| match m {
                crate::analysis::program::Milled::Checked(r) => OperationReport::Milled {
                    made: crate::analysis::program::Process::Milled,
                    report: Box::new(crate::report::thread_mill::ThreadMillJson::of(r)),
                },
                crate::analysis::program::Milled::NotChecked { line, reason } => {
                    OperationReport::NotChecked {
                        made: crate::analysis::program::Process::Milled,
                        line: *line,
                        reason,
                        verdict: Verdict::Fail,
                    }
                }
            }))
            .collect();
        ProgramReport {
            program: &pv.program,
            dialect: pv.dialect,
            verdict: Verdict::of(pv.pass()),
            operations,
            skipped_blocks: pv.skipped_blocks,
            read_past_blocks: pv.read_past_blocks,
            notes: &pv.notes,
            machine: &pv.machine,
            control: &pv.control,
        }
    }
}

/// A control finding as one sentence: `line 5 (G33.1): the tap moves X from 0 to 5 …;
/// LinuxCNC: "Bug code not g0 or g1"` (its file when not the program's own).
pub fn control_sentence(f: &crate::analysis::control::ControlFinding) -> String {
    let place = match &f.file {
        Some(file) => format!("line {} of {file}", f.line),
        None => format!("line {}", f.line),
    };
    let alarm = f.alarm.map_or(String::new(), |a| match a.number {
        Some(n) => format!("; {} alarm {n}: \"{}\"", a.control, a.text),
        None => format!("; {} refuses it: \"{}\"", a.control, a.text),
    });
    format!("{place} ({}): {}{alarm}", f.code, f.message)
}

/// The text of a program's control findings: a heading, then a line each (`✗` an error, `!`
/// a warning) with its rule and what it assumed; empty when there are none.
fn control_text(findings: &[crate::analysis::control::ControlFinding]) -> String {
    if findings.is_empty() {
        return String::new();
    }
    let errors = findings.iter().filter(|f| f.level == crate::gcode::Level::Error).count();
    let warnings = findings.len() - errors;
    let mut s = format!(
        "== before the machine: {}, {}\n\n",
        plural(errors, "error", "errors"),
        plural(warnings, "warning", "warnings")
    );
    for f in findings {
        let mark = if f.level == crate::gcode::Level::Error { "✗" } else { "!" };
        let _ = writeln!(s, "  {mark} {}", control_sentence(f));
        let _ = writeln!(s, "    rule {}", f.rule);
        if let Some(a) = &f.assumed {
            let _ = writeln!(s, "    assumed: {a}");
        }
    }
    s.push('\n');
    s
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
pub fn program_text(pv: &crate::analysis::program::ProgramVerification) -> String {
    let mut s = String::new();
    let n = pv.operations_in_program;
    let named = match pv.operations.as_slice() {
        [o] if n > 1 => format!(" (operation {} checked)", o.operation.index),
        _ => String::new(),
    };
    let what = if named.is_empty() {
        program_counts(pv)
    } else {
        format!("{n} threading operation{}", if n == 1 { "" } else { "s" })
    };
    let _ = writeln!(s, "{}: {what}{named}{}\n", pv.program, read_past_text(pv.read_past_blocks));
    for o in &pv.operations {
        let op = &o.operation;
        let _ = writeln!(
            s,
            "== operation {} of {n}: {} at line {}{}{}, {} passes",
            op.index,
            op.cycle,
            op.source_line,
            op.source_file.as_ref().map_or(String::new(), |f| format!(" of {f}")),
            op.tool.map_or(String::new(), |t| format!(", tool T{t}")),
            op.passes.len()
        );
        match &o.result {
            crate::analysis::turn::OperationResult::Verified(v) => s.push_str(&verify_text(v)),
            crate::analysis::turn::OperationResult::NoCut { reason, suggested_final_x } => {
                let _ = writeln!(
                    s,
                    "{}: nothing to measure\n\nverdict: FAIL (no cut: {reason})",
                    o.named.designation.text
                );
                if !o.named.why.is_empty() {
                    let _ = writeln!(s, "note: {}", o.named.why);
                }
                if let Some(next) = no_cut_next(*suggested_final_x) {
                    let _ = writeln!(s, "next: {next}");
                }
                for note in &op.notes {
                    let _ = writeln!(s, "note: {}", note.marked());
                }
            }
        }
        s.push('\n');
    }
    if let Some(t) = &pv.tapped {
        let _ = writeln!(
            s,
            "== tapped: {} tapping cycle{}, {} drilling cycle{}",
            t.holes.len(),
            if t.holes.len() == 1 { "" } else { "s" },
            t.drills,
            if t.drills == 1 { "" } else { "s" }
        );
        s.push_str(&crate::report::tap::holes_text(t));
        s.push('\n');
    }
    match &pv.milled {
        Some(crate::analysis::program::Milled::Checked(r)) => {
            let _ = writeln!(s, "== milled: {} helices\n", r.helices.len());
            s.push_str(&crate::report::thread_mill::text(r));
            s.push('\n');
        }
        Some(crate::analysis::program::Milled::NotChecked { line, reason }) => {
            let _ =
                writeln!(s, "== milled: helices from line {line}\n\nverdict: FAIL (not checked: {reason})\n");
        }
        None => {}
    }
    s.push_str(&control_text(&pv.control));
    for note in &pv.notes {
        let _ = writeln!(s, "note: {}", note.marked());
    }
    let tapped = pv.tapped.as_ref().map_or(0, |t| t.holes.len());
    let milled = usize::from(pv.milled.is_some());
    let refused = pv.control.iter().filter(|f| f.level == crate::gcode::Level::Error).count();
    if n + tapped + milled > 1 || refused > 0 {
        let mut failed: Vec<String> = pv
            .operations
            .iter()
            .filter(|o| !o.result.pass())
            .map(|o| format!("operation {}", o.operation.index))
            .collect();
        failed.extend(pv.tapped.iter().flat_map(|t| &t.holes).filter(|h| !h.pass).map(|h| {
            match &h.cycle.source_file {
                Some(f) => format!("the tap at line {} of {}", h.cycle.line, f),
                None => format!("the tap at line {}", h.cycle.line),
            }
        }));
        if pv.milled.as_ref().is_some_and(|m| !m.pass()) {
            failed.push("the milled thread".to_string());
        }
        if refused > 0 {
            failed.push(format!("before the machine: {}", plural(refused, "error", "errors")));
        }
        let all = process_counts(n, tapped, milled);
        if failed.is_empty() && tapped + milled == 0 {
            let _ = writeln!(s, "program verdict: PASS (all {n} operations)");
        } else if failed.is_empty() {
            let _ = writeln!(s, "program verdict: PASS ({all})");
        } else {
            let _ = writeln!(s, "program verdict: FAIL ({})", failed.join(", "));
        }
    }
    s
}

/// What a program makes, for a heading: `2 threading operations` when it only turns threads
/// (as ever), else `1 turned operation, 4 tapped holes, 1 milled thread`.
pub(crate) fn program_counts(pv: &crate::analysis::program::ProgramVerification) -> String {
    let n = pv.operations.len();
    let tapped = pv.tapped.as_ref().map_or(0, |t| t.holes.len());
    let milled = usize::from(pv.milled.is_some());
    // A program whose only thread is a tap a post wrote as a drilling cycle.
    let drilled = pv
        .control
        .iter()
        .filter(|f| {
            matches!(
                f.rule,
                r if r == crate::gcode::ControlRule::TapInDrillCycle.id()
                    || r == crate::gcode::ControlRule::TapInBoringCycle.id()
            )
        })
        .count();
    if n + tapped + milled == 0 && drilled > 0 {
        plural(drilled, "tap in a drilling or boring cycle", "taps in drilling or boring cycles")
    } else if tapped + milled == 0 {
        format!("{n} threading operation{}", if n == 1 { "" } else { "s" })
    } else {
        process_counts(n, tapped, milled)
    }
}

/// `1 error`, `2 errors`.
fn plural(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// `2 turned operations, 4 tapped holes, 1 milled thread`: the counts that are not zero.
pub(crate) fn process_counts(turned: usize, tapped: usize, milled: usize) -> String {
    let mut parts = Vec::new();
    if turned > 0 || (tapped == 0 && milled == 0) {
        parts.push(plural(turned, "turned operation", "turned operations"));
    }
    if tapped > 0 {
        parts.push(plural(tapped, "tapped hole", "tapped holes"));
    }
    if milled > 0 {
        parts.push(plural(milled, "milled thread", "milled threads"));
    }
    parts.join(", ")
}

/// The blank before threading across the panel: between the surface and the far side.
pub(crate) fn blank_polygon(f: &Frame, kind: ThreadKind, surface_r: f64, far_r: f64) -> Polygon {
    let zr = f.z_range();
    let (b0, b1) = if kind == ThreadKind::External { (far_r, surface_r) } else { (surface_r, far_r) };
    Polygon::new()
        .set(
            "points",
            f.points(&[
                Point::new(zr.0, b0),
                Point::new(zr.1, b0),
                Point::new(zr.1, b1),
                Point::new(zr.0, b1),
            ]),
        )
        .set("fill", "#e9e9e9")
        .set("stroke", "none")
}

pub(crate) fn colour(i: usize, n: usize) -> String {
    let h = if n <= 1 { 220.0 } else { 220.0 - 220.0 * i as f64 / (n - 1) as f64 };
    format!("hsl({h:.0},75%,45%)")
}

pub(crate) fn view(v: &Verification, pic: Option<&Picture>, f: &Frame, id: &str, label: &str) -> Group {
    let kind = v.kind;
    let zr = f.z_range();
    let surface = rad(v.blank_diameter);
    let far = v.section.far_r;
    let (mut g, mut body) = panel(f, id, label);
    body = body.add(Group::new().set("id", format!("{id}-blank")).add(blank_polygon(f, kind, surface, far)));
    // As-cut material.
    let mut cut = Group::new().set("id", format!("{id}-as-cut"));
    for (ext, holes) in v.section.polygons() {
        let mut d = String::new();
        for ring in std::iter::once(&ext).chain(holes.iter()) {
            d.push_str(&format!("M {} Z ", f.points(ring).replace(' ', " L ")));
        }
        cut = cut.add(
            svg::node::element::Path::new()
                .set("d", d)
                .set("fill", "#b8c7d9")
                .set("fill-rule", "evenodd")
                .set("stroke", "none"),
        );
    }
    // The tolerance zone between the maximum- and minimum-material profiles, over the material
    // and translucent: both its sides show, in material and in air.
    let zone = zone_group(pic.and_then(|p| p.zone(zr)), f, id);
    let profile = Polyline::new()
        .set("points", f.points(&v.section.profile()))
        .set("fill", "none")
        .set("stroke", "#111")
        .set("stroke-width", 2.0);
    let basic = pic.map(|p| Picture::clip(&p.basic, zr)).unwrap_or_default();
    let basic_g = Group::new().set("id", format!("{id}-basic-profile")).add(
        Polyline::new()
            .set("points", f.points(&basic))
            .set("fill", "none")
            .set("stroke", "#555")
            .set("stroke-dasharray", "6 4")
            .set("stroke-width", 1.0),
    );
    // Every pass's insert at the measured groove, coloured by order (blue first, red last).
    let mut passes = Group::new().set("id", format!("{id}-passes"));
    let n = v.passes.len();
    for (i, p) in v.passes.iter().enumerate() {
        let Some(z) = p.crossings(v.z_ref - 0.5 * p.lead, v.z_ref + 0.5 * p.lead).into_iter().next() else {
            continue;
        };
        let pts = v.insert.placed(&Insert::placement(z, rad(p.x_at(z)), kind));
        passes = passes.add(
            Polygon::new()
                .set("points", f.points(&pts))
                .set("fill", "none")
                .set("stroke", colour(i, n))
                .set("stroke-width", 0.8)
                .set("stroke-opacity", 0.8),
        );
    }
    body = body
        .add(cut)
        .add(zone)
        .add(basic_g)
        .add(passes)
        .add(Group::new().set("id", format!("{id}-profile")).add(profile));
    body = body.add(dimension_lines(&dimension_features(v), &v.checks, f, id));
    g = g.add(body);
    g.add(axes(f, true, v.units))
}

/// The diameters dimensioned in the picture: major, pitch and minor, as measured.
pub(crate) fn dimension_features(v: &Verification) -> [(crate::CheckFeature, f64); 3] {
    let m = &v.measurement;
    [
        (crate::CheckFeature::MajorDiameter, m.major_diameter),
        (crate::CheckFeature::PitchDiameter, m.pitch_diameter),
        (crate::CheckFeature::MinorDiameter, m.minor_diameter),
    ]
}

/// The dimension labels of the tooth panel, in the column left of it (`right` is the column's
/// right edge): value, limits and unit, each joined to its line by a leader, spread so that
/// no two overlap, red when out of limits.
pub(crate) fn dimension_labels(v: &Verification, f: &Frame, right: f64) -> Group {
    labels_of_dimensions(&dimension_features(v), &v.checks, v.kind, v.units, f, right)
}

/// The whole thread along its length: blank, material as cut and the cut surface.
pub(crate) fn full_view(section: &crate::geometry::sweep::Section, f: &Frame, v: &Verification) -> Group {
    let (g, mut body) = panel(f, "full-length", "full length: incomplete teeth at the thread's ends");
    body = body.add(blank_polygon(f, v.kind, section.surface_r, section.far_r));
    for (ext, _) in section.polygons() {
        body = body
            .add(Polygon::new().set("points", f.points(&ext)).set("fill", "#b8c7d9").set("stroke", "none"));
    }
    body = body.add(
        Polyline::new()
            .set("points", f.points(&section.profile()))
            .set("fill", "none")
            .set("stroke", "#111")
            .set("stroke-width", 1.2),
    );
    g.add(body).add(axes(f, true, v.units))
}

pub(crate) fn legend(x: f64, y: f64, kind: ThreadKind) -> Group {
    let mut g = Group::new().set("id", "legend");
    let blank = if kind == ThreadKind::External { "blank before threading" } else { "bore before threading" };
    let items: [(&str, &str, bool); 6] = [
        ("#e9e9e9", blank, true),
        ("#b8c7d9", "material as cut", true),
        (ZONE, "tolerance zone (solid: max. material, dashed: min.)", true),
        ("#555", "basic profile (dashed)", false),
        ("#111", "as-cut profile", false),
        ("hsl(120,75%,45%)", "insert at each pass, blue first, red last", false),
    ];
    for (i, (c, label, fill)) in items.iter().enumerate() {
        let yy = y + 16.0 * i as f64;
        if *fill {
            g = g.add(
                Rectangle::new()
                    .set("x", x)
                    .set("y", yy - 10.0)
                    .set("width", 14)
                    .set("height", 10)
                    .set("fill", *c)
                    .set("fill-opacity", if *c == ZONE { 0.35 } else { 1.0 }),
            );
        } else {
            g = g.add(
                Line::new()
                    .set("x1", x)
                    .set("x2", x + 14.0)
                    .set("y1", yy - 5.0)
                    .set("y2", yy - 5.0)
                    .set("stroke", *c)
                    .set("stroke-width", 2),
            );
        }
        g = g.add(text(x + 20.0, yy, 11.0, *label));
    }
    g
}

/// The check table: every check in words, its value, limits, deviation and verdict.
pub(crate) fn check_table(v: &Verification, x: f64, y: f64) -> (Group, f64) {
    let mut g = Group::new().set("id", "check-table");
    let title =
        if v.units == crate::analysis::turn::Units::Inch { "checks, lengths in inches" } else { "checks" };
    g = g.add(text(x, y, 12.0, title).set("font-weight", "bold"));
    let cols = [x, x + 145.0, x + 195.0, x + 305.0, x + 365.0];
    let head = ["feature", "value", "limits", "off", ""];
    for (c, h) in cols.iter().zip(head) {
        g = g.add(text(*c, y + 16.0, 10.0, h).set("fill", "#555"));
    }
    let mut yy = y + 32.0;
    for c in &v.checks {
        let counts = c.counts(v.gauge_only);
        let colour = if c.ok && counts {
            "#1d1d1d"
        } else if counts {
            FAIL
        } else {
            "#8a6d00"
        };
        // Values, limits and deviations in the check's own unit (the text table's cells).
        let cells = super::check_cells(c, super::Lengths(v.units));
        // Lengths carry their unit in the column's head; degrees stick to the number.
        let unit = match cells.unit {
            "mm" | "in" | "" => String::new(),
            "°" => "°".to_string(),
            u => format!(" {u}"),
        };
        let value = format!("{}{}", cells.value, if unit == "°" { "°" } else { "" });
        let lim = match c.feature.unit() {
            crate::CheckUnit::YesNo => String::new(),
            _ => shown_limits(c.min, c.max, &cells, &unit),
        };
        // A passing value past its shown limit (within the standard's resolution): the text's
        // "rounds to the limit", short enough for the picture's column.
        let off = if c.ok && !cells.deviation.is_empty() { "at limit".to_string() } else { cells.deviation };
        let verdict = match (c.ok, counts) {
            _ if c.unverified.is_some() => "unverified",
            (true, _) => "ok",
            (false, true) => "OUT",
            (false, false) => "form",
        };
        let mut feature = c.feature.words(v.kind).to_string();
        if let Some(n) = &c.note {
            if c.feature == crate::CheckFeature::FlankAngle {
                feature = format!("{feature} {}", n.split_whitespace().next().unwrap_or(""));
            }
        }
        for (col, s) in cols.iter().zip([feature, value, lim, off, verdict.to_string()]) {
            g = g.add(text(*col, yy, 10.0, s).set("fill", colour));
        }
        yy += 14.0;
    }
    (g, yy)
}

/// Chip area per pass as bars with axes: pass numbers below, mm² on the left.
pub(crate) fn chip_chart(v: &Verification, x: f64, y: f64, w: f64, h: f64) -> Group {
    let mut g = Group::new().set("id", "chip-chart");
    g = g.add(text(x - 36.0, y - 8.0, 12.0, "chip area per pass").set("font-weight", "bold"));
    let max = v.metrics.iter().map(|m| m.chip_area).fold(0.0, f64::max);
    let n = v.metrics.len().max(1);
    let bw = w / n as f64;
    g = g
        .add(
            Line::new().set("x1", x).set("x2", x + w).set("y1", y + h).set("y2", y + h).set("stroke", "#333"),
        )
        .add(Line::new().set("x1", x).set("x2", x).set("y1", y).set("y2", y + h).set("stroke", "#333"));
    let step = tick_step(max, 3.0);
    // The scale's top: the tick above the tallest bar with room for its value (the tallest bar
    // once touched the frame's top and had no value).
    let top = if max > 0.0 { (max * 1.15 / step).ceil() * step } else { 1.0 };
    let mut a = 0.0;
    while a <= top * (1.0 + 1e-9) && max > 0.0 {
        let yy = y + h - h * a / top;
        g = g
            .add(
                Line::new().set("x1", x - 4.0).set("x2", x).set("y1", yy).set("y2", yy).set("stroke", "#333"),
            )
            .add(text(x - 6.0, yy + 3.0, 9.0, tick_label(a, step)).set("text-anchor", "end"));
        a += step;
    }
    g = g.add(text(x - 36.0, y + h + 28.0, 9.0, "mm² (bars) by pass number; each bar's value above it"));
    let label_every = ((n as f64 * 18.0 / w).ceil() as usize).max(1);
    // A value needs about 26 px: narrower bars show every k-th value.
    let value_every = ((n as f64 * 26.0 / w).ceil() as usize).max(1);
    for (i, m) in v.metrics.iter().enumerate() {
        let bh = if max > 0.0 { h * m.chip_area / top } else { 0.0 };
        g = g.add(
            Rectangle::new()
                .set("x", format!("{:.2}", x + i as f64 * bw + 0.1 * bw))
                .set("y", format!("{:.2}", y + h - bh))
                .set("width", format!("{:.2}", 0.8 * bw))
                .set("height", format!("{bh:.2}"))
                .set("fill", colour(i, n)),
        );
        if (i + 1) % label_every == 0 || i == 0 {
            g = g.add(
                text(x + (i as f64 + 0.5) * bw, y + h + 12.0, 9.0, (i + 1).to_string())
                    .set("text-anchor", "middle"),
            );
        }
        if (i + 1) % value_every == 0 || i == 0 {
            g = g.add(
                text(x + (i as f64 + 0.5) * bw, y + h - bh - 3.0, 8.0, format!("{:.3}", m.chip_area))
                    .set("text-anchor", "middle")
                    .set("class", "chip-value"),
            );
        }
    }
    g
}

/// The normal deviation of the as-cut profile, and of the maximum- and minimum-material
/// profiles, from the basic profile along one pitch (root, flank, crest, flank), magnified, as a
/// contour-measuring machine reports it, with the values at the flank midpoints.
pub(crate) fn deviation_plot(
    pic: &Picture,
    units: crate::analysis::turn::Units,
    x: f64,
    y: f64,
    w: f64,
    h: f64,
) -> Group {
    let f = Frame { x0: x, y0: y, w, h, z_min: 0.0, r_max: 0.0, scale: 1.0 };
    // The scale in µm, or in ten-thousandths of an inch (an inch shop's "tenths").
    let (tick_per_um, unit_label, title_unit) = match units {
        crate::analysis::turn::Units::Mm => (1.0, "µm", "µm"),
        crate::analysis::turn::Units::Inch => (1.0 / 2.54, "tenths", "in tenths (0.0001 in)"),
    };
    let title = format!("deviation from the basic profile, normal to it, {title_unit}");
    let (mut g, mut body) = panel(&f, "deviation-plot", &title);
    let dev = &pic.deviation;
    let (samples, mmc, lmc) = (&dev.as_cut, &dev.max_material, &dev.min_material);
    if samples.is_empty() {
        return g.add(body);
    }
    let s_max = samples.last().map_or(1.0, |s| s.s).max(1e-9);
    let all = samples.iter().chain(mmc).chain(lmc).map(|s| s.deviation.abs()).fold(0.0, f64::max).max(1e-4);
    let um = 1000.0;
    let span = all * um * 1.15;
    let px = |s: f64| x + 40.0 + (w - 60.0) * s / s_max;
    let py = |d: f64| y + 0.5 * h - (0.5 * h - 12.0) * (d * um) / span;
    let line = |pts: &[DeviationSample]| pixel_points(pts.iter().map(|q| (px(q.s), py(q.deviation))));
    if !mmc.is_empty() && mmc.len() == lmc.len() {
        let mut band: Vec<DeviationSample> = mmc.clone();
        band.extend(lmc.iter().rev().copied());
        body = body
            .add(
                Polygon::new()
                    .set("points", line(&band))
                    .set("fill", ZONE)
                    .set("fill-opacity", 0.3)
                    .set("stroke", "none"),
            )
            .add(Polyline::new().set("points", line(mmc)).set("fill", "none").set("stroke", ZONE))
            .add(
                Polyline::new()
                    .set("points", line(lmc))
                    .set("fill", "none")
                    .set("stroke", ZONE)
                    .set("stroke-dasharray", "4 2"),
            );
    }
    body = body
        .add(
            Line::new()
                .set("x1", px(0.0))
                .set("x2", px(s_max))
                .set("y1", py(0.0))
                .set("y2", py(0.0))
                .set("stroke", "#555")
                .set("stroke-dasharray", "6 4"),
        )
        .add(
            Polyline::new()
                .set("points", line(samples))
                .set("fill", "none")
                .set("stroke", "#111")
                .set("stroke-width", 1.6),
        );
    // The regions (root, flank, crest) and the values at the flank midpoints.
    let mut labels: Vec<(f64, String)> = Vec::new();
    let mut start = 0;
    for i in 1..=samples.len() {
        if i == samples.len() || samples[i].region != samples[start].region {
            let mid = &samples[(start + i - 1) / 2];
            let name = match samples[start].region {
                ProfileRegion::Root => "root",
                ProfileRegion::Flank => "flank",
                ProfileRegion::Crest => "crest",
            };
            let cx = px(0.5 * (samples[start].s + samples[i - 1].s));
            if samples[start].region == ProfileRegion::Flank {
                // The value at the flank's middle: a dot on the curve, the number below the panel.
                body = body.add(
                    svg::node::element::Circle::new()
                        .set("cx", format!("{:.2}", px(mid.s)))
                        .set("cy", format!("{:.2}", py(mid.deviation)))
                        .set("r", 2.5)
                        .set("fill", "#111"),
                );
                // In tenths, the µm beside them.
                let value = match units {
                    crate::analysis::turn::Units::Mm => format!("{:+.1} µm", mid.deviation * um),
                    crate::analysis::turn::Units::Inch => format!(
                        "{:+.1} {unit_label} ({:+.1} µm)",
                        mid.deviation * um * tick_per_um,
                        mid.deviation * um
                    ),
                };
                labels.push((px(mid.s), format!("flank {value}")));
            } else {
                labels.push((cx, name.to_string()));
            }
            start = i;
        }
    }
    g = g.add(body);
    // Region names and flank values below the panel, on two rows when they would touch.
    let mut last_end = [f64::NEG_INFINITY; 2];
    for (cx, l) in labels {
        let half = 0.5 * 0.6 * 9.0 * l.chars().count() as f64;
        let row = usize::from(cx - half < last_end[0] + 4.0);
        last_end[row] = cx + half;
        g = g.add(
            text(cx, y + h + 12.0 + 12.0 * row as f64, 9.0, l)
                .set("text-anchor", "middle")
                .set("fill", "#333"),
        );
    }
    // The scale on the left, outside the panel, in the reader's unit.
    let span_u = span * tick_per_um;
    let step = tick_step(span_u, 2.0);
    let mut d = -(span_u / step).floor() * step;
    while d <= span_u + 1e-9 {
        let yy = py(d / tick_per_um / um);
        g = g
            .add(
                Line::new()
                    .set("x1", x - 4.0)
                    .set("x2", x)
                    .set("y1", format!("{yy:.2}"))
                    .set("y2", format!("{yy:.2}"))
                    .set("stroke", "#333"),
            )
            .add(text(x - 6.0, yy + 3.0, 9.0, tick_label(d, step)).set("text-anchor", "end"));
        d += step;
    }
    g.add(
        text(
            x + w,
            y + h + 40.0,
            9.0,
            "along one pitch: black as cut, green the tolerance zone; + is material added",
        )
        .set("text-anchor", "end"),
    )
}

/// The SVG document of a verification.
pub fn verify_svg(v: &Verification) -> String {
    let (g, height) = verification_group(v);
    Document::new()
        .set("viewBox", (0, 0, WIDTH, height))
        .set("width", WIDTH)
        .set("height", height)
        .add(g)
        .to_string()
}

pub(crate) const WIDTH: f64 = 1100.0;

/// The amber of a warning.
const WARN: &str = "#a15c00";

/// The program's verdict in words: `IN TOLERANCE`, `OUT OF TOLERANCE`, or `WILL NOT RUN AS
/// WRITTEN` when every thread is in tolerance but the control refuses a block (or the tool
/// breaks).
fn program_verdict_words(pv: &crate::analysis::program::ProgramVerification) -> &'static str {
    match (pv.threads_pass(), pv.refused()) {
        (true, false) => "IN TOLERANCE",
        (true, true) => "WILL NOT RUN AS WRITTEN",
        (false, _) => "OUT OF TOLERANCE",
    }
}

/// The SVG of every operation of a program, one section each, stacked.
pub fn program_svg(pv: &crate::analysis::program::ProgramVerification) -> String {
    use crate::analysis::program::Milled;
    // A program that makes one kind of thread other than turned: that kind's own picture
    // (unless the control's findings need the program's heading).
    if pv.operations.is_empty() && pv.control.is_empty() {
        match (&pv.tapped, &pv.milled) {
            (Some(t), None | Some(Milled::NotChecked { .. })) => return crate::report::tap::tap_svg(t),
            (None, Some(Milled::Checked(r))) => return crate::report::thread_mill::thread_mill_svg(r),
            _ => {}
        }
    }
    // The program's verdict first, one line per operation, then each operation's section.
    let pass = pv.pass();
    let mut head = Group::new()
        .set("id", "program-verdict")
        .add(Rectangle::new().set("width", WIDTH).set("height", 1).set("fill", "white"));
    // The headline wraps (a long program name never cuts the verdict off).
    let mut y = 30.0;
    let headline =
        format!("{} — {}: {}", label_name(&pv.program), program_verdict_words(pv), program_counts(pv));
    for l in wrap(&headline, 90) {
        head = head.add(
            text(20.0, y, 20.0, l)
                .set("fill", if pass { "#1d7a36" } else { FAIL })
                .set("font-weight", "bold"),
        );
        y += 26.0;
    }
    for o in &pv.operations {
        let what = match &o.result {
            crate::analysis::turn::OperationResult::Verified(v) => {
                let mut w = verdict_words(v);
                if let Some(c) = &v.correction {
                    w.push_str(&format!(" · next: {}", super::correction_text(c)));
                }
                w
            }
            crate::analysis::turn::OperationResult::NoCut { reason, suggested_final_x } => {
                match no_cut_next(*suggested_final_x) {
                    Some(next) => format!("OUT OF TOLERANCE: {reason} · next: {next}"),
                    None => format!("OUT OF TOLERANCE: {reason}"),
                }
            }
        };
        let line = format!(
            "{}. {} at line {}, {}: {what}",
            o.operation.index, o.operation.cycle, o.operation.source_line, o.named.designation.text
        );
        for l in wrap(&line, 125) {
            head =
                head.add(text(20.0, y, 13.0, l).set("fill", if o.result.pass() { "#1d7a36" } else { FAIL }));
            y += 17.0;
        }
    }
    // The tapped holes and the milled thread after the turned operations, a line each.
    let mut more = Vec::new();
    if let Some(t) = &pv.tapped {
        let n = t.holes.len();
        let line = format!(
            "tapped: {n} tapping cycle{}: {}",
            if n == 1 { "" } else { "s" },
            if t.pass { "IN TOLERANCE" } else { "OUT OF TOLERANCE" }
        );
        let (d, w, h) = crate::report::tap::tap_document(t);
        more.push((line, t.pass, "tapped", Some((d, w, h))));
    }
    match &pv.milled {
        Some(Milled::Checked(r)) => {
            let line = format!(
                "milled: {}: {}",
                r.designation,
                if r.pass { "IN TOLERANCE" } else { "OUT OF TOLERANCE" }
            );
            let (d, w, h) = crate::report::thread_mill::thread_mill_document(r);
            more.push((line, r.pass, "milled", Some((d, w, h))));
        }
        Some(Milled::NotChecked { line, reason }) => {
            more.push((
                format!("milled: helices from line {line}: NOT CHECKED: {reason}"),
                false,
                "milled",
                None,
            ));
        }
        None => {}
    }
    for (line, pass, _, _) in &more {
        for l in wrap(line, 125) {
            head = head.add(text(20.0, y, 13.0, l).set("fill", if *pass { "#1d7a36" } else { FAIL }));
            y += 17.0;
        }
    }
    // What the control will refuse and what the post got wrong, a line each (an error in the
    // failing colour, a warning in amber), by the operation's line they name.
    if !pv.control.is_empty() {
        let mut g = Group::new().set("id", "control");
        for f in &pv.control {
            let error = f.level == crate::gcode::Level::Error;
            let line =
                format!("{} before the machine, {}", if error { "✗" } else { "!" }, control_sentence(f));
            for l in wrap(&line, 125) {
                g = g.add(text(20.0, y, 13.0, l).set("fill", if error { FAIL } else { WARN }));
                y += 17.0;
            }
        }
        head = head.add(g);
    }
    y += 12.0;
    let mut doc = Document::new()
        .add(Rectangle::new().set("width", WIDTH).set("height", y).set("fill", "white"))
        .add(head);
    for o in &pv.operations {
        let head = format!(
            "operation {} of {}: {} at line {} of {}{}",
            o.operation.index,
            pv.operations_in_program,
            o.operation.cycle,
            o.operation.source_line,
            label_name(&pv.program),
            o.operation.tool.map_or(String::new(), |t| format!(", tool T{t}"))
        );
        let (band, band_h) = band(&head, WIDTH);
        let mut g = Group::new()
            .set("id", format!("operation-{}", o.operation.index))
            .set("transform", format!("translate(0,{y})"))
            .add(band);
        // The control's findings on this operation, under its band (issue 63: each by the
        // operation it concerns; the program's head lists them all).
        let (found, found_h) = findings_group(
            pv.control.iter().filter(|f| {
                f.made == crate::analysis::made::Process::Turned
                    && f.file == o.operation.source_file
                    && turned_owner(pv, f.line) == Some(o.operation.index)
            }),
            format!("operation-{}-control", o.operation.index),
        );
        if found_h > 0.0 {
            g = g.add(found.set("transform", format!("translate(0,{band_h})")));
        }
        let band_h = band_h + found_h;
        let h = match &o.result {
            crate::analysis::turn::OperationResult::Verified(v) => {
                let (vg, height) = verification_group(v);
                g = g.add(vg.set("transform", format!("translate(0,{band_h})")));
                band_h + height
            }
            crate::analysis::turn::OperationResult::NoCut { reason, suggested_final_x } => {
                let next = no_cut_next(*suggested_final_x).map_or(String::new(), |n| format!(" · next: {n}"));
                let lines =
                    wrap(&format!("OUT OF TOLERANCE ({}): {reason}{next}", o.named.designation.text), 100);
                for (i, l) in lines.iter().enumerate() {
                    g = g.add(
                        text(20.0, band_h + 30.0 + 20.0 * i as f64, 16.0, l.clone())
                            .set("fill", FAIL)
                            .set("font-weight", "bold"),
                    );
                }
                (band_h + 76.0).max(band_h + 30.0 + 20.0 * lines.len() as f64 + 16.0)
            }
        };
        doc = doc.add(g);
        y += h;
    }
    // Each other process's own picture under a band that names it, as drawn on its own.
    let width = more.iter().filter_map(|m| m.3.as_ref()).map(|p| p.1).fold(WIDTH, f64::max);
    for (line, _, id, picture) in more {
        let Some((d, _, h)) = picture else { continue };
        let (band, band_h) = band(&line, width);
        let made = if id == "tapped" {
            crate::analysis::made::Process::Tapped
        } else {
            crate::analysis::made::Process::Milled
        };
        let (found, found_h) =
            findings_group(pv.control.iter().filter(|f| f.made == made), format!("{id}-control"));
        let mut banded = Group::new()
            .set("id", format!("{id}-band"))
            .set("transform", format!("translate(0,{y})"))
            .add(band);
        if found_h > 0.0 {
            banded = banded.add(found.set("transform", format!("translate(0,{band_h})")));
        }
        doc = doc.add(banded);
        y += band_h + found_h;
        doc = doc.add(d.set("id", id).set("x", 0).set("y", y));
        y += h;
    }
    doc.set("viewBox", (0, 0, width, y)).set("width", width).set("height", y).to_string()
}

/// The turned operation a finding at `line` concerns: the last one that starts at or before it.
fn turned_owner(pv: &crate::analysis::program::ProgramVerification, line: usize) -> Option<usize> {
    pv.operations
        .iter()
        .filter(|o| o.operation.source_line <= line)
        .max_by_key(|o| o.operation.source_line)
        .map(|o| o.operation.index)
}

/// An operation's control findings as lines under its band (an error in the failing colour, a
/// warning in amber), and their height (0 with none).
fn findings_group<'a>(
    findings: impl Iterator<Item = &'a crate::analysis::control::ControlFinding>,
    id: String,
) -> (Group, f64) {
    let mut g = Group::new().set("id", id);
    let mut y = 0.0;
    for f in findings {
        let error = f.level == crate::gcode::Level::Error;
        let line = format!("{} before the machine, {}", if error { "✗" } else { "!" }, control_sentence(f));
        for l in wrap(&line, 125) {
            y += 17.0;
            g = g.add(text(20.0, y, 13.0, l).set("fill", if error { FAIL } else { WARN }));
        }
    }
    (g, if y > 0.0 { y + 8.0 } else { 0.0 })
}

/// An operation's control findings as paragraphs of the page (an error as a failing verdict, a
/// warning in the notes' colour).
fn control_html<'a>(findings: impl Iterator<Item = &'a crate::analysis::control::ControlFinding>) -> String {
    let mut out = String::new();
    for f in findings {
        let error = f.level == crate::gcode::Level::Error;
        let _ = writeln!(
            out,
            "<p class=\"{}\">{} before the machine, {}</p>",
            if error { "out" } else { "form" },
            if error { "✗" } else { "!" },
            esc(&control_sentence(f))
        );
    }
    out
}

/// The verdict in a machinist's words.
pub(crate) fn verdict_words(v: &Verification) -> String {
    let failed: Vec<String> = v
        .checks
        .iter()
        .filter(|c| c.fails(v.gauge_only))
        .map(|c| {
            if c.feature.is_length() && c.deviation_um != 0.0 {
                let dir = if c.deviation_um > 0.0 { "over" } else { "under" };
                let by = super::Lengths(v.units).deviation(c.deviation_um, false);
                format!("{} {by} {dir}", c.feature.words(v.kind))
            } else {
                c.feature.words(v.kind).to_string()
            }
        })
        .collect();
    let gauge = if v.gauge_only { " (gauge-only: form checks are not counted)" } else { "" };
    let form = form_only_from_tip(v).map_or(String::new(), |tip| {
        format!(" (form only: the insert's {} mm tip)", crate::ground::fmt::fmt_num(tip))
    });
    // Checks a tool nobody chose decides: said beside the verdict, never failed.
    let unverified = if v.checks.iter().any(|c| c.unverified.is_some()) {
        " — form unverified: tool not known"
    } else {
        ""
    };
    if failed.is_empty() {
        format!("IN TOLERANCE{gauge}{unverified}")
    } else {
        format!("OUT OF TOLERANCE{form}: {}{gauge}{unverified}", failed.join(", "))
    }
}

/// One verification's picture: title, tooth with its dimension labels, window, check table,
/// legend, chip chart, deviation plot and full length.
pub(crate) fn verification_group(v: &Verification) -> (Group, f64) {
    let t = &v.designation.thread;
    let p = t.pitch;
    let m = &v.measurement;
    let lo = m.minor_diameter.min(m.major_diameter);
    let hi = m.major_diameter.max(m.minor_diameter).max(v.blank_diameter);
    let (r0, r1) = (rad(lo) - 0.15 * p, rad(hi) + 0.12 * p);
    let part =
        if v.kind == ThreadKind::External { "bolt (external thread)" } else { "nut (internal thread)" };
    let stock = if v.kind == ThreadKind::External { "blank" } else { "bore" };
    let mut title = Group::new().set("id", "title");
    let mut yy = 30.0;
    for l in wrap(&format!("{} — {part}, class {}", v.designation.text, v.limits.class), 80) {
        title = title.add(text(20.0, yy, 20.0, l));
        yy += 24.0;
    }
    yy += 20.0 - 24.0;
    let source = match &v.program {
        Some(p) => format!("program {}", label_name(p)),
        None => format!("infeed: {}", v.infeed),
    };
    let l = super::Lengths(v.units);
    let sub = format!(
        "insert: {} · {} · {} passes · {stock} {} · last pass {}",
        v.insert.name,
        source,
        v.passes.len(),
        l.word("Ø", v.blank_diameter),
        l.word("X", v.final_x),
    );
    for l in wrap(&sub, 150) {
        title = title.add(text(20.0, yy, 12.0, l));
        yy += 16.0;
    }
    for l in wrap(&verdict_words(v), 110) {
        title = title.add(
            text(20.0, yy + 4.0, 15.0, l)
                .set("fill", if v.pass { "#1d7a36" } else { FAIL })
                .set("font-weight", "bold"),
        );
        yy += 19.0;
    }
    // The next step: the correction in the program's words (or the plan's X), then what the
    // form failures say about the insert or the infeed.
    let mut next: Vec<String> = Vec::new();
    match (&v.correction, v.suggested_final_x) {
        (Some(c), _) => next.push(format!("next: {}", super::correction_text(c))),
        (None, Some(x)) if !v.pass => next.push(format!(
            "next: program the last pass at {} for the middle of the d2 tolerance",
            l.word("X", x)
        )),
        _ => {}
    }
    next.extend(v.hints.iter().map(|h| format!("hint: {}", super::hint_text(h))));
    for l in next.iter().flat_map(|n| wrap(n, 120)) {
        title = title.add(text(20.0, yy + 4.0, 13.0, l).set("fill", "#1d1d1d").set("id", "next"));
        yy += 17.0;
    }
    // The views start below the title, however many lines it took (at least where three
    // verdict lines end).
    let top = (yy + 24.0).max(120.0);
    let tooth = Frame::new(
        200.0,
        top,
        430.0,
        400.0,
        (m.groove_center - 0.75 * p, m.groove_center + 0.75 * p),
        (r0, r1),
    );
    let w = v.section.window;
    let window = Frame::new(690.0, top, 350.0, 220.0, (w.z_min, w.z_max), (r0 - 0.2 * p, r1 + 0.1 * p));
    let (table, table_end) = check_table(v, 690.0, top + 220.0 + 50.0);
    let legend_y = table_end + 16.0;
    let below = (top + 460.0).max(legend_y + 6.0 * 16.0 + 30.0);
    let height = below + 260.0 + 160.0 + 40.0;
    let mut doc = Group::new()
        .add(Rectangle::new().set("width", WIDTH).set("height", height).set("fill", "white"))
        .add(title)
        .add(view(v, v.picture.as_ref(), &tooth, "tooth", "one tooth"))
        .add(dimension_labels(v, &tooth, 188.0))
        .add(view(v, v.picture.as_ref(), &window, "window", "four pitches"))
        .add(table)
        .add(legend(690.0, legend_y, v.kind));
    // The deviation plot and the whole thread, run-out included, are drawn from the
    // verification's picture (computed when `VerifySpec::picture` asks for it).
    if let Some(pic) = &v.picture {
        doc = doc.add(deviation_plot(pic, v.units, 60.0, below, 570.0, 200.0));
    }
    if !v.metrics.is_empty() {
        doc = doc.add(chip_chart(v, 730.0, below + 20.0, 330.0, 150.0));
    }
    let doc = match &v.picture {
        Some(pic) => {
            let f = &pic.full_length;
            let fw = f.window;
            let frame = Frame::new(
                20.0,
                below + 260.0,
                1020.0,
                160.0,
                (fw.z_min, fw.z_max),
                (r0 - 0.3 * p, r1 + 0.2 * p),
            );
            doc.add(full_view(f, &frame, v))
        }
        None => doc,
    };
    (doc, height)
}

/// The sections of one verification: verdict, picture, checks, passes, extras, notes.
pub(crate) fn verification_body(v: &Verification, svg: &str, level: u8) -> String {
    let h = |n: u8| format!("h{}", (level + n).min(6));
    let mut s = String::new();
    let (cls, words) = if v.pass { ("ok", "IN TOLERANCE") } else { ("out", "OUT OF TOLERANCE") };
    let gauge = if v.gauge_only { " (gauge-only: form checks are not counted)" } else { "" };
    let unverified = match v.checks.iter().find_map(|c| c.unverified.as_deref()) {
        Some(why) => format!(" — form unverified: {why}"),
        None => String::new(),
    };
    let _ = writeln!(s, "<p class=\"verdict {cls}\">{words}{}{}</p>", esc(gauge), esc(&unverified));
    let stock = if v.kind == ThreadKind::External { "blank" } else { "bore" };
    let l = super::Lengths(v.units);
    let _ = writeln!(
        s,
        "<p>{} {}, class {} · insert {} · {} passes · {stock} Ø{} · last pass X{}{}</p>",
        esc(&v.designation.text),
        v.kind.name(),
        esc(&v.limits.class),
        esc(&v.insert.name),
        v.passes.len(),
        l.both(v.blank_diameter),
        l.both(v.final_x),
        v.program.as_ref().map_or(String::new(), |p| format!(" · program {}", esc(&p.to_string())))
    );
    if let Some(x) = v.suggested_final_x {
        if !v.pass {
            match &v.correction {
                Some(c) => {
                    let _ = writeln!(
                        s,
                        "<p>For the middle of the pitch-diameter tolerance: <b>{}</b> (the last pass at X{} on the diameter).</p>",
                        esc(&super::correction_text(c)),
                        l.both(x)
                    );
                }
                None => {
                    let _ = writeln!(s, "<p>For the middle of the pitch-diameter tolerance, program the last pass at <b>X{}</b>.</p>", l.both(x));
                }
            }
        }
    }
    for hint in &v.hints {
        let _ = writeln!(s, "<p class=\"form\">Hint: {}</p>", esc(&super::hint_text(hint)));
    }
    let _ = writeln!(s, "<div class=\"pic\">{svg}</div>");
    let inch = l.inch();
    let _ = writeln!(s, "<{0}>Checks</{0}>", h(0));
    s.push_str(if inch {
        "<table><tr><th>feature</th><th>value, in</th><th>min</th><th>max</th><th>value, mm</th><th>deviation</th><th>ok</th><th>note</th></tr>\n"
    } else {
        "<table><tr><th>feature</th><th>value</th><th>min</th><th>max</th><th>deviation</th><th>ok</th><th>note</th></tr>\n"
    });
    for c in &v.checks {
        let counts = c.counts(v.gauge_only);
        let cells = super::check_cells(c, l);
        let (cls, word) = match (c.ok, counts) {
            _ if c.unverified.is_some() => ("form", "unverified"),
            (true, _) => ("ok", "ok"),
            (false, true) => ("out", "OUT"),
            (false, false) => ("form", "out (not counted)"),
        };
        // In inch, each length's mm beside it.
        let in_cell = match (inch, c.feature.unit()) {
            (true, crate::CheckUnit::Mm) => format!("<td class=\"n\">{:.4}</td>", c.value),
            (true, _) => "<td></td>".to_string(),
            (false, _) => String::new(),
        };
        s.push_str(&check_row(c, v.kind, &cells, &in_cell, cls, word));
    }
    s.push_str("</table>\n");
    let _ = writeln!(s, "<{0}>Passes</{0}>", h(0));
    s.push_str("<table><tr><th>pass</th><th>start</th><th>X mm</th><th>Z start mm</th><th>Z end mm</th><th>radial depth mm</th><th>chip area mm²</th><th>line</th></tr>\n");
    let surface = 0.5 * v.blank_diameter;
    for (i, p) in v.passes.iter().enumerate() {
        let _ = writeln!(
            s,
            "<tr><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{:.4}</td><td class=\"n\">{:.4}</td><td class=\"n\">{:.4}</td><td class=\"n\">{:.4}</td><td class=\"n\">{}</td><td class=\"n\">{}</td></tr>",
            p.index,
            p.start + 1,
            p.x_end,
            p.z_start,
            p.z_end,
            (0.5 * p.x_end - surface).abs(),
            v.metrics.get(i).map_or("—".to_string(), |m| format!("{:.4}", m.chip_area)),
            p.source_line.map_or("—".to_string(), |l| l.to_string())
        );
    }
    s.push_str("</table>\n");
    let m = &v.measurement;
    let _ = writeln!(s, "<{0}>Measured</{0}>", h(0));
    s.push_str("<table>\n");
    let mut row = |k: &str, val: String| {
        let _ = writeln!(s, "<tr><th>{}</th><td class=\"n\">{}</td></tr>", esc(k), esc(&val));
    };
    row("major diameter, mm", format!("{:.4}", m.major_diameter));
    row("pitch diameter, mm", format!("{:.4}", m.pitch_diameter));
    row("minor diameter, mm", format!("{:.4}", m.minor_diameter));
    row(
        "flank half-angles, low-z / high-z, °",
        format!("{:.3} / {:.3}", m.flank_angles[0], m.flank_angles[1]),
    );
    row("root radius, mm", opt(m.root_radius, 4));
    row("thread depth, mm", format!("{:.4}", m.thread_depth));
    row("crest width, mm", format!("{:.4}", m.crest_width));
    match m.three_wire {
        Some(w) => row("three wires: wire Ø / M over wires, mm", format!("{:.4} / {:.4}", w.wire, w.m)),
        None => row("three wires", "—".into()),
    }
    row("GO gauge clearance (maximum material), mm", opt(m.max_material_clearance, 4));
    row("helix angle at the pitch diameter, °", format!("{:.3}", v.helix_angle));
    s.push_str("</table>\n");
    if !v.notes.is_empty() {
        let _ = writeln!(s, "<{0}>Notes and assumptions</{0}>\n<ul class=\"notes\">", h(0));
        for n in &v.notes {
            let _ = writeln!(s, "<li>{}</li>", esc(&n.marked().to_string()));
        }
        s.push_str("</ul>\n");
    }
    s
}

/// The HTML report of one verification.
pub fn verify_html(v: &Verification) -> String {
    let title = format!("threadcheck: {} {}", v.designation.text, v.kind.name());
    let body = format!(
        "<h1>{}</h1>\n{}",
        esc(&title),
        verification_body(v, &crate::report::verify::verify_svg(v), 2)
    );
    page(&title, &body)
}

/// The HTML report of a program: one section per operation.
pub fn program_html(pv: &ProgramVerification) -> String {
    let title = format!("threadcheck: {}", pv.program);
    let mut body = format!("<h1>{}</h1>\n", esc(&title));
    let cls = if pv.pass() { "ok" } else { "out" };
    let words = program_verdict_words(pv);
    let _ = writeln!(body, "<p class=\"verdict {cls}\">{words}: {}</p>", esc(&program_counts(pv)));
    // Every finding under the headline, as the picture gives them; each again under its
    // operation's heading below, where the page has one.
    if !pv.control.is_empty() {
        body.push_str("<h2>Before the machine</h2>\n");
        body.push_str(&control_html(pv.control.iter()));
    }
    if !pv.notes.is_empty() {
        body.push_str("<ul class=\"notes\">\n");
        for n in &pv.notes {
            let _ = writeln!(body, "<li>{}</li>", esc(&n.marked().to_string()));
        }
        body.push_str("</ul>\n");
    }
    for o in &pv.operations {
        let op = &o.operation;
        let _ = writeln!(
            body,
            "<h2>Operation {} of {}: {} at line {}{} — {}</h2>",
            op.index,
            pv.operations_in_program,
            esc(&op.cycle),
            op.source_line,
            op.tool.map_or(String::new(), |t| format!(", tool T{t}")),
            esc(&o.named.designation.text)
        );
        body.push_str(&control_html(pv.control.iter().filter(|f| {
            f.made == crate::analysis::made::Process::Turned
                && f.file == op.source_file
                && turned_owner(pv, f.line) == Some(op.index)
        })));
        for n in &op.notes {
            let _ = writeln!(body, "<p class=\"form\">{}</p>", esc(&n.marked().to_string()));
        }
        match &o.result {
            OperationResult::Verified(v) => {
                body.push_str(&verification_body(v, &crate::report::verify::verify_svg(v), 3))
            }
            OperationResult::NoCut { reason, suggested_final_x } => {
                let _ = writeln!(body, "<p class=\"verdict out\">OUT OF TOLERANCE: {}</p>", esc(reason));
                if let Some(next) = no_cut_next(*suggested_final_x) {
                    let _ = writeln!(body, "<p class=\"next\">next: {}</p>", esc(&next));
                }
            }
        }
    }
    // The tapped holes and the milled thread, each with its picture.
    if let Some(t) = &pv.tapped {
        let _ = writeln!(
            body,
            "<h2>Tapped: {} tapping cycle{} — {}</h2>",
            t.holes.len(),
            if t.holes.len() == 1 { "" } else { "s" },
            if t.pass { "IN TOLERANCE" } else { "OUT OF TOLERANCE" }
        );
        body.push_str(&control_html(
            pv.control.iter().filter(|f| f.made == crate::analysis::made::Process::Tapped),
        ));
        let _ = writeln!(body, "<pre class=\"wrap\">{}</pre>", esc(&crate::report::tap::holes_text(t)));
        let _ = writeln!(body, "<div class=\"pic\">{}</div>", crate::report::tap::tap_svg(t));
    }
    match &pv.milled {
        Some(crate::analysis::program::Milled::Checked(r)) => {
            let _ = writeln!(
                body,
                "<h2>Milled: {} — {}</h2>",
                esc(&r.designation),
                if r.pass { "IN TOLERANCE" } else { "OUT OF TOLERANCE" }
            );
            body.push_str(&control_html(
                pv.control.iter().filter(|f| f.made == crate::analysis::made::Process::Milled),
            ));
            let _ = writeln!(body, "<pre class=\"wrap\">{}</pre>", esc(&crate::report::thread_mill::text(r)));
            let _ =
                writeln!(body, "<div class=\"pic\">{}</div>", crate::report::thread_mill::thread_mill_svg(r));
        }
        Some(crate::analysis::program::Milled::NotChecked { line, reason }) => {
            let _ = writeln!(
                body,
                "<h2>Milled: helices from line {line}</h2>\n<p class=\"verdict out\">NOT CHECKED: {}</p>",
                esc(reason)
            );
        }
        None => {}
    }
    page(&title, &body)
}
