//! One interpreter for every dialect: a program counter over the blocks, one variable store with
//! a local frame per call level, loops, jumps and calls. Each dialect's syntax reaches it as the
//! same statements ([`Stmt`]) and the same call requests ([`Flow`]).
//!
//! Safety: the blocks executed, the loop iterations and jumps back, the call depth and the
//! repetitions are bounded (`limits.rs`), so a runaway program is a located error, never a hang.

use super::dialect::{n_key, Ctx, Flow, Language, Rules, Store, SysParams};
use super::expr::{self, Env, Expr, Value, VarKey, VarRef};
use super::lexer::{Block, OKw, PastKind, Stmt, WVal};
use super::motion::{Motion, RBlock, RWord};
use crate::ground::bounds::{MAX_CALL_DEPTH, MAX_REPEATS};
use crate::ground::note::NoteKind;
use crate::Error;
use std::collections::{HashMap, HashSet};

/// Numbered variables kept in a vector (fast), the rest in a map.
const FAST_VARS: usize = 2000;

struct Vars {
    lang: Language,
    globals: Vec<Value>,
    named_globals: HashMap<String, f64>,
    /// Local frames: #1–#33 (Fanuc) or #1–#30 (LinuxCNC), and LinuxCNC's local named
    /// parameters. Frame 0 is the main program's.
    frames: Vec<(Vec<Value>, HashMap<String, f64>)>,
    other: HashMap<i64, f64>,
    warned: HashSet<VarKey>,
    /// Reads of unset variables, to report with their places.
    pending: Vec<(VarKey, usize, usize)>,
    /// Where the block being run stands, for warnings.
    here: (usize, usize),
    /// Values of LinuxCNC's read-only system parameters (`#<_x>`, …), set before each block.
    system: SysParams,
    /// The expressions met so far, compiled ([`expr::Compiled`]), by their address in the
    /// program's blocks (which live as long as the run): a loop's blocks are walked as trees
    /// once, then run as flat steps.
    compiled:
        HashMap<usize, Option<std::rc::Rc<expr::Compiled>>, std::hash::BuildHasherDefault<AddressHasher>>,
}

/// A condition that is not written: false (a static, so that its address is its own).
static ZERO: Expr = Expr::Num(0.0);

/// Most expressions kept compiled in one run: a long program without loops runs the rest as
/// trees, in bounded memory.
const MAX_COMPILED: usize = 4096;

/// A hasher for addresses: they are distinct already, and spread by a multiplication.
#[derive(Default)]
struct AddressHasher(u64);

impl std::hash::Hasher for AddressHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for b in bytes {
            self.0 = (self.0 ^ u64::from(*b)).wrapping_mul(0x100_0000_01b3);
        }
    }
    fn write_usize(&mut self, n: usize) {
        self.0 = (n as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    }
}

/// What [`expr::eval`] gives for `e` with the variables of `vars`, by its compiled form where
/// it has one (the tree answers wherever a step would fail, with the error).
fn fast_eval(e: &Expr, vars: &mut Vars) -> Result<Value, String> {
    let key = e as *const Expr as usize;
    let compiled = match vars.compiled.get(&key) {
        Some(c) => c.clone(),
        None if vars.compiled.len() < MAX_COMPILED => {
            let c = expr::Compiled::for_env(e, vars.lang.arithmetic).map(std::rc::Rc::new);
            vars.compiled.insert(key, c.clone());
            c
        }
        None => None,
    };
    if let Some(v) = compiled.and_then(|c| c.run_in(&mut EvalEnv { vars })) {
        return Ok(v);
    }
    expr::eval(e, &mut EvalEnv { vars }, 0)
}

impl Vars {
    fn new(lang: Language) -> Vars {
        Vars {
            lang,
            globals: vec![None; FAST_VARS],
            named_globals: HashMap::new(),
            frames: vec![(vec![None; 34], HashMap::new())],
            other: HashMap::new(),
            warned: HashSet::new(),
            pending: Vec::new(),
            here: (0, 0),
            system: SysParams::default(),
            compiled: HashMap::default(),
        }
    }

    fn local_range(&self) -> i64 {
        self.lang.local_range
    }

    fn read(&self, k: &VarKey) -> Value {
        match k {
            VarKey::Num(0) if self.lang.fanuc_macro => None,
            VarKey::Num(n) if *n >= 1 && *n <= self.local_range() => {
                self.frames.last().and_then(|f| f.0[*n as usize])
            }
            VarKey::Num(n) if (0..FAST_VARS as i64).contains(n) => self.globals[*n as usize],
            // A parameter the dialect's state sets (LinuxCNC's #5220, #5420…) unless the program
            // wrote it.
            VarKey::Num(n) => self.other.get(n).copied().or_else(|| self.system.get_numbered(*n)),
            VarKey::Named(s) if s.starts_with('_') => {
                self.system.get(s).or_else(|| self.named_globals.get(s).copied())
            }
            VarKey::Named(s) => self.frames.last().and_then(|f| f.1.get(s)).copied(),
        }
    }

    fn write(&mut self, k: &VarKey, v: Value) -> Result<(), String> {
        match k {
            VarKey::Num(0) if self.lang.fanuc_macro => {
                return Err("#0 is always null and cannot be set".into())
            }
            VarKey::Num(n) if *n < 0 => return Err(format!("#{n} is not a variable")),
            VarKey::Num(n) if *n >= 1 && *n <= self.local_range() => {
                if let Some(f) = self.frames.last_mut() {
                    f.0[*n as usize] = v;
                }
            }
            VarKey::Num(n) if (*n as usize) < FAST_VARS => self.globals[*n as usize] = v,
            VarKey::Num(n) => {
                if (1000..5000).contains(n) && self.lang.fanuc_macro {
                    return Err(format!("#{n} is a system variable: threadcheck does not model the control's system variables"));
                }
                match v {
                    Some(x) => self.other.insert(*n, x),
                    None => self.other.remove(n),
                };
            }
            VarKey::Named(s) if s.starts_with('_') => {
                if self.system.has(s) || self.lang.read_only_names.contains(&s.as_str()) {
                    return Err(format!("#<{s}> is read-only"));
                }
                match v {
                    Some(x) => self.named_globals.insert(s.clone(), x),
                    None => self.named_globals.remove(s),
                };
            }
            VarKey::Named(s) => {
                if let Some(f) = self.frames.last_mut() {
                    match v {
                        Some(x) => f.1.insert(s.clone(), x),
                        None => f.1.remove(s),
                    };
                }
            }
        }
        Ok(())
    }

