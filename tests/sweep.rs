//! Issue 3: the sweep engine against analytic geometry. Every expected value below is derived
//! in its comment from the standard's form (ISO 68-1, DIN 13, BS 84) or from plane geometry,
//! never copied from threadcheck's output.

use proptest::prelude::*;
use threadcheck::Insert;
use threadcheck::UnionStrategy;
use threadcheck::{measure, MeasureSetup, Measurement};
use threadcheck::{parse_designation, BasicThread, ParseOptions, ThreadKind};
use threadcheck::{sweep, SweepSetup, Window};
use threadcheck::{Infeed, PlanSpec, Schedule};

const TOL: f64 = 5e-5; // chord tolerance, mm
const UM01: f64 = 1e-4; // 0.1 µm in mm

fn thread(d: &str) -> BasicThread {
    parse_designation(d, ParseOptions::default()).unwrap().thread
}

/// Radial passes (constant area) ending with the tip on diameter `final_x`; returns the measured
/// groove at z = 0.
fn cut(
    t: &BasicThread,
    kind: ThreadKind,
    insert: &Insert,
    blank: f64,
    final_x: f64,
    n: usize,
    infeed: Infeed,
) -> Measurement {
    let spec = PlanSpec {
        starts: t.starts,
        infeed,
        z_start: 5.0 * t.lead(),
        length: 10.0 * t.lead(),
        ..PlanSpec::new(kind, t.pitch, blank, final_x, n)
    };
    let passes = spec.generate().unwrap();
    let setup = SweepSetup { kind, insert, blank_diameter: blank, pitch: t.pitch };
    // The last pass's groove: flank infeed moves it along Z.
    let last = passes[passes.len() - 1];
    let z_groove = last.z_start - 5.0 * t.lead();
    let s =
        sweep(&setup, &passes, Window::around(z_groove, t.pitch, 4.0), UnionStrategy::BalancedTree).unwrap();
    let ms =
        MeasureSetup { thread: t, kind, mmc_pitch_diameter: None, mmc_major_diameter: None, extras: true };
    measure(&ms, &s.section.profile(), z_groove).unwrap()
}

fn near(got: f64, want: f64, tol: f64, what: &str) {
    assert!((got - want).abs() <= tol, "{what}: got {got:.7}, want {want:.7} (±{tol})");
}

/// A full-profile insert with its last radial pass at d3 = d − 1.226869·P forms the DIN 13 bolt:
/// d2 = d − 0.649519·P, d3 at the tip, root radius H/6 = 0.144338·P, flanks at 30°, and the crest
/// topped flat at d.
#[test]
fn full_profile_metric_forms_the_basic_bolt() {
    for d in ["M10x1.5", "M6x1", "M20x1.5", "M30x3.5"] {
        let t = thread(d);
        let p = t.pitch;
        let ins = Insert::full_profile(&t, ThreadKind::External, TOL);
        let d3 = t.nominal_diameter - 1.226869 * p;
        let m = cut(&t, ThreadKind::External, &ins, t.nominal_diameter + 0.1, d3, 8, Infeed::Radial);
        near(m.pitch_diameter, t.nominal_diameter - 0.649519 * p, UM01 + 1e-6 * p, &format!("{d} d2"));
        near(m.minor_diameter, d3, UM01 + 1e-6 * p, &format!("{d} d3"));
        near(m.major_diameter, t.nominal_diameter, UM01, &format!("{d} d"));
        near(m.root_radius.unwrap(), 0.144338 * p, 1e-3, &format!("{d} root radius"));
        near(m.flank_angles[0], 30.0, 1e-3, &format!("{d} low-Z flank"));
        near(m.flank_angles[1], 30.0, 1e-3, &format!("{d} high-Z flank"));
    }
}

