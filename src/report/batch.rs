//! `verify` over many programs: one line per operation and a summary (text), one object per
//! program and a summary (JSON Lines), SARIF 2.1.0 for code scanning (a result per failing check
//! at its line and column) and JUnit XML for a CI server's test view (a suite per program, a case
//! per operation, with the elements and attributes of Jenkins xUnit's `junit-10.xsd`, which CI
//! servers validate against; `tests/data/schemas/`). Views of the verifications; nothing is
//! computed here.

use crate::analysis::check::Verdict;
use crate::analysis::naming::DesignationFrom;
use crate::analysis::program::ProgramVerification;
use crate::analysis::program::{Milled, Process};
use crate::analysis::turn::OperationResult;
use quick_xml::events::{BytesDecl, BytesText, Event};
use quick_xml::Writer;
use serde::Serialize;
use serde_sarif::sarif;
use std::fmt::Write;

/// One operation of a program in a run of many.
#[derive(Clone, Debug, Serialize)]
pub struct BatchOperation {
    /// How it makes its thread.
    pub made: Process,
    /// Its line (the cycle's; a milled thread's first helix).
    pub line: usize,
    /// The subprogram file that line is in, when not the program's own.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub in_file: Option<String>,
    /// Its column on that line: the word that calls the cycle (1 for a milled thread).
    pub column: usize,
    /// The thread it was checked against (empty when not checked).
    pub designation: String,
    /// Where that came from (`None` when not checked).
    pub designation_from: Option<DesignationFrom>,
    /// `pass` or `fail`.
    pub verdict: Verdict,
    /// The checks that fail, by name (or why it was not checked, or nothing was cut).
    pub failed: Vec<String>,
    /// The same, each as a finding: its rule and a sentence with the value and the limit.
    pub findings: Vec<Finding>,
    /// The checks that rest on a tool nobody chose, as findings of their own (SARIF notes).
    #[serde(skip)]
    pub unverified: Vec<Finding>,
    /// What the control runs and the thread suffers from (SARIF warnings; `control` in the
    /// program's JSON).
    #[serde(skip)]
    pub warnings: Vec<Finding>,
}

/// A failing check of an operation, as SARIF, JUnit, the filter and the editor show it.
#[derive(Clone, Debug, Serialize)]
pub struct Finding {
    /// The rule: the process and the check's JSON name (`turned.pitch_diameter`,
    /// `tapped.drill_diameter`, `turned.no_cut`, `milled.not_checked`).
    pub rule: String,
    /// The sentence: what is off and by how much.
    pub message: String,
}

/// A turned (or milled) check's sentence: `pitch diameter d2 22.5312 mm, limits 22.5670 …
/// 22.6690 mm (−35.8 µm); low-z`.
pub(crate) fn check_sentence(
    c: &crate::analysis::check::Check,
    kind: crate::ThreadKind,
    lengths: super::Lengths,
) -> String {
    let cells = super::check_cells(c, lengths);
    let unit = if cells.unit.is_empty() { String::new() } else { format!(" {}", cells.unit) };
    let limits = match (cells.min.trim_start_matches('—'), cells.max.trim_start_matches('—')) {
        ("", "") => String::new(),
        (lo, "") => format!(", at least {lo}{unit}"),
        ("", hi) => format!(", at most {hi}{unit}"),
        (lo, hi) => format!(", limits {lo} … {hi}{unit}"),
    };
    let dev = if cells.deviation.is_empty() { String::new() } else { format!(" ({})", cells.deviation) };
    let note = c.note.as_deref().map_or(String::new(), |n| format!("; {n}"));
    format!("{} {}{unit}{limits}{dev}{note}", c.feature.words(kind), cells.value)
}

