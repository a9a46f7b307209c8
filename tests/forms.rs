//! Issue 13 (the Unified form so far): designations, limits against the reference check set,
//! and the full-profile cut against the basic pitch diameter.

use crate::*;
use threadcheck::limits_for;
use threadcheck::{parse_designation, ParseOptions, ThreadForm, ThreadKind};

const IN: f64 = 25.4;

fn des(s: &str) -> threadcheck::Designation {
    parse_designation(s, ParseOptions::default()).unwrap_or_else(|e| panic!("{s}: {e}"))
}

/// Every limit of the check set, at the tables' 0.0001 in.
#[test]
fn unified_limits_match_the_check_set() {
    let t = data_toml("unified-limits.toml");
    let checks = t["check"].as_array().unwrap();
    assert_eq!(checks.len(), 8);
    for c in checks {
        let name = c["designation"].as_str().unwrap();
        let d = des(name);
        let close = |got: Option<f64>, want: f64, what: &str| {
            let got = got.unwrap_or_else(|| panic!("{name}: no {what}")) / IN;
            assert!((got - want).abs() < 0.5e-4, "{name} {what}: {got:.5} in, published {want}");
        };
        if let Some(e) = c.get("external") {
            let l = limits_for(&d, ThreadKind::External).unwrap().unwrap();
            close(l.major_diameter.max, e["d_max"].as_float().unwrap(), "d max");
            close(l.major_diameter.min, e["d_min"].as_float().unwrap(), "d min");
            close(l.pitch_diameter.max, e["d2_max"].as_float().unwrap(), "d2 max");
            close(l.pitch_diameter.min, e["d2_min"].as_float().unwrap(), "d2 min");
        }
        if let Some(i) = c.get("internal") {
            let l = limits_for(&d, ThreadKind::Internal).unwrap().unwrap();
            close(l.minor_diameter.min, i["D1_min"].as_float().unwrap(), "D1 min");
            close(l.minor_diameter.max, i["D1_max"].as_float().unwrap(), "D1 max");
            close(l.pitch_diameter.min, i["D2_min"].as_float().unwrap(), "D2 min");
            close(l.pitch_diameter.max, i["D2_max"].as_float().unwrap(), "D2 max");
        }
    }
}

/// Number sizes (0.060 + 0.013·N in), fractions, decimals, fits, LH, UNR, and the series check.
#[test]
fn unified_designations() {
    let d = des("#10-32 UNF-2A");
    assert!(
        (d.thread.nominal_diameter - 0.190 * IN).abs() < 1e-9 && (d.thread.pitch - IN / 32.0).abs() < 1e-12
    );
    assert_eq!(d.thread.form, ThreadForm::Unified);
    assert!((des("0-80 UNF-2A").thread.nominal_diameter - 0.060 * IN).abs() < 1e-9);
    // 1-8 is the one-inch coarse thread, not #1 (which has 64 and 72 tpi).
    assert!((des("1-8 UNC-2A").thread.nominal_diameter - IN).abs() < 1e-9);
    let lh = des("1 1/4-7 UNC-2A-LH");
    assert!((lh.thread.nominal_diameter - 1.25 * IN).abs() < 1e-9);
    assert_eq!(lh.thread.hand, threadcheck::Hand::Left);
    let fit = des("1/2-13 UNC-2B/2A");
    assert!(fit.external.is_some() && fit.internal.is_some());
    assert!((des(".250-20 UNC-2A").thread.nominal_diameter - 6.35).abs() < 1e-9);
    // UNR: the external root radius is at least 0.108·P.
    let unr = limits_for(&des("1/4-20 UNRC-2A"), ThreadKind::External).unwrap().unwrap();
    assert!((unr.root_radius_min.unwrap() - 0.108 * IN / 20.0).abs() < 1e-12);
    // Not in the series: refused with the standard tpi, unless UNS or --allow-nonstandard.
    let e = parse_designation("1/4-24 UNC-2A", ParseOptions::default()).unwrap_err().to_string();
    assert!(e.contains("has 20 tpi"), "{e}");
    assert!(parse_designation("1/4-24 UNS-2A", ParseOptions::default()).is_ok());
    assert!(
        parse_designation("1/4-24 UNC-2A", ParseOptions { allow_nonstandard: true }).unwrap().nonstandard
    );
}

