//! The jobs behind the command line, one per command: `main.rs` parses arguments into one of
//! these, runs it and maps the [`Outcome`] to an exit code. A job returns what the command prints,
//! so everything here is usable without the CLI (the Python package runs the same jobs).

use crate::report::{fmt_num, LimitsReport};
use crate::standards::tolerance::{basic_rounded, limits_for, Limit, ThreadLimits};
use crate::standards::{parse_designation, Designation, ParseOptions, ThreadKind};
use crate::Error;
use std::fmt::Write as _;

/// What a job concluded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// The job did its work; for `verify`, the thread is within every limit (exit 0).
    Pass,
    /// `verify` ran and the thread is out of tolerance (exit 1).
    OutOfTolerance,
}

impl Outcome {
    /// The process exit code: 0 pass, 1 out of tolerance (2, errors, is the caller's).
    pub fn exit_code(self) -> i32 {
        match self {
            Outcome::Pass => 0,
            Outcome::OutOfTolerance => 1,
        }
    }
}

/// `threadcheck limits`: the limits of size of a designation.
///
/// ```
/// use threadcheck::{LimitsJob, Outcome};
/// let job = LimitsJob { designation: "M10x1.5-6g".into(), allow_nonstandard: false, json: Some("-".into()), coating: 0.0, coating_limits: Default::default() };
/// let (json, outcome) = job.run()?;
/// let v: serde_json::Value = serde_json::from_str(&json).expect("JSON");
/// assert_eq!(v["external"]["pitch_diameter"]["max"], 8.994); // ISO 965-2
/// assert_eq!(outcome, Outcome::Pass);
/// # Ok::<(), threadcheck::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct LimitsJob {
    /// The designation text.
    pub designation: String,
    /// Accept sizes outside the standard series.
    pub allow_nonstandard: bool,
    /// The JSON: `-` prints it on stdout instead of the table, a path writes it there.
    pub json: Option<String>,
    /// A coating's thickness, mm: the limits before coating (0: the class's own).
    pub coating: f64,
    /// Which limits the class applies to under the coating.
    pub coating_limits: crate::standards::tolerance::CoatingLimits,
}

impl LimitsJob {
    /// Runs the job, returning what to print on stdout.
    pub fn run(&self) -> Result<(String, Outcome), Error> {
        let des =
            parse_designation(&self.designation, ParseOptions { allow_nonstandard: self.allow_nonstandard })?;
        let t = &des.thread;
        let coat = |l: Option<ThreadLimits>| {
            l.map(|l| crate::analysis::verify::coated(l, t, self.coating, self.coating_limits)).transpose()
        };
        let ext = coat(limits_for(&des, ThreadKind::External)?)?;
        let int = coat(limits_for(&des, ThreadKind::Internal)?)?;
        let json_text = self
            .json
            .as_ref()
            .map(|_| pretty(&LimitsReport::new(&des, ext.as_ref(), int.as_ref())))
            .transpose()?;
        let text = limits_table(&des, ext.as_ref(), int.as_ref());
        Ok((route_json(self.json.as_deref(), json_text, text)?, Outcome::Pass))
    }
}

fn limits_table(des: &Designation, ext: Option<&ThreadLimits>, int: Option<&ThreadLimits>) -> String {
    let t = &des.thread;
    let (d, d2, d3, d1, h) = basic_rounded(t);
    let mut s = String::new();
    let hand = if t.hand == crate::Hand::Left { "left-hand" } else { "right-hand" };
    let _ = writeln!(
        s,
        "{}  {}, P = {} mm{}, lead {} mm, {} start{}, {}{}",
        des.text,
        t.form.name(),
        crate::standards::tolerance::round_um(t.pitch),
        if t.form.is_inch() {
            format!(" ({} tpi)", crate::standards::tolerance::round_um(25.4 / t.pitch))
        } else {
            String::new()
        },
        crate::standards::tolerance::round_um(t.lead()),
        t.starts,
        if t.starts == 1 { "" } else { "s" },
        hand,
        if des.nonstandard { " (non-standard size)" } else { "" }
    );
    let _ = writeln!(s, "\nbasic (mm)");
    let _ = writeln!(s, "  {:<34}{d:>9.3}", "major diameter d = D");
    let _ = writeln!(s, "  {:<34}{d2:>9.3}", "pitch diameter d2 = D2");
    let _ = writeln!(s, "  {:<34}{d3:>9.3}", "minor diameter of the bolt d3");
    let _ = writeln!(s, "  {:<34}{d1:>9.3}", "minor diameter of the nut D1");
    let _ = writeln!(s, "  {:<34}{h:>9.4}", "fundamental triangle height H");
    for l in [ext, int].into_iter().flatten() {
        let dev_name = if l.kind == ThreadKind::External { "es" } else { "EI" };
        let head = format!(
            "{} {} ({dev_name} = {} µm)",
            l.kind.name(),
            l.class,
            fmt_num((l.fundamental_deviation_um * 10.0).round() / 10.0)
        );
        let _ = writeln!(s, "\n{head:<36}{:>9} {:>9}", "max", "min");
        // Inch tables (ASME B1.1) print inches: show them beside the mm.
        let inch = matches!(t.form, crate::ThreadForm::Unified | crate::ThreadForm::Acme);
        let row = |s: &mut String, name: &str, lim: &Limit| {
            let _ = write!(
                s,
                "  {name:<34}{:>9} {:>9}",
                crate::report::opt(lim.max, 3),
                crate::report::opt(lim.min, 3)
            );
            if inch {
                let i = |v: Option<f64>| v.map_or_else(|| "—".to_string(), |x| format!("{:.4}", x / 25.4));
                let _ = write!(s, "   {:>7} {:>7} in", i(lim.max), i(lim.min));
            }
            s.push('\n');
        };
        let (maj, minor) = if l.kind == ThreadKind::External {
            ("major diameter d", "minor: d1+es (max) / d3 min (min)")
        } else {
            ("major diameter D", "minor diameter D1")
        };
        if let Some(gp) = &l.gauge_plane {
            let _ = writeln!(
                s,
                "  {:<34}{:>9.3}   at {:.3} mm {}, ±{} turn (±{:.3} mm); taper 1:{}",
                "gauge plane: pitch diameter",
                gp.pitch_diameter,
                gp.distance,
                if l.kind == ThreadKind::External { "from the small end" } else { "(the face)" },
                gp.tolerance_turns,
                gp.tolerance_turns * t.pitch,
                fmt_num(1.0 / gp.taper)
            );
            for n in &l.notes {
                let _ = writeln!(s, "  note: {n}");
            }
            continue;
        }
        row(&mut s, maj, &l.major_diameter);
        row(
            &mut s,
            if l.kind == ThreadKind::External { "pitch diameter d2" } else { "pitch diameter D2" },
            &l.pitch_diameter,
        );
        row(&mut s, minor, &l.minor_diameter);
        if let Some(r) = l.root_radius_min {
            let _ = writeln!(s, "  {:<34}{:>9} {:>9.3}", "root radius R", "", r);
        }
        for n in &l.notes {
            let _ = writeln!(s, "  note: {n}");
        }
    }
    if ext.is_none() && int.is_none() {
        let (e, i) =
            (des.with_example_class(ThreadKind::External), des.with_example_class(ThreadKind::Internal));
        let example = if e == i { e } else { format!("{e} or {i}") };
        let _ = writeln!(s, "\nno class given: add one for limits, e.g. {example}");
    }
    s
}

