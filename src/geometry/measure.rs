//! Measuring the as-cut profile the way a metrology lab would.
//!
//! Work happens in a **normalised frame** `(z, y)` with the material below the profile:
//! `y = r` for external threads and `y = −r` for internal ones, so that "crest" is always up and
//! "root" down. Results are converted back to diameters.

use crate::geometry::parry::{distance_to_graph, Line};
use crate::ground::plane::{cross_at_level, dia, height_at, Point};
use crate::standards::{BasicThread, ProfileKind, ThreadKind};
use crate::Error;
use serde::Serialize;

/// The three-wire measurement over best-size wires.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ThreeWire {
    /// Wire diameter w, mm (best size P / (2·cos(α/2))).
    pub wire: f64,
    /// Measurement over the wires M, mm (no lead-angle correction).
    pub m: f64,
}

/// What was measured on one groove and its two neighbouring teeth.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Measurement {
    /// Major diameter, mm: the crest of the bolt (external) or the root of the nut (internal).
    pub major_diameter: f64,
    /// Simple pitch diameter, mm: where the groove is P/2 wide.
    pub pitch_diameter: f64,
    /// Minor diameter, mm: the root d3 of the bolt (external) or the crest D1 of the nut.
    pub minor_diameter: f64,
    /// Thread depth (major − minor)/2, mm: h3 for a bolt.
    pub thread_depth: f64,
    /// Depth of engagement with the basic mating thread, mm: (d − D1_measured)/2 for a nut,
    /// (d_measured − D1)/2 for a bolt (H1 is 5H/8 at basic size).
    pub engagement_depth: f64,
    /// Flank half-angles from the radial, degrees: `[low-Z flank, high-Z flank]` of the groove,
    /// each fitted by least squares on the straight middle half of the flank.
    pub flank_angles: [f64; 2],
    /// Smallest radius of curvature of the root (concave side), mm; `None` where the root has no
    /// rounded part (a flat root with sharp corners, as a full-profile trapezoidal or Acme
    /// insert cuts it; a sharp V).
    pub root_radius: Option<f64>,
    /// Width of the narrower of the two crests, mm: its width 1 µm below the top less what two
    /// sharp flanks would span there. Near zero: the grooves meet, no crest is left.
    pub crest_width: f64,
    /// Axial position of the groove centre on the pitch line, mm.
    pub groove_center: f64,
    /// Separate pockets in the root (local minima parted by a ridge over 1 µm high); more than
    /// one means the passes did not land in one groove.
    pub root_pockets: usize,
    /// The highest a fin or notch stands inside the groove, mm: how far the profile rises again
    /// on its way down from either crest to the root (0 where it falls all the way). Steep flank
    /// infeed leaves one between passes.
    pub fin_height: f64,
    /// True when the pitch line lay outside the cut flanks and the fitted flank lines were
    /// extended to find it.
    pub pitch_line_extrapolated: bool,
    /// Three-wire measurement (external threads only).
    pub three_wire: Option<ThreeWire>,
    /// Signed smallest distance from the as-cut profile to the maximum-material profile, mm:
    /// positive where the GO gauge enters with clearance, negative where it would not.
    pub max_material_clearance: Option<f64>,
}

/// The profile of one groove in the normalised frame, with its crests.
struct Groove {
    pts: Vec<Point>,
    root: usize,
    left: usize,
    right: usize,
}

fn normalise(profile: &[Point], kind: ThreadKind) -> Vec<Point> {
    let s = if kind == ThreadKind::External { 1.0 } else { -1.0 };
    profile.iter().map(|p| Point::new(p.z, s * p.r)).collect()
}

impl Groove {
    fn find(pts: Vec<Point>, z_ref: f64, pitch: f64) -> Result<Groove, Error> {
        let within = |lo: f64, hi: f64| -> Vec<usize> {
            (0..pts.len()).filter(|&i| pts[i].z >= lo && pts[i].z <= hi).collect()
        };
        let root = within(z_ref - 0.5 * pitch, z_ref + 0.5 * pitch)
            .into_iter()
            .min_by(|&a, &b| pts[a].r.total_cmp(&pts[b].r))
            .ok_or_else(|| Error::Geometry("no groove in the measured window".into()))?;
        let zr = pts[root].z;
        // A crest: the highest point within a pitch; of a flat top, the end nearest the groove.
        let crest = |range: Vec<usize>, nearest_last: bool| -> Option<usize> {
            let top = range.iter().map(|&i| pts[i].r).fold(f64::NEG_INFINITY, f64::max);
            let mut on_top = range.into_iter().filter(|&i| pts[i].r >= top - 1e-9);
            if nearest_last {
                on_top.next_back()
            } else {
                on_top.next()
            }
        };
        let left = crest(within(zr - pitch, zr), true);
        let right = crest(within(zr, zr + pitch), false);
        match (left, right) {
            (Some(l), Some(r)) if l < root && root < r => Ok(Groove { pts, root, left: l, right: r }),
            _ => Err(Error::Geometry("the measured window does not hold a groove between two teeth".into())),
        }
    }

