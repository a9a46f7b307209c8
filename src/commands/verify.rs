//! `threadcheck verify`: the thread cut in the computer and checked against its class.

use super::args::{tool_table, PlanArgs, Source};
use super::{pretty, Dest, Document, Job, Outcome, Outputs, Request};
use crate::analysis::tools::InsertChoice;
use crate::analysis::turn::{ProgramSource, VerifySpec};
use crate::Error;
use serde::Deserialize;
use std::path::PathBuf;

/// The arguments of `verify`.
///
/// ```
/// use threadcheck::{Command, Document, Files, Outcome, Request};
/// // A full-profile insert with its tip on d3 = d − 1.226869·P = 8.160 cuts the basic d2, 9.026;
/// // X8.2 is shallower still, so d2 comes out above 6g's 8.994.
/// let c = Command::from_api("verify", r#"{"thread": "M10x1.5-6g", "insert": "full", "final_x": 8.2}"#)?;
/// let out = c.run(&Request::api(Document::Text, Files::Refused))?;
/// assert_eq!(out.outcome, Outcome::OutOfTolerance);
/// assert!(out.document(Document::Text).unwrap_or("").contains("verdict: FAIL"));
/// # Ok::<(), threadcheck::Error>(())
/// ```
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct VerifyArgs {
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    #[allow(missing_docs)]
    pub plan: PlanArgs,
    /// Tool table: which insert each T number of the program holds (TOML: a file on the command
    /// line, its text through the API).
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE.toml", value_parser = Source::path))]
    #[serde(deserialize_with = "super::args::source_text")]
    pub tools: Option<Source>,
    /// Of a program that cuts several threads, the one to take (1-based, in program order, as
    /// `verify` and `passes` number them); `verify` checks every one without it.
    #[cfg_attr(feature = "cli", arg(long, value_name = "N", requires = "program", value_parser = crate::commands::args::operation_number))]
    pub operation: Option<usize>,
    /// Leave form checks (root radius, minor-diameter zone, flank angles) out of the verdict.
    #[cfg_attr(feature = "cli", arg(long))]
    pub gauge_only: bool,
    /// Z of the stock's bottom face, mm: a tapped hole whose drill passes it with its full
    /// diameter is a through hole, whose depth needs no room below the tap (default: the
    /// program's own stock definition, Klartext's BLK FORM, else every hole blind).
    #[cfg_attr(feature = "cli", arg(long, value_name = "Z", allow_hyphen_values = true, value_parser = crate::commands::args::finite))]
    pub stock_bottom: Option<f64>,
    /// Skip the per-pass chip and edge metrics: a faster verdict.
    #[cfg_attr(feature = "cli", arg(long))]
    pub no_pass_metrics: bool,
    /// Write the program with each operation's correction (the word that sets its final
    /// depth, put to mid-tolerance d2) to this file; `-` prints it instead of the report.
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE|-", requires = "program"))]
    #[serde(skip)]
    pub fix: Option<String>,
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    #[allow(missing_docs)]
    pub out: super::args::PictureArgs,
    /// Programs and folders to verify in one run (folders recursively, their files with the
    /// dialects' extensions: .nc .ngc .mpf .spf .min .ssb .sub .tap .cnc .eia .gcode .iso, and
    /// .h files that open a Klartext program), in parallel: one line per operation, then a
    /// summary; exit status the worst.
    #[cfg_attr(feature = "cli", arg(value_name = "PROGRAM|FOLDER", conflicts_with_all = ["program", "final_x", "fix", "operation"]))]
    #[serde(skip)]
    pub programs: Vec<PathBuf>,
    /// With PROGRAM|FOLDER (or one --program): JSON Lines for scripts, one object per program (its verdict and each
    /// operation's), then `{"summary": …}`, to this file or `-` (standard output).
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE|-"))]
    #[serde(skip)]
    pub json_lines: Option<String>,
    /// With PROGRAM|FOLDER (or one --program): SARIF 2.1.0 for code scanning (a result per failing check, at the
    /// operation's line and column; one per unreadable program), to this file or `-`.
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE|-"))]
    #[serde(skip)]
    pub sarif: Option<String>,
    /// With PROGRAM|FOLDER (or one --program): JUnit XML for a CI server's test view (a suite per program, a case
    /// per operation), to this file or `-`.
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE|-"))]
    #[serde(skip)]
    pub junit: Option<String>,
    /// With PROGRAM|FOLDER (or one --program): what standard output shows instead of the lines: `sarif`, `junit` or
    /// `json-lines` (the same as `--sarif -`, `--junit -`, `--json-lines -`).
    #[cfg_attr(feature = "cli", arg(long, value_name = "FORMAT", value_parser = ["text", "sarif", "junit", "json-lines"]))]
    #[serde(skip)]
    pub format: Option<String>,
}

