//! A program's turned threads: each operation named, its side and diameters weighed against
//! what the user gave, its insert (given or assumed), verified.

use super::core::*;
use super::passes::*;
use super::resolve::*;
use super::spec::*;
use crate::analysis::check::verdict;
use crate::analysis::tools::InsertChoice;
use crate::standards::ThreadKind;
use crate::toolpath::passes::Pass;
use crate::Error;

/// What became of one operation of a program.
#[derive(Clone, Debug)]
pub enum OperationResult {
    /// Cut and measured.
    Verified(Box<Verification>),
    /// The passes never reach the material (or leave no groove to measure): a failing verdict
    /// with the reason.
    NoCut {
        /// Why nothing could be measured.
        reason: String,
        /// The last pass's X that cuts the thread mid-tolerance with this insert from this blank
        /// (a generated plan's, solved as `verify` without a program solves it), mm; `None` when
        /// that plan cannot be cut either.
        suggested_final_x: Option<f64>,
    },
}

impl OperationResult {
    /// Whether the operation passes.
    pub fn pass(&self) -> bool {
        match self {
            OperationResult::Verified(v) => v.pass,
            OperationResult::NoCut { .. } => false,
        }
    }
}

/// One operation of a program and its result.
#[derive(Clone, Debug)]
pub struct OperationVerdict {
    /// The operation as the program cuts it.
    pub operation: crate::gcode::Operation,
    /// The designation it was verified against: where it came from (given, a comment,
    /// inferred) and how it was read.
    pub named: crate::analysis::naming::Named,
    /// The verdict.
    pub result: OperationResult,
}

/// Verifies one operation of a program read already: the insert and designation come from
/// `spec` (its `program` is ignored).
pub fn verify_operation(
    spec: &VerifySpec,
    op: &crate::gcode::Operation,
    label: &ProgramLabel,
) -> Result<OperationResult, Error> {
    let mut r = resolve(spec)?;
    let side = if r.kind == ThreadKind::External { "blank" } else { "bore" };
    let mut blank_from = match spec.blank_diameter {
        Some(_) => format!("the {side} as given (‹blank_diameter›, or the stock the program declares)"),
        None => format!(
            "the default {side}: no feed move of the program turns the thread's stretch (‹blank_diameter› gives it)"
        ),
    };
    if spec.blank_diameter.is_none() {
        if let Some((d, line)) = program_blank(op, r.kind) {
            r.blank = d;
            blank_from = format!("the {side} the program's moves leave, turned at line {line}");
            r.notes.push(crate::ground::note::Note::at(
                &label.file,
                line,
                1,
                format!(
                    "the {} is the program's own: Ø{d:.4}, the material its moves leave over the thread, turned here (‹blank_diameter› overrides)",
                    if r.kind == ThreadKind::External { "blank" } else { "bore" },
                ),
            ));
        }
    }
    match verify_given(&r, op, label) {
        Ok(v) => Ok(OperationResult::Verified(Box::new(v))),
        Err(Error::Geometry(m)) => {
            let plan = VerifySpec {
                program: None,
                operation: None,
                final_x: None,
                blank_diameter: Some(r.blank),
                metrics: false,
                picture: false,
                machine: None,
                designation: Some(r.designation.clone()),
                ..spec.clone()
            };
            // Passes nowhere near the designation's size: no final X is offered (it would plunge
            // to another thread's diameter); the reason names both.
            if let Some((_, misfit)) = diameter_misfit(&r, op, &op.passes) {
                return Ok(OperationResult::NoCut {
                    reason: format!("{m}; {blank_from}; {misfit}: no correction is offered"),
                    suggested_final_x: None,
                });
            }
            let suggested_final_x = verify(&plan).ok().map(|v| v.final_x);
            Ok(OperationResult::NoCut { reason: format!("{m}; {blank_from}"), suggested_final_x })
        }
        Err(e) => Err(e),
    }
}

/// The side the passes cut (inward pass by pass from a bar, outward in a bore) must be the
/// designation's: a contradiction is refused at the operation's line, never verified as the
/// other side.
pub(super) fn side_agrees(
    r: &Resolved,
    op: &crate::gcode::Operation,
    passes: &[Pass],
    label: &ProgramLabel,
) -> Result<(), Error> {
    let (Some(first), last) = (passes.first(), last_head(passes)) else { return Ok(()) };
    let dx = last.x_end - first.x_end;
    if dx.abs() < 1e-6 {
        return Ok(());
    }
    let inward = dx < 0.0;
    let (cut, other) = match (r.kind, inward) {
        (ThreadKind::External, false) => ("outward pass by pass, as in a bore", "an internal class"),
        (ThreadKind::Internal, true) => ("inward pass by pass, as on a bar", "an external class"),
        // Passes that move the way the class's side cuts.
        (ThreadKind::External, true) | (ThreadKind::Internal, false) => return Ok(()),
    };
    Err(Error::Program {
        file: label.file.clone(),
        line: op.source_line,
        column: 1,
        message: format!(
            "{} is {} thread, but the passes of this {} move {cut} (X{:.4} to X{:.4}): give {other} or check the program",
            r.designation.text,
            if r.kind == ThreadKind::External { "an external" } else { "an internal" },
            op.cycle,
            first.x_end,
            last.x_end,
        ),
    })
}

