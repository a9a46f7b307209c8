//! The shop's tool table: which insert each T number holds, so that a program's `T0303` chooses
//! the insert threadcheck cuts with.
//!
//! ```toml
//! # T number = "full", "partial", "partial:TIP_RADIUS" or an insert TOML file (relative to this file);
//! # a tap "tap:DESIGNATION[:CHAMFER_PITCHES]" (a form tap "form-tap:…"), a drill
//! # "drill:DIAMETER" (the tapping check)
//! [tools]
//! 3 = "full"
//! 4 = "partial:0.05"
//! 7 = "inserts/tr-30deg.toml"
//! 5 = "drill:8.5"
//! 6 = "tap:M10x1.5-6H"
//! ```

use crate::Error;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Which insert to cut with.
#[derive(Clone, Debug, PartialEq)]
pub enum InsertChoice {
    /// Full profile for the thread's form and pitch.
    Full,
    /// Partial-profile V of the form's angle with this tip radius, mm.
    Partial {
        /// Tip radius, mm.
        tip_radius: f64,
    },
    /// A TOML insert file.
    File(PathBuf),
    /// An insert file's TOML text (the API and the Python package, which read no file of the
    /// server's); `name` stands for the file in messages.
    Toml {
        /// What messages call the insert.
        name: String,
        /// The insert's TOML.
        text: String,
    },
}

impl std::str::FromStr for InsertChoice {
    type Err = Error;

    /// `full`, `partial` (tip radius 0.04 mm), `partial:R` (tip radius R mm) or a TOML file's path.
    ///
    /// ```
    /// use threadcheck::InsertChoice;
    /// assert_eq!("partial:0.035".parse::<InsertChoice>()?, InsertChoice::Partial { tip_radius: 0.035 });
    /// # Ok::<(), threadcheck::Error>(())
    /// ```
    fn from_str(s: &str) -> Result<Self, Error> {
        let lower = s.to_ascii_lowercase();
        match lower.as_str() {
            "full" => Ok(InsertChoice::Full),
            "partial" => Ok(InsertChoice::Partial { tip_radius: 0.04 }),
            // A word that is neither a keyword nor a file name (no extension, no folder).
            _ if !s.is_empty() && !s.contains(['.', '/', '\\', ':']) => Err(Error::Input(format!(
                "insert '{s}': expected full, partial, partial:TIP_RADIUS or an insert FILE.toml"
            ))),
            _ => match lower.strip_prefix("partial:").map(|_| &s[8..]) {
                Some(r) => {
                    let tip_radius: f64 = r.trim().parse().map_err(|_| {
                        Error::Input(format!("insert '{s}': the tip radius '{r}' is not a number"))
                    })?;
                    if !(tip_radius.is_finite() && tip_radius >= 0.0) {
                        return Err(Error::Input(format!(
                            "insert '{s}': the tip radius must be a length ≥ 0"
                        )));
                    }
                    Ok(InsertChoice::Partial { tip_radius })
                }
                None if s.is_empty() => {
                    Err(Error::Input("insert '': expected full, partial[:TIP_RADIUS] or FILE.toml".into()))
                }
                None => Ok(InsertChoice::File(PathBuf::from(s))),
            },
        }
    }
}

/// The chamfer length of a tap given without one, in pitches: form C of ISO 8830 / DIN 2197
/// (2 to 3 threads), taken at its middle; a named default the tapping check states.
pub const DEFAULT_TAP_CHAMFER_PITCHES: f64 = 2.5;

/// What a tool of the table is.
#[derive(Clone, Debug, PartialEq)]
pub enum Tool {
    /// A threading insert.
    Insert(InsertChoice),
    /// A tap: the thread it cuts and its chamfer (lead) length in pitches.
    Tap {
        /// The designation with the class, e.g. M10x1.5-6H.
        designation: String,
        /// Chamfer length, pitches.
        chamfer_pitches: f64,
        /// The chamfer was given (else the default).
        chamfer_given: bool,
        /// A form (roll) tap (`form-tap:`): it displaces the metal into the thread, and its
        /// hole is larger than a cutting tap's.
        forming: bool,
    },
    /// A drill of this diameter, mm.
    Drill {
        /// Diameter, mm.
        diameter: f64,
        /// Its point's included angle, degrees (`drill:8.5:135`); `None` takes a twist drill's
        /// 118°, stated.
        point_angle: Option<f64>,
    },
}

