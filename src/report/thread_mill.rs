//! The thread-milling check's text (its JSON is the report itself).

use super::kit::*;
use crate::analysis::thread_mill::ThreadMillReport;
use crate::geometry::helix::{Cutter, Helix};
use crate::ground::fmt::fmt_num;
use crate::ground::plane::{rad, Point};
use crate::report::MeasuredReport;
use crate::standards::ThreadKind;
use serde::Serialize;
use std::fmt::Write as _;
use svg::node::element::{Group, Line, Polygon, Polyline, Rectangle};
use svg::Document;

/// The cutter's kind in words: `single-form`, or `multi-form (8 rows 1.5 mm apart)`.
pub(crate) fn cutter_kind(c: &Cutter) -> String {
    if c.rows <= 1 {
        "single-form".into()
    } else {
        format!("multi-form ({} rows {} mm apart)", c.rows, fmt_num(c.row_pitch))
    }
}

/// The text `threadcheck thread-mill` prints.
/// The lines of a run of `n` helices from `first` to `last`: one line a loop runs again is named
/// once with its count (`line 34, 20 times`), never as `lines 34–34`.
fn lines_label(first: usize, last: usize, n: usize) -> String {
    match (first == last, n) {
        (true, 1) => format!("line {first}"),
        (true, n) => format!("line {first}, {n} times"),
        (false, _) => format!("lines {first}–{last}"),
    }
}

