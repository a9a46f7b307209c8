//! The arguments several commands share, typed once for clap and serde: the thread and its plan
//! or program ([`PlanArgs`]), a file given by path on the command line and as text through the
//! API ([`Source`]), and the readers both sides use.

use crate::analysis::tools::InsertChoice;
use crate::analysis::turn::{ProgramSource, Units, VerifySpec};
use crate::gcode::{Dialect, DialectFrom, GCodeSystem, LinuxCncRelease, ProgramUnits};
use crate::standards::tolerance::CoatingLimits;
use crate::standards::{parse_designation, Designation, ParseOptions};
use crate::toolpath::passes::{InfeedChoice, Schedule};
use crate::Error;
use serde::Deserialize;
use serde_with::{serde_as, DisplayFromStr};
use std::path::{Path, PathBuf};

/// A file an argument names: a path on the command line, its text through the API and Python.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Source {
    /// A file to read.
    Path(PathBuf),
    /// The file's text.
    Text(String),
}

impl Source {
    /// A path (clap's reader).
    pub fn path(s: &str) -> Result<Source, String> {
        Ok(Source::Path(PathBuf::from(s)))
    }

    /// The path, when it is one (a file no output may replace).
    pub fn file(&self) -> Option<PathBuf> {
        match self {
            Source::Path(p) => Some(p.clone()),
            Source::Text(_) => None,
        }
    }

    /// The name messages use (the path, else `text_name`) and the text, read when it is a path.
    pub fn load(&self, text_name: &str) -> Result<(String, String), Error> {
        self.program(text_name).load()
    }

    /// As a program's source, called `text_name` when it is text.
    pub fn program(&self, text_name: &str) -> ProgramSource {
        match self {
            Source::Path(p) => ProgramSource::File(p.clone()),
            Source::Text(t) => ProgramSource::text(text_name, t.clone()),
        }
    }
}

/// Reads an optional [`Source`] from a JSON string: the file's text.
pub(crate) fn source_text<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Option<Source>, D::Error> {
    Ok(Option::<String>::deserialize(d)?.map(Source::Text))
}

/// Reads one designation or a list of them.
pub(crate) fn one_or_many<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Vec<String>, D::Error> {
    #[derive(Deserialize)]
    #[serde(untagged, expecting = "a designation or a list of them")]
    enum OneOrMany {
        One(String),
        Many(Vec<String>),
    }
    Ok(match Option::<OneOrMany>::deserialize(d)? {
        None => Vec::new(),
        Some(OneOrMany::One(s)) => vec![s],
        Some(OneOrMany::Many(v)) => v,
    })
}

/// A finite number (clap's own `f64` reader takes `inf` and `NaN`).
#[cfg_attr(not(feature = "cli"), allow(dead_code))]
pub(crate) fn finite(s: &str) -> Result<f64, String> {
    let v: f64 = s.trim().parse().map_err(|_| "not a number".to_string())?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err("not a finite number".into())
    }
}

/// A pass count of at least one.
#[cfg_attr(not(feature = "cli"), allow(dead_code))]
pub(crate) fn pass_count(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(0) => Err("a thread needs at least one pass".into()),
        Ok(n) => Ok(n),
        Err(_) => Err("not a whole number".into()),
    }
}

/// An operation's number: 1 or more.
#[cfg_attr(not(feature = "cli"), allow(dead_code))]
pub(crate) fn operation_number(s: &str) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(n) if n >= 1 => Ok(n),
        _ => Err("an operation's number, from 1".into()),
    }
}

/// An O-program's number, written `O3101` or `3101`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ONumber(pub u32);

impl std::str::FromStr for ONumber {
    type Err = Error;

    fn from_str(s: &str) -> Result<ONumber, Error> {
        let digits = s.strip_prefix(['O', 'o']).unwrap_or(s);
        match digits.parse::<u32>() {
            Ok(n) if !digits.starts_with('+') => Ok(ONumber(n)),
            _ => Err(Error::Input(format!("'{s}' is not an O-program number such as O3101"))),
        }
    }
}

/// The dialect to read a program called `name` in: the one given, else the one its extension
/// names, else Fanuc; and how it was chosen.
pub fn dialect_for(given: Option<Dialect>, name: &Path) -> (Dialect, DialectFrom) {
    match (given, Dialect::by_extension(name)) {
        (Some(d), _) => (d, DialectFrom::Given),
        (None, Some(d)) => (d, DialectFrom::Extension),
        (None, None) => (Dialect::Fanuc, DialectFrom::Default),
    }
}

/// The JSON's destination on the command line: `--json` or `--json -` for standard output,
/// `--json FILE` for a file.
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[derive(Clone, Debug, Default)]
pub struct JsonArg {
    /// JSON: on stdout instead of the text (`--json` or `--json -`), or written to FILE.
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE|-", num_args = 0..=1, default_missing_value = "-"))]
    pub json: Option<String>,
}

