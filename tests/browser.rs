//! Issue 15: the pictures and the HTML report as a person sees them, rendered by headless
//! Chromium and checked pixel by pixel. Without Chromium these tests fail with a message: they
//! never pass unseen (`.ci/run` installs Debian's `chromium` when it is missing).

use crate::*;
use std::path::{Path, PathBuf};

/// Chromium, or a failure that says how to get it.
fn chromium() -> PathBuf {
    for dir in std::env::var("PATH").unwrap_or_default().split(':').chain(["/usr/bin"]) {
        for name in ["chromium", "chromium-browser"] {
            let p = Path::new(dir).join(name);
            if p.is_file() {
                return p;
            }
        }
    }
    panic!("Chromium is not installed: the browser tests need it (apt-get install chromium; .ci/run installs it)");
}

/// A screenshot: its size, RGB pixels and Chromium's log (console messages included).
struct Shot {
    w: usize,
    h: usize,
    rgb: Vec<[u8; 3]>,
    log: String,
}

impl Shot {
    fn at(&self, x: usize, y: usize) -> [u8; 3] {
        self.rgb[y * self.w + x]
    }
}

/// Opens `file` in headless Chromium with a `w`×`h` window and takes a screenshot.
fn screenshot(file: &Path, w: usize, h: usize) -> Shot {
    let dir = tempdir("chromium");
    let png = dir.join("shot.png");
    let out = std::process::Command::new(chromium())
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--hide-scrollbars",
            "--enable-logging=stderr",
            "--v=0",
            "--force-device-scale-factor=1",
        ])
        .arg(format!("--user-data-dir={}", dir.join("profile").display()))
        .arg(format!("--window-size={w},{h}"))
        .arg(format!("--screenshot={}", png.display()))
        .arg(format!("file://{}", file.display()))
        .output()
        .unwrap();
    assert!(png.is_file(), "Chromium wrote no screenshot: {}", String::from_utf8_lossy(&out.stderr));
    Shot { log: String::from_utf8_lossy(&out.stderr).into_owned(), ..read_png(&png) }
}

/// Nothing runs off a page's sides: its outer columns stay background.
fn edges_stay_background(shot: &Shot, what: &str) {
    for y in 0..shot.h {
        for x in [0, 1, shot.w - 2, shot.w - 1] {
            let [r, g, b] = shot.at(x, y);
            assert!(
                u32::from(r) + u32::from(g) + u32::from(b) > 600,
                "{what}: dark pixel at the page's edge ({x}, {y})"
            );
        }
    }
}

/// The console messages Chromium logged for the page (it logs `console.error` at INFO level, so
/// every message counts: the reports have no script, so any message is an error).
fn console_errors(log: &str) -> Vec<&str> {
    log.lines().filter(|l| l.contains(":CONSOLE") || l.contains("Uncaught")).collect()
}

/// The translucent tolerance zone over the as-cut material (blue-grey) and over the air
/// (white): green dominates in both.
fn zone_over_material(p: [u8; 3]) -> bool {
    let [r, g, b] = p.map(i32::from);
    g > r + 25 && g > b && g < 215
}

fn zone_over_air(p: [u8; 3]) -> bool {
    let [r, g, b] = p.map(i32::from);
    g > r + 20 && g > b + 10 && g >= 215
}

/// The y of an SVG line element `id` (its `y1`).
fn line_y(svg: &str, id: &str) -> f64 {
    let at = svg.find(&format!("id=\"{id}\"")).unwrap_or_else(|| panic!("no {id} in the SVG"));
    let tag_start = svg[..at].rfind('<').unwrap();
    let tag = &svg[tag_start..tag_start + svg[tag_start..].find('>').unwrap()];
    let v = tag.split("y1=\"").nth(1).unwrap();
    v[..v.find('"').unwrap()].parse().unwrap()
}

/// The SVG's width and height.
fn svg_size(svg: &str) -> (usize, usize) {
    let attr = |k: &str| -> usize {
        let v = svg.split(&format!(" {k}=\"")).nth(1).unwrap();
        v[..v.find('"').unwrap()].parse::<f64>().unwrap().ceil() as usize
    };
    (attr("width"), attr("height"))
}

/// The tolerance zone shows on both sides of the as-cut flank at the pitch diameter, over the
/// material and over the air, for a bolt and for a nut; and no dark pixel touches the picture's
/// edges (no text clipped).
#[test]
fn tolerance_zone_shows_on_both_sides_of_d2_for_bolt_and_nut() {
    for (thread, extra, id) in [
        ("M10x1.5-6g", None, "tooth-dim-pitch_diameter"),
        ("M10x1.5-6H", Some("--internal"), "tooth-dim-pitch_diameter"),
    ] {
        let dir = tempdir("zone");
        let svg_path = dir.join("v.svg");
        let mut args = vec!["verify", "--thread", thread, "--svg", svg_path.to_str().unwrap()];
        args.extend(extra);
        let o = run(&args);
        assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
        let svg = std::fs::read_to_string(&svg_path).unwrap();
        let (w, h) = svg_size(&svg);
        let shot = screenshot(&svg_path, w, h);
        assert_eq!((shot.w, shot.h), (w, h));
        let y = line_y(&svg, id).round() as usize;
        // The tooth panel spans x 200 … 630.
        let count = |rows: std::ops::Range<usize>, f: fn([u8; 3]) -> bool| {
            rows.flat_map(|yy| (200..630).map(move |x| (x, yy))).filter(|&(x, yy)| f(shot.at(x, yy))).count()
        };
        for (rows, side) in [(y - 8..y - 2, "above"), (y + 3..y + 9, "below")] {
            let m = count(rows.clone(), zone_over_material);
            let a = count(rows, zone_over_air);
            assert!(m >= 6 && a >= 6, "{thread}: zone {side} d2: {m} px over material, {a} px over air");
        }
        for (x, yy) in (0..w)
            .flat_map(|x| [(x, 0), (x, 1), (x, h - 2), (x, h - 1)])
            .chain((0..h).flat_map(|yy| [(0, yy), (1, yy), (w - 2, yy), (w - 1, yy)]))
        {
            let [r, g, b] = shot.at(x, yy);
            assert!(
                u32::from(r) + u32::from(g) + u32::from(b) > 600,
                "{thread}: dark pixel at the edge ({x}, {yy})"
            );
        }
    }
}

/// The HTML report opens offline with no console error, its picture inline; the detector itself
/// sees an error when a page has one.
#[test]
fn html_report_renders_without_console_errors() {
    let dir = tempdir("html");
    let bad = dir.join("bad.html");
    std::fs::write(
        &bad,
        "<!DOCTYPE html><html><body><script>console.error('planted')</script></body></html>",
    )
    .unwrap();
    assert!(
        !console_errors(&screenshot(&bad, 400, 300).log).is_empty(),
        "the console-error detector saw nothing"
    );
    let html = dir.join("r.html");
    let o = run(&["verify", "--thread", "M10x1.5-6g", "--html", html.to_str().unwrap()]);
    assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
    let text = std::fs::read_to_string(&html).unwrap();
    // Self-contained: the picture inline, no script, no outside resource.
    assert!(
        text.contains("<svg")
            && !text.contains("<script")
            && !text.contains("src=")
            && !text.contains("<link")
    );
    let shot = screenshot(&html, 1200, 1600);
    assert!(console_errors(&shot.log).is_empty(), "{:?}", console_errors(&shot.log));
    edges_stay_background(&shot, "HTML report");
    // The verdict is drawn: some dark-green or red text in the top 200 px.
    let coloured = (0..200).flat_map(|y| (0..1200).map(move |x| (x, y))).filter(|&(x, y)| {
        let [r, g, b] = shot.at(x, y);
        (r > 150 && g < 80 && b < 80) || (g > 90 && r < 60 && b < 90)
    });
    assert!(coloured.count() > 50, "no verdict drawn");
}

/// A box: x0, y0, x1, y1 in px.
type Boxed = [f64; 4];

/// Every text's box, estimated (0.6 em per character, an em tall), and every panel's frame.
fn layout(svg: &str) -> (Vec<(String, Boxed)>, Vec<Boxed>) {
    let mut texts = Vec::new();
    for part in svg.split("<text").skip(1) {
        let tag = &part[..part.find('>').unwrap()];
        let content = &part[part.find('>').unwrap() + 1..part.find("</text>").unwrap()];
        let content = content.trim().replace("&lt;", "<").replace("&gt;", ">").replace("&amp;", "&");
        let n = |k: &str| attr(tag, k).unwrap().parse::<f64>().unwrap();
        let (x, y, size) = (n("x"), n("y"), n("font-size"));
        let w = 0.6 * size * content.chars().count() as f64;
        let x0 = match attr(tag, "text-anchor").as_deref() {
            Some("end") => x - w,
            Some("middle") => x - 0.5 * w,
            _ => x,
        };
        if !content.trim().is_empty() {
            texts.push((content, [x0, y - 0.8 * size, x0 + w, y + 0.2 * size]));
        }
    }
    let panels = svg
        .split("<rect")
        .skip(1)
        .map(|p| &p[..p.find('>').unwrap()])
        .filter(|t| t.contains("class=\"panel\""))
        .map(|t| {
            let n = |k: &str| attr(t, k).unwrap().parse::<f64>().unwrap();
            [n("x"), n("y"), n("x") + n("width"), n("y") + n("height")]
        })
        .collect();
    (texts, panels)
}

