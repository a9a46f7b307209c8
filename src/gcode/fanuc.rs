//! Fanuc: `G32` (F the lead along the longer axis, Q the start angle), `G92` (with X-only repeat
//! blocks and R taper), the two-block `G76` of the 0T/16T/0i controls, the one-block `G76` of
//! the Series 10/11/15 tape format (recognised by its K and D words), subprograms `M98 P… L…`
//! and macro calls `G65 P… A… B…`, `M99` returns.

use super::cycles::{self, Modal, Shift};
use super::dialect::{Ctx, Flow, Rules};
use super::motion::{Motion, RBlock, RWord};
use crate::Error;

/// The first G76 block's settings.
#[derive(Clone, Copy, Debug)]
pub(crate) struct G76First {
    finish_passes: u32,
    chamfer_tenths: u32,
    angle: f64,
    min_depth: f64,
    finish: f64,
}

/// Fanuc's modal cycle state.
#[derive(Default)]
pub(crate) struct State {
    g76: Option<G76First>,
    /// The G92 cycle in force: its operation, end Z, taper R and start-angle shift.
    g92: Option<(usize, f64, f64, f64)>,
}

/// G65 argument letters → local variables (argument specification I).
pub(crate) fn g65_local(letter: &str) -> Option<i64> {
    Some(match letter {
        "A" => 1,
        "B" => 2,
        "C" => 3,
        "I" => 4,
        "J" => 5,
        "K" => 6,
        "D" => 7,
        "E" => 8,
        "F" => 9,
        "H" => 11,
        "M" => 13,
        "Q" => 17,
        "R" => 18,
        "S" => 19,
        "T" => 20,
        "U" => 21,
        "V" => 22,
        "W" => 23,
        "X" => 24,
        "Y" => 25,
        "Z" => 26,
        _ => return None,
    })
}

/// The call and return words shared by Fanuc and Haas (M98, G65, M99, M30/M2). `None` when the
/// block is none of them.
pub(crate) fn calls(m: &Motion, b: &RBlock<'_>) -> Result<Option<Flow>, Error> {
    let file = m.file.as_str();
    if b.has_m(30.0) || b.has_m(2.0) {
        return Ok(Some(Flow::End));
    }
    if let Some((_, col)) = b.gs().find(|(g, _)| *g == 65.0 || *g == 66.0) {
        let p = b.get("P").ok_or_else(|| m.err(b.line, col, "G65 needs P, the macro's program number"))?;
        if b.gs().any(|(g, _)| g == 66.0) {
            return Err(m.err(b.line, col, "G66 modal macro calls are not supported (G65 is)"));
        }
        let reps = b.get("L").map_or(1.0, |l| l.v);
        let mut locals = Vec::new();
        for w in &b.words {
            match w.name {
                "G" | "P" | "L" | "N" | "O" => {}
                l => match g65_local(l) {
                    Some(k) => locals.push((k, w.v)),
                    None => return Err(b.werr(file, w, format!("{l} is not a G65 argument"))),
                },
            }
        }
        return Ok(Some(Flow::Call {
            name: program_name(p.v),
            repeats: whole(m, b, reps, col)?,
            locals: Some(locals),
            col,
        }));
    }
    for w in &b.words {
        if w.name != "M" {
            continue;
        }
        match w.v {
            98.0 => {
                let p = b.get("P").ok_or_else(|| b.werr(file, w, "M98 needs P, the subprogram number"))?;
                // P51002: O1002 five times (more than four digits: the leading ones repeat).
                let pv = p.v.round() as u64;
                let (prog, reps) = match b.get("L") {
                    Some(l) => (pv, l.v),
                    None if pv >= 10_000 && p.text.len() > 5 => (pv % 10_000, (pv / 10_000) as f64),
                    None => (pv, 1.0),
                };
                return Ok(Some(Flow::Call {
                    name: format!("O{prog}"),
                    repeats: whole(m, b, reps, w.col)?,
                    locals: None,
                    col: w.col,
                }));
            }
            99.0 => {
                return Ok(Some(Flow::Return { to_n: b.get("P").map(|p| p.v), col: w.col }));
            }
            _ => {}
        }
    }
    Ok(None)
}

fn program_name(v: f64) -> String {
    format!("O{}", v.round() as u64)
}

fn whole(m: &Motion, b: &RBlock<'_>, v: f64, col: usize) -> Result<u32, Error> {
    if !(v >= 0.0 && v.fract() == 0.0 && v <= crate::ground::bounds::MAX_REPEATS as f64) {
        return Err(m.err(
            b.line,
            col,
            format!(
                "repetition count {v} must be a whole number up to {}",
                crate::ground::bounds::MAX_REPEATS
            ),
        ));
    }
    Ok(v as u32)
}

