//! Issue 47, lathes as shops write them (round 2): the blank the thread is cut into, subprograms
//! in files beside the program, Haas's live tapping.

use crate::*;

/// Verifies a Fanuc lathe program's text with a full-profile insert; the report's text.
fn verify_text(name: &str, text: &str) -> (i32, String) {
    let dir = tempdir("lathes");
    std::fs::write(dir.join(name), text).unwrap();
    let o = run_in(&dir, &["verify", "--program", name, "--insert", "full"]);
    (o.status.code().unwrap(), stdout(&o))
}

/// The M24x2 thread of these programs: the shaft's G76 (last pass X21.423: a full-profile insert
/// leaves d2 22.578, inside 6g's 22.493 … 22.663, ISO 965-1), cut into whatever the lines above
/// it left.
const THREAD: &str = "G0 X40 Z50\nT0202\nG97 S700 M3\nG0 X26 Z5\nG76 P010060 Q100 R0.05\nG76 X21.423 Z-30 P1289 Q350 F2.0\nG0 X100 Z100\nM30\n%\n";

/// Issue 47 item 1: the blank is the material the moves leave, never an air move. The bar is
/// turned to Ø23.9 (line 8, inside 6g's major diameter 23.682 … 23.962); a feed along the part
/// at X28 afterwards (line 12) cuts air. The thread is cut into Ø23.9 and passes; the air move
/// at Ø28 as its blank would put d at 28, far over 23.962.
#[test]
fn an_air_move_after_the_part_was_turned_smaller_is_not_the_blank() {
    let text = format!(
        "%\nO4701 (M24X2 THREAD)\nG21 G18 G99\nT0101\nG97 S800 M3\nG0 X30 Z2\nG1 X23.9 F0.2\nG1 Z-32\nG0 X30\nG0 Z2\nG1 X28 F0.3\nG1 Z-32\n{THREAD}"
    );
    let (code, out) = verify_text("air.nc", &text);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("blank X23.9000, final X21.4230"), "{out}");
    assert!(out.contains("air.nc:8:1: the blank is the program's own: Ø23.9000"), "{out}");
}

/// A box cut (G90 X26, line 7) turned away by the roughing cycle after it, whose profile
/// (N100–N200, read as the finished contour) turns Ø23.9 at line 12: the thread's blank is 23.9.
#[test]
fn a_box_cut_turned_away_by_a_later_roughing_cycle_is_not_the_blank() {
    let text = format!(
        "%\nO4702 (M24X2 THREAD)\nG21 G18 G99\nT0101\nG97 S800 M3\nG0 X32 Z2\nG90 X26 Z-32 F0.25\nG0 X32 Z2\nG71 U1.5 R0.5\nG71 P100 Q200 U0.4 W0.1 F0.25\nN100 G0 X23.9\nG1 Z-32\nN200 G1 X32\nG70 P100 Q200\n{THREAD}"
    );
    let (code, out) = verify_text("rough.nc", &text);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("rough.nc:12:1: the blank is the program's own: Ø23.9000"), "{out}");
}

/// A journal (Ø23.9 from Z2 to Z-12, line 8) shorter than the pass, whose long run-in starts at
/// Z8: the middle half of the pass (Z+3 … −7) runs off the journal, the journal is still the
/// blank.
#[test]
fn a_journal_under_a_long_run_in_is_the_blank() {
    let text = "%\nO4703 (M24X2 THREAD)\nG21 G18 G99\nT0101\nG97 S800 M3\nG0 X30 Z2\nG1 X23.9 F0.2\nG1 Z-12\nG1 X30\nG0 X40 Z50\nT0202\nG97 S700 M3\nG0 X26 Z8\nG76 P010060 Q100 R0.05\nG76 X21.423 Z-12 P1289 Q350 F2.0\nG0 X100 Z100\nM30\n%\n";
    let (code, out) = verify_text("journal.nc", text);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("journal.nc:8:1: the blank is the program's own: Ø23.9000"), "{out}");
}

/// "Nothing is cut" names the blank's diameter and where it came from: the part turned to
/// Ø20 at line 8 is under the thread's crest, so the G76's passes (deepest X21.423) miss it.
#[test]
fn nothing_is_cut_names_the_blank_and_its_line() {
    let text = format!(
        "%\nO4704 (M24X2 THREAD)\nG21 G18 G99\nT0101\nG97 S800 M3\nG0 X30 Z2\nG1 X20 F0.2\nG1 Z-32\nG0 X30\n{THREAD}"
    );
    let (code, out) = verify_text("small.nc", &text);
    assert_eq!(code, 1, "{out}");
    assert!(
        out.contains("no pass reaches the blank Ø20.0000: the deepest pass is at X21.4230, so nothing is cut (is the blank diameter or the thread wrong?); the blank the program's moves leave, turned at line 8"),
        "{out}"
    );
}

/// A Haas lathe program tapping M8x1.25 on the face after its Ø6.8 drill (ISO 2306's tap
/// drill), the main spindle stopped (M5) before the tap; `code` is the tapping block.
fn haas_tap(code: &str, tap: &str) -> String {
    format!(
        "%\nO4705 (HAAS LATHE: TAP ON THE FACE)\nG21 G18 G99\nT505 (DRILL 6.8)\nG97 S1200 M3\nG0 X0 Z5\nG83 Z-20 R2 Q4000 F0.1\nG80\nM5\nG0 X100 Z100\nT606 (TAP {tap})\nG97 S400\nG0 X0 Z8\n{code}\nG80\nG0 X100 Z100\nM30\n%\n"
    )
}

