//! Splits a program into blocks of words and macro statements, per dialect, keeping the line and
//! column of everything (columns count characters of the line as written, blanks included) and
//! whether each number had a decimal point (Fanuc reads some words in least-input increments).
//!
//! Fanuc, Haas, LinuxCNC and Dyna ignore blanks outside comments, so `O 1234`, `S 500` and
//! `X 84` are `O1234`, `S500` and `X84`: the line is read with its blanks taken out, and a map
//! keeps every character's column. Sinumerik separates words with blanks and writes expressions
//! after `=`, so it is read token by token, blanks allowed around `=` and between an address and
//! its number (`I 1.82`).

use super::expr::{Expr, Parser, Syntax, VarRef};
use super::Dialect;

/// A word's value as written.
#[derive(Clone, Debug, PartialEq)]
pub enum WVal {
    /// A number, and whether it was written with a decimal point.
    Num {
        /// The value.
        v: f64,
        /// Written with a decimal point.
        point: bool,
    },
    /// An expression (`X[#1+2]`, `X#24`, Sinumerik `X=R3`), evaluated when the block runs.
    Expr(Expr),
    /// Arguments of a Sinumerik call such as `CYCLE97(1.5,,0,…)`: each parsed (None where
    /// empty) with its column.
    Args(Vec<(Option<Expr>, usize)>),
    /// A bare name (`DIAMON`).
    Bare,
}

/// One word: an address (upper case) and its value, at a column.
#[derive(Clone, Debug, PartialEq)]
pub struct Word {
    /// Address: `X`, `G`, `CYCLE97`, `SF`, …
    pub name: String,
    /// The value.
    pub val: WVal,
    /// 1-based column of the word's first character.
    pub col: usize,
    /// The word as written (`P1.950`), for messages.
    pub text: String,
}

/// A LinuxCNC O-word keyword.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OKw {
    /// `sub`
    Sub,
    /// `endsub`
    EndSub,
    /// `call`
    Call,
    /// `return`
    Return,
    /// `while`
    While,
    /// `endwhile`
    EndWhile,
    /// `do`
    Do,
    /// `if`
    If,
    /// `elseif`
    ElseIf,
    /// `else`
    Else,
    /// `endif`
    EndIf,
    /// `repeat`
    Repeat,
    /// `endrepeat`
    EndRepeat,
    /// `break`
    Break,
    /// `continue`
    Continue,
}

/// A macro statement.
#[derive(Clone, Debug, PartialEq)]
pub enum Stmt {
    /// `#1=…`, `R3=…`.
    Assign {
        /// The variable set.
        var: VarRef,
        /// Its new value.
        expr: Expr,
        /// Column of the variable.
        col: usize,
        /// The statement as written, for messages.
        text: String,
    },
    /// Fanuc `GOTO n`.
    Goto {
        /// The sequence number.
        target: Expr,
        /// Column.
        col: usize,
    },
    /// Fanuc `IF [c] GOTO n`.
    IfGoto {
        /// Condition.
        cond: Expr,
        /// Sequence number.
        target: Expr,
        /// Column.
        col: usize,
    },
    /// Fanuc `IF [c] THEN #i=…`.
    IfThen {
        /// Condition.
        cond: Expr,
        /// The assignment done when true.
        then: Box<Stmt>,
        /// Column.
        col: usize,
    },
    /// Fanuc `WHILE [c] DOm`.
    While {
        /// Condition.
        cond: Expr,
        /// Loop number m.
        id: u32,
        /// Column.
        col: usize,
    },
    /// Fanuc `DOm` without WHILE: an endless loop.
    Do {
        /// Loop number.
        id: u32,
        /// Column.
        col: usize,
    },
    /// Fanuc `ENDm`.
    End {
        /// Loop number.
        id: u32,
        /// Column.
        col: usize,
    },
    /// Sinumerik `GOTOF label`, `GOTOB label`, `GOTO label`, optionally behind `IF cond`.
    Jump {
        /// Some(true) forward, Some(false) backward, None both (GOTO).
        forward: Option<bool>,
        /// Label or sequence number (`N100`).
        label: String,
        /// Condition.
        cond: Option<Expr>,
        /// Column.
        col: usize,
    },
    /// A LinuxCNC O-word.
    O {
        /// Its name: `100` or `<threading>` (lower case).
        name: String,
        /// The keyword.
        kw: OKw,
        /// The bracketed condition (while, if, elseif, repeat count, do … while) or return value.
        cond: Option<Expr>,
        /// Call arguments.
        args: Vec<Expr>,
        /// Column.
        col: usize,
    },
}

/// A block.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Block {
    /// The file it stands in: 0 the program's own, else a subprogram's file read beside it.
    pub file: usize,
    /// 1-based line.
    pub line: usize,
    /// Column of the first word.
    pub col: usize,
    /// Sequence number `N…`, if the block starts with one.
    pub n: Option<f64>,
    /// A Sinumerik label (`MARK1:`).
    pub label: Option<String>,
    /// A program header: Fanuc `O1234`, a Sinumerik subprogram (`L9` alone on its line after the
    /// main program, or `%_N_L9_SPF`).
    pub header: Option<String>,
    /// The words in order.
    pub words: Vec<Word>,
    /// Macro statements in order.
    pub stmts: Vec<Stmt>,
    /// What the block holds that threadcheck does not model (a message, a tool called by name,
    /// a call of a cycle that is not threading): read past with a note, never silently.
    pub past: Vec<Past>,
    /// It begins with `/`: the control's block-delete switch decides whether it runs.
    pub block_delete: bool,
}

/// Something in a block that threadcheck reads past.
#[derive(Clone, Debug, PartialEq)]
pub struct Past {
    /// What it is: `MSG`, `T="ROUGH"`, `CYCLE95`, `(MSG,…)`.
    pub name: String,
    /// What kind of thing it is.
    pub kind: PastKind,
    /// 1-based column.
    pub col: usize,
}

/// The kinds of things read past in the lexer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PastKind {
    /// A Denford simulator's stock line (`[BILLET X30 Z60`): on a lathe X the bar's diameter,
    /// Z its length (mm as written).
    Billet {
        /// X as written.
        x: Option<f64>,
        /// Z as written.
        z: Option<f64>,
    },
    /// Another line of a training simulator's set-up (`[TOOLDEF T1 D6`, `[EDGEMOVE X0`, `[STEP …`).
    Simulator,
    /// A message or display for the operator (`MSG("…")`, LinuxCNC `(MSG,…)`).
    Message,
    /// A tool called by name (`T="ROUGH"`).
    ToolName,
    /// A call of a named cycle or function with its arguments (`CYCLE95("CONT",…)`).
    Call,
    /// A Heidenhain DIN PLUS section of set-up or contour data (`BLANK`, `FINISHED`, …): its
    /// blocks are geometry and data, not moves.
    Section,
    /// An Okuma rotary (live) tool's spindle speed `SB=…`: a setting threadcheck does not model.
    RotarySpeed,
    /// An Okuma LAP cycle (`G85 NTURN D… U… W… F…`): rough turning of the shape the named
    /// sequence starts (its own blocks, `NTURN G81` to `G80`, follow and are read as moves).
    Lap,
    /// An Okuma block that names a sequence as its operand (`GOTO NSTRT`): a jump not followed.
    SequenceJump,
    /// The start of an Okuma LAP cycle's shape (`NSHP G81`: G81 a longitudinal shape, G82 a
    /// transverse one, G83 a shape copied, to the G80 that ends it).
    LapShape,
}

impl Block {
    fn new(line: usize) -> Block {
        Block { line, col: 1, ..Block::default() }
    }

    /// The block with no spare capacity: a program of a million one-word blocks held 400 bytes
    /// of unused word slots in each.
    fn compact(mut self) -> Block {
        self.words.shrink_to_fit();
        self.stmts.shrink_to_fit();
        self.past.shrink_to_fit();
        for w in &mut self.words {
            w.name.shrink_to_fit();
            w.text.shrink_to_fit();
        }
        self
    }