/// How a program is read: the flags of every command that reads one (verify, passes, compare,
/// correct, capability, tap, thread-mill, mill), declared here once. The API and Python take
/// them as keys beside the command's own.
#[serde_as]
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ReadingArgs {
    /// fanuc | haas | sinumerik | linuxcnc | dyna | okuma | mitsubishi | mazak | heidenhain | klartext (default:
    /// the program's extension names it, .ngc linuxcnc, .mpf/.spf sinumerik, .min/.ssb/.sub okuma, .h klartext;
    /// else fanuc)
    #[cfg_attr(feature = "cli", arg(long))]
    #[serde_as(as = "Option<DisplayFromStr>")]
    pub dialect: Option<Dialect>,
    /// The units of a program that sets neither G20 nor G21 (the control's default).
    #[cfg_attr(feature = "cli", arg(long, value_name = "mm|inch"))]
    #[serde_as(as = "Option<DisplayFromStr>")]
    pub default_units: Option<ProgramUnits>,
    /// The main program of a file that holds several O-programs (default: the one no other
    /// calls; the output says which)
    #[cfg_attr(feature = "cli", arg(long, value_name = "O-NUMBER"))]
    #[serde_as(as = "Option<DisplayFromStr>")]
    pub main: Option<ONumber>,
    /// The LinuxCNC release whose comparisons (EQ, NE, LE, GE) a linuxcnc program follows:
    /// current (2.9.0 and later, within 1e-6; the default) or before-2.9 (EQ and NE within 1e-4,
    /// as Debian 12's linuxcnc-uspace package does)
    #[cfg_attr(feature = "cli", arg(long, value_name = "current|before-2.9"))]
    #[serde_as(as = "Option<DisplayFromStr>")]
    pub linuxcnc_release: Option<LinuxCncRelease>,
    /// The G-code system a Fanuc-family lathe control (fanuc, mitsubishi, mazak) is set to: a (G92
    /// threading cycle), b (G78 threading cycle, G92 coordinates) or c (G21 threading cycle, G78
    /// multiple cycle). Default: the program's own words (a G91 is B's or C's: b), else a.
    #[cfg_attr(feature = "cli", arg(long, value_name = "a|b|c"))]
    #[serde_as(as = "Option<DisplayFromStr>")]
    pub gcode_system: Option<GCodeSystem>,
    /// The machine the program runs on: lathe, mill (a machining centre; G90/G91 absolute and
    /// incremental, G98/G99 return levels, G73/G74/G76 drilling, left-hand tapping, fine
    /// boring) or mill-turn (each section by its plane: G18 a lathe's, G17/G19 a mill's).
    /// Default: the machine file's `type`, else the program's own evidence (G17/G18, T12 M6 or
    /// T0101, a drilling cycle's return level, U/W; both kinds: mill-turn), else a lathe; the
    /// notes say which and why. A block that contradicts a lathe or mill given is refused.
    #[cfg_attr(feature = "cli", arg(long, value_name = "lathe|mill|mill-turn"))]
    #[serde_as(as = "Option<DisplayFromStr>")]
    pub machine_type: Option<crate::gcode::MachineType>,
    /// The control's block-delete switch on: skip the program's blocks that begin with `/`
    /// (default off: they run, and the notes say so).
    #[cfg_attr(feature = "cli", arg(long))]
    pub block_delete: bool,
    /// Folders where a LinuxCNC program's `o<name> call` finds `name.ngc` (its INI's
    /// SUBROUTINE_PATH, `:` between folders), after the program's own folder, where Fanuc's
    /// `M98 P2000` finds the file of O2000 too.
    #[cfg_attr(feature = "cli", arg(long, value_name = "DIR[:DIR…]", value_delimiter = ':'))]
    #[serde(skip)]
    pub subroutine_path: Vec<PathBuf>,
}

impl ReadingArgs {
    /// How the program is read: these flags, else what its project file or modeline sets
    /// (`set`), else the machine file's `type` (`machine`), each said where it came from. The
    /// dialect's choice, the subprograms' folders and the settings' notes are the caller's.
    pub(crate) fn options(
        &self,
        set: &super::settings::Settings,
        machine: Option<&crate::analysis::process::MachineProfile>,
    ) -> crate::gcode::ReadOptions {
        let (machine_type, machine_type_by) = match (self.machine_type, &set.machine_type) {
            (Some(t), _) => (Some(t), None),
            (None, Some((t, by))) => (Some(*t), Some(by.phrase())),
            (None, None) => match machine.and_then(|m| m.machine_type.map(|t| (t, &m.name))) {
                Some((t, name)) => (Some(t), Some(format!("the machine file '{name}'"))),
                None => (None, None),
            },
        };
        let (default_units, default_units_by) = set.default_units(self.default_units);
        crate::gcode::ReadOptions {
            default_units,
            default_units_by,
            main: self.main.map(|o| o.0),
            linuxcnc: self.linuxcnc_release.unwrap_or_default(),
            gcode_system: self.gcode_system,
            machine_type,
            machine_type_by,
            block_delete: self.block_delete,
            ..Default::default()
        }
    }