/// The source of [`ToolTable::none`], which names no file.
const NO_TABLE: &str = "no tool table";

/// T numbers and their tools.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ToolTable {
    /// Where the table came from, for messages.
    pub source: String,
    tools: BTreeMap<u32, (Tool, String)>,
    /// `[offsets]`: the cutter radius compensation value (the D register) of each T, mm.
    offsets: BTreeMap<u32, f64>,
    /// `in_spindle = 2`: the tool in the spindle when the program starts, which its cycles take
    /// until it calls another.
    in_spindle: Option<u32>,
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct Raw {
    tools: BTreeMap<String, String>,
    #[serde(default)]
    offsets: BTreeMap<String, f64>,
    in_spindle: Option<u32>,
}

impl ToolTable {
    /// Reads a tool table; insert files are taken relative to `dir`.
    ///
    /// ```
    /// use threadcheck::ToolTable;
    /// use threadcheck::InsertChoice;
    /// let t = ToolTable::from_toml("[tools]\n3 = \"full\"\n", "tools.toml", std::path::Path::new("."))?;
    /// assert_eq!(t.insert(3).map(|x| x.0), Some(&InsertChoice::Full));
    /// # Ok::<(), threadcheck::Error>(())
    /// ```
    pub fn from_toml(text: &str, source: &str, dir: &Path) -> Result<ToolTable, Error> {
        let ferr = |m: String| Error::File { file: source.to_string(), message: m };
        let raw: Raw =
            toml::from_str(text).map_err(|e| crate::ground::error::toml_error(&e, text, source))?;
        let mut tools = BTreeMap::new();
        for (k, v) in raw.tools {
            let t: u32 = k
                .trim_start_matches(['T', 't'])
                .parse()
                .map_err(|_| ferr(format!("tool '{k}' is not a T number (write 3 = \"full\")")))?;
            let forming = v.starts_with("form-tap:");
            let tool = if let Some(rest) = v.strip_prefix("tap:").or_else(|| v.strip_prefix("form-tap:")) {
                let (designation, chamfer) = match rest.rsplit_once(':') {
                    Some((d, c)) => (d, Some(c)),
                    None => (rest, None),
                };
                let chamfer_pitches = match chamfer {
                    Some(c) => c.trim().parse::<f64>().ok().filter(|c| c.is_finite() && *c > 0.0 && *c <= 20.0).ok_or_else(|| {
                        ferr(format!("tool {k} = \"{v}\": the chamfer after the designation is a number of pitches, from over 0 to 20"))
                    })?,
                    None => DEFAULT_TAP_CHAMFER_PITCHES,
                };
                Tool::Tap {
                    designation: designation.trim().to_string(),
                    chamfer_pitches,
                    chamfer_given: chamfer.is_some(),
                    forming,
                }
            } else if let Some(rest) = v.strip_prefix("drill:") {
                let (dia, point) = match rest.split_once(':') {
                    Some((d, p)) => (d, Some(p)),
                    None => (rest, None),
                };
                let bad = || {
                    ferr(format!(
                        "tool {k} = \"{v}\": a drill is drill:DIAMETER in mm, e.g. drill:8.5, or drill:DIAMETER:POINT_ANGLE with its point's included angle in degrees (over 0, under 180), e.g. drill:8.5:135"
                    ))
                };
                let diameter = dia
                    .trim()
                    .parse::<f64>()
                    .ok()
                    .filter(|d| d.is_finite() && *d > 0.0 && *d < 1000.0)
                    .ok_or_else(bad)?;
                let point_angle = point
                    .map(|p| {
                        p.trim()
                            .parse::<f64>()
                            .ok()
                            .filter(|a| a.is_finite() && *a > 0.0 && *a < 180.0)
                            .ok_or_else(bad)
                    })
                    .transpose()?;
                Tool::Drill { diameter, point_angle }
            } else {
                Tool::Insert(match v.parse::<InsertChoice>()? {
                    InsertChoice::File(p) if p.is_relative() => InsertChoice::File(dir.join(p)),
                    c => c,
                })
            };
            // The entry as written, shown in reports: its control characters escaped.
            tools.insert(t, (tool, crate::ground::fmt::shown_text(&v)));
        }
        let mut offsets = BTreeMap::new();
        for (k, v) in raw.offsets {
            let t: u32 = k
                .trim_start_matches(['T', 't'])
                .parse()
                .map_err(|_| ferr(format!("offset '{k}' is not a T number (write 12 = 3.0)")))?;
            if !(v.is_finite() && v.abs() < 1000.0) {
                return Err(ferr(format!("offset {k} = {v}: a compensation value in mm")));
            }
            offsets.insert(t, v);
        }
        Ok(ToolTable {
            source: crate::ground::fmt::shown_text(source),
            tools,
            offsets,
            in_spindle: raw.in_spindle,
        })
    }