pub fn text(r: &ThreadMillReport) -> String {
    let mut s = String::new();
    let c = &r.cutter;
    let _ = writeln!(
        s,
        "{}: {} {} thread-milled by a Ø{} {} cutter ({}°, tip r{}), {:.0} % of the thread's diameter",
        r.program,
        r.designation,
        r.kind.name(),
        fmt_num(c.diameter),
        cutter_kind(c),
        fmt_num(c.angle_deg),
        fmt_num(c.tip_radius),
        100.0 * r.cutter_ratio
    );
    // Consecutive helices of one radius, lead and direction as one line.
    let mut i = 0;
    while i < r.helices.len() {
        let h = &r.helices[i];
        let mut j = i + 1;
        while j < r.helices.len() {
            let g = &r.helices[j];
            if (g.radius - h.radius).abs() > 1e-9 || (g.lead - h.lead).abs() > 1e-9 || g.climb != h.climb {
                break;
            }
            j += 1;
        }
        let last = &r.helices[j - 1];
        let turns: f64 = r.helices[i..j].iter().map(|g| g.sweep_deg.abs() / 360.0).sum();
        let _ = writeln!(
            s,
            "  {}: {} turn{} at radius {:.4}, Z{} to Z{}, lead {:.4} mm/rev, {} milling",
            lines_label(h.line, last.line, j - i),
            fmt_num(turns),
            if (turns - 1.0).abs() < 1e-9 { "" } else { "s" },
            h.radius,
            fmt_num(h.z[0]),
            fmt_num(last.z[1]),
            h.lead.abs(),
            if h.climb { "climb" } else { "conventional" }
        );
        i = j;
    }
    // Each run of helices at one feed: the centre's as written, the edge's it makes.
    let mut k = 0;
    while k < r.feeds.len() {
        let f = &r.feeds[k];
        let mut j = k + 1;
        while j < r.feeds.len()
            && r.feeds[j].centre == f.centre
            && (r.feeds[j].factor - f.factor).abs() < 1e-9
            && r.feeds[j].per_tooth == f.per_tooth
        {
            j += 1;
        }
        let lines = lines_label(f.line, r.feeds[j - 1].line, j - k);
        let per_min = |mm: f64| {
            if f.inch {
                format!("{:.2} in/min ({:.0} mm/min)", mm / 25.4, mm)
            } else {
                format!("{mm:.0} mm/min")
            }
        };
        let tooth = match (f.per_tooth, f.spindle) {
            (Some(fz), Some(sp)) if f.inch => {
                format!("; {:.5} in ({fz:.4} mm) a tooth at S{}", fz / 25.4, crate::ground::fmt::fmt_num(sp))
            }
            (Some(fz), Some(sp)) => format!("; {fz:.4} mm a tooth at S{}", crate::ground::fmt::fmt_num(sp)),
            _ => String::new(),
        };
        let _ = writeln!(
            s,
            "  feed ({lines}): {} at the cutter's centre is {} at its edge (× {:.3}, D/(D {} d)){tooth}",
            per_min(f.centre),
            per_min(f.edge),
            f.factor,
            if r.kind == crate::standards::ThreadKind::Internal { "−" } else { "+" }
        );
        k = j;
    }
    // The thread's sizes in the report's unit (inches for an inch thread, the mm beside them).
    let l = super::Lengths(r.units);
    let m = &r.measured;
    let _ = writeln!(
        s,
        "\nas milled: D/d {}, pitch diameter {}, minor {}, flanks {:.3}° / {:.3}°",
        l.both(m.major_diameter),
        l.both(m.pitch_diameter),
        l.both(m.minor_diameter),
        m.flank_angles[0],
        m.flank_angles[1]
    );
    if let Some(p) = &r.thread_percent {
        let _ = writeln!(
            s,
            "thread from the bore {}: {}",
            l.word("Ø", r.blank_diameter),
            super::thread_percent_words(p)
        );
    }
    let t = &r.tooth_profile;
    let _ = writeln!(
        s,
        "the tooth profile alone: pitch diameter {}, flanks {:.3}° / {:.3}°",
        l.both(t.pitch_diameter),
        t.flank_angles[0],
        t.flank_angles[1]
    );
    let _ = writeln!(
        s,
        "profile distortion: pitch diameter {}, flank angles {:+.3}° / {:+.3}°\n",
        l.deviation(r.distortion_pitch_diameter_um, true),
        r.distortion_flank_angles_deg[0],
        r.distortion_flank_angles_deg[1]
    );
    let _ = writeln!(s, "    check                         value       min       max   deviation");
    for k in &r.checks {
        // Every table's cells: yes/no in words, deviations in the check's own unit.
        let c = super::check_cells(k, super::Lengths(r.units));
        let _ = writeln!(
            s,
            "  {} {:<28} {:>8} {:>9} {:>9}   {}",
            if k.ok { "✓" } else { "✗" },
            k.feature.words(r.kind),
            c.value,
            c.min,
            c.max,
            c.deviation
        );
    }
    let mut failed: Vec<&str> = r.checks.iter().filter(|k| !k.ok).map(|k| k.feature.words(r.kind)).collect();
    for g in &r.after_finish.gouges {
        let _ = writeln!(
            s,
            "  ✗ after the last helix: line {} ({}) cuts the finished thread, its teeth {:.3} mm past the crest",
            g.line, g.code, g.depth
        );
    }
    if !r.after_finish.gouges.is_empty() {
        failed.push("a move after the last helix cuts the thread");
    }
    for c in &r.crossings {
        let _ = writeln!(
            s,
            "  ✗ line {} ({}) crosses the thread's grooves ({} mm per revolution{}), its teeth {:.3} mm past the crest",
            c.line,
            c.code,
            crate::ground::fmt::fmt_num((c.lead * 1e4).round() / 1e4),
            if c.other_hand.is_some() { ", the other hand" } else { "" },
            c.depth
        );
    }
    if !r.crossings.is_empty() {
        failed.push("a helix crosses the thread");
    }
    if let (Some(first), n) = (r.after_finish.compensated.first(), r.after_finish.compensated.len()) {
        let _ = writeln!(
            s,
            "  note: {n} move{} after the last helix from line {first} run under cutter compensation: not judged (the centre is not the programmed path)",
            if n == 1 { "" } else { "s" }
        );
    }
    let _ = writeln!(
        s,
        "verdict: {}",
        if r.pass { "PASS".to_string() } else { format!("FAIL ({})", failed.join(", ")) }
    );
    for n in &r.notes {
        let _ = writeln!(s, "note: {}", n.marked());
    }
    s
}

