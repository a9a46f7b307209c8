//! What `verify` is asked and what it answers: the spec (`VerifySpec`), the verification
//! (`Verification`), a program's source and its label.

use crate::analysis::check::Check;
use crate::analysis::tools::InsertChoice;
use crate::geometry::insert::Insert;
use crate::geometry::measure::Measurement;
use crate::geometry::sweep::{PassMetrics, Section};
use crate::standards::tolerance::ThreadLimits;
use crate::standards::{parse_designation, Designation, ParseOptions, ThreadKind};
use crate::toolpath::passes::{Infeed, InfeedChoice, Pass, Schedule};
use crate::Error;
use std::path::PathBuf;

/// Everything `verify` needs; the CLI fills it from its options.
#[derive(Clone, Debug, PartialEq)]
pub struct VerifySpec {
    /// The thread with its class (`M10x1.5-6g`), parsed once where it was given; `None` when a
    /// program names its own threads.
    pub designation: Option<Designation>,
    /// Verify the internal thread (else external, unless the designation names only an internal
    /// class).
    pub internal: bool,
    /// Accept sizes outside the standard series.
    pub allow_nonstandard: bool,
    /// The insert.
    pub insert: InsertChoice,
    /// Infeed; `None` picks [`InfeedChoice::Modified`]: flank infeed at half the thread angle less
    /// 0.5°.
    pub infeed: Option<InfeedChoice>,
    /// Cutting passes; `None` uses [`default_pass_count`](super::resolve::default_pass_count).
    pub passes: Option<usize>,
    /// Depth of the first pass, mm (sets the pass count instead).
    pub first_depth: Option<f64>,
    /// Smallest rough step, mm.
    pub min_depth: f64,
    /// Finishing allowance, mm.
    pub finish: f64,
    /// Spring passes.
    pub spring: usize,
    /// Diameter change per mm of travel (taper threads; `passes` only, `verify` checks parallel
    /// threads).
    pub taper: f64,
    /// Run-out chamfer at the thread end, in leads.
    pub chamfer_leads: f64,
    /// Depth schedule.
    pub schedule: Schedule,
    /// Tip diameter of the last pass, mm; `None` solves for the middle of the pitch-diameter
    /// tolerance.
    pub final_x: Option<f64>,
    /// Blank (external) or bore (internal) diameter, mm; `None` uses [`default_blank`](super::resolve::default_blank).
    pub blank_diameter: Option<f64>,
    /// Leave form checks out of the verdict.
    pub gauge_only: bool,
    /// Take the passes from this G-code program (a file, or text held in memory) instead of
    /// generating a plan.
    pub program: Option<(ProgramSource, crate::gcode::Dialect)>,
    /// How to read the program: its default units, how its dialect was chosen.
    pub reading: crate::gcode::ReadOptions,
    /// Compute the per-pass chip and edge metrics (polygon booleans; reports need them, a
    /// catalogue sweep does not).
    pub metrics: bool,
    /// Compute what the pictures draw ([`Picture`](crate::Picture): the
    /// full-length section, the zone and basic profiles, the deviation samples), for a report.
    pub picture: bool,
    /// Chord tolerance for arcs, mm.
    pub tolerance: f64,
    /// Lengths in the text and the picture: mm, or mm with inches beside them.
    pub units: Units,
    /// `units` was chosen by the user; else each operation of a program takes its own
    /// designation's default ([`VerifySpec::default_units`]).
    pub units_given: bool,
    /// Z of the stock's bottom face, mm: a program's tapped holes whose drill passes it are
    /// through holes (`None`: not known).
    pub stock_bottom: Option<f64>,
    /// The machine whose limits the process checks of a program use.
    pub machine: Option<crate::analysis::process::MachineProfile>,
    /// The insert's side clearance angle, degrees, for the flank-clearance check.
    pub clearance_angle: Option<f64>,
    /// Thickness of a coating the thread gets after cutting (plating, anodizing), mm; 0 for
    /// none. The thread is checked against the limits before coating
    /// ([`ThreadLimits::for_coating`]) and the report says what it measures after.
    pub coating: f64,
    /// Which limits the class applies to under a coating: before it (the standards' default)
    /// or after it (when the drawing says so).
    pub coating_limits: crate::standards::tolerance::CoatingLimits,
    /// The length of engagement a gauge feels, mm, over which a program's lead error adds up
    /// (`None`: the nominal diameter, or a taper thread's L1).
    pub engagement: Option<f64>,
    /// Of a program that cuts several threads, the one operation to check (1-based, in program
    /// order): `correct` and `capability` take one, a program of one needs none.
    pub operation: Option<usize>,
}

