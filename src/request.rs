//! One door for the API (`threadcheck serve`) and the Python package: a command's arguments as
//! one JSON object whose keys are the Python functions' keyword arguments, run as the command
//! line runs it, the answer one document (the JSON `--json -` prints, the text, the SVG, the HTML
//! page or the corrected program) and the outcome.
//!
//! The keys and their types are read here; the rules between them are the jobs' own
//! ([`VerifySpec::validate`] and the computations), so the command line, the API and Python
//! refuse the same input with the same line. Nothing is written to disk, and with
//! [`Files::Refused`] (the server) nothing is read from it either: programs, inserts, tool tables,
//! machine profiles and targets arrive as text.

use crate::analysis::verify::{InsertChoice, ProgramSource, VerifySpec};
use crate::jobs::{
    CapabilityJob, CompareJob, CorrectJob, FitJob, LimitsJob, MillJob, Outcome, PassesJob, Sink, VerifyJob,
};
use crate::Error;
use serde_json::{Map, Value};
use std::path::PathBuf;

/// A command the door runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command {
    /// `verify`.
    Verify,
    /// `passes`.
    Passes,
    /// `limits`.
    Limits,
    /// `compare`.
    Compare,
    /// `fit`.
    Fit,
    /// `correct`.
    Correct,
    /// `capability`.
    Capability,
    /// `mill`.
    Mill,
    /// `tap`.
    Tap,
    /// `thread-mill`.
    ThreadMill,
}

impl Command {
    /// Every command, in the order the documentation lists them.
    pub const ALL: [Command; 10] = [
        Command::Verify,
        Command::Passes,
        Command::Limits,
        Command::Compare,
        Command::Fit,
        Command::Correct,
        Command::Capability,
        Command::Mill,
        Command::Tap,
        Command::ThreadMill,
    ];

    /// The command's name, as the command line spells it.
    pub fn name(self) -> &'static str {
        match self {
            Command::Verify => "verify",
            Command::Passes => "passes",
            Command::Limits => "limits",
            Command::Compare => "compare",
            Command::Fit => "fit",
            Command::Correct => "correct",
            Command::Capability => "capability",
            Command::Mill => "mill",
            Command::Tap => "tap",
            Command::ThreadMill => "thread-mill",
        }
    }

    /// The keys the command takes.
    pub fn keys(self) -> Vec<&'static str> {
        const PLAN: &[&str] = &[
            "thread",
            "program",
            "program_name",
            "dialect",
            "insert",
            "insert_toml",
            "internal",
            "allow_nonstandard",
            "infeed",
            "schedule",
            "depths",
            "passes",
            "first_depth",
            "min_depth",
            "finish",
            "spring",
            "taper",
            "chamfer",
            "coating",
            "coating_limits",
            "engagement",
            "final_x",
            "blank_diameter",
            "units",
            "default_units",
            "main",
            "linuxcnc_release",
            "gcode_system",
        ];
        let own: &[&str] = match self {
            Command::Verify => {
                &["tools", "machine", "clearance_angle", "gauge_only", "no_pass_metrics", "operation"]
            }
            Command::Passes => &[],
            Command::Compare => &["modified"],
            Command::Correct => &[
                "machine",
                "clearance_angle",
                "measured_m",
                "wire",
                "measured_d2",
                "gauge",
                "pickup_z",
                "operation",
            ],
            Command::Capability => {
                &["gauge_only", "x_sigma", "tip_radius_tol", "wear_per_part", "samples", "seed", "operation"]
            }
            Command::Limits => {
                return vec!["thread", "designation", "allow_nonstandard", "coating", "coating_limits"]
            }
            Command::Fit => {
                return vec![
                    "thread",
                    "allow_nonstandard",
                    "bolt_program",
                    "bolt_dialect",
                    "bolt_final_x",
                    "bolt_insert",
                    "nut_program",
                    "nut_dialect",
                    "nut_final_x",
                    "nut_insert",
                ]
            }
            Command::Mill => {
                return vec![
                    "program",
                    "program_name",
                    "target",
                    "tool_diameter",
                    "dialect",
                    "tolerance",
                    "n_order",
                ]
            }
            Command::ThreadMill => {
                return vec![
                    "program",
                    "program_name",
                    "dialect",
                    "thread",
                    "allow_nonstandard",
                    "cutter_diameter",
                    "cutter_angle",
                    "cutter_tip_radius",
                    "cutter_rows",
                    "cutter_row_pitch",
                    "blank_diameter",
                    "comp_radius",
                ]
            }
            Command::Tap => {
                return vec![
                    "program",
                    "program_name",
                    "dialect",
                    "tools",
                    "allow_nonstandard",
                    "default_units",
                    "gcode_system",
                ]
            }
        };
        PLAN.iter().chain(own).copied().collect()
    }

    /// The documents the command gives.
    pub fn documents(self) -> &'static [Document] {
        use Document::*;
        match self {
            Command::Verify => &[Json, Text, Svg, Html, Fix],
            Command::Correct => &[Json, Text, Html, Fix],
            Command::Capability => &[Json, Text, Svg, Html],
            Command::Compare => &[Json, Text, Html],
            Command::Fit | Command::Mill => &[Json, Text, Svg],
            Command::Passes | Command::Limits => &[Json, Text],
            Command::Tap | Command::ThreadMill => &[Json, Text, Svg, Html],
        }
    }
}