/// `threadcheck verify`: the text (or JSON) the command prints, and pass or out of tolerance.
///
/// ```
/// use threadcheck::{Outcome, VerifyJob};
/// use threadcheck::{InsertChoice, VerifySpec};
/// let spec = VerifySpec { insert: InsertChoice::Full, final_x: Some(8.2), ..VerifySpec::new("M10x1.5-6g") };
/// let job = VerifyJob { spec, threads: vec!["M10x1.5-6g".into()], insert_given: true, tools: None, svg: None, html: None, json: None, fix: None };
/// let (text, outcome) = job.run()?;
/// // A full-profile insert with its tip on d3 = d − 1.226869·P = 8.160 cuts the basic d2, 9.026;
/// // X8.2 is shallower still, so d2 comes out above 6g's 8.994.
/// assert_eq!(outcome, Outcome::OutOfTolerance);
/// assert!(text.contains("verdict: FAIL"));
/// # Ok::<(), threadcheck::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct VerifyJob {
    /// What to verify.
    pub spec: crate::analysis::verify::VerifySpec,
    /// With a program: one designation for all its operations, or one per operation.
    pub threads: Vec<String>,
    /// The insert was chosen on the command line (else the tool table, else the default).
    pub insert_given: bool,
    /// T numbers → inserts.
    pub tools: Option<crate::analysis::tools::ToolTable>,
    /// Write the SVG cross-section here.
    pub svg: Option<std::path::PathBuf>,
    /// Write the self-contained HTML report here.
    pub html: Option<std::path::PathBuf>,
    /// Write the JSON report here; `-` prints it on stdout instead of the table.
    pub json: Option<String>,
    /// Write the program with each operation's correction applied here (`-`: on stdout,
    /// instead of the text report).
    pub fix: Option<String>,
}

impl VerifyJob {
    /// Runs the job: the report on stdout, files written atomically, pass or out of tolerance.
    pub fn run(&self) -> Result<(String, Outcome), Error> {
        self.run_to(&mut Sink::Disk)
    }

    /// Runs the job with its files going to `sink`.
    pub(crate) fn run_to(&self, sink: &mut Sink) -> Result<(String, Outcome), Error> {
        // The pictures and the JSON's deviation samples are computed with the verification.
        let spec = crate::analysis::verify::VerifySpec {
            picture: self.svg.is_some() || self.html.is_some() || self.json.is_some(),
            ..self.spec.clone()
        };
        if let Some((source, dialect)) = &spec.program {
            return self.run_program(&spec, source, *dialect, sink);
        }
        if self.fix.is_some() {
            return Err(Error::Input("--fix corrects a program: give it with --program".into()));
        }
        let v = crate::analysis::verify::verify(&spec)?;
        let outcome = if v.pass { Outcome::Pass } else { Outcome::OutOfTolerance };
        // Render everything before writing anything, so a failure leaves no file half-done.
        let json_text =
            self.json.as_ref().map(|_| pretty(&crate::report::VerifyReport::of(&v))).transpose()?;
        let svg_text = self.svg.as_ref().map(|_| crate::report::verify::verify_svg(&v));
        let html_text = self.html.as_ref().map(|_| crate::report::verify::verify_html(&v));
        let text = crate::report::verify_text(&v);
        self.write(sink, json_text, svg_text, html_text, None, text, outcome)
    }

