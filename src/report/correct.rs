//! The `correct` report: JSON (docs/json.md), the text a machinist reads at the machine, and a
//! small HTML page.

use crate::analysis::check::Verdict;
use crate::analysis::study::correct::{CorrectReport, MeasuredState, Pickup, WearOffset};
use crate::report::kit::{esc, page};
use crate::report::{correction_text, CorrectionReport};
use crate::standards::tolerance::Limit;
use serde::Serialize;
use std::fmt::Write as _;

/// The thread as the program or plan cuts it.
#[derive(Clone, Debug, Serialize)]
pub struct ComputedReport {
    /// The last pass's tip diameter, mm.
    pub final_x: f64,
    /// Whether the final X was solved for mid-tolerance (a plan without `--final-x`).
    pub final_x_solved: bool,
    /// The pitch diameter it cuts, mm.
    pub pitch_diameter: f64,
}

/// `correct --json`.
#[derive(Clone, Debug, Serialize)]
pub struct CorrectJson<'a> {
    /// As written.
    pub designation: &'a str,
    /// `external` or `internal`.
    pub kind: &'static str,
    /// The program, when one was read.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub program: Option<&'a crate::analysis::turn::ProgramLabel>,
    /// `pass` when the part is in tolerance (or for a pick-up alone), else `fail`.
    pub verdict: Verdict,
    /// The pitch diameter's limits, mm (before coating, with `--coating`).
    pub pitch_diameter_limits: Limit,
    /// The middle of them, mm: what a correction aims at.
    pub target_pitch_diameter: Option<f64>,
    /// The thread as computed.
    pub computed: ComputedReport,
    /// The part as measured.
    pub measured: Option<&'a MeasuredState>,
    /// The change of the pitch diameter to make, mm.
    pub delta_pitch_diameter: Option<f64>,
    /// The plan's last tip diameter that makes it, mm.
    pub suggested_final_x: Option<f64>,
    /// The same in the program's words.
    pub correction: Option<CorrectionReport<'a>>,
    /// Or as a change of the tool's X wear offset.
    pub wear_offset: Option<&'a WearOffset>,
    /// Where to re-enter an existing thread.
    pub pickup: Option<&'a Pickup>,
    /// The verification's notes, then correct's own.
    pub notes: Vec<&'a crate::ground::note::Note>,
}

impl<'a> CorrectJson<'a> {
    /// The report of a correction.
    pub fn of(r: &'a CorrectReport) -> Self {
        let v = &r.verification;
        CorrectJson {
            designation: &v.designation.text,
            kind: v.kind.name(),
            program: v.program.as_ref(),
            verdict: r.verdict(),
            pitch_diameter_limits: v.limits.pitch_diameter,
            target_pitch_diameter: v.limits.pitch_diameter.mid(),
            computed: ComputedReport {
                final_x: v.final_x,
                final_x_solved: v.final_x_solved,
                pitch_diameter: v.measurement.pitch_diameter,
            },
            measured: r.measured.as_ref(),
            delta_pitch_diameter: r.delta_pitch_diameter,
            suggested_final_x: r.suggested_final_x,
            correction: r
                .correction
                .as_ref()
                .map(|c| CorrectionReport { correction: c, text: correction_text(c) }),
            wear_offset: r.wear_offset.as_ref(),
            pickup: r.pickup.as_ref(),
            notes: v.notes.iter().chain(&r.notes).collect(),
        }
    }
}

