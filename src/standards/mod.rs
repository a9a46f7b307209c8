//! Thread standards: forms, basic dimensions, one-pitch profiles and the embedded catalogues.
//!
//! This is where the data path starts: a designation (`M10x1.5-6g`) becomes a [`Designation`]
//! holding a [`BasicThread`] and its classes; [`crate::standards::tolerance`] turns those into limits.
//!
//! Sources: ISO 68-1 and DIN 13 for the metric form, BS 84 for Whitworth, ISO 228-1 for the
//! BSP parallel pipe thread. The numeric data lives in `profiles/*.toml`, embedded in the binary.

pub mod data;
pub mod designation;
pub mod drills;
pub mod tolerance;
pub mod torque;

pub use data::{catalog, Catalog, UnifiedSize};
pub use designation::{parse_designation, ClassSpec, Designation, DesignationError, ParseOptions};

use crate::ground::plane::{extend_dedup, Arc, Point};
use serde::Serialize;
use std::f64::consts::FRAC_PI_2;

/// Millimetres per inch, exact.
pub const MM_PER_INCH: f64 = 25.4;

/// The thread form: flank angle and the shape of crest and root.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ThreadForm {
    /// ISO metric, ISO 68-1: 60°, flat crest, basic flat root; DIN 13 rounded bolt root H/6.
    IsoMetric,
    /// Whitworth, BS 84 (BSW, BSF): 55°, crest and root rounded with r = 0.137329·P.
    Whitworth,
    /// BSP parallel pipe thread, ISO 228-1 (G): the Whitworth form on pipe sizes.
    BspParallel,
    /// Unified inch, ASME B1.1 (UN, UNR): the ISO 68-1 basic profile on inch sizes; the UNR
    /// external root is rounded.
    Unified,
    /// ISO metric trapezoidal, ISO 2901–2904 (Tr): 30°, flat crest and root with the crest
    /// clearance ac.
    Trapezoidal,
    /// General-purpose Acme, ASME B1.5 (2G, 3G, 4G): 29°, basic depth P/2, crest flat 0.3707·P,
    /// root clearance 0.010 in (10 tpi and coarser) or 0.005 in on the radius.
    Acme,
    /// NPT taper pipe thread, ASME B1.20.1: 60°, taper 1:16, thread height 0.8·P with flat
    /// truncations of at least 0.033·P at crest and root.
    Npt,
    /// ISO 7-1 taper pipe thread (R external, Rc internal): the Whitworth form on a 1:16 cone.
    Iso7Taper,
}

/// The profile families: how crest and root are shaped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Family {
    /// ISO 68-1's truncated 60° V: flat crest H/8, nut crest P/4, root radius up to H/6.
    TruncatedV,
    /// Whitworth: H/6 rounded off both ends.
    Rounded,
    /// ISO 2901 trapezoid: H1 = P/2 overlap, flat crest and root, clearance ac at both ends.
    Trapezoid,
    /// ASME B1.20.1's 60° V truncated 0.033·P at crest and root: height 0.8·P, the same for pipe
    /// and fitting.
    PipeV,
}

/// What each form is, in one place: every use asks its form here, so a new form does not
/// compile until it says what it is.
#[derive(Clone, Copy, Debug, PartialEq)]
struct FormSpec {
    /// Included flank angle, degrees.
    angle: f64,
    /// How crest and root are shaped.
    family: Family,
    /// Smallest bolt root radius as a fraction of P that the form itself sets (ISO 965-1:
    /// 0.125; UNR sets its 0.108 in its class limits).
    min_root_radius_p: Option<f64>,
    /// Root radius of the bolt with the smallest root the limits allow (profile of
    /// `ProfileKind::BoltMinRoot`), as a fraction of P.
    min_root_profile_p: f64,
}

