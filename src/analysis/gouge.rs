//! A thread mill's moves after its last helix (issue 63): the retract, the way out of the
//! thread and any move before the tool leaves it must not cut the thread just finished. A
//! cutter whose teeth reach past the thread's crest (an internal thread's minor diameter, an
//! external one's major) while it moves along Z, or across the grooves in the plane, drags its
//! teeth through the flanks (FreeCAD #7855: "passes right through the work piece"). Leaving
//! the groove straight toward the hole's axis (away from an external thread's) lifts the teeth
//! out of it and is safe.
//!
//! Read for the cutter's centre where no compensation is in force (under G41/G42 the centre is
//! not the programmed path: those moves are named, not judged), over the helices' Z span, until
//! the tool changes.

use crate::gcode::Move;
use crate::geometry::helix::Helix;
use crate::standards::ThreadKind;
use serde::Serialize;

/// The angle within which a move in the plane counts as straight out of the groove, degrees.
pub const RADIAL_EXIT_DEG: f64 = 1.0;

/// How far the teeth may reach past the crest before it is a gouge, mm (the standard's 1 µm).
pub const GOUGE_TOLERANCE_MM: f64 = 0.001;

/// A move after the last helix that cuts the finished thread.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Gouge {
    /// Its program line.
    pub line: usize,
    /// Its motion: `G0`, `G1`, `G2` or `G3`.
    pub code: &'static str,
    /// How deep the teeth reach past the thread's crest, radially, mm.
    pub depth: f64,
    /// A rapid move (G0).
    pub rapid: bool,
    /// It moves along Z (a retract or a plunge), else in the plane.
    pub along_z: bool,
}

/// What the moves after the last helix do to the thread: the gouges, and the lines of moves
/// under compensation that were not judged.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct AfterFinish {
    /// The moves that cut the finished thread.
    pub gouges: Vec<Gouge>,
    /// Moves under cutter compensation, not judged.
    pub compensated: Vec<usize>,
}

/// The moves after the last of `helices` (the same tool's, until it changes) against the
/// finished thread's crest radius `crest` (mm from the helices' axis), for a cutter of tip
/// radius `tip` (half its diameter over the teeth).
pub fn after_finish(
    moves: &[Move],
    helices: &[Helix],
    kind: ThreadKind,
    tip: f64,
    crest: f64,
) -> AfterFinish {
    let mut out = AfterFinish::default();
    let Some(last) = helices.last() else { return out };
    let Some(at) = moves.iter().rposition(|m| m.arc.is_some() && m.line == last.line) else { return out };
    let tool = moves[at].tool;
    let (z_lo, z_hi) = helices
        .iter()
        .flat_map(|h| h.z)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), z| (lo.min(z), hi.max(z)));
    let c = last.centre;
    let r = |p: [f64; 3]| (p[0] - c[0]).hypot(p[1] - c[1]);
    // How far past the crest the teeth reach with the centre at distance `d` from the axis.
    let past = |d: f64| match kind {
        ThreadKind::Internal => d + tip - crest,
        ThreadKind::External => crest - (d - tip),
    };
    for m in &moves[at + 1..] {
        if m.tool != tool {
            break;
        }
        // Only where the thread is: the move's Z range meets the helices'.
        let (lo, hi) = (m.from[2].min(m.to[2]), m.from[2].max(m.to[2]));
        if hi < z_lo - 1e-9 || lo > z_hi + 1e-9 {
            if lo > z_hi + 1e-9 {
                // Above the thread: out of the hole, done with it.
                break;
            }
            continue;
        }
        if m.comp != 0 {
            out.compensated.push(m.line);
            continue;
        }
        let along_z = (m.to[2] - m.from[2]).abs() > 1e-9;
        // The farthest reach along the move: at an end for a straight move (the distance from
        // the axis is convex along it), the arc's own radius for an arc about the axis.
        let worst = match m.arc {
            Some((centre, _)) if (centre[0] - c[0]).hypot(centre[1] - c[1]) < 1e-6 => {
                past(r(m.from)).max(past(r(m.to)))
            }
            Some(_) => continue,
            None => {
                let (d0, d1) = (r(m.from), r(m.to));
                if !along_z && is_radial_exit(m, c, kind) {
                    continue;
                }
                past(d0).max(past(d1))
            }
        };
        // An arc in the plane at the helix's own radius (a return circle) and every move
        // along Z or across the grooves whose teeth pass the crest.
        if worst > GOUGE_TOLERANCE_MM {
            let code = match (m.rapid, m.arc) {
                (true, _) => "G0",
                (false, None) => "G1",
                (false, Some((_, dir))) if dir > 0.0 => "G3",
                (false, Some(_)) => "G2",
            };
            out.gouges.push(Gouge { line: m.line, code, depth: worst, rapid: m.rapid, along_z });
        }
    }
    out
}

