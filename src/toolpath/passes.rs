//! Passes and generated pass plans: infeed strategies and depth schedules.
//!
//! A [`Pass`] is where the tool tip runs during one threading move. In the axial section it
//! leaves one imprint of the insert per lead, at `z_start + k·Ph` along the feed direction.

use crate::ground::bounds::MAX_PASSES;
use crate::standards::ThreadKind;
use crate::Error;
use serde::Serialize;

/// One threading pass: the tip's diameter and axial position at both ends of the move.
///
/// X values are tip **diameters** (mm). `z_start` → `z_end` is the direction of feed (usually
/// towards the chuck, decreasing Z). For a parallel thread `x_start == x_end`; a taper or a
/// run-out changes X linearly with Z.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, serde::Deserialize)]
pub struct Pass {
    /// 1-based position in the cutting order.
    pub index: usize,
    /// Tip diameter at `z_start`, mm.
    pub x_start: f64,
    /// Tip diameter at `z_end`, mm.
    pub x_end: f64,
    /// Z where the threading move starts, mm.
    pub z_start: f64,
    /// Z where the threading move ends, mm.
    pub z_end: f64,
    /// Z of one crossing of the helix with the half-plane, mm: the pass crosses at
    /// `z_phase + k·lead` for whole k. It is `z_start` for a single move; a later segment of a
    /// synchronised chain (G32/G33 blocks one after the other) continues the chain's helix: the
    /// first segment's phase at the same lead, the turns made so far carried on at another.
    pub z_phase: f64,
    /// Lead (axial advance per revolution), mm.
    pub lead: f64,
    /// Which start of a multi-start thread (0-based); its grooves are offset by this many pitches,
    /// already included in `z_start`.
    pub start: u32,
    /// The program line the pass came from (1-based), `None` for generated plans.
    pub source_line: Option<usize>,
    /// Length of Z (mm) at the start of the move over which X ramps in from `x_taper`
    /// (LinuxCNC entry taper); 0 for none.
    pub taper_in: f64,
    /// Length of Z (mm) at the end of the move over which X ramps out to `x_taper` (Fanuc
    /// chamfer, LinuxCNC exit taper, a run-out block); 0 for none.
    pub taper_out: f64,
    /// Tip diameter at the outer ends of the tapers, mm (usually the crest line).
    pub x_taper: f64,
}

impl Pass {
    /// A parallel pass without tapers: tip on diameter `x` from `z_start` to `z_end`.
    pub fn parallel(index: usize, x: f64, z_start: f64, z_end: f64, lead: f64) -> Pass {
        Pass {
            index,
            x_start: x,
            x_end: x,
            z_start,
            z_end,
            z_phase: z_start,
            lead,
            start: 0,
            source_line: None,
            taper_in: 0.0,
            taper_out: 0.0,
            x_taper: x,
        }
    }

    /// Direction of feed along Z: −1 towards the chuck, +1 away from it.
    pub fn feed_direction(&self) -> f64 {
        if self.z_end < self.z_start {
            -1.0
        } else {
            1.0
        }
    }

    /// Tip diameter of the main line at `z` (linear between `x_start` and `x_end`), mm.
    fn x_main(&self, z: f64) -> f64 {
        let span = self.z_end - self.z_start;
        if span == 0.0 {
            return self.x_end;
        }
        let t = ((z - self.z_start) / span).clamp(0.0, 1.0);
        self.x_start + t * (self.x_end - self.x_start)
    }

    /// Tip diameter where the move crosses axial position `z`, mm: the main line, ramped from or
    /// to `x_taper` over the entry and exit tapers.
    pub fn x_at(&self, z: f64) -> f64 {
        let main = self.x_main(z);
        let from_start = (z - self.z_start).abs();
        let to_end = (self.z_end - z).abs();
        if self.taper_out > 0.0 && to_end < self.taper_out {
            let t = 1.0 - to_end / self.taper_out;
            return main + t * (self.x_taper - main);
        }
        if self.taper_in > 0.0 && from_start < self.taper_in {
            let t = 1.0 - from_start / self.taper_in;
            return main + t * (self.x_taper - main);
        }
        main
    }