    fn y_root(&self) -> f64 {
        self.pts[self.root].r
    }

    fn y_top(&self) -> f64 {
        self.pts[self.left].r.min(self.pts[self.right].r)
    }

    /// Where the low-Z flank crosses level `y`, searching out from the root.
    fn left_z(&self, y: f64) -> Option<f64> {
        (self.left..self.root).rev().find_map(|i| cross_at_level(self.pts[i], self.pts[i + 1], y))
    }

    fn right_z(&self, y: f64) -> Option<f64> {
        (self.root..self.right).find_map(|i| cross_at_level(self.pts[i], self.pts[i + 1], y))
    }

    fn width(&self, y: f64) -> Option<f64> {
        Some(self.right_z(y)? - self.left_z(y)?)
    }

    /// Least-squares line z = a + b·y through the flank crossings in the middle half of the
    /// depth; returns (a, b) for the low-Z and high-Z flank.
    fn fit_flanks(&self) -> Option<((f64, f64), (f64, f64))> {
        let (y0, y1) = (self.y_root(), self.y_top());
        let n = 21;
        let fit = |f: &dyn Fn(f64) -> Option<f64>| -> Option<(f64, f64)> {
            let pts: Vec<(f64, f64)> = (0..n)
                .filter_map(|k| {
                    let y = y0 + (y1 - y0) * (0.25 + 0.5 * k as f64 / (n - 1) as f64);
                    f(y).map(|z| (y, z))
                })
                .collect();
            if pts.len() < 2 {
                return None;
            }
            let m = pts.len() as f64;
            let (sy, sz) = pts.iter().fold((0.0, 0.0), |(a, b), (y, z)| (a + y, b + z));
            let (my, mz) = (sy / m, sz / m);
            let (sxy, sxx) = pts
                .iter()
                .fold((0.0, 0.0), |(a, b), (y, z)| (a + (y - my) * (z - mz), b + (y - my) * (y - my)));
            let b = sxy / sxx;
            Some((mz - b * my, b))
        };
        Some((fit(&|y| self.left_z(y))?, fit(&|y| self.right_z(y))?))
    }
}

/// Counts the pockets of a groove: local minima separated by a ridge rising more than `ridge`
/// above the higher of the two.
fn count_pockets(pts: &[Point], ridge: f64) -> usize {
    let mut pockets = 0;
    let mut low = f64::INFINITY;
    let mut high_since_low = f64::NEG_INFINITY;
    for p in pts {
        if p.r < low {
            low = p.r;
            high_since_low = p.r;
        }
        high_since_low = high_since_low.max(p.r);
        if pockets == 0 && low.is_finite() {
            pockets = 1;
        }
        // Climbing out of the current pocket by more than the ridge height and back down counts
        // a new pocket once it goes below the ridge again.
        if high_since_low - low > ridge && p.r < high_since_low - ridge && p.r < low + ridge {
            pockets += 1;
            low = p.r;
            high_since_low = p.r;
        }
    }
    pockets
}

/// How far the groove's profile rises again on its way down from either crest to the root: the
/// largest height of a point over the lowest before it, walking from the left crest to the root
/// and from the right crest back to it, among the points below `cap`: P/16 under the lower
/// crest, so the notch a taper thread's turns leave in a crest (they top it at heights about
/// P/32 apart) does not count.
fn fin_height(pts: &[Point], root: usize, cap: f64) -> f64 {
    let rise = |walk: &mut dyn Iterator<Item = &Point>| {
        let mut low = f64::INFINITY;
        let mut worst = 0.0f64;
        for p in walk.filter(|p| p.r < cap) {
            low = low.min(p.r);
            worst = worst.max(p.r - low);
        }
        worst
    };
    rise(&mut pts[..=root].iter()).max(rise(&mut pts[root..].iter().rev()))
}

/// The largest turn at a vertex that still counts as a step along a rounded contour: a circle
/// tessellated to threadcheck's chord tolerances turns by under 20° a vertex down to radii of a
/// few µm, while a sharp corner of a flat root (75° on a trapezoidal thread) or a V (120°) turns
/// by far more.
const ARC_TURN_DEG: f64 = 30.0;

/// Smallest circumradius over concave vertex triples (left turns in the normalised frame) that
/// lie on a rounded stretch (each turning by under [`ARC_TURN_DEG`]), after merging vertices
/// closer than 0.1 µm so that boolean slivers cannot fake a tiny radius. `None` where the root
/// has no rounded part: a flat root with sharp corners, a sharp V (whose radius is 0 for the
/// root-radius check).
fn min_concave_radius(pts: &[Point]) -> Option<f64> {
    let mut v: Vec<Point> = Vec::with_capacity(pts.len());
    for p in pts {
        if v.last().is_none_or(|q: &Point| q.distance(*p) > 1e-4) {
            v.push(*p);
        }
    }
    let mut best: Option<f64> = None;
    for w in v.windows(3) {
        let (a, b, c) = (w[0], w[1], w[2]);
        let cross = (b.z - a.z) * (c.r - a.r) - (b.r - a.r) * (c.z - a.z);
        if cross <= 0.0 {
            continue;
        }
        let dot = (b.z - a.z) * (c.z - b.z) + (b.r - a.r) * (c.r - b.r);
        if cross.atan2(dot).to_degrees() >= ARC_TURN_DEG {
            continue;
        }
        let r = a.distance(b) * b.distance(c) * c.distance(a) / (2.0 * cross);
        best = Some(best.map_or(r, |x: f64| x.min(r)));
    }
    best
}

