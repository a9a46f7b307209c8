//! The thread-milling check's text (its JSON is the report itself).

use crate::analysis::threadmill::{Cutter, Helix, ThreadMillReport};
use crate::ground::fmt::fmt_num;
use crate::report::MeasuredReport;
use serde::Serialize;
use std::fmt::Write as _;

/// The cutter's kind in words: `single-form`, or `multi-form (8 rows 1.5 mm apart)`.
pub(crate) fn cutter_kind(c: &Cutter) -> String {
    if c.rows <= 1 {
        "single-form".into()
    } else {
        format!("multi-form ({} rows {} mm apart)", c.rows, fmt_num(c.row_pitch))
    }
}

/// The text `threadcheck thread-mill` prints.
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
            if j - i == 1 { format!("line {}", h.line) } else { format!("lines {}–{}", h.line, last.line) },
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
    let m = &r.measured;
    let _ = writeln!(
        s,
        "\nas milled: D/d {:.4}, pitch diameter {:.4}, minor {:.4}, flanks {:.3}° / {:.3}°",
        m.major_diameter, m.pitch_diameter, m.minor_diameter, m.flank_angles[0], m.flank_angles[1]
    );
    let t = &r.tooth_profile;
    let _ = writeln!(
        s,
        "the tooth profile alone: pitch diameter {:.4}, flanks {:.3}° / {:.3}°",
        t.pitch_diameter, t.flank_angles[0], t.flank_angles[1]
    );
    let _ = writeln!(
        s,
        "profile distortion: pitch diameter {:+.1} µm, flank angles {:+.3}° / {:+.3}°\n",
        r.distortion_pitch_diameter_um, r.distortion_flank_angles_deg[0], r.distortion_flank_angles_deg[1]
    );
    let _ = writeln!(s, "    check                         value       min       max   deviation");
    for k in &r.checks {
        let num = |v: Option<f64>| v.map_or("—".to_string(), |v| format!("{v:.4}"));
        let _ = writeln!(
            s,
            "  {} {:<28} {:>8.4} {:>9} {:>9}   {}",
            if k.ok { "✓" } else { "✗" },
            k.feature.words(r.kind),
            k.value,
            num(k.min),
            num(k.max),
            if k.ok { String::new() } else { format!("{:+.1} µm", k.deviation_um) }
        );
    }
    let failed: Vec<&str> = r.checks.iter().filter(|k| !k.ok).map(|k| k.feature.words(r.kind)).collect();
    let _ = writeln!(
        s,
        "verdict: {}",
        if r.pass { "PASS".to_string() } else { format!("FAIL ({})", failed.join(", ")) }
    );
    for n in &r.notes {
        let _ = writeln!(s, "note: {n}");
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
    /// `internal` or `external`.
    pub kind: crate::standards::ThreadKind,
    /// The cutter.
    pub cutter: Cutter,
    /// The cutter's diameter over the thread's.
    pub cutter_ratio: f64,
    /// The helices.
    pub helices: &'a [Helix],
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
    pub notes: &'a [String],
}

impl<'a> ThreadMillJson<'a> {
    /// The JSON view of a report.
    pub fn of(r: &'a ThreadMillReport) -> Self {
        ThreadMillJson {
            program: &r.program,
            designation: &r.designation,
            kind: r.kind,
            cutter: r.cutter,
            cutter_ratio: r.cutter_ratio,
            helices: &r.helices,
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
