//! Issue 44: every command the README and the docs show in a code block runs as written from the
//! repository's root, and ends as documented (0, or 1 where the example fails on purpose): the
//! front page's first command and each guide's. The commands run in a scratch folder that sees
//! the repository's `tests/` and `profiles/` and has a `reports/` of its own, so the committed
//! pictures are never overwritten. `serve` (it runs until stopped) is left out (the page's
//! tests drive it), and so is a synopsis (`[options]`, `<PLACEHOLDER>`).

use crate::*;
use std::path::{Path, PathBuf};

/// A command line split as a shell would (single and double quotes, backslash-newline joined),
/// up to a `#` comment.
fn words(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cur = String::new();
    let mut quote: Option<char> = None;
    let mut any = false;
    for c in line.chars() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), c) => cur.push(c),
            (None, '\'' | '"') => {
                quote = Some(c);
                any = true;
            }
            (None, c) if c.is_whitespace() => {
                if any || !cur.is_empty() {
                    out.push(std::mem::take(&mut cur));
                    any = false;
                }
            }
            (None, '#') if cur.is_empty() && !any => break,
            (None, c) => cur.push(c),
        }
    }
    if any || !cur.is_empty() {
        out.push(cur);
    }
    out
}

/// Every `threadcheck …` (or `$ threadcheck …`, `cargo run --release -- …`) line of the fenced
/// code blocks of `text`, as the arguments after the program's name.
fn commands(text: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let mut fence = false;
    let mut held = String::new();
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fence = !fence;
            continue;
        }
        if !fence {
            continue;
        }
        let line = format!("{held}{line}");
        if let Some(head) = line.strip_suffix('\\') {
            held = format!("{head} ");
            continue;
        }
        held.clear();
        let l = line.trim().trim_start_matches("$ ");
        let rest = l
            .strip_prefix("threadcheck ")
            .or_else(|| l.strip_prefix("cargo run --release -- "))
            .or_else(|| l.strip_prefix("target/release/threadcheck "));
        // A synopsis (`[options]`, `<PLACEHOLDER>`, `(a | b)`) is not a command to run.
        if let Some(rest) = rest.filter(|r| !r.contains(" [") && !r.contains('<') && !r.contains(" (")) {
            out.push(words(rest));
        }
    }
    out
}

fn docs() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = vec![root.join("README.md")];
    for dir in ["docs", "docs/guide"] {
        let mut md: Vec<PathBuf> = std::fs::read_dir(root.join(dir))
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|x| x == "md"))
            .collect();
        md.sort();
        files.extend(md);
    }
    files
}

#[test]
fn the_shell_words_are_split_as_a_shell_does() {
    assert_eq!(
        words(r#"verify --thread "1/2-13 UNC-2A" --svg x.svg   # a comment"#),
        ["verify", "--thread", "1/2-13 UNC-2A", "--svg", "x.svg"]
    );
    assert_eq!(
        commands("```sh\nthreadcheck tap \\\n  --program p.nc\n```\nthreadcheck no\n"),
        [["tap", "--program", "p.nc"]]
    );
}

/// The folder the docs' commands run in: the repository's `tests/` and `profiles/` seen through
/// links, and a `reports/` of its own.
fn docs_scratch(tag: &str) -> crate::util::Scratch {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let scratch = tempdir(tag);
    for shared in ["tests", "profiles"] {
        std::os::unix::fs::symlink(root.join(shared), scratch.join(shared)).unwrap();
    }
    std::fs::create_dir(scratch.join("reports")).unwrap();
    scratch
}

#[test]
fn docs_commands_run() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let scratch = docs_scratch("docs-commands");
    let mut ran = Vec::new();
    for file in docs() {
        let text = std::fs::read_to_string(&file).unwrap();
        for args in commands(&text) {
            if args.first().map(String::as_str) == Some("serve") {
                continue;
            }
            let a: Vec<&str> = args.iter().map(String::as_str).collect();
            let o = run_in(&scratch, &a);
            let name = file.strip_prefix(root).unwrap().display().to_string();
            assert!(
                matches!(o.status.code(), Some(0 | 1)),
                "{name}: threadcheck {}: exit {:?}: {}",
                args.join(" "),
                o.status.code(),
                stderr(&o)
            );
            ran.push(format!("{name}: {}", args.join(" ")));
        }
    }
    // The front page's first command and every guide's main command, at least.
    for must in [
        "README.md: verify",
        "verify-a-lathe-program.md: verify",
        "check-a-whole-program.md: verify",
        "tap-and-thread-mill.md: tap",
        "tap-and-thread-mill.md: thread-mill",
        "correct-after-measuring.md: correct",
        "capability.md: capability",
        "capability.md: fit",
    ] {
        assert!(ran.iter().any(|r| r.contains(must)), "no command '{must}' ran: {ran:#?}");
    }
}

