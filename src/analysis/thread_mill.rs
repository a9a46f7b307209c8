//! Thread milling (issue 31): a single-form thread mill, a body of revolution about an axis
//! parallel to the thread's, moves on the helices a program commands (G2/G3 with a Z change in
//! G17). The thread it leaves is the envelope of the cutter's positions, cut by the part's axial
//! half-plane: not the cutter's tooth profile, because the cutter meets that plane at many
//! positions along the helix, each at its own height and its own angle.
//!
//! **The envelope, exactly.** Take the part's axis as Z and the half-plane θ = 0 (direction +X
//! from the hole's centre). With the cutter's axis at distance R from the part's and at angle ψ
//! from the half-plane, its tooth centre at height zc(ψ) (the helix), the point (r, z) of the
//! half-plane lies inside the cutter when its distance from the cutter's axis, √(r² + R² −
//! 2rR·cos ψ), is at most the cutter's radius ρ(z − zc) at that height. So the largest radius an
//! internal thread's cutter reaches at height z is
//!
//!   r(z) = max over the helix of R·cos ψ + √(ρ(z − zc(ψ))² − R²·sin² ψ)
//!
//! (an external thread's cutter, outside the bolt, the least: R·cos ψ − √(…)). At ψ = 0 this is
//! R + ρ(z − zc): the tooth profile moved out by R; every other ψ can only add to it, and adds
//! more the larger the cutter is against the hole. The maximum over ψ is found on a grid of the
//! helix parameter and refined by golden section; the profile then goes through the same
//! measurement and class checks as a turned thread.
//!
//! The cutter: `diameter` over the tooth's tip, the tooth's included `angle` and tip radius, a
//! tooth as deep as the thread's fundamental triangle H below the tip (deeper than any standard
//! thread, so the neck never reaches it: a named default). Under cutter radius compensation (G41/G42) the helix
//! radius is the programmed one moved by the compensation value given (the D register's).

use crate::analysis::check::{checks, Check};
use crate::gcode::{Dialect, Move, ProgramUnits, ReadOptions};
use crate::geometry::helix::{reach, section_cost};
use crate::geometry::helix::{Cutter, Helix};
use crate::geometry::measure::{measure, MeasureSetup, Measurement};
use crate::standards::tolerance::{limits_for, ThreadLimits};
use crate::standards::{ParseOptions, ThreadKind};
use crate::{Error, Point};
use rayon::prelude::*;
use serde::Serialize;

/// What the thread-milling check reads.
#[derive(Clone, Debug)]
pub struct ThreadMillSpec {
    /// The program's text and name.
    pub program: (String, String),
    /// Its dialect.
    pub dialect: Dialect,
    /// The thread with its class, parsed; `None` takes the one the program names (the nearest
    /// comment above the first helix, else the standard size its lead and diameter cut).
    pub designation: Option<crate::standards::Designation>,
    /// Accept sizes outside the standard series.
    pub allow_nonstandard: bool,
    /// The cutter; `None` takes the helix's tool from `tools`.
    pub cutter: Option<Cutter>,
    /// The tool table: the thread mill's file by T number, and `[offsets]`.
    pub tools: Option<crate::analysis::tools::ToolTable>,
    /// The bore (internal) or blank (external) diameter, mm; default the class's minor (internal)
    /// or major (external) diameter limit's middle.
    pub blank_diameter: Option<f64>,
    /// The cutter radius compensation value (the D register) G41/G42 apply, mm; a helix under
    /// compensation without it is refused.
    pub comp_radius: Option<f64>,
    /// How the program is read: the units of a program that sets neither G20 nor G21, the
    /// machine, where its subprograms' files are (its toolpath and `allow_no_threading` are this
    /// check's own).
    pub reading: ReadOptions,
    /// The cutter's teeth (flutes), for the feed per tooth at its edge (`None`: not given).
    pub teeth: Option<u32>,
}

/// The thread a thread mill leaves, measured and checked.
#[derive(Clone, Debug, Serialize)]
pub struct ThreadMillReport {
    /// The program.
    pub program: String,
    /// The designation.
    pub designation: String,
    /// Where it came from, and how it was read.
    pub named: crate::analysis::naming::Named,
    /// Internal or external.
    pub kind: ThreadKind,
    /// How the text and the picture give lengths: inch for a thread of an inch size (the
    /// JSON stays in mm).
    #[serde(skip)]
    pub units: crate::analysis::turn::Units,
    /// The cutter.
    pub cutter: Cutter,
    /// The cutter's diameter over the thread's major (internal) diameter.
    pub cutter_ratio: f64,
    /// The helices of the operation, in program order.
    pub helices: Vec<Helix>,
    /// The feed each helix's cutter edge sees, from the centre feed the program writes (the
    /// helices with a known feed, in program order).
    pub feeds: Vec<HelixFeed>,
    /// What the moves after the last helix do to the finished thread (issue 63).
    #[serde(skip)]
    pub after_finish: crate::analysis::gouge::AfterFinish,
    /// The helices that cross the thread's grooves instead of following them: a return helix
    /// of the other hand or another lead, its teeth in the thread (issue 63).
    #[serde(skip)]
    pub crossings: Vec<crate::analysis::gouge::Crossing>,
    /// An internal 60° thread's percent of thread from its bore (the charts' figure, issue 64).
    pub thread_percent: Option<crate::analysis::percent::ThreadPercent>,
    /// The bore or blank diameter, mm.
    pub blank_diameter: f64,
    /// The as-cut thread, measured.
    pub measured: Measurement,
    /// The thread the tooth profile alone would leave (ψ = 0 only), measured.
    pub tooth_profile: Measurement,
    /// The profile distortion: d2 of the milled thread less the tooth profile's, µm.
    pub distortion_pitch_diameter_um: f64,
    /// The flank angles' change from the tooth profile's, degrees (low-z, high-z flank).
    pub distortion_flank_angles_deg: [f64; 2],
    /// The class's limits.
    pub limits: ThreadLimits,
    /// Size and form checks, and the program's (`lead`).
    pub checks: Vec<Check>,
    /// Every check passes, and no move after the last helix cuts the thread.
    pub pass: bool,
    /// What was assumed.
    pub notes: Vec<crate::ground::note::Note>,
    /// The measured axial section (z, r), mm, over four pitches.
    #[serde(skip)]
    pub profile: Vec<Point>,
    /// The tooth profile's section over the same heights.
    #[serde(skip)]
    pub tooth_points: Vec<Point>,
    /// The helix's widening of the groove along the section: (z mm, the as-milled radius's
    /// distance from the tooth profile's, µm) at each height.
    #[serde(skip)]
    pub widening_um: Vec<(f64, f64)>,
    /// The basic profile placed on the measured groove, over the same heights.
    #[serde(skip)]
    pub basic: Vec<Point>,
    /// The tolerance zone's maximum- and minimum-material sides over them (`None` when the
    /// class lacks a pitch-diameter limit).
    #[serde(skip)]
    pub zone: Option<crate::analysis::picture::ZoneSides>,
}

/// The feed a helix's cutter edge sees, from the centre feed the program writes.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct HelixFeed {
    /// The helix's program line.
    pub line: usize,
    /// The cutter centre's feed the program writes, mm/min.
    pub centre: f64,
    /// The feed at the cutter's edge on the thread's major diameter, mm/min.
    pub edge: f64,
    /// Edge over centre: the radii's ratio, D/(D − d) for an internal thread, D/(D + d) for an
    /// external one.
    pub factor: f64,
    /// The program writes the feed in inches (a minute).
    pub inch: bool,
    /// The spindle speed at the helix, rpm (`None`: the program gives none).
    pub spindle: Option<f64>,
    /// The feed per tooth at the edge, mm: edge / (S · teeth), when the cutter's teeth are
    /// given (`--cutter-teeth`) and the spindle speed is known.
    pub per_tooth: Option<f64>,
}

/// The edge feeds of the helices with a feed. The control moves the cutter's centre at F (the
/// programmed path's feed: under G41/G42 the compensated centre's, a named default); the
/// cutting edge on the thread's major diameter D moves in proportion to its radius, D/(D − d)
/// faster inside (the centre runs on a circle of D − d), D/(D + d) slower outside, with d the
/// cutter's diameter: the thread-mill makers' feed adjustment, taken on D as they publish it
/// (the 9/16-18 example: a 0.370 in cutter, 8.3 in/min at the edge is 2.84 in/min at the centre
/// inside, 13.76 outside). The helix's Z travel is left out (its lead angle's cosine: 0.999 at
/// P 2 on a Ø10 circle).
fn edge_feeds(
    hs: &[Helix],
    moves: &[Move],
    major: f64,
    cutter_diameter: f64,
    kind: ThreadKind,
    teeth: Option<u32>,
) -> Vec<HelixFeed> {
    let factor = match kind {
        ThreadKind::Internal => major / (major - cutter_diameter),
        ThreadKind::External => major / (major + cutter_diameter),
    };
    if !(factor.is_finite() && factor > 0.0) {
        return Vec::new();
    }
    hs.iter()
        .filter_map(|h| {
            let centre = h.feed?;
            let mv = moves.iter().find(|m| m.line == h.line);
            let inch = mv.is_some_and(|m| m.units == ProgramUnits::Inch);
            let spindle = mv.and_then(|m| m.spindle).filter(|s| *s > 0.0);
            let edge = centre * factor;
            let per_tooth = match (spindle, teeth) {
                (Some(s), Some(z)) if z > 0 => Some(edge / (s * f64::from(z))),
                _ => None,
            };
            Some(HelixFeed { line: h.line, centre, edge, factor, inch, spindle, per_tooth })
        })
        .collect()
}

