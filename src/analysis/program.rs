//! One verify for every thread a program makes: its turned threads (every threading cycle and
//! G32/G33 chain), its tapped holes (every tapping cycle, with its drill) and its thread-milled
//! thread (the helices), each checked as its own command checks it, in one report with one
//! verdict.
//!
//! The thread of each comes from `--thread` (the turned operations'; a program with no turned
//! thread gives it to its milled one), else from the program (a comment above it, the tool table's
//! tap, else the standard size it cuts: [`crate::analysis::naming`]). A milled thread whose cutter
//! is not known (no tool table names the helix's tool as a thread mill) is reported as not
//! checked, which fails: nothing a program makes is passed unseen.

use crate::analysis::tap::TapSpec;
use crate::analysis::thread_mill::{ThreadMillReport, ThreadMillSpec};
use crate::analysis::tools::{Tool, ToolTable};
use crate::analysis::turn::{InsertFor, OperationVerdict, ProgramLabel, TurnedProgram, VerifySpec};
use crate::gcode::{Dialect, HoleKind, ReadOptions};
use crate::Error;

/// Every operation of a program, verified.
#[derive(Clone, Debug)]
pub struct ProgramVerification {
    /// The program's name and dialect, as shown.
    pub program: ProgramLabel,
    /// The dialect.
    pub dialect: crate::gcode::Dialect,
    /// Each threading operation in program order (the one `VerifySpec::operation` names, when
    /// it names one).
    pub operations: Vec<OperationVerdict>,
    /// How many threading operations the program has (more than `operations` holds when one
    /// was named).
    pub operations_in_program: usize,
    /// Program-wide warnings (variables read before set, repeated sequence numbers, …).
    pub notes: Vec<crate::ground::note::Note>,
    /// Blocks read for position only.
    pub skipped_blocks: usize,
    /// Blocks holding something threadcheck does not model, read past (named in the notes).
    pub read_past_blocks: usize,
    /// The machine the program was read for, and why.
    pub machine: crate::gcode::MachineReading,
    /// Its tapping cycles, checked (`verify_whole`; `None` when it has none).
    pub tapped: Option<crate::analysis::tap::TapReport>,
    /// Its thread-milled thread (`verify_whole`; `None` when it has no helix).
    pub milled: Option<Milled>,
    /// What the control will refuse and what the post got wrong (`verify_whole`): an error
    /// fails the program.
    pub control: Vec<crate::analysis::control::ControlFinding>,
}

impl ProgramVerification {
    /// The verification of `prog`'s turned `operations` (of `n` in the program), its notes and
    /// reading; no tapped or milled thread yet.
    pub(crate) fn of(turned: TurnedProgram) -> ProgramVerification {
        let TurnedProgram { prog, label: program, operations, operations_in_program: n } = turned;
        ProgramVerification {
            dialect: program.dialect,
            program,
            operations,
            operations_in_program: n,
            notes: prog.notes,
            skipped_blocks: prog.skipped_blocks,
            read_past_blocks: prog.read_past_blocks,
            machine: prog.machine,
            tapped: None,
            milled: None,
            control: Vec::new(),
        }
    }

    /// True when every operation passes, turned, tapped and milled, and the control refuses
    /// nothing.
    pub fn pass(&self) -> bool {
        self.threads_pass() && !self.refused()
    }

    /// True when every thread it makes is within its checks (whatever the control says).
    pub fn threads_pass(&self) -> bool {
        self.operations.iter().all(|o| o.result.pass())
            && self.tapped.as_ref().is_none_or(|t| t.pass)
            && self.milled.as_ref().is_none_or(Milled::pass)
    }

    /// True when a control finding is an error: the control refuses a block, or the cut breaks
    /// the tool.
    pub fn refused(&self) -> bool {
        crate::analysis::control::any_error(&self.control)
    }
}

/// Verifies every threading operation of a program held in memory: `threads` gives one
/// designation for all operations or one per operation in program order; `insert_for` chooses
/// each operation's insert (from its tool number, say) and says what it assumed.
///
/// ```
/// use threadcheck::{verify_program, InsertChoice, VerifySpec};
/// use threadcheck::Dialect;
/// let text = "G0 X22 Z5\nG76 P011060 Q100 R0.05\nG76 X18.16 Z-20 P920 Q350 F1.5\n";
/// let spec = VerifySpec { insert: InsertChoice::Full, ..VerifySpec::of("M20x1.5-6g")? };
/// let m20 = spec.designation.clone().into_iter().collect::<Vec<_>>();
/// let r = verify_program(&spec, text, "m20.nc", Dialect::Fanuc, &m20, &|_| None)?;
/// assert_eq!(r.operations.len(), 1);
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn verify_program(
    spec: &VerifySpec,
    text: &str,
    name: &str,
    dialect: crate::gcode::Dialect,
    threads: &[crate::standards::Designation],
    insert_for: &InsertFor<'_>,
) -> Result<ProgramVerification, Error> {
    crate::analysis::turn::turned_program(spec, text, name, dialect, threads, insert_for)
        .map(ProgramVerification::of)
}

