//! Issue 6: what geometry alone says about one-flank versus two-flank infeed. Every expected value
//! is derived in the comment above its test.

use threadcheck::Insert;
use threadcheck::UnionStrategy;
use threadcheck::{measure, MeasureSetup, Measurement};
use threadcheck::{parse_designation, BasicThread, ParseOptions, Point, ThreadKind};
use threadcheck::{reference_groove, InsertChoice, VerifySpec};
use threadcheck::{sweep, SweepSetup, Window};
use threadcheck::{Infeed, Pass, PlanSpec, Schedule};

const TAN30: f64 = 0.577_350_269_189_625_8;

fn thread(d: &str) -> BasicThread {
    parse_designation(d, ParseOptions::default()).unwrap().thread
}

fn profile(t: &BasicThread, ins: &Insert, blank: f64, passes: &[Pass], z: f64) -> Vec<Point> {
    let setup = SweepSetup { kind: ThreadKind::External, insert: ins, blank_diameter: blank, pitch: t.pitch };
    sweep(&setup, passes, Window::around(z, t.pitch, 3.0), UnionStrategy::BalancedTree)
        .unwrap()
        .section
        .profile()
}

fn measured(t: &BasicThread, ins: &Insert, blank: f64, passes: &[Pass], z: f64) -> Measurement {
    let ms = MeasureSetup {
        thread: t,
        kind: ThreadKind::External,
        mmc_pitch_diameter: None,
        mmc_major_diameter: None,
        extras: true,
    };
    measure(&ms, &profile(t, ins, blank, passes, z), z).unwrap()
}

fn plan(
    t: &BasicThread,
    blank: f64,
    final_x: f64,
    n: usize,
    schedule: Schedule,
    infeed: Infeed,
) -> Vec<Pass> {
    PlanSpec {
        schedule,
        infeed,
        z_start: 5.0 * t.pitch,
        length: 10.0 * t.pitch,
        ..PlanSpec::new(ThreadKind::External, t.pitch, blank, final_x, n)
    }
    .generate()
    .unwrap()
}

/// A V or rounded-V insert K is convex and open upwards; K + v ⊂ K for every v in its recession
/// cone, the directions within α/2 of the radial. A pass Δdepth shallower and |Δz| ≤
/// Δdepth·tan(α/2) to the side is such a translate of the deeper one, so it lies inside it. Hence
/// for any infeed angle from 0 to α/2 the as-cut profile is that of the last pass alone: radial
/// and flank infeed give the same tooth. Checked to 0.1 µm over four threads, three schedules,
/// five angles and three inserts (sharp V, r 0.04, full profile).
#[test]
fn every_infeed_up_to_half_the_angle_leaves_the_last_pass_alone() {
    let mut cases = 0;
    for d in ["M6x1", "M10x1.5", "M20x2.5", "M36x4"] {
        let t = thread(d);
        let p = t.pitch;
        let h = t.fundamental_height();
        for (kind, ins) in [
            ("sharp", Insert::partial_for(&t, 0.0, 1e-4).unwrap()),
            ("r0.04", Insert::partial_for(&t, 0.04, 1e-4).unwrap()),
            ("full", Insert::full_profile(&t, ThreadKind::External, 1e-4)),
        ] {
            let blank = if kind == "full" { t.nominal_diameter + 0.1 } else { t.nominal_diameter - 0.1 };
            let final_x = if kind == "full" {
                t.minor_diameter_external()
            } else {
                t.nominal_diameter - 2.0 * (0.875 * h - 0.04)
            };
            for schedule in [Schedule::ConstantDepth, Schedule::ConstantArea, Schedule::Sandvik] {
                for angle in [0.0, 15.0, 27.0, 29.5, 30.0] {
                    let passes = plan(
                        &t,
                        blank,
                        final_x,
                        (3.5 + 2.0 * p).round() as usize,
                        schedule.clone(),
                        Infeed::Flank { angle },
                    );
                    let z = reference_groove(&passes);
                    let last = passes[passes.len() - 1];
                    let all = profile(&t, &ins, blank, &passes, z);
                    let alone = profile(&t, &ins, blank, &[last], z);
                    let dist = crate::hausdorff(&all, &alone);
                    assert!(dist < 1e-4, "{d} {kind} {schedule:?} {angle}°: {dist}");
                    cases += 1;
                }
            }
        }
    }
    assert_eq!(cases, 180);
}

