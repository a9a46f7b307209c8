//! What the dialects share: the modal G codes, the depth laws of the threading cycles, and the
//! passes of a cycle laid out from a list of depths.

use super::lexer::{Past, PastKind};
use super::motion::{Motion, Profile, RBlock};
use super::Dialect;
use crate::gcode::SystemCode;
use crate::ground::bounds::MAX_PASSES;
use crate::toolpath::passes::Pass;
use crate::Error;

/// The motion G code of a block, after the modal codes were applied.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Modal {
    /// The motion code in force for this block and its column (the block's own, or modal).
    pub motion: f64,
    /// Column of the block's own motion word, if it has one.
    pub col: Option<usize>,
    /// A one-shot code that makes the block no move of its own (G4 dwell, G28, turning cycles
    /// G70–G75, LinuxCNC G92 offsets, G10 data, a G92 S speed clamp).
    pub one_shot: Option<f64>,
}

/// What a G code does in the model, for the codes that are not motion and not handled one by
/// one in [`modal`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum GRole {
    /// A setting that changes nothing threadcheck models (exact stop, compensation, feed and
    /// spindle modes, return levels, look-ahead, …).
    Setting,
    /// A work offset or coordinate shift: the position in program coordinates becomes unknown.
    Offset,
    /// Data setting (Fanuc, LinuxCNC G10): the block's words are data, not a move; offsets
    /// may change, so the position becomes unknown.
    Data,
    /// A canned cycle that is not threading (drilling, tapping, boring): modal, its blocks are
    /// read past and leave the position unknown.
    OtherCycle,
    /// A coordinate-system code the dialect applies itself (LinuxCNC's G10 L2/L20, G52,
    /// G54–G59.3, G92 and its kin): G10 and G52 take the block's words as data, not a move.
    Coordinates,
    /// Fanuc and Haas lathes' box cycles G90 (turning) and G94 (facing): modal, read past,
    /// each returns to its start point.
    BoxCycle,
    /// Not a code threadcheck knows in this dialect: read past with a note; the block's axis
    /// words are read as a move in the modal motion (the named default).
    Unknown,
}

/// The role of the whole-number G code `g` in dialect `d` (`lathe` for a turning program).
fn g_role(d: Dialect, g: u32, lathe: bool) -> GRole {
    use GRole::*;
    match d {
        Dialect::Fanuc | Dialect::Haas | Dialect::Mitsubishi | Dialect::Mazak => match g {
            90 | 94 if lathe => BoxCycle,
            73 | 74 | 76 if !lathe => OtherCycle,
            // A Haas lathe's G95 is live-tool rigid tapping, not a feed mode (HAAS-L84).
            95 if lathe && d == Dialect::Haas => OtherCycle,
            9 | 22 | 23 | 25 | 26 | 40..=44 | 49 | 61..=64 | 67..=69 | 80 | 94 | 95 | 98 | 99 | 103 | 187 => {
                Setting
            }
            52 | 54..=59 | 100 | 101 | 110 | 111 | 154 => Offset,
            // A Haas mill's additional work offsets G110–G129 (G154 P1–P20).
            112..=129 if !lathe && d == Dialect::Haas => Offset,
            10 | 11 => Data,
            81..=89 | 184 | 186 | 195 | 196 => OtherCycle,
            // A Haas lathe's radial drilling cycles (live tool, along X).
            241..=243 if lathe && d == Dialect::Haas => OtherCycle,
            _ => Unknown,
        },
        Dialect::Sinumerik => match g {
            9 | 25 | 26 | 40..=42 | 60 | 64 | 93..=95 | 110..=112 | 450 | 451 | 601..=603 | 641..=645 => {
                Setting
            }
            54..=59 | 153 | 500 | 505..=599 => Offset,
            63 | 331 | 332 => OtherCycle,
            _ => Unknown,
        },
        Dialect::LinuxCnc => match g {
            40..=43 | 49 | 61 | 64 | 93..=95 | 98 | 99 => Setting,
            10 | 52 | 54..=59 | 92 => Coordinates,
            73 | 74 | 81..=89 => OtherCycle,
            _ => Unknown,
        },
        Dialect::Dyna => match g {
            9 | 40..=44 | 49 | 61 | 64 | 94 | 95 | 98 | 99 => Setting,
            54..=59 | 92 => Offset,
            73 | 74 | 81..=89 => OtherCycle,
            _ => Unknown,
        },
        // OSP: G50 the spindle speed clamp, G94/G95 feed per minute/revolution, G40–G42 nose
        // radius compensation; G15/G16 work coordinate selection; G73–G75 and G81–G89 turning and
        // drilling cycles (read past).
        Dialect::Okuma => match g {
            9 | 40..=42 | 50 | 61 | 64 | 94 | 95 => Setting,
            15 | 16 | 92 => Offset,
            73..=75 | 81..=89 => OtherCycle,
            _ => Unknown,
        },
        // MANUALplus / CNC PILOT DIN: G14 the tool change point, G26 the speed limit, G40–G42
        // nose radius compensation, G47 the safety clearance, G57/G58 oversizes, G59 the datum
        // shift; G20/G21 define the blank (read past where they stand outside their section);
        // G36 tapping, G71–G74 drilling and G81–G87 turning cycles (read past).
        Dialect::Heidenhain => match g {
            // G14 (heidenhain.rs) leaves the position unknown.
            9 | 14 | 20 | 21 | 26 | 40..=42 | 47 | 48 | 50 | 57 | 58 | 60 | 94 | 95 => Setting,
            59 => Offset,
            36 | 71..=74 | 81..=87 => OtherCycle,
            _ => Unknown,
        },
        // Klartext has no G codes (its own reader reads it).
        Dialect::Klartext => Unknown,
    }
}

/// Whether the M code `c` is one threadcheck knows in dialect `d` (the rest are noted as read
/// past: an M code never moves the axes in the model).
fn m_known(d: Dialect, c: u32) -> bool {
    // M13/M14 (spindle on with coolant) are common enough to be known on every control.
    let common = matches!(c, 0..=9 | 13 | 14 | 19 | 30 | 40..=44);
    common
        || match d {
            Dialect::Fanuc | Dialect::Mitsubishi | Dialect::Mazak => {
                matches!(c, 10..=11 | 23 | 24 | 29 | 98 | 99)
            }
            // Heidenhain's lathe M codes beyond the common ones are not modelled.
            Dialect::Heidenhain | Dialect::Klartext => false,
            Dialect::Haas => matches!(
                c,
                10..=15
                    | 21..=24
                    | 31
                    | 33
                    | 36
                    | 51..=59
                    | 69
                    | 85
                    | 86
                    | 88
                    | 89
                    | 95..=99
                    | 109
                    | 110
                    | 119
                    | 121..=128
                    | 133..=135
                    | 143..=145
                    | 154
                    | 155
            ),
            Dialect::Sinumerik => matches!(c, 17 | 45),
            Dialect::LinuxCnc => matches!(c, 48..=53 | 60..=73),
            Dialect::Dyna => matches!(c, 73 | 74 | 98 | 99),
            // M23/M24 chamfer on/off; M32–M34 the infeed (single blade, zig-zag, reverse);
            // M73–M75 the depth pattern of G71/G72.
            Dialect::Okuma => matches!(c, 23 | 24 | 32..=34 | 73..=75),
        }
}

/// Threading codes whose decimal variants are other functions: refused by name, never read as
/// the threading code.
const THREADING: [f64; 5] = [32.0, 33.0, 76.0, 78.0, 92.0];

