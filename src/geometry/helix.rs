//! The thread a thread mill leaves, as geometry: the cutter (one tooth form or several rows of
//! them), the helices it moves on, and the farthest (internal) or nearest (external) radius it
//! reaches at each height of the part's axial half-plane.
//!
//! **The envelope, exactly.** Take the part's axis as Z and the half-plane θ = 0 (direction +X
//! from the hole's centre). With the cutter's axis at distance R from the part's and at angle ψ
//! from the half-plane, its tooth centre at height zc(ψ) (the helix), the point (r, z) of the
//! half-plane lies inside the cutter when its distance from the cutter's axis, √(r² + R² −
//! 2rR·cos ψ), is at most the cutter's radius ρ(z − zc) at that height. So the largest radius an
//! internal thread's cutter reaches at height z is
//!
//!   r(z) = max over the helix of R·cos ψ + √(ρ(z − zc(ψ))² − R²·sin² ψ)
//!
//! (an external thread's cutter, outside the bolt, the least: R·cos ψ − √(…)). At ψ = 0 this is
//! R + ρ(z − zc): the tooth profile moved out by R; every other ψ can only add to it, and adds
//! more the larger the cutter is against the hole. The maximum over ψ is found on a grid of the
//! helix parameter and refined by golden section; the profile then goes through the same
//! measurement and class checks as a turned thread.
//!
//! The cutter: `diameter` over the tooth's tip, the tooth's included `angle` and tip radius, a
//! tooth as deep as the thread's fundamental triangle H below the tip (deeper than any standard
//! thread, so the neck never reaches it: a named default). Under cutter radius compensation (G41/G42) the helix
//! radius is the programmed one moved by the compensation value given (the D register's).

use crate::Error;
use serde::Serialize;

/// A thread mill: one tooth form (single-form) or `rows` of them `row_pitch` apart along its
/// axis (multi-form), the first at the programmed point and the others above it, toward the
/// shank (a named default).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Cutter {
    /// Diameter over the tooth's tip, mm.
    pub diameter: f64,
    /// The tooth's included angle, degrees.
    pub angle_deg: f64,
    /// The tooth's tip radius, mm.
    pub tip_radius: f64,
    /// Rows of teeth: 1 for a single-form cutter.
    pub rows: u32,
    /// The rows' axial spacing, mm (0 for a single-form cutter).
    pub row_pitch: f64,
}

/// A thread mill's TOML file, as a tool table names it (`[tools] 12 = "thread-mill.toml"`).
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct CutterFile {
    kind: String,
    diameter: f64,
    #[serde(default = "sixty")]
    angle: f64,
    #[serde(default)]
    tip_radius: f64,
    #[serde(default)]
    flat: f64,
    #[serde(default = "one")]
    rows: u32,
    #[serde(default)]
    row_pitch: Option<f64>,
}

fn sixty() -> f64 {
    60.0
}

fn one() -> u32 {
    1
}

impl Cutter {
    /// A single-form cutter.
    ///
    /// ```
    /// use threadcheck::Cutter;
    /// let c = Cutter::single_form(12.0, 60.0, 0.0);
    /// assert_eq!((c.rows, c.row_pitch), (1, 0.0));
    /// ```
    pub fn single_form(diameter: f64, angle_deg: f64, tip_radius: f64) -> Cutter {
        Cutter { diameter, angle_deg, tip_radius, rows: 1, row_pitch: 0.0 }
    }