impl std::str::FromStr for Command {
    type Err = Error;

    fn from_str(s: &str) -> Result<Command, Error> {
        Command::ALL.into_iter().find(|c| c.name() == s).ok_or_else(|| {
            let names: Vec<&str> = Command::ALL.iter().map(|c| c.name()).collect();
            Error::Input(format!("unknown command '{s}': expected {}", names.join(", ")))
        })
    }
}

/// What a run answers with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Document {
    /// What `--json -` prints.
    Json,
    /// What the command prints without `--json`.
    Text,
    /// The picture `--svg` writes.
    Svg,
    /// The page `--html` writes.
    Html,
    /// The program with its correction, as `--fix` writes it.
    Fix,
}

impl Document {
    /// The document's name (`json`, `text`, `svg`, `html`, `fix`).
    pub fn name(self) -> &'static str {
        match self {
            Document::Json => "json",
            Document::Text => "text",
            Document::Svg => "svg",
            Document::Html => "html",
            Document::Fix => "fix",
        }
    }

    /// Its media type.
    pub fn media_type(self) -> &'static str {
        match self {
            Document::Json => "application/json",
            Document::Text | Document::Fix => "text/plain; charset=utf-8",
            Document::Svg => "image/svg+xml",
            Document::Html => "text/html; charset=utf-8",
        }
    }
}

impl std::str::FromStr for Document {
    type Err = Error;

    fn from_str(s: &str) -> Result<Document, Error> {
        [Document::Json, Document::Text, Document::Svg, Document::Html, Document::Fix]
            .into_iter()
            .find(|d| d.name() == s)
            .ok_or_else(|| {
                Error::Input(format!("unknown document '{s}': expected json, text, svg, html or fix"))
            })
    }
}

/// Whether a run may read files named in its arguments.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Files {
    /// The caller's own files (the Python package): an insert, tool table or machine profile
    /// may be a path.
    Allowed,
    /// Nothing is read from disk (the server): files arrive as text.
    Refused,
}

/// A run's answer: the document and the outcome (the exit code's 0 or 1).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Answer {
    /// The document's text.
    pub body: String,
    /// What the run concluded.
    pub outcome: Outcome,
}

