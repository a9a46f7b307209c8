//! LinuxCNC conformance: the `linuxcnc` dialect held to LinuxCNC's own interpreter, `rs274`
//! (Debian's `linuxcnc-uspace` package), on programs generated from a seed.
//!
//! Each program is run by `rs274 -g`, which prints the canonical motion, and read by
//! threadcheck with the comparison rules of the interpreter at hand (Debian 12 ships a build
//! from before LinuxCNC 2.9.0: `--linuxcnc-release before-2.9`). Every synchronised pass is
//! compared point for point (its start, the ends of its tapers and of its synchronised
//! straight, in machine coordinates: `rs274` prints program coordinates and its offsets
//! separately), with the distance per revolution of every feed, to `rs274`'s print precision
//! (4 decimals of program units, X as a radius; 6 decimals of K); the number of passes must be
//! equal; a program `rs274` refuses threadcheck must refuse too.
//!
//! `THREADCHECK_RS274_PROGRAMS` (default 1 000) and `THREADCHECK_RS274_SEED` (default 1) set the
//! run; `tests/rs274-long.sh` runs 10 000 others; `THREADCHECK_RS274_VERBOSE` prints
//! the refusals both sides agree on. A missing `rs274` fails the test with a message.

use crate::util::tempdir;
use proptest::prelude::RngExt;
use proptest::test_runner::{RngAlgorithm, TestRng};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use threadcheck::{read_program_with, Dialect, LinuxCncRelease, ReadOptions};

/// `rs274` on the PATH, or where `tests/install-rs274.sh` unpacks it when Debian's package cannot
/// be installed (`target/linuxcnc/bin/rs274`), or a failure that says how to get it.
pub(crate) fn rs274() -> PathBuf {
    let unpacked = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/linuxcnc/bin/rs274");
    let found = std::env::var_os("PATH")
        .and_then(|paths| std::env::split_paths(&paths).map(|d| d.join("rs274")).find(|p| p.is_file()))
        .or_else(|| unpacked.is_file().then_some(unpacked));
    found.unwrap_or_else(|| {
        panic!(
            "rs274 (LinuxCNC's standalone interpreter) is not installed: the LinuxCNC conformance \
             test needs it. Install Debian's linuxcnc-uspace package \
             (apt-get install --no-install-recommends linuxcnc-uspace), or run tests/install-rs274.sh, which \
             unpacks it into target/linuxcnc when the package cannot be installed"
        )
    })
}

/// A folder for `rs274` runs, with the tool table they read (tools 1–99 in pockets 1–99, no
/// offsets).
pub(crate) fn rs274_dir(tag: &str) -> crate::util::Scratch {
    let dir = tempdir(tag);
    let table: String = (1..=99).map(|i| format!("T{i} P{i} D0 ;\n")).collect();
    std::fs::write(dir.join("tool.tbl"), table).unwrap();
    dir
}

/// One synchronised pass: its points in machine coordinates (X diameter, Z; mm), the distance
/// per revolution of each feed between them (program units, as K is written) and how far
/// each point may be off (mm) at the print precision.
#[derive(Debug, Clone)]
struct Seg {
    pts: Vec<[f64; 2]>,
    k: Vec<f64>,
    tol: Vec<[f64; 2]>,
}

/// What one side made of a program.
#[derive(Debug)]
enum Outcome {
    Passes(Vec<Seg>),
    Refused(String),
}

/// The numbers in an argument list `1, 0.5000, CANON_X` (the words that are not numbers
/// are left out).
pub(crate) fn numbers(args: &str) -> Vec<f64> {
    args.split(',').filter_map(|a| a.trim().parse::<f64>().ok()).collect()
}

/// Reads `rs274 -g`'s canonical output.
fn parse_canon(out: &str) -> Outcome {
    let (mut unit, mut g5x, mut g92) = (1.0, [0.0f64; 2], [0.0f64; 2]);
    // How many times each offset was printed (once at the start).
    let mut offsets = [0u32; 2];
    let mut xz_plane = false;
    let mut pos = [0.0f64; 2];
    let mut sync: Option<Seg> = None;
    let mut k = 0.0;
    let mut segs = Vec::new();
    let mut errors = Vec::new();
    let (calls, rs_errors) = canon_calls(out);
    errors.extend(rs_errors);
    for (name, args) in calls {
        let v = numbers(args);
        let machine = |p: [f64; 2], unit: f64, g5x: [f64; 2], g92: [f64; 2]| {
            [2.0 * (p[0] + g5x[0] + g92[0]) * unit, (p[1] + g5x[1] + g92[1]) * unit]
        };
        // Each printed number is rounded to 4 decimals: the position, and each offset once the
        // program has set one (an offset of 0.00004 prints as 0.0000).
        let n = 1.0 + f64::from(u8::from(offsets[0] > 1)) + f64::from(u8::from(offsets[1] > 1));
        let tol = [2.0 * 0.00005 * n * unit + 1e-9, 0.00005 * n * unit + 1e-9];
        match name {
            "USE_LENGTH_UNITS" => unit = if args.contains("INCHES") { 25.4 } else { 1.0 },
            "SELECT_PLANE" => xz_plane = args.contains("XZ"),
            "SET_G5X_OFFSET" => {
                g5x = [v[1], v[3]];
                offsets[0] += 1;
            }
            "SET_G92_OFFSET" => {
                g92 = [v[0], v[2]];
                offsets[1] += 1;
            }
            "STRAIGHT_TRAVERSE" | "STRAIGHT_FEED" | "ARC_FEED" => {
                pos = match name {
                    // ARC_FEED(first end, second end, …, axis end): Z, X in the XZ plane.
                    "ARC_FEED" if xz_plane => [v[1], v[0]],
                    "ARC_FEED" => [v[0], v[5]],
                    _ => [v[0], v[2]],
                };
                if let Some(s) = sync.as_mut() {
                    s.pts.push(machine(pos, unit, g5x, g92));
                    s.tol.push(tol);
                    s.k.push(k);
                }
            }
            "START_SPEED_FEED_SYNC" => {
                k = v[0];
                if sync.is_none() {
                    sync =
                        Some(Seg { pts: vec![machine(pos, unit, g5x, g92)], k: Vec::new(), tol: vec![tol] });
                }
            }
            "STOP_SPEED_FEED_SYNCH" => segs.extend(sync.take()),
            _ => {}
        }
    }
    if !errors.is_empty() {
        return Outcome::Refused(errors.join(" | "));
    }
    // The radial feed of a G76 entry taper (from the drive line out to the taper's outer end,
    // above the crest, at the start Z) cuts nothing: the pass starts where it ends.
    for s in &mut segs {
        if s.pts.len() > 2 && (s.pts[1][1] - s.pts[0][1]).abs() < 1e-9 {
            s.pts.remove(0);
            s.tol.remove(0);
            s.k.remove(0);
        }
    }
    Outcome::Passes(segs)
}