    fn is_empty(&self) -> bool {
        self.n.is_none()
            && self.label.is_none()
            && self.header.is_none()
            && self.words.is_empty()
            && self.stmts.is_empty()
            && self.past.is_empty()
    }
}

/// A lexing error: line, column, message.
pub type LexError = (usize, usize, String);

/// Splits `text` into blocks. A UTF-8 byte-order mark is skipped; CR LF line ends are accepted.
pub fn lex(text: &str, dialect: Dialect) -> Result<Vec<Block>, LexError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut blocks = Vec::new();
    let mut section = Section::Moves;
    // Sinumerik: whether the main program has ended (M2, M30 or M17, or a subprogram began):
    // a line holding only `L9` starts subprogram L9 after it and calls it before it.
    let mut main_ended = false;
    for (i, raw) in text.split('\n').enumerate() {
        let line = raw.strip_suffix('\r').unwrap_or(raw);
        // LinuxCNC reads lines shorter than its LINELEN, 255 bytes (`src/emc/linuxcnc.h`), and
        // refuses a longer one ("Command too long", `interp_read.cc`).
        if dialect == Dialect::LinuxCnc && line.len() >= 255 {
            return Err((
                i + 1,
                255,
                format!(
                    "the line is {} bytes long: LinuxCNC reads lines of at most 254 (Command too long)",
                    line.len()
                ),
            ));
        }
        match dialect {
            Dialect::Sinumerik => {
                let before = blocks.len();
                sinumerik_line(line, i + 1, main_ended, &mut blocks)?;
                main_ended = main_ended
                    || blocks[before..].iter().any(|b| {
                        b.header.is_some() || b.words.iter().any(|w| {
                            w.name == "M"
                                && matches!(w.val, WVal::Num { v, .. } if v == 2.0 || v == 30.0 || v == 17.0)
                        })
                    });
            }
            // An OSP header line (`$NAME.MIN%`) names the file: nothing to run.
            Dialect::Okuma if line.trim_start().starts_with('$') => {}
            Dialect::Heidenhain => heidenhain_line(line, i + 1, &mut section, &mut blocks)?,
            // Klartext is not G-code: its own reader (klartext.rs) reads it, never this lexer.
            Dialect::Klartext => {
                return Err((
                    i + 1,
                    1,
                    "a Klartext program is read by the Klartext reader, not as G-code".into(),
                ))
            }
            Dialect::Okuma => okuma_line(line, i + 1, &mut blocks)?,
            // A training simulator's set-up line (Denford's `[BILLET X30 Z60`, `[TOOLDEF T1 D6`).
            Dialect::Fanuc | Dialect::Haas | Dialect::Dyna | Dialect::Mitsubishi | Dialect::Mazak
                if simulator_line(line, i + 1, &mut blocks) => {}
            Dialect::Fanuc
            | Dialect::Haas
            | Dialect::LinuxCnc
            | Dialect::Dyna
            | Dialect::Mitsubishi
            | Dialect::Mazak => bracket_line(line, i + 1, dialect, &mut blocks)?,
        }
    }
    Ok(blocks)
}

/// A training simulator's set-up line, as Denford's Fanuc simulators read them: `[` and a word
/// at the line's start (`[BILLET X30 Z60`, `[TOOLDEF T01 D.5`, `[EDGEMOVE X0 Y0`), to the line's
/// end (a closing `]` or `;` is fine). `BILLET` declares the stock; the others are read past.
/// False when the line is not one.
fn simulator_line(line: &str, ln: usize, blocks: &mut Vec<Block>) -> bool {
    let trimmed = line.trim_start();
    let Some(rest) = trimmed.strip_prefix('[') else { return false };
    let word: String = rest.chars().take_while(char::is_ascii_alphabetic).collect();
    if word.len() < 3 {
        return false;
    }
    let col = line.len() - trimmed.len() + 1;
    let upper = rest.to_ascii_uppercase();
    let value = |letter: char| -> Option<f64> {
        let i = upper[word.len()..].find(letter)? + word.len() + 1;
        let num: String =
            upper[i..].chars().take_while(|c| c.is_ascii_digit() || matches!(c, '.' | '-' | '+')).collect();
        num.parse().ok()
    };
    let kind = if word.eq_ignore_ascii_case("BILLET") {
        PastKind::Billet { x: value('X'), z: value('Z') }
    } else {
        PastKind::Simulator
    };
    let shown: String = trimmed.trim_end_matches([']', ';', ' ']).chars().take(40).collect();
    let mut b = Block::new(ln);
    b.past.push(Past { name: shown, kind, col });
    blocks.push(b);
    true
}

/// An OSP line as shops write it (Okuma 5238-E): a sequence name (`NAT06`, `NSTRT`: N and a
/// letter) labels the block; `SB=1200`, a rotary tool's speed, is read past; `CALL O…`, a
/// subprogram call, is read past as a call whose end position is not modelled (its threading,
/// if any, is not read: the note says so). The rest is read as ever, at its own columns.
fn okuma_line(line: &str, ln: usize, blocks: &mut Vec<Block>) -> Result<(), LexError> {
    let mut chars: Vec<char> = line.chars().collect();
    let mut label = None;
    let mut past = Vec::new();
    let start = chars.iter().position(|c| !c.is_whitespace()).unwrap_or(chars.len());
    let code_end = chars.iter().position(|&c| c == '(').unwrap_or(chars.len());
    if chars.get(start) == Some(&'N') && chars.get(start + 1).is_some_and(|c| c.is_ascii_uppercase()) {
        let end = (start + 1..code_end).find(|&k| !chars[k].is_ascii_alphanumeric()).unwrap_or(code_end);
        label = Some(chars[start..end].iter().collect::<String>());
        chars[start..end].iter_mut().for_each(|c| *c = ' ');
    }
    // A sequence name as an operand (`G85 NTURN …`, `GOTO NSTRT`): the LAP cycle or the jump is
    // the whole block, read past by name.
    let operand = (start..code_end).find(|&k| {
        (k == 0 || !chars[k - 1].is_ascii_alphanumeric())
            && chars[k] == 'N'
            && chars.get(k + 1).is_some_and(|c| c.is_ascii_uppercase())
    });
    if let Some(at) = operand {
        let head: String = chars[start..at].iter().collect::<String>().trim().to_string();
        let name_end = (at + 1..code_end).find(|&k| !chars[k].is_ascii_alphanumeric()).unwrap_or(code_end);
        let seq: String = chars[at..name_end].iter().collect();
        // `/` is block delete: `/G85 …` is the LAP cycle too.
        let lap = head
            .split_whitespace()
            .any(|w| ["G85", "G86", "G87", "G88"].contains(&w.trim_start_matches('/')));
        let kind = if lap { PastKind::Lap } else { PastKind::SequenceJump };
        let name = format!("{} {seq}", head.trim_start_matches('/').trim());
        chars[start..code_end].iter_mut().for_each(|c| *c = ' ');
        past.push(Past { name: name.trim().to_string(), kind, col: start + 1 });
    }
    // A labelled G81, G82 or G83 opens a LAP cycle's shape (a lathe's OSP has them so), not a
    // drilling cycle.
    if label.is_some() {
        for g in ["G81", "G82", "G83"] {
            let gc: Vec<char> = g.chars().collect();
            let found = (start..code_end.saturating_sub(2)).find(|&k| {
                chars[k..].starts_with(&gc)
                    && (k == 0 || !chars[k - 1].is_ascii_alphanumeric())
                    && chars.get(k + 3).is_none_or(|c| !c.is_ascii_digit() && *c != '.')
            });
            if let Some(k) = found {
                chars[k..k + 3].iter_mut().for_each(|c| *c = ' ');
                past.push(Past { name: g.to_string(), kind: PastKind::LapShape, col: k + 1 });
            }
        }
    }
    let mut k = 0;
    while k + 3 <= code_end {
        let word_start = k == 0 || !chars[k - 1].is_ascii_alphanumeric();
        if word_start && chars[k..].starts_with(&['S', 'B', '=']) {
            let end = (k + 3..code_end)
                .find(|&e| !(chars[e].is_ascii_digit() || matches!(chars[e], '.' | '-' | '+')))
                .unwrap_or(code_end);
            past.push(Past { name: chars[k..end].iter().collect(), kind: PastKind::RotarySpeed, col: k + 1 });
            chars[k..end].iter_mut().for_each(|c| *c = ' ');
            k = end;
        } else if word_start
            && chars[k..].starts_with(&['C', 'A', 'L', 'L'])
            && chars.get(k + 4) == Some(&' ')
        {
            let end = (k + 5..code_end).find(|&e| chars[e].is_whitespace() && e > k + 5).unwrap_or(code_end);
            let name: String = chars[k..end].iter().collect();
            past.push(Past { name: name.trim_end().to_string(), kind: PastKind::Call, col: k + 1 });
            chars[k..end].iter_mut().for_each(|c| *c = ' ');
            k = end;
        } else {
            k += 1;
        }
    }
    let before = blocks.len();
    let cleaned: String = chars.into_iter().collect();
    bracket_line(&cleaned, ln, Dialect::Okuma, blocks)?;
    if label.is_some() || !past.is_empty() {
        if blocks.len() == before {
            blocks.push(Block::new(ln));
        }
        if let Some(b) = blocks.last_mut() {
            b.label = b.label.take().or(label);
            b.past.extend(past);
        }
    }
    Ok(())
}