fn overlap(a: [f64; 4], b: [f64; 4]) -> bool {
    a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
}

/// No label crosses another label, none lies on a panel where the profiles are drawn, and every
/// one is inside the picture: the text boxes computed from the SVG, for a bolt that passes, a
/// failing partial-insert bolt with long inch labels, and a nut.
#[test]
fn svg_labels_do_not_overlap_each_other_or_the_panels() {
    for args in [
        vec!["--thread", "M10x1.5-6g", "--insert", "full"],
        vec!["--thread", "M20x2.5-6g", "--final-x", "17.2", "--units", "inch", "--gauge-only"],
        vec!["--thread", "M10x1.5-6H", "--internal"],
        vec!["--thread", "1/4-20 UNC-2A"],
    ] {
        let dir = tempdir("layout");
        let path = dir.join("v.svg");
        let mut all = vec!["verify"];
        all.extend(&args);
        all.extend(["--svg", path.to_str().unwrap()]);
        let o = run(&all);
        assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
        let svg = std::fs::read_to_string(&path).unwrap();
        let panels = assert_laid_out(&svg, &format!("{args:?}"));
        assert!(panels >= 4, "{args:?}: {panels} panels");
    }
}

/// Nothing written in `svg` leaves the picture, lies on a panel or crosses another label;
/// returns the number of panels.
fn assert_laid_out(svg: &str, what: &str) -> usize {
    let (w, h) = svg_size(svg);
    let (texts, panels) = layout(svg);
    for (i, (ta, a)) in texts.iter().enumerate() {
        assert!(
            a[0] >= 0.0 && a[1] >= 0.0 && a[2] <= w as f64 && a[3] <= h as f64,
            "{what}: '{ta}' leaves the picture"
        );
        for p in &panels {
            assert!(!overlap(*a, *p), "{what}: '{ta}' lies on a panel");
        }
        for (tb, b) in &texts[i + 1..] {
            assert!(!overlap(*a, *b), "{what}: '{ta}' crosses '{tb}'");
        }
    }
    panels.len()
}

/// Issue 28: the fit picture is laid out as verify's: nothing written leaves the picture, lies
/// on a panel or crosses another label, and the clearance is dimensioned at the tightest place
/// (47.0 µm for mid-tolerance M10x1.5-6H/6g: (9.116 − 8.928)/2 · sin 30°), or the interference
/// in red when the bolt is cut too large.
#[test]
fn fit_svg_is_laid_out_and_dimensions_the_clearance() {
    for (args, says) in [
        (vec!["--bolt-insert", "full", "--nut-insert", "full"], "clearance 47.0 µm"),
        (vec!["--bolt-insert", "full", "--nut-insert", "full", "--bolt-final-x", "8.3"], "interference"),
    ] {
        let dir = tempdir("fit-layout");
        let path = dir.join("f.svg");
        let mut all = vec!["fit", "--thread", "M10x1.5-6H/6g"];
        all.extend(&args);
        all.extend(["--svg", path.to_str().unwrap()]);
        let o = run(&all);
        assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
        let svg = std::fs::read_to_string(&path).unwrap();
        assert!(svg.contains("id=\"clearance-dimension\"") && svg.contains(says), "{args:?}: {says}");
        let panels = assert_laid_out(&svg, &format!("{args:?}"));
        assert_eq!(panels, 2, "{args:?}: the pair and the tightest place");
    }
}

