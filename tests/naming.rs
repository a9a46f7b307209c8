//! Issue 46 item 2, the thread named by the program: `verify --program P` without `--thread`
//! takes each operation's designation from the nearest comment above it (each dialect's comment
//! forms, shops' spellings), else the standard size of the lead and diameter it cuts (ISO 261 in
//! mm, ASME B1.1 in inches), with the standard's default class; `--thread` still wins. The
//! expected designations are read off the programs (their comments) and derived by hand for the
//! inferred ones (the last pass's tip on d3 = d − 2·0.613435·P on a bar).

use crate::*;

/// `verify --program tests/data/naming/NAME --json -` with `extra`: each operation's
/// (designation, designation_from, designation_line).
fn named(name: &str, extra: &[&str]) -> Vec<(String, String, Option<u64>)> {
    let program = data(&format!("naming/{name}"));
    let mut args = vec!["verify", "--program", program.to_str().unwrap()];
    args.extend(extra);
    args.extend(["--json", "-"]);
    let (_, v) = run_json(&args);
    v["operations"]
        .as_array()
        .unwrap()
        .iter()
        .map(|o| {
            (
                o["thread"]["designation"].as_str().unwrap().to_string(),
                o["designation_from"].as_str().unwrap().to_string(),
                o["designation_line"].as_u64(),
            )
        })
        .collect()
}

fn one(d: &str, from: &str, line: u64) -> (String, String, Option<u64>) {
    (d.to_string(), from.to_string(), Some(line))
}

/// Fanuc `(…)` in capitals two lines above the G76, the class as its own word: `6G` in a comment
/// that has no lower case is read as 6g, the class of the bar the passes cut (inward).
#[test]
fn a_comment_in_capitals_names_the_thread_and_its_class() {
    assert_eq!(named("fanuc-capitals.nc", &[]), [one("M24X2-6g", "comment", 6)]);
    let o = run(&["verify", "--program", data("naming/fanuc-capitals.nc").to_str().unwrap()]);
    let text = stdout(&o);
    assert!(
        text.contains("M24X2-6g: named by the comment at line 6 (\"THREAD M24X2 6G\"); comments are read without regard to case: its class 6G is read as 6g"),
        "{text}"
    );
}

/// Each dialect's comment: LinuxCNC's `;` (no class: 6g, the default for a bar), Sinumerik's `;`
/// with a decimal comma and the class as its own word (6H in a bore: CYCLE97 VARI 2), Heidenhain's
/// `[…]` with an inch mark (2A on a bar), Okuma's `(…)` with LH written without its hyphen.
#[test]
fn every_dialect_s_comment_names_the_thread() {
    assert_eq!(named("linuxcnc-semicolon.ngc", &[]), [one("M20x1.5-6g", "comment", 4)]);
    assert_eq!(named("sinumerik-gewinde.mpf", &[]), [one("M20x1.5-6H", "comment", 3)]);
    assert_eq!(
        named("heidenhain-brackets.nc", &["--dialect", "heidenhain"]),
        [one("1/2-13 UNC-2A", "comment", 5)]
    );
    assert_eq!(named("okuma-lh.min", &[]), [one("M30X2-LH-6g", "comment", 3)]);
}

/// No comment names a thread (`(COOLANT M8 ON)` is not one: no thread word): the lead 1.5 and
/// the last pass at X14.16 make d ≈ 14.16 + 2·0.613435·1.5 = 16.000, M16x1.5 of ISO 261, class
/// 6g. In inches: F.0769 (13 tpi to the increment) and X.4047 make d ≈ 10.279 + 2.397 = 12.676
/// mm, 1/2-13 UNC (12.700), class 2A.
#[test]
fn a_program_without_a_name_gets_the_standard_size_it_cuts() {
    assert_eq!(named("fanuc-inferred.nc", &[]), [one("M16x1.5-6g", "inferred", 8)]);
    assert_eq!(named("fanuc-inch-inferred.nc", &[]), [one("1/2-13 UNC-2A", "inferred", 7)]);
    let o = run(&["verify", "--program", data("naming/fanuc-inferred.nc").to_str().unwrap()]);
    assert!(
        stdout(&o).contains("M16x1.5-6g: inferred from the operation at line 8 (lead 1.5000 mm"),
        "{}",
        stdout(&o)
    );
}

