//! `verify` as a library call: from a designation with its class, an insert and a pass plan to
//! the as-cut thread, its measurement, the checks and the verdict.

use crate::analysis::check::{checks, verdict, Check};
use crate::analysis::taper::{cone_of, taper_of, true_flank_angles, Taper, TAPER_FACE_NOTE};
use crate::analysis::tools::InsertChoice;
use crate::geometry::boolean::UnionStrategy;
use crate::geometry::insert::{Insert, InsertKind};
use crate::geometry::measure::{measure, MeasureSetup, Measurement};
use crate::geometry::sweep::{pass_metrics, sweep, PassMetrics, Section, SweepSetup, Window};
use crate::ground::bounds::MAX_DATA_FILE_BYTES;
use crate::standards::tolerance::{limits_for, ThreadLimits};
use crate::standards::{parse_designation, Designation, ParseOptions, ProfileKind, ThreadKind};
use crate::toolpath::passes::{Infeed, InfeedChoice, Pass, PlanSpec, Schedule};
use crate::{BasicThread, Error};
use std::path::PathBuf;

/// Everything `verify` needs; the CLI fills it from its options.
#[derive(Clone, Debug, PartialEq)]
pub struct VerifySpec {
    /// Designation with a class (`M10x1.5-6g`).
    pub designation: String,
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
    /// Cutting passes; `None` uses [`default_pass_count`].
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
    /// Blank (external) or bore (internal) diameter, mm; `None` uses [`default_blank`].
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
    /// let spec = VerifySpec { passes: Some(0), ..VerifySpec::new("M10x1.5-6g") };
    /// assert_eq!(spec.validate().map_err(|e| e.to_string()), Err("passes 0: a thread needs at least one pass".into()));
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
    /// forms (UN, Acme, NPT, BSW, BSP), else mm; a designation that does not parse gets mm (its
    /// error is reported where it is resolved).
    pub fn default_units(designation: &str, allow_nonstandard: bool) -> Units {
        match parse_designation(designation, ParseOptions { allow_nonstandard }) {
            Ok(d) if d.thread.form.is_inch() => Units::Inch,
            _ => Units::Mm,
        }
    }

