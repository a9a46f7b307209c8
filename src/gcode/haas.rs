//! Haas lathes: Fanuc's G32, G92, macro B and calls, plus the one-block
//! `G76 X(U) Z(W) K D F [I] [A] [P] [Q]`, M23/M24 chamfer on/off and M97 local subroutines.
//!
//! Defaults where the Haas text is silent (stated in the output): Setting 86 (finish
//! allowance) = 0, Setting 99 (minimum cut) = 0, Setting 95 (chamfer size) = 1 lead at 45°
//! (Setting 96); P1 (one edge, constant chip area) when P is absent; no A = radial infeed.

use super::cycles;
use super::dialect::{Ctx, Flow, Rules};
use super::fanuc::{self, one_block_g76, Settings};
use super::motion::{Motion, RBlock};
use crate::Error;

/// Haas state: Fanuc's plus the chamfer switch.
#[derive(Default)]
pub(crate) struct State {
    fanuc: fanuc::State,
    chamfer_on: Option<bool>,
}

/// Runs one block.
fn block(s: &mut State, m: &mut Motion, b: &RBlock<'_>, cx: &mut Ctx<'_>) -> Result<Flow, Error> {
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
    if cycles::polar_block(m, b, &md)? {
        return Ok(Flow::Next);
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

impl Rules for State {
    fn block(&mut self, m: &mut Motion, b: &RBlock<'_>, cx: &mut Ctx<'_>) -> Result<Flow, Error> {
        block(self, m, b, cx)
    }
}
