//! Issue 25: every shop's program. Programs written for these tests (never copies of others'),
//! each with its hand derivation in its comments; the values asserted come from those.

use crate::*;

/// `verify --program shop/FILE --thread T --insert full … --json -`: exit code and report.
fn verify_json(file: &str, thread: &str, more: &[&str]) -> (i32, serde_json::Value) {
    let path = data(&format!("programs/shop/{file}"));
    let mut args =
        vec!["verify", "--program", path.to_str().unwrap(), "--thread", thread, "--insert", "full"];
    args.extend_from_slice(more);
    args.extend(["--json", "-"]);
    let o = run(&args);
    let code = o.status.code().unwrap();
    assert!(code == 0 || code == 1, "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    (code, v["operations"][0].clone())
}

fn check<'a>(v: &'a serde_json::Value, feature: &str) -> Option<&'a serde_json::Value> {
    v["checks"].as_array().unwrap().iter().find(|c| c["feature"] == feature)
}

/// A metric control's F1.814 for 14 tpi is 25.4/14 rounded to its 0.001 mm: it matches. Issue 48:
/// the lead error adds up over the thread the gauge engages, NPT's L1 = 0.320 in = 8.128 mm (ASME
/// B1.20.1), not the whole 30 mm pass: −0.2857 µm a turn × 8.128/1.8142857 turns = −1.280 µm,
/// × cot 30° = 2.217 µm on the pitch diameter, the gauge off 2.217e-3 / 0.0625 / 1.8142857 =
/// 0.020 turn (it said 0.072 over the whole pass).
#[test]
fn an_npt_job_at_f1_814_verifies_with_its_lead_error() {
    let (code, v) = verify_json("npt-1-2-14-metric-f1814.nc", "1/2-14 NPT", &[]);
    assert_eq!(code, 0, "{v}");
    let ld = &v["lead_deviation"];
    assert!((ld["cumulative"].as_f64().unwrap() * 1000.0 + 1.280).abs() < 1e-3, "{ld}");
    assert!((ld["pitch_diameter_equivalent"].as_f64().unwrap() * 1000.0 - 2.217).abs() < 1e-3, "{ld}");
    assert_eq!(
        (ld["length"].as_f64(), ld["engagement"].as_f64(), ld["pass_length"].as_f64()),
        (Some(8.128), Some(8.128), Some(30.0))
    );
    assert_eq!(ld["increment"], 0.001);
    let gp = check(&v, "gauge_plane").unwrap();
    assert!(gp["note"].as_str().unwrap().contains("stands the gauge off 0.020 turn"), "{gp}");
    let f = v["measured"]["functional_pitch_diameter"].as_f64().unwrap();
    let d2 = v["measured"]["pitch_diameter"].as_f64().unwrap();
    assert!(((f - d2) * 1000.0 - 2.217).abs() < 1e-3);
}

/// G1/8 at F0.907: d2 9.119868 by the insert's geometry. The lead error over LE = D = 9.728 mm
/// (ISO 228-1's major diameter; issue 48): −0.1429 µm a turn × 10.724 turns = −1.532 µm, × cot
/// 27.5° = 2.943 µm: functional 9.122811, under d2 max 9.147.
#[test]
fn a_28_tpi_pipe_thread_at_f0_907_passes_with_its_functional_diameter() {
    let (code, v) = verify_json("bsp-g1-8-28tpi-f0907.nc", "G1/8 A", &[]);
    assert_eq!(code, 0, "{v}");
    let c = check(&v, "functional_pitch_diameter").unwrap();
    assert!((c["value"].as_f64().unwrap() - 9.122811).abs() < 1e-6, "{c}");
    assert_eq!(c["max"], 9.147);
    assert!(c["ok"].as_bool().unwrap());
}

/// The same thread 25 µm larger: d2 9.144868 passes, the functional 9.147811 is 0.811 µm over.
#[test]
fn a_lead_error_fails_the_go_side_where_the_pitch_diameter_alone_passes() {
    let (code, v) = verify_json("bsp-g1-8-28tpi-f0907-at-max.nc", "G1/8 A", &[]);
    assert_eq!(code, 1, "{v}");
    assert!(check(&v, "pitch_diameter").unwrap()["ok"].as_bool().unwrap());
    let c = check(&v, "functional_pitch_diameter").unwrap();
    assert!(!c["ok"].as_bool().unwrap());
    assert!((c["deviation_um"].as_f64().unwrap() - 0.811).abs() < 1e-3, "{c}");
}

