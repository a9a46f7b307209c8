//! Threading inserts as polygons in their own frame.
//!
//! **Insert frame**: `z` across the insert (the lathe's Z direction when mounted for an external
//! thread), `r` from the tip **into the tool body**. The tip reference point, the point that
//! reaches the programmed X, is the origin, and the whole insert lies at `r ≥ 0`. Outlines are
//! counter-clockwise. Arcs are tessellated to an explicit chord tolerance (mm) with their
//! extreme points kept as vertices.
//!
//! Placement in the part uses a `nalgebra` isometry: a rotation of 0 for external threads, π for
//! internal threads (the tip then points away from the axis), so an inclined or mis-set insert is
//! one more rotation away.

use crate::geometry::boolean::signed_area;
use crate::geometry::parry::Placement;
use crate::ground::bounds::{MAX_INSERT_REACH, MAX_OUTLINE_POINTS};
use crate::ground::plane::{deg, extend_dedup, Arc, Point};
use crate::standards::{BasicThread, ProfileKind, ThreadKind};
use crate::Error;
use serde::{Deserialize, Serialize};
use std::f64::consts::{FRAC_PI_2, PI};

/// What kind of insert this is, as reported.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum InsertKind {
    /// Forms the whole standard tooth, including the crest, for one pitch and form.
    Full,
    /// A V insert with a small tip radius for a range of pitches.
    Partial,
    /// Any polygon read from a TOML file.
    Custom,
}

/// A threading insert: its outline in the insert frame and what is known about it.
#[derive(Clone, Debug, PartialEq)]
pub struct Insert {
    /// Full, partial or custom.
    pub kind: InsertKind,
    /// A name for reports (`full M10x1.5`, `partial 60° r0.04`, the TOML file's `name`).
    pub name: String,
    /// Included angle of the cutting edges, degrees (60, 55, …).
    pub angle: f64,
    /// Tip (nose) radius, mm.
    pub tip_radius: f64,
    /// Pitches the insert is made for, mm, inclusive; `None` when unrestricted.
    pub pitch_range: Option<(f64, f64)>,
    /// The side clearance angle under the cutting edges, degrees, when the insert file gives it
    /// (for the flank-clearance process check).
    pub clearance_angle: Option<f64>,
    /// Height of the tip zone, mm: outline points below it count as the tip when engaged edges
    /// are reported; the rest is the leading or trailing flank.
    pub tip_zone: f64,
    /// Closed outline, counter-clockwise, first point not repeated, in the insert frame (mm).
    pub outline: Vec<Point>,
}

impl Insert {
    /// A full-profile insert for `thread` as `kind`: it forms both flanks, the standard root
    /// (DIN 13 radius H/6, or the Whitworth radius) and tops the crest (the crest-forming edges
    /// reach the crest line: d for external threads, D1 for internal ones). A trapezoid form's
    /// insert (Tr, Acme) forms the flanks and the flat root only.
    ///
    /// Its shoulders run P/32 past the tooth centre on each side, inside the neighbouring crest,
    /// so that adjacent imprints overlap instead of touching edge to edge.
    pub fn full_profile(thread: &BasicThread, kind: ThreadKind, tolerance: f64) -> Insert {
        let variant = match kind {
            ThreadKind::External => ProfileKind::BoltDesign,
            ThreadKind::Internal => ProfileKind::Nut,
        };
        let g = thread.groove(variant);
        let bottom = g.bottom();
        let half = 0.5 * thread.pitch;
        let s = thread.pitch / 32.0;
        let top = bottom + thread.pitch.max(1.0);
        let mut outline = Vec::new();
        if thread.form.full_insert_tops_crest() {
            // Along the cutting edge, left to right: the groove profile, turned so depth becomes
            // height above the tip.
            extend_dedup(&mut outline, [Point::new(-half - s, bottom)]);
            extend_dedup(
                &mut outline,
                g.polyline(tolerance).into_iter().map(|q| Point::new(q.z, bottom - q.r)),
            );
            extend_dedup(
                &mut outline,
                [Point::new(half + s, bottom), Point::new(half + s, top), Point::new(-half - s, top)],
            );
        } else {
            // The flat tip of the root and the flanks carried on past the crest line: the
            // insert forms flanks and root and leaves the turned crest alone.
            let zr = g.flank_z(bottom);
            let zt = g.flank_z(bottom - top);
            outline.extend([
                Point::new(-zt, top),
                Point::new(-zr, 0.0),
                Point::new(zr, 0.0),
                Point::new(zt, top),
            ]);
        }
        let tip_radius = match g.root {
            crate::standards::Feature::Arc(r) => r,
            // A flat root is formed by a flat tip: no tip radius.
            crate::standards::Feature::Flat | crate::standards::Feature::FlatAt(_) => 0.0,
        };
        Insert {
            kind: InsertKind::Full,
            name: if thread.form.is_inch() {
                format!(
                    "full-profile {} {} tpi",
                    thread.form.name(),
                    crate::ground::fmt::fmt_num(25.4 / thread.pitch)
                )
            } else {
                format!("full-profile {} P{}", thread.form.name(), crate::ground::fmt::fmt_num(thread.pitch))
            },
            angle: thread.form.flank_angle(),
            tip_radius,
            pitch_range: Some((thread.pitch, thread.pitch)),
            clearance_angle: None,
            tip_zone: tip_radius.max(1e-9),
            outline,
        }
    }