/// Issue 65 item 4: the extensions a folder's programs are found by are one list: the walker's
/// constant, the help of `verify PROGRAM|FOLDER`, the guide and the error of a folder without
/// programs all name it, with Klartext's `.h`.
#[test]
fn the_program_extensions_are_one_list() {
    let list = threadcheck::PROGRAM_EXTENSIONS.map(|e| format!(".{e}")).join(" ");
    let help = stdout(&run(&["verify", "--help"])).split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(help.contains(&format!("{list}, and .h files that open a Klartext program")), "{help}");
    let guide = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/guide/check-a-whole-program.md"),
    )
    .unwrap()
    .split_whitespace()
    .collect::<Vec<_>>()
    .join(" ");
    assert!(guide.contains(&format!("`{list}`, and `.h` files that open a Klartext program")), "{list}");
    let dir = tempdir("extensions");
    std::fs::create_dir(dir.join("empty")).unwrap();
    let e = one_line_error(&run_in(&dir, &["verify", "empty"]));
    assert!(
        e.contains(&format!("(looked for the extensions {list}, and .h files that open a Klartext program)")),
        "{e}"
    );
}

/// The transcripts in the docs: a fenced block whose first line is `$ threadcheck …`, each such
/// line in it with the lines it shows printed after it (up to the next `$` line).
fn transcripts(text: &str) -> Vec<(Vec<String>, Vec<String>)> {
    let mut out = Vec::new();
    let mut block: Option<Vec<String>> = None;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            match block.take() {
                // Each `$ threadcheck` line of a block opens a transcript of its own.
                Some(lines) if lines.first().is_some_and(|l| l.starts_with("$ threadcheck ")) => {
                    for (i, l) in lines.iter().enumerate() {
                        if let Some(cmd) = l.strip_prefix("$ threadcheck ") {
                            let shown =
                                lines[i + 1..].iter().take_while(|l| !l.starts_with("$ ")).cloned().collect();
                            out.push((words(cmd), shown));
                        }
                    }
                }
                Some(_) => {}
                None => block = Some(Vec::new()),
            }
            continue;
        }
        if let Some(b) = &mut block {
            b.push(line.to_string());
        }
    }
    out
}

/// Issue 65 item 4: every transcript in the README and the docs prints what it shows: the lines
/// shown are lines the command prints, one after another (a line `…` or `...` stands for any
/// number of lines left out, and so do the lines before the first shown and after the last; a
/// line ending ` …` for the printed line it begins). A change that moves a number moves the
/// doc with it.
#[test]
fn docs_transcripts_print_what_they_show() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let scratch = docs_scratch("docs-transcripts");
    let mut stale = Vec::new();
    let mut seen = 0;
    for file in docs() {
        let name = file.strip_prefix(root).unwrap().display().to_string();
        for (args, shown) in transcripts(&std::fs::read_to_string(&file).unwrap()) {
            seen += 1;
            let a: Vec<&str> = args.iter().map(String::as_str).collect();
            let printed = stdout(&run_in(&scratch, &a));
            let printed: Vec<&str> = printed.lines().collect();
            // The first line shown may be any printed line; the ones after it follow it.
            let mut at = 0;
            let mut skipping = true;
            for want in &shown {
                if matches!(want.trim(), "…" | "...") {
                    skipping = true;
                    continue;
                }
                // A line cut short by the doc (`d2 …`) stands for the lines it begins.
                let same = |p: &&str| match want.strip_suffix(" …") {
                    Some(head) => p.starts_with(head),
                    None => *p == want,
                };
                let found = if skipping {
                    printed[at..].iter().position(&same).map(|k| at + k)
                } else {
                    printed.get(at).filter(|p| same(p)).map(|_| at)
                };
                match found {
                    Some(k) => at = k + 1,
                    None => {
                        stale.push(format!(
                            "{name}: threadcheck {}:\n  shown:   {want}\n  printed: {}",
                            args.join(" "),
                            printed.get(at).unwrap_or(&"(nothing)")
                        ));
                        break;
                    }
                }
                skipping = false;
            }
        }
    }
    assert!(seen >= 8, "the docs show {seen} transcripts");
    assert!(stale.is_empty(), "transcripts that no longer print what they show:\n{}", stale.join("\n"));
}

