//! Sinumerik: `G33 Z K` (`I` for steep tapers, `SF=` start offset), `CYCLE97`, `CYCLE99`, the old 810T/3T
//! cycles `L96` and `L97` (R-parameters, from the 1994 thesis), subprograms `L9 P33` in the
//! same listing (ending at `M17`), `DIAMON`/`DIAMOF`, `G70`/`G71`.
//!
//! L97 defaults where the sources are silent (stated in the output): the finishing allowance
//! R25 is cut in one pass at full depth; the R23 idle passes follow it; the run-in R26 starts
//! before R22 and the run-out R27 runs on beyond R32; every pass is shifted along Z by
//! depth·tan R29 in the direction of feed (R29 = 0: radial). L96: constant depth increments
//! (|R15| − R16)/R17, radial, from (R10, R11) to (R12, R13).

use super::cycles::{self, Shift};
use super::dialect::{Ctx, Flow, Rules};
use super::motion::{Motion, RBlock, RWord};
use crate::toolpath::passes::Pass;
use crate::Error;

/// Sinumerik state: the start offset SF, the feed in force and the modal cycle `MCALL` set.
#[derive(Default)]
pub(crate) struct State {
    start_offset_deg: f64,
    /// F in force, mm (per minute or per revolution as G94/G95 say).
    feed: Option<f64>,
    /// `MCALL CYCLE8x(…)`: the cycle every later positioning block calls, until `MCALL` alone.
    mcall: Option<HoleCall>,
}

/// A drilling or tapping cycle's call as written.
#[derive(Clone)]
struct HoleCall {
    name: String,
    args: Vec<Option<f64>>,
    line: usize,
    col: usize,
}

/// A frame statement on a machining centre (G17): `TRANS X… Y… Z…` sets the translation (and
/// clears the rotation), `ATRANS` adds one in the frame in force, `ROT RPL=a` sets the rotation
/// in the plane about the frame's origin (and clears the translation), `AROT RPL=a` adds to it;
/// `TRANS` alone clears the frame. `MIRROR X0 Y0` mirrors the named axes about the frame's zero
/// (the values are not read, as the control reads none) and replaces the frame, `AMIRROR` adds
/// a mirror to the frame in force (mirroring an axis twice undoes it); a helix under a mirror is
/// refused (its hand turns over). The frame moves every later hole into the workpiece's
/// coordinates. Scale, a mirrored Z, rotations about X or Y, and frames on a lathe are refused
/// by name: the positions (and a thread's axis) under them would be wrong.
fn frame(m: &mut Motion, b: &RBlock<'_>, w: &RWord<'_>) -> Result<(), Error> {
    let refuse = |m: &Motion, why: &str| Err(b.werr(&m.file, w, format!("{} {why}", w.name)));
    let axes: Vec<&RWord<'_>> = b.words.iter().filter(|x| matches!(x.name, "X" | "Y" | "Z")).collect();
    let rpl = b.get("RPL");
    let empty = axes.is_empty() && rpl.is_none();
    if matches!(w.name, "SCALE" | "ASCALE") || (w.name == "AMIRROR" && empty) {
        if empty && w.name == "SCALE" {
            m.local = [0.0; 3];
            m.rotation = None;
            m.mirror = [None; 2];
            return Ok(());
        }
        return refuse(m, "is not modelled: the positions under a scaled frame would be wrong (TRANS, ATRANS, ROT, AROT, MIRROR and AMIRROR are read)");
    }
    if m.lathe() && !empty {
        return refuse(m, "on a lathe is not modelled: the passes would not be moved (frames are read on a machining centre, G17)");
    }
    if matches!(w.name, "MIRROR" | "AMIRROR") {
        if axes.iter().any(|a| a.name == "Z") {
            return refuse(m, "Z is not modelled: a mirrored Z turns the thread's axis over");
        }
        if w.name == "MIRROR" {
            m.local = [0.0; 3];
            m.rotation = None;
            m.mirror = [None; 2];
        }
        for a in &axes {
            let i = usize::from(a.name == "Y");
            // Mirrored twice is not mirrored; about the frame's zero, whatever value is written.
            m.mirror[i] = if m.mirror[i].is_some() { None } else { Some(0.0) };
        }
        // Mirroring one axis turns a later AROT the other way; the rotation already in the
        // frame stays outside the mirror.
        if !empty {
            m.read_past(
                b.line,
                w.col,
                w.name,
                "a mirrored frame: later holes are placed in the workpiece's coordinates through it (a helix under it is refused: its hand turns over)",
            );
        }
        return Ok(());
    }
    let (angle, origin) = (m.rotation.map_or(0.0, |r| r.2), m.local);
    // One mirrored axis: the frame's own directions under it are mirrored too.
    let flips = [m.mirror[0].is_some(), m.mirror[1].is_some()];
    match w.name {
        "TRANS" | "ATRANS" => {
            let mut d = [0.0; 3];
            for a in &axes {
                d[match a.name {
                    "X" => 0,
                    "Y" => 1,
                    _ => 2,
                }] = m.len(a);
            }
            if w.name == "TRANS" {
                m.local = d;
                m.rotation = None;
                m.mirror = [None; 2];
            } else {
                // A translation added inside a mirror is mirrored with it.
                for (i, f) in flips.iter().enumerate() {
                    if *f {
                        d[i] = -d[i];
                    }
                }
                // Along the frame's own (rotated) axes.
                let (s, c) = angle.to_radians().sin_cos();
                m.local =
                    [origin[0] + c * d[0] - s * d[1], origin[1] + s * d[0] + c * d[1], origin[2] + d[2]];
            }
        }
        _ => {
            let about_z = axes.is_empty() || (axes.len() == 1 && axes[0].name == "Z" && rpl.is_none());
            if !about_z {
                return refuse(m, "about X or Y is not modelled: a thread's axis would tilt (ROT RPL=… and ROT Z… in G17 are read)");
            }
            let a = rpl.or(axes.first().copied()).map_or(0.0, |r| r.v);
            if w.name == "ROT" {
                m.local = [0.0; 3];
                m.mirror = [None; 2];
                m.rotation = (a != 0.0).then_some((0.0, 0.0, a));
            } else {
                // About the frame's origin, which the translation holds; inside a mirror of one
                // axis the turn runs the other way (M·R(a) = R(−a)·M).
                let a = if flips[0] != flips[1] { -a } else { a };
                m.rotation = Some((0.0, 0.0, angle + a));
            }
        }
    }
    m.read_past(
        b.line,
        w.col,
        w.name,
        "a frame: later holes are placed in the workpiece's coordinates through it",
    );
    Ok(())
}

