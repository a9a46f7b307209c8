//! The one module that talks to the polygon-boolean backend (`geo`, which runs `i_overlay`).
//!
//! Everything else in threadcheck sees [`Region`] and [`Point`]s. Rings handed to the backend are
//! oriented counter-clockwise first: geo's `unary_union` picks its fill rule from the first
//! ring's winding and silently drops rings wound the other way.
//!
//! **Precision.** i_overlay snaps every operation's input to an integer grid of pitch
//! `2^(⌊log2 h⌋ − 29)` where `h` is half the larger side of the operands' bounding box, centred
//! on that box: about 5 nm for a 6 mm window, 22 nm for the 24 mm window of M68x6. Callers keep
//! their operands tight (a blank only a little taller than the cut, a window of a few pitches)
//! so that snapping stays far inside the 0.1 µm budget.

use crate::ground::plane::Point;
use geo::orient::{Direction, Orient};
use geo::{Area, BooleanOps, Coord, LineString, MultiLineString, MultiPolygon, Polygon};
use rayon::prelude::*;

/// Signed area of a closed ring (geo's `Area`), mm²: positive when counter-clockwise in the
/// `(z, r)` plane.
pub fn signed_area(ring: &[Point]) -> f64 {
    if ring.len() < 3 {
        return 0.0;
    }
    Polygon::new(LineString::from(ring.iter().map(|p| Coord { x: p.z, y: p.r }).collect::<Vec<_>>()), vec![])
        .signed_area()
}

/// Whether the closed ring `ring` (first point not repeated, or repeated) holds `p` (geo's
/// `Contains`: a point on the boundary is not inside).
pub fn ring_contains(ring: &[Point], p: Point) -> bool {
    use geo::Contains;
    if ring.len() < 3 {
        return false;
    }
    Polygon::new(to_coords(ring), Vec::new()).contains(&Coord { x: p.z, y: p.r })
}

/// A set of polygons in the axial plane (z, r), mm. Exteriors counter-clockwise, holes clockwise.
#[derive(Clone, Debug, PartialEq)]
pub struct Region(MultiPolygon<f64>);

impl Default for Region {
    fn default() -> Region {
        Region::empty()
    }
}

/// How many polygons are unioned.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnionStrategy {
    /// Fold them one at a time: the textbook loop, quadratic in the size of the running result.
    Sequential,
    /// One `unary_union` over all rings at once (one overlay of everything).
    Unary,
    /// Pairwise as a balanced binary tree, neighbours first; levels run in parallel.
    BalancedTree,
    /// No union at all: the sweep takes the lower envelope of the imprints
    /// (the private `envelope` module). For a plain union of regions it is the balanced tree; the sweep falls
    /// back to the tree for inserts whose underside is not a function of z.
    Envelope,
}

fn to_coords(ring: &[Point]) -> LineString<f64> {
    let mut c: Vec<Coord<f64>> = ring.iter().map(|p| Coord { x: p.z, y: p.r }).collect();
    if let (Some(f), Some(l)) = (c.first().copied(), c.last().copied()) {
        if f != l {
            c.push(f);
        }
    }
    LineString::new(c)
}

fn from_coords(ls: &LineString<f64>) -> Vec<Point> {
    let mut v: Vec<Point> = ls.coords().map(|c| Point::new(c.x, c.y)).collect();
    if v.len() > 1 && v.first() == v.last() {
        v.pop();
    }
    remove_spikes(v)
}

/// Distance (mm) under which a vertex counts as lying on the line through its neighbours: a few
/// backend grid steps, far below the offset of a real arc vertex (about four times the chord
/// tolerance, which is at least [`crate::ground::plane::MIN_TOLERANCE`]).
pub const COLLINEAR: f64 = 2e-8;

