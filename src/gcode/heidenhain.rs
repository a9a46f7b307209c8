//! Heidenhain MANUALplus / CNC PILOT lathes, DIN programming (sources in docs/dialects.md,
//! "Heidenhain"):
//!
//! - `G31 X Z F U I [R] [B] [P] [A] [V] [H] [Q] [C] [D]`, the thread cycle (MANUALplus 4110
//!   Pilot p. 74 and User Manual p. 336; the MANUALplus 620 / CNC PILOT 640 DIN manual for D):
//!   the thread runs from the tool's Z to Z, X its diameter at the end (the major diameter of an
//!   outside thread, the bore of an inside one) and R = (X − XA)/2 the taper; U the thread depth
//!   (U > 0 an inside thread, U ≤ 0 outside); I the largest infeed; V the infeed law: 0 constant
//!   cross-section (I the first cut, each further cut of the same cross-section: I·√n), 1 constant
//!   infeeds not over I, 2 and 3 infeeds of I with the first reduced by the remainder of U/I, 2
//!   dividing the last cut into 1/2, 1/4, 1/8, 1/8; H the offset of the cuts along Z: 0 none,
//!   1 to the left, 2 to the right, 3 alternating; A the infeed angle (default arctan(F/2U),
//!   range 0–60°); Q the number of air cuts after the last; C the start angle; D the number of
//!   starts; B and P the run-in and overrun (default F·S/1000 each).
//! - `G33 X Z F [C]`: one thread path from the tool's position, chained with the G33 blocks
//!   that follow it (tapers and chains), F the lead along the longer axis.
//!
//! Named defaults, stated in the output where they act: "left" is toward −Z; the flank offsets
//! H1/H2 move each cut depth·tan A along Z from the first, H3 alternates as the alternating
//! infeed of the other dialects does, beginning on the left; with D starts F is the lead and the
//! starts lie F/D apart, cut depth by depth; B and P, when absent, are F·S/1000 with the program's
//! spindle speed in rpm, and 0 (noted) where it is not known. Refused by name: G31 without X and
//! Z (a thread on the contour that follows), G32 (the simple thread cycle).

use super::cycles::{self, Shift};
use super::dialect::{Ctx, Flow, Rules};
use super::motion::{Motion, RBlock};
use crate::ground::fmt::{fmt_num, fmt_shown};
use crate::Error;

/// Heidenhain state: none beyond the interpreter's (G31 is a one-block cycle).
#[derive(Default)]
pub(crate) struct State;

fn block(m: &mut Motion, b: &RBlock<'_>) -> Result<Flow, Error> {
    let md = cycles::modal(m, b)?;
    if let Some((_, col)) = b.gs().find(|&(g, _)| g == 14.0) {
        m.lose_position(b.line, "G14", true, true);
        m.read_past(
            b.line,
            col,
            "G14",
            "the move to the tool change point, a machine setting: the position is unknown until the next X and Z",
        );
        return Ok(Flow::Next);
    }
    if md.one_shot.is_some() {
        cycles::other_block(m, b, &md)?;
        return Ok(Flow::Next);
    }
    let col = md.col.unwrap_or(b.col);
    match md.motion as u32 {
        31 if md.col.is_some() => g31(m, b, col)?,
        33 => g33(m, b, col)?,
        _ => cycles::other_block(m, b, &md)?,
    }
    Ok(Flow::Next)
}

/// G33: one thread path, chained with its neighbours.
fn g33(m: &mut Motion, b: &RBlock<'_>, col: usize) -> Result<(), Error> {
    if b.get("X").is_none() && b.get("Z").is_none() {
        m.skipped += 1;
        return Ok(());
    }
    cycles::need_lathe_plane(m, b, col, "G33")?;
    b.allow_only(&m.file, "GXZFCNMST", "G33")?;
    let f = match b.get("F") {
        Some(w) => m.len(w),
        None => m.lead.ok_or_else(|| m.err(b.line, col, "G33 needs F, the thread pitch"))?,
    };
    if !(f > 0.0 && f.is_finite()) {
        return Err(m.err(b.line, col, format!("G33 F{}: the pitch must be positive", fmt_num(f))));
    }
    m.lead = Some(f);
    let c = b.get("C").map_or(0.0, |w| w.v);
    m.thread_move(b, col, "G33", |dx, dz| cycles::axial_lead_longer_axis(f, dx, dz), c)
}