impl ThreadForm {
    fn spec(self) -> FormSpec {
        match self {
            ThreadForm::IsoMetric => FormSpec {
                angle: 60.0,
                family: Family::TruncatedV,
                min_root_radius_p: Some(0.125),
                min_root_profile_p: 0.125,
            },
            ThreadForm::Unified => FormSpec {
                angle: 60.0,
                family: Family::TruncatedV,
                min_root_radius_p: None,
                min_root_profile_p: 0.108,
            },
            ThreadForm::Npt => FormSpec {
                angle: 60.0,
                family: Family::PipeV,
                min_root_radius_p: None,
                min_root_profile_p: 0.0,
            },
            ThreadForm::Whitworth | ThreadForm::BspParallel | ThreadForm::Iso7Taper => FormSpec {
                angle: 55.0,
                family: Family::Rounded,
                min_root_radius_p: None,
                min_root_profile_p: 0.137329,
            },
            ThreadForm::Acme => FormSpec {
                angle: 29.0,
                family: Family::Trapezoid,
                min_root_radius_p: None,
                min_root_profile_p: 0.0,
            },
            ThreadForm::Trapezoidal => FormSpec {
                angle: 30.0,
                family: Family::Trapezoid,
                min_root_radius_p: None,
                min_root_profile_p: 0.0,
            },
        }
    }

    /// Included flank angle α, degrees.
    pub fn flank_angle(self) -> f64 {
        self.spec().angle
    }

    /// The name used in reports (`iso-metric`, `whitworth`, `bsp-parallel`).
    pub fn name(self) -> &'static str {
        match self {
            ThreadForm::IsoMetric => "iso-metric",
            ThreadForm::Whitworth => "whitworth",
            ThreadForm::BspParallel => "bsp-parallel",
            ThreadForm::Unified => "unified",
            ThreadForm::Trapezoidal => "trapezoidal",
            ThreadForm::Acme => "acme",
            ThreadForm::Npt => "npt",
            ThreadForm::Iso7Taper => "iso7-taper",
        }
    }

    /// True for the rounded Whitworth family (BS 84 and ISO 228-1).
    pub fn is_whitworth(self) -> bool {
        self.spec().family == Family::Rounded
    }

    /// Whether a full-profile insert of this form also forms the crest (the 60° and 55° forms:
    /// their crest is part of the insert's profile) or only the flanks and root (the trapezoid
    /// forms, whose inserts leave the turned crest alone).
    pub fn full_insert_tops_crest(self) -> bool {
        match self.spec().family {
            Family::TruncatedV | Family::Rounded | Family::PipeV => true,
            Family::Trapezoid => false,
        }
    }

    /// The taper on the diameter per unit of length: 1/16 for the pipe threads, 0 for parallel
    /// forms.
    pub fn taper(self) -> f64 {
        match self {
            ThreadForm::Npt | ThreadForm::Iso7Taper => 1.0 / 16.0,
            ThreadForm::IsoMetric
            | ThreadForm::Whitworth
            | ThreadForm::BspParallel
            | ThreadForm::Unified
            | ThreadForm::Trapezoidal
            | ThreadForm::Acme => 0.0,
        }
    }

    /// True for forms whose sizes are inches (BS 84, ISO 228-1 and Unified sizes).
    pub fn is_inch(self) -> bool {
        match self {
            ThreadForm::IsoMetric | ThreadForm::Trapezoidal | ThreadForm::Iso7Taper => false,
            ThreadForm::Whitworth
            | ThreadForm::BspParallel
            | ThreadForm::Unified
            | ThreadForm::Acme
            | ThreadForm::Npt => true,
        }
    }
}

/// External (bolt) or internal (nut) thread.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ThreadKind {
    /// Bolt: material inside, the insert cuts towards the axis.
    External,
    /// Nut: material outside, the insert cuts away from the axis.
    Internal,
}

impl ThreadKind {
    /// Direction of cutting in radius: −1 for external (towards the axis), +1 for internal.
    pub fn depth_sign(self) -> f64 {
        match self {
            ThreadKind::External => -1.0,
            ThreadKind::Internal => 1.0,
        }
    }

    /// `external` or `internal`.
    pub fn name(self) -> &'static str {
        match self {
            ThreadKind::External => "external",
            ThreadKind::Internal => "internal",
        }
    }
}

/// Right- or left-hand helix.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Hand {
    /// Right-hand (the default).
    #[default]
    Right,
    /// Left-hand (`LH`).
    Left,
}

impl Hand {
    /// `right` or `left`, as the JSON and the reports name it.
    pub fn name(self) -> &'static str {
        match self {
            Hand::Right => "right",
            Hand::Left => "left",
        }
    }

    /// The other hand.
    pub fn other(self) -> Hand {
        match self {
            Hand::Right => Hand::Left,
            Hand::Left => Hand::Right,
        }
    }
}

