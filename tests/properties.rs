//! Issue 8: property tests on the geometry (the sweep's own properties are in sweep.rs).

use proptest::prelude::*;
use threadcheck::reference_groove;
use threadcheck::Insert;
use threadcheck::UnionStrategy;
use threadcheck::{measure, MeasureSetup};
use threadcheck::{sweep, Section, SweepSetup, Window};
use threadcheck::{BasicThread, ThreadKind};
use threadcheck::{Infeed, Pass, PlanSpec};

fn metric(d: f64, p: f64) -> BasicThread {
    BasicThread::metric(d, p)
}

fn plan(
    kind: ThreadKind,
    p: f64,
    surface: f64,
    final_x: f64,
    n: usize,
    angle: f64,
    z_start: f64,
) -> Vec<Pass> {
    PlanSpec {
        infeed: Infeed::Flank { angle },
        z_start,
        length: 12.0 * p,
        ..PlanSpec::new(kind, p, surface, final_x, n)
    }
    .generate()
    .unwrap()
}

fn section(kind: ThreadKind, ins: &Insert, blank: f64, p: f64, passes: &[Pass], z: f64) -> Section {
    let setup = SweepSetup { kind, insert: ins, blank_diameter: blank, pitch: p };
    sweep(&setup, passes, Window::around(z, p, 4.0), UnionStrategy::BalancedTree).unwrap().section
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    /// Shifting every pass by one lead shifts the cut by one lead: every measured value is the
    /// same (to the backend's nanometre snapping) and the groove centre moves by exactly a lead.
    #[test]
    fn measurement_is_invariant_under_a_shift_by_one_lead(
        pi in 0usize..4, r in 0.0f64..0.08, n in 1usize..10, angle in 0.0f64..30.0, phase in -0.5f64..0.5,
    ) {
        let (d, p) = [(6.0, 1.0), (10.0, 1.5), (20.0, 2.5), (36.0, 4.0)][pi];
        let t = metric(d, p);
        let ins = Insert::partial_for(&t, r, 1e-3).unwrap();
        let final_x = d - 2.0 * (0.875 * t.fundamental_height() - r);
        let a = plan(ThreadKind::External, p, d - 0.1, final_x, n, angle, 6.0 * p + phase);
        let b: Vec<Pass> = a.iter().map(|q| Pass { z_start: q.z_start + p, z_end: q.z_end + p, z_phase: q.z_phase + p, ..*q }).collect();
        let (za, zb) = (reference_groove(&a), reference_groove(&b));
        prop_assert!((zb - za - p).abs() < 1e-9);
        let ms = MeasureSetup { thread: &t, kind: ThreadKind::External, mmc_pitch_diameter: Some(t.pitch_diameter()), mmc_major_diameter: None, extras: true };
        let ma = measure(&ms, &section(ThreadKind::External, &ins, d - 0.1, p, &a, za).profile(), za).unwrap();
        let mb = measure(&ms, &section(ThreadKind::External, &ins, d - 0.1, p, &b, zb).profile(), zb).unwrap();
        let eps = 1e-5;
        prop_assert!((ma.pitch_diameter - mb.pitch_diameter).abs() < eps);
        prop_assert!((ma.major_diameter - mb.major_diameter).abs() < eps);
        prop_assert!((ma.minor_diameter - mb.minor_diameter).abs() < eps);
        prop_assert!((ma.flank_angles[0] - mb.flank_angles[0]).abs() < 1e-3);
        prop_assert!((ma.flank_angles[1] - mb.flank_angles[1]).abs() < 1e-3);
        prop_assert!((ma.groove_center + p - mb.groove_center).abs() < eps);
        prop_assert!((ma.max_material_clearance.unwrap() - mb.max_material_clearance.unwrap()).abs() < eps);
    }

    /// A bolt cut with a full-profile insert to d3 and a nut cut with a full-profile insert to D,
    /// both basic, the nut's grooves on the bolt's teeth: they share the flank lines (zero
    /// clearance: the profiles touch) and do not overlap (the common area is only snapping noise).
    #[test]
    fn basic_bolt_and_nut_fit_with_zero_clearance(pi in 0usize..6, angle in 0.0f64..30.0, n in 2usize..10) {
        let (d, p) = [(6.0, 1.0), (10.0, 1.5), (12.0, 1.25), (20.0, 2.5), (36.0, 4.0), (64.0, 6.0)][pi];
        let t = metric(d, p);
        let bolt_ins = Insert::full_profile(&t, ThreadKind::External, 1e-3);
        let nut_ins = Insert::full_profile(&t, ThreadKind::Internal, 1e-3);
        let d1 = t.minor_diameter_internal();
        let bolt = plan(ThreadKind::External, p, d + 0.1, t.minor_diameter_external(), n, angle, 6.0 * p);
        // The nut's grooves sit on the bolt's teeth, half a pitch along. The flank infeed moves
        // each last groove by its own total depth·tan(angle), so align the nut's plan on it.
        let nut0 = plan(ThreadKind::Internal, p, d1 - 0.1, d, n, angle, 6.0 * p);
        let zb = reference_groove(&bolt);
        let shift = zb + 0.5 * p - reference_groove(&nut0);
        let nut: Vec<Pass> = nut0.iter().map(|q| Pass { z_start: q.z_start + shift, z_end: q.z_end + shift, z_phase: q.z_phase + shift, ..*q }).collect();
        let zn = reference_groove(&nut);
        prop_assert!((zn - zb - 0.5 * p).abs() < 1e-9);
        let sb = section(ThreadKind::External, &bolt_ins, d + 0.1, p, &bolt, zb);
        let sn = section(ThreadKind::Internal, &nut_ins, d1 - 0.1, p, &nut, zb);
        let overlap = sb.region().intersection(sn.region()).area();
        let length: f64 = sb.profile().windows(2).map(|w| w[0].distance(w[1])).sum();
        prop_assert!(overlap < 1e-5 * length, "overlap {overlap}");
        // Touching: the nut profile passes within 0.01 µm of the bolt's flank at the pitch line.
        use parry2d_f64::math::Point as P;
        use parry2d_f64::query::PointQuery;
        use parry2d_f64::shape::Polyline;
        let nut_line = Polyline::new(sn.profile().iter().map(|q| P::new(q.z, q.r)).collect(), None);
        let r2 = 0.5 * t.pitch_diameter();
        for z in [zb - 0.25 * p, zb + 0.25 * p] {
            let dist = nut_line.distance_to_local_point(&P::new(z, r2), false);
            prop_assert!(dist < 1e-5, "flank gap {dist} at z {z}");
        }
        // And both measure basic pitch diameter.
        let mb = measure(&MeasureSetup { thread: &t, kind: ThreadKind::External, mmc_pitch_diameter: None, mmc_major_diameter: None, extras: true }, &sb.profile(), zb).unwrap();
        let mn = measure(&MeasureSetup { thread: &t, kind: ThreadKind::Internal, mmc_pitch_diameter: None, mmc_major_diameter: None, extras: true }, &sn.profile(), zn).unwrap();
        prop_assert!((mb.pitch_diameter - t.pitch_diameter()).abs() < 1e-5);
        prop_assert!((mn.pitch_diameter - t.pitch_diameter()).abs() < 1e-5);
    }
}

proptest! {
    /// A comment of any text is read or passed over, never a panic; a tool list's line in
    /// Autodesk's form gives back its tool and diameter, in the program's units.
    #[test]
    fn a_comment_names_a_thread_mill_or_nothing(text in "\\PC{0,80}", t in 1u32..999, d in 0.5f64..60.0) {
        let _ = threadcheck::thread_mill_in_comment(&text, threadcheck::ProgramUnits::Mm);
        let line = format!("T{t}  D={d:.3} CR=0. - ZMIN=-12. - thread mill");
        let m = threadcheck::thread_mill_in_comment(&line, threadcheck::ProgramUnits::Mm).unwrap();
        prop_assert_eq!(m.tool, Some(t));
        prop_assert!((m.diameter - (d * 1000.0).round() / 1000.0).abs() < 1e-9);
        let inch = threadcheck::thread_mill_in_comment(&line, threadcheck::ProgramUnits::Inch).unwrap();
        prop_assert!((inch.diameter - 25.4 * (d * 1000.0).round() / 1000.0).abs() < 1e-9);
    }
}
