//! Okuma OSP lathes (sources in docs/dialects.md, "Okuma OSP"):
//!
//! - `G33 X Z F [J] [C]`, a fixed cycle: one block is one pass from the start point (rapid in,
//!   thread to Z, rapid out and back, like Fanuc's G92), and the blocks after it that give only
//!   X repeat it at new diameters (OSP-P200L programming manual 5238-E, p. 97; CIMCO's OSP
//!   sample programs for the X-only repeats). `J` is the number of threads within F (the lead is
//!   F/J: `F25.4 J13` is 13 threads per inch); `C` is the start's phase, degrees.
//! - `G71 X Z B D U H F [J] [Q] [L]` (G72 for face threads, refused), the compound threading
//!   cycle (Okuma threading manual 3277-E, pp. 166–170; OSP-P200L p. 114): from the start point
//!   to the end point X Z, X the root diameter there; `H` the thread height, `D` the first cut
//!   depth and `U` the finishing allowance, all three **diameters**; `B` the included angle of
//!   the cut (0: straight in); `Q` the number of starts. The infeed is set by M32 (single
//!   blade: along one flank at B/2), M34 (reverse single blade: along the other) or M33
//!   (zig-zag: read as alternating flanks, a named default, its odd passes' law being lost in
//!   the source's page image); the depth pattern by M73, M74 or M75.
//!
//! Pattern 3 (M75 with M32 or M34), sourced (3277-E): the nth pass cuts to √n·D until the path
//! reaches H − U, then the tool is fed by U for the finishing pass.
//! Named defaults, stated in the output where they act: pattern 1 (M73) cuts n·D (constant
//! depth per pass; recalled, not read in a source); without M32–M34 and M73–M75 in force the
//! control's power-on states M32 and M73 are taken; F is the lead and Q starts lie lead/Q apart,
//! cut depth by depth. Refused by
//! name: M74 (pattern
//! 2: not in the pages read), G72, tapers (A, I), a lead change (E) and the multi-start phase of
//! G71 beyond Q.

use super::cycles::{self, Shift};
use super::dialect::{Ctx, Flow, Rules};
use super::motion::{Motion, RBlock};
use crate::Error;

/// Okuma state: the G33 fixed cycle in force (for X-only repeats) and the modal infeed and
/// depth-pattern M codes.
#[derive(Default)]
pub(crate) struct State {
    /// The G33 cycle an X-only block repeats: operation, end Z, lead, start Z.
    g33: Option<(usize, f64, f64, f64)>,
    /// M32, M33 or M34, once a block sets it.
    infeed: Option<u32>,
    /// M73, M74 or M75, once a block sets it.
    pattern: Option<u32>,
}

fn block(s: &mut State, m: &mut Motion, b: &RBlock<'_>, _cx: &mut Ctx<'_>) -> Result<Flow, Error> {
    let md = cycles::modal(m, b)?;
    for w in b.words.iter().filter(|w| w.name == "M") {
        match w.v {
            32.0 | 33.0 | 34.0 => s.infeed = Some(w.v as u32),
            73.0 | 74.0 | 75.0 => s.pattern = Some(w.v as u32),
            _ => {}
        }
    }
    if md.one_shot.is_some() {
        cycles::other_block(m, b, &md)?;
        return Ok(Flow::Next);
    }
    let col = md.col.unwrap_or(b.col);
    match md.motion as u32 {
        33 => g33(s, m, b, col),
        71 if md.col.is_some() => {
            s.g33 = None;
            g71(s, m, b, col)
        }
        72 if md.col.is_some() => Err(m.err(
            b.line,
            col,
            "G72 (Okuma's compound cycle for face threads) is not supported: threadcheck checks threads along Z",
        )),
        _ => {
            s.g33 = None;
            cycles::other_block(m, b, &md)
        }
    }?;
    Ok(Flow::Next)
}

/// The lead: F, divided by J (threads within F) when J is given.
fn lead(m: &Motion, b: &RBlock<'_>, col: usize, what: &str) -> Result<Option<f64>, Error> {
    let Some(f) = b.get("F") else { return Ok(None) };
    let f = m.len(f);
    let j = b.get("J").map_or(1.0, |w| w.v);
    if !(f > 0.0 && j >= 1.0 && j.fract() == 0.0) {
        return Err(m.err(
            b.line,
            col,
            format!("{what} F{f} J{j}: the lead F must be positive and J (threads within F) a whole number from 1"),
        ));
    }
    Ok(Some(f / j))
}

