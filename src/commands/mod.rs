//! The commands, one file each: the command's arguments as one struct, read by clap on the
//! command line (the `cli` feature) and by serde from the API's and Python's JSON, so that a
//! flag's name, a JSON key and a Python keyword are one field; and the command's job, which
//! computes (below, in `analysis/`), renders the documents asked for (in `report/`) and returns
//! them typed. One writer ([`deliver`]) writes what the command line asked, all or none; the API
//! and Python take the one document they asked for.
//!
//! Adding a command is its computation in `analysis/`, its renderings in `report/`, its file
//! here and one line in [`commands!`].
//!
//! ```
//! use threadcheck::{Command, Document, Files, Request};
//! let c = Command::from_api("limits", r#"{"thread": "M10x1.5-6g"}"#)?;
//! let out = c.run(&Request::api(Document::Json, Files::Refused))?;
//! let v: serde_json::Value = serde_json::from_str(out.document(Document::Json).unwrap_or("")).expect("JSON");
//! assert_eq!(v["external"]["pitch_diameter"]["max"], 8.994); // ISO 965-2
//! # Ok::<(), threadcheck::Error>(())
//! ```

// The fields' doc comments are the command line's help, where `partial[:TIP_RADIUS]` is the
// usage's own notation, not a link.
#![allow(rustdoc::broken_intra_doc_links)]

pub(crate) mod args;
mod capability;
mod compare;
mod correct;
mod filter;
mod fit;
mod limits;
mod mill;
mod passes;
mod progress;
mod report;
pub(crate) mod settings;
mod sweep;
mod tap;
mod thread_mill;
mod verify;
mod write;

pub use args::{JsonArg, ONumber, PlanArgs, ProgramArgs, ReadingArgs, Source, StandardArgs};
pub use capability::{CapabilityArgs, CAPABLE_CPK};
pub use compare::CompareArgs;
pub use correct::CorrectArgs;
pub use filter::{filter, FilterArgs, Filtered};
pub use fit::FitArgs;
pub use limits::LimitsArgs;
pub use mill::MillArgs;
pub use passes::PassesArgs;
pub use report::{ReportArgs, ReportName};
pub use sweep::{FormSet, InsertSet, SeriesSet, SweepArgs};
pub use tap::TapArgs;
pub use thread_mill::ThreadMillArgs;
pub use verify::VerifyArgs;
pub use write::{deliver, Dest, Shown};

use crate::Error;
use serde_json::{Map, Value};
use std::path::PathBuf;

/// What a run concluded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// The job did its work; for `verify`, the thread is within every limit (exit 0).
    Pass,
    /// The thread (or the capability, the fit, the milled curve) is out of tolerance (exit 1).
    OutOfTolerance,
    /// A run of many programs met one it could not read (each named in the output; exit 2, the
    /// worst, though every other program was verified).
    Unreadable,
}

impl Outcome {
    /// The process exit code: 0 pass, 1 out of tolerance (2, errors, is the caller's).
    pub fn exit_code(self) -> i32 {
        match self {
            Outcome::Pass => 0,
            Outcome::OutOfTolerance => 1,
            Outcome::Unreadable => 2,
        }
    }

    /// Pass when `pass`.
    pub fn of(pass: bool) -> Outcome {
        if pass {
            Outcome::Pass
        } else {
            Outcome::OutOfTolerance
        }
    }
}

/// A document a command gives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Document {
    /// The JSON report (`--json`).
    Json,
    /// What the command prints without `--json`.
    Text,
    /// The picture (`--svg`).
    Svg,
    /// The self-contained page (`--html`).
    Html,
    /// The program with its correction written in (`--fix`).
    Fix,
    /// The comparison's table as Markdown (`compare --markdown`).
    Markdown,
    /// One JSON object per program of a run of many, then a summary (`verify --json-lines`).
    JsonLines,
    /// A run of many as SARIF 2.1.0: a result per failing check (`verify --sarif`).
    Sarif,
    /// A run of many as JUnit XML: a test case per operation (`verify --junit`).
    Junit,
}

impl Document {
    /// Whether this is a run of many programs' document (JSON Lines, SARIF, JUnit XML): made by
    /// `verify FOLDER` on the command line, never by the API, which verifies one program.
    pub fn of_many(self) -> bool {
        matches!(self, Document::JsonLines | Document::Sarif | Document::Junit)
    }

