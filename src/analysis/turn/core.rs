//! The core of `verify`: the passes swept, the groove measured and judged against the class;
//! and the re-cut a Monte Carlo calls per sampled part.

use super::passes::*;
use super::resolve::*;
use super::spec::*;
use crate::analysis::check::{checks, verdict};
use crate::analysis::taper::{cone_of, taper_of, true_flank_angles, Taper, TAPER_FACE_NOTE};
use crate::geometry::boolean::UnionStrategy;
use crate::geometry::insert::Insert;
use crate::geometry::measure::{measure, MeasureSetup, Measurement};
use crate::geometry::sweep::{pass_metrics, sweep, Section, SweepSetup, Window};
use crate::standards::tolerance::ThreadLimits;
use crate::standards::ThreadKind;
use crate::toolpath::passes::Pass;
use crate::Error;

/// The passes of one program operation, with what to say about them.
pub(super) struct Given {
    pub(super) passes: Vec<Pass>,
    pub(super) depth_word: Option<crate::gcode::DepthWord>,
    pub(super) units: crate::gcode::ProgramUnits,
    pub(super) lead: Option<crate::analysis::turn::lead::LeadDeviation>,
    pub(super) label: ProgramLabel,
    pub(super) notes: Vec<crate::ground::note::Note>,
}

/// What measuring a cut needs: the sweep's setup, the measurement's, and a taper thread's cone
/// (measured along it: the section sheared so the cone's pitch line runs level).
pub(super) struct Measurer<'a> {
    pub(super) r: &'a Resolved,
    pub(super) t: &'a crate::standards::BasicThread,
    pub(super) setup: SweepSetup<'a>,
    pub(super) ms: MeasureSetup<'a>,
    pub(super) taper: Option<Taper>,
    pub(super) mid: Option<f64>,
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
pub(super) fn gauge_cone(
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
pub(super) fn judge(
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
pub(super) fn verify_core(r: &Resolved, given: Option<Given>) -> Result<Verification, Error> {
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
pub(super) fn picture_of(v: &Verification) -> Result<crate::analysis::picture::Picture, Error> {
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
pub(super) fn measured_notes(
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