/// Refuses the words of `what` that set what threadcheck does not model (tapers, a lead change).
fn refuse_words(m: &Motion, b: &RBlock<'_>, what: &str) -> Result<(), Error> {
    for (w, why) in [
        ("A", "a taper (A, the taper angle) is not modelled for Okuma threads"),
        ("I", "a taper (I, the radius difference) is not modelled for Okuma threads"),
        ("E", "a lead change per revolution (E, variable lead) is not modelled"),
    ] {
        if let Some(word) = b.get(w).filter(|x| x.v != 0.0) {
            return Err(b.werr(&m.file, word, format!("{what} {w}{}: {why}", word.v)));
        }
    }
    Ok(())
}

/// G33: one pass from the start point; an X-only block repeats it.
fn g33(s: &mut State, m: &mut Motion, b: &RBlock<'_>, col: usize) -> Result<(), Error> {
    refuse_words(m, b, "G33")?;
    b.allow_only(&m.file, "GXZFJCLNMST", "G33")?;
    cycles::need_lathe_plane(m, b, col, "G33")?;
    let (x, _, z) = m.target(b);
    let (_, z0) = m.need_position(b.line, col, "G33")?;
    let given = lead(m, b, col, "G33")?;
    let repeat = match s.g33 {
        Some((op, z_end, lead, zs)) if z.is_none() && given.is_none() => Some((op, z_end, lead, zs)),
        _ => None,
    };
    let (op, z_end, lead, zs) = match repeat {
        Some(r) => r,
        None => {
            let lead = given.or(m.lead).ok_or_else(|| m.err(b.line, col, "G33 needs F, the lead"))?;
            let z_end = z.ok_or_else(|| m.err(b.line, col, "G33 needs Z, the end of the thread"))?;
            let c = b.get("C").map_or(0.0, |w| w.v);
            let dir = if z_end < z0 { -1.0 } else { 1.0 };
            let zs = z0 + dir * c / 360.0 * lead;
            m.break_chain();
            (m.begin_op("G33", b), z_end, lead, zs)
        }
    };
    m.lead = Some(lead);
    s.g33 = Some((op, z_end, lead, zs));
    let Some(x_end) = x else {
        return Err(m.err(b.line, col, "G33 needs X, the diameter of this pass"));
    };
    if m.css {
        m.note(b.line, col, "G33 under constant surface speed (G96); threading wants G97");
    }
    m.push(op, b.line, cycles::pass(x_end, x_end, zs, z_end, lead, b.line, 0.0, x_end))
}

