//! Checks of a measured thread against its limits, and the verdict.
//!
//! Each check is `size` (what GO/NO-GO gauges see: major and pitch diameter, the
//! maximum-material condition, and whether a crest is left at all) or `form` (root radius,
//! minor-diameter zone, flank angles, a single groove). `--gauge-only` leaves the form checks
//! out of the verdict but reports them.

use crate::geometry::measure::Measurement;
use crate::standards::tolerance::{Limit, ThreadLimits};
use crate::standards::{BasicThread, ThreadKind};
use serde::Serialize;

/// Flank half-angles have no product tolerance in ISO 965-1 (it is absorbed by the pitch
/// diameter); threadcheck flags a flank more than this many degrees off nominal.
pub const FLANK_ANGLE_TOLERANCE_DEG: f64 = 1.0;

/// The maximum-material check allows this much apparent interference, mm (0.05 µm): the
/// geometry's own accuracy, so that a thread cut exactly at basic size with an `h`/`H` class
/// passes.
pub const MMC_SLACK: f64 = 5e-5;

/// Flank angles are compared at 0.001°.
fn at_millidegree(deg: f64) -> f64 {
    (deg * 1000.0).round() / 1000.0
}

/// A crest narrower than this (mm) 1 µm below its top is no crest: the grooves have met.
pub const MIN_CREST_WIDTH: f64 = 1e-3;

/// Whether a check is what a thread gauge decides (size) or a form requirement.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum CheckKind {
    /// GO/NO-GO gauging: major, pitch, maximum material, crest present.
    Size,
    /// Form: root radius, minor-diameter zone, flank angles, single groove.
    Form,
    /// Process: constant spindle speed, the machine's speed and feed, flank clearance.
    Process,
}

impl CheckKind {
    /// Whether a check of this kind counts in the verdict: with `gauge_only`, the form checks
    /// are reported but left out.
    pub fn counts(self, gauge_only: bool) -> bool {
        match self {
            CheckKind::Size | CheckKind::Process => true,
            CheckKind::Form => !gauge_only,
        }
    }

    /// `size`, `form` or `process`.
    pub fn name(self) -> &'static str {
        match self {
            CheckKind::Size => "size",
            CheckKind::Form => "form",
            CheckKind::Process => "process",
        }
    }
}

/// What a check's value is measured in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CheckUnit {
    /// Millimetres (deviations in µm).
    Mm,
    /// Degrees.
    Degree,
    /// A whole number.
    Count,
    /// Turns of the thread (the gauge plane's place).
    Turn,
    /// Change of diameter per unit of length (a taper).
    DiameterPerLength,
    /// Yes (1) or no (0).
    YesNo,
    /// Revolutions per minute.
    Rpm,
    /// Millimetres per minute.
    MmPerMin,
}

/// What a check measures. The JSON names are the snake-case variant names
/// (`pitch_diameter`, …); adding one makes every `match` on it say what it does.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum CheckFeature {
    /// Major diameter d (D for a nut), mm.
    MajorDiameter,
    /// Pitch diameter d2 (D2), mm.
    PitchDiameter,
    /// The functional (virtual) pitch diameter where the program's lead deviates: d2 with the
    /// lead error's equivalent, against the maximum-material limit, mm.
    FunctionalPitchDiameter,
    /// Minor diameter d3 (D1), mm.
    MinorDiameter,
    /// Smallest root radius, mm.
    RootRadius,
    /// One flank's half angle, degrees (`note` names the flank).
    FlankAngle,
    /// Signed clearance to the maximum-material profile (the GO gauge), mm.
    MaxMaterial,
    /// Crest present: the insert left part of the blank's diameter.
    Crest,
    /// One groove per lead: no second pocket at the root.
    SingleGroove,
    /// A program's threads: the starts it cuts against the designation's (a count).
    Starts,
    /// Taper threads: the gauge plane's position, turns.
    GaugePlane,
    /// Taper threads: the taper of the passes, diameter per length.
    Taper,
    /// Process: no constant surface speed at a threading cycle.
    ConstantSpindleSpeed,
    /// Process: the machine's spindle speed limit, rpm.
    SpindleSpeed,
    /// Process: the machine's feed limit (S·lead), mm/min.
    Feed,
    /// Process: the leading flank's side clearance against the helix, degrees.
    FlankClearance,
    /// Process: room for the insert beyond the last pass, mm.
    RunOut,
    /// A thread-milling helix's Z travel per revolution against the designation's lead (issue 31).
    Lead,
    /// A multi-form thread mill's row pitch against the thread's pitch.
    RowPitch,
    /// A thread mill's deepest radial pass, from the bore or blank, against the thread's depth
    /// to its fundamental triangle's root (issues 63 and 64).
    RadialDepth,
    /// A thread-milling helix's hand (its turning direction × its Z direction) against the
    /// designation's (issue 46).
    Hand,
}

