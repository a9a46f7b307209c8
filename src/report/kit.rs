//! The drawing kit every report shares: the panel frame mapping the axial plane into pixels,
//! axes, text, the tolerance zone, dimension lines and labels, limits as the tables print them,
//! and the HTML page around a report (its style and escaping).

use crate::ground::plane::{rad, Point};
use crate::standards::ThreadKind;
use svg::node::element::{Group, Line, Polygon, Polyline, Rectangle, Text};

/// Maps the axial plane (mm) into a panel (px), radius up.
#[derive(Clone, Copy)]
pub(crate) struct Frame {
    pub(crate) x0: f64,
    pub(crate) y0: f64,
    pub(crate) w: f64,
    pub(crate) h: f64,
    pub(crate) z_min: f64,
    pub(crate) r_max: f64,
    pub(crate) scale: f64,
}

impl Frame {
    pub(crate) fn new(x0: f64, y0: f64, w: f64, h: f64, z: (f64, f64), r: (f64, f64)) -> Frame {
        let scale = (w / (z.1 - z.0)).min(h / (r.1 - r.0));
        // Centre the drawing in the panel.
        let z_min = 0.5 * (z.0 + z.1) - 0.5 * w / scale;
        let r_max = 0.5 * (r.0 + r.1) + 0.5 * h / scale;
        Frame { x0, y0, w, h, z_min, r_max, scale }
    }

    pub(crate) fn x(&self, z: f64) -> f64 {
        self.x0 + (z - self.z_min) * self.scale
    }

    pub(crate) fn y(&self, r: f64) -> f64 {
        self.y0 + (self.r_max - r) * self.scale
    }

    pub(crate) fn points(&self, pts: &[Point]) -> String {
        pixel_points(pts.iter().map(|p| (self.x(p.z), self.y(p.r))))
    }

    pub(crate) fn z_range(&self) -> (f64, f64) {
        (self.z_min, self.z_min + self.w / self.scale)
    }
}

/// A polyline's points in pixels for an SVG `points` attribute, to 0.01 px, leaving out each
/// point that lies within 0.02 px of the straight line from the last one kept to the next (a
/// zone's flat stretches, a straight flank sampled every pixel): the same picture in far fewer
/// bytes.
pub(crate) fn pixel_points(pts: impl Iterator<Item = (f64, f64)>) -> String {
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

pub(crate) fn text(x: f64, y: f64, size: f64, s: impl Into<String>) -> Text {
    Text::new(s.into())
        .set("x", format!("{x:.1}"))
        .set("y", format!("{y:.1}"))
        .set("font-size", size)
        .set("font-family", "sans-serif")
}

/// A panel: its group (with the clip path, white background, frame and the caption above it)
/// and the group to draw in, clipped to the panel. The frame carries `class="panel"`: nothing
/// written in the picture lies inside one (the layout test checks it).
pub(crate) fn panel(f: &Frame, id: &str, label: &str) -> (Group, Group) {
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
pub(crate) fn tick_step(span: f64, n: f64) -> f64 {
    let raw = (span / n).max(1e-9);
    let e = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0].into_iter().map(|k| k * e).find(|s| *s >= raw).unwrap_or(10.0 * e)
}

/// A tick label without float noise.
pub(crate) fn tick_label(v: f64, step: f64) -> String {
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    let s = format!("{v:.decimals$}");
    if s.starts_with('-') && s.trim_start_matches(['-', '0', '.']).is_empty() {
        s[1..].to_string()
    } else {
        s
    }
}

/// Axes of a panel: Z (mm) ticks below it, diameter (mm, twice the radius) ticks on its right.
pub(crate) fn axes(f: &Frame, diameter_axis: bool, units: crate::analysis::turn::Units) -> Group {
    // Ticks at round numbers of the reader's unit: mm, or inches (the frame stays in mm).
    let (per, name) = match units {
        crate::analysis::turn::Units::Mm => (1.0, "mm"),
        crate::analysis::turn::Units::Inch => (25.4, "in"),
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
            g = g.add(
                Line::new()
                    .set("x1", f.x0 + f.w)
                    .set("x2", f.x0 + f.w + 4.0)
                    .set("y1", y)
                    .set("y2", y)
                    .set("stroke", "#333"),
            );
            // A tick at the panel's top edge keeps its line; its label (9 px text, from about
            // 5.5 px above its tick) would cross the unit's, whose foot lies 2.5 px above the
            // edge ("13" on "Ø mm", 1 px below the edge, seen in Chromium).
            if y - f.y0 >= 4.0 {
                g = g.add(text(f.x0 + f.w + 6.0, y + 3.0, 9.0, tick_label(d, step)));
            }
            d += step;
        }
        g = g.add(text(f.x0 + f.w + 6.0, f.y0 - 5.0, 9.0, format!("Ø {name}")));
    }
    g
}