/// Runs `command` on the JSON object `args` and answers with `document`.
///
/// ```
/// use threadcheck::{run_request, Command, Document, Files, Outcome};
/// let args = r#"{"thread": "M10x1.5-6g", "insert": "full"}"#;
/// let a = run_request(Command::Verify, Document::Json, args, Files::Refused)?;
/// assert_eq!(a.outcome, Outcome::Pass);
/// let v: serde_json::Value = serde_json::from_str(&a.body).expect("JSON");
/// assert_eq!(v["verdict"], "pass");
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn run_request(command: Command, document: Document, args: &str, files: Files) -> Result<Answer, Error> {
    if !command.documents().contains(&document) {
        let names: Vec<&str> = command.documents().iter().map(|d| d.name()).collect();
        return Err(Error::Input(format!(
            "{} gives no {} document: it gives {}",
            command.name(),
            document.name(),
            names.join(", ")
        )));
    }
    let value: Value = serde_json::from_str(args)
        .map_err(|e| Error::Input(format!("the arguments are not a JSON object: {e}")))?;
    let Value::Object(map) = value else {
        return Err(Error::Input("the arguments must be a JSON object of keyword arguments".into()));
    };
    let keys = command.keys();
    for k in map.keys() {
        if !keys.contains(&k.as_str()) {
            return Err(Error::Input(format!(
                "{} takes no argument '{k}'; it takes {}",
                command.name(),
                keys.join(", ")
            )));
        }
    }
    let a = Args { map, files, command };
    let want = |d: Document| (document == d).then(|| PathBuf::from(d.name()));
    let json = (document == Document::Json).then(|| "-".to_string());
    let mut sink = Sink::Memory(Vec::new());
    let (shown, outcome) = match command {
        Command::Verify => {
            let threads = a.threads()?;
            if threads.is_empty() {
                return Err(Error::Input("verify needs a thread with a class, e.g. M10x1.5-6g".into()));
            }
            let mut spec = a.plan(&threads)?;
            spec.gauge_only = a.flag("gauge_only")?;
            spec.metrics = !a.flag("no_pass_metrics")?;
            spec.machine = a.machine()?;
            spec.clearance_angle = a.num("clearance_angle")?;
            let tools = a.tools()?;
            if document == Document::Fix && spec.program.is_none() {
                return Err(Error::Input("fix corrects a program: give its text as program".into()));
            }
            let fix = (document == Document::Fix).then(|| "fix".to_string());
            let job = VerifyJob {
                spec,
                insert_given: a.has("insert") || a.has("insert_toml"),
                threads,
                tools,
                svg: want(Document::Svg),
                html: want(Document::Html),
                json,
                fix,
            };
            job.run_to(&mut sink)?
        }
        Command::Passes => {
            let threads = a.threads()?;
            if threads.is_empty() && !a.has("program") {
                return Err(Error::Input("passes needs a thread (e.g. M10x1.5-6g) or a program".into()));
            }
            PassesJob { spec: a.plan(&threads)?, json }.run()?
        }
        Command::Limits => {
            let designation = match (a.text("designation")?, a.threads()?.as_slice()) {
                (Some(d), []) => d,
                (None, [t]) => t.clone(),
                (Some(_), [_, ..]) => {
                    return Err(Error::Input("give the designation once: designation or thread".into()))
                }
                _ => return Err(Error::Input("limits needs a designation, e.g. M10x1.5-6g".into())),
            };
            LimitsJob {
                designation,
                allow_nonstandard: a.flag("allow_nonstandard")?,
                json,
                coating: a.num("coating")?.unwrap_or(0.0),
                coating_limits: a.coating_limits()?,
            }
            .run()?
        }
        Command::Compare => {
            let threads = a.one_thread("compare")?;
            let spec = a.plan(&threads)?;
            let modified = match a.numbers("modified")? {
                Some(m) => m,
                None => {
                    let des = crate::standards::parse_designation(
                        &spec.designation,
                        crate::standards::ParseOptions { allow_nonstandard: spec.allow_nonstandard },
                    )?;
                    let half = 0.5 * des.thread.form.flank_angle();
                    vec![half - 0.5, half - 3.0]
                }
            };
            if a.has("units") {
                return Err(Error::Input(
                    "compare's table is in mm: units gives inches in verify's text and pictures".into(),
                ));
            }
            let choice = crate::analysis::compare::CompareChoice {
                infeed: a.text("infeed")?.map(|s| s.parse()).transpose()?,
                schedule: a.schedule()?,
            };
            CompareJob { spec, modified, choice, json, markdown: None, html: want(Document::Html) }
                .run_to(&mut sink)?
        }
        Command::Fit => {
            let thread = a.one_thread("fit")?.remove(0);
            let side = |who: &str| -> Result<crate::analysis::fit::FitSide, Error> {
                let program = a.text(&format!("{who}_program"))?;
                let final_x = a.num(&format!("{who}_final_x"))?;
                if program.is_some() && final_x.is_some() {
                    return Err(Error::Input(format!(
                        "{who}_program and {who}_final_x exclude each other: the program sets the passes"
                    )));
                }
                let dialect = a.text(&format!("{who}_dialect"))?.unwrap_or_else(|| "fanuc".into()).parse()?;
                let insert = a
                    .insert_word(&format!("{who}_insert"))?
                    .unwrap_or(InsertChoice::Partial { tip_radius: 0.04 });
                Ok(crate::analysis::fit::FitSide {
                    insert,
                    final_x,
                    program: program.map(|t| (t, format!("<{who} program>"), dialect)),
                })
            };
            let spec = crate::analysis::fit::FitSpec {
                thread,
                allow_nonstandard: a.flag("allow_nonstandard")?,
                bolt: side("bolt")?,
                nut: side("nut")?,
            };
            FitJob { spec, svg: want(Document::Svg), json }.run_to(&mut sink)?
        }
        Command::Correct => {
            let threads = a.one_thread("correct")?;
            let mut verify = a.plan(&threads)?;
            verify.machine = a.machine()?;
            verify.clearance_angle = a.num("clearance_angle")?;
            let measured =
                match (a.num("measured_m")?, a.num("wire")?, a.num("measured_d2")?, a.text("gauge")?) {
                    (Some(m), Some(wire), None, None) => {
                        Some(crate::analysis::correct::Measured::OverWires { m, wire })
                    }
                    (Some(_), None, _, _) | (None, Some(_), _, _) => {
                        return Err(Error::Input("measured_m and wire go together".into()))
                    }
                    (None, None, Some(d2), None) => {
                        Some(crate::analysis::correct::Measured::PitchDiameter(d2))
                    }
                    (None, None, None, Some(g)) => {
                        Some(crate::analysis::correct::Measured::Gauge(g.parse()?))
                    }
                    (None, None, None, None) => None,
                    _ => {
                        return Err(Error::Input(
                            "give one measurement: measured_m with wire, measured_d2 or gauge".into(),
                        ))
                    }
                };
            if document == Document::Fix && verify.program.is_none() {
                return Err(Error::Input("fix corrects a program: give its text as program".into()));
            }
            let spec =
                crate::analysis::correct::CorrectSpec { verify, measured, pickup_z: a.num("pickup_z")? };
            let fix = (document == Document::Fix).then(|| "fix".to_string());
            CorrectJob { spec, html: want(Document::Html), json, fix }.run_to(&mut sink)?
        }
        Command::Capability => {
            let threads = a.one_thread("capability")?;
            let mut verify = a.plan(&threads)?;
            verify.gauge_only = a.flag("gauge_only")?;
            let mut spec = crate::analysis::capability::CapabilitySpec::new(verify);
            spec.x_sigma = a.num("x_sigma")?.unwrap_or(0.0);
            spec.tip_radius_tol = a.num("tip_radius_tol")?.unwrap_or(0.0);
            spec.wear_per_part = a.num("wear_per_part")?.unwrap_or(0.0);
            if let Some(n) = a.count("samples")? {
                spec.samples = n;
            }
            if let Some(s) = a.whole("seed")? {
                spec.seed = s;
            }
            CapabilityJob { spec, svg: want(Document::Svg), html: want(Document::Html), json }
                .run_to(&mut sink)?
        }
        Command::ThreadMill => {
            let program = a
                .text("program")?
                .ok_or_else(|| Error::Input("thread-mill needs program (its text)".into()))?;
            let name = a.program_name()?;
            let (dialect, _) = a.dialect(&name)?;
            let designation = a.one_thread("thread-mill")?.remove(0);
            let rows = match a.num("cutter_rows")? {
                None => 1,
                Some(r) if r.fract() == 0.0 && (1.0..=200.0).contains(&r) => r as u32,
                Some(r) => {
                    return Err(Error::Input(format!("cutter_rows {r}: a whole number from 1 to 200")))
                }
            };
            let cutter = Some(
                crate::geometry::helix::Cutter::single_form(
                    a.num("cutter_diameter")?
                        .ok_or_else(|| Error::Input("thread-mill needs cutter_diameter (mm)".into()))?,
                    a.num("cutter_angle")?.unwrap_or(60.0),
                    a.num("cutter_tip_radius")?.unwrap_or(0.0),
                )
                .with_rows(rows, a.num("cutter_row_pitch")?)?,
            );
            let spec = crate::analysis::threadmill::ThreadMillSpec {
                program: (program, name),
                dialect,
                designation,
                allow_nonstandard: a.flag("allow_nonstandard")?,
                cutter,
                tools: None,
                blank_diameter: a.num("blank_diameter")?,
                comp_radius: a.num("comp_radius")?,
            };
            crate::jobs::ThreadMillJob { spec, svg: want(Document::Svg), html: want(Document::Html), json }
                .run_to(&mut sink)?
        }
        Command::Tap => {
            let program =
                a.text("program")?.ok_or_else(|| Error::Input("tap needs program (its text)".into()))?;
            let name = a.program_name()?;
            let (dialect, from) = a.dialect(&name)?;
            let mut reading = crate::gcode::ReadOptions { dialect_from: from, ..Default::default() };
            reading.default_units = a.text("default_units")?.map(|u| u.parse()).transpose()?;
            if let Some(g) = a.text("gcode_system")? {
                reading.gcode_system = g.parse()?;
            }
            let text = a
                .text("tools")?
                .ok_or_else(|| Error::Input("tap needs tools (the tool table's TOML text)".into()))?;
            let tools =
                crate::analysis::tools::ToolTable::from_toml(&text, "<tools>", std::path::Path::new("."))?;
            if let Some((t, written)) = tools.file_entry().filter(|_| a.files == Files::Refused) {
                return Err(Error::Input(format!(
                    "tools: T{t} = '{written}' names an insert file, and the server reads none"
                )));
            }
            let spec = crate::analysis::tapping::TapSpec {
                program: (program, name),
                dialect,
                reading,
                tools,
                allow_nonstandard: a.flag("allow_nonstandard")?,
            };
            crate::jobs::TapJob { spec, svg: want(Document::Svg), html: want(Document::Html), json }
                .run_to(&mut sink)?
        }
        Command::Mill => {
            let program =
                a.text("program")?.ok_or_else(|| Error::Input("mill needs program (its text)".into()))?;
            let target =
                a.text("target")?.ok_or_else(|| Error::Input("mill needs target (its TOML text)".into()))?;
            let tool_diameter = a
                .num("tool_diameter")?
                .ok_or_else(|| Error::Input("mill needs tool_diameter (mm)".into()))?;
            let name = a.program_name()?;
            // As every command: the dialect given, else the program name's extension's.
            let (dialect, _) = a.dialect(&name)?;
            let spec = crate::analysis::mill::MillSpec {
                program: (program, name),
                dialect,
                n_order: a.flag("n_order")?,
                tool_diameter,
                target: crate::analysis::mill::Target::from_toml(&target, "<target>")?,
                tolerance: a.num("tolerance")?.unwrap_or(0.01),
            };
            MillJob { spec, svg: want(Document::Svg), json }.run_to(&mut sink)?
        }
    };
    let body = match document {
        Document::Json | Document::Text => shown,
        Document::Svg | Document::Html | Document::Fix => {
            let Sink::Memory(kept) = sink else { unreachable!("the sink is in memory") };
            let name = PathBuf::from(document.name());
            let bytes = kept.into_iter().find(|(p, _)| *p == name).map(|(_, b)| b).ok_or_else(|| {
                Error::Input(format!(
                    "{} made no {} document for this input",
                    command.name(),
                    document.name()
                ))
            })?;
            String::from_utf8(bytes).map_err(|_| Error::Data("a document is not UTF-8".into()))?
        }
    };
    Ok(Answer { body, outcome })
}

