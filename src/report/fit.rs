//! The fit of a bolt and a nut for a reader: the JSON report, the text and the picture.

use crate::analysis::fit::{FitReport, FitVerdict};
use crate::ground::plane::Point;
/// `fit --json` (docs/json.md).
#[derive(Clone, Debug, serde::Serialize)]
pub struct FitJson<'a> {
    /// The fit designation.
    pub thread: &'a str,
    /// Fits or interferes.
    pub verdict: FitVerdict,
    /// Signed flank clearance at the best axial position, µm (negative: interference).
    pub clearance_um: f64,
    /// (bolt major − nut minor)/2, mm.
    pub engagement_depth: f64,
    /// Flank overlap, mm.
    pub flank_overlap: f64,
    /// The bolt's verify report.
    pub bolt: super::VerifyReport<'a>,
    /// The nut's verify report.
    pub nut: super::VerifyReport<'a>,
}

impl<'a> FitJson<'a> {
    /// The report of a fit.
    pub fn of(r: &'a FitReport) -> Self {
        FitJson {
            thread: &r.bolt.designation.text,
            verdict: if r.fits { FitVerdict::Fits } else { FitVerdict::Interferes },
            clearance_um: r.clearance_um,
            engagement_depth: r.engagement_depth,
            flank_overlap: r.flank_overlap,
            bolt: super::VerifyReport::of(&r.bolt),
            nut: super::VerifyReport::of(&r.nut),
        }
    }
}

/// The text report.
pub fn text(r: &FitReport) -> String {
    let b = &r.bolt.measurement;
    let n = &r.nut.measurement;
    format!(
        "{} fit: bolt {} ({} insert, d2 {:.4}), nut {} ({} insert, D2 {:.4})\n\n  flank clearance at the best axial position  {:+.1} µm\n  engagement depth (bolt d − nut D1)/2      {:.4} mm\n  flank overlap                             {:.4} mm\n\nverdict: {}\n",
        r.bolt.designation.text,
        r.bolt.limits.class,
        r.bolt.insert.name,
        b.pitch_diameter,
        r.nut.limits.class,
        r.nut.insert.name,
        n.pitch_diameter,
        r.clearance_um,
        r.engagement_depth,
        r.flank_overlap,
        if r.fits { "FITS (the bolt screws into the nut)" } else { "INTERFERES (the bolt does not go into the nut)" }
    )
}

/// An SVG of the pair over three pitches: the bolt's material below its profile, the nut's
/// above, to scale, with the clearance in the title.
pub fn svg(r: &FitReport) -> String {
    use svg::node::element::{Polygon, Rectangle, Text};
    let p = r.bolt.designation.thread.pitch;
    let cb = r.bolt.measurement.groove_center;
    let shift = cb + 0.5 * p - r.nut.measurement.groove_center;
    let (z0, z1) = (cb - p, cb + 2.0 * p);
    let bolt: Vec<Point> = r.bolt.section.profile().into_iter().filter(|q| q.z >= z0 && q.z <= z1).collect();
    let nut: Vec<Point> = r
        .nut
        .section
        .profile()
        .into_iter()
        .map(|q| Point::new(q.z + shift, q.r))
        .filter(|q| q.z >= z0 && q.z <= z1)
        .collect();
    let lo = bolt.iter().chain(&nut).map(|q| q.r).fold(f64::INFINITY, f64::min) - 0.3 * p;
    let hi = bolt.iter().chain(&nut).map(|q| q.r).fold(f64::NEG_INFINITY, f64::max) + 0.3 * p;
    let (w, h) = (900.0, 560.0);
    let sx = (w - 80.0) / (z1 - z0);
    let sy = (h - 120.0) / (hi - lo);
    let s = sx.min(sy);
    let x = |z: f64| 40.0 + (z - z0) * s;
    let y = |r: f64| h - 40.0 - (r - lo) * s;
    let poly = |pts: &[Point], base: f64| -> String {
        let mut v: Vec<String> = pts.iter().map(|q| format!("{:.2},{:.2}", x(q.z), y(q.r))).collect();
        if let (Some(a), Some(b)) = (pts.first(), pts.last()) {
            v.push(format!("{:.2},{:.2}", x(b.z), y(base)));
            v.push(format!("{:.2},{:.2}", x(a.z), y(base)));
        }
        v.join(" ")
    };
    let title = format!(
        "{} — {} — flank clearance {:+.1} µm, engagement {:.3} mm",
        r.bolt.designation.text,
        if r.fits { "FITS" } else { "INTERFERES" },
        r.clearance_um,
        r.engagement_depth
    );
    svg::Document::new()
        .set("viewBox", (0, 0, w, h))
        .set("width", w)
        .set("height", h)
        .add(Rectangle::new().set("width", w).set("height", h).set("fill", "white"))
        .add(
            Polygon::new()
                .set("points", poly(&bolt, lo))
                .set("fill", "#9aa4ad")
                .set("fill-opacity", 0.8)
                .set("id", "bolt"),
        )
        .add(
            Polygon::new()
                .set("points", poly(&nut, hi))
                .set("fill", "#5b8fd6")
                .set("fill-opacity", 0.6)
                .set("id", "nut"),
        )
        .add(
            Text::new(title)
                .set("x", 20)
                .set("y", 28)
                .set("font-family", "sans-serif")
                .set("font-size", 16)
                .set("fill", if r.fits { "#1d7a36" } else { "#b3261e" }),
        )
        .add(
            Text::new(
                "bolt (grey) and nut (blue) in the axial section, to scale, nut at its best axial position",
            )
            .set("x", 20)
            .set("y", 50)
            .set("font-family", "sans-serif")
            .set("font-size", 12),
        )
        .to_string()
}
