//! One-flank versus two-flank infeed: the same thread, insert and final X cut with radial, flank,
//! modified-flank and alternating infeed, each with constant-depth and constant-area schedules.
//!
//! Every strategy ends at the **same** final X (given, or the one that centres the pitch
//! diameter with radial, constant-area passes), so differences in the tooth come from the infeed
//! alone.

use crate::geometry::deg;
use crate::passes::{Infeed, Schedule};
use crate::verify::{verify, Verification, VerifySpec};
use crate::Error;
use serde::Serialize;
use std::fmt::Write as _;

/// A pass counts as two-flank when its trailing edge engages more than this much (mm) beyond the
/// strip below the previous root, which even flank infeed cuts (see [`Summary::two_flank_passes`]).
pub const TWO_FLANK_MARGIN: f64 = 1e-3;

/// Per-strategy figures.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Summary {
    /// Strategy label (`radial`, `flank 30°`, `modified 29.5°`, `alternating 30°`).
    pub infeed: String,
    /// `constant-depth` or `constant-area`.
    pub schedule: String,
    /// Number of passes.
    pub passes: usize,
    /// Chip area of the first pass, mm².
    pub chip_first: f64,
    /// Largest chip area, mm².
    pub chip_max: f64,
    /// Chip area of the last cutting pass, mm².
    pub chip_last: f64,
    /// Largest over smallest chip area of the cutting passes.
    pub chip_spread: f64,
    /// Passes whose trailing edge cuts above the previous root: its engaged length exceeds the
    /// strip (Δdepth / cos(α/2)) below the previous root by more than [`TWO_FLANK_MARGIN`].
    pub two_flank_passes: usize,
    /// Share of all chip area that lies on the trailing side of the tip, 0 to 1 (about 0.5 for
    /// radial infeed).
    pub trailing_share: f64,
    /// Measured pitch diameter, mm.
    pub pitch_diameter: f64,
    /// Measured minor (root) diameter, mm.
    pub minor_diameter: f64,
    /// Measured flank half-angles, degrees.
    pub flank_angles: [f64; 2],
    /// Verdict.
    pub pass: bool,
}

/// A comparison of strategies for one thread.
#[derive(Clone, Debug)]
pub struct Comparison {
    /// The final X all strategies end at, mm.
    pub final_x: f64,
    /// One verification per strategy, with its summary.
    pub runs: Vec<(Summary, Verification)>,
}

/// The strategies compared: radial, flank at half the thread angle, each modified-flank angle,
/// and alternating at half the thread angle.
pub fn strategies(half_angle: f64, modified: &[f64]) -> Vec<(String, Infeed)> {
    let mut v = vec![
        ("radial".to_string(), Infeed::Radial),
        (format!("flank {half_angle}°"), Infeed::Flank { angle: half_angle }),
    ];
    for a in modified {
        v.push((format!("modified {a}°"), Infeed::Flank { angle: *a }));
    }
    v.push((format!("alternating {half_angle}°"), Infeed::Alternating { angle: half_angle }));
    v
}

fn summarise(label: &str, schedule: &str, v: &Verification) -> Summary {
    let cutting: Vec<&crate::sweep::PassMetrics> = v.metrics.iter().filter(|m| m.chip_area > 1e-12).collect();
    let areas: Vec<f64> = cutting.iter().map(|m| m.chip_area).collect();
    let max = areas.iter().copied().fold(0.0, f64::max);
    let min = areas.iter().copied().fold(f64::INFINITY, f64::min);
    let beta = deg(0.5 * v.designation.thread.form.flank_angle());
    let mut prev_depth = 0.0;
    let mut two = 0;
    let (mut chip_total, mut trail_total) = (0.0, 0.0);
    for (p, m) in v.passes.iter().zip(&v.metrics) {
        let depth = 0.5 * (p.x_at(v.z_ref) - v.blank_diameter).abs();
        let strip = (depth - prev_depth).max(0.0) / beta.cos();
        if m.trailing > strip + TWO_FLANK_MARGIN {
            two += 1;
        }
        chip_total += m.chip_area;
        trail_total += m.trailing_area;
        prev_depth = depth;
    }
    Summary {
        infeed: label.to_string(),
        schedule: schedule.to_string(),
        passes: v.passes.len(),
        chip_first: areas.first().copied().unwrap_or(0.0),
        chip_max: max,
        chip_last: areas.last().copied().unwrap_or(0.0),
        chip_spread: if min > 0.0 { max / min } else { f64::INFINITY },
        two_flank_passes: two,
        trailing_share: if chip_total > 0.0 { trail_total / chip_total } else { 0.0 },
        pitch_diameter: v.measurement.pitch_diameter,
        minor_diameter: v.measurement.minor_diameter,
        flank_angles: v.measurement.flank_angles,
        pass: v.pass,
    }
}

