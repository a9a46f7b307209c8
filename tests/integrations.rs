//! Issue 49: threadcheck where programs are made and run. SARIF and JUnit for a repository of
//! programs, the LinuxCNC filter and gate, the language server. Each runs its real protocol end
//! to end; the schemas' validation of the SARIF and JUnit documents is in the Python tests
//! (`python/tests/test_integrations.py`: `jsonschema` and `xmlschema` against
//! `tests/data/schemas/`).

use crate::*;
use std::path::Path;

/// The shaft of `tests/data/whole` with its G76 ending at X21.7 instead of X21.423: with the
/// full-profile insert assumed (no tool known, issue 59) d2 = 21.7 + (22.701 − 21.546) = 22.855,
/// over 6g's 22.663: a turned thread that fails on size whatever the insert's form.
fn failing_shaft() -> Vec<u8> {
    let text = std::fs::read_to_string(data("whole/shaft.nc")).unwrap();
    assert!(text.contains("G76 X21.423 "));
    text.replace("G76 X21.423 ", "G76 X21.7 ").into_bytes()
}

/// Our test programs in a folder (the shaft's thread failing), with a broken one whose place is
/// known: line 3's bare `G` at column 29.
fn library(tag: &str) -> crate::util::Scratch {
    let dir = tempdir(tag);
    let lib = dir.join("lib");
    std::fs::create_dir_all(&lib).unwrap();
    std::fs::copy(data("whole/plate.nc"), lib.join("plate.nc")).unwrap();
    std::fs::write(lib.join("shaft.nc"), failing_shaft()).unwrap();
    std::fs::write(
        lib.join("broken.nc"),
        "G0 X10 Z5\nG76 P010060 Q100 R0.05\nG76 X8 Z-10 P1000 Q300 F1.5 G\n",
    )
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
            want("lib/shaft.nc", 8, 1, "turned.major_diameter"),
            want("lib/shaft.nc", 8, 1, "turned.pitch_diameter"),
            want("lib/shaft.nc", 8, 1, "turned.max_material"),
            // What the assumed insert alone decides (issue 59): notes, never errors.
            want("lib/shaft.nc", 8, 1, "turned.minor_diameter.unverified"),
            want("lib/shaft.nc", 8, 1, "turned.root_radius.unverified"),
            want("lib/shaft.nc", 8, 1, "turned.crest.unverified"),
        ]
    );
    let levels: Vec<&str> = results.iter().map(|r| r["level"].as_str().unwrap()).collect();
    assert_eq!(levels, ["error", "error", "error", "error", "error", "note", "note", "note"]);
    assert!(results[6]["message"]["text"].as_str().unwrap().contains("unverified: root radius"));
    let d2 = results[3]["message"]["text"].as_str().unwrap();
    assert!(d2.starts_with("turned M24X2-6g: pitch diameter d2 "), "{d2}");
    assert!(d2.contains("limits 22.4930 … 22.6630 mm"), "{d2}");
    let rules: Vec<&str> = run["tool"]["driver"]["rules"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["id"].as_str().unwrap())
        .collect();
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
    assert!(
        xml.contains("<testsuites name=\"threadcheck\" tests=\"8\" failures=\"2\" errors=\"1\">"),
        "{xml}"
    );
    assert!(
        xml.contains("<testsuite name=\"lib/plate.nc\" tests=\"5\" failures=\"1\" errors=\"0\" skipped=\"0\" file=\"lib/plate.nc\">"),
        "{xml}"
    );
    assert!(
        xml.contains("<testcase name=\"line 18: tapped M8X1.25-6H\" classname=\"lib/plate.nc\"/>"),
        "{xml}"
    );
    assert!(xml.contains("<testcase name=\"line 8: turned M24X2-6g\" classname=\"lib/shaft.nc\">"), "{xml}");
    assert!(xml.contains("<failure type=\"turned.major_diameter\" message=\"major diameter d, pitch diameter d2, GO gauge (max. material)\">lib/shaft.nc:8:1: major diameter d "), "{xml}");
    assert!(
        xml.contains(
            "<error type=\"unreadable\" message=\"error: lib/broken.nc:3:29: word G has no number\"/>"
        ),
        "{xml}"
    );
    assert_eq!(xml.matches("<testcase ").count(), 8);
}

