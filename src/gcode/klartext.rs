//! Heidenhain Klartext (TNC conversational) programs, read for the threads a machining centre
//! makes: the drilling cycles 200, 201, 203 and 205 and the tapping cycles 206, 207 and 209 at
//! every point they are called (`CYCL CALL`, `CYCL CALL POS`, `L … M99`, `CYCL CALL PAT` with
//! `PATTERN DEF POS…`, the pattern cycles 220 and 221), the thread-milling cycles 262–265
//! (inside) and 267 (outside) as the helices they mill, and helices written by hand (`CC`, `CP IPA… IZ…
//! DR±`). Lines `L`, `LP`, `C`, `CR`, `CT`, `CP`, labels and their calls (`CALL LBL n REP k`),
//! Q-parameter arithmetic (`FN 0`–`FN 5`, formulas), `FN 9`–`FN 12` jumps, the datum shift
//! (cycle 7) and rotation (cycle 10). Sources: docs/dialects.md, "Heidenhain Klartext".

use std::collections::HashMap;

use super::expr::{self, Env, Syntax, Value, VarKey};
use super::machine::{MachineReading, MachineType};
use super::{Dialect, HoleCycle, HoleKind, Move, Program, ProgramUnits, ReadOptions, SpindleDir};
use crate::ground::note::{Note, NoteKind};
use crate::standards::Hand;
use crate::Error;

/// A located error before it has its file: line, column, message.
type KErr = (usize, usize, String);

/// One block: its line and the column of its first word (block number and comment gone), its
/// words, and the Q-parameter lines of a cycle definition under it.
#[derive(Debug)]
struct KBlock {
    line: usize,
    col: usize,
    text: String,
    params: Vec<Param>,
}

/// A cycle's parameter line (`Q201=-18 ;DEPTH`): its number, its value as written, its place.
#[derive(Debug)]
struct Param {
    q: u32,
    text: String,
    line: usize,
    col: usize,
}

/// The code of a line: the part before a `;` that is not inside `"…"`.
fn code_of(line: &str) -> &str {
    let mut quoted = false;
    for (i, c) in line.char_indices() {
        match c {
            '"' => quoted = !quoted,
            ';' if !quoted => return &line[..i],
            _ => {}
        }
    }
    line
}

/// `Q201=-18` at the start of `t`: the parameter's number and the value's offset in `t`.
fn param_head(t: &str) -> Option<(u32, usize)> {
    let rest = t.strip_prefix(['Q', 'q'])?;
    let digits = rest.bytes().take_while(u8::is_ascii_digit).count();
    let after = rest[digits..].trim_start();
    if digits == 0 || !after.starts_with('=') {
        return None;
    }
    let q = rest[..digits].parse().ok()?;
    Some((q, t.len() - after.len() + 1))
}

/// Splits a program into blocks: a numbered line starts one (`18 CYCL DEF 207 …`); a line after
/// one ending in `~`, and an unnumbered `Q…=` line under a `CYCL DEF`, belong to it (the TNC 320
/// listings and the newer files); `* -` lines and `;` comments are comments.
fn blocks(text: &str) -> Result<Vec<KBlock>, KErr> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut out: Vec<KBlock> = Vec::new();
    let mut continued = false;
    for (i, raw) in text.split('\n').enumerate() {
        let ln = i + 1;
        let line = raw.strip_suffix('\r').unwrap_or(raw);
        let code = code_of(line).trim_end();
        let (code, tilde) = match code.strip_suffix('~') {
            Some(c) => (c.trim_end(), true),
            None => (code, false),
        };
        let lead = code.len() - code.trim_start().len();
        let t = code.trim_start();
        let was_continued = continued;
        continued = tilde;
        if t.is_empty() {
            continued = was_continued || tilde;
            continue;
        }
        let digits = t.bytes().take_while(u8::is_ascii_digit).count();
        let numbered = digits > 0 && t[digits..].starts_with([' ', '\t']);
        let (body, col) = if numbered {
            let b = t[digits..].trim_start();
            (b, lead + (t.len() - b.len()) + 1)
        } else {
            (t, lead + 1)
        };
        // `*` lines are comments; so is a block number with only a comment after it (`1 ; …`).
        if body.starts_with('*') || !numbered && t.bytes().all(|c| c.is_ascii_digit()) {
            continue;
        }
        let under_def = out.last().is_some_and(|b| b.text.starts_with("CYCL DEF"));
        if !numbered && (was_continued || under_def) && !out.is_empty() {
            let Some(last) = out.last_mut() else { continue };
            if let Some((q, at)) = param_head(body) {
                last.params.push(Param { q, text: body[at..].trim().to_string(), line: ln, col: col + at });
                continue;
            }
            if was_continued {
                last.text.push(' ');
                last.text.push_str(body);
                continue;
            }
        }
        out.push(KBlock { line: ln, col, text: body.to_string(), params: Vec::new() });
    }
    Ok(out)
}

/// A word of a block: its letters, its value as written (a number, `+Q3`, `-Q3` or nothing),
/// its column.
#[derive(Clone, Debug)]
struct KWord {
    name: String,
    val: String,
    col: usize,
}

/// The words of `text` from byte `from` on (`X+10`, `IZ-1.5`, `DR+`, `R0`, `FMAX`, `F MAX`).
fn words(text: &str, from: usize, col0: usize) -> Vec<KWord> {
    let mut out: Vec<KWord> = Vec::new();
    let mut i = from;
    let b = text.as_bytes();
    while i < b.len() {
        if b[i] == b' ' || b[i] == b'\t' {
            i += 1;
            continue;
        }
        let start = i;
        while i < b.len() && b[i] != b' ' && b[i] != b'\t' {
            i += 1;
        }
        let tok = &text[start..i];
        let letters = tok.bytes().take_while(u8::is_ascii_alphabetic).count();
        let (name, val) = tok.split_at(letters);
        // `F MAX`: one word.
        if name == "MAX" && val.is_empty() {
            if let Some(last) = out.last_mut().filter(|w| w.name == "F" && w.val.is_empty()) {
                last.name = "FMAX".into();
                continue;
            }
        }
        out.push(KWord { name: name.to_ascii_uppercase(), val: val.to_string(), col: col0 + start });
    }
    out
}

/// Where Q-parameters live.
struct QVars<'a>(&'a HashMap<i64, f64>);

impl Env for QVars<'_> {
    fn get(&mut self, key: &VarKey) -> Result<Value, String> {
        match key {
            VarKey::Num(n) => Ok(Some(self.0.get(n).copied().unwrap_or(0.0))),
            VarKey::Named(n) => Err(format!("{n} is not a Q-parameter")),
        }
    }

    fn exists(&mut self, _: &VarKey) -> bool {
        false
    }
}

/// A cycle as its `CYCL DEF` defines it.
#[derive(Clone, Debug)]
struct CycleDef {
    number: u32,
    name: String,
    q: HashMap<u32, f64>,
    line: usize,
    col: usize,
}

impl CycleDef {
    fn get(&self, q: u32) -> Option<f64> {
        self.q.get(&q).copied()
    }
}

/// What a cycle number makes: a hole (drilled or tapped), a milled thread, or nothing threadcheck
/// checks.
enum CycleKind {
    Drill,
    /// Floating-holder tapping (206): the feed Q206 per minute.
    TapFloating,
    /// Rigid tapping (207, 209): the pitch Q239, its sign the hand.
    TapRigid,
    /// Thread milling: 262 inside, 267 outside.
    Mill {
        external: bool,
    },
}

fn cycle_kind(n: u32) -> Option<CycleKind> {
    match n {
        200 | 201 | 203 | 205 => Some(CycleKind::Drill),
        206 => Some(CycleKind::TapFloating),
        207 | 209 => Some(CycleKind::TapRigid),
        // 263 (with countersinking), 264 (with drilling) and 265 (helical, drilling with it):
        // their thread read as 262's with one helix over the depth; the rest is not modelled.
        262..=265 => Some(CycleKind::Mill { external: false }),
        267 => Some(CycleKind::Mill { external: true }),
        _ => None,
    }
}

/// The reading state.
struct St<'a> {
    file: &'a str,
    scale: f64,
    units_set: bool,
    /// Position in program coordinates, and which axes are known.
    pos: [f64; 3],
    known: [bool; 3],
    cc: Option<[f64; 2]>,
    /// The direction of the last move's end (for `CT`).
    tangent: Option<[f64; 2]>,
    comp: u8,
    /// The rotary axes A, B, C as last written (degrees; 0 until written).
    rotary: [f64; 3],
    /// The feed the last TOOL CALL gave (its F), mm/min: what a cycle's FAUTO takes.
    tool_feed: Option<f64>,
    /// The feed in force for contour moves (F in mm/min, or FAUTO's tool call feed).
    feed: Option<f64>,
    /// Cycle parameters written as a feed word that is not a number (`Q206=FMAX`): where.
    symbolic: HashMap<u32, (usize, usize, String)>,
    tool: Option<u32>,
    spindle: Option<f64>,
    dir: Option<SpindleDir>,
    q: HashMap<i64, f64>,
    cycle: Option<CycleDef>,
    /// Datum shift (program units, mm after scale) and rotation (degrees).
    shift: [f64; 3],
    rot_deg: f64,
    pattern: Option<(Vec<[f64; 3]>, usize)>,
    holes: Vec<HoleCycle>,
    moves: Vec<Move>,
    notes: Vec<Note>,
    /// What was read past (each named once), the blocks that held it, and the last such line.
    past: std::collections::HashSet<String>,
    read_past_blocks: usize,
    past_last_line: usize,
    /// The first line at which the toolpath passed its bound (the program is refused there).
    moves_overflow: Option<usize>,
    stock_bottom: Option<(f64, usize)>,
}

