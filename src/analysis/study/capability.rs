//! `capability`: how many parts a program keeps in tolerance. A Monte Carlo after JCGM 101
//! (the GUM's supplement 1) over the verify core: each sample is one part cut with a fresh
//! edge, its passes moved by the machine's X scatter and its insert's tip radius drawn within
//! its tolerance; the sizes' spread gives Cp and Cpk (ISO 22514-2, normal model), the samples'
//! verdicts the share of good parts, and the wear per part the parts per edge.
//!
//! The model, stated in every report:
//! - X: one offset per part, normal with standard deviation σx on the diameter, the same on
//!   every pass (the slide's repeatability from part to part);
//! - tip radius: uniform within ± its tolerance (a partial-profile insert's);
//! - wear: w per part radially, part k (from 1) cut with the wear of k parts (its finishing pass
//!   comes last), which moves every diameter by 2·k·w, up on a bolt and down in a nut;
//! - a part is predicted out when its pitch diameter's mean ± 3σ leaves the limits.

use crate::analysis::check::{CheckFeature, CheckKind};
use crate::analysis::turn::correction::Correction;
use crate::analysis::turn::{Recut, Verification, VerifySpec};
use crate::standards::ThreadKind;
use crate::Error;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use rayon::prelude::*;
use serde::Serialize;

/// One sampled part: each check's value and whether it is within its limits, and the verdict.
type Sampled = (Vec<f64>, Vec<bool>, bool);

/// The most samples a run takes (about 20 µs each); [`MAX_SAMPLE_WORK`] bounds them further.
pub const MAX_SAMPLES: usize = 1_000_000;

/// The work one run may do, counted as samples × (passes + [`SAMPLE_OVERHEAD_PASSES`]): a sample
/// costs about 20 µs plus 0.5 µs per pass on the 2-core machine of reports/bounds.md, so the
/// largest run takes about a second (42 553 samples of a 7-pass thread, 1 923 of 1 000 passes).
pub const MAX_SAMPLE_WORK: usize = 2_000_000;

/// The least wear per part taken (1 nm): the parts an edge lasts stay countable (at most
/// 1 mm of room / 2 nm = 500 000).
pub const MIN_WEAR_PER_PART: f64 = 1e-6;

/// A sample's fixed cost in passes' worth of work (the measurement and checks of the part).
pub const SAMPLE_OVERHEAD_PASSES: usize = 40;

/// Everything `capability` needs.
#[derive(Clone, Debug)]
pub struct CapabilitySpec {
    /// The thread and its program or plan, as `verify` takes them.
    pub verify: VerifySpec,
    /// X repeatability, one standard deviation on the diameter, mm.
    pub x_sigma: f64,
    /// The insert's tip radius tolerance, ± mm (uniform).
    pub tip_radius_tol: f64,
    /// Radial insert wear per part, mm.
    pub wear_per_part: f64,
    /// Monte Carlo samples.
    pub samples: usize,
    /// The seed: the same seed gives the same report whatever the number of threads.
    pub seed: u64,
}

impl CapabilitySpec {
    /// A spec with 10 000 samples, seed 1 and no variation.
    pub fn new(verify: VerifySpec) -> CapabilitySpec {
        CapabilitySpec {
            verify,
            x_sigma: 0.0,
            tip_radius_tol: 0.0,
            wear_per_part: 0.0,
            samples: 10_000,
            seed: 1,
        }
    }
}

/// One checked size over the samples.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SizeCapability {
    /// What is checked.
    pub feature: CheckFeature,
    /// Which flank or other detail.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
    /// Lower limit, mm.
    pub min: Option<f64>,
    /// Upper limit, mm.
    pub max: Option<f64>,
    /// The samples' mean, mm.
    pub mean: f64,
    /// Their standard deviation, mm.
    pub sigma: f64,
    /// (max − min) / 6σ; `None` without two limits or without spread (σ under 0.1 nm).
    pub cp: Option<f64>,
    /// min(max − mean, mean − min) / 3σ over the limits there are; `None` without spread.
    pub cpk: Option<f64>,
    /// Parts out of tolerance per million among the samples.
    pub ppm_counted: f64,
    /// The same from the normal model (mean, σ); `None` without spread.
    pub ppm_normal: Option<f64>,
}

/// A histogram: `counts[i]` samples in [lo + i·width, lo + (i+1)·width).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Histogram {
    /// Lower edge of the first bin, mm.
    pub lo: f64,
    /// Bin width, mm.
    pub width: f64,
    /// Samples per bin.
    pub counts: Vec<usize>,
}

