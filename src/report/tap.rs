//! The tapping check's text (its JSON is the report itself, `TapReport` derives `Serialize`).

use super::kit::*;
use crate::analysis::tap::{TapFeature, TapReport};
use crate::ground::fmt::fmt_num;
use crate::standards::drills::{DrillSource, PassingDrill};
use std::fmt::Write as _;
use svg::node::element::{Group, Line, Polygon, Rectangle};
use svg::Document;

pub fn feature_name(f: TapFeature) -> &'static str {
    match f {
        TapFeature::DrillDiameter => "drill diameter",
        TapFeature::Feed => "feed",
        TapFeature::Depth => "depth below",
        TapFeature::Spindle => "spindle",
    }
}

/// Where a suggested drill comes from, in words.
pub(crate) fn drill_source_words(s: DrillSource) -> &'static str {
    match s {
        DrillSource::Iso2306Coarse => "ISO 2306's tap drill",
        DrillSource::Iso2306Fine => "ISO 2306's fine-series tap drill",
        DrillSource::MetricSeries => "the 0.1 mm drill nearest the middle",
        DrillSource::InchGauge => "the inch drill nearest the middle",
    }
}

/// The drill that would pass, in words: `Ø8.5 mm (ISO 2306's tap drill); D1's middle 8.526 mm`.
pub(crate) fn passing_drill_words(d: &PassingDrill, window: &str) -> String {
    match (&d.name, d.diameter, d.source) {
        (Some(name), Some(dia), Some(src)) => {
            let inch = src == DrillSource::InchGauge;
            format!(
                "{} ({}{}); {window}'s middle {:.3} mm",
                if inch {
                    format!("{name}, {:.4} in", dia / crate::MM_PER_INCH)
                } else {
                    format!("Ø{name} mm")
                },
                drill_source_words(src),
                if inch { format!(", {:.3} mm", dia) } else { String::new() },
                d.middle
            )
        }
        _ => format!("Ø{:.3} mm, {window}'s middle (no stocked drill lies within it)", d.middle),
    }
}

/// `a drill that passes: …` for a hole whose drill fails D1 or is not known; `None` when the
/// drill passes (or the tap is a taper pipe tap).
pub(crate) fn passing_drill_line(h: &crate::analysis::tap::TappedHole) -> Option<String> {
    let drill_bad = h.checks.iter().any(|k| k.feature == TapFeature::DrillDiameter && !k.ok);
    let drill_unknown = h.drill.as_ref().is_none_or(|d| d.diameter.is_none());
    let pd = h.drill_that_passes.as_ref().filter(|_| drill_bad || drill_unknown)?;
    let window = if h.tap.forming { "the form tap's hole" } else { "D1" };
    Some(format!("a drill that passes: {}", passing_drill_words(pd, window)))
}

/// The text `threadcheck tap` prints.
pub fn text(r: &TapReport) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{} ({}): {} tapping cycle{}, {} drilling cycle{}",
        r.program,
        r.dialect.name(),
        r.holes.len(),
        if r.holes.len() == 1 { "" } else { "s" },
        r.drills,
        if r.drills == 1 { "" } else { "s" }
    );
    s.push_str(&holes_text(r));
    if r.holes.len() > 1 {
        let _ = writeln!(s, "\nprogram verdict: {}", if r.pass { "PASS" } else { "FAIL" });
    }
    for n in &r.notes {
        let _ = writeln!(s, "note: {}", n.marked());
    }
    s
}

/// Each tapped hole's section: its cycle, tap and drill, its checks, its verdict and notes (what
/// `tap` prints between its heading and its program verdict; `verify` prints it among the
/// program's operations).
/// A position as a program writes it, to the micrometre (a computed place, 34.641016, as 34.641).
fn micron(v: f64) -> String {
    fmt_num((v * 1000.0).round() / 1000.0)
}

