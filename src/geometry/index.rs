//! The one door to `rstar`: a search tree over many straight segments, bulk-loaded in
//! O(n log n), for the nearest segment to many points (the mill check builds one per level for
//! the target's samples and one for the cutter path). Every other module speaks [`Point`]s.

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
    /// The polyline through `pts` in order: segment i joins points i and i + 1.
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

/// Distance from `q` to the segment a → b.
fn segment_distance(q: Point, a: Point, b: Point) -> f64 {
    let (dz, dr) = (b.z - a.z, b.r - a.r);
    let l2 = dz * dz + dr * dr;
    let u = if l2 > 0.0 { (((q.z - a.z) * dz + (q.r - a.r) * dr) / l2).clamp(0.0, 1.0) } else { 0.0 };
    Point::new(a.z + u * dz, a.r + u * dr).distance(q)
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
