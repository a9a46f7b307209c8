//! The computations: plain data in, plain data out, no text for a reader.

pub mod capability;
pub mod catalogue;
pub mod check;
pub mod compare;
pub mod control;
pub mod correct;
pub mod correction;
pub mod cut_plan;
pub mod fit;
pub mod fusion;
pub mod gouge;
pub mod lead;
pub mod made;
pub mod mill;
pub mod naming;
pub mod percent;
pub mod picture;
pub mod process;
pub mod program;
pub mod rolled;
pub mod taper;
pub mod tapping;
pub mod threadmill;
pub mod tools;
pub mod verify;
