//! `threadcheck compare`: the same thread with every infeed strategy.

use super::args::{JsonArg, PlanArgs};
use super::{pretty, Dest, Document, Job, Outcome, Outputs, Request};
use crate::analysis::study::compare::CompareChoice;
use crate::toolpath::passes::Schedule;
use crate::Error;
use serde::Deserialize;
use std::path::PathBuf;

/// The arguments of `compare`.
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CompareArgs {
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    #[allow(missing_docs)]
    pub plan: PlanArgs,
    /// Modified-flank angles, degrees (comma-separated); default half the thread angle less
    /// 0.5° and less 3° (29.5,27 for 60° threads, 14.5,12 for trapezoidal).
    #[cfg_attr(feature = "cli", arg(long, value_name = "ANGLES", value_delimiter = ',', value_parser = crate::commands::args::finite))]
    pub modified: Vec<f64>,
    /// Write the table as Markdown to this file.
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE"))]
    #[serde(skip)]
    pub markdown: Option<PathBuf>,
    /// Write a self-contained HTML report (the table and each strategy's picture) to this file.
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE"))]
    #[serde(skip)]
    pub html: Option<PathBuf>,
    /// JSON (every verify report and the per-strategy figures).
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    pub out: JsonArg,
}

super::args::api_args!(CompareArgs, shares plan: PlanArgs, reads thread at plan.standard);

impl Job for CompareArgs {
    const NAME: &'static str = "compare";
    const DOCUMENTS: &'static [Document] =
        &[Document::Json, Document::Text, Document::Html, Document::Markdown];

    fn run(&self, request: &Request) -> Result<Outputs, Error> {
        self.plan.one_thread("compare")?;
        if self.plan.units.is_some() {
            return Err(Error::Input(
                "compare's table is in mm: ‹units› gives inches in verify's text and pictures".into(),
            ));
        }
        let spec = crate::analysis::turn::VerifySpec {
            picture: request.wants(Document::Html),
            ..self.plan.spec(request.files)?
        };
        let modified = if self.modified.is_empty() {
            let des = spec.designation.as_ref().ok_or_else(crate::standards::designation::none_given)?;
            let half = 0.5 * des.thread.form.flank_angle();
            vec![half - 0.5, half - 3.0]
        } else {
            self.modified.clone()
        };
        let choice = CompareChoice {
            infeed: self.plan.infeed,
            schedule: if self.plan.depths.is_empty() {
                self.plan.schedule.clone()
            } else {
                Some(Schedule::Explicit(self.plan.depths.clone()))
            },
        };
        let c = crate::analysis::study::compare::compare(&spec, &modified, &choice)?;
        Ok(Outputs::new(
            Outcome::Pass,
            [
                request.render(Document::Json, || pretty(&crate::report::compare::CompareReport::of(&c)))?,
                request.render(Document::Html, || Ok(crate::report::compare::compare_html(&c)))?,
                request.render(Document::Markdown, || Ok(crate::report::compare::markdown_report(&c)))?,
                Some((Document::Text, crate::report::compare::text(&c))),
            ],
        )
        .reading(self.plan.inputs()))
    }

    fn destinations(&self) -> Vec<(Document, Dest)> {
        Dest::list(
            [(Document::Json, &self.out.json)],
            [(Document::Markdown, &self.markdown), (Document::Html, &self.html)],
        )
    }
}
