//! What the pictures of a verification draw, computed once and carried with it: the basic,
//! maximum- and minimum-material profiles around the measured groove, the normal deviation of
//! the as-cut profile (and of the zone's sides) from the basic one, and the section over the
//! thread's full length, run-out included. `report/` draws these and computes nothing; the JSON
//! carries the deviation samples.

use crate::geometry::boolean::UnionStrategy;
use crate::geometry::insert::Insert;
use crate::geometry::measure::{deviation_along, DeviationSample};
use crate::geometry::sweep::{full_length_window, sweep, Section, SweepSetup};
use crate::ground::plane::{rad, Point};
use crate::standards::tolerance::ThreadLimits;
use crate::standards::{BasicThread, ProfileKind, ThreadKind};
use crate::toolpath::passes::Pass;
use crate::Error;
use serde::Serialize;

/// Samples along one pitch of the basic profile in the deviation plot.
pub const DEVIATION_SAMPLES: usize = 400;

/// The normal deviation from the basic profile along one pitch centred on the measured groove,
/// as a contour-measuring machine reports it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Deviation {
    /// The as-cut profile.
    pub as_cut: Vec<DeviationSample>,
    /// The maximum-material profile (empty when the class has no pitch-diameter limits).
    pub max_material: Vec<DeviationSample>,
    /// The minimum-material profile (likewise).
    pub min_material: Vec<DeviationSample>,
}

/// What a picture is drawn from: the verification's thread, cut and measured groove.
#[derive(Clone, Copy, Debug)]
pub struct Cut<'a> {
    /// The basic thread.
    pub thread: &'a BasicThread,
    /// External or internal.
    pub kind: ThreadKind,
    /// Its limits of size.
    pub limits: &'a ThreadLimits,
    /// The measured groove's centre, mm.
    pub groove_center: f64,
    /// The measured section.
    pub section: &'a Section,
    /// The insert.
    pub insert: &'a Insert,
    /// The blank (or bore) diameter, mm.
    pub blank_diameter: f64,
    /// The passes.
    pub passes: &'a [Pass],
}

/// What the pictures draw.
#[derive(Clone, Debug)]
pub struct Picture {
    /// The basic profile (the nut's for an internal thread) at the basic pitch diameter, in part
    /// coordinates, over every pitch a picture shows.
    pub basic: Vec<Point>,
    /// The maximum- and minimum-material profiles over the same span, when the class has both
    /// pitch-diameter limits.
    pub zone: Option<(Vec<Point>, Vec<Point>)>,
    /// The deviation samples.
    pub deviation: Deviation,
    /// The section over the thread's full length.
    pub full_length: Section,
}

impl Picture {
    /// The points of `profile` within `z_range`.
    pub fn clip(profile: &[Point], z_range: (f64, f64)) -> Vec<Point> {
        profile.iter().copied().filter(|q| q.z >= z_range.0 && q.z <= z_range.1).collect()
    }

    /// The zone's two sides within `z_range`.
    pub fn zone(&self, z_range: (f64, f64)) -> Option<(Vec<Point>, Vec<Point>)> {
        self.zone.as_ref().map(|(a, b)| (Picture::clip(a, z_range), Picture::clip(b, z_range)))
    }
}

/// The profile `variant` shifted to pitch diameter `d2`, repeated pitch by pitch from the groove
/// at `zc` over `z_range` (a pitch beyond it each way, so that clipping any range inside it gives
/// the same points), its crest cut at radius `crest` when given.
fn shifted_profile(
    v: &Zone<'_>,
    variant: ProfileKind,
    d2: f64,
    zc: f64,
    z_range: (f64, f64),
    crest: Option<f64>,
) -> Vec<Point> {
    let t = v.thread;
    let one = t.profile(variant, 1e-3);
    let shift = 0.5 * (d2 - t.pitch_diameter());
    let p = t.pitch;
    let k0 = ((z_range.0 - zc) / p).floor() as i64 - 1;
    let k1 = ((z_range.1 - zc) / p).ceil() as i64 + 1;
    let mut raw: Vec<Point> = Vec::new();
    for k in k0..=k1 {
        for q in &one {
            raw.push(Point::new(q.z + zc + k as f64 * p, q.r + shift));
        }
    }
    // The crest cut at radius `crest`: each segment that crosses it gets the crossing as a
    // vertex, so the flanks keep their angle up to the cut (clamping the vertices alone tilted
    // the flank from its last vertex to the clamped one).
    let clamp = |r: f64| match (crest, v.kind) {
        (Some(c), ThreadKind::External) => r.min(c),
        (Some(c), ThreadKind::Internal) => r.max(c),
        (None, _) => r,
    };
    let mut out: Vec<Point> = Vec::new();
    let mut push = |q: Point| {
        if out.last().is_none_or(|l| (l.z - q.z).abs() > 1e-12 || (l.r - q.r).abs() > 1e-12) {
            out.push(q);
        }
    };
    for (i, a) in raw.iter().enumerate() {
        push(Point::new(a.z, clamp(a.r)));
        if let (Some(c), Some(b)) = (crest, raw.get(i + 1)) {
            if (a.r - c) * (b.r - c) < 0.0 {
                let t = (c - a.r) / (b.r - a.r);
                push(Point::new(a.z + t * (b.z - a.z), c));
            }
        }
    }
    Picture::clip(&out, z_range)
}