    /// The Z range over which the tip is on its main line (no taper), as (low, high), mm.
    pub fn full_depth_range(&self) -> (f64, f64) {
        let dir = self.feed_direction();
        let a = self.z_start + dir * self.taper_in;
        let b = self.z_end - dir * self.taper_out;
        (a.min(b), a.max(b))
    }

    /// The axial positions in `[lo, hi]` where this pass crosses the half-plane:
    /// `z_phase + k·lead` for whole k, within the move.
    pub fn crossings(&self, lo: f64, hi: f64) -> Vec<f64> {
        let (zmin, zmax) = (self.z_start.min(self.z_end), self.z_start.max(self.z_end));
        let (lo, hi) = (lo.max(zmin), hi.min(zmax));
        if !(hi >= lo) || !(self.lead > 0.0) {
            return Vec::new();
        }
        // k range from the window, so a long pass costs nothing outside it. The move's own ends
        // count (a crossing at z_start within rounding).
        let eps = 1e-12 * (1.0 + self.z_start.abs());
        let k0 = ((lo - eps - self.z_phase) / self.lead).ceil();
        let k1 = ((hi + eps - self.z_phase) / self.lead).floor();
        if k1 < k0 || k1 - k0 > 1e6 {
            return Vec::new();
        }
        let mut v: Vec<f64> =
            (k0 as i64..=k1 as i64).map(|k| self.z_phase + (k as f64) * self.lead).collect();
        if self.feed_direction() < 0.0 {
            v.reverse();
        }
        v
    }
}

/// How the tip moves from pass to pass.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, serde::Deserialize)]
#[serde(tag = "method", rename_all = "lowercase")]
pub enum Infeed {
    /// Straight in X: both edges cut (two-flank).
    Radial,
    /// Along a line `angle` degrees from the radial, towards the feed direction, so that the
    /// leading edge cuts and the trailing edge follows the finished flank: `Δz = Δx_radial·tan(angle)`.
    /// Flank infeed proper is half the thread angle; modified flank a few degrees less.
    Flank {
        /// Infeed angle from the radial, degrees.
        angle: f64,
    },
    /// Alternates between the two flanks: each pass moves `Δdepth·tan(angle)` along Z, the
    /// direction changing every pass, as a control that works in increments does.
    Alternating {
        /// Infeed angle from the radial, degrees.
        angle: f64,
    },
}

/// An infeed as a user names it, before the thread's angle is known: the one vocabulary of
/// `verify --infeed`, `sweep --infeed` and Python's `infeed=`.
///
/// | text | infeed |
/// |---|---|
/// | `radial` | straight in X |
/// | `flank` / `flank:A` | along the flank at half the thread angle / at A° from the radial |
/// | `modified` | flank infeed at half the thread angle less 0.5° (the default) |
/// | `alternating` / `alternating:A` | alternating flanks at half the thread angle / at A° |
///
/// ```
/// use threadcheck::{Infeed, InfeedChoice};
/// let m: InfeedChoice = "modified".parse()?;
/// assert_eq!(m.resolve(60.0), Infeed::Flank { angle: 29.5 });
/// let f: InfeedChoice = "flank:27".parse()?;
/// assert_eq!(f.resolve(30.0), Infeed::Flank { angle: 27.0 });
/// # Ok::<(), threadcheck::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum InfeedChoice {
    /// Straight in X.
    Radial,
    /// Along a flank line: at `angle` degrees from the radial, or half the thread angle.
    Flank {
        /// Degrees from the radial; `None`: half the thread angle.
        angle: Option<f64>,
    },
    /// Modified flank: half the thread angle less 0.5°.
    Modified,
    /// Alternating flanks at `angle`, or half the thread angle.
    Alternating {
        /// Degrees from the radial; `None`: half the thread angle.
        angle: Option<f64>,
    },
}

impl InfeedChoice {
    /// The words [`InfeedChoice::from_str`](std::str::FromStr) reads, for messages.
    pub const WORDS: &'static str = "radial, flank[:ANGLE], modified or alternating[:ANGLE]";

    /// The infeed for a form of included angle `thread_angle` (degrees).
    pub fn resolve(self, thread_angle: f64) -> Infeed {
        let half = 0.5 * thread_angle;
        match self {
            InfeedChoice::Radial => Infeed::Radial,
            InfeedChoice::Flank { angle } => Infeed::Flank { angle: angle.unwrap_or(half) },
            InfeedChoice::Modified => Infeed::Flank { angle: half - 0.5 },
            InfeedChoice::Alternating { angle } => Infeed::Alternating { angle: angle.unwrap_or(half) },
        }
    }

