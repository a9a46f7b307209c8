//! A program's verification as an editor shows it (`threadcheck lsp`): a diagnostic per
//! thread-making operation at its line (an error when it fails, with its failing checks; an
//! information when it passes), a hover per operation with every check, and the correction's word
//! edits as a quick fix. A view of the verification; nothing is computed here.

use super::batch::{check_sentence, tap_sentence, BatchProgram};
use crate::analysis::check::Verdict;
use crate::analysis::program::Milled;
use crate::analysis::program::ProgramVerification;
use crate::analysis::turn::OperationResult;
use crate::gcode::WordEdit;
use std::fmt::Write as _;

/// How serious a diagnostic is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Severity {
    /// An operation that fails, or a program that cannot be read.
    Error,
    /// What the control runs while the thread suffers (a control finding's warning).
    Warning,
    /// An operation that passes.
    Information,
}

/// A diagnostic at a place of the program.
#[derive(Clone, Debug, PartialEq)]
pub struct EditorDiagnostic {
    /// Line, from 1.
    pub line: usize,
    /// Column, from 1 (in characters).
    pub column: usize,
    /// Error or information.
    pub severity: Severity,
    /// The rule (`turned.pitch_diameter`, `program.unreadable`, `pass`).
    pub code: String,
    /// What the editor shows.
    pub message: String,
}

/// What hovering over an operation's line shows (Markdown).
#[derive(Clone, Debug, PartialEq)]
pub struct EditorHover {
    /// Line, from 1.
    pub line: usize,
    /// The text.
    pub markdown: String,
}

/// A quick fix: the words a correction rewrites.
#[derive(Clone, Debug, PartialEq)]
pub struct EditorFix {
    /// The operation's line, from 1.
    pub line: usize,
    /// What the fix does, in words.
    pub title: String,
    /// The word edits, in the program's own words.
    pub edits: Vec<WordEdit>,
}

/// The editor's view of one program.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EditorView {
    /// Its diagnostics.
    pub diagnostics: Vec<EditorDiagnostic>,
    /// Its hovers.
    pub hovers: Vec<EditorHover>,
    /// Its quick fixes.
    pub fixes: Vec<EditorFix>,
}

impl EditorView {
    /// The view of a verified program; `fixes` holds each correction's title and edits, by the
    /// operation's line.
    pub fn of(pv: &ProgramVerification, fixes: Vec<EditorFix>) -> EditorView {
        let batch = BatchProgram::of("", pv);
        let diagnostics = batch
            .operations
            .iter()
            .map(|o| {
                let what = format!(
                    "{} {}",
                    o.made.name(),
                    if o.designation.is_empty() { "thread" } else { &o.designation }
                );
                let from = o.designation_from.map_or(String::new(), |f| format!(" (named: {})", f.name()));
                // An operation in a subprogram's file: at the document's first line, with its place.
                let (line, column, what) = match &o.in_file {
                    Some(f) => (1, 1, format!("{what} (at {f}:{})", o.line)),
                    None => (o.line, o.column, what),
                };
                if o.verdict == Verdict::Pass {
                    EditorDiagnostic {
                        line,
                        column,
                        severity: Severity::Information,
                        code: "pass".into(),
                        message: format!("threadcheck: PASS {what}{from}"),
                    }
                } else {
                    let found: Vec<&str> = o.findings.iter().map(|f| f.message.as_str()).collect();
                    EditorDiagnostic {
                        line,
                        column,
                        severity: Severity::Error,
                        code: o.findings.first().map_or_else(|| "fail".into(), |f| f.rule.clone()),
                        message: format!("threadcheck: FAIL {what}{from}: {}", found.join("; ")),
                    }
                }
            })
            .chain(batch.operations.iter().flat_map(|o| {
                o.warnings.iter().map(move |w| EditorDiagnostic {
                    line: o.line,
                    column: o.column,
                    severity: Severity::Warning,
                    code: w.rule.clone(),
                    message: format!("threadcheck: {}", w.message),
                })
            }))
            .collect();
        EditorView { diagnostics, hovers: hovers(pv), fixes }
    }

    /// A program that cannot be read: its one line at its place (line 1 when it names none).
    pub fn unreadable(message: String, at: Option<(usize, usize)>) -> EditorView {
        let (line, column) = at.unwrap_or((1, 1));
        EditorView {
            diagnostics: vec![EditorDiagnostic {
                line,
                column,
                severity: Severity::Error,
                code: "program.unreadable".into(),
                message: format!("threadcheck: {message}"),
            }],
            ..EditorView::default()
        }
    }
}

/// A check's line in a hover: `✓ pitch diameter d2 22.5777 mm, limits …`.
fn mark(ok: bool) -> &'static str {
    if ok {
        "✓"
    } else {
        "✗"
    }
}

/// One hover per operation: its thread, where the name came from, its verdict and every check.
fn hovers(pv: &ProgramVerification) -> Vec<EditorHover> {
    let mut out = Vec::new();
    // Hovers on the document's own lines: an operation in a subprogram's file has none here.
    for o in pv.operations.iter().filter(|o| o.operation.source_file.is_none()) {
        let mut md =
            format!("**{} {}** (turned, {})", o.operation.cycle, o.named.designation.text, o.named.why);
        match &o.result {
            OperationResult::Verified(v) => {
                let _ = write!(
                    md,
                    " — **{}**\n\n{} passes\n\n",
                    if v.pass { "PASS" } else { "FAIL" },
                    o.operation.passes.len()
                );
                for c in v.checks.iter().filter(|c| c.counts(v.gauge_only)) {
                    let _ = writeln!(
                        md,
                        "- {} {}",
                        mark(c.ok),
                        check_sentence(c, v.kind, super::Lengths(v.units))
                    );
                }
                if let Some(c) = &v.correction {
                    let _ = write!(md, "\n{}\n", super::correction_text(c));
                }
            }
            OperationResult::NoCut { reason, .. } => {
                let _ = write!(md, " — **FAIL**\n\nno cut: {reason}\n");
            }
        }
        out.push(EditorHover { line: o.operation.source_line, markdown: md });
    }
    for h in pv.tapped.iter().flat_map(|t| &t.holes).filter(|h| h.cycle.source_file.is_none()) {
        let mut md = format!(
            "**{} {}** (tapped) — **{}**\n\n",
            h.cycle.code,
            h.tap.designation,
            if h.pass { "PASS" } else { "FAIL" }
        );
        for k in &h.checks {
            let _ = writeln!(md, "- {} {}", mark(k.ok), tap_sentence(k));
        }
        out.push(EditorHover { line: h.cycle.line, markdown: md });
    }
    if let Some(m) = &pv.milled {
        match m {
            Milled::Checked(r) => {
                let mut md = format!(
                    "**{}** (thread-milled, {} helices) — **{}**\n\n",
                    r.designation,
                    r.helices.len(),
                    if r.pass { "PASS" } else { "FAIL" }
                );
                for c in &r.checks {
                    let _ = writeln!(
                        md,
                        "- {} {}",
                        mark(c.ok),
                        check_sentence(c, r.kind, super::Lengths(r.units))
                    );
                }
                out.push(EditorHover { line: r.helices.first().map_or(1, |h| h.line), markdown: md });
            }
            Milled::NotChecked { line, reason } => {
                out.push(EditorHover {
                    line: *line,
                    markdown: format!("**thread-milled** — not checked: {reason}\n"),
                });
            }
        }
    }
    out
}
