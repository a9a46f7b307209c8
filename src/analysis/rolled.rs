//! A rolled external thread (issue 64): the blank it needs and the thread a blank gives, by
//! volume constancy (`geometry::forming`). Named defaults, stated in every report: the dies set
//! the pitch diameter at the middle of the class's d2 limits; their crests form the root at the
//! rounded root's bottom, H/3 under the pitch line (ISO 965-1's d3 = d − 1.2269·P with its
//! largest root radius; the UNR root alike), taken flat; their roots leave the crest free, up to
//! the full crest 3H/8 over the pitch line (the basic form's, P/8 wide).

use crate::geometry::forming::{blank_for_crest, rolled_major, FormProfile, Rolled};
use crate::standards::tolerance::ThreadLimits;
use crate::standards::{Designation, ThreadForm};
use crate::Error;
use serde::Serialize;

/// A rolled thread's blank, and what a given blank gives.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RolledThread {
    /// The pitch diameter the dies are set to: the middle of the class's d2 limits, mm.
    pub pitch_diameter: f64,
    /// The root the dies' crests form, mm (H/3 under the pitch line).
    pub root_diameter: f64,
    /// The full crest, mm (3H/8 over the pitch line).
    pub full_crest: f64,
    /// The blank that fills the crest to the full crest, mm.
    pub blank_for_full_crest: f64,
    /// The blank given, mm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub blank: Option<f64>,
    /// The major diameter the given blank forms, mm (`None`: overfilled, or no blank given).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub major_formed: Option<f64>,
    /// The given blank holds more metal than the teeth: the crest laps over.
    pub overfilled: bool,
    /// The formed major within the class's major-diameter limits (`None` without a blank).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub major_ok: Option<bool>,
    /// The crest stops short of the full crest (a rounded, unfilled crest: not a defect while
    /// the major is within its limits).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub crest_short: Option<bool>,
}

/// The rolled thread of `des` in its external class `limits`, with the blank `blank` (mm) when
/// given. 60° forms only (ISO metric, Unified).
///
/// ```
/// use threadcheck::{parse_designation, limits_for, rolled_thread, ParseOptions, ThreadKind};
/// let des = parse_designation("M10x1.5-6g", ParseOptions::default())?;
/// let l = limits_for(&des, ThreadKind::External)?.unwrap();
/// let r = rolled_thread(&des, &l, None)?;
/// // d2 set at 8.928 (6g's 8.862–8.994); the blank near the pitch diameter, a little over it.
/// assert!((r.pitch_diameter - 8.928).abs() < 1e-9);
/// assert!(r.blank_for_full_crest > 8.928 && r.blank_for_full_crest < 9.0);
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn rolled_thread(
    des: &Designation,
    limits: &ThreadLimits,
    blank: Option<f64>,
) -> Result<RolledThread, Error> {
    let t = &des.thread;
    if !matches!(t.form, ThreadForm::IsoMetric | ThreadForm::Unified) {
        return Err(Error::Input(format!(
            "a rolled blank is computed for the 60° forms (ISO metric, Unified), not {}",
            t.form.name()
        )));
    }
    let (Some(lo), Some(hi)) = (limits.pitch_diameter.min, limits.pitch_diameter.max) else {
        return Err(Error::Input(format!(
            "{}: the class gives no pitch-diameter limits to roll to",
            des.text
        )));
    };
    if let Some(b) = blank.filter(|b| !(b.is_finite() && *b > 0.0)) {
        return Err(Error::Input(format!("‹blank› {b}: a blank is a diameter over 0")));
    }
    let d2 = 0.5 * (lo + hi);
    let h = t.fundamental_height();
    let profile = FormProfile { p: t.pitch, r2: 0.5 * d2, tan_half: t.half_angle().tan() };
    let root = d2 - 2.0 * h / 3.0;
    let full_crest = d2 + 0.75 * h;
    let formed = blank.map(|b| rolled_major(&profile, root, b));
    let major_formed = match formed {
        Some(Rolled::Major(m)) => Some(m.min(full_crest)),
        _ => None,
    };
    let res = limits.resolution;
    // Over the full crest by more than the standard's resolution: the metal laps over.
    let overfilled = matches!(formed, Some(Rolled::Overfilled))
        || matches!(formed, Some(Rolled::Major(m)) if res.round(m) > res.round(full_crest));
    let major_ok = blank.map(|_| {
        !overfilled
            && major_formed.is_some_and(|m| {
                let m = res.round(m);
                limits.major_diameter.min.is_none_or(|lo| m >= res.round(lo))
                    && limits.major_diameter.max.is_none_or(|hi| m <= res.round(hi))
            })
    });
    Ok(RolledThread {
        pitch_diameter: d2,
        root_diameter: root,
        full_crest,
        blank_for_full_crest: blank_for_crest(&profile, root, full_crest),
        blank,
        major_formed,
        overfilled,
        major_ok,
        crest_short: major_formed.map(|m| m < full_crest - 1e-6),
    })
}