impl St<'_> {
    fn note(&mut self, line: usize, col: usize, msg: String) {
        self.notes.push(Note::at(self.file, line, col, msg));
    }

    fn read_past(&mut self, line: usize, col: usize, what: &str, why: &str) {
        if self.past_last_line != line {
            self.read_past_blocks += 1;
            self.past_last_line = line;
        }
        if !self.past.insert(what.to_string()) {
            return;
        }
        self.notes.push(
            Note::at(self.file, line, col, format!("{what} read past: {why}")).of_kind(NoteKind::ReadPast),
        );
    }

    /// A value as written (`+10`, `-Q3`, `Q3`), in program units.
    fn value(&self, w: &KWord, line: usize) -> Result<f64, KErr> {
        let v = w.val.trim();
        let (neg, body) = match v.strip_prefix('-') {
            Some(b) => (true, b),
            None => (false, v.strip_prefix('+').unwrap_or(v)),
        };
        let x = if let Some(n) = body.strip_prefix(['Q', 'q']) {
            let n: i64 = n
                .parse()
                .map_err(|_| (line, w.col, format!("{}{}: Q needs a parameter number", w.name, w.val)))?;
            self.q.get(&n).copied().unwrap_or(0.0)
        } else {
            match body.parse::<f64>() {
                Ok(x) if x.is_finite() && !body.is_empty() && !body.starts_with(['+', '-']) => x,
                _ => {
                    return Err((
                        line,
                        w.col,
                        format!("{}{}: {} needs a number or a Q-parameter", w.name, w.val, w.name),
                    ))
                }
            }
        };
        Ok(if neg { -x } else { x })
    }

    fn len(&self, w: &KWord, line: usize) -> Result<f64, KErr> {
        Ok(self.value(w, line)? * self.scale)
    }

    /// A point in program coordinates to the workpiece's: rotated about the shifted datum, then
    /// shifted.
    fn to_work(&self, p: [f64; 3]) -> [f64; 3] {
        let (s, c) = self.rot_deg.to_radians().sin_cos();
        [self.shift[0] + c * p[0] - s * p[1], self.shift[1] + s * p[0] + c * p[1], self.shift[2] + p[2]]
    }

    fn push_move(&mut self, rapid: bool, to: [f64; 3], arc: Option<([f64; 2], f64, u32)>, line: usize) {
        let from = self.pos;
        if self.moves.len() >= crate::ground::bounds::MAX_IMPRINTS {
            self.moves_overflow.get_or_insert(line);
        } else if self.known.iter().all(|k| *k) {
            let a = self.to_work(from);
            let b = self.to_work(to);
            let arc_w = arc.map(|(c, d, _)| {
                let cw = self.to_work([c[0], c[1], 0.0]);
                ([cw[0], cw[1]], d)
            });
            self.moves.push(Move {
                rapid,
                from: a,
                to: b,
                arc: arc_w,
                line,
                comp: self.comp,
                tool: self.tool,
                extra_turns: arc.map_or(0, |a| a.2),
                units: ProgramUnits::of_scale(self.scale),
                feed: if rapid { None } else { self.feed },
                spindle: self.spindle,
            });
        }
        self.tangent = match arc {
            None => {
                let d = [to[0] - from[0], to[1] - from[1]];
                let n = d[0].hypot(d[1]);
                (n > 1e-12).then(|| [d[0] / n, d[1] / n]).or(self.tangent)
            }
            Some((c, dir, _)) => {
                let r = [to[0] - c[0], to[1] - c[1]];
                let n = r[0].hypot(r[1]).max(1e-12);
                Some([-dir * r[1] / n, dir * r[0] / n])
            }
        };
        self.pos = to;
        self.known = [true; 3];
    }
}

/// Control flow after a block.
enum Flow {
    Next,
    Jump(usize),
    Call(usize),
    Return,
    End,
}

/// Reads a Klartext program.
pub(crate) fn read(
    text: &str,
    file: &str,
    opts: &ReadOptions,
    out: Option<std::sync::mpsc::SyncSender<Vec<Move>>>,
) -> Result<Program, Error> {
    let perr =
        |(line, column, message): KErr| Error::Program { file: file.to_string(), line, column, message };
    let bl = blocks(text).map_err(perr)?;
    let mut labels: HashMap<String, usize> = HashMap::new();
    for (k, b) in bl.iter().enumerate() {
        if let Some(rest) = b.text.strip_prefix("LBL ") {
            let name = rest.trim().trim_matches('"').to_string();
            if name != "0" && labels.insert(name.clone(), k).is_some() {
                return Err(perr((b.line, b.col, format!("LBL {name} is defined twice"))));
            }
        }
    }
    let mut st = St {
        file,
        scale: opts.default_units.map_or(1.0, |u| u.mm()),
        units_set: false,
        pos: [0.0; 3],
        known: [false; 3],
        rotary: [0.0; 3],
        tool_feed: None,
        feed: None,
        symbolic: HashMap::new(),
        cc: None,
        tangent: None,
        comp: 0,
        tool: None,
        spindle: None,
        dir: None,
        q: HashMap::new(),
        cycle: None,
        shift: [0.0; 3],
        rot_deg: 0.0,
        pattern: None,
        holes: Vec::new(),
        moves: Vec::new(),
        notes: Vec::new(),
        past: std::collections::HashSet::new(),
        read_past_blocks: 0,
        past_last_line: 0,
        moves_overflow: None,
        stock_bottom: None,
    };
    let budget = opts.budget.unwrap_or_default();
    let mut executed = 0usize;
    let mut backward = 0usize;
    let mut stack: Vec<usize> = Vec::new();
    let mut repeats: HashMap<usize, u32> = HashMap::new();
    let mut pc = 0usize;
    while pc < bl.len() {
        executed += 1;
        // A request no longer wanted (the server's time budget) stops here, as the interpreter's.
        if executed % 4096 == 0 {
            crate::ground::cancel::check()?;
        }
        if executed > budget.blocks {
            return Err(perr((
                bl[pc].line,
                bl[pc].col,
                format!("the program runs more than {} blocks", budget.blocks),
            )));
        }
        let b = &bl[pc];
        let flow = block(&mut st, b, pc, &bl, &labels, &mut repeats, &stack).map_err(perr)?;
        let next = match flow {
            Flow::Next => pc + 1,
            Flow::Jump(to) => to,
            Flow::Call(to) => {
                if stack.len() >= 8 {
                    return Err(perr((
                        b.line,
                        b.col,
                        "labels called more than 8 deep (the TNC's limit)".into(),
                    )));
                }
                stack.push(pc + 1);
                to
            }
            Flow::Return => stack.pop().unwrap_or(pc + 1),
            Flow::End => break,
        };
        if next <= pc {
            backward += 1;
            if backward > budget.backward_jumps {
                return Err(perr((
                    b.line,
                    b.col,
                    format!("more than {} jumps back: a loop that does not end?", budget.backward_jumps),
                )));
            }
        }
        pc = next;
    }
    if let Some(line) = st.moves_overflow {
        return Err(perr((
            line,
            1,
            format!("the program moves more than {} times", crate::ground::bounds::MAX_IMPRINTS),
        )));
    }
    let notes_units = (!st.units_set).then(|| {
        format!(
            "{file}:1: the program has no BEGIN PGM … MM|INCH line: read in {}",
            if st.scale == 1.0 { "mm" } else { "inches" }
        )
    });
    let mut notes = vec![Note::from(
        "read as Heidenhain Klartext (TNC conversational) on a machining centre: X and Y in the plane, Z the tool axis",
    )];
    notes.extend(notes_units.map(Note::from));
    notes.append(&mut st.notes);
    if !opts.allow_no_threading {
        // A turning check (the passes of a lathe's thread): a Klartext program turns none.
        let mut why =
            format!("no threading pass in the program (looked for {})", Dialect::Klartext.threading_words());
        let mut place = (1, 1);
        if let Some(h) = st.holes.iter().find(|h| h.kind == HoleKind::Tap) {
            place = (h.line, h.column);
            why.push_str(&format!(
                "; {} taps a hole: threadcheck tap (or verify) checks tapping cycles",
                h.code
            ));
        } else if let Some(m) =
            st.moves.iter().find(|m| m.arc.is_some() && (m.from[2] - m.to[2]).abs() > 1e-9)
        {
            place = (m.line, 1);
            why.push_str("; it mills a helix: threadcheck thread-mill (or verify) checks milled threads");
        }
        return Err(perr((place.0, place.1, why)));
    }
    let mut moves = std::mem::take(&mut st.moves);
    if let Some(out) = out {
        let _ = out.send(std::mem::take(&mut moves));
    }
    Ok(Program {
        passes: Vec::new(),
        operations: Vec::new(),
        skipped_blocks: 0,
        read_past_blocks: st.read_past_blocks,
        notes,
        moves,
        holes: st.holes,
        machine: MachineReading {
            machine_type: MachineType::Mill,
            reason: "a Heidenhain Klartext program: read as a machining centre's (TNC), X and Y in the plane, Z the tool axis".into(),
        },
        stock: None,
        stock_bottom: st.stock_bottom,
        control: Vec::new(),
    })
}

