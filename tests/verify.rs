//! Issue 5: `threadcheck verify` end to end, from the command line.

use crate::*;

const M10_D3: &str = "8.160"; // d3 = d − 1.226869·P for M10x1.5 (ISO 68-1 / DIN 13)

fn json_of(args: &[&str]) -> (i32, serde_json::Value) {
    let mut a = args.to_vec();
    a.extend(["--json", "-"]);
    let o = run(&a);
    let code = o.status.code().unwrap();
    assert!(code == 0 || code == 1, "{}", stderr(&o));
    (code, serde_json::from_slice(&o.stdout).unwrap())
}

fn check<'a>(v: &'a serde_json::Value, feature: &str) -> &'a serde_json::Value {
    v["checks"].as_array().unwrap().iter().find(|c| c["feature"] == feature).unwrap()
}

/// Full profile, final X solved for mid-tolerance d2 (8.928 = (8.994 + 8.862)/2, ISO 965-2):
/// every check passes, exit 0.
#[test]
fn full_profile_m10_mid_tolerance_passes() {
    let (code, v) = json_of(&["verify", "--thread", "M10x1.5-6g", "--insert", "full"]);
    assert_eq!(code, 0, "{v:#}");
    assert_eq!(v["verdict"], "pass");
    let d2 = v["measured"]["pitch_diameter"].as_f64().unwrap();
    assert!((d2 - 8.928).abs() < 1e-4, "{d2}");
    // At X = d3 = 8.159696 the full-profile insert gives basic d2 = 9.025721; X and d2 move one
    // for one, so d2 = 8.928 needs X = 8.159696 − (9.025721 − 8.928) = 8.061975.
    let x = v["plan"]["final_x"].as_f64().unwrap();
    assert!((x - 8.061975).abs() < 1e-6, "{x}");
}

/// The same plan ending at X = d3: d2 = basic 9.026, 32 µm over d2 max = 8.994 (es(g) = −32 µm
/// at P 1.5, ISO 965-1 Table 1). Exit 1, and the report suggests the X that fixes it.
#[test]
fn full_profile_m10_at_d3_is_32_um_over() {
    let (code, v) = json_of(&["verify", "--thread", "M10x1.5-6g", "--insert", "full", "--final-x", M10_D3]);
    assert_eq!(code, 1);
    assert_eq!(v["verdict"], "fail");
    let c = check(&v, "pitch_diameter");
    assert_eq!(c["ok"], false);
    let dev = c["deviation_um"].as_f64().unwrap();
    // 9.02572 + 0.0003 (X 8.160 vs 8.1597) − 8.994 = 32.0 µm.
    assert!((dev - 32.0).abs() < 0.5, "{dev}");
    let x = v["suggested_final_x"].as_f64().unwrap();
    assert!((x - 8.061975).abs() < 1e-6, "{x}");
}

/// A partial insert (r 0.04) cut to the full-profile depth X = d3: its tip lies 7H/8 − r − h3 =
/// 0.1766 mm higher than the depth that gives basic d2, so d2 = 9.026 + 0.353 = 9.379, 385 µm
/// over 8.994.
#[test]
fn partial_insert_at_full_profile_depth_is_far_over() {
    let (code, v) =
        json_of(&["verify", "--thread", "M10x1.5-6g", "--insert", "partial", "--final-x", M10_D3]);
    assert_eq!(code, 1);
    let dev = check(&v, "pitch_diameter")["deviation_um"].as_f64().unwrap();
    assert!(dev > 300.0, "{dev}");
    let want = (0.875 * 1.299038 - 0.04 - 0.613435 * 1.5) * 2.0 * 1000.0 + 32.0;
    assert!((dev - want).abs() < 1.0, "{dev} vs {want}");
}

/// Partial insert at mid-tolerance d2: the 0.04 mm root radius is below R min = 0.125·P and the
/// root below d3 min, both form checks; `--gauge-only` leaves them out and the thread passes.
#[test]
fn gauge_only_turns_a_partial_thread_from_fail_to_pass() {
    let (code, v) = json_of(&["verify", "--thread", "M10x1.5-6g", "--insert", "partial"]);
    assert_eq!(code, 1);
    assert_eq!(check(&v, "root_radius")["ok"], false);
    assert_eq!(check(&v, "root_radius")["kind"], "form");
    let (code, v) = json_of(&["verify", "--thread", "M10x1.5-6g", "--insert", "partial", "--gauge-only"]);
    assert_eq!(code, 0);
    assert_eq!(v["verdict"], "pass");
    assert_eq!(check(&v, "root_radius")["ok"], false, "still reported");
}