impl CheckFeature {
    /// The JSON name (`pitch_diameter`).
    pub fn name(self) -> &'static str {
        match self {
            CheckFeature::MajorDiameter => "major_diameter",
            CheckFeature::PitchDiameter => "pitch_diameter",
            CheckFeature::FunctionalPitchDiameter => "functional_pitch_diameter",
            CheckFeature::MinorDiameter => "minor_diameter",
            CheckFeature::RootRadius => "root_radius",
            CheckFeature::FlankAngle => "flank_angle",
            CheckFeature::MaxMaterial => "max_material",
            CheckFeature::Crest => "crest",
            CheckFeature::SingleGroove => "single_groove",
            CheckFeature::Starts => "starts",
            CheckFeature::GaugePlane => "gauge_plane",
            CheckFeature::Taper => "taper",
            CheckFeature::ConstantSpindleSpeed => "constant_spindle_speed",
            CheckFeature::SpindleSpeed => "spindle_speed",
            CheckFeature::Feed => "feed",
            CheckFeature::FlankClearance => "flank_clearance",
            CheckFeature::RunOut => "run_out",
            CheckFeature::Lead => "lead",
            CheckFeature::RowPitch => "row_pitch",
            CheckFeature::RadialDepth => "radial_depth",
            CheckFeature::Hand => "hand",
        }
    }

    /// The name in the text report (`pitch diameter`).
    pub fn label(self) -> &'static str {
        match self {
            CheckFeature::MajorDiameter => "major diameter",
            CheckFeature::PitchDiameter => "pitch diameter",
            CheckFeature::FunctionalPitchDiameter => "functional d2",
            CheckFeature::MinorDiameter => "minor diameter",
            CheckFeature::RootRadius => "root radius",
            CheckFeature::FlankAngle => "flank angle",
            CheckFeature::MaxMaterial => "max material",
            CheckFeature::Crest => "crest",
            CheckFeature::SingleGroove => "one groove",
            CheckFeature::Starts => "starts",
            CheckFeature::GaugePlane => "gauge plane",
            CheckFeature::Taper => "taper",
            CheckFeature::ConstantSpindleSpeed => "constant rpm",
            CheckFeature::SpindleSpeed => "spindle speed",
            CheckFeature::Feed => "feed S×lead",
            CheckFeature::FlankClearance => "flank clearance",
            CheckFeature::RunOut => "run-out room",
            CheckFeature::Lead => "helix lead",
            CheckFeature::RowPitch => "row pitch",
            CheckFeature::RadialDepth => "radial depth",
            CheckFeature::Hand => "hand",
        }
    }

    /// The words a machinist uses for the feature of a bolt (`External`) or a nut: `pitch
    /// diameter d2`, `minor diameter D1`, `GO gauge (maximum material)`.
    pub fn words(self, kind: crate::ThreadKind) -> &'static str {
        let ext = kind == crate::ThreadKind::External;
        match self {
            CheckFeature::MajorDiameter if ext => "major diameter d",
            CheckFeature::MajorDiameter => "major diameter D",
            CheckFeature::PitchDiameter if ext => "pitch diameter d2",
            CheckFeature::PitchDiameter => "pitch diameter D2",
            CheckFeature::FunctionalPitchDiameter if ext => "functional pitch diameter d2",
            CheckFeature::FunctionalPitchDiameter => "functional pitch diameter D2",
            CheckFeature::MinorDiameter if ext => "minor diameter d3",
            CheckFeature::MinorDiameter => "minor diameter D1",
            CheckFeature::RootRadius => "root radius",
            CheckFeature::FlankAngle => "flank angle",
            CheckFeature::MaxMaterial => "GO gauge (max. material)",
            CheckFeature::Crest => "crest left standing",
            CheckFeature::SingleGroove => "one groove per pitch",
            CheckFeature::Starts => "starts cut",
            CheckFeature::GaugePlane => "gauge plane",
            CheckFeature::Taper => "taper",
            CheckFeature::ConstantSpindleSpeed => "constant rpm (G97)",
            CheckFeature::SpindleSpeed => "spindle speed",
            CheckFeature::Feed => "feed (S × lead)",
            CheckFeature::FlankClearance => "flank clearance",
            CheckFeature::RunOut => "run-out room",
            CheckFeature::Lead => "lead per revolution",
            CheckFeature::RowPitch => "cutter row pitch",
            CheckFeature::RadialDepth => "radial depth of the passes",
            CheckFeature::Hand => "hand of the helix",
        }
    }

    /// What the check's value, limits and deviation are measured in.
    pub fn unit(self) -> CheckUnit {
        match self {
            CheckFeature::MajorDiameter
            | CheckFeature::PitchDiameter
            | CheckFeature::FunctionalPitchDiameter
            | CheckFeature::MinorDiameter
            | CheckFeature::RootRadius
            | CheckFeature::MaxMaterial
            | CheckFeature::Crest
            | CheckFeature::RunOut
            | CheckFeature::Lead
            | CheckFeature::RowPitch
            | CheckFeature::RadialDepth => CheckUnit::Mm,
            CheckFeature::FlankAngle | CheckFeature::FlankClearance => CheckUnit::Degree,
            CheckFeature::SingleGroove | CheckFeature::ConstantSpindleSpeed | CheckFeature::Hand => {
                CheckUnit::YesNo
            }
            CheckFeature::Starts => CheckUnit::Count,
            CheckFeature::GaugePlane => CheckUnit::Turn,
            CheckFeature::Taper => CheckUnit::DiameterPerLength,
            CheckFeature::SpindleSpeed => CheckUnit::Rpm,
            CheckFeature::Feed => CheckUnit::MmPerMin,
        }
    }

    /// Whether the value is a length in mm (shown in inches beside it with `--units inch`).
    pub fn is_length(self) -> bool {
        self.unit() == CheckUnit::Mm
    }
}