/// The points (in the program's frame) of the hole patterns, from their arguments (ncplot7py's
/// Siemens mill handler: `HOLES1(SPCA, SPCO, STA1, FDIS, DBH, NUM)` a row from the reference
/// point at angle STA1, the first hole FDIS from it, then every DBH; `HOLES2(CPA, CPO, RAD, STA1,
/// INDA, NUM)` a circle, INDA 0 dividing it in NUM; `CYCLE801(SPCA, SPCO, STA, DIS1, DIS2, NUM1,
/// NUM2)` a grid of NUM1 columns DIS1 apart along STA and NUM2 lines DIS2 apart).
fn pattern_points(m: &Motion, b: &RBlock<'_>, w: &RWord<'_>) -> Result<Vec<(f64, f64)>, Error> {
    let args: Vec<Option<f64>> = w.args.iter().flatten().map(|a| a.0).collect();
    let arg = |k: usize| args.get(k).copied().flatten().unwrap_or(0.0);
    let count = |k: usize| -> Result<usize, Error> {
        let n = arg(k);
        if n >= 1.0 && n.fract() == 0.0 && n <= crate::ground::bounds::MAX_HOLES as f64 {
            Ok(n as usize)
        } else {
            Err(b.werr(
                &m.file,
                w,
                format!("{}: {} holes: a whole number from 1", w.name, crate::ground::fmt::fmt_num(n)),
            ))
        }
    };
    let sc = m.scale;
    let mut out = Vec::new();
    match w.name {
        "HOLES1" => {
            let (x0, y0, a, fdis, dbh, n) =
                (arg(0) * sc, arg(1) * sc, arg(2).to_radians(), arg(3) * sc, arg(4) * sc, count(5)?);
            for k in 0..n {
                let d = fdis + dbh * k as f64;
                out.push((x0 + d * a.cos(), y0 + d * a.sin()));
            }
        }
        "HOLES2" => {
            let (cx, cy, r, a0, n) = (arg(0) * sc, arg(1) * sc, arg(2) * sc, arg(3), count(5)?);
            let step = if arg(4) == 0.0 { 360.0 / n as f64 } else { arg(4) };
            for k in 0..n {
                let a = (a0 + step * k as f64).to_radians();
                out.push((cx + r * a.cos(), cy + r * a.sin()));
            }
        }
        _ => {
            let (x0, y0, a, d1, d2) =
                (arg(0) * sc, arg(1) * sc, arg(2).to_radians(), arg(3) * sc, arg(4) * sc);
            let (n1, n2) = (count(5)?, count(6)?);
            if n1 * n2 > crate::ground::bounds::MAX_HOLES {
                return Err(b.werr(
                    &m.file,
                    w,
                    format!("CYCLE801: {n1} × {n2} holes, over {}", crate::ground::bounds::MAX_HOLES),
                ));
            }
            for j in 0..n2 {
                for i in 0..n1 {
                    let (u, v) = (d1 * i as f64, d2 * j as f64);
                    out.push((x0 + u * a.cos() - v * a.sin(), y0 + u * a.sin() + v * a.cos()));
                }
            }
        }
    }
    Ok(out)
}

/// A word written as a name alone (`THRSUB`, `SOFT`): no value, no arguments, and no word
/// threadcheck models.
fn is_bare_name(w: &RWord<'_>) -> bool {
    w.args.is_none() && w.text.eq_ignore_ascii_case(w.name) && super::lexer::sinumerik_named_call(w.name)
}

/// A call's repetitions `P` (1 without): a whole number up to the bound.
fn repetitions(m: &Motion, b: &RBlock<'_>, w: &RWord<'_>) -> Result<u32, Error> {
    let reps = b.get("P").map_or(1.0, |p| p.v);
    if !(reps >= 0.0 && reps.fract() == 0.0 && reps <= crate::ground::bounds::MAX_REPEATS as f64) {
        return Err(b.werr(
            &m.file,
            w,
            format!(
                "{} P{reps}: repetitions must be a whole number up to {}",
                w.text,
                crate::ground::bounds::MAX_REPEATS
            ),
        ));
    }
    Ok(reps as u32)
}

/// Runs one block.
fn block(s: &mut State, m: &mut Motion, b: &RBlock<'_>, cx: &mut Ctx<'_>) -> Result<Flow, Error> {
    for w in &b.words {
        match w.name {
            "DIAMON" => m.diameter = true,
            "DIAMOF" => m.diameter = false,
            "SF" => s.start_offset_deg = w.v,
            "F" => s.feed = Some(m.len(w)),
            _ => {}
        }
    }
    if b.has_m(2.0) || b.has_m(30.0) {
        return Ok(Flow::End);
    }
    if let Some(w) = b.words.iter().find(|w| w.name == "M" && w.v == 17.0).or_else(|| b.get("RET")) {
        return Ok(Flow::Return { to_n: None, col: w.col });
    }
    if let Some(w) = b.get("CYCLE97") {
        cycles::modal(m, b)?;
        return cycle97(m, b, w).map(|_| Flow::Next);
    }
    if let Some(w) = b.get("CYCLE99") {
        cycles::modal(m, b)?;
        return cycle99(m, b, w).map(|_| Flow::Next);
    }
    if let Some(w) = b.words.iter().find(|w| hole_kind(w.name).is_some()) {
        let md = cycles::modal(m, b)?;
        cycles::other_block(m, b, &md)?;
        let call = HoleCall {
            name: w.name.to_string(),
            args: w.args.iter().flatten().map(|a| a.0).collect(),
            line: b.line,
            col: w.col,
        };
        if b.get("MCALL").is_some() {
            // Modal: called at every later position, not here.
            s.mcall = Some(call);
            m.read_past(
                b.line,
                w.col,
                &format!("MCALL {}", w.name),
                "a modal drilling or tapping cycle (threadcheck tap checks it); each later position calls it",
            );
        } else {
            hole(s, m, &call, b.line)?;
        }
        return Ok(Flow::Next);
    }
    if b.get("MCALL").is_some() {
        s.mcall = None;
    }
    if let Some(w) = b.words.iter().find(|w| w.name.starts_with("CYCLE") || w.name == "LCYC97") {
        return Err(b.werr(
            &m.file,
            w,
            format!("{} is not a threading cycle threadcheck reads (CYCLE97 and CYCLE99 are)", w.name),
        ));
    }
    // A frame statement: its axis words are the frame's, not a move.
    if let Some(w) =
        b.words.iter().find(|w| super::lexer::SINUMERIK_FRAMES.contains(&w.name) && w.args.is_none())
    {
        frame(m, b, w)?;
        return Ok(Flow::Next);
    }
    // A hole pattern: the modal cycle at each of its points.
    if let Some(w) = b.words.iter().find(|w| matches!(w.name, "HOLES1" | "HOLES2" | "CYCLE801")) {
        cycles::modal(m, b)?;
        let pts = pattern_points(m, b, w)?;
        match s.mcall.clone() {
            Some(call) => {
                for (x, y) in pts {
                    m.x = Some(x);
                    m.y = Some(y);
                    hole(s, m, &call, b.line)?;
                }
            }
            None => m.read_past(
                b.line,
                w.col,
                &format!("{}(…)", w.name),
                "a hole pattern with no MCALL cycle in force: it calls nothing",
            ),
        }
        return Ok(Flow::Next);
    }
    // A bare name: the subprogram of that name (`THRSUB`, `THRSUB P2`), else a word threadcheck
    // does not model, read past with a note.
    for w in b.words.iter().filter(|w| is_bare_name(w)) {
        if cx.subs.contains(w.name) {
            cycles::modal(m, b)?;
            let reps = repetitions(m, b, w)?;
            return Ok(Flow::Call { name: w.name.to_string(), repeats: reps, locals: None, col: w.col });
        }
        m.read_past(
            b.line,
            w.col,
            w.name,
            &format!(
                "a word threadcheck does not model; were it a subprogram's call, its subprogram is neither in this file nor a file {}.SPF beside it",
                w.name
            ),
        );
    }
    // Subprogram call: L9 P33, or the old thread cycles L96/L97 when the file does not define them.
    if let Some(w) = b.get("L") {
        cycles::modal(m, b)?;
        let name = format!("L{}", w.v.round() as i64);
        let reps = repetitions(m, b, w)?;
        if !cx.subs.contains(&name) {
            match name.as_str() {
                "L97" | "L96" => {
                    for _ in 0..reps {
                        if name == "L97" {
                            l97(m, b, w, cx)?;
                        } else {
                            l96(m, b, w, cx)?;
                        }
                    }
                    return Ok(Flow::Next);
                }
                _ => {
                    return Err(b.werr(
                        &m.file,
                        w,
                        format!("subprogram {name} is not in this file, nor its file {name}.SPF beside it (for a program read from a file)"),
                    ))
                }
            }
        }
        return Ok(Flow::Call { name, repeats: reps, locals: None, col: w.col });
    }
    let md = cycles::modal(m, b)?;
    if md.motion == 33.0 && md.one_shot.is_none() {
        let col = md.col.unwrap_or(b.col);
        if let Some(w) = b.get("K").or_else(|| b.get("I")) {
            let v = m.len(w);
            if !(v > 0.0) {
                return Err(b.werr(&m.file, w, "G33 lead must be greater than zero"));
            }
        }
        let (x, _, z) = m.target(b);
        if x.is_none() && z.is_none() {
            m.skipped += 1;
            return Ok(Flow::Next);
        }
        cycles::need_lathe_plane(m, b, col, "G33")?;
        let k = b.get("K").map(|w| m.len(w));
        let i = b.get("I").map(|w| m.len(w));
        if let Some(k) = k {
            m.lead = Some(k);
        }
        let lead = match (k, i) {
            (Some(k), _) => Some((k, false)),
            (None, Some(i)) => Some((i, true)),
            (None, None) => m.lead.map(|l| (l, false)),
        };
        let Some((l, along_x)) = lead else {
            return Err(m.err(b.line, col, "G33 without a lead: add K (or I for a steep taper)"));
        };
        m.thread_move(
            b,
            col,
            "G33",
            |dx, dz| if along_x && dx != 0.0 { l * dz.abs() / dx.abs() } else { l },
            s.start_offset_deg,
        )?;
        return Ok(Flow::Next);
    }
    cycles::other_block(m, b, &md)?;
    if let Some(call) = s.mcall.clone() {
        if ["X", "Y"].iter().any(|a| b.get(a).is_some()) {
            hole(s, m, &call, b.line)?;
        }
    }
    Ok(Flow::Next)
}

