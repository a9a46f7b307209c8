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
