//! Self-contained HTML reports (`verify --html`, `compare --html`): one file that opens offline,
//! with the SVG inline, the check table, the pass table with its source lines, the measured
//! extras, the notes and the stated assumptions. No script, no outside resource; every piece
//! of user text (designations, program names, notes) is escaped.

use crate::analysis::compare::Comparison;
use crate::analysis::verify::{OperationResult, ProgramVerification, Verification};
use crate::report::opt;
use crate::standards::ThreadKind;
use std::fmt::Write as _;

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

const STYLE: &str = "body{font-family:sans-serif;margin:24px;color:#1d1d1d;max-width:1160px}\
h1{font-size:22px}h2{font-size:18px;margin-top:28px}h3{font-size:15px}\
table{border-collapse:collapse;margin:8px 0 16px}th,td{border:1px solid #ccc;padding:3px 8px;font-size:13px}\
th{background:#eef1f5;text-align:left}td.n{text-align:right;font-variant-numeric:tabular-nums}\
.ok{color:#1d7a36}.out{color:#c62828;font-weight:bold}.form{color:#8a6d00}\
.verdict{font-size:18px;font-weight:bold}.pic{overflow-x:auto}.pic svg{max-width:100%;height:auto}\
ul.notes li{font-size:13px;margin:2px 0}";

pub(crate) fn page(title: &str, body: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n{body}</body>\n</html>\n",
        esc(title)
    )
}