/// A tolerance zone's maximum- and minimum-material sides.
pub type ZoneSides = (Vec<Point>, Vec<Point>);

/// What the basic profile and the tolerance zone are drawn from: the thread, its kind and
/// limits, and the measured groove's centre (mm) they are placed on.
#[derive(Clone, Copy, Debug)]
pub struct Zone<'a> {
    /// The basic thread.
    pub thread: &'a BasicThread,
    /// External or internal.
    pub kind: ThreadKind,
    /// Its limits of size.
    pub limits: &'a ThreadLimits,
    /// The measured groove's centre, mm.
    pub groove_center: f64,
}

impl Zone<'_> {
    /// The basic profile (the nut's for an internal thread) at the basic pitch diameter over
    /// `span`, and the maximum- and minimum-material profiles over it when the class has both
    /// pitch-diameter limits.
    pub fn profiles(&self, span: (f64, f64)) -> (Vec<Point>, Option<ZoneSides>) {
        let basic_variant = match self.kind {
            ThreadKind::External => ProfileKind::Basic,
            ThreadKind::Internal => ProfileKind::Nut,
        };
        let basic = shifted_profile(self, basic_variant, self.basic_d2(), self.groove_center, span, None);
        (basic, zone_profiles(self, span))
    }

    /// The basic pitch diameter where the groove is: a taper thread's basic cone's there (the
    /// face at Z0, the thread going −Z), else the thread's.
    fn basic_d2(&self) -> f64 {
        match self.limits.gauge_plane {
            Some(gp) => {
                let depth = -self.groove_center - gp.distance;
                match self.kind {
                    ThreadKind::External => gp.pitch_diameter + depth * gp.taper,
                    ThreadKind::Internal => gp.pitch_diameter - depth * gp.taper,
                }
            }
            None => self.thread.pitch_diameter(),
        }
    }
}

/// The maximum- and minimum-material profiles over `zr`.
fn zone_profiles(v: &Zone<'_>, zr: (f64, f64)) -> Option<(Vec<Point>, Vec<Point>)> {
    let l = v.limits;
    let (mmc_d2, lmc_d2) = match (l.gauge_plane, v.kind) {
        // A taper thread's zone: the gauge's turns either way, on the diameter where the groove
        // is (the gauge plane moves one turn for P·taper of pitch diameter).
        (Some(gp), kind) => {
            let band = gp.tolerance_turns * v.thread.pitch * gp.taper;
            let d2 = v.basic_d2();
            match kind {
                ThreadKind::External => (Some(d2 + band), Some(d2 - band)),
                ThreadKind::Internal => (Some(d2 - band), Some(d2 + band)),
            }
        }
        (None, ThreadKind::External) => (l.pitch_diameter.max, l.pitch_diameter.min),
        (None, ThreadKind::Internal) => (l.pitch_diameter.min, l.pitch_diameter.max),
    };
    let (a, b) = (mmc_d2?, lmc_d2?);
    let (mmc_variant, lmc_variant, lmc_crest) = match v.kind {
        ThreadKind::External => (ProfileKind::Basic, ProfileKind::BoltMinRoot, l.major_diameter.min.map(rad)),
        ThreadKind::Internal => (ProfileKind::Nut, ProfileKind::Nut, l.minor_diameter.max.map(rad)),
    };
    let zc = v.groove_center;
    Some((
        shifted_profile(v, mmc_variant, a, zc, zr, None),
        shifted_profile(v, lmc_variant, b, zc, zr, lmc_crest),
    ))
}

/// Computes what the pictures of a cut draw.
pub fn picture(v: &Cut<'_>) -> Result<Picture, Error> {
    let t = v.thread;
    let p = t.pitch;
    let zc = v.groove_center;
    // Every span a picture shows: the measured window and one tooth (± 0.75 P), and a pitch
    // each way beyond the deviation plot's.
    let w = v.section.window;
    let span = (w.z_min.min(zc - 3.0 * p) - p, w.z_max.max(zc + 3.0 * p) + p);
    let (basic, zone) = Zone { thread: t, kind: v.kind, limits: v.limits, groove_center: zc }.profiles(span);
    // The deviation along one pitch of the basic profile centred on the groove.
    let one = Picture::clip(&basic, (zc - 0.5 * p, zc + 0.5 * p));
    let air_up = v.kind == ThreadKind::External;
    let along = |prof: &[Point]| deviation_along(&one, prof, air_up, DEVIATION_SAMPLES);
    let as_cut = along(&v.section.profile());
    let (max_material, min_material) = match (&zone, as_cut.is_empty()) {
        (Some((a, b)), false) => {
            let zr = (zc - 1.5 * p, zc + 1.5 * p);
            (along(&Picture::clip(a, zr)), along(&Picture::clip(b, zr)))
        }
        _ => (Vec::new(), Vec::new()),
    };
    // The whole thread, run-out included: the envelope over the full length.
    let setup = SweepSetup { kind: v.kind, insert: v.insert, blank_diameter: v.blank_diameter, pitch: p };
    let full = sweep(&setup, v.passes, full_length_window(v.passes, p), UnionStrategy::Envelope)?;
    Ok(Picture {
        basic,
        zone,
        deviation: Deviation { as_cut, max_material, min_material },
        full_length: full.section,
    })
}
