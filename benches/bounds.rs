//! The largest input each bounded computation allows (issue 42), run through the release binary
//! as a user would: wall time and the process's peak memory (the children's maximum resident
//! set, read by Python's `resource.getrusage`), each the best of three runs. Writes
//! `reports/bounds.md`; every figure should be about a second or less on 2 cores.
//!
//! `cargo bench --bench bounds`

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

/// One case: what it is, its bound, and the command line (run in the case folder).
struct Case {
    what: &'static str,
    bound: &'static str,
    args: Vec<String>,
    /// The exit code the run must end with (0 pass, 1 out of tolerance).
    exit: i32,
}

/// Runs `args` three times under a Python helper that reports the child's peak memory; the best
/// wall time (s), the largest peak (MiB) and the exit code.
fn measure(dir: &Path, args: &[String]) -> (f64, f64, i32) {
    let helper = r#"
import resource, subprocess, sys, time
t = time.perf_counter()
r = subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
dt = time.perf_counter() - t
sys.stderr.write(r.stderr.decode(errors="replace")[-300:])
print(dt, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024.0, r.returncode)
"#;
    let mut best = (f64::INFINITY, 0.0f64, 0);
    for _ in 0..3 {
        let out = Command::new("python3")
            .arg("-c")
            .arg(helper)
            .arg(env!("CARGO_BIN_EXE_threadcheck"))
            .args(args)
            .current_dir(dir)
            .output()
            .expect("python3 runs the measuring helper");
        let text = String::from_utf8_lossy(&out.stdout);
        let v: Vec<&str> = text.split_whitespace().collect();
        assert_eq!(v.len(), 3, "{text} {}", String::from_utf8_lossy(&out.stderr));
        let (t, m, code) = (v[0].parse().unwrap(), v[1].parse::<f64>().unwrap(), v[2].parse().unwrap());
        best = (best.0.min(t), best.1.max(m), code);
    }
    best
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    std::fs::write(dir.join(name), text).unwrap();
    name.to_string()
}