    /// Reads a thread mill's TOML: `kind = "thread-mill"`, `diameter` (mm, over the tooth's tip),
    /// `angle` (the tooth's included angle, 60 by default), `tip_radius` (0), `rows` (1: a
    /// single-form cutter) and, for a multi-form cutter (`rows` > 1), `row_pitch` (mm).
    ///
    /// ```
    /// use threadcheck::Cutter;
    /// let c = Cutter::from_toml("kind = \"thread-mill\"\ndiameter = 14.0\n", "tm.toml")?;
    /// assert_eq!((c.diameter, c.angle_deg, c.tip_radius), (14.0, 60.0, 0.0));
    /// # Ok::<(), threadcheck::Error>(())
    /// ```
    pub fn from_toml(text: &str, source: &str) -> Result<Cutter, Error> {
        let ferr = |m: String| Error::File { file: source.to_string(), message: m };
        let f: CutterFile =
            toml::from_str(text).map_err(|e| crate::ground::error::toml_error(&e, text, source))?;
        if f.kind != "thread-mill" {
            return Err(ferr(format!(
                "kind = \"{}\": a thread mill's file says kind = \"thread-mill\"",
                f.kind
            )));
        }
        let row_pitch = row_pitch_of(f.rows, f.row_pitch).map_err(ferr)?;
        if f.flat != 0.0 {
            return Err(ferr(
                "flat: a flat tooth tip is not modelled; give the tip's radius (tip_radius)".into(),
            ));
        }
        Ok(Cutter {
            diameter: f.diameter,
            angle_deg: f.angle,
            tip_radius: f.tip_radius,
            rows: f.rows,
            row_pitch,
        })
    }

    /// The cutter with `rows` rows of teeth `row_pitch` mm apart (a multi-form cutter; `rows` 1
    /// and no row pitch: single-form).
    ///
    /// ```
    /// use threadcheck::Cutter;
    /// let c = Cutter::single_form(14.0, 60.0, 0.0).with_rows(8, Some(1.5))?;
    /// assert_eq!((c.rows, c.row_pitch), (8, 1.5));
    /// assert!(Cutter::single_form(14.0, 60.0, 0.0).with_rows(8, None).is_err());
    /// # Ok::<(), threadcheck::Error>(())
    /// ```
    pub fn with_rows(self, rows: u32, row_pitch: Option<f64>) -> Result<Cutter, Error> {
        let row_pitch = row_pitch_of(rows, row_pitch).map_err(Error::Input)?;
        Ok(Cutter { rows, row_pitch, ..self })
    }

    /// The cutter's radius at axial offset `h` from its first tooth's centre, down to `neck`:
    /// the largest of its rows' (the nearest row and its neighbours).
    pub(crate) fn rho(&self, h: f64, neck: f64) -> f64 {
        if self.rows <= 1 {
            return self.tooth_rho(h, neck);
        }
        let last = i64::from(self.rows - 1);
        let k = ((h / self.row_pitch).round() as i64).clamp(0, last);
        ((k - 1).max(0)..=(k + 1).min(last))
            .map(|j| self.tooth_rho(h - j as f64 * self.row_pitch, neck))
            .fold(neck, f64::max)
    }

    /// The axial length from the first row's centre to the last's, mm.
    pub(crate) fn span(&self) -> f64 {
        f64::from(self.rows.saturating_sub(1)) * self.row_pitch
    }

    /// One tooth's radius at axial offset `h` from its centre, down to `neck`.
    pub(crate) fn tooth_rho(&self, h: f64, neck: f64) -> f64 {
        let half = (0.5 * self.angle_deg).to_radians();
        let tip = 0.5 * self.diameter;
        let rr = self.tip_radius;
        let h = h.abs();
        let v = if h <= rr * half.cos() {
            tip - rr + (rr * rr - h * h).max(0.0).sqrt()
        } else {
            // The flank, tangent to the tip arc: its sharp apex lies rr(1/sin − 1) above the tip.
            let apex = tip + rr * (1.0 / half.sin() - 1.0);
            apex - h / half.tan()
        };
        v.max(neck)
    }

    /// The axial half width of the tooth above `neck`.
    pub(crate) fn half_width(&self, neck: f64) -> f64 {
        let half = (0.5 * self.angle_deg).to_radians();
        let apex = 0.5 * self.diameter + self.tip_radius * (1.0 / half.sin() - 1.0);
        ((apex - neck) * half.tan()).max(0.0)
    }
}

