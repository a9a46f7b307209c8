//! Issue 4: programs read as the control would expand them. Expected values are derived in the
//! comments from each control's documented rule, never copied from threadcheck's output.

use crate::*;
use proptest::prelude::*;
use threadcheck::{read_program, Dialect};

fn prog(name: &str, d: Dialect) -> threadcheck::Program {
    let text = std::fs::read_to_string(data(&format!("programs/{name}"))).unwrap();
    read_program(&text, name, d).unwrap()
}

const IN: f64 = 25.4;

/// LinuxCNC G76 P0.05 Z-0.5 I-0.075 J0.008 K0.045 H3 R2.0 Q29.5 E0.05 L2 from X0.2 Z0.2 in inch
/// radius mode: the crest is at radius 0.2 − 0.075 = 0.125 in; pass n cuts to J·n^(1/2) while
/// that is below K (0.008·√31 = 0.04454 < 0.045 ≤ 0.008·√32 = 0.04525): 31 passes; then one at
/// K and H = 3 spring passes: 4 at full depth. Each starts depth·tan 29.5° further along −Z and
/// tapers out to the crest over the last E = 0.05 in.
#[test]
fn linuxcnc_g76_reference_example() {
    let p = prog("linuxcnc-g76.ngc", Dialect::LinuxCnc);
    assert_eq!(p.passes.len(), 35);
    let q = 29.5f64.to_radians().tan();
    for (i, pass) in p.passes.iter().enumerate() {
        let depth = if i < 31 { 0.008 * ((i + 1) as f64).sqrt() } else { 0.045 };
        let x = 2.0 * (0.125 - depth) * IN;
        assert!(
            (pass.x_start - x).abs() < 1e-9 && (pass.x_end - x).abs() < 1e-9,
            "pass {} X {}",
            i + 1,
            pass.x_start
        );
        assert!((pass.z_start - (0.2 - depth * q) * IN).abs() < 1e-9, "pass {} Z", i + 1);
        // The synchronised stretch ends at target_z − zoff = −0.5 + (K − depth)·tan Q.
        assert!((pass.z_end - (-0.5 + (0.045 - depth) * q) * IN).abs() < 1e-9, "pass {} end", i + 1);
        assert!((pass.lead - 0.05 * IN).abs() < 1e-12);
        assert!((pass.taper_out - 0.05 * IN).abs() < 1e-12 && pass.taper_in == 0.0);
        // The exit taper climbs to (K − depth) above the crest.
        assert!((pass.x_taper - 2.0 * (0.125 + 0.045 - depth) * IN).abs() < 1e-9);
        assert_eq!(pass.source_line, Some(6));
    }
}

/// Fanuc G76, k = 1.534, Δd = 0.4, Δd min = 0.5, d = 0.05: depth after pass n is
/// max(Δd·√n, previous + Δd min): 0.5, 1.0, then 1.5 passes the rough end k − d = 1.484 and is
/// cut there; one finishing pass (m = 01) at k. X = root + 2·(k − depth); the flank infeed shifts
/// each start by depth·tan 30° towards −Z. Without the clamp there would be 14 rough passes.
#[test]
fn fanuc_g76_minimum_step_clamps() {
    let p = prog("fanuc-g76-min-step.nc", Dialect::Fanuc);
    let depths = [0.5, 1.0, 1.484, 1.534];
    assert_eq!(p.passes.len(), depths.len());
    let t30 = 30f64.to_radians().tan();
    for (pass, d) in p.passes.iter().zip(depths) {
        assert!((pass.x_end - (16.933 + 2.0 * (1.534 - d))).abs() < 1e-9, "{pass:?}");
        assert!((pass.z_start - (5.0 - d * t30)).abs() < 1e-9);
        assert_eq!(pass.z_end, -30.0);
        assert_eq!(pass.lead, 2.5);
        // Line 7: `%`, the O line and five blocks come before it.
        assert_eq!(pass.source_line, Some(7));
        // Chamfer r = 00: no run-out.
        assert_eq!(pass.taper_out, 0.0);
    }
}