/// An inch control's F.0714 for 14 tpi: 0.0001 in increment. Over LE = D = 0.875 in = 22.225 mm
/// (ASME B1.1; the finishing pass threads 1.173211 in): −0.0000286 in a turn × 12.25 turns =
/// −8.890 µm, × cot 30° = +15.398 µm on d2. `--engagement` sets another length.
#[test]
fn an_inch_program_at_f_0714_matches_14_tpi_at_a_ten_thousandth() {
    let (code, v) = verify_json("unf-7-8-14-inch-f0714.nc", "7/8-14 UNF-2A", &["--dialect", "haas"]);
    assert_eq!(code, 0, "{v}");
    let ld = &v["lead_deviation"];
    assert_eq!(ld["units"], "inch");
    assert_eq!(ld["increment"], 0.0001);
    assert!((ld["length"].as_f64().unwrap() - 22.225).abs() < 1e-9, "{ld}");
    assert!((ld["pass_length"].as_f64().unwrap() - 29.7996).abs() < 1e-4, "{ld}");
    assert!((ld["pitch_diameter_equivalent"].as_f64().unwrap() * 1000.0 - 15.398).abs() < 1e-3, "{ld}");
    // 11.1125 mm of engagement given: half of it.
    let (_, h) = verify_json(
        "unf-7-8-14-inch-f0714.nc",
        "7/8-14 UNF-2A",
        &["--dialect", "haas", "--engagement", "11.1125"],
    );
    assert!(
        (h["lead_deviation"]["pitch_diameter_equivalent"].as_f64().unwrap() * 1000.0 - 7.699).abs() < 1e-3
    );
}

/// Issue 48: a program with 3 mm of run-in in air (the pass from Z3 to Z−12, the part's face at
/// Z0) adds its lead error up over the 12 mm on the part, capped at LE = D = 11.1125 mm for
/// 7/16-14 UNC (ASME B1.1), not over the 15 mm pass: −0.2857 µm a turn × 11.1125/1.8142857 turns
/// = −1.750 µm, × cot 30° = 3.031 µm (the whole pass would give 4.091 µm).
#[test]
fn run_in_in_air_adds_no_lead_error() {
    let text =
        "G21 G97 S500 M3\nG0 X13 Z3\nG92 X10.9 Z-12 F1.814\nX10.5\nX10.2\nX9.95\nX9.8\nG0 X20 Z20\nM30\n";
    let dir = tempdir("run-in");
    std::fs::write(dir.join("p.nc"), text).unwrap();
    let o = run_in(
        &dir,
        &["verify", "--program", "p.nc", "--thread", "7/16-14 UNC-2A", "--insert", "full", "--json"],
    );
    assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let ld = &v["operations"][0]["lead_deviation"];
    assert!((ld["length"].as_f64().unwrap() - 11.1125).abs() < 1e-9, "{ld}");
    assert_eq!(ld["pass_length"].as_f64(), Some(15.0));
    assert!((ld["pitch_diameter_equivalent"].as_f64().unwrap() * 1000.0 - 3.031).abs() < 1e-3, "{ld}");
}

/// A lead further off than the program's increment rounds is refused, both leads to four
/// decimals (never sixteen digits).
#[test]
fn a_lead_beyond_the_rounding_is_refused_with_both_leads_short() {
    let text = std::fs::read_to_string(data("programs/shop/bsp-g1-8-28tpi-f0907.nc")).unwrap();
    let dir = tempdir("lead");
    std::fs::write(dir.join("p.nc"), text.replace("F0.907", "F0.91")).unwrap();
    let o = run_in(&dir, &["verify", "--program", "p.nc", "--thread", "G1/8 A"]);
    assert_eq!(o.status.code(), Some(2));
    let e = one_line_error(&o);
    assert!(
        e.contains("p.nc:8:1: the program cuts a lead of 0.9100 mm, the designation G1/8 A has 0.9071 mm"),
        "{e}"
    );
}

