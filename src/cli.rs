//! The command line's arguments, typed once: every option is parsed by clap into the library's
//! own types (`InsertChoice`, `InfeedChoice`, `Schedule`, `Dialect`, finite `f64`s), so a bad
//! value is a usage error naming the option. This module belongs to the binary, not the library.

use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;
use threadcheck::Dialect;
use threadcheck::{
    CapabilityJob, CompareJob, CorrectJob, FitJob, InfeedReportJob, LimitsJob, MillJob, Outcome, PassesJob,
    SweepJob, VerifyJob,
};
use threadcheck::{Error, ThreadForm};
use threadcheck::{InfeedChoice, Schedule};
use threadcheck::{InsertChoice, ProgramSource, Units, VerifySpec};

/// Predicts the thread a CNC lathe program cuts and checks it against its standard.
#[derive(Parser)]
#[command(name = "threadcheck", version, about)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// A finite number (clap's own `f64` parser takes `inf` and `NaN`).
fn finite(s: &str) -> Result<f64, String> {
    let v: f64 = s.trim().parse().map_err(|_| "not a number".to_string())?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err("not a finite number".into())
    }
}

/// A pass count of at least one.
fn pass_count(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(0) => Err("a thread needs at least one pass".into()),
        Ok(n) => Ok(n),
        Err(_) => Err("not a whole number".into()),
    }
}

/// The one-line form of clap's rendered error: the message and its tips, without the usage
/// block and the `--help` hint.
pub fn one_line(rendered: &str) -> String {
    let mut parts = Vec::new();
    for line in rendered.lines() {
        let l = line.trim();
        if l.starts_with("Usage:") || l.starts_with("For more information") {
            break;
        }
        if !l.is_empty() {
            parts.push(l.strip_prefix("error: ").unwrap_or(l));
        }
    }
    parts.join(" ")
}

/// Where `--json` goes: `--json` or `--json -` for stdout, `--json FILE` for a file.
#[derive(Args)]
struct JsonArg {
    /// JSON: on stdout instead of the text (`--json` or `--json -`), or written to FILE.
    #[arg(long, value_name = "FILE|-", num_args = 0..=1, default_missing_value = "-")]
    json: Option<String>,
}

/// Which operation of a program that cuts several threads `verify`, `correct` and `capability`
/// take.
#[derive(Args)]
struct OperationArg {
    /// Of a program that cuts several threads, the one to take (1-based, in program order, as
    /// `verify` and `passes` number them); `verify` checks every one without it.
    #[arg(long, value_name = "N", requires = "program", value_parser = operation_number)]
    operation: Option<usize>,
}

/// An operation's number: 1 or more.
fn operation_number(s: &str) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(n) if n >= 1 => Ok(n),
        _ => Err("an operation's number, from 1".into()),
    }
}

#[derive(Subcommand)]
enum Command {
    /// Limits of size of a designation (ISO 965-1, BS 84, ISO 228-1, ASME B1.1, ISO 2903, ASME
    /// B1.5, ASME B1.20.1, ISO 7-1).
    Limits {
        /// Designation, e.g. M10x1.25-6g, M10-6H/6g, "BSF 3/8 medium", "G1/2 A", "1/4-20 UNC-2A".
        #[arg(conflicts_with = "thread")]
        designation: Option<String>,
        /// The designation as an option, as the other commands take it.
        #[arg(long)]
        thread: Option<String>,
        #[command(flatten)]
        json: JsonArg,
        /// Accept a diameter/pitch pair outside the standard series.
        #[arg(long)]
        allow_nonstandard: bool,
        /// The limits to cut to before a coating of this thickness, mm (plating, anodizing).
        #[arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = finite, default_value = "0")]
        coating: f64,
        /// Under a coating, the class applies before it (the standards' default) or after it
        /// (when the drawing says so).
        #[arg(long, value_enum, default_value = "before")]
        coating_limits: CoatingLimitsArg,
    },
    /// Cut the thread in the computer and check it against its class.
    Verify {
        #[command(flatten)]
        plan: PlanArgs,
        #[command(flatten)]
        operation: OperationArg,
        /// Leave form checks (root radius, minor-diameter zone, flank angles) out of the verdict.
        #[arg(long)]
        gauge_only: bool,
        /// Skip the per-pass chip and edge metrics: a faster verdict.
        #[arg(long)]
        no_pass_metrics: bool,
        /// Write an SVG cross-section to this file.
        #[arg(long, value_name = "FILE")]
        svg: Option<PathBuf>,
        /// Write a self-contained HTML report (picture, checks, passes, notes) to this file.
        #[arg(long, value_name = "FILE")]
        html: Option<PathBuf>,
        /// Write the program with each operation's correction (the word that sets its final
        /// depth, put to mid-tolerance d2) to this file; `-` prints it instead of the report.
        #[arg(long, value_name = "FILE|-", requires = "program")]
        fix: Option<String>,
        #[command(flatten)]
        json: JsonArg,
    },
    /// After measuring the first part: the part's pitch diameter from the measurement and the
    /// change to make, in the program's words (exit 0 in tolerance, 1 when a correction is
    /// needed); a pick-up's start angle or Z shift.
    Correct(CorrectArgs),
    /// How many parts a program (or plan) keeps in tolerance: a Monte Carlo over the X
    /// scatter, the tip radius tolerance and the wear per part (Cp, Cpk, ppm, parts per edge;
    /// exit 0 when the pitch diameter's Cpk reaches 1.33).
    Capability(CapabilityArgs),
    /// The same thread with radial, flank, modified-flank and alternating infeed.
    Compare {
        #[command(flatten)]
        plan: PlanArgs,
        /// Modified-flank angles, degrees (comma-separated); default half the thread angle less
        /// 0.5° and less 3° (29.5,27 for 60° threads, 14.5,12 for trapezoidal).
        #[arg(long, value_name = "ANGLES", value_delimiter = ',', value_parser = finite)]
        modified: Vec<f64>,
        /// JSON (every verify report and the per-strategy figures).
        #[command(flatten)]
        json: JsonArg,
        /// Write the table as Markdown to this file.
        #[arg(long, value_name = "FILE")]
        markdown: Option<PathBuf>,
        /// Write a self-contained HTML report (the table and each strategy's picture) to this file.
        #[arg(long, value_name = "FILE")]
        html: Option<PathBuf>,
    },
    /// Verify the catalogue in parallel: ISO 261 (M1–M68, coarse and fine) by default, every
    /// form's series with --form all.
    Sweep(SweepArgs),
    /// Regenerate a committed report.
    Report {
        /// Which report.
        name: ReportName,
        /// Folder to write it and its pictures into.
        #[arg(long, default_value = "reports")]
        out: PathBuf,
    },
    /// A bolt and a nut cut in the computer and assembled: do they screw together?
    Fit(FitArgs),
    /// A milling program's cutter swept along each Z level and measured against a target curve:
    /// gouge and material left.
    Mill(MillArgs),
    /// A program's tapping cycles (G84, G74) against their taps and the drills that made the
    /// holes: the drill against D1 of the tap's class, the feed against the lead, the depth
    /// left for the tap's chamfer, the spindle's direction (exit 0 all pass, 1 one fails).
    Tap(TapArgs),
    /// The thread a thread-milling program leaves (helical G2/G3 in G17 with a single-form
    /// cutter): the exact envelope of the cutter in the part's axial section, measured and
    /// checked, with the profile distortion against the tooth profile and the lead per turn.
    ThreadMill(ThreadMillArgs),
    /// The shop's page and the JSON API on this computer: open the address it prints in a
    /// browser (verify, compare, fit, limits); scripts POST to /api/verify and the like.
    Serve(ServeArgs),
    /// Print the expanded pass plan.
    Passes {
        #[command(flatten)]
        plan: PlanArgs,
        #[command(flatten)]
        json: JsonArg,
    },
}

