//! A turned thread re-cut with its passes moved radially and its insert's tip radius changed:
//! what a Monte Carlo (`capability`) calls once per sampled part.

use super::core::*;
use super::program::*;
use super::resolve::*;
use super::spec::*;
use crate::analysis::tools::InsertChoice;
use crate::toolpath::passes::Pass;
use crate::Error;

/// One thread re-cut with its passes moved radially and its insert's tip radius changed: the
/// verify core a Monte Carlo calls once per sampled part.
#[derive(Clone, Debug)]
pub(crate) struct Recut {
    pub(crate) r: Resolved,
    pub(crate) passes: Vec<Pass>,
    pub(crate) label: ProgramLabel,
}

impl Recut {
    /// The thread of `spec` as `verify` cuts it (plan or program), ready to be re-cut.
    pub(crate) fn new(spec: &VerifySpec) -> Result<(Recut, Verification), Error> {
        let quick = VerifySpec { metrics: false, picture: false, ..spec.clone() };
        let v = verify(&quick)?;
        // The program's text is read once, by `verify`: the re-cuts take its passes.
        let r = resolve(&VerifySpec {
            program: None,
            operation: None,
            final_x: None,
            blank_diameter: Some(v.blank_diameter),
            ..quick
        })?;
        let label = v
            .program
            .clone()
            .unwrap_or(ProgramLabel { file: "<plan>".into(), dialect: crate::gcode::Dialect::Fanuc });
        Ok((Recut { r, passes: v.passes.clone(), label }, v))
    }

    /// How many passes each re-cut sweeps.
    pub(crate) fn pass_count(&self) -> usize {
        self.passes.len()
    }

    /// The tip radius of a partial-profile insert, mm (`None` for the others).
    pub(crate) fn tip_radius(&self) -> Option<f64> {
        match self.r.spec.insert {
            InsertChoice::Partial { tip_radius } => Some(tip_radius),
            InsertChoice::Full | InsertChoice::File(_) | InsertChoice::Toml { .. } => None,
        }
    }

    /// The thread cut with every pass's X moved by `dx` mm (diameter) and, when given, a
    /// partial insert of tip radius `tip`.
    pub(crate) fn cut(&self, dx: f64, tip: Option<f64>) -> Result<Verification, Error> {
        let mut r = self.r.clone();
        if let Some(tip) = tip {
            let t = r.designation.thread;
            r.insert =
                build_insert(&InsertChoice::Partial { tip_radius: tip }, &t, r.kind, r.spec.tolerance)?;
        }
        let passes = self
            .passes
            .iter()
            .map(|p| Pass { x_start: p.x_start + dx, x_end: p.x_end + dx, x_taper: p.x_taper + dx, ..*p })
            .collect();
        let given = Given {
            passes,
            depth_word: None,
            units: crate::gcode::ProgramUnits::Mm,
            lead: None,
            label: self.label.clone(),
            notes: Vec::new(),
        };
        verify_core(&r, Some(given))
    }
}
