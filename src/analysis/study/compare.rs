//! One-flank versus two-flank infeed: the same thread, insert and final X cut with radial, flank,
//! modified-flank and alternating infeed, each with constant-depth and constant-area schedules.
//!
//! Every strategy ends at the **same** final X (given, or the one that centres the pitch
//! diameter with radial, constant-area passes), so differences in the tooth come from the infeed
//! alone.

use crate::analysis::check::CheckFeature;
use crate::analysis::turn::{verify, Verification, VerifySpec};
use crate::ground::plane::deg;
use crate::toolpath::passes::{Infeed, InfeedChoice, Schedule};
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
    /// The checks that fail (in the verdict), why the verdict is `fail`.
    pub failed: Vec<CheckFeature>,
}

impl Summary {
    /// The last cutting pass's chip over the first's.
    pub fn chip_growth(&self) -> f64 {
        self.chip_last / self.chip_first
    }
}

/// What decided a recommendation, in the order applied.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Ground {
    /// Only strategies whose thread is in tolerance.
    InTolerance,
    /// Not flank infeed at exactly half the thread angle, where the trailing edge rubs the
    /// finished flank instead of cutting (why the trade takes a modified angle a little less).
    TrailingEdgeCuts,
    /// The least chip behind the tip (on the trailing edge), within 5 points of the least:
    /// the chip flows off the leading edge.
    LeastChipBehindTheTip,
    /// The most even chips (largest over smallest chip area, within 5 %).
    ChipBalance,
    /// The fewest passes.
    FewestPasses,
}

/// The strategy to use, and why.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Recommendation {
    /// Its row in [`Comparison::runs`].
    pub index: usize,
    /// Its infeed label.
    pub infeed: String,
    /// Its schedule.
    pub schedule: String,
    /// What decided it, in order (empty when one strategy was compared).
    pub grounds: Vec<Ground>,
    /// Whether any strategy is in tolerance (if none, the recommendation is the best of the
    /// failing ones, and their shared failure is not the infeed's doing).
    pub any_in_tolerance: bool,
}

/// A comparison of strategies for one thread.
#[derive(Clone, Debug)]
pub struct Comparison {
    /// The final X all strategies end at, mm.
    pub final_x: f64,
    /// One verification per strategy, with its summary.
    pub runs: Vec<(Summary, Verification)>,
    /// The strategy to use.
    pub recommended: Option<Recommendation>,
}

/// Which strategies to compare: every infeed and both schedules, or the ones the user chose.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CompareChoice {
    /// Compare this infeed alone.
    pub infeed: Option<InfeedChoice>,
    /// Compare this schedule alone (else constant depth and constant area).
    pub schedule: Option<Schedule>,
}

/// The recommendation among `runs`: in tolerance first, then a trailing edge that cuts, the
/// least chip behind the tip, the most even chips, the fewest passes (see [`Ground`]).
fn recommend(runs: &[(Summary, Verification)], half_angle: f64) -> Option<Recommendation> {
    if runs.is_empty() {
        return None;
    }
    let mut left: Vec<usize> = (0..runs.len()).collect();
    let mut grounds = Vec::new();
    let any = runs.iter().any(|(m, _)| m.pass);
    // Keeps what `keep` keeps of the strategies left, unless it would keep none.
    let mut narrow = |left: &mut Vec<usize>, keep: &dyn Fn(usize, &[usize]) -> bool, g: Ground| {
        let kept: Vec<usize> = left.iter().copied().filter(|&i| keep(i, left)).collect();
        if !kept.is_empty() && kept.len() < left.len() {
            *left = kept;
            grounds.push(g);
        }
    };
    narrow(&mut left, &|i, _| runs[i].0.pass, Ground::InTolerance);
    narrow(
        &mut left,
        &|i, _| !matches!(runs[i].1.infeed, Infeed::Flank { angle } if (angle - half_angle).abs() < 1e-9),
        Ground::TrailingEdgeCuts,
    );
    let least = |all: &[usize], f: &dyn Fn(&Summary) -> f64| {
        all.iter().map(|&j| f(&runs[j].0)).fold(f64::INFINITY, f64::min)
    };
    narrow(
        &mut left,
        &|i, all| runs[i].0.trailing_share <= least(all, &|m| m.trailing_share) + 0.05,
        Ground::LeastChipBehindTheTip,
    );
    narrow(
        &mut left,
        &|i, all| runs[i].0.chip_spread <= least(all, &|m| m.chip_spread) * 1.05,
        Ground::ChipBalance,
    );
    narrow(
        &mut left,
        &|i, all| runs[i].0.passes as f64 <= least(all, &|m| m.passes as f64),
        Ground::FewestPasses,
    );
    let index = left[0];
    let m = &runs[index].0;
    Some(Recommendation {
        index,
        infeed: m.infeed.clone(),
        schedule: m.schedule.clone(),
        grounds,
        any_in_tolerance: any,
    })
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
        failed: v.checks.iter().filter(|c| c.fails(v.gauge_only)).map(|c| c.feature).collect(),
    }
}

/// Runs every strategy × {constant depth, constant area} on `base` (or the infeed and schedule
/// `choice` names), all ending at one final X, and recommends one.
///
/// ```
/// use threadcheck::{compare, CompareChoice};
/// use threadcheck::{InsertChoice, VerifySpec};
/// let base = VerifySpec { insert: InsertChoice::Full, final_x: Some(8.2), ..VerifySpec::of("M10x1.5-6g")? };
/// // Radial, flank, one modified angle and alternating, each with two schedules.
/// let c = compare(&base, &[29.5], &CompareChoice::default())?;
/// assert_eq!(c.runs.len(), 8);
/// assert!(c.runs.iter().all(|(_, v)| v.final_x == 8.2));
/// assert!(c.recommended.is_some());
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn compare(base: &VerifySpec, modified: &[f64], choice: &CompareChoice) -> Result<Comparison, Error> {
    if base.program.is_some() {
        return Err(Error::Input(
            "compare lays out each infeed strategy's own passes, and a program fixes its own: verify the program, or compare its thread without ‹program›".into(),
        ));
    }
    if base.taper != 0.0 {
        return Err(Error::Input(
            "‹taper› lays out a tapered pass plan for `passes`; compare takes a taper thread's taper from its designation (NPT, ISO 7-1)".into(),
        ));
    }
    let final_x = match base.final_x {
        Some(x) => x,
        None => {
            let mut s = base.clone();
            s.infeed = Some(crate::toolpath::passes::InfeedChoice::Radial);
            s.schedule = Schedule::ConstantArea;
            verify(&s)?.final_x
        }
    };
    let des = base.designation.clone().ok_or_else(crate::standards::designation::none_given)?;
    let half = 0.5 * des.thread.form.flank_angle();
    let infeeds = match choice.infeed {
        Some(c) => {
            let i = c.resolve(des.thread.form.flank_angle());
            vec![(i.to_string(), i)]
        }
        None => strategies(half, modified),
    };
    let schedules = match &choice.schedule {
        Some(s) => vec![s.clone()],
        None => vec![Schedule::ConstantDepth, Schedule::ConstantArea],
    };
    let mut runs = Vec::new();
    for (label, infeed) in infeeds {
        for schedule in &schedules {
            let mut s = base.clone();
            s.infeed = Some(infeed.into());
            s.schedule = schedule.clone();
            s.final_x = Some(final_x);
            let v = verify(&s)?;
            runs.push((summarise(&label, schedule.name(), &v), v));
        }
    }
    let recommended = recommend(&runs, half);
    Ok(Comparison { final_x, runs, recommended })
}