/// What a Sinumerik drilling or tapping cycle does: CYCLE81–83 and CYCLE85–89 make the hole,
/// CYCLE84 (rigid) and CYCLE840 (with a compensating chuck) tap it.
fn hole_kind(name: &str) -> Option<super::HoleKind> {
    match name {
        "CYCLE81" | "CYCLE82" | "CYCLE83" | "CYCLE85" | "CYCLE86" | "CYCLE87" | "CYCLE88" | "CYCLE89" => {
            Some(super::HoleKind::Drill)
        }
        "CYCLE84" | "CYCLE840" => Some(super::HoleKind::Tap),
        _ => None,
    }
}

/// Runs a drilling or tapping cycle at the current position: records it for `threadcheck tap`
/// and leaves Z unknown (the cycle ends at its retraction plane RTP; X and Y stay).
///
/// The arguments (Siemens, *SINUMERIK 840D sl / 828D Cycles*, Programming Manual: CYCLE81 to
/// CYCLE89, CYCLE84, CYCLE840): every cycle begins `RTP, RFP, SDIS, DP, DPR`, DP the final
/// depth (absolute) and DPR the depth below the reference plane RFP (unsigned); where both are
/// given the cycle takes DPR. CYCLE84 continues `DTB, SDAC, MPIT, PIT, POSS, SST, SST1`: the
/// pitch as a value PIT or as a metric size MPIT (3 for M3 … 48 for M48, the coarse pitch),
/// its sign the hand (positive right, as M3; negative left, as M4); the cycle makes its own
/// feed from the pitch. CYCLE840 continues `DTB, SDR, SDAC, ENC, MPIT, PIT`: ENC 0 taps with
/// the encoder (the feed from the pitch), ENC 1 without (the feed F in force, which must then be
/// the pitch under G95 or S × pitch under G94); the spindle turns as M3/M4 left it.
fn hole(s: &State, m: &mut Motion, call: &HoleCall, line: usize) -> Result<(), Error> {
    let Some(kind) = hole_kind(&call.name) else { return Ok(()) };
    let arg = |k: usize| call.args.get(k).copied().flatten();
    let sc = m.scale;
    let (rfp, dp, dpr) = (arg(1).map(|v| v * sc), arg(3).map(|v| v * sc), arg(4).map(|v| v * sc));
    let bottom = match (dp, dpr.filter(|v| *v != 0.0), rfp) {
        (Some(dp), Some(dpr), Some(rfp)) => {
            if (rfp - dpr - dp).abs() > 1e-6 {
                m.note(
                    line,
                    call.col,
                    format!(
                        "{}: DP {} and DPR {} below RFP {} disagree; the cycle takes DPR",
                        call.name,
                        crate::ground::fmt::fmt_num(dp / sc),
                        crate::ground::fmt::fmt_num(dpr / sc),
                        crate::ground::fmt::fmt_num(rfp / sc)
                    ),
                );
            }
            Some(rfp - dpr)
        }
        (_, Some(dpr), Some(rfp)) => Some(rfp - dpr),
        (Some(dp), _, _) => Some(dp),
        _ => None,
    };
    let mut feed = None;
    let mut feed_word = "F";
    let mut hand = None;
    let mut feed_per_rev = true;
    let mut spindle_dir = m.spindle_dir;
    if kind == super::HoleKind::Tap {
        // CYCLE840's ENC (its ninth argument); CYCLE84 always taps from the pitch.
        let (mpit_at, pit_at, enc) =
            if call.name == "CYCLE84" { (7, 8, None) } else { (9, 10, Some(arg(8).unwrap_or(0.0))) };
        let encoder = enc.is_none_or(|e| e == 0.0);
        if let Some(enc) = enc.filter(|e| *e != 0.0 && *e != 1.0) {
            m.note(
                line,
                call.col,
                format!("CYCLE840 ENC {enc}: threadcheck reads ENC 0 and 1; the feed is not checked"),
            );
        } else if encoder {
            let pitch = match (arg(pit_at).filter(|v| *v != 0.0), arg(mpit_at).filter(|v| *v != 0.0)) {
                (Some(pit), _) => {
                    feed_word = "PIT";
                    Some(pit * sc)
                }
                (None, Some(mpit)) => {
                    feed_word = "MPIT";
                    // The control taps with MPIT's pitch or alarms: a size it has no pitch for
                    // refuses the program (MPIT 99 once passed without a feed check).
                    let p = coarse_pitch_for(mpit.abs()).filter(|_| mpit.abs() <= 48.0).ok_or_else(|| {
                        m.err(
                            line,
                            call.col,
                            format!(
                                "{} MPIT {}: not a metric size M3 to M48 with a coarse pitch (ISO 261): the cycle has no pitch to tap with",
                                call.name,
                                crate::ground::fmt::fmt_num(mpit)
                            ),
                        )
                    })?;
                    Some(p.copysign(mpit))
                }
                (None, None) => {
                    return Err(m.err(
                        line,
                        call.col,
                        format!(
                            "{} without PIT or MPIT: the cycle taps from the pitch and has none (give PIT, argument {}, or MPIT, argument {})",
                            call.name,
                            pit_at + 1,
                            mpit_at + 1
                        ),
                    ))
                }
            };
            if let Some(p) = pitch {
                feed = Some(p.abs());
                if call.name == "CYCLE84" {
                    let right = p > 0.0;
                    hand = Some(if right {
                        crate::standards::Hand::Right
                    } else {
                        crate::standards::Hand::Left
                    });
                    spindle_dir = Some(if right { super::SpindleDir::Cw } else { super::SpindleDir::Ccw });
                }
            }
        } else {
            feed = s.feed;
            feed_per_rev = m.feed_per_rev.unwrap_or(false);
        }
    }
    let assumed = kind == super::HoleKind::Tap && feed_word == "F" && m.feed_per_rev.is_none();
    // Through the frame in force (TRANS, ROT …) into the workpiece's coordinates.
    let (wx, wy, wz) = m.work_point(m.x, m.y, bottom);
    m.push_hole(super::HoleCycle {
        code: call.name.clone(),
        units: m.program_units(),
        kind,
        line,
        column: if line == call.line { call.col } else { 1 },
        x: wx,
        y: wy,
        radial: None,
        bottom: wz,
        feed,
        feed_word: feed_word.into(),
        hand,
        feed_per_rev,
        feed_mode_assumed: assumed,
        spindle: m.s,
        spindle_dir,
        tool: m.tool,
        // Set where it is recorded (Motion::push_hole).
        work_offset: None,
        source_file: None,
        main_line: 0,
        machine_xy: None,
        rigid: call.name == "CYCLE84",
        constant_surface_speed: false,
        r_level: None,
    })?;
    m.lose_position(line, &format!("{}(…)", call.name), false, true);
    m.read_past(
        line,
        if line == call.line { call.col } else { 1 },
        &format!("{}(…)", call.name),
        "a drilling or tapping cycle (threadcheck tap checks it); it ends at its retraction plane RTP",
    );
    Ok(())
}

