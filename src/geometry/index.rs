//! The nearest segment to many points. [`Segments`] is the one door to `rstar`: a search tree
//! over segments in any order, bulk-loaded in O(n log n) (the mill check builds one per level
//! for the cutter path when a target sample needs it). [`Polyline`] is a polyline's own index,
//! built in O(n) from its order: the bounding discs of runs of its segments, searched from a
//! guess (the target's samples, asked about from points that follow the path). Every other
//! module speaks [`Point`]s.

use crate::ground::plane::Point;
use rstar::primitives::{GeomWithData, Line};
use rstar::RTree;

type Seg = GeomWithData<Line<[f64; 2]>, usize>;

/// Segments with their search tree, each carrying its index in the order given.
pub struct Segments(RTree<Seg>);

impl std::fmt::Debug for Segments {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_tuple("Segments").field(&self.0.size()).finish()
    }
}

fn xy(p: Point) -> [f64; 2] {
    [p.z, p.r]
}

impl Segments {
    /// The polyline through `pts` in order: segment i joins points i and i + 1 (the tests' tree
    /// for a [`Polyline`] to agree with).
    #[cfg(test)]
    pub fn through(pts: &[Point]) -> Segments {
        let segs = pts.windows(2).enumerate().map(|(i, w)| (i, w[0], w[1]));
        Segments::build(segs)
    }

    /// Separate segments, each given by its two ends, numbered in the order given.
    pub fn separate(segs: impl IntoIterator<Item = (Point, Point)>) -> Segments {
        Segments::build(segs.into_iter().enumerate().map(|(i, (a, b))| (i, a, b)))
    }

    fn build(segs: impl Iterator<Item = (usize, Point, Point)>) -> Segments {
        let v: Vec<Seg> = segs.map(|(i, a, b)| GeomWithData::new(Line::new(xy(a), xy(b)), i)).collect();
        Segments(RTree::bulk_load(v))
    }

    /// The nearest point of the segments to `q` and the index of its segment; `None` without
    /// segments.
    pub fn project(&self, q: Point) -> Option<(Point, usize)> {
        let s = self.0.nearest_neighbor(&xy(q))?;
        let p = s.geom().nearest_point(&xy(q));
        Some((Point::new(p[0], p[1]), s.data))
    }
}

/// The point of the segment a → b nearest to `q`, and its squared distance.
fn segment_foot(q: Point, a: Point, b: Point) -> (Point, f64) {
    let (dz, dr) = (b.z - a.z, b.r - a.r);
    let l2 = dz * dz + dr * dr;
    let u = if l2 > 0.0 { (((q.z - a.z) * dz + (q.r - a.r) * dr) / l2).clamp(0.0, 1.0) } else { 0.0 };
    let f = Point::new(a.z + u * dz, a.r + u * dr);
    (f, (f.z - q.z).powi(2) + (f.r - q.r).powi(2))
}

/// Distance from `q` to the segment a → b.
fn segment_distance(q: Point, a: Point, b: Point) -> f64 {
    segment_foot(q, a, b).1.sqrt()
}

/// Segments in a run of a [`Polyline`]'s index, and runs in a run of runs.
const RUN: usize = 16;

/// A disc holding points: the centre of their bounding box and the farthest point's distance
/// from it (a run of a curved polyline fits a disc far tighter than a box when it runs askew).
#[derive(Clone, Copy, Debug)]
struct Disc {
    centre: Point,
    radius: f64,
}

impl Disc {
    fn of(pts: &[Point]) -> Disc {
        let (mut lo, mut hi) = (pts[0], pts[0]);
        for p in pts {
            lo = Point::new(lo.z.min(p.z), lo.r.min(p.r));
            hi = Point::new(hi.z.max(p.z), hi.r.max(p.r));
        }
        let centre = Point::new(0.5 * (lo.z + hi.z), 0.5 * (lo.r + hi.r));
        Disc { centre, radius: pts.iter().map(|p| p.distance(centre)).fold(0.0, f64::max) }
    }

    /// The disc holding both.
    fn union(a: Disc, b: Disc) -> Disc {
        let d = a.centre.distance(b.centre);
        if d + b.radius <= a.radius {
            return a;
        }
        if d + a.radius <= b.radius {
            return b;
        }
        let radius = 0.5 * (d + a.radius + b.radius);
        let u = (radius - a.radius) / d;
        let centre = Point::new(
            a.centre.z + u * (b.centre.z - a.centre.z),
            a.centre.r + u * (b.centre.r - a.centre.r),
        );
        // A little room for rounding: the disc only prunes.
        Disc { centre, radius: radius * (1.0 + 1e-12) + 1e-12 }
    }

    /// The squared distance from `q` to the disc (0 inside): no point in it is nearer.
    fn dist2(&self, q: Point) -> f64 {
        let d = (q.distance(self.centre) - self.radius).max(0.0);
        d * d
    }
}

/// A polyline (segment i joins points i and i + 1) with the bounding discs of its runs of
/// [`RUN`] segments and of its runs of [`RUN`] runs: the nearest segment to a point, exact
/// whatever the guess, fastest when the guess is the answer's neighbour.
pub struct Polyline {
    pts: Vec<Point>,
    runs: Vec<Disc>,
    groups: Vec<Disc>,
}

impl Polyline {
    /// The polyline through `pts` in order.
    pub fn through(pts: &[Point]) -> Polyline {
        let n = pts.len().saturating_sub(1);
        let runs: Vec<Disc> =
            (0..n.div_ceil(RUN)).map(|k| Disc::of(&pts[k * RUN..=((k + 1) * RUN).min(n)])).collect();
        let groups = runs.chunks(RUN).map(|c| c.iter().copied().fold(c[0], Disc::union)).collect();
        Polyline { pts: pts.to_vec(), runs, groups }
    }