/// What `capability` found.
#[derive(Clone, Debug)]
pub struct CapabilityReport {
    /// The thread as the program or plan cuts it with no variation.
    pub verification: Verification,
    /// The spec's variation and sampling.
    pub x_sigma: f64,
    /// ± mm.
    pub tip_radius_tol: f64,
    /// mm per part.
    pub wear_per_part: f64,
    /// Samples taken.
    pub samples: usize,
    /// Their seed.
    pub seed: u64,
    /// Each checked size.
    pub sizes: Vec<SizeCapability>,
    /// Share of the sampled parts that pass every check of the verdict, 0…1.
    pub pass_share: f64,
    /// Parts per insert edge before the first is predicted out, at the program's X (`None`
    /// without wear).
    pub parts_per_edge: Option<usize>,
    /// The last pass's tip diameter that gives the most parts per edge (without wear: the one
    /// that centres the pitch diameter), mm.
    pub best_final_x: f64,
    /// Parts per edge at it.
    pub best_parts_per_edge: Option<usize>,
    /// The change that makes it, in the program's words.
    pub best_correction: Option<Correction>,
    /// The pitch diameter's histogram.
    pub histogram: Histogram,
    /// The Monte Carlo's own standard uncertainty of the pitch diameter's Cpk (JCGM 101's
    /// numerical tolerance, from the normal model: Cpk·√(1/(9·N·Cpk²) + 1/(2(N − 1)))).
    pub cpk_uncertainty: Option<f64>,
    /// The model, stated.
    pub notes: Vec<crate::ground::note::Note>,
}

/// The standard normal distribution function.
fn phi(z: f64) -> f64 {
    0.5 * libm::erfc(-z / std::f64::consts::SQRT_2)
}

