//! The as-cut surface as the lower envelope of the imprints, without polygon booleans.
//!
//! In the normalised frame (material below; `y = r` for external threads, `y = −r` for internal
//! ones) an imprint removes everything above its **bottom chain**, the part of the insert
//! outline from its leftmost to its rightmost point along the underside. When that chain is a
//! function of `z` (true for V, rounded-V and full-profile inserts), the cut surface is the
//! pointwise minimum of the blank's top and every bottom chain: a lower envelope of
//! piecewise-linear functions. Merging one chain into the envelope costs time proportional to the
//! part of the envelope under that chain, so the cost per pass stays flat however many passes
//! there are, and the arithmetic is plain `f64` with no snapping grid.
//!
//! A chain is a polyline with non-decreasing `z`; equal `z` on consecutive vertices is a
//! vertical step (where an imprint's domain begins or ends).

use crate::geometry::Point;

/// A lower envelope (or any chain) in the normalised frame: vertices with non-decreasing `z`.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Chain(pub Vec<Point>);

impl Chain {
    /// The constant function `y` over `[z0, z1]`.
    pub fn flat(z0: f64, z1: f64, y: f64) -> Chain {
        Chain(vec![Point::new(z0, y), Point::new(z1, y)])
    }

    /// The pointwise minimum of `self` and `f` (see [`Chain::merge`]).
    #[cfg(test)]
    pub fn min_with(&self, f: &[Point]) -> Chain {
        let mut c = self.clone();
        c.merge(f);
        c
    }

    /// The value at `z` inside the domain (linear between vertices; at a vertical step, the value
    /// after it).
    pub fn value(&self, z: f64) -> f64 {
        let v = &self.0;
        let i = v.partition_point(|p| p.z <= z).clamp(1, v.len() - 1);
        let (a, b) = (v[i - 1], v[i]);
        if b.z > a.z {
            a.r + (b.r - a.r) * (z - a.z) / (b.z - a.z)
        } else {
            b.r
        }
    }

    /// ∫ y dz over `[z0, z1]` ∩ the domain, exactly (trapezoids; steps add nothing).
    pub fn integral(&self, z0: f64, z1: f64) -> f64 {
        let mut sum = 0.0;
        for w in self.0.windows(2) {
            let (a, b) = (w[0].z.max(z0), w[1].z.min(z1));
            if b > a && w[1].z > w[0].z {
                let at = |z: f64| w[0].r + (w[1].r - w[0].r) * (z - w[0].z) / (w[1].z - w[0].z);
                sum += 0.5 * (at(a) + at(b)) * (b - a);
            }
        }
        sum
    }

