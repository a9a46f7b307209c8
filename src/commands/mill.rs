//! `threadcheck mill`: a milling program's cutter against a target curve.

use super::args::{JsonArg, ProgramArgs, Source};
use super::{pretty, Dest, Document, Job, Outcome, Outputs, Request};
use crate::analysis::mill::{MillSpec, Target};
use crate::Error;
use serde::Deserialize;
use std::path::PathBuf;

/// The arguments of `mill`.
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MillArgs {
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    #[allow(missing_docs)]
    pub file: ProgramArgs,
    /// Run the blocks in the order of their N numbers (a listing whose page break moved blocks).
    #[cfg_attr(feature = "cli", arg(long))]
    pub n_order: bool,
    /// Cutter diameter, mm.
    #[cfg_attr(feature = "cli", arg(long, value_name = "MM", required = true, value_parser = crate::commands::args::finite))]
    pub tool_diameter: Option<f64>,
    /// The target curve (TOML: x, y in t and z; t range; material inside|outside; optional z
    /// range): a file on the command line, its text through the API.
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE.toml", required = true, value_parser = Source::path))]
    #[serde(deserialize_with = "super::args::source_text")]
    pub target: Option<Source>,
    /// Allowed gouge and material left, mm (default 0.01).
    #[cfg_attr(feature = "cli", arg(long, value_name = "MM", value_parser = crate::commands::args::finite))]
    pub tolerance: Option<f64>,
    /// Write an SVG of the worst level.
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE"))]
    #[serde(skip)]
    pub svg: Option<PathBuf>,
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    #[allow(missing_docs)]
    pub out: JsonArg,
}

super::args::api_args!(MillArgs, shares file: ProgramArgs);

impl Job for MillArgs {
    const NAME: &'static str = "mill";
    const DOCUMENTS: &'static [Document] = &[Document::Json, Document::Text, Document::Svg];

    /// Pass when the gouge and the leftover are within the tolerance.
    fn run(&self, request: &Request) -> Result<Outputs, Error> {
        let set = self.file.settings(request.files)?;
        let (program, dialect, from) = self.file.read("mill", &set)?;
        let target = match &self.target {
            None => return Err(Error::Input("mill needs ‹target› (its TOML)".into())),
            Some(Source::Path(p)) => Target::read(p)?,
            Some(Source::Text(t)) => Target::from_toml(t, "<target>")?,
        };
        let spec = MillSpec {
            program,
            dialect,
            n_order: self.n_order,
            tool_diameter: self
                .tool_diameter
                .ok_or_else(|| Error::Input("mill needs ‹tool_diameter› (mm)".into()))?,
            target,
            tolerance: self.tolerance.unwrap_or(0.01),
            reading: crate::gcode::ReadOptions {
                dialect_from: from,
                sub_files: self.file.sub_files(request.files),
                settings_notes: set.notes(&super::settings::Given {
                    dialect: self.file.reading.dialect.map(|d| d.name().to_string()),
                    machine_type: self.file.reading.machine_type.map(|m| m.name().to_string()),
                    default_units: self.file.reading.default_units.map(|u| u.name().to_string()),
                    ..Default::default()
                }),
                ..self.file.reading.options(&set, None)
            },
        };
        let r = crate::analysis::mill::mill(&spec)?;
        let inputs = self.file.inputs().into_iter().chain(self.target.as_ref().and_then(Source::file));
        Ok(Outputs::new(
            Outcome::of(r.verdict == crate::analysis::check::Verdict::Pass),
            [
                request.render(Document::Json, || pretty(&r))?,
                request.render(Document::Svg, || Ok(crate::report::mill::mill_svg(&r)))?,
                Some((Document::Text, crate::report::mill::text(&r))),
            ],
        )
        .reading(inputs))
    }

    fn destinations(&self) -> Vec<(Document, Dest)> {
        Dest::list([(Document::Json, &self.out.json)], [(Document::Svg, &self.svg)])
    }
}