/// An R-parameter for a cycle: a required one must be set; an optional one reads as 0.
fn r(
    m: &mut Motion,
    cx: &mut Ctx<'_>,
    n: i64,
    b: &RBlock<'_>,
    w: &RWord<'_>,
    cycle: &str,
    required: &[(i64, &str)],
) -> Result<f64, Error> {
    match cx.get(m, n, b.line, w.col) {
        Some(v) => Ok(v),
        None => match required.iter().find(|(k, _)| *k == n) {
            Some((_, what)) => Err(b.werr(
                &m.file,
                w,
                format!("{cycle} reads R{n} ({what}), which is not set before the call"),
            )),
            None => Ok(0.0),
        },
    }
}

const L97_NEEDS: [(i64, &str); 7] = [
    (20, "the pitch"),
    (21, "the start diameter"),
    (22, "the start Z"),
    (24, "the thread depth"),
    (28, "the number of rough cuts"),
    (31, "the end diameter"),
    (32, "the end Z"),
];

const L96_NEEDS: [(i64, &str); 8] = [
    (10, "the start X"),
    (11, "the start Z"),
    (12, "the end X"),
    (13, "the end Z"),
    (14, "the pitch"),
    (15, "the thread depth"),
    (17, "the number of rough cuts"),
    (19, "radius or diameter programming"),
];

/// L97: the thesis's parameters (R20 pitch, R21/R22 start, R23 idle passes, R24 depth, negative
/// external and positive internal, R25 finishing allowance, R26 run-in, R27 run-out, R28 rough
/// cuts, R29 infeed angle, R31/R32 end). Rough cut i of R28 ends at t·√(i/R28), t = |R24| − R25.
fn l97(m: &mut Motion, b: &RBlock<'_>, w: &RWord<'_>, cx: &mut Ctx<'_>) -> Result<(), Error> {
    let sc = m.scale;
    let mut g = |n: i64| r(m, cx, n, b, w, "L97", &L97_NEEDS);
    let (pitch, x_a, z_a, idle, depth, fin, run_in, run_out, nrough, angle, x_e, z_e) = (
        g(20)? * sc,
        g(21)? * sc,
        g(22)? * sc,
        g(23)?,
        g(24)? * sc,
        g(25)? * sc,
        g(26)? * sc,
        g(27)? * sc,
        g(28)?,
        g(29)?,
        g(31)? * sc,
        g(32)? * sc,
    );
    let e = |msg: &str| b.werr(&m.file, w, format!("L97: {msg}"));
    if !(pitch > 0.0) {
        return Err(e("R20, the pitch, must be greater than zero"));
    }
    if !(nrough >= 1.0 && nrough.fract() == 0.0 && nrough <= crate::ground::bounds::MAX_REPEATS as f64) {
        return Err(e("R28, the number of rough cuts, must be a whole number from 1"));
    }
    if !(idle >= 0.0 && idle.fract() == 0.0 && idle <= crate::ground::bounds::MAX_REPEATS as f64) {
        return Err(e("R23, the number of idle passes, must be a whole number"));
    }
    let t_full = depth.abs();
    if !(t_full > 0.0 && fin >= 0.0 && fin < t_full) {
        return Err(e("R24 must not be 0 and the finishing allowance R25 must be from 0 to under |R24|"));
    }
    if !(run_in >= 0.0 && run_out >= 0.0) {
        return Err(e("R26 and R27 are paths without sign"));
    }
    if (z_e - z_a).abs() < 1e-9 {
        return Err(e("R22 and R32 are the same: the thread has no length"));
    }
    if !(0.0..90.0).contains(&angle.abs()) {
        return Err(e("R29, the infeed angle, must be under 90°"));
    }
    let external = depth < 0.0;
    let sx = if external { -1.0 } else { 1.0 };
    let dz = (z_e - z_a).signum();
    let (z0, z1) = (z_a - dz * run_in, z_e + dz * run_out);
    let crest = |z: f64| x_a + (x_e - x_a) * (z - z_a) / (z_e - z_a);
    let t = t_full - fin;
    let n = nrough as usize;
    let mut depths: Vec<f64> = (1..=n).map(|i| t * (i as f64 / nrough).sqrt()).collect();
    if fin > 0.0 {
        depths.push(t_full);
    }
    depths.extend(std::iter::repeat_n(t_full, idle as usize));
    let shift = if angle != 0.0 { Shift::Flank(angle.abs()) } else { Shift::Radial };
    let shifts = cycles::shifts(shift, &depths, dz);
    let op = m.begin_op("L97", b);
    {
        let o = m.op_mut(op);
        o.infeed_angle = Some((angle.abs(), "R29".into()));
        o.notes.push(crate::ground::note::Note::from(
            "L97: the finishing allowance R25 is cut in one pass and the R23 idle passes follow it; R27 runs on beyond R32; each pass is shifted along Z by depth·tan R29 (assumed where the sources are silent)",
        ));
    }
    for (d, sh) in depths.iter().zip(shifts) {
        let (za, zb) = (z0 + sh, z1 + sh);
        let xa = crest(za) + 2.0 * sx * d;
        let xb = crest(zb) + 2.0 * sx * d;
        m.push(op, b.line, cycles::pass(xa, xb, za, zb, pitch, b.line, 0.0, xb))?;
    }
    m.op_mut(op).depth_word = Some(r_parameter_word("R24", depth / sc, b, w));
    Ok(())
}

