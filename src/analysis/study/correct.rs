//! `correct`: from what was measured on the first part to what to change in the program. The
//! thread the program (or plan) cuts is computed as `verify` does; the measurement says how far
//! the real part lies from it. The part is taken to differ from the computed one by its depth
//! only (an X offset, a worn or re-set insert): the whole groove moved radially, so every
//! diameter moves one for one with the final X.

use crate::analysis::check::Verdict;
use crate::analysis::turn::correction::Correction;
use crate::analysis::turn::{verify, Verification, VerifySpec};
use crate::standards::ThreadKind;
use crate::toolpath::passes::Pass;
use crate::Error;
use serde::Serialize;

/// What a gauge said.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum GaugeResult {
    /// The GO gauge does not screw on (in): too much material.
    GoFails,
    /// The NO-GO gauge enters more than the standard allows: too little material.
    NogoEnters,
    /// GO enters and NO-GO does not.
    Ok,
}

impl std::str::FromStr for GaugeResult {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self, Error> {
        match s.trim() {
            "go-fails" => Ok(GaugeResult::GoFails),
            "nogo-enters" => Ok(GaugeResult::NogoEnters),
            "ok" => Ok(GaugeResult::Ok),
            other => Err(Error::Input(format!(
                "gauge result '{}': expected go-fails, nogo-enters or ok",
                crate::ground::error::one_line(other)
            ))),
        }
    }
}

/// What was measured on the part.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Measured {
    /// Over three wires of diameter `wire`: the reading `m`, mm.
    OverWires {
        /// M, mm.
        m: f64,
        /// Wire diameter, mm.
        wire: f64,
    },
    /// The pitch diameter itself (thread micrometer, optical), mm.
    PitchDiameter(f64),
    /// A GO/NO-GO gauge's result.
    Gauge(GaugeResult),
}

/// Everything `correct` needs.
#[derive(Clone, Debug)]
pub struct CorrectSpec {
    /// The thread and its program or plan, as `verify` takes them.
    pub verify: VerifySpec,
    /// What was measured (`None`: a pick-up only).
    pub measured: Option<Measured>,
    /// For a pick-up: the axial position of a groove's centre on the pitch line, measured on
    /// the re-clamped part from the program's Z0, mm.
    pub pickup_z: Option<f64>,
}

/// The three-wire reading turned into a pitch diameter on the as-cut profile.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct WireReading {
    /// The reading M, mm.
    pub m: f64,
    /// The wires, mm.
    pub wire: f64,
    /// The helix term added to M before it is compared with the axial section, mm: the wire's
    /// exact contact with the helicoidal flanks ([`crate::wire_helix_term`]).
    pub helix_term: f64,
    /// The classical first-order term −(w/2)·cos β·cot β·tan² λ, mm, for comparison.
    pub helix_term_classical: f64,
    /// M the computed thread gives over the same wires in its axial section, mm.
    pub m_computed: f64,
    /// The computed thread's pitch diameter, mm.
    pub pitch_diameter_computed: f64,
    /// What the standard formula gives on a perfect profile (M − w(1 + 1/sin β) + P/(2 tan β)
    /// plus the helix term; 60° threads: M − 3w + 0.866025·P), mm, for comparison.
    pub pitch_diameter_formula: Option<f64>,
}

/// The part's state as measured.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MeasuredState {
    /// `over-wires`, `pitch-diameter` or `gauge`.
    pub method: &'static str,
    /// The pitch diameter, mm (`None` after a gauge: it is not known).
    pub pitch_diameter: Option<f64>,
    /// Its distance from the middle of the tolerance, µm (+ larger).
    pub off_middle_um: Option<f64>,
    /// Its distance outside the limits, µm (0 inside).
    pub deviation_um: Option<f64>,
    /// The wires' reading, for `over-wires`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub over_wires: Option<WireReading>,
    /// The gauge's result, for `gauge`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gauge: Option<GaugeResult>,
    /// What the measurement does not tell.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unknown: Option<String>,
}

/// A wear offset that does what the correction does, without editing the program.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct WearOffset {
    /// The change of the tool's X wear offset (on the diameter), program units.
    pub x: f64,
    /// The program's units.
    pub units: crate::gcode::ProgramUnits,
}

/// Where to re-enter an existing thread.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Pickup {
    /// The groove centre measured, mm from the program's Z0.
    pub measured_z: f64,
    /// Where the program puts a groove centre, mm.
    pub program_z: f64,
    /// How far the program would cut beside the existing groove, mm (−P/2, P/2].
    pub phase_error: f64,
    /// The Z shift of the threading start that puts the insert into the groove, mm.
    pub z_shift: f64,
    /// Or the change of the cycle's start angle, degrees (−180, 180]: the spindle's angle of the
    /// start mark moves the helix by lead/360 per degree, along the cut's direction.
    pub start_angle_deg: f64,
    /// The threading moves run towards −Z.
    pub towards_minus_z: bool,
}

