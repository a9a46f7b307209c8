//! Plain geometry of the axial section: points, arcs tessellated by chord tolerance, polylines.
//!
//! Coordinates are `(z, r)` in millimetres: `z` along the spindle axis (the lathe's Z), `r` the
//! **radius** from the axis. Lathe X values are diameters; convert with [`dia`] and [`rad`] at the
//! edges of the program, never inside geometry, so that angles stay Euclidean.

use std::f64::consts::PI;

/// A point of the axial half-plane: `z` along the axis, `r` radius from the axis, both in mm.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Point {
    /// Axial position, mm.
    pub z: f64,
    /// Radius from the spindle axis, mm (half the lathe X value).
    pub r: f64,
}

impl Point {
    /// A point from its axial position and radius, both in mm.
    pub const fn new(z: f64, r: f64) -> Point {
        Point { z, r }
    }

    /// Euclidean distance to `other`, mm. The square root of the sum of squares: libm's
    /// `hypot` guards against overflow and underflow that lengths in mm never reach, at several
    /// times the cost, and the envelope and measurement call this in their inner loops.
    pub fn distance(self, other: Point) -> f64 {
        ((self.z - other.z).powi(2) + (self.r - other.r).powi(2)).sqrt()
    }

    /// True when both coordinates are finite.
    pub fn is_finite(self) -> bool {
        self.z.is_finite() && self.r.is_finite()
    }
}

impl std::ops::Add for Point {
    type Output = Point;
    fn add(self, o: Point) -> Point {
        Point::new(self.z + o.z, self.r + o.r)
    }
}

impl std::ops::Sub for Point {
    type Output = Point;
    fn sub(self, o: Point) -> Point {
        Point::new(self.z - o.z, self.r - o.r)
    }
}

/// Diameter (lathe X) from a radius, mm.
pub fn dia(radius: f64) -> f64 {
    2.0 * radius
}

/// Radius from a diameter (lathe X), mm.
pub fn rad(diameter: f64) -> f64 {
    0.5 * diameter
}

/// Smallest chord tolerance accepted, mm (0.001 µm): finer would put arc vertices within the
/// backend's snapping noise.
pub const MIN_TOLERANCE: f64 = 1e-6;

/// Default chord tolerance for arcs, mm: 0.05 µm, so that tessellation stays well inside the
/// 0.1 µm accuracy budget of every measured value.
pub const DEFAULT_TOLERANCE: f64 = 5e-5;

/// A circular arc in the axial plane. Angles are radians, measured from the +z axis towards +r,
/// and the arc runs from `start` to `end` (counter-clockwise when `end > start`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Arc {
    /// Centre of the circle.
    pub center: Point,
    /// Radius of the circle, mm (> 0).
    pub radius: f64,
    /// Start angle, radians.
    pub start: f64,
    /// End angle, radians; `end < start` runs clockwise.
    pub end: f64,
}

impl Arc {
    /// The point of the arc at angle `a` (radians).
    pub fn point_at(&self, a: f64) -> Point {
        Point::new(self.center.z + self.radius * a.cos(), self.center.r + self.radius * a.sin())
    }

    /// Number of chords needed so that no chord is farther than `tolerance` (mm) from the arc.
    ///
    /// The sagitta of a chord spanning angle θ is `R·(1 − cos(θ/2))`; solving for θ gives the
    /// largest step. At least one chord is always used.
    pub fn segments_for(&self, tolerance: f64) -> usize {
        let sweep = (self.end - self.start).abs();
        if sweep == 0.0 || self.radius <= tolerance {
            return 1;
        }
        let step = 2.0 * (1.0 - tolerance / self.radius).clamp(-1.0, 1.0).acos();
        // Bounded so that an absurd tolerance cannot ask for millions of points.
        ((sweep / step).ceil() as usize).clamp(1, 100_000)
    }

    /// The arc as points from start to end inclusive, each on the circle, chords within
    /// `tolerance` (mm) of the true arc.
    pub fn tessellate(&self, tolerance: f64) -> Vec<Point> {
        let n = self.segments_for(tolerance);
        (0..=n)
            .map(|i| self.point_at(self.start + (self.end - self.start) * (i as f64) / (n as f64)))
            .collect()
    }
}

/// Appends `pts` to `out`, skipping a first point that repeats the current last one.
pub fn extend_dedup(out: &mut Vec<Point>, pts: impl IntoIterator<Item = Point>) {
    for p in pts {
        if out.last().is_none_or(|q| q.distance(p) > 1e-12) {
            out.push(p);
        }
    }
}

/// Angle in radians from degrees.
pub fn deg(d: f64) -> f64 {
    d * PI / 180.0
}

/// Height of `line` (vertices with non-decreasing z) at `z`, if it spans it; at a vertical step,
/// the higher end.
pub(crate) fn height_at(line: &[Point], z: f64) -> Option<f64> {
    let j = line.partition_point(|q| q.z < z);
    if j == 0 || j >= line.len() {
        return (j < line.len() && line[j].z == z).then(|| line[j].r);
    }
    let (a, b) = (line[j - 1], line[j]);
    if a.z == b.z {
        return Some(a.r.max(b.r));
    }
    Some(a.r + (z - a.z) / (b.z - a.z) * (b.r - a.r))
}

/// Where the segment `a`–`b` crosses the horizontal line `r = level`, as a `z` value, if it does
/// (end points included).
pub fn cross_at_level(a: Point, b: Point, level: f64) -> Option<f64> {
    if (a.r - level) * (b.r - level) > 0.0 || a.r == b.r {
        return None;
    }
    let t = (level - a.r) / (b.r - a.r);
    Some(a.z + t * (b.z - a.z))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chord_tolerance_is_respected_and_tight() {
        let arc = Arc { center: Point::new(0.0, 0.0), radius: 0.2165, start: 0.0, end: PI };
        let tol = 5e-5;
        let pts = arc.tessellate(tol);
        // Sagitta of every chord is within tolerance, and not wastefully small (over half).
        let mut worst: f64 = 0.0;
        for w in pts.windows(2) {
            let mid = Point::new(0.5 * (w[0].z + w[1].z), 0.5 * (w[0].r + w[1].r));
            worst = worst.max(arc.radius - mid.distance(arc.center));
        }
        assert!(worst <= tol * (1.0 + 1e-9), "sagitta {worst}");
        assert!(worst > 0.5 * tol, "sagitta {worst} is needlessly fine");
        for p in &pts {
            assert!((p.distance(arc.center) - arc.radius).abs() < 1e-12);
        }
    }

    #[test]
    fn level_crossing() {
        let z = cross_at_level(Point::new(0.0, 0.0), Point::new(2.0, 4.0), 1.0);
        assert_eq!(z, Some(0.5));
        assert_eq!(cross_at_level(Point::new(0.0, 2.0), Point::new(1.0, 3.0), 1.0), None);
    }
}
