//! Issue 16, the process checks: what a machinist checks besides the profile. Expected values are
//! derived by hand in the comments.

use crate::*;

fn json(args: &[&str]) -> (Option<i32>, serde_json::Value) {
    let mut a = args.to_vec();
    a.extend(["--no-pass-metrics", "--json", "-"]);
    let o = run(&a);
    (o.status.code(), serde_json::from_slice(&o.stdout).unwrap_or_else(|_| panic!("{}", stderr(&o))))
}

/// `verify --program tests/data/programs/NAME --thread M20x1.5-6g` and `extra`, as JSON.
fn verify_m20(name: &str, extra: &[&str]) -> (Option<i32>, serde_json::Value) {
    let prog = data(&format!("programs/{name}"));
    let mut a = vec!["verify", "--program", prog.to_str().unwrap(), "--thread", "M20x1.5-6g"];
    a.extend_from_slice(extra);
    json(&a)
}

fn check<'a>(op: &'a serde_json::Value, feature: &str) -> &'a serde_json::Value {
    op["checks"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["feature"] == feature)
        .unwrap_or_else(|| panic!("no {feature}: {op:#}"))
}

/// G96 before the G92: the process check fails and says why, and the verdict fails with it.
#[test]
fn g96_at_a_threading_cycle_fails() {
    let (code, v) = verify_m20("fanuc-g96-g92.nc", &["--insert", "full"]);
    assert_eq!(code, Some(1));
    let c = check(&v["operations"][0], "constant_spindle_speed");
    assert_eq!((c["ok"].as_bool(), c["kind"].as_str()), (Some(false), Some("process")));
    assert!(c["note"].as_str().unwrap().contains("G96"), "{c}");
}

/// The G97 program: four G92 passes of 25 mm (Z5 to Z−20) at S500, lead 1.5: 25/(500·1.5) min
/// = 2 s each, 8 s cutting. Each cycle comes in from X24 and goes back out and along Z at the
/// test machine's 6000 mm/min: (25 + 2·(24 − X)/2) mm for X = 19.4, 19, 18.6, 18.376, 120.624 mm
/// in all, 1.20624 s. S·lead = 750 mm/min is within 1000; S500 within 2000 rpm.
#[test]
fn machining_time_and_machine_limits() {
    let machine = data("machine.toml");
    let (_, v) =
        verify_m20("fanuc-g97-g92.nc", &["--insert", "full", "--machine", machine.to_str().unwrap()]);
    let op = &v["operations"][0];
    let t = &op["process"]["machining_time"];
    assert!((t["cutting"].as_f64().unwrap() - 8.0).abs() < 1e-9, "{t}");
    assert!((t["rapid"].as_f64().unwrap() - 1.20624).abs() < 1e-9, "{t}");
    assert!((t["total"].as_f64().unwrap() - 9.20624).abs() < 1e-9, "{t}");
    assert_eq!(check(op, "feed")["value"], 750.0);
    assert_eq!(check(op, "spindle_speed")["ok"], true);
    // The thesis's training lathe allows 320 rpm at P 1.5 (its Table 2.2): S500 fails.
    let (code, v) = verify_m20("fanuc-g97-g92.nc", &["--insert", "full", "--machine", "training-lathe"]);
    assert_eq!(code, Some(1));
    let c = check(&v["operations"][0], "spindle_speed");
    assert_eq!((c["ok"].as_bool(), c["max"].as_f64()), (Some(false), Some(320.0)));
}

/// Helix angle at d2 = atan(lead/(π·d2)): M20x2.5, d2 = 20 − 0.649519·2.5 = 18.3762, 2.4797°;
/// the two-start Tr40x14(P7), d2 = 36.5, atan(14/(π·36.5)) = 6.96087°. With a 3° clearance insert
/// the M20x1.5 (1.4376°) keeps 1.5624° on the leading flank; a 1° insert rubs.
#[test]
fn helix_angle_and_flank_clearance() {
    let (_, v) = json(&["verify", "--thread", "M20x2.5-6g"]);
    assert!((v["helix_angle"].as_f64().unwrap() - 2.4797).abs() < 1e-4, "{}", v["helix_angle"]);
    let (_, v) = json(&["verify", "--thread", "Tr40x14(P7)-7e", "--insert", "full"]);
    assert!((v["helix_angle"].as_f64().unwrap() - 6.96087).abs() < 1e-4, "{}", v["helix_angle"]);
    let helix = (1.5f64 / (std::f64::consts::PI * (20.0 - 0.649_519_052_838_329 * 1.5))).atan().to_degrees();
    for (clearance, ok) in [("3", true), ("1", false)] {
        let (_, v) = verify_m20("fanuc-g97-g92.nc", &["--insert", "full", "--clearance-angle", clearance]);
        let c = check(&v["operations"][0], "flank_clearance");
        assert_eq!(c["ok"], ok, "{c}");
        let want = clearance.parse::<f64>().unwrap() - helix;
        assert!((c["value"].as_f64().unwrap() - want).abs() < 1e-9);
    }
}

