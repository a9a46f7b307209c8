//! `threadcheck thread-mill`: the thread a thread-milling program leaves.

use super::args::{tool_table, ProgramArgs, Source};
use super::{pretty, Dest, Document, Job, Outcome, Outputs, Request};
use crate::analysis::thread_mill::ThreadMillSpec;
use crate::geometry::helix::Cutter;
use crate::Error;
use serde::Deserialize;
use serde_with::serde_as;

/// The arguments of `thread-mill`.
#[serde_as]
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ThreadMillArgs {
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    #[allow(missing_docs)]
    pub file: ProgramArgs,
    /// The thread with its class, e.g. M20x1.5-6H (default: the one the program names in a
    /// comment above its first helix, else the standard size of the helix's lead and diameter).
    #[cfg_attr(feature = "cli", arg(long))]
    pub thread: Option<String>,
    /// How the designation is read.
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    pub standard: super::StandardArgs,
    /// The cutter's diameter over its tooth's tip, mm (else the tool table's thread mill, else the
    /// one the program's comments name for the helices' tool: `(T5 D=8. … - thread mill)`).
    #[cfg_attr(feature = "cli", arg(long, value_name = "MM", value_parser = crate::commands::args::finite))]
    pub cutter_diameter: Option<f64>,
    /// The tool table: the helices' T as a thread mill's file (`12 = "thread-mill.toml"`:
    /// kind = "thread-mill", diameter, angle, tip_radius, rows, row_pitch) and `[offsets]` (12 = 3.0,
    /// the compensation value G41/G42 apply).
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE.toml", conflicts_with = "cutter_diameter", value_parser = Source::path))]
    #[serde(deserialize_with = "super::args::source_text")]
    pub tools: Option<Source>,
    /// The tooth's included angle, degrees (default 60).
    #[cfg_attr(feature = "cli", arg(long, value_name = "DEG", value_parser = crate::commands::args::finite))]
    pub cutter_angle: Option<f64>,
    /// The tooth's tip radius, mm (default 0).
    #[cfg_attr(feature = "cli", arg(long, value_name = "MM", value_parser = crate::commands::args::finite))]
    pub cutter_tip_radius: Option<f64>,
    /// Rows of teeth: 1 for a single-form cutter (the default), more for a multi-form one (with
    /// --cutter-row-pitch).
    #[cfg_attr(feature = "cli", arg(long, value_name = "N"))]
    pub cutter_rows: Option<u32>,
    /// A multi-form cutter's row spacing, mm (no default: a cutter of more rows needs it).
    #[cfg_attr(feature = "cli", arg(long, value_name = "MM", value_parser = crate::commands::args::finite))]
    pub cutter_row_pitch: Option<f64>,
    /// The cutter's teeth (flutes), for each helix's feed per tooth at the edge (edge feed / (S ·
    /// teeth)); any cutter, given or from a tool table or comment (default: not given, the feed
    /// per tooth is not computed).
    #[cfg_attr(feature = "cli", arg(long, value_name = "N"))]
    pub cutter_teeth: Option<u32>,
    /// The bore (internal) or blank (external) diameter, mm (default: the middle of the class's D1
    /// limits (internal) or major diameter limits (external), stated).
    #[cfg_attr(feature = "cli", arg(long, value_name = "MM", value_parser = crate::commands::args::finite))]
    pub blank_diameter: Option<f64>,
    /// The value G41/G42 compensate by (the D register), mm: the cutter centre runs that far to
    /// the left (G41) or right (G42) of the programmed helix (default: the tool table's
    /// `[offsets]`; a helix under compensation without either is refused).
    #[cfg_attr(feature = "cli", arg(long, value_name = "MM", value_parser = crate::commands::args::finite))]
    pub comp_radius: Option<f64>,
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    #[allow(missing_docs)]
    pub out: super::args::PictureArgs,
}

super::args::api_args!(ThreadMillArgs, shares file: ProgramArgs, reads thread at standard);

impl Job for ThreadMillArgs {
    const NAME: &'static str = "thread-mill";
    const DOCUMENTS: &'static [Document] = &[Document::Json, Document::Text, Document::Svg, Document::Html];

