//! Issue 49: threadcheck where programs are made and run. SARIF and JUnit for a repository of
//! programs, the LinuxCNC filter and gate, the language server. Each runs its real protocol end
//! to end; the schemas' validation of the SARIF and JUnit documents is in the Python tests
//! (`python/tests/test_integrations.py`: `jsonschema` and `xmlschema` against
//! `tests/data/schemas/`).

use crate::*;

/// Our test programs in a folder, with a broken one whose place is known: line 3's bare `G` at
/// column 29.
fn library(tag: &str) -> std::path::PathBuf {
    let dir = tempdir(tag);
    let lib = dir.join("lib");
    std::fs::create_dir_all(&lib).unwrap();
    std::fs::copy(data("whole/plate.nc"), lib.join("plate.nc")).unwrap();
    std::fs::copy(data("whole/shaft.nc"), lib.join("shaft.nc")).unwrap();
    std::fs::write(lib.join("broken.nc"), "G0 X10 Z5\nG76 P010060 Q100 R0.05\nG76 X8 Z-10 P1000 Q300 F1.5 G\n")
        .unwrap();
    dir
}

/// SARIF: one result per failing check at the operation's line and column (the shaft's G76 at
/// 8:1, the plate's first helix at 28:1), one for the unreadable program at its place; every
/// result's rule is in the driver's rules. The shaft's M24x2-6g limits are ISO 965-1's (d2 =
/// 22.701, es = −38 µm, Td2 = 170 µm: 22.493 … 22.663).
#[test]
fn sarif_puts_each_failing_check_at_its_line_and_column() {
    let dir = library("sarif");
    let o = run_in(&dir, &["verify", "lib", "--format", "sarif"]);
    assert_eq!(o.status.code(), Some(2), "the broken program is the worst: {}", stderr(&o));
    let log: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(log["version"], "2.1.0");
    let run = &log["runs"][0];
    assert_eq!(run["tool"]["driver"]["name"], "threadcheck");
    assert_eq!(run["invocations"][0]["exitCode"], 2);
    let results = run["results"].as_array().unwrap();
    let at = |r: &serde_json::Value| {
        let l = &r["locations"][0]["physicalLocation"];
        (
            l["artifactLocation"]["uri"].as_str().unwrap().to_string(),
            l["region"]["startLine"].as_u64().unwrap(),
            l["region"]["startColumn"].as_u64().unwrap(),
            r["ruleId"].as_str().unwrap().to_string(),
        )
    };
    let found: Vec<_> = results.iter().map(at).collect();
    let want = |uri: &str, line, col, rule: &str| (uri.to_string(), line, col, rule.to_string());
    assert_eq!(
        found,
        vec![
            want("lib/broken.nc", 3, 29, "program.unreadable"),
            want("lib/plate.nc", 28, 1, "milled.not_checked"),
            want("lib/shaft.nc", 8, 1, "turned.pitch_diameter"),
            want("lib/shaft.nc", 8, 1, "turned.root_radius"),
            want("lib/shaft.nc", 8, 1, "turned.max_material"),
        ]
    );
    let d2 = results[2]["message"]["text"].as_str().unwrap();
    assert!(d2.starts_with("turned M24X2-6g: pitch diameter d2 "), "{d2}");
    assert!(d2.contains("limits 22.4930 … 22.6630 mm"), "{d2}");
    let rules: Vec<&str> =
        run["tool"]["driver"]["rules"].as_array().unwrap().iter().map(|r| r["id"].as_str().unwrap()).collect();
    for r in results {
        let i = r["ruleIndex"].as_u64().unwrap() as usize;
        assert_eq!(rules[i], r["ruleId"].as_str().unwrap());
    }
    // The same log to a file, beside the lines on standard output.
    let o = run_in(&dir, &["verify", "lib", "--sarif", "out.sarif"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stdout(&o).ends_with("2 programs read, 7 operations: 5 pass, 2 fail; 1 unreadable\n"));
    let again: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out.sarif")).unwrap()).unwrap();
    assert_eq!(again, log);
}

/// JUnit: a suite per program, a case per operation (the plate's four taps pass, its helices
/// fail unchecked; the shaft's turned thread fails, its tap passes), an error case for the
/// unreadable program; the counts add up.
#[test]
fn junit_has_a_case_per_operation() {
    let dir = library("junit");
    let o = run_in(&dir, &["verify", "lib", "--junit", "out.xml"]);
    assert_eq!(o.status.code(), Some(2));
    let xml = std::fs::read_to_string(dir.join("out.xml")).unwrap();
    assert!(xml.starts_with("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"), "{xml}");
    assert!(xml.contains("<testsuites name=\"threadcheck\" tests=\"8\" failures=\"2\" errors=\"1\">"), "{xml}");
    assert!(
        xml.contains("<testsuite name=\"lib/plate.nc\" tests=\"5\" failures=\"1\" errors=\"0\" skipped=\"0\" file=\"lib/plate.nc\">"),
        "{xml}"
    );
    assert!(xml.contains("<testcase name=\"line 18: tapped M8X1.25-6H\" classname=\"lib/plate.nc\"/>"), "{xml}");
    assert!(xml.contains("<testcase name=\"line 8: turned M24X2-6g\" classname=\"lib/shaft.nc\">"), "{xml}");
    assert!(xml.contains("<failure type=\"turned.pitch_diameter\" message=\"pitch diameter d2, root radius, GO gauge (max. material)\">lib/shaft.nc:8:1: pitch diameter d2 "), "{xml}");
    assert!(xml.contains("<error type=\"unreadable\" message=\"error: lib/broken.nc:3:29: word G has no number\"/>"), "{xml}");
    assert_eq!(xml.matches("<testcase ").count(), 8);
}

/// `--format`, `--sarif`, `--junit` and `--json-lines` need programs given as PROGRAM|FOLDER
/// (regression: `verify --program P --json-lines -` printed nothing and exited 0, clap's
/// `requires` on the positional list not holding); two documents on standard output are refused.
#[test]
fn sarif_and_junit_belong_to_a_run_of_programs() {
    let dir = library("sarif-refusals");
    for flag in [["--format", "sarif"], ["--sarif", "-"], ["--junit", "x.xml"], ["--json-lines", "-"]] {
        let o = run_in(&dir, &["verify", "--program", "lib/shaft.nc", flag[0], flag[1]]);
        assert_eq!(o.status.code(), Some(2), "{flag:?}");
        assert_eq!(
            one_line_error(&o),
            format!(
                "threadcheck: error: {} describes a run of programs: name them as PROGRAM|FOLDER (without --program)",
                flag[0]
            )
        );
    }
    let o = run_in(&dir, &["verify", "lib", "--format", "sarif", "--junit", "-"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(one_line_error(&o).lines().count(), 1);
}
