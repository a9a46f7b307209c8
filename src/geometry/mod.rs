//! The cut in the axial section: the insert's outline, the imprints of the passes and their
//! envelope, the section left standing and its measurement; a thread mill's reach along its
//! helices (`helix`).
//!
//! `boolean` is the one door to `geo`, `parry` the one door to `parry2d-f64`.

pub mod boolean;
pub mod envelope;
pub mod forming;
pub mod helix;
pub mod index;
pub mod insert;
pub mod measure;
pub mod parry;
pub mod sweep;
pub mod wire;