/// Runs the Monte Carlo: see the module's documentation.
///
/// ```
/// use threadcheck::{capability, CapabilitySpec, InsertChoice, VerifySpec};
/// // A full-profile M10x1.5-6g plan centred in 8.862–8.994 (T = 132 µm) with σx = 11 µm:
/// // Cpk = (T/2)/(3σ) = 66/33 = 2.0, within the Monte Carlo's error.
/// let mut spec = CapabilitySpec::new(VerifySpec { insert: InsertChoice::Full, ..VerifySpec::of("M10x1.5-6g")? });
/// spec.x_sigma = 0.011;
/// spec.samples = 2000;
/// let r = capability(&spec)?;
/// let d2 = r.sizes.iter().find(|s| s.feature == threadcheck::CheckFeature::PitchDiameter).unwrap();
/// assert!((d2.cpk.unwrap() - 2.0).abs() < 0.1);
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn capability(spec: &CapabilitySpec) -> Result<CapabilityReport, Error> {
    checked_inputs(spec)?;
    let (recut, v) = Recut::new(&spec.verify)?;
    // The work is bounded before it starts: each sample costs a fixed part and a part per pass.
    let work = spec.samples.saturating_mul(recut.pass_count() + SAMPLE_OVERHEAD_PASSES);
    if work > MAX_SAMPLE_WORK {
        return Err(Error::Input(format!(
            "{} samples of a thread cut in {} passes: samples × (passes + {SAMPLE_OVERHEAD_PASSES}) is {}, over the budget of {} (about a second on 2 cores); take at most {} samples",
            spec.samples,
            recut.pass_count(),
            crate::ground::fmt::fmt_shown(work as f64),
            crate::ground::fmt::fmt_shown(MAX_SAMPLE_WORK as f64),
            MAX_SAMPLE_WORK / (recut.pass_count() + SAMPLE_OVERHEAD_PASSES)
        )));
    }
    let tip = match (recut.tip_radius(), spec.tip_radius_tol) {
        (_, 0.0) => None,
        (Some(r), t) if t < r => Some((r, t)),
        (Some(r), t) => {
            return Err(Error::Input(format!(
                "‹tip_radius_tol› {} mm: must be under the tip radius {} mm",
                crate::ground::fmt::fmt_num(t),
                crate::ground::fmt::fmt_num(r)
            )))
        }
        (None, _) => {
            return Err(Error::Input(
                "‹tip_radius_tol› varies a partial-profile insert's tip radius: give ‹insert› partial:R"
                    .into(),
            ))
        }
    };
    let limits = v.limits.pitch_diameter;
    let (Some(lo_lim), Some(hi_lim)) = (limits.min, limits.max) else {
        return Err(Error::Input(
            "capability needs two-sided pitch-diameter limits: a taper thread is gauged by its stand-off"
                .into(),
        ));
    };
    let (values, oks, passed) = sampled(spec, &recut, tip)?;
    let nominal = recut.cut(0.0, None)?;
    let n = spec.samples as f64;
    // Every sample carries the nominal cut's checks, in its order.
    let same_checks = values.iter().all(|v| v.len() == nominal.checks.len());
    let mut sizes = Vec::new();
    for (k, c) in nominal.checks.iter().enumerate() {
        if c.kind != CheckKind::Size || !same_checks {
            continue;
        }
        sizes.push(size_capability(c, k, &values, &oks));
    }
    let d2 = sizes
        .iter()
        .find(|s| s.feature == CheckFeature::PitchDiameter)
        .cloned()
        .ok_or_else(|| Error::Input("no pitch-diameter check to sample".into()))?;
    let d2k = nominal.checks.iter().position(|c| c.feature == CheckFeature::PitchDiameter).unwrap_or(0);
    let (mu, s) = (d2.mean, d2.sigma);
    let (lo, hi) = (lo_lim + 3.0 * s, hi_lim - 3.0 * s);
    let w = spec.wear_per_part;
    // Wear moves a bolt's diameters up, a nut's down.
    let up = v.kind == ThreadKind::External;
    let count = |mu: f64| -> usize {
        let first = if up { mu + 2.0 * w } else { mu - 2.0 * w };
        if !(first >= lo - 1e-12 && first <= hi + 1e-12) {
            return 0;
        }
        let room = if up { hi - mu } else { mu - lo };
        ((room / (2.0 * w)) + 1e-9).floor().max(0.0) as usize
    };
    let (parts_per_edge, best_mu, best_parts) = if w > 0.0 {
        // The best start puts part 1's mean on the limit's side the wear leaves from.
        let best_mu = if hi < lo {
            0.5 * (lo_lim + hi_lim)
        } else if up {
            lo - 2.0 * w
        } else {
            hi + 2.0 * w
        };
        (Some(count(mu)), best_mu, Some(count(best_mu)))
    } else {
        (None, 0.5 * (lo_lim + hi_lim), None)
    };
    // X and every diameter move one for one.
    let shift = best_mu - mu;
    let best_final_x = v.final_x + shift;
    let best_correction = v.correction_for(shift);
    let (h_lo, h_hi) = values.iter().map(|v| v[d2k]).fold((lo_lim, hi_lim), |(a, b), x| (a.min(x), b.max(x)));
    let bins = 40usize;
    let width = ((h_hi - h_lo) / bins as f64).max(1e-9);
    let mut counts = vec![0usize; bins];
    for v in &values {
        let i = (((v[d2k] - h_lo) / width).floor().max(0.0) as usize).min(bins - 1);
        counts[i] += 1;
    }
    let cpk_uncertainty = d2.cpk.map(|c| c * (1.0 / (9.0 * n * c * c) + 1.0 / (2.0 * (n - 1.0))).sqrt());
    let mut notes: Vec<crate::ground::note::Note> = vec![format!(
        "Monte Carlo after JCGM 101: {} parts, seed {}; each part cut with a fresh edge, every pass's X moved by one offset drawn from N(0, {} mm) on the diameter{}",
        spec.samples,
        spec.seed,
        crate::ground::fmt::fmt_num(spec.x_sigma),
        match tip {
            Some((r, t)) => format!(
                ", the tip radius drawn uniformly from {}–{} mm",
                crate::ground::fmt::fmt_num(r - t),
                crate::ground::fmt::fmt_num(r + t)
            ),
            None => String::new(),
        }
    )
    .into()];
    if w > 0.0 {
        notes.push(
            format!(
                "wear {} mm per part radially: part k cut with the wear of k parts (its finishing pass comes last), every diameter {} by 2·k·w; a part is predicted out when its pitch diameter's mean ± 3σ leaves the limits",
                crate::ground::fmt::fmt_num(w),
                if up { "up" } else { "down" }
            )
            .into(),
        );
    }
    notes.push(
        "Cp, Cpk after ISO 22514-2 (normal model); ppm counted among the samples and from the normal model"
            .into(),
    );
    if nominal.lead_deviation.is_none() && v.lead_deviation.is_some() {
        notes.push("the lead deviation's functional check is not sampled: it does not vary with X".into());
    }
    Ok(CapabilityReport {
        verification: v,
        x_sigma: spec.x_sigma,
        tip_radius_tol: spec.tip_radius_tol,
        wear_per_part: w,
        samples: spec.samples,
        seed: spec.seed,
        sizes,
        pass_share: passed as f64 / n,
        parts_per_edge,
        best_final_x,
        best_parts_per_edge: best_parts,
        best_correction,
        histogram: Histogram { lo: h_lo, width, counts },
        cpk_uncertainty,
        notes,
    })
}