/// The thread a thread-milling program names: the nearest comment above its first helix that
/// names one (its side from the helix: the cutter inside the thread, D = 2R + Dc, or outside it,
/// d3 = 2R − Dc, whichever the designation's diameter is nearer), else the standard size of the
/// helix's lead and diameter, internal unless the compensation puts the cutter outside its path
/// (a named default: thread milling is mostly of holes).
fn name_milled(
    text: &str,
    dialect: Dialect,
    moves: &[Move],
    hs: &[Helix],
    (cutter, cutter_angle): (f64, f64),
    opts: ParseOptions,
    file: &str,
) -> Result<crate::analysis::naming::Named, Error> {
    use crate::analysis::naming::{from_comments, infer_designation_with};
    let Some(first) = hs.first() else {
        return Err(Error::Program {
            file: file.to_string(),
            line: 1,
            column: 1,
            message: "no helix in the program (G2/G3 with a Z change in G17): nothing is thread-milled"
                .into(),
        });
    };
    let comments = crate::gcode::comments(text, dialect);
    let r = first.radius;
    if let Some(n) = from_comments(&comments, 0, first.line, ThreadKind::Internal, opts) {
        let d = n.designation.thread.nominal_diameter;
        let external = (2.0 * r - cutter - d).abs() < (2.0 * r + cutter - d).abs();
        if !external {
            return Ok(n);
        }
        if let Some(e) = from_comments(&comments, 0, first.line, ThreadKind::External, opts) {
            return Ok(e);
        }
    }
    // Outside the helix: the compensation puts the cutter there, or (with none) the tool came
    // down to the helix's level beyond its path and moved in, as one mills a bolt (a bore's
    // cutter comes down inside it).
    let approach = approach_side(moves, first);
    let outside = first.radius > first.programmed_radius + 1e-9 || approach == Some(ThreadKind::External);
    let (kind, major) = if outside {
        (ThreadKind::External, 2.0 * r - cutter + 2.0 * 0.613_434_5 * first.lead.abs())
    } else {
        (ThreadKind::Internal, 2.0 * r + cutter)
    };
    let place = |e: Error| match e {
        Error::Input(message) => {
            Error::Program { file: file.to_string(), line: first.line, column: 1, message }
        }
        e => e,
    };
    // The lead per whole turn (arcs of part turns written rounded make it up between them).
    let leads = turn_leads(hs);
    let lead = if leads.is_empty() {
        first.lead.abs()
    } else {
        leads.iter().map(|l| l.1).sum::<f64>() / leads.len() as f64
    };
    let lead = (lead * 1e6).round() / 1e6;
    let angle = Some(cutter_angle);
    let mut n =
        infer_designation_with(lead, 1, major, kind, crate::gcode::ProgramUnits::Mm, first.line, angle)
            .or_else(|e| {
                infer_designation_with(
                    lead,
                    1,
                    major,
                    kind,
                    crate::gcode::ProgramUnits::Inch,
                    first.line,
                    angle,
                )
                .map_err(|_| e)
            })
            .map_err(place)?;
    match (kind, approach) {
        (ThreadKind::External, Some(ThreadKind::External))
            if first.radius <= first.programmed_radius + 1e-9 =>
        {
            n.why.push_str(
                "; an external thread: the tool comes down outside the helix's path and moves in to it",
            );
        }
        (ThreadKind::Internal, Some(ThreadKind::Internal)) => {
            n.why.push_str(
                "; an internal thread: the tool comes down inside the helix's path and moves out to it",
            );
        }
        (ThreadKind::Internal, _) => {
            n.why.push_str("; an internal thread, a named default (neither the compensation nor the approach puts the cutter outside its path)");
        }
        _ => {}
    }
    Ok(n)
}

/// The side the tool approaches a helix from: where the last move that brings it down before the
/// helix ends, against the helix's programmed path (beyond it: an external thread; inside it: a
/// bore). `None` when that point lies on the path or no move brings the tool down.
fn approach_side(moves: &[Move], first: &Helix) -> Option<ThreadKind> {
    let at = moves.iter().position(|m| m.arc.is_some() && m.line == first.line)?;
    let down = moves[..at].iter().rev().find(|m| m.arc.is_none() && m.to[2] < m.from[2] - 1e-9)?;
    let d = (down.to[0] - first.centre[0]).hypot(down.to[1] - first.centre[1]);
    if d > first.programmed_radius + 1e-3 {
        Some(ThreadKind::External)
    } else if d < first.programmed_radius - 1e-3 {
        Some(ThreadKind::Internal)
    } else {
        None
    }
}

/// The helices (G2/G3 arcs with a Z change in G17) of `moves`, each at its cutter centre's
/// radius: the programmed radius, moved by the compensation `comp` under G41/G42 (to the left of
/// the travel for G41: toward the axis on a counter-clockwise G3, away on a clockwise G2).
fn helices(
    moves: &[Move],
    file: &str,
    comp: Option<f64>,
    notes: &mut Vec<String>,
) -> Result<Vec<Helix>, Error> {
    let mut out = Vec::new();
    // Counted before any is measured: 1.9 million turns took 14 s to end in an error.
    let mut turns = 0.0f64;
    for mv in moves {
        let Some((c, dir)) = mv.arc else { continue };
        let dz = mv.to[2] - mv.from[2];
        if dz.abs() < 1e-9 {
            continue;
        }
        let shift = match (mv.comp, comp) {
            (0, _) => 0.0,
            (_, None) => {
                return Err(Error::Program {
                    file: file.to_string(),
                    line: mv.line,
                    column: 1,
                    message: format!(
                        "a helix under cutter radius compensation (G4{}): give the compensation value the D register holds (‹comp_radius› MM)",
                        mv.comp
                    ),
                })
            }
            // Left of a counter-clockwise travel is toward the centre.
            (1, Some(d)) => -dir * d,
            (_, Some(d)) => dir * d,
        };
        let a0 = (mv.from[1] - c[1]).atan2(mv.from[0] - c[0]);
        let a1 = (mv.to[1] - c[1]).atan2(mv.to[0] - c[0]);
        let r0 = (mv.from[0] - c[0]).hypot(mv.from[1] - c[1]);
        let r1 = (mv.to[0] - c[0]).hypot(mv.to[1] - c[1]);
        if r0 < 1e-6 || r1 < 1e-6 {
            return Err(Error::Program {
                file: file.to_string(),
                line: mv.line,
                column: 1,
                message: "a helix that starts or ends on its own axis: not a thread-milling helix".into(),
            });
        }
        let mut sweep = dir * (a1 - a0);
        while sweep <= 1e-9 {
            sweep += std::f64::consts::TAU;
        }
        sweep += std::f64::consts::TAU * f64::from(mv.extra_turns);
        turns += sweep / std::f64::consts::TAU;
        if turns > crate::ground::bounds::MAX_HELIX_TURNS as f64 {
            return Err(Error::Program {
                file: file.to_string(),
                line: mv.line,
                column: 1,
                message: format!(
                    "the helices up to here make {} turns, more than the {} threadcheck measures in one operation",
                    crate::ground::fmt::fmt_shown(turns.round()),
                    crate::ground::bounds::MAX_HELIX_TURNS
                ),
            });
        }
        let lead = dz * std::f64::consts::TAU / sweep;
        let radius = r0 + shift;
        if radius <= 0.0 {
            return Err(Error::Program {
                file: file.to_string(),
                line: mv.line,
                column: 1,
                message: format!("the compensation moves the cutter centre through the helix axis (radius {r0:.4} mm, shift {shift:.4} mm)"),
            });
        }
        out.push(Helix {
            line: mv.line,
            centre: c,
            radius,
            programmed_radius: r0,
            radius_change: r1 - r0,
            z: [mv.from[2], mv.to[2]],
            sweep_deg: dir * sweep.to_degrees(),
            lead,
            climb: false,
            feed: mv.feed,
            angle_start: a0,
        });
    }
    Ok(main_axis(out, notes))
}

