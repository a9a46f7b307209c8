//! The `threadcheck` command line: parses arguments into a validated job from the library, runs
//! it, and maps the outcome to the exit code (0 pass, 1 out of tolerance, 2 error).

use clap::{Args, Parser, Subcommand};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use threadcheck::app::{
    parse_infeed, parse_insert, parse_len, parse_schedule, CompareJob, LimitsJob, Outcome, PassesJob,
    VerifyJob,
};
use threadcheck::verify::VerifySpec;

/// Predicts the thread a CNC lathe program cuts and checks it against its standard.
#[derive(Parser)]
#[command(name = "threadcheck", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Limits of size of a designation (ISO 965-1, BS 84, ISO 228-1).
    Limits {
        /// Designation, e.g. M10x1.25-6g, M10-6H/6g, "BSF 3/8 medium", "G1/2 A", "1/4-20 UNC-2A".
        #[arg(conflicts_with = "thread")]
        designation: Option<String>,
        /// The designation as an option, as the other commands take it.
        #[arg(long)]
        thread: Option<String>,
        /// JSON: on stdout instead of the table (`--json` or `--json -`), or written to FILE.
        #[arg(long, value_name = "FILE|-", num_args = 0..=1, default_missing_value = "-")]
        json: Option<String>,
        /// Accept a diameter/pitch pair outside the standard series.
        #[arg(long)]
        allow_nonstandard: bool,
    },
    /// Cut the thread in the computer and check it against its class.
    Verify {
        #[command(flatten)]
        plan: PlanArgs,
        /// Leave form checks (root radius, minor-diameter zone, flank angles) out of the verdict.
        #[arg(long)]
        gauge_only: bool,
        /// Skip the per-pass chip and edge metrics (polygon booleans): a faster verdict.
        #[arg(long)]
        no_pass_metrics: bool,
        /// Write an SVG cross-section to this file.
        #[arg(long, value_name = "FILE")]
        svg: Option<PathBuf>,
        /// JSON: on stdout instead of the text (`--json` or `--json -`), or written to FILE.
        #[arg(long, value_name = "FILE|-", num_args = 0..=1, default_missing_value = "-")]
        json: Option<String>,
    },
    /// The same thread with radial, flank, modified-flank and alternating infeed.
    Compare {
        #[command(flatten)]
        plan: PlanArgs,
        /// Modified-flank angles, degrees (comma-separated); default half the thread angle less
        /// 0.5° and less 3° (29.5,27 for 60° threads, 14.5,12 for trapezoidal).
        #[arg(long, value_name = "ANGLES")]
        modified: Option<String>,
        /// JSON (every verify report and the per-strategy figures): on stdout instead of the
        /// table (`--json` or `--json -`), or written to FILE.
        #[arg(long, value_name = "FILE|-", num_args = 0..=1, default_missing_value = "-")]
        json: Option<String>,
        /// Write the table as Markdown to this file.
        #[arg(long, value_name = "FILE")]
        markdown: Option<PathBuf>,
    },
    /// Verify the catalogue in parallel: ISO 261 (M1–M68, coarse and fine) by default, every
    /// form's series with --form all.
    Sweep {
        /// Forms (comma-separated): iso-metric, unified, trapezoidal, acme, whitworth,
        /// bsp-parallel, npt, iso7-taper, or all.
        #[arg(long, default_value = "iso-metric")]
        form: String,
        /// Also the internal threads, in each form's medium internal class.
        #[arg(long)]
        internal: bool,
        /// coarse | fine | all
        #[arg(long, default_value = "all")]
        series: String,
        /// Smallest nominal diameter, mm.
        #[arg(long, default_value_t = 1.0)]
        min_d: f64,
        /// Largest nominal diameter, mm.
        #[arg(long, default_value_t = 68.0)]
        max_d: f64,
        /// Tolerance class of the external thread.
        #[arg(long, default_value = "6g")]
        class: String,
        /// full | partial | both
        #[arg(long, default_value = "both")]
        insert: String,
        /// Comma-separated infeeds: radial, flank (half the thread angle), modified (0.5° less),
        /// alternating.
        #[arg(long, default_value = "radial,flank,modified,alternating")]
        infeed: String,
        /// Comma-separated schedules: constant-area, constant-depth, sandvik.
        #[arg(long, default_value = "constant-area,constant-depth")]
        schedule: String,
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
    },
    /// Regenerate a committed report (`infeed-comparison`).
    Report {
        /// Which report: infeed-comparison.
        name: String,
        /// Folder to write it and its pictures into.
        #[arg(long, default_value = "reports")]
        out: PathBuf,
    },
    /// A bolt and a nut cut in the computer and assembled: do they screw together?
    Fit {
        /// A fit designation, e.g. M10x1.5-6H/6g.
        #[arg(long)]
        thread: String,
        /// Accept a diameter/pitch pair outside the standard series.
        #[arg(long)]
        allow_nonstandard: bool,
        /// The bolt's program (else a generated plan).
        #[arg(long, value_name = "FILE")]
        bolt_program: Option<PathBuf>,
        /// Its dialect.
        #[arg(long, default_value = "fanuc")]
        bolt_dialect: String,
        /// The nut's program (else a generated plan).
        #[arg(long, value_name = "FILE")]
        nut_program: Option<PathBuf>,
        /// Its dialect.
        #[arg(long, default_value = "fanuc")]
        nut_dialect: String,
        /// The bolt plan's last tip diameter (default: mid-tolerance).
        #[arg(long, value_name = "DIA", allow_hyphen_values = true)]
        bolt_final_x: Option<String>,
        /// The nut plan's last tip diameter (default: mid-tolerance).
        #[arg(long, value_name = "DIA", allow_hyphen_values = true)]
        nut_final_x: Option<String>,
        /// The bolt's insert: full | partial[:TIP_RADIUS] | FILE.toml.
        #[arg(long, default_value = "partial")]
        bolt_insert: String,
        /// The nut's insert.
        #[arg(long, default_value = "partial")]
        nut_insert: String,
        /// Write an SVG of the pair.
        #[arg(long, value_name = "FILE")]
        svg: Option<PathBuf>,
        /// JSON: on stdout instead of the text (`--json` or `--json -`), or written to FILE.
        #[arg(long, value_name = "FILE|-", num_args = 0..=1, default_missing_value = "-")]
        json: Option<String>,
    },
    /// Print the expanded pass plan.
    Passes {
        #[command(flatten)]
        plan: PlanArgs,
        /// JSON: on stdout instead of the table (`--json` or `--json -`), or written to FILE.
        #[arg(long, value_name = "FILE|-", num_args = 0..=1, default_missing_value = "-")]
        json: Option<String>,
    },
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
    insert: Option<String>,
    /// Tool table: which insert each T number of the program holds (TOML).
    #[arg(long, value_name = "FILE.toml", requires = "program")]
    tools: Option<PathBuf>,
    /// radial | flank[:ANGLE] | alternating[:ANGLE] (default: flank at half the thread angle − 0.5°)
    #[arg(long)]
    infeed: Option<String>,
    /// Number of cutting passes (default about 3.5 + 2·P).
    #[arg(long, conflicts_with = "first_depth")]
    passes: Option<usize>,
    /// Depth of the first pass, mm (sets the pass count).
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    first_depth: Option<String>,
    /// Smallest radial step, mm.
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    min_depth: Option<String>,
    /// Finishing allowance, mm.
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    finish: Option<String>,
    /// Spring (idle) passes at full depth.
    #[arg(long, default_value_t = 0)]
    spring: usize,
    /// constant-area | constant-depth | sandvik
    #[arg(long, default_value = "constant-area")]
    schedule: String,
    /// Explicit cumulative radial depths, mm, e.g. 0.2,0.35,0.45 (instead of a schedule).
    #[arg(long, value_name = "LIST", conflicts_with_all = ["passes", "first_depth"])]
    depths: Option<String>,
    /// Taper: diameter change per mm of travel, e.g. 0.0625 for 1:16 (passes only).
    #[arg(long, value_name = "RATIO", allow_hyphen_values = true)]
    taper: Option<String>,
    /// Run-out chamfer at the thread end, in leads.
    #[arg(long, value_name = "LEADS")]
    chamfer: Option<String>,
    /// Tip diameter of the last pass (default: what puts the pitch diameter mid-tolerance).
    #[arg(long, value_name = "DIA", allow_hyphen_values = true)]
    final_x: Option<String>,
    /// Blank (external) or bore (internal) diameter, mm.
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    blank_diameter: Option<String>,
    /// Take the passes from this G-code program.
    #[arg(long, value_name = "FILE")]
    program: Option<PathBuf>,
    /// A machine profile for the process checks of a program: FILE.toml or training-lathe.
    #[arg(long, value_name = "FILE.toml|training-lathe", requires = "program")]
    machine: Option<String>,
    /// The insert's side clearance angle, degrees: checks the leading flank against the helix.
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    clearance_angle: Option<String>,
    /// Lengths in the text and the SVG: mm, or mm with inches beside them.
    #[arg(long, value_parser = ["mm", "inch"], default_value = "mm")]
    units: String,
    /// fanuc | haas | sinumerik | linuxcnc | dyna
    #[arg(long, default_value = "fanuc", requires = "program")]
    dialect: String,
}