pub(crate) const ZONE: &str = "#2e9e4f";

pub(crate) const FAIL: &str = "#c62828";

/// The tolerance zone between its maximum- and minimum-material sides, translucent over the
/// material and the air (`{id}-tolerance-zone`): the maximum-material side solid, the other
/// dashed.
pub(crate) fn zone_group(sides: Option<(Vec<Point>, Vec<Point>)>, f: &Frame, id: &str) -> Group {
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

/// Dimension lines of the measured diameters across a panel, red when out of their limits;
/// each `{id}-dim-{feature}`.
pub(crate) fn dimension_lines(
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

/// The dimension labels of `items` (measured diameters) beside panel `f`, as
/// [`dimension_labels`] places them.
pub(crate) fn labels_of_dimensions(
    items_in: &[(crate::CheckFeature, f64)],
    checks: &[crate::Check],
    kind: ThreadKind,
    units: crate::analysis::turn::Units,
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
        // In the report's unit, the mm beside the inches; the limits and the deviation as the
        // check table gives them.
        let lengths = super::Lengths(units);
        let line1 = format!("{name} {}", lengths.both(d));
        let line2 = check.map_or(String::new(), |c| {
            let cells = super::check_cells(c, lengths);
            let lim = match (c.min, c.max) {
                (None, None) => String::new(),
                (min, max) => format!("[{}]", shown_limits(min, max, &cells, "")),
            };
            if c.ok {
                lim
            } else {
                format!("{lim} {}", cells.deviation)
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

/// A limit as the tables give it: three decimals at their 1 µm, four for the inch forms'
/// limits converted to mm.
pub(crate) fn fmt_limit(v: f64) -> String {
    if ((v * 1e3).round() - v * 1e3).abs() < 1e-6 {
        format!("{v:.3}")
    } else {
        format!("{v:.4}")
    }
}

/// A pair of limits (`8.862 – 8.994`, `≥ 0.187`), `unit` at the end.
pub(crate) fn fmt_limits(min: Option<f64>, max: Option<f64>, unit: &str) -> String {
    match (min, max) {
        (Some(a), Some(b)) => format!("{} – {}{unit}", fmt_limit(a), fmt_limit(b)),
        (Some(a), None) => format!("≥ {}{unit}", fmt_limit(a)),
        (None, Some(b)) => format!("≤ {}{unit}", fmt_limit(b)),
        (None, None) => String::new(),
    }
}

/// A pair of limits as a table shows them: in mm as the tables give them (`fmt_limits`), in
/// inches the cells' own (`0.4436 – 0.4485`, `≥ 0.0000`).
pub(crate) fn shown_limits(
    min: Option<f64>,
    max: Option<f64>,
    cells: &super::CheckCells,
    unit: &str,
) -> String {
    if cells.unit != "in" && cells.unit != "in/min" {
        return fmt_limits(min, max, unit);
    }
    match (min, max) {
        (Some(_), Some(_)) => format!("{} – {}{unit}", cells.min, cells.max),
        (Some(_), None) => format!("≥ {}{unit}", cells.min),
        (None, Some(_)) => format!("≤ {}{unit}", cells.max),
        (None, None) => String::new(),
    }
}

/// A band that names a section of a picture, `width` wide: its words in bold, wrapped (never
/// cut), and the band's height.
pub(crate) fn band(words: &str, width: f64) -> (Group, f64) {
    let lines = wrap(words, 120);
    let h = 34.0 + 19.0 * (lines.len().max(1) - 1) as f64;
    let mut g =
        Group::new().add(Rectangle::new().set("width", width).set("height", h).set("fill", "#eef1f5"));
    for (i, l) in lines.into_iter().enumerate() {
        g = g.add(text(20.0, 23.0 + 19.0 * i as f64, 15.0, l).set("font-weight", "bold"));
    }
    (g, h)
}

/// `s` in lines of at most `n` characters, broken at spaces, a word longer than a line (a long
/// file name) broken inside itself, never cut (the text reports wrap their prose with it too).
pub(crate) fn wrap(s: &str, n: usize) -> Vec<String> {
    let n = n.max(1);
    let mut lines = vec![String::new()];
    for word in s.split(' ') {
        let chars: Vec<char> = word.chars().collect();
        for piece in chars.chunks(n) {
            let last = lines.last_mut().map_or(0, |l| l.chars().count());
            if last > 0 && last + 1 + piece.len() > n {
                lines.push(String::new());
            }
            if let Some(l) = lines.last_mut() {
                if !l.is_empty() {
                    l.push(' ');
                }
                l.extend(piece);
            }
        }
    }
    lines
}

/// A program's file name without its folders: a picture's title has no room for a long path
/// (the HTML page and the text keep it whole).
pub(crate) fn file_name(program: &str) -> String {
    std::path::Path::new(program)
        .file_name()
        .map_or(program.to_string(), |n| n.to_string_lossy().into_owned())
}

/// The file name of a program label, with its dialect (`dir/p.nc (fanuc)` → `p.nc (fanuc)`).
pub(crate) fn label_name(label: &crate::analysis::turn::ProgramLabel) -> String {
    format!("{} ({})", file_name(&label.file), label.dialect.name())
}

/// A scale bar's length, mm: a round number about `px` pixels long at `s` px/mm.
pub(crate) fn scale_bar_mm(s: f64, px: f64) -> f64 {
    tick_step(px / s, 1.0)
}

/// Text for HTML: `& < > " '` escaped.
pub(crate) fn esc(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

pub(crate) const STYLE: &str = "body{font-family:sans-serif;margin:24px;color:#1d1d1d;max-width:1160px}\
h1{font-size:22px}h2{font-size:18px;margin-top:28px}h3{font-size:15px}\
table{border-collapse:collapse;margin:8px 0 16px}th,td{border:1px solid #ccc;padding:3px 8px;font-size:13px}\
th{background:#eef1f5;text-align:left}td.n{text-align:right;font-variant-numeric:tabular-nums}\
.ok{color:#1d7a36}.out{color:#c62828;font-weight:bold}.form{color:#8a6d00}\
.verdict{font-size:18px;font-weight:bold}.pic{overflow-x:auto}.pic svg{max-width:100%;height:auto}\
ul.notes li{font-size:13px;margin:2px 0}pre.wrap{white-space:pre-wrap;font-size:12px}";

pub(crate) fn page(title: &str, body: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n{body}</body>\n</html>\n",
        esc(title)
    )
}

/// One row of a check table: the feature, value, limits, (the value in inches), deviation, the
/// verdict word and the note.
pub(crate) fn check_row(
    c: &crate::analysis::check::Check,
    kind: ThreadKind,
    cells: &super::CheckCells,
    in_cell: &str,
    cls: &str,
    word: &str,
) -> String {
    format!(
        "<tr><td>{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td>{in_cell}<td class=\"n\">{}</td><td class=\"{cls}\">{word}</td><td>{}</td></tr>\n",
        esc(c.feature.words(kind)),
        esc(&cells.value),
        esc(cells.min.trim_start_matches('—')),
        esc(cells.max.trim_start_matches('—')),
        esc(&cells.deviation),
        esc(c.note.as_deref().unwrap_or(""))
    )
}