/// Runs every strategy × {constant depth, constant area} on `base`, all ending at one final X.
///
/// ```
/// use threadcheck::compare::compare;
/// use threadcheck::{InsertChoice, VerifySpec};
/// let base = VerifySpec { insert: InsertChoice::Full, final_x: Some(8.2), ..VerifySpec::new("M10x1.5-6g") };
/// // Radial, flank, one modified angle and alternating, each with two schedules.
/// let c = compare(&base, &[29.5])?;
/// assert_eq!(c.runs.len(), 8);
/// assert!(c.runs.iter().all(|(_, v)| v.final_x == 8.2));
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn compare(base: &VerifySpec, modified: &[f64]) -> Result<Comparison, Error> {
    let final_x = match base.final_x {
        Some(x) => x,
        None => {
            let mut s = base.clone();
            s.infeed = Some(crate::passes::InfeedChoice::Radial);
            s.schedule = Schedule::ConstantArea;
            verify(&s)?.final_x
        }
    };
    let des = crate::parse_designation(
        &base.designation,
        crate::ParseOptions { allow_nonstandard: base.allow_nonstandard },
    )?;
    let half = 0.5 * des.thread.form.flank_angle();
    let mut runs = Vec::new();
    for (label, infeed) in strategies(half, modified) {
        for (sname, schedule) in
            [("constant-depth", Schedule::ConstantDepth), ("constant-area", Schedule::ConstantArea)]
        {
            let mut s = base.clone();
            s.infeed = Some(infeed.into());
            s.schedule = schedule;
            s.final_x = Some(final_x);
            let v = verify(&s)?;
            runs.push((summarise(&label, sname, &v), v));
        }
    }
    Ok(Comparison { final_x, runs })
}

/// The column headers of the comparison table (Markdown), and the same for the text table.
const HEADERS: [(&str, &str); 13] = [
    ("infeed", "infeed"),
    ("schedule", "schedule"),
    ("passes", "passes"),
    ("chip first mm²", "chip 1st"),
    ("chip max mm²", "chip max"),
    ("chip last mm²", "chip end"),
    ("max/min", "max/min"),
    ("two-flank passes", "2-fl"),
    ("chip behind the tip", "behind"),
    ("d2 mm", "d2"),
    ("d3 mm", "d3"),
    ("flanks °", "flanks"),
    ("verdict", "verdict"),
];

/// The cells of one strategy's row, formatted once for both tables.
fn cells(m: &Summary) -> [String; 13] {
    [
        m.infeed.clone(),
        m.schedule.clone(),
        m.passes.to_string(),
        format!("{:.4}", m.chip_first),
        format!("{:.4}", m.chip_max),
        format!("{:.4}", m.chip_last),
        format!("{:.2}", m.chip_spread),
        m.two_flank_passes.to_string(),
        pct(m.trailing_share),
        format!("{:.4}", m.pitch_diameter),
        format!("{:.4}", m.minor_diameter),
        format!("{:.2}/{:.2}", m.flank_angles[0], m.flank_angles[1]),
        (if m.pass { "pass" } else { "fail" }).to_string(),
    ]
}

/// The comparison as a Markdown table.
pub fn markdown(c: &Comparison) -> String {
    let mut s = String::new();
    let head: Vec<&str> = HEADERS.iter().map(|h| h.0).collect();
    let _ = writeln!(s, "| {} |", head.join(" | "));
    let _ = writeln!(s, "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|");
    for (m, _) in &c.runs {
        let _ = writeln!(s, "| {} |", cells(m).join(" | "));
    }
    s
}

/// The comparison as a plain-text table.
pub fn text(c: &Comparison) -> String {
    let mut s = String::new();
    if let Some((_, v)) = c.runs.first() {
        let _ = writeln!(
            s,
            "{} {}, insert '{}', blank X{:.4}, all strategies ending at X{:.4}\n",
            v.designation.text,
            v.kind.name(),
            v.insert.name,
            v.blank_diameter,
            c.final_x
        );
    }
    // Widths per column: left-aligned words, right-aligned numbers.
    const W: [(usize, bool); 13] = [
        (18, true),
        (16, true),
        (6, false),
        (10, false),
        (10, false),
        (10, false),
        (8, false),
        (6, false),
        (7, false),
        (10, false),
        (10, false),
        (14, false),
        (9, false),
    ];
    let line = |s: &mut String, row: &[String]| {
        for (cell, (w, left)) in row.iter().zip(W) {
            let _ = if left { write!(s, "{cell:<w$}") } else { write!(s, "{cell:>w$}") };
        }
        s.push('\n');
    };
    line(&mut s, &HEADERS.iter().map(|h| h.1.to_string()).collect::<Vec<_>>());
    for (m, _) in &c.runs {
        line(&mut s, &cells(m));
    }
    s
}