/// The flank rule written with the tangent on the wrong side, Δx = tan(α/2)·Δz, infeeds at
/// θ = atan(1/tan 30°) = 60° from the radial. Two passes Δ = 0.1 mm apart in depth with a sharp V:
/// the first sits Δ·tan θ further along +Z, its trailing flank Δ·(tan θ − tan 30°) outside the
/// last one's. Above the first tip the groove is that much wider, so the pitch line (width P/2)
/// drops by that over 2·tan 30° and d2 by Δ·(tan θ / tan 30° − 1) = 2Δ = 0.2 mm at 60°
/// (0.0732 mm at 45°). The groove centre moves by half the widening, and the profile is no
/// longer symmetric about the last pass.
#[test]
fn the_wrong_tangent_gouges_the_trailing_flank() {
    let t = thread("M10x1.5");
    let h = t.fundamental_height();
    let ins = Insert::partial_for(&t, 0.0, 1e-4).unwrap();
    let depth = 0.875 * h; // sharp vertex of the fundamental triangle: flanks through basic d2
    let delta = 0.1;
    for (theta, want) in [(60.0f64, 0.2), (45.0, 0.1 * (1.0 / TAN30 - 1.0))] {
        let tt = theta.to_radians().tan();
        let x = |d: f64| 10.0 - 2.0 * d;
        // Feed towards −Z; the earlier, shallower pass sits Δ·tan θ towards +Z of the last.
        let passes = [
            Pass::parallel(1, x(depth - delta), 6.0 + delta * tt, -6.0, 1.5),
            Pass::parallel(2, x(depth), 6.0, -6.0, 1.5),
        ];
        let m = measured(&t, &ins, 10.0, &passes, 0.0);
        let basic = 10.0 - 0.649_519_052_838_329 * 1.5;
        assert!(
            (basic - m.pitch_diameter - want).abs() < 1e-7,
            "{theta}°: d2 {} basic {basic}",
            m.pitch_diameter
        );
        let widening = delta * (tt - TAN30);
        assert!((m.groove_center - 0.5 * widening).abs() < 1e-7, "{theta}°: centre {}", m.groove_center);
        let radial = measured(&t, &ins, 10.0, &[passes[1]], 0.0);
        assert!((radial.pitch_diameter - basic).abs() < 1e-7);
    }
}

/// Two final passes at the same depth, s apart along Z, widen the groove by s at every height
/// above the tip; the pitch line drops by s/(2·tan 30°) and d2 by s/tan 30° = 1.7320508·s. This is
/// what the "axial spread of the last passes" of an alternating scheme, or a per-pass phase error
/// of the control (passes not landing in one groove), costs: 17.32 µm of pitch diameter per
/// 0.01 mm of spread, linearly.
#[test]
fn spread_of_the_last_passes_and_phase_error_cost_d2() {
    let t = thread("M10x1.5");
    let ins = Insert::partial_for(&t, 0.04, 1e-4).unwrap();
    let depth = 0.875 * t.fundamental_height() - 0.04;
    let x = 10.0 - 2.0 * depth;
    let base = measured(&t, &ins, 9.85, &[Pass::parallel(1, x, 6.0, -6.0, 1.5)], 0.0).pitch_diameter;
    for s in [0.01, 0.02, 0.05] {
        let passes = [Pass::parallel(1, x, 6.0, -6.0, 1.5), Pass::parallel(2, x, 6.0 + s, -6.0, 1.5)];
        let m = measured(&t, &ins, 9.85, &passes, 0.0);
        let loss = base - m.pitch_diameter;
        assert!((loss - s / TAN30).abs() < 1e-7, "spread {s}: loss {loss}");
    }
}

/// Alternating flank as an incremental control cuts it: each pass moves Δdepth·tan θ along Z,
/// changing side every pass. With θ ≤ α/2 every pass still nests in the next, so the final
/// spread is inside the last V and the tooth equals radial infeed's; the groove centre ends where
/// the alternation left it.
#[test]
fn incremental_alternating_nests_like_flank_infeed() {
    let t = thread("M10x1.5");
    let ins = Insert::partial_for(&t, 0.04, 1e-4).unwrap();
    let final_x = 10.0 - 2.0 * (0.875 * t.fundamental_height() - 0.04);
    for schedule in [Schedule::ConstantDepth, Schedule::ConstantArea] {
        let alt = plan(&t, 9.85, final_x, 8, schedule.clone(), Infeed::Alternating { angle: 30.0 });
        let rad = plan(&t, 9.85, final_x, 8, schedule, Infeed::Radial);
        let (za, zr) = (reference_groove(&alt), reference_groove(&rad));
        let (ma, mr) = (measured(&t, &ins, 9.85, &alt, za), measured(&t, &ins, 9.85, &rad, zr));
        assert!((ma.pitch_diameter - mr.pitch_diameter).abs() < 1e-7);
        assert!((ma.minor_diameter - mr.minor_diameter).abs() < 1e-7);
    }
}