    /// The flags given (by their keys) that describe a program: refused without one.
    pub(crate) fn given_keys(&self) -> Vec<&'static str> {
        [
            ("dialect", self.dialect.is_some()),
            ("default_units", self.default_units.is_some()),
            ("main", self.main.is_some()),
            ("gcode_system", self.gcode_system.is_some()),
            ("linuxcnc_release", self.linuxcnc_release.is_some()),
            ("machine_type", self.machine_type.is_some()),
            ("block_delete", self.block_delete),
            ("subroutine_path", !self.subroutine_path.is_empty()),
        ]
        .into_iter()
        .filter_map(|(k, given)| given.then_some(k))
        .collect()
    }
}

/// The thread and its plan, or its program: the arguments of verify, passes, compare, correct
/// and capability.
#[serde_as]
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PlanArgs {
    /// Thread with its class, e.g. M10x1.5-6g. With a program that cuts several threads, give it
    /// once for all or once per operation, in program order.
    #[cfg_attr(feature = "cli", arg(long, value_name = "THREAD"))]
    #[serde(deserialize_with = "one_or_many")]
    pub thread: Vec<String>,
    /// The internal thread (else external; implied by an upper-case class alone).
    #[cfg_attr(feature = "cli", arg(long))]
    pub internal: bool,
    /// How the designations are read.
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    pub standard: StandardArgs,
    /// full | partial[:TIP_RADIUS] | FILE.toml (default partial, r0.04 mm)
    #[cfg_attr(feature = "cli", arg(long))]
    #[serde_as(as = "Option<DisplayFromStr>")]
    pub insert: Option<InsertChoice>,
    /// An insert file's text (the API and Python; the command line takes its path as --insert).
    #[cfg_attr(feature = "cli", arg(skip))]
    pub insert_toml: Option<String>,
    /// radial | flank[:ANGLE] | modified | alternating[:ANGLE] (default modified: half the thread
    /// angle less 0.5°)
    #[cfg_attr(feature = "cli", arg(long))]
    #[serde_as(as = "Option<DisplayFromStr>")]
    pub infeed: Option<InfeedChoice>,
    /// Number of cutting passes (default about 3.5 + 2·P).
    #[cfg_attr(feature = "cli", arg(long, conflicts_with = "first_depth", value_parser = crate::commands::args::pass_count))]
    pub passes: Option<usize>,
    /// Depth of the first pass, mm (sets the pass count).
    #[cfg_attr(feature = "cli", arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = crate::commands::args::finite))]
    pub first_depth: Option<f64>,
    /// Smallest radial step, mm (default 0).
    #[cfg_attr(feature = "cli", arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = crate::commands::args::finite))]
    pub min_depth: Option<f64>,
    /// Finishing allowance, mm (default 0).
    #[cfg_attr(feature = "cli", arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = crate::commands::args::finite))]
    pub finish: Option<f64>,
    /// Spring (idle) passes at full depth (default 0).
    #[cfg_attr(feature = "cli", arg(long, value_name = "N"))]
    pub spring: Option<usize>,
    /// constant-area | constant-depth | sandvik (default constant-area; compare: both
    /// constant-area and constant-depth unless one is given)
    #[cfg_attr(feature = "cli", arg(long))]
    #[serde_as(as = "Option<DisplayFromStr>")]
    pub schedule: Option<Schedule>,
    /// Explicit cumulative radial depths, mm, e.g. 0.2,0.35,0.45 (instead of a schedule).
    #[cfg_attr(feature = "cli", arg(long, value_name = "LIST", value_delimiter = ',', value_parser = crate::commands::args::finite,
          conflicts_with_all = ["passes", "first_depth", "schedule"]))]
    pub depths: Vec<f64>,
    /// Taper: diameter change per mm of travel, e.g. 0.0625 for 1:16 (passes only; default 0).
    #[cfg_attr(feature = "cli", arg(long, value_name = "RATIO", allow_hyphen_values = true, value_parser = crate::commands::args::finite))]
    pub taper: Option<f64>,
    /// Run-out chamfer at the thread end, in leads (default 0).
    #[cfg_attr(feature = "cli", arg(long, value_name = "LEADS", value_parser = crate::commands::args::finite))]
    pub chamfer: Option<f64>,
    /// A coating the thread gets after cutting, mm (plating, anodizing): checked against the
    /// limits before coating (default 0).
    #[cfg_attr(feature = "cli", arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = crate::commands::args::finite))]
    pub coating: Option<f64>,
    /// Under a coating, the class applies before it (the standards' default: ISO 965-1 §8.5,
    /// ASME B1.1 §7) or after it (when the drawing says so): before | after
    #[cfg_attr(feature = "cli", arg(long, value_name = "before|after"))]
    #[serde_as(as = "Option<DisplayFromStr>")]
    pub coating_limits: Option<CoatingLimits>,
    /// The length of engagement a gauge feels, mm, over which a program's lead error adds up
    /// (default: the nominal diameter, ASME B1.1's LE = D; a taper thread's L1).
    #[cfg_attr(feature = "cli", arg(long, value_name = "MM", value_parser = crate::commands::args::finite))]
    pub engagement: Option<f64>,
    /// Tip diameter of the last pass (default: what puts the pitch diameter mid-tolerance).
    #[cfg_attr(feature = "cli", arg(long, value_name = "DIA", allow_hyphen_values = true, value_parser = crate::commands::args::finite))]
    pub final_x: Option<f64>,
    /// Blank (external) or bore (internal) diameter, mm (default: the middle of the class's major
    /// diameter limits (external) or D1 limits (internal); with a full-profile insert that tops
    /// the crest, d + 0.1 or D1 − 0.1).
    #[cfg_attr(feature = "cli", arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = crate::commands::args::finite))]
    pub blank_diameter: Option<f64>,
    /// Take the passes from this G-code program (a file on the command line, its text through
    /// the API and Python).
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE", value_parser = Source::path))]
    #[serde(deserialize_with = "source_text")]
    pub program: Option<Source>,
    /// What messages call a program given as text; its extension chooses the dialect.
    #[cfg_attr(feature = "cli", arg(skip))]
    pub program_name: Option<String>,
    /// A machine profile for the process checks of a program: FILE.toml (its text through the
    /// API) or training-lathe.
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE.toml|training-lathe", value_parser = Source::path))]
    #[serde(deserialize_with = "source_text")]
    pub machine: Option<Source>,
    /// The insert's side clearance angle, degrees: checks the leading flank against the helix
    /// (default: not given, the leading flank's clearance is not checked).
    #[cfg_attr(feature = "cli", arg(long, value_name = "DEG", allow_hyphen_values = true, value_parser = crate::commands::args::finite))]
    pub clearance_angle: Option<f64>,
    /// Lengths in the text, the SVG and the HTML: mm, or inches with the mm beside them (default:
    /// inch for threads of inch sizes (UN, Acme, NPT, BSW, BSP), else mm)
    #[cfg_attr(feature = "cli", arg(long, value_name = "mm|inch"))]
    pub units: Option<Units>,
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    #[allow(missing_docs)]
    pub reading: ReadingArgs,
    /// The program is an editor's document saved at `program_name` (the language server): its
    /// project file is read as a file's is, though the server reads no other file by name.
    #[cfg_attr(feature = "cli", arg(skip))]
    #[serde(skip)]
    pub saved_document: bool,
}