    /// Every document, in the order the documentation lists them.
    pub const ALL: [Document; 9] = [
        Document::Json,
        Document::Text,
        Document::Svg,
        Document::Html,
        Document::Fix,
        Document::Markdown,
        Document::JsonLines,
        Document::Sarif,
        Document::Junit,
    ];

    /// The document's name (`json`, `text`, `svg`, `html`, `fix`, `markdown`).
    pub fn name(self) -> &'static str {
        match self {
            Document::Json => "json",
            Document::Text => "text",
            Document::Svg => "svg",
            Document::Html => "html",
            Document::Fix => "fix",
            Document::Markdown => "markdown",
            Document::JsonLines => "json-lines",
            Document::Sarif => "sarif",
            Document::Junit => "junit",
        }
    }

    /// Its media type.
    pub fn media_type(self) -> &'static str {
        match self {
            Document::Json => "application/json",
            Document::JsonLines => "application/jsonl",
            Document::Sarif => "application/sarif+json",
            Document::Junit => "application/xml",
            Document::Text | Document::Fix => "text/plain; charset=utf-8",
            Document::Markdown => "text/markdown; charset=utf-8",
            Document::Svg => "image/svg+xml",
            Document::Html => "text/html; charset=utf-8",
        }
    }
}

impl std::str::FromStr for Document {
    type Err = Error;

    fn from_str(s: &str) -> Result<Document, Error> {
        Document::ALL.into_iter().find(|d| d.name() == s).ok_or_else(|| {
            let names: Vec<&str> = Document::ALL.iter().map(|d| d.name()).collect();
            Error::Input(format!("unknown document '{s}': expected {}", names.join(", ")))
        })
    }
}

/// Whether a run may read files named in its arguments.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Files {
    /// The caller's own files (the command line, the Python package): an insert, tool table or
    /// machine profile may be a path.
    Allowed,
    /// Nothing is read from disk (the server): files arrive as text.
    Refused,
}

/// What a run is asked for: the documents to render and whether files may be read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Request {
    /// The documents to render (the text is always rendered).
    pub wanted: Vec<Document>,
    /// Whether files named in the arguments may be read.
    pub files: Files,
    /// Who reads the messages: how they name arguments.
    pub reader: crate::Audience,
    /// Whether a run of many draws its progress on standard error (the command line sets it
    /// when that is a terminal; the bar appears after a second).
    pub progress: bool,
}

impl Request {
    /// One document for the API or Python.
    pub fn api(document: Document, files: Files) -> Request {
        Request { wanted: vec![document], files, reader: crate::Audience::Api, progress: false }
    }

    /// Whether `d` is asked for.
    pub fn wants(&self, d: Document) -> bool {
        self.wanted.contains(&d)
    }

    /// `render()` when `d` is asked for.
    pub(crate) fn render<F: FnOnce() -> Result<String, Error>>(
        &self,
        d: Document,
        render: F,
    ) -> Result<Option<(Document, String)>, Error> {
        if self.wants(d) {
            Ok(Some((d, render()?)))
        } else {
            Ok(None)
        }
    }
}

/// A run's result: its documents, the files it read (which no output may replace), files of
/// its own to write with the documents, and the outcome.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Outputs {
    /// What the run concluded.
    pub outcome: Outcome,
    /// The documents rendered: the text always, the others as asked.
    pub documents: Vec<(Document, String)>,
    /// The files the run read.
    pub inputs: Vec<PathBuf>,
    /// Files the command writes besides its documents (a report's pictures, sweep's placements).
    pub files: Vec<(PathBuf, Vec<u8>)>,
    /// A line for standard error when standard output carries the JSON (sweep's summary).
    pub aside: Option<String>,
}

impl Outputs {
    /// The outputs of a job that rendered `documents`.
    pub(crate) fn new(
        outcome: Outcome,
        documents: impl IntoIterator<Item = Option<(Document, String)>>,
    ) -> Self {
        Outputs {
            outcome,
            documents: documents.into_iter().flatten().collect(),
            inputs: Vec::new(),
            files: Vec::new(),
            aside: None,
        }
    }

    /// With the files the run read.
    pub(crate) fn reading(mut self, inputs: impl IntoIterator<Item = PathBuf>) -> Self {
        self.inputs.extend(inputs);
        self
    }

    /// The document `d`, when rendered.
    pub fn document(&self, d: Document) -> Option<&str> {
        self.documents.iter().find(|(k, _)| *k == d).map(|(_, t)| t.as_str())
    }
}

