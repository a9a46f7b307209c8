//! Issue 31, tapping: G84/G74 cycles checked against the tap's class and the drill that made the
//! hole. Limits from ISO 965-2 (M10x1.5-6H: D1 8.376–8.676); the rest derived in the comments.

use crate::*;

fn program() -> String {
    std::fs::read_to_string(data("programs/tapping/m10-g84.nc")).unwrap()
}

/// Runs `tap --json -` on `text` with the tool table `tools` (TOML text): exit code and JSON.
fn tap(text: &str, tools: &str) -> (i32, serde_json::Value, String) {
    let dir = tempdir("tap");
    std::fs::write(dir.join("p.nc"), text).unwrap();
    std::fs::write(dir.join("tools.toml"), tools).unwrap();
    let o = run_in(
        &dir,
        &["tap", "--program", "p.nc", "--tools", "tools.toml", "--dialect", "fanuc", "--json", "-"],
    );
    let code = o.status.code().unwrap();
    let v = if code < 2 { serde_json::from_slice(&o.stdout).unwrap() } else { serde_json::Value::Null };
    (code, v, stderr(&o))
}

fn check<'a>(v: &'a serde_json::Value, feature: &str) -> &'a serde_json::Value {
    v["holes"][0]["checks"].as_array().unwrap().iter().find(|c| c["feature"] == feature).unwrap()
}

const TOOLS: &str = "[tools]\n5 = \"drill:8.5\"\n6 = \"tap:M10x1.5-6H\"\n";

/// Ø8.5 (ISO 2306's tap drill for M10x1.5) lies within D1 8.376–8.676 of 6H; Ø8.0 lies 376 µm
/// under D1 min whatever the tap.
#[test]
fn the_drill_is_checked_against_d1() {
    let (code, v, e) = tap(&program(), TOOLS);
    assert_eq!(code, 0, "{e}");
    let d1 = check(&v, "drill_diameter");
    assert_eq!(
        (d1["value"].as_f64(), d1["min"].as_f64(), d1["max"].as_f64()),
        (Some(8.5), Some(8.376), Some(8.676))
    );
    assert_eq!(d1["ok"], true);
    assert_eq!(v["holes"][0]["drill"]["cycle"]["line"], 7);
    let (code, v, e) = tap(&program(), &TOOLS.replace("drill:8.5", "drill:8.0"));
    assert_eq!(code, 1, "{e}");
    let d1 = check(&v, "drill_diameter");
    assert_eq!(d1["ok"], false);
    assert!((d1["deviation"].as_f64().unwrap() + 376.0).abs() < 1e-9, "{d1}");
}

/// Feed per revolution (G99) must be the pitch: F1.4 is 0.1 mm/rev short. Per minute (G98) it
/// must be S × P = 300 × 1.5 = 450 mm/min: F450 passes, F400 fails by 50.
#[test]
fn the_feed_is_checked_against_the_lead() {
    let (code, v, _) = tap(&program().replace("G84 Z-18.0 R5.0 F1.5", "G84 Z-18.0 R5.0 F1.4"), TOOLS);
    assert_eq!(code, 1);
    let f = check(&v, "feed");
    assert_eq!((f["ok"].as_bool(), f["unit"].as_str()), (Some(false), Some("mm/rev")));
    assert!((f["deviation"].as_f64().unwrap() + 100.0).abs() < 1e-6, "{f}");
    let per_min = program()
        .replace("G21 G99 G18", "G21 G98 G18")
        .replace("G83 Z-25.0 R2.0 Q5000 F0.12", "G83 Z-25.0 R2.0 Q5000 F120");
    let (code, v, e) = tap(&per_min.replace("G84 Z-18.0 R5.0 F1.5", "G84 Z-18.0 R5.0 F450"), TOOLS);
    assert_eq!(code, 0, "{e} {v}");
    assert_eq!(check(&v, "feed")["min"], 450.0);
    let (code, v, _) = tap(&per_min.replace("G84 Z-18.0 R5.0 F1.5", "G84 Z-18.0 R5.0 F400"), TOOLS);
    assert_eq!(code, 1);
    assert!((check(&v, "feed")["deviation"].as_f64().unwrap() + 50.0).abs() < 1e-9);
}