/// `thread-mill --json` (docs/json.md, schema `command_thread_mill`): the report, its
/// measurements as `verify`'s `measured`, its verdict as a word.
#[derive(Clone, Debug, Serialize)]
pub struct ThreadMillJson<'a> {
    /// The program.
    pub program: &'a str,
    /// The designation.
    pub designation: &'a str,
    /// Where it came from: given, comment or inferred.
    pub designation_from: crate::analysis::naming::DesignationFrom,
    /// The comment's line (the first helix's, when inferred); null when given.
    pub designation_line: Option<usize>,
    /// `internal` or `external`.
    pub kind: crate::standards::ThreadKind,
    /// The cutter.
    pub cutter: Cutter,
    /// The cutter's diameter over the thread's.
    pub cutter_ratio: f64,
    /// The helices.
    pub helices: &'a [Helix],
    /// The feed at the cutter's edge of each helix with a known feed.
    pub feeds: &'a [crate::analysis::thread_mill::HelixFeed],
    /// What the moves after the last helix do to the finished thread: the gouges and the moves
    /// under compensation not judged (issue 63).
    pub after_finish: &'a crate::analysis::gouge::AfterFinish,
    /// An internal thread's percent of thread from its bore.
    pub thread_percent: Option<crate::analysis::percent::ThreadPercent>,
    /// The bore or blank, mm.
    pub blank_diameter: f64,
    /// The milled thread.
    pub measured: MeasuredReport,
    /// The tooth profile alone.
    pub tooth_profile: MeasuredReport,
    /// Milled d2 less the tooth profile's, µm.
    pub distortion_pitch_diameter_um: f64,
    /// The flank angles' change, degrees.
    pub distortion_flank_angles_deg: [f64; 2],
    /// The class's limits.
    pub limits: &'a crate::standards::tolerance::ThreadLimits,
    /// The checks.
    pub checks: &'a [crate::analysis::check::Check],
    /// `pass` or `fail`.
    pub verdict: crate::analysis::check::Verdict,
    /// What was assumed.
    pub notes: &'a [crate::ground::note::Note],
}

impl<'a> ThreadMillJson<'a> {
    /// The JSON view of a report.
    pub fn of(r: &'a ThreadMillReport) -> Self {
        ThreadMillJson {
            program: &r.program,
            designation: &r.designation,
            designation_from: r.named.from,
            designation_line: r.named.line,
            kind: r.kind,
            cutter: r.cutter,
            cutter_ratio: r.cutter_ratio,
            helices: &r.helices,
            feeds: &r.feeds,
            after_finish: &r.after_finish,
            thread_percent: r.thread_percent,
            blank_diameter: r.blank_diameter,
            measured: MeasuredReport::of(&r.measured, None),
            tooth_profile: MeasuredReport::of(&r.tooth_profile, None),
            distortion_pitch_diameter_um: r.distortion_pitch_diameter_um,
            distortion_flank_angles_deg: r.distortion_flank_angles_deg,
            limits: &r.limits,
            checks: &r.checks,
            verdict: crate::analysis::check::Verdict::of(r.pass),
            notes: &r.notes,
        }
    }
}

/// `threadcheck thread-mill --svg`: the milled thread's axial section over four pitches, true
/// to scale with Z (mm) and diameter ticks: the material (grey-blue) the cutter's envelope
/// leaves, the class's tolerance zone over it (green), the basic profile (grey dashed), the
/// tooth profile alone (brown dashed), D1's limits (blue dotted), and the measured D, D2 and D1
/// dimensioned with their values and limits (red with the deviation when out); below it, the
/// helix's widening of the groove (radial µm) against the same Z.
pub fn thread_mill_svg(r: &crate::analysis::thread_mill::ThreadMillReport) -> String {
    thread_mill_document(r).0.to_string()
}