    /// The explicit angle, if one was given.
    pub fn angle(self) -> Option<f64> {
        match self {
            InfeedChoice::Radial | InfeedChoice::Modified => None,
            InfeedChoice::Flank { angle } | InfeedChoice::Alternating { angle } => angle,
        }
    }
}

impl From<Infeed> for InfeedChoice {
    fn from(i: Infeed) -> Self {
        match i {
            Infeed::Radial => InfeedChoice::Radial,
            Infeed::Flank { angle } => InfeedChoice::Flank { angle: Some(angle) },
            Infeed::Alternating { angle } => InfeedChoice::Alternating { angle: Some(angle) },
        }
    }
}

impl std::str::FromStr for InfeedChoice {
    type Err = Error;

    fn from_str(s: &str) -> Result<Self, Error> {
        let bad = || Error::Input(format!("infeed '{s}': expected {}", InfeedChoice::WORDS));
        let (name, angle) = match s.trim().split_once(':') {
            Some((n, a)) => {
                let a: f64 = a.trim().parse().map_err(|_| bad())?;
                if !(0.0..90.0).contains(&a) {
                    return Err(Error::Input(format!(
                        "infeed '{s}': the angle must be from 0 to under 90 degrees"
                    )));
                }
                (n, Some(a))
            }
            None => (s.trim(), None),
        };
        match (name, angle) {
            ("radial", None) => Ok(InfeedChoice::Radial),
            ("flank", angle) => Ok(InfeedChoice::Flank { angle }),
            ("modified", None) => Ok(InfeedChoice::Modified),
            ("alternating", angle) => Ok(InfeedChoice::Alternating { angle }),
            _ => Err(bad()),
        }
    }
}

/// How deep each pass goes.
#[derive(Clone, Debug, PartialEq, Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Schedule {
    /// Equal radial depth per pass: depth after pass i = t·i/N.
    ConstantDepth,
    /// Constant chip area: depth after pass i = t·√(i/N).
    ConstantArea,
    /// Sandvik's degressive series: depth after pass x = t·√(φ/(N−1)), φ = 0.3, 1, 2, …, N−1.
    Sandvik,
    /// Explicit cumulative radial depths (mm), the last being the total.
    Explicit(Vec<f64>),
}

impl Schedule {
    /// The schedule's name as the command line takes it: `constant-depth`, `constant-area`,
    /// `sandvik`, `explicit`.
    pub fn name(&self) -> &'static str {
        match self {
            Schedule::ConstantDepth => "constant-depth",
            Schedule::ConstantArea => "constant-area",
            Schedule::Sandvik => "sandvik",
            Schedule::Explicit(_) => "explicit",
        }
    }
}

impl std::fmt::Display for Infeed {
    /// The infeed as words: `radial`, `flank 29.5°`, `alternating 30°`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        use crate::ground::fmt::fmt_num;
        match self {
            Infeed::Radial => f.write_str("radial"),
            Infeed::Flank { angle } => write!(f, "flank {}°", fmt_num(*angle)),
            Infeed::Alternating { angle } => write!(f, "alternating {}°", fmt_num(*angle)),
        }
    }
}

impl std::str::FromStr for Schedule {
    type Err = Error;

    /// `constant-area`, `constant-depth` or `sandvik` (explicit depths are a list, not a name).
    fn from_str(s: &str) -> Result<Self, Error> {
        match s.trim() {
            "constant-area" => Ok(Schedule::ConstantArea),
            "constant-depth" => Ok(Schedule::ConstantDepth),
            "sandvik" => Ok(Schedule::Sandvik),
            _ => Err(Error::Input(format!(
                "schedule '{s}': expected constant-area, constant-depth or sandvik"
            ))),
        }
    }
}