/// Golden-section search for the minimum of `f` on `[a, b]`: (argument, value).
pub(crate) fn golden_min(f: &dyn Fn(f64) -> f64, mut a: f64, mut b: f64, iters: usize) -> (f64, f64) {
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let mut c = b - g * (b - a);
    let mut d = a + g * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..iters {
        if fc < fd {
            b = d;
            d = c;
            fd = fc;
            c = b - g * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + g * (b - a);
            fd = f(d);
        }
    }
    if fc < fd {
        (c, fc)
    } else {
        (d, fd)
    }
}

/// The lowest a ball of radius `rw` can sit in the groove: its centre height and axial position.
/// Where a ball of radius `rw` rests on two straight flanks `z = a + b·y` (low-Z flank, b < 0
/// going down) and `z = c + d·y`: the point at distance `rw` from both lines, inside the groove.
fn rest_on_lines(left: (f64, f64), right: (f64, f64), rw: f64) -> Option<(f64, f64)> {
    // Line z − b·y − a = 0 has unit normal (1, −b)/√(1 + b²); inside the groove is +z of the
    // low-Z flank and −z of the high-Z flank.
    let ((a, b), (c, d)) = (left, right);
    let (nl, nr) = ((1.0 + b * b).sqrt(), (1.0 + d * d).sqrt());
    // z − b·y − a = rw·nl and −(z − d·y − c) = rw·nr.
    let det = (-b) - (-d);
    if det.abs() < 1e-12 {
        return None;
    }
    let y = ((c - rw * nr) - (a + rw * nl)) / (b - d);
    let z = a + rw * nl + b * y;
    (z.is_finite() && y.is_finite()).then_some((z, y))
}

/// The lowest a ball of radius `rw` can sit in the groove: its centre's axial position and
/// height. On straight flanks the centre is where the flank lines offset by `rw` meet; that is
/// accepted only when parry finds no part of the profile nearer than `rw` (the wire touches the
/// flanks, not the root or a crest). Otherwise the ball is dropped onto the profile with parry
/// shape casts and the lowest resting place found by golden section.
fn wire_rest(g: &Groove, rw: f64, flanks: ((f64, f64), (f64, f64))) -> Option<(f64, f64)> {
    let chain = &g.pts[g.left..=g.right];
    if let Some((z, y)) = rest_on_lines(flanks.0, flanks.1, rw) {
        // The groove's nearest point to the centre (its height there bounds the search).
        let d = height_at(chain, z).map(|h| distance_to_graph(chain, Point::new(z, y), h));
        if d.is_some_and(|d| (d - rw).abs() < 1e-9) {
            return Some((z, y));
        }
    }
    let line = Line::through(chain.iter().copied());
    let top = chain.iter().map(|p| p.r).fold(f64::NEG_INFINITY, f64::max) + 2.0 * rw + 1.0;
    let drop = |z: f64| -> f64 { line.ball_rest(z, top, rw).unwrap_or(f64::INFINITY) };
    let (z0, z1) = (g.pts[g.left].z, g.pts[g.right].z);
    let (z, y) = golden_min(&drop, z0, z1, 56);
    y.is_finite().then_some((z, y))
}

/// The as-cut groove and the maximum-material profile, each with its search tree built once,
/// for the signed clearance at any axial shift of the gauge.
struct Clearance {
    cut: Vec<Point>,
    mmc: Vec<Point>,
}

impl Clearance {
    fn new(cut: Vec<Point>, mmc: Vec<Point>) -> Clearance {
        Clearance { cut, mmc }
    }

    /// Signed clearance of one vertex with the gauge moved by `dz`: its distance to the other
    /// profile, negative where the cut stands outside the maximum-material profile. Vertices
    /// `0..cut.len()` are the cut's, the rest the gauge's. 1-Lipschitz in `dz`.
    fn vertex(&self, k: usize, dz: f64) -> Option<f64> {
        if k < self.cut.len() {
            let p = self.cut[k];
            // The gauge moved by dz is the gauge at rest seen from p moved by −dz.
            let q = Point::new(p.z - dz, p.r);
            let h = height_at(&self.mmc, q.z)?;
            let d = distance_to_graph(&self.mmc, q, h);
            Some(if p.r > h + 1e-9 { -d } else { d })
        } else {
            let m = self.mmc[k - self.cut.len()];
            let q = Point::new(m.z + dz, m.r);
            let h = height_at(&self.cut, q.z)?;
            let d = distance_to_graph(&self.cut, q, h);
            Some(if h > q.r + 1e-9 { -d } else { d })
        }
    }

