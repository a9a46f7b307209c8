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
