//! Issue 59 item 5: every suggestion names an option the command in use accepts. Messages carry
//! the options they suggest as `‹key›` markers, rendered for the command line as the flag; a key
//! the command in use lacks is named with the command that has it (`threadcheck tap --tap`).
//! Here every marker in `src/` is walked against the commands' clap definitions (their `--help`).

use crate::*;
use std::collections::BTreeSet;

/// Every command's flags, as keys (`--cutter-diameter` is `cutter_diameter`), read off `--help`.
fn flags_of(command: &str) -> BTreeSet<String> {
    let help = stdout(&run(&[command, "--help"]));
    help.lines()
        .filter_map(|l| {
            let l = l.trim_start();
            let l = l
                .strip_prefix("-")
                .filter(|r| r.chars().nth(1) == Some(','))
                .map_or(l, |r| r[2..].trim_start());
            let flag = l.strip_prefix("--")?;
            Some(flag.split(|c: char| !(c.is_ascii_alphanumeric() || c == '-')).next()?.replace('-', "_"))
        })
        .collect()
}

fn commands() -> Vec<String> {
    let help = stdout(&run(&["--help"]));
    help.lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| !l.trim().is_empty())
        .filter_map(|l| l.split_whitespace().next().map(str::to_string))
        .filter(|c| c != "help")
        .collect()
}

/// The `‹key›` markers of every source file.
fn markers() -> BTreeSet<(String, String)> {
    let mut out = BTreeSet::new();
    let mut stack = vec![std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src")];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(&dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "rs") {
                let text = std::fs::read_to_string(&p).unwrap();
                for piece in text.split('‹').skip(1) {
                    let Some(key) = piece.split('›').next() else { continue };
                    if !key.is_empty()
                        && key.chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
                    {
                        out.insert((key.to_string(), p.display().to_string()));
                    }
                }
            }
        }
    }
    out
}

/// Every key a message suggests is a flag of some command (or one of the few named here: keys of
/// the API alone, the renderer's own documentation).
#[test]
fn every_suggested_option_exists() {
    let all: BTreeSet<String> = commands().iter().flat_map(|c| flags_of(c)).collect();
    assert!(all.contains("thread") && all.contains("cutter_diameter") && all.contains("tap"), "{all:?}");
    // insert_toml: the API's text of an insert file (the command line's --insert reads the file);
    // designation: the API's key for `limits D`; key and x: the renderer's own doc example.
    let api_only = ["insert_toml", "designation", "key", "x"];
    let missing: Vec<_> =
        markers().into_iter().filter(|(k, _)| !all.contains(k) && !api_only.contains(&k.as_str())).collect();
    assert!(missing.is_empty(), "suggested options no command has: {missing:?}");
}

/// A key the command in use lacks is named with the command that has it: `verify` on a tapping
/// cycle whose tap no table names said "give --tap", which verify refuses.
#[test]
fn a_suggestion_names_the_command_that_takes_it() {
    let dir = tempdir("suggest");
    std::fs::write(
        dir.join("tap.nc"),
        "G21 G17 G90\nT2 M6\nS500 M3\nG0 X20 Y20 Z5\nG43 H2\nG84 Z-14 R3 F625\nG80\nM30\n",
    )
    .unwrap();
    assert!(!flags_of("verify").contains("tap") && flags_of("tap").contains("tap"));
    let e = stderr(&run_in(&dir, &["verify", "--program", "tap.nc"]));
    assert!(e.contains("give `threadcheck tap --tap`") && !e.contains("give --tap"), "{e}");
    assert!(e.contains("in --tools"), "verify's own flag stays as it is: {e}");
    let e = stderr(&run_in(&dir, &["tap", "--program", "tap.nc"]));
    assert!(e.contains("give --tap"), "{e}");
}