/// The JSON of a report, as every command writes it.
pub(crate) fn pretty<T: serde::Serialize>(v: &T) -> Result<String, Error> {
    crate::report::to_json_pretty(v)
}

/// A command's job.
pub trait Job {
    /// The command's name, as the command line and the API spell it.
    const NAME: &'static str;
    /// The documents it gives.
    const DOCUMENTS: &'static [Document];
    /// Runs it, rendering what `request` asks for.
    fn run(&self, request: &Request) -> Result<Outputs, Error>;
    /// Where the command line's flags send each document (the text to standard output unless
    /// another document takes it).
    fn destinations(&self) -> Vec<(Document, Dest)>;
}

/// The arguments of a command the API and Python run: read from a JSON object whose keys are
/// the struct's fields and those of the arguments it shares with other commands
/// ([`Shared`](ApiArgs::Shared)), which clap flattens into it.
pub trait ApiArgs: serde::de::DeserializeOwned + Sized {
    /// The arguments shared with other commands: [`PlanArgs`], [`ProgramArgs`] or [`NoShared`].
    type Shared: SharedArgs;
    /// Where they sit in the struct.
    fn shared_mut(&mut self) -> Option<&mut Self::Shared>;

    /// The command reads a designation, and holds the flags that say how ([`StandardArgs`]).
    const READS_THREAD: bool = false;

    /// Where the designation-reading flags sit (`None` for a command that reads none).
    fn standard_mut(&mut self) -> Option<&mut args::StandardArgs> {
        None
    }

    /// The keys the command takes: the shared arguments', the program-reading flags' where
    /// they read a program ([`ReadingArgs`]), the designation-reading flags' where they read a
    /// thread ([`StandardArgs`]), its own.
    fn keys() -> Vec<&'static str> {
        let shared = serde_aux::serde_introspection::serde_introspect::<Self::Shared>();
        let own = serde_aux::serde_introspection::serde_introspect::<Self>();
        shared
            .iter()
            .chain(reading_keys::<Self::Shared>())
            .chain(standard_keys::<Self>())
            .chain(own)
            .copied()
            .collect()
    }
}

/// The designation-reading flags' keys where `T` reads a thread.
fn standard_keys<T: ApiArgs>() -> &'static [&'static str] {
    if T::READS_THREAD {
        serde_aux::serde_introspection::serde_introspect::<args::StandardArgs>()
    } else {
        &[]
    }
}

/// Arguments that several commands share; those that read a program hold the reading flags.
pub trait SharedArgs: serde::de::DeserializeOwned {
    /// They read a program, and hold its reading flags.
    const READS: bool;
    /// Where the program-reading flags sit (`None` when they read none).
    fn reading_mut(&mut self) -> Option<&mut args::ReadingArgs>;
}

impl SharedArgs for PlanArgs {
    const READS: bool = true;
    fn reading_mut(&mut self) -> Option<&mut args::ReadingArgs> {
        Some(&mut self.reading)
    }
}

impl SharedArgs for ProgramArgs {
    const READS: bool = true;
    fn reading_mut(&mut self) -> Option<&mut args::ReadingArgs> {
        Some(&mut self.reading)
    }
}

impl SharedArgs for NoShared {
    const READS: bool = false;
    fn reading_mut(&mut self) -> Option<&mut args::ReadingArgs> {
        None
    }
}

/// The reading flags' keys where `S` reads a program.
fn reading_keys<S: SharedArgs>() -> &'static [&'static str] {
    if S::READS {
        serde_aux::serde_introspection::serde_introspect::<args::ReadingArgs>()
    } else {
        &[]
    }
}

/// The shared arguments of a command that shares none.
#[derive(Clone, Copy, Debug, Default, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NoShared {}