/// A full-profile insert cut to the basic root d − 1.226869·P measures the basic pitch diameter
/// d − 0.649519·P to 0.1 µm; at the solved mid-tolerance X it passes.
#[test]
fn unified_full_profile_cuts_the_basic_pitch_diameter() {
    for (name, d, tpi) in [
        ("1/4-20 UNC-2A", 0.25, 20.0),
        ("1/2-13 UNC-2A", 0.5, 13.0),
        ("3/4-16 UNF-2A", 0.75, 16.0),
        ("#10-32 UNF-2A", 0.19, 32.0),
    ] {
        let p = IN / tpi;
        let d = d * IN;
        let x3 = format!("{}", d - 1.226_869_027_954_1 * p);
        let o = run(&[
            "verify",
            "--thread",
            name,
            "--insert",
            "full",
            "--final-x",
            &x3,
            "--no-pass-metrics",
            "--json",
            "-",
        ]);
        let v: serde_json::Value =
            serde_json::from_slice(&o.stdout).unwrap_or_else(|_| panic!("{name}: {}", stderr(&o)));
        let d2 = v["measured"]["pitch_diameter"].as_f64().unwrap();
        assert!((d2 - (d - 0.649_519_052_838_329 * p)).abs() < 1e-4, "{name}: d2 {d2} (to 0.1 µm)");
        let o = run(&["verify", "--thread", name, "--insert", "full", "--no-pass-metrics"]);
        assert_eq!(o.status.code(), Some(0), "{name}: {}", stdout(&o));
    }
}