/// Cumulative radial depths (mm) of `n` passes reaching `total`.
pub fn schedule_depths(schedule: &Schedule, total: f64, n: usize) -> Result<Vec<f64>, Error> {
    if let Schedule::Explicit(v) = schedule {
        if v.is_empty() || v.len() > MAX_PASSES {
            return Err(Error::Input(format!("an explicit schedule needs 1 to {MAX_PASSES} depths")));
        }
        if v.iter().any(|d| !d.is_finite() || *d < 0.0) || v.windows(2).any(|w| w[1] < w[0]) {
            return Err(Error::Input("explicit depths must be finite, ≥ 0 and not decreasing".into()));
        }
        return Ok(v.clone());
    }
    if n == 0 || n > MAX_PASSES {
        return Err(Error::Input(format!("{n} passes: the pass count must be 1 to {MAX_PASSES}")));
    }
    if !(total.is_finite() && total > 0.0) {
        return Err(Error::Geometry(format!(
            "thread depth {total} mm: the final X must lie inside the blank"
        )));
    }
    let nf = n as f64;
    let depth = |i: usize| {
        let i = i as f64;
        match schedule {
            Schedule::ConstantDepth => total * i / nf,
            Schedule::Sandvik if n > 1 => {
                let phi = if i == 1.0 { 0.3 } else { i - 1.0 };
                total * (phi / (nf - 1.0)).sqrt()
            }
            // Sandvik's series needs two passes; one pass is the whole depth, as constant area.
            Schedule::ConstantArea | Schedule::Sandvik => total * (i / nf).sqrt(),
            Schedule::Explicit(_) => unreachable!("an explicit schedule is returned above"),
        }
    };
    Ok((1..=n).map(depth).collect())
}

/// Axial offsets of the tip (mm) for cumulative depths `depths`, with the feed direction `dir`.
pub fn infeed_offsets(infeed: Infeed, depths: &[f64], dir: f64) -> Vec<f64> {
    match infeed {
        Infeed::Radial => vec![0.0; depths.len()],
        Infeed::Flank { angle } => {
            let t = crate::ground::plane::deg(angle).tan();
            depths.iter().map(|d| dir * d * t).collect()
        }
        Infeed::Alternating { angle } => {
            let t = crate::ground::plane::deg(angle).tan();
            let mut z = 0.0;
            let mut prev = 0.0;
            depths
                .iter()
                .enumerate()
                .map(|(i, d)| {
                    let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
                    z += sign * dir * (d - prev) * t;
                    prev = *d;
                    z
                })
                .collect()
        }
    }
}

/// The steepest taper a plan accepts, diameter change per mm of length.
pub const MAX_TAPER: f64 = 1.0;

/// A generated plan: everything needed to lay out the passes of a parallel thread.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanSpec {
    /// External or internal.
    pub kind: ThreadKind,
    /// Pitch, mm.
    pub pitch: f64,
    /// Number of starts.
    pub starts: u32,
    /// Diameter where the depth is zero: the blank (external) or the bore (internal), mm.
    pub surface_x: f64,
    /// Tip diameter of the last pass, mm.
    pub final_x: f64,
    /// Number of cutting passes per start.
    pub passes: usize,
    /// Depth schedule.
    pub schedule: Schedule,
    /// Infeed strategy.
    pub infeed: Infeed,
    /// Spring (idle) passes at the final position.
    pub spring: usize,
    /// Depth of the first pass, mm: when given, it sets the number of rough passes
    /// (constant area: N = ⌈(t/first)²⌉; constant depth: N = ⌈t/first⌉) instead of `passes`.
    pub first_depth: Option<f64>,
    /// Smallest radial step of a rough pass, mm (the Fanuc G76 Q rule); 0 for none.
    pub min_depth: f64,
    /// Finishing allowance, mm: the rough passes stop this short of the final depth and one
    /// finishing pass takes it; 0 for none.
    pub finish: f64,
    /// Diameter change per mm of travel along the feed (taper threads); 0 for parallel.
    pub taper: f64,
    /// Run-out chamfer at the thread end, in leads: X ramps back to the surface over that length.
    pub chamfer_leads: f64,
    /// Left-hand thread: the tool feeds towards +Z (away from the chuck).
    pub left_hand: bool,
    /// Z where each move starts (for start 0 and zero offset), mm.
    pub z_start: f64,
    /// Length of the threading move, mm (it ends at `z_start − length`).
    pub length: f64,
}

