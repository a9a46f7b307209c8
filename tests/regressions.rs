//! One test per bug, named after it: each failed on the code before its fix.

use crate::*;
use threadcheck::{verify, CheckFeature, InsertChoice, VerifySpec};

/// Issue 23: sizes were compared at 1 µm for every standard, though ASME B1.1 prints its limits
/// to 0.0001 in (2.54 µm). 1/2-13 UNC-2A has d2 max = 0.4485 in = 11.3919 mm (ASME B1.1): a
/// pitch diameter 1.2 µm above it is 0.000047 in above, which rounds to the limit at 0.0001 in
/// (within), while at 1 µm it was 11.393 > 11.3919 (out). 1.4 µm above (0.000055 in) is out either
/// way.
#[test]
fn unified_sizes_are_compared_at_a_ten_thousandth_of_an_inch() {
    let d2_max = 0.4485 * 25.4;
    let at = |final_x: f64| {
        let spec = VerifySpec {
            insert: InsertChoice::Full,
            final_x: Some(final_x),
            ..VerifySpec::of("1/2-13 UNC-2A").unwrap()
        };
        verify(&spec).unwrap()
    };
    // A full-profile insert with radial infeed moves d2 with the final X one to one (diameters).
    let probe = at(10.0);
    let d2_0 = probe.measurement.pitch_diameter;
    for (over_um, ok) in [(1.2, true), (1.4, false)] {
        let v = at(10.0 + (d2_max + over_um / 1000.0 - d2_0));
        let d2 = v.measurement.pitch_diameter;
        assert!((d2 - d2_max - over_um / 1000.0).abs() < 1e-5, "d2 {d2} is not {over_um} µm over {d2_max}");
        let c = v.checks.iter().find(|c| c.feature == CheckFeature::PitchDiameter).unwrap();
        assert_eq!(c.max, Some(d2_max));
        assert_eq!(c.ok, ok, "{over_um} µm over d2 max: {c:?}");
        // Issue 59: a value shown past its shown limit never passes without a word.
        if ok {
            let x = format!("{:.6}", 10.0 + (d2_max + over_um / 1000.0 - d2_0));
            let o = run(&[
                "verify",
                "--thread",
                "1/2-13 UNC-2A",
                "--insert",
                "full",
                "--final-x",
                &x,
                "--json",
                "-",
            ]);
            let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
            let d2 =
                v["checks"].as_array().unwrap().iter().find(|c| c["feature"] == "pitch_diameter").unwrap();
            assert_eq!(
                (d2["ok"].as_bool(), d2["shown"]["deviation"].as_str()),
                (Some(true), Some("rounds to the limit")),
                "{d2}"
            );
        }
    }
}

/// Issue 24: notes were deduplicated by a linear search (quadratic in their number: 100 000
/// never-called subprograms took 32 s) and the never-called ones came out in hash order, which
/// changed from run to run. They come in the order the subprograms stand, once each.
#[test]
fn never_called_subprograms_are_noted_in_file_order() {
    let mut text = String::from(
        "O0001\nG21 G99\nT0101\nG0 X12 Z5\nG76 P010060 Q50 R0.02\nG76 X8.16 Z-20 P920 Q300 F1.5\nM30\n",
    );
    let n = 3000;
    for k in 0..n {
        text.push_str(&format!("O{}\nG0 X20\nM99\n", 2000 + k));
    }
    let p = threadcheck::read_program(&text, "many.nc", threadcheck::Dialect::Fanuc).unwrap();
    let never: Vec<(usize, String)> = p
        .notes
        .iter()
        .filter(|n| n.kind == threadcheck::NoteKind::NeverCalled)
        .map(|n| (n.place.as_ref().unwrap().line, n.message.clone()))
        .collect();
    assert_eq!(never.len(), n);
    for (k, (line, msg)) in never.iter().enumerate() {
        // Subprogram k's header stands on line 8 + 3k.
        assert_eq!(*line, 8 + 3 * k);
        assert_eq!(msg, &format!("subprogram O{} is defined but never called", 2000 + k));
    }
}

/// Issue 24: a flat sum of about 130 000 terms (a 262 kB line, far under the program limit)
/// overflowed the stack when its expression tree was freed, in every dialect; a legal sum of 66
/// terms was refused as nesting too deeply. A sum is one level, whatever its length (LinuxCNC's
/// long one is refused as LinuxCNC refuses a line of 255 bytes or more).
#[test]
fn a_long_flat_sum_is_one_level_deep() {
    for terms in [66usize, 130_000] {
        // 0+0+…+0+1.5 (terms − 1 zeros): the lead of the G32 pass.
        let sum = format!("{}1.5", "0+".repeat(terms - 1));
        let text = format!("#100=[{sum}]\nG21 G99\nG0 X12 Z5\nX9.2\nG32 Z-20 F#100\nG0 X12\nZ5\nM30\n");
        let p = threadcheck::read_program(&text, "sum.nc", threadcheck::Dialect::Fanuc).unwrap();
        assert_eq!(p.passes.len(), 1);
        assert_eq!(p.passes[0].lead, 1.5, "{terms} terms");
        // LinuxCNC: the same sum in a named parameter.
        let text = format!(
            "#<lead>=[{sum}]\nG21 G18 G7 S500 M3\nG0 X12 Z5\nX9.2\nG33 Z-20 K#<lead>\nG0 X12\nZ5\nM2\n"
        );
        match threadcheck::read_program(&text, "sum.ngc", threadcheck::Dialect::LinuxCnc) {
            Ok(p) => assert_eq!(p.passes[0].lead, 1.5, "{terms} terms, LinuxCNC"),
            // LinuxCNC itself reads no line of 255 bytes or more (issue 47: "Command too long"):
            // `#<lead>=[` and `1.5]` around 129 999 `0+`, 9 + 259 998 + 4 bytes.
            Err(e) => {
                assert!(terms > 100, "{e}");
                assert!(e.to_string().starts_with("sum.ngc:1:255: the line is 260011 bytes long: LinuxCNC reads lines of at most 254 (Command too long)"), "{e}");
            }
        }
    }
}

/// Issue 24: a FIFO with no writer blocked the reader for ever. It is given up after the stated
/// time with one line naming it; a pipe that delivers is read as before.
#[cfg(unix)]
#[test]
fn a_fifo_with_no_writer_is_given_up() {
    let dir = crate::tempdir("fifo");
    let fifo = dir.join("program.nc");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status().expect("mkfifo runs");
    assert!(made.success());
    let out = crate::run(&["verify", "--thread", "M10x1.5-6g", "--program", fifo.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let err = crate::one_line_error(&out);
    assert!(
        err.ends_with("program.nc: no data within 10 s: a FIFO or device with no writer is not read"),
        "{err}"
    );
}

/// Issue 24: `verify --svg old.svg --html /dev/full` exited 2 with old.svg already replaced:
/// outputs were renamed one after another. Now every output of a run is written, or none.
#[cfg(unix)]
#[test]
fn a_failed_output_keeps_every_old_output() {
    let dir = crate::tempdir("all-or-none");
    let old = dir.join("old.svg");
    std::fs::write(&old, "old").unwrap();
    let out = crate::run(&[
        "verify",
        "--thread",
        "M10x1.5-6g",
        "--svg",
        old.to_str().unwrap(),
        "--html",
        "/dev/full",
    ]);
    assert!(crate::one_line_error(&out).ends_with("/dev/full: No space left on device (os error 28)"));
    assert_eq!(std::fs::read_to_string(&old).unwrap(), "old");
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1, "a temporary was left behind");
}

/// Issue 24: an output path equal to the program silently overwrote the program.
#[test]
fn an_output_that_is_an_input_is_refused() {
    let dir = crate::tempdir("input-output");
    let prog = dir.join("m10.nc");
    let text = "G0 X12 Z5\nG76 P011060 Q100 R0.05\nG76 X8.16 Z-20 P920 Q350 F1.5\n";
    std::fs::write(&prog, text).unwrap();
    let p = prog.to_str().unwrap();
    for flag in ["--svg", "--html", "--json"] {
        let out = crate::run(&["verify", "--thread", "M10x1.5-6g", "--program", p, flag, p]);
        let err = crate::one_line_error(&out);
        assert!(err.ends_with("m10.nc: is an input of this run; an output must not replace it"), "{err}");
        assert_eq!(std::fs::read_to_string(&prog).unwrap(), text);
    }
}

/// Issue 24: a write error on standard output (a full disk) exited 0.
#[cfg(unix)]
#[test]
fn a_stdout_write_error_exits_2() {
    let full = std::fs::OpenOptions::new().write(true).open("/dev/full").unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_threadcheck"))
        .args(["limits", "M10x1.5-6g"])
        .stdout(full)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr).trim_end(),
        "threadcheck: error: standard output: No space left on device (os error 28)"
    );
}

/// Issue 24: a replaced output changed its mode from 0600 to 0644.
#[cfg(unix)]
#[test]
fn a_replaced_output_keeps_its_mode() {
    use std::os::unix::fs::PermissionsExt;
    let dir = crate::tempdir("mode");
    let json = dir.join("v.json");
    std::fs::write(&json, "{}").unwrap();
    std::fs::set_permissions(&json, std::fs::Permissions::from_mode(0o600)).unwrap();
    let out = crate::run(&["verify", "--thread", "M10x1.5-6g", "--json", json.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1), "{}", crate::stderr(&out)); // the partial insert fails d3
    assert_eq!(std::fs::metadata(&json).unwrap().permissions().mode() & 0o777, 0o600);
    assert!(std::fs::read_to_string(&json).unwrap().contains("\"verdict\""));
}