    fn run_program(
        &self,
        spec: &crate::analysis::verify::VerifySpec,
        source: &crate::analysis::verify::ProgramSource,
        dialect: crate::gcode::Dialect,
        sink: &mut Sink,
    ) -> Result<(String, Outcome), Error> {
        if spec.final_x.is_some() {
            return Err(Error::Input(
                "--final-x and --program exclude each other: the program sets the passes".into(),
            ));
        }
        let (shown, text) = source.load()?;
        let default = spec.insert.clone();
        let insert_for =
            |op: &crate::gcode::Operation| -> Option<(crate::analysis::verify::InsertChoice, String, bool)> {
                if self.insert_given {
                    return None;
                }
                if let (Some(tt), Some(t)) = (&self.tools, op.tool) {
                    if let Some((choice, written)) = tt.insert(t) {
                        let (choice, written) = (choice, written.to_string());
                        return Some((
                            choice.clone(),
                            format!("insert of tool T{t} from {}: {written}", tt.source),
                            false,
                        ));
                    }
                }
                let why = match (op.tool, &self.tools) {
                    (Some(t), Some(tt)) => match tt.tool(t) {
                        Some((_, written)) => {
                            format!("tool T{t} is \"{written}\" in {}, not a threading insert", tt.source)
                        }
                        None => format!("tool T{t} is not in {}", tt.source),
                    },
                    (Some(t), None) => {
                        format!("the program names tool T{t} but no tool table was given (--tools)")
                    }
                    (None, _) => "the program names no tool".to_string(),
                };
                let what = match &default {
                    crate::analysis::verify::InsertChoice::Full => "a full-profile insert".to_string(),
                    crate::analysis::verify::InsertChoice::Partial { tip_radius } => {
                        format!("a partial-profile insert with a {} mm tip", fmt_num(*tip_radius))
                    }
                    crate::analysis::verify::InsertChoice::File(p) => format!("the insert {}", p.display()),
                    crate::analysis::verify::InsertChoice::Toml { name, .. } => format!("the insert {name}"),
                };
                Some((
                    default.clone(),
                    format!("insert assumed: {what} ({why}; choose with --insert or --tools)"),
                    true,
                ))
            };
        // `spec`, not `self.spec`: the pictures are computed only when the spec asks (the
        // program's picture once lost its zone, basic profile, deviation plot and full length).
        let pv = crate::analysis::verify::verify_program(
            spec,
            &text,
            &shown,
            dialect,
            &self.threads,
            &insert_for,
        )?;
        let outcome = if pv.pass() { Outcome::Pass } else { Outcome::OutOfTolerance };
        let json_text =
            self.json.as_ref().map(|_| pretty(&crate::report::ProgramReport::of(&pv))).transpose()?;
        let svg_text = self.svg.as_ref().map(|_| crate::report::verify::program_svg(&pv));
        let html_text = self.html.as_ref().map(|_| crate::report::verify::program_html(&pv));
        let report = crate::report::program_text(&pv);
        let fixed = self.fix.as_ref().map(|_| fixed_program(&pv, &text, &shown)).transpose()?;
        match (self.fix.as_deref(), fixed) {
            // `--fix -`: the corrected program is what stdout shows.
            (Some("-"), Some(program)) => {
                if self.json.as_deref() == Some("-") {
                    return Err(Error::Input(
                        "--fix - and --json - both want stdout: write one to a file".into(),
                    ));
                }
                self.write(sink, json_text, svg_text, html_text, None, program, outcome)
            }
            (_, fixed) => self.write(sink, json_text, svg_text, html_text, fixed, report, outcome),
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn write(
        &self,
        sink: &mut Sink,
        json_text: Option<String>,
        svg_text: Option<String>,
        html_text: Option<String>,
        fixed: Option<String>,
        text: String,
        outcome: Outcome,
    ) -> Result<(String, Outcome), Error> {
        // The corrected program goes to its file with the others (`--fix -` is shown instead).
        let fix_path = self.fix.as_deref().filter(|f| *f != "-").map(std::path::PathBuf::from);
        let files = [(&self.svg, svg_text), (&self.html, html_text), (&fix_path, fixed)];
        let mut inputs = spec_inputs(&self.spec);
        inputs.extend(self.tools.iter().map(|t| std::path::PathBuf::from(&t.source)));
        Ok((write_outputs(sink, &inputs, &files, self.json.as_deref(), json_text, text)?, outcome))
    }
}

/// The program with every operation's correction written in; an operation whose correction
/// is not a plain number in place (an expression, an R-parameter set elsewhere) is an error that
/// says what to change by hand.
fn fixed_program(
    pv: &crate::analysis::verify::ProgramVerification,
    text: &str,
    shown: &str,
) -> Result<String, Error> {
    let mut edits = Vec::new();
    for o in &pv.operations {
        let crate::analysis::verify::OperationResult::Verified(v) = &o.result else {
            continue;
        };
        let Some(c) = &v.correction else { continue };
        edits.extend(correction_edits(c, shown)?);
    }
    crate::gcode::rewrite_words(text, shown, &edits)
}

/// Where a job's files go: to disk (the command line), or kept in memory by their names (the
/// API and the Python package, which write nothing).
pub(crate) enum Sink {
    /// Written atomically, all or none.
    Disk,
    /// Kept: each output's path as the job was given it, and its bytes.
    Memory(Vec<(std::path::PathBuf, Vec<u8>)>),
}

/// The one output step of the jobs, after everything is rendered: every picture, page and JSON
/// file of the run written together, all or none (so a failure leaves no file half-done and
/// every old output in place); the JSON routed as [`route_json`] does. Returns what to print.
fn write_outputs(
    sink: &mut Sink,
    inputs: &[std::path::PathBuf],
    files: &[(&Option<std::path::PathBuf>, Option<String>)],
    json: Option<&str>,
    json_text: Option<String>,
    text: String,
) -> Result<String, Error> {
    let mut outputs: Vec<(std::path::PathBuf, Vec<u8>)> = Vec::new();
    for (path, t) in files {
        if let (Some(path), Some(t)) = (path, t) {
            outputs.push((path.clone(), t.clone().into_bytes()));
        }
    }
    let shown = match (json, json_text) {
        (Some("-"), Some(t)) => t,
        (Some(p), Some(t)) => {
            outputs.push((std::path::PathBuf::from(p), t.into_bytes()));
            text
        }
        _ => text,
    };
    match sink {
        Sink::Disk => {
            crate::report::output::refuse_inputs(&outputs, inputs)?;
            crate::report::output::write_all_atomic(&outputs)?;
        }
        Sink::Memory(kept) => kept.extend(outputs),
    }
    Ok(shown)
}

/// The files a verification spec reads: its program and its insert.
fn spec_inputs(spec: &crate::analysis::verify::VerifySpec) -> Vec<std::path::PathBuf> {
    let mut v = Vec::new();
    if let Some((crate::analysis::verify::ProgramSource::File(p), _)) = &spec.program {
        v.push(p.clone());
    }
    if let crate::analysis::verify::InsertChoice::File(p) = &spec.insert {
        v.push(p.clone());
    }
    v
}

/// Where `--json` sends the JSON: `-` prints it on stdout instead of the text; a path writes it
/// there (atomically) and the text goes to stdout; without `--json`, the text.
pub(crate) fn route_json(
    json: Option<&str>,
    json_text: Option<String>,
    text: String,
) -> Result<String, Error> {
    match (json, json_text) {
        (Some("-"), Some(t)) => Ok(t),
        (Some(p), Some(t)) => {
            crate::report::output::write_atomic(std::path::Path::new(p), t.as_bytes())?;
            Ok(text)
        }
        _ => Ok(text),
    }
}

fn pretty<T: serde::Serialize>(v: &T) -> Result<String, Error> {
    crate::report::to_json_pretty(v)
}

/// `threadcheck correct`: what was measured on the part, turned into the change to make.
///
/// ```
/// use threadcheck::{CorrectJob, CorrectSpec, InsertChoice, Measured, Outcome, VerifySpec};
/// let spec = CorrectSpec {
///     verify: VerifySpec { insert: InsertChoice::Full, ..VerifySpec::new("M10x1.5-6g") },
///     measured: Some(Measured::PitchDiameter(8.950)),
///     pickup_z: None,
/// };
/// let (text, outcome) = CorrectJob { spec, html: None, json: None, fix: None }.run()?;
/// assert_eq!(outcome, Outcome::Pass); // 8.950 lies within 8.862–8.994
/// assert!(text.contains("IN TOLERANCE"));
/// # Ok::<(), threadcheck::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct CorrectJob {
    /// The thread, its program or plan, and what was measured.
    pub spec: crate::analysis::correct::CorrectSpec,
    /// Write the HTML page here.
    pub html: Option<std::path::PathBuf>,
    /// The JSON: `-` on stdout instead of the text, a path writes it there.
    pub json: Option<String>,
    /// Write the program with the correction applied here (`-`: on stdout).
    pub fix: Option<String>,
}

impl CorrectJob {
    /// Runs the job: in tolerance passes, a needed correction is out of tolerance.
    pub fn run(&self) -> Result<(String, Outcome), Error> {
        self.run_to(&mut Sink::Disk)
    }

