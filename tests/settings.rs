//! Issue 65 item 2: a folder says how its programs are read (`.threadcheck.toml`, found from the
//! program's folder upwards) and a program says it in its first lines (a modeline); flags win.
//! The language server's half is in `integrations.rs` (its scripted client).

use crate::util::*;

/// A LinuxCNC lathe program (G7 diameters, the one-block G76 with its I, J, K) saved as `.nc`,
/// which reads as Fanuc by its extension, where the G76 takes no J. Read as LinuxCNC, from the
/// drive line X12 I-2.15 puts the crest on the turned Ø9.85 and K1.84 the root at X8.01: M10x1.5
/// in tolerance with a full-profile insert (`integrations.rs`'s filter test derives it, and
/// `rs274` agrees on the G76's last feed).
pub(crate) const LINUXCNC_AS_NC: &str = "%\n(M10X1.5 THREAD)\nG7 G18 G21 G90\nS500 M3\nG0 X9.85 Z2\nG1 Z-25 F0.1\nG0 X12 Z2\nG76 P1.5 Z-20 I-2.15 J0.05 K1.84 Q29.5 R1.5 H1 E0 L0\nG0 X20 Z20\nM2\n%\n";

fn verify_json(dir: &std::path::Path, args: &[&str]) -> (i32, serde_json::Value, String) {
    let mut a = vec!["verify", "--insert", "full", "--json", "-"];
    a.extend_from_slice(args);
    let o = run_in(dir, &a);
    let code = o.status.code().unwrap();
    let v = if code < 2 { serde_json::from_slice(&o.stdout).unwrap() } else { serde_json::Value::Null };
    (code, v, stderr(&o))
}

fn notes(v: &serde_json::Value) -> String {
    v["notes"].to_string()
}

/// The project file in the program's folder, and in a folder above it, chooses the dialect; the
/// notes say which file; `--dialect` wins over it, and the notes say that too.
#[test]
fn a_project_file_chooses_the_dialect() {
    let dir = tempdir("project-dialect");
    std::fs::create_dir_all(dir.join("lathe/2026")).unwrap();
    std::fs::write(dir.join("lathe/2026/part.nc"), LINUXCNC_AS_NC).unwrap();
    // No project file: read as Fanuc, whose one-block G76 takes no J.
    let (code, _, e) = verify_json(&dir, &["--program", "lathe/2026/part.nc"]);
    assert_eq!(code, 2, "{e}");
    assert!(e.contains("lathe/2026/part.nc:8:22: word J is not part of the one-block G76"), "{e}");
    // Two folders up.
    std::fs::write(dir.join(".threadcheck.toml"), "dialect = \"linuxcnc\"\n").unwrap();
    let (code, v, e) = verify_json(&dir, &["--program", "lathe/2026/part.nc"]);
    assert_eq!(code, 0, "{e}");
    assert_eq!(v["dialect"], "linuxcnc", "{v}");
    assert!(
        notes(&v).contains("read with the project file .threadcheck.toml: dialect linuxcnc"),
        "{}",
        notes(&v)
    );
    // The nearest one wins: one beside the program says fanuc.
    std::fs::write(dir.join("lathe/2026/.threadcheck.toml"), "dialect = \"fanuc\"\n").unwrap();
    let (code, _, e) = verify_json(&dir, &["--program", "lathe/2026/part.nc"]);
    assert_eq!(code, 2, "{e}");
    std::fs::remove_file(dir.join("lathe/2026/.threadcheck.toml")).unwrap();
    // The flag wins, said.
    let (code, v, e) = verify_json(&dir, &["--program", "lathe/2026/part.nc", "--dialect", "linuxcnc"]);
    assert_eq!(code, 0, "{e}");
    assert!(
        notes(&v).contains(
            "--dialect linuxcnc is given, over dialect linuxcnc that the project file .threadcheck.toml sets"
        ),
        "{}",
        notes(&v)
    );
    let (code, _, e) = verify_json(&dir, &["--program", "lathe/2026/part.nc", "--dialect", "fanuc"]);
    assert_eq!(code, 2, "{e}");
}