/// `.ngc` is read as LinuxCNC and `.mpf` as Sinumerik without `--dialect`, and the output says so.
#[test]
fn the_extension_chooses_the_dialect_and_says_so() {
    let dir = tempdir("ext");
    // LinuxCNC G76 in G7 diameter mode, M10x1.5 by hand: the drive line X11 and I-1 put the
    // crest at Ø10; K0.92 is the radial thread depth to the tip.
    std::fs::write(
        dir.join("m10.ngc"),
        "G21 G7 G18 S500 M3\nG0 X12 Z3\nG76 P1.5 Z-15 I-1 J0.2 K0.92 Q29.5 H1\nM2\n",
    )
    .unwrap();
    let o = run_in(&dir, &["verify", "--program", "m10.ngc", "--thread", "M10x1.5-6g"]);
    assert!(o.status.code() == Some(0) || o.status.code() == Some(1), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("m10.ngc (linuxcnc)"), "{out}");
    assert!(out.contains("read as linuxcnc, the dialect of its extension .ngc"), "{out}");
}

/// An inch shop's program with neither G20 nor G21: read in mm it cuts a 0.05 mm lead (refused
/// against 1/4-20's 1.27 mm, with the assumption named); `--default-units inch` reads it as the
/// inch control does, and says so.
#[test]
fn default_units_read_a_program_that_sets_none() {
    let dir = tempdir("units");
    std::fs::write(dir.join("q.nc"), "O0020\nT0404\nG0 X0.3 Z0.1\nG76 X0.2 Z-0.25 K0.044 D0.01 F0.05\nM30\n")
        .unwrap();
    let args = ["verify", "--program", "q.nc", "--thread", "1/4-20 UNC-2A", "--dialect", "haas"];
    let o = run_in(&dir, &args);
    assert_eq!(o.status.code(), Some(2));
    let e = one_line_error(&o);
    assert!(e.contains("the program cuts a lead of 0.0500 mm"), "{e}");
    assert!(e.contains("read in inches it is the designation's"), "{e}");
    let mut with = args.to_vec();
    with.extend(["--default-units", "inch"]);
    let o = run_in(&dir, &with);
    assert!(o.status.code() == Some(0) || o.status.code() == Some(1), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("the program sets no units (G20/G21) before it threads: read in inch"), "{out}");
    // X0.2 in is the tip's diameter: 5.08 mm (given in inches first, issue 65).
    assert!(out.contains("final X0.2000 (5.0800 mm)"), "{out}");
}

/// `verify --fix OUT` and the re-verification of OUT: (report before, report after, the fixed
/// program's text).
fn fix_and_reverify(
    file: &str,
    thread: &str,
    more: &[&str],
) -> (serde_json::Value, serde_json::Value, String) {
    let mut spec = vec!["--thread", thread, "--insert", "full"];
    spec.extend_from_slice(more);
    let (before, after, text) = fix_then_verify(&data(&format!("programs/shop/{file}")), &spec);
    (before["operations"][0].clone(), after["operations"][0].clone(), text)
}

fn d2(v: &serde_json::Value) -> f64 {
    v["measured"]["pitch_diameter"].as_f64().unwrap()
}

/// A G20 Haas G76: the correction is its X in inches (a diameter), and d2 moves one for one with
/// it: ΔX·25.4. The fixed program's d2 is within the 0.0001 in rounding (1.27 µm on d2) plus the
/// table's own rounding of the middle of ASME B1.1's 1/2-13 UNC-2A band, 0.4435–0.4485 in.
#[test]
fn a_g20_program_is_corrected_in_inches() {
    let (before, after, text) =
        fix_and_reverify("haas-g20-1-2-13-unc.nc", "1/2-13 UNC-2A", &["--dialect", "haas"]);
    let c = &before["correction"];
    assert_eq!(c["word"], "X");
    assert_eq!(c["units"], "inch");
    assert_eq!(c["line"], 6);
    assert!(
        c["text"].as_str().unwrap().starts_with("change X0.4072 at line 6:5 to X0.4016 (inch, diameter)"),
        "{c}"
    );
    assert!(text.contains("G76 X0.4016 Z-1.0 K0.0471"), "{text}");
    let dx = (c["value"].as_f64().unwrap() - c["was"].as_f64().unwrap()) * 25.4;
    assert!((d2(&after) - d2(&before) - dx).abs() < 1e-6);
    assert!((d2(&after) - 0.4460 * 25.4).abs() < 0.00127 + 0.00127, "{}", d2(&after));
}

