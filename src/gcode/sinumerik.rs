//! Sinumerik: `G33 Z K` (`I` for steep tapers, `SF=` start offset), `CYCLE97`, the old 810T/3T
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
use crate::gcode::passes::Pass;
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
            format!("{} is not a threading cycle threadcheck reads (CYCLE97 is)", w.name),
        ));
    }
    // Subprogram call: L9 P33, or the old thread cycles L96/L97 when the file does not define them.
    if let Some(w) = b.get("L") {
        cycles::modal(m, b)?;
        let name = format!("L{}", w.v.round() as i64);
        let reps = b.get("P").map_or(1.0, |p| p.v);
        if !(reps >= 0.0 && reps.fract() == 0.0 && reps <= crate::ground::bounds::MAX_REPEATS as f64) {
            return Err(b.werr(
                &m.file,
                w,
                format!(
                    "{name} P{reps}: repetitions must be a whole number up to {}",
                    crate::ground::bounds::MAX_REPEATS
                ),
            ));
        }
        if !cx.subs.contains(&name) {
            match name.as_str() {
                "L97" | "L96" => {
                    for _ in 0..reps as usize {
                        if name == "L97" {
                            l97(m, b, w, cx)?;
                        } else {
                            l96(m, b, w, cx)?;
                        }
                    }
                    return Ok(Flow::Next);
                }
                _ => return Err(b.werr(&m.file, w, format!("subprogram {name} is not in this file"))),
            }
        }
        return Ok(Flow::Call { name, repeats: reps as u32, locals: None, col: w.col });
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
                    let p = coarse_pitch_for(mpit.abs()).filter(|_| mpit.abs() <= 48.0);
                    if p.is_none() {
                        m.note(
                            line,
                            call.col,
                            format!(
                                "{} MPIT {}: not a metric size M3 to M48 with a coarse pitch; the feed is not checked",
                                call.name,
                                crate::ground::fmt::fmt_num(mpit)
                            ),
                        );
                    }
                    p.map(|p| p.copysign(mpit))
                }
                (None, None) => None,
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
    if m.holes.len() < crate::ground::bounds::MAX_PASSES {
        m.holes.push(super::HoleCycle {
            code: call.name.clone(),
            kind,
            line,
            column: if line == call.line { call.col } else { 1 },
            x: m.x,
            y: m.y,
            bottom,
            feed,
            feed_word: feed_word.into(),
            hand,
            feed_per_rev,
            feed_mode_assumed: assumed,
            spindle: m.s,
            spindle_dir,
            tool: m.tool,
            rigid: call.name == "CYCLE84",
        });
    }
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
    let op = m.begin_op("L97", b.line);
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
    let op = m.begin_op("L96", b.line);
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
    let vari = if vari == 0.0 { 1.0 } else { vari };
    if ![1.0, 2.0, 3.0, 4.0].contains(&vari) {
        return Err(b.werr(&m.file, w, format!("CYCLE97 VARI {vari} must be 1, 2, 3 or 4")));
    }
    let (tdep, fal) = (tdep * s, fal * s);
    if !(tdep > 0.0 && fal >= 0.0 && fal < tdep) {
        return Err(b.werr(&m.file, w, "CYCLE97 needs TDEP > 0 and 0 ≤ FAL < TDEP"));
    }
    let nrc = if nrc == 0.0 { 1.0 } else { nrc };
    let numt = if numt == 0.0 { 1.0 } else { numt };
    let whole = |v: f64, lo: f64, hi: f64| v >= lo && v <= hi && v.fract() == 0.0;
    let max = crate::ground::bounds::MAX_REPEATS as f64;
    if !whole(nrc, 1.0, max) || !whole(nid, 0.0, max) || !whole(numt, 1.0, 64.0) {
        return Err(b.werr(&m.file, w, "CYCLE97 NRC, NID and NUMT must be whole numbers in range"));
    }
    if m.css {
        m.note(b.line, w.col, "CYCLE97 under constant surface speed (G96); threading wants G97");
    }
    let external = vari == 1.0 || vari == 3.0;
    let area = vari >= 3.0;
    let rough = tdep - fal;
    let n = nrc as usize;
    let mut depths: Vec<f64> = (1..=n)
        .map(|i| if area { rough * (i as f64 / nrc).sqrt() } else { rough * i as f64 / nrc })
        .collect();
    if fal > 0.0 {
        depths.push(tdep);
    }
    depths.extend(std::iter::repeat_n(tdep, nid as usize));
    let shift = if iang > 0.0 {
        Shift::Flank(iang)
    } else if iang < 0.0 {
        Shift::Alternating(-iang)
    } else {
        Shift::Radial
    };
    let (spl, fpl) = (spl * s, fpl * s);
    let dir = if fpl < spl { -1.0 } else { 1.0 };
    let offsets = cycles::shifts(shift, &depths, dir);
    let lead = pitch * numt;
    let (d1, d2) = (dm1 * s, dm2 * s);
    let op = m.begin_op("CYCLE97", b.line);
    m.op_mut(op).infeed_angle = Some((iang.abs(), "IANG".into()));
    let tdep_col = args.get(8).map_or(w.col, |a| a.1);
    // TDEP as written: the ninth argument of the call's text, when it is a plain number.
    let tdep_text = w
        .text
        .split_once('(')
        .and_then(|(_, rest)| rest.trim_end_matches(')').split(',').nth(8))
        .map(|t| t.trim().to_string())
        .filter(|t| t.parse::<f64>().is_ok());
    for start in 0..numt as u32 {
        let phase = f64::from(start) * pitch + nsp / 360.0 * lead;
        for (d, off) in depths.iter().zip(&offsets) {
            // External: DM is the major diameter, cut inwards. Internal: DM is the tap-hole
            // diameter, cut outwards (Sinumerik cycle documentation).
            let xd = |dm: f64| if external { dm - 2.0 * d } else { dm + 2.0 * d };
            let zs = spl - dir * app * s + off - dir * phase;
            let mut p = cycles::pass(xd(d1), xd(d2), zs, fpl + dir * rop * s, lead, b.line, 0.0, xd(d2));
            p.start = start;
            m.push(op, b.line, p)?;
        }
    }
    m.op_mut(op).depth_word = Some(super::DepthWord {
        word: "TDEP".into(),
        value: tdep / s,
        line: b.line,
        column: tdep_col,
        form: if tdep_text.is_some() {
            super::WordForm::Argument
        } else {
            super::WordForm::ArgumentExpression
        },
        written: tdep_text.unwrap_or_else(|| format!("{}", tdep / s)),
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