/// The arguments of one run, read key by key with the key named in every message.
struct Args {
    map: Map<String, Value>,
    files: Files,
    command: Command,
}

impl Args {
    fn has(&self, key: &str) -> bool {
        self.map.get(key).is_some_and(|v| !v.is_null())
    }

    fn get(&self, key: &str) -> Option<&Value> {
        self.map.get(key).filter(|v| !v.is_null())
    }

    fn wrong(&self, key: &str, expected: &str, v: &Value) -> Error {
        let got = match v {
            Value::Null => "null",
            Value::Bool(_) => "a boolean",
            Value::Number(_) => "a number",
            Value::String(_) => "a string",
            Value::Array(_) => "a list",
            Value::Object(_) => "an object",
        };
        Error::Input(format!("{}: {key} must be {expected}, not {got}", self.command.name()))
    }

    /// `coating_limits`: `before` (the default) or `after`.
    fn coating_limits(&self) -> Result<crate::standards::tolerance::CoatingLimits, Error> {
        self.text("coating_limits")?.map_or(Ok(Default::default()), |t| t.parse())
    }

    fn text(&self, key: &str) -> Result<Option<String>, Error> {
        match self.get(key) {
            None => Ok(None),
            Some(Value::String(s)) => Ok(Some(s.clone())),
            Some(v) => Err(self.wrong(key, "a string", v)),
        }
    }