/// The spec's spreads, wear and sample count within their bounds.
fn checked_inputs(spec: &CapabilitySpec) -> Result<(), Error> {
    let nonneg = |v: f64, what: &str, max: f64| {
        if v.is_finite() && v >= 0.0 && v <= max {
            Ok(())
        } else {
            Err(Error::Input(format!(
                "{what} {} mm: must be from 0 to {} mm",
                crate::ground::fmt::fmt_shown(v),
                crate::ground::fmt::fmt_num(max)
            )))
        }
    };
    nonneg(spec.x_sigma, "‹x_sigma›", 1.0)?;
    nonneg(spec.tip_radius_tol, "‹tip_radius_tol›", 1.0)?;
    nonneg(spec.wear_per_part, "‹wear_per_part›", 1.0)?;
    // Under a nanometre a part the edge would last beyond any count (1e-300 printed
    // 18446744073709551615 parts, a saturated integer).
    if spec.wear_per_part > 0.0 && spec.wear_per_part < MIN_WEAR_PER_PART {
        return Err(Error::Input(format!(
            "‹wear_per_part› {} mm: a wear is 0 or at least {} mm (1 nm) a part",
            crate::ground::fmt::fmt_shown(spec.wear_per_part),
            crate::ground::fmt::fmt_shown(MIN_WEAR_PER_PART)
        )));
    }
    if !(2..=MAX_SAMPLES).contains(&spec.samples) {
        return Err(Error::Input(format!("‹samples› {}: must be from 2 to {MAX_SAMPLES}", spec.samples)));
    }
    Ok(())
}

/// Every sample cut: each check's value and verdict per part, and how many parts passed. One
/// random stream per sample, so the draws do not depend on the threads.
#[allow(clippy::type_complexity)]
fn sampled(
    spec: &CapabilitySpec,
    recut: &Recut,
    tip: Option<(f64, f64)>,
) -> Result<(Vec<Vec<f64>>, Vec<Vec<bool>>, usize), Error> {
    let stop = crate::ground::cancel::current();
    let runs: Vec<Result<Sampled, Error>> = (0..spec.samples)
        .into_par_iter()
        .map(|i| {
            if let Some(stop) = &stop {
                stop.check()?;
            }
            // One stream per sample: the draws do not depend on which thread takes it.
            let mut rng = ChaCha8Rng::seed_from_u64(spec.seed);
            rng.set_stream(i as u64);
            let z: f64 = StandardNormal.sample(&mut rng);
            let u: f64 = rng.random();
            let dx = spec.x_sigma * z;
            let r = tip.map(|(r, t)| r + t * (2.0 * u - 1.0));
            let c = recut.cut(dx, r)?;
            Ok((c.checks.iter().map(|c| c.value).collect(), c.checks.iter().map(|c| c.ok).collect(), c.pass))
        })
        .collect();
    let mut values: Vec<Vec<f64>> = Vec::with_capacity(spec.samples);
    let mut oks: Vec<Vec<bool>> = Vec::with_capacity(spec.samples);
    let mut passed = 0usize;
    for r in runs {
        let (vals, ok, pass) = r?;
        values.push(vals);
        oks.push(ok);
        passed += usize::from(pass);
    }
    Ok((values, oks, passed))
}

/// One size check's capability over the samples (its `k`th value in each): mean, σ, Cp, Cpk
/// and ppm counted and from the normal model.
fn size_capability(
    c: &crate::analysis::check::Check,
    k: usize,
    values: &[Vec<f64>],
    oks: &[Vec<bool>],
) -> SizeCapability {
    let n = values.len() as f64;
    let xs: Vec<f64> = values.iter().map(|v| v[k]).collect();
    let mean = xs.iter().sum::<f64>() / n;
    let sigma = (xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
    // Under 0.1 nm the spread is float noise, not variation.
    let spread = sigma > 1e-7;
    let cp = match (c.min, c.max) {
        (Some(a), Some(b)) if spread => Some((b - a) / (6.0 * sigma)),
        _ => None,
    };
    let sides: Vec<f64> = [c.max.map(|b| b - mean), c.min.map(|a| mean - a)].into_iter().flatten().collect();
    let cpk = (spread && !sides.is_empty())
        .then(|| sides.iter().fold(f64::INFINITY, |m, s| m.min(*s)) / (3.0 * sigma));
    let out = oks.iter().filter(|o| !o[k]).count() as f64;
    let ppm_normal = spread.then(|| {
        1e6 * (c.min.map_or(0.0, |a| phi((a - mean) / sigma))
            + c.max.map_or(0.0, |b| phi((mean - b) / sigma)))
    });
    SizeCapability {
        feature: c.feature,
        note: c.note.clone(),
        min: c.min,
        max: c.max,
        mean,
        sigma,
        cp,
        cpk,
        ppm_counted: 1e6 * out / n,
        ppm_normal,
    }
}
