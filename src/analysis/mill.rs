//! Contour milling: the cutter of a milling program as a disk swept along the feed moves of each
//! Z level, measured against an analytic target curve.
//!
//! The same parts as the lathe path: the program is expanded by [`crate::gcode`] (any dialect,
//! macros included) with its moves recorded; the target's formulas are read by the macro
//! expression engine; distances are parry queries as in [`crate::geometry::measure`]; the picture's swept
//! area is the union of the cutter's imprints through the same boolean door as the thread
//! sweep ([`crate::geometry::sweep`]).
//!
//! **What is measured.** At a level Z, the cutter removes every point within the tool radius r of
//! its centre path. With sd(c) the signed distance from a centre c to the target curve (positive
//! on the side without material), the cutter at c reaches r − sd(c) past the curve into the
//! part: that is the *gouge* when positive (the deepest point the disk reaches into the part,
//! for a target locally smoother than the disk). It is the largest over every centre of every
//! feed move of the level, straight moves and arcs (arcs as chords within 0.01 µm). A target
//! point P is *left over* by dist(P, path) − r when that is positive and P lies within the
//! cutter's reach (dist(P, path) ≤ 2r): material outside the target that the cutter passed
//! without taking.
//!
//! The curve is evaluated exactly: a polyline of samples only finds the basin of the nearest
//! point, which Newton's method then places on the curve itself, so the gouge is right to far
//! better than 0.1 µm.
//!
//! **Inside a move.** Every move end is measured; a move's inside only where a bound from its
//! ends could beat the worst gouge found by more than 0.01 µm. The bounds (see `inside_bound`):
//! the distance is 1-Lipschitz; d² − |x|² is concave for the distance to any set; and, where both
//! ends' nearest points lie on one smooth stretch of the target and the move is short against the
//! distance, the cubic through the ends' values and slopes, within 1 nm. A path of chords that
//! follows the offset exactly (every chord gouging by its sag) is then refined once per level, not
//! once per chord: a level of 20 000 chords went from 25.6 s to 1.3 s.
//!
//! **Levels.** A feed move belongs to the level of its deeper end (a plunge is a point there).
//! Each level is checked against the target at its own Z, the section its tool bottom cuts: the
//! tool's flank also passes the sections above, which is the same check for targets that do not
//! grow upward (prisms such as a cam, domes). Levels at or above the target's top (its `z` range,
//! else Z0) cut air and are left out.

use crate::analysis::check::Verdict;
use crate::gcode::expr::{parse_all, Arithmetic, BinOp, Compiled, Env, Expr, Syntax, Value, VarKey, VarRef};
use crate::gcode::{Dialect, Move, ReadOptions};
use crate::geometry::index::{PathSegments, Polyline};
use crate::geometry::measure::golden_min;
use crate::ground::bounds::{
    MAX_FORMULA_TERMS, MAX_FORMULA_WORK, MAX_MILL_LEVELS, MAX_MILL_SEGMENTS, MAX_TOOL_DIAMETER,
};
use crate::ground::plane::Point;
use crate::Error;
use serde::{Deserialize, Serialize};

/// Arcs become chords no farther than this from the arc, mm (0.01 µm).
const ARC_TOLERANCE: f64 = 1e-5;
/// Every how many move ends the target's polyline is searched for the signed distance before
/// anything else (the ends between are bounded from these).
const ANCHOR: usize = 8;

/// Moves either side of the last answer a target sample is first tried against (the leftover
/// scan): consecutive samples are reached by neighbouring moves.
const PATH_WINDOW: usize = 4;

/// Spacing of the target's sample polyline, mm: it only finds the nearest point's basin.
const SAMPLE_SPACING: f64 = 0.05;
/// A limit met to within this passes, mm (0.1 µm, the resolution the gouge is computed to).
const RESOLUTION: f64 = 1e-7;

/// Which side of the closed target curve is the part.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Material {
    /// The part is inside the curve (a cam, a boss): the cutter works outside it.
    Inside,
    /// The part is outside the curve (a pocket): the cutter works inside it.
    Outside,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTarget {
    x: String,
    y: String,
    t: [f64; 2],
    material: Material,
    z: Option<[f64; 2]>,
}

/// A target curve: x(t, z), y(t, z) in mm, t in degrees over a range, z the level.
///
/// ```
/// use threadcheck::Target;
/// let cam = Target::from_toml(r#"
///     x = "20*(1+cos(t))*cos(t)"
///     y = "20*(1+cos(t))*sin(t)"
///     t = [0, 360]
///     material = "inside"
/// "#, "cam.toml")?;
/// let p = cam.point(90.0, -1.0)?;
/// assert!((p.z - 0.0).abs() < 1e-12 && (p.r - 20.0).abs() < 1e-12); // (x, y) = (0, 20)
/// # Ok::<(), threadcheck::Error>(())
/// ```
#[derive(Clone, Debug, Serialize)]
pub struct Target {
    /// The x formula as written.
    pub x: String,
    /// The y formula as written.
    pub y: String,
    /// The parameter range, degrees.
    pub t: [f64; 2],
    /// The part's Z range (bottom, top), if given; else its top is Z0.
    pub z: Option<[f64; 2]>,
    /// Which side is the part.
    pub material: Material,
    #[serde(skip)]
    pub(crate) source: String,
    #[serde(skip)]
    ex: Expr,
    #[serde(skip)]
    ey: Expr,
    #[serde(skip)]
    uses_z: bool,
}

/// The environment of a target formula: `t` and `z`, nothing else.
struct TZ {
    t: f64,
    z: f64,
}

impl Env for TZ {
    fn get(&mut self, key: &VarKey) -> Result<Value, String> {
        match key {
            VarKey::Named(n) => self.get_named(n),
            VarKey::Num(n) => Err(format!("#{n}: a target formula reads only t and z")),
        }
    }

    fn exists(&mut self, _key: &VarKey) -> bool {
        false
    }

    fn get_named(&mut self, name: &str) -> Result<Value, String> {
        match name {
            "t" => Ok(Some(self.t)),
            "z" => Ok(Some(self.z)),
            _ => Err(format!(
                "unknown name '{name}': a target formula reads t (degrees) and z (the level, mm)"
            )),
        }
    }
}

/// `e` at level `z`: z replaced by its value and every subexpression without t evaluated once,
/// so that a curve's many evaluations pay only for what depends on t.
fn fold(e: &Expr, z: f64) -> Expr {
    let constant = |e: Expr| -> Expr {
        let mut env = TZ { t: f64::NAN, z };
        match crate::gcode::expr::eval(&e, &mut env, 0) {
            Ok(Some(v)) if v.is_finite() => Expr::Num(v),
            _ => e,
        }
    };
    match e {
        Expr::Var(VarRef::Named(n)) if n == "z" => Expr::Num(z),
        Expr::Num(_) | Expr::Var(_) => e.clone(),
        Expr::Neg(a) => {
            let a = fold(a, z);
            match a {
                Expr::Num(v) => Expr::Num(-v),
                a => Expr::Neg(Box::new(a)),
            }
        }
        Expr::Chain(first, rest) => {
            let first = fold(first, z);
            let rest: Vec<(BinOp, Expr)> = rest.iter().map(|(op, e)| (*op, fold(e, z))).collect();
            let all = matches!(first, Expr::Num(_)) && rest.iter().all(|(_, e)| matches!(e, Expr::Num(_)));
            let f = Expr::Chain(Box::new(first), rest);
            if all {
                constant(f)
            } else {
                f
            }
        }
        Expr::Call(func, args) => {
            let args: Vec<Expr> = args.iter().map(|a| fold(a, z)).collect();
            let all = args.iter().all(|a| matches!(a, Expr::Num(_)));
            let f = Expr::Call(*func, args);
            if all {
                constant(f)
            } else {
                f
            }
        }
    }
}