/// Issue 47 item 8, Haas lathe tapping as Haas documents it (the G84 page, HAAS-L84 in
/// ../shared/notes/machining-centres.md §7): the control starts the spindle for G84 (clockwise)
/// and G184 (counter-clockwise, a left-hand tap) itself, so a stopped spindle passes; G95 and G186
/// tap with a live tool (right- and left-hand), which the control turns itself; G195/G196 tap
/// along X, placed by Z and C: one with no C known is refused at its line. F1.25 in G99 is the
/// lead.
#[test]
fn haas_lathe_tapping_cycles_start_their_own_spindle() {
    let dir = tempdir("haas-tap");
    for (code, tap, hand_note) in [
        ("G84 Z-14 R5 F1.25", "M8X1.25", "starts the spindle clockwise for G84 itself"),
        ("G184 Z-14 R5 F1.25", "M8X1.25LH", "starts the spindle counter-clockwise for G184 itself"),
        ("G95 Z-14 R5 F1.25", "M8X1.25", "G95 is the Haas lathe's live-tool rigid tapping: the control turns the live tool clockwise"),
        ("G186 Z-14 R5 F1.25", "M8X1.25LH", "G186 is the Haas lathe's live-tool rigid tapping: the control turns the live tool counter-clockwise"),
    ] {
        std::fs::write(dir.join("tap.nc"), haas_tap(code, tap)).unwrap();
        let o = run_in(&dir, &["verify", "--program", "tap.nc", "--dialect", "haas"]);
        assert_eq!(o.status.code(), Some(0), "{code}: {}{}", stdout(&o), stderr(&o));
        assert!(stdout(&o).contains(hand_note), "{code}: {}", stdout(&o));
        assert!(stdout(&o).contains("tapped"), "{code}");
    }
    // A right-hand tap under G184 turns the wrong way.
    std::fs::write(dir.join("tap.nc"), haas_tap("G184 Z-14 R5 F1.25", "M8X1.25")).unwrap();
    let o = run_in(&dir, &["verify", "--program", "tap.nc", "--dialect", "haas"]);
    assert_eq!(o.status.code(), Some(1), "{}", stdout(&o));
    std::fs::write(dir.join("tap.nc"), haas_tap("G195 X10 R15 F1.25", "M8X1.25")).unwrap();
    let o = run_in(&dir, &["verify", "--program", "tap.nc", "--dialect", "haas"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        one_line_error(&o),
        "threadcheck: error: tap.nc:14:1: G195 makes a radial hole with a live tool: its Z and C (the spindle's angle) place it, and C is not known here"
    );
}

/// A nose turned at the part's tip (Ø4 for 0.5 mm, line 8) and a taper up from it: the only
/// cylinder under the pass runs along 0.5 of its 25 mm, far under a quarter, so it is not the
/// blank (the thread would cut nothing into Ø4); the program turns no diameter for the thread and
/// the default blank stands, as without the nose.
#[test]
fn a_nose_at_the_tip_is_not_the_blank() {
    let nose = "%\nO4706 (M10X1.5 THREAD)\nG21 G18 G99\nT0101\nG97 S800 M3\nG0 X12 Z2\nG1 X4 Z0 F0.1\nG1 Z-0.5\nG1 X9.85 Z-3\nG0 X20\nG0 X40 Z50\nT0202\nG97 S700 M3\nG0 X12 Z5\nG76 P010060 Q100 R0.05\nG76 X8.16 Z-20 P920 Q300 F1.5\nG0 X100 Z100\nM30\n%\n";
    let (code, out) = verify_text("nose.nc", nose);
    assert!(!out.contains("the blank is the program's own"), "{out}");
    assert!(!out.contains("no cut"), "{out}");
    let plain = nose.replace("G1 X4 Z0 F0.1\nG1 Z-0.5\nG1 X9.85 Z-3\nG0 X20\n", "");
    let (plain_code, plain_out) = verify_text("plain.nc", &plain);
    assert_eq!(code, plain_code);
    let blank = |o: &str| o.lines().find(|l| l.starts_with("blank X")).map(str::to_string);
    assert_eq!(blank(&out), blank(&plain_out));
}

/// Issue 47 item 5, subprograms where the control finds them. A LinuxCNC program calls
/// `o<thr>`, whose file `thr.ngc` stands in a library folder (`--subroutine-path lib`); the
/// library's preview lines begin with `/` and end in `/ o<thr> return`. With the block-delete
/// switch off (the default, said) the return runs before the G76, so the program makes no thread,
/// and the refusal names the library's line; with `--block-delete` the G76 runs: its depth
/// `#1 · (1 + #<_lathe_radius_mode>)` = 1.84 in G7 (diameter) puts the root at 9.85 − 1.84 =
/// X8.01, inside 6g's d3 (ISO 965-1), and the operation is named by its file. Without the path
/// the call is refused at its line.
#[test]
fn a_linuxcnc_subroutine_library_in_another_folder() {
    let dir = tempdir("sub-library");
    std::fs::create_dir_all(dir.join("lib")).unwrap();
    std::fs::write(
        dir.join("main.ngc"),
        "(M10X1.5 THREAD)\nG7 G18 G21 G90\nS500 M3\nG0 X9.85 Z2\nG1 Z-25 F0.1\nG0 X12 Z2\no<thr> call [1.84]\nG0 X20 Z20\nM2\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("lib/thr.ngc"),
        "o<thr> sub\n/ G0 X30 Z30 (preview)\n/ o<thr> return\n#<depth> = [#1 * [1 + #<_lathe_radius_mode>]]\nG76 P1.5 Z-20 I-2.15 J0.05 K#<depth> Q29.5 R1.5 H1 E0 L0\no<thr> endsub\n",
    )
    .unwrap();
    let args = ["verify", "--program", "main.ngc", "--insert", "full", "--subroutine-path", "lib"];
    let o = run_in(&dir, &args);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        one_line_error(&o).ends_with("lib/thr.ngc:2: 2 blocks begin with / (block delete): the control's switch is taken as off, so they run (--block-delete skips them)"),
        "{}",
        one_line_error(&o)
    );
    let o = run_in(&dir, &[&args[..], &["--block-delete"]].concat());
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("== operation 1 of 1: G76 at line 5 of lib/thr.ngc"), "{out}");
    assert!(out.contains("blank X9.8500, final X8.0100"), "{out}");
    assert!(
        out.contains(
            "note: subprograms read from files beside the program, where the control finds them: lib/thr.ngc"
        ),
        "{out}"
    );
    let o = run_in(&dir, &["verify", "--program", "main.ngc", "--insert", "full"]);
    assert_eq!(
        one_line_error(&o),
        "threadcheck: error: main.ngc:7:1: o<thr> call: no o<thr> sub in this file, nor its file where the control looks (the program's folder and --subroutine-path, for a program read from a file)"
    );
}

