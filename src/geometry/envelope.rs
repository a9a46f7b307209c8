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

use crate::ground::plane::Point;

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

/// The lower envelope over `[z_min, z_max]` of the surface `y = surface` and `chain` (strictly
/// increasing `z`, acting on its own domain only) translated by every `(z, y)` in `tips`: the
/// cut surface of every imprint at once.
///
/// The chain is split at its concave vertices into convex runs; a chain is the pointwise minimum
/// of its runs, each on its own domain (carried past its concave ends while it stays above the
/// chain, so that neighbouring runs overlap). The translates of one convex run on an interval
/// cross pairwise at most once in the order of their offsets (the difference of two translates
/// is monotone where both are defined), so their envelope is one stack pass over the tips
/// sorted by `z`, each crossing found by binary search on the run's vertices: O(n log m) for n
/// tips and m vertices instead of a merge per imprint. The widest run's envelope is laid
/// against the surface directly, the others' (a full profile's crest shoulders, which become
/// one flat run across the insert) are merged into it with [`Chain::merge`]. A chain of more
/// than a few runs (concave arcs, every vertex a run) is merged imprint by imprint instead.
/// The same function as merging every imprint in turn, to rounding (unit tests hold the two
/// together, vertex by vertex).
pub fn lower_envelope(chain: &[Point], tips: &[(f64, f64)], z_min: f64, z_max: f64, surface: f64) -> Chain {
    lower_envelope_runs(chain, tips, (z_min, z_max), surface, MAX_RUNS)
}

/// [`lower_envelope`] with the number of convex runs above which it merges imprint by imprint.
fn lower_envelope_runs(
    chain: &[Point],
    tips: &[(f64, f64)],
    (z_min, z_max): (f64, f64),
    surface: f64,
    max_runs: usize,
) -> Chain {
    debug_assert!(chain.windows(2).all(|w| w[1].z > w[0].z), "a chain runs with increasing z");
    if chain.len() < 2 || tips.is_empty() {
        return Chain::flat(z_min, z_max, surface);
    }
    // Sorted by z; of equal z only the lowest, which lies under the others everywhere.
    let mut sorted = tips.to_vec();
    sorted.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    sorted.dedup_by(|b, a| a.0 == b.0);
    let runs = convex_runs(chain);
    if runs.len() > max_runs {
        let mut env = Chain::flat(z_min, z_max, surface);
        let mut f: Vec<Point> = Vec::with_capacity(chain.len());
        for &(zt, yt) in &sorted {
            f.clear();
            f.extend(chain.iter().map(|p| Point::new(zt + p.z, yt + p.r)));
            env.merge(&f);
        }
        return env;
    }
    // The widest run (a V's whole underside, a full profile's flanks and root) is laid against
    // the surface directly; the others (crest shoulders) are merged into that.
    let width = |r: &[Point]| r[r.len() - 1].z - r[0].z;
    let widest = (0..runs.len()).max_by(|&a, &b| width(&runs[a]).total_cmp(&width(&runs[b]))).unwrap_or(0);
    let mut env = against_surface(&runs[widest], &sorted, z_min, z_max, surface);
    let mut stretch: Vec<Point> = Vec::new();
    for (_, run) in runs.iter().enumerate().filter(|(i, _)| *i != widest) {
        for (zk, yk, a, b) in pieces(run, &sorted, z_min, z_max) {
            // A gap before this piece ends the stretch so far.
            if stretch.last().is_some_and(|p| p.z < a) {
                flush(&mut env, &mut stretch);
            }
            push_piece(&mut stretch, run, zk, yk, a, b);
        }
        flush(&mut env, &mut stretch);
    }
    env
}