/// The M10x1.5 numbers of the issue: d2 = 9.026 (9.02572), d3 = 8.160, R = H/6 = 0.2165.
#[test]
fn full_profile_m10_matches_the_published_design_values() {
    let t = thread("M10x1.5");
    let ins = Insert::full_profile(&t, ThreadKind::External, TOL);
    let m = cut(&t, ThreadKind::External, &ins, 10.1, 8.160, 12, Infeed::Radial);
    // Tip at X = 8.160 instead of d3 = 8.159696: 0.3 µm deeper on the radius, so d2 rises by 0.3 µm.
    near(m.pitch_diameter, 9.025721 + (8.160 - 8.159696), UM01, "d2");
    near(m.minor_diameter, 8.160, UM01, "d3");
    near(m.root_radius.unwrap(), 0.2165, 1e-3, "R");
}

/// A 60° V insert with tip radius r, tip at X = d − 2·(7H/8 − r), has its flanks through the
/// fundamental triangle, hence d2 = basic. (The tip circle's centre is 2r above the sharp vertex,
/// its lowest point r above it; the sharp vertex is 7H/8 below the crest line.)
#[test]
fn partial_profile_reaches_basic_d2_at_7h8_minus_r() {
    let r = 0.04;
    for p in [0.5, 0.75, 1.0, 1.25, 1.5, 2.0] {
        let t = BasicThread { pitch: p, ..thread("M16") };
        let h = 0.866025403784 * p;
        let x = t.nominal_diameter - 2.0 * (7.0 * h / 8.0 - r);
        let ins = Insert::partial_for(&t, r, TOL).unwrap();
        let m = cut(&t, ThreadKind::External, &ins, t.nominal_diameter - 0.1, x, 8, Infeed::Radial);
        near(m.pitch_diameter, t.nominal_diameter - 0.649519053 * p, UM01, &format!("P{p} d2"));
        near(m.minor_diameter, x, UM01, &format!("P{p} root"));
        near(m.root_radius.unwrap(), r, 1e-3, &format!("P{p} root radius"));
        near(m.flank_angles[0], 30.0, 1e-3, "flank");
    }
}

/// Internal M10x1.5, partial insert with the tip at X = D + H/4 − 2r: the nut's flanks pass
/// through the fundamental triangle (its sharp root vertex is H/8 beyond D, and the tip's
/// outermost point is r short of the vertex), so D2 = 9.026 (9.025721).
#[test]
fn internal_partial_profile_reaches_basic_d2() {
    let t = thread("M10x1.5");
    let h = 0.866025403784 * 1.5;
    let r = 0.04;
    let x = 10.0 + h / 4.0 - 2.0 * r;
    let ins = Insert::partial_for(&t, r, TOL).unwrap();
    let bore = 8.376 + 0.15; // mid D1 tolerance of 6H
    let m = cut(&t, ThreadKind::Internal, &ins, bore, x, 8, Infeed::Radial);
    near(m.pitch_diameter, 9.025721, UM01, "D2");
    near(m.major_diameter, x, UM01, "root of the nut");
    near(m.minor_diameter, bore, UM01, "D1 = bore");
}

/// Whitworth BSW 1/2 (12 tpi) with a full-profile 55° insert, tip at d − 2h: d2 = d − 0.640327·P,
/// crest and root radius 0.137329·P.
#[test]
fn whitworth_full_profile() {
    let t = thread("BSW 1/2");
    let p = t.pitch;
    let ins = Insert::full_profile(&t, ThreadKind::External, TOL);
    let x = t.nominal_diameter - 2.0 * 0.640327 * p;
    let m = cut(&t, ThreadKind::External, &ins, t.nominal_diameter + 0.1, x, 10, Infeed::Radial);
    near(m.pitch_diameter, t.nominal_diameter - 0.640327 * p, UM01 + 1e-6 * p, "d2");
    near(m.root_radius.unwrap(), 0.137329 * p, 1e-3, "root radius");
    near(m.major_diameter, t.nominal_diameter, UM01, "crest");
    near(m.flank_angles[0], 27.5, 1e-3, "flank");
}

