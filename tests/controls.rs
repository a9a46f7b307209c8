//! Issue 27: controls beyond the first five. Fanuc G-code systems B and C: the same functions
//! under other codes (the G-code list of Fanuc's lathe operator's manuals, systems A, B, C;
//! docs/dialects.md), read into system A's passes. Pass lists derived by hand in the comments.

use crate::*;

/// The passes' final X of `passes --json` for `program` with `args`.
fn pass_xs(program: &str, args: &[&str]) -> (Vec<Vec<f64>>, serde_json::Value) {
    let p = data(&format!("programs/{program}"));
    let mut all = vec!["passes", "--program", p.to_str().unwrap(), "--json", "-"];
    all.extend(args);
    let o = run(&all);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let ops = v["operations"]
        .as_array()
        .unwrap()
        .iter()
        .map(|op| op["passes"].as_array().unwrap().iter().map(|q| q["x_end"].as_f64().unwrap()).collect())
        .collect();
    (ops, v)
}

fn close(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-9)
}

/// System B: G78 is the threading cycle (system A's G92), one pass per X word, the X-only
/// blocks repeating it; G92 S is the spindle clamp (A's G50); G91 makes X and Z incremental,
/// each repeat's X from the cycle's start point X22 (X−2.8 → 19.2, X−3.2 → 18.8), Z−25 from Z5 →
/// −20.
#[test]
fn system_b_g78_is_the_threading_cycle() {
    let (ops, v) = pass_xs("fanuc-system-b-g78.nc", &["--gcode-system", "b"]);
    assert!(close(&ops[0], &[19.2, 18.8, 18.5, 18.3, 18.2]), "{ops:?}");
    assert!(close(&ops[1], &[19.2, 18.8]), "{ops:?}");
    let op2 = &v["operations"][1];
    assert_eq!(op2["cycle"], "G78");
    assert!(op2["passes"].as_array().unwrap().iter().all(|p| p["z_end"] == -20.0));
    let notes = v["notes"].to_string();
    assert!(notes.contains("G-code system B"), "{notes}");
    // Verified: the last pass at X18.2 with a full-profile insert cuts d2 = X + (d2 − d3) =
    // 18.2 + 0.866 = 19.066, 72 µm over 6g's 18.994 (the G76 sheet's figure), and the
    // correction names the program's own G78 repeat.
    let p = data("programs/fanuc-system-b-g78.nc");
    let (code, v) = run_json(&[
        "verify",
        "--thread",
        "M20x1.5-6g",
        "--program",
        p.to_str().unwrap(),
        "--insert",
        "full",
        "--gcode-system",
        "b",
        "--json",
        "-",
    ]);
    assert_eq!(code, 1);
    let d2 = check_of(&v["operations"][0], "pitch_diameter");
    assert!((d2["deviation_um"].as_f64().unwrap() - 72.0).abs() < 0.05, "{d2}");
    assert_eq!(v["operations"][0]["correction"]["line"], 11);
}

