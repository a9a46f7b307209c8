//! Process checks of a program's threading operation: what a machinist checks besides the
//! profile. Constant spindle speed (G97, never G96, at a threading cycle), the spindle speed
//! and the feed within a machine's limits, the machining time, and the helix angle with the
//! insert inclination and flank clearance it asks for.
//!
//! A machine profile (`--machine FILE.toml`, or the built-in `training-lathe`):
//!
//! ```toml
//! name = "my lathe"
//! max_rpm = 3000
//! max_feed_mm_min = 5000
//! rapid_mm_min = 10000
//! # optional: the fastest spindle speed by pitch, pitch up to (mm) and rpm
//! rpm_per_pitch = [[0.5, 950], [1.0, 500]]
//! # optional: the Z axis's servo time constant, s (the run-in check; default 0.033)
//! servo_time_constant_s = 0.02
//! # optional: the Z axis's acceleration, mm/s² (the run-in check: V²/(2a) when longer)
//! z_acceleration_mm_s2 = 2000
//! # optional: the taps' holder, "rigid" (the feed is held exact) or "floating" (a
//! # tension-compression holder: an under-feed up to 5 % is taken up, said)
//! tap_holder = "floating"
//! ```

use crate::analysis::check::{Check, CheckKind};
use crate::gcode::Operation;
use crate::Error;
use serde::Serialize;

/// The rapid traverse rate assumed where a machine profile gives none, mm/min (stated in the
/// output wherever it is used).
pub const ASSUMED_RAPID_MM_MIN: f64 = 5000.0;

/// A machine's limits for threading. A profile file names only what it limits: `name` defaults
/// to the file's name and `rapid_mm_min` to 5000 mm/min, said in the name.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MachineProfile {
    /// Its name, for the report.
    pub name: String,
    /// Fastest spindle speed, rpm.
    #[serde(default)]
    pub max_rpm: Option<f64>,
    /// Fastest feed the axes follow, mm/min.
    #[serde(default)]
    pub max_feed_mm_min: Option<f64>,
    /// Rapid traverse rate, mm/min, for the machining time.
    pub rapid_mm_min: f64,
    /// What kind of machine it is (`type = "lathe"`, `"mill"` or `"mill-turn"`): how its
    /// programs are read, unless ‹machine_type› says otherwise.
    pub machine_type: Option<crate::gcode::MachineType>,
    /// Fastest spindle speed by pitch: (pitch up to, mm; rpm), ascending.
    #[serde(default)]
    pub rpm_per_pitch: Vec<(f64, f64)>,
    /// The Z axis's servo time constant, seconds: how far it needs to reach a threading feed
    /// (`None`: the run-in check's named default).
    #[serde(default)]
    pub servo_time_constant_s: Option<f64>,
    /// The spindle's torque, N·m, at the speeds it taps at (a spindle's rated S1 torque below
    /// its base speed): a tap's torque is held against it (`None`: not checked, said).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spindle_torque_nm: Option<f64>,
    /// The spindle's power, kW: a tap's power at its S is held against it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spindle_power_kw: Option<f64>,
    /// The Z axis's acceleration, mm/s²: the run-in check takes the distance it needs to reach
    /// the threading feed, V²/(2a), where longer than the servo's (`None`: not used, said).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub z_acceleration_mm_s2: Option<f64>,
    /// The taps' holder (`None`: rigid assumed where it changes a result, said).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tap_holder: Option<TapHolder>,
}

/// How a tap is held.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum TapHolder {
    /// A rigid holder (a collet or a synchro holder): the feed must be the lead exactly.
    Rigid,
    /// A floating (tension-compression) holder: its axial float takes up a small under-feed.
    Floating,
}

impl MachineProfile {
    /// The training lathe of the 1994 thesis (its Table 2.2: the fastest spindle speed by
    /// pitch, 0.02 to 4.99 mm). The thesis gives no rapid rate and no feed limit: 5000 mm/min
    /// rapid is assumed and said so.
    pub fn training_lathe() -> MachineProfile {
        MachineProfile {
            name: "training-lathe (thesis Table 2.2; rapid 5000 mm/min assumed)".into(),
            max_rpm: Some(950.0),
            max_feed_mm_min: None,
            rapid_mm_min: 5000.0,
            machine_type: Some(crate::gcode::MachineType::Lathe),
            servo_time_constant_s: None,
            spindle_torque_nm: None,
            spindle_power_kw: None,
            z_acceleration_mm_s2: None,
            tap_holder: None,
            rpm_per_pitch: vec![
                (0.5, 950.0),
                (1.0, 500.0),
                (1.5, 320.0),
                (2.0, 250.0),
                (3.0, 170.0),
                (4.0, 130.0),
                (4.99, 100.0),
            ],
        }
    }