/// How many numbers, variables and functions a formula holds (its evaluation's cost).
fn terms(e: &Expr) -> usize {
    match e {
        Expr::Num(_) | Expr::Var(_) => 1,
        Expr::Neg(a) => terms(a),
        Expr::Chain(first, rest) => terms(first) + rest.iter().map(|(_, e)| terms(e)).sum::<usize>(),
        Expr::Call(_, args) => 1 + args.iter().map(terms).sum::<usize>(),
    }
}

fn names_z(e: &Expr) -> bool {
    match e {
        Expr::Num(_) => false,
        Expr::Var(VarRef::Named(n)) => n == "z",
        Expr::Var(_) => false,
        Expr::Neg(a) => names_z(a),
        Expr::Chain(first, rest) => names_z(first) || rest.iter().any(|(_, e)| names_z(e)),
        Expr::Call(_, args) => args.iter().any(names_z),
    }
}

impl Target {
    /// Reads a target from TOML text; `source` names it in messages.
    pub fn from_toml(text: &str, source: &str) -> Result<Target, Error> {
        let ferr = |m: String| Error::File { file: source.to_string(), message: m };
        let raw: RawTarget =
            toml::from_str(text).map_err(|e| crate::ground::error::toml_error(&e, text, source))?;
        let [t0, t1] = raw.t;
        if !(t0.is_finite() && t1.is_finite() && t0 < t1) {
            return Err(ferr(format!("t = [{t0}, {t1}]: the range must be finite and increasing")));
        }
        if let Some([z0, z1]) = raw.z {
            if !(z0.is_finite() && z1.is_finite() && z0 < z1) {
                return Err(ferr(format!("z = [{z0}, {z1}]: the range must be finite and increasing")));
            }
        }
        let parse = |what: &str, s: &str| {
            let e = parse_all(s.trim(), Syntax::Formula)
                .map_err(|(i, m)| ferr(format!("{what} = \"{s}\": column {}: {m}", i + 1)))?;
            let n = terms(&e);
            if n > MAX_FORMULA_TERMS {
                return Err(ferr(format!(
                    "{what}: the formula has {n} terms (numbers, variables and functions), more than the {MAX_FORMULA_TERMS} a target formula may have"
                )));
            }
            Ok(e)
        };
        let (ex, ey) = (parse("x", &raw.x)?, parse("y", &raw.y)?);
        let uses_z = names_z(&ex) || names_z(&ey);
        let target = Target {
            x: raw.x,
            y: raw.y,
            t: raw.t,
            z: raw.z,
            material: raw.material,
            source: source.into(),
            ex,
            ey,
            uses_z,
        };
        // One evaluation names an unknown word or a bad function now, not halfway through a run.
        let z = raw.z.map_or(0.0, |z| z[0]);
        target.point(t0, z).map_err(|e| ferr(e.to_string()))?;
        Ok(target)
    }

    /// Reads a target file.
    pub fn read(path: &std::path::Path) -> Result<Target, Error> {
        let shown = path.display().to_string();
        let text = crate::ground::input::read_text_bounded(
            path,
            crate::ground::bounds::MAX_DATA_FILE_BYTES,
            "a target file",
        )?;
        Target::from_toml(&text, &shown)
    }

    /// The point at parameter `t` (degrees) of level `z`, as (x, y) in a [`Point`]'s (z, r).
    pub fn point(&self, t: f64, z: f64) -> Result<Point, Error> {
        eval_xy(&self.ex, &self.ey, t, z)
    }

    /// The part's top: levels at or above it cut air.
    pub fn top(&self) -> f64 {
        self.z.map_or(0.0, |z| z[1])
    }
}

/// A target's two formulas at one level, compiled where they can be: the point at t, as
/// [`eval_xy`] gives it (which answers wherever the compiled form cannot, with its error).
/// The target formulas' evaluations of one run, counted in terms against
/// [`MAX_FORMULA_WORK`]: a long formula on a program of many levels stops at the budget
/// instead of running for minutes (a 1 000-term formula on the dome's 799 levels took 28 s).
struct Meter(std::sync::atomic::AtomicU64);

impl Meter {
    fn new() -> Meter {
        Meter(std::sync::atomic::AtomicU64::new(0))
    }

    /// Counts `terms` more; false once the budget is spent.
    fn spend(&self, terms: u64) -> bool {
        use std::sync::atomic::Ordering;
        self.0.fetch_add(terms, Ordering::Relaxed).saturating_add(terms) <= MAX_FORMULA_WORK
    }

    fn over(&self) -> bool {
        self.0.load(std::sync::atomic::Ordering::Relaxed) > MAX_FORMULA_WORK
    }

    fn error(&self) -> Error {
        Error::Input(format!(
            "the target's formulas need more than {} term evaluations over this program's levels (about a second): shorten the formulas or check fewer levels",
            crate::ground::fmt::fmt_shown(MAX_FORMULA_WORK as f64)
        ))
    }
}

struct Formulas {
    ex: Expr,
    ey: Expr,
    compiled: Option<(Compiled, Compiled)>,
    /// The terms one evaluation of both formulas computes.
    cost: u64,
}

impl Formulas {
    fn new(ex: Expr, ey: Expr) -> Formulas {
        let c = |e: &Expr| Compiled::new(e, &["t", "z"], Arithmetic::Exact);
        let compiled = c(&ex).zip(c(&ey));
        let cost = (terms(&ex) + terms(&ey)) as u64;
        Formulas { ex, ey, compiled, cost }
    }

    fn at(&self, t: f64, z: f64) -> Result<Point, Error> {
        if let Some((cx, cy)) = &self.compiled {
            if let (Some(x), Some(y)) = (cx.run(&[t, z]), cy.run(&[t, z])) {
                return Ok(Point::new(x, y));
            }
        }
        eval_xy(&self.ex, &self.ey, t, z)
    }
}

fn eval_xy(ex: &Expr, ey: &Expr, t: f64, z: f64) -> Result<Point, Error> {
    {
        let mut env = TZ { t, z };
        let mut ev = |e: &Expr, what: &str| match crate::gcode::expr::eval(e, &mut env, 0) {
            Ok(v) => {
                let v = v.unwrap_or(0.0);
                if v.is_finite() {
                    Ok(v)
                } else {
                    Err(Error::Input(format!("target {what} at t = {t}, z = {z} is not a finite number")))
                }
            }
            Err(m) => Err(Error::Input(format!("target {what} at t = {t}, z = {z}: {m}"))),
        };
        Ok(Point::new(ev(ex, "x")?, ev(ey, "y")?))
    }
}

/// The target at one level: samples, their polyline, and the exact curve behind them.
struct Curve<'a> {
    target: &'a Target,
    meter: &'a Meter,
    z: f64,
    /// The formulas folded at this level.
    formulas: Formulas,
    t: Vec<f64>,
    p: Vec<Point>,
    poly: Polyline,
    ccw: bool,
    /// How far the sample polyline may stray from the exact curve, mm: twice the largest gap
    /// at the segments' middle parameters (a signed distance to the polyline is within this of
    /// the one to the curve).
    sag: f64,
}

/// The nearest point of the curve to a point.
#[derive(Clone, Copy, Debug)]
struct Near {
    t: f64,
    /// Signed distance: positive on the side without material.
    sd: f64,
    /// The nearest curve point itself.
    foot: Point,
}

