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
        text.contains("M24X2-6g: named by the comment at line 6 (\"THREAD M24X2 6G\"); the comment is in capitals: its class 6G is read as 6g"),
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
        format!("threadcheck: error: {}:3:1: no size of ISO 261 has a lead of 1.7000 mm and a major diameter near Ø19.986: name the thread (--thread, or a comment such as (M20X1.5) above the operation)", p.display())
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