/// Runs one block.
#[allow(clippy::too_many_arguments)]
fn block(
    st: &mut St<'_>,
    b: &KBlock,
    pc: usize,
    all: &[KBlock],
    labels: &HashMap<String, usize>,
    repeats: &mut HashMap<usize, u32>,
    stack: &[usize],
) -> Result<Flow, KErr> {
    let t = b.text.as_str();
    let up = t.to_ascii_uppercase();
    let first = up.split_whitespace().next().unwrap_or("");
    match first {
        "BEGIN" => {
            if up.split_whitespace().any(|w| w == "INCH") {
                st.scale = 25.4;
            } else if up.split_whitespace().any(|w| w == "MM") {
                st.scale = 1.0;
            } else {
                return Err((b.line, b.col, "BEGIN PGM needs its unit, MM or INCH, after the name".into()));
            }
            st.units_set = true;
            return Ok(Flow::Next);
        }
        "END" => return Ok(if stack.is_empty() { Flow::End } else { Flow::Return }),
        "BLK" => {
            // BLK FORM 0.1 Z X… Y… Z… (the minimum point), 0.2 X… Y… Z… (the maximum).
            let ws = words(t, 0, b.col);
            if ws.len() >= 3 && ws[2].val == "0.1" {
                if ws.get(3).is_some_and(|w| w.name != "Z" || !w.val.is_empty()) {
                    let w = &ws[3];
                    return Err((
                        b.line,
                        w.col,
                        format!("BLK FORM 0.1 {}{}: only the tool axis Z is read", w.name, w.val),
                    ));
                }
                let mut min = [0.0; 3];
                for w in ws.iter().skip(4) {
                    let k = axis(&w.name).ok_or((
                        b.line,
                        w.col,
                        format!("BLK FORM: {} is not X, Y or Z", w.name),
                    ))?;
                    min[k] = st.len(w, b.line)?;
                }
                st.stock_bottom = Some((st.to_work(min)[2], b.line));
            } else if !(ws.len() >= 3 && ws[2].val == "0.2") {
                st.read_past(
                    b.line,
                    b.col,
                    "BLK FORM",
                    "a stock form threadcheck does not read (BLK FORM 0.1 and 0.2 are)",
                );
            }
            return Ok(Flow::Next);
        }
        "TOOL" => return tool(st, b, &up),
        "L" | "LP" | "C" | "CR" | "CT" | "CP" | "CC" => return path(st, b, first),
        "RND" | "CHF" => {
            st.read_past(b.line, b.col, first, "a corner's rounding or chamfer: the corner is read sharp");
            return Ok(Flow::Next);
        }
        "APPR" | "DEP" => return approach(st, b, first),
        "LBL" => {
            let name = t[3..].trim().trim_matches('"');
            if name == "0" {
                return Ok(if stack.is_empty() { Flow::Next } else { Flow::Return });
            }
            return Ok(Flow::Next);
        }
        "CALL" => return call(st, b, &up, pc, all, labels, repeats),
        "FN" => return fn_block(st, b, &up, labels),
        "CYCL" => return cycle(st, b, &up),
        "PATTERN" => return pattern(st, b, &up),
        "PLANE" => {
            let ok = up.contains("RESET")
                || (up.contains("SPATIAL")
                    && ["SPA", "SPB", "SPC"].iter().all(|a| {
                        up.split_whitespace().find(|w| w.starts_with(a)).is_some_and(|w| {
                            w[3..].trim_start_matches(['+', '-']).parse::<f64>().is_ok_and(|v| v == 0.0)
                        })
                    }));
            if !ok {
                return Err((b.line, b.col, "PLANE tilts the working plane: a thread's axis that is not Z is not read (PLANE RESET and PLANE SPATIAL SPA0 SPB0 SPC0 are)".into()));
            }
            st.read_past(
                b.line,
                b.col,
                "PLANE",
                "an untilted working plane (all angles 0): Z stays the tool axis",
            );
            return Ok(Flow::Next);
        }
        // A TNC 640 that turns (option 50): its turning cycles are not read.
        "FUNCTION" if up.contains("MODE TURN") => {
            return Err((
                b.line,
                b.col,
                "FUNCTION MODE TURN: turning on a TNC (its turning cycles and diameters) is not read; the milling blocks are".into(),
            ))
        }
        "STOP" => {
            let ws = words(t, 4, b.col);
            return m_words(st, b, &ws).map(|end| if end { Flow::End } else { Flow::Next });
        }
        _ => {}
    }
    if param_head(t).is_some() {
        assign(st, b, t)?;
        return Ok(Flow::Next);
    }
    // A block of M words alone (`M3`, `M5 M9`): the spindle's direction and the program's end
    // are read, as in an L block (it was read past while the tapping check used its M3).
    let ws = words(t, 0, b.col);
    if !ws.is_empty() && ws.iter().all(|w| w.name == "M") {
        return m_words(st, b, &ws).map(|end| if end { Flow::End } else { Flow::Next });
    }
    st.read_past(b.line, b.col, first, "a Klartext block threadcheck does not model");
    Ok(Flow::Next)
}

/// `X`, `Y`, `Z` (absolute) and `IX`, `IY`, `IZ` (incremental): the axis and whether it is an
/// increment.
fn axis_word(name: &str) -> Option<(usize, bool)> {
    match name.strip_prefix('I') {
        Some(rest) => axis(rest).map(|k| (k, true)),
        None => axis(name).map(|k| (k, false)),
    }
}

fn axis(name: &str) -> Option<usize> {
    match name {
        "X" => Some(0),
        "Y" => Some(1),
        "Z" => Some(2),
        _ => None,
    }
}

/// M words: the spindle's direction, the program's end. Returns whether the program ends.
fn m_words(st: &mut St<'_>, b: &KBlock, ws: &[KWord]) -> Result<bool, KErr> {
    let mut end = false;
    for w in ws.iter().filter(|w| w.name == "M") {
        let m = st.value(w, b.line)?;
        match m as i64 {
            3 | 13 => st.dir = Some(SpindleDir::Cw),
            4 | 14 => st.dir = Some(SpindleDir::Ccw),
            5 | 0 => st.dir = Some(SpindleDir::Stopped),
            2 | 30 => end = true,
            89 => {
                return Err((b.line, w.col, "M89 (a modal cycle call) is not read: call the cycle with M99, CYCL CALL or CYCL CALL PAT at each point".into()))
            }
            _ => {}
        }
    }
    Ok(end)
}

/// `TOOL CALL 5 Z S1200`, `TOOL CALL "TAP M8" Z S600`.
fn tool(st: &mut St<'_>, b: &KBlock, up: &str) -> Result<Flow, KErr> {
    if !up.starts_with("TOOL CALL") {
        st.read_past(b.line, b.col, "TOOL DEF", "a tool's preparation: the tool changes at TOOL CALL");
        return Ok(Flow::Next);
    }
    let rest = &b.text[9..];
    let lead = rest.len() - rest.trim_start().len();
    let r = rest.trim_start();
    let mut from = 9 + lead;
    if let Some(q) = r.strip_prefix('"') {
        let close = q.find('"').ok_or((
            b.line,
            b.col + from,
            "TOOL CALL \"…: the name has no closing '\"'".to_string(),
        ))?;
        st.tool = None;
        st.read_past(b.line, b.col + from, "TOOL CALL \"name\"", "a tool called by name: its number is not known; its name is read as a comment is, for the tap's or drill's size (`TOOL CALL \"TAP M8X1.25\"`)");
        from += close + 2;
    } else {
        let n = r.bytes().take_while(u8::is_ascii_digit).count();
        if n == 0 {
            // `TOOL CALL Z S…`: the tool in the spindle, a new speed.
        } else {
            let v: u32 = r[..n]
                .parse()
                .map_err(|_| (b.line, b.col + from, "TOOL CALL: the tool number is too large".to_string()))?;
            st.tool = Some(v);
            from += n;
        }
    }
    let ws = words(&b.text, from, b.col);
    st.tool_feed = None;
    for (k, w) in ws.iter().enumerate() {
        match w.name.as_str() {
            "Z" if w.val.is_empty() => {}
            "X" | "Y" if w.val.is_empty() && k == 0 => {
                return Err((
                    b.line,
                    w.col,
                    format!(
                        "TOOL CALL … {}: the tool axis is {}; only Z (a vertical spindle, G17) is read",
                        w.name, w.name
                    ),
                ))
            }
            "S" => st.spindle = Some(st.value(w, b.line)?),
            "F" => {
                st.tool_feed = Some(st.len(w, b.line)?);
            }
            "DL" | "DR" | "DR2" if st.value(w, b.line)? != 0.0 => {
                st.read_past(
                    b.line,
                    w.col,
                    &format!("TOOL CALL {}", w.name),
                    "a delta of the tool's length or radius, not modelled: the tool table's values are taken",
                );
            }
            _ => {}
        }
    }
    Ok(Flow::Next)
}