/// A modeline in a program's first lines, in either comment: it chooses the dialect and the
/// thread (quoted, as designations hold spaces), and wins over the project file; a key it does
/// not take, or a value its key does not, is refused at its line and column.
#[test]
fn a_modeline_chooses_the_dialect_and_the_thread() {
    let dir = tempdir("modeline");
    let with = |line: &str| LINUXCNC_AS_NC.replacen("%\n", &format!("%\n{line}\n"), 1);
    std::fs::write(dir.join("a.nc"), with("(threadcheck: dialect=linuxcnc)")).unwrap();
    let (code, v, e) = verify_json(&dir, &["--program", "a.nc"]);
    assert_eq!(code, 0, "{e}");
    assert!(
        notes(&v).contains("read with the program's modeline (line 2): dialect linuxcnc"),
        "{}",
        notes(&v)
    );
    assert_eq!(v["operations"][0]["thread"]["designation"], "M10X1.5-6g");
    // The thread, quoted; 6h's d2 max is the basic 9.026, so the same cut is checked against it.
    std::fs::write(dir.join("b.nc"), with("; threadcheck: dialect=linuxcnc thread=\"M10x1.5-6h\"")).unwrap();
    let (code, v, e) = verify_json(&dir, &["--program", "b.nc"]);
    assert!(code < 2, "{e}");
    assert_eq!(v["operations"][0]["thread"]["designation"], "M10x1.5-6h", "{v}");
    assert_eq!(v["operations"][0]["designation_from"], "given", "{v}");
    // Over the project file's.
    std::fs::write(dir.join(".threadcheck.toml"), "dialect = \"fanuc\"\n").unwrap();
    let (code, v, e) = verify_json(&dir, &["--program", "a.nc"]);
    assert_eq!(code, 0, "{e}");
    assert_eq!(v["dialect"], "linuxcnc");
    std::fs::remove_file(dir.join(".threadcheck.toml")).unwrap();
    for (line, at, words) in [
        (
            "(threadcheck: dialect=linuxcnc colour=red)",
            "c.nc:2:32: modeline: unknown key 'colour'",
            "a modeline takes dialect, machine-type, default-units and thread",
        ),
        (
            "(threadcheck: dialect=linuxcn)",
            "c.nc:2:15: modeline: dialect: unknown dialect 'linuxcn'",
            "expected fanuc, haas",
        ),
        ("(threadcheck: linuxcnc)", "c.nc:2:15: modeline: 'linuxcnc' is not key=value", ""),
    ] {
        std::fs::write(dir.join("c.nc"), with(line)).unwrap();
        let o = run_in(&dir, &["verify", "--program", "c.nc"]);
        assert_eq!(o.status.code(), Some(2));
        let e = one_line_error(&o);
        assert!(e.contains(at) && e.contains(words), "{e}");
    }
}