/// Fanuc's lead word F (E for the inch-precise form), modal.
pub(crate) fn lead(m: &mut Motion, b: &RBlock<'_>, col: usize, what: &str) -> Result<f64, Error> {
    let mut f = None;
    for w in b.words.iter().filter(|w| w.name == "F" || w.name == "E") {
        let v = m.len(w);
        if !(v > 0.0) {
            return Err(b.werr(&m.file, w, format!("lead {v} must be greater than zero")));
        }
        f = Some(v);
    }
    if let Some(f) = f {
        m.lead = Some(f);
    }
    m.lead.ok_or_else(|| match b.why_missing("F").or_else(|| b.why_missing("E")) {
        Some(why) => m.err(b.line, col, format!("{what} without a lead: {why}")),
        None => m.err(b.line, col, format!("{what} without a lead: add F (the lead per revolution)")),
    })
}

/// A start-angle word Q of G32/G92 (0.001° without a decimal point).
fn start_angle(b: &RBlock<'_>) -> f64 {
    b.get("Q").map_or(0.0, |q| if q.point { q.v } else { q.v / 1000.0 })
}

/// Runs one block.
fn block(s: &mut State, m: &mut Motion, b: &RBlock<'_>, cx: &mut Ctx<'_>) -> Result<Flow, Error> {
    let md = cycles::modal(m, b)?;
    if let Some(f) = calls(m, b)? {
        return Ok(f);
    }
    if cycles::polar_block(m, b, &md)? {
        return Ok(Flow::Next);
    }
    check_turning_cycle_targets(m, b, &md, cx);
    thread_block(s, m, b, &md)?;
    Ok(Flow::Next)
}

/// Notes a Fanuc turning cycle (G70–G73) whose P/Q blocks do not exist: it is read past.
pub(crate) fn check_turning_cycle_targets(m: &mut Motion, b: &RBlock<'_>, md: &Modal, cx: &Ctx<'_>) {
    if let Some(g) = md.one_shot.filter(|g| (70.0..=73.0).contains(g)) {
        for n in ["P", "Q"] {
            if let Some(w) = b.get(n) {
                if !cx.has_n(w.v) {
                    m.note(
                        b.line,
                        w.col,
                        format!(
                            "G{g} {n}{}: there is no block N{} in this program; the cycle is skipped",
                            w.v, w.v
                        ),
                    );
                }
            }
        }
    }
}

/// The threading words of Fanuc and Haas programs, after the modal codes.
pub(crate) fn thread_block(s: &mut State, m: &mut Motion, b: &RBlock<'_>, md: &Modal) -> Result<(), Error> {
    let col = md.col.unwrap_or(b.col);
    if md.one_shot.is_some() {
        return cycles::other_block(m, b, md);
    }
    if md.motion != 92.0 {
        s.g92 = None;
    }
    match md.motion as u32 {
        // On a machining centre G76 is fine boring (cycles.rs).
        76 if md.col.is_some() && m.lathe() => {
            let name = m.g_name(76);
            cycles::need_lathe_plane(m, b, col, &name)?;
            if b.has("K") || b.has("D") {
                one_block_g76(m, b, col, &Settings::default(), &name)
            } else {
                two_block_g76(s, m, b, col)
            }
        }
        92 if m.lathe() => g92(s, m, b, col),
        32 | 33 => {
            if b.get("X").is_none() && b.get("Z").is_none() && b.get("U").is_none() && b.get("W").is_none() {
                m.skipped += 1;
                return Ok(());
            }
            let name = m.g_name(32);
            // Along Z on the centre line: a tap, not a thread turned (../shared/notes/
            // machining-centres.md §7).
            if m.lathe() && m.x.is_some_and(|x| x.abs() < 1e-9) && !b.has("X") && !b.has("U") {
                return centre_tap(m, b, col, &name);
            }
            cycles::need_lathe_plane(m, b, col, &name)?;
            b.allow_only(&m.file, "GXZUWFEQNMST", &name)?;
            let f = lead(m, b, col, &name)?;
            m.thread_move(b, col, &name, |dx, dz| cycles::axial_lead_longer_axis(f, dx, dz), start_angle(b))
        }
        _ => cycles::other_block(m, b, md),
    }
}