/// `compare --json`: every verify report, and the per-strategy figures (docs/json.md).
#[derive(Clone, Debug, serde::Serialize)]
pub struct CompareReport<'a> {
    /// The last pass's X, shared by every strategy, mm.
    pub final_x: f64,
    /// One verify report per strategy.
    pub reports: Vec<crate::report::VerifyReport<'a>>,
    /// The per-strategy figures.
    pub strategies: Vec<&'a Summary>,
}

impl<'a> CompareReport<'a> {
    /// The report of a comparison.
    pub fn of(c: &'a Comparison) -> Self {
        CompareReport {
            final_x: c.final_x,
            reports: c.runs.iter().map(|(_, v)| crate::report::VerifyReport::of(v)).collect(),
            strategies: c.runs.iter().map(|(m, _)| m).collect(),
        }
    }
}

/// The threads of the committed comparison report.
pub const REPORT_THREADS: [&str; 4] = ["M6x1-6g", "M10x1.5-6g", "M20x2.5-6g", "M36x4-6g"];

fn pct(x: f64) -> String {
    format!("{:.0}%", 100.0 * x)
}

/// Writes `infeed-comparison.md` and its SVGs into `dir` (atomically, deterministically: the
/// same build writes the same bytes). Returns the Markdown.
pub fn write_report(dir: &std::path::Path) -> Result<String, Error> {
    use crate::verify::InsertChoice;
    let mut md = String::new();
    let _ = writeln!(md, "# One-flank versus two-flank infeed: what the geometry says\n");
    let _ = writeln!(
        md,
        "Generated by `cargo run --release -- report infeed-comparison --out reports` (threadcheck {}). \
         Every number below is measured on the as-cut section that threadcheck computes; nothing is \
         typed in by hand.\n",
        env!("CARGO_PKG_VERSION")
    );
    md.push_str(
        "## How the comparison is made\n\n\
         For each thread and insert, threadcheck cuts the same thread ten ways: radial (two-flank) \
         infeed, flank infeed at half the thread angle (one-flank), modified flank at 29.5° and 27°, \
         and alternating flank, each with constant-depth passes (d_i = t·i/N) and constant-area passes \
         (d_i = t·√(i/N)). All ten end at the **same final X**, the one that puts the pitch diameter \
         in the middle of 6g with radial infeed, so any difference in the tooth comes from the infeed \
         alone. The blank is what a shop turns: d + 0.1 mm for a full-profile insert (it tops the crest), \
         the middle of the major-diameter tolerance for a partial-profile insert (tip radius 0.04 mm).\n\n\
         Columns: *chip* is the cross-section a pass removes from one groove; *max/min* the spread of \
         chip areas; *two-flank passes* the passes whose trailing edge cuts above the previous root \
         (flank infeed only cuts the strip below it, where the old flank line is extended); *chip \
         behind the tip* the share of all chip area on the trailing side of the tip.\n\n",
    );
    let mut findings: Vec<String> = Vec::new();
    for d in REPORT_THREADS {
        for (iname, choice) in [
            ("full-profile", InsertChoice::Full),
            ("partial-profile r0.04", InsertChoice::Partial { tip_radius: 0.04 }),
        ] {
            let mut spec = VerifySpec::new(d);
            spec.insert = choice;
            let c = compare(&spec, &[29.5, 27.0])?;
            let Some((_, v0)) = c.runs.first() else { continue };
            let _ = writeln!(md, "## {d}, {iname} insert\n");
            let _ = writeln!(
                md,
                "Blank X{:.3}, {} passes, every strategy ends at X{:.4}. Limits: d2 {:.3} to {:.3}.\n",
                v0.blank_diameter,
                v0.passes.len(),
                c.final_x,
                v0.limits.pitch_diameter.min.unwrap_or(f64::NAN),
                v0.limits.pitch_diameter.max.unwrap_or(f64::NAN)
            );
            md.push_str(&markdown(&c));
            md.push('\n');
            let slug = d.to_ascii_lowercase().replace('.', "_");
            let islug = if iname.starts_with("full") { "full" } else { "partial" };
            for (label, sched) in [("radial", "constant-area"), ("flank 30°", "constant-area")] {
                if let Some((_, v)) = c.runs.iter().find(|(m, _)| m.infeed == label && m.schedule == sched) {
                    let name = format!(
                        "infeed-{slug}-{islug}-{}.svg",
                        if label == "radial" { "radial" } else { "flank" }
                    );
                    crate::output::write_atomic(&dir.join(&name), crate::render::verify_svg(v).as_bytes())?;
                    let _ = writeln!(md, "![{d} {iname}, {label} infeed, {sched}]({name})");
                }
            }
            md.push('\n');
            let get = |i: &str, s: &str| {
                c.runs.iter().find(|(m, _)| m.infeed == i && m.schedule == s).map(|(m, _)| m.clone())
            };
            if let (Some(rd), Some(ra), Some(fa), Some(ma)) = (
                get("radial", "constant-depth"),
                get("radial", "constant-area"),
                get("flank 30°", "constant-area"),
                get("modified 29.5°", "constant-area"),
            ) {
                let d2s: Vec<f64> = c.runs.iter().map(|(m, _)| m.pitch_diameter).collect();
                let spread = d2s.iter().copied().fold(f64::NEG_INFINITY, f64::max)
                    - d2s.iter().copied().fold(f64::INFINITY, f64::min);
                findings.push(format!(
                    "| {d} | {iname} | {:.1}× | {:.2} | {} / {} / {} | {:.2} µm |",
                    rd.chip_last / rd.chip_first,
                    ra.chip_spread,
                    pct(ra.trailing_share),
                    pct(ma.trailing_share),
                    pct(fa.trailing_share),
                    1000.0 * spread
                ));
            }
        }
    }
    md.push_str(
        "## What the numbers show\n\n\
         | thread | insert | constant depth: last chip / first | constant area: max/min chip | chip behind the tip: radial / modified 29.5° / flank | d2 spread over all ten ways |\n\
         |---|---|---:|---:|---|---:|\n",
    );
    for f in &findings {
        md.push_str(f);
        md.push('\n');
    }
    md.push_str(
        "\n1. **The final tooth does not depend on the infeed** as long as the infeed angle stays between \
         0 and half the thread angle. An earlier, shallower pass sits inside a later V when its axial offset \
         is at most Δdepth·tan(α/2), so the last pass alone shapes the groove: pitch diameter, root and flank \
         angles are the same for radial, flank, modified-flank and (incrementally) alternating infeed, to \
         well under 0.1 µm. Geometry does not make radial infeed drift the depth or the pitch diameter; where \
         that happens on a machine it comes from forces, deflection and wear, which threadcheck does not model.\n\
         2. **What the infeed changes is the chip.** Radial infeed puts half of every chip behind the tip and \
         engages both flanks along their whole length on every pass after the first: a V-shaped chip that \
         has nowhere to flow. Flank infeed at α/2 puts most of the chip in front of the tip on the leading \
         edge; the trailing edge only forms the short strip below the previous root. Modified flank (29.5°, \
         27°) adds a thin cut along the whole trailing flank, so the trailing edge cuts instead of rubbing, \
         while the chip stays mostly on the leading side.\n\
         3. **Constant-depth schedules grow the chip with every pass** (for a sharp V the last chip is 2N − 1 \
         times the first); constant-area schedules hold it nearly flat, which evens out the load on the \
         insert. With a full-profile insert the last passes also top the crest, which adds to their chips.\n\
         4. **What does move the pitch diameter**: an infeed angle above α/2 (the flank rule written with the \
         tangent on the wrong side infeeds at 60° and gouges the trailing flank: d2 drops by \
         Δdepth·(tan θ / tan 30° − 1), 2·Δdepth at 60°), and passes that do not land in one groove (a phase \
         error or final passes spread along Z): every 0.01 mm of spread costs s / tan 30° = 17.3 µm of pitch \
         diameter on a 60° thread. Both are in `tests/infeed_comparison.rs`.\n\n\
         ## Recommendation\n\n\
         Use **modified flank infeed at 27°–29.5° with constant-area (degressive) depths**: it produces the \
         same tooth as any other method, keeps each chip about the same size, puts most of it on the leading \
         edge, and still lets the trailing edge cut a thin chip rather than rub. Use radial infeed only for \
         fine pitches, where the V chip is small. Never infeed at more than half the thread angle, and check \
         that the control's passes land in one groove (a phase error shows up directly as lost pitch diameter). \
         A partial-profile insert passes the size checks at the solved X but cannot meet ISO 965-1's root \
         requirements (R min = 0.125·P, d3 min); where those matter, use a full-profile insert.\n",
    );
    crate::output::write_atomic(&dir.join("infeed-comparison.md"), md.as_bytes())?;
    Ok(md)
}