/// Where a Heidenhain DIN PLUS program's line stands: among moves (the `MACHINING` section, or
/// a program without sections) or in a section of data read past.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Section {
    Moves,
    Data,
}

/// The DIN PLUS section codes (English and German, as the MANUALplus 620 / CNC PILOT 640
/// manuals write them) and whether their blocks are moves.
const HEIDENHAIN_SECTIONS: [(&str, Section); 26] = [
    ("MACHINING", Section::Moves),
    ("BEARBEITUNG", Section::Moves),
    ("SUBPROGRAM", Section::Moves),
    ("UNTERPROGRAMM", Section::Moves),
    ("HEADER", Section::Data),
    ("PROGRAMMKOPF", Section::Data),
    ("TURRET", Section::Data),
    ("REVOLVER", Section::Data),
    ("CHUCKING", Section::Data),
    ("SPANNMITTEL", Section::Data),
    ("BLANK", Section::Data),
    ("ROHTEIL", Section::Data),
    ("FINISHED", Section::Data),
    ("FERTIGTEIL", Section::Data),
    ("AUXIL_BLANK", Section::Data),
    ("HILFSROHTEIL", Section::Data),
    ("AUXIL_CONTOUR", Section::Data),
    ("HILFSKONTUR", Section::Data),
    ("FRONT", Section::Data),
    ("STIRN", Section::Data),
    ("LATERAL", Section::Data),
    ("MANTEL", Section::Data),
    ("REAR_SIDE", Section::Data),
    ("RUECKSEITE", Section::Data),
    ("END", Section::Data),
    ("ENDE", Section::Data),
];

/// One line of a Heidenhain MANUALplus / CNC PILOT DIN program: `%name` names the file, `[ … ]`
/// is a comment, a section code alone on its line (`FINISHED`, `MACHINING`, …) switches between
/// data read past (one note for the section) and moves; the rest lexes as Fanuc's.
fn heidenhain_line(
    line: &str,
    ln: usize,
    section: &mut Section,
    out: &mut Vec<Block>,
) -> Result<(), LexError> {
    let trimmed = line.trim();
    if trimmed.starts_with('%') {
        return Ok(());
    }
    let first = trimmed.split_whitespace().next().unwrap_or("");
    if let Some(&(name, s)) = HEIDENHAIN_SECTIONS.iter().find(|(n, _)| first.eq_ignore_ascii_case(n)) {
        *section = s;
        if s == Section::Data {
            let col = line.len() - line.trim_start().len() + 1;
            let mut b = Block::new(ln);
            b.past.push(Past { name: name.to_string(), kind: PastKind::Section, col });
            out.push(b);
        }
        return Ok(());
    }
    if *section == Section::Data {
        return Ok(());
    }
    // `[ … ]` comments become blanks, keeping every other character's column.
    let mut kept = String::with_capacity(line.len());
    let mut open: Option<usize> = None;
    for (i, c) in line.chars().enumerate() {
        match (c, open) {
            ('[', None) => {
                open = Some(i + 1);
                kept.push(' ');
            }
            (']', Some(_)) => {
                open = None;
                kept.push(' ');
            }
            (_, Some(_)) => kept.push(' '),
            (c, None) => kept.push(c),
        }
    }
    if let Some(col) = open {
        return Err((ln, col, "a comment opened with [ is not closed with ] on its line".to_string()));
    }
    bracket_line(&kept, ln, Dialect::Heidenhain, out)
}

/// The expression syntax of a dialect.
pub fn syntax_of(d: Dialect) -> Syntax {
    d.facts().syntax
}

/// One line of a bracket dialect, blanks removed, with the column of every kept character.
struct Squeezed {
    c: Vec<char>,
    col: Vec<usize>,
    /// LinuxCNC's message comments in the segment: `(MSG,…)`, `(DEBUG,…)`, `(PRINT,…)`.
    past: Vec<Past>,
}

impl Squeezed {
    fn col_at(&self, i: usize) -> usize {
        self.col.get(i).copied().unwrap_or_else(|| self.col.last().map_or(1, |c| c + 1))
    }
}

/// Takes comments out and splits at `;` where it ends a block (Fanuc, Haas, Dyna); LinuxCNC's
/// `;` starts a comment.
fn squeeze(line: &str, ln: usize, dialect: Dialect) -> Result<Vec<Squeezed>, LexError> {
    let chars: Vec<char> = line.chars().collect();
    let mut out = vec![Squeezed { c: Vec::new(), col: Vec::new(), past: Vec::new() }];
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        match c {
            ' ' | '\t' => i += 1,
            '(' => {
                let close = chars[i..].iter().position(|&x| x == ')').ok_or((
                    ln,
                    i + 1,
                    "comment '(' is not closed on this line".to_string(),
                ))?;
                if dialect == Dialect::LinuxCnc {
                    let inner: String = chars[i + 1..i + close].iter().collect();
                    let head = inner.trim_start().to_ascii_uppercase();
                    if let Some(kw) = ["MSG,", "DEBUG,", "PRINT,"].iter().find(|k| head.starts_with(**k)) {
                        if let Some(s) = out.last_mut() {
                            s.past.push(Past {
                                name: format!("({}…)", kw),
                                kind: PastKind::Message,
                                col: i + 1,
                            });
                        }
                    }
                }
                i += close + 1;
            }
            // A semicolon is a comment to the line's end in LinuxCNC, the end of a block elsewhere.
            ';' if semicolon_ends_line(dialect) => break,
            ';' => {
                out.push(Squeezed { c: Vec::new(), col: Vec::new(), past: Vec::new() });
                i += 1;
            }
            _ => {
                if let Some(s) = out.last_mut() {
                    s.c.push(c.to_ascii_uppercase());
                    s.col.push(i + 1);
                }
                i += 1;
            }
        }
    }
    Ok(out)
}

fn bracket_line(line: &str, ln: usize, dialect: Dialect, out: &mut Vec<Block>) -> Result<(), LexError> {
    // LinuxCNC named parameters keep their case-insensitive names; everything is upper case here
    // and names are lower-cased when read.
    let trimmed = line.trim();
    if trimmed.starts_with('%') {
        return Ok(());
    }
    for seg in squeeze(line, ln, dialect)? {
        if seg.c.is_empty() && seg.past.is_empty() {
            continue;
        }
        let mut b = Block::new(ln);
        bracket_block(&seg, ln, dialect, &mut b)?;
        b.past = seg.past;
        if !b.is_empty() {
            out.push(b.compact());
        }
    }
    Ok(())
}