/// Issue 60's "the committed reports regenerate byte for byte": every picture and page the
/// README and the guides show from `reports/` is what the command they give draws today (the
/// infeed comparison is held by its own test). A change to a picture regenerates them.
#[test]
fn the_committed_pictures_are_what_their_commands_draw() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = crate::tempdir("pictures");
    let out = |name: &str| dir.join(name).to_str().unwrap().to_string();
    // (the command, the flag that writes the document, the committed file).
    let pictures: [(&[&str], &str, &str); 10] = [
        (&["verify", "--thread", "M10x1.5-6g"], "--svg", "m10x1.5-6g-partial.svg"),
        (&["verify", "--thread", "M10x1.5-6g"], "--html", "m10x1.5-6g-partial.html"),
        (&["verify", "--thread", "M10x1.5-6g", "--insert", "full"], "--svg", "m10x1.5-6g-full.svg"),
        (&["verify", "--thread", "1/2-13 UNC-2A", "--final-x", "10.2"], "--svg", "unc-1_2-13-2a-inch.svg"),
        (
            &[
                "verify",
                "--thread",
                "M20x1.5-6g",
                "--program",
                "tests/data/programs/fanuc-g76-timing.nc",
                "--insert",
                "full",
            ],
            "--svg",
            "m20x1.5-g76-program.svg",
        ),
        (
            &[
                "capability",
                "--thread",
                "M10x1.5-6g",
                "--x-sigma",
                "0.008",
                "--tip-radius-tol",
                "0.01",
                "--wear-per-part",
                "0.0005",
                "--gauge-only",
            ],
            "--svg",
            "capability-m10x1.5-6g.svg",
        ),
        (
            &["fit", "--thread", "M10x1.5-6H/6g", "--bolt-insert", "full", "--nut-insert", "full"],
            "--svg",
            "fit-m10x1.5-6H-6g.svg",
        ),
        (
            &[
                "tap",
                "--program",
                "tests/data/programs/tapping/m10-g84.nc",
                "--tools",
                "tests/data/programs/tapping/tools-80.toml",
            ],
            "--svg",
            "tap-m10-drill80.svg",
        ),
        (
            &[
                "thread-mill",
                "--program",
                "tests/data/programs/threadmill/m20-dc14.nc",
                "--thread",
                "M20x1.5-6H",
                "--cutter-diameter",
                "14",
            ],
            "--svg",
            "thread-mill-m20-dc14.svg",
        ),
        (
            &[
                "mill",
                "--program",
                "tests/data/programs/milling/seed002-cardioid-cam.nc",
                "--dialect",
                "dyna",
                "--n-order",
                "--tool-diameter",
                "6",
                "--target",
                "tests/data/targets/cardioid.toml",
            ],
            "--svg",
            "mill-cardioid-cam.svg",
        ),
    ];
    let mut stale = Vec::new();
    for (args, flag, name) in pictures {
        let path = out(name);
        let mut all = args.to_vec();
        all.extend([flag, path.as_str()]);
        let o = crate::run_in(root, &all);
        let fresh =
            std::fs::read(&path).unwrap_or_else(|_| panic!("{all:?} wrote no {name}: {}", crate::stderr(&o)));
        let committed = std::fs::read(root.join("reports").join(name)).unwrap_or_default();
        if fresh != committed {
            let words: Vec<String> = args
                .iter()
                .map(|a| if a.contains(' ') { format!("\"{a}\"") } else { a.to_string() })
                .collect();
            stale.push(format!("threadcheck {} {flag} reports/{name}", words.join(" ")));
        }
    }
    // The worked example's text is the command's standard output.
    let o = crate::run_in(root, &["verify", "--thread", "M10x1.5-6g"]);
    if o.stdout != std::fs::read(root.join("reports/m10x1.5-6g-partial.txt")).unwrap_or_default() {
        stale.push("threadcheck verify --thread M10x1.5-6g > reports/m10x1.5-6g-partial.txt".into());
    }
    assert!(
        stale.is_empty(),
        "committed pictures no longer what their commands draw; regenerate:\n{}",
        stale.join("\n")
    );
}
