//! LinuxCNC: `G33 X Z K` (K the distance per revolution along the programmed line) and
//! `G76 P Z I J K [R] [Q] [H] [E] [L]` exactly as LinuxCNC's interpreter lays it out
//! (`convert_threading_cycle`): pass n at J·n^(1/R) beyond the crest while below K, one pass at
//! K and H spring passes; each pass starts depth·tan Q further along the drive line and its
//! synchronised stretch ends (K − depth)·tan Q beyond Z; with L2 (L3) an exit (entry) taper over
//! E ramps out to (K − depth) above the crest. G7/G8, G92 offsets, `#<_x>`, `#<_z>`,
//! `#<_imperial>`, `#<_metric>`.

use super::cycles;
use super::dialect::{Ctx, Flow, Rules, SysParams};
use super::motion::{Motion, RBlock};
use crate::Error;

/// One offset along X (diameter), Y and Z, mm. An offset set from a position threadcheck does
/// not know is a number relative to an arbitrary frame: `var` names that unknown (0 for none),
/// so that a change of the total offset is known exactly when its unknowns cancel.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Offset {
    v: [f64; 3],
    var: [u32; 3],
    /// The XY plane's rotation about the offset's origin, degrees counter-clockwise (G10 L2 R;
    /// a coordinate system's, LinuxCNC's #5210 + 20·k; 0 for the G92 offset).
    rot: f64,
}

/// LinuxCNC's coordinate systems and spindle, beyond the shared motion state.
#[derive(Default)]
pub(crate) struct State {
    /// The work offsets of G54…G59.3 (index 1–9; LinuxCNC's #5221…#5389), zero at the start
    /// as in LinuxCNC's standalone interpreter without a parameter file.
    g5x: [Offset; 10],
    /// The coordinate system in force less one (0 = G54, … 8 = G59.3; #5220 is this plus 1).
    system0: usize,
    /// The G92 (or G52) offset in force, and the stored one G92.3 restores (#5211–#5213).
    g92: Offset,
    g92_stored: Offset,
    /// The last unknown named.
    vars: u32,
    /// An X offset change was noted.
    x_noted: bool,
    /// The last X (radius) and Z in program units as LinuxCNC keeps them, each with the
    /// position in mm, the offset and the units it was set under: `#<_x>` and `#<_z>` are these
    /// while the three still hold (mm do not always divide back to the number written).
    written: [Option<Written>; 2],
    /// The spindle turns (M3, M4): LinuxCNC refuses G33 and G76 with it stopped; M5, M19 and a
    /// tool change (M6) stop it.
    spindle_on: bool,
    /// The tool in the spindle: the one selected at the last M6 (`#<_current_tool>`, #5400).
    current_tool: u32,
    /// The motion mode in force, as `#<_motion_mode>` gives it (G-code × 10; G80, 800, at the
    /// start, as in LinuxCNC).
    motion_mode: Option<f64>,
    /// The switches and modes LinuxCNC's predefined parameters read, as the program set them
    /// (`None`: the standalone interpreter's state at the start, which `Switches::start` gives).
    switches: Option<Switches>,
}

/// What `#<_feed>`, `#<_mist>`, `#<_flood>`, the override and feed-hold switches, the
/// inverse-time mode, the return level and the arc-centre mode read.
#[derive(Clone, Copy, Debug)]
struct Switches {
    feed: f64,
    mist: bool,
    flood: bool,
    /// M51 (and M48/M49): the spindle speed override.
    speed_override: bool,
    /// M50 (and M48/M49): the feed override.
    feed_override: bool,
    adaptive_feed: bool,
    feed_hold: bool,
    inverse_time: bool,
    /// G99 (return to the R plane) against G98.
    r_plane: bool,
    ijk_absolute: bool,
}

impl Switches {
    /// LinuxCNC's standalone interpreter at the start (`rs274`, no INI startup code): F0, the
    /// coolant off, both overrides and the feed hold enabled, G99's return level, incremental
    /// arc centres.
    fn start() -> Switches {
        Switches {
            feed: 0.0,
            mist: false,
            flood: false,
            speed_override: true,
            feed_override: true,
            adaptive_feed: false,
            feed_hold: true,
            inverse_time: false,
            r_plane: true,
            ijk_absolute: false,
        }
    }