/// `--format`, `--sarif`, `--junit` and `--json-lines` describe a run of programs: one program
/// file given with `--program` is a run of one (issue 65), the same documents as naming it
/// (regression: `verify --program P --json-lines -` once printed nothing and exited 0); with
/// `--fix`, one program's, they are refused; two documents on standard output are refused.
#[test]
fn sarif_and_junit_belong_to_a_run_of_programs() {
    let dir = library("sarif-refusals");
    for flag in [["--format", "sarif"], ["--sarif", "-"], ["--json-lines", "-"], ["--format", "junit"]] {
        let one = run_in(&dir, &["verify", "--program", "lib/shaft.nc", flag[0], flag[1]]);
        let named = run_in(&dir, &["verify", "lib/shaft.nc", flag[0], flag[1]]);
        assert_eq!(one.status.code(), Some(1), "{flag:?}: {}", stderr(&one));
        assert!(!one.stdout.is_empty(), "{flag:?}");
        assert_eq!(stdout(&one), stdout(&named), "{flag:?}");
    }
    let o = run_in(&dir, &["verify", "--program", "lib/shaft.nc", "--fix", "f.nc", "--format", "sarif"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        one_line_error(&o),
        "threadcheck: error: --format describes a run of programs: name them as PROGRAM|FOLDER, or one program file with --program"
    );
    let o = run_in(&dir, &["verify", "lib", "--format", "sarif", "--junit", "-"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(one_line_error(&o).lines().count(), 1);
}

/// Code scanning (issue 65): each result's fingerprint names its file, the operation's process
/// and thread and its rule, never its line, so an edit that moves every line keeps them; the
/// rules carry a full description and help naming their guide.
#[test]
fn sarif_fingerprints_survive_an_edit_that_moves_lines() {
    let dir = library("sarif-fingerprints");
    let prints = |dir: &Path| -> Vec<(String, u64)> {
        let o = run_in(dir, &["verify", "lib", "--format", "sarif"]);
        let log: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
        log["runs"][0]["results"]
            .as_array()
            .unwrap()
            .iter()
            .map(|r| {
                (
                    r["partialFingerprints"]["threadcheck/v1"].as_str().unwrap().to_string(),
                    r["locations"][0]["physicalLocation"]["region"]["startLine"].as_u64().unwrap(),
                )
            })
            .collect()
    };
    let before = prints(&dir);
    // Three comment lines on top of the shaft: its results move three lines down.
    let shaft = dir.join("lib/shaft.nc");
    let text = std::fs::read_to_string(&shaft).unwrap();
    std::fs::write(&shaft, format!("(A)\n(B)\n(C)\n{text}")).unwrap();
    let after = prints(&dir);
    assert_eq!(before.len(), after.len());
    for (b, a) in before.iter().zip(&after) {
        assert_eq!(b.0, a.0);
        let moved = if b.0.starts_with("lib/shaft.nc|") { 3 } else { 0 };
        assert_eq!(a.1, b.1 + moved, "{}", b.0);
    }
    let keys: Vec<&str> = before.iter().map(|b| b.0.as_str()).collect();
    assert!(keys.contains(&"lib/shaft.nc|turned|M24X2-6g|turned.pitch_diameter|1"), "{keys:?}");
    assert!(keys.contains(&"lib/broken.nc|program.unreadable|1"), "{keys:?}");
    let mut unique = keys.clone();
    unique.sort_unstable();
    unique.dedup();
    assert_eq!(unique.len(), keys.len(), "every fingerprint its own");
    let o = run_in(&dir, &["verify", "lib", "--format", "sarif"]);
    let log: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    for rule in log["runs"][0]["tool"]["driver"]["rules"].as_array().unwrap() {
        let help = rule["help"]["text"].as_str().unwrap();
        let guide = help.trim_start_matches("See ").split(' ').next().unwrap();
        assert!(Path::new(env!("CARGO_MANIFEST_DIR")).join(guide).is_file(), "{rule}");
        assert!(rule["fullDescription"]["text"].as_str().unwrap().contains(rule["id"].as_str().unwrap()));
    }
}

/// What LinuxCNC's AXIS does with a `[FILTER]` program (`src/emc/usr_intf/axis/scripts/axis.py`,
/// `filter_program`, lines 1130–1165 at LinuxCNC commit 5c41560e): runs `sh -c "FILTER 'FILE'"`
/// (a `'` in the name written `'\''`) with `AXIS_PROGRESS_BAR=1` in the environment and no
/// standard input, the program's standard output into the file it then loads, and reads standard
/// error line by line: a line matching `^FILTER_PROGRESS=(\d*)$` moves the progress bar, every
/// other line is kept and shown in the "Filter failed" dialog when the exit code is not 0 (and
/// the program is then not loaded). Returns the exit code, the loaded bytes, the kept text and
/// the progress values. Written here from that description, not copied.
fn as_axis_runs(filter: &str, file: &std::path::Path) -> (i32, Vec<u8>, String, Vec<u32>) {
    use std::io::BufRead;
    let out_dir = tempdir("axis-filtered");
    let loaded = out_dir.join("filtered");
    let quoted = file.to_str().unwrap().replace('\'', "'\\''");
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(format!("{filter} '{quoted}'"))
        .env("AXIS_PROGRESS_BAR", "1")
        .stdin(std::process::Stdio::null())
        .stdout(std::fs::File::create(&loaded).unwrap())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let (mut kept, mut progress) = (String::new(), Vec::new());
    for line in std::io::BufReader::new(child.stderr.take().unwrap()).lines() {
        let line = line.unwrap();
        match line.strip_prefix("FILTER_PROGRESS=").filter(|d| d.chars().all(|c| c.is_ascii_digit())) {
            Some(d) => progress.push(d.parse().unwrap()),
            None => {
                kept.push_str(&line);
                kept.push('\n');
            }
        }
    }
    let code = child.wait().unwrap().code().unwrap();
    (code, std::fs::read(&loaded).unwrap(), kept, progress)
}

/// Issue 49 item 1: the filter as AXIS runs it. A program whose threads pass loads as it is
/// (every byte, a Latin-1 comment byte included; progress 0 then 100); one whose turned thread
/// fails (the shaft with the default partial insert: its root radius 0.04 mm under ISO 68-1's
/// 0.125·P = 0.25 mm) is refused with `--gate`, the dialog showing one located line; a program
/// threadcheck cannot read loads with its reason, unless `--strict`. A name with a quote in it
/// reaches the filter whole.
#[test]
fn the_filter_as_axis_runs_it() {
    let dir = tempdir("filter");
    let bin = env!("CARGO_BIN_EXE_threadcheck");
    let mut shaft = std::fs::read(data("whole/shaft.nc")).unwrap();
    // A comment byte of a Latin-1 editor (0xB0, the degree sign) in the tool's line.
    let at = shaft.windows(4).position(|w| w == b"(OD ").unwrap();
    shaft.splice(at + 1..at + 1, [0xB0u8, b' ']);
    let good = dir.join("shop's shaft.nc");
    std::fs::write(&good, &shaft).unwrap();
    let (code, loaded, kept, progress) = as_axis_runs(&format!("{bin} filter --gate --insert full"), &good);
    assert_eq!(code, 0, "{kept}");
    assert_eq!(loaded, shaft, "the program is loaded unchanged");
    assert_eq!(kept, "", "nothing to show");
    assert_eq!(progress, vec![0, 100]);

    // Given the partial insert, its sharp tip fails the root.
    let (code, loaded, kept, _) = as_axis_runs(&format!("{bin} filter --gate --insert partial"), &good);
    assert_eq!(code, 1);
    assert_eq!(loaded, shaft);
    let lines: Vec<&str> = kept.lines().collect();
    assert_eq!(lines.len(), 1, "{kept}");
    let place = format!("threadcheck: {}:8:1: FAIL turned M24X2-6g: ", good.display());
    assert!(lines[0].starts_with(&place), "{kept}");
    assert!(lines[0].contains("root radius 0.0400 mm, at least 0.2500 mm"), "{kept}");
    // Without --gate the same findings are printed and the program loads.
    let (code, _, kept_too, _) = as_axis_runs(&format!("{bin} filter --insert partial"), &good);
    assert_eq!((code, kept_too), (0, kept));

    let broken = dir.join("broken.ngc");
    std::fs::write(&broken, "G18 G21\nG0 X10 Z5\nG33 Z-10 K\n").unwrap();
    let (code, loaded, kept, _) = as_axis_runs(&format!("{bin} filter --gate"), &broken);
    assert_eq!(code, 0, "an unreadable program loads without --strict");
    assert_eq!(loaded, std::fs::read(&broken).unwrap());
    assert!(kept.starts_with(&format!("threadcheck: not checked: {}:3:", broken.display())), "{kept}");
    let (code, _, _, _) = as_axis_runs(&format!("{bin} filter --gate --strict"), &broken);
    assert_eq!(code, 2);

    let missing = dir.join("missing.ngc");
    let (code, _, kept, _) = as_axis_runs(&format!("{bin} filter --gate"), &missing);
    assert_eq!(code, 2);
    assert!(kept.starts_with("threadcheck: error: "), "{kept}");
}

/// `--msg`: each finding as a `(MSG, …)` line after the program's opening `%`, which LinuxCNC's
/// own interpreter reads as a message (rs274 prints `MESSAGE(…)`); the rest of the program
/// follows unchanged.
#[test]
fn the_filter_s_messages_are_read_by_linuxcnc() {
    let dir = tempdir("filter-msg");
    let program = dir.join("part.ngc");
    // A LinuxCNC lathe program whose G76 cuts far too shallow for M10x1.5: from the drive line
    // X12, I-2.15 puts the crest on the turned Ø9.85 and K0.2 the root at X9.65 (in G7 both are
    // diameters, as rs274 agrees: its last feed is at radius 4.825), where 6g's d3 is at most
    // 8.344 (ISO 965-1). K1.84 (root X8.01) cuts the thread in tolerance.
    let text = "%\n(M10X1.5 THREAD)\nG7 G18 G21 G90\nS500 M3\nG0 X9.85 Z2\nG1 Z-25 F0.1\nG0 X12 Z2\nG76 P1.5 Z-20 I-2.15 J0.05 K0.2 Q29.5 R1.5 H1 E0 L0\nG0 X20 Z20\nM2\n%\n";
    std::fs::write(dir.join("good.ngc"), text.replace("K0.2 ", "K1.84 ")).unwrap();
    let o = run_in(&dir, &["filter", "--msg", "--gate", "--insert", "full", "good.ngc"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(stdout(&o), text.replace("K0.2 ", "K1.84 "), "a passing program gets no message");
    std::fs::write(&program, text).unwrap();
    let o = run_in(&dir, &["filter", "--msg", "--insert", "full", "part.ngc"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let filtered = stdout(&o);
    let lines: Vec<&str> = filtered.lines().collect();
    assert_eq!(lines[0], "%");
    // One message per failing check: d2, d3, both flank angles, the GO gauge.
    let msgs: Vec<&str> = lines[1..].iter().copied().take_while(|l| l.starts_with("(MSG, ")).collect();
    assert_eq!(msgs.len(), 5, "{filtered}");
    assert!(
        msgs[0].starts_with("(MSG, threadcheck: part.ngc:8: FAIL turned M10X1.5-6g: pitch diameter d2 "),
        "{filtered}"
    );
    for m in &msgs {
        assert!(m.len() <= 254, "LinuxCNC reads lines of at most 254 bytes: {m}");
        assert!(!m[1..m.len() - 1].contains(['(', ')']), "one comment: {m}");
    }
    assert_eq!(&filtered[filtered.find("(M10X1.5").unwrap()..], &text[2..]);
    let written = dir.join("filtered.ngc");
    std::fs::write(&written, &filtered).unwrap();
    // With a tool table of its own: rs274 unpacked outside its package (tests/install-rs274.sh)
    // finds no default one and prints nothing without it.
    std::fs::write(dir.join("tool.tbl"), "T1 P1 D0 ;\n").unwrap();
    let canon = Command::new(crate::linuxcnc::rs274())
        .current_dir(&dir)
        .env("HOME", &*dir)
        .arg("-t")
        .arg(dir.join("tool.tbl"))
        .arg("-g")
        .arg(&written)
        .output()
        .unwrap();
    let canon = String::from_utf8_lossy(&canon.stdout).to_string();
    let shown: Vec<&str> = canon.lines().filter(|l| l.contains("MESSAGE(")).collect();
    assert_eq!(shown.len(), 5, "{canon}");
    assert!(
        shown[0].contains("MESSAGE(\" threadcheck: part.ngc:8: FAIL turned M10X1.5-6g: pitch diameter d2"),
        "{canon}"
    );
}

/// The M150 gate (`docs/guide/linuxcnc/M150`) as LinuxCNC runs a user M-code: `M150 P Q` with P
/// and Q as its arguments, the program stopped when it exits non-zero. Its one dependency on a
/// running LinuxCNC, `linuxcnc.stat().file` (the loaded program), is a stand-in module here that
/// answers what the GUI would; the threadcheck it calls is this build.
#[test]
fn the_m150_gate_stops_a_program_whose_thread_fails() {
    let dir = tempdir("m150");
    let bin_dir = dir.join("bin");
    std::fs::create_dir_all(&bin_dir).unwrap();
    std::os::unix::fs::symlink(env!("CARGO_BIN_EXE_threadcheck"), bin_dir.join("threadcheck")).unwrap();
    std::fs::write(
        dir.join("linuxcnc.py"),
        "import os\nclass stat:\n    def poll(self):\n        self.file = os.environ['LOADED']\n",
    )
    .unwrap();
    let shaft = dir.join("shaft.nc");
    std::fs::copy(data("whole/shaft.nc"), &shaft).unwrap();
    let broken = dir.join("broken.nc");
    std::fs::write(&broken, "G0 X10 Z5\nG76 P010060 Q100 R0.05\nG76 X8 Z-10 P1000 Q300 F1.5 G\n").unwrap();
    let m150 = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/guide/linuxcnc/M150");
    let gate = |loaded: &Path, flags: &str, p: &str| {
        let path = format!("{}:{}", bin_dir.display(), std::env::var("PATH").unwrap_or_default());
        Command::new(&m150)
            .args([p, "0"])
            .env("PATH", path)
            .env("PYTHONPATH", &dir)
            .env("LOADED", loaded)
            .env("THREADCHECK_FLAGS", flags)
            .output()
            .unwrap()
    };
    // The shaft's turned thread cut with the partial insert fails (its root radius).
    let o = gate(&shaft, "--insert partial", "0");
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("shaft.nc:8:1: FAIL turned M24X2-6g"), "{}", stderr(&o));
    assert_eq!(stdout(&o), "", "the program's copy is not printed");
    let o = gate(&shaft, "--insert full", "0");
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    // An unreadable program runs unless P1 asks for --strict.
    assert_eq!(gate(&broken, "", "0").status.code(), Some(0));
    assert_eq!(gate(&broken, "", "1").status.code(), Some(2));
}

/// A scripted language client: framed JSON-RPC messages over the server's standard input and
/// output (the Base Protocol's `Content-Length` header), each message read as JSON.
struct Client {
    child: std::process::Child,
    input: std::process::ChildStdin,
    output: std::io::BufReader<std::process::ChildStdout>,
    /// Notifications read while waiting for a response.
    notes: Vec<serde_json::Value>,
}

impl Client {
    fn start() -> Client {
        let mut child = Command::new(env!("CARGO_BIN_EXE_threadcheck"))
            .arg("lsp")
            .stdin(std::process::Stdio::piped())
            .stdout(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        let input = child.stdin.take().unwrap();
        let output = std::io::BufReader::new(child.stdout.take().unwrap());
        Client { child, input, output, notes: Vec::new() }
    }

    fn send_raw(&mut self, body: &str) {
        use std::io::Write;
        write!(self.input, "Content-Length: {}\r\n\r\n{body}", body.len()).unwrap();
        self.input.flush().unwrap();
    }

    fn send(&mut self, v: serde_json::Value) {
        self.send_raw(&v.to_string());
    }

    fn request(&mut self, id: i64, method: &str, params: serde_json::Value) -> serde_json::Value {
        self.send(serde_json::json!({"jsonrpc": "2.0", "id": id, "method": method, "params": params}));
        self.response(serde_json::json!(id))
    }

    fn notify(&mut self, method: &str, params: serde_json::Value) {
        self.send(serde_json::json!({"jsonrpc": "2.0", "method": method, "params": params}));
    }

    fn read(&mut self) -> serde_json::Value {
        use std::io::{BufRead, Read};
        let mut length = None;
        loop {
            let mut line = String::new();
            assert!(self.output.read_line(&mut line).unwrap() > 0, "the server closed its output");
            let line = line.trim_end();
            if line.is_empty() {
                break;
            }
            if let Some(n) = line.strip_prefix("Content-Length: ") {
                length = Some(n.parse::<usize>().unwrap());
            }
        }
        let mut body = vec![0; length.expect("a Content-Length header")];
        self.output.read_exact(&mut body).unwrap();
        serde_json::from_slice(&body).unwrap()
    }

    /// The response with this id; notifications before it are kept.
    fn response(&mut self, id: serde_json::Value) -> serde_json::Value {
        loop {
            let m = self.read();
            if m.get("method").is_some() {
                self.notes.push(m);
            } else {
                assert_eq!(m["id"], id, "responses come in order: {m}");
                return m;
            }
        }
    }

    /// The next `publishDiagnostics` (kept or read).
    fn diagnostics(&mut self) -> serde_json::Value {
        loop {
            if let Some(i) = self.notes.iter().position(|n| n["method"] == "textDocument/publishDiagnostics")
            {
                return self.notes.remove(i)["params"].clone();
            }
            let m = self.read();
            self.notes.push(m);
        }
    }

    /// A server started with `options`, one document (`uri`, `text`) opened, and its first
    /// diagnostics.
    fn with_document(options: serde_json::Value, uri: &str, text: &str) -> (Client, serde_json::Value) {
        let mut c = Client::start();
        c.request(1, "initialize", serde_json::json!({"capabilities": {}, "initializationOptions": options}));
        c.notify("initialized", serde_json::json!({}));
        c.notify(
            "textDocument/didOpen",
            serde_json::json!({"textDocument": {"uri": uri, "languageId": "gcode", "version": 1, "text": text}}),
        );
        let d = c.diagnostics();
        (c, d)
    }

    /// `shutdown`, then `exit`: the server ends with 0.
    fn finish(mut self) {
        self.request(99, "shutdown", serde_json::Value::Null);
        self.notify("exit", serde_json::Value::Null);
        assert_eq!(self.child.wait().unwrap().code(), Some(0));
    }
}

/// Issue 49 item 2: the language server through a scripted client exchange. The program is our
/// lathe shaft with its M24x2 thread cut too shallow (last pass X21.9 where ISO 965-1's 6g puts
/// d3 at most 21.797 and d2 at most 22.663): the diagnostic sits on the G76 (line 8, characters
/// 0–3), the hover lists the checks against the standard's limits, the quick fix rewrites the
/// X word in place (characters 4–9), and the text so corrected passes. Two changes sent at once
/// are verified as the newer one. A message that is not JSON is answered with the parse error
/// and the server reads on; an unknown method, bad parameters and a request before initialize
/// get the protocol's errors; `shutdown` then `exit` ends it with 0.
#[test]
fn the_language_server_through_a_scripted_client() {
    let dir = tempdir("lsp");
    let path = dir.join("shaft.nc");
    let uri = format!("file://{}", path.display());
    let shaft = std::fs::read_to_string(data("whole/shaft.nc")).unwrap();
    let shallow = shaft.replace("G76 X21.423 ", "G76 X21.9 ");
    let mut c = Client::start();

    let early = c.request(0, "textDocument/hover", serde_json::json!({}));
    assert_eq!(early["error"]["code"], -32002, "{early}");

    let init = c.request(
        1,
        "initialize",
        serde_json::json!({"capabilities": {}, "initializationOptions": {"insert": "full"}}),
    );
    let caps = &init["result"]["capabilities"];
    assert_eq!(caps["textDocumentSync"], 1, "whole documents");
    assert_eq!(caps["hoverProvider"], true);
    assert_eq!(caps["codeActionProvider"], true);
    c.notify("initialized", serde_json::json!({}));

    c.notify(
        "textDocument/didOpen",
        serde_json::json!({"textDocument": {"uri": uri, "languageId": "gcode", "version": 1, "text": shallow}}),
    );
    let d = c.diagnostics();
    assert_eq!(d["uri"], uri);
    assert_eq!(d["version"], 1);
    let diags = d["diagnostics"].as_array().unwrap();
    assert_eq!(diags.len(), 2, "the turned thread and the tap: {d}");
    let turned = &diags[0];
    assert_eq!(
        turned["range"],
        serde_json::json!({"start": {"line": 7, "character": 0}, "end": {"line": 7, "character": 3}})
    );
    assert_eq!(turned["severity"], 1, "an error");
    assert_eq!(turned["source"], "threadcheck");
    let message = turned["message"].as_str().unwrap();
    assert!(message.starts_with("threadcheck: FAIL turned M24X2-6g (named: comment): "), "{message}");
    assert!(message.contains("pitch diameter d2"), "{message}");
    assert_eq!(diags[1]["range"]["start"], serde_json::json!({"line": 18, "character": 0}), "the G84");
    assert_eq!(diags[1]["severity"], 3, "the tap passes: information");

    let hover = c.request(
        2,
        "textDocument/hover",
        serde_json::json!({"textDocument": {"uri": uri}, "position": {"line": 7, "character": 1}}),
    );
    let md = hover["result"]["contents"]["value"].as_str().unwrap();
    assert!(md.starts_with("**G76 M24X2-6g**"), "{md}");
    assert!(md.contains("**FAIL**"), "{md}");
    assert!(md.contains("- ✗ pitch diameter d2 ") && md.contains("limits 22.4930 … 22.6630 mm"), "{md}");
    let none = c.request(
        3,
        "textDocument/hover",
        serde_json::json!({"textDocument": {"uri": uri}, "position": {"line": 2, "character": 0}}),
    );
    assert_eq!(none["result"], serde_json::Value::Null, "no operation on line 3");

    let actions = c.request(
        4,
        "textDocument/codeAction",
        serde_json::json!({"textDocument": {"uri": uri}, "range": {"start": {"line": 7, "character": 0}, "end": {"line": 7, "character": 0}}, "context": {"diagnostics": []}}),
    );
    let action = &actions["result"][0];
    assert_eq!(action["kind"], "quickfix");
    let edit = &action["edit"]["changes"][&uri][0];
    assert_eq!(
        edit["range"],
        serde_json::json!({"start": {"line": 7, "character": 4}, "end": {"line": 7, "character": 9}})
    );
    let new_x = edit["newText"].as_str().unwrap().to_string();
    assert!(new_x.starts_with('X'), "{edit}");
    let corrected = shallow.replace("G76 X21.9 ", &format!("G76 {new_x} "));

    // Two changes at once: a broken text, then the corrected one.
    let broken = format!("{shallow}G76 X8 Z-10 P1000 Q300 F1.5 G\n");
    c.notify(
        "textDocument/didChange",
        serde_json::json!({"textDocument": {"uri": uri, "version": 2}, "contentChanges": [{"text": broken}]}),
    );
    c.notify("textDocument/didChange", serde_json::json!({"textDocument": {"uri": uri, "version": 3}, "contentChanges": [{"text": corrected}]}));
    let mut d = c.diagnostics();
    while d["version"] != 3 {
        assert_eq!(d["version"], 2, "versions in order: {d}");
        d = c.diagnostics();
    }
    let diags = d["diagnostics"].as_array().unwrap();
    assert_eq!(diags[0]["severity"], 3, "the corrected thread passes: {d}");
    assert!(diags[0]["message"].as_str().unwrap().starts_with("threadcheck: PASS turned M24X2-6g"), "{d}");

    // A broken text's diagnostic sits at its error's place.
    c.notify("textDocument/didChange", serde_json::json!({"textDocument": {"uri": uri, "version": 4}, "contentChanges": [{"text": "G0 X10 Z5\nG76 X8 Z-10 P1000 Q300 F1.5 G\n"}]}));
    let d = c.diagnostics();
    assert_eq!(d["version"], 4);
    assert_eq!(d["diagnostics"][0]["code"], "program.unreadable");
    assert_eq!(d["diagnostics"][0]["range"]["start"], serde_json::json!({"line": 1, "character": 28}), "{d}");

    c.send_raw("{\"jsonrpc\": \"2.0\", \"id\": 5, \"method\": }");
    let parse = c.response(serde_json::Value::Null);
    assert_eq!(parse["error"]["code"], -32700, "{parse}");
    let unknown = c.request(6, "textDocument/rename", serde_json::json!({}));
    assert_eq!(unknown["error"]["code"], -32601, "{unknown}");
    let bad = c.request(7, "textDocument/hover", serde_json::json!({"textDocument": {"uri": uri}}));
    assert_eq!(bad["error"]["code"], -32602, "{bad}");

    let down = c.request(8, "shutdown", serde_json::Value::Null);
    assert_eq!(down["result"], serde_json::Value::Null);
    c.notify("exit", serde_json::Value::Null);
    assert_eq!(c.child.wait().unwrap().code(), Some(0));
}

/// Without `shutdown` first, `exit` (or the end of the input) ends the server with 1, as the
/// protocol says; options verify does not take are refused at initialize.
#[test]
fn the_language_server_exits_as_the_protocol_says() {
    let mut c = Client::start();
    let init = c.request(
        1,
        "initialize",
        serde_json::json!({"capabilities": {}, "initializationOptions": {"wire": 1}}),
    );
    assert_eq!(init["error"]["code"], -32602, "{init}");
    assert!(init["error"]["message"].as_str().unwrap().contains("verify takes no argument 'wire'"), "{init}");
    c.notify("exit", serde_json::Value::Null);
    assert_eq!(c.child.wait().unwrap().code(), Some(1));
    let mut c = Client::start();
    drop(c.input);
    assert_eq!(c.child.wait().unwrap().code(), Some(1));
}

/// The guide's git pre-commit hook, as the guide prints it (`docs/guide/where-programs-live.md`),
/// in a repository of its own: a commit whose program's thread fails is refused (git aborts on the
/// hook's exit 1), one whose threads pass goes in, one with no program needs no check.
#[test]
fn the_guide_s_pre_commit_hook_refuses_a_failing_thread() {
    let guide = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/guide/where-programs-live.md"),
    )
    .unwrap();
    let after = &guide[guide.find("**pre-commit hook**").unwrap()..];
    let start = after.find("```sh\n").unwrap() + "```sh\n".len();
    let hook = &after[start..start + after[start..].find("```").unwrap()];
    assert!(hook.starts_with("#!/bin/sh\n"), "{hook}");
    let dir = tempdir("pre-commit");
    let bin_dir = dir.join("bin");
    std::fs::create_dir_all(&bin_dir).unwrap();
    std::os::unix::fs::symlink(env!("CARGO_BIN_EXE_threadcheck"), bin_dir.join("threadcheck")).unwrap();
    let repo = dir.join("repo");
    std::fs::create_dir_all(&repo).unwrap();
    let path = format!("{}:{}", bin_dir.display(), std::env::var("PATH").unwrap_or_default());
    let git = |args: &[&str]| {
        Command::new("git")
            .args(["-c", "user.name=t", "-c", "user.email=t@example.com", "-c", "commit.gpgsign=false"])
            .args(args)
            .current_dir(&repo)
            .env("PATH", &path)
            .output()
            .unwrap()
    };
    assert!(git(&["init", "-q"]).status.success());
    let hook_file = repo.join(".git/hooks/pre-commit");
    std::fs::write(&hook_file, hook).unwrap();
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&hook_file, std::fs::Permissions::from_mode(0o755)).unwrap();

    std::fs::write(repo.join("notes.txt"), "no program here\n").unwrap();
    git(&["add", "notes.txt"]);
    assert!(git(&["commit", "-qm", "notes"]).status.success());
    // The shaft fails its turned thread (d2, X21.7).
    std::fs::write(repo.join("shaft.nc"), failing_shaft()).unwrap();
    git(&["add", "shaft.nc"]);
    let o = git(&["commit", "-qm", "shaft"]);
    assert!(!o.status.success(), "the hook refuses it");
    // git shows a hook's output on its standard error.
    assert!(stderr(&o).contains("shaft.nc:8: FAIL turned M24X2-6g"), "{}{}", stdout(&o), stderr(&o));
    // A program whose one tap passes (M8x1.25 after a Ø6.8 drill, ISO 2306's tap drill, F625 at
    // S500 = 1.25 mm a turn) goes in.
    std::fs::write(repo.join("tapped.nc"), "(TAP M8X1.25)\nG21 G17 G90\nT2 M6 (DRILL 6.8)\nS1000 M3\nG0 X20 Y20 Z5\nG43 H2\nG81 Z-20 R3 F100\nG80\nT3 M6 (TAP M8X1.25)\nM29 S500\nG0 X20 Y20 Z5\nG43 H3\nG84 Z-14 R3 F625\nG80\nM30\n").unwrap();
    git(&["reset", "-q", "shaft.nc"]);
    git(&["add", "tapped.nc"]);
    let o = git(&["commit", "-qm", "tapped"]);
    assert!(o.status.success(), "{}{}", stdout(&o), stderr(&o));
}

/// A document saved on this computer finds its subprograms' files as `verify` does (its folder,
/// and the editor's `subroutine_path`): the G76 in `lib/thr.ngc` is checked and its diagnostic,
/// at the document's first line, names its file's line; without the path the call's line says
/// where it looked.
#[test]
fn the_language_server_finds_subroutine_files() {
    let dir = tempdir("lsp-sub");
    std::fs::create_dir_all(dir.join("lib")).unwrap();
    std::fs::write(
        dir.join("lib/thr.ngc"),
        "o<thr> sub\nG76 P1.5 Z-20 I-2.15 J0.05 K#1 Q29.5 R1.5 H1 E0 L0\no<thr> endsub\n",
    )
    .unwrap();
    let text = "(M10X1.5 THREAD)\nG7 G18 G21 G90\nS500 M3\nG0 X9.85 Z2\nG1 Z-25 F0.1\nG0 X12 Z2\no<thr> call [1.84]\nM2\n";
    let uri = format!("file://{}", dir.join("main.ngc").display());
    for (options, opened) in [
        (
            serde_json::json!({"insert": "full", "subroutine_path": dir.join("lib").display().to_string()}),
            true,
        ),
        (serde_json::json!({"insert": "full"}), false),
    ] {
        let (c, d) = Client::with_document(options, &uri, text);
        let first = &d["diagnostics"][0];
        if opened {
            assert_eq!(first["severity"], 3, "the thread passes: {d}");
            assert!(
                first["message"].as_str().unwrap().starts_with("threadcheck: PASS turned M10X1.5-6g (at "),
                "{d}"
            );
            assert!(first["message"].as_str().unwrap().contains("thr.ngc:2)"), "{d}");
            assert_eq!(first["range"]["start"], serde_json::json!({"line": 0, "character": 0}), "{d}");
        } else {
            assert_eq!(first["code"], "program.unreadable", "{d}");
            assert_eq!(first["range"]["start"], serde_json::json!({"line": 6, "character": 0}), "{d}");
        }
        c.finish();
    }
}

/// Issue 58 item 7: a control character in a program's file name (here ESC) is written in the
/// JUnit report as its escape: XML 1.0 forbids it even as a character reference, and a CI server
/// rejected the whole report.
#[test]
fn junit_escapes_what_xml_forbids() {
    let dir = tempdir("junit-esc");
    let lib = dir.join("lib");
    std::fs::create_dir_all(&lib).unwrap();
    std::fs::write(lib.join("shaft\u{1b}[31m.nc"), failing_shaft()).unwrap();
    let o = run_in(&dir, &["verify", "lib", "--junit", "out.xml"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let xml = std::fs::read_to_string(dir.join("out.xml")).unwrap();
    assert!(!xml.contains('\u{1b}'), "{xml}");
    assert!(xml.contains("classname=\"lib/shaft\\u{1b}[31m.nc\""), "{xml}");
}

/// Issue 58 item 5: a `Content-Length` of 10¹² (it aborted the server: SIGABRT allocating it) is
/// answered with JSON-RPC's invalid-request error and a null id, nothing allocated, and the
/// valid request after it is answered; a stream that breaks (a header with no length) ends the
/// server with 1, the protocol's code for an end without `shutdown` (it exited 2).
#[test]
fn the_language_server_survives_a_huge_content_length() {
    let framed = |s: &str| format!("Content-Length: {}\r\n\r\n{s}", s.len());
    let input = [
        "Content-Length: 999999999999\r\n\r\n{\"jsonrpc\":\"2.0\",\"id\":7,\"method\":\"initialize\"}"
            .to_string(),
        framed(r#"{"jsonrpc":"2.0","id":1,"method":"initialize","params":{"capabilities":{}}}"#),
        framed(r#"{"jsonrpc":"2.0","id":2,"method":"shutdown"}"#),
        framed(r#"{"jsonrpc":"2.0","method":"exit"}"#),
    ]
    .concat();
    let mut out = Vec::new();
    let code = threadcheck::lsp_run(std::io::Cursor::new(input.into_bytes()), &mut out).unwrap();
    let out = String::from_utf8(out).unwrap();
    assert_eq!(code, 0, "{out}");
    assert!(
        out.contains(r#""error":{"code":-32600,"message":"a message of 999999999999 bytes is larger than"#),
        "{out}"
    );
    assert!(out.contains(r#""id":null"#) && out.contains(r#""hoverProvider":true"#), "{out}");
    // A header without a length: nothing after it can be read.
    let mut out = Vec::new();
    let code =
        threadcheck::lsp_run(std::io::Cursor::new(b"Content-Type: x\r\n\r\n{}".to_vec()), &mut out).unwrap();
    assert_eq!(code, 1);
}

/// Issue 58 item 3: a document whose check is long (a Klartext loop of about 2 s) does not stop
/// the server: a newer version replaces it at once (its diagnostics come within a second, and
/// none for the old version), and `shutdown` sent while a check runs is answered within a second.
#[test]
fn the_language_server_answers_while_a_document_is_checked() {
    let dir = tempdir("lsp-busy");
    let uri = format!("file://{}", dir.join("loop.h").display());
    let looping = "0 BEGIN PGM LOOP MM\n1 LBL 1\n2 Q1 = Q1 + 1\n3 FN 12: IF +Q1 LT +100000000 GOTO LBL 1\n4 END PGM LOOP MM\n";
    let quick = "0 BEGIN PGM QUICK MM\n1 L Z+100 R0 FMAX\n2 END PGM QUICK MM\n";
    let mut c = Client::start();
    c.request(1, "initialize", serde_json::json!({"capabilities": {}}));
    c.notify("initialized", serde_json::json!({}));
    let open = |c: &mut Client, version: i64, text: &str| {
        c.notify(
            "textDocument/didOpen",
            serde_json::json!({"textDocument": {"uri": uri, "languageId": "klartext", "version": version, "text": text}}),
        );
    };
    open(&mut c, 1, looping);
    std::thread::sleep(std::time::Duration::from_millis(100));
    let t = std::time::Instant::now();
    c.notify(
        "textDocument/didChange",
        serde_json::json!({"textDocument": {"uri": uri, "version": 2}, "contentChanges": [{"text": quick}]}),
    );
    let d = c.diagnostics();
    assert!(t.elapsed() < std::time::Duration::from_secs(1), "the new version waited {:?}", t.elapsed());
    assert_eq!(d["version"], 2, "the looping version was stopped, not published: {d}");
    // A hover asked before the check has ended is answered when it ends (here: nothing on line 1).
    let other = format!("file://{}", dir.join("other.h").display());
    c.notify(
        "textDocument/didOpen",
        serde_json::json!({"textDocument": {"uri": other, "languageId": "klartext", "version": 1, "text": quick}}),
    );
    let hover = c.request(
        5,
        "textDocument/hover",
        serde_json::json!({"textDocument": {"uri": other}, "position": {"line": 0, "character": 0}}),
    );
    assert_eq!(hover["result"], serde_json::Value::Null, "{hover}");
    assert_eq!(c.diagnostics()["uri"], other.as_str(), "published before the hover was answered");
    // The loop again, and shutdown while it is checked.
    c.notify(
        "textDocument/didChange",
        serde_json::json!({"textDocument": {"uri": uri, "version": 3}, "contentChanges": [{"text": looping}]}),
    );
    std::thread::sleep(std::time::Duration::from_millis(100));
    let t = std::time::Instant::now();
    let down = c.request(2, "shutdown", serde_json::Value::Null);
    assert!(t.elapsed() < std::time::Duration::from_secs(1), "shutdown waited {:?}", t.elapsed());
    assert_eq!(down["result"], serde_json::Value::Null, "{down}");
    c.notify("exit", serde_json::Value::Null);
    assert_eq!(c.child.wait().unwrap().code(), Some(0));
    assert!(
        c.notes.iter().all(|n| n["params"]["version"] != 3),
        "no diagnostics of the stopped check: {:?}",
        c.notes
    );
}

/// Issue 58 item 6: an output that is a FIFO no program reads was opened and waited for forever
/// (`--svg`, `--json-lines`, Python's `svg=`): it is given up after the stated 5 s with a line
/// naming it, exit 2, and the run's other files are not written (all or none).
#[cfg(unix)]
#[test]
fn an_output_fifo_with_no_reader_is_given_up() {
    let dir = tempdir("fifo-out");
    let lib = dir.join("lib");
    std::fs::create_dir_all(&lib).unwrap();
    std::fs::write(lib.join("shaft.nc"), failing_shaft()).unwrap();
    assert!(Command::new("mkfifo").arg(dir.join("out.svg")).status().unwrap().success());
    assert!(Command::new("mkfifo").arg(dir.join("out.jsonl")).status().unwrap().success());
    let t = std::time::Instant::now();
    let o = run_in(
        &dir,
        &["verify", "--thread", "M10x1.5-6g", "--insert", "full", "--svg", "out.svg", "--json", "r.json"],
    );
    let took = t.elapsed();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(
        stderr(&o).trim_end(),
        "threadcheck: error: out.svg: a FIFO that no program read within 5 s: nothing was written to it"
    );
    assert!(
        took >= std::time::Duration::from_secs(5) && took < std::time::Duration::from_secs(8),
        "{took:?}"
    );
    assert!(!dir.join("r.json").exists(), "all or none: the JSON waits for the FIFO");
    let o = run_in(&dir, &["verify", "lib", "--json-lines", "out.jsonl"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("out.jsonl: a FIFO that no program read within 5 s"), "{}", stderr(&o));
}

/// Issue 58 item 7: what a text report prints of a user's file is escaped: a machine profile
/// named `lathe\nverdict: PASS` forged a verdict line (the server's text answer echoed it), and
/// in a run of many an ESC in a program's bad token reached the terminal raw.
#[test]
fn text_reports_escape_names_and_tokens() {
    let dir = tempdir("text-esc");
    std::fs::write(dir.join("m.toml"), "name = \"lathe\\nverdict: PASS\"\nmax_rpm = 2000\n").unwrap();
    std::fs::copy(data("whole/shaft.nc"), dir.join("shaft.nc")).unwrap();
    let o = run_in(&dir, &["verify", "--program", "shaft.nc", "--insert", "full", "--machine", "m.toml"]);
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(out.contains("on lathe\\u{a}verdict: PASS (rapid 5000 mm/min assumed)"), "{out}");
    assert!(!out.lines().any(|l| l.starts_with("verdict: PASS (rapid")), "{out}");
    let lib = dir.join("lib");
    std::fs::create_dir_all(&lib).unwrap();
    std::fs::write(lib.join("a.nc"), "G0 X10 Z5\nG76 X8 Z-10 P1000 Q300 F1.5 \u{1b}[31mEVIL\n").unwrap();
    let o = run_in(&dir, &["verify", "lib"]);
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(!out.contains('\u{1b}'), "{out}");
    assert!(out.contains("error: lib/a.nc:2:29: unexpected character '\\u{1b}'"), "{out}");
}

/// Found by the `lsp` fuzz target (issue 58): a header line whose bytes are not UTF-8 (read as
/// U+FFFD, three bytes each) across its 15th byte panicked the framing reader, which sliced
/// it there; the stream is refused as broken, exit 1.
#[test]
fn regression_lsp_header_of_invalid_bytes_panicked() {
    let mut input = b"CA{noC\nME".to_vec();
    input.extend([0xff; 61]);
    input.extend(b"a}");
    let mut out = Vec::new();
    let code = threadcheck::lsp_run(std::io::Cursor::new(input), &mut out).unwrap();
    assert_eq!(code, 1);
}

/// Issue 65 item 2: the language server reads the project file of a document saved on this
/// computer and the modeline of any document, as `verify` does: `LINUXCNC_AS_NC` (a LinuxCNC
/// program in a `.nc` file, unreadable as Fanuc) passes with either, and is unreadable at its
/// G76's J without them.
#[test]
fn the_language_server_reads_the_project_file_and_the_modeline() {
    let dir = tempdir("lsp-project");
    let text = crate::settings::LINUXCNC_AS_NC;
    std::fs::write(dir.join("part.nc"), text).unwrap();
    let uri = format!("file://{}", dir.join("part.nc").display());
    let modeline = text.replacen("%\n", "%\n(threadcheck: dialect=linuxcnc)\n", 1);
    for (project, text, passes) in
        [(false, text.to_string(), false), (true, text.to_string(), true), (false, modeline, true)]
    {
        if project {
            std::fs::write(dir.join(".threadcheck.toml"), "dialect = \"linuxcnc\"\n").unwrap();
        } else {
            let _ = std::fs::remove_file(dir.join(".threadcheck.toml"));
        }
        let (c, d) = Client::with_document(serde_json::json!({"insert": "full"}), &uri, &text);
        let first = &d["diagnostics"][0];
        if passes {
            assert_eq!(first["severity"], 3, "the thread passes: {d}");
            assert!(
                first["message"].as_str().unwrap().starts_with("threadcheck: PASS turned M10X1.5-6g"),
                "{d}"
            );
        } else {
            assert_eq!(first["code"], "program.unreadable", "{d}");
            assert!(
                first["message"].as_str().unwrap().contains("word J is not part of the one-block G76"),
                "{d}"
            );
        }
        c.finish();
    }
}

/// Runs `threadcheck ARGS` in `dir` under a pseudo-terminal (util-linux's `script`, as a person
/// at a terminal runs it), standard output to /dev/null: what the terminal showed.
fn at_a_terminal(dir: &Path, env: &[(&str, &str)], args: &str) -> String {
    let bin = env!("CARGO_BIN_EXE_threadcheck");
    let out = std::process::Command::new("script")
        .args(["-q", "-e", "-c", &format!("{bin} {args} > /dev/null"), "/dev/null"])
        .envs(env.iter().copied())
        .current_dir(dir)
        .output()
        .expect("util-linux's `script` runs a command under a pseudo-terminal: install util-linux");
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// Issue 65: a run of many shows its progress on standard error when that is a terminal and
/// the run passes its wait (a second; 0 here, through `THREADCHECK_PROGRESS_AFTER`), the bar
/// counting the programs to the last and cleared at the end; a quick run at a terminal shows
/// none, and a run whose standard error is not a terminal never does.
#[test]
fn a_run_of_many_shows_its_progress_at_a_terminal_only() {
    let dir = library("progress");
    let shown = at_a_terminal(&dir, &[("THREADCHECK_PROGRESS_AFTER", "0")], "verify lib");
    assert!(shown.contains("3/3 programs"), "{shown:?}");
    // Cleared at the end: the terminal's line erased after the last count.
    let last = shown.rfind("3/3 programs").unwrap();
    assert!(shown[last..].contains("\u{1b}[2K"), "{shown:?}");
    let quick = at_a_terminal(&dir, &[], "verify lib");
    assert!(!quick.contains("programs,"), "a run under a second drew a bar: {quick:?}");
    let o = Command::new(env!("CARGO_BIN_EXE_threadcheck"))
        .args(["verify", "lib"])
        .env("THREADCHECK_PROGRESS_AFTER", "0")
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(!stderr(&o).contains("programs,"), "{}", stderr(&o));
}

/// Issue 65: each file a run writes is said on standard error (standard output keeps the
/// document): `wrote m10.svg (N bytes)`, N the file's size.
#[test]
fn each_file_written_is_said_on_standard_error() {
    let dir = tempdir("wrote");
    let o = run_in(&dir, &["verify", "--thread", "M10x1.5-6g", "--svg", "m10.svg", "--json", "-"]);
    let size = std::fs::metadata(dir.join("m10.svg")).unwrap().len();
    assert!(stderr(&o).contains(&format!("wrote m10.svg ({size} bytes)\n")), "{}", stderr(&o));
    assert!(stdout(&o).starts_with('{'), "{}", stdout(&o));
}