/// The lines of the report, shared by the text and the page.
fn lines(r: &CorrectReport) -> (String, Vec<String>) {
    let v = &r.verification;
    let mut out = Vec::new();
    let lim = v.limits.pitch_diameter;
    out.push(format!(
        "{} {}: pitch diameter {}–{} mm{}",
        v.designation.text,
        v.kind.name(),
        crate::report::opt(lim.min, 3),
        crate::report::opt(lim.max, 3),
        match &v.program {
            Some(p) => format!(
                ", as {p} cuts it: d2 {:.4} mm (last pass X{:.4})",
                v.measurement.pitch_diameter, v.final_x
            ),
            None => format!(
                ", the plan's last pass X{:.4} cuts d2 {:.4} mm",
                v.final_x, v.measurement.pitch_diameter
            ),
        }
    ));
    if let Some(m) = &r.measured {
        if let Some(w) = &m.over_wires {
            out.push(format!(
                "measured over {:.4} mm wires: M {:.4} mm{}; the computed thread gives M {:.4} mm over them",
                w.wire,
                w.m,
                if w.helix_term != 0.0 {
                    format!(" (helix term {:+.4})", w.helix_term)
                } else {
                    String::new()
                },
                w.m_computed
            ));
            if let Some(f) = w.pitch_diameter_formula {
                out.push(format!("  (the perfect-profile formula would say d2 {f:.4} mm)"));
            }
        }
        match (m.pitch_diameter, m.gauge) {
            (Some(d2), _) => out.push(format!(
                "the part's pitch diameter: {d2:.4} mm, {:+.1} µm from the middle{}",
                m.off_middle_um.unwrap_or(0.0),
                match m.deviation_um {
                    Some(d) if d != 0.0 => format!(", {d:+.1} µm outside the limits"),
                    _ => ", within the limits".into(),
                }
            )),
            (None, Some(g)) => out.push(format!(
                "gauge: {}",
                match g {
                    crate::analysis::study::correct::GaugeResult::GoFails => "GO fails",
                    crate::analysis::study::correct::GaugeResult::NogoEnters => "NO-GO enters",
                    crate::analysis::study::correct::GaugeResult::Ok => "GO enters, NO-GO does not",
                }
            )),
            (None, None) => {}
        }
        if let Some(u) = &m.unknown {
            out.push(format!("still unknown: {u}"));
        }
    }
    if let Some(d) = r.delta_pitch_diameter {
        out.push(format!("change: pitch diameter {:+.1} µm, to the middle of the tolerance", d * 1e3));
        match (&r.correction, r.suggested_final_x) {
            (Some(c), _) => out.push(format!("correction: {}", correction_text(c))),
            (None, Some(x)) => out.push(format!("correction: last pass X{x:.4} (was X{:.4})", v.final_x)),
            _ => {}
        }
        if let Some(w) = &r.wear_offset {
            let (n, unit) = match w.units {
                crate::gcode::ProgramUnits::Mm => (format!("{:+.3}", w.x), "mm"),
                crate::gcode::ProgramUnits::Inch => (format!("{:+.4}", w.x), "in"),
            };
            out.push(format!(
                "or without editing the program: add {n} {unit} to the tool's X wear offset (diameter)"
            ));
        }
    }
    if let Some(p) = &r.pickup {
        out.push(format!(
            "pick-up: the groove measured at Z{:.4}, the program's at Z{:.4}: the program would cut {:+.4} mm beside it",
            p.measured_z, p.program_z, p.phase_error
        ));
        out.push(format!(
            "  shift the threading start by Z{:+.4} mm, or change the cycle's start angle by {:+.3}° (Fanuc/Haas Q, Sinumerik SF; cutting towards {}Z)",
            p.z_shift,
            p.start_angle_deg,
            if p.towards_minus_z { "−" } else { "+" }
        ));
    }
    let verdict = match (r.verdict(), &r.measured) {
        (_, None) => "verdict: pick-up only".to_string(),
        (Verdict::Pass, _) => "verdict: IN TOLERANCE (no correction needed)".to_string(),
        (Verdict::Fail, _) => "verdict: CORRECT the program".to_string(),
    };
    (verdict, out)
}

/// The text report.
pub fn correct_text(r: &CorrectReport) -> String {
    let (verdict, body) = lines(r);
    let mut s = String::new();
    for l in body {
        let _ = writeln!(s, "{l}");
    }
    let _ = writeln!(s, "\n{verdict}");
    for n in r.verification.notes.iter().chain(&r.notes) {
        let _ = writeln!(s, "note: {}", n.marked());
    }
    s
}

/// The HTML page: the same lines, the verdict first.
pub fn correct_html(r: &CorrectReport) -> String {
    let (verdict, body) = lines(r);
    let cls = if r.verdict() == Verdict::Pass { "ok" } else { "out" };
    let mut s = String::new();
    let _ = writeln!(s, "<h1>threadcheck correct: {}</h1>", esc(&r.verification.designation.text));
    let _ = writeln!(s, "<p class=\"verdict {cls}\">{}</p>\n<ul>", esc(&verdict));
    for l in body {
        let _ = writeln!(s, "<li>{}</li>", esc(&l));
    }
    let _ = writeln!(s, "</ul>\n<h2>Notes</h2>\n<ul class=\"notes\">");
    for n in r.verification.notes.iter().chain(&r.notes) {
        let _ = writeln!(s, "<li>{}</li>", esc(&n.marked().to_string()));
    }
    s.push_str("</ul>\n");
    page(&format!("threadcheck correct {}", r.verification.designation.text), &s)
}
