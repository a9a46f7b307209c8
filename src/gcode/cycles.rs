//! What the dialects share: the modal G codes, the depth laws of the threading cycles, and the
//! passes of a cycle laid out from a list of depths.

use super::motion::{Motion, RBlock};
use super::Dialect;
use crate::gcode::passes::Pass;
use crate::ground::bounds::MAX_PASSES;
use crate::Error;

/// The motion G code of a block, after the modal codes were applied.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Modal {
    /// The motion code in force for this block and its column (the block's own, or modal).
    pub motion: f64,
    /// Column of the block's own motion word, if it has one.
    pub col: Option<usize>,
    /// A one-shot code that makes the block no move of its own (G4 dwell, G28, turning cycles
    /// G70–G75, LinuxCNC G92 offsets).
    pub one_shot: Option<f64>,
}

/// Threading codes whose decimal variants are other functions: refused by name, never read as
/// the threading code.
const THREADING: [f64; 5] = [32.0, 33.0, 76.0, 78.0, 92.0];

/// Applies the block's modal G codes (units, distance mode, diameter mode, spindle mode, plane)
/// and returns its motion code.
pub(crate) fn modal(m: &mut Motion, b: &RBlock<'_>) -> Result<Modal, Error> {
    let d = m.dialect;
    let mut motion = None;
    let mut one_shot = None;
    let fanuc_like = match d {
        Dialect::Fanuc | Dialect::Haas => true,
        Dialect::Sinumerik | Dialect::LinuxCnc | Dialect::Dyna => false,
    };
    let inch_codes = d.unit_codes();
    let inch_codes = (f64::from(inch_codes.0), f64::from(inch_codes.1));
    for (g, col) in b.gs() {
        if g < 0.0 {
            return Err(m.err(b.line, col, "G with no code"));
        }
        if g.fract() != 0.0 {
            let base = g.trunc();
            match (d, g) {
                (Dialect::LinuxCnc, 92.1 | 92.2) => {
                    m.offset = [0.0; 3];
                    one_shot = Some(g);
                }
                (Dialect::LinuxCnc, 33.1) => {
                    return Err(m.err(
                        b.line,
                        col,
                        "G33.1 is rigid tapping, not a turned thread: threadcheck does not read it",
                    ))
                }
                _ if THREADING.contains(&base) => {
                    return Err(m.err(
                        b.line,
                        col,
                        format!("G{g} is not G{base}: threadcheck reads G{base} and does not read G{g}"),
                    ))
                }
                // G7.1, G42.1, G43.1 and kin: not lathe threading; the block is read for position.
                _ => {}
            }
            continue;
        }
        match g as u32 {
            0 | 1 | 2 | 3 | 32 | 33 | 76 => motion = Some((g, col)),
            92 if d == Dialect::LinuxCnc => one_shot = Some(g),
            92 => motion = Some((g, col)),
            78 if fanuc_like || d == Dialect::Sinumerik => {
                return Err(m.err(
                    b.line,
                    col,
                    "G78 (the EMCO training-lathe thread cycle) is not supported: its word format is not published; write G92 or G76",
                ))
            }
            7 if d == Dialect::LinuxCnc => m.diameter = true,
            8 if d == Dialect::LinuxCnc => m.diameter = false,
            c if f64::from(c) == inch_codes.0 => m.set_scale(25.4),
            c if f64::from(c) == inch_codes.1 => m.set_scale(1.0),
            700 if d == Dialect::Sinumerik => m.set_scale(25.4),
            710 if d == Dialect::Sinumerik => m.set_scale(1.0),
            90 => m.absolute = true,
            91 => m.absolute = false,
            96 => m.css = true,
            97 => m.css = false,
            17 => m.plane = 17,
            18 => m.plane = 18,
            19 => m.plane = 19,
            80 => motion = Some((80.0, col)),
            4 | 28 | 53 => one_shot = Some(g),
            70..=75 if fanuc_like || d == Dialect::LinuxCnc => one_shot = Some(g),
            _ => {}
        }
    }
    if let Some((g, _)) = motion {
        m.motion = g;
    }
    if let Some(s) = b.get("S") {
        if !(one_shot == Some(4.0)) {
            m.s = Some(s.v);
        }
    }
    if let Some(t) = b.get("T") {
        // T0303: tool 03 with offset 03 (Fanuc, Haas); T4 (Sinumerik, LinuxCNC).
        let v = t.v.max(0.0) as u32;
        m.tool = Some(if fanuc_like && v >= 100 { v / 100 } else { v });
    }
    Ok(Modal { motion: m.motion, col: motion.map(|x| x.1), one_shot })
}