    fn warn_unset(&mut self, m: &mut Motion, k: &VarKey, line: usize, col: usize) {
        if self.warned.insert(k.clone()) {
            let name = match k {
                VarKey::Num(n) if self.lang.r_parameters => format!("R{n}"),
                VarKey::Num(n) => format!("#{n}"),
                VarKey::Named(s) => format!("#<{s}>"),
            };
            let how = self.lang.unset_reads;
            // LinuxCNC's persistent parameters (homes, G92 and the work offsets, #5161–#5390)
            // live in the machine's parameter file, not in the program.
            let stored = matches!((k, self.lang.stored_numbered), (VarKey::Num(n), Some((lo, hi))) if (lo..=hi).contains(n));
            let message = if stored {
                format!("{name} is one of LinuxCNC's stored parameters (a home position, the G92 or a work offset), kept in the machine's parameter file: threadcheck reads it as 0, a fresh file's value (rs274's)")
            } else {
                format!("{name} is read before it is set: {how}")
            };
            m.note_of(NoteKind::UnsetVariable, line, col, message);
        }
    }
}

struct EvalEnv<'a> {
    vars: &'a mut Vars,
}

impl Env for EvalEnv<'_> {
    fn arithmetic(&self) -> expr::Arithmetic {
        self.vars.lang.arithmetic
    }

    fn get(&mut self, k: &VarKey) -> Result<Value, String> {
        let v = self.vars.read(k);
        if v.is_none() {
            if let VarKey::Named(s) = k {
                if let Some((_, what)) = self
                    .vars
                    .lang
                    .unmodelled_names
                    .iter()
                    .find(|(n, _)| s == n || (n.ends_with('[') && s.starts_with(n)))
                {
                    return Err(format!(
                        "#<{s}> is LinuxCNC's predefined parameter of {what}, which threadcheck does not model: a program that reads it is refused"
                    ));
                }
                if self.vars.lang.named_must_exist {
                    return Err(format!("named parameter #<{s}> is not defined"));
                }
            }
            let fanuc_null = matches!(k, VarKey::Num(0)) && self.vars.lang.fanuc_macro;
            if !fanuc_null {
                let (l, c) = self.vars.here;
                self.vars.pending.push((k.clone(), l, c));
            }
        }
        Ok(v)
    }

    fn exists(&mut self, k: &VarKey) -> bool {
        self.vars.read(k).is_some()
    }
}

/// Loop and branch structure found before running.
#[derive(Default)]
struct Layout {
    /// Fanuc/Haas/Sinumerik/LinuxCNC subprograms: name → (first block, end block).
    subs: HashMap<String, (usize, usize)>,
    /// Where the main program starts and ends (exclusive).
    main_start: usize,
    main_end: usize,
    /// The main program's name when the file holds several programs.
    main_name: Option<String>,
    /// Sections (programs) each block belongs to: (start, end).
    section: Vec<(usize, usize)>,
    /// Fanuc WHILE/DO ↔ END, LinuxCNC while ↔ endwhile, do ↔ while, repeat ↔ endrepeat, and
    /// sub → endsub: both directions.
    pair: HashMap<usize, usize>,
    /// LinuxCNC if/elseif/else: the next branch of the chain, and the endif.
    next_branch: HashMap<usize, usize>,
    endif: HashMap<usize, usize>,
    /// LinuxCNC break/continue → the loop's head block.
    loop_of: HashMap<usize, usize>,
    /// Sequence numbers → blocks.
    n_index: HashMap<u64, Vec<usize>>,
    /// Sinumerik labels → blocks.
    labels: HashMap<String, Vec<usize>>,
}

/// The O-numbers a program section calls by a literal word: `M98 P…` (more than four digits:
/// the last four) and `G65 P…`.
pub(crate) fn static_calls(blocks: &[Block]) -> Vec<String> {
    let num = |w: &super::lexer::Word| match w.val {
        super::lexer::WVal::Num { v, .. } => Some(v),
        _ => None,
    };
    let mut out = Vec::new();
    for b in blocks {
        let has = |name: &str, v: f64| b.words.iter().any(|w| w.name == name && num(w) == Some(v));
        let Some(p) = b.words.iter().rev().find(|w| w.name == "P") else { continue };
        let Some(pv) = num(p) else { continue };
        let pv = pv.round().max(0.0) as u64;
        if has("M", 98.0) {
            let prog = if pv >= 10_000 && p.text.len() > 5 && !b.words.iter().any(|w| w.name == "L") {
                pv % 10_000
            } else {
                pv
            };
            out.push(format!("O{prog}"));
        } else if has("G", 65.0) || has("G", 66.0) {
            out.push(format!("O{pv}"));
        }
    }
    out
}

/// Chooses the main program of a file: with several O-programs, the one `--main` names, else
/// the one no other calls (the first such when several are not called), said in a note; with
/// one, `--main` must name it.
fn choose_main(
    blocks: &[Block],
    headers: &[usize],
    several: bool,
    first_is_main: bool,
    main: Option<u32>,
    l: &mut Layout,
    m: &mut Motion,
) -> Result<(), Error> {
    let name_at = |h: usize| blocks[h].header.clone().unwrap_or_default();
    let names: Vec<String> = headers.iter().map(|&h| name_at(h)).collect();
    if !several {
        if let Some(o) = main {
            let want = format!("O{o}");
            if !(first_is_main && names.first() == Some(&want)) {
                let has = if first_is_main { names.first().cloned() } else { None };
                return Err(Error::Input(match has {
                    Some(n) => format!("‹main› {want}: the file holds one program, {n}"),
                    None => format!("‹main› {want}: the file names no O-program"),
                }));
            }
        }
        return Ok(());
    }
    let range = |k: usize| (headers[k] + 1, headers.get(k + 1).copied().unwrap_or(blocks.len()));
    let k = match main {
        Some(o) => {
            let want = format!("O{o}");
            names.iter().position(|n| *n == want).ok_or_else(|| {
                Error::Input(format!("‹main› {want}: the file's programs are {}", names.join(", ")))
            })?
        }
        None => {
            let mut called: HashSet<String> = HashSet::new();
            for (k, name) in names.iter().enumerate() {
                let (a, b) = range(k);
                for c in static_calls(&blocks[a..b]) {
                    if c != *name {
                        called.insert(c);
                    }
                }
            }
            names.iter().position(|n| !called.contains(n)).unwrap_or(0)
        }
    };
    let (a, b) = range(k);
    l.main_start = a;
    l.main_end = b;
    l.main_name = Some(names[k].clone());
    let hb = &blocks[headers[k]];
    let why = match main {
        Some(_) => "as ‹main› says".to_string(),
        None => {
            let others: Vec<&String> =
                names.iter().enumerate().filter(|(j, _)| *j != k).map(|(_, n)| n).collect();
            format!(
                "the file holds {} programs ({}) and no other calls it (‹main› picks another)",
                names.len(),
                std::iter::once(&names[k]).chain(others).cloned().collect::<Vec<_>>().join(", ")
            )
        }
    };
    m.note(hb.line, hb.col, format!("{} is the main program: {why}", names[k]));
    Ok(())
}