/// A tapping check's sentence: `feed 1.2000 mm/rev, limits 1.2500 … 1.2500 (−50.0 µm); …`.
pub(crate) fn tap_sentence(k: &crate::analysis::tap::TapCheck) -> String {
    let num = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v:.4}"));
    let unit = if k.unit.is_empty() { String::new() } else { format!(" {}", k.unit) };
    let value = k.value.map_or(String::new(), |v| format!(" {v:.4}{unit}"));
    let limits = match (num(k.min), num(k.max)) {
        (lo, hi) if lo.is_empty() && hi.is_empty() => String::new(),
        (lo, hi) if hi.is_empty() => format!(", at least {lo}{unit}"),
        (lo, hi) if lo.is_empty() => format!(", at most {hi}{unit}"),
        (lo, hi) => format!(", limits {lo} … {hi}{unit}"),
    };
    let dev = if k.deviation == 0.0 || k.value.is_none() {
        String::new()
    } else if k.unit == "mm/min" {
        format!(" ({:+.1} mm/min)", k.deviation)
    } else {
        format!(" ({:+.1} µm)", k.deviation)
    };
    let note = if k.note.is_empty() { String::new() } else { format!("; {}", k.note) };
    format!("{}{value}{limits}{dev}{note}", crate::report::tap::feature_name(k.feature))
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
    /// Where that error is, when it names a place in the program: line and column.
    #[serde(skip)]
    pub error_at: Option<(usize, usize)>,
}

