//! The sweep: every pass leaves one imprint of the insert per lead in the axial section; the
//! union of the imprints, subtracted from the blank, is the as-cut section.
//!
//! All polygon booleans go through the private `boolean` module. The blank is kept only a little taller than
//! the cut and the window only a few pitches wide, which keeps the backend's snapping grid in the
//! nanometres (see the private `boolean` module).

use crate::geometry::boolean::{union_all, Region, UnionStrategy};
use crate::geometry::insert::Insert;
use crate::geometry::parry::Line;
use crate::ground::bounds::MAX_IMPRINTS;
use crate::ground::plane::{rad, Point};
use crate::standards::ThreadKind;
use crate::toolpath::passes::Pass;
use crate::Error;
use serde::Serialize;

/// An axial range of the section, mm.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Window {
    /// Lower Z, mm.
    pub z_min: f64,
    /// Upper Z, mm.
    pub z_max: f64,
}

impl Window {
    /// The window of `pitches` pitches centred on `z_center`.
    pub fn around(z_center: f64, pitch: f64, pitches: f64) -> Window {
        Window { z_min: z_center - 0.5 * pitches * pitch, z_max: z_center + 0.5 * pitches * pitch }
    }
}

/// What the sweep works on.
#[derive(Clone, Copy, Debug)]
pub struct SweepSetup<'a> {
    /// External or internal.
    pub kind: ThreadKind,
    /// The insert.
    pub insert: &'a Insert,
    /// Diameter of the blank: the turned bar (external) or the bore (internal), mm.
    pub blank_diameter: f64,
    /// Pitch, mm (for windows and grooves).
    pub pitch: f64,
}

/// One imprint: pass `pass` (0-based index into the pass list) crossing at `z` with its tip on
/// diameter `x`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Imprint {
    /// Index into the pass list (0-based).
    pub pass: usize,
    /// Axial position of the tip, mm.
    pub z: f64,
    /// Tip diameter, mm.
    pub x: f64,
}

/// The as-cut section: material polygons, exteriors counter-clockwise, holes clockwise, every
/// coordinate finite. Built only by the sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct Section {
    /// External or internal.
    pub kind: ThreadKind,
    /// The window it covers.
    pub window: Window,
    /// Radius of the blank surface (the crest left by turning), mm.
    pub surface_r: f64,
    /// Radius of the artificial far side of the blank (floor or ceiling), mm.
    pub far_r: f64,
    /// The material as polygons: from the booleans, or built from the exact profile when first
    /// asked for (a verify that only measures never needs it).
    region: std::sync::OnceLock<Region>,
    /// The cut surface when the envelope computed it exactly.
    exact_profile: Option<Vec<Point>>,
}

impl Section {
    /// Material area, mm².
    pub fn area(&self) -> f64 {
        self.region().area()
    }

    /// The polygons as (exterior, holes).
    pub fn polygons(&self) -> Vec<(Vec<Point>, Vec<Vec<Point>>)> {
        self.region().polygons()
    }

    /// The material as a region, for further booleans.
    pub fn region(&self) -> &Region {
        self.region.get_or_init(|| {
            // Only envelope sections leave it unset, and they hold their profile.
            let profile = self.exact_profile.as_deref().unwrap_or_default();
            let w = self.window;
            let mut ring = vec![Point::new(w.z_min, self.far_r), Point::new(w.z_max, self.far_r)];
            ring.extend(profile.iter().rev().copied());
            Region::from_ring(&ring)
        })
    }

    /// The cut surface as a polyline from low to high Z: the material boundary without the
    /// window's sides and the far side. Where the section falls apart into pieces, the longest
    /// stretch is returned.
    pub fn profile(&self) -> Vec<Point> {
        if let Some(p) = &self.exact_profile {
            return p.clone();
        }
        let eps = 1e-6;
        let w = self.window;
        let artificial = |a: Point, b: Point| {
            ((a.z - w.z_min).abs() < eps && (b.z - w.z_min).abs() < eps)
                || ((a.z - w.z_max).abs() < eps && (b.z - w.z_max).abs() < eps)
                || ((a.r - self.far_r).abs() < eps && (b.r - self.far_r).abs() < eps)
        };
        let mut best: Vec<Point> = Vec::new();
        for (ext, _) in self.polygons() {
            let n = ext.len();
            // Start the walk just after an artificial edge so that runs are not split.
            let Some(s) = (0..n).find(|&i| artificial(ext[i], ext[(i + 1) % n])) else { continue };
            let mut run: Vec<Point> = Vec::new();
            for k in 1..=n {
                let i = (s + k) % n;
                let (a, b) = (ext[i], ext[(i + 1) % n]);
                if artificial(a, b) {
                    if run.len() > best.len() {
                        best = std::mem::take(&mut run);
                    }
                    run.clear();
                } else {
                    if run.is_empty() {
                        run.push(a);
                    }
                    run.push(b);
                }
            }
            if run.len() > best.len() {
                best = run;
            }
        }
        if best.len() > 1 && best[0].z > best[best.len() - 1].z {
            best.reverse();
        }
        best
    }
}