    /// The nearest point of the polyline to `q` and its segment's index, searched first around
    /// segment `guess`; `None` without segments.
    pub fn project(&self, q: Point, guess: usize) -> Option<(Point, usize)> {
        let n = self.pts.len().saturating_sub(1);
        if n == 0 {
            return None;
        }
        let seg = |i: usize| segment_foot(q, self.pts[i], self.pts[i + 1]);
        let g = guess.min(n - 1);
        let (f, d2) = seg(g);
        let mut best = (d2, f, g);
        let visit = |i: usize, best: &mut (f64, Point, usize)| {
            let (f, d2) = seg(i);
            if d2 < best.0 {
                *best = (d2, f, i);
            }
        };
        // The guess's own run first: a good guess then prunes almost every other disc.
        let k0 = g / RUN;
        for i in k0 * RUN..((k0 + 1) * RUN).min(n) {
            visit(i, &mut best);
        }
        for (j, group) in self.groups.iter().enumerate() {
            if group.dist2(q) >= best.0 {
                continue;
            }
            for k in j * RUN..((j + 1) * RUN).min(self.runs.len()) {
                if k == k0 || self.runs[k].dist2(q) >= best.0 {
                    continue;
                }
                for i in k * RUN..((k + 1) * RUN).min(n) {
                    visit(i, &mut best);
                }
            }
        }
        Some((best.1, best.2))
    }
}

/// Segments in path order (a cutter's moves), for many points that follow the path: a point is
/// first tried against the few segments around the last answer, and the search tree is built
/// only when some point needs it.
pub struct PathSegments {
    segs: Vec<(Point, Point)>,
    tree: std::cell::OnceCell<Segments>,
}

impl PathSegments {
    /// The segments, numbered in the order given.
    pub fn new(segs: Vec<(Point, Point)>) -> PathSegments {
        PathSegments { segs, tree: std::cell::OnceCell::new() }
    }

    /// A segment within `reach` of `q` among the `window` segments either side of `hint` (the
    /// nearest of them, with its distance), or `None`: then no segment there reaches `q`, and
    /// [`PathSegments::nearest`] decides.
    pub fn within_near(&self, q: Point, reach: f64, hint: usize, window: usize) -> Option<(f64, usize)> {
        let n = self.segs.len();
        if n == 0 {
            return None;
        }
        let lo = hint.min(n - 1).saturating_sub(window);
        let hi = (hint + window).min(n - 1);
        (lo..=hi)
            .map(|i| (segment_distance(q, self.segs[i].0, self.segs[i].1), i))
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .filter(|(d, _)| *d <= reach)
    }

    /// The nearest segment to `q`: its distance and index (`None` without segments).
    pub fn nearest(&self, q: Point) -> Option<(f64, usize)> {
        let tree = self.tree.get_or_init(|| Segments::separate(self.segs.iter().copied()));
        tree.project(q).map(|(p, i)| (p.distance(q), i))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Hand-made: the corner path (0,0)–(2,0)–(2,2); from (3,1) the nearest point is (2,1) on
    /// segment 1, at distance 1; from (1,−1) it is (1,0) on segment 0.
    #[test]
    fn nearest_segment_by_hand() {
        let s = Segments::through(&[Point::new(0.0, 0.0), Point::new(2.0, 0.0), Point::new(2.0, 2.0)]);
        assert_eq!(s.project(Point::new(3.0, 1.0)), Some((Point::new(2.0, 1.0), 1)));
        assert_eq!(s.project(Point::new(1.0, -1.0)), Some((Point::new(1.0, 0.0), 0)));
        let none = Segments::separate(std::iter::empty());
        assert_eq!(none.project(Point::new(0.0, 0.0)), None);
    }

    /// The polyline index answers as the tree does, whatever the guess: a zig-zag of 100
    /// segments asked from many points, each from three guesses.
    #[test]
    fn polyline_index_agrees_with_the_tree() {
        let pts: Vec<Point> = (0..=100)
            .map(|i| Point::new(i as f64 * 0.3, if i % 2 == 0 { 0.0 } else { 1.0 + 0.01 * i as f64 }))
            .collect();
        let (tree, poly) = (Segments::through(&pts), Polyline::through(&pts));
        for k in 0..400 {
            let q = Point::new(-2.0 + 0.09 * k as f64, -1.5 + 0.013 * ((k * 37) % 300) as f64);
            let (want, _) = tree.project(q).unwrap();
            for guess in [0, 50, 99, 1000] {
                let (got, _) = poly.project(q, guess).unwrap();
                assert!((got.distance(q) - want.distance(q)).abs() < 1e-12, "{q:?} from {guess}");
            }
        }
        assert_eq!(Polyline::through(&pts[..1]).project(Point::new(0.0, 0.0), 0), None);
    }

    /// The same corner path in path order: from (2.5, 1.5) segment 1 lies 0.5 away; asked
    /// with a hint of 0 and a window of 1 it is found within reach 0.6 and not within 0.4; the
    /// tree answers the same.
    #[test]
    fn path_segments_by_hand() {
        let (a, b, c) = (Point::new(0.0, 0.0), Point::new(2.0, 0.0), Point::new(2.0, 2.0));
        let p = PathSegments::new(vec![(a, b), (b, c)]);
        let q = Point::new(2.5, 1.5);
        assert_eq!(p.within_near(q, 0.6, 0, 1), Some((0.5, 1)));
        assert_eq!(p.within_near(q, 0.4, 0, 1), None);
        assert_eq!(p.within_near(q, 0.6, 0, 0), None);
        assert_eq!(p.nearest(q), Some((0.5, 1)));
        assert_eq!(PathSegments::new(Vec::new()).nearest(q), None);
    }
}