    /// The clearance over the vertices `ks`: the smallest signed value (the deepest penetration,
    /// negative, wherever the cut stands outside the gauge).
    fn over(&self, ks: &[usize], dz: f64) -> f64 {
        ks.iter().filter_map(|&k| self.vertex(k, dz)).fold(f64::INFINITY, f64::min)
    }

    /// The best clearance over axial shifts in `[-reach, reach]`, as a gauge screws on to where
    /// it fits best. The search (see [`Clearance::search`]) takes the clearance as unimodal in
    /// the shift; so it looks first within an eighth of the reach, where the gauge, centred on
    /// the groove's pitch line, nearly always fits best, and a best shift strictly inside that
    /// is the best of all. Only where it lands at that bracket's edge is the whole reach searched.
    /// The narrow bracket lets the first pruning keep only the vertices within its width of
    /// touching.
    fn best(&self, reach: f64) -> f64 {
        self.best_at(reach).1
    }

    /// [`Clearance::best`] and the shift that reaches it.
    fn best_at(&self, reach: f64) -> (f64, f64) {
        let near = 0.125 * reach;
        let (x, v) = self.search(-near, near);
        if x.abs() < near * (1.0 - 1e-3) {
            return (x, v);
        }
        self.search(-reach, reach)
    }

    /// The best clearance over axial shifts in `[a, b]` and the shift that reaches it, as a gauge
    /// screws on to where it fits best: a golden search on the shift (24 steps narrow it to
    /// 0.618²⁴·(b − a), a few nm). Now and then the vertices that cannot be the least anywhere in the bracket are
    /// dropped: with the bracket w wide around its middle m, each value moves at most w/2, so a
    /// vertex whose value at m exceeds the least there by more than w never becomes the least.
    /// The search then runs on the few vertices that touch, with the same result as on all.
    ///
    /// Once few vertices are left ([`FEW`]) and the bracket is under 50 µm, the search tries to finish
    /// exactly: where the touching vertices face straight flanks, each value is linear in the
    /// shift, so the best shift is where the chords of their values across the bracket cross
    /// (the maximum of the least of a few lines). The finish is taken when every vertex's value
    /// there lies on its chord to 1e-10 mm (the touching parts are straight); otherwise the
    /// golden steps go on. Either way the result is a value the gauge reaches at some shift.
    fn search(&self, a: f64, b: f64) -> (f64, f64) {
        let mut ks: Vec<usize> = (0..self.cut.len() + self.mmc.len()).collect();
        let g = 0.5 * (5f64.sqrt() - 1.0);
        let (mut a, mut b) = (a, b);
        let prune = |ks: &mut Vec<usize>, a: f64, b: f64| {
            let m = 0.5 * (a + b);
            let mut least = f64::INFINITY;
            let mut vals: Vec<(usize, f64)> = Vec::with_capacity(ks.len());
            for &k in ks.iter() {
                if let Some(v) = self.vertex(k, m) {
                    least = least.min(v);
                    vals.push((k, v));
                }
            }
            ks.clear();
            ks.extend(vals.into_iter().filter(|x| x.1 <= least + (b - a)).map(|x| x.0));
        };
        prune(&mut ks, a, b);
        let (mut c, mut d) = (b - g * (b - a), a + g * (b - a));
        let (mut fc, mut fd) = (self.over(&ks, c), self.over(&ks, d));
        let mut tried_exact = false;
        for step in 0..24 {
            // Maximise the clearance.
            if fc > fd {
                b = d;
                d = c;
                fd = fc;
                c = b - g * (b - a);
                fc = self.over(&ks, c);
            } else {
                a = c;
                c = d;
                fc = fd;
                d = a + g * (b - a);
                fd = self.over(&ks, d);
            }
            // Prune while it pays: every other step until few vertices are left, then seldom.
            if ks.len() > 2 && (step % 2 == 1 && (ks.len() > FEW || step % 8 == 7)) {
                prune(&mut ks, a, b);
            }
            if !tried_exact && ks.len() <= FEW && b - a < 0.05 {
                tried_exact = true;
                if let Some((x, v)) = self.exact_finish(&ks, a, b) {
                    return [(x, v), (c, fc), (d, fd)].into_iter().fold((x, v), |m, p| {
                        if p.1 > m.1 {
                            p
                        } else {
                            m
                        }
                    });
                }
            }
        }
        if fc > fd {
            (c, fc)
        } else {
            (d, fd)
        }
    }

