//! One-flank versus two-flank infeed: the same thread, insert and final X cut with radial, flank,
//! modified-flank and alternating infeed, each with constant-depth and constant-area schedules.
//!
//! Every strategy ends at the **same** final X (given, or the one that centres the pitch
//! diameter with radial, constant-area passes), so differences in the tooth come from the infeed
//! alone.

use crate::analysis::verify::{verify, Verification, VerifySpec};
use crate::gcode::passes::{Infeed, Schedule};
use crate::ground::plane::deg;
use crate::Error;
use serde::Serialize;

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

impl Summary {
    /// The last cutting pass's chip over the first's.
    pub fn chip_growth(&self) -> f64 {
        self.chip_last / self.chip_first
    }
}

/// A comparison of strategies for one thread.
#[derive(Clone, Debug)]
pub struct Comparison {
    /// The final X all strategies end at, mm.
    pub final_x: f64,
    /// One verification per strategy, with its summary.
    pub runs: Vec<(Summary, Verification)>,
}

impl Comparison {
    /// The largest minus the smallest pitch diameter over every strategy, mm.
    pub fn pitch_diameter_spread(&self) -> f64 {
        let d2 = || self.runs.iter().map(|(m, _)| m.pitch_diameter);
        d2().fold(f64::NEG_INFINITY, f64::max) - d2().fold(f64::INFINITY, f64::min)
    }
}

/// The threads of the committed infeed-comparison report.
pub const REPORT_THREADS: [&str; 4] = ["M6x1-6g", "M10x1.5-6g", "M20x2.5-6g", "M36x4-6g"];

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
    let cutting: Vec<&crate::geometry::sweep::PassMetrics> =
        v.metrics.iter().filter(|m| m.chip_area > 1e-12).collect();
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
/// use threadcheck::compare;
/// use threadcheck::{InsertChoice, VerifySpec};
/// let base = VerifySpec { insert: InsertChoice::Full, final_x: Some(8.2), ..VerifySpec::new("M10x1.5-6g") };
/// // Radial, flank, one modified angle and alternating, each with two schedules.
/// let c = compare(&base, &[29.5])?;
/// assert_eq!(c.runs.len(), 8);
/// assert!(c.runs.iter().all(|(_, v)| v.final_x == 8.2));
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn compare(base: &VerifySpec, modified: &[f64]) -> Result<Comparison, Error> {
    if base.program.is_some() {
        return Err(Error::Input(
            "compare lays out each infeed strategy's own passes, and a program fixes its own: verify the program, or compare its thread without --program".into(),
        ));
    }
    if base.taper != 0.0 {
        return Err(Error::Input(
            "--taper lays out a tapered pass plan for `passes`; compare takes a taper thread's taper from its designation (NPT, ISO 7-1)".into(),
        ));
    }
    let final_x = match base.final_x {
        Some(x) => x,
        None => {
            let mut s = base.clone();
            s.infeed = Some(crate::gcode::passes::InfeedChoice::Radial);
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