    /// A table of `entries` (T, tool, how the source wrote it), from `source` (another
    /// library's format: [`fusion_tool_table`](crate::fusion_tool_table)).
    pub fn from_entries(source: &str, entries: Vec<(u32, Tool, String)>) -> ToolTable {
        ToolTable {
            source: crate::ground::fmt::shown_text(source),
            tools: entries
                .into_iter()
                .map(|(t, tool, w)| (t, (tool, crate::ground::fmt::shown_text(&w))))
                .collect(),
            offsets: BTreeMap::new(),
            in_spindle: None,
        }
    }

    /// No tool table: a program whose tools are named by its own comments, or by options.
    pub fn none() -> ToolTable {
        ToolTable {
            source: NO_TABLE.to_string(),
            tools: BTreeMap::new(),
            offsets: BTreeMap::new(),
            in_spindle: None,
        }
    }

    /// A table was given (a file or a text), not [`none`](Self::none).
    pub fn is_given(&self) -> bool {
        self.source != NO_TABLE
    }

    /// The tool in the spindle when the program starts (`in_spindle = T`), if the table says.
    pub fn in_spindle(&self) -> Option<u32> {
        self.in_spindle
    }

    /// Reads a tool table file.
    pub fn read(path: &Path) -> Result<ToolTable, Error> {
        let shown = path.display().to_string();
        let text = crate::ground::input::read_text_bounded(
            path,
            crate::ground::bounds::MAX_DATA_FILE_BYTES,
            "a tool table",
        )?;
        ToolTable::from_toml(&text, &shown, path.parent().unwrap_or(Path::new(".")))
    }

    /// The first tool whose insert is a file, and how the table wrote it (a server reads no
    /// file).
    pub fn file_entry(&self) -> Option<(u32, &str)> {
        self.tools.iter().find_map(|(t, (c, w))| match c {
            Tool::Insert(InsertChoice::File(_)) => Some((*t, w.as_str())),
            Tool::Insert(InsertChoice::Full | InsertChoice::Partial { .. } | InsertChoice::Toml { .. })
            | Tool::Tap { .. }
            | Tool::Drill { .. } => None,
        })
    }

    /// The insert of tool `t` and how the table wrote it (`None` for a tap, a drill or a tool
    /// not in the table).
    pub fn insert(&self, t: u32) -> Option<(&InsertChoice, &str)> {
        match self.tools.get(&t) {
            Some((Tool::Insert(c), w)) => Some((c, w.as_str())),
            Some((Tool::Tap { .. } | Tool::Drill { .. }, _)) | None => None,
        }
    }

    /// The compensation value of tool `t` (`[offsets]`), mm.
    pub fn offset(&self, t: u32) -> Option<f64> {
        self.offsets.get(&t).copied()
    }

    /// Tool `t` and how the table wrote it.
    pub fn tool(&self, t: u32) -> Option<(&Tool, &str)> {
        self.tools.get(&t).map(|(tool, w)| (tool, w.as_str()))
    }
}
