//! Toolpaths: where the tool tip runs, pass by pass, whoever laid it out. A generated plan
//! ([`passes::PlanSpec`]: infeed, depth schedule, spring passes) and a program read as a control
//! would (`gcode/`) both end here as [`passes::Pass`]es; `geometry/` cuts passes and never
//! needs to know a program (`tests/layout.rs` holds it).
//!
//! Imports only `ground/` and `standards/`.

pub mod passes;
