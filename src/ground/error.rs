//! The one error type. Every message is one line that names the bad input and states the domain
//! fact it breaks; the CLI prints it and exits with code 2.

/// Everything that can go wrong before a verdict.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A thread designation that cannot be read.
    #[error(transparent)]
    Designation(#[from] DesignationError),
    /// A G-code program that cannot be read or expanded, with its place.
    #[error("{file}:{line}:{column}: {message}")]
    Program {
        /// File name as given.
        file: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What is wrong.
        message: String,
    },
    /// A TOML file (insert, plan) that cannot be read, with its place.
    #[error("{file}: {message}")]
    File {
        /// File name as given.
        file: String,
        /// What is wrong (with line and column where known).
        message: String,
    },
    /// Geometry that cannot exist or cannot be cut (a tip radius too large, no crest left, …).
    #[error("{0}")]
    Geometry(String),
    /// An option value or combination that makes no sense.
    #[error("{0}")]
    Input(String),
    /// The embedded data is broken (a build defect, never the user's input).
    #[error("embedded data: {0}")]
    Data(String),
    /// Reading or writing a file failed.
    #[error("{path}: {source}")]
    Io {
        /// The path.
        path: String,
        /// The operating system's error.
        #[source]
        source: std::io::Error,
    },
}

impl Error {
    /// An [`Error::Io`] for `path`.
    pub fn io(path: impl std::fmt::Display, source: std::io::Error) -> Error {
        Error::Io { path: path.to_string(), source }
    }
}

/// Shorthand for results in this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// A designation that cannot be read, with the offending part of the text.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("designation '{text}', column {column}{}: {message}", if part.is_empty() { String::new() } else { format!(" ('{part}')") })]
pub struct DesignationError {
    /// The whole designation.
    pub text: String,
    /// 1-based column (in characters) where the bad part starts.
    pub column: usize,
    /// The bad part of the text (may be empty at the end of the text).
    pub part: String,
    /// What is wrong, in domain terms.
    pub message: String,
}