/// A Fanuc program's `M98 P2000` finds O2000 in the file of that number beside it (`O2000.nc`,
/// or `2000` without an extension and without its O line); the thread it cuts (the shaft's
/// M24x2 G76, last pass X21.423) is checked against the main program's comment, and a run of
/// many places its lines in the subprogram's file.
#[test]
fn m98_finds_its_subprogram_in_the_file_of_its_number() {
    let dir = tempdir("sub-m98");
    let main = "%\nO1000 (M24X2-6G THREAD)\nG21 G18 G99\nT0101\nG97 S800 M3\nG0 X30 Z2\nG1 X23.9 F0.2\nG1 Z-32\nG0 X40 Z50\nM98 P2000\nG0 X100 Z100\nM30\n%\n";
    let sub =
        "T0202\nG97 S700 M3\nG0 X26 Z5\nG76 P010060 Q100 R0.05\nG76 X21.423 Z-30 P1289 Q350 F2.0\nM99\n";
    std::fs::write(dir.join("o1000.nc"), main).unwrap();
    std::fs::write(dir.join("O2000.nc"), format!("%\nO2000\n{sub}%\n")).unwrap();
    let o = run_in(&dir, &["verify", "--program", "o1000.nc", "--insert", "full"]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    assert!(stdout(&o).contains("G76 at line 7 of O2000.nc, tool T2"), "{}", stdout(&o));
    assert!(stdout(&o).contains("M24X2-6g: named by the comment at line 2"), "{}", stdout(&o));
    std::fs::remove_file(dir.join("O2000.nc")).unwrap();
    std::fs::write(dir.join("2000"), sub).unwrap();
    let o = run_in(&dir, &["verify", "o1000.nc"]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "the full-profile insert assumed, its form unverified: {}",
        stdout(&o)
    );
    assert!(stdout(&o).starts_with("2000:5: PASS turned M24X2-6g (comment)"), "{}", stdout(&o));
}

/// Sinumerik: `L9` alone on a line of the main program calls L9 (regression: it was read as the
/// start of subprogram L9, so the call never ran and the program was said to define L9 without
/// calling it), found in `L9.SPF` beside the program; after M30 the same line still starts a
/// subprogram of the listing.
#[test]
fn a_sinumerik_call_finds_its_spf_file() {
    let dir = tempdir("sub-spf");
    std::fs::write(dir.join("MAIN.MPF"), "G18 G90 G95\nT1 D1\nS500 M3\nG0 X12 Z2\nL9\nM30\n").unwrap();
    std::fs::write(dir.join("L9.SPF"), "G0 X12 Z2\nG33 Z-20 K1.5 X8.4\nM17\n").unwrap();
    let o = run_in(&dir, &["passes", "--program", "MAIN.MPF"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stdout(&o).contains("operation 1: G33 at line 2 of L9.SPF"), "{}", stdout(&o));
    // The same subprogram in the listing after M30.
    std::fs::remove_file(dir.join("L9.SPF")).unwrap();
    std::fs::write(
        dir.join("ONE.MPF"),
        "G18 G90 G95\nT1 D1\nS500 M3\nG0 X12 Z2\nL9\nM30\nL9\nG0 X12 Z2\nG33 Z-20 K1.5 X8.4\nM17\n",
    )
    .unwrap();
    let o = run_in(&dir, &["passes", "--program", "ONE.MPF"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stdout(&o).contains("operation 1: G33 at line 9, tool T1"), "{}", stdout(&o));
    let o = run_in(&dir, &["passes", "--program", "MAIN.MPF"]);
    assert_eq!(
        one_line_error(&o),
        "threadcheck: error: MAIN.MPF:5:1: subprogram L9 is not in this file, nor its file L9.SPF beside it (for a program read from a file)"
    );
}

/// Sinumerik subprograms called by a name of letters (`THRSUB`): found in `THRSUB.SPF` beside the
/// program (its `PROC THRSUB SAVE` line names it), in the listing after M30 (`%_N_THRSUB_SPF` or
/// the name alone on its line), repeated by `P`. Regression: such a call was read past silently,
/// so the thread in the subprogram was never seen. A bare word that names no subprogram (`SOFT`)
/// is read past with a note naming it.
#[test]
fn a_sinumerik_call_by_name_finds_its_subprogram() {
    let dir = tempdir("sub-named");
    let main = "G18 G90 G95 DIAMON\nT1 D1\nS500 M3\nSOFT\nG0 X12 Z2\nTHRSUB P2\nM30\n";
    std::fs::write(dir.join("MAIN.MPF"), main).unwrap();
    std::fs::write(dir.join("thrsub.spf"), "PROC THRSUB SAVE\nG0 X12 Z2\nG33 Z-20 K1.5 X8.4\nM17\n").unwrap();
    let o = run_in(&dir, &["passes", "--program", "MAIN.MPF"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("operation 1: G33 at line 3 of thrsub.spf"), "{out}");
    let o = run_in(&dir, &["passes", "--json", "--program", "MAIN.MPF"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    // P2: the subprogram runs twice, so its one G33 is two passes at X8.4.
    let passes = v["operations"][0]["passes"].as_array().unwrap();
    assert_eq!(passes.len(), 2, "{v}");
    for p in passes {
        assert!((p["x_end"].as_f64().unwrap() - 8.4).abs() < 1e-9, "{p}");
    }
    let o = run_in(&dir, &["verify", "--program", "MAIN.MPF", "--thread", "M12x1.5-6g"]);
    assert!(
        stdout(&o).contains("MAIN.MPF:4:1: SOFT read past: a word threadcheck does not model"),
        "{}",
        stdout(&o)
    );
    // The listing's two forms of a subprogram after the main program.
    std::fs::remove_file(dir.join("thrsub.spf")).unwrap();
    for head in ["%_N_THRSUB_SPF", "THRSUB"] {
        std::fs::write(dir.join("ONE.MPF"), format!("{main}{head}\nG0 X12 Z2\nG33 Z-20 K1.5 X8.4\nM17\n"))
            .unwrap();
        let o = run_in(&dir, &["passes", "--program", "ONE.MPF"]);
        assert_eq!(o.status.code(), Some(0), "{head}: {}", stderr(&o));
        assert!(stdout(&o).contains("operation 1: G33 at line 10, tool T1"), "{head}: {}", stdout(&o));
    }
    // Without the file: no thread, and the call named in the notes.
    let o = run_in(&dir, &["verify", "--program", "MAIN.MPF", "--thread", "M12x1.5-6g"]);
    assert_eq!(o.status.code(), Some(2), "{}", stdout(&o));
    std::fs::write(dir.join("P.MPF"), "PROC THRSUB(REAL DEPTH)\nM17\n").unwrap();
    let o = run_in(&dir, &["passes", "--program", "P.MPF"]);
    assert_eq!(
        one_line_error(&o),
        "threadcheck: error: P.MPF:1:12: PROC THRSUB(…): a subprogram with parameters is not supported (one without is)"
    );
}

/// LinuxCNC's stored parameters (#5161–#5390: the homes, G92 and the work offsets) live in the
/// machine's parameter file: read unset, they are a fresh file's 0 (as `rs274` reads them), and
/// the note says where the value really comes from, not that LinuxCNC reads it as 0.
#[test]
fn linuxcnc_stored_parameters_are_named_as_such() {
    let dir = tempdir("stored-params");
    std::fs::write(
        dir.join("st.ngc"),
        "G21 G18 G7\n#1=#5221\n#2=#100\nS500 M3\nG0 X12 Z2\nG76 P1.5 Z-20 I-1 J0.2 K0.92 R2 Q29.5 L0 E0 H0\nM2\n",
    )
    .unwrap();
    let o = run_in(&dir, &["passes", "--program", "st.ngc"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("note: st.ngc:2:1: #5221 is one of LinuxCNC's stored parameters (a home position, the G92 or a work offset), kept in the machine's parameter file: threadcheck reads it as 0, a fresh file's value (rs274's)"), "{out}");
    assert!(out.contains("note: st.ngc:3:1: #100 is read before it is set: LinuxCNC reads it as 0"), "{out}");
}

/// LinuxCNC reads lines of at most 254 bytes (LINELEN 255, `src/emc/linuxcnc.h`): a longer one is
/// refused at its column 255, as LinuxCNC refuses it ("Command too long"), and a line of 254 is read.
#[test]
fn a_linuxcnc_line_longer_than_linuxcnc_reads_is_refused() {
    let dir = tempdir("linelen");
    let pad = |n: usize| format!("#<p> = [{}1]", "0+".repeat((n - 10) / 2));
    assert_eq!(pad(254).len(), 254);
    for (n, ok) in [(254, true), (256, false)] {
        let line = pad(n);
        let text = format!(
            "G21 G18 G7\n{line}\nS500 M3\nG0 X12 Z2\nG76 P1.5 Z-20 I-1 J0.2 K0.92 R2 Q29.5 L0 E0 H0\nM2\n"
        );
        std::fs::write(dir.join("l.ngc"), text).unwrap();
        let o = run_in(&dir, &["passes", "--program", "l.ngc"]);
        if ok {
            assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        } else {
            assert_eq!(
                one_line_error(&o),
                format!("threadcheck: error: l.ngc:2:255: the line is {n} bytes long: LinuxCNC reads lines of at most 254 (Command too long)")
            );
        }
    }
}

/// Issue 61 item 4: a Fanuc lathe program that writes `G28 G91 X0 Z0` (a reference return) and
/// cuts with G32 is read in G-code system A, G32 its thread cutting (systems B and C write G33),
/// the G91 read past with a note naming both lines: it was taken for system B on the G91 alone
/// and the G32 dropped ("no threading pass"). Hand-derived: three passes at X19.4, X19.1, X18.9
/// from Z3 to Z-20, lead 1.5. Read as system B when told, the G32 is refused at its place.
#[test]
fn a_g91_reference_return_does_not_turn_a_g32_program_into_system_b() {
    let dir = tempdir("g28-g91-g32");
    let program = "O0061 (M20X1.5)\nG18 G21 G40\nG28 G91 X0 Z0\nG90\nT0101 M3 S500\nG0 X24 Z3\nX19.4\nG32 Z-20 F1.5\nG0 X24\nZ3\nX19.1\nG32 Z-20 F1.5\nG0 X24\nZ3\nX18.9\nG32 Z-20 F1.5\nG0 X24\nZ3\nG28 G91 X0 Z0\nM30\n";
    std::fs::write(dir.join("g32.nc"), program).unwrap();
    let o = run_in(&dir, &["passes", "--program", "g32.nc", "--json", "-"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let ops = v["operations"].as_array().unwrap();
    let passes: Vec<(f64, f64, f64)> = ops
        .iter()
        .flat_map(|op| op["passes"].as_array().unwrap().clone())
        .map(|p| {
            (p["x_start"].as_f64().unwrap(), p["z_start"].as_f64().unwrap(), p["z_end"].as_f64().unwrap())
        })
        .collect();
    assert_eq!(passes, vec![(19.4, 3.0, -20.0), (19.1, 3.0, -20.0), (18.9, 3.0, -20.0)], "{v}");
    let notes = v.to_string();
    assert!(
        notes.contains(
            "line 3:5 writes G91, which Fanuc G-code system A does not have, but line 8:1 writes G32"
        ),
        "{notes}"
    );
    let o = run_in(&dir, &["passes", "--program", "g32.nc", "--gcode-system", "b"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).starts_with("threadcheck: error: g32.nc:8:1: G32 is thread cutting in Fanuc G-code system A; this program is read in system B"), "{}", stderr(&o));
}

/// Issue 61 item 1: a turret lathe that indexes with `T0707 M06` (Denford's Fanuc-style
/// controls) is a lathe: the four-digit T word (station and offset) decides, not the M6 (it was
/// read as a mill-turn, its G76 a fine-boring cycle: "no thread-making operation"); the tool word
/// is named as written. Hand-derived: G70/G71 finish the journal to Ø20 over Z0…−25 (line 9),
/// the blank of the G76 (X16.933, P1534: an M20x2.5).
#[test]
fn a_turret_lathe_that_indexes_with_m06_is_a_lathe() {
    let dir = tempdir("t0707-m06");
    let program = "(M20X2.5)\nG21 G40 G99\nT0101 M06\nG97 S1500 M03\nG00 X32 Z2\nG71 U1 R0.5\nG71 P10 Q20 U0.2 W0.1 F0.2\nN10 G00 X20\nG01 Z-25 F0.1\nX30\nN20 Z-40\nG70 P10 Q20\nG28 U0 W0\nT0707 M06\nG97 S600 M03\nG00 X22 Z5\nG76 P010060 Q100 R0.05\nG76 X16.933 Z-20 P1534 Q400 F2.5\nG28 U0 W0\nM30\n";
    std::fs::write(dir.join("denford.nc"), program).unwrap();
    let o = run_in(&dir, &["verify", "--program", "denford.nc", "--insert", "full", "--json", "-"]);
    let v: serde_json::Value =
        serde_json::from_slice(&o.stdout).unwrap_or_else(|e| panic!("{e}: {}", stderr(&o)));
    assert_eq!(v["machine"]["reason"], "read as a lathe: line 3 writes T0101 M06, a turret station and its offset (--machine-type chooses otherwise)");
    let op = &v["operations"][0];
    assert_eq!(op["made"], "turned", "{op}");
    assert_eq!(op["plan"]["blank_diameter"], 20.0, "{op}");
    assert_eq!(op["plan"]["final_x"], 16.933, "{op}");
    // The user's word, lathe, is taken without a refusal.
    let o =
        run_in(&dir, &["verify", "--program", "denford.nc", "--insert", "full", "--machine-type", "lathe"]);
    assert!(matches!(o.status.code(), Some(0 | 1)), "{}", stderr(&o));
}

/// Issue 61 item 3: an internal M30x1.5 in a part turned outside to Ø48, drilled on the axis
/// and bored to Ø28.4: its bore is the Ø28.4 the boring bar leaves (line 15), never the outside
/// Ø48 (it was taken, and the thread got "no cut") nor the drill's path on the axis.
#[test]
fn an_internal_thread_s_bore_is_the_bored_diameter() {
    let dir = tempdir("bore");
    let program = "(M30X1.5-6H)\nG18 G21 G40 G99\nT0101\nG97 S800 M3\nG0 X50 Z2\nG1 X48 F0.2\nZ-40\nG0 X60 Z2\nT0202\nG0 X0 Z5\nG1 Z-40 F0.1\nG0 Z5\nT0303\nG0 X28.4 Z2\nG1 Z-30 F0.1\nG0 X26 Z5\nT0404\nG0 X27 Z5\nG76 P010060 Q100 R0.05\nG76 X30 Z-25 P812 Q250 F1.5\nG0 Z50\nM30\n";
    std::fs::write(dir.join("bore.nc"), program).unwrap();
    let o =
        run_in(&dir, &["verify", "--program", "bore.nc", "--insert", "full", "--internal", "--json", "-"]);
    let v: serde_json::Value =
        serde_json::from_slice(&o.stdout).unwrap_or_else(|e| panic!("{e}: {}", stderr(&o)));
    let op = &v["operations"][0];
    assert_eq!(op["plan"]["blank_diameter"], 28.4, "{op}");
    assert!(v.to_string().contains("bore.nc:15:1: the bore is the program's own: Ø28.4000"), "{v}");
}

/// Issue 61 item 3: a Swiss-type part at negative X with a collar (Ø24 from Z-20) in the
/// run-out of a thread that ends at Z-20.2: the last pass runs into the collar, so the run-out
/// check fails, naming X24 at Z-20.95 against the thread's X20 (half a pitch beyond the end). It
/// compared the negative turned X with a positive thread X and passed.
#[test]
fn a_negative_x_collar_in_the_run_out_fails() {
    let dir = tempdir("swiss");
    let program = "(M20X1.5-6G SWISS)\nG18 G21 G99\nT0101\nG97 S1000 M3\nG0 X-26 Z2\nG1 X-20 F0.1\nZ-20\nX-24\nZ-30\nG0 X-30 Z2\nT0202\nG0 X-22 Z5\nG76 P010060 Q100 R0.05\nG76 X-18.16 Z-20.2 P920 Q300 F1.5\nG0 X-30 Z50\nM30\n";
    std::fs::write(dir.join("swiss.nc"), program).unwrap();
    let o = run_in(&dir, &["verify", "--program", "swiss.nc", "--insert", "full"]);
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert_eq!(o.status.code(), Some(1), "{out}{}", stderr(&o));
    assert!(out.contains("the last pass ends at Z-20.200, but the turned contour stands at X24.000 at Z-20.950, above the thread's X20.000"), "{out}");
}

/// Issue 61 item 2: on a lathe-based mill-turn read in Fanuc G-code system A, G98/G99 stay the
/// feed modes in the live tool's G17 section (F0i-CON: "G98 and G99 are modal … feed per minute,
/// feed per revolution"): `G17 G98` then `G84 … F750` at S600 taps M8x1.25 at F = S·P =
/// 600 × 1.25 = 750 mm/min, which passes. It was read as feed per revolution (G98 a return
/// level) and failed by +748 750 µm.
#[test]
fn a_live_tool_s_g98_is_feed_per_minute_in_system_a() {
    let dir = tempdir("live-g98");
    let program = "(M8X1.25 LIVE TAP)\nG18 G21 G99\nT0101\nG97 S800 M3\nG0 X30 Z2\nG1 X24 F0.1\nZ-20\nG0 X40 Z5\nT0505 (DRILL 6.8)\nG17 G98\nM45 S1200\nG0 X0 Y0 Z5\nG81 Z-15 R2 F120\nG80\nT0606 (TAP M8X1.25)\nG17 G98\nS600\nG0 X0 Y0 Z5\nG84 Z-12 R2 F750\nG80\nG18\nM30\n";
    std::fs::write(dir.join("live.nc"), program).unwrap();
    let o = run_in(&dir, &["verify", "--program", "live.nc"]);
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert_eq!(o.status.code(), Some(0), "{out}{}", stderr(&o));
    assert!(out.contains("mm/min; feed per minute: F must be S × lead = 600 × 1.25"), "{out}");
}

/// Issue 61 item 3: a G71 roughing cycle's profile written in modal G00 (`N10 G00 X26` and the
/// blocks after it give no G01) is the contour the roughing and the G70 cut: the blank of the
/// M30x1.5 that follows is its Ø29.9 cylinder at line 13 (Z-2 to Z-30), not the Ø44 box cut at
/// line 7 (which then failed the first pass: "ends inside the blank"). A full-profile tip at
/// X28.06 leaves d2 = 28.06 + 0.57735·1.5 = 28.926, inside 6g's
/// 28.844–28.994 (ISO 965-1: d2 29.026, es −32, Td2 150 µm).
#[test]
fn a_roughing_profile_written_in_g00_is_the_turned_contour() {
    let dir = tempdir("g00-profile");
    let program = "(M30X1.5-6G)\nG21 G40 G99\nT0101\nG96 S180 M3\nG50 S2500\nG0 X52 Z2\nG90 X44 Z-45 F0.25\nG71 U1.5 R0.5\nG71 P10 Q20 U0.4 W0.1 F0.25\nN10 G0 X26\nZ0\nX29.9 Z-2\nZ-30\nX40\nZ-45\nN20 X52\nG70 P10 Q20 F0.1\nG0 X100 Z100\nT0303\nG97 S800 M3\nG0 X32 Z5\nG76 P010060 Q50 R0.05\nG76 X28.06 Z-26 P970 Q400 F1.5\nG0 X100 Z100\nM30\n";
    std::fs::write(dir.join("profile.nc"), program).unwrap();
    let o = run_in(&dir, &["verify", "--program", "profile.nc", "--insert", "full", "--json", "-"]);
    let v: serde_json::Value =
        serde_json::from_slice(&o.stdout).unwrap_or_else(|e| panic!("{e}: {}", stderr(&o)));
    let op = &v["operations"][0];
    assert_eq!(op["plan"]["blank_diameter"], 29.9, "{op}");
    assert!(v.to_string().contains("profile.nc:13:1"), "{v}");
    assert_eq!(v["verdict"], "pass", "{v}");
}

/// Issue 61 item 1: a lathe's live tool milling a face in polar coordinate interpolation
/// (G12.1 … G13.1, Fanuc's F0i-TF; G112 … G113 as also written) is a milling section: the program
/// is a mill-turn's (line 2's G18 and line 12's G12.1 named), the moves under it are read past
/// by name, not as turning (a face move to X-20 at Z-3 is no diameter), the X after G13.1 is
/// unknown until given, and the thread after it is turned as written. A G76 under G12.1 is
/// refused at its place: the control cuts no thread there.
#[test]
fn polar_interpolation_is_a_milling_section_read_past() {
    let dir = tempdir("polar");
    let program = |inside: &str| {
        format!("(M20X1.5-6G)\nG18 G21 G99\nT0101\nG97 S800 M3\nG0 X22 Z2\nG1 X19.9 F0.1\nZ-25\nG0 X30 Z5\nT0505\nG98\nG0 X40 C0 Z2\nG112\nG1 Z-3 F100\nX20 C5.77\nX-20 C5.77\n{inside}G113\nG0 Z5\nG18 G99\nT0303\nG97 S700 M3\nG0 X22 Z5\nG76 P010060 Q100 R0.05\nG76 X18.06 Z-20 P970 Q300 F1.5\nG0 X40 Z50\nM30\n")
    };
    std::fs::write(dir.join("polar.nc"), program("")).unwrap();
    let o = run_in(&dir, &["verify", "--program", "polar.nc", "--insert", "full"]);
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert_eq!(o.status.code(), Some(0), "{out}{}", stderr(&o));
    assert!(
        out.contains("read as a mill-turn: line 2 writes G18, the turning plane and line 12 writes G112"),
        "{out}"
    );
    assert!(out.contains("polar.nc:12:1: G112 read past: polar coordinate interpolation"), "{out}");
    assert!(out.contains("polar.nc:13:1: moves under G12.1 read past (3 times)"), "{out}");
    assert!(out.contains("blank X19.9000, final X18.0600"), "{out}");
    std::fs::write(dir.join("inside.nc"), program("G76 X18.06 Z-20 P970 Q300 F1.5\n")).unwrap();
    let o = run_in(&dir, &["verify", "--program", "inside.nc", "--insert", "full"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("inside.nc:16:1: G76 under the polar coordinate interpolation of line 12"),
        "{}",
        stderr(&o)
    );
}

/// Issue 61 item 2: a lathe-based mill-turn read in Fanuc G-code system B (or C) keeps G94/G95
/// the feed modes and G98/G99 the drilling cycles' initial and R level in its milling sections
/// too (F0i-TF's G-code list). `G17 G94` then a G84 at F750 and S600 taps M8x1.25 at
/// S·P = 750 mm/min (read per revolution it failed by +748 750 µm, G94 being taken for system
/// A's G98, a return level). The return level decides where the next G91 cycle starts: after
/// `G98 G81 … R2` from Z5 the tool is back at Z5, so `G91 G84 R-3 Z-10` has R at 5 − 3 = 2 and
/// its bottom at 2 − 10 = −8; after `G99`, at the R level Z2: R −1, bottom −11.
#[test]
fn system_b_mill_turn_keeps_feed_modes_and_return_levels_apart() {
    let dir = tempdir("sysb-mill-turn");
    for (ret, r_level, bottom) in [("G98", 2.0, -8.0), ("G99", -1.0, -11.0)] {
        let program = format!("(M8X1.25 LIVE TAP)\nG18 G21 G95\nT0101\nG97 S800 M3\nG0 X30 Z2\nG1 X24 F0.1\nZ-20\nG0 X40 Z5\nT0505 (DRILL 6.8)\nG17 G94\nS1200\nG0 X0 Y0 Z5\n{ret} G81 Z-15 R2 F120\nG80\nT0606 (TAP M8X1.25)\nS600\nG91 G84 X0 Y0 R-3 Z-10 F750\nG80 G90\nG18\nM30\n");
        std::fs::write(dir.join("b.nc"), program).unwrap();
        let o = run_in(&dir, &["tap", "--program", "b.nc", "--gcode-system", "b", "--json", "-"]);
        let v: serde_json::Value =
            serde_json::from_slice(&o.stdout).unwrap_or_else(|e| panic!("{e}: {}", stderr(&o)));
        let cycle = &v["holes"][0]["cycle"];
        assert_eq!(cycle["feed_per_rev"], false, "{ret}: {cycle}");
        assert_eq!(cycle["r_level"], r_level, "{ret}: {cycle}");
        assert_eq!(cycle["bottom"], bottom, "{ret}: {cycle}");
        assert_eq!(o.status.code(), Some(0), "{ret}: {v}");
    }
}

/// Issue 61 (the Okuma A-6266 nut's correction): a correction computed with an insert nobody
/// chose is withheld. An M30x1.5-6H nut whose G76 ends at X30.146 is nearer the default partial
/// insert's tip position (r0.04: D2 + H − 2r = 29.026 + 1.299 − 0.080 = 30.245) than a
/// full-profile insert's (D = 30.000), so the partial is assumed: D2 = 30.146 − 1.219 = 28.927,
/// −99 µm under 6H's 29.026. With a full-profile insert the same passes leave D2 = 30.146 −
/// 0.974 = 29.172, inside 29.026–29.226 (ISO 965-1: TD2 200 µm): moving X by the partial's
/// figure would scrap that part. Given the insert, the correction is offered.
#[test]
fn no_correction_rests_on_an_assumed_insert() {
    let dir = tempdir("assumed-correction");
    let program = "(M30X1.5-6H NUT)\nG18 G21 G99\nT0101\nG97 S800 M3\nG0 X27 Z2\nG1 X28.4 F0.1\nZ-25\nG0 X26 Z5\nT0303\nG0 X28 Z5\nG76 P010060 Q100 R0.05\nG76 X30.146 Z-20 P870 Q200 F1.5\nG0 Z50\nM30\n";
    std::fs::write(dir.join("nut.nc"), program).unwrap();
    let o = run_in(&dir, &["verify", "--program", "nut.nc", "--json", "-"]);
    let v: serde_json::Value =
        serde_json::from_slice(&o.stdout).unwrap_or_else(|e| panic!("{e}: {}", stderr(&o)));
    let op = &v["operations"][0];
    assert!((op["measured"]["pitch_diameter"].as_f64().unwrap() - 28.927).abs() < 5e-4, "{op}");
    assert!(op["correction"].is_null(), "{op}");
    let notes = op["notes"].to_string();
    assert!(
        notes.contains("no correction is offered: the pitch diameter 28.9270 rests on the insert assumed"),
        "{notes}"
    );
    assert!(
        notes.contains("with full-profile iso-metric P1.5 the passes leave D2 29.1717, inside the class"),
        "{notes}"
    );
    let o = run_in(&dir, &["verify", "--program", "nut.nc", "--insert", "partial"]);
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(out.contains("change X30.146 at line 12:5"), "{out}");
}

/// Issue 61's done-when: a Denford-style turret lathe program (every index `T0x0x M06`) that
/// centre-drills on the axis (`G01 Z-5` at X0), roughs and finishes a journal with G71/G70 (its
/// profile in a modal G00 first block), grooves with G75 and threads M20x2.5 with G76, read as a
/// lathe with and without `--machine-type lathe`. Hand-derived: the blank is the G70 journal
/// Ø19.9 (line 15), never the drill's path on the axis; G75 is read past by name; the run-out at
/// Z-22 lies on the journal (clear); a full-profile tip at X16.933 (d3 = 20 − 1.226869·2.5 =
/// 16.93283) leaves d2 = 18.37620 + 0.00017 = 18.37637, 42.4 µm over 6g's d2 max 18.334
/// (ISO 965-1: es −42 µm).
#[test]
fn a_denford_style_lathe_program_reads_whole() {
    let dir = tempdir("denford");
    let program = "(M20X2.5)\nG21 G40 G99\nT0202 M06 (CENTRE DRILL)\nG97 S1500 M03\nG00 X0 Z2\nG01 Z-5 F0.05\nG00 Z5\nT0101 M06\nG96 S180 M03\nG50 S2500\nG00 X32 Z2\nG71 U1 R0.5\nG71 P10 Q20 U0.2 W0.1 F0.2\nN10 G00 X19.9\nG01 Z-25 F0.1\nX30\nN20 Z-40\nG70 P10 Q20\nG28 U0 W0\nT0505 M06 (GROOVE 3MM)\nG97 S600 M03\nG00 X32 Z-25\nG75 R0.5\nG75 X16 Z-25 P1000 Q2000 F0.08\nG28 U0 W0\nT0707 M06\nG97 S600 M03\nG00 X22 Z5\nG76 P010060 Q100 R0.05\nG76 X16.933 Z-22 P1534 Q400 F2.5\nG28 U0 W0\nM30\n";
    std::fs::write(dir.join("denford.nc"), program).unwrap();
    for given in [&[][..], &["--machine-type", "lathe"][..]] {
        let mut args = vec!["verify", "--program", "denford.nc", "--insert", "full"];
        args.extend_from_slice(given);
        let o = run_in(&dir, &args);
        let out = String::from_utf8_lossy(&o.stdout).into_owned();
        assert_eq!(o.status.code(), Some(1), "{out}{}", stderr(&o));
        assert!(out.contains("read as a lathe"), "{out}");
        assert!(out.contains("denford.nc:15:1: the blank is the program's own: Ø19.9000"), "{out}");
        assert!(out.contains("denford.nc:23:1: G75 read past"), "{out}");
        assert!(out.contains("pitch diameter     18.3764   18.1640   18.3340    +42.4 µm"), "{out}");
        assert!(out.contains("✓ run-out room"), "{out}");
    }
}

/// Issue 64 item 1: a turned internal thread's percent of thread from its bore, in the charts'
/// definition: the M30x1.5 nut bored to Ø28.4 has (30 − 28.4)/(1.299038·1.5) = 82.1 % of
/// thread, (30 − 28.4)/(1.082532·1.5) = 98.5 % of the basic height D − D1.
#[test]
fn a_turned_nut_s_percent_of_thread_is_its_bore_s() {
    let dir = tempdir("nut-percent");
    let program = "(M30X1.5-6H NUT)\nG18 G21 G99\nT0101\nG97 S800 M3\nG0 X27 Z2\nG1 X28.4 F0.1\nZ-25\nG0 X26 Z5\nT0303\nG0 X28 Z5\nG76 P010060 Q100 R0.05\nG76 X30.146 Z-20 P870 Q200 F1.5\nG0 Z50\nM30\n";
    std::fs::write(dir.join("nut.nc"), program).unwrap();
    let o = run_in(&dir, &["verify", "--program", "nut.nc", "--insert", "full", "--json", "-"]);
    let v: serde_json::Value =
        serde_json::from_slice(&o.stdout).unwrap_or_else(|e| panic!("{e}: {}", stderr(&o)));
    let t = &v["operations"][0]["thread_percent"];
    assert!((t["percent"].as_f64().unwrap() - 1.6 / (1.299_038 * 1.5) * 100.0).abs() < 1e-3, "{t}");
    assert!((t["of_basic_height"].as_f64().unwrap() - 1.6 / (1.082_532 * 1.5) * 100.0).abs() < 1e-3, "{t}");
    let o = run_in(&dir, &["verify", "--program", "nut.nc", "--insert", "full"]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("thread from the bore Ø28.4000: 82.1 %"));
}
