//! The motion state every dialect moves: position, units and modes, spindle, tool, and the
//! threading operations with their passes.

use super::{Dialect, Operation, ProgramUnits, Spindle, XWords};
use crate::ground::bounds::MAX_PASSES;
use crate::ground::note::{Note, NoteKind, Notes};
use crate::toolpath::passes::Pass;
use crate::Error;
use serde::Serialize;

/// A word with its value evaluated.
#[derive(Clone, Debug)]
pub(crate) struct RWord<'b> {
    /// Address, upper case.
    pub name: &'b str,
    /// Its value (0 for bare names and calls).
    pub v: f64,
    /// Written with a decimal point (an expression counts as written with one unless whole).
    pub point: bool,
    /// Column.
    pub col: usize,
    /// As written.
    pub text: &'b str,
    /// Call arguments (`CYCLE97(…)`), evaluated.
    pub args: Option<Vec<(Option<f64>, usize)>>,
}

/// An address word of block `b` (`X8.539`, `K#5`) as the depth word that means `means`.
pub(crate) fn address_word(b: &RBlock<'_>, w: &RWord<'_>, means: super::WordMeans) -> super::DepthWord {
    let plain = w.text.get(w.name.len()..).is_some_and(|v| v.trim().parse::<f64>().is_ok());
    super::DepthWord {
        word: w.name.to_string(),
        value: w.v,
        line: b.line,
        column: w.col,
        written: w.text.to_string(),
        form: if plain { super::WordForm::Number } else { super::WordForm::Expression },
        means,
    }
}

/// A block with its words evaluated: what a dialect module sees.
#[derive(Clone, Debug)]
pub(crate) struct RBlock<'b> {
    /// 1-based line.
    pub line: usize,
    /// Column of the first word.
    pub col: usize,
    /// The words.
    pub words: Vec<RWord<'b>>,
    /// Words dropped because their variable is vacant (Fanuc drops the address): name, the
    /// word as written, column.
    pub vacant: Vec<(&'b str, &'b str, usize)>,
}