/// The name of the file a block stands in: the program's, or a subprogram file's.
fn file_of<'n>(names: &'n [String], b: &Block) -> &'n str {
    names.get(b.file).or(names.first()).map_or("", String::as_str)
}

fn layout(
    blocks: &[Block],
    lang: Language,
    m: &mut Motion,
    main: Option<u32>,
    names: &[String],
) -> Result<Layout, Error> {
    let name_of = |b: &Block| file_of(names, b);
    let mut l = Layout {
        main_end: blocks.len(),
        section: vec![(0, blocks.len()); blocks.len()],
        ..Layout::default()
    };
    let perr = |b: &Block, col: usize, msg: String| Error::Program {
        file: name_of(b).to_string(),
        line: b.line,
        column: col,
        message: msg,
    };
    split_programs(blocks, lang, m, main, &mut l, &perr)?;
    // Sequence numbers and labels, per section; repeated numbers are warned.
    let mut seen: HashMap<(usize, u64), usize> = HashMap::new();
    for (i, b) in blocks.iter().enumerate() {
        if let Some(n) = b.n {
            let k = n_key(n);
            l.n_index.entry(k).or_default().push(i);
            if let Some(first) = seen.insert((l.section[i].0, k), b.line) {
                m.note(
                    b.line,
                    b.col,
                    format!("N{n} is repeated (first at line {first}): a jump to it is ambiguous"),
                );
            }
        }
        if let Some(lab) = &b.label {
            l.labels.entry(lab.clone()).or_default().push(i);
        }
    }
    // Loop pairs.
    let mut stack: Vec<(usize, u32)> = Vec::new();
    let mut ostack: Vec<(usize, String, OKw)> = Vec::new();
    // The labels that open a control block, per subroutine (`None`: outside any), and the
    // line of each: LinuxCNC refuses a label used twice ("duplicate O-word label").
    let mut opened: HashMap<(Option<usize>, String), usize> = HashMap::new();
    let mut section_start = 0;
    for (i, b) in blocks.iter().enumerate() {
        if l.section[i].0 != section_start {
            if let Some((j, id)) = stack.last() {
                return Err(perr(&blocks[*j], 1, format!("DO{id} has no END{id} in its program")));
            }
            section_start = l.section[i].0;
        }
        for s in &b.stmts {
            match s {
                Stmt::While { id, .. } | Stmt::Do { id, .. } => {
                    if lang.max_while_nesting.is_some_and(|max| stack.len() >= max) {
                        m.note(
                            b.line,
                            b.col,
                            "WHILE loops nest deeper than 3, more than a Fanuc control allows",
                        );
                    }
                    stack.push((i, *id));
                }
                Stmt::End { id, col } => match stack.pop() {
                    Some((j, jd)) if jd == *id => {
                        l.pair.insert(j, i);
                        l.pair.insert(i, j);
                    }
                    Some((_, jd)) => {
                        return Err(perr(
                            b,
                            *col,
                            format!("END{id} closes DO{jd}: DO/END ranges must not cross"),
                        ))
                    }
                    None => return Err(perr(b, *col, format!("END{id} without WHILE … DO{id}"))),
                },
                Stmt::O { name, kw, col, .. } => {
                    pair_o_word(&mut l, &mut ostack, &mut opened, (i, b), (name, kw, col), &perr)?;
                }
                Stmt::Assign { .. }
                | Stmt::Goto { .. }
                | Stmt::IfGoto { .. }
                | Stmt::IfThen { .. }
                | Stmt::Jump { .. } => {}
            }
        }
    }
    if let Some((j, id)) = stack.last() {
        return Err(perr(&blocks[*j], 1, format!("DO{id} has no END{id}")));
    }
    if let Some((j, n, k)) = ostack.last() {
        return Err(perr(&blocks[*j], 1, format!("o{n} {} is never closed", okw(*k))));
    }
    Ok(l)
}

/// Programs in one file: the main program's blocks and each subprogram's, by their headers (the
/// main one chosen where several are programs); `main` refused where the dialect has none.
fn split_programs(
    blocks: &[Block],
    lang: Language,
    m: &mut Motion,
    main: Option<u32>,
    l: &mut Layout,
    perr: &dyn Fn(&Block, usize, String) -> Error,
) -> Result<(), Error> {
    // Programs in one file.
    let headers: Vec<usize> =
        blocks.iter().enumerate().filter(|(_, b)| b.header.is_some()).map(|(i, _)| i).collect();
    if lang.headers_split_programs {
        {
            // Fanuc: the first O-number program is the main one (a leading header names it).
            // Sinumerik: subprograms follow the main program, each after its name.
            // A training simulator's set-up lines (`[BILLET …`) may stand before it.
            let setup_only = |b: &Block| {
                b.words.is_empty()
                    && b.stmts.is_empty()
                    && !b.past.is_empty()
                    && b.past.iter().all(|p| matches!(p.kind, PastKind::Billet { .. } | PastKind::Simulator))
            };
            let first_is_main = lang.leading_header_is_main
                && headers.first().is_some_and(|&h| blocks[..h].iter().all(setup_only));
            // Several O-programs in one file: every one is a program; the main one is chosen
            // below (the one no other calls, or --main).
            let several = first_is_main && headers.len() >= 2;
            let sub_headers: &[usize] = if first_is_main && !several { &headers[1..] } else { &headers[..] };
            l.main_end = sub_headers.first().copied().unwrap_or(blocks.len());
            for i in 0..l.main_end {
                l.section[i] = (0, l.main_end);
            }
            for (k, &h) in sub_headers.iter().enumerate() {
                let end = sub_headers.get(k + 1).copied().unwrap_or(blocks.len());
                let name = blocks[h].header.clone().unwrap_or_default();
                if l.subs.insert(name.clone(), (h + 1, end)).is_some() {
                    return Err(perr(&blocks[h], 1, format!("subprogram {name} is defined twice")));
                }
                for i in h..end {
                    l.section[i] = (h + 1, end);
                }
            }
            choose_main(blocks, &headers, several, first_is_main, main, l, m)?;
        }
    } else if let Some(o) = main {
        return Err(Error::Input(format!(
            "‹main› O{o}: the {} dialect has no O-numbered programs to choose from",
            m.dialect.name()
        )));
    }
    Ok(())
}