/// The thread-milling picture as a document with its width and height, for a program's picture
/// to stack.
pub(crate) fn thread_mill_document(
    r: &crate::analysis::thread_mill::ThreadMillReport,
) -> (Document, f64, f64) {
    use super::kit::text;
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
    let (mut sec, mut body) = panel(
        &f,
        "section",
        if r.limits.gauge_plane.is_some() {
            "milled section over four pitches, sheared along the cone"
        } else {
            "the milled section over four pitches (axial, true to scale)"
        },
    );
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
    sec = sec.add(body).add(axes(&f, true, r.units));
    let labels = labels_of_dimensions(&items, &r.checks, r.kind, r.units, &f, px0 - 14.0);
    // The legend under the section.
    let ly = f.y0 + f.h + 46.0;
    let legend = legend(ly);
    let (wid, bottom) = widening(r, &f, (px0, pw), ly, (z0, z1));
    let h = bottom + 50.0;
    let mut failed: Vec<&str> = r.checks.iter().filter(|k| !k.ok).map(|k| k.feature.words(r.kind)).collect();
    if !r.after_finish.gouges.is_empty() {
        failed.push("a move after the last helix cuts the thread");
    }
    if !r.crossings.is_empty() {
        failed.push("a helix crosses the thread");
    }
    let verdict =
        if r.pass { "IN TOLERANCE".to_string() } else { format!("OUT OF TOLERANCE: {}", failed.join(", ")) };
    let d2n = if internal { "D2" } else { "d2" };
    // The title and the verdict wrap (never cut): what they take past a line each moves the
    // rest down.
    // 17 px bold ran 8.5 px a character in Chromium (82 in 693 px): 88 fill some 750 of 900.
    let title_lines = wrap(
        &format!(
            "{}: {} thread-milled with a Ø{} {} cutter",
            file_name(&r.program),
            r.designation,
            fmt_num(r.cutter.diameter),
            crate::report::thread_mill::cutter_kind(&r.cutter)
        ),
        88,
    );
    let verdict_lines = wrap(&verdict, 95);
    let extra = 22.0 * (title_lines.len() - 1) as f64 + 20.0 * (verdict_lines.len() - 1) as f64;
    let h = h + extra;
    let mut doc = Document::new().set("viewBox", (0, 0, w, h)).set("width", w).set("height", h);
    doc = doc.add(Rectangle::new().set("width", w).set("height", h).set("fill", "white"));
    let mut y = 30.0;
    for l in title_lines {
        doc = doc.add(text(20.0, y, 17.0, l).set("font-weight", "bold"));
        y += 22.0;
    }
    for l in verdict_lines {
        doc = doc.add(
            text(20.0, y, 15.0, l).set("font-weight", "bold").set("fill", if r.pass { ZONE } else { FAIL }),
        );
        y += 20.0;
    }
    // The distortion and the flanks, wrapped to the picture (an inch report's run longer): at most
    // three lines above the section's caption.
    let l = super::Lengths(r.units);
    let info = [
        format!(
            "{d2n} {} as milled, {} by the tooth profile alone: the helix widens the groove by {}",
            l.both(r.measured.pitch_diameter),
            l.both(r.tooth_profile.pitch_diameter),
            l.deviation(r.distortion_pitch_diameter_um, true)
        ),
        format!(
            "flanks {:.3}° / {:.3}° ({:+.3}° / {:+.3}°); the cutter is {:.0} % of the thread's diameter",
            r.measured.flank_angles[0],
            r.measured.flank_angles[1],
            r.distortion_flank_angles_deg[0],
            r.distortion_flank_angles_deg[1],
            100.0 * r.cutter_ratio
        ),
    ];
    let mut rest = Group::new().set("transform", format!("translate(0,{extra})"));
    let lines: Vec<String> = info.iter().flat_map(|i| wrap(i, 110)).collect();
    let step = if lines.len() > 2 { 18.0 } else { 20.0 };
    for (i, line) in lines.into_iter().enumerate() {
        rest = rest.add(text(20.0, 76.0 + step * i as f64, 13.0, line));
    }
    let rest = rest.add(sec).add(labels).add(legend).add(wid);
    (doc.add(rest), w, h)
}