/// Issue 28: screenshots of the fit picture, the compare page and an inch picture, looked at as
/// verify's are: nothing dark at the edges (nothing cut off), no console error; the interfering
/// fit shows red in the magnified tightest place; the inch picture its axes.
#[test]
fn screenshots_of_fit_compare_and_inch_pictures() {
    let dir = tempdir("shots");
    let edges_clean = |shot: &Shot, what: &str| {
        for (x, y) in (0..shot.w)
            .flat_map(|x| [(x, 0), (x, 1), (x, shot.h - 2), (x, shot.h - 1)])
            .chain((0..shot.h).flat_map(|y| [(0, y), (1, y), (shot.w - 2, y), (shot.w - 1, y)]))
        {
            let [r, g, b] = shot.at(x, y);
            assert!(
                u32::from(r) + u32::from(g) + u32::from(b) > 600,
                "{what}: dark pixel at the edge ({x}, {y})"
            );
        }
    };
    let fit = dir.join("fit.svg");
    let o = run(&[
        "fit",
        "--thread",
        "M10x1.5-6H/6g",
        "--bolt-insert",
        "full",
        "--nut-insert",
        "full",
        "--bolt-final-x",
        "8.3",
        "--svg",
        fit.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let (w, h) = svg_size(&std::fs::read_to_string(&fit).unwrap());
    let shot = screenshot(&fit, w, h);
    edges_clean(&shot, "fit");
    // The tightest place's panel (x 650…970, y 106…366): the overlap drawn red.
    let red = (106..366).flat_map(|y| (650..970).map(move |x| (x, y))).filter(|&(x, y)| {
        let [r, g, b] = shot.at(x, y);
        r > 120 && u32::from(r) > u32::from(g) + 40 && u32::from(r) > u32::from(b) + 40
    });
    assert!(red.count() > 500, "no red overlap in the magnified tightest place");
    let page = dir.join("c.html");
    let o = run(&["compare", "--thread", "M10x1.5-6g", "--insert", "full", "--html", page.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let shot = screenshot(&page, 1200, 1600);
    assert!(console_errors(&shot.log).is_empty(), "{:?}", console_errors(&shot.log));
    // A page scrolls down: only its sides must stay background.
    edges_stay_background(&shot, "compare page");
    let inch = dir.join("i.svg");
    let o =
        run(&["verify", "--thread", "1/2-13 UNC-2A", "--final-x", "10.2", "--svg", inch.to_str().unwrap()]);
    assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
    let (w, h) = svg_size(&std::fs::read_to_string(&inch).unwrap());
    edges_clean(&screenshot(&inch, w, h), "inch picture");
}

/// `verify --html` for a program cutting two threads: one section per operation, and user text
/// (here the program's file name) escaped. `compare --html`: one table row and one picture per
/// strategy (radial, flank, one modified angle, alternating × two schedules = 8).
#[test]
fn html_reports_of_programs_and_comparisons() {
    let dir = tempdir("html-program");
    let name = "two<b>&threads.nc";
    std::fs::write(
        dir.join(name),
        "G21 G97 S500 M3\nG0 X22 Z5\nG76 P010060 Q100 R0.02\nG76 X18.2 Z-20 P900 Q300 F1.5\nG0 X12 Z5\nG92 X9.6 Z-15 F1.5\nX9.2\nX8.8\nX8.4\nX8.2\nG0 X50\nM30\n",
    )
    .unwrap();
    let o = run_in(
        &dir,
        &[
            "verify",
            "--thread",
            "M20x1.5-6g",
            "--thread",
            "M10x1.5-6g",
            "--program",
            name,
            "--insert",
            "full",
            "--html",
            "r.html",
        ],
    );
    assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
    let html = std::fs::read_to_string(dir.join("r.html")).unwrap();
    assert!(html.contains("Operation 1 of 2") && html.contains("Operation 2 of 2"));
    assert_eq!(html.matches("<svg").count(), 2);
    assert!(html.contains("two&lt;b&gt;&amp;threads.nc") && !html.contains("two<b>"));
    let o = run_in(
        &dir,
        &["compare", "--thread", "M10x1.5-6g", "--insert", "full", "--modified", "29.5", "--html", "c.html"],
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let html = std::fs::read_to_string(dir.join("c.html")).unwrap();
    // One picture per infeed (radial, flank 30°, modified 29.5°, alternating 30°), one row per
    // infeed and schedule, and the recommendation.
    assert_eq!(html.matches("<svg").count(), 4);
    assert_eq!(html.matches("<tr><td>").count(), 8, "8 strategy rows");
    assert!(html.contains("recommended: modified 29.5° infeed, constant-area"), "{}", &html[..2000]);
    // The default comparison (five infeeds) stays small.
    let o = run_in(&dir, &["compare", "--thread", "M10x1.5-6g", "--html", "d.html"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let size = std::fs::metadata(dir.join("d.html")).unwrap().len();
    assert!(size < 300_000, "the default comparison's page is {size} bytes");
}

/// A PNG file's pixels.
fn read_png(path: &Path) -> Shot {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    let ch = match info.color_type {
        png::ColorType::Rgba => 4,
        png::ColorType::Rgb => 3,
        other => panic!("unexpected PNG colour type {other:?}"),
    };
    let rgb = buf[..info.buffer_size()].chunks(ch).map(|c| [c[0], c[1], c[2]]).collect();
    Shot { w: info.width as usize, h: info.height as usize, rgb, log: String::new() }
}

/// Node and playwright-core (tests/page's lock file), or a failure that says how to get them.
fn playwright() -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/page");
    let node = std::process::Command::new("node").arg("--version").output();
    assert!(
        node.is_ok_and(|o| o.status.success()),
        "Node.js is not installed: the page tests need it (apt-get install nodejs npm; tests/install-and-test.sh installs it)"
    );
    assert!(
        dir.join("node_modules/playwright-core/package.json").is_file(),
        "playwright-core is not installed in tests/page: run `npm ci` there (tests/install-and-test.sh does)"
    );
    dir.join("page.mjs")
}

/// Issue 30: the page as a machinist uses it, in Chromium: paste a program, choose the thread
/// and the insert, verify, read the verdict and the correction, download the corrected program
/// and the report; upload a LinuxCNC file; a bad designation; compare, fit and limits. The page
/// shows what the command line says for the same input, the pictures load inside the window,
/// nothing is wider than the window, and the console stays empty.
#[test]
fn page_in_chromium() {
    let script = playwright();
    let chromium = chromium();
    let server = crate::serve::start(&[]);
    let out = tempdir("page");
    let program = data("programs/fanuc-g76-timing.nc");
    let upload = data("programs/linuxcnc-g76.ngc");
    let tap_program = data("programs/tapping/m10-cycle84.mpf");
    let mill_program = data("programs/threadmill/m20-dc14.nc");
    let misfit = data("programs/m30x1.5-turned.nc");
    let o = std::process::Command::new("node")
        .arg(&script)
        .arg(&server.url)
        .arg(&out)
        .arg(&chromium)
        .arg(&program)
        .arg(&upload)
        .arg(&tap_program)
        .arg(&mill_program)
        .arg(&misfit)
        .output()
        .unwrap();
    assert!(o.status.success(), "the page script failed: {}", String::from_utf8_lossy(&o.stderr));
    let seen: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    // The one message: the browser's own line for the bad designation's 400 answer.
    assert_eq!(
        seen["console"],
        serde_json::json!([
            "bad-designation: error: Failed to load resource: the server responded with a status of 400 (Bad Request)",
            "misfit: error: Failed to load resource: the server responded with a status of 400 (Bad Request)",
            "nonstandard: error: Failed to load resource: the server responded with a status of 400 (Bad Request)"
        ]),
        "console messages"
    );
    assert_eq!(seen["title"], "threadcheck");

    // Every field starts empty (issue 59): the program's own naming and tools are used.
    assert_eq!(
        seen["fields_as_found"],
        serde_json::json!({"thread": "", "insert": "", "tap_tools": "", "mill_thread": "", "mill_diameter": ""})
    );
    // The verdict and the correction, as the CLI gives them for the same program, nothing else
    // given: the thread its comment names (M20X1.5), the full-profile insert assumed and the
    // form it alone decides unverified.
    let p = program.to_str().unwrap();
    let cli = run(&["verify", "--program", p, "--json", "-"]);
    let v: serde_json::Value = serde_json::from_slice(&cli.stdout).unwrap();
    // With the insert assumed no correction is offered (it would rest on the assumption): the
    // next step is the insert, with the pitch diameter the other candidate leaves, and no
    // corrected program to download.
    let withheld = v["operations"][0]["notes"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|n| n.as_str())
        .find(|n| n.starts_with("no correction is offered"))
        .unwrap()
        .replace("give --insert or --tools", "choose the Insert or give a tool table");
    assert!(v["operations"][0]["correction"].is_null());
    let full = run(&["verify", "--program", p, "--insert", "full", "--json", "-"]);
    let full: serde_json::Value = serde_json::from_slice(&full.stdout).unwrap();
    let correction =
        full["operations"][0]["correction"]["text"].as_str().unwrap().replace(p, "pasted program");
    assert_eq!(
        seen["verdict"],
        "OUT OF TOLERANCE — form unverified: tool not known (choose the insert or a tool table)"
    );
    let unverified = seen["checks"].as_array().unwrap().iter().find(|r| r[0] == "root radius").unwrap();
    assert_eq!(unverified[6], "unverified");
    assert_eq!(seen["correction"].as_str().unwrap(), format!("Next: {withheld}"));
    assert_eq!(seen["fixed_visible_as_found"], false);
    // The insert chosen (full profile): the CLI's correction.
    assert_eq!(seen["correction_full"].as_str().unwrap(), format!("Next: {correction}"));
    // The G76 sheet's result: d2 19.066 against 6g's 18.994, 72.0 µm over.
    let d2 = seen["checks"].as_array().unwrap().iter().find(|r| r[0] == "pitch diameter").unwrap();
    assert_eq!(d2[2], "19.0660");
    // Issue 43: the page's table reads like the SVG's: a signed deviation, OUT, yes/no in words.
    assert_eq!(d2[5], "+72.0 µm");
    assert_eq!(d2[6], "OUT");
    let groove = seen["checks"].as_array().unwrap().iter().find(|r| r[0] == "single groove").unwrap();
    assert_eq!(
        (groove[2].as_str(), groove[3].as_str(), groove[6].as_str()),
        (Some("yes"), Some(""), Some("ok"))
    );
    // Every pass shows its program line: G76 X18.2 (the two-block G76's second block).
    let passes = seen["passes"].as_array().unwrap();
    assert_eq!(passes.len(), v["operations"][0]["passes"].as_array().unwrap().len());
    assert!(passes.iter().all(|r| r[5] == "6" && r[6] == "G76 X18.2 Z-20. P900 Q450 F1.5"), "{passes:?}");

    // Downloads: the corrected program is `verify --fix -`; the report is `--html`'s page.
    let fixed = run(&["verify", "--program", p, "--insert", "full", "--fix", "-"]);
    let got = std::fs::read(seen["fixed.nc"]["path"].as_str().unwrap()).unwrap();
    let expected = String::from_utf8(fixed.stdout).unwrap().replace(p, "pasted program");
    assert_eq!(String::from_utf8(got).unwrap(), expected);
    assert_eq!(seen["fixed.nc"]["suggested"], "program-fixed.nc");
    let report = std::fs::read_to_string(seen["report.html"]["path"].as_str().unwrap()).unwrap();
    assert!(report.starts_with("<!DOCTYPE html>") && report.contains("<svg"), "{}", &report[..200]);
    let json: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(seen["report.json"]["path"].as_str().unwrap()).unwrap(),
    )
    .unwrap();
    assert_eq!(json["verdict"], "fail");

    // The uploaded .ngc is read as LinuxCNC because of its name, and the page says so.
    assert!(
        seen["upload_heading"].as_str().unwrap().starts_with("Operation 1: G76 at line 6"),
        "{}",
        seen["upload_heading"]
    );
    let notes = seen["upload_notes"].as_array().unwrap();
    assert!(notes.iter().any(|n| n.as_str().unwrap().contains("linuxcnc")), "{notes:?}");

    // A bad designation: the CLI's line.
    let bad = run(&["verify", "--thread", "M20x1.5-6q"]);
    let line = stderr(&bad).trim().strip_prefix("threadcheck: error: ").unwrap().to_string();
    assert_eq!(seen["error"].as_str().unwrap(), line);
    // Issue 43: after the error nothing of the previous answer remains: no result, verdict,
    // next step, download, operation or picture (the screenshot after-error.png shows it).
    assert_eq!(
        seen["after_error"],
        serde_json::json!({
            "result_visible": false, "verdict": "", "next_visible": false, "fixed_visible": false,
            "operations": 0, "picture": null
        }),
        "what the page shows after an error"
    );
    let after = read_png(Path::new(seen["shots"]["after-error"].as_str().unwrap()));
    let zone = after.rgb.iter().filter(|&&p| zone_over_material(p) || zone_over_air(p)).count();
    assert!(zone < 50, "a tolerance zone ({zone} pixels) is on screen after the error");
    // A designation typed by mistake over an M30x1.5 program (issue 59): refused naming both
    // diameters (the passes' X28.160 is d3 of M30x1.5, 30 − 2·0.920; M20x1.5's d3 is 18.160), and
    // nothing on the page offers a correction.
    let misfit = &seen["misfit"];
    assert_eq!(
        misfit["error"],
        "pasted program:12:1: G76: the passes cut about Ø30.0 (final X28.160), the designation M20x1.5-6g is Ø20 (d3 18.160): they differ by more than a thread depth; check the thread (the passes fit M30x1.5-6g, inferred)"
    );
    assert_eq!(misfit["next_visible"], false);
    assert_eq!(misfit["corrections"], serde_json::json!([]));
    // A pasted program is called so; the error of a size outside the series names the page's
    // control, and ticking it verifies the thread.
    let heading = seen["pasted_heading"].as_str().unwrap();
    assert!(heading.contains("pasted program") && !heading.contains("<program>"), "{heading}");
    let nonstandard = seen["nonstandard_error"].as_str().unwrap();
    assert!(
        nonstandard.contains("(tick 'non-standard size')") && !nonstandard.contains("allow_nonstandard"),
        "{nonstandard}"
    );
    // The plan with the partial insert fails on form alone: the banner says so, and the hint
    // names the page's controls (issue 43's first run).
    let banner = seen["nonstandard_verdict"].as_str().unwrap();
    assert!(banner.starts_with("OUT OF TOLERANCE — form only: the insert's tip"), "{banner}");
    let hint = seen["nonstandard_hint"].as_str().unwrap();
    assert!(
        hint.contains("(Insert: full profile)")
            && hint.contains("the 'gauge only' box")
            && !hint.contains("--"),
        "{hint}"
    );

    // Compare: one row per strategy of `compare --json`; fit: the CLI's verdict; limits: ISO 965-2.
    let c = run(&["compare", "--thread", "M10x1.5-6g", "--json", "-"]);
    let c: serde_json::Value = serde_json::from_slice(&c.stdout).unwrap();
    assert_eq!(seen["compare_rows"].as_u64().unwrap() as usize, c["strategies"].as_array().unwrap().len());
    assert!(seen["compare_recommended"].as_str().unwrap().starts_with("Recommended: "));
    assert!(seen["fit"].as_str().unwrap().starts_with("FITS: clearance"), "{}", seen["fit"]);
    let limits = seen["limits"].as_array().unwrap();
    let d2 = limits.iter().find(|r| r[1] == "pitch diameter").unwrap();
    assert_eq!((d2[2].as_str().unwrap(), d2[3].as_str().unwrap()), ("8.8620", "8.9940"));
    // Rolled (issue 64): the dies set d2 at 6g's middle, 8.928, and form the root H/3 under the
    // pitch line, 8.928 − (2/3)·0.866025·1.5 = 8.0620; the blank for the full crest beside them.
    let rolled = seen["limits_rolled"].as_array().unwrap();
    assert_eq!(rolled.len(), 3, "{rolled:?}");
    assert_eq!(
        (rolled[0][1].as_str(), rolled[0][2].as_str()),
        (Some("pitch diameter the dies set"), Some("8.9280"))
    );
    assert_eq!((rolled[1][1].as_str(), rolled[1][2].as_str()), (Some("root the dies form"), Some("8.0620")));
    assert_eq!(rolled[2][1], "blank for the full crest");

    // Tap: the uploaded Sinumerik program's two CYCLE84 pass, as `tap` says; eight rows of checks,
    // and each hole's percent of thread, (10 − 8.5)/(0.01299·1.5) = 77.0 %, and the torque of a
    // plug hand tap in Ck 45, tan 30° · 3900 · 1.35 · 1.5² · 27 / 24 000 = 7.69 N·m (issue 64).
    assert_eq!(seen["tap"], "IN TOLERANCE: 2 tapping cycles, 2 drilling cycles");
    let tap_rows = seen["tap_rows"].as_array().unwrap();
    assert_eq!(tap_rows.len(), 12);
    let percent: Vec<&serde_json::Value> = tap_rows.iter().filter(|r| r[2] == "thread %").collect();
    assert_eq!(percent.len(), 2);
    assert_eq!(
        (percent[0][3].as_str(), percent[0][4].as_str(), percent[0][5].as_str()),
        (Some("77.0"), Some("60"), Some("75"))
    );
    let torque: Vec<&serde_json::Value> = tap_rows.iter().filter(|r| r[2] == "torque N·m").collect();
    assert_eq!(torque.len(), 2);
    assert_eq!(torque[0][3], "7.69");
    assert!(
        torque[0][7].as_str().unwrap().contains("Ck 45, kc 3900 N/mm², hand-plug tap, K 1.35"),
        "{:?}",
        torque[0]
    );
    let d1 = tap_rows.iter().find(|r| r[2] == "drill diameter").unwrap();
    assert_eq!(
        (d1[3].as_str(), d1[4].as_str(), d1[5].as_str()),
        (Some("8.5000 mm"), Some("8.3760"), Some("8.6760"))
    );
    // Thread mill: the Ø14 cutter's distortion as the CLI gives it (+38.8 µm, README).
    let m = run(&[
        "thread-mill",
        "--program",
        mill_program.to_str().unwrap(),
        "--thread",
        "M20x1.5-6H",
        "--cutter-diameter",
        "14",
        "--json",
        "-",
    ]);
    let m: serde_json::Value = serde_json::from_slice(&m.stdout).unwrap();
    assert_eq!(seen["mill"], if m["verdict"] == "pass" { "IN TOLERANCE" } else { "OUT OF TOLERANCE" });
    let want = format!("profile distortion {:.1} µm", m["distortion_pitch_diameter_um"].as_f64().unwrap());
    assert!(seen["mill_distortion"].as_str().unwrap().contains(&want), "{}", seen["mill_distortion"]);
    assert_eq!(seen["mill_rows"].as_array().unwrap().len(), m["checks"].as_array().unwrap().len());

    // Layout: nothing wider than the window, every picture loaded and inside it.
    for (name, l) in seen["layout"].as_object().unwrap() {
        assert!(
            l["scroll_width"].as_f64() <= l["viewport_width"].as_f64(),
            "{name}: wider than the window: {l}"
        );
        for pic in l["pictures"].as_array().unwrap() {
            assert_eq!(pic["loaded"], true, "{name}: {pic}");
            assert!(
                pic["left"].as_f64().unwrap() >= 0.0 && pic["right"].as_f64() <= l["viewport_width"].as_f64(),
                "{name}: {pic}"
            );
            assert!(pic["height"].as_f64().unwrap() > 200.0, "{name}: {pic}");
        }
    }
    // The screenshots: the red verdict banner and the picture's tolerance zone are on screen.
    let shot = read_png(Path::new(seen["shots"]["verify"].as_str().unwrap()));
    let near = |p: [u8; 3], q: [u8; 3]| p.iter().zip(q).all(|(a, b)| a.abs_diff(b) <= 3);
    let banner = (0..shot.h.min(1200))
        .flat_map(|y| (0..shot.w).map(move |x| (x, y)))
        .filter(|&(x, y)| near(shot.at(x, y), [0xfd, 0xe7, 0xe7]))
        .count();
    assert!(banner > 5000, "no red verdict banner in the verify screenshot ({banner} pixels)");
    let zone = shot.rgb.iter().filter(|&&p| zone_over_material(p) || zone_over_air(p)).count();
    assert!(zone > 500, "no tolerance zone in the verify screenshot ({zone} pixels)");
    let fit = read_png(Path::new(seen["shots"]["fit"].as_str().unwrap()));
    let green = fit.rgb.iter().filter(|&&p| near(p, [0xe3, 0xf4, 0xe8])).count();
    assert!(green > 5000, "no green FITS banner in the fit screenshot ({green} pixels)");
}

/// Issue 31: the thread-milling picture is laid out (nothing written leaves it or crosses
/// another label) for a small and a large cutter, and says the distortion.
#[test]
fn thread_mill_svg_is_laid_out() {
    for (program, cutter) in [("m20-dc6.nc", "6"), ("m20-dc14.nc", "14")] {
        let dir = tempdir("tm-svg");
        let svg_path = dir.join("t.svg");
        let o = run_thread_mill(program, cutter, &["--svg", svg_path.to_str().unwrap()]);
        assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
        let svg = std::fs::read_to_string(&svg_path).unwrap();
        assert!(svg.contains("the helix widens the groove by"), "{program}");
        assert_laid_out(&svg, program);
    }
}

/// Issue 31: the tapping picture is laid out (nothing written leaves it or crosses another
/// label) for one hole drilled too small and for two holes of a Sinumerik program, named by a
/// long absolute path (regression: the path was written whole in the title and left the picture).
#[test]
fn tap_svg_is_laid_out() {
    for (program, tools) in [("m10-g84.nc", "tools-80.toml"), ("m10-cycle84.mpf", "tools-85.toml")] {
        let dir = tempdir("tap-svg");
        let svg_path = dir.join("t.svg");
        let deep = dir.join("a-folder-with-a-long-name-for-the-shop-programs/and-another-one-below-it");
        std::fs::create_dir_all(&deep).unwrap();
        let p = deep.join(program);
        std::fs::copy(data(&format!("programs/tapping/{program}")), &p).unwrap();
        let t = data(&format!("programs/tapping/{tools}"));
        let o = run_tap(&p, &t, &["--svg", svg_path.to_str().unwrap()]);
        assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
        let svg = std::fs::read_to_string(&svg_path).unwrap();
        assert!(svg.contains("drill Z-25"), "{program}");
        assert_laid_out(&svg, program);
    }
}

/// Issue 43: the thread-mill picture as verify's: scales on Z and the diameter (read back from
/// its tick labels), the class's tolerance zone over the milled section, and the measured
/// diameters labelled with ISO 965-2's limits. For M20x1.5-6H the zone is TD2 = 0.190 mm wide on
/// the diameter (D2 19.026–19.216), so at the basic pitch diameter each flank's band is
/// 0.095 · tan 30° = 0.054848 mm wide along Z (the flanks stand 30° from the radial); the
/// maximum-material side is the basic profile (EI = 0 for H). Chromium shows the band in green
/// on that row, and the widening plot has its own µm and Z scales.
#[test]
fn thread_mill_picture_has_zone_scales_and_limits() {
    let dir = tempdir("tm-zone");
    let svg_path = dir.join("t.svg");
    let o = run_thread_mill("m20-dc6.nc", "6", &["--svg", svg_path.to_str().unwrap()]);
    assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
    let svg = std::fs::read_to_string(&svg_path).unwrap();
    // The scales, from the section's tick labels: Z below, Ø at the right.
    let sc = Scales::of(&svg, "section");
    // True to scale: one mm of Z is one mm of radius (two of diameter).
    assert!(
        (sc.px_per_mm - 2.0 * sc.px_per_mm_d).abs() < 0.05 * sc.px_per_mm,
        "{} vs {}",
        sc.px_per_mm,
        sc.px_per_mm_d
    );
    let y = sc.y_of_d(19.026 + 0.001);
    assert_zone_bands(&svg, y, 0.095 * 30f64.to_radians().tan() * sc.px_per_mm);
    // The measured diameters with their limits; D2 out of them in red with its deviation.
    assert!(svg.contains("[19.026 – 19.216]") && svg.contains("[18.376 – 18.676]"), "limits");
    assert!(svg.contains("D2 18.7071 mm"), "D2's value");
    // The widening plot: µm and Z scales of its own.
    assert!(!tick_labels(&svg, "id=\"widening\"").is_empty() && svg.contains("µm, radial"));
    assert_laid_out(&svg, "thread-mill");
    assert_zone_painted_on_row(&svg_path, &svg, y);
}

/// The section's tolerance zone crosses the row at `y` in at least three bands, each `want_px`
/// wide along Z.
fn assert_zone_bands(svg: &str, y: f64, want_px: f64) {
    let bands = zone_bands(svg, "section-tolerance-zone", y);
    assert!(bands.len() >= 3, "{} bands at D2", bands.len());
    for band in bands {
        assert!((band - want_px).abs() < 0.35, "band {band:.2} px, want {want_px:.2}");
    }
}

/// Chromium paints the zone (green over the material or the air) at least six times along the
/// row at `y` of the picture `svg` at `path`.
fn assert_zone_painted_on_row(path: &Path, svg: &str, y: f64) {
    let (w, h) = svg_size(svg);
    let shot = screenshot(path, w, h);
    let row = y.round() as usize;
    let green: Vec<usize> = (0..shot.w)
        .filter(|&x| zone_over_material(shot.at(x, row)) || zone_over_air(shot.at(x, row)))
        .collect();
    let runs = green.windows(2).filter(|w| w[1] > w[0] + 1).count() + usize::from(!green.is_empty());
    assert!(runs >= 6, "the zone shows {runs} times on the D2 row");
}

/// Issue 46: the picture of a taper thread milled on its cone (`npt-half-internal.nc`, 1/2-14
/// NPT): the section sheared level along the cone (its title says so), the tolerance zone drawn
/// where the groove is measured, about the basic cone's pitch diameter there, E1 − 4P/16 =
/// 19.318551 mm, and as wide as the gauge's ±1 turn: P/16 = 0.113393 mm either side on the
/// diameter, so each flank's band is 0.113393 · tan 30° = 0.065467 mm wide along Z on any row
/// (it was drawn at the face's diameter, 0.45 mm off the groove). Chromium paints it green there.
#[test]
fn taper_thread_mill_picture_draws_its_zone_on_the_cone() {
    let dir = tempdir("tm-taper");
    let svg_path = dir.join("t.svg");
    let p = data("programs/threadmill/npt-half-internal.nc");
    let o = run(&[
        "thread-mill",
        "--program",
        p.to_str().unwrap(),
        "--cutter-diameter",
        "10",
        "--svg",
        svg_path.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let svg = std::fs::read_to_string(&svg_path).unwrap();
    assert!(svg.contains("milled section over four pitches, sheared along the cone"));
    let sc = Scales::of(&svg, "section");
    let y = sc.y_of_d(19.318551);
    assert_zone_bands(&svg, y, 25.4 / 14.0 / 16.0 * 30f64.to_radians().tan() * sc.px_per_mm);
    assert_laid_out(&svg, "taper thread-mill");
    assert_zone_painted_on_row(&svg_path, &svg, y);
}

/// A CAM post's thread-milling program (its cutter from its tool list): the picture's title names
/// the file, the thread and the cutter whole (82 characters were cut to 80 with an ellipsis,
/// seen in Chromium), inside the picture and clear of every other label.
#[test]
fn cam_thread_mill_picture_names_its_cutter_whole() {
    let dir = tempdir("tm-cam");
    let svg_path = dir.join("t.svg");
    let p = data("programs/threadmill/m12-cam-helical-lead-in.nc");
    let o = run(&["thread-mill", "--program", p.to_str().unwrap(), "--svg", svg_path.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let svg = std::fs::read_to_string(&svg_path).unwrap();
    let title = "m12-cam-helical-lead-in.nc: M12X1.75-6H thread-milled with a Ø8 single-form cutter";
    let (texts, _) = layout(&svg);
    assert!(texts.iter().any(|(t, _)| t == title), "{:?}", texts.iter().take(3).collect::<Vec<_>>());
    assert_laid_out(&svg, "CAM thread-mill");
}

/// Issue 45: the tap picture of radial holes (a live tool along X on a lathe,
/// `haas-radial-taps.nc`): each panel names its hole's Z and C, the heights along the hole's
/// axis are written as the program's X (the tap's bottom X24, the drill's X20; no Z label), and
/// the picture is laid out.
#[test]
fn tap_picture_of_radial_holes_writes_x() {
    let dir = tempdir("tap-radial");
    let svg_path = dir.join("r.svg");
    let p = data("machining/haas-radial-taps.nc");
    let o = run(&[
        "tap",
        "--program",
        p.to_str().unwrap(),
        "--dialect",
        "haas",
        "--svg",
        svg_path.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let svg = std::fs::read_to_string(&svg_path).unwrap();
    assert!(svg.contains("G195 line 12, T2 at Z-10 C0") && svg.contains("G195 line 13, T2 at Z-10 C90"));
    assert_eq!(svg.matches(">\ntap X24\n</text>").count(), 2);
    assert_eq!(svg.matches(">\ndrill X20\n</text>").count(), 2);
    assert!(!svg.contains(" Z-10\n</text>") && !svg.contains("tap Z"), "a Z label on a radial hole");
    assert_laid_out(&svg, "radial taps");
}

/// Issue 43: the tap picture dimensions the drill and D1 true to its scale bar: the Ø8 drill's
/// dimension is 8 mm long and red (it lies under D1 min 8.376, ISO 965-2), D1's limits are
/// 8.376 and 8.676 mm apart, and it names the drill that passes, ISO 2306's 8.5.
#[test]
fn tap_picture_dimensions_the_drill_and_d1() {
    let dir = tempdir("tap-dims");
    let svg_path = dir.join("t.svg");
    let o = run_tap(
        &data("programs/tapping/m10-g84.nc"),
        &data("programs/tapping/tools-80.toml"),
        &["--svg", svg_path.to_str().unwrap()],
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let svg = std::fs::read_to_string(&svg_path).unwrap();
    let n = |id: &str, k: &str| attr(tag_of(&svg, id), k).unwrap().parse::<f64>().unwrap();
    let s = (n("scale-bar", "x2") - n("scale-bar", "x1")) / n("scale-bar", "data-mm");
    let len = n("hole-0-drill-dimension", "x2") - n("hole-0-drill-dimension", "x1");
    assert!((len - 8.0 * s).abs() < 0.01, "the drill's dimension {len} px at {s} px/mm");
    for (which, d1) in [("min", 8.376), ("max", 8.676)] {
        let apart =
            n(&format!("hole-0-d1-{which}-right"), "x1") - n(&format!("hole-0-d1-{which}-left"), "x1");
        assert!((apart - d1 * s).abs() < 0.01, "D1 {which}: {apart} px");
    }
    assert_eq!(attr(tag_of(&svg, "hole-0-drill-dimension"), "stroke").as_deref(), Some("#c62828"));
    let passing = &svg[svg.find("id=\"hole-0-passing-drill\"").unwrap()..];
    assert!(passing[..passing.find("</text>").unwrap()].contains("a drill that passes: Ø8.5 mm"));
    assert!(svg.contains("D1 of M10x1.5-6H: 8.376 – 8.676 mm"));
    assert_laid_out(&svg, "tap");
    // Chromium draws the dimension in red.
    let (w, h) = svg_size(&svg);
    let shot = screenshot(&svg_path, w, h);
    let y = n("hole-0-drill-dimension", "y1").round() as usize;
    let xm = (0.5 * (n("hole-0-drill-dimension", "x1") + n("hole-0-drill-dimension", "x2"))) as usize;
    let red = (y - 1..=y + 1).flat_map(|y| (xm - 20..xm + 20).map(move |x| (x, y))).filter(|&(x, y)| {
        let [r, g, b] = shot.at(x, y);
        r > 150 && g < 110 && b < 110
    });
    assert!(red.count() >= 20, "the drill's dimension is not drawn red");
}

/// Issue 45/46: the tap picture of a Klartext program whose stock `BLK FORM` ends at Z−20 (the
/// holes are through holes): the stock is drawn down to its bottom face and no further (its
/// height is 20 mm at the scale bar's px/mm), labelled `stock Z-20`, or said in the tap's label
/// where the tap ends at the stock's bottom (the M12 holes: `tap = stock Z-20`, one label, not
/// two over each other); each panel names its hole's place (X100 Y70 after the datum shift and
/// the rotation). Chromium paints the stock's blue only above its bottom face.
#[test]
fn tap_picture_draws_the_stock_to_its_bottom_face() {
    let dir = tempdir("tap-stock");
    let svg_path = dir.join("plate.svg");
    let o = run(&[
        "tap",
        "--program",
        data("klartext/plate.h").to_str().unwrap(),
        "--svg",
        svg_path.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let svg = std::fs::read_to_string(&svg_path).unwrap();
    let n = |id: &str, k: &str| attr(tag_of(&svg, id), k).unwrap().parse::<f64>().unwrap();
    let s = (n("scale-bar", "x2") - n("scale-bar", "x1")) / n("scale-bar", "data-mm");
    for k in 0..4 {
        let h = n(&format!("hole-{k}-stock"), "height");
        assert!((h - 20.0 * s).abs() < 0.02, "hole {k}: the stock is {h} px, 20 mm is {} px", 20.0 * s);
    }
    assert_eq!(svg.matches(">\nstock Z-20\n</text>").count(), 2, "the M8 holes' stock labels");
    assert_eq!(svg.matches(">\ntap = stock Z-20\n</text>").count(), 2, "the M12 holes' one label each");
    assert!(svg.contains("CYCL 209 line 66, T4 at X100 Y70"));
    assert_laid_out(&svg, "tap");
    let (w, hgt) = svg_size(&svg);
    let shot = screenshot(&svg_path, w, hgt);
    let x = n("hole-0-stock", "x") as usize + 3;
    let bottom = (n("hole-0-stock", "y") + n("hole-0-stock", "height")).round() as usize;
    let blue = |y: usize| {
        let [r, g, b] = shot.at(x, y);
        b > 190 && r < 200 && g < 215 && b > r + 20
    };
    assert!(blue(bottom - 4), "the stock is painted above its bottom face");
    assert!(!blue(bottom + 6), "nothing is painted below the stock's bottom face");
}

/// Issue 46: `verify --html` of a program that taps four holes and mills a thread, as seen in
/// Chromium: both sections with their verdicts and pictures (four tap panels, the milled
/// thread's tolerance zone), no console error, nothing wider than the window (the tap's long
/// notes wrap instead of running off the side, as they did before this test).
#[test]
fn html_report_of_a_whole_program_shows_every_process() {
    let dir = tempdir("html-whole");
    let html = dir.join("plate.html");
    let tools = data("whole/plate-tools.toml");
    let o = run(&[
        "verify",
        "--program",
        data("whole/plate.nc").to_str().unwrap(),
        "--tools",
        tools.to_str().unwrap(),
        "--html",
        html.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = std::fs::read_to_string(&html).unwrap();
    assert!(text.contains("IN TOLERANCE: 4 tapped holes, 1 milled thread"), "{}", &text[..1500]);
    assert!(text.contains("<h2>Tapped: 4 tapping cycles — IN TOLERANCE</h2>"));
    assert!(text.contains("<h2>Milled: M20X1.5-6H — IN TOLERANCE</h2>"));
    assert_eq!(text.matches("<svg").count(), 2, "the tap picture and the thread-mill picture");
    assert_eq!(text.matches("<g id=\"hole-").count(), 4, "four tap panels");
    let shot = screenshot(&html, 1280, 3000);
    assert!(console_errors(&shot.log).is_empty(), "{:?}", console_errors(&shot.log));
    edges_stay_background(&shot, "HTML report");
    // The milled thread's tolerance zone is drawn (green over the material or the air).
    let zone = (0..shot.h)
        .flat_map(|y| (0..shot.w).map(move |x| (x, y)))
        .filter(|&(x, y)| zone_over_material(shot.at(x, y)) || zone_over_air(shot.at(x, y)))
        .count();
    assert!(zone > 500, "no tolerance zone seen ({zone} px)");
}

/// Issue 46: `verify --svg` of a program that makes threads of several processes draws every
/// one (it drew the turned threads alone, and a program that taps and mills drew its taps
/// alone): under the verdict's lines, each turned operation, then the tapped holes' picture and
/// the milled thread's, each under a band naming it. Chromium paints the part (blue-grey) in
/// the tapped holes' panels and the tolerance zone (green) in the milled section.
#[test]
fn program_svg_draws_every_process() {
    for (program, tools, turned, code) in [
        ("machining/fanuc-mixed.nc", "machining/fanuc-mixed.toml", true, 1),
        ("whole/plate.nc", "whole/plate-tools.toml", false, 0),
    ] {
        let dir = tempdir("svg-whole");
        let svg_path = dir.join("p.svg");
        let o = run(&[
            "verify",
            "--program",
            data(program).to_str().unwrap(),
            "--tools",
            data(tools).to_str().unwrap(),
            "--svg",
            svg_path.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(code), "{program}: {}", stderr(&o));
        let svg = std::fs::read_to_string(&svg_path).unwrap();
        assert_eq!(svg.contains("id=\"operation-1\""), turned, "{program}");
        assert!(svg.contains("tapped: 4 tapping cycles: IN TOLERANCE"), "{program}: the tapped line");
        assert!(svg.contains("milled: M20X1.5-6H: "), "{program}: the milled line");
        assert_eq!(svg.matches("<g id=\"hole-").count(), 4, "{program}: four tap panels");
        let n = |id: &str, k: &str| attr(tag_of(&svg, id), k).unwrap().parse::<f64>().unwrap();
        let tapped = (n("tapped", "y"), n("tapped", "y") + n("tapped", "height"));
        let milled = (n("milled", "y"), n("milled", "y") + n("milled", "height"));
        assert!(tapped.1 <= milled.0, "{program}: the pictures overlap");
        let (w, h) = svg_size(&svg);
        assert!((milled.1 - h as f64).abs() < 1.0, "{program}: the milled picture ends the SVG");
        let shot = screenshot(&svg_path, w, h);
        let count = |(y0, y1): (f64, f64), f: &dyn Fn([u8; 3]) -> bool| {
            (y0 as usize..(y1 as usize).min(shot.h))
                .flat_map(|y| (0..shot.w).map(move |x| (x, y)))
                .filter(|&(x, y)| f(shot.at(x, y)))
                .count()
        };
        let part = |[r, g, b]: [u8; 3]| b > 190 && r < 200 && g < 215 && b > r + 20;
        let zone = |p: [u8; 3]| zone_over_material(p) || zone_over_air(p);
        assert!(count(tapped, &part) > 5000, "{program}: no part painted in the tap panels");
        assert!(count(milled, &zone) > 500, "{program}: no tolerance zone in the milled section");
    }
}

/// `whole.mjs` on the page for `program` (its dialect chosen when given): what it saw.
fn page_whole(tag: &str, program: &std::path::Path, dialect: Option<&str>) -> serde_json::Value {
    let script = playwright().with_file_name("whole.mjs");
    let chromium = chromium();
    let server = crate::serve::start(&[]);
    let out = tempdir(tag);
    let mut node = std::process::Command::new("node");
    node.arg(&script).arg(&server.url).arg(&*out).arg(&chromium).arg(program);
    if let Some(d) = dialect {
        node.arg(d);
    }
    let o = node.output().unwrap();
    assert!(o.status.success(), "the page script failed: {}", String::from_utf8_lossy(&o.stderr));
    serde_json::from_slice(&o.stdout).unwrap()
}

/// Issue 46 on the page, in Chromium: a pasted program that turns M24x2 and taps M8, the thread
/// field left empty: each operation's block names its thread and the comment it came from, the
/// tapped hole its four checks, with no console message (the field was `required`, so the page
/// refused to send a program without a thread before this test).
#[test]
fn the_page_verifies_every_thread_a_pasted_program_names() {
    let seen = page_whole("page-whole", &data("whole/shaft.nc"), None);
    assert_eq!(seen["console"], serde_json::json!([]));
    assert_eq!(seen["verdict"], "IN TOLERANCE: every check passes");
    assert_eq!(
        seen["headings"],
        serde_json::json!([
            "Operation 1: G76 at line 8, M24X2-6g (named by the comment at line 4)",
            "Tapped: G84 at line 19, tap M8X1.25-6H (named by the comment at line 16)"
        ])
    );
    assert_eq!(seen["verdicts"], serde_json::json!(["IN TOLERANCE", "IN TOLERANCE"]));
    assert_eq!(seen["tap_checks"], serde_json::json!(["drill diameter", "feed", "depth", "spindle"]));
}

/// Issue 63 on the page, in Chromium, as a new user leaves its fields (the dialect chosen): a
/// LinuxCNC program whose G33.1 moves X as it taps is "will not run as written", the finding
/// listed under its tapped hole as an error with its line, and the picture's heading says the
/// same and lists it.
#[test]
fn the_page_says_what_the_control_will_refuse() {
    let seen = page_whole("page-control", &data("programs/control/sideways-tap.ngc"), Some("linuxcnc"));
    assert_eq!(seen["console"], serde_json::json!([]));
    assert!(
        seen["verdict"].as_str().unwrap().starts_with("WILL NOT RUN AS WRITTEN — 1 error before the machine"),
        "{}",
        seen["verdict"]
    );
    assert_eq!(seen["control"].as_array().unwrap().len(), 1, "{}", seen["control"]);
    assert_eq!(seen["control"][0]["level"], "error");
    let text = seen["control"][0]["text"].as_str().unwrap();
    assert!(text.starts_with("✗ Before the machine, line 6 (G33.1): the tap moves X from 0 to 5"), "{text}");
    assert!(text.ends_with("[post.tap_moves_sideways]"), "{text}");
    let picture: Vec<&str> =
        seen["picture_control"].as_array().unwrap().iter().filter_map(|t| t.as_str()).collect();
    assert!(
        picture.first().is_some_and(|t| t.starts_with("✗ before the machine, line 6 (G33.1)")),
        "{picture:?}"
    );
    assert!(
        seen["picture_verdict"].as_str().unwrap().contains("WILL NOT RUN AS WRITTEN"),
        "{}",
        seen["picture_verdict"]
    );
}

/// Issue 64 on the page, in Chromium, as a new user leaves its fields: a pasted program whose
/// comment names a form tap (`(FORM TAP M10X1.5)`) over a Ø9.3 drill. The drill check's limits
/// are the tap makers' hole for 60–75 % of thread, D − 0.0068·P·% = 9.235–9.388 mm (not 6H's D1
/// 8.376–8.676, which Ø9.3 would fail), and the picture shows the D1 the tap forms beside the cut
/// threads' limits.
#[test]
fn the_page_checks_a_form_tap_against_the_hole_it_needs() {
    let seen = page_whole("page-form-tap", &data("programs/tapping/form-tap-m10.nc"), None);
    assert_eq!(seen["console"], serde_json::json!([]));
    assert_eq!(seen["verdict"], "IN TOLERANCE: every check passes");
    let rows = seen["check_rows"].as_array().unwrap();
    let drill = rows.iter().find(|r| r[0] == "drill diameter").unwrap_or_else(|| panic!("{rows:?}"));
    assert_eq!(
        (drill[2].as_str(), drill[3].as_str(), drill[4].as_str()),
        (Some("9.3000"), Some("9.2350"), Some("9.3880")),
        "{drill:?}"
    );
    assert!(
        drill.as_array().unwrap().last().unwrap().as_str().unwrap().starts_with("a form tap's hole"),
        "{drill:?}"
    );
    let picture: Vec<&str> =
        seen["picture_text"].as_array().unwrap().iter().filter_map(|t| t.as_str()).collect();
    assert!(
        picture
            .iter()
            .any(|t| t.starts_with("D1 formed 8.94") && t.contains("(cut threads'): 8.376 – 8.676 mm")),
        "{picture:?}"
    );
    assert!(picture.contains(&"the drill for the form tap's hole: Ø9.3 mm"), "{picture:?}");
}

/// Issue 65 item 2 on the page, in Chromium: a pasted LinuxCNC program in a `.nc` file whose
/// modeline says `dialect=linuxcnc`, the dialect list left at "by the modeline or the file name":
/// read as LinuxCNC (as Fanuc its G76's J is refused), in tolerance (the program
/// `settings::LINUXCNC_AS_NC` derives), and the notes say the modeline chose it.
#[test]
fn the_page_reads_a_pasted_program_s_modeline() {
    let seen = page_whole("page-modeline", &data("programs/settings/linuxcnc-modeline.nc"), None);
    assert_eq!(seen["console"], serde_json::json!([]));
    assert_eq!(seen["verdict"], "IN TOLERANCE: every check passes", "{seen}");
    assert_eq!(
        seen["headings"][0],
        "Operation 1: G76 at line 9, M10X1.5-6g (named by the comment at line 3)"
    );
    let notes: Vec<&str> = seen["notes"].as_array().unwrap().iter().filter_map(|n| n.as_str()).collect();
    assert!(notes.contains(&"read with the program's modeline (line 2): dialect linuxcnc"), "{notes:?}");
}

/// Issue 45 on the page, in Chromium: the dialect list offers every dialect (Klartext among
/// them), and a pasted Klartext plate read as Klartext gives its six tapped holes, each named by
/// its comment and placed (X120 Y50: the pattern's 270° point turned by 90° and shifted), the
/// M12 ones left-hand, with no console message.
#[test]
fn the_page_reads_a_klartext_program() {
    let seen = page_whole("page-klartext", &data("klartext/plate.h"), Some("klartext"));
    assert_eq!(seen["console"], serde_json::json!([]));
    let offered: Vec<&str> = seen["dialects"].as_array().unwrap().iter().filter_map(|d| d.as_str()).collect();
    for d in threadcheck::Dialect::ALL {
        assert!(offered.contains(&d.name()), "{} is not offered: {offered:?}", d.name());
    }
    assert_eq!(seen["verdict"], "IN TOLERANCE: every check passes");
    let headings: Vec<&str> =
        seen["headings"].as_array().unwrap().iter().filter_map(|h| h.as_str()).collect();
    assert_eq!(headings.len(), 6, "{headings:?}");
    // Each hole's place: the four of the pattern cycle share its line.
    assert!(headings[0].starts_with("Tapped: CYCL 207 at line 26 (X20 Y20), tap M8X1.25-6H"), "{headings:?}");
    assert!(
        headings[5].starts_with("Tapped: CYCL 209 at line 66 (X120 Y50), tap M12X1.75-LH-6H"),
        "{headings:?}"
    );
}

/// Every text of a picture as Chromium reads it (`tests/page/texts.mjs`).
fn picture_texts(svg: &Path) -> Vec<String> {
    picture_texts_in(svg, None)
}

/// The texts of a picture inside the elements `selector` names (every text without one).
fn picture_texts_in(svg: &Path, selector: Option<&str>) -> Vec<String> {
    let script = playwright().with_file_name("texts.mjs");
    let mut cmd = std::process::Command::new("node");
    cmd.arg(&script).arg(chromium()).arg(svg);
    cmd.args(selector);
    let o = cmd.output().unwrap();
    assert!(o.status.success(), "texts.mjs failed: {}", String::from_utf8_lossy(&o.stderr));
    serde_json::from_slice(&o.stdout).unwrap()
}

/// Issue 63: the picture shows each control finding under the operation it concerns (and all
/// of them in the program's head). Our shaft with two threads, the second started 0.83 mm before
/// the face at S2500: its Z axis needs δ1 = t1·V·(−1 − ln 0.01) = 0.033 s × 62.5 mm/s × 3.6052
/// = 7.44 mm (Fanuc's run-in, t1 the named default), so the run-in warning stands under the
/// second operation's band alone; our LinuxCNC G33.1 that moves X as it feeds has its error
/// under the tapped band. Read in Chromium.
#[test]
fn each_control_finding_stands_under_its_operation() {
    let dir = tempdir("control-in-picture");
    let svg = dir.join("two.svg");
    let prog = data("programs/control/two-threads-one-short.nc");
    let o = run(&["verify", "--program", prog.to_str().unwrap(), "--svg", svg.to_str().unwrap()]);
    assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
    let first = picture_texts_in(&svg, Some("#operation-1-control"));
    assert!(first.is_empty(), "{first:?}");
    let second = picture_texts_in(&svg, Some("#operation-2-control")).join(" ");
    assert!(second.starts_with("! before the machine, line 15 (G76): the first pass starts"), "{second}");
    assert!(second.contains("the Z axis needs 7.44 mm"), "{second}");
    let head = picture_texts_in(&svg, Some("#control")).join(" ");
    assert!(head.contains("line 15 (G76)"), "{head}");
    // The page (--html): the warning under operation 2's heading, before operation 1's none.
    let html = dir.join("two.html");
    let o = run(&["verify", "--program", prog.to_str().unwrap(), "--html", html.to_str().unwrap()]);
    assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
    let page = std::fs::read_to_string(&html).unwrap();
    let at = |s: &str| page.find(s).unwrap_or_else(|| panic!("no {s} in the page"));
    // Once under the headline (every finding, as the picture gives them), once under
    // operation 2's heading.
    let warning = "! before the machine, line 15 (G76)";
    let (head, under) = (at(warning), page.rfind(warning).unwrap());
    assert!(head < at("Operation 1 of 2") && under > at("Operation 2 of 2"));
    assert_eq!(page.matches("before the machine, line").count(), 2);
    let svg = dir.join("tap.svg");
    let prog = data("programs/control/sideways-tap.ngc");
    let o = run(&["verify", "--program", prog.to_str().unwrap(), "--svg", svg.to_str().unwrap()]);
    assert!(o.status.code().is_some_and(|c| c < 3), "{}", stderr(&o));
    let tapped = picture_texts_in(&svg, Some("#tapped-control")).join(" ");
    assert!(
        tapped.starts_with("✗ before the machine, line 6 (G33.1): the tap moves X from 0 to 5"),
        "{tapped}"
    );
}

/// Issue 63: a post that wrote a tap's operation as a peck drilling cycle. Our program's CAM
/// tool list names T6 an M8x1.25 tap, and T6 runs in G83: the program has no other thread, and
/// the picture and the page say the program will not run as written, with the finding under
/// the headline, as Chromium shows them.
#[test]
fn a_tap_in_a_drilling_cycle_heads_the_picture_and_the_page() {
    let dir = tempdir("tap-in-g83");
    let prog = data("programs/control/tap-in-peck-cycle.nc");
    let (svg, html) = (dir.join("p.svg"), dir.join("p.html"));
    let o = run(&[
        "verify",
        "--program",
        prog.to_str().unwrap(),
        "--svg",
        svg.to_str().unwrap(),
        "--html",
        html.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let finding = "✗ before the machine, line 17 (G83): T6 is a tap in the program's tool list at line 5, and G83 retracts at rapid";
    let head = picture_texts_in(&svg, None);
    assert!(head[0].contains("WILL NOT RUN AS WRITTEN"), "{head:?}");
    assert!(picture_texts_in(&svg, Some("#control")).join(" ").starts_with(finding), "{head:?}");
    let page = picture_texts_in(&html, None);
    let verdict = page.iter().position(|t| t.starts_with("WILL NOT RUN AS WRITTEN")).expect("the verdict");
    let said = page.iter().position(|t| t.starts_with(finding)).unwrap_or_else(|| panic!("{page:?}"));
    assert!(verdict < said, "{page:?}");
}

/// What a text says in mm or µm outside the parentheses that follow an inch figure (`0.4500 in
/// (11.4303 mm)`, `0.0015 in (38.4 µm)`, `+37.5 tenths (+95.3 µm)`): empty when the text is in
/// inches throughout. The chip chart's mm² is its own unit (insert makers give chip areas so).
fn metric_outside_inches(text: &str) -> Option<String> {
    let mut rest = String::new();
    let mut depth = 0;
    for c in text.chars() {
        match c {
            '(' => depth += 1,
            ')' => depth -= 1,
            c if depth == 0 => rest.push(c),
            _ => {}
        }
    }
    let rest = rest.replace("mm²", "");
    (rest.contains(" mm") || rest.contains("µm") || rest.ends_with("mm")).then_some(rest)
}

/// Issue 65: an inch report's picture is in inches in every text, checked in Chromium: our
/// Haas program cutting 1/2-13 UNC-2A (its title, verdict, labels, check table, axes, deviation
/// plot) and our inch tapping program (its places, depths, drill, feed, D1 and scale bar). The mm
/// and µm stand only beside an inch figure, in parentheses.
#[test]
fn an_inch_picture_is_in_inches_in_every_text() {
    let dir = tempdir("inch-texts");
    let turned = dir.join("turned.svg");
    let prog = data("programs/haas-g76-1-2-13-unc.nc");
    let o = run(&["verify", "--program", prog.to_str().unwrap(), "--svg", turned.to_str().unwrap()]);
    assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
    let texts = picture_texts(&turned);
    assert!(texts.iter().any(|t| t.contains("checks, lengths in inches")), "{texts:?}");
    assert!(texts.iter().any(|t| t.contains("pitch diameter d2 0.0015 in (38.4 µm) over")), "{texts:?}");
    assert!(texts.iter().any(|t| t == "0.4436 – 0.4485"), "{texts:?}");
    let metric: Vec<String> = texts.iter().filter_map(|t| metric_outside_inches(t)).collect();
    assert!(metric.is_empty(), "texts in mm in the inch picture: {metric:?}");
    let tapped = dir.join("tapped.svg");
    let prog = data("programs/tapping/quarter-20-inch.nc");
    let o = run(&["tap", "--program", prog.to_str().unwrap(), "--svg", tapped.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let texts = picture_texts(&tapped);
    assert!(texts.iter().any(|t| t.contains("G84 line 16, T4 at X1 Y1")), "{texts:?}");
    assert!(texts.iter().any(|t| t.ends_with(" in") && t.starts_with("0.")), "no inch scale bar: {texts:?}");
    let metric: Vec<String> = texts.iter().filter_map(|t| metric_outside_inches(t)).collect();
    assert!(metric.is_empty(), "texts in mm in the inch tapping picture: {metric:?}");
}

/// The page's notes name its own fields, never the API's keys: our Haas program pasted as it is
/// is read as a lathe by its G18 (the page has no machine-type field: a modeline chooses
/// otherwise) in Fanuc's G-code system A (the command line's flag chooses B or C); an inch
/// thread's next step and table are in inches. Looked at in Chromium.
#[test]
fn the_page_s_notes_name_its_own_fields() {
    let seen = page_whole("page-notes", &data("programs/haas-g76-1-2-13-unc.nc"), None);
    assert_eq!(seen["console"], serde_json::json!([]));
    let notes: Vec<&str> = seen["notes"].as_array().unwrap().iter().filter_map(|n| n.as_str()).collect();
    let lathe = notes.iter().find(|n| n.starts_with("read as a lathe")).unwrap();
    assert!(lathe.contains("(threadcheck: machine-type=…)"), "{lathe}");
    let system = notes.iter().find(|n| n.contains("G-code system")).unwrap();
    assert!(system.contains("needs the command line's --gcode-system b or c"), "{system}");
    for n in &notes {
        assert!(!n.contains("machine_type") && !n.contains("gcode_system") && !n.contains('‹'), "{n}");
    }
}

/// Issue 64 on the page: an inch program's tapped holes in its inches on the Tap tab, each value
/// with its unit: our 1/4-20 program's #7 drill 0.2010 in against 2B's D1 0.1960–0.2070 in (ASME
/// B1.1), its feed 25.0 in/min (500 × 0.05 in) and the second hole's 24.0 in/min out.
#[test]
fn the_tap_tab_gives_an_inch_program_in_inches() {
    let script = playwright().with_file_name("taptab.mjs");
    let server = crate::serve::start(&[]);
    let program = data("programs/tapping/quarter-20-inch.nc");
    let o = std::process::Command::new("node")
        .arg(&script)
        .arg(&server.url)
        .arg(chromium())
        .arg(&program)
        .output()
        .unwrap();
    assert!(o.status.success(), "taptab.mjs failed: {}", String::from_utf8_lossy(&o.stderr));
    let seen: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(seen["console"], serde_json::json!([]));
    let rows = seen["rows"].as_array().unwrap();
    let cells = |line: &str, check: &str| -> Vec<String> {
        let r = rows.iter().find(|r| r[0] == line && r[2] == check).unwrap();
        r.as_array().unwrap().iter().map(|c| c.as_str().unwrap().to_string()).collect()
    };
    assert_eq!(cells("G84 line 16", "drill diameter")[3..7], ["0.2010 in", "0.1960", "0.2070", "ok"]);
    assert_eq!(cells("G84 line 16", "feed")[3..7], ["25.0 in/min", "25.0", "25.0", "ok"]);
    assert_eq!(cells("G84 line 17", "feed")[3..7], ["24.0 in/min", "25.0", "25.0", "OUT"]);
}
