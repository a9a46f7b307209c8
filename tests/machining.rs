//! Issue 45, machining centres: a program is read for the machine it runs on (lathe or mill),
//! given or found in its own words, and a machining centre's codes mean what they mean there
//! (G90/G91 absolute and incremental, G98/G99 return levels, G73/G74/G76 drilling, left-hand
//! tapping and fine boring, K repeats). Positions and levels are derived by hand in the
//! comments from the rules of ../shared/notes/machining-centres.md §1.2 (G91: X, Y increments;
//! R from the initial level; Z from the R level).

use crate::*;

/// `tap --json -` on a file of `tests/data/machining/` with its tool table; extra arguments
/// after.
fn tap_file(name: &str, extra: &[&str]) -> (i32, serde_json::Value, String) {
    let program = data(&format!("machining/{name}.nc"));
    let tools = data(&format!("machining/{name}.toml"));
    let mut args = vec!["tap", "--program", program.to_str().unwrap(), "--tools", tools.to_str().unwrap()];
    args.extend(extra);
    args.extend(["--json", "-"]);
    let o = run(&args);
    let code = o.status.code().unwrap();
    let v = if code < 2 { serde_json::from_slice(&o.stdout).unwrap() } else { serde_json::Value::Null };
    (code, v, stderr(&o))
}

/// The line of each tap's drilling cycle.
fn drill_lines(v: &serde_json::Value) -> Vec<u64> {
    v["holes"].as_array().unwrap().iter().map(|h| h["drill"]["cycle"]["line"].as_u64().unwrap()).collect()
}

/// A hole: x, y, bottom (mm) and its cycle's line.
type Hole = (Option<f64>, Option<f64>, Option<f64>, u64);

/// Every hole's (x, y, bottom) and the line of its cycle.
fn holes(v: &serde_json::Value) -> Vec<Hole> {
    v["holes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|h| {
            let c = &h["cycle"];
            (c["x"].as_f64(), c["y"].as_f64(), c["bottom"].as_f64(), c["line"].as_u64().unwrap())
        })
        .collect()
}

/// A Fanuc machining-centre program with the usual header (`G28 G91 Z0.` then `G90 G54`):
/// G99 drilling at X20 and X40 Y15 (G90: positions), then `G91 X20. Z-22. R-22. K2` from X40:
/// holes at X60 and X80, R = the initial level Z25 − 22 = Z3, bottom Z3 − 22 = Z−19; a G98 G76
/// fine boring at X20 (a hole-making cycle on a mill, no thread); then M29 rigid tapping G99 G84
/// at X20 and X40 to Z−15 (R5), and `G91 G98 X20. Z-20. R-20. K2`: R = 25 − 20 = Z5, bottom
/// Z5 − 20 = Z−15 at X60 and X80. G99 is the return level, not feed per revolution: F750 at
/// S600 is 600 × 1.25, the M8x1.25 tap's lead, per minute (the mill's power-on G94). Each tap
/// finds its hole's drill (Ø6.9 bore at X20, Ø6.8 drill elsewhere, both within 6H's D1
/// 6.647–6.912, ISO 965-2) 4 mm below its bottom, more than the 1.997 mm at which the tap's
/// point (D1 basic 6.647) meets the drill's 118° point (6.647/2 / tan 59°).
#[test]
fn a_machining_centre_program_with_the_g91_header_drills_bores_and_taps_where_it_says() {
    let (code, v, e) = tap_file("fanuc-mill-plate", &[]);
    assert_eq!(code, 0, "{e}");
    assert_eq!(v["machine"]["machine_type"], "mill");
    assert!(v["machine"]["reason"].as_str().unwrap().contains("line 5 writes G17"), "{}", v["machine"]);
    assert_eq!(
        holes(&v),
        [
            (Some(20.0), Some(15.0), Some(-15.0), 26),
            (Some(40.0), Some(15.0), Some(-15.0), 27),
            (Some(60.0), Some(15.0), Some(-15.0), 28),
            (Some(80.0), Some(15.0), Some(-15.0), 28),
        ]
    );
    // Four drilled holes and the bore: five hole-making cycles.
    assert_eq!(v["drills"], 5);
    let drills: Vec<(String, u64)> = v["holes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|h| {
            let c = &h["drill"]["cycle"];
            (c["code"].as_str().unwrap_or("").to_string(), c["line"].as_u64().unwrap_or(0))
        })
        .collect();
    assert_eq!(drills[0], ("G76".into(), 18));
    assert_eq!(drills[1], ("G81".into(), 10));
    assert_eq!(drills[2], ("G81".into(), 11));
    let bore = &v["holes"][0]["drill"];
    assert_eq!((bore["diameter"].as_f64(), bore["cycle"]["bottom"].as_f64()), (Some(6.9), Some(-19.0)));
    for h in v["holes"].as_array().unwrap() {
        let feed = h["checks"].as_array().unwrap().iter().find(|c| c["feature"] == "feed").unwrap();
        assert_eq!(feed["value"].as_f64(), Some(750.0), "{feed}");
        assert_eq!(feed["ok"], true);
        assert_eq!(h["pass"], true, "{h}");
    }
}

/// The same program read as a lathe (`--machine-type lathe`): the type given is obeyed (issue
/// 61: the user's word wins; it was refused at the G17 of line 5), so its G76 is a lathe's
/// threading cycle, which under G17 is refused at its own place; read as a mill, the type given
/// is stated.
#[test]
fn the_machine_type_given_wins() {
    let (code, _, e) = tap_file("fanuc-mill-plate", &["--machine-type", "lathe"]);
    assert_eq!(code, 2);
    assert!(
        e.ends_with(
            "fanuc-mill-plate.nc:18:5: G76 under G17: threading is programmed in the lathe plane G18\n"
        ),
        "{e}"
    );
    let (code, v, e) = tap_file("fanuc-mill-plate", &["--machine-type", "mill"]);
    assert_eq!(code, 0, "{e}");
    assert_eq!(v["machine"]["reason"], "read as a mill, as --machine-type says");
}