/// The result of a sweep.
#[derive(Clone, Debug)]
pub struct Sweep {
    /// The as-cut section.
    pub section: Section,
    /// The imprints placed, in pass order.
    pub imprints: Vec<Imprint>,
}

fn check_finite(passes: &[Pass]) -> Result<(), Error> {
    for p in passes {
        for (name, v) in
            [("X", p.x_start), ("X", p.x_end), ("Z", p.z_start), ("Z", p.z_end), ("lead", p.lead)]
        {
            if !v.is_finite() {
                return Err(Error::Input(format!("pass {}: {name} is not a finite number", p.index)));
            }
        }
        if !(p.lead > 0.0) {
            return Err(Error::Input(format!(
                "pass {}: lead {} mm must be greater than zero",
                p.index, p.lead
            )));
        }
    }
    Ok(())
}

/// The far side of the blank (floor for external threads, ceiling for internal ones), radius mm.
///
/// The insert cannot cut deeper below the surface than its own height (the sweep refuses passes
/// where it would), so a floor a little beyond that height holds every cut, and it does not
/// depend on the passes: sections of different plans are directly comparable.
fn far_side(kind: ThreadKind, surface_r: f64, insert_height: f64) -> f64 {
    let margin = 0.05;
    match kind {
        ThreadKind::External => (surface_r - insert_height - margin).max(0.0),
        ThreadKind::Internal => surface_r + insert_height + margin,
    }
}

/// The window from one pitch before the threading moves start to one pitch past where they
/// end: the whole thread, with its incomplete teeth at the run-out.
pub fn full_length_window(passes: &[Pass], pitch: f64) -> Window {
    let (lo, hi) = passes.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
        (lo.min(p.z_start.min(p.z_end)), hi.max(p.z_start.max(p.z_end)))
    });
    Window { z_min: lo - pitch, z_max: hi + pitch }
}

/// The blank rectangle and every placed imprint outline (part coordinates, counter-clockwise)
/// that a sweep of `passes` over `window` works on: what a baseline with another geometry
/// library needs to redo the cut.
pub fn placements(
    setup: &SweepSetup<'_>,
    passes: &[Pass],
    window: Window,
) -> Result<(Vec<Point>, Vec<Vec<Point>>), Error> {
    let imps = imprints(setup, passes, window)?;
    let surface_r = rad(setup.blank_diameter);
    let far_r = far_side(setup.kind, surface_r, setup.insert.height());
    let (r0, r1) = if setup.kind == ThreadKind::External { (far_r, surface_r) } else { (surface_r, far_r) };
    let blank = vec![
        Point::new(window.z_min, r0),
        Point::new(window.z_max, r0),
        Point::new(window.z_max, r1),
        Point::new(window.z_min, r1),
    ];
    let rings =
        imps.iter().map(|im| setup.insert.placed(&Insert::placement(im.z, rad(im.x), setup.kind))).collect();
    Ok((blank, rings))
}

/// The imprints of `passes` that touch `window`.
pub fn imprints(setup: &SweepSetup<'_>, passes: &[Pass], window: Window) -> Result<Vec<Imprint>, Error> {
    check_finite(passes)?;
    let (lo, hi) = setup.insert.z_extent();
    let reach = lo.abs().max(hi.abs());
    let mut out = Vec::new();
    for (i, p) in passes.iter().enumerate() {
        for z in p.crossings(window.z_min - reach, window.z_max + reach) {
            out.push(Imprint { pass: i, z, x: p.x_at(z) });
            if out.len() > MAX_IMPRINTS {
                return Err(Error::Input(format!("more than {MAX_IMPRINTS} imprints in one section")));
            }
        }
    }
    Ok(out)
}