impl<'a> Curve<'a> {
    /// Samples the target at level `z`; `None` when the curve has no extent there (a dome's apex).
    fn new(target: &'a Target, z: f64, meter: &'a Meter) -> Result<Option<Curve<'a>>, Error> {
        let [t0, t1] = target.t;
        let formulas = Formulas::new(fold(&target.ex, z), fold(&target.ey, z));
        let sample = |n: usize| -> Result<(Vec<f64>, Vec<Point>), Error> {
            if !meter.spend(formulas.cost * (2 * n as u64 + 2)) {
                return Err(meter.error());
            }
            let t: Vec<f64> = (0..=n).map(|i| t0 + (t1 - t0) * i as f64 / n as f64).collect();
            let p = t.iter().map(|&t| formulas.at(t, z)).collect::<Result<Vec<_>, _>>()?;
            Ok((t, p))
        };
        let length = |p: &[Point]| p.windows(2).map(|w| w[0].distance(w[1])).sum::<f64>();
        let (t_coarse, coarse) = sample(1024)?;
        let len = length(&coarse);
        if !(len > 1e-6) {
            return Ok(None);
        }
        if coarse[0].distance(coarse[coarse.len() - 1]) > 1e-6 * len.max(1.0) {
            return Err(Error::Input(format!(
                "{}: the target is not closed at Z{z}: t = {t0} gives ({:.4}, {:.4}), t = {t1} gives ({:.4}, {:.4})",
                target.source,
                coarse[0].z,
                coarse[0].r,
                coarse[coarse.len() - 1].z,
                coarse[coarse.len() - 1].r
            )));
        }
        let n = ((len / SAMPLE_SPACING).ceil() as usize).clamp(1024, 100_000);
        let (t, p) = if n == 1024 { (t_coarse, coarse) } else { sample(n)? };
        let ccw = crate::geometry::boolean::signed_area(&p[..p.len() - 1]) > 0.0;
        let poly = Polyline::through(&p);
        let mut sag = 0.0f64;
        for (w, tw) in p.windows(2).zip(t.windows(2)) {
            if let Ok(m) = formulas.at(0.5 * (tw[0] + tw[1]), z) {
                let (d, ab) = ((w[1].z - w[0].z, w[1].r - w[0].r), w[0].distance(w[1]));
                let gap = if ab > 0.0 {
                    ((m.z - w[0].z) * d.1 - (m.r - w[0].r) * d.0).abs() / ab
                } else {
                    m.distance(w[0])
                };
                sag = sag.max(gap);
            }
        }
        Ok(Some(Curve { target, meter, z, formulas, t, p, poly, ccw, sag: 2.0 * sag + 1e-9 }))
    }

    fn at(&self, t: f64) -> Point {
        // Every t in range evaluated once already when sampling; a failure here is a formula
        // that fails between samples, which the sampled neighbours stand in for. Past the
        // work budget the samples stand in too, and the run ends in the meter's error.
        let sampled = || {
            let i = self.t.partition_point(|&s| s < t).min(self.p.len() - 1);
            self.p[i]
        };
        if !self.meter.spend(self.formulas.cost) {
            return sampled();
        }
        self.formulas.at(t, self.z).unwrap_or_else(|_| sampled())
    }

    /// The nearest curve point to `c`: the sample polyline's nearest segment (searched first
    /// around segment `guess`), then Newton's method on the exact curve within the neighbouring
    /// samples.
    fn nearest(&self, c: Point, guess: usize) -> Near {
        let projection = self.poly.project(c, guess).unwrap_or((self.p[0], 0));
        self.nearest_from(c, projection)
    }

    /// [`Curve::nearest`] from the polyline's nearest point `q` to `c`, on segment `i`.
    fn nearest_from(&self, c: Point, (q, i): (Point, usize)) -> Near {
        let n = self.t.len() - 1;
        let (a, b) = (self.t[i.saturating_sub(1)], self.t[(i + 2).min(n)]);
        let (pi, pj) = (self.p[i], self.p[(i + 1).min(n)]);
        let u = {
            let l = pi.distance(pj);
            if l > 0.0 {
                (pi.distance(q) / l).clamp(0.0, 1.0)
            } else {
                0.0
            }
        };
        let t_guess = self.t[i] + u * (self.t[(i + 1).min(n)] - self.t[i]);
        let phi_of = |p: Point| (p.z - c.z).powi(2) + (p.r - c.r).powi(2);
        let h = 1e-3 * (b - a).max(1e-12) / 3.0;
        let mut t = t_guess;
        let mut ok = false;
        // The last points either side of t, for the tangent.
        let mut side: Option<(Point, Point)> = None;
        for _ in 0..12 {
            let (p0, pp, pm) = (self.at(t), self.at((t + h).min(b)), self.at((t - h).max(a)));
            side = Some((pp, pm));
            let (f0, fp, fm) = (phi_of(p0), phi_of(pp), phi_of(pm));
            let d1 = (fp - fm) / (2.0 * h);
            let d2 = (fp - 2.0 * f0 + fm) / (h * h);
            if !(d2 > 0.0) {
                break;
            }
            let step = d1 / d2;
            let next = (t - step).clamp(a, b);
            // Done when the step moves the curve point by under 1 pm (the distance then changes
            // by far less): a step measured in t would meet the rounding noise of the finite
            // differences on a large curve first.
            let speed = pp.distance(pm) / ((t + h).min(b) - (t - h).max(a));
            let done = (next - t).abs() * speed <= 1e-9 || (next - t).abs() <= 1e-12 * (b - a);
            t = next;
            if done {
                ok = true;
                break;
            }
        }
        if !ok {
            t = golden_min(&|t| phi_of(self.at(t)), a, b, 80).0;
            side = None;
        }
        let p = self.at(t);
        let dist = p.distance(c);
        let (p1, p0) = side.unwrap_or_else(|| (self.at((t + h).min(b)), self.at((t - h).max(a))));
        let tangent = Point::new(p1.z - p0.z, p1.r - p0.r);
        let outside = self.outside(c, p, tangent, dist);
        let free = match self.target.material {
            Material::Inside => outside,
            Material::Outside => !outside,
        };
        Near { t, sd: if free { dist } else { -dist }, foot: p }
    }

    /// The signed distance from `c` to the sample polyline (positive on the side without
    /// material): within [`Curve::sag`] of the exact one, without evaluating the formulas; and
    /// the nearest segment's index (searched first around `guess`).
    fn approx_sd(&self, c: Point, guess: usize) -> (f64, (Point, usize)) {
        let Some((q, i)) = self.poly.project(c, guess) else { return (f64::INFINITY, (self.p[0], 0)) };
        let n = self.p.len() - 1;
        let (a, b) = (self.p[i], self.p[(i + 1).min(n)]);
        let dist = q.distance(c);
        let outside = self.outside(c, q, Point::new(b.z - a.z, b.r - a.r), dist);
        let free = match self.target.material {
            Material::Inside => outside,
            Material::Outside => !outside,
        };
        (if free { dist } else { -dist }, (q, i))
    }

    /// Whether `c` lies outside the closed curve, from the normal at its nearest point `p`, or
    /// from the sample polygon where the normal does not decide (a cusp, a corner).
    fn outside(&self, c: Point, p: Point, tangent: Point, dist: f64) -> bool {
        let tl = (tangent.z * tangent.z + tangent.r * tangent.r).sqrt();
        if dist > 0.0 && tl > 0.0 {
            let sign = if self.ccw { 1.0 } else { -1.0 };
            let dot = sign * ((c.z - p.z) * tangent.r - (c.r - p.r) * tangent.z) / (tl * dist);
            if dot.abs() > 0.5 {
                return dot > 0.0;
            }
        }
        !crate::geometry::boolean::ring_contains(&self.p, c)
    }

    /// The arc length of the samples up to sample `i`, for spacing along the curve.
    fn spacing(&self) -> f64 {
        self.p.windows(2).map(|w| w[0].distance(w[1])).sum::<f64>() / (self.p.len() - 1) as f64
    }
}

