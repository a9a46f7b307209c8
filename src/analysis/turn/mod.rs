//! A turned thread on a lathe, `verify`'s pipeline: the spec (`spec`) resolved (`resolve`), the
//! passes (`passes`) swept, the groove measured and checked (`core`), a program's turned threads
//! (`program`); the plan read back from the passes (`cut_plan`), the lead against the
//! designation's (`lead`) and the correction in the program's words (`correction`).

pub mod core;
pub mod correction;
pub mod cut_plan;
pub mod lead;
pub mod passes;
pub mod program;
pub mod recut;
pub mod resolve;
pub mod spec;

pub use passes::*;
pub use program::*;
pub(crate) use recut::Recut;
pub use resolve::*;
pub use spec::*;