/// A comment names the operations below it down to the next operation; a later operation with
/// no comment of its own takes the nearest comment above whose lead is its own (the roughing and
/// finishing G76 of M20x1.5), and one whose lead no comment has is inferred (2 mm at X27.546:
/// d ≈ 27.546 + 2.454 = 30.000, M30x2).
#[test]
fn a_later_operation_takes_the_comment_of_its_lead() {
    assert_eq!(
        named("fanuc-two-threads.nc", &[]),
        [one("M20X1.5-6g", "comment", 3), one("M20X1.5-6g", "comment", 3), one("M30x2-6g", "inferred", 15)]
    );
}

/// `--thread` still wins over the comment.
#[test]
fn the_given_thread_wins() {
    assert_eq!(
        named("fanuc-capitals.nc", &["--thread", "M24x2-4g6g"]),
        [("M24x2-4g6g".to_string(), "given".to_string(), None)]
    );
}

/// A lead no standard size has near the diameter cut: one line that says what to do.
#[test]
fn an_unnamed_nonstandard_thread_asks_for_its_name() {
    let dir = tempdir("naming-nonstandard");
    let p = dir.join("odd.nc");
    // Lead 1.7 mm: no ISO 261 size has it.
    std::fs::write(&p, "G0 X22 Z5\nG76 P010060 Q100 R0.05\nG76 X17.9 Z-20 P1040 Q300 F1.7\nM30\n").unwrap();
    let o = run(&["verify", "--program", p.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        one_line_error(&o),
        format!("threadcheck: error: {}:3:1: cannot name the thread: no size of ISO 261, ASME B1.1, BS 84, ISO 228-1 or ISO 2902 has a lead of 1.7000 mm and a major diameter within a thread depth of Ø19.986: name it (--thread, or a comment such as (M20X1.5) above the operation)", p.display())
    );
}

/// The comment scanner and the designation finder as a library: the words shops write.
#[test]
fn shops_spellings_are_read() {
    use threadcheck::{designation_in_comment, ParseOptions};
    let find = |c: &str| designation_in_comment(c, ParseOptions::default()).map(|f| f.text);
    assert_eq!(find("M10×1,25 TAP").as_deref(), Some("M10x1.25"));
    assert_eq!(find("1/2 BSP").as_deref(), Some("G1/2"));
    assert_eq!(find("BSPP 3/4").as_deref(), Some("G3/4"));
    assert_eq!(find("TR40X7-7E").as_deref(), Some("TR40X7-7e"));
    assert_eq!(find("1/4-18 NPT").as_deref(), Some("1/4-18 NPT"));
    assert_eq!(find("GEWINDE M12"), Some("M12".into()));
    assert_eq!(find("T12 M6 TOOL CHANGE"), None);
    assert_eq!(find("SPINDLE M3 S800"), None);
}

/// What a comment-free program must be named: its designation, or the words of its refusal.
type Named<'a> = Result<&'a str, &'a [&'a str]>;

/// A lathe program with no comment: G76 from X`crest` to the last pass at X`root` and lead `f`,
/// in mm (G21) or inches (G20), outside (`bore` false: passes inward) or in a bore.
fn bare_g76(units: &str, crest: &str, root: &str, f: &str, bore: bool) -> String {
    let start = if bore { "X0.1 Z5" } else { "X99 Z5" };
    let (start, crest) = if units == "G20" {
        (start.replace("X99", "X4").replace("X0.1", "X0.01"), crest)
    } else {
        (start.to_string(), crest)
    };
    format!(
        "{units} G18 G99\nT0101\nG97 S500 M3\nG0 {start}\nG0 X{crest} Z5\nG76 P010060 Q100 R0.01\nG76 X{root} Z-20 P600 Q150 F{f}\nG0 {start}\nM30\n"
    )
}