/// A Haas 1/2-13 UNC program of ours: its root X.4056 in is 0.000025 in inside the basic root
/// d3 = 0.5 − 1.226869/13 = 0.405625 in, so a full-profile insert cuts d2 = basic 0.450037 in
/// less 0.000025 in, over 2A's d2 max 0.4485 in by (0.450012 − 0.4485)·25.4 mm = 38.4 µm.
#[test]
fn unified_program_gets_a_verdict() {
    let prog = data("programs/haas-g76-1-2-13-unc.nc");
    let o = run(&[
        "verify",
        "--program",
        prog.to_str().unwrap(),
        "--dialect",
        "haas",
        "--thread",
        "1/2-13 UNC-2A",
        "--insert",
        "full",
        "--no-pass-metrics",
        "--json",
        "-",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let c = v["operations"][0]["checks"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["feature"] == "pitch_diameter")
        .unwrap()
        .clone();
    let basic = 0.5 - 0.649_519_052_838_329 / 13.0;
    let want = ((basic - 0.000_025) - 0.4485) * IN * 1000.0;
    assert!((c["deviation_um"].as_f64().unwrap() - want).abs() < 0.1, "{c} vs {want}");
}

/// Every limit of the trapezoidal check set, to the micrometre.
#[test]
fn trapezoidal_limits_match_the_check_set() {
    let t = data_toml("trapezoidal-limits.toml");
    let checks = t["check"].as_array().unwrap();
    assert_eq!(checks.len(), 4);
    for c in checks {
        let name = c["designation"].as_str().unwrap();
        let d = des(name);
        let eq = |got: Option<f64>, want: f64, what: &str| {
            let got = got.unwrap_or_else(|| panic!("{name}: no {what}"));
            assert!((got - want).abs() < 0.5e-3, "{name} {what}: {got}, published {want}");
        };
        if let Some(e) = c.get("external") {
            let l = limits_for(&d, ThreadKind::External).unwrap().unwrap();
            eq(l.major_diameter.max, e["d_max"].as_float().unwrap(), "d max");
            eq(l.major_diameter.min, e["d_min"].as_float().unwrap(), "d min");
            eq(l.pitch_diameter.max, e["d2_max"].as_float().unwrap(), "d2 max");
            eq(l.pitch_diameter.min, e["d2_min"].as_float().unwrap(), "d2 min");
            eq(l.minor_diameter.max, e["d3_max"].as_float().unwrap(), "d3 max");
            eq(l.minor_diameter.min, e["d3_min"].as_float().unwrap(), "d3 min");
        }
        if let Some(i) = c.get("internal") {
            let l = limits_for(&d, ThreadKind::Internal).unwrap().unwrap();
            eq(l.minor_diameter.min, i["D1_min"].as_float().unwrap(), "D1 min");
            eq(l.minor_diameter.max, i["D1_max"].as_float().unwrap(), "D1 max");
            eq(l.pitch_diameter.min, i["D2_min"].as_float().unwrap(), "D2 min");
            eq(l.pitch_diameter.max, i["D2_max"].as_float().unwrap(), "D2 max");
            eq(l.major_diameter.min, i["D4_min"].as_float().unwrap(), "D4 min");
        }
    }
}

/// Multi-start and left-hand designations; the series check; es(c) is sourced at P 2 only.
#[test]
fn trapezoidal_designations() {
    let d = des("Tr40x14(P7)-7e");
    assert_eq!((d.thread.pitch, d.thread.starts, d.thread.lead()), (7.0, 2, 14.0));
    assert_eq!(des("Tr40x7LH-7e").thread.hand, threadcheck::Hand::Left);
    assert_eq!(des("Tr40x7-LH-7H/7e").thread.hand, threadcheck::Hand::Left);
    let e = parse_designation("Tr40x8-7e", ParseOptions::default()).unwrap_err().to_string();
    assert!(e.contains("3, 7, 10"), "{e}");
    let e = limits_for(&des("Tr40x7-8c"), ThreadKind::External).unwrap_err().to_string();
    assert!(e.contains("es(c)") && e.contains("not in the sources"), "{e}");
}

/// A full-profile insert cut to d3 = d − P − 2ac measures d2 = d − 0.5·P to 0.1 µm; the solved
/// mid-tolerance cut passes.
#[test]
fn trapezoidal_full_profile_cuts_the_basic_pitch_diameter() {
    for (name, d, p, ac) in
        [("Tr40x7-7e", 40.0, 7.0, 0.5), ("Tr20x4-7e", 20.0, 4.0, 0.25), ("Tr10x2-7e", 10.0, 2.0, 0.25)]
    {
        let x3 = format!("{}", d - p - 2.0 * ac);
        let o = run(&[
            "verify",
            "--thread",
            name,
            "--insert",
            "full",
            "--final-x",
            &x3,
            "--no-pass-metrics",
            "--json",
            "-",
        ]);
        let v: serde_json::Value =
            serde_json::from_slice(&o.stdout).unwrap_or_else(|_| panic!("{name}: {}", stderr(&o)));
        let d2 = v["measured"]["pitch_diameter"].as_f64().unwrap();
        assert!((d2 - (d - 0.5 * p)).abs() < 1e-4, "{name}: d2 {d2} (to 0.1 µm)");
        let o = run(&["verify", "--thread", name, "--insert", "full", "--no-pass-metrics"]);
        assert_eq!(o.status.code(), Some(0), "{name}: {}", stdout(&o));
    }
}

/// One-flank against two-flank on a Tr40x7: with the infeed along the 15° flank, fewer passes
/// cut with both edges than with radial infeed, and less chip area lies behind the tip.
#[test]
fn compare_runs_on_a_trapezoidal_thread() {
    let o = run(&["compare", "--thread", "Tr40x7-7e", "--insert", "full", "--json"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let rows = v["strategies"].as_array().unwrap_or_else(|| panic!("{v:#}"));
    let get = |infeed: &str, schedule: &str| {
        rows.iter()
            .find(|r| r["infeed"].as_str().unwrap().starts_with(infeed) && r["schedule"] == schedule)
            .unwrap_or_else(|| panic!("{infeed} {schedule}: {rows:#?}"))
            .clone()
    };
    let radial = get("radial", "constant-depth");
    let flank = get("flank", "constant-depth");
    assert!(flank["two_flank_passes"].as_u64().unwrap() < radial["two_flank_passes"].as_u64().unwrap());
    assert!(flank["trailing_share"].as_f64().unwrap() < radial["trailing_share"].as_f64().unwrap());
}

/// Every Acme limit of the check set, at 0.0001 in.
#[test]
fn acme_limits_match_the_check_set() {
    let t = data_toml("acme-limits.toml");
    let checks = t["check"].as_array().unwrap();
    assert_eq!(checks.len(), 7);
    let keys = [
        ("d_max", true, 0),
        ("d_min", true, 1),
        ("d2_max", true, 2),
        ("d2_min", true, 3),
        ("d3_max", true, 4),
        ("d3_min", true, 5),
        ("D1_max", false, 6),
    ];
    for c in checks {
        let name = c["designation"].as_str().unwrap();
        let d = des(name);
        for side in ["external", "internal"] {
            let Some(vals) = c.get(side) else { continue };
            let kind = if side == "external" { ThreadKind::External } else { ThreadKind::Internal };
            let l = limits_for(&d, kind).unwrap().unwrap();
            for (key, _, which) in keys {
                let Some(want) = vals.get(key).and_then(|v| v.as_float()) else { continue };
                let got = match which {
                    0 => l.major_diameter.max,
                    1 => l.major_diameter.min,
                    2 => l.pitch_diameter.max,
                    3 => l.pitch_diameter.min,
                    4 => l.minor_diameter.max,
                    5 => l.minor_diameter.min,
                    _ => l.minor_diameter.max,
                }
                .unwrap()
                    / IN;
                assert!((got - want).abs() < 0.5e-4 + 1e-9, "{name} {key}: {got:.5}, published {want}");
            }
        }
    }
}

/// A full-profile Acme insert (flat tip, 29°) cut to d3 = D − P − c measures the basic pitch
/// diameter E = D − 0.5·P to 0.1 µm; the solved mid-tolerance cut passes, the crest left as turned.
#[test]
fn acme_full_profile_cuts_the_basic_pitch_diameter() {
    for (name, d, tpi) in
        [("1/2-10 ACME-2G", 0.5, 10.0), ("1-5 ACME-3G", 1.0, 5.0), ("1/4-16 ACME-4G", 0.25, 16.0)]
    {
        let p = IN / tpi;
        let c = if tpi <= 10.0 { 0.020 } else { 0.010 } * IN;
        let x3 = format!("{}", d * IN - p - c);
        let o = run(&[
            "verify",
            "--thread",
            name,
            "--insert",
            "full",
            "--final-x",
            &x3,
            "--no-pass-metrics",
            "--json",
            "-",
        ]);
        let v: serde_json::Value =
            serde_json::from_slice(&o.stdout).unwrap_or_else(|_| panic!("{name}: {}", stderr(&o)));
        let d2 = v["measured"]["pitch_diameter"].as_f64().unwrap();
        assert!((d2 - (d * IN - 0.5 * p)).abs() < 1e-4, "{name}: d2 {d2} (to 0.1 µm)");
        assert_eq!(v["insert"]["angle"], 29.0);
        let o = run(&["verify", "--thread", name, "--insert", "full", "--no-pass-metrics"]);
        assert_eq!(o.status.code(), Some(0), "{name}: {}", stdout(&o));
    }
}

/// NPT and ISO 7-1: sizes, the gauge plane's basic pitch diameter and distance (the reference
/// tables: NPT E1/L1 in inches, ISO 7-1 gauge-plane d2 and gauge length in mm).
#[test]
fn taper_pipe_designations_and_gauge_planes() {
    let npt = des("1/2-14 NPT");
    assert!((npt.thread.pitch - IN / 14.0).abs() < 1e-12);
    let l = limits_for(&npt, ThreadKind::External).unwrap().unwrap();
    let gp = l.gauge_plane.unwrap();
    assert!((gp.pitch_diameter - 0.77843 * IN).abs() < 1e-9 && (gp.distance - 0.320 * IN).abs() < 1e-9);
    assert!((gp.taper - 1.0 / 16.0).abs() < 1e-15 && gp.tolerance_turns == 1.0);
    assert_eq!(limits_for(&npt, ThreadKind::Internal).unwrap().unwrap().gauge_plane.unwrap().distance, 0.0);
    assert!((des("1-1/4-11.5 NPT").thread.pitch - IN / 11.5).abs() < 1e-12);
    let r = des("R 1/8");
    assert!(r.external.is_some() && r.internal.is_none());
    let gp = limits_for(&r, ThreadKind::External).unwrap().unwrap().gauge_plane.unwrap();
    assert_eq!((gp.pitch_diameter, gp.distance), (9.147, 3.97));
    assert!(des("R1/8").external.is_some());
    assert!(des("Rc 1/4").internal.is_some());
    let e = parse_designation("Rp 1/2", ParseOptions::default()).unwrap_err().to_string();
    assert!(e.contains("Rp") && e.contains("not in the sources"), "{e}");
}

/// A G92 program for 1/2-14 NPT: R −0.5625 = (radius at Z2) − (radius at Z−16) makes the 1:16
/// cone, and the last pass ends at X18.9127. With a full-profile insert the pitch line is 0.4·P
/// above the root: at the basic gauge plane (L1 = 0.320 in from the small end at Z0) X is
/// 18.9127 − (16 − 8.128)/16 = 18.4207, so E = 18.4207 + 0.8·P = 19.8721, 0.1000 mm over E1 =
/// 19.7721: the gauge stops 16·0.1000 = 1.600 mm, −0.882 turns, further out. The same program
/// with the R sign turned cuts the cone the wrong way: the taper check fails.
#[test]
fn npt_program_gauge_plane_and_taper() {
    let p = IN / 14.0;
    let x_gp = 18.9127 - (16.0 - 0.320 * IN) / 16.0;
    let e = x_gp + 0.8 * p;
    let want = -16.0 * (e - 0.77843 * IN) / p;
    let run_json = |prog: &str| {
        let prog = data(&format!("programs/{prog}"));
        let o = run(&[
            "verify",
            "--program",
            prog.to_str().unwrap(),
            "--thread",
            "1/2-14 NPT",
            "--insert",
            "full",
            "--no-pass-metrics",
            "--json",
            "-",
        ]);
        let v: serde_json::Value =
            serde_json::from_slice(&o.stdout).unwrap_or_else(|_| panic!("{}", stderr(&o)));
        (o.status.code(), v["operations"][0]["checks"].as_array().unwrap().clone())
    };
    let (code, checks) = run_json("fanuc-g92-npt-1-2.nc");
    assert_eq!(code, Some(0));
    let gp = checks.iter().find(|c| c["feature"] == "gauge_plane").unwrap()["value"].as_f64().unwrap();
    // The section is sheared along the cone to measure it; that reads E 0.5 µm off the
    // symmetric-V value (a second-order effect of the 1.79° cone): 0.01 turn is 1.1 µm on E.
    assert!((gp - want).abs() < 0.01, "{gp} turns, derived {want}");
    let (code, checks) = run_json("fanuc-g92-npt-wrong-r.nc");
    assert_eq!(code, Some(1));
    let taper = checks.iter().find(|c| c["feature"] == "taper").unwrap();
    assert_eq!(taper["ok"], false);
    assert!((taper["value"].as_f64().unwrap() + 1.0 / 16.0).abs() < 1e-9);
}

/// `--units inch` gives the report in inches with the mm beside them, in the text and the SVG:
/// 1/4-20 UNC-2A's d2 limits are 0.2127 and 0.2164 in (ASME B1.1's table), 5.4026 and 5.4966 mm.
#[test]
fn units_inch_in_the_text_and_the_svg() {
    let dir = tempdir("units");
    let svg = dir.join("un.svg");
    let o = run(&[
        "verify",
        "--thread",
        "1/4-20 UNC-2A",
        "--insert",
        "full",
        "--units",
        "inch",
        "--no-pass-metrics",
        "--svg",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = stdout(&o);
    let line = out.lines().find(|l| l.contains("✓ pitch diameter")).unwrap();
    let cells: Vec<&str> = line.split_whitespace().collect();
    assert_eq!(cells[4..6], ["0.2127", "0.2164"], "{line}");
    assert!(line.contains("5.4026") && line.contains("5.4966") && line.ends_with(" mm"), "{line}");
    let picture = std::fs::read_to_string(&svg).unwrap();
    assert!(picture.contains("d2 0.2") && picture.contains(" in (5."), "no inch label in the SVG");
    assert!(picture.contains("0.2127 – 0.2164"), "the SVG's check table is not in inches");
    let e = run(&["verify", "--thread", "1/4-20 UNC-2A", "--units", "furlong"]);
    assert_eq!(e.status.code(), Some(2));
}

/// Regression: on an 11-tpi ISO 7-1 thread cut with a full-profile insert, neighbouring turns
/// top the crest at heights 1/32 of a pitch apart; that notch in the crest was counted as a
/// second root pocket and `one groove` failed. Pockets are counted below mid-depth.
#[test]
fn regression_crest_notch_on_a_taper_is_not_a_second_pocket() {
    for size in ["R 1", "R 2"] {
        let o = run(&[
            "verify",
            "--thread",
            size,
            "--insert",
            "full",
            "--infeed",
            "radial",
            "--no-pass-metrics",
            "--json",
            "-",
        ]);
        assert_eq!(o.status.code(), Some(0), "{size}: {}", stdout(&o));
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        let g =
            v["checks"].as_array().unwrap().iter().find(|c| c["feature"] == "single_groove").unwrap().clone();
        assert_eq!(g["ok"], true, "{size}: {g}");
    }
}
