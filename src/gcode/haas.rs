//! Haas lathes: Fanuc's G32, G92, macro B and calls, plus the one-block
//! `G76 X(U) Z(W) K D F [I] [A] [P] [Q]`, M23/M24 chamfer on/off and M97 local subroutines.
//!
//! Defaults where the Haas text is silent (stated in the output): Setting 86 (finish
//! allowance) = 0, Setting 99 (minimum cut) = 0, Setting 95 (chamfer size) = 1 lead at 45°
//! (Setting 96); P1 (one edge, constant chip area) when P is absent; no A = radial infeed.

use super::cycles::{self, Shift};
use super::fanuc;
use super::interp::{Ctx, Flow};
use super::motion::{Motion, RBlock};
use crate::Error;

/// Haas's machine settings the G76 cycle reads.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Settings {
    /// Setting 86, thread finish allowance (radius, mm).
    pub finish: f64,
    /// Setting 99, thread minimum cut (radius, mm).
    pub min_cut: f64,
    /// Setting 95, chamfer size in leads (when M23 is on).
    pub chamfer_leads: f64,
    /// M23 on (chamfer) or M24 off.
    pub chamfer: bool,
}

impl Default for Settings {
    fn default() -> Settings {
        Settings { finish: 0.0, min_cut: 0.0, chamfer_leads: 1.0, chamfer: false }
    }
}

/// Haas state: Fanuc's plus the chamfer switch.
#[derive(Default)]
pub(crate) struct State {
    fanuc: fanuc::State,
    chamfer_on: Option<bool>,
}

/// Runs one block.
pub(crate) fn block(s: &mut State, m: &mut Motion, b: &RBlock<'_>, cx: &mut Ctx<'_>) -> Result<Flow, Error> {
    let md = cycles::modal(m, b)?;
    for w in b.words.iter().filter(|w| w.name == "M") {
        match w.v {
            23.0 => s.chamfer_on = Some(true),
            24.0 => s.chamfer_on = Some(false),
            97.0 => {
                let p = b.get("P").ok_or_else(|| {
                    b.werr(&m.file, w, "M97 needs P, the sequence number of the local subroutine")
                })?;
                let reps = b.get("L").map_or(1.0, |l| l.v);
                if !(reps >= 0.0 && reps.fract() == 0.0 && reps <= crate::ground::bounds::MAX_REPEATS as f64)
                {
                    return Err(b.werr(
                        &m.file,
                        w,
                        format!("M97 L{reps}: repetitions must be a whole number"),
                    ));
                }
                return Ok(Flow::LocalCall { n: p.v, repeats: reps as u32, col: w.col });
            }
            _ => {}
        }
    }
    if let Some(f) = fanuc::calls(m, b)? {
        return Ok(f);
    }
    fanuc::check_turning_cycle_targets(m, b, &md, cx);
    if md.motion == 76.0 && md.col.is_some() && md.one_shot.is_none() {
        let col = md.col.unwrap_or(b.col);
        cycles::need_lathe_plane(m, b, col, "G76")?;
        let settings = Settings { chamfer: s.chamfer_on.unwrap_or(false), ..Settings::default() };
        let op_note = s.chamfer_on.is_none();
        one_block_g76(m, b, col, &settings, "G76")?;
        if op_note {
            let line = b.line;
            m.note(line, col, "no M23/M24 before G76: the thread chamfer is taken as off (M24)");
        }
        return Ok(Flow::Next);
    }
    fanuc::thread_block(&mut s.fanuc, m, b, &md)?;
    Ok(Flow::Next)
}

