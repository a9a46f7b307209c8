//! Issue 2: limits of size against published tables, properties over the whole series, the
//! designation parser's errors, and the `limits` command.

use crate::*;
use proptest::prelude::*;
use threadcheck::{iso_limits, limits_for, IsoClass};
use threadcheck::{parse_designation, ParseOptions, ThreadKind};

fn close(got: Option<f64>, want: f64, what: &str) {
    let g = got.unwrap_or_else(|| panic!("{what}: missing"));
    assert!((g - want).abs() < 0.0005, "{what}: got {g}, published {want}");
}

fn f(v: &toml::Value, k: &str) -> f64 {
    v.get(k)
        .and_then(|x| x.as_float().or_else(|| x.as_integer().map(|i| i as f64)))
        .unwrap_or_else(|| panic!("key {k}"))
}

/// Every 6g and 6H limit set of ISO 965-2 in tests/data/iso965-limits.toml, to 0.001 mm.
#[test]
fn iso965_published_limits_are_reproduced() {
    let doc = data_toml("iso965-limits.toml");
    let threads = doc["thread"].as_array().unwrap();
    assert!(threads.len() >= 4);
    for t in threads {
        let name = t["designation"].as_str().unwrap();
        let des = parse_designation(name, ParseOptions::default()).unwrap();
        let e = limits_for(&des, ThreadKind::External).unwrap().unwrap();
        let i = limits_for(&des, ThreadKind::Internal).unwrap().unwrap();
        let x = &t["external"];
        close(e.major_diameter.max, f(x, "d_max"), &format!("{name} d max"));
        close(e.major_diameter.min, f(x, "d_min"), &format!("{name} d min"));
        close(e.pitch_diameter.max, f(x, "d2_max"), &format!("{name} d2 max"));
        close(e.pitch_diameter.min, f(x, "d2_min"), &format!("{name} d2 min"));
        close(e.minor_diameter.max, f(x, "d1_max"), &format!("{name} d1 + es"));
        close(e.minor_diameter.min, f(x, "d3_min"), &format!("{name} d3 min"));
        assert_eq!(e.fundamental_deviation_um, f(t, "es_um"), "{name} es");
        let n = &t["internal"];
        close(i.minor_diameter.min, f(n, "D1_min"), &format!("{name} D1 min"));
        close(i.minor_diameter.max, f(n, "D1_max"), &format!("{name} D1 max"));
        close(i.pitch_diameter.min, f(n, "D2_min"), &format!("{name} D2 min"));
        close(i.pitch_diameter.max, f(n, "D2_max"), &format!("{name} D2 max"));
        close(i.major_diameter.min, f(n, "D_min"), &format!("{name} D min"));
        assert_eq!(i.major_diameter.max, None);
    }
}

/// ISO 228-1 G1/8, G1/4 (iso965-limits.toml) and G1/2, G1 (bsp-limits.toml): basic sizes and the
/// class A, B and internal limits.
#[test]
fn iso228_basic_sizes_and_limits() {
    let mut pipes = data_toml("iso965-limits.toml")["pipe"].as_array().unwrap().clone();
    pipes.extend(data_toml("bsp-limits.toml")["pipe"].as_array().unwrap().iter().cloned());
    assert_eq!(pipes.len(), 4);
    for p in &pipes {
        let name = p["designation"].as_str().unwrap();
        let (d, d2, d1) = (f(p, "d"), f(p, "d2"), f(p, "d1"));
        let int = parse_designation(name, ParseOptions::default()).unwrap();
        assert!((int.thread.pitch - 25.4 / f(p, "tpi")).abs() < 1e-12);
        let il = limits_for(&int, ThreadKind::Internal).unwrap().unwrap();
        close(il.major_diameter.min, d, &format!("{name} D"));
        close(il.pitch_diameter.min, d2, &format!("{name} D2 min"));
        close(il.pitch_diameter.max, d2 + f(p, "TD2_internal"), &format!("{name} D2 max"));
        close(il.minor_diameter.min, d1, &format!("{name} D1 min"));
        close(il.minor_diameter.max, d1 + f(p, "TD1_internal"), &format!("{name} D1 max"));
        for (cls, td2) in [("A", f(p, "Td2_class_A")), ("B", f(p, "Td2_class_B"))] {
            let des = parse_designation(&format!("{name} {cls}"), ParseOptions::default()).unwrap();
            let el = limits_for(&des, ThreadKind::External).unwrap().unwrap();
            close(el.major_diameter.max, d, &format!("{name} {cls} d max"));
            close(el.major_diameter.min, d - f(p, "Td_external"), &format!("{name} {cls} d min"));
            close(el.pitch_diameter.max, d2, &format!("{name} {cls} d2 max"));
            close(el.pitch_diameter.min, d2 - td2, &format!("{name} {cls} d2 min"));
            close(el.minor_diameter.max, d1, &format!("{name} {cls} d1"));
        }
    }
}

