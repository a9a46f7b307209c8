//! The drill a tapped hole asks for: a tap forms the flanks, the drill leaves the minor diameter
//! D1, so a drill passes when its diameter lies within the class's D1 limits.
//!
//! [`drill_that_passes`] gives the middle of D1 and the nearest drill a shop stocks that lies
//! within D1, from `profiles/drills.toml`:
//! - **ISO metric**: ISO 2306's tap drill (the coarse series from its table; the fine series by
//!   the rule every fine row of the published charts follows: D − P on the 0.1 mm series, a half
//!   step to the even tenth), when it lies within the class's D1; otherwise
//!   the metric drill nearest the middle of D1 (a named default: drills every 0.1 mm, every
//!   0.05 mm under 3 mm, as ISO 235's jobber drills are stocked).
//! - **Trapezoidal**: the metric drill nearest the middle of D1 (ISO 2306 has no Tr row).
//! - **Inch forms** (Unified, Whitworth, BSP parallel, Acme): the inch drill nearest the middle
//!   of D1, from the fractional (every 1/64 in), number (#1–#60) and letter (A–Z) gauges; of two
//!   equally near, the smaller (more thread).
//! - **Taper pipe threads** (NPT, ISO 7-1): none; a taper tap's hole is reamed to the taper.

use crate::standards::tolerance::{Limit, Resolution};
use crate::standards::{BasicThread, ThreadForm, MM_PER_INCH};
use serde::Serialize;

/// Where a suggested drill comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum DrillSource {
    /// ISO 2306's table of the coarse series.
    Iso2306Coarse,
    /// ISO 2306's fine series as the published charts give it: D − P on the 0.1 mm series, a
    /// half step to the even tenth.
    Iso2306Fine,
    /// The metric drill (0.1 mm steps, 0.05 mm under 3 mm) nearest the middle of D1.
    MetricSeries,
    /// The inch drill (fractional, number or letter) nearest the middle of D1.
    InchGauge,
}

/// A drill that leaves D1 within its limits.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PassingDrill {
    /// The middle of the class's D1 limits, mm.
    pub middle: f64,
    /// The drill a shop stocks nearest it within the limits, mm (`None` when no stocked drill
    /// lies within them).
    pub diameter: Option<f64>,
    /// Its name on the drill: `8.5`, `#7`, `F`, `27/64`.
    pub name: Option<String>,
    /// Where it comes from.
    pub source: Option<DrillSource>,
}

/// The middle of `d1` and the nearest stocked drill within it, for a tap of `thread`; `None`
/// for a taper pipe thread or when the class gives D1 only one limit. `res` is the standard's
/// resolution: a drill exactly on a limit passes.
///
/// ```
/// use threadcheck::{drill_that_passes, BasicThread, Limit, Resolution};
/// // M10x1.5-6H: D1 8.376 … 8.676 (ISO 965-2); ISO 2306's tap drill is 8.5.
/// let d1 = Limit { min: Some(8.376), max: Some(8.676) };
/// let d = drill_that_passes(&BasicThread::metric(10.0, 1.5), d1, Resolution::Micrometre)?.unwrap();
/// assert_eq!((d.middle, d.diameter), (8.526, Some(8.5)));
/// // 5/8-18 UNF-2B: D1 0.5650 … 0.5780 in (ASME B1.1); no inch drill lies within (9/16 =
/// // 0.5625, 37/64 = 0.5781), the 14.5 mm drill (0.5709 in) does.
/// let d1 = Limit { min: Some(0.565 * 25.4), max: Some(0.578 * 25.4) };
/// let unf = BasicThread { form: threadcheck::ThreadForm::Unified, nominal_diameter: 0.625 * 25.4, pitch: 25.4 / 18.0, ..BasicThread::metric(0.0, 1.0) };
/// let d = drill_that_passes(&unf, d1, Resolution::TenThousandthInch)?.unwrap();
/// assert_eq!((d.diameter, d.name.as_deref()), (Some(14.5), Some("14.5")));
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn drill_that_passes(
    thread: &BasicThread,
    d1: Limit,
    res: Resolution,
) -> Result<Option<PassingDrill>, crate::Error> {
    let (Some(lo), Some(hi)) = (d1.min, d1.max) else { return Ok(None) };
    let middle = res.round(0.5 * (lo + hi));
    let within = |d: f64| res.round(d) >= res.round(lo) && res.round(d) <= res.round(hi);
    let tables = &crate::standards::catalog()?.drills;
    let (d, p) = (thread.nominal_diameter, thread.pitch);
    let pick = |choice: Option<(f64, String, DrillSource)>| match choice {
        Some((dia, name, source)) => {
            PassingDrill { middle, diameter: Some(dia), name: Some(name), source: Some(source) }
        }
        None => PassingDrill { middle, diameter: None, name: None, source: None },
    };
    let metric = || nearest_metric(middle, &within).map(|x| (x, metric_name(x), DrillSource::MetricSeries));
    let out = match thread.form {
        ThreadForm::IsoMetric => {
            let t = &tables.iso2306_coarse;
            let standard = match t.d.iter().position(|&x| (x - d).abs() < 1e-9) {
                Some(i) if is_coarse(d, p)? => (t.drill[i], DrillSource::Iso2306Coarse),
                _ => (fine_series_drill(d - p), DrillSource::Iso2306Fine),
            };
            if within(standard.0) {
                pick(Some((standard.0, metric_name(standard.0), standard.1)))
            } else {
                pick(metric())
            }
        }
        ThreadForm::Trapezoidal => pick(metric()),
        // An inch thread takes an inch drill; where none of the gauges lies within D1 (5/8-18
        // UNF-2B: 9/16 is under, 37/64 over), the metric drill that does (14.5 mm).
        ThreadForm::Unified | ThreadForm::Whitworth | ThreadForm::BspParallel | ThreadForm::Acme => {
            pick(nearest_inch(middle, &within, &tables.inch_drills).or_else(metric))
        }
        ThreadForm::Npt | ThreadForm::Iso7Taper => return Ok(None),
    };
    debug_assert!(out.diameter.is_none_or(within));
    Ok(Some(out))
}