/// How the text report and the picture give lengths.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Units {
    /// Millimetres.
    #[default]
    Mm,
    /// Inches, with the mm beside them (the inch forms' tables print inches).
    Inch,
}

impl std::str::FromStr for Units {
    type Err = Error;

    /// `mm` or `inch`.
    fn from_str(s: &str) -> Result<Units, Error> {
        match s {
            "mm" => Ok(Units::Mm),
            "inch" => Ok(Units::Inch),
            _ => Err(Error::Input(format!("units '{s}': expected mm or inch"))),
        }
    }
}

impl VerifySpec {
    /// The rules every door shares (the command line, the API, the Python package): numbers
    /// finite, at least one pass, and a program or a final X, not both. The computation checks
    /// the ranges that depend on the thread (a tip radius, a coating, a blank) where it resolves
    /// it.
    ///
    /// ```
    /// use threadcheck::VerifySpec;
    /// let spec = VerifySpec { passes: Some(0), ..VerifySpec::of("M10x1.5-6g")? };
    /// assert_eq!(spec.validate().map_err(|e| e.to_string()), Err("passes 0: a thread needs at least one pass".into()));
    /// # Ok::<(), threadcheck::Error>(())
    /// ```
    pub fn validate(&self) -> Result<(), Error> {
        if self.passes == Some(0) {
            return Err(Error::Input("passes 0: a thread needs at least one pass".into()));
        }
        match (self.operation, &self.program) {
            (Some(0), _) => return Err(Error::Input("operation 0: operations are numbered from 1".into())),
            (Some(_), None) => {
                return Err(Error::Input("an operation is a program's: give the program it is one of".into()))
            }
            _ => {}
        }
        let numbers = [
            ("first_depth", self.first_depth),
            ("min_depth", Some(self.min_depth)),
            ("finish", Some(self.finish)),
            ("taper", Some(self.taper)),
            ("chamfer", Some(self.chamfer_leads)),
            ("coating", Some(self.coating)),
            ("final_x", self.final_x),
            ("blank_diameter", self.blank_diameter),
            ("clearance_angle", self.clearance_angle),
            ("engagement", self.engagement),
        ];
        for (name, v) in numbers {
            if let Some(v) = v.filter(|v| !v.is_finite()) {
                return Err(Error::Input(format!("{name} {v} is not a finite number")));
            }
        }
        if let Some(le) = self.engagement.filter(|le| !(*le > 0.0 && *le <= 10_000.0)) {
            return Err(Error::Input(format!(
                "engagement {} mm: a length of engagement is above 0 and at most 10 000 mm",
                crate::ground::fmt::fmt_num(le)
            )));
        }
        if let Schedule::Explicit(d) = &self.schedule {
            if d.iter().any(|x| !x.is_finite()) {
                return Err(Error::Input("depths: every depth must be a finite number".into()));
            }
        }
        if self.program.is_some() && self.final_x.is_some() {
            return Err(Error::Input(
                "a final X and a program exclude each other: the program sets the passes".into(),
            ));
        }
        Ok(())
    }

    /// The units a designation is reported in by default: inches beside the mm for the inch
    /// forms (UN, Acme, NPT, BSW, BSP), else mm (and for none).
    pub fn default_units(designation: Option<&Designation>) -> Units {
        match designation {
            Some(d) if d.thread.form.is_inch() => Units::Inch,
            _ => Units::Mm,
        }
    }

    /// A spec for the thread `designation` names, its size in its standard series, with the
    /// defaults for everything else.
    ///
    /// ```
    /// use threadcheck::VerifySpec;
    /// assert_eq!(VerifySpec::of("M10x1.5-6g")?.designation.map(|d| d.thread.pitch), Some(1.5));
    /// assert!(VerifySpec::of("M10x1.3-6g").is_err()); // not an ISO 261 pitch for M10
    /// # Ok::<(), threadcheck::Error>(())
    /// ```
    pub fn of(designation: &str) -> Result<VerifySpec, Error> {
        Ok(VerifySpec::new(Some(parse_designation(designation, ParseOptions::default())?)))
    }

