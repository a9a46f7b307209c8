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
    assert!(
        last["reason"].as_str().unwrap().contains("the thread mill T12 of the helices is not known"),
        "{last}"
    );
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

/// Issue 46 item 3, a library in one run: `verify FOLDER FILE…` verifies every program (a
/// folder's by their extensions, recursively, in name order), one line per operation and a
/// summary; an unreadable file is its one located line in the run, not its end, and the exit
/// status is the worst (2). Copies of our test programs, so the lines are known: the plate's four
/// taps pass and its helices (no thread mill known) fail; the shaft's partial-insert default fails
/// its turned thread on the root radius and more, its tap passes.
#[test]
fn a_library_in_one_run_with_json_lines() {
    let dir = tempdir("library");
    let lib = dir.join("lib");
    std::fs::create_dir_all(lib.join("lathe")).unwrap();
    std::fs::copy(data("whole/plate.nc"), lib.join("plate.nc")).unwrap();
    // The shaft's G76 ending at X21.7 (d2 22.855 over 6g's 22.663): a turned thread that fails.
    let shaft =
        std::fs::read_to_string(data("whole/shaft.nc")).unwrap().replace("G76 X21.423 ", "G76 X21.7 ");
    std::fs::write(lib.join("lathe/shaft.NC"), shaft).unwrap();
    std::fs::write(lib.join("notes.txt"), "not a program").unwrap();
    std::fs::write(
        lib.join("broken.nc"),
        "G0 X10 Z5\nG76 P010060 Q100 R0.05\nG76 X8 Z-10 P1000 Q300 F1.5 G\n",
    )
    .unwrap();
    let o = run_in(&dir, &["verify", "lib", "--json-lines", "out.jsonl"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let text = stdout(&o);
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines[0].starts_with("error: lib/broken.nc:3:"), "{text}");
    assert_eq!(lines[1], "lib/lathe/shaft.NC:8: FAIL turned M24X2-6g (comment): major diameter d, pitch diameter d2, GO gauge (max. material)");
    assert_eq!(lines[2], "lib/lathe/shaft.NC:19: PASS tapped M8X1.25-6H (comment)");
    assert_eq!(lines[3], "lib/plate.nc:18: PASS tapped M8X1.25-6H (comment)");
    assert!(
        lines[7].starts_with("lib/plate.nc:28: FAIL milled —: not checked: the thread mill T12"),
        "{text}"
    );
    assert_eq!(lines[8], "2 programs read, 7 operations: 5 pass, 2 fail; 1 unreadable");
    assert_eq!(lines.len(), 9, "notes.txt is not a program: {text}");
    let jsonl = std::fs::read_to_string(dir.join("out.jsonl")).unwrap();
    let objects: Vec<serde_json::Value> = jsonl.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert_eq!(objects.len(), 4);
    assert_eq!(objects[0]["verdict"], "error");
    assert_eq!(objects[1]["file"], "lib/lathe/shaft.NC");
    assert_eq!(objects[1]["operations"][1]["made"], "tapped");
    assert_eq!(
        objects[3]["summary"],
        serde_json::json!({"programs": 2, "operations": 7, "pass": 5, "fail": 2, "unreadable": 1})
    );
    // Without the broken file the worst is a failing operation (exit 1); with the shaft as drawn
    // (X21.423), the thread mill and a full-profile insert (as the one-program tests above)
    // every operation passes (exit 0).
    std::fs::remove_file(lib.join("broken.nc")).unwrap();
    let o = run_in(&dir, &["verify", "lib"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    std::fs::copy(data("whole/shaft.nc"), lib.join("lathe/shaft.NC")).unwrap();
    let tools = data("whole/plate-tools.toml");
    let o = run_in(&dir, &["verify", "lib", "--insert", "full", "--tools", tools.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stdout(&o).ends_with("2 programs read, 7 operations: 7 pass, 0 fail\n"), "{}", stdout(&o));
}

/// A run of many refuses the one program's documents, and an empty folder says what it looked for.
#[test]
fn a_library_run_refuses_one_program_s_documents() {
    let dir = tempdir("library-refusals");
    std::fs::create_dir_all(dir.join("empty")).unwrap();
    let o = run_in(&dir, &["verify", "empty"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        one_line_error(&o),
        "threadcheck: error: no program in empty (looked for the extensions .nc .ngc .mpf .spf .min .ssb .sub .tap .cnc .eia .gcode .iso, and .h files that open a Klartext program)"
    );
    let o = run_in(&dir, &["verify", "empty", "--svg", "x.svg"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        one_line_error(&o),
        "threadcheck: error: --svg is one program's: give it with --program, or --json-lines for a run of many"
    );
}

/// Issue 58 item 4: a run of many follows symbolic links to programs and folders (a failing
/// program linked in was skipped: exit 0 and PASS), names a loop once, never opens a FIFO (one
/// named `*.h` hung the run for ever), names files that are not UTF-8 apart and escapes a
/// newline in a name (it forged a line of the report).
#[test]
fn a_library_run_follows_links_and_opens_only_regular_files() {
    use std::os::unix::ffi::OsStrExt;
    let dir = tempdir("library-links");
    let (lib, other) = (dir.join("lib"), dir.join("other"));
    std::fs::create_dir_all(&lib).unwrap();
    std::fs::create_dir_all(other.join("deep")).unwrap();
    // A failing shaft (G76 to X21.7: d2 22.855 over 6g's 22.663) outside the folder, linked in.
    let failing =
        std::fs::read_to_string(data("whole/shaft.nc")).unwrap().replace("G76 X21.423 ", "G76 X21.7 ");
    std::fs::write(other.join("failing.nc"), &failing).unwrap();
    std::fs::write(other.join("deep/plain.nc"), std::fs::read(data("whole/shaft.nc")).unwrap()).unwrap();
    std::os::unix::fs::symlink("../other/failing.nc", lib.join("linked.nc")).unwrap();
    std::os::unix::fs::symlink("../other/deep", lib.join("deep")).unwrap();
    std::os::unix::fs::symlink("..", lib.join("up")).unwrap();
    for fifo in ["pipe.h", "pipe.nc"] {
        assert!(Command::new("mkfifo").arg(lib.join(fifo)).status().unwrap().success());
    }
    for name in [&b"a\xfe.nc"[..], &b"a\xff.nc"[..], &b"nl\nPASS.nc"[..]] {
        std::fs::write(
            lib.join(std::ffi::OsStr::from_bytes(name)),
            std::fs::read(data("whole/shaft.nc")).unwrap(),
        )
        .unwrap();
    }
    let o = run_in(&dir, &["verify", "lib", "--insert", "full"]);
    let text = stdout(&o);
    assert_eq!(o.status.code(), Some(2), "{text}");
    assert!(text.contains("lib/linked.nc:8: FAIL turned M24X2-6g"), "{text}");
    assert!(text.contains("lib/deep/plain.nc:8: PASS"), "{text}");
    assert!(text.contains("lib/a\\xfe.nc:8: PASS") && text.contains("lib/a\\xff.nc:8: PASS"), "{text}");
    assert!(
        text.contains("lib/nl\\u{a}PASS.nc:8: PASS") && !text.lines().any(|l| l.starts_with("PASS")),
        "{text}"
    );
    for fifo in ["pipe.h", "pipe.nc"] {
        assert!(text.contains(&format!("{fifo}: not a regular file")), "{text}");
    }
    assert!(text.contains("a link back to a folder it is in (a loop)"), "{text}");
    // Each file once: the linked shaft is not read again through `up`.
    assert_eq!(text.matches(":8: FAIL turned").count(), 1, "{text}");
}