/// A full-profile insert cut once to the basic minor diameter d3 of M10x1.5 leaves the basic
/// pitch diameter, 10 − 0.649519·1.5 = 9.0257 mm:
///
/// ```
/// use threadcheck::{measure, sweep, BasicThread, Insert, MeasureSetup, Pass, SweepSetup, ThreadKind, UnionStrategy, Window};
/// let m10 = BasicThread::metric(10.0, 1.5);
/// let insert = Insert::full_profile(&m10, ThreadKind::External, 5e-5);
/// let d3 = 10.0 - 1.226869 * 1.5;
/// let passes = [Pass::parallel(1, d3, 5.0, -20.0, 1.5)];
/// let setup = SweepSetup { kind: ThreadKind::External, insert: &insert, blank_diameter: 10.0, pitch: 1.5 };
/// let cut = sweep(&setup, &passes, Window::around(-10.0, 1.5, 4.0), UnionStrategy::Envelope)?;
/// let ms = MeasureSetup { thread: &m10, kind: ThreadKind::External, mmc_pitch_diameter: None, mmc_major_diameter: None, extras: false };
/// let m = measure(&ms, &cut.section.profile(), -10.0)?;
/// assert!((m.pitch_diameter - 9.0257).abs() < 1e-4);
/// # Ok::<(), threadcheck::Error>(())
/// ```
/// Sweeps the insert along `passes` and returns the material left in `window`.
pub fn sweep(
    setup: &SweepSetup<'_>,
    passes: &[Pass],
    window: Window,
    strategy: UnionStrategy,
) -> Result<Sweep, Error> {
    if !(window.z_max > window.z_min) || !window.z_min.is_finite() || !window.z_max.is_finite() {
        return Err(Error::Input("the section window is empty".into()));
    }
    if !(setup.blank_diameter.is_finite() && setup.blank_diameter > 0.0) {
        return Err(Error::Input(format!(
            "blank diameter {} mm must be a positive length",
            setup.blank_diameter
        )));
    }
    let imps = imprints(setup, passes, window)?;
    if imps.is_empty() {
        return Err(Error::Geometry(
            "no pass crosses the section: the passes do not reach the thread".into(),
        ));
    }
    let kind = setup.kind;
    let surface_r = rad(setup.blank_diameter);
    let height = setup.insert.height();
    for im in &imps {
        let r = rad(im.x);
        let p = &passes[im.pass];
        match kind {
            ThreadKind::External => {
                if im.x < 0.0 {
                    return Err(Error::Geometry(format!(
                        "pass {}: tip at X{:.4} is beyond the spindle axis",
                        p.index, im.x
                    )));
                }
                if r + height <= surface_r {
                    return Err(Error::Geometry(format!(
                        "pass {}: the insert ({height:.3} mm tall) ends inside the blank at X{:.4}; it cannot cut that deep",
                        p.index, im.x
                    )));
                }
            }
            ThreadKind::Internal => {
                if r - height >= surface_r {
                    return Err(Error::Geometry(format!(
                        "pass {}: the insert ({height:.3} mm tall) ends inside the part at X{:.4}; it cannot cut that deep",
                        p.index, im.x
                    )));
                }
            }
        }
    }
    let far_r = far_side(kind, surface_r, height);
    if strategy == UnionStrategy::Envelope {
        if let Some(chain) = crate::geometry::envelope::bottom_chain(&setup.insert.outline) {
            let section = envelope_section(kind, &chain, &imps, window, surface_r, far_r);
            return Ok(Sweep { section, imprints: imps });
        }
    }
    let (r0, r1) = if kind == ThreadKind::External { (far_r, surface_r) } else { (surface_r, far_r) };
    let blank = Region::rect(window.z_min, window.z_max, r0, r1);
    let mut sorted = imps.clone();
    sorted.sort_by(|a, b| a.z.total_cmp(&b.z).then(a.pass.cmp(&b.pass)));
    let regions: Vec<Region> = sorted
        .iter()
        .map(|im| Region::from_ring(&setup.insert.placed(&Insert::placement(im.z, rad(im.x), kind))))
        .collect();
    let cut = union_all(regions, strategy);
    let material = blank.difference(&cut);
    for (ext, holes) in material.polygons() {
        if ext.iter().chain(holes.iter().flatten()).any(|p| !p.is_finite()) {
            return Err(Error::Geometry("the section has a non-finite vertex".into()));
        }
    }
    Ok(Sweep {
        section: Section { kind, window, surface_r, far_r, region: material.into(), exact_profile: None },
        imprints: imps,
    })
}