/// Issue 59 item 4: comment-free programs across the series are named by their diameters first
/// (the series whose size lies within a thread depth), then the nearest size of that series; two
/// series that fit alike are refused naming both, never guessed. Each root is the standard's
/// d3 (a bar: d − 2·h, h = 0.613435·P metric/unified, 0.640327·P Whitworth, P/2 + ac Tr) or D
/// (a bore), worked by hand.
#[test]
fn comment_free_programs_are_named_by_their_series_first() {
    let dir = tempdir("series");
    let cases: &[(&str, String, Named<'_>)] = &[
        // BSW 1/2: 12 tpi, d 0.5 in: root 0.5 − 2·0.640327/12 = 0.3933 in; 9/16-12 UNC (Ø14.29)
        // lies 1.6 mm away, beyond its thread depth 1.30 mm.
        ("bsw-half.nc", bare_g76("G20", ".5", ".3933", ".083333", false), Ok("BSW 1/2 medium")),
        // 1/2-13 UNC: root 0.5 − 2·0.613435/13 = 0.4056 in.
        ("unc-half.nc", bare_g76("G20", ".5", ".4056", ".076923", false), Ok("1/2-13 UNC-2A")),
        // 3/8-24 UNF: root 0.375 − 2·0.613435/24 = 0.3239 in.
        ("unf-3-8.nc", bare_g76("G20", ".375", ".3239", ".041667", false), Ok("3/8-24 UNF-2A")),
        // M20x1.5: root 20 − 1.8403 = 18.160.
        ("m20.nc", bare_g76("G21", "20", "18.16", "1.5", false), Ok("M20x1.5-6g")),
        // M12x1.75: root 12 − 2.1470 = 9.853.
        ("m12.nc", bare_g76("G21", "12", "9.853", "1.75", false), Ok("M12x1.75-6g")),
        // M8x1.25: root 8 − 1.5336 = 6.466.
        ("m8.nc", bare_g76("G21", "8", "6.466", "1.25", false), Ok("M8x1.25-6g")),
        // G1/2 (BSP, 14 tpi, d 20.955): root 20.955 − 2·0.640327·1.81429 = 18.632.
        ("g-half.nc", bare_g76("G21", "20.955", "18.632", "1.814", false), Ok("G1/2 A")),
        // Tr20x4 (ac 0.25): root 20 − 2·(2 + 0.25) = 15.5.
        ("tr20.nc", bare_g76("G21", "20", "15.5", "4", false), Ok("Tr20x4-7e")),
        // M30x2 in a bore: the last pass on D = 30.
        ("m30-bore.nc", bare_g76("G21", "27.8", "30", "2", true), Ok("M30x2-6H")),
        // 1-8: 1-8 UNC and BSW 1 are both Ø25.4 at 8 tpi; the passes cannot tell 60° from 55°.
        ("one-inch-8.nc", bare_g76("G20", "1", ".8467", ".125", false), Err(&["1-8 UNC", "BSW 1"])),
        // Ø50 at 1.3 mm: no standard size of any series.
        ("odd.nc", bare_g76("G21", "50", "48.4", "1.3", false), Err(&["cannot name the thread", "Ø"])),
    ];
    for (file, text, want) in cases {
        std::fs::write(dir.join(file), text).unwrap();
        let o = run_in(&dir, &["verify", "--program", file, "--json", "-"]);
        match want {
            Ok(designation) => {
                assert!(matches!(o.status.code(), Some(0 | 1)), "{file}: {}", stderr(&o));
                let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
                let op = &v["operations"][0];
                assert_eq!(op["thread"]["designation"], *designation, "{file}");
                assert_eq!(op["designation_from"], "inferred", "{file}");
            }
            Err(words) => {
                assert_eq!(o.status.code(), Some(2), "{file}: {}", stdout(&o));
                let e = stderr(&o);
                assert!(e.contains(&format!("{file}:7:1:")), "{file}: {e}");
                for w in *words {
                    assert!(e.contains(w), "{file}: {w} not in {e}");
                }
            }
        }
    }
}

/// Issue 59 item 4: a comment's class is read without regard to case, the operation's side
/// deciding: `(OD THREAD M24X2-6G deburr after)` over a bar is M24X2-6g (it was read as the
/// internal 6G, and the program refused).
#[test]
fn a_comment_s_class_is_read_without_regard_to_case() {
    let dir = tempdir("class-case");
    let text = bare_g76("G21", "24", "21.546", "2", false)
        .replace("T0101\n", "T0101 (OD THREAD M24X2-6G deburr after)\n");
    std::fs::write(dir.join("m24.nc"), text).unwrap();
    let o = run_in(&dir, &["verify", "--program", "m24.nc", "--json", "-"]);
    assert!(matches!(o.status.code(), Some(0 | 1)), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["operations"][0]["thread"]["designation"], "M24X2-6g");
}

/// Issue 59 item 4: an M24x3 bolt thread-milled with no G41/G42, the tool coming down outside
/// the helix (X30) and moving in to it: external, M24x3-6g. The Ø10 cutter's centre runs on
/// r = d3/2 + 5 = (24 − 2·0.613435·3)/2 + 5 = 15.1596 (it was named M42x3-6H, from 2r + 10).
#[test]
fn a_bolt_milled_without_compensation_is_named_by_its_approach() {
    let dir = tempdir("milled-bolt");
    let mut text =
        String::from("G21 G17 G90\nT1 M6\nS3000 M3\nG0 X30 Y0\nG0 Z5\nG1 Z-20 F500\nG1 X15.1596 F200\n");
    for k in 1..=6 {
        text.push_str(&format!("G3 X15.1596 Y0 I-15.1596 J0 Z{} F200\n", -20 + 3 * k));
    }
    text.push_str("G1 X30\nG0 Z50\nM30\n");
    std::fs::write(dir.join("bolt.nc"), text).unwrap();
    let o = run_in(&dir, &["thread-mill", "--program", "bolt.nc", "--cutter-diameter", "10", "--json", "-"]);
    assert!(matches!(o.status.code(), Some(0 | 1)), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["designation"], "M24x3-6g", "{}", stdout(&o));
    assert_eq!(v["designation_from"], "inferred");
}

/// Issue 61 item 6: a shop's inch comments name the tap and the drill: `(3/8-16 TAP)` is
/// 3/8-16 UNC (the Unified series whose standard size it is; class 2B, the default for a tapped
/// hole) and `(5/16 DRILL)` a 0.3125 in drill, 7.9375 mm, inside 3/8-16 UNC-2B's minor diameter
/// 0.3070–0.3210 in (ASME B1.1 table 2A: 7.798–8.153 mm): the tap passes. It was refused at the
/// G84 ("no tool table names" T2).
#[test]
fn inch_tap_and_drill_comments_name_the_tools() {
    let dir = tempdir("inch-comments");
    let program = "%\nO1000 (INCH TAP)\nG20 G17 G90\nT1 M6 (5/16 DRILL)\nS1000 M3\nG0 X0 Y0 Z0.2\nG81 Z-0.8 R0.1 F5.\nG80\nT2 M6 (3/8-16 TAP)\nS500 M3\nG0 X0 Y0 Z0.2\nG84 Z-0.6 R0.2 F31.25\nG80\nM30\n%\n";
    std::fs::write(dir.join("inch.nc"), program).unwrap();
    let o = run_in(&dir, &["verify", "--program", "inch.nc", "--json", "-"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(text.contains("3/8-16 UNC-2B"), "{text}");
    assert!(text.contains("the drill's diameter Ø7.9375 is the comment's at line 4"), "{text}");
}