/// Issue 26, item 1: after a false `if`, LinuxCNC runs the `else` (or the first true
/// `elseif`). Here J ends at 0.3, and G76 P1.5 I-1 J0.3 K1.0 cuts at 0.3, 0.6, 0.9 (J·n while
/// below K) and at K: 4 passes, as LinuxCNC's interpreter lays it out (the issue's own run);
/// J stayed 0.1 (10 passes) before.
#[test]
fn linuxcnc_runs_the_else_after_a_false_if() {
    let head = "#<j>=0.1\n";
    let tail = "G7 G21 G18 S500 M3\nG0 X11 Z2\nG8\nG76 P1.5 Z-20 I-1 J#<j> K1.0\nM2\n";
    for (flow, passes) in [
        ("o1 if [0]\n#<j>=0.2\no1 else\n#<j>=0.3\no1 endif\n", 4),
        ("o1 if [1]\n#<j>=0.2\no1 else\n#<j>=0.3\no1 endif\n", 5),
        ("o1 if [0]\n#<j>=0.2\no1 elseif [0]\n#<j>=0.25\no1 elseif [1]\n#<j>=0.3\no1 else\n#<j>=0.4\no1 endif\n", 4),
        ("o1 if [0]\n#<j>=0.2\no1 elseif [0]\n#<j>=0.25\no1 endif\n", 10),
    ] {
        let p = threadcheck::read_program(&format!("{head}{flow}{tail}"), "if.ngc", threadcheck::Dialect::LinuxCnc)
            .unwrap();
        assert_eq!(p.passes.len(), passes, "{flow}");
    }
}

/// Issue 26, item 2: `#<_x>` and `#<_z>` on a line of parameter assignments are the position
/// the last move left (they were refreshed only before blocks with words: `#<z0>=#<_z>` was
/// "not defined"). After G1 Z-5 from X20: #<_z> = −5, #<_x> = 10 (a radius, as LinuxCNC's
/// #5420 is), so the G0 goes to X22 Z3; under G7 I−1 and J0.3 are diameters, and the first
/// pass is at 22 − 1 − 0.3 = X20.7 from Z3.
#[test]
fn linuxcnc_position_parameters_are_current_on_assignment_lines() {
    let text = "G7 G21 G18 G90 S500 M3\nG0 X20 Z3\nG1 Z-5 F0.1\n#<z0>=#<_z>\n#1=#<_x>\nG0 X[#1*2+2] Z[#<z0>+8]\nG76 P1.5 Z-20 I-1 J0.3 K1.0\nM2\n";
    let p = threadcheck::read_program(text, "sys.ngc", threadcheck::Dialect::LinuxCnc).unwrap();
    assert!((p.passes[0].x_start - 20.7).abs() < 1e-9, "{:?}", p.passes[0]);
    assert!((p.passes[0].z_start - 3.0).abs() < 1e-9, "{:?}", p.passes[0]);
}

/// Issue 26, items 3 and 5: LinuxCNC counts G76 passes in program units and its own order
/// (|I| + |J|·n^(1/R) while below |K| + |I|): `G76 P1.5 Z-20 I-1 J0.3 K0.9` from X11 Z2 cuts 3
/// passes under LinuxCNC (1 + 0.3·3 rounds to 1.9, not below it), where the mm comparison
/// 0.3·3 < 0.9 gave 4. Q−1 is no compound angle, L is a bit mask (L5 = entry taper, as L1) and
/// an F word on the G76 line is accepted, as LinuxCNC reads them.
#[test]
fn linuxcnc_g76_counts_passes_and_reads_q_l_f_as_linuxcnc_does() {
    let read = |g76: &str| {
        threadcheck::read_program(
            &format!("G18 G21 G90 S500 M3\nG0 X11 Z2\n{g76}\nM2\n"),
            "g76.ngc",
            threadcheck::Dialect::LinuxCnc,
        )
        .unwrap()
        .passes
    };
    assert_eq!(read("G76 P1.5 Z-20 I-1 J0.3 K0.9").len(), 3);
    assert_eq!(read("G76 P1.5 Z-20 I-1 J0.2 K1.0 Q-1"), read("G76 P1.5 Z-20 I-1 J0.2 K1.0 Q0"));
    assert_eq!(read("G76 P1.5 Z-20 I-1 J0.2 K1.0 L5 E2"), read("G76 P1.5 Z-20 I-1 J0.2 K1.0 L1 E2"));
    assert_eq!(read("G76 P1.5 Z-20 I-1 J0.2 K1.0 F100"), read("G76 P1.5 Z-20 I-1 J0.2 K1.0"));
}

/// Issue 26, items 4 and 5: LinuxCNC compares EQ, NE, LE and GE within 1e-6 (its
/// `TOLERANCE_EQUAL`) and its MOD is never negative (fmod, plus |divisor| when below 0). Each
/// case sets J to 0.3 only under LinuxCNC's rules; G76 I-1 J0.3 K1.0 then cuts 4 passes (0.3,
/// 0.6, 0.9, 1.0), J0.1 10.
#[test]
fn linuxcnc_comparisons_and_mod_follow_its_interpreter() {
    let tail = "G7 G21 G18 S500 M3\nG0 X11 Z2\nG8\nG76 P1.5 Z-20 I-1 J#<j> K1.0\nM2\n";
    for flow in [
        "#<j>=0.1\no1 if [0.3 EQ 0.3000005]\n#<j>=0.3\no1 endif\n",
        "#<j>=0.1\no1 if [0.3000005 LE 0.3]\n#<j>=0.3\no1 endif\n",
        "#<j>=0.1\no1 if [0.3 GE 0.3000005]\n#<j>=0.3\no1 endif\n",
        "#<j>=0.3\no1 if [0.3 NE 0.3000005]\n#<j>=0.1\no1 endif\n",
        "#<j>=[[5 MOD -3] / 10 + 0.1]\n",
    ] {
        let p =
            threadcheck::read_program(&format!("{flow}{tail}"), "cmp.ngc", threadcheck::Dialect::LinuxCnc)
                .unwrap();
        assert_eq!(p.passes.len(), 4, "{flow}");
    }
}

/// Issue 26, item 2, in a condition: `o1 if [#<_z> LT -4]` right after `G1 Z-5` reads Z−5 (it
/// read the Z before the move, 3, when the parameters were refreshed only before blocks with
/// words): J becomes 0.3, and G76 I-1 J0.3 K1.0 cuts 4 passes (10 with J0.1).
#[test]
fn linuxcnc_position_parameters_are_current_in_conditions() {
    let text = "G7 G21 G18 G90 S500 M3\nG0 X20 Z3\nG1 Z-5 F0.1\n#<j>=0.1\no1 if [#<_z> LT -4]\n#<j>=0.3\no1 endif\nG0 X22 Z3\nG76 P1.5 Z-20 I-1 J#<j> K1.0\nM2\n";
    let p = threadcheck::read_program(text, "cond.ngc", threadcheck::Dialect::LinuxCnc).unwrap();
    assert_eq!(p.passes.len(), 4);
}

/// Reads a LinuxCNC program (current release rules unless `before_29`) and gives its passes'
/// tip diameter, start Z and end Z.
fn linuxcnc_passes(text: &str, before_29: bool) -> Result<Vec<(f64, f64, f64)>, String> {
    let opts = threadcheck::ReadOptions {
        linuxcnc: if before_29 {
            threadcheck::LinuxCncRelease::Before29
        } else {
            threadcheck::LinuxCncRelease::Current
        },
        ..threadcheck::ReadOptions::default()
    };
    threadcheck::read_program_with(text, "p.ngc", threadcheck::Dialect::LinuxCnc, opts)
        .map(|p| p.passes.iter().map(|q| (q.x_start, q.z_start, q.z_end)).collect())
        .map_err(|e| e.to_string())
}

/// Issue 26, item 5: work offsets between passes (G10 L2, G55, G92, G92.1, G54) move the
/// program's coordinates, not the passes already cut; each pass stands where the machine cut
/// it, in the coordinates the program started in. By hand (G7, X diameters; LinuxCNC's rs274
/// prints the same with its offsets): G10 L2 P2 X0.4 Z-2 and G55 put X9 Z5…-8 at Ø9.4,
/// Z3…-10, over the first pass. G92 X10 Z1 at program X12 Z-8 (G55) sets the G92 offset to
/// Ø2 and Z-9, so X8.8 Z1…-9 is Ø8.8 + 0.4 + 2 = Ø11.2, Z1 − 2 − 9 = -10 … -20. G92.1 and G54
/// return to the first coordinates: X8.6 Z3…-10 is Ø8.6, Z3…-10.
#[test]
fn linuxcnc_work_offsets_between_passes_move_the_program_not_the_passes() {
    let text = "G18 G21 G90 G7 S500 M3\nG0 X12 Z3\nG1 X9.4 F100\nG33 Z-10 K1.5\nG0 X12\n\
                G10 L2 P2 X0.4 Z-2\nG55\nG0 Z5\nG1 X9\nG33 Z-8 K1.5\nG0 X12\n\
                G92 X10 Z1\nG1 X8.8\nG33 Z-9 K1.5\nG0 X12\nG92.1\nG54\nG0 Z3\nG1 X8.6\nG33 Z-10 K1.5\nM5\nM2\n";
    let got = linuxcnc_passes(text, false).unwrap();
    let want = [(9.4, 3.0, -10.0), (9.4, 3.0, -10.0), (11.2, -10.0, -20.0), (8.6, 3.0, -10.0)];
    assert_eq!(got.len(), want.len());
    for (g, w) in got.iter().zip(want) {
        assert!((g.0 - w.0).abs() < 1e-9 && (g.1 - w.1).abs() < 1e-9 && (g.2 - w.2).abs() < 1e-9, "{got:?}");
    }
}

/// Issue 26, item 5: LinuxCNC refuses G33 and G76 with the spindle stopped ("Spindle not
/// turning in G33"); a tool change (M6) and M5 stop it, M3 and M4 start it.
#[test]
fn linuxcnc_refuses_threading_with_the_spindle_stopped() {
    let cut = "G0 X12 Z3\nG1 X9.4 F100\nG33 Z-10 K1.5\nM2\n";
    for (head, ok) in [
        ("", false),
        ("S500 M3\n", true),
        ("S500 M4\n", true),
        ("S500 M3\nM5\n", false),
        ("S500 M3\nT1 M6\n", false),
        ("T1 M6 S500 M3\n", true),
    ] {
        let r = linuxcnc_passes(&format!("G18 G21 G90 G7\n{head}{cut}"), false);
        assert_eq!(r.is_ok(), ok, "{head:?}: {r:?}");
        if let Err(e) = r {
            assert!(e.contains("spindle stopped"), "{e}");
        }
    }
}

