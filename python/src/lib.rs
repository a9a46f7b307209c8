//! The compiled half of the Python package `threadcheck`: one function, `run`, that hands a
//! command's keyword arguments (as a JSON object) to the library's request door, the same one
//! `threadcheck serve` answers through, so the command line, the API and Python share one
//! validation. `threadcheck/__init__.py` builds the arguments and turns the JSON into dicts.
//! Every error is a `ValueError` with the command line's one-line message.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use threadcheck::{run_request, Command, Document, Files, Outcome};

fn value_error(e: threadcheck::Error) -> PyErr {
    PyValueError::new_err(e.one_line())
}

/// Runs `command` (`verify`, `passes`, `limits`, `compare`, `fit`, `correct`, `capability`,
/// `mill`) on `args`, a JSON object of its keyword arguments, and returns `document` (`json`,
/// `text`, `svg`, `html`, `fix`) and whether the job passed. Files named in the arguments (an
/// insert, a tool table's inserts) are the caller's own and may be read.
#[pyfunction]
fn run(py: Python<'_>, command: &str, document: &str, args: &str) -> PyResult<(String, bool)> {
    let command: Command = command.parse().map_err(value_error)?;
    let document: Document = document.parse().map_err(value_error)?;
    let args = args.to_string();
    py.detach(move || run_request(command, document, &args, Files::Allowed))
        .map(|a| (a.body, a.outcome == Outcome::Pass))
        .map_err(value_error)
}

#[pymodule]
fn _threadcheck(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