/// How a refusal of a designation of another size ends (the inferred one is said after it).
pub(super) const MISFIT_END: &str = "check the thread";

/// Where the designation is not the thread the passes cut. Both sides of the profile are
/// compared, each against one thread depth on the radius (plus, on a taper, what the cone changes
/// over the pass and the nominal length): the deepest pass's tip against the designation's root
/// (d3 on a bar, D in a bore), and the crest side (the diameter the program turned or bored for
/// the thread, else its first pass) against its crest (d, D1). Off on both, the designation names
/// another size and no correction would be safe; off on the root alone, the program cuts this
/// size too deep or too shallow, which the checks show. The last pass's line and what to say,
/// naming both diameters.
pub(super) fn diameter_misfit(
    r: &Resolved,
    op: &crate::gcode::Operation,
    passes: &[Pass],
) -> Option<(Option<usize>, String)> {
    let t = &r.designation.thread;
    let last = last_head(passes);
    let final_x = 0.5 * (last.x_start.abs() + last.x_end.abs());
    let xs = passes.iter().map(|p| 0.5 * (p.x_start.abs() + p.x_end.abs()));
    let (root, root_name, crest, about, crest_side) = match r.kind {
        ThreadKind::External => (
            t.minor_diameter_external(),
            "d3",
            t.nominal_diameter,
            final_x + 2.0 * t.thread_depth(),
            program_blank(op, r.kind).map_or_else(|| xs.fold(f64::NEG_INFINITY, f64::max), |b| b.0),
        ),
        ThreadKind::Internal => (
            t.nominal_diameter,
            "D",
            t.minor_diameter_internal(),
            final_x,
            program_blank(op, r.kind).map_or_else(|| xs.fold(f64::INFINITY, f64::min), |b| b.0),
        ),
    };
    let cone = t.form.taper() * ((last.z_end - last.z_start).abs() + t.nominal_diameter);
    let margin = 2.0 * t.thread_depth() + cone;
    if (final_x - root).abs() <= margin || (crest_side - crest).abs() <= margin {
        return None;
    }
    Some((
        last.source_line,
        format!(
            "the passes cut about Ø{about:.1} (final X{:.3}), the designation {} is Ø{} ({root_name} {root:.3}): they differ by more than a thread depth; {MISFIT_END}",
            last.x_end,
            r.designation.text,
            crate::ground::fmt::fmt_num(t.nominal_diameter),
        ),
    ))
}

/// [`diameter_misfit`] as a refusal at the last pass's line.
pub(super) fn diameter_agrees(
    r: &Resolved,
    op: &crate::gcode::Operation,
    passes: &[Pass],
    label: &ProgramLabel,
) -> Result<(), Error> {
    match diameter_misfit(r, op, passes) {
        None => Ok(()),
        Some((line, message)) => Err(Error::Program {
            file: label.file.clone(),
            line: line.unwrap_or(op.source_line),
            column: 1,
            message: format!("{}: {message}", op.cycle),
        }),
    }
}