/// Three-wire M over best wires: M = d2 + 3w − 0.866025·P for 60° (w = P/(2·cos 30°) = 0.866025
/// for P = 1.5), with d2 basic.
#[test]
fn three_wire_over_best_wires() {
    let t = thread("M10x1.5");
    let ins = Insert::full_profile(&t, ThreadKind::External, TOL);
    let d3 = 10.0 - 1.226869 * 1.5;
    let m = cut(&t, ThreadKind::External, &ins, 10.1, d3, 8, Infeed::Radial);
    let tw = m.three_wire.unwrap();
    near(tw.wire, 0.866025, 1e-6, "best wire");
    near(tw.m, m.pitch_diameter + 3.0 * tw.wire - 0.866025 * 1.5, UM01, "M");
    near(tw.m, 9.025721 + 3.0 * 0.8660254 - 1.2990381, 2.0 * UM01, "M from basic d2");
}

/// Random but valid plans: a thread, an insert, cumulative depths and an infeed angle up to α/2.
fn plan_strategy() -> impl Strategy<Value = (usize, bool, f64, Vec<f64>, f64, f64)> {
    (
        0usize..3,
        any::<bool>(),
        0.0f64..0.1,
        proptest::collection::vec(0.01f64..1.0, 1..8),
        0.0f64..30.0,
        -0.3f64..0.3,
    )
}

fn build(
    case: &(usize, bool, f64, Vec<f64>, f64, f64),
) -> (BasicThread, Insert, f64, Vec<threadcheck::Pass>) {
    let (ti, full, r, fr, angle, phase) = case;
    let t = thread(["M6x1", "M10x1.5", "M20x2.5"][*ti]);
    let ins = if *full {
        Insert::full_profile(&t, ThreadKind::External, 1e-3)
    } else {
        Insert::partial_for(&t, *r, 1e-3).unwrap()
    };
    let blank = t.nominal_diameter + 0.1;
    // Depths as fractions of the full-profile depth, sorted: any cutting order is allowed.
    let total = 0.7 * t.pitch;
    let mut depths: Vec<f64> = fr.iter().map(|f| f * total).collect();
    depths.sort_by(f64::total_cmp);
    let (final_x, n) = (blank - 2.0 * depths[depths.len() - 1], depths.len());
    let spec = PlanSpec {
        schedule: Schedule::Explicit(depths),
        infeed: Infeed::Flank { angle: *angle },
        z_start: 6.0 * t.pitch + phase,
        length: 12.0 * t.pitch,
        ..PlanSpec::new(ThreadKind::External, t.pitch, blank, final_x, n)
    };
    (t, ins, blank, spec.generate().unwrap())
}

fn section(
    t: &BasicThread,
    ins: &Insert,
    blank: f64,
    passes: &[threadcheck::Pass],
    center: f64,
) -> threadcheck::Section {
    let setup = SweepSetup { kind: ThreadKind::External, insert: ins, blank_diameter: blank, pitch: t.pitch };
    sweep(&setup, passes, Window::around(center, t.pitch, 3.0), UnionStrategy::BalancedTree).unwrap().section
}

/// Hausdorff distance between two profiles (mm), exact on the polylines (parry point queries).
fn profile_distance(a: &[threadcheck::Point], b: &[threadcheck::Point]) -> f64 {
    use parry2d_f64::math::Point as P;
    use parry2d_f64::query::PointQuery;
    use parry2d_f64::shape::Polyline;
    let line = |v: &[threadcheck::Point]| Polyline::new(v.iter().map(|p| P::new(p.z, p.r)).collect(), None);
    let (la, lb) = (line(a), line(b));
    let one = |pts: &[threadcheck::Point], l: &Polyline| {
        pts.iter().map(|p| l.distance_to_local_point(&P::new(p.z, p.r), false)).fold(0.0, f64::max)
    };
    one(a, &lb).max(one(b, &la))
}

/// Backend snapping moves vertices by nanometres (see boolean.rs); results that should be equal
/// are compared to 0.01 µm, a tenth of the accuracy budget.
const SNAP: f64 = 1e-5;