/// A place on the part: the tool centre (gouge) or the target point (leftover), the curve
/// parameter of the target point, the level and the program line.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Spot {
    /// mm.
    pub x: f64,
    /// mm.
    pub y: f64,
    /// The level, mm.
    pub z: f64,
    /// The target's parameter at the nearest curve point, degrees.
    pub t: f64,
    /// The program line of the move (0 for a leftover, which no one move made).
    pub line: usize,
}

/// One level's figures.
#[derive(Clone, Debug, Serialize)]
pub struct LevelReport {
    /// Z of the level, mm.
    pub z: f64,
    /// Feed moves at this level.
    pub moves: usize,
    /// Largest gouge, mm (0: none).
    pub gouge: f64,
    /// Where (the tool centre).
    pub gouge_at: Option<Spot>,
    /// Largest leftover within the cutter's reach, mm (0: none).
    pub leftover: f64,
    /// Where (the target point).
    pub leftover_at: Option<Spot>,
}

/// The deviation at one tool centre of the worst level: sd − r, negative where the cutter
/// gouges, positive where it stays clear of the target.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct ProfilePoint {
    /// Tool centre x, mm.
    pub x: f64,
    /// Tool centre y, mm.
    pub y: f64,
    /// The nearest target point's parameter, degrees.
    pub t: f64,
    /// sd − r, mm.
    pub deviation: f64,
}

/// What the picture of the worst level needs.
#[derive(Clone, Debug)]
pub struct MillPicture {
    /// The level.
    pub z: f64,
    /// The target's samples at that level.
    pub target: Vec<Point>,
    /// dist(P, path) − r at each sample, mm.
    pub deviation: Vec<f64>,
    /// The tool centre path's feed moves (arcs as chords).
    pub path: Vec<(Point, Point)>,
    /// The area the cutter swept (the union of its imprints).
    pub swept: Vec<(Vec<Point>, Vec<Vec<Point>>)>,
    /// The worst gouge's place, if any.
    pub gouge_at: Option<Spot>,
}

/// `threadcheck mill`: the whole report (docs/json.md).
#[derive(Clone, Debug, Serialize)]
pub struct MillReport {
    /// The program's name.
    pub program: String,
    /// Its dialect.
    pub dialect: Dialect,
    /// Cutter diameter, mm.
    pub tool_diameter: f64,
    /// Allowed gouge and leftover, mm.
    pub tolerance: f64,
    /// The target.
    pub target: Target,
    /// Pass when the gouge and the leftover are within the tolerance.
    pub verdict: Verdict,
    /// The gouge is beyond the tolerance.
    #[serde(skip)]
    pub gouge_out: bool,
    /// The leftover is beyond the tolerance.
    #[serde(skip)]
    pub leftover_out: bool,
    /// Largest gouge over all levels, mm.
    pub gouge_max: f64,
    /// Where.
    pub gouge_at: Option<Spot>,
    /// Largest leftover over all levels, mm.
    pub leftover_max: f64,
    /// Where.
    pub leftover_at: Option<Spot>,
    /// Every level that cuts, top down.
    pub levels: Vec<LevelReport>,
    /// The level the profile and the picture show: the worst gouge's, else the worst
    /// leftover's.
    pub worst_level: Option<f64>,
    /// The deviation at each tool centre (move end) of that level.
    pub profile: Vec<ProfilePoint>,
    /// Warnings from the program and the stated assumptions.
    pub notes: Vec<crate::ground::note::Note>,
    /// The picture's data.
    #[serde(skip)]
    pub picture: Option<MillPicture>,
}

/// What to check.
#[derive(Clone, Debug)]
pub struct MillSpec {
    /// The program's text and its name for messages.
    pub program: (String, String),
    /// Its dialect.
    pub dialect: Dialect,
    /// Run the blocks in N order (a listing whose page break moved blocks).
    pub n_order: bool,
    /// Cutter diameter, mm.
    pub tool_diameter: f64,
    /// The target.
    pub target: Target,
    /// Allowed gouge and leftover, mm.
    pub tolerance: f64,
    /// How the program is read: its machine, units, G-code system, main program, subprograms'
    /// folders (its toolpath and N order are this check's own).
    pub reading: ReadOptions,
}

/// One level's moves: (from, to, line), centres in the XY plane.
#[derive(Clone)]
struct LevelMoves {
    z: f64,
    segs: Vec<(Point, Point, usize)>,
}

/// The level of a feed move: its deeper end's Z, to 1 nm.
fn level_key(m: &Move) -> f64 {
    (m.from[2].min(m.to[2]) * 1e6).round() / 1e6
}

/// A feed move's points in the XY plane: its ends, an arc as chords within [`ARC_TOLERANCE`].
fn chords(m: &Move) -> Vec<Point> {
    let (a, b) = (Point::new(m.from[0], m.from[1]), Point::new(m.to[0], m.to[1]));
    match m.arc {
        Some((c, dir)) => {
            let c = Point::new(c[0], c[1]);
            let r = c.distance(a);
            let s = (a.r - c.r).atan2(a.z - c.z);
            let mut e = (b.r - c.r).atan2(b.z - c.z);
            if dir > 0.0 {
                while e <= s {
                    e += std::f64::consts::TAU;
                }
            } else {
                while e >= s {
                    e -= std::f64::consts::TAU;
                }
            }
            let mut pts = crate::ground::plane::Arc { center: c, radius: r, start: s, end: e }
                .tessellate(ARC_TOLERANCE);
            if let Some(last) = pts.last_mut() {
                *last = b;
            }
            pts
        }
        None => vec![a, b],
    }
}

/// One level as the moves stream in: its moves so far, shared with a measurement under way,
/// and how many times moves joined it after it was sent to be measured.
struct Level {
    moves: std::sync::Arc<LevelMoves>,
    /// Bumped when a move joins the level: a measurement of an older generation is stale.
    generation: u32,
    /// The generation last sent to be measured.
    sent: Option<u32>,
}

/// Groups the feed moves by level (the deeper end's Z, to 1 nm), arcs as chords, as they
/// stream in. A level is ready to measure once the toolpath has moved on through two other
/// levels since its last move (a finished level's moves rarely come back; when they do, the
/// level is measured again with all of them).
struct Assembler {
    levels: Vec<Level>,
    /// Level by key, found in constant time (a linear search made many levels quadratic).
    index: std::collections::HashMap<u64, usize>,
    /// Levels not yet sent, in order of their last move.
    open: std::collections::VecDeque<usize>,
    current: Option<usize>,
    segments: usize,
    /// The first bound a move broke (too many pieces): the rest is only counted, not kept.
    overflow: Option<Error>,
}

impl Assembler {
    fn new() -> Assembler {
        Assembler {
            levels: Vec::new(),
            index: std::collections::HashMap::new(),
            open: std::collections::VecDeque::new(),
            current: None,
            segments: 0,
            overflow: None,
        }
    }