fn fit(args: &[&str]) -> (Option<i32>, serde_json::Value) {
    let mut a = vec!["fit"];
    a.extend_from_slice(args);
    a.extend(["--json", "-"]);
    let o = run(&a);
    (o.status.code(), serde_json::from_slice(&o.stdout).unwrap_or_else(|_| panic!("{}", stderr(&o))))
}

/// A mid-tolerance 6H nut on a mid-tolerance 6g bolt, both full profile: D2 = (9.026 + 9.206)/2
/// = 9.116, d2 = (8.862 + 8.994)/2 = 8.928 (ISO 965-1), so the flanks stand (9.116 − 8.928)/2 ·
/// sin 30° = 47.0 µm apart. A bolt cut 0.238 mm larger (d2 9.166 > D2 9.116) interferes by at
/// least (9.166 − 9.116)/2 · sin 30° = 12.5 µm.
#[test]
fn fit_mid_tolerance_and_oversize_bolt() {
    let (code, v) = fit(&["--thread", "M10x1.5-6H/6g", "--bolt-insert", "full", "--nut-insert", "full"]);
    assert_eq!(code, Some(0));
    assert!((v["clearance_um"].as_f64().unwrap() - 47.0).abs() < 0.1, "{}", v["clearance_um"]);
    assert_eq!(v["verdict"], "fits");
    let (code, v) = fit(&[
        "--thread",
        "M10x1.5-6H/6g",
        "--bolt-insert",
        "full",
        "--nut-insert",
        "full",
        "--bolt-final-x",
        "8.3",
    ]);
    assert_eq!(code, Some(1));
    assert!(v["clearance_um"].as_f64().unwrap() <= -12.5 + 0.1, "{}", v["clearance_um"]);
    assert_eq!(v["verdict"], "interferes");
}

/// Every form: 1/4-20 UNC-2B/2A mid on mid: (0.21995 − 0.21455) in / 2 · sin 30° = 34.29 µm;
/// Tr40x7-7H/7e: (36.7375 − 36.1975)/2 · sin 15° = 69.88 µm.
#[test]
fn fit_unified_and_trapezoidal() {
    let (_, v) = fit(&["--thread", "1/4-20 UNC-2B/2A", "--bolt-insert", "full", "--nut-insert", "full"]);
    let want = (0.21995 - 0.21455) * 25.4 / 2.0 * 0.5 * 1000.0;
    assert!((v["clearance_um"].as_f64().unwrap() - want).abs() < 0.1, "{} vs {want}", v["clearance_um"]);
    let (_, v) = fit(&["--thread", "Tr40x7-7H/7e", "--bolt-insert", "full", "--nut-insert", "full"]);
    let want = (36.7375 - 36.1975) / 2.0 * 15f64.to_radians().sin() * 1000.0;
    assert!((v["clearance_um"].as_f64().unwrap() - want).abs() < 0.1, "{} vs {want}", v["clearance_um"]);
}