/// Issue 26: LinuxCNC breaks out of and continues while and do loops only; `o1 break` in a
/// repeat loop is its error "no matching while/do label".
#[test]
fn linuxcnc_break_in_a_repeat_loop_is_refused() {
    let text =
        "G18 G21 G90 G7 S500 M3\nG0 X12 Z3\no1 repeat [3]\nG33 Z-10 K1.5\no1 break\no1 endrepeat\nM2\n";
    let e = linuxcnc_passes(text, false).unwrap_err();
    assert!(e.contains("repeat loop"), "{e}");
}

/// Issue 26, found by the conformance test: after `continue`, LinuxCNC skips to the next line
/// with the loop's name, and a `break` there runs even in a branch not taken. In a do-while
/// loop the break wins: the continue on turn 2 ends the loop (1 pass). In a while loop the
/// continue's flag wins at `endwhile` and the loop goes on: passes on turns 1, 3 and 4, the
/// break of turn 5 ends it (3 passes). And the `break` of a while loop leaves its flag set, so
/// the next do-while loop runs once instead of three times. (rs274 of Debian's
/// linuxcnc-uspace cuts 1, 3 and 1 passes; interp_o_word.cc reads the same today.)
#[test]
fn linuxcnc_follows_its_interpreter_through_break_and_continue() {
    let body = "#1 = [#1 + 1]\no2 if [#1 EQ 2]\no1 continue\no2 elseif [#1 GT 4]\no1 break\no2 endif\n\
                G0 X5\nG33 Z-10 K1.5\nG0 X12\nZ2\n";
    let head = "G18 G21 G90 G8 S500 M3\nG0 X12 Z2\n#1 = 0\n";
    let do_loop = format!("{head}o1 do\n{body}o1 while [#1 LT 5]\nM2\n");
    assert_eq!(linuxcnc_passes(&do_loop, false).unwrap().len(), 1);
    let while_loop = format!("{head}o1 while [#1 LT 5]\n{body}o1 endwhile\nM2\n");
    assert_eq!(linuxcnc_passes(&while_loop, false).unwrap().len(), 3);
    // A while loop left by break, then a do-while loop of three turns: it runs once.
    let text = "G18 G21 G90 G8 S500 M3\nG0 X12 Z2\n#1 = 0\no1 while [#1 LT 5]\n#1 = [#1 + 1]\no1 break\n\
                o1 endwhile\n#2 = 0\no3 do\n#2 = [#2 + 1]\nG0 X5\nG33 Z-10 K1.5\nG0 X12\nZ2\n\
                o3 while [#2 LT 3]\nM2\n";
    assert_eq!(linuxcnc_passes(text, false).unwrap().len(), 1);
}

/// Issue 26, found by the conformance test: an `endsub` or `return` without a value sets
/// `#<_value>` to 0 (LinuxCNC's interp_read.cc), so a test of the value after a plain call
/// reads 0, not the value an earlier call returned: here the break never comes, 3 passes.
#[test]
fn linuxcnc_a_return_without_a_value_zeroes_value() {
    let text = "G18 G21 G90 G8 S500 M3\no<d> sub\no<d> return [1]\no<d> endsub\n\
                o<p> sub\nG0 X5\nG33 Z-10 K1.5\nG0 X12\nZ2\no<p> endsub\nG0 X12 Z2\n#1 = 0\n\
                o1 while [#1 LT 3]\n#1 = [#1 + 1]\no<d> call\no<p> call\n\
                o2 if [#<_value> EQ 1]\no1 break\no2 endif\no1 endwhile\nM2\n";
    assert_eq!(linuxcnc_passes(text, false).unwrap().len(), 3);
}

/// Issue 26, found by the conformance test: spaces mean nothing to LinuxCNC, so `1 EQ ACOS[1]`
/// is `1EQACOS[1]`, and the operator is EQ followed by ACOS (it was "']' missing").
#[test]
fn linuxcnc_an_operator_runs_into_the_word_after_it() {
    let text = "G18 G21 G90 G8 S500 M3\n#1 = [0 EQ ACOS[1]]\nG0 X12 Z2\nG1 X[5 + #1]\nG33 Z-10 K1.5\nM2\n";
    assert_eq!(linuxcnc_passes(text, false).unwrap()[0].0, 12.0);
}

/// Issue 26, found by the conformance test: LinuxCNC turns degrees into radians and back in
/// long double, rounding once; `ASIN[SIN[3]]` is 3 there (rs274 prints 3 MOD 0.02 =
/// 0.020000 for it) where two roundings give 3.0000000000000004, whose MOD 0.02 is 0: the
/// pass below is at radius 5 + 100·0.02 = 7, Ø14, under LinuxCNC.
#[test]
fn linuxcnc_degrees_are_rounded_once_as_its_interpreter_does() {
    let text = "G18 G21 G90 G8 S500 M3\n#1 = [ABS[ASIN[SIN[3]]] MOD 0.02]\nG0 X12 Z2\nG1 X[5 + 100 * #1]\nG33 Z-10 K1.5\nM2\n";
    assert!((linuxcnc_passes(text, false).unwrap()[0].0 - 14.0).abs() < 1e-9);
}

/// Issue 26, item 4: LinuxCNC before 2.9.0 (Debian 12's package among them) compares EQ and NE
/// within 1e-4 and LE, GE exactly; 2.9.0 and later compare all four within 1e-6. Here the
/// loop `while [#1 LE 0.0375]` after 75 steps of 0.0005 (the sum is 0.0375000000000000x) runs
/// 75 times before 2.9, 76 from 2.9 on; `--linuxcnc-release before-2.9` chooses the old rules
/// from the command line.
#[test]
fn linuxcnc_release_before_2_9_compares_as_debian_s_interpreter() {
    let text = "G18 G21 G90 G8 S500 M3\n#1 = 0\no1 while [#1 LE 0.0375]\nG0 X12 Z2\nG1 X[5 - #1]\nG33 Z-10 K1.5\nG0 X12\n#1 = [#1 + 0.0005]\no1 endwhile\nM2\n";
    assert_eq!(linuxcnc_passes(text, true).unwrap().len(), 75);
    assert_eq!(linuxcnc_passes(text, false).unwrap().len(), 76);
    let eq = "G18 G21 G90 G8 S500 M3\nG0 X12 Z2\no1 if [1 EQ 1.00005]\nG1 X5\no1 else\nG1 X6\no1 endif\nG33 Z-10 K1.5\nM2\n";
    assert_eq!(linuxcnc_passes(eq, true).unwrap()[0].0, 10.0);
    assert_eq!(linuxcnc_passes(eq, false).unwrap()[0].0, 12.0);
    let dir = crate::tempdir("release");
    std::fs::write(dir.join("eq.ngc"), eq).unwrap();
    let o =
        crate::run_in(&dir, &["passes", "--program", "eq.ngc", "--linuxcnc-release", "before-2.9", "--json"]);
    assert_eq!(o.status.code(), Some(0), "{}", crate::stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["passes"][0]["x_start"], 10.0);
}

/// Issue 26, found by the conformance test: LinuxCNC keeps the current point in program units,
/// so after `G0 X0.22` (inch, radius mode) `#<_x>` is 0.22 itself; threadcheck keeps mm, and
/// 0.22 · 25.4 · 2 / 2 / 25.4 is 0.22000000000000003, whose MOD 0.02 is 0 where 0.22's is
/// 0.019999999999999997. The G0 below goes to X0.5 + 10 · 0.02 = 0.7 in (rs274 prints
/// STRAIGHT_TRAVERSE(0.7000, …)): Ø35.56 mm.
#[test]
fn linuxcnc_position_parameters_are_the_numbers_written() {
    let text = "G18 G20 G90 G8 S500 M3\nG0 X0.22 Z0.1\n#1 = [#<_x> MOD 0.02]\nG0 X[0.5 + 10 * #1]\nG33 Z-0.5 K0.05\nM2\n";
    let x = linuxcnc_passes(text, false).unwrap()[0].0;
    assert!((x - 35.56).abs() < 1e-9, "{x}");
}

/// Issue 26: a G92 where threadcheck does not know the position (LinuxCNC starts wherever the
/// tool is) defines the coordinates when no pass was cut before it: `G92 X20 Z2` then X9.4 is
/// Ø9.4 from Z2. After threading passes, a G92 from an unknown position (here after a G53 move
/// in machine coordinates) leaves the later passes without a known relation to the earlier
/// ones: the next threading operation is refused, naming the G92.
#[test]
fn linuxcnc_g92_from_an_unknown_position() {
    let cut = "G1 X9.4 F100\nG33 Z-10 K1.5\nG0 X20\nZ2\n";
    let first = format!("G18 G21 G90 G7 S500 M3\nG92 X20 Z2\n{cut}M2\n");
    let got = linuxcnc_passes(&first, false).unwrap();
    assert_eq!(got, vec![(9.4, 2.0, -10.0)]);
    let after = format!("G18 G21 G90 G7 S500 M3\nG0 X20 Z2\n{cut}G53 G0 X100\nG92 X20 Z2\n{cut}M2\n");
    let e = linuxcnc_passes(&after, false).unwrap_err();
    assert!(e.contains("line 8 (G92)") && e.contains("does not know"), "{e}");
}