    /// Pass when the milled thread is within every limit and the lead is right.
    fn run(&self, request: &Request) -> Result<Outputs, Error> {
        let set = self.file.settings(request.files)?;
        let (program, dialect, from) = self.file.read("thread-mill", &set)?;
        // Without ‹thread›, the project file's or the modeline's, else the thread the program
        // names (a comment), else the size it cuts.
        let designation =
            self.thread.clone().or_else(|| set.thread.as_ref().and_then(|t| t.0.first().cloned()));
        let tools_source =
            self.tools.clone().or_else(|| set.tools.as_ref().map(|t| Source::Path(t.0.clone())));
        let settings_notes = set.notes(&super::settings::Given {
            dialect: self.file.reading.dialect.map(|d| d.name().to_string()),
            machine_type: self.file.reading.machine_type.map(|m| m.name().to_string()),
            default_units: self.file.reading.default_units.map(|u| u.name().to_string()),
            tools: self.tools.as_ref().map(super::args::source_words),
            thread: self.thread.clone(),
            ..Default::default()
        });
        let rows = self.cutter_rows.unwrap_or(1);
        if !(1..=200).contains(&rows) {
            return Err(Error::Input(format!("‹cutter_rows› {rows}: a whole number from 1 to 200")));
        }
        // The cutter's shape goes with its diameter: a tool table's or a comment's thread mill
        // is whole, and a shape word beside it would be dropped unsaid.
        if self.cutter_diameter.is_none() {
            let shape = [
                (self.cutter_angle.is_some(), "cutter_angle"),
                (self.cutter_tip_radius.is_some(), "cutter_tip_radius"),
                (self.cutter_rows.is_some(), "cutter_rows"),
                (self.cutter_row_pitch.is_some(), "cutter_row_pitch"),
            ];
            if let Some((_, word)) = shape.iter().find(|(given, _)| *given) {
                return Err(Error::Input(format!(
                    "‹{word}› describes the cutter ‹cutter_diameter› gives: give it too (a tool table's thread mill has its own file)"
                )));
            }
        }
        let cutter = self
            .cutter_diameter
            .map(|diameter| {
                Cutter::single_form(
                    diameter,
                    self.cutter_angle.unwrap_or(60.0),
                    self.cutter_tip_radius.unwrap_or(0.0),
                )
                .with_rows(rows, self.cutter_row_pitch)
            })
            .transpose()?;
        if self.cutter_teeth.is_some_and(|z| !(1..=100).contains(&z)) {
            return Err(Error::Input(format!(
                "‹cutter_teeth› {}: a whole number from 1 to 100",
                self.cutter_teeth.unwrap_or(0)
            )));
        }
        let tools = tools_source.as_ref().map(|t| tool_table(t, request.files)).transpose()?;
        // The thread given, parsed once.
        let designation = designation.map(|d| self.standard.parse(&d)).transpose()?;
        let spec = ThreadMillSpec {
            program,
            dialect,
            designation,
            allow_nonstandard: self.standard.allow_nonstandard,
            cutter,
            tools,
            blank_diameter: self.blank_diameter,
            comp_radius: self.comp_radius,
            reading: crate::gcode::ReadOptions {
                dialect_from: from,
                sub_files: self.file.sub_files(request.files),
                settings_notes,
                ..self.file.reading.options(&set, None)
            },
            teeth: self.cutter_teeth,
        };
        let r = crate::analysis::thread_mill::thread_mill(&spec)?;
        let inputs = self.file.inputs().into_iter().chain(tools_source.as_ref().and_then(Source::file));
        Ok(Outputs::new(
            Outcome::of(r.pass),
            [
                request
                    .render(Document::Json, || pretty(&crate::report::thread_mill::ThreadMillJson::of(&r)))?,
                request.render(Document::Svg, || Ok(crate::report::thread_mill::thread_mill_svg(&r)))?,
                request.render(Document::Html, || Ok(crate::report::thread_mill::thread_mill_html(&r)))?,
                Some((Document::Text, crate::report::thread_mill::text(&r))),
            ],
        )
        .reading(inputs))
    }

    fn destinations(&self) -> Vec<(Document, Dest)> {
        self.out.destinations(None)
    }
}