/// The diameter the program turned (or bored) for the thread before cutting it, and the line of
/// the move that left it: the material its feed moves leave over the finishing pass's Z span.
/// At each Z the moves that cover it bring the material down to their X (a bore: open it up to
/// their X), so a feed through the air at a larger diameter after the part was turned smaller
/// changes nothing, and a later cut to a smaller diameter (a roughing cycle's profile, a finishing
/// pass) replaces an earlier one; of that material's cylinders along at least a quarter of the
/// pass (a taper is a chamfer, or an approach from beyond the face; a shorter cylinder a nose or
/// a collar) the outermost (a bore: innermost) is the blank, so chamfers and a run-in beyond the
/// part's end do not hide the journal. Distances from the axis (a tool beyond it writes X negative). `None`
/// when no feed move covers the pass.
pub(super) fn program_blank(op: &crate::gcode::Operation, kind: ThreadKind) -> Option<(f64, usize)> {
    let passes = &op.passes;
    if passes.is_empty() {
        return None;
    }
    let last = last_head(passes);
    let (t0, t1) = (last.z_start.min(last.z_end), last.z_start.max(last.z_end));
    const EPS: f64 = 1e-9;
    // Moves along Z over the pass (a radial move, a face or a plunge, covers no length).
    let moves: Vec<&crate::gcode::Turned> = op
        .contour
        .iter()
        .filter(|t| {
            let (zl, zh) = (t.from[1].min(t.to[1]), t.from[1].max(t.to[1]));
            zh - zl > 1e-6 && zh >= t0 - EPS && zl <= t1 + EPS
        })
        .collect();
    if moves.is_empty() {
        return None;
    }
    // The material is piecewise linear between the moves' ends: it is looked at halfway
    // between each two.
    let mut zs: Vec<f64> = vec![t0, t1];
    zs.extend(moves.iter().flat_map(|t| [t.from[1], t.to[1]]).filter(|z| (t0..=t1).contains(z)));
    zs.sort_by(f64::total_cmp);
    zs.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    let external = kind == ThreadKind::External;
    // The thread's root: its deepest pass (the least X of a bolt's, the greatest of a nut's).
    // Only the surface on the thread's side of it is the blank: a bolt's material lies above
    // its root (a centre drill's X0 or a bore below it is not its blank), a nut's below (the
    // outside a part is turned to is not its bore).
    let xs = passes.iter().flat_map(|p| [p.x_start.abs(), p.x_end.abs()]);
    let root = if external { xs.fold(f64::INFINITY, f64::min) } else { xs.fold(0.0, f64::max) };
    // At one Z: the material's distance from the axis, the move that left it (of equal ones,
    // the last) and whether that move turned a cylinder. The surface on the thread's side of its
    // root first; only where there is none, the one on the other side nearest the root (a part
    // turned under a bolt's root: nothing is cut, and the message names that diameter).
    let material = |z: f64| -> Option<(f64, usize, bool)> {
        let mut best: Option<(f64, usize, bool)> = None;
        let mut beyond: Option<(f64, usize, bool)> = None;
        for t in &moves {
            let (za, zb) = (t.from[1], t.to[1]);
            if z < za.min(zb) - EPS || z > za.max(zb) + EPS {
                continue;
            }
            let f = ((z - za) / (zb - za)).clamp(0.0, 1.0);
            let x = (t.from[0] + f * (t.to[0] - t.from[0])).abs();
            let here = (x, t.line, (t.from[0] - t.to[0]).abs() < 1e-3);
            // On the axis: a drill's path, whose hole is the drill's diameter, not the path's.
            if x < 1e-3 {
                continue;
            }
            if (external && x <= root + 1e-6) || (!external && x >= root - 1e-6) {
                let nearer = match beyond {
                    None => true,
                    Some((b, _, _)) if external => x >= b - 1e-6,
                    Some((b, _, _)) => x <= b + 1e-6,
                };
                if nearer {
                    beyond = Some(here);
                }
                continue;
            }
            let deeper = match best {
                None => true,
                Some((b, _, _)) if external => x <= b + 1e-6,
                Some((b, _, _)) => x >= b - 1e-6,
            };
            if deeper {
                best = Some(here);
            }
        }
        best.or(beyond)
    };
    // The cylinders of that material and the length of the pass each runs along: a taper there
    // is a chamfer or an approach from beyond the part's face, and a cylinder along less than a
    // quarter of the pass (a nose, a collar) is not the diameter the thread is cut into.
    let mut cylinders: Vec<(f64, usize, f64)> = Vec::new();
    for w in zs.windows(2) {
        let Some((x, line, true)) = material(0.5 * (w[0] + w[1])) else { continue };
        match cylinders.iter_mut().find(|c| (c.0 - x).abs() < 1e-6) {
            Some(c) => {
                c.1 = line;
                c.2 += w[1] - w[0];
            }
            None => cylinders.push((x, line, w[1] - w[0])),
        }
    }
    let least = 0.25 * (t1 - t0);
    cylinders.into_iter().filter(|c| c.2 >= least - 1e-9).map(|(x, line, _)| (x, line)).reduce(|a, b| {
        if (external && b.0 > a.0 + 1e-6) || (!external && b.0 < a.0 - 1e-6) {
            b
        } else {
            a
        }
    })
}