/// Threading is programmed in the lathe plane G18.
pub(crate) fn need_lathe_plane(m: &Motion, b: &RBlock<'_>, col: usize, what: &str) -> Result<(), Error> {
    if m.plane != 18 {
        return Err(m.err(
            b.line,
            col,
            format!("{what} under G{}: threading is programmed in the lathe plane G18", m.plane),
        ));
    }
    Ok(())
}

/// Reads past a block that is not threading: moves update the position, the rest counts as
/// skipped. G53 (machine coordinates) leaves the position unknown in program coordinates.
pub(crate) fn other_block(m: &mut Motion, b: &RBlock<'_>, modal: &Modal) -> Result<(), Error> {
    m.break_chain();
    match modal.one_shot {
        Some(53.0) | Some(28.0) => {
            let (x, _, z) = m.target(b);
            if x.is_some() {
                m.x = None;
            }
            if z.is_some() {
                m.z = None;
            }
            m.skipped += 1;
            return Ok(());
        }
        Some(92.0) => {
            // LinuxCNC G92: the current point gets the given coordinates.
            for w in &b.words {
                match w.name {
                    "X" => {
                        if let Some(x) = m.x {
                            m.offset[0] = x - m.x_dia(w);
                        }
                    }
                    "Z" => {
                        if let Some(z) = m.z {
                            m.offset[2] = z - m.len(w);
                        }
                    }
                    _ => {}
                }
            }
            m.skipped += 1;
            return Ok(());
        }
        Some(_) => {
            m.skipped += 1;
            return Ok(());
        }
        None => {}
    }
    let moved = match modal.motion as u32 {
        2 => m.arc_to(b, -1.0)?,
        3 => m.arc_to(b, 1.0)?,
        _ => m.move_to(b),
    };
    if !moved {
        m.skipped += 1;
    }
    Ok(())
}

/// Fanuc two-block G76 depths: pass n at max(Δd·√n, previous + Δd min) while below the rough
/// end, then the rough end itself.
pub(crate) fn sqrt_law_with_min(dd: f64, min_step: f64, rough_to: f64) -> Result<Vec<f64>, String> {
    let mut depths = Vec::new();
    let mut prev = 0.0f64;
    let mut n = 1.0f64;
    loop {
        let mut d = dd * n.sqrt();
        if d - prev < min_step {
            d = prev + min_step;
        }
        if d >= rough_to - 1e-12 {
            depths.push(rough_to);
            return Ok(depths);
        }
        depths.push(d);
        prev = d;
        n += 1.0;
        if depths.len() > MAX_PASSES {
            return Err("the cycle expands to too many passes".into());
        }
    }
}

/// How the tip moves along Z from pass to pass.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Shift {
    /// Straight in X.
    Radial,
    /// Along one flank: depth · tan(angle) in the direction of feed.
    Flank(f64),
    /// Alternating flanks, each pass shifted by ± depth increment · tan(angle) (Haas P2/P4).
    Alternating(f64),
}

/// Z shift of each pass for the depths (cumulative from the crest), in the feed direction `dir`.
pub(crate) fn shifts(shift: Shift, depths: &[f64], dir: f64) -> Vec<f64> {
    match shift {
        Shift::Radial => vec![0.0; depths.len()],
        Shift::Flank(a) => {
            let t = a.to_radians().tan();
            depths.iter().map(|d| dir * d * t).collect()
        }
        Shift::Alternating(a) => {
            let infeed = crate::gcode::passes::Infeed::Alternating { angle: a };
            crate::gcode::passes::infeed_offsets(infeed, depths, dir)
        }
    }
}

/// A straight threading pass with an optional run-out.
#[allow(clippy::too_many_arguments)]
pub(crate) fn pass(
    x_start: f64,
    x_end: f64,
    z_start: f64,
    z_end: f64,
    lead: f64,
    line: usize,
    taper_out: f64,
    x_taper: f64,
) -> Pass {
    Pass {
        index: 0,
        x_start,
        x_end,
        z_start,
        z_end,
        z_phase: z_start,
        lead,
        start: 0,
        source_line: Some(line),
        taper_in: 0.0,
        taper_out,
        x_taper,
    }
}

/// The axial lead of a G32-style move whose F is the lead along the longer axis (Fanuc, Haas):
/// for a steep taper (more X than Z) F runs along X.
pub(crate) fn axial_lead_longer_axis(f: f64, dx_radius: f64, dz: f64) -> f64 {
    if dx_radius.abs() > dz.abs() {
        f * dz.abs() / dx_radius.abs()
    } else {
        f
    }
}