    /// Whether the toolpath broke a bound: nothing more is kept or measured.
    fn broken(&self) -> bool {
        self.overflow.is_some() || self.index.len() > MAX_MILL_LEVELS
    }

    /// The bound the toolpath broke, the number of levels first (as when it was read whole).
    fn check(self, name: &str) -> Result<Assembler, Error> {
        if self.index.len() > MAX_MILL_LEVELS {
            return Err(Error::Input(format!(
                "{name}: {} Z levels, more than the {MAX_MILL_LEVELS} threadcheck checks",
                self.index.len()
            )));
        }
        match self.overflow {
            Some(e) => Err(e),
            None => Ok(self),
        }
    }

    /// Adds a move; the levels it makes ready go to `ready`. Past a bound, moves are only
    /// counted by level (the error names how many there are).
    fn push(&mut self, m: &Move, name: &str, ready: &mut Vec<usize>) {
        if m.rapid {
            return;
        }
        let key = level_key(m);
        let fresh = self.levels.len();
        let n = *self.index.entry(key.to_bits()).or_insert(fresh);
        if self.broken() {
            return;
        }
        if n == fresh {
            self.levels.push(Level {
                moves: std::sync::Arc::new(LevelMoves { z: key, segs: Vec::new() }),
                generation: 0,
                sent: None,
            });
        }
        let pts = chords(m);
        self.segments += pts.len() - 1;
        if self.segments > MAX_MILL_SEGMENTS {
            self.overflow = Some(Error::Input(format!(
                "{name}:{}: more than {MAX_MILL_SEGMENTS} straight pieces to check (arcs count as chords within 0.01 µm)",
                m.line
            )));
            // What was kept is no longer needed.
            self.levels.clear();
            self.open.clear();
            return;
        }
        let level = &mut self.levels[n];
        level.generation += 1;
        let lm = std::sync::Arc::make_mut(&mut level.moves);
        for w in pts.windows(2) {
            lm.segs.push((w[0], w[1], m.line));
        }
        if self.current != Some(n) {
            self.current = Some(n);
            if let Some(k) = self.open.iter().position(|&o| o == n) {
                self.open.remove(k);
            }
            self.open.push_back(n);
            while self.open.len() > 2 {
                ready.extend(self.open.pop_front());
            }
        }
    }

    /// Every level not yet measured with all its moves.
    fn rest(&mut self) -> Vec<usize> {
        self.open.clear();
        if self.broken() {
            return Vec::new();
        }
        (0..self.levels.len()).filter(|&n| self.levels[n].sent != Some(self.levels[n].generation)).collect()
    }
}

/// A move's inside is refined only when its bound beats the worst gouge found by more than
/// this, mm (0.01 µm, a tenth of the resolution the gouge is reported to).
const GOUGE_SLACK: f64 = 1e-8;
/// The largest error allowed to the cubic model of a move's inside, mm.
const MODEL_ERROR: f64 = 1e-9;

/// Golden-section steps that narrow a move of `length` mm to 1 nm.
fn golden_iterations(length: f64) -> usize {
    let steps = (length.max(1e-9) / 1e-6).ln() / 1.618_033_988_75_f64.ln();
    (steps.ceil() as usize).clamp(8, 60)
}

/// An upper bound on the gouge r − sd inside the straight move a → b from its ends' nearest
/// points, and where on the move (0…1) the model puts the largest, when it applies.
///
/// Three bounds, the least taken:
/// - sd is 1-Lipschitz: the inside beats the ends' mean by at most half the length;
/// - d² − |x|² is concave for the distance d to any set, so along the move
///   d(λ)² ≥ (1−λ)·d_a² + λ·d_b² − λ(1−λ)·L² (while that stays positive the move keeps to one
///   side of the target);
/// - the model: where both ends' nearest points lie on one smooth stretch of the target (the
///   normals turn by α ≤ 0.05 rad, the move is no longer than the distance, the nearest point
///   moves by at most 4L), sd along the move is the cubic through the ends' values and slopes
///   (the slope is −(c − foot)·u / sd), within 3α³L/384 (the fourth derivative of a distance to
///   a curve is about 3/ρ³ where α = L/ρ); allowed only when that is under [`MODEL_ERROR`].
///   The move is then measured where the cubic peaks.
fn inside_bound(a: Point, b: Point, na: &Near, nb: &Near, r: f64) -> (f64, Option<f64>) {
    let l = a.distance(b);
    let (ga, gb) = (r - na.sd, r - nb.sd);
    let mut bound = 0.5 * (ga + gb + l);
    if l <= 0.0 {
        return (ga.max(gb), None);
    }
    if na.sd > 0.0 && nb.sd > 0.0 {
        let (da2, db2, l2) = (na.sd * na.sd, nb.sd * nb.sd, l * l);
        let lam = ((da2 - db2 + l2) / (2.0 * l2)).clamp(0.0, 1.0);
        let q = (1.0 - lam) * da2 + lam * db2 - lam * (1.0 - lam) * l2;
        if q > 0.0 {
            bound = bound.min(r - q.sqrt());
        }
    }
    let same_side = (na.sd > 1e-9 && nb.sd > 1e-9) || (na.sd < -1e-9 && nb.sd < -1e-9);
    if !same_side || l > na.sd.abs().min(nb.sd.abs()) || na.foot.distance(nb.foot) > 4.0 * l + 1e-9 {
        return (bound, None);
    }
    let (u_z, u_r) = ((b.z - a.z) / l, (b.r - a.r) / l);
    let (va, vb) = ((a.z - na.foot.z, a.r - na.foot.r), (b.z - nb.foot.z, b.r - nb.foot.r));
    let (la, lb) = (va.0.hypot(va.1), vb.0.hypot(vb.1));
    let cos = ((va.0 * vb.0 + va.1 * vb.1) / (la * lb)).clamp(-1.0, 1.0);
    let alpha = cos.acos();
    if !(alpha <= 0.05 && 3.0 * alpha.powi(3) * l / 384.0 <= MODEL_ERROR) {
        return (bound, None);
    }
    // g = r − sd: values and slopes per unit s = x / L.
    let m0 = -(va.0 * u_z + va.1 * u_r) / na.sd * l;
    let m1 = -(vb.0 * u_z + vb.1 * u_r) / nb.sd * l;
    let (c3, c2, c1, c0) = (2.0 * (ga - gb) + m0 + m1, 3.0 * (gb - ga) - 2.0 * m0 - m1, m0, ga);
    let cubic = |s: f64| ((c3 * s + c2) * s + c1) * s + c0;
    let mut peak = if ga >= gb { (ga, 0.0) } else { (gb, 1.0) };
    // Roots of 3·c3·s² + 2·c2·s + c1 in (0, 1).
    let (qa, qb, qc) = (3.0 * c3, 2.0 * c2, c1);
    let roots: [Option<f64>; 2] = if qa.abs() < 1e-300 {
        [(qb != 0.0).then(|| -qc / qb), None]
    } else {
        let disc = qb * qb - 4.0 * qa * qc;
        if disc < 0.0 {
            [None, None]
        } else {
            let sq = disc.sqrt();
            [Some((-qb + sq) / (2.0 * qa)), Some((-qb - sq) / (2.0 * qa))]
        }
    };
    for s in roots.into_iter().flatten() {
        if s > 0.0 && s < 1.0 && cubic(s) > peak.0 {
            peak = (cubic(s), s);
        }
    }
    (bound.min(peak.0 + MODEL_ERROR), Some(peak.1))
}

