//! How a thread is made: the process every report and finding names (its own file, so that
//! the program's verification and the checks it gathers both name it without importing each
//! other).

use serde::Serialize;

/// How a thread is made.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Process {
    /// Turned on a lathe: threading cycles and G32/G33 chains.
    Turned,
    /// Cut by a tap in a tapping cycle.
    Tapped,
    /// Milled by a thread mill on helices.
    Milled,
}

impl Process {
    /// The word the reports use.
    pub fn name(self) -> &'static str {
        match self {
            Process::Turned => "turned",
            Process::Tapped => "tapped",
            Process::Milled => "milled",
        }
    }
}