/// The lines and arcs: `L`, `LP`, `C`, `CR`, `CT`, `CP`, and the pole `CC`.
fn path(st: &mut St<'_>, b: &KBlock, kind: &str) -> Result<Flow, KErr> {
    let ws = words(&b.text, kind.len(), b.col);
    let PathWords { target, given, rapid, dr, radius, pr, pa, ipa, ipr, m99, mb, machine } =
        path_words(st, b, kind, &ws)?;
    if kind == "CC" {
        // The pole: the point given, or the position when none is.
        let c = if given[0] || given[1] {
            [target[0], target[1]]
        } else {
            if !(st.known[0] && st.known[1]) {
                return Err((
                    b.line,
                    b.col,
                    "CC without X and Y takes the position, which the program has not set".into(),
                ));
            }
            [st.pos[0], st.pos[1]]
        };
        st.cc = Some(c);
        return Ok(Flow::Next);
    }
    let ends = m_words(st, b, &ws)?;
    if let Some(col) = mb {
        // The retract's height is the machine's (MAX: the travel limit): Z unknown until the
        // program sets it again; nothing is cut on the way.
        st.known[2] = false;
        st.read_past(b.line, col, "M140 MB", "a retract along the tool axis (MB MAX: to the travel limit); Z is taken as unknown until the program sets it");
        return Ok(if ends { Flow::End } else { Flow::Next });
    }
    if let Some((col, code)) = machine {
        // Positions in the machine's coordinates: not the program's, so unknown after it.
        for (known, given) in st.known.iter_mut().zip(given) {
            if given {
                *known = false;
            }
        }
        st.read_past(b.line, col, &format!("M{code}"), "a move in machine coordinates (M91: the machine datum, M92: the machine's reference point): the axes it moves are taken as unknown until the program sets them");
        return Ok(if ends { Flow::End } else { Flow::Next });
    }
    path_move(
        st,
        b,
        kind,
        &PathWords { target, given, rapid, dr, radius, pr, pa, ipa, ipr, m99, mb, machine },
    )?;
    if let Some(col) = m99 {
        let here = st.pos;
        run_cycle(st, here, b.line, col, None)?;
    }
    Ok(if ends { Flow::End } else { Flow::Next })
}

/// What a path block's words give: the target, which axes it names, rapid, the arc's direction,
/// radius and polar words, an M99, a retract (MB) and a machine-coordinate M91/M92.
struct PathWords {
    target: [f64; 3],
    given: [bool; 3],
    rapid: bool,
    dr: Option<f64>,
    radius: Option<f64>,
    pr: Option<f64>,
    pa: Option<f64>,
    ipa: Option<f64>,
    ipr: Option<f64>,
    m99: Option<usize>,
    mb: Option<usize>,
    machine: Option<(usize, String)>,
}

/// A path block's words read (rotary axes, feeds and compensation set on the way).
fn path_words(st: &mut St<'_>, b: &KBlock, kind: &str, ws: &[KWord]) -> Result<PathWords, KErr> {
    let mut target = st.pos;
    let mut given = [false; 3];
    let (mut rapid, mut dr, mut radius, mut pr, mut pa, mut ipa, mut ipr) =
        (false, None, None, None, None, None, None);
    let mut m99 = None;
    // `M140 MB MAX` / `MB+50`: the retract along the tool axis; M91/M92: machine coordinates.
    let (mut mb, mut machine) = (None, None);
    for (i, w) in ws.iter().enumerate() {
        if w.name == "MAX" && i > 0 && ws[i - 1].name == "MB" && ws[i - 1].val.is_empty() {
            continue;
        }
        if let Some(k) = ["A", "B", "C"].iter().position(|a| *a == w.name).filter(|_| kind == "L") {
            st.rotary[k] = st.value(w, b.line)?;
            continue;
        }
        if let Some(k) = ["IA", "IB", "IC"].iter().position(|a| *a == w.name).filter(|_| kind == "L") {
            st.rotary[k] += st.value(w, b.line)?;
            continue;
        }
        if w.name == "MB" {
            mb = Some(w.col);
            if !w.val.is_empty() {
                st.len(w, b.line)?;
            }
            continue;
        }
        if w.name == "M" && matches!(w.val.as_str(), "91" | "92") {
            machine = Some((w.col, w.val.clone()));
        }
        if let Some((k, inc)) = axis_word(&w.name) {
            let v = st.len(w, b.line)?;
            if inc {
                if !st.known[k] {
                    return Err((
                        b.line,
                        w.col,
                        format!("{}{}: an increment from a position the program has not set", w.name, w.val),
                    ));
                }
                target[k] = st.pos[k] + v;
            } else {
                target[k] = v;
            }
            given[k] = true;
            continue;
        }
        match w.name.as_str() {
            "FMAX" => rapid = true,
            "F" if w.val.is_empty() => return Err((b.line, w.col, "F needs a feed".into())),
            "F" => {
                st.feed = Some(st.len(w, b.line)?);
            }
            // The tool call's feed; per revolution and per tooth are not modelled: unknown.
            "FAUTO" => st.feed = st.tool_feed,
            "FU" | "FZ" => st.feed = None,
            "R" if kind == "CR" => radius = Some(st.len(w, b.line)?),
            "R" if w.val == "0" => st.comp = 0,
            "RL" => st.comp = 1,
            "RR" => st.comp = 2,
            "DR" => {
                dr = Some(match w.val.as_str() {
                    "+" => 1.0,
                    "-" => -1.0,
                    _ => return Err((b.line, w.col, format!("DR{}: DR+ or DR-", w.val))),
                })
            }
            "PR" => pr = Some(st.len(w, b.line)?),
            "IPR" => ipr = Some(st.len(w, b.line)?),
            "PA" => pa = Some(st.value(w, b.line)?),
            "IPA" => ipa = Some(st.value(w, b.line)?),
            "M" => {
                if st.value(w, b.line)? == 99.0 {
                    m99 = Some(w.col);
                }
            }
            other => {
                return Err((
                    b.line,
                    w.col,
                    format!("{kind} … {other}{}: a word {kind} does not take", w.val),
                ))
            }
        }
    }
    Ok(PathWords { target, given, rapid, dr, radius, pr, pa, ipa, ipr, m99, mb, machine })
}

