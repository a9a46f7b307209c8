//! Issue 46 item 1, one verify for every thread a program makes: its turned threads, its tapped
//! holes (with their drills) and its thread-milled thread, each checked as `verify`, `tap` and
//! `thread-mill` check them, in one report with one verdict. The programs in
//! `tests/data/whole/` are ours; each expected value is derived by hand in the comments.

use crate::*;

fn verify_json(name: &str, extra: &[&str]) -> (i32, serde_json::Value) {
    let program = data(&format!("whole/{name}"));
    let mut args = vec!["verify", "--program", program.to_str().unwrap()];
    args.extend(extra);
    args.extend(["--json", "-"]);
    run_json(&args)
}

fn processes(v: &serde_json::Value) -> Vec<&str> {
    v["operations"].as_array().unwrap().iter().map(|o| o["made"].as_str().unwrap()).collect()
}

/// A lathe program that turns M24x2 and taps M8 on the centre line, each named by its comment.
/// Turned with a full-profile insert to X21.423: d2 = basic d2 + (X − basic d3) = 22.70102 +
/// (21.423 − 21.54626) = 22.57776, inside 6g's 22.493–22.663. Tapped: Ø6.8 (the drill's comment)
/// inside M8x1.25-6H's D1 6.647–6.912 (ISO 965-2); F1.25 per revolution = P; the drill's bottom
/// Z-20 lies 6 mm below the tap's Z-14, and the tap's point (basic D1 = 8 − 1.0825·1.25 = 6.647)
/// meets a 118° point 6.647/2/tan 59° = 1.997 mm above the drill's bottom.
#[test]
fn a_lathe_program_s_turned_and_tapped_threads_in_one_report() {
    let (code, v) = verify_json("shaft.nc", &["--insert", "full"]);
    assert_eq!(code, 0, "{v}");
    assert_eq!(processes(&v), ["turned", "tapped"]);
    let ops = v["operations"].as_array().unwrap();
    assert_eq!(ops[0]["thread"]["designation"], "M24X2-6g");
    let d2 = check_of(&ops[0], "pitch_diameter")["value"].as_f64().unwrap();
    assert!((d2 - 22.57776).abs() < 5e-4, "{d2}");
    let tap = &ops[1];
    assert_eq!(tap["tap"]["designation"], "M8X1.25-6H");
    assert_eq!(
        (tap["tap"]["designation_from"].as_str(), tap["tap"]["designation_line"].as_u64()),
        (Some("comment"), Some(16))
    );
    assert_eq!(tap["drill"]["diameter"], 6.8);
    let depth = check_of(tap, "depth");
    let d1_basic = 8.0 - 2.0 * 5.0 / 8.0 * (1.25 * 3f64.sqrt() / 2.0);
    assert!(
        (depth["min"].as_f64().unwrap() - 0.5 * d1_basic / 59f64.to_radians().tan()).abs() < 1e-4,
        "{depth}"
    );
    assert_eq!(tap["verdict"], "pass");
    assert_eq!(v["verdict"], "pass");
}

/// A machining-centre plate: four M8 taps after their drills, at (20, 20), (60, 20), (60, 60)
/// and (20, 60) (G98 G81/G84 repeats at the X/Y words), and an M20x1.5 milled on helices of
/// radius 7.21 by a sharp 60° Ø6 cutter. Tapped: F625 per minute = S500 × 1.25. Milled: the
/// tooth's tip runs at 7.21 + 3 = 10.21, and a sharp 60° V is P/2 wide 0.6495 (= P/(4·tan 30°))
/// inside its tip, so the tooth profile's D2 = 2·(10.21 − 0.6495) = 19.121, 6H's middle
/// (19.026–19.216).
#[test]
fn a_machining_centre_s_taps_and_milled_thread_in_one_report() {
    let tools = data("whole/plate-tools.toml");
    let (code, v) = verify_json("plate.nc", &["--tools", tools.to_str().unwrap()]);
    assert_eq!(code, 0, "{v}");
    assert_eq!(processes(&v), ["tapped", "tapped", "tapped", "tapped", "milled"]);
    let ops = v["operations"].as_array().unwrap();
    let at: Vec<(f64, f64)> = ops[..4]
        .iter()
        .map(|o| (o["cycle"]["x"].as_f64().unwrap(), o["cycle"]["y"].as_f64().unwrap()))
        .collect();
    assert_eq!(at, [(20.0, 20.0), (60.0, 20.0), (60.0, 60.0), (20.0, 60.0)]);
    for o in &ops[..4] {
        assert_eq!(o["tap"]["designation"], "M8X1.25-6H");
        assert_eq!(o["drill"]["diameter"], 6.8);
        assert_eq!(check_of(o, "feed")["min"], 625.0);
        assert_eq!(o["verdict"], "pass");
    }
    let milled = &ops[4];
    assert_eq!(milled["designation"], "M20X1.5-6H");
    assert_eq!(
        (milled["designation_from"].as_str(), milled["designation_line"].as_u64()),
        (Some("comment"), Some(23))
    );
    let d2 = milled["tooth_profile"]["pitch_diameter"].as_f64().unwrap();
    let expected = 2.0 * (10.21 - 1.5 / (4.0 * 30f64.to_radians().tan()));
    assert!((d2 - expected).abs() < 5e-4, "{d2} against {expected}");
    assert_eq!(milled["verdict"], "pass");
}

/// Without the thread mill in a tool table the helices are not checked, and the program does
/// not pass: nothing a program makes is passed unseen.
#[test]
fn helices_whose_cutter_is_not_known_fail_as_not_checked() {
    let (code, v) = verify_json("plate.nc", &[]);
    assert_eq!(code, 1);
    let last = v["operations"].as_array().unwrap().last().unwrap().clone();
    assert_eq!(last["made"], "milled");
    assert_eq!(last["verdict"], "fail");
    // The first G3 (line 28; line 27 is the straight feed in).
    assert_eq!(last["line"], 28);
    assert!(last["reason"].as_str().unwrap().contains("tool T12 are not checked"), "{last}");
    let o = run(&["verify", "--program", data("whole/plate.nc").to_str().unwrap()]);
    assert!(stdout(&o).contains("program verdict: FAIL (the milled thread)"), "{}", stdout(&o));
}

/// `tap` reads the taps and drills from the program's comments too: no tool table needed.
#[test]
fn tap_names_its_taps_and_drills_from_the_comments() {
    let o = run(&["tap", "--program", data("whole/plate.nc").to_str().unwrap(), "--json", "-"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["holes"].as_array().unwrap().len(), 4);
    assert!(v["holes"]
        .as_array()
        .unwrap()
        .iter()
        .all(|h| h["drill"]["diameter"] == 6.8 && h["pass"] == true));
}
