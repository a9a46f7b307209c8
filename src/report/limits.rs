//! `limits --json`: the basic dimensions and the classes' limits of a designation.

use super::*;
use serde::Serialize;

/// The `basic` object of `limits --json`: the basic sizes, rounded as the tables print them.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct BasicReport {
    /// d = D, mm.
    pub major_diameter: f64,
    /// d2 = D2, mm.
    pub pitch_diameter: f64,
    /// d3, mm.
    pub minor_diameter_external: f64,
    /// D1, mm.
    pub minor_diameter_internal: f64,
    /// H, mm.
    pub fundamental_triangle_height: f64,
}

/// `limits --json` (docs/json.md).
#[derive(Clone, Debug, Serialize)]
pub struct LimitsReport<'a> {
    /// As written.
    pub designation: &'a str,
    /// The form's name.
    pub form: &'static str,
    /// mm.
    pub nominal_diameter: f64,
    /// mm.
    pub pitch: f64,
    /// mm.
    pub lead: f64,
    /// Number of starts.
    pub starts: u32,
    /// `right` or `left`.
    pub hand: &'static str,
    /// Outside the standard series.
    pub nonstandard: bool,
    /// Basic sizes.
    pub basic: BasicReport,
    /// The external thread's limits, when the designation has an external class.
    pub external: Option<&'a crate::standards::tolerance::ThreadLimits>,
    /// The internal thread's limits.
    pub internal: Option<&'a crate::standards::tolerance::ThreadLimits>,
}

impl<'a> LimitsReport<'a> {
    /// The report of a designation's limits.
    pub fn new(
        des: &'a crate::standards::Designation,
        external: Option<&'a crate::standards::tolerance::ThreadLimits>,
        internal: Option<&'a crate::standards::tolerance::ThreadLimits>,
    ) -> Self {
        let t = &des.thread;
        let (major_diameter, pitch_diameter, minor_diameter_external, minor_diameter_internal, h) =
            crate::standards::tolerance::basic_rounded(t);
        LimitsReport {
            designation: &des.text,
            form: t.form.name(),
            nominal_diameter: crate::standards::tolerance::named_diameter(t),
            pitch: t.pitch,
            lead: t.lead(),
            starts: t.starts,
            hand: match t.hand {
                Hand::Left => "left",
                Hand::Right => "right",
            },
            nonstandard: des.nonstandard,
            basic: BasicReport {
                major_diameter,
                pitch_diameter,
                minor_diameter_external,
                minor_diameter_internal,
                fundamental_triangle_height: h,
            },
            external,
            internal,
        }
    }
}