impl PlanArgs {
    fn spec(&self, gauge_only: bool) -> Result<VerifySpec, threadcheck::Error> {
        let mut s = VerifySpec::new(self.thread.first().map_or("", String::as_str));
        s.internal = self.internal;
        s.allow_nonstandard = self.allow_nonstandard;
        s.insert = parse_insert(self.insert.as_deref().unwrap_or("partial"))?;
        if let Some(i) = &self.infeed {
            // The half angle depends on the form; parse it once the designation is known.
            let des = threadcheck::parse_designation(
                &s.designation,
                threadcheck::ParseOptions { allow_nonstandard: self.allow_nonstandard },
            )?;
            s.infeed = Some(parse_infeed(i, 0.5 * des.thread.form.flank_angle())?);
        }
        if self.passes == Some(0) {
            return Err(threadcheck::Error::Input("--passes 0: a thread needs at least one pass".into()));
        }
        s.passes = self.passes;
        let opt = |v: &Option<String>, what: &str| v.as_deref().map(|x| parse_len(x, what)).transpose();
        s.first_depth = opt(&self.first_depth, "--first-depth")?;
        s.min_depth = opt(&self.min_depth, "--min-depth")?.unwrap_or(0.0);
        s.finish = opt(&self.finish, "--finish")?.unwrap_or(0.0);
        s.spring = self.spring;
        s.schedule = parse_schedule(&self.schedule)?;
        if let Some(list) = &self.depths {
            let d = list.split(',').map(|x| parse_len(x, "--depths")).collect::<Result<Vec<f64>, _>>()?;
            s.schedule = threadcheck::passes::Schedule::Explicit(d);
        }
        s.taper = opt(&self.taper, "--taper")?.unwrap_or(0.0);
        s.chamfer_leads = opt(&self.chamfer, "--chamfer")?.unwrap_or(0.0);
        s.final_x = opt(&self.final_x, "--final-x")?;
        s.blank_diameter = opt(&self.blank_diameter, "--blank-diameter")?;
        s.gauge_only = gauge_only;
        s.machine = self.machine.as_deref().map(threadcheck::process::MachineProfile::read).transpose()?;
        s.clearance_angle = opt(&self.clearance_angle, "--clearance-angle")?;
        s.units = if self.units == "inch" {
            threadcheck::verify::Units::Inch
        } else {
            threadcheck::verify::Units::Mm
        };
        if let Some(p) = &self.program {
            s.program = Some((
                threadcheck::verify::ProgramSource::File(p.clone()),
                threadcheck::gcode::Dialect::parse(&self.dialect)?,
            ));
        }
        Ok(s)
    }
}