/// One program operation verified; passes that cut nothing are an [`Error::Geometry`].
pub(super) fn verify_given(
    r: &Resolved,
    op: &crate::gcode::Operation,
    label: &ProgramLabel,
) -> Result<Verification, Error> {
    let passes = program_passes(op, &r.designation, &label.file)?;
    let mut notes: Vec<crate::ground::note::Note> = op.notes.clone();
    let mut lines = std::collections::BTreeMap::new();
    let off_helix = off_helix_segments(op, &r.designation.thread);
    for (p, _) in op.passes.iter().zip(off_helix).filter(|(_, off)| *off) {
        lines.entry(p.source_line.unwrap_or(0)).or_insert(p.lead);
    }
    for (line, lead) in lines {
        notes.push(crate::ground::note::Note::from(format!(
            "the taper segment at line {line} moves {} mm along Z per turn, not the thread's {} mm (a run-in or run-out steeper than 45° takes its F along X; a LinuxCNC G33 its K along the path): it leaves the helix, and where it still cuts, it cuts off the thread's last turns",
            crate::ground::fmt::fmt_num(lead),
            crate::ground::fmt::fmt_num(r.designation.thread.lead())
        )));
    }
    if let Some((angle, word)) = &op.infeed_angle {
        let half = 0.5 * r.insert.angle;
        if *angle > half + 1e-9 {
            notes.push(crate::ground::note::Note::from(format!(
                "infeed angle {word} = {angle}° is above half the insert angle ({half}°): each pass moves away from the trailing flank faster than the flank slopes, so the groove widens at the crest and the trailing flank is stepped"
            )));
        }
    }
    side_agrees(r, op, &passes, label)?;
    // The passes must reach the material: external below the blank, internal above the bore.
    let deepest = match r.kind {
        ThreadKind::External => passes.iter().map(|p| p.x_end.min(p.x_start)).fold(f64::INFINITY, f64::min),
        ThreadKind::Internal => {
            passes.iter().map(|p| p.x_end.max(p.x_start)).fold(f64::NEG_INFINITY, f64::max)
        }
    };
    let misses = match r.kind {
        ThreadKind::External => deepest >= r.blank,
        ThreadKind::Internal => deepest <= r.blank,
    };
    if misses {
        return Err(Error::Geometry(format!(
                "no pass reaches the {} Ø{:.4}: the deepest pass is at X{deepest:.4}, so nothing is cut (is the {} or the thread wrong?)",
                if r.kind == ThreadKind::External { "blank" } else { "bore" },
                r.blank,
                if r.kind == ThreadKind::External { "blank diameter" } else { "bore diameter" },
        )));
    }
    // Passes that cut the material but not near the designation's size: refused, never corrected.
    diameter_agrees(r, op, &passes, label)?;
    // The lead error adds up over the thread a gauge engages: the thread on the part (its face
    // taken at Z0, the part at Z ≤ 0: a named default), capped at the length of engagement.
    let last = last_head(&passes);
    let pass_length = (last.z_end - last.z_start).abs();
    let (za, zb) = (last.z_start.min(last.z_end), last.z_start.max(last.z_end));
    let on_part = if za < 0.0 { zb.min(0.0) - za } else { pass_length };
    let (engagement, basis) = match (r.spec.engagement, r.limits.gauge_plane) {
        (Some(le), _) => (le, "as given".to_string()),
        (None, Some(gp)) => (gp.distance, "the gauge's L1".to_string()),
        (None, None) => (
            r.designation.thread.nominal_diameter,
            format!(
                "LE = D = {:.3} mm, the length ASME B1.1 and BS 84 base their tolerances on",
                r.designation.thread.nominal_diameter
            ),
        ),
    };
    let used = on_part.min(engagement);
    let lead = crate::analysis::turn::lead::lead_deviation(last.lead, op.units, &r.designation.thread, used)
        .unwrap_or(None)
        .map(|d| crate::analysis::turn::lead::LeadDeviation { pass_length, engagement, ..d });
    if let Some(d) = &lead {
        let whole = d.pitch_diameter_equivalent * pass_length / used.max(1e-9);
        notes.push(crate::ground::note::Note::from(format!(
            "the lead error adds up over {:.3} mm: the thread on the part from its face at Z0 ({:.3} mm of the finishing pass's {:.3} mm) up to the length of engagement ({basis}; ‹engagement› sets it); {:.1} µm on the pitch diameter, {:.1} µm over the whole pass",
            used,
            on_part,
            pass_length,
            d.pitch_diameter_equivalent * 1e3,
            whole * 1e3
        )));
    }
    // The starts cut: by their phase against the designation's pitch when it has several,
    // else as the program's reading told them apart.
    let t = &r.designation.thread;
    let cut: std::collections::BTreeSet<u32> =
        if t.starts > 1 { &passes } else { &op.passes }.iter().map(|p| p.start).collect();
    // A start off a whole number of pitches (two increments of the program's, to allow for its
    // rounding) is misplaced: it fails by its offset (issue 47).
    // Each start's phase is its last pass's (the infeed moves a flank-fed pass along Z; every
    // start's last pass is at full depth alike).
    // The starts as the program's reading told them apart (one cycle per start) when it did,
    // else as their phases are assigned above.
    let read: std::collections::BTreeSet<u32> = op.passes.iter().map(|p| p.start).collect();
    let grouped = if read.len() > 1 { &op.passes } else { &passes };
    let mut phases: Vec<f64> = Vec::new();
    for s in grouped.iter().map(|p| p.start).collect::<std::collections::BTreeSet<u32>>() {
        if let Some(p) = grouped.iter().rev().find(|p| p.start == s) {
            phases.push(p.z_phase);
        }
    }
    let tolerance = 2.0 * op.units.least_increment() * op.units.mm() + 1e-9;
    let misplaced = if t.starts > 1 {
        crate::analysis::check::misplaced_starts(&phases, t.pitch, t.lead(), tolerance)
    } else {
        Vec::new()
    };
    let starts = crate::analysis::check::starts_check(&cut, t.starts, t.pitch, &misplaced);
    let mut v = verify_core(
        r,
        Some(Given {
            passes,
            depth_word: op.depth_word.clone(),
            units: op.units,
            lead,
            label: label.clone(),
            notes,
        }),
    )?;
    // One cycle per start: the correction changes each cycle's word alike, when they are
    // written alike; otherwise it is said for the first and the others are named.
    if let Some(d) = v.depth.as_mut() {
        for w in &op.start_words {
            d.also.push(crate::analysis::turn::correction::Place { line: w.line, column: w.column });
            d.alike &= w.written == d.word.written && w.form == d.word.form;
        }
        d.pass_x_words = op.pass_x_words.clone();
        if let Some(c) = v.correction.as_mut() {
            d.apply_to(c, v.kind);
        }
    }
    if !starts.ok {
        // A start missing (or one too many) is no matter of X: no correction is offered.
        v.correction = None;
        v.depth = None;
        v.suggested_final_x = None;
        v.middle_final_x = None;
        v.notes.push(crate::ground::note::Note::from(format!(
            "no correction is offered while the starts are wrong: {}",
            starts.note.as_deref().unwrap_or_default()
        )));
    }
    v.checks.push(starts);
    v.pass = verdict(&v.checks, v.gauge_only);
    v.hints = crate::analysis::check::hints(
        &v.checks,
        &v.insert,
        &v.limits,
        v.designation.thread.half_angle().to_degrees(),
    );
    Ok(v)
}