/// L96: R10/R11 start, R12/R13 end, R14 pitch, R15 depth (− external), R16 finishing allowance,
/// R17 rough cuts, R18 idle cuts, R19 1 radius / 2 diameter programming; radial infeed.
fn l96(m: &mut Motion, b: &RBlock<'_>, w: &RWord<'_>, cx: &mut Ctx<'_>) -> Result<(), Error> {
    let sc = m.scale;
    let mut g = |n: i64| r(m, cx, n, b, w, "L96", &L96_NEEDS);
    let (x_a, z_a, x_e, z_e, pitch, depth, fin, nrough, idle, mode) = (
        g(10)? * sc,
        g(11)? * sc,
        g(12)? * sc,
        g(13)? * sc,
        g(14)? * sc,
        g(15)? * sc,
        g(16)? * sc,
        g(17)?,
        g(18)?,
        g(19)?,
    );
    let e = |msg: &str| b.werr(&m.file, w, format!("L96: {msg}"));
    if !(pitch > 0.0) {
        return Err(e("R14, the pitch, must be greater than zero"));
    }
    if !(nrough >= 1.0 && nrough.fract() == 0.0 && nrough <= crate::ground::bounds::MAX_REPEATS as f64) {
        return Err(e("R17, the number of rough cuts, must be a whole number from 1"));
    }
    if !(idle >= 0.0 && idle.fract() == 0.0 && idle <= crate::ground::bounds::MAX_REPEATS as f64) {
        return Err(e("R18, the number of idle cuts, must be a whole number"));
    }
    let dia = match mode {
        1.0 => 2.0,
        2.0 => 1.0,
        _ => return Err(e("R19 must be 1 (radius programming) or 2 (diameter programming)")),
    };
    let t_full = depth.abs();
    if !(t_full > 0.0 && fin >= 0.0 && fin < t_full) {
        return Err(e("R15 must not be 0 and the finishing allowance R16 must be from 0 to under |R15|"));
    }
    if (z_e - z_a).abs() < 1e-9 {
        return Err(e("R11 and R13 are the same: the thread has no length"));
    }
    let sx = if depth < 0.0 { -1.0 } else { 1.0 };
    let (xa, xe) = (x_a * dia, x_e * dia);
    let step = (t_full - fin) / nrough;
    let mut depths: Vec<f64> = (1..=nrough as usize).map(|i| step * i as f64).collect();
    if fin > 0.0 {
        depths.push(t_full);
    }
    depths.extend(std::iter::repeat_n(t_full, idle as usize));
    let op = m.begin_op("L96", b);
    {
        let o = m.op_mut(op);
        o.infeed_angle = Some((0.0, "L96 (radial)".into()));
        o.notes.push("L96: constant depth increments (|R15| − R16)/R17, radial, no run-in or run-out (assumed where the thesis is silent)".into());
    }
    for d in depths {
        let p =
            Pass { ..cycles::pass(xa + 2.0 * sx * d, xe + 2.0 * sx * d, z_a, z_e, pitch, b.line, 0.0, xe) };
        m.push(op, b.line, p)?;
    }
    m.op_mut(op).depth_word = Some(r_parameter_word("R15", depth / sc, b, w));
    Ok(())
}

/// The R-parameter that holds a cycle's depth: set somewhere before the call, so a fix cannot
/// rewrite it in place; the call's place stands for it.
fn r_parameter_word(name: &str, value: f64, b: &RBlock<'_>, w: &RWord<'_>) -> super::DepthWord {
    super::DepthWord {
        word: name.into(),
        value,
        line: b.line,
        column: w.col,
        written: format!("{name}={value}"),
        form: super::WordForm::Parameter,
        means: super::WordMeans::Depth { per_radial: 1.0 },
    }
}

/// A Sinumerik turning thread cycle (CYCLE97, CYCLE99) read into the words its law needs, mm.
struct ThreadCall {
    name: &'static str,
    /// The pitch; with `starts` starts the lead is `starts`·pitch, the starts one pitch apart.
    pitch: f64,
    starts: u32,
    /// Every start at each depth before the next depth (CYCLE99 VARI millions 1), or one
    /// start's every depth after the other's.
    starts_interleaved: bool,
    /// Where the thread lies, mm.
    at: Span,
    nsp_deg: f64,
    external: bool,
    /// Each pass's depth (radial, from the crest), in cutting order.
    depths: Vec<f64>,
    shift: Shift,
    iang: f64,
    tdep: f64,
    /// TDEP's place among the call's arguments (0-based).
    tdep_arg: usize,
}

/// Where a Sinumerik thread cycle cuts, mm: the start SPL on diameter DM1, the end FPL on DM2,
/// the run-in APP before the start and the run-out ROP past the end.
#[derive(Clone, Copy, Debug)]
struct Span {
    spl: f64,
    dm1: f64,
    fpl: f64,
    dm2: f64,
    app: f64,
    rop: f64,
}

impl Span {
    /// The words as written, in program units, times `scale`.
    fn scaled([spl, dm1, fpl, dm2, app, rop]: [f64; 6], scale: f64) -> Span {
        Span {
            spl: spl * scale,
            dm1: dm1 * scale,
            fpl: fpl * scale,
            dm2: dm2 * scale,
            app: app * scale,
            rop: rop * scale,
        }
    }
}

/// The flank infeed CYCLE97 reads from IANG's sign: > 0 one flank, < 0 alternating, 0 radial.
fn shift_by_sign(iang: f64) -> Shift {
    if iang > 0.0 {
        Shift::Flank(iang)
    } else if iang < 0.0 {
        Shift::Alternating(-iang)
    } else {
        Shift::Radial
    }
}

/// Depths of the Sinumerik law (the thread-cutting and thread-chain cycles' pages, see
/// docs/dialects.md): FAL is taken off TDEP and the rest divided into `cuts` rough cuts,
/// constant depth (`degressive` false) or constant cross-section (depth ∝ √i); a finishing cut at
/// TDEP when FAL > 0; then `idle` passes at TDEP.
fn sinumerik_depths(
    tdep: f64,
    fal: f64,
    cuts: usize,
    degressive: bool,
    rough: bool,
    finish: bool,
    idle: usize,
) -> Vec<f64> {
    let rough_end = tdep - fal;
    let n = cuts as f64;
    let mut depths: Vec<f64> = if rough {
        (1..=cuts)
            .map(|i| if degressive { rough_end * (i as f64 / n).sqrt() } else { rough_end * i as f64 / n })
            .collect()
    } else {
        Vec::new()
    };
    if finish {
        if fal > 0.0 || !rough {
            depths.push(tdep);
        }
        depths.extend(std::iter::repeat_n(tdep, idle));
    }
    debug_assert!(depths.iter().all(|d| *d > 0.0 && *d <= tdep + 1e-12));
    depths
}

