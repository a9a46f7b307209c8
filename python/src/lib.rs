//! The compiled half of the Python package `threadcheck`: `run`, that hands a command's keyword
//! arguments (as a JSON object) to the library's request door, the same one `threadcheck serve`
//! answers through, so the command line, the API and Python share one validation; and
//! `write_files`, the command line's own output writer. `threadcheck/__init__.py` builds the
//! arguments and turns the JSON into dicts. Every error is a `ValueError` with the command
//! line's one-line message.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use threadcheck::{run_request, Audience, Command, Document, Files, Outcome};

fn value_error(e: threadcheck::Error) -> PyErr {
    PyValueError::new_err(e.one_line_for(Audience::Api))
}

/// Runs `command` (`verify`, `passes`, `limits`, `compare`, `fit`, `correct`, `capability`,
/// `mill`, `tap`, `thread-mill`) on `args`, a JSON object of its keyword arguments, and returns `document` (`json`,
/// `text`, `svg`, `html`, `fix`) and whether the job passed. Files named in the arguments (an
/// insert, a tool table's inserts) are the caller's own and may be read.
#[pyfunction]
fn run(py: Python<'_>, command: &str, document: &str, args: &str) -> PyResult<(String, bool)> {
    let document: Document = document.parse().map_err(value_error)?;
    let (command, args) = (command.to_string(), args.to_string());
    // The files this run reads are the ones `write_files` will not replace.
    threadcheck::forget_reads();
    py.detach(move || run_request(&command, document, &args, Files::Allowed, threadcheck::Audience::Api))
        .map(|(body, outcome)| (body, outcome == Outcome::Pass))
        .map_err(value_error)
}

/// The keyword arguments `command` takes: the same fields the command line's flags and the
/// API's keys are read into (the package's functions are checked against them).
#[pyfunction]
fn keys(command: &str) -> PyResult<Vec<&'static str>> {
    Command::keys(command).map_err(value_error)
}

/// Writes `files` (path, text) as the command line writes its outputs: none that the last
/// `run` read (a program, an insert, a tool table and what it names) or that shares a file with
/// another, all or none, atomically; devices and FIFOs in place, links followed, modes kept.
#[pyfunction]
fn write_files(py: Python<'_>, files: Vec<(String, String)>) -> PyResult<()> {
    let outputs: Vec<(std::path::PathBuf, Vec<u8>)> =
        files.into_iter().map(|(p, t)| (std::path::PathBuf::from(p), t.into_bytes())).collect();
    py.detach(move || threadcheck::write_files(&outputs)).map_err(value_error)
}

#[pymodule]
fn _threadcheck(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add_function(wrap_pyfunction!(write_files, m)?)?;
    m.add_function(wrap_pyfunction!(keys, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