/// Fanuc G92 internal taper thread: R = radius(start) − radius(end) = −0.4, so each pass starts
/// 0.8 mm smaller on the diameter than it ends; the seven X-only blocks repeat the cycle.
#[test]
fn fanuc_g92_taper_internal_with_repeats() {
    let p = prog("fanuc-g92-taper-internal.nc", Dialect::Fanuc);
    let xs = [20.2, 20.4, 20.6, 20.7, 20.8, 20.9, 21.0, 21.05];
    assert_eq!(p.passes.len(), 8);
    for (i, (pass, x)) in p.passes.iter().zip(xs).enumerate() {
        assert!((pass.x_end - x).abs() < 1e-12 && (pass.x_start - (x - 0.8)).abs() < 1e-12, "{pass:?}");
        assert_eq!((pass.z_start, pass.z_end, pass.lead), (3.0, -25.0, 1.5));
        assert_eq!(pass.source_line, Some(5 + i));
    }
}

/// Fanuc G32 by hand: three passes from the X set before each; the last G32 block with X
/// continues the third pass's helix as a run-out from X10.6 at Z-20 to X12.4 at Z-21.5: a fourth
/// segment of the same chain, phased from the chain's start at Z5 (its F1.5 runs along Z, the
/// longer axis).
#[test]
fn fanuc_g32_sequence() {
    let p = prog("fanuc-g32.nc", Dialect::Fanuc);
    assert_eq!(p.operations.len(), 1);
    let xs = [11.4, 10.9, 10.6];
    assert_eq!(p.passes.len(), 4);
    for (pass, x) in p.passes.iter().zip(xs) {
        assert_eq!((pass.x_start, pass.x_end, pass.z_start, pass.z_end, pass.lead), (x, x, 5.0, -20.0, 1.5));
        assert_eq!(pass.z_phase, 5.0);
    }
    let out = &p.passes[3];
    assert_eq!(
        (out.x_start, out.x_end, out.z_start, out.z_end, out.z_phase, out.lead),
        (10.6, 12.4, -20.0, -21.5, 5.0, 1.5)
    );
    assert!((out.x_at(-20.75) - 11.5).abs() < 1e-12);
}

/// Regression (A3): a G33 chain straight → taper → straight keeps every segment: the deeper
/// stretch after the taper is cut at its own diameter, on the helix of the chain's start.
#[test]
fn g33_chain_keeps_the_stretch_after_a_taper() {
    let text = "G21 G18 G8 S500 M3\nG0 X25 Z2\nG33 K2 X25 Z-10\nG33 K2 X25 Z-20\nG33 X20 Z-30 K2.2360679775\nG33 K2 X20 Z-41\nG0 X30\nM2\n";
    let p = read_program(text, "chain.ngc", Dialect::LinuxCnc).unwrap();
    assert_eq!(p.passes.len(), 4);
    // Radius mode: X25 is Ø50. The taper drops 5 mm of radius over 10 mm of Z: K along the
    // line √125 = 11.18 mm per 10 mm of Z, so K2.2360679775 advances Z by 2 per revolution.
    let xs = [(50.0, 50.0), (50.0, 50.0), (50.0, 40.0), (40.0, 40.0)];
    for (pass, (a, b)) in p.passes.iter().zip(xs) {
        assert_eq!((pass.x_start, pass.x_end), (a, b));
        assert_eq!(pass.z_phase, 2.0);
        assert!((pass.lead - 2.0).abs() < 1e-9, "{}", pass.lead);
    }
    assert_eq!((p.passes[3].z_start, p.passes[3].z_end), (-30.0, -41.0));
    // Crossings of the last segment are on the helix from Z2: −32, −34, …, −40.
    assert_eq!(p.passes[3].crossings(-41.0, -30.5), vec![-32.0, -34.0, -36.0, -38.0, -40.0]);
}

/// Sinumerik: L9 P33 runs the subprogram 33 times; each run sets R3 = R3 − 0.05 from 21.7 and cuts
/// G33 at X = R3: X = 21.7 − 0.05·i, i = 1..33, ending at 20.05.
#[test]
fn sinumerik_r_parameter_subprogram_33_passes() {
    let p = prog("sinumerik-r-param-l9.mpf", Dialect::Sinumerik);
    assert_eq!(p.passes.len(), 33);
    for (i, pass) in p.passes.iter().enumerate() {
        let x = 21.7 - 0.05 * (i + 1) as f64;
        assert!((pass.x_start - x).abs() < 1e-9, "pass {}: {}", i + 1, pass.x_start);
        assert_eq!((pass.z_start, pass.z_end, pass.lead), (5.0, -30.0, 2.0));
        // The G33 block of L9 is line 13 of the listing.
        assert_eq!(pass.source_line, Some(13));
    }
}