/// A thread's basic size: form, nominal (major) diameter, pitch and starts.
///
/// All lengths in mm. For Whitworth and BSP threads the pitch is `25.4 / tpi` exactly.
/// Derived dimensions are exact (unrounded); the limits of size ([`crate::limits_for`]) round them to 0.001 mm the way
/// the standards' tables print them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BasicThread {
    /// Thread form.
    pub form: ThreadForm,
    /// Basic major diameter d = D, mm.
    pub nominal_diameter: f64,
    /// Pitch P (axial distance between adjacent grooves), mm.
    pub pitch: f64,
    /// Number of starts n; the lead is `n·P`.
    pub starts: u32,
    /// Helix hand.
    pub hand: Hand,
}

impl BasicThread {
    /// A single-start, right-hand ISO metric thread: nominal diameter `d` and pitch `p`, mm.
    pub fn metric(d: f64, p: f64) -> BasicThread {
        BasicThread {
            form: ThreadForm::IsoMetric,
            nominal_diameter: d,
            pitch: p,
            starts: 1,
            hand: Hand::Right,
        }
    }

    /// Lead Ph = n·P, mm: the axial advance per revolution.
    pub fn lead(&self) -> f64 {
        self.pitch * f64::from(self.starts)
    }

    /// Half the included flank angle, radians.
    pub fn half_angle(&self) -> f64 {
        0.5 * crate::ground::plane::deg(self.form.flank_angle())
    }

    /// Height of the fundamental (sharp) triangle H = P / (2·tan(α/2)), mm:
    /// 0.866025·P for 60°, 0.960491·P for 55°.
    pub fn fundamental_height(&self) -> f64 {
        self.pitch / (2.0 * self.half_angle().tan())
    }

    /// Basic pitch diameter d2 = D2, mm: metric d − 3H/4 (= d − 0.649519·P), Whitworth d − h.
    pub fn pitch_diameter(&self) -> f64 {
        let h = self.fundamental_height();
        match self.form.spec().family {
            Family::TruncatedV => self.nominal_diameter - 0.75 * h,
            Family::Rounded => self.nominal_diameter - self.thread_depth(),
            Family::Trapezoid => self.nominal_diameter - 0.5 * self.pitch,
            Family::PipeV => self.nominal_diameter - 0.8 * self.pitch,
        }
    }

    /// Basic minor diameter of the nut D1 (metric d − 5H/4), or the common minor diameter of the
    /// Whitworth forms d − 2h, mm.
    pub fn minor_diameter_internal(&self) -> f64 {
        match self.form.spec().family {
            Family::TruncatedV => self.nominal_diameter - 1.25 * self.fundamental_height(),
            Family::Rounded => self.nominal_diameter - 2.0 * self.thread_depth(),
            Family::Trapezoid => self.nominal_diameter - self.pitch,
            Family::PipeV => self.nominal_diameter - 1.6 * self.pitch,
        }
    }

    /// Root diameter of the bolt d3, mm: metric d − 2·h3 (DIN 13, h3 = 17H/24), Whitworth d − 2h.
    pub fn minor_diameter_external(&self) -> f64 {
        self.nominal_diameter - 2.0 * self.thread_depth()
    }

    /// Thread depth of the bolt, mm: h3 = 17H/24 (metric, DIN 13) or h = 2H/3 (Whitworth).
    pub fn thread_depth(&self) -> f64 {
        let h = self.fundamental_height();
        match self.form.spec().family {
            Family::TruncatedV => 17.0 * h / 24.0,
            Family::Rounded => 2.0 * h / 3.0,
            Family::Trapezoid => 0.5 * self.pitch + self.crest_clearance(),
            Family::PipeV => 0.8 * self.pitch,
        }
    }

    /// Basic depth of engagement H1, mm: 5H/8 (metric) or h (Whitworth).
    pub fn engagement_depth(&self) -> f64 {
        match self.form.spec().family {
            Family::TruncatedV => 0.625 * self.fundamental_height(),
            Family::Rounded => self.thread_depth(),
            Family::Trapezoid => 0.5 * self.pitch,
            Family::PipeV => 0.8 * self.pitch,
        }
    }