/// A cutter's row pitch from its rows and the pitch given: 0 for one row; a multi-form cutter
/// needs one between 0 and 100 mm.
pub(crate) fn row_pitch_of(rows: u32, row_pitch: Option<f64>) -> Result<f64, String> {
    if !(1..=200).contains(&rows) {
        return Err(format!("rows = {rows}: from 1 (a single-form cutter) to 200"));
    }
    match (rows, row_pitch) {
        (1, None) => Ok(0.0),
        (1, Some(p)) => Err(format!("row_pitch = {p} with rows = 1: a single-form cutter has no row pitch")),
        (_, None) => {
            Err(format!("rows = {rows}: a multi-form cutter needs row_pitch, the rows' spacing in mm"))
        }
        (_, Some(p)) if !(p.is_finite() && p > 0.0 && p < 100.0) => {
            Err(format!("row_pitch = {p}: a length over 0 and under 100 mm"))
        }
        (_, Some(p)) => Ok(p),
    }
}

/// One helix of the program.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Helix {
    /// Its program line.
    pub line: usize,
    /// The helix axis (X, Y), mm.
    pub centre: [f64; 2],
    /// The cutter centre's distance from it, mm.
    pub radius: f64,
    /// The programmed path's distance from it, mm (the centre's, unless G41/G42 moves it).
    pub programmed_radius: f64,
    /// How much the cutter centre's radius grows from the helix's start to its end, mm: 0 on a
    /// circular helix; a taper thread's helix spirals, its radius linear in the angle (a named
    /// reading of an arc whose end lies off its start's circle, as the controls' spiral
    /// interpolation moves it).
    pub radius_change: f64,
    /// Z at its start and end, mm.
    pub z: [f64; 2],
    /// Its sweep, degrees (positive counter-clockwise, G3).
    pub sweep_deg: f64,
    /// Z travel per revolution, mm (the lead the helix cuts).
    pub lead: f64,
    /// Climb milling (else conventional), with the spindle turning clockwise.
    pub climb: bool,
    /// The feed the program writes for it, mm/min: the cutter centre's (`None` when not given).
    pub feed: Option<f64>,
    /// The angle of its start from the measured half-plane, radians.
    #[serde(skip)]
    pub(crate) angle_start: f64,
}

/// The helix parameter range (radians from its start) whose teeth reach height `z`: z − zc
/// within [−hw, span + hw]; `None` when none does.
pub(crate) fn reach_range(h: &Helix, cutter: &Cutter, hw: f64, z: f64) -> Option<(f64, f64)> {
    let sweep = h.sweep_deg.to_radians().abs();
    let dz = h.z[1] - h.z[0];
    let ta = (z - cutter.span() - hw - h.z[0]) * sweep / dz;
    let tb = (z + hw - h.z[0]) * sweep / dz;
    let (t_a, t_b) = (ta.min(tb).max(0.0), ta.max(tb).min(sweep));
    (t_a <= t_b).then_some((t_a, t_b))
}

/// The samples [`reach`] takes over a parameter range (800 a radian), before its 60-step
/// golden-section refinement.
pub(crate) fn samples(t_a: f64, t_b: f64) -> usize {
    (((t_b - t_a) * 800.0).ceil() as usize).clamp(8, 200_000)
}

