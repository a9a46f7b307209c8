//! SVG cross-sections of a verification: self-contained, readable in any browser.
//!
//! Layers are `<g id="…">` groups: `title`, `blank`, `tolerance-zone`, `basic-profile`,
//! `passes`, `as-cut`, `dimensions`, `legend`, `chip-chart`, each view (`tooth`, `window`) holding
//! its own copies. Text from user input (designations, insert names) is escaped by the `svg`
//! crate.

use crate::analysis::picture::Picture;
use crate::analysis::verify::Verification;
use crate::geometry::insert::Insert;
use crate::geometry::measure::{DeviationSample, ProfileRegion};
use crate::ground::plane::{rad, Point};
use crate::standards::ThreadKind;
use svg::node::element::{Group, Line, Polygon, Polyline, Rectangle, Text};
use svg::Document;

/// Maps the axial plane (mm) into a panel (px), radius up.
#[derive(Clone, Copy)]
pub(super) struct Frame {
    x0: f64,
    y0: f64,
    w: f64,
    h: f64,
    z_min: f64,
    r_max: f64,
    scale: f64,
}

impl Frame {
    pub(super) fn new(x0: f64, y0: f64, w: f64, h: f64, z: (f64, f64), r: (f64, f64)) -> Frame {
        let scale = (w / (z.1 - z.0)).min(h / (r.1 - r.0));
        // Centre the drawing in the panel.
        let z_min = 0.5 * (z.0 + z.1) - 0.5 * w / scale;
        let r_max = 0.5 * (r.0 + r.1) + 0.5 * h / scale;
        Frame { x0, y0, w, h, z_min, r_max, scale }
    }

    pub(super) fn x(&self, z: f64) -> f64 {
        self.x0 + (z - self.z_min) * self.scale
    }

    pub(super) fn y(&self, r: f64) -> f64 {
        self.y0 + (self.r_max - r) * self.scale
    }

    pub(super) fn points(&self, pts: &[Point]) -> String {
        pixel_points(pts.iter().map(|p| (self.x(p.z), self.y(p.r))))
    }

    fn z_range(&self) -> (f64, f64) {
        (self.z_min, self.z_min + self.w / self.scale)
    }
}

/// A polyline's points in pixels for an SVG `points` attribute, to 0.01 px, leaving out each
/// point that lies within 0.02 px of the straight line from the last one kept to the next (a
/// zone's flat stretches, a straight flank sampled every pixel): the same picture in far fewer
/// bytes.
fn pixel_points(pts: impl Iterator<Item = (f64, f64)>) -> String {
    let v: Vec<(f64, f64)> = pts.collect();
    // On the segment a–b (between its ends) within 0.02 px.
    let near = |p: (f64, f64), a: (f64, f64), b: (f64, f64)| {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let l2 = dx * dx + dy * dy;
        let along = (p.0 - a.0) * dx + (p.1 - a.1) * dy;
        l2 > 0.0
            && ((p.0 - a.0) * dy - (p.1 - a.1) * dx).abs() <= 0.02 * l2.sqrt()
            && (0.0..=l2).contains(&along)
    };
    let mut kept: Vec<(f64, f64)> = Vec::with_capacity(v.len());
    let mut last = 0usize;
    for (i, &p) in v.iter().enumerate() {
        // Left out while every point since the last kept one lies on the line to the next.
        if let (false, Some(&b)) = (kept.is_empty(), v.get(i + 1)) {
            let a = v[last];
            if (last + 1..=i).all(|j| near(v[j], a, b)) {
                continue;
            }
        }
        kept.push(p);
        last = i;
    }
    kept.iter().map(|(x, y)| format!("{x:.2},{y:.2}")).collect::<Vec<_>>().join(" ")
}

pub(super) fn text(x: f64, y: f64, size: f64, s: impl Into<String>) -> Text {
    Text::new(s.into())
        .set("x", format!("{x:.1}"))
        .set("y", format!("{y:.1}"))
        .set("font-size", size)
        .set("font-family", "sans-serif")
}

/// A panel: its group (with the clip path, white background, frame and the caption above it)
/// and the group to draw in, clipped to the panel. The frame carries `class="panel"`: nothing
/// written in the picture lies inside one (the layout test checks it).
pub(super) fn panel(f: &Frame, id: &str, label: &str) -> (Group, Group) {
    let clip_id = format!("clip-{id}");
    let frame = Rectangle::new().set("x", f.x0).set("y", f.y0).set("width", f.w).set("height", f.h);
    let g = Group::new()
        .set("id", id)
        .add(
            svg::node::element::Definitions::new()
                .add(svg::node::element::ClipPath::new().set("id", clip_id.clone()).add(frame.clone())),
        )
        .add(frame.set("fill", "white").set("stroke", "#999").set("class", "panel"))
        .add(text(f.x0, f.y0 - 5.0, 12.0, label).set("font-weight", "bold"));
    (g, Group::new().set("clip-path", format!("url(#{clip_id})")))
}

/// A tick step of 1, 2 or 5 × 10ⁿ giving about `n` ticks over `span`.
fn tick_step(span: f64, n: f64) -> f64 {
    let raw = (span / n).max(1e-9);
    let e = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0].into_iter().map(|k| k * e).find(|s| *s >= raw).unwrap_or(10.0 * e)
}

/// A tick label without float noise.
fn tick_label(v: f64, step: f64) -> String {
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    let s = format!("{v:.decimals$}");
    if s.starts_with('-') && s.trim_start_matches(['-', '0', '.']).is_empty() {
        s[1..].to_string()
    } else {
        s
    }
}

/// Axes of a panel: Z (mm) ticks below it, diameter (mm, twice the radius) ticks on its right.
pub(super) fn axes(f: &Frame, diameter_axis: bool, units: crate::analysis::verify::Units) -> Group {
    // Ticks at round numbers of the reader's unit: mm, or inches (the frame stays in mm).
    let (per, name) = match units {
        crate::analysis::verify::Units::Mm => (1.0, "mm"),
        crate::analysis::verify::Units::Inch => (25.4, "in"),
    };
    let mut g = Group::new().set("class", "axes");
    let (z0, z1) = f.z_range();
    let (u0, u1) = (z0 / per, z1 / per);
    let step = tick_step(u1 - u0, 6.0);
    let mut u = (u0 / step).ceil() * step;
    while u <= u1 + 1e-9 * step.max(1.0) {
        let x = f.x(u * per);
        g = g
            .add(
                Line::new()
                    .set("x1", x)
                    .set("x2", x)
                    .set("y1", f.y0 + f.h)
                    .set("y2", f.y0 + f.h + 4.0)
                    .set("stroke", "#333"),
            )
            .add(text(x, f.y0 + f.h + 14.0, 9.0, tick_label(u, step)).set("text-anchor", "middle"));
        u += step;
    }
    g = g.add(text(f.x0 + f.w, f.y0 + f.h + 26.0, 9.0, format!("Z {name}")).set("text-anchor", "end"));
    if diameter_axis {
        let r_lo = f.r_max - f.h / f.scale;
        let (d0, d1) = (2.0 * r_lo / per, 2.0 * f.r_max / per);
        let step = tick_step(d1 - d0, 5.0);
        let mut d = (d0 / step).ceil() * step;
        while d <= d1 + 1e-9 * step.max(1.0) {
            let y = f.y(0.5 * d * per);
            g = g
                .add(
                    Line::new()
                        .set("x1", f.x0 + f.w)
                        .set("x2", f.x0 + f.w + 4.0)
                        .set("y1", y)
                        .set("y2", y)
                        .set("stroke", "#333"),
                )
                .add(text(f.x0 + f.w + 6.0, y + 3.0, 9.0, tick_label(d, step)));
            d += step;
        }
        g = g.add(text(f.x0 + f.w + 6.0, f.y0 - 5.0, 9.0, format!("Ø {name}")));
    }
    g
}