    /// Runs the job with its files going to `sink`.
    pub(crate) fn run_to(&self, sink: &mut Sink) -> Result<(String, Outcome), Error> {
        let r = crate::analysis::correct::correct(&self.spec)?;
        let outcome = match r.verdict() {
            crate::analysis::check::Verdict::Pass => Outcome::Pass,
            crate::analysis::check::Verdict::Fail => Outcome::OutOfTolerance,
        };
        let json_text =
            self.json.as_ref().map(|_| pretty(&crate::report::correct::CorrectJson::of(&r))).transpose()?;
        let html_text = self.html.as_ref().map(|_| crate::report::correct::correct_html(&r));
        let text = crate::report::correct::correct_text(&r);
        let fixed = match &self.fix {
            None => None,
            Some(_) => {
                let Some((source, _)) = &self.spec.verify.program else {
                    return Err(Error::Input("--fix corrects a program: give it with --program".into()));
                };
                let (shown, program) = source.load()?;
                let edits = match &r.correction {
                    None => Vec::new(),
                    Some(c) => correction_edits(c, &shown)?,
                };
                Some(crate::gcode::rewrite_words(&program, &shown, &edits)?)
            }
        };
        let (fixed, text) = match (self.fix.as_deref(), fixed) {
            (Some("-"), Some(program)) => {
                if self.json.as_deref() == Some("-") {
                    return Err(Error::Input(
                        "--fix - and --json - both want stdout: write one to a file".into(),
                    ));
                }
                (None, program)
            }
            (_, fixed) => (fixed, text),
        };
        let fix_path = self.fix.as_deref().filter(|f| *f != "-").map(std::path::PathBuf::from);
        let files = [(&self.html, html_text), (&fix_path, fixed)];
        let inputs = spec_inputs(&self.spec.verify);
        Ok((write_outputs(sink, &inputs, &files, self.json.as_deref(), json_text, text)?, outcome))
    }
}

/// The word edits of one correction (its word, the same in each other start's cycle, and the
/// earlier passes deeper than its new value).
fn correction_edits(
    c: &crate::analysis::correction::Correction,
    shown: &str,
) -> Result<Vec<crate::gcode::WordEdit>, Error> {
    let not_plain = |line, column| Error::Program {
        file: shown.to_string(),
        line,
        column,
        message: format!("--fix rewrites plain numbers only: {}", crate::report::correction_text(c)),
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

/// `threadcheck capability`: a program's (or plan's) parts over the machine's and the insert's
/// variation.
///
/// ```
/// use threadcheck::{CapabilityJob, CapabilitySpec, InsertChoice, Outcome, VerifySpec};
/// let mut spec = CapabilitySpec::new(VerifySpec { insert: InsertChoice::Full, ..VerifySpec::new("M10x1.5-6g") });
/// spec.x_sigma = 0.005;
/// spec.samples = 200;
/// let (text, outcome) = CapabilityJob { spec, svg: None, html: None, json: None }.run()?;
/// assert_eq!(outcome, Outcome::Pass);
/// assert!(text.contains("Cpk"));
/// # Ok::<(), threadcheck::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct CapabilityJob {
    /// The thread and the variation.
    pub spec: crate::analysis::capability::CapabilitySpec,
    /// Write the histogram here.
    pub svg: Option<std::path::PathBuf>,
    /// Write the HTML page here.
    pub html: Option<std::path::PathBuf>,
    /// The JSON: `-` on stdout instead of the text, a path writes it there.
    pub json: Option<String>,
}

/// The least pitch-diameter Cpk a capable program keeps (ISO 22514's usual requirement).
pub const CAPABLE_CPK: f64 = 1.33;

impl CapabilityJob {
    /// Runs the job: pass when the pitch diameter's Cpk reaches `CAPABLE_CPK`, 1.33 (or, without
    /// variation, when every sampled part passes).
    pub fn run(&self) -> Result<(String, Outcome), Error> {
        self.run_to(&mut Sink::Disk)
    }

    /// Runs the job with its files going to `sink`.
    pub(crate) fn run_to(&self, sink: &mut Sink) -> Result<(String, Outcome), Error> {
        let r = crate::analysis::capability::capability(&self.spec)?;
        let d2 = r.sizes.iter().find(|s| s.feature == crate::analysis::check::CheckFeature::PitchDiameter);
        let capable = match d2.and_then(|d| d.cpk) {
            Some(cpk) => cpk >= CAPABLE_CPK,
            None => r.pass_share == 1.0,
        };
        let outcome = if capable { Outcome::Pass } else { Outcome::OutOfTolerance };
        let json_text = self
            .json
            .as_ref()
            .map(|_| pretty(&crate::report::capability::CapabilityJson::of(&r)))
            .transpose()?;
        let svg_text = self.svg.as_ref().map(|_| crate::report::capability::capability_svg(&r));
        let html_text = self.html.as_ref().map(|_| crate::report::capability::capability_html(&r));
        let text = crate::report::capability::capability_text(&r);
        let files = [(&self.svg, svg_text), (&self.html, html_text)];
        let inputs = spec_inputs(&self.spec.verify);
        Ok((write_outputs(sink, &inputs, &files, self.json.as_deref(), json_text, text)?, outcome))
    }
}

/// `threadcheck fit`: a bolt and a nut assembled.
#[derive(Clone, Debug)]
pub struct FitJob {
    /// The pair.
    pub spec: crate::analysis::fit::FitSpec,
    /// Write the SVG of the pair here.
    pub svg: Option<std::path::PathBuf>,
    /// Write the JSON here; `-` prints it on stdout instead of the text.
    pub json: Option<String>,
}

impl FitJob {
    /// Runs the job: exit 0 when the pair screws together, 1 when it does not.
    pub fn run(&self) -> Result<(String, Outcome), Error> {
        self.run_to(&mut Sink::Disk)
    }

    /// Runs the job with its files going to `sink`.
    pub(crate) fn run_to(&self, sink: &mut Sink) -> Result<(String, Outcome), Error> {
        let r = crate::analysis::fit::fit(&self.spec)?;
        let outcome = if r.fits { Outcome::Pass } else { Outcome::OutOfTolerance };
        let json_text =
            self.json.as_ref().map(|_| pretty(&crate::report::fit::FitJson::of(&r))).transpose()?;
        let svg_text = self.svg.as_ref().map(|_| crate::report::fit::svg(&r));
        let text = crate::report::fit::text(&r);
        let inputs: Vec<std::path::PathBuf> = [&self.spec.bolt, &self.spec.nut]
            .iter()
            .flat_map(|side| {
                let program = side.program.as_ref().map(|(_, name, _)| std::path::PathBuf::from(name));
                let insert = match &side.insert {
                    crate::analysis::verify::InsertChoice::File(p) => Some(p.clone()),
                    crate::analysis::verify::InsertChoice::Full
                    | crate::analysis::verify::InsertChoice::Partial { .. }
                    | crate::analysis::verify::InsertChoice::Toml { .. } => None,
                };
                program.into_iter().chain(insert)
            })
            .collect();
        Ok((
            write_outputs(sink, &inputs, &[(&self.svg, svg_text)], self.json.as_deref(), json_text, text)?,
            outcome,
        ))
    }
}

/// `threadcheck passes`: the expanded pass plan.
///
/// ```
/// use threadcheck::PassesJob;
/// use threadcheck::{Dialect, VerifySpec};
/// // A G92 box cycle: one pass per X word.
/// let program = "G0 X12 Z3\nG92 X9.4 Z-15 F1.5\nX9.0\nX8.6\nX8.2\nG0 X50\nM30\n";
/// let spec = VerifySpec::new("").with_program_text("box.nc", program, Dialect::Fanuc);
/// let (json, _) = PassesJob { spec, json: Some("-".into()) }.run()?;
/// let v: serde_json::Value = serde_json::from_str(&json).expect("JSON");
/// let xs: Vec<f64> = v["passes"].as_array().expect("passes").iter().map(|p| p["x_end"].as_f64().unwrap_or(0.0)).collect();
/// assert_eq!(xs, [9.4, 9.0, 8.6, 8.2]);
/// # Ok::<(), threadcheck::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct PassesJob {
    /// The plan, as for verify (the final X is solved the same way when not given).
    pub spec: crate::analysis::verify::VerifySpec,
    /// The JSON: `-` prints it on stdout instead of the table, a path writes it there.
    pub json: Option<String>,
}

impl PassesJob {
    /// Runs the job: a program is read and expanded; a generated plan is laid out as `verify`
    /// would (solving the final X when it is not given).
    pub fn run(&self) -> Result<(String, Outcome), Error> {
        self.spec.validate()?;
        let mut operations = None;
        let mut program_notes = None;
        let (thread, passes, header) = match (&self.spec.program, self.spec.designation.is_empty()) {
            (Some((source, dialect)), no_thread) => {
                let (shown, text) = source.load()?;
                let prog = crate::gcode::read_program_with(&text, &shown, *dialect, self.spec.reading)?;
                let thread = if no_thread {
                    None
                } else {
                    let r = crate::analysis::verify::resolve(&self.spec)?;
                    Some((r.designation, r.kind, r.limits.class))
                };
                let leads: Vec<String> = prog.operations.iter().map(|o| fmt_num(o.lead())).collect();
                let mut header = format!(
                    "{shown} ({}): {} operation{}, {} passes, lead {} mm, {} other blocks read for position{}\n",
                    dialect.name(),
                    prog.operations.len(),
                    if prog.operations.len() == 1 { "" } else { "s" },
                    prog.passes.len(),
                    leads.join(" / "),
                    prog.skipped_blocks,
                    crate::report::read_past_text(prog.read_past_blocks),
                );
                for n in &prog.notes {
                    header.push_str(&format!("note: {n}\n"));
                }
                operations = Some(prog.operations.clone());
                program_notes = Some((prog.notes.clone(), prog.read_past_blocks));
                (thread, prog.passes, header)
            }
            (None, _) if self.spec.final_x.is_some() => {
                // With the final X given, the plan is laid out without cutting it.
                let r = crate::analysis::verify::resolve(&self.spec)?;
                let x = self.spec.final_x.unwrap_or_default();
                let passes = r.plan(x).generate()?;
                let header = format!(
                    "{} {}: {} passes, blank X{:.4}, final X{x:.4}\n",
                    r.designation.text,
                    r.kind.name(),
                    passes.len(),
                    r.blank
                );
                (Some((r.designation, r.kind, r.limits.class)), passes, header)
            }
            (None, _) => {
                let v = crate::analysis::verify::verify(&self.spec)?;
                let header = format!(
                    "{} {}: {} passes, blank X{:.4}, final X{:.4}\n",
                    v.designation.text,
                    v.kind.name(),
                    v.passes.len(),
                    v.blank_diameter,
                    v.final_x
                );
                (Some((v.designation, v.kind, v.limits.class)), v.passes, header)
            }
        };
        let json_text = if self.json.is_some() {
            let thread = thread.as_ref().map(|(d, k, c)| crate::report::ThreadReport::new(d, *k, c));
            Some(pretty(&crate::report::PassesReport::new(
                thread,
                &passes,
                operations.as_deref(),
                program_notes.as_ref().map(|(n, r)| (n.as_slice(), *r)),
            ))?)
        } else {
            None
        };
        let text = {
            let mut s = header;
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
            match &operations {
                Some(ops) => {
                    for op in ops {
                        let _ = writeln!(
                            s,
                            "\noperation {}: {} at line {}{}, lead {} mm, {} passes",
                            op.index,
                            op.cycle,
                            op.source_line,
                            op.tool.map_or(String::new(), |t| format!(", tool T{t}")),
                            fmt_num(op.lead()),
                            op.passes.len()
                        );
                        for n in &op.notes {
                            let _ = writeln!(s, "  note: {n}");
                        }
                        s.push_str(head);
                        for p in &op.passes {
                            row(&mut s, p);
                        }
                    }
                }
                None => {
                    s.push('\n');
                    s.push_str(head);
                    for p in &passes {
                        row(&mut s, p);
                    }
                }
            }
            s
        };
        Ok((route_json(self.json.as_deref(), json_text, text)?, Outcome::Pass))
    }
}

/// `threadcheck compare`: the same thread with every infeed strategy.
#[derive(Clone, Debug)]
pub struct CompareJob {
    /// Thread, insert and plan (infeed and schedule are varied).
    pub spec: crate::analysis::verify::VerifySpec,
    /// Modified-flank angles, degrees.
    pub modified: Vec<f64>,
    /// The infeed or schedule the user chose to compare alone.
    pub choice: crate::analysis::compare::CompareChoice,
    /// The JSON: `-` prints it on stdout instead of the table, a path writes it there.
    pub json: Option<String>,
    /// Write the table as Markdown here.
    pub markdown: Option<std::path::PathBuf>,
    /// Write the self-contained HTML report (the table and every strategy's picture) here.
    pub html: Option<std::path::PathBuf>,
}

impl CompareJob {
    /// Runs the job.
    pub fn run(&self) -> Result<(String, Outcome), Error> {
        self.run_to(&mut Sink::Disk)
    }