/// The fine series' tap drill as the published charts give it: D − P, on the 0.1 mm series
/// with a half step to the even tenth (M8x0.75 7.25 → 7.2, M12x1.25 10.75 → 10.8, as every
/// fine row of the charts reads), and on the 0.05 mm series under 3 mm (M3x0.35 2.65).
fn fine_series_drill(x: f64) -> f64 {
    if x < 3.0 {
        return (x * 20.0).round() / 20.0;
    }
    let tenths = x * 10.0;
    let r = tenths.round();
    // A half step (within float noise) goes to the even tenth.
    let r = if ((tenths - tenths.floor()) - 0.5).abs() < 1e-6 {
        let down = tenths.floor();
        if down % 2.0 == 0.0 {
            down
        } else {
            down + 1.0
        }
    } else {
        r
    };
    r / 10.0
}

/// Whether `p` is the coarse pitch of ISO 261's size `d`.
fn is_coarse(d: f64, p: f64) -> Result<bool, crate::Error> {
    let series = &crate::standards::catalog()?.iso.series.sizes;
    Ok(series.iter().any(|s| (s.d - d).abs() < 1e-9 && s.coarse.is_some_and(|c| (c - p).abs() < 1e-9)))
}

/// A metric drill's name: its diameter in mm, without trailing zeros.
fn metric_name(d: f64) -> String {
    crate::ground::fmt::fmt_num(d)
}

/// The metric drill nearest `middle` that passes: 0.1 mm steps, 0.05 mm under 3 mm.
fn nearest_metric(middle: f64, within: &impl Fn(f64) -> bool) -> Option<f64> {
    let step = if middle < 3.0 { 0.05 } else { 0.1 };
    let k = (middle / step).round();
    // The nearest step, then its neighbours outward: the first one within the limits.
    (0..=2)
        .flat_map(|i| [k - i as f64, k + i as f64])
        .map(|k| (k * step * 100.0).round() / 100.0)
        .filter(|&x| x > 0.0 && within(x))
        .min_by(|a, b| {
            ((a - middle).abs(), *a)
                .partial_cmp(&((b - middle).abs(), *b))
                .unwrap_or(std::cmp::Ordering::Equal)
        })
}

