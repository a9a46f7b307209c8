//! SVG cross-sections of a verification: self-contained, readable in any browser.
//!
//! Layers are `<g id="…">` groups: `title`, `blank`, `tolerance-zone`, `basic-profile`,
//! `passes`, `as-cut`, `dimensions`, `legend`, `chip-chart`, each view (`tooth`, `window`) holding
//! its own copies. Text from user input (designations, insert names) is escaped by the `svg`
//! crate.

use crate::geometry::{rad, Point};
use crate::insert::Insert;
use crate::standards::{ProfileKind, ThreadKind};
use crate::verify::Verification;
use svg::node::element::{Group, Line, Polygon, Polyline, Rectangle, Text};
use svg::Document;

/// Maps the axial plane (mm) into a panel (px), radius up.
#[derive(Clone, Copy)]
struct Frame {
    x0: f64,
    y0: f64,
    w: f64,
    h: f64,
    z_min: f64,
    r_max: f64,
    scale: f64,
}

impl Frame {
    fn new(x0: f64, y0: f64, w: f64, h: f64, z: (f64, f64), r: (f64, f64)) -> Frame {
        let scale = (w / (z.1 - z.0)).min(h / (r.1 - r.0));
        // Centre the drawing in the panel.
        let z_min = 0.5 * (z.0 + z.1) - 0.5 * w / scale;
        let r_max = 0.5 * (r.0 + r.1) + 0.5 * h / scale;
        Frame { x0, y0, w, h, z_min, r_max, scale }
    }

    fn x(&self, z: f64) -> f64 {
        self.x0 + (z - self.z_min) * self.scale
    }

    fn y(&self, r: f64) -> f64 {
        self.y0 + (self.r_max - r) * self.scale
    }

    fn points(&self, pts: &[Point]) -> String {
        pts.iter().map(|p| format!("{:.2},{:.2}", self.x(p.z), self.y(p.r))).collect::<Vec<_>>().join(" ")
    }

    fn z_range(&self) -> (f64, f64) {
        (self.z_min, self.z_min + self.w / self.scale)
    }
}

fn text(x: f64, y: f64, size: f64, s: impl Into<String>) -> Text {
    Text::new(s.into())
        .set("x", format!("{x:.1}"))
        .set("y", format!("{y:.1}"))
        .set("font-size", size)
        .set("font-family", "sans-serif")
}

/// The profile `kind` of the thread moved radially so its pitch diameter is `d2`, repeated over
/// `z_range` around the groove at `zc`, and clamped to the crest limit `crest` (radius) if given.
fn shifted_profile(
    v: &Verification,
    variant: ProfileKind,
    d2: f64,
    zc: f64,
    z_range: (f64, f64),
    crest: Option<f64>,
) -> Vec<Point> {
    let t = &v.designation.thread;
    let one = t.profile(variant, 1e-3);
    let shift = 0.5 * (d2 - t.pitch_diameter());
    let p = t.pitch;
    let k0 = ((z_range.0 - zc) / p).floor() as i64 - 1;
    let k1 = ((z_range.1 - zc) / p).ceil() as i64 + 1;
    let mut out: Vec<Point> = Vec::new();
    for k in k0..=k1 {
        for q in &one {
            let mut r = q.r + shift;
            if let Some(c) = crest {
                r = match v.kind {
                    ThreadKind::External => r.min(c),
                    ThreadKind::Internal => r.max(c),
                };
            }
            let z = q.z + zc + k as f64 * p;
            if out.last().is_none_or(|l| (l.z - z).abs() > 1e-12 || (l.r - r).abs() > 1e-12) {
                out.push(Point::new(z, r));
            }
        }
    }
    out.into_iter().filter(|q| q.z >= z_range.0 && q.z <= z_range.1).collect()
}