/// The JSON report carries every key of the CLI contract (shared/spec/cli.md).
#[test]
fn verify_json_has_the_contract_keys() {
    let (_, v) = json_of(&["verify", "--thread", "M10x1.5-6g"]);
    for k in ["designation", "form", "kind", "nominal_diameter", "pitch", "lead", "starts", "hand", "class"] {
        assert!(v["thread"].get(k).is_some(), "thread.{k}");
    }
    for k in ["kind", "angle", "tip_radius"] {
        assert!(v["insert"].get(k).is_some(), "insert.{k}");
    }
    let p = &v["passes"][0];
    for k in ["index", "x", "z", "depth", "chip_area"] {
        assert!(p.get(k).is_some(), "passes[].{k}");
    }
    for k in ["leading", "trailing", "tip"] {
        assert!(p["engaged_edge"].get(k).is_some(), "engaged_edge.{k}");
    }
    for k in
        ["major_diameter", "pitch_diameter", "minor_diameter", "root_radius", "flank_angles", "thread_depth"]
    {
        assert!(v["measured"].get(k).is_some(), "measured.{k}");
    }
    let features =
        ["major_diameter", "pitch_diameter", "minor_diameter", "root_radius", "flank_angle", "max_material"];
    for f in features {
        let c = check(&v, f);
        for k in ["feature", "kind", "value", "min", "max", "ok", "deviation_um"] {
            assert!(c.get(k).is_some(), "checks[{f}].{k}");
        }
        let kind =
            if ["major_diameter", "pitch_diameter", "max_material"].contains(&f) { "size" } else { "form" };
        assert_eq!(c["kind"], kind, "{f}");
    }
    assert!(v["verdict"] == "pass" || v["verdict"] == "fail");
    assert_eq!(v["thread"]["kind"], "external");
    assert_eq!(v["insert"]["kind"], "partial");
}

/// The SVG has each layer as a named group, and text from user input is escaped.
#[test]
fn svg_has_named_layers_and_escapes_text() {
    let dir = tempdir("svg");
    let ins = dir.join("ins.toml");
    std::fs::write(
        &ins,
        "name = \"<script>alert(1)</script> & co\"\nangle = 60\ntip_radius = 0.05\nheight = 3\n",
    )
    .unwrap();
    let svg = dir.join("out.svg");
    let o = run_in(&dir, &["verify", "--thread", "M10x1.5-6g", "--insert", "ins.toml", "--svg", "out.svg"]);
    assert!(o.status.code() == Some(0) || o.status.code() == Some(1), "{}", stderr(&o));
    let text = std::fs::read_to_string(&svg).unwrap();
    for id in ["title", "legend", "chip-chart", "tooth", "window", "full-length"] {
        assert!(text.contains(&format!("id=\"{id}\"")), "group {id}");
    }
    for layer in ["blank", "tolerance-zone", "basic-profile", "passes", "as-cut", "dimensions"] {
        assert!(text.contains(&format!("id=\"tooth-{layer}\"")), "layer {layer}");
    }
    assert!(!text.contains("<script>"));
    assert!(text.contains("&lt;script&gt;"));
    // Well-formed enough to start like an SVG document.
    assert!(text.trim_start().starts_with("<svg"));
}

/// An error mid-run (here: an impossible final X) leaves an existing output file untouched.
#[test]
fn an_error_leaves_existing_outputs_untouched() {
    let dir = tempdir("keep");
    std::fs::write(dir.join("r.json"), "old").unwrap();
    std::fs::write(dir.join("r.svg"), "old").unwrap();
    let o = run_in(
        &dir,
        &["verify", "--thread", "M10x1.5-6g", "--final-x", "12.0", "--json", "r.json", "--svg", "r.svg"],
    );
    one_line_error(&o);
    assert_eq!(std::fs::read_to_string(dir.join("r.json")).unwrap(), "old");
    assert_eq!(std::fs::read_to_string(dir.join("r.svg")).unwrap(), "old");
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 2, "no temporary left behind");
}