/// Issue 28: a machine profile names only what the machine limits. A file with `max_rpm` and
/// `max_feed_mm_min` alone (what the verify guide's process section describes) was refused for its
/// missing `name` and `rapid_mm_min`; now it is the machine named after its file, with the
/// rapid rate of 5000 mm/min assumed and said. The G97 program's four G92 passes of 25 mm at
/// S500, lead 1.5, come in from X24 and go back at 5000 mm/min: 120.624 mm of rapid (see
/// process.rs) in 1.447488 s. A field the profile does not know is still an error, on one line.
#[test]
fn a_machine_profile_needs_only_its_limits() {
    let dir = crate::tempdir("machine");
    let file = dir.join("small-lathe.toml");
    std::fs::write(&file, "max_rpm = 3000\nmax_feed_mm_min = 5000\n").unwrap();
    let prog = crate::data("programs/fanuc-g97-g92.nc");
    let args = ["verify", "--program", prog.to_str().unwrap(), "--thread", "M20x1.5-6g", "--insert", "full"];
    let mut a = args.to_vec();
    a.extend(["--machine", file.to_str().unwrap(), "--no-pass-metrics", "--json", "-"]);
    let o = crate::run(&a);
    let v: serde_json::Value =
        serde_json::from_slice(&o.stdout).unwrap_or_else(|_| panic!("{}", crate::stderr(&o)));
    let p = &v["operations"][0]["process"];
    assert_eq!(p["machine"], "small-lathe (rapid 5000 mm/min assumed)");
    assert!((p["machining_time"]["rapid"].as_f64().unwrap() - 1.447488).abs() < 1e-9, "{p}");
    std::fs::write(&file, "max_rpm = 3000\nmax_speed = 5\n").unwrap();
    let mut a = args.to_vec();
    a.extend(["--machine", file.to_str().unwrap()]);
    let o = crate::run(&a);
    assert_eq!(o.status.code(), Some(2));
    let e = crate::stderr(&o);
    assert_eq!(e.trim_end().lines().count(), 1, "{e}");
    assert!(e.contains("max_speed"), "{e}");
}

/// Issue 28: the top-level help named ISO 965-1, BS 84 and ISO 228-1 only; it names every
/// standard threadcheck checks against.
#[test]
fn the_help_names_every_standard() {
    let o = crate::run(&["--help"]);
    let out = crate::stdout(&o);
    for s in
        ["ISO 965-1", "BS 84", "ISO 228-1", "ASME B1.1", "ISO 2903", "ASME B1.5", "ASME B1.20.1", "ISO 7-1"]
    {
        assert!(out.contains(s), "{s} missing from --help:\n{out}");
    }
}

/// Issue 28: the process checks read like code (`constant_spindle_speed    1.0000`, an rpm check
/// with four decimals and a deviation of 0.0 µm). The text table names them in words, shows
/// each value in its unit, and the deviation in the check's unit: S500 against the training
/// lathe's 320 rpm for P 1.5 (its Table 2.2) is 180 rpm over; a 1° clearance insert on
/// M20x1.5 at d2 (helix 1.438°) keeps 1 − 1.438 = −0.438° on the leading flank, 0.438° short
/// of the 0° it needs.
#[test]
fn process_checks_read_in_words_and_units() {
    let prog = crate::data("programs/fanuc-g97-g92.nc");
    let o = crate::run(&[
        "verify",
        "--program",
        prog.to_str().unwrap(),
        "--thread",
        "M20x1.5-6g",
        "--insert",
        "full",
        "--machine",
        "training-lathe",
        "--clearance-angle",
        "1",
        "--no-pass-metrics",
    ]);
    let out = crate::stdout(&o);
    let line = |start: &str| {
        out.lines().find(|l| l.contains(start)).unwrap_or_else(|| panic!("{start}:\n{out}")).to_string()
    };
    let rpm = line("✗ spindle speed");
    assert!(rpm.contains(" 500 ") && rpm.contains(" 320 ") && rpm.contains("+180 rpm"), "{rpm}");
    assert!(line("constant rpm").contains(" yes "), "{out}");
    assert!(line("✗ flank clearance").contains("-0.438°"), "{out}");
    assert!(!out.contains("constant_spindle_speed") && !out.contains("1.0000         —"), "{out}");
}