/// The one-block G76 (Haas; Fanuc Series 10/11/15 tape format): X the root diameter, K the
/// thread height, D the first depth (radius), F the lead, I the taper (radius), A the tool
/// angle (flank infeed at A/2; none: radial), P the cutting method (P1 one edge, constant chip
/// area; P2 alternating, constant area; P3 one edge, constant depth; P4 alternating, constant
/// depth), Q the start angle (0.001°). Pass n goes to D·√n (P1, P2) or n·D (P3, P4) while below
/// K less the finish allowance, each step at least the minimum cut; then the allowance at K.
pub(crate) fn one_block_g76(
    m: &mut Motion,
    b: &RBlock<'_>,
    col: usize,
    st: &Settings,
    cycle: &str,
) -> Result<(), Error> {
    b.allow_only(&m.file, "GXZUWKDFEIAPQNMST", "the one-block G76")?;
    let f = fanuc::lead(m, b, col, cycle)?;
    let (x0, z0) = m.need_position(b.line, col, cycle)?;
    let (x, _, z) = m.target(b);
    let x_root = x.ok_or_else(|| m.err(b.line, col, format!("{cycle} needs X, the root diameter")))?;
    let z_end = z.ok_or_else(|| m.err(b.line, col, format!("{cycle} needs Z, the end of the thread")))?;
    let k = b
        .get("K")
        .map(|w| m.len(w))
        .ok_or_else(|| m.err(b.line, col, format!("{cycle} needs K, the thread height")))?;
    let d = b
        .get("D")
        .map(|w| m.len(w))
        .ok_or_else(|| m.err(b.line, col, format!("{cycle} needs D, the first depth")))?;
    let taper = b.get("I").map_or(0.0, |w| m.len(w));
    let a = b.get("A").map_or(0.0, |w| w.v);
    let p = b.get("P").map_or(1.0, |w| w.v);
    let q = b.get("Q").map_or(0.0, |w| if w.point { w.v } else { w.v / 1000.0 });
    if let Some(w) = b.get("A").filter(|w| w.point && w.v.fract() != 0.0) {
        return Err(b.werr(
            &m.file,
            w,
            format!("{cycle} A{} has a decimal point: write the tool angle in whole degrees", w.v),
        ));
    }
    if !(k > 0.0 && d > 0.0) {
        return Err(m.err(b.line, col, format!("{cycle} K and D must be greater than zero")));
    }
    if !(0.0..=120.0).contains(&a) {
        return Err(m.err(b.line, col, format!("{cycle} tool angle A{a} must be from 0 to 120")));
    }
    if ![1.0, 2.0, 3.0, 4.0].contains(&p) {
        return Err(m.err(b.line, col, format!("{cycle} P{p}: the cutting method is P1, P2, P3 or P4")));
    }
    if st.finish >= k {
        return Err(m.err(
            b.line,
            col,
            format!("{cycle} finish allowance {} mm is not less than K", st.finish),
        ));
    }
    if m.css {
        m.note(b.line, col, format!("{cycle} under constant surface speed (G96); threading wants G97"));
    }
    let rough_to = k - st.finish;
    let mut depths = Vec::new();
    let mut prev = 0.0f64;
    let mut n = 1.0f64;
    loop {
        let mut dn = if p <= 2.0 { d * n.sqrt() } else { d * n };
        if dn - prev < st.min_cut {
            dn = prev + st.min_cut;
        }
        // Within rounding of the end (D = K/4 is a common CAM choice: 16 passes exactly).
        if dn >= rough_to - 1e-9 {
            depths.push(rough_to);
            break;
        }
        depths.push(dn);
        prev = dn;
        n += 1.0;
        if depths.len() > crate::ground::bounds::MAX_PASSES {
            return Err(m.err(b.line, col, format!("{cycle} expands to too many passes")));
        }
    }
    if st.finish > 0.0 {
        depths.push(k);
    }
    let sign = if x_root < x0 { 1.0 } else { -1.0 };
    let dir = if z_end < z0 { -1.0 } else { 1.0 };
    let half = 0.5 * a;
    let shift = match (half > 0.0, p == 2.0 || p == 4.0) {
        (false, _) => Shift::Radial,
        (true, false) => Shift::Flank(half),
        (true, true) => Shift::Alternating(half),
    };
    let shifts = cycles::shifts(shift, &depths, dir);
    let chamfer = if st.chamfer { st.chamfer_leads * f } else { 0.0 };
    let phase = dir * q / 360.0 * f;
    let op = m.begin_op(cycle, b.line);
    if half > 0.0 {
        m.op_mut(op).infeed_angle = Some((half, "A/2".into()));
    }
    m.op_mut(op).notes.push(format!(
        "{cycle}: Setting 86 (finish allowance) {} mm and Setting 99 (minimum cut) {} mm assumed; P{p}",
        st.finish, st.min_cut
    ));
    for (dn, sh) in depths.iter().zip(shifts) {
        let x_end = x_root + sign * 2.0 * (k - dn);
        let x_start = x_end + 2.0 * taper;
        let x_out = x_end + sign * 2.0 * chamfer;
        m.push(op, b.line, cycles::pass(x_start, x_end, z0 + sh + phase, z_end, f, b.line, chamfer, x_out))?;
    }
    m.x = Some(x0);
    m.z = Some(z0);
    Ok(())
}
