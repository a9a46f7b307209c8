//! Lathe programs: reads Fanuc, Sinumerik and LinuxCNC G-code and expands its threading cycles
//! into passes, exactly as the control would lay them out.
//!
//! Conventions: X is a diameter (LinuxCNC's radius mode G8 and Sinumerik's DIAMOF are converted),
//! inch programs (G20, G70) are converted to mm, and every pass keeps the program line it came
//! from. Blocks that move the tool without threading update the position and are otherwise
//! counted as skipped.
//!
//! Cycles:
//! - Fanuc `G32`, `G92` (with modal X-only repeats and R taper) and the two-block `G76`
//!   (`P(m)(r)(a) Q(Δd min) R(d)` then `X Z R P(k) Q(Δd) F`): depth after pass n is Δd·√n,
//!   each step at least Δd min, rough to k − d, then m finishing passes at k; infeed along the
//!   flank at a/2; chamfer r/10 leads at 45° at the end. P and Q are read in least-input
//!   increments (µm) and must be written without a decimal point.
//! - Sinumerik `G33 Z K` (`I` for steep tapers, `SF=` start offset), `CYCLE97`, R-parameter
//!   arithmetic and subprograms (`L9 P33` repeats, `M17` return, in the same file after `M30`).
//! - LinuxCNC `G76 P Z I J K R Q H E L` (pass n at J·n^(1/R) beyond the crest, one pass at K,
//!   H spring passes, start offset depth·tan Q along the drive line, entry/exit tapers).

mod lexer;

use crate::limits::{MAX_CALL_DEPTH, MAX_EXECUTED_BLOCKS, MAX_PASSES, MAX_REPEATS};
use crate::passes::Pass;
use crate::Error;
use lexer::{lex, Block, Val, Word};
use std::collections::HashMap;

pub use lexer::Val as WordValue;

/// Which control's G-code.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dialect {
    /// Fanuc (and its many compatibles).
    Fanuc,
    /// Siemens Sinumerik.
    Sinumerik,
    /// LinuxCNC.
    LinuxCnc,
}

impl Dialect {
    /// The dialect's command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Dialect::Fanuc => "fanuc",
            Dialect::Sinumerik => "sinumerik",
            Dialect::LinuxCnc => "linuxcnc",
        }
    }

    /// Reads a dialect name.
    pub fn parse(s: &str) -> Result<Dialect, Error> {
        match s {
            "fanuc" => Ok(Dialect::Fanuc),
            "sinumerik" => Ok(Dialect::Sinumerik),
            "linuxcnc" => Ok(Dialect::LinuxCnc),
            _ => Err(Error::Input(format!("--dialect '{s}': expected fanuc, sinumerik or linuxcnc"))),
        }
    }
}

/// An expanded program.
#[derive(Clone, Debug, PartialEq)]
pub struct Program {
    /// The threading passes in cutting order (X diameters in mm).
    pub passes: Vec<Pass>,
    /// Blocks read for position only (turning, tool changes, …).
    pub skipped_blocks: usize,
    /// Warnings worth printing (G96 during threading, …).
    pub notes: Vec<String>,
}

impl Program {
    /// The lead common to all passes, mm.
    pub fn lead(&self) -> Option<f64> {
        self.passes.first().map(|p| p.lead)
    }
}

/// Reads `text` (the contents of `file`) as a `dialect` program and expands its threading.
pub fn read_program(text: &str, file: &str, dialect: Dialect) -> Result<Program, Error> {
    let perr = |line: usize, column: usize, message: String| Error::Program {
        file: file.to_string(),
        line,
        column,
        message,
    };
    let blocks = lex(text, dialect).map_err(|(l, c, m)| perr(l, c, m))?;
    let mut m = Machine::new(dialect, file);
    m.run_program(&blocks)?;
    if m.passes.is_empty() {
        return Err(perr(
            1,
            1,
            format!(
                "no threading pass in the program (looked for {})",
                match dialect {
                    Dialect::Fanuc => "G32, G92 and G76",
                    Dialect::Sinumerik => "G33 and CYCLE97",
                    Dialect::LinuxCnc => "G33 and G76",
                }
            ),
        ));
    }
    let lead = m.passes[0].lead;
    if let Some(p) = m.passes.iter().find(|p| (p.lead - lead).abs() > 1e-9) {
        return Err(perr(
            p.source_line.unwrap_or(1),
            1,
            format!("this pass has lead {} mm, the first had {lead} mm; threadcheck verifies one thread per program", p.lead),
        ));
    }
    Ok(Program { passes: m.passes, skipped_blocks: m.skipped, notes: m.notes })
}

#[derive(Clone, Copy, Debug)]
struct G76First {
    finish_passes: u32,
    chamfer_tenths: u32,
    angle: f64,
    min_depth: f64,
    finish: f64,
}

#[derive(Clone, Copy, Debug)]
struct G92State {
    z_end: f64,
    r: f64,
}