/// Internal threads: a partial insert at mid-tolerance D2 of 6H passes the size checks.
#[test]
fn internal_thread_verifies() {
    let (code, v) = json_of(&["verify", "--thread", "M10x1.5-6H", "--gauge-only"]);
    assert_eq!(v["thread"]["kind"], "internal");
    assert_eq!(code, 0, "{v:#}");
    let d2 = v["measured"]["pitch_diameter"].as_f64().unwrap();
    assert!((d2 - (9.026 + 9.206) / 2.0).abs() < 1e-4);
}

#[test]
fn verify_errors_are_one_line() {
    for (args, part) in [
        (vec!["verify", "--thread", "M10x1.5"], "names no external class"),
        (vec!["verify", "--thread", "M10x1.5-6g", "--insert", "partial:0.5"], "tip radius"),
        (vec!["verify", "--thread", "M10x1.5-6g", "--final-x", "NaN"], "--final-x"),
        (vec!["verify", "--thread", "M10x1.5-6g", "--passes", "1000000000"], "passes"),
        (vec!["verify", "--thread", "M10x1.5-6g", "--infeed", "sideways"], "--infeed"),
        (vec!["verify", "--thread", "M10x1.5-6g", "--insert", "no-such.toml"], "no-such.toml"),
    ] {
        let line = one_line_error(&run(&args));
        assert!(line.contains(part), "{args:?}: {line}");
    }
}

/// A Fanuc G76 with the full-profile depth (X = d3 = 8.160, P = 0.6134·P = 920 µm) cut with a
/// partial insert: the V stops 7H/8 − r − h3 = 0.1766 mm short of the depth that gives basic d2,
/// so d2 ≈ 9.026 + 0.353 = 9.379, over its maximum 8.994 by about 385 µm.
#[test]
fn partial_insert_with_a_full_profile_g76_program() {
    let prog = data("programs/fanuc-m10-full-depth-g76.nc");
    let (code, v) = json_of(&[
        "verify",
        "--thread",
        "M10x1.5-6g",
        "--insert",
        "partial",
        "--program",
        prog.to_str().unwrap(),
        "--dialect",
        "fanuc",
    ]);
    assert_eq!(code, 1);
    // A program's report holds one full report per threading operation.
    assert_eq!(v["operations"].as_array().unwrap().len(), 1);
    let v = &v["operations"][0];
    assert_eq!(v["operation"]["cycle"], "G76");
    let c = check(v, "pitch_diameter");
    let dev = c["deviation_um"].as_f64().unwrap();
    assert!(dev > 300.0, "{dev}");
    assert!((dev - 385.2).abs() < 1.5, "{dev}");
    // Every pass points back to the G76 line of the program.
    assert!(v["passes"].as_array().unwrap().iter().all(|p| p["source_line"] == 6));
}

/// The same program with the full-profile insert it was written for: d2 = basic 9.026, which
/// is 32 µm over 6g's 8.994 (the program has no allowance for es).
#[test]
fn full_profile_insert_with_the_same_program() {
    let prog = data("programs/fanuc-m10-full-depth-g76.nc");
    let (code, v) = json_of(&[
        "verify",
        "--thread",
        "M10x1.5-6g",
        "--insert",
        "full",
        "--program",
        prog.to_str().unwrap(),
    ]);
    assert_eq!(code, 1);
    let dev = check(&v["operations"][0], "pitch_diameter")["deviation_um"].as_f64().unwrap();
    assert!((dev - 32.0).abs() < 0.5, "{dev}");
}

/// Grooves so deep that they meet leave no crest: a partial V at X7.0 from a 9.85 blank is
/// 2·1.425·tan 30° = 1.645 mm wide at the blank, more than the 1.5 mm pitch. Its own failure,
/// with its own message.
#[test]
fn grooves_that_meet_leave_no_crest() {
    let (code, v) = json_of(&["verify", "--thread", "M10x1.5-6g", "--final-x", "7.0"]);
    assert_eq!(code, 1);
    let c = check(&v, "crest");
    assert_eq!(c["ok"], false);
    assert!(c["note"].as_str().unwrap().contains("no crest left"), "{c}");
}