    /// What block `b` sets.
    fn after(mut self, b: &RBlock<'_>) -> Switches {
        let p_on = || b.get("P").is_none_or(|p| p.v != 0.0);
        if let Some(f) = b.get("F") {
            self.feed = f.v;
        }
        if b.has_m(7.0) {
            self.mist = true;
        }
        if b.has_m(8.0) {
            self.flood = true;
        }
        if b.has_m(9.0) {
            (self.mist, self.flood) = (false, false);
        }
        if b.has_m(48.0) {
            (self.speed_override, self.feed_override) = (true, true);
        }
        if b.has_m(49.0) {
            (self.speed_override, self.feed_override) = (false, false);
        }
        if b.has_m(50.0) {
            self.feed_override = p_on();
        }
        if b.has_m(51.0) {
            self.speed_override = p_on();
        }
        if b.has_m(52.0) {
            self.adaptive_feed = p_on();
        }
        if b.has_m(53.0) {
            self.feed_hold = p_on();
        }
        for (g, _) in b.gs() {
            match (g * 10.0).round() as i64 {
                930 => self.inverse_time = true,
                940 | 950 => self.inverse_time = false,
                980 => self.r_plane = false,
                990 => self.r_plane = true,
                901 => self.ijk_absolute = true,
                911 => self.ijk_absolute = false,
                _ => {}
            }
        }
        self
    }
}

/// A coordinate in program units and what it was set under.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Written {
    /// X as a radius, or Z, in program units.
    value: f64,
    /// The position in mm (X a diameter), the offset and the units scale it was set under.
    mm: f64,
    offset: f64,
    scale: f64,
}

impl State {
    /// The coordinate of axis `k` (0 X, 1 Z) in program units, if the motion state still
    /// stands where it was written.
    fn written(&self, m: &Motion, k: usize) -> Option<f64> {
        let w = self.written[k]?;
        let (pos, off) = if k == 0 { (m.x, m.offset[0]) } else { (m.z, m.offset[2]) };
        (pos == Some(w.mm) && off == w.offset && m.scale == w.scale).then_some(w.value)
    }

    /// Remembers the block's X and Z words as LinuxCNC's current point: absolute words as
    /// written (X halved under G7), incremental ones added to the coordinate before.
    fn remember(&mut self, m: &Motion, b: &RBlock<'_>, before: [Option<f64>; 2]) {
        for (k, name) in ["X", "Z"].iter().enumerate() {
            let (pos, off) = if k == 0 { (m.x, m.offset[0]) } else { (m.z, m.offset[2]) };
            let Some(mm) = pos else {
                self.written[k] = None;
                continue;
            };
            match b.get(name) {
                Some(w) => {
                    let v = if k == 0 && m.diameter { w.v / 2.0 } else { w.v };
                    let value = if m.absolute { Some(v) } else { before[k].map(|p| p + v) };
                    self.written[k] = value.map(|value| Written { value, mm, offset: off, scale: m.scale });
                }
                None => {
                    // Unchanged, or moved by something else (a cycle's end, an offset).
                    if self.written[k].is_some_and(|w| w.mm != mm || w.offset != off) {
                        self.written[k] = None;
                    }
                }
            }
        }
    }
}

/// The coordinate system a G code selects (G54 … G59, G59.1 … G59.3 are 1 … 9).
fn system_of(g: f64) -> Option<usize> {
    match g {
        54.0..=59.0 if g.fract() == 0.0 => Some(g as usize - 53),
        59.1 => Some(7),
        59.2 => Some(8),
        59.3 => Some(9),
        _ => None,
    }
}

impl State {
    fn system(&self) -> usize {
        self.system0 + 1
    }

    /// A new unknown.
    fn unknown(&mut self) -> u32 {
        self.vars += 1;
        self.vars
    }

    /// The unknowns of the total offset on each axis, in order.
    fn unknowns(&self) -> [[u32; 2]; 3] {
        let (w, g) = (self.g5x[self.system()], self.g92);
        [0, 1, 2].map(|a| {
            let mut u = [w.var[a], g.var[a]];
            u.sort_unstable();
            u
        })
    }

    /// Sets the motion's offset to the work offset plus the G92 offset; where the change of
    /// the total holds an unknown (`before` are the unknowns before it), the frame is lost
    /// (`what` at `line` did it).
    fn apply(&mut self, m: &mut Motion, before: [[u32; 2]; 3], line: usize, what: &str) {
        let (w, g) = (self.g5x[self.system()], self.g92);
        // The position is kept unrotated (the program's point plus both offsets); a rotation
        // turns it about the work offset's origin, as LinuxCNC's canon does (the G92 offset
        // added, rotated, the G5x offset added). Where the rotation or its centre changes, the
        // point the machine stands at stays.
        let now = m.rotation.map(|(cx, cy, deg)| ([cx, cy], deg));
        let next = (w.rot != 0.0 && !m.lathe()).then_some(([w.v[0], w.v[1]], w.rot));
        if now != next {
            if let (Some(x), Some(y)) = (m.x, m.y) {
                let turn = |p: [f64; 2], c: [f64; 2], deg: f64| {
                    let (s, co) = deg.to_radians().sin_cos();
                    let (dx, dy) = (p[0] - c[0], p[1] - c[1]);
                    [c[0] + co * dx - s * dy, c[1] + s * dx + co * dy]
                };
                let at = now.map_or([x, y], |(c, deg)| turn([x, y], c, deg));
                let u = next.map_or(at, |(c, deg)| turn(at, c, -deg));
                m.x = Some(u[0]);
                m.y = Some(u[1]);
            }
            m.rotation = next.map(|(c, deg)| (c[0], c[1], deg));
        }
        let after = self.unknowns();
        let dx = w.v[0] + g.v[0] - m.offset[0];
        if dx.abs() > 1e-9 && !self.x_noted {
            self.x_noted = true;
            m.note(
                line,
                1,
                format!(
                    "{what} moves X0 by Ø{}: threadcheck measures diameters from the X0 the program starts with (a lathe's X offsets keep X0 on the spindle axis; assumed)",
                    crate::ground::fmt::fmt_num(dx)
                ),
            );
        }
        for a in 0..3 {
            m.offset[a] = w.v[a] + g.v[a];
            if before[a] != after[a] {
                m.lose_frame(line, what);
            }
        }
    }
}