    /// Makes `self` the pointwise minimum of itself and `f`, where `f` is defined on
    /// `[f.first.z, f.last.z]` (and has no effect outside) with strictly increasing `z`. Only
    /// the stretch under `f` is rebuilt and spliced in: the cost is that stretch, not the chain.
    pub fn merge(&mut self, f: &[Point]) {
        let v = &self.0;
        let (lo, hi) = (f[0].z.max(v[0].z), f[f.len() - 1].z.min(v[v.len() - 1].z));
        if !(hi > lo) {
            return;
        }
        let i0 = v.partition_point(|p| p.z < lo);
        let i1 = v.partition_point(|p| p.z <= hi);
        // The new stretch, between the untouched neighbours on either side (kept so that the
        // simplification sees across the junctions).
        let mut out: Vec<Point> = Vec::with_capacity(i1 - i0 + 2 * f.len() + 4);
        if i0 > 0 {
            out.push(v[i0 - 1]);
        }
        // Events: every vertex z of both in [lo, hi], merged from the two sorted lists.
        let mut zs: Vec<f64> = Vec::with_capacity(i1 - i0 + f.len() + 2);
        zs.push(lo);
        let (mut a, mut b) = (i0, 0);
        while a < i1 || b < f.len() {
            let za = if a < i1 { v[a].z } else { f64::INFINITY };
            let zb = if b < f.len() { f[b].z } else { f64::INFINITY };
            let z = if za <= zb {
                a += 1;
                za
            } else {
                b += 1;
                zb
            };
            if z > lo && z < hi && zs.last().is_none_or(|l| *l != z) {
                zs.push(z);
            }
        }
        zs.push(hi);
        // The imprint acts on its own domain only: where that domain starts (not where the
        // envelope's window cuts it) the left limit is the envelope's, where it ends the right
        // limit is.
        let (own_start, own_end) = (f[0].z >= v[0].z, f[f.len() - 1].z <= v[v.len() - 1].z);
        // Left and right limits of both chains at every event, walking both once.
        let (mut we, mut wf) = (Walker::new(v, i0), Walker::new(f, 0));
        let lim: Vec<[f64; 4]> = zs
            .iter()
            .map(|&z| {
                we.seek(z);
                wf.seek(z);
                [we.left(z), we.right(z), wf.left(z), wf.right(z)]
            })
            .collect();
        let last_k = zs.len() - 1;
        for (k, &z) in zs.iter().enumerate() {
            let [el, er, fl, fr] = lim[k];
            let left = if k == 0 && own_start { el } else { el.min(fl) };
            let right = if k == last_k && own_end { er } else { er.min(fr) };
            out.push(Point::new(z, left));
            // A real step (an imprint's end, a vertical in either chain), not rounding noise.
            if (right - left).abs() > STEP {
                out.push(Point::new(z, right));
            }
            if k < last_k {
                let zb = zs[k + 1];
                let [ebl, _, fbl, _] = lim[k + 1];
                let (da, db) = (er - fr, ebl - fbl);
                if (da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0) {
                    let t = da / (da - db);
                    out.push(Point::new(z + t * (zb - z), er + t * (ebl - er)));
                }
            }
        }
        if i1 < v.len() {
            out.push(v[i1]);
        }
        let out = simplify(out);
        // The neighbours are first and last of `out` (simplify keeps the ends): splice over them.
        self.0.splice(i0.saturating_sub(1)..(i1 + 1).min(self.0.len()), out);
    }
}

/// Walks a chain with increasing query points, keeping the indices of the first vertex at or
/// past the point (for the left limit) and strictly past it (for the right limit).
struct Walker<'a> {
    v: &'a [Point],
    lo: usize,
    hi: usize,
}