impl std::fmt::Display for CheckFeature {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// One check: value, limits, verdict and deviation.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Check {
    /// What is measured.
    pub feature: CheckFeature,
    /// Size or form.
    pub kind: CheckKind,
    /// Measured value (mm, or degrees for flank angles).
    pub value: f64,
    /// Lower limit, if any.
    pub min: Option<f64>,
    /// Upper limit, if any.
    pub max: Option<f64>,
    /// Within the limits.
    pub ok: bool,
    /// 0 inside the limits, else the signed distance to the nearer limit, µm (degrees × 1000
    /// for flank angles is not used: angles report their deviation in degrees in `note`).
    pub deviation_um: f64,
    /// Which flank (`low-z`, `high-z`) or other detail.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
    /// Set when the value rests on a tool nobody chose (the program names no insert): what was
    /// assumed. Such a check is reported `unverified` and left out of the verdict, whatever
    /// `ok` says of the assumed tool.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unverified: Option<String>,
}

impl Check {
    /// Whether the check counts in the verdict: not when it is unverified, nor a form check with
    /// `gauge_only`.
    pub fn counts(&self, gauge_only: bool) -> bool {
        self.unverified.is_none() && self.kind.counts(gauge_only)
    }

    /// Whether it fails the verdict: out of its limits and counted.
    pub fn fails(&self, gauge_only: bool) -> bool {
        !self.ok && self.counts(gauge_only)
    }
}