    /// A spec with the defaults for everything but the designation (`None`: a program names its
    /// threads).
    pub fn new(designation: Option<Designation>) -> VerifySpec {
        VerifySpec {
            designation,
            internal: false,
            allow_nonstandard: false,
            insert: InsertChoice::Partial { tip_radius: 0.04 },
            infeed: None,
            passes: None,
            first_depth: None,
            min_depth: 0.0,
            finish: 0.0,
            taper: 0.0,
            chamfer_leads: 0.0,
            spring: 0,
            schedule: Schedule::ConstantArea,
            final_x: None,
            blank_diameter: None,
            gauge_only: false,
            program: None,
            reading: crate::gcode::ReadOptions::default(),
            metrics: true,
            picture: false,
            tolerance: crate::DEFAULT_TOLERANCE,
            units: Units::Mm,
            units_given: false,
            stock_bottom: None,
            machine: None,
            clearance_angle: None,
            coating: 0.0,
            coating_limits: crate::standards::tolerance::CoatingLimits::Before,
            engagement: None,
            operation: None,
        }
    }

    /// The same spec with its passes taken from program text held in memory (a post-processor's
    /// output); `name` is what messages call it (`name:line:column`).
    ///
    /// ```
    /// use threadcheck::{verify, InsertChoice, VerifySpec};
    /// use threadcheck::Dialect;
    /// let g76 = "G0 X22 Z5\nG76 P010060 Q100 R0.02\nG76 X18.2 Z-20 P900 Q300 F1.5\n";
    /// let spec = VerifySpec { insert: InsertChoice::Full, ..VerifySpec::of("M20x1.5-6g")? };
    /// let v = verify(&spec.with_program_text("post.nc", g76, Dialect::Fanuc))?;
    /// // A full-profile tip at X18.2 leaves d2 = 18.2 + 0.57735·1.5 = 19.066: 72 µm over 6g.
    /// assert!(!v.pass);
    /// assert!(v.suggested_final_x.unwrap() < 18.2);
    /// # Ok::<(), threadcheck::Error>(())
    /// ```
    pub fn with_program_text(
        self,
        name: impl Into<String>,
        text: impl Into<String>,
        dialect: crate::gcode::Dialect,
    ) -> VerifySpec {
        VerifySpec { program: Some((ProgramSource::text(name, text), dialect)), ..self }
    }
}

/// Everything `verify` found.
#[derive(Clone, Debug)]
pub struct Verification {
    /// The parsed designation.
    pub designation: Designation,
    /// External or internal.
    pub kind: ThreadKind,
    /// Limits of the class verified.
    pub limits: ThreadLimits,
    /// The insert used.
    pub insert: Insert,
    /// Infeed used.
    pub infeed: Infeed,
    /// Schedule used.
    pub schedule: Schedule,
    /// For a program's passes, the infeed and depth law read back from them (`infeed` and
    /// `schedule` are then the options', which the passes did not follow).
    pub cut_plan: Option<crate::analysis::turn::cut_plan::CutPlan>,
    /// An internal 60° thread's percent of thread from its bore (the charts' figure, issue 64).
    pub thread_percent: Option<crate::analysis::percent::ThreadPercent>,
    /// Blank or bore diameter, mm.
    pub blank_diameter: f64,
    /// Tip diameter of the last pass, mm.
    pub final_x: f64,
    /// True when `final_x` was solved for mid-tolerance pitch diameter.
    pub final_x_solved: bool,
    /// The passes.
    pub passes: Vec<Pass>,
    /// Per-pass chip and edge metrics at the measured groove.
    pub metrics: Vec<PassMetrics>,
    /// The as-cut section around the measured groove.
    pub section: Section,
    /// Axial position of the measured groove, mm.
    pub z_ref: f64,
    /// The measurement.
    pub measurement: Measurement,
    /// The checks.
    pub checks: Vec<Check>,
    /// The verdict.
    pub pass: bool,
    /// Final X that would put the pitch diameter mid-tolerance, when it is off, mm.
    pub suggested_final_x: Option<f64>,
    /// Final X that puts the pitch diameter mid-tolerance, whether it is off or not (what a
    /// post-processor emits), mm; `None` when no X helps (a start missing).
    pub middle_final_x: Option<f64>,
    /// Form checks left out of the verdict.
    pub gauge_only: bool,
    /// Assumptions and warnings worth printing.
    pub notes: Vec<crate::ground::note::Note>,
    /// The program the passes came from and its dialect, when they came from one.
    pub program: Option<ProgramLabel>,
    /// Lengths in the text and the picture.
    pub units: Units,
    /// Helix angle at the basic pitch diameter, degrees: the insert inclination it asks for.
    pub helix_angle: f64,
    /// The process checks' findings, for a program's operation.
    pub process: Option<crate::analysis::process::ProcessReport>,
    /// A program's lead that matches the designation's only after rounding to the program's
    /// increment: the difference and its pitch-diameter equivalent.
    pub lead_deviation: Option<crate::analysis::turn::lead::LeadDeviation>,
    /// The change of the program's own depth word that puts d2 mid-tolerance, when d2 (or the
    /// gauge plane, or the functional d2) is off and the program has such a word.
    pub correction: Option<crate::analysis::turn::correction::Correction>,
    /// The functional (virtual) pitch diameter where the lead deviates: the measured d2 plus
    /// (external) or less (internal) the lead error's equivalent, mm.
    pub functional_pitch_diameter: Option<f64>,
    /// What the pictures draw, when the spec asked for it.
    pub picture: Option<crate::analysis::picture::Picture>,
    /// What the failing form checks say about the insert or the infeed.
    pub hints: Vec<crate::analysis::check::Hint>,
    /// The program's word that sets the final depth, for a correction by any amount
    /// ([`Verification::correction_for`]).
    pub(super) depth: Option<DepthAt>,
}