/// The designation of a turned operation from its program: the nearest comment above it (back
/// to the operation before) that names a thread, else the nearest one higher up whose lead is
/// the operation's, else the standard size of its lead and diameter (the last pass's tip is on
/// d3 ≈ d − 1.2269·P on a bar, on D in a bore).
pub(super) fn name_turned(
    op: &crate::gcode::Operation,
    before: Option<&crate::gcode::Operation>,
    comments: &[crate::gcode::Comment],
    internal: bool,
    opts: crate::standards::designation::ParseOptions,
    file: &str,
) -> Result<crate::analysis::naming::Named, Error> {
    use crate::analysis::naming::{from_comments, infer_designation_with};
    let kind = match (internal, pass_side(&op.passes)) {
        (true, _) => ThreadKind::Internal,
        (false, Some(k)) => k,
        (false, None) => ThreadKind::External,
    };
    let lead = op.passes.first().map_or(0.0, |p| p.lead);
    let upto = op
        .passes
        .iter()
        .filter_map(|p| p.source_line)
        .chain([op.source_line])
        .max()
        .unwrap_or(op.source_line);
    // The comments are the program's own: an operation in a subprogram's file has none above it
    // there, and takes the program's nearest comment of its lead.
    let in_sub = op.source_file.is_some();
    let after = if in_sub { usize::MAX } else { before.map_or(0, |b| b.source_line) };
    if let Some(n) = from_comments(comments, after, upto, kind, opts).filter(|_| !in_sub) {
        return Ok(n);
    }
    let same_lead = comments
        .iter()
        .rev()
        .filter(|c| c.line <= after)
        .find(|c| {
            crate::analysis::naming::designation_in_comment(&c.text, opts).is_some_and(|f| {
                crate::analysis::turn::lead::lead_deviation(lead, op.units, &f.designation.thread, 1.0)
                    .is_ok()
            })
        })
        .map(|c| c.line);
    if let Some(line) = same_lead {
        if let Some(n) = from_comments(comments, line - 1, line, kind, opts) {
            return Ok(n);
        }
    }
    let last = last_head(&op.passes).x_end;
    let starts = op.passes.iter().map(|p| p.start + 1).max().unwrap_or(1);
    let pitch = lead / f64::from(starts);
    let major = match kind {
        ThreadKind::External => last + 2.0 * 0.613_434_5 * pitch,
        ThreadKind::Internal => last,
    };
    // A G76's angle word is the tool's included angle: twice the infeed angle it sets.
    let tool_angle = op.infeed_angle.as_ref().filter(|_| op.cycle == "G76").map(|(a, _)| 2.0 * a);
    infer_designation_with(lead, starts, major, kind, op.units, op.source_line, tool_angle).map_err(|e| {
        match e {
            Error::Input(message) => {
                Error::Program { file: file.to_string(), line: op.source_line, column: 1, message }
            }
            e => e,
        }
    })
}

/// How a program's operation gets its insert: `None` keeps the spec's; else the insert, the
/// note that says where it came from, and whether it is the assumed default.
pub type InsertFor<'a> = dyn Fn(&crate::gcode::Operation) -> Option<(InsertChoice, String, bool)> + 'a;

