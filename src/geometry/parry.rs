//! The one door to `parry2d-f64`: distances to polylines and segments, projections, the
//! rigid placement of an outline and a ball dropped onto a polyline. Every other module speaks
//! [`Point`]s; parry's and nalgebra's types stay in here.

use crate::ground::plane::Point;
use parry2d_f64::math::Point as PPoint;
use parry2d_f64::na::{Isometry2, Point2, Vector2};
use parry2d_f64::query::{cast_shapes, PointQuery, PointQueryWithLocation, ShapeCastOptions};
use parry2d_f64::shape::{Ball, Polyline, Segment};

fn pp(p: Point) -> PPoint<f64> {
    PPoint::new(p.z, p.r)
}

/// A polyline with its search tree, built once for many queries.
#[derive(Clone)]
pub struct Line(Polyline);

impl std::fmt::Debug for Line {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_tuple("Line").field(&self.0.vertices().len()).finish()
    }
}

impl Line {
    /// The polyline through `pts` in order.
    pub fn through(pts: impl IntoIterator<Item = Point>) -> Line {
        Line(Polyline::new(pts.into_iter().map(pp).collect(), None))
    }

    /// Distance from `q` to the line.
    pub fn distance(&self, q: Point) -> f64 {
        self.0.distance_to_local_point(&pp(q), false)
    }

    /// The nearest point of the line to `q` and the index of its segment.
    pub fn project(&self, q: Point) -> (Point, usize) {
        let (proj, (seg, _)) = self.0.project_local_point_and_get_location(&pp(q), false);
        (Point::new(proj.point.x, proj.point.y), seg as usize)
    }

    /// Where a ball of radius `radius` dropped straight down (−r) from height `top` at axial
    /// position `z` first touches the line: the height of its centre, or `None` when it misses.
    pub fn ball_rest(&self, z: f64, top: f64, radius: f64) -> Option<f64> {
        let hit = cast_shapes(
            &Isometry2::new(Vector2::new(z, top), 0.0),
            &Vector2::new(0.0, -1.0),
            &Ball::new(radius),
            &Isometry2::identity(),
            &Vector2::zeros(),
            &self.0,
            ShapeCastOptions::with_max_time_of_impact(1e6),
        );
        match hit {
            Ok(Some(h)) => Some(top - h.time_of_impact),
            _ => None,
        }
    }
}

/// Distance from `q` to `line` (non-decreasing z), whose height at `q.z` is `h`: the point
/// straight above or below is on the line, so the nearest lies within |q.r − h| along z, and
/// only the segments there are asked (parry's point–segment query), not the whole line.
pub fn distance_to_graph(line: &[Point], q: Point, h: f64) -> f64 {
    // Segment i's distance, asked of parry only when its bounding box lies nearer than `best`
    // (the arcs' many short segments near a tip mostly do not).
    let seg = |i: usize, best: f64| {
        let (a, b) = (line[i], line[i + 1]);
        let off_r = (a.r.min(b.r) - q.r).max(q.r - a.r.max(b.r));
        let off_z = (a.z - q.z).max(q.z - b.z);
        if off_r >= best || off_z >= best {
            return best;
        }
        best.min(Segment::new(pp(a), pp(b)).distance_to_local_point(&pp(q), false))
    };
    // The segment under q first (it is often the nearest), then outward on both sides, each side
    // stopping where the segments lie farther along z than the best distance so far.
    let mut best = (q.r - h).abs();
    let start = line.partition_point(|p| p.z < q.z);
    if start > 0 && start < line.len() {
        best = seg(start - 1, best);
    }
    let mut i = start;
    while i + 1 < line.len() && line[i].z <= q.z + best {
        best = seg(i, best);
        i += 1;
    }
    let mut j = start.saturating_sub(1);
    while j > 0 && line[j].z >= q.z - best {
        best = seg(j - 1, best);
        j -= 1;
    }
    best
}

/// A rigid placement of the axial half-plane: a rotation by `angle` (radians) about the origin,
/// then a translation to `(z, r)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement(Isometry2<f64>);

impl Placement {
    /// Rotation by `angle`, then translation by `(z, r)`.
    pub fn new(z: f64, r: f64, angle: f64) -> Placement {
        Placement(Isometry2::new(Vector2::new(z, r), angle))
    }

    /// `p` placed.
    pub fn apply(&self, p: Point) -> Point {
        let q = self.0 * Point2::new(p.z, p.r);
        Point::new(q.x, q.y)
    }
}