/// `--coating-limits`.
#[derive(Clone, Copy, ValueEnum)]
enum CoatingLimitsArg {
    /// The class applies before coating; after it the thread stays within the basic profile.
    Before,
    /// The class applies after coating.
    After,
}

impl CoatingLimitsArg {
    fn rule(self) -> threadcheck::CoatingLimits {
        match self {
            CoatingLimitsArg::Before => threadcheck::CoatingLimits::Before,
            CoatingLimitsArg::After => threadcheck::CoatingLimits::After,
        }
    }
}

/// The committed reports `report` regenerates.
#[derive(Clone, Copy, ValueEnum)]
enum ReportName {
    /// reports/infeed-comparison.md and its SVGs.
    InfeedComparison,
}

/// A form of `sweep --form`.
#[derive(Clone, Copy, ValueEnum)]
enum FormArg {
    /// ISO metric, ISO 261.
    #[value(alias = "metric")]
    IsoMetric,
    /// Unified inch, ASME B1.1.
    Unified,
    /// ISO metric trapezoidal.
    Trapezoidal,
    /// General-purpose Acme.
    Acme,
    /// BS 84 Whitworth.
    Whitworth,
    /// ISO 228-1 parallel pipe.
    #[value(alias = "bsp")]
    BspParallel,
    /// ASME B1.20.1 NPT.
    Npt,
    /// ISO 7-1 taper pipe.
    #[value(alias = "iso7")]
    Iso7Taper,
    /// Every form.
    All,
}

impl FormArg {
    fn forms(self) -> Vec<ThreadForm> {
        match self {
            FormArg::IsoMetric => vec![ThreadForm::IsoMetric],
            FormArg::Unified => vec![ThreadForm::Unified],
            FormArg::Trapezoidal => vec![ThreadForm::Trapezoidal],
            FormArg::Acme => vec![ThreadForm::Acme],
            FormArg::Whitworth => vec![ThreadForm::Whitworth],
            FormArg::BspParallel => vec![ThreadForm::BspParallel],
            FormArg::Npt => vec![ThreadForm::Npt],
            FormArg::Iso7Taper => vec![ThreadForm::Iso7Taper],
            FormArg::All => threadcheck::CatalogueSpec::all_forms().forms,
        }
    }
}

/// `coarse`, `fine` or `all`.
#[derive(Clone, Copy, ValueEnum)]
enum SeriesArg {
    Coarse,
    Fine,
    All,
}

/// `full`, `partial` or `both`.
#[derive(Clone, Copy, ValueEnum)]
enum InsertSet {
    Full,
    Partial,
    Both,
}

/// Lengths in the text and the SVG.
#[derive(Clone, Copy, ValueEnum)]
enum UnitsArg {
    /// Millimetres.
    Mm,
    /// Millimetres with inches beside them.
    Inch,
}