    /// Design root radius of the bolt, mm: H/6 (DIN 13) or 0.137329·P (Whitworth).
    pub fn root_radius(&self) -> f64 {
        match self.form.spec().family {
            Family::TruncatedV => self.fundamental_height() / 6.0,
            Family::Rounded => self.whitworth_radius(),
            // The root corners may be rounded up to ac (ISO 2901, R2 max).
            Family::Trapezoid => self.crest_clearance(),
            // The largest arc inside the 0.033·P truncation of a 60° V: 0.033·P.
            Family::PipeV => 0.033 * self.pitch,
        }
    }

    /// Crest radius, mm: `None` for the flat metric crest, 0.137329·P for Whitworth.
    pub fn crest_radius(&self) -> Option<f64> {
        self.form.is_whitworth().then(|| self.whitworth_radius())
    }

    /// Smallest root radius the standard allows on the bolt, mm: 0.125·P (ISO 965-1) for metric;
    /// BS 84 and ISO 228-1 set none.
    pub fn min_root_radius(&self) -> Option<f64> {
        self.form.spec().min_root_radius_p.map(|k| k * self.pitch)
    }

    /// The crest clearance of the trapezoid forms on the radius, mm: ISO 2901's ac (0.15 at
    /// P 1.5, 0.25 to P 5, 0.5 to P 12, 1.0 to P 44), or ASME B1.5's 0.010 in for 10 tpi and
    /// coarser, 0.005 in finer (half its diametral 0.020 / 0.010 in); 0 for the other forms.
    pub fn crest_clearance(&self) -> f64 {
        match self.form {
            ThreadForm::IsoMetric
            | ThreadForm::Whitworth
            | ThreadForm::BspParallel
            | ThreadForm::Unified
            | ThreadForm::Npt
            | ThreadForm::Iso7Taper => 0.0,
            ThreadForm::Acme => {
                let tpi = MM_PER_INCH / self.pitch;
                if tpi <= 10.0 + 1e-9 {
                    0.010 * MM_PER_INCH
                } else {
                    0.005 * MM_PER_INCH
                }
            }
            ThreadForm::Trapezoidal => match catalog().map(|c| &c.tr) {
                Ok(t) => t
                    .ac_pitch_up_to
                    .iter()
                    .zip(&t.ac)
                    .find(|(up, _)| self.pitch <= **up + 1e-9)
                    .map_or(t.ac.last().copied().unwrap_or(1.0), |(_, a)| *a),
                Err(_) => 0.0,
            },
        }
    }

    fn whitworth_radius(&self) -> f64 {
        // The arc cuts H/6 off the sharp triangle and is tangent to both flanks.
        let b = self.half_angle();
        self.fundamental_height() / 6.0 / (1.0 / b.sin() - 1.0)
    }

    /// The groove shape of `variant` in the groove frame (see [`GrooveForm`]).
    pub fn groove(&self, variant: ProfileKind) -> GrooveForm {
        let h = self.fundamental_height();
        let beta = self.half_angle();
        let spec = self.form.spec();
        // The trapezoid: the pitch line P/4 below the crest line (d2 = d − P/2, D1 = d − P), so
        // the flanks meet P/4 − (P/4)/tan β above it; the root flat at P/2 (basic) or P/2 + ac.
        let tr_crest = 0.25 * self.pitch - 0.25 * self.pitch / beta.tan();
        let tr_root = 0.5 * self.pitch + self.crest_clearance();
        let (sharp_crest, crest, root) = match (spec.family, variant) {
            (Family::TruncatedV, ProfileKind::Basic) => (-h / 8.0, Feature::Flat, Feature::FlatAt(0.625 * h)),
            (Family::TruncatedV, ProfileKind::BoltDesign) => (-h / 8.0, Feature::Flat, Feature::Arc(h / 6.0)),
            (Family::TruncatedV, ProfileKind::BoltMinRoot) => {
                (-h / 8.0, Feature::Flat, Feature::Arc(spec.min_root_profile_p * self.pitch))
            }
            // Seen from the nut: its crest is the D1 flat (P/4 wide), its root the D flat (P/8).
            (Family::TruncatedV, ProfileKind::Nut) => (-h / 4.0, Feature::Flat, Feature::FlatAt(0.625 * h)),
            (
                Family::Rounded,
                ProfileKind::Basic | ProfileKind::BoltDesign | ProfileKind::BoltMinRoot | ProfileKind::Nut,
            ) => {
                let r = self.whitworth_radius();
                (-h / 6.0, Feature::Arc(r), Feature::Arc(r))
            }
            (Family::Trapezoid, ProfileKind::Basic) => {
                (tr_crest, Feature::Flat, Feature::FlatAt(0.5 * self.pitch))
            }
            // Bolt (root at d3 = d − P − 2ac) and nut (from D1 = d − P to D4 = d + 2ac) have the
            // same groove, each from its own crest line.
            (Family::Trapezoid, ProfileKind::BoltDesign | ProfileKind::BoltMinRoot | ProfileKind::Nut) => {
                (tr_crest, Feature::Flat, Feature::FlatAt(tr_root))
            }
            // Pipe and fitting alike: flats 0.033·P into the sharp V at both ends.
            (
                Family::PipeV,
                ProfileKind::Basic | ProfileKind::BoltDesign | ProfileKind::BoltMinRoot | ProfileKind::Nut,
            ) => (-0.033 * self.pitch, Feature::Flat, Feature::FlatAt(0.8 * self.pitch)),
        };
        GrooveForm { pitch: self.pitch, half_angle: beta, sharp_crest, crest, root }
    }