/// CYCLE97(PIT, MPIT, SPL, FPL, DM1, DM2, APP, ROP, TDEP, FAL, IANG, NSP, NRC, NID, VARI, NUMT).
///
/// PIT is the pitch; with NUMT starts the lead is NUMT·PIT and the starts are one pitch
/// apart. VARI 1/3 external, 2/4 internal (DM1/DM2 are then the tap-hole diameters);
/// 1/2 constant depth, 3/4 constant chip area.
/// NRC rough passes to TDEP − FAL, one finishing pass at TDEP, NID idle passes. IANG > 0
/// infeeds along one flank, IANG < 0 alternates flanks.
fn cycle97(m: &mut Motion, b: &RBlock<'_>, w: &RWord<'_>) -> Result<(), Error> {
    let args = w.args.clone().unwrap_or_default();
    if args.len() > 20 {
        return Err(b.werr(&m.file, w, format!("CYCLE97 takes 16 parameters, not {}", args.len())));
    }
    let mut v = [0.0f64; 16];
    for (k, (x, _)) in args.iter().enumerate().take(16) {
        if let Some(x) = x {
            v[k] = *x;
        }
    }
    let [pit, mpit, spl, fpl, dm1, dm2, app, rop, tdep, fal, iang, nsp, nrc, nid, vari, numt] = v;
    let s = m.scale;
    let pitch = if pit > 0.0 {
        pit * s
    } else {
        coarse_pitch_for(mpit)
            .ok_or_else(|| b.werr(&m.file, w, "CYCLE97 needs PIT, or MPIT the metric size 3 to 60"))?
    };
    // An empty or zero VARI, NRC or NUMT: the cycle's own default, stated (a named default:
    // Siemens' screen form offers 1 for each; the Job planning manual does not print it).
    let defaulted: Vec<(&str, &str)> =
        [("NRC", nrc, "NRC 1, one rough cut"), ("NUMT", numt, "NUMT 1, a single start")]
            .into_iter()
            .filter(|(_, v, _)| *v == 0.0)
            .map(|(n, _, means)| (n, means))
            .collect();
    if !defaulted.is_empty() {
        let names: Vec<&str> = defaulted.iter().map(|d| d.0).collect();
        let means: Vec<&str> = defaulted.iter().map(|d| d.1).collect();
        m.note(
            b.line,
            w.col,
            format!(
                "CYCLE97 {} empty or 0: taken as 1 (a named default: {})",
                names.join(", "),
                means.join("; ")
            ),
        );
    }
    // VARI has no default: the cycle checks it is 1 to 4 and stops otherwise (issue 64; Siemens'
    // cycle alarm 61002, "type of machining incorrectly defined", in its Cycles manual's list,
    // which is not among the sources read here).
    if vari == 0.0 {
        return Err(b.werr(
            &m.file,
            w,
            "CYCLE97 VARI empty or 0: the control refuses the cycle (its machining type is 1 to 4: 1 outside and 2 inside with constant depth, 3 outside and 4 inside with constant cross-section; cycle alarm 61002)",
        ));
    }
    if ![1.0, 2.0, 3.0, 4.0].contains(&vari) {
        return Err(b.werr(&m.file, w, format!("CYCLE97 VARI {vari} must be 1, 2, 3 or 4")));
    }
    let (tdep, fal) = (tdep * s, fal * s);
    if !(tdep > 0.0 && fal >= 0.0 && fal < tdep) {
        return Err(b.werr(&m.file, w, "CYCLE97 needs TDEP > 0 and 0 ≤ FAL < TDEP"));
    }
    let nrc = if nrc == 0.0 { 1.0 } else { nrc };
    let numt = if numt == 0.0 { 1.0 } else { numt };
    let max = crate::ground::bounds::MAX_REPEATS as f64;
    if !cycles::whole_in(nrc, 1.0, max)
        || !cycles::whole_in(nid, 0.0, max)
        || !cycles::whole_in(numt, 1.0, 64.0)
    {
        return Err(b.werr(&m.file, w, "CYCLE97 NRC, NID and NUMT must be whole numbers in range"));
    }
    let call = ThreadCall {
        name: "CYCLE97",
        pitch,
        starts: numt as u32,
        starts_interleaved: false,
        at: Span::scaled([spl, dm1, fpl, dm2, app, rop], s),
        nsp_deg: nsp,
        external: vari == 1.0 || vari == 3.0,
        depths: sinumerik_depths(tdep, fal, nrc as usize, vari >= 3.0, true, true, nid as usize),
        shift: shift_by_sign(iang),
        iang,
        tdep,
        tdep_arg: 8,
    };
    cut_thread_call(m, b, w, &call)
}

/// The arguments CYCLE99 is read by (a named default: docs/dialects.md, "Sinumerik CYCLE99").
const CYCLE99_ORDER: [&str; 15] = [
    "SPL", "DM1", "FPL", "DM2", "APP", "ROP", "TDEP", "FAL", "IANG", "NSP", "NRC", "NID", "PIT", "VARI",
    "NUMTH",
];