/// The legend under the thread-milling picture's section, its baseline at `ly`.
fn legend(ly: f64) -> Group {
    use super::kit::text;
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
    legend
}

/// The groove's widening along Z under the section, on its Z scale; and where the panel ends.
fn widening(
    r: &crate::analysis::thread_mill::ThreadMillReport,
    f: &Frame,
    (px0, pw): (f64, f64),
    ly: f64,
    (z0, z1): (f64, f64),
) -> (Group, f64) {
    use super::kit::text;
    // The groove's widening along Z, on the section's own Z scale.
    let widen = &r.widening_um;
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
    wid = wid.add(wbody).add(axes(&fs, false, r.units));
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
    (wid, sy + sh)
}

/// The thread-milling page: the verdict, the distortion, the section, the checks, the helices
/// and the notes.
pub fn thread_mill_html(r: &crate::analysis::thread_mill::ThreadMillReport) -> String {
    let mut s = String::new();
    let (cls, words) = if r.pass { ("ok", "IN TOLERANCE") } else { ("out", "OUT OF TOLERANCE") };
    let _ = writeln!(s, "<h1>{} thread-milled</h1>", esc(&r.designation));
    let _ = writeln!(s, "<p class=\"verdict {cls}\">{words}</p>");
    let _ = writeln!(
        s,
        "<p>{} · Ø{} mm {} cutter, {}° tooth, tip r{} mm ({:.0} % of the diameter) · profile distortion {:+.1} µm on the pitch diameter, flanks {:+.3}° / {:+.3}°</p>",
        esc(&r.program),
        crate::ground::fmt::fmt_num(r.cutter.diameter),
        esc(&crate::report::thread_mill::cutter_kind(&r.cutter)),
        crate::ground::fmt::fmt_num(r.cutter.angle_deg),
        crate::ground::fmt::fmt_num(r.cutter.tip_radius),
        100.0 * r.cutter_ratio,
        r.distortion_pitch_diameter_um,
        r.distortion_flank_angles_deg[0],
        r.distortion_flank_angles_deg[1]
    );
    let _ = writeln!(s, "<div class=\"pic\">{}</div>", thread_mill_svg(r));
    s.push_str("<h2>Checks</h2>\n<table><tr><th>feature</th><th>value</th><th>min</th><th>max</th><th>deviation</th><th>ok</th><th>note</th></tr>\n");
    for c in &r.checks {
        let (cls, word) = if c.ok { ("ok", "ok") } else { ("out", "OUT") };
        s.push_str(&check_row(c, r.kind, &super::check_cells(c, super::Lengths(r.units)), "", cls, word));
    }
    s.push_str("</table>\n<h2>Helices</h2>\n<table><tr><th>line</th><th>radius mm</th><th>Z from</th><th>Z to</th><th>sweep °</th><th>lead mm/rev</th><th>milling</th></tr>\n");
    for h in &r.helices {
        let _ = writeln!(
            s,
            "<tr><td class=\"n\">{}</td><td class=\"n\">{:.4}</td><td class=\"n\">{:.4}</td><td class=\"n\">{:.4}</td><td class=\"n\">{:.1}</td><td class=\"n\">{:.4}</td><td>{}</td></tr>",
            h.line,
            h.radius,
            h.z[0],
            h.z[1],
            h.sweep_deg,
            h.lead.abs(),
            if h.climb { "climb" } else { "conventional" }
        );
    }
    s.push_str("</table>\n");
    for n in &r.notes {
        let _ = writeln!(s, "<p class=\"form\">{}</p>", esc(&n.marked().to_string()));
    }
    page(&format!("threadcheck: {} thread-milled", r.designation), &s)
}