fn letters(c: &[char], i: usize) -> String {
    let mut j = i;
    while j < c.len() && c[j].is_ascii_alphabetic() {
        j += 1;
    }
    c[i..j].iter().collect()
}

/// The letters at `i` that stand together in the line as written (`X INF` is X, then INF).
fn adjacent_letters(s: &Squeezed, i: usize) -> String {
    let c = &s.c;
    let mut j = i;
    while j < c.len() && c[j].is_ascii_alphabetic() && (j == i || s.col_at(j) == s.col_at(j - 1) + 1) {
        j += 1;
    }
    c[i..j].iter().collect()
}

fn bracket_block(s: &Squeezed, ln: usize, dialect: Dialect, b: &mut Block) -> Result<(), LexError> {
    let c = &s.c;
    let syntax = syntax_of(dialect);
    let perr = |i: usize, m: String| (ln, s.col_at(i), m);
    let mut i = 0;
    if c.first() == Some(&'/') {
        // Block delete: the reader runs or skips it as the switch says.
        b.block_delete = true;
        i += 1;
    }
    b.col = s.col_at(i);
    // Sequence number.
    if c.get(i) == Some(&'N') && c.get(i + 1).is_some_and(|d| d.is_ascii_digit()) {
        let mut j = i + 1;
        while j < c.len() && (c[j].is_ascii_digit() || c[j] == '.') {
            j += 1;
        }
        let t: String = c[i + 1..j].iter().collect();
        b.n = t.parse().ok();
        i = j;
    }
    // Program headers and O-words.
    if c.get(i) == Some(&'O') || (c.get(i) == Some(&':') && i == 0) {
        let o_col = i;
        let j = i + 1;
        if o_words_are_flow(dialect) {
            return o_word(s, j, ln, b, o_col);
        }
        let mut k = j;
        while k < c.len() && c[k].is_ascii_digit() {
            k += 1;
        }
        if k == j {
            return Err(perr(o_col, "O must be followed by the program number".into()));
        }
        let num: String = c[j..k].iter().collect();
        if k < c.len() && letters(c, k).len() > 1 {
            let w = letters(c, k).to_ascii_lowercase();
            return Err(perr(
                o_col,
                format!(
                    "'o{num} {w}' is a LinuxCNC O-word; in the {} dialect O{num} names a program (subprograms end with M99 and are called with M98 P{num})",
                    dialect.name()
                ),
            ));
        }
        b.header = Some(format!("O{}", num.trim_start_matches('0')));
        if k < c.len() {
            // `O1000 G0 …`: the rest is an ordinary block.
            i = k;
        } else {
            return Ok(());
        }
    }
    while i < c.len() {
        let ch = c[i];
        if ch == '#' {
            // Assignment: #n=expr.
            let mut p = Parser::new(c, i, syntax);
            let var = p.var().map_err(|(o, m)| perr(o, m))?;
            if c.get(p.i) != Some(&'=') {
                return Err(perr(i, format!("{var} stands alone: write {var}=value, or use it in a word")));
            }
            p.i += 1;
            let expr = p.expr().map_err(|(o, m)| perr(o, m))?;
            let text = line_text(s, i, p.i);
            b.stmts.push(Stmt::Assign { var, expr, col: s.col_at(i), text });
            i = p.i;
            continue;
        }
        // LinuxCNC's polar coordinates: `@` the distance from the origin, `^` the angle.
        if dialect == Dialect::LinuxCnc && (ch == '@' || ch == '^') {
            let start = i;
            i += 1;
            let name = ch.to_string();
            let val = value(s, &mut i, ln, &name, syntax)?;
            let text: String = line_text(s, start, i);
            b.words.push(Word { name, val, col: s.col_at(start), text });
            continue;
        }
        if !ch.is_ascii_alphabetic() {
            return Err(perr(i, format!("unexpected character '{ch}'")));
        }
        let w = adjacent_letters(s, i);
        if w.len() > 1 {
            i = keyword(s, i, &w, ln, dialect, b)?;
            continue;
        }
        // One-letter address and its value.
        let start = i;
        i += 1;
        let val = value(s, &mut i, ln, &w, syntax)?;
        let text: String = line_text(s, start, i);
        b.words.push(Word { name: w, val, col: s.col_at(start), text });
    }
    Ok(())
}

fn line_text(s: &Squeezed, from: usize, to: usize) -> String {
    s.c[from..to.min(s.c.len())].iter().collect()
}

/// The value of a one-letter address at `c[*i]`: a number (with decimal-comma and exponent
/// checks), or an expression (`#1`, `-#1`, `[…]`).
fn value(s: &Squeezed, i: &mut usize, ln: usize, name: &str, syntax: Syntax) -> Result<WVal, LexError> {
    let c = &s.c;
    let perr = |i: usize, m: String| (ln, s.col_at(i), m);
    let mut j = *i;
    while j < c.len() && matches!(c[j], '-' | '+') {
        j += 1;
    }
    let is_expr = matches!(c.get(j), Some('#' | '['))
        || (c.get(j).is_some_and(|x| x.is_ascii_alphabetic())
            && syntax == Syntax::Dyna
            && letters(c, j).len() > 1);
    if is_expr {
        let mut p = Parser::new(c, *i, syntax);
        let e = p.unary().map_err(|(o, m)| perr(o, format!("{name}: {m}")))?;
        *i = p.i;
        return Ok(WVal::Expr(e));
    }
    let start = *i;
    if !(c.get(j).is_some_and(|x| x.is_ascii_digit() || *x == '.')) || j > *i + 1 {
        return Err(perr(start.saturating_sub(1), format!("word {name} has no number")));
    }
    *i = j;
    let mut point = false;
    let mut digits = 0;
    while *i < c.len() && (c[*i].is_ascii_digit() || (c[*i] == '.' && !point)) {
        if c[*i] == '.' {
            point = true;
        } else {
            digits += 1;
        }
        *i += 1;
    }
    let text: String = c[start..*i].iter().collect();
    if *i + 1 < c.len() && c[*i] == ',' && c[*i + 1].is_ascii_digit() {
        let mut k = *i + 1;
        while k < c.len() && c[k].is_ascii_digit() {
            k += 1;
        }
        let frac: String = c[*i + 1..k].iter().collect();
        return Err(perr(
            start - 1,
            format!("decimal comma in {name}{text},{frac}: write {name}{text}.{frac}"),
        ));
    }
    if digits == 0 {
        return Err(perr(start - 1, format!("word {name} has no number")));
    }
    // `X1e309` would otherwise read as X1 and an E word: G-code has no exponents. Only when the
    // E stands right after the digits in the line as written (`H3 E5` is two words).
    if *i + 1 < c.len()
        && c[*i] == 'E'
        && s.col_at(*i) == s.col_at(*i - 1) + 1
        && (c[*i + 1].is_ascii_digit()
            || (matches!(c[*i + 1], '+' | '-') && c.get(*i + 2).is_some_and(|x| x.is_ascii_digit())))
        && s.col_at(*i + 1) == s.col_at(*i) + 1
    {
        let mut k = *i + 1;
        if matches!(c[k], '+' | '-') {
            k += 1;
        }
        while k < c.len() && c[k].is_ascii_digit() {
            k += 1;
        }
        let all: String = c[start..k].iter().collect::<String>().replace('E', "e");
        return Err(perr(
            start - 1,
            format!("{name}{all}: G-code numbers have no exponent; write the value in full"),
        ));
    }
    let v: f64 = text.parse().map_err(|_| perr(start, format!("'{name}{text}' is not a number")))?;
    if !v.is_finite() {
        return Err(perr(start, format!("'{name}{text}' is not a finite number")));
    }
    Ok(WVal::Num { v, point })
}

/// A bracketed condition at `c[*i]` (`[…]`).
fn bracketed(s: &Squeezed, i: &mut usize, ln: usize, syntax: Syntax, what: &str) -> Result<Expr, LexError> {
    if s.c.get(*i) != Some(&'[') {
        return Err((ln, s.col_at(*i), format!("{what} needs its condition in [ ]")));
    }
    let mut p = Parser::new(&s.c, *i, syntax);
    let e = p.unary().map_err(|(o, m)| (ln, s.col_at(o), m))?;
    *i = p.i;
    Ok(e)
}