fn compare_sharp(schedule_n: usize) -> threadcheck::Comparison {
    let mut spec = VerifySpec::of("M10x1.5-6g").unwrap();
    spec.insert = InsertChoice::Partial { tip_radius: 0.0 };
    spec.passes = Some(schedule_n);
    threadcheck::compare(&spec, &[29.5], &Default::default()).unwrap()
}

/// Radial passes with a sharp V engage both flanks along their whole length d_i / cos 30° on
/// every pass; from the second pass on that is more than the strip below the previous root, so
/// N − 1 passes are two-flank. Flank infeed at α/2 engages the trailing edge only over that strip
/// (the old flank line extended below the old root): no two-flank pass. Half of each radial chip
/// lies behind the tip (the V is symmetric).
#[test]
fn radial_cuts_with_both_flanks_flank_infeed_with_one() {
    let n = 8;
    let c = compare_sharp(n);
    let find = |infeed: &str, schedule: &str| {
        c.runs.iter().find(|(m, _)| m.infeed == infeed && m.schedule == schedule).unwrap().0.clone()
    };
    for schedule in ["constant-depth", "constant-area"] {
        let radial = find("radial", schedule);
        assert_eq!(radial.two_flank_passes, n - 1, "{schedule}");
        assert!((radial.trailing_share - 0.5).abs() < 1e-6, "{schedule}: {}", radial.trailing_share);
        let flank = find("flank 30°", schedule);
        assert_eq!(flank.two_flank_passes, 0, "{schedule}");
        assert!(flank.trailing_share < 0.25, "{schedule}: {}", flank.trailing_share);
    }
    // The engaged lengths themselves, pass by pass.
    let (_, v) = c.runs.iter().find(|(m, _)| m.infeed == "radial" && m.schedule == "constant-area").unwrap();
    let c30 = 30f64.to_radians().cos();
    for (p, m) in v.passes.iter().zip(&v.metrics) {
        let d = 0.5 * (v.blank_diameter - p.x_end);
        assert!(
            (m.leading - d / c30).abs() < 1e-6 && (m.trailing - d / c30).abs() < 1e-6,
            "pass {}",
            p.index
        );
    }
}

/// Chip areas of a sharp V from a flat surface: the groove of depth d has area d²·tan 30°, so pass
/// i removes tan 30°·(d_i² − d_{i−1}²). Constant depth (d_i = t·i/N) gives tan 30°·t²·(2i − 1)/N²:
/// growing linearly, last over first = 2N − 1 (15 for N = 8). Constant area (d_i = t·√(i/N))
/// gives tan 30°·t²/N for every pass: max over min = 1.
#[test]
fn constant_depth_grows_the_chip_constant_area_holds_it() {
    let n = 8;
    let c = compare_sharp(n);
    for (m, v) in &c.runs {
        let t_depth = 0.5 * (v.blank_diameter - c.final_x);
        if m.schedule == "constant-depth" {
            assert!(
                (m.chip_last / m.chip_first - (2 * n - 1) as f64).abs() < 1e-6,
                "{}: {}",
                m.infeed,
                m.chip_last / m.chip_first
            );
            assert!((m.chip_first - TAN30 * t_depth * t_depth / (n * n) as f64).abs() < 1e-8);
        } else {
            assert!((m.chip_spread - 1.0).abs() < 1e-6, "{}: {}", m.infeed, m.chip_spread);
            assert!((m.chip_max - TAN30 * t_depth * t_depth / n as f64).abs() < 1e-8);
        }
    }
}

/// The committed report regenerates byte for byte with its command.
#[test]
fn the_committed_report_regenerates_byte_for_byte() {
    let dir = crate::tempdir("report");
    let report =
        threadcheck::ReportArgs { name: threadcheck::ReportName::InfeedComparison, out: dir.to_path_buf() };
    // The command line's report: its words name flags (`--insert full`).
    let request = threadcheck::Request {
        wanted: vec![threadcheck::Document::Text],
        files: threadcheck::Files::Allowed,
        reader: threadcheck::Audience::Cli,
        progress: false,
    };
    let out = threadcheck::Job::run(&report, &request).unwrap();
    threadcheck::deliver(&out, &[], threadcheck::Audience::Cli).unwrap();
    let committed = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("reports");
    let mut n = 0;
    for e in std::fs::read_dir(&dir).unwrap() {
        let name = e.unwrap().file_name();
        let fresh = std::fs::read(dir.join(&name)).unwrap();
        let old = std::fs::read(committed.join(&name))
            .unwrap_or_else(|_| panic!("{name:?} is not committed in reports/"));
        assert!(fresh == old, "{name:?} differs from the committed copy: run `cargo run --release -- report infeed-comparison --out reports`");
        n += 1;
    }
    assert_eq!(n, 17);
}
