//! `threadcheck capability`: a program's (or plan's) parts over the machine's and the insert's
//! variation.

use super::args::PlanArgs;
use super::{pretty, Dest, Document, Job, Outcome, Outputs, Request};
use crate::analysis::study::capability::CapabilitySpec;
use crate::Error;
use serde::Deserialize;

/// The least pitch-diameter Cpk a capable program keeps (ISO 22514's usual requirement).
pub const CAPABLE_CPK: f64 = 1.33;

/// The arguments of `capability`.
///
/// ```
/// use threadcheck::{Command, Document, Files, Outcome, Request};
/// let args = r#"{"thread": "M10x1.5-6g", "insert": "full", "x_sigma": 0.005, "samples": 200}"#;
/// let out = Command::from_api("capability", args)?.run(&Request::api(Document::Text, Files::Refused))?;
/// assert_eq!(out.outcome, Outcome::Pass);
/// assert!(out.document(Document::Text).unwrap_or("").contains("Cpk"));
/// # Ok::<(), threadcheck::Error>(())
/// ```
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CapabilityArgs {
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    #[allow(missing_docs)]
    pub plan: PlanArgs,
    /// Of a program that cuts several threads, the one to take (1-based, in program order).
    #[cfg_attr(feature = "cli", arg(long, value_name = "N", requires = "program", value_parser = crate::commands::args::operation_number))]
    pub operation: Option<usize>,
    /// X repeatability, one standard deviation on the diameter, mm (default 0).
    #[cfg_attr(feature = "cli", arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = crate::commands::args::finite))]
    pub x_sigma: Option<f64>,
    /// The insert's tip radius tolerance, ± mm (uniform; a partial-profile insert; default 0).
    #[cfg_attr(feature = "cli", arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = crate::commands::args::finite))]
    pub tip_radius_tol: Option<f64>,
    /// Radial insert wear per part, mm (default 0).
    #[cfg_attr(feature = "cli", arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = crate::commands::args::finite))]
    pub wear_per_part: Option<f64>,
    /// Monte Carlo samples (default 10 000).
    #[cfg_attr(feature = "cli", arg(long, value_name = "N"))]
    pub samples: Option<usize>,
    /// The seed (the same seed gives the same report on any number of cores; default 1).
    #[cfg_attr(feature = "cli", arg(long, value_name = "N"))]
    pub seed: Option<u64>,
    /// Leave form checks out of each part's verdict (the share of good parts).
    #[cfg_attr(feature = "cli", arg(long))]
    pub gauge_only: bool,
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    #[allow(missing_docs)]
    pub out: super::args::PictureArgs,
}

super::args::api_args!(CapabilityArgs, shares plan: PlanArgs, reads thread at plan.standard);

impl Job for CapabilityArgs {
    const NAME: &'static str = "capability";
    const DOCUMENTS: &'static [Document] = &[Document::Json, Document::Text, Document::Svg, Document::Html];

    /// Pass when the pitch diameter's Cpk reaches [`CAPABLE_CPK`], 1.33 (or, without variation,
    /// when every sampled part passes).
    fn run(&self, request: &Request) -> Result<Outputs, Error> {
        self.plan.one_thread("capability")?;
        let verify = crate::analysis::turn::VerifySpec {
            operation: self.operation,
            gauge_only: self.gauge_only,
            ..self.plan.spec(request.files)?
        };
        let mut spec = CapabilitySpec::new(verify);
        spec.x_sigma = self.x_sigma.unwrap_or(0.0);
        spec.tip_radius_tol = self.tip_radius_tol.unwrap_or(0.0);
        spec.wear_per_part = self.wear_per_part.unwrap_or(0.0);
        spec.samples = self.samples.unwrap_or(spec.samples);
        spec.seed = self.seed.unwrap_or(spec.seed);
        let r = crate::analysis::study::capability::capability(&spec)?;
        let d2 = r.sizes.iter().find(|s| s.feature == crate::analysis::check::CheckFeature::PitchDiameter);
        let capable = match d2.and_then(|d| d.cpk) {
            Some(cpk) => cpk >= CAPABLE_CPK,
            None => r.pass_share == 1.0,
        };
        Ok(Outputs::new(
            Outcome::of(capable),
            [
                request
                    .render(Document::Json, || pretty(&crate::report::capability::CapabilityJson::of(&r)))?,
                request.render(Document::Svg, || Ok(crate::report::capability::capability_svg(&r)))?,
                request.render(Document::Html, || Ok(crate::report::capability::capability_html(&r)))?,
                Some((Document::Text, crate::report::capability::capability_text(&r))),
            ],
        )
        .reading(self.plan.inputs()))
    }

    fn destinations(&self) -> Vec<(Document, Dest)> {
        self.out.destinations(None)
    }
}
