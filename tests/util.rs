//! Helpers shared by every test module: paths into `tests/data`, running the binary, reading
//! its output, and the one Hausdorff distance.

use std::path::{Path, PathBuf};
pub use std::process::{Command, Output};

/// Path to a file in `tests/data`.
pub fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(name)
}

/// Parses a TOML file of `tests/data`.
pub fn data_toml(name: &str) -> toml::Value {
    let text = std::fs::read_to_string(data(name)).unwrap();
    toml::from_str(&text).unwrap()
}

/// Runs the built `threadcheck` binary with `args` in folder `dir`.
pub fn run_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_threadcheck")).args(args).current_dir(dir).output().unwrap()
}

/// Runs the built `threadcheck` binary with `args` in a fresh temporary folder.
pub fn run(args: &[&str]) -> Output {
    let dir = tempdir("run");
    run_in(&dir, args)
}

/// A fresh, empty temporary folder unique to this test and `tag`, removed with everything in it
/// when the value is dropped (a test run used to leave some three hundred folders behind).
pub fn tempdir(tag: &str) -> Scratch {
    let dir = tempfile::Builder::new().prefix(&format!("threadcheck-{tag}-")).tempdir().unwrap();
    Scratch(dir)
}

/// A temporary folder that is removed when dropped; it reads as the [`Path`] of the folder.
pub struct Scratch(tempfile::TempDir);

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        self.0.path()
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        self.0.path()
    }
}

impl AsRef<std::ffi::OsStr> for Scratch {
    fn as_ref(&self) -> &std::ffi::OsStr {
        self.0.path().as_os_str()
    }
}

/// `sweep` over M10 coarse alone (P 1.5), one insert set, the given infeeds, constant area.
pub fn sweep_m10(insert: &str, infeeds: &str, more: &[&str]) -> Output {
    let mut args = vec![
        "sweep",
        "--min-d",
        "10",
        "--max-d",
        "10",
        "--series",
        "coarse",
        "--insert",
        insert,
        "--infeed",
        infeeds,
        "--schedule",
        "constant-area",
    ];
    args.extend_from_slice(more);
    run(&args)
}

/// stdout as text.
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// stderr as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Asserts the run failed with exit code 2 and exactly one line on stderr; returns that line.
pub fn one_line_error(o: &Output) -> String {
    assert_eq!(o.status.code(), Some(2), "stdout: {} stderr: {}", stdout(o), stderr(o));
    let e = stderr(o);
    assert_eq!(e.trim_end().lines().count(), 1, "stderr is not one line: {e:?}");
    e.trim_end().to_string()
}

/// Hausdorff distance between two polylines in the axial plane, mm: every vertex of each against
/// the other's segments (parry's point-to-polyline query). geo's `HausdorffDistance` measures
/// vertex to vertex, which differently tessellated profiles of one curve would fail.
pub fn hausdorff(a: &[threadcheck::Point], b: &[threadcheck::Point]) -> f64 {
    use parry2d_f64::math::Point as P;
    use parry2d_f64::query::PointQuery;
    use parry2d_f64::shape::Polyline;
    let line = |v: &[threadcheck::Point]| Polyline::new(v.iter().map(|p| P::new(p.z, p.r)).collect(), None);
    let (la, lb) = (line(a), line(b));
    let one = |pts: &[threadcheck::Point], l: &Polyline| {
        pts.iter().map(|p| l.distance_to_local_point(&P::new(p.z, p.r), false)).fold(0.0, f64::max)
    };
    one(a, &lb).max(one(b, &la))
}

/// Runs the binary with `args` (a command that ends in `--json -`): its exit code (0 or 1,
/// asserted) and its JSON.
pub fn run_json(args: &[&str]) -> (i32, serde_json::Value) {
    let o = run(args);
    let code = o.status.code().unwrap_or(-1);
    assert!(code == 0 || code == 1, "exit {code}: {}", stderr(&o));
    (code, serde_json::from_slice(&o.stdout).unwrap())
}

/// The check of `feature` in a report's (or one operation's) `checks`.
pub fn check_of<'a>(v: &'a serde_json::Value, feature: &str) -> &'a serde_json::Value {
    v["checks"]
        .as_array()
        .and_then(|cs| cs.iter().find(|c| c["feature"] == feature))
        .unwrap_or_else(|| panic!("no {feature} check in {v}"))
}