/// A machining centre's G74 is a left-hand tapping cycle (with the spindle counter-clockwise),
/// and a G76 between the drill and the tap is no threading cycle.
#[test]
fn g74_taps_left_hand_on_a_mill() {
    let dir = tempdir("g74");
    let program = "G17 G21 G90 G54\nT5 M6\nG0 X0 Y0 S800 M3\nG43 H5 Z20.\nG98 G81 Z-20. R2. F120\nG80\nT6 M6\nG0 X0 Y0 S300 M4\nG43 H6 Z20.\nG94 G98 G74 Z-14. R3. F450.\nG80\nM30\n";
    std::fs::write(dir.join("lh.nc"), program).unwrap();
    std::fs::write(dir.join("t.toml"), "[tools]\n5 = \"drill:8.5\"\n6 = \"tap:M10x1.5-LH-6H\"\n").unwrap();
    let o = run_in(&dir, &["tap", "--program", "lh.nc", "--tools", "t.toml", "--json", "-"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let c = &v["holes"][0]["cycle"];
    // 300 rpm × 1.5 mm = 450 mm/min; the hole at X0 Y0 to Z−14.
    assert_eq!(
        (c["code"].as_str(), c["hand"].as_str(), c["bottom"].as_f64()),
        (Some("G74"), Some("left"), Some(-14.0))
    );
    assert_eq!(c["x"].as_f64(), Some(0.0));
}

/// LinuxCNC on a mill (G17 shows it): X is X, not a diameter; G33.1 taps at X12.5 Y8.
#[test]
fn linuxcnc_on_a_mill_reads_x_as_x() {
    let dir = tempdir("lcnc-mill");
    let program = "G17 G21 G90\nT1 M6\nG0 X12.5 Y8 Z5\nS500 M3\nG33.1 Z-15 K1.5\nM2\n";
    std::fs::write(dir.join("tap.ngc"), program).unwrap();
    std::fs::write(dir.join("t.toml"), "[tools]\n1 = \"tap:M10x1.5-6H\"\n").unwrap();
    let o = run_in(&dir, &["tap", "--program", "tap.ngc", "--tools", "t.toml", "--json", "-"]);
    assert!(o.status.code().unwrap() < 2, "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["machine"]["machine_type"], "mill");
    let c = &v["holes"][0]["cycle"];
    assert_eq!(
        (c["x"].as_f64(), c["y"].as_f64(), c["bottom"].as_f64()),
        (Some(12.5), Some(8.0), Some(-15.0))
    );
}

/// A lathe program stays a lathe's: its T0101 shows it, and the notes say so.
#[test]
fn a_lathe_program_shows_its_lathe() {
    let dir = tempdir("lathe-evidence");
    let program = "T0101\nG97 S800 M3\nG0 X22 Z5\nG92 X19.2 Z-20 F1.5\nX18.8\nX18.376\nG0 X50\nM30\n";
    std::fs::write(dir.join("l.nc"), program).unwrap();
    let o = run_in(&dir, &["passes", "--program", "l.nc", "--json", "-"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["machine"]["machine_type"], "lathe");
    assert!(v["machine"]["reason"].as_str().unwrap().contains("line 1 writes T0101"), "{}", v["machine"]);
    assert_eq!(v["passes"].as_array().unwrap().len(), 3);
}

/// A repeat count that is no whole number is one located line.
#[test]
fn a_repeat_count_must_be_whole() {
    let dir = tempdir("k-bad");
    std::fs::write(
        dir.join("k.nc"),
        "G17 G21 G90\nT1 M6\nG0 X0 Y0 Z10\nG91 G99 G81 X10. Z-5. R-8. K2.5 F100\nM30\n",
    )
    .unwrap();
    std::fs::write(dir.join("t.toml"), "[tools]\n1 = \"drill:8.5\"\n").unwrap();
    let o = run_in(&dir, &["tap", "--program", "k.nc", "--tools", "t.toml"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        one_line_error(&o),
        "threadcheck: error: k.nc:4:28: K2.5: a cycle's repeat count is a whole number from 0 to 9999"
    );
}

/// G68 rotates the tap's programmed X0 Y75 about X0 Y0 by 0°, 90°, 180° and 270°: the holes at
/// (0, 75), (−75, 0), (0, −75) and (75, 0), where the drill made them (each matched to its own
/// G81 position at lines 6–9); G52 X100 Y50 moves the tap at X10 Y10 to (110, 60), line 10's
/// hole. Every position in the G54 frame.
#[test]
fn g68_rotation_and_g52_local_system_place_the_holes() {
    let (code, v, e) = tap_file("fanuc-g68-g52", &[]);
    assert_eq!(code, 0, "{e}");
    assert_eq!(
        holes(&v),
        [
            (Some(0.0), Some(75.0), Some(-18.0), 17),
            (Some(-75.0), Some(0.0), Some(-18.0), 21),
            (Some(0.0), Some(-75.0), Some(-18.0), 25),
            (Some(75.0), Some(0.0), Some(-18.0), 29),
            (Some(110.0), Some(60.0), Some(-18.0), 33),
        ]
    );
    assert_eq!(drill_lines(&v), [6, 7, 8, 9, 10]);
}

/// Haas G70 I40 J0 L6 in an M97 local subroutine, after a cycle stored with L0: six holes 60°
/// apart on a 40 mm radius about X0 Y0 from 0°, so (40, 0), (20, 34.641), (−20, 34.641),
/// (−40, 0), (−20, −34.641), (20, −34.641) (40·cos 60° = 20, 40·sin 60° = 34.641), drilled to
/// Z−20 and tapped to Z−16 at each; F750 = S600 × 1.25 per minute.
#[test]
fn a_haas_bolt_circle_in_an_m97_subroutine_drills_and_taps_six_holes() {
    let (code, v, e) = tap_file("haas-g70-m97", &["--dialect", "haas"]);
    assert_eq!(code, 0, "{e}");
    assert_eq!(v["drills"], 6);
    let s = 40.0 * 60f64.to_radians().sin();
    let want = [(40.0, 0.0), (20.0, s), (-20.0, s), (-40.0, 0.0), (-20.0, -s), (20.0, -s)];
    let got = holes(&v);
    assert_eq!(got.len(), 6);
    for ((x, y, bottom, line), (wx, wy)) in got.into_iter().zip(want) {
        assert!((x.unwrap() - wx).abs() < 1e-9 && (y.unwrap() - wy).abs() < 1e-9, "({x:?}, {y:?})");
        assert_eq!((bottom, line), (Some(-16.0), 17));
    }
    assert!(v["holes"].as_array().unwrap().iter().all(|h| h["pass"] == true));
}

/// Haas's holes along an angle, `G72 I15. J30. L4` from X10 Y5 after a drilling and a tapping
/// cycle written with L0: four holes 15 mm apart on the 30° line, the first at the current point
/// (the named default): (10 + 15k·cos 30°, 5 + 15k·sin 30°) for k = 0…3, i.e. (10, 5),
/// (22.990381, 12.5), (35.980762, 20), (48.971143, 27.5); each drilled to Z−20 and tapped to
/// Z−16 (F750 = S600 × 1.25), the default said.
#[test]
fn a_haas_line_of_holes_at_an_angle_is_drilled_and_tapped() {
    let (code, v, e) = tap_file("haas-g72-line", &["--dialect", "haas"]);
    assert_eq!(code, 0, "{e}");
    assert_eq!(v["drills"], 4);
    let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    let got = holes(&v);
    assert_eq!(got.len(), 4);
    for (k, (x, y, bottom, line)) in got.into_iter().enumerate() {
        let (wx, wy) = (10.0 + 15.0 * k as f64 * c, 5.0 + 15.0 * k as f64 * s);
        assert!((x.unwrap() - wx).abs() < 1e-9 && (y.unwrap() - wy).abs() < 1e-9, "hole {k}: ({x:?}, {y:?})");
        assert_eq!((bottom, line), (Some(-16.0), 14));
    }
    assert!(v["holes"].as_array().unwrap().iter().all(|h| h["pass"] == true));
    assert!(
        v["notes"].to_string().contains("the first at the current point (a named default"),
        "{}",
        v["notes"]
    );
}

/// Work offsets: `fanuc-g10-fixtures.nc` sets G54's origin to X−400 Y−200, G55's and G54.1 P2's
/// to X−250 Y−200 by G10 L2/L20, drills X20 Y10 in G54 with Ø6.8 (machine −380, −190) and in G55
/// with Ø6.0 (machine −230, −190), then taps M8x1.25 four times. By hand: the G54 tap at X20 Y10
/// is the Ø6.8 hole (passes, D1 6.647–6.912); the G55 tap at X20 Y10 is the Ø6.0 one (fails: it
/// was matched to the last drill at X20 Y10 whatever its offset); the G54 tap at X170 Y10 lies at
/// machine −230, −190, the G55 hole (fails); the G54.1 P2 tap at X20 Y10 too (fails).
#[test]
fn taps_find_their_drills_in_their_own_work_offsets() {
    let (code, v, e) = tap_file("fanuc-g10-fixtures", &[]);
    assert_eq!(code, 1, "{e}");
    let hs = v["holes"].as_array().unwrap();
    let got: Vec<(u64, f64, bool, String)> = hs
        .iter()
        .map(|h| {
            (
                h["drill"]["cycle"]["line"].as_u64().unwrap(),
                h["drill"]["diameter"].as_f64().unwrap(),
                h["pass"].as_bool().unwrap(),
                h["cycle"]["work_offset"].as_str().unwrap().to_string(),
            )
        })
        .collect();
    let want = [
        (10, 6.8, true, "G54"),
        (15, 6.0, false, "G55"),
        (15, 6.0, false, "G54"),
        (15, 6.0, false, "G54.1 P2"),
    ];
    for (g, w) in got.iter().zip(want) {
        assert_eq!((g.0, g.1, g.2, g.3.as_str()), w, "{got:?}");
    }
    // Each hole's place in machine coordinates, by hand from the G10 origins (issue 62): the
    // G54 drill at X20 Y10 stands at (−380, −190), the G55 one at (−230, −190).
    let machine: Vec<(f64, f64)> = hs
        .iter()
        .map(|h| {
            let m = &h["drill"]["cycle"]["machine_xy"];
            (m[0].as_f64().unwrap(), m[1].as_f64().unwrap())
        })
        .collect();
    assert_eq!(machine, [(-380.0, -190.0), (-230.0, -190.0), (-230.0, -190.0), (-230.0, -190.0)]);
    assert!(v["notes"]
        .to_string()
        .contains("G10 L20 P2 read past: sets G54.1 P2's origin in machine coordinates"));
}

/// Haas's additional work offsets: G129 is G154 P20 (G110 = G154 P1), so a tap in G154 P20 finds
/// the drill made in G129 at the same X Y, and a tap in G154 P19 does not.
#[test]
fn haas_g110_to_g129_are_g154_p1_to_p20() {
    let dir = tempdir("haas-g129");
    let program = |tap_offset: &str| {
        format!("G17 G21 G90 G94\nT1 M6 (DRILL 6.8)\nG129 G0 X10. Y10. S2000 M3\nG98 G81 Z-20. R2. F200.\nG80\nT2 M6 (TAP M8X1.25)\n{tap_offset} G0 X10. Y10. S600 M3\nG98 G84 Z-15. R3. F750.\nG80\nM30\n")
    };
    for (offset, drilled) in [("G154 P20", true), ("G154 P19", false)] {
        std::fs::write(dir.join("h.nc"), program(offset)).unwrap();
        let (code, v) = run_json(&[
            "tap",
            "--program",
            dir.join("h.nc").to_str().unwrap(),
            "--dialect",
            "haas",
            "--json",
            "-",
        ]);
        assert!(code < 2, "{v}");
        let h = &v["holes"][0];
        assert_eq!(h["cycle"]["work_offset"], offset);
        assert_eq!(h["drill"].is_object(), drilled, "{offset}: {h}");
    }
}

/// Radial holes with a live tool on a lathe (issue 45 item 4): `haas-radial-taps.nc` drills Ø5 to
/// X20 with G241 and taps M6x1 to X24 with G195 at Z−10, C0 and C90 (the drill and the tap named
/// in comments). By hand: each tap finds the drill at its Z and C; their bottoms are the radii 12
/// and 10, 2 mm apart along X; the tap's point (Ø4.9175, D1 basic = 6 − 1.25·0.866025) meets the
/// drill's 118° point 0.5·4.91747 / tan 59° = 1.4774 mm above its bottom, so the depth passes;
/// F1 under G99 is the lead. Fanuc's G87/G88 from the side read the same way.
#[test]
fn radial_live_tool_holes_are_drilled_and_tapped_along_x() {
    let program = data("machining/haas-radial-taps.nc");
    let (code, v) =
        run_json(&["tap", "--program", program.to_str().unwrap(), "--dialect", "haas", "--json", "-"]);
    assert_eq!(code, 0, "{v}");
    let hs = v["holes"].as_array().unwrap();
    assert_eq!(hs.len(), 2, "{v}");
    for (h, (c, drill_line)) in hs.iter().zip([(0.0, 7), (90.0, 8)]) {
        assert_eq!(h["cycle"]["radial"]["z"].as_f64(), Some(-10.0));
        assert_eq!(h["cycle"]["radial"]["c_deg"].as_f64(), Some(c));
        assert_eq!(h["cycle"]["bottom"].as_f64(), Some(12.0));
        assert_eq!(h["drill"]["cycle"]["bottom"].as_f64(), Some(10.0));
        assert_eq!(h["drill"]["cycle"]["line"].as_u64(), Some(drill_line));
        let depth = h["checks"].as_array().unwrap().iter().find(|k| k["feature"] == "depth").unwrap();
        assert_eq!(depth["value"].as_f64(), Some(2.0));
        assert_eq!(depth["min"].as_f64(), Some(1.4774));
        assert_eq!(h["pass"], true, "{h}");
    }
    let dir = tempdir("fanuc-radial");
    std::fs::write(
        dir.join("f.nc"),
        "G18 G21 G99\nT0101 (DRILL 5.0)\nG97 S1000 M3\nG0 X40. Z-10. C0.\nG87 X20. Z-10. C0. R-4. F0.08\nC180.\nG80\nT0202 (TAP M6X1)\nG0 X40. Z-10. C0.\nG88 X24. Z-10. C0. R-4. F1.\nC180.\nG80\nM30\n",
    )
    .unwrap();
    let o = run_in(&dir, &["tap", "--program", "f.nc"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("== G88 at line 11 (Z-10 C180, radial), tool T2, tap M6X1-6H"), "{out}");
    assert!(out.contains("drilled by G87 at line 6, tool T1, Ø5, bottom X20"), "{out}");
}

/// A bolt pattern with no drilling or tapping cycle in force has nothing to place: one located
/// line.
#[test]
fn a_bolt_pattern_needs_a_cycle() {
    let dir = tempdir("g70-alone");
    std::fs::write(dir.join("b.nc"), "G17 G21 G90\nT1 M06\nG0 X0 Y0 Z10\nG70 I40. J0 L6\nM30\n").unwrap();
    std::fs::write(dir.join("t.toml"), "[tools]\n1 = \"drill:8.5\"\n").unwrap();
    let o = run_in(&dir, &["tap", "--program", "b.nc", "--dialect", "haas", "--tools", "t.toml"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        one_line_error(&o),
        "threadcheck: error: b.nc:4:1: G70 places the holes of a drilling or tapping cycle, and none is in force"
    );
}

/// A file as a shop's software writes it: a comment in Latin-1/CP1251 (not UTF-8), CR LF line
/// ends and a DOS end-of-file byte (^Z) after M30. Read: the G92's three passes at X19.2, X18.8
/// and X18.376, and a note naming the comment's line.
#[test]
fn comments_in_another_encoding_and_a_dos_eof_are_read() {
    let p = data("machining/latin1-comment-dos-eof.nc");
    let o = run(&["passes", "--program", p.to_str().unwrap(), "--json", "-"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let xs: Vec<f64> = v["passes"].as_array().unwrap().iter().map(|p| p["x_end"].as_f64().unwrap()).collect();
    assert_eq!(xs, [19.2, 18.8, 18.376]);
    let notes = v["notes"].to_string();
    assert!(
        notes.contains("latin1-comment-dos-eof.nc:1: a comment holds bytes that are not UTF-8"),
        "{notes}"
    );
}

/// A lathe taps on the centre line with thread-cutting moves: `G32 Z-20 F1.5` in at X0, M4, `G32
/// Z5` out. That is a tap of lead 1.5 (M10x1.5) to Z−20 with the spindle clockwise going in (a
/// right-hand thread), after the G83 Ø8.5 drill to Z−25: D1 8.376–8.676 holds 8.5 (ISO 965-2),
/// 5 mm below the tap's bottom clears the drill's point for the tap's point (Ø8.376, D1 basic):
/// 4.188 / tan 59° = 2.516 mm. It was refused ("reaches or crosses
/// the axis").
#[test]
fn a_lathe_taps_on_the_centre_line_with_g32() {
    let (code, v, e) = tap_file("lathe-centre-g32-tap", &[]);
    assert_eq!(code, 0, "{e}");
    assert_eq!(v["machine"]["machine_type"], "lathe");
    // Line 12: the first G32, one line below the program's comment.
    assert_eq!(holes(&v), [(Some(0.0), None, Some(-20.0), 12)]);
    let c = &v["holes"][0]["cycle"];
    assert_eq!(
        (c["code"].as_str(), c["feed"].as_f64(), c["feed_per_rev"].as_bool()),
        (Some("G32"), Some(1.5), Some(true))
    );
    assert_eq!(v["holes"][0]["pass"], true);
}

/// Issue 47: a lead written truncated to the program's increment matches as a rounded one does.
/// 11.5 tpi is 1/11.5 = 0.0869565 in: F0.0870 is its rounding, F0.0869 its truncation to the
/// inch control's 0.0001 in; both are 1-11.5 NPT's lead, and F0.0868 (0.00016 in short, more
/// than one increment) is not. The functional size still counts the remaining error
/// (0.0869565 − 0.0869 = 0.0000565 in a turn).
#[test]
fn a_lead_truncated_to_the_increment_matches() {
    use threadcheck::{lead_deviation, parse_designation, ParseOptions, ProgramUnits};
    let npt = parse_designation("1-11.5 NPT", ParseOptions::default()).unwrap().thread;
    for f in [0.0870, 0.0869] {
        assert!(lead_deviation(f * 25.4, ProgramUnits::Inch, &npt, 25.4).is_ok(), "F{f}");
    }
    assert_eq!(lead_deviation(0.0868 * 25.4, ProgramUnits::Inch, &npt, 25.4), Err(0.0001));
    let d = lead_deviation(0.0869 * 25.4, ProgramUnits::Inch, &npt, 25.4).unwrap().unwrap();
    assert!((d.program_lead - d.designation_lead - (0.0869 - 1.0 / 11.5) * 25.4).abs() < 1e-12);
}

/// Issue 47: a Haas lathe's G84 after M05 passes the spindle check: the control starts the
/// spindle clockwise itself (Haas's G84 page), and the notes say so.
#[test]
fn haas_g84_starts_its_own_spindle() {
    let dir = tempdir("haas-g84");
    let program = "G18 G21 G99\nT0505\nG97 S800 M3\nG0 X0 Z5\nG83 Z-25 R2 Q5000 F0.1\nG80\nM05\nT0606\nG97 S300\nG0 X0 Z5\nG84 Z-18 R5 F1.5\nG80\nM30\n";
    std::fs::write(dir.join("h.nc"), program).unwrap();
    std::fs::write(dir.join("t.toml"), "[tools]\n5 = \"drill:8.5\"\n6 = \"tap:M10x1.5-6H\"\n").unwrap();
    let o =
        run_in(&dir, &["tap", "--program", "h.nc", "--dialect", "haas", "--tools", "t.toml", "--json", "-"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let spindle =
        v["holes"][0]["checks"].as_array().unwrap().iter().find(|c| c["feature"] == "spindle").unwrap();
    assert_eq!(spindle["ok"], true);
    assert!(v["holes"][0]["notes"].to_string().contains("starts the spindle clockwise for G84 itself"));
}

/// Okuma as shops write it: sequence names (`NSTRT`, `NAT06`) label their blocks, `SB=1200`
/// (the rotary tool's speed) is read past with a note, and M33 (zig-zag) is read as alternating
/// flanks (a named default). G71 with M75 (pattern 3, 3277-E): the nth pass to √n·D (D 0.4 on
/// the diameter) until H − U = 1.524, then H = 1.624: 16 passes, X = 27.546 + 1.624 − depth.
/// Alternating at B/2 = 30°: each pass moves along Z by its radial depth increment · tan 30°,
/// one way and then the other, toward −Z first (the cycle threads toward −Z from Z5).
#[test]
fn okuma_labels_rotary_speed_and_zig_zag() {
    let p = data("machining/okuma-labels-m33.min");
    let o = run(&["passes", "--program", p.to_str().unwrap(), "--json", "-"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let passes = v["passes"].as_array().unwrap();
    let mut dia: Vec<f64> = (1..=14).map(|n| 0.4 * f64::from(n).sqrt()).collect();
    dia.extend([1.524, 1.624]);
    assert_eq!(passes.len(), dia.len());
    let (t, mut z, mut prev) = (30f64.to_radians().tan(), 0.0, 0.0);
    for (i, (p, d)) in passes.iter().zip(&dia).enumerate() {
        let r = 0.5 * d;
        z += if i % 2 == 0 { -1.0 } else { 1.0 } * (r - prev) * t;
        prev = r;
        assert!((p["x_end"].as_f64().unwrap() - (27.546 + 1.624 - d)).abs() < 1e-9, "pass {}: {p}", i + 1);
        assert!((p["z_start"].as_f64().unwrap() - (5.0 + z)).abs() < 1e-9, "pass {}: {p}", i + 1);
    }
    let notes = v["notes"].to_string() + &v["operations"][0]["notes"].to_string();
    assert!(notes.contains("SB=1200 read past"), "{notes}");
    assert!(notes.contains("M33 (zig-zag) read as alternating flanks"), "{notes}");
    // Issue 61 item 5: verify's plan says what was cut, read back from the passes (it said the
    // options' `flank 29.5`, `constant-area`): alternating at B/2 = 30°, √n·0.2 mm a side (D 0.4
    // on the diameter) for the 14 passes before H − U.
    let o = run(&["verify", "--program", p.to_str().unwrap(), "--json", "-"]);
    let v: serde_json::Value =
        serde_json::from_slice(&o.stdout).unwrap_or_else(|e| panic!("{e}: {}", stderr(&o)));
    let plan = &v["operations"][0]["plan"];
    assert_eq!(plan["infeed"], serde_json::json!({"method": "alternating", "angle": 30.0}), "{plan}");
    assert_eq!(
        (&plan["schedule"], &plan["from"], &plan["law_passes"]),
        (&"constant-area".into(), &"passes".into(), &14.into()),
        "{plan}"
    );
    assert!((plan["first_depth"].as_f64().unwrap() - 0.2).abs() < 1e-9, "{plan}");
}

/// Issue 45 item 3: a Heidenhain Klartext plate (`tests/data/klartext/plate.h`). Cycle 200 drills
/// Ø6.8 at the two points of `PATTERN DEF` (`CYCL CALL PAT`), cycle 207 taps M8x1.25 at the
/// same points (`L … M99`); then a datum shift (cycle 7: X+100 Y+50) and a rotation (cycle 10:
/// 90°) move the polar pattern of cycle 220 (Ø40 about the datum, four holes from 0°, Q247 = 0
/// over a full circle: every 90°) that drills Ø10.2 and taps M12x1.75LH with cycle 209, its
/// pitch Q239 = Q1 = −1.75 (a left-hand tap). By hand, the pattern's points (20, 0), (0, 20),
/// (−20, 0), (0, −20) turned by 90° ((x, y) → (−y, x)) and shifted: (100, 70), (80, 50),
/// (100, 30), (120, 50). Bottoms: Q203 + Q201, −15 and −20. The stock's bottom is BLK FORM's
/// Z−20: the Ø6.8 drill's full diameter passes it at −25 + 3.4/tan 59° = −22.9571, so the M8
/// holes are through holes.
#[test]
fn klartext_taps_at_patterns_shifted_and_rotated() {
    let program = data("klartext/plate.h");
    let (code, v) = run_json(&["tap", "--program", program.to_str().unwrap(), "--json", "-"]);
    assert_eq!(code, 0, "{v}");
    let got = holes(&v);
    let want = [
        (20.0, 20.0, -15.0),
        (60.0, 20.0, -15.0),
        (100.0, 70.0, -20.0),
        (80.0, 50.0, -20.0),
        (100.0, 30.0, -20.0),
        (120.0, 50.0, -20.0),
    ];
    assert_eq!(got.len(), want.len(), "{got:?}");
    for (g, w) in got.iter().zip(want) {
        assert!((g.0.unwrap() - w.0).abs() < 1e-9 && (g.1.unwrap() - w.1).abs() < 1e-9, "{g:?} {w:?}");
        assert!((g.2.unwrap() - w.2).abs() < 1e-9, "{g:?} {w:?}");
    }
    let hs = v["holes"].as_array().unwrap();
    assert_eq!(hs[0]["tap"]["designation"], "M8X1.25-6H");
    assert_eq!(hs[2]["tap"]["designation"], "M12X1.75-LH-6H");
    assert_eq!(hs[2]["cycle"]["hand"], "left");
    assert_eq!(hs[2]["cycle"]["feed"].as_f64(), Some(1.75));
    assert_eq!(hs[2]["cycle"]["feed_word"], "Q239");
    // The M8 holes' drills are the pattern's, the M12 holes' the second cycle 200's.
    assert_eq!(hs[0]["drill"]["diameter"].as_f64(), Some(6.8));
    assert_eq!(hs[5]["drill"]["diameter"].as_f64(), Some(10.2));
    let depth = check_of(&hs[0], "depth");
    assert!(
        depth["note"].as_str().unwrap().contains("stock's bottom (Z-20, BLK FORM at line 2) at Z-22.9571"),
        "{depth}"
    );
    // The same file through `verify`: every thread it makes, one verdict.
    let o = run(&["verify", program.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    assert!(stdout(&o).contains("6 operations: 6 pass, 0 fail"), "{}", stdout(&o));
}

/// Issue 45 item 3: cycle 262 mills M20x1.5 inside (`nut.h`: Q335 = 20, Q239 = +1.5, Q201 =
/// −15, Q355 = 1, Q351 = +1 climb) as the TNC does, about the cycle's point, compensated by the
/// cutter's radius: a Ø14 cutter's centre runs at 10 − 7 = 3 mm, counter-clockwise and rising
/// (right hand, climb: `docs/dialects.md`), 15/1.5 = 10 turns from Z−15 to Z0; its tip reaches
/// D = 2·(3 + 7) = 20. The helix written by hand (`helix.h`: `CC`, `CP IPA+360 IZ+1.5 DR+`
/// repeated by `CALL LBL 1 REP 9`, ten turns at radius 3, uncompensated) makes the same thread.
#[test]
fn klartext_thread_milling_cycle_is_the_helix_by_hand() {
    let mut got = Vec::new();
    for name in ["nut", "helix"] {
        let program = data(&format!("klartext/{name}.h"));
        let (code, v) = run_json(&[
            "thread-mill",
            "--program",
            program.to_str().unwrap(),
            "--cutter-diameter",
            "14",
            "--thread",
            "M20x1.5-6H",
            "--json",
            "-",
        ]);
        assert_eq!(code, 1, "a sharp tip at D leaves D2 small: {v}");
        let hs = v["helices"].as_array().unwrap();
        let sweep: f64 = hs.iter().map(|h| h["sweep_deg"].as_f64().unwrap()).sum();
        assert!(hs.iter().all(|h| (h["radius"].as_f64().unwrap() - 3.0).abs() < 1e-9), "{name}: {v}");
        assert!((sweep - 3600.0).abs() < 1e-6, "{name}: {sweep}");
        assert!((hs[0]["z"][0].as_f64().unwrap() + 15.0).abs() < 1e-9, "{name}: {v}");
        assert!(hs[hs.len() - 1]["z"][1].as_f64().unwrap().abs() < 1e-9, "{name}: {v}");
        assert!((v["measured"]["major_diameter"].as_f64().unwrap() - 20.0).abs() < 1e-4, "{name}: {v}");
        assert!(
            check_of(&v, "lead")["ok"].as_bool().unwrap() && check_of(&v, "hand")["ok"].as_bool().unwrap()
        );
        got.push(v["measured"]["pitch_diameter"].as_f64().unwrap());
    }
    assert!((got[0] - got[1]).abs() < 1e-7, "{got:?}");
}

/// Cycle 262 up-cut (Q351 = −1) goes clockwise and falls; a left-hand pitch (Q239 = −1.5) climbs
/// counter-clockwise and falls: each is its hand's helix (the `hand` check), and a right-hand
/// designation fails the left-hand helix. Cycle 267 mills outside: its tip reaches the minor
/// diameter d3 = 20 − 2·0.61343·1.5 = 18.1597 (ISO 68-1's h3, the named default), the Ø14
/// cutter's centre 7 mm further out.
#[test]
fn klartext_thread_milling_directions_and_outside() {
    let base = std::fs::read_to_string(data("klartext/nut.h")).unwrap();
    let dir = tempdir("klartext-mill");
    let cases = [
        ("upcut", base.replace("Q351=+1", "Q351=-1"), "M20x1.5-6H", true, -1.0),
        ("left", base.replace("Q239=+1.5", "Q239=-1.5"), "M20x1.5-LH-6H", true, 1.0),
        ("left-as-right", base.replace("Q239=+1.5", "Q239=-1.5"), "M20x1.5-6H", false, 1.0),
    ];
    // `thread-mill --json` of `text` with a Ø14 cutter against `thread`.
    let mill14 = |name: &str, text: &str, thread: &str| {
        let p = dir.join(format!("{name}.h"));
        std::fs::write(&p, text).unwrap();
        let args =
            ["thread-mill", "--program", p.to_str().unwrap(), "--cutter-diameter", "14", "--thread", thread];
        run_json(&[&args[..], &["--json", "-"]].concat()).1
    };
    for (name, text, thread, hand_ok, sense) in cases {
        let v = mill14(name, &text, thread);
        assert_eq!(check_of(&v, "hand")["ok"].as_bool(), Some(hand_ok), "{name}: {v}");
        // Counter-clockwise (+) or clockwise (−) as the direction table says.
        assert_eq!(v["helices"][0]["sweep_deg"].as_f64().unwrap().signum(), sense, "{name}: {v}");
    }
    // 263 (with countersinking): its thread as 262's, one helix over Q201 (the countersink not
    // modelled, said).
    let v =
        mill14("countersink", &base.replace("262 THREAD MILLING", "263 THREAD MLLNG/CNTSNKG"), "M20x1.5-6H");
    assert!((v["measured"]["major_diameter"].as_f64().unwrap() - 20.0).abs() < 1e-4, "{v}");
    assert!((v["helices"][0]["sweep_deg"].as_f64().unwrap() - 3600.0).abs() < 1e-6, "{v}");
    assert!(
        v["notes"]
            .as_array()
            .unwrap()
            .iter()
            .any(|n| n.as_str().unwrap().contains("its countersinking is not modelled")),
        "{v}"
    );
    let v = mill14("outside", &base.replace("262 THREAD MILLING", "267 OUTSIDE THREAD MLLNG"), "M20x1.5-6g");
    let h = &v["helices"][0];
    assert!((h["radius"].as_f64().unwrap() - (10.0 - 0.613_434_5 * 1.5 + 7.0)).abs() < 1e-9, "{v}");
    assert!(
        (v["measured"]["minor_diameter"].as_f64().unwrap() - (20.0 - 2.0 * 0.613_434_5 * 1.5)).abs() < 1e-4,
        "{v}"
    );
}

/// Issue 45 item 2: Sinumerik hole patterns and frames (`sinumerik-holes.mpf`). `MCALL
/// CYCLE81`/`CYCLE84` then `HOLES2(50, 50, 20, 0, 0, 4)`: a circle of radius 20 about (50, 50),
/// INDA 0 dividing it in four from 0°: (70, 50), (50, 70), (30, 50), (50, 30). Then `TRANS X100
/// Y20` and `AROT RPL=90`, and `HOLES1(0, 0, 0, 10, 15, 3)`: a row along 0° from the frame's
/// origin, the first hole 10 from it and then every 15, at (10, 0), (25, 0), (40, 0) in the
/// frame; turned by 90° ((x, y) → (−y, x)) and shifted: (100, 30), (100, 45), (100, 60). Each tap
/// finds its drill at the same point (Ø6.8 by the comment) and passes.
#[test]
fn sinumerik_holes_under_frames() {
    let program = data("machining/sinumerik-holes.mpf");
    let (code, v) = run_json(&["tap", "--program", program.to_str().unwrap(), "--json", "-"]);
    assert_eq!(code, 0, "{v}");
    let want =
        [(70.0, 50.0), (50.0, 70.0), (30.0, 50.0), (50.0, 30.0), (100.0, 30.0), (100.0, 45.0), (100.0, 60.0)];
    let got = holes(&v);
    assert_eq!(got.len(), want.len(), "{got:?}");
    for (g, w) in got.iter().zip(want) {
        assert!((g.0.unwrap() - w.0).abs() < 1e-9 && (g.1.unwrap() - w.1).abs() < 1e-9, "{g:?} {w:?}");
        assert_eq!(g.2, Some(-15.0));
    }
    for h in v["holes"].as_array().unwrap() {
        assert_eq!(h["drill"]["diameter"].as_f64(), Some(6.8), "{h}");
        assert_eq!(h["pass"], true, "{h}");
    }
}

/// Issue 45 item 2: Sinumerik's mirrored frames (`sinumerik-mirror.mpf`), the drill and the tap
/// each called by MCALL at `X30 Y10` four times: as written, (30, 10); under `MIRROR X0`, X about
/// the frame's zero, (−30, 10); after `TRANS X100` (which clears the mirror) and `AMIRROR Y0`,
/// (30, −10) + (100, 0) = (130, −10); after `AROT RPL=90` in that frame, the point turned first
/// and mirrored after, (30, 10) → (−10, 30) → (−10, −30), + (100, 0) = (90, −30). Each tap finds
/// its drill there. A helix under MIRROR is refused (its hand turns over), as is a mirrored Z.
#[test]
fn sinumerik_mirrored_frames_place_the_holes() {
    let program = data("machining/sinumerik-mirror.mpf");
    let (code, v) = run_json(&["tap", "--program", program.to_str().unwrap(), "--json", "-"]);
    assert_eq!(code, 0, "{v}");
    let want = [(30.0, 10.0), (-30.0, 10.0), (130.0, -10.0), (90.0, -30.0)];
    let got = holes(&v);
    assert_eq!(got.len(), want.len(), "{got:?}");
    for (g, w) in got.iter().zip(want) {
        assert!((g.0.unwrap() - w.0).abs() < 1e-9 && (g.1.unwrap() - w.1).abs() < 1e-9, "{g:?} {w:?}");
    }
    assert_eq!(drill_lines(&v), [7, 9, 12, 14]);
    let dir = tempdir("sin-mirror");
    std::fs::write(
        dir.join("m.mpf"),
        "G17 G90 G94\nT1 D1 M6\nMIRROR X0\nG0 X7 Y0 Z5\nG3 X7 Y0 Z3.5 I-7 J0\nM30\n",
    )
    .unwrap();
    let o = run_in(
        &dir,
        &["thread-mill", "--program", "m.mpf", "--thread", "M20x1.5-6H", "--cutter-diameter", "6"],
    );
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        one_line_error(&o),
        "threadcheck: error: m.mpf:5:1: an arc under MIRROR (a mirrored frame, which reverses its direction and a thread's hand) is not read: write it without"
    );
    std::fs::write(dir.join("z.mpf"), "G17 G90 G94\nMIRROR Z0\nM30\n").unwrap();
    let o = run_in(&dir, &["tap", "--program", "z.mpf"]);
    assert_eq!(
        one_line_error(&o),
        "threadcheck: error: z.mpf:2:1: MIRROR Z is not modelled: a mirrored Z turns the thread's axis over"
    );
}

/// Issue 45 item 2: Fanuc polar coordinates and the mirror image (`fanuc-polar-mirror.nc`).
/// Under G16, X40 is the radius and Y30/Y150/Y270 the angles about the work zero: (40 cos 30°,
/// 40 sin 30°) = (34.641016, 20), (−34.641016, 20), (0, −40). `G51.1 X0` mirrors X25 Y−10 to
/// (−25, −10); after `G50.1` the same block is (25, −10). Each tap meets its drill at the same
/// point (the drill's line asserted), F750 = S600 × 1.25 under G94.
#[test]
fn fanuc_polar_coordinates_and_mirror_image() {
    let program = data("machining/fanuc-polar-mirror.nc");
    let (code, v) = run_json(&["tap", "--program", program.to_str().unwrap(), "--json", "-"]);
    assert_eq!(code, 0, "{v}");
    let r = 40.0 * 30f64.to_radians().cos();
    let want = [(r, 20.0, 8), (-r, 20.0, 9), (0.0, -40.0, 10), (-25.0, -10.0, 14), (25.0, -10.0, 16)];
    let hs = v["holes"].as_array().unwrap();
    assert_eq!(hs.len(), want.len(), "{v}");
    for (h, (x, y, drill_line)) in hs.iter().zip(want) {
        let c = &h["cycle"];
        assert!(
            (c["x"].as_f64().unwrap() - x).abs() < 1e-9 && (c["y"].as_f64().unwrap() - y).abs() < 1e-9,
            "{c}"
        );
        assert_eq!(h["drill"]["cycle"]["line"], drill_line, "{h}");
        assert_eq!(h["pass"], true, "{h}");
    }
    // A helix under the mirror would change hand: refused at its line.
    let dir = tempdir("mirror-helix");
    let p = dir.join("m.nc");
    std::fs::write(&p, "G17 G21 G90\nT12 M6\nS3000 M3\nG51.1 X0\nG0 X7 Y0 Z5\nG1 Z-15 F100\nG3 X7 Y0 Z-13.5 I-7 J0 F200\nM30\n").unwrap();
    let o = run(&[
        "thread-mill",
        "--program",
        p.to_str().unwrap(),
        "--cutter-diameter",
        "6",
        "--thread",
        "M20x1.5-6H",
    ]);
    assert!(one_line_error(&o).ends_with("m.nc:7:1: an arc under G51.1 (a mirror image, which reverses its direction and a thread's hand) is not read: write it without"), "{}", one_line_error(&o));
}

/// Issue 45 item 1: a mill-turn program (`fanuc-mill-turn.nc`, a Fanuc lathe with live tools):
/// G18 (line 3) and G17 (line 11) make it a mill-turn, each section read by its plane. The
/// turning section's G99 is feed per revolution and its G76 a threading cycle (last pass at
/// the X21.546 it writes); the milling section's G94 is feed per minute, G98 the return level
/// and X plain X: the taps at (20, 0) and (−20, 0) to Z−10 over the drills of lines 13 and 14,
/// F750 = S600 × 1.25 per minute. Given `--machine-type lathe`, line 11 contradicts it.
#[test]
fn a_mill_turn_program_is_read_section_by_section() {
    let program = data("machining/fanuc-mill-turn.nc");
    let p = program.to_str().unwrap();
    let (code, v) = run_json(&["verify", "--program", p, "--insert", "full", "--json", "-"]);
    assert_eq!(code, 1, "the full-profile insert leaves d2 37.7 µm over: {v}");
    assert_eq!(v["machine"]["machine_type"], "mill-turn", "{v}");
    let ops = v["operations"].as_array().unwrap();
    assert_eq!(ops.len(), 3, "{v}");
    assert_eq!(ops[0]["made"], "turned");
    let last = ops[0]["passes"].as_array().unwrap().last().unwrap().clone();
    assert!((last["x"].as_f64().unwrap() - 21.546).abs() < 1e-9, "{last}");
    for (op, (x, drill)) in ops[1..].iter().zip([(20.0, 13), (-20.0, 14)]) {
        assert_eq!(op["made"], "tapped");
        let c = &op["cycle"];
        assert_eq!(
            (c["x"].as_f64(), c["y"].as_f64(), c["bottom"].as_f64()),
            (Some(x), Some(0.0), Some(-10.0)),
            "{c}"
        );
        assert_eq!(c["feed_per_rev"], false, "{c}");
        assert_eq!(op["drill"]["cycle"]["line"], drill, "{op}");
        assert_eq!(op["pass"], true, "{op}");
    }
    // Given as a lathe, it is read as one with a note naming the G17 (it was refused there).
    let o = run(&["verify", "--program", p, "--insert", "full", "--machine-type", "lathe"]);
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(
        out.contains("read as a lathe, as --machine-type says, though line 11 writes G17, the milling plane"),
        "{out}"
    );
}

/// Issue 45 item 4: face tapping with a live tool on a Fanuc lathe (`fanuc-live-tool.nc`):
/// `G83`/`G84 X40 C0 … ` then `C90`: each hole placed by X (a diameter: radius 20) and the
/// spindle's angle C, (20 cos C, 20 sin C) on the face: (20, 0) and (0, 20), each tap over the
/// drill at the same angle; the tap's F1.25 is per revolution (G99, the lathe's). Side tapping
/// (G88, along X) makes a radial hole placed by Z and C.
#[test]
fn live_tool_face_tapping_on_a_lathe() {
    let program = data("machining/fanuc-live-tool.nc");
    let (code, v) = run_json(&["tap", "--program", program.to_str().unwrap(), "--json", "-"]);
    assert_eq!(code, 0, "{v}");
    let hs = v["holes"].as_array().unwrap();
    let want = [(20.0, 0.0, 6), (0.0, 20.0, 7)];
    assert_eq!(hs.len(), 2, "{v}");
    for (h, (x, y, drill)) in hs.iter().zip(want) {
        let c = &h["cycle"];
        assert_eq!((c["x"].as_f64(), c["y"].as_f64()), (Some(x), Some(y)), "{c}");
        assert_eq!(c["feed_per_rev"], true, "{c}");
        assert_eq!(h["drill"]["cycle"]["line"], drill, "{h}");
    }
    let dir = tempdir("g88");
    std::fs::write(
        dir.join("side.nc"),
        "G18 G21 G99\nG97 S800 M3\nG0 X60 Z-10 C0\nG88 Z-10 X20 C0 R55 F1.25\nG80\nM30\n",
    )
    .unwrap();
    // G88 taps from the side (it was refused): a radial hole at Z−10 C0, no drill before it.
    let o = run_in(&dir, &["tap", "--program", "side.nc", "--tap", "M8x1.25-6H"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stdout(&o).contains("== G88 at line 4 (Z-10 C0, radial), tap M8x1.25-6H"), "{}", stdout(&o));
}

/// Issue 46 (its mixed example, now one file): a mill-turn program (`fanuc-mixed.nc`) turns
/// M24x2 in G18 (the last pass at the X21.546 it writes), drills and taps four M8 holes in G17 at
/// (30, 0), (−30, 0), (0, 30), (0, −30) (each tap over its drill, F750 = S600 × 1.25 per minute)
/// and thread-mills M20x1.5 at the centre with T4, a Ø6 cutter (the tool table's): ten G3 turns
/// of radius 7 rising 1.5 each, so its tip reaches D = 2·(7 + 3) = 20. One `verify`, six
/// operations, each checked by its process.
#[test]
fn a_mixed_mill_turn_program_is_verified_whole() {
    let (p, t) = (data("machining/fanuc-mixed.nc"), data("machining/fanuc-mixed.toml"));
    let (code, v) = run_json(&[
        "verify",
        "--program",
        p.to_str().unwrap(),
        "--tools",
        t.to_str().unwrap(),
        "--insert",
        "full",
        "--json",
        "-",
    ]);
    assert_eq!(code, 1, "{v}");
    assert_eq!(v["machine"]["machine_type"], "mill-turn");
    let ops = v["operations"].as_array().unwrap();
    let made: Vec<&str> = ops.iter().map(|o| o["made"].as_str().unwrap()).collect();
    assert_eq!(made, ["turned", "tapped", "tapped", "tapped", "tapped", "milled"]);
    let last = ops[0]["passes"].as_array().unwrap().last().unwrap().clone();
    assert!((last["x"].as_f64().unwrap() - 21.546).abs() < 1e-9, "{last}");
    for (op, (x, y)) in ops[1..5].iter().zip([(30.0, 0.0), (-30.0, 0.0), (0.0, 30.0), (0.0, -30.0)]) {
        assert_eq!((op["cycle"]["x"].as_f64(), op["cycle"]["y"].as_f64()), (Some(x), Some(y)), "{op}");
        assert_eq!(op["drill"]["diameter"].as_f64(), Some(6.8));
        assert_eq!(op["pass"], true, "{op}");
    }
    let milled = &ops[5];
    assert_eq!(milled["designation"], "M20X1.5-6H");
    assert!((milled["measured"]["major_diameter"].as_f64().unwrap() - 20.0).abs() < 1e-4, "{milled}");
    assert!(check_of(milled, "lead")["ok"].as_bool().unwrap());
}

/// `tap --json -` on program `text` written as `name` in a fresh folder, with the tool table
/// `tools` beside it.
fn tap_text(name: &str, text: &str, tools: &str) -> (i32, serde_json::Value, String) {
    tap_text_with(name, text, tools, &[])
}

/// [`tap_text`] with more arguments (`--dialect haas`, `--tap …`).
fn tap_text_with(name: &str, text: &str, tools: &str, extra: &[&str]) -> (i32, serde_json::Value, String) {
    let dir = tempdir("mc-text");
    std::fs::write(dir.join(name), text).unwrap();
    std::fs::write(dir.join("tools.toml"), tools).unwrap();
    let mut args = vec!["tap", "--program", name, "--tools", "tools.toml", "--json", "-"];
    args.extend_from_slice(extra);
    let o = run_in(&dir, &args);
    let code = o.status.code().unwrap();
    let v = if code < 2 { serde_json::from_slice(&o.stdout).unwrap() } else { serde_json::Value::Null };
    (code, v, stderr(&o))
}

/// The drilled holes' (x, y, R, bottom).
fn drilled(v: &serde_json::Value) -> Vec<[f64; 4]> {
    v["drilled"]
        .as_array()
        .unwrap()
        .iter()
        .map(|h| ["x", "y", "r_level", "bottom"].map(|k| h[k].as_f64().unwrap()))
        .collect()
}

/// Issue 62: a row of five holes by L5 (LinuxCNC) and K5 (Fanuc) in G91, then tapped. From Z10,
/// `G91 G99 G81 X12 R-8 Z-15 L5`: R = 10 − 8 = 2, bottom = 2 − 15 = −13 (R from the initial level,
/// Z from R), holes at X 12, 24, 36, 48, 60 (Y0); the tool ends at R (G99), X60. The tapping
/// row `G90 G98 G84 X12 Y0 R2 Z-11 F500` at S400 (500 = 400 × 1.25) and `X24`: the tap's
/// feed is M8x1.25's lead, its drill the hole beneath it.
#[test]
fn a_g91_row_of_holes_repeats_by_l_and_by_k() {
    let tools = "[tools]\n1 = \"drill:6.8\"\n2 = \"tap:M8x1.25-6H\"\n";
    for (name, repeat, dialect_words) in [
        ("row.ngc", "L5", "G17 G21 G90 G94\nT1 M6\nS1200 M3\n"),
        ("row.nc", "K5", "G17 G21 G90 G94\nT1 M6\nS1200 M3\n"),
    ] {
        let program = format!(
            "{dialect_words}G0 X0 Y0 Z10\nG91 G99 G81 X12 R-8 Z-15 {repeat} F100\nG80\nG90 G0 Z10\nT2 M6\nS400 M3\nG98 G84 X12 Y0 R2 Z-11 F500\nX24\nG80\nM5\nM30\n"
        );
        let (code, v, err) = tap_text(name, &program, tools);
        assert_eq!(code, 0, "{name}: {err}");
        let want: Vec<[f64; 4]> = (1..=5).map(|i| [12.0 * f64::from(i), 0.0, 2.0, -13.0]).collect();
        assert_eq!(drilled(&v), want, "{name}");
        let taps = holes(&v);
        assert_eq!(
            taps.iter().map(|h| (h.0, h.2)).collect::<Vec<_>>(),
            [(Some(12.0), Some(-11.0)), (Some(24.0), Some(-11.0))]
        );
        assert_eq!(v["pass"], true, "{name}");
    }
}

/// Issue 62: LinuxCNC's G73 drills (it was read as a lathe cycle), its G84 taps (it was passed
/// over: "no tapping cycle"), and a block that writes only Y under the cycle keeps the X it
/// left (it was a hole with no X): `G98 G73 X5 Y5 R2 Z-12 Q3` then `Y15` drill (5, 5) and (5, 15).
/// LinuxCNC refuses G84 with the spindle counter-clockwise, at the cycle's line.
#[test]
fn linuxcnc_g73_drills_and_g84_taps_where_the_tool_stands() {
    let tools = "[tools]\n1 = \"drill:6.8\"\n2 = \"tap:M8x1.25-6H\"\n";
    let program = "G17 G21 G90 G94\nT1 M6\nS1200 M3\nG0 X0 Y0 Z10\nG98 G73 X5 Y5 R2 Z-12 Q3 F100\nY15\nG80\nT2 M6\nS400 M3\nG98 G84 X5 Y5 R2 Z-10 F500\nY15\nG80\nM2\n";
    let (code, v, err) = tap_text("p.ngc", program, tools);
    assert_eq!(code, 0, "{err}");
    assert_eq!(drilled(&v), [[5.0, 5.0, 2.0, -12.0], [5.0, 15.0, 2.0, -12.0]]);
    assert_eq!(
        holes(&v).iter().map(|h| (h.0, h.1)).collect::<Vec<_>>(),
        [(Some(5.0), Some(5.0)), (Some(5.0), Some(15.0))]
    );
    let ccw = program.replace("S400 M3", "S400 M4");
    let (code, _, err) = tap_text("p.ngc", &ccw, tools);
    assert_eq!(code, 2);
    assert!(
        err.contains("p.ngc:10:5: G84 with the spindle turning counter-clockwise: LinuxCNC refuses it"),
        "{err}"
    );
}

/// Issue 62: a LinuxCNC rigid-tap test that writes no G17 and no tool length offset, in inch:
/// its Y moves show a machining centre (a lathe has no Y axis), so X3 is 76.2 mm, not a
/// diameter (it was read as a lathe, every X doubled). A program that sets no units says mm
/// was assumed.
#[test]
fn a_y_move_shows_a_machining_centre_and_missing_units_are_said() {
    let program =
        "G20 G90\nM3 S300\nG0 X0 Y1 Z0.1\nG33.1 Z-0.5 K0.05\nG0 X3 Y1 Z0.1\nG33.1 Z-0.5 K0.05\nM5\nM2\n";
    let tap = ["--tap", "1/4-20 UNC-2B"];
    let (code, v, err) = tap_text_with("rt.ngc", program, "[tools]\n", &tap);
    assert!(code < 2, "{err}");
    let xs: Vec<f64> = holes(&v).iter().map(|h| h.0.unwrap()).collect();
    assert!(xs.len() == 2 && xs[0].abs() < 1e-9 && (xs[1] - 76.2).abs() < 1e-9, "{xs:?}");
    assert_eq!(v["machine"]["machine_type"], "mill");
    assert!(
        v["machine"]["reason"].as_str().unwrap().contains("line 3 writes Y1, a Y move"),
        "{}",
        v["machine"]
    );
    let no_units = program.replace("G20 G90", "G90");
    let (code, v, err) = tap_text_with("rt.ngc", &no_units, "[tools]\n", &tap);
    assert!(code < 2, "{err}");
    let notes = v["notes"].to_string();
    assert!(notes.contains("the program sets no units (G20/G21) before it threads: read in mm"), "{notes}");
}

/// Issue 62: a Haas program whose taps lie in an M97 local subprogram, read in the default
/// dialect (Fanuc, which does not run M97): the refusal is at the M97 and names the Haas
/// dialect; read as Haas its two holes are tapped (F25 in/min at S500 = 0.05 in = 1/4-20's lead).
#[test]
fn a_haas_m97_read_as_fanuc_names_the_haas_dialect() {
    let program = "%\nO01234 (TAPS IN A LOCAL SUBPROGRAM)\nG17 G20 G90 G40 G80\nT3 M06\nG54 G00 X0 Y0 S500 M03\nG43 H03 Z1.\nM97 P1000\nG80 G00 Z1.\nM30\nN1000 G98 G84 X1. Y1. Z-0.5 R0.1 F25.\nX2.\nM99\n%\n";
    let dir = tempdir("mc-m97");
    std::fs::write(dir.join("h.nc"), program).unwrap();
    let o = run_in(&dir, &["tap", "--program", "h.nc", "--tap", "1/4-20 UNC-2B"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        one_line_error(&o),
        "threadcheck: error: h.nc:7:1: no tapping cycle in the program (looked for G84 and G74 in the fanuc dialect); M97 read past: Haas's call of a local subprogram (M97 P…, an N label in the same program), which the fanuc dialect does not run: a Haas program is read with --dialect haas"
    );
    let o = run_in(
        &dir,
        &["tap", "--program", "h.nc", "--tap", "1/4-20 UNC-2B", "--dialect", "haas", "--json", "-"],
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(
        holes(&v).iter().map(|h| (h.0, h.1)).collect::<Vec<_>>(),
        [(Some(25.4), Some(25.4)), (Some(50.8), Some(25.4))]
    );
}

/// Issue 62: Klartext as a CAM post writes it (`tests/data/klartext/cam-post.h`, written here):
/// a tool list in `;` comments, `FUNCTION`, `CYCL DEF 32`, `L M140 MB MAX`, rotary axes at 0,
/// `Q206=FAUTO`, PATTERN DEF, M92. The drill T7 and the tap T9 are the list's (Ø6.8; a right-hand
/// tap of Ø8 at Q239 1.25: M8x1.25-6H, its D1 6.647–6.912 holds 6.8), three holes each at (10,
/// 10), (30, 10), (30, 25), tapped to Z-14 over drills to Z-16. With B tilted the tap's axis is
/// not Z: refused at the cycle call; a pitch of 1.27 fits no M8 (1.25, 1, 0.75): refused naming
/// both.
#[test]
fn klartext_as_a_cam_post_writes_it_reaches_a_verdict() {
    let program = std::fs::read_to_string(data("klartext/cam-post.h")).unwrap();
    let (code, v, err) = tap_text("cam-post.h", &program, "[tools]\n");
    assert_eq!(code, 0, "{err}");
    let places: Vec<(f64, f64, f64)> =
        holes(&v).iter().map(|h| (h.0.unwrap(), h.1.unwrap(), h.2.unwrap())).collect();
    assert_eq!(places, [(10.0, 10.0, -14.0), (30.0, 10.0, -14.0), (30.0, 25.0, -14.0)]);
    for h in v["holes"].as_array().unwrap() {
        assert_eq!(h["tap"]["designation"], "M8x1.25-6H");
        assert_eq!(h["drill"]["diameter"].as_f64(), Some(6.8));
    }
    let tilted = program.replace("23 L Z+15 R0 FMAX", "23 L B+90 R0 FMAX");
    let (code, _, err) = tap_text("cam-post.h", &tilted, "[tools]\n");
    assert_eq!(code, 2);
    assert!(
        err.contains("cam-post.h:42:4: cycle 207 with the rotary axis B at 90°: the hole's axis is tilted"),
        "{err}"
    );
    // The tap called by name (Fusion 360's `TOOL CALL "name"`): the name says its size.
    let named = program.replace("TOOL CALL 9 Z S500", "TOOL CALL \"TAP M8X1.25\" Z S500");
    let (code, v, err) = tap_text("cam-post.h", &named, "[tools]\n");
    assert_eq!(code, 0, "{err}");
    let first = &v["holes"][0]["tap"];
    assert_eq!(
        (first["designation"].as_str(), first["designation_from"].as_str()),
        (Some("M8X1.25-6H"), Some("comment"))
    );
    let wrong = program.replace("Q239=+1.25", "Q239=+1.27");
    let (code, _, err) = tap_text("cam-post.h", &wrong, "[tools]\n");
    assert_eq!(code, 2);
    assert!(
        err.contains("T9 is a tap of Ø8 in the program's tool list at line 4, and the cycle's lead 1.27 mm fits no standard thread of that diameter (M8 has 1.25, 1, 0.75)"),
        "{err}"
    );
}

/// Issue 62: a Mastercam-style Haas program, written here: its tool list names the drill
/// `( T4 | NO. 29 DRILL | H4 )` (#29 = 0.1360 in = 3.4544 mm) and the tap `( T5 | NO. 8-32 TAPRH | H5 )`;
/// both cycles stand in an M97 subprogram called at two positions. #8-32 UNC-2B's D1 limits are
/// 0.1300–0.1450 in (ASME B1.1), so the #29 drill passes; F = S × 1/32 in = 600/32 = 18.75 in/min.
#[test]
fn a_mastercam_tool_list_names_the_tap_and_the_drill() {
    let program = "%\nO1001 (TOOL LIST WRITTEN HERE)\n( T4 | NO. 29 DRILL | H4 )\n( T5 | NO. 8-32 TAPRH | H5 )\nG20 G17 G40 G80 G90 G94\nT4 M06\nG00 G54 X0. Y0. S2500 M03\nG43 H4 Z1.\nG98 G81 Z-.5 R.1 F10. L0\nM97 P100\nG80\nT5 M06\nG00 G54 X0. Y0. S600 M03\nG43 H5 Z1.\nG98 G84 Z-.4 R.1 F18.75 L0\nM97 P100\nG80\nM30\nN100 X1. Y1.\nX2. Y1.\nM99\n%\n";
    let (code, v, err) = tap_text_with("m.nc", program, "[tools]\n", &["--dialect", "haas"]);
    assert_eq!(code, 0, "{err}");
    let hs = v["holes"].as_array().unwrap();
    assert_eq!(hs.len(), 2);
    for h in hs {
        assert_eq!(h["tap"]["designation"], "#8-32 UNC-2B");
        assert!((h["drill"]["diameter"].as_f64().unwrap() - 3.4544).abs() < 1e-9, "{}", h["drill"]);
        assert_eq!(h["pass"], true);
    }
}

/// Issue 62: tool lists in SolidCAM's and hyperMILL's header forms (written here; the forms
/// differ by post, these are threadcheck's default reading): `(TOOL 3 - TAP M8X1.25 - DIA 8.)`,
/// `(TOOL NUMBER: 4  DRILL D6.8)`, far above the cycles that use them. ISO 965-1 gives M8x1.25-6H
/// D1 6.647–6.912 mm, so the Ø6.8 drill passes; F = S × lead = 400 × 1.25 = 500 mm/min. A Klartext
/// tap called by its German name (`TOOL CALL "GEWINDEBOHRER M8"`) is M8 coarse, 1.25 mm (ISO 261).
#[test]
fn solidcam_and_hypermill_tool_lists_name_the_tap_and_the_drill() {
    let program = "%\nO5001\n(TOOL LIST)\n(TOOL 3 - TAP M8X1.25 - DIA 8.)\n(TOOL NUMBER: 4  DRILL D6.8)\n(TOOL 5 - END MILL D10)\nG21 G17 G90 G40 G80\nT4 M6\nG54 G0 X10. Y10. S1200 M3\nG43 H4 Z10.\nG98 G83 Z-20. R3. Q3. F120.\nG80\nT5 M6\nG0 X0 Y0 S3000 M3\nG43 H5 Z10.\nG1 Z-1. F300.\nG0 Z50.\nT3 M6\nG0 X10. Y10. S400 M3\nG43 H3 Z10.\nM29 S400\nG98 G84 Z-15. R3. F500.\nG80\nM30\n%\n";
    let (code, v, err) = tap_text("solidcam.nc", program, "[tools]\n");
    assert_eq!(code, 0, "{err}");
    let h = &v["holes"][0];
    assert_eq!(h["tap"]["designation"], "M8X1.25-6H");
    assert_eq!(h["drill"]["diameter"].as_f64(), Some(6.8));
    assert_eq!(h["pass"], true);
    // The cycle's pitch 1.0 against a list that says M8X1.25: the feed fails by name.
    let (code, v, _) = tap_text("solidcam.nc", &program.replace("F500.", "F400."), "[tools]\n");
    assert_eq!((code, &v["holes"][0]["pass"]), (1, &serde_json::Value::Bool(false)));
    let klartext = "0 BEGIN PGM 1 MM\n1 BLK FORM 0.1 Z X-50 Y-50 Z-20\n2 BLK FORM 0.2 X+50 Y+50 Z+0\n3 TOOL CALL \"GEWINDEBOHRER M8\" Z S400\n4 L Z+100 R0 FMAX M91\n5 L X+10 Y+10 R0 FMAX M3\n6 CYCL DEF 207 RIGID TAPPING ~\n  Q200=2 ;SET-UP CLEARANCE ~\n  Q201=-15 ;DEPTH ~\n  Q239=+1.25 ;THREAD PITCH ~\n  Q203=+0 ;SURFACE COORDINATE ~\n  Q204=50 ;2ND SET-UP CLEARANCE\n7 L Z+50 R0 FMAX\n8 CYCL CALL\n9 L M140 MB MAX\n10 M30\n11 END PGM 1 MM\n";
    let (code, v, err) = tap_text("named.h", klartext, "[tools]\n");
    assert_eq!(code, 0, "{err}");
    assert_eq!(v["holes"][0]["tap"]["designation"], "M8-6H");
}

/// Issue 62: Haas's own codes read under the default dialect are its evidence, named at their
/// place with the choice that reads them: G187 (smoothness; no move) and M97 (a local
/// subprogram, which Fanuc does not run).
#[test]
fn haas_codes_under_the_default_dialect_name_the_haas_choice() {
    let program = "%\nO1000\nG20 G17 G90\nT1 M6 (TAP 1/4-20)\nG187 P1 E0.001\nG0 G54 X1. Y1. S500 M3\nG43 H1 Z1.\nG98 G84 Z-.5 R.1 F25.\nG80\nM30\n%\n";
    let (code, v, err) = tap_text("g187.nc", program, "[tools]\n");
    assert_eq!(code, 0, "{err}");
    assert!(v["notes"].to_string().contains("g187.nc:5:1: G187 read past: Haas's smoothness and corner accuracy setting, which the fanuc dialect does not have (no move here): a Haas program is read with --dialect haas"), "{}", v["notes"]);
    let m97 = program
        .replace("G98 G84 Z-.5 R.1 F25.\n", "M97 P100\n")
        .replace("M30\n", "M30\nN100 G98 G84 Z-.5 R.1 F25.\nM99\n");
    let (code, _, err) = tap_text("m97.nc", &m97, "[tools]\n");
    assert_eq!(code, 2);
    assert!(
        err.contains("M97 read past: Haas's call of a local subprogram") && err.contains("--dialect haas"),
        "{err}"
    );
}

/// Issue 62: a Fanuc-family machining centre drills along the plane's normal, Y in G18: the
/// cycle is refused at its place, not read as a hole along Z at (X10, Y-10).
#[test]
fn a_canned_cycle_in_g18_on_a_machining_centre_is_refused_at_its_place() {
    let program = "G21 G90 G18\nT1 M6\nG43 H1 Z10\nS500 M3\nG0 X10 Y10\nG98 G84 Y-10 R3 F625\nG80\nM30\n";
    let (code, _, err) =
        tap_text_with("g18.nc", program, "[tools]\n1 = \"tap:M8x1.25-6H\"\n", &["--machine-type", "mill"]);
    assert_eq!(code, 2);
    assert!(err.contains("g18.nc:6:5: G84: a canned cycle in the plane G18, which drills along Y"), "{err}");
}

/// Issue 62: LinuxCNC's `G10 L2 P1 X100 Y50 R90` turns G54's XY plane 90° about its origin
/// (100, 50): the hole written at X10 Y0 stands at (100 − 0, 50 + 10) = (100, 60), and the
/// G91 row `X5 L2` after it runs along the turned X: (100, 65), (100, 70). (Rotation was noted as
/// not modelled and the unrotated (110, 50) reported.)
#[test]
fn a_rotated_linuxcnc_work_offset_turns_the_holes() {
    let program = "G17 G21 G90 G94\nT1 M6\nS1200 M3\nG10 L2 P1 X100 Y50 Z0 R90\nG54\nG0 X0 Y0 Z10\nG99 G81 X10 Y0 R2 Z-5 F100\nG91 X5 L2\nG90 G80\nM2\n";
    let p = threadcheck::read_program_with(
        program,
        "rot.ngc",
        threadcheck::Dialect::LinuxCnc,
        threadcheck::ReadOptions { allow_no_threading: true, ..Default::default() },
    )
    .unwrap();
    let xy: Vec<(f64, f64)> = p.holes.iter().map(|h| (h.x.unwrap(), h.y.unwrap())).collect();
    let want = [(100.0, 60.0), (100.0, 65.0), (100.0, 70.0)];
    assert_eq!(xy.len(), 3);
    for (a, b) in xy.iter().zip(want) {
        assert!((a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9, "{xy:?}");
    }
}