/// The read-only system parameters, from the motion state, before each block, each set once
/// and always in the same order.
/// LinuxCNC's read-only parameters threadcheck keeps, in their slots' order.
/// The rest are the modes the motion state holds, as LinuxCNC's documentation of its predefined
/// named parameters gives them (`docs/src/gcode/overview.adoc`, "Predefined Named Parameters";
/// issue 47): `_lathe_radius_mode` and `_lathe_diameter_mode` 1 or 0, `_coord_system` 540 … 593,
/// `_plane` 170, 180 or 190, `_spindle_on`, `_spindle_cw`, `_spindle_css_mode`,
/// `_spindle_rpm_mode`, `_units_per_rev`, `_units_per_minute` 1 or 0, `_rpm` S, `_current_tool` T.
const SYSTEM_NAMES: [&str; 45] = [
    "_x",
    "_z",
    "_imperial",
    "_metric",
    "_absolute",
    "_incremental",
    "_lathe_radius_mode",
    "_lathe_diameter_mode",
    "_coord_system",
    "_plane",
    "_spindle_on",
    "_spindle_cw",
    "_spindle_css_mode",
    "_spindle_rpm_mode",
    "_units_per_rev",
    "_units_per_minute",
    "_rpm",
    "_current_tool",
    "_selected_tool",
    "_motion_mode",
    "_ccomp",
    "_y",
    "_a",
    "_b",
    "_c",
    "_u",
    "_v",
    "_w",
    "_call_level",
    "_remap_level",
    "_line",
    "_feed",
    "_mist",
    "_flood",
    "_speed_override",
    "_feed_override",
    "_adaptive_feed",
    "_feed_hold",
    "_inverse_time",
    "_retract_r_plane",
    "_retract_old_z",
    "_ijk_absolute_mode",
    "_abs_x",
    "_abs_z",
    "_abs_y",
];