/// A program read, and its turned threads verified.
#[derive(Clone, Debug)]
pub struct TurnedProgram {
    /// The program as read (its notes and reading go to the whole program's verification).
    pub prog: crate::gcode::Program,
    /// The program's name and dialect, as shown.
    pub label: ProgramLabel,
    /// Each turned operation verified, in program order (the one `VerifySpec::operation` names,
    /// when it names one).
    pub operations: Vec<OperationVerdict>,
    /// How many threading operations the program has.
    pub operations_in_program: usize,
}

/// The turned threads of a program held in memory, each verified: `threads` gives one designation
/// for all operations or one per operation in program order; `insert_for` chooses each
/// operation's insert (from its tool number, say) and says what it assumed. The whole program's
/// verification ([`verify_program`](crate::verify_program)) is made of these.
pub fn turned_program(
    spec: &VerifySpec,
    text: &str,
    name: &str,
    dialect: crate::gcode::Dialect,
    threads: &[crate::standards::Designation],
    insert_for: &InsertFor<'_>,
) -> Result<TurnedProgram, Error> {
    let prog = crate::gcode::read_program_with(text, name, dialect, spec.reading.clone())?;
    let n = prog.operations.len();
    if !(threads.is_empty() || threads.len() == 1 || threads.len() == n) {
        let lines: Vec<String> =
            prog.operations.iter().map(|o| format!("{} at line {}", o.cycle, o.source_line)).collect();
        return Err(Error::Input(format!(
            "{name} cuts {n} thread{} ({}); give one designation for all of them or one per operation, not {} times",
            if n == 1 { "" } else { "s" },
            lines.join(", "),
            threads.len()
        )));
    }
    let label = ProgramLabel { file: name.to_string(), dialect };
    let mut operations = Vec::with_capacity(n);
    // One operation when the spec names it, else every one.
    let only = spec.operation.map(|k| operation_index(&prog, name, Some(k))).transpose()?;
    let comments = if threads.is_empty() { crate::gcode::comments(text, dialect) } else { Vec::new() };
    for (i, op) in prog.operations.iter().enumerate() {
        if only.is_some_and(|k| k != i) {
            continue;
        }
        let named = match threads {
            [] => name_turned(
                op,
                i.checked_sub(1).map(|k| &prog.operations[k]),
                &comments,
                spec.internal,
                crate::standards::designation::ParseOptions { allow_nonstandard: spec.allow_nonstandard },
                name,
            )?,
            [one] => crate::analysis::naming::Named::given(one.clone()),
            many => crate::analysis::naming::Named::given(many[i].clone()),
        };
        let designation = &named.designation;
        let mut s = VerifySpec {
            units: if spec.units_given { spec.units } else { VerifySpec::default_units(Some(designation)) },
            designation: Some(designation.clone()),
            program: None,
            operation: None,
            final_x: None,
            ..spec.clone()
        };
        let mut extra = Vec::new();
        if !named.why.is_empty() {
            extra.push(named.why.clone());
        }
        // The program's declared stock is the blank of an external thread it turns no diameter
        // for (issue 47: a training simulator's `[BILLET X30`).
        if let (None, None, Some((d, line))) =
            (spec.blank_diameter, program_blank(op, ThreadKind::External), prog.stock)
        {
            if pass_side(&op.passes) != Some(ThreadKind::Internal) && !spec.internal {
                s.blank_diameter = Some(d);
                extra.push(format!(
                    "the blank is the stock the program declares at line {line}: Ø{} (‹blank_diameter› overrides)",
                    crate::ground::fmt::fmt_num(d)
                ));
            }
        }
        let mut assumed = false;
        if let Some((choice, note, default)) = insert_for(op) {
            if default {
                let (choice, what) = assumed_insert(op, &s);
                s.insert = choice;
                extra.push(format!(
                    "insert assumed: {what} ({note}; choose with ‹insert› or ‹tools›): the root radius, the crest and the diameters its tip and crest leave are unverified"
                ));
            } else {
                s.insert = choice;
                extra.push(note);
            }
            assumed = default;
        }
        // A thread given: the one the passes cut, by their lead and diameters, is said beside it
        // when the two differ (and in the refusal of one far from it).
        let inferred = (!threads.is_empty())
            .then(|| {
                let opts =
                    crate::standards::designation::ParseOptions { allow_nonstandard: spec.allow_nonstandard };
                let cut = name_turned(op, None, &[], spec.internal, opts, name).ok()?;
                let (a, b) = (cut.designation.thread, designation.thread);
                let same = a.form == b.form
                    && (a.nominal_diameter - b.nominal_diameter).abs() < 1e-6
                    && (a.pitch - b.pitch).abs() < 1e-6
                    && a.starts == b.starts;
                (!same).then_some(cut.designation)
            })
            .flatten();
        if let Some(cut) = &inferred {
            extra.push(format!(
                "the thread given is {designation}; the passes' lead and diameters are those of {cut} (inferred)"
            ));
        }
        let mut result = verify_operation(&s, op, &label).map_err(|e| match (e, &inferred) {
            (Error::Program { file, line, column, message }, Some(cut)) if message.ends_with(MISFIT_END) => {
                Error::Program {
                    file,
                    line,
                    column,
                    message: format!("{message} (the passes fit {cut}, inferred)"),
                }
            }
            (e, _) => e,
        })?;
        if let OperationResult::Verified(v) = &mut result {
            v.notes.extend(extra.into_iter().map(crate::ground::note::Note::from));
            let t = v.designation.thread;
            let (checks, report) = crate::analysis::process::process_checks(
                op,
                t.pitch,
                t.pitch_diameter(),
                spec.machine.as_ref(),
                spec.clearance_angle.or(v.insert.clearance_angle),
            );
            v.checks.extend(checks);
            v.process = Some(report);
            if assumed {
                unverified_by_assumed_insert(v);
                if v.correction.is_some() || v.suggested_final_x.is_some() {
                    let other = other_candidate(&s, op, &label);
                    withhold_correction(v, other);
                }
                // The mid-tolerance X rests on the insert as the correction does.
                v.middle_final_x = None;
            }
            v.pass = verdict(&v.checks, v.gauge_only);
        }
        operations.push(OperationVerdict { operation: op.clone(), named, result });
    }
    Ok(TurnedProgram { prog, label, operations, operations_in_program: n })
}