fn main() {
    let dir: PathBuf = std::env::temp_dir().join(format!("threadcheck-bounds-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let data = root.join("tests/data");
    let s = |v: &[&str]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>();

    // Heidenhain G31 V1 at the pass bound: U 0.92 in infeeds of 0.00092 = 1 000 cuts.
    let g31 = write(&dir, "g31-1000.nc", "G0 X22 Z5\nG31 X20 Z-20 F1.5 U-0.92 I0.00092 V1\n");
    // 1 000 passes of a plan.
    // The Monte Carlo at its work bound: 42 553 samples of 7 passes; 1 923 of 1 000 passes.
    // thread-mill: passes of a six-turn helix, each 0.5 µm further out, all cutting the
    // section: 36 of them near the 4·10⁷ evaluations allowed (the reach is sought only where the
    // cutter can pass the tooth profile's own and the bore, issue 62: the 20 one-turn helices
    // 0.35 mm apart that stood here at the bound take a tenth of it now).
    let mut tm = String::from("G17 G21 G90 G40 G94\nT12 M6\nS3000 M3\nG0 X0 Y0 Z5\n");
    for i in 0..36 {
        let r = 7.0 + 0.0005 * f64::from(i);
        writeln!(tm, "G0 Z-16\nG1 X{r:.4} Y0 F100\nG3 X{r:.4} Y0 Z-7 I-{r:.4} J0 P6 F150\nG1 X0 Y0").unwrap();
    }
    tm.push_str("G0 Z50\nM30\n");
    let tm = write(&dir, "thread-mill-crowded.ngc", &tm);
    // thread-mill, issue 62: a comb cutter (Ø11.9, 5 rows 2 mm apart) in 4 radial passes of 3
    // one-turn helices, M16x2 in a Ø14 bore; a single-form cutter on one helix of 100 turns.
    let comb = data.join("programs/threadmill/m16x2-comb-4-passes.nc").to_string_lossy().into_owned();
    let long = write(
        &dir,
        "thread-mill-100-turns.ngc",
        "G17 G21 G90 G40 G94\nT12 M6\nS3000 M3\nG0 X0 Y0 Z5\nG0 Z-160\nG1 X7 Y0 F100\nG3 X7 Y0 Z-10 I-7 J0 P100 F150\nG1 X0 Y0\nG0 Z50\nM30\n",
    );
    // tap: 10 000 tapped holes (the hole bound), none drilled before (D1 not checked, said).
    let mut tap = String::from("G90 G54 G17 G94\nT1 M6\nS600 M3\nG0 X0 Y0 Z5\nG99 G84 X0 Y0 Z-10 R2 F750\n");
    for i in 1..10_000 {
        writeln!(tap, "X{i}").unwrap();
    }
    tap.push_str("G80\nM30\n");
    let tap = write(&dir, "tap-10000.nc", &tap);
    let tools = write(&dir, "tap-tools.toml", "[tools]\n1 = \"tap:M8x1.25-6H\"\n");
    // tap, issue 62: 1 000 holes as LinuxCNC writes rows of them (G91 with L), drilled then
    // tapped: 20 rows of 25 drilled and 25 tapped holes.
    let mut rows = String::from("G17 G21 G90 G94\nT2 M6\nS1200 M3\nG0 X0 Y0 Z10\n");
    for (tool, cycle) in [(2, "G81 R-8 Z-12 F100"), (1, "G84 R-8 Z-10 F750")] {
        rows.push_str(&format!("T{tool} M6\nS{} M3\n", if tool == 1 { 600 } else { 1200 }));
        for r in 0..20 {
            rows.push_str(&format!("G90 G0 X0 Y{}\nG91 G99 {cycle} X10 L25\nG90 G80 G0 Z10\n", 10 * r));
        }
    }
    rows.push_str("M5\nM2\n");
    let rows = write(&dir, "tap-rows-1000.ngc", &rows);
    let row_tools = write(&dir, "row-tools.toml", "[tools]\n1 = \"tap:M8x1.25-6H\"\n2 = \"drill:6.8\"\n");
    // mill: the boss with formulas of 203 terms each for x and y, near the largest this
    // program's levels allow within the 8·10⁷ term evaluations (about 260 each are refused).
    let zeros = vec!["0*t"; 100].join("+");
    let target = write(
        &dir,
        "long-formula.toml",
        &format!(
            "x = \"20*cos(t)+{zeros}\"\ny = \"20*sin(t)+{zeros}\"\nt = [0, 360]\nmaterial = \"inside\"\n"
        ),
    );
    // The interpreter at its block bound: a macro B loop that never ends (10 million blocks).
    let runaway = write(&dir, "runaway.nc", "#1=0\nWHILE[#1GE0]DO1\n#1=#1+1\nEND1\nM30\n");
    // Klartext PATTERN DEF (issue 58: it was read in quadratic time, 16 000 points in 36 s): one
    // of 9 999 points tapped, one of 16 000 (refused at the 10 000-hole bound) and one filling
    // the 2 MiB input limit.
    let pattern = |n: usize, limit: Option<usize>| {
        let mut p = String::from(
            "0 BEGIN PGM PAT MM\n1 TOOL CALL 2 Z S600\n2 L Z+100 R0 FMAX M3\n3 CYCL DEF 207 RIGID TAPPING NEW ~\n  Q200=+2 ~\n  Q201=-15 ~\n  Q239=+1.25 ~\n  Q203=+0 ~\n  Q204=+50\n4 PATTERN DEF ~\n",
        );
        let tail = "\n5 CYCL CALL PAT FMAX\n6 L Z+100 R0 FMAX M30\n7 END PGM PAT MM\n";
        let mut i = 1;
        loop {
            let point = format!("  POS{i} (X+{} Y+{} Z+0)", i % 200, i / 200);
            let full = limit.is_some_and(|l| p.len() + point.len() + 3 + tail.len() > l);
            if i > n || full {
                break;
            }
            if i > 1 {
                p.push_str(" ~\n");
            }
            p.push_str(&point);
            i += 1;
        }
        p.push_str(tail);
        p
    };
    let pat9999 = write(&dir, "pattern-9999.h", &pattern(9_999, None));
    let pat16000 = write(&dir, "pattern-16000.h", &pattern(16_000, None));
    let pat_limit = write(&dir, "pattern-limit.h", &pattern(usize::MAX, Some(2 * 1024 * 1024)));
    let tap_tools = write(&dir, "pattern-tools.toml", "[tools]\n2 = \"tap:M8x1.25-6H\"\n");
    let cases = vec![
        Case {
            what: "Klartext PATTERN DEF of 9 999 points, tapped (tap)",
            bound: "10 000 holes",
            args: s(&["tap", "--program", &pat9999, "--tools", &tap_tools]),
            exit: 0,
        },
        Case {
            what: "Klartext PATTERN DEF of 16 000 points (refused at the hole bound)",
            bound: "10 000 holes",
            args: s(&["tap", "--program", &pat16000, "--tools", &tap_tools]),
            exit: 2,
        },
        Case {
            what: "Klartext PATTERN DEF filling the input limit (refused at the hole bound)",
            bound: "2 MiB of program",
            args: s(&["tap", "--program", &pat_limit, "--tools", &tap_tools]),
            exit: 2,
        },
        Case {
            what: "Heidenhain G31 V1 of 1 000 cuts (verify)",
            bound: "1 000 passes",
            args: s(&["verify", "--thread", "M20x1.5-6g", "--dialect", "heidenhain", "--program", &g31]),
            exit: 1,
        },
        Case {
            what: "a plan of 1 000 passes (verify, with its picture)",
            bound: "1 000 passes",
            args: s(&[
                "verify",
                "--thread",
                "M10x1.5-6g",
                "--insert",
                "full",
                "--passes",
                "1000",
                "--svg",
                "p.svg",
            ]),
            exit: 0,
        },
        Case {
            what: "capability, 42 553 samples of 7 passes",
            bound: "samples × (passes + 40) ≤ 2·10⁶",
            args: s(&[
                "capability",
                "--thread",
                "M10x1.5-6g",
                "--insert",
                "full",
                "--samples",
                "42553",
                "--x-sigma",
                "0.01",
            ]),
            exit: 0,
        },
        Case {
            what: "capability, 1 923 samples of 1 000 passes",
            bound: "samples × (passes + 40) ≤ 2·10⁶",
            args: s(&[
                "capability",
                "--thread",
                "M10x1.5-6g",
                "--insert",
                "full",
                "--passes",
                "1000",
                "--samples",
                "1923",
                "--x-sigma",
                "0.01",
            ]),
            exit: 0,
        },
        Case {
            what: "thread-mill, 36 passes of a six-turn helix 0.5 µm apart",
            bound: "4·10⁷ reach evaluations a section; 10 000 turns",
            args: s(&["thread-mill", "--thread", "M20x1.5-6H", "--cutter-diameter", "6", "--program", &tm]),
            exit: 1,
        },
        Case {
            what: "thread-mill, a comb cutter's 4 passes of 3 turns (M16x2, 5 rows)",
            bound: "4·10⁷ reach evaluations a section",
            args: s(&[
                "thread-mill",
                "--thread",
                "M16x2-6H",
                "--cutter-diameter",
                "11.9",
                "--cutter-rows",
                "5",
                "--cutter-row-pitch",
                "2",
                "--program",
                &comb,
            ]),
            exit: 1,
        },
        Case {
            what: "thread-mill, one helix of 100 turns",
            bound: "4·10⁷ reach evaluations a section; 10 000 turns",
            args: s(&["thread-mill", "--thread", "M20x1.5-6H", "--cutter-diameter", "6", "--program", &long]),
            exit: 1,
        },
        Case {
            what: "tap, 1 000 holes in LinuxCNC G91 L rows (500 drilled, 500 tapped)",
            bound: "10 000 holes",
            args: s(&["tap", "--program", &rows, "--tools", &row_tools]),
            exit: 0,
        },
        Case {
            what: "tap, 10 000 tapped holes (with SVG and HTML)",
            bound: "10 000 holes",
            args: s(&["tap", "--program", &tap, "--tools", &tools, "--svg", "t.svg", "--html", "t.html"]),
            exit: 0,
        },
        Case {
            what: "mill, the Ø40 boss with 203-term formulas",
            bound: "500 terms a formula; 8·10⁷ term evaluations",
            args: s(&[
                "mill",
                "--program",
                data.join("programs/milling/boss-arcs.nc").to_str().unwrap(),
                "--tool-diameter",
                "6",
                "--target",
                &target,
            ]),
            exit: 1,
        },
        Case {
            what: "mill, the dome of 799 levels (1.15 million pieces)",
            bound: "2·10⁶ pieces; 8·10⁷ term evaluations",
            args: s(&[
                "mill",
                "--program",
                data.join("programs/milling/seed004-paraboloid.nc").to_str().unwrap(),
                "--dialect",
                "dyna",
                "--tool-diameter",
                "12",
                "--target",
                data.join("targets/paraboloid.toml").to_str().unwrap(),
            ]),
            exit: 1,
        },
        Case {
            what: "a runaway macro loop (passes)",
            bound: "10⁷ blocks executed",
            args: s(&["passes", "--program", &runaway]),
            exit: 2,
        },
    ];
    let mut md = String::from(
        "# The bounded computations at their largest allowed input\n\n\
         Written by `cargo bench --bench bounds` (issue 42): each case runs the release binary three\n\
         times; the best wall time and the largest peak resident memory of the process. The bounds\n\
         are in `src/ground/bounds.rs` and `src/analysis/study/capability.rs`; each is checked before the\n\
         work starts (or, for the interpreter and the mill's formulas, counted as it goes), and\n\
         reaching it is a one-line refusal with its place.\n\n",
    );
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|c| {
            c.lines()
                .find(|l| l.starts_with("model name"))
                .map(|l| l.split(':').nth(1).unwrap_or("").trim().to_string())
        })
        .unwrap_or_default();
    let cores = std::thread::available_parallelism().map_or(0, usize::from);
    writeln!(md, "Machine: {cores} cores ({cpu}).\n").unwrap();
    md.push_str("| input | bound | time, s | peak memory, MiB | exit |\n|---|---|---:|---:|---:|\n");
    for c in &cases {
        let (t, m, code) = measure(&dir, &c.args);
        assert_eq!(code, c.exit, "{}: exit {code}", c.what);
        println!("{:<55} {t:>6.2} s {m:>7.1} MiB", c.what);
        writeln!(md, "| {} | {} | {t:.2} | {m:.0} | {code} |", c.what, c.bound).unwrap();
    }
    std::fs::write(root.join("reports/bounds.md"), md).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
}