/// A whole-number word within `lo..=hi`, or its default.
fn whole(
    m: &Motion,
    b: &RBlock<'_>,
    name: &str,
    lo: f64,
    hi: f64,
    default: f64,
    what: &str,
) -> Result<f64, Error> {
    let Some(w) = b.get(name) else { return Ok(default) };
    if !cycles::whole_in(w.v, lo, hi) {
        return Err(b.werr(
            &m.file,
            w,
            format!("G31 {name}{}: {what} is a whole number from {lo} to {hi}", fmt_num(w.v)),
        ));
    }
    Ok(w.v)
}

/// G31's infeed law V.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Law {
    /// V0: constant cross-section, the nth cut at I·√n.
    CrossSection,
    /// V1: constant infeeds of at most I.
    Constant,
    /// V2: infeeds of I, the first reduced by the remainder, the last divided in four.
    LastDivided,
    /// V3: infeeds of I, the first reduced by the remainder.
    RemainderFirst,
}

/// V0 to V3 in order: a V the block gives indexes it (bounded by `whole` before).
const LAWS: [Law; 4] = [Law::CrossSection, Law::Constant, Law::LastDivided, Law::RemainderFirst];

/// G31's offset type H.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Offset {
    /// H0: every cut on the thread's axis line (radial infeed).
    Radial,
    /// H1: each cut offset toward −Z (left).
    Left,
    /// H2: each cut offset toward +Z (right).
    Right,
    /// H3: alternating, the first toward −Z.
    Alternating,
}

/// H0 to H3 in order.
const OFFSETS: [Offset; 4] = [Offset::Radial, Offset::Left, Offset::Right, Offset::Alternating];

/// How many cuts the infeed law `v` makes for the depth `u` in infeeds of at most `i`, counted
/// before any is made: V1 to V3 take ⌈U/I⌉ (V2 three more), V0 the n with I·√n ≥ U.
fn cut_count(v: Law, u: f64, i: f64) -> f64 {
    match v {
        Law::CrossSection => (u / i).powi(2).ceil(),
        Law::LastDivided => (u / i).ceil() + 3.0,
        Law::Constant | Law::RemainderFirst => (u / i).ceil(),
    }
}

/// The depths (radial, from the thread's surface) of the cuts for the infeed law `v`; the caller
/// has bounded their count ([`cut_count`]).
fn depths(v: Law, u: f64, i: f64) -> Vec<f64> {
    debug_assert!(cut_count(v, u, i) <= crate::ground::bounds::MAX_PASSES as f64 + 1.0);
    let mut out = Vec::new();
    match v {
        // Constant cross-section: the nth cut reaches I·√n, the last U.
        Law::CrossSection => {
            let mut n = 1.0f64;
            loop {
                let d = i * n.sqrt();
                if d >= u - 1e-9 || out.len() >= crate::ground::bounds::MAX_PASSES {
                    out.push(u);
                    break;
                }
                out.push(d);
                n += 1.0;
            }
        }
        // Constant infeeds of at most I.
        Law::Constant => {
            let n = (u / i - 1e-9).ceil().max(1.0);
            out.extend((1..=n as usize).map(|k| u * k as f64 / n));
        }
        // Infeeds of I, the first reduced by the remainder of U/I; V2 divides the last.
        Law::LastDivided | Law::RemainderFirst => {
            let full = (u / i + 1e-9).floor();
            let rest = u - full * i;
            let mut d = 0.0;
            if rest > 1e-9 {
                d = rest;
                out.push(d);
            }
            for _ in 0..full as usize {
                d += i;
                out.push(d.min(u));
            }
            if v == Law::LastDivided {
                let last = out.pop().unwrap_or(u);
                let before = out.last().copied().unwrap_or(0.0);
                let cut = last - before;
                for part in [0.5, 0.75, 0.875] {
                    out.push(before + part * cut);
                }
                out.push(last);
            }
        }
    }
    out
}