/// The helices of a parallel thread, each on one circle: an arc whose end lies up to a rounding
/// off its start's circle (points written rounded) is measured at the mean of its two radii,
/// said; one further off is refused at its line.
fn circular(hs: Vec<Helix>, file: &str, notes: &mut Vec<String>) -> Result<Vec<Helix>, Error> {
    // Helices that all widen one way along Z: a taper thread's, named as a parallel one.
    let spirals = |h: &Helix| h.radius_change * (h.z[1] - h.z[0]);
    let tapering = hs.iter().all(|h| spirals(h) > 0.0) || hs.iter().all(|h| spirals(h) < 0.0);
    // Every arc off its circle the same way, adding up past a rounding: a spiral, not points
    // written rounded (those scatter either way).
    let (dr, dz) = hs.iter().fold((0.0, 0.0), |(r, z), h| (r + h.radius_change, z + (h.z[1] - h.z[0])));
    if let (true, Some(first)) = (
        tapering && hs.iter().all(|h| h.radius_change.abs() > 1e-3) && dr.abs() > RADIUS_ROUNDING,
        hs.first(),
    ) {
        return Err(Error::Program {
            file: file.to_string(),
            line: first.line,
            column: 1,
            message: format!(
                "the helices from here spiral one way along Z, their radius growing {} mm over {} mm of Z (a taper of 1:{} on the diameter): a taper thread's helices, not a parallel thread's; name the taper thread (NPT, ISO 7-1 R/Rc) in a comment or ‹thread›",
                crate::ground::fmt::fmt_num((dr * 1e4).round() / 1e4),
                crate::ground::fmt::fmt_num((dz * 1e4).round() / 1e4),
                crate::ground::fmt::fmt_num(((dz / (2.0 * dr)).abs() * 10.0).round() / 10.0)
            ),
        });
    }
    let mut rounded = Vec::new();
    let mut out = Vec::with_capacity(hs.len());
    for mut h in hs {
        let (r0, r1) = (h.programmed_radius, h.programmed_radius + h.radius_change);
        if h.radius_change.abs() > RADIUS_ROUNDING {
            return Err(Error::Program {
                file: file.to_string(),
                line: h.line,
                column: 1,
                message: format!(
                    "a helix whose start and end radii differ ({r0:.4} and {r1:.4} mm), by more than a rounding ({RADIUS_ROUNDING} mm): not a parallel thread's helix{}",
                    if tapering {
                        "; the helices spiral one way along Z, as a taper thread's do: name the taper thread (NPT, ISO 7-1 R/Rc) in a comment or ‹thread›"
                    } else {
                        ""
                    }
                ),
            });
        }
        if h.radius_change.abs() > 1e-3 {
            rounded.push(h.line);
        }
        // Points written to a coarser rounding than the arc's centre: the mean radius.
        h.radius += 0.5 * h.radius_change;
        h.programmed_radius += 0.5 * h.radius_change;
        h.radius_change = 0.0;
        out.push(h);
    }
    if let Some(first) = rounded.first() {
        notes.push(format!(
            "{} helix arc{} from line {first} end{} up to {RADIUS_ROUNDING} mm off {} circle (points written rounded): measured at the mean of {} radii",
            rounded.len(),
            if rounded.len() == 1 { "" } else { "s" },
            if rounded.len() == 1 { "s" } else { "" },
            if rounded.len() == 1 { "its" } else { "their" },
            if rounded.len() == 1 { "its" } else { "their" }
        ));
    }
    Ok(out)
}

/// How far a helix arc's start and end radii may differ and still be read as one circle: points
/// a CAM post writes to 0.01 mm lie up to 0.007 mm off it (a named reading; a control takes such
/// an arc within its own radius tolerance).
const RADIUS_ROUNDING: f64 = 0.02;

/// The helices about the axis with the most turns (the thread); arcs about other axes (a
/// tangential entry or exit, another hole's thread) are left out, with a note that names them.
fn main_axis(hs: Vec<Helix>, notes: &mut Vec<String>) -> Vec<Helix> {
    let same = |a: &Helix, b: &Helix| (a.centre[0] - b.centre[0]).hypot(a.centre[1] - b.centre[1]) <= 1e-3;
    let turns = |c: &Helix| hs.iter().filter(|h| same(h, c)).map(|h| h.sweep_deg.abs()).sum::<f64>();
    let Some(main) = hs.iter().max_by(|a, b| turns(a).total_cmp(&turns(b))).cloned() else { return hs };
    // An arc whose centre lies within a rounding of the main axis (an R-format arc through a
    // point written rounded: its centre moves with the point) is the same helix, measured about
    // the main axis from its own end points.
    let near = |h: &Helix| {
        let d = (h.centre[0] - main.centre[0]).hypot(h.centre[1] - main.centre[1]);
        d > 1e-3 && d <= RADIUS_ROUNDING
    };
    let moved = hs.iter().filter(|h| near(h)).count();
    let first_moved = hs.iter().find(|h| near(h)).map(|h| h.line);
    let hs: Vec<Helix> =
        hs.into_iter().map(|h| if near(&h) { recentred(h, main.centre) } else { h }).collect();
    if let Some(first) = first_moved {
        notes.push(format!(
            "{moved} helix arc{} from line {first} {} centres up to {RADIUS_ROUNDING} mm off the helices' axis (arcs by their radius through points written rounded): measured about the axis, from {} end points",
            if moved == 1 { "" } else { "s" },
            if moved == 1 { "has its" } else { "have their" },
            if moved == 1 { "its" } else { "their" },
        ));
    }
    let (kept, others): (Vec<Helix>, Vec<Helix>) = hs.into_iter().partition(|h| same(h, &main));
    if !others.is_empty() {
        let lines: Vec<String> = others.iter().take(6).map(|h| h.line.to_string()).collect();
        // An entry or exit arc inside the helices' circle cuts no deeper than they do.
        let inside = others.iter().all(|h| {
            (h.centre[0] - main.centre[0]).hypot(h.centre[1] - main.centre[1]) + h.radius
                <= main.radius + 1e-6
        });
        notes.push(format!(
            "{} helical arc{} about another axis (line {}{}) left out{}: this check reads the helices about X{} Y{}, the ones with the most turns",
            others.len(),
            if others.len() == 1 { "" } else { "s" },
            lines.join(", "),
            if others.len() > 6 { ", …" } else { "" },
            if inside {
                ", inside the helices' circle (an entry or exit arc): it cuts no deeper than they do"
            } else {
                " (another hole's thread, or an arc that reaches past the helices' circle: not swept)"
            },
            crate::ground::fmt::fmt_num(main.centre[0]),
            crate::ground::fmt::fmt_num(main.centre[1])
        ));
    }
    kept
}

/// Helix `h` about the axis at `centre` instead of its own: its end points kept, its radii,
/// start angle and sweep (the same turns and direction) taken about `centre`.
fn recentred(h: Helix, centre: [f64; 2]) -> Helix {
    let sweep = h.sweep_deg.to_radians();
    let (r0, r1) = (h.programmed_radius, h.programmed_radius + h.radius_change);
    let at = |r: f64, a: f64| [h.centre[0] + r * a.cos(), h.centre[1] + r * a.sin()];
    let (from, to) = (at(r0, h.angle_start), at(r1, h.angle_start + sweep));
    let polar = |p: [f64; 2]| {
        ((p[0] - centre[0]).hypot(p[1] - centre[1]), (p[1] - centre[1]).atan2(p[0] - centre[0]))
    };
    let ((n0, b0), (n1, b1)) = (polar(from), polar(to));
    // The small turn of each end point about the new centre, added to the sweep.
    let wrap = |a: f64| (a + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI;
    let d_start = wrap(b0 - h.angle_start);
    let d_end = wrap(b1 - (h.angle_start + sweep));
    let new_sweep = sweep + (d_end - d_start);
    let shift = h.radius - h.programmed_radius;
    let lead = (h.z[1] - h.z[0]) * std::f64::consts::TAU / new_sweep.abs();
    Helix {
        centre,
        radius: n0 + shift,
        programmed_radius: n0,
        radius_change: n1 - n0,
        sweep_deg: new_sweep.to_degrees(),
        lead,
        angle_start: b0,
        ..h
    }
}

/// The distinct phases of the helices: Z where each crosses the +X half-plane, modulo `lead`
/// (within 5 µm one phase), in program order (the first is start 1's).
fn start_phases(hs: &[Helix], lead: f64) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::new();
    for h in hs {
        let sweep = h.sweep_deg.to_radians();
        if sweep.abs() < 1e-12 || lead <= 0.0 {
            continue;
        }
        let z0 = h.z[0] - h.angle_start * (h.z[1] - h.z[0]) / sweep;
        let p = z0.rem_euclid(lead);
        let near = |q: f64| {
            let d = (p - q).rem_euclid(lead);
            d.min(lead - d) <= 0.005
        };
        if !out.iter().any(|&q| near(q)) {
            out.push(p);
        }
    }
    out
}