impl<'b> RBlock<'b> {
    /// The last word with this address.
    pub fn get(&self, name: &str) -> Option<&RWord<'b>> {
        self.words.iter().rev().find(|w| w.name == name)
    }

    /// Why the block has no `name` word, when a vacant variable dropped it: for a message.
    pub fn why_missing(&self, name: &str) -> Option<String> {
        self.vacant.iter().find(|(n, _, _)| *n == name).map(|(_, text, col)| {
            format!("{text} (column {col}) reads a variable that is not set, and a vacant variable drops its word")
        })
    }

    /// Whether the block has this address.
    pub fn has(&self, name: &str) -> bool {
        self.words.iter().any(|w| w.name == name)
    }

    /// The G codes with their columns.
    pub fn gs(&self) -> impl Iterator<Item = (f64, usize)> + '_ {
        self.words.iter().filter(|w| w.name == "G").map(|w| (w.v, w.col))
    }

    /// Whether an M code is in the block.
    pub fn has_m(&self, code: f64) -> bool {
        self.words.iter().any(|w| w.name == "M" && w.v == code)
    }

    /// An error at a word.
    pub fn werr(&self, file: &str, w: &RWord<'_>, message: impl Into<String>) -> Error {
        Error::Program { file: file.to_string(), line: self.line, column: w.col, message: message.into() }
    }

    /// Every word must be one of `allowed` (one-letter addresses).
    pub fn allow_only(&self, file: &str, allowed: &str, cycle: &str) -> Result<(), Error> {
        for w in &self.words {
            if w.name.len() != 1 || !allowed.contains(w.name) {
                return Err(self.werr(
                    file,
                    w,
                    format!(
                        "word {} is not part of {cycle} (it takes {})",
                        w.name,
                        allowed.chars().map(String::from).collect::<Vec<_>>().join(" ")
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// One recorded move (milling toolpaths): straight or an arc in the XY plane.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Move {
    /// Rapid (G0).
    pub rapid: bool,
    /// Start point X, Y, Z (mm).
    pub from: [f64; 3],
    /// End point.
    pub to: [f64; 3],
    /// Arc centre (X, Y) and direction (+1 counter-clockwise G3, −1 clockwise G2), for arcs.
    pub arc: Option<([f64; 2], f64)>,
    /// Program line.
    pub line: usize,
    /// Cutter radius compensation in force: 0 none (G40), 1 left (G41), 2 right (G42).
    pub comp: u8,
    /// The tool in force.
    pub tool: Option<u32>,
    /// Full turns an arc makes beyond its first (LinuxCNC's `P`: P3 is two more turns).
    pub extra_turns: u32,
    /// The program's units at the move (what a diameter in its comments is written in).
    #[serde(skip)]
    pub units: super::ProgramUnits,
    /// The feed in force, mm/min (F per minute; per revolution times the spindle speed);
    /// `None` for a rapid and where the program has not given one (or per revolution without S).
    #[serde(skip)]
    pub feed: Option<f64>,
    /// The spindle speed in force, rpm (`None` where the program has not given one).
    #[serde(skip)]
    pub spindle: Option<f64>,
}

/// An open chain of synchronised moves (G32/G33 blocks one after the other): one helix.
#[derive(Clone, Debug)]
struct Chain {
    op: usize,
    z_phase: f64,
    /// The Z travel of the chain's longest segment, and the X word that set its depth: the
    /// chain's depth word (a run-out or run-in segment is never the word to correct).
    longest: f64,
    word: Option<super::DepthWord>,
    /// The last segment's lead and phase: a segment with another lead (a run-out steeper than
    /// 45°) continues the helix where the last one left it.
    last: Option<(f64, f64)>,
}

/// The shared motion state.
pub(crate) struct Motion {
    pub dialect: Dialect,
    /// The Fanuc G-code system the program's codes are read in.
    pub gsystem: super::GCodeSystem,
    /// Read as a milling toolpath (X and Y in the plane, G17).
    mill: bool,
    /// A mill-turn program: `mill` follows the plane.
    mill_turn: bool,
    /// A lathe-based mill-turn (its first evidence a lathe's: a T-series control with live
    /// tools), whose G98/G99 stay the feed modes in G-code system A in every plane.
    lathe_based: bool,
    pub file: String,
    /// The program's own file (`file` names a subprogram file while its blocks run).
    pub main_file: String,
    /// Position: X (diameter, mm, for lathes; plain X for mills), Y, Z — in machine coordinates.
    pub x: Option<f64>,
    pub y: Option<f64>,
    pub z: Option<f64>,
    /// The offset of program coordinates from machine coordinates (X diameter, Y, Z), mm:
    /// LinuxCNC's work offset plus its G92 offset.
    pub offset: [f64; 3],
    /// Why the program's coordinates lost their relation to the earlier passes' (an offset
    /// set from an unknown position after threading passes): the line and what did it.
    frame_lost: Option<(usize, String)>,
    pub absolute: bool,
    /// 25.4 under inch units, else 1.
    pub scale: f64,
    /// The program set its units (G20/G21, G70/G71, G700/G710) before its first threading
    /// operation.
    pub units_set: bool,
    /// X words are diameters.
    pub diameter: bool,
    /// Modal motion code (0, 1, 2, 3, 32, 33, 76, 92, …).
    pub motion: f64,
    /// Modal thread lead, mm.
    pub lead: Option<f64>,
    pub css: bool,
    pub s: Option<f64>,
    pub tool: Option<u32>,
    /// The spindle's direction as the last M3, M4 or M5 left it.
    pub spindle_dir: Option<super::SpindleDir>,
    /// Feed per revolution (G99 on a Fanuc or Haas lathe, G95 in G17), per minute (G98, G94),
    /// or not set by the program.
    pub feed_per_rev: Option<bool>,
    /// M29 (rigid tapping) given for the next tapping cycle.
    pub rigid_next: bool,
    /// The drilling and tapping cycles read, in program order.
    pub holes: Vec<super::HoleCycle>,
    /// What the control will refuse or a post got wrong, seen while reading (issue 63).
    pub control: Vec<super::control::ControlEvent>,
    /// The main program's line of the call that runs the subprogram file being read (`None`
    /// in the main program's own file).
    pub call_line: Option<usize>,
    /// The work offset the program selected last (`G55`, `G54.1 P3`), `None` before any.
    pub work_offset: Option<String>,
    /// The origins of work offsets the program set itself (`G10 L2 P2 X… Y…`), in machine
    /// coordinates, per axis when written.
    pub work_origins: std::collections::HashMap<String, [Option<f64>; 3]>,
    /// The stock the program declares (a training simulator's `[BILLET X…`): its diameter, mm,
    /// and line.
    pub stock: Option<(f64, usize)>,
    /// The modal bottom Z and feed of the canned cycle in force.
    pub hole_modal: (Option<f64>, Option<f64>),
    /// A machining centre's canned cycle: the initial level (Z where the cycle began), the R
    /// level, and whether G99 returns to R (else G98, to the initial level).
    pub cycle_levels: (Option<f64>, Option<f64>),
    /// G99 (return to the R level) in force on a machining centre.
    pub return_to_r: bool,
    /// The canned cycle's R and Z as last written (mm; in G91 increments), for the blocks
    /// that leave them out.
    pub cycle_words: (Option<f64>, Option<f64>),
    /// The canned cycle whose holes the last cycle block made, until another motion (LinuxCNC
    /// refuses a cycle's first block without R and Z).
    pub cycle_in_force: Option<u32>,
    /// A machining centre's local coordinate system (Fanuc G52 X Y Z), mm.
    pub local: [f64; 3],
    /// A machining centre's coordinate rotation (Fanuc G68): centre X, Y (mm) and angle
    /// (degrees, counter-clockwise).
    pub rotation: Option<(f64, f64, f64)>,
    /// A machining centre's programmable mirror image (Fanuc G51.1): the X and Y about which
    /// positions are mirrored.
    pub mirror: [Option<f64>; 2],
    /// A machining centre's polar coordinates (Fanuc G16): the last radius and angle written.
    pub polar: Option<(Option<f64>, Option<f64>)>,
    /// A lathe's C axis (the spindle's angle, degrees) as last written: live-tool holes.
    pub c_axis: Option<f64>,
    /// The bottom (a radius) of the last radial hole, for a repeat that gives none.
    pub radial_bottom: Option<f64>,
    /// The radial holes' reading said once.
    pub radial_said: bool,
    /// The live-tool placement was said in a note.
    pub live_tool_said: bool,
    /// Cutter radius compensation: 0 G40, 1 G41, 2 G42.
    pub comp: u8,
    /// A lathe's tool nose radius compensation (G41/G42 outside G17): 0 G40, 1 G41, 2 G42.
    pub nose_comp: u8,
    /// LinuxCNC's G90.1: an arc's I and J are its centre's coordinates (G91.1, the power-on
    /// state: offsets from its start).
    pub arc_centres_absolute: bool,
    /// Working plane (17, 18, 19).
    pub plane: u32,
    ops: Vec<Operation>,
    /// The operation loose G32/G33 passes may still join.
    loose: Option<usize>,
    chain: Option<Chain>,
    pub skipped: usize,
    pub notes: Notes,
    moves: Option<Vec<Move>>,
    /// Where recorded moves go as they are made, in chunks (a reader streaming a milling
    /// toolpath); `None` keeps them all for [`Motion::finish`].
    moves_out: Option<std::sync::mpsc::SyncSender<Vec<Move>>>,
    passes_total: usize,
    /// The last X word read (the tip's position of a G32/G33 chain or a G92 run).
    pub last_x: Option<super::DepthWord>,
    /// What was read past, by what it is, in the order first met.
    past: Vec<PastEntry>,
    past_index: std::collections::HashMap<String, usize>,
    /// Blocks read past (a block with two such things counts once).
    pub past_blocks: usize,
    past_last_line: usize,
    /// The last X and Z of a modal box cycle (its later blocks may give only one).
    pub box_last: Option<(f64, f64)>,
    /// Why the position became unknown last: the line and what did it.
    lost: Option<(usize, String)>,
    /// The turned contour so far: feed moves (G1, G2, G3) of the lathe dialects as
    /// (X0, Z0, X1, Z1), diameters, capped at `MAX_CONTOUR` segments.
    contour: Vec<super::Turned>,
    /// A roughing cycle's finished profile (Fanuc G71/G72/G73 `P… Q…`): the sequence numbers
    /// of its first and last block, and whether its blocks are being read. The roughing cuts
    /// along the profile whatever motion its blocks are written in (a modal G00 included), so
    /// they are all kept as the turned contour.
    pub profile: Option<Profile>,
    /// The line of a lathe's G12.1 (G112), polar coordinate interpolation, while it is in force:
    /// a live tool mills the face in X and C; its moves are read past, not as turning.
    pub face_polar: Option<usize>,
    /// A milling toolpath's F, mm (a minute's or a revolution's travel, as the feed mode says).
    mill_f: Option<f64>,
}

/// The sequence numbers a roughing cycle's profile runs between, and whether it is being read.
#[derive(Clone, Copy, Debug)]
pub struct Profile {
    pub first: f64,
    pub last: f64,
    pub on: bool,
}

/// Moves sent at once to a streaming reader's receiver.
const MOVE_CHUNK: usize = 4096;

/// Most contour segments kept for the run-out check.
const MAX_CONTOUR: usize = 100_000;

impl Motion {
    /// A motion state at the program start. `record_moves` records a milling toolpath's moves;
    /// `mill` reads the program for a machining centre: X and Y are plane coordinates in every
    /// dialect, G17 the plane.
    pub fn new(dialect: Dialect, file: &str, record_moves: bool, mill: bool) -> Motion {
        let mill = mill || record_moves;
        Motion {
            dialect,
            gsystem: super::GCodeSystem::A,
            mill,
            mill_turn: false,
            lathe_based: false,
            file: file.to_string(),
            main_file: file.to_string(),
            x: None,
            y: None,
            z: None,
            offset: [0.0; 3],
            frame_lost: None,
            absolute: true,
            scale: 1.0,
            units_set: false,
            // LinuxCNC starts in radius mode (G8); lathes with Fanuc, Haas and Sinumerik in
            // diameter; Dyna is a mill (X is X).
            diameter: match dialect {
                _ if mill => false,
                Dialect::Fanuc
                | Dialect::Haas
                | Dialect::Sinumerik
                | Dialect::Okuma
                | Dialect::Mitsubishi
                | Dialect::Mazak
                | Dialect::Heidenhain
                | Dialect::Klartext => true,
                Dialect::LinuxCnc | Dialect::Dyna => false,
            },
            motion: 0.0,
            lead: None,
            css: false,
            s: None,
            tool: None,
            spindle_dir: None,
            feed_per_rev: None,
            rigid_next: false,
            holes: Vec::new(),
            control: Vec::new(),
            work_offset: None,
            call_line: None,
            work_origins: std::collections::HashMap::new(),
            stock: None,
            hole_modal: (None, None),
            cycle_levels: (None, None),
            return_to_r: false,
            cycle_words: (None, None),
            arc_centres_absolute: false,
            cycle_in_force: None,
            local: [0.0; 3],
            rotation: None,
            mirror: [None; 2],
            polar: None,
            c_axis: None,
            radial_bottom: None,
            radial_said: false,
            live_tool_said: false,
            comp: 0,
            nose_comp: 0,
            plane: if !mill && lathe_dialect(dialect) { 18 } else { 17 },
            ops: Vec::new(),
            loose: None,
            chain: None,
            skipped: 0,
            notes: Notes::default(),
            moves: record_moves.then(Vec::new),
            moves_out: None,
            passes_total: 0,
            contour: Vec::new(),
            profile: None,
            face_polar: None,
            mill_f: None,
            last_x: None,
            past: Vec::new(),
            past_index: std::collections::HashMap::new(),
            past_blocks: 0,
            past_last_line: 0,
            lost: None,
            box_last: None,
        }
    }

    /// Records what the control will refuse or a post got wrong at a block (`code` the block's
    /// cycle), reading on.
    pub fn flag(
        &mut self,
        rule: super::control::ControlRule,
        code: &str,
        line: usize,
        column: usize,
        detail: String,
    ) {
        let file = (self.file != self.main_file).then(|| self.file.clone());
        self.control.push(super::control::ControlEvent {
            rule,
            code: code.to_string(),
            line,
            column,
            file,
            detail,
        });
    }

    /// Records something read past: `what` as the program writes it, `why` what threadcheck
    /// does with it. Every kind is one note at its first place, with how often it was met.
    pub fn read_past(&mut self, line: usize, col: usize, what: &str, why: &str) {
        if self.past_last_line != line {
            self.past_blocks += 1;
            self.past_last_line = line;
        }
        self.record(line, col, what, why, true);
    }

    /// Records a cycle that is modelled as holes, not as turning passes (a drilling or tapping
    /// cycle: the tapping check reads its holes): said once with its count, never "read past".
    pub fn read_as_holes(&mut self, line: usize, col: usize, what: &str, why: &str) {
        self.record(line, col, what, why, false);
    }

    fn record(&mut self, line: usize, col: usize, what: &str, why: &str, past: bool) {
        match self.past_index.get(what) {
            Some(&k) => self.past[k].count += 1,
            None => {
                self.past_index.insert(what.to_string(), self.past.len());
                self.past.push(PastEntry {
                    what: what.to_string(),
                    why: why.to_string(),
                    line,
                    col,
                    count: 1,
                    past,
                });
            }
        }
    }

    /// The position becomes unknown (in X, Z or both) because of `what` at `line`: a threading
    /// operation that starts from it is refused, naming it.
    pub fn lose_position(&mut self, line: usize, what: &str, x: bool, z: bool) {
        if x {
            self.x = None;
        }
        if z {
            self.z = None;
        }
        if x || z {
            self.lost = Some((line, what.to_string()));
            self.break_chain();
        }
    }

    /// The offset of program coordinates changed by an amount threadcheck cannot know
    /// (`what` at `line`): with threading passes before it, a later threading operation cannot
    /// be placed against them and is refused, naming it; with none, the frame is arbitrary.
    pub fn lose_frame(&mut self, line: usize, what: &str) {
        if self.passes_total > 0 && self.frame_lost.is_none() {
            self.frame_lost = Some((line, what.to_string()));
        }
    }

    /// Remembers a block's X word, the depth word of the passes it sets.
    pub fn note_x_word(&mut self, b: &RBlock<'_>) {
        if let Some(w) = b.get("X") {
            let means = if self.diameter || !self.lathe() {
                super::WordMeans::Diameter
            } else {
                super::WordMeans::Radius
            };
            self.last_x = Some(address_word(b, w, means));
        }
    }

    /// A mill-turn program: each section read by its plane (G18 a lathe's, G17 and G19 a
    /// machining centre's), from the machine its first evidence shows at the start.
    pub(crate) fn set_mill_turn(&mut self, start_as_mill: bool) {
        self.mill_turn = true;
        self.mill = start_as_mill;
        self.lathe_based = !start_as_mill;
    }

    /// Whether G98/G99 are the feed modes (per minute, per revolution) here: on a lathe, and in
    /// every section of a lathe-based mill-turn read in G-code system A (a T-series control's
    /// live tool drills and taps with the lathe's feed words: F0i-CON, notes §1.1).
    pub(crate) fn g98_is_feed(&self) -> bool {
        self.lathe() || (self.lathe_based && self.gsystem == super::GCodeSystem::A)
    }

    /// On a mill-turn program, the machine the plane just set names.
    pub(crate) fn plane_changed(&mut self) {
        if self.mill_turn {
            self.mill = self.plane != 18;
        }
    }

    /// Whether the program runs on a lathe: a lathe's, or a mill-turn's (a live tool's
    /// polar interpolation is a lathe's code in every section).
    pub(crate) fn lathe_program(&self) -> bool {
        self.lathe() || self.mill_turn
    }

    /// Whether the program is read as a milling toolpath.
    pub(crate) fn mill_reading(&self) -> bool {
        self.mill
    }

    /// Whether X words are turned into diameters (lathe dialects).
    pub(crate) fn lathe(&self) -> bool {
        !self.mill && lathe_dialect(self.dialect)
    }

    pub fn err(&self, line: usize, column: usize, message: impl Into<String>) -> Error {
        Error::Program { file: self.file.clone(), line, column, message: message.into() }
    }

    /// A warning with its place.
    pub fn note(&mut self, line: usize, column: usize, message: impl Into<String>) {
        self.notes.push(Note::at(&self.file, line, column, message));
    }

    /// A note of a kind the reader decides on, with its place.
    pub fn note_of(&mut self, kind: NoteKind, line: usize, column: usize, message: impl Into<String>) {
        self.notes.push(Note::at(&self.file, line, column, message).of_kind(kind));
    }

    /// A length word in mm.
    pub fn len(&self, w: &RWord<'_>) -> f64 {
        w.v * self.scale
    }

    /// An X word as a diameter in mm.
    pub fn x_dia(&self, w: &RWord<'_>) -> f64 {
        let v = self.len(w);
        if self.diameter || !self.lathe() {
            v
        } else {
            2.0 * v
        }
    }

    /// The code the program writes for system A's G code `a` (`G78` for a system B program's
    /// threading cycle), for names and messages.
    pub fn g_name(&self, a: u32) -> String {
        format!("G{}", self.gsystem.written(a))
    }

    /// Target position of a block: X/Y/Z absolute or incremental, U/W incremental
    /// (Fanuc, Haas). Program coordinates are machine coordinates less the G92 offset.
    pub fn target(&self, b: &RBlock<'_>) -> (Option<f64>, Option<f64>, Option<f64>) {
        // U and W are incremental X and Z on a lathe with Fanuc's codes only (OSP programs
        // incremental moves with G91; Heidenhain's U is G31's thread depth).
        let uw = self.dialect.facts().fanuc_codes && self.lathe();
        let (mut x, mut y, mut z) = (None, None, None);
        // G16: X the radius and Y the angle about the work zero (remembered in `cycles::modal`).
        let polar = self.polar.filter(|_| b.get("X").is_some() || b.get("Y").is_some());
        if let Some((Some(r), Some(a))) = polar {
            let (s, c) = a.to_radians().sin_cos();
            let tidy = |v: f64| if v.abs() < 1e-9 { 0.0 } else { v };
            x = Some(tidy(r * c) + self.offset[0]);
            y = Some(tidy(r * s) + self.offset[1]);
        }
        // LinuxCNC's polar words: `@` the distance from the program's origin, `^` the angle
        // (degrees) from +X; one left out is the current point's; in G91 both are increments of
        // the current point's (its checks in linuxcnc.rs: never with X or Y).
        let lpolar = self.dialect == Dialect::LinuxCnc && (b.get("@").is_some() || b.get("^").is_some());
        if lpolar {
            let cur = match (self.x, self.y) {
                (Some(x), Some(y)) => {
                    let (px, py) = (x - self.offset[0], y - self.offset[1]);
                    Some((px.hypot(py), py.atan2(px).to_degrees()))
                }
                _ => None,
            };
            let r = b.get("@").map(|w| self.len(w));
            let a = b.get("^").map(|w| w.v);
            let ra = match (self.absolute, r, a, cur) {
                (true, Some(r), Some(a), _) => Some((r, a)),
                (true, r, a, Some((r0, a0))) => Some((r.unwrap_or(r0), a.unwrap_or(a0))),
                (false, r, a, Some((r0, a0))) => Some((r0 + r.unwrap_or(0.0), a0 + a.unwrap_or(0.0))),
                _ => None,
            };
            if let Some((r, a)) = ra {
                let (s, c) = a.to_radians().sin_cos();
                x = Some(r * c + self.offset[0]);
                y = Some(r * s + self.offset[1]);
            }
        }
        for w in &b.words {
            match w.name {
                "X" | "Y" if polar.is_some() || lpolar => {}
                "X" => {
                    let v = self.x_dia(w);
                    x = Some(if self.absolute { v + self.offset[0] } else { self.x.unwrap_or(0.0) + v });
                }
                // Y on a lathe only in the machining centre's plane G17 (drilling and tapping
                // positions) and in LinuxCNC, which keeps it everywhere.
                "Y" if !self.lathe() || self.dialect == Dialect::LinuxCnc || self.plane == 17 => {
                    let v = self.len(w);
                    y = Some(if self.absolute { v + self.offset[1] } else { self.y.unwrap_or(0.0) + v });
                }
                "Z" => {
                    let v = self.len(w);
                    z = Some(if self.absolute { v + self.offset[2] } else { self.z.unwrap_or(0.0) + v });
                }
                "U" if uw => x = Some(self.x.unwrap_or(0.0) + self.x_dia(w)),
                "W" if uw => z = Some(self.z.unwrap_or(0.0) + self.len(w)),
                _ => {}
            }
        }
        (x, y, z)
    }

    /// A point of the program (X, Y, Z in its coordinates) in the workpiece coordinates of the
    /// work offset in force: mirrored (G51.1), rotated about the G68 centre, then shifted by the
    /// G52 local system.
    pub fn work_point(
        &self,
        x: Option<f64>,
        y: Option<f64>,
        z: Option<f64>,
    ) -> (Option<f64>, Option<f64>, Option<f64>) {
        // The mirror first, then the rotation, then the local system.
        let x = match self.mirror[0] {
            Some(m) => x.map(|v| 2.0 * m - v),
            None => x,
        };
        let y = match self.mirror[1] {
            Some(m) => y.map(|v| 2.0 * m - v),
            None => y,
        };
        let (x, y) = match (self.rotation, x, y) {
            (Some((cx, cy, deg)), Some(x), Some(y)) => {
                let (s, c) = deg.to_radians().sin_cos();
                let (dx, dy) = (x - cx, y - cy);
                // A rounding's leftover (cos 90° = 6e-17) is no position: zero it below 1 pm.
                let tidy = |v: f64| if v.abs() < 1e-9 { 0.0 } else { v };
                (Some(tidy(cx + c * dx - s * dy)), Some(tidy(cy + s * dx + c * dy)))
            }
            // A rotated point with one coordinate unknown is unknown.
            (Some(_), _, _) => (None, None),
            (None, x, y) => (x, y),
        };
        (x.map(|v| v + self.local[0]), y.map(|v| v + self.local[1]), z.map(|v| v + self.local[2]))
    }

    /// A milling toolpath's feed in force after the block's F, mm/min (`None`: not given, or
    /// per revolution with no spindle speed).
    fn mill_feed(&mut self, b: &RBlock<'_>) -> Option<f64> {
        if let Some(w) = b.get("F") {
            self.mill_f = Some(self.len(w));
        }
        match self.feed_per_rev {
            Some(true) => self.mill_f.zip(self.s).map(|(f, s)| f * s),
            _ => self.mill_f,
        }
    }

    /// Moves to the block's target; true if it moved. Records the move when asked.
    pub fn move_to(&mut self, b: &RBlock<'_>) -> bool {
        // A block's F holds for the moves after it, whether it moves or not (`F500` alone).
        let feed = if self.moves.is_some() { self.mill_feed(b) } else { None };
        let (x, y, z) = self.target(b);
        let moved = x.is_some() || y.is_some() || z.is_some();
        if moved {
            self.break_chain();
            let units = self.program_units();
            let feed = if self.motion == 0.0 { None } else { feed };
            if let Some(mv) = self.moves.as_mut() {
                let from = [self.x.unwrap_or(0.0), self.y.unwrap_or(0.0), self.z.unwrap_or(0.0)];
                let to = [x.unwrap_or(from[0]), y.unwrap_or(from[1]), z.unwrap_or(from[2])];
                mv.push(Move {
                    rapid: self.motion == 0.0,
                    from,
                    to,
                    arc: None,
                    line: b.line,
                    comp: self.comp,
                    tool: self.tool,
                    extra_turns: 0,
                    units,
                    feed,
                    spindle: self.s,
                });
                self.stream_moves(false);
            }
            self.record_contour(x, z, b.line);
        }
        if let Some(x) = x {
            self.x = Some(x);
        }
        if let Some(y) = y {
            self.y = Some(y);
        }
        if let Some(z) = z {
            self.z = Some(z);
        }
        moved
    }

    /// Records an arc in the XY plane (G2 −1, G3 +1) to the block's target, centre from I J
    /// (incremental) or R.
    pub fn arc_to(&mut self, b: &RBlock<'_>, dir: f64) -> Result<bool, Error> {
        let (x, y, z) = self.target(b);
        if x.is_none() && y.is_none() && z.is_none() {
            return Ok(false);
        }
        if self.polar.is_some() || self.mirror.iter().any(Option::is_some) {
            let what = match (self.polar.is_some(), self.dialect) {
                (true, _) => "G16 (polar coordinates)",
                (false, Dialect::Sinumerik) => {
                    "MIRROR (a mirrored frame, which reverses its direction and a thread's hand)"
                }
                (false, _) => "G51.1 (a mirror image, which reverses its direction and a thread's hand)",
            };
            return Err(self.err(
                b.line,
                b.col,
                format!("an arc under {what} is not read: write it without"),
            ));
        }
        self.break_chain();
        // LinuxCNC's P: the number of turns of the arc (a helix of several turns in one block);
        // Sinumerik's TURN: the full circles added to it.
        let extra_turns = match (self.dialect, b.get("P")) {
            (Dialect::LinuxCnc, Some(p)) => {
                if !(p.v >= 1.0 && p.v.fract() == 0.0 && p.v <= 10_000.0) {
                    return Err(b.werr(
                        &self.file,
                        p,
                        format!("P{}: an arc's number of turns is a whole number from 1", p.v),
                    ));
                }
                p.v as u32 - 1
            }
            // Sinumerik's TURN=n: n full circles more than the programmed arc (a helix).
            (Dialect::Sinumerik, _) => match b.get("TURN") {
                Some(t) if !(t.v >= 0.0 && t.v.fract() == 0.0 && t.v <= 10_000.0) => {
                    return Err(b.werr(
                        &self.file,
                        t,
                        format!("TURN={}: the added full circles are a whole number from 0", t.v),
                    ))
                }
                Some(t) => t.v as u32,
                None => 0,
            },
            // One turn: LinuxCNC without P, and the dialects whose arcs have no turns word.
            (Dialect::LinuxCnc, None)
            | (
                Dialect::Fanuc
                | Dialect::Haas
                | Dialect::Okuma
                | Dialect::Mitsubishi
                | Dialect::Mazak
                | Dialect::Dyna
                | Dialect::Heidenhain
                | Dialect::Klartext,
                _,
            ) => 0,
        };
        // An arc of the turned contour is kept as its chord: enough to see a shoulder.
        self.record_contour(x, z, b.line);
        let from = [self.x.unwrap_or(0.0), self.y.unwrap_or(0.0), self.z.unwrap_or(0.0)];
        let to = [x.unwrap_or(from[0]), y.unwrap_or(from[1]), z.unwrap_or(from[2])];
        if self.moves.is_some() && self.plane == 17 {
            let centre = if let Some(rw) = b.get("R") {
                let r = self.len(rw);
                let (dx, dy) = (to[0] - from[0], to[1] - from[1]);
                let d = (dx * dx + dy * dy).sqrt();
                if d == 0.0 || d > 2.0 * r.abs() + 1e-9 {
                    return Err(self.err(
                        b.line,
                        rw.col,
                        format!("arc radius R{} cannot reach the end point", rw.v),
                    ));
                }
                let h = (r * r - 0.25 * d * d).max(0.0).sqrt();
                // R > 0: the shorter arc; the centre lies to the left of the chord for G3.
                let s = dir * r.signum();
                [from[0] + 0.5 * dx - s * h * dy / d, from[1] + 0.5 * dy + s * h * dx / d]
            } else if self.arc_centres_absolute {
                // G90.1 (LinuxCNC): I and J are the centre's coordinates, in the program's frame
                // as X and Y are; an axis left out is 0 there.
                let i = b.get("I").map_or(0.0, |w| self.len(w)) + self.offset[0];
                let j = b.get("J").map_or(0.0, |w| self.len(w)) + self.offset[1];
                [i, j]
            } else {
                let i = b.get("I").map_or(0.0, |w| self.len(w));
                let j = b.get("J").map_or(0.0, |w| self.len(w));
                [from[0] + i, from[1] + j]
            };
            let units = self.program_units();
            let feed = if self.moves.is_some() { self.mill_feed(b) } else { None };
            if let Some(mv) = self.moves.as_mut() {
                mv.push(Move {
                    rapid: false,
                    from,
                    to,
                    arc: Some((centre, dir)),
                    line: b.line,
                    comp: self.comp,
                    tool: self.tool,
                    extra_turns,
                    units,
                    feed,
                    spindle: self.s,
                });
                self.stream_moves(false);
            }
        }
        self.x = Some(to[0]);
        self.y = Some(to[1]);
        self.z = Some(to[2]);
        Ok(true)
    }

    /// A block numbered as a roughing cycle's profile's first opens it.
    pub fn profile_starts(&mut self, n: Option<f64>) {
        if let (Some(p), Some(n)) = (self.profile.as_mut(), n) {
            if n == p.first {
                p.on = true;
            }
        }
    }

    /// A block numbered as the profile's last closes it, once read.
    pub fn profile_ends(&mut self, n: Option<f64>) {
        if self.profile.is_some_and(|p| p.on && n == Some(p.last)) {
            self.profile = None;
        }
    }

    /// Keeps a feed move of a lathe program as a segment of the turned contour (and a rapid one
    /// of a roughing cycle's profile, which the roughing cuts).
    fn record_contour(&mut self, x: Option<f64>, z: Option<f64>, line: usize) {
        let feed = matches!(self.motion as u32, 1..=3) && self.motion.fract() == 0.0;
        let profile = self.profile.is_some_and(|p| p.on) && self.motion == 0.0;
        if !(feed || profile) || !self.lathe() || self.contour.len() >= MAX_CONTOUR {
            return;
        }
        if let (Some(x0), Some(z0)) = (self.x, self.z) {
            self.contour.push(super::Turned {
                from: [x0, z0],
                to: [x.unwrap_or(x0), z.unwrap_or(z0)],
                line,
                rapid: !feed,
            });
        }
    }

    /// A box cycle's cut (Fanuc/Haas G90): the tool feeds along Z at diameter `x` from the
    /// start point's Z to `z` and returns, so the cylinder turned is that stretch.
    pub fn record_box_cut(&mut self, x: f64, z: f64, line: usize) {
        if let Some(z0) = self.z {
            if self.lathe() && self.contour.len() < MAX_CONTOUR {
                self.contour.push(super::Turned { from: [x, z0], to: [x, z], line, rapid: false });
            }
        }
    }

    /// The current X and Z, or an error naming what needs them.
    pub fn need_position(&self, line: usize, col: usize, what: &str) -> Result<(f64, f64), Error> {
        if let Some((l, why)) = &self.frame_lost {
            return Err(self.err(
                line,
                col,
                format!(
                    "{what} cannot be placed against the earlier threading passes: line {l} ({why}) set an offset from a position threadcheck does not know"
                ),
            ));
        }
        match (self.x, self.z) {
            (Some(x), Some(z)) => Ok((x, z)),
            _ => Err(self.err(
                line,
                col,
                match &self.lost {
                    Some((l, why)) => format!(
                        "{what} starts from a position unknown since line {l} ({why}, read past): move to X and Z first"
                    ),
                    None => format!("{what} starts from an unknown position: move to X and Z first"),
                },
            )),
        }
    }

    /// Sets the units (25.4 for inches, 1 for mm); before the first threading operation this
    /// is the program setting its units.
    pub fn set_scale(&mut self, scale: f64) {
        self.scale = scale;
        if self.ops.is_empty() {
            self.units_set = true;
        }
    }

    /// Ends an open synchronised chain.
    pub fn break_chain(&mut self) {
        self.chain = None;
    }

    /// The spindle as it stands.
    pub fn spindle(&self) -> Spindle {
        Spindle { s: self.s, constant_surface_speed: self.css, dir: self.spindle_dir }
    }

    /// Starts a new operation for a cycle call in block `b`; returns its index.
    pub fn begin_op(&mut self, cycle: &str, b: &RBlock<'_>) -> usize {
        // The column of the word that names the cycle (`G76`, `CYCLE97`, `L97`), else the
        // block's first word's.
        let column = b
            .words
            .iter()
            .find(|w| {
                w.name.eq_ignore_ascii_case(cycle)
                    || cycle.strip_prefix(w.name).and_then(|c| c.parse::<f64>().ok()) == Some(w.v)
            })
            .map_or(b.col, |w| w.col);
        let line = b.line;
        self.break_chain();
        self.loose = None;
        self.ops.push(Operation {
            index: self.ops.len() + 1,
            cycle: cycle.to_string(),
            source_line: line,
            source_column: column,
            source_file: (self.file != self.main_file).then(|| self.file.clone()),
            tool: self.tool,
            spindle: self.spindle(),
            infeed_angle: None,
            start: self.x.zip(self.z),
            contour: self.contour.clone(),
            passes: Vec::new(),
            notes: Vec::new(),
            units: self.program_units(),
            x_words: if self.diameter { XWords::Diameter } else { XWords::Radius },
            depth_word: None,
            start_words: Vec::new(),
            pass_x_words: Vec::new(),
        });
        self.ops.len() - 1
    }

    /// An operation being built.
    pub fn op_mut(&mut self, op: usize) -> &mut Operation {
        &mut self.ops[op]
    }

    /// The units the program's words are in now.
    pub fn program_units(&self) -> ProgramUnits {
        ProgramUnits::of_scale(self.scale)
    }

    /// Records a drilling or tapping cycle; past [`MAX_HOLES`](crate::ground::bounds::MAX_HOLES)
    /// the program is refused at the cycle's place, never cut short.
    pub fn push_hole(&mut self, mut h: super::HoleCycle) -> Result<(), Error> {
        h.work_offset = self.work_offset.clone();
        h.source_file = (self.file != self.main_file).then(|| self.file.clone());
        h.main_line = match (&h.source_file, self.call_line) {
            (Some(_), Some(call)) => call,
            _ => h.line,
        };
        h.machine_xy = match (&self.work_offset, h.x, h.y) {
            (_, Some(x), Some(y)) if self.dialect == Dialect::LinuxCnc && h.radial.is_none() => Some((x, y)),
            (Some(name), Some(x), Some(y)) => {
                self.work_origins.get(name).and_then(|o| Some((x + o[0]?, y + o[1]?)))
            }
            _ => None,
        };
        if self.holes.len() >= crate::ground::bounds::MAX_HOLES {
            return Err(self.err(
                h.line,
                h.column,
                format!(
                    "{}: more than {} drilling and tapping cycles in one program",
                    h.code,
                    crate::ground::bounds::MAX_HOLES
                ),
            ));
        }
        self.holes.push(h);
        Ok(())
    }

    /// Records a spindle-synchronized tap (LinuxCNC's G33.1, a lathe's G32 on the centre line):
    /// feed per revolution given by `feed_word`, rigid, its hand the spindle's; spindle, direction
    /// and tool as in force.
    #[allow(clippy::too_many_arguments)]
    pub fn push_synced_tap(
        &mut self,
        code: &str,
        line: usize,
        column: usize,
        (x, y): (Option<f64>, Option<f64>),
        bottom: Option<f64>,
        feed: Option<f64>,
        feed_word: &str,
    ) -> Result<(), Error> {
        // In the frame holes are reported in (LinuxCNC's plane rotation applied).
        let (x, y, bottom) = self.work_point(x, y, bottom);
        self.push_hole(super::HoleCycle {
            code: code.to_string(),
            units: self.program_units(),
            kind: super::HoleKind::Tap,
            line,
            column,
            x,
            y,
            radial: None,
            bottom,
            feed,
            feed_word: feed_word.to_string(),
            hand: None,
            feed_per_rev: true,
            feed_mode_assumed: false,
            spindle: self.s,
            spindle_dir: self.spindle_dir,
            tool: self.tool,
            // Set where it is recorded (Motion::push_hole).
            work_offset: None,
            source_file: None,
            main_line: 0,
            machine_xy: None,
            rigid: true,
            constant_surface_speed: self.css,
            r_level: None,
        })
    }

    /// Adds a pass to an operation.
    pub fn push(&mut self, op: usize, line: usize, mut p: Pass) -> Result<(), Error> {
        self.passes_total += 1;
        if self.passes_total > MAX_PASSES {
            return Err(self.err(line, 1, format!("more than {MAX_PASSES} passes")));
        }
        // A tool beyond the spindle axis (Swiss-type and gang-tool lathes: every X negative)
        // cuts the same thread at the same distance from the axis: the pass is read mirrored,
        // once said (issue 47). A pass that reaches or crosses the axis is refused.
        // Only a tool that stays beyond the axis: its cycle starts there too, and no variable
        // read before it was set explains the sign (an R-parameter read as 0 is refused, naming it).
        let beyond = p.x_start < 0.0
            && p.x_end < 0.0
            && p.x_taper <= 0.0
            && self.ops[op].start.is_none_or(|(x, _)| x < 0.0)
            && self.notes.find(NoteKind::UnsetVariable).is_none();
        if beyond {
            p.x_start = -p.x_start;
            p.x_end = -p.x_end;
            p.x_taper = -p.x_taper;
            let o = &mut self.ops[op];
            if !o.notes.iter().any(|n| n.message.starts_with("the passes run at negative X")) {
                o.notes.push(Note::at(
                    &self.file,
                    line,
                    1,
                    "the passes run at negative X, a tool beyond the spindle axis (Swiss-type and gang-tool lathes): read by their distance from the axis, on the same side as ever (the thread is the same)",
                ));
            }
        }
        if !(p.x_start > 0.0 && p.x_end > 0.0) {
            let x = if p.x_start <= 0.0 { p.x_start } else { p.x_end };
            let mut msg = format!(
                "{} pass at X{x} reaches or crosses the axis: no thread can be cut there",
                self.ops[op].cycle
            );
            if let Some(n) = self.notes.find(NoteKind::UnsetVariable) {
                if let Some(p) = &n.place {
                    msg.push_str(&format!(" (line {}:{}: {})", p.line, p.column, n.message));
                }
            }
            return Err(self.err(line, 1, msg));
        }
        let far = [("X", p.x_start), ("X", p.x_end), ("Z", p.z_start), ("Z", p.z_end), ("Z", p.z_phase)]
            .into_iter()
            .find(|(_, v)| !(v.abs() <= crate::ground::bounds::MAX_COORDINATE));
        if let Some((axis, v)) = far {
            return Err(self.err(
                line,
                1,
                format!(
                    "{} pass at {axis}{v}: beyond the {} mm from the origin threadcheck reads",
                    self.ops[op].cycle,
                    crate::ground::bounds::MAX_COORDINATE
                ),
            ));
        }
        let word = self.last_x.clone();
        let o = &mut self.ops[op];
        p.index = o.passes.len() + 1;
        o.passes.push(p);
        if let Some(w) = &word {
            let (lo, hi) = (p.z_start.min(p.z_end), p.z_start.max(p.z_end));
            match o.pass_x_words.iter_mut().find(|k| k.word.line == w.line && k.word.column == w.column) {
                Some(k) => {
                    k.z_min = k.z_min.min(lo);
                    k.z_max = k.z_max.max(hi);
                }
                None => o.pass_x_words.push(super::PassXWord { word: w.clone(), z_min: lo, z_max: hi }),
            }
        }
        // The X that set this pass; a cycle whose depth is another word says so after.
        o.depth_word = word;
        Ok(())
    }

    /// A single synchronised move from the current position to the block's target (G32/G33):
    /// `lead_of(Δx radius, Δz)` gives the axial lead of the segment. Consecutive synchronised
    /// blocks form one chain on one helix: each segment is its own pass, phased from the chain's
    /// start, so a straight–taper–straight chain keeps its deeper stretch.
    pub fn thread_move(
        &mut self,
        b: &RBlock<'_>,
        col: usize,
        cycle: &str,
        lead_of: impl Fn(f64, f64) -> f64,
        start_offset_deg: f64,
    ) -> Result<(), Error> {
        let (x0, z0) = self.need_position(b.line, col, cycle)?;
        let (x, _, z) = self.target(b);
        let (x1, z1) = (x.unwrap_or(x0), z.unwrap_or(z0));
        if (z1 - z0).abs() < 1e-12 {
            return Err(self.err(b.line, col, format!("{cycle} has no Z travel: a face (scroll) thread, which the control cuts but threadcheck does not measure (it measures threads along Z)")));
        }
        let lead = lead_of(0.5 * (x1 - x0), z1 - z0);
        if !(lead > 0.0 && lead.is_finite()) {
            return Err(self.err(b.line, col, format!("{cycle} lead must be greater than zero")));
        }
        if self.css {
            self.note(
                b.line,
                col,
                format!("{cycle} under constant surface speed (G96); threading wants G97"),
            );
        }
        let dir = if z1 < z0 { -1.0 } else { 1.0 };
        let mut chain = match self.chain.take() {
            Some(c) => c,
            None => {
                let z_phase = z0 + dir * start_offset_deg / 360.0 * lead;
                // A new chain joins the loose operation when it cuts the same helix over the
                // same stretch; otherwise it starts an operation of its own.
                let op = match self.loose {
                    Some(op) if self.joins(op, lead, z0, z1) => op,
                    _ => {
                        let op = self.begin_op(cycle, b);
                        // Passes written by hand: their rapids are blocks of their own.
                        self.ops[op].start = None;
                        self.loose = Some(op);
                        op
                    }
                };
                Chain { op, z_phase, longest: 0.0, word: None, last: None }
            }
        };
        // The turns made up to z0 on the last segment's helix go on at this segment's lead.
        let z_phase = match chain.last {
            Some((l, ph)) if (l - lead).abs() > 1e-12 => z0 - lead * (z0 - ph) / l,
            Some((_, ph)) => ph,
            None => chain.z_phase,
        };
        chain.last = Some((lead, z_phase));
        let p = Pass {
            index: 0,
            x_start: x0,
            x_end: x1,
            z_start: z0,
            z_end: z1,
            z_phase,
            lead,
            start: 0,
            source_line: Some(b.line),
            taper_in: 0.0,
            taper_out: 0.0,
            x_taper: x1,
        };
        self.push(chain.op, b.line, p)?;
        let travel = (z1 - z0).abs();
        if travel > chain.longest {
            chain.longest = travel;
            chain.word = self.ops[chain.op].depth_word.clone();
        } else {
            self.ops[chain.op].depth_word = chain.word.clone();
        }
        self.chain = Some(chain);
        self.x = Some(x1);
        self.z = Some(z1);
        Ok(())
    }

    fn joins(&self, op: usize, lead: f64, z0: f64, z1: f64) -> bool {
        let o = &self.ops[op];
        let (lo, hi) = (z0.min(z1), z0.max(z1));
        let same_lead = (o.lead() - lead).abs() < 1e-9;
        let overlap = o.passes.iter().any(|p| {
            let (a, b) = (p.z_start.min(p.z_end), p.z_start.max(p.z_end));
            a.max(lo) < b.min(hi)
        });
        same_lead && overlap
    }

    /// Sends the moves recorded so far to [`Motion::moves_out`] once there are a chunk of them
    /// (all of them when `all`). A receiver that has hung up (its check stopped) stops the
    /// recording: nothing more is kept.
    fn stream_moves(&mut self, all: bool) {
        let Some(tx) = &self.moves_out else { return };
        let Some(mv) = self.moves.as_mut() else { return };
        if mv.is_empty() || !all && mv.len() < MOVE_CHUNK {
            return;
        }
        if tx.send(std::mem::take(mv)).is_err() {
            self.moves = None;
            self.moves_out = None;
        }
    }

    /// Streams the recorded moves to `out` as they are made instead of keeping them.
    pub fn stream_to(&mut self, out: std::sync::mpsc::SyncSender<Vec<Move>>) {
        self.moves_out = Some(out);
    }

    /// The operations, skipped-block count, notes and moves. Each operation gets the warnings
    /// of its own passes (passes that cut nothing, passes beyond the axis).
    pub fn finish(mut self) -> (Vec<Operation>, usize, Vec<Note>, Vec<Move>, usize) {
        self.stream_moves(true);
        self.moves_out = None;
        let file = self.file.clone();
        self.ops.retain(|o| !o.passes.is_empty());
        for o in &mut self.ops {
            // Passes written one by one tell their starts by their phase; a cycle lays out its
            // own starts.
            if matches!(o.cycle.as_str(), "G32" | "G33" | "G92") {
                assign_starts(o);
            }
        }
        merge_starts(&mut self.ops, &file);
        for o in &mut self.ops {
            shallow_pass_notes(o, &file);
        }
        for (i, o) in self.ops.iter_mut().enumerate() {
            o.index = i + 1;
        }
        for e in std::mem::take(&mut self.past) {
            let times = if e.count == 1 { String::new() } else { format!(" ({} times)", e.count) };
            self.notes.push(if e.past {
                Note::at(&file, e.line, e.col, format!("{} read past{times}: {}", e.what, e.why))
                    .of_kind(NoteKind::ReadPast)
            } else {
                Note::at(&file, e.line, e.col, format!("{}{times}: {}", e.what, e.why))
            });
        }
        (self.ops, self.skipped, self.notes.into_vec(), self.moves.unwrap_or_default(), self.past_blocks)
    }
}

/// One kind of thing read past.
#[derive(Clone, Debug)]
struct PastEntry {
    what: String,
    why: String,
    line: usize,
    col: usize,
    count: usize,
    /// Read past (else modelled elsewhere: a hole cycle's holes).
    past: bool,
}

/// The most a flank infeed moves a pass along Z per mm of radial depth: tan 30°, half the
/// included angle of a 60° thread, the widest of the forms threadcheck cuts.
const FLANK_SHIFT_PER_DEPTH: f64 = 0.577_350_269_189_625_8;

/// Tells the starts of an operation of passes written one by one (G32, G33, G92) apart, the
/// named default: a pass belongs to a start when its helix phase (mod the lead) lies within
/// what a flank infeed explains of one of that start's passes, |Δx|/2 · tan 30° (+1 µm);
/// otherwise it begins a new start. Passes shifted along Z and start angles (Q, SF) read the
/// same way.
fn assign_starts(o: &mut Operation) {
    let mut starts: Vec<Vec<(f64, f64)>> = Vec::new();
    for p in &mut o.passes {
        let lead = p.lead;
        let circ = |a: f64, b: f64| {
            let d = (a - b).rem_euclid(lead);
            d.min(lead - d)
        };
        let found = starts.iter().position(|s| {
            s.iter().any(|&(ph, x)| {
                circ(p.z_phase, ph) <= 0.5 * (p.x_end - x).abs() * FLANK_SHIFT_PER_DEPTH + 1e-3
            })
        });
        let k = match found {
            Some(k) => k,
            None => {
                starts.push(Vec::new());
                starts.len() - 1
            }
        };
        starts[k].push((p.z_phase, p.x_end));
        p.start = k as u32;
    }
}

/// Joins an operation to the one before when it cuts another start of the same thread: the
/// same cycle, lead and pass diameters, every pass shifted along Z by one amount under a lead
/// and not zero (one cycle per start, shifted by the pitch); the note says so.
fn merge_starts(ops: &mut Vec<Operation>, file: &str) {
    let mut out: Vec<Operation> = Vec::with_capacity(ops.len());
    // How many passes the first cycle of the last operation in `out` has.
    let mut first_len = 0;
    for o in ops.drain(..) {
        if let Some(a) = out.last_mut() {
            let k = first_len;
            let b = &o;
            let same = a.cycle == b.cycle
                && k == b.passes.len()
                && a.passes
                    .iter()
                    .zip(&b.passes)
                    .all(|(p, q)| (p.lead - q.lead).abs() < 1e-12 && (p.x_end - q.x_end).abs() < 1e-6);
            let shift = b.passes[0].z_phase - a.passes[0].z_phase;
            let constant =
                a.passes.iter().zip(&b.passes).all(|(p, q)| (q.z_phase - p.z_phase - shift).abs() < 1e-6);
            let lead = a.passes[0].lead;
            let r = shift.rem_euclid(lead);
            // Another start lies less than a lead away; further along Z it is another thread.
            if same && constant && shift.abs() < lead - 1e-3 && r.min(lead - r) > 1e-3 {
                a.notes.push(Note::at(
                    file,
                    b.source_line,
                    1,
                    format!(
                        "the {} at line {} cuts another start of this thread, {:.4} mm along Z: one operation",
                        b.cycle, b.source_line, shift
                    ),
                ));
                let next = a.passes.iter().map(|p| p.start + 1).max().unwrap_or(1);
                a.passes.extend(b.passes.iter().map(|p| Pass { start: next + p.start, ..*p }));
                a.notes.extend(b.notes.iter().cloned());
                a.start_words.extend(b.depth_word.clone());
                a.pass_x_words.extend(b.pass_x_words.iter().cloned());
                continue;
            }
        }
        first_len = o.passes.len();
        out.push(o);
    }
    *ops = out;
}

/// Notes on passes that go deeper than no earlier pass anywhere (by 1 µm, at either end of the
/// last pass's stretch) and come out shallower than them somewhere: such a pass cuts nothing. A
/// spring pass at the same depth is normal and not noted.
fn shallow_pass_notes(o: &mut Operation, file: &str) {
    // The passes that begin a cut (a chain's later segments, a run-out taper, keep the phase of
    // its first): the first and the last of them tell inward from outward.
    let heads: Vec<&Pass> = o.passes.iter().filter(|p| (p.z_phase - p.z_start).abs() <= 1e-12).collect();
    let (first, last) = match heads.as_slice() {
        [first, .., last] => (**first, **last),
        _ => return,
    };
    let zs = [last.z_start, last.z_end];
    // Inward (external) when the passes end below where they began.
    let inward = last.x_at(zs[0]) + last.x_at(zs[1]) < first.x_at(zs[0]) + first.x_at(zs[1]);
    let depth = |x: f64| if inward { -x } else { x };
    // Each start is its own groove: a pass is compared with the passes of its start.
    let mut deepest_of: Vec<Option<([f64; 2], usize)>> = Vec::new();
    let mut notes = Vec::new();
    for p in &o.passes {
        if (p.z_phase - p.z_start).abs() > 1e-12 {
            // A later segment of a chain: its depth is its own.
            continue;
        }
        let s = p.start as usize;
        if deepest_of.len() <= s {
            deepest_of.resize(s + 1, None);
        }
        let deepest = &mut deepest_of[s];
        let d = [depth(p.x_at(zs[0])), depth(p.x_at(zs[1]))];
        if let Some((dd, line)) = *deepest {
            let deeper = (d[0] - dd[0]).max(d[1] - dd[1]);
            let shallower = (dd[0] - d[0]).max(dd[1] - d[1]);
            if deeper <= 1e-3 && shallower > 1e-3 {
                notes.push(Note::at(
                    file,
                    p.source_line.unwrap_or(0),
                    1,
                    format!(
                        "pass {} is {:.3} mm shallower than the pass of line {line} (on the diameter) and nowhere deeper: it cuts nothing",
                        p.index, shallower
                    ),
                ));
            }
        }
        *deepest = Some(match *deepest {
            None => (d, p.source_line.unwrap_or(0)),
            Some((dd, line)) => {
                let nd = [dd[0].max(d[0]), dd[1].max(d[1])];
                let l = if d[0] > dd[0] + 1e-12 || d[1] > dd[1] + 1e-12 {
                    p.source_line.unwrap_or(0)
                } else {
                    line
                };
                (nd, l)
            }
        });
    }
    o.notes.extend(notes);
}

/// Whether the dialect's programs turn (X a diameter, the lathe plane G18 at the start): every
/// control's but Dyna's, a mill.
fn lathe_dialect(d: Dialect) -> bool {
    match d {
        Dialect::Fanuc
        | Dialect::Haas
        | Dialect::Sinumerik
        | Dialect::LinuxCnc
        | Dialect::Okuma
        | Dialect::Mitsubishi
        | Dialect::Mazak
        | Dialect::Heidenhain
        | Dialect::Klartext => true,
        Dialect::Dyna => false,
    }
}