/// CYCLE97 VARI 3 (external, constant cross-section), TDEP 1.534, FAL 0.05, NRC 8, NID 2: rough
/// depth i = 1.484·√(i/8), one finishing pass at 1.534, two idle passes; IANG 29.5 shifts each
/// start depth·tan 29.5° along the feed (−Z); run-in APP 3 before SPL 0, run-out ROP 2 past FPL.
#[test]
fn sinumerik_cycle97_constant_area() {
    let p = prog("sinumerik-cycle97.mpf", Dialect::Sinumerik);
    assert_eq!(p.passes.len(), 11);
    let t = 29.5f64.to_radians().tan();
    for (i, pass) in p.passes.iter().enumerate() {
        let d = if i < 8 { 1.484 * ((i + 1) as f64 / 8.0).sqrt() } else { 1.534 };
        assert!((pass.x_start - (20.0 - 2.0 * d)).abs() < 1e-9, "pass {}", i + 1);
        assert!((pass.z_start - (3.0 - d * t)).abs() < 1e-9, "pass {} z {}", i + 1, pass.z_start);
        assert_eq!((pass.z_end, pass.lead), (-32.0, 2.5));
    }
}

fn program_error(name: &str, text: &str, d: Dialect) -> String {
    read_program(text, name, d).unwrap_err().to_string()
}

#[test]
fn malformed_programs_name_file_line_column() {
    let cases = [
        (
            "unknown-word.nc",
            "G0 X22 Z5\nG76 P010060 Q100 R0.05\nG76 X16.933 Z-30 P1534 Q400 F2.5 Y2\n",
            "unknown-word.nc:3:34:",
            "word Y is not part of the second G76 block",
        ),
        (
            "no-first.nc",
            "G0 X22 Z5\nG76 X16.933 Z-30 P1534 Q400 F2.5\n",
            "no-first.nc:2:1:",
            "without its first block",
        ),
        ("no-f.nc", "G0 X14 Z5\nX11.4\nG32 Z-20\n", "no-f.nc:3:1:", "add F"),
        ("comma.nc", "G0 X14 Z5\nG32 Z-39,65 F1.5\n", "comma.nc:2:5:", "write Z-39.65"),
        ("point.nc", "G0 X22 Z5\nG76 P1.950 Q100 R0.05\n", "point.nc:2:5:", "P(m)(r)(a) is six digits"),
        ("nothing.nc", "G0 X10 Z5\nG1 Z-20 F0.2\nM30\n", "nothing.nc:1:1:", "no threading pass"),
    ];
    for (name, text, place, msg) in cases {
        let e = program_error(name, text, Dialect::Fanuc);
        assert!(e.starts_with(place), "{name}: {e}");
        assert!(e.contains(msg), "{name}: {e}");
        assert!(!e.contains('\n'));
    }
    let e = program_error(
        "loop.mpf",
        "N10 G0 X20 Z5\nN20 L9 P2\nN30 M30\nL9\nN10 L9\nN20 M17\n",
        Dialect::Sinumerik,
    );
    assert!(e.starts_with("loop.mpf:5:5:") && e.contains("nest deeper"), "{e}");
}