/// A lathe's tap on the centre line written as thread-cutting moves (`G32 Z-20 F1.5`, the
/// spindle reversed, `G32 Z5`): the move into the part (toward −Z) is a tapping cycle of lead F,
/// its bottom the move's end, its hand the spindle's going in (a named reading: Haas documents
/// G32 as a synchronized move, and the note §7 reads the pair as a tap); the move out is its
/// return.
fn centre_tap(m: &mut Motion, b: &RBlock<'_>, col: usize, name: &str) -> Result<(), Error> {
    let (_, _, z) = m.target(b);
    let Some(z) = z else {
        m.skipped += 1;
        return Ok(());
    };
    let f = lead(m, b, col, name)?;
    let into = m.z.is_some_and(|from| z < from);
    if into {
        m.push_synced_tap(name, b.line, col, (Some(0.0), None), Some(z), Some(f), "F")?;
    }
    m.z = Some(z);
    m.read_past(
        b.line,
        col,
        name,
        if into {
            "a tap on the centre line (thread cutting along Z at X0; threadcheck tap checks it)"
        } else {
            "a tap's return along Z at X0"
        },
    );
    Ok(())
}

fn g92(s: &mut State, m: &mut Motion, b: &RBlock<'_>, col: usize) -> Result<(), Error> {
    let name = m.g_name(92);
    b.allow_only(&m.file, "GXZUWRFEQNMST", &name)?;
    cycles::need_lathe_plane(m, b, col, &name)?;
    m.break_chain();
    let lead = lead(m, b, col, &name)?;
    let (x, _, z) = m.target(b);
    let (_, z0) = m.need_position(b.line, col, &name)?;
    let r = match b.get("R") {
        Some(w) => m.len(w),
        None => s.g92.map_or(0.0, |g| g.2),
    };
    let q = if b.has("Q") { start_angle(b) } else { s.g92.map_or(0.0, |g| g.3) };
    let z_end = z
        .or(s.g92.map(|g| g.1))
        .ok_or_else(|| m.err(b.line, col, format!("{name} needs Z, the end of the thread")))?;
    let op = match s.g92 {
        Some((op, ze, _, _)) if (ze - z_end).abs() < 1e-9 && (m.op_mut(op).lead() - lead).abs() < 1e-12 => op,
        _ => m.begin_op(&name, b),
    };
    s.g92 = Some((op, z_end, r, q));
    let Some(x_end) = x else {
        // A G92 block without X only sets the cycle up.
        return Ok(());
    };
    if m.css {
        m.note(b.line, col, format!("{name} under constant surface speed (G96); threading wants G97"));
    }
    // The cycle starts and ends at the start point; R is radius(start) − radius(end).
    let x_start = x_end + 2.0 * r;
    let dir = if z_end < z0 { -1.0 } else { 1.0 };
    let zs = z0 + dir * q / 360.0 * lead;
    m.push(op, b.line, cycles::pass(x_start, x_end, zs, z_end, lead, b.line, 0.0, x_end))
}

/// An integer word read in least-input increments: 0.001 mm, or 0.0001 in under G20.
fn increments(m: &Motion, b: &RBlock<'_>, w: &RWord<'_>, what: &str) -> Result<f64, Error> {
    let per_unit = if m.scale == 1.0 { 1000.0 } else { 10_000.0 };
    if w.point {
        return Err(b.werr(
            &m.file,
            w,
            format!(
                "G76 {} has a decimal point, but {what} is read in least-input increments ({}): write {}{}",
                w.text,
                if m.scale == 1.0 { "µm" } else { "0.0001 in" },
                w.name,
                (w.v * per_unit).round() as i64
            ),
        ));
    }
    Ok(w.v / per_unit * m.scale)
}