/// A path block's move: a line (L, LP) or an arc (C, CP, CR, CT) from the position.
fn path_move(st: &mut St<'_>, b: &KBlock, kind: &str, pw: &PathWords) -> Result<(), KErr> {
    let &PathWords { target, given, rapid, dr, radius, pr, pa, ipa, ipr, .. } = pw;
    let needs_pos = |st: &St<'_>| -> Result<(), KErr> {
        if st.known[0] && st.known[1] {
            Ok(())
        } else {
            Err((b.line, b.col, format!("{kind}: an arc from a position the program has not set")))
        }
    };
    let pole = |st: &St<'_>| st.cc.ok_or((b.line, b.col, format!("{kind} needs a pole: CC before it")));
    match kind {
        "L" => {
            if !given.iter().any(|g| *g) {
                // `L M3`, `L FMAX M99`: no move.
            } else {
                for k in 0..3 {
                    if given[k] && !st.known[k] {
                        st.pos[k] = target[k];
                        st.known[k] = true;
                    }
                }
                if st.known.iter().all(|k| *k) {
                    st.push_move(rapid, target, None, b.line);
                } else {
                    st.pos = target;
                }
            }
        }
        "LP" => {
            let c = pole(st)?;
            needs_pos(st)?;
            let (r0, a0) = polar(st.pos, c);
            let r = pr.unwrap_or(r0) + ipr.unwrap_or(0.0);
            let a = pa.unwrap_or(a0) + ipa.unwrap_or(0.0);
            let to = [c[0] + r * a.to_radians().cos(), c[1] + r * a.to_radians().sin(), target[2]];
            st.push_move(rapid, to, None, b.line);
        }
        "C" | "CP" => {
            let c = pole(st)?;
            needs_pos(st)?;
            let d = dr.ok_or((b.line, b.col, format!("{kind} needs its direction, DR+ or DR-")))?;
            let (r, a0) = polar(st.pos, c);
            if r < 1e-9 {
                return Err((
                    b.line,
                    b.col,
                    format!("{kind}: the position is on the pole, so the arc has no radius"),
                ));
            }
            let sweep = if kind == "CP" {
                match (pa, ipa) {
                    (_, Some(i)) => {
                        if i * d < 0.0 {
                            return Err((
                                b.line,
                                b.col,
                                format!(
                                    "CP IPA{i:+} DR{}: IPA and DR must have the same sign",
                                    if d > 0.0 { "+" } else { "-" }
                                ),
                            ));
                        }
                        if i.abs() > 5400.0 {
                            return Err((b.line, b.col, format!("CP IPA{i}: the TNC takes at most ±5400°")));
                        }
                        i
                    }
                    (Some(p), None) => swept(a0, p, d),
                    (None, None) => return Err((b.line, b.col, "CP needs PA or IPA".into())),
                }
            } else {
                let end = [target[0], target[1]];
                let (re, ae) = polar([end[0], end[1], 0.0], c);
                if (re - r).abs() > 0.001 * st.scale.max(1.0) {
                    return Err((
                        b.line,
                        b.col,
                        format!("C: the end point is {:.4} mm from the pole, the start {:.4} mm", re, r),
                    ));
                }
                let s = swept(a0, ae, d);
                if s.abs() < 1e-9 {
                    360.0 * d
                } else {
                    s
                }
            };
            let ae = a0 + sweep;
            let to = [c[0] + r * ae.to_radians().cos(), c[1] + r * ae.to_radians().sin(), target[2]];
            let turns = (sweep.abs() / 360.0 - 1e-9).floor().max(0.0) as u32;
            st.push_move(false, to, Some((c, d, turns)), b.line);
        }
        "CR" => {
            needs_pos(st)?;
            let d = dr.ok_or((b.line, b.col, "CR needs its direction, DR+ or DR-".to_string()))?;
            let rr = radius.ok_or((b.line, b.col, "CR needs its radius R".to_string()))?;
            let (p, q) = ([st.pos[0], st.pos[1]], [target[0], target[1]]);
            let chord = [q[0] - p[0], q[1] - p[1]];
            let l = chord[0].hypot(chord[1]);
            if l < 1e-9 || l > 2.0 * rr.abs() + 1e-9 {
                return Err((
                    b.line,
                    b.col,
                    format!("CR R{rr}: no arc of that radius joins the points ({l:.4} mm apart)"),
                ));
            }
            let h = (rr * rr - l * l / 4.0).max(0.0).sqrt();
            // Left of the chord for a short counter-clockwise arc.
            let n = [-chord[1] / l, chord[0] / l];
            let side = d * rr.signum();
            let c = [p[0] + chord[0] / 2.0 + side * h * n[0], p[1] + chord[1] / 2.0 + side * h * n[1]];
            st.push_move(false, target, Some((c, d, 0)), b.line);
        }
        "CT" => {
            needs_pos(st)?;
            let t =
                st.tangent.ok_or((b.line, b.col, "CT: no move before it gives the tangent".to_string()))?;
            let (p, q) = ([st.pos[0], st.pos[1]], [target[0], target[1]]);
            let v = [q[0] - p[0], q[1] - p[1]];
            let n = [-t[1], t[0]];
            let along = v[0] * n[0] + v[1] * n[1];
            if along.abs() < 1e-9 {
                return Err((
                    b.line,
                    b.col,
                    "CT: the end point lies on the tangent, so no arc is tangent there".into(),
                ));
            }
            let r = (v[0] * v[0] + v[1] * v[1]) / (2.0 * along);
            let c = [p[0] + r * n[0], p[1] + r * n[1]];
            st.push_move(false, target, Some((c, r.signum(), 0)), b.line);
        }
        _ => unreachable!("path kinds"),
    }
    Ok(())
}

/// Radius and angle (degrees) of `p` about `c`.
fn polar(p: [f64; 3], c: [f64; 2]) -> (f64, f64) {
    let (dx, dy) = (p[0] - c[0], p[1] - c[1]);
    (dx.hypot(dy), dy.atan2(dx).to_degrees())
}

/// The angle swept from `a0` to `a1` in direction `d` (+1 counter-clockwise), in (0, 360].
fn swept(a0: f64, a1: f64, d: f64) -> f64 {
    let mut s = (a1 - a0) * d;
    s = s.rem_euclid(360.0);
    d * s
}

/// `APPR`/`DEP`: read as a straight move to the point they name (the contour's first point, or
/// the point after it), said in a note: their tangential arcs are not modelled.
fn approach(st: &mut St<'_>, b: &KBlock, kind: &str) -> Result<Flow, KErr> {
    let ws = words(&b.text, kind.len(), b.col);
    let mut target = st.pos;
    let mut any = false;
    let (mut pr, mut pa) = (None, None);
    for w in ws.iter().skip(1) {
        if let Some((k, false)) = axis_word(&w.name) {
            target[k] = st.len(w, b.line)?;
            any = true;
            continue;
        }
        match w.name.as_str() {
            "PR" => pr = Some(st.len(w, b.line)?),
            "PA" => pa = Some(st.value(w, b.line)?),
            "RL" => st.comp = 1,
            "RR" => st.comp = 2,
            "R" if w.val == "0" => st.comp = 0,
            "F" if !w.val.is_empty() => {
                st.len(w, b.line)?;
            }
            _ => {}
        }
    }
    if let (Some(r), Some(a), Some(c)) = (pr, pa, st.cc) {
        target[0] = c[0] + r * a.to_radians().cos();
        target[1] = c[1] + r * a.to_radians().sin();
        any = true;
    }
    st.read_past(
        b.line,
        b.col,
        kind,
        "an approach or departure, read as a straight feed to the point it names (its tangential arc is not modelled)",
    );
    if any && st.known.iter().all(|k| *k) {
        st.push_move(false, target, None, b.line);
    }
    Ok(Flow::Next)
}

/// `CALL LBL n [REP k]`: a section repeat (the label before the call, no `LBL 0` between) or a
/// subprogram call (to `LBL 0`).
fn call(
    st: &mut St<'_>,
    b: &KBlock,
    up: &str,
    pc: usize,
    all: &[KBlock],
    labels: &HashMap<String, usize>,
    repeats: &mut HashMap<usize, u32>,
) -> Result<Flow, KErr> {
    let Some(rest) = up.strip_prefix("CALL LBL") else {
        if up.starts_with("CALL PGM") {
            return Err((b.line, b.col, "CALL PGM calls another program's file, which threadcheck does not read for Klartext (write its blocks in this file, or check that file)".into()));
        }
        st.read_past(b.line, b.col, "CALL", "a call threadcheck does not model");
        return Ok(Flow::Next);
    };
    let rest = rest.trim();
    let (name, rep) = match rest.find(" REP") {
        Some(k) => {
            let r = rest[k + 4..].trim();
            let r = r.split('/').next().unwrap_or("").trim();
            let n: u32 = r.parse().ok().filter(|n| (1..=65534).contains(n)).ok_or((
                b.line,
                b.col,
                format!("CALL LBL … REP {r}: REP takes 1 to 65534"),
            ))?;
            (rest[..k].trim(), Some(n))
        }
        None => (rest, None),
    };
    let name = name.trim_matches('"').to_string();
    let &to =
        labels.get(&name).ok_or((b.line, b.col, format!("CALL LBL {name}: no LBL {name} in the program")))?;
    let section = to < pc && !all[to + 1..pc].iter().any(|x| x.text.trim() == "LBL 0");
    match (section, rep) {
        (true, Some(n)) => {
            let left = repeats.entry(pc).or_insert(n);
            if *left == 0 {
                repeats.remove(&pc);
                Ok(Flow::Next)
            } else {
                *left -= 1;
                Ok(Flow::Jump(to + 1))
            }
        }
        (true, None) => Err((
            b.line,
            b.col,
            format!("CALL LBL {name} without REP calls back into the section before it, which runs forever"),
        )),
        (false, None) => Ok(Flow::Call(to + 1)),
        (false, Some(_)) => {
            st.note(b.line, b.col, format!("CALL LBL {name} REP: a subprogram's call with REP runs it once here (the repeat of a section is the label before its call)"));
            Ok(Flow::Call(to + 1))
        }
    }
}

/// `Q5 = (Q1 + 2) / 3`.
fn assign(st: &mut St<'_>, b: &KBlock, t: &str) -> Result<(), KErr> {
    let (q, at) = param_head(t).ok_or((b.line, b.col, "Qn = … expected".to_string()))?;
    let v = eval(st, &t[at..], b.line, b.col + at)?;
    st.q.insert(q as i64, v);
    Ok(())
}

fn eval(st: &St<'_>, text: &str, line: usize, col: usize) -> Result<f64, KErr> {
    let lead = text.len() - text.trim_start().len();
    let e = expr::parse_all(&text.trim().to_ascii_uppercase(), Syntax::Klartext)
        .map_err(|(o, m)| (line, col + lead + o, m))?;
    let v = expr::eval(&e, &mut QVars(&st.q), 0).map_err(|m| (line, col, m))?.unwrap_or(0.0);
    if !v.is_finite() {
        return Err((line, col, format!("{} is not a finite number", text.trim())));
    }
    Ok(v)
}