/// A panel: its group (with the clip path, white background and label) and the group to draw
/// in, clipped to the panel.
fn panel(f: &Frame, id: &str, label: &str) -> (Group, Group) {
    let clip_id = format!("clip-{id}");
    let frame = Rectangle::new().set("x", f.x0).set("y", f.y0).set("width", f.w).set("height", f.h);
    let g = Group::new()
        .set("id", id)
        .add(
            svg::node::element::Definitions::new()
                .add(svg::node::element::ClipPath::new().set("id", clip_id.clone()).add(frame.clone())),
        )
        .add(frame.set("fill", "white").set("stroke", "#999"))
        .add(text(f.x0 + 6.0, f.y0 + 16.0, 12.0, label));
    (g, Group::new().set("clip-path", format!("url(#{clip_id})")))
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

fn view(v: &Verification, f: &Frame, id: &str, label: &str) -> Group {
    let kind = v.kind;
    let m = &v.measurement;
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
    cut = cut.add(
        Polyline::new()
            .set("points", f.points(&v.section.profile()))
            .set("fill", "none")
            .set("stroke", "#111")
            .set("stroke-width", 2.2),
    );
    // Tolerance zone between the maximum- and minimum-material profiles.
    let l = &v.limits;
    let (mmc_d2, lmc_d2) = match kind {
        ThreadKind::External => (l.pitch_diameter.max, l.pitch_diameter.min),
        ThreadKind::Internal => (l.pitch_diameter.min, l.pitch_diameter.max),
    };
    let mut zone = Group::new().set("id", format!("{id}-tolerance-zone"));
    if let (Some(a), Some(b)) = (mmc_d2, lmc_d2) {
        let (mmc_variant, lmc_variant, lmc_crest) = match kind {
            ThreadKind::External => {
                (ProfileKind::Basic, ProfileKind::BoltMinRoot, l.major_diameter.min.map(rad))
            }
            ThreadKind::Internal => (ProfileKind::Nut, ProfileKind::Nut, l.minor_diameter.max.map(rad)),
        };
        let mmc = shifted_profile(v, mmc_variant, a, m.groove_center, zr, None);
        let mut lmc = shifted_profile(v, lmc_variant, b, m.groove_center, zr, lmc_crest);
        let mut poly = mmc.clone();
        lmc.reverse();
        poly.extend(lmc);
        zone = zone
            .add(
                Polygon::new()
                    .set("points", f.points(&poly))
                    .set("fill", "#2e9e4f")
                    .set("fill-opacity", 0.25)
                    .set("stroke", "none"),
            )
            .add(
                Polyline::new()
                    .set("points", f.points(&mmc))
                    .set("fill", "none")
                    .set("stroke", "#2e9e4f")
                    .set("stroke-width", 1.2),
            );
    }
    let basic_variant = if kind == ThreadKind::External { ProfileKind::Basic } else { ProfileKind::Nut };
    let basic =
        shifted_profile(v, basic_variant, v.designation.thread.pitch_diameter(), m.groove_center, zr, None);
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
    body = body.add(zone).add(cut).add(basic_g).add(passes);
    g = g.add(body);
    // Dimension lines of the measured diameters.
    let mut dims = Group::new().set("id", format!("{id}-dimensions"));
    for (name, d, colour) in [
        ("d", m.major_diameter, "#b03030"),
        (if kind == ThreadKind::External { "d2" } else { "D2" }, m.pitch_diameter, "#1f5fbf"),
        (if kind == ThreadKind::External { "d3" } else { "D1" }, m.minor_diameter, "#7a3fb0"),
    ] {
        let name = if name == "d" && kind == ThreadKind::Internal { "D" } else { name };
        let y = f.y(rad(d));
        if y < f.y0 || y > f.y0 + f.h {
            continue;
        }
        dims = dims
            .add(
                Line::new()
                    .set("x1", f.x0)
                    .set("x2", f.x0 + f.w)
                    .set("y1", y)
                    .set("y2", y)
                    .set("stroke", colour)
                    .set("stroke-width", 0.8)
                    .set("stroke-dasharray", "2 3"),
            )
            .add(
                text(
                    f.x0 + f.w - if v.units == crate::verify::Units::Inch { 200.0 } else { 120.0 },
                    y - 3.0,
                    11.0,
                    if v.units == crate::verify::Units::Inch {
                        format!("{name} = {d:.4} mm ({:.5} in)", d / 25.4)
                    } else {
                        format!("{name} = {d:.4}")
                    },
                )
                .set("fill", colour),
            );
    }
    g.add(dims)
}

/// The whole thread along its length: blank, material as cut and the cut surface.
fn full_view(section: &crate::sweep::Section, f: &Frame, v: &Verification) -> Group {
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
    g.add(body)
}

fn legend(x: f64, y: f64) -> Group {
    let mut g = Group::new().set("id", "legend");
    let items: [(&str, &str, bool); 6] = [
        ("#e9e9e9", "blank before threading", true),
        ("#b8c7d9", "material as cut", true),
        ("#2e9e4f", "tolerance zone (max. to min. material)", true),
        ("#555", "basic profile (dashed)", false),
        ("#111", "as-cut profile", false),
        ("hsl(120,75%,45%)", "insert at each pass, blue first, red last", false),
    ];
    for (i, (c, label, fill)) in items.iter().enumerate() {
        let yy = y + 18.0 * i as f64;
        if *fill {
            g = g.add(
                Rectangle::new()
                    .set("x", x)
                    .set("y", yy - 10.0)
                    .set("width", 14)
                    .set("height", 10)
                    .set("fill", *c)
                    .set("fill-opacity", if *c == "#2e9e4f" { 0.4 } else { 1.0 }),
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

fn chip_chart(v: &Verification, x: f64, y: f64, w: f64, h: f64) -> Group {
    let mut g = Group::new().set("id", "chip-chart");
    g = g.add(text(x, y - 6.0, 12.0, "chip area per pass, mm²"));
    let max = v.metrics.iter().map(|m| m.chip_area).fold(0.0, f64::max);
    let n = v.metrics.len().max(1);
    let bw = w / n as f64;
    g = g.add(
        Line::new().set("x1", x).set("x2", x + w).set("y1", y + h).set("y2", y + h).set("stroke", "#333"),
    );
    for (i, m) in v.metrics.iter().enumerate() {
        let bh = if max > 0.0 { h * m.chip_area / max } else { 0.0 };
        g = g.add(
            Rectangle::new()
                .set("x", format!("{:.2}", x + i as f64 * bw + 0.1 * bw))
                .set("y", format!("{:.2}", y + h - bh))
                .set("width", format!("{:.2}", 0.8 * bw))
                .set("height", format!("{bh:.2}"))
                .set("fill", colour(i, n)),
        );
    }
    g.add(text(x + w + 4.0, y + 10.0, 10.0, format!("{max:.4}")))
}

/// The SVG document of a verification.
pub fn verify_svg(v: &Verification) -> String {
    let (width, height) = (1100.0, 960.0);
    Document::new()
        .set("viewBox", (0, 0, width, height))
        .set("width", width)
        .set("height", height)
        .add(verification_group(v))
        .to_string()
}

/// The SVG of every operation of a program, one section each, stacked.
pub fn program_svg(pv: &crate::verify::ProgramVerification) -> String {
    let width = 1100.0;
    let mut y = 0.0;
    let mut doc = Document::new();
    for o in &pv.operations {
        let head = format!(
            "operation {} of {}: {} at line {} of {}{}",
            o.operation.index,
            pv.operations.len(),
            o.operation.cycle,
            o.operation.source_line,
            pv.program,
            o.operation.tool.map_or(String::new(), |t| format!(", tool T{t}"))
        );
        let mut g = Group::new()
            .set("id", format!("operation-{}", o.operation.index))
            .set("transform", format!("translate(0,{y})"))
            .add(Rectangle::new().set("width", width).set("height", 34).set("fill", "#eef1f5"))
            .add(text(20.0, 23.0, 15.0, head).set("font-weight", "bold"));
        let h = match &o.result {
            crate::verify::OperationResult::Verified(v) => {
                g = g.add(verification_group(v).set("transform", "translate(0,34)"));
                34.0 + 960.0
            }
            crate::verify::OperationResult::NoCut { reason } => {
                g = g.add(
                    text(20.0, 64.0, 16.0, format!("verdict: FAIL ({}) — {reason}", o.designation))
                        .set("fill", "#b3261e")
                        .set("font-weight", "bold"),
                );
                90.0
            }
        };
        doc = doc.add(g);
        y += h;
    }
    doc.set("viewBox", (0, 0, width, y)).set("width", width).set("height", y).to_string()
}

/// One verification's picture: title, tooth, window, legend, chip chart and full length.
fn verification_group(v: &Verification) -> Group {
    let t = &v.designation.thread;
    let p = t.pitch;
    let m = &v.measurement;
    let (width, height) = (1100.0, 960.0);
    let lo = m.minor_diameter.min(m.major_diameter);
    let hi = m.major_diameter.max(m.minor_diameter).max(v.blank_diameter);
    let (r0, r1) = (rad(lo) - 0.15 * p, rad(hi) + 0.12 * p);
    let tooth = Frame::new(
        20.0,
        90.0,
        640.0,
        460.0,
        (m.groove_center - 0.75 * p, m.groove_center + 0.75 * p),
        (r0, r1),
    );
    let w = v.section.window;
    let window = Frame::new(680.0, 90.0, 400.0, 300.0, (w.z_min, w.z_max), (r0 - 0.2 * p, r1 + 0.1 * p));
    let verdict = if v.pass { "PASS" } else { "FAIL" };
    let failed: Vec<&str> = v.checks.iter().filter(|c| !c.ok).map(|c| c.feature.name()).collect();
    let title = Group::new()
        .set("id", "title")
        .add(text(
            20.0,
            30.0,
            20.0,
            format!("{} — {} thread, class {}", v.designation.text, v.kind.name(), v.limits.class),
        ))
        .add(text(
            20.0,
            52.0,
            13.0,
            format!(
                "insert: {} · {} · {} passes · blank X{:.3} · final X{:.4}",
                v.insert.name,
                match &v.program {
                    Some(p) => format!("program {p}"),
                    None => format!("infeed: {}", crate::report::infeed_text(&v.infeed)),
                },
                v.passes.len(),
                v.blank_diameter,
                v.final_x
            ),
        ))
        .add(
            text(
                20.0,
                76.0,
                16.0,
                if v.pass {
                    format!("verdict: {verdict}")
                } else {
                    format!("verdict: {verdict} ({})", failed.join(", "))
                },
            )
            .set("fill", if v.pass { "#1d7a36" } else { "#b3261e" })
            .set("font-weight", "bold"),
        );
    // The whole thread, run-out included: the envelope over the full length (the tree for
    // undercut custom inserts).
    let full = {
        let setup = crate::sweep::SweepSetup {
            kind: v.kind,
            insert: &v.insert,
            blank_diameter: v.blank_diameter,
            pitch: p,
        };
        let w = crate::sweep::full_length_window(&v.passes, p);
        crate::sweep::sweep(&setup, &v.passes, w, crate::boolean::UnionStrategy::Envelope).ok()
    };
    let doc = Group::new()
        .add(Rectangle::new().set("width", width).set("height", height).set("fill", "white"))
        .add(title)
        .add(view(v, &tooth, "tooth", "one tooth"))
        .add(view(v, &window, "window", "four pitches"))
        .add(legend(690.0, 420.0))
        .add(chip_chart(v, 690.0, 570.0, 360.0, 150.0));
    match &full {
        Some(f) => {
            let fw = f.section.window;
            let frame =
                Frame::new(20.0, 770.0, 1060.0, 170.0, (fw.z_min, fw.z_max), (r0 - 0.3 * p, r1 + 0.2 * p));
            doc.add(full_view(&f.section, &frame, v))
        }
        None => doc,
    }
}

/// The SVG of a milling check: the worst level's target, the area the cutter swept, the tool
/// centre path, and the deviation along the target, magnified.
pub fn mill_svg(r: &crate::mill::MillReport) -> String {
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
    let name = std::path::Path::new(&r.program)
        .file_name()
        .map_or(r.program.clone(), |n| n.to_string_lossy().into_owned());
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
    let ccw = crate::boolean::signed_area(&pic.target[..n.saturating_sub(1)]) > 0.0;
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
        crate::report::Verdict::Pass => "PASS",
        crate::report::Verdict::Fail => "FAIL",
    };
    doc = doc.add(text(
        20.0,
        30.0,
        18.0,
        format!("{name}: level Z{} — {verdict}", crate::report::fmt_num(pic.z)),
    ));
    doc = doc.add(text(
        20.0,
        54.0,
        13.0,
        format!(
            "Ø{} mm cutter; gouge {:.4} mm, leftover {:.4} mm, tolerance {} mm; red: deviation from the target × {}",
            crate::report::fmt_num(r.tool_diameter),
            r.gouge_max,
            r.leftover_max,
            crate::report::fmt_num(r.tolerance),
            crate::report::fmt_num((mag * 10.0).round() / 10.0)
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
