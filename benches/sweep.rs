//! Criterion benches of the sweep engine. Run with `cargo bench --bench sweep`; CI only builds
//! them (`cargo bench --no-run`). Results go to `reports/performance.md` by hand with the machine
//! named.

#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::hint::black_box;
use threadcheck::Insert;
use threadcheck::UnionStrategy;
use threadcheck::{measure, MeasureSetup};
use threadcheck::{parse_designation, BasicThread, ParseOptions, ThreadKind};
use threadcheck::{sweep, SweepSetup, Window};
use threadcheck::{Infeed, Pass, PlanSpec};

fn m10() -> BasicThread {
    parse_designation("M10x1.5", ParseOptions::default()).unwrap().thread
}

fn plan(n: usize, infeed: Infeed) -> Vec<Pass> {
    if n > 1000 {
        // Beyond the plans' 1 000 passes: the same constant-area flank plan laid out by hand
        // (radial depth 0.875·√(i/n), each pass moved along Z by its depth·tan 29.5°).
        let flank = match infeed {
            Infeed::Flank { angle } => angle.to_radians().tan(),
            _ => 0.0,
        };
        return (1..=n)
            .map(|i| {
                let d = 0.875 * (i as f64 / n as f64).sqrt();
                let z = 6.0 - d * flank;
                Pass::parallel(i, 9.85 - 2.0 * d, z, z - 12.0, 1.5)
            })
            .collect();
    }
    PlanSpec { infeed, z_start: 6.0, length: 12.0, ..PlanSpec::new(ThreadKind::External, 1.5, 9.85, 8.10, n) }
        .generate()
        .unwrap()
}

fn groove(passes: &[Pass]) -> f64 {
    passes[passes.len() - 1].z_start - 6.0
}

/// One M10x1.5 thread, 12 passes, partial insert, end to end as a post-processor calls it:
/// designation, limits, plan, sweep, measure (with three-wire M and the maximum-material check)
/// and checks, with the final X given and no per-pass chip metrics.
fn one_thread(c: &mut Criterion) {
    let mut spec = threadcheck::VerifySpec::of("M10x1.5-6g").unwrap();
    spec.passes = Some(12);
    spec.final_x = Some(7.709);
    spec.metrics = false;
    c.bench_function("verify M10x1.5-6g, 12 passes (sweep+measure+check)", |b| {
        b.iter(|| black_box(threadcheck::verify(&spec).unwrap().pass))
    });
    // The CLI's default: the same with the per-pass chip and edge metrics (from envelopes).
    let mut with_metrics = spec.clone();
    with_metrics.metrics = true;
    c.bench_function("verify M10x1.5-6g, 12 passes, with per-pass metrics", |b| {
        b.iter(|| black_box(threadcheck::verify(&with_metrics).unwrap().pass))
    });
    let mut solve = spec.clone();
    solve.final_x = None;
    c.bench_function("verify M10x1.5-6g, 12 passes, final X solved", |b| {
        b.iter(|| black_box(threadcheck::verify(&solve).unwrap().pass))
    });
}

/// The union strategies side by side on the same placements.
fn union_strategies(c: &mut Criterion) {
    let t = m10();
    let ins = Insert::partial_for(&t, 0.04, 5e-5).unwrap();
    let mut g = c.benchmark_group("union strategy, M10x1.5");
    g.sample_size(10);
    for n in [12usize, 100] {
        let passes = plan(n, Infeed::Flank { angle: 29.5 });
        let setup = SweepSetup { kind: ThreadKind::External, insert: &ins, blank_diameter: 9.85, pitch: 1.5 };
        let w = Window::around(groove(&passes), 1.5, 4.0);
        for (name, s) in [
            ("tree", UnionStrategy::BalancedTree),
            ("unary", UnionStrategy::Unary),
            ("sequential", UnionStrategy::Sequential),
        ] {
            g.bench_with_input(BenchmarkId::new(name, n), &n, |b, _| {
                b.iter(|| black_box(sweep(&setup, &passes, w, s).unwrap()))
            });
        }
    }
    g.finish();
}

/// Cost per pass from 10 to 10 000 passes: the envelope (threadcheck's method) to 10 000, the
/// balanced tree to 1 000 (at 10 000 one tree sweep takes about 20 s).
fn scaling(c: &mut Criterion) {
    let t = m10();
    let ins = Insert::partial_for(&t, 0.04, 5e-5).unwrap();
    let mut g = c.benchmark_group("scaling, M10x1.5");
    g.sample_size(10);
    for (name, s, sizes) in [
        ("envelope", UnionStrategy::Envelope, &[10usize, 100, 1_000, 10_000][..]),
        ("tree", UnionStrategy::BalancedTree, &[10usize, 100, 1_000][..]),
    ] {
        for &n in sizes {
            let passes = plan(n, Infeed::Flank { angle: 29.5 });
            let setup =
                SweepSetup { kind: ThreadKind::External, insert: &ins, blank_diameter: 9.85, pitch: 1.5 };
            let w = Window::around(groove(&passes), 1.5, 4.0);
            g.bench_with_input(BenchmarkId::new(name, n), &n, |b, _| {
                b.iter(|| black_box(sweep(&setup, &passes, w, s).unwrap()))
            });
        }
    }
    g.finish();
}

/// Measurement alone on a finished section.
fn measurement(c: &mut Criterion) {
    let t = m10();
    let ins = Insert::partial_for(&t, 0.04, 5e-5).unwrap();
    let passes = plan(12, Infeed::Flank { angle: 29.5 });
    let setup = SweepSetup { kind: ThreadKind::External, insert: &ins, blank_diameter: 9.85, pitch: 1.5 };
    let z = groove(&passes);
    let s = sweep(&setup, &passes, Window::around(z, 1.5, 4.0), UnionStrategy::Envelope).unwrap();
    let profile = s.section.profile();
    let ms = MeasureSetup {
        thread: &t,
        kind: ThreadKind::External,
        mmc_pitch_diameter: Some(8.994),
        mmc_major_diameter: None,
        extras: true,
    };
    c.bench_function("measure M10x1.5", |b| b.iter(|| black_box(measure(&ms, &profile, z).unwrap())));
}

/// `capability --samples 10000` of M10x1.5-6g (target: under 0.5 s on 2 cores).
fn capability(c: &mut Criterion) {
    let mut g = c.benchmark_group("capability");
    g.sample_size(10);
    g.bench_function("M10x1.5-6g, 10 000 samples, X scatter and tip radius", |b| {
        b.iter(|| {
            let mut spec =
                threadcheck::CapabilitySpec::new(threadcheck::VerifySpec::of("M10x1.5-6g").unwrap());
            spec.x_sigma = 0.008;
            spec.tip_radius_tol = 0.01;
            black_box(threadcheck::capability(&spec).unwrap())
        })
    });
    g.finish();
}

criterion_group!(benches, one_thread, union_strategies, scaling, measurement, capability);
criterion_main!(benches);
