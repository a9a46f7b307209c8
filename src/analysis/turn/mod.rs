//! A turned thread on a lathe: the spec resolved, every pass swept, the groove measured and
//! checked (`verify`); the plan read back from the passes (`cut_plan`), the lead against the
//! designation's (`lead`) and the correction in the program's words (`correction`).

pub mod correction;
pub mod cut_plan;
pub mod lead;
pub mod verify;