/// The starts the helices cut against the designation's: each phase's offset from the first's
/// must be a whole number of pitches (to 5 µm); a start missing, one too many or one misplaced
/// fails, naming it.
fn starts_of(phases: &[f64], t: &crate::standards::BasicThread) -> Check {
    let first = phases.first().copied().unwrap_or(0.0);
    let misplaced = crate::analysis::check::misplaced_starts(phases, t.pitch, t.lead(), 0.005);
    let cut: std::collections::BTreeSet<u32> = phases
        .iter()
        .map(|&p| (p - first).rem_euclid(t.lead()))
        .filter(|off| !misplaced.iter().any(|m| (m - off).abs() <= 0.005))
        .map(|off| ((off / t.pitch).round() as u32) % t.starts.max(1))
        .collect();
    crate::analysis::check::starts_check(&cut, t.starts, t.pitch, &misplaced)
}

/// The lead each whole turn of the helices cuts: for every helix end one turn or more into its
/// run (consecutive helices about one axis), the Z travelled over the turn before it (within an
/// arc, Z is linear in the angle); runs shorter than a turn give each helix's own lead. Half
/// turns of 1.748 and 1.752 make a 1.750 lead.
fn turn_leads(hs: &[Helix]) -> Vec<(usize, f64)> {
    let mut out = Vec::new();
    let mut start = 0;
    while start < hs.len() {
        let mut end = start + 1;
        while end < hs.len()
            && (hs[end].centre[0] - hs[start].centre[0]).hypot(hs[end].centre[1] - hs[start].centre[1])
                <= 1e-3
            && (hs[end].z[0] - hs[end - 1].z[1]).abs() < 1e-6
            && hs[end].sweep_deg.signum() == hs[start].sweep_deg.signum()
        {
            end += 1;
        }
        // Cumulative angle (radians) and Z at each helix's end, from the run's start.
        let mut pts = vec![(0.0f64, hs[start].z[0])];
        for h in &hs[start..end] {
            let a = pts.last().map_or(0.0, |p| p.0) + h.sweep_deg.abs().to_radians();
            pts.push((a, h.z[1]));
        }
        let z_at = |a: f64| -> f64 {
            let k = pts.iter().rposition(|p| p.0 <= a + 1e-12).unwrap_or(0).min(pts.len() - 2);
            let (p, q) = (pts[k], pts[k + 1]);
            p.1 + (q.1 - p.1) * (a - p.0) / (q.0 - p.0)
        };
        let tau = std::f64::consts::TAU;
        let whole = pts.last().map_or(0.0, |p| p.0) >= tau - 1e-9;
        for (i, h) in hs[start..end].iter().enumerate() {
            let (a, z) = pts[i + 1];
            if whole && a >= tau - 1e-9 {
                out.push((h.line, (z - z_at(a - tau)).abs()));
            } else if !whole {
                out.push((h.line, h.lead.abs()));
            }
        }
        start = end;
    }
    out
}

/// A thread mill a comment of the program names for a tool.
#[derive(Clone, Copy, Debug)]
pub(crate) struct CommentedCutter {
    /// The cutter: the comment's diameter, its angle or 60°, tip radius 0, one row.
    pub cutter: Cutter,
    /// The comment's line.
    pub line: usize,
    /// The comment wrote the tooth's angle.
    pub angle_given: bool,
}

impl CommentedCutter {
    /// The note that says where the cutter came from.
    fn note(&self, tool: u32) -> String {
        format!(
            "the thread mill T{tool} is the program's comment at line {}: Ø{}, its tooth {}°{}, tip radius 0 and one row (a named default; ‹cutter_diameter› or a tool table gives the cutter)",
            self.line,
            crate::ground::fmt::fmt_num(self.cutter.diameter),
            crate::ground::fmt::fmt_num(self.cutter.angle_deg),
            if self.angle_given { " as written" } else { ", the default" }
        )
    }
}

/// The thread mill the program's comments name for the tool of `helix` (its first), when the
/// tool table `tools` does not name that tool: a tool list's line (`(T5  D=8. CR=0. - thread
/// mill)`, as Autodesk's posts write one for every tool at the top; `( 8. THREAD MILL TOOL - 5
/// DIA. OFF. - 5 LEN. - 5 DIA. - 8. )`, Mastercam's), else a comment on a line that calls the
/// tool (`T5 M6 (THREAD MILL D10 60 DEG)`); its diameter in the program's units at the helix.
pub(crate) fn cutter_in_comments(
    text: &str,
    dialect: crate::gcode::Dialect,
    tools: Option<&crate::analysis::tools::ToolTable>,
    helix: &Move,
) -> Option<CommentedCutter> {
    use crate::analysis::naming::thread_mill_in_comment;
    let tool = helix.tool?;
    if tools.is_some_and(|tt| tt.tool(tool).is_some()) {
        return None;
    }
    let units = helix.units;
    let comments = crate::gcode::comments(text, dialect);
    let calls_tool = |line: usize, column: usize| -> bool {
        let code: Vec<char> =
            text.lines().nth(line - 1).unwrap_or("").chars().take(column.saturating_sub(2)).collect();
        (0..code.len()).any(|i| {
            code[i].eq_ignore_ascii_case(&'T') && (i == 0 || !code[i - 1].is_ascii_alphabetic()) && {
                let digits: String = code[i + 1..].iter().take_while(|c| c.is_ascii_digit()).collect();
                digits.parse::<u32>().ok() == Some(tool)
            }
        })
    };
    let listed = comments.iter().find_map(|c| {
        thread_mill_in_comment(&c.text, units).filter(|m| m.tool == Some(tool)).map(|m| (m, c.line))
    });
    let at_call = || {
        comments.iter().find_map(|c| {
            thread_mill_in_comment(&c.text, units)
                .filter(|m| m.tool.is_none() && calls_tool(c.line, c.column))
                .map(|m| (m, c.line))
        })
    };
    let (m, line) = listed.or_else(at_call)?;
    (m.diameter < 1000.0).then(|| CommentedCutter {
        cutter: Cutter::single_form(m.diameter, m.angle_deg.unwrap_or(60.0), 0.0),
        line,
        angle_given: m.angle_deg.is_some(),
    })
}

/// How the cutter reaches its first helix and leaves its last: by an arc in the plane (a
/// tangential entry, the usual practice) or by a straight feed move, which meets the thread
/// square on and leaves a witness mark where it stops.
/// The helices are the measured ones, `hs`: a helical arc about another axis before or after
/// them (a CAM system's helical lead-in) is an arc in too.
fn entry_and_exit(moves: &[Move], hs: &[Helix]) -> Vec<String> {
    let is_helix = |m: &Move| m.arc.is_some() && (m.to[2] - m.from[2]).abs() > 1e-9;
    let (Some(h0), Some(h1)) = (hs.first(), hs.last()) else { return Vec::new() };
    let Some(first) = moves.iter().position(|m| is_helix(m) && m.line == h0.line) else {
        return Vec::new();
    };
    let last = moves.iter().rposition(|m| is_helix(m) && m.line == h1.line).unwrap_or(first);
    let word = |m: Option<&Move>, what: &str| -> String {
        match m {
            Some(m) if m.rapid => format!("the cutter {what} its helices by a rapid move (line {}): it should feed", m.line),
            Some(m) if m.arc.is_some() => format!(
                "the cutter {what} its helices on {} (line {}): a tangential {}",
                if is_helix(m) { "a helical arc about another axis" } else { "an arc in the plane" },
                m.line,
                if what == "reaches" { "entry" } else { "exit" }
            ),
            Some(m) => format!(
                "the cutter {what} its helices by a straight feed move (line {}): it meets the thread square on and leaves a witness mark; an arc {} is the usual practice",
                m.line,
                if what == "reaches" { "in" } else { "out" }
            ),
            None => format!("nothing {} the helices", if what == "reaches" { "comes before" } else { "follows" }),
        }
    };
    vec![
        word(first.checked_sub(1).and_then(|i| moves.get(i)), "reaches"),
        word(moves.get(last + 1), "leaves"),
    ]
}