impl BatchProgram {
    /// The view of a program's verification.
    pub fn of(file: &str, pv: &ProgramVerification) -> BatchProgram {
        let mut operations: Vec<BatchOperation> = pv
            .operations
            .iter()
            .map(|o| {
                let (verdict, failed, findings, unverified) = match &o.result {
                    OperationResult::Verified(v) => {
                        let bad: Vec<_> = v.checks.iter().filter(|c| c.fails(v.gauge_only)).collect();
                        (
                            Verdict::of(v.pass),
                            bad.iter().map(|c| c.feature.words(v.kind).to_string()).collect(),
                            bad.iter()
                                .map(|c| Finding {
                                    rule: format!("turned.{}", c.feature.name()),
                                    message: check_sentence(c, v.kind, super::Lengths(v.units)),
                                })
                                .collect(),
                            v.checks
                                .iter()
                                .filter_map(|c| {
                                    Some(Finding {
                                        rule: format!("turned.{}.unverified", c.feature.name()),
                                        message: format!(
                                            "unverified: {} ({})",
                                            check_sentence(c, v.kind, super::Lengths(v.units)),
                                            c.unverified.as_deref()?
                                        ),
                                    })
                                })
                                .collect(),
                        )
                    }
                    OperationResult::NoCut { reason, .. } => (
                        Verdict::Fail,
                        vec![format!("no cut: {reason}")],
                        vec![Finding { rule: "turned.no_cut".into(), message: format!("no cut: {reason}") }],
                        Vec::new(),
                    ),
                };
                BatchOperation {
                    warnings: Vec::new(),
                    made: Process::Turned,
                    line: o.operation.source_line,
                    in_file: o.operation.source_file.clone(),
                    column: o.operation.source_column,
                    designation: o.named.designation.text.clone(),
                    designation_from: Some(o.named.from),
                    verdict,
                    failed,
                    findings,
                    unverified,
                }
            })
            .collect();
        operations.extend(pv.tapped.iter().flat_map(|t| &t.holes).map(|h| {
            BatchOperation {
                unverified: Vec::new(),
                warnings: Vec::new(),
                made: Process::Tapped,
                line: h.cycle.line,
                in_file: h.cycle.source_file.clone(),
                column: h.cycle.column,
                designation: h.tap.designation.clone(),
                designation_from: Some(h.tap.designation_from),
                verdict: Verdict::of(h.pass),
                failed: h
                    .checks
                    .iter()
                    .filter(|c| !c.ok)
                    .map(|c| crate::report::tap::feature_name(c.feature).to_string())
                    .collect(),
                findings: h
                    .checks
                    .iter()
                    .filter(|c| !c.ok)
                    .map(|k| Finding {
                        rule: format!("tapped.{}", k.feature.name()),
                        message: tap_sentence(k),
                    })
                    .collect(),
            }
        }));
        operations.extend(pv.milled.iter().map(|m| {
            match m {
                Milled::Checked(r) => BatchOperation {
                    unverified: Vec::new(),
                    warnings: Vec::new(),
                    made: Process::Milled,
                    line: r.helices.first().map_or(1, |h| h.line),
                    in_file: None,
                    column: 1,
                    designation: r.designation.clone(),
                    designation_from: Some(r.named.from),
                    verdict: Verdict::of(r.pass),
                    failed: r
                        .checks
                        .iter()
                        .filter(|c| !c.ok)
                        .map(|c| c.feature.words(r.kind).to_string())
                        .collect(),
                    findings: r
                        .checks
                        .iter()
                        .filter(|c| !c.ok)
                        .map(|c| Finding {
                            rule: format!("milled.{}", c.feature.name()),
                            message: check_sentence(c, r.kind, super::Lengths(r.units)),
                        })
                        .collect(),
                },
                Milled::NotChecked { line, reason } => BatchOperation {
                    unverified: Vec::new(),
                    warnings: Vec::new(),
                    made: Process::Milled,
                    line: *line,
                    in_file: None,
                    column: 1,
                    designation: String::new(),
                    designation_from: None,
                    verdict: Verdict::Fail,
                    failed: vec![format!("not checked: {reason}")],
                    findings: vec![Finding {
                        rule: "milled.not_checked".into(),
                        message: format!("not checked: {reason}"),
                    }],
                },
            }
        }));
        // What the control will refuse or runs badly, with the operation it concerns: a milled
        // thread's own at any line, a tapped hole's at its line, a turned operation's the last
        // one that starts at or before it in its file (as the picture places them). One that
        // concerns none of them (a tap a post wrote as a drilling cycle) is a line of its own,
        // never dropped.
        for f in &pv.control {
            let same = |o: &BatchOperation| o.made == f.made && o.in_file == f.file;
            let at = match f.made {
                Process::Milled => operations.iter().position(|o| o.made == Process::Milled),
                Process::Tapped => operations.iter().position(|o| same(o) && o.line == f.line),
                Process::Turned => operations
                    .iter()
                    .enumerate()
                    .filter(|(_, o)| same(o) && o.line <= f.line)
                    .max_by_key(|(_, o)| o.line)
                    .map(|(i, _)| i),
            };
            let at = at.unwrap_or_else(|| {
                operations.push(BatchOperation {
                    unverified: Vec::new(),
                    warnings: Vec::new(),
                    made: f.made,
                    line: f.line,
                    in_file: f.file.clone(),
                    column: f.column,
                    designation: String::new(),
                    designation_from: None,
                    verdict: Verdict::Pass,
                    failed: Vec::new(),
                    findings: Vec::new(),
                });
                operations.len() - 1
            });
            let o = &mut operations[at];
            let finding =
                Finding { rule: f.rule.to_string(), message: crate::report::verify::control_sentence(f) };
            if f.level == crate::gcode::Level::Error {
                o.verdict = Verdict::Fail;
                o.failed.push(format!("before the machine: {}", f.rule));
                o.findings.push(finding);
            } else {
                o.warnings.push(finding);
            }
        }
        BatchProgram {
            file: file.to_string(),
            dialect: Some(pv.dialect),
            verdict: if pv.pass() { "pass" } else { "fail" },
            operations,
            error: None,
            error_at: None,
        }
    }

    /// A program that could not be read: `line` is the error's one line.
    pub fn unreadable(file: &str, line: String, at: Option<(usize, usize)>) -> BatchProgram {
        BatchProgram {
            file: file.to_string(),
            dialect: None,
            verdict: "error",
            operations: Vec::new(),
            error: Some(line),
            error_at: at,
        }
    }