    /// The exact finish of [`Clearance::search`] on `[a, b]`: the shift where the least of the
    /// vertices' chords is greatest, and the clearance there, when every vertex's value there
    /// lies on its chord (None otherwise, or where a vertex has no value).
    fn exact_finish(&self, ks: &[usize], a: f64, b: f64) -> Option<(f64, f64)> {
        let mut lines: Vec<(f64, f64)> = Vec::with_capacity(ks.len());
        for &k in ks {
            let (va, vb) = (self.vertex(k, a)?, self.vertex(k, b)?);
            lines.push((va, (vb - va) / (b - a)));
        }
        let least = |x: f64| lines.iter().map(|&(v, m)| v + m * (x - a)).fold(f64::INFINITY, f64::min);
        let mut x_best = a;
        let mut candidates = vec![a, b];
        for (i, &(v1, m1)) in lines.iter().enumerate() {
            for &(v2, m2) in &lines[i + 1..] {
                if m1 != m2 {
                    let x = a + (v2 - v1) / (m1 - m2);
                    if x > a && x < b {
                        candidates.push(x);
                    }
                }
            }
        }
        for x in candidates {
            if least(x) > least(x_best) {
                x_best = x;
            }
        }
        let mut f = f64::INFINITY;
        for (&k, &(v, m)) in ks.iter().zip(&lines) {
            let got = self.vertex(k, x_best)?;
            if (got - (v + m * (x_best - a))).abs() > 1e-10 {
                return None;
            }
            f = f.min(got);
        }
        Some((x_best, f))
    }
}

/// So many vertices or fewer left in a clearance search count as few: pruned seldom, and
/// tried for the exact finish (the crest corners of both flanks and the gauge's own corners
/// often stay within a narrow bracket's width of touching, eight of them on a symmetric cut).
const FEW: usize = 12;

/// Where a bolt and a nut are tightest: the signed clearance at the nut's best axial shift
/// (negative: interference), that shift, and the two points that face each other there (in the
/// bolt's frame, the nut's point moved by the shift).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Contact {
    pub(crate) clearance: f64,
    pub(crate) shift: f64,
    pub(crate) bolt: Point,
    pub(crate) nut: Point,
}

