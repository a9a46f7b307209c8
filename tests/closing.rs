//! Closing the loop at the machine: `correct` (wires, measured d2, gauges, pick-up), coatings
//! and `capability`. Every expected value is derived by hand in the comments from the standard
//! formulas and ISO 965-1's limits (M10x1.5: 6g d2 8.862–8.994, d 9.732–9.968; 6H D2
//! 9.026–9.206), never taken from threadcheck's own output.

use crate::util::*;

fn json(o: &Output) -> serde_json::Value {
    serde_json::from_str(&stdout(o)).unwrap_or_else(|e| panic!("{e}: {}{}", stdout(o), stderr(o)))
}

/// The helix term of M10x1.5 over 0.866 mm wires, mm: the exact contact (held to a sampled
/// helicoid by `geometry::wire`'s test), −1.733 µm as the audit of issue 48 computed it with an
/// independent 3-D model (the classical −0.75·w·tan² λ gives −1.817 µm).
fn helix_m10() -> f64 {
    let c = threadcheck::wire_helix_term(9.025_721, 1.5, 1.5, 30f64.to_radians(), 0.866);
    assert!((c * 1000.0 + 1.733).abs() < 0.005, "{c}");
    c
}

/// The mid-tolerance final X of a full-profile M10x1.5 insert: its tip cuts d3, and
/// d2 − d3 = (0.649519 − 1.226869)·P… = 0.577350·P, so X = 8.928 − 0.866025.
const FULL_X_MID: f64 = 8.928 - 0.577_350_269 * 1.5;