super::args::api_args!(VerifyArgs, shares plan: PlanArgs, reads thread at plan.standard);

impl Job for VerifyArgs {
    const NAME: &'static str = "verify";
    const DOCUMENTS: &'static [Document] = &[
        Document::Json,
        Document::Text,
        Document::Svg,
        Document::Html,
        Document::Fix,
        Document::JsonLines,
        Document::Sarif,
        Document::Junit,
    ];

    fn run(&self, request: &Request) -> Result<Outputs, Error> {
        if !self.programs.is_empty() {
            return self.run_many(request);
        }
        for (given, what) in [
            (self.json_lines.is_some(), "json_lines"),
            (self.sarif.is_some(), "sarif"),
            (self.junit.is_some(), "junit"),
            (self.format.is_some(), "format"),
        ] {
            if !given {
                continue;
            }
            // One program file is a run of one (issue 65: `--program P --format sarif`); a
            // program given as text (the API) is not a file a run's documents can name.
            match &self.plan.program {
                Some(Source::Path(p)) if self.fix.is_none() && self.plan.final_x.is_none() && self.operation.is_none() => {
                    let one = VerifyArgs {
                        programs: vec![p.clone()],
                        plan: PlanArgs { program: None, ..self.plan.clone() },
                        ..self.clone()
                    };
                    return one.run_many(request);
                }
                _ => {
                    return Err(Error::Input(format!(
                        "‹{what}› describes a run of programs: name them as PROGRAM|FOLDER, or one program file with ‹program›"
                    )))
                }
            }
        }
        if self.stock_bottom.is_some() && self.plan.program.is_none() {
            return Err(Error::Input(
                "‹stock_bottom› describes a program's holes: give the program with ‹program›".into(),
            ));
        }
        if self.tools.is_some() && self.plan.program.is_none() {
            return Err(Error::Input(
                "‹tools› names a program's tools: give the program with ‹program›".into(),
            ));
        }
        if self.plan.program.is_none() {
            self.plan.need_thread("verify")?;
        }
        // The program's project file and modeline, read once for the spec and the project.
        let set = self.plan.settings(request.files)?;
        let (mut spec, threads) = self.plan.spec_with(&set, request.files)?;
        spec.gauge_only = self.gauge_only;
        spec.metrics = !self.no_pass_metrics;
        spec.operation = self.operation;
        spec.stock_bottom = self.stock_bottom;
        // The pictures and the JSON's deviation samples are computed with the verification.
        spec.picture = [Document::Svg, Document::Html, Document::Json].into_iter().any(|d| request.wants(d));
        let tools = self.tools.as_ref().map(|t| tool_table(t, request.files)).transpose()?;
        let own_tools = self.project(&mut spec, &set, request.files)?;
        let tools = tools.or(own_tools);
        let mut inputs = self.plan.inputs();
        inputs.extend(self.tools.as_ref().and_then(Source::file));
        if let Some((source, dialect)) = &spec.program {
            return Ok(self
                .run_program(&spec, source, *dialect, &threads, tools.as_ref(), request)?
                .reading(inputs));
        }
        if request.wants(Document::Fix) {
            return Err(Error::Input("‹fix› corrects a program: give it with ‹program›".into()));
        }
        let v = crate::analysis::turn::verify(&spec)?;
        Ok(Outputs::new(
            Outcome::of(v.pass),
            [
                request.render(Document::Json, || pretty(&crate::report::VerifyReport::of(&v)))?,
                request.render(Document::Svg, || Ok(crate::report::verify::verify_svg(&v)))?,
                request.render(Document::Html, || Ok(crate::report::verify::verify_html(&v)))?,
                Some((Document::Text, crate::report::verify_text(&v))),
            ],
        )
        .reading(inputs))
    }

    fn destinations(&self) -> Vec<(Document, Dest)> {
        let mut d = self.out.destinations(Some(&self.fix));
        d.extend(super::Dest::list(
            [
                (Document::JsonLines, &self.json_lines),
                (Document::Sarif, &self.sarif),
                (Document::Junit, &self.junit),
            ],
            [],
        ));
        let to_stdout = match self.format.as_deref() {
            Some("sarif") => Some(Document::Sarif),
            Some("junit") => Some(Document::Junit),
            Some("json-lines") => Some(Document::JsonLines),
            _ => None,
        };
        d.extend(to_stdout.map(|doc| (doc, Dest::Stdout)));
        d
    }
}