/// The pieces of the envelope of one run's translates, in z order: the translate `(zk, yk)` is
/// the lowest over `[a, b]` (a > b never; pieces of no length are left out, their one value
/// seen by no other point). Pieces reaching past the window by more than the run's width are
/// cut there (still outside it, so that a merge sees them cross the window's edge).
fn pieces<'a>(
    run: &'a [Point],
    tips: &'a [(f64, f64)],
    z_min: f64,
    z_max: f64,
) -> impl Iterator<Item = (f64, f64, f64, f64)> + 'a {
    let stack = run_envelope(run, tips);
    let (u0, u1) = (run[0].z, run[run.len() - 1].z);
    (0..stack.len()).filter_map(move |i| {
        let (k, s) = stack[i];
        let (zk, yk) = tips[k];
        let e = stack.get(i + 1).map_or(zk + u1, |n| n.1);
        let a = s.max(zk + u0).max(z_min - (u1 - u0));
        let b = e.min(z_max + (u1 - u0));
        (b > a).then_some((zk, yk, a, b))
    })
}

/// Appends the translate `(zk, yk)` of `run` over `[a, b]`: its values at both ends and its
/// vertices between.
fn push_piece(out: &mut Vec<Point>, run: &[Point], zk: f64, yk: f64, a: f64, b: f64) {
    out.push(Point::new(a, yk + at(run, a - zk)));
    let first = run.partition_point(|p| zk + p.z <= a);
    let last = run.partition_point(|p| zk + p.z < b);
    out.extend(run[first..last].iter().map(|p| Point::new(zk + p.z, yk + p.r)));
    out.push(Point::new(b, yk + at(run, b - zk)));
}

/// The minimum of the surface and the envelope of one run's translates over `[z_min, z_max]`,
/// laid out in one pass: the pieces inside the window, the surface across the gaps between
/// them (with vertical steps where a piece ends below it), then everything above the surface
/// brought down to it, with a vertex where a piece crosses it.
fn against_surface(run: &[Point], tips: &[(f64, f64)], z_min: f64, z_max: f64, surface: f64) -> Chain {
    let all = pieces(run, tips, z_min, z_max);
    let mut raw: Vec<Point> = Vec::with_capacity(all.size_hint().1.unwrap_or(0) * (run.len() + 4) + 4);
    for (zk, yk, a, b) in all {
        let (a, b) = (a.max(z_min), b.min(z_max));
        if b < a || (b == a && a != z_min) {
            continue;
        }
        match raw.last() {
            None if a > z_min => raw.extend([Point::new(z_min, surface), Point::new(a, surface)]),
            Some(&last) if last.z < a => {
                raw.extend([Point::new(last.z, surface), Point::new(a, surface)]);
            }
            _ => {}
        }
        push_piece(&mut raw, run, zk, yk, a, b);
    }
    match raw.last() {
        None => return Chain::flat(z_min, z_max, surface),
        Some(&last) if last.z < z_max => {
            raw.extend([Point::new(last.z, surface), Point::new(z_max, surface)])
        }
        _ => {}
    }
    let mut out: Vec<Point> = Vec::with_capacity(raw.len() + 8);
    for (i, &p) in raw.iter().enumerate() {
        out.push(Point::new(p.z, p.r.min(surface)));
        if let Some(&q) = raw.get(i + 1) {
            let (dp, dq) = (p.r - surface, q.r - surface);
            if q.z > p.z && ((dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0)) {
                let t = dp / (dp - dq);
                out.push(Point::new(p.z + t * (q.z - p.z), surface));
            }
        }
    }
    Chain(simplify(out))
}

/// Merges one defined stretch of a run's envelope into `env` and empties it. Where pieces meet
/// at a crossing the stretch holds the point twice; where one piece ends and the next starts
/// at another height, it holds a vertical step, which the merge splits into two stretches.
fn flush(env: &mut Chain, stretch: &mut Vec<Point>) {
    stretch.dedup_by(|b, a| a.z == b.z && (a.r - b.r).abs() <= STEP);
    let mut start = 0;
    for i in 1..=stretch.len() {
        if i == stretch.len() || stretch[i].z <= stretch[i - 1].z {
            if i - start >= 2 {
                env.merge(&stretch[start..i]);
            }
            start = i;
        }
    }
    stretch.clear();
}