/// Reads `T` from the JSON object `map`: a key the command does not take, or a value of the
/// wrong type, is one line naming the key.
fn from_map<T: ApiArgs>(name: &str, map: Map<String, Value>) -> Result<T, Error> {
    let keys = T::keys();
    if let Some(k) = map.keys().find(|k| !keys.contains(&k.as_str())) {
        return Err(Error::Input(format!("{name} takes no argument '{k}'; it takes {}", keys.join(", "))));
    }
    let shared_keys = serde_aux::serde_introspection::serde_introspect::<T::Shared>();
    let reading_keys = reading_keys::<T::Shared>();
    let standard_keys = standard_keys::<T>();
    let (standard, rest): (Map<String, Value>, Map<String, Value>) =
        map.into_iter().filter(|(_, v)| !v.is_null()).partition(|(k, _)| standard_keys.contains(&k.as_str()));
    let (reading, rest): (Map<String, Value>, Map<String, Value>) =
        rest.into_iter().partition(|(k, _)| reading_keys.contains(&k.as_str()));
    let (shared, own): (Map<String, Value>, Map<String, Value>) =
        rest.into_iter().partition(|(k, _)| shared_keys.contains(&k.as_str()));
    let mut args: T = typed(name, own)?;
    let mut shared: T::Shared = typed(name, shared)?;
    if let Some(r) = shared.reading_mut() {
        *r = typed(name, reading)?;
    }
    if let Some(s) = args.shared_mut() {
        *s = shared;
    }
    if let Some(s) = args.standard_mut() {
        *s = typed(name, standard)?;
    }
    Ok(args)
}

fn typed<T: serde::de::DeserializeOwned>(name: &str, map: Map<String, Value>) -> Result<T, Error> {
    serde_path_to_error::deserialize(Value::Object(map)).map_err(|e| {
        let key = e.path().to_string();
        Error::Input(format!("{name}: {key}: {}", e.into_inner()))
    })
}

/// Declares the command list once: the enum the command line parses (each variant's doc is its
/// help), its name, documents, job and destinations, and the commands the API and Python run.
macro_rules! commands {
    ($($(#[$doc:meta])* $variant:ident($args:ty) $(, api $api:literal)?;)*) => {
        /// A command with its arguments.
        #[cfg_attr(feature = "cli", derive(clap::Subcommand))]
        #[derive(Clone, Debug)]
        #[allow(clippy::large_enum_variant)]
        pub enum Command {
            $($(#[$doc])* $variant($args),)*
        }

        impl Command {
            /// The commands' names, as the command line spells them.
            pub const NAMES: &'static [&'static str] = &[$(<$args as Job>::NAME),*];
            /// The commands the API and Python run.
            pub const API: &'static [&'static str] = &[$($($api,)?)*];

            /// The command's name.
            pub fn name(&self) -> &'static str {
                match self { $(Command::$variant(_) => <$args as Job>::NAME,)* }
            }

            /// The documents it gives.
            pub fn documents(&self) -> &'static [Document] {
                match self { $(Command::$variant(_) => <$args as Job>::DOCUMENTS,)* }
            }

            /// Runs the command, rendering what `request` asks for.
            pub fn run(&self, request: &Request) -> Result<Outputs, Error> {
                match self { $(Command::$variant(a) => a.run(request),)* }
            }

            /// Where the command line's flags send each document.
            pub fn destinations(&self) -> Vec<(Document, Dest)> {
                match self { $(Command::$variant(a) => a.destinations(),)* }
            }

            /// The command `name` of the API with its arguments, the JSON object `args`.
            ///
            /// ```
            /// let e = threadcheck::Command::from_api("verify", r#"{"thread": "M10x1.5-6g", "wire": 1}"#).unwrap_err();
            /// assert!(e.to_string().starts_with("verify takes no argument 'wire'; it takes thread, internal"));
            /// ```
            pub fn from_api(name: &str, args: &str) -> Result<Command, Error> {
                let value: Value = serde_json::from_str(args)
                    .map_err(|e| Error::Input(format!("the arguments are not a JSON object: {e}")))?;
                let Value::Object(map) = value else {
                    return Err(Error::Input("the arguments must be a JSON object of keyword arguments".into()));
                };
                $($(if name == $api { return Ok(Command::$variant(from_map::<$args>(name, map)?)); })?)*
                Err(unknown(name))
            }

            /// The documents the API command `name` gives (none for an unknown name).
            pub fn documents_of(name: &str) -> &'static [Document] {
                $($(if name == $api { return <$args as Job>::DOCUMENTS; })?)*
                &[]
            }

            /// The documents the API (and Python) serve of command `name`: its documents but
            /// a run of many's (JSON Lines, SARIF, JUnit), which `verify FOLDER` makes on the
            /// command line.
            pub fn api_documents(name: &str) -> Vec<Document> {
                Command::documents_of(name).iter().copied().filter(|d| !d.of_many()).collect()
            }

            /// Whether the API serves `document` of command `name`; else why not, naming what
            /// it serves.
            pub fn served(name: &str, document: Document) -> Result<(), Error> {
                let served = Command::api_documents(name);
                if served.contains(&document) {
                    return Ok(());
                }
                let names: Vec<&str> = served.iter().map(|d| d.name()).collect();
                let why = if document.of_many() && Command::documents_of(name).contains(&document) {
                    format!(
                        "{} is a run of many programs' document, made on the command line (threadcheck {name} FOLDER --{}); the API verifies one program",
                        document.name(),
                        document.name()
                    )
                } else {
                    format!("{name} gives no {} document", document.name())
                };
                Err(Error::Input(format!("{why}: {name} gives {}", names.join(", "))))
            }

            /// The keys the API command `name` takes (Python's keyword arguments).
            pub fn keys(name: &str) -> Result<Vec<&'static str>, Error> {
                $($(if name == $api { return Ok(<$args as ApiArgs>::keys()); })?)*
                Err(unknown(name))
            }
        }
    };
}