/// The O-word blocks (LinuxCNC) paired: each closing block with its opening one, a branch with
/// the next, a break with its loop; a label used twice or blocks that do not nest refused.
#[allow(clippy::type_complexity)]
fn pair_o_word(
    l: &mut Layout,
    ostack: &mut Vec<(usize, String, OKw)>,
    opened: &mut HashMap<(Option<usize>, String), usize>,
    (i, b): (usize, &Block),
    (name, kw, col): (&String, &OKw, &usize),
    perr: &dyn Fn(&Block, usize, String) -> Error,
) -> Result<(), Error> {
    let close = |want: &[OKw], ostack: &mut Vec<(usize, String, OKw)>| -> Result<(usize, OKw), Error> {
        match ostack.last() {
            Some((j, n, k)) if n == name && want.contains(k) => {
                let r = (*j, *k);
                ostack.pop();
                Ok(r)
            }
            Some((_, n, k)) => Err(perr(
                b,
                *col,
                format!("o{name} {} inside o{n} {}: O-word blocks must nest", okw(*kw), okw(*k)),
            )),
            None => Err(perr(b, *col, format!("o{name} {} has no opening block", okw(*kw)))),
        }
    };
    match kw {
        OKw::Sub | OKw::While | OKw::Do | OKw::If | OKw::Repeat => {
            // A `while` that closes a `do` of the same name.
            if *kw == OKw::While {
                if let Some((j, n, OKw::Do)) = ostack.last() {
                    if n == name {
                        let j = *j;
                        ostack.pop();
                        l.pair.insert(j, i);
                        l.pair.insert(i, j);
                        return Ok(());
                    }
                }
            }
            if *kw != OKw::Sub {
                let scope = ostack.iter().rev().find(|(_, _, k)| *k == OKw::Sub).map(|(j, _, _)| *j);
                if let Some(first) = opened.insert((scope, name.clone()), b.line) {
                    return Err(perr(
                        b,
                        *col,
                        format!(
                            "o{name} {}: the label o{name} already opens a block at line {first}, and LinuxCNC refuses a label used twice (\"duplicate O-word label\"): give each loop and branch a label of its own",
                            okw(*kw)
                        ),
                    ));
                }
            }
            ostack.push((i, name.clone(), *kw));
        }
        OKw::EndSub => {
            let (j, _) = close(&[OKw::Sub], ostack)?;
            l.pair.insert(j, i);
            // The endsub itself runs (it returns, and sets #<_value>).
            l.subs.insert(name.clone(), (j + 1, i + 1));
        }
        OKw::EndWhile => {
            let (j, _) = close(&[OKw::While], ostack)?;
            l.pair.insert(j, i);
            l.pair.insert(i, j);
        }
        OKw::EndRepeat => {
            let (j, _) = close(&[OKw::Repeat], ostack)?;
            l.pair.insert(j, i);
            l.pair.insert(i, j);
        }
        OKw::ElseIf | OKw::Else => {
            let (j, _) = close(&[OKw::If, OKw::ElseIf], ostack)?;
            l.next_branch.insert(j, i);
            ostack.push((i, name.clone(), if *kw == OKw::Else { OKw::ElseIf } else { *kw }));
        }
        OKw::EndIf => {
            let (j, _) = close(&[OKw::If, OKw::ElseIf], ostack)?;
            l.next_branch.insert(j, i);
            // Every branch head of the chain leads to this endif.
            let mut k = j;
            loop {
                l.endif.insert(k, i);
                match l.next_branch.iter().find(|(_, &v)| v == k) {
                    Some((&prev, _)) => k = prev,
                    None => break,
                }
            }
        }
        OKw::Break | OKw::Continue => {
            // LinuxCNC breaks out of while and do loops only: a repeat loop's
            // name is no label for break or continue (interp_o_word.cc).
            if ostack.iter().rev().any(|(_, n, k)| n == name && *k == OKw::Repeat) {
                return Err(perr(
                    b,
                    *col,
                    format!("o{name} {}: o{name} is a repeat loop, and LinuxCNC breaks out of and continues while and do loops only", okw(*kw)),
                ));
            }
            let head = ostack
                .iter()
                .rev()
                .find(|(_, n, k)| n == name && matches!(k, OKw::While | OKw::Do))
                .map(|(j, _, _)| *j)
                .ok_or_else(|| perr(b, *col, format!("o{name} {} outside a loop named o{name}", okw(*kw))))?;
            l.loop_of.insert(i, head);
        }
        OKw::Call | OKw::Return => {}
    }
    Ok(())
}

fn okw(k: OKw) -> &'static str {
    match k {
        OKw::Sub => "sub",
        OKw::EndSub => "endsub",
        OKw::Call => "call",
        OKw::Return => "return",
        OKw::While => "while",
        OKw::EndWhile => "endwhile",
        OKw::Do => "do",
        OKw::If => "if",
        OKw::ElseIf => "elseif",
        OKw::Else => "else",
        OKw::EndIf => "endif",
        OKw::Repeat => "repeat",
        OKw::EndRepeat => "endrepeat",
        OKw::Break => "break",
        OKw::Continue => "continue",
    }
}

struct Frame {
    /// Where to go back to.
    ret: usize,
    /// The subprogram's first block and end.
    start: usize,
    end: usize,
    repeats_left: u32,
    /// A local frame was pushed (G65, LinuxCNC call).
    own_locals: bool,
    /// The caller's section (for M99 Pn).
    caller_section: (usize, usize),
    /// The call's place.
    line: usize,
    col: usize,
    name: String,
    /// Dyna loops open when the call was made.
    loops: usize,
}

struct DynaLoop {
    body: usize,
    left: u64,
}

/// The interpreter's state while it runs a program: where it is, the calls and loops open.
struct Exec<'a> {
    blocks: &'a [Block],
    lay: Layout,
    file: &'a str,
    vars: Vars,
    /// The block being run and the end of the (sub)program it is in.
    pc: usize,
    end: usize,
    frames: Vec<Frame>,
    loops: Vec<DynaLoop>,
    /// LinuxCNC repeat counters by block.
    repeats: HashMap<usize, f64>,
    called: HashSet<String>,
    /// The branch of an if chain being entered by a jump (evaluate it rather than skip it).
    entering_branch: bool,
    /// LinuxCNC's loop flags (interp_o_word.cc): after `break` or `continue` the interpreter
    /// skips to the next line that carries the loop's name, so a `break` of that loop further in
    /// the body runs even in a branch not taken; `doing_break` and `doing_continue` are global
    /// and outlive their loop: a loop end reached while skipping loops back when
    /// `doing_continue` is set, and the end of a do-while loop leaves it when `doing_break` is.
    doing_break: bool,
    doing_continue: bool,
    /// The loop end is reached by skipping (after break or continue).
    skipping_to_end: bool,
}

/// What a block's statements decided: the block to run next, and its assignments.
struct Step<'a> {
    next: usize,
    jumped_back: bool,
    skip_words: bool,
    enter_branch: bool,
    assigns: Vec<(&'a VarRef, &'a Expr, usize, &'a str)>,
}

/// After a block's flow: go on, start the next block now (no jump counted), or end.
enum Then {
    Go,
    Skip(usize),
    Stop,
}

/// An error at a block's column.
fn perr(file: &str, b: &Block, col: usize, msg: String) -> Error {
    Error::Program { file: file.to_string(), line: b.line, column: col, message: msg }
}

/// A condition's truth: non-zero.
fn truth(v: Value) -> bool {
    v.unwrap_or(0.0) != 0.0
}