/// An inch program is offered an inch tap in its suggestions (it was offered tap:M10x1.5-6H and
/// the comment (TAP M10X1.5)), and the comment suggested is one the reader takes.
#[test]
fn an_inch_program_is_offered_an_inch_tap() {
    let dir = tempdir("suggest-inch");
    let program = "G20 G17 G90\nT2 M6\nS500 M3\nG0 X2 Y2 Z.2\nG43 H2\nG84 Z-.5 R.1 F25\nG80\nM30\n";
    std::fs::write(dir.join("inch.nc"), program).unwrap();
    let e = stderr(&run_in(&dir, &["tap", "--program", "inch.nc"]));
    assert!(
        e.contains("2 = \"tap:1/4-20 UNC-2B\"") && e.contains("(TAP 1/4-20 UNC)") && !e.contains("M10"),
        "{e}"
    );
    // The suggested comment, written above the cycle, names the tap: 1/4-20 at F25 and S500
    // (0.05 in a turn, 20 tpi) passes its feed check.
    std::fs::write(dir.join("named.nc"), program.replace("T2 M6\n", "(TAP 1/4-20 UNC)\nT2 M6\n")).unwrap();
    let o = run_in(&dir, &["tap", "--program", "named.nc"]);
    assert!(matches!(o.status.code(), Some(0 | 1)), "{}", stderr(&o));
    assert!(stdout(&o).contains("tap 1/4-20 UNC-2B"), "{}", stdout(&o));
}

/// Reports agree with themselves (issue 59 item 5): a Klartext block of M words alone sets the
/// spindle (its `M3` was "read past" beside the tapping check's "spindle clockwise (M3)"), and
/// the suggestion for a tap no table names is a comment in Klartext's own syntax.
#[test]
fn a_klartext_m3_block_is_read_and_suggestions_use_its_comments() {
    let dir = tempdir("klartext-m3");
    let program = "BEGIN PGM T MM\nBLK FORM 0.1 Z X+0 Y+0 Z-20\nBLK FORM 0.2 X+100 Y+100 Z+0\nTOOL CALL 5 Z S600\nM3\nL Z+50 R0 FMAX\nCYCL DEF 207 RIGID TAPPING ~\n  Q200=+2 ;SET-UP CLEARANCE ~\n  Q201=-14 ;DEPTH ~\n  Q239=+1.25 ;PITCH ~\n  Q203=+0 ;SURFACE COORDINATE ~\n  Q204=+50 ;2ND SET-UP CLEARANCE\nL X+20 Y+20 R0 FMAX M99\nL Z+50 R0 FMAX M30\nEND PGM T MM\n";
    std::fs::write(dir.join("t.h"), program).unwrap();
    let e = stderr(&run_in(&dir, &["tap", "--program", "t.h"]));
    assert!(
        e.contains("name the tap in a comment above the cycle: ; TAP M10X1.5") && !e.contains("(TAP"),
        "{e}"
    );
    std::fs::write(dir.join("named.h"), program.replace("TOOL CALL 5", "; TAP M10X1.25\nTOOL CALL 5"))
        .unwrap();
    let o = run_in(&dir, &["tap", "--program", "named.h"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(!out.contains("M3 read past") && out.contains("the spindle is clockwise (M3)"), "{out}");
}

/// Issue 58 item 9: a Klartext tapping cycle the control would not run is refused at its Q201
/// line, naming the parameter: DEPTH 0 (the TNC does not run the cycle) and a positive depth
/// (+1e9 passed as a hole).
#[test]
fn a_klartext_cycle_of_depth_zero_or_positive_is_refused_at_its_parameter() {
    let dir = tempdir("klartext-depth");
    let program = "BEGIN PGM T MM\n; TAP M10X1.25\nTOOL CALL 5 Z S600\nM3\nL Z+50 R0 FMAX\nCYCL DEF 207 RIGID TAPPING ~\n  Q200=+2 ;SET-UP CLEARANCE ~\n  Q201=-14 ;DEPTH ~\n  Q239=+1.25 ;PITCH ~\n  Q203=+0 ;SURFACE COORDINATE ~\n  Q204=+50 ;2ND SET-UP CLEARANCE\nL X+20 Y+20 R0 FMAX M99\nL Z+50 R0 FMAX M30\nEND PGM T MM\n";
    for (depth, words) in [
        ("+0", "Q201 (DEPTH) = 0: the control does not run a cycle of depth 0"),
        ("+1000000000", "a positive depth"),
    ] {
        std::fs::write(dir.join("t.h"), program.replace("Q201=-14", &format!("Q201={depth}"))).unwrap();
        let o = run_in(&dir, &["tap", "--program", "t.h"]);
        assert_eq!(o.status.code(), Some(2), "{depth}: {}", stdout(&o));
        let e = stderr(&o);
        assert!(e.contains("t.h:8:8: CYCL DEF 207") && e.contains(words), "{depth}: {e}");
    }
}