fn system_params(s: &State, m: &Motion, sys: &mut SysParams) {
    let unit = m.scale;
    if let Some(x) = m.x {
        // In program units and as a radius, whatever the diameter mode (LinuxCNC's #5420): the
        // number written while the point stands where it was written; else the X word as it
        // would be written (a diameter under G7), halved under G7.
        let x = s.written(m, 0).unwrap_or_else(|| {
            let off = m.offset[0];
            let (per, dia) = if m.diameter { (1.0, true) } else { (2.0, false) };
            let p = as_written(x, (x - off) / unit / per, |p| {
                (if dia { p * unit } else { 2.0 * (p * unit) }) + off
            });
            if dia {
                0.5 * p
            } else {
                p
            }
        });
        sys.set(0, x);
    }
    if let Some(z) = m.z {
        let off = m.offset[2];
        let z = s.written(m, 1).unwrap_or_else(|| as_written(z, (z - off) / unit, |p| p * unit + off));
        sys.set(1, z);
    }
    let imperial = if m.scale == 1.0 { 0.0 } else { 1.0 };
    sys.set(2, imperial);
    sys.set(3, 1.0 - imperial);
    sys.set(4, if m.absolute { 1.0 } else { 0.0 });
    sys.set(5, if m.absolute { 0.0 } else { 1.0 });
    let flag = |b: bool| if b { 1.0 } else { 0.0 };
    sys.set(6, flag(!m.diameter));
    sys.set(7, flag(m.diameter));
    // G54 is 540, …, G59 590, G59.1 591, G59.2 592, G59.3 593.
    let system = match s.system0 {
        k @ 0..=5 => 540.0 + 10.0 * k as f64,
        k => 585.0 + k as f64,
    };
    sys.set(8, system);
    sys.set(9, f64::from(m.plane) * 10.0);
    let on = matches!(m.spindle_dir, Some(super::SpindleDir::Cw | super::SpindleDir::Ccw));
    sys.set(10, flag(on));
    sys.set(11, flag(m.spindle_dir == Some(super::SpindleDir::Cw)));
    sys.set(12, flag(m.css));
    sys.set(13, flag(!m.css));
    let per_rev = m.feed_per_rev.unwrap_or(false);
    sys.set(14, flag(per_rev));
    sys.set(15, flag(!per_rev));
    if let Some(rpm) = m.s {
        sys.set(16, rpm);
    }
    // The tool in the spindle (last M6) and the one selected (last T), 0 before any.
    sys.set(17, f64::from(s.current_tool));
    sys.set(18, f64::from(m.tool.unwrap_or(0)));
    sys.set(19, s.motion_mode.unwrap_or(800.0));
    // G40, G41, G42: 400, 410, 420.
    sys.set(20, 400.0 + 10.0 * f64::from(m.comp));
    // A lathe program's Y and the rotary and U V W axes: where it put Y, else 0.
    sys.set(21, m.y.map_or(0.0, |y| (y - m.offset[1]) / unit));
    for k in 22..=27 {
        sys.set(k, 0.0);
    }
    // The subroutine depth (28) and the line (30) are the interpreter's (interp.rs); no remap.
    sys.set(29, 0.0);
    let sw = s.switches.unwrap_or_else(Switches::start);
    sys.set(31, sw.feed);
    for (k, on) in [
        (32, sw.mist),
        (33, sw.flood),
        (34, sw.speed_override),
        (35, sw.feed_override),
        (36, sw.adaptive_feed),
        (37, sw.feed_hold),
        (38, sw.inverse_time),
        (39, sw.r_plane),
        (40, !sw.r_plane),
        (41, sw.ijk_absolute),
    ] {
        sys.set(k, flag(on));
    }
    // G93 is neither per minute nor per revolution.
    if sw.inverse_time {
        sys.set(14, 0.0);
        sys.set(15, 0.0);
    }
    // The position with no offsets, in program units, X as a radius whatever the mode.
    sys.set(42, m.x.map_or(0.0, |x| 0.5 * x / unit));
    sys.set(43, m.z.map_or(0.0, |z| z / unit));
    sys.set(44, m.y.map_or(0.0, |y| y / unit));
    // The numbered parameters the docs list that follow the program's state (LinuxCNC's
    // docs/src/gcode/overview.adoc, "Numbered Parameters"): #5220 the coordinate system (1 =
    // G54 … 9 = G59.3), #5400 the tool number, #5420–#5428 the current position in program
    // units (X as #<_x>, Z as #<_z>; Y and the rotary and U V W axes 0 on a lathe).
    sys.set_numbered(5220, s.system0 as f64 + 1.0);
    sys.set_numbered(5400, f64::from(s.current_tool));
    for (k, slot) in [(5420, Some(0)), (5421, None), (5422, Some(1))] {
        let v = slot.and_then(|k| sys.get(SYSTEM_NAMES[k])).unwrap_or(0.0);
        sys.set_numbered(k, v);
    }
    for k in 5423..=5428 {
        sys.set_numbered(k, 0.0);
    }
}

/// The program value whose position (mm) the reader computed as `fwd(value)` to be `mm`: the
/// unscaled `guess` or a neighbouring double. LinuxCNC keeps positions in program units, and
/// an inch value times 25.4 does not always divide back to itself; a parameter such as
/// `#<_x>` must be the number the program wrote, or a MOD after it can jump.
fn as_written(mm: f64, guess: f64, fwd: impl Fn(f64) -> f64) -> f64 {
    if fwd(guess) == mm || guess == 0.0 || !guess.is_finite() {
        return guess;
    }
    let bits = guess.to_bits();
    for d in [1u64, 2] {
        for c in [f64::from_bits(bits + d), f64::from_bits(bits - d)] {
            if fwd(c) == mm {
                return c;
            }
        }
    }
    guess
}

/// M6, then M3/M4/M5/M19, in LinuxCNC's order of execution within a block.
fn spindle(s: &mut State, b: &RBlock<'_>) {
    if b.has_m(6.0) {
        s.spindle_on = false;
    }
    if b.has_m(3.0) || b.has_m(4.0) {
        s.spindle_on = true;
    }
    if b.has_m(5.0) || b.has_m(19.0) {
        s.spindle_on = false;
    }
}

/// The machine position along axis `a` (X diameter, Y, Z), mm.
fn pos(m: &Motion, a: usize) -> Option<f64> {
    [m.x, m.y, m.z][a]
}

fn set_pos(m: &mut Motion, a: usize, v: f64) {
    match a {
        0 => m.x = Some(v),
        1 => m.y = Some(v),
        _ => m.z = Some(v),
    }
}