pub use crate::analysis::made::Process;

/// What became of a program's thread-milled thread.
#[derive(Clone, Debug)]
pub enum Milled {
    /// Measured and checked.
    Checked(Box<ThreadMillReport>),
    /// Not checked (the cutter is not known): a failing verdict with the reason.
    NotChecked {
        /// The first helix's line.
        line: usize,
        /// Why, and what to give.
        reason: String,
    },
}

impl Milled {
    /// Whether it passes (never when not checked).
    pub fn pass(&self) -> bool {
        match self {
            Milled::Checked(r) => r.pass,
            Milled::NotChecked { .. } => false,
        }
    }
}

/// What a program holds besides thread-making operations (`; it has 2 drilling cycles (G81 at
/// line 5, …)`), for the message of a program that makes none; empty when nothing is worth naming.
fn contents(prog: &crate::gcode::Program) -> String {
    let drills = prog.holes.iter().filter(|h| h.kind == HoleKind::Drill).count();
    let arcs = prog.moves.iter().filter(|m| m.arc.is_some()).count();
    let mut parts = Vec::new();
    if drills > 0 {
        let lines: Vec<String> = prog
            .holes
            .iter()
            .filter(|h| h.kind == HoleKind::Drill)
            .take(4)
            .map(|h| format!("{} at line {}", h.code, h.line))
            .collect();
        parts.push(format!(
            "{drills} drilling cycle{} ({}{})",
            if drills == 1 { "" } else { "s" },
            lines.join(", "),
            if drills > 4 { ", …" } else { "" }
        ));
    }
    if arcs > 0 {
        parts.push(format!("{arcs} arc{} without a Z change", if arcs == 1 { "" } else { "s" }));
    }
    if parts.is_empty() {
        String::new()
    } else {
        format!("; it has {}", parts.join(", "))
    }
}