/// The diameter, mm, of an inch drill named by its gauge: a number drill (`#29`, 1 to 60), a
/// letter drill (`F`, A to Z) or a fractional one (`5/16`, a fraction of 2 to 64 parts).
///
/// ```
/// use threadcheck::inch_drill;
/// assert_eq!(inch_drill("5/16"), Some(0.3125 * 25.4));
/// assert!((inch_drill("#29").unwrap() - 0.136 * 25.4).abs() < 1e-9);
/// assert!((inch_drill("F").unwrap() - 0.257 * 25.4).abs() < 1e-9);
/// assert_eq!(inch_drill("#61"), None);
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn inch_drill(name: &str) -> Option<f64> {
    let gauge = &crate::standards::catalog().ok()?.drills.inch_drills;
    let inches = if let Some(n) = name.strip_prefix('#') {
        let n: usize = n.parse().ok()?;
        *gauge.number.get(n.checked_sub(1)?)?
    } else if let Some((a, b)) = name.split_once('/') {
        let (a, b): (u32, u32) = (a.parse().ok()?, b.parse().ok()?);
        if !(2..=64).contains(&b) || !b.is_power_of_two() || a == 0 || a >= 4 * b {
            return None;
        }
        f64::from(a) / f64::from(b)
    } else {
        let mut c = name.chars();
        let (Some(l), None) = (c.next(), c.next()) else { return None };
        if !l.is_ascii_uppercase() {
            return None;
        }
        *gauge.letter.get(usize::from(l as u8 - b'A'))?
    };
    Some(inches * MM_PER_INCH)
}

/// The inch drill nearest `middle` (mm) that passes, of the fractional, number and letter
/// gauges; of two equally near, the smaller.
fn nearest_inch(
    middle: f64,
    within: &impl Fn(f64) -> bool,
    gauge: &crate::standards::data::InchDrills,
) -> Option<(f64, String, DrillSource)> {
    let mut all: Vec<(f64, String)> = Vec::new();
    for (i, &d) in gauge.number.iter().enumerate() {
        all.push((d, format!("#{}", i + 1)));
    }
    for (i, &d) in gauge.letter.iter().enumerate() {
        all.push((d, char::from(b'A' + i as u8).to_string()));
    }
    let m_in = middle / MM_PER_INCH;
    let n = (m_in * 64.0).round() as i64;
    for k in (n - 2).max(1)..=n + 2 {
        all.push((k as f64 / 64.0, fraction(k)));
    }
    all.into_iter()
        .map(|(d, name)| (d * MM_PER_INCH, name))
        .filter(|(d, _)| within(*d))
        // Nearest at the gauge's 0.0001 in: a tie goes to the smaller drill.
        .min_by(|a, b| {
            let key =
                |d: f64| (((d - middle).abs() / MM_PER_INCH * 1e5).round() as i64, (d * 1e6).round() as i64);
            key(a.0).cmp(&key(b.0))
        })
        .map(|(d, name)| (d, name, DrillSource::InchGauge))
}

/// `k`/64 in lowest terms, with whole inches: `27/64`, `1/2`, `1 1/4`.
fn fraction(k: i64) -> String {
    let (whole, mut num) = (k / 64, k % 64);
    let mut den = 64;
    while num > 0 && num % 2 == 0 {
        num /= 2;
        den /= 2;
    }
    match (whole, num) {
        (0, _) => format!("{num}/{den}"),
        (w, 0) => format!("{w}"),
        (w, _) => format!("{w} {num}/{den}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fine rows of the charts (profiles/drills.toml's sources): M6x0.75 5.2, M8x0.75 7.2,
    /// M8x1 7.0, M10x0.75 9.2, M10x1.25 8.8, M12x1.25 10.8, M14x1.25 12.8, M2.5x0.35 2.15,
    /// M3x0.35 2.65.
    #[test]
    fn the_fine_series_rule_reads_as_the_charts() {
        for (d, p, drill) in [
            (6.0, 0.75, 5.2),
            (8.0, 0.75, 7.2),
            (8.0, 1.0, 7.0),
            (10.0, 0.75, 9.2),
            (10.0, 1.25, 8.8),
            (12.0, 1.25, 10.8),
            (14.0, 1.25, 12.8),
            (2.5, 0.35, 2.15),
            (3.0, 0.35, 2.65),
        ] {
            assert!((fine_series_drill(d - p) - drill).abs() < 1e-9, "M{d}x{p}");
        }
    }

    #[test]
    fn fractions_are_in_lowest_terms() {
        assert_eq!(fraction(27), "27/64");
        assert_eq!(fraction(32), "1/2");
        assert_eq!(fraction(80), "1 1/4");
        assert_eq!(fraction(128), "2");
    }
}