/// A length as the cycle's program writes it: mm to the micrometre, or, in an inch program, inches
/// to the 0.0001 in its words carry (`Z-0.5` for Z-12.7 mm).
fn word(c: &crate::gcode::HoleCycle, v: f64) -> String {
    match c.units {
        crate::gcode::ProgramUnits::Mm => micron(v),
        crate::gcode::ProgramUnits::Inch => fmt_num((v / crate::MM_PER_INCH * 1e4).round() / 1e4),
    }
}

/// In an inch program, a tapping check's unit in inches and its decimals (a length 0.0001 in, a
/// feed per minute 0.1 in/min, per revolution 0.0001 in); `None` in a mm program or for a unit
/// that is not a length's.
fn tap_inch_unit(c: &crate::gcode::HoleCycle, unit: &str) -> Option<(&'static str, usize)> {
    if c.units != crate::gcode::ProgramUnits::Inch {
        return None;
    }
    match unit {
        "mm" => Some(("in", 4)),
        "mm/min" => Some(("in/min", 1)),
        "mm/rev" => Some(("in/rev", 4)),
        _ => None,
    }
}

/// A failing tapping check's distance to its limit in the program's units: `+1.5 mm/min`,
/// `-12.0 µm`; in inch `-1.0 in/min`, `-0.0005 in`.
fn tap_off(c: &crate::gcode::HoleCycle, k: &crate::analysis::tap::TapCheck) -> String {
    let inch = c.units == crate::gcode::ProgramUnits::Inch;
    match (k.unit, inch) {
        ("mm/min", true) => format!("{:+.1} in/min", k.deviation / crate::MM_PER_INCH),
        ("mm/min", false) => format!("{:+.1} mm/min", k.deviation),
        ("mm/rev", true) => format!("{:+.5} in/rev", k.deviation / 1000.0 / crate::MM_PER_INCH),
        _ => lengths(c).deviation_cell(k.deviation),
    }
}

/// D1's limits as the hole's picture gives them: `8.376 – 8.676 mm` as the tables print them, or
/// in an inch program `0.1960 – 0.2070 in`.
fn d1_limits(c: &crate::gcode::HoleCycle, min: Option<f64>, max: Option<f64>) -> String {
    if c.units == crate::gcode::ProgramUnits::Inch {
        let n = |v: Option<f64>| v.map_or("—".to_string(), |v| format!("{:.4}", v / crate::MM_PER_INCH));
        format!("{} – {} in", n(min), n(max))
    } else {
        fmt_limits(min, max, " mm")
    }
}

/// Pound-force inches in a newton metre: 1 / (4.4482216152605 N × 0.0254 m).
const LBF_IN_PER_NM: f64 = 8.850_745_791_327_185;

/// How the cycle's report gives lengths: in its program's units, the mm beside inches.
fn lengths(c: &crate::gcode::HoleCycle) -> super::Lengths {
    super::Lengths(match c.units {
        crate::gcode::ProgramUnits::Mm => crate::analysis::turn::Units::Mm,
        crate::gcode::ProgramUnits::Inch => crate::analysis::turn::Units::Inch,
    })
}

/// A machining centre's hole's place, ` (X20 Y15)`, when both are known (a lathe's holes on the
/// axis have no Y): the holes of one pattern cycle share its line.
fn place(c: &crate::gcode::HoleCycle) -> String {
    match (c.x, c.y, c.radial) {
        (_, _, Some(r)) => format!(" (Z{} C{}, radial)", word(c, r.z), micron(r.c_deg)),
        (Some(x), Some(y), None) => format!(" (X{} Y{}{})", word(c, x), word(c, y), in_offset(c)),
        _ => String::new(),
    }
}

/// A height along a hole's axis as the program writes it: `Z-15`, or a radial hole's `X20` (its
/// radius 10 as the lathe's diameter).
fn along(c: &crate::gcode::HoleCycle, v: f64) -> String {
    match c.radial {
        Some(_) => format!("X{}", word(c, 2.0 * v)),
        None => format!("Z{}", word(c, v)),
    }
}

