//! The computations: plain data in, plain data out, no text for a reader.
//!
//! By process: [`program`] (a whole program: every thread it makes, one verdict) above the
//! processes, [`turn`] (a turned thread), [`tap`], [`thread_mill`] and [`mill`] (contours); what
//! they share beside them; the studies of a turned thread in [`study`].

pub mod check;
pub mod control;
pub mod fusion;
pub mod gouge;
pub mod made;
pub mod mill;
pub mod naming;
pub mod percent;
pub mod picture;
pub mod process;
pub mod program;
pub mod rolled;
pub mod study;
pub mod tap;
pub mod taper;
pub mod thread_mill;
pub mod tools;
pub mod turn;