    fn flag(&self, key: &str) -> Result<bool, Error> {
        match self.get(key) {
            None => Ok(false),
            Some(Value::Bool(b)) => Ok(*b),
            Some(v) => Err(self.wrong(key, "true or false", v)),
        }
    }

    fn num(&self, key: &str) -> Result<Option<f64>, Error> {
        match self.get(key) {
            None => Ok(None),
            Some(Value::Number(n)) => match n.as_f64().filter(|x| x.is_finite()) {
                Some(x) => Ok(Some(x)),
                None => Err(Error::Input(format!("{}: {key} is not a finite number", self.command.name()))),
            },
            Some(v) => Err(self.wrong(key, "a number", v)),
        }
    }

    fn whole(&self, key: &str) -> Result<Option<u64>, Error> {
        match self.get(key) {
            None => Ok(None),
            Some(Value::Number(n)) => n.as_u64().map(Some).ok_or_else(|| {
                Error::Input(format!("{}: {key} must be a whole number from 0", self.command.name()))
            }),
            Some(v) => Err(self.wrong(key, "a whole number", v)),
        }
    }

    /// `operation`: the number (from 1) of the program's operation to take.
    fn operation(&self) -> Result<Option<usize>, Error> {
        match self.whole("operation")? {
            Some(0) => Err(Error::Input("operation is an operation's number, from 1".into())),
            n => Ok(n.map(|n| n as usize)),
        }
    }