/// Two passes at the same depth 0.4 mm apart along Z (a phase error) cut two V pockets with a
/// ridge 0.4 / (2·tan 30°) = 0.35 mm high between them: the passes do not land in one groove.
#[test]
fn passes_off_the_helix_do_not_land_in_one_groove() {
    let prog = data("programs/fanuc-g32-phase-error.nc");
    let (code, v) =
        json_of(&["verify", "--thread", "M10x1.5-6g", "--program", prog.to_str().unwrap(), "--gauge-only"]);
    let v = &v["operations"][0];
    let c = check(v, "single_groove");
    assert_eq!(c["ok"], false, "{v:#}");
    assert!(c["note"].as_str().unwrap().contains("do not land in one groove"));
    // The check is a form check: --gauge-only leaves it out, the size checks decide.
    let size_ok =
        v["checks"].as_array().unwrap().iter().filter(|c| c["kind"] == "size").all(|c| c["ok"] == true);
    assert_eq!(code, if size_ok { 0 } else { 1 });
    let (code_full, _) = json_of(&["verify", "--thread", "M10x1.5-6g", "--program", prog.to_str().unwrap()]);
    assert_eq!(code_full, 1);
}

/// `--no-pass-metrics` gives the same verdict and measurement without the per-pass chip data.
#[test]
fn no_pass_metrics_keeps_the_verdict() {
    let (code_a, a) = json_of(&["verify", "--thread", "M10x1.5-6g"]);
    let (code_b, b) = json_of(&["verify", "--thread", "M10x1.5-6g", "--no-pass-metrics"]);
    assert_eq!(code_a, code_b);
    assert_eq!(a["measured"], b["measured"]);
    assert_eq!(a["verdict"], b["verdict"]);
    assert!(a["passes"][0].get("chip_area").is_some());
    assert!(b["passes"][0].get("chip_area").is_none());
    assert_eq!(a["passes"].as_array().unwrap().len(), b["passes"].as_array().unwrap().len());
}

/// Bug: inside a nut the maximum-material profile was moved the wrong way, so a 6G nut was
/// gauged against a GO profile 2·EI below the basic D2 instead of EI above it (M20x1.5-6G at
/// D2 = D2 min read +16 µm clearance). A full-profile insert at X cuts D2 = X − 0.649519·P and
/// clears the maximum-material flanks by (D2 − D2 min)/2 · sin 30° (normal distance between
/// parallel 60° flanks); D2 min = D2 min(6H) + EI(G), EI(G) = −es(g) (ISO 965-1).
#[test]
fn regression_internal_gauge_moved_the_wrong_way() {
    let t = data_toml("iso965-limits.toml");
    let row = t["thread"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["designation"].as_str() == Some("M20x1.5-6H/6g"))
        .unwrap();
    let ei_g = -row["es_um"].as_integer().unwrap() as f64 * 1e-3;
    let d2_min_6g_nut = row["internal"]["D2_min"].as_float().unwrap() + ei_g;
    let d2_max_bolt = row["external"]["d2_max"].as_float().unwrap();
    let sin30 = 0.5;
    let cases: [(&str, &[&str], f64, f64); 3] = [
        ("M20x1.5-6G", &[], 20.052, d2_min_6g_nut),
        // Not at X = D min: the published D2 min (from the rounded basic 19.026) puts the GO
        // profile's flats 0.14 µm off the exact basic, which would decide a case on the limit.
        ("M20x1.5-6G", &[], 20.042, d2_min_6g_nut),
        // The bolt with a blank below d max, so the crest is not topped above the GO profile.
        ("M20x1.5-6g", &["--blank-diameter", "19.9"], 18.124, d2_max_bolt),
    ];
    for (thread, extra, x, d2_mmc) in cases {
        let xs = format!("{x}");
        let mut args = vec!["verify", "--thread", thread, "--insert", "full", "--infeed", "radial"];
        args.extend(["--final-x", &xs]);
        args.extend(extra);
        let (_, v) = json_of(&args);
        let internal = thread.ends_with('G');
        // Basic: d2 = d − 0.649519·P; the insert's tip at X = d (nut) or X = d3 (bolt).
        let d2 = if internal { x - 0.649_519 * 1.5 } else { x + 1.226_869 * 1.5 - 0.649_519 * 1.5 };
        let m = &v["measured"];
        assert!((m["pitch_diameter"].as_f64().unwrap() - d2).abs() < 2e-6, "{thread} X{x}: {m:#}");
        let want = if internal { d2 - d2_mmc } else { d2_mmc - d2 } / 2.0 * sin30;
        let got = m["max_material_clearance"].as_f64().unwrap();
        assert!((got - want).abs() < 1e-5, "{thread} X{x}: clearance {got} mm, analytic {want} mm");
    }
}

