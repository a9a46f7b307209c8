//! Issue 16, the process checks: what a machinist checks besides the profile. Expected values are
//! derived by hand in the comments.

use crate::*;

fn json(args: &[&str]) -> (Option<i32>, serde_json::Value) {
    let mut a = args.to_vec();
    a.extend(["--no-pass-metrics", "--json", "-"]);
    let o = run(&a);
    (o.status.code(), serde_json::from_slice(&o.stdout).unwrap_or_else(|_| panic!("{}", stderr(&o))))
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
    let prog = data("programs/fanuc-g96-g92.nc");
    let (code, v) =
        json(&["verify", "--program", prog.to_str().unwrap(), "--thread", "M20x1.5-6g", "--insert", "full"]);
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
    let prog = data("programs/fanuc-g97-g92.nc");
    let machine = data("machine.toml");
    let (_, v) = json(&[
        "verify",
        "--program",
        prog.to_str().unwrap(),
        "--thread",
        "M20x1.5-6g",
        "--insert",
        "full",
        "--machine",
        machine.to_str().unwrap(),
    ]);
    let op = &v["operations"][0];
    let t = &op["process"]["machining_time"];
    assert!((t["cutting"].as_f64().unwrap() - 8.0).abs() < 1e-9, "{t}");
    assert!((t["rapid"].as_f64().unwrap() - 1.20624).abs() < 1e-9, "{t}");
    assert!((t["total"].as_f64().unwrap() - 9.20624).abs() < 1e-9, "{t}");
    assert_eq!(check(op, "feed")["value"], 750.0);
    assert_eq!(check(op, "spindle_speed")["ok"], true);
    // The thesis's training lathe allows 320 rpm at P 1.5 (its Table 2.2): S500 fails.
    let (code, v) = json(&[
        "verify",
        "--program",
        prog.to_str().unwrap(),
        "--thread",
        "M20x1.5-6g",
        "--insert",
        "full",
        "--machine",
        "training-lathe",
    ]);
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
    let prog = data("programs/fanuc-g97-g92.nc");
    let helix = (1.5f64 / (std::f64::consts::PI * (20.0 - 0.649_519_052_838_329 * 1.5))).atan().to_degrees();
    for (clearance, ok) in [("3", true), ("1", false)] {
        let (_, v) = json(&[
            "verify",
            "--program",
            prog.to_str().unwrap(),
            "--thread",
            "M20x1.5-6g",
            "--insert",
            "full",
            "--clearance-angle",
            clearance,
        ]);
        let c = check(&v["operations"][0], "flank_clearance");
        assert_eq!(c["ok"], ok, "{c}");
        let want = clearance.parse::<f64>().unwrap() - helix;
        assert!((c["value"].as_f64().unwrap() - want).abs() < 1e-9);
    }
}