/// One level measured: its report, the profile at its move ends, and the deviation along the
/// target for the picture.
struct Measured {
    report: LevelReport,
    profile: Vec<ProfilePoint>,
    deviation: Vec<f64>,
    samples: Vec<Point>,
}

/// Measures one level. With `detail` every move end is measured on the exact curve (the
/// profile of the level the report shows); without, the ends are first placed against the
/// sample polyline and measured exactly only where that could change the level's worst gouge.
fn measure_level(curve: &Curve<'_>, lm: &LevelMoves, r: f64, detail: bool) -> Measured {
    let z = lm.z;
    // The move ends, each once.
    let mut ends: Vec<Point> = Vec::with_capacity(lm.segs.len() + 1);
    let mut seg_ends: Vec<(usize, usize)> = Vec::with_capacity(lm.segs.len());
    for &(a, b, _) in &lm.segs {
        let ia = match ends.last() {
            Some(p) if *p == a => ends.len() - 1,
            _ => {
                ends.push(a);
                ends.len() - 1
            }
        };
        ends.push(b);
        seg_ends.push((ia, ends.len() - 1));
    }
    // The polyline's signed distance and nearest point of every ANCHOR-th end (and the last),
    // each search starting from the last answer (the path follows the curve). Any other end's
    // signed distance is at least its anchor's less the distance between them (a distance
    // moves no faster than the point), and is computed only when that bound cannot rule the end
    // out.
    let mut approx: Vec<Option<(f64, (Point, usize))>> = vec![None; ends.len()];
    let mut guess = 0usize;
    for i in (0..ends.len()).step_by(ANCHOR).chain(ends.len().checked_sub(1)) {
        if approx[i].is_none() {
            let a = curve.approx_sd(ends[i], guess);
            guess = a.1 .1;
            approx[i] = Some(a);
        }
    }
    let anchor = |i: usize| -> usize {
        let lo = i / ANCHOR * ANCHOR;
        let hi = (lo + ANCHOR).min(ends.len() - 1);
        if i - lo <= hi.saturating_sub(i) {
            lo
        } else {
            hi
        }
    };
    let sd_low: Vec<f64> = (0..ends.len())
        .map(|i| {
            let a = anchor(i);
            approx[a].map_or(f64::NEG_INFINITY, |x| x.0) - ends[i].distance(ends[a])
        })
        .collect();
    let approx_of = |i: usize, approx: &mut Vec<Option<(f64, (Point, usize))>>| -> (f64, (Point, usize)) {
        if approx[i].is_none() {
            let guess = approx[anchor(i)].map_or(0, |x| x.1 .1);
            approx[i] = Some(curve.approx_sd(ends[i], guess));
        }
        approx[i].unwrap_or((f64::INFINITY, (ends[i], 0)))
    };
    let mut exact: Vec<Option<Near>> = vec![None; ends.len()];
    let near =
        |i: usize, exact: &mut Vec<Option<Near>>, approx: &mut Vec<Option<(f64, (Point, usize))>>| -> Near {
            if let Some(n) = exact[i] {
                return n;
            }
            // The polyline's nearest point is the one its signed distance came from.
            let n = curve.nearest_from(ends[i], approx_of(i, approx).1);
            exact[i] = Some(n);
            n
        };
    let g = |n: &Near| r - n.sd;
    let e = curve.sag;
    // The line of each end, for the report (an end shared by two moves takes the first's).
    let mut line_of = vec![0usize; ends.len()];
    for (k, &(ia, ib)) in seg_ends.iter().enumerate().rev() {
        line_of[ia] = lm.segs[k].2;
        line_of[ib] = lm.segs[k].2;
    }
    let mut best: Option<(f64, Point, Near, usize)> = None;
    // The ends in order of their bound on the gouge: measured exactly while one could beat the
    // worst found (every one with `detail`), the polyline's distance first.
    let mut by_end: Vec<usize> = (0..ends.len()).collect();
    by_end.sort_by(|&x, &y| sd_low[x].total_cmp(&sd_low[y]));
    for i in by_end {
        let top = best.map_or(f64::NEG_INFINITY, |b| b.0);
        if !detail && r - sd_low[i] + e <= top + GOUGE_SLACK {
            break;
        }
        if !detail && r - approx_of(i, &mut approx).0 + e <= top + GOUGE_SLACK {
            continue;
        }
        let n = near(i, &mut exact, &mut approx);
        if best.is_none_or(|b| g(&n) > b.0) {
            best = Some((g(&n), ends[i], n, line_of[i]));
        }
    }
    // Each move's inside is bounded from its ends, the moves refined in order of their bound
    // until no bound beats the worst gouge found (see `inside_bound`); a move's loose bound
    // from the polyline comes first, its ends measured exactly only when it could beat it.
    let loose = |k: usize, sda: f64, sdb: f64| {
        let (a, b, _) = lm.segs[k];
        0.5 * (2.0 * r - sda - sdb + a.distance(b)) + e
    };
    let mut order: Vec<(f64, usize)> =
        seg_ends.iter().enumerate().map(|(k, &(ia, ib))| (loose(k, sd_low[ia], sd_low[ib]), k)).collect();
    order.sort_by(|x, y| y.0.total_cmp(&x.0));
    let mut refine: Vec<(f64, Option<f64>, usize)> = Vec::new();
    for (bound, k) in order {
        let top = best.map_or(f64::NEG_INFINITY, |b| b.0);
        if bound <= top + GOUGE_SLACK {
            break;
        }
        let (ia, ib) = seg_ends[k];
        if loose(k, approx_of(ia, &mut approx).0, approx_of(ib, &mut approx).0) <= top + GOUGE_SLACK {
            continue;
        }
        let (a, b, _) = lm.segs[k];
        let (na, nb) = (near(ia, &mut exact, &mut approx), near(ib, &mut exact, &mut approx));
        let (bound, s) = inside_bound(a, b, &na, &nb, r);
        refine.push((bound, s, k));
    }
    refine.sort_by(|x, y| y.0.total_cmp(&x.0));
    for (bound, s_model, k) in refine {
        let top = best.map_or(f64::NEG_INFINITY, |b| b.0);
        if bound <= top + GOUGE_SLACK {
            break;
        }
        let (a, b, line) = lm.segs[k];
        let at = |s: f64| Point::new(a.z + s * (b.z - a.z), a.r + s * (b.r - a.r));
        let s = match s_model {
            Some(s) => s,
            None => {
                let iters = golden_iterations(a.distance(b));
                let guess = approx[seg_ends[k].0].map_or(0, |x| x.1 .1);
                golden_min(&|s| -g(&curve.nearest(at(s), guess)), 0.0, 1.0, iters).0
            }
        };
        let c = at(s);
        let near = curve.nearest(c, approx[seg_ends[k].0].map_or(0, |x| x.1 .1));
        if g(&near) > top {
            best = Some((g(&near), c, near, line));
        }
    }
    let ends: Vec<(Point, Near)> = if detail {
        (0..ends.len()).map(|i| (ends[i], near(i, &mut exact, &mut approx))).collect()
    } else {
        Vec::new()
    };
    let profile =
        ends.iter().map(|(p, n)| ProfilePoint { x: p.z, y: p.r, t: n.t, deviation: n.sd - r }).collect();
    let (gouge, gouge_at) = match best {
        Some((v, c, n, line)) if v > 0.0 => (v, Some(Spot { x: c.z, y: c.r, z, t: n.t, line })),
        _ => (0.0, None),
    };
    let (deviation, leftover, leftover_at) = leftover(curve, lm, r, detail);
    Measured {
        report: LevelReport { z, moves: lm.segs.len(), gouge, gouge_at, leftover, leftover_at },
        profile,
        deviation,
        samples: curve.p.clone(),
    }
}