/// The project file's machine type, tool table and thread rules: `[[threads]]` globs beside
/// the project file (`*` within a folder, `**` across), the first rule that names the program;
/// the tool table's path beside the project file; a key it does not take refused at its place.
#[test]
fn a_project_file_s_tools_and_thread_rules() {
    let dir = tempdir("project-rules");
    std::fs::create_dir_all(dir.join("bolts/m10")).unwrap();
    std::fs::create_dir_all(dir.join("tables")).unwrap();
    std::fs::write(dir.join("bolts/m10/part.ngc"), LINUXCNC_AS_NC).unwrap();
    std::fs::write(dir.join("tables/lathe.toml"), "[tools]\n1 = \"full\"\n").unwrap();
    std::fs::write(
        dir.join(".threadcheck.toml"),
        "machine-type = \"lathe\"\ntools = \"tables/lathe.toml\"\n[[threads]]\nfiles = \"bolts/*.ngc\"\nthread = \"M10x1.5-4h\"\n[[threads]]\nfiles = \"bolts/**/*.ngc\"\nthread = [\"M10x1.5-6h\"]\n",
    )
    .unwrap();
    let o = run_in(&dir, &["verify", "--program", "bolts/m10/part.ngc", "--json", "-"]);
    assert!(o.status.code().unwrap() < 2, "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["operations"][0]["thread"]["designation"], "M10x1.5-6h", "{v}");
    // The tool table's T1 is the full-profile insert: the insert is known, not assumed.
    assert!(v["operations"][0]["insert"]["name"].as_str().unwrap().starts_with("full-profile"), "{v}");
    let n = notes(&v);
    assert!(
        n.contains(
            "read with the project file .threadcheck.toml: machine type lathe, tool table tables/lathe.toml"
        ),
        "{n}"
    );
    assert!(
        n.contains("read with the project file .threadcheck.toml ('bolts/**/*.ngc'): thread M10x1.5-6h"),
        "{n}"
    );
    assert!(n.contains("read as a lathe, as the project file .threadcheck.toml says"), "{n}");
    std::fs::write(dir.join(".threadcheck.toml"), "dialect = \"linuxcnc\"\ncolour = \"red\"\n").unwrap();
    let o = run_in(&dir, &["verify", "--program", "bolts/m10/part.ngc"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        one_line_error(&o).contains(".threadcheck.toml:2:1: unknown field `colour`"),
        "{}",
        one_line_error(&o)
    );
}

/// A run of many and the LinuxCNC filter read each program's project file: a folder of `.nc`
/// programs that are LinuxCNC's.
#[test]
fn a_run_and_the_filter_read_the_project_file() {
    let dir = tempdir("project-run");
    std::fs::create_dir_all(dir.join("shop")).unwrap();
    std::fs::write(dir.join("shop/part.nc"), LINUXCNC_AS_NC).unwrap();
    let o = run_in(&dir, &["verify", "shop", "--insert", "full"]);
    assert_eq!(o.status.code(), Some(2), "unread without it: {}", stdout(&o));
    let o = run_in(&dir, &["filter", "--msg", "--insert", "full", "shop/part.nc"]);
    assert!(
        stdout(&o).contains(
            "(MSG, threadcheck: part.nc:8:22: not checked: word J is not part of the one-block G76"
        ),
        "{}",
        stdout(&o)
    );
    std::fs::write(dir.join("shop/.threadcheck.toml"), "dialect = \"linuxcnc\"\n").unwrap();
    let o = run_in(&dir, &["verify", "shop", "--insert", "full"]);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    let o = run_in(&dir, &["filter", "--msg", "--gate", "--insert", "full", "shop/part.nc"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(stdout(&o), LINUXCNC_AS_NC, "a passing program gets no message");
}

/// `tap` reads the project file's tool table, units and machine file: a program whose T1 drills
/// Ø8.5 and T2 taps M10x1.5 (F1.5 per revolution at S400, G95) names neither in a comment, so
/// without a tool table the tap is not known; with the project's it passes (Ø8.5 within 6H's
/// D1 8.376–8.676; the feed the lead).
#[test]
fn tap_reads_the_project_file() {
    let dir = tempdir("project-tap");
    std::fs::write(
        dir.join("plate.nc"),
        "%\nG21 G17 G90 G95\nT1 M6\nS800 M3\nG0 X0 Y0 Z5\nG81 Z-20 R2 F0.1\nG80\nT2 M6\nS400 M3\nG84 Z-15 R5 F1.5\nG80\nM30\n%\n",
    )
    .unwrap();
    let o = run_in(&dir, &["tap", "--program", "plate.nc"]);
    assert_eq!(o.status.code(), Some(2), "{}", stdout(&o));
    assert!(one_line_error(&o).contains("T2"), "{}", one_line_error(&o));
    std::fs::write(dir.join("tools.toml"), "[tools]\n1 = \"drill:8.5\"\n2 = \"tap:M10x1.5-6H\"\n").unwrap();
    std::fs::write(dir.join("mill.toml"), "name = \"vmc\"\ntype = \"mill\"\n").unwrap();
    std::fs::write(dir.join(".threadcheck.toml"), "tools = \"tools.toml\"\nmachine = \"mill.toml\"\n")
        .unwrap();
    let o = run_in(&dir, &["tap", "--program", "plate.nc", "--json", "-"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["holes"][0]["tap"]["designation"], "M10x1.5-6H");
    let n = v["notes"].to_string();
    assert!(
        n.contains(
            "read with the project file .threadcheck.toml: machine file mill.toml, tool table tools.toml"
        ),
        "{n}"
    );
    assert!(n.contains("read as a mill, as the machine file 'vmc"), "{n}");
}