/// Removes zero-width spikes (vertices where the ring runs out along a line and straight back),
/// vertices within 1e-7 mm of their neighbour, and vertices within [`COLLINEAR`] of the line
/// through their neighbours.
/// The backend leaves them where two operands share a collinear edge (a trailing flank sliding
/// along the finished flank); they enclose no area but would count twice as boundary.
fn remove_spikes(mut v: Vec<Point>) -> Vec<Point> {
    let mut changed = true;
    while changed && v.len() >= 3 {
        changed = false;
        let n = v.len();
        for i in 0..n {
            if v.len() < 3 {
                break;
            }
            let (a, b, c) = (v[(i + n - 1) % n], v[i], v[(i + 1) % n]);
            let (u, w) = (b - a, c - b);
            let (lu, lw) = (u.z.hypot(u.r), w.z.hypot(w.r));
            // Vertices a few grid steps apart are one vertex (a spike's apex can carry a jog).
            if lu < 1e-7 || lw < 1e-7 {
                v.remove(i);
                changed = true;
                break;
            }
            let cross = (u.z * w.r - u.r * w.z) / (lu * lw);
            let dot = u.z * w.z + u.r * w.r;
            if cross.abs() < 1e-6 && dot < 0.0 {
                v.remove(i);
                changed = true;
                break;
            }
            // A vertex within COLLINEAR of the line through its neighbours is one the backend
            // inserted where nearly coincident edges crossed (repeated passes snapped on
            // different grids); it lies on a chord, and a 3-point radius through it is wrong.
            let base = a.distance(c);
            if base > 0.0 && dot > 0.0 {
                let off = ((c.z - a.z) * (b.r - a.r) - (c.r - a.r) * (b.z - a.z)).abs() / base;
                if off < COLLINEAR {
                    v.remove(i);
                    changed = true;
                    break;
                }
            }
        }
    }
    v
}

impl Region {
    /// The empty region.
    pub fn empty() -> Region {
        Region(MultiPolygon::new(Vec::new()))
    }

    /// A simple polygon from one ring (any winding; it is oriented counter-clockwise).
    pub fn from_ring(ring: &[Point]) -> Region {
        let p = Polygon::new(to_coords(ring), Vec::new());
        Region(MultiPolygon::new(vec![p.orient(Direction::Default)]))
    }

    /// The axis-aligned rectangle z ∈ [z0, z1], r ∈ [r0, r1].
    pub fn rect(z0: f64, z1: f64, r0: f64, r1: f64) -> Region {
        Region::from_ring(&[Point::new(z0, r0), Point::new(z1, r0), Point::new(z1, r1), Point::new(z0, r1)])
    }

    /// True when the region holds no polygon.
    pub fn is_empty(&self) -> bool {
        self.0 .0.is_empty()
    }

    /// Area, mm².
    pub fn area(&self) -> f64 {
        self.0.unsigned_area()
    }

    /// Union with `other`.
    pub fn union(&self, other: &Region) -> Region {
        if self.is_empty() {
            return other.clone();
        }
        if other.is_empty() {
            return self.clone();
        }
        Region(self.0.union(&other.0).orient(Direction::Default))
    }

    /// `self` minus `other`.
    pub fn difference(&self, other: &Region) -> Region {
        if self.is_empty() || other.is_empty() {
            return self.clone();
        }
        Region(self.0.difference(&other.0).orient(Direction::Default))
    }

    /// `self` ∩ `other`.
    pub fn intersection(&self, other: &Region) -> Region {
        if self.is_empty() || other.is_empty() {
            return Region::empty();
        }
        Region(self.0.intersection(&other.0).orient(Direction::Default))
    }

    /// The polygons as (exterior, holes); exteriors counter-clockwise, holes clockwise, rings not
    /// closed (the first point is not repeated).
    pub fn polygons(&self) -> Vec<(Vec<Point>, Vec<Vec<Point>>)> {
        self.0
            .iter()
            .map(|p| (from_coords(p.exterior()), p.interiors().iter().map(from_coords).collect()))
            .collect()
    }

    /// The parts of the open polyline `line` that lie inside the region (boundary included).
    pub fn clip_polyline(&self, line: &[Point]) -> Vec<Vec<Point>> {
        if self.is_empty() || line.len() < 2 {
            return Vec::new();
        }
        let ls = LineString::new(line.iter().map(|p| Coord { x: p.z, y: p.r }).collect());
        let mls = MultiLineString::new(vec![ls]);
        self.0
            .clip(&mls, false)
            .0
            .iter()
            .map(|l| l.coords().map(|c| Point::new(c.x, c.y)).collect())
            .collect()
    }
}