/// The blank before threading across the panel: between the surface and the far side.
fn blank_polygon(f: &Frame, kind: ThreadKind, surface_r: f64, far_r: f64) -> Polygon {
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

fn colour(i: usize, n: usize) -> String {
    let h = if n <= 1 { 220.0 } else { 220.0 - 220.0 * i as f64 / (n - 1) as f64 };
    format!("hsl({h:.0},75%,45%)")
}

const ZONE: &str = "#2e9e4f";
const FAIL: &str = "#c62828";

fn view(v: &Verification, pic: Option<&Picture>, f: &Frame, id: &str, label: &str) -> Group {
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

/// Dimension lines of the measured diameters across a panel, red when out of their limits;
/// each `{id}-dim-{feature}`.
fn dimension_lines(
    items: &[(crate::CheckFeature, f64)],
    checks: &[crate::Check],
    f: &Frame,
    id: &str,
) -> Group {
    let mut dims = Group::new().set("id", format!("{id}-dimensions"));
    for &(feature, d) in items {
        let y = f.y(rad(d));
        if y < f.y0 || y > f.y0 + f.h {
            continue;
        }
        let ok = checks.iter().find(|c| c.feature == feature).is_none_or(|c| c.ok);
        dims = dims.add(
            Line::new()
                .set("id", format!("{id}-dim-{}", feature.name()))
                .set("x1", f.x0)
                .set("x2", f.x0 + f.w)
                .set("y1", format!("{y:.2}"))
                .set("y2", format!("{y:.2}"))
                .set("stroke", if ok { "#1f5fbf" } else { FAIL })
                .set("stroke-width", if ok { 0.8 } else { 1.4 })
                .set("stroke-dasharray", "2 3"),
        );
    }
    dims
}

/// The tolerance zone between its maximum- and minimum-material sides, translucent over the
/// material and the air (`{id}-tolerance-zone`): the maximum-material side solid, the other
/// dashed.
fn zone_group(sides: Option<(Vec<Point>, Vec<Point>)>, f: &Frame, id: &str) -> Group {
    let mut zone = Group::new().set("id", format!("{id}-tolerance-zone"));
    if let Some((mmc, mut lmc)) = sides {
        let mut poly = mmc.clone();
        let lmc_line = lmc.clone();
        lmc.reverse();
        poly.extend(lmc);
        zone = zone
            .add(
                Polygon::new()
                    .set("points", f.points(&poly))
                    .set("fill", ZONE)
                    .set("fill-opacity", 0.35)
                    .set("stroke", "none"),
            )
            .add(
                Polyline::new()
                    .set("points", f.points(&mmc))
                    .set("fill", "none")
                    .set("stroke", ZONE)
                    .set("stroke-width", 1.0),
            )
            .add(
                Polyline::new()
                    .set("points", f.points(&lmc_line))
                    .set("fill", "none")
                    .set("stroke", ZONE)
                    .set("stroke-width", 1.0)
                    .set("stroke-dasharray", "4 2"),
            );
    }
    zone
}

/// The diameters dimensioned in the picture: major, pitch and minor, as measured.
fn dimension_features(v: &Verification) -> [(crate::CheckFeature, f64); 3] {
    let m = &v.measurement;
    [
        (crate::CheckFeature::MajorDiameter, m.major_diameter),
        (crate::CheckFeature::PitchDiameter, m.pitch_diameter),
        (crate::CheckFeature::MinorDiameter, m.minor_diameter),
    ]
}

/// A limit as the tables give it: three decimals at their 1 µm, four for the inch forms'
/// limits converted to mm.
fn fmt_limit(v: f64) -> String {
    if ((v * 1e3).round() - v * 1e3).abs() < 1e-6 {
        format!("{v:.3}")
    } else {
        format!("{v:.4}")
    }
}

/// A pair of limits (`8.862 – 8.994`, `≥ 0.187`), `unit` at the end.
fn fmt_limits(min: Option<f64>, max: Option<f64>, unit: &str) -> String {
    match (min, max) {
        (Some(a), Some(b)) => format!("{} – {}{unit}", fmt_limit(a), fmt_limit(b)),
        (Some(a), None) => format!("≥ {}{unit}", fmt_limit(a)),
        (None, Some(b)) => format!("≤ {}{unit}", fmt_limit(b)),
        (None, None) => String::new(),
    }
}

/// The dimension labels of the tooth panel, in the column left of it (`right` is the column's
/// right edge): value, limits and unit, each joined to its line by a leader, spread so that
/// no two overlap, red when out of limits.
fn dimension_labels(v: &Verification, f: &Frame, right: f64) -> Group {
    labels_of_dimensions(&dimension_features(v), &v.checks, v.kind, v.units, f, right)
}

/// The dimension labels of `items` (measured diameters) beside panel `f`, as
/// [`dimension_labels`] places them.
fn labels_of_dimensions(
    items_in: &[(crate::CheckFeature, f64)],
    checks: &[crate::Check],
    kind: ThreadKind,
    units: crate::analysis::verify::Units,
    f: &Frame,
    right: f64,
) -> Group {
    let mut g = Group::new().set("id", "dimension-labels");
    let mut items: Vec<(f64, String, String, bool)> = Vec::new();
    for &(feature, d) in items_in {
        let y = f.y(rad(d));
        if y < f.y0 || y > f.y0 + f.h {
            continue;
        }
        let check = checks.iter().find(|c| c.feature == feature);
        let ok = check.is_none_or(|c| c.ok);
        let name = feature.words(kind).rsplit(' ').next().unwrap_or("");
        let line1 = if units == crate::analysis::verify::Units::Inch {
            format!("{name} {d:.4} mm ({:.5} in)", d / 25.4)
        } else {
            format!("{name} {d:.4} mm")
        };
        let line2 = check.map_or(String::new(), |c| {
            let lim = match (c.min, c.max) {
                (None, None) => String::new(),
                (min, max) => format!("[{}]", fmt_limits(min, max, "")),
            };
            if c.ok {
                lim
            } else {
                format!("{lim} {:+.1} µm", c.deviation_um)
            }
        });
        items.push((y, line1, line2, ok));
    }
    items.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Spread: each label needs 28 px; push down, then pull back up from the panel's bottom.
    let mut ys: Vec<f64> = items.iter().map(|i| i.0).collect();
    for i in 1..ys.len() {
        ys[i] = ys[i].max(ys[i - 1] + 28.0);
    }
    let bottom = f.y0 + f.h - 14.0;
    for i in (0..ys.len()).rev() {
        let limit = if i + 1 < ys.len() { ys[i + 1] - 28.0 } else { bottom };
        ys[i] = ys[i].min(limit).max(f.y0 + 12.0);
    }
    for ((y, l1, l2, ok), ly) in items.into_iter().zip(ys) {
        let c = if ok { "#1f5fbf" } else { FAIL };
        g = g
            .add(
                Line::new()
                    .set("x1", right + 2.0)
                    .set("y1", format!("{ly:.2}"))
                    .set("x2", f.x0)
                    .set("y2", format!("{y:.2}"))
                    .set("stroke", c)
                    .set("stroke-width", 0.7),
            )
            .add(
                text(right, ly - 2.0, 11.0, l1)
                    .set("text-anchor", "end")
                    .set("fill", c)
                    .set("font-weight", if ok { "normal" } else { "bold" }),
            )
            .add(text(right, ly + 11.0, 10.0, l2).set("text-anchor", "end").set("fill", c));
    }
    g
}

/// The whole thread along its length: blank, material as cut and the cut surface.
fn full_view(section: &crate::geometry::sweep::Section, f: &Frame, v: &Verification) -> Group {
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

fn legend(x: f64, y: f64, kind: ThreadKind) -> Group {
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
fn check_table(v: &Verification, x: f64, y: f64) -> (Group, f64) {
    let mut g = Group::new().set("id", "check-table");
    g = g.add(text(x, y, 12.0, "checks").set("font-weight", "bold"));
    let cols = [x, x + 145.0, x + 195.0, x + 305.0, x + 365.0];
    let head = ["feature", "value", "limits", "off", ""];
    for (c, h) in cols.iter().zip(head) {
        g = g.add(text(*c, y + 16.0, 10.0, h).set("fill", "#555"));
    }
    let mut yy = y + 32.0;
    for c in &v.checks {
        let counts = c.kind.counts(v.gauge_only);
        let colour = if c.ok {
            "#1d1d1d"
        } else if counts {
            FAIL
        } else {
            "#8a6d00"
        };
        // Values, limits and deviations in the check's own unit (the text table's cells).
        let cells = super::check_cells(c);
        // Lengths carry their unit in the column's head; degrees stick to the number.
        let unit = match cells.unit {
            "mm" | "" => String::new(),
            "°" => "°".to_string(),
            u => format!(" {u}"),
        };
        let value = format!("{}{}", cells.value, if unit == "°" { "°" } else { "" });
        let lim = match c.feature.unit() {
            crate::CheckUnit::YesNo => String::new(),
            _ => fmt_limits(c.min, c.max, &unit),
        };
        let off = cells.deviation;
        let verdict = match (c.ok, counts) {
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
fn chip_chart(v: &Verification, x: f64, y: f64, w: f64, h: f64) -> Group {
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
fn deviation_plot(
    pic: &Picture,
    units: crate::analysis::verify::Units,
    x: f64,
    y: f64,
    w: f64,
    h: f64,
) -> Group {
    let f = Frame { x0: x, y0: y, w, h, z_min: 0.0, r_max: 0.0, scale: 1.0 };
    // The scale in µm, or in ten-thousandths of an inch (an inch shop's "tenths").
    let (tick_per_um, unit_label) = match units {
        crate::analysis::verify::Units::Mm => (1.0, "µm"),
        crate::analysis::verify::Units::Inch => (1.0 / 2.54, "0.0001 in"),
    };
    let title = format!("deviation from the basic profile, normal to it, {unit_label}");
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
                labels.push((
                    px(mid.s),
                    format!("flank {:+.1} {unit_label}", mid.deviation * um * tick_per_um),
                ));
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

const WIDTH: f64 = 1100.0;

/// The SVG of every operation of a program, one section each, stacked.
pub fn program_svg(pv: &crate::analysis::verify::ProgramVerification) -> String {
    // The program's verdict first, one line per operation, then each operation's section.
    let pass = pv.pass();
    let mut head = Group::new()
        .set("id", "program-verdict")
        .add(Rectangle::new().set("width", WIDTH).set("height", 1).set("fill", "white"))
        .add(
            text(
                20.0,
                30.0,
                20.0,
                shorten(
                    &format!(
                        "{} — {}: {} threading operation{}",
                        label_name(&pv.program),
                        if pass { "IN TOLERANCE" } else { "OUT OF TOLERANCE" },
                        pv.operations.len(),
                        if pv.operations.len() == 1 { "" } else { "s" }
                    ),
                    90,
                ),
            )
            .set("fill", if pass { "#1d7a36" } else { FAIL })
            .set("font-weight", "bold"),
        );
    let mut y = 56.0;
    for o in &pv.operations {
        let what = match &o.result {
            crate::analysis::verify::OperationResult::Verified(v) => {
                let mut w = verdict_words(v);
                if let Some(c) = &v.correction {
                    w.push_str(&format!(" · next: {}", super::correction_text(c)));
                }
                w
            }
            crate::analysis::verify::OperationResult::NoCut { reason, suggested_final_x } => {
                match super::no_cut_next(*suggested_final_x) {
                    Some(next) => format!("OUT OF TOLERANCE: {reason} · next: {next}"),
                    None => format!("OUT OF TOLERANCE: {reason}"),
                }
            }
        };
        let line = format!(
            "{}. {} at line {}, {}: {what}",
            o.operation.index, o.operation.cycle, o.operation.source_line, o.designation
        );
        for l in wrap(&line, 125).into_iter().take(2) {
            head =
                head.add(text(20.0, y, 13.0, l).set("fill", if o.result.pass() { "#1d7a36" } else { FAIL }));
            y += 17.0;
        }
    }
    y += 12.0;
    let mut doc = Document::new()
        .add(Rectangle::new().set("width", WIDTH).set("height", y).set("fill", "white"))
        .add(head);
    for o in &pv.operations {
        let head = shorten(
            &format!(
                "operation {} of {}: {} at line {} of {}{}",
                o.operation.index,
                pv.operations_in_program,
                o.operation.cycle,
                o.operation.source_line,
                label_name(&pv.program),
                o.operation.tool.map_or(String::new(), |t| format!(", tool T{t}"))
            ),
            120,
        );
        let mut g = Group::new()
            .set("id", format!("operation-{}", o.operation.index))
            .set("transform", format!("translate(0,{y})"))
            .add(Rectangle::new().set("width", WIDTH).set("height", 34).set("fill", "#eef1f5"))
            .add(text(20.0, 23.0, 15.0, head).set("font-weight", "bold"));
        let h = match &o.result {
            crate::analysis::verify::OperationResult::Verified(v) => {
                let (vg, height) = verification_group(v);
                g = g.add(vg.set("transform", "translate(0,34)"));
                34.0 + height
            }
            crate::analysis::verify::OperationResult::NoCut { reason, suggested_final_x } => {
                let next =
                    super::no_cut_next(*suggested_final_x).map_or(String::new(), |n| format!(" · next: {n}"));
                for (i, l) in wrap(&format!("OUT OF TOLERANCE ({}): {reason}{next}", o.designation), 100)
                    .iter()
                    .enumerate()
                {
                    g = g.add(
                        text(20.0, 64.0 + 20.0 * i as f64, 16.0, l.clone())
                            .set("fill", FAIL)
                            .set("font-weight", "bold"),
                    );
                }
                110.0
            }
        };
        doc = doc.add(g);
        y += h;
    }
    doc.set("viewBox", (0, 0, WIDTH, y)).set("width", WIDTH).set("height", y).to_string()
}

/// The file name of a program label, with its dialect (`dir/p.nc (fanuc)` → `p.nc (fanuc)`).
fn label_name(label: &crate::analysis::verify::ProgramLabel) -> String {
    format!("{} ({})", file_name(&label.file), label.dialect.name())
}

/// `s` cut to `n` characters with an ellipsis.
fn shorten(s: &str, n: usize) -> String {
    if s.chars().count() <= n {
        s.to_string()
    } else {
        s.chars().take(n - 1).collect::<String>() + "…"
    }
}

/// `s` in lines of at most `n` characters, broken at spaces (the text reports wrap their prose
/// with it too).
pub(crate) fn wrap(s: &str, n: usize) -> Vec<String> {
    let mut lines = vec![String::new()];
    for word in s.split(' ') {
        let last = lines.last_mut().map_or(0, |l| l.chars().count());
        if last > 0 && last + 1 + word.chars().count() > n {
            lines.push(String::new());
        }
        if let Some(l) = lines.last_mut() {
            if !l.is_empty() {
                l.push(' ');
            }
            l.push_str(&shorten(word, n));
        }
    }
    lines
}

/// The verdict in a machinist's words.
fn verdict_words(v: &Verification) -> String {
    let failed: Vec<String> = v
        .checks
        .iter()
        .filter(|c| !c.ok && c.kind.counts(v.gauge_only))
        .map(|c| {
            if c.feature.is_length() && c.deviation_um != 0.0 {
                let dir = if c.deviation_um > 0.0 { "over" } else { "under" };
                format!("{} {:.1} µm {dir}", c.feature.words(v.kind), c.deviation_um.abs())
            } else {
                c.feature.words(v.kind).to_string()
            }
        })
        .collect();
    let gauge = if v.gauge_only { " (gauge-only: form checks are not counted)" } else { "" };
    let form = super::form_only_from_tip(v).map_or(String::new(), |tip| {
        format!(" (form only: the insert's {} mm tip)", crate::ground::fmt::fmt_num(tip))
    });
    if failed.is_empty() {
        format!("IN TOLERANCE{gauge}")
    } else {
        format!("OUT OF TOLERANCE{form}: {}{gauge}", failed.join(", "))
    }
}

/// One verification's picture: title, tooth with its dimension labels, window, check table,
/// legend, chip chart, deviation plot and full length.
fn verification_group(v: &Verification) -> (Group, f64) {
    let t = &v.designation.thread;
    let p = t.pitch;
    let m = &v.measurement;
    let lo = m.minor_diameter.min(m.major_diameter);
    let hi = m.major_diameter.max(m.minor_diameter).max(v.blank_diameter);
    let (r0, r1) = (rad(lo) - 0.15 * p, rad(hi) + 0.12 * p);
    let part =
        if v.kind == ThreadKind::External { "bolt (external thread)" } else { "nut (internal thread)" };
    let stock = if v.kind == ThreadKind::External { "blank" } else { "bore" };
    let mut title = Group::new().set("id", "title").add(text(
        20.0,
        30.0,
        20.0,
        shorten(&format!("{} — {part}, class {}", v.designation.text, v.limits.class), 80),
    ));
    let source = match &v.program {
        Some(p) => format!("program {}", label_name(p)),
        None => format!("infeed: {}", v.infeed),
    };
    let inch = |mm: f64| match v.units {
        crate::analysis::verify::Units::Mm => String::new(),
        crate::analysis::verify::Units::Inch => format!(" ({:.5} in)", mm / 25.4),
    };
    let sub = format!(
        "insert: {} · {} · {} passes · {stock} Ø{:.3}{} · last pass X{:.4}{}",
        v.insert.name,
        source,
        v.passes.len(),
        v.blank_diameter,
        inch(v.blank_diameter),
        v.final_x,
        inch(v.final_x)
    );
    let mut yy = 50.0;
    for l in wrap(&sub, 150).into_iter().take(2) {
        title = title.add(text(20.0, yy, 12.0, l));
        yy += 16.0;
    }
    for l in wrap(&verdict_words(v), 110).into_iter().take(3) {
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
            "next: program the last pass at X{x:.4}{} for the middle of the d2 tolerance",
            inch(x)
        )),
        _ => {}
    }
    next.extend(v.hints.iter().map(|h| format!("hint: {}", super::hint_text(h))));
    for l in next.iter().flat_map(|n| wrap(n, 120)).take(4) {
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

/// The SVG of a milling check: the worst level's target, the area the cutter swept, the tool
/// centre path, and the deviation along the target, magnified.
pub fn mill_svg(r: &crate::analysis::mill::MillReport) -> String {
    let (w, h) = (900.0, 760.0);
    let mut doc = Document::new().set("viewBox", (0, 0, w, h)).set("width", w).set("height", h);
    doc = doc.add(Rectangle::new().set("width", w).set("height", h).set("fill", "white"));
    let Some(pic) = &r.picture else {
        return doc.add(text(20.0, 40.0, 16.0, "no level cut the part")).to_string();
    };
    let (mut x0, mut x1, mut y0, mut y1) =
        (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for p in pic.target.iter() {
        x0 = x0.min(p.z);
        x1 = x1.max(p.z);
        y0 = y0.min(p.r);
        y1 = y1.max(p.r);
    }
    let name = file_name(&r.program);
    let pad = 0.5 * r.tool_diameter + 0.08 * (x1 - x0).max(y1 - y0);
    let f = Frame::new(40.0, 90.0, w - 80.0, h - 150.0, (x0 - pad, x1 + pad), (y0 - pad, y1 + pad));
    let mut g = Group::new().set("id", "level");
    for (ext, holes) in &pic.swept {
        let mut d = String::new();
        for ring in std::iter::once(ext).chain(holes.iter()) {
            d.push_str(&format!("M{}Z", f.points(ring).replace(' ', " L")));
        }
        g = g.add(
            svg::node::element::Path::new()
                .set("d", d)
                .set("fill", "#9ecae1")
                .set("fill-opacity", 0.6)
                .set("fill-rule", "evenodd")
                .set("stroke", "none"),
        );
    }
    g = g.add(
        Polyline::new()
            .set("points", f.points(&pic.target))
            .set("fill", "none")
            .set("stroke", "black")
            .set("stroke-width", 1.2),
    );
    for (a, b) in &pic.path {
        g = g.add(
            Line::new()
                .set("x1", format!("{:.2}", f.x(a.z)))
                .set("y1", format!("{:.2}", f.y(a.r)))
                .set("x2", format!("{:.2}", f.x(b.z)))
                .set("y2", format!("{:.2}", f.y(b.r)))
                .set("stroke", "#08519c")
                .set("stroke-width", 0.5),
        );
    }
    // The deviation, magnified along the outward normal of the target.
    let n = pic.target.len();
    let worst = pic.deviation.iter().fold(0.0f64, |m, d| m.max(d.abs().min(0.5 * r.tool_diameter)));
    let size = (x1 - x0).max(y1 - y0);
    let mag = if worst > 0.0 { (0.08 * size / worst).clamp(1.0, 1e5) } else { 1.0 };
    let ccw = crate::geometry::boolean::signed_area(&pic.target[..n.saturating_sub(1)]) > 0.0;
    let sign = if ccw { 1.0 } else { -1.0 };
    let outward = |i: usize| {
        let (a, b) = (pic.target[i.saturating_sub(1)], pic.target[(i + 1).min(n - 1)]);
        let (tz, tr) = (b.z - a.z, b.r - a.r);
        let l = tz.hypot(tr).max(1e-12);
        (sign * tr / l, -sign * tz / l)
    };
    let dev: Vec<Point> = (0..n)
        .map(|i| {
            let d = pic.deviation[i].clamp(-0.5 * r.tool_diameter, 0.5 * r.tool_diameter) * mag;
            let (nx, ny) = outward(i);
            Point::new(pic.target[i].z + nx * d, pic.target[i].r + ny * d)
        })
        .collect();
    g = g.add(
        Polyline::new()
            .set("points", f.points(&dev))
            .set("fill", "none")
            .set("stroke", "#d62728")
            .set("stroke-width", 1.0),
    );
    if let Some(s) = pic.gouge_at {
        let (cx, cy) = (f.x(s.x), f.y(s.y));
        g = g.add(
            svg::node::element::Circle::new()
                .set("cx", format!("{cx:.2}"))
                .set("cy", format!("{cy:.2}"))
                .set("r", 0.5 * r.tool_diameter * f.scale)
                .set("fill", "none")
                .set("stroke", "#d62728")
                .set("stroke-width", 1.5),
        );
        // The label beside the circle, on the side away from the part's middle.
        let rr = 0.5 * r.tool_diameter * f.scale;
        let left = s.x < 0.5 * (x0 + x1);
        let lx = if left { cx - rr - 6.0 } else { cx + rr + 6.0 };
        g = g.add(
            text(lx, cy - rr - 4.0, 13.0, format!("worst gouge {:.4} mm", r.gouge_max))
                .set("fill", "#d62728")
                .set("text-anchor", if left { "end" } else { "start" }),
        );
    }
    doc = doc.add(g);
    let verdict = match r.verdict {
        crate::analysis::check::Verdict::Pass => "PASS",
        crate::analysis::check::Verdict::Fail => "FAIL",
    };
    doc = doc.add(text(
        20.0,
        30.0,
        18.0,
        format!("{name}: level Z{} — {verdict}", crate::ground::fmt::fmt_num(pic.z)),
    ));
    doc = doc.add(text(
        20.0,
        54.0,
        13.0,
        format!(
            "Ø{} mm cutter; gouge {:.4} mm, leftover {:.4} mm, tolerance {} mm; red: deviation from the target × {}",
            crate::ground::fmt::fmt_num(r.tool_diameter),
            r.gouge_max,
            r.leftover_max,
            crate::ground::fmt::fmt_num(r.tolerance),
            crate::ground::fmt::fmt_num((mag * 10.0).round() / 10.0)
        ),
    ));
    doc = doc.add(text(20.0, 74.0, 12.0, "black: target; blue: area the cutter swept and its centre path; red inside the black line: gouge, outside: material left"));
    // A 10 mm scale bar.
    let bar = 10.0 * f.scale;
    doc = doc.add(
        Line::new()
            .set("x1", 40)
            .set("y1", h - 30.0)
            .set("x2", 40.0 + bar)
            .set("y2", h - 30.0)
            .set("stroke", "black")
            .set("stroke-width", 2),
    );
    doc = doc.add(text(40.0, h - 12.0, 12.0, "10 mm"));
    doc.to_string()
}

/// `threadcheck thread-mill --svg`: the milled thread's axial section over four pitches, true
/// to scale with Z (mm) and diameter ticks: the material (grey-blue) the cutter's envelope
/// leaves, the class's tolerance zone over it (green), the basic profile (grey dashed), the
/// tooth profile alone (brown dashed), D1's limits (blue dotted), and the measured D, D2 and D1
/// dimensioned with their values and limits (red with the deviation when out); below it, the
/// helix's widening of the groove (radial µm) against the same Z.
pub fn threadmill_svg(r: &crate::analysis::threadmill::ThreadMillReport) -> String {
    use crate::ground::fmt::fmt_num;
    let w = 900.0;
    let internal = r.kind == ThreadKind::Internal;
    let (z0, z1) = (r.profile.first().map_or(0.0, |p| p.z), r.profile.last().map_or(1.0, |p| p.z));
    let rs = r.profile.iter().chain(&r.tooth_points).map(|p| p.r);
    let (lo, hi) = rs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
    let pad = 0.2 * (hi - lo).max(1e-3);
    // The section: true to scale, as wide as the column allows, as tall as its radii need.
    let (px0, pw) = (230.0, 580.0);
    let scale = pw / (z1 - z0).max(1e-6);
    let ph = ((hi - lo + 2.0 * pad) * scale).clamp(140.0, 320.0);
    let f = Frame::new(px0, 140.0, pw, ph, (z0, z1), (lo - pad, hi + pad));
    let edge = if internal { hi + 10.0 * pad } else { lo - 10.0 * pad };
    let mut material = r.profile.clone();
    material.push(Point::new(z1, edge));
    material.push(Point::new(z0, edge));
    let (mut sec, mut body) =
        panel(&f, "section", "the milled section over four pitches (axial, true to scale)");
    body = body
        .add(Group::new().set("id", "section-material").add(
            Polygon::new().set("points", f.points(&material)).set("fill", "#b8c7d9").set("stroke", "none"),
        ))
        .add(zone_group(r.zone.clone(), &f, "section"))
        .add(
            Group::new().set("id", "section-basic-profile").add(
                Polyline::new()
                    .set("points", f.points(&r.basic))
                    .set("fill", "none")
                    .set("stroke", "#555")
                    .set("stroke-dasharray", "6 4")
                    .set("stroke-width", 1.0),
            ),
        )
        .add(
            Group::new().set("id", "section-tooth-profile").add(
                Polyline::new()
                    .set("points", f.points(&r.tooth_points))
                    .set("fill", "none")
                    .set("stroke", "#a35a00")
                    .set("stroke-width", 1.0)
                    .set("stroke-dasharray", "3 3"),
            ),
        )
        .add(
            Group::new().set("id", "section-profile").add(
                Polyline::new()
                    .set("points", f.points(&r.profile))
                    .set("fill", "none")
                    .set("stroke", "#111")
                    .set("stroke-width", 1.6),
            ),
        );
    // D1's limits, the bore's: dotted blue across the section.
    let mut d1 = Group::new().set("id", "section-d1-limits");
    for v in [r.limits.minor_diameter.min, r.limits.minor_diameter.max].into_iter().flatten() {
        let y = f.y(rad(v));
        d1 = d1.add(
            Line::new()
                .set("x1", f.x0)
                .set("x2", f.x0 + f.w)
                .set("y1", format!("{y:.2}"))
                .set("y2", format!("{y:.2}"))
                .set("stroke", "#1f5fa8")
                .set("stroke-width", 0.6)
                .set("stroke-dasharray", "1 3"),
        );
    }
    let m = &r.measured;
    let items = [
        (crate::CheckFeature::MajorDiameter, m.major_diameter),
        (crate::CheckFeature::PitchDiameter, m.pitch_diameter),
        (crate::CheckFeature::MinorDiameter, m.minor_diameter),
    ];
    body = body.add(d1).add(dimension_lines(&items, &r.checks, &f, "section"));
    sec = sec.add(body).add(axes(&f, true, crate::analysis::verify::Units::Mm));
    let labels =
        labels_of_dimensions(&items, &r.checks, r.kind, crate::analysis::verify::Units::Mm, &f, px0 - 14.0);
    // The legend under the section.
    let ly = f.y0 + f.h + 46.0;
    let mut legend = Group::new().set("id", "legend");
    let mut lx = 20.0;
    for (name, colour, dash, fill) in [
        ("as milled", "#111", "", false),
        ("tooth profile alone", "#a35a00", "3 3", false),
        ("basic profile", "#555", "6 4", false),
        ("tolerance zone (D2)", ZONE, "", true),
        ("D1 limits", "#1f5fa8", "1 3", false),
    ] {
        legend = if fill {
            legend.add(
                Rectangle::new()
                    .set("x", lx)
                    .set("y", ly - 8.0)
                    .set("width", 24)
                    .set("height", 9)
                    .set("fill", colour)
                    .set("fill-opacity", 0.35),
            )
        } else {
            legend.add(
                Line::new()
                    .set("x1", lx)
                    .set("x2", lx + 24.0)
                    .set("y1", ly - 4.0)
                    .set("y2", ly - 4.0)
                    .set("stroke", colour)
                    .set("stroke-width", 1.4)
                    .set("stroke-dasharray", dash),
            )
        };
        legend = legend.add(text(lx + 30.0, ly, 11.0, name));
        lx += 30.0 + 6.6 * name.chars().count() as f64 + 22.0;
    }
    // The groove's widening along Z: the milled radius less the tooth profile's, in µm, on the
    // section's own Z scale.
    let widen: Vec<(f64, f64)> =
        r.profile.iter().zip(&r.tooth_points).map(|(a, b)| (a.z, (a.r - b.r).abs() * 1000.0)).collect();
    let peak = widen.iter().map(|p| p.1).fold(0.0f64, f64::max);
    let step = tick_step(peak.max(1e-3), 4.0);
    let top = (peak / step).ceil().max(1.0) * step;
    let (sy, sh) = (ly + 56.0, 120.0);
    let fs = Frame::new(px0, sy, pw, sh, (z0, z1), (0.0, 1e-9));
    let sy_of = |v: f64| sy + sh - v / top * sh;
    let strip = pixel_points(widen.iter().map(|&(z, v)| (f.x(z), sy_of(v))));
    let (mut wid, mut wbody) =
        panel(&fs, "widening", "the helix's widening of the groove beyond the tooth profile alone");
    wbody = wbody.add(
        Polyline::new().set("points", strip).set("fill", "none").set("stroke", FAIL).set("stroke-width", 1.2),
    );
    wid = wid.add(wbody).add(axes(&fs, false, crate::analysis::verify::Units::Mm));
    let mut v = 0.0;
    while v <= top + 1e-9 * step {
        let y = sy_of(v);
        wid = wid
            .add(
                Line::new()
                    .set("x1", px0 - 4.0)
                    .set("x2", px0)
                    .set("y1", y)
                    .set("y2", y)
                    .set("stroke", "#333"),
            )
            .add(text(px0 - 6.0, y + 3.0, 9.0, tick_label(v, step)).set("text-anchor", "end"));
        v += step;
    }
    wid = wid
        .add(text(px0 - 6.0, sy - 6.0, 9.0, "µm, radial").set("text-anchor", "end"))
        .add(text(20.0, sy + 0.5 * sh - 6.0, 11.0, "0 on crests and roots,"))
        .add(text(20.0, sy + 0.5 * sh + 8.0, 11.0, "which the tooth alone"))
        .add(text(20.0, sy + 0.5 * sh + 22.0, 11.0, "shapes; the flanks widen"));
    let h = sy + sh + 50.0;
    let failed: Vec<&str> = r.checks.iter().filter(|k| !k.ok).map(|k| k.feature.words(r.kind)).collect();
    let verdict =
        if r.pass { "IN TOLERANCE".to_string() } else { format!("OUT OF TOLERANCE: {}", failed.join(", ")) };
    let d2n = if internal { "D2" } else { "d2" };
    let mut doc = Document::new().set("viewBox", (0, 0, w, h)).set("width", w).set("height", h);
    doc = doc
        .add(Rectangle::new().set("width", w).set("height", h).set("fill", "white"))
        .add(
            text(
                20.0,
                30.0,
                17.0,
                shorten(
                    &format!(
                        "{}: {} thread-milled with a Ø{} {} cutter",
                        file_name(&r.program),
                        r.designation,
                        fmt_num(r.cutter.diameter),
                        crate::report::threadmill::cutter_kind(&r.cutter)
                    ),
                    80,
                ),
            )
            .set("font-weight", "bold"),
        )
        .add(
            text(20.0, 52.0, 15.0, shorten(&verdict, 95))
                .set("font-weight", "bold")
                .set("fill", if r.pass { ZONE } else { FAIL }),
        )
        .add(text(
            20.0,
            76.0,
            13.0,
            format!(
                "{d2n} {:.4} mm as milled, {:.4} mm by the tooth profile alone: the helix widens the groove by {:+.1} µm",
                r.measured.pitch_diameter, r.tooth_profile.pitch_diameter, r.distortion_pitch_diameter_um
            ),
        ))
        .add(text(
            20.0,
            96.0,
            13.0,
            format!(
                "flanks {:.3}° / {:.3}° ({:+.3}° / {:+.3}°); the cutter is {:.0} % of the thread's diameter",
                r.measured.flank_angles[0],
                r.measured.flank_angles[1],
                r.distortion_flank_angles_deg[0],
                r.distortion_flank_angles_deg[1],
                100.0 * r.cutter_ratio
            ),
        ))
        .add(sec)
        .add(labels)
        .add(legend)
        .add(wid);
    doc.to_string()
}

/// A program's file name without its folders: a picture's title has no room for a long path
/// (the HTML page and the text keep it whole).
fn file_name(program: &str) -> String {
    std::path::Path::new(program)
        .file_name()
        .map_or(program.to_string(), |n| n.to_string_lossy().into_owned())
}

/// Most tapped holes drawn side by side; the rest are counted under the picture.
const TAP_PANELS: usize = 4;

/// A scale bar's length, mm: a round number about `px` pixels long at `s` px/mm.
fn scale_bar_mm(s: f64, px: f64) -> f64 {
    tick_step(px / s, 1.0)
}

/// `threadcheck tap --svg`: each tapped hole's axial section, hole axis up, true to scale (a
/// scale bar under the holes): the part in grey, the hole in white (the tap's thread, its
/// chamfer, the plain bore and the drill's point), D1's limits dashed blue, the drill's diameter
/// dimensioned across the plain bore (red when out of D1), the tap's and the drill's bottoms,
/// the checks with their limits, and the drill that would pass.
pub fn tap_svg(r: &crate::analysis::tapping::TapReport) -> String {
    use crate::analysis::tapping::TapFeature;
    use crate::ground::fmt::fmt_num;
    let shown: Vec<_> = r.holes.iter().take(TAP_PANELS).collect();
    let panel_w = 300.0;
    let w = (40.0 + panel_w * shown.len().max(1) as f64).max(760.0);
    let (box_h, box_w) = (420.0, panel_w - 120.0);
    // One scale for every panel: the deepest hole's height and the widest drill fit.
    let span = |hole: &crate::analysis::tapping::TappedHole| {
        let z = hole.wall.iter().map(|p| p.z);
        let (lo, hi) = z.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
        (
            if hole.wall.is_empty() { 0.0 } else { hi - lo },
            2.0 * hole.wall.iter().map(|p| p.r).fold(0.0, f64::max),
        )
    };
    let (tall, wide) =
        shown.iter().map(|h| span(h)).fold((1e-3f64, 1e-3f64), |a, b| (a.0.max(b.0), a.1.max(b.1)));
    let s = (box_h / tall).min(box_w / (1.6 * wide));
    let y0 = 120.0;
    // Below the holes: D1, the checks with their limits, the drill that passes; the picture
    // ends under the longest of these.
    let text_top = y0 + (tall * s).max(60.0) + 30.0;
    let mut text_bottom = text_top;
    let mut holes = Vec::new();
    let verdict = if r.pass {
        "IN TOLERANCE".to_string()
    } else {
        let bad = r.holes.iter().filter(|h| !h.pass).count();
        format!("OUT OF TOLERANCE: {bad} of {} tapping cycles", r.holes.len())
    };
    for (k, hole) in shown.iter().enumerate() {
        let x0 = 20.0 + panel_w * k as f64;
        let cx = x0 + 0.5 * box_w + 10.0;
        let c = &hole.cycle;
        let mut g = Group::new().set("id", format!("hole-{k}"));
        g = g.add(
            text(
                x0,
                80.0,
                12.0,
                format!("{} line {}{}", c.code, c.line, c.tool.map_or(String::new(), |t| format!(", T{t}"))),
            )
            .set("font-weight", "bold"),
        );
        g = g.add(text(x0, 96.0, 12.0, format!("tap {}", hole.tap.designation)));
        let drill_check = hole.checks.iter().find(|k| k.feature == TapFeature::DrillDiameter);
        let drill_ok = drill_check.is_none_or(|k| k.ok);
        let d1 = &hole.tap.minor_diameter;
        if hole.wall.is_empty() {
            g = g.add(text(x0, y0 + 20.0, 12.0, "the drill's diameter or a bottom"));
            g = g.add(text(x0, y0 + 36.0, 12.0, "is not known: not drawn"));
        } else {
            let top = hole.wall.first().map_or(0.0, |p| p.z);
            let bottom = hole.wall.last().map_or(0.0, |p| p.z);
            let y = |z: f64| y0 + (top - z) * s;
            let x = |r: f64| cx + r * s;
            let half_w = 0.8 * wide * s;
            g = g.add(
                Rectangle::new()
                    .set("x", format!("{:.2}", cx - half_w))
                    .set("y", format!("{y0:.2}"))
                    .set("width", format!("{:.2}", 2.0 * half_w))
                    .set("height", format!("{:.2}", y(bottom) - y0 + 12.0))
                    .set("fill", "#b8c7d9"),
            );
            let mut pts: Vec<String> =
                hole.wall.iter().map(|p| format!("{:.2},{:.2}", x(p.r), y(p.z))).collect();
            pts.extend(hole.wall.iter().rev().map(|p| format!("{:.2},{:.2}", x(-p.r), y(p.z))));
            g = g.add(
                Polygon::new()
                    .set("id", format!("hole-{k}-wall"))
                    .set("points", pts.join(" "))
                    .set("fill", "white")
                    .set("stroke", "black")
                    .set("stroke-width", 0.8),
            );
            for (v, which) in [(d1.min, "min"), (d1.max, "max")] {
                let Some(v) = v else { continue };
                for (sign, side) in [(-1.0, "left"), (1.0, "right")] {
                    g = g.add(
                        Line::new()
                            .set("id", format!("hole-{k}-d1-{which}-{side}"))
                            .set("x1", format!("{:.3}", x(sign * 0.5 * v)))
                            .set("x2", format!("{:.3}", x(sign * 0.5 * v)))
                            .set("y1", format!("{y0:.2}"))
                            .set("y2", format!("{:.2}", y(bottom)))
                            .set("stroke", "#1f5fa8")
                            .set("stroke-width", 0.7)
                            .set("stroke-dasharray", "3 3"),
                    );
                }
            }
            let mark = |g: Group, z: f64, colour: &str, label: String| -> Group {
                g.add(
                    Line::new()
                        .set("x1", format!("{:.2}", cx - half_w))
                        .set("x2", format!("{:.2}", cx + half_w + 6.0))
                        .set("y1", format!("{:.2}", y(z)))
                        .set("y2", format!("{:.2}", y(z)))
                        .set("stroke", colour.to_string())
                        .set("stroke-width", 0.8)
                        .set("stroke-dasharray", "5 3"),
                )
                .add(text(cx + half_w + 8.0, y(z) + 4.0, 11.0, label).set("fill", colour.to_string()))
            };
            if let Some(tz) = c.bottom {
                g = mark(g, tz, "#333", format!("tap Z{}", fmt_num(tz)));
                if let Some(f) = hole.tap.full_thread_z {
                    g = mark(g, f, "#777", format!("full Z{}", fmt_num(f)));
                }
            }
            if let Some(db) = hole.drill.as_ref().and_then(|d| d.cycle.bottom) {
                g = mark(g, db, "#a35a00", format!("drill Z{}", fmt_num(db)));
            }
            // The drill's diameter across the plain bore, between the tap's bottom and the
            // drill's point, with arrowheads.
            if let (Some(dia), Some(tz), Some(db)) = (
                hole.drill.as_ref().and_then(|d| d.diameter),
                c.bottom,
                hole.drill.as_ref().and_then(|d| d.cycle.bottom),
            ) {
                let point = db + 0.5 * dia / (59f64).to_radians().tan();
                let yd = y(0.5 * (tz.min(top) + point.max(db)));
                let colour = if drill_ok { "#1f5fbf" } else { FAIL };
                let (xa, xb) = (x(-0.5 * dia), x(0.5 * dia));
                let head = |tip: f64, dir: f64| {
                    Polygon::new()
                        .set(
                            "points",
                            format!(
                                "{tip:.2},{yd:.2} {:.2},{:.2} {:.2},{:.2}",
                                tip + 7.0 * dir,
                                yd - 3.0,
                                tip + 7.0 * dir,
                                yd + 3.0
                            ),
                        )
                        .set("fill", colour)
                };
                g = g
                    .add(
                        Line::new()
                            .set("id", format!("hole-{k}-drill-dimension"))
                            .set("x1", format!("{xa:.3}"))
                            .set("x2", format!("{xb:.3}"))
                            .set("y1", format!("{yd:.2}"))
                            .set("y2", format!("{yd:.2}"))
                            .set("stroke", colour)
                            .set("stroke-width", 1.0),
                    )
                    .add(head(xa, 1.0))
                    .add(head(xb, -1.0))
                    .add(
                        text(cx, yd - 5.0, 11.0, format!("Ø{}", fmt_num(dia)))
                            .set("text-anchor", "middle")
                            .set("fill", colour)
                            .set("font-weight", "bold"),
                    );
            }
            g = g.add(
                text(cx + half_w + 8.0, y0 + 10.0, 11.0, format!("top Z{}", fmt_num(top)))
                    .set("fill", "#555"),
            );
        }
        // Under the hole: the drill against D1, the checks with their limits, a drill that passes.
        let mut ty = text_top;
        let line = |g: Group, ty: &mut f64, size: f64, colour: &str, bold: bool, s: String| -> Group {
            let t = text(x0, *ty, size, s).set("fill", colour.to_string());
            *ty += if size >= 12.0 { 15.0 } else { 19.0 };
            g.add(if bold { t.set("font-weight", "bold") } else { t })
        };
        g = line(
            g,
            &mut ty,
            11.0,
            "#1f5fa8",
            false,
            format!("D1 of {}: {}", hole.tap.designation, fmt_limits(d1.min, d1.max, " mm")),
        );
        ty += 4.0;
        for ck in &hole.checks {
            let word = crate::report::tapping::feature_name(ck.feature);
            let val = ck.value.map_or(String::new(), |v| format!(" {}", fmt_num((v * 1e4).round() / 1e4)));
            let unit = if ck.value.is_some() && !ck.unit.is_empty() {
                format!(" {}", ck.unit)
            } else {
                String::new()
            };
            let colour = if ck.ok { ZONE } else { FAIL };
            g = line(
                g,
                &mut ty,
                12.0,
                colour,
                !ck.ok,
                format!("{} {word}{val}{unit}", if ck.ok { "✓" } else { "✗" }),
            );
            let lim = if ck.min == ck.max {
                ck.min.map_or(String::new(), |v| format!("must be {}", fmt_num(v)))
            } else {
                match (ck.min, ck.max) {
                    (Some(a), Some(b)) => format!("limits {} – {}", fmt_limit(a), fmt_limit(b)),
                    (Some(a), None) => format!("at least {}", fmt_num(a)),
                    (None, Some(b)) => format!("at most {}", fmt_num(b)),
                    (None, None) => String::new(),
                }
            };
            let off = if ck.ok || ck.value.is_none() {
                String::new()
            } else if ck.unit == "mm/min" {
                format!(", {:+.1} mm/min", ck.deviation)
            } else {
                format!(", {:+.1} µm", ck.deviation)
            };
            let lim = if lim.is_empty() || ck.unit.is_empty() { lim } else { format!("{lim} {}", ck.unit) };
            if !lim.is_empty() || !off.is_empty() {
                g = line(
                    g,
                    &mut ty,
                    10.0,
                    if ck.ok { "#555" } else { FAIL },
                    false,
                    format!("    {lim}{off}"),
                );
            }
        }
        let drill_unknown = hole.drill.as_ref().is_none_or(|d| d.diameter.is_none());
        if let Some(pd) = hole.drill_that_passes.as_ref() {
            ty += 6.0;
            let head = if drill_ok && !drill_unknown { "the drill for D1" } else { "a drill that passes" };
            let (what, why) = match (&pd.name, pd.diameter, pd.source) {
                (Some(name), Some(dia), Some(src)) => (
                    if src == crate::standards::drills::DrillSource::InchGauge {
                        format!("{head}: {name} ({:.4} in)", dia / crate::MM_PER_INCH)
                    } else {
                        format!("{head}: Ø{name} mm")
                    },
                    format!(
                        "{}; D1's middle {:.3}",
                        crate::report::tapping::drill_source_words(src),
                        pd.middle
                    ),
                ),
                _ => (
                    format!("{head}: Ø{:.3} mm", pd.middle),
                    "D1's middle; no stocked drill lies within D1".into(),
                ),
            };
            let colour = if drill_ok && !drill_unknown { "#333" } else { ZONE };
            g = g.add(
                text(x0, ty, 12.0, what)
                    .set("fill", colour)
                    .set("font-weight", "bold")
                    .set("id", format!("hole-{k}-passing-drill")),
            );
            ty += 14.0;
            g = g.add(text(x0, ty, 10.0, why).set("fill", "#555"));
        }
        text_bottom = text_bottom.max(ty);
        holes.push(g);
    }
    let h = text_bottom + 70.0;
    let mut doc = Document::new().set("viewBox", (0, 0, w, h)).set("width", w).set("height", h);
    doc = doc
        .add(Rectangle::new().set("width", w).set("height", h).set("fill", "white"))
        .add(
            text(20.0, 28.0, 16.0, format!("{}: tapped holes", file_name(&r.program)))
                .set("font-weight", "bold"),
        )
        .add(
            text(20.0, 50.0, 14.0, verdict)
                .set("font-weight", "bold")
                .set("fill", if r.pass { ZONE } else { FAIL }),
        );
    for g in holes {
        doc = doc.add(g);
    }
    // The scale bar: one scale for every hole.
    let bar = scale_bar_mm(s, 80.0);
    let (bx, by) = (20.0, h - 40.0);
    doc = doc
        .add(
            Line::new()
                .set("id", "scale-bar")
                .set("data-mm", bar)
                .set("x1", bx)
                .set("x2", format!("{:.3}", bx + bar * s))
                .set("y1", by)
                .set("y2", by)
                .set("stroke", "black")
                .set("stroke-width", 2),
        )
        .add(text(bx + bar * s + 8.0, by + 4.0, 11.0, format!("{} mm", fmt_num(bar))));
    let mut foot =
        String::from("D1 min and max of the tap's class dashed blue; the drill's point drawn at 118°");
    if r.holes.len() > shown.len() {
        foot = format!("{foot}; {} more tapping cycles in the text and JSON", r.holes.len() - shown.len());
    }
    doc = doc.add(text(20.0, h - 14.0, 11.0, foot).set("fill", "#555"));
    doc.to_string()
}