/// A check of `value` against `lim`, compared at the resolution `at` rounds to (the standard's:
/// [`Resolution::round`]): inside at that resolution is within, so a limit exactly met passes;
/// outside, the deviation is the true distance to the limit.
fn check(
    feature: CheckFeature,
    kind: CheckKind,
    value: f64,
    lim: Limit,
    note: Option<String>,
    at: impl Fn(f64) -> f64,
) -> Check {
    let dev = if lim.deviation(at(value)) == 0.0 { 0.0 } else { lim.deviation(value) };
    Check {
        feature,
        kind,
        value,
        min: lim.min,
        max: lim.max,
        ok: dev == 0.0,
        deviation_um: dev * 1000.0,
        note,
        unverified: None,
    }
}

/// The starts a program cuts (0-based start indices) against the designation's `wanted`: a
/// start missing or one too many fails, naming them. A size check: a missing start is a groove
/// the GO gauge meets.
pub fn starts_check(
    cut: &std::collections::BTreeSet<u32>,
    wanted: u32,
    pitch: f64,
    misplaced: &[f64],
) -> Check {
    let missing: Vec<String> = (0..wanted)
        .filter(|s| !cut.contains(s))
        .map(|s| format!("start {} ({:.4} mm along Z from start 1)", s + 1, f64::from(s) * pitch))
        .collect();
    let extra = cut.iter().filter(|s| **s >= wanted).count();
    let note = if !misplaced.is_empty() {
        let offs: Vec<String> = misplaced.iter().map(|o| format!("{o:.4} mm")).collect();
        format!(
            "a start lies {} along Z from start 1, not a whole number of pitches ({} mm)",
            offs.join(", "),
            crate::ground::fmt::fmt_num(pitch)
        )
    } else if !missing.is_empty() {
        format!("{} of {wanted} starts cut; missing: {}", cut.len(), missing.join(", "))
    } else if extra > 0 {
        format!("the passes cut {} starts, the designation has {wanted}", cut.len())
    } else {
        format!("{wanted} of {wanted} starts cut")
    };
    let w = f64::from(wanted);
    let c = check(
        CheckFeature::Starts,
        CheckKind::Size,
        cut.len() as f64,
        Limit { min: Some(w), max: Some(w) },
        Some(note),
        |v| v,
    );
    // A count has no deviation in µm: the note says what is missing or misplaced.
    Check { deviation_um: 0.0, ok: c.ok && misplaced.is_empty(), ..c }
}

/// The offsets (mm along Z from the first start, modulo the lead) of starts that lie off a
/// whole number of pitches by more than `tolerance`: the phases of the cuts, the first start's
/// first.
pub fn misplaced_starts(phases: &[f64], pitch: f64, lead: f64, tolerance: f64) -> Vec<f64> {
    let Some(&first) = phases.first() else { return Vec::new() };
    let mut out: Vec<f64> = Vec::new();
    for &p in phases {
        let off = (p - first).rem_euclid(lead);
        let k = (off / pitch).round();
        let off_grid = (off - k * pitch).abs() > tolerance && (lead - off).abs() > tolerance;
        if off_grid && !out.iter().any(|o| (o - off).abs() <= tolerance) {
            out.push(off);
        }
    }
    out
}

/// The functional pitch diameter `value` (mm) against the maximum-material side of the class
/// (d2 max for a bolt, D2 min for a nut), as a GO gauge checks it; the note says what the lead
/// error adds.
pub fn functional_check(
    value: f64,
    limits: &ThreadLimits,
    kind: ThreadKind,
    ld: crate::analysis::turn::lead::LeadDeviation,
) -> Check {
    let lim = match kind {
        ThreadKind::External => Limit { min: None, max: limits.pitch_diameter.max },
        ThreadKind::Internal => Limit { min: limits.pitch_diameter.min, max: None },
    };
    let note = format!(
        "lead {:.6} mm against {:.6} mm: {:+.2} µm over {:.2} mm, {:+.2} µm on the pitch diameter",
        ld.program_lead,
        ld.designation_lead,
        ld.cumulative * 1000.0,
        ld.length,
        match kind {
            ThreadKind::External => 1.0,
            ThreadKind::Internal => -1.0,
        } * ld.pitch_diameter_equivalent
            * 1000.0
    );
    check(CheckFeature::FunctionalPitchDiameter, CheckKind::Size, value, lim, Some(note), |v| {
        limits.resolution.round(v)
    })
}

