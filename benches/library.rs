//! Issue 46 item 3: a shop's library verified in one run. Generates libraries of 1 000 and
//! 4 000 typical programs of our own (lathe programs turning one of ten metric threads named in a
//! comment, a third of them also drilling and tapping M8 in the face; every fifth a machining
//! centre's plate with four tapped holes), runs `verify FOLDER --json-lines FILE` through the
//! release binary as a user would, and writes `reports/library.md`: wall time (best of three) and
//! peak memory (the child's maximum resident set, read by Python's `resource.getrusage`), so that
//! the memory's growth with the library's size shows.
//!
//! `cargo bench --bench library`

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The threads the lathe programs turn: (d, P).
const THREADS: [(f64, f64); 10] = [
    (6.0, 1.0),
    (8.0, 1.25),
    (10.0, 1.5),
    (12.0, 1.75),
    (16.0, 2.0),
    (20.0, 2.5),
    (24.0, 3.0),
    (20.0, 1.5),
    (24.0, 2.0),
    (30.0, 2.0),
];

/// Program `i` of a library.
fn program(i: usize) -> (String, String) {
    if i % 5 == 4 {
        let x0 = 20 + (i % 7) * 5;
        let mut p = format!(
            "%\nO{:04} (PLATE {i}: 4 X M8 TAPPED)\nG17 G21 G90 G94 G40 G80\nT1 M6 (DRILL 6.8)\nS2500 M3\nG0 G54 X{x0} Y20 Z25\nG43 H1 Z5\nG98 G81 Z-20 R2 F250\n",
            i % 10_000
        );
        p.push_str(&format!(
            "X{}\nY60\nX{x0}\nG80\nT2 M6 (TAP M8X1.25-6H)\nS500 M3\nG0 X{x0} Y20 Z5\nG43 H2\nM29 S500\n",
            x0 + 40
        ));
        p.push_str(&format!("G98 G84 Z-14 R3 F625\nX{}\nY60\nX{x0}\nG80\nM30\n%\n", x0 + 40));
        return (format!("plate-{i:05}.nc"), p);
    }
    let (d, pitch) = THREADS[i % THREADS.len()];
    let final_x = d - 1.226_869 * pitch - 0.02 * ((i % 9) as f64);
    let mut p = format!(
        "%\nO{:04} (SHAFT {i})\nG21 G18 G99 G40\nT0101 (THREAD M{d}X{pitch} 6G)\nG97 S{} M3\nG0 X{} Z5\nG76 P010060 Q100 R0.05\nG76 X{final_x:.3} Z-{} P{} Q{} F{pitch}\nG0 X100 Z100\n",
        i % 10_000,
        600 + 10 * (i % 30),
        d + 2.0,
        10 + i % 20,
        (((d - final_x) / 2.0) * 1000.0).round(),
        (pitch * 100.0).round()
    );
    if i % 3 == 0 {
        p.push_str("T0505 (DRILL 6.8)\nG97 S1200 M3\nG0 X0 Z5\nG83 Z-20 R2 Q4000 F0.1\nG80\nG0 X100 Z100\n");
        p.push_str("T0606 (TAP M8X1.25)\nG97 S400 M3\nG0 X0 Z8\nG84 Z-14 R5 F1.25\nG80\nG0 X100 Z100\n");
    }
    p.push_str("M30\n%\n");
    (format!("shaft-{i:05}.nc"), p)
}

/// A library of `n` programs in `dir`.
fn library(dir: &Path, n: usize) {
    std::fs::create_dir_all(dir).unwrap();
    for i in 0..n {
        let (name, text) = program(i);
        std::fs::write(dir.join(name), text).unwrap();
    }
}