/// A full-profile M10x1.5-6g plan measured over 0.866 mm wires: straight 60° flanks, so the
/// wires give d2 = M − 3w + 0.866025·P + the helix term (−1.733 µm), and the
/// correction moves the final X by the d2 error to the middle, 8.928.
#[test]
fn wires_on_a_full_profile_give_the_standard_formula_and_the_x_moves_by_the_error() {
    let (m, w) = (10.32, 0.866);
    let o = run(&[
        "correct",
        "--thread",
        "M10x1.5-6g",
        "--insert",
        "full",
        "--measured-m",
        "10.32",
        "--wire",
        "0.866",
        "--json",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let v = json(&o);
    // The helix term is taken at the part's own d2 (issue 64), which it moves: d2 = M − 3w +
    // 0.866025·P + h(d2), settled by repeating; it differs from the term at the basic d2 by
    // hundredths of a micrometre here.
    let (helix_basic, term) =
        (helix_m10(), |d2: f64| threadcheck::wire_helix_term(d2, 1.5, 1.5, 30f64.to_radians(), w));
    let mut d2 = m - 3.0 * w + 0.866_025_404 * 1.5 + helix_basic;
    for _ in 0..5 {
        d2 = m - 3.0 * w + 0.866_025_404 * 1.5 + term(d2);
    }
    let helix = term(d2);
    assert!((helix - helix_basic).abs() < 1e-4 && helix != helix_basic, "{helix} {helix_basic}");
    let got = v["measured"]["pitch_diameter"].as_f64().unwrap();
    assert!((got - d2).abs() < 1e-9, "d2 {got} against {d2}");
    assert!(
        (v["measured"]["over_wires"]["helix_term"].as_f64().unwrap() - helix).abs() < 1e-9,
        "the helix term at the measured d2 {d2}"
    );
    let delta = 8.928 - d2;
    assert!((v["delta_pitch_diameter"].as_f64().unwrap() - delta).abs() < 1e-6);
    let x = v["suggested_final_x"].as_f64().unwrap();
    assert!((x - (FULL_X_MID + delta)).abs() < 1e-6, "final X {x}");
    assert_eq!(v["verdict"], "fail");
}

/// A partial-profile insert (r 0.04): its flanks are straight 60° where the wires touch them
/// (best-size wires touch at the pitch line, far above the tip's radius), so a reading M that
/// means d2 = 8.950 by the formula, M = 8.950 + 3w − 0.866025·P − the helix term at 8.950, gives 8.950 from the
/// as-cut flanks, the same as `--measured-d2 8.950`.
#[test]
fn a_partial_profile_reads_the_same_d2_from_wires_as_measured() {
    let w = 0.866;
    // The helix term at the part's d2 8.950 (issue 64), the same contact model as at the basic d2.
    let _ = helix_m10();
    let m = 8.950 + 3.0 * w
        - 0.866_025_404 * 1.5
        - threadcheck::wire_helix_term(8.950, 1.5, 1.5, 30f64.to_radians(), w);
    let by_wires = json(&run(&[
        "correct",
        "--thread",
        "M10x1.5-6g",
        "--insert",
        "partial:0.04",
        "--measured-m",
        &format!("{m:.9}"),
        "--wire",
        "0.866",
        "--json",
    ]));
    let by_d2 = json(&run(&[
        "correct",
        "--thread",
        "M10x1.5-6g",
        "--insert",
        "partial:0.04",
        "--measured-d2",
        "8.950",
        "--json",
    ]));
    let a = by_wires["measured"]["pitch_diameter"].as_f64().unwrap();
    let b = by_d2["measured"]["pitch_diameter"].as_f64().unwrap();
    assert!((a - 8.950).abs() < 1e-6 && (b - 8.950).abs() < 1e-12, "{a} {b}");
    // Within 8.862–8.994: no correction, exit 0.
    assert_eq!(by_wires["verdict"], "pass");
    assert!(by_wires["correction"].is_null() && by_wires["delta_pitch_diameter"].is_null());
}

/// In a program the correction is the program's own X word and a wear offset: the G92 run's
/// last X8.062 cuts d2 8.062 + 0.866025 = 8.928; the part measured 9.020 must come down
/// 92 µm: X8.062 → X7.970, or −0.092 mm on the tool's X wear. `--fix -` writes it.
#[test]
fn a_measured_program_is_corrected_in_its_own_words_and_by_wear_offset() {
    let prog = data("programs/m10-g92-radial.nc");
    let p = prog.to_str().unwrap();
    let o = run(&[
        "correct",
        "--thread",
        "M10x1.5-6g",
        "--insert",
        "full",
        "--program",
        p,
        "--measured-d2",
        "9.020",
        "--json",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let v = json(&o);
    assert_eq!(v["correction"]["word"], "X");
    assert_eq!(v["correction"]["line"], 10);
    assert!((v["correction"]["value"].as_f64().unwrap() - 7.970).abs() < 1e-9, "{}", v["correction"]);
    assert!((v["wear_offset"]["x"].as_f64().unwrap() + 0.092).abs() < 1e-9);
    let fixed = run(&[
        "correct",
        "--thread",
        "M10x1.5-6g",
        "--insert",
        "full",
        "--program",
        p,
        "--measured-d2",
        "9.020",
        "--fix",
        "-",
    ]);
    assert_eq!(fixed.status.code(), Some(1));
    let text = stdout(&fixed);
    assert!(text.lines().any(|l| l.trim() == "X7.970"), "{text}");
    assert!(!text.contains("X8.062"), "{text}");
}

/// A program that cuts several threads: `correct` takes the one measured, `--operation N` (the
/// Heidenhain DIN test program's three M20x1.5 operations, each cutting to 18.16, d2 19.026 with
/// a full-profile insert). The part of operation 2 measures d2 19.066: to 6g's middle 18.924 is
/// −142 µm, 71 µm deeper radially, so its G31 depth U−0.92 becomes U−0.991 at line 18, and
/// `--fix` changes that word alone. Without `--operation` the error lists the three.
#[test]
fn correct_takes_the_measured_operation_of_a_program_of_several() {
    let prog = data("programs/heidenhain-g31-g33.nc");
    let p = prog.to_str().unwrap();
    let args =
        ["correct", "--thread", "M20x1.5-6g", "--insert", "full", "--program", p, "--dialect", "heidenhain"];
    let o = run(&[&args[..], &["--measured-d2", "19.066"]].concat());
    assert_eq!(o.status.code(), Some(2));
    assert!(
        one_line_error(&o).ends_with(
            "cuts 3 threads (G31 at line 15, G31 at line 18, G33 at line 21): say which one with --operation 1 to 3"
        ),
        "{}",
        stderr(&o)
    );
    let o = run(&[&args[..], &["--measured-d2", "19.066", "--operation", "2", "--json"]].concat());
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let v = json(&o);
    assert_eq!(
        (v["correction"]["written"].as_str(), v["correction"]["line"].as_u64()),
        (Some("U-0.92"), Some(18))
    );
    assert!((v["correction"]["value"].as_f64().unwrap() + 0.991).abs() < 1e-9, "{}", v["correction"]);
    let o = run(&[&args[..], &["--measured-d2", "19.066", "--operation", "2", "--fix", "-"]].concat());
    let text = stdout(&o);
    let changed: Vec<&str> = text
        .lines()
        .zip(std::fs::read_to_string(&prog).unwrap().lines().collect::<Vec<_>>())
        .filter(|(a, b)| a != b)
        .map(|(a, _)| a)
        .collect();
    assert_eq!(changed, ["N15 G31 X20 Z-20 F1.5 U-0.991 I0.3 V1 H3 A30 B0 P0"]);
    let o = run(&[&args[..], &["--measured-d2", "19.066", "--operation", "4"]].concat());
    assert_eq!(o.status.code(), Some(2));
    assert!(one_line_error(&o).ends_with("there is no operation 4"), "{}", stderr(&o));
    // verify of operation 2 alone: the program's three are counted, that one checked.
    let mut ver = vec!["verify"];
    ver.extend(&args[1..]);
    ver.extend(["--operation", "2"]);
    let o = run(&ver);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let text = stdout(&o);
    assert!(text.contains("3 threading operations (operation 2 checked)"), "{text}");
    assert!(text.contains("== operation 2 of 3: G31 at line 18"), "{text}");
    assert!(!text.contains("== operation 1") && !text.contains("== operation 3"), "{text}");
    // capability of operation 3 (the chained G33): X σ 5 µm on the diameter moves d2 one for one,
    // around 19.026 (its mean within 4σ/√500 = 0.9 µm).
    let mut cap = vec!["capability"];
    cap.extend(&args[1..]);
    cap.extend(["--x-sigma", "0.005", "--samples", "500", "--operation", "3", "--json"]);
    let o = run(&cap);
    let v = json(&o);
    let d2 = v["sizes"].as_array().unwrap().iter().find(|s| s["feature"] == "pitch_diameter").unwrap();
    assert!((d2["mean"].as_f64().unwrap() - 19.026025).abs() < 0.0009, "{d2}");
    assert!((d2["sigma"].as_f64().unwrap() - 0.005).abs() < 0.0005, "{d2}");
}

/// A gauge tells the side, not the size: GO fails on a bolt means d2 over 8.994 by an unknown
/// amount; taken at 8.994 (the least it can be), the change to the middle is −66 µm, and the
/// report says what is unknown. `ok` needs no correction.
#[test]
fn a_gauge_result_gives_the_least_correction_and_says_what_is_unknown() {
    let v = json(&run(&[
        "correct",
        "--thread",
        "M10x1.5-6g",
        "--insert",
        "full",
        "--gauge",
        "go-fails",
        "--json",
    ]));
    assert!((v["delta_pitch_diameter"].as_f64().unwrap() + 0.066).abs() < 1e-9);
    assert!(v["measured"]["unknown"].as_str().unwrap().contains("how far"));
    assert!(v["measured"]["pitch_diameter"].is_null());
    // A nut's NO-GO entering means D2 over 9.206: the same side of the change, −90 µm.
    let n = json(&run(&[
        "correct",
        "--thread",
        "M10x1.5-6H",
        "--insert",
        "full",
        "--gauge",
        "nogo-enters",
        "--json",
    ]));
    assert!((n["delta_pitch_diameter"].as_f64().unwrap() + 0.090).abs() < 1e-9);
    let ok = run(&["correct", "--thread", "M10x1.5-6g", "--gauge", "ok"]);
    assert_eq!(ok.status.code(), Some(0));
}

/// Pick-up: the program's grooves lie at Z3 − k·1.5, centres on Z ≡ 0 (mod 1.5) with radial
/// passes and a symmetric insert. A groove measured at Z0.25 is 0.25 mm off on a 1.5 mm lead:
/// 0.25/1.5·360 = 60° of start angle (cutting towards −Z), or a Z shift of 0.25; at Z−0.25,
/// −60°; at Z1.75 the next groove is again 0.25 off.
#[test]
fn a_pickup_quarter_millimetre_off_on_a_one_and_a_half_lead_is_sixty_degrees() {
    let prog = data("programs/m10-g92-radial.nc");
    let p = prog.to_str().unwrap();
    for (z, deg, shift) in [("0.25", 60.0, 0.25), ("-0.25", -60.0, -0.25), ("1.75", 60.0, 0.25)] {
        let o = run(&[
            "correct",
            "--thread",
            "M10x1.5-6g",
            "--insert",
            "full",
            "--program",
            p,
            "--pickup-z",
            z,
            "--json",
        ]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        let v = json(&o);
        let pk = &v["pickup"];
        assert!((pk["start_angle_deg"].as_f64().unwrap() - deg).abs() < 1e-6, "{z}: {pk}");
        assert!((pk["z_shift"].as_f64().unwrap() - shift).abs() < 1e-6, "{z}: {pk}");
    }
}

/// `limits --coating T [--coating-limits RULE] --json`: (min, max) of each diameter, external
/// and internal, as (major, pitch, minor).
fn coated_limits(designation: &str, t: &str, rule: &str) -> serde_json::Value {
    json(&run(&["limits", designation, "--coating", t, "--coating-limits", rule, "--json"]))
}

fn pair(v: &serde_json::Value, side: &str, size: &str) -> (Option<f64>, Option<f64>) {
    (v[side][size]["min"].as_f64(), v[side][size]["max"].as_f64())
}

const IN: f64 = 25.4;

/// Issue 48: a coat of t grows a 60° bolt's d2 by 2t/sin 30° = 4t and its d by 2t (a nut's shrink
/// as much). **The standards' rule** (the default): the class applies before coating (ISO 965-1
/// §8.5, ASME B1.1 §7) and after coating the thread stays within the basic profile (h/H), so the
/// maximum-material side is capped at basic ∓ growth, rounded inward:
/// - M10x1.5-6g, t = 10 µm: d2 8.862–min(8.994, 9.026 − 0.040 = 8.986); d max 9.968 < 10 − 0.020
///   stays. t = 5 µm: 9.026 − 0.020 = 9.006 > 8.994: unchanged.
/// - M10x1.5-6H, t = 10 µm: D2 max(9.026, 9.026 + 0.040)–9.206 = 9.066–9.206; D1 min 8.376 + 0.020
///   = 8.396; D min 10.020. t = 5 µm: D2 9.046, D1 8.386, D 10.010.
/// - 1/2-13 UNC-2A: d2 max 0.4485 in; t = 5 µm: 0.4500 − 0.000787 = 0.449213 > 0.4485, unchanged;
///   t = 10 µm: 0.4500 − 0.001575 = 0.448425 → 0.4484 in (inward to 0.0001 in).
/// - 1/2-13 UNC-3A (no allowance): t = 5 µm: d2 max 0.4492 in, d max 0.5 − 0.000394 → 0.4996 in;
///   t = 10 µm: d2 0.4484 in, d 0.4992 in.
/// - Tr40x7-7e (30°: d2 grows 2t/sin 15° = 7.727t): d2 max 36.375 < 36.5 − 0.077 stays; d max
///   40 → 39.980 (t = 10 µm), 39.990 (t = 5 µm).
///
/// **After** (`--coating-limits after`, a drawing that says so): every limit moves by the growth:
/// 6g d2 8.822–8.954 and d 9.712–9.948 (t = 10 µm), 6H D2 9.066–9.246.
#[test]
fn coats_of_five_and_ten_micrometres_under_both_rules() {
    let g = coated_limits("M10x1.5-6H/6g", "0.010", "before");
    assert_eq!(pair(&g, "external", "pitch_diameter"), (Some(8.862), Some(8.986)));
    assert_eq!(pair(&g, "external", "major_diameter"), (Some(9.732), Some(9.968)));
    assert_eq!(pair(&g, "internal", "pitch_diameter"), (Some(9.066), Some(9.206)));
    assert_eq!(pair(&g, "internal", "minor_diameter"), (Some(8.396), Some(8.676)));
    assert_eq!(pair(&g, "internal", "major_diameter").0, Some(10.020));
    let g5 = coated_limits("M10x1.5-6H/6g", "0.005", "before");
    assert_eq!(pair(&g5, "external", "pitch_diameter"), (Some(8.862), Some(8.994)));
    assert_eq!(pair(&g5, "internal", "pitch_diameter"), (Some(9.046), Some(9.206)));
    assert_eq!(pair(&g5, "internal", "minor_diameter").0, Some(8.386));
    assert_eq!(pair(&g5, "internal", "major_diameter").0, Some(10.010));
    let inch = |v: Option<f64>| v.map(|x| (x / IN * 1e4).round() / 1e4);
    for (class, t, d2_max, d_max) in [
        ("2A", "0.005", 0.4485, 0.4985),
        ("2A", "0.010", 0.4484, 0.4985),
        ("3A", "0.005", 0.4492, 0.4996),
        ("3A", "0.010", 0.4484, 0.4992),
    ] {
        let u = coated_limits(&format!("1/2-13 UNC-{class}"), t, "before");
        assert_eq!(inch(pair(&u, "external", "pitch_diameter").1), Some(d2_max), "{class} {t}");
        assert_eq!(inch(pair(&u, "external", "major_diameter").1), Some(d_max), "{class} {t}");
    }
    for (t, d_max) in [("0.010", 39.980), ("0.005", 39.990)] {
        let tr = coated_limits("Tr40x7-7e", t, "before");
        assert_eq!(pair(&tr, "external", "pitch_diameter").1, Some(36.375), "{t}");
        assert_eq!(pair(&tr, "external", "major_diameter").1, Some(d_max), "{t}");
    }
    let a = coated_limits("M10x1.5-6H/6g", "0.010", "after");
    assert_eq!(pair(&a, "external", "pitch_diameter"), (Some(8.822), Some(8.954)));
    assert_eq!(pair(&a, "external", "major_diameter"), (Some(9.712), Some(9.948)));
    assert_eq!(pair(&a, "internal", "pitch_diameter"), (Some(9.066), Some(9.246)));
    // verify aims at the middle of the limits before plating and says what plating makes of it:
    // by the standards' rule (8.862 + 8.986)/2 = 8.924, coated 8.964 (at most basic 9.026);
    // after, (8.822 + 8.954)/2 = 8.888, coated 8.928.
    for (rule, mid, coated) in [("before", 8.924, "8.9640"), ("after", 8.888, "8.9280")] {
        let o = run(&[
            "verify",
            "--thread",
            "M10x1.5-6g",
            "--insert",
            "full",
            "--coating",
            "0.010",
            "--coating-limits",
            rule,
            "--json",
        ]);
        let r = json(&o);
        assert!((r["measured"]["pitch_diameter"].as_f64().unwrap() - mid).abs() < 1e-6, "{rule}");
        let notes = r["notes"].to_string();
        assert!(notes.contains("after coating") && notes.contains(coated), "{rule}: {notes}");
    }
    // A coat that fills the thread is refused in one line; so is one that leaves no tolerance.
    let bad = run(&["limits", "M10x1.5-6g", "--coating", "0.5"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(one_line_error(&bad).contains("coating 0.5 mm"), "{}", stderr(&bad));
    let thick = run(&["limits", "M10x1.5-4h", "--coating", "0.05"]);
    assert_eq!(thick.status.code(), Some(2));
    assert!(
        one_line_error(&thick).contains("leaves no tolerance on the pitch diameter"),
        "{}",
        stderr(&thick)
    );
}

/// X scatter alone on a centred X: d2 moves one for one with X, so σ(d2) = σx and
/// Cpk = (T/2)/(3σ) = (0.132/2)/(3·0.011) = 2.0. The Monte Carlo's standard uncertainty of a
/// Cpk estimate from N = 10 000 normal samples is Cpk·√(1/(9N·Cpk²) + 1/(2(N−1))) ≈ 0.0142;
/// the test allows three of it.
#[test]
fn capability_with_x_scatter_alone_has_cpk_half_the_tolerance_over_three_sigma() {
    let o =
        run(&["capability", "--thread", "M10x1.5-6g", "--insert", "full", "--x-sigma", "0.011", "--json"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v = json(&o);
    let d2 = v["sizes"].as_array().unwrap().iter().find(|s| s["feature"] == "pitch_diameter").unwrap();
    let u = (1.0f64 / (9.0 * 1e4 * 4.0) + 1.0 / (2.0 * 9999.0)).sqrt() * 2.0;
    let cpk = d2["cpk"].as_f64().unwrap();
    assert!((cpk - 2.0).abs() < 3.0 * u, "Cpk {cpk}, u {u}");
    assert!((v["cpk_uncertainty"].as_f64().unwrap() - u).abs() < 0.002);
    let sigma = d2["sigma"].as_f64().unwrap();
    assert!((sigma - 0.011).abs() < 3.0 * 0.011 / (2.0f64 * 1e4).sqrt(), "σ {sigma}");
    assert_eq!(v["pass_share"].as_f64(), Some(1.0));
    let hist: usize =
        v["histogram"]["counts"].as_array().unwrap().iter().map(|c| c.as_u64().unwrap() as usize).sum();
    assert_eq!(hist, 10_000);
}

/// Wear alone, w per part: part k carries k parts' wear, d2 = d2(1) + 2(k − 1)w. Started at the
/// best X (part 1 on the lower limit 8.862), parts stay in while 8.862 + 2(k − 1)w ≤ 8.994:
/// k ≤ 0.132/(2w) + 1, so ⌊0.132/0.004⌋ + 1 = 34 parts for w = 2 µm, the final X
/// 8.862 − 0.004 − 8.928 = 70 µm below the centred one. From the centred X (d2 8.928,
/// part k at 8.928 + 0.004k) ⌊0.066/0.004⌋ = 16 parts. A nut wears the other way:
/// M10x1.5-6H, T = 0.180: ⌊0.180/0.004⌋ + 1 = 46.
#[test]
fn capability_with_wear_alone_counts_parts_per_edge_as_derived() {
    let v = json(&run(&[
        "capability",
        "--thread",
        "M10x1.5-6g",
        "--insert",
        "full",
        "--wear-per-part",
        "0.002",
        "--samples",
        "100",
        "--json",
    ]));
    assert_eq!(v["best_parts_per_edge"].as_u64(), Some(34));
    assert_eq!(v["parts_per_edge"].as_u64(), Some(16));
    assert!((v["best_final_x"].as_f64().unwrap() - (FULL_X_MID - 0.070)).abs() < 1e-6);
    let n = json(&run(&[
        "capability",
        "--thread",
        "M10x1.5-6H",
        "--insert",
        "full",
        "--wear-per-part",
        "0.002",
        "--samples",
        "100",
        "--json",
    ]));
    assert_eq!(n["best_parts_per_edge"].as_u64(), Some(46));
}

/// The same seed gives the same report on one core and on two.
#[test]
fn capability_is_the_same_for_a_seed_whatever_the_threads() {
    let args = [
        "capability",
        "--thread",
        "M10x1.5-6g",
        "--x-sigma",
        "0.008",
        "--tip-radius-tol",
        "0.01",
        "--samples",
        "500",
        "--seed",
        "7",
        "--json",
    ];
    let dir = tempdir("cap-seed");
    let one = Command::new(env!("CARGO_BIN_EXE_threadcheck"))
        .args(args)
        .env("RAYON_NUM_THREADS", "1")
        .current_dir(&dir)
        .output()
        .unwrap();
    let two = Command::new(env!("CARGO_BIN_EXE_threadcheck"))
        .args(args)
        .env("RAYON_NUM_THREADS", "2")
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(one.status.code(), two.status.code());
    assert_eq!(stdout(&one), stdout(&two));
    let other = run(&[
        "capability",
        "--thread",
        "M10x1.5-6g",
        "--x-sigma",
        "0.008",
        "--tip-radius-tol",
        "0.01",
        "--samples",
        "500",
        "--seed",
        "8",
        "--json",
    ]);
    assert_ne!(stdout(&one), stdout(&other));
}

/// The pictures: the histogram SVG and the HTML page with it, written together.
#[test]
fn capability_and_correct_write_their_pages() {
    let dir = tempdir("cap-pages");
    let o = run_in(
        &dir,
        &[
            "capability",
            "--thread",
            "M10x1.5-6g",
            "--x-sigma",
            "0.01",
            "--samples",
            "300",
            "--svg",
            "h.svg",
            "--html",
            "h.html",
        ],
    );
    assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
    let svg = std::fs::read_to_string(dir.join("h.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("min 8.8620") && svg.contains("max 8.9940"), "{svg}");
    let html = std::fs::read_to_string(dir.join("h.html")).unwrap();
    assert!(html.contains("<svg") && html.contains("Cpk"));
    let c = run_in(&dir, &["correct", "--thread", "M10x1.5-6g", "--measured-d2", "9.1", "--html", "c.html"]);
    assert_eq!(c.status.code(), Some(1));
    let page = std::fs::read_to_string(dir.join("c.html")).unwrap();
    assert!(page.contains("CORRECT the program"), "{page}");
}

/// What correct and capability refuse, each in one line.
#[test]
fn correct_and_capability_refuse_what_they_cannot_read() {
    for (args, says) in [
        (vec!["correct", "--thread", "M10x1.5-6g"], "needs what was measured"),
        (
            vec!["correct", "--thread", "M10x1.5-6H", "--measured-m", "10", "--wire", "0.866"],
            "external thread",
        ),
        (vec!["correct", "--thread", "M10x1.5-6g", "--measured-d2", "-1"], "positive length"),
        (vec!["correct", "--thread", "M10x1.5-6g", "--gauge", "maybe"], "go-fails, nogo-enters or ok"),
        (
            vec!["capability", "--thread", "M10x1.5-6g", "--insert", "full", "--tip-radius-tol", "0.01"],
            "partial-profile",
        ),
        (vec!["capability", "--thread", "M10x1.5-6g", "--samples", "0"], "--samples 0"),
        (vec!["capability", "--thread", "M10x1.5-6g", "--x-sigma", "-0.01"], "--x-sigma"),
    ] {
        let o = run(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stdout(&o));
        let e = one_line_error(&o);
        assert!(e.contains(says), "{args:?}: {e}");
    }
}