/// The block's X, Y, Z words as offsets in mm (X as a diameter).
fn axis_words(m: &Motion, b: &RBlock<'_>) -> [Option<f64>; 3] {
    [b.get("X").map(|w| m.x_dia(w)), b.get("Y").map(|w| m.len(w)), b.get("Z").map(|w| m.len(w))]
}

/// Applies the block's coordinate-system codes in LinuxCNC's order of execution (the system
/// selection, then G10, G52 and the G92 series); true when the block is one of those data
/// blocks and has no move of its own.
fn coordinates(s: &mut State, m: &mut Motion, b: &RBlock<'_>, md: &cycles::Modal) -> Result<bool, Error> {
    if let Some((sys, g)) = b.gs().find_map(|(g, _)| system_of(g).map(|k| (k, g))) {
        if sys != s.system() {
            let before = s.unknowns();
            s.system0 = sys - 1;
            // The machine position stays; the program coordinates move into the new system.
            s.apply(m, before, b.line, &format!("G{g}"));
        }
    }
    let Some(g) = md.one_shot else { return Ok(false) };
    let col = b.gs().find(|(c, _)| *c == g).map_or(b.col, |x| x.1);
    let words = axis_words(m, b);
    let before = s.unknowns();
    match g {
        10.0 => {
            let l = b.get("L").map(|w| w.v);
            let (Some(l @ (2.0 | 20.0)), Some(p)) = (l, b.get("P")) else {
                // G10 L1, L10, L11 (the tool table) and the rest: no coordinate system changes.
                m.read_past(
                    b.line,
                    col,
                    "G10",
                    "tool-table data (only G10 L2 and L20 change coordinates here)",
                );
                m.skipped += 1;
                return Ok(true);
            };
            let k = (p.v + 0.0001) as usize;
            if !(p.v > -0.5 && k <= 9) {
                return Err(b.werr(
                    &m.file,
                    p,
                    "G10 P must be a coordinate system 0 to 9 (0 the one in force)",
                ));
            }
            let k = if k == 0 { s.system() } else { k };
            let active = k == s.system();
            if let Some(r) = b.get("R") {
                // The XY plane's rotation about the system's origin (applied to the holes'
                // places; a lathe's passes in XZ do not turn with it).
                if m.lathe() {
                    if r.v != 0.0 {
                        m.lose_position(b.line, "G10 with R, a rotation of the XY plane", true, true);
                        m.lose_frame(b.line, "G10 with R, a rotation of the XY plane");
                        m.read_past(b.line, col, "G10 R", "a rotation of the XY plane, not modelled on a lathe (its X would turn out of the XZ plane)");
                    }
                } else {
                    s.g5x[k].rot = r.v;
                }
            }
            for (a, v) in words.iter().enumerate() {
                let Some(v) = *v else { continue };
                let fresh = s.unknown();
                let o = &mut s.g5x[k];
                if l == 2.0 {
                    o.v[a] = v;
                    o.var[a] = 0;
                } else if let Some(p) = pos(m, a) {
                    // L20: the current point gets the given coordinates in system k.
                    o.v[a] = p - s.g92.v[a] - v;
                    o.var[a] = if s.g92.var[a] == 0 { 0 } else { fresh };
                } else {
                    // From a position threadcheck does not know: the point gets its
                    // coordinates, the offset is relative to an arbitrary frame.
                    if active {
                        set_pos(m, a, v + m.offset[a]);
                        o.v[a] = m.offset[a] - s.g92.v[a];
                    }
                    o.var[a] = fresh;
                }
            }
        }
        52.0 | 92.0 => {
            for (a, v) in words.iter().enumerate() {
                let Some(v) = *v else { continue };
                let fresh = s.unknown();
                let w = s.g5x[s.system()];
                if g == 52.0 {
                    // G52: the offset itself.
                    s.g92.v[a] = v;
                    s.g92.var[a] = 0;
                } else if let Some(p) = pos(m, a) {
                    // G92: the current point gets the given coordinates.
                    s.g92.v[a] = p - w.v[a] - v;
                    s.g92.var[a] = if w.var[a] == 0 { 0 } else { fresh };
                } else {
                    set_pos(m, a, v + m.offset[a]);
                    s.g92.v[a] = m.offset[a] - w.v[a];
                    s.g92.var[a] = fresh;
                }
            }
            s.g92_stored = s.g92;
        }
        92.1 | 92.2 => {
            s.g92 = Offset::default();
            if g == 92.1 {
                s.g92_stored = Offset::default();
            }
        }
        92.3 => s.g92 = s.g92_stored,
        _ => return Ok(false),
    }
    s.apply(m, before, b.line, &format!("G{g}"));
    m.break_chain();
    m.skipped += 1;
    Ok(true)
}

