//! `threadcheck correct`: what was measured on the part, turned into the change to make.

use super::args::{JsonArg, PlanArgs};
use super::{pretty, Dest, Document, Job, Outcome, Outputs, Request};
use crate::analysis::study::correct::{CorrectSpec, GaugeResult, Measured};
use crate::Error;
use serde::Deserialize;
use serde_with::{serde_as, DisplayFromStr};
use std::path::PathBuf;

/// The arguments of `correct`.
///
/// ```
/// use threadcheck::{Command, Document, Files, Outcome, Request};
/// let c = Command::from_api("correct", r#"{"thread": "M10x1.5-6g", "insert": "full", "measured_d2": 8.95}"#)?;
/// let out = c.run(&Request::api(Document::Text, Files::Refused))?;
/// assert_eq!(out.outcome, Outcome::Pass); // 8.950 lies within 8.862–8.994
/// assert!(out.document(Document::Text).unwrap_or("").contains("IN TOLERANCE"));
/// # Ok::<(), threadcheck::Error>(())
/// ```
#[serde_as]
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CorrectArgs {
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    #[allow(missing_docs)]
    pub plan: PlanArgs,
    /// Of a program that cuts several threads, the one measured (1-based, in program order).
    #[cfg_attr(feature = "cli", arg(long, value_name = "N", requires = "program", value_parser = crate::commands::args::operation_number))]
    pub operation: Option<usize>,
    /// The measurement over three wires, mm (with --wire).
    #[cfg_attr(feature = "cli", arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = crate::commands::args::finite, requires = "wire",
          conflicts_with_all = ["measured_d2", "gauge"]))]
    pub measured_m: Option<f64>,
    /// The wires' diameter, mm.
    #[cfg_attr(feature = "cli", arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = crate::commands::args::finite, requires = "measured_m"))]
    pub wire: Option<f64>,
    /// The pitch diameter measured (thread micrometer, optical), mm.
    #[cfg_attr(feature = "cli", arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = crate::commands::args::finite, conflicts_with = "gauge"))]
    pub measured_d2: Option<f64>,
    /// What the GO/NO-GO gauges said: go-fails | nogo-enters | ok.
    #[cfg_attr(feature = "cli", arg(long, value_name = "RESULT"))]
    #[serde_as(as = "Option<DisplayFromStr>")]
    pub gauge: Option<GaugeResult>,
    /// Pick-up: a groove centre's Z on the re-clamped part (at the pitch line, from the
    /// program's Z0), mm.
    #[cfg_attr(feature = "cli", arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = crate::commands::args::finite))]
    pub pickup_z: Option<f64>,
    /// Write a self-contained HTML page to this file.
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE"))]
    #[serde(skip)]
    pub html: Option<PathBuf>,
    /// Write the program with the correction to this file; `-` prints it instead of the report.
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE|-", requires = "program"))]
    #[serde(skip)]
    pub fix: Option<String>,
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    #[allow(missing_docs)]
    pub out: JsonArg,
}

super::args::api_args!(CorrectArgs, shares plan: PlanArgs, reads thread at plan.standard);

impl CorrectArgs {
    /// The one measurement given, if any.
    fn measured(&self) -> Result<Option<Measured>, Error> {
        Ok(match (self.measured_m, self.wire, self.measured_d2, self.gauge) {
            (Some(m), Some(wire), None, None) => Some(Measured::OverWires { m, wire }),
            (Some(_), None, _, _) | (None, Some(_), _, _) => {
                return Err(Error::Input("‹measured_m› and ‹wire› go together".into()))
            }
            (None, None, Some(d2), None) => Some(Measured::PitchDiameter(d2)),
            (None, None, None, Some(g)) => Some(Measured::Gauge(g)),
            (None, None, None, None) => None,
            _ => {
                return Err(Error::Input(
                    "give one measurement: ‹measured_m› with ‹wire›, ‹measured_d2› or ‹gauge›".into(),
                ))
            }
        })
    }
}

impl Job for CorrectArgs {
    const NAME: &'static str = "correct";
    const DOCUMENTS: &'static [Document] = &[Document::Json, Document::Text, Document::Html, Document::Fix];

    fn run(&self, request: &Request) -> Result<Outputs, Error> {
        self.plan.one_thread("correct")?;
        let verify =
            crate::analysis::turn::VerifySpec { operation: self.operation, ..self.plan.spec(request.files)? };
        let spec = CorrectSpec { verify, measured: self.measured()?, pickup_z: self.pickup_z };
        let r = crate::analysis::study::correct::correct(&spec)?;
        let outcome = match r.verdict() {
            crate::analysis::check::Verdict::Pass => Outcome::Pass,
            crate::analysis::check::Verdict::Fail => Outcome::OutOfTolerance,
        };
        let fixed = || {
            let Some((source, _)) = &spec.verify.program else {
                return Err(Error::Input("‹fix› corrects a program: give it with ‹program›".into()));
            };
            let (shown, program) = source.load()?;
            let edits = match &r.correction {
                None => Vec::new(),
                Some(c) => super::verify::correction_edits(c, &shown)?,
            };
            crate::gcode::rewrite_words(&program, &shown, &edits)
        };
        Ok(Outputs::new(
            outcome,
            [
                request.render(Document::Json, || pretty(&crate::report::correct::CorrectJson::of(&r)))?,
                request.render(Document::Html, || Ok(crate::report::correct::correct_html(&r)))?,
                request.render(Document::Fix, fixed)?,
                Some((Document::Text, crate::report::correct::correct_text(&r))),
            ],
        )
        .reading(self.plan.inputs()))
    }

    fn destinations(&self) -> Vec<(Document, Dest)> {
        Dest::list(
            [(Document::Json, &self.out.json), (Document::Fix, &self.fix)],
            [(Document::Html, &self.html)],
        )
    }
}
