//! Validated jobs behind the command line. `main.rs` parses arguments into one of these, runs it
//! and maps the [`Outcome`] to an exit code; everything here is usable without the CLI.

use crate::standards::{parse_designation, Designation, ParseOptions, ThreadKind};
use crate::tolerance::{basic_rounded, limits_for, Limit, ThreadLimits};
use crate::Error;
use serde_json::json;
use std::fmt::Write as _;

/// What a job concluded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// The job did its work; for `verify`, the thread is within every limit (exit 0).
    Pass,
    /// `verify` ran and the thread is out of tolerance (exit 1).
    OutOfTolerance,
}

impl Outcome {
    /// The process exit code: 0 pass, 1 out of tolerance (2, errors, is the caller's).
    pub fn exit_code(self) -> i32 {
        match self {
            Outcome::Pass => 0,
            Outcome::OutOfTolerance => 1,
        }
    }
}

/// `threadcheck limits`: the limits of size of a designation.
#[derive(Clone, Debug)]
pub struct LimitsJob {
    /// The designation text.
    pub designation: String,
    /// Accept sizes outside the standard series.
    pub allow_nonstandard: bool,
    /// JSON instead of the table.
    pub json: bool,
}

impl LimitsJob {
    /// Runs the job, returning what to print on stdout.
    pub fn run(&self) -> Result<(String, Outcome), Error> {
        let des =
            parse_designation(&self.designation, ParseOptions { allow_nonstandard: self.allow_nonstandard })?;
        let ext = limits_for(&des, ThreadKind::External)?;
        let int = limits_for(&des, ThreadKind::Internal)?;
        let text = if self.json {
            let mut s = serde_json::to_string_pretty(&limits_json(&des, ext.as_ref(), int.as_ref()))
                .map_err(|e| Error::Data(e.to_string()))?;
            s.push('\n');
            s
        } else {
            limits_table(&des, ext.as_ref(), int.as_ref())
        };
        Ok((text, Outcome::Pass))
    }
}

/// The `limits --json` object of the CLI contract.
pub fn limits_json(
    des: &Designation,
    ext: Option<&ThreadLimits>,
    int: Option<&ThreadLimits>,
) -> serde_json::Value {
    let t = &des.thread;
    let (d, d2, d3, d1, h) = basic_rounded(t);
    let side =
        |l: Option<&ThreadLimits>| l.map(|l| serde_json::to_value(l).unwrap_or(serde_json::Value::Null));
    json!({
        "designation": des.text,
        "form": t.form.name(),
        "nominal_diameter": t.nominal_diameter,
        "pitch": t.pitch,
        "lead": t.lead(),
        "starts": t.starts,
        "hand": match t.hand { crate::Hand::Right => "right", crate::Hand::Left => "left" },
        "nonstandard": des.nonstandard,
        "basic": {
            "major_diameter": d,
            "pitch_diameter": d2,
            "minor_diameter_external": d3,
            "minor_diameter_internal": d1,
            "fundamental_triangle_height": h,
        },
        "external": side(ext),
        "internal": side(int),
    })
}

fn fmt_opt(v: Option<f64>) -> String {
    v.map_or_else(|| "—".to_string(), |x| format!("{x:.3}"))
}

fn limits_table(des: &Designation, ext: Option<&ThreadLimits>, int: Option<&ThreadLimits>) -> String {
    let t = &des.thread;
    let (d, d2, d3, d1, h) = basic_rounded(t);
    let mut s = String::new();
    let hand = if t.hand == crate::Hand::Left { "left-hand" } else { "right-hand" };
    let _ = writeln!(
        s,
        "{}  {}, P = {} mm{}, lead {} mm, {} start{}, {}{}",
        des.text,
        t.form.name(),
        crate::tolerance::round_um(t.pitch),
        if t.form.is_whitworth() {
            format!(" ({} tpi)", crate::tolerance::round_um(25.4 / t.pitch))
        } else {
            String::new()
        },
        crate::tolerance::round_um(t.lead()),
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
        let head = format!("{} {} ({dev_name} = {} µm)", l.kind.name(), l.class, l.fundamental_deviation_um);
        let _ = writeln!(s, "\n{head:<36}{:>9} {:>9}", "max", "min");
        let row = |s: &mut String, name: &str, lim: &Limit| {
            let _ = writeln!(s, "  {name:<34}{:>9} {:>9}", fmt_opt(lim.max), fmt_opt(lim.min));
        };
        let (maj, minor) = if l.kind == ThreadKind::External {
            ("major diameter d", "minor: d1+es (max) / d3 min (min)")
        } else {
            ("major diameter D", "minor diameter D1")
        };
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
        let _ =
            writeln!(s, "\nno class given: add one for limits, e.g. {}-6g or {}-6H/6g", des.text, des.text);
    }
    s
}