/// Runs one block.
fn block(s: &mut State, m: &mut Motion, b: &RBlock<'_>, _cx: &mut Ctx<'_>) -> Result<Flow, Error> {
    // G7/G8 with G76 in one block scale I, J, K twice in LinuxCNC (read the interpreter's
    // convert_lathe_diameter_mode and convert_threading_cycle); separate lines are right.
    let mode_and_g76 = b.gs().any(|(g, _)| g == 76.0) && b.gs().any(|(g, _)| g == 7.0 || g == 8.0);
    let md = cycles::modal(m, b)?;
    if b.has_m(6.0) {
        s.current_tool = m.tool.unwrap_or(0);
    }
    // The modal motion group (G0–G3, G33, G33.1, G38.n, G73, G76, G80–G89).
    if let Some((g, _)) = b
        .gs()
        .filter(|(g, _)| {
            matches!(*g as u32, 0..=3 | 33 | 38 | 73 | 76 | 80..=89)
                && (g.fract() == 0.0 || matches!(*g as u32, 33 | 38))
        })
        .last()
    {
        s.motion_mode = Some((g * 10.0).round());
    }
    s.switches = Some(s.switches.unwrap_or_else(Switches::start).after(b));
    spindle(s, b);
    spindle_for_cycle(s, m, b, &md)?;
    tapping_words(m, b, &md);
    polar_words(m, b, &md)?;
    if coordinates(s, m, b, &md)? {
        return Ok(Flow::Next);
    }
    if b.has_m(2.0) || b.has_m(30.0) {
        return Ok(Flow::End);
    }
    let threading = md.motion == 76.0 && md.col.is_some() || md.motion == 33.0 && (b.has("X") || b.has("Z"));
    if threading && !s.spindle_on && md.one_shot.is_none() {
        let col = md.col.unwrap_or(b.col);
        return Err(m.err(
            b.line,
            col,
            format!(
                "G{} with the spindle stopped: LinuxCNC refuses it (start the spindle with M3 or M4 first; M5, M19 and a tool change M6 stop it)",
                md.motion
            ),
        ));
    }
    if md.one_shot.is_some() {
        cycles::other_block(m, b, &md)?;
        return Ok(Flow::Next);
    }
    let comp = m.comp.max(m.nose_comp);
    if threading && comp != 0 {
        // LinuxCNC's interpreter refuses a threading move under cutter compensation (its
        // convert_straight_comp1/comp2 take G0 and G1 only): said, and read on.
        let col = md.col.unwrap_or(b.col);
        let code = format!("G{}", md.motion);
        m.flag(
            super::ControlRule::SyncUnderCompensation,
            &code,
            b.line,
            col,
            format!("{code} with cutter radius compensation G4{comp} in force"),
        );
    }
    match md.motion as u32 {
        76 if md.col.is_some() => {
            let col = md.col.unwrap_or(b.col);
            if mode_and_g76 {
                return Err(m.err(
                    b.line,
                    col,
                    "G7/G8 and G76 in one block: LinuxCNC scales I, J and K twice there; put G7 or G8 on a line of its own",
                ));
            }
            g76(m, b, col)?;
        }
        33 => {
            let col = md.col.unwrap_or(b.col);
            let (x, _, z) = m.target(b);
            if x.is_none() && z.is_none() {
                m.skipped += 1;
                return Ok(Flow::Next);
            }
            cycles::need_lathe_plane(m, b, col, "G33")?;
            b.allow_only(&m.file, "GXZKNMS", "G33")?;
            let k =
                b.get("K").ok_or_else(|| m.err(b.line, col, "G33 without K, the distance per revolution"))?;
            let kv = m.len(k);
            if !(kv > 0.0) {
                return Err(b.werr(&m.file, k, "G33 K must be greater than zero"));
            }
            // K runs along the programmed line: its Z component is the axial lead.
            m.thread_move(b, col, "G33", |dx, dz| kv * dz.abs() / dx.hypot(dz), 0.0)?;
        }
        _ => cycles::other_block(m, b, &md)?,
    }
    Ok(Flow::Next)
}

/// The words LinuxCNC refuses on a tapping block, said and read on: a peck depth `Q` (LinuxCNC
/// has no peck tapping: G84, G74 and G33.1 take no Q) and an `F` on G33.1 (its feed is K).
fn tapping_words(m: &mut Motion, b: &RBlock<'_>, md: &cycles::Modal) {
    let moves = b.has("X") || b.has("Y") || b.has("Z");
    let code = match md.one_shot {
        Some(33.1) => "G33.1",
        _ if !moves || md.motion.fract() != 0.0 => return,
        _ => match md.motion as u32 {
            74 => "G74",
            84 => "G84",
            _ => return,
        },
    };
    if let Some(q) = b.get("Q") {
        let detail = format!("{code} with {}: LinuxCNC has no peck tapping", q.text);
        m.flag(super::ControlRule::TapPeckQ, code, b.line, q.col, detail);
    }
    if let (Some(f), "G33.1") = (b.get("F"), code) {
        let detail = format!("G33.1 with {}: its feed per revolution is K", f.text);
        m.flag(super::ControlRule::FeedWordInSync, code, b.line, f.col, detail);
    }
}