    /// A spec with the defaults for everything but the designation.
    pub fn new(designation: &str) -> VerifySpec {
        VerifySpec {
            designation: designation.to_string(),
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
    /// let spec = VerifySpec { insert: InsertChoice::Full, ..VerifySpec::new("M20x1.5-6g") };
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
    pub(crate) depth: Option<DepthAt>,
}

/// A program operation's depth word, its units, and the same word in the cycles of its other
/// starts (with whether they are written alike).
#[derive(Clone, Debug)]
pub(crate) struct DepthAt {
    word: crate::gcode::DepthWord,
    units: crate::gcode::ProgramUnits,
    also: Vec<crate::analysis::turn::correction::Place>,
    alike: bool,
    /// The X words that set the operation's passes.
    pass_x_words: Vec<crate::gcode::PassXWord>,
}

impl DepthAt {
    /// The same change in the other starts' cycles (a word written otherwise in one of them is
    /// not rewritten in place), and the earlier passes that cut deeper than the new value.
    fn apply_to(&self, c: &mut crate::analysis::turn::correction::Correction, kind: ThreadKind) {
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

/// Usual number of passes for a pitch P (mm): about 3.5 + 2·P, the order of the insert makers'
/// recommendations for steel (4 passes at P 0.5, 6 at P 1.5, 15 at P 6). A default, not a standard.
pub fn default_pass_count(pitch: f64) -> usize {
    (3.5 + 2.0 * pitch).round().clamp(3.0, 40.0) as usize
}

/// The blank a shop turns before threading: for a full-profile insert that tops the crest, d +
/// 0.1 mm (external) or D1 − 0.1 mm (internal); otherwise the middle of the major-diameter
/// tolerance (external) or of the D1 tolerance (internal), since that is the crest left.
pub fn default_blank(thread: &BasicThread, kind: ThreadKind, limits: &ThreadLimits, insert: &Insert) -> f64 {
    match (insert.kind == InsertKind::Full && thread.form.full_insert_tops_crest(), kind) {
        (true, ThreadKind::External) => thread.nominal_diameter + 0.1,
        (true, ThreadKind::Internal) => thread.minor_diameter_internal() - 0.1,
        (false, ThreadKind::External) => limits
            .major_diameter
            .mid()
            .unwrap_or_else(|| limits.major_diameter.max.unwrap_or(thread.nominal_diameter)),
        (false, ThreadKind::Internal) => {
            limits.minor_diameter.mid().unwrap_or(thread.minor_diameter_internal())
        }
    }
}

fn resolve_kind(des: &Designation, internal: bool) -> Result<ThreadKind, Error> {
    let kind = if internal || (des.external.is_none() && des.internal.is_some()) {
        ThreadKind::Internal
    } else {
        ThreadKind::External
    };
    if des.class(kind).is_none() {
        return Err(Error::Input(format!(
            "'{}' names no {} class to verify against; add one, e.g. {}",
            des.text,
            kind.name(),
            des.with_example_class(kind)
        )));
    }
    Ok(kind)
}

fn build_insert(choice: &InsertChoice, t: &BasicThread, kind: ThreadKind, tol: f64) -> Result<Insert, Error> {
    let ins = match choice {
        InsertChoice::Full => Insert::full_profile(t, kind, tol),
        InsertChoice::Partial { tip_radius } => {
            let limit = t.root_radius();
            if *tip_radius > limit {
                return Err(Error::Geometry(format!(
                    "tip radius {tip_radius} mm is larger than the thread allows: the largest root radius at pitch {} mm ({} form) is {limit:.4} mm",
                    crate::ground::fmt::fmt_num(t.pitch),
                    t.form.name()
                )));
            }
            Insert::partial_for(t, *tip_radius, tol)?
        }
        InsertChoice::File(path) => {
            let text = crate::ground::input::read_text_bounded(path, MAX_DATA_FILE_BYTES, "an insert file")?;
            Insert::from_toml(&text, &path.display().to_string(), tol)?
        }
        InsertChoice::Toml { name, text } => {
            if text.len() > MAX_DATA_FILE_BYTES {
                return Err(Error::File {
                    file: name.clone(),
                    message: format!("an insert file is larger than {MAX_DATA_FILE_BYTES} bytes"),
                });
            }
            Insert::from_toml(text, name, tol)?
        }
    };
    if let Some((lo, hi)) = ins.pitch_range {
        if ins.kind != InsertKind::Full && !(lo - 1e-9 <= t.pitch && t.pitch <= hi + 1e-9) {
            return Err(Error::Geometry(format!(
                "insert '{}' covers pitches {lo} to {hi} mm, not {} mm",
                ins.name, t.pitch
            )));
        }
    }
    if ins.kind != InsertKind::Full {
        // Width at the thread depth: wider than the pitch, it would cut the neighbouring teeth.
        let h = t.thread_depth();
        let width = width_at(&ins.outline, h);
        if width > t.pitch {
            return Err(Error::Geometry(format!(
                "insert '{}' is {width:.3} mm wide at the thread depth {h:.3} mm, wider than the pitch {} mm",
                ins.name, t.pitch
            )));
        }
    }
    Ok(ins)
}

/// Width of a closed outline at height `y` (extent of its crossings of that level), mm.
fn width_at(outline: &[crate::Point], y: f64) -> f64 {
    let n = outline.len();
    let zs: Vec<f64> = (0..n)
        .filter_map(|i| crate::ground::plane::cross_at_level(outline[i], outline[(i + 1) % n], y))
        .collect();
    let (lo, hi) = zs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), z| (a.min(*z), b.max(*z)));
    if hi >= lo {
        hi - lo
    } else {
        0.0
    }
}

/// A first guess of the final X that puts d2 at `target`: the insert's depth for basic d2,
/// moved by the wanted pitch-diameter change (X and d2 move one for one).
fn initial_final_x(t: &BasicThread, kind: ThreadKind, ins: &Insert, target: f64) -> f64 {
    let delta = target - t.pitch_diameter();
    let (variant, base) = match kind {
        ThreadKind::External => (ProfileKind::BoltDesign, t.nominal_diameter),
        ThreadKind::Internal => (ProfileKind::Nut, t.minor_diameter_internal()),
    };
    let g = t.groove(variant);
    let depth = match ins.kind {
        InsertKind::Full => g.bottom(),
        InsertKind::Partial | InsertKind::Custom => {
            let b = t.half_angle();
            g.sharp_root() - (ins.tip_radius / b.sin() - ins.tip_radius)
        }
    };
    match kind {
        ThreadKind::External => base - 2.0 * depth + delta,
        ThreadKind::Internal => base + 2.0 * depth + delta,
    }
}

/// The last pass of the first start that begins a threading move (not a later segment of a
/// synchronised chain, such as a run-out).
pub fn last_head(passes: &[Pass]) -> Pass {
    let head = |p: &&Pass| (p.z_phase - p.z_start).abs() < 1e-12;
    passes
        .iter()
        .rev()
        .find(|p| p.start == 0 && head(p))
        .or_else(|| passes.iter().rev().find(|p| p.start == 0))
        .or(passes.last())
        .copied()
        .unwrap_or_else(|| Pass::parallel(0, 0.0, 0.0, 0.0, 1.0))
}

/// Where to measure: the groove of the last pass of the first start, on the crossing nearest the
/// middle of its full-depth stretch (clear of run-in and run-out).
///
/// ```
/// use threadcheck::{reference_groove, Pass};
/// // One pass from Z5 to Z−20 at lead 1.5, phase at Z5: the groove nearest the middle, Z−7.5,
/// // on the lead's grid 5 − 1.5·k is Z−8.5 or Z−7 (k = 9 gives −8.5; k = 8 gives −7).
/// let z = reference_groove(&[Pass::parallel(1, 8.16, 5.0, -20.0, 1.5)]);
/// assert!(((z - 5.0) / 1.5).fract().abs() < 1e-9 && (z + 7.5).abs() <= 0.75);
/// ```
pub fn reference_groove(passes: &[Pass]) -> f64 {
    if passes.is_empty() {
        return 0.0;
    }
    let last = last_head(passes);
    let (lo, hi) = last.full_depth_range();
    let k = ((0.5 * (lo + hi) - last.z_phase) / last.lead).round();
    last.z_phase + k * last.lead
}

/// The crossing of the last threading move nearest `z`.
pub fn groove_near(passes: &[Pass], z: f64) -> f64 {
    if passes.is_empty() {
        return z;
    }
    let last = last_head(passes);
    let k = ((z - last.z_phase) / last.lead).round();
    last.z_phase + k * last.lead
}

/// An operation's passes checked against the designation: the lead must match, and the starts
/// of a multi-start thread are told apart by their phase (pitch apart along the lead).
///
/// ```
/// use threadcheck::{parse_designation, program_passes, read_program, Dialect, ParseOptions};
/// let p = read_program("G0 X22 Z5\nG76 P011060 Q100 R0.05\nG76 X18.16 Z-20 P920 Q350 F1.5\n", "m20.nc", Dialect::Fanuc)?;
/// let des = parse_designation("M20x1.5-6g", ParseOptions::default())?;
/// let passes = program_passes(&p.operations[0], &des, "m20.nc")?;
/// assert!(passes.iter().all(|q| q.lead == 1.5 && q.start == 0));
/// // A designation with another lead is refused.
/// assert!(program_passes(&p.operations[0], &parse_designation("M20x2-6g", ParseOptions::default())?, "m20.nc").is_err());
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn program_passes(
    op: &crate::gcode::Operation,
    des: &Designation,
    file: &str,
) -> Result<Vec<Pass>, Error> {
    let t = &des.thread;
    let lead = t.lead();
    let Some(p0) = op.passes.first().copied() else {
        return Err(Error::Input(format!("{file}: operation {} has no passes", op.index)));
    };
    let off_helix = off_helix_segments(op, t);
    for (p, _) in op.passes.iter().zip(&off_helix).filter(|(_, off)| !**off) {
        if let Err(inc) = crate::analysis::turn::lead::lead_deviation(p.lead, op.units, t, 0.0) {
            let u = op.units;
            let in_units = |mm: f64| match u {
                crate::gcode::ProgramUnits::Mm => format!("{mm:.4} mm"),
                crate::gcode::ProgramUnits::Inch => format!("{:.4} in ({mm:.4} mm)", mm / u.mm()),
            };
            // A lead that matches once read in inches: the program is an inch control's.
            let inch = crate::gcode::ProgramUnits::Inch;
            let hint = if u == crate::gcode::ProgramUnits::Mm
                && crate::analysis::turn::lead::lead_deviation(p.lead * inch.mm(), inch, t, 0.0).is_ok()
            {
                "; read in inches it is the designation's (G20, or ‹default_units› inch if the program sets no units)"
                    .to_string()
            } else {
                String::new()
            };
            return Err(Error::Program {
                file: file.to_string(),
                line: p.source_line.unwrap_or(1),
                column: 1,
                message: format!(
                    "the program cuts a lead of {}, the designation {} has {}: they differ by more than rounding{}{hint}",
                    in_units(p.lead),
                    des.text,
                    in_units(lead),
                    // A lead computed from a taper (not written) has no increment of its own.
                    if inc >= 1e-6 {
                        format!(" to the program's {} {} increment", crate::ground::fmt::fmt_num(inc), u.name())
                    } else {
                        String::new()
                    }
                ),
            });
        }
    }
    let mut passes = op.passes.clone();
    if t.starts > 1 {
        let n = f64::from(t.starts);
        for p in &mut passes {
            let k = ((p.z_phase - p0.z_phase) / t.pitch).round();
            p.start = k.rem_euclid(n) as u32;
        }
    }
    Ok(passes)
}

/// For each pass of `op`, whether it is a run-in or run-out segment off the thread's helix: a
/// taper segment whose axial lead is not the designation's while another pass of the operation
/// cuts at it (a chained run-out steeper than 45° whose F the control takes along X, a LinuxCNC
/// G33 taper whose K runs along the path). It is swept as it moves; a note says so.
fn off_helix_segments(op: &crate::gcode::Operation, t: &crate::standards::BasicThread) -> Vec<bool> {
    let off: Vec<bool> = op
        .passes
        .iter()
        .map(|q| crate::analysis::turn::lead::lead_deviation(q.lead, op.units, t, 0.0).is_err())
        .collect();
    let some_on = off.iter().any(|o| !o);
    op.passes.iter().zip(off).map(|(p, o)| o && some_on && (p.x_end - p.x_start).abs() > 1e-9).collect()
}

struct Cut {
    passes: Vec<Pass>,
    section: Section,
    z_ref: f64,
    measurement: Measurement,
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

/// A spec resolved against the standards: everything but the passes.
#[derive(Clone, Debug)]
pub struct Resolved {
    /// The designation.
    pub designation: Designation,
    /// External or internal.
    pub kind: ThreadKind,
    /// The class's limits.
    pub limits: ThreadLimits,
    /// The insert.
    pub insert: Insert,
    /// Blank or bore diameter, mm.
    pub blank: f64,
    /// Infeed.
    pub infeed: Infeed,
    /// Notes so far.
    pub notes: Vec<crate::ground::note::Note>,
    spec: VerifySpec,
}

impl Resolved {
    /// The generated plan that ends with its tip on diameter `final_x`.
    pub fn plan(&self, final_x: f64) -> PlanSpec {
        let t = &self.designation.thread;
        let s = &self.spec;
        // A taper pipe thread: from a run-in of two leads before the face (Z0) inwards, the
        // external thread growing by 1:16 on the diameter, the fitting narrowing.
        let (taper, z_start, length) = match self.limits.gauge_plane {
            Some(gp) => (
                match self.kind {
                    ThreadKind::External => gp.taper,
                    ThreadKind::Internal => -gp.taper,
                },
                2.0 * t.lead(),
                gp.distance + 2.0 * t.lead() + 10.0 * t.pitch,
            ),
            None => (s.taper, 0.0, 10.0 * t.lead()),
        };
        PlanSpec {
            z_start,
            starts: t.starts,
            schedule: s.schedule.clone(),
            infeed: self.infeed,
            spring: s.spring,
            first_depth: s.first_depth,
            min_depth: s.min_depth,
            finish: s.finish,
            taper,
            chamfer_leads: s.chamfer_leads,
            left_hand: t.hand == crate::Hand::Left,
            length,
            ..PlanSpec::new(
                self.kind,
                t.pitch,
                self.blank,
                final_x,
                s.passes.unwrap_or_else(|| default_pass_count(t.pitch)),
            )
        }
    }
}

/// The limits to cut to under a coating of `thickness` mm: the class's own for 0, else the
/// limits before coating; a thickness that is no coat of a thread (negative, or a tenth of the
/// pitch and more, which fills the flanks) is refused.
pub fn coated(
    limits: ThreadLimits,
    t: &BasicThread,
    thickness: f64,
    rule: crate::standards::tolerance::CoatingLimits,
) -> Result<ThreadLimits, Error> {
    if !(thickness.is_finite() && thickness >= 0.0 && thickness < 0.1 * t.pitch) {
        return Err(Error::Input(format!(
            "coating {} mm: a coat's thickness is from 0 to under a tenth of the pitch ({} mm)",
            crate::ground::fmt::fmt_num(thickness),
            crate::ground::fmt::fmt_num(0.1 * t.pitch)
        )));
    }
    if thickness == 0.0 {
        return Ok(limits);
    }
    let pre = limits.for_coating(thickness, t, rule);
    // A coat as thick as the tolerance leaves nothing to cut to.
    for (name, l) in
        [("major", pre.major_diameter), ("pitch", pre.pitch_diameter), ("minor", pre.minor_diameter)]
    {
        if let (Some(lo), Some(hi)) = (l.min, l.max) {
            if lo > hi + 1e-9 {
                return Err(Error::Input(format!(
                    "coating {} mm: it leaves no tolerance on the {name} diameter before coating ({} over {}): a thinner coat, another class, or ‹coating_limits› after if the drawing says the class applies after coating",
                    crate::ground::fmt::fmt_num(thickness),
                    crate::ground::fmt::fmt_num(lo),
                    crate::ground::fmt::fmt_num(hi)
                )));
            }
        }
    }
    Ok(pre)
}

/// Resolves a spec: designation, kind, limits, insert, blank and infeed.
pub fn resolve(spec: &VerifySpec) -> Result<Resolved, Error> {
    spec.validate()?;
    if !(spec.tolerance.is_finite()
        && spec.tolerance >= crate::ground::plane::MIN_TOLERANCE
        && spec.tolerance <= 0.01)
    {
        return Err(Error::Input(format!("chord tolerance {} mm must be from 1e-6 to 0.01", spec.tolerance)));
    }
    let des =
        parse_designation(&spec.designation, ParseOptions { allow_nonstandard: spec.allow_nonstandard })?;
    let kind = resolve_kind(&des, spec.internal)?;
    let limits = limits_for(&des, kind)?.ok_or_else(|| Error::Input("no class".into()))?;
    let t = des.thread;
    let limits = coated(limits, &t, spec.coating, spec.coating_limits)?;
    let insert = build_insert(&spec.insert, &t, kind, spec.tolerance)?;
    let blank = match spec.blank_diameter {
        Some(b) if !(b.is_finite() && b > 0.0) => {
            return Err(Error::Input(format!("blank diameter {b} mm must be a positive length")));
        }
        Some(b) => b,
        None => default_blank(&t, kind, &limits, &insert),
    };
    let infeed = spec.infeed.unwrap_or(InfeedChoice::Modified).resolve(t.form.flank_angle());
    if let Some(a) = spec.infeed.and_then(InfeedChoice::angle) {
        if !(0.0..90.0).contains(&a) {
            return Err(Error::Input(format!("infeed angle {a}°: must be from 0 to under 90 degrees")));
        }
    }
    let notes = limits.notes.iter().map(|n| crate::ground::note::Note::from(n.as_str())).collect();
    Ok(Resolved { designation: des, kind, limits, insert, blank, infeed, notes, spec: spec.clone() })
}

/// Runs `verify`: resolves the thread, its limits and the insert, lays out (or reads) the passes,
/// cuts them, measures the groove and checks it.
///
/// ```
/// use threadcheck::{verify, InsertChoice, VerifySpec};
/// // A full-profile insert, the final X solved for the middle of 6g's d2 band (8.862–8.994).
/// let v = verify(&VerifySpec { insert: InsertChoice::Full, ..VerifySpec::new("M10x1.5-6g") })?;
/// assert!(v.pass);
/// assert!((v.measurement.pitch_diameter - 8.928).abs() < 1e-3);
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn verify(spec: &VerifySpec) -> Result<Verification, Error> {
    spec.validate()?;
    if let Some((source, dialect)) = &spec.program {
        if spec.final_x.is_some() {
            return Err(Error::Input(
                "a final X and a program exclude each other: the program sets the passes".into(),
            ));
        }
        let (shown, text) = source.load()?;
        let prog = crate::gcode::read_program_with(&text, &shown, *dialect, spec.reading.clone())?;
        let index = operation_index(&prog, &shown, spec.operation)?;
        let label = ProgramLabel { file: shown, dialect: *dialect };
        let mut v = verify_given(&resolve(spec)?, &prog.operations[index], &label)?;
        v.notes.extend(prog.notes.iter().cloned());
        return Ok(v);
    }
    verify_core(&resolve(spec)?, None)
}

/// The index of the operation `operation` (1-based) names in `prog`, or of its only one.
fn operation_index(
    prog: &crate::gcode::Program,
    shown: &str,
    operation: Option<usize>,
) -> Result<usize, Error> {
    let n = prog.operations.len();
    let list = || {
        prog.operations
            .iter()
            .map(|o| format!("{} at line {}", o.cycle, o.source_line))
            .collect::<Vec<_>>()
            .join(", ")
    };
    match operation {
        Some(k) if (1..=n).contains(&k) => Ok(k - 1),
        Some(k) => Err(Error::Input(format!(
            "{shown} cuts {n} thread{} ({}): there is no operation {k}",
            if n == 1 { "" } else { "s" },
            list()
        ))),
        None if n == 1 => Ok(0),
        None => Err(Error::Input(format!(
            "{shown} cuts {n} threads ({}): say which one with ‹operation› 1 to {n}",
            list()
        ))),
    }
}

/// The passes of one program operation, with what to say about them.
struct Given {
    passes: Vec<Pass>,
    depth_word: Option<crate::gcode::DepthWord>,
    units: crate::gcode::ProgramUnits,
    lead: Option<crate::analysis::turn::lead::LeadDeviation>,
    label: ProgramLabel,
    notes: Vec<crate::ground::note::Note>,
}

/// What measuring a cut needs: the sweep's setup, the measurement's, and a taper thread's cone
/// (measured along it: the section sheared so the cone's pitch line runs level).
struct Measurer<'a> {
    r: &'a Resolved,
    t: &'a crate::standards::BasicThread,
    setup: SweepSetup<'a>,
    ms: MeasureSetup<'a>,
    taper: Option<Taper>,
    mid: Option<f64>,
}

impl Measurer<'_> {
    /// The groove measured: near the taper's measuring height, or the reference groove.
    fn z_of(&self, passes: &[Pass]) -> f64 {
        match self.taper {
            Some((_, z, _)) => groove_near(passes, z),
            None => reference_groove(passes),
        }
    }

    /// The section's profile, sheared level along a taper's cone.
    fn profile_of(&self, section: &Section, z_ref: f64) -> Vec<crate::Point> {
        let p = section.profile();
        match self.taper {
            Some((_, _, slope)) => {
                p.into_iter().map(|q| crate::Point::new(q.z, q.r - slope * (q.z - z_ref))).collect()
            }
            None => p,
        }
    }

    /// The pitch diameter to aim at where the thread is measured: the middle of the tolerance,
    /// or on a taper thread the basic cone's pitch diameter there.
    fn target_at(&self, z_ref: f64) -> f64 {
        match self.taper {
            Some((gp, _, _)) => match self.setup.kind {
                ThreadKind::External => gp.pitch_diameter + (-z_ref - gp.distance) * gp.taper,
                ThreadKind::Internal => gp.pitch_diameter - (-z_ref - gp.distance) * gp.taper,
            },
            None => self.mid.unwrap_or_default(),
        }
    }

    /// Sweeps `passes` and measures the groove, by `ms`.
    fn measure_passes(&self, passes: Vec<Pass>, ms: &MeasureSetup<'_>) -> Result<Cut, Error> {
        let z_ref = self.z_of(&passes);
        let window = Window::around(z_ref, self.t.pitch, 4.0);
        let s = sweep(&self.setup, &passes, window, UnionStrategy::Envelope)?;
        let measurement = measure(ms, &self.profile_of(&s.section, z_ref), z_ref)?;
        Ok(Cut { passes, section: s.section, z_ref, measurement })
    }

    /// The plan to `final_x`, cut and measured by `ms`.
    fn run_with(&self, final_x: f64, ms: &MeasureSetup<'_>) -> Result<Cut, Error> {
        self.measure_passes(self.r.plan(final_x).generate()?, ms)
    }

    /// The final X that lands the pitch diameter on its target, and its cut fully measured. X and
    /// d2 move one for one, so a few corrections converge to well below 0.01 µm; while solving
    /// only the pitch diameter matters (sizes only).
    fn solve(&self, insert: &Insert) -> Result<(f64, Cut), Error> {
        let ms_solve = self.ms.sizes_only();
        let target = self.target_at(self.taper.map_or(0.0, |(_, z, _)| z));
        let mut x = initial_final_x(self.t, self.setup.kind, insert, target);
        let mut cut = self.run_with(x, &ms_solve)?;
        for _ in 0..6 {
            let err = self.target_at(cut.z_ref) - cut.measurement.pitch_diameter;
            if err.abs() < 1e-8 {
                break;
            }
            x += err;
            cut = self.run_with(x, &ms_solve)?;
        }
        // The full measurement, maximum-material check included, on the solved cut.
        let measurement = measure(&self.ms, &self.profile_of(&cut.section, cut.z_ref), cut.z_ref)?;
        Ok((x, Cut { measurement, ..cut }))
    }
}

/// The gauge plane of a taper thread: where the pitch cone reaches the basic gauge diameter, from
/// the pitch diameter measured at the cut's groove and the taper, against its basic distance.
fn gauge_cone(
    taper: Option<Taper>,
    kind: ThreadKind,
    cut: &Cut,
    t: &crate::standards::BasicThread,
) -> Option<crate::analysis::check::Cone> {
    taper.map(|(gp, _, _)| {
        let last = last_head(&cut.passes);
        let run = (last.z_end - last.z_start).abs();
        let measured_taper = if run > 0.0 {
            (last.x_end - last.x_start) * if kind == ThreadKind::External { 1.0 } else { -1.0 } / run
        } else {
            0.0
        };
        cone_of(gp, kind, cut.z_ref, cut.measurement.pitch_diameter, measured_taper, t.pitch)
    })
}

/// The checks of a measured cut: sizes and form, a taper's gauge plane (stood off by the lead
/// error's share), and the functional pitch diameter when the program's lead is off; with the
/// functional pitch diameter.
fn judge(
    m: &Measurement,
    limits: &ThreadLimits,
    t: &crate::standards::BasicThread,
    kind: ThreadKind,
    cone: Option<crate::analysis::check::Cone>,
    taper: bool,
    lead_deviation: Option<crate::analysis::turn::lead::LeadDeviation>,
) -> (Vec<crate::analysis::check::Check>, Option<f64>) {
    // The lead error's equivalent: the functional pitch diameter has more material than the
    // measured one (larger on a bolt, smaller in a nut); on a taper thread the gauge stands off
    // by the equivalent over the taper.
    let functional = lead_deviation.map(|ld| match kind {
        ThreadKind::External => m.pitch_diameter + ld.pitch_diameter_equivalent,
        ThreadKind::Internal => m.pitch_diameter - ld.pitch_diameter_equivalent,
    });
    // The gauge's stand-off from the lead error, turns.
    let lead_turns =
        cone.zip(lead_deviation).map(|(c, ld)| ld.pitch_diameter_equivalent / (c.nominal_taper * t.pitch));
    let cone = cone.map(|c| crate::analysis::check::Cone { turns: c.turns - lead_turns.unwrap_or(0.0), ..c });
    let mut cs = checks(m, limits, t, kind, m.root_pockets <= 1, cone);
    if let (Some(f), Some(ld), false) = (functional, lead_deviation, taper) {
        cs.push(crate::analysis::check::functional_check(f, limits, kind, ld));
    }
    if let (Some(ld), Some(share)) = (lead_deviation, lead_turns) {
        if let Some(gp) =
            cs.iter_mut().find(|c| c.feature == crate::analysis::check::CheckFeature::GaugePlane)
        {
            let note = gp.note.take().unwrap_or_default();
            gp.note = Some(format!(
                "{note}; functional: the lead {:.6} mm against {:.6} mm stands the gauge off {share:.3} turn",
                ld.program_lead, ld.designation_lead
            ));
        }
    }
    (cs, functional)
}

/// The verification of a resolved spec, with the passes of a program operation or its own plan.
/// A cut that leaves nothing to measure is an [`Error::Geometry`].
fn verify_core(r: &Resolved, given: Option<Given>) -> Result<Verification, Error> {
    let spec = &r.spec;
    if spec.taper != 0.0 {
        return Err(Error::Input("‹taper› lays out a tapered pass plan for `passes`; verify takes a taper thread's taper from its designation (NPT, ISO 7-1) or from a program".into()));
    }
    let (des, kind, limits, insert, blank, infeed) =
        (r.designation.clone(), r.kind, r.limits.clone(), r.insert.clone(), r.blank, r.infeed);
    let mut notes = r.notes.clone();
    let t = des.thread;
    // A taper thread is measured along its cone: at the gauge plane (external, the face at Z0)
    // or four pitches in (internal), the section sheared so the cone's pitch line runs level.
    let taper = taper_of(&limits, kind, t.pitch);
    if taper.is_some() {
        notes.push(TAPER_FACE_NOTE.into());
    }
    // A taper thread's maximum-material check is its gauge plane's, not a parallel profile's.
    let parallel = MeasureSetup::for_class(&t, kind, &limits);
    let mid = limits.pitch_diameter.mid();
    if taper.is_none() && mid.is_none() {
        return Err(Error::Input("the class has no two-sided pitch-diameter tolerance".into()));
    }
    let mr = Measurer {
        r,
        t: &t,
        setup: SweepSetup { kind, insert: &insert, blank_diameter: blank, pitch: t.pitch },
        ms: match taper {
            Some(_) => MeasureSetup { mmc_pitch_diameter: None, ..parallel },
            None => parallel,
        },
        taper,
        mid,
    };
    let program_label = given.as_ref().map(|g| g.label.clone());
    let lead_deviation = given.as_ref().and_then(|g| g.lead);
    let depth_word = given.as_ref().and_then(|g| g.depth_word.clone().map(|w| (w, g.units)));
    let cut_plan = given.as_ref().map(|g| crate::analysis::turn::cut_plan::cut_plan(&g.passes));
    let (final_x, solved, cut) = if let Some(g) = given {
        notes.extend(g.notes);
        let final_x = last_head(&g.passes).x_at(mr.z_of(&g.passes));
        (final_x, false, mr.measure_passes(g.passes, &mr.ms)?)
    } else {
        match spec.final_x {
            Some(x) if !x.is_finite() => {
                return Err(Error::Input(format!("final X {x} is not a finite number")))
            }
            Some(x) => (x, false, mr.run_with(x, &mr.ms)?),
            None => {
                let (x, cut) = mr.solve(&insert)?;
                (x, true, cut)
            }
        }
    };
    // A taper thread is measured on its section sheared so the pitch cone runs level; its flank
    // angles are turned back into the true axial section before they are checked.
    let cut = match taper {
        Some((_, _, slope_r)) => {
            let mut m = cut.measurement.clone();
            m.flank_angles = true_flank_angles(m.flank_angles, slope_r, kind);
            Cut { measurement: m, ..cut }
        }
        None => cut,
    };
    let metrics = if spec.metrics { pass_metrics(&mr.setup, &cut.passes, cut.z_ref)? } else { Vec::new() };
    let m = &cut.measurement;
    notes.extend(measured_notes(m, (spec.coating, spec.coating_limits), &t, kind));
    let cone = gauge_cone(taper, kind, &cut, &t);
    let (cs, functional) = judge(m, &limits, &t, kind, cone, taper.is_some(), lead_deviation);
    let pass = verdict(&cs, spec.gauge_only);
    let d2_off = {
        use crate::analysis::check::CheckFeature as F;
        crate::analysis::check::any_fails(&cs, &[F::PitchDiameter, F::GaugePlane, F::FunctionalPitchDiameter])
    };
    let delta = mr.target_at(cut.z_ref) - m.pitch_diameter;
    let suggested = d2_off.then_some(final_x + delta);
    let correction = match (d2_off, &depth_word) {
        (true, Some((w, units))) => {
            Some(crate::analysis::turn::correction::correction(w, *units, kind, delta))
        }
        _ => None,
    };
    if spec.gauge_only {
        notes.push("gauge only: form checks are reported but left out of the verdict".into());
    }
    // A taper thread's pitch diameter is reported where its gauge checks it, at the gauge
    // plane: measured on the groove nearest it and carried along the cone.
    let carry = match taper {
        Some((gp, _, _)) => {
            let zc = cut.measurement.groove_center;
            match kind {
                ThreadKind::External => (zc + gp.distance) * gp.taper,
                ThreadKind::Internal => -zc * gp.taper,
            }
        }
        None => 0.0,
    };
    let mut v = Verification {
        designation: des,
        kind,
        limits,
        insert,
        infeed,
        schedule: spec.schedule.clone(),
        cut_plan,
        thread_percent: match kind {
            ThreadKind::Internal => crate::analysis::percent::thread_percent(&t, blank),
            ThreadKind::External => None,
        },
        blank_diameter: blank,
        final_x,
        final_x_solved: solved,
        passes: cut.passes,
        metrics,
        section: cut.section,
        z_ref: cut.z_ref,
        measurement: Measurement {
            pitch_diameter: cut.measurement.pitch_diameter + carry,
            ..cut.measurement
        },
        checks: cs,
        pass,
        suggested_final_x: suggested,
        middle_final_x: Some(final_x + delta),
        gauge_only: spec.gauge_only,
        notes,
        program: program_label,
        units: spec.units,
        helix_angle: crate::analysis::process::helix_angle(t.lead(), t.pitch_diameter()),
        process: None,
        lead_deviation,
        functional_pitch_diameter: functional.map(|f| f + carry),
        correction,
        picture: None,
        hints: Vec::new(),
        depth: depth_word.map(|(word, units)| DepthAt {
            word,
            units,
            also: Vec::new(),
            alike: true,
            pass_x_words: Vec::new(),
        }),
    };
    v.hints = crate::analysis::check::hints(&v.checks, &v.insert, &v.limits, t.half_angle().to_degrees());
    if spec.picture {
        v.picture = Some(picture_of(&v)?);
    }
    Ok(v)
}

/// What a verification's pictures draw, computed from it.
fn picture_of(v: &Verification) -> Result<crate::analysis::picture::Picture, Error> {
    crate::analysis::picture::picture(&crate::analysis::picture::Cut {
        thread: &v.designation.thread,
        kind: v.kind,
        limits: &v.limits,
        groove_center: v.measurement.groove_center,
        section: &v.section,
        insert: &v.insert,
        blank_diameter: v.blank_diameter,
        passes: &v.passes,
    })
}

/// The notes a measurement adds: the pitch diameter after a coating of `coating` mm, and a
/// pitch line found on the flank lines extended.
fn measured_notes(
    m: &Measurement,
    (coating, rule): (f64, crate::standards::tolerance::CoatingLimits),
    t: &crate::standards::BasicThread,
    kind: ThreadKind,
) -> Vec<crate::ground::note::Note> {
    let mut notes = Vec::new();
    if coating > 0.0 {
        let grow = crate::standards::tolerance::coat_pitch_growth(coating, t.half_angle());
        let after = match kind {
            ThreadKind::External => m.pitch_diameter + grow,
            ThreadKind::Internal => m.pitch_diameter - grow,
        };
        let bound = match (rule, kind) {
            (crate::standards::tolerance::CoatingLimits::After, _) => {
                "the class's limits apply to it".to_string()
            }
            (crate::standards::tolerance::CoatingLimits::Before, ThreadKind::External) => {
                format!("at most the basic {:.3} mm, h", t.pitch_diameter())
            }
            (crate::standards::tolerance::CoatingLimits::Before, ThreadKind::Internal) => {
                format!("at least the basic {:.3} mm, H", t.pitch_diameter())
            }
        };
        notes.push(crate::ground::note::Note::from(format!(
            "after coating the pitch diameter measured here becomes {after:.4} mm ({bound})"
        )));
    }
    if m.pitch_line_extrapolated {
        notes.push(crate::ground::note::Note::from(
            "the pitch line lies outside the cut flanks; the fitted flank lines were extended to find it",
        ));
    }
    notes
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

/// What became of one operation of a program.
#[derive(Clone, Debug)]
pub enum OperationResult {
    /// Cut and measured.
    Verified(Box<Verification>),
    /// The passes never reach the material (or leave no groove to measure): a failing verdict
    /// with the reason.
    NoCut {
        /// Why nothing could be measured.
        reason: String,
        /// The last pass's X that cuts the thread mid-tolerance with this insert from this blank
        /// (a generated plan's, solved as `verify` without a program solves it), mm; `None` when
        /// that plan cannot be cut either.
        suggested_final_x: Option<f64>,
    },
}

impl OperationResult {
    /// Whether the operation passes.
    pub fn pass(&self) -> bool {
        match self {
            OperationResult::Verified(v) => v.pass,
            OperationResult::NoCut { .. } => false,
        }
    }
}

/// One operation of a program and its result.
#[derive(Clone, Debug)]
pub struct OperationVerdict {
    /// The operation as the program cuts it.
    pub operation: crate::gcode::Operation,
    /// The designation it was verified against.
    pub designation: String,
    /// Where the designation came from (given, a comment, inferred) and how it was read.
    pub named: crate::analysis::naming::Named,
    /// The verdict.
    pub result: OperationResult,
}

/// Verifies one operation of a program read already: the insert and designation come from
/// `spec` (its `program` is ignored).
pub fn verify_operation(
    spec: &VerifySpec,
    op: &crate::gcode::Operation,
    label: &ProgramLabel,
) -> Result<OperationResult, Error> {
    let mut r = resolve(spec)?;
    let side = if r.kind == ThreadKind::External { "blank" } else { "bore" };
    let mut blank_from = match spec.blank_diameter {
        Some(_) => format!("the {side} as given (‹blank_diameter›, or the stock the program declares)"),
        None => format!(
            "the default {side}: no feed move of the program turns the thread's stretch (‹blank_diameter› gives it)"
        ),
    };
    if spec.blank_diameter.is_none() {
        if let Some((d, line)) = program_blank(op, r.kind) {
            r.blank = d;
            blank_from = format!("the {side} the program's moves leave, turned at line {line}");
            r.notes.push(crate::ground::note::Note::at(
                &label.file,
                line,
                1,
                format!(
                    "the {} is the program's own: Ø{d:.4}, the material its moves leave over the thread, turned here (‹blank_diameter› overrides)",
                    if r.kind == ThreadKind::External { "blank" } else { "bore" },
                ),
            ));
        }
    }
    match verify_given(&r, op, label) {
        Ok(v) => Ok(OperationResult::Verified(Box::new(v))),
        Err(Error::Geometry(m)) => {
            let plan = VerifySpec {
                program: None,
                operation: None,
                final_x: None,
                blank_diameter: Some(r.blank),
                metrics: false,
                picture: false,
                machine: None,
                designation: r.designation.text.clone(),
                ..spec.clone()
            };
            // Passes nowhere near the designation's size: no final X is offered (it would plunge
            // to another thread's diameter); the reason names both.
            if let Some((_, misfit)) = diameter_misfit(&r, op, &op.passes) {
                return Ok(OperationResult::NoCut {
                    reason: format!("{m}; {blank_from}; {misfit}: no correction is offered"),
                    suggested_final_x: None,
                });
            }
            let suggested_final_x = verify(&plan).ok().map(|v| v.final_x);
            Ok(OperationResult::NoCut { reason: format!("{m}; {blank_from}"), suggested_final_x })
        }
        Err(e) => Err(e),
    }
}

/// The side the passes cut (inward pass by pass from a bar, outward in a bore) must be the
/// designation's: a contradiction is refused at the operation's line, never verified as the
/// other side.
fn side_agrees(
    r: &Resolved,
    op: &crate::gcode::Operation,
    passes: &[Pass],
    label: &ProgramLabel,
) -> Result<(), Error> {
    let (Some(first), last) = (passes.first(), last_head(passes)) else { return Ok(()) };
    let dx = last.x_end - first.x_end;
    if dx.abs() < 1e-6 {
        return Ok(());
    }
    let inward = dx < 0.0;
    let (cut, other) = match (r.kind, inward) {
        (ThreadKind::External, false) => ("outward pass by pass, as in a bore", "an internal class"),
        (ThreadKind::Internal, true) => ("inward pass by pass, as on a bar", "an external class"),
        // Passes that move the way the class's side cuts.
        (ThreadKind::External, true) | (ThreadKind::Internal, false) => return Ok(()),
    };
    Err(Error::Program {
        file: label.file.clone(),
        line: op.source_line,
        column: 1,
        message: format!(
            "{} is {} thread, but the passes of this {} move {cut} (X{:.4} to X{:.4}): give {other} or check the program",
            r.designation.text,
            if r.kind == ThreadKind::External { "an external" } else { "an internal" },
            op.cycle,
            first.x_end,
            last.x_end,
        ),
    })
}

/// How a refusal of a designation of another size ends (the inferred one is said after it).
const MISFIT_END: &str = "check the thread";

/// Where the designation is not the thread the passes cut. Both sides of the profile are
/// compared, each against one thread depth on the radius (plus, on a taper, what the cone changes
/// over the pass and the nominal length): the deepest pass's tip against the designation's root
/// (d3 on a bar, D in a bore), and the crest side (the diameter the program turned or bored for
/// the thread, else its first pass) against its crest (d, D1). Off on both, the designation names
/// another size and no correction would be safe; off on the root alone, the program cuts this
/// size too deep or too shallow, which the checks show. The last pass's line and what to say,
/// naming both diameters.
fn diameter_misfit(
    r: &Resolved,
    op: &crate::gcode::Operation,
    passes: &[Pass],
) -> Option<(Option<usize>, String)> {
    let t = &r.designation.thread;
    let last = last_head(passes);
    let final_x = 0.5 * (last.x_start.abs() + last.x_end.abs());
    let xs = passes.iter().map(|p| 0.5 * (p.x_start.abs() + p.x_end.abs()));
    let (root, root_name, crest, about, crest_side) = match r.kind {
        ThreadKind::External => (
            t.minor_diameter_external(),
            "d3",
            t.nominal_diameter,
            final_x + 2.0 * t.thread_depth(),
            program_blank(op, r.kind).map_or_else(|| xs.fold(f64::NEG_INFINITY, f64::max), |b| b.0),
        ),
        ThreadKind::Internal => (
            t.nominal_diameter,
            "D",
            t.minor_diameter_internal(),
            final_x,
            program_blank(op, r.kind).map_or_else(|| xs.fold(f64::INFINITY, f64::min), |b| b.0),
        ),
    };
    let cone = t.form.taper() * ((last.z_end - last.z_start).abs() + t.nominal_diameter);
    let margin = 2.0 * t.thread_depth() + cone;
    if (final_x - root).abs() <= margin || (crest_side - crest).abs() <= margin {
        return None;
    }
    Some((
        last.source_line,
        format!(
            "the passes cut about Ø{about:.1} (final X{:.3}), the designation {} is Ø{} ({root_name} {root:.3}): they differ by more than a thread depth; {MISFIT_END}",
            last.x_end,
            r.designation.text,
            crate::ground::fmt::fmt_num(t.nominal_diameter),
        ),
    ))
}

/// [`diameter_misfit`] as a refusal at the last pass's line.
fn diameter_agrees(
    r: &Resolved,
    op: &crate::gcode::Operation,
    passes: &[Pass],
    label: &ProgramLabel,
) -> Result<(), Error> {
    match diameter_misfit(r, op, passes) {
        None => Ok(()),
        Some((line, message)) => Err(Error::Program {
            file: label.file.clone(),
            line: line.unwrap_or(op.source_line),
            column: 1,
            message: format!("{}: {message}", op.cycle),
        }),
    }
}

/// The diameter the program turned (or bored) for the thread before cutting it, and the line of
/// the move that left it: the material its feed moves leave over the finishing pass's Z span.
/// At each Z the moves that cover it bring the material down to their X (a bore: open it up to
/// their X), so a feed through the air at a larger diameter after the part was turned smaller
/// changes nothing, and a later cut to a smaller diameter (a roughing cycle's profile, a finishing
/// pass) replaces an earlier one; of that material's cylinders along at least a quarter of the
/// pass (a taper is a chamfer, or an approach from beyond the face; a shorter cylinder a nose or
/// a collar) the outermost (a bore: innermost) is the blank, so chamfers and a run-in beyond the
/// part's end do not hide the journal. Distances from the axis (a tool beyond it writes X negative). `None`
/// when no feed move covers the pass.
fn program_blank(op: &crate::gcode::Operation, kind: ThreadKind) -> Option<(f64, usize)> {
    let passes = &op.passes;
    if passes.is_empty() {
        return None;
    }
    let last = last_head(passes);
    let (t0, t1) = (last.z_start.min(last.z_end), last.z_start.max(last.z_end));
    const EPS: f64 = 1e-9;
    // Moves along Z over the pass (a radial move, a face or a plunge, covers no length).
    let moves: Vec<&crate::gcode::Turned> = op
        .contour
        .iter()
        .filter(|t| {
            let (zl, zh) = (t.from[1].min(t.to[1]), t.from[1].max(t.to[1]));
            zh - zl > 1e-6 && zh >= t0 - EPS && zl <= t1 + EPS
        })
        .collect();
    if moves.is_empty() {
        return None;
    }
    // The material is piecewise linear between the moves' ends: it is looked at halfway
    // between each two.
    let mut zs: Vec<f64> = vec![t0, t1];
    zs.extend(moves.iter().flat_map(|t| [t.from[1], t.to[1]]).filter(|z| (t0..=t1).contains(z)));
    zs.sort_by(f64::total_cmp);
    zs.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    let external = kind == ThreadKind::External;
    // The thread's root: its deepest pass (the least X of a bolt's, the greatest of a nut's).
    // Only the surface on the thread's side of it is the blank: a bolt's material lies above
    // its root (a centre drill's X0 or a bore below it is not its blank), a nut's below (the
    // outside a part is turned to is not its bore).
    let xs = passes.iter().flat_map(|p| [p.x_start.abs(), p.x_end.abs()]);
    let root = if external { xs.fold(f64::INFINITY, f64::min) } else { xs.fold(0.0, f64::max) };
    // At one Z: the material's distance from the axis, the move that left it (of equal ones,
    // the last) and whether that move turned a cylinder. The surface on the thread's side of its
    // root first; only where there is none, the one on the other side nearest the root (a part
    // turned under a bolt's root: nothing is cut, and the message names that diameter).
    let material = |z: f64| -> Option<(f64, usize, bool)> {
        let mut best: Option<(f64, usize, bool)> = None;
        let mut beyond: Option<(f64, usize, bool)> = None;
        for t in &moves {
            let (za, zb) = (t.from[1], t.to[1]);
            if z < za.min(zb) - EPS || z > za.max(zb) + EPS {
                continue;
            }
            let f = ((z - za) / (zb - za)).clamp(0.0, 1.0);
            let x = (t.from[0] + f * (t.to[0] - t.from[0])).abs();
            let here = (x, t.line, (t.from[0] - t.to[0]).abs() < 1e-3);
            // On the axis: a drill's path, whose hole is the drill's diameter, not the path's.
            if x < 1e-3 {
                continue;
            }
            if (external && x <= root + 1e-6) || (!external && x >= root - 1e-6) {
                let nearer = match beyond {
                    None => true,
                    Some((b, _, _)) if external => x >= b - 1e-6,
                    Some((b, _, _)) => x <= b + 1e-6,
                };
                if nearer {
                    beyond = Some(here);
                }
                continue;
            }
            let deeper = match best {
                None => true,
                Some((b, _, _)) if external => x <= b + 1e-6,
                Some((b, _, _)) => x >= b - 1e-6,
            };
            if deeper {
                best = Some(here);
            }
        }
        best.or(beyond)
    };
    // The cylinders of that material and the length of the pass each runs along: a taper there
    // is a chamfer or an approach from beyond the part's face, and a cylinder along less than a
    // quarter of the pass (a nose, a collar) is not the diameter the thread is cut into.
    let mut cylinders: Vec<(f64, usize, f64)> = Vec::new();
    for w in zs.windows(2) {
        let Some((x, line, true)) = material(0.5 * (w[0] + w[1])) else { continue };
        match cylinders.iter_mut().find(|c| (c.0 - x).abs() < 1e-6) {
            Some(c) => {
                c.1 = line;
                c.2 += w[1] - w[0];
            }
            None => cylinders.push((x, line, w[1] - w[0])),
        }
    }
    let least = 0.25 * (t1 - t0);
    cylinders.into_iter().filter(|c| c.2 >= least - 1e-9).map(|(x, line, _)| (x, line)).reduce(|a, b| {
        if (external && b.0 > a.0 + 1e-6) || (!external && b.0 < a.0 - 1e-6) {
            b
        } else {
            a
        }
    })
}

/// One program operation verified; passes that cut nothing are an [`Error::Geometry`].
fn verify_given(
    r: &Resolved,
    op: &crate::gcode::Operation,
    label: &ProgramLabel,
) -> Result<Verification, Error> {
    let passes = program_passes(op, &r.designation, &label.file)?;
    let mut notes: Vec<crate::ground::note::Note> = op.notes.clone();
    let mut lines = std::collections::BTreeMap::new();
    let off_helix = off_helix_segments(op, &r.designation.thread);
    for (p, _) in op.passes.iter().zip(off_helix).filter(|(_, off)| *off) {
        lines.entry(p.source_line.unwrap_or(0)).or_insert(p.lead);
    }
    for (line, lead) in lines {
        notes.push(crate::ground::note::Note::from(format!(
            "the taper segment at line {line} moves {} mm along Z per turn, not the thread's {} mm (a run-in or run-out steeper than 45° takes its F along X; a LinuxCNC G33 its K along the path): it leaves the helix, and where it still cuts, it cuts off the thread's last turns",
            crate::ground::fmt::fmt_num(lead),
            crate::ground::fmt::fmt_num(r.designation.thread.lead())
        )));
    }
    if let Some((angle, word)) = &op.infeed_angle {
        let half = 0.5 * r.insert.angle;
        if *angle > half + 1e-9 {
            notes.push(crate::ground::note::Note::from(format!(
                "infeed angle {word} = {angle}° is above half the insert angle ({half}°): each pass moves away from the trailing flank faster than the flank slopes, so the groove widens at the crest and the trailing flank is stepped"
            )));
        }
    }
    side_agrees(r, op, &passes, label)?;
    // The passes must reach the material: external below the blank, internal above the bore.
    let deepest = match r.kind {
        ThreadKind::External => passes.iter().map(|p| p.x_end.min(p.x_start)).fold(f64::INFINITY, f64::min),
        ThreadKind::Internal => {
            passes.iter().map(|p| p.x_end.max(p.x_start)).fold(f64::NEG_INFINITY, f64::max)
        }
    };
    let misses = match r.kind {
        ThreadKind::External => deepest >= r.blank,
        ThreadKind::Internal => deepest <= r.blank,
    };
    if misses {
        return Err(Error::Geometry(format!(
                "no pass reaches the {} Ø{:.4}: the deepest pass is at X{deepest:.4}, so nothing is cut (is the {} or the thread wrong?)",
                if r.kind == ThreadKind::External { "blank" } else { "bore" },
                r.blank,
                if r.kind == ThreadKind::External { "blank diameter" } else { "bore diameter" },
        )));
    }
    // Passes that cut the material but not near the designation's size: refused, never corrected.
    diameter_agrees(r, op, &passes, label)?;
    // The lead error adds up over the thread a gauge engages: the thread on the part (its face
    // taken at Z0, the part at Z ≤ 0: a named default), capped at the length of engagement.
    let last = last_head(&passes);
    let pass_length = (last.z_end - last.z_start).abs();
    let (za, zb) = (last.z_start.min(last.z_end), last.z_start.max(last.z_end));
    let on_part = if za < 0.0 { zb.min(0.0) - za } else { pass_length };
    let (engagement, basis) = match (r.spec.engagement, r.limits.gauge_plane) {
        (Some(le), _) => (le, "as given".to_string()),
        (None, Some(gp)) => (gp.distance, "the gauge's L1".to_string()),
        (None, None) => (
            r.designation.thread.nominal_diameter,
            format!(
                "LE = D = {:.3} mm, the length ASME B1.1 and BS 84 base their tolerances on",
                r.designation.thread.nominal_diameter
            ),
        ),
    };
    let used = on_part.min(engagement);
    let lead = crate::analysis::turn::lead::lead_deviation(last.lead, op.units, &r.designation.thread, used)
        .unwrap_or(None)
        .map(|d| crate::analysis::turn::lead::LeadDeviation { pass_length, engagement, ..d });
    if let Some(d) = &lead {
        let whole = d.pitch_diameter_equivalent * pass_length / used.max(1e-9);
        notes.push(crate::ground::note::Note::from(format!(
            "the lead error adds up over {:.3} mm: the thread on the part from its face at Z0 ({:.3} mm of the finishing pass's {:.3} mm) up to the length of engagement ({basis}; ‹engagement› sets it); {:.1} µm on the pitch diameter, {:.1} µm over the whole pass",
            used,
            on_part,
            pass_length,
            d.pitch_diameter_equivalent * 1e3,
            whole * 1e3
        )));
    }
    // The starts cut: by their phase against the designation's pitch when it has several,
    // else as the program's reading told them apart.
    let t = &r.designation.thread;
    let cut: std::collections::BTreeSet<u32> =
        if t.starts > 1 { &passes } else { &op.passes }.iter().map(|p| p.start).collect();
    // A start off a whole number of pitches (two increments of the program's, to allow for its
    // rounding) is misplaced: it fails by its offset (issue 47).
    // Each start's phase is its last pass's (the infeed moves a flank-fed pass along Z; every
    // start's last pass is at full depth alike).
    // The starts as the program's reading told them apart (one cycle per start) when it did,
    // else as their phases are assigned above.
    let read: std::collections::BTreeSet<u32> = op.passes.iter().map(|p| p.start).collect();
    let grouped = if read.len() > 1 { &op.passes } else { &passes };
    let mut phases: Vec<f64> = Vec::new();
    for s in grouped.iter().map(|p| p.start).collect::<std::collections::BTreeSet<u32>>() {
        if let Some(p) = grouped.iter().rev().find(|p| p.start == s) {
            phases.push(p.z_phase);
        }
    }
    let tolerance = 2.0 * op.units.least_increment() * op.units.mm() + 1e-9;
    let misplaced = if t.starts > 1 {
        crate::analysis::check::misplaced_starts(&phases, t.pitch, t.lead(), tolerance)
    } else {
        Vec::new()
    };
    let starts = crate::analysis::check::starts_check(&cut, t.starts, t.pitch, &misplaced);
    let mut v = verify_core(
        r,
        Some(Given {
            passes,
            depth_word: op.depth_word.clone(),
            units: op.units,
            lead,
            label: label.clone(),
            notes,
        }),
    )?;
    // One cycle per start: the correction changes each cycle's word alike, when they are
    // written alike; otherwise it is said for the first and the others are named.
    if let Some(d) = v.depth.as_mut() {
        for w in &op.start_words {
            d.also.push(crate::analysis::turn::correction::Place { line: w.line, column: w.column });
            d.alike &= w.written == d.word.written && w.form == d.word.form;
        }
        d.pass_x_words = op.pass_x_words.clone();
        if let Some(c) = v.correction.as_mut() {
            d.apply_to(c, v.kind);
        }
    }
    if !starts.ok {
        // A start missing (or one too many) is no matter of X: no correction is offered.
        v.correction = None;
        v.depth = None;
        v.suggested_final_x = None;
        v.middle_final_x = None;
        v.notes.push(crate::ground::note::Note::from(format!(
            "no correction is offered while the starts are wrong: {}",
            starts.note.as_deref().unwrap_or_default()
        )));
    }
    v.checks.push(starts);
    v.pass = verdict(&v.checks, v.gauge_only);
    v.hints = crate::analysis::check::hints(
        &v.checks,
        &v.insert,
        &v.limits,
        v.designation.thread.half_angle().to_degrees(),
    );
    Ok(v)
}

/// The side a turned operation's passes cut: inward pass by pass from a bar (external), outward
/// in a bore (internal); `None` when every pass ends at one X.
pub fn pass_side(passes: &[Pass]) -> Option<ThreadKind> {
    let first = passes.first()?;
    let dx = last_head(passes).x_end - first.x_end;
    if dx.abs() < 1e-6 {
        None
    } else if dx < 0.0 {
        Some(ThreadKind::External)
    } else {
        Some(ThreadKind::Internal)
    }
}

/// The designation of a turned operation from its program: the nearest comment above it (back
/// to the operation before) that names a thread, else the nearest one higher up whose lead is
/// the operation's, else the standard size of its lead and diameter (the last pass's tip is on
/// d3 ≈ d − 1.2269·P on a bar, on D in a bore).
fn name_turned(
    op: &crate::gcode::Operation,
    before: Option<&crate::gcode::Operation>,
    comments: &[crate::gcode::Comment],
    internal: bool,
    opts: crate::standards::designation::ParseOptions,
    file: &str,
) -> Result<crate::analysis::naming::Named, Error> {
    use crate::analysis::naming::{from_comments, infer_designation_with};
    let kind = match (internal, pass_side(&op.passes)) {
        (true, _) => ThreadKind::Internal,
        (false, Some(k)) => k,
        (false, None) => ThreadKind::External,
    };
    let lead = op.passes.first().map_or(0.0, |p| p.lead);
    let upto = op
        .passes
        .iter()
        .filter_map(|p| p.source_line)
        .chain([op.source_line])
        .max()
        .unwrap_or(op.source_line);
    // The comments are the program's own: an operation in a subprogram's file has none above it
    // there, and takes the program's nearest comment of its lead.
    let in_sub = op.source_file.is_some();
    let after = if in_sub { usize::MAX } else { before.map_or(0, |b| b.source_line) };
    if let Some(n) = from_comments(comments, after, upto, kind, opts).filter(|_| !in_sub) {
        return Ok(n);
    }
    let same_lead = comments
        .iter()
        .rev()
        .filter(|c| c.line <= after)
        .find(|c| {
            crate::analysis::naming::designation_in_comment(&c.text, opts).is_some_and(|f| {
                crate::analysis::turn::lead::lead_deviation(lead, op.units, &f.designation.thread, 1.0)
                    .is_ok()
            })
        })
        .map(|c| c.line);
    if let Some(line) = same_lead {
        if let Some(n) = from_comments(comments, line - 1, line, kind, opts) {
            return Ok(n);
        }
    }
    let last = last_head(&op.passes).x_end;
    let starts = op.passes.iter().map(|p| p.start + 1).max().unwrap_or(1);
    let pitch = lead / f64::from(starts);
    let major = match kind {
        ThreadKind::External => last + 2.0 * 0.613_434_5 * pitch,
        ThreadKind::Internal => last,
    };
    // A G76's angle word is the tool's included angle: twice the infeed angle it sets.
    let tool_angle = op.infeed_angle.as_ref().filter(|_| op.cycle == "G76").map(|(a, _)| 2.0 * a);
    infer_designation_with(lead, starts, major, kind, op.units, op.source_line, tool_angle).map_err(|e| {
        match e {
            Error::Input(message) => {
                Error::Program { file: file.to_string(), line: op.source_line, column: 1, message }
            }
            e => e,
        }
    })
}

/// How a program's operation gets its insert: `None` keeps the spec's; else the insert, the
/// note that says where it came from, and whether it is the assumed default.
pub type InsertFor<'a> = dyn Fn(&crate::gcode::Operation) -> Option<(InsertChoice, String, bool)> + 'a;

/// A program read, and its turned threads verified.
#[derive(Clone, Debug)]
pub struct TurnedProgram {
    /// The program as read (its notes and reading go to the whole program's verification).
    pub prog: crate::gcode::Program,
    /// The program's name and dialect, as shown.
    pub label: ProgramLabel,
    /// Each turned operation verified, in program order (the one `VerifySpec::operation` names,
    /// when it names one).
    pub operations: Vec<OperationVerdict>,
    /// How many threading operations the program has.
    pub operations_in_program: usize,
}

/// The turned threads of a program held in memory, each verified: `threads` gives one designation
/// for all operations or one per operation in program order; `insert_for` chooses each
/// operation's insert (from its tool number, say) and says what it assumed. The whole program's
/// verification ([`verify_program`](crate::verify_program)) is made of these.
pub fn turned_program(
    spec: &VerifySpec,
    text: &str,
    name: &str,
    dialect: crate::gcode::Dialect,
    threads: &[String],
    insert_for: &InsertFor<'_>,
) -> Result<TurnedProgram, Error> {
    let prog = crate::gcode::read_program_with(text, name, dialect, spec.reading.clone())?;
    let n = prog.operations.len();
    if !(threads.is_empty() || threads.len() == 1 || threads.len() == n) {
        let lines: Vec<String> =
            prog.operations.iter().map(|o| format!("{} at line {}", o.cycle, o.source_line)).collect();
        return Err(Error::Input(format!(
            "{name} cuts {n} thread{} ({}); give one designation for all of them or one per operation, not {} times",
            if n == 1 { "" } else { "s" },
            lines.join(", "),
            threads.len()
        )));
    }
    let label = ProgramLabel { file: name.to_string(), dialect };
    let mut operations = Vec::with_capacity(n);
    // One operation when the spec names it, else every one.
    let only = spec.operation.map(|k| operation_index(&prog, name, Some(k))).transpose()?;
    let comments = if threads.is_empty() { crate::gcode::comments(text, dialect) } else { Vec::new() };
    for (i, op) in prog.operations.iter().enumerate() {
        if only.is_some_and(|k| k != i) {
            continue;
        }
        let named = match threads {
            [] => name_turned(
                op,
                i.checked_sub(1).map(|k| &prog.operations[k]),
                &comments,
                spec.internal,
                crate::standards::designation::ParseOptions { allow_nonstandard: spec.allow_nonstandard },
                name,
            )?,
            [one] => crate::analysis::naming::Named::given(one),
            many => crate::analysis::naming::Named::given(&many[i]),
        };
        let designation = named.designation.clone();
        let mut s = VerifySpec {
            units: if spec.units_given {
                spec.units
            } else {
                VerifySpec::default_units(&designation, spec.allow_nonstandard)
            },
            designation: designation.clone(),
            program: None,
            operation: None,
            final_x: None,
            ..spec.clone()
        };
        let mut extra = Vec::new();
        if !named.why.is_empty() {
            extra.push(named.why.clone());
        }
        // The program's declared stock is the blank of an external thread it turns no diameter
        // for (issue 47: a training simulator's `[BILLET X30`).
        if let (None, None, Some((d, line))) =
            (spec.blank_diameter, program_blank(op, ThreadKind::External), prog.stock)
        {
            if pass_side(&op.passes) != Some(ThreadKind::Internal) && !spec.internal {
                s.blank_diameter = Some(d);
                extra.push(format!(
                    "the blank is the stock the program declares at line {line}: Ø{} (‹blank_diameter› overrides)",
                    crate::ground::fmt::fmt_num(d)
                ));
            }
        }
        let mut assumed = false;
        if let Some((choice, note, default)) = insert_for(op) {
            if default {
                let (choice, what) = assumed_insert(op, &s);
                s.insert = choice;
                extra.push(format!(
                    "insert assumed: {what} ({note}; choose with ‹insert› or ‹tools›): the root radius, the crest and the diameters its tip and crest leave are unverified"
                ));
            } else {
                s.insert = choice;
                extra.push(note);
            }
            assumed = default;
        }
        // A thread given: the one the passes cut, by their lead and diameters, is said beside it
        // when the two differ (and in the refusal of one far from it).
        let inferred = (!threads.is_empty())
            .then(|| {
                let opts =
                    crate::standards::designation::ParseOptions { allow_nonstandard: spec.allow_nonstandard };
                let cut = name_turned(op, None, &[], spec.internal, opts, name).ok()?;
                let size = |d: &str| parse_designation(d, opts).ok().map(|d| d.thread);
                let (a, b) = (size(&cut.designation)?, size(&designation)?);
                let same = a.form == b.form
                    && (a.nominal_diameter - b.nominal_diameter).abs() < 1e-6
                    && (a.pitch - b.pitch).abs() < 1e-6
                    && a.starts == b.starts;
                (!same).then_some(cut.designation)
            })
            .flatten();
        if let Some(cut) = &inferred {
            extra.push(format!(
                "the thread given is {designation}; the passes' lead and diameters are those of {cut} (inferred)"
            ));
        }
        let mut result = verify_operation(&s, op, &label).map_err(|e| match (e, &inferred) {
            (Error::Program { file, line, column, message }, Some(cut)) if message.ends_with(MISFIT_END) => {
                Error::Program {
                    file,
                    line,
                    column,
                    message: format!("{message} (the passes fit {cut}, inferred)"),
                }
            }
            (e, _) => e,
        })?;
        if let OperationResult::Verified(v) = &mut result {
            v.notes.extend(extra.into_iter().map(crate::ground::note::Note::from));
            let t = v.designation.thread;
            let (checks, report) = crate::analysis::process::process_checks(
                op,
                t.pitch,
                t.pitch_diameter(),
                spec.machine.as_ref(),
                spec.clearance_angle.or(v.insert.clearance_angle),
            );
            v.checks.extend(checks);
            v.process = Some(report);
            if assumed {
                unverified_by_assumed_insert(v);
                if v.correction.is_some() || v.suggested_final_x.is_some() {
                    let other = other_candidate(&s, op, &label);
                    withhold_correction(v, other);
                }
                // The mid-tolerance X rests on the insert as the correction does.
                v.middle_final_x = None;
            }
            v.pass = verdict(&v.checks, v.gauge_only);
        }
        operations.push(OperationVerdict { operation: op.clone(), designation, named, result });
    }
    Ok(TurnedProgram { prog, label, operations, operations_in_program: n })
}

/// The insert a program's passes are written for when no tool is known: of the full-profile
/// insert (its tip on the basic root: d3 on a bar, D in a bore) and the default partial-profile
/// insert (tip r0.04: the flanks on the basic d2 put the tip H − 2r(1/sin α − 1) beyond d2 on the
/// diameter), the one whose tip position lies nearer the deepest pass; the full one on a tie or
/// when the designation cannot be read here (the verification then says why). With what to say.
fn assumed_insert(op: &crate::gcode::Operation, spec: &VerifySpec) -> (InsertChoice, String) {
    const TIP: f64 = 0.04;
    let full = (
        InsertChoice::Full,
        "the full-profile insert of the thread's pitch, the one the passes' depth is written for".to_string(),
    );
    let Ok(des) =
        parse_designation(&spec.designation, ParseOptions { allow_nonstandard: spec.allow_nonstandard })
    else {
        return full;
    };
    let t = des.thread;
    if op.passes.is_empty() || t.form.taper() != 0.0 || TIP > t.root_radius() {
        return full;
    }
    let internal = spec.internal
        || (des.external.is_none() && des.internal.is_some())
        || pass_side(&op.passes) == Some(ThreadKind::Internal);
    let last = last_head(&op.passes);
    let x = 0.5 * (last.x_start.abs() + last.x_end.abs());
    let below_d2 = t.fundamental_height() - 2.0 * TIP * (1.0 / t.half_angle().sin() - 1.0);
    let (x_full, x_partial) = if internal {
        (t.nominal_diameter, t.pitch_diameter() + below_d2)
    } else {
        (t.minor_diameter_external(), t.pitch_diameter() - below_d2)
    };
    if (x - x_partial).abs() < (x - x_full).abs() - 1e-9 {
        (
            InsertChoice::Partial { tip_radius: TIP },
            format!(
                "a partial-profile insert with a {} mm tip, the one the passes' depth is written for (the last pass X{x:.3} lies nearer its X{x_partial:.3} than a full-profile insert's X{x_full:.3})",
                crate::ground::fmt::fmt_num(TIP)
            ),
        )
    } else {
        full
    }
}

/// The insert a program's passes could equally be written for, beside the one assumed (the
/// full-profile insert of the pitch and the default partial one), and the pitch diameter it
/// leaves (`None` when it cannot cut this thread).
fn other_candidate(
    spec: &VerifySpec,
    op: &crate::gcode::Operation,
    label: &ProgramLabel,
) -> Option<(String, f64, bool)> {
    let other = match spec.insert {
        InsertChoice::Full => InsertChoice::Partial { tip_radius: 0.04 },
        InsertChoice::Partial { .. } => InsertChoice::Full,
        _ => return None,
    };
    let s = VerifySpec { insert: other, metrics: false, picture: false, ..spec.clone() };
    match verify_operation(&s, op, label).ok()? {
        OperationResult::Verified(o) => {
            use crate::analysis::check::CheckFeature as F;
            let size_ok = !crate::analysis::check::any_fails(
                &o.checks,
                &[F::PitchDiameter, F::MaxMaterial, F::FunctionalPitchDiameter],
            );
            Some((o.insert.name, o.measurement.pitch_diameter, size_ok))
        }
        OperationResult::NoCut { .. } => None,
    }
}

/// A correction computed with an insert nobody chose is no instruction: the pitch diameter the
/// passes leave depends on the insert (a partial-profile insert's flanks stand off its tip
/// otherwise than a full-profile one's), and moving X by the assumed insert's figure scraps the
/// part cut with the other (issue 61: an Okuma M25x1.25 nut, −44.5 µm with the partial r0.04
/// assumed, +51 µm inside 6H with a full-profile insert; its X.990 moved to X.9955 would have left it
/// over D2 max). It is withheld, with the other insert's pitch diameter said.
pub fn withhold_correction(v: &mut Verification, other: Option<(String, f64, bool)>) {
    v.correction = None;
    v.suggested_final_x = None;
    v.middle_final_x = None;
    let pd = v.measurement.pitch_diameter;
    let also = match other {
        Some((name, d2, ok)) => format!(
            "; with {name} the passes leave {} {d2:.4}, {}",
            if v.kind == ThreadKind::External { "d2" } else { "D2" },
            if ok { "inside the class" } else { "outside the class too" }
        ),
        None => String::new(),
    };
    v.notes.push(crate::ground::note::Note::from(format!(
        "no correction is offered: the pitch diameter {pd:.4} rests on the insert assumed ({}){also}; give ‹insert› or ‹tools› for a correction",
        v.insert.name
    )));
}

/// What an insert nobody chose decides: the root radius, the diameter its tip leaves (d3 on a
/// bar, D in a bore), the crest (a full-profile insert tops it, a partial one leaves the
/// blank's) and the crest's diameter where the insert topped the blank. With the insert assumed these checks are reported
/// `unverified`, with what was assumed, and left out of the verdict; the sizes the passes decide
/// (d2, the GO gauge, the crest diameter the blank leaves) and the flanks count.
pub fn unverified_by_assumed_insert(v: &mut Verification) {
    use crate::analysis::check::CheckFeature as F;
    let kind = v.kind;
    let assumed = format!("tool not known: the insert assumed is {}", v.insert.name);
    // The crest diameter is the blank's unless the assumed insert topped it.
    let blank = v.blank_diameter;
    for c in &mut v.checks {
        let on_tool = match (c.feature, kind) {
            (F::RootRadius | F::Crest, _) => true,
            (F::MinorDiameter, ThreadKind::External) | (F::MajorDiameter, ThreadKind::Internal) => true,
            (F::MajorDiameter, ThreadKind::External) => c.value < blank - 1e-4,
            (F::MinorDiameter, ThreadKind::Internal) => c.value > blank + 1e-4,
            _ => false,
        };
        if on_tool {
            c.unverified = Some(assumed.clone());
        }
    }
    // Hints about a failing root or crest speak of the assumed insert: not the program's.
    v.hints.retain(|h| !matches!(h, crate::analysis::check::Hint::TipRadius { .. }));
}

/// One thread re-cut with its passes moved radially and its insert's tip radius changed: the
/// verify core a Monte Carlo calls once per sampled part.
#[derive(Clone, Debug)]
pub(crate) struct Recut {
    r: Resolved,
    passes: Vec<Pass>,
    label: ProgramLabel,
}

impl Recut {
    /// The thread of `spec` as `verify` cuts it (plan or program), ready to be re-cut.
    pub(crate) fn new(spec: &VerifySpec) -> Result<(Recut, Verification), Error> {
        let quick = VerifySpec { metrics: false, picture: false, ..spec.clone() };
        let v = verify(&quick)?;
        // The program's text is read once, by `verify`: the re-cuts take its passes.
        let r = resolve(&VerifySpec {
            program: None,
            operation: None,
            final_x: None,
            blank_diameter: Some(v.blank_diameter),
            ..quick
        })?;
        let label = v
            .program
            .clone()
            .unwrap_or(ProgramLabel { file: "<plan>".into(), dialect: crate::gcode::Dialect::Fanuc });
        Ok((Recut { r, passes: v.passes.clone(), label }, v))
    }

    /// How many passes each re-cut sweeps.
    pub(crate) fn pass_count(&self) -> usize {
        self.passes.len()
    }

    /// The tip radius of a partial-profile insert, mm (`None` for the others).
    pub(crate) fn tip_radius(&self) -> Option<f64> {
        match self.r.spec.insert {
            InsertChoice::Partial { tip_radius } => Some(tip_radius),
            InsertChoice::Full | InsertChoice::File(_) | InsertChoice::Toml { .. } => None,
        }
    }

    /// The thread cut with every pass's X moved by `dx` mm (diameter) and, when given, a
    /// partial insert of tip radius `tip`.
    pub(crate) fn cut(&self, dx: f64, tip: Option<f64>) -> Result<Verification, Error> {
        let mut r = self.r.clone();
        if let Some(tip) = tip {
            let t = r.designation.thread;
            r.insert =
                build_insert(&InsertChoice::Partial { tip_radius: tip }, &t, r.kind, r.spec.tolerance)?;
        }
        let passes = self
            .passes
            .iter()
            .map(|p| Pass { x_start: p.x_start + dx, x_end: p.x_end + dx, x_taper: p.x_taper + dx, ..*p })
            .collect();
        let given = Given {
            passes,
            depth_word: None,
            units: crate::gcode::ProgramUnits::Mm,
            lead: None,
            label: self.label.clone(),
            notes: Vec::new(),
        };
        verify_core(&r, Some(given))
    }
}