fn run(cli: Cli) -> Result<Outcome, threadcheck::Error> {
    let (text, outcome) = match cli.command {
        Command::Limits { designation, thread, json, allow_nonstandard } => {
            let Some(designation) = designation.or(thread) else {
                return Err(threadcheck::Error::Input(match json.as_deref() {
                    Some(v) if v != "-" => format!(
                        "limits needs a designation: --json took '{v}' as its file; write `limits {v} --json`"
                    ),
                    _ => "limits needs a designation, e.g. limits M10x1.5-6g".into(),
                }));
            };
            LimitsJob { designation, allow_nonstandard, json }.run()?
        }
        Command::Verify { plan, gauge_only, no_pass_metrics, svg, json } => {
            if plan.thread.is_empty() {
                return Err(threadcheck::Error::Input(
                    "verify needs --thread with a class, e.g. --thread M10x1.5-6g".into(),
                ));
            }
            if plan.thread.len() > 1 && plan.program.is_none() {
                return Err(threadcheck::Error::Input(
                    "--thread is given more than once: only a program with several threads takes one per operation".into(),
                ));
            }
            let mut spec = plan.spec(gauge_only)?;
            spec.metrics = !no_pass_metrics;
            let tools = plan.tools.as_deref().map(threadcheck::tools::ToolTable::read).transpose()?;
            VerifyJob {
                spec,
                threads: plan.thread.clone(),
                insert_given: plan.insert.is_some(),
                tools,
                svg,
                json,
            }
            .run()?
        }
        Command::Passes { plan, json } => PassesJob { spec: plan.spec(false)?, json }.run()?,
        Command::Fit {
            thread,
            allow_nonstandard,
            bolt_program,
            bolt_dialect,
            nut_program,
            nut_dialect,
            bolt_final_x,
            nut_final_x,
            bolt_insert,
            nut_insert,
            svg,
            json,
        } => {
            use threadcheck::fit::FitSide;
            let side = |prog: &Option<PathBuf>,
                        dialect: &str,
                        x: &Option<String>,
                        insert: &str,
                        what: &str| {
                let program = match prog {
                    Some(p) => Some((
                        threadcheck::verify::read_program_text(p)?,
                        p.display().to_string(),
                        threadcheck::gcode::Dialect::parse(dialect)?,
                    )),
                    None => None,
                };
                if program.is_some() && x.is_some() {
                    return Err(threadcheck::Error::Input(format!(
                        "--{what}-final-x and --{what}-program exclude each other: the program sets the passes"
                    )));
                }
                Ok::<_, threadcheck::Error>(FitSide {
                    insert: parse_insert(insert)?,
                    final_x: x.as_deref().map(|v| parse_len(v, &format!("--{what}-final-x"))).transpose()?,
                    program,
                })
            };
            let spec = threadcheck::fit::FitSpec {
                thread,
                allow_nonstandard,
                bolt: side(&bolt_program, &bolt_dialect, &bolt_final_x, &bolt_insert, "bolt")?,
                nut: side(&nut_program, &nut_dialect, &nut_final_x, &nut_insert, "nut")?,
            };
            threadcheck::app::FitJob { spec, svg, json }.run()?
        }
        Command::Sweep {
            form,
            internal,
            series,
            min_d,
            max_d,
            class,
            insert,
            infeed,
            schedule,
            gauge_only,
            json,
            export_placements,
        } => {
            let mut spec = threadcheck::catalogue::CatalogueSpec::default();
            (spec.coarse, spec.fine) = one_or_both("series", &series, ["coarse", "fine", "all"])?;
            if !(min_d.is_finite() && max_d.is_finite() && min_d <= max_d) {
                return Err(threadcheck::Error::Input(
                    "--min-d and --max-d must be finite with min ≤ max".into(),
                ));
            }
            spec.diameters = (min_d, max_d);
            spec.class = class;
            (spec.full, spec.partial) = one_or_both("insert", &insert, ["full", "partial", "both"])?;
            use threadcheck::catalogue::InfeedKind;
            spec.forms = form
                .split(',')
                .map(|f| match f.trim() {
                    "iso-metric" | "metric" => Ok(vec![threadcheck::ThreadForm::IsoMetric]),
                    "unified" => Ok(vec![threadcheck::ThreadForm::Unified]),
                    "trapezoidal" => Ok(vec![threadcheck::ThreadForm::Trapezoidal]),
                    "acme" => Ok(vec![threadcheck::ThreadForm::Acme]),
                    "whitworth" => Ok(vec![threadcheck::ThreadForm::Whitworth]),
                    "bsp-parallel" | "bsp" => Ok(vec![threadcheck::ThreadForm::BspParallel]),
                    "npt" => Ok(vec![threadcheck::ThreadForm::Npt]),
                    "iso7-taper" | "iso7" => Ok(vec![threadcheck::ThreadForm::Iso7Taper]),
                    "all" => Ok(threadcheck::catalogue::CatalogueSpec::all_forms().forms),
                    other => Err(threadcheck::Error::Input(format!(
                        "--form '{other}': expected iso-metric, unified, trapezoidal, acme, whitworth, bsp-parallel, npt, iso7-taper or all"
                    ))),
                })
                .collect::<Result<Vec<_>, _>>()?
                .concat();
            spec.internal = internal;
            spec.infeeds = infeed
                .split(',')
                .map(|i| match i.trim() {
                    "radial" => Ok(InfeedKind::Radial),
                    "flank" => Ok(InfeedKind::Flank),
                    "modified" => Ok(InfeedKind::Modified),
                    "alternating" => Ok(InfeedKind::Alternating),
                    other => Err(threadcheck::Error::Input(format!(
                        "--infeed '{other}': expected radial, flank, modified or alternating"
                    ))),
                })
                .collect::<Result<_, _>>()?;
            spec.schedules =
                schedule.split(',').map(|s| parse_schedule(s.trim())).collect::<Result<_, _>>()?;
            spec.gauge_only = gauge_only;
            let (out, summary, outcome) =
                threadcheck::app::SweepJob { spec, json: json.is_some(), export_placements }.run()?;
            match json.as_deref() {
                Some("-") => {
                    eprint!("{summary}");
                    (out, outcome)
                }
                Some(path) => {
                    threadcheck::output::write_atomic(std::path::Path::new(path), out.as_bytes())?;
                    (summary, outcome)
                }
                None => (out + &summary, outcome),
            }
        }
        Command::Report { name, out } => {
            if name != "infeed-comparison" {
                return Err(threadcheck::Error::Input(format!(
                    "unknown report '{name}': expected infeed-comparison"
                )));
            }
            threadcheck::compare::write_report(&out)?;
            (format!("wrote {}\n", out.join("infeed-comparison.md").display()), Outcome::Pass)
        }
        Command::Compare { plan, modified, json, markdown } => {
            if plan.thread.is_empty() {
                return Err(threadcheck::Error::Input(
                    "compare needs --thread with a class, e.g. --thread M10x1.5-6g".into(),
                ));
            }
            let spec = plan.spec(false)?;
            let modified = match modified {
                Some(m) => m
                    .split(',')
                    .filter(|s| !s.trim().is_empty())
                    .map(|a| parse_len(a, "--modified"))
                    .collect::<Result<Vec<f64>, _>>()?,
                None => {
                    let des = threadcheck::parse_designation(
                        &spec.designation,
                        threadcheck::ParseOptions { allow_nonstandard: spec.allow_nonstandard },
                    )?;
                    let half = 0.5 * des.thread.form.flank_angle();
                    vec![half - 0.5, half - 3.0]
                }
            };
            CompareJob { spec, modified, json, markdown }.run()?
        }
    };
    let mut out = std::io::stdout().lock();
    // A closed pipe (`| head`) is not an error worth a message.
    let _ = out.write_all(text.as_bytes());
    Ok(outcome)
}

/// A two-way option: `[first, second, both]` becomes (first, second) flags.
fn one_or_both(option: &str, value: &str, names: [&str; 3]) -> Result<(bool, bool), threadcheck::Error> {
    let [a, b, both] = names;
    match value {
        v if v == a => Ok((true, false)),
        v if v == b => Ok((false, true)),
        v if v == both => Ok((true, true)),
        _ => Err(threadcheck::Error::Input(format!("--{option} '{value}': expected {a}, {b} or {both}"))),
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(o) => ExitCode::from(o.exit_code() as u8),
        Err(e) => {
            // One line, whatever the message carried.
            eprintln!("threadcheck: error: {}", e.to_string().replace('\n', " "));
            ExitCode::from(2)
        }
    }
}
