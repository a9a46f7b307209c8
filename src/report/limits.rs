//! `limits --json`: the basic dimensions and the classes' limits of a designation.

use super::*;
use serde::Serialize;

/// The `basic` object of `limits --json`: the basic sizes, rounded as the tables print them.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct BasicReport {
    /// d = D, mm.
    pub major_diameter: f64,
    /// d2 = D2, mm.
    pub pitch_diameter: f64,
    /// d3, mm.
    pub minor_diameter_external: f64,
    /// D1, mm.
    pub minor_diameter_internal: f64,
    /// H, mm.
    pub fundamental_triangle_height: f64,
}

/// `limits --json` (docs/json.md).
#[derive(Clone, Debug, Serialize)]
pub struct LimitsReport<'a> {
    /// As written.
    pub designation: &'a str,
    /// The form's name.
    pub form: &'static str,
    /// mm.
    pub nominal_diameter: f64,
    /// mm.
    pub pitch: f64,
    /// mm.
    pub lead: f64,
    /// Number of starts.
    pub starts: u32,
    /// `right` or `left`.
    pub hand: &'static str,
    /// Outside the standard series.
    pub nonstandard: bool,
    /// Basic sizes.
    pub basic: BasicReport,
    /// The external thread's limits, when the designation has an external class.
    pub external: Option<&'a crate::standards::tolerance::ThreadLimits>,
    /// The internal thread's limits.
    pub internal: Option<&'a crate::standards::tolerance::ThreadLimits>,
    /// A rolled external thread's blank (`--rolled`, `--blank`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rolled: Option<&'a crate::analysis::rolled::RolledThread>,
}

impl<'a> LimitsReport<'a> {
    /// The report of a designation's limits.
    pub fn new(
        des: &'a crate::standards::Designation,
        external: Option<&'a crate::standards::tolerance::ThreadLimits>,
        internal: Option<&'a crate::standards::tolerance::ThreadLimits>,
    ) -> Self {
        let t = &des.thread;
        let (major_diameter, pitch_diameter, minor_diameter_external, minor_diameter_internal, h) =
            crate::standards::tolerance::basic_rounded(t);
        LimitsReport {
            designation: &des.text,
            form: t.form.name(),
            nominal_diameter: crate::standards::tolerance::named_diameter(t),
            pitch: t.pitch,
            lead: t.lead(),
            starts: t.starts,
            hand: t.hand.name(),
            nonstandard: des.nonstandard,
            basic: BasicReport {
                major_diameter,
                pitch_diameter,
                minor_diameter_external,
                minor_diameter_internal,
                fundamental_triangle_height: h,
            },
            external,
            internal,
            rolled: None,
        }
    }

    /// With a rolled thread's blank.
    pub fn with_rolled(mut self, rolled: Option<&'a crate::analysis::rolled::RolledThread>) -> Self {
        self.rolled = rolled;
        self
    }
}