    /// Its lines of text: one per operation (`file:line: FAIL tapped M8X1.25-6H (comment): feed`,
    /// with `; warning before the machine: RULE` where the control runs it badly), or the
    /// error's.
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
            // What the control runs and the thread suffers from: named as the JSON Lines and
            // SARIF name it (a warning does not fail the operation).
            let warned = if o.warnings.is_empty() {
                String::new()
            } else {
                let rules: Vec<&str> = o.warnings.iter().map(|w| w.rule.as_str()).collect();
                format!("; warning before the machine: {}", rules.join(", "))
            };
            let _ = writeln!(
                s,
                "{}:{}: {} {} {}{from}{failed}{warned}",
                o.in_file.as_deref().unwrap_or(&self.file),
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

/// The characters a SARIF `uri` keeps as they are (RFC 3986's unreserved ones and the path's
/// `/`); every other byte is percent-encoded.
const URI_PATH: &percent_encoding::AsciiSet =
    &percent_encoding::NON_ALPHANUMERIC.remove(b'-').remove(b'.').remove(b'_').remove(b'~').remove(b'/');

/// A program's path as a SARIF artifact `uri`: relative paths stay relative (code scanning
/// places them from the repository's root), absolute ones become `file://` URIs.
pub fn artifact_uri(file: &str) -> String {
    let slashed = file.replace('\\', "/");
    let encoded = percent_encoding::utf8_percent_encode(&slashed, URI_PATH).to_string();
    if slashed.starts_with('/') {
        format!("file://{encoded}")
    } else {
        encoded.trim_start_matches("./").to_string()
    }
}

/// What a rule checks, for the SARIF rule's short description.
fn rule_words(rule: &str) -> String {
    if let Some(r) = crate::gcode::ControlRule::ALL.iter().find(|r| r.id() == rule) {
        return r.what().to_string();
    }
    let (made, check) = rule.split_once('.').unwrap_or(("", rule));
    let made = match made {
        "turned" => "turned thread",
        "tapped" => "tapped hole",
        "milled" => "thread-milled hole",
        _ => "program",
    };
    format!("{made}: {}", check.replace('_', " "))
}

/// The guide that explains a rule, from the repository's root.
fn rule_guide(rule: &str) -> &'static str {
    match rule.split_once('.').map_or(rule, |(made, _)| made) {
        "control" | "post" => "docs/guide/before-the-machine.md",
        "turned" => "docs/guide/verify-a-lathe-program.md",
        "tapped" | "milled" => "docs/guide/tap-and-thread-mill.md",
        _ => "docs/guide/check-a-whole-program.md",
    }
}

/// The most results a SARIF run holds: GitHub's code scanning keeps 25 000 a run.
pub const SARIF_MAX_RESULTS: usize = 25_000;

/// The key of a result's fingerprint (SARIF `partialFingerprints`).
pub const FINGERPRINT_KEY: &str = "threadcheck/v1";

/// The SARIF log of a run: `version` is threadcheck's. Each result carries a fingerprint that
/// survives edits elsewhere in its file: its file, the operation's process and thread, its
/// rule, and its rank among the results that share those (`lib/shaft.nc|turned|M24X2-6g|
/// turned.pitch_diameter|1`); never its line. A run of more than [`SARIF_MAX_RESULTS`] results
/// keeps the first ones and says so in the invocation's notifications.
pub fn sarif_log(programs: &[BatchProgram], version: &str, exit_code: i32) -> Result<String, crate::Error> {
    let mut rules: Vec<String> = Vec::new();
    let mut results = Vec::new();
    let mut rule_index = |rule: &str| -> i64 {
        match rules.iter().position(|r| r == rule) {
            Some(i) => i as i64,
            None => {
                rules.push(rule.to_string());
                rules.len() as i64 - 1
            }
        }
    };
    let location = |file: &str, at: Option<(usize, usize)>| {
        let artifact = sarif::ArtifactLocation::builder().uri(artifact_uri(file)).build();
        let physical = match at {
            Some((line, column)) => sarif::PhysicalLocation::builder()
                .artifact_location(artifact)
                .region(
                    sarif::Region::builder()
                        .start_line(line.max(1) as i64)
                        .start_column(column.max(1) as i64)
                        .build(),
                )
                .build(),
            None => sarif::PhysicalLocation::builder().artifact_location(artifact).build(),
        };
        sarif::Location::builder().physical_location(physical).build()
    };
    // Fingerprints: how many results have shared a key so far.
    let mut seen: std::collections::HashMap<String, usize> = std::collections::HashMap::new();
    let mut fingerprint = |key: String| -> std::collections::BTreeMap<String, String> {
        let n = seen.entry(key.clone()).or_insert(0);
        *n += 1;
        std::iter::once((FINGERPRINT_KEY.to_string(), format!("{key}|{n}"))).collect()
    };
    for p in programs {
        if let Some(e) = &p.error {
            let i = rule_index("program.unreadable");
            results.push(
                sarif::Result::builder()
                    .rule_id("program.unreadable")
                    .rule_index(i)
                    .level(sarif::ResultLevel::Error)
                    .partial_fingerprints(fingerprint(format!(
                        "{}|program.unreadable",
                        artifact_uri(&p.file)
                    )))
                    .message(sarif::Message::builder().text(e.clone()).build())
                    .locations(vec![location(&p.file, p.error_at)])
                    .build(),
            );
            continue;
        }
        for o in &p.operations {
            let what = format!(
                "{} {}",
                o.made.name(),
                if o.designation.is_empty() { "thread" } else { &o.designation }
            );
            let levels = o
                .findings
                .iter()
                .map(|f| (f, sarif::ResultLevel::Error))
                .chain(o.warnings.iter().map(|f| (f, sarif::ResultLevel::Warning)))
                .chain(o.unverified.iter().map(|f| (f, sarif::ResultLevel::Note)));
            for (f, level) in levels {
                let i = rule_index(&f.rule);
                let file = o.in_file.as_deref().unwrap_or(&p.file);
                let key = format!("{}|{}|{}|{}", artifact_uri(file), o.made.name(), o.designation, f.rule);
                results.push(
                    sarif::Result::builder()
                        .rule_id(f.rule.clone())
                        .rule_index(i)
                        .level(level)
                        .partial_fingerprints(fingerprint(key))
                        .message(sarif::Message::builder().text(format!("{what}: {}", f.message)).build())
                        .locations(vec![location(
                            o.in_file.as_deref().unwrap_or(&p.file),
                            Some((o.line, o.column)),
                        )])
                        .build(),
                );
            }
        }
    }
    let descriptors: Vec<sarif::ReportingDescriptor> = rules
        .iter()
        .map(|r| {
            let guide = rule_guide(r);
            sarif::ReportingDescriptor::builder()
                .id(r.clone())
                .short_description(sarif::MultiformatMessageString::builder().text(rule_words(r)).build())
                .full_description(
                    sarif::MultiformatMessageString::builder()
                        .text(format!("{} (threadcheck's rule {r}; {guide})", rule_words(r)))
                        .build(),
                )
                .help(
                    sarif::MultiformatMessageString::builder()
                        .text(format!("See {guide} in threadcheck's repository."))
                        .markdown(format!("See [{guide}]({guide}) in threadcheck's repository."))
                        .build(),
                )
                .build()
        })
        .collect();
    let driver = sarif::ToolComponent::builder()
        .name("threadcheck")
        .version(version.to_string())
        .rules(descriptors)
        .build();
    // GitHub's code scanning keeps 25 000 results a run: the first ones, and the rest counted.
    let found = results.len();
    results.truncate(SARIF_MAX_RESULTS);
    let notifications: Vec<sarif::Notification> = (found > SARIF_MAX_RESULTS)
        .then(|| {
            sarif::Notification::builder()
                .level(serde_json::json!("warning"))
                .message(
                    sarif::Message::builder()
                        .text(format!(
                            "{found} results, of which the first {SARIF_MAX_RESULTS} are here (code scanning keeps {SARIF_MAX_RESULTS} a run): run the folders apart"
                        ))
                        .build(),
                )
                .build()
        })
        .into_iter()
        .collect();
    let invocation = sarif::Invocation::builder()
        .execution_successful(true)
        .exit_code(i64::from(exit_code))
        .tool_execution_notifications(notifications)
        .build();
    let run = sarif::Run::builder()
        .tool(sarif::Tool::builder().driver(driver).build())
        .invocations(vec![invocation])
        .results(results)
        .build();
    let log = sarif::Sarif::builder()
        .schema("https://json.schemastore.org/sarif-2.1.0.json")
        .version(serde_json::json!("2.1.0"))
        .runs(vec![run])
        .build();
    super::to_json_pretty(&log)
}

/// The JUnit XML of a run.
pub fn junit_xml(programs: &[BatchProgram]) -> Result<String, crate::Error> {
    let cases = |p: &BatchProgram| p.operations.len() + usize::from(p.error.is_some());
    let failures = |p: &BatchProgram| p.operations.iter().filter(|o| o.verdict != Verdict::Pass).count();
    let errors = |p: &BatchProgram| usize::from(p.error.is_some());
    let total = |f: &dyn Fn(&BatchProgram) -> usize| programs.iter().map(f).sum::<usize>().to_string();
    let mut w = Writer::new_with_indent(Vec::new(), b' ', 2);
    let xml = w.write_event(Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None))).and_then(|()| {
        w.create_element("testsuites")
            .with_attributes([
                ("name", "threadcheck"),
                ("tests", total(&cases).as_str()),
                ("failures", total(&failures).as_str()),
                ("errors", total(&errors).as_str()),
            ])
            .write_inner_content(|w| {
                for p in programs {
                    suite(w, p, cases(p), failures(p), errors(p))?;
                }
                Ok(())
            })
            .map(|_| ())
    });
    xml.map_err(|e| crate::Error::Data(format!("JUnit XML: {e}")))?;
    let xml = String::from_utf8(w.into_inner()).map_err(|e| crate::Error::Data(format!("JUnit XML: {e}")))?;
    // XML 1.0 forbids most control characters even escaped (a CI server rejects the whole
    // report): one in a file name or a program's token is written as its escape, `\u{1b}`.
    let mut out = String::with_capacity(xml.len() + 1);
    for c in xml.chars() {
        let allowed =
            matches!(c, '\t' | '\n' | '\r' | '\u{20}'..='\u{D7FF}' | '\u{E000}'..='\u{FFFD}' | '\u{10000}'..);
        if allowed {
            out.push(c);
        } else {
            out.push_str(&format!("\\u{{{:x}}}", u32::from(c)));
        }
    }
    out.push('\n');
    Ok(out)
}