/// G31: the thread cycle with an end point.
fn g31(m: &mut Motion, b: &RBlock<'_>, col: usize) -> Result<(), Error> {
    cycles::need_lathe_plane(m, b, col, "G31")?;
    let (x, _, z) = m.target(b);
    let (Some(x_end), Some(z_end)) = (x, z) else {
        return Err(m.err(
            b.line,
            col,
            "G31 without X and Z (a thread on the contour that follows, up to G80) is not supported: give the end point X Z",
        ));
    };
    b.allow_only(&m.file, "GXZFUIRBPAVHQCDNMST", "G31")?;
    let (x0, z0) = m.need_position(b.line, col, "G31")?;
    let need = |what: &str| m.err(b.line, col, format!("G31 needs {what}"));
    let f = b.get("F").map(|w| m.len(w)).ok_or_else(|| need("F, the thread pitch"))?;
    let u = b
        .get("U")
        .map(|w| m.len(w))
        .ok_or_else(|| need("U, the thread depth (U > 0 inside, U < 0 outside)"))?;
    let i = b.get("I").map(|w| m.len(w)).ok_or_else(|| need("I, the largest infeed"))?;
    if !(f > 0.0 && f.is_finite() && u != 0.0 && u.is_finite() && i > 0.0 && i.is_finite()) {
        return Err(m.err(
            b.line,
            col,
            format!(
                "G31 F{} U{} I{}: the pitch F and the infeed I must be positive and the depth U not 0",
                fmt_num(f),
                fmt_num(u),
                fmt_num(i)
            ),
        ));
    }
    let depth = u.abs();
    let inside = u > 0.0;
    let r = b.get("R").map_or(0.0, |w| m.len(w));
    let v_number = whole(m, b, "V", 0.0, 3.0, 0.0, "the infeed type V")? as usize;
    let h_number = whole(m, b, "H", 0.0, 3.0, 0.0, "the offset type H")? as usize;
    let range = |w: &str| m.err(b.line, col, format!("G31 {w}: from 0 to 3"));
    let law = *LAWS.get(v_number).ok_or_else(|| range("V"))?;
    let offset = *OFFSETS.get(h_number).ok_or_else(|| range("H"))?;
    let q = whole(m, b, "Q", 0.0, 100.0, 0.0, "the number of air cuts Q")?;
    let starts = whole(m, b, "D", 1.0, 100.0, 1.0, "the number of starts D")?;
    let c = b.get("C").map_or(0.0, |w| w.v);
    let mut notes = Vec::new();
    let angle = match b.get("A") {
        Some(w) if (0.0..60.0).contains(&w.v) => w.v,
        Some(w) => {
            return Err(b.werr(
                &m.file,
                w,
                format!("G31 A{}: the infeed angle is from 0 to under 60 degrees", fmt_num(w.v)),
            ))
        }
        None => {
            let a = (0.5 * f / depth).atan().to_degrees();
            if offset != Offset::Radial {
                notes.push(format!(
                    "G31 without A: the infeed angle is arctan(F/2U) = {a:.2}°, the MANUALplus 4110's default (the 620 and 640 take 30°)"
                ));
            }
            a
        }
    };
    let dir = if z_end < z0 { -1.0 } else { 1.0 };
    // Run-in and overrun: given, or F·S/1000 with the spindle speed in rpm.
    let rpm = m.s.filter(|_| !m.css);
    let mut run = |name: &str, what: &str| -> f64 {
        if let Some(w) = b.get(name) {
            return m.len(w);
        }
        match rpm {
            Some(s) => {
                let v = f * s / 1000.0;
                notes.push(format!(
                    "G31 without {name} ({what}): F·S/1000 = {} mm with S{} rpm, the 4110's default",
                    fmt_num(v),
                    fmt_num(s)
                ));
                v
            }
            None => {
                notes.push(format!(
                    "G31 without {name} ({what}): its default F·S/1000 needs the spindle speed in rpm (G97 S), which the program does not give here: taken as 0"
                ));
                0.0
            }
        }
    };
    let run_in = run("B", "the run-in length");
    let overrun = run("P", "the overrun length");
    // The cuts are counted before any is made (an I of 10⁻¹² asked for 9·10¹¹ of them).
    let cuts = cut_count(law, depth, i) + q;
    if !(cuts <= crate::ground::bounds::MAX_PASSES as f64) {
        return Err(m.err(
            b.line,
            col,
            format!(
                "G31 U{} I{} V{v_number}: {} cuts, more than the {} passes threadcheck accepts (the infeed I is too small for the depth U)",
                fmt_num(u),
                fmt_shown(i),
                fmt_shown(cuts),
                crate::ground::bounds::MAX_PASSES
            ),
        ));
    }
    let mut radial = depths(law, depth, i);
    radial.extend(std::iter::repeat_n(depth, q as usize));
    let shifts = match offset {
        Offset::Radial => vec![0.0; radial.len()],
        // H1 moves the cuts to the left (−Z), H2 to the right.
        Offset::Left => cycles::shifts(Shift::Flank(angle), &radial, -1.0),
        Offset::Right => cycles::shifts(Shift::Flank(angle), &radial, 1.0),
        Offset::Alternating => cycles::shifts(Shift::Alternating(angle), &radial, -1.0),
    };
    if offset != Offset::Radial {
        notes.push(format!(
            "G31 H{h_number}: {} taken toward {} (a named default: the manuals say left and right)",
            if offset == Offset::Alternating { "the first offset is" } else { "each cut's offset is" },
            if offset == Offset::Right { "+Z" } else { "−Z" }
        ));
    }
    if starts > 1.0 {
        notes.push(format!(
            "G31 D{}: F taken as the lead, the starts {} mm apart, cut depth by depth (a named default)",
            fmt_num(starts),
            fmt_num(f / starts)
        ));
    }
    if m.css {
        m.note(b.line, col, "G31 under constant surface speed (G96); threading wants G97");
    }
    let x_start = x_end - 2.0 * r;
    let sign = if inside { 1.0 } else { -1.0 };
    m.break_chain();
    let op = m.begin_op("G31", b);
    if matches!(offset, Offset::Left | Offset::Right) {
        m.op_mut(op).infeed_angle = Some((angle, format!("A (H{h_number})")));
    }
    for note in notes {
        m.op_mut(op).notes.push(crate::ground::note::Note::from(note));
    }
    let phase0 = dir * c / 360.0 * f;
    for (d, sh) in radial.iter().zip(&shifts) {
        for k in 0..starts as usize {
            let phase = phase0 + dir * f * k as f64 / starts;
            let (xs, xe) = (x_start + sign * 2.0 * d, x_end + sign * 2.0 * d);
            let mut p = cycles::pass(
                xs,
                xe,
                z0 - dir * run_in + sh + phase,
                z_end + dir * overrun + sh,
                f,
                b.line,
                0.0,
                xe,
            );
            // The thread's phase is set where the cut starts.
            p.z_phase = p.z_start;
            m.push(op, b.line, p)?;
        }
    }
    // The depth is U's (the last cut is at U): the word to correct, not the end point X.
    if let Some(w) = b.get("U") {
        m.op_mut(op).depth_word =
            Some(super::motion::address_word(b, w, super::WordMeans::Depth { per_radial: 1.0 }));
    }
    m.x = Some(x0);
    m.z = Some(z0);
    Ok(())
}