    fn count(&self, key: &str) -> Result<Option<usize>, Error> {
        Ok(self.whole(key)?.map(|n| usize::try_from(n).unwrap_or(usize::MAX)))
    }

    fn numbers(&self, key: &str) -> Result<Option<Vec<f64>>, Error> {
        match self.get(key) {
            None => Ok(None),
            Some(Value::Array(items)) => items
                .iter()
                .map(|v| match v.as_f64().filter(|x| x.is_finite()) {
                    Some(x) => Ok(x),
                    None => Err(self.wrong(key, "a list of finite numbers", v)),
                })
                .collect::<Result<Vec<f64>, Error>>()
                .map(Some),
            Some(v) => Err(self.wrong(key, "a list of numbers", v)),
        }
    }

    /// `thread`: one designation, or a list of them (one per threading operation).
    fn threads(&self) -> Result<Vec<String>, Error> {
        match self.get("thread") {
            None => Ok(Vec::new()),
            Some(Value::String(s)) => Ok(vec![s.clone()]),
            Some(Value::Array(items)) => items
                .iter()
                .map(|v| {
                    v.as_str().map(str::to_string).ok_or_else(|| self.wrong("thread", "a list of strings", v))
                })
                .collect(),
            Some(v) => Err(self.wrong("thread", "a designation or a list of them", v)),
        }
    }