/// `verify --program PROGRAM --fix OUT --json -` with `spec` (exit 1: a correction is needed),
/// then `verify` of OUT (exit 0: it lands): the first report, the second, and OUT's text.
pub fn fix_then_verify(program: &Path, spec: &[&str]) -> (serde_json::Value, serde_json::Value, String) {
    let dir = tempdir("fix");
    let ext = program.extension().and_then(|e| e.to_str()).unwrap_or("nc");
    let out = dir.join(format!("fixed.{ext}"));
    let verify = |p: &Path, more: &[&str]| {
        let mut args = vec!["verify", "--program", p.to_str().unwrap()];
        args.extend_from_slice(spec);
        args.extend_from_slice(more);
        args.extend(["--json", "-"]);
        run_in(&dir, &args)
    };
    let o = verify(program, &["--fix", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let before: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let o = verify(&out, &[]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let after: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    (before, after, std::fs::read_to_string(out).unwrap())
}

/// An attribute of a tag's text.
pub fn attr(tag: &str, k: &str) -> Option<String> {
    let v = tag.split(&format!(" {k}=\"")).nth(1)?;
    Some(v[..v.find('"')?].to_string())
}

/// The whole tag of the element whose `id` is `id`.
pub fn tag_of<'a>(svg: &'a str, id: &str) -> &'a str {
    let at = svg.find(&format!("id=\"{id}\"")).unwrap_or_else(|| panic!("no {id} in the SVG"));
    let start = svg[..at].rfind('<').unwrap();
    &svg[start..start + svg[start..].find('>').unwrap()]
}

/// The numeric text labels of the first `<g class="axes">` after `after`: (x, y, value).
pub fn tick_labels(svg: &str, after: &str) -> Vec<(f64, f64, f64)> {
    let from = svg.find(after).unwrap_or_else(|| panic!("no {after} in the SVG"));
    let g = &svg[from..];
    let g = &g[g.find("class=\"axes\"").expect("no axes")..];
    let g = &g[..g.find("</g>").unwrap()];
    g.split("<text")
        .skip(1)
        .filter_map(|part| {
            let tag = &part[..part.find('>')?];
            let content = part[part.find('>')? + 1..part.find("</text>")?].trim();
            let v = content.parse::<f64>().ok()?;
            Some((attr(tag, "x")?.parse().ok()?, attr(tag, "y")?.parse().ok()?, v))
        })
        .collect()
}

/// Where the horizontal line `y` crosses the closed polygon `points` (SVG `x,y x,y …`), sorted.
pub fn crossings(points: &str, y: f64) -> Vec<f64> {
    let p: Vec<(f64, f64)> = points
        .split_whitespace()
        .map(|xy| {
            let (a, b) = xy.split_once(',').unwrap();
            (a.parse().unwrap(), b.parse().unwrap())
        })
        .collect();
    let mut xs = Vec::new();
    for i in 0..p.len() {
        let (a, b) = (p[i], p[(i + 1) % p.len()]);
        if (a.1 - y) * (b.1 - y) < 0.0 {
            xs.push(a.0 + (y - a.1) / (b.1 - a.1) * (b.0 - a.0));
        }
    }
    xs.sort_by(f64::total_cmp);
    xs
}

/// A panel's scales read back from its tick labels: Z (mm) below it, the diameter (mm) at its
/// right; an inch panel's (`Z in`) ticks read as the mm they stand for.
pub struct Scales {
    /// Pixels per mm along Z.
    pub px_per_mm: f64,
    /// Pixels per mm of diameter.
    pub px_per_mm_d: f64,
    /// A diameter tick: its label's baseline y and its value.
    d_tick: (f64, f64),
}

impl Scales {
    /// The scales of the panel whose group is `id`.
    pub fn of(svg: &str, id: &str) -> Scales {
        let from = svg.find(&format!("id=\"{id}\"")).unwrap_or_else(|| panic!("no {id} in the SVG"));
        let axes = &svg[from..];
        let axes = &axes[axes.find("class=\"axes\"").expect("no axes")..];
        let per = if axes[..axes.find("</g>").unwrap()].contains("\nZ in\n") { 25.4 } else { 1.0 };
        let ticks: Vec<(f64, f64, f64)> =
            tick_labels(svg, &format!("id=\"{id}\"")).into_iter().map(|(x, y, v)| (x, y, v * per)).collect();
        let z_row = ticks.iter().map(|t| t.1).fold(f64::NEG_INFINITY, f64::max);
        let z: Vec<_> = ticks.iter().filter(|t| t.1 == z_row).collect();
        let d: Vec<_> = ticks.iter().filter(|t| t.1 != z_row).collect();
        assert!(z.len() >= 2 && d.len() >= 2, "{id}: ticks {ticks:?}");
        Scales {
            px_per_mm: (z[1].0 - z[0].0) / (z[1].2 - z[0].2),
            px_per_mm_d: (d[0].1 - d[1].1) / (d[1].2 - d[0].2),
            d_tick: (d[0].1, d[0].2),
        }
    }

    /// The y of diameter `dia` (a label's baseline sits 3 px under its tick).
    pub fn y_of_d(&self, dia: f64) -> f64 {
        self.d_tick.0 - 3.0 - (dia - self.d_tick.1) * self.px_per_mm_d
    }
}

/// The widths along Z (px) of the tolerance zone's bands `zone_id` where the row `y` crosses
/// them: one a flank, each between its two sides.
pub fn zone_bands(svg: &str, zone_id: &str, y: f64) -> Vec<f64> {
    let zone = tag_of(svg, zone_id);
    let after = &svg[svg.find(zone).unwrap()..];
    let poly = &after[after.find("<polygon").unwrap()..];
    let points = attr(&poly[..poly.find('>').unwrap()], "points").unwrap();
    let xs = crossings(&points, y);
    assert!(xs.len() >= 2 && xs.len() % 2 == 0, "{} crossings of {zone_id} at y {y}", xs.len());
    xs.chunks(2).map(|p| p[1] - p[0]).collect()
}

/// `threadcheck tap --program P --tools T` with `extra` arguments.
pub fn run_tap(program: &Path, tools: &Path, extra: &[&str]) -> Output {
    let mut args = vec!["tap", "--program", program.to_str().unwrap(), "--tools", tools.to_str().unwrap()];
    args.extend(extra);
    run(&args)
}

/// `threadcheck thread-mill` of `tests/data/programs/threadmill/NAME` for M20x1.5-6H with a
/// cutter of `diameter`, with `extra` arguments.
pub fn run_thread_mill(name: &str, diameter: &str, extra: &[&str]) -> Output {
    let p = data(&format!("programs/threadmill/{name}"));
    let mut args = vec![
        "thread-mill",
        "--program",
        p.to_str().unwrap(),
        "--thread",
        "M20x1.5-6H",
        "--cutter-diameter",
        diameter,
    ];
    args.extend(extra);
    run(&args)
}