/// Issue 28: `compare --program` failed with "a final X and a program exclude each other" though
/// no X was given, and `compare --taper` spoke of verify and of three standards; each now says
/// what compare does instead.
#[test]
fn compare_says_why_it_takes_no_program_and_no_taper() {
    let prog = crate::data("programs/fanuc-g97-g92.nc");
    let o = crate::run(&["compare", "--thread", "M20x1.5-6g", "--program", prog.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let e = crate::stderr(&o);
    assert!(
        e.contains("compare lays out each infeed strategy's own passes") && !e.contains("final X"),
        "{e}"
    );
    let o = crate::run(&["compare", "--thread", "M20x1.5-6g", "--taper", "0.0625"]);
    assert_eq!(o.status.code(), Some(2));
    let e = crate::stderr(&o);
    assert!(e.contains("compare takes a taper thread's taper from its designation"), "{e}");
}

/// Issue 28: `--units inch` added inch columns to the check table only; the header, the measured
/// line and the correction stayed in mm. The inch program's last pass is X.9 (in): 22.86 mm,
/// shown as 0.90000 in beside it; the measured line and the correction give inches too.
#[test]
fn units_inch_reach_the_header_the_measured_line_and_the_correction() {
    let prog = crate::data("programs/fanuc-g76-inch.nc");
    let o = crate::run(&[
        "verify",
        "--program",
        prog.to_str().unwrap(),
        "--thread",
        "1-16-UN-2A",
        "--units",
        "inch",
        // The insert given: a correction resting on an assumed one is withheld.
        "--insert",
        "full",
    ]);
    let out = crate::stdout(&o);
    // Issue 65: in inches first, the mm beside them (X.9 is 22.86 mm).
    assert!(out.contains("final X0.9000 (22.8600 mm)"), "{out}");
    let measured = out.lines().find(|l| l.contains("measured:")).unwrap();
    assert!(measured.contains("thread depth") && measured.matches(" mm)").count() >= 3, "{measured}");
    let fix = out.lines().find(|l| l.contains("for mid-tolerance")).unwrap();
    assert!(
        fix.contains(" in (-") && fix.contains(" µm) off") && fix.contains(" mm) on the diameter"),
        "{fix}"
    );
}

/// Issue 28: an inch thread is read in inches by default (issue 65: the mm beside them); `--units
/// mm` keeps the mm alone, and a metric thread stays in mm. 1/2-13 UNC: major diameter 0.5 in
/// nominal, so the table's first column reads 0.49… and the mm beside it 12.…
#[test]
fn inch_threads_default_to_inches() {
    let table = |args: &[&str]| crate::stdout(&crate::run(args));
    let unc = table(&["verify", "--thread", "1/2-13-UNC-2A", "--insert", "full"]);
    let major = unc.lines().find(|l| l.contains("major diameter")).unwrap();
    assert!(
        major.trim_end().ends_with(" mm") && major.contains(" 0.49") && major.contains(" 12."),
        "{major}"
    );
    let mm = table(&["verify", "--thread", "1/2-13-UNC-2A", "--insert", "full", "--units", "mm"]);
    assert!(!mm.lines().any(|l| l.contains("major diameter") && l.contains(" 0.49")), "{mm}");
    let metric = table(&["verify", "--thread", "M10x1.5-6g", "--insert", "full"]);
    assert!(!metric.contains(" in)") && !metric.lines().any(|l| l.trim_end().ends_with(" mm")), "{metric}");
}

/// Issue 28: a flat root has no root radius. A full-profile Tr20x4 insert (ISO 2904: a flat
/// crest) and a 1/2-10 Acme one cut flat roots with sharp corners, which once reported 1.5542
/// and 1.0658 mm (the circle through a flank point and both corners); now null. The ISO metric
/// full-profile insert's root is the rounded H/6 = P/(4√3) = 0.216506 mm for P 1.5.
#[test]
fn a_flat_root_reports_no_root_radius() {
    for d in ["Tr20x4-7e", "1/2-10 ACME-2G"] {
        let v = verify(&VerifySpec { insert: InsertChoice::Full, ..VerifySpec::of(d).unwrap() }).unwrap();
        assert_eq!(v.measurement.root_radius, None, "{d}");
    }
    let m10 =
        verify(&VerifySpec { insert: InsertChoice::Full, ..VerifySpec::of("M10x1.5-6g").unwrap() }).unwrap();
    let r = m10.measurement.root_radius.unwrap();
    assert!((r - 1.5 / (4.0 * 3f64.sqrt())).abs() < 1e-6, "{r}");
}

/// Issue 28: flank infeed steeper than the flank leaves a fin between passes. Each pass's
/// trailing edge stands at 30° while the passes step along 40°, so the next pass cuts beside the
/// last one's tip instead of through it: the last tip's radius rises again before the next
/// pass's edge falls, a ridge inside the groove, which `one groove` passed. At 29.5° (less than
/// the flank) each pass recuts the last one's trailing flank and the groove falls cleanly.
#[test]
fn a_steep_flank_infeed_fin_fails_one_groove() {
    let groove = |infeed: &str| {
        let o = crate::run(&[
            "verify",
            "--thread",
            "M10x1.5-6g",
            "--infeed",
            infeed,
            "--no-pass-metrics",
            "--json",
        ]);
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        let c =
            v["checks"].as_array().unwrap().iter().find(|c| c["feature"] == "single_groove").unwrap().clone();
        (c, v["measured"]["fin_height"].as_f64().unwrap())
    };
    let (steep, fin) = groove("flank:40");
    assert_eq!(steep["ok"], false, "{steep}");
    assert!(fin > 0.001 && steep["note"].as_str().unwrap().contains("fin or notch"), "{fin} {steep}");
    let (clean, fin) = groove("flank:29.5");
    assert_eq!(clean["ok"], true, "{clean}");
    assert!(fin <= 0.001, "{fin}");
}

/// Issue 28: compare honours --infeed and --schedule (one row: radial, Sandvik), says why a
/// strategy fails, and recommends one on stated grounds. The default M10x1.5-6g comparison with
/// its partial insert fails everywhere on the insert's root (d3 and R: ISO 965-1 wants
/// R ≥ 0.125·P = 0.1875 mm); flank infeed at exactly 30° rubs, radial and alternating put about
/// half the chip behind the tip, so modified 29.5° with constant-area depths is recommended.
#[test]
fn compare_honours_its_options_and_recommends_a_strategy() {
    let json = |args: &[&str]| -> serde_json::Value {
        let o = crate::run(args);
        assert_eq!(o.status.code(), Some(0), "{}", crate::stderr(&o));
        serde_json::from_slice(&o.stdout).unwrap()
    };
    let one =
        json(&["compare", "--thread", "M10x1.5-6g", "--infeed", "radial", "--schedule", "sandvik", "--json"]);
    let rows = one["strategies"].as_array().unwrap();
    assert_eq!(rows.len(), 1);
    assert_eq!((rows[0]["infeed"].as_str(), rows[0]["schedule"].as_str()), (Some("radial"), Some("sandvik")));
    let all = json(&["compare", "--thread", "M10x1.5-6g", "--json"]);
    assert_eq!(all["strategies"].as_array().unwrap().len(), 10);
    let r = &all["recommended"];
    assert_eq!(
        (r["infeed"].as_str(), r["schedule"].as_str()),
        (Some("modified 29.5°"), Some("constant-area"))
    );
    assert_eq!(r["any_in_tolerance"], false);
    let why = all["strategies"][0]["failed"].to_string();
    assert!(why.contains("minor_diameter") && why.contains("root_radius"), "{why}");
    let text = crate::stdout(&crate::run(&["compare", "--thread", "M10x1.5-6g"]));
    assert!(text.contains("fail: minor diameter d3, root radius"), "{text}");
    assert!(text.contains("recommended: modified 29.5° infeed, constant-area"), "{text}");
    let units = crate::run(&["compare", "--thread", "M10x1.5-6g", "--units", "inch"]);
    assert_eq!(units.status.code(), Some(2));
}

/// Issue 28: the picture says the next step. A program whose d2 is off shows its correction
/// in the program's words; a partial insert under ISO 965-1's root radius (0.125·P = 0.1875 mm
/// for P 1.5) shows the hint that no final X fixes it; a program's picture opens with its
/// verdict and one line per operation.
#[test]
fn the_svg_says_the_next_step() {
    let dir = crate::tempdir("svg-next");
    let prog = crate::data("programs/source-docs/seed003-two-threads.nc");
    let o = crate::run_in(
        &dir,
        &[
            "verify",
            "--thread",
            "M20x1.5-6g",
            "--thread",
            "M10x1.5-6g",
            "--insert",
            "full",
            "--program",
            prog.to_str().unwrap(),
            "--svg",
            "p.svg",
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}", crate::stderr(&o));
    let svg = std::fs::read_to_string(dir.join("p.svg")).unwrap();
    assert!(
        svg.contains("id=\"program-verdict\"") && svg.contains("OUT OF TOLERANCE: 2 threading operations"),
        "{}",
        &svg[..600]
    );
    assert!(svg.contains("1. G76 at line 6, M20x1.5-6g") && svg.contains("2. G76 at line 9, M10x1.5-6g"));
    assert!(svg.contains("next: change X18.2 at line 6:5 to X18.058"), "no correction in the picture");
    let o = crate::run_in(&dir, &["verify", "--thread", "M10x1.5-6g", "--svg", "h.svg", "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["hints"][0]["hint"], "tip_radius");
    assert_eq!(v["hints"][0]["root_radius_min"].as_f64(), Some(0.1875));
    let svg = std::fs::read_to_string(dir.join("h.svg")).unwrap();
    assert!(
        svg.contains("hint: the insert&apos;s tip radius 0.04 mm")
            || svg.contains("hint: the insert's tip radius 0.04 mm"),
        "no hint in the picture"
    );
}

/// Issue 28: inches reach the pictures and the page. 1/2-13 UNC-2A cut to X10.2 mm: the title
/// gives 10.2/25.4 = 0.4016 in (issue 65: the mm beside it), the axes are in inches (`Z in`,
/// `Ø in`), the deviation plot in ten-thousandths of an inch; the HTML's table is in inches with
/// a mm column. The inch program's picture gives its correction in the program's own (inch) word.
#[test]
fn inches_reach_the_svg_and_the_html() {
    let dir = crate::tempdir("inch-svg");
    let o = crate::run_in(
        &dir,
        &["verify", "--thread", "1/2-13 UNC-2A", "--final-x", "10.2", "--svg", "i.svg", "--html", "i.html"],
    );
    assert_eq!(o.status.code(), Some(1), "{}", crate::stderr(&o));
    let svg = std::fs::read_to_string(dir.join("i.svg")).unwrap();
    for s in ["last pass X0.4016 (10.2000 mm)", "\nZ in\n", "\nØ in\n", "normal to it, in tenths (0.0001 in)"]
    {
        assert!(svg.contains(s), "{s} not in the SVG");
    }
    let html = std::fs::read_to_string(dir.join("i.html")).unwrap();
    assert!(
        html.contains("<th>value, in</th>")
            && html.contains("<th>value, mm</th>")
            && html.contains("X0.4016 in (10.2000 mm)"),
        "no inches in the HTML"
    );
    // Metric stays metric.
    let o = crate::run_in(&dir, &["verify", "--thread", "M10x1.5-6g", "--svg", "m.svg"]);
    assert!(o.status.code().is_some_and(|c| c < 2));
    let svg = std::fs::read_to_string(dir.join("m.svg")).unwrap();
    assert!(svg.contains("\nZ mm\n") && !svg.contains(" in)"));
    let prog = crate::data("programs/fanuc-g76-inch.nc");
    let o = crate::run_in(
        &dir,
        &[
            "verify",
            "--program",
            prog.to_str().unwrap(),
            "--thread",
            "1-16-UN-2A",
            "--insert",
            "partial",
            "--svg",
            "p.svg",
        ],
    );
    assert!(o.status.code().is_some_and(|c| c < 2), "{}", crate::stderr(&o));
    let svg = std::fs::read_to_string(dir.join("p.svg")).unwrap();
    // X.9 in leaves d2 48.8 µm under: the correction is an inch word.
    assert!(
        svg.contains("next: change X.9 at line 6:5 to X0.9044 (inch, diameter)"),
        "no inch correction in the picture"
    );
    assert!(svg.contains("\nZ in\n"));
}

/// Issue 28: a taper thread's numbers in the true axial section. 1/2-14 NPT cut with a
/// full-profile insert has 30°/30° flanks (reported as 30.454°/29.558°, the sheared section's)
/// and its pitch diameter is reported at the gauge plane: E1 = 0.77843 in = 19.772122 mm
/// (within 1 µm: the sheared construction reads E about 0.5 µm off). ISO 7-1's R and Rc: 27.5°.
#[test]
fn taper_threads_report_true_flanks_and_d2_at_the_gauge_plane() {
    for (d, half, e1) in
        [("1/2-14 NPT", 30.0, 0.77843 * 25.4), ("R 1/2", 27.5, 19.793), ("Rc 1/2", 27.5, 19.793)]
    {
        let v =
            verify(&VerifySpec { insert: InsertChoice::Full, metrics: false, ..VerifySpec::of(d).unwrap() })
                .unwrap();
        let [a, b] = v.measurement.flank_angles;
        assert!((a - half).abs() < 1e-6 && (b - half).abs() < 1e-6, "{d}: {a} / {b}");
        assert!(
            (v.measurement.pitch_diameter - e1).abs() < 1e-3,
            "{d}: d2 {} against {e1}",
            v.measurement.pitch_diameter
        );
    }
}

/// Issue 27 (found writing Heidenhain's chained G33): a straight pass chained with its run-out
/// taper up and out of the thread made the last segment (the taper, climbing to X22) decide
/// whether the thread was cut inward; the outside thread was taken as an inside one and its
/// deeper passes (X18.8, X18.16 after X19.4) were noted as "cutting nothing".
#[test]
fn regression_a_chained_run_out_does_not_turn_an_outside_thread_inside() {
    let text = "G21 G97 S800 M3\nG0 X19.4 Z5\nG32 Z-18 F1.5\nG32 X22 Z-20\nG0 X24\nG0 Z5\nX18.8\nG32 Z-18 F1.5\nG32 X22 Z-20\nG0 X24\nG0 Z5\nX18.16\nG32 Z-18 F1.5\nG32 X22 Z-20\nG0 X24\nM30\n";
    let p = threadcheck::read_program(text, "runout.nc", threadcheck::Dialect::Fanuc).unwrap();
    assert_eq!(p.passes.len(), 6);
    let notes: Vec<String> = p.operations[0].notes.iter().map(|n| n.message.clone()).collect();
    assert!(notes.iter().all(|n| !n.contains("cuts nothing")), "{notes:?}");
}

/// Found reviewing the Heidenhain corrections: in a pass chained with its run-out (a straight
/// G32 to Z−18, then G32 X22 Z−20 climbing out), the correction named the run-out's X22 (the
/// last X of the chain), whose change leaves the thread as it was. The chain's longest segment
/// sets the word: the X18.16 that put the last pass at its depth. M20x1.5-6g's d2 band is
/// 18.854–18.994 (ISO 965-2), the middle 18.924; the last pass cuts d2 18.16 + 0.866025 = 19.026
/// with a full-profile insert, so X18.16 − 2·0.051 = X18.058, and the fixed program lands on
/// mid-tolerance.
#[test]
fn regression_a_chained_run_out_is_not_the_word_corrected() {
    let dir = crate::tempdir("runout-fix");
    let text = "G21 G97 S800 M3\nG0 X24 Z5\nX19.4\nG32 Z-18 F1.5\nG32 X22 Z-20\nG0 X24\nZ5\nX18.16\nG32 Z-18\nG32 X22 Z-20\nG0 X24\nZ5\nM30\n";
    std::fs::write(dir.join("chain.nc"), text).unwrap();
    let (v, _, fixed) =
        crate::fix_then_verify(&dir.join("chain.nc"), &["--thread", "M20x1.5-6g", "--insert", "full"]);
    let c = &v["operations"][0]["correction"];
    assert_eq!(
        (c["line"].as_u64(), c["was"].as_f64(), c["value"].as_f64()),
        (Some(8), Some(18.16), Some(18.058)),
        "{c}"
    );
    assert_eq!(fixed, text.replace("X18.16\n", "X18.058\n"));
}

/// Found reviewing the Heidenhain corrections: G31's correction named its end point X20 (moving
/// the whole thread) instead of its depth U. Our M20x1.5 DIN program's G31s cut to U−0.92 (d2
/// 18.16 + 0.866025 = 19.026, ISO 965-2's 6g band 18.854–18.994): U−0.92 − 0.051 = U−0.971, and
/// the chained G33's X18.16 (not its run-out's X22) to X18.058; the fixed program passes.
#[test]
fn regression_heidenhain_g31_is_corrected_in_its_depth_u() {
    let src = crate::data("programs/heidenhain-g31-g33.nc");
    let spec = ["--thread", "M20x1.5-6g", "--dialect", "heidenhain", "--insert", "full"];
    let (v, _, _) = crate::fix_then_verify(&src, &spec);
    let words: Vec<(String, f64)> = v["operations"]
        .as_array()
        .unwrap()
        .iter()
        .map(|op| {
            (
                op["correction"]["written"].as_str().unwrap().to_string(),
                op["correction"]["value"].as_f64().unwrap(),
            )
        })
        .collect();
    assert_eq!(words, [("U-0.92".into(), -0.971), ("U-0.92".into(), -0.971), ("X18.16".into(), 18.058)]);
}

/// Found checking that every test program's `--fix` lands on mid-tolerance: a correction that
/// makes a G92 run shallower changed only its last X, and an earlier pass deeper than the new
/// value still cut the thread too small. M12x1.75-6g (ISO 965-2: d2 10.679–10.829, middle 10.754)
/// with a full-profile insert: d2 = X + 0.57735·1.75 = X + 1.010363. The run ends at X9.6 (d2
/// 10.6104, −68.6 µm); the correction is X10.754 − 1.010363 = X9.744 (at 0.001), and the X9.7 before
/// it cuts deeper than that, so it is named and set to X9.744 too; X10.0 is not. The fixed program
/// passes with d2 10.754.
#[test]
fn regression_a_shallower_correction_moves_the_deeper_passes_too() {
    let dir = crate::tempdir("deeper-fix");
    let text =
        "G21 G97 S600 M3\nG0 X14 Z4\nG92 X11.4 Z-20 F1.75\nX10.6\nX10.0\nX9.7\nX9.6\nG0 X50 Z50\nM30\n";
    std::fs::write(dir.join("run.nc"), text).unwrap();
    let (v, after, fixed) =
        crate::fix_then_verify(&dir.join("run.nc"), &["--thread", "M12x1.75-6g", "--insert", "full"]);
    let c = &v["operations"][0]["correction"];
    assert_eq!((c["line"].as_u64(), c["value"].as_f64()), (Some(7), Some(9.744)), "{c}");
    assert_eq!(
        c["deeper"],
        serde_json::json!([{"line": 6, "column": 1, "written": "X9.7", "editable": true}])
    );
    assert!(
        c["text"].as_str().unwrap().contains("X9.7 at line 6:1 cuts deeper than that: set it to X9.744 too"),
        "{c}"
    );
    assert_eq!(fixed, text.replace("X9.7\nX9.6\n", "X9.744\nX9.744\n"));
    let d2 = crate::check_of(&after["operations"][0], "pitch_diameter");
    assert!((d2["value"].as_f64().unwrap() - 10.754).abs() < 0.001, "{d2}");
}

/// Found checking `--fix` on every test program: a pass chained with a run-out that climbs
/// steeper than 45° was refused as a wrong lead, though the program is sound. Fanuc takes a G32
/// taper's F along the longer axis: from X18.16 Z−18 to X24 Z−20 the radial travel 2.92 exceeds
/// the axial 2, so the axial lead is 1.5·2/2.92 = 1.027397 mm. LinuxCNC's G33 K runs along the
/// path: to X22 Z−20, 1.5·2/√(1.92² + 2²) = 1.082081 mm. Both segments are swept as they move, a
/// note names them, and the thread's d2 is the straight pass's: 18.16 + 0.866025 = 19.026.
#[test]
fn regression_a_steep_chained_run_out_is_not_a_wrong_lead() {
    let dir = crate::tempdir("steep-runout");
    let cases = [
        (
            "st.nc",
            "G21 G97 S800 M3\nG0 X24 Z5\nX18.16\nG32 Z-18 F1.5\nG32 X24 Z-20\nG0 X26\nM30\n",
            5,
            1.027397,
        ),
        (
            "lc.ngc",
            "G21 G7 G90\nS800 M3\nG0 X24 Z5\nX18.16\nG33 Z-18 K1.5\nG33 X22 Z-20 K1.5\nG0 X24\nM2\n",
            6,
            1.082081,
        ),
    ];
    for (name, text, line, lead) in cases {
        std::fs::write(dir.join(name), text).unwrap();
        let o = crate::run_in(
            &dir,
            &["verify", "--program", name, "--thread", "M20x1.5-6g", "--insert", "full", "--json", "-"],
        );
        assert_eq!(o.status.code(), Some(1), "{name}: {}", crate::stderr(&o));
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        let op = &v["operations"][0];
        let d2 = op["checks"].as_array().unwrap().iter().find(|c| c["feature"] == "pitch_diameter").unwrap();
        assert!((d2["value"].as_f64().unwrap() - 19.026).abs() < 0.0005, "{name}: {d2}");
        let want = format!("the taper segment at line {line} moves {lead} mm along Z per turn");
        assert!(op["notes"].to_string().contains(&want), "{name}: {}", op["notes"]);
    }
}

/// Found with the steep run-outs: a chained segment with another lead kept the phase of the
/// chain's first segment, so its helix jumped at the seam. The straight G32 from Z5 (lead 1.5)
/// reaches Z−18 after 23/1.5 = 15⅓ turns, its last crossing at Z−17.5; the run-out to X24 Z−20
/// (axial lead 1.5·2/2.92, F along X) must cross next after the remaining ⅔ turn: at
/// −18 − ⅔·1.027397 = −18.684932, not on the first segment's grid.
#[test]
fn regression_a_chained_segment_with_another_lead_continues_the_helix() {
    let text = "G21 G97 S800 M3\nG0 X24 Z5\nX18.16\nG32 Z-18 F1.5\nG32 X24 Z-20\nG0 X26\nM30\n";
    let p = threadcheck::read_program(text, "st.nc", threadcheck::Dialect::Fanuc).unwrap();
    let (a, b) = (&p.passes[0], &p.passes[1]);
    assert!((a.crossings(-18.0, -17.0).last().unwrap() + 17.5).abs() < 1e-9);
    let lead = 1.5 * 2.0 / 2.92;
    assert!((b.lead - lead).abs() < 1e-12);
    let c = b.crossings(-20.0, -18.0);
    assert_eq!(c.len(), 2, "{c:?}");
    assert!((c[0] - (-18.0 - 2.0 / 3.0 * lead)).abs() < 1e-9, "{c:?}");
}

/// Found right after the deeper-pass correction: on one G33 chain that steps down a taper
/// (X18.16 from Z0 to −10, a taper to X17.16 at −20, on to −30), the taper's X17.16 was named as
/// a pass "deeper" than the corrected X18.058, though it cuts another stretch of the thread.
/// Only words whose passes share Z with the corrected word's are compared.
#[test]
fn regression_a_taper_elsewhere_on_the_chain_is_not_a_deeper_pass() {
    let dir = crate::tempdir("chain-deeper");
    let text =
        "G90 G71 G0 X24 Z5\nG0 X18.16\nG33 Z-10 K1.5\nG33 X17.16 Z-20 K1.5\nG33 Z-30 K1.5\nG0 X24\nM30\n";
    std::fs::write(dir.join("chain.mpf"), text).unwrap();
    let o = crate::run_in(
        &dir,
        &["verify", "--program", "chain.mpf", "--thread", "M20x1.5-6g", "--insert", "full", "--json", "-"],
    );
    assert_eq!(o.status.code(), Some(1), "{}", crate::stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let c = &v["operations"][0]["correction"];
    assert_eq!((c["written"].as_str(), c["value"].as_f64()), (Some("X18.16"), Some(18.058)), "{c}");
    assert!(c.get("deeper").is_none(), "{c}");
}

/// The points of the first `<polygon>` or `<polyline>` after `id="{id}"` in `svg` (pixels).
fn first_points(svg: &str, id: &str) -> Vec<(f64, f64)> {
    let at = svg.find(&format!("id=\"{id}\"")).unwrap_or_else(|| panic!("no {id}"));
    // Within the group itself: an empty group's `points` would be the next element's.
    let rest = &svg[at..];
    let rest = &rest[..rest.find("</g>").unwrap_or(rest.len())];
    let p = rest.find("points=\"").unwrap_or_else(|| panic!("{id} draws nothing"));
    let pts = &rest[p + 8..p + 8 + rest[p + 8..].find('"').unwrap()];
    pts.split_whitespace()
        .map(|xy| {
            let (x, y) = xy.split_once(',').unwrap();
            (x.parse().unwrap(), y.parse().unwrap())
        })
        .collect()
}

/// Issue 43: `verify --program P --svg` drew no tolerance zone, basic profile, deviation plot
/// or full-length strip (the program's operations were verified without the spec that asks for
/// the picture). For a program of each dialect family, and for each of three operations in one
/// program: every element is drawn, and the zone's polygon brackets the measured d2's line in
/// the tooth panel (x 200–630).
#[test]
fn regression_the_program_picture_has_its_zone_plot_and_strip() {
    let cases: [(&str, &str, &str, usize); 7] = [
        ("programs/fanuc-g76-timing.nc", "M20x1.5-6g", "fanuc", 1),
        ("programs/haas-g76-metric.nc", "M20x2-6g", "haas", 1),
        ("programs/sinumerik-cycle97.mpf", "M20x2.5-6g", "sinumerik", 1),
        ("programs/shop/linuxcnc-g8-m10.ngc", "M10x1.5-6g", "linuxcnc", 1),
        ("programs/okuma-g33-repeats.min", "M20x1.5-6g", "okuma", 1),
        ("programs/mazak-g76.nc", "M30x2-6g", "mazak", 1),
        ("programs/heidenhain-g31-g33.nc", "M20x1.5-6g", "heidenhain", 3),
    ];
    for (program, thread, dialect, ops) in cases {
        let dir = tempdir("program-picture");
        let svg_path = dir.join("p.svg");
        let p = data(program);
        let o = run(&[
            "verify",
            "--thread",
            thread,
            "--program",
            p.to_str().unwrap(),
            "--dialect",
            dialect,
            "--insert",
            "full",
            "--svg",
            svg_path.to_str().unwrap(),
        ]);
        assert!(o.status.code().is_some_and(|c| c < 2), "{program}: {}", stderr(&o));
        let svg = std::fs::read_to_string(&svg_path).unwrap();
        let sections: Vec<&str> = svg.split("id=\"operation-").skip(1).collect();
        assert_eq!(sections.len(), ops, "{program}");
        for (k, op) in sections.iter().enumerate() {
            for id in [
                "tooth-tolerance-zone",
                "tooth-basic-profile",
                "window-tolerance-zone",
                "deviation-plot",
                "full-length",
            ] {
                assert!(op.contains(&format!("id=\"{id}\"")), "{program} operation {}: no {id}", k + 1);
            }
            // The chip chart gives each bar's value (the G76 sheet's five passes: five values).
            let values = op.matches("class=\"chip-value\"").count();
            assert!(values >= 1, "{program}: the chip chart has no values");
            if program.ends_with("fanuc-g76-timing.nc") {
                assert_eq!(values, 5, "{program}");
            }
            let zone = first_points(op, "tooth-tolerance-zone");
            assert!(zone.len() >= 4, "{program} operation {}: the zone has {} points", k + 1, zone.len());
            assert!(
                zone.iter().all(|&(x, _)| (199.0..=631.0).contains(&x)),
                "{program}: zone outside the tooth panel"
            );
            assert!(first_points(op, "tooth-basic-profile").len() >= 4, "{program}: no basic profile");
            // The measured d2's dimension line lies within the zone's height.
            let at = op
                .find("id=\"tooth-dim-pitch_diameter\"")
                .unwrap_or_else(|| panic!("{program}: no d2 label"));
            let tag = &op[op[..at].rfind('<').unwrap()..at + op[at..].find('>').unwrap()];
            let y: f64 = tag.split("y1=\"").nth(1).unwrap().split('"').next().unwrap().parse().unwrap();
            let (lo, hi) =
                zone.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &(_, y)| (a.min(y), b.max(y)));
            assert!(lo < y && y < hi, "{program} operation {}: d2 at y {y}, the zone spans {lo}–{hi}", k + 1);
        }
    }
}

/// Issue 43: `compare` printed one table of 13 columns, 180 characters a row; the chips and
/// the thread are two tables now, and the prose is wrapped: no line over 100 characters.
#[test]
fn regression_compare_text_fits_100_columns() {
    for thread in ["M10x1.5-6g", "Tr40x7-7e", "1/2-13 UNC-2A"] {
        let o = run(&["compare", "--thread", thread]);
        assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
        let text = stdout(&o);
        for line in text.lines() {
            assert!(line.chars().count() <= 100, "{thread}: {} characters: {line}", line.chars().count());
        }
        assert!(text.contains("chip 1st") && text.contains("verdict"), "{text}");
    }
}

/// Issue 43 (found by the thread-mill picture's zone test): the minimum-material side of the
/// tolerance zone was cut at its crest limit vertex by vertex, which tilted the flank from its
/// last vertex to the clamped one: at the pitch diameter the zone of M10x1.5-6g was drawn too
/// wide. Between the pitch diameter and the crest cut, each flank's band is (d2 max − d2 min)/2 ·
/// tan 30° = (8.994 − 8.862)/2 · 0.57735 = 0.038105 mm wide along Z (ISO 965-2's limits), read
/// back from the picture's own tick labels.
#[test]
fn regression_the_zone_keeps_its_flank_angle_up_to_the_crest_cut() {
    let dir = tempdir("zone-flank");
    let path = dir.join("v.svg");
    let o = run(&["verify", "--thread", "M10x1.5-6g", "--insert", "full", "--svg", path.to_str().unwrap()]);
    assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
    let svg = std::fs::read_to_string(&path).unwrap();
    let sc = Scales::of(&svg, "tooth");
    let want = 0.5 * (8.994 - 8.862) * 30f64.to_radians().tan() * sc.px_per_mm;
    // At d2 max, and halfway from it to d min 9.732 where the minimum-material crest is cut.
    for dia in [8.994 - 0.001, 0.5 * (8.994 + 9.732)] {
        for band in zone_bands(&svg, "tooth-tolerance-zone", sc.y_of_d(dia)) {
            assert!((band - want).abs() < 0.3, "Ø{dia}: band {band:.2} px, want {want:.2}");
        }
    }
}

/// Issue 48: `correct` rounded an inch thread's measured d2 to 0.0001 in before taking its
/// deviation: 1/2-13 UNC-2A measured at 11.4000 mm, 8.1 µm over d2 max 0.4485 in = 11.3919 mm
/// (ASME B1.1), was reported +7.6 µm (0.4488 in − 0.4485 in). In or out is decided at the
/// standard's resolution; the deviation is the true distance, as `verify` gives it.
#[test]
fn regression_correct_reports_an_inch_threads_true_deviation() {
    let o =
        run(&["correct", "--thread", "1/2-13 UNC-2A", "--insert", "full", "--measured-d2", "11.4", "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let dev = v["measured"]["deviation_um"].as_f64().unwrap();
    assert!((dev - 8.1).abs() < 1e-6, "{dev}");
}

/// Issue 47: two starts of M24xPh3P1.5 cut 1.0623 mm apart (the second cycle's start Z 7.0623
/// instead of 7.5) passed `2 of 2 starts` and got a correction. Each start's phase is its last
/// pass's Z crossing; the second lies 1.0623 mm from the first, not a whole number of pitches
/// (1.5): the starts fail naming the offset, and no correction is offered. At 1.5 apart they pass.
#[test]
fn regression_a_misplaced_start_fails_by_its_offset() {
    let dir = tempdir("misplaced-start");
    let program = |second: &str| {
        format!(
            "(M24XPH3P1.5-6G, TWO STARTS)\nG21 G97 S500 M3\nG0 X26 Z6\nG76 P010060 Q100 R0.05\nG76 X22.16 Z-20 P920 Q300 F3.0\nG0 X26 Z{second}\nG76 P010060 Q100 R0.05\nG76 X22.16 Z-20 P920 Q300 F3.0\nM30\n"
        )
    };
    for (name, second, ok) in [("good.nc", "7.5", true), ("bad.nc", "7.0623", false)] {
        std::fs::write(dir.join(name), program(second)).unwrap();
        let o = run_in(&dir, &["verify", "--program", name, "--insert", "full", "--json", "-"]);
        assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        let op = &v["operations"][0];
        let starts = check_of(op, "starts");
        assert_eq!(starts["ok"], ok, "{starts}");
        if !ok {
            assert_eq!(
                starts["note"],
                "a start lies 1.0623 mm along Z from start 1, not a whole number of pitches (1.5 mm)"
            );
            assert!(op["correction"].is_null());
        }
    }
}

/// Issue 47: a training lathe's file (Denford's simulator: `[BILLET X29.9 Z60` and `[TOOLDEF`
/// before the O-number, a DOS end-of-file byte at the end) was refused. The set-up lines are read
/// past with a note; BILLET's X is the blank of the thread the program turns no diameter for, so
/// the partial-profile insert leaves the crest at Ø29.9 (6g's d: 29.682–29.962); `--blank-diameter`
/// still wins.
#[test]
fn regression_a_simulator_s_billet_is_the_blank() {
    let dir = tempdir("billet");
    std::fs::write(
        dir.join("billet.nc"),
        b"[BILLET X29.9 Z60\n[TOOLDEF T01 D0\nO0030 (M30X2 ON A TRAINING LATHE)\nG21 G95 G97 S500 M3\nT0101\nG0 X32 Z5\nG76 P010060 Q100 R0.05\nG76 X27.546 Z-30 P1227 Q350 F2.0\nG0 X100 Z100\nM30\n\x1a",
    )
    .unwrap();
    let (_, v) = {
        let o = run_in(&dir, &["verify", "--program", "billet.nc", "--json", "-"]);
        assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
        (0, serde_json::from_slice::<serde_json::Value>(&o.stdout).unwrap())
    };
    let op = &v["operations"][0];
    assert_eq!(check_of(op, "major_diameter")["value"], 29.9);
    let notes: Vec<String> =
        op["notes"].as_array().unwrap().iter().map(|n| n.as_str().unwrap_or_default().to_string()).collect();
    assert!(
        notes.iter().any(|n| n
            == "the blank is the stock the program declares at line 1: Ø29.9 (--blank-diameter overrides)"),
        "{notes:?}"
    );
    let o = run_in(&dir, &["verify", "--program", "billet.nc", "--blank-diameter", "29.8", "--json", "-"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(check_of(&v["operations"][0], "major_diameter")["value"], 29.8);
}

/// Issue 47: a Swiss-type lathe's tool beyond the spindle axis writes every X negative; its G92
/// run was refused as "reaches or crosses the axis". It is read by its distance from the axis
/// (a note says so), its blank too, and corrected in its own sign: M10x1.5-6g with a full-profile
/// insert to has d2 = 9.02597 + (8.16 − 8.15970) = 9.02627 against 6g's middle 8.928, so
/// the last pass moves to |X| 8.16 − 0.09827 = 8.062, written.
#[test]
fn regression_negative_x_is_a_tool_beyond_the_axis() {
    let dir = tempdir("swiss");
    let text = "(M10X1.5-6G)\nG21 G99 G97 S2000 M3\nT0101\nG0 X-12 Z1\nG1 X-9.95 F0.1\nG1 Z-16\nG0 X-12\nZ1\nG92 X-9.6 Z-15 F1.5\nX-9.2\nX-8.8\nX-8.4\nX-8.16\nG0 X-12\nM30\n";
    std::fs::write(dir.join("swiss.nc"), text).unwrap();
    let o = run_in(&dir, &["verify", "--program", "swiss.nc", "--insert", "full", "--json", "-"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let op = &v["operations"][0];
    let d2 = check_of(op, "pitch_diameter")["value"].as_f64().unwrap();
    // To half a micrometre: the full-profile insert's root is rounded within the standard's limits.
    assert!((d2 - (9.025_97 + (8.16 - (10.0 - 1.226_869 * 1.5)))).abs() < 5e-4, "{d2}");
    // The same program on the near side of the axis cuts the same thread.
    std::fs::write(dir.join("near.nc"), text.replace("X-", "X")).unwrap();
    let o = run_in(&dir, &["verify", "--program", "near.nc", "--insert", "full", "--json", "-"]);
    let near: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(check_of(&near["operations"][0], "pitch_diameter")["value"].as_f64().unwrap(), d2);
    assert_eq!(check_of(op, "major_diameter")["value"], 9.95);
    assert!(
        op["operation"]["notes"].to_string().contains("the passes run at negative X"),
        "{}",
        op["operation"]
    );
    let o = run_in(&dir, &["verify", "--program", "swiss.nc", "--insert", "full", "--fix", "-"]);
    assert!(String::from_utf8(o.stdout).unwrap().contains("\nX-8.062\n"));
    // A pass that crosses the axis is still refused.
    std::fs::write(dir.join("cross.nc"), "G0 X10 Z1\nG32 X-1 Z-15 F1.5\nM30\n").unwrap();
    let o = run_in(&dir, &["verify", "--program", "cross.nc", "--thread", "M10x1.5-6g"]);
    assert_eq!(o.status.code(), Some(2));
}

/// Issue 47: blocks that begin with `/` (block delete) ran without a word, so a program whose
/// `/M30` preview line ends it never reached its G76, and the refusal did not say why. The
/// switch is taken as off, said in the notes and in that refusal; `--block-delete` skips them.
#[test]
fn regression_block_delete_is_a_stated_switch() {
    let dir = tempdir("block-delete");
    std::fs::write(
        dir.join("bd.nc"),
        "(M20X1.5-6G)\nG21 G97 S500 M3\nG0 X22 Z5\n/G0 X40\n/M30\nG76 P010060 Q100 R0.05\nG76 X18.16 Z-20 P920 Q300 F1.5\nM30\n",
    )
    .unwrap();
    let o = run_in(&dir, &["verify", "--program", "bd.nc", "--insert", "full"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        one_line_error(&o),
        "threadcheck: error: bd.nc:1:1: no thread-making operation in the program (looked for G32, G92 and G76, tapping cycles, and helices: G2/G3 with a Z change); bd.nc:4: 2 blocks begin with / (block delete): the control's switch is taken as off, so they run (--block-delete skips them)"
    );
    let o = run_in(&dir, &["verify", "--program", "bd.nc", "--insert", "full", "--block-delete"]);
    assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
    assert!(stdout(&o).contains(
        "note: bd.nc:4: 2 blocks begin with / (block delete) and are skipped, as --block-delete says"
    ));
    // A run of many takes the reading options too.
    let o = run_in(&dir, &["verify", ".", "--dialect", "fanuc", "--block-delete", "--insert", "full"]);
    assert!(stdout(&o).starts_with("./bd.nc:7: "), "{}", stdout(&o));
}

/// Issue 46: `thread-mill` (and `verify`'s milled section) read a mill-turn program as a
/// machining centre's toolpath, so the turning section's G76 threading cycle was said to be "a
/// drilling, tapping or boring cycle" read past. A milling toolpath of a program that shows
/// both machines is read as a mill-turn's: its G18 section as a lathe's.
#[test]
fn regression_thread_mill_reads_a_mill_turn_program_as_one() {
    let o = run(&[
        "thread-mill",
        "--program",
        data("machining/fanuc-mixed.nc").to_str().unwrap(),
        "--tools",
        data("machining/fanuc-mixed.toml").to_str().unwrap(),
    ]);
    assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(!out.contains("G76 read past"), "{out}");
    // Its G84 holes are checked: said as read, never "read past" (issue 59).
    assert!(out.contains("G84 (4 times): a drilling, tapping or boring cycle, read as its holes"), "{out}");
    assert!(!out.contains("G84 read past"), "{out}");
}

/// `tap` and `thread-mill` did not look for subprogram files (`verify` did): a program whose
/// holes or helices stand in `O2000.nc` (`M98 P2000`) had none. And a hole read from a
/// subprogram file was placed and named as the main program's (an error said `main.nc:3`, the
/// tap's comment was looked for above line 3 of the main program). Now each hole names its file,
/// and the comments are read above the call that runs it.
#[test]
fn regression_tap_and_thread_mill_read_subprogram_files() {
    let dir = tempdir("tap-subfile");
    std::fs::write(
        dir.join("main.nc"),
        "%\nO1000 (THE HOLES IN O2000)\nG17 G21 G90 G94\nT1 M6 (DRILL 6.8)\nG0 X0 Y0 S2000 M3\nG43 H1 Z25.\nG98 G81 Z-20. R2. F200. L0\nM98 P2000\nG80\nT2 M6 (TAP M8X1.25)\nG0 X0 Y0 S600 M3\nG43 H2 Z25.\nG98 G84 Z-15. R3. F750. L0\nM98 P2000\nG80\nM30\n%\n",
    )
    .unwrap();
    std::fs::write(dir.join("O2000.nc"), "%\nO2000 (THE HOLES)\nX20. Y0\nX-20. Y0\nM99\n%\n").unwrap();
    let o = run_in(&dir, &["tap", "--program", "main.nc"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("== G84 at line 3 of O2000.nc (X20 Y0), tool T2, tap M8X1.25-6H"), "{out}");
    assert!(out.contains("drilled by G81 at line 4 of O2000.nc, tool T1, Ø6.8"), "{out}");
    assert!(out.contains("named by the comment at line 10 (\"TAP M8X1.25\")"), "{out}");
    // The error at a subprogram's hole names its file.
    std::fs::write(dir.join("t.toml"), "[tools]\n2 = \"drill:6.8\"\n").unwrap();
    let o = run_in(&dir, &["tap", "--program", "main.nc", "--tools", "t.toml"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        one_line_error(&o).starts_with("threadcheck: error: O2000.nc:3:1: G84 with tool T2"),
        "{}",
        one_line_error(&o)
    );
    // Helices in a subprogram file: a Ø6 cutter on radius 7 mills D = 2·(7 + 3) = 20.
    let helices: String =
        (1..=10).map(|k| format!("G3 X7. Y0 Z{:.1} I-7. J0\n", -16.0 + 1.5 * f64::from(k))).collect();
    std::fs::write(
        dir.join("O3000.nc"),
        format!("%\nO3000 (THE HELICES)\nG1 X7. Y0 F150\n{helices}G1 X0 Y0\nM99\n%\n"),
    )
    .unwrap();
    std::fs::write(
        dir.join("mill.nc"),
        "%\nO1001\nG17 G21 G90 G94 G40\nG0 X0 Y0 Z5. S3000 M3\nG1 Z-16. F500\nM98 P3000\nG0 Z50.\nM30\n%\n",
    )
    .unwrap();
    let o = run_in(
        &dir,
        &[
            "thread-mill",
            "--program",
            "mill.nc",
            "--thread",
            "M20x1.5-6H",
            "--cutter-diameter",
            "6",
            "--json",
            "-",
        ],
    );
    assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!((v["measured"]["major_diameter"].as_f64().unwrap() - 20.0).abs() < 1e-4, "{v}");
}

/// Seen in Chromium on a real M10x1.5 nut program: a D2 0.3 µm under its limit, which passes at
/// the standard's 1 µm, was "rounds to the limit" in the picture's 60-pixel "off" column, running
/// over the verdict column ("rounds to the lim" over "ok"), and glued to the max column in the text
/// (`9.2060rounds to the limit`). A full-profile tip at D = 10 leaves D2 = 10 − 0.974279 =
/// 9.02572, under 6H's 9.026.
#[test]
fn a_value_that_rounds_to_its_limit_fits_its_column() {
    let dir = crate::tempdir("at-limit");
    let svg = dir.join("nut.svg");
    let o = crate::run(&[
        "verify",
        "--thread",
        "M10x1.5-6H",
        "--insert",
        "full",
        "--final-x",
        "10",
        "--svg",
        svg.to_str().unwrap(),
    ]);
    let out = crate::stdout(&o);
    assert!(out.contains("9.2060  rounds to the limit"), "{out}");
    let svg = std::fs::read_to_string(&svg).unwrap();
    let table = &svg[svg.find("check-table").unwrap()..];
    assert!(table.contains("\nat limit\n") && !table.contains("rounds to the limit"), "{table}");
}

/// Issue 65: a long program name wraps the picture's headline instead of cutting the verdict
/// off (it once ended `…` before the verdict, and the next step stopped mid-sentence): every
/// word of the headline, the operation's band and the verdict is in the picture, and nothing is
/// cut with an ellipsis.
#[test]
fn a_long_program_name_wraps_the_headline() {
    let dir = crate::tempdir("long-name");
    let name =
        format!("{}-1-2-13-unc-bolt-for-the-customer-drawing-4711-revision-c.nc", "very-long".repeat(8));
    std::fs::copy(crate::data("programs/haas-g76-1-2-13-unc.nc"), dir.join(&name)).unwrap();
    let o = crate::run_in(&dir, &["verify", "--program", &name, "--svg", "p.svg"]);
    assert!(o.status.code().is_some_and(|c| c < 2), "{}", crate::stderr(&o));
    let svg = std::fs::read_to_string(dir.join("p.svg")).unwrap();
    assert!(!svg.contains('…'), "a text cut with an ellipsis");
    let texts: Vec<String> = svg
        .split("<text")
        .skip(1)
        .map(|p| p[p.find('>').unwrap() + 1..p.find("</text>").unwrap()].trim().to_string())
        .collect();
    // A word longer than a line (the name) breaks inside itself: compared without the spaces.
    let all = texts.join("").replace(' ', "");
    for words in [
        format!("{name} (fanuc) — OUT OF TOLERANCE: 1 threading operation"),
        format!("operation 1 of 1: G76 at line 8 of {name} (fanuc), tool T5"),
    ] {
        assert!(all.contains(&words.replace(' ', "")), "{words} is not whole in the picture: {texts:?}");
    }
    assert!(texts.iter().all(|t| t.chars().count() <= 150), "a line too long for the picture");
}
