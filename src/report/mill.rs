//! The milling report for a reader.

use super::kit::*;
use crate::analysis::check::Verdict;
use crate::analysis::mill::{LevelReport, Material, MillReport, Spot};
use crate::ground::plane::Point;
use svg::node::element::{Group, Line, Polyline, Rectangle};
use svg::Document;

/// The text report.
pub fn text(r: &MillReport) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{} ({}): Ø{} mm cutter, {} levels checked against x = {}, y = {} (material {})",
        r.program,
        r.dialect.name(),
        crate::ground::fmt::fmt_num(r.tool_diameter),
        r.levels.len(),
        r.target.x,
        r.target.y,
        match r.target.material {
            Material::Inside => "inside",
            Material::Outside => "outside",
        }
    );
    let spot = |p: &Option<Spot>| {
        p.map_or(String::new(), |p| {
            format!(
                " at X{:.4} Y{:.4} Z{} (t = {:.2}°{})",
                p.x,
                p.y,
                crate::ground::fmt::fmt_num(p.z),
                p.t,
                if p.line > 0 { format!(", line {}", p.line) } else { String::new() }
            )
        })
    };
    let _ = writeln!(s, "\n  gouge     {:.4} mm{}", r.gouge_max, spot(&r.gouge_at));
    let _ = writeln!(s, "  leftover  {:.4} mm{}", r.leftover_max, spot(&r.leftover_at));
    let _ = writeln!(s, "  tolerance {:.4} mm", r.tolerance);
    if r.levels.len() > 1 {
        let _ = writeln!(s, "\n  level Z     moves     gouge mm   leftover mm");
        let show: Vec<&LevelReport> = if r.levels.len() <= 12 {
            r.levels.iter().collect()
        } else {
            // The first and last few, and the worst.
            let mut v: Vec<&LevelReport> =
                r.levels.iter().take(4).chain(r.levels.iter().rev().take(4).rev()).collect();
            if let Some(w) = r.levels.iter().max_by(|a, b| a.gouge.total_cmp(&b.gouge)) {
                if !v.iter().any(|l| l.z == w.z) {
                    v.push(w);
                }
            }
            v.sort_by(|a, b| b.z.total_cmp(&a.z));
            v
        };
        let mut last_z = None;
        for l in show {
            if let Some(prev) = last_z {
                let gap = r.levels.iter().filter(|m| m.z < prev && m.z > l.z).count();
                if gap > 0 {
                    let _ = writeln!(s, "  … {gap} more");
                }
            }
            let _ = writeln!(
                s,
                "  {:>8}  {:>7}  {:>10.4}  {:>12.4}",
                crate::ground::fmt::fmt_num(l.z),
                l.moves,
                l.gouge,
                l.leftover
            );
            last_z = Some(l.z);
        }
    }
    let _ = writeln!(
        s,
        "\nverdict: {}",
        match r.verdict {
            Verdict::Pass => "PASS".to_string(),
            Verdict::Fail => {
                let mut why = Vec::new();
                if r.gouge_out {
                    why.push("gouge");
                }
                if r.leftover_out {
                    why.push("material left");
                }
                format!("FAIL ({} beyond {} mm)", why.join(", "), crate::ground::fmt::fmt_num(r.tolerance))
            }
        }
    );
    for n in &r.notes {
        let _ = writeln!(s, "note: {}", n.marked());
    }
    s
}

/// The SVG of a milling check: the worst level's target, the area the cutter swept, the tool
/// centre path, and the deviation along the target, magnified.
pub fn mill_svg(r: &crate::analysis::mill::MillReport) -> String {
    use super::kit::text;
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
