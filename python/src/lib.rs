//! The compiled half of the Python package `threadcheck`: each function runs the same job as the
//! command line and returns its JSON text; `threadcheck/__init__.py` turns it into dicts.
//! Every error is a `ValueError` with the command line's one-line message.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use threadcheck::Dialect;
use threadcheck::{CapabilityJob, CorrectJob, LimitsJob, Outcome, PassesJob, VerifyJob};
use threadcheck::{ProgramSource, VerifySpec};

fn value_error(e: threadcheck::Error) -> PyErr {
    PyValueError::new_err(e.one_line())
}

/// The plan and program arguments `verify` and `passes` share, as the CLI's `PlanArgs`.
#[allow(clippy::too_many_arguments)]
fn spec(
    threads: &[String],
    program: Option<String>,
    program_name: &str,
    dialect: &str,
    insert: Option<&str>,
    final_x: Option<f64>,
    internal: bool,
    infeed: Option<&str>,
    passes: Option<usize>,
    blank_diameter: Option<f64>,
    allow_nonstandard: bool,
    default_units: Option<&str>,
    main: Option<&str>,
    linuxcnc_release: &str,
) -> Result<VerifySpec, threadcheck::Error> {
    let mut s = VerifySpec::new(threads.first().map_or("", String::as_str));
    s.internal = internal;
    s.allow_nonstandard = allow_nonstandard;
    s.insert = insert.unwrap_or("partial").parse()?;
    s.infeed = infeed.map(str::parse).transpose()?;
    if passes == Some(0) {
        return Err(threadcheck::Error::Input("passes = 0: a thread needs at least one pass".into()));
    }
    s.passes = passes;
    for (v, what) in [(final_x, "final_x"), (blank_diameter, "blank_diameter")] {
        if v.is_some_and(|x| !x.is_finite()) {
            return Err(threadcheck::Error::Input(format!("{what} is not a finite number")));
        }
    }
    s.final_x = final_x;
    s.blank_diameter = blank_diameter;
    if let Some(text) = program {
        s.program = Some((ProgramSource::text(program_name, text), dialect.parse::<Dialect>()?));
    }
    s.reading.default_units = default_units.map(str::parse).transpose()?;
    s.reading.main = main
        .map(|m| {
            let digits = m.strip_prefix(['O', 'o']).unwrap_or(m);
            digits.parse::<u32>().ok().filter(|_| !digits.starts_with('+')).ok_or_else(|| {
                threadcheck::Error::Input(format!("main = '{m}' is not an O-program number such as O3101"))
            })
        })
        .transpose()?;
    s.reading.linuxcnc = linuxcnc_release.parse()?;
    Ok(s)
}

/// `verify --json -` (`command = "verify"`), `passes --json`, `correct --json` or
/// `capability --json`: returns the JSON text and whether the job passed. They take the same
/// plan and program arguments; `correct` and `capability` their own too.
#[pyfunction]
#[pyo3(signature = (command, threads, program=None, dialect="fanuc", insert=None, final_x=None,
    internal=false, infeed=None, passes=None, blank_diameter=None, gauge_only=false,
    allow_nonstandard=false, program_name="<program>", default_units=None, main=None,
    linuxcnc_release="current", coating=0.0, measured_m=None, wire=None, measured_d2=None,
    gauge=None, pickup_z=None, x_sigma=0.0, tip_radius_tol=0.0, wear_per_part=0.0,
    samples=10000, seed=1))]