    /// The crest line radius of `kind` (mm): d/2 for the bolt, D1/2 for the nut.
    pub fn crest_radius_line(&self, kind: ThreadKind) -> f64 {
        match kind {
            ThreadKind::External => 0.5 * self.nominal_diameter,
            ThreadKind::Internal => 0.5 * self.minor_diameter_internal(),
        }
    }

    /// The basic profile over one pitch of the axial section, as `(z, r)` points from the tooth
    /// centre at `z = −P/2` through the groove centred at `z = 0` to the next tooth centre at
    /// `z = +P/2`. Arcs are tessellated to `tolerance` (mm).
    ///
    /// `ProfileKind::Nut` gives the internal thread's groove (centred on the bolt's tooth).
    ///
    /// ```
    /// use threadcheck::{BasicThread, ProfileKind};
    /// let m10 = BasicThread::metric(10.0, 1.5);
    /// let p = m10.profile(ProfileKind::BoltDesign, 5e-5);
    /// let lowest = p.iter().map(|q| q.r).fold(f64::INFINITY, f64::min);
    /// assert!((2.0 * lowest - 8.160).abs() < 1e-3); // d3 = d − 1.226869·P
    /// ```
    pub fn profile(&self, variant: ProfileKind, tolerance: f64) -> Vec<Point> {
        let kind = if variant == ProfileKind::Nut { ThreadKind::Internal } else { ThreadKind::External };
        let g = self.groove(variant);
        let base = self.crest_radius_line(kind);
        let s = -kind.depth_sign();
        g.polyline(tolerance).into_iter().map(|q| Point::new(q.z, base - s * q.r)).collect()
    }
}

/// Which of a form's profiles to build.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProfileKind {
    /// The basic profile common to nut and bolt (ISO 68-1: flat crest and flat root at D1).
    Basic,
    /// The bolt as designed: DIN 13 root radius H/6 (metric), rounded crest and root (Whitworth).
    BoltDesign,
    /// The bolt with the smallest root ISO 965-1 allows, R = 0.125·P (metric only).
    BoltMinRoot,
    /// The nut's groove: crest at D1, root at D.
    Nut,
}

/// Crest or root of a groove.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Feature {
    /// Flat at depth 0 (only for crests).
    Flat,
    /// Flat at the given depth below the crest line, mm (only for roots).
    FlatAt(f64),
    /// Arc of the given radius tangent to both flanks, mm.
    Arc(f64),
}

/// A symmetric V groove in its own frame: `z` across the groove (centre 0), `r` = **depth** below
/// the crest line (0 at the crest line, positive into the part).
///
/// The flanks meet at the sharp root vertex at depth `sharp_crest + P/(2·tan β)` and reach the
/// sharp crest at `sharp_crest` (negative: above the crest line) at `z = ±P/2`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GrooveForm {
    /// Pitch, mm: the period of the profile.
    pub pitch: f64,
    /// Half the included angle β, radians.
    pub half_angle: f64,
    /// Depth of the sharp crest (negative or zero), mm.
    pub sharp_crest: f64,
    /// Crest: flat at depth 0, or an arc whose top is at depth 0.
    pub crest: Feature,
    /// Root: flat at a depth, or an arc tangent to both flanks.
    pub root: Feature,
}