/// The insert a program's passes are written for when no tool is known: of the full-profile
/// insert (its tip on the basic root: d3 on a bar, D in a bore) and the default partial-profile
/// insert (tip r0.04: the flanks on the basic d2 put the tip H − 2r(1/sin α − 1) beyond d2 on the
/// diameter), the one whose tip position lies nearer the deepest pass; the full one on a tie or
/// when the designation cannot be read here (the verification then says why). With what to say.
pub(super) fn assumed_insert(op: &crate::gcode::Operation, spec: &VerifySpec) -> (InsertChoice, String) {
    const TIP: f64 = 0.04;
    let full = (
        InsertChoice::Full,
        "the full-profile insert of the thread's pitch, the one the passes' depth is written for".to_string(),
    );
    let Some(des) = &spec.designation else {
        return full;
    };
    let t = des.thread;
    if op.passes.is_empty() || t.form.taper() != 0.0 || TIP > t.root_radius() {
        return full;
    }
    let internal = spec.internal
        || (des.external.is_none() && des.internal.is_some())
        || pass_side(&op.passes) == Some(ThreadKind::Internal);
    let last = last_head(&op.passes);
    let x = 0.5 * (last.x_start.abs() + last.x_end.abs());
    let below_d2 = t.fundamental_height() - 2.0 * TIP * (1.0 / t.half_angle().sin() - 1.0);
    let (x_full, x_partial) = if internal {
        (t.nominal_diameter, t.pitch_diameter() + below_d2)
    } else {
        (t.minor_diameter_external(), t.pitch_diameter() - below_d2)
    };
    if (x - x_partial).abs() < (x - x_full).abs() - 1e-9 {
        (
            InsertChoice::Partial { tip_radius: TIP },
            format!(
                "a partial-profile insert with a {} mm tip, the one the passes' depth is written for (the last pass X{x:.3} lies nearer its X{x_partial:.3} than a full-profile insert's X{x_full:.3})",
                crate::ground::fmt::fmt_num(TIP)
            ),
        )
    } else {
        full
    }
}

/// The insert a program's passes could equally be written for, beside the one assumed (the
/// full-profile insert of the pitch and the default partial one), and the pitch diameter it
/// leaves (`None` when it cannot cut this thread).
pub(super) fn other_candidate(
    spec: &VerifySpec,
    op: &crate::gcode::Operation,
    label: &ProgramLabel,
) -> Option<(String, f64, bool)> {
    let other = match spec.insert {
        InsertChoice::Full => InsertChoice::Partial { tip_radius: 0.04 },
        InsertChoice::Partial { .. } => InsertChoice::Full,
        _ => return None,
    };
    let s = VerifySpec { insert: other, metrics: false, picture: false, ..spec.clone() };
    match verify_operation(&s, op, label).ok()? {
        OperationResult::Verified(o) => {
            use crate::analysis::check::CheckFeature as F;
            let size_ok = !crate::analysis::check::any_fails(
                &o.checks,
                &[F::PitchDiameter, F::MaxMaterial, F::FunctionalPitchDiameter],
            );
            Some((o.insert.name, o.measurement.pitch_diameter, size_ok))
        }
        OperationResult::NoCut { .. } => None,
    }
}