    /// Runs the job with its files going to `sink`.
    pub(crate) fn run_to(&self, sink: &mut Sink) -> Result<(String, Outcome), Error> {
        let spec = crate::analysis::verify::VerifySpec { picture: self.html.is_some(), ..self.spec.clone() };
        let c = crate::analysis::compare::compare(&spec, &self.modified, &self.choice)?;
        let md = self.markdown.as_ref().map(|_| crate::report::compare::markdown_report(&c));
        let json_text =
            self.json.as_ref().map(|_| pretty(&crate::report::compare::CompareReport::of(&c))).transpose()?;
        let html = self.html.as_ref().map(|_| crate::report::compare::compare_html(&c));
        let files = [(&self.markdown, md), (&self.html, html)];
        Ok((
            write_outputs(
                sink,
                &spec_inputs(&spec),
                &files,
                self.json.as_deref(),
                json_text,
                crate::report::compare::text(&c),
            )?,
            Outcome::Pass,
        ))
    }
}

/// `threadcheck sweep`: the catalogue in parallel.
#[derive(Clone, Debug)]
pub struct SweepJob {
    /// What to sweep.
    pub spec: crate::analysis::catalogue::CatalogueSpec,
    /// JSON Lines, one verify report per case: `-` prints them on stdout (the summary line then
    /// goes to stderr), a path writes them there.
    pub json: Option<String>,
    /// Write every case's blank, insert placements and measured d2 here (JSON Lines), for an
    /// outside baseline to redo the cut.
    pub export_placements: Option<std::path::PathBuf>,
}

impl SweepJob {
    /// Runs the job: what to print on stdout, what on stderr (the summary line with `--json -`),
    /// and the outcome: out of tolerance when any case fails.
    pub fn run(&self) -> Result<(String, String, Outcome), Error> {
        let start = std::time::Instant::now();
        let cases = crate::analysis::catalogue::cases(&self.spec)?;
        if cases.is_empty() {
            return Err(Error::Input("the catalogue selection is empty".into()));
        }
        // Each case becomes its lines as soon as it is verified, in parallel: no verification is
        // kept, so memory stays at one case per thread.
        let lines =
            crate::analysis::catalogue::run_map(&cases, |c, r| -> Result<(bool, String, String), Error> {
                let mut out = String::new();
                let mut export = String::new();
                let ok = match r {
                    Ok(v) => {
                        if self.json.is_some() {
                            out.push_str(&crate::report::to_json_line(&crate::report::VerifyReport::of(&v))?);
                        } else if !v.pass {
                            let failed: Vec<String> = v
                                .checks
                                .iter()
                                .filter(|k| !k.ok && k.kind.counts(v.gauge_only))
                                .map(|k| {
                                    if k.deviation_um != 0.0 {
                                        format!("{} {:+.1} µm", k.feature, k.deviation_um)
                                    } else {
                                        k.feature.to_string()
                                    }
                                })
                                .collect();
                            let _ = writeln!(out, "FAIL {}: {}", c.label, failed.join(", "));
                        }
                        if self.export_placements.is_some() {
                            export.push_str(&placements_line(&c.label, &c.spec, &v)?);
                        }
                        v.pass
                    }
                    Err(e) => {
                        if self.json.is_some() {
                            out.push_str(&crate::report::to_json_line(&crate::report::CaseError {
                                case: &c.label,
                                error: e.to_string(),
                            })?);
                        } else {
                            let _ = writeln!(out, "ERROR {}: {e}", c.label);
                        }
                        false
                    }
                };
                Ok((ok, out, export))
            });
        let (mut pass, mut fail) = (0usize, 0usize);
        let mut out = String::new();
        let mut export = String::new();
        for l in lines {
            let (ok, o, e) = l?;
            if ok {
                pass += 1;
            } else {
                fail += 1;
            }
            out.push_str(&o);
            export.push_str(&e);
        }
        if let Some(p) = &self.export_placements {
            crate::report::output::write_atomic(p, export.as_bytes())?;
        }
        let summary = format!(
            "{} cases, {pass} pass, {fail} fail, {:.3} s\n",
            cases.len(),
            start.elapsed().as_secs_f64()
        );
        // Exit 1 when any case fails, as verify does.
        let outcome = if fail > 0 { Outcome::OutOfTolerance } else { Outcome::Pass };
        match self.json.as_deref() {
            Some("-") => Ok((out, summary, outcome)),
            Some(path) => {
                crate::report::output::write_atomic(std::path::Path::new(path), out.as_bytes())?;
                Ok((summary, String::new(), outcome))
            }
            None => Ok((out + &summary, String::new(), outcome)),
        }
    }
}

fn placements_line(
    label: &str,
    spec: &crate::analysis::verify::VerifySpec,
    v: &crate::analysis::verify::Verification,
) -> Result<String, Error> {
    let t = &v.designation.thread;
    let setup = crate::geometry::sweep::SweepSetup {
        kind: v.kind,
        insert: &v.insert,
        blank_diameter: v.blank_diameter,
        pitch: t.pitch,
    };
    let window = crate::geometry::sweep::Window::around(v.z_ref, t.pitch, 4.0);
    let (blank, rings) = crate::geometry::sweep::placements(&setup, &v.passes, window)?;
    // threadcheck's own time for the same work on the same placements (sweep + pitch
    // diameter), best of five, so the baseline can state a ratio measured in one run.
    let ms = crate::geometry::measure::MeasureSetup {
        thread: t,
        kind: v.kind,
        mmc_pitch_diameter: None,
        mmc_major_diameter: None,
        extras: false,
    };
    let mut best = f64::INFINITY;
    for _ in 0..5 {
        let start = std::time::Instant::now();
        let s = crate::geometry::sweep::sweep(
            &setup,
            &v.passes,
            window,
            crate::geometry::boolean::UnionStrategy::Envelope,
        )?;
        let m = crate::geometry::measure::measure(&ms, &s.section.profile(), v.z_ref)?;
        std::hint::black_box(m.pitch_diameter);
        best = best.min(start.elapsed().as_secs_f64());
    }
    // And the whole verify of the case (designation, limits, plan, sweep, measure with the
    // three-wire M and the GO clearance, checks), best of five.
    let mut whole = f64::INFINITY;
    for _ in 0..5 {
        let start = std::time::Instant::now();
        std::hint::black_box(crate::analysis::verify::verify(spec)?.pass);
        whole = whole.min(start.elapsed().as_secs_f64());
    }
    let ring = |r: &[crate::Point]| r.iter().map(|p| [p.z, p.r]).collect::<Vec<_>>();
    crate::report::to_json_line(&crate::report::PlacementsLine {
        verify_seconds: whole,
        case: label,
        kind: v.kind.name(),
        pitch: t.pitch,
        z_ref: v.z_ref,
        blank: ring(&blank),
        placements: rings.iter().map(|r| ring(r)).collect(),
        pitch_diameter: v.measurement.pitch_diameter,
        threadcheck_seconds: best,
    })
}

/// `threadcheck thread-mill`: the thread a thread-milling program leaves.
#[derive(Clone, Debug)]
pub struct ThreadMillJob {
    /// The program, the thread and the cutter.
    pub spec: crate::analysis::threadmill::ThreadMillSpec,
    /// Write the axial section's SVG here.
    pub svg: Option<std::path::PathBuf>,
    /// Write the self-contained HTML page here.
    pub html: Option<std::path::PathBuf>,
    /// The JSON: `-` prints it on stdout instead of the text, a path writes it there.
    pub json: Option<String>,
}

impl ThreadMillJob {
    /// Runs the job: pass when the milled thread is within every limit and the lead is right.
    pub fn run(&self) -> Result<(String, Outcome), Error> {
        self.run_to(&mut Sink::Disk)
    }