/// One program's test suite.
fn suite(
    w: &mut Writer<Vec<u8>>,
    p: &BatchProgram,
    cases: usize,
    failures: usize,
    errors: usize,
) -> std::io::Result<()> {
    w.create_element("testsuite")
        .with_attributes([
            ("name", p.file.as_str()),
            ("tests", cases.to_string().as_str()),
            ("failures", failures.to_string().as_str()),
            ("errors", errors.to_string().as_str()),
            ("skipped", "0"),
            ("file", p.file.as_str()),
        ])
        .write_inner_content(|w| {
            if let Some(e) = &p.error {
                w.create_element("testcase")
                    .with_attributes([("name", "read the program"), ("classname", p.file.as_str())])
                    .write_inner_content(|w| {
                        w.create_element("error")
                            .with_attributes([("type", "unreadable"), ("message", e.as_str())])
                            .write_empty()
                            .map(|_| ())
                    })?;
            }
            for o in &p.operations {
                let name = format!(
                    "line {}: {} {}",
                    o.line,
                    o.made.name(),
                    if o.designation.is_empty() { "thread" } else { &o.designation }
                );
                let case = w
                    .create_element("testcase")
                    .with_attributes([("name", name.as_str()), ("classname", p.file.as_str())]);
                if o.verdict == Verdict::Pass {
                    case.write_empty()?;
                    continue;
                }
                let text: Vec<String> = o
                    .findings
                    .iter()
                    .map(|f| format!("{}:{}:{}: {}", p.file, o.line, o.column, f.message))
                    .collect();
                let failed = o.failed.join(", ");
                case.write_inner_content(|w| {
                    w.create_element("failure")
                        .with_attributes([
                            ("type", o.findings.first().map_or("fail", |f| f.rule.as_str())),
                            ("message", failed.as_str()),
                        ])
                        .write_text_content(BytesText::new(&text.join("\n")))
                        .map(|_| ())
                })?;
            }
            Ok(())
        })
        .map(|_| ())
}