/// The evaluations of the cutter's reach that cutting the section at heights `zs` takes, from
/// a sample of 33 of them: counted before the section is cut, with the pruning [`reach`] does
/// (`beyond` as it is given there).
pub(crate) fn section_cost(
    hs: &[Helix],
    cutter: &Cutter,
    neck: f64,
    zs: &[f64],
    internal: bool,
    beyond: f64,
) -> f64 {
    let hw = cutter.half_width(neck);
    let k = 32usize;
    let per: f64 = (0..=k)
        .map(|i| {
            let z = zs[i * (zs.len() - 1) / k];
            let thr = threshold(hs, cutter, neck, z, internal, beyond);
            hs.iter()
                .filter_map(|h| reach_range(h, cutter, hw, z).map(|r| (h, r)))
                .map(|(h, (a, b))| {
                    let step = (b - a) / samples(a, b) as f64;
                    let n: usize = windows(h, cutter, a, b, step, internal, thr)
                        .iter()
                        .map(|&(i0, i1)| i1 + 1 - i0)
                        .sum();
                    if n == 0 {
                        1.0
                    } else {
                        n as f64 + 122.0
                    }
                })
                .sum::<f64>()
        })
        .sum();
    per / (k + 1) as f64 * zs.len() as f64
}

/// The reach at height `z` that a point of the helices must pass to matter: the better of the
/// tooth profile's own (the cutter where it crosses the half-plane, reached for certain) and
/// `beyond`, the blank's radius, which the section is clamped to anyway.
fn threshold(hs: &[Helix], cutter: &Cutter, neck: f64, z: f64, internal: bool, beyond: f64) -> f64 {
    let tooth = reach_crossings(hs, cutter, neck, z, internal);
    match (tooth, internal) {
        (Some(t), true) => t.max(beyond),
        (Some(t), false) => t.min(beyond),
        (None, _) => beyond,
    }
}

/// The runs of sample indices `i` (t = t_a + i·step, 0 ≤ i ≤ n) where helix `h`'s cutter can
/// reach past `thr` at all, each widened by a sample either side; the bound is the cutter at its
/// largest radius ρmax (its tip): an internal cutter reaches at most R·cos ψ + ρmax on the
/// half-plane's line; an external one, outside the bolt (R > ρmax), at least where a disc of
/// radius ρmax at angle ψ meets it, which moves out as |ψ| grows. Anything else is sampled whole.
fn windows(
    h: &Helix,
    cutter: &Cutter,
    t_a: f64,
    t_b: f64,
    step: f64,
    internal: bool,
    thr: f64,
) -> Vec<(usize, usize)> {
    let n = samples(t_a, t_b);
    let whole = vec![(0, n)];
    let rho = 0.5 * cutter.diameter;
    let r_end = h.radius + h.radius_change;
    let (r_lo, r_hi) = (h.radius.min(r_end), h.radius.max(r_end));
    // The half-width of the ψ window around each crossing of the half-plane (ψ = 2πk).
    let half = if internal {
        if !thr.is_finite() || thr - rho <= 0.0 || r_hi <= 0.0 {
            return whole;
        }
        let c_min = (thr - rho) / r_hi;
        if c_min > 1.0 {
            return Vec::new();
        }
        c_min.acos()
    } else {
        if !thr.is_finite() || r_lo <= rho || thr <= 0.0 {
            return whole;
        }
        if thr <= r_lo - rho {
            return Vec::new();
        }
        if thr * thr >= r_lo * r_lo - rho * rho {
            (rho / r_lo).asin()
        } else {
            ((r_lo * r_lo + thr * thr - rho * rho) / (2.0 * r_lo * thr)).clamp(-1.0, 1.0).acos()
        }
    };
    if half >= std::f64::consts::PI {
        return whole;
    }
    let dir = h.sweep_deg.signum();
    let to_t = |psi: f64| dir * (psi - h.angle_start);
    let mut out: Vec<(usize, usize)> = Vec::new();
    for k in crossings(h, t_a, t_b) {
        let centre = k as f64 * std::f64::consts::TAU;
        let (a, b) = (to_t(centre - half), to_t(centre + half));
        let (a, b) = (a.min(b) - step, a.max(b) + step);
        if b < t_a || a > t_b {
            continue;
        }
        let i0 = (((a - t_a) / step).floor().max(0.0)) as usize;
        let i1 = (((b - t_a) / step).ceil().max(0.0) as usize).min(n);
        if i0 > i1 {
            continue;
        }
        out.push((i0, i1));
    }
    // A clockwise helix's windows come last first: in order, then the overlapping ones joined.
    out.sort_unstable();
    let mut runs: Vec<(usize, usize)> = Vec::with_capacity(out.len());
    for (i0, i1) in out {
        match runs.last_mut() {
            Some(last) if i0 <= last.1 + 1 => last.1 = last.1.max(i1),
            _ => runs.push((i0, i1)),
        }
    }
    runs
}