/// The sections of one verification: verdict, picture, checks, passes, extras, notes.
fn verification_body(v: &Verification, svg: &str, level: u8) -> String {
    let h = |n: u8| format!("h{}", (level + n).min(6));
    let mut s = String::new();
    let (cls, words) = if v.pass { ("ok", "IN TOLERANCE") } else { ("out", "OUT OF TOLERANCE") };
    let gauge = if v.gauge_only { " (gauge-only: form checks are not counted)" } else { "" };
    let _ = writeln!(s, "<p class=\"verdict {cls}\">{words}{}</p>", esc(gauge));
    let stock = if v.kind == ThreadKind::External { "blank" } else { "bore" };
    let inch = |mm: f64| match v.units {
        crate::analysis::verify::Units::Mm => String::new(),
        crate::analysis::verify::Units::Inch => format!(" ({:.5} in)", mm / 25.4),
    };
    let _ = writeln!(
        s,
        "<p>{} {}, class {} · insert {} · {} passes · {stock} Ø{:.3} mm{} · last pass X{:.4}{}{}</p>",
        esc(&v.designation.text),
        v.kind.name(),
        esc(&v.limits.class),
        esc(&v.insert.name),
        v.passes.len(),
        v.blank_diameter,
        inch(v.blank_diameter),
        v.final_x,
        inch(v.final_x),
        v.program.as_ref().map_or(String::new(), |p| format!(" · program {}", esc(&p.to_string())))
    );
    if let Some(x) = v.suggested_final_x {
        if !v.pass {
            match &v.correction {
                Some(c) => {
                    let _ = writeln!(
                        s,
                        "<p>For the middle of the pitch-diameter tolerance: <b>{}</b> (the last pass at X{x:.4} mm on the diameter).</p>",
                        esc(&super::correction_text(c))
                    );
                }
                None => {
                    let _ = writeln!(s, "<p>For the middle of the pitch-diameter tolerance, program the last pass at <b>X{x:.4}</b>{}.</p>", inch(x));
                }
            }
        }
    }
    for hint in &v.hints {
        let _ = writeln!(s, "<p class=\"form\">Hint: {}</p>", esc(&super::hint_text(hint)));
    }
    let _ = writeln!(s, "<div class=\"pic\">{svg}</div>");
    let inch = v.units == crate::analysis::verify::Units::Inch;
    let _ = writeln!(s, "<{0}>Checks</{0}>", h(0));
    s.push_str(if inch {
        "<table><tr><th>feature</th><th>value</th><th>min</th><th>max</th><th>value, in</th><th>deviation</th><th>ok</th><th>note</th></tr>\n"
    } else {
        "<table><tr><th>feature</th><th>value</th><th>min</th><th>max</th><th>deviation</th><th>ok</th><th>note</th></tr>\n"
    });
    for c in &v.checks {
        let counts = c.kind.counts(v.gauge_only);
        let cells = super::check_cells(c);
        let (cls, word) = match (c.ok, counts) {
            (true, _) => ("ok", "ok"),
            (false, true) => ("out", "OUT"),
            (false, false) => ("form", "out (not counted)"),
        };
        // Lengths in inches beside the mm, with --units inch (or an inch thread).
        let in_cell = match (inch, c.feature.unit()) {
            (true, crate::CheckUnit::Mm) => format!("<td class=\"n\">{:.5}</td>", c.value / 25.4),
            (true, _) => "<td></td>".to_string(),
            (false, _) => String::new(),
        };
        s.push_str(&check_row(c, v.kind, &cells, &in_cell, cls, word));
    }
    s.push_str("</table>\n");
    let _ = writeln!(s, "<{0}>Passes</{0}>", h(0));
    s.push_str("<table><tr><th>pass</th><th>start</th><th>X mm</th><th>Z start mm</th><th>Z end mm</th><th>radial depth mm</th><th>chip area mm²</th><th>line</th></tr>\n");
    let surface = 0.5 * v.blank_diameter;
    for (i, p) in v.passes.iter().enumerate() {
        let _ = writeln!(
            s,
            "<tr><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{:.4}</td><td class=\"n\">{:.4}</td><td class=\"n\">{:.4}</td><td class=\"n\">{:.4}</td><td class=\"n\">{}</td><td class=\"n\">{}</td></tr>",
            p.index,
            p.start + 1,
            p.x_end,
            p.z_start,
            p.z_end,
            (0.5 * p.x_end - surface).abs(),
            v.metrics.get(i).map_or("—".to_string(), |m| format!("{:.4}", m.chip_area)),
            p.source_line.map_or("—".to_string(), |l| l.to_string())
        );
    }
    s.push_str("</table>\n");
    let m = &v.measurement;
    let _ = writeln!(s, "<{0}>Measured</{0}>", h(0));
    s.push_str("<table>\n");
    let mut row = |k: &str, val: String| {
        let _ = writeln!(s, "<tr><th>{}</th><td class=\"n\">{}</td></tr>", esc(k), esc(&val));
    };
    row("major diameter, mm", format!("{:.4}", m.major_diameter));
    row("pitch diameter, mm", format!("{:.4}", m.pitch_diameter));
    row("minor diameter, mm", format!("{:.4}", m.minor_diameter));
    row(
        "flank half-angles, low-z / high-z, °",
        format!("{:.3} / {:.3}", m.flank_angles[0], m.flank_angles[1]),
    );
    row("root radius, mm", opt(m.root_radius, 4));
    row("thread depth, mm", format!("{:.4}", m.thread_depth));
    row("crest width, mm", format!("{:.4}", m.crest_width));
    match m.three_wire {
        Some(w) => row("three wires: wire Ø / M over wires, mm", format!("{:.4} / {:.4}", w.wire, w.m)),
        None => row("three wires", "—".into()),
    }
    row("GO gauge clearance (maximum material), mm", opt(m.max_material_clearance, 4));
    row("helix angle at the pitch diameter, °", format!("{:.3}", v.helix_angle));
    s.push_str("</table>\n");
    if !v.notes.is_empty() {
        let _ = writeln!(s, "<{0}>Notes and assumptions</{0}>\n<ul class=\"notes\">", h(0));
        for n in &v.notes {
            let _ = writeln!(s, "<li>{}</li>", esc(&n.to_string()));
        }
        s.push_str("</ul>\n");
    }
    s
}

/// The HTML report of one verification.
pub fn verify_html(v: &Verification) -> String {
    let title = format!("threadcheck: {} {}", v.designation.text, v.kind.name());
    let body =
        format!("<h1>{}</h1>\n{}", esc(&title), verification_body(v, &crate::report::svg::verify_svg(v), 2));
    page(&title, &body)
}