fn profile_length(s: &threadcheck::Section) -> f64 {
    s.profile().windows(2).map(|w| w[0].distance(w[1])).sum()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    #[test]
    fn adding_a_pass_never_adds_material(case in plan_strategy()) {
        let (t, ins, blank, passes) = build(&case);
        let mut prev = f64::INFINITY;
        for k in 1..=passes.len() {
            let s = section(&t, &ins, blank, &passes[..k], 0.0);
            let a = s.area();
            prop_assert!(a <= prev + SNAP * profile_length(&s), "pass {k}: {a} > {prev}");
            prev = a;
        }
    }

    #[test]
    fn pass_order_does_not_matter(case in plan_strategy(), seed in any::<u64>()) {
        let (t, ins, blank, passes) = build(&case);
        let mut shuffled = passes.clone();
        // A deterministic shuffle from the seed.
        let mut x = seed | 1;
        for i in (1..shuffled.len()).rev() {
            x ^= x << 13; x ^= x >> 7; x ^= x << 17;
            shuffled.swap(i, (x % (i as u64 + 1)) as usize);
        }
        let a = section(&t, &ins, blank, &passes, 0.0);
        let b = section(&t, &ins, blank, &shuffled, 0.0);
        prop_assert!(profile_distance(&a.profile(), &b.profile()) < SNAP);
    }

    #[test]
    fn a_spring_pass_changes_nothing(case in plan_strategy()) {
        let (t, ins, blank, passes) = build(&case);
        let mut sprung = passes.clone();
        sprung.push(passes[passes.len() - 1]);
        let a = section(&t, &ins, blank, &passes, 0.0);
        let b = section(&t, &ins, blank, &sprung, 0.0);
        prop_assert!(profile_distance(&a.profile(), &b.profile()) < SNAP);
    }

    #[test]
    fn the_section_repeats_with_the_lead(case in plan_strategy()) {
        let (t, ins, blank, passes) = build(&case);
        let a = section(&t, &ins, blank, &passes, 0.0);
        let b = section(&t, &ins, blank, &passes, -t.lead());
        // The profile one lead further along is the same profile shifted by one lead.
        let shifted: Vec<threadcheck::Point> = b.profile().iter().map(|q| threadcheck::Point::new(q.z + t.lead(), q.r)).collect();
        prop_assert!(profile_distance(&a.profile(), &shifted) < SNAP);
        prop_assert!((a.area() - b.area()).abs() < SNAP * profile_length(&a));
    }
}

fn metrics(
    t: &BasicThread,
    ins: &Insert,
    blank: f64,
    depths: &[f64],
    infeed: Infeed,
) -> Vec<threadcheck::PassMetrics> {
    let spec = PlanSpec {
        schedule: Schedule::Explicit(depths.to_vec()),
        infeed,
        z_start: 6.0 * t.pitch,
        length: 12.0 * t.pitch,
        ..PlanSpec::new(
            ThreadKind::External,
            t.pitch,
            blank,
            blank - 2.0 * depths[depths.len() - 1],
            depths.len(),
        )
    };
    let passes = spec.generate().unwrap();
    let setup = SweepSetup { kind: ThreadKind::External, insert: ins, blank_diameter: blank, pitch: t.pitch };
    threadcheck::pass_metrics(&setup, &passes, 0.0).unwrap()
}