/// The leftover of a level: each target sample's distance to the swept path less r (exact for
/// every one with `detail`), and the largest, refined on the exact curve, with where it is.
fn leftover(curve: &Curve<'_>, lm: &LevelMoves, r: f64, detail: bool) -> (Vec<f64>, f64, Option<Spot>) {
    let z = lm.z;
    // The leftover: target samples against the path, the largest refined on the exact curve.
    let path = PathSegments::new(
        lm.segs.iter().filter(|(a, b, _)| a.distance(*b) > 1e-12).map(|&(a, b, _)| (a, b)).collect(),
    );
    let lone: Vec<Point> = lm.segs.iter().filter(|(a, b, _)| a.distance(*b) <= 1e-12).map(|s| s.0).collect();
    let dist_to_path = |p: Point| {
        let d = path.nearest(p).map_or(f64::INFINITY, |n| n.0);
        lone.iter().map(|q| q.distance(p)).fold(d, f64::min)
    };
    // Each sample's distance to the path less r. A sample some move reaches needs no exact
    // distance (it is no leftover): the moves around the last sample's nearest are tried first,
    // and a reached sample keeps that upper bound (≤ 0); with `detail` every one is exact.
    let mut hint = 0usize;
    let deviation: Vec<f64> = curve
        .p
        .iter()
        .map(|&p| {
            if !detail {
                if let Some((d, i)) = path.within_near(p, r, hint, PATH_WINDOW) {
                    hint = i;
                    return d - r;
                }
            }
            let (d, i) = path.nearest(p).unwrap_or((f64::INFINITY, hint));
            hint = i;
            lone.iter().map(|q| q.distance(p)).fold(d, f64::min) - r
        })
        .collect();
    let reach = |d: f64| d > 0.0 && d <= r;
    let mut left: Option<(f64, f64)> = None;
    let n = curve.t.len() - 1;
    let spacing = curve.spacing();
    let mut cands: Vec<usize> = (0..=n).filter(|&i| reach(deviation[i])).collect();
    cands.sort_by(|&a, &b| deviation[b].total_cmp(&deviation[a]));
    for i in cands {
        let top = left.map_or(0.0, |l| l.0);
        if deviation[i] + spacing <= top {
            break;
        }
        let (a, b) = (curve.t[i.saturating_sub(1)], curve.t[(i + 1).min(n)]);
        let iters = golden_iterations(curve.p[i.saturating_sub(1)].distance(curve.p[(i + 1).min(n)]));
        let t = golden_min(&|t| -dist_to_path(curve.at(t)), a, b, iters).0;
        let d = dist_to_path(curve.at(t)) - r;
        let (d, t) = if d >= deviation[i] { (d, t) } else { (deviation[i], curve.t[i]) };
        if reach(d) && d > top {
            left = Some((d, t));
        }
    }
    let (leftover, leftover_at) = match left {
        Some((d, t)) => {
            let p = curve.at(t);
            (d, Some(Spot { x: p.z, y: p.r, z, t, line: 0 }))
        }
        None => (0.0, None),
    };
    (deviation, leftover, leftover_at)
}