    /// Reads `training-lathe` or a TOML file.
    pub fn read(arg: &str) -> Result<MachineProfile, Error> {
        if arg == "training-lathe" {
            return Ok(MachineProfile::training_lathe());
        }
        let text = crate::ground::input::read_text_bounded(
            std::path::Path::new(arg),
            crate::ground::bounds::MAX_DATA_FILE_BYTES,
            "a machine profile",
        )?;
        MachineProfile::from_toml(&text, arg)
    }

    /// A machine profile from its TOML text; `source` names it in messages.
    ///
    /// ```
    /// let m = threadcheck::MachineProfile::from_toml(
    ///     "name = \"lathe\"\nrapid_mm_min = 8000\nmax_rpm = 3000",
    ///     "lathe.toml",
    /// )?;
    /// assert_eq!(m.max_rpm, Some(3000.0));
    /// # Ok::<(), threadcheck::Error>(())
    /// ```
    pub fn from_toml(text: &str, source: &str) -> Result<MachineProfile, Error> {
        /// The file as written: every field optional.
        #[derive(serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        struct File {
            name: Option<String>,
            max_rpm: Option<f64>,
            max_feed_mm_min: Option<f64>,
            rapid_mm_min: Option<f64>,
            #[serde(default)]
            rpm_per_pitch: Vec<(f64, f64)>,
            #[serde(rename = "type")]
            machine_type: Option<crate::gcode::MachineType>,
            servo_time_constant_s: Option<f64>,
            spindle_torque_nm: Option<f64>,
            spindle_power_kw: Option<f64>,
            z_acceleration_mm_s2: Option<f64>,
            tap_holder: Option<TapHolder>,
        }
        let arg = source;
        let f: File = toml::from_str(text).map_err(|e| crate::ground::error::toml_error(&e, text, arg))?;
        let stem = std::path::Path::new(source)
            .file_stem()
            .map_or(source.to_string(), |s| s.to_string_lossy().into_owned());
        // Shown in every report: its control characters escaped (a newline forged a verdict line).
        let mut name = crate::ground::fmt::shown_text(&f.name.unwrap_or(stem));
        if f.rapid_mm_min.is_none() {
            name.push_str(&format!(" (rapid {ASSUMED_RAPID_MM_MIN} mm/min assumed)"));
        }
        let m = MachineProfile {
            name,
            max_rpm: f.max_rpm,
            max_feed_mm_min: f.max_feed_mm_min,
            rapid_mm_min: f.rapid_mm_min.unwrap_or(ASSUMED_RAPID_MM_MIN),
            rpm_per_pitch: f.rpm_per_pitch,
            machine_type: f.machine_type,
            servo_time_constant_s: f.servo_time_constant_s,
            spindle_torque_nm: f.spindle_torque_nm,
            spindle_power_kw: f.spindle_power_kw,
            z_acceleration_mm_s2: f.z_acceleration_mm_s2,
            tap_holder: f.tap_holder,
        };
        let positive = |v: f64| v > 0.0 && v.is_finite();
        if !positive(m.rapid_mm_min)
            || m.max_rpm.is_some_and(|r| !positive(r))
            || m.max_feed_mm_min.is_some_and(|f| !positive(f))
            || m.servo_time_constant_s.is_some_and(|t| !positive(t))
            || m.spindle_torque_nm.is_some_and(|t| !positive(t))
            || m.spindle_power_kw.is_some_and(|p| !positive(p))
            || m.z_acceleration_mm_s2.is_some_and(|a| !positive(a))
            || m.rpm_per_pitch.iter().any(|(up, rpm)| !positive(*up) || !positive(*rpm))
        {
            return Err(Error::File {
                file: arg.to_string(),
                message: "rates, speeds and pitches must be finite and greater than zero".into(),
            });
        }
        Ok(m)
    }

    /// The fastest spindle speed for a pitch, rpm, if the machine sets one.
    pub fn max_rpm_for(&self, pitch: f64) -> Option<f64> {
        let by_pitch = self.rpm_per_pitch.iter().find(|(up, _)| pitch <= *up + 1e-9).map(|x| x.1);
        match (by_pitch, self.max_rpm) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        }
    }
}

/// Time to cut an operation, seconds.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MachiningTime {
    /// Synchronised cutting: each pass's axial length at the lead per revolution.
    pub cutting: f64,
    /// Rapid moves: the retract, the return stroke and the infeed of each pass.
    pub rapid: f64,
    /// The two together.
    pub total: f64,
    /// Each pass's cutting plus rapid time.
    pub per_pass: Vec<f64>,
}