/// Verifies every thread a program makes: its turned operations as
/// [`verify_program`](crate::verify_program) does, its tapping cycles as
/// [`tap`](crate::tap) does, its helices as [`thread_mill`](crate::thread_mill) does.
/// `threads` (empty: the program names them) are the turned operations'; `tools` gives the
/// inserts, taps, drills and thread mills by T number.
///
/// ```
/// use threadcheck::{verify_whole, Dialect, InsertChoice, VerifySpec};
/// // A lathe program that turns an M20x1.5 and taps an M8 on the centre line, each named by a comment.
/// let text = "(M20X1.5-6G)\nG99 G0 X22 Z5\nG76 P010060 Q100 R0.05\nG76 X18.16 Z-20 P920 Q300 F1.5\n\
///             T0505 (DRILL 6.8)\nG97 S900 M3\nG0 X0 Z5\nG83 Z-25 R2 Q5000 F0.1\nG80\n\
///             T0606 (TAP M8X1.25)\nG0 X0 Z8\nG84 Z-16 R5 F1.25\nG80\nM30\n";
/// let spec = VerifySpec { insert: InsertChoice::Full, ..VerifySpec::new(None) };
/// let r = verify_whole(&spec, text, "part.nc", Dialect::Fanuc, &[], &|_| None, None)?;
/// assert_eq!(r.operations.len(), 1);
/// let tapped = r.tapped.as_ref().expect("a tapping cycle");
/// assert_eq!(tapped.holes[0].tap.designation, "M8X1.25-6H");
/// assert!(tapped.holes[0].pass); // Ø6.8 within D1 6.647–6.912; F1.25 = P; room for the point
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn verify_whole(
    spec: &VerifySpec,
    text: &str,
    name: &str,
    dialect: Dialect,
    threads: &[crate::standards::Designation],
    insert_for: &InsertFor<'_>,
    tools: Option<&ToolTable>,
) -> Result<ProgramVerification, Error> {
    let reading = ReadOptions { allow_no_threading: true, ..spec.reading.clone() };
    let mut prog = crate::gcode::read_program_with(text, name, dialect, reading.clone())?;
    // On a machining centre, its toolpath too (a recorded toolpath is read as a mill's).
    if prog.machine.machine_type != crate::gcode::MachineType::Lathe {
        // A mill-turn program's toolpath is still read section by section (its reading kept).
        let machine = prog.machine.clone();
        let mill_turn = (machine.machine_type == crate::gcode::MachineType::MillTurn)
            .then_some(crate::gcode::MachineType::MillTurn);
        let again = ReadOptions { moves: true, machine_type: mill_turn.or(reading.machine_type), ..reading };
        prog = crate::gcode::read_program_with(text, name, dialect, again)?;
        prog.machine = machine;
    }
    let taps = prog.holes.iter().any(|h| h.kind == HoleKind::Tap);
    let helix = prog.moves.iter().find(|m| m.arc.is_some() && (m.to[2] - m.from[2]).abs() > 1e-9);
    // A tap a post wrote as a drilling cycle: the program's one thread-making operation, wrong.
    let taps_drilled = crate::analysis::control::taps_in_drill_cycles(
        &prog,
        dialect,
        tools,
        &crate::gcode::comments(text, dialect),
        spec.allow_nonstandard,
    );
    if prog.operations.is_empty() && !taps && helix.is_none() && taps_drilled.is_empty() {
        let (line, column, hint) = crate::gcode::no_thread_hint(&prog.notes)
            .map_or((1, 1, String::new()), |(l, c, h)| (l, c, format!("; {h}")));
        return Err(Error::Program {
            file: name.to_string(),
            line,
            column,
            message: format!(
                "no thread-making operation in the program (looked for {}, tapping cycles, and helices: G2/G3 with a Z change){hint}{}",
                dialect.threading_words(),
                contents(&prog)
            ),
        });
    }
    let mut pv = if prog.operations.is_empty() {
        ProgramVerification::of(TurnedProgram {
            prog: prog.clone(),
            label: ProgramLabel { file: name.to_string(), dialect },
            operations: Vec::new(),
            operations_in_program: 0,
        })
    } else {
        verify_program(spec, text, name, dialect, threads, insert_for)?
    };
    if taps {
        let t = TapSpec {
            program: (text.to_string(), name.to_string()),
            dialect,
            reading: spec.reading.clone(),
            tools: tools.cloned().unwrap_or_else(ToolTable::none),
            allow_nonstandard: spec.allow_nonstandard,
            from_program: true,
            stock_bottom: spec.stock_bottom,
            tap: None,
            torque: None,
            machine: spec.machine.clone(),
        };
        let mut r = crate::analysis::tap::tap(&t)?;
        // The program's notes are the report's, once.
        r.notes.clear();
        pv.tapped = Some(r);
    }
    pv.control =
        crate::analysis::control::before_machine(&prog, dialect, pv.tapped.as_ref(), spec.machine.as_ref());
    pv.control.extend(taps_drilled);
    if let Some(h) = helix {
        // The thread mill: the helix's tool in the table, as a thread mill's file, else the one
        // the program's comments name for it.
        let in_table = match (tools, h.tool) {
            (Some(tt), Some(t)) => matches!(tt.tool(t), Some((Tool::Insert(_), _))),
            _ => false,
        };
        let cutter_known =
            in_table || crate::analysis::thread_mill::cutter_in_comments(text, dialect, tools, h).is_some();
        pv.milled = Some(if cutter_known {
            let m = ThreadMillSpec {
                program: (text.to_string(), name.to_string()),
                dialect,
                designation: match (prog.operations.is_empty(), threads) {
                    (true, [one]) => Some(one.clone()),
                    _ => None,
                },
                allow_nonstandard: spec.allow_nonstandard,
                cutter: None,
                tools: tools.cloned(),
                blank_diameter: None,
                comp_radius: None,
                reading: spec.reading.clone(),
                teeth: None,
            };
            let mut r = crate::analysis::thread_mill::thread_mill(&m)?;
            // The program's notes are the report's, once.
            let program: Vec<String> = prog.notes.iter().map(|n| n.marked().to_string()).collect();
            r.notes.retain(|n| !program.contains(&n.marked().to_string()));
            pv.control.extend(crate::analysis::control::milled(&r, dialect));
            Milled::Checked(Box::new(r))
        } else {
            Milled::NotChecked {
                line: h.line,
                reason: match h.tool {
                    Some(t) => format!(
                        "the thread mill T{t} of the helices is not known (‹tools›: {t} = \"thread-mill.toml\", the cutter's file; a comment such as (T{t} THREAD MILL D8); or `thread-mill` with ‹cutter_diameter›)"
                    ),
                    None => "the program names no tool before its helices (`thread-mill` with ‹cutter_diameter›)".to_string(),
                },
            }
        });
    }
    Ok(pv)
}