/// More convex runs than this (a chain with concave arcs, where every arc vertex is a run)
/// are cheaper merged imprint by imprint.
const MAX_RUNS: usize = 4;

/// The chain as the pointwise minimum of convex runs, each on its own domain: split at its
/// concave vertices (turns within rounding of straight count as convex), each run then carried
/// on past a concave end along its end segment for as long as that line stays on or above the
/// chain. The runs so overlap by at least a segment, so no rounding of where one ends and the
/// next begins can leave a gap between them; a run that becomes another's duplicate (a full
/// profile's two crest shoulders, each carried across the whole insert) is kept once.
fn convex_runs(c: &[Point]) -> Vec<Vec<Point>> {
    let n = c.len();
    let mut cuts = vec![0];
    for i in 1..n.saturating_sub(1) {
        let (a, b, d) = (c[i - 1], c[i], c[i + 1]);
        let cross = (b.z - a.z) * (d.r - b.r) - (b.r - a.r) * (d.z - b.z);
        if cross < -1e-12 * a.distance(b) * b.distance(d) {
            cuts.push(i);
        }
    }
    cuts.push(n - 1);
    // How far the line through `p` with slope `m` stays on or above the chain, walking the
    // vertices `order` away from p: the z where it passes below the chain, or the last vertex.
    let reach = |p: Point, m: f64, order: &mut dyn Iterator<Item = usize>| -> Point {
        let line = |z: f64| p.r + m * (z - p.z);
        let mut prev = p;
        for k in order {
            let q = c[k];
            let gap = q.r - line(q.z);
            if gap > 1e-12 {
                // Crosses between prev (on or under the line) and q.
                let g0 = prev.r - line(prev.z);
                let t = -g0 / (gap - g0);
                let z = prev.z + t * (q.z - prev.z);
                return Point::new(z, line(z));
            }
            prev = q;
        }
        Point::new(prev.z, line(prev.z))
    };
    let mut runs: Vec<Vec<Point>> = Vec::with_capacity(cuts.len() - 1);
    for w in cuts.windows(2) {
        let (i0, i1) = (w[0], w[1]);
        let mut run = Vec::with_capacity(i1 - i0 + 3);
        if i0 > 0 {
            let (a, b) = (c[i0], c[i0 + 1]);
            let e = reach(a, (b.r - a.r) / (b.z - a.z), &mut (0..i0).rev());
            if e.z < a.z {
                run.push(e);
            }
        }
        run.extend_from_slice(&c[i0..=i1]);
        if i1 < n - 1 {
            let (a, b) = (c[i1 - 1], c[i1]);
            let e = reach(b, (b.r - a.r) / (b.z - a.z), &mut (i1 + 1..n));
            if e.z > b.z {
                run.push(e);
            }
        }
        let run = simplify(run);
        if !runs.contains(&run) {
            runs.push(run);
        }
    }
    runs
}

/// The value of a run (strictly increasing z) at `u` inside its domain.
fn at(run: &[Point], u: f64) -> f64 {
    let i = run.partition_point(|p| p.z < u).clamp(1, run.len() - 1);
    let (a, b) = (run[i - 1], run[i]);
    a.r + (b.r - a.r) * (u - a.z) / (b.z - a.z)
}

/// The envelope of the translates of one convex run by `tips` (sorted by z, distinct z): the
/// tips on it in z order, each with the z from which it is the lowest (the one before it is
/// the lowest up to there).
fn run_envelope(run: &[Point], tips: &[(f64, f64)]) -> Vec<(usize, f64)> {
    let mut stack: Vec<(usize, f64)> = Vec::with_capacity(tips.len());
    for j in 0..tips.len() {
        let mut x = f64::NEG_INFINITY;
        while let Some(&(k, s)) = stack.last() {
            x = crossing(run, tips[k], tips[j]);
            if x <= s {
                stack.pop();
                x = f64::NEG_INFINITY;
            } else {
                break;
            }
        }
        stack.push((j, x));
    }
    stack
}