/// What the process checks found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ProcessReport {
    /// The machine profile used, if any.
    pub machine: Option<String>,
    /// Spindle speed at the cycle, rpm (under G97).
    pub spindle_rpm: Option<f64>,
    /// Helix angle at the pitch diameter, degrees: atan(lead / (π·d2)).
    pub helix_angle: f64,
    /// The insert inclination the helix asks for (the shim angle), degrees: the helix angle.
    pub insert_inclination: f64,
    /// The insert's side clearance less the helix angle on the leading flank, degrees, when the
    /// clearance angle is known.
    pub leading_flank_clearance: Option<f64>,
    /// The machining time, when the spindle speed is known.
    pub machining_time: Option<MachiningTime>,
}

fn process_check(
    feature: crate::analysis::check::CheckFeature,
    value: f64,
    max: Option<f64>,
    ok: bool,
    note: String,
) -> Check {
    Check {
        feature,
        kind: CheckKind::Process,
        value,
        min: None,
        max,
        ok,
        deviation_um: 0.0,
        note: Some(note),
        unverified: None,
    }
}

/// The helix angle at pitch diameter `d2` for `lead`, degrees.
pub fn helix_angle(lead: f64, d2: f64) -> f64 {
    (lead / (std::f64::consts::PI * d2)).atan().to_degrees()
}

/// The process checks of one program operation: constant spindle speed; with a machine, the
/// spindle speed (overall and for the pitch) and the feed S·lead; the machining time; the helix
/// angle and, with a clearance angle, the leading flank's clearance.
pub fn process_checks(
    op: &Operation,
    pitch: f64,
    d2: f64,
    machine: Option<&MachineProfile>,
    clearance_angle: Option<f64>,
) -> (Vec<Check>, ProcessReport) {
    let lead = op.lead();
    let mut checks = vec![process_check(
        crate::analysis::check::CheckFeature::ConstantSpindleSpeed,
        if op.spindle.constant_surface_speed { 0.0 } else { 1.0 },
        None,
        !op.spindle.constant_surface_speed,
        if op.spindle.constant_surface_speed {
            format!("{} runs under G96 (constant surface speed): the spindle speed changes with X and the passes leave the helix; program G97", op.cycle)
        } else {
            "G97 (constant spindle speed)".into()
        },
    )];
    let rpm = (!op.spindle.constant_surface_speed).then_some(op.spindle.s).flatten();
    if let (Some(m), Some(s)) = (machine, rpm) {
        if let Some(max) = m.max_rpm_for(pitch) {
            checks.push(process_check(
                crate::analysis::check::CheckFeature::SpindleSpeed,
                s,
                Some(max),
                s <= max + 1e-9,
                format!(
                    "S{s} rpm against {max} rpm for P {} mm on {}",
                    crate::ground::fmt::fmt_num(pitch),
                    m.name
                ),
            ));
        }
        if let Some(fmax) = m.max_feed_mm_min {
            let f = s * lead;
            checks.push(process_check(
                crate::analysis::check::CheckFeature::Feed,
                f,
                Some(fmax),
                f <= fmax + 1e-9,
                format!("S·lead = {} mm/min against {fmax} mm/min", crate::ground::fmt::fmt_num(f)),
            ));
        }
    }
    let machining_time = rpm.filter(|s| *s > 0.0).map(|s| {
        let rapid = machine.map_or(ASSUMED_RAPID_MM_MIN, |m| m.rapid_mm_min);
        let mut cutting = 0.0;
        let mut rapid_t = 0.0;
        let mut per_pass = Vec::with_capacity(op.passes.len());
        for p in &op.passes {
            let length = (p.z_end - p.z_start).abs();
            let cut = length / (s * p.lead) * 60.0;
            // Out to the start diameter, back along Z, in again.
            let lift = op.start.map_or(0.0, |(x0, _)| 0.5 * (x0 - p.x_end).abs());
            let back = if (p.z_phase - p.z_start).abs() < 1e-12 {
                (length + 2.0 * lift) / rapid * 60.0
            } else {
                0.0
            };
            cutting += cut;
            rapid_t += back;
            per_pass.push(cut + back);
        }
        MachiningTime { cutting, rapid: rapid_t, total: cutting + rapid_t, per_pass }
    });
    if let Some(c) = run_out(op, pitch) {
        checks.push(c);
    }
    let helix = helix_angle(lead, d2);
    let leading = clearance_angle.map(|c| c - helix);
    if let Some(l) = leading {
        let mut c = process_check(
            crate::analysis::check::CheckFeature::FlankClearance,
            l,
            None,
            l > 0.0,
            if l > 0.0 {
                format!("leading flank clearance {l:.2}° (insert clearance less the helix angle {helix:.2}°)")
            } else {
                format!("the helix angle {helix:.2}° eats the insert's clearance: the leading flank rubs; incline the insert by {helix:.2}° (a shim)")
            },
        );
        // The leading flank needs some clearance: more than 0°.
        c.min = Some(0.0);
        checks.push(c);
    }
    let report = ProcessReport {
        machine: machine.map(|m| m.name.clone()),
        spindle_rpm: rpm,
        helix_angle: helix,
        insert_inclination: helix,
        leading_flank_clearance: leading,
        machining_time,
    };
    (checks, report)
}