/// The part of a bottom chain (insert frame, heights above the tip) at or below `height`, cut at
/// the crossings; the chain's ends above that height cannot touch the blank.
fn clip_chain(chain: &[Point], height: f64) -> Vec<Point> {
    let first = chain.iter().position(|p| p.r <= height);
    let last = chain.iter().rposition(|p| p.r <= height);
    let (Some(i), Some(j)) = (first, last) else { return chain.to_vec() };
    let mut out = Vec::with_capacity(j - i + 3);
    if i > 0 {
        if let Some(z) = crate::ground::plane::cross_at_level(chain[i - 1], chain[i], height) {
            out.push(Point::new(z, height));
        }
    }
    out.extend_from_slice(&chain[i..=j]);
    if j + 1 < chain.len() {
        if let Some(z) = crate::ground::plane::cross_at_level(chain[j], chain[j + 1], height) {
            out.push(Point::new(z, height));
        }
    }
    out.dedup_by(|a, b| a.z == b.z && a.r == b.r);
    if out.windows(2).all(|w| w[1].z > w[0].z) {
        out
    } else {
        chain.to_vec()
    }
}

/// The section as the lower envelope of the imprints' bottom chains (normalised frame: `y = r`
/// external, `y = −r` internal, where an internal placement also mirrors the insert in z).
fn envelope_section(
    kind: ThreadKind,
    chain: &[Point],
    imps: &[Imprint],
    window: Window,
    surface_r: f64,
    far_r: f64,
) -> Section {
    let s = if kind == ThreadKind::External { 1.0 } else { -1.0 };
    // Only the part of the chain that can reach into the blank matters: clip it at the greatest
    // height (above its own tip) that any imprint's tip lies below the surface. That shortens
    // the chain's reach along Z and so the number of imprints a window sees.
    let reach = imps.iter().map(|im| s * surface_r - s * rad(im.x)).fold(0.0f64, f64::max) + 1e-6;
    let clipped = clip_chain(chain, reach);
    let mirrored: Vec<Point> = clipped.iter().rev().map(|p| Point::new(-p.z, p.r)).collect();
    let local = if kind == ThreadKind::External { &clipped[..] } else { &mirrored[..] };
    let (lo, hi) = (local[0].z, local[local.len() - 1].z);
    // An imprint whose (clipped) chain misses the window, or stays above the surface, cannot
    // change the envelope.
    let tips: Vec<(f64, f64)> = imps
        .iter()
        .map(|im| (im.z, s * rad(im.x)))
        .filter(|&(zt, yt)| zt + hi > window.z_min && zt + lo < window.z_max && yt < s * surface_r)
        .collect();
    let env =
        crate::geometry::envelope::lower_envelope(local, &tips, window.z_min, window.z_max, s * surface_r);
    let profile: Vec<Point> = env.0.iter().map(|p| Point::new(p.z, s * p.r)).collect();
    Section {
        kind,
        window,
        surface_r,
        far_r,
        region: std::sync::OnceLock::new(),
        exact_profile: Some(profile),
    }
}

/// The greatest `distance` (to an insert's outline) along segment `a`–`b`. Distance to a polyline, taken along a
/// segment, is a lower envelope of convex functions and may peak inside the segment (the middle
/// of a first pass's flat chip top, above the tip), so the segment is sampled and the best sample
/// refined by golden section.
///
/// `floor` is the greatest distance found so far elsewhere: distance is 1-Lipschitz along the
/// segment, so nothing on it exceeds (d(a) + d(b) + |ab|)/2, and a segment whose bound stays
/// at or under the floor is settled by its two ends.
fn farthest_on_segment(distance: &dyn Fn(Point) -> f64, a: Point, b: Point, floor: f64, convex: bool) -> f64 {
    let at = |t: f64| distance(Point::new(a.z + t * (b.z - a.z), a.r + t * (b.r - a.r)));
    let len = a.distance(b);
    let (d0, d1) = (at(0.0), at(1.0));
    if 0.5 * (d0 + d1 + len) <= floor {
        return d0.max(d1);
    }
    if convex {
        // Inside a convex insert the distance to its outline is the least of the distances to
        // its edges' lines, concave along the segment: the chords just inside either end,
        // carried on, bound it from above; where they cannot beat what is known, the ends
        // settle it, else a golden search on the whole segment (a concave function is
        // unimodal) finds its top.
        let e = 1e-6;
        let (de0, de1) = (at(e), at(1.0 - e));
        let best = d0.max(d1).max(de0).max(de1);
        let (s0, s1) = ((de0 - d0) / e, (d1 - de1) / e);
        // The greatest of min(d0 + s0·t, d1 − s1·(1 − t)) over [0, 1]: at an end or where the
        // lines meet.
        let lower = |t: f64| (d0 + s0 * t).min(d1 - s1 * (1.0 - t));
        let meet = if s0 != s1 { ((d1 - s1) - d0) / (s0 - s1) } else { 0.0 };
        let bound = lower(0.0).max(lower(1.0)).max(lower(meet.clamp(0.0, 1.0)));
        if bound <= floor.max(best) + 1e-12 {
            return best;
        }
        let (_, f) = crate::geometry::measure::golden_min(&|t| -at(t), 0.0, 1.0, 40);
        return best.max(-f);
    }
    let n = 6;
    let mut d = [0.0; 7];
    (d[0], d[n]) = (d0, d1);
    for (k, v) in d.iter_mut().enumerate().take(n).skip(1) {
        *v = at(k as f64 / n as f64);
    }
    let best_k = (0..=n).fold(0, |b, k| if d[k] > d[b] { k } else { b });
    let best = d[best_k];
    // Where no stretch between samples can rise above the floor, the samples settle it.
    if (0..n).all(|k| 0.5 * (d[k] + d[k + 1] + len / n as f64) <= floor.max(best)) {
        return best;
    }
    let (lo, hi) = (best_k.saturating_sub(1) as f64 / n as f64, (best_k + 1).min(n) as f64 / n as f64);
    let (_, f) = crate::geometry::measure::golden_min(&|t| -at(t), lo, hi, 28);
    best.max(-f)
}