/// The HTML report of a program: one section per operation.
pub fn program_html(pv: &ProgramVerification) -> String {
    let title = format!("threadcheck: {}", pv.program);
    let mut body = format!("<h1>{}</h1>\n", esc(&title));
    let (cls, words) = if pv.pass() { ("ok", "IN TOLERANCE") } else { ("out", "OUT OF TOLERANCE") };
    let _ = writeln!(
        body,
        "<p class=\"verdict {cls}\">{words}: {} threading operation{}</p>",
        pv.operations.len(),
        if pv.operations.len() == 1 { "" } else { "s" }
    );
    if !pv.notes.is_empty() {
        body.push_str("<ul class=\"notes\">\n");
        for n in &pv.notes {
            let _ = writeln!(body, "<li>{}</li>", esc(&n.to_string()));
        }
        body.push_str("</ul>\n");
    }
    for o in &pv.operations {
        let op = &o.operation;
        let _ = writeln!(
            body,
            "<h2>Operation {} of {}: {} at line {}{} — {}</h2>",
            op.index,
            pv.operations_in_program,
            esc(&op.cycle),
            op.source_line,
            op.tool.map_or(String::new(), |t| format!(", tool T{t}")),
            esc(&o.designation)
        );
        for n in &op.notes {
            let _ = writeln!(body, "<p class=\"form\">{}</p>", esc(&n.to_string()));
        }
        match &o.result {
            OperationResult::Verified(v) => {
                body.push_str(&verification_body(v, &crate::report::svg::verify_svg(v), 3))
            }
            OperationResult::NoCut { reason, suggested_final_x } => {
                let _ = writeln!(body, "<p class=\"verdict out\">OUT OF TOLERANCE: {}</p>", esc(reason));
                if let Some(next) = crate::report::no_cut_next(*suggested_final_x) {
                    let _ = writeln!(body, "<p class=\"next\">next: {}</p>", esc(&next));
                }
            }
        }
    }
    page(&title, &body)
}

/// The HTML report of a comparison: the table of strategies and each one's picture.
pub fn compare_html(c: &Comparison) -> String {
    let Some((_, first)) = c.runs.first() else {
        return page("threadcheck: comparison", "<p>no strategy</p>\n");
    };
    let title = format!("threadcheck: infeed comparison, {} {}", first.designation.text, first.kind.name());
    let mut body = format!("<h1>{}</h1>\n", esc(&title));
    let _ = writeln!(
        body,
        "<p>Every strategy ends at X{:.4} with insert {}.</p>",
        c.final_x,
        esc(&first.insert.name)
    );
    if let Some(r) = &c.recommended {
        let _ = writeln!(
            body,
            "<p class=\"verdict\">{}</p>",
            esc(&crate::report::compare::recommendation_text(r))
        );
    }
    body.push_str("<table><tr><th>infeed</th><th>schedule</th><th>passes</th><th>first chip mm²</th><th>largest chip mm²</th><th>last chip mm²</th><th>largest/smallest</th><th>two-flank passes</th><th>chip behind the tip</th><th>d2 mm</th><th>minor mm</th><th>flanks °</th><th>verdict</th></tr>\n");
    for (m, v) in &c.runs {
        let why: Vec<&str> = m.failed.iter().map(|f| f.words(v.kind)).collect();
        let _ = writeln!(
            body,
            "<tr><td>{}</td><td>{}</td><td class=\"n\">{}</td><td class=\"n\">{:.4}</td><td class=\"n\">{:.4}</td><td class=\"n\">{:.4}</td><td class=\"n\">{:.1}</td><td class=\"n\">{}</td><td class=\"n\">{:.0}%</td><td class=\"n\">{:.4}</td><td class=\"n\">{:.4}</td><td class=\"n\">{:.2} / {:.2}</td><td class=\"{}\">{}</td></tr>",
            esc(&m.infeed),
            esc(&m.schedule),
            m.passes,
            m.chip_first,
            m.chip_max,
            m.chip_last,
            m.chip_spread,
            m.two_flank_passes,
            100.0 * m.trailing_share,
            m.pitch_diameter,
            m.minor_diameter,
            m.flank_angles[0],
            m.flank_angles[1],
            if m.pass { "ok" } else { "out" },
            if m.pass { "in tolerance".to_string() } else { esc(&format!("OUT: {}", why.join(", "))) }
        );
    }
    body.push_str("</table>\n");
    // One picture per infeed: its run with the recommended schedule (else its first).
    let schedule = c.recommended.as_ref().map(|r| r.schedule.as_str());
    let mut shown: Vec<&str> = Vec::new();
    for run in &c.runs {
        if shown.contains(&run.0.infeed.as_str()) {
            continue;
        }
        let mut same = c.runs.iter().filter(|(o, _)| o.infeed == run.0.infeed);
        let (m, v) = same.find(|(o, _)| Some(o.schedule.as_str()) == schedule).unwrap_or(run);
        shown.push(&m.infeed);
        let _ = writeln!(body, "<h2>{} infeed, {}</h2>", esc(&m.infeed), esc(&m.schedule));
        let _ = writeln!(body, "<div class=\"pic\">{}</div>", crate::report::svg::verify_svg(v));
    }
    page(&title, &body)
}