/// The folder a program file stands in (`.` for a bare file name).
pub(crate) fn program_folder(p: &Path) -> &Path {
    p.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."))
}

/// Where a program in folder `own` finds its subprograms' files: there, then in each folder of
/// the subroutine path.
pub(crate) fn sub_finder_in(own: &Path, subroutine_path: &[PathBuf]) -> crate::gcode::SubFinder {
    let mut dirs = vec![own.to_path_buf()];
    dirs.extend(subroutine_path.iter().cloned());
    sub_finder(dirs)
}

/// Finds the files of the subprograms a program calls in `dirs`, as the controls name them:
/// LinuxCNC's `o<name> call` the file `name.ngc`, Fanuc's `M98 P2000` a file named `O2000`,
/// `O02000` or `2000`, with a program extension or none, Sinumerik's `L9` and `THRSUB` (asked for
/// as `L9.SPF`, `THRSUB.SPF`) the file of that name in any case. Each file is read as a program is
/// (bounded, its encoding checked).
fn sub_finder(dirs: Vec<PathBuf>) -> crate::gcode::SubFinder {
    crate::gcode::SubFinder(std::sync::Arc::new(move |name: &str| {
        let number =
            name.strip_prefix('O').filter(|n| !n.is_empty() && n.bytes().all(|c| c.is_ascii_digit()));
        let stems: Vec<String> = match number {
            Some(n) => {
                let n: String = n.trim_start_matches('0').to_string();
                vec![format!("o{n}"), format!("o{n:0>4}"), format!("o{n:0>5}"), n.clone(), format!("{n:0>4}")]
            }
            None => Vec::new(),
        };
        // Sinumerik's `L9` and `THRSUB`: asked for as `L9.SPF`, `THRSUB.SPF` (any case).
        let sinumerik = name.ends_with(".SPF");
        for dir in &dirs {
            let found = match number {
                None if sinumerik => std::fs::read_dir(dir).ok().and_then(|entries| {
                    entries.filter_map(Result::ok).take(100_000).map(|e| e.path()).find(|p| {
                        p.is_file()
                            && p.file_name()
                                .and_then(|f| f.to_str())
                                .is_some_and(|f| f.eq_ignore_ascii_case(name))
                    })
                }),
                None => Some(dir.join(format!("{name}.ngc"))).filter(|p| p.is_file()),
                Some(_) => std::fs::read_dir(dir).ok().and_then(|entries| {
                    entries.filter_map(Result::ok).take(100_000).map(|e| e.path()).find(|p| {
                        let stem = p.file_stem().and_then(|s| s.to_str()).map(str::to_ascii_lowercase);
                        let ext = p.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
                        p.is_file()
                            && stem.is_some_and(|s| stems.contains(&s))
                            && ext.is_none_or(|e| crate::gcode::PROGRAM_EXTENSIONS.contains(&e.as_str()))
                    })
                }),
            };
            if let Some(path) = found {
                // Named as the program is (`lib/thr.ngc`), without the `./` of its own folder.
                let shown = path.strip_prefix(".").unwrap_or(&path).display().to_string();
                return Some(crate::analysis::turn::read_program_text(&path).map(|text| (shown, text)));
            }
        }
        None
    }))
}