/// What one pass does at one groove.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Default)]
pub struct PassMetrics {
    /// Area of the chip cross-section this pass removes from one groove, mm².
    pub chip_area: f64,
    /// Engaged cutting-edge length on the leading flank (facing the feed), mm.
    pub leading: f64,
    /// Engaged cutting-edge length on the trailing flank, mm.
    pub trailing: f64,
    /// Engaged cutting-edge length on the tip (below the insert's tip zone), mm.
    pub tip: f64,
    /// Largest chip thickness: the greatest distance from the removed material to the new
    /// surface, measured normal to the cutting edge, mm.
    pub max_chip_thickness: f64,
    /// Part of the chip area on the trailing side of the tip (behind it, against the feed),
    /// mm²: about half the chip for radial infeed, little for flank infeed.
    pub trailing_area: f64,
}

/// Per-pass metrics at the groove nearest `z_ref`, in cutting order.
///
/// The chip of a pass is what its imprint takes from the material left by every earlier pass
/// and by its own previous revolution (one lead back along the feed), in steady state.
///
/// ```
/// use threadcheck::{pass_metrics, BasicThread, Insert, Pass, SweepSetup, ThreadKind};
/// let m10 = BasicThread::metric(10.0, 1.5);
/// let insert = Insert::full_profile(&m10, ThreadKind::External, 5e-5);
/// // Two radial passes: the second takes the strip between X9.0 and X8.16.
/// let passes = [Pass::parallel(1, 9.0, 5.0, -20.0, 1.5), Pass::parallel(2, 8.16, 5.0, -20.0, 1.5)];
/// let setup = SweepSetup { kind: ThreadKind::External, insert: &insert, blank_diameter: 10.0, pitch: 1.5 };
/// let m = pass_metrics(&setup, &passes, -10.0)?;
/// assert_eq!(m.len(), 2);
/// assert!(m[0].chip_area > 0.0 && m[1].chip_area > 0.0);
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn pass_metrics(setup: &SweepSetup<'_>, passes: &[Pass], z_ref: f64) -> Result<Vec<PassMetrics>, Error> {
    check_finite(passes)?;
    if let Some(chain) = crate::geometry::envelope::bottom_chain(&setup.insert.outline) {
        return Ok(envelope_pass_metrics(setup, passes, z_ref, &chain));
    }
    boolean_pass_metrics(setup, passes, z_ref)
}

/// The window the per-pass metrics look at: the groove at `z_ref`, the insert's reach and one
/// pitch either side.
fn metrics_window(setup: &SweepSetup<'_>, z_ref: f64) -> Window {
    let (lo, hi) = setup.insert.z_extent();
    let reach = lo.abs().max(hi.abs());
    Window { z_min: z_ref - reach - setup.pitch, z_max: z_ref + reach + setup.pitch }
}

/// Where `pass` crosses the groove at `z_ref`: its crossing nearest to it within half a pitch.
fn groove_crossing(pass: &Pass, z_ref: f64, pitch: f64) -> Option<f64> {
    pass.crossings(z_ref - 0.5 * pitch, z_ref + 0.5 * pitch)
        .into_iter()
        .min_by(|a, b| (a - z_ref).abs().total_cmp(&(b - z_ref).abs()))
}