    /// A partial-profile V insert: included angle `angle` (degrees), tip radius `tip_radius`
    /// (mm, tangent to both edges), edges `height` mm tall above the tip.
    pub fn partial(angle: f64, tip_radius: f64, height: f64, tolerance: f64) -> Result<Insert, Error> {
        if !(angle.is_finite() && angle > 0.0 && angle < 180.0) {
            return Err(Error::Input(format!("insert angle {angle}° is not between 0 and 180")));
        }
        if !(tip_radius.is_finite() && tip_radius >= 0.0) {
            return Err(Error::Input(format!("tip radius {tip_radius} mm is not a length ≥ 0")));
        }
        if !(height.is_finite() && height > 2.0 * tip_radius) {
            return Err(Error::Input(format!("insert height {height} mm must exceed twice the tip radius")));
        }
        let b = 0.5 * deg(angle);
        let mut outline = Vec::new();
        let flank_z = |y: f64| {
            // Edge line tangent to the tip circle (centre (0, rε)): |z| = (y − y_t)·tan β + rε·cos β.
            let yt = tip_radius * (1.0 - b.sin());
            (y - yt) * b.tan() + tip_radius * b.cos()
        };
        let zt = flank_z(height);
        outline.push(Point::new(-zt, height));
        if tip_radius > 0.0 {
            let c = Point::new(0.0, tip_radius);
            for (s, e) in [(b - PI, -FRAC_PI_2), (-FRAC_PI_2, -b)] {
                let a = Arc { center: c, radius: tip_radius, start: s, end: e };
                extend_dedup(&mut outline, a.tessellate(tolerance));
            }
        } else {
            outline.push(Point::new(0.0, 0.0));
        }
        extend_dedup(&mut outline, [Point::new(zt, height)]);
        Ok(Insert {
            kind: InsertKind::Partial,
            name: format!("partial {angle}° r{}", crate::ground::fmt::fmt_num(tip_radius)),
            angle,
            tip_radius,
            pitch_range: None,
            clearance_angle: None,
            tip_zone: tip_radius.max(1e-9),
            outline,
        })
    }

    /// The default partial insert for `thread`: the form's angle, tip radius `tip_radius`, tall
    /// enough for the deepest partial-profile cut plus half a millimetre.
    pub fn partial_for(thread: &BasicThread, tip_radius: f64, tolerance: f64) -> Result<Insert, Error> {
        let h = thread.fundamental_height();
        Insert::partial(thread.form.flank_angle(), tip_radius, 1.2 * h + 0.5, tolerance)
    }