/// Runs the binary with `args` three times; the best wall time (s), the largest peak (MiB), the
/// exit code, and the last line of standard output (the summary).
fn measure(args: &[String]) -> (f64, f64, i32, String) {
    let helper = r#"
import resource, subprocess, sys, time
t = time.perf_counter()
r = subprocess.run(sys.argv[1:], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
dt = time.perf_counter() - t
last = (r.stdout.decode(errors="replace").strip().splitlines() or [""])[-1]
print(dt, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024.0, r.returncode)
print(last)
"#;
    let mut best = (f64::INFINITY, 0.0f64, 0, String::new());
    for _ in 0..3 {
        let out = Command::new("python3")
            .arg("-c")
            .arg(helper)
            .arg(env!("CARGO_BIN_EXE_threadcheck"))
            .args(args)
            .output()
            .expect("python3 runs the measuring helper");
        let text = String::from_utf8_lossy(&out.stdout);
        let mut lines = text.lines();
        let v: Vec<&str> = lines.next().unwrap_or("").split_whitespace().collect();
        assert_eq!(v.len(), 3, "{text} {}", String::from_utf8_lossy(&out.stderr));
        let (t, m, code) = (v[0].parse().unwrap(), v[1].parse::<f64>().unwrap(), v[2].parse().unwrap());
        best = (best.0.min(t), best.1.max(m), code, lines.next().unwrap_or("").to_string());
    }
    best
}

fn main() {
    let root: PathBuf = std::env::temp_dir().join(format!("threadcheck-library-{}", std::process::id()));
    let mut rows = Vec::new();
    for n in [1_000usize, 4_000] {
        let dir = root.join(format!("lib-{n}"));
        library(&dir, n);
        let out = root.join(format!("lib-{n}.jsonl"));
        let args = vec![
            "verify".to_string(),
            dir.display().to_string(),
            "--json-lines".to_string(),
            out.display().to_string(),
        ];
        let (t, m, code, summary) = measure(&args);
        assert!(code == 0 || code == 1, "exit {code}: {summary}");
        let lines = std::fs::read_to_string(&out).unwrap().lines().count();
        assert_eq!(lines, n + 1, "one JSON line per program and the summary");
        eprintln!("{n} programs: {t:.3} s, {m:.1} MiB: {summary}");
        rows.push((n, t, m, summary));
    }
    std::fs::remove_dir_all(&root).ok();
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|c| {
            c.lines()
                .find(|l| l.starts_with("model name"))
                .map(|l| l.split(':').nth(1).unwrap_or("").trim().to_string())
        })
        .unwrap_or_default();
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut md = String::from("# A library verified in one run\n\n");
    md.push_str("Regenerated by `cargo bench --bench library` (`benches/library.rs`): `threadcheck verify FOLDER --json-lines FILE` over generated libraries of typical programs of our own (lathe programs turning one of ten metric threads named in a comment, a third also drilling and tapping M8 in the face; every fifth a machining centre's plate with four tapped holes), through the release binary; wall time the best of three runs, peak memory the process's maximum resident set.\n\n");
    let _ = writeln!(md, "Machine: {cores} cores, {cpu}.\n");
    md.push_str("| programs | wall time | peak memory | summary |\n|---:|---:|---:|---|\n");
    for (n, t, m, summary) in &rows {
        let _ = writeln!(md, "| {n} | {t:.2} s | {m:.1} MiB | {summary} |");
    }
    let (t1, m1) = (rows[0].1, rows[0].2);
    let (m4, t4) = (rows[1].2, rows[1].1);
    let _ = writeln!(
        md,
        "\nTarget: 1 000 typical programs in under 2 s wall on 2 cores: {} ({t1:.2} s). Memory flat in the number of programs: {:.2}× from 1 000 to 4 000 programs ({m1:.1} to {m4:.1} MiB; the programs are verified 64 at a time and only each one's lines are kept); time {:.2}× for 4× the programs.",
        if t1 < 2.0 { "met" } else { "not met" },
        m4 / m1,
        t4 / t1
    );
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("reports/library.md");
    std::fs::write(&path, md).unwrap();
    eprintln!("wrote {}", path.display());
}