/// Pass metrics from envelopes, for inserts whose underside is a function of z: the chip of a
/// pass lies between the envelope before it (every earlier pass and its own previous
/// revolution) and its bottom chain, so its area is the integral of their gap, its engaged edge
/// the part of the chain under the material, its thickness the material side's greatest
/// distance from the insert. No polygon boolean: exact to rounding.
fn envelope_pass_metrics(
    setup: &SweepSetup<'_>,
    passes: &[Pass],
    z_ref: f64,
    chain: &[Point],
) -> Vec<PassMetrics> {
    use crate::geometry::envelope::Chain;
    let kind = setup.kind;
    let window = metrics_window(setup, z_ref);
    let s = if kind == ThreadKind::External { 1.0 } else { -1.0 };
    let surface = s * rad(setup.blank_diameter);
    // A convex insert (a V or rounded V) makes the distance from it concave along a line.
    let o = &setup.insert.outline;
    let convex = (0..o.len()).all(|i| {
        let (p, q, r) = (o[i], o[(i + 1) % o.len()], o[(i + 2) % o.len()]);
        (q.z - p.z) * (r.r - q.r) - (q.r - p.r) * (r.z - q.z) >= -1e-12 * p.distance(q) * q.distance(r)
    });
    let mirrored: Vec<Point> = chain.iter().rev().map(|q| Point::new(-q.z, q.r)).collect();
    let local = if kind == ThreadKind::External { chain } else { &mirrored[..] };
    let placed =
        |z: f64, y: f64| -> Vec<Point> { local.iter().map(|q| Point::new(z + q.z, y + q.r)).collect() };
    // In contact: somewhere more than 1 nm of material above the edge (an edge sliding along the
    // finished surface is not cutting).
    const CONTACT: f64 = 1e-6;
    let mut env = Chain::flat(window.z_min, window.z_max, surface);
    let mut out = Vec::with_capacity(passes.len());
    for pass in passes {
        let Some(z) = groove_crossing(pass, z_ref, setup.pitch) else {
            out.push(PassMetrics::default());
            continue;
        };
        let y_tip = s * rad(pass.x_at(z));
        let prev_z = z - pass.feed_direction() * pass.lead;
        let mut before = env.clone();
        before.merge(&placed(prev_z, s * rad(pass.x_at(prev_z))));
        let f = placed(z, y_tip);
        let mut after = before.clone();
        after.merge(&f);
        let mut m = PassMetrics::default();
        let (w0, w1) = (window.z_min, window.z_max);
        m.chip_area = (before.integral(w0, w1) - after.integral(w0, w1)).max(0.0);
        if m.chip_area > 0.0 {
            let (t0, t1) = if pass.feed_direction() < 0.0 { (z, w1) } else { (w0, z) };
            m.trailing_area = (before.integral(t0, t1) - after.integral(t0, t1)).max(0.0);
            // Between every breakpoint of the chain and of the material before it, both are
            // straight: the gap is linear there.
            let (f0, f1) = (f[0].z.max(w0), f[f.len() - 1].z.min(w1));
            let mut zs: Vec<f64> = f
                .iter()
                .map(|q| q.z)
                .chain(before.0.iter().map(|q| q.z))
                .filter(|&q| q > f0 && q < f1)
                .collect();
            zs.push(f0);
            zs.push(f1);
            // Where the edge leaves the tip zone, so that each stretch is tip or flank (a sharp
            // tip has no zone to leave).
            let zone = y_tip + setup.insert.tip_zone;
            for w in f.windows(2).filter(|_| setup.insert.tip_zone > 1e-6) {
                if (w[0].r - zone) * (w[1].r - zone) < 0.0 {
                    zs.push(w[0].z + (w[1].z - w[0].z) * (zone - w[0].r) / (w[1].r - w[0].r));
                }
            }
            zs.retain(|&q| q >= f0 && q <= f1);
            zs.sort_by(f64::total_cmp);
            zs.dedup();
            let edge = Chain(f.clone());
            // The insert's outline in the normalised frame (a chip point lies inside it), as one
            // parry polyline with its search tree.
            let outline = setup.insert.placed(&Insert::placement(z, rad(pass.x_at(z)), kind));
            let line = Line::through(outline.iter().chain(outline.first()).map(|q| Point::new(q.z, s * q.r)));
            let distance = |q: Point| line.distance(q);
            let mut tops: Vec<(f64, Point, Point)> = Vec::new();
            for w in zs.windows(2) {
                let (a, b) = (w[0], w[1]);
                if !(b > a) {
                    continue;
                }
                let eps = 1e-9 * (b - a);
                let gap = |q: f64| before.value(q) - edge.value(q);
                let (ga, gb) = (gap(a + eps), gap(b - eps));
                // The stretch of [a, b] under material, when the material there is thicker than
                // the contact threshold somewhere.
                if ga.max(gb) <= CONTACT {
                    continue;
                }
                let (c0, c1) = match (ga > 0.0, gb > 0.0) {
                    (true, true) => (a, b),
                    (false, false) => continue,
                    (true, false) => (a, a + (b - a) * ga / (ga - gb)),
                    (false, true) => (a + (b - a) * (-ga) / (gb - ga), b),
                };
                let (ya, yb) = (edge.value(c0 + eps), edge.value(c1 - eps));
                let len = (c1 - c0).hypot(yb - ya);
                let mid = 0.5 * (c0 + c1);
                if 0.5 * (ya + yb) - y_tip <= setup.insert.tip_zone {
                    m.tip += len;
                } else if (mid - z) * pass.feed_direction() > 0.0 {
                    m.leading += len;
                } else {
                    m.trailing += len;
                }
                // The material's side of the chip; the gap straight down to the edge bounds its
                // distance from the insert.
                let (pa, pb) =
                    (Point::new(c0, before.value(c0 + eps)), Point::new(c1, before.value(c1 - eps)));
                // Consecutive stretches under one straight piece of material are one segment.
                match tops.last_mut() {
                    Some(last)
                        if last.2 == pa
                            && ((last.2.z - last.1.z) * (pb.r - pa.r)
                                - (last.2.r - last.1.r) * (pb.z - pa.z))
                                .abs()
                                <= 1e-12 * (1.0 + last.1.distance(pb).powi(2)) =>
                    {
                        last.0 = last.0.max(ga.max(gb));
                        last.2 = pb;
                    }
                    _ => tops.push((ga.max(gb), pa, pb)),
                }
            }
            tops.sort_by(|a, b| b.0.total_cmp(&a.0));
            for (bound, pa, pb) in tops {
                if bound <= m.max_chip_thickness {
                    break;
                }
                m.max_chip_thickness = m.max_chip_thickness.max(farthest_on_segment(
                    &distance,
                    pa,
                    pb,
                    m.max_chip_thickness,
                    convex,
                ));
            }
        }
        env.merge(&f);
        out.push(m);
    }
    out
}