/// `FN 0: Q1 = +5`, `FN 1:`–`FN 5:` (+, −, ×, DIV, SQRT), `FN 9:`–`FN 12:` (IF … GOTO LBL).
fn fn_block(st: &mut St<'_>, b: &KBlock, up: &str, labels: &HashMap<String, usize>) -> Result<Flow, KErr> {
    let colon = up.find(':').ok_or((b.line, b.col, "FN n: needs its colon".to_string()))?;
    let n: u32 =
        up[2..colon].trim().parse().map_err(|_| (b.line, b.col, "FN n: needs its number".to_string()))?;
    let body = &up[colon + 1..];
    let bcol = b.col + colon + 1;
    match n {
        0..=5 => {
            let (q, at) =
                param_head(body.trim_start()).ok_or((b.line, bcol, format!("FN {n}: Qn = … expected")))?;
            let lead = body.len() - body.trim_start().len();
            let rhs = &body.trim_start()[at..];
            let formula = match n {
                0 => rhs.to_string(),
                4 => rhs.replace("DIV", "/"),
                5 => format!("SQRT({})", rhs.trim().trim_start_matches("SQRT")),
                _ => rhs.to_string(),
            };
            let v = eval(st, &formula, b.line, bcol + lead + at)?;
            st.q.insert(q as i64, v);
            Ok(Flow::Next)
        }
        9..=12 => {
            // IF +Q1 EQU +Q2 GOTO LBL 5
            let s = body.trim();
            let s =
                s.strip_prefix("IF").ok_or((b.line, bcol, format!("FN {n}: IF … GOTO LBL … expected")))?;
            let op = ["EQU", "NE", "GT", "LT"][(n - 9) as usize];
            let k = s.find(op).ok_or((b.line, bcol, format!("FN {n}: {op} expected")))?;
            let g = s.find("GOTO").filter(|&g| g >= k + op.len()).ok_or((
                b.line,
                bcol,
                format!("FN {n}: GOTO LBL expected after {op}"),
            ))?;
            let a = eval(st, &s[..k], b.line, bcol)?;
            let c = eval(st, &s[k + op.len()..g], b.line, bcol)?;
            let label =
                s[g + 4..].trim().strip_prefix("LBL").unwrap_or("").trim().trim_matches('"').to_string();
            let &to =
                labels.get(&label).ok_or((b.line, bcol, format!("FN {n}: no LBL {label} in the program")))?;
            let yes = match n {
                9 => (a - c).abs() <= 1e-9 * a.abs().max(c.abs()).max(1.0),
                10 => (a - c).abs() > 1e-9 * a.abs().max(c.abs()).max(1.0),
                11 => a > c,
                _ => a < c,
            };
            Ok(if yes { Flow::Jump(to + 1) } else { Flow::Next })
        }
        _ => Err((b.line, b.col, format!("FN {n}: not read (FN 0 to 5 and the jumps FN 9 to 12 are)"))),
    }
}

/// `CYCL DEF n NAME` with its Q lines, the dotted cycles 7 and 10, and `CYCL CALL …`.
fn cycle(st: &mut St<'_>, b: &KBlock, up: &str) -> Result<Flow, KErr> {
    if let Some(rest) = up.strip_prefix("CYCL CALL") {
        return cycle_call(st, b, up, rest);
    }
    let rest = up
        .strip_prefix("CYCL DEF")
        .ok_or((b.line, b.col, "CYCL DEF or CYCL CALL expected".to_string()))?
        .trim();
    let num_text: String = rest.chars().take_while(|c| c.is_ascii_digit() || *c == '.').collect();
    let name = rest[num_text.len()..].trim().to_string();
    let (major, minor) = match num_text.split_once('.') {
        Some((a, m)) => (a.parse::<u32>().ok(), m.parse::<u32>().ok()),
        None => (num_text.parse::<u32>().ok(), None),
    };
    let major = major.ok_or((b.line, b.col, format!("CYCL DEF {rest}: the cycle's number")))?;
    if coordinate_cycle(st, b, up, &num_text, (major, minor))? {
        return Ok(Flow::Next);
    }
    // A cycle with Q parameters: evaluated now, in order; each also a Q-parameter after it.
    let mut q = HashMap::new();
    for p in &b.params {
        // A feed written as a word (CAM posts' `Q206=FAUTO`): FAUTO is the feed of the TOOL
        // CALL, FMAX the rapid rate, FU and FZ a feed per revolution and per tooth.
        let word = p.text.trim().to_ascii_uppercase();
        if matches!(word.as_str(), "FAUTO" | "FMAX" | "FU" | "FZ") {
            match (word.as_str(), st.tool_feed) {
                ("FAUTO", Some(f)) => {
                    q.insert(p.q, f);
                    st.q.insert(p.q as i64, f);
                }
                _ => {
                    // Kept unknown: a cycle that needs it is refused at its line.
                    st.symbolic.insert(p.q, (p.line, p.col, word.clone()));
                }
            }
            continue;
        }
        st.symbolic.remove(&p.q);
        let v = eval(st, &p.text, p.line, p.col)
            .map_err(|(l, c, m)| (l, c, format!("Q{}={}: {m}", p.q, p.text)))?;
        q.insert(p.q, v);
        st.q.insert(p.q as i64, v);
    }
    let def = CycleDef { number: major, name, q, line: b.line, col: b.col };
    machining_cycle(st, b, def)?;
    Ok(Flow::Next)
}

/// `CYCL CALL`, `CYCL CALL PAT` and `CYCL CALL POS`: the cycle in force run where they say.
fn cycle_call(st: &mut St<'_>, b: &KBlock, up: &str, rest: &str) -> Result<Flow, KErr> {
    let rest = rest.trim();
    if rest.starts_with("PAT") {
        let (pts, _) = st.pattern.clone().ok_or((
            b.line,
            b.col,
            "CYCL CALL PAT without a PATTERN DEF before it".to_string(),
        ))?;
        for p in pts {
            run_cycle(st, [p[0], p[1], st.pos[2]], b.line, b.col, Some(p[2]))?;
        }
    } else if let Some(pos) = rest.strip_prefix("POS") {
        let off = up.len() - pos.len();
        let ws = words(&b.text, off, b.col);
        let mut p = st.pos;
        for w in &ws {
            match axis_word(&w.name) {
                Some((k, false)) => p[k] = st.len(w, b.line)?,
                Some((k, true)) => p[k] = st.pos[k] + st.len(w, b.line)?,
                None => {}
            }
        }
        for k in 0..3 {
            st.known[k] = true;
        }
        st.pos = p;
        m_words(st, b, &ws)?;
        run_cycle(st, p, b.line, b.col, None)?;
    } else {
        if !(st.known[0] && st.known[1]) {
            return Err((b.line, b.col, "CYCL CALL at a position the program has not set".into()));
        }
        let ws = words(&b.text, 9, b.col);
        m_words(st, b, &ws)?;
        let here = st.pos;
        run_cycle(st, here, b.line, b.col, None)?;
    }
    Ok(Flow::Next)
}

/// The coordinate transformation cycles (7 datum shift, 10 rotation; 8, 11, 26 mirror and
/// scaling and 19 a tilted plane refused): applied, `true`; `false` for any other cycle.
fn coordinate_cycle(
    st: &mut St<'_>,
    b: &KBlock,
    up: &str,
    num_text: &str,
    (major, minor): (u32, Option<u32>),
) -> Result<bool, KErr> {
    match (major, minor) {
        (7, Some(0)) | (10, Some(0)) => return Ok(true),
        (7, Some(1..=3)) => {
            // 7.1 X+10 (IX: an increment of the shift).
            let ws = words(&b.text, up.find(num_text).unwrap_or(0) + num_text.len(), b.col);
            for w in &ws {
                if w.name == "#" || w.val.starts_with('#') {
                    return Err((
                        b.line,
                        w.col,
                        "CYCL DEF 7 with a datum table row (#n) is not read: write the shift as X, Y, Z"
                            .into(),
                    ));
                }
                let Some((k, inc)) = axis_word(&w.name) else {
                    return Err((
                        b.line,
                        w.col,
                        format!("CYCL DEF 7: {}{} is not a shift of X, Y or Z", w.name, w.val),
                    ));
                };
                let v = st.len(w, b.line)?;
                st.shift[k] = if inc { st.shift[k] + v } else { v };
            }
            return Ok(true);
        }
        (10, Some(1)) => {
            let ws = words(&b.text, up.find("10.1").unwrap_or(0) + 4, b.col);
            for w in &ws {
                match w.name.as_str() {
                    "ROT" => st.rot_deg = st.value(w, b.line)?,
                    "IROT" => st.rot_deg += st.value(w, b.line)?,
                    _ => {
                        return Err((
                            b.line,
                            w.col,
                            format!("CYCL DEF 10.1: {}{} (ROT or IROT expected)", w.name, w.val),
                        ))
                    }
                }
            }
            return Ok(true);
        }
        (8 | 11 | 26, _) => {
            let what = match major {
                8 => "MIRROR IMAGE (a mirrored helix or tap changes hand)",
                _ => "SCALING",
            };
            if minor.is_none_or(|m| m == 0) {
                return Err((
                    b.line,
                    b.col,
                    format!(
                        "CYCL DEF {major} {what} is not read: positions and hands under it would be wrong"
                    ),
                ));
            }
            return Ok(true);
        }
        (19, _) => {
            let zero = minor == Some(0)
                || b.text.split_whitespace().skip(3).all(|w| {
                    w.trim_start_matches(|c: char| c.is_ascii_alphabetic())
                        .trim_start_matches(['+', '-'])
                        .parse::<f64>()
                        .is_ok_and(|v| v == 0.0)
                });
            if !zero {
                return Err((
                    b.line,
                    b.col,
                    "CYCL DEF 19 WORKING PLANE tilts the plane: a thread's axis that is not Z is not read"
                        .into(),
                ));
            }
            return Ok(true);
        }
        _ => {}
    }
    Ok(false)
}