/// LinuxCNC's polar words `@` and `^` where threadcheck reads them: in the XY plane of a
/// machining centre, without X or Y in the same block (LinuxCNC refuses the mix), and in a
/// canned cycle only in G90 (its G91 polar increments per repeat are not read).
fn polar_words(m: &Motion, b: &RBlock<'_>, md: &cycles::Modal) -> Result<(), Error> {
    let Some(w) = b.words.iter().find(|w| w.name == "@" || w.name == "^") else { return Ok(()) };
    let refuse = |why: &str| Err(m.err(b.line, w.col, format!("{}: {why}", w.name)));
    if m.lathe() || m.plane != 17 {
        return refuse("polar coordinates are read in the XY plane of a machining centre (G17)");
    }
    if b.has("X") || b.has("Y") {
        return refuse("polar coordinates with X or Y in the same block: LinuxCNC refuses the mix");
    }
    let cycle = md.motion.fract() == 0.0 && matches!(md.motion as u32, 73 | 74 | 81..=89);
    if cycle && !m.absolute {
        return refuse("a canned cycle's polar increments in G91 are not read: write the positions in G90");
    }
    Ok(())
}

/// The spindle a cycle needs, as LinuxCNC refuses it (its `convert_cycle_g74_g84`, `g86`–`g88`
/// and `convert_straight` for G33.1): turning for G33.1 and G86–G88, clockwise for G84 and
/// counter-clockwise for G74, each in LinuxCNC's own words.
fn spindle_for_cycle(s: &State, m: &Motion, b: &RBlock<'_>, md: &cycles::Modal) -> Result<(), Error> {
    let moves = b.has("X") || b.has("Y") || b.has("Z");
    let code = match md.one_shot {
        Some(33.1) => "G33.1",
        _ if !moves || m.lathe() => return Ok(()),
        _ => match md.motion as u32 {
            _ if md.motion.fract() != 0.0 => return Ok(()),
            74 => "G74",
            84 => "G84",
            86 => "G86",
            87 => "G87",
            88 => "G88",
            _ => return Ok(()),
        },
    };
    let dir = if s.spindle_on { m.spindle_dir } else { Some(super::SpindleDir::Stopped) };
    let refusal = match (code, dir) {
        (_, Some(super::SpindleDir::Stopped) | None) => format!("Spindle not turning in {code}"),
        ("G74", Some(super::SpindleDir::Cw)) => "Spindle turning clockwise in G74".to_string(),
        ("G84", Some(super::SpindleDir::Ccw)) => "Spindle turning counterclockwise in G84".to_string(),
        _ => return Ok(()),
    };
    let col = md.col.or_else(|| b.gs().find(|(g, _)| *g == 33.1).map(|(_, c)| c)).unwrap_or(b.col);
    Err(m.err(
        b.line,
        col,
        format!(
            "{code} with the spindle {}: LinuxCNC refuses it (\"{refusal}\"); start it with {} first",
            match dir {
                Some(super::SpindleDir::Cw) => "turning clockwise",
                Some(super::SpindleDir::Ccw) => "turning counter-clockwise",
                _ => "stopped",
            },
            match code {
                "G74" => "M4",
                "G84" => "M3",
                _ => "M3 or M4",
            }
        ),
    ))
}

