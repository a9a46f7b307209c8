//! The fit of a bolt and a nut for a reader: the JSON report, the text and the picture.

use crate::analysis::study::fit::{FitReport, FitVerdict};
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

/// The picture of the pair: the bolt and the nut to scale over three pitches with axes, the nut
/// at its best axial position; the tightest place magnified with the clearance dimensioned in
/// µm (red where they interfere); both parts' diameters against their limits; the verdict in
/// words.
pub fn svg(r: &FitReport) -> String {
    use super::kit::{axes, panel, text, Frame};
    use svg::node::element::{Circle, Line, Polygon, Rectangle};
    const GOOD: &str = "#1d7a36";
    const BAD: &str = "#c62828";
    let p = r.bolt.designation.thread.pitch;
    let cb = r.bolt.measurement.groove_center;
    let (z0, z1) = (cb - p, cb + 2.0 * p);
    let bolt: Vec<Point> = r.bolt.section.profile().into_iter().filter(|q| q.z >= z0 && q.z <= z1).collect();
    let nut: Vec<Point> = r
        .nut
        .section
        .profile()
        .into_iter()
        .map(|q| Point::new(q.z + r.nut_shift, q.r))
        .filter(|q| q.z >= z0 - p && q.z <= z1 + p)
        .collect();
    let lo = bolt.iter().chain(&nut).map(|q| q.r).fold(f64::INFINITY, f64::min) - 0.3 * p;
    let hi = bolt.iter().chain(&nut).map(|q| q.r).fold(f64::NEG_INFINITY, f64::max) + 0.3 * p;
    let (w, h) = (1000.0, 660.0);
    let colour = if r.fits { GOOD } else { BAD };
    let filled = |f: &Frame, pts: &[Point], base: f64| -> String {
        let mut v = f.points(pts);
        if let (Some(a), Some(b)) = (pts.first(), pts.last()) {
            v.push_str(&format!(" {:.2},{:.2} {:.2},{:.2}", f.x(b.z), f.y(base), f.x(a.z), f.y(base)));
        }
        v
    };
    let pair = |f: &Frame, base_lo: f64, base_hi: f64| {
        svg::node::element::Group::new()
            .add(
                Polygon::new()
                    .set("points", filled(f, &bolt, base_lo))
                    .set("fill", "#9aa4ad")
                    .set("fill-opacity", 0.85),
            )
            // Where they interfere the nut is drawn red: the overlap shows red on the bolt.
            .add(
                Polygon::new()
                    .set("points", filled(f, &nut, base_hi))
                    .set("fill", if r.fits { "#5b8fd6" } else { BAD })
                    .set("fill-opacity", 0.55)
                    .set("class", "nut"),
            )
    };
    let mut doc = svg::Document::new()
        .set("viewBox", (0, 0, w, h))
        .set("width", w)
        .set("height", h)
        .add(Rectangle::new().set("width", w).set("height", h).set("fill", "white"));
    // The verdict in words, then what was assembled.
    let gap = r.clearance_um;
    let verdict = if r.fits {
        format!("{} — FITS: {:.1} µm of clearance at the tightest place", r.bolt.designation.text, gap)
    } else {
        format!(
            "{} — INTERFERES: {:.1} µm of interference, the bolt does not go in",
            r.bolt.designation.text, -gap
        )
    };
    doc = doc.add(text(20.0, 32.0, 17.0, verdict).set("fill", colour).set("font-weight", "bold"));
    doc = doc
        .add(text(
            20.0,
            54.0,
            12.0,
            format!(
                "bolt {}, {} insert · nut {}, {} insert",
                r.bolt.limits.class, r.bolt.insert.name, r.nut.limits.class, r.nut.insert.name
            ),
        ))
        .add(text(
            20.0,
            70.0,
            12.0,
            format!(
                "engagement depth {:.3} mm · flank overlap {:.3} mm",
                r.engagement_depth, r.flank_overlap
            ),
        ));
    // The pair to scale.
    let main = Frame::new(40.0, 106.0, 540.0, 430.0, (z0, z1), (lo, hi));
    let (g, body) = panel(&main, "pair", "bolt (grey) and nut (blue; red where they interfere), to scale");
    let (tb, tn) = r.tightest;
    let mark = |f: &Frame| {
        Circle::new()
            .set("cx", format!("{:.2}", f.x(0.5 * (tb.z + tn.z))))
            .set("cy", format!("{:.2}", f.y(0.5 * (tb.r + tn.r))))
            .set("r", 9)
            .set("fill", "none")
            .set("stroke", colour)
            .set("stroke-width", 2)
    };
    doc =
        doc.add(g.add(body.add(pair(&main, lo, hi).set("id", "pair-to-scale")).add(mark(&main))).add(axes(
            &main,
            true,
            r.bolt.units,
        )));
    // The tightest place magnified: the gap a third of the panel, at least ±5 µm shown.
    let gap_mm = tb.distance(tn);
    let half = (1.5 * gap_mm).max(0.005);
    let (cz, cr) = (0.5 * (tb.z + tn.z), 0.5 * (tb.r + tn.r));
    let inset = Frame::new(650.0, 106.0, 320.0, 260.0, (cz - half, cz + half), (cr - half, cr + half));
    let times = inset.x(cz + 1.0) - inset.x(cz);
    let mm_per_px_main = 1.0 / (main.x(z0 + 1.0) - main.x(z0));
    let (g, body) = panel(
        &inset,
        "tightest",
        &format!("the tightest place, ×{:.0} the pair's scale", times * mm_per_px_main),
    );
    let dim = Line::new()
        .set("id", "clearance-dimension")
        .set("x1", format!("{:.2}", inset.x(tb.z)))
        .set("y1", format!("{:.2}", inset.y(tb.r)))
        .set("x2", format!("{:.2}", inset.x(tn.z)))
        .set("y2", format!("{:.2}", inset.y(tn.r)))
        .set("stroke", colour)
        .set("stroke-width", 2);
    let dots = [tb, tn].map(|q| {
        Circle::new()
            .set("cx", format!("{:.2}", inset.x(q.z)))
            .set("cy", format!("{:.2}", inset.y(q.r)))
            .set("r", 3)
            .set("fill", colour)
    });
    let [d0, d1] = dots;
    doc = doc.add(g.add(body.add(pair(&inset, cr - 2.0 * half, cr + 2.0 * half)).add(dim).add(d0).add(d1)));
    doc = doc.add(
        text(
            650.0,
            388.0,
            14.0,
            if r.fits { format!("clearance {gap:.1} µm") } else { format!("interference {:.1} µm", -gap) },
        )
        .set("fill", colour)
        .set("font-weight", "bold"),
    );
    doc = doc.add(text(
        650.0,
        406.0,
        11.0,
        if r.fits {
            "the shortest gap between the two profiles"
        } else {
            "the deepest overlap of the two profiles"
        },
    ));
    // Both parts' diameters against their limits.
    let mut y = 436.0;
    for (who, v) in [("bolt", &r.bolt), ("nut", &r.nut)] {
        doc = doc.add(text(650.0, y, 12.0, format!("{who} ({})", v.limits.class)).set("font-weight", "bold"));
        y += 17.0;
        for c in v.checks.iter().filter(|c| {
            matches!(
                c.feature,
                crate::CheckFeature::MajorDiameter
                    | crate::CheckFeature::PitchDiameter
                    | crate::CheckFeature::MinorDiameter
            )
        }) {
            let lim = match (c.min, c.max) {
                (Some(a), Some(b)) => format!("{a:.3} – {b:.3}"),
                (Some(a), None) => format!("≥ {a:.3}"),
                (None, Some(b)) => format!("≤ {b:.3}"),
                (None, None) => String::new(),
            };
            doc = doc.add(
                text(
                    662.0,
                    y,
                    11.0,
                    format!(
                        "{} {:.4} mm  [{lim}] {}",
                        c.feature.words(v.kind),
                        c.value,
                        if c.ok { "ok" } else { "OUT" }
                    ),
                )
                .set("fill", if c.ok { "#1d1d1d" } else { BAD }),
            );
            y += 15.0;
        }
        y += 8.0;
    }
    doc = doc.add(text(
        40.0,
        h - 60.0,
        11.0,
        "the nut stands at the axial position where it fits best; the circle marks the tightest place, magnified on the right",
    ));
    doc.to_string()
}
