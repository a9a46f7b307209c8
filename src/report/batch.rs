//! `verify` over many programs: one line per operation and a summary (text), one object per
//! program and a summary (JSON Lines). Views of the verifications; nothing is computed here.

use crate::analysis::check::Verdict;
use crate::analysis::naming::DesignationFrom;
use crate::analysis::verify::{OperationResult, ProgramVerification};
use crate::analysis::whole::{Milled, Process};
use serde::Serialize;
use std::fmt::Write;

/// One operation of a program in a run of many.
#[derive(Clone, Debug, Serialize)]
pub struct BatchOperation {
    /// How it makes its thread.
    pub made: Process,
    /// Its line (the cycle's; a milled thread's first helix).
    pub line: usize,
    /// The thread it was checked against (empty when not checked).
    pub designation: String,
    /// Where that came from (`None` when not checked).
    pub designation_from: Option<DesignationFrom>,
    /// `pass` or `fail`.
    pub verdict: Verdict,
    /// The checks that fail, by name (or why it was not checked, or nothing was cut).
    pub failed: Vec<String>,
}

/// One program of a run: its verdict and operations, or the one line that says why it could
/// not be read.
#[derive(Clone, Debug, Serialize)]
pub struct BatchProgram {
    /// The file as found.
    pub file: String,
    /// Its dialect (absent when unreadable).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dialect: Option<crate::gcode::Dialect>,
    /// `pass`, `fail`, or `error` (unreadable).
    pub verdict: &'static str,
    /// Its operations (absent when unreadable).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub operations: Vec<BatchOperation>,
    /// Why it could not be read: the one located line (absent when read).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

impl BatchProgram {
    /// The view of a program's verification.
    pub fn of(file: &str, pv: &ProgramVerification) -> BatchProgram {
        let mut operations: Vec<BatchOperation> = pv
            .operations
            .iter()
            .map(|o| {
                let (verdict, failed) = match &o.result {
                    OperationResult::Verified(v) => (
                        Verdict::of(v.pass),
                        v.checks
                            .iter()
                            .filter(|c| !c.ok && c.kind.counts(v.gauge_only))
                            .map(|c| c.feature.words(v.kind).to_string())
                            .collect(),
                    ),
                    OperationResult::NoCut { reason, .. } => {
                        (Verdict::Fail, vec![format!("no cut: {reason}")])
                    }
                };
                BatchOperation {
                    made: Process::Turned,
                    line: o.operation.source_line,
                    designation: o.designation.clone(),
                    designation_from: Some(o.named.from),
                    verdict,
                    failed,
                }
            })
            .collect();
        operations.extend(pv.tapped.iter().flat_map(|t| &t.holes).map(|h| {
            BatchOperation {
                made: Process::Tapped,
                line: h.cycle.line,
                designation: h.tap.designation.clone(),
                designation_from: Some(h.tap.designation_from),
                verdict: Verdict::of(h.pass),
                failed: h
                    .checks
                    .iter()
                    .filter(|c| !c.ok)
                    .map(|c| crate::report::tapping::feature_name(c.feature).to_string())
                    .collect(),
            }
        }));
        operations.extend(pv.milled.iter().map(|m| match m {
            Milled::Checked(r) => BatchOperation {
                made: Process::Milled,
                line: r.helices.first().map_or(1, |h| h.line),
                designation: r.designation.clone(),
                designation_from: Some(r.named.from),
                verdict: Verdict::of(r.pass),
                failed:
                    r.checks.iter().filter(|c| !c.ok).map(|c| c.feature.words(r.kind).to_string()).collect(),
            },
            Milled::NotChecked { line, reason } => BatchOperation {
                made: Process::Milled,
                line: *line,
                designation: String::new(),
                designation_from: None,
                verdict: Verdict::Fail,
                failed: vec![format!("not checked: {reason}")],
            },
        }));
        BatchProgram {
            file: file.to_string(),
            dialect: Some(pv.dialect),
            verdict: if pv.pass() { "pass" } else { "fail" },
            operations,
            error: None,
        }
    }

    /// A program that could not be read: `line` is the error's one line.
    pub fn unreadable(file: &str, line: String) -> BatchProgram {
        BatchProgram {
            file: file.to_string(),
            dialect: None,
            verdict: "error",
            operations: Vec::new(),
            error: Some(line),
        }
    }

    /// Its lines of text: one per operation (`file:line: FAIL tapped M8X1.25-6H (comment): feed`),
    /// or the error's.
    pub fn text(&self) -> String {
        let mut s = String::new();
        if let Some(e) = &self.error {
            let _ = writeln!(s, "{e}");
            return s;
        }
        for o in &self.operations {
            let from = o.designation_from.map_or(String::new(), |f| format!(" ({})", f.name()));
            let failed =
                if o.failed.is_empty() { String::new() } else { format!(": {}", o.failed.join(", ")) };
            let _ = writeln!(
                s,
                "{}:{}: {} {} {}{from}{failed}",
                self.file,
                o.line,
                if o.verdict == Verdict::Pass { "PASS" } else { "FAIL" },
                o.made.name(),
                if o.designation.is_empty() { "—" } else { &o.designation },
            );
        }
        s
    }
}

/// What a run of many programs found.
#[derive(Clone, Debug, Default, Serialize)]
pub struct BatchSummary {
    /// Programs read.
    pub programs: usize,
    /// Their operations.
    pub operations: usize,
    /// Operations that pass.
    pub pass: usize,
    /// Operations that fail.
    pub fail: usize,
    /// Programs that could not be read.
    pub unreadable: usize,
}

impl BatchSummary {
    /// Counts one program in.
    pub fn add(&mut self, p: &BatchProgram) {
        if p.error.is_some() {
            self.unreadable += 1;
            return;
        }
        self.programs += 1;
        self.operations += p.operations.len();
        self.pass += p.operations.iter().filter(|o| o.verdict == Verdict::Pass).count();
        self.fail += p.operations.iter().filter(|o| o.verdict != Verdict::Pass).count();
    }

    /// The summary line.
    pub fn text(&self) -> String {
        format!(
            "{} program{} read, {} operation{}: {} pass, {} fail{}\n",
            self.programs,
            if self.programs == 1 { "" } else { "s" },
            self.operations,
            if self.operations == 1 { "" } else { "s" },
            self.pass,
            self.fail,
            if self.unreadable == 0 { String::new() } else { format!("; {} unreadable", self.unreadable) }
        )
    }
}

/// The last line of a run's JSON Lines.
#[derive(Clone, Debug, Serialize)]
pub struct SummaryLine<'a> {
    /// The counts.
    pub summary: &'a BatchSummary,
}