/// A machining cycle's definition kept for its calls (a pattern cycle runs the one before it at
/// its points), its words checked first; a cycle that makes no thread is read past.
fn machining_cycle(st: &mut St<'_>, b: &KBlock, def: CycleDef) -> Result<(), KErr> {
    let major = def.number;
    match major {
        220 | 221 => {
            let Some(target) = st.cycle.clone() else {
                return Err((
                    b.line,
                    b.col,
                    format!("CYCL DEF {major}: a pattern with no machining cycle defined before it"),
                ));
            };
            let pts = pattern_cycle(&def, b)?;
            st.note(
                b.line,
                b.col,
                format!(
                    "cycle {major} calls cycle {} at {} points; its Q203 (surface), where given, replaces the machining cycle's (a named default: the pattern pages read do not say)",
                    target.number,
                    pts.len()
                ),
            );
            for p in pts {
                let surface = def.get(203);
                run_with(st, &target, [p[0], p[1], st.pos[2]], b.line, b.col, surface)?;
            }
        }
        n if cycle_kind(n).is_some() => {
            let need: &[u32] = match cycle_kind(n) {
                Some(CycleKind::Drill) => &[201, 203],
                Some(CycleKind::TapFloating) => &[201, 203, 206],
                Some(CycleKind::TapRigid) => &[201, 203, 239],
                Some(CycleKind::Mill { .. }) => &[335, 239, 201, 203],
                None => &[],
            };
            if let Some(m) = need.iter().find(|q| !def.q.contains_key(q)) {
                if let Some((line, col, word)) =
                    b.params.iter().find(|p| p.q == *m).and_then(|_| st.symbolic.get(m).cloned())
                {
                    return Err((
                        line,
                        col,
                        format!(
                            "CYCL DEF {n} {}: Q{m}={word}: {}",
                            def.name,
                            match word.as_str() {
                                "FAUTO" =>
                                    "the feed of the TOOL CALL, which gives no F: the tap's feed is not known",
                                _ => "a feed this cycle's check cannot take as the tap's: write it in mm/min",
                            }
                        ),
                    ));
                }
                return Err((b.line, b.col, format!("CYCL DEF {n} {}: Q{m} is missing", def.name)));
            }
            // The depth as the control takes it: with DEPTH = 0 it does not run the cycle, and a
            // positive depth works upward from the surface (the TNC's cycle pages; the control
            // refuses it where its displayDepthErr is set): no hole either way, refused at the
            // parameter's place.
            let depth = def.get(201).unwrap_or(0.0);
            if depth >= 0.0 {
                let (line, col) =
                    b.params.iter().find(|p| p.q == 201).map_or((b.line, b.col), |p| (p.line, p.col));
                return Err((
                    line,
                    col,
                    format!(
                        "CYCL DEF {n} {}: Q201 (DEPTH) = {}: {}",
                        def.name,
                        crate::ground::fmt::fmt_num(depth),
                        if depth == 0.0 {
                            "the control does not run a cycle of depth 0, so nothing is drilled or tapped"
                        } else {
                            "a positive depth works upward from the surface Q203, into no material (the control refuses it where its displayDepthErr parameter is set): write the depth negative"
                        }
                    ),
                ));
            }
            st.cycle = Some(def);
        }
        _ => {
            st.read_past(
                b.line,
                b.col,
                &format!("CYCL DEF {major}"),
                "a cycle that makes no thread (its calls are read past too)",
            );
            st.cycle = Some(def);
        }
    }
    Ok(())
}

/// The points of the pattern cycles 220 (polar) and 221 (Cartesian).
fn pattern_cycle(def: &CycleDef, b: &KBlock) -> Result<Vec<[f64; 2]>, KErr> {
    let need =
        |q: u32| def.get(q).ok_or((b.line, b.col, format!("CYCL DEF {}: Q{q} is missing", def.number)));
    let mut out = Vec::new();
    if def.number == 220 {
        let (cx, cy, d, start, stop) = (need(216)?, need(217)?, need(244)?, need(245)?, need(246)?);
        let step = def.get(247).unwrap_or(0.0);
        let n = need(241)?;
        if !(n >= 1.0 && n.fract() == 0.0 && n <= 10_000.0) {
            return Err((b.line, b.col, format!("CYCL DEF 220: Q241 = {n}: a whole number of operations")));
        }
        let n = n as usize;
        // Q247 = 0: the step from the start and stop angles (a full circle when they are equal).
        let step = if step != 0.0 {
            step
        } else if (stop - start).abs() < 1e-9 || ((stop - start).abs() - 360.0).abs() < 1e-9 {
            360.0 / n as f64
        } else if n > 1 {
            (stop - start) / (n - 1) as f64
        } else {
            0.0
        };
        for k in 0..n {
            let a = (start + step * k as f64).to_radians();
            out.push([cx + 0.5 * d * a.cos(), cy + 0.5 * d * a.sin()]);
        }
    } else {
        let (sx, sy, dx, dy) = (need(225)?, need(226)?, need(237)?, need(238)?);
        let (cols, rows) = (need(242)?, need(243)?);
        let rot = def.get(224).unwrap_or(0.0).to_radians();
        if !(cols >= 1.0
            && rows >= 1.0
            && cols.fract() == 0.0
            && rows.fract() == 0.0
            && cols * rows <= 10_000.0)
        {
            return Err((
                b.line,
                b.col,
                "CYCL DEF 221: Q242 and Q243 are whole numbers of columns and lines".into(),
            ));
        }
        for j in 0..rows as usize {
            for i in 0..cols as usize {
                let (u, v) = (i as f64 * dx, j as f64 * dy);
                out.push([sx + u * rot.cos() - v * rot.sin(), sy + u * rot.sin() + v * rot.cos()]);
            }
        }
    }
    Ok(out)
}

/// `PATTERN DEF POS1 (X+25 Y+33 Z+0) POS2 (…)`.
fn pattern(st: &mut St<'_>, b: &KBlock, up: &str) -> Result<Flow, KErr> {
    let mut pts = Vec::new();
    let mut rest = up.strip_prefix("PATTERN DEF").unwrap_or(up);
    let mut off = up.len() - rest.len();
    loop {
        let t = rest.trim_start();
        off += rest.len() - t.len();
        if t.is_empty() {
            break;
        }
        let name: String = t.chars().take_while(|c| c.is_ascii_alphanumeric()).collect();
        if !name.starts_with("POS") {
            return Err((b.line, b.col + off, format!("PATTERN DEF {name} is not read (POS points are)")));
        }
        let open = t.find('(').ok_or((b.line, b.col + off, format!("PATTERN DEF {name}: '(' expected")))?;
        let close = t.find(')').ok_or((b.line, b.col + off, format!("PATTERN DEF {name}: ')' expected")))?;
        // Only the words between the brackets: reading to the block's end at every point was
        // quadratic (16 000 points took 36 s).
        let ws = words(&b.text[..off + close], off + open + 1, b.col);
        let mut p = [0.0; 3];
        for w in &ws {
            let w = KWord { val: w.val.trim_end_matches(')').to_string(), ..w.clone() };
            let k = axis(&w.name).ok_or((
                b.line,
                w.col,
                format!("PATTERN DEF {name}: {} is not X, Y or Z", w.name),
            ))?;
            p[k] = st.len(&w, b.line)?;
        }
        pts.push(p);
        rest = &t[close + 1..];
        off += close + 1;
    }
    if pts.is_empty() {
        return Err((b.line, b.col, "PATTERN DEF with no points".into()));
    }
    st.pattern = Some((pts, b.line));
    Ok(Flow::Next)
}

/// Runs the defined cycle at `p` (program coordinates), called from `line`:`col`; `surface_shift`
/// is a pattern point's Z (added to Q203).
fn run_cycle(
    st: &mut St<'_>,
    p: [f64; 3],
    line: usize,
    col: usize,
    surface_shift: Option<f64>,
) -> Result<(), KErr> {
    let def = st.cycle.clone().ok_or((line, col, "a cycle call with no CYCL DEF before it".to_string()))?;
    let surface = surface_shift.map(|z| def.get(203).unwrap_or(0.0) + z);
    run_with(st, &def, p, line, col, surface)
}

