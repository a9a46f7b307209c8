//! The ground every wing stands on: the one error type, the bounds on input, the plane's
//! points and arcs, and number formatting. Nothing here imports another wing.

pub mod bounds;
pub mod cancel;
pub mod error;
pub mod fmt;
pub mod input;
pub mod note;
pub mod plane;