#[allow(clippy::too_many_arguments)]
fn job_json(
    py: Python<'_>,
    command: &str,
    threads: Vec<String>,
    program: Option<String>,
    dialect: &str,
    insert: Option<&str>,
    final_x: Option<f64>,
    internal: bool,
    infeed: Option<&str>,
    passes: Option<usize>,
    blank_diameter: Option<f64>,
    gauge_only: bool,
    allow_nonstandard: bool,
    program_name: &str,
    default_units: Option<&str>,
    main: Option<&str>,
    linuxcnc_release: &str,
    coating: f64,
    measured_m: Option<f64>,
    wire: Option<f64>,
    measured_d2: Option<f64>,
    gauge: Option<&str>,
    pickup_z: Option<f64>,
    x_sigma: f64,
    tip_radius_tol: f64,
    wear_per_part: f64,
    samples: usize,
    seed: u64,
) -> PyResult<(String, bool)> {
    let run = || -> Result<(String, bool), threadcheck::Error> {
        let verify = match command {
            "verify" | "correct" | "capability" => true,
            "passes" => false,
            other => {
                return Err(threadcheck::Error::Input(format!(
                    "unknown job '{other}': expected verify, passes, correct or capability"
                )))
            }
        };
        if verify && threads.is_empty() {
            return Err(threadcheck::Error::Input(
                "verify needs a thread with a class, e.g. M10x1.5-6g".into(),
            ));
        }
        if !verify && threads.is_empty() && program.is_none() {
            return Err(threadcheck::Error::Input(
                "passes needs a thread (e.g. M10x1.5-6g) or a program".into(),
            ));
        }
        if threads.len() > 1 && program.is_none() {
            return Err(threadcheck::Error::Input(
                "several threads are given: only a program with several threads takes one per operation"
                    .into(),
            ));
        }
        let mut spec = spec(
            &threads,
            program.clone(),
            program_name,
            dialect,
            insert,
            final_x,
            internal,
            infeed,
            passes,
            blank_diameter,
            allow_nonstandard,
            default_units,
            main,
            linuxcnc_release,
        )?;
        spec.gauge_only = gauge_only;
        spec.coating = coating;
        let one = |what: &str| {
            if threads.len() > 1 {
                Err(threadcheck::Error::Input(format!("{what} takes one thread")))
            } else {
                Ok(())
            }
        };
        let (text, outcome) = if command == "correct" {
            one("correct")?;
            let measured = match (measured_m, wire, measured_d2, gauge) {
                (Some(m), Some(wire), None, None) => Some(threadcheck::Measured::OverWires { m, wire }),
                (Some(_), None, _, _) | (None, Some(_), _, _) => {
                    return Err(threadcheck::Error::Input("measured_m and wire go together".into()))
                }
                (None, None, Some(d2), None) => Some(threadcheck::Measured::PitchDiameter(d2)),
                (None, None, None, Some(g)) => Some(threadcheck::Measured::Gauge(g.parse()?)),
                (None, None, None, None) => None,
                _ => {
                    return Err(threadcheck::Error::Input(
                        "give one measurement: measured_m with wire, measured_d2 or gauge".into(),
                    ))
                }
            };
            let spec = threadcheck::CorrectSpec { verify: spec, measured, pickup_z };
            CorrectJob { spec, html: None, json: Some("-".into()), fix: None }.run()?
        } else if command == "capability" {
            one("capability")?;
            let spec = threadcheck::CapabilitySpec {
                verify: spec,
                x_sigma,
                tip_radius_tol,
                wear_per_part,
                samples,
                seed,
            };
            CapabilityJob { spec, svg: None, html: None, json: Some("-".into()) }.run()?
        } else if verify {
            VerifyJob {
                spec,
                threads: threads.clone(),
                insert_given: insert.is_some(),
                tools: None,
                svg: None,
                html: None,
                json: Some("-".into()),
                fix: None,
            }
            .run()?
        } else {
            PassesJob { spec, json: Some("-".into()) }.run()?
        };
        Ok((text, outcome == Outcome::Pass))
    };
    py.detach(run).map_err(value_error)
}

/// `threadcheck limits D --json`.
#[pyfunction]
#[pyo3(signature = (designation, allow_nonstandard=false, coating=0.0))]
fn limits_json(
    py: Python<'_>,
    designation: String,
    allow_nonstandard: bool,
    coating: f64,
) -> PyResult<String> {
    py.detach(|| LimitsJob { designation, allow_nonstandard, json: Some("-".into()), coating }.run())
        .map(|(text, _)| text)
        .map_err(value_error)
}

/// `threadcheck fit --json`: a bolt and a nut, each from a program's text or a plan.
#[pyfunction]
#[pyo3(signature = (thread, allow_nonstandard=false, bolt_program=None, bolt_dialect="fanuc",
    bolt_final_x=None, bolt_insert="partial", nut_program=None, nut_dialect="fanuc", nut_final_x=None,
    nut_insert="partial"))]