    fn one_thread(&self, what: &str) -> Result<Vec<String>, Error> {
        let t = self.threads()?;
        match t.len() {
            0 => Err(Error::Input(format!("{what} needs a thread with a class, e.g. M10x1.5-6g"))),
            1 => Ok(t),
            _ => Err(Error::Input(format!("{what} takes one thread"))),
        }
    }

    /// The dialect given, else the one the program's name's extension names, else Fanuc; and
    /// how it was chosen (the notes say so when it was not given).
    fn dialect(&self, name: &str) -> Result<(crate::gcode::Dialect, crate::gcode::DialectFrom), Error> {
        Ok(match self.text("dialect")? {
            Some(d) => (d.parse()?, crate::gcode::DialectFrom::Given),
            None => match crate::gcode::Dialect::by_extension(std::path::Path::new(name)) {
                Some(d) => (d, crate::gcode::DialectFrom::Extension),
                None => (crate::gcode::Dialect::Fanuc, crate::gcode::DialectFrom::Default),
            },
        })
    }

    fn program_name(&self) -> Result<String, Error> {
        Ok(self.text("program_name")?.unwrap_or_else(|| "<program>".into()))
    }

    /// `insert` (full, partial, partial:R; a path where files are allowed) or `insert_toml`.
    fn insert(&self) -> Result<Option<InsertChoice>, Error> {
        match (self.insert_word("insert")?, self.text("insert_toml")?) {
            (Some(_), Some(_)) => Err(Error::Input("insert and insert_toml exclude each other".into())),
            (Some(i), None) => Ok(Some(i)),
            (None, Some(text)) => Ok(Some(InsertChoice::Toml { name: "<insert>".into(), text })),
            (None, None) => Ok(None),
        }
    }

    fn insert_word(&self, key: &str) -> Result<Option<InsertChoice>, Error> {
        let Some(word) = self.text(key)? else { return Ok(None) };
        match word.parse::<InsertChoice>()? {
            InsertChoice::File(p) if self.files == Files::Refused => Err(Error::Input(format!(
                "{key} '{}' names a file, and the server reads none: send its TOML text as insert_toml",
                p.display()
            ))),
            c => Ok(Some(c)),
        }
    }

    fn schedule(&self) -> Result<Option<crate::toolpath::passes::Schedule>, Error> {
        match (self.text("schedule")?, self.numbers("depths")?) {
            (Some(_), Some(_)) => Err(Error::Input("schedule and depths exclude each other".into())),
            (Some(s), None) => Ok(Some(s.parse()?)),
            (None, Some(d)) => Ok(Some(crate::toolpath::passes::Schedule::Explicit(d))),
            (None, None) => Ok(None),
        }
    }

    fn tools(&self) -> Result<Option<crate::analysis::tools::ToolTable>, Error> {
        let Some(text) = self.text("tools")? else { return Ok(None) };
        if !self.has("program") {
            return Err(Error::Input("tools is a program's tool table: give the program too".into()));
        }
        let table =
            crate::analysis::tools::ToolTable::from_toml(&text, "<tools>", std::path::Path::new("."))?;
        if self.files == Files::Refused {
            if let Some((t, written)) = table.file_entry() {
                return Err(Error::Input(format!(
                    "tools: T{t} = '{written}' names an insert file, and the server reads none: use full, partial or partial:R"
                )));
            }
        }
        Ok(Some(table))
    }