/// The canonical calls in `rs274 -g`'s output (name, arguments), and the lines that are not
/// one (its errors; `executing`, its banner, left out).
pub(crate) fn canon_calls(out: &str) -> (Vec<(&str, &str)>, Vec<String>) {
    let (mut calls, mut errors) = (Vec::new(), Vec::new());
    for line in out.lines() {
        let t = line.trim();
        if t.is_empty() || t == "executing" {
            continue;
        }
        let canon = t.split_once("N..... ").and_then(|(n, rest)| {
            n.trim().parse::<u64>().ok()?;
            let (name, args) = rest.split_once('(')?;
            Some((name, args.strip_suffix(')')?))
        });
        match canon {
            Some(c) => calls.push(c),
            None => errors.push(t.to_string()),
        }
    }
    (calls, errors)
}

/// `rs274 -g`'s output (stdout and stderr) for `program`, run with its own `HOME` (it keeps
/// files there) and the tool table in `dir`.
pub(crate) fn rs274_text(exe: &Path, program: &str, dir: &Path) -> String {
    let file = dir.join("p.ngc");
    std::fs::write(&file, program).unwrap();
    let out = std::process::Command::new(exe)
        .current_dir(dir)
        .env("HOME", dir)
        .arg("-t")
        .arg(dir.join("tool.tbl"))
        .arg("-g")
        .arg(&file)
        .stdin(std::process::Stdio::null())
        .output()
        .unwrap();
    String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr)
}

/// Runs `rs274` on `program`: its passes.
fn run_rs274(exe: &Path, program: &str, dir: &Path) -> Outcome {
    parse_canon(&rs274_text(exe, program, dir))
}

/// The random draws of a program generator.
pub(crate) trait Draws {
    fn rng(&mut self) -> &mut TestRng;
    fn f(&mut self, lo: f64, hi: f64) -> f64 {
        self.rng().random_range(lo..hi)
    }
    fn i(&mut self, lo: i64, hi: i64) -> i64 {
        self.rng().random_range(lo..=hi)
    }
    fn chance(&mut self, p: f64) -> bool {
        self.rng().random_bool(p)
    }
    fn pick<T: Copy>(&mut self, xs: &[T]) -> T {
        let k = self.rng().random_range(0..xs.len());
        xs[k]
    }
}

/// A generator's random numbers from `seed` (`salt` keeps two generators' streams apart).
pub(crate) fn seeded(seed: u64, salt: u8) -> TestRng {
    let mut bytes = [0u8; 32];
    for (i, b) in bytes.iter_mut().enumerate() {
        *b = (seed.rotate_left(8 * (i as u32 % 8)) as u8) ^ (i as u8).wrapping_mul(salt);
    }
    TestRng::from_seed(RngAlgorithm::ChaCha, &bytes)
}

/// threadcheck's passes of `program` as the same points.
fn threadcheck(program: &str) -> Outcome {
    threadcheck_with(program, ReadOptions::default())
}

/// [`threadcheck`] with reading options (the subprogram files it finds).
fn threadcheck_with(program: &str, opts: ReadOptions) -> Outcome {
    let opts = ReadOptions { linuxcnc: LinuxCncRelease::Before29, ..opts };
    let p = match read_program_with(program, "p.ngc", Dialect::LinuxCnc, opts) {
        Ok(p) => p,
        Err(e) => return Outcome::Refused(e.to_string()),
    };
    let mut segs = Vec::new();
    for op in &p.operations {
        let unit = op.units.mm();
        for q in &op.passes {
            let dir = q.feed_direction();
            let mut pts = Vec::new();
            if q.taper_in > 0.0 {
                pts.push([q.x_taper, q.z_start]);
            }
            pts.push([q.x_start, q.z_start + dir * q.taper_in]);
            pts.push([q.x_end, q.z_end - dir * q.taper_out]);
            if q.taper_out > 0.0 {
                pts.push([q.x_taper, q.z_end]);
            }
            // K along each feed: the axial lead stretched to the path.
            let k = pts
                .windows(2)
                .map(|w| {
                    let (dx, dz) = (0.5 * (w[1][0] - w[0][0]), w[1][1] - w[0][1]);
                    q.lead * dx.hypot(dz) / dz.abs() / unit
                })
                .collect();
            segs.push(Seg { tol: vec![[0.0; 2]; pts.len()], pts, k });
        }
    }
    Outcome::Passes(segs)
}

