//! One test per bug, named after it: each failed on the code before its fix.

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
            ..VerifySpec::new("1/2-13 UNC-2A")
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
/// terms was refused as nesting too deeply. A sum is one level, whatever its length.
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
        let text =
            format!("#<lead>=[{sum}]\nG21 G18 G7\nG0 X12 Z5\nX9.2\nG33 Z-20 K#<lead>\nG0 X12\nZ5\nM2\n");
        let p = threadcheck::read_program(&text, "sum.ngc", threadcheck::Dialect::LinuxCnc).unwrap();
        assert_eq!(p.passes[0].lead, 1.5, "{terms} terms, LinuxCNC");
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
    let tail = "G7 G21 G18\nG0 X11 Z2\nG8\nG76 P1.5 Z-20 I-1 J#<j> K1.0\nM2\n";
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
    let text = "G7 G21 G18 G90\nG0 X20 Z3\nG1 Z-5 F0.1\n#<z0>=#<_z>\n#1=#<_x>\nG0 X[#1*2+2] Z[#<z0>+8]\nG76 P1.5 Z-20 I-1 J0.3 K1.0\nM2\n";
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
            &format!("G18 G21 G90\nG0 X11 Z2\n{g76}\nM2\n"),
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
    let tail = "G7 G21 G18\nG0 X11 Z2\nG8\nG76 P1.5 Z-20 I-1 J#<j> K1.0\nM2\n";
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
    let text = "G7 G21 G18 G90\nG0 X20 Z3\nG1 Z-5 F0.1\n#<j>=0.1\no1 if [#<_z> LT -4]\n#<j>=0.3\no1 endif\nG0 X22 Z3\nG76 P1.5 Z-20 I-1 J#<j> K1.0\nM2\n";
    let p = threadcheck::read_program(text, "cond.ngc", threadcheck::Dialect::LinuxCnc).unwrap();
    assert_eq!(p.passes.len(), 4);
}