/// Pass metrics with polygon booleans: for inserts whose underside doubles back.
fn boolean_pass_metrics(
    setup: &SweepSetup<'_>,
    passes: &[Pass],
    z_ref: f64,
) -> Result<Vec<PassMetrics>, Error> {
    let kind = setup.kind;
    let window = metrics_window(setup, z_ref);
    let surface_r = rad(setup.blank_diameter);
    let far_r = far_side(kind, surface_r, setup.insert.height());
    let (r0, r1) = if kind == ThreadKind::External { (far_r, surface_r) } else { (surface_r, far_r) };
    let blank = Region::rect(window.z_min, window.z_max, r0, r1);
    let mut removed = Region::empty();
    let mut out = Vec::with_capacity(passes.len());
    for pass in passes {
        let Some(z) = groove_crossing(pass, z_ref, setup.pitch) else {
            out.push(PassMetrics::default());
            continue;
        };
        let place = |z: f64| {
            let iso = Insert::placement(z, rad(pass.x_at(z)), kind);
            (setup.insert.placed(&iso), iso)
        };
        let (outline, _) = place(z);
        let imprint = Region::from_ring(&outline);
        // The same pass one revolution earlier, one lead back against the feed.
        let prev_z = z - pass.feed_direction() * pass.lead;
        let before = removed.union(&Region::from_ring(&place(prev_z).0));
        let material = blank.difference(&before);
        let chip = imprint.intersection(&material);
        let mut m = PassMetrics { chip_area: chip.area(), ..PassMetrics::default() };
        if m.chip_area > 0.0 {
            let (z0, z1) = if pass.feed_direction() < 0.0 { (z, window.z_max) } else { (window.z_min, z) };
            m.trailing_area = chip.intersection(&Region::rect(z0, z1, r0, r1)).area();
        }
        if m.chip_area > 0.0 {
            let mut closed = outline.clone();
            closed.push(outline[0]);
            let line = Line::through(closed.iter().copied());
            let r_tip = rad(pass.x_at(z));
            for (ext, holes) in chip.polygons() {
                // A sliver (mean thickness 2·area/perimeter under 0.01 µm) is snapping noise where
                // an edge slides along the finished surface, not a chip.
                let perimeter: f64 = (0..ext.len()).map(|k| ext[k].distance(ext[(k + 1) % ext.len()])).sum();
                let area = crate::geometry::boolean::signed_area(&ext).abs();
                if 2.0 * area < 1e-5 * perimeter {
                    m.chip_area -= area;
                    continue;
                }
                for ring in std::iter::once(&ext).chain(holes.iter()) {
                    for k in 0..ring.len() {
                        let (a, b) = (ring[k], ring[(k + 1) % ring.len()]);
                        let mid = Point::new(0.5 * (a.z + b.z), 0.5 * (a.r + b.r));
                        let on_edge = [a, mid, b].iter().all(|q| line.distance(*q) < 1e-6);
                        let len = a.distance(b);
                        if on_edge {
                            let up = (mid.r - r_tip).abs();
                            if up <= setup.insert.tip_zone {
                                m.tip += len;
                            } else if (mid.z - z) * pass.feed_direction() > 0.0 {
                                m.leading += len;
                            } else {
                                m.trailing += len;
                            }
                        } else {
                            let distance = |q: Point| line.distance(q);
                            m.max_chip_thickness = m.max_chip_thickness.max(farthest_on_segment(
                                &distance,
                                a,
                                b,
                                m.max_chip_thickness,
                                false,
                            ));
                        }
                    }
                }
            }
        }
        removed = removed.union(&imprint);
        out.push(m);
    }
    Ok(out)
}