/// The run-out against the turned contour, where the program turned one before the thread:
/// within half a pitch beyond the last pass's end (the insert's own half width) the contour must
/// not stand above the diameter turned for the thread (external; below it, internal): a
/// shoulder there, with no undercut or chamfer to run out into, meets the insert. `None` when
/// the program shows no contour there.
fn run_out(op: &Operation, pitch: f64) -> Option<Check> {
    let last = op.passes.iter().rev().find(|p| (p.z_phase - p.z_start).abs() < 1e-12)?;
    let dir = last.feed_direction();
    // Distances from the axis throughout: a tool working at negative X (a Swiss or rear tool
    // post) is measured by them as one at positive X (a negative turned X compared with a
    // positive thread X passed a shoulder in the run-out).
    let external = op.passes.first().is_some_and(|f| last.x_end.abs() <= f.x_end.abs());
    // The material the contour leaves at a Z: a later or deeper cut replaces an earlier one, so
    // it is the least distance from the axis that a move along Z there reached (a bore's: the
    // greatest); a box cut's cylinder under a profile turned smaller is gone. Moves more than a
    // pitch (in diameter) beyond the thread's root are the part's other side (a bore or a drill's
    // path in a shaft, the outside of a nut), not the surface the thread is cut into; an
    // undercut (DIN 76: about 0.4 P below d3, 0.3 P above D) lies within it.
    let xs = op.passes.iter().flat_map(|p| [p.x_start.abs(), p.x_end.abs()]);
    let root = if external { xs.fold(f64::INFINITY, f64::min) } else { xs.fold(0.0, f64::max) };
    let along: Vec<([f64; 2], [f64; 2])> = op
        .contour
        .iter()
        .map(|t| ([t.from[0].abs(), t.from[1]], [t.to[0].abs(), t.to[1]]))
        .filter(|(a, b)| (b[1] - a[1]).abs() > 1e-12)
        .filter(
            |(a, b)| if external { a[0].min(b[0]) >= root - pitch } else { a[0].max(b[0]) <= root + pitch },
        )
        .collect();
    let material = |z: f64| -> Option<f64> {
        let mut m: Option<f64> = None;
        for ([x0, z0], [x1, z1]) in &along {
            if z < z0.min(*z1) - 1e-9 || z > z0.max(*z1) + 1e-9 {
                continue;
            }
            let x = x0 + (x1 - x0) * ((z - z0) / (z1 - z0)).clamp(0.0, 1.0);
            if m.is_none_or(|w| if external { x < w } else { x > w }) {
                m = Some(x);
            }
        }
        m
    };
    // Its extreme over [lo, hi] (external the largest, internal the smallest), looked at at
    // every move's end there and halfway between.
    let extreme = |lo: f64, hi: f64| -> Option<(f64, f64)> {
        let mut zs: Vec<f64> = vec![lo, hi];
        zs.extend(along.iter().flat_map(|(a, b)| [a[1], b[1]]).filter(|z| (lo..=hi).contains(z)));
        zs.sort_by(f64::total_cmp);
        zs.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
        let mids: Vec<f64> = zs.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect();
        let mut worst: Option<(f64, f64)> = None;
        for z in zs.into_iter().chain(mids) {
            if let Some(x) = material(z) {
                if worst.is_none_or(|(_, w)| if external { x > w } else { x < w }) {
                    worst = Some((z, x));
                }
            }
        }
        worst
    };
    let (t0, t1) = (last.z_start.min(last.z_end), last.z_start.max(last.z_end));
    // The diameter turned for the thread: its middle half (clear of chamfers at either end).
    let q = 0.25 * (t1 - t0);
    let (_, turned) = extreme(t0 + q, t1 - q)?;
    let (a, b) = (last.z_end, last.z_end + dir * 0.5 * pitch);
    let (z, x) = extreme(a.min(b), a.max(b))?;
    let clear = if external { x <= turned + 1e-3 } else { x >= turned - 1e-3 };
    Some(process_check(
        crate::analysis::check::CheckFeature::RunOut,
        x,
        Some(turned),
        clear,
        if clear {
            format!("the last pass runs out at Z{:.3} over turned X{x:.3}, no higher than the thread's X{turned:.3}", last.z_end)
        } else {
            format!(
                "the last pass ends at Z{:.3}, but the turned contour stands at X{x:.3} at Z{z:.3}, above the thread's X{turned:.3}: no undercut or chamfer to run out into, the insert meets the shoulder",
                last.z_end
            )
        },
    ))
}