impl PlanArgs {
    /// Whether the insert was chosen (else a tool table's, else the default).
    pub fn insert_given(&self) -> bool {
        self.insert.is_some() || self.insert_toml.is_some()
    }

    /// The checks a command that cuts a thread needs before it runs.
    pub fn need_thread(&self, command: &str) -> Result<(), Error> {
        if self.thread.is_empty() {
            return Err(Error::Input(format!("{command} needs ‹thread› with a class, e.g. M10x1.5-6g")));
        }
        if self.thread.len() > 1 && self.program.is_none() {
            return Err(Error::Input(
                "‹thread› is given more than once: only a program with several threads takes one per operation"
                    .into(),
            ));
        }
        Ok(())
    }

    /// One designation alone (correct, capability, compare).
    pub fn one_thread(&self, command: &str) -> Result<(), Error> {
        self.need_thread(command)?;
        if self.thread.len() > 1 {
            return Err(Error::Input(format!("{command} takes one thread: ‹thread› once")));
        }
        Ok(())
    }

    /// The files this plan reads.
    pub fn inputs(&self) -> Vec<PathBuf> {
        let insert = match &self.insert {
            Some(InsertChoice::File(p)) => Some(p.clone()),
            _ => None,
        };
        [self.program.as_ref().and_then(Source::file), self.machine.as_ref().and_then(Source::file), insert]
            .into_iter()
            .flatten()
            .collect()
    }

    /// What the program's project file and modeline set (nothing without a program).
    pub(crate) fn settings(&self, files: super::Files) -> Result<super::settings::Settings, Error> {
        let files = if self.saved_document { super::Files::Allowed } else { files };
        program_settings(self.program.as_ref(), self.program_name.as_deref(), files)
    }

    /// The flags given that a project file or a modeline also sets, with their values' words.
    pub(crate) fn given(&self) -> super::settings::Given {
        super::settings::Given {
            dialect: self.reading.dialect.map(|d| d.name().to_string()),
            machine_type: self.reading.machine_type.map(|m| m.name().to_string()),
            default_units: self.reading.default_units.map(|u| u.name().to_string()),
            machine: self.machine.as_ref().map(source_words),
            tools: None,
            thread: (!self.thread.is_empty()).then(|| self.thread.join(", ")),
        }
    }

    /// These arguments with what `set` sets where no flag is given.
    fn settled(&self, set: &super::settings::Settings) -> PlanArgs {
        let mut me = self.clone();
        me.reading.dialect = me.reading.dialect.or(set.dialect.as_ref().map(|d| d.0));
        if me.machine.is_none() {
            me.machine = set.machine.as_ref().map(|m| Source::Path(m.0.clone()));
        }
        if me.thread.is_empty() {
            me.thread = set.thread.as_ref().map(|t| t.0.clone()).unwrap_or_default();
        }
        me
    }