impl PlanSpec {
    /// A single-start, right-hand, parallel plan of `passes` radial constant-area passes from the
    /// surface at `surface_x` to the tip on `final_x`, starting at Z0 over ten pitches; change
    /// the rest with struct-update syntax (`PlanSpec { infeed, ..PlanSpec::new(…) }`).
    pub fn new(kind: ThreadKind, pitch: f64, surface_x: f64, final_x: f64, passes: usize) -> PlanSpec {
        PlanSpec {
            kind,
            pitch,
            starts: 1,
            surface_x,
            final_x,
            passes,
            schedule: Schedule::ConstantArea,
            infeed: Infeed::Radial,
            spring: 0,
            first_depth: None,
            min_depth: 0.0,
            finish: 0.0,
            taper: 0.0,
            chamfer_leads: 0.0,
            left_hand: false,
            z_start: 0.0,
            length: 10.0 * pitch,
        }
    }

    /// Total radial depth from the surface to the final tip, mm.
    pub fn total_depth(&self) -> f64 {
        match self.kind {
            ThreadKind::External => 0.5 * (self.surface_x - self.final_x),
            ThreadKind::Internal => 0.5 * (self.final_x - self.surface_x),
        }
    }

    /// Cumulative radial depths of the cutting passes (mm), rough then finish.
    pub fn depths(&self) -> Result<Vec<f64>, Error> {
        if self.final_x < 0.0 {
            return Err(Error::Geometry(format!(
                "final X{:.4} lies beyond the spindle axis: X is a diameter and cannot be negative",
                self.final_x
            )));
        }
        let total = self.total_depth();
        if !(total.is_finite() && total > 0.0) {
            return Err(Error::Geometry(format!(
                "final X{:.4} does not cut into the {} at X{:.4}",
                self.final_x,
                if self.kind == ThreadKind::External { "blank" } else { "bore" },
                self.surface_x
            )));
        }
        for (name, v) in [("finishing allowance", self.finish), ("minimum depth", self.min_depth)] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(Error::Input(format!("{name} {v} mm must be a length ≥ 0")));
            }
        }
        if self.finish >= total {
            return Err(Error::Input(format!(
                "finishing allowance {} mm is not less than the thread depth {total:.4} mm",
                self.finish
            )));
        }
        let rough_total = total - self.finish;
        let finish_passes = usize::from(self.finish > 0.0);
        let rough_n = match self.first_depth {
            Some(f) if !(f.is_finite() && f > 0.0) => {
                return Err(Error::Input(format!("first depth {f} mm must be greater than zero")));
            }
            Some(f) => {
                // A hair below, so that an exact ratio (0.9 / 0.3) does not round up a pass.
                let ratio = rough_total / f * (1.0 - 1e-12);
                // The first pass's depth under each law: t/N (constant depth), t·√(1/N)
                // (constant area), t·√(0.3/(N−1)) (Sandvik); an explicit list sets its own count.
                let n = match &self.schedule {
                    Schedule::ConstantDepth => ratio.ceil(),
                    Schedule::ConstantArea => (ratio * ratio).ceil(),
                    Schedule::Sandvik => (0.3 * ratio * ratio).ceil() + 1.0,
                    Schedule::Explicit(v) => v.len() as f64,
                };
                if n > MAX_PASSES as f64 {
                    return Err(Error::Input(format!(
                        "a first depth of {f} mm needs {n} passes, more than {MAX_PASSES}"
                    )));
                }
                (n as usize).max(1)
            }
            None => self.passes.saturating_sub(finish_passes).max(1),
        };
        let mut depths = schedule_depths(&self.schedule, rough_total, rough_n)?;
        if self.min_depth > 0.0 {
            let mut prev = 0.0f64;
            let mut clamped = Vec::with_capacity(depths.len());
            for d in depths {
                let d = d.max(prev + self.min_depth).min(rough_total);
                if d > prev {
                    clamped.push(d);
                    prev = d;
                }
            }
            depths = clamped;
        }
        if finish_passes > 0 {
            depths.push(total);
        }
        Ok(depths)
    }

    /// Lays out the passes, start after start.
    ///
    /// ```
    /// use threadcheck::{PlanSpec, Schedule};
    /// use threadcheck::ThreadKind;
    /// // 0.8 mm deep in four equal radial steps: X 9.6, 9.2, 8.8, 8.4.
    /// let plan = PlanSpec { schedule: Schedule::ConstantDepth, ..PlanSpec::new(ThreadKind::External, 1.5, 10.0, 8.4, 4) };
    /// let xs: Vec<f64> = plan.generate()?.iter().map(|p| p.x_end).collect();
    /// for (x, want) in xs.iter().zip([9.6, 9.2, 8.8, 8.4]) {
    ///     assert!((x - want).abs() < 1e-12);
    /// }
    /// # Ok::<(), threadcheck::Error>(())
    /// ```
    pub fn generate(&self) -> Result<Vec<Pass>, Error> {
        for (name, v) in [
            ("pitch", self.pitch),
            ("surface X", self.surface_x),
            ("final X", self.final_x),
            ("length", self.length),
            ("Z start", self.z_start),
        ] {
            if !v.is_finite() {
                return Err(Error::Input(format!("{name} is not a finite number")));
            }
        }
        if !(self.pitch > 0.0) {
            return Err(Error::Input(format!("pitch {} mm must be greater than zero", self.pitch)));
        }
        let depths = self.depths()?;
        let per_start = depths.len() + self.spring;
        if self.starts == 0 || per_start.saturating_mul(self.starts as usize) > MAX_PASSES {
            return Err(Error::Input(format!(
                "{} passes × {} starts is more than the {MAX_PASSES} threadcheck accepts",
                per_start, self.starts
            )));
        }
        // A thread cone steeper than a half-angle of 26.6° (a diameter change of 1 mm per mm) is
        // a face, not a taper thread; NPT's 1:16 is 0.0625.
        if !(self.taper.abs() <= MAX_TAPER) {
            return Err(Error::Input(format!(
                "taper {} must be between −{MAX_TAPER} and {MAX_TAPER} (diameter change per mm of length; 1:16 is 0.0625)",
                crate::ground::fmt::fmt_shown(self.taper)
            )));
        }
        // A run-out longer than the thread's length in leads cannot be cut.
        if !(self.chamfer_leads >= 0.0
            && self.chamfer_leads * self.pitch <= self.length.abs().max(self.pitch))
        {
            return Err(Error::Input(format!(
                "chamfer {} leads must be from 0 to the thread's length ({} mm)",
                crate::ground::fmt::fmt_shown(self.chamfer_leads),
                self.length
            )));
        }
        let dir = if self.left_hand { 1.0 } else { -1.0 };
        let offsets = infeed_offsets(self.infeed, &depths, dir);
        let sign = self.kind.depth_sign();
        let lead = self.pitch * f64::from(self.starts);
        let mut out = Vec::with_capacity(per_start * self.starts as usize);
        for start in 0..self.starts {
            let z0 = self.z_start - dir * f64::from(start) * self.pitch;
            let mut push = |depth: f64, off: f64| {
                let x = self.surface_x + 2.0 * sign * depth;
                out.push(Pass {
                    index: out.len() + 1,
                    x_start: x,
                    x_end: x + self.taper * self.length,
                    z_start: z0 + off,
                    z_end: z0 + off + dir * self.length,
                    z_phase: z0 + off,
                    lead,
                    start,
                    source_line: None,
                    taper_in: 0.0,
                    taper_out: self.chamfer_leads * lead,
                    x_taper: self.surface_x + self.taper * self.length,
                });
            };
            for (d, o) in depths.iter().zip(&offsets) {
                push(*d, *o);
            }
            let (dl, ol) = (depths[depths.len() - 1], offsets[offsets.len() - 1]);
            for _ in 0..self.spring {
                push(dl, ol);
            }
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn schedules_reach_the_total_and_grow() {
        for s in [Schedule::ConstantDepth, Schedule::ConstantArea, Schedule::Sandvik] {
            let d = schedule_depths(&s, 0.9, 9).unwrap();
            assert!((d[8] - 0.9).abs() < 1e-15, "{s:?}");
            assert!(d.windows(2).all(|w| w[1] > w[0]), "{s:?}");
        }
        // Constant area: first step t/√N.
        let d = schedule_depths(&Schedule::ConstantArea, 0.9, 9).unwrap();
        assert!((d[0] - 0.3).abs() < 1e-15);
        // Sandvik: the first pass is √0.3 of the second.
        let s = schedule_depths(&Schedule::Sandvik, 1.0, 5).unwrap();
        assert!((s[0] / s[1] - 0.3f64.sqrt()).abs() < 1e-15);
    }

    #[test]
    fn flank_infeed_keeps_the_trailing_flank_on_one_line() {
        let depths = [0.1, 0.3, 0.6];
        let z = infeed_offsets(Infeed::Flank { angle: 30.0 }, &depths, -1.0);
        for (d, z) in depths.iter().zip(&z) {
            assert!((z + d * (30f64).to_radians().tan()).abs() < 1e-15);
        }
    }

    #[test]
    fn left_hand_taper_and_chamfer() {
        let spec = PlanSpec {
            schedule: Schedule::ConstantDepth,
            infeed: Infeed::Flank { angle: 30.0 },
            taper: 1.0 / 16.0,
            chamfer_leads: 1.5,
            left_hand: true,
            z_start: -30.0,
            length: 20.0,
            ..PlanSpec::new(ThreadKind::External, 1.5, 20.0, 18.0, 4)
        };
        let p = spec.generate().unwrap();
        let last = p[3];
        // Feed towards +Z; the flank offset goes with the feed; 1:16 on the diameter over 20 mm.
        assert!((last.z_end - last.z_start - 20.0).abs() < 1e-12);
        assert!((last.z_start - (-30.0 + 1.0 * 30f64.to_radians().tan())).abs() < 1e-12);
        assert!((last.x_end - last.x_start - 1.25).abs() < 1e-12);
        assert!((last.taper_out - 2.25).abs() < 1e-12 && (last.x_taper - 21.25).abs() < 1e-12);
    }

    #[test]
    fn tapers_ramp_to_the_crest() {
        let mut p = Pass::parallel(1, 9.0, 0.0, -10.0, 1.5);
        p.taper_out = 2.0;
        p.x_taper = 10.0;
        assert_eq!(p.x_at(-5.0), 9.0);
        assert!((p.x_at(-9.0) - 9.5).abs() < 1e-12);
        assert!((p.x_at(-10.0) - 10.0).abs() < 1e-12);
        assert_eq!(p.full_depth_range(), (-8.0, 0.0));
    }

    #[test]
    fn crossings_step_by_the_lead_inside_the_window() {
        let p = Pass::parallel(1, 9.0, 0.2, -30.0, 1.5);
        let z = p.crossings(-5.0, 0.0);
        assert_eq!(z.len(), 3);
        assert!((z[0] - (0.2 - 1.5)).abs() < 1e-12 && (z[2] - (0.2 - 4.5)).abs() < 1e-12);
        assert!(p.crossings(5.0, 6.0).is_empty());
    }

    #[test]
    fn first_depth_min_step_and_finish() {
        let mut spec = PlanSpec {
            first_depth: Some(0.3),
            length: 10.0,
            ..PlanSpec::new(ThreadKind::External, 1.5, 10.0, 8.2, 0)
        };
        // t = 0.9, first 0.3: (0.9/0.3)² = 9 passes of constant area.
        assert_eq!(spec.depths().unwrap().len(), 9);
        spec.first_depth = None;
        spec.passes = 9;
        spec.finish = 0.05;
        spec.min_depth = 0.08;
        let d = spec.depths().unwrap();
        assert!((d[d.len() - 1] - 0.9).abs() < 1e-12 && (d[d.len() - 2] - 0.85).abs() < 1e-12);
        assert!(d[..d.len() - 1]
            .windows(2)
            .all(|w| w[1] - w[0] >= 0.08 - 1e-12 || (w[1] - 0.85).abs() < 1e-12));
    }

    #[test]
    fn generated_plan_has_spring_passes_and_starts() {
        let spec = PlanSpec {
            starts: 2,
            spring: 1,
            z_start: 1.0,
            length: 20.0,
            ..PlanSpec::new(ThreadKind::External, 2.0, 24.0, 21.5, 6)
        };
        let p = spec.generate().unwrap();
        assert_eq!(p.len(), 14);
        assert_eq!(p[6].x_start, p[5].x_start);
        // The second start begins one pitch back against the feed (−Z feed: at +2 mm).
        assert!((p[7].z_start - 3.0).abs() < 1e-12 && p[7].start == 1 && p[7].lead == 4.0);
    }
}