#[derive(Args)]
struct SweepArgs {
    /// Forms (comma-separated).
    #[arg(long, value_delimiter = ',', default_value = "iso-metric")]
    form: Vec<FormArg>,
    /// Also the internal threads, in each form's medium internal class.
    #[arg(long)]
    internal: bool,
    /// Pitch series.
    #[arg(long, value_enum, default_value = "all")]
    series: SeriesArg,
    /// Smallest nominal diameter, mm.
    #[arg(long, default_value = "1", value_parser = finite)]
    min_d: f64,
    /// Largest nominal diameter, mm.
    #[arg(long, default_value = "68", value_parser = finite)]
    max_d: f64,
    /// Tolerance class of the external thread.
    #[arg(long, default_value = "6g")]
    class: String,
    /// Inserts.
    #[arg(long, value_enum, default_value = "both")]
    insert: InsertSet,
    /// Comma-separated infeeds, as verify takes them: radial, flank[:ANGLE], modified,
    /// alternating[:ANGLE].
    #[arg(long, value_delimiter = ',', default_value = "radial,flank,modified,alternating")]
    infeed: Vec<InfeedChoice>,
    /// Comma-separated schedules: constant-area, constant-depth, sandvik.
    #[arg(long, value_delimiter = ',', default_value = "constant-area,constant-depth")]
    schedule: Vec<Schedule>,
    /// Leave form checks out of the verdicts.
    #[arg(long)]
    gauge_only: bool,
    /// One verify report per line (JSON Lines): on stdout (`--json` or `--json -`, the
    /// summary then goes to stderr), or written to FILE.
    #[arg(long, value_name = "FILE|-", num_args = 0..=1, default_missing_value = "-")]
    json: Option<String>,
    /// Write each case's blank, placements and measured d2 here (JSON Lines).
    #[arg(long, value_name = "FILE")]
    export_placements: Option<PathBuf>,
}

#[derive(Args)]
struct FitArgs {
    /// A fit designation, e.g. M10x1.5-6H/6g.
    #[arg(long)]
    thread: String,
    /// Accept a diameter/pitch pair outside the standard series.
    #[arg(long)]
    allow_nonstandard: bool,
    /// The bolt's program (else a generated plan).
    #[arg(long, value_name = "FILE", conflicts_with = "bolt_final_x")]
    bolt_program: Option<PathBuf>,
    /// Its dialect: fanuc, haas, sinumerik, linuxcnc, dyna, okuma, mitsubishi, mazak or heidenhain.
    #[arg(long)]
    bolt_dialect: Option<Dialect>,
    /// The nut's program (else a generated plan).
    #[arg(long, value_name = "FILE", conflicts_with = "nut_final_x")]
    nut_program: Option<PathBuf>,
    /// Its dialect.
    #[arg(long)]
    nut_dialect: Option<Dialect>,
    /// The bolt plan's last tip diameter (default: mid-tolerance).
    #[arg(long, value_name = "DIA", allow_hyphen_values = true, value_parser = finite)]
    bolt_final_x: Option<f64>,
    /// The nut plan's last tip diameter (default: mid-tolerance).
    #[arg(long, value_name = "DIA", allow_hyphen_values = true, value_parser = finite)]
    nut_final_x: Option<f64>,
    /// The bolt's insert: full | partial[:TIP_RADIUS] | FILE.toml.
    #[arg(long, default_value = "partial")]
    bolt_insert: InsertChoice,
    /// The nut's insert.
    #[arg(long, default_value = "partial")]
    nut_insert: InsertChoice,
    /// Write an SVG of the pair.
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
    #[command(flatten)]
    json: JsonArg,
}

#[derive(Args)]
struct CapabilityArgs {
    #[command(flatten)]
    plan: PlanArgs,
    #[command(flatten)]
    operation: OperationArg,
    /// X repeatability, one standard deviation on the diameter, mm.
    #[arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = finite, default_value = "0")]
    x_sigma: f64,
    /// The insert's tip radius tolerance, ± mm (uniform; a partial-profile insert).
    #[arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = finite, default_value = "0")]
    tip_radius_tol: f64,
    /// Radial insert wear per part, mm.
    #[arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = finite, default_value = "0")]
    wear_per_part: f64,
    /// Monte Carlo samples.
    #[arg(long, value_name = "N", default_value_t = 10_000)]
    samples: usize,
    /// The seed (the same seed gives the same report on any number of cores).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Leave form checks out of each part's verdict (the share of good parts).
    #[arg(long)]
    gauge_only: bool,
    /// Write the pitch diameter's histogram (SVG) to this file.
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
    /// Write a self-contained HTML page to this file.
    #[arg(long, value_name = "FILE")]
    html: Option<PathBuf>,
    #[command(flatten)]
    json: JsonArg,
}

#[derive(Args)]
struct CorrectArgs {
    #[command(flatten)]
    plan: PlanArgs,
    #[command(flatten)]
    operation: OperationArg,
    /// The measurement over three wires, mm (with --wire).
    #[arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = finite, requires = "wire",
          conflicts_with_all = ["measured_d2", "gauge"])]
    measured_m: Option<f64>,
    /// The wires' diameter, mm.
    #[arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = finite, requires = "measured_m")]
    wire: Option<f64>,
    /// The pitch diameter measured (thread micrometer, optical), mm.
    #[arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = finite, conflicts_with = "gauge")]
    measured_d2: Option<f64>,
    /// What the GO/NO-GO gauges said: go-fails | nogo-enters | ok.
    #[arg(long, value_name = "RESULT")]
    gauge: Option<threadcheck::GaugeResult>,
    /// Pick-up: a groove centre's Z on the re-clamped part (at the pitch line, from the
    /// program's Z0), mm.
    #[arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = finite)]
    pickup_z: Option<f64>,
    /// Write a self-contained HTML page to this file.
    #[arg(long, value_name = "FILE")]
    html: Option<PathBuf>,
    /// Write the program with the correction to this file; `-` prints it instead of the report.
    #[arg(long, value_name = "FILE|-", requires = "program")]
    fix: Option<String>,
    #[command(flatten)]
    json: JsonArg,
}