/// Sharp 60° V, radial, constant-area depths d_i = t·√(i/N): every chip is tan30°·t²/N
/// (a V groove of depth d has area d²·tan β), both flanks engage over d_i / cos β, the tip not at
/// all, and the chip is (d_i − d_{i−1})·sin β thick.
#[test]
fn radial_chips_of_a_sharp_v_are_analytic() {
    let t = thread("M10x1.5");
    let ins = Insert::partial(60.0, 0.0, 2.0, TOL).unwrap();
    let (total, n) = (0.9, 6);
    let depths: Vec<f64> = (1..=n).map(|i| total * (i as f64 / n as f64).sqrt()).collect();
    let m = metrics(&t, &ins, 9.9, &depths, Infeed::Radial);
    let b = 30f64.to_radians();
    let mut prev = 0.0;
    for (i, (d, pm)) in depths.iter().zip(&m).enumerate() {
        near(pm.chip_area, b.tan() * total * total / n as f64, 1e-8, &format!("pass {} chip", i + 1));
        near(pm.leading, d / b.cos(), 1e-6, &format!("pass {} leading", i + 1));
        near(pm.trailing, d / b.cos(), 1e-6, &format!("pass {} trailing", i + 1));
        near(pm.tip, 0.0, 1e-9, "tip");
        near(pm.max_chip_thickness, (d - prev) * b.sin(), 1e-6, &format!("pass {} thickness", i + 1));
        prev = *d;
    }
}

/// Flank infeed at α/2 with a sharp V: the leading edge (facing the feed, −Z) engages over its
/// whole length d_i / cos β. From the second pass on, the trailing edge lies on the finished
/// flank line and forms new surface only below the previous root: (d_i − d_{i−1}) / cos β, the
/// strip the trade's "only one edge cuts" leaves out. The first pass meets a flat surface and
/// engages both edges fully. The chip area is tan β·(d_i² − d_{i−1}²): the groove is a V of depth
/// d_i either way.
#[test]
fn flank_infeed_engages_only_the_leading_edge() {
    let t = thread("M10x1.5");
    let ins = Insert::partial(60.0, 0.0, 2.0, TOL).unwrap();
    let depths = [0.2, 0.4, 0.55, 0.7, 0.8];
    let m = metrics(&t, &ins, 9.9, &depths, Infeed::Flank { angle: 30.0 });
    let b = 30f64.to_radians();
    let mut prev = 0.0f64;
    for (i, (d, pm)) in depths.iter().zip(&m).enumerate() {
        near(pm.chip_area, b.tan() * (d * d - prev * prev), 1e-8, &format!("pass {} chip", i + 1));
        near(pm.leading, d / b.cos(), 1e-6, &format!("pass {} leading", i + 1));
        let trailing = (d - prev) / b.cos();
        near(pm.trailing, trailing, 1e-6, &format!("pass {} trailing", i + 1));
        prev = *d;
    }
}

