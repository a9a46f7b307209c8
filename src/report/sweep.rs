//! The catalogue run's JSON lines: a case's error and the placements line.

use serde::Serialize;

/// A case of `sweep --json` that could not be verified.
#[derive(Clone, Debug, Serialize)]
pub struct CaseError<'a> {
    /// The case's label.
    pub case: &'a str,
    /// The one-line error.
    pub error: String,
}

/// One line of `sweep --export-placements`: what an outside baseline needs to redo the cut.
#[derive(Clone, Debug, Serialize)]
pub struct PlacementsLine<'a> {
    /// The case's label.
    pub case: &'a str,
    /// `external` or `internal`.
    pub kind: &'static str,
    /// mm.
    pub pitch: f64,
    /// Axial position of the measured groove, mm.
    pub z_ref: f64,
    /// The blank's outline, (z, r) mm.
    pub blank: Vec<[f64; 2]>,
    /// Every insert placement's outline, (z, r) mm.
    pub placements: Vec<Vec<[f64; 2]>>,
    /// Measured d2, mm.
    pub pitch_diameter: f64,
    /// threadcheck's best time for the same cut (sweep and pitch diameter), s.
    pub threadcheck_seconds: f64,
    /// threadcheck's best time for the case's whole verify, s.
    pub verify_seconds: f64,
}