/// Where translate `j` of a convex run starts to lie below translate `k` (`k.0 < j.0`): the
/// translates are defined on intervals of equal length, `j`'s starting later, and their
/// difference is non-decreasing where both are defined, so `j` is the lower one from that z on
/// (undefined counts as infinitely high). Exact: binary search over both translates' vertices
/// for the stretch where the difference is linear, then its root.
fn crossing(run: &[Point], k: (f64, f64), j: (f64, f64)) -> f64 {
    let (u0, u1) = (run[0].z, run[run.len() - 1].z);
    let (lo, hi) = (j.0 + u0, k.0 + u1);
    if lo > hi {
        // Disjoint: k ends before j starts.
        return hi;
    }
    let d = |z: f64| (k.1 + at(run, z - k.0)) - (j.1 + at(run, z - j.0));
    let (mut a, mut b) = (lo, hi);
    let (mut da, mut db) = (d(a), d(b));
    if da > 0.0 {
        return lo;
    }
    if db <= 0.0 {
        return hi;
    }
    // Narrow [a, b] (d(a) ≤ 0 < d(b)) to the vertices of each translate in turn.
    for off in [k.0, j.0] {
        let first = run.partition_point(|p| off + p.z <= a);
        let last = run.partition_point(|p| off + p.z < b);
        let (mut l, mut r) = (first, last);
        while l < r {
            let mid = (l + r) / 2;
            if d(off + run[mid].z) > 0.0 {
                r = mid;
            } else {
                l = mid + 1;
            }
        }
        if l < last {
            b = off + run[l].z;
            db = d(b);
        }
        if l > first {
            a = off + run[l - 1].z;
            da = d(a);
        }
    }
    debug_assert!(da <= 0.0 && db > 0.0);
    a + (b - a) * (-da / (db - da))
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

/// The indices of an outline's leftmost and rightmost vertices (the lowest of ties), where its
/// underside (the bottom chain) starts and ends; counter-clockwise, the rest of the outline runs
/// from the rightmost back to the leftmost.
pub fn chain_ends(outline: &[Point]) -> (usize, usize) {
    let n = outline.len();
    let pick = |better: &dyn Fn(Point, Point) -> bool| {
        (0..n).fold(0, |b, i| if better(outline[i], outline[b]) { i } else { b })
    };
    let left = pick(&|p, q| p.z < q.z || (p.z == q.z && p.r < q.r));
    let right = pick(&|p, q| p.z > q.z || (p.z == q.z && p.r < q.r));
    (left, right)
}

/// The bottom chain of a counter-clockwise outline (insert frame: `r` up into the tool): from its
/// leftmost to its rightmost vertex along the underside, with strictly increasing `z`; `None`
/// when the underside doubles back (an undercut), which the envelope cannot represent.
pub fn bottom_chain(outline: &[Point]) -> Option<Vec<Point>> {
    let n = outline.len();
    if n < 3 {
        return None;
    }
    let (left, right) = chain_ends(outline);
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

    /// A small deterministic generator for the comparison below (no test depends on its
    /// sequence, only on the two envelopes agreeing).
    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// Every vertex of either chain lies on the other (vertical steps included), to 1e-12 mm:
    /// no spike of rounding width where runs or imprints meet.
    fn assert_same(one: &Chain, each: &Chain, label: &str) {
        let off = |p: Point, c: &Chain| {
            c.0.windows(2)
                .map(|w| {
                    let (a, b) = (w[0], w[1]);
                    let (dz, dr) = (b.z - a.z, b.r - a.r);
                    let l2 = dz * dz + dr * dr;
                    let t = if l2 > 0.0 {
                        (((p.z - a.z) * dz + (p.r - a.r) * dr) / l2).clamp(0.0, 1.0)
                    } else {
                        0.0
                    };
                    Point::new(a.z + t * dz, a.r + t * dr).distance(p)
                })
                .fold(f64::INFINITY, f64::min)
        };
        for (x, y) in [(one, each), (each, one)] {
            for &p in &x.0 {
                assert!(off(p, y) < 1e-12, "{label}: vertex {p:?} is {} off", off(p, y));
            }
        }
    }

    fn merge_each(chain: &[Point], tips: &[(f64, f64)], z0: f64, z1: f64, surface: f64) -> Chain {
        let mut each = Chain::flat(z0, z1, surface);
        let mut sorted = tips.to_vec();
        sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (zt, yt) in sorted {
            let f: Vec<Point> = chain.iter().map(|p| Point::new(zt + p.z, yt + p.r)).collect();
            each.merge(&f);
        }
        each
    }

    /// Regression (the crest of a Whitworth nut read as the bore): the runs of a nut insert
    /// whose shoulders meet the flanks in concave arcs, every arc vertex a run, through the runs
    /// however many, on the passes that showed it, agree with merging each imprint.
    #[test]
    fn runs_meeting_in_concave_arcs_leave_no_gap() {
        use crate::ground::plane::rad;
        use crate::standards::{parse_designation, ParseOptions, ThreadKind};
        use crate::toolpath::passes::{PlanSpec, Schedule};
        // BSW 7/16 (14 tpi): a full-profile nut insert, twelve alternating constant-depth passes
        // from the basic minor diameter to the major.
        let t = parse_designation("BSW 7/16 medium", ParseOptions::default()).unwrap().thread;
        let kind = ThreadKind::Internal;
        let insert =
            crate::geometry::insert::Insert::full_profile(&t, kind, crate::ground::plane::DEFAULT_TOLERANCE);
        let bore = t.nominal_diameter - 1.280654 * t.pitch;
        let passes = PlanSpec {
            infeed: crate::toolpath::passes::Infeed::Alternating { angle: 27.5 },
            schedule: Schedule::ConstantDepth,
            ..PlanSpec::new(kind, t.pitch, bore, t.nominal_diameter, 12)
        }
        .generate()
        .unwrap();
        let chain: Vec<Point> =
            bottom_chain(&insert.outline).unwrap().iter().rev().map(|p| Point::new(-p.z, p.r)).collect();
        assert!(convex_runs(&chain).len() > MAX_RUNS);
        let setup = crate::geometry::sweep::SweepSetup {
            kind,
            insert: &insert,
            blank_diameter: bore,
            pitch: t.pitch,
        };
        let w = crate::geometry::sweep::Window::around(-5.0 * t.pitch, t.pitch, 4.0);
        let tips: Vec<(f64, f64)> = crate::geometry::sweep::imprints(&setup, &passes, w)
            .unwrap()
            .iter()
            .map(|im| (im.z, -rad(im.x)))
            .collect();
        let surface = -rad(bore);
        let one = lower_envelope_runs(&chain, &tips, (w.z_min, w.z_max), surface, usize::MAX);
        assert_same(&one, &merge_each(&chain, &tips, w.z_min, w.z_max, surface), "BSW 7/16 nut");
    }

    /// The one-pass envelope of translates is the same function as merging every imprint in
    /// turn, for a rounded V (one convex run), a full-profile chain (flat shoulders: three runs,
    /// vertical steps where shoulders end) and arbitrary non-convex chains, with tips above and
    /// below the surface, overlapping, disjoint and at equal z.
    #[test]
    fn envelope_of_translates_matches_merging_each_imprint() {
        let mut g = Lcg(7);
        let rounded_v: Vec<Point> = {
            let mut v = vec![Point::new(-1.2, 2.0)];
            for k in 0..=12 {
                let a = -60f64.to_radians() + k as f64 * 10f64.to_radians();
                v.push(Point::new(0.04 * a.sin(), 0.04 * (1.0 - a.cos())));
            }
            v.push(Point::new(1.2, 2.0));
            v
        };
        let full = vec![
            Point::new(-0.80, 0.92),
            Point::new(-0.66, 0.92),
            Point::new(-0.1, 0.05),
            Point::new(0.0, 0.0),
            Point::new(0.1, 0.05),
            Point::new(0.66, 0.92),
            Point::new(0.80, 0.92),
        ];
        // A Whitworth nut insert: flat shoulders, concave arcs down to the flanks (every arc
        // vertex a run of its own), a convex root arc.
        let rounded_full: Vec<Point> = {
            let mut v = vec![Point::new(-0.96, 1.16)];
            for k in 0..=10 {
                let a = k as f64 * 5.5f64.to_radians();
                v.push(Point::new(-0.91 + 0.15 * a.sin(), 1.16 - 0.15 * (1.0 - a.cos())));
            }
            for k in 0..=10 {
                let a = -27.5f64.to_radians() + k as f64 * 5.5f64.to_radians();
                v.push(Point::new(0.2 * a.sin(), 0.2 * (1.0 - a.cos())));
            }
            for k in (0..=10).rev() {
                let a = k as f64 * 5.5f64.to_radians();
                v.push(Point::new(0.91 - 0.15 * a.sin(), 1.16 - 0.15 * (1.0 - a.cos())));
            }
            v.push(Point::new(0.96, 1.16));
            v
        };
        assert!(rounded_full.windows(2).all(|w| w[1].z > w[0].z));
        for case in 0..160 {
            let chain: Vec<Point> = match case % 4 {
                0 => rounded_v.clone(),
                1 => full.clone(),
                2 => rounded_full.clone(),
                _ => {
                    let mut z = -1.0;
                    (0..8)
                        .map(|_| {
                            z += 0.05 + 0.3 * g.next();
                            Point::new(z, g.next())
                        })
                        .collect()
                }
            };
            let n = 1 + (g.next() * 40.0) as usize;
            let mut tips: Vec<(f64, f64)> =
                (0..n).map(|_| (-3.0 + 6.0 * g.next(), 0.5 - 1.5 * g.next())).collect();
            // Equal z, and a pitch-spaced row as passes leave.
            tips.push(tips[0]);
            tips.push((tips[0].0, tips[0].1 - 0.01));
            tips.extend((0..5).map(|i| (-2.0 + 1.5 * i as f64, -0.3)));
            // Passes as a lathe leaves them: a row of tips one pitch apart per pass, each pass
            // deeper and shifted along the flank or alternately, so that breakpoints of different
            // imprints fall within rounding of each other.
            let pitch = 1.8142857142857143;
            for pass in 0..8 {
                let shift = if case % 2 == 0 { 0.02 * pass as f64 } else { 0.03 * (pass % 2) as f64 - 0.015 };
                let y = -0.05 - 0.04 * pass as f64;
                tips.extend((-2..=2).map(|k| (-0.3 + shift + k as f64 * pitch, y)));
            }
            let (z0, z1, surface) = (-2.5, 2.5, 0.6);
            // Both ways: the default, and every chain through its convex runs however many.
            let one = if case % 8 < 4 {
                lower_envelope(&chain, &tips, z0, z1, surface)
            } else {
                lower_envelope_runs(&chain, &tips, (z0, z1), surface, usize::MAX)
            };
            let each = merge_each(&chain, &tips, z0, z1, surface);
            for k in 0..4000 {
                let z = z0 + (z1 - z0) * (k as f64 + 0.37) / 4000.0;
                let (a, b) = (one.value(z), each.value(z));
                assert!((a - b).abs() < 1e-12, "case {case}: at z {z}: {a} against {b}");
            }
            assert!((one.integral(z0, z1) - each.integral(z0, z1)).abs() < 1e-12, "case {case}");
            assert_same(&one, &each, &format!("case {case}"));
        }
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
        assert!(crate::geometry::boolean::signed_area(&hook) > 0.0);
        assert_eq!(bottom_chain(&hook), None);
    }
}