/// A taper thread's cone as measured: where its gauge plane lies against the basic position, in
/// turns (+ deeper into the part), and the taper of its passes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cone {
    /// Gauge plane offset from its basic position, turns.
    pub turns: f64,
    /// Allowed offset either way, turns.
    pub tolerance_turns: f64,
    /// The taper the passes cut, on the diameter per mm.
    pub taper: f64,
    /// The form's taper.
    pub nominal_taper: f64,
}

/// The taper's own tolerance used for the `taper` check: 1/96 in per in on the diameter either
/// way (recalled for NPT, not sourced here; stated in the check's note).
pub const TAPER_TOLERANCE: f64 = 1.0 / 96.0;

/// Both flank angles against half the form's angle ±1°; the deviation in degrees goes in the note.
fn flank_checks(m: &Measurement, thread: &BasicThread) -> Vec<Check> {
    let nominal = 0.5 * thread.form.flank_angle();
    let lim = Limit::new(nominal - FLANK_ANGLE_TOLERANCE_DEG, nominal + FLANK_ANGLE_TOLERANCE_DEG);
    m.flank_angles
        .iter()
        .zip(["low-z flank", "high-z flank"])
        .map(|(a, which)| {
            let mut c = check(
                CheckFeature::FlankAngle,
                CheckKind::Form,
                *a,
                lim,
                Some(which.to_string()),
                at_millidegree,
            );
            // Angles are not lengths: report the deviation in degrees in the note, 0 µm.
            if !c.ok {
                c.note = Some(format!(
                    "{which}, {:+.3}° outside ±{FLANK_ANGLE_TOLERANCE_DEG}°",
                    lim.deviation(*a)
                ));
            }
            c.deviation_um = 0.0;
            c
        })
        .collect()
}

/// ```
/// use threadcheck::{checks, verify, CheckFeature, InsertChoice, ThreadKind, VerifySpec};
/// let v = verify(&VerifySpec { insert: InsertChoice::Full, ..VerifySpec::of("M10x1.5-6g")? })?;
/// let again = checks(&v.measurement, &v.limits, &v.designation.thread, ThreadKind::External, true, None);
/// let d2 = again.iter().find(|c| c.feature == CheckFeature::PitchDiameter).expect("a d2 check");
/// assert_eq!((d2.min, d2.max), (Some(8.862), Some(8.994))); // ISO 965-2
/// # Ok::<(), threadcheck::Error>(())
/// ```
/// Everything checked for one thread.
pub fn checks(
    m: &Measurement,
    limits: &ThreadLimits,
    thread: &BasicThread,
    kind: ThreadKind,
    single_groove: bool,
    cone: Option<Cone>,
) -> Vec<Check> {
    if let Some(c) = cone {
        return taper_checks(m, thread, single_groove, c);
    }
    let at = |v: f64| limits.resolution.round(v);
    let mut out = vec![
        check(
            CheckFeature::MajorDiameter,
            CheckKind::Size,
            m.major_diameter,
            limits.major_diameter,
            None,
            at,
        ),
        check(
            CheckFeature::PitchDiameter,
            CheckKind::Size,
            m.pitch_diameter,
            limits.pitch_diameter,
            None,
            at,
        ),
        check(
            CheckFeature::MinorDiameter,
            CheckKind::Form,
            m.minor_diameter,
            limits.minor_diameter,
            None,
            at,
        ),
    ];
    if kind == ThreadKind::External {
        if let Some(rmin) = limits.root_radius_min {
            let r = m.root_radius.unwrap_or(0.0);
            out.push(check(
                CheckFeature::RootRadius,
                CheckKind::Form,
                r,
                Limit { min: Some(rmin), max: None },
                None,
                at,
            ));
        }
    }
    out.extend(flank_checks(m, thread));
    if let Some(cl) = m.max_material_clearance {
        let mut c = check(
            CheckFeature::MaxMaterial,
            CheckKind::Size,
            cl,
            Limit { min: Some(-MMC_SLACK), max: None },
            None,
            at,
        );
        c.min = Some(0.0);
        if !c.ok {
            c.deviation_um = cl * 1000.0;
            c.note = Some("the GO gauge would not enter".into());
        }
        out.push(c);
    }
    let crest_ok = m.crest_width >= MIN_CREST_WIDTH;
    out.push(Check {
        feature: CheckFeature::Crest,
        kind: CheckKind::Size,
        value: m.crest_width,
        min: Some(MIN_CREST_WIDTH),
        max: None,
        ok: crest_ok,
        deviation_um: if crest_ok { 0.0 } else { (m.crest_width - MIN_CREST_WIDTH) * 1000.0 },
        note: (!crest_ok).then(|| "no crest left: the grooves overlap and meet in a sharp edge".to_string()),
        unverified: None,
    });
    out.push(single_groove_check(single_groove, m.fin_height));
    out
}