/// Whether the file's first 4 KiB hold `BEGIN PGM` (a Klartext program's first block).
fn opens_klartext(path: &std::path::Path) -> bool {
    use std::io::Read;
    let mut head = Vec::new();
    std::fs::File::open(path).and_then(|f| f.take(4096).read_to_end(&mut head)).is_ok()
        && String::from_utf8_lossy(&head).contains("BEGIN PGM")
}

/// The programs of `paths`: a file as named, a folder's files with [`PROGRAM_EXTENSIONS`](crate::gcode::PROGRAM_EXTENSIONS) found
/// recursively (and `.h` files that open a Klartext program), in name order; at most [`MAX_BATCH_PROGRAMS`](crate::ground::bounds::MAX_BATCH_PROGRAMS).
/// Symbolic links to programs and folders are followed and named as linked (a loop is listed
/// once, by the link that closes it, and its line says so); a file reached twice is read once,
/// under the first name. Entries that are not regular files (a FIFO, a device, a socket) are
/// listed and never opened: their line says so.
fn program_files(paths: &[PathBuf]) -> Result<Vec<PathBuf>, Error> {
    let mut out = Vec::new();
    let mut seen = std::collections::HashSet::new();
    for p in paths {
        if p.is_dir() {
            for entry in walkdir::WalkDir::new(p).follow_links(true).sort_by_file_name() {
                let entry = match entry {
                    Ok(e) => e,
                    // A link back to a folder above it: named, never walked again.
                    Err(e) if e.loop_ancestor().is_some() => {
                        if let Some(path) = e.path() {
                            out.push(path.to_path_buf());
                        }
                        continue;
                    }
                    Err(e) => {
                        return Err(Error::File {
                            file: e
                                .path()
                                .map_or_else(|| p.display().to_string(), |q| q.display().to_string()),
                            message: format!("cannot be listed: {e}"),
                        })
                    }
                };
                if entry.file_type().is_dir() {
                    continue;
                }
                let ext = entry.path().extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
                let regular = entry.file_type().is_file();
                // A `.h` file is a Klartext program when it opens one (else a C header, say);
                // only a regular file is opened to see.
                let klartext = ext.as_deref() == Some("h") && (!regular || opens_klartext(entry.path()));
                if !(klartext || ext.is_some_and(|e| crate::gcode::PROGRAM_EXTENSIONS.contains(&e.as_str())))
                {
                    continue;
                }
                let once = std::fs::canonicalize(entry.path()).unwrap_or_else(|_| entry.path().to_path_buf());
                if seen.insert(once) {
                    out.push(entry.into_path());
                }
            }
        } else {
            // A file as named (a missing one is its own error line in the run).
            out.push(p.clone());
        }
        if out.len() > crate::ground::bounds::MAX_BATCH_PROGRAMS {
            return Err(Error::Input(format!(
                "more than {} programs in one run: verify the folders one by one",
                crate::ground::bounds::MAX_BATCH_PROGRAMS
            )));
        }
    }
    Ok(out)
}

