//! Taper threads (ISO 7-1, ASME B1.20.1) as every process measures them: where the cone is
//! measured, the gauge plane its pitch diameter reaches, and the flank angles of a section
//! sheared level along the taper. Shared by the turned and the thread-milled checks.

use crate::standards::tolerance::ThreadLimits;
use crate::standards::ThreadKind;

/// A taper thread's cone where it is measured: its gauge plane, the measuring height (the gauge
/// plane on an external thread, four pitches in on an internal one) and the cone's radial slope.
pub(crate) type Taper = (crate::standards::tolerance::GaugePlane, f64, f64);

/// A taper thread's cone as its gauge finds it: the pitch diameter measured at `z_ref` (the face
/// at Z0, the thread going −Z) carried along the basic taper to the basic gauge diameter, its
/// distance from the gauge plane's in turns of `pitch`; `measured_taper` the diameter's change per
/// mm of depth the toolpath cuts (growing on a bolt, narrowing in a nut).
pub(crate) fn cone_of(
    gp: crate::standards::tolerance::GaugePlane,
    kind: ThreadKind,
    z_ref: f64,
    pitch_diameter: f64,
    measured_taper: f64,
    pitch: f64,
) -> crate::analysis::check::Cone {
    let s_ref = -z_ref;
    let s_gp = match kind {
        ThreadKind::External => s_ref + (gp.pitch_diameter - pitch_diameter) / gp.taper,
        ThreadKind::Internal => s_ref + (pitch_diameter - gp.pitch_diameter) / gp.taper,
    };
    crate::analysis::check::Cone {
        turns: (s_gp - gp.distance) / pitch,
        tolerance_turns: gp.tolerance_turns,
        taper: measured_taper,
        nominal_taper: gp.taper,
    }
}

/// Where a taper thread's cone is measured (the gauge plane on an external thread, four pitches
/// in on an internal one, the face at Z0) and its radial slope along Z: the section there is
/// sheared level by it.
pub(crate) fn taper_of(limits: &ThreadLimits, kind: ThreadKind, pitch: f64) -> Option<Taper> {
    limits.gauge_plane.map(|gp| {
        let (z_meas, slope_r) = match kind {
            ThreadKind::External => (-gp.distance, -0.5 * gp.taper),
            ThreadKind::Internal => (-4.0 * pitch, 0.5 * gp.taper),
        };
        (gp, z_meas, slope_r)
    })
}

/// What a taper thread's measurement assumes of the part, said in its notes.
pub(crate) const TAPER_FACE_NOTE: &str =
    "taper thread: the face (the small end of an external thread, the opening of a fitting) is taken at Z0";

/// Flank half-angles measured on a section sheared by `slope_r` (radius per mm of z) turned
/// back into the true axial section: a flank with dz/dr' = ±t in the sheared section has
/// dz/dr = ±t / (1 ± s·t) in the true one. A bolt's low-z flank falls towards its root as z
/// grows (−t), a nut's rises.
pub(crate) fn true_flank_angles(sheared: [f64; 2], slope_r: f64, kind: ThreadKind) -> [f64; 2] {
    let sign = match kind {
        ThreadKind::External => [-1.0, 1.0],
        ThreadKind::Internal => [1.0, -1.0],
    };
    let mut out = [0.0; 2];
    for k in 0..2 {
        let d = sign[k] * sheared[k].to_radians().tan();
        out[k] = (d / (1.0 + slope_r * d)).abs().atan().to_degrees();
    }
    out
}