    /// Reads a custom insert from TOML text (see `profiles/inserts/`). `file` names it in errors.
    pub fn from_toml(text: &str, file: &str, tolerance: f64) -> Result<Insert, Error> {
        let ferr = |m: String| Error::File { file: file.to_string(), message: m };
        let spec: InsertFile =
            toml::from_str(text).map_err(|e| crate::ground::error::toml_error(&e, text, file))?;
        let tip_radius = spec.tip_radius.unwrap_or(0.0);
        let mut ins = match (&spec.outline, spec.angle) {
            (Some(points), _) => {
                let outline = outline_from_points(points, tolerance).map_err(ferr)?;
                Insert {
                    kind: InsertKind::Custom,
                    name: crate::ground::fmt::shown_text(spec.name.as_deref().unwrap_or(file)),
                    angle: spec.angle.unwrap_or(0.0),
                    tip_radius,
                    pitch_range: None,
                    clearance_angle: None,
                    tip_zone: spec.tip_zone.unwrap_or(tip_radius.max(0.01)),
                    outline,
                }
            }
            (None, Some(angle)) => {
                let height = spec.height.unwrap_or(3.0);
                let mut i =
                    Insert::partial(angle, tip_radius, height, tolerance).map_err(|e| ferr(e.to_string()))?;
                if let Some(n) = &spec.name {
                    i.name = crate::ground::fmt::shown_text(n);
                }
                i
            }
            (None, None) => {
                return Err(ferr("an insert needs `angle` (V insert) or `outline` (polygon)".into()))
            }
        };
        if let Some([a, b]) = spec.pitch_range {
            if !(a.is_finite() && b.is_finite() && 0.0 < a && a <= b) {
                return Err(ferr(format!("pitch_range [{a}, {b}] is not an increasing pair of pitches")));
            }
            ins.pitch_range = Some((a, b));
        }
        if let Some(c) = spec.clearance_angle {
            if !(c.is_finite() && (0.0..45.0).contains(&c)) {
                return Err(ferr(format!("clearance_angle {c}° must be from 0 to under 45")));
            }
            ins.clearance_angle = Some(c);
        }
        Ok(ins)
    }