/// A move in the plane straight out of the groove: toward the axis for an internal thread,
/// away from it for an external one, within [`RADIAL_EXIT_DEG`] of the radial direction.
fn is_radial_exit(m: &Move, c: [f64; 2], kind: ThreadKind) -> bool {
    let (dx, dy) = (m.to[0] - m.from[0], m.to[1] - m.from[1]);
    let (rx, ry) = (m.from[0] - c[0], m.from[1] - c[1]);
    let (len, rl) = (dx.hypot(dy), rx.hypot(ry));
    if len < 1e-9 || rl < 1e-9 {
        return true;
    }
    // The cosine of the angle between the move and the outward radial direction.
    let cos = (dx * rx + dy * ry) / (len * rl);
    let want = match kind {
        ThreadKind::Internal => -1.0,
        ThreadKind::External => 1.0,
    };
    (cos * want) >= RADIAL_EXIT_DEG.to_radians().cos()
}

/// How far a helix may drift axially from the thread's groove over its own travel before it
/// crosses the grooves rather than follows them, mm (a named default: ten times the programs'
/// 1 µm resolution, above the drift of arcs written in rounded quarters).
pub const RETURN_DRIFT_MM: f64 = 0.01;

/// A helix that crosses the thread's grooves where it should follow them: a return helix
/// written with the other hand, or at a lead that is not the thread's, its teeth in the
/// thread (FreeCAD #7855: the return helix "passes right through the work piece").
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Crossing {
    /// Its program line.
    pub line: usize,
    /// `G2` or `G3`.
    pub code: &'static str,
    /// How deep its teeth reach past the thread's crest, radially, mm.
    pub depth: f64,
    /// Its hand, where it is the other one than the thread's (`None`: the thread's own).
    pub other_hand: Option<crate::standards::Hand>,
    /// The lead it moves at, mm per revolution (Z travel over its turns).
    pub lead: f64,
    /// The thread's lead, mm.
    pub thread_lead: f64,
    /// How far it drifts axially from the groove it starts in over its own travel, mm.
    pub drift: f64,
}

/// The helices of `helices` that cross the grooves of a thread of `lead` (mm) and `hand`
/// instead of following them, with their teeth (tip radius `tip`) reaching past its crest
/// radius `crest` (mm from the helices' axis) by more than [`GOUGE_TOLERANCE_MM`].
pub fn crossing_helices(
    helices: &[Helix],
    lead: f64,
    hand: crate::standards::Hand,
    kind: ThreadKind,
    tip: f64,
    crest: f64,
) -> Vec<Crossing> {
    helices
        .iter()
        .filter_map(|h| {
            let dz = h.z[1] - h.z[0];
            let turns = h.sweep_deg / 360.0;
            // A right-hand helix rises turning counter-clockwise (G3) and falls turning
            // clockwise (G2): its Z travel has the sign of its sweep.
            let sign = match hand {
                crate::standards::Hand::Right => 1.0,
                crate::standards::Hand::Left => -1.0,
            };
            let drift = (dz - sign * lead * turns).abs();
            let past = match kind {
                ThreadKind::Internal => h.radius.max(h.radius + h.radius_change) + tip - crest,
                ThreadKind::External => crest - (h.radius.min(h.radius + h.radius_change) - tip),
            };
            (drift > RETURN_DRIFT_MM && past > GOUGE_TOLERANCE_MM).then(|| Crossing {
                line: h.line,
                code: if h.sweep_deg > 0.0 { "G3" } else { "G2" },
                depth: past,
                other_hand: (dz != 0.0 && (dz > 0.0) != (sign * turns > 0.0)).then_some(hand.other()),
                lead: if turns != 0.0 { (dz / turns).abs() } else { 0.0 },
                thread_lead: lead,
                drift,
            })
        })
        .collect()
}
