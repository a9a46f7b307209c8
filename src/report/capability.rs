//! The `capability` report: JSON (docs/json.md), the text, the pitch diameter's histogram
//! against its limits (SVG) and a small HTML page with it.

use crate::analysis::check::CheckFeature;
use crate::analysis::study::capability::{CapabilityReport, Histogram, SizeCapability};
use crate::report::kit::{esc, page};
use crate::report::{correction_text, CorrectionReport};
use serde::Serialize;
use std::fmt::Write as _;

/// `capability --json`.
#[derive(Clone, Debug, Serialize)]
pub struct CapabilityJson<'a> {
    /// As written.
    pub designation: &'a str,
    /// `external` or `internal`.
    pub kind: &'static str,
    /// The program, when one was read.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub program: Option<&'a crate::analysis::turn::ProgramLabel>,
    /// The last pass's tip diameter as programmed (or planned), mm.
    pub final_x: f64,
    /// X repeatability, one σ on the diameter, mm.
    pub x_sigma: f64,
    /// Tip radius tolerance, ± mm.
    pub tip_radius_tol: f64,
    /// Radial wear per part, mm.
    pub wear_per_part: f64,
    /// Samples.
    pub samples: usize,
    /// Seed.
    pub seed: u64,
    /// Each checked size.
    pub sizes: &'a [SizeCapability],
    /// Share of sampled parts passing every check, 0…1.
    pub pass_share: f64,
    /// Parts per edge at the program's X (`null` without wear).
    pub parts_per_edge: Option<usize>,
    /// The final X with the most parts per edge (or centring d2), mm.
    pub best_final_x: f64,
    /// Parts per edge there.
    pub best_parts_per_edge: Option<usize>,
    /// The change to it in the program's words.
    pub best_correction: Option<CorrectionReport<'a>>,
    /// The Monte Carlo's standard uncertainty of d2's Cpk.
    pub cpk_uncertainty: Option<f64>,
    /// d2's histogram.
    pub histogram: &'a Histogram,
    /// The model and the verification's notes.
    pub notes: Vec<&'a crate::ground::note::Note>,
}

impl<'a> CapabilityJson<'a> {
    /// The report of a capability run.
    pub fn of(r: &'a CapabilityReport) -> Self {
        let v = &r.verification;
        CapabilityJson {
            designation: &v.designation.text,
            kind: v.kind.name(),
            program: v.program.as_ref(),
            final_x: v.final_x,
            x_sigma: r.x_sigma,
            tip_radius_tol: r.tip_radius_tol,
            wear_per_part: r.wear_per_part,
            samples: r.samples,
            seed: r.seed,
            sizes: &r.sizes,
            pass_share: r.pass_share,
            parts_per_edge: r.parts_per_edge,
            best_final_x: r.best_final_x,
            best_parts_per_edge: r.best_parts_per_edge,
            best_correction: r
                .best_correction
                .as_ref()
                .map(|c| CorrectionReport { correction: c, text: correction_text(c) }),
            cpk_uncertainty: r.cpk_uncertainty,
            histogram: &r.histogram,
            notes: r.notes.iter().chain(&v.notes).collect(),
        }
    }
}

fn num(v: Option<f64>, prec: usize) -> String {
    v.map_or("—".into(), |v| format!("{v:.prec$}"))
}

/// The text report.
pub fn capability_text(r: &CapabilityReport) -> String {
    let v = &r.verification;
    let k = v.kind;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{} {}: {} parts, last pass X{:.4}{}",
        v.designation.text,
        k.name(),
        r.samples,
        v.final_x,
        v.program.as_ref().map(|p| format!(" ({p})")).unwrap_or_default()
    );
    let _ = writeln!(
        s,
        "variation: X σ {} mm (diameter), tip radius ± {} mm, wear {} mm per part\n",
        crate::report::fmt_num(r.x_sigma),
        crate::report::fmt_num(r.tip_radius_tol),
        crate::report::fmt_num(r.wear_per_part)
    );
    let _ = writeln!(
        s,
        "    {:<24}{:>10}{:>10}{:>10}{:>9}{:>8}{:>8}{:>11}",
        "size", "min", "max", "mean", "σ µm", "Cp", "Cpk", "ppm out"
    );
    for z in &r.sizes {
        let name = match &z.note {
            Some(n) => format!("{} ({n})", z.feature.words(k)),
            None => z.feature.words(k).to_string(),
        };
        let _ = writeln!(
            s,
            "    {:<24}{:>10}{:>10}{:>10.4}{:>9.2}{:>8}{:>8}{:>11.0}",
            name,
            num(z.min, 4),
            num(z.max, 4),
            z.mean,
            z.sigma * 1e3,
            num(z.cp, 2),
            num(z.cpk, 2),
            z.ppm_counted
        );
    }
    let _ = writeln!(s, "\n{:.2} % of the parts pass every check", 100.0 * r.pass_share);
    if let Some(u) = r.cpk_uncertainty {
        let _ =
            writeln!(s, "pitch diameter's Cpk known to ± {u:.3} (the Monte Carlo's standard uncertainty)");
    }
    match (r.parts_per_edge, r.best_parts_per_edge) {
        (Some(n), Some(b)) => {
            let _ = writeln!(
                s,
                "parts per edge: {n} at the program's X; {b} with the last pass at X{:.4}",
                r.best_final_x
            );
        }
        _ => {
            let _ = writeln!(s, "the pitch diameter is centred with the last pass at X{:.4}", r.best_final_x);
        }
    }
    if let Some(c) = &r.best_correction {
        let _ = writeln!(s, "  in the program: {}", correction_text(c));
    }
    for n in r.notes.iter().chain(&v.notes) {
        let _ = writeln!(s, "note: {}", n.marked());
    }
    s
}