/// Runs the check: expands the program, measures every level against the target.
///
/// ```
/// use threadcheck::{mill, MillSpec, Target};
/// use threadcheck::Dialect;
/// // A Ø40 boss cut with a Ø6 cutter along 36 chords of the centre circle R = 23: the worst
/// // gouge is the chord sag 23·(1 − cos 5°) = 0.087518 mm, at the middle of a chord.
/// let mut prog = String::from("G0 X23 Y0 Z2\nG1 Z-1\n");
/// for k in 1..=36 {
///     let a = (10.0 * k as f64).to_radians();
///     prog.push_str(&format!("G1 X{:.9} Y{:.9}\n", 23.0 * a.cos(), 23.0 * a.sin()));
/// }
/// prog.push_str("G0 Z2\nM30\n");
/// let target = Target::from_toml("x = \"20*cos(t)\"\ny = \"20*sin(t)\"\nt = [0, 360]\nmaterial = \"inside\"", "boss.toml")?;
/// let spec = MillSpec { program: (prog, "boss.nc".into()), dialect: Dialect::Fanuc, n_order: false,
///                       tool_diameter: 6.0, target, tolerance: 0.01, reading: Default::default() };
/// let r = mill(&spec)?;
/// assert!((r.gouge_max - 23.0 * (1.0 - 5f64.to_radians().cos())).abs() < 1e-7);
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn mill(spec: &MillSpec) -> Result<MillReport, Error> {
    checked_inputs(spec)?;
    let d = spec.tool_diameter;
    let r = 0.5 * d;
    let (text, name) = &spec.program;
    let opts =
        ReadOptions { moves: true, allow_no_threading: true, n_order: spec.n_order, ..spec.reading.clone() };
    let top = spec.target.top();
    let bottom = spec.target.z.map(|z| z[0]);
    // Levels above the part cut air, levels below its bottom are left out: neither is measured.
    let cuts = |z: f64| z < top - 1e-9 && bottom.is_none_or(|b| z >= b - 1e-9);
    let meter = Meter::new();
    let stop = crate::ground::cancel::current();
    // A target that does not depend on z is sampled once.
    let (shared, shared_err) = match spec.target.uses_z {
        true => (None, None),
        false => match Curve::new(&spec.target, 0.0, &meter) {
            Ok(Some(c)) => (Some(c), None),
            Ok(None) => (None, Some(Error::Input("the target curve has no extent".into()))),
            Err(e) => (None, Some(e)),
        },
    };
    let measure = |lm: &LevelMoves, detail: bool| -> Result<Option<Measured>, Error> {
        if let Some(stop) = &stop {
            stop.check()?;
        }
        if meter.over() {
            return Err(meter.error());
        }
        match &shared {
            Some(c) => Ok(Some(measure_level(c, lm, r, detail))),
            None => Ok(Curve::new(&spec.target, lm.z, &meter)?.map(|c| measure_level(&c, lm, r, detail))),
        }
    };
    // The program is read on one thread while the levels it has finished are measured on the
    // others: each level's report only (its samples and profile are dropped as soon as it is
    // measured; the one level the picture shows is measured again below), the moves themselves
    // kept only as each level's chords.
    type Measurement = (usize, u32, Result<Option<LevelReport>, Error>);
    let results: std::sync::Mutex<Vec<Measurement>> = std::sync::Mutex::new(Vec::new());
    let (tx, rx) = std::sync::mpsc::sync_channel::<Vec<Move>>(8);
    let (read, assembled) = std::thread::scope(|threads| {
        let reader =
            threads.spawn(move || crate::gcode::read_program_streaming(text, name, spec.dialect, opts, tx));
        let assembled = rayon::in_place_scope(|jobs| -> Result<Assembler, Error> {
            let mut asm = Assembler::new();
            let send = |asm: &mut Assembler, ready: Vec<usize>| {
                if asm.broken() {
                    return;
                }
                for n in ready {
                    let level = &mut asm.levels[n];
                    if !cuts(level.moves.z) || shared_err.is_some() {
                        continue;
                    }
                    level.sent = Some(level.generation);
                    let (lm, generation) = (level.moves.clone(), level.generation);
                    let (measure, results) = (&measure, &results);
                    jobs.spawn(move |_| {
                        let report = measure(&lm, false).map(|m| m.map(|m| m.report));
                        results.lock().unwrap_or_else(|p| p.into_inner()).push((n, generation, report));
                    });
                }
            };
            let mut ready = Vec::new();
            for chunk in rx {
                for m in &chunk {
                    asm.push(m, name, &mut ready);
                }
                send(&mut asm, std::mem::take(&mut ready));
            }
            let rest = asm.rest();
            send(&mut asm, rest);
            asm.check(name)
        });
        (reader.join().unwrap_or_else(|p| std::panic::resume_unwind(p)), assembled)
    });
    // The program's own errors first, then the toolpath's, as when it was read whole.
    let prog = read?;
    let asm = assembled?;
    let mut notes = prog.notes.clone();
    if spec.n_order {
        notes.push("the blocks run in the order of their N numbers, not as printed".into());
    }
    let mut results = results.into_inner().unwrap_or_else(|p| p.into_inner());
    let mut all: Vec<(usize, std::sync::Arc<LevelMoves>)> =
        asm.levels.iter().enumerate().map(|(n, l)| (n, l.moves.clone())).collect();
    all.sort_by(|a, b| b.1.z.total_cmp(&a.1.z));
    if all.is_empty() {
        return Err(Error::Input(format!("{name}: no feed move (G1, G2, G3) to check")));
    }
    let cut = levels_cut(all, top, bottom, &cuts, &mut notes);
    notes.push(crate::ground::note::Note::from(
        "each level is checked against the target at its own Z (the section its tool bottom cuts); the tool's flank also passes the sections above it",
    ));
    if let Some(e) = shared_err {
        return Err(e);
    }
    // Each level's measurement of its last generation, in the order of the levels.
    results.retain(|(n, generation, _)| asm.levels[*n].generation == *generation);
    let mut by_level: std::collections::HashMap<usize, Result<Option<LevelReport>, Error>> =
        results.into_iter().map(|(n, _, r)| (n, r)).collect();
    let mut levels_out = Vec::new();
    let mut kept: Vec<(LevelReport, &LevelMoves)> = Vec::new();
    for (n, lm) in &cut {
        let m = by_level
            .remove(n)
            .unwrap_or_else(|| Err(Error::Input(format!("level Z{} was not measured", lm.z))));
        match m? {
            Some(report) => {
                levels_out.push(report.clone());
                kept.push((report, lm));
            }
            None => notes.push(crate::ground::note::Note::from(format!(
                "the target has no extent at Z{}: that level is not checked",
                crate::ground::fmt::fmt_num(lm.z)
            ))),
        }
    }
    let worst_g = kept.iter().max_by(|a, b| a.0.gouge.total_cmp(&b.0.gouge));
    let worst_l = kept.iter().max_by(|a, b| a.0.leftover.total_cmp(&b.0.leftover));
    let gouge_max = worst_g.map_or(0.0, |m| m.0.gouge);
    let leftover_max = worst_l.map_or(0.0, |m| m.0.leftover);
    let shown_level = if gouge_max > 0.0 { worst_g } else { worst_l };
    let shown: Option<(Measured, &LevelMoves)> = match shown_level {
        Some((_, lm)) => measure(lm, true)?.map(|m| (m, *lm)),
        None => None,
    };
    let shown = shown.as_ref();
    let picture = shown.map(|(m, lm)| {
        let path: Vec<(Point, Point)> = lm.segs.iter().map(|&(a, b, _)| (a, b)).collect();
        MillPicture {
            z: m.report.z,
            target: m.samples.clone(),
            deviation: m.deviation.clone(),
            swept: crate::geometry::sweep::swept_disk(&path, r, 1e-3).polygons(),
            path,
            gouge_at: m.report.gouge_at,
        }
    });
    let gouge_out = gouge_max > spec.tolerance + RESOLUTION;
    let leftover_out = leftover_max > spec.tolerance + RESOLUTION;
    // Past the budget some nearest points were the samples' stand-ins: no verdict on them.
    if meter.over() {
        return Err(meter.error());
    }
    Ok(MillReport {
        program: name.clone(),
        dialect: spec.dialect,
        tool_diameter: d,
        tolerance: spec.tolerance,
        target: spec.target.clone(),
        verdict: Verdict::of(!gouge_out && !leftover_out),
        gouge_out,
        leftover_out,
        gouge_max,
        gouge_at: worst_g.and_then(|m| m.0.gouge_at),
        leftover_max,
        leftover_at: worst_l.and_then(|m| m.0.leftover_at),
        worst_level: shown.map(|m| m.0.report.z),
        profile: shown.map(|m| m.0.profile.clone()).unwrap_or_default(),
        levels: levels_out,
        notes,
        picture,
    })
}

/// The tool's diameter and the tolerance within their bounds.
fn checked_inputs(spec: &MillSpec) -> Result<(), Error> {
    let d = spec.tool_diameter;
    if !(d.is_finite() && d > 0.0) {
        return Err(Error::Input(format!("tool diameter {d} mm must be a positive length")));
    }
    if d > MAX_TOOL_DIAMETER {
        return Err(Error::Input(format!(
            "tool diameter {} mm: threadcheck checks cutters up to {MAX_TOOL_DIAMETER} mm",
            crate::ground::fmt::fmt_num(d)
        )));
    }
    if !(spec.tolerance.is_finite() && spec.tolerance >= 0.0) {
        return Err(Error::Input(format!("tolerance {} mm must be a length ≥ 0", spec.tolerance)));
    }
    Ok(())
}

/// The levels that cut the part, deepest last; the levels in air or below the part's bottom,
/// and a target reaching below the deepest level, noted.
fn levels_cut(
    all: Vec<(usize, std::sync::Arc<LevelMoves>)>,
    top: f64,
    bottom: Option<f64>,
    cuts: &dyn Fn(f64) -> bool,
    notes: &mut Vec<crate::ground::note::Note>,
) -> Vec<(usize, std::sync::Arc<LevelMoves>)> {
    let air: Vec<f64> = all.iter().map(|l| l.1.z).filter(|&z| z >= top - 1e-9).collect();
    if !air.is_empty() {
        notes.push(crate::ground::note::Note::from(format!(
            "{} level{} at or above the part's top Z{} cut air and {} left out (Z{} … Z{})",
            air.len(),
            if air.len() == 1 { "" } else { "s" },
            crate::ground::fmt::fmt_num(top),
            if air.len() == 1 { "is" } else { "are" },
            crate::ground::fmt::fmt_num(air[air.len() - 1]),
            crate::ground::fmt::fmt_num(air[0]),
        )));
    }
    let below = all.iter().filter(|l| l.1.z < top - 1e-9 && !cuts(l.1.z)).count();
    if below > 0 {
        notes.push(crate::ground::note::Note::from(format!(
            "{below} level{} below the part's bottom Z{} left out",
            if below == 1 { "" } else { "s" },
            crate::ground::fmt::fmt_num(bottom.unwrap_or(0.0))
        )));
    }
    let cut: Vec<(usize, std::sync::Arc<LevelMoves>)> = all.into_iter().filter(|l| cuts(l.1.z)).collect();
    if let (Some(bottom), Some(deepest)) = (bottom, cut.last()) {
        if deepest.1.z > bottom + 1e-9 {
            notes.push(crate::ground::note::Note::from(format!(
                "the target reaches down to Z{} but the deepest level cut is Z{}: {} mm of it is never machined",
                crate::ground::fmt::fmt_num(bottom),
                crate::ground::fmt::fmt_num(deepest.1.z),
                crate::ground::fmt::fmt_num(deepest.1.z - bottom)
            )));
        }
    }
    cut
}