impl<'a> Walker<'a> {
    fn new(v: &'a [Point], from: usize) -> Walker<'a> {
        Walker { v, lo: from, hi: from }
    }

    fn seek(&mut self, z: f64) {
        while self.lo < self.v.len() && self.v[self.lo].z < z {
            self.lo += 1;
        }
        self.hi = self.hi.max(self.lo);
        while self.hi < self.v.len() && self.v[self.hi].z <= z {
            self.hi += 1;
        }
    }

    fn value(&self, i: usize, z: f64, from_right: bool) -> f64 {
        let v = self.v;
        if i == 0 {
            return v[0].r;
        }
        if i >= v.len() {
            return v[v.len() - 1].r;
        }
        let (a, b) = (v[i - 1], v[i]);
        if b.z == a.z {
            return if from_right { b.r } else { a.r };
        }
        a.r + (z - a.z) / (b.z - a.z) * (b.r - a.r)
    }

    fn left(&self, z: f64) -> f64 {
        self.value(self.lo, z, false)
    }

    fn right(&self, z: f64) -> f64 {
        self.value(self.hi, z, true)
    }
}

/// Steps smaller than this (mm) are rounding between a left and a right evaluation, not steps.
const STEP: f64 = 1e-12;

/// Removes repeated vertices and vertices exactly on the line through their neighbours (on a
/// stretch with increasing z). Merging emits such points where one chain's vertex falls on the
/// other's segment; on an arc they would sit on a chord and spoil a 3-point root radius.
fn simplify(v: Vec<Point>) -> Vec<Point> {
    let mut out: Vec<Point> = Vec::with_capacity(v.len());
    for p in v {
        if let Some(&last) = out.last() {
            if (last.z - p.z).abs() <= STEP && (last.r - p.r).abs() <= STEP {
                continue;
            }
            if out.len() >= 2 {
                let a = out[out.len() - 2];
                if a.z < last.z && last.z < p.z {
                    let cross = (last.z - a.z) * (p.r - a.r) - (last.r - a.r) * (p.z - a.z);
                    // Distance of `last` from the line a–p under 1e-10 mm: on it, to rounding.
                    // (sqrt of the sum: libm's hypot guards against overflow that mm never
                    // reach, and costs a tenth of a sweep here.)
                    let len = ((p.z - a.z).powi(2) + (p.r - a.r).powi(2)).sqrt();
                    if cross.abs() <= 1e-10 * len {
                        out.pop();
                    }
                }
            }
        }
        out.push(p);
    }
    out
}

/// The bottom chain of a counter-clockwise outline (insert frame: `r` up into the tool): from its
/// leftmost to its rightmost vertex along the underside, with strictly increasing `z`; `None`
/// when the underside doubles back (an undercut), which the envelope cannot represent.
pub fn bottom_chain(outline: &[Point]) -> Option<Vec<Point>> {
    let n = outline.len();
    if n < 3 {
        return None;
    }
    // Leftmost vertex (the lowest of ties) and rightmost vertex (the lowest of ties).
    let pick = |better: &dyn Fn(Point, Point) -> bool| {
        (0..n).fold(0, |b, i| if better(outline[i], outline[b]) { i } else { b })
    };
    let left = pick(&|p, q| p.z < q.z || (p.z == q.z && p.r < q.r));
    let right = pick(&|p, q| p.z > q.z || (p.z == q.z && p.r < q.r));
    // Counter-clockwise, the underside runs from the leftmost to the rightmost vertex.
    let mut chain = Vec::new();
    let mut i = left;
    loop {
        chain.push(outline[i]);
        if i == right {
            break;
        }
        i = (i + 1) % n;
        if chain.len() > n {
            return None;
        }
    }
    chain.windows(2).all(|w| w[1].z > w[0].z).then_some(chain)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn min_of_a_flat_and_a_v() {
        let e = Chain::flat(-2.0, 2.0, 1.0);
        let v = [Point::new(-1.0, 2.0), Point::new(0.0, 0.0), Point::new(1.0, 2.0)];
        let m = e.min_with(&v);
        // Flat at 1 until the V crosses it at z = ±0.5, down to 0 at z = 0.
        let want = [(-2.0, 1.0), (-0.5, 1.0), (0.0, 0.0), (0.5, 1.0), (2.0, 1.0)];
        assert_eq!(m.0.len(), want.len(), "{m:?}");
        for (p, (z, r)) in m.0.iter().zip(want) {
            assert!((p.z - z).abs() < 1e-15 && (p.r - r).abs() < 1e-15, "{m:?}");
        }
    }

    #[test]
    fn a_step_where_an_imprint_domain_ends() {
        let e = Chain::flat(0.0, 4.0, 1.0);
        let m = e.min_with(&[Point::new(1.0, 0.5), Point::new(2.0, 0.5)]);
        assert_eq!(
            m.0,
            vec![
                Point::new(0.0, 1.0),
                Point::new(1.0, 1.0),
                Point::new(1.0, 0.5),
                Point::new(2.0, 0.5),
                Point::new(2.0, 1.0),
                Point::new(4.0, 1.0)
            ]
        );
        // Merging the same imprint again changes nothing.
        assert_eq!(m.min_with(&[Point::new(1.0, 0.5), Point::new(2.0, 0.5)]), m);
    }

    #[test]
    fn bottom_chain_of_a_v_and_of_an_undercut() {
        let v = [Point::new(-1.0, 2.0), Point::new(0.0, 0.0), Point::new(1.0, 2.0)];
        assert_eq!(bottom_chain(&v).unwrap(), v.to_vec());
        // An undercut: the underside runs right to z = 2, back to z = 1, then on to z = 3.
        let hook = [
            Point::new(0.0, 0.0),
            Point::new(2.0, 0.0),
            Point::new(1.0, 0.5),
            Point::new(3.0, 0.2),
            Point::new(3.0, 2.0),
            Point::new(0.0, 2.0),
        ];
        assert!(crate::boolean::signed_area(&hook) > 0.0);
        assert_eq!(bottom_chain(&hook), None);
    }
}