/// CYCLE99(SPL, DM1, FPL, DM2, APP, ROP, TDEP, FAL, IANG, NSP, NRC, NID, PIT, VARI, NUMTH, …).
///
/// The order is the thread-chain cycle CYCLE98's published list for one segment (a named
/// default: Siemens' CYCLE99 page was not read here); VARI is CYCLE98's published digit code:
/// units 1–4 outside/inside with linear/degressive infeed, hundreds 1 one flank / 2 alternating,
/// ten-thousands NRC or MID (the 11th argument as the largest infeed), hundred-thousands
/// roughing / finishing / both, millions the order of the starts. The later arguments must be
/// zero or empty (read as the cycle's defaults); any other is refused by its place.
fn cycle99(m: &mut Motion, b: &RBlock<'_>, w: &RWord<'_>) -> Result<(), Error> {
    let args = w.args.clone().unwrap_or_default();
    let col = |k: usize| args.get(k).map_or(w.col, |a| a.1);
    let file = m.file.clone();
    let err = |k: usize, msg: String| Error::Program {
        file: file.clone(),
        line: b.line,
        column: col(k),
        message: msg,
    };
    if args.len() > 64 {
        return Err(b.werr(
            &m.file,
            w,
            format!("CYCLE99 with {} arguments: threadcheck reads at most 64", args.len()),
        ));
    }
    for (k, (x, _)) in args.iter().enumerate().skip(CYCLE99_ORDER.len()) {
        if let Some(x) = x.filter(|x| *x != 0.0) {
            return Err(err(
                k,
                format!(
                    "CYCLE99 argument {} = {x}: threadcheck reads the first 15 (SPL … NUMTH, a named order); \
                     the later ones (pitch unit, pitch change, …) have no published place here: leave them 0 or empty",
                    k + 1
                ),
            ));
        }
    }
    let mut v = [0.0f64; 15];
    for (k, (x, _)) in args.iter().enumerate().take(15) {
        if let Some(x) = x {
            v[k] = *x;
        }
    }
    let [spl, dm1, fpl, dm2, app, rop, tdep, fal, iang, nsp, nrc, nid, pit, vari, numth] = v;
    // An empty DM2: the thread is cylindrical, DM2 = DM1 (a named default, noted).
    let dm2_empty = args.get(3).is_none_or(|a| a.0.is_none());
    let dm2 = if dm2_empty { dm1 } else { dm2 };
    if dm2_empty {
        m.note(b.line, col(3), "CYCLE99 DM2 empty: read as DM1, a cylindrical thread (a named default)");
    }
    let s = m.scale;
    if !(pit > 0.0) {
        return Err(err(12, "CYCLE99 PIT (argument 13) must be a pitch greater than zero".into()));
    }
    if !(dm1 > 0.0 && dm2 > 0.0) {
        return Err(err(
            1,
            format!(
                "CYCLE99 DM1 {dm1} and DM2 {dm2} (arguments 2 and 4) must be diameters greater than zero"
            ),
        ));
    }
    if spl == fpl {
        return Err(err(
            2,
            "CYCLE99 SPL = FPL: a face thread; threadcheck reads longitudinal and taper threads".into(),
        ));
    }
    let (tdep, fal) = (tdep * s, fal * s);
    if !(tdep > 0.0 && fal >= 0.0 && fal < tdep) {
        return Err(err(6, "CYCLE99 needs TDEP > 0 and 0 ≤ FAL < TDEP (arguments 7 and 8)".into()));
    }
    let digits = Vari99::parse(vari).map_err(|msg| err(13, msg))?;
    let max = crate::ground::bounds::MAX_REPEATS as f64;
    if numth == 0.0 {
        m.note(
            b.line,
            w.col,
            "CYCLE99 NUMTH empty or 0: taken as 1, a single start (a named default)".to_string(),
        );
    }
    let numth = if numth == 0.0 { 1.0 } else { numth };
    if !cycles::whole_in(nid, 0.0, max) || !cycles::whole_in(numth, 1.0, 64.0) {
        return Err(err(11, "CYCLE99 NID and NUMTH must be whole numbers in range".into()));
    }
    let rough_end = tdep - fal;
    let cuts = if digits.max_infeed {
        let mid = nrc * s;
        if !(mid > 0.0) {
            return Err(err(
                10,
                "CYCLE99 VARI ten-thousands 1: MID (argument 11) is the largest infeed and must be > 0"
                    .into(),
            ));
        }
        // The fewest cuts whose largest (the first, degressive) is at most MID.
        let q = rough_end / mid;
        let n = if digits.degressive { (q * q - 1e-9).ceil() } else { (q - 1e-9).ceil() };
        n.max(1.0)
    } else if nrc == 0.0 {
        m.note(
            b.line,
            w.col,
            "CYCLE99 NRC empty or 0: taken as 1, one rough cut (a named default)".to_string(),
        );
        1.0
    } else {
        nrc
    };
    if !cycles::whole_in(cuts, 1.0, max) {
        return Err(err(10, format!("CYCLE99 NRC/MID gives {cuts} cuts: at most {max}")));
    }
    let shift = match digits.flank {
        // The form before the digit: the sign of IANG chooses (as CYCLE97).
        FlankDigit::BySign => shift_by_sign(iang),
        // One flank: IANG > 0 the rear flank, < 0 the front (the operating manual's α).
        FlankDigit::One => Shift::Flank(iang),
        FlankDigit::Alternating => Shift::Alternating(iang.abs()),
    };
    m.note(
        b.line,
        w.col,
        format!(
            "CYCLE99 read as ({}): a named default, CYCLE98's published list for one segment (Siemens' CYCLE99 page was not read); VARI {vari} read by CYCLE98's digit code: {}",
            CYCLE99_ORDER.join(", "),
            digits.describe()
        ),
    );
    if args.len() > CYCLE99_ORDER.len() {
        m.note(
            b.line,
            col(CYCLE99_ORDER.len()),
            format!(
                "CYCLE99 arguments 16 to {} are zero or empty: read as the cycle's defaults (pitch in mm/rev or in/rev as G71/G70, no pitch change)",
                args.len()
            ),
        );
    }
    let call = ThreadCall {
        name: "CYCLE99",
        pitch: pit * s,
        starts: numth as u32,
        starts_interleaved: digits.starts_interleaved,
        at: Span::scaled([spl, dm1, fpl, dm2, app, rop], s),
        nsp_deg: nsp,
        external: digits.external,
        depths: sinumerik_depths(
            tdep,
            fal,
            cuts as usize,
            digits.degressive,
            digits.rough,
            digits.finish,
            nid as usize,
        ),
        shift,
        iang,
        tdep,
        tdep_arg: 6,
    };
    cut_thread_call(m, b, w, &call)
}

/// CYCLE99's VARI hundreds digit: how the cuts move along the flanks.
#[derive(Clone, Copy, Debug, PartialEq)]
enum FlankDigit {
    /// 0: the sign of IANG chooses, as CYCLE97.
    BySign,
    /// 1: one flank at IANG.
    One,
    /// 2: alternating flanks.
    Alternating,
}

/// CYCLE99's VARI read by CYCLE98's published digit code.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Vari99 {
    external: bool,
    degressive: bool,
    /// Hundreds: 0 the sign of IANG chooses, 1 one flank, 2 alternating.
    flank: FlankDigit,
    /// Ten-thousands 1: the 11th argument is MID, the largest infeed, not NRC.
    max_infeed: bool,
    rough: bool,
    finish: bool,
    starts_interleaved: bool,
}

impl Vari99 {
    fn parse(vari: f64) -> Result<Vari99, String> {
        if !(vari.fract() == 0.0 && (1.0..2_000_000.0).contains(&vari)) {
            return Err(format!(
                "CYCLE99 VARI {vari} (argument 14): the machining code is a whole number from 1 to 1999999"
            ));
        }
        let v = vari as u32;
        let d = |k: u32| (v / 10u32.pow(k)) % 10;
        let bad = |place: &str, digit: u32, what: &str| {
            Err(format!("CYCLE99 VARI {v} (argument 14): {place} digit {digit}; threadcheck reads {what} (CYCLE98's code)"))
        };
        if !(1..=4).contains(&d(0)) {
            return bad("units", d(0), "1–4 (outside/inside, linear/degressive)");
        }
        if d(1) != 0 {
            return bad("tens", d(1), "0");
        }
        if d(2) > 2 {
            return bad("hundreds", d(2), "0–2 (by IANG's sign, one flank, alternating)");
        }
        if d(3) != 0 {
            return bad("thousands", d(3), "0");
        }
        if d(4) > 1 {
            return bad("ten-thousands", d(4), "0 (NRC) or 1 (MID)");
        }
        if d(5) > 3 {
            return bad("hundred-thousands", d(5), "0–3 (both, roughing, finishing, both)");
        }
        let h = d(5);
        Ok(Vari99 {
            external: d(0) % 2 == 1,
            degressive: d(0) >= 3,
            flank: match d(2) {
                0 => FlankDigit::BySign,
                1 => FlankDigit::One,
                2 => FlankDigit::Alternating,
                other => return bad("hundreds", other, "0–2 (by IANG's sign, one flank, alternating)"),
            },
            max_infeed: d(4) == 1,
            rough: h != 2,
            finish: h != 1,
            starts_interleaved: d(6) == 1,
        })
    }

