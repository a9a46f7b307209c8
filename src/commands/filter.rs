//! `threadcheck filter FILE`: LinuxCNC's program filter. LinuxCNC runs the filter a `[FILTER]`
//! section names on every program it opens with that extension (`sh -c "FILTER 'FILE'"`, the
//! program on standard output, `FILTER_PROGRESS=N` lines on standard error driving the progress
//! bar, any other standard-error line shown in the error dialog when the filter exits non-zero:
//! `src/emc/usr_intf/axis/scripts/axis.py`'s `filter_program`, LinuxCNC's `docs/src/config/ini-config.adoc`
//! `[FILTER]`). This filter copies the program unchanged, writes one line per failing
//! thread-making operation to standard error, and with `--gate` exits non-zero so that the
//! control refuses the program.

use super::args::{tool_table, PlanArgs, Source};
use super::verify::VerifyArgs;
use super::{Files, Outcome, Request};
use crate::Error;
use std::path::PathBuf;

/// The arguments of `filter`.
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[derive(Clone, Debug, Default)]
pub struct FilterArgs {
    /// The program LinuxCNC opens (it passes the file's name).
    #[cfg_attr(feature = "cli", arg(value_name = "FILE"))]
    pub file: PathBuf,
    /// Exit 1 when a thread-making operation fails its check, so that LinuxCNC refuses to load
    /// the program (its error dialog shows the findings).
    #[cfg_attr(feature = "cli", arg(long))]
    pub gate: bool,
    /// With --gate: refuse a program threadcheck cannot read too (exit 2); without it, such a
    /// program is copied and loads, with the reason on standard error.
    #[cfg_attr(feature = "cli", arg(long, requires = "gate"))]
    pub strict: bool,
    /// Also put each finding in the program as a `(MSG, …)` comment after its opening lines,
    /// which LinuxCNC shows the operator when the program runs.
    #[cfg_attr(feature = "cli", arg(long))]
    pub msg: bool,
    /// Tool table: which insert, tap, drill or thread mill each T number holds (TOML).
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE.toml", value_parser = Source::path))]
    pub tools: Option<Source>,
    /// Leave form checks out of the verdict (sizes and the GO gauge only).
    #[cfg_attr(feature = "cli", arg(long))]
    pub gauge_only: bool,
    #[cfg_attr(feature = "cli", command(flatten))]
    #[allow(missing_docs)]
    pub plan: PlanArgs,
}

/// What the filter writes and how it ends.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Filtered {
    /// Standard output: the program's bytes as read (with `--msg`, its findings' comments
    /// inserted after its opening lines).
    pub stdout: Vec<u8>,
    /// Standard error: the progress lines and one line per finding.
    pub stderr: String,
    /// How it ends: a pass unless `--gate` (out of tolerance: a failing thread; unreadable, with
    /// `--strict`: a program threadcheck cannot read).
    pub outcome: Outcome,
}

/// The progress line LinuxCNC's filter runners read (`^FILTER_PROGRESS=(\d*)$`).
fn progress(percent: u8) -> String {
    format!("FILTER_PROGRESS={percent}\n")
}

/// The longest line LinuxCNC's interpreter reads, in bytes: `strlen(command) >= LINELEN` is
/// "Command too long", LINELEN being 255 (`src/emc/linuxcnc.h`, `src/emc/rs274ngc/interp_read.cc`).
pub const LINUXCNC_MAX_LINE: usize = 254;

/// A `(MSG, …)` line: one line, no parenthesis that would end the comment early, cut (with `…`)
/// to [`LINUXCNC_MAX_LINE`] bytes.
fn msg_comment(text: &str) -> String {
    let t: String = text
        .chars()
        .map(|c| match c {
            '(' => '[',
            ')' => ']',
            c if c.is_control() => ' ',
            c => c,
        })
        .collect();
    let room = LINUXCNC_MAX_LINE - "(MSG, )".len();
    let t = if t.len() <= room {
        t
    } else {
        let mut end = room - '…'.len_utf8();
        while !t.is_char_boundary(end) {
            end -= 1;
        }
        format!("{}…", &t[..end])
    };
    debug_assert!(t.len() + "(MSG, )".len() <= LINUXCNC_MAX_LINE);
    format!("(MSG, {t})\n")
}