/// A correction computed with an insert nobody chose is no instruction: the pitch diameter the
/// passes leave depends on the insert (a partial-profile insert's flanks stand off its tip
/// otherwise than a full-profile one's), and moving X by the assumed insert's figure scraps the
/// part cut with the other (issue 61: an Okuma M25x1.25 nut, −44.5 µm with the partial r0.04
/// assumed, +51 µm inside 6H with a full-profile insert; its X.990 moved to X.9955 would have left it
/// over D2 max). It is withheld, with the other insert's pitch diameter said.
pub fn withhold_correction(v: &mut Verification, other: Option<(String, f64, bool)>) {
    v.correction = None;
    v.suggested_final_x = None;
    v.middle_final_x = None;
    let pd = v.measurement.pitch_diameter;
    let also = match other {
        Some((name, d2, ok)) => format!(
            "; with {name} the passes leave {} {d2:.4}, {}",
            if v.kind == ThreadKind::External { "d2" } else { "D2" },
            if ok { "inside the class" } else { "outside the class too" }
        ),
        None => String::new(),
    };
    v.notes.push(crate::ground::note::Note::from(format!(
        "no correction is offered: the pitch diameter {pd:.4} rests on the insert assumed ({}){also}; give ‹insert› or ‹tools› for a correction",
        v.insert.name
    )));
}

/// What an insert nobody chose decides: the root radius, the diameter its tip leaves (d3 on a
/// bar, D in a bore), the crest (a full-profile insert tops it, a partial one leaves the
/// blank's) and the crest's diameter where the insert topped the blank. With the insert assumed these checks are reported
/// `unverified`, with what was assumed, and left out of the verdict; the sizes the passes decide
/// (d2, the GO gauge, the crest diameter the blank leaves) and the flanks count.
pub fn unverified_by_assumed_insert(v: &mut Verification) {
    use crate::analysis::check::CheckFeature as F;
    let kind = v.kind;
    let assumed = format!("tool not known: the insert assumed is {}", v.insert.name);
    // The crest diameter is the blank's unless the assumed insert topped it.
    let blank = v.blank_diameter;
    for c in &mut v.checks {
        let on_tool = match (c.feature, kind) {
            (F::RootRadius | F::Crest, _) => true,
            (F::MinorDiameter, ThreadKind::External) | (F::MajorDiameter, ThreadKind::Internal) => true,
            (F::MajorDiameter, ThreadKind::External) => c.value < blank - 1e-4,
            (F::MinorDiameter, ThreadKind::Internal) => c.value > blank + 1e-4,
            _ => false,
        };
        if on_tool {
            c.unverified = Some(assumed.clone());
        }
    }
    // Hints about a failing root or crest speak of the assumed insert: not the program's.
    v.hints.retain(|h| !matches!(h, crate::analysis::check::Hint::TipRadius { .. }));
}

/// Runs `verify`: resolves the thread, its limits and the insert, lays out (or reads) the passes,
/// cuts them, measures the groove and checks it.
///
/// ```
/// use threadcheck::{verify, InsertChoice, VerifySpec};
/// // A full-profile insert, the final X solved for the middle of 6g's d2 band (8.862–8.994).
/// let v = verify(&VerifySpec { insert: InsertChoice::Full, ..VerifySpec::of("M10x1.5-6g")? })?;
/// assert!(v.pass);
/// assert!((v.measurement.pitch_diameter - 8.928).abs() < 1e-3);
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn verify(spec: &VerifySpec) -> Result<Verification, Error> {
    spec.validate()?;
    if let Some((source, dialect)) = &spec.program {
        if spec.final_x.is_some() {
            return Err(Error::Input(
                "a final X and a program exclude each other: the program sets the passes".into(),
            ));
        }
        let (shown, text) = source.load()?;
        let prog = crate::gcode::read_program_with(&text, &shown, *dialect, spec.reading.clone())?;
        let index = operation_index(&prog, &shown, spec.operation)?;
        let label = ProgramLabel { file: shown, dialect: *dialect };
        let mut v = verify_given(&resolve(spec)?, &prog.operations[index], &label)?;
        v.notes.extend(prog.notes.iter().cloned());
        return Ok(v);
    }
    verify_core(&resolve(spec)?, None)
}

/// The index of the operation `operation` (1-based) names in `prog`, or of its only one.
pub(super) fn operation_index(
    prog: &crate::gcode::Program,
    shown: &str,
    operation: Option<usize>,
) -> Result<usize, Error> {
    let n = prog.operations.len();
    let list = || {
        prog.operations
            .iter()
            .map(|o| format!("{} at line {}", o.cycle, o.source_line))
            .collect::<Vec<_>>()
            .join(", ")
    };
    match operation {
        Some(k) if (1..=n).contains(&k) => Ok(k - 1),
        Some(k) => Err(Error::Input(format!(
            "{shown} cuts {n} thread{} ({}): there is no operation {k}",
            if n == 1 { "" } else { "s" },
            list()
        ))),
        None if n == 1 => Ok(0),
        None => Err(Error::Input(format!(
            "{shown} cuts {n} threads ({}): say which one with ‹operation› 1 to {n}",
            list()
        ))),
    }
}