    /// Width of the insert (extent in z), mm.
    pub fn width(&self) -> f64 {
        let (lo, hi) = self
            .outline
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| (lo.min(p.z), hi.max(p.z)));
        hi - lo
    }

    /// Extent in z, (min, max), mm.
    pub fn z_extent(&self) -> (f64, f64) {
        self.outline.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| (lo.min(p.z), hi.max(p.z)))
    }

    /// Height of the insert above its tip, mm.
    pub fn height(&self) -> f64 {
        self.outline.iter().map(|p| p.r).fold(0.0, f64::max)
    }

    /// The isometry that puts the insert tip at axial position `z` and radius `r_tip`, for an
    /// external (rotation 0) or internal (rotation π) thread.
    pub fn placement(z: f64, r_tip: f64, kind: ThreadKind) -> Placement {
        let angle = match kind {
            ThreadKind::External => 0.0,
            ThreadKind::Internal => PI,
        };
        Placement::new(z, r_tip, angle)
    }

    /// The outline placed by `at`, in part coordinates `(z, r)`, still counter-clockwise
    /// (a proper rotation keeps the orientation).
    pub fn placed(&self, at: &Placement) -> Vec<Point> {
        self.outline.iter().map(|&p| at.apply(p)).collect()
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct InsertFile {
    name: Option<String>,
    angle: Option<f64>,
    tip_radius: Option<f64>,
    height: Option<f64>,
    tip_zone: Option<f64>,
    pitch_range: Option<[f64; 2]>,
    /// Side clearance angle, degrees.
    clearance_angle: Option<f64>,
    /// Points `[z, r]` or `[z, r, bulge]`: a bulge b ≠ 0 makes the edge to the next point an arc
    /// of included angle 4·atan(b), counter-clockwise for b > 0 (the DXF convention).
    outline: Option<Vec<Vec<f64>>>,
}

fn outline_from_points(points: &[Vec<f64>], tolerance: f64) -> Result<Vec<Point>, String> {
    if points.len() < 3 {
        return Err(format!("an outline needs at least 3 points, not {}", points.len()));
    }
    if points.len() > crate::ground::bounds::MAX_OUTLINE_POINTS {
        return Err(format!(
            "an outline of {} points is more than the {} threadcheck accepts",
            points.len(),
            crate::ground::bounds::MAX_OUTLINE_POINTS
        ));
    }
    let mut verts = Vec::with_capacity(points.len());
    for (i, p) in points.iter().enumerate() {
        let (z, r, b) = match p.as_slice() {
            [z, r] => (*z, *r, 0.0),
            [z, r, b] => (*z, *r, *b),
            _ => return Err(format!("outline point {} must be [z, r] or [z, r, bulge]", i + 1)),
        };
        if !(z.is_finite() && r.is_finite() && b.is_finite()) {
            return Err(format!("outline point {} is not finite", i + 1));
        }
        if z.hypot(r) > MAX_INSERT_REACH {
            return Err(format!(
                "outline point {} is {:.1} mm from the tip; an insert reaches at most {MAX_INSERT_REACH} mm",
                i + 1,
                z.hypot(r)
            ));
        }
        if b.abs() > 1e3 {
            return Err(format!("outline point {}: bulge {b} is not a usable arc", i + 1));
        }
        verts.push((Point::new(z, r), b));
    }
    let mut out = Vec::new();
    for i in 0..verts.len() {
        let (a, b) = verts[i];
        let (c, _) = verts[(i + 1) % verts.len()];
        extend_dedup(&mut out, [a]);
        if b != 0.0 && a.distance(c) > 0.0 {
            // Bulge arc: included angle θ = 4·atan(b); radius from the chord.
            let theta = 4.0 * b.atan();
            let chord = a.distance(c);
            let radius = chord / (2.0 * (0.5 * theta).sin().abs());
            let mid = Point::new(0.5 * (a.z + c.z), 0.5 * (a.r + c.r));
            let dist = radius * (0.5 * theta).cos();
            let (dz, dr) = ((c.z - a.z) / chord, (c.r - a.r) / chord);
            // Centre lies to the left of the chord for a counter-clockwise arc of less than π.
            let sign = if theta > 0.0 { 1.0 } else { -1.0 };
            let centre = Point::new(mid.z - sign * dr * dist, mid.r + sign * dz * dist);
            let start = (a.r - centre.r).atan2(a.z - centre.z);
            let arc = Arc { center: centre, radius, start, end: start + theta };
            if out.len() + arc.segments_for(tolerance) > MAX_OUTLINE_POINTS {
                return Err(format!(
                    "the arc after outline point {} needs more than the {MAX_OUTLINE_POINTS} outline points threadcheck accepts at a {tolerance} mm chord tolerance",
                    i + 1
                ));
            }
            let pts = arc.tessellate(tolerance);
            extend_dedup(&mut out, pts.into_iter().skip(1).take_while(|p| p.distance(c) > 1e-12));
        }
    }
    if out.len() > 1 && out[0].distance(out[out.len() - 1]) < 1e-12 {
        out.pop();
    }
    if let Some((i, j)) = first_self_intersection(&out) {
        return Err(format!("the outline crosses itself (edges {} and {})", i + 1, j + 1));
    }
    let area = signed_area(&out);
    if area.abs() < 1e-12 {
        return Err("the outline encloses no area".into());
    }
    if area < 0.0 {
        out.reverse();
    }
    let min_r = out.iter().map(|p| p.r).fold(f64::INFINITY, f64::min);
    if min_r.abs() > 1e-6 {
        return Err(format!("the tip reference point must be the origin: the lowest outline point is at r = {min_r} mm, not 0"));
    }
    Ok(out)
}

fn first_self_intersection(ring: &[Point]) -> Option<(usize, usize)> {
    let n = ring.len();
    let seg = |i: usize| (ring[i], ring[(i + 1) % n]);
    // Sweep along z: only edges whose z-extents overlap can cross.
    let extent = |i: usize| {
        let (a, b) = (ring[i], ring[(i + 1) % n]);
        (a.z.min(b.z), a.z.max(b.z))
    };
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| extent(a).0.total_cmp(&extent(b).0));
    let mut found: Option<(usize, usize)> = None;
    for (k, &i) in order.iter().enumerate() {
        let hi = extent(i).1;
        for &j in &order[k + 1..] {
            if extent(j).0 > hi {
                break;
            }
            let (a, b) = (i.min(j), i.max(j));
            if b == a + 1 || (a == 0 && b == n - 1) {
                continue;
            }
            if crate::geometry::boolean::segments_meet(seg(a), seg(b)) && found.is_none_or(|f| (a, b) < f) {
                found = Some((a, b));
            }
        }
    }
    found
}

#[cfg(test)]
mod tests {
    use super::*;

    fn m(d: f64, p: f64) -> BasicThread {
        BasicThread::metric(d, p)
    }

    #[test]
    fn partial_insert_geometry() {
        let i = Insert::partial(60.0, 0.04, 2.0, 5e-5).unwrap();
        assert!(signed_area(&i.outline) > 0.0);
        let low = i.outline.iter().map(|p| p.r).fold(f64::INFINITY, f64::min);
        assert_eq!(low, 0.0);
        // The sharp vertex of the V is r/sin(30°) − r = r below the tip: its edges, extended,
        // meet at r = −0.04.
        let top = i.outline[0];
        let slope = top.z.abs() / (top.r + 0.04);
        assert!((slope - deg(30.0).tan()).abs() < 1e-12);
    }