/// The fit of a bolt's tooth and a nut's profile (normal frame, radii), the nut free to move
/// axially by up to `reach`: where it fits best and where it is tightest there.
pub(crate) fn fit_contact(bolt: Vec<Point>, nut: Vec<Point>, reach: f64) -> Contact {
    let c = Clearance::new(bolt, nut);
    let (shift, clearance) = c.best_at(reach);
    let n = c.cut.len() + c.mmc.len();
    let k = (0..n)
        .filter_map(|k| c.vertex(k, shift).map(|v| (k, v)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map_or(0, |x| x.0);
    let moved: Vec<Point> = c.mmc.iter().map(|m| Point::new(m.z + shift, m.r)).collect();
    let nearest = |poly: &[Point], p: Point| -> Point {
        let mut best = (f64::INFINITY, p);
        for w in poly.windows(2) {
            let (a, b) = (w[0], w[1]);
            let (dz, dr) = (b.z - a.z, b.r - a.r);
            let l2 = dz * dz + dr * dr;
            let t = if l2 > 0.0 { (((p.z - a.z) * dz + (p.r - a.r) * dr) / l2).clamp(0.0, 1.0) } else { 0.0 };
            let q = Point::new(a.z + t * dz, a.r + t * dr);
            if q.distance(p) < best.0 {
                best = (q.distance(p), q);
            }
        }
        best.1
    };
    let (b, m) = if k < c.cut.len() {
        (c.cut[k], nearest(&moved, c.cut[k]))
    } else {
        let q = moved[k - c.cut.len()];
        (nearest(&c.cut, q), q)
    };
    Contact { clearance, shift, bolt: b, nut: m }
}

/// What to measure against: the thread, its kind and (optionally) the maximum-material limits.
#[derive(Clone, Copy, Debug)]
pub struct MeasureSetup<'a> {
    /// The basic thread.
    pub thread: &'a BasicThread,
    /// External or internal.
    pub kind: ThreadKind,
    /// Maximum-material pitch diameter (external d2 max, internal D2 min), mm; with it the
    /// maximum-material profile is the basic profile moved radially to that pitch diameter.
    pub mmc_pitch_diameter: Option<f64>,
    /// Largest major diameter of an external thread, mm, where it lies above the basic crest
    /// moved with the pitch diameter (trapezoid forms keep d in position h, Acme's allowance is
    /// on d2 only): the GO gauge's root is relieved up to it, so a crest within its limits never
    /// touches the gauge.
    pub mmc_major_diameter: Option<f64>,
    /// Compute the costlier extras: the three-wire M and the maximum-material clearance.
    pub extras: bool,
}

impl<'a> MeasureSetup<'a> {
    /// The setup of a parallel thread of a class, extras included: its maximum-material pitch
    /// diameter (an external thread's d2 max, an internal one's D2 min) and an external thread's
    /// largest major diameter.
    pub fn for_class(
        thread: &'a BasicThread,
        kind: ThreadKind,
        limits: &crate::standards::tolerance::ThreadLimits,
    ) -> Self {
        let (mmc_pitch_diameter, mmc_major_diameter) = match kind {
            ThreadKind::External => (limits.pitch_diameter.max, limits.major_diameter.max),
            ThreadKind::Internal => (limits.pitch_diameter.min, None),
        };
        MeasureSetup { thread, kind, mmc_pitch_diameter, mmc_major_diameter, extras: true }
    }

    /// The same setup measuring sizes only (no three-wire M, no maximum-material check): what an
    /// iteration on the final X needs.
    pub fn sizes_only(&self) -> Self {
        MeasureSetup { extras: false, ..*self }
    }
}

/// Measures the groove of `profile` (part coordinates, low to high Z) nearest `z_ref`.
///
/// The basic profile of M10x1.5 measures its basic pitch diameter, d − 0.649519·P:
///
/// ```
/// use threadcheck::{measure, BasicThread, MeasureSetup, ProfileKind, ThreadKind};
/// let m10 = BasicThread::metric(10.0, 1.5);
/// // Four pitches of the basic profile, grooves centred at z = 0, ±1.5, ±3.
/// let one = m10.profile(ProfileKind::Basic, 5e-5);
/// let profile: Vec<_> = (-2..2).flat_map(|k| one.iter().map(move |p| threadcheck::Point::new(p.z + 1.5 * k as f64, p.r))).collect();
/// let ms = MeasureSetup { thread: &m10, kind: ThreadKind::External, mmc_pitch_diameter: None, mmc_major_diameter: None, extras: false };
/// let m = measure(&ms, &profile, 0.0)?;
/// assert!((m.pitch_diameter - (10.0 - 0.649519 * 1.5)).abs() < 1e-5);
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn measure(setup: &MeasureSetup<'_>, profile: &[Point], z_ref: f64) -> Result<Measurement, Error> {
    let t = setup.thread;
    let p = t.pitch;
    let kind = setup.kind;
    let s = if kind == ThreadKind::External { 1.0 } else { -1.0 };
    let g = Groove::find(normalise(profile, kind), z_ref, p)?;
    let (y_root, y_top) = (g.y_root(), g.y_top());
    let y_crest = g.pts[g.left].r.max(g.pts[g.right].r);
    if !(y_top > y_root) {
        return Err(Error::Geometry("the groove has no depth".into()));
    }
    let flanks =
        g.fit_flanks().ok_or_else(|| Error::Geometry("the groove flanks could not be traced".into()))?;
    // Pitch line: where the groove is P/2 wide. Bisection on the cut flanks when it lies between
    // root and crest, else on the fitted flank lines extended.
    let half = 0.5 * p;
    let w_lo = g.width(y_root + 1e-12 * (y_top - y_root).max(1.0)).unwrap_or(0.0);
    let w_hi = g.width(y_top).unwrap_or(f64::INFINITY);
    let (y_pitch, extrapolated, zc) = if w_lo <= half && half <= w_hi {
        // Between two vertex heights both flank crossings run along fixed segments, so the
        // width is linear there: a binary search over the heights finds the stretch where it
        // reaches P/2, and the line there the level, exactly.
        let mut hs: Vec<f64> =
            g.pts[g.left..=g.right].iter().map(|q| q.r).filter(|&r| r > y_root && r < y_top).collect();
        hs.push(y_root);
        hs.push(y_top);
        hs.sort_by(f64::total_cmp);
        hs.dedup();
        let w = |y: f64| g.width(y).unwrap_or(0.0);
        let (mut i, mut j) = (0, hs.len() - 1);
        while j - i > 1 {
            let m = (i + j) / 2;
            if w(hs[m]) < half {
                i = m;
            } else {
                j = m;
            }
        }
        // The line through two points inside the stretch (where the crossing moves from one
        // flank segment to the next around a notch, the width jumps at a vertex height, and the
        // stretch's own line starts after the jump); where a jump passes P/2, at the jump.
        let (ya, yb) = (hs[i] + (hs[j] - hs[i]) / 3.0, hs[i] + 2.0 * (hs[j] - hs[i]) / 3.0);
        let (wa, wb) = (w(ya), w(yb));
        let y = if wb > wa {
            (ya + (half - wa) / (wb - wa) * (yb - ya)).clamp(hs[i], hs[j])
        } else if wa >= half {
            hs[i]
        } else {
            hs[j]
        };
        let zc = 0.5 * (g.left_z(y).unwrap_or(0.0) + g.right_z(y).unwrap_or(0.0));
        (y, false, zc)
    } else {
        let ((al, bl), (ar, br)) = flanks;
        // (ar − al) + (br − bl)·y = P/2
        let y = (half - (ar - al)) / (br - bl);
        (y, true, 0.5 * ((al + bl * y) + (ar + br * y)))
    };
    let angle = |b: f64| b.abs().atan().to_degrees();
    // Width of each crest 1 µm below its top, less what two flanks meeting in a sharp peak would
    // span there (2·1 µm·tan β): about 0 for a peak, the flat or rounded top's width otherwise.
    let delta = 1e-3;
    let peak = 2.0 * delta * t.half_angle().tan();
    let crest_width = [g.left, g.right]
        .iter()
        .map(|&i| {
            let y = g.pts[i].r - delta;
            let lo = (0..i).rev().find_map(|k| cross_at_level(g.pts[k], g.pts[k + 1], y));
            let hi = (i..g.pts.len() - 1).find_map(|k| cross_at_level(g.pts[k], g.pts[k + 1], y));
            match (lo, hi) {
                (Some(a), Some(b)) => (b - a - peak).max(0.0),
                _ => f64::INFINITY,
            }
        })
        .fold(f64::INFINITY, f64::min);
    let root_radius = min_concave_radius(&g.pts[g.left..=g.right]);
    let beta = t.half_angle();
    let three_wire = if kind == ThreadKind::External && setup.extras {
        let w = p / (2.0 * beta.cos());
        wire_rest(&g, 0.5 * w, flanks).map(|(_, yc)| ThreeWire { wire: w, m: dia(yc) + w })
    } else {
        None
    };
    let max_material_clearance = setup.mmc_pitch_diameter.filter(|_| setup.extras).map(|d2m| {
        // The maximum-material profile: the basic profile moved radially so its pitch diameter
        // is d2m, centred on the measured groove; then the best axial fit, as a gauge finds it.
        let variant = if kind == ThreadKind::External { ProfileKind::Basic } else { ProfileKind::Nut };
        // In normalised coordinates (r = −radius inside a nut) a larger pitch diameter is a
        // shift of s·Δd2/2.
        let shift_r = s * 0.5 * (d2m - t.pitch_diameter());
        let mut one = normalise(&t.profile(variant, 5e-5), kind);
        if let (ThreadKind::External, Some(dmax)) = (kind, setup.mmc_major_diameter) {
            // Relieve the gauge's root: the crest flat goes up to d max with vertical steps.
            let top = one.iter().map(|q| q.r).fold(f64::NEG_INFINITY, f64::max);
            let raise = 0.5 * dmax - (top + shift_r);
            if raise > 0.0 {
                let at_top = |q: &Point| q.r >= top - 1e-12;
                let mut relieved = Vec::with_capacity(one.len() + 4);
                for (i, q) in one.iter().enumerate() {
                    let prev_top = i > 0 && at_top(&one[i - 1]);
                    let next_top = i + 1 < one.len() && at_top(&one[i + 1]);
                    if at_top(q) {
                        if !prev_top {
                            relieved.push(*q);
                        }
                        relieved.push(Point::new(q.z, q.r + raise));
                        if !next_top {
                            relieved.push(*q);
                        }
                    } else {
                        relieved.push(*q);
                    }
                }
                one = relieved;
            }
        }
        let cut: Vec<Point> = g.pts[g.left..=g.right].to_vec();
        let mut mmc = Vec::new();
        for k in -1..=1 {
            for q in &one {
                mmc.push(Point::new(q.z + zc + k as f64 * p, q.r + shift_r));
            }
        }
        mmc.dedup_by(|a, b| a.distance(*b) < 1e-12);
        let c = Clearance::new(cut, mmc);
        // 8 coarse and 16 fine golden steps narrow the gauge's axial position to well under
        // 0.01 µm; the clearance changes at most that much with it.
        c.best(0.125 * p)
    });
    let (major, minor) = if kind == ThreadKind::External {
        (dia(y_crest), dia(y_root))
    } else {
        (dia(-y_root), dia(-y_crest))
    };
    let engagement_depth = match kind {
        ThreadKind::External => 0.5 * (major - t.minor_diameter_internal()),
        ThreadKind::Internal => 0.5 * (t.nominal_diameter - minor),
    };
    Ok(Measurement {
        major_diameter: major,
        pitch_diameter: dia(s * y_pitch),
        minor_diameter: minor,
        thread_depth: 0.5 * (major - minor),
        engagement_depth,
        flank_angles: [angle(flanks.0 .1), angle(flanks.1 .1)],
        root_radius,
        crest_width,
        groove_center: zc,
        root_pockets: {
            // Pockets are counted below mid-depth only: a notch in a crest (on a taper thread,
            // where neighbouring turns top the crest at different heights) is no second pocket.
            let mid = 0.5 * (y_root + y_top);
            let i0 = (g.left..=g.root).rev().find(|&i| g.pts[i].r >= mid).unwrap_or(g.left);
            let i1 = (g.root..=g.right).find(|&i| g.pts[i].r >= mid).unwrap_or(g.right);
            count_pockets(&g.pts[i0..=i1], 1e-3)
        },
        fin_height: fin_height(
            &g.pts[g.left..=g.right],
            g.root - g.left,
            g.pts[g.left].r.min(g.pts[g.right].r) - p / 16.0,
        ),
        pitch_line_extrapolated: extrapolated,
        three_wire,
        max_material_clearance,
    })
}

/// The measurement over wires M of an external thread's groove nearest `z_ref` for wires of
/// diameter `wire`, mm, in the axial section (no helix term): twice the height where a wire of
/// that size comes to rest on the as-cut profile, plus the wire. The wire rests on the flanks
/// where they are straight, else wherever the profile holds it (a step, a worn tip's radius).
///
/// On straight 60° flanks with the wire touching them, M = d2 + 3w − 0.866025·P:
///
/// ```
/// use threadcheck::{over_wires, BasicThread, MeasureSetup, ProfileKind, ThreadKind};
/// let m10 = BasicThread::metric(10.0, 1.5);
/// let one = m10.profile(ProfileKind::Basic, 5e-5);
/// let profile: Vec<_> = (-2..2).flat_map(|k| one.iter().map(move |p| threadcheck::Point::new(p.z + 1.5 * k as f64, p.r))).collect();
/// let ms = MeasureSetup { thread: &m10, kind: ThreadKind::External, mmc_pitch_diameter: None, mmc_major_diameter: None, extras: false };
/// let m = over_wires(&ms, &profile, 0.0, 0.866)?;
/// let d2 = 10.0 - 0.649519053 * 1.5;
/// assert!((m - (d2 + 3.0 * 0.866 - 0.866025404 * 1.5)).abs() < 1e-6);
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn over_wires(setup: &MeasureSetup<'_>, profile: &[Point], z_ref: f64, wire: f64) -> Result<f64, Error> {
    if setup.kind != ThreadKind::External {
        return Err(Error::Input("a measurement over wires is taken on an external thread".into()));
    }
    if !(wire.is_finite() && wire > 0.0) {
        return Err(Error::Input(format!("wire diameter {wire} mm must be a positive length")));
    }
    let g = Groove::find(normalise(profile, setup.kind), z_ref, setup.thread.pitch)?;
    let flanks =
        g.fit_flanks().ok_or_else(|| Error::Geometry("the groove flanks could not be traced".into()))?;
    let (_, yc) = wire_rest(&g, 0.5 * wire, flanks)
        .ok_or_else(|| Error::Geometry(format!("a wire of {wire} mm finds no rest in the groove")))?;
    Ok(dia(yc) + wire)
}

/// Where along a thread profile a point lies.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ProfileRegion {
    /// The root.
    Root,
    /// A flank.
    Flank,
    /// The crest.
    Crest,
}