/// The turns k whose crossing of the half-plane (ψ = angle_start + dir·t = k·2π) may fall in the
/// parameter range [t_a, t_b], one either side to spare: k runs between its values at t_a and
/// t_b (a clockwise helix's k falls as t grows; counting up from t_a missed its crossings).
fn crossings(h: &Helix, t_a: f64, t_b: f64) -> std::ops::RangeInclusive<i64> {
    let k_of = |t: f64| (h.angle_start + h.sweep_deg.signum() * t) / std::f64::consts::TAU;
    let (k_lo, k_hi) = (k_of(t_a).min(k_of(t_b)), k_of(t_a).max(k_of(t_b)));
    (k_lo.floor() as i64 - 1)..=(k_hi.ceil() as i64 + 1)
}

/// The reach of the tooth profile alone: the cutter where it crosses the half-plane (ψ = 0
/// mod 2π), over every helix.
fn reach_crossings(hs: &[Helix], cutter: &Cutter, neck: f64, z: f64, internal: bool) -> Option<f64> {
    let hw = cutter.half_width(neck);
    let mut best: Option<f64> = None;
    let better = |a: f64, b: f64| if internal { a > b } else { a < b };
    for h in hs {
        let Some((t_a, t_b)) = reach_range(h, cutter, hw, z) else { continue };
        let sweep = h.sweep_deg.to_radians().abs();
        let dir = h.sweep_deg.signum();
        for k in crossings(h, t_a, t_b) {
            let t = dir * (k as f64 * std::f64::consts::TAU - h.angle_start);
            if t >= t_a - 1e-12 && t <= t_b + 1e-12 {
                if let Some(v) = eval_at(h, cutter, neck, z, internal, t.clamp(0.0, sweep)) {
                    if best.is_none_or(|b| better(v, b)) {
                        best = Some(v);
                    }
                }
            }
        }
    }
    best
}

/// The reach on the half-plane's line of helix `h`'s cutter at parameter `t` (radians from
/// its start), at height `z`; `None` where the cutter does not meet the line (or, outside a
/// bolt, meets it only behind the axis).
fn eval_at(h: &Helix, cutter: &Cutter, neck: f64, z: f64, internal: bool, t: f64) -> Option<f64> {
    let sweep = h.sweep_deg.to_radians().abs();
    let dir = h.sweep_deg.signum();
    let zc = h.z[0] + (h.z[1] - h.z[0]) * t / sweep;
    let psi = h.angle_start + dir * t;
    let (s, c) = psi.sin_cos();
    let rho = cutter.rho(z - zc, neck);
    let radius = h.radius + h.radius_change * t / sweep;
    let q = rho * rho - radius * radius * s * s;
    if q < 0.0 {
        return None;
    }
    // The cutter covers r from R·cos ψ − √q to R·cos ψ + √q on the half-plane's line; of
    // a bolt it removes from the outside in, so only a chord reaching r > 0 counts.
    let (lo, hi) = (radius * c - q.sqrt(), radius * c + q.sqrt());
    if internal {
        Some(hi)
    } else if hi > 0.0 {
        Some(lo.max(0.0))
    } else {
        None
    }
}