fn loop_id(s: &Squeezed, i: &mut usize, ln: usize, what: &str) -> Result<u32, LexError> {
    let st = *i;
    while *i < s.c.len() && s.c[*i].is_ascii_digit() {
        *i += 1;
    }
    let t: String = s.c[st..*i].iter().collect();
    t.parse::<u32>().ok().filter(|n| (1..=9).contains(n)).ok_or((
        ln,
        s.col_at(st),
        format!("{what} needs a loop number 1 to 9"),
    ))
}

/// A multi-letter keyword of the macro languages at `c[i]` (`IF`, `WHILE`, `GOTO`, `DO`, `END`),
/// or a named refusal.
fn keyword(
    s: &Squeezed,
    i: usize,
    w: &str,
    ln: usize,
    dialect: Dialect,
    b: &mut Block,
) -> Result<usize, LexError> {
    let c = &s.c;
    let syntax = syntax_of(dialect);
    let col = s.col_at(i);
    let macro_b = dialect.facts().macro_b_keywords;
    let refuse = |m: String| Err((ln, col, m));
    let mut j = i + w.len();
    // The keywords may be run together with what follows (`GOTO10`, `END1`, `DO1`).
    if macro_b && w.starts_with("GOTO") {
        j = i + 4;
        let mut p = Parser::new(c, j, syntax);
        let target = p.unary().map_err(|(o, m)| (ln, s.col_at(o), format!("GOTO: {m}")))?;
        b.stmts.push(Stmt::Goto { target, col });
        return Ok(p.i);
    }
    if macro_b && w.starts_with("IF") && c.get(i + 2) == Some(&'[') {
        j = i + 2;
        let cond = bracketed(s, &mut j, ln, syntax, "IF")?;
        let next = letters(c, j);
        if next.starts_with("GOTO") {
            let mut p = Parser::new(c, j + 4, syntax);
            let target = p.unary().map_err(|(o, m)| (ln, s.col_at(o), format!("GOTO: {m}")))?;
            b.stmts.push(Stmt::IfGoto { cond, target, col });
            return Ok(p.i);
        }
        if next.starts_with("THEN") {
            let k = j + 4;
            if c.get(k) != Some(&'#') {
                return Err((ln, s.col_at(k), "IF … THEN takes one assignment, #i=…".into()));
            }
            let mut p = Parser::new(c, k, syntax);
            let var = p.var().map_err(|(o, m)| (ln, s.col_at(o), m))?;
            if c.get(p.i) != Some(&'=') {
                return Err((ln, s.col_at(k), "IF … THEN takes one assignment, #i=…".into()));
            }
            p.i += 1;
            let expr = p.expr().map_err(|(o, m)| (ln, s.col_at(o), m))?;
            let text = line_text(s, k, p.i);
            b.stmts.push(Stmt::IfThen {
                cond,
                then: Box::new(Stmt::Assign { var, expr, col: s.col_at(k), text }),
                col,
            });
            return Ok(p.i);
        }
        return Err((ln, s.col_at(j), "IF [ ] must be followed by GOTO n or THEN #i=…".into()));
    }
    if macro_b && w.starts_with("WHILE") && c.get(i + 5) == Some(&'[') {
        j = i + 5;
        let cond = bracketed(s, &mut j, ln, syntax, "WHILE")?;
        if letters(c, j) != "DO" {
            return Err((ln, s.col_at(j), "WHILE [ ] must be followed by DOm".into()));
        }
        j += 2;
        let id = loop_id(s, &mut j, ln, "DO")?;
        b.stmts.push(Stmt::While { cond, id, col });
        return Ok(j);
    }
    if macro_b && w == "DO" {
        let id = loop_id(s, &mut j, ln, "DO")?;
        b.stmts.push(Stmt::Do { id, col });
        return Ok(j);
    }
    if macro_b && w == "END" {
        let id = loop_id(s, &mut j, ln, "END")?;
        b.stmts.push(Stmt::End { id, col });
        return Ok(j);
    }
    match (w, dialect) {
        ("THREAD", Dialect::Dyna) => refuse(
            "the DYNA THREAD cycle is not supported: its pass law is not published (program the passes with G33)".into(),
        ),
        ("SUB" | "ENDSUB" | "CALL" | "WHILE" | "ENDWHILE" | "IF" | "ENDIF", _) if !o_words_are_flow(dialect) => {
            refuse(format!("'{w}' is a LinuxCNC O-word keyword; this is the {} dialect", dialect.name()))
        }
        _ => refuse(format!("'{w}' is not a word of the {} dialect", dialect.name())),
    }
}