    /// In words, for the note.
    fn describe(&self) -> String {
        format!(
            "{}, {} infeed, {}, the 11th argument {}, {}, {}",
            if self.external { "outside" } else { "inside" },
            if self.degressive { "degressive (constant cross-section)" } else { "linear (constant depth)" },
            match self.flank {
                FlankDigit::BySign => "flank by the sign of IANG",
                FlankDigit::One => "one flank at IANG",
                FlankDigit::Alternating => "alternating flanks",
            },
            if self.max_infeed { "MID, the largest infeed" } else { "NRC, the number of rough cuts" },
            match (self.rough, self.finish) {
                (true, true) => "roughing and finishing",
                (true, false) => "roughing only",
                (false, true) => "finishing only",
                // parse() never gives neither: hundred-thousands 1 is roughing, 2 finishing.
                (false, false) => "no cut",
            },
            if self.starts_interleaved { "every start at each depth" } else { "one start after the other" },
        )
    }
}

/// The passes of a Sinumerik turning thread cycle.
fn cut_thread_call(m: &mut Motion, b: &RBlock<'_>, w: &RWord<'_>, c: &ThreadCall) -> Result<(), Error> {
    if m.css {
        m.note(b.line, w.col, format!("{} under constant surface speed (G96); threading wants G97", c.name));
    }
    let dir = if c.at.fpl < c.at.spl { -1.0 } else { 1.0 };
    let offsets = cycles::shifts(c.shift, &c.depths, dir);
    let lead = c.pitch * f64::from(c.starts);
    let op = m.begin_op(c.name, b);
    m.op_mut(op).infeed_angle = Some((c.iang.abs(), "IANG".into()));
    let args = w.args.as_deref().unwrap_or_default();
    let tdep_col = args.get(c.tdep_arg).map_or(w.col, |a| a.1);
    // TDEP as written: its argument of the call's text, when it is a plain number.
    let tdep_text = w
        .text
        .split_once('(')
        .and_then(|(_, rest)| rest.trim_end_matches(')').split(',').nth(c.tdep_arg))
        .map(|t| t.trim().to_string())
        .filter(|t| t.parse::<f64>().is_ok());
    let order: Vec<(u32, usize)> = if c.starts_interleaved {
        (0..c.depths.len()).flat_map(|k| (0..c.starts).map(move |s| (s, k))).collect()
    } else {
        (0..c.starts).flat_map(|s| (0..c.depths.len()).map(move |k| (s, k))).collect()
    };
    for (start, k) in order {
        let (d, off) = (c.depths[k], offsets[k]);
        let phase = f64::from(start) * c.pitch + c.nsp_deg / 360.0 * lead;
        // External: DM is the major diameter, cut inwards. Internal: DM is the tap-hole
        // diameter, cut outwards (Sinumerik cycle documentation).
        let xd = |dm: f64| if c.external { dm - 2.0 * d } else { dm + 2.0 * d };
        let zs = c.at.spl - dir * c.at.app + off - dir * phase;
        let mut p = cycles::pass(
            xd(c.at.dm1),
            xd(c.at.dm2),
            zs,
            c.at.fpl + dir * c.at.rop,
            lead,
            b.line,
            0.0,
            xd(c.at.dm2),
        );
        p.start = start;
        m.push(op, b.line, p)?;
    }
    let s = m.scale;
    m.op_mut(op).depth_word = Some(super::DepthWord {
        word: "TDEP".into(),
        value: c.tdep / s,
        line: b.line,
        column: tdep_col,
        form: if tdep_text.is_some() {
            super::WordForm::Argument
        } else {
            super::WordForm::ArgumentExpression
        },
        written: tdep_text.unwrap_or_else(|| format!("{}", c.tdep / s)),
        means: super::WordMeans::Depth { per_radial: 1.0 },
    });
    Ok(())
}

/// ISO 261 coarse pitch of the sizes CYCLE97's MPIT accepts (M3 to M60).
fn coarse_pitch_for(size: f64) -> Option<f64> {
    let cat = crate::standards::catalog().ok()?;
    cat.iso
        .series
        .sizes
        .iter()
        .find(|s| (s.d - size).abs() < 1e-9 && (3.0..=60.0).contains(&size))
        .and_then(|s| s.coarse)
}

impl Rules for State {
    fn block(&mut self, m: &mut Motion, b: &RBlock<'_>, cx: &mut Ctx<'_>) -> Result<Flow, Error> {
        block(self, m, b, cx)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// CYCLE98's published VARI code (Siemens, Job planning 02/2011, p. 811), digit by digit.
    #[test]
    fn cycle99_vari_reads_the_cycle98_digit_code() {
        let v = Vari99::parse(1300101.0).unwrap();
        assert_eq!(
            v,
            Vari99 {
                external: true,
                degressive: false,
                flank: FlankDigit::One,
                max_infeed: false,
                rough: true,
                finish: true,
                starts_interleaved: true
            }
        );
        let v = Vari99::parse(210204.0).unwrap();
        assert!(
            !v.external
                && v.degressive
                && v.flank == FlankDigit::Alternating
                && v.max_infeed
                && !v.rough
                && v.finish
        );
        assert!(!v.starts_interleaved);
        let v = Vari99::parse(100003.0).unwrap();
        assert!(v.external && v.degressive && v.flank == FlankDigit::BySign && v.rough && !v.finish);
        for bad in [0.0, 5.0, 11.0, 301.0, 1001.0, 20001.0, 400001.0, 2000001.0, 1.5, -1.0] {
            assert!(Vari99::parse(bad).is_err(), "{bad}");
        }
    }

    /// The law's depths: 0.87 in 3 linear cuts, the finishing cut and 2 idle passes; finishing
    /// only is one cut at TDEP and the idle passes; roughing only stops at TDEP − FAL.
    #[test]
    fn sinumerik_depths_follow_the_machining_choice() {
        let d = sinumerik_depths(0.92, 0.05, 3, false, true, true, 2);
        let want = [0.29, 0.58, 0.87, 0.92, 0.92, 0.92];
        assert!(d.len() == want.len() && d.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-12), "{d:?}");
        assert_eq!(sinumerik_depths(0.92, 0.05, 3, false, false, true, 1), [0.92, 0.92]);
        let d = sinumerik_depths(0.92, 0.05, 3, false, true, false, 1);
        assert!(d.len() == 3 && (d[2] - 0.87).abs() < 1e-12, "{d:?}");
        assert_eq!(sinumerik_depths(0.92, 0.0, 1, true, true, true, 0), [0.92]);
    }
}
