//! The house rule, held by a test: the wings along the data path import only the wings above
//! them (ground, standards, gcode, geometry, analysis, report, jobs, request, serve), so nothing below `report/`
//! reaches presentation, and `src/` keeps at most eight top-level files besides `lib.rs` and
//! `main.rs`.

use std::path::{Path, PathBuf};

const WINGS: [&str; 9] =
    ["ground", "standards", "gcode", "geometry", "analysis", "report", "jobs", "request", "serve"];

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The code of a file without comments and without its unit-test modules (`#[cfg(test)]` and
/// the braced item after it).
fn code(text: &str) -> String {
    let text: String =
        text.lines().map(|l| l.split("//").next().unwrap_or("")).collect::<Vec<_>>().join("\n");
    let mut out = String::new();
    let mut rest = text.as_str();
    while let Some(i) = rest.find("#[cfg(test)]") {
        out.push_str(&rest[..i]);
        rest = &rest[i..];
        let Some(open) = rest.find('{') else { break };
        let mut depth = 0;
        let mut end = rest.len();
        for (k, c) in rest[open..].char_indices() {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        end = open + k + 1;
                        break;
                    }
                }
                _ => {}
            }
        }
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
}

#[test]
fn imports_point_down_the_data_path() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut wrong = Vec::new();
    for f in &files {
        let rel = f.strip_prefix(&src).unwrap();
        let first = rel.components().next().unwrap().as_os_str().to_string_lossy().into_owned();
        let wing = first.trim_end_matches(".rs");
        let Some(rank) = WINGS.iter().position(|w| *w == wing) else { continue };
        let text = code(&std::fs::read_to_string(f).unwrap());
        for (i, _) in text.match_indices("crate::") {
            let rest = &text[i + 7..];
            let name: String = rest.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_').collect();
            if let Some(r) = WINGS.iter().position(|w| *w == name) {
                if r > rank {
                    wrong.push(format!("{} imports crate::{name}", rel.display()));
                }
            }
        }
    }
    assert!(wrong.is_empty(), "imports that point up the data path:\n{}", wrong.join("\n"));
}

#[test]
fn src_has_few_top_level_files() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let top: Vec<String> = std::fs::read_dir(&src)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_file())
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .filter(|n| n != "lib.rs" && n != "main.rs")
        .collect();
    assert!(top.len() <= 8, "{top:?}");
}

/// Each backend behind one door: `geo` only in `geometry/boolean.rs`, `parry2d-f64` only in
/// `geometry/parry.rs`, `rstar` only in `geometry/index.rs`, the HTTP stack (`axum`, `tokio`)
/// only in `serve/mod.rs`.
#[test]
fn each_backend_has_one_door() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut wrong = Vec::new();
    for f in &files {
        let rel = f.strip_prefix(&src).unwrap().to_string_lossy().replace('\\', "/");
        let text = code(&std::fs::read_to_string(f).unwrap());
        for (krate, door) in [
            ("geo::", "geometry/boolean.rs"),
            ("parry2d_f64::", "geometry/parry.rs"),
            ("rstar::", "geometry/index.rs"),
            ("axum::", "serve/mod.rs"),
            ("tokio::", "serve/mod.rs"),
        ] {
            let uses = text.match_indices(krate).any(|(i, _)| {
                !text[..i].ends_with(|c: char| c.is_ascii_alphanumeric() || c == '_' || c == ':')
            });
            if uses && rel != door {
                wrong.push(format!("{rel} uses {krate}"));
            }
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}