/// `3`, or `3 of O2000.nc` for a cycle that stands in a subprogram file.
fn line_of(c: &crate::gcode::HoleCycle) -> String {
    match &c.source_file {
        Some(f) => format!("{} of {}", c.line, file_name(f)),
        None => c.line.to_string(),
    }
}

/// ` in G55`: the work offset a hole's place is in, when the program selected one other than G54.
fn in_offset(c: &crate::gcode::HoleCycle) -> String {
    match c.work_offset.as_deref() {
        Some(w) if w != "G54" => format!(" in {w}"),
        _ => String::new(),
    }
}

pub fn holes_text(r: &TapReport) -> String {
    let mut s = String::new();
    for h in &r.holes {
        let c = &h.cycle;
        let _ = writeln!(
            s,
            "\n== {} at line {}{}{}, tap {} (chamfer {} P{}){}",
            c.code,
            line_of(c),
            place(c),
            c.tool.map_or(String::new(), |t| format!(", tool T{t}")),
            h.tap.designation,
            fmt_num(h.tap.chamfer_pitches),
            if h.tap.chamfer_given { "" } else { ", default" },
            if c.rigid { ", rigid" } else { "" }
        );
        match &h.drill {
            Some(d) => {
                let _ = writeln!(
                    s,
                    "drilled by {} at line {}{}{}{}",
                    d.cycle.code,
                    line_of(&d.cycle),
                    d.cycle.tool.map_or(String::new(), |t| format!(", tool T{t}")),
                    d.diameter.map_or(String::new(), |v| match c.units {
                        crate::gcode::ProgramUnits::Mm => format!(", Ø{}", fmt_num(v)),
                        crate::gcode::ProgramUnits::Inch => format!(", {}", lengths(c).word("Ø", v)),
                    }),
                    d.cycle.bottom.map_or(String::new(), |z| format!(", bottom {}", along(&d.cycle, z)))
                );
            }
            None => {
                let _ = writeln!(s, "no drilling cycle at this position before it");
            }
        }
        let _ = writeln!(s, "    check                value        min        max   off");
        for k in &h.checks {
            // In an inch program, its lengths and feeds in inches (the feed per minute to 0.1 in/min).
            let (scale, prec, unit) = match tap_inch_unit(c, k.unit) {
                Some((u, p)) => (1.0 / crate::MM_PER_INCH, p, u),
                None => (1.0, 4, k.unit),
            };
            let num = |v: Option<f64>| v.map_or("—".to_string(), |v| format!("{:.prec$}", v * scale));
            let off = if k.ok {
                String::new()
            } else if k.feature == TapFeature::Spindle {
                "wrong".to_string()
            } else {
                tap_off(c, k)
            };
            let _ = writeln!(
                s,
                "  {} {:<16} {:>10} {:>10} {:>10}   {off}  {}{}",
                if k.ok { "✓" } else { "✗" },
                feature_name(k.feature),
                num(k.value),
                num(k.min),
                num(k.max),
                if unit.is_empty() { String::new() } else { format!("{unit}; ") },
                k.note
            );
        }
        match (&h.thread_percent, h.tap.forming) {
            (Some(t), false) => {
                let _ = writeln!(
                    s,
                    "thread: {}; shops' band for a cutting tap {}–{} % (a named default)",
                    super::thread_percent_words(t),
                    fmt_num(t.band[0]),
                    fmt_num(t.band[1])
                );
            }
            (Some(t), true) => {
                let _ = writeln!(
                    s,
                    "thread: {} % (the form-tap makers' percent, (D − hole)/(0.0068·P)); their band {}–{} % (a named default){}",
                    fmt_num((t.percent * 10.0).round() / 10.0),
                    fmt_num(t.band[0]),
                    fmt_num(t.band[1]),
                    match h.formed {
                        // In the program's units (an inch program's inches, 0.0001 in).
                        Some(f) => format!(
                            "; formed D1 {}, class D1 {}–{} (cut threads'); 65 % is a {} hole",
                            f.minor_diameter.map_or("— (overfilled)".to_string(), |d| lengths(c).number(d)),
                            h.tap.minor_diameter.min.map_or("—".to_string(), |v| lengths(c).number(v)),
                            h.tap.minor_diameter.max.map_or("—".to_string(), |v| lengths(c).number(v)),
                            lengths(c).word("Ø", f.hole_for_65_percent)
                        ),
                        None => String::new(),
                    }
                );
            }
            (None, _) => {}
        }
        if let Some(t) = &h.torque {
            let _ = writeln!(
                s,
                "torque: {} N·m{}{} (the tap maker's equation: {}, kc {} N/mm²; {} tap, K {} for a {} pitch)",
                fmt_num((t.newton_metres * 100.0).round() / 100.0),
                // An inch program's shop reads torque in lbf·in (1 N·m = 8.850746 lbf·in).
                if lengths(c).inch() {
                    format!(" ({} lbf·in)", fmt_num((t.newton_metres * LBF_IN_PER_NM * 10.0).round() / 10.0))
                } else {
                    String::new()
                },
                t.power_kw.map_or(String::new(), |p| format!(
                    ", {} kW at the spindle",
                    fmt_num((p * 1000.0).round() / 1000.0)
                )),
                t.material,
                fmt_num(t.kc),
                t.tap_kind.name(),
                fmt_num(t.k),
                if t.coarse { "coarse" } else { "fine" }
            );
            if t.spindle_torque_nm.is_some() || t.spindle_power_kw.is_some() {
                let given: Vec<String> = [
                    t.spindle_torque_nm.map(|v| format!("{} N·m", fmt_num(v))),
                    t.spindle_power_kw.map(|v| format!("{} kW", fmt_num(v))),
                ]
                .into_iter()
                .flatten()
                .collect();
                let _ = writeln!(
                    s,
                    "spindle: {} ({})",
                    given.join(", "),
                    if t.exceeds_spindle { "EXCEEDED: see the warning" } else { "within" }
                );
            }
        }
        if let Some(line) = passing_drill_line(h) {
            let _ = writeln!(s, "{line}");
        }
        let _ = writeln!(
            s,
            "verdict: {}",
            if h.pass {
                "PASS".to_string()
            } else {
                let failed: Vec<&str> =
                    h.checks.iter().filter(|k| !k.ok).map(|k| feature_name(k.feature)).collect();
                format!("FAIL ({})", failed.join(", "))
            }
        );
        for n in &h.notes {
            let _ = writeln!(s, "note: {}", n.marked());
        }
    }
    s
}

