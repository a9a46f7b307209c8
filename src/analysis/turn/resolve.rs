//! A spec resolved against the standards: the designation, its side and limits, the insert,
//! the blank and the pass plan's defaults, everything but the passes.

use super::spec::*;
use crate::analysis::tools::InsertChoice;
use crate::geometry::insert::{Insert, InsertKind};
use crate::ground::bounds::MAX_DATA_FILE_BYTES;
use crate::standards::tolerance::{limits_for, ThreadLimits};
use crate::standards::{Designation, ProfileKind, ThreadKind};
use crate::toolpath::passes::{Infeed, InfeedChoice, PlanSpec};
use crate::{BasicThread, Error};

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

pub(super) fn resolve_kind(des: &Designation, internal: bool) -> Result<ThreadKind, Error> {
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

pub(super) fn build_insert(
    choice: &InsertChoice,
    t: &BasicThread,
    kind: ThreadKind,
    tol: f64,
) -> Result<Insert, Error> {
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
pub(super) fn width_at(outline: &[crate::Point], y: f64) -> f64 {
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
pub(super) fn initial_final_x(t: &BasicThread, kind: ThreadKind, ins: &Insert, target: f64) -> f64 {
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
    pub(super) spec: VerifySpec,
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
    let des = spec.designation.clone().ok_or_else(crate::standards::designation::none_given)?;
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