/// Why a listed entry of a run is not read: a folder (a link's loop) or anything but a regular
/// file. `None` for a regular file (or one that cannot be looked at: its read says why).
fn not_a_program_file(path: &std::path::Path) -> Option<&'static str> {
    let meta = std::fs::metadata(path).ok()?;
    if meta.is_dir() {
        Some("a link back to a folder it is in (a loop): its programs are read once, under their first name")
    } else if !meta.is_file() {
        Some("not a regular file (a FIFO, a device or a socket is never opened in a run of many)")
    } else {
        None
    }
}

impl VerifyArgs {
    /// `verify P1 P2 FOLDER`: every program verified as `--program` verifies one, in parallel,
    /// a chunk at a time (only the lines are kept); one line per operation and a summary.
    fn run_many(&self, request: &Request) -> Result<Outputs, Error> {
        use crate::report::batch::{BatchProgram, BatchSummary, SummaryLine};
        use rayon::prelude::*;
        for (given, what) in [
            (self.out.svg.is_some(), "svg"),
            (self.out.html.is_some(), "html"),
            (self.out.json.is_some(), "json"),
        ] {
            if given {
                return Err(Error::Input(format!(
                    "‹{what}› is one program's: give it with ‹program›, or ‹json_lines› for a run of many"
                )));
            }
        }
        let files = program_files(&self.programs)?;
        if files.is_empty() {
            return Err(Error::Input(format!(
                "no program in {} (looked for the extensions {}, and .h files that open a Klartext program)",
                self.programs.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", "),
                crate::gcode::PROGRAM_EXTENSIONS.map(|e| format!(".{e}")).join(" ")
            )));
        }
        let tools = self.tools.as_ref().map(|t| tool_table(t, request.files)).transpose()?;
        let lines = request.wants(Document::JsonLines);
        let (mut text, mut jsonl, mut summary) = (String::new(), String::new(), BatchSummary::default());
        // SARIF and JUnit are one document over the whole run: the programs' views are kept
        // (their lines only, never the verifications).
        let keep = request.wants(Document::Sarif) || request.wants(Document::Junit);
        let mut kept = Vec::new();
        let progress = super::progress::Progress::new(request.progress, files.len());
        for chunk in files.chunks(64) {
            let done: Vec<BatchProgram> = chunk
                .par_iter()
                .map(|file| {
                    let p = self.one_of_many(file, tools.as_ref(), request);
                    progress.inc();
                    p
                })
                .collect();
            for p in &done {
                summary.add(p);
                text.push_str(&p.text());
                if lines {
                    jsonl.push_str(&serde_json::to_string(p).map_err(|e| Error::Data(e.to_string()))?);
                    jsonl.push('\n');
                }
            }
            if keep {
                kept.extend(done);
            }
        }
        progress.finish();
        text.push_str(&summary.text());
        if lines {
            jsonl.push_str(
                &serde_json::to_string(&SummaryLine { summary: &summary })
                    .map_err(|e| Error::Data(e.to_string()))?,
            );
            jsonl.push('\n');
        }
        let outcome =
            if summary.unreadable > 0 { Outcome::Unreadable } else { Outcome::of(summary.fail == 0) };
        let mut inputs = files;
        inputs.extend(self.tools.as_ref().and_then(Source::file));
        Ok(Outputs::new(
            outcome,
            [
                Some((Document::Text, text)),
                lines.then_some((Document::JsonLines, jsonl)),
                request.render(Document::Sarif, || {
                    crate::report::batch::sarif_log(&kept, env!("CARGO_PKG_VERSION"), outcome.exit_code())
                })?,
                request.render(Document::Junit, || crate::report::batch::junit_xml(&kept))?,
            ],
        )
        .reading(inputs))
    }

    /// One program of a run (or of the LinuxCNC filter): its view, or the located line that says
    /// why it could not be read. Only the views are kept: no pictures, no per-pass metrics.
    pub(crate) fn one_of_many(
        &self,
        file: &std::path::Path,
        tools: Option<&crate::analysis::tools::ToolTable>,
        request: &Request,
    ) -> crate::report::batch::BatchProgram {
        use crate::report::batch::BatchProgram;
        let shown = crate::ground::fmt::path_name(file);
        if let Some(why) = not_a_program_file(file) {
            return BatchProgram::unreadable(
                &shown,
                format!("error: {}: {why}", crate::ground::error::one_line(&shown)),
                None,
            );
        }
        match self.verify_one(Source::Path(file.to_path_buf()), None, tools, request) {
            Ok((shown, _, pv)) => BatchProgram::of(&shown, &pv),
            Err(e) => {
                let (line, at) = located(&e, &shown);
                BatchProgram::unreadable(&shown, format!("error: {line}"), at)
            }
        }
    }

    /// A program open in an editor (`threadcheck lsp`), its text as the editor has it and `name`
    /// its path (the dialect comes from its extension): the editor's view, with each
    /// correction's word edits as a quick fix.
    pub(crate) fn for_editor(
        &self,
        name: &str,
        text: String,
        tools: Option<&crate::analysis::tools::ToolTable>,
        request: &Request,
    ) -> crate::report::lsp::EditorView {
        use crate::report::lsp::{EditorFix, EditorView};
        // A document saved on this computer finds its subprograms' files as the program does.
        let own = std::path::Path::new(name).parent().filter(|d| d.is_absolute() && d.is_dir());
        let finder = own.map(|d| super::args::sub_finder_in(d, &self.plan.reading.subroutine_path));
        match self.verify_one_finding(Source::Text(text), Some(name.to_string()), tools, request, finder) {
            Ok((shown, _, pv)) => {
                let fixes = pv
                    .operations
                    .iter()
                    .filter_map(|o| match &o.result {
                        // A correction in a subprogram's file is not this document's to edit.
                        crate::analysis::turn::OperationResult::Verified(_)
                            if o.operation.source_file.is_some() =>
                        {
                            None
                        }
                        crate::analysis::turn::OperationResult::Verified(v) => {
                            let c = v.correction.as_ref()?;
                            let edits = correction_edits(c, &shown).ok()?;
                            Some(EditorFix {
                                line: o.operation.source_line,
                                title: format!("threadcheck: {}", crate::report::correction_text(c)),
                                edits,
                            })
                        }
                        crate::analysis::turn::OperationResult::NoCut { .. } => None,
                    })
                    .collect();
                EditorView::of(&pv, fixes)
            }
            Err(e) => {
                let (line, at) = located(&e, name);
                EditorView::unreadable(request.reader.words(&line), at)
            }
        }
    }

    /// One program verified as a run verifies it (no pictures, no per-pass metrics): the name as
    /// shown, its text and every thread it makes, checked.
    fn verify_one(
        &self,
        program: Source,
        name: Option<String>,
        tools: Option<&crate::analysis::tools::ToolTable>,
        request: &Request,
    ) -> Result<(String, String, crate::analysis::program::ProgramVerification), Error> {
        self.verify_one_finding(program, name, tools, request, None)
    }

    /// [`Self::verify_one`] with the finder of its subprograms' files, when not the one its
    /// source gives (an editor's document saved on this computer).
    fn verify_one_finding(
        &self,
        program: Source,
        name: Option<String>,
        tools: Option<&crate::analysis::tools::ToolTable>,
        request: &Request,
        finder: Option<crate::gcode::SubFinder>,
    ) -> Result<(String, String, crate::analysis::program::ProgramVerification), Error> {
        let one = VerifyArgs {
            // An editor's document saved on this computer (its subprograms' files are found)
            // reads its project file as a file does.
            plan: PlanArgs {
                program: Some(program),
                program_name: name,
                saved_document: finder.is_some(),
                ..self.plan.clone()
            },
            programs: Vec::new(),
            json_lines: None,
            sarif: None,
            junit: None,
            format: None,
            ..self.clone()
        };
        let set = one.plan.settings(request.files)?;
        let (mut spec, threads) = one.plan.spec_with(&set, request.files)?;
        spec.gauge_only = self.gauge_only;
        spec.stock_bottom = self.stock_bottom;
        spec.metrics = false;
        spec.picture = false;
        if finder.is_some() {
            spec.reading.sub_files = finder;
        }
        let own_tools = one.project(&mut spec, &set, request.files)?;
        let tools = tools.or(own_tools.as_ref());
        let (source, dialect) = spec.program.clone().ok_or_else(|| Error::Input("no program".into()))?;
        one.verification(&spec, &source, dialect, &threads, tools)
    }

    /// What the program's project file sets beyond `spec` (its notes are `spec`'s): the tool
    /// table it names when none is given (`None` when one is: the given one wins, said).
    fn project(
        &self,
        spec: &mut VerifySpec,
        set: &super::settings::Settings,
        files: super::Files,
    ) -> Result<Option<crate::analysis::tools::ToolTable>, Error> {
        let Some((path, _)) = &set.tools else { return Ok(None) };
        if let Some(t) = &self.tools {
            let given =
                super::settings::Given { tools: Some(super::args::source_words(t)), ..self.plan.given() };
            spec.reading.settings_notes = set.notes(&given);
            return Ok(None);
        }
        Ok(Some(tool_table(&Source::Path(path.clone()), files)?))
    }

    /// One program verified: its name as shown and every thread it makes, checked.
    fn verification(
        &self,
        spec: &VerifySpec,
        source: &ProgramSource,
        dialect: crate::gcode::Dialect,
        threads: &[crate::standards::Designation],
        tools: Option<&crate::analysis::tools::ToolTable>,
    ) -> Result<(String, String, crate::analysis::program::ProgramVerification), Error> {
        let (shown, text) = source.load()?;
        let insert_given = self.plan.insert_given();
        let insert_for = |op: &crate::gcode::Operation| insert_of(op, tools, insert_given);
        // `spec` asks for the pictures only when a document draws them (the program's picture
        // once lost its zone, basic profile, deviation plot and full length).
        let pv = crate::analysis::program::verify_whole(
            spec,
            &text,
            &shown,
            dialect,
            threads,
            &insert_for,
            tools,
        )?;
        Ok((shown, text, pv))
    }

    fn run_program(
        &self,
        spec: &VerifySpec,
        source: &ProgramSource,
        dialect: crate::gcode::Dialect,
        threads: &[crate::standards::Designation],
        tools: Option<&crate::analysis::tools::ToolTable>,
        request: &Request,
    ) -> Result<Outputs, Error> {
        if spec.final_x.is_some() {
            return Err(Error::Input(
                "‹final_x› and ‹program› exclude each other: the program sets the passes".into(),
            ));
        }
        let (shown, text, pv) = self.verification(spec, source, dialect, threads, tools)?;
        Ok(Outputs::new(
            Outcome::of(pv.pass()),
            [
                request.render(Document::Json, || pretty(&crate::report::ProgramReport::of(&pv)))?,
                request.render(Document::Svg, || Ok(crate::report::verify::program_svg(&pv)))?,
                request.render(Document::Html, || Ok(crate::report::verify::program_html(&pv)))?,
                request.render(Document::Fix, || fixed_program(&pv, &text, &shown))?,
                Some((Document::Text, crate::report::program_text(&pv))),
            ],
        ))
    }
}