/// One sample of a profile's normal deviation from a reference profile.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct DeviationSample {
    /// Arc length along the reference from its start, mm.
    pub s: f64,
    /// Signed normal distance, mm: positive where the profile lies on the air side (more
    /// material).
    pub deviation: f64,
    /// Where on the reference the sample lies.
    pub region: ProfileRegion,
}

/// The normal deviation of profile `other` from the `reference` profile (both in part
/// coordinates, low to high Z), at `n` points spaced evenly along the reference. The distance is
/// positive where `other` lies on the air side (more material): the air is above the profile
/// (`air_up`, a bolt) or below it (a nut). The region is read off the reference's slope and
/// height.
pub fn deviation_along(reference: &[Point], other: &[Point], air_up: bool, n: usize) -> Vec<DeviationSample> {
    if reference.len() < 2 || other.len() < 2 || n < 2 {
        return Vec::new();
    }
    let lengths: Vec<f64> = std::iter::once(0.0)
        .chain(reference.windows(2).scan(0.0, |acc, w| {
            *acc += w[0].distance(w[1]);
            Some(*acc)
        }))
        .collect();
    let total = lengths[lengths.len() - 1];
    let (r_lo, r_hi) =
        reference.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| (a.min(p.r), b.max(p.r)));
    let mid = 0.5 * (r_lo + r_hi);
    let line = Line::through(other.iter().copied());
    let mut out = Vec::with_capacity(n);
    for k in 0..n {
        let s = total * k as f64 / (n - 1) as f64;
        let i = lengths.partition_point(|&l| l < s).clamp(1, reference.len() - 1);
        let (a, b) = (reference[i - 1], reference[i]);
        let seg = lengths[i] - lengths[i - 1];
        let u = if seg > 0.0 { ((s - lengths[i - 1]) / seg).clamp(0.0, 1.0) } else { 0.0 };
        let q = Point::new(a.z + u * (b.z - a.z), a.r + u * (b.r - a.r));
        let (tz, tr) = ((b.z - a.z) / seg.max(1e-15), (b.r - a.r) / seg.max(1e-15));
        let (nz, nr) = if air_up { (-tr, tz) } else { (tr, -tz) };
        let (proj, _) = line.project(q);
        let (cz, cr) = (proj.z - q.z, proj.r - q.r);
        let d = cz.hypot(cr);
        let dev = if cz * nz + cr * nr >= 0.0 { d } else { -d };
        let region = if tr.abs() > 0.05 {
            ProfileRegion::Flank
        } else if (q.r < mid) == air_up {
            ProfileRegion::Root
        } else {
            ProfileRegion::Crest
        };
        out.push(DeviationSample { s, deviation: dev, region });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pockets_are_counted_across_ridges_only() {
        let v = |r: &[f64]| r.iter().enumerate().map(|(i, &r)| Point::new(i as f64, r)).collect::<Vec<_>>();
        assert_eq!(count_pockets(&v(&[1.0, 0.5, 0.0, 0.5, 1.0]), 1e-3), 1);
        assert_eq!(count_pockets(&v(&[1.0, 0.0, 0.3, 0.0, 1.0]), 1e-3), 2);
        // A ridge lower than the threshold is not a second pocket.
        assert_eq!(count_pockets(&v(&[1.0, 0.0, 0.0005, 0.0, 1.0]), 1e-3), 1);
    }
}