/// Most tapped holes drawn side by side; the rest are counted under the picture.
const TAP_PANELS: usize = 4;

/// `threadcheck tap --svg`: each tapped hole's axial section, hole axis up, true to scale (a
/// scale bar under the holes): the part in grey, the hole in white (the tap's thread, its
/// chamfer, the plain bore and the drill's point), D1's limits dashed blue, the drill's diameter
/// dimensioned across the plain bore (red when out of D1), the tap's and the drill's bottoms,
/// the checks with their limits, and the drill that would pass.
pub fn tap_svg(r: &crate::analysis::tap::TapReport) -> String {
    tap_document(r).0.to_string()
}

/// The tap picture as a document with its width and height, for a program's picture to stack.
pub(crate) fn tap_document(r: &crate::analysis::tap::TapReport) -> (Document, f64, f64) {
    use super::kit::text;
    use crate::ground::fmt::fmt_num;
    let shown: Vec<_> = r.holes.iter().take(TAP_PANELS).collect();
    let panel_w = 300.0;
    let w = (40.0 + panel_w * shown.len().max(1) as f64).max(760.0);
    let (box_h, box_w) = (420.0, panel_w - 120.0);
    // One scale for every panel: the deepest hole's height and the widest drill fit.
    let span = |hole: &crate::analysis::tap::TappedHole| {
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
    let frame = Frame { panel_w, box_w, s, wide, y0, text_top };
    let mut text_bottom = text_top;
    let mut holes = Vec::new();
    let verdict = if r.pass {
        "IN TOLERANCE".to_string()
    } else {
        let bad = r.holes.iter().filter(|h| !h.pass).count();
        format!("OUT OF TOLERANCE: {bad} of {} tapping cycles", r.holes.len())
    };
    for (k, hole) in shown.iter().enumerate() {
        let (g, bottom) = hole_panel(r, k, hole, frame);
        text_bottom = text_bottom.max(bottom);
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
    // The scale bar: one scale for every hole, a round length of the program's unit (1, 2 or 5
    // × 10ⁿ mm or in); none when no hole was drawn (nothing to scale).
    if shown.iter().any(|h| !h.wall.is_empty()) {
        let inch = shown.iter().all(|h| h.cycle.units == crate::gcode::ProgramUnits::Inch);
        let (per, unit) = if inch { (crate::MM_PER_INCH, "in") } else { (1.0, "mm") };
        let bar = scale_bar_mm(s * per, 80.0);
        let (bx, by) = (20.0, h - 40.0);
        doc = doc
            .add(
                Line::new()
                    .set("id", "scale-bar")
                    .set("data-mm", bar * per)
                    .set("x1", bx)
                    .set("x2", format!("{:.3}", bx + bar * per * s))
                    .set("y1", by)
                    .set("y2", by)
                    .set("stroke", "black")
                    .set("stroke-width", 2),
            )
            .add(text(bx + bar * per * s + 8.0, by + 4.0, 11.0, format!("{} {unit}", fmt_num(bar))));
    }
    let mut foot =
        String::from("D1 min and max of the tap's class dashed blue; the drill's point drawn at 118°");
    if r.holes.len() > shown.len() {
        foot = format!("{foot}; {} more tapping cycles in the text and JSON", r.holes.len() - shown.len());
    }
    doc = doc.add(text(20.0, h - 14.0, 11.0, foot).set("fill", "#555"));
    (doc, w, h)
}

/// Where a tap picture's panels stand: one scale for every panel, the holes' top and the text's.
#[derive(Clone, Copy)]
struct Frame {
    panel_w: f64,
    box_w: f64,
    /// Pixels per mm.
    s: f64,
    /// The widest hole's diameter, mm.
    wide: f64,
    y0: f64,
    text_top: f64,
}

/// One tapped hole's panel: its heading, its section and the lines under it; and where they end.
fn hole_panel(
    r: &crate::analysis::tap::TapReport,
    k: usize,
    hole: &crate::analysis::tap::TappedHole,
    frame: Frame,
) -> (Group, f64) {
    use super::kit::text;
    use crate::analysis::tap::TapFeature;
    let Frame { panel_w, box_w, y0, text_top, .. } = frame;
    let x0 = 20.0 + panel_w * k as f64;
    let cx = x0 + 0.5 * box_w + 10.0;
    let c = &hole.cycle;
    let mut g = Group::new().set("id", format!("hole-{k}"));
    g = g.add(
        text(
            x0,
            80.0,
            12.0,
            format!(
                "{} line {}{}{}",
                c.code,
                line_of(c),
                c.tool.map_or(String::new(), |t| format!(", T{t}")),
                match (c.x, c.y, c.radial) {
                    (_, _, Some(r)) => format!(" at Z{} C{}", word(c, r.z), micron(r.c_deg)),
                    (Some(x), Some(y), None) => {
                        format!(" at X{} Y{}{}", word(c, x), word(c, y), in_offset(c))
                    }
                    _ => String::new(),
                }
            ),
        )
        .set("font-weight", "bold"),
    );
    g = g.add(text(x0, 96.0, 12.0, format!("tap {}", hole.tap.designation)));
    let drill_check = hole.checks.iter().find(|k| k.feature == TapFeature::DrillDiameter);
    let drill_ok = drill_check.is_none_or(|k| k.ok);
    if hole.wall.is_empty() {
        g = g.add(text(x0, y0 + 20.0, 12.0, "the drill's diameter or a bottom"));
        g = g.add(text(x0, y0 + 36.0, 12.0, "is not known: not drawn"));
    } else {
        g = hole_section(g, r, k, hole, frame, cx, drill_ok);
    }
    panel_lines(g, k, hole, (x0, text_top), drill_ok)
}

/// A tapped hole's axial section, true to scale: the stock, the hole's wall, D1's limits, the
/// bottoms, the drill's diameter dimensioned.
fn hole_section(
    mut g: Group,
    r: &crate::analysis::tap::TapReport,
    k: usize,
    hole: &crate::analysis::tap::TappedHole,
    frame: Frame,
    cx: f64,
    drill_ok: bool,
) -> Group {
    use super::kit::text;
    let Frame { s, wide, y0, .. } = frame;
    let c = &hole.cycle;
    let d1 = &hole.tap.minor_diameter;
    let top = hole.wall.first().map_or(0.0, |p| p.z);
    let bottom = hole.wall.last().map_or(0.0, |p| p.z);
    let y = |z: f64| y0 + (top - z) * s;
    let x = |r: f64| cx + r * s;
    let half_w = 0.8 * wide * s;
    // The stock: down to its bottom face when known (a through hole opens there).
    // The stock's bottom face is a Z: a radial hole's axis does not meet it.
    let stock_end = r.stock_bottom.filter(|sb| c.radial.is_none() && *sb < top && *sb > bottom - 12.0 / s);
    let stock_h = stock_end.map_or(y(bottom) - y0 + 12.0, |sb| y(sb) - y0);
    g = g.add(
        Rectangle::new()
            .set("id", format!("hole-{k}-stock"))
            .set("x", format!("{:.2}", cx - half_w))
            .set("y", format!("{y0:.2}"))
            .set("width", format!("{:.2}", 2.0 * half_w))
            .set("height", format!("{stock_h:.2}"))
            .set("fill", "#b8c7d9"),
    );
    let mut pts: Vec<String> = hole.wall.iter().map(|p| format!("{:.2},{:.2}", x(p.r), y(p.z))).collect();
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
    // The stock's bottom on the same height as the tap's (or near it, under a label's
    // height) is said in the tap's label, so the two never overlap.
    let stock_with_tap = stock_end.is_some_and(|sb| c.bottom.is_some_and(|tz| (y(tz) - y(sb)).abs() < 12.0));
    if let Some(tz) = c.bottom {
        let label = if stock_with_tap { "tap = stock" } else { "tap" };
        g = mark(g, tz, "#333", format!("{label} {}", along(c, tz)));
        if let Some(f) = hole.tap.full_thread_z {
            g = mark(g, f, "#777", format!("full {}", along(c, f)));
        }
    }
    if let Some(db) = hole.drill.as_ref().and_then(|d| d.cycle.bottom) {
        g = mark(g, db, "#a35a00", format!("drill {}", along(c, db)));
    }
    if let Some(sb) = stock_end.filter(|_| !stock_with_tap) {
        g = mark(g, sb, "#2b6e2b", format!("stock Z{}", word(c, sb)));
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
                text(cx, yd - 5.0, 11.0, format!("Ø{}", word(c, dia)))
                    .set("text-anchor", "middle")
                    .set("fill", colour)
                    .set("font-weight", "bold"),
            );
    }
    g = g.add(text(cx + half_w + 8.0, y0 + 10.0, 11.0, format!("top {}", along(c, top))).set("fill", "#555"));
    g
}

/// The lines under a hole's section: D1, the checks with their limits, % of thread and torque,
/// a drill that passes; and where they end.
fn panel_lines(
    mut g: Group,
    k: usize,
    hole: &crate::analysis::tap::TappedHole,
    (x0, text_top): (f64, f64),
    drill_ok: bool,
) -> (Group, f64) {
    use super::kit::text;
    use crate::ground::fmt::fmt_num;
    let c = &hole.cycle;
    let d1 = &hole.tap.minor_diameter;
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
        match hole.formed.and_then(|f| f.minor_diameter) {
            Some(formed) => format!(
                "D1 formed {}; D1 of {} (cut threads'): {}",
                match c.units {
                    crate::gcode::ProgramUnits::Mm => format!("{} mm", fmt_num((formed * 1e4).round() / 1e4)),
                    crate::gcode::ProgramUnits::Inch => lengths(c).both(formed),
                },
                hole.tap.designation,
                d1_limits(c, d1.min, d1.max)
            ),
            None => format!("D1 of {}: {}", hole.tap.designation, d1_limits(c, d1.min, d1.max)),
        },
    );
    ty += 4.0;
    for ck in &hole.checks {
        let word = crate::report::tap::feature_name(ck.feature);
        let inch = tap_inch_unit(c, ck.unit);
        let n = |v: f64| match inch {
            Some((_, prec)) => format!("{:.prec$}", v / crate::MM_PER_INCH),
            None => fmt_num((v * 1e4).round() / 1e4),
        };
        let shown_unit = inch.map_or(ck.unit, |(u, _)| u);
        let val = ck.value.map_or(String::new(), |v| format!(" {}", n(v)));
        let unit = if ck.value.is_some() && !shown_unit.is_empty() {
            format!(" {shown_unit}")
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
        let m = |v: f64| if inch.is_some() { n(v) } else { fmt_num(v) };
        let range = |v: f64| if inch.is_some() { n(v) } else { fmt_limit(v) };
        let lim = if ck.min == ck.max {
            ck.min.map_or(String::new(), |v| format!("must be {}", m(v)))
        } else {
            match (ck.min, ck.max) {
                (Some(a), Some(b)) => format!("limits {} – {}", range(a), range(b)),
                (Some(a), None) => format!("at least {}", m(a)),
                (None, Some(b)) => format!("at most {}", m(b)),
                (None, None) => String::new(),
            }
        };
        let off = if ck.ok || ck.value.is_none() { String::new() } else { format!(", {}", tap_off(c, ck)) };
        let lim = if lim.is_empty() || shown_unit.is_empty() { lim } else { format!("{lim} {shown_unit}") };
        if !lim.is_empty() || !off.is_empty() {
            g = line(g, &mut ty, 10.0, if ck.ok { "#555" } else { FAIL }, false, format!("    {lim}{off}"));
        }
    }
    // How much thread the drill leaves, and the torque the tap needs (issue 64).
    if hole.thread_percent.is_some() || hole.torque.is_some() {
        ty += 4.0;
    }
    if let Some(t) = &hole.thread_percent {
        g = line(
            g,
            &mut ty,
            11.0,
            "#333",
            false,
            format!(
                "thread {} % (shops' band {}–{} %)",
                fmt_num((t.percent * 10.0).round() / 10.0),
                fmt_num(t.band[0]),
                fmt_num(t.band[1])
            ),
        );
    }
    if let Some(t) = &hole.torque {
        let spindle = [
            t.spindle_torque_nm.map(|v| format!("{} N·m", fmt_num(v))),
            t.spindle_power_kw.map(|v| format!("{} kW", fmt_num(v))),
        ]
        .into_iter()
        .flatten()
        .collect::<Vec<_>>();
        let against = if spindle.is_empty() {
            String::new()
        } else {
            format!("; spindle {}{}", spindle.join(", "), if t.exceeds_spindle { ": EXCEEDED" } else { "" })
        };
        g = line(
            g,
            &mut ty,
            11.0,
            if t.exceeds_spindle { FAIL } else { "#333" },
            t.exceeds_spindle,
            format!(
                "torque {} N·m{}{against}",
                fmt_num((t.newton_metres * 100.0).round() / 100.0),
                t.power_kw
                    .map_or(String::new(), |p| format!(", {} kW", fmt_num((p * 1000.0).round() / 1000.0)))
            ),
        );
    }
    let drill_unknown = hole.drill.as_ref().is_none_or(|d| d.diameter.is_none());
    if let Some(pd) = hole.drill_that_passes.as_ref() {
        ty += 6.0;
        let window = if hole.tap.forming { "the form tap's hole" } else { "D1" };
        let head = if drill_ok && !drill_unknown {
            format!("the drill for {window}")
        } else {
            "a drill that passes".to_string()
        };
        let (what, why) = match (&pd.name, pd.diameter, pd.source) {
            (Some(name), Some(dia), Some(src)) => (
                if src == crate::standards::drills::DrillSource::InchGauge {
                    format!("{head}: {name} ({:.4} in)", dia / crate::MM_PER_INCH)
                } else {
                    format!("{head}: Ø{name} mm")
                },
                format!(
                    "{}; {window}'s middle {:.3}",
                    crate::report::tap::drill_source_words(src),
                    pd.middle
                ),
            ),
            _ => (
                format!("{head}: Ø{:.3} mm", pd.middle),
                format!("{window}'s middle; no stocked drill lies within it"),
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
    (g, ty)
}

/// `threadcheck tap --html`: one self-contained page: the verdict, the holes' sections, and per
/// tapping cycle its tap, its drill, its checks and its notes.
pub fn tap_html(r: &crate::analysis::tap::TapReport) -> String {
    use crate::ground::fmt::fmt_num;
    let mut s = String::new();
    let (cls, words) = if r.pass { ("ok", "IN TOLERANCE") } else { ("out", "OUT OF TOLERANCE") };
    let _ = writeln!(s, "<h1>{}: tapped holes</h1>", esc(&r.program));
    let _ = writeln!(s, "<p class=\"verdict {cls}\">{words}</p>");
    let _ = writeln!(
        s,
        "<p>{} tapping cycles, {} drilling cycles, read as {}</p>",
        r.holes.len(),
        r.drills,
        esc(r.dialect.name())
    );
    let _ = writeln!(s, "<div class=\"pic\">{}</div>", tap_svg(r));
    for h in &r.holes {
        let c = &h.cycle;
        let _ = writeln!(
            s,
            "<h2>{} at line {}{}{}: tap {}</h2>",
            esc(&c.code),
            esc(&line_of(c)),
            place(c),
            c.tool.map_or(String::new(), |t| format!(", T{t}")),
            esc(&h.tap.designation)
        );
        let drill = match &h.drill {
            Some(d) => format!(
                "drilled by {} at line {}{}{}",
                d.cycle.code,
                line_of(&d.cycle),
                d.diameter.map_or(String::new(), |v| format!(", Ø{}", fmt_num(v))),
                d.cycle.bottom.map_or(String::new(), |z| format!(", bottom {}", along(&d.cycle, z)))
            ),
            None => "no drilling cycle at this position before it".into(),
        };
        let _ = writeln!(s, "<p>{}</p>", esc(&drill));
        s.push_str("<table><tr><th>check</th><th>value</th><th>min</th><th>max</th><th>deviation</th><th>ok</th><th>note</th></tr>\n");
        for k in &h.checks {
            let num = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v:.4}"));
            let dev = if k.ok {
                String::new()
            } else if k.unit == "mm/min" {
                format!("{:+.1} mm/min", k.deviation)
            } else if k.unit.is_empty() {
                "wrong".into()
            } else {
                format!("{:+.1} µm", k.deviation)
            };
            let (cls, word) = if k.ok { ("ok", "ok") } else { ("out", "OUT") };
            let _ = writeln!(
                s,
                "<tr><td>{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"{cls}\">{word}</td><td>{}</td></tr>",
                esc(crate::report::tap::feature_name(k.feature)),
                num(k.value),
                num(k.min),
                num(k.max),
                esc(&dev),
                esc(&k.note)
            );
        }
        s.push_str("</table>\n");
        if let Some(line) = crate::report::tap::passing_drill_line(h) {
            let _ = writeln!(s, "<p class=\"next\">{}</p>", esc(&line));
        }
        for n in &h.notes {
            let _ = writeln!(s, "<p class=\"form\">{}</p>", esc(&n.marked().to_string()));
        }
    }
    for n in &r.notes {
        let _ = writeln!(s, "<p class=\"form\">{}</p>", esc(&n.marked().to_string()));
    }
    page(&format!("threadcheck: {} tapped", r.program), &s)
}