/// The farthest (internal) or nearest (external) radius the cutter reaches at height `z` in
/// the half-plane at angle 0 from the helix axis, over every helix; `None` when none reaches it.
/// Only reach past `beyond` (the blank's radius, which the caller clamps the section to; ±∞ for
/// none) is sought: a reach that does not pass it may come back as any value that does not
/// either. The helix is sampled only where the cutter can pass both `beyond` and the tooth
/// profile's own reach ([`windows`]), which leaves the result as sampling it all would.
pub(crate) fn reach(
    hs: &[Helix],
    cutter: &Cutter,
    neck: f64,
    z: f64,
    internal: bool,
    only_psi0: bool,
    beyond: f64,
) -> Option<f64> {
    if only_psi0 {
        return reach_crossings(hs, cutter, neck, z, internal);
    }
    reach_sampled(hs, cutter, neck, z, internal, Some(beyond))
}

/// [`reach`] sampling each helix's whole range when `prune` is `None`.
fn reach_sampled(
    hs: &[Helix],
    cutter: &Cutter,
    neck: f64,
    z: f64,
    internal: bool,
    prune: Option<f64>,
) -> Option<f64> {
    let hw = cutter.half_width(neck);
    let tooth = reach_crossings(hs, cutter, neck, z, internal);
    let thr = prune.map(|beyond| threshold(hs, cutter, neck, z, internal, beyond));
    let better = |a: f64, b: f64| if internal { a > b } else { a < b };
    // The tooth profile's reach is reached for certain: the start of the search.
    let mut best = tooth;
    for h in hs {
        let Some((t_a, t_b)) = reach_range(h, cutter, hw, z) else { continue };
        let eval = |t: f64| eval_at(h, cutter, neck, z, internal, t);
        let n = samples(t_a, t_b);
        let step = (t_b - t_a) / n as f64;
        let runs = match thr {
            Some(thr) => windows(h, cutter, t_a, t_b, step, internal, thr),
            None => vec![(0, n)],
        };
        let mut top: Option<(f64, f64)> = None;
        for (i0, i1) in runs {
            for i in i0..=i1 {
                let t = t_a + step * i as f64;
                if let Some(v) = eval(t) {
                    if top.is_none_or(|(_, b)| better(v, b)) {
                        top = Some((t, v));
                    }
                }
            }
        }
        let Some((t0, mut v0)) = top else { continue };
        // Golden-section refinement within one step either side.
        let (mut lo, mut hi) = ((t0 - step).max(t_a), (t0 + step).min(t_b));
        let g = 0.618_033_988_749_895;
        let score = |t: f64| eval(t).map(|v| if internal { v } else { -v }).unwrap_or(f64::NEG_INFINITY);
        for _ in 0..60 {
            let a = hi - g * (hi - lo);
            let b = lo + g * (hi - lo);
            if score(a) > score(b) {
                hi = b;
            } else {
                lo = a;
            }
        }
        if let Some(v) = eval(0.5 * (lo + hi)) {
            if better(v, v0) {
                v0 = v;
            }
        }
        if best.is_none_or(|b| better(v0, b)) {
            best = Some(v0);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A helix run backwards passes the same places: six turns of G3 spiralling in from
    /// (7.3, 0, Z0) to (7, 0, Z9), 1.5 mm a turn (a taper's), and the same path as G2 falling
    /// from Z9. Under a comb cutter reaching five turns of it, each height's section is the same,
    /// the tooth profile alone too (the clockwise helix's crossings of the section were counted
    /// from the wrong end, so only two turns of its reach were found, and on a spiral the
    /// farthest row was missed).
    #[test]
    fn a_helix_run_backwards_cuts_the_same_section() {
        let cutter = Cutter::single_form(6.0, 60.0, 0.0).with_rows(5, Some(1.5)).unwrap();
        let up = Helix {
            line: 1,
            centre: [0.0, 0.0],
            radius: 7.3,
            programmed_radius: 7.3,
            radius_change: -0.3,
            z: [0.0, 9.0],
            sweep_deg: 6.0 * 360.0,
            lead: 1.5,
            climb: true,
            feed: None,
            angle_start: 0.0,
        };
        let down = Helix {
            radius: 7.0,
            programmed_radius: 7.0,
            radius_change: 0.3,
            z: [9.0, 0.0],
            sweep_deg: -6.0 * 360.0,
            climb: false,
            ..up.clone()
        };
        let neck = 3.0 - 1.3;
        for i in 0..=700 {
            let z = 2.0 + 0.01 * i as f64;
            for only_psi0 in [true, false] {
                let a =
                    reach(std::slice::from_ref(&up), &cutter, neck, z, true, only_psi0, f64::NEG_INFINITY);
                let b =
                    reach(std::slice::from_ref(&down), &cutter, neck, z, true, only_psi0, f64::NEG_INFINITY);
                let (Some(a), Some(b)) = (a, b) else { panic!("z {z}: {a:?} {b:?}") };
                assert!((a - b).abs() < 1e-7, "z {z}, tooth alone {only_psi0}: {a} {b}");
            }
        }
    }

    /// Sampling a helix only where its cutter can pass the tooth profile's reach and the blank
    /// leaves the section as sampling it whole: internal and external, single-form and comb,
    /// circles and spirals, climb and conventional, at heights over the whole of their reach.
    #[test]
    fn the_pruned_reach_is_the_whole_reach() {
        let mut checked = 0;
        for (internal, radius, change, d, rows, blank) in [
            (true, 2.05, 0.0, 11.9, 5u32, 14.0),
            (true, 1.3, 0.0, 11.9, 5, 14.0),
            (true, 3.0, 0.2, 6.0, 1, 15.0),
            (true, 5.0, 0.0, 8.0, 1, 17.5),
            (false, 9.0, 0.0, 6.0, 1, 20.0),
            (false, 8.2, -0.3, 6.0, 3, 20.0),
            (false, 11.0, 0.0, 12.0, 1, 20.0),
        ] {
            for g3 in [true, false] {
                let cutter = if rows == 1 {
                    Cutter::single_form(d, 60.0, 0.05)
                } else {
                    Cutter::single_form(d, 60.0, 0.05).with_rows(rows, Some(2.0)).unwrap()
                };
                let h = Helix {
                    line: 1,
                    centre: [0.0, 0.0],
                    radius,
                    programmed_radius: radius,
                    radius_change: change,
                    z: [-6.0, 0.0],
                    sweep_deg: if g3 { 3.0 * 360.0 } else { -3.0 * 360.0 },
                    lead: 2.0,
                    climb: g3,
                    feed: None,
                    angle_start: 0.37,
                };
                let neck = 0.5 * d - 2.0 * 0.866;
                let bound = 0.5 * blank;
                for i in 0..=300 {
                    let z = -8.0 + 0.06 * i as f64 + cutter.span() * i as f64 / 300.0;
                    let a = reach(std::slice::from_ref(&h), &cutter, neck, z, internal, false, bound);
                    let b = reach_sampled(std::slice::from_ref(&h), &cutter, neck, z, internal, None);
                    let clamp = |r: Option<f64>| match (r, internal) {
                        (Some(r), true) => r.max(bound),
                        (Some(r), false) => r.min(bound),
                        (None, _) => bound,
                    };
                    let (a, b) = (clamp(a), clamp(b));
                    assert!(
                        (a - b).abs() < 1e-9 || (if internal { a > b } else { a < b }),
                        "internal {internal}, R {radius}, g3 {g3}, z {z}: pruned {a}, whole {b}"
                    );
                    assert!(
                        (a - b).abs() < 1e-7,
                        "internal {internal}, R {radius}, g3 {g3}, z {z}: pruned {a}, whole {b}"
                    );
                    checked += 1;
                }
            }
        }
        assert_eq!(checked, 7 * 2 * 301);
    }
}
