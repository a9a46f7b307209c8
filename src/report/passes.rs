//! `passes --json`: each operation's passes with their source lines.

use super::*;
use serde::Serialize;

/// One operation of `passes --json`.
#[derive(Clone, Debug, Serialize)]
pub struct PassesOperation<'a> {
    /// 1-based, in program order.
    pub index: usize,
    /// The cycle (`G76`, `G33`, `L97`, …).
    pub cycle: &'a str,
    /// First program line.
    pub source_line: usize,
    /// The T number, if named.
    pub tool: Option<u32>,
    /// Spindle state.
    pub spindle: crate::gcode::Spindle,
    /// Lead, mm.
    pub lead: f64,
    /// Warnings and assumed defaults.
    pub notes: &'a [crate::ground::note::Note],
    /// Its passes.
    pub passes: &'a [crate::toolpath::passes::Pass],
}

/// `passes --json` (docs/json.md).
#[derive(Clone, Debug, Serialize)]
pub struct PassesReport<'a> {
    /// The thread, when one was given.
    pub thread: Option<ThreadReport<'a>>,
    /// Largest Z any pass reaches, mm.
    pub thread_start: f64,
    /// Smallest Z any pass reaches, mm.
    pub thread_end: f64,
    /// Every pass in cutting order.
    pub passes: &'a [crate::toolpath::passes::Pass],
    /// A program's passes by operation.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub operations: Option<Vec<PassesOperation<'a>>>,
    /// A program's notes (assumptions, what was read past).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub notes: Option<&'a [crate::ground::note::Note]>,
    /// A program's blocks read past (each kind named in `notes`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub read_past_blocks: Option<usize>,
    /// The machine a program was read for, and why.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub machine: Option<&'a crate::gcode::MachineReading>,
}

impl<'a> PassesReport<'a> {
    /// The report of `passes`, grouped by `operations` when they come from a program.
    pub fn new(
        thread: Option<ThreadReport<'a>>,
        passes: &'a [crate::toolpath::passes::Pass],
        operations: Option<&'a [crate::gcode::Operation]>,
        program: Option<(&'a [crate::ground::note::Note], usize, &'a crate::gcode::MachineReading)>,
    ) -> Self {
        let (thread_start, thread_end) =
            passes.iter().fold((f64::NEG_INFINITY, f64::INFINITY), |(a, b), p| {
                (a.max(p.z_start.max(p.z_end)), b.min(p.z_start.min(p.z_end)))
            });
        PassesReport {
            thread,
            thread_start,
            thread_end,
            passes,
            notes: program.map(|p| p.0),
            read_past_blocks: program.map(|p| p.1),
            machine: program.map(|p| p.2),
            operations: operations.map(|ops| {
                ops.iter()
                    .map(|op| PassesOperation {
                        index: op.index,
                        cycle: &op.cycle,
                        source_line: op.source_line,
                        tool: op.tool,
                        spindle: op.spindle,
                        lead: op.lead(),
                        notes: &op.notes,
                        passes: &op.passes,
                    })
                    .collect()
            }),
        }
    }
}

/// Where `passes` took its passes from, for its text's header.
#[derive(Clone, Copy, Debug)]
pub enum PassesSource<'a> {
    /// A program, read in `dialect`.
    Program {
        /// What messages call it.
        shown: &'a str,
        /// Its dialect.
        dialect: crate::gcode::Dialect,
        /// The program read.
        program: &'a crate::gcode::Program,
    },
    /// A generated plan.
    Plan {
        /// The designation as written.
        designation: &'a str,
        /// External or internal.
        kind: crate::standards::ThreadKind,
        /// The blank's diameter, mm.
        blank: f64,
        /// The last pass's X, mm.
        final_x: f64,
    },
}

/// The text `passes` prints: a header line, a program's notes, and a row per pass (by operation
/// for a program).
pub fn text(source: PassesSource<'_>, passes: &[crate::toolpath::passes::Pass]) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    match source {
        PassesSource::Program { shown, dialect, program: prog } => {
            let leads: Vec<String> = prog.operations.iter().map(|o| fmt_num(o.lead())).collect();
            let _ = writeln!(
                s,
                "{shown} ({}): {} operation{}, {} passes, lead {} mm, {} other blocks read for position{}",
                dialect.name(),
                prog.operations.len(),
                if prog.operations.len() == 1 { "" } else { "s" },
                prog.passes.len(),
                leads.join(" / "),
                prog.skipped_blocks,
                read_past_text(prog.read_past_blocks),
            );
            for n in &prog.notes {
                let _ = writeln!(s, "note: {}", n.marked());
            }
        }
        PassesSource::Plan { designation, kind, blank, final_x } => {
            let _ = writeln!(
                s,
                "{designation} {}: {} passes, blank X{blank:.4}, final X{final_x:.4}",
                kind.name(),
                passes.len()
            );
        }
    }
    let row = |s: &mut String, p: &crate::toolpath::passes::Pass| {
        let _ = writeln!(
            s,
            "  {:>4}  {:>5}  {:>9.4}  {:>9.4}  {:>9.4}  {:>9.4}  {:>5}",
            p.index,
            p.start + 1,
            p.x_start,
            p.x_end,
            p.z_start,
            p.z_end,
            p.source_line.map_or("—".to_string(), |l| l.to_string())
        );
    };
    let head = "  pass  start    X start      X end    Z start      Z end   line\n";
    match source {
        PassesSource::Program { program, .. } => {
            for op in &program.operations {
                let _ = writeln!(
                    s,
                    "\noperation {}: {} at line {}{}{}, lead {} mm, {} passes",
                    op.index,
                    op.cycle,
                    op.source_line,
                    op.source_file.as_ref().map_or(String::new(), |f| format!(" of {f}")),
                    op.tool.map_or(String::new(), |t| format!(", tool T{t}")),
                    fmt_num(op.lead()),
                    op.passes.len()
                );
                for n in &op.notes {
                    let _ = writeln!(s, "  note: {}", n.marked());
                }
                s.push_str(head);
                for p in &op.passes {
                    row(&mut s, p);
                }
            }
        }
        PassesSource::Plan { .. } => {
            s.push('\n');
            s.push_str(head);
            for p in passes {
                row(&mut s, p);
            }
        }
    }
    s
}