#[allow(clippy::too_many_arguments)]
fn fit_json(
    py: Python<'_>,
    thread: String,
    allow_nonstandard: bool,
    bolt_program: Option<String>,
    bolt_dialect: &str,
    bolt_final_x: Option<f64>,
    bolt_insert: &str,
    nut_program: Option<String>,
    nut_dialect: &str,
    nut_final_x: Option<f64>,
    nut_insert: &str,
) -> PyResult<(String, bool)> {
    let run = || -> Result<(String, bool), threadcheck::Error> {
        let side = |program: Option<String>, dialect: &str, final_x: Option<f64>, insert: &str, who: &str| {
            if program.is_some() && final_x.is_some() {
                return Err(threadcheck::Error::Input(format!(
                    "{who}_program and {who}_final_x exclude each other: the program sets the passes"
                )));
            }
            let program = match program {
                Some(text) => Some((text, format!("<{who} program>"), dialect.parse::<Dialect>()?)),
                None => None,
            };
            Ok(threadcheck::FitSide { insert: insert.parse()?, final_x, program })
        };
        let spec = threadcheck::FitSpec {
            thread,
            allow_nonstandard,
            bolt: side(bolt_program, bolt_dialect, bolt_final_x, bolt_insert, "bolt")?,
            nut: side(nut_program, nut_dialect, nut_final_x, nut_insert, "nut")?,
        };
        let (text, outcome) = threadcheck::FitJob { spec, svg: None, json: Some("-".into()) }.run()?;
        Ok((text, outcome == Outcome::Pass))
    };
    py.detach(run).map_err(value_error)
}

/// `threadcheck compare --json`: every infeed strategy on one thread (or the infeed and schedule
/// given).
#[pyfunction]
#[pyo3(signature = (thread, insert=None, final_x=None, internal=false, allow_nonstandard=false,
    infeed=None, schedule=None, modified=None))]
#[allow(clippy::too_many_arguments)]
fn compare_json(
    py: Python<'_>,
    thread: String,
    insert: Option<&str>,
    final_x: Option<f64>,
    internal: bool,
    allow_nonstandard: bool,
    infeed: Option<&str>,
    schedule: Option<&str>,
    modified: Option<Vec<f64>>,
) -> PyResult<String> {
    let run = || -> Result<String, threadcheck::Error> {
        let threads = [thread.clone()];
        let spec = spec(
            &threads,
            None,
            "<program>",
            "fanuc",
            insert,
            final_x,
            internal,
            None,
            None,
            None,
            allow_nonstandard,
            None,
            None,
            "current",
        )?;
        let choice = threadcheck::CompareChoice {
            infeed: infeed.map(str::parse).transpose()?,
            schedule: schedule.map(str::parse).transpose()?,
        };
        let modified = match modified {
            Some(m) => m,
            None => {
                let des =
                    threadcheck::parse_designation(&thread, threadcheck::ParseOptions { allow_nonstandard })?;
                let half = 0.5 * des.thread.form.flank_angle();
                vec![half - 0.5, half - 3.0]
            }
        };
        let job = threadcheck::CompareJob {
            spec,
            modified,
            choice,
            json: Some("-".into()),
            markdown: None,
            html: None,
        };
        Ok(job.run()?.0)
    };
    py.detach(run).map_err(value_error)
}

/// `threadcheck mill --json`: a milling program's text against a target given as TOML text.
#[pyfunction]
#[pyo3(signature = (program, target, tool_diameter, dialect="fanuc", tolerance=0.01, n_order=false,
    program_name="<program>"))]
#[allow(clippy::too_many_arguments)]
fn mill_json(
    py: Python<'_>,
    program: String,
    target: String,
    tool_diameter: f64,
    dialect: &str,
    tolerance: f64,
    n_order: bool,
    program_name: &str,
) -> PyResult<(String, bool)> {
    let run = || -> Result<(String, bool), threadcheck::Error> {
        let spec = threadcheck::MillSpec {
            program: (program, program_name.to_string()),
            dialect: dialect.parse::<Dialect>()?,
            n_order,
            tool_diameter,
            target: threadcheck::Target::from_toml(&target, "<target>")?,
            tolerance,
        };
        let (text, outcome) = threadcheck::MillJob { spec, svg: None, json: Some("-".into()) }.run()?;
        Ok((text, outcome == Outcome::Pass))
    };
    py.detach(run).map_err(value_error)
}

#[pymodule]
fn _threadcheck(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(job_json, m)?)?;
    m.add_function(wrap_pyfunction!(fit_json, m)?)?;
    m.add_function(wrap_pyfunction!(compare_json, m)?)?;
    m.add_function(wrap_pyfunction!(mill_json, m)?)?;
    m.add_function(wrap_pyfunction!(limits_json, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