fn two_block_g76(s: &mut State, m: &mut Motion, b: &RBlock<'_>, col: usize) -> Result<(), Error> {
    let name = m.g_name(76);
    let second = b.has("X") || b.has("U") || b.has("Z") || b.has("W");
    if !second {
        // First block: P(m)(r)(a) Q(Δd min) R(d).
        b.allow_only(&m.file, "GPQRNMST", &format!("the first {name} block"))?;
        let p = b
            .get("P")
            .ok_or_else(|| m.err(b.line, col, "the first G76 block needs P(m)(r)(a), e.g. P011060"))?;
        if p.point {
            return Err(b.werr(
                &m.file,
                p,
                format!("{name} {} has a decimal point: P(m)(r)(a) is six digits, e.g. P011060", p.text),
            ));
        }
        let pv = p.v as u64;
        let (mm, r, a) = ((pv / 10_000) as u32, ((pv / 100) % 100) as u32, (pv % 100) as f64);
        if ![80.0, 60.0, 55.0, 30.0, 29.0, 0.0].contains(&a) {
            return Err(b.werr(
                &m.file,
                p,
                format!("{name} tool angle {a} is not one of 80, 60, 55, 30, 29, 0"),
            ));
        }
        let q = match b.get("Q") {
            Some(w) => increments(m, b, w, "the minimum depth Q")?,
            None => 0.0,
        };
        let finish = match b.get("R") {
            // R without a point is in least-input increments too.
            Some(w) if !w.point => w.v / if m.scale == 1.0 { 1000.0 } else { 10_000.0 } * m.scale,
            Some(w) => m.len(w),
            None => 0.0,
        };
        s.g76 =
            Some(G76First { finish_passes: mm.max(1), chamfer_tenths: r, angle: a, min_depth: q, finish });
        return Ok(());
    }
    b.allow_only(&m.file, "GXZUWRPQFENMST", "the second G76 block")?;
    let Some(first) = s.g76 else {
        return Err(m.err(
            b.line,
            col,
            format!(
                "{name} second block (X Z P Q F) without its first block ({name} P(m)(r)(a) Q R) before it"
            ),
        ));
    };
    let lead = lead(m, b, col, &name)?;
    let (x0, z0) = m.need_position(b.line, col, &name)?;
    let (x, _, z) = m.target(b);
    let x_root = x.ok_or_else(|| m.err(b.line, col, format!("{name} needs X, the root diameter")))?;
    let z_end = z.ok_or_else(|| m.err(b.line, col, format!("{name} needs Z, the end of the thread")))?;
    let k = increments(
        m,
        b,
        b.get("P").ok_or_else(|| m.err(b.line, col, format!("{name} needs P, the thread height")))?,
        "the thread height P",
    )?;
    let dd = increments(
        m,
        b,
        b.get("Q").ok_or_else(|| m.err(b.line, col, format!("{name} needs Q, the first depth")))?,
        "the first depth Q",
    )?;
    let taper = b.get("R").map_or(0.0, |w| m.len(w));
    if !(k > 0.0 && dd > 0.0) {
        return Err(m.err(
            b.line,
            col,
            format!("{name} thread height P and first depth Q must be greater than zero"),
        ));
    }
    if first.finish >= k {
        return Err(m.err(
            b.line,
            col,
            format!(
                "{name} finishing allowance {} mm is not less than the thread height {k} mm",
                first.finish
            ),
        ));
    }
    if m.css {
        m.note(b.line, col, format!("{name} under constant surface speed (G96); threading wants G97"));
    }
    // External when the root lies inside the start point, internal when outside.
    let sign = if x_root < x0 { 1.0 } else { -1.0 };
    let mut depths = cycles::sqrt_law_with_min(dd, first.min_depth, k - first.finish)
        .map_err(|e| m.err(b.line, col, e))?;
    for _ in 0..first.finish_passes {
        depths.push(k);
    }
    let dir = if z_end < z0 { -1.0 } else { 1.0 };
    let half = 0.5 * first.angle;
    let shifts = cycles::shifts(if half > 0.0 { Shift::Flank(half) } else { Shift::Radial }, &depths, dir);
    let chamfer = f64::from(first.chamfer_tenths) / 10.0 * lead;
    let op = m.begin_op(&name, b);
    m.op_mut(op).infeed_angle = Some((half, "P(m)(r)(a): a/2".into()));
    for (d, sh) in depths.iter().zip(shifts) {
        // Root X at the end; the taper R (radius start − end) applies to every pass.
        let x_end = x_root + sign * 2.0 * (k - d);
        let x_start = x_end + 2.0 * taper;
        let x_out = x_end + sign * 2.0 * chamfer;
        m.push(op, b.line, cycles::pass(x_start, x_end, z0 + sh, z_end, lead, b.line, chamfer, x_out))?;
    }
    m.x = Some(x0);
    m.z = Some(z0);
    Ok(())
}

/// The machine settings the one-block G76 reads (Haas's numbers; Fanuc's tape format takes the
/// defaults).
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
    let f = lead(m, b, col, cycle)?;
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
    let op = m.begin_op(cycle, b);
    if half > 0.0 {
        m.op_mut(op).infeed_angle = Some((half, "A/2".into()));
    }
    m.op_mut(op).notes.push(crate::ground::note::Note::from(format!(
        "{cycle}: Setting 86 (finish allowance) {} mm and Setting 99 (minimum cut) {} mm assumed; P{p}",
        st.finish, st.min_cut
    )));
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

impl Rules for State {
    fn block(&mut self, m: &mut Motion, b: &RBlock<'_>, cx: &mut Ctx<'_>) -> Result<Flow, Error> {
        block(self, m, b, cx)
    }
}