/// The program file of `mill`, `tap` and `thread-mill`, and its dialect.
#[derive(Args)]
struct ProgramFile {
    /// The program.
    #[arg(long, value_name = "FILE")]
    program: PathBuf,
    /// fanuc | haas | sinumerik | linuxcnc | dyna | okuma | mitsubishi | mazak | heidenhain (default: by
    /// the extension, else fanuc)
    #[arg(long)]
    dialect: Option<Dialect>,
}

impl ProgramFile {
    /// The program's text and name, its dialect and how the dialect was chosen.
    fn read(&self) -> Result<((String, String), Dialect, threadcheck::DialectFrom), Error> {
        let (dialect, from) = dialect_for(self.dialect, &self.program);
        Ok((
            (threadcheck::read_program_text(&self.program)?, self.program.display().to_string()),
            dialect,
            from,
        ))
    }
}

#[derive(Args)]
struct ThreadMillArgs {
    #[command(flatten)]
    file: ProgramFile,
    /// The thread with its class, e.g. M20x1.5-6H.
    #[arg(long)]
    thread: String,
    /// Accept a diameter/pitch pair outside the standard series.
    #[arg(long)]
    allow_nonstandard: bool,
    /// The cutter's diameter over its tooth's tip, mm (else the tool table's thread mill).
    #[arg(long, value_name = "MM", value_parser = finite, required_unless_present = "tools")]
    cutter_diameter: Option<f64>,
    /// The tool table: the helices' T as a thread mill's file (`12 = "thread-mill.toml"`:
    /// kind = "thread-mill", diameter, angle, tip_radius, rows, row_pitch) and `[offsets]` (12 = 3.0,
    /// the compensation value G41/G42 apply).
    #[arg(long, value_name = "FILE.toml", conflicts_with = "cutter_diameter")]
    tools: Option<PathBuf>,
    /// The tooth's included angle, degrees.
    #[arg(long, value_name = "DEG", value_parser = finite, default_value = "60")]
    cutter_angle: f64,
    /// The tooth's tip radius, mm.
    #[arg(long, value_name = "MM", value_parser = finite, default_value = "0")]
    cutter_tip_radius: f64,
    /// Rows of teeth: 1 for a single-form cutter, more for a multi-form one (with
    /// --cutter-row-pitch).
    #[arg(long, value_name = "N", default_value = "1", value_parser = clap::value_parser!(u32).range(1..=200))]
    cutter_rows: u32,
    /// A multi-form cutter's row spacing, mm.
    #[arg(long, value_name = "MM", value_parser = finite)]
    cutter_row_pitch: Option<f64>,
    /// The bore (internal) or blank (external) diameter, mm.
    #[arg(long, value_name = "MM", value_parser = finite)]
    blank_diameter: Option<f64>,
    /// The value G41/G42 compensate by (the D register), mm: the cutter centre runs that far to
    /// the left (G41) or right (G42) of the programmed helix.
    #[arg(long, value_name = "MM", value_parser = finite)]
    comp_radius: Option<f64>,
    /// Write the milled thread's axial section (SVG) to this file.
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
    /// Write a self-contained HTML page (the section, the checks, the helices) to this file.
    #[arg(long, value_name = "FILE")]
    html: Option<PathBuf>,
    #[command(flatten)]
    json: JsonArg,
}

#[derive(Args)]
struct TapArgs {
    #[command(flatten)]
    file: ProgramFile,
    /// The tool table: each tap as T = "tap:M10x1.5-6H[:CHAMFER_PITCHES]", each drill as
    /// T = "drill:8.5".
    #[arg(long, value_name = "FILE.toml")]
    tools: PathBuf,
    /// Accept a diameter/pitch pair outside the standard series.
    #[arg(long)]
    allow_nonstandard: bool,
    /// The units of a program that sets neither G20 nor G21.
    #[arg(long, value_name = "mm|inch")]
    default_units: Option<threadcheck::ProgramUnits>,
    /// The G-code system of a Fanuc-family control (fanuc, mitsubishi, mazak): a, b or c.
    #[arg(long, value_name = "a|b|c", default_value = "a")]
    gcode_system: threadcheck::GCodeSystem,
    /// Write the tapped holes' sections (SVG) to this file.
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
    /// Write a self-contained HTML page (the sections, the checks, the notes) to this file.
    #[arg(long, value_name = "FILE")]
    html: Option<PathBuf>,
    #[command(flatten)]
    json: JsonArg,
}