/// A program operation's depth word, its units, and the same word in the cycles of its other
/// starts (with whether they are written alike).
#[derive(Clone, Debug)]
pub(super) struct DepthAt {
    pub(super) word: crate::gcode::DepthWord,
    pub(super) units: crate::gcode::ProgramUnits,
    pub(super) also: Vec<crate::analysis::turn::correction::Place>,
    pub(super) alike: bool,
    /// The X words that set the operation's passes.
    pub(super) pass_x_words: Vec<crate::gcode::PassXWord>,
}

impl DepthAt {
    /// The same change in the other starts' cycles (a word written otherwise in one of them is
    /// not rewritten in place), and the earlier passes that cut deeper than the new value.
    pub(super) fn apply_to(&self, c: &mut crate::analysis::turn::correction::Correction, kind: ThreadKind) {
        c.also = self.also.clone();
        if !self.alike {
            c.form = crate::gcode::WordForm::Expression;
        }
        c.deeper = crate::analysis::turn::correction::deeper_words(c, &self.pass_x_words, kind);
    }
}

impl Verification {
    /// The correction in the program's words that moves the pitch diameter by `delta_d2` mm (+
    /// larger): `None` for a generated plan, or where no correction is offered (the starts are
    /// wrong, the program sets no depth word).
    pub fn correction_for(&self, delta_d2: f64) -> Option<crate::analysis::turn::correction::Correction> {
        let d = self.depth.as_ref()?;
        let mut c = crate::analysis::turn::correction::correction(&d.word, d.units, self.kind, delta_d2);
        d.apply_to(&mut c, self.kind);
        Some(c)
    }
}

/// Where a program comes from: a file, or text a post-processor holds in memory.
///
/// ```
/// use threadcheck::ProgramSource;
/// let p = ProgramSource::text("post.nc", "G0 X22 Z5\nG76 P010060 Q50 R0.02\n");
/// let (name, text) = p.load()?;
/// assert_eq!(name, "post.nc");
/// assert!(text.starts_with("G0"));
/// # Ok::<(), threadcheck::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum ProgramSource {
    /// A program file.
    File(PathBuf),
    /// Program text; `name` stands for the file in messages (`name:line:column`).
    Text {
        /// What messages call the program.
        name: String,
        /// The program.
        text: String,
    },
}

impl ProgramSource {
    /// Program text in memory, called `name` in messages.
    pub fn text(name: impl Into<String>, text: impl Into<String>) -> Self {
        ProgramSource::Text { name: name.into(), text: text.into() }
    }