/// The bolt from a program: the M10 G76 cut to the full-profile depth gives the basic d2 =
/// 9.02572 with a full-profile insert; on a mid-tolerance 6H nut (D2 9.116) the flanks stand
/// (9.116 − 9.02572)/2 · sin 30° = 22.57 µm apart. The SVG of the pair is written.
#[test]
fn fit_with_a_bolt_program() {
    let dir = tempdir("fit");
    let svg = dir.join("fit.svg");
    let prog = data("programs/fanuc-m10-full-depth-g76.nc");
    let (code, v) = fit(&[
        "--thread",
        "M10x1.5-6H/6g",
        "--bolt-program",
        prog.to_str().unwrap(),
        "--bolt-insert",
        "full",
        "--nut-insert",
        "full",
        "--svg",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(code, Some(0));
    let want = (9.116 - (10.0 - 0.649_519_052_838_329 * 1.5)) / 2.0 * 0.5 * 1000.0;
    assert!((v["clearance_um"].as_f64().unwrap() - want).abs() < 0.1, "{} vs {want}", v["clearance_um"]);
    let picture = std::fs::read_to_string(&svg).unwrap();
    assert!(picture.contains("FITS") && picture.contains("class=\"nut\""));
    let e = run(&["fit", "--thread", "M10x1.5-6g"]);
    assert!(one_line_error(&e).contains("names no fit"));
}

/// G76 P010060 Q200 R0 / X18.2 Z-20 P900 Q450 F1.5 from X24 Z5 at S400: k = 0.9, Δd = 0.45,
/// Δd min = 0.2: depths 0.45, max(0.636, 0.65) = 0.65, max(0.779, 0.85) = 0.85, then 1.05 passes
/// k: 0.9, and one finishing pass at 0.9. Each pass starts d·tan 30° further along −Z, so it
/// cuts L = 25 − d·tan 30° mm at 400·1.5 = 600 mm/min (L/10 s), and its rapids run out to X24,
/// back L and in again: (L + 2·(24 − X)/2) mm at 6000 mm/min, X = 18.2 + 2·(0.9 − d). The same
/// program under G96 fails the constant-speed check.
#[test]
fn g76_machining_time_and_g96() {
    let machine = data("machine.toml");
    let (_, v) =
        verify_m20("fanuc-g76-timing.nc", &["--insert", "full", "--machine", machine.to_str().unwrap()]);
    let t30 = 30f64.to_radians().tan();
    let (mut cut, mut rapid) = (0.0, 0.0);
    for d in [0.45, 0.65, 0.85, 0.9, 0.9] {
        let l = 25.0 - d * t30;
        let x = 18.2 + 2.0 * (0.9 - d);
        cut += l / 600.0 * 60.0;
        rapid += (l + (24.0 - x)) / 6000.0 * 60.0;
    }
    let t = &v["operations"][0]["process"]["machining_time"];
    assert_eq!(t["per_pass"].as_array().unwrap().len(), 5);
    assert!((t["cutting"].as_f64().unwrap() - cut).abs() < 1e-9, "{t} vs {cut}");
    assert!((t["rapid"].as_f64().unwrap() - rapid).abs() < 1e-9, "{t} vs {rapid}");
    let (code, v) = verify_m20("fanuc-g96-g76.nc", &["--insert", "full"]);
    assert_eq!(code, Some(1));
    let c = check(&v["operations"][0], "constant_spindle_speed");
    assert!(c["ok"] == false && c["note"].as_str().unwrap().contains("G76 runs under G96"), "{c}");
}

/// Run-out: turned to X20 up to a shoulder X30 at Z−25 and threaded to Z−25, the insert meets
/// the shoulder; with an undercut X17 from Z−22 to Z−26 and the thread ending at Z−23.5 it runs
/// out into the groove.
#[test]
fn run_out_against_the_turned_shoulder() {
    let run_out = |name: &str| {
        let (_, v) = verify_m20(name, &["--insert", "full"]);
        check(&v["operations"][0], "run_out").clone()
    };
    let c = run_out("fanuc-runout-shoulder.nc");
    assert_eq!(
        (c["ok"].as_bool(), c["value"].as_f64(), c["max"].as_f64()),
        (Some(false), Some(30.0), Some(20.0)),
        "{c}"
    );
    assert!(c["note"].as_str().unwrap().contains("shoulder"));
    let c = run_out("fanuc-runout-undercut.nc");
    assert_eq!((c["ok"].as_bool(), c["value"].as_f64()), (Some(true), Some(17.0)), "{c}");
}

/// The insert file's `clearance_angle` (1°) is used when `--clearance-angle` is not given: the
/// M20x1.5's 1.44° helix eats it.
#[test]
fn clearance_angle_from_the_insert_file() {
    let ins = data("insert-clearance-1deg.toml");
    let (_, v) = verify_m20("fanuc-g97-g92.nc", &["--insert", ins.to_str().unwrap()]);
    let c = check(&v["operations"][0], "flank_clearance");
    assert_eq!(c["ok"], false, "{c}");
}