/// G71: the compound threading cycle along Z.
fn g71(s: &mut State, m: &mut Motion, b: &RBlock<'_>, col: usize) -> Result<(), Error> {
    refuse_words(m, b, "G71")?;
    b.allow_only(&m.file, "GXZBDUHFJQLNMST", "G71")?;
    cycles::need_lathe_plane(m, b, col, "G71")?;
    let (x0, z0) = m.need_position(b.line, col, "G71")?;
    let (x, _, z) = m.target(b);
    let need = |what: &str| m.err(b.line, col, format!("G71 needs {what}"));
    let x_root = x.ok_or_else(|| need("X, the root diameter at the end of the thread"))?;
    let z_end = z.ok_or_else(|| need("Z, the end of the thread"))?;
    let lead = lead(m, b, col, "G71")?.ok_or_else(|| need("F, the lead"))?;
    let h = b.get("H").map(|w| m.len(w)).ok_or_else(|| need("H, the thread height (diameter)"))?;
    let d = b.get("D").map(|w| m.len(w)).ok_or_else(|| need("D, the first cut depth (diameter)"))?;
    let u = b.get("U").map_or(0.0, |w| m.len(w));
    let angle = b.get("B").map_or(0.0, |w| w.v);
    let starts = b.get("Q").map_or(1.0, |w| w.v);
    if !(h > 0.0 && d > 0.0 && u >= 0.0 && u < h) {
        return Err(m.err(
            b.line,
            col,
            format!("G71 H{h} D{d} U{u}: H and D must be positive and U from 0 to under H (all diameters)"),
        ));
    }
    if !(0.0..180.0).contains(&angle) {
        return Err(m.err(
            b.line,
            col,
            format!("G71 B{angle}: the cut angle is from 0 to under 180 degrees"),
        ));
    }
    if !(starts >= 1.0 && starts.fract() == 0.0 && starts <= 100.0) {
        return Err(m.err(
            b.line,
            col,
            format!("G71 Q{starts}: the number of starts is a whole number from 1"),
        ));
    }
    let mut notes = Vec::new();
    let infeed = match s.infeed {
        Some(c) => c,
        None => {
            notes.push(
                "no M32, M33 or M34 before G71: M32 (single blade), the control's power-on state, is taken"
                    .to_string(),
            );
            32
        }
    };
    let pattern = match s.pattern {
        Some(p) => p,
        None => {
            notes.push(
                "no M73, M74 or M75 before G71: M73 (pattern 1), the control's power-on state, is taken"
                    .to_string(),
            );
            73
        }
    };
    if infeed == 33 {
        notes.push(
            "G71 M33 (zig-zag) read as alternating flanks: each pass moves along the flank at B/2 by its depth increment, to one side and then the other (threadcheck's alternating infeed); a named default, the law of its odd passes not being legible in the source read (Okuma OSP-P200L p. 114)"
                .to_string(),
        );
    }
    let rough_to = h - u;
    let mut depths = Vec::new();
    let mut n = 1.0f64;
    loop {
        let dn = match pattern {
            73 => d * n,
            75 => d * n.sqrt(),
            _ => {
                return Err(m.err(
                    b.line,
                    col,
                    "G71 with M74 (depth pattern 2) is not supported: its law is not in the sources read; use M73 or M75",
                ))
            }
        };
        if dn >= rough_to - 1e-9 {
            depths.push(rough_to);
            break;
        }
        depths.push(dn);
        n += 1.0;
        if depths.len() > crate::ground::bounds::MAX_PASSES {
            return Err(m.err(b.line, col, "G71 expands to too many passes"));
        }
    }
    if u > 0.0 {
        depths.push(h);
    }
    if pattern == 73 {
        notes.push(format!(
            "G71 M73 (pattern 1) taken as a constant depth D = {} mm (diameter) per pass: a named default, not read in a source",
            crate::ground::fmt::fmt_num(d)
        ));
    }
    notes.push(
        "G71 D, U and H read as diameters: Okuma's threading manual 3277-E shows them halved (D/2, H/2, U/2) in one figure, its text does not say (inferred from that figure)"
            .to_string(),
    );
    if b.has("L") {
        notes.push(
            "G71 L (the overrun at the last pass with M23) is not modelled: the passes end at Z".to_string(),
        );
    }
    // Radial depths (the words are diameters) for the shifts along the flank.
    let radial: Vec<f64> = depths.iter().map(|v| 0.5 * v).collect();
    let external = x_root < x0;
    let sign = if external { 1.0 } else { -1.0 };
    let dir = if z_end < z0 { -1.0 } else { 1.0 };
    let half = 0.5 * angle;
    let shift = match (half > 0.0, infeed) {
        (true, 33) => Shift::Alternating(half),
        (true, _) => Shift::Flank(half),
        (false, _) => Shift::Radial,
    };
    // M34 (reverse single blade) feeds along the other flank.
    let flank_dir = if infeed == 34 { -dir } else { dir };
    let shifts = cycles::shifts(shift, &radial, flank_dir);
    if m.css {
        m.note(b.line, col, "G71 under constant surface speed (G96); threading wants G97");
    }
    m.break_chain();
    let op = m.begin_op("G71", b);
    if half > 0.0 {
        m.op_mut(op).infeed_angle = Some((half, format!("B/2 (M{infeed})")));
    }
    for note in notes {
        m.op_mut(op).notes.push(crate::ground::note::Note::from(note));
    }
    let n_starts = starts as usize;
    for (dn, sh) in depths.iter().zip(&shifts) {
        for k in 0..n_starts {
            let phase = dir * lead * k as f64 / starts;
            let x_pass = x_root + sign * (h - dn);
            m.push(
                op,
                b.line,
                cycles::pass(x_pass, x_pass, z0 + sh + phase, z_end, lead, b.line, 0.0, x_pass),
            )?;
        }
    }
    m.x = Some(x0);
    m.z = Some(z0);
    Ok(())
}

impl Rules for State {
    fn block(&mut self, m: &mut Motion, b: &RBlock<'_>, cx: &mut Ctx<'_>) -> Result<Flow, Error> {
        block(self, m, b, cx)
    }
}