/// An O-word statement: its name, keyword, condition, arguments and column.
type OWord<'a> = (&'a String, OKw, Option<&'a Expr>, &'a [Expr], usize);

impl<'a> Exec<'a> {
    /// `e` evaluated at column `col` of block `b`.
    fn ev(&mut self, b: &Block, e: &Expr, col: usize) -> Result<Value, Error> {
        self.vars.here = (b.line, col);
        fast_eval(e, &mut self.vars).map_err(|msg| perr(self.file, b, col, msg))
    }

    /// Returns from the innermost call ([`do_return`]).
    fn ret(&mut self, to_n: Option<f64>) -> Result<Option<usize>, Error> {
        do_return(
            &mut self.frames,
            &mut self.end,
            &mut self.vars,
            &mut self.loops,
            to_n,
            &self.lay,
            self.file,
        )
    }

    /// Block `pc`'s statements: jumps, conditions, loops and calls, and the assignments to make.
    fn statements(&mut self, b: &'a Block, pc: usize, arrived_skipping: bool) -> Result<Step<'a>, Error> {
        let mut st = Step {
            next: pc + 1,
            jumped_back: false,
            skip_words: false,
            enter_branch: false,
            assigns: Vec::new(),
        };
        for s in &b.stmts {
            match s {
                Stmt::Assign { var, expr, col, text } => st.assigns.push((var, expr, *col, text)),
                Stmt::Goto { target, col } => {
                    let n = self.ev(b, target, *col)?.unwrap_or(0.0);
                    st.next = goto_n(&self.lay, pc, n).ok_or_else(|| {
                        perr(self.file, b, *col, format!("GOTO {n}: no block N{n} in this program"))
                    })?;
                    st.jumped_back = st.next <= pc;
                }
                Stmt::IfGoto { cond: c, target, col } => {
                    if truth(self.ev(b, c, *col)?) {
                        let n = self.ev(b, target, *col)?.unwrap_or(0.0);
                        st.next = goto_n(&self.lay, pc, n).ok_or_else(|| {
                            perr(self.file, b, *col, format!("GOTO {n}: no block N{n} in this program"))
                        })?;
                        st.jumped_back = st.next <= pc;
                    }
                }
                Stmt::IfThen { cond: c, then, col } => {
                    if truth(self.ev(b, c, *col)?) {
                        if let Stmt::Assign { var, expr, col, text } = then.as_ref() {
                            st.assigns.push((var, expr, *col, text));
                        }
                    }
                }
                Stmt::While { cond: c, id, col } => {
                    if !truth(self.ev(b, c, *col)?) {
                        let e = self
                            .lay
                            .pair
                            .get(&pc)
                            .copied()
                            .ok_or_else(|| perr(self.file, b, *col, format!("DO{id} has no END{id}")))?;
                        st.next = e + 1;
                    }
                }
                Stmt::Do { .. } => {}
                Stmt::End { id, col } => {
                    st.next = self
                        .lay
                        .pair
                        .get(&pc)
                        .copied()
                        .ok_or_else(|| perr(self.file, b, *col, format!("END{id} without DO{id}")))?;
                    st.jumped_back = true;
                }
                Stmt::Jump { forward, label, cond: c, col } => {
                    let take = match c {
                        Some(c) => truth(self.ev(b, c, *col)?),
                        None => true,
                    };
                    if take {
                        st.next = jump_label(&self.lay, pc, label, *forward, self.end).ok_or_else(|| {
                            perr(
                                self.file,
                                b,
                                *col,
                                format!(
                                    "no label or block {label} {} in this program",
                                    match forward {
                                        Some(true) => "after this block",
                                        Some(false) => "before this block",
                                        None => "",
                                    }
                                ),
                            )
                        })?;
                        st.jumped_back = st.next <= pc;
                    }
                }
                Stmt::O { name, kw, cond: c, args, col } => {
                    self.o_word(b, pc, (name, *kw, c.as_ref(), args, *col), arrived_skipping, &mut st)?;
                }
            }
        }
        Ok(st)
    }

    /// An O-word (LinuxCNC's subroutines, loops and conditionals) of block `pc`.
    fn o_word(
        &mut self,
        b: &'a Block,
        pc: usize,
        (name, kw, c, args, col): OWord<'a>,
        arrived_skipping: bool,
        st: &mut Step<'a>,
    ) -> Result<(), Error> {
        match kw {
            OKw::Sub => {
                // A definition met in the program's flow: read past it.
                st.next = self.lay.pair.get(&pc).copied().unwrap_or(pc) + 1;
                st.skip_words = true;
            }
            OKw::EndSub | OKw::Return => {
                // An endsub or return with a value sets #<_value> and
                // #<_value_returned> to 1; one without sets both to 0 (LinuxCNC's
                // interp_read.cc).
                let value = match c {
                    Some(c) => self.ev(b, c, col)?,
                    None => None,
                };
                st.next = do_return(
                    &mut self.frames,
                    &mut self.end,
                    &mut self.vars,
                    &mut self.loops,
                    None,
                    &self.lay,
                    self.file,
                )?
                .ok_or_else(|| {
                    perr(self.file, b, col, format!("o{name} {} outside a subroutine call", okw(kw)))
                })?;
                let returned = if value.is_some() { 1.0 } else { 0.0 };
                self.vars.named_globals.insert("_value".into(), value.unwrap_or(0.0));
                self.vars.named_globals.insert("_value_returned".into(), returned);
            }
            OKw::Call => {
                let mut vals = Vec::new();
                for a in args {
                    vals.push(self.ev(b, a, col)?.unwrap_or(0.0));
                }
                let Some(&(start, send)) = self.lay.subs.get(name.as_str()) else {
                    return Err(perr(self.file, b, col, format!("o{name} call: no o{name} sub in this file, nor its file where the control looks (the program's folder and ‹subroutine_path›, for a program read from a file)")));
                };
                if self.frames.len() + 1 > MAX_CALL_DEPTH {
                    return Err(perr(
                        self.file,
                        b,
                        col,
                        format!("calls nest deeper than {MAX_CALL_DEPTH}: does o{name} call itself?"),
                    ));
                }
                self.called.insert(name.clone());
                self.vars.frames.push((vec![None; 34], HashMap::new()));
                if let Some(f) = self.vars.frames.last_mut() {
                    for (k, v) in vals.iter().enumerate().take(30) {
                        f.0[k + 1] = Some(*v);
                    }
                }
                self.frames.push(Frame {
                    ret: pc + 1,
                    start,
                    end: send,
                    repeats_left: 0,
                    own_locals: true,
                    caller_section: self.lay.section[pc],
                    line: b.line,
                    col,
                    name: format!("o{name}"),
                    loops: self.loops.len(),
                });
                self.end = send;
                st.next = start;
            }
            OKw::While => {
                // The closing `while` of a do-loop, or a loop head.
                let closes_do = self.lay.pair.get(&pc).is_some_and(|&j| j < pc);
                let t = match c {
                    Some(c) => truth(self.ev(b, c, col)?),
                    None => false,
                };
                if closes_do {
                    if t && !self.doing_break {
                        st.next = self.lay.pair[&pc] + 1;
                        st.jumped_back = true;
                    } else {
                        self.doing_break = false;
                    }
                } else if !t {
                    let tail = self.lay.pair.get(&pc).copied().unwrap_or(pc);
                    self.doing_break |= break_between(self.blocks, pc, tail, name);
                    st.next = tail;
                    self.skipping_to_end = true;
                }
            }
            OKw::EndWhile | OKw::EndRepeat => {
                let head = self.lay.pair[&pc];
                if arrived_skipping && !self.doing_continue {
                    // Skipped here (a break, a false head): done.
                    self.repeats.remove(&head);
                } else {
                    // Skipped here after a continue: its flag is spent.
                    if arrived_skipping {
                        self.doing_continue = false;
                    }
                    st.next = head;
                    st.jumped_back = true;
                }
            }
            OKw::Do => {}
            OKw::Repeat => {
                let left = match self.repeats.get(&pc) {
                    Some(l) => *l,
                    None => self.ev(b, c.unwrap_or(&ZERO), col)?.unwrap_or(0.0).floor(),
                };
                if left <= 0.0 {
                    self.repeats.remove(&pc);
                    let tail = self.lay.pair.get(&pc).copied().unwrap_or(pc);
                    self.doing_break |= break_between(self.blocks, pc, tail, name);
                    st.next = tail;
                    self.skipping_to_end = true;
                } else {
                    self.repeats.insert(pc, left - 1.0);
                }
            }
            OKw::If | OKw::ElseIf | OKw::Else => {
                let head = kw == OKw::If || self.entering_branch;
                if !head {
                    // Reached from the end of the branch before: done.
                    st.next = self.lay.endif.get(&pc).copied().unwrap_or(pc) + 1;
                } else {
                    let t = match c {
                        Some(c) => truth(self.ev(b, c, col)?),
                        None => true, // else
                    };
                    if !t {
                        st.next = self.lay.next_branch.get(&pc).copied().unwrap_or(pc + 1);
                        // Land on the next branch head and evaluate it.
                        if self.blocks.get(st.next).is_some_and(|nb| {
                            nb.stmts.iter().any(|s| matches!(s, Stmt::O { kw: OKw::ElseIf | OKw::Else, .. }))
                        }) {
                            // The next block is run as the branch's head (its
                            // condition evaluated, an else entered).
                            st.enter_branch = true;
                        } else {
                            st.next += 1;
                        }
                    }
                }
            }
            OKw::EndIf => {}
            OKw::Break | OKw::Continue => {
                // Skip to the loop's end; a break of this loop on the way runs.
                let head = self.lay.loop_of[&pc];
                let tail = self.lay.pair.get(&head).copied().unwrap_or(head);
                if kw == OKw::Break {
                    self.doing_break = true;
                } else {
                    self.doing_continue = true;
                }
                self.doing_break |= break_between(self.blocks, pc, tail, name);
                st.next = tail;
                self.skipping_to_end = true;
            }
        }
        Ok(())
    }

    /// What the block's words asked of the flow: calls, returns, the end, Dyna's loops.
    fn flow(
        &mut self,
        flow: Flow,
        b: &Block,
        pc: usize,
        st: &mut Step<'a>,
        m: &mut Motion,
        rules: &mut dyn Rules,
    ) -> Result<Then, Error> {
        match flow {
            Flow::Next => {}
            Flow::End => {
                if !self.frames.is_empty() {
                    let f = &self.frames[self.frames.len() - 1];
                    m.note(
                        b.line,
                        b.col,
                        format!("the program ends inside {} (called from line {})", f.name, f.line),
                    );
                }
                return Ok(Then::Stop);
            }
            Flow::Call { name, repeats: reps, locals, col } => {
                let Some(&(start, send)) = self.lay.subs.get(&name) else {
                    return Err(perr(self.file, b, col, format!("subprogram {name} is not in this file, nor in a file of its number beside it (for a program read from a file)")));
                };
                if reps as usize > MAX_REPEATS {
                    return Err(perr(
                        self.file,
                        b,
                        col,
                        format!("{name}: {reps} repetitions, more than {MAX_REPEATS}"),
                    ));
                }
                if self.frames.len() + 1 > MAX_CALL_DEPTH {
                    return Err(perr(
                        self.file,
                        b,
                        col,
                        format!(
                            "subprogram calls nest deeper than {MAX_CALL_DEPTH}: does {name} call itself?"
                        ),
                    ));
                }
                if reps == 0 {
                    return Ok(Then::Skip(st.next));
                }
                self.called.insert(name.clone());
                let own = locals.is_some();
                if let Some(ls) = locals {
                    self.vars.frames.push((vec![None; 34], HashMap::new()));
                    if let Some(f) = self.vars.frames.last_mut() {
                        for (k, v) in ls {
                            if (1..=33).contains(&k) {
                                f.0[k as usize] = Some(v);
                            }
                        }
                    }
                }
                self.frames.push(Frame {
                    ret: st.next,
                    start,
                    end: send,
                    repeats_left: reps - 1,
                    own_locals: own,
                    caller_section: self.lay.section[pc],
                    line: b.line,
                    col,
                    name,
                    loops: self.loops.len(),
                });
                self.end = send;
                st.next = start;
            }
            Flow::LocalCall { n, repeats: reps, col } => {
                let sec = self.lay.section[pc];
                let target = self
                    .lay
                    .n_index
                    .get(&n_key(n))
                    .and_then(|v| v.iter().copied().find(|&i| i >= sec.0 && i < sec.1))
                    .ok_or_else(|| {
                        perr(self.file, b, col, format!("M97 P{n}: no block N{n} in this program"))
                    })?;
                if self.frames.len() + 1 > MAX_CALL_DEPTH {
                    return Err(perr(
                        self.file,
                        b,
                        col,
                        format!("subprogram calls nest deeper than {MAX_CALL_DEPTH}"),
                    ));
                }
                if reps > 0 {
                    self.frames.push(Frame {
                        ret: st.next,
                        start: target,
                        end: self.end,
                        repeats_left: reps - 1,
                        own_locals: false,
                        caller_section: sec,
                        line: b.line,
                        col,
                        name: format!("N{n}"),
                        loops: self.loops.len(),
                    });
                    st.next = target;
                }
            }
            Flow::Return { to_n, col } => {
                match self.ret(to_n)? {
                    Some(n) => st.next = n,
                    None => {
                        m.note(b.line, col, "M99 in the main program would run it again from the start; threadcheck ends it here");
                        return Ok(Then::Stop);
                    }
                }
            }
            Flow::LoopStart { count, col } => {
                if !(0.0..=1e9).contains(&count) {
                    return Err(perr(
                        self.file,
                        b,
                        col,
                        format!("loop count {count} must be a whole number from 0"),
                    ));
                }
                let k = count.round() as u64;
                if k == 0 {
                    // Skip to the matching M74.
                    st.next = rules
                        .loop_end(self.blocks, pc)
                        .ok_or_else(|| perr(self.file, b, col, "M73 without its M74".into()))?
                        + 1;
                } else {
                    self.loops.push(DynaLoop { body: st.next, left: k });
                }
            }
            Flow::LoopEnd { col } => {
                let Some(l) = self.loops.last_mut() else {
                    return Err(perr(self.file, b, col, "M74 without an open M73 loop".into()));
                };
                l.left -= 1;
                if l.left > 0 {
                    st.next = l.body;
                    st.jumped_back = true;
                } else {
                    self.loops.pop();
                }
            }
        }
        Ok(Then::Go)
    }

    /// Subroutines defined and never called are read past; say so, in the order they stand.
    fn never_called(&self, m: &mut Motion) {
        let mut never: Vec<(usize, &String)> = self
            .lay
            .subs
            .iter()
            .filter(|(name, _)| !self.called.contains(*name) && self.lay.main_name.as_ref() != Some(*name))
            .map(|(name, &(start, _))| (start, name))
            .collect();
        never.sort_unstable();
        for (start, name) in never {
            if start > 0 {
                let hb = &self.blocks[start - 1];
                let what = (self.vars.lang.sub_word)(name);
                m.note_of(
                    NoteKind::NeverCalled,
                    hb.line,
                    hb.col,
                    format!("{what} is defined but never called"),
                );
            }
        }
    }
}

/// Runs the program.
pub(crate) fn run(
    blocks: &[Block],
    lang: Language,
    rules: &mut dyn Rules,
    m: &mut Motion,
    names: &[String],
    budget: super::Budget,
    main: Option<u32>,
) -> Result<(), Error> {
    debug_assert!(!names.is_empty() && blocks.iter().all(|b| b.file < names.len()));
    let name_of = |b: &Block| file_of(names, b);
    let lay = layout(blocks, lang, m, main, names)?;
    let mut file: &str = &names[0];
    let sub_names: HashSet<String> = lay.subs.keys().cloned().collect();
    let n_numbers: HashSet<u64> = lay.n_index.keys().copied().collect();
    let mut vars = Vars::new(lang);
    vars.system = SysParams::new(rules.system_names());
    let mut x = Exec {
        blocks,
        pc: lay.main_start,
        end: lay.main_end,
        lay,
        file,
        vars,
        frames: Vec::new(),
        loops: Vec::new(),
        repeats: HashMap::new(),
        called: HashSet::new(),
        entering_branch: false,
        doing_break: false,
        doing_continue: false,
        skipping_to_end: false,
    };
    let mut executed = 0usize;
    let mut back = 0usize;
    loop {
        if x.pc >= x.end {
            // The end of a subprogram without M99/M17/endsub returns; the main program ends.
            match x.ret(None)? {
                Some(next) => {
                    x.pc = next;
                    continue;
                }
                None => break,
            }
        }
        let pc = x.pc;
        let b = &blocks[pc];
        // Errors and notes name the file the block stands in.
        if name_of(b) != file {
            file = name_of(b);
            x.file = file;
            m.file = file.to_string();
            // A subprogram file's blocks are made at the main program's outermost call (the
            // file changes at every entry from the main program and at the return to it).
            m.call_line = if m.file == m.main_file { None } else { x.frames.first().map(|f| f.line) };
        }
        executed += 1;
        // A request no longer wanted (the server's time budget) stops here within microseconds.
        if executed % 4096 == 0 {
            crate::ground::cancel::check()?;
        }
        if executed > budget.blocks {
            return Err(perr(
                file,
                b,
                b.col,
                format!("more than {} blocks executed: the program loops", budget.blocks),
            ));
        }
        x.vars.here = (b.line, b.col);
        // The read-only position parameters (#<_x>, #<_z>) as the last move left them, for the
        // block's conditions, assignments and words alike.
        rules.system_params(m, &mut x.vars.system);
        // The interpreter's own: the subroutine depth and the block's line (LinuxCNC's
        // `#<_call_level>`, `#<_line>`), where the dialect has them.
        let depth = x.frames.len() as f64;
        x.vars.system.set_named("_call_level", depth);
        x.vars.system.set_named("_line", b.line as f64);
        let arrived_skipping = std::mem::take(&mut x.skipping_to_end);
        let mut st = x.statements(b, pc, arrived_skipping)?;
        x.entering_branch = st.enter_branch;
        // Words: evaluated (LinuxCNC before its assignments, the others after them).
        let deferred = x.vars.lang.deferred_assignments;
        if !deferred {
            do_assigns(&st.assigns, &mut x.vars, b, file)?;
        }
        let mut flow = Flow::Next;
        if !st.skip_words {
            for p in &b.past {
                super::cycles::read_past_item(m, b.line, p)?;
            }
        }
        if !st.skip_words && (!b.words.is_empty()) {
            let rb = resolve(b, &mut x.vars, file)?;
            flush_pending(&mut x.vars, m);
            // LinuxCNC's lathe cycles G70/G71/G72 (and G71.1/G72.1) run the profile subroutine
            // named by Q: it is called, for turning.
            if x.vars.lang.lathe_cycles_call_q
                && rb.gs().any(|(g, _)| {
                    matches!(g as u32, 70..=72)
                        && (g.fract() == 0.0 || (g - 71.1).abs() < 1e-9 || (g - 72.1).abs() < 1e-9)
                })
            {
                if let Some(q) = rb.get("Q") {
                    x.called.insert(format!("{}", q.v.round() as i64));
                }
            }
            let mut cx = Ctx { store: &mut x.vars, subs: &sub_names, ns: &n_numbers };
            m.note_x_word(&rb);
            m.profile_starts(b.n);
            flow = rules.block(m, &rb, &mut cx)?;
            m.profile_ends(b.n);
        }
        if deferred {
            do_assigns(&st.assigns, &mut x.vars, b, file)?;
        }
        flush_pending(&mut x.vars, m);
        match x.flow(flow, b, pc, &mut st, m, rules)? {
            Then::Go => {}
            Then::Skip(next) => {
                x.pc = next;
                continue;
            }
            Then::Stop => break,
        }
        // Every jump back (loops, GOTO, subprogram returns and repetitions) counts.
        if st.jumped_back || st.next <= pc {
            back += 1;
            if back > budget.backward_jumps {
                return Err(perr(
                    file,
                    b,
                    b.col,
                    format!("more than {} loop iterations: the program loops", budget.backward_jumps),
                ));
            }
        }
        x.pc = st.next;
    }
    x.never_called(m);
    Ok(())
}

/// Returns from the innermost call: the block to go on with, `None` when there is no call to
/// return from. A call with repetitions left runs its subprogram again.
#[allow(clippy::too_many_arguments)]
fn do_return(
    frames: &mut Vec<Frame>,
    end: &mut usize,
    vars: &mut Vars,
    loops: &mut Vec<DynaLoop>,
    to_n: Option<f64>,
    lay: &Layout,
    file: &str,
) -> Result<Option<usize>, Error> {
    let Some(f) = frames.last_mut() else { return Ok(None) };
    loops.truncate(f.loops);
    if f.repeats_left > 0 {
        f.repeats_left -= 1;
        *end = f.end;
        return Ok(Some(f.start));
    }
    let Some(f) = frames.pop() else { return Ok(None) };
    if f.own_locals {
        vars.frames.pop();
    }
    *end = match frames.last() {
        Some(g) => g.end,
        None => lay.main_end,
    };
    match to_n {
        None => Ok(Some(f.ret)),
        Some(n) => lay
            .n_index
            .get(&n_key(n))
            .and_then(|v| v.iter().copied().find(|&i| i >= f.caller_section.0 && i < f.caller_section.1))
            .map(Some)
            .ok_or_else(|| Error::Program {
                file: file.to_string(),
                line: f.line,
                column: f.col,
                message: format!("M99 P{n}: no block N{n} in the calling program"),
            }),
    }
}

fn do_assigns(
    assigns: &[(&VarRef, &Expr, usize, &str)],
    vars: &mut Vars,
    b: &Block,
    file: &str,
) -> Result<(), Error> {
    let perr = |col: usize, text: &str, msg: String| Error::Program {
        file: file.to_string(),
        line: b.line,
        column: col,
        message: format!("{text}: {msg}"),
    };
    // LinuxCNC sets the parameters of a line after reading all of them; the others in order.
    let deferred = vars.lang.deferred_assignments;
    let mut vals = Vec::new();
    for (var, e, col, text) in assigns {
        vars.here = (b.line, *col);
        let v = fast_eval(e, vars).map_err(|m| perr(*col, text, m))?;
        let k = expr::key_of(var, &mut EvalEnv { vars }).map_err(|m| perr(*col, text, m))?;
        let v = if deferred { v.or(Some(0.0)) } else { v };
        if deferred {
            vals.push((k, v, *col, *text));
        } else {
            vars.write(&k, v).map_err(|m| perr(*col, text, m))?;
        }
    }
    for (k, v, col, text) in vals {
        vars.write(&k, v).map_err(|m| perr(col, text, m))?;
    }
    Ok(())
}

fn flush_pending(vars: &mut Vars, m: &mut Motion) {
    let pending = std::mem::take(&mut vars.pending);
    for (k, l, c) in pending {
        vars.warn_unset(m, &k, l, c);
    }
}

/// The block's words with their values; a Fanuc word whose variable is null is dropped with its
/// address, as the control does.
fn resolve<'b>(b: &'b Block, vars: &mut Vars, file: &str) -> Result<RBlock<'b>, Error> {
    let mut words = Vec::with_capacity(b.words.len());
    let mut vacant = Vec::new();
    for w in &b.words {
        vars.here = (b.line, w.col);
        let perr = |msg: String| Error::Program {
            file: file.to_string(),
            line: b.line,
            column: w.col,
            message: msg,
        };
        let (v, point, args) = match &w.val {
            WVal::Num { v, point } => (*v, *point, None),
            WVal::Expr(e) => {
                let v = fast_eval(e, vars).map_err(|m| perr(format!("{}: {m}", w.name)))?;
                match v {
                    Some(v) => (v, v.fract() != 0.0, None),
                    None if vars.lang.null_word_omitted => {
                        vacant.push((w.name.as_str(), w.text.as_str(), w.col));
                        continue;
                    }
                    None => (0.0, false, None),
                }
            }
            WVal::Args(a) => {
                let mut out = Vec::with_capacity(a.len());
                for (e, col) in a {
                    let v = match e {
                        Some(e) => fast_eval(e, vars)
                            .map_err(|m| Error::Program {
                                file: file.to_string(),
                                line: b.line,
                                column: *col,
                                message: format!("{}: {m}", w.name),
                            })?
                            .or(Some(0.0)),
                        None => None,
                    };
                    out.push((v, *col));
                }
                (0.0, false, Some(out))
            }
            WVal::Bare => (0.0, false, None),
        };
        words.push(RWord { name: &w.name, v, point, col: w.col, text: &w.text, args });
    }
    Ok(RBlock { line: b.line, col: b.col, words, vacant })
}