/// What `correct` found.
#[derive(Clone, Debug)]
pub struct CorrectReport {
    /// The thread as the program (or plan) cuts it.
    pub verification: Verification,
    /// The part as measured.
    pub measured: Option<MeasuredState>,
    /// The pitch diameter is within its limits (a gauge's `ok` included).
    pub in_tolerance: bool,
    /// The change of the pitch diameter to make, mm (+ larger): to the middle of the tolerance.
    pub delta_pitch_diameter: Option<f64>,
    /// The plan's last tip diameter that makes it, mm.
    pub suggested_final_x: Option<f64>,
    /// The same in the program's words.
    pub correction: Option<Correction>,
    /// Or as a wear offset (Fanuc-family controls: the tool's X wear, diameter).
    pub wear_offset: Option<WearOffset>,
    /// The pick-up, when asked for.
    pub pickup: Option<Pickup>,
    /// What was assumed.
    pub notes: Vec<crate::ground::note::Note>,
}

impl CorrectReport {
    /// Pass when in tolerance (and for a pick-up alone).
    pub fn verdict(&self) -> Verdict {
        Verdict::of(self.measured.is_none() || self.in_tolerance)
    }
}

/// Turns a measurement into the correction: see the module's documentation.
///
/// ```
/// use threadcheck::{correct, CorrectSpec, InsertChoice, Measured, VerifySpec};
/// // A full-profile M10x1.5-6g plan; the part measures d2 = 9.010, 16 µm over 8.994.
/// let spec = CorrectSpec {
///     verify: VerifySpec { insert: InsertChoice::Full, ..VerifySpec::of("M10x1.5-6g")? },
///     measured: Some(Measured::PitchDiameter(9.010)),
///     pickup_z: None,
/// };
/// let r = correct(&spec)?;
/// assert!(!r.in_tolerance);
/// // To the middle, 8.928: 82 µm smaller, the final X 82 µm smaller too.
/// assert!((r.delta_pitch_diameter.unwrap() + 0.082).abs() < 1e-9);
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn correct(spec: &CorrectSpec) -> Result<CorrectReport, Error> {
    if spec.measured.is_none() && spec.pickup_z.is_none() {
        return Err(Error::Input(
            "correct needs what was measured: ‹measured_m› with ‹wire›, ‹measured_d2› or ‹gauge› (or ‹pickup_z›)"
                .into(),
        ));
    }
    let v = verify(&VerifySpec { picture: false, ..spec.verify.clone() })?;
    if v.limits.gauge_plane.is_some() {
        return Err(Error::Input(
            "correct takes parallel threads: a taper thread is gauged by its stand-off in turns, which verify reports"
                .into(),
        ));
    }
    let t = v.designation.thread;
    let lim = v.limits.pitch_diameter;
    let (Some(min), Some(max)) = (lim.min, lim.max) else {
        return Err(Error::Input("the class has no two-sided pitch-diameter tolerance".into()));
    };
    let mid = 0.5 * (min + max);
    let res = v.limits.resolution;
    let mut notes = Vec::new();
    let d2_model = v.measurement.pitch_diameter;
    let measured = match spec.measured {
        None => None,
        Some(Measured::PitchDiameter(d2)) => {
            positive(d2, "measured pitch diameter")?;
            Some(known("pitch-diameter", d2, mid, lim, res, None))
        }
        Some(Measured::OverWires { m, wire }) => {
            positive(m, "measurement over wires")?;
            positive(wire, "wire diameter")?;
            if v.kind != ThreadKind::External {
                return Err(Error::Input(
                    "‹measured_m› is a measurement over wires of an external thread: measure a nut's pitch diameter (‹measured_d2›) or gauge it".into(),
                ));
            }
            let m_computed = over_wires_of(&v, wire)?;
            // The wires ride higher across the helix than in the axial section: the exact contact
            // with the helicoidal flanks, the classical first-order term beside it.
            // The term is taken at the part's own d2, the one the reading gives (issue 64; it was
            // taken at the basic d2): a fixed point, d2 = d2_model + M + helix(d2) − M_computed,
            // which settles in a few steps (the term changes by well under a nanometre a micrometre).
            let half = t.half_angle();
            let term = |d2: f64| crate::geometry::wire::wire_helix_term(d2, t.pitch, t.lead(), half, wire);
            let mut at = d2_model + (m - m_computed);
            for _ in 0..8 {
                let next = d2_model + (m + term(at) - m_computed);
                let settled = (next - at).abs() < 1e-12;
                at = next;
                if settled {
                    break;
                }
            }
            let helix = term(at);
            let classical = crate::geometry::wire::classical_wire_helix_term(at, t.lead(), half, wire);
            notes.push(crate::ground::note::Note::from(format!(
                "helix term {:+.4} mm added to M: the wire's exact contact with the helicoidal flanks, settled at its lowest inclination; the classical −(w/2)·cos β·cot β·tan² λ gives {:+.4} mm ({:+.2} µm apart)",
                helix,
                classical,
                (classical - helix) * 1e3
            )));
            // The part's groove is the computed one moved radially: M and d2 move together.
            let d2 = d2_model + (m + helix - m_computed);
            let formula = Some(m - wire * (1.0 + 1.0 / half.sin()) + 0.5 * t.pitch / half.tan() + helix);
            notes.push(crate::ground::note::Note::from(
                "the wires rest on the as-cut flanks the program leaves; the part is taken to differ from them by its depth only (an X offset, insert wear)",
            ));
            let reading = WireReading {
                m,
                wire,
                helix_term: helix,
                helix_term_classical: classical,
                m_computed,
                pitch_diameter_computed: d2_model,
                pitch_diameter_formula: formula,
            };
            Some(known("over-wires", d2, mid, lim, res, Some(reading)))
        }
        Some(Measured::Gauge(g)) => Some(gauged(g, v.kind)),
    };
    // A size beyond one pitch of the tolerance's middle is not a measurement of this thread
    // (a typing slip, another thread, another unit): 1e308 once wrote X-inf into the program.
    if let Some(d2) = measured.as_ref().and_then(|s| s.pitch_diameter) {
        if !((d2 - mid).abs() <= t.pitch) {
            let what = match spec.measured {
                Some(Measured::OverWires { m, .. }) => format!(
                    "the measurement over wires M {} mm gives a pitch diameter of {} mm, which is",
                    crate::ground::fmt::fmt_shown(m),
                    crate::ground::fmt::fmt_shown(d2)
                ),
                _ => format!("the measured pitch diameter {} mm is", crate::ground::fmt::fmt_shown(d2)),
            };
            return Err(Error::Input(format!(
                "{what} more than one pitch ({} mm) from the middle of {}'s pitch-diameter tolerance ({} mm): not a measurement of this thread (check the value and its unit)",
                crate::ground::fmt::fmt_num(t.pitch),
                v.designation.text,
                crate::ground::fmt::fmt_num(mid)
            )));
        }
    }
    // The change to make: to the middle of the tolerance; after a gauge, from the limit it
    // failed (the least the part can be off).
    let (in_tol, delta) = match &measured {
        None => (true, None),
        Some(s) => match (s.gauge, s.pitch_diameter) {
            (Some(GaugeResult::Ok), _) => (true, None),
            (Some(g), _) => {
                let too_big = matches!(
                    (g, v.kind),
                    (GaugeResult::GoFails, ThreadKind::External)
                        | (GaugeResult::NogoEnters, ThreadKind::Internal)
                );
                notes.push(crate::ground::note::Note::from(format!(
                    "assumed: the part at the limit its gauge failed ({} mm), the least it can be off; the correction brings such a part to the middle of the tolerance",
                    crate::ground::fmt::fmt_num(if too_big { max } else { min })
                )));
                (false, Some(if too_big { mid - max } else { mid - min }))
            }
            (None, Some(d2)) => {
                let inside = res.round(d2) >= min - 1e-9 && res.round(d2) <= max + 1e-9;
                (inside, (!inside).then_some(mid - d2))
            }
            (None, None) => (true, None),
        },
    };
    let suggested_final_x = delta.map(|d| v.final_x + d);
    let correction = delta.and_then(|d| v.correction_for(d));
    // --fix never writes a number the control could not take.
    if let Some(c) = correction.as_ref().filter(|c| !(c.value.abs() <= crate::ground::bounds::MAX_COORDINATE))
    {
        return Err(Error::Input(format!(
            "the correction would write {}{} at line {}:{}, beyond the {} mm a coordinate may reach",
            c.word,
            crate::ground::fmt::fmt_shown(c.value),
            c.line,
            c.column,
            crate::ground::fmt::fmt_shown(crate::ground::bounds::MAX_COORDINATE)
        )));
    }
    let wear_offset = match (&v.program, delta, &correction) {
        (Some(p), Some(d), Some(c)) if wear_offset_in_x(p.dialect) => {
            Some(WearOffset { x: round_to(d / c.units.mm(), c.units.least_increment()), units: c.units })
        }
        _ => None,
    };
    if v.program.is_some() && delta.is_some() && correction.is_none() {
        notes.push(crate::ground::note::Note::from(
            "the program gives no word that sets the final depth in a form threadcheck can change: move the final X by the change",
        ));
    }
    let pickup = spec.pickup_z.map(|z| pickup(&v, z)).transpose()?;
    Ok(CorrectReport {
        verification: v,
        measured,
        in_tolerance: in_tol,
        delta_pitch_diameter: delta,
        suggested_final_x,
        correction,
        wear_offset,
        pickup,
        notes,
    })
}