#[derive(Args)]
struct ServeArgs {
    /// The address to listen on; anything but loopback lets other machines in (said at start).
    #[arg(long, default_value = "127.0.0.1")]
    bind: std::net::IpAddr,
    /// The port (0: any free one, printed at start).
    #[arg(long, default_value_t = 8080)]
    port: u16,
    /// Requests computed at once (default twice the cores); others wait, then get 503.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1024))]
    max_in_flight: Option<u32>,
    /// Seconds a request waits for its turn before it is answered 503 (0: at once).
    #[arg(long, value_name = "SECONDS", default_value_t = 5.0, value_parser = queue_seconds)]
    queue_wait: f64,
    /// Seconds one request may compute before it is stopped and answered 503.
    #[arg(long, value_name = "SECONDS", default_value_t = 10.0, value_parser = positive_seconds)]
    time_budget: f64,
    /// Seconds a connection may take to send a request's head, or stay idle between requests.
    #[arg(long, value_name = "SECONDS", default_value_t = 5.0, value_parser = positive_seconds)]
    header_timeout: f64,
    /// Seconds a request's body may take to arrive once its turn has come (else 408).
    #[arg(long, value_name = "SECONDS", default_value_t = 10.0, value_parser = positive_seconds)]
    body_timeout: f64,
    /// Connections open at once; past it the server accepts no more until one closes.
    #[arg(long, value_name = "N", default_value_t = 256, value_parser = clap::value_parser!(u32).range(1..=65536))]
    max_connections: u32,
    /// A host name to answer besides the bound address and localhost (repeat for more): the
    /// Host header of every other request is refused (403), so that a web page cannot reach
    /// the server through a name of its own.
    #[arg(long, value_name = "NAME")]
    allow_host: Vec<String>,
}

#[derive(Args)]
struct MillArgs {
    #[command(flatten)]
    file: ProgramFile,
    /// Run the blocks in the order of their N numbers (a listing whose page break moved blocks).
    #[arg(long)]
    n_order: bool,
    /// Cutter diameter, mm.
    #[arg(long, value_name = "MM", value_parser = finite)]
    tool_diameter: f64,
    /// The target curve (TOML: x, y in t and z; t range; material inside|outside; optional z range).
    #[arg(long, value_name = "FILE.toml")]
    target: PathBuf,
    /// Allowed gouge and material left, mm.
    #[arg(long, value_name = "MM", value_parser = finite, default_value = "0.01")]
    tolerance: f64,
    /// Write an SVG of the worst level.
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
    #[command(flatten)]
    json: JsonArg,
}

#[derive(Args)]
struct PlanArgs {
    /// Thread with its class, e.g. M10x1.5-6g. With a program that cuts several threads, give it
    /// once for all or once per operation, in program order.
    #[arg(long, required_unless_present = "program")]
    thread: Vec<String>,
    /// The internal thread (else external; implied by an upper-case class alone).
    #[arg(long)]
    internal: bool,
    /// Accept a diameter/pitch pair outside the standard series.
    #[arg(long)]
    allow_nonstandard: bool,
    /// full | partial[:TIP_RADIUS] | FILE.toml (default partial, r0.04 mm)
    #[arg(long)]
    insert: Option<InsertChoice>,
    /// Tool table: which insert each T number of the program holds (TOML).
    #[arg(long, value_name = "FILE.toml", requires = "program")]
    tools: Option<PathBuf>,
    /// radial | flank[:ANGLE] | modified | alternating[:ANGLE] (default modified: half the thread
    /// angle less 0.5°)
    #[arg(long)]
    infeed: Option<InfeedChoice>,
    /// Number of cutting passes (default about 3.5 + 2·P).
    #[arg(long, conflicts_with = "first_depth", value_parser = pass_count)]
    passes: Option<usize>,
    /// Depth of the first pass, mm (sets the pass count).
    #[arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = finite)]
    first_depth: Option<f64>,
    /// Smallest radial step, mm.
    #[arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = finite, default_value = "0")]
    min_depth: f64,
    /// Finishing allowance, mm.
    #[arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = finite, default_value = "0")]
    finish: f64,
    /// Spring (idle) passes at full depth.
    #[arg(long, default_value_t = 0)]
    spring: usize,
    /// constant-area | constant-depth | sandvik (default constant-area; compare: both
    /// constant-area and constant-depth unless one is given)
    #[arg(long)]
    schedule: Option<Schedule>,
    /// Explicit cumulative radial depths, mm, e.g. 0.2,0.35,0.45 (instead of a schedule).
    #[arg(long, value_name = "LIST", value_delimiter = ',', value_parser = finite,
          conflicts_with_all = ["passes", "first_depth"])]
    depths: Vec<f64>,
    /// Taper: diameter change per mm of travel, e.g. 0.0625 for 1:16 (passes only).
    #[arg(long, value_name = "RATIO", allow_hyphen_values = true, value_parser = finite, default_value = "0")]
    taper: f64,
    /// Run-out chamfer at the thread end, in leads.
    #[arg(long, value_name = "LEADS", value_parser = finite, default_value = "0")]
    chamfer: f64,
    /// A coating the thread gets after cutting, mm (plating, anodizing): checked against the
    /// limits before coating.
    #[arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = finite, default_value = "0")]
    coating: f64,
    /// Under a coating, the class applies before it (the standards' default: ISO 965-1 §8.5,
    /// ASME B1.1 §7) or after it (when the drawing says so).
    #[arg(long, value_enum, default_value = "before")]
    coating_limits: CoatingLimitsArg,
    /// The length of engagement a gauge feels, mm, over which a program's lead error adds up
    /// (default: the nominal diameter, ASME B1.1's LE = D; a taper thread's L1).
    #[arg(long, value_name = "MM", value_parser = finite)]
    engagement: Option<f64>,
    /// Tip diameter of the last pass (default: what puts the pitch diameter mid-tolerance).
    #[arg(long, value_name = "DIA", allow_hyphen_values = true, value_parser = finite)]
    final_x: Option<f64>,
    /// Blank (external) or bore (internal) diameter, mm.
    #[arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = finite)]
    blank_diameter: Option<f64>,
    /// Take the passes from this G-code program.
    #[arg(long, value_name = "FILE")]
    program: Option<PathBuf>,
    /// A machine profile for the process checks of a program: FILE.toml or training-lathe.
    #[arg(long, value_name = "FILE.toml|training-lathe", requires = "program")]
    machine: Option<String>,
    /// The insert's side clearance angle, degrees: checks the leading flank against the helix.
    #[arg(long, value_name = "DEG", allow_hyphen_values = true, value_parser = finite)]
    clearance_angle: Option<f64>,
    /// Lengths in the text and the SVG: mm, or mm with inches beside them (default: inch for
    /// threads of inch sizes (UN, Acme, NPT, BSW, BSP), else mm)
    #[arg(long, value_enum)]
    units: Option<UnitsArg>,
    /// fanuc | haas | sinumerik | linuxcnc | dyna | okuma | mitsubishi | mazak | heidenhain (default: the
    /// program's extension names it,
    /// .ngc linuxcnc, .mpf/.spf sinumerik, .min/.ssb/.sub okuma; else fanuc)
    #[arg(long, requires = "program")]
    dialect: Option<Dialect>,
    /// The units of a program that sets neither G20 nor G21 (the control's default).
    #[arg(long, value_name = "mm|inch", requires = "program")]
    default_units: Option<threadcheck::ProgramUnits>,
    /// The main program of a file that holds several O-programs (default: the one no other
    /// calls; the output says which)
    #[arg(long, value_name = "O-NUMBER", requires = "program", value_parser = o_number)]
    main: Option<u32>,
    /// The LinuxCNC release whose comparisons (EQ, NE, LE, GE) a linuxcnc program follows:
    /// current (2.9.0 and later, within 1e-6) or before-2.9 (EQ and NE within 1e-4, as
    /// Debian 12's linuxcnc-uspace package does)
    #[arg(long, value_name = "current|before-2.9", requires = "program", default_value = "current")]
    linuxcnc_release: threadcheck::LinuxCncRelease,
    /// The G-code system a Fanuc-family lathe control (fanuc, mitsubishi, mazak) is set to: a (G92
    /// threading cycle, the default),
    /// b (G78 threading cycle, G92 coordinates) or c (G21 threading cycle, G78 multiple cycle)
    #[arg(long, value_name = "a|b|c", requires = "program", default_value = "a")]
    gcode_system: threadcheck::GCodeSystem,
}