/// LinuxCNC in G8: the last pass's X is a radius, so d2 moves by twice its change. M10x1.5-6g's
/// d2 band is 8.862–8.994 (ISO 965-2): the middle 8.928, met to the 0.001 mm rounding (2 µm on d2).
#[test]
fn a_linuxcnc_radius_program_is_corrected_as_a_radius() {
    let (before, after, text) = fix_and_reverify("linuxcnc-g8-m10.ngc", "M10x1.5-6g", &[]);
    let c = &before["correction"];
    assert_eq!((c["word"].as_str(), c["line"].as_u64()), (Some("X"), Some(15)));
    assert_eq!(c["means"], "radius");
    assert!(text.lines().nth(14) == Some("G0 X4.031"), "{text}");
    let dx = c["value"].as_f64().unwrap() - c["was"].as_f64().unwrap();
    assert!((d2(&after) - d2(&before) - 2.0 * dx).abs() < 1e-6);
    assert!((d2(&after) - 8.928).abs() <= 0.002, "{}", d2(&after));
}

/// CYCLE97: the correction is TDEP, a radial depth: d2 moves by −2·ΔTDEP. M20x2.5-6g's band is
/// 18.164–18.334 (ISO 965-2), the middle 18.249.
#[test]
fn a_cycle97_program_is_corrected_in_its_depth() {
    let (before, after, text) = fix_and_reverify("cycle97-m20.mpf", "M20x2.5-6g", &[]);
    let c = &before["correction"];
    assert_eq!(c["word"], "TDEP");
    assert!(c["text"].as_str().unwrap().starts_with("change TDEP 1.400 at line 3:34 to 1.597"), "{c}");
    assert!(text.contains("CYCLE97(2.5,,0,-30,20,20,3,2,1.597,0.05,"), "{text}");
    let dt = c["value"].as_f64().unwrap() - c["was"].as_f64().unwrap();
    assert!((d2(&after) - d2(&before) + 2.0 * dt).abs() < 1e-6);
    assert!((d2(&after) - 18.249).abs() <= 0.002, "{}", d2(&after));
}

/// CYCLE99 (read in its named order, docs/dialects.md): the correction is TDEP, its 7th
/// argument, a radial depth. The program cuts 18.16 at 0.92: d2 19.026; M20x1.5-6g's band is
/// 18.854–18.994 (ISO 965-2), the middle 18.924: TDEP 0.92 + (19.026 − 18.924)/2 = 0.971.
#[test]
fn a_cycle99_program_is_corrected_in_its_depth() {
    let (before, after, text) = fix_and_reverify("../sinumerik-cycle99.mpf", "M20x1.5-6g", &[]);
    let c = &before["correction"];
    assert_eq!(c["word"], "TDEP");
    assert!(c["text"].as_str().unwrap().starts_with("change TDEP 0.92 at line 7:29 to 0.971"), "{c}");
    assert!(text.contains("CYCLE99(0,20,-25,20,3,2,0.971,0.05,30,"), "{text}");
    assert!((d2(&after) - 18.924).abs() <= 0.002, "{}", d2(&after));
}

/// A word that is not a plain number in place is not rewritten: the error says what to change.
#[test]
fn fix_refuses_an_expression_and_names_the_word() {
    let dir = tempdir("fixexpr");
    std::fs::write(
        dir.join("e.nc"),
        "G21 G97 S600 M3\n#1=8.2\nG0 X12 Z3\nG92 X9.4 Z-15 F1.5\nX8.8\nX[#1]\nG0 X30 Z30\nM30\n",
    )
    .unwrap();
    let o = run_in(
        &dir,
        &["verify", "--program", "e.nc", "--thread", "M10x1.5-6g", "--insert", "full", "--fix", "out.nc"],
    );
    assert_eq!(o.status.code(), Some(2));
    let e = one_line_error(&o);
    assert!(
        e.contains("e.nc:6:1: --fix rewrites plain numbers only: make X (written X[#1] at line 6:1)"),
        "{e}"
    );
    assert!(!dir.join("out.nc").exists());
}