/// Bug: `--json /dev/null` wrote a temporary file in /dev and renamed it over the device, so
/// (run as root) /dev/null became a regular file and every later `2>/dev/null` filled it. A
/// FIFO stands in for the device here: it must still be a FIFO afterwards and carry the report.
/// The read end is opened non-blocking, so a regression fails instead of hanging.
#[cfg(target_os = "linux")]
#[test]
fn regression_json_to_dev_null_replaced_the_device() {
    use std::io::Read;
    use std::os::unix::fs::{FileTypeExt, OpenOptionsExt};
    const O_NONBLOCK: i32 = 0o4000; // Linux, x86-64 and AArch64
    let dir = tempdir("fifo");
    let fifo = dir.join("report.json");
    let made = Command::new("mkfifo").arg(&fifo).status();
    if !made.is_ok_and(|s| s.success()) {
        return; // no mkfifo on this machine: nothing to check
    }
    let mut reader = std::fs::OpenOptions::new().read(true).custom_flags(O_NONBLOCK).open(&fifo).unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_threadcheck"))
        .args(["verify", "--thread", "M10x1.5-6g", "--insert", "full", "--json"])
        .arg(&fifo)
        .stdout(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let (mut got, mut buf, mut done) = (Vec::new(), [0u8; 65536], false);
    loop {
        match reader.read(&mut buf) {
            Ok(n) if n > 0 => got.extend_from_slice(&buf[..n]),
            Ok(_) if done => break,
            _ => std::thread::sleep(std::time::Duration::from_millis(2)),
        }
        // One more read after the exit drains what the child wrote last.
        done = done || child.try_wait().unwrap().is_some();
    }
    assert!(std::fs::metadata(&fifo).unwrap().file_type().is_fifo(), "the FIFO was replaced");
    let v: serde_json::Value = serde_json::from_slice(&got).expect("the report came through the FIFO");
    assert_eq!(v["verdict"], "pass");
}

/// Regression (A2): the basic profile of M30x1.5 (a full-profile insert at X30 in the nut) meets
/// 6H's D2 min = 29.026 (the table's rounding of 29.02572) exactly: compared at the tables'
/// 1 µm resolution, it passes.
#[test]
fn regression_a2_a_limit_exactly_met_passes() {
    let (code, v) = json_of(&[
        "verify",
        "--thread",
        "M30x1.5-6H",
        "--insert",
        "full",
        "--final-x",
        "30",
        "--no-pass-metrics",
    ]);
    assert_eq!(code, 0, "{v:#}");
    let c = check(&v, "pitch_diameter");
    assert_eq!((c["ok"].as_bool(), c["min"].as_f64()), (Some(true), Some(29.026)));
    assert!(
        c["value"].as_f64().unwrap() < 29.026,
        "the measured value is the true one, below the rounded limit"
    );
}

/// Regression (A6): a program whose passes stop above the blank gets a FAIL verdict that says
/// why, not an error.
#[test]
fn regression_a6_passes_that_miss_the_blank_fail_with_a_reason() {
    let prog = data("programs/fanuc-g92-above-blank.nc");
    let (code, v) = json_of(&["verify", "--thread", "M20x1.5-6g", "--program", prog.to_str().unwrap()]);
    assert_eq!(code, 1);
    let op = &v["operations"][0];
    assert_eq!(op["verdict"], "fail");
    let reason = op["reason"].as_str().unwrap();
    assert!(reason.contains("no pass reaches the blank") && reason.contains("X20.5000"), "{reason}");
}

/// `--tools` maps the program's T0303 to the full-profile insert; without it the report says
/// which insert it assumed and why.
#[test]
fn tool_table_chooses_the_insert_of_the_programs_tool() {
    let prog = data("programs/haas-g76-metric.nc");
    let tools = data("tools.toml");
    let args = [
        "verify",
        "--thread",
        "M20x2-6g",
        "--program",
        prog.to_str().unwrap(),
        "--dialect",
        "haas",
        "--no-pass-metrics",
    ];
    let mut with = args.to_vec();
    with.extend(["--tools", tools.to_str().unwrap()]);
    let (_, v) = json_of(&with);
    let op = &v["operations"][0];
    assert_eq!(op["insert"]["kind"], "full", "{op:#}");
    assert!(op["notes"]
        .as_array()
        .unwrap()
        .iter()
        .any(|n| n.as_str().unwrap().contains("insert of tool T3")));
    assert!(check(op, "root_radius")["unverified"].is_null(), "the table's insert is known");
    // Without the table: the full-profile insert assumed (issue 59), its root unverified.
    let (_, v) = json_of(&args);
    let op = &v["operations"][0];
    assert_eq!(op["insert"]["kind"], "full");
    assert!(check(op, "root_radius")["unverified"].as_str().unwrap().contains("tool not known"));
    let notes: Vec<&str> = op["notes"].as_array().unwrap().iter().map(|n| n.as_str().unwrap()).collect();
    assert!(
        notes.iter().any(|n| n.to_string().contains("insert assumed")
            && n.to_string().contains("T3")
            && n.to_string().contains("--tools")),
        "{notes:?}"
    );
}

/// Issue 14's CLI points: `limits --thread` as the other commands take it, `--passes 0` is an
/// error, and `sweep` exits 1 when a case fails (a partial insert leaves M10's root radius below
/// 0.125·P) and 0 when none does.
#[test]
fn cli_limits_thread_passes_zero_and_sweep_exit_codes() {
    let a = run(&["limits", "--thread", "M10-6g", "--json"]);
    let b = run(&["limits", "M10-6g", "--json"]);
    assert_eq!(a.status.code(), Some(0));
    assert_eq!(a.stdout, b.stdout);
    let e = run(&["verify", "--thread", "M10x1.5-6g", "--passes", "0"]);
    let line = one_line_error(&e);
    assert!(line.contains("'0' for '--passes") && line.contains("at least one pass"), "{line}");
    // One M10 coarse case, radial, constant area: the partial insert fails its form checks, the
    // full-profile insert passes.
    let fail = sweep_m10("partial", "radial", &[]);
    assert_eq!(fail.status.code(), Some(1), "{}", stdout(&fail));
    assert!(stdout(&fail).contains("1 cases, 0 pass, 1 fail"));
    let pass = sweep_m10("full", "radial", &[]);
    assert_eq!(pass.status.code(), Some(0), "{}", stdout(&pass));
}

/// `--json` means the same in every command: alone or with `-` the JSON on stdout, with a path
/// the JSON in that file and the text on stdout. `limits --json M10…` names the mistake.
#[test]
fn json_flag_is_the_same_in_every_command() {
    let dir = tempdir("json-flag");
    for (args, text_marker) in [
        (vec!["limits", "M10x1.5-6g"], "fundamental triangle height"),
        (vec!["passes", "--thread", "M10x1.5-6g"], "X start"),
        (vec!["verify", "--thread", "M10x1.5-6g", "--insert", "full"], "pitch diameter"),
        (vec!["compare", "--thread", "M10x1.5-6g", "--insert", "full", "--passes", "6"], "radial"),
    ] {
        let bare = run_in(&dir, &[args.as_slice(), &["--json"]].concat());
        let dash = run_in(&dir, &[args.as_slice(), &["--json", "-"]].concat());
        assert!(matches!(bare.status.code(), Some(0 | 1)), "{args:?}: {}", stderr(&bare));
        assert_eq!(bare.status.code(), dash.status.code());
        assert_eq!(bare.stdout, dash.stdout, "{args:?}");
        let on_stdout: serde_json::Value = serde_json::from_slice(&bare.stdout).unwrap();
        let file = run_in(&dir, &[args.as_slice(), &["--json", "out.json"]].concat());
        assert_eq!(file.status.code(), bare.status.code());
        assert!(stdout(&file).contains(text_marker), "{args:?}: {}", stdout(&file));
        let written: serde_json::Value =
            serde_json::from_slice(&std::fs::read(dir.join("out.json")).unwrap()).unwrap();
        // The same report either way (compare's chip figures are deterministic too).
        assert_eq!(written, on_stdout, "{args:?}");
    }
    let e = run(&["limits", "--json", "M10x1.5-6g"]);
    assert_eq!(
        one_line_error(&e),
        "threadcheck: error: limits needs a designation: --json took 'M10x1.5-6g' as its file; write `limits M10x1.5-6g --json`"
    );
}

/// Issue 14: `verify --infeed` and `sweep --infeed` read the same words. `modified` is half the
/// thread angle less 0.5° (29.5° on a 60° thread, 14.5° on a 30° trapezoidal), `flank:27` is 27°
/// whatever the form, `flank` alone half the thread angle.
#[test]
fn infeed_words_are_the_same_in_verify_and_sweep() {
    let angle = |v: &serde_json::Value| v["plan"]["infeed"]["angle"].as_f64().unwrap();
    let verify = |thread: &str, infeed: &str| {
        let o = run(&["verify", "--thread", thread, "--infeed", infeed, "--no-pass-metrics", "--json"]);
        serde_json::from_slice::<serde_json::Value>(&o.stdout).unwrap()
    };
    assert_eq!(angle(&verify("M10x1.5-6g", "modified")), 29.5);
    assert_eq!(angle(&verify("Tr40x7-7e", "modified")), 14.5);
    assert_eq!(angle(&verify("Tr40x7-7e", "flank")), 15.0);
    assert_eq!(angle(&verify("M10x1.5-6g", "flank:27")), 27.0);
    let o = sweep_m10("full", "modified,flank:27", &["--json"]);
    let angles: Vec<f64> =
        stdout(&o).lines().map(|l| angle(&serde_json::from_str::<serde_json::Value>(l).unwrap())).collect();
    assert_eq!(angles, [29.5, 27.0]);
}

/// Issue 14: the value types of the reports read back (`Deserialize`): a post can keep the pass
/// list of `passes --json` as `Vec<Pass>`. A G92 box cycle with X words 9.4, 9.0, 8.6, 8.2 from
/// Z3 to Z-15 at lead 1.5.
#[test]
fn passes_json_reads_back_as_pass_values() {
    use threadcheck::Pass;
    let dir = tempdir("readback");
    std::fs::write(dir.join("box.nc"), "G0 X12 Z3\nG92 X9.4 Z-15 F1.5\nX9.0\nX8.6\nX8.2\nG0 X50\nM30\n")
        .unwrap();
    let o = run_in(&dir, &["passes", "--program", "box.nc", "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let passes: Vec<Pass> = serde_json::from_value(v["passes"].clone()).unwrap();
    let xs: Vec<f64> = passes.iter().map(|p| p.x_end).collect();
    assert_eq!(xs, [9.4, 9.0, 8.6, 8.2]);
    assert!(passes.iter().all(|p| p.z_start == 3.0 && p.z_end == -15.0 && p.lead == 1.5));
    let infeed: threadcheck::Infeed = serde_json::from_str(r#"{"method":"flank","angle":29.5}"#).unwrap();
    assert_eq!(infeed, threadcheck::Infeed::Flank { angle: 29.5 });
}

/// Issue 14: labels carry no float noise: 0.035 is not 0.034999999999999996.
#[test]
fn insert_label_has_no_float_noise() {
    let o = run(&[
        "verify",
        "--thread",
        "M10x1.5-6g",
        "--insert",
        "partial:0.035",
        "--no-pass-metrics",
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["insert"]["name"], "partial 60° r0.035");
    assert_eq!(v["insert"]["tip_radius"], 0.035);
}

/// Issue 59: a designation given by mistake is refused where the program cuts another size,
/// naming both, and no correction is offered. An M30x1.5 bolt turned to Ø29.97 and threaded to
/// X28.16 (= 30 − 2·h3, h3 = 17/24·0.866025·1.5 = 0.920) given `M20x1.5-6g` (d3 = 20 − 1.840 =
/// 18.160): 10 mm apart on the diameter, far over one thread depth.
#[test]
fn a_designation_of_another_size_is_refused_naming_both() {
    let p = data("programs/m30x1.5-turned.nc");
    let o = run(&["verify", "--program", p.to_str().unwrap(), "--thread", "M20x1.5-6g"]);
    assert_eq!(o.status.code(), Some(2), "{}", stdout(&o));
    let e = stderr(&o);
    assert_eq!(e.lines().count(), 1, "{e}");
    assert!(e.contains("m30x1.5-turned.nc:12:1:"), "{e}");
    assert!(e.contains("about Ø30.0 (final X28.160)") && e.contains("M20x1.5-6g is Ø20 (d3 18.160)"), "{e}");
    assert!(!e.contains("X18") && !e.contains("change"), "no correction: {e}");
    // The thread the passes cut, by their lead and diameters, beside the one given.
    assert!(e.trim_end().ends_with("check the thread (the passes fit M30x1.5-6g, inferred)"), "{e}");
    // The size it cuts is checked as ever.
    let o = run(&["verify", "--program", p.to_str().unwrap(), "--thread", "M30x1.5-6g"]);
    assert!(matches!(o.status.code(), Some(0 | 1)), "{}", stderr(&o));
}

/// Issue 59: with no turned blank, the wrong designation's default blank is never reached: a FAIL
/// (no cut) that names both diameters and offers no final X (it was "a last pass at X17.7050",
/// a 5 mm plunge into the M30 bolt).
#[test]
fn a_designation_of_another_size_offers_no_plunge() {
    let dir = tempdir("misfit");
    let text = std::fs::read_to_string(data("programs/m30x1.5-turned.nc")).unwrap();
    let untouched: String =
        text.lines().filter(|l| !l.starts_with("G1 ")).map(|l| format!("{l}\n")).collect();
    std::fs::write(dir.join("m30.nc"), untouched).unwrap();
    let o = run_in(&dir, &["verify", "--program", "m30.nc", "--thread", "M20x1.5-6g"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(
        out.contains("no cut")
            && out.contains("M20x1.5-6g is Ø20")
            && out.contains("no correction is offered"),
        "{out}"
    );
    assert!(!out.contains("a last pass at X"), "{out}");
    let o = run_in(&dir, &["verify", "--program", "m30.nc", "--thread", "M20x1.5-6g", "--json", "-"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let op = &v["operations"][0];
    assert!(op["suggested_final_x"].is_null(), "{op}");
}

/// Issue 59: a program that names no insert is cut with the full-profile insert its depth is
/// written for, and what that insert's shape alone decides is `unverified`, never failed. An
/// M30x1.5 bolt turned to Ø29.85 (inside 6g's d, 29.732–29.968) and threaded to X28.053: a
/// full-profile tip there leaves d2 = 28.053 + 0.57735·1.5 = 28.919, the middle of 6g's
/// 28.844–28.994: PASS on size, with d3, the root radius and the crest unverified.
#[test]
fn a_program_without_its_tool_passes_on_size_with_its_form_unverified() {
    let p = data("programs/m30x1.5-mid.nc");
    let (code, v) = json_of(&["verify", "--program", p.to_str().unwrap()]);
    assert_eq!(code, 0, "{v}");
    let op = &v["operations"][0];
    assert_eq!(op["unverified"], serde_json::json!(["minor_diameter", "root_radius", "crest"]));
    assert!((check(op, "pitch_diameter")["value"].as_f64().unwrap() - 28.919).abs() < 1e-4);
    assert!(check(op, "pitch_diameter")["unverified"].is_null());
    assert!(check(op, "root_radius")["unverified"].as_str().unwrap().contains("tool not known"));
    let text = stdout(&run(&["verify", "--program", p.to_str().unwrap()]));
    assert!(text.contains("verdict: PASS — form unverified (minor diameter d3, root radius, crest left standing): tool not known"), "{text}");
    // The picture and the page say it too: the verdict line, and the three rows (seen in Chromium).
    let dir = tempdir("unverified-svg");
    let o = run_in(&dir, &["verify", "--program", p.to_str().unwrap(), "--svg", "m.svg", "--html", "m.html"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let svg = std::fs::read_to_string(dir.join("m.svg")).unwrap();
    assert!(svg.contains("IN TOLERANCE — form unverified: tool not known"), "no verdict line");
    assert_eq!(svg.matches(">\nunverified\n<").count(), 3, "three unverified rows");
    let html = std::fs::read_to_string(dir.join("m.html")).unwrap();
    assert!(html.contains(
        "IN TOLERANCE — form unverified: tool not known: the insert assumed is full-profile iso-metric P1.5"
    ));
    // A tool table naming a partial-profile insert with a 0.04 mm tip: the root radius is the
    // program's now, and 0.04 is under the standard's 0.125·P = 0.1875 mm.
    let dir = tempdir("tools-04");
    std::fs::write(dir.join("tools.toml"), "[tools]\n3 = \"partial:0.04\"\n").unwrap();
    let o =
        run_in(&dir, &["verify", "--program", p.to_str().unwrap(), "--tools", "tools.toml", "--json", "-"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let root = check(&v["operations"][0], "root_radius");
    assert_eq!(root["ok"].as_bool(), Some(false));
    assert!((root["value"].as_f64().unwrap() - 0.04).abs() < 1e-9, "{root}");
    assert!(root["unverified"].is_null());
}
