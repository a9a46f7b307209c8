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
}

impl<'a> PassesReport<'a> {
    /// The report of `passes`, grouped by `operations` when they come from a program.
    pub fn new(
        thread: Option<ThreadReport<'a>>,
        passes: &'a [crate::toolpath::passes::Pass],
        operations: Option<&'a [crate::gcode::Operation]>,
        program: Option<(&'a [crate::ground::note::Note], usize)>,
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