    /// The verification the arguments describe, with what the program's project file and
    /// modeline set where no flag is given (each stated in the notes); `files` says whether an
    /// insert may be a path.
    pub fn spec(&self, files: super::Files) -> Result<VerifySpec, Error> {
        self.spec_with(&self.settings(files)?, files).map(|(s, _)| s)
    }

    /// [`spec`](Self::spec) with the project file and modeline already read (`set`): a run
    /// reads them once per program. With every thread given, each parsed once (the spec's
    /// designation is the first).
    pub(crate) fn spec_with(
        &self,
        set: &super::settings::Settings,
        files: super::Files,
    ) -> Result<(VerifySpec, Vec<Designation>), Error> {
        if set.is_empty() {
            return self.spec_as_given(set, files);
        }
        let (mut s, threads) = self.settled(set).spec_as_given(set, files)?;
        s.reading.settings_notes = set.notes(&self.given());
        Ok((s, threads))
    }

    /// The verification the arguments describe, with `set`'s reading where they give none, and
    /// the threads given, parsed.
    fn spec_as_given(
        &self,
        set: &super::settings::Settings,
        files: super::Files,
    ) -> Result<(VerifySpec, Vec<Designation>), Error> {
        let mut s = VerifySpec::new(None);
        s.internal = self.internal;
        s.allow_nonstandard = self.standard.allow_nonstandard;
        s.insert = self.insert_choice(files)?.unwrap_or(InsertChoice::Partial { tip_radius: 0.04 });
        s.infeed = self.infeed;
        s.passes = self.passes;
        s.first_depth = self.first_depth;
        if s.passes.is_some() && s.first_depth.is_some() {
            return Err(Error::Input("‹passes› and ‹first_depth› exclude each other".into()));
        }
        s.min_depth = self.min_depth.unwrap_or(0.0);
        s.finish = self.finish.unwrap_or(0.0);
        s.spring = self.spring.unwrap_or(0);
        s.schedule = match (&self.schedule, self.depths.is_empty()) {
            (Some(_), false) => {
                return Err(Error::Input("‹schedule› and ‹depths› exclude each other".into()))
            }
            (_, false) => Schedule::Explicit(self.depths.clone()),
            (Some(sch), true) => sch.clone(),
            (None, true) => Schedule::ConstantArea,
        };
        s.taper = self.taper.unwrap_or(0.0);
        s.chamfer_leads = self.chamfer.unwrap_or(0.0);
        s.coating = self.coating.unwrap_or(0.0);
        s.coating_limits = self.coating_limits.unwrap_or_default();
        s.engagement = self.engagement;
        s.final_x = self.final_x;
        s.blank_diameter = self.blank_diameter;
        s.clearance_angle = self.clearance_angle;
        match &self.program {
            Some(source) => {
                if let Source::Text(text) = source {
                    if files == super::Files::Allowed && !text.contains('\n') && Path::new(text).is_file() {
                        return Err(Error::Input(format!(
                            "‹program› '{text}' is a file's path: pass the program's text (for example open(path).read())"
                        )));
                    }
                }
                let name = self.program_name.clone().unwrap_or_else(|| "<program>".into());
                let shown = match source {
                    Source::Path(p) => p.clone(),
                    Source::Text(_) => PathBuf::from(&name),
                };
                let (dialect, from) = dialect_for(self.reading.dialect, &shown);
                s.program = Some((source.program(&name), dialect));
                s.reading.dialect_from = from;
                // A program read from a file finds its subprograms' files where the control
                // would: its own folder, then the subroutine path.
                if let (Source::Path(p), super::Files::Allowed) = (source, files) {
                    s.reading.sub_files =
                        Some(sub_finder_in(program_folder(p), &self.reading.subroutine_path));
                }
            }
            None => {
                let mut given = self.reading.given_keys();
                given.extend(
                    [("program_name", self.program_name.is_some()), ("machine", self.machine.is_some())]
                        .into_iter()
                        .filter_map(|(k, g)| g.then_some(k)),
                );
                if let Some(key) = given.first() {
                    return Err(Error::Input(format!(
                        "‹{key}› describes a program: give the program with ‹program› too"
                    )));
                }
            }
        }
        s.machine = self.machine_profile()?;
        s.reading = crate::gcode::ReadOptions {
            dialect_from: s.reading.dialect_from,
            sub_files: s.reading.sub_files.take(),
            ..self.reading.options(set, s.machine.as_ref())
        };
        s.validate()?;
        // Each designation parsed here, once; the rest receives the parse.
        let threads =
            self.thread.iter().map(|t| self.standard.parse(t)).collect::<Result<Vec<_>, Error>>()?;
        s.designation = threads.first().cloned();
        // An inch thread is read in inches beside the mm.
        s.units = self.units.unwrap_or_else(|| VerifySpec::default_units(s.designation.as_ref()));
        s.units_given = self.units.is_some();
        Ok((s, threads))
    }