/// Mills the thread in the computer and checks it.
///
/// ```
/// use threadcheck::{thread_mill, Cutter, Dialect, ReadOptions, ThreadMillSpec};
/// // M20x1.5-6H with a Ø12 single-form cutter: the helix radius 10 − 6 = 4 puts the tooth's tip on
/// // D = 20; eight turns climbing 1.5 mm each.
/// let mut program = String::from("G17 G90 G40\nG0 X4 Y0 Z-14\n");
/// for k in 1..=8 { program += &format!("G3 X4 Y0 Z{} I-4 J0 F200\n", -14.0 + 1.5 * k as f64); }
/// let cutter = Some(Cutter::single_form(12.0, 60.0, 0.0));
/// let spec = ThreadMillSpec { program: (program, "mill.nc".into()), dialect: Dialect::Fanuc, designation: Some(threadcheck::parse_designation("M20x1.5-6H", Default::default())?), allow_nonstandard: false, cutter, tools: None, blank_diameter: None, comp_radius: None, reading: ReadOptions::default(), teeth: None };
/// let r = thread_mill(&spec)?;
/// assert!((r.measured.major_diameter - 20.0).abs() < 1e-4);
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn thread_mill(spec: &ThreadMillSpec) -> Result<ThreadMillReport, Error> {
    let (text, name) = &spec.program;
    let opts = ReadOptions { moves: true, allow_no_threading: true, ..spec.reading.clone() };
    let prog = crate::gcode::read_program_with(text, name, spec.dialect, opts)?;
    let mut notes: Vec<String> = prog.notes.iter().map(|n| n.marked().to_string()).collect();
    let (c, first_tool) = cutter_of(spec, &prog, &mut notes)?;
    let comp = compensation(spec, &prog, c, first_tool, &mut notes)?;
    let opts = ParseOptions { allow_nonstandard: spec.allow_nonstandard };
    let (hs, named, des, kind, limits) = thread_of(spec, &prog, c, comp, opts, &mut notes)?;
    let internal = kind == ThreadKind::Internal;
    let t = des.thread;
    let p = t.pitch;
    let taper = crate::analysis::taper::taper_of(&limits, kind, p);
    let (hs, first) = prepared_helices(hs, taper, &prog.moves, comp, c, internal, name, &mut notes)?;
    let blank = blank_of(spec.blank_diameter, &limits, &t, internal, &mut notes)?;
    // The tooth reaches the depth of the thread's fundamental triangle, deeper than any
    // standard thread (an NPT's 0.8·P and a Whitworth's 0.64·P passed the 0.625·P taken before,
    // so the neck cut their crests flat).
    let tooth_depth = t.fundamental_height();
    notes.push(format!(
        "the cutter's tooth is taken as deep as the thread's fundamental triangle, H = P/(2·tan(α/2)) = {} mm below its tip (a named default; deeper than the thread, its neck never reaches it)",
        crate::ground::fmt::fmt_num((tooth_depth * 1e4).round() / 1e4)
    ));
    let neck = (0.5 * c.diameter - tooth_depth).max(0.0);
    let sweep = Sweep { hs: &hs, c: &c, neck, internal };
    let z_mid = section_middle(&sweep, p, taper, &first, name)?;
    let (zs, profile, tooth) = cut_sections(&sweep, blank, taper, z_mid, p, &first, name)?;
    let (measured, tooth_m, phases) = measure_sections(
        &sweep,
        (&profile, &tooth),
        &des,
        kind,
        &limits,
        taper,
        z_mid,
        &first,
        name,
        &mut notes,
    )?;
    // A taper thread's cone: the gauge plane from the pitch diameter measured at Z{z_mid}, the
    // taper from the helices' spiral (the diameter's change per mm of depth).
    let cone = taper.map(|(gp, _, _)| {
        let (dr, dz) = hs.iter().fold((0.0, 0.0), |(r, z), h| (r + h.radius_change, z + (h.z[1] - h.z[0])));
        let measured_taper =
            if dz.abs() > 1e-12 { 2.0 * dr / dz * if internal { 1.0 } else { -1.0 } } else { 0.0 };
        crate::analysis::taper::cone_of(gp, kind, z_mid, measured.pitch_diameter, measured_taper, p)
    });
    let mut cs = checks(&measured, &limits, &t, kind, measured.root_pockets <= 1, cone);
    process_checks(&mut cs, &hs, &phases, &des, c, &limits, &mut notes);
    if hs.iter().any(|h| !h.climb) {
        notes.push("conventional milling on some helices (climb milling wants G3 for a nut, G2 for a bolt, spindle M3)".into());
    }
    let radii: Vec<f64> = {
        let mut r: Vec<f64> = hs.iter().map(|h| h.radius).collect();
        r.sort_by(f64::total_cmp);
        r.dedup_by(|a, b| (*a - *b).abs() < 1e-6);
        r
    };
    if radii.len() > 1 && taper.is_none() {
        let steps: Vec<String> = radii.windows(2).map(|w| format!("{:.4}", w[1] - w[0])).collect();
        notes.push(format!(
            "{} radial passes; radial engagement between them {} mm",
            radii.len(),
            steps.join(", ")
        ));
        cs.push(radial_depth_check(&t, kind, blank, 0.5 * c.diameter, &radii, limits.resolution));
    }
    let ratio = c.diameter / t.nominal_diameter;
    if ratio > 0.7 {
        notes.push(format!(
            "the cutter is {:.0} % of the thread's diameter: tool makers advise under 70 %, above it the profile distortion grows fast",
            100.0 * ratio
        ));
    }
    let feeds = edge_feeds(&hs, &prog.moves, t.nominal_diameter, c.diameter, kind, spec.teeth);
    // The moves after the last helix against the finished crest (a straight thread's: a taper
    // thread's crest is not one radius, and is not judged).
    let crest = match kind {
        ThreadKind::Internal => 0.5 * measured.minor_diameter,
        ThreadKind::External => 0.5 * measured.major_diameter,
    };
    let (after_finish, crossings) = if taper.is_none() {
        (
            crate::analysis::gouge::after_finish(&prog.moves, &hs, kind, 0.5 * c.diameter, crest),
            crate::analysis::gouge::crossing_helices(&hs, t.lead(), t.hand, kind, 0.5 * c.diameter, crest),
        )
    } else {
        (crate::analysis::gouge::AfterFinish::default(), Vec::new())
    };
    let unfed: Vec<String> = hs.iter().filter(|h| h.feed.is_none()).map(|h| h.line.to_string()).collect();
    if !unfed.is_empty() {
        notes.push(format!(
            "no feed is known for the helix at line {} (no F before it, or F per revolution with no spindle speed): its edge feed is not computed",
            unfed.join(", ")
        ));
    }
    // A move after the last helix that cuts the finished thread scraps it, whatever the
    // helices measured.
    let pass =
        crate::analysis::check::verdict(&cs, false) && after_finish.gouges.is_empty() && crossings.is_empty();
    let span = (zs[0], zs[zs.len() - 1]);
    let (basic, zone) = crate::analysis::picture::Zone {
        thread: &t,
        kind,
        limits: &limits,
        groove_center: measured.groove_center,
    }
    .profiles(span);
    let dist_d2 = (measured.pitch_diameter - tooth_m.pitch_diameter) * 1000.0;
    let dist_fl = [
        measured.flank_angles[0] - tooth_m.flank_angles[0],
        measured.flank_angles[1] - tooth_m.flank_angles[1],
    ];
    Ok(ThreadMillReport {
        program: name.clone(),
        designation: des.text.clone(),
        named,
        kind,
        units: if t.form.is_inch() {
            crate::analysis::turn::Units::Inch
        } else {
            crate::analysis::turn::Units::Mm
        },
        cutter: c,
        cutter_ratio: ratio,
        helices: hs,
        feeds,
        after_finish,
        crossings,
        thread_percent: match kind {
            ThreadKind::Internal => crate::analysis::percent::thread_percent(&t, blank),
            ThreadKind::External => None,
        },
        blank_diameter: blank,
        measured,
        tooth_profile: tooth_m,
        distortion_pitch_diameter_um: dist_d2,
        distortion_flank_angles_deg: dist_fl,
        limits,
        checks: cs,
        pass,
        notes: notes.into_iter().map(crate::ground::note::Note::from).collect(),
        widening_um: profile.iter().zip(&tooth).map(|(a, b)| (a.z, (a.r - b.r).abs() * 1000.0)).collect(),
        profile,
        tooth_points: tooth,
        basic,
        zone,
    })
}