    #[test]
    fn full_profile_insert_spans_a_pitch_and_is_ccw() {
        let i = Insert::full_profile(&m(10.0, 1.5), ThreadKind::External, 5e-5);
        assert!(signed_area(&i.outline) > 0.0);
        assert!((i.width() - 1.5 * (1.0 + 1.0 / 16.0)).abs() < 1e-12);
        assert!((i.tip_radius - 1.5 * 0.866025 / 6.0).abs() < 1e-6);
        assert!(first_self_intersection(&i.outline).is_none());
    }

    #[test]
    fn custom_outline_with_bulge_and_errors() {
        let v =
            "name = \"v\"\noutline = [[-1.0, 2.0], [-0.05, 0.05, 0.2679491924], [0.05, 0.05], [1.0, 2.0]]\n";
        let i = Insert::from_toml(v, "v.toml", 5e-5).unwrap_err();
        // The lowest point of that arc is below the origin: it must say so.
        assert!(i.to_string().contains("tip reference"), "{i}");
        let bow = "outline = [[0, 0], [1, 1], [1, 0], [0, 1]]\n";
        let e = Insert::from_toml(bow, "bow.toml", 5e-5).unwrap_err().to_string();
        assert!(e.contains("crosses itself"), "{e}");
        let bad = "angle = 60\ntip_radius = \"x\"\n";
        let e = Insert::from_toml(bad, "bad.toml", 5e-5).unwrap_err().to_string();
        assert!(e.starts_with("bad.toml:2:"), "{e}");
    }

    /// Every shipped insert file loads, is counter-clockwise and has its tip at the origin.
    #[test]
    fn shipped_insert_files_load() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("profiles/inserts");
        let mut n = 0;
        for e in std::fs::read_dir(dir).unwrap() {
            let path = e.unwrap().path();
            let text = std::fs::read_to_string(&path).unwrap();
            let ins = Insert::from_toml(&text, &path.display().to_string(), 5e-5).unwrap();
            assert!(signed_area(&ins.outline) > 0.0);
            let low = ins.outline.iter().map(|p| p.r).fold(f64::INFINITY, f64::min);
            assert!(low.abs() < 1e-6, "{}: {low}", path.display());
            n += 1;
        }
        assert!(n >= 4);
    }

    /// The bulge example is a V with a 0.1 mm tip arc: its edges are tangent to that arc, so it
    /// matches the analytic partial insert (centre 2r above the sharp vertex).
    #[test]
    fn bulge_outline_matches_the_analytic_v() {
        let path =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("profiles/inserts/custom-example.toml");
        let ins = Insert::from_toml(&std::fs::read_to_string(path).unwrap(), "custom", 5e-5).unwrap();
        // All arc points at distance 0.1 from the centre (0, 0.1).
        let arc: Vec<&Point> = ins.outline.iter().filter(|p| p.r < 0.05 - 1e-9).collect();
        assert!(arc.len() > 5);
        for p in arc {
            assert!((p.distance(Point::new(0.0, 0.1)) - 0.1).abs() < 1e-6, "{p:?}");
        }
    }

    /// Regression (found by the insert_toml fuzz target): a bulge arc with a 10⁸ mm chord was
    /// tessellated to 100 000 points and the self-intersection check took 19 s. It is refused at
    /// once for its reach, and an arc that needs too many points is refused by name.
    #[test]
    fn regression_fuzz_insert_huge_bulge_arc_timeout() {
        let text = "outline = [[-111266025, 0.05, 0.57735003], [5.0866, 0.05], [1.1547005, 2.0]]\n";
        let e = Insert::from_toml(text, "fuzz.toml", 1e-3).unwrap_err().to_string();
        assert!(e.contains("from the tip"), "{e}");
        // A large but plausible half circle at a needlessly fine tolerance: too many points.
        let text = "outline = [[-99, 0, 1.0], [99, 0], [0, 1]]\n";
        let e = Insert::from_toml(text, "big.toml", 1e-9).unwrap_err().to_string();
        assert!(e.contains("outline points"), "{e}");
    }

    #[test]
    fn placement_turns_internal_inserts_over() {
        let i = Insert::partial(60.0, 0.0, 1.0, 5e-5).unwrap();
        let out = i.placed(&Insert::placement(3.0, 5.0, ThreadKind::Internal));
        assert!(out.iter().all(|p| p.r <= 5.0 + 1e-12));
        assert!(signed_area(&out) > 0.0);
    }
}