/// A LinuxCNC O-word at `c[j]` (after the `O`).
fn o_word(s: &Squeezed, mut j: usize, ln: usize, b: &mut Block, o_col: usize) -> Result<(), LexError> {
    let c = &s.c;
    let col = s.col_at(o_col);
    let name = if c.get(j) == Some(&'<') {
        let close =
            c[j..].iter().position(|&x| x == '>').ok_or((ln, col, "O<… has no closing '>'".to_string()))?;
        let n: String = c[j + 1..j + close].iter().collect::<String>().to_ascii_lowercase();
        j += close + 1;
        format!("<{n}>")
    } else {
        let st = j;
        while j < c.len() && c[j].is_ascii_digit() {
            j += 1;
        }
        if st == j {
            return Err((ln, col, "O must be followed by a number or <name>".into()));
        }
        c[st..j].iter().collect::<String>().trim_start_matches('0').to_string()
    };
    let w = letters(c, j);
    let kw = match w.as_str() {
        "SUB" => OKw::Sub,
        "ENDSUB" => OKw::EndSub,
        "CALL" => OKw::Call,
        "RETURN" => OKw::Return,
        "WHILE" => OKw::While,
        "ENDWHILE" => OKw::EndWhile,
        "DO" => OKw::Do,
        "IF" => OKw::If,
        "ELSEIF" => OKw::ElseIf,
        "ELSE" => OKw::Else,
        "ENDIF" => OKw::EndIf,
        "REPEAT" => OKw::Repeat,
        "ENDREPEAT" => OKw::EndRepeat,
        "BREAK" => OKw::Break,
        "CONTINUE" => OKw::Continue,
        "" => return Err((ln, col, format!("O{name} needs a keyword (sub, call, while, if, …)"))),
        other => {
            return Err((
                ln,
                s.col_at(j),
                format!("'{}' is not an O-word keyword", other.to_ascii_lowercase()),
            ))
        }
    };
    j += w.len();
    let mut cond = None;
    let mut args = Vec::new();
    while c.get(j) == Some(&'[') {
        let mut p = Parser::new(c, j, Syntax::LinuxCnc);
        let e = p.unary().map_err(|(o, m)| (ln, s.col_at(o), m))?;
        j = p.i;
        if kw == OKw::Call {
            args.push(e);
        } else if cond.is_none() {
            cond = Some(e);
        } else {
            return Err((ln, s.col_at(j), "one [condition] only".into()));
        }
    }
    if j < c.len() {
        return Err((ln, s.col_at(j), format!("unexpected '{}' after the O-word", c[j])));
    }
    let needs_cond = matches!(kw, OKw::While | OKw::If | OKw::ElseIf | OKw::Repeat);
    if needs_cond && cond.is_none() {
        return Err((ln, col, format!("O{name} {} needs a [condition]", w.to_ascii_lowercase())));
    }
    b.stmts.push(Stmt::O { name, kw, cond, args, col });
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// Sinumerik

fn skip_spaces(chars: &[char], i: &mut usize) {
    while *i < chars.len() && (chars[*i] == ' ' || chars[*i] == '\t') {
        *i += 1;
    }
}

fn sinumerik_line(line: &str, ln: usize, main_ended: bool, out: &mut Vec<Block>) -> Result<(), LexError> {
    let chars: Vec<char> = line.chars().collect();
    let trimmed = line.trim();
    // `%_N_L9_SPF` starts subprogram L9 (file headers of a listing); `%7772` names the program.
    if let Some(rest) = trimmed.strip_prefix("%_N_") {
        let name = rest.trim_end_matches("_SPF").trim_end_matches("_MPF").to_ascii_uppercase();
        if rest.ends_with("_SPF") {
            out.push(Block { line: ln, col: 1, header: Some(name), ..Block::default() });
        }
        return Ok(());
    }
    if trimmed.starts_with('%') {
        return Ok(());
    }
    // A subprogram in the same listing starts with a line holding only its name (`L9`), after
    // the main program; within it, the same line calls it (read as a block).
    let bare = trimmed.split(';').next().unwrap_or("").trim().trim_end_matches("LF").trim();
    if main_ended
        && bare.len() > 1
        && bare.starts_with(['L', 'l'])
        && bare[1..].chars().all(|c| c.is_ascii_digit())
    {
        let n: u64 = bare[1..].parse().unwrap_or(0);
        out.push(Block { line: ln, col: 1, header: Some(format!("L{n}")), ..Block::default() });
        return Ok(());
    }
    // A subprogram called by a name of letters starts with that name alone on its line after
    // the main program too (`THRSUB`), as `L9` does.
    if main_ended && sinumerik_named_call(&bare.to_ascii_uppercase()) {
        out.push(Block { line: ln, col: 1, header: Some(bare.to_ascii_uppercase()), ..Block::default() });
        return Ok(());
    }
    // `PROC THRSUB` (with `SAVE`, `SBLOF`, `DISPLOF` or `ACTBLOCNO` after it) opens the
    // subprogram THRSUB: its file's first line, or a subprogram in the listing.
    if let Some(header) = sinumerik_proc(&chars, ln)? {
        out.push(Block { line: ln, col: 1, header: Some(header), ..Block::default() });
        return Ok(());
    }
    let mut b = Block::new(ln);
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let col = i + 1;
        match c {
            ' ' | '\t' => i += 1,
            ';' => break,
            '/' if b.words.is_empty() && b.stmts.is_empty() => i += 1,
            '%' => return Err((ln, col, "'%' inside a block".into())),
            c if c.is_ascii_alphabetic() || c == '_' || c == '$' => {
                let start = i;
                while i < chars.len()
                    && (chars[i].is_ascii_alphabetic() || chars[i] == '_' || chars[i] == '$')
                {
                    i += 1;
                }
                let letters: String = chars[start..i].iter().collect::<String>().to_ascii_uppercase();
                if b.words.is_empty() && b.stmts.is_empty() {
                    b.col = col;
                }
                // `LF` written at the end of a listing line is the block end.
                if letters == "LF" && chars[i..].iter().all(|c| c.is_whitespace()) {
                    break;
                }
                if letters.starts_with('$') {
                    return Err((ln, col, format!("system variable {letters} is not supported")));
                }
                // A label: `MARK1:` (letters, digits, underscores, then a colon).
                let mut k = i;
                while k < chars.len() && (chars[k].is_ascii_alphanumeric() || chars[k] == '_') {
                    k += 1;
                }
                if chars.get(k) == Some(&':')
                    && letters.len() >= 2
                    && b.words.is_empty()
                    && b.stmts.is_empty()
                {
                    b.label = Some(chars[start..k].iter().collect::<String>().to_ascii_uppercase());
                    i = k + 1;
                    continue;
                }
                match letters.as_str() {
                    "GOTOF" | "GOTOB" | "GOTO" | "IF" => {
                        i = sinumerik_jump(&chars, start, ln, &mut b)?;
                        continue;
                    }
                    "ELSE" | "ENDIF" | "WHILE" | "ENDWHILE" | "FOR" | "ENDFOR" | "REPEAT" | "UNTIL"
                    | "LOOP" | "ENDLOOP" | "DEF" | "PROC" | "CASE" => {
                        return Err((
                            ln,
                            col,
                            format!("Sinumerik {letters} is not supported (labels, GOTOF/GOTOB and IF … GOTOF are)"),
                        ));
                    }
                    _ => {}
                }
                let word = sinumerik_word(&chars, &mut i, letters, col, ln)?;
                match word {
                    SinWord::Word(mut w) => {
                        w.text = chars[start..i].iter().collect();
                        if w.name == "N" && b.words.is_empty() && b.n.is_none() {
                            if let WVal::Num { v, .. } = w.val {
                                b.n = Some(v);
                                continue;
                            }
                        }
                        b.words.push(w);
                    }
                    SinWord::Assign(s) => b.stmts.push(s),
                    SinWord::Past(p) => b.past.push(p),
                }
            }
            _ => return Err((ln, col, format!("unexpected character '{c}'"))),
        }
    }
    if !b.is_empty() {
        out.push(b.compact());
    }
    Ok(())
}

/// The bare words (no value) a Sinumerik program writes that threadcheck models, besides the
/// frames: never a subprogram's name.
const SINUMERIK_BARE_WORDS: [&str; 6] = ["DIAMON", "DIAMOF", "MCALL", "RET", "M30", "M17"];

/// The frame statements: substitutive (`TRANS`, `ROT`, `MIRROR`, `SCALE`: the programmable frame
/// anew) and additive (`ATRANS`, `AROT`, …: onto the frame in force). Siemens, SINUMERIK 808D
/// Programming (Milling) p.56; SINUMERIK ONE NC programming p.309.
pub(crate) const SINUMERIK_FRAMES: [&str; 8] =
    ["TRANS", "ATRANS", "ROT", "AROT", "MIRROR", "AMIRROR", "SCALE", "ASCALE"];

/// Whether a Sinumerik bare word (`THRSUB`, upper case) is read as a call of the subprogram of
/// that name: a program name that is no word threadcheck models.
pub(crate) fn sinumerik_named_call(name: &str) -> bool {
    is_sinumerik_program_name(name)
        && !SINUMERIK_BARE_WORDS.contains(&name)
        && !SINUMERIK_FRAMES.contains(&name)
}

/// A Sinumerik program name: a letter or `_`, then letters, digits and `_`, at least two
/// characters (Siemens' rule for program names; `L` and digits alone are the old numbered form).
fn is_sinumerik_program_name(s: &str) -> bool {
    s.len() >= 2
        && s.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
        && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        && !(s.starts_with(['L', 'l']) && s[1..].chars().all(|c| c.is_ascii_digit()))
}

/// `PROC NAME` with nothing after the name but the subprogram attributes `SAVE`, `SBLOF`,
/// `DISPLOF`, `ACTBLOCNO`: the subprogram's name. A `PROC` with parameters is refused at them.
fn sinumerik_proc(chars: &[char], ln: usize) -> Result<Option<String>, LexError> {
    let text: String = chars.iter().collect();
    let code = text.split(';').next().unwrap_or("");
    let lead = code.len() - code.trim_start().len();
    let mut words = code.split_whitespace();
    if !words.next().is_some_and(|w| w.eq_ignore_ascii_case("PROC")) {
        return Ok(None);
    }
    let col = lead + 6;
    let Some(name) = words.next() else {
        return Err((ln, lead + 1, "PROC needs the subprogram's name".into()));
    };
    if let Some(p) = name.find('(') {
        let at = code.find(name).unwrap_or(0) + p + 1;
        return Err((
            ln,
            at,
            format!("PROC {}(…): a subprogram with parameters is not supported (one without is)", &name[..p]),
        ));
    }
    let numbered =
        name.len() > 1 && name.starts_with(['L', 'l']) && name[1..].chars().all(|c| c.is_ascii_digit());
    if !is_sinumerik_program_name(name) && !numbered {
        return Err((ln, col, format!("PROC {name}: not a program name")));
    }
    for w in words {
        if !["SAVE", "SBLOF", "DISPLOF", "ACTBLOCNO"].iter().any(|a| w.eq_ignore_ascii_case(a)) {
            let at = lead + code[lead..].find(w).unwrap_or(0) + 1;
            return Err((
                ln,
                at,
                format!("PROC {name} … {w}: only SAVE, SBLOF, DISPLOF and ACTBLOCNO are read after the name"),
            ));
        }
    }
    Ok(Some(name.to_ascii_uppercase()))
}

