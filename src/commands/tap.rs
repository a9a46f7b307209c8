//! `threadcheck tap`: a program's tapping cycles against their taps and drills.

use super::args::{tool_table, ProgramArgs, Source};
use super::{pretty, Dest, Document, Job, Outcome, Outputs, Request};
use crate::analysis::tap::TapSpec;
use crate::gcode::ReadOptions;
use crate::Error;
use serde::Deserialize;
use serde_with::{serde_as, DisplayFromStr};

/// The arguments of `tap`.
#[serde_as]
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TapArgs {
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    #[allow(missing_docs)]
    pub file: ProgramArgs,
    /// The tool table: each tap as T = "tap:M10x1.5-6H[:CHAMFER_PITCHES]" (a form tap
    /// "form-tap:M10x1.5-6H", checked against the larger hole it needs), each drill as
    /// T = "drill:8.5" (a file on the command line, its text through the API); a tap or drill it
    /// does not name is taken from the program's comments ((TAP M10X1.5), (DRILL 8.5)), else the
    /// tap is the standard size of its lead over its drill.
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE.toml", value_parser = Source::path))]
    #[serde(deserialize_with = "super::args::source_text")]
    pub tools: Option<Source>,
    /// How the designation is read.
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    pub standard: super::StandardArgs,
    /// Z of the stock's bottom face, mm: a hole whose drill passes it with its full diameter is a
    /// through hole, whose depth needs no room below the tap (default: the program's own stock
    /// definition, Klartext's BLK FORM, else every hole blind).
    #[cfg_attr(feature = "cli", arg(long, value_name = "Z", allow_hyphen_values = true, value_parser = crate::commands::args::finite))]
    pub stock_bottom: Option<f64>,
    /// The tap of the tapping cycles whose tool is not known (no T before them and no in_spindle
    /// in the tool table, or a T the tool table does not name), e.g. M10x1.5-6H
    #[cfg_attr(feature = "cli", arg(long, value_name = "DESIGNATION"))]
    pub tap: Option<String>,
    /// The workpiece's material, for each hole's tapping torque and power by the tap maker's
    /// equation (st44-2, ck15, ck35, ck45 or c45, ck60, 42crmo4, 42crmo4-30hrc, 42crmo4-40hrc,
    /// x6crni18-10, c105w2, cuzn40, g-alsi8cu3, gg-25).
    #[cfg_attr(feature = "cli", arg(long, value_name = "MATERIAL"))]
    pub material: Option<String>,
    /// The taps' kind, for the torque: hand-plug, hand-bottoming, spiral-fluted (the default) or
    /// spiral-pointed.
    #[cfg_attr(feature = "cli", arg(long, value_name = "KIND"))]
    #[serde_as(as = "Option<DisplayFromStr>")]
    pub tap_kind: Option<crate::standards::torque::TapKind>,
    /// The machine file (FILE.toml; its text through the API): its `type` reads the program,
    /// its `spindle_torque_nm` and `spindle_power_kw` hold each tap's torque and power.
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE.toml", value_parser = Source::path))]
    #[serde(deserialize_with = "super::args::source_text")]
    pub machine: Option<Source>,
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    #[allow(missing_docs)]
    pub out: super::args::PictureArgs,
}

super::args::api_args!(TapArgs, shares file: ProgramArgs, reads thread at standard);

impl Job for TapArgs {
    const NAME: &'static str = "tap";
    const DOCUMENTS: &'static [Document] = &[Document::Json, Document::Text, Document::Svg, Document::Html];

    /// Pass when every tapping cycle passes every check.
    fn run(&self, request: &Request) -> Result<Outputs, Error> {
        let set = self.file.settings(request.files)?;
        let (program, dialect, from) = self.file.read("tap", &set)?;
        let machine_source =
            self.machine.clone().or_else(|| set.machine.as_ref().map(|m| Source::Path(m.0.clone())));
        let tools_source =
            self.tools.clone().or_else(|| set.tools.as_ref().map(|t| Source::Path(t.0.clone())));
        let machine = super::args::machine_profile(machine_source.as_ref())?;
        let settings_notes = set.notes(&super::settings::Given {
            dialect: self.file.reading.dialect.map(|d| d.name().to_string()),
            machine_type: self.file.reading.machine_type.map(|m| m.name().to_string()),
            default_units: self.file.reading.default_units.map(|u| u.name().to_string()),
            machine: self.machine.as_ref().map(super::args::source_words),
            tools: self.tools.as_ref().map(super::args::source_words),
            thread: self.tap.clone(),
        });
        let reading = ReadOptions {
            dialect_from: from,
            settings_notes,
            sub_files: self.file.sub_files(request.files),
            ..self.file.reading.options(&set, machine.as_ref())
        };
        let tools = match &tools_source {
            Some(t) => tool_table(t, request.files)?,
            None => crate::analysis::tools::ToolTable::none(),
        };
        // The tap given, else the project file's or the modeline's thread: parsed once.
        let tap = self.tap.clone().or_else(|| set.thread.as_ref().and_then(|t| t.0.first().cloned()));
        let tap = tap.map(|t| self.standard.parse(&t)).transpose()?;
        let spec = TapSpec {
            program,
            dialect,
            reading,
            tools,
            allow_nonstandard: self.standard.allow_nonstandard,
            from_program: true,
            stock_bottom: self.stock_bottom,
            tap,
            torque: match &self.material {
                Some(m) => Some(crate::analysis::tap::TorqueSpec {
                    material: crate::standards::torque::material(m)?,
                    kind: self.tap_kind.unwrap_or(crate::standards::torque::TapKind::SpiralFluted),
                    kind_given: self.tap_kind.is_some(),
                }),
                None if self.tap_kind.is_some() => {
                    return Err(Error::Input(
                        "‹tap_kind› is for the torque, which needs the workpiece's ‹material›".into(),
                    ))
                }
                None => None,
            },
            machine,
        };
        let r = crate::analysis::tap::tap(&spec)?;
        let inputs = self
            .file
            .inputs()
            .into_iter()
            .chain(tools_source.as_ref().and_then(Source::file))
            .chain(machine_source.as_ref().and_then(Source::file));
        Ok(Outputs::new(
            Outcome::of(r.pass),
            [
                request.render(Document::Json, || pretty(&r))?,
                request.render(Document::Svg, || Ok(crate::report::tap::tap_svg(&r)))?,
                request.render(Document::Html, || Ok(crate::report::tap::tap_html(&r)))?,
                Some((Document::Text, crate::report::tap::text(&r))),
            ],
        )
        .reading(inputs))
    }

    fn destinations(&self) -> Vec<(Document, Dest)> {
        self.out.destinations(None)
    }
}