/// The checks of a taper thread: the gauge plane's position and the taper (size), the flank
/// angles and the single groove. The crest is not checked: on the cone the insert's crest edge,
/// parallel to the axis, leaves a crest tilted by the taper, and a groove cut too deep shows as
/// the gauge plane's offset.
fn taper_checks(m: &Measurement, thread: &BasicThread, single_groove: bool, c: Cone) -> Vec<Check> {
    let gp_ok = c.turns.abs() <= c.tolerance_turns + 1e-9;
    let mut out = vec![Check {
        feature: CheckFeature::GaugePlane,
        kind: CheckKind::Size,
        value: c.turns,
        min: Some(-c.tolerance_turns),
        max: Some(c.tolerance_turns),
        ok: gp_ok,
        deviation_um: if gp_ok {
            0.0
        } else {
            (c.turns.abs() - c.tolerance_turns) * c.turns.signum() * thread.pitch * 1000.0
        },
        note: Some(format!(
            "turns from the basic gauge plane ({}), ±{} turn assumed",
            if c.turns >= 0.0 { "further in" } else { "further out" },
            c.tolerance_turns
        )),
        unverified: None,
    }];
    let taper_ok = (c.taper - c.nominal_taper).abs() <= TAPER_TOLERANCE + 1e-12;
    out.push(Check {
        feature: CheckFeature::Taper,
        kind: CheckKind::Size,
        value: c.taper,
        min: Some(c.nominal_taper - TAPER_TOLERANCE),
        max: Some(c.nominal_taper + TAPER_TOLERANCE),
        ok: taper_ok,
        deviation_um: 0.0,
        note: Some(format!(
            "taper of the passes on the diameter, 1:{:.1} (1:16 ± 1/96 assumed)",
            if c.taper != 0.0 { 1.0 / c.taper } else { f64::INFINITY }
        )),
        unverified: None,
    });
    out.extend(flank_checks(m, thread));
    out.push(single_groove_check(single_groove, m.fin_height));
    out
}

/// The highest fin or notch a groove may hold, mm: 1 µm, the resolution sizes are read to.
pub const FIN_TOLERANCE: f64 = 1e-3;

/// One groove per pitch (a form check, parallel and taper threads alike): the root has at most
/// one pocket below mid-depth, and no fin or notch over [`FIN_TOLERANCE`] stands anywhere
/// between the crests.
fn single_groove_check(single_groove: bool, fin_height: f64) -> Check {
    let clean = fin_height <= FIN_TOLERANCE;
    let ok = single_groove && clean;
    let note = match (single_groove, clean) {
        (false, _) => Some("the passes do not land in one groove: the root has more than one pocket".to_string()),
        (true, false) => Some(format!(
            "a fin or notch {:.1} µm high stands inside the groove: the passes leave a step (flank infeed steeper than the flank?)",
            fin_height * 1e3
        )),
        (true, true) => None,
    };
    Check {
        feature: CheckFeature::SingleGroove,
        kind: CheckKind::Form,
        value: if ok { 1.0 } else { 0.0 },
        min: Some(1.0),
        max: None,
        ok,
        deviation_um: 0.0,
        note,
        unverified: None,
    }
}