/// Fanuc GOTO n: the block Nn of the current program, searched forward from here, then from the
/// program's start (the search order is the Fanuc manuals' as recalled, unsourced here).
fn goto_n(lay: &Layout, pc: usize, n: f64) -> Option<usize> {
    let sec = lay.section[pc];
    let cands = lay.n_index.get(&n_key(n))?;
    cands
        .iter()
        .copied()
        .find(|&i| i > pc && i < sec.1)
        .or_else(|| cands.iter().copied().find(|&i| i >= sec.0 && i <= pc))
}

/// Sinumerik GOTOF/GOTOB/GOTO: a label or a sequence number (`N100`).
fn jump_label(lay: &Layout, pc: usize, label: &str, forward: Option<bool>, end: usize) -> Option<usize> {
    let sec = lay.section.get(pc).copied().unwrap_or((0, end));
    let mut cands: Vec<usize> = lay.labels.get(label).cloned().unwrap_or_default();
    if let Some(num) = label.strip_prefix('N').and_then(|s| s.parse::<f64>().ok()) {
        cands.extend(lay.n_index.get(&n_key(num)).cloned().unwrap_or_default());
    }
    cands.sort_unstable();
    let fwd = cands.iter().copied().find(|&i| i > pc && i < sec.1);
    let bwd = cands.iter().rev().copied().find(|&i| i <= pc && i >= sec.0);
    match forward {
        Some(true) => fwd,
        Some(false) => bwd,
        None => fwd.or(bwd),
    }
}

impl Store for Vars {
    fn numbered(&mut self, m: &mut Motion, n: i64, line: usize, col: usize) -> Option<f64> {
        let v = self.read(&VarKey::Num(n));
        if v.is_none() {
            self.warn_unset(m, &VarKey::Num(n), line, col);
        }
        v
    }
}

/// Whether a `break` of the loop named `name` lies strictly between blocks `from` and `to`:
/// LinuxCNC's interpreter, skipping to the loop's end, stops at every line with the loop's name
/// and runs a `break` it finds there (interp_o_word.cc, `O_break` while `skipping_o`).
fn break_between(blocks: &[Block], from: usize, to: usize, name: &str) -> bool {
    blocks.get(from + 1..to).is_some_and(|bs| {
        bs.iter().any(|b| {
            b.stmts.iter().any(|s| matches!(s, Stmt::O { kw: OKw::Break, name: n, .. } if n == name))
        })
    })
}