/// Whether the control's tool wear offset is an X on the diameter that the report can name:
/// the Fanuc family's (Fanuc, Haas: the X wear of the tool's offset, diameter in diameter mode).
fn wear_offset_in_x(d: crate::gcode::Dialect) -> bool {
    // Mitsubishi and Mazak are read as the Fanuc model, their wear offsets with it. Sinumerik's
    // wear is a length per tool edge whose diameter or radius meaning depends on machine data;
    // LinuxCNC's, Dyna's, Okuma OSP's and Heidenhain's wear offsets are not modelled.
    d.facts().fanuc_codes
}

fn positive(v: f64, what: &str) -> Result<(), Error> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(Error::Input(format!("{what} {} mm must be a positive length", crate::ground::fmt::fmt_shown(v))))
    }
}

fn round_to(v: f64, step: f64) -> f64 {
    (v / step).round() * step
}

/// A measured pitch diameter's state.
fn known(
    method: &'static str,
    d2: f64,
    mid: f64,
    lim: crate::standards::tolerance::Limit,
    res: crate::standards::tolerance::Resolution,
    over_wires: Option<WireReading>,
) -> MeasuredState {
    // Inside or out at the standard's resolution (a limit exactly met passes); outside, the true
    // distance to the limit, as verify reports it.
    let dev = if lim.deviation(res.round(d2)) == 0.0 { 0.0 } else { lim.deviation(d2) };
    MeasuredState {
        method,
        pitch_diameter: Some(d2),
        off_middle_um: Some((d2 - mid) * 1e3),
        deviation_um: Some(dev * 1e3),
        over_wires,
        gauge: None,
        unknown: None,
    }
}