/// `GOTOF label`, `GOTOB label`, `GOTO label`, `IF cond GOTOF label`.
fn sinumerik_jump(chars: &[char], start: usize, ln: usize, b: &mut Block) -> Result<usize, LexError> {
    let col = start + 1;
    let mut i = start;
    let mut cond = None;
    let word_at = |i: usize| -> String {
        let mut j = i;
        while j < chars.len() && chars[j].is_ascii_alphabetic() {
            j += 1;
        }
        chars[i..j].iter().collect::<String>().to_ascii_uppercase()
    };
    if word_at(i) == "IF" {
        i += 2;
        // The condition runs to GOTOF/GOTOB/GOTO.
        // A char index, not a byte offset: the line may hold characters of several bytes.
        let at = chars[i..]
            .windows(4)
            .position(|w| w.iter().map(|c| c.to_ascii_uppercase()).eq("GOTO".chars()))
            .ok_or((
                ln,
                col,
                "Sinumerik IF without GOTOF/GOTOB: only IF … GOTOF label is supported".to_string(),
            ))?;
        let text: String = chars[i..i + at].iter().collect::<String>().to_ascii_uppercase();
        let e = super::expr::parse_all(text.trim_end(), Syntax::Sinumerik)
            .map_err(|(o, m)| (ln, i + o + 1 + (text.len() - text.trim_start().len()), m))?;
        cond = Some(e);
        i += at;
    }
    let w = word_at(i);
    let forward = match w.as_str() {
        "GOTOF" => Some(true),
        "GOTOB" => Some(false),
        "GOTO" => None,
        _ => return Err((ln, i + 1, "GOTOF, GOTOB or GOTO expected".into())),
    };
    i += w.len();
    skip_spaces(chars, &mut i);
    let ls = i;
    while i < chars.len() && (chars[i].is_ascii_alphanumeric() || chars[i] == '_') {
        i += 1;
    }
    if ls == i {
        return Err((ln, ls + 1, format!("{w} needs a label")));
    }
    let label: String = chars[ls..i].iter().collect::<String>().to_ascii_uppercase();
    b.stmts.push(Stmt::Jump { forward, label, cond, col });
    Ok(i)
}

enum SinWord {
    Word(Word),
    Assign(Stmt),
    Past(Past),
}

/// The index of the `)` that closes the `(` at `open`, strings in double quotes skipped.
fn closing_paren(chars: &[char], open: usize) -> Option<usize> {
    let mut depth = 0usize;
    let mut quoted = false;
    for (k, &c) in chars.iter().enumerate().skip(open) {
        match c {
            '"' => quoted = !quoted,
            '(' if !quoted => depth += 1,
            ')' if !quoted => {
                depth -= 1;
                if depth == 0 {
                    return Some(k);
                }
            }
            _ => {}
        }
    }
    None
}

/// A Sinumerik number at `chars[*i]` (sign allowed), with decimal-comma and exponent checks.
fn sin_number(chars: &[char], i: &mut usize, ln: usize, name: &str) -> Result<(f64, bool), LexError> {
    let s: String = chars.iter().collect::<String>().to_ascii_uppercase();
    let sq = Squeezed { c: s.chars().collect(), col: (1..=chars.len()).collect(), past: Vec::new() };
    let mut j = *i;
    let v = value(&sq, &mut j, ln, name, Syntax::Sinumerik)?;
    *i = j;
    match v {
        WVal::Num { v, point } => Ok((v, point)),
        _ => Err((ln, *i + 1, format!("word {name} has no number"))),
    }
}

fn sin_expr(chars: &[char], i: &mut usize, ln: usize, name: &str) -> Result<Expr, LexError> {
    let up: Vec<char> = chars.iter().map(|c| c.to_ascii_uppercase()).collect();
    let mut p = Parser::new(&up, *i, Syntax::Sinumerik);
    let e = p.expr().map_err(|(o, m)| (ln, o + 1, format!("{name}=: {m}")))?;
    *i = p.i;
    Ok(e)
}

/// Sinumerik calls whose arguments are read: the threading cycles CYCLE97 and CYCLE99, the
/// drilling and tapping cycles `threadcheck tap` checks and the hole patterns that call them
/// (every other call is read past whole).
pub(crate) const ARGUMENT_CALLS: [&str; 15] = [
    "CYCLE97", "CYCLE99", "CYCLE81", "CYCLE82", "CYCLE83", "CYCLE84", "CYCLE840", "CYCLE85", "CYCLE86",
    "CYCLE87", "CYCLE88", "CYCLE89", "HOLES1", "HOLES2", "CYCLE801",
];

/// A Sinumerik word: `X-20`, `G33`, `R3=R3-0.05`, `X=R3`, `SF=90`, `CYCLE97(…)`, `DIAMON`, `L9`,
/// `S 500`.
fn sinumerik_word(
    chars: &[char],
    i: &mut usize,
    letters: String,
    col: usize,
    ln: usize,
) -> Result<SinWord, LexError> {
    let dstart = *i;
    while *i < chars.len() && chars[*i].is_ascii_digit() {
        *i += 1;
    }
    let digits: String = chars[dstart..*i].iter().collect();
    let mut after = *i;
    skip_spaces(chars, &mut after);
    let next = chars.get(after).copied();
    let word = |name: String, val: WVal| Ok(SinWord::Word(Word { name, val, col, text: String::new() }));
    if letters == "T" && digits.is_empty() && next == Some('=') {
        // `T="ROUGH"`: a tool called by name, read past (the insert comes from --insert).
        let mut q = after + 1;
        skip_spaces(chars, &mut q);
        if chars.get(q) == Some(&'"') {
            let close = chars[q + 1..].iter().position(|&c| c == '"').ok_or((
                ln,
                q + 1,
                "T=\" has no closing '\"'".to_string(),
            ))?;
            *i = q + close + 2;
            let name: String = chars[q..*i].iter().collect();
            return Ok(SinWord::Past(Past { name: format!("T={name}"), kind: PastKind::ToolName, col }));
        }
    }
    if letters.len() == 1 && !digits.is_empty() && next != Some('=') {
        // `G33`, `L9`, `M17`, `X10.5`: a one-letter address and its number.
        *i = dstart;
        let (v, point) = sin_number(chars, i, ln, &letters)?;
        return word(letters, WVal::Num { v, point });
    }
    let mut name = letters.clone();
    name.push_str(&digits);
    match next {
        Some('=') => {
            *i = after + 1;
            skip_spaces(chars, i);
            if *i >= chars.len() || chars[*i] == ';' {
                return Err((ln, *i + 1, format!("{name}= has no value")));
            }
            if chars[*i] == '"' {
                return Err((ln, *i + 1, format!("{name}=\"…\": strings are not supported")));
            }
            let expr_start = *i;
            let expr = sin_expr(chars, i, ln, &name)?;
            if letters == "R" && !digits.is_empty() {
                let n: i64 =
                    digits.parse().map_err(|_| (ln, col, format!("{name} is not an R-parameter")))?;
                let text = format!("{name}={}", chars[expr_start..*i].iter().collect::<String>().trim());
                return Ok(SinWord::Assign(Stmt::Assign { var: VarRef::Num(n), expr, col, text }));
            }
            word(name, WVal::Expr(expr))
        }
        Some('(') if !ARGUMENT_CALLS.contains(&name.as_str()) => {
            // Another cycle or function (`CYCLE95("CONT",…)`, `MSG("…")`): read past whole.
            *i = closing_paren(chars, after).ok_or((ln, after + 1, format!("{name}( is not closed")))? + 1;
            let kind = if name == "MSG" { PastKind::Message } else { PastKind::Call };
            Ok(SinWord::Past(Past { name: format!("{name}(…)"), kind, col }))
        }
        Some('(') => {
            let close =
                closing_paren(chars, after).ok_or((ln, after + 1, format!("{name}( is not closed")))? - after;
            let mut args = Vec::new();
            let mut c0 = after + 1;
            let inner_end = after + close;
            *i = after + close + 1;
            while c0 <= inner_end {
                let end = chars[c0..inner_end].iter().position(|&c| c == ',').map_or(inner_end, |p| c0 + p);
                let part: String = chars[c0..end].iter().collect();
                let t = part.trim();
                let e = if t.is_empty() {
                    None
                } else {
                    let lead = part.len() - part.trim_start().len();
                    match super::expr::parse_all(&t.to_ascii_uppercase(), Syntax::Sinumerik) {
                        Ok(e) => Some(e),
                        // A drilling or tapping cycle with an argument the expression reader
                        // does not take (a string of a later cycle version): read past whole.
                        Err(_) if !matches!(name.as_str(), "CYCLE97" | "CYCLE99") && t.starts_with('"') => {
                            return Ok(SinWord::Past(Past {
                                name: format!("{name}(…)"),
                                kind: PastKind::Call,
                                col,
                            }))
                        }
                        Err((o, m)) => return Err((ln, c0 + lead + o + 1, format!("{name} parameter: {m}"))),
                    }
                };
                args.push((e, c0 + 1));
                c0 = end + 1;
            }
            word(name, WVal::Args(args))
        }
        _ if letters.len() == 1
            && digits.is_empty()
            && chars.get(after).is_some_and(|c| c.is_ascii_digit() || matches!(c, '.' | '-' | '+')) =>
        {
            // `S 500`, `I 1.82`: a blank between the address and its number.
            *i = after;
            let (v, point) = sin_number(chars, i, ln, &letters)?;
            word(name, WVal::Num { v, point })
        }
        _ => word(name, WVal::Bare),
    }
}