/// The pitch diameter's histogram against its limits.
pub fn capability_svg(r: &CapabilityReport) -> String {
    use svg::node::element::{Line, Rectangle, Text};
    let v = &r.verification;
    let h = &r.histogram;
    let d2 = r.sizes.iter().find(|s| s.feature == CheckFeature::PitchDiameter);
    let (w, ht) = (900.0, 460.0);
    let (left, right, top, bottom) = (70.0, 30.0, 80.0, 70.0);
    let lo = h.lo;
    let hi = h.lo + h.width * h.counts.len() as f64;
    let x = |d: f64| left + (d - lo) / (hi - lo).max(1e-12) * (w - left - right);
    let peak = h.counts.iter().copied().max().unwrap_or(1).max(1) as f64;
    let y = |c: f64| ht - bottom - c / peak * (ht - top - bottom);
    let font = |t: Text| t.set("font-family", "sans-serif");
    let mut doc = svg::Document::new()
        .set("viewBox", (0, 0, w, ht))
        .set("width", w)
        .set("height", ht)
        .add(Rectangle::new().set("width", w).set("height", ht).set("fill", "white"));
    let title = format!(
        "{} — pitch diameter of {} parts: Cpk {} — {:.2} % pass",
        v.designation.text,
        r.samples,
        num(d2.and_then(|d| d.cpk), 2),
        100.0 * r.pass_share
    );
    doc = doc.add(font(Text::new(title)).set("x", 20).set("y", 30).set("font-size", 18));
    doc = doc.add(
        font(Text::new(format!(
            "X σ {} mm, tip radius ± {} mm, wear {} mm per part; limits in red",
            crate::report::fmt_num(r.x_sigma),
            crate::report::fmt_num(r.tip_radius_tol),
            crate::report::fmt_num(r.wear_per_part)
        )))
        .set("x", 20)
        .set("y", 54)
        .set("font-size", 13),
    );
    for (i, &c) in h.counts.iter().enumerate() {
        let (a, b) = (h.lo + i as f64 * h.width, h.lo + (i + 1) as f64 * h.width);
        doc = doc.add(
            Rectangle::new()
                .set("x", format!("{:.2}", x(a)))
                .set("y", format!("{:.2}", y(c as f64)))
                .set("width", format!("{:.2}", (x(b) - x(a) - 1.0).max(0.5)))
                .set("height", format!("{:.2}", ht - bottom - y(c as f64)))
                .set("fill", "#5b8fd6"),
        );
    }
    // The axis with five ticks, mm.
    doc = doc.add(
        Line::new()
            .set("x1", left)
            .set("x2", w - right)
            .set("y1", ht - bottom)
            .set("y2", ht - bottom)
            .set("stroke", "#333"),
    );
    for i in 0..=4 {
        let d = lo + (hi - lo) * i as f64 / 4.0;
        doc = doc.add(
            font(Text::new(format!("{d:.4}")))
                .set("x", format!("{:.2}", x(d)))
                .set("y", ht - bottom + 18.0)
                .set("font-size", 12)
                .set("text-anchor", "middle"),
        );
    }
    doc = doc.add(
        font(Text::new("pitch diameter, mm"))
            .set("x", w / 2.0)
            .set("y", ht - 20.0)
            .set("font-size", 13)
            .set("text-anchor", "middle"),
    );
    let lim = v.limits.pitch_diameter;
    for (val, label, anchor) in [(lim.min, "min", "start"), (lim.max, "max", "end")] {
        if let Some(val) = val {
            doc = doc
                .add(
                    Line::new()
                        .set("x1", format!("{:.2}", x(val)))
                        .set("x2", format!("{:.2}", x(val)))
                        .set("y1", top - 10.0)
                        .set("y2", ht - bottom)
                        .set("stroke", "#c62828")
                        .set("stroke-width", 2),
                )
                .add(
                    font(Text::new(format!("{label} {val:.4}")))
                        .set("x", format!("{:.2}", x(val) + if anchor == "start" { 4.0 } else { -4.0 }))
                        .set("y", top - 14.0)
                        .set("font-size", 12)
                        .set("fill", "#c62828")
                        .set("text-anchor", anchor),
                );
        }
    }
    doc.to_string()
}

/// The HTML page: the histogram and the table.
pub fn capability_html(r: &CapabilityReport) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "<h1>threadcheck capability: {}</h1>", esc(&r.verification.designation.text));
    let _ = writeln!(s, "<div class=\"pic\">{}</div>", capability_svg(r));
    let _ = writeln!(s, "<pre>{}</pre>", esc(&capability_text(r)));
    page(&format!("threadcheck capability {}", r.verification.designation.text), &s)
}
