//! The integration tests: one binary, one module per area, shared helpers in `util.rs`.
//!
//! Tests read reference data only from `tests/data/` (each file names its sources), never from
//! `../shared`.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod bad_inputs;
mod before_machine;
mod browser;
mod closing;
mod controls;
mod docs;
mod forms;
mod gcode;
mod infeed_comparison;
mod integrations;
mod lathes;
mod layout;
mod limits;
mod linuxcnc;
mod linuxcnc_holes;
mod machining;
mod messages;
mod mill;
mod naming;
mod process;
mod programs;
mod properties;
mod regressions;
pub mod serve;
mod settings;
mod shop;
mod sweep;
mod tapping;
mod threadmill;
mod util;
mod verify;
mod whole;

pub use util::*;