/// Regression: repeated passes at one position (spring passes, a finishing pass plus idle passes)
/// made the backend insert vertices on the root arc's chords, and the smallest root radius of a
/// full-profile M20x2.5 dropped from H/6 = 0.3608 to 0.136. It must stay H/6 whatever the number
/// of repeats.
#[test]
fn regression_repeated_passes_fake_a_small_root_radius() {
    let t = thread("M20x2.5");
    let ins = Insert::full_profile(&t, ThreadKind::External, TOL);
    let d3 = 20.0 - 1.226869 * 2.5;
    for spring in 0..4 {
        let spec = PlanSpec {
            infeed: Infeed::Flank { angle: 29.5 },
            spring,
            z_start: 12.5,
            length: 25.0,
            ..PlanSpec::new(ThreadKind::External, 2.5, 20.1, d3, 9)
        };
        let passes = spec.generate().unwrap();
        let z = threadcheck::reference_groove(&passes);
        let setup = SweepSetup { kind: ThreadKind::External, insert: &ins, blank_diameter: 20.1, pitch: 2.5 };
        let s = sweep(&setup, &passes, Window::around(z, 2.5, 4.0), UnionStrategy::BalancedTree).unwrap();
        let ms = MeasureSetup {
            thread: &t,
            kind: ThreadKind::External,
            mmc_pitch_diameter: None,
            mmc_major_diameter: None,
            extras: true,
        };
        let m = measure(&ms, &s.section.profile(), z).unwrap();
        near(m.root_radius.unwrap(), 0.144338 * 2.5, 1e-3, &format!("{spring} spring passes"));
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// The lower envelope and the polygon booleans are two independent ways to the same cut:
    /// their profiles agree to 0.01 µm, for external and internal threads, V and full-profile
    /// inserts, any infeed up to 60° and any schedule.
    #[test]
    fn envelope_and_booleans_agree(
        ti in 0usize..4, full in any::<bool>(), internal in any::<bool>(), r in 0.0f64..0.1,
        fr in proptest::collection::vec(0.02f64..1.0, 1..10), angle in 0.0f64..60.0, phase in -0.4f64..0.4,
    ) {
        let t = thread(["M6x1", "M10x1.5", "M20x2.5", "M36x4"][ti]);
        let kind = if internal { ThreadKind::Internal } else { ThreadKind::External };
        let ins = if full { Insert::full_profile(&t, kind, 1e-3) } else { Insert::partial_for(&t, r, 1e-3).unwrap() };
        let (surface, sign) = match kind {
            ThreadKind::External => (t.nominal_diameter + 0.1, -1.0),
            ThreadKind::Internal => (t.minor_diameter_internal() - 0.1, 1.0),
        };
        let total = 0.7 * t.pitch;
        let mut depths: Vec<f64> = fr.iter().map(|f| f * total).collect();
        depths.sort_by(f64::total_cmp);
        let spec = PlanSpec {
            kind, pitch: t.pitch, starts: 1, surface_x: surface,
            final_x: surface + sign * 2.0 * depths[depths.len() - 1], passes: depths.len(),
            schedule: Schedule::Explicit(depths), infeed: Infeed::Flank { angle }, spring: 0,
            first_depth: None, min_depth: 0.0, finish: 0.0, taper: 0.0, chamfer_leads: 0.0, left_hand: false,
            z_start: 6.0 * t.pitch + phase, length: 12.0 * t.pitch,
        };
        let passes = spec.generate().unwrap();
        let setup = SweepSetup { kind, insert: &ins, blank_diameter: surface, pitch: t.pitch };
        let w = Window::around(0.0, t.pitch, 3.0);
        let a = sweep(&setup, &passes, w, UnionStrategy::Envelope).unwrap().section;
        let b = sweep(&setup, &passes, w, UnionStrategy::BalancedTree).unwrap().section;
        let d = profile_distance(&a.profile(), &b.profile());
        prop_assert!(d < SNAP, "distance {d}");
        prop_assert!((a.area() - b.area()).abs() < SNAP * profile_length(&a), "areas {} {}", a.area(), b.area());
    }
}

/// A nut insert whose crest shoulders run into the flanks through concave arcs (Whitworth), the
/// case the property test above (metric forms) does not reach: the envelope agrees with the
/// polygon booleans, crest included, and the insert tops the crest above the bore. (The unit
/// test `runs_meeting_in_concave_arcs_leave_no_gap` holds the envelope's convex runs to the
/// same passes, where they once lost this crest in rounding-wide gaps.)
#[test]
fn whitworth_nut_full_insert_tops_the_crest() {
    let mut spec = threadcheck::VerifySpec::of("BSW 7/16 medium").unwrap();
    spec.internal = true;
    spec.insert = threadcheck::InsertChoice::Full;
    spec.infeed = Some("alternating:27.5".parse().unwrap());
    spec.schedule = Schedule::ConstantDepth;
    let v = threadcheck::verify(&spec).unwrap();
    let setup = SweepSetup {
        kind: v.kind,
        insert: &v.insert,
        blank_diameter: v.blank_diameter,
        pitch: v.designation.thread.pitch,
    };
    let w = v.section.window;
    let a = sweep(&setup, &v.passes, w, UnionStrategy::Envelope).unwrap().section;
    let b = sweep(&setup, &v.passes, w, UnionStrategy::BalancedTree).unwrap().section;
    let d = profile_distance(&a.profile(), &b.profile());
    assert!(d < SNAP, "distance {d}");
    // The crest is cut: the minor diameter lies above the bore.
    assert!(v.measurement.minor_diameter > v.blank_diameter + 0.1, "{:?}", v.measurement);
}