/// The cutter of the helices: the one given, else the thread mill the program's comments name for
/// the first helix's tool, else the tool table's; and that tool.
fn cutter_of(
    spec: &ThreadMillSpec,
    prog: &crate::gcode::Program,
    notes: &mut Vec<String>,
) -> Result<(Cutter, Option<u32>), Error> {
    let text = &spec.program.0;
    // The tool of the first helix: its cutter and its compensation from the table.
    let first_helix = prog.moves.iter().find(|m| m.arc.is_some() && (m.to[2] - m.from[2]).abs() > 1e-9);
    let first_tool = first_helix.and_then(|m| m.tool);
    // Else the thread mill the program's comments name for that tool.
    let commented = match (spec.cutter, first_helix) {
        (None, Some(m)) => cutter_in_comments(text, spec.dialect, spec.tools.as_ref(), m),
        _ => None,
    };
    let c = match (spec.cutter, &spec.tools, commented) {
        (Some(c), _, _) => c,
        (None, _, Some(found)) => {
            notes.push(found.note(first_tool.unwrap_or(0)));
            found.cutter
        }
        (None, Some(tt), None) => {
            let t = first_tool.ok_or_else(|| {
                Error::Input(
                    "the program names no tool before its helices: give the cutter (‹cutter_diameter›)"
                        .into(),
                )
            })?;
            match tt.tool(t) {
                Some((crate::analysis::tools::Tool::Insert(crate::analysis::tools::InsertChoice::File(p)), _)) => {
                    let text = crate::ground::input::read_text_bounded(p, crate::ground::bounds::MAX_DATA_FILE_BYTES, "a thread mill's file")?;
                    Cutter::from_toml(&text, &p.display().to_string())?
                }
                Some((crate::analysis::tools::Tool::Insert(crate::analysis::tools::InsertChoice::Toml { name, text }), _)) => {
                    Cutter::from_toml(text, name)?
                }
                Some((_, written)) => {
                    return Err(Error::Input(format!(
                        "tool T{t} is \"{written}\" in {}, not a thread mill's file (write {t} = \"thread-mill.toml\")",
                        tt.source
                    )))
                }
                None => return Err(Error::Input(format!("tool T{t} of the helices is not in {}", tt.source))),
            }
        }
        (None, None, None) => {
            return Err(Error::Input(match first_tool {
                Some(t) => format!("give the cutter: ‹cutter_diameter›, a tool table (‹tools›), or a comment naming T{t} a thread mill, such as (T{t} THREAD MILL D8)"),
                None => "give the cutter: ‹cutter_diameter› or a tool table (‹tools›)".into(),
            }))
        }
    };
    Ok((c, first_tool))
}

/// The cutter checked, and the compensation the helices are read with: the one given, a TNC's
/// tool radius, else the tool table's offset.
fn compensation(
    spec: &ThreadMillSpec,
    prog: &crate::gcode::Program,
    c: Cutter,
    first_tool: Option<u32>,
    notes: &mut Vec<String>,
) -> Result<Option<f64>, Error> {
    // A TNC compensates RL/RR by the tool table's radius, which is the cutter's: a Klartext
    // program's helices (its thread-milling cycles' among them) need no D register.
    let tnc = spec.dialect == crate::gcode::Dialect::Klartext;
    let tnc_comp = (tnc && spec.comp_radius.is_none() && prog.moves.iter().any(|m| m.comp != 0)).then(|| {
        notes.push(format!(
            "RL/RR compensate by the cutter's radius, {} mm, as a TNC takes it from its tool table (‹comp_radius› gives another)",
            crate::ground::fmt::fmt_num(0.5 * c.diameter)
        ));
        0.5 * c.diameter
    });
    let comp = match (spec.comp_radius.or(tnc_comp), &spec.tools, first_tool) {
        (Some(d), _, _) => Some(d),
        (None, Some(tt), Some(t)) => Some(tt.offset(t).unwrap_or_else(|| {
            if prog.moves.iter().any(|m| m.comp != 0) {
                notes.push(format!(
                    "no [offsets] entry for T{t} in {}: the compensation is taken as 0.0 mm",
                    tt.source
                ));
            }
            0.0
        })),
        _ => None,
    };
    if !(c.diameter.is_finite() && c.diameter > 0.0 && c.diameter < 1000.0) {
        return Err(Error::Input(format!("cutter diameter {} mm: a positive length under 1 m", c.diameter)));
    }
    if !(c.angle_deg.is_finite() && c.angle_deg > 0.0 && c.angle_deg < 180.0) {
        return Err(Error::Input(format!("cutter angle {}°: from over 0 to under 180", c.angle_deg)));
    }
    if !(c.tip_radius.is_finite() && c.tip_radius >= 0.0 && c.tip_radius < 0.5 * c.diameter) {
        return Err(Error::Input(format!(
            "cutter tip radius {} mm: from 0 to under the cutter's radius",
            c.tip_radius
        )));
    }
    if let Some(d) = comp.filter(|d| !(d.is_finite() && *d >= 0.0)) {
        return Err(Error::Input(format!("compensation {d} mm must be a length ≥ 0")));
    }
    Ok(comp)
}

/// The helices and the thread they mill: its designation (given, else named from the program),
/// the side it is on and its class's limits.
#[allow(clippy::type_complexity)]
fn thread_of(
    spec: &ThreadMillSpec,
    prog: &crate::gcode::Program,
    c: Cutter,
    comp: Option<f64>,
    opts: ParseOptions,
    notes: &mut Vec<String>,
) -> Result<
    (Vec<Helix>, crate::analysis::naming::Named, crate::standards::Designation, ThreadKind, ThreadLimits),
    Error,
> {
    let (text, name) = &spec.program;
    // The helices, read once: the thread's name may come from them.
    let hs = helices(&prog.moves, name, comp, notes)?;
    let named = match &spec.designation {
        Some(d) => crate::analysis::naming::Named::given(d.clone()),
        None => name_milled(text, spec.dialect, &prog.moves, &hs, (c.diameter, c.angle_deg), opts, name)?,
    };
    if !named.why.is_empty() {
        notes.push(named.why.clone());
    }
    let des = named.designation.clone();
    let kind = match (&des.external, &des.internal) {
        (None, Some(_)) => ThreadKind::Internal,
        (Some(_), None) | (None, None) => ThreadKind::External,
        // Both sides named (an NPT size, `6H/6g`): the side the helices cut, inside the
        // thread's diameter or outside it.
        (Some(_), Some(_)) => {
            let inside = hs.first().is_some_and(|h| 2.0 * h.radius < des.thread.nominal_diameter);
            let kind = if inside { ThreadKind::Internal } else { ThreadKind::External };
            notes.push(format!(
                "{} names both sides: the helices run {} its diameter, so its {} thread is checked",
                des.text,
                if inside { "inside" } else { "outside" },
                kind.name()
            ));
            kind
        }
    };
    let limits =
        limits_for(&des, kind)?.ok_or_else(|| Error::Input("the designation needs its class".into()))?;
    Ok((hs, named, des, kind, limits))
}

/// The helices as they are swept: on circles (a spiral for a taper thread), the compensation on
/// its side, climb milling marked; and the first.
#[allow(clippy::too_many_arguments)]
fn prepared_helices(
    hs: Vec<Helix>,
    taper: Option<crate::analysis::taper::Taper>,
    moves: &[Move],
    comp: Option<f64>,
    c: Cutter,
    internal: bool,
    name: &str,
    notes: &mut Vec<String>,
) -> Result<(Vec<Helix>, Helix), Error> {
    let mut hs = match taper {
        Some(_) => {
            notes.push(crate::analysis::taper::TAPER_FACE_NOTE.into());
            if hs.iter().any(|h| h.radius_change != 0.0) {
                notes.push("each helix arc whose end lies off its start's circle is swept as a spiral, its radius linear in the angle (a named reading: the controls' spiral interpolation)".into());
            }
            hs
        }
        None => circular(hs, name, notes)?,
    };
    notes.extend(entry_and_exit(moves, &hs));
    if let Some(d) = comp {
        if hs.iter().any(|h| (h.radius - h.programmed_radius).abs() > 1e-12)
            && (d - 0.5 * c.diameter).abs() > 1e-3
        {
            notes.push(format!(
                "the compensation {d} mm is not the cutter's radius {} mm: the helix radius follows the D register, and so does the thread",
                crate::ground::fmt::fmt_num(0.5 * c.diameter)
            ));
        }
    }
    // Compensation on the wrong side: an internal thread is milled with the cutter's centre
    // inside its programmed path (G41 with G3, G42 with G2), an external one outside it.
    if let Some(h) = hs.iter().find(|h| {
        let out = h.radius - h.programmed_radius;
        if internal {
            out > 1e-9
        } else {
            out < -1e-9
        }
    }) {
        return Err(Error::Program {
            file: name.to_string(),
            line: h.line,
            column: 1,
            message: format!(
                "the compensation puts the cutter's centre {} mm {} the programmed helix (radius {} mm), {}: {}",
                crate::ground::fmt::fmt_num((h.radius - h.programmed_radius).abs()),
                if internal { "outside" } else { "inside" },
                crate::ground::fmt::fmt_num(h.programmed_radius),
                if internal { "into the bore's wall" } else { "into the blank" },
                if internal {
                    "an internal thread is milled with the cutter inside its path (G41 with G3, G42 with G2)"
                } else {
                    "an external thread is milled with the cutter outside its path (G42 with G3, G41 with G2)"
                }
            ),
        });
    }
    let Some(first) = hs.first().cloned() else {
        return Err(Error::Program {
            file: name.to_string(),
            line: 1,
            column: 1,
            message: "no helix in the program (G2/G3 with a Z change in G17): nothing is thread-milled"
                .into(),
        });
    };
    // Climb milling (spindle clockwise): an internal thread's cutter goes counter-clockwise
    // (G3), an external one's clockwise (G2).
    for h in &mut hs {
        h.climb = (h.sweep_deg > 0.0) == internal;
    }
    Ok((hs, first))
}