/// An error's one line, starting with the program's name, and its place in the program when it
/// names one.
fn located(e: &Error, shown: &str) -> (String, Option<(usize, usize)>) {
    let at = match e {
        Error::Program { line, column, .. } => Some((*line, *column)),
        _ => None,
    };
    // One line with control characters escaped (an ESC in a bad token coloured the terminal).
    let line = e.one_line();
    (if line.starts_with(shown) { line } else { format!("{shown}: {line}") }, at)
}

/// The insert of a program's operation: `None` keeps the one given (‹insert›); else the tool
/// table's insert of its T number, or (the third value true) none known, with why: the analysis
/// then assumes the insert the passes' depth is written for.
fn insert_of(
    op: &crate::gcode::Operation,
    tools: Option<&crate::analysis::tools::ToolTable>,
    insert_given: bool,
) -> Option<(InsertChoice, String, bool)> {
    if insert_given {
        return None;
    }
    if let (Some(tt), Some(t)) = (tools, op.tool) {
        if let Some((choice, written)) = tt.insert(t) {
            return Some((
                choice.clone(),
                format!("insert of tool T{t} from {}: {written}", tt.source),
                false,
            ));
        }
    }
    let why = match (op.tool, tools) {
        (Some(t), Some(tt)) => match tt.tool(t) {
            Some((_, written)) => {
                format!("tool T{t} is \"{written}\" in {}, not a threading insert", tt.source)
            }
            None => format!("tool T{t} is not in {}", tt.source),
        },
        (Some(t), None) => {
            format!("the program names tool T{t} but no tool table was given (‹tools›)")
        }
        (None, _) => "the program names no tool".to_string(),
    };
    // The insert assumed is chosen by the analysis from the passes' depth (the one the program's
    // numbers are written for); here only why it is assumed.
    Some((InsertChoice::Full, why, true))
}