/// Unions `regions` with `strategy`. Give them in a spatial order (e.g. by z) for the balanced
/// tree to merge neighbours first.
pub fn union_all(regions: Vec<Region>, strategy: UnionStrategy) -> Region {
    match strategy {
        UnionStrategy::Sequential => regions.iter().fold(Region::empty(), |acc, r| acc.union(r)),
        UnionStrategy::Unary => {
            let polys: Vec<Polygon<f64>> = regions.into_iter().flat_map(|r| r.0 .0).collect();
            Region(geo::unary_union(&polys).orient(Direction::Default))
        }
        UnionStrategy::BalancedTree | UnionStrategy::Envelope => {
            let mut level = regions;
            while level.len() > 1 {
                let pair = |c: &[Region]| if c.len() == 2 { c[0].union(&c[1]) } else { c[0].clone() };
                // Parallel only where there is enough work to pay for the threads.
                level = if level.len() >= 64 {
                    level.par_chunks(2).map(pair).collect()
                } else {
                    level.chunks(2).map(pair).collect()
                };
            }
            level.pop().unwrap_or_default()
        }
    }
}

/// Whether the segments `a` and `b` (each two ends) meet: cross, touch or overlap.
pub fn segments_meet(a: (Point, Point), b: (Point, Point)) -> bool {
    use geo::line_intersection::line_intersection;
    let line = |(p, q): (Point, Point)| geo::Line::new(Coord { x: p.z, y: p.r }, Coord { x: q.z, y: q.r });
    line_intersection(line(a), line(b)).is_some()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn signed_area_is_positive_counter_clockwise() {
        let square = [Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(1.0, 1.0), Point::new(0.0, 1.0)];
        assert_eq!(signed_area(&square), 1.0);
        let mut clockwise = square;
        clockwise.reverse();
        assert_eq!(signed_area(&clockwise), -1.0);
    }

    #[test]
    fn rectangles_union_and_difference() {
        let a = Region::rect(0.0, 2.0, 0.0, 1.0);
        let b = Region::rect(1.0, 3.0, 0.0, 1.0);
        assert!((a.union(&b).area() - 3.0).abs() < 1e-12);
        assert!((a.difference(&b).area() - 1.0).abs() < 1e-12);
        assert!((a.intersection(&b).area() - 1.0).abs() < 1e-12);
    }

    /// A clockwise ring is oriented before it reaches the backend, so it is not dropped.
    #[test]
    fn clockwise_rings_are_not_dropped() {
        let cw = [Point::new(0.0, 0.0), Point::new(0.0, 1.0), Point::new(1.0, 1.0), Point::new(1.0, 0.0)];
        let ccw = Region::rect(2.0, 3.0, 0.0, 1.0);
        for s in [UnionStrategy::Sequential, UnionStrategy::Unary, UnionStrategy::BalancedTree] {
            let u = union_all(vec![ccw.clone(), Region::from_ring(&cw)], s);
            assert!((u.area() - 2.0).abs() < 1e-12, "{s:?}");
        }
    }

    #[test]
    fn strategies_agree_on_overlapping_squares() {
        let regions: Vec<Region> =
            (0..50).map(|i| Region::rect(0.1 * i as f64, 0.1 * i as f64 + 1.0, 0.0, 1.0)).collect();
        let want = 5.9;
        for s in [UnionStrategy::Sequential, UnionStrategy::Unary, UnionStrategy::BalancedTree] {
            let got = union_all(regions.clone(), s).area();
            // 50 operations on a 6 mm box: each may move a 1 mm edge by one 4 nm grid step.
            assert!((got - want).abs() < 50.0 * 1.0 * 4e-9, "{s:?} {got}");
        }
    }

    #[test]
    fn spikes_are_removed() {
        let ring = vec![
            Point::new(0.0, 0.0),
            Point::new(2.0, 0.0),
            Point::new(2.0, 1.0),
            Point::new(3.0, 2.0), // out along a line ...
            Point::new(2.0, 1.0), // ... and back
            Point::new(0.0, 1.0),
        ];
        let clean = remove_spikes(ring);
        assert_eq!(clean.len(), 4);
    }

    #[test]
    fn clipping_a_polyline() {
        let a = Region::rect(0.0, 1.0, 0.0, 1.0);
        let parts = a.clip_polyline(&[Point::new(-1.0, 0.5), Point::new(2.0, 0.5)]);
        let len: f64 = parts.iter().map(|p| p.windows(2).map(|w| w[0].distance(w[1])).sum::<f64>()).sum();
        assert!((len - 1.0).abs() < 1e-12);
    }
}