/// The bore (internal) or blank (external) diameter: the one given, else the middle of the
/// class's D1 or d limits.
fn blank_of(
    given: Option<f64>,
    limits: &ThreadLimits,
    t: &crate::standards::BasicThread,
    internal: bool,
    notes: &mut Vec<String>,
) -> Result<f64, Error> {
    let blank = match given {
        Some(b) if !(b.is_finite() && b > 0.0) => {
            return Err(Error::Input(format!("blank diameter {b} mm must be positive")))
        }
        Some(b) => b,
        None => {
            let lim = if internal { limits.minor_diameter } else { limits.major_diameter };
            let (b, from) = match (lim.min, lim.max) {
                (Some(a), Some(b)) => (0.5 * (a + b), "the middle of the class's"),
                (Some(a), None) | (None, Some(a)) => (a, "the class's"),
                // A taper thread: the basic cone's diameter at its gauge plane, a cylinder (as
                // `verify` turns it).
                (None, None) if internal => {
                    (t.minor_diameter_internal(), "a cylinder at the gauge plane's basic")
                }
                (None, None) => (t.nominal_diameter, "a cylinder at the gauge plane's basic"),
            };
            notes.push(format!(
                "the {} is taken as Ø{b:.4}, {from} {}{} (‹blank_diameter› sets it)",
                if internal { "bore" } else { "blank" },
                if internal { "D1" } else { "d" },
                if lim.min.is_some() && lim.max.is_some() {
                    " limits"
                } else if lim.min.is_some() || lim.max.is_some() {
                    " limit"
                } else {
                    ""
                }
            ));
            b
        }
    };
    Ok(blank)
}

/// The height the section is measured about: the helices' middle, or a taper thread's gauge
/// point; refused when the helices span under four pitches or miss a taper's gauge point.
fn section_middle(
    sweep: &Sweep,
    p: f64,
    taper: Option<crate::analysis::taper::Taper>,
    first: &Helix,
    name: &str,
) -> Result<f64, Error> {
    let (hs, c, internal) = (sweep.hs, sweep.c, sweep.internal);
    // The section: around the helices' middle height, a whole number of leads from a crossing.
    // A multi-form cutter's rows reach `span` above the helices.
    let z_lo = hs.iter().map(|h| h.z[0].min(h.z[1])).fold(f64::INFINITY, f64::min);
    let z_hi = hs.iter().map(|h| h.z[0].max(h.z[1])).fold(f64::NEG_INFINITY, f64::max) + c.span();
    if z_hi - z_lo < 4.0 * p {
        return Err(Error::Program {
            file: name.to_string(),
            line: first.line,
            column: 1,
            message: format!(
                "the helices (and the cutter's rows) span {:.3} mm of Z, under the four pitches ({:.3} mm) a groove is measured in{}",
                z_hi - z_lo,
                4.0 * p,
                if c.rows == 1 {
                    // A comb (multi-form) cutter's rows each cut the thread a row pitch higher.
                    format!(
                        "; if the cutter is a comb (multi-form) one, its rows reach higher: give them (‹cutter_rows› and ‹cutter_row_pitch› {}, or rows and row_pitch in the thread mill's file)",
                        crate::ground::fmt::fmt_num(p)
                    )
                } else {
                    String::new()
                }
            ),
        });
    }
    // A taper thread is measured where its gauge would read it (the face at Z0), which the
    // helices must cut two pitches either side of.
    let z_mid = match taper {
        Some((_, z_meas, _)) => {
            if z_meas - 2.0 * p < z_lo - 1e-9 || z_meas + 2.0 * p > z_hi + 1e-9 {
                return Err(Error::Program {
                    file: name.to_string(),
                    line: first.line,
                    column: 1,
                    message: format!(
                        "the helices (and the cutter's rows) span Z{} to Z{}: a taper thread is measured at Z{} ({}, the face taken at Z0), which they do not reach two pitches ({} mm) either side of",
                        crate::ground::fmt::fmt_num(z_lo),
                        crate::ground::fmt::fmt_num(z_hi),
                        crate::ground::fmt::fmt_num(z_meas),
                        if internal { "four pitches into the fitting" } else { "the gauge plane, L1 from the small end" },
                        crate::ground::fmt::fmt_num(2.0 * p)
                    ),
                });
            }
            z_meas
        }
        None => 0.5 * (z_lo + z_hi),
    };
    Ok(z_mid)
}

/// The axial sections the helices leave (the whole cutter's and its tooth's at the helices'
/// own phase alone), four pitches about `z_mid`, their cost bounded first.
#[allow(clippy::type_complexity)]
fn cut_sections(
    sweep: &Sweep,
    blank: f64,
    taper: Option<crate::analysis::taper::Taper>,
    z_mid: f64,
    p: f64,
    first: &Helix,
    name: &str,
) -> Result<(Vec<f64>, Vec<Point>, Vec<Point>), Error> {
    let (hs, c, neck, internal) = (sweep.hs, sweep.c, sweep.neck, sweep.internal);
    let n = 1600usize;
    let zs: Vec<f64> = (0..=n).map(|i| z_mid - 2.0 * p + 4.0 * p * i as f64 / n as f64).collect();
    // The section's cost is counted before it is cut (10 000 one-turn helices stacked
    // 0.0006 mm apart took 372 s): the helix pieces and turns that reach each height.
    let bound = 0.5 * blank;
    let beyond = bound;
    let cost = section_cost(hs, c, neck, &zs, internal, beyond);
    if !(cost <= crate::ground::bounds::MAX_SECTION_EVALS as f64) {
        return Err(Error::Program {
            file: name.to_string(),
            line: first.line,
            column: 1,
            message: format!(
                "{} helices from here cut the measured section: cutting it takes {} evaluations of the cutter's reach, more than the {} threadcheck allows (about a second)",
                hs.len(),
                crate::ground::fmt::fmt_shown((cost / 1e6).round() * 1e6),
                crate::ground::fmt::fmt_shown(crate::ground::bounds::MAX_SECTION_EVALS as f64)
            ),
        });
    }
    let section = |only_psi0: bool| -> Vec<Point> {
        zs.par_iter()
            .map(|&z| {
                let r = reach(hs, c, neck, z, internal, only_psi0, beyond);
                let v = match (r, internal) {
                    (Some(r), true) => r.max(bound),
                    (Some(r), false) => r.min(bound),
                    (None, _) => bound,
                };
                // A taper thread's section sheared level along its cone (its pitch line level).
                Point::new(z, v - taper.map_or(0.0, |(_, _, slope)| slope * (z - z_mid)))
            })
            .collect()
    };
    let profile = section(false);
    let tooth = section(true);
    Ok((zs, profile, tooth))
}

/// The milled thread and the tooth profile measured, their root radii from the exact reach, a
/// taper thread's flanks as they stand to the axis; and the helices' starts.
#[allow(clippy::too_many_arguments)]
fn measure_sections(
    sweep: &Sweep,
    (profile, tooth): (&[Point], &[Point]),
    des: &crate::standards::Designation,
    kind: ThreadKind,
    limits: &ThreadLimits,
    taper: Option<crate::analysis::taper::Taper>,
    z_mid: f64,
    first: &Helix,
    name: &str,
    notes: &mut Vec<String>,
) -> Result<(Measurement, Measurement, Vec<f64>), Error> {
    let (hs, c, neck, internal) = (sweep.hs, sweep.c, sweep.neck, sweep.internal);
    let t = des.thread;
    let ms = match taper {
        // A taper thread's maximum material is its gauge plane's, not a parallel profile's.
        Some(_) => MeasureSetup { mmc_pitch_diameter: None, ..MeasureSetup::for_class(&t, kind, limits) },
        None => MeasureSetup::for_class(&t, kind, limits),
    };
    // A section that holds no thread to measure is the helices' fault: said at their first line,
    // with the starts they cut when the designation has more.
    let phases = start_phases(hs, t.lead());
    let at_helices = |e: Error| match e {
        Error::Geometry(m) => {
            let starts = if (phases.len() as u32) < t.starts {
                format!(
                    "; the helices cut {} of the {} starts {} has, a pitch ({} mm) apart",
                    phases.len(),
                    t.starts,
                    des.text,
                    crate::ground::fmt::fmt_num(t.pitch)
                )
            } else {
                String::new()
            };
            Error::Program {
                file: name.to_string(),
                line: first.line,
                column: 1,
                message: format!("the thread the helices from here mill cannot be measured: {m}{starts}"),
            }
        }
        e => e,
    };
    let mut measured = measure(&ms, profile, z_mid).map_err(at_helices)?;
    let mut tooth_m = measure(&ms, tooth, z_mid).map_err(at_helices)?;
    // The root radius is the envelope's own curvature at its deepest point, from the exact reach
    // (the sampled section's 3.75 µm spacing cannot resolve a root of a few µm).
    let root_of = |pts: &[Point], only_psi0: bool| -> Option<f64> {
        let deepest = |p: &&Point| if internal { p.r } else { -p.r };
        let near: Vec<&Point> = pts.iter().filter(|p| (p.z - z_mid).abs() <= 0.5 * t.pitch).collect();
        let at = near.iter().copied().max_by(|a, b| deepest(a).total_cmp(&deepest(b)))?;
        let r_at = |z: f64| {
            reach(
                hs,
                c,
                neck,
                z,
                internal,
                only_psi0,
                if internal { f64::NEG_INFINITY } else { f64::INFINITY },
            )
            .map(|r| if internal { r } else { -r })
        };
        let dz = 4.0 * t.pitch / 1600.0;
        let (z0, _) = crate::geometry::measure::golden_min(
            &|z| r_at(z).map_or(f64::INFINITY, |r| -r),
            at.z - dz,
            at.z + dz,
            80,
        );
        let radius = |h: f64| -> Option<f64> {
            let (r0, rp, rm) = (r_at(z0)?, r_at(z0 + h)?, r_at(z0 - h)?);
            let second = (rp + rm - 2.0 * r0) / (h * h);
            (second < 0.0).then(|| 1.0 / -second)
        };
        // A corner (a sharp tooth's tip alone) gives a "radius" that halves with the step: 0.
        let (a, b) = (radius(2e-4)?, radius(1e-4)?);
        Some(if b < 0.75 * a { 0.0 } else { b })
    };
    if let Some((_, _, slope)) = taper {
        // The flanks as they stand to the axis (the section was sheared level along the cone).
        measured.flank_angles = crate::analysis::taper::true_flank_angles(measured.flank_angles, slope, kind);
        tooth_m.flank_angles = crate::analysis::taper::true_flank_angles(tooth_m.flank_angles, slope, kind);
        notes.push("taper thread: measured along its cone (the section sheared level by the taper), the flank angles as they stand to the axis".into());
    }
    measured.root_radius = root_of(profile, false).or(measured.root_radius);
    tooth_m.root_radius = root_of(tooth, true).or(tooth_m.root_radius);
    notes.push("the root radius is the envelope's curvature at its deepest point, from the cutter's exact reach (0.1 µm either side; 0 where it is a corner)".into());
    Ok((measured, tooth_m, phases))
}