/// The program with every operation's correction written in; an operation whose correction
/// is not a plain number in place (an expression, an R-parameter set elsewhere) is an error that
/// says what to change by hand.
fn fixed_program(
    pv: &crate::analysis::program::ProgramVerification,
    text: &str,
    shown: &str,
) -> Result<String, Error> {
    let mut edits = Vec::new();
    for o in &pv.operations {
        let crate::analysis::turn::OperationResult::Verified(v) = &o.result else {
            continue;
        };
        let Some(c) = &v.correction else { continue };
        if let Some(sub) = &o.operation.source_file {
            return Err(Error::Program {
                file: sub.clone(),
                line: c.line,
                column: c.column,
                message: format!(
                    "‹fix› rewrites the program's own file, and this correction is in its subprogram's: {}",
                    crate::report::correction_text(c)
                ),
            });
        }
        edits.extend(correction_edits(c, shown)?);
    }
    crate::gcode::rewrite_words(text, shown, &edits)
}

/// The word edits of one correction (its word, the same in each other start's cycle, and the
/// earlier passes deeper than its new value).
pub(super) fn correction_edits(
    c: &crate::analysis::turn::correction::Correction,
    shown: &str,
) -> Result<Vec<crate::gcode::WordEdit>, Error> {
    let not_plain = |line, column| Error::Program {
        file: shown.to_string(),
        line,
        column,
        message: format!("‹fix› rewrites plain numbers only: {}", crate::report::correction_text(c)),
    };
    let Some(new) = crate::report::correction_replacement(c) else {
        return Err(not_plain(c.line, c.column));
    };
    // The word, the same word in the other starts' cycles, and the earlier passes that cut
    // deeper than the new value: each takes it.
    std::iter::once((c.line, c.column, &c.written, true))
        .chain(c.also.iter().map(|p| (p.line, p.column, &c.written, true)))
        .chain(c.deeper.iter().map(|d| (d.line, d.column, &d.written, d.form.editable())))
        .map(|(line, column, old, editable)| {
            if editable {
                Ok(crate::gcode::WordEdit { line, column, old: old.clone(), new: new.clone() })
            } else {
                Err(not_plain(line, column))
            }
        })
        .collect()
}