/// The text `limits` prints: the basic sizes and each class's limits (inches beside the mm for
/// the inch forms).
pub fn text(
    des: &crate::standards::Designation,
    ext: Option<&crate::standards::tolerance::ThreadLimits>,
    int: Option<&crate::standards::tolerance::ThreadLimits>,
) -> String {
    use crate::standards::tolerance::{basic_rounded, Limit};
    use crate::standards::ThreadKind;
    use std::fmt::Write as _;
    let t = &des.thread;
    let (d, d2, d3, d1, h) = basic_rounded(t);
    let mut s = String::new();
    let hand = if t.hand == crate::Hand::Left { "left-hand" } else { "right-hand" };
    let _ = writeln!(
        s,
        "{}  {}, P = {} mm{}, lead {} mm, {} start{}, {}{}",
        des.text,
        t.form.name(),
        crate::standards::tolerance::round_um(t.pitch),
        if t.form.is_inch() {
            format!(" ({} tpi)", crate::standards::tolerance::round_um(25.4 / t.pitch))
        } else {
            String::new()
        },
        crate::standards::tolerance::round_um(t.lead()),
        t.starts,
        if t.starts == 1 { "" } else { "s" },
        hand,
        if des.nonstandard { " (non-standard size)" } else { "" }
    );
    let _ = writeln!(s, "\nbasic (mm)");
    let _ = writeln!(s, "  {:<34}{d:>9.3}", "major diameter d = D");
    let _ = writeln!(s, "  {:<34}{d2:>9.3}", "pitch diameter d2 = D2");
    let _ = writeln!(s, "  {:<34}{d3:>9.3}", "minor diameter of the bolt d3");
    let _ = writeln!(s, "  {:<34}{d1:>9.3}", "minor diameter of the nut D1");
    let _ = writeln!(s, "  {:<34}{h:>9.4}", "fundamental triangle height H");
    for l in [ext, int].into_iter().flatten() {
        let dev_name = if l.kind == ThreadKind::External { "es" } else { "EI" };
        let head = format!(
            "{} {} ({dev_name} = {} µm)",
            l.kind.name(),
            l.class,
            fmt_num((l.fundamental_deviation_um * 10.0).round() / 10.0)
        );
        let _ = writeln!(s, "\n{head:<36}{:>9} {:>9}", "max", "min");
        // Inch tables (ASME B1.1) print inches: show them beside the mm.
        let inch = matches!(t.form, crate::ThreadForm::Unified | crate::ThreadForm::Acme);
        let row = |s: &mut String, name: &str, lim: &Limit| {
            let _ = write!(s, "  {name:<34}{:>9} {:>9}", super::opt(lim.max, 3), super::opt(lim.min, 3));
            if inch {
                let i = |v: Option<f64>| v.map_or_else(|| "—".to_string(), |x| format!("{:.4}", x / 25.4));
                let _ = write!(s, "   {:>7} {:>7} in", i(lim.max), i(lim.min));
            }
            s.push('\n');
        };
        let (maj, minor) = if l.kind == ThreadKind::External {
            ("major diameter d", "minor: d1+es (max) / d3 min (min)")
        } else {
            ("major diameter D", "minor diameter D1")
        };
        if let Some(gp) = &l.gauge_plane {
            let _ = writeln!(
                s,
                "  {:<34}{:>9.3}   at {:.3} mm {}, ±{} turn (±{:.3} mm); taper 1:{}",
                "gauge plane: pitch diameter",
                gp.pitch_diameter,
                gp.distance,
                if l.kind == ThreadKind::External { "from the small end" } else { "(the face)" },
                gp.tolerance_turns,
                gp.tolerance_turns * t.pitch,
                fmt_num(1.0 / gp.taper)
            );
            for n in &l.notes {
                let _ = writeln!(s, "  note: {n}");
            }
            continue;
        }
        row(&mut s, maj, &l.major_diameter);
        row(
            &mut s,
            if l.kind == ThreadKind::External { "pitch diameter d2" } else { "pitch diameter D2" },
            &l.pitch_diameter,
        );
        row(&mut s, minor, &l.minor_diameter);
        if let Some(r) = l.root_radius_min {
            let _ = writeln!(s, "  {:<34}{:>9} {:>9.3}", "root radius R", "", r);
        }
        for n in &l.notes {
            let _ = writeln!(s, "  note: {n}");
        }
    }
    if ext.is_none() && int.is_none() {
        let (e, i) =
            (des.with_example_class(ThreadKind::External), des.with_example_class(ThreadKind::Internal));
        let example = if e == i { e } else { format!("{e} or {i}") };
        let _ = writeln!(s, "\nno class given: add one for limits, e.g. {example}");
    }
    s
}

/// The text of a rolled thread's blank (`limits --rolled`), in mm and, for an inch form, inches.
pub fn rolled_text(des: &crate::standards::Designation, r: &crate::analysis::rolled::RolledThread) -> String {
    use std::fmt::Write as _;
    let inch = des.thread.form.is_inch();
    let v = |x: f64| {
        if inch {
            format!("{:.4} in ({x:.3} mm)", x / crate::MM_PER_INCH)
        } else {
            format!("{x:.3} mm")
        }
    };
    let mut s = String::new();
    let _ = writeln!(
        s,
        "
rolled (volume constancy of the profile)"
    );
    let _ = writeln!(s, "  blank for the full crest            {}", v(r.blank_for_full_crest));
    if let Some(b) = r.blank {
        let formed = match (r.major_formed, r.overfilled) {
            (_, true) => {
                "overfilled: more metal than the teeth take, the crest laps over (the dies are overloaded)"
                    .to_string()
            }
            (Some(m), false) => format!(
                "major {} {}{}",
                v(m),
                if r.major_ok == Some(true) {
                    "within the class"
                } else {
                    "OUTSIDE the class's major limits"
                },
                if r.crest_short == Some(true) {
                    format!(", crest short of the full {}", v(r.full_crest))
                } else {
                    ", the crest full".to_string()
                }
            ),
            (None, false) => String::new(),
        };
        let _ = writeln!(s, "  from a blank of {}: {formed}", v(b));
    }
    let _ = writeln!(
        s,
        "  note: named defaults: the dies set d2 at the class's middle, {}; their crests form the root at {} (H/3 under the pitch line, the rounded root's bottom, taken flat); the full crest {} (3H/8 over it)",
        v(r.pitch_diameter),
        v(r.root_diameter),
        v(r.full_crest)
    );
    s
}