    /// Runs the job with its files going to `sink`.
    pub(crate) fn run_to(&self, sink: &mut Sink) -> Result<(String, Outcome), Error> {
        let r = crate::analysis::threadmill::thread_mill(&self.spec)?;
        let outcome = if r.pass { Outcome::Pass } else { Outcome::OutOfTolerance };
        let json_text = self
            .json
            .as_ref()
            .map(|_| pretty(&crate::report::threadmill::ThreadMillJson::of(&r)))
            .transpose()?;
        let svg_text = self.svg.as_ref().map(|_| crate::report::threadmill::threadmill_svg(&r));
        let html_text = self.html.as_ref().map(|_| crate::report::threadmill::threadmill_html(&r));
        let inputs = [std::path::PathBuf::from(&self.spec.program.1)];
        let text = crate::report::threadmill::text(&r);
        let files = [(&self.svg, svg_text), (&self.html, html_text)];
        Ok((write_outputs(sink, &inputs, &files, self.json.as_deref(), json_text, text)?, outcome))
    }
}

/// `threadcheck tap`: a program's tapping cycles against their taps and drills.
#[derive(Clone, Debug)]
pub struct TapJob {
    /// The program and its tool table.
    pub spec: crate::analysis::tapping::TapSpec,
    /// Write the tapped holes' sections (SVG) here.
    pub svg: Option<std::path::PathBuf>,
    /// Write the self-contained HTML page here.
    pub html: Option<std::path::PathBuf>,
    /// The JSON: `-` prints it on stdout instead of the text, a path writes it there.
    pub json: Option<String>,
}

impl TapJob {
    /// Runs the job: pass when every tapping cycle passes every check.
    pub fn run(&self) -> Result<(String, Outcome), Error> {
        self.run_to(&mut Sink::Disk)
    }