/// Where the two sides differ, or `None`.
fn compare(expect_refusal: Option<&str>, rs: &Outcome, tc: &Outcome) -> Option<String> {
    match (rs, tc) {
        (Outcome::Refused(_), Outcome::Refused(_)) => None,
        (Outcome::Passes(_), Outcome::Refused(e)) if expect_refusal.is_some_and(|x| e.contains(x)) => None,
        // No pass at all: threadcheck says so as its error.
        (Outcome::Passes(a), Outcome::Refused(e)) if a.is_empty() && e.contains("no threading pass") => None,
        (Outcome::Refused(r), Outcome::Passes(_)) => {
            Some(format!("rs274 refuses ({r}); threadcheck does not"))
        }
        (Outcome::Passes(_), Outcome::Refused(e)) => {
            Some(format!("threadcheck refuses ({e}); rs274 does not"))
        }
        (Outcome::Passes(a), Outcome::Passes(b)) => {
            if a.len() != b.len() {
                return Some(format!("rs274 cuts {} passes, threadcheck {}", a.len(), b.len()));
            }
            for (i, (r, t)) in a.iter().zip(b).enumerate() {
                if r.pts.len() != t.pts.len() {
                    return Some(format!("pass {}: rs274 {:?}, threadcheck {:?}", i + 1, r.pts, t.pts));
                }
                for (j, (p, q)) in r.pts.iter().zip(&t.pts).enumerate() {
                    let tol = r.tol[j];
                    if (p[0] - q[0]).abs() > tol[0] || (p[1] - q[1]).abs() > tol[1] {
                        return Some(format!(
                            "pass {}, point {j}: rs274 X{} Z{}, threadcheck X{} Z{} (mm, X a diameter)",
                            i + 1,
                            p[0],
                            p[1],
                            q[0],
                            q[1]
                        ));
                    }
                }
                for (j, (kr, kt)) in r.k.iter().zip(&t.k).enumerate() {
                    if (kr - kt).abs() > 5.1e-7 + 1e-12 * kt.abs() {
                        return Some(format!("pass {}, feed {j}: rs274 K{kr}, threadcheck K{kt}", i + 1));
                    }
                }
            }
            None
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The generator.

/// A program generator: one seed, one program.
struct Gen {
    r: TestRng,
    s: String,
    /// Program units are inches (G20).
    inch: bool,
    /// X words are diameters (G7).
    dia: bool,
    /// A substring of the refusal threadcheck owes this program (a feature it names and does
    /// not measure), if any.
    refusal: Option<&'static str>,
}

impl Draws for Gen {
    fn rng(&mut self) -> &mut TestRng {
        &mut self.r
    }
}

impl Gen {
    fn new(seed: u64) -> Gen {
        Gen { r: seeded(seed, 37), s: String::new(), inch: false, dia: false, refusal: None }
    }
    /// A number with at most 4 decimals.
    fn n4(v: f64) -> String {
        let s = format!("{v:.4}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        if s == "-0" {
            "0".into()
        } else {
            s.to_string()
        }
    }
    /// A length in mm as program units.
    fn len(&self, mm: f64) -> String {
        Gen::n4(mm / if self.inch { 25.4 } else { 1.0 })
    }
    /// A diameter in mm as an X word's value.
    fn x(&self, dia_mm: f64) -> String {
        self.len(if self.dia { dia_mm } else { dia_mm / 2.0 })
    }
    /// A radial length in mm as a G76 I, J or K value (diameters under G7).
    fn radial(&self, mm: f64) -> String {
        self.len(if self.dia { 2.0 * mm } else { mm })
    }
    fn line(&mut self, l: &str) {
        self.s.push_str(l);
        self.s.push('\n');
    }

    /// A whole program.
    fn program(&mut self, seed: u64) -> String {
        self.inch = self.chance(0.3);
        self.dia = self.chance(0.5);
        self.line(&format!("(threadcheck conformance program, seed {seed})"));
        let units = if self.inch { "G20" } else { "G21" };
        self.line(&format!("G18 G90 {units} G64"));
        self.line(if self.dia { "G7" } else { "G8" });
        if self.chance(0.5) {
            self.line("T1 M6");
        }
        let dir = if self.chance(0.8) { "M3" } else { "M4" };
        let s = self.i(300, 1500);
        self.line(&format!("S{s} {dir}"));
        if self.chance(0.25) {
            let k = self.i(1, 9);
            // A lathe's X offset keeps X0 on the spindle axis: small in X, anything in Z.
            let (ox, oz) = (self.f(-0.5, 0.5), self.f(-30.0, 30.0));
            let (ox, oz) = (self.x(ox), self.len(oz));
            self.line(&format!("G10 L2 P{k} X{ox} Z{oz}"));
            let g = ["", "G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3"][k as usize];
            self.line(g);
        }
        if self.chance(0.03) {
            // LinuxCNC refuses threading with the spindle stopped.
            self.line("M5");
        }
        match self.i(0, 9) {
            0..=3 => self.g76_body(),
            4..=6 => self.g33_body(),
            _ => self.macro_body(),
        }
        self.line("M5");
        self.line("M2");
        std::mem::take(&mut self.s)
    }

    /// A G92 that keeps X near the axis's own coordinates (a lathe's X offset is the axis):
    /// the current X (from `#<_x>`, a radius) moved by up to a millimetre, any Z.
    fn g92(&mut self) -> String {
        let (dx, z) = (self.f(-1.0, 1.0), self.f(-5.0, 5.0));
        let times = if self.dia { 2 } else { 1 };
        format!("G92 X[#<_x> * {times} + {}] Z{}", self.x(dx), self.len(z))
    }

    /// Offsets between operations or passes: G92, G52, G92.1/.2/.3, G10 L2 and L20, G5x.
    fn offsets_between(&mut self) {
        match self.i(0, 12) {
            0 => {
                let g92 = self.g92();
                self.line(&g92);
            }
            1 => {
                let z = self.f(-5.0, 5.0);
                let z = self.len(z);
                self.line(&format!("G52 Z{z}"));
            }
            2 => self.line("G92.1"),
            3 => self.line("G92.2"),
            4 => self.line("G92.3"),
            5 => {
                let k = self.i(1, 6);
                let (x, z) = (self.f(-0.5, 0.5), self.f(-3.0, 3.0));
                let (x, z) = (self.x(x), self.len(z));
                self.line(&format!("G10 L2 P{k} X{x} Z{z}"));
                self.line(&format!("G{}", 53 + k));
            }
            6 => {
                let z = self.f(-3.0, 3.0);
                let z = self.len(z);
                self.line(&format!("G10 L20 P0 Z{z}"));
            }
            7 => self.line("G54"),
            _ => {}
        }
    }

    /// G76 operations with every word.
    fn g76_body(&mut self) {
        let ops = if self.chance(0.2) { 2 } else { 1 };
        for op in 0..ops {
            if op > 0 {
                self.offsets_between();
            }
            let external = self.chance(0.75);
            let d = self.f(8.0, 60.0);
            let p = self.pick(&[0.5, 0.75, 1.0, 1.25, 1.5, 2.0, 2.5, 3.0]);
            let k = 0.6134 * p * self.f(0.9, 1.1);
            let j = k / self.f(2.5, 12.0);
            let clr = self.f(0.2, 2.0);
            let r0 = if external { d / 2.0 + clr } else { (d - 1.0825 * p) / 2.0 - clr };
            let i = if external { -clr } else { clr };
            let length = self.f(5.0, 40.0);
            let toward_minus = self.chance(0.85);
            let zs = if toward_minus { self.f(1.0, 5.0) } else { -length - self.f(1.0, 5.0) };
            let ze = if toward_minus { zs - length } else { zs + length };
            let (x0, z0) = (self.x(2.0 * r0), self.len(zs));
            self.line(&format!("G0 X{x0} Z{z0}"));
            if op == 0 && self.chance(0.2) {
                let g92 = self.g92();
                self.line(&g92);
            }
            let mut w = format!(
                "G76 P{} Z{} I{} J{} K{}",
                self.len(p),
                self.len(ze - zs),
                self.radial(i),
                self.radial(j),
                self.radial(k)
            );
            // Z is absolute: rewrite it from the program coordinates of the start.
            w = w.replace(&format!("Z{}", self.len(ze - zs)), &format!("Z[#<_z> + {}]", self.len(ze - zs)));
            if self.chance(0.6) {
                let r: f64 = self.pick(&[1.0, 1.5, 2.0, 2.5, 3.0, 0.5]);
                if (k / j).powf(r.max(1.0)) <= 80.0 {
                    let _ = write!(w, " R{r}");
                }
            }
            if self.chance(0.7) {
                let q = self.pick(&[0.0, 29.5, 30.0, -1.0, 15.0, 27.5]);
                let _ = write!(w, " Q{q}");
            }
            if self.chance(0.5) {
                let h = self.i(0, 3);
                let _ = write!(w, " H{h}");
            }
            if self.chance(0.5) {
                let e = p * self.f(0.1, 2.0);
                let _ = write!(w, " E{}", self.len(e));
            }
            if self.chance(0.6) {
                let l = self.pick(&[0, 1, 2, 3, 5, 6, 7]);
                let _ = write!(w, " L{l}");
            }
            if self.chance(0.1) {
                let _ = write!(w, " F{}", self.i(10, 200));
            }
            self.line(&w);
        }
    }

    /// G33 passes: single, tapered, chained (straight then a synchronised exit), face (X only),
    /// incremental; work offsets changed between passes.
    fn g33_body(&mut self) {
        let d = self.f(8.0, 50.0);
        let p = self.pick(&[0.5, 1.0, 1.25, 1.5, 2.0, 2.5]);
        let n = self.i(1, 6);
        let depth = 0.6134 * p;
        let zs = self.f(1.0, 4.0);
        let length = self.f(5.0, 30.0);
        let ze = zs - length;
        let kind = self.i(0, 19);
        let clear = d + 2.0;
        for pass in 1..=n {
            if pass > 1 && self.chance(0.1) {
                self.offsets_between();
            }
            let x = d - 2.0 * depth * (pass as f64 / n as f64).sqrt();
            let (xc, z0, xp) = (self.x(clear), self.len(zs), self.x(x));
            self.line(&format!("G0 X{xc} Z{z0}"));
            self.line(&format!("G1 X{xp} F100"));
            let k = self.len(p);
            match kind {
                0..=9 => self.line(&format!("G33 Z{} K{k}", self.len(ze))),
                10..=12 => {
                    // A taper of 1:16 on the diameter.
                    let xe = x + length / 16.0;
                    self.line(&format!("G33 X{} Z{} K{k}", self.x(xe), self.len(ze)));
                }
                13..=16 => {
                    // A chain: the straight, then a synchronised exit at 45° over one lead.
                    let zm = ze + p;
                    self.line(&format!("G33 Z{} K{k}", self.len(zm)));
                    let kk = p * 2f64.sqrt();
                    self.line(&format!("G33 X{} Z{} K{}", self.x(x + 2.0 * p), self.len(ze), self.len(kk)));
                }
                17 => {
                    self.line(&format!("G91 G33 Z{} K{k}", self.len(-length)));
                    self.line("G90");
                }
                _ => {
                    // A face (scroll) thread: X only.
                    self.line(&format!("G33 X{} K{k}", self.x(x - 2.0)));
                    self.refusal = Some("face (scroll) thread");
                }
            }
            self.line(&format!("G0 X{xc}"));
        }
    }

    /// An expression of the language with a finite value (or one both sides refuse alike), and
    /// whether SIN, COS or TAN are in it. LinuxCNC on amd64 computes those three in x87 long
    /// double (`cosl` of its long-double argument), threadcheck in double from that argument:
    /// the last bit can differ, so such a value never meets MOD, FIX, FUP or ROUND here, which
    /// would turn an ulp into a jump (docs/dialects.md says so).
    fn expr(&mut self, depth: u32) -> (String, bool) {
        if depth == 0 || self.chance(0.3) {
            let leaf = match self.i(0, 6) {
                0 => "#<n>".into(),
                6 => self.pick(&["EXISTS[#<_crest>]", "EXISTS[#<nothing>]"]).into(),
                1 => "#<_z>".into(),
                2 => "#<_x>".into(),
                3 => "#100".into(),
                _ => {
                    let v = self.f(-5.0, 5.0);
                    Gen::n4(v)
                }
            };
            return (leaf, false);
        }
        let (a, ta) = self.expr(depth - 1);
        let (b, tb) = self.expr(depth - 1);
        let lit = {
            let v = self.f(0.5, 4.0);
            let v = if self.chance(0.3) { -v } else { v };
            Gen::n4(v)
        };
        let t = ta || tb;
        let op = self.i(0, 25);
        // MOD, FIX, FUP, ROUND and the exact comparisons jump: not on a trig value.
        let op = if ta && matches!(op, 4 | 9 | 15 | 16 | 17 | 18) { 0 } else { op };
        let op = if t && matches!(op, 21 | 22) { 1 } else { op };
        let e = match op {
            0 => format!("[{a} + {b}]"),
            1 => format!("[{a} - {b}]"),
            2 => format!("[{a} * {b}]"),
            3 => format!("[{a} / {lit}]"),
            4 => format!("[{a} MOD {lit}]"),
            5 => format!("[[ABS[{a}] + 0.5] ** {}]", Gen::n4(self.f(-1.5, 1.5))),
            6 => format!("ABS[{a}]"),
            7 => format!("SIN[{a}]"),
            8 => format!("COS[{a}]"),
            9 => format!("TAN[[{a}] MOD 80]"),
            10 => format!("ATAN[{a}]/[{lit}]"),
            11 => format!("ASIN[SIN[{a}]]"),
            12 => format!("ACOS[COS[{a}]]"),
            13 => format!("SQRT[ABS[{a}]]"),
            14 => format!("LN[ABS[{a}] + 1]"),
            15 => format!("EXP[[{a}] MOD 2]"),
            16 => format!("FIX[{a}]"),
            17 => format!("FUP[{a}]"),
            18 => format!("ROUND[{a}]"),
            19 => format!("[{a} EQ {b}]"),
            20 => format!("[{a} NE {b}]"),
            21 => format!("[{a} GT {b}]"),
            22 => format!("[{a} LE {b}]"),
            23 => format!("[[{a} GT 0] AND [{b} LT 0]]"),
            24 => format!("[[{a} GT 0] OR [{b} LT 0]]"),
            _ => format!("[[{a} GT 0] XOR [{b} LT 0]]"),
        };
        let trig = matches!(op, 7 | 8 | 9 | 11 | 12);
        (e, t || trig)
    }

    /// A comparison near its tolerance: EQ and NE within 1e-4 before LinuxCNC 2.9.0, 1e-6
    /// after; LE and GE exact before.
    fn near_cond(&mut self) -> String {
        let delta = self.pick(&["0", "0.0000005", "0.000002", "0.00005", "0.0002", "-0.00005", "-0.0000005"]);
        let op = self.pick(&["EQ", "NE", "LE", "GE", "LT", "GT"]);
        format!("[[#<n> * 0.1] {op} [#<n> * 0.1 + {delta}]]")
    }

    /// A threading macro: O-word subroutines with arguments and return values, loops of every
    /// kind with break and continue, branches, local and global parameters, `#<_x>`/`#<_z>`.
    fn macro_body(&mut self) {
        let d = self.f(8.0, 50.0);
        let p = self.pick(&[0.75, 1.0, 1.5, 2.0, 2.5]);
        let full = 0.6134 * p;
        let first = full / self.f(3.0, 8.0);
        let zs = self.f(1.0, 4.0);
        let ze = zs - self.f(5.0, 30.0);
        // The pass: X (program units), Z start, Z end, K, clearance (program units of X).
        self.line("o<tc_pass> sub");
        self.line("  #<xc> = [#1 + #5]");
        self.line("  G0 X#<xc> Z#2");
        self.line("  G0 X#1");
        self.line("  G33 Z#3 K#4");
        self.line("  G0 X#<xc>");
        self.line("  G0 Z#2");
        self.line("o<tc_pass> endsub");
        // The depth of pass #1 from the first depth #2, the full depth #3 and a law #4.
        self.line("o<tc_depth> sub");
        self.line("  o101 if [#4 EQ 0]");
        self.line("    #<d> = [#2 * SQRT[#1]]");
        self.line("  o101 elseif [#4 EQ 1]");
        self.line("    #<d> = [#2 * #1]");
        self.line("  o101 else");
        self.line("    #<d> = [#2 * [#1 ** 0.6]]");
        self.line("  o101 endif");
        self.line("  o102 if [#<d> GT #3]");
        self.line("    #<d> = #3");
        self.line("  o102 endif");
        self.line("  o<tc_depth> return [#<d>]");
        self.line("o<tc_depth> endsub");
        let (z0, z1, k) = (self.len(zs), self.len(ze), self.len(p));
        let crest = self.x(d);
        let per_depth = if self.dia { 2 } else { 1 };
        let clear = self.x(2.0);
        self.line(&format!("G0 X{} Z{z0}", self.x(d + 2.0)));
        let g100 = self.f(-2.0, 2.0);
        self.line(&format!("#100 = {}", Gen::n4(g100)));
        self.line(&format!("#<_crest> = {crest}"));
        self.line("#<n> = 0");
        let law = self.i(0, 2);
        self.line(&format!("#<law> = {law}"));
        let n_max = self.i(3, 12);
        let kind = self.i(0, 2);
        match kind {
            0 => self.line(&format!("o200 while [#<n> LT {n_max}]")),
            1 => self.line("o200 do"),
            _ => self.line(&format!("o200 repeat [{n_max}]")),
        }
        self.line("  #<n> = [#<n> + 1]");
        self.line(&format!("  o<tc_depth> call [#<n>] [{}] [{}] [#<law>]", self.len(first), self.len(full)));
        self.line(&format!("  #<x> = [#<_crest> - #<_value> * {per_depth}]"));
        let (e, trig) = self.expr(3);
        self.line(&format!("  #<noise> = {e}"));
        if trig {
            self.line("  #<x> = [#<x> - 0.01 * [1 + SIN[#<noise>]]]");
        } else {
            self.line("  #<x> = [#<x> - [ABS[#<noise>] MOD 0.02]]");
        }
        // LinuxCNC refuses break and continue in a repeat loop: now and then.
        let jumps = if kind == 2 { 0.05 } else { 0.4 };
        if self.chance(jumps) {
            let c = self.near_cond();
            self.line(&format!("  o210 if {c}"));
            self.line("    o200 continue");
            if self.chance(0.3) {
                let c2 = self.near_cond();
                self.line(&format!("  o210 elseif {c2}"));
                self.line("    o200 break");
            }
            self.line("  o210 endif");
        }
        self.line(&format!("  o<tc_pass> call [#<x>] [{z0}] [{z1}] [{k}] [{clear}]"));
        if self.chance(jumps * 0.75) {
            self.line(&format!("  o220 if [#<_value> GE {}]", self.len(full)));
            self.line("    o200 break");
            self.line("  o220 endif");
        }
        match kind {
            0 => self.line("o200 endwhile"),
            1 => self.line(&format!("o200 while [#<n> LT {n_max}]")),
            _ => self.line("o200 endrepeat"),
        }
        // Spring passes at the last X, in a loop of another kind.
        let spring = self.i(0, 2);
        if spring > 0 {
            self.line(&format!("o300 repeat [{spring}]"));
            self.line(&format!("  o<tc_pass> call [#<x>] [{z0}] [{z1}] [{k}] [{clear}]"));
            self.line("o300 endrepeat");
        }
    }
}

/// Runs `count` generated programs from `seed` on both sides, on every core.
fn conform(seed: u64, count: u64) {
    let exe = rs274();
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get()) * 2;
    let failures = std::sync::Mutex::new(Vec::new());
    let kinds = std::sync::Mutex::new([0usize; 3]);
    std::thread::scope(|scope| {
        for t in 0..threads as u64 {
            let (exe, failures, kinds) = (&exe, &failures, &kinds);
            scope.spawn(move || {
                let dir = tempdir("rs274");
                let table: String = (1..=20).map(|i| format!("T{i} P{i} D0 ;\n")).collect();
                std::fs::write(dir.join("tool.tbl"), table).unwrap();
                let mut n = seed + t;
                while n < seed + count {
                    let mut g = Gen::new(n);
                    let program = g.program(n);
                    let rs = run_rs274(exe, &program, &dir);
                    let tc = threadcheck(&program);
                    {
                        let mut k = kinds.lock().unwrap();
                        match (&rs, &tc) {
                            (Outcome::Passes(_), Outcome::Passes(_)) => k[0] += 1,
                            (Outcome::Refused(_), _) => k[1] += 1,
                            _ => k[2] += 1,
                        }
                    }
                    if std::env::var_os("THREADCHECK_RS274_VERBOSE").is_some() {
                        if let (Outcome::Refused(r), Outcome::Refused(t)) = (&rs, &tc) {
                            eprintln!("seed {n}: both refuse: rs274 {r} / threadcheck {t}");
                        }
                    }
                    if let Some(why) = compare(g.refusal, &rs, &tc) {
                        failures.lock().unwrap().push(format!("seed {n}: {why}\n{program}"));
                    }
                    n += threads as u64;
                }
                let _ = std::fs::remove_dir_all(&dir);
            });
        }
    });
    let failures = failures.into_inner().unwrap();
    let k = kinds.into_inner().unwrap();
    eprintln!(
        "rs274 conformance: {count} programs from seed {seed}: {} cut by both, {} refused by rs274, {} refused by threadcheck as documented; {} disagree",
        k[0],
        k[1],
        k[2],
        failures.len()
    );
    let mut failures = failures;
    failures.sort();
    let summary: Vec<&str> = failures.iter().take(40).filter_map(|f| f.lines().next()).collect();
    assert!(
        failures.is_empty(),
        "{} of {count} programs disagree with rs274:\n{}\nthe first in full:\n{}",
        failures.len(),
        summary.join("\n"),
        failures[0]
    );
    // The run is not vacuous: most programs cut threads on both sides.
    assert!(k[0] * 10 >= count as usize * 8, "only {} of {count} programs were cut by both", k[0]);
}

fn env_u64(name: &str, default: u64) -> u64 {
    std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

/// Issue 26: generated G76, G33 and macro programs agree with LinuxCNC's interpreter pass for
/// pass.
#[test]
fn generated_programs_agree_with_rs274() {
    conform(env_u64("THREADCHECK_RS274_SEED", 1), env_u64("THREADCHECK_RS274_PROGRAMS", 1000));
}

/// The files named in `THREADCHECK_RS274_FILES` (separated by `:`) agree with `rs274` pass for
/// pass: for programs that are not the project's (tests/rs274-files.sh runs it on the shared
/// corpus).
#[test]
#[ignore = "reads the files named in THREADCHECK_RS274_FILES; run by tests/rs274-files.sh"]
fn named_files_agree_with_rs274() {
    let exe = rs274();
    let files = std::env::var("THREADCHECK_RS274_FILES").expect("THREADCHECK_RS274_FILES names the files");
    let dir = rs274_dir("rs274-files");
    let mut bad = Vec::new();
    for f in files.split(':').filter(|f| !f.is_empty()) {
        let text = std::fs::read_to_string(f).unwrap();
        let (rs, tc) = (run_rs274(&exe, &text, &dir), threadcheck(&text));
        let n = match &rs {
            Outcome::Passes(s) => format!("{} passes", s.len()),
            Outcome::Refused(e) => format!("refused: {e}"),
        };
        match compare(None, &rs, &tc) {
            None => eprintln!("{f}: agrees ({n})"),
            Some(why) => bad.push(format!("{f}: {why}")),
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

/// Issue 47: LinuxCNC's predefined named parameters of the modes (`_lathe_radius_mode`,
/// `_lathe_diameter_mode`, `_coord_system`, `_plane`, `_spindle_on`, `_spindle_cw`,
/// `_spindle_css_mode`, `_spindle_rpm_mode`, `_units_per_rev`, `_units_per_minute`, `_rpm`) were
/// refused as not defined. Each moves the G76's drive line by its own weight, in two programs that
/// set every mode both ways, so a value that differs from `rs274`'s moves every pass.
#[test]
fn predefined_mode_parameters_agree_with_rs274() {
    let exe = rs274();
    let dir = rs274_dir("rs274-predefined");
    let weigh = "#<a> = [#<_lathe_radius_mode> + 2*#<_lathe_diameter_mode> + 4*#<_spindle_on> + 8*#<_spindle_cw> + 16*#<_spindle_css_mode> + 32*#<_spindle_rpm_mode> + 64*#<_units_per_rev> + 128*#<_units_per_minute>]\n#<b> = [#<_coord_system> / 1000 + #<_rpm> / 100000]\n";
    let programs = [
        // Diameter mode, G55, G18, the spindle clockwise at constant rpm, feed per minute.
        format!("G21 G18 G7 G94\nG55\nS500 M3\n{weigh}#<c> = #<_plane>\nG0 X[20 + #<a> / 10] Z[2 + #<b> + #<c> / 1000]\nG76 P1.5 Z-20 I-1 J0.2 K0.92 R2 Q29.5 L0 E0 H0\nM2\n"),
        // Radius mode, G59.3, G17 read then G18 again (a lathe's program: G18 first), counter-clockwise
        // at constant surface speed, per revolution.
        format!("G21 G18 G8 G95\nG59.3\nG96 D1500 S120 M4\nG17\n#<c> = #<_plane>\nG18\n{weigh}G0 X[10 + #<a> / 20] Z[2 + #<b> + #<c> / 1000]\nG76 P1.5 Z-20 I-1 J0.2 K0.92 R2 Q29.5 L0 E0 H0\nM2\n"),
    ];
    for p in &programs {
        let (rs, tc) = (run_rs274(&exe, p, &dir), threadcheck(p));
        assert!(matches!(&rs, Outcome::Passes(s) if !s.is_empty()), "rs274 cut nothing: {p}");
        if let Some(why) = compare(None, &rs, &tc) {
            panic!("{why}\n{p}");
        }
    }
}

/// Issue 47 item 4: LinuxCNC's numbered parameters that follow the program's state (#5220 the
/// coordinate system, #5400 the tool, #5420 and #5422 the current X and Z in program units) were
/// read as unset. Each moves the G76's drive line by its own weight, after a tool change, a G56
/// and a move, in diameter and radius mode, so a value that differs from `rs274`'s moves every
/// pass.
#[test]
fn numbered_state_parameters_agree_with_rs274() {
    let exe = rs274();
    let dir = rs274_dir("rs274-numbered");
    let programs = [
        "G21 G18 G7\nT3 M6\nG56\nS500 M3\nG0 X30 Z5\n#<a> = [#5220 + #5400 / 10 + #5420 / 100 + #5422 / 1000 + #5421 + #5423 + #5428]\nG0 X[20 + #<a>] Z2\nG76 P1.5 Z-20 I-1 J0.2 K0.92 R2 Q29.5 L0 E0 H0\nM2\n",
        "G21 G18 G8\nT7 M6\nG59.3\nS500 M3\nG0 X15 Z4\n#<a> = [#5220 + #5400 / 10 + #5420 / 100 + #5422 / 1000]\nG0 X[10 + #<a> / 2] Z2\nG76 P1.5 Z-20 I-1 J0.2 K0.92 R2 Q29.5 L0 E0 H0\nM2\n",
    ];
    for p in programs {
        let (rs, tc) = (run_rs274(&exe, p, &dir), threadcheck(p));
        assert!(matches!(&rs, Outcome::Passes(s) if !s.is_empty()), "rs274 cut nothing: {p}");
        if let Some(why) = compare(None, &rs, &tc) {
            panic!("{why}\n{p}");
        }
    }
}

/// Issue 47 item 4: more of LinuxCNC's predefined named parameters from the program's state
/// (`_current_tool` after M6 and `_selected_tool` after T, `_motion_mode` G-code × 10,
/// `_ccomp`, `_y` and the other axes, `_call_level` inside a subroutine, `_remap_level`, `_line`
/// the block's line): each moves the G76's drive line by its own weight, so a value that differs
/// from `rs274`'s moves every pass.
#[test]
fn state_parameters_agree_with_rs274() {
    let exe = rs274();
    let dir = rs274_dir("rs274-state-params");
    let p = "G21 G18 G7\nT3 M6\nT2\nG1 X30 Z5 F0.1\no<s> sub\n#<_lvl> = [#<_call_level> + #<_line> / 1000]\no<s> endsub\no<s> call\n#<w> = [#<_current_tool> + #<_selected_tool> * 10 + #<_motion_mode> / 100 + #<_ccomp> / 1000 + #<_y> + #<_a> + #<_b> + #<_c> + #<_u> + #<_v> + #<_w> + #<_lvl> * 100 + #<_remap_level> + #5400 / 10000 + #<_line> / 100000]\nS500 M3\nG0 X[20 + #<w> / 100] Z2\nG76 P1.5 Z-20 I-1 J0.2 K0.92 R2 Q29.5 L0 E0 H0\nM2\n";
    let (rs, tc) = (run_rs274(&exe, p, &dir), threadcheck(p));
    assert!(matches!(&rs, Outcome::Passes(s) if !s.is_empty()), "rs274 cut nothing");
    assert!(compare(None, &rs, &tc).is_none(), "{:?}", compare(None, &rs, &tc));
}

/// Issue 47 item 4: the switches and modes LinuxCNC's predefined parameters read (`_feed`,
/// `_mist`, `_flood`, the overrides M48–M51, `_adaptive_feed` M52, `_feed_hold` M53,
/// `_inverse_time` G93, the return level G98/G99, `_ijk_absolute_mode` G90.1, `_abs_x`/`_abs_z`
/// with a G55 offset), read at the start, after the program sets them and after it resets them:
/// each moves the G76's drive line by its own weight.
#[test]
fn switch_parameters_agree_with_rs274() {
    let exe = rs274();
    let dir = rs274_dir("rs274-switch-params");
    // Two lines each (LinuxCNC reads lines of at most 254 bytes).
    let weigh = |v: &str| {
        format!(
            "#<{v}1> = [#<_feed> + #<_mist> * 2 + #<_flood> * 4 + #<_speed_override> * 8 + #<_feed_override> * 16 + #<_adaptive_feed> * 32 + #<_feed_hold> * 64]\n#<{v}> = [#<{v}1> + #<_inverse_time> * 128 + #<_retract_r_plane> * 256 + #<_retract_old_z> * 512 + #<_ijk_absolute_mode> * 1024 + #<_units_per_minute> * 2048 + #<_abs_x> / 10 + #<_abs_z> / 100 + #<_abs_y>]\n"
        )
    };
    let p = format!(
        "G21 G18 G7\n{}G55\nG10 L2 P2 X1 Z2\nG1 X30 Z5 F0.1\nM7\nM8\nM49\nM52 P1\nM53 P0\nG93\nG98\nG90.1\n{}M9\nM48\nM50 P0\nG94 G99 G91.1\n{}S500 M3\nG0 X[20 + #<a> / 1000 + #<b> / 10000 + #<c> / 100000] Z2\nG76 P1.5 Z-20 I-1 J0.2 K0.92 R2 Q29.5 L0 E0 H0\nM2\n",
        weigh("a"),
        weigh("b"),
        weigh("c")
    );
    let (rs, tc) = (run_rs274(&exe, &p, &dir), threadcheck(&p));
    assert!(matches!(&rs, Outcome::Passes(s) if !s.is_empty()), "rs274 cut nothing");
    assert!(compare(None, &rs, &tc).is_none(), "{:?}", compare(None, &rs, &tc));
}

/// Issue 47 item 5: a subroutine in a file of its own, found where LinuxCNC looks (`rs274`
/// runs in the folder that holds `thr.ngc`; threadcheck's commands search the program's folder and
/// `--subroutine-path`, here a finder that holds the one file). The library reads
/// `#<_lathe_radius_mode>` and the program turns a G90.1 arc before it: the passes agree with
/// `rs274`'s, and a call of a file that is not there is refused at the call.
#[test]
fn a_subroutine_file_beside_the_program_agrees_with_rs274() {
    let exe = rs274();
    let dir = rs274_dir("rs274-sub-file");
    let thr = "o<thr> sub\n#<depth> = [#1 * [2 - #<_lathe_radius_mode>]]\nG76 P1.5 Z-20 I-1 J0.2 K#<depth> R2 Q29.5 L0 E0 H0\no<thr> endsub\nM2\n";
    std::fs::write(dir.join("thr.ngc"), thr).unwrap();
    let p = "G21 G18 G8 G90.1\nS500 M3\nG0 X10 Z2\nG1 X10 Z0 F0.1\nG3 X11 Z-1 I10 K-1\nG0 X12 Z2\no<thr> call [0.92]\nM2\n";
    let finder = threadcheck::SubFinder(std::sync::Arc::new(move |name: &str| {
        (name == "thr").then(|| Ok(("thr.ngc".to_string(), thr.to_string())))
    }));
    let rs = run_rs274(&exe, p, &dir);
    assert!(matches!(&rs, Outcome::Passes(s) if !s.is_empty()), "rs274 cut nothing");
    let tc = threadcheck_with(p, ReadOptions { sub_files: Some(finder), ..ReadOptions::default() });
    assert!(compare(None, &rs, &tc).is_none(), "{:?}", compare(None, &rs, &tc));
    match threadcheck(&p.replace("<thr>", "<missing>")) {
        Outcome::Refused(e) => {
            assert!(e.starts_with("p.ngc:7:1: o<missing> call: no o<missing> sub in this file"), "{e}")
        }
        other => panic!("{other:?}"),
    }
}

/// Issue 47: LinuxCNC's roughing cycle of type 2, `G71.1 Q…`, was read silently as a position
/// block and its profile subroutine reported as never called. It is named as G71 is, its profile
/// counts as called, and the thread after it (from a rapid to its start, as programs write it:
/// where `rs274`'s G71.1 leaves the tool is not modelled) agrees with `rs274` pass for pass;
/// G90.1 is named.
#[test]
fn g71_1_is_named_and_calls_its_profile() {
    let p = "G21 G18 G7 G90.1\nS500 M3\nG0 X22 Z2\nG71.1 Q100 D1 R0.5 F0.2\nG0 X22 Z2\nG76 P1.5 Z-20 I-1 J0.2 K0.92 R2 Q29.5 L0 E0 H0\nM2\no100 sub\nG1 X20 Z0 F0.2\nG1 Z-20\no100 endsub\n";
    let exe = rs274();
    let dir = rs274_dir("rs274-g71-1");
    let (rs, tc) = (run_rs274(&exe, p, &dir), threadcheck(p));
    assert!(compare(None, &rs, &tc).is_none(), "{:?}", compare(None, &rs, &tc));
    std::fs::write(dir.join("g711.ngc"), p).unwrap();
    let o = crate::run_in(&dir, &["passes", "--program", "g711.ngc"]);
    let text = crate::stdout(&o);
    assert!(
        text.contains(
            "note: g711.ngc:4:1: G71.1 read past: a turning or grooving cycle; it returns to its start point"
        ),
        "{text}"
    );
    assert!(text.contains("G90.1 read past: the arc centres' distance mode"), "{text}");
    assert!(!text.contains("never called"), "{text}");
}