fn all_series() -> Vec<(f64, f64)> {
    let cat = threadcheck::catalog().unwrap();
    let mut v = Vec::new();
    for s in &cat.iso.series.sizes {
        v.extend(s.coarse.map(|p| (s.d, p)));
        v.extend(s.fine.iter().map(|&p| (s.d, p)));
    }
    v
}

fn class(s: &str) -> IsoClass {
    IsoClass::parse(s).unwrap()
}

fn thread(d: f64, p: f64) -> threadcheck::BasicThread {
    parse_designation(&format!("M{d}x{p}"), ParseOptions::default()).unwrap().thread
}

/// Over every ISO 261 pair and every class: max > min, tolerances never shrink with the grade,
/// and es(e) < es(f) < es(g) < es(h) = 0.
#[test]
fn series_properties_hold_for_every_size_and_class() {
    let pairs = all_series();
    assert!(pairs.len() > 150);
    for &(d, p) in &pairs {
        let t = thread(d, p);
        let mut prev_ext: Option<(f64, f64)> = None;
        for g in [3u8, 4, 5, 6, 7, 8, 9] {
            let crest = if g <= 4 {
                4
            } else if g <= 6 {
                6
            } else {
                8
            };
            let l = iso_limits(&t, &class(&format!("{g}h{crest}h"))).unwrap();
            for lim in [&l.major_diameter, &l.pitch_diameter, &l.minor_diameter] {
                assert!(lim.max.unwrap() > lim.min.unwrap(), "M{d}x{p} {g}h");
            }
            let td2 = l.pitch_diameter.max.unwrap() - l.pitch_diameter.min.unwrap();
            let td = l.major_diameter.max.unwrap() - l.major_diameter.min.unwrap();
            if let Some((ptd2, ptd)) = prev_ext {
                assert!(td2 >= ptd2 - 1e-9 && td >= ptd - 1e-9, "M{d}x{p} grade {g} shrinks");
            }
            prev_ext = Some((td2, td));
        }
        if p >= 0.3 {
            let mut prev: Option<(f64, f64)> = None;
            for g in [4u8, 5, 6, 7, 8] {
                let l = iso_limits(&t, &class(&format!("{g}H"))).unwrap();
                let td2 = l.pitch_diameter.max.unwrap() - l.pitch_diameter.min.unwrap();
                let td1 = l.minor_diameter.max.unwrap() - l.minor_diameter.min.unwrap();
                assert!(td2 > 0.0 && td1 > 0.0);
                if let Some((a, b)) = prev {
                    assert!(td2 >= a - 1e-9 && td1 >= b - 1e-9, "M{d}x{p} {g}H shrinks");
                }
                prev = Some((td2, td1));
            }
        }
        if p >= 0.5 {
            let es: Vec<f64> = ["6e", "6f", "6g", "6h"]
                .iter()
                .map(|c| iso_limits(&t, &class(c)).unwrap().fundamental_deviation_um)
                .collect();
            assert!(es[0] < es[1] && es[1] < es[2] && es[2] < es[3] && es[3] == 0.0, "M{d}x{p}: {es:?}");
            let ei_g = iso_limits(&t, &class("6G")).unwrap().fundamental_deviation_um;
            assert!(ei_g > 0.0 && ei_g == -es[2]);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    /// Random text never panics the parser; errors are one line.
    #[test]
    fn parser_never_panics(s in "\\PC{0,24}") {
        if let Err(e) = parse_designation(&s, ParseOptions::default()) {
            prop_assert!(!e.to_string().contains('\n'));
        }
    }

    /// Text shaped like a designation never panics either, with or without --allow-nonstandard.
    #[test]
    fn designation_shaped_text_never_panics(s in "(M|G|BSW |BSF |m|Q)[0-9./ x-]{0,6}(Ph[0-9.]{0,3}P[0-9.]{0,3})?(-[0-9][a-zA-Z])?(/[0-9][a-zA-Z])?( (A|B|medium|free|LH))?", ns in any::<bool>()) {
        let _ = parse_designation(&s, ParseOptions { allow_nonstandard: ns });
    }
}

#[test]
fn limits_command_runs_from_any_folder() {
    let dir = tempdir("anyfolder");
    let o = run_in(&dir, &["limits", "M10-6H/6g"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let s = stdout(&o);
    // ISO 965-2 M10 6g and 6H values.
    for v in ["9.968", "8.862", "7.938", "9.206", "8.676"] {
        assert!(s.contains(v), "missing {v} in\n{s}");
    }
}

#[test]
fn limits_json_follows_the_contract() {
    let o = run(&["limits", "M10x1.25-6g", "--json"]);
    assert_eq!(o.status.code(), Some(0));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    // The example object of the CLI contract (shared/spec/cli.md), whose values are ISO 965-2's.
    assert_eq!(v["designation"], "M10x1.25-6g");
    assert_eq!(v["form"], "iso-metric");
    assert_eq!(v["pitch"], 1.25);
    assert_eq!(v["basic"]["pitch_diameter"], 9.188);
    assert_eq!(v["basic"]["minor_diameter_external"], 8.466);
    assert_eq!(v["basic"]["minor_diameter_internal"], 8.647);
    assert_eq!(v["external"]["major_diameter"]["max"], 9.972);
    assert_eq!(v["external"]["major_diameter"]["min"], 9.76);
    assert_eq!(v["external"]["pitch_diameter"]["max"], 9.16);
    assert_eq!(v["external"]["pitch_diameter"]["min"], 9.042);
    assert_eq!(v["external"]["minor_diameter"]["max"], 8.619);
    assert_eq!(v["external"]["minor_diameter"]["min"], 8.272);
    assert!(v["internal"].is_null());
}

#[test]
fn bad_designations_exit_2_with_one_line() {
    for (d, part) in
        [("M10x1.3-6g", "'1.3'"), ("Q10", "column 1"), ("M10-6k", "'6k'"), ("G9/7", "'9/7'"), ("", "empty")]
    {
        let line = one_line_error(&run(&["limits", d]));
        assert!(line.contains(part), "{d}: {line}");
    }
}

/// Issue 28: NPT's gauge plane as ASME B1.20.1's Table 2 prints it, size by size: E1 at the hand-
/// tight plane, L1 from the small end (0.1615 in for 1/8 and 0.2278 in for 1/4, once 0.162 and
/// 0.228), E0 = E1 − L1/16 within the table's 5-decimal rounding, and ±1 turn of gauging
/// tolerance (ASME B1.20.1 §4.1.2: "one turn large or small").
#[test]
fn npt_gauge_plane_matches_asme_b1_20_1_table_2_for_every_size() {
    // size, tpi, E0, E1, L1 (inches), ASME B1.20.1 Table 2.
    let table = [
        ("1/16-27 NPT", 0.27118, 0.28118, 0.160),
        ("1/8-27 NPT", 0.36351, 0.37360, 0.1615),
        ("1/4-18 NPT", 0.47739, 0.49163, 0.2278),
        ("3/8-18 NPT", 0.61201, 0.62701, 0.240),
        ("1/2-14 NPT", 0.75843, 0.77843, 0.320),
        ("3/4-14 NPT", 0.96768, 0.98887, 0.339),
        ("1-11.5 NPT", 1.21363, 1.23863, 0.400),
        ("1-1/4-11.5 NPT", 1.55713, 1.58338, 0.420),
        ("1-1/2-11.5 NPT", 1.79609, 1.82234, 0.420),
        ("2-11.5 NPT", 2.26902, 2.29627, 0.436),
    ];
    for (d, e0, e1, l1) in table {
        let o = run(&["limits", d, "--json"]);
        assert_eq!(o.status.code(), Some(0), "{d}: {}", stderr(&o));
        let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
        let gp = &v["external"]["gauge_plane"];
        assert!((gp["pitch_diameter"].as_f64().unwrap() - e1 * 25.4).abs() < 1e-9, "{d}: E1 {gp}");
        assert!((gp["distance"].as_f64().unwrap() - l1 * 25.4).abs() < 1e-9, "{d}: L1 {gp}");
        assert_eq!(gp["tolerance_turns"].as_f64(), Some(1.0), "{d}");
        // The table's own consistency: E1 − E0 = L1 · 1/16 to its rounding of E.
        assert!(((e1 - e0) - l1 / 16.0).abs() <= 1e-5, "{d}: E1 − E0 against L1/16");
    }
}

/// Issue 28: an NPT size is named by its pipe's outside diameter (ASME B1.20.1's D: 0.840 in for
/// 1/2, 0.405 in for 1/8), not by its thread's major diameter at the gauge plane (E1 + 0.8·P).
#[test]
fn npt_nominal_diameter_is_the_pipe_outside_diameter() {
    for (d, od) in [("1/2-14 NPT", 0.840), ("1/8-27 NPT", 0.405), ("2-11.5 NPT", 2.375)] {
        let v: serde_json::Value = serde_json::from_str(&stdout(&run(&["limits", d, "--json"]))).unwrap();
        assert!(
            (v["nominal_diameter"].as_f64().unwrap() - od * 25.4).abs() < 1e-9,
            "{d}: {}",
            v["nominal_diameter"]
        );
    }
}

/// Issue 48: a designation without a class is told the classes its own standard has: BS 84's
/// close/medium/free, ISO 2903's 7e/7H, ASME B1.1's 2A/2B, ASME B1.5's 2G, ISO 965's 6g/6H (it
/// suggested 6g/6H for every form).
#[test]
fn a_missing_class_is_suggested_in_the_standards_own_words() {
    for (d, says) in [
        ("BSW 1/2", "e.g. BSW 1/2 medium"),
        ("Tr40x7", "e.g. Tr40x7-7e or Tr40x7-7H"),
        ("1/2-13 UNC", "e.g. 1/2-13 UNC-2A or 1/2-13 UNC-2B"),
        ("1/2-10 ACME", "e.g. 1/2-10 ACME-2G"),
        ("M10x1.5", "e.g. M10x1.5-6g or M10x1.5-6H"),
    ] {
        let o = run(&["limits", d]);
        assert!(stdout(&o).contains(says), "{d}: {}", stdout(&o));
    }
}

/// Issue 64, rolled threads. M10x1.5-6g: the dies set d2 at 6g's middle 8.928; their crests form
/// the root at 8.928 − 2H/3 = 8.062, the full crest stands at 8.928 + 3H/4 = 9.902 (H = 1.299).
/// By hand, planar areas at their centroid radii: with the blank at d2 the groove below it
/// (0.25 → 0.75 mm wide over 0.433 mm: 0.2165 mm² at r ≈ 4.28) is short of the tooth above it
/// (0.75 → 0.1875 mm over 0.487 mm: 0.2283 mm² at r ≈ 4.69); a blank δ over the pitch radius moves
/// 0.75·δ from one to the other: 0.2165·4.28 + 0.75δ·4.464 = (0.2283 − 0.75δ)·4.69, δ ≈ 0.021,
/// blank ≈ 8.970 (shop charts give M10 roll blanks of about 8.95–9.0).
#[test]
fn a_rolled_thread_gives_its_blank_and_what_a_blank_gives() {
    let o = run(&["limits", "M10x1.5-6g", "--rolled", "--json", "-"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let r = &v["rolled"];
    assert!((r["pitch_diameter"].as_f64().unwrap() - 8.928).abs() < 1e-9);
    assert!((r["root_diameter"].as_f64().unwrap() - (8.928 - 1.5 * 3f64.sqrt() / 3.0)).abs() < 1e-9);
    assert!((r["full_crest"].as_f64().unwrap() - (8.928 + 0.75 * 1.5 * 3f64.sqrt() / 2.0)).abs() < 1e-9);
    let blank = r["blank_for_full_crest"].as_f64().unwrap();
    assert!((blank - 8.970).abs() < 0.003, "{blank}");
    // 1-8 UNC-2A from a 0.912 in blank: short of the 0.9165 in that fills it, the major forms
    // under 2A's smallest, 0.9830 in (ASME B1.1, LE = D): exit 1, the crest short.
    let o = run(&["limits", "1-8 UNC-2A", "--blank", "0.912", "--json", "-"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let r = &v["rolled"];
    let major = r["major_formed"].as_f64().unwrap() / 25.4;
    assert!(major > 0.9135 && major < 0.9830, "{major}");
    assert_eq!(
        (&r["major_ok"], &r["crest_short"]),
        (&serde_json::Value::Bool(false), &serde_json::Value::Bool(true))
    );
    // A nut is not rolled.
    let o = run(&["limits", "M10x1.5-6H", "--rolled"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("a rolled thread is external"), "{}", stderr(&o));
}
