//! Issue 8: the bad-input corpus in tests/data/bad: exit code 2, exactly the expected line on
//! stderr, nothing on stdout, no hang, no file left behind.

use crate::*;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

#[test]
fn every_bad_input_gives_its_one_line_error() {
    let dir = data("bad");
    let mut cases: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "expect"))
        .collect();
    cases.sort();
    assert!(cases.len() >= 30, "only {} cases", cases.len());
    let before: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name()).collect();
    for case in &cases {
        let spec = std::fs::read_to_string(case).unwrap();
        let field = |k: &str| {
            spec.lines()
                .find_map(|l| l.strip_prefix(k))
                .unwrap_or_else(|| panic!("{case:?}: no {k}"))
                .to_string()
        };
        let args = field("args: ");
        let want = field("error: ");
        let mut child = Command::new(env!("CARGO_BIN_EXE_threadcheck"))
            .args(args.split_whitespace())
            .current_dir(&dir)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let start = Instant::now();
        // A hang guard, not a timing target: a case still running after 30 s has hung (a
        // loaded CI machine runs the 10M-block runaway cases in several seconds).
        while child.try_wait().unwrap().is_none() {
            if start.elapsed() > Duration::from_secs(30) {
                let _ = child.kill();
                panic!("{case:?}: hung");
            }
            std::thread::sleep(Duration::from_millis(5));
        }
        let out = child.wait_with_output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{case:?}");
        assert!(out.stdout.is_empty(), "{case:?}: stdout {:?}", String::from_utf8_lossy(&out.stdout));
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.trim_end(), want, "{case:?}");
        assert_eq!(err.trim_end().lines().count(), 1, "{case:?}");
    }
    let after: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(before, after, "a case left a file behind");
}

/// Issue 58 item 9: the 65th subprogram file's refusal had no place; it names the call's
/// `file:line:column` (line 66: the first line sets the plane, the calls follow).
#[test]
fn the_sixty_fifth_subprogram_file_is_refused_at_its_call() {
    let dir = tempdir("sub-files");
    let mut main = String::from("G18 G21 G90\n");
    for i in 1..=70 {
        std::fs::write(dir.join(format!("s{i}.ngc")), format!("o<s{i}> sub\nG0 X1\no<s{i}> endsub\n"))
            .unwrap();
        main.push_str(&format!("o<s{i}> call\n"));
    }
    main.push_str("M2\n");
    std::fs::write(dir.join("main.ngc"), main).unwrap();
    let o = run_in(&dir, &["verify", "--program", "main.ngc"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr(&o).trim_end(),
        "threadcheck: error: main.ngc:66:1: more than 64 subprogram files for one program: s65.ngc is one too many"
    );
}

/// Issue 58 item 9: a file named as a table that is no table (here a system file's kind of
/// line) is refused at its place with the reader's message alone: its text was quoted in the
/// error (`| 1 | root:x:0:0:…`), through the command line and the language server's
/// `tools_file` alike.
#[test]
fn a_file_that_is_no_table_is_not_quoted() {
    let dir = tempdir("no-table");
    std::fs::write(dir.join("passwd"), "root:x:0:0:secret-gecos:/root:/bin/bash\n").unwrap();
    std::fs::copy(data("whole/shaft.nc"), dir.join("shaft.nc")).unwrap();
    for flag in ["--tools", "--machine"] {
        let o = run_in(&dir, &["verify", "--program", "shaft.nc", flag, "passwd"]);
        assert_eq!(o.status.code(), Some(2));
        assert_eq!(
            stderr(&o).trim_end(),
            "threadcheck: error: passwd:1:40: key with no value, expected `=`",
            "{flag}"
        );
    }
    let framed = |s: &str| format!("Content-Length: {}\r\n\r\n{s}", s.len());
    let init = serde_json::json!({"jsonrpc": "2.0", "id": 1, "method": "initialize",
        "params": {"capabilities": {}, "initializationOptions": {"tools_file": dir.join("passwd").display().to_string()}}});
    let input = [framed(&init.to_string()), framed(r#"{"jsonrpc":"2.0","method":"exit"}"#)].concat();
    let mut out = Vec::new();
    threadcheck::lsp_run(std::io::Cursor::new(input.into_bytes()), &mut out).unwrap();
    let out = String::from_utf8(out).unwrap();
    assert!(out.contains("key with no value") && !out.contains("secret-gecos"), "{out}");
}

/// Issue 58 item 9: a subprogram file over the program limit (2 MiB) was refused at its own name
/// with no place; it is refused at the call's `file:line:column`.
#[test]
fn a_subprogram_file_over_the_limit_is_refused_at_its_call() {
    let dir = tempdir("sub-big");
    let line = format!("({})\n", "x".repeat(100));
    std::fs::write(dir.join("big.ngc"), format!("o<big> sub\n{}o<big> endsub\n", line.repeat(22_000)))
        .unwrap();
    std::fs::write(dir.join("main.ngc"), "G18 G21 G90\nG0 X10 Z5\no<big> call\nM2\n").unwrap();
    let o = run_in(&dir, &["verify", "--program", "main.ngc"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr(&o).trim_end(),
        "threadcheck: error: main.ngc:3:1: the subprogram file ./big.ngc: the program is larger than 2097152 bytes"
    );
}