impl Rules for State {
    fn block(&mut self, m: &mut Motion, b: &RBlock<'_>, _cx: &mut Ctx<'_>) -> Result<Flow, Error> {
        block(m, b)
    }
}

#[cfg(test)]
mod tests {
    use super::{depths, Law};

    fn close(a: &[f64], b: &[f64]) -> bool {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12)
    }

    #[test]
    fn infeed_laws_as_the_4110_manual_states_them() {
        // U 0.92, I 0.3. V0: 0.3·√n below 0.92 (n = 1..9: 0.3·√9 = 0.9), then 0.92.
        let v0: Vec<f64> = (1..=9).map(|n| 0.3 * f64::from(n).sqrt()).chain([0.92]).collect();
        assert!(close(&depths(Law::CrossSection, 0.92, 0.3), &v0));
        // V1: ceil(0.92/0.3) = 4 equal infeeds of 0.23.
        assert!(close(&depths(Law::Constant, 0.92, 0.3), &[0.23, 0.46, 0.69, 0.92]));
        // V3: 0.92 = 3·0.3 + 0.02: the first infeed 0.02, then 0.3 each.
        assert!(close(&depths(Law::RemainderFirst, 0.92, 0.3), &[0.02, 0.32, 0.62, 0.92]));
        // V2: as V3 up to 0.62, the last 0.3 in 1/2, 1/4, 1/8, 1/8: 0.15, 0.075, 0.0375, 0.0375.
        assert!(close(&depths(Law::LastDivided, 0.92, 0.3), &[0.02, 0.32, 0.62, 0.77, 0.845, 0.8825, 0.92]));
        // An exact division has no reduced first infeed.
        assert!(close(&depths(Law::RemainderFirst, 0.9, 0.3), &[0.3, 0.6, 0.9]));
    }
}