/// The thread-milling page: the verdict, the distortion, the section, the checks, the helices
/// and the notes.
pub fn threadmill_html(r: &crate::analysis::threadmill::ThreadMillReport) -> String {
    let mut s = String::new();
    let (cls, words) = if r.pass { ("ok", "IN TOLERANCE") } else { ("out", "OUT OF TOLERANCE") };
    let _ = writeln!(s, "<h1>{} thread-milled</h1>", esc(&r.designation));
    let _ = writeln!(s, "<p class=\"verdict {cls}\">{words}</p>");
    let _ = writeln!(
        s,
        "<p>{} · Ø{} mm {} cutter, {}° tooth, tip r{} mm ({:.0} % of the diameter) · profile distortion {:+.1} µm on the pitch diameter, flanks {:+.3}° / {:+.3}°</p>",
        esc(&r.program),
        crate::ground::fmt::fmt_num(r.cutter.diameter),
        esc(&crate::report::threadmill::cutter_kind(&r.cutter)),
        crate::ground::fmt::fmt_num(r.cutter.angle_deg),
        crate::ground::fmt::fmt_num(r.cutter.tip_radius),
        100.0 * r.cutter_ratio,
        r.distortion_pitch_diameter_um,
        r.distortion_flank_angles_deg[0],
        r.distortion_flank_angles_deg[1]
    );
    let _ = writeln!(s, "<div class=\"pic\">{}</div>", crate::report::svg::threadmill_svg(r));
    s.push_str("<h2>Checks</h2>\n<table><tr><th>feature</th><th>value</th><th>min</th><th>max</th><th>deviation</th><th>ok</th><th>note</th></tr>\n");
    for c in &r.checks {
        let (cls, word) = if c.ok { ("ok", "ok") } else { ("out", "OUT") };
        s.push_str(&check_row(c, r.kind, &super::check_cells(c), "", cls, word));
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
        let _ = writeln!(s, "<p class=\"form\">{}</p>", esc(n));
    }
    page(&format!("threadcheck: {} thread-milled", r.designation), &s)
}

/// `threadcheck tap --html`: one self-contained page: the verdict, the holes' sections, and per
/// tapping cycle its tap, its drill, its checks and its notes.
pub fn tap_html(r: &crate::analysis::tapping::TapReport) -> String {
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
    let _ = writeln!(s, "<div class=\"pic\">{}</div>", crate::report::svg::tap_svg(r));
    for h in &r.holes {
        let c = &h.cycle;
        let _ = writeln!(
            s,
            "<h2>{} at line {}{}: tap {}</h2>",
            esc(&c.code),
            c.line,
            c.tool.map_or(String::new(), |t| format!(", T{t}")),
            esc(&h.tap.designation)
        );
        let drill = match &h.drill {
            Some(d) => format!(
                "drilled by {} at line {}{}{}",
                d.cycle.code,
                d.cycle.line,
                d.diameter.map_or(String::new(), |v| format!(", Ø{}", fmt_num(v))),
                d.cycle.bottom.map_or(String::new(), |z| format!(", bottom Z{}", fmt_num(z)))
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
                esc(crate::report::tapping::feature_name(k.feature)),
                num(k.value),
                num(k.min),
                num(k.max),
                esc(&dev),
                esc(&k.note)
            );
        }
        s.push_str("</table>\n");
        if let Some(line) = crate::report::tapping::passing_drill_line(h) {
            let _ = writeln!(s, "<p class=\"next\">{}</p>", esc(&line));
        }
        for n in &h.notes {
            let _ = writeln!(s, "<p class=\"form\">{}</p>", esc(n));
        }
    }
    for n in &r.notes {
        let _ = writeln!(s, "<p class=\"form\">{}</p>", esc(&n.to_string()));
    }
    page(&format!("threadcheck: {} tapped", r.program), &s)
}

/// One row of a check table: the feature, value, limits, (the value in inches), deviation, the
/// verdict word and the note.
fn check_row(
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
