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

/// `verify --thread THREAD --program tests/data/programs/PROGRAM --insert full --json -` with
/// `extra` flags: the exit code and the JSON.
fn verify_full(program: &str, thread: &str, extra: &[&str]) -> (i32, serde_json::Value) {
    let p = data(&format!("programs/{program}"));
    let mut args = vec!["verify", "--thread", thread, "--program", p.to_str().unwrap(), "--insert", "full"];
    args.extend_from_slice(extra);
    args.extend(["--json", "-"]);
    run_json(&args)
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
    let (code, v) = verify_full("fanuc-system-b-g78.nc", "M20x1.5-6g", &["--gcode-system", "b"]);
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

/// Without the system, and without a word that shows it (issue 45: a G91 is system B's or C's,
/// so the program is read in B, said), G78 is refused with the systems that define it; a system
/// of another dialect is refused; system A's codes read in B are not A's.
#[test]
fn g78_is_never_read_without_its_system() {
    // The system-B program's G91 at line 13 shows its system.
    let p = data("programs/fanuc-system-b-g78.nc");
    let o = run_in(p.parent().unwrap(), &["passes", "--program", "fanuc-system-b-g78.nc"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("read in Fanuc G-code system B, as its own words show: line 13:1 writes G91, which system A does not have"),
        "{}",
        stdout(&o)
    );
    // Without that part (lines 13–17), nothing in it shows the system.
    let dir = tempdir("system-b-unshown");
    let text = std::fs::read_to_string(&p).unwrap();
    let first: Vec<&str> = text.lines().take(12).collect();
    std::fs::write(dir.join("fanuc-system-b-g78.nc"), format!("{}\nM30\n%\n", first.join("\n"))).unwrap();
    for (program, at, args, line) in [
        (
            "fanuc-system-b-g78.nc",
            &*dir as &std::path::Path,
            vec![],
            "fanuc-system-b-g78.nc:7:1: G78 is not a code of Fanuc G-code system A, which this program is read in: a control set to system B reads it as the threading cycle (G92 in A), one set to system C as the multiple threading cycle (G76 in A); give --gcode-system b or c (the EMCO training lathe's G78 box cycle is not supported)",
        ),
        (
            "haas-g76-metric.nc",
            &data("programs") as &std::path::Path,
            vec!["--dialect", "haas", "--gcode-system", "b"],
            "G-code system B is a setting of Fanuc-family lathe controls (fanuc, mitsubishi, mazak): a haas program has one G-code list (leave --gcode-system out)",
        ),
    ] {
        let mut all = vec!["passes", "--program", program];
        all.extend(args);
        let o = run_in(at, &all);
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
    let (code, v) = verify_full("okuma-g33-repeats.min", "M20x1.5-6g", &[]);
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
        ) && notes.contains("G71 D, U and H read as diameters")
            && notes.contains("inferred from that figure"),
        "{notes}"
    );
    // Verified: the finishing pass's tip on d3 = 71.546 with a full-profile insert cuts the basic
    // d2 72.701, 37.7 µm over 6g's 72.663 (es = −38 µm on M74x2).
    let (code, v) = verify_full("okuma-g71-m74x2.min", "M74x2-6g", &["--allow-nonstandard"]);
    assert_eq!(code, 1);
    for op in v["operations"].as_array().unwrap() {
        let d2 = check_of(op, "pitch_diameter");
        assert!((d2["deviation_um"].as_f64().unwrap() - 37.7).abs() < 0.1, "{d2}");
    }
}

/// The `z_start` of every pass of operation `op`.
fn z_starts(v: &serde_json::Value, op: usize) -> Vec<f64> {
    v["operations"][op]["passes"].as_array().unwrap().iter().map(|p| p["z_start"].as_f64().unwrap()).collect()
}

/// Each operation's pitch-diameter deviation (µm) in `verify --json` for `program`.
fn d2_deviations(program: &str, thread: &str, args: &[&str]) -> Vec<f64> {
    let p = data(&format!("programs/{program}"));
    let mut all = vec![
        "verify",
        "--thread",
        thread,
        "--program",
        p.to_str().unwrap(),
        "--insert",
        "full",
        "--json",
        "-",
    ];
    all.extend(args);
    let (code, v) = run_json(&all);
    assert_eq!(code, 1, "{v}");
    v["operations"]
        .as_array()
        .unwrap()
        .iter()
        .map(|op| check_of(op, "pitch_diameter")["deviation_um"].as_f64().unwrap())
        .collect()
}

/// Heidenhain MANUALplus G31 (4110 Pilot p. 74, User Manual p. 336) for M20x1.5, X20 the major
/// diameter, U−0.92 (outside), I0.3, from the tool at X22 Z5 to Z−20:
/// - V0 (constant cross-section): the nth cut to 0.3·√n while under 0.92 (n = 1 … 9, 0.3·√9 =
///   0.9), then 0.92: X = 20 − 2·depth; without B and P the run-in and overrun are F·S/1000 =
///   1.5·800/1000 = 1.2 mm: Z from 6.2 to −21.2.
/// - V1 (constant infeed ≤ I): ⌈0.92/0.3⌉ = 4 cuts of 0.23: X 19.54, 19.08, 18.62, 18.16; H3
///   with A30 alternates, first toward −Z: the shifts −0.23·tan 30°, 0, −0.23·tan 30°, 0.
/// - G33 single paths at X19.4, 18.8, 18.16 to Z−18, each chained with its taper run-out to
///   X22 Z−20 (one phase, no pass read as cutting nothing).
///
/// Every last cut reaches 18.16 (on the final flank lines, H3's offsets included): with a
/// full-profile insert d2 = 18.16 + 0.866025 = 19.026, 32.0 µm over 6g's 18.994.
#[test]
fn heidenhain_g31_v0_v1_h3_and_chained_g33() {
    let (ops, v) = pass_xs("heidenhain-g31-g33.nc", &["--dialect", "heidenhain"]);
    let mut v0: Vec<f64> = (1..=9).map(|n| 20.0 - 2.0 * 0.3 * f64::from(n).sqrt()).collect();
    v0.push(18.16);
    assert!(close(&ops[0], &v0), "{ops:?}");
    assert!(close(&z_starts(&v, 0), &[6.2; 10]), "{:?}", z_starts(&v, 0));
    assert!(v["operations"][0]["passes"]
        .as_array()
        .unwrap()
        .iter()
        .all(|p| (p["z_end"].as_f64().unwrap() + 21.2).abs() < 1e-9));
    assert!(close(&ops[1], &[19.54, 19.08, 18.62, 18.16]), "{ops:?}");
    let s = 0.23 * 30f64.to_radians().tan();
    assert!(close(&z_starts(&v, 1), &[5.0 - s, 5.0, 5.0 - s, 5.0]), "{:?}", z_starts(&v, 1));
    assert_eq!(v["operations"][2]["cycle"], "G33");
    assert!(close(&ops[2], &[19.4, 22.0, 18.8, 22.0, 18.16, 22.0]), "{ops:?}");
    let notes = v.to_string();
    assert!(notes.contains("FINISHED read past: a DIN PLUS section"), "{notes}");
    assert!(notes.contains("F·S/1000 = 1.2 mm with S800 rpm"), "{notes}");
    assert!(!notes.contains("cuts nothing"), "{notes}");
    for dev in d2_deviations("heidenhain-g31-g33.nc", "M20x1.5-6g", &["--dialect", "heidenhain"]) {
        assert!((dev - 32.0).abs() < 0.1, "{dev}");
    }
}

/// Fanuc's two-block G76 as Mitsubishi (M20x1.5) and Mazak (M30x2) programs write it: depth
/// after pass n = max(Δd·√n, previous + Δd min) up to the rough end k − d, then m finishing
/// passes at k; X = root + 2·(k − depth).
/// - Mitsubishi: k 0.92, Δd 0.3, Δd min 0.1, d 0.05, m 1: 0.3, 0.424264 (√2·0.3), then the
///   minimum step rules: 0.524264, 0.624264, 0.724264, 0.824264; 0.924264 passes 0.87: cut at
///   0.87; 0.92. The last at X18.16: d2 19.026, 32.0 µm over 6g.
/// - Mazak: k 1.227, Δd 0.4, Δd min 0.15, d 0.02, m 2: 0.4, 0.565685 (√2·0.4), 0.715685,
///   0.865685, 1.015685, 1.165685; 1.315685 passes 1.207: cut there; 1.227 twice. The last at
///   X27.546 (d3 basic of M30x2): d2 = 27.546 + 1.154701 (d2 − d3 = 0.57735·P) = 28.7007, 37.7 µm
///   over 6g's 28.663 (es −38 µm).
#[test]
fn mitsubishi_and_mazak_g76_read_as_the_fanuc_model() {
    let (ops, v) = pass_xs("mitsubishi-g76.nc", &["--dialect", "mitsubishi"]);
    let depths = [0.3, 0.3 * 2f64.sqrt(), 0.524264, 0.624264, 0.724264, 0.824264, 0.87, 0.92];
    let want: Vec<f64> = depths.iter().map(|d| 18.16 + 2.0 * (0.92 - d)).collect();
    assert!(ops[0].iter().zip(&want).all(|(a, b)| (a - b).abs() < 2e-6) && ops[0].len() == 8, "{ops:?}");
    assert!(v["notes"].to_string().contains("mitsubishi read as the Fanuc model"), "{}", v["notes"]);
    let (ops, v) = pass_xs("mazak-g76.nc", &["--dialect", "mazak"]);
    let depths = [0.4, 0.4 * 2f64.sqrt(), 0.715685, 0.865685, 1.015685, 1.165685, 1.207, 1.227, 1.227];
    let want: Vec<f64> = depths.iter().map(|d| 27.546 + 2.0 * (1.227 - d)).collect();
    assert!(ops[0].iter().zip(&want).all(|(a, b)| (a - b).abs() < 2e-6) && ops[0].len() == 9, "{ops:?}");
    assert!(v["notes"].to_string().contains("mazak read as the Fanuc model"), "{}", v["notes"]);
    let dev = d2_deviations("mitsubishi-g76.nc", "M20x1.5-6g", &["--dialect", "mitsubishi"]);
    assert!((dev[0] - 32.0).abs() < 0.1, "{dev:?}");
    let dev = d2_deviations("mazak-g76.nc", "M30x2-6g", &["--dialect", "mazak"]);
    assert!((dev[0] - 37.7).abs() < 0.1, "{dev:?}");
    // The G-code systems are theirs too: G78 needs one, system B reads it.
    // The same passes as system_b_g78_is_the_threading_cycle derives by hand.
    let (ops_b, _) = pass_xs("fanuc-system-b-g78.nc", &["--dialect", "mazak", "--gcode-system", "b"]);
    assert!(close(&ops_b[0], &[19.2, 18.8, 18.5, 18.3, 18.2]), "{ops_b:?}");
    assert!(close(&ops_b[1], &[19.2, 18.8]), "{ops_b:?}");
}

/// Every dialect is in the JSON schema's dialect enums (okuma was missing from them).
#[test]
fn regression_the_schema_lists_every_dialect() {
    let schema =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/json-schema.json")).unwrap();
    for d in threadcheck::Dialect::ALL {
        assert_eq!(
            schema.matches(&format!("\"{}\"", d.name())).count(),
            2,
            "{} in the schema's two dialect enums",
            d.name()
        );
    }
}

/// Sinumerik CYCLE99 read in the named order (SPL, DM1, FPL, DM2, APP, ROP, TDEP, FAL, IANG,
/// NSP, NRC, NID, PIT, VARI, NUMTH) with the thread chain CYCLE98's published VARI code
/// (docs/dialects.md, "Sinumerik CYCLE99"); the law is the Sinumerik thread cycles' (TDEP − FAL
/// in rough cuts, one finishing cut at TDEP, NID idle passes).
/// - M20x1.5, VARI 300103 (outside, degressive, one flank, NRC, roughing and finishing):
///   0.92 − 0.05 = 0.87 in NRC 6 cuts of constant cross-section, depth 0.87·√(i/6); the
///   finishing cut at 0.92 and NID 1 idle pass: X = 20 − 2·depth. IANG 30 > 0: each start
///   shifted depth·tan 30° along the feed (−Z) from SPL 0 brought forward by APP 3, so Z starts
///   3 − depth·tan 30°; every pass ends ROP 2 past FPL −25, at −27. The last at X18.16: d2 =
///   18.16 + 0.866025 = 19.026, +32.0 µm over 6g's 18.994 (ISO 965-2).
/// - Two starts of pitch 1.5 on Ø24 (lead 3), VARI 1310201 (outside, linear, alternating, MID,
///   both, every start at each depth): 0.92 − 0.1 = 0.82 in ⌈0.82/0.3⌉ = 3 cuts of 0.273333;
///   0.92; start 2 one pitch (1.5) behind start 1 at each depth. Alternating flanks, each
///   increment toward the other flank: shifts −0.273333·t, 0, −0.273333·t, −0.173333·t (t =
///   tan 30°). d2 = 22.16 + 0.866025 = 23.026, +32.0 µm over M24 6g's 22.994.
#[test]
fn sinumerik_cycle99_degressive_flank_and_two_starts() {
    let (ops, v) = pass_xs("sinumerik-cycle99.mpf", &[]);
    let mut depths: Vec<f64> = (1..=6).map(|i| 0.87 * (f64::from(i) / 6.0).sqrt()).collect();
    depths.extend([0.92, 0.92]);
    let t = 30f64.to_radians().tan();
    assert!(close(&ops[0], &depths.iter().map(|d| 20.0 - 2.0 * d).collect::<Vec<_>>()), "{ops:?}");
    assert!(close(&z_starts(&v, 0), &depths.iter().map(|d| 3.0 - d * t).collect::<Vec<_>>()), "{v}");
    let passes = v["operations"][0]["passes"].as_array().unwrap();
    assert!(passes.iter().all(|p| p["z_end"] == -27.0 && p["lead"] == 1.5), "{v}");
    let notes = v["notes"].to_string();
    assert!(notes.contains("CYCLE99 read as (SPL, DM1, FPL, DM2, APP, ROP, TDEP"), "{notes}");
    assert!(notes.contains("a named default"), "{notes}");
    assert!(
        notes.contains("outside, degressive (constant cross-section) infeed, one flank at IANG"),
        "{notes}"
    );

    let (ops, v) = pass_xs("sinumerik-cycle99-two-start.mpf", &[]);
    let xs: Vec<f64> =
        [0.82 / 3.0, 2.0 * 0.82 / 3.0, 0.82, 0.92].iter().flat_map(|d| [24.0 - 2.0 * d; 2]).collect();
    assert!(close(&ops[0], &xs), "{ops:?}");
    let shifts = [-0.82 / 3.0 * t, 0.0, -0.82 / 3.0 * t, (-0.82 / 3.0 + 0.1) * t];
    let zs: Vec<f64> = shifts.iter().flat_map(|s| [3.0 + s, 4.5 + s]).collect();
    assert!(close(&z_starts(&v, 0), &zs), "{:?}", z_starts(&v, 0));
    let passes = v["operations"][0]["passes"].as_array().unwrap();
    assert!(passes.iter().all(|p| p["z_end"] == -22.0 && p["lead"] == 3.0), "{v}");
    let starts: Vec<u64> = passes.iter().map(|p| p["start"].as_u64().unwrap()).collect();
    assert_eq!(starts, [0, 1, 0, 1, 0, 1, 0, 1]);
    assert!(v["notes"].to_string().contains("arguments 16 to 19 are zero or empty"), "{}", v["notes"]);

    for (program, thread) in
        [("sinumerik-cycle99.mpf", "M20x1.5-6g"), ("sinumerik-cycle99-two-start.mpf", "M24xPh3P1.5-6g")]
    {
        for dev in d2_deviations(program, thread, &[]) {
            assert!((dev - 32.0).abs() < 0.1, "{program}: {dev}");
        }
    }
}

/// Issue 45 item 1: the G-code system from the program's own words. The header `G28 G91 Z0.` /
/// `G90` is system B's or C's (system A has no G91; its G90 is the box cycle, which needs a
/// position): the program is read in B, the named default of the two, and said, so G90 makes the
/// G76 absolute again and its last pass is the X27.546 it writes (read in A, G91 stayed in force
/// and every pass drifted to X57.8 and beyond). A G92 with F in such a program is system A's
/// threading cycle and B's coordinate setting: refused at its line. Given `--gcode-system a`, G91
/// is no code of system A's lathe and is read past with a note.
#[test]
fn the_gcode_system_is_read_from_the_program() {
    let dir = tempdir("gsystem-evidence");
    let header = "O5001 (M30X2)\nG21 G18 G99\nG28 G91 Z0.\nG90\nT0101\nG97 S600 M3\nG0 X32 Z5\n";
    std::fs::write(
        dir.join("g76.nc"),
        format!("{header}G76 P010060 Q100 R0.05\nG76 X27.546 Z-30 P1227 Q350 F2.0\nG0 X100 Z100\nM30\n"),
    )
    .unwrap();
    let o = run_in(&dir, &["passes", "--program", "g76.nc", "--json", "-"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let passes = v["operations"][0]["passes"].as_array().unwrap();
    assert_eq!(passes.last().unwrap()["x_end"], 27.546);
    assert!(passes.iter().all(|p| p["x_end"].as_f64().unwrap() < 32.0), "every pass under the start X32");
    let o = run_in(&dir, &["passes", "--program", "g76.nc"]);
    assert!(
        stdout(&o)
            .contains("note: read in Fanuc G-code system B, as its own words show: line 3:5 writes G91"),
        "{}",
        stdout(&o)
    );

    std::fs::write(dir.join("g92.nc"), format!("{header}G92 X29 Z-30 F2.0\nX28.5\nG0 X100 Z100\nM30\n"))
        .unwrap();
    let o = run_in(&dir, &["passes", "--program", "g92.nc"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        one_line_error(&o),
        "threadcheck: error: g92.nc:8:1: G92 with F is Fanuc G-code system A's threading cycle, but line 3 writes G91, which system A does not have (systems B and C: incremental programming): give --gcode-system"
    );
    let o = run_in(&dir, &["passes", "--program", "g92.nc", "--gcode-system", "a"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("g92.nc:3:5: G91 read past: not a code threadcheck knows in this dialect"),
        "{}",
        stdout(&o)
    );
    // A G90 without a position in a safety line is no evidence (regression: a system A program
    // whose first line is `G20 G90 G18` was refused at its G92 threading cycle).
    std::fs::write(
        dir.join("safe.nc"),
        "G20 G90 G18\nG0 X2.0 Z0.2\nM3\nS500\nG92 X1.9 Z-1.0 F0.05\nX1.8\nM5\nM2\n",
    )
    .unwrap();
    let o = run_in(&dir, &["passes", "--program", "safe.nc"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stdout(&o).contains("read in Fanuc G-code system A"), "{}", stdout(&o));
}

/// Issue 61 item 5: an Okuma program with a LAP rough-turning cycle (`G85 NSHP D… U… W… F…`), its
/// shape (`NSHP G81` to `G80`) and a `/GOTO NSTRT` was refused ("'NSHP' is not a word"). Read
/// now: the LAP and the jump are read past by name, the shape's blocks are moves, so the blank
/// is the shape's Ø73.8 (line 12), and the G71 cuts the passes of the M74x2 program above
/// (D 0.4 per pass in diameter, U 0.1, H 2.454: X73.6 … X71.546).
#[test]
fn an_okuma_lap_cycle_and_its_shape_are_read() {
    let (ops, v) = pass_xs("okuma-lap-m74x2.min", &[]);
    let depths = [0.4, 0.8, 1.2, 1.6, 2.0, 2.354, 2.454];
    let x: Vec<f64> = depths.iter().map(|d| 71.546 + (2.454 - d)).collect();
    assert!(close(&ops[0], &x), "{ops:?}");
    let notes = v.to_string();
    for said in [
        "G85 NSHP read past: an Okuma LAP rough-turning cycle",
        "G81 read past: the start of an Okuma LAP cycle's shape",
        "GOTO NSTRT read past: a jump or call to a sequence name, not followed",
    ] {
        assert!(notes.contains(said), "{said}: {notes}");
    }
    let (_, v) = verify_full("okuma-lap-m74x2.min", "M74x2-6g", &["--allow-nonstandard"]);
    let op = &v["operations"][0];
    assert_eq!(op["plan"]["blank_diameter"], 73.8);
    assert!(
        v.to_string().contains("okuma-lap-m74x2.min:12:1: the blank is the program's own: Ø73.8000"),
        "{v}"
    );
}
