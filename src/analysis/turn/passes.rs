//! The passes of a turned thread: a program operation's passes as the sweep takes them, the
//! reference groove, the side they cut.

use crate::geometry::measure::Measurement;
use crate::geometry::sweep::Section;
use crate::standards::{Designation, ThreadKind};
use crate::toolpath::passes::Pass;
use crate::Error;

/// The last pass of the first start that begins a threading move (not a later segment of a
/// synchronised chain, such as a run-out).
pub fn last_head(passes: &[Pass]) -> Pass {
    let head = |p: &&Pass| (p.z_phase - p.z_start).abs() < 1e-12;
    passes
        .iter()
        .rev()
        .find(|p| p.start == 0 && head(p))
        .or_else(|| passes.iter().rev().find(|p| p.start == 0))
        .or(passes.last())
        .copied()
        .unwrap_or_else(|| Pass::parallel(0, 0.0, 0.0, 0.0, 1.0))
}

/// Where to measure: the groove of the last pass of the first start, on the crossing nearest the
/// middle of its full-depth stretch (clear of run-in and run-out).
///
/// ```
/// use threadcheck::{reference_groove, Pass};
/// // One pass from Z5 to Z−20 at lead 1.5, phase at Z5: the groove nearest the middle, Z−7.5,
/// // on the lead's grid 5 − 1.5·k is Z−8.5 or Z−7 (k = 9 gives −8.5; k = 8 gives −7).
/// let z = reference_groove(&[Pass::parallel(1, 8.16, 5.0, -20.0, 1.5)]);
/// assert!(((z - 5.0) / 1.5).fract().abs() < 1e-9 && (z + 7.5).abs() <= 0.75);
/// ```
pub fn reference_groove(passes: &[Pass]) -> f64 {
    if passes.is_empty() {
        return 0.0;
    }
    let last = last_head(passes);
    let (lo, hi) = last.full_depth_range();
    let k = ((0.5 * (lo + hi) - last.z_phase) / last.lead).round();
    last.z_phase + k * last.lead
}

/// The crossing of the last threading move nearest `z`.
pub fn groove_near(passes: &[Pass], z: f64) -> f64 {
    if passes.is_empty() {
        return z;
    }
    let last = last_head(passes);
    let k = ((z - last.z_phase) / last.lead).round();
    last.z_phase + k * last.lead
}

/// An operation's passes checked against the designation: the lead must match, and the starts
/// of a multi-start thread are told apart by their phase (pitch apart along the lead).
///
/// ```
/// use threadcheck::{parse_designation, program_passes, read_program, Dialect, ParseOptions};
/// let p = read_program("G0 X22 Z5\nG76 P011060 Q100 R0.05\nG76 X18.16 Z-20 P920 Q350 F1.5\n", "m20.nc", Dialect::Fanuc)?;
/// let des = parse_designation("M20x1.5-6g", ParseOptions::default())?;
/// let passes = program_passes(&p.operations[0], &des, "m20.nc")?;
/// assert!(passes.iter().all(|q| q.lead == 1.5 && q.start == 0));
/// // A designation with another lead is refused.
/// assert!(program_passes(&p.operations[0], &parse_designation("M20x2-6g", ParseOptions::default())?, "m20.nc").is_err());
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn program_passes(
    op: &crate::gcode::Operation,
    des: &Designation,
    file: &str,
) -> Result<Vec<Pass>, Error> {
    let t = &des.thread;
    let lead = t.lead();
    let Some(p0) = op.passes.first().copied() else {
        return Err(Error::Input(format!("{file}: operation {} has no passes", op.index)));
    };
    let off_helix = off_helix_segments(op, t);
    for (p, _) in op.passes.iter().zip(&off_helix).filter(|(_, off)| !**off) {
        if let Err(inc) = crate::analysis::turn::lead::lead_deviation(p.lead, op.units, t, 0.0) {
            let u = op.units;
            let in_units = |mm: f64| match u {
                crate::gcode::ProgramUnits::Mm => format!("{mm:.4} mm"),
                crate::gcode::ProgramUnits::Inch => format!("{:.4} in ({mm:.4} mm)", mm / u.mm()),
            };
            // A lead that matches once read in inches: the program is an inch control's.
            let inch = crate::gcode::ProgramUnits::Inch;
            let hint = if u == crate::gcode::ProgramUnits::Mm
                && crate::analysis::turn::lead::lead_deviation(p.lead * inch.mm(), inch, t, 0.0).is_ok()
            {
                "; read in inches it is the designation's (G20, or ‹default_units› inch if the program sets no units)"
                    .to_string()
            } else {
                String::new()
            };
            return Err(Error::Program {
                file: file.to_string(),
                line: p.source_line.unwrap_or(1),
                column: 1,
                message: format!(
                    "the program cuts a lead of {}, the designation {} has {}: they differ by more than rounding{}{hint}",
                    in_units(p.lead),
                    des.text,
                    in_units(lead),
                    // A lead computed from a taper (not written) has no increment of its own.
                    if inc >= 1e-6 {
                        format!(" to the program's {} {} increment", crate::ground::fmt::fmt_num(inc), u.name())
                    } else {
                        String::new()
                    }
                ),
            });
        }
    }
    let mut passes = op.passes.clone();
    if t.starts > 1 {
        let n = f64::from(t.starts);
        for p in &mut passes {
            let k = ((p.z_phase - p0.z_phase) / t.pitch).round();
            p.start = k.rem_euclid(n) as u32;
        }
    }
    Ok(passes)
}

/// For each pass of `op`, whether it is a run-in or run-out segment off the thread's helix: a
/// taper segment whose axial lead is not the designation's while another pass of the operation
/// cuts at it (a chained run-out steeper than 45° whose F the control takes along X, a LinuxCNC
/// G33 taper whose K runs along the path). It is swept as it moves; a note says so.
pub(super) fn off_helix_segments(
    op: &crate::gcode::Operation,
    t: &crate::standards::BasicThread,
) -> Vec<bool> {
    let off: Vec<bool> = op
        .passes
        .iter()
        .map(|q| crate::analysis::turn::lead::lead_deviation(q.lead, op.units, t, 0.0).is_err())
        .collect();
    let some_on = off.iter().any(|o| !o);
    op.passes.iter().zip(off).map(|(p, o)| o && some_on && (p.x_end - p.x_start).abs() > 1e-9).collect()
}

pub(super) struct Cut {
    pub(super) passes: Vec<Pass>,
    pub(super) section: Section,
    pub(super) z_ref: f64,
    pub(super) measurement: Measurement,
}

/// The side a turned operation's passes cut: inward pass by pass from a bar (external), outward
/// in a bore (internal); `None` when every pass ends at one X.
pub fn pass_side(passes: &[Pass]) -> Option<ThreadKind> {
    let first = passes.first()?;
    let dx = last_head(passes).x_end - first.x_end;
    if dx.abs() < 1e-6 {
        None
    } else if dx < 0.0 {
        Some(ThreadKind::External)
    } else {
        Some(ThreadKind::Internal)
    }
}
