//! `threadcheck fit`: a bolt and a nut cut in the computer and assembled.

use super::args::{dialect_for, JsonArg, Source};
use super::{pretty, Dest, Document, Files, Job, Outcome, Outputs, Request};
use crate::analysis::study::fit::{FitSide, FitSpec};
use crate::analysis::tools::InsertChoice;
use crate::gcode::Dialect;
use crate::Error;
use serde::Deserialize;
use serde_with::{serde_as, DisplayFromStr};
use std::path::PathBuf;

/// The arguments of `fit`.
#[serde_as]
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FitArgs {
    /// A fit designation, e.g. M10x1.5-6H/6g.
    #[cfg_attr(feature = "cli", arg(long, required = true))]
    pub thread: Option<String>,
    /// How the designation is read.
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    pub standard: super::StandardArgs,
    /// The bolt's program (else a generated plan).
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE", conflicts_with = "bolt_final_x", value_parser = Source::path))]
    #[serde(deserialize_with = "super::args::source_text")]
    pub bolt_program: Option<Source>,
    /// Its dialect: fanuc, haas, sinumerik, linuxcnc, dyna, okuma, mitsubishi, mazak, heidenhain or klartext.
    #[cfg_attr(feature = "cli", arg(long))]
    #[serde_as(as = "Option<DisplayFromStr>")]
    pub bolt_dialect: Option<Dialect>,
    /// The bolt plan's last tip diameter (default: mid-tolerance).
    #[cfg_attr(feature = "cli", arg(long, value_name = "DIA", allow_hyphen_values = true, value_parser = crate::commands::args::finite))]
    pub bolt_final_x: Option<f64>,
    /// The bolt's insert: full | partial[:TIP_RADIUS] | FILE.toml (default partial).
    #[cfg_attr(feature = "cli", arg(long))]
    #[serde_as(as = "Option<DisplayFromStr>")]
    pub bolt_insert: Option<InsertChoice>,
    /// The nut's program (else a generated plan).
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE", conflicts_with = "nut_final_x", value_parser = Source::path))]
    #[serde(deserialize_with = "super::args::source_text")]
    pub nut_program: Option<Source>,
    /// Its dialect.
    #[cfg_attr(feature = "cli", arg(long))]
    #[serde_as(as = "Option<DisplayFromStr>")]
    pub nut_dialect: Option<Dialect>,
    /// The nut plan's last tip diameter (default: mid-tolerance).
    #[cfg_attr(feature = "cli", arg(long, value_name = "DIA", allow_hyphen_values = true, value_parser = crate::commands::args::finite))]
    pub nut_final_x: Option<f64>,
    /// The nut's insert (default partial).
    #[cfg_attr(feature = "cli", arg(long))]
    #[serde_as(as = "Option<DisplayFromStr>")]
    pub nut_insert: Option<InsertChoice>,
    /// Write an SVG of the pair.
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE"))]
    #[serde(skip)]
    pub svg: Option<PathBuf>,
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    #[allow(missing_docs)]
    pub out: JsonArg,
}

super::args::api_args!(FitArgs, shares nothing, reads thread at standard);

/// One side of the pair: its program (read), or its plan's final X, and its insert.
fn side(
    who: &str,
    program: &Option<Source>,
    dialect: Option<Dialect>,
    final_x: Option<f64>,
    insert: &Option<InsertChoice>,
    files: Files,
) -> Result<FitSide, Error> {
    if program.is_some() && final_x.is_some() {
        return Err(Error::Input(format!(
            "‹{who}_program› and ‹{who}_final_x› exclude each other: the program sets the passes"
        )));
    }
    let insert = match insert {
        Some(InsertChoice::File(p)) if files == Files::Refused => {
            return Err(Error::Input(format!(
                "‹{who}_insert› '{}' names a file, and the server reads none: use full, partial or partial:R",
                p.display()
            )))
        }
        Some(i) => i.clone(),
        None => InsertChoice::Partial { tip_radius: 0.04 },
    };
    let program = match program {
        None => None,
        Some(source) => {
            let (shown, text) = source.load(&format!("<{who} program>"))?;
            let dialect = dialect_for(dialect, std::path::Path::new(&shown)).0;
            Some((text, shown, dialect))
        }
    };
    Ok(FitSide { insert, final_x, program })
}

impl Job for FitArgs {
    const NAME: &'static str = "fit";
    const DOCUMENTS: &'static [Document] = &[Document::Json, Document::Text, Document::Svg];

    /// Pass when the pair screws together.
    fn run(&self, request: &Request) -> Result<Outputs, Error> {
        let thread = self
            .thread
            .as_deref()
            .ok_or_else(|| Error::Input("fit needs ‹thread›, a fit such as M10x1.5-6H/6g".into()))?;
        let thread = self.standard.parse(thread)?;
        let f = request.files;
        let spec = FitSpec {
            thread,
            bolt: side(
                "bolt",
                &self.bolt_program,
                self.bolt_dialect,
                self.bolt_final_x,
                &self.bolt_insert,
                f,
            )?,
            nut: side("nut", &self.nut_program, self.nut_dialect, self.nut_final_x, &self.nut_insert, f)?,
        };
        let r = crate::analysis::study::fit::fit(&spec)?;
        let inserts = [&self.bolt_insert, &self.nut_insert].into_iter().filter_map(|i| match i {
            Some(InsertChoice::File(p)) => Some(p.clone()),
            _ => None,
        });
        let programs = [&self.bolt_program, &self.nut_program].into_iter().filter_map(|p| p.as_ref()?.file());
        Ok(Outputs::new(
            Outcome::of(r.fits),
            [
                request.render(Document::Json, || pretty(&crate::report::fit::FitJson::of(&r)))?,
                request.render(Document::Svg, || Ok(crate::report::fit::svg(&r)))?,
                Some((Document::Text, crate::report::fit::text(&r))),
            ],
        )
        .reading(programs.chain(inserts)))
    }

    fn destinations(&self) -> Vec<(Document, Dest)> {
        Dest::list([(Document::Json, &self.out.json)], [(Document::Svg, &self.svg)])
    }
}