/// The picture and the page say the correction too.
#[test]
fn the_svg_and_the_page_say_the_correction() {
    let dir = tempdir("fixsvg");
    let src = data("programs/shop/cycle97-m20.mpf");
    let o = run_in(
        &dir,
        &[
            "verify",
            "--program",
            src.to_str().unwrap(),
            "--thread",
            "M20x2.5-6g",
            "--insert",
            "full",
            "--svg",
            "c.svg",
            "--html",
            "c.html",
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    for f in ["c.svg", "c.html"] {
        let t = std::fs::read_to_string(dir.join(f)).unwrap();
        assert!(t.contains("change TDEP 1.400 at line 3:34 to 1.597 (mm, thread depth)"), "{f}");
    }
}

/// `m10x1.5-6g` is M10x1.5-6g (ISO's series letter in the wrong case); a decimal comma is named
/// with the designation written right; `--insert Full` is `full`, and a word that is neither a
/// keyword nor a file is named with the words `--insert` takes.
#[test]
fn designations_and_insert_words_are_read_as_a_person_writes_them() {
    let o = run(&["limits", "m10x1.5-6g", "--json", "-"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    // ISO 965-2: d2 of 6g is 8.862–8.994.
    assert_eq!(v["external"]["pitch_diameter"]["max"], 8.994, "{v}");
    let o = run(&["limits", "M10x1,5-6g"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        one_line_error(&o).contains("a decimal comma: write a decimal point, M10x1.5-6g"),
        "{}",
        stderr(&o)
    );
    let o = run(&["verify", "--thread", "M10x1.5-6g", "--insert", "Full"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let o = run(&["verify", "--thread", "M10x1.5-6g", "--insert", "fulll"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(one_line_error(&o).contains("expected full, partial, partial:TIP_RADIUS or an insert FILE.toml"));
}

/// `--fix -` prints the corrected program instead of the report (and will not share stdout with
/// `--json -`); `--fix` onto the program itself is refused and the program is kept.
#[test]
fn fix_to_stdout_and_never_over_the_program() {
    let dir = tempdir("fixstd");
    let text = std::fs::read_to_string(data("programs/shop/haas-g20-1-2-13-unc.nc")).unwrap();
    std::fs::write(dir.join("h.nc"), &text).unwrap();
    let base =
        ["verify", "--program", "h.nc", "--dialect", "haas", "--thread", "1/2-13 UNC-2A", "--insert", "full"];
    let mut args = base.to_vec();
    args.extend(["--fix", "-"]);
    let o = run_in(&dir, &args);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert_eq!(stdout(&o), text.replace("G76 X0.4072 ", "G76 X0.4016 "));
    args.extend(["--json", "-"]);
    let o = run_in(&dir, &args);
    assert_eq!(o.status.code(), Some(2));
    assert!(one_line_error(&o).contains("--json - and --fix - both want standard output"));
    let mut args = base.to_vec();
    args.extend(["--fix", "h.nc"]);
    let o = run_in(&dir, &args);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(dir.join("h.nc")).unwrap(), text);
}

/// The units note names the dialect's own codes: G70/G71 on a Sinumerik.
#[test]
fn the_units_note_names_the_dialects_codes() {
    let dir = tempdir("sinunits");
    std::fs::write(
        dir.join("s.mpf"),
        "G0 X25 Z10\nCYCLE97(2.5,,0,-30,20,20,3,2,1.534,0.05,29.5,0,8,2,3,1)\nM30\n",
    )
    .unwrap();
    let o = run_in(&dir, &["passes", "--program", "s.mpf"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("the program sets no units (G70/G71) before it threads: read in mm"),
        "{}",
        stdout(&o)
    );
}

/// `passes --program shop/FILE --json`: the program's passes and notes.
fn passes_json(file: &str) -> serde_json::Value {
    let path = data(&format!("programs/shop/{file}"));
    let o = run(&["passes", "--program", path.to_str().unwrap(), "--json"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    serde_json::from_slice(&o.stdout).unwrap()
}

fn notes_of(v: &serde_json::Value) -> Vec<String> {
    v["notes"].as_array().unwrap().iter().map(|n| n.as_str().unwrap().to_string()).collect()
}

/// A Sinumerik turning job: the tool names, messages, CYCLE95 with its contour name and CYCLE83
/// are read past, each named at its place; the CYCLE97 gives its 8 + 1 + 2 passes, the last at
/// X16.932 (the program's comments), and the verdict is reached.
#[test]
fn a_sinumerik_job_reads_past_what_is_not_threading() {
    let v = passes_json("cycle97-read-past.mpf");
    let passes = v["passes"].as_array().unwrap();
    assert_eq!(passes.len(), 11);
    assert!((passes[10]["x_end"].as_f64().unwrap() - 16.932).abs() < 1e-9);
    let notes = notes_of(&v);
    for (place, what) in [
        (":7:5:", "T=\"ROUGH_80\" read past"),
        (":8:5:", "MSG(…) read past (2 times)"),
        (":10:5:", "CYCLE95(…) read past"),
        (":12:5:", "CYCLE83(…) read past"),
        (":14:5:", "T=\"THREAD_60\" read past"),
    ] {
        assert!(notes.iter().any(|n| n.contains(place) && n.contains(what)), "{what}: {notes:?}");
    }
    let (code, r) = verify_json("cycle97-read-past.mpf", "M20x2.5-6g", &[]);
    assert!(code == 0 || code == 1);
    assert!(r["verdict"].is_string());
    let path = data("programs/shop/cycle97-read-past.mpf");
    let o =
        run(&["verify", "--program", path.to_str().unwrap(), "--thread", "M20x2.5-6g", "--insert", "full"]);
    assert!(stdout(&o).contains("6 blocks read past (named in the notes)"), "{}", stdout(&o));
}

/// A thread that depends on what was read past is refused, naming it.
#[test]
fn a_pass_that_starts_where_a_drilling_cycle_left_the_tool_is_refused() {
    let path = data("programs/shop/g33-after-cycle83.mpf");
    let o = run(&["passes", "--program", path.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains(
            "g33-after-cycle83.mpf:6:5: G33 starts from a position unknown since line 5 (CYCLE83(…), read past)"
        ),
        "{}",
        stderr(&o)
    );
}

/// Fanuc system A: the G90 box cycles return to X12 Z2, so the G76's first pass (0.4 deep)
/// starts 0.4·tan 30° before Z2; G92 S is named as a speed clamp, M21 as an unknown M code.
#[test]
fn a_fanuc_box_cycle_returns_to_its_start_and_g92_s_is_a_speed_clamp() {
    let v = passes_json("fanuc-box-cycle-m10.nc");
    let p0 = &v["passes"][0];
    assert!((p0["z_start"].as_f64().unwrap() - (2.0 - 0.4 * 30f64.to_radians().tan())).abs() < 1e-9, "{p0}");
    assert!((v["passes"].as_array().unwrap().last().unwrap()["x_end"].as_f64().unwrap() - 8.16).abs() < 1e-9);
    let notes = notes_of(&v);
    assert!(
        notes.iter().any(|n| n.contains(":10:1: G92 S2200 read past: a spindle speed clamp")),
        "{notes:?}"
    );
    assert!(notes
        .iter()
        .any(|n| n.contains(":13:1: G90 read past (2 times): a turning or facing box cycle")));
    assert!(notes.iter().any(|n| n.contains(":15:1: M21 read past: an M code threadcheck does not know")));
}

/// LinuxCNC's `(MSG,…)` comment and a user M code are named; the G76 is read as before (G7:
/// I, J, K are diameters): the last pass at radius 5.1 − 0.05 − 0.46, X9.18.
#[test]
fn linuxcnc_messages_and_user_m_codes_are_named() {
    let v = passes_json("linuxcnc-msg-m10.ngc");
    let last = v["passes"].as_array().unwrap().last().unwrap().clone();
    assert!((last["x_end"].as_f64().unwrap() - 9.18).abs() < 1e-9, "{last}");
    let notes = notes_of(&v);
    assert!(notes.iter().any(|n| n.contains(":6:1: (MSG,…) read past: a message")), "{notes:?}");
    assert!(notes.iter().any(|n| n.contains(":7:1: M101 read past")), "{notes:?}");
}

/// Two O-programs, the subprogram written first: the main one is O3101, which no other calls,
/// and it runs O3102's six G92 passes (the program's comments); the note says so. `--main`
/// picks one by name, and a name the file lacks is refused naming those it has.
#[test]
fn a_file_with_two_programs_runs_the_one_no_other_calls() {
    let v = passes_json("two-programs-m12.nc");
    let xs: Vec<f64> = v["passes"].as_array().unwrap().iter().map(|p| p["x_end"].as_f64().unwrap()).collect();
    assert_eq!(xs, [11.4, 11.0, 10.6, 10.2, 9.9, 9.853]);
    assert_eq!(v["operations"][0]["tool"], 5, "O3101's T0505 is in effect");
    let notes = notes_of(&v);
    assert!(
        notes.iter().any(|n| n.contains(":13:1: O3101 is the main program: the file holds 2 programs")),
        "{notes:?}"
    );
    assert!(!notes.iter().any(|n| n.contains("never called")), "{notes:?}");
    let path = data("programs/shop/two-programs-m12.nc");
    let o = run(&["passes", "--program", path.to_str().unwrap(), "--main", "O3102", "--json"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["operations"][0]["tool"], serde_json::Value::Null, "O3102 alone sets no tool");
    let o = run(&["passes", "--program", path.to_str().unwrap(), "--main", "O99"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(stderr(&o).trim(), "threadcheck: error: --main O99: the file's programs are O3102, O3101");
}

/// A program whose sizes pass: with no tool known it passes, its form unverified (issue 59);
/// given the partial insert it fails only on its form (the sharp tip's root, d3 below its
/// minimum), and the verdict says so with the options that change it.
#[test]
fn only_form_failures_with_the_partial_insert_say_so() {
    let path = data("programs/shop/partial-insert-m12.nc");
    let args = [
        "verify",
        "--program",
        path.to_str().unwrap(),
        "--thread",
        "M12x1.75-6g",
        "--blank-diameter",
        "11.9",
    ];
    let o = run(&args);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    assert!(
        stdout(&o).contains("verdict: PASS — form unverified (minor diameter d3, root radius"),
        "{}",
        stdout(&o)
    );
    let partial = [&args[..], &["--insert", "partial"]].concat();
    let o = run(&partial);
    assert_eq!(o.status.code(), Some(1));
    let out = stdout(&o);
    assert!(out.contains("verdict: FAIL (minor diameter d3, root radius) — form only, from the insert's 0.04 mm tip: --insert full cuts the standard root; --gauge-only judges the sizes and the GO gauge alone"), "{out}");
    let o = run(&[&partial[..], &["--gauge-only"]].concat());
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
}

/// G92 passes that move outward (X28.2 to X30.0) cut in a bore: an external class is refused
/// at the cycle's line, never verified as a bar.
#[test]
fn passes_that_contradict_the_designations_side_are_refused() {
    let path = data("programs/shop/internal-g92-m30.nc");
    let o = run(&["verify", "--program", path.to_str().unwrap(), "--thread", "M30x2-6g"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr(&o).trim(),
        format!(
            "threadcheck: error: {}:5:1: M30x2-6g is an external thread, but the passes of this G92 move outward pass by pass, as in a bore (X28.2000 to X30.0000): give an internal class or check the program",
            path.display()
        )
    );
    let o = run(&["verify", "--program", path.to_str().unwrap(), "--thread", "M30x2-6H"]);
    assert!(matches!(o.status.code(), Some(0 | 1)), "{}", stderr(&o));
}

/// The program turns Ø24.0 (line 8) before an M24x2-6g, whose d max is 24 − 0.038 = 23.962
/// (ISO 965-1: es = −38 µm for P2 in g): the blank is the program's, named, and the major
/// diameter fails; --blank-diameter overrides it.
#[test]
fn the_programs_own_turned_diameter_is_the_blank() {
    let (code, v) = verify_json("turned-24-m24.nc", "M24x2-6g", &[]);
    assert_eq!(code, 1);
    let d = check(&v, "major_diameter").unwrap();
    assert_eq!(d["max"], 23.962);
    assert!(!d["ok"].as_bool().unwrap(), "{d}");
    assert!(d["value"].as_f64().unwrap() > 23.99, "{d}");
    let notes: Vec<&str> = v["notes"].as_array().unwrap().iter().map(|n| n.as_str().unwrap()).collect();
    assert!(
        notes.iter().any(|n| n.contains("turned-24-m24.nc:8:1: the blank is the program's own: Ø24.0000")),
        "{notes:?}"
    );
    let (_, v) = verify_json("turned-24-m24.nc", "M24x2-6g", &["--blank-diameter", "23.8"]);
    let d = check(&v, "major_diameter").unwrap();
    assert!(d["ok"].as_bool().unwrap(), "{d}");
    assert!((d["value"].as_f64().unwrap() - 23.8).abs() < 1e-3, "{d}");
}

/// ASME B1.1 writes `1/2-13 UNC-2A`; a hyphen where the blank stands is read as the blank.
#[test]
fn a_unified_designation_with_a_hyphen_before_the_series_is_read() {
    let o = run(&["limits", "1/2-13-UNC-2A", "--json"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    // 13 tpi: P = 25.4/13 mm.
    assert!((v["pitch"].as_f64().unwrap() - 25.4 / 13.0).abs() < 1e-9, "{v}");
    assert_eq!(v["external"]["class"], "2A");
}

/// M20xPh5P2.5: two G76 cycles 2.5 mm apart along Z (the program's comments) are one thread of
/// two starts, which passes, `starts` included. Written 0.127 mm larger (X16.933), its
/// correction changes both cycles' X alike, and the corrected program re-verifies
/// mid-tolerance. The same program with one cycle fails `starts`, naming start 2, and offers no
/// correction.
#[test]
fn a_two_start_thread_cut_by_two_shifted_cycles_is_one_operation() {
    let (code, v) = verify_json("two-start-m20-ph5.nc", "M20xPh5P2.5-6g", &[]);
    assert_eq!(code, 0, "{v}");
    let s = check(&v, "starts").unwrap();
    assert!(s["ok"].as_bool().unwrap(), "{s}");
    assert_eq!(s["value"], 2.0);
    let passes = v["passes"].as_array().unwrap();
    assert_eq!(passes.iter().filter(|p| p["start"] == 1).count(), passes.len() / 2);

    let dir = tempdir("two-start-fix");
    let off = dir.join("off.nc");
    let text = std::fs::read_to_string(data("programs/shop/two-start-m20-ph5.nc")).unwrap();
    std::fs::write(&off, text.replace("G76 X16.806", "G76 X16.933")).unwrap();
    let args =
        ["verify", "--program", off.to_str().unwrap(), "--thread", "M20xPh5P2.5-6g", "--insert", "full"];
    let o = run(&[&args[..], &["--json", "-"]].concat());
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let c = &v["operations"][0]["correction"];
    assert_eq!((c["line"].as_u64(), c["also"][0]["line"].as_u64()), (Some(15), Some(18)), "{c}");
    let fixed = stdout(&run(&[&args[..], &["--fix", "-"]].concat()));
    let new = format!("G76 X{} Z-30", c["value"].as_f64().unwrap());
    assert_eq!(fixed.matches(&new).count(), 2, "{fixed}");
    let out = dir.join("fixed.nc");
    std::fs::write(&out, &fixed).unwrap();
    let o = run(&[
        "verify",
        "--program",
        out.to_str().unwrap(),
        "--thread",
        "M20xPh5P2.5-6g",
        "--insert",
        "full",
        "--json",
        "-",
    ]);
    let v2: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let d2 = check(&v2["operations"][0], "pitch_diameter").unwrap();
    let mid = 0.5 * (d2["min"].as_f64().unwrap() + d2["max"].as_f64().unwrap());
    assert!((d2["value"].as_f64().unwrap() - mid).abs() < 0.005, "{d2}");

    let (code, v) = verify_json("one-start-m20-ph5.nc", "M20xPh5P2.5-6g", &[]);
    assert_eq!(code, 1);
    let s = check(&v, "starts").unwrap();
    assert!(!s["ok"].as_bool().unwrap());
    assert_eq!(s["note"], "1 of 2 starts cut; missing: start 2 (2.5000 mm along Z from start 1)");
    assert!(v["correction"].is_null() && v["suggested_final_x"].is_null(), "{v}");
}

/// The thesis's three-start G33 passes (Z6, Z8, Z10 for a lead of 6) are starts 1, 2 and 3,
/// three passes each; none is noted as cutting nothing.
#[test]
fn passes_written_one_by_one_show_their_start() {
    let path = data("programs/source-docs/thesis-g33-three-start.mpf");
    let o = run(&["passes", "--program", path.to_str().unwrap(), "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let starts: Vec<u64> =
        v["passes"].as_array().unwrap().iter().map(|p| p["start"].as_u64().unwrap()).collect();
    assert_eq!(starts, [0, 0, 0, 1, 1, 1, 2, 2, 2]);
    assert!(v["operations"][0]["notes"]
        .as_array()
        .unwrap()
        .iter()
        .all(|n| !n.as_str().unwrap().contains("cuts nothing")));
}