/// The process checks of the helices: the lead of each turn, the starts, the hand, a comb
/// cutter's row pitch.
fn process_checks(
    cs: &mut Vec<Check>,
    hs: &[Helix],
    phases: &[f64],
    des: &crate::standards::Designation,
    c: Cutter,
    limits: &ThreadLimits,
    notes: &mut Vec<String>,
) {
    let t = des.thread;
    let p = t.pitch;
    // The lead each turn cuts against the designation's, at the program's resolution.
    let lead_err =
        turn_leads(hs)
            .iter()
            .map(|(_, l)| l - t.lead())
            .fold(0.0f64, |a, e| if e.abs() > a.abs() { e } else { a });
    // Sums of rounded Z travels: nanometres are the arithmetic's, not the program's.
    let lead_err = (lead_err * 1e9).round() / 1e9;
    let lead_ok = lead_err.abs() <= 0.0005 + 1e-9;
    cs.push(Check {
        feature: crate::analysis::check::CheckFeature::Lead,
        kind: crate::analysis::check::CheckKind::Process,
        value: t.lead() + lead_err,
        min: Some(t.lead()),
        max: Some(t.lead()),
        ok: lead_ok,
        deviation_um: if lead_ok { 0.0 } else { (lead_err * 1e4).round() / 10.0 },
        note: Some("the Z travel of each turn of the helices against the designation's lead".into()),
        unverified: None,
    });
    // The starts: each helix's Z where it crosses the +X half-plane, modulo the lead; a
    // multi-start thread's starts lie a pitch apart (issue 46).
    if t.starts > 1 || phases.len() > 1 {
        cs.push(starts_of(phases, &t));
    }
    // The hand: in G17, looking down the tool axis, a right-hand helix turns counter-clockwise
    // (G3) rising or clockwise (G2) falling, inside a bore or outside a blank alike
    // (../shared/notes/machining-centres.md §3.2, after Heidenhain's helix table).
    let hand_of = |h: &crate::geometry::helix::Helix| {
        if (h.z[1] > h.z[0]) == (h.sweep_deg > 0.0) {
            crate::standards::Hand::Right
        } else {
            crate::standards::Hand::Left
        }
    };
    let other_hand = hs.iter().find(|h| hand_of(h) != t.hand);
    cs.push(Check {
        feature: crate::analysis::check::CheckFeature::Hand,
        kind: crate::analysis::check::CheckKind::Size,
        value: if other_hand.is_none() { 1.0 } else { 0.0 },
        min: None,
        max: None,
        ok: other_hand.is_none(),
        deviation_um: 0.0,
        note: Some(match other_hand {
            None => format!(
                "every helix cuts a {}-hand thread, the designation's",
                crate::standards::Hand::name(t.hand)
            ),
            Some(h) => format!(
                "the helix at line {} turns {} going {} in Z: a {}-hand thread, the designation {} is {}-hand",
                h.line,
                if h.sweep_deg > 0.0 { "counter-clockwise (G3)" } else { "clockwise (G2)" },
                if h.z[1] > h.z[0] { "up" } else { "down" },
                crate::standards::Hand::name(hand_of(h)),
                des.text,
                crate::standards::Hand::name(t.hand)
            ),
        }),
        unverified: None,
    });
    if c.rows > 1 {
        // Each row cuts the groove its neighbour cuts one pitch along: the rows must lie a pitch
        // apart, at the standard's resolution.
        let off = c.row_pitch - p;
        let ok = limits.resolution.round(c.row_pitch) == limits.resolution.round(p);
        cs.push(Check {
            feature: crate::analysis::check::CheckFeature::RowPitch,
            kind: crate::analysis::check::CheckKind::Process,
            value: c.row_pitch,
            min: Some(p),
            max: Some(p),
            ok,
            deviation_um: if ok { 0.0 } else { (off * 1e4).round() / 10.0 },
            note: Some(format!(
                "the {} rows of the multi-form cutter must lie one pitch apart; each cuts its neighbour's groove",
                c.rows
            )),
            unverified: None,
        });
        notes.push(format!(
            "a multi-form cutter of {} rows {} mm apart, the first at the programmed point and the others above it (a named default)",
            c.rows,
            crate::ground::fmt::fmt_num(c.row_pitch)
        ));
    }
}

/// What sweeps the section: the helices, the cutter, its neck's radius and the thread's side.
struct Sweep<'a> {
    hs: &'a [Helix],
    c: &'a Cutter,
    neck: f64,
    internal: bool,
}

/// The radial passes' depths from the bore (internal) or blank (external) against the thread's
/// depth (issues 63 and 64: a generator whose last increment went 3 mm deep for a 2.5 mm thread):
/// the deepest pass, the cutter's tip reach `rho` beyond its helix radius, may reach the
/// fundamental triangle's root (D2 + H internal, d2 − H external: past it no flank of the
/// profile's angle is left where the class wants it) and not beyond, at the standard's
/// resolution. `radii` ascending.
fn radial_depth_check(
    t: &crate::standards::BasicThread,
    kind: ThreadKind,
    blank: f64,
    rho: f64,
    radii: &[f64],
    resolution: crate::standards::tolerance::Resolution,
) -> Check {
    let h = t.fundamental_height();
    let (depths, root): (Vec<f64>, f64) = match kind {
        ThreadKind::Internal => {
            (radii.iter().map(|r| r + rho - 0.5 * blank).collect(), 0.5 * (t.pitch_diameter() + h - blank))
        }
        ThreadKind::External => (
            radii.iter().rev().map(|r| 0.5 * blank - (r - rho)).collect(),
            0.5 * (blank - (t.pitch_diameter() - h)),
        ),
    };
    let deepest = depths.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let ok = resolution.round(deepest) <= resolution.round(root);
    let shown: Vec<String> = depths.iter().map(|d| format!("{d:.4}")).collect();
    Check {
        feature: crate::analysis::check::CheckFeature::RadialDepth,
        kind: crate::analysis::check::CheckKind::Process,
        value: deepest,
        min: None,
        max: Some(root),
        ok,
        deviation_um: if ok { 0.0 } else { ((deepest - root) * 1e4).round() / 10.0 },
        note: Some(format!(
            "the passes reach {} mm {} the {} Ø{blank:.4}; the thread is {root:.4} mm deep there to its fundamental triangle's root ({}), the deepest any pass may go{}",
            shown.join(", "),
            if kind == ThreadKind::Internal { "past" } else { "into" },
            if kind == ThreadKind::Internal { "bore" } else { "blank" },
            if kind == ThreadKind::Internal { "D2 + H" } else { "d2 − H" },
            if ok { "" } else { ": the last pass cuts deeper than the thread" }
        )),
        unverified: None,
    }
}