#[test]
fn passes_command_reads_a_program() {
    let o = run(&[
        "passes",
        "--program",
        data("programs/fanuc-g92-taper-internal.nc").to_str().unwrap(),
        "--dialect",
        "fanuc",
        "--json",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let p = v["passes"].as_array().unwrap();
    assert_eq!(p.len(), 8);
    for k in ["index", "x_start", "x_end", "z_start", "z_end", "lead", "start", "source_line"] {
        assert!(p[0].get(k).is_some(), "{k}");
    }
    assert_eq!(p[0]["source_line"], 5);
    assert_eq!(p[7]["x_end"], 21.05);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 600, ..ProptestConfig::default() })]

    /// No text makes the reader panic, in any dialect.
    #[test]
    fn reader_never_panics_on_random_text(s in "\\PC{0,120}", d in 0usize..3) {
        let dialect = [Dialect::Fanuc, Dialect::Sinumerik, Dialect::LinuxCnc][d];
        let _ = read_program(&s, "fuzz.nc", dialect);
    }

    /// Text made of G-code-like pieces, which reaches deeper into the cycles.
    #[test]
    fn reader_never_panics_on_gcode_like_text(
        parts in proptest::collection::vec(prop_oneof![
            Just("G0 X20 Z5\n".to_string()), Just("G76 P010060 Q100 R0.05\n".to_string()),
            Just("G76 X16 Z-30 P1500 Q300 F2\n".to_string()), Just("G92 X19 Z-20 F1.5\n".to_string()),
            Just("X18.5\n".to_string()), Just("G32 Z-10 F1\n".to_string()), Just("G33 Z-10 K1\n".to_string()),
            Just("R3=R3-0.1\n".to_string()), Just("L9 P3\n".to_string()), Just("M30\n".to_string()),
            Just("L9\n".to_string()), Just("M17\n".to_string()), Just("G8\n".to_string()),
            Just("G76 P0.05 Z-0.5 I-0.075 J0.008 K0.045 R2 Q29.5\n".to_string()),
            "[A-Z][-0-9.,]{0,6}[ ;\n]".prop_map(|s| s),
        ], 0..20),
        d in 0usize..3,
    ) {
        let dialect = [Dialect::Fanuc, Dialect::Sinumerik, Dialect::LinuxCnc][d];
        let _ = read_program(&parts.concat(), "fuzz.nc", dialect);
    }
}

/// CYCLE97 VARI 2 (internal, constant depth): DM is the tap-hole diameter and the cut goes
/// outwards; TDEP 0.812 (H1 of P 1.5) in 4 equal steps, no allowance, one idle pass:
/// X = 18.376 + 2·0.812·i/4, then once more at full depth.
#[test]
fn sinumerik_cycle97_internal_cuts_outwards_from_the_tap_hole() {
    let p = prog("sinumerik-cycle97-internal.mpf", Dialect::Sinumerik);
    assert_eq!(p.passes.len(), 5);
    for (i, pass) in p.passes.iter().enumerate() {
        let d = 0.812 * ((i + 1).min(4) as f64) / 4.0;
        assert!((pass.x_start - (18.376 + 2.0 * d)).abs() < 1e-9, "pass {}: {}", i + 1, pass.x_start);
        assert_eq!(pass.z_start, 2.0);
        assert_eq!(pass.z_end, -21.0);
    }
}

/// Issue 44: an empty NRC and NUMT of CYCLE97 are taken as 1 (one rough cut, a single start)
/// and the program says so: TDEP 1.534 less FAL 0.05 in one rough cut to 1.484, the finishing
/// cut at 1.534 and NID 1 idle pass. An empty VARI is refused (issue 64): the cycle's machining
/// type is 1 to 4 and the control stops on any other.
#[test]
fn cycle97_empty_nrc_numt_are_stated_defaults_and_an_empty_vari_is_refused() {
    let empty_vari = "G0 X25 Z10\nCYCLE97(2.5,,0,-30,20,20,3,2,1.534,0.05,0,0,,1,,)\nM30\n";
    let e = read_program(empty_vari, "d.mpf", Dialect::Sinumerik).unwrap_err().to_string();
    assert!(e.starts_with("d.mpf:2:1: CYCLE97 VARI empty or 0: the control refuses the cycle"), "{e}");
    let text = "G0 X25 Z10\nCYCLE97(2.5,,0,-30,20,20,3,2,1.534,0.05,0,0,,1,1,)\nM30\n";
    let p = read_program(text, "d.mpf", Dialect::Sinumerik).unwrap();
    let depths: Vec<f64> = p.passes.iter().map(|q| (20.0 - q.x_start) / 2.0).collect();
    assert_eq!(depths.len(), 3, "{depths:?}");
    for (d, want) in depths.iter().zip([1.484, 1.534, 1.534]) {
        assert!((d - want).abs() < 1e-9, "{depths:?}");
    }
    let said: Vec<String> = p
        .notes
        .iter()
        .chain(p.operations.iter().flat_map(|o| o.notes.iter()))
        .map(|n| n.to_string())
        .collect();
    assert!(said.iter().any(|n| n.contains("CYCLE97 NRC, NUMT empty or 0: taken as 1")), "{said:#?}");
}
