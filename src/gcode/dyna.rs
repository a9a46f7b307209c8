//! Dyna DM2900 / Myte training controls, the dialect of the two seed milling papers: `#n=`
//! assignments (`#0` is an ordinary variable here), functions without brackets (`COS#14`,
//! `SQR #13`), counted loops `M73 N k` … `M74`, G0/G1/G2/G3 moves in G17. The conversational
//! `THREAD` cycle is refused: its pass law is not published.

use super::cycles;
use super::dialect::{Ctx, Flow, Rules};
use super::lexer::Block;
use super::motion::{Motion, RBlock};
use crate::Error;

/// Dyna needs no modal state beyond the motion state.
#[derive(Default)]
pub(crate) struct State {}

/// Refuses a program in Dyna's conversational threading language before reading it, naming the
/// THREAD block (its other lines, `G0fX 21.000`, are not G-code either).
pub(crate) fn prescan(text: &str) -> Result<(), (usize, usize, String)> {
    for (i, line) in text.lines().enumerate() {
        let t = line.trim_start();
        if t.to_ascii_uppercase().starts_with("THREAD") {
            return Err((
                i + 1,
                line.len() - t.len() + 1,
                "the DYNA THREAD cycle is not supported: its pass law is not published (program the passes with G33)".into(),
            ));
        }
    }
    Ok(())
}

/// Runs one block.
fn block(_s: &mut State, m: &mut Motion, b: &RBlock<'_>, _cx: &mut Ctx<'_>) -> Result<Flow, Error> {
    let md = cycles::modal(m, b)?;
    for w in b.words.iter().filter(|w| w.name == "M") {
        match w.v {
            30.0 | 2.0 => return Ok(Flow::End),
            73.0 => {
                let n = b
                    .words
                    .iter()
                    .rev()
                    .find(|x| x.name == "N")
                    .ok_or_else(|| b.werr(&m.file, w, "M73 needs N, the loop count"))?;
                return Ok(Flow::LoopStart { count: n.v, col: w.col });
            }
            74.0 => return Ok(Flow::LoopEnd { col: w.col }),
            _ => {}
        }
    }
    cycles::other_block(m, b, &md)?;
    Ok(Flow::Next)
}

/// The M74 that closes the M73 at `pc`.
fn matching_end(blocks: &[Block], pc: usize) -> Option<usize> {
    let mut depth = 0i64;
    for (i, b) in blocks.iter().enumerate().skip(pc) {
        for w in b.words.iter().filter(|w| w.name == "M") {
            if let super::lexer::WVal::Num { v, .. } = w.val {
                if v == 73.0 {
                    depth += 1;
                } else if v == 74.0 {
                    depth -= 1;
                    if depth == 0 {
                        return Some(i);
                    }
                }
            }
        }
    }
    None
}

impl Rules for State {
    fn block(&mut self, m: &mut Motion, b: &RBlock<'_>, cx: &mut Ctx<'_>) -> Result<Flow, Error> {
        block(self, m, b, cx)
    }

    fn loop_end(&self, blocks: &[Block], pc: usize) -> Option<usize> {
        matching_end(blocks, pc)
    }
}