impl GrooveForm {
    /// Depth of the sharp root vertex, mm.
    pub fn sharp_root(&self) -> f64 {
        self.sharp_crest + 0.5 * self.pitch / self.half_angle.tan()
    }

    /// Depth of the groove bottom, mm (the deepest point of the root).
    pub fn bottom(&self) -> f64 {
        match self.root {
            Feature::Flat => 0.0,
            Feature::FlatAt(w) => w,
            Feature::Arc(r) => self.sharp_root() - r / self.half_angle.sin() + r,
        }
    }

    /// Half-width of the groove (|z| on the right flank) at depth `w`, mm, on the straight flank.
    pub fn flank_z(&self, w: f64) -> f64 {
        (self.sharp_root() - w) * self.half_angle.tan()
    }

    /// Width of the groove at the depth of the pitch line, where groove and tooth are equal: P/2.
    /// Returns that depth, mm.
    pub fn pitch_line_depth(&self) -> f64 {
        self.sharp_root() - 0.25 * self.pitch / self.half_angle.tan()
    }

    /// The groove from `z = −P/2` (tooth centre) to `z = +P/2`, in `(z, depth)` coordinates.
    pub fn polyline(&self, tolerance: f64) -> Vec<Point> {
        let b = self.half_angle;
        let half = 0.5 * self.pitch;
        let mut out = Vec::new();
        // Left crest: from the tooth centre at z = −P/2 to where the left flank starts.
        match self.crest {
            Feature::Arc(rc) => {
                // Arc centre below the sharp crest (in depth: larger depth), top at depth 0.
                let c = Point::new(-half, rc);
                // In (z, depth) the arc bulges upward (towards smaller depth): parametrise by
                // angle in a frame with depth flipped.
                let a = Arc { center: Point::new(c.z, -c.r), radius: rc, start: FRAC_PI_2, end: b };
                extend_dedup(&mut out, a.tessellate(tolerance).into_iter().map(|p| Point::new(p.z, -p.r)));
            }
            Feature::Flat | Feature::FlatAt(_) => {
                debug_assert!(
                    !matches!(self.crest, Feature::FlatAt(d) if d != 0.0),
                    "a crest lies on the crest line"
                );
                extend_dedup(&mut out, [Point::new(-half, 0.0), Point::new(-self.flank_z(0.0), 0.0)]);
            }
        }
        // Root.
        match self.root {
            Feature::Arc(rr) => {
                let cz = 0.0;
                let cdepth = self.sharp_root() - rr / b.sin();
                // Flipped frame again: the root arc's lowest point is its greatest depth.
                // Two halves, so that the lowest point (d3) is a vertex of the polyline.
                for (start, end) in [(b - std::f64::consts::PI, -FRAC_PI_2), (-FRAC_PI_2, -b)] {
                    let a = Arc { center: Point::new(cz, -cdepth), radius: rr, start, end };
                    extend_dedup(
                        &mut out,
                        a.tessellate(tolerance).into_iter().map(|p| Point::new(p.z, -p.r)),
                    );
                }
            }
            Feature::FlatAt(w) => {
                let zf = self.flank_z(w);
                extend_dedup(&mut out, [Point::new(-zf, w), Point::new(zf, w)]);
            }
            Feature::Flat => {}
        }
        // Right crest (mirror of the left one).
        match self.crest {
            Feature::Arc(rc) => {
                let a = Arc {
                    center: Point::new(half, -rc),
                    radius: rc,
                    start: std::f64::consts::PI - b,
                    end: FRAC_PI_2,
                };
                extend_dedup(&mut out, a.tessellate(tolerance).into_iter().map(|p| Point::new(p.z, -p.r)));
            }
            Feature::Flat | Feature::FlatAt(_) => {
                extend_dedup(&mut out, [Point::new(self.flank_z(0.0), 0.0), Point::new(half, 0.0)]);
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn metric(d: f64, p: f64) -> BasicThread {
        BasicThread::metric(d, p)
    }

    /// ISO 68-1 / DIN 13 coefficients (shared/reference/README.md, VERIFIED).
    #[test]
    fn metric_basic_dimensions_match_iso_68_1() {
        for p in [0.5, 1.0, 1.5, 2.5, 6.0] {
            let t = metric(30.0, p);
            assert!((t.fundamental_height() - 0.866025 * p).abs() < 1e-6 * p);
            assert!((t.pitch_diameter() - (30.0 - 0.649519 * p)).abs() < 1e-6 * p);
            assert!((t.minor_diameter_internal() - (30.0 - 1.082532 * p)).abs() < 1e-6 * p);
            assert!((t.minor_diameter_external() - (30.0 - 1.226869 * p)).abs() < 1e-6 * p);
            assert!((t.engagement_depth() - 0.541266 * p).abs() < 1e-6 * p);
            assert!((t.thread_depth() - 0.613435 * p).abs() < 1e-6 * p);
            assert!((t.root_radius() - 0.144338 * p).abs() < 1e-6 * p);
        }
    }

    /// BS 84 form constants (shared/reference/README.md, VERIFIED).
    #[test]
    fn whitworth_form_constants() {
        let t = BasicThread {
            form: ThreadForm::Whitworth,
            nominal_diameter: 12.7,
            pitch: 25.4 / 12.0,
            starts: 1,
            hand: Hand::Right,
        };
        let p = t.pitch;
        assert!((t.fundamental_height() - 0.960491 * p).abs() < 1e-6 * p);
        assert!((t.thread_depth() - 0.640327 * p).abs() < 1e-6 * p);
        assert!((t.root_radius() - 0.137329 * p).abs() < 1e-6 * p);
    }

    /// The profile's flanks cross the pitch line where the groove is P/2 wide, at d2.
    #[test]
    fn profiles_put_the_pitch_line_at_d2() {
        for t in [metric(10.0, 1.5), metric(6.0, 1.0)] {
            for v in [ProfileKind::Basic, ProfileKind::BoltDesign, ProfileKind::BoltMinRoot, ProfileKind::Nut]
            {
                let g = t.groove(v);
                let w = g.pitch_line_depth();
                assert!((g.flank_z(w) - 0.25 * t.pitch).abs() < 1e-12);
                let r = match v {
                    ProfileKind::Nut => 0.5 * t.minor_diameter_internal() + w,
                    _ => 0.5 * t.nominal_diameter - w,
                };
                assert!((2.0 * r - t.pitch_diameter()).abs() < 1e-12, "{v:?}");
            }
        }
    }

    #[test]
    fn profile_depths_match_the_standard() {
        let t = metric(10.0, 1.5);
        let low = |v| t.profile(v, 5e-5).iter().map(|q| q.r).fold(f64::INFINITY, f64::min);
        let high = |v| t.profile(v, 5e-5).iter().map(|q| q.r).fold(f64::NEG_INFINITY, f64::max);
        assert!((2.0 * low(ProfileKind::BoltDesign) - t.minor_diameter_external()).abs() < 1e-12);
        assert!((2.0 * low(ProfileKind::Basic) - t.minor_diameter_internal()).abs() < 1e-12);
        assert!((2.0 * high(ProfileKind::Nut) - t.nominal_diameter).abs() < 1e-12);
        assert!((2.0 * low(ProfileKind::Nut) - t.minor_diameter_internal()).abs() < 1e-12);
        let w = BasicThread {
            form: ThreadForm::Whitworth,
            nominal_diameter: 12.7,
            pitch: 25.4 / 12.0,
            starts: 1,
            hand: Hand::Right,
        };
        let pts = w.profile(ProfileKind::BoltDesign, 5e-5);
        let top = pts.iter().map(|q| q.r).fold(f64::NEG_INFINITY, f64::max);
        let bot = pts.iter().map(|q| q.r).fold(f64::INFINITY, f64::min);
        assert!((top - 6.35).abs() < 1e-12);
        assert!((6.35 - bot - 0.640327 * w.pitch).abs() < 1e-6);
        // The profile is a function of z, left to right.
        assert!(pts.windows(2).all(|p| p[1].z >= p[0].z - 1e-15));
    }
}