/// LinuxCNC's `;` starts a comment to the line's end; elsewhere it ends a block (EOB).
fn semicolon_ends_line(dialect: Dialect) -> bool {
    dialect.facts().semicolon_ends_line
}

/// O-words are LinuxCNC's flow control (`o100 sub`), program numbers elsewhere.
fn o_words_are_flow(dialect: Dialect) -> bool {
    dialect.facts().o_words_are_flow
}

#[cfg(test)]
mod tests {
    use super::*;

    fn num(w: &Word) -> Option<f64> {
        match w.val {
            WVal::Num { v, .. } => Some(v),
            _ => None,
        }
    }

    #[test]
    fn fanuc_blocks_words_and_points() {
        let b = lex(
            "%\nO1000 (THREAD)\nN10 G76 P011060 Q100 R0.05;\nN20 G76 X8.16 Z-20. P920 Q350 F1.5;\n%",
            Dialect::Fanuc,
        )
        .unwrap();
        assert_eq!(b.len(), 3);
        assert_eq!(b[0].header.as_deref(), Some("O1000"));
        assert_eq!(b[1].line, 3);
        assert_eq!(b[1].n, Some(10.0));
        let p = &b[1].words[1];
        assert_eq!((p.name.as_str(), p.val.clone()), ("P", WVal::Num { v: 11060.0, point: false }));
        assert_eq!(b[2].words[1].val, WVal::Num { v: 8.16, point: true });
        assert_eq!(b[2].words[1].col, 9);
    }

    #[test]
    fn blanks_inside_words_keep_their_columns() {
        let b = lex("O 1234\nG0 X 4 2. Z5.;\nS 500 M3", Dialect::Fanuc).unwrap();
        assert_eq!(b[0].header.as_deref(), Some("O1234"));
        assert_eq!(num(&b[1].words[1]), Some(42.0));
        assert_eq!(b[1].words[1].col, 4);
        assert_eq!(b[1].words[2].col, 11);
        assert_eq!(num(&b[2].words[0]), Some(500.0));
        let e = lex("G0 X 4 2,5", Dialect::Fanuc).unwrap_err();
        assert_eq!((e.0, e.1), (1, 4));
        let b = lex("N40 G33 Z-36 X = R9 K2 LF\nN30 S 500 M03 LF\nG33 X114.9 I 1.82 K5", Dialect::Sinumerik)
            .unwrap();
        assert_eq!(b[0].n, Some(40.0));
        assert_eq!(b[0].words[2].name, "X");
        assert!(matches!(b[0].words[2].val, WVal::Expr(_)));
        assert_eq!(num(&b[0].words[3]), Some(2.0));
        assert_eq!(num(&b[1].words[0]), Some(500.0));
        assert_eq!((num(&b[2].words[2]), b[2].words[2].col), (Some(1.82), 12));
    }

    #[test]
    fn decimal_comma_says_how_to_write_it() {
        let e = lex("G32 Z-39,65 F1.5", Dialect::Fanuc).unwrap_err();
        assert_eq!((e.0, e.1), (1, 5));
        assert!(e.2.contains("write Z-39.65"), "{}", e.2);
    }

    #[test]
    fn macro_statements() {
        let b =
            lex("#1=#1+1\nWHILE[#1LT10]DO1\nIF[#1 EQ 3]GOTO 20\nEND1\nX[#1*COS[#2]] Z-#3", Dialect::Fanuc)
                .unwrap();
        assert!(matches!(b[0].stmts[0], Stmt::Assign { .. }));
        assert!(matches!(b[1].stmts[0], Stmt::While { id: 1, .. }));
        assert!(matches!(b[2].stmts[0], Stmt::IfGoto { .. }));
        assert!(matches!(b[3].stmts[0], Stmt::End { id: 1, .. }));
        assert!(matches!(b[4].words[0].val, WVal::Expr(_)));
        assert!(matches!(b[4].words[1].val, WVal::Expr(_)));
        let b = lex(
            "o100 while [#1 GE .04]\no<threading> call [1] [2]\n#<od> = [#1 - 0.1] ; c",
            Dialect::LinuxCnc,
        )
        .unwrap();
        assert!(matches!(&b[0].stmts[0], Stmt::O { kw: OKw::While, cond: Some(_), .. }));
        assert!(matches!(&b[1].stmts[0], Stmt::O { kw: OKw::Call, args, .. } if args.len() == 2));
        assert!(matches!(&b[2].stmts[0], Stmt::Assign { var: VarRef::Named(n), .. } if n == "od"));
    }

    #[test]
    fn sinumerik_assignments_calls_labels_and_lf() {
        let b = lex(
            "N10 R3 = R3 - 0.05 LF\nN20 G0 X=R3 Z2 ; comment\nL9 P33\nCYCLE97(1.5,,0,-30,20,20,3,2,0.92)\nLOOP1: G0 X1\nIF R3>1 GOTOB LOOP1",
            Dialect::Sinumerik,
        )
        .unwrap();
        assert!(matches!(b[0].stmts[0], Stmt::Assign { var: VarRef::Num(3), .. }));
        assert_eq!(b[1].words[1].name, "X");
        assert_eq!(num(&b[1].words[2]), Some(2.0));
        assert_eq!(b[2].words[0].name, "L");
        match &b[3].words[0].val {
            WVal::Args(a) => assert_eq!((a.len(), a[1].0.clone()), (9, None)),
            v => panic!("{v:?}"),
        }
        assert_eq!(b[4].label.as_deref(), Some("LOOP1"));
        assert!(matches!(&b[5].stmts[0], Stmt::Jump { forward: Some(false), cond: Some(_), .. }));
    }

    #[test]
    fn crlf_and_bom_keep_positions() {
        let b = lex("\u{feff}G0 X10\r\nG32 Z-5 F1\r\n", Dialect::Fanuc).unwrap();
        assert_eq!(b[1].line, 2);
        assert_eq!(b[1].words[1].col, 5);
        let e = lex("\u{feff}G0 X10\r\nG32 Z-5,5 F1\r\n", Dialect::Fanuc).unwrap_err();
        assert_eq!((e.0, e.1), (2, 5));
    }
}