/// A gauge's state: what it says and what it leaves unknown.
fn gauged(g: GaugeResult, kind: ThreadKind) -> MeasuredState {
    let side = match (g, kind) {
        (GaugeResult::Ok, _) => {
            "where in the tolerance the pitch diameter lies (measure it over wires to aim at the middle)"
        }
        (GaugeResult::GoFails, ThreadKind::External) | (GaugeResult::NogoEnters, ThreadKind::Internal) => {
            "how far the pitch diameter lies over its largest limit, and whether lead or flank errors (which a GO gauge also feels) take part: measure it over wires to know"
        }
        (GaugeResult::GoFails, ThreadKind::Internal) | (GaugeResult::NogoEnters, ThreadKind::External) => {
            "how far the pitch diameter lies under its smallest limit: measure it to know"
        }
    };
    MeasuredState {
        method: "gauge",
        pitch_diameter: None,
        off_middle_um: None,
        deviation_um: None,
        over_wires: None,
        gauge: Some(g),
        unknown: Some(side.to_string()),
    }
}

/// M over wires of the computed thread.
fn over_wires_of(v: &Verification, wire: f64) -> Result<f64, Error> {
    let t = v.designation.thread;
    let ms = crate::geometry::measure::MeasureSetup {
        thread: &t,
        kind: v.kind,
        mmc_pitch_diameter: None,
        mmc_major_diameter: None,
        extras: false,
    };
    crate::geometry::measure::over_wires(&ms, &v.section.profile(), v.z_ref, wire)
}

/// The pick-up: the program's groove against the measured one.
fn pickup(v: &Verification, measured_z: f64) -> Result<Pickup, Error> {
    if !(measured_z.abs() <= crate::ground::bounds::MAX_COORDINATE) {
        return Err(Error::Input(format!(
            "‹pickup_z› {}: a groove's position is a finite number within {} mm of the program's Z0",
            crate::ground::fmt::fmt_shown(measured_z),
            crate::ground::fmt::fmt_shown(crate::ground::bounds::MAX_COORDINATE)
        )));
    }
    let t = v.designation.thread;
    let (p, lead) = (t.pitch, t.lead());
    let program_z = v.measurement.groove_center;
    // The grooves of every start lie a pitch apart: the nearest one counts.
    let mut e = (measured_z - program_z).rem_euclid(p);
    if e > 0.5 * p {
        e -= p;
    }
    let last: &Pass = v.passes.last().ok_or_else(|| Error::Input("no pass".into()))?;
    let towards_minus_z = last.z_end < last.z_start;
    let turn = 360.0 * e / lead;
    let start_angle_deg = if towards_minus_z { turn } else { -turn };
    Ok(Pickup { measured_z, program_z, phase_error: e, z_shift: e, start_angle_deg, towards_minus_z })
}