fn unknown(name: &str) -> Error {
    if Command::NAMES.contains(&name) {
        Error::Input(format!(
            "{name} runs on the command line only; the API runs {}",
            Command::API.join(", ")
        ))
    } else {
        Error::Input(format!("unknown command '{name}': expected {}", Command::API.join(", ")))
    }
}

commands! {
    /// Cut the thread in the computer and check it against its class.
    Verify(VerifyArgs), api "verify";
    /// Print the expanded pass plan.
    Passes(PassesArgs), api "passes";
    /// Limits of size of a designation (ISO 965-1, BS 84, ISO 228-1, ASME B1.1, ISO 2903, ASME
    /// B1.5, ASME B1.20.1, ISO 7-1).
    Limits(LimitsArgs), api "limits";
    /// The same thread with radial, flank, modified-flank and alternating infeed.
    Compare(CompareArgs), api "compare";
    /// A bolt and a nut cut in the computer and assembled: do they screw together?
    Fit(FitArgs), api "fit";
    /// After measuring the first part: the part's pitch diameter from the measurement and the
    /// change to make, in the program's words (exit 0 in tolerance, 1 when a correction is
    /// needed); a pick-up's start angle or Z shift.
    Correct(CorrectArgs), api "correct";
    /// How many parts a program (or plan) keeps in tolerance: a Monte Carlo over the X
    /// scatter, the tip radius tolerance and the wear per part (Cp, Cpk, ppm, parts per edge;
    /// exit 0 when the pitch diameter's Cpk reaches 1.33).
    Capability(CapabilityArgs), api "capability";
    /// A milling program's cutter swept along each Z level and measured against a target curve:
    /// gouge and material left.
    Mill(MillArgs), api "mill";
    /// A program's tapping cycles (G84, G74) against their taps and the drills that made the
    /// holes: the drill against D1 of the tap's class, the feed against the lead, the depth
    /// left for the tap's point above the drill's, the spindle's direction (exit 0 all pass, 1 one fails).
    Tap(TapArgs), api "tap";
    /// The thread a thread-milling program leaves (helical G2/G3 in G17 with a single-form
    /// cutter): the exact envelope of the cutter in the part's axial section, measured and
    /// checked, with the profile distortion against the tooth profile and the lead per turn.
    ThreadMill(ThreadMillArgs), api "thread-mill";
    /// Verify the catalogue in parallel: ISO 261 (M1–M68, coarse and fine) by default, every
    /// form's series with --form all.
    Sweep(SweepArgs);
    /// Regenerate a committed report.
    Report(ReportArgs);
}

/// Runs the API command `name` on the JSON object `args` and answers with `document` and the
/// outcome; messages name arguments for `reader` (the API's keys, or the page's fields).
///
/// ```
/// use threadcheck::{run_request, Audience, Document, Files, Outcome};
/// let args = r#"{"thread": "M10x1.5-6g", "insert": "full"}"#;
/// let (body, outcome) = run_request("verify", Document::Json, args, Files::Refused, Audience::Api)?;
/// assert_eq!(outcome, Outcome::Pass);
/// let v: serde_json::Value = serde_json::from_str(&body).expect("JSON");
/// assert_eq!(v["verdict"], "pass");
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn run_request(
    name: &str,
    document: Document,
    args: &str,
    files: Files,
    reader: crate::Audience,
) -> Result<(String, Outcome), Error> {
    let command = Command::from_api(name, args)?;
    Command::served(name, document)?;
    let out = command.run(&Request { reader, ..Request::api(document, files) })?;
    let body = out
        .document(document)
        .ok_or_else(|| Error::Input(format!("{name} made no {} document for this input", document.name())))?;
    Ok((reader.words(body), out.outcome))
}