    /// Runs the job with its files going to `sink`.
    pub(crate) fn run_to(&self, sink: &mut Sink) -> Result<(String, Outcome), Error> {
        let r = crate::analysis::tapping::tapping(&self.spec)?;
        let outcome = if r.pass { Outcome::Pass } else { Outcome::OutOfTolerance };
        let json_text = self.json.as_ref().map(|_| pretty(&r)).transpose()?;
        let svg_text = self.svg.as_ref().map(|_| crate::report::tapping::tap_svg(&r));
        let html_text = self.html.as_ref().map(|_| crate::report::tapping::tap_html(&r));
        let inputs = [std::path::PathBuf::from(&self.spec.program.1)];
        let text = crate::report::tapping::text(&r);
        let files = [(&self.svg, svg_text), (&self.html, html_text)];
        Ok((write_outputs(sink, &inputs, &files, self.json.as_deref(), json_text, text)?, outcome))
    }
}

/// `threadcheck mill`: a milling program's cutter against a target curve.
#[derive(Clone, Debug)]
pub struct MillJob {
    /// What to check.
    pub spec: crate::analysis::mill::MillSpec,
    /// Write the SVG of the worst level here.
    pub svg: Option<std::path::PathBuf>,
    /// The JSON: `-` prints it on stdout instead of the text, a path writes it there.
    pub json: Option<String>,
}

impl MillJob {
    /// Runs the job: pass when the gouge and the leftover are within the tolerance.
    pub fn run(&self) -> Result<(String, Outcome), Error> {
        self.run_to(&mut Sink::Disk)
    }