struct Machine<'a> {
    dialect: Dialect,
    file: &'a str,
    x: Option<f64>,
    z: Option<f64>,
    absolute: bool,
    scale: f64,
    diameter: bool,
    motion: u32,
    lead: Option<f64>,
    g92: Option<G92State>,
    g76: Option<(G76First, usize)>,
    css: bool,
    start_offset_deg: f64,
    r: HashMap<u32, f64>,
    passes: Vec<Pass>,
    skipped: usize,
    notes: Vec<String>,
    executed: usize,
    last_thread: bool,
    subs: HashMap<String, (usize, usize)>,
}

fn words_named<'w>(b: &'w Block, name: &'w str) -> impl Iterator<Item = &'w Word> + 'w {
    b.words.iter().filter(move |w| w.name == name)
}

impl<'a> Machine<'a> {
    fn new(dialect: Dialect, file: &'a str) -> Machine<'a> {
        Machine {
            dialect,
            file,
            x: None,
            z: None,
            absolute: true,
            scale: 1.0,
            // LinuxCNC starts in radius mode (G8); lathes with Fanuc and Sinumerik in diameter.
            diameter: dialect != Dialect::LinuxCnc,
            motion: 0,
            lead: None,
            g92: None,
            g76: None,
            css: false,
            start_offset_deg: 0.0,
            r: HashMap::new(),
            passes: Vec::new(),
            skipped: 0,
            notes: Vec::new(),
            executed: 0,
            last_thread: false,
            subs: HashMap::new(),
        }
    }

    fn err(&self, line: usize, column: usize, message: impl Into<String>) -> Error {
        Error::Program { file: self.file.to_string(), line, column, message: message.into() }
    }

    fn werr(&self, b: &Block, w: &Word, message: impl Into<String>) -> Error {
        self.err(b.line, w.col, message)
    }

    /// A number word's value; expressions are evaluated against the R-parameters.
    fn value(&self, b: &Block, w: &Word) -> Result<f64, Error> {
        match &w.val {
            Val::Num { v, .. } => Ok(*v),
            Val::Expr(e) => eval(e, &self.r).map_err(|m| self.werr(b, w, format!("{}={e}: {m}", w.name))),
            _ => Err(self.werr(b, w, format!("{} has no value", w.name))),
        }
    }

    fn g_codes(&self, b: &Block) -> Result<Vec<(u32, usize)>, Error> {
        let mut v = Vec::new();
        for w in words_named(b, "G") {
            let g = w.num().unwrap_or(-1.0);
            if g < 0.0 || g.fract() != 0.0 {
                // G7.1 and kin: not lathe threading; keep the block readable.
                if g >= 0.0 {
                    continue;
                }
                return Err(self.werr(b, w, "G with no code"));
            }
            v.push((g as u32, w.col));
        }
        Ok(v)
    }

    fn len(&self, b: &Block, w: &Word) -> Result<f64, Error> {
        Ok(self.value(b, w)? * self.scale)
    }

    fn x_dia(&self, b: &Block, w: &Word) -> Result<f64, Error> {
        let v = self.len(b, w)?;
        Ok(if self.diameter { v } else { 2.0 * v })
    }

    /// Target position of a block: X/Z absolute or incremental, U/W incremental (Fanuc).
    fn target(&self, b: &Block) -> Result<(Option<f64>, Option<f64>), Error> {
        let mut x = None;
        let mut z = None;
        for w in &b.words {
            match w.name.as_str() {
                "X" => {
                    let v = self.x_dia(b, w)?;
                    x = Some(if self.absolute { v } else { self.x.unwrap_or(0.0) + v });
                }
                "Z" => {
                    let v = self.len(b, w)?;
                    z = Some(if self.absolute { v } else { self.z.unwrap_or(0.0) + v });
                }
                "U" if self.dialect == Dialect::Fanuc => x = Some(self.x.unwrap_or(0.0) + self.x_dia(b, w)?),
                "W" if self.dialect == Dialect::Fanuc => z = Some(self.z.unwrap_or(0.0) + self.len(b, w)?),
                _ => {}
            }
        }
        Ok((x, z))
    }

    fn count(&mut self, b: &Block) -> Result<(), Error> {
        self.executed += 1;
        if self.executed > MAX_EXECUTED_BLOCKS {
            return Err(self.err(
                b.line,
                b.col,
                format!("more than {MAX_EXECUTED_BLOCKS} blocks executed: the program loops"),
            ));
        }
        if self.passes.len() > MAX_PASSES {
            return Err(self.err(b.line, b.col, format!("more than {MAX_PASSES} passes")));
        }
        Ok(())
    }

    fn push_pass(&mut self, mut p: Pass) {
        p.index = self.passes.len() + 1;
        self.passes.push(p);
    }

    fn run_program(&mut self, blocks: &[Block]) -> Result<(), Error> {
        // Sinumerik listings carry subprograms after the main program's end: index them.
        let mut main_end = blocks.len();
        if self.dialect == Dialect::Sinumerik {
            let mut i = 0;
            while i < blocks.len() {
                if let Some(name) = &blocks[i].label {
                    main_end = main_end.min(i);
                    let start = i + 1;
                    let mut end = start;
                    while end < blocks.len()
                        && !blocks[end].words.iter().any(|w| w.name == "M" && w.num() == Some(17.0))
                    {
                        if blocks[end].label.is_some() {
                            break;
                        }
                        end += 1;
                    }
                    self.subs.insert(name.clone(), (start, end.min(blocks.len())));
                    i = end;
                } else {
                    i += 1;
                }
            }
        }
        self.run(blocks, 0, main_end, 0)
    }

    fn run(&mut self, blocks: &[Block], from: usize, to: usize, depth: usize) -> Result<(), Error> {
        for b in &blocks[from..to] {
            self.count(b)?;
            let ended = match self.dialect {
                Dialect::Fanuc => self.fanuc_block(b)?,
                Dialect::Sinumerik => self.sinumerik_block(blocks, b, depth)?,
                Dialect::LinuxCnc => self.linuxcnc_block(b)?,
            };
            if ended {
                break;
            }
        }
        Ok(())
    }

    /// Modal settings common to the dialects; returns the motion G code of the block, if any.
    fn modal(&mut self, b: &Block) -> Result<Option<(u32, usize)>, Error> {
        let mut motion = None;
        for (g, col) in self.g_codes(b)? {
            match g {
                0 | 1 | 2 | 3 | 32 | 33 | 76 | 92 => motion = Some((g, col)),
                7 if self.dialect == Dialect::LinuxCnc => self.diameter = true,
                8 if self.dialect == Dialect::LinuxCnc => self.diameter = false,
                20 if self.dialect != Dialect::Sinumerik => self.scale = 25.4,
                21 if self.dialect != Dialect::Sinumerik => self.scale = 1.0,
                70 | 700 if self.dialect == Dialect::Sinumerik => self.scale = 25.4,
                71 | 710 if self.dialect == Dialect::Sinumerik => self.scale = 1.0,
                90 => self.absolute = true,
                91 => self.absolute = false,
                96 => self.css = true,
                97 => self.css = false,
                17 | 19 => {
                    return Err(self.err(
                        b.line,
                        col,
                        format!("G{g}: threading is programmed in the lathe plane G18"),
                    ))
                }
                _ => {}
            }
        }
        Ok(motion)
    }

    fn move_to(&mut self, b: &Block) -> Result<bool, Error> {
        let (x, z) = self.target(b)?;
        let moved = x.is_some() || z.is_some();
        if let Some(x) = x {
            self.x = Some(x);
        }
        if let Some(z) = z {
            self.z = Some(z);
        }
        Ok(moved)
    }

    fn need_position(&self, b: &Block, col: usize, what: &str) -> Result<(f64, f64), Error> {
        match (self.x, self.z) {
            (Some(x), Some(z)) => Ok((x, z)),
            _ => Err(self.err(
                b.line,
                col,
                format!("{what} starts from an unknown position: move to X and Z first"),
            )),
        }
    }

    fn check_css(&mut self, b: &Block, what: &str) {
        if self.css {
            self.notes.push(format!(
                "line {}: {what} under constant surface speed (G96); threading wants G97",
                b.line
            ));
        }
    }

    /// A single threading move from the current position to the block's target (G32/G33).
    fn thread_move(&mut self, b: &Block, col: usize, lead: f64, what: &str) -> Result<(), Error> {
        let (x0, z0) = self.need_position(b, col, what)?;
        let (x, z) = self.target(b)?;
        let (x1, z1) = (x.unwrap_or(x0), z.unwrap_or(z0));
        if (z1 - z0).abs() < 1e-12 {
            return Err(self.err(b.line, col, format!("{what} has no Z travel: a thread needs Z")));
        }
        // A second threading block straight after the first continues the same helix: a run-out.
        if self.last_thread {
            if let Some(prev) = self.passes.last_mut() {
                if (prev.z_end - z0).abs() < 1e-9 && (prev.lead - lead).abs() < 1e-12 {
                    prev.taper_out = (z1 - z0).abs();
                    prev.x_taper = x1;
                    prev.z_end = z1;
                    self.x = Some(x1);
                    self.z = Some(z1);
                    return Ok(());
                }
            }
        }
        let offset = self.start_offset_deg / 360.0 * lead;
        let dir = if z1 < z0 { -1.0 } else { 1.0 };
        self.push_pass(Pass {
            index: 0,
            x_start: x0,
            x_end: x1,
            z_start: z0 + dir * offset,
            z_end: z1,
            lead,
            start: 0,
            source_line: Some(b.line),
            taper_in: 0.0,
            taper_out: 0.0,
            x_taper: x1,
        });
        self.x = Some(x1);
        self.z = Some(z1);
        Ok(())
    }

    fn allow_only(&self, b: &Block, allowed: &str, cycle: &str) -> Result<(), Error> {
        for w in &b.words {
            if w.name.len() != 1 || !allowed.contains(w.name.as_str()) {
                return Err(self.werr(
                    b,
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

    fn fanuc_lead(&mut self, b: &Block, col: usize, what: &str) -> Result<f64, Error> {
        let mut f = None;
        for w in words_named(b, "F").chain(words_named(b, "E")) {
            let v = self.len(b, w)?;
            if !(v > 0.0) {
                return Err(self.werr(b, w, format!("lead {v} must be greater than zero")));
            }
            f = Some(v);
        }
        if let Some(f) = f {
            self.lead = Some(f);
        }
        self.lead.ok_or_else(|| {
            self.err(b.line, col, format!("{what} without a lead: add F (the lead per revolution)"))
        })
    }

    fn fanuc_block(&mut self, b: &Block) -> Result<bool, Error> {
        let motion = self.modal(b)?;
        if b.words.iter().any(|w| w.name == "M" && matches!(w.num(), Some(2.0) | Some(30.0))) {
            return Ok(true);
        }
        let (g, col) = match motion {
            Some(m) => {
                self.motion = m.0;
                m
            }
            None => (self.motion, b.col),
        };
        let threading = matches!(g, 32 | 33 | 76 | 92);
        let was_thread = self.last_thread;
        self.last_thread = false;
        match g {
            76 => self.fanuc_g76(b, col)?,
            92 => {
                self.allow_only(b, "GXZUWRFNM", "G92")?;
                let lead = self.fanuc_lead(b, col, "G92")?;
                self.check_css(b, "G92");
                let (_, z0) = self.need_position(b, col, "G92")?;
                let (x, z) = self.target(b)?;
                let r = match words_named(b, "R").next() {
                    Some(w) => self.len(b, w)?,
                    None => self.g92.map_or(0.0, |s| s.r),
                };
                let z_end = z
                    .or(self.g92.map(|s| s.z_end))
                    .ok_or_else(|| self.err(b.line, col, "G92 needs Z, the end of the thread"))?;
                let Some(x_end) = x else {
                    // A G92 block without X repeats nothing: it only sets the cycle up.
                    self.g92 = Some(G92State { z_end, r });
                    return Ok(false);
                };
                self.g92 = Some(G92State { z_end, r });
                // The cycle starts and ends at the start point; R is radius(start) − radius(end).
                let x_start = x_end + 2.0 * r;
                self.push_pass(Pass {
                    index: 0,
                    x_start,
                    x_end,
                    z_start: z0,
                    z_end,
                    lead,
                    start: 0,
                    source_line: Some(b.line),
                    taper_in: 0.0,
                    taper_out: 0.0,
                    x_taper: x_end,
                });
            }
            32 | 33 => {
                self.allow_only(b, "GXZUWFENM", "G32")?;
                let lead = self.fanuc_lead(b, col, "G32")?;
                self.last_thread = was_thread;
                self.thread_move(b, col, lead, "G32")?;
                self.last_thread = true;
            }
            _ => {
                if !self.move_to(b)? || !threading {
                    self.skipped += 1;
                }
            }
        }
        Ok(false)
    }

    fn fanuc_g76(&mut self, b: &Block, col: usize) -> Result<(), Error> {
        let has = |n: &str| b.words.iter().any(|w| w.name == n);
        let integer_word = |this: &Self, n: &str, what: &str| -> Result<Option<f64>, Error> {
            match words_named(b, n).next() {
                Some(w) => match w.val {
                    Val::Num { v, point: false } => Ok(Some(v)),
                    Val::Num { v, point: true } => Err(this.werr(
                        b,
                        w,
                        format!(
                            "G76 {} has a decimal point, but {what} is read in least-input increments (µm): write {n}{}",
                            w.text,
                            (v * 1000.0).round() as i64
                        ),
                    )),
                    _ => Err(this.werr(b, w, format!("G76 {n} needs a number"))),
                },
                None => Ok(None),
            }
        };
        let second = has("X") || has("U") || has("Z") || has("W");
        if !second {
            // First block: P(m)(r)(a) Q(Δd min) R(d).
            self.allow_only(b, "GPQRNM", "the first G76 block")?;
            let p = integer_word(self, "P", "P (m r a)")?
                .ok_or_else(|| self.err(b.line, col, "the first G76 block needs P(m)(r)(a), e.g. P011060"))?;
            let p = p as u64;
            let (m, r, a) = ((p / 10_000) as u32, ((p / 100) % 100) as u32, (p % 100) as f64);
            if ![80.0, 60.0, 55.0, 30.0, 29.0, 0.0].contains(&a) {
                let w = words_named(b, "P").next().map_or(col, |w| w.col);
                return Err(self.err(
                    b.line,
                    w,
                    format!("G76 tool angle {a} is not one of 80, 60, 55, 30, 29, 0"),
                ));
            }
            let q = integer_word(self, "Q", "the minimum depth Q")?.unwrap_or(0.0);
            let finish = match words_named(b, "R").next() {
                Some(w) => match w.val {
                    // R without a point is in least-input increments too.
                    Val::Num { v, point: false } => v / 1000.0 * self.scale,
                    _ => self.len(b, w)?,
                },
                None => 0.0,
            };
            self.g76 = Some((
                G76First {
                    finish_passes: m.max(1),
                    chamfer_tenths: r,
                    angle: a,
                    min_depth: q / 1000.0 * self.scale,
                    finish,
                },
                b.line,
            ));
            return Ok(());
        }
        self.allow_only(b, "GXZUWRPQFENM", "the second G76 block")?;
        let Some((first, _)) = self.g76 else {
            return Err(self.err(
                b.line,
                col,
                "G76 second block (X Z P Q F) without its first block (G76 P(m)(r)(a) Q R) before it",
            ));
        };
        let lead = self.fanuc_lead(b, col, "G76")?;
        self.check_css(b, "G76");
        let (x0, z0) = self.need_position(b, col, "G76")?;
        let (x, z) = self.target(b)?;
        let x_root = x.ok_or_else(|| self.err(b.line, col, "G76 needs X, the root diameter"))?;
        let z_end = z.ok_or_else(|| self.err(b.line, col, "G76 needs Z, the end of the thread"))?;
        let k = integer_word(self, "P", "the thread height P")?
            .ok_or_else(|| self.err(b.line, col, "G76 needs P, the thread height in µm"))?
            / 1000.0
            * self.scale;
        let dd = integer_word(self, "Q", "the first depth Q")?
            .ok_or_else(|| self.err(b.line, col, "G76 needs Q, the first depth in µm"))?
            / 1000.0
            * self.scale;
        let taper = match words_named(b, "R").next() {
            Some(w) => self.len(b, w)?,
            None => 0.0,
        };
        if !(k > 0.0 && dd > 0.0) {
            return Err(self.err(
                b.line,
                col,
                "G76 thread height P and first depth Q must be greater than zero",
            ));
        }
        if first.finish >= k {
            return Err(self.err(
                b.line,
                col,
                format!(
                    "G76 finishing allowance {} mm is not less than the thread height {k} mm",
                    first.finish
                ),
            ));
        }
        // External when the root lies inside the start point, internal when outside.
        let sign = if x_root < x0 { 1.0 } else { -1.0 };
        let rough_to = k - first.finish;
        let mut depths = Vec::new();
        let mut prev = 0.0f64;
        let mut n = 1.0f64;
        loop {
            let mut d = dd * n.sqrt();
            if d - prev < first.min_depth {
                d = prev + first.min_depth;
            }
            if d >= rough_to - 1e-12 {
                depths.push(rough_to);
                break;
            }
            depths.push(d);
            prev = d;
            n += 1.0;
            if depths.len() > MAX_PASSES {
                return Err(self.err(b.line, col, "G76 expands to too many passes"));
            }
        }
        for _ in 0..first.finish_passes {
            depths.push(k);
        }
        let dir = if z_end < z0 { -1.0 } else { 1.0 };
        let half = (0.5 * first.angle).to_radians().tan();
        let chamfer = f64::from(first.chamfer_tenths) / 10.0 * lead;
        for d in depths {
            // Root X at the end; the taper R (radius start − end) applies to every pass.
            let x_end = x_root + sign * 2.0 * (k - d);
            let x_start = x_end + 2.0 * taper;
            let x_out = x_end + sign * 2.0 * chamfer;
            self.push_pass(Pass {
                index: 0,
                x_start,
                x_end,
                z_start: z0 + dir * d * half,
                z_end,
                lead,
                start: 0,
                source_line: Some(b.line),
                taper_in: 0.0,
                taper_out: chamfer,
                x_taper: x_out,
            });
        }
        self.x = Some(x0);
        self.z = Some(z0);
        Ok(())
    }

    fn linuxcnc_block(&mut self, b: &Block) -> Result<bool, Error> {
        let motion = self.modal(b)?;
        if b.words.iter().any(|w| w.name == "M" && matches!(w.num(), Some(2.0) | Some(30.0))) {
            return Ok(true);
        }
        let was_thread = self.last_thread;
        self.last_thread = false;
        match motion {
            Some((76, col)) => self.linuxcnc_g76(b, col)?,
            Some((33, col)) => {
                self.allow_only(b, "GXZKNM", "G33")?;
                let k = words_named(b, "K")
                    .next()
                    .ok_or_else(|| self.err(b.line, col, "G33 without K, the distance per revolution"))?;
                let lead = self.len(b, k)?;
                if !(lead > 0.0) {
                    return Err(self.werr(b, k, "G33 K must be greater than zero"));
                }
                self.last_thread = was_thread;
                self.thread_move(b, col, lead, "G33")?;
                self.last_thread = true;
            }
            Some((g, _)) => {
                self.motion = g;
                if !self.move_to(b)? {
                    self.skipped += 1;
                }
            }
            None => {
                if !self.move_to(b)? {
                    self.skipped += 1;
                }
            }
        }
        Ok(false)
    }

    fn linuxcnc_g76(&mut self, b: &Block, col: usize) -> Result<(), Error> {
        self.allow_only(b, "GPZIJKRQHELNM", "G76")?;
        let (x0, z0) = self.need_position(b, col, "G76")?;
        let get = |this: &Self, n: &str| -> Result<Option<f64>, Error> {
            words_named(b, n).next().map(|w| this.value(b, w)).transpose()
        };
        let need = |this: &Self, n: &str, what: &str| -> Result<f64, Error> {
            get(this, n)?.ok_or_else(|| this.err(b.line, col, format!("G76 needs {n}, {what}")))
        };
        let pitch = need(self, "P", "the pitch")? * self.scale;
        let z_end = need(self, "Z", "the end of the thread")? * self.scale;
        let z_end = if self.absolute { z_end } else { z0 + z_end };
        // In diameter mode (G7) I, J and K are diameters; work in radius here.
        let to_r = |v: f64| if self.diameter { 0.5 * v } else { v } * self.scale;
        let i = to_r(need(self, "I", "the crest offset from the drive line")?);
        let j = to_r(need(self, "J", "the first depth")?);
        let k = to_r(need(self, "K", "the full depth")?);
        let r = get(self, "R")?.unwrap_or(1.0);
        let q = get(self, "Q")?.unwrap_or(0.0);
        let h = get(self, "H")?.unwrap_or(0.0);
        let e = get(self, "E")?.unwrap_or(0.0) * self.scale;
        let l = get(self, "L")?.unwrap_or(0.0);
        if !(pitch > 0.0 && j > 0.0 && k > 0.0 && r >= 1.0) {
            return Err(self.err(b.line, col, "G76 needs P, J, K greater than zero and R of at least 1"));
        }
        if !whole_in(h, 0.0, MAX_REPEATS as f64) || ![0.0, 1.0, 2.0, 3.0].contains(&l) {
            return Err(self.err(
                b.line,
                col,
                "G76 H must be a whole number of spring passes and L one of 0, 1, 2, 3",
            ));
        }
        // The crest (peak) is I from the drive line; external when I < 0.
        let drive_r = 0.5 * x0;
        let peak_r = drive_r + i;
        let inward = if i < 0.0 { -1.0 } else { 1.0 };
        let mut depths = Vec::new();
        let mut n = 1.0f64;
        loop {
            let d = j * n.powf(1.0 / r);
            if d >= k {
                break;
            }
            depths.push(d);
            n += 1.0;
            if depths.len() > MAX_PASSES {
                return Err(self.err(b.line, col, "G76 expands to too many passes"));
            }
        }
        depths.push(k);
        for _ in 0..h as usize {
            depths.push(k);
        }
        let dir = if z_end < z0 { -1.0 } else { 1.0 };
        let tq = q.to_radians().tan();
        let (tin, tout) =
            (if l == 1.0 || l == 3.0 { e } else { 0.0 }, if l == 2.0 || l == 3.0 { e } else { 0.0 });
        for d in depths {
            let x = 2.0 * (peak_r + inward * d);
            self.push_pass(Pass {
                index: 0,
                x_start: x,
                x_end: x,
                z_start: z0 + dir * d * tq,
                z_end,
                lead: pitch,
                start: 0,
                source_line: Some(b.line),
                taper_in: tin,
                taper_out: tout,
                x_taper: 2.0 * peak_r,
            });
        }
        self.x = Some(x0);
        self.z = Some(z0);
        Ok(())
    }

    fn sinumerik_block(&mut self, blocks: &[Block], b: &Block, depth: usize) -> Result<bool, Error> {
        // R-parameter assignments run first, in order, so that X=R3 in the same block sees them.
        for w in &b.words {
            if let Some(idx) = w.name.strip_prefix('R').and_then(|s| s.parse::<u32>().ok()) {
                if let Val::Expr(_) = w.val {
                    let v = self.value(b, w)?;
                    self.r.insert(idx, v);
                }
            }
        }
        for w in &b.words {
            match (w.name.as_str(), &w.val) {
                ("DIAMON", Val::Bare) => self.diameter = true,
                ("DIAMOF", Val::Bare) => self.diameter = false,
                ("SF", _) => self.start_offset_deg = self.value(b, w)?,
                ("CYCLE", _) | ("CYCLE97", Val::Args(_)) => {}
                _ => {}
            }
        }
        if b.words.iter().any(|w| w.name == "M" && matches!(w.num(), Some(2.0) | Some(30.0) | Some(17.0))) {
            return Ok(true);
        }
        if let Some(w) = b.words.iter().find(|w| w.name == "CYCLE97") {
            return self.cycle97(b, w).map(|_| false);
        }
        if let Some(w) = b.words.iter().find(|w| w.name.starts_with("CYCLE") || w.name == "LCYC97") {
            return Err(self.werr(
                b,
                w,
                format!("{} is not a threading cycle threadcheck reads (CYCLE97 is)", w.name),
            ));
        }
        // Subprogram call: L9 P33.
        if let Some(w) = words_named(b, "L").next() {
            let name = format!("L{}", w.num().unwrap_or(0.0) as i64);
            let reps = match words_named(b, "P").next() {
                Some(p) => self.value(b, p)?,
                None => 1.0,
            };
            if !whole_in(reps, 0.0, MAX_REPEATS as f64) {
                return Err(self.werr(
                    b,
                    w,
                    format!("{name} P{reps}: repetitions must be a whole number up to {MAX_REPEATS}"),
                ));
            }
            let Some(&(from, to)) = self.subs.get(&name) else {
                let hint = if name == "L97" {
                    " (the old thread cycle L97 is not supported: use CYCLE97 or G33)"
                } else {
                    ""
                };
                return Err(self.werr(b, w, format!("subprogram {name} is not in this file{hint}")));
            };
            if depth + 1 > MAX_CALL_DEPTH {
                return Err(self.werr(
                    b,
                    w,
                    format!("subprogram calls nest deeper than {MAX_CALL_DEPTH}: does {name} call itself?"),
                ));
            }
            for _ in 0..reps as usize {
                self.run(blocks, from, to, depth + 1)?;
            }
            return Ok(false);
        }
        let motion = self.modal(b)?;
        let was_thread = self.last_thread;
        self.last_thread = false;
        let g = match motion {
            Some((g, _)) => {
                self.motion = g;
                g
            }
            None => self.motion,
        };
        if g == 33 {
            let col = motion.map_or(b.col, |m| m.1);
            if let Some(w) = words_named(b, "K").next().or_else(|| words_named(b, "I").next()) {
                let v = self.len(b, w)?;
                if !(v > 0.0) {
                    return Err(self.werr(b, w, "G33 lead must be greater than zero"));
                }
                self.lead = Some(v);
            }
            let (x, z) = self.target(b)?;
            if x.is_none() && z.is_none() {
                self.skipped += 1;
                return Ok(false);
            }
            let lead = self
                .lead
                .ok_or_else(|| self.err(b.line, col, "G33 without a lead: add K (or I for a steep taper)"))?;
            self.check_css(b, "G33");
            self.last_thread = was_thread;
            self.thread_move(b, col, lead, "G33")?;
            self.last_thread = true;
        } else if !self.move_to(b)? {
            self.skipped += 1;
        }
        Ok(false)
    }

    /// CYCLE97(PIT, MPIT, SPL, FPL, DM1, DM2, APP, ROP, TDEP, FAL, IANG, NSP, NRC, NID, VARI, NUMT).
    ///
    /// PIT is the pitch; with NUMT starts the lead is NUMT·PIT and the starts are one pitch
    /// apart. VARI 1/3 external, 2/4 internal (DM1/DM2 are then the tap-hole diameters);
    /// 1/2 constant depth, 3/4 constant chip area.
    /// NRC rough passes to TDEP − FAL, one finishing pass at TDEP, NID idle passes. IANG > 0
    /// infeeds along one flank, IANG < 0 alternates flanks.
    fn cycle97(&mut self, b: &Block, w: &Word) -> Result<(), Error> {
        let Val::Args(args) = &w.val else {
            return Err(self.werr(b, w, "CYCLE97 needs its parameters in ( )"));
        };
        let names = [
            "PIT", "MPIT", "SPL", "FPL", "DM1", "DM2", "APP", "ROP", "TDEP", "FAL", "IANG", "NSP", "NRC",
            "NID", "VARI", "NUMT",
        ];
        if args.len() > names.len() + 4 {
            return Err(self.werr(
                b,
                w,
                format!("CYCLE97 takes {} parameters, not {}", names.len(), args.len()),
            ));
        }
        let mut v = [0.0f64; 16];
        for (k, (text, col)) in args.iter().enumerate().take(16) {
            if let Some(t) = text {
                v[k] = eval(t, &self.r)
                    .map_err(|m| self.err(b.line, *col, format!("CYCLE97 {}: {m}", names[k])))?;
            }
        }
        let [pit, mpit, spl, fpl, dm1, dm2, app, rop, tdep, fal, iang, nsp, nrc, nid, vari, numt] = v;
        let s = self.scale;
        let pitch = if pit > 0.0 {
            pit * s
        } else {
            coarse_pitch_for(mpit)
                .ok_or_else(|| self.werr(b, w, "CYCLE97 needs PIT, or MPIT the metric size 3 to 60"))?
        };
        let vari = if vari == 0.0 { 1.0 } else { vari };
        if ![1.0, 2.0, 3.0, 4.0].contains(&vari) {
            return Err(self.werr(b, w, format!("CYCLE97 VARI {vari} must be 1, 2, 3 or 4")));
        }
        let (tdep, fal) = (tdep * s, fal * s);
        if !(tdep > 0.0 && fal >= 0.0 && fal < tdep) {
            return Err(self.werr(b, w, "CYCLE97 needs TDEP > 0 and 0 ≤ FAL < TDEP"));
        }
        let nrc = if nrc == 0.0 { 1.0 } else { nrc };
        let numt = if numt == 0.0 { 1.0 } else { numt };
        if !whole_in(nrc, 1.0, MAX_REPEATS as f64)
            || !whole_in(nid, 0.0, MAX_REPEATS as f64)
            || !whole_in(numt, 1.0, 64.0)
        {
            return Err(self.werr(b, w, "CYCLE97 NRC, NID and NUMT must be whole numbers in range"));
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
        for _ in 0..nid as usize {
            depths.push(tdep);
        }
        let infeed = if iang > 0.0 {
            crate::passes::Infeed::Flank { angle: iang }
        } else if iang < 0.0 {
            crate::passes::Infeed::Alternating { angle: -iang }
        } else {
            crate::passes::Infeed::Radial
        };
        let (spl, fpl) = (spl * s, fpl * s);
        let dir = if fpl < spl { -1.0 } else { 1.0 };
        let offsets = crate::passes::infeed_offsets(infeed, &depths, dir);
        let lead = pitch * numt;
        let (d1, d2) = (dm1 * s, dm2 * s);
        for start in 0..numt as u32 {
            let phase = f64::from(start) * pitch + nsp / 360.0 * lead;
            for (d, off) in depths.iter().zip(&offsets) {
                // External: DM is the major diameter, cut inwards. Internal: DM is the tap-hole
                // diameter, cut outwards (Sinumerik cycle documentation).
                let xd = |dm: f64| if external { dm - 2.0 * d } else { dm + 2.0 * d };
                self.push_pass(Pass {
                    index: 0,
                    x_start: xd(d1),
                    x_end: xd(d2),
                    z_start: spl - dir * app * s + off - dir * phase,
                    z_end: fpl + dir * rop * s,
                    lead,
                    start,
                    source_line: Some(b.line),
                    taper_in: 0.0,
                    taper_out: 0.0,
                    x_taper: xd(d2),
                });
            }
        }
        Ok(())
    }
}

/// True for a whole number in `[lo, hi]` (false for NaN).
fn whole_in(v: f64, lo: f64, hi: f64) -> bool {
    v >= lo && v <= hi && v.fract() == 0.0
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

/// Evaluates a Sinumerik arithmetic expression: numbers, R-parameters, + − * /, parentheses,
/// unary signs, and SIN COS TAN (degrees), SQRT, ABS.
pub fn eval(expr: &str, r: &HashMap<u32, f64>) -> Result<f64, String> {
    let chars: Vec<char> = expr.chars().filter(|c| !c.is_whitespace()).collect();
    let mut i = 0;
    let v = sum(&chars, &mut i, r, 0)?;
    if i != chars.len() {
        return Err(format!("unexpected '{}' in the expression", chars[i]));
    }
    if !v.is_finite() {
        return Err("the expression is not a finite number".into());
    }
    Ok(v)
}

fn sum(c: &[char], i: &mut usize, r: &HashMap<u32, f64>, depth: usize) -> Result<f64, String> {
    let mut v = product(c, i, r, depth)?;
    while *i < c.len() && matches!(c[*i], '+' | '-') {
        let op = c[*i];
        *i += 1;
        let w = product(c, i, r, depth)?;
        v = if op == '+' { v + w } else { v - w };
    }
    Ok(v)
}

fn product(c: &[char], i: &mut usize, r: &HashMap<u32, f64>, depth: usize) -> Result<f64, String> {
    let mut v = unary(c, i, r, depth)?;
    while *i < c.len() && matches!(c[*i], '*' | '/') {
        let op = c[*i];
        *i += 1;
        let w = unary(c, i, r, depth)?;
        if op == '/' && w == 0.0 {
            return Err("division by zero".into());
        }
        v = if op == '*' { v * w } else { v / w };
    }
    Ok(v)
}

fn unary(c: &[char], i: &mut usize, r: &HashMap<u32, f64>, depth: usize) -> Result<f64, String> {
    if depth > 64 {
        return Err("the expression nests too deeply".into());
    }
    match c.get(*i) {
        Some('-') => {
            *i += 1;
            Ok(-unary(c, i, r, depth + 1)?)
        }
        Some('+') => {
            *i += 1;
            unary(c, i, r, depth + 1)
        }
        Some('(') => {
            *i += 1;
            let v = sum(c, i, r, depth + 1)?;
            if c.get(*i) != Some(&')') {
                return Err("')' missing".into());
            }
            *i += 1;
            Ok(v)
        }
        Some(ch) if ch.is_ascii_digit() || *ch == '.' => {
            let s = *i;
            while *i < c.len() && (c[*i].is_ascii_digit() || c[*i] == '.') {
                *i += 1;
            }
            let t: String = c[s..*i].iter().collect();
            t.parse::<f64>().map_err(|_| format!("'{t}' is not a number"))
        }
        Some(ch) if ch.is_ascii_alphabetic() => {
            let s = *i;
            while *i < c.len() && c[*i].is_ascii_alphabetic() {
                *i += 1;
            }
            let name: String = c[s..*i].iter().collect::<String>().to_ascii_uppercase();
            if name == "R" {
                let ds = *i;
                while *i < c.len() && c[*i].is_ascii_digit() {
                    *i += 1;
                }
                let idx: u32 = c[ds..*i]
                    .iter()
                    .collect::<String>()
                    .parse()
                    .map_err(|_| "R needs a parameter number".to_string())?;
                return r.get(&idx).copied().ok_or_else(|| format!("R{idx} is used before it is set"));
            }
            let f: fn(f64) -> f64 = match name.as_str() {
                "SIN" => |x: f64| x.to_radians().sin(),
                "COS" => |x: f64| x.to_radians().cos(),
                "TAN" => |x: f64| x.to_radians().tan(),
                "SQRT" => f64::sqrt,
                "ABS" => f64::abs,
                _ => return Err(format!("unknown name {name}")),
            };
            if c.get(*i) != Some(&'(') {
                return Err(format!("{name} needs ( )"));
            }
            let v = unary(c, i, r, depth + 1)?;
            Ok(f(v))
        }
        Some(ch) => Err(format!("unexpected '{ch}'")),
        None => Err("the expression ends too early".into()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn expressions() {
        let mut r = HashMap::new();
        r.insert(3, 20.0);
        assert_eq!(eval("R3-0.05", &r).unwrap(), 19.95);
        assert_eq!(eval("-(R3+1)*2/4", &r).unwrap(), -10.5);
        assert!((eval("SQRT(16)+SIN(30)", &r).unwrap() - 4.5).abs() < 1e-12);
        assert!(eval("R4", &r).unwrap_err().contains("before it is set"));
        assert!(eval("R3/0", &r).is_err());
        assert!(eval("((((", &r).is_err());
    }
}