    fn machine(&self) -> Result<Option<crate::analysis::process::MachineProfile>, Error> {
        let Some(text) = self.text("machine")? else { return Ok(None) };
        if !self.has("program") {
            return Err(Error::Input("machine checks a program: give the program too".into()));
        }
        if text == "training-lathe" {
            return crate::analysis::process::MachineProfile::read(&text).map(Some);
        }
        crate::analysis::process::MachineProfile::from_toml(&text, "<machine>").map(Some)
    }

    /// The plan and program arguments of verify, passes, compare, correct and capability.
    fn plan(&self, threads: &[String]) -> Result<VerifySpec, Error> {
        let first = threads.first().map_or("", String::as_str);
        if threads.len() > 1 && !self.has("program") {
            return Err(Error::Input(
                "several threads are given: only a program with several threads takes one per operation"
                    .into(),
            ));
        }
        let mut s = VerifySpec::new(first);
        s.internal = self.flag("internal")?;
        s.allow_nonstandard = self.flag("allow_nonstandard")?;
        if let Some(i) = self.insert()? {
            s.insert = i;
        }
        s.infeed = self.text("infeed")?.map(|t| t.parse()).transpose()?;
        if let Some(sch) = self.schedule()? {
            s.schedule = sch;
        }
        s.passes = self.count("passes")?;
        s.first_depth = self.num("first_depth")?;
        if s.passes.is_some() && s.first_depth.is_some() {
            return Err(Error::Input("passes and first_depth exclude each other".into()));
        }
        s.min_depth = self.num("min_depth")?.unwrap_or(0.0);
        s.finish = self.num("finish")?.unwrap_or(0.0);
        s.spring = self.count("spring")?.unwrap_or(0);
        s.taper = self.num("taper")?.unwrap_or(0.0);
        s.chamfer_leads = self.num("chamfer")?.unwrap_or(0.0);
        s.coating = self.num("coating")?.unwrap_or(0.0);
        s.coating_limits = self.coating_limits()?;
        s.engagement = self.num("engagement")?;
        s.final_x = self.num("final_x")?;
        s.blank_diameter = self.num("blank_diameter")?;
        // Only the commands whose keys list `operation` take it.
        s.operation = self.operation()?;
        s.units = match self.text("units")?.as_deref() {
            None => VerifySpec::default_units(first, s.allow_nonstandard),
            Some("mm") => crate::analysis::verify::Units::Mm,
            Some("inch") => crate::analysis::verify::Units::Inch,
            Some(u) => return Err(Error::Input(format!("units '{u}': expected mm or inch"))),
        };
        if let Some(text) = self.text("program")? {
            let name = self.program_name()?;
            if self.files == Files::Allowed && !text.contains('\n') && std::path::Path::new(&text).is_file() {
                return Err(Error::Input(format!(
                    "program '{}' is a file's path: pass the program's text (for example open(path).read())",
                    text
                )));
            }
            let (dialect, from) = self.dialect(&name)?;
            s.program = Some((ProgramSource::text(name, text), dialect));
            s.reading.dialect_from = from;
        } else {
            for key in ["dialect", "default_units", "main", "program_name", "gcode_system"] {
                if self.has(key) {
                    return Err(Error::Input(format!(
                        "{key} describes a program: give the program's text too"
                    )));
                }
            }
        }
        s.reading.default_units = self.text("default_units")?.map(|u| u.parse()).transpose()?;
        s.reading.main = self
            .text("main")?
            .map(|m| {
                let digits = m.strip_prefix(['O', 'o']).unwrap_or(&m);
                digits.parse::<u32>().ok().filter(|_| !digits.starts_with('+')).ok_or_else(|| {
                    Error::Input(format!("main '{m}' is not an O-program number such as O3101"))
                })
            })
            .transpose()?;
        if let Some(r) = self.text("linuxcnc_release")? {
            s.reading.linuxcnc = r.parse()?;
        }
        if let Some(g) = self.text("gcode_system")? {
            s.reading.gcode_system = g.parse()?;
        }
        s.validate()?;
        Ok(s)
    }
}
