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

#[test]
fn docs_commands_run() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let scratch = tempdir("docs-commands");
    for shared in ["tests", "profiles"] {
        std::os::unix::fs::symlink(root.join(shared), scratch.join(shared)).unwrap();
    }
    std::fs::create_dir(scratch.join("reports")).unwrap();
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