/// What a failing form check says about the insert or the infeed: the next step after a form
/// failure, which a new final X does not fix.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "hint")]
pub enum Hint {
    /// The root radius (or the minor diameter it sets) fails with an insert whose tip radius is
    /// under the standard's smallest root radius: a larger tip or a full-profile insert.
    TipRadius {
        /// The insert's tip radius, mm.
        tip_radius: f64,
        /// The standard's smallest root radius, mm.
        root_radius_min: f64,
    },
    /// A flank stands steeper than the thread's half angle: the infeed angle (or the insert's
    /// angle) exceeds it.
    FlankAngle {
        /// The thread's half angle, degrees.
        half_angle: f64,
    },
    /// A fin, notch or second pocket in the groove: the passes do not follow one groove.
    Groove,
}

/// The hints of a verification's failing form checks, at most one of each kind.
pub fn hints(
    checks: &[Check],
    insert: &crate::geometry::insert::Insert,
    limits: &ThreadLimits,
    half_angle: f64,
) -> Vec<Hint> {
    let failed = |f: CheckFeature| checks.iter().any(|c| c.feature == f && !c.ok);
    let mut out = Vec::new();
    if let Some(rmin) = limits.root_radius_min {
        if (failed(CheckFeature::RootRadius) || failed(CheckFeature::MinorDiameter))
            && insert.tip_radius < rmin
        {
            out.push(Hint::TipRadius { tip_radius: insert.tip_radius, root_radius_min: rmin });
        }
    }
    if checks.iter().any(|c| c.feature == CheckFeature::FlankAngle && !c.ok && c.value > half_angle) {
        out.push(Hint::FlankAngle { half_angle });
    }
    if failed(CheckFeature::SingleGroove) {
        out.push(Hint::Groove);
    }
    out
}

/// Whether any of the checks of these features fails.
pub fn any_fails(checks: &[Check], features: &[CheckFeature]) -> bool {
    checks.iter().any(|c| features.contains(&c.feature) && !c.ok)
}

/// True when every check that counts passes; with `gauge_only`, only size checks count.
pub fn verdict(checks: &[Check], gauge_only: bool) -> bool {
    !checks.iter().any(|c| c.fails(gauge_only))
}

/// A verdict.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Verdict {
    /// Every counted check is within its limits.
    Pass,
    /// At least one is not.
    Fail,
}

impl Verdict {
    /// `Pass` when `ok`.
    pub fn of(ok: bool) -> Verdict {
        if ok {
            Verdict::Pass
        } else {
            Verdict::Fail
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauge_only_ignores_form() {
        let mk = |kind, ok| Check {
            feature: CheckFeature::Crest,
            kind,
            value: 0.0,
            min: None,
            max: None,
            ok,
            deviation_um: 0.0,
            note: None,
            unverified: None,
        };
        let cs = vec![mk(CheckKind::Size, true), mk(CheckKind::Form, false)];
        assert!(!verdict(&cs, false));
        assert!(verdict(&cs, true));
        // An unverified check is reported, never failed.
        let cs = vec![
            mk(CheckKind::Size, true),
            Check { unverified: Some("assumed".into()), ..mk(CheckKind::Size, false) },
        ];
        assert!(verdict(&cs, false));
    }

    #[test]
    fn deviation_is_distance_to_the_nearer_limit_in_um() {
        let c = check(
            CheckFeature::PitchDiameter,
            CheckKind::Size,
            9.026,
            Limit::new(8.862, 8.994),
            None,
            crate::standards::tolerance::round_um,
        );
        assert!(!c.ok && (c.deviation_um - 32.0).abs() < 1e-9);
        let c = check(
            CheckFeature::PitchDiameter,
            CheckKind::Size,
            8.9,
            Limit::new(8.862, 8.994),
            None,
            crate::standards::tolerance::round_um,
        );
        assert!(c.ok && c.deviation_um == 0.0);
    }
}