/// The area a disk of `radius` sweeps along straight moves in a plane: one imprint (a capsule)
/// per move, united through the same boolean door as the thread's imprints. Milling uses it with
/// a [`Point`]'s (z, r) carrying (x, y); arcs are given as chords. `tolerance` bounds the
/// capsules' arcs, mm.
pub(crate) fn swept_disk(moves: &[(Point, Point)], radius: f64, tolerance: f64) -> Region {
    use std::f64::consts::{FRAC_PI_2, PI};
    let capsule = |&(a, b): &(Point, Point)| {
        let phi = if a.distance(b) > 1e-12 { (b.r - a.r).atan2(b.z - a.z) } else { 0.0 };
        let arc = |c: Point, s: f64, e: f64| {
            crate::ground::plane::Arc { center: c, radius, start: s, end: e }.tessellate(tolerance)
        };
        let mut ring = arc(b, phi - FRAC_PI_2, phi + FRAC_PI_2);
        ring.extend(arc(a, phi + FRAC_PI_2, phi + PI + FRAC_PI_2));
        Region::from_ring(&ring)
    };
    union_all(moves.iter().map(capsule).collect(), UnionStrategy::BalancedTree)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toolpath::passes::{Infeed, PlanSpec};

    /// The envelope metrics and the polygon-boolean metrics measure the same chips: the areas to
    /// the booleans' snapping (1e-8 mm²), the engaged edge in total and the thickness to 1 nm,
    /// for a partial insert with radial, flank and alternating infeed.
    #[test]
    fn envelope_metrics_agree_with_the_booleans() {
        let m10 = crate::parse_designation("M10x1.5", crate::ParseOptions::default()).expect("M10").thread;
        let insert = Insert::partial_for(&m10, 0.04, 5e-5).expect("insert");
        let setup =
            SweepSetup { kind: ThreadKind::External, insert: &insert, blank_diameter: 9.85, pitch: 1.5 };
        for infeed in [Infeed::Radial, Infeed::Flank { angle: 29.5 }, Infeed::Alternating { angle: 30.0 }] {
            let passes = PlanSpec {
                infeed,
                z_start: 2.0,
                length: 20.0,
                ..PlanSpec::new(ThreadKind::External, 1.5, 9.85, 7.9, 7)
            }
            .generate()
            .expect("plan");
            let chain =
                crate::geometry::envelope::bottom_chain(&insert.outline).expect("a V has a bottom chain");
            let a = envelope_pass_metrics(&setup, &passes, -8.0, &chain);
            let b = boolean_pass_metrics(&setup, &passes, -8.0).expect("booleans");
            for (i, (x, y)) in a.iter().zip(&b).enumerate() {
                let what = format!("{infeed:?} pass {}", i + 1);
                assert!(
                    (x.chip_area - y.chip_area).abs() < 1e-8,
                    "{what}: {} vs {}",
                    x.chip_area,
                    y.chip_area
                );
                assert!((x.trailing_area - y.trailing_area).abs() < 1e-8, "{what}");
                let (ex, ey) = (x.leading + x.trailing + x.tip, y.leading + y.trailing + y.tip);
                assert!((ex - ey).abs() < 1e-6, "{what}: engaged {ex} vs {ey}");
                assert!((x.max_chip_thickness - y.max_chip_thickness).abs() < 1e-6, "{what}");
            }
        }
    }
}