    /// The insert chosen: `insert` (a path where files may be read) or `insert_toml`.
    fn insert_choice(&self, files: super::Files) -> Result<Option<InsertChoice>, Error> {
        match (&self.insert, &self.insert_toml) {
            (Some(_), Some(_)) => Err(Error::Input("‹insert› and ‹insert_toml› exclude each other".into())),
            (Some(InsertChoice::File(p)), None) if files == super::Files::Refused => {
                Err(Error::Input(format!(
                "‹insert› '{}' names a file, and the server reads none: send its TOML text as ‹insert_toml›",
                p.display()
            )))
            }
            (Some(i), None) => Ok(Some(i.clone())),
            (None, Some(text)) => {
                Ok(Some(InsertChoice::Toml { name: "<insert>".into(), text: text.clone() }))
            }
            (None, None) => Ok(None),
        }
    }

    /// The machine profile: a file, `training-lathe`, or a profile's TOML text.
    fn machine_profile(&self) -> Result<Option<crate::analysis::process::MachineProfile>, Error> {
        machine_profile(self.machine.as_ref())
    }
}

/// What a program's project file and modeline set: `program` its file or text, `name` what a
/// text is called.
fn program_settings(
    program: Option<&Source>,
    name: Option<&str>,
    files: super::Files,
) -> Result<super::settings::Settings, Error> {
    use super::settings::Settings;
    match program {
        Some(Source::Path(p)) => Settings::of(Some(p), None, files),
        Some(Source::Text(t)) => Settings::of(name.map(Path::new), Some(t), files),
        None => Ok(Settings::default()),
    }
}

/// A file argument's words in a note: its path, or `its text`.
pub(crate) fn source_words(s: &Source) -> String {
    match s {
        Source::Path(p) => crate::ground::fmt::path_name(p),
        Source::Text(_) => "(its text)".into(),
    }
}

/// A machine profile given as a file, `training-lathe`, or a profile's TOML text.
pub(crate) fn machine_profile(
    machine: Option<&Source>,
) -> Result<Option<crate::analysis::process::MachineProfile>, Error> {
    use crate::analysis::process::MachineProfile;
    match machine {
        None => Ok(None),
        Some(Source::Path(p)) => MachineProfile::read(&p.display().to_string()).map(Some),
        Some(Source::Text(t)) if t == "training-lathe" => MachineProfile::read(t).map(Some),
        Some(Source::Text(t)) => MachineProfile::from_toml(t, "<machine>").map(Some),
    }
}

/// A tool table: read from its file, or from its text (whose inserts must not be files when
/// files are refused).
pub(crate) fn tool_table(
    source: &Source,
    files: super::Files,
) -> Result<crate::analysis::tools::ToolTable, Error> {
    use crate::analysis::tools::ToolTable;
    match source {
        // A Fusion tool library (JSON) or a tool table (TOML), by what the file holds.
        Source::Path(p) => {
            let text = crate::ground::input::read_text_bounded(
                p,
                crate::ground::bounds::MAX_DATA_FILE_BYTES,
                "a tool table",
            )?;
            if crate::analysis::fusion::is_json(&text) {
                crate::analysis::fusion::tool_table(&text, &p.display().to_string())
            } else {
                ToolTable::from_toml(&text, &p.display().to_string(), p.parent().unwrap_or(Path::new(".")))
            }
        }
        Source::Text(text) if crate::analysis::fusion::is_json(text) => {
            crate::analysis::fusion::tool_table(text, "<tools>")
        }
        Source::Text(text) => {
            let table = ToolTable::from_toml(text, "<tools>", Path::new("."))?;
            if files == super::Files::Refused {
                if let Some((t, written)) = table.file_entry() {
                    return Err(Error::Input(format!(
                        "‹tools›: T{t} = '{written}' names an insert file, and the server reads none: use full, partial or partial:R"
                    )));
                }
            }
            Ok(table)
        }
    }
}

/// The program of `mill`, `tap` and `thread-mill`, and its dialect.
#[serde_as]
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ProgramArgs {
    /// The program (a file on the command line, its text through the API and Python).
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE", required = true, value_parser = Source::path))]
    #[serde(deserialize_with = "source_text")]
    pub program: Option<Source>,
    /// What messages call a program given as text; its extension chooses the dialect.
    #[cfg_attr(feature = "cli", arg(skip))]
    pub program_name: Option<String>,
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    #[allow(missing_docs)]
    pub reading: ReadingArgs,
}