/// System C: G78 is the multiple threading cycle (A's G76) in its two-block form, G21 the
/// single threading cycle (A's G92), G71 metric input (A's G21), G70 inch input.
/// Fanuc's G76 law with k = 0.9, Δd = 0.3, Δd min 0.1, d = 0.02: the nth depth is
/// Δd·√n of k − d, X = 18.2 + 2d + 2(k − d − Δd√n): n = 1 → 19.4, n = 2 → 19.1515; from n = 3
/// the step Δd(√3 − √2) = 0.095 is under Δd min, so 0.1 a pass: 18.9515, 18.7515, 18.5515,
/// 18.3515; then k − d (18.24) and the finishing pass at 18.2.
#[test]
fn system_c_g78_is_the_multiple_threading_cycle() {
    let (ops, v) = pass_xs("fanuc-system-c-g78.nc", &["--gcode-system", "c"]);
    let x = |depth: f64| 18.24 + 2.0 * (0.88 - depth);
    let d2 = 0.3 * 2f64.sqrt();
    let expected = [x(0.3), x(d2), x(d2 + 0.1), x(d2 + 0.2), x(d2 + 0.3), x(d2 + 0.4), 18.24, 18.2];
    assert!(close(&ops[0], &expected), "{ops:?} against {expected:?}");
    assert!(close(&ops[1], &[19.0, 18.6]), "{ops:?}");
    assert_eq!(v["operations"][0]["cycle"], "G78");
    assert_eq!(v["operations"][1]["cycle"], "G21");
    assert!(v["operations"][0]["passes"].as_array().unwrap().iter().all(|p| p["lead"] == 1.5));
    // G70 is inch input in system C: F1.5 is then 1.5 in = 38.1 mm of lead.
    let dir = tempdir("system-c-inch");
    let text = std::fs::read_to_string(data("programs/fanuc-system-c-g78.nc"))
        .unwrap()
        .replace("G71 G97", "G70 G97");
    std::fs::write(dir.join("c-inch.nc"), text).unwrap();
    let o = run_in(&dir, &["passes", "--program", "c-inch.nc", "--gcode-system", "c", "--json", "-"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!((v["operations"][0]["passes"][0]["lead"].as_f64().unwrap() - 38.1).abs() < 1e-9, "{v}");
}

/// Without the system, G78 is refused with the systems that define it; a system of another
/// dialect is refused; system A's codes read in B are not A's.
#[test]
fn g78_is_never_read_without_its_system() {
    for (program, args, line) in [
        (
            "fanuc-system-b-g78.nc",
            vec![],
            "fanuc-system-b-g78.nc:7:1: G78 is not a code of Fanuc G-code system A, which this program is read in: a control set to system B reads it as the threading cycle (G92 in A), one set to system C as the multiple threading cycle (G76 in A); give --gcode-system b or c (the EMCO training lathe's G78 box cycle is not supported)",
        ),
        (
            "haas-g76-metric.nc",
            vec!["--dialect", "haas", "--gcode-system", "b"],
            "G-code system B is a setting of Fanuc lathe controls: a haas program has one G-code list (read it as --dialect fanuc, or leave --gcode-system out)",
        ),
    ] {
        let p = data(&format!("programs/{program}"));
        let dir = p.parent().unwrap();
        let mut all = vec!["passes", "--program", program];
        all.extend(args);
        let o = run_in(dir, &all);
        assert_eq!(o.status.code(), Some(2));
        assert_eq!(stderr(&o).trim(), format!("threadcheck: error: {line}"));
    }
    // System B has no G32 (its thread cutting is G33): a G32 pass depends on a code it does not know.
    let dir = tempdir("system-b-g32");
    std::fs::write(dir.join("b.nc"), "G21 G97 S500 M3\nG0 X22 Z5\nG32 X19 Z-20 F1.5\n").unwrap();
    let o = run_in(&dir, &["passes", "--program", "b.nc", "--gcode-system", "b"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let g33 = "G21 G97 S500 M3\nG0 X22 Z5\nG33 X19 Z-20 F1.5\n";
    std::fs::write(dir.join("b33.nc"), g33).unwrap();
    let o = run_in(&dir, &["passes", "--program", "b33.nc", "--gcode-system", "b", "--json", "-"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["operations"][0]["cycle"], "G33");
    assert_eq!(v["passes"][0]["x_end"], 19.0);
}

/// Okuma OSP G33 is a fixed cycle: one pass per block from the start point, each X-only block
/// one more pass at its diameter (OSP-P200L p. 97; CIMCO's OSP samples). With a full-profile
/// insert the last pass at X18.16 cuts d2 = 18.16 + (d2 − d3 basic) = 18.16 + 0.866025 = 19.026:
/// 32 µm over 6g's 18.994.
#[test]
fn okuma_g33_fixed_cycle_repeats_on_x_only_blocks() {
    let (ops, v) = pass_xs("okuma-g33-repeats.min", &[]);
    assert!(close(&ops[0], &[19.4, 19.0, 18.6, 18.3, 18.16]), "{ops:?}");
    assert!(v["passes"].as_array().unwrap().iter().all(|p| p["z_start"] == 5.0 && p["z_end"] == -20.0));
    assert!(v["notes"].to_string().contains("read as okuma, the dialect of its extension .min"));
    let p = data("programs/okuma-g33-repeats.min");
    let (code, v) = run_json(&[
        "verify",
        "--thread",
        "M20x1.5-6g",
        "--program",
        p.to_str().unwrap(),
        "--insert",
        "full",
        "--json",
        "-",
    ]);
    assert_eq!(code, 1);
    let d2 = check_of(&v["operations"][0], "pitch_diameter");
    assert!((d2["value"].as_f64().unwrap() - 19.026).abs() < 1e-4, "{d2}");
    assert!((d2["deviation_um"].as_f64().unwrap() - 32.0).abs() < 0.1, "{d2}");
    // The correction names the last repeat's X.
    assert_eq!(v["operations"][0]["correction"]["line"], 9);
}

/// Okuma G71, the compound threading cycle, for M74x2 (H = 2·0.61343·P = 2.454 on the diameter,
/// X71.546 the root; D0.4 and U0.1 diameters; B60 with M32: along one flank at 30°).
/// Pattern 1 (M73, the named default n·D): depths 0.4, 0.8, 1.2, 1.6, 2.0, then H − U = 2.354
/// and the finishing pass at H; X = 71.546 + (2.454 − depth), the start Z moved back along the
/// flank by depth/2 · tan 30°. Pattern 3 (M75, Okuma 3277-E): √n·0.4 while under 2.354
/// (n = 1 … 34, 0.4·√34 = 2.332), then 2.354 and 2.454: 36 passes.
#[test]
fn okuma_g71_patterns_1_and_3_with_single_blade_infeed() {
    let (ops, v) = pass_xs("okuma-g71-m74x2.min", &[]);
    let depths1 = [0.4, 0.8, 1.2, 1.6, 2.0, 2.354, 2.454];
    let x1: Vec<f64> = depths1.iter().map(|d| 71.546 + (2.454 - d)).collect();
    assert!(close(&ops[0], &x1), "{ops:?}");
    let z1: Vec<f64> = v["operations"][0]["passes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["z_start"].as_f64().unwrap())
        .collect();
    let t = 30f64.to_radians().tan();
    assert!(close(&z1, &depths1.map(|d| 5.0 - 0.5 * d * t)), "{z1:?}");
    let mut depths3: Vec<f64> = (1..=34).map(|n| 0.4 * f64::from(n).sqrt()).collect();
    depths3.extend([2.354, 2.454]);
    let x3: Vec<f64> = depths3.iter().map(|d| 71.546 + (2.454 - d)).collect();
    assert!(close(&ops[1], &x3), "{} passes: {:?}", ops[1].len(), ops[1]);
    let notes = v["operations"][0]["notes"].to_string();
    assert!(
        notes.contains(
            "M73 (pattern 1) taken as a constant depth D = 0.4 mm (diameter) per pass: a named default"
        ),
        "{notes}"
    );
    // Verified: the finishing pass's tip on d3 = 71.546 with a full-profile insert cuts the basic
    // d2 72.701, 37.7 µm over 6g's 72.663 (es = −38 µm on M74x2).
    let p = data("programs/okuma-g71-m74x2.min");
    let (code, v) = run_json(&[
        "verify",
        "--thread",
        "M74x2-6g",
        "--allow-nonstandard",
        "--program",
        p.to_str().unwrap(),
        "--insert",
        "full",
        "--json",
        "-",
    ]);
    assert_eq!(code, 1);
    for op in v["operations"].as_array().unwrap() {
        let d2 = check_of(op, "pitch_diameter");
        assert!((d2["deviation_um"].as_f64().unwrap() - 37.7).abs() < 0.1, "{d2}");
    }
}