/// Runs the filter on `args.file`.
///
/// ```
/// let dir = std::env::temp_dir().join(format!("threadcheck-filter-doc-{}", std::process::id()));
/// std::fs::create_dir_all(&dir)?;
/// let file = dir.join("part.ngc");
/// std::fs::write(&file, "G21 G18\nG0 X12 Z2\n")?;
/// let args = threadcheck::FilterArgs { file, gate: true, ..Default::default() };
/// let out = threadcheck::filter(&args)?;
/// // A program without a thread is copied as it is, and passes the gate.
/// assert_eq!(out.stdout, b"G21 G18\nG0 X12 Z2\n");
/// assert_eq!(out.outcome, threadcheck::Outcome::Pass);
/// assert!(out.stderr.starts_with("FILTER_PROGRESS=0\n"));
/// # std::fs::remove_dir_all(&dir)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn filter(args: &FilterArgs) -> Result<Filtered, Error> {
    if args.plan.program.is_some() {
        return Err(Error::Input("filter takes the program as FILE, not ‹program›".into()));
    }
    // The bytes as LinuxCNC would read them: copied whatever threadcheck makes of them.
    // Through the bounded reader (a FIFO with no writer or /dev/zero is refused, never waited on
    // or grown without bound).
    let bytes = crate::ground::input::read_bounded(
        &args.file,
        crate::ground::bounds::MAX_PROGRAM_BYTES,
        "the program",
    )?;
    let request =
        Request { wanted: Vec::new(), files: Files::Allowed, reader: crate::Audience::Cli, progress: false };
    let tools = args.tools.as_ref().map(|t| tool_table(t, Files::Allowed)).transpose()?;
    let verify = VerifyArgs {
        plan: args.plan.clone(),
        tools: args.tools.clone(),
        gauge_only: args.gauge_only,
        no_pass_metrics: true,
        ..VerifyArgs::default()
    };
    let mut stderr = progress(0);
    let checked = verify.one_of_many(&args.file, tools.as_ref(), &request);
    let words = |s: &str| crate::Audience::Cli.words(s);
    // Standard error: a line per failing operation; the messages: a line per finding.
    let (mut lines, mut messages) = (Vec::new(), Vec::new());
    let base =
        args.file.file_name().map_or_else(|| checked.file.clone(), |n| n.to_string_lossy().to_string());
    if let Some(e) = &checked.error {
        let e = words(e.trim_start_matches("error: "));
        lines.push(format!("threadcheck: not checked: {e}"));
        // The place stays with the file's name: `part.ngc:8:22: not checked: …`.
        let rest = e.strip_prefix(&checked.file).unwrap_or(&e);
        messages.push(match rest.strip_prefix(':').and_then(place_and_message) {
            Some((place, message)) => format!("threadcheck: {base}:{place}: not checked: {message}"),
            None => format!("threadcheck: {base} not checked: {}", rest.trim_start_matches([':', ' '])),
        });
    }
    let mut failing = 0;
    for o in checked.operations.iter().filter(|o| o.verdict != crate::analysis::check::Verdict::Pass) {
        failing += 1;
        let what = format!(
            "FAIL {} {}",
            o.made.name(),
            if o.designation.is_empty() { "thread" } else { &o.designation }
        );
        let detail: Vec<String> = o.findings.iter().map(|f| words(&f.message)).collect();
        lines.push(format!(
            "threadcheck: {}:{}:{}: {what}: {}",
            o.in_file.as_deref().unwrap_or(&checked.file),
            o.line,
            o.column,
            detail.join("; ")
        ));
        messages.extend(detail.iter().map(|d| format!("threadcheck: {base}:{}: {what}: {d}", o.line)));
    }
    for l in &lines {
        stderr.push_str(&crate::one_line(l));
        stderr.push('\n');
    }
    stderr.push_str(&progress(100));
    let stdout = if args.msg && !messages.is_empty() { with_messages(&bytes, &messages) } else { bytes };
    let outcome = match (args.gate, checked.error.is_some(), failing > 0) {
        (true, _, true) => Outcome::OutOfTolerance,
        (true, true, false) if args.strict => Outcome::Unreadable,
        _ => Outcome::Pass,
    };
    Ok(Filtered { stdout, stderr, outcome })
}

/// The program with a `(MSG, …)` line per finding after its opening lines: after a leading `%`
/// line (LinuxCNC's demarcation, which must come first), else at the top.
fn with_messages(bytes: &[u8], findings: &[String]) -> Vec<u8> {
    // The first line, when it is `%` (blank lines before it allowed): its end.
    let mut at = 0;
    let mut pos = 0;
    for line in bytes.split_inclusive(|&b| b == b'\n') {
        pos += line.len();
        let t = line.trim_ascii();
        if t.is_empty() {
            continue;
        }
        if t == b"%" {
            at = pos;
        }
        break;
    }
    let mut out = Vec::with_capacity(bytes.len() + 200 * findings.len());
    out.extend_from_slice(&bytes[..at]);
    if at > 0 && !bytes[..at].ends_with(b"\n") {
        out.push(b'\n');
    }
    for f in findings {
        out.extend_from_slice(msg_comment(f).as_bytes());
    }
    out.extend_from_slice(&bytes[at..]);
    out
}

/// `8:22: word J …` as its place (`8:22`) and its message.
fn place_and_message(rest: &str) -> Option<(&str, &str)> {
    let mut parts = rest.splitn(3, ':');
    let (line, column, message) = (parts.next()?, parts.next()?, parts.next()?);
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    (digits(line) && digits(column)).then(|| (&rest[..line.len() + 1 + column.len()], message.trim_start()))
}