/// Applies the block's modal G codes (units, distance mode, diameter mode, spindle mode, plane)
/// and returns its motion code.
pub(crate) fn modal(m: &mut Motion, b: &RBlock<'_>) -> Result<Modal, Error> {
    let d = m.dialect;
    let mut acc = Codes::default();
    let fanuc_like = fanuc_like(d);
    for (g, col) in b.gs() {
        if g < 0.0 {
            return Err(m.err(b.line, col, "G with no code"));
        }
        if g.fract() != 0.0 {
            decimal_code(m, b, g, col, &mut acc)?;
            continue;
        }
        let Some(g) = in_system_a(m, b, g, col, &mut acc)? else {
            continue;
        };
        whole_code(m, b, g, col, &mut acc)?;
    }
    let Codes { motion, one_shot, offset, unknown } = acc;
    // Under G16 the block's X is the radius and Y the angle: remembered, so that a block that
    // gives one takes the other from before (the move itself is made in `Motion::target`).
    if let Some((r0, a0)) = m.polar {
        let (xw, yw) = (b.get("X"), b.get("Y"));
        if xw.is_some() || yw.is_some() {
            if !m.absolute {
                return Err(m.err(
                    b.line,
                    b.col,
                    "G16 with G91 (an incremental radius or angle) is not read: write them absolute",
                ));
            }
            let r = xw.map(|w| m.len(w)).or(r0);
            let a = yw.map(|w| w.v).or(a0);
            if r.is_none() || a.is_none() {
                return Err(m.err(
                    b.line,
                    b.col,
                    format!("G16: the {} is not known yet: write X (the radius) and Y (the angle) in the first polar block", if r.is_none() { "radius X" } else { "angle Y" }),
                ));
            }
            m.polar = Some((r, a));
        }
    }
    // A lathe's C axis (the spindle's angle for live tools): kept for the holes it places.
    if let Some(c) = b.get("C").filter(|_| fanuc_like && m.lathe()) {
        m.c_axis = Some(c.v);
    }
    for w in b.words.iter().filter(|w| w.name == "M") {
        match w.v {
            3.0 => m.spindle_dir = Some(super::SpindleDir::Cw),
            4.0 => m.spindle_dir = Some(super::SpindleDir::Ccw),
            5.0 => m.spindle_dir = Some(super::SpindleDir::Stopped),
            29.0 if fanuc_like => m.rigid_next = true,
            _ => {}
        }
        if w.v == 97.0 && fanuc_like && d != Dialect::Haas {
            // The evidence of a Haas program read in another dialect (issue 62): named.
            m.read_past(
                b.line,
                w.col,
                "M97",
                &format!("Haas's call of a local subprogram (M97 P…, an N label in the same program), which the {} dialect does not run: a Haas program is read with ‹dialect› haas", d.name()),
            );
        } else if w.v >= 0.0 && w.v.fract() == 0.0 && w.v < 1e6 && !m_known(d, w.v as u32) {
            m.read_past(
                b.line,
                w.col,
                &format!("M{}", w.v),
                "an M code threadcheck does not know (M codes do not move the axes here)",
            );
        }
    }
    if let Some((g, col)) = unknown.first().copied() {
        if let Some((t, _)) = motion.filter(|(t, _)| THREADING.contains(t)) {
            return Err(m.err(
                b.line,
                col,
                format!("G{g} is not a code threadcheck knows in the {} dialect, and this G{t} block depends on it", d.name()),
            ));
        }
        let modal_now = motion.map_or(m.motion, |x| x.0);
        m.read_past(
            b.line,
            col,
            &format!("G{g}"),
            &format!("not a code threadcheck knows in this dialect; the block's axis words are read as a move in the modal G{modal_now} (assumed)"),
        );
    }
    if let Some(what) = offset {
        m.lose_position(b.line, &what, true, true);
    }
    if let Some((g, _)) = motion {
        m.motion = g;
        if !is_hole_cycle(g) {
            m.cycle_levels = (None, None);
            m.cycle_in_force = None;
        }
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

/// What a block's G codes set that the block's move needs: its motion code and column, a
/// one-shot code, what lost the position, and the codes not known.
#[derive(Default)]
struct Codes {
    motion: Option<(f64, usize)>,
    one_shot: Option<f64>,
    offset: Option<String>,
    unknown: Vec<(f64, usize)>,
}

/// A G code with a decimal (G33.1, G54.1, G51.1…): applied, or refused where it is a threading
/// code's variant.
fn decimal_code(m: &mut Motion, b: &RBlock<'_>, g: f64, col: usize, acc: &mut Codes) -> Result<(), Error> {
    let d = m.dialect;
    let fanuc_like = fanuc_like(d);
    let base = g.trunc();
    match (d, g) {
        // Applied by the dialect (linuxcnc.rs) after the modal codes.
        (Dialect::LinuxCnc, 92.1 | 92.2 | 92.3) => acc.one_shot = Some(g),
        (Dialect::LinuxCnc, 59.1 | 59.2 | 59.3) => {}
        (Dialect::LinuxCnc, 33.1) => {
            // Rigid tapping: recorded for `threadcheck tap`, read past by the rest.
            let (x, y, z) = m.target(b);
            let feed = b.get("K").map(|w| m.len(w));
            m.push_synced_tap("G33.1", b.line, col, (x.or(m.x), y.or(m.y)), z, feed, "K")?;
            // LinuxCNC moves the tap in a straight line to X Y Z: X or Y away from
            // where it stands drags it sideways (its documentation: preposition X and
            // Y, give only Z).
            let from = [m.x, m.y];
            let sideways: Vec<String> = [("X", x, from[0]), ("Y", y, from[1])]
                .iter()
                .filter_map(|(n, to, at)| match (to, at) {
                    (Some(to), Some(at)) if (to - at).abs() > 1e-6 => Some(format!(
                        "{n} from {} to {}",
                        crate::ground::fmt::fmt_num(*at),
                        crate::ground::fmt::fmt_num(*to)
                    )),
                    _ => None,
                })
                .collect();
            if !sideways.is_empty() {
                m.flag(
                    super::ControlRule::TapMovesSideways,
                    "G33.1",
                    b.line,
                    col,
                    format!("the tap moves {} as it feeds to the bottom", sideways.join(" and ")),
                );
            }
            m.read_past(
                b.line,
                col,
                "G33.1",
                "rigid tapping (threadcheck tap checks it); it returns to its start",
            );
            acc.one_shot = Some(g);
        }
        // The additional work offsets (G54.1 P1…P48/300): a work offset as G54…G59 are.
        (Dialect::Fanuc | Dialect::Mitsubishi | Dialect::Mazak, 54.1) => {
            if let Some(name) = work_offset_name(d, g, b) {
                m.work_offset = Some(name);
            }
            acc.offset = Some(format!("G{g}, a work offset"));
        }
        // A machining centre's programmable mirror image (SIE-ISO p.3-65): G51.1 X… Y…
        // mirrors the positions about the axis values given, G50.1 cancels them.
        (_, 51.1) if fanuc_like && !m.lathe() => {
            acc.one_shot = Some(g);
            for (i, axis) in ["X", "Y"].iter().enumerate() {
                if let Some(w) = b.get(axis) {
                    m.mirror[i] = Some(m.len(w));
                }
            }
            if b.get("Z").is_some() {
                return Err(m.err(b.line, col, "G51.1 Z: a mirrored tool axis is not read (X and Y are)"));
            }
        }
        (_, 50.1) if fanuc_like && !m.lathe() => {
            acc.one_shot = Some(g);
            let (x, y) = (b.get("X").is_some(), b.get("Y").is_some());
            if x || !y {
                m.mirror[0] = None;
            }
            if y || !x {
                m.mirror[1] = None;
            }
        }
        // The roughing cycles of type 2 run their profile subroutine (Q) as G71 and G72
        // do: read past, named.
        (Dialect::LinuxCnc, 71.1 | 72.1) => acc.one_shot = Some(g),
        // Arc centres absolute (G90.1) or incremental (G91.1): a lathe's arcs are kept as
        // chords of the turned contour, so the mode is named, not needed.
        (Dialect::LinuxCnc, 90.1 | 91.1) => {
            m.arc_centres_absolute = g == 90.1;
            if m.lathe() {
                m.read_past(
                    b.line,
                    col,
                    &format!("G{g}"),
                    "the arc centres' distance mode; the turned contour's arcs are read as chords",
                );
            }
        }
        _ if THREADING.contains(&base) => {
            return Err(m.err(
                b.line,
                col,
                format!("G{g} is not G{base}: threadcheck reads G{base} and does not read G{g}"),
            ))
        }
        // A lathe's polar coordinate interpolation (F0i-TF: G12.1 on, G13.1 off): a live
        // tool mills the face in X and C.
        (_, 12.1) if fanuc_like && m.lathe_program() => polar(m, b.line, col, "G12.1"),
        (_, 13.1) if fanuc_like && m.lathe_program() => polar_off(m, b.line, col, "G13.1"),
        // G7.1, G42.1, G43.1 and kin: not lathe threading; the block is read for position.
        _ => {}
    }
    Ok(())
}

/// A whole G code in Fanuc G-code system A's terms (`None` when a system B or C code was applied
/// or noted here); other dialects' codes as they are.
fn in_system_a(
    m: &mut Motion,
    b: &RBlock<'_>,
    g: f64,
    col: usize,
    acc: &mut Codes,
) -> Result<Option<f64>, Error> {
    let d = m.dialect;
    // Systems B and C keep the feed modes and the return levels apart in every section
    // (F0i-TF's G-code list: G94/G95 feed per minute/revolution, G98/G99 the drilling
    // cycles' initial and R level), as a machining centre does.
    if d.fanuc_family() && m.gsystem != super::GCodeSystem::A && g.fract() == 0.0 {
        match g as u32 {
            94 | 95 => {
                m.feed_per_rev = Some(g == 95.0);
                return Ok(None);
            }
            98 | 99 => {
                m.return_to_r = g == 99.0;
                return Ok(None);
            }
            _ => {}
        }
    }
    // A program of G-code system B or C: its code in system A's terms.
    let g = if d.fanuc_family() {
        match m.gsystem.to_a(g as u32) {
            // System A has no G91 on a lathe (U and W are its increments).
            SystemCode::A(91) if m.gsystem == super::GCodeSystem::A && m.lathe() => {
                acc.unknown.push((g, col));
                return Ok(None);
            }
            SystemCode::A(a) => f64::from(a),
            SystemCode::Absolute => {
                m.absolute = true;
                return Ok(None);
            }
            SystemCode::Incremental => {
                m.absolute = false;
                return Ok(None);
            }
            SystemCode::Setting => return Ok(None),
            // System A's thread cutting in a program read in B or C (which write G33): never
            // dropped, refused at its place.
            SystemCode::Foreign if g == 32.0 => {
                return Err(m.err(
                    b.line,
                    col,
                    format!(
                        "G32 is thread cutting in Fanuc G-code system A; this program is read in system {} (thread cutting G33), so the G32 would not cut a thread: give ‹gcode_system› a if the control runs system A",
                        m.gsystem.name()
                    ),
                ));
            }
            SystemCode::Foreign => {
                acc.unknown.push((g, col));
                return Ok(None);
            }
        }
    } else {
        g
    };
    Ok(Some(g))
}

/// A whole G code applied: compensation, modes, planes, coordinate systems, or the block's motion.
fn whole_code(m: &mut Motion, b: &RBlock<'_>, g: f64, col: usize, acc: &mut Codes) -> Result<(), Error> {
    let d = m.dialect;
    let fanuc_like = fanuc_like(d);
    // A dialect without unit codes (Heidenhain) matches none (no G code is negative).
    let inch_codes = d.unit_codes().map_or((-1.0, -1.0), |(i, mm)| (f64::from(i), f64::from(mm)));
    if m.plane == 17 || m.mill_reading() {
        match g as u32 {
            40 => m.comp = 0,
            41 => m.comp = 1,
            42 => m.comp = 2,
            _ => {}
        }
    } else if matches!(g as u32, 40..=42) {
        m.nose_comp = g as u8 - 40;
    }
    match g as u32 {
        // G112/G113: G12.1/G13.1 as Fanuc's lathes also write them (Haas: G112, XY to XC).
        112 if fanuc_like && m.lathe_program() => polar(m, b.line, col, "G112"),
        113 if fanuc_like && m.lathe_program() => polar_off(m, b.line, col, "G113"),
        // Heidenhain's thread cycle G31 (heidenhain.rs); its G32, the simple thread cycle,
        // is refused by name; its G76 is no threading code.
        31 if d == Dialect::Heidenhain => acc.motion = Some((g, col)),
        32 if d == Dialect::Heidenhain => {
            return Err(m.err(
                b.line,
                col,
                "G32 (Heidenhain's simple thread cycle) is not supported: its word list is not in the pages read; write G31 (the thread cycle) or G33 (single thread paths)",
            ))
        }
        76 if d == Dialect::Heidenhain => acc.unknown.push((g, col)),
        // A machining centre's peck drilling, left-hand tapping and fine boring.
        73 | 74 | 76 if fanuc_like && !m.lathe() => acc.motion = Some((g, col)),
        // LinuxCNC's G73 is chip-breaking drilling and its G74 left-hand tapping on every
        // machine (its lathe cycles are G70–G72 and G76).
        73 | 74 if d == Dialect::LinuxCnc => acc.motion = Some((g, col)),
        0 | 1 | 2 | 3 | 32 | 33 | 76 => acc.motion = Some((g, col)),
        92 if d == Dialect::LinuxCnc => acc.one_shot = Some(g),
        92 if fanuc_like && b.has("S") && !["X", "Z", "U", "W", "F", "E", "R"].iter().any(|w| b.has(w)) => {
            m.read_past(
                b.line,
                col,
                &format!("G92 S{}", b.get("S").map_or(0.0, |w| w.v)),
                "a spindle speed clamp, as G-code systems B and C write it (system A, which this dialect reads, writes G50 S); it cuts no thread",
            );
            acc.one_shot = Some(g);
        }
        // A machining centre's local coordinate system, kept per axis until changed; G52 X0 Y0
        // Z0 cancels it.
        52 if fanuc_like && !m.lathe() => {
            acc.one_shot = Some(g);
            for (i, axis) in ["X", "Y", "Z"].iter().enumerate() {
                if let Some(w) = b.get(axis) {
                    m.local[i] = m.len(w);
                }
            }
        }
        // A machining centre's coordinate rotation in G17: about X Y (the current point when
        // not given) by R degrees counter-clockwise; G69 ends it.
        68 if fanuc_like && !m.lathe() => {
            acc.one_shot = Some(g);
            let centre = |axis: &str, now: Option<f64>| b.get(axis).map(|w| m.len(w)).or(now);
            let (Some(cx), Some(cy)) = (centre("X", m.x), centre("Y", m.y)) else {
                return Err(m.err(b.line, col, "G68 without X and Y rotates about the current point, which is not known here: give the centre"));
            };
            if m.plane != 17 {
                return Err(m.err(b.line, col, format!("G68 under G{}: threadcheck reads rotation in the plane G17", m.plane)));
            }
            m.rotation = Some((cx, cy, b.get("R").map_or(0.0, |w| w.v)));
        }
        69 if fanuc_like && !m.lathe() => m.rotation = None,
        // A machining centre's polar coordinates (F16MC 9.2): under G16 in G17, X is the
        // radius and Y the angle (degrees) about the work zero; G15 ends them.
        16 if fanuc_like && !m.lathe() => {
            if m.plane != 17 {
                return Err(m.err(b.line, col, format!("G16 under G{}: threadcheck reads polar coordinates in the plane G17", m.plane)));
            }
            m.polar = Some((None, None));
        }
        15 if fanuc_like && !m.lathe() => m.polar = None,
        // Scaling moves every later position by a factor about a centre: not read.
        51 if fanuc_like && !m.lathe() => {
            return Err(m.err(b.line, col, "G51 (scaling) is not read: the positions under it would be wrong (G51.1, the mirror image, is)"));
        }
        // Haas's bolt-hole patterns on a mill (../shared/notes/machining-centres.md §2).
        70..=72 if d == Dialect::Haas && !m.lathe() => acc.one_shot = Some(g),
        // A machining centre's G92: the current point gets the given coordinates.
        92 if fanuc_like && !m.lathe() => {
            acc.one_shot = Some(g);
            acc.offset = Some("G92, a coordinate system set at the current point".to_string());
        }
        92 => acc.motion = Some((g, col)),
        78 if d.fanuc_family() => {
            return Err(m.err(
                b.line,
                col,
                "G78 is not a code of Fanuc G-code system A, which this program is read in: a control set to system B reads it as the threading cycle (G92 in A), one set to system C as the multiple threading cycle (G76 in A); give ‹gcode_system› b or c (the EMCO training lathe's G78 box cycle is not supported)",
            ))
        }
        78 if fanuc_like || d == Dialect::Sinumerik => {
            return Err(m.err(
                b.line,
                col,
                "G78 (the EMCO training-lathe thread cycle) is not supported: its word format is not published; write G92 or G76",
            ))
        }
        50 if fanuc_like && m.lathe() => acc.one_shot = Some(g),
        // Feed modes (the tapping check reads them): G98/G99 on a lathe (and in a lathe-based
        // mill-turn's milling sections in system A), G94/G95 in G17.
        98 if fanuc_like && m.g98_is_feed() => m.feed_per_rev = Some(false),
        99 if fanuc_like && m.g98_is_feed() => m.feed_per_rev = Some(true),
        // A machining centre's G98/G99: the canned cycles' return level.
        98 if fanuc_like || d == Dialect::LinuxCnc => m.return_to_r = false,
        99 if fanuc_like || d == Dialect::LinuxCnc => m.return_to_r = true,
        94 if fanuc_like && (m.plane == 17 || !m.lathe()) => m.feed_per_rev = Some(false),
        95 if fanuc_like && (m.plane == 17 || !m.lathe()) => m.feed_per_rev = Some(true),
        // Sinumerik's feed modes hold in every plane.
        94 if matches!(d, Dialect::Sinumerik | Dialect::Heidenhain) => m.feed_per_rev = Some(false),
        95 if matches!(d, Dialect::Sinumerik | Dialect::Heidenhain) => m.feed_per_rev = Some(true),
        // LinuxCNC: G94 units per minute, G95 units per revolution (its `_units_per_rev`).
        94 if d == Dialect::LinuxCnc => m.feed_per_rev = Some(false),
        95 if d == Dialect::LinuxCnc => m.feed_per_rev = Some(true),
        90 | 94 if fanuc_like && m.lathe() => acc.motion = Some((g, col)),
        30 => acc.one_shot = Some(g),
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
        17 => {
            m.plane = 17;
            m.plane_changed();
        }
        18 => {
            m.plane = 18;
            m.plane_changed();
        }
        19 => {
            m.plane = 19;
            m.plane_changed();
        }
        80 => acc.motion = Some((80.0, col)),
        4 | 28 | 53 => acc.one_shot = Some(g),
        // Okuma's compound threading cycles (okuma.rs).
        71 | 72 if d == Dialect::Okuma => acc.motion = Some((g, col)),
        70..=75 if fanuc_like || d == Dialect::LinuxCnc => acc.one_shot = Some(g),
        c => match g_role(d, c, m.lathe()) {
            // Haas's own code read in another Fanuc-family dialect: its evidence named.
            GRole::Setting if c == 187 && d != Dialect::Haas => m.read_past(
                b.line,
                col,
                "G187",
                &format!("Haas's smoothness and corner accuracy setting, which the {} dialect does not have (no move here): a Haas program is read with ‹dialect› haas", d.name()),
            ),
            GRole::Setting => {}
            GRole::Offset => {
                acc.offset = Some(format!("G{g}, a work offset"));
                if let Some(name) = work_offset_name(d, g, b) {
                    m.work_offset = Some(name);
                }
            }
            GRole::Data => {
                acc.one_shot = Some(g);
                acc.offset = Some(format!("G{g}, data setting"));
                if c == 10 && !m.lathe() {
                    set_work_origin(m, b, col);
                }
            }
            GRole::Coordinates => {
                if c == 10 || c == 52 {
                    acc.one_shot = Some(g);
                }
            }
            GRole::OtherCycle | GRole::BoxCycle => acc.motion = Some((g, col)),
            GRole::Unknown => acc.unknown.push((g, col)),
        },
    }
    Ok(())
}

/// The work offset a block selects, by one name per offset: `G54`…`G59`; Fanuc's `G54.1 P3`;
/// Haas's `G154 P3`, which its `G110`…`G129` also name (G110 = G154 P1); Sinumerik's `G505`…`G599`.
/// `None` for a code that selects none (G52, G92 and their kin, G500/G53/G153 on Sinumerik).
fn work_offset_name(d: Dialect, g: f64, b: &RBlock<'_>) -> Option<String> {
    let p = || b.get("P").map(|w| w.v).filter(|v| v.fract() == 0.0 && *v >= 1.0).map(|v| v as u32);
    match (d, g) {
        (_, g) if g.fract() == 0.0 && (54.0..=59.0).contains(&g) => Some(format!("G{g}")),
        (Dialect::Fanuc | Dialect::Mitsubishi | Dialect::Mazak, 54.1) => Some(format!("G54.1 P{}", p()?)),
        (Dialect::Haas, 154.0) => Some(format!("G154 P{}", p()?)),
        (Dialect::Haas, g) if g.fract() == 0.0 && (110.0..=129.0).contains(&g) => {
            Some(format!("G154 P{}", g as u32 - 109))
        }
        (Dialect::Sinumerik, g) if g.fract() == 0.0 && (505.0..=599.0).contains(&g) => Some(format!("G{g}")),
        _ => None,
    }
}

/// A machining centre's `G10 L2 Pn X Y Z` (G54…G59's origins, P1…P6) or `G10 L20 Pn` (the
/// additional offsets: Fanuc's G54.1 Pn, Haas's G154 Pn) under G90: the origin the program gives
/// an offset, in machine coordinates, per axis written. Under G91 the words add to values not in
/// the program: the offset's origin is forgotten.
fn set_work_origin(m: &mut Motion, b: &RBlock<'_>, col: usize) {
    let (Some(l), Some(p)) = (b.get("L").map(|w| w.v), b.get("P").map(|w| w.v)) else { return };
    if p.fract() != 0.0 || p < 1.0 {
        return;
    }
    let n = p as u32;
    let name = match l as u32 {
        2 if l.fract() == 0.0 && n <= 6 => format!("G{}", 53 + n),
        20 if l.fract() == 0.0 && m.dialect == Dialect::Haas => format!("G154 P{n}"),
        20 if l.fract() == 0.0 => format!("G54.1 P{n}"),
        _ => return,
    };
    let code = format!("G10 L{l} P{n}");
    if !m.absolute {
        m.read_past(
            b.line,
            col,
            &code,
            &format!("under G91 it adds to {name}'s origin, a value not in the program: holes in {name} are matched to their drills in it alone"),
        );
        m.work_origins.remove(&name);
        return;
    }
    m.read_past(
        b.line,
        col,
        &code,
        &format!("sets {name}'s origin in machine coordinates: a tap in it finds its drill by their places on the machine, in whichever offset whose origin the program sets"),
    );
    let given = ["X", "Y", "Z"].map(|axis| b.get(axis).map(|w| m.len(w)));
    let entry = m.work_origins.entry(name).or_insert([None; 3]);
    for (old, new) in entry.iter_mut().zip(given) {
        if new.is_some() {
            *old = new;
        }
    }
}

/// Sinumerik threading cycles that threadcheck does not read: refused by name, never read past.
const THREADING_CALLS: [&str; 2] = ["CYCLE98", "LCYC97"];

/// Reads past what the lexer set aside in a block: messages and tools called by name leave the
/// motion as it is; a cycle call leaves the position unknown (a threading operation that starts
/// from it is refused, naming the cycle); a threading cycle threadcheck does not read refuses.
pub(crate) fn read_past_item(m: &mut Motion, line: usize, p: &Past) -> Result<(), Error> {
    match p.kind {
        PastKind::Message => m.read_past(line, p.col, &p.name, "a message for the operator"),
        PastKind::ToolName => {
            m.tool = None;
            m.read_past(
                line,
                p.col,
                &p.name,
                "a tool called by name; the insert is the one ‹insert› (or ‹tools› by number) gives",
            );
        }
        // Sinumerik's thread milling and free hole positions: their arguments' order is seen in
        // CAM posts and readers, their meanings in no manual read (notes/machining-centres.md §4).
        PastKind::Call if matches!(p.name.strip_suffix("(…)"), Some("CYCLE90" | "CYCLE802")) => {
            let what = if p.name.starts_with("CYCLE90(") { "thread milling" } else { "a pattern of free hole positions" };
            return Err(m.err(
                line,
                p.col,
                format!(
                    "{} ({what}) is not read: the meanings of its arguments are not published in the sources read (write the helices as G2/G3 with Z, or the positions as blocks)",
                    p.name.trim_end_matches("(…)")
                ),
            ));
        }
        PastKind::Call if THREADING_CALLS.iter().any(|t| p.name.strip_suffix("(…)") == Some(t)) => {
            return Err(m.err(
                line,
                p.col,
                format!(
                    "{} is a threading cycle threadcheck does not read (CYCLE97 and CYCLE99 are)",
                    p.name.trim_end_matches("(…)")
                ),
            ))
        }
        PastKind::RotarySpeed => m.read_past(line, p.col, &p.name, "a rotary (live) tool's spindle speed, not modelled"),
        PastKind::Lap => {
            m.lose_position(line, &p.name, true, true);
            m.read_past(
                line,
                p.col,
                &p.name,
                "an Okuma LAP rough-turning cycle: its roughing passes are not modelled; the shape it names is read from its own blocks, which follow, as moves",
            );
        }
        PastKind::LapShape => m.read_past(
            line,
            p.col,
            &p.name,
            "the start of an Okuma LAP cycle's shape (to its G80): its blocks are read as moves, the finished profile",
        ),
        PastKind::SequenceJump => m.read_past(
            line,
            p.col,
            &p.name,
            "a jump or call to a sequence name, not followed (the blocks after it are read in order)",
        ),
        PastKind::Billet { x, z } => {
            // The bar a lathe program turns: its diameter is the blank of a thread the program
            // turns no diameter for.
            if let Some(d) = x.filter(|d| d.is_finite() && *d > 0.0) {
                m.stock = Some((d * m.scale, line));
            }
            let _ = z;
            m.read_past(
                line,
                p.col,
                &p.name,
                "a training simulator's stock (Denford's BILLET): X the bar's diameter, the blank of a thread the program turns no diameter for",
            );
        }
        PastKind::Simulator => m.read_past(line, p.col, &p.name, "a training simulator's set-up line (Denford's), not a move"),
        PastKind::Section => m.read_past(
            line,
            p.col,
            &p.name,
            "a DIN PLUS section of set-up or contour data: its blocks are geometry and data, not moves, and are read past up to the next MACHINING",
        ),
        PastKind::Call => {
            m.lose_position(line, &p.name, true, true);
            m.read_past(
                line,
                p.col,
                &p.name,
                "a cycle that is not threading; where it leaves the tool is not modelled",
            );
        }
    }
    Ok(())
}

/// A lathe's polar coordinate interpolation starts: its moves mill the face, read past.
fn polar(m: &mut Motion, line: usize, col: usize, code: &str) {
    m.face_polar = Some(line);
    m.read_past(
        line,
        col,
        code,
        "polar coordinate interpolation: a live tool mills the face in X and C; its moves, to the G13.1 (G113), are read past, not as turning",
    );
}

/// Polar coordinate interpolation ends: the X it left is not known here (its X was a point of
/// the face, not a diameter), so the next move must give one.
fn polar_off(m: &mut Motion, line: usize, col: usize, code: &str) {
    if m.face_polar.take().is_some() {
        m.lose_position(line, &format!("{code} ending polar coordinate interpolation"), true, false);
    } else {
        m.read_past(line, col, code, "cancels polar coordinate interpolation, which is not in force");
    }
}

/// A block under a lathe's polar coordinate interpolation: its moves mill the face and are read
/// past (true); a threading word there is refused, since the control cuts no thread in it.
pub(crate) fn polar_block(m: &mut Motion, b: &RBlock<'_>, md: &Modal) -> Result<bool, Error> {
    let Some(from) = m.face_polar else { return Ok(false) };
    if matches!(md.motion as u32, 32 | 33 | 76 | 92) && md.motion.fract() == 0.0 && md.col.is_some() {
        return Err(m.err(
            b.line,
            md.col.unwrap_or(b.col),
            format!(
                "G{} under the polar coordinate interpolation of line {from}: a thread is turned in G18 after G13.1 (G113)",
                md.motion
            ),
        ));
    }
    if ["X", "Y", "Z", "C", "U", "W", "H"].iter().any(|w| b.has(w)) {
        m.read_past(
            b.line,
            b.col,
            "moves under G12.1",
            "a live tool milling the face in polar coordinate interpolation (X and C a plane): read past, not as turning",
        );
        if b.has("Z") || b.has("W") {
            m.lose_position(b.line, "a move under polar coordinate interpolation", false, true);
        }
    }
    Ok(true)
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
        Some(50.0) => {
            // Fanuc and Haas lathes' G50 X Z: the current point gets the given coordinates
            // (G50 S alone is the spindle speed clamp).
            for w in &b.words {
                match w.name {
                    "X" => m.x = Some(m.x_dia(w)),
                    "Z" => m.z = Some(m.len(w)),
                    "U" | "W" => m.lose_position(b.line, "G50 with U or W, a coordinate shift", true, true),
                    _ => {}
                }
            }
            m.skipped += 1;
            return Ok(());
        }
        Some(g) if (g == 70.0 || g == 71.0 || g == 72.0) && m.dialect == Dialect::Haas && !m.lathe() => {
            return bolt_pattern(m, b, modal, g);
        }
        Some(g) if (70.0..=75.0).contains(&g) && m.dialect != Dialect::Sinumerik => {
            // The turning, facing, pattern and grooving cycles: read past; each returns to its
            // start point (a profile's blocks that follow run as moves). A roughing cycle's
            // profile (G71/G72/G73 P… Q…) is what it cuts, in whatever motion its blocks are
            // written: they are kept as the turned contour.
            if matches!(g as u32, 71..=73) && m.lathe() {
                if let (Some(p), Some(q)) = (b.get("P"), b.get("Q")) {
                    m.profile = Some(Profile { first: p.v, last: q.v, on: false });
                }
            }
            m.read_past(
                b.line,
                modal.col.unwrap_or(b.col),
                &format!("G{g}"),
                "a turning or grooving cycle; it returns to its start point",
            );
            return Ok(());
        }
        Some(_) => {
            m.skipped += 1;
            return Ok(());
        }
        None => {}
    }
    if modal.motion.fract() == 0.0 && modal.motion >= 0.0 {
        match g_role(m.dialect, modal.motion as u32, m.lathe()) {
            GRole::BoxCycle => {
                if b.has("X") || b.has("Z") || b.has("U") || b.has("W") {
                    // G90 turns a cylinder (no R taper) at its X from the start point's Z to
                    // its Z; G94 faces and turns no diameter.
                    if modal.motion == 90.0 && !b.has("R") {
                        let (x, _, z) = m.target(b);
                        let xz = (x.or(m.box_last.map(|l| l.0)), z.or(m.box_last.map(|l| l.1)));
                        if let (Some(x), Some(z)) = xz {
                            m.record_box_cut(x, z, b.line);
                            m.box_last = Some((x, z));
                        }
                    }
                    m.read_past(
                        b.line,
                        modal.col.unwrap_or(b.col),
                        &format!("G{}", modal.motion),
                        "a turning or facing box cycle; it returns to its start point",
                    );
                } else {
                    m.skipped += 1;
                }
                return Ok(());
            }
            GRole::OtherCycle
                if !m.lathe()
                    && (m.dialect.fanuc_family()
                        || matches!(m.dialect, Dialect::Haas | Dialect::LinuxCnc)) =>
            {
                return mill_holes(m, b, modal);
            }
            GRole::OtherCycle => {
                let (x, y, z) = m.target(b);
                let what = format!("G{}", modal.motion);
                record_hole(m, b, modal, (x, y, z))?;
                if x.is_some() || z.is_some() || modal.col.is_some() {
                    // A drilling or tapping cycle along Z ends at its X (the face's cycles: a
                    // live tool's next hole is placed by C alone); the side's (G87, G88) do not.
                    let radial = matches!(modal.motion as u32, 87 | 88 | 195 | 196 | 241..=243);
                    let keep_x = x.or(m.x).filter(|_| !radial);
                    // A radial cycle ends at its Z (the next hole may be placed by C alone).
                    let keep_z = z.or(m.z).filter(|_| radial);
                    m.lose_position(b.line, &what, true, true);
                    if m.lathe() {
                        m.x = keep_x;
                        if radial {
                            m.z = keep_z;
                        }
                    }
                    m.read_past(
                        b.line,
                        modal.col.unwrap_or(b.col),
                        &what,
                        "a drilling or tapping cycle; where it leaves the tool is not modelled",
                    );
                } else {
                    m.skipped += 1;
                }
                return Ok(());
            }
            _ => {}
        }
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

/// The dialects read with Fanuc's codes (G-code system A on a lathe, the M-series' on a
/// machining centre): Fanuc's family and Haas.
fn fanuc_like(d: Dialect) -> bool {
    d.facts().fanuc_codes
}

/// Records a Fanuc or Haas drilling or tapping cycle's hole (one per block that gives a
/// position while the cycle is in force).
fn record_hole(
    m: &mut Motion,
    b: &RBlock<'_>,
    modal: &Modal,
    (x, y, z): (Option<f64>, Option<f64>, Option<f64>),
) -> Result<(), Error> {
    let fanuc_like = fanuc_like(m.dialect);
    let code = modal.motion as u32;
    let haas_lathe = m.dialect == Dialect::Haas && m.lathe();
    let kind = match code {
        74 | 84 => super::HoleKind::Tap,
        // A Haas lathe's G184 (left-hand tapping), G95 and G186 (live-tool rigid tapping along
        // Z, right- and left-hand; HAAS-L84).
        95 | 184 | 186 if haas_lathe => super::HoleKind::Tap,
        // Radial holes with a live tool, along X: Haas's G195/G196 tapping (right, left) and
        // G241–G243 drilling (HAAS-L84 names them), Fanuc's G88 tapping and G87 drilling from
        // the side (FT-BLOG's table).
        195 | 196 if haas_lathe => return record_radial_hole(m, b, modal, super::HoleKind::Tap, (x, z)),
        241..=243 if haas_lathe => return record_radial_hole(m, b, modal, super::HoleKind::Drill, (x, z)),
        88 if fanuc_like && m.lathe() => {
            return record_radial_hole(m, b, modal, super::HoleKind::Tap, (x, z))
        }
        87 if fanuc_like && m.lathe() => {
            return record_radial_hole(m, b, modal, super::HoleKind::Drill, (x, z))
        }
        73 | 81..=83 | 85..=89 => super::HoleKind::Drill,
        _ => return Ok(()),
    };
    let reads = fanuc_like || m.dialect == Dialect::LinuxCnc && kind == super::HoleKind::Drill;
    let c_word = b.get("C").is_some() && fanuc_like && m.lathe();
    if !reads || !(x.is_some() || y.is_some() || z.is_some() || modal.col.is_some() || c_word) {
        return Ok(());
    }
    let bottom = z.or(m.hole_modal.0);
    let (mut x, mut y) = (x.or(m.x), y.or(m.y));
    // A live tool on a lathe's face: X (a diameter) and the spindle's angle C place the hole
    // (FT-BLOG's G83/G84 with C; C0 along +X, a named default).
    if let (Some(c), true, Some(d)) = (m.c_axis, fanuc_like && m.lathe(), x) {
        let (s, co) = c.to_radians().sin_cos();
        let tidy = |v: f64| if v.abs() < 1e-9 { 0.0 } else { v };
        x = Some(tidy(0.5 * d * co));
        y = Some(tidy(0.5 * d * s));
        if !m.live_tool_said {
            m.live_tool_said = true;
            m.note(
                b.line,
                modal.col.unwrap_or(b.col),
                "a live tool on the face: each hole placed by X (a diameter) and C (the spindle's angle, C0 along +X), as X and Y on the face (a named default)",
            );
        }
    }
    push_hole_at(m, b, modal, kind, (x, y), bottom)
}

/// A radial hole on a lathe (a live tool along X): placed by the block's Z (else the current Z)
/// and C (else the last C), its bottom the block's X (a diameter; else the cycle's last), kept
/// as its radius. The words as the face cycles' with X and Z changing roles (FT-BLOG's G87 table;
/// Haas's G195 and G241 read so, a named reading said once).
fn record_radial_hole(
    m: &mut Motion,
    b: &RBlock<'_>,
    modal: &Modal,
    kind: super::HoleKind,
    (x, z): (Option<f64>, Option<f64>),
) -> Result<(), Error> {
    let col = modal.col.unwrap_or(b.col);
    let code = m.g_name(modal.motion as u32);
    if !(x.is_some() || z.is_some() || modal.col.is_some() || b.get("C").is_some()) {
        return Ok(());
    }
    let bottom = x.map(|d| 0.5 * d).or(m.radial_bottom);
    m.radial_bottom = bottom;
    let (Some(zp), Some(c)) = (z.or(m.z), m.c_axis) else {
        return Err(m.err(
            b.line,
            col,
            format!("{code} makes a radial hole with a live tool: its Z and C (the spindle's angle) place it, and {} not known here", if m.c_axis.is_none() { "C is" } else { "Z is" }),
        ));
    };
    if !m.radial_said {
        m.radial_said = true;
        m.note(
            b.line,
            col,
            "a live tool from the side: each hole placed by Z and C (the spindle's angle), its bottom by X (a diameter), its depth along X (a named reading: the face cycles' words with X and Z changing roles)",
        );
    }
    push_hole_at(m, b, modal, kind, (None, None), bottom)?;
    if let Some(h) = m.holes.last_mut() {
        h.radial = Some(super::RadialPlace { z: zp, c_deg: c });
        h.hand = match modal.motion as u32 {
            196 => Some(crate::standards::Hand::Left),
            195 | 88 => Some(crate::standards::Hand::Right),
            _ => h.hand,
        };
    }
    Ok(())
}

/// Haas's bolt-hole circle `G70 I J L` and arc `G71 I J K L` on a mill: L holes on a circle of
/// radius I about the current point (or the block's X Y), from J degrees counter-clockwise of
/// +X, every 360°/L (G70; L's sign the direction) or every K degrees (G71), each made by the
/// drilling or tapping cycle in force (YASNAC PCNC pp.4-33; helmancnc for G71; Haas inherits
/// the Yasnac format, a named reading); and the holes along an angle `G72 I J L`: L holes I apart
/// on a line at J degrees from +X through the current point (YASNAC p.4-35), the first at that
/// point (a named default, said: the pages read give the line, not whether its start is a hole).
fn bolt_pattern(m: &mut Motion, b: &RBlock<'_>, modal: &Modal, g: f64) -> Result<(), Error> {
    let col = modal.col.unwrap_or(b.col);
    let name = format!("G{g}");
    if !is_hole_cycle(m.motion) {
        return Err(m.err(
            b.line,
            col,
            format!("{name} places the holes of a drilling or tapping cycle, and none is in force"),
        ));
    }
    let need = |w: &str, what: &str| {
        b.get(w).map(|v| v.v).ok_or_else(|| m.err(b.line, col, format!("{name} needs {w}, {what}")))
    };
    let radius = need("I", if g == 72.0 { "the distance between holes" } else { "the circle's radius" })?;
    let start = need("J", if g == 72.0 { "the line's angle" } else { "the first hole's angle" })?;
    let count = need("L", "the number of holes")?;
    if count.fract() != 0.0 || count == 0.0 || count.abs() > 9999.0 {
        return Err(m.err(
            b.line,
            col,
            format!("{name} L{count}: the number of holes is a whole number from 1 to 9999"),
        ));
    }
    let step = match g as u32 {
        70 => 360.0 / count,
        71 => need("K", "the angle between holes")?,
        _ => 0.0,
    };
    let centre = |axis: &str, now: Option<f64>| {
        b.get(axis).map(|w| m.len(w) + if axis == "X" { m.offset[0] } else { m.offset[1] }).or(now)
    };
    let (Some(cx), Some(cy)) = (centre("X", m.x), centre("Y", m.y)) else {
        return Err(m.err(
            b.line,
            col,
            format!("{name}: the circle's centre (the current point) is not known here"),
        ));
    };
    let r = radius * m.scale;
    let kind = if matches!(m.motion as u32, 74 | 84) { super::HoleKind::Tap } else { super::HoleKind::Drill };
    let bottom = m.hole_modal.0;
    let mut last = (cx, cy);
    for i in 0..count.abs() as usize {
        last = if g == 72.0 {
            // Along the line: the first hole at the current point, each next I further.
            let a = start.to_radians();
            (cx + r * i as f64 * a.cos(), cy + r * i as f64 * a.sin())
        } else {
            let a = (start + step * i as f64).to_radians();
            (cx + r * a.cos(), cy + r * a.sin())
        };
        push_hole_at(m, b, modal, kind, (Some(last.0), Some(last.1)), bottom)?;
    }
    m.x = Some(last.0);
    m.y = Some(last.1);
    m.read_past(
        b.line,
        col,
        &name,
        if g == 72.0 {
            "holes along an angle: made by the cycle in force (threadcheck tap checks them), the first at the current point (a named default: the pages read give the line, not whether its start is a hole)"
        } else {
            "a bolt-hole pattern: its holes are made by the cycle in force (threadcheck tap checks them)"
        },
    );
    Ok(())
}

/// Whether `g` is a drilling, tapping or boring cycle's code.
fn is_hole_cycle(g: f64) -> bool {
    g.fract() == 0.0 && matches!(g as u32, 73 | 74 | 76 | 81..=89)
}

/// Records one hole of the cycle in force at `(x, y)` down to `bottom`, with the feed, spindle,
/// tool and rigid-tapping state in force.
fn push_hole_at(
    m: &mut Motion,
    b: &RBlock<'_>,
    modal: &Modal,
    kind: super::HoleKind,
    (x, y): (Option<f64>, Option<f64>),
    bottom: Option<f64>,
) -> Result<(), Error> {
    let code = modal.motion as u32;
    let feed = b.get("F").map(|w| m.len(w)).or(m.hole_modal.1);
    m.hole_modal = (bottom, feed);
    // Reported in the workpiece coordinates of the work offset: G68's rotation and G52's shift
    // applied (none on a lathe).
    let (x, y, bottom) = m.work_point(x, y, bottom);
    let rigid = std::mem::take(&mut m.rigid_next) || b.words.iter().any(|w| w.name == "M" && w.v == 29.0);
    let (feed_per_rev, assumed) = match m.feed_per_rev {
        Some(r) => (r, false),
        // A lathe's power-on state is feed per revolution (G99), a machining centre's per minute.
        None => (m.lathe() && m.plane != 17, true),
    };
    m.push_hole(super::HoleCycle {
        code: m.g_name(code),
        units: m.program_units(),
        kind,
        line: b.line,
        column: modal.col.unwrap_or(b.col),
        x,
        y,
        radial: None,
        bottom,
        feed,
        feed_word: "F".into(),
        hand: match code {
            84 => Some(crate::standards::Hand::Right),
            74 => Some(crate::standards::Hand::Left),
            95 if m.dialect == Dialect::Haas => Some(crate::standards::Hand::Right),
            184 | 186 if m.dialect == Dialect::Haas => Some(crate::standards::Hand::Left),
            _ => None,
        },
        feed_per_rev,
        feed_mode_assumed: assumed,
        spindle: m.s,
        spindle_dir: m.spindle_dir,
        tool: m.tool,
        // Set where it is recorded (Motion::push_hole).
        work_offset: None,
        source_file: None,
        main_line: 0,
        machine_xy: None,
        rigid,
        constant_surface_speed: m.css,
        r_level: None,
    })
}

/// A machining centre's drilling, tapping or boring cycle block (Fanuc, Haas, Mitsubishi,
/// Mazak, LinuxCNC; ../shared/notes/machining-centres.md §1.2, LinuxCNC's `convert_cycle_xy`):
/// in G90 X, Y, Z and R are positions; in G91 X and Y are increments from the current point, R
/// the distance from the initial level (Z where the cycle began) to the R level and Z the
/// distance from the R level to the bottom, each kept as written for the blocks that follow. K
/// (Fanuc; L on LinuxCNC and Haas too) repeats the hole, each time moved by the increment in
/// G91 (in place in G90, one hole). The tool returns to the initial level (G98) or the R level
/// (G99) and stays at the last hole. LinuxCNC's own rules: a block that writes only Z makes a
/// hole too; a tool below the R level rises to it first and G98 returns there; it refuses a
/// cycle whose first block lacks R or Z (or the P, Q a cycle needs), R below Z, L0, a cycle under
/// cutter compensation and any plane but G17 (threadcheck reads G17's).
fn mill_holes(m: &mut Motion, b: &RBlock<'_>, modal: &Modal) -> Result<(), Error> {
    let code = modal.motion as u32;
    let kind = match code {
        74 | 84 => super::HoleKind::Tap,
        // G76 fine-bores the hole: its size is the boring tool's, as a drill's is the drill's.
        73 | 76 | 81..=83 | 85..=89 => super::HoleKind::Drill,
        _ => return Ok(()),
    };
    let linuxcnc = m.dialect == Dialect::LinuxCnc;
    let col = modal.col.unwrap_or(b.col);
    let name = m.g_name(code);
    let at = |name: &str| b.get(name).map(|w| m.len(w));
    let (xw, yw, zw, rw) = (at("X"), at("Y"), at("Z"), at("R"));
    let polar = b.get("@").is_some() || b.get("^").is_some();
    let positioned =
        xw.is_some() || yw.is_some() || modal.col.is_some() || linuxcnc && (zw.is_some() || polar);
    if positioned && m.plane != 17 {
        // The control drills along the plane's normal (Y in G18, X in G19); threadcheck's holes
        // are along Z: a located refusal, not a hole misplaced.
        let axis = if m.plane == 18 { "Y" } else { "X" };
        return Err(m.err(b.line, col, format!("{name}: a canned cycle in the plane G{}, which drills along {axis}: threadcheck reads a machining centre's canned cycles in G17 (its drilling axis Z)", m.plane)));
    }
    if linuxcnc && positioned {
        let refuse = |why: String| Err(m.err(b.line, col, format!("{name}: {why}")));
        if m.comp != 0 {
            return refuse("LinuxCNC refuses canned cycles with cutter compensation on (G41/G42): cancel it with G40 first".into());
        }
        // The words the first block of a cycle must give (LinuxCNC's convert_cycle_xy).
        let first = m.cycle_in_force != Some(code);
        let mut need = vec![("R", "the R level"), ("Z", "the bottom")];
        match code {
            73 | 83 => need.push(("Q", "the peck depth")),
            82 | 86 | 88 | 89 => need.push(("P", "the dwell")),
            87 => need.extend([
                ("I", "the offset in X"),
                ("J", "the offset in Y"),
                ("K", "the back bore's top"),
            ]),
            _ => {}
        }
        if first {
            if let Some((w, what)) = need.iter().find(|(w, _)| b.get(w).is_none()) {
                return refuse(format!("the first block of a canned cycle gives {w} ({what}), and LinuxCNC refuses one without it"));
            }
        }
        if let Some(q) = b.get("Q").filter(|q| matches!(code, 73 | 83) && q.v <= 0.0) {
            return Err(b.werr(
                &m.file,
                q,
                format!("{name} Q{}: the peck depth must be over zero (LinuxCNC refuses it)", q.v),
            ));
        }
        if let Some(l) = b.get("L").filter(|l| l.v == 0.0) {
            return Err(b.werr(&m.file, l, "L0: LinuxCNC cannot do zero repeats of a canned cycle"));
        }
        // LinuxCNC's word check (check_other_codes) lists the cycles that take L, and G74 is not
        // among them in the interpreter tested here (Debian 12's 2.9.0~pre1).
        if let Some(l) = b.get("L").filter(|_| code == 74) {
            return Err(b.werr(&m.file, l, "L with G74: LinuxCNC refuses it (\"L word with no G10, cutter compensation, canned cycle, digital/analog input, M98 or NURBS code\"): G74 does not repeat"));
        }
    }
    if m.cycle_levels.0.is_none() {
        m.cycle_levels.0 = m.z;
    }
    let initial = m.cycle_levels.0;
    // R and Z as written, kept for the blocks that leave them out.
    if rw.is_some() {
        m.cycle_words.0 = rw;
    }
    if zw.is_some() {
        m.cycle_words.1 = zw;
    }
    let r_level = match (m.cycle_words.0, m.absolute) {
        (Some(r), true) => Some(r + m.offset[2]),
        (Some(r), false) => initial.map(|i| i + r),
        (None, _) => m.cycle_levels.1,
    };
    m.cycle_levels.1 = r_level;
    let bottom = match (m.cycle_words.1, m.absolute) {
        (Some(z), true) => Some(z + m.offset[2]),
        (Some(z), false) => r_level.map(|r| r + z),
        (None, _) => m.hole_modal.0,
    };
    let repeat_word = if linuxcnc { b.get("L") } else { b.get("K").or_else(|| b.get("L")) };
    let repeats = match repeat_word {
        None => 1,
        Some(w) if w.v >= 0.0 && w.v.fract() == 0.0 && w.v <= 9999.0 => w.v as usize,
        Some(w) => {
            return Err(m.err(
                b.line,
                w.col,
                format!("{}{}: a cycle's repeat count is a whole number from 0 to 9999", w.name, w.v),
            ))
        }
    };
    if !positioned {
        m.skipped += 1;
        return Ok(());
    }
    if linuxcnc {
        if let (Some(r), Some(z)) = (r_level, bottom) {
            if r < z {
                return Err(m.err(
                    b.line,
                    col,
                    format!(
                        "{name}: the R level Z{} lies below the bottom Z{} (LinuxCNC refuses R less than Z)",
                        crate::ground::fmt::fmt_num(r / m.scale),
                        crate::ground::fmt::fmt_num(z / m.scale)
                    ),
                ));
            }
        }
    }
    let (dx, dy) = (xw.unwrap_or(0.0), yw.unwrap_or(0.0));
    let (mut x, mut y) = (m.x, m.y);
    if m.absolute {
        // The block's target, as every move reads it (G16's radius and angle included).
        let (tx, ty, _) = m.target(b);
        x = tx.or(x);
        y = ty.or(y);
    }
    let holes = if m.absolute { repeats.min(1) } else { repeats };
    for _ in 0..holes {
        if !m.absolute {
            x = x.map(|v| v + dx);
            y = y.map(|v| v + dy);
        }
        push_hole_at(m, b, modal, kind, (x, y), bottom)?;
        if let Some(h) = m.holes.last_mut() {
            h.r_level = r_level;
        }
    }
    if repeats == 0 {
        // K0: the cycle is stored for the positions that follow (Haas's L0 at a bolt pattern's
        // centre).
        m.hole_modal.0 = bottom;
    }
    m.cycle_in_force = Some(code);
    m.x = x;
    m.y = y;
    // LinuxCNC: a tool below the R level rises to it first, and G98 returns there.
    let clear = match (initial, r_level) {
        (Some(i), Some(r)) if linuxcnc && i < r => Some(r),
        _ => initial,
    };
    m.z = if m.return_to_r { r_level } else { clear };
    m.read_as_holes(
        b.line,
        col,
        &format!("G{}", modal.motion),
        "a drilling, tapping or boring cycle, read as its holes (the tapping check of verify and tap takes them; no turning pass); the tool ends at the return level",
    );
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
            let infeed = crate::toolpath::passes::Infeed::Alternating { angle: a };
            crate::toolpath::passes::infeed_offsets(infeed, depths, dir)
        }
    }
}

/// `v` is a whole number from `lo` to `hi` (a count or code word of a cycle).
pub(crate) fn whole_in(v: f64, lo: f64, hi: f64) -> bool {
    v >= lo && v <= hi && v.fract() == 0.0
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