fn run_with(
    st: &mut St<'_>,
    def: &CycleDef,
    p: [f64; 3],
    line: usize,
    col: usize,
    surface: Option<f64>,
) -> Result<(), KErr> {
    let Some(kind) = cycle_kind(def.number) else {
        st.read_past(line, col, &format!("call of cycle {}", def.number), "a cycle that makes no thread");
        return Ok(());
    };
    // A tilted tool axis (A or B turned) drills and taps along another axis than Z.
    if let Some(k) = (0..2).find(|&k| st.rotary[k] != 0.0) {
        return Err((
            line,
            col,
            format!(
                "cycle {} with the rotary axis {} at {}°: the hole's axis is tilted, and threadcheck reads holes along Z (A and B at 0)",
                def.number,
                ["A", "B"][k],
                crate::ground::fmt::fmt_num(st.rotary[k])
            ),
        ));
    }
    if st.rotary[2] != 0.0 {
        st.read_past(line, col, "C (a turned table)", "the rotary table C is turned: the holes' X and Y are in the program's coordinates, not the part's as it stood at C0");
    }
    let s = st.scale;
    let q = |n: u32| def.get(n).unwrap_or(0.0);
    let top = surface.unwrap_or(q(203)) * s;
    let bottom = top + q(201) * s;
    let w = st.to_work([p[0], p[1], bottom]);
    let code = format!("CYCL {}", def.number);
    let units = ProgramUnits::of_scale(s);
    let mut hole = HoleCycle {
        code,
        kind: HoleKind::Drill,
        line,
        column: col,
        x: Some(w[0]),
        y: Some(w[1]),
        radial: None,
        bottom: Some(w[2]),
        feed: def.get(206).map(|f| f * s),
        feed_word: "Q206".into(),
        hand: None,
        feed_per_rev: false,
        feed_mode_assumed: false,
        spindle: st.spindle,
        spindle_dir: st.dir,
        tool: st.tool,
        // A TNC's datum shift (cycle 7) is applied to the place itself.
        work_offset: None,
        source_file: None,
        main_line: line,
        machine_xy: None,
        rigid: false,
        constant_surface_speed: false,
        units,
        // The set-up clearance Q200 above the surface: where the cycle feeds from.
        r_level: Some(st.to_work([p[0], p[1], top + q(200) * s])[2]),
    };
    if st.holes.len() >= crate::ground::bounds::MAX_HOLES {
        return Err((line, col, format!("more than {} holes", crate::ground::bounds::MAX_HOLES)));
    }
    match kind {
        CycleKind::Drill => st.holes.push(hole),
        CycleKind::TapFloating => {
            hole.kind = HoleKind::Tap;
            st.holes.push(hole);
        }
        CycleKind::TapRigid => {
            let pitch = q(239);
            hole.kind = HoleKind::Tap;
            hole.feed = Some(pitch.abs() * s);
            hole.feed_word = "Q239".into();
            hole.feed_per_rev = true;
            hole.rigid = true;
            hole.hand = Some(if pitch < 0.0 { Hand::Left } else { Hand::Right });
            // The cycle turns the spindle itself, by Q239's sign.
            hole.spindle_dir = Some(if pitch < 0.0 { SpindleDir::Ccw } else { SpindleDir::Cw });
            st.holes.push(hole);
        }
        CycleKind::Mill { external } => mill(st, def, p, line, top, bottom, external)?,
    }
    Ok(())
}

/// The helices of the thread-milling cycles 262–265 (inside) and 267 (outside) as the TNC mills
/// them about the called point: the programmed contour is the thread's nominal circle (Q335),
/// compensated by the cutter's radius (RL/RR as the direction and side give it), over the depth
/// Q201 below the surface. Named defaults, stated in a note: the helix starts at +X of the
/// centre; Q355 = 1 one helix over the whole depth, 0 one 360° turn at the bottom (a comb
/// cutter), n > 1 one turn every n pitches; the cutter enters and leaves on a half circle in the
/// plane (the cycle's tangential approach) at the helix's own Z.
fn mill(
    st: &mut St<'_>,
    def: &CycleDef,
    p: [f64; 3],
    line: usize,
    top: f64,
    bottom: f64,
    external: bool,
) -> Result<(), KErr> {
    let s = st.scale;
    let q = |n: u32| def.get(n).unwrap_or(0.0);
    let pitch = q(239) * s;
    // The cutter's tip reaches the nominal diameter inside (D) and, outside, the minor diameter
    // d3 = d − 2·h3, h3 = 0.61343·P (ISO 68-1's external thread depth; a named default, said).
    let r = 0.5 * q(335) * s - if external { 0.613_434_5 * pitch.abs() } else { 0.0 };
    if !(r > 0.0) || pitch == 0.0 {
        return Err((def.line, def.col, format!("CYCL DEF {}: Q335 and Q239 must not be 0", def.number)));
    }
    // 265 writes no Q351: climb milling, a named default (said below).
    let climb = q(351) >= 0.0 || def.number == 265;
    let right = pitch > 0.0;
    let lead = pitch.abs();
    // Inside, climb milling (spindle M3) goes counter-clockwise; outside, clockwise.
    let ccw = climb != external;
    // A right-hand thread rises counter-clockwise (G17, Z the tool axis).
    let rising = ccw == right;
    let dir = if ccw { 1.0 } else { -1.0 };
    let depth = (top - bottom).abs();
    // Only 262 and 267 write Q355; 263 to 265 mill the thread in one helix over its depth (a
    // named default, said: their countersinking and drilling paths are not modelled).
    let per_step = if matches!(def.number, 262 | 267) { q(355) } else { 1.0 };
    let steps: Vec<(f64, f64)> = if per_step == 1.0 || depth < 1e-9 {
        vec![(bottom, top)]
    } else if per_step <= 0.0 {
        vec![(bottom, bottom + lead)]
    } else {
        let h = per_step * lead;
        let n = (depth / h - 1e-9).ceil().max(1.0) as usize;
        (0..n).map(|k| (bottom + k as f64 * h, bottom + k as f64 * h + lead)).collect()
    };
    let saved_comp = st.comp;
    let clear = top + q(200).abs() * s;
    let c = [p[0], p[1]];
    st.comp = 0;
    let first = [c[0] + if external { 2.0 * r } else { 0.0 }, c[1], clear];
    if st.known.iter().all(|k| *k) {
        st.push_move(true, first, None, line);
    } else {
        st.pos = first;
        st.known = [true; 3];
    }
    st.note(
        line,
        def.col,
        format!(
            "cycle {} mills about X{} Y{}: the circle Ø{} ({}) compensated by the cutter's radius, {} {} over {} mm; named defaults: the helix starts at +X, Q355 = {} read as {}, entry and exit on half circles in the plane",
            def.number,
            crate::ground::fmt::fmt_num(c[0]),
            crate::ground::fmt::fmt_num(c[1]),
            crate::ground::fmt::fmt_num((2.0 * r * 1e4).round() / 1e4),
            if external { "the nominal diameter less twice ISO 68-1's h3 = 0.61343·P, the minor diameter the tip reaches" } else { "the nominal diameter, which the tip reaches" },
            if ccw { "counter-clockwise" } else { "clockwise" },
            if rising { "rising" } else { "falling" },
            crate::ground::fmt::fmt_num(depth),
            per_step,
            if per_step == 1.0 { "one helix over the depth" } else if per_step <= 0.0 { "one turn at the bottom" } else { "one turn every Q355 pitches" }
        ),
    );
    if (263..=265).contains(&def.number) {
        st.note(
            line,
            def.col,
            format!(
                "cycle {}: only its thread is read, one helix over the depth Q201 (a named default{}); its countersinking{} is not modelled",
                def.number,
                if def.number == 265 { ", climb milling" } else { "" },
                if def.number == 263 { "" } else { " and drilling" }
            ),
        );
    }
    let comp = if ccw != external { 1 } else { 2 };
    // Inside, the cutter enters from the centre; outside, from a radius further out; the half
    // circles in and out turn the other way round outside, so that they meet the helix
    // tangentially.
    let (reach, arc_dir) = if external { (2.0 * r, -dir) } else { (0.0, dir) };
    let mut last = [c[0] + reach, c[1]];
    for (lo, hi) in steps {
        let (z0, z1) = if rising { (lo, hi) } else { (hi, lo) };
        let start = [c[0] + r, c[1], z0];
        // Down (or up) to the helix's start height beside it.
        st.push_move(false, [c[0] + reach, c[1], z0], None, line);
        // Enter on a half circle from there to the start point.
        st.comp = comp;
        let mid = [c[0] + 0.5 * (r + reach), c[1]];
        st.push_move(false, start, Some((mid, arc_dir, 0)), line);
        let turns = (z1 - z0).abs() / lead;
        let sweep = 360.0 * turns;
        let ae = (dir * sweep).to_radians();
        let u = [ae.cos(), ae.sin()];
        let end = [c[0] + r * u[0], c[1] + r * u[1], z1];
        let extra = (sweep / 360.0 - 1e-9).floor().max(0.0) as u32;
        st.push_move(false, end, Some((c, dir, extra)), line);
        // Leave on a half circle to the centre (inside) or outward.
        last = [c[0] + reach * u[0], c[1] + reach * u[1]];
        let em = [c[0] + 0.5 * (r + reach) * u[0], c[1] + 0.5 * (r + reach) * u[1]];
        st.push_move(false, [last[0], last[1], z1], Some((em, arc_dir, 0)), line);
        st.comp = 0;
    }
    st.push_move(true, [last[0], last[1], clear], None, line);
    st.comp = saved_comp;
    Ok(())
}