impl ProgramArgs {
    /// Where a program read from a file finds its subprograms' files, as the control would: its
    /// own folder, then the subroutine path (`None` for a program given as text, or when no file
    /// may be read).
    pub fn sub_files(&self, files: super::Files) -> Option<crate::gcode::SubFinder> {
        match (&self.program, files) {
            (Some(Source::Path(p)), super::Files::Allowed) => {
                Some(sub_finder_in(program_folder(p), &self.reading.subroutine_path))
            }
            _ => None,
        }
    }

    /// What the program's project file and modeline set (nothing without a program).
    pub(crate) fn settings(&self, files: super::Files) -> Result<super::settings::Settings, Error> {
        program_settings(self.program.as_ref(), self.program_name.as_deref(), files)
    }

    /// The program's text and name, its dialect (the one given, else the one `set` sets, else
    /// by its extension) and how the dialect was chosen.
    pub fn read(
        &self,
        command: &str,
        set: &super::settings::Settings,
    ) -> Result<((String, String), Dialect, DialectFrom), Error> {
        let source =
            self.program.as_ref().ok_or_else(|| Error::Input(format!("{command} needs ‹program›")))?;
        let (shown, text) = source.load(self.program_name.as_deref().unwrap_or("<program>"))?;
        // A project file's or a modeline's dialect is stated by the settings' notes.
        let dialect = self.reading.dialect.or(set.dialect.as_ref().map(|d| d.0));
        let (dialect, from) = dialect_for(dialect, Path::new(&shown));
        Ok(((text, shown), dialect, from))
    }

    /// The program's file, when it is one.
    pub fn inputs(&self) -> Vec<PathBuf> {
        self.program.as_ref().and_then(Source::file).into_iter().collect()
    }
}

/// Where the command line sends a command's picture, page and JSON.
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[derive(Clone, Debug, Default)]
pub struct PictureArgs {
    /// Write the picture (SVG) to this file.
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE"))]
    pub svg: Option<PathBuf>,
    /// Write a self-contained HTML page (the picture, the checks, the notes) to this file.
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE"))]
    pub html: Option<PathBuf>,
    /// JSON: on stdout instead of the text (`--json` or `--json -`), or written to FILE.
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE|-", num_args = 0..=1, default_missing_value = "-"))]
    pub json: Option<String>,
}

impl PictureArgs {
    /// The destinations, with a corrected program's (`fix`) where the command writes one.
    pub(crate) fn destinations(&self, fix: Option<&Option<String>>) -> Vec<(super::Document, super::Dest)> {
        use super::Document;
        let fix = fix.into_iter().map(|f| (Document::Fix, f));
        super::Dest::list(
            std::iter::once((Document::Json, &self.json)).chain(fix),
            [(Document::Svg, &self.svg), (Document::Html, &self.html)],
        )
    }
}

/// How a command reads a designation: the flags of every command that takes a thread (verify,
/// passes, compare, correct, capability, limits, fit, tap, thread-mill), declared here once. The
/// API and Python take them as keys beside the command's own.
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[derive(Clone, Copy, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct StandardArgs {
    /// Accept a diameter/pitch pair outside the standard series.
    #[cfg_attr(feature = "cli", arg(long))]
    pub allow_nonstandard: bool,
}

impl StandardArgs {
    /// The parser's options these flags set.
    pub fn options(self) -> ParseOptions {
        ParseOptions { allow_nonstandard: self.allow_nonstandard }
    }

    /// `text` parsed, once: the rest of the run receives the parse.
    pub fn parse(self, text: &str) -> Result<Designation, Error> {
        parse_designation(text, self.options())
    }
}

/// Implements [`ApiArgs`](super::ApiArgs) for a command's arguments: `shares field: Type` for a
/// command that flattens shared arguments into its own, `shares nothing` for one that does not;
/// `reads thread at path` where its [`StandardArgs`] sit, for one that reads a designation.
macro_rules! api_args {
    ($args:ty, shares $field:ident: $shared:ty $(, reads thread at $($standard:ident).+)?) => {
        impl $crate::commands::ApiArgs for $args {
            type Shared = $shared;
            fn shared_mut(&mut self) -> Option<&mut $shared> {
                Some(&mut self.$field)
            }
            $($crate::commands::args::api_args!(@standard $($standard).+);)?
        }
    };
    ($args:ty, shares nothing $(, reads thread at $($standard:ident).+)?) => {
        impl $crate::commands::ApiArgs for $args {
            type Shared = $crate::commands::NoShared;
            fn shared_mut(&mut self) -> Option<&mut $crate::commands::NoShared> {
                None
            }
            $($crate::commands::args::api_args!(@standard $($standard).+);)?
        }
    };
    (@standard $($standard:ident).+) => {
        const READS_THREAD: bool = true;
        fn standard_mut(&mut self) -> Option<&mut $crate::commands::args::StandardArgs> {
            Some(&mut self.$($standard).+)
        }
    };
}
pub(crate) use api_args;
