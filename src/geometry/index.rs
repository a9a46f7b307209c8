//! The one door to `rstar`: a search tree over many straight segments, bulk-loaded in
//! O(n log n), for the nearest segment to many points (the mill check builds one per level for
//! the target's samples and one for the cutter path). Every other module speaks [`Point`]s.

use crate::ground::plane::Point;
use rstar::primitives::{GeomWithData, Line};
use rstar::{PointDistance, RTree};

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

    /// Distance from `q` to the nearest segment (infinite without segments).
    pub fn distance(&self, q: Point) -> f64 {
        self.0.nearest_neighbor(&xy(q)).map_or(f64::INFINITY, |s| s.distance_2(&xy(q)).sqrt())
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
        assert_eq!(s.distance(Point::new(3.0, 1.0)), 1.0);
        let none = Segments::separate(std::iter::empty());
        assert_eq!(none.project(Point::new(0.0, 0.0)), None);
        assert_eq!(none.distance(Point::new(0.0, 0.0)), f64::INFINITY);
    }
}