fn g76(m: &mut Motion, b: &RBlock<'_>, col: usize) -> Result<(), Error> {
    b.allow_only(&m.file, "GPZIJKRQHELNMSXF", "G76")?;
    cycles::need_lathe_plane(m, b, col, "G76")?;
    let (x0, z0) = m.need_position(b.line, col, "G76")?;
    let need = |n: &str, what: &str| -> Result<f64, Error> {
        b.get(n).map(|w| w.v).ok_or_else(|| m.err(b.line, col, format!("G76 needs {n}, {what}")))
    };
    let pitch = need("P", "the pitch")? * m.scale;
    let z_end = need("Z", "the end of the thread")? * m.scale;
    let z_end = if m.absolute { z_end + m.offset[2] } else { z0 + z_end };
    // In diameter mode (G7) I, J and K are diameters; work in radius here.
    // In program units as radii (halved under G7, as LinuxCNC does first), then in mm.
    let half = if m.diameter { 0.5 } else { 1.0 };
    let (iu, ju, ku) = (
        need("I", "the crest offset from the drive line")? * half,
        need("J", "the first depth")? * half,
        need("K", "the full depth")? * half,
    );
    let (i, j, k) = (iu * m.scale, ju * m.scale, ku * m.scale);
    // R below 1 (or absent) is 1, as LinuxCNC's code does (its documentation calls it an error).
    let r = b.get("R").map_or(1.0, |w| w.v).max(1.0);
    // Q−1 is no compound angle, as LinuxCNC reads it.
    let q = b.get("Q").map_or(0.0, |w| if w.v == -1.0 { 0.0 } else { w.v });
    let h = b.get("H").map_or(0.0, |w| w.v);
    let e = b.get("E").map_or(0.0, |w| w.v).max(0.0) * m.scale;
    // L is a bit mask (1 entry taper, 2 exit taper) and a negative L is 0, as LinuxCNC reads it.
    let l = b.get("L").map_or(0.0, |w| w.v.max(0.0));
    if i == 0.0 {
        return Err(m.err(
            b.line,
            col,
            "G76 I must not be 0: it is the offset from the drive line to the crest",
        ));
    }
    if !(pitch > 0.0 && j > 0.0 && k > j) {
        return Err(m.err(b.line, col, "G76 needs P and J greater than zero and K greater than J"));
    }
    let h_ok = h >= -1.0 && h.fract() == 0.0 && h <= crate::ground::bounds::MAX_REPEATS as f64;
    if !(h_ok && l.fract() == 0.0 && l <= f64::from(u32::MAX)) {
        return Err(m.err(
            b.line,
            col,
            "G76 H must be a whole number of spring passes and L a whole number (1 entry taper, 2 exit taper, 3 both)",
        ));
    }
    let l_bits = l as u32;
    if m.css {
        m.note(b.line, col, "G76 under constant surface speed (G96); threading wants G97");
    }
    let external = i < 0.0;
    // Depths beyond the crest; the crest is |I| from the drive line.
    let peak_r = 0.5 * x0 + i;
    // The depths in program units and LinuxCNC's own order (halved under G7, measured from the
    // drive line: |I| + |J|·n^(1/R) while below |K| + |I|), so that a depth on a boundary of
    // floating-point rounding gives LinuxCNC's count.
    let (iu, ju, ku) = (iu.abs(), ju.abs(), ku.abs());
    let mut depths = Vec::new();
    let mut n = 1.0f64;
    let mut du = iu + ju;
    while du < ku + iu {
        depths.push((du - iu) * m.scale);
        n += 1.0;
        du = iu + ju * n.powf(1.0 / r);
        if depths.len() > crate::ground::bounds::MAX_PASSES {
            return Err(m.err(b.line, col, "G76 expands to too many passes"));
        }
    }
    // One pass at K and H spring passes (H−1 leaves out the pass at K, as LinuxCNC does).
    for _ in 0..(h + 1.0) as usize {
        depths.push(k);
    }
    let dir = if z_end < z0 { -1.0 } else { 1.0 };
    let tq = q.to_radians().tan();
    let (tin, tout) = (if l_bits & 1 != 0 { e } else { 0.0 }, if l_bits & 2 != 0 { e } else { 0.0 });
    let op = m.begin_op("G76", b);
    m.op_mut(op).infeed_angle = Some((q.abs(), "Q".into()));
    let inward = if external { -1.0 } else { 1.0 };
    for d in depths {
        let x = 2.0 * (peak_r + inward * d);
        // The tapers ramp to (K − depth) beyond the crest, away from the work.
        let x_taper = 2.0 * (peak_r - inward * (k - d));
        // Each pass starts depth·tan Q along the feed from Z; its synchronised stretch ends
        // (K − depth)·tan Q short of the end Z (LinuxCNC: target_z − zoff, target_z = end + K·tan Q).
        let (zs, ze) = (z0 + dir * d * tq, z_end - dir * (k - d) * tq);
        let mut p = cycles::pass(x, x, zs, ze, pitch, b.line, tout, x_taper);
        p.taper_in = tin;
        m.push(op, b.line, p)?;
    }
    if let Some(kw) = b.get("K") {
        let means = super::WordMeans::Depth { per_radial: if m.diameter { 2.0 } else { 1.0 } };
        m.op_mut(op).depth_word = Some(super::motion::address_word(b, kw, means));
    }
    if let Some(xw) = b.get("X") {
        m.x = Some(m.x_dia(xw));
    } else {
        m.x = Some(x0);
    }
    m.z = Some(z_end);
    Ok(())
}

impl Rules for State {
    fn block(&mut self, m: &mut Motion, b: &RBlock<'_>, cx: &mut Ctx<'_>) -> Result<Flow, Error> {
        let before = [self.written(m, 0), self.written(m, 1)];
        let flow = block(self, m, b, cx)?;
        self.remember(m, b, before);
        Ok(flow)
    }

    fn system_names(&self) -> &'static [&'static str] {
        &SYSTEM_NAMES
    }

    fn system_params(&self, m: &Motion, sys: &mut SysParams) {
        system_params(self, m, sys);
    }
}
