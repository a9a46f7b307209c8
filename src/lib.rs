//! # threadcheck
//!
//! Tells a machinist, before any metal is cut, what thread a CNC lathe program will produce and
//! whether that thread meets its standard.
//!
//! The modules follow the path the data takes:
//!
//! 1. [`standards`]: a designation (`M10x1.5-6g`) becomes a basic thread and its class;
//! 2. [`tolerance`]: the class becomes limits of size (ISO 965-1, BS 84, ISO 228-1);
//!
//! All lengths are millimetres (`f64`). Lathe X values are **diameters**; geometry works in the
//! axial half-plane with `(z, r)` where `r` is a radius. Deviations are reported in µm.

pub mod app;
pub mod boolean;
pub mod error;
pub mod geometry;
pub mod insert;
pub mod limits;
pub mod measure;
pub mod output;
pub mod passes;
pub mod standards;
pub mod sweep;
pub mod tolerance;

pub use error::{Error, Result};
pub use geometry::{Arc, Point, DEFAULT_TOLERANCE};
pub use standards::{
    parse_designation, BasicThread, ClassSpec, Designation, DesignationError, Hand, ParseOptions,
    ProfileKind, ThreadForm, ThreadKind,
};
pub use tolerance::{Limit, ThreadLimits};