    /// Runs the job with its files going to `sink`.
    pub(crate) fn run_to(&self, sink: &mut Sink) -> Result<(String, Outcome), Error> {
        let r = crate::analysis::mill::mill(&self.spec)?;
        let svg_text = self.svg.as_ref().map(|_| crate::report::mill::mill_svg(&r));
        let json_text = self.json.as_ref().map(|_| pretty(&r)).transpose()?;
        let outcome = if r.verdict == crate::analysis::check::Verdict::Pass {
            Outcome::Pass
        } else {
            Outcome::OutOfTolerance
        };
        let text = crate::report::mill::text(&r);
        let inputs = [
            std::path::PathBuf::from(&self.spec.program.1),
            std::path::PathBuf::from(&self.spec.target.source),
        ];
        Ok((
            write_outputs(sink, &inputs, &[(&self.svg, svg_text)], self.json.as_deref(), json_text, text)?,
            outcome,
        ))
    }
}

/// `threadcheck report infeed-comparison`: every strategy compared on the report's threads with
/// a full- and a partial-profile insert, the page and its pictures written together.
#[derive(Clone, Debug)]
pub struct InfeedReportJob {
    /// The folder to write `infeed-comparison.md` and its pictures into.
    pub out: std::path::PathBuf,
}

impl InfeedReportJob {
    /// Runs the comparisons, renders the page and writes it with its pictures. Returns the
    /// Markdown.
    pub fn run(&self) -> Result<String, Error> {
        use crate::analysis::compare::{compare, REPORT_THREADS};
        use crate::analysis::verify::{InsertChoice, VerifySpec};
        let inserts = [
            ("full-profile", InsertChoice::Full),
            ("partial-profile r0.04", InsertChoice::Partial { tip_radius: 0.04 }),
        ];
        let mut runs = Vec::new();
        for d in REPORT_THREADS {
            for (iname, choice) in &inserts {
                let spec = VerifySpec { insert: choice.clone(), picture: true, ..VerifySpec::new(d) };
                runs.push((d, *iname, compare(&spec, &[29.5, 27.0], &Default::default())?));
            }
        }
        let sections: Vec<crate::report::compare::InfeedSection<'_>> = runs
            .iter()
            .map(|(thread, insert, comparison)| crate::report::compare::InfeedSection {
                thread,
                insert,
                comparison,
            })
            .collect();
        let (md, pictures) = crate::report::compare::infeed_comparison_page(&sections);
        let mut files: Vec<(std::path::PathBuf, Vec<u8>)> =
            pictures.into_iter().map(|(name, svg)| (self.out.join(name), svg.into_bytes())).collect();
        files.push((self.out.join("infeed-comparison.md"), md.clone().into_bytes()));
        crate::report::output::write_all_atomic(&files)?;
        Ok(md)
    }
}