    /// The name messages use and the text, read from the file if it is one; bounded in size and
    /// read by [`text_of`]'s rules either way.
    pub fn load(&self) -> Result<(String, String), Error> {
        match self {
            ProgramSource::File(path) => Ok((crate::ground::fmt::path_name(path), read_program_text(path)?)),
            ProgramSource::Text { name, text } => {
                if text.len() > crate::ground::bounds::MAX_PROGRAM_BYTES {
                    return Err(Error::Program {
                        file: name.clone(),
                        line: 1,
                        column: 1,
                        message: format!(
                            "the program is larger than {} bytes",
                            crate::ground::bounds::MAX_PROGRAM_BYTES
                        ),
                    });
                }
                // The file's rules for pasted text too (issue 58: one reader for every route): a
                // DOS end-of-file ^Z ends it, a NUL byte or an empty program is refused.
                Ok((name.clone(), text_of(text.as_bytes(), name)?))
            }
        }
    }
}

/// Reads a program file as text, bounded in size, refusing binary files.
///
/// ```
/// let e = threadcheck::read_program_text(std::path::Path::new("no/such/program.nc")).unwrap_err();
/// assert!(e.to_string().starts_with("no/such/program.nc:"));
/// ```
pub fn read_program_text(path: &std::path::Path) -> Result<String, Error> {
    let shown = crate::ground::fmt::path_name(path);
    let bytes =
        crate::ground::input::read_bounded(path, crate::ground::bounds::MAX_PROGRAM_BYTES, "the program")?;
    text_of(&bytes, &shown)
}

/// The text of a program file: UTF-8 (a byte-order mark is fine), no NUL bytes. A DOS
/// end-of-file byte (^Z, 0x1A), which training-lathe software still writes, ends the text.
/// Bytes that are not UTF-8 are refused, unless every one lies in a comment (`(…)` or after
/// `;`: shops' files carry CP1251, GBK and Latin-1 comments), where each becomes U+FFFD and the
/// program's notes say so.
///
/// ```
/// let t = threadcheck::text_of(b"G0 X10 (\xc4\xe5\xf2\xe0\xeb\xfc)\nM30\n\x1a", "p.nc")?;
/// assert_eq!(t, "G0 X10 (\u{fffd}\u{fffd}\u{fffd}\u{fffd}\u{fffd}\u{fffd})\nM30\n");
/// assert!(threadcheck::text_of(b"G0 X1\xe5\n", "p.nc").is_err());
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn text_of(bytes: &[u8], file: &str) -> Result<String, Error> {
    let at = |offset: usize, message: String| {
        let before = &bytes[..offset];
        let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
        let column = offset - before.iter().rposition(|&b| b == b'\n').map_or(0, |p| p + 1) + 1;
        Error::Program { file: file.to_string(), line, column, message }
    };
    let bytes = match bytes.iter().position(|&b| b == 0x1a) {
        Some(end) => &bytes[..end],
        None => bytes,
    };
    if bytes.is_empty() {
        return Err(at(0, "the program is empty".into()));
    }
    if let Some(i) = bytes.iter().position(|&b| b == 0) {
        return Err(at(
            i,
            "a NUL byte: this is a binary file, not a program (a control's own stored format, a Mazatrol conversational program's among them, is no G-code: export the program as EIA/ISO code)".into(),
        ));
    }
    if let Ok(text) = std::str::from_utf8(bytes) {
        return Ok(text.to_string());
    }
    // Line by line: the bytes that are not UTF-8 must all sit in comments.
    let mut out = String::with_capacity(bytes.len());
    let mut offset = 0;
    for line in bytes.split_inclusive(|&b| b == b'\n') {
        let decoded = String::from_utf8_lossy(line);
        if let std::borrow::Cow::Owned(_) = decoded {
            let code_end = line.iter().position(|&b| b == b'(' || b == b';').unwrap_or(line.len());
            if let Err(e) = std::str::from_utf8(&line[..code_end]) {
                return Err(at(
                    offset + e.valid_up_to(),
                    "not UTF-8 text outside a comment: a binary file or another encoding".into(),
                ));
            }
        }
        out.push_str(&decoded);
        offset += line.len();
    }
    Ok(out)
}

/// A program as the reports name it: the file (as given) and the dialect it was read in.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ProgramLabel {
    /// The file's name as given (messages name it so).
    pub file: String,
    /// The dialect.
    pub dialect: crate::gcode::Dialect,
}

impl std::fmt::Display for ProgramLabel {
    /// `dir/p.nc (fanuc)`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} ({})", self.file, self.dialect.name())
    }
}

impl serde::Serialize for ProgramLabel {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}