/// Seconds to wait, from 0 to an hour.
fn positive_seconds(s: &str) -> Result<f64, String> {
    match finite(s)? {
        v if (0.01..=3600.0).contains(&v) => Ok(v),
        _ => Err("from 0.01 to 3600 seconds".into()),
    }
}

fn queue_seconds(s: &str) -> Result<f64, String> {
    match finite(s)? {
        v if (0.0..=3600.0).contains(&v) => Ok(v),
        _ => Err("from 0 to 3600 seconds".into()),
    }
}

/// `O3101` or `3101`: an O-program's number.
fn o_number(s: &str) -> Result<u32, String> {
    let digits = s.strip_prefix(['O', 'o']).unwrap_or(s);
    match digits.parse::<u32>() {
        Ok(n) if !digits.starts_with('+') => Ok(n),
        _ => Err(format!("'{s}' is not an O-program number such as O3101")),
    }
}

/// The dialect to read `program` in: the one given, else the one its extension names, else
/// Fanuc; and how it was chosen.
fn dialect_for(given: Option<Dialect>, program: &std::path::Path) -> (Dialect, threadcheck::DialectFrom) {
    match (given, Dialect::by_extension(program)) {
        (Some(d), _) => (d, threadcheck::DialectFrom::Given),
        (None, Some(d)) => (d, threadcheck::DialectFrom::Extension),
        (None, None) => (Dialect::Fanuc, threadcheck::DialectFrom::Default),
    }
}

impl PlanArgs {
    fn spec(&self, gauge_only: bool) -> Result<VerifySpec, Error> {
        let mut s = VerifySpec::new(self.thread.first().map_or("", String::as_str));
        s.internal = self.internal;
        s.allow_nonstandard = self.allow_nonstandard;
        s.insert = self.insert.clone().unwrap_or(InsertChoice::Partial { tip_radius: 0.04 });
        s.infeed = self.infeed;
        s.passes = self.passes;
        s.first_depth = self.first_depth;
        s.min_depth = self.min_depth;
        s.finish = self.finish;
        s.spring = self.spring;
        s.schedule = if self.depths.is_empty() {
            self.schedule.clone().unwrap_or(Schedule::ConstantArea)
        } else {
            Schedule::Explicit(self.depths.clone())
        };
        s.taper = self.taper;
        s.chamfer_leads = self.chamfer;
        s.final_x = self.final_x;
        s.blank_diameter = self.blank_diameter;
        s.gauge_only = gauge_only;
        s.machine = self.machine.as_deref().map(threadcheck::MachineProfile::read).transpose()?;
        s.clearance_angle = self.clearance_angle;
        s.coating = self.coating;
        s.coating_limits = self.coating_limits.rule();
        s.engagement = self.engagement;
        s.units = match self.units {
            Some(UnitsArg::Mm) => Units::Mm,
            Some(UnitsArg::Inch) => Units::Inch,
            // An inch thread is read in inches beside the mm; a designation that does not parse
            // is reported where it is resolved.
            None => VerifySpec::default_units(
                self.thread.first().map_or("", String::as_str),
                self.allow_nonstandard,
            ),
        };
        if let Some(p) = &self.program {
            let (dialect, from) = dialect_for(self.dialect, p);
            s.program = Some((ProgramSource::File(p.clone()), dialect));
            s.reading.dialect_from = from;
        }
        s.reading.default_units = self.default_units;
        s.reading.main = self.main;
        s.reading.linuxcnc = self.linuxcnc_release;
        s.reading.gcode_system = self.gcode_system;
        Ok(s)
    }