/// The tap's bottom must stay its chamfer above the drill's: 2.5 pitches = 3.75 mm by default.
/// Tapped to Z−22 in a hole drilled to Z−25 leaves 3 mm: fails; with a 1.5-pitch (2.25 mm)
/// chamfer tap it passes.
#[test]
fn the_depth_leaves_room_for_the_chamfer() {
    let deep = program().replace("G84 Z-18.0", "G84 Z-22.0");
    let (code, v, _) = tap(&deep, TOOLS);
    assert_eq!(code, 1);
    let d = check(&v, "depth");
    assert_eq!(
        (d["value"].as_f64(), d["min"].as_f64(), d["ok"].as_bool()),
        (Some(3.0), Some(3.75), Some(false))
    );
    let (code, v, _) = tap(&deep, &TOOLS.replace("tap:M10x1.5-6H", "tap:M10x1.5-6H:1.5"));
    assert_eq!(code, 0);
    assert_eq!(check(&v, "depth")["min"], 2.25);
}

/// G84 cuts a right-hand thread with the spindle clockwise: M4 before it fails.
#[test]
fn the_spindle_turns_the_taps_way() {
    let (code, v, _) = tap(&program().replace("G97 S300 M3", "G97 S300 M4"), TOOLS);
    assert_eq!(code, 1);
    assert_eq!(check(&v, "spindle")["ok"], false);
}

/// A tap the table does not know, and a program without a tapping cycle, are errors that say so.
#[test]
fn a_tap_needs_its_tool() {
    let (code, _, e) = tap(&program(), "[tools]\n5 = \"drill:8.5\"\n6 = \"full\"\n");
    assert_eq!(code, 2);
    assert_eq!(
        e.trim(),
        "threadcheck: error: p.nc:14:1: G84 with tool T6, which tools.toml calls \"full\", not a tap (write 6 = \"tap:M10x1.5-6H\")"
    );
    let (code, _, e) = tap("G0 X0 Z5\nG83 Z-25 R2 F0.1\nM30\n", TOOLS);
    assert_eq!(code, 2);
    assert!(e.contains("no tapping cycle in the program"), "{e}");
}

/// LinuxCNC's rigid tapping G33.1 Z K (K the distance per revolution) after a G83: the same
/// checks, K against the lead (K1.4 for M10x1.5 is 0.1 mm/rev short).
#[test]
fn linuxcnc_g33_1_is_a_tapping_cycle() {
    let program = "G21 G18\nT1 M6\nS600 M3\nG0 X0 Z5\nG83 X0 Z-25 R2 Q5 F0.1\nG80\nT2 M6\nS300 M3\nG0 X0 Z8\nG33.1 Z-18 K1.5\nM2\n";
    let tools = "[tools]\n1 = \"drill:8.5\"\n2 = \"tap:M10x1.5-6H\"\n";
    let run_tap = |text: &str| {
        let dir = tempdir("tap-lcnc");
        std::fs::write(dir.join("p.ngc"), text).unwrap();
        std::fs::write(dir.join("tools.toml"), tools).unwrap();
        let o = run_in(&dir, &["tap", "--program", "p.ngc", "--tools", "tools.toml", "--json", "-"]);
        (o.status.code().unwrap(), serde_json::from_slice::<serde_json::Value>(&o.stdout).unwrap_or_default())
    };
    let (code, v) = run_tap(program);
    assert_eq!(code, 0, "{v}");
    assert_eq!(v["dialect"], "linuxcnc");
    assert_eq!(v["holes"][0]["cycle"]["code"], "G33.1");
    assert_eq!(check(&v, "drill_diameter")["ok"], true);
    let (code, v) = run_tap(&program.replace("K1.5", "K1.4"));
    assert_eq!(code, 1);
    assert!((check(&v, "feed")["deviation"].as_f64().unwrap() + 100.0).abs() < 1e-6);
}