    /// The checks a command that cuts a thread needs before it runs.
    fn need_thread(&self, command: &str) -> Result<(), Error> {
        if self.thread.is_empty() {
            return Err(Error::Input(format!(
                "{command} needs --thread with a class, e.g. --thread M10x1.5-6g"
            )));
        }
        if self.thread.len() > 1 && self.program.is_none() {
            return Err(Error::Input(
                "--thread is given more than once: only a program with several threads takes one per operation"
                    .into(),
            ));
        }
        Ok(())
    }
}

impl Cli {
    /// Runs the command: what to print on stdout and on stderr, and the outcome.
    pub fn run(self) -> Result<(String, String, Outcome), Error> {
        let done = |(text, outcome): (String, Outcome)| Ok((text, String::new(), outcome));
        match self.command {
            Command::Limits {
                designation,
                thread,
                json: JsonArg { json },
                allow_nonstandard,
                coating,
                coating_limits,
            } => {
                let Some(designation) = designation.or(thread) else {
                    return Err(Error::Input(match json.as_deref() {
                        Some(v) if v != "-" => format!(
                            "limits needs a designation: --json took '{v}' as its file; write `limits {v} --json`"
                        ),
                        _ => "limits needs a designation, e.g. limits M10x1.5-6g".into(),
                    }));
                };
                done(
                    LimitsJob {
                        designation,
                        allow_nonstandard,
                        json,
                        coating,
                        coating_limits: coating_limits.rule(),
                    }
                    .run()?,
                )
            }
            Command::Verify {
                plan,
                operation,
                gauge_only,
                no_pass_metrics,
                svg,
                html,
                fix,
                json: JsonArg { json },
            } => {
                plan.need_thread("verify")?;
                let mut spec = plan.spec(gauge_only)?;
                spec.metrics = !no_pass_metrics;
                spec.operation = operation.operation;
                let tools = plan.tools.as_deref().map(threadcheck::ToolTable::read).transpose()?;
                done(
                    VerifyJob {
                        spec,
                        threads: plan.thread.clone(),
                        insert_given: plan.insert.is_some(),
                        tools,
                        svg,
                        html,
                        json,
                        fix,
                    }
                    .run()?,
                )
            }
            Command::Capability(c) => {
                c.plan.need_thread("capability")?;
                if c.plan.thread.len() > 1 || c.plan.tools.is_some() {
                    return Err(Error::Input(
                        "capability takes one thread and one insert: --thread once, --insert (not --tools)"
                            .into(),
                    ));
                }
                let spec = threadcheck::CapabilitySpec {
                    verify: threadcheck::VerifySpec {
                        operation: c.operation.operation,
                        ..c.plan.spec(c.gauge_only)?
                    },
                    x_sigma: c.x_sigma,
                    tip_radius_tol: c.tip_radius_tol,
                    wear_per_part: c.wear_per_part,
                    samples: c.samples,
                    seed: c.seed,
                };
                done(CapabilityJob { spec, svg: c.svg, html: c.html, json: c.json.json }.run()?)
            }
            Command::Correct(c) => {
                c.plan.need_thread("correct")?;
                if c.plan.thread.len() > 1 {
                    return Err(Error::Input("correct takes one thread: --thread once".into()));
                }
                if c.plan.tools.is_some() {
                    return Err(Error::Input(
                        "correct reads one insert: give it with --insert (a tool table is for verify)".into(),
                    ));
                }
                let measured = match (c.measured_m, c.wire, c.measured_d2, c.gauge) {
                    (Some(m), Some(wire), _, _) => Some(threadcheck::Measured::OverWires { m, wire }),
                    (_, _, Some(d2), _) => Some(threadcheck::Measured::PitchDiameter(d2)),
                    (_, _, _, Some(g)) => Some(threadcheck::Measured::Gauge(g)),
                    _ => None,
                };
                let verify =
                    threadcheck::VerifySpec { operation: c.operation.operation, ..c.plan.spec(false)? };
                let spec = threadcheck::CorrectSpec { verify, measured, pickup_z: c.pickup_z };
                done(CorrectJob { spec, html: c.html, json: c.json.json, fix: c.fix }.run()?)
            }
            Command::Passes { plan, json: JsonArg { json } } => {
                done(PassesJob { spec: plan.spec(false)?, json }.run()?)
            }
            Command::Compare { plan, modified, json: JsonArg { json }, markdown, html } => {
                plan.need_thread("compare")?;
                let spec = plan.spec(false)?;
                let modified = if modified.is_empty() {
                    let des = threadcheck::parse_designation(
                        &spec.designation,
                        threadcheck::ParseOptions { allow_nonstandard: spec.allow_nonstandard },
                    )?;
                    let half = 0.5 * des.thread.form.flank_angle();
                    vec![half - 0.5, half - 3.0]
                } else {
                    modified
                };
                if plan.units.is_some() {
                    return Err(Error::Input(
                        "compare's table is in mm: --units gives inches in verify's text and pictures".into(),
                    ));
                }
                let choice = threadcheck::CompareChoice {
                    infeed: plan.infeed,
                    schedule: if plan.depths.is_empty() {
                        plan.schedule.clone()
                    } else {
                        Some(Schedule::Explicit(plan.depths.clone()))
                    },
                };
                done(CompareJob { spec, modified, choice, json, markdown, html }.run()?)
            }
            Command::Fit(f) => {
                use threadcheck::FitSide;
                let side = |prog: &Option<PathBuf>,
                            dialect: Option<Dialect>,
                            final_x: Option<f64>,
                            insert: &InsertChoice| {
                    let program = match prog {
                        Some(p) => Some((
                            threadcheck::read_program_text(p)?,
                            p.display().to_string(),
                            dialect_for(dialect, p).0,
                        )),
                        None => None,
                    };
                    Ok::<_, Error>(FitSide { insert: insert.clone(), final_x, program })
                };
                let spec = threadcheck::FitSpec {
                    thread: f.thread,
                    allow_nonstandard: f.allow_nonstandard,
                    bolt: side(&f.bolt_program, f.bolt_dialect, f.bolt_final_x, &f.bolt_insert)?,
                    nut: side(&f.nut_program, f.nut_dialect, f.nut_final_x, &f.nut_insert)?,
                };
                done(FitJob { spec, svg: f.svg, json: f.json.json }.run()?)
            }
            Command::Sweep(a) => {
                if a.min_d > a.max_d {
                    return Err(Error::Input("--min-d must not be above --max-d".into()));
                }
                let mut spec = threadcheck::CatalogueSpec::default();
                (spec.coarse, spec.fine) = match a.series {
                    SeriesArg::Coarse => (true, false),
                    SeriesArg::Fine => (false, true),
                    SeriesArg::All => (true, true),
                };
                (spec.full, spec.partial) = match a.insert {
                    InsertSet::Full => (true, false),
                    InsertSet::Partial => (false, true),
                    InsertSet::Both => (true, true),
                };
                spec.diameters = (a.min_d, a.max_d);
                spec.class = a.class;
                spec.forms = a.form.iter().flat_map(|f| f.forms()).collect();
                spec.forms.dedup();
                spec.internal = a.internal;
                spec.infeeds = a.infeed;
                spec.schedules = a.schedule;
                spec.gauge_only = a.gauge_only;
                SweepJob { spec, json: a.json, export_placements: a.export_placements }.run()
            }
            Command::Mill(m) => {
                let (program, dialect, _) = m.file.read()?;
                let spec = threadcheck::MillSpec {
                    program,
                    dialect,
                    n_order: m.n_order,
                    tool_diameter: m.tool_diameter,
                    target: threadcheck::Target::read(&m.target)?,
                    tolerance: m.tolerance,
                };
                done(MillJob { spec, svg: m.svg, json: m.json.json }.run()?)
            }
            Command::ThreadMill(a) => {
                let (program, dialect, _) = a.file.read()?;
                let spec = threadcheck::ThreadMillSpec {
                    program,
                    dialect,
                    designation: a.thread,
                    allow_nonstandard: a.allow_nonstandard,
                    cutter: a
                        .cutter_diameter
                        .map(|diameter| {
                            threadcheck::Cutter::single_form(diameter, a.cutter_angle, a.cutter_tip_radius)
                                .with_rows(a.cutter_rows, a.cutter_row_pitch)
                        })
                        .transpose()?,
                    tools: a.tools.as_deref().map(threadcheck::ToolTable::read).transpose()?,
                    blank_diameter: a.blank_diameter,
                    comp_radius: a.comp_radius,
                };
                done(threadcheck::ThreadMillJob { spec, svg: a.svg, html: a.html, json: a.json.json }.run()?)
            }
            Command::Tap(a) => {
                let (program, dialect, from) = a.file.read()?;
                let mut reading = threadcheck::ReadOptions { dialect_from: from, ..Default::default() };
                reading.default_units = a.default_units;
                reading.gcode_system = a.gcode_system;
                let spec = threadcheck::TapSpec {
                    program,
                    dialect,
                    reading,
                    tools: threadcheck::ToolTable::read(&a.tools)?,
                    allow_nonstandard: a.allow_nonstandard,
                };
                done(threadcheck::TapJob { spec, svg: a.svg, html: a.html, json: a.json.json }.run()?)
            }
            Command::Serve(a) => {
                let mut options =
                    threadcheck::ServeOptions { bind: a.bind, port: a.port, ..Default::default() };
                if let Some(n) = a.max_in_flight {
                    options.max_in_flight = n as usize;
                }
                options.time_budget = std::time::Duration::from_secs_f64(a.time_budget);
                options.queue_wait = std::time::Duration::from_secs_f64(a.queue_wait);
                options.header_timeout = std::time::Duration::from_secs_f64(a.header_timeout);
                options.body_timeout = std::time::Duration::from_secs_f64(a.body_timeout);
                options.max_connections = a.max_connections as usize;
                options.allow_hosts = a.allow_host.clone();
                threadcheck::serve(options, |line| {
                    use std::io::Write;
                    let mut out = std::io::stdout().lock();
                    let _ = writeln!(out, "{line}");
                    let _ = out.flush();
                })?;
                done((String::new(), Outcome::Pass))
            }
            Command::Report { name, out } => match name {
                ReportName::InfeedComparison => {
                    InfeedReportJob { out: out.clone() }.run()?;
                    done((format!("wrote {}\n", out.join("infeed-comparison.md").display()), Outcome::Pass))
                }
            },
        }
    }
}
