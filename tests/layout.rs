//! The house rule, held by a test: the wings along the data path import only the wings above
//! them (ground, standards, toolpath, gcode, geometry, analysis, report, commands, serve and lsp),
//! so nothing below `report/` reaches presentation; `geometry/` never imports `gcode/` (the cut
//! knows passes, not programs); an import is seen whether it names the wing's path or a name
//! `lib.rs` re-exports from it, in a module's code and in its unit tests alike; and `src/` keeps
//! at most eight top-level files besides `lib.rs` and `main.rs`.

use std::path::{Path, PathBuf};

const WINGS: [&str; 10] = [
    "ground",
    "standards",
    "toolpath",
    "gcode",
    "geometry",
    "analysis",
    "report",
    "commands",
    "serve",
    "lsp",
];

/// Pairs (importer, imported) forbidden though the imported wing lies above: the cut needs
/// passes, never a program.
const APART: [(&str, &str); 1] = [("geometry", "gcode")];

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

/// Every file of `src/`: its path below `src/` (with `/`) and its code (see [`code`]).
fn src_code() -> Vec<(String, String)> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files
        .iter()
        .map(|f| {
            let rel = f.strip_prefix(&src).unwrap().to_string_lossy().replace('\\', "/");
            (rel, code(&std::fs::read_to_string(f).unwrap()))
        })
        .collect()
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

/// The code of a file without comments (its unit tests kept).
fn code_and_tests(text: &str) -> String {
    text.lines().map(|l| l.split("//").next().unwrap_or("")).collect::<Vec<_>>().join("\n")
}

/// The names `lib.rs` re-exports at the crate's root, each with the wing it comes from:
/// `pub use standards::drills::{drill_that_passes, …}` gives `drill_that_passes` → `standards`.
fn reexports(lib: &str) -> Vec<(String, String)> {
    let lib = code_and_tests(lib);
    let mut out = Vec::new();
    for stmt in lib.split(';') {
        let Some(i) = stmt.find("pub use ") else { continue };
        let path = stmt[i + 8..].trim();
        let wing: String = path.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_').collect();
        if !WINGS.contains(&wing.as_str()) {
            continue;
        }
        let names = match (path.find('{'), path.rfind('}')) {
            (Some(a), Some(b)) => path[a + 1..b].to_string(),
            _ => path.rsplit("::").next().unwrap_or("").to_string(),
        };
        for n in names.split(',') {
            // `check as check_cancelled`: the name the crate's root has.
            let n = n.split(" as ").last().unwrap_or("").trim();
            if !n.is_empty() {
                out.push((n.to_string(), wing.clone()));
            }
        }
    }
    out
}

#[test]
fn imports_point_down_the_data_path() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let roots = reexports(&std::fs::read_to_string(src.join("lib.rs")).unwrap());
    assert!(
        roots.iter().any(|(n, w)| n == "Pass" && w == "toolpath"),
        "the re-exports were not read: {roots:?}"
    );
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut wrong = Vec::new();
    for f in &files {
        let rel = f.strip_prefix(&src).unwrap();
        let first = rel.components().next().unwrap().as_os_str().to_string_lossy().into_owned();
        let wing = first.trim_end_matches(".rs");
        let Some(rank) = WINGS.iter().position(|w| *w == wing) else { continue };
        let text = code_and_tests(&std::fs::read_to_string(f).unwrap());
        for (i, _) in text.match_indices("crate::") {
            if text[..i].ends_with(|c: char| c.is_ascii_alphanumeric() || c == '_') {
                continue;
            }
            let rest = &text[i + 7..];
            let name: String = rest.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_').collect();
            // The wing a path names, or the wing a root re-export comes from.
            let to = WINGS
                .iter()
                .find(|w| **w == name)
                .map(|w| w.to_string())
                .or_else(|| roots.iter().find(|(n, _)| *n == name).map(|(_, w)| w.clone()));
            let Some(to) = to else { continue };
            let r = WINGS.iter().position(|w| *w == to).unwrap();
            if r > rank || APART.contains(&(wing, to.as_str())) {
                wrong.push(format!("{} imports crate::{name} ({to})", rel.display()));
            }
        }
    }
    wrong.sort();
    wrong.dedup();
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
/// only in `serve/mod.rs`, the language server's (`lsp-server`, `lsp-types`) only in `lsp/mod.rs`,
/// SARIF's types and the XML writer only in `report/batch.rs` (verify's run of many).
#[test]
fn each_backend_has_one_door() {
    let mut wrong = Vec::new();
    for (rel, text) in src_code() {
        for (krate, door) in [
            ("geo::", "geometry/boolean.rs"),
            ("parry2d_f64::", "geometry/parry.rs"),
            ("rstar::", "geometry/index.rs"),
            ("axum::", "serve/mod.rs"),
            ("tokio::", "serve/mod.rs"),
            ("lsp_server::", "lsp/mod.rs"),
            ("lsp_types", "lsp/mod.rs"),
            ("serde_sarif::", "report/batch.rs"),
            ("quick_xml::", "report/batch.rs"),
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

/// `report/` is cut one way, by command: no file named after a medium, and the shared drawing
/// kit in `kit.rs`.
#[test]
fn report_is_cut_by_command() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/report");
    let names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    for medium in ["svg.rs", "html.rs", "text.rs", "json.rs", "markdown.rs"] {
        assert!(!names.iter().any(|n| n == medium), "report/{medium}: a file named after a medium");
    }
    assert!(names.iter().any(|n| n == "kit.rs"), "report/kit.rs, the shared drawing kit, is missing");
}

/// A command lives in one place: `commands/` holds a file per command, named as the command
/// line spells it, and no other wing defines a command's arguments (no clap attribute outside
/// `commands/`, `serve/args.rs`, `lsp/args.rs` and the binary's `cli.rs` and `main.rs`).
#[test]
fn a_command_lives_in_one_file() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    for name in threadcheck::Command::NAMES {
        let file = src.join("commands").join(format!("{}.rs", name.replace('-', "_")));
        assert!(file.is_file(), "{name}: no {}", file.display());
    }
    for (rel, text) in src_code() {
        if rel.starts_with("commands/")
            || rel == "serve/args.rs"
            || rel == "lsp/args.rs"
            || rel == "cli.rs"
            || rel == "main.rs"
        {
            continue;
        }
        assert!(!text.contains("clap::"), "{rel} names clap: a command's arguments belong in commands/");
    }
}

/// Below `commands/` a message names an argument by its key (`‹min_depth›`), never as a flag
/// (`--min-depth`): the command line and the API each show it as their user typed it.
#[test]
fn no_wing_below_the_commands_names_a_flag() {
    let mut wrong = Vec::new();
    for (rel, text) in src_code() {
        let Some(wing) =
            rel.split('/').next().filter(|w| rel.contains('/') && !["commands", "serve", "lsp"].contains(w))
        else {
            continue;
        };
        assert!(WINGS.contains(&wing), "{rel}");
        for (n, line) in text.lines().enumerate() {
            // Strings only: `--` between quotes, followed by a flag's letter.
            let mut quoted = false;
            let chars: Vec<char> = line.chars().collect();
            for (i, c) in chars.iter().enumerate() {
                if *c == '"' && (i == 0 || chars[i - 1] != '\\') {
                    quoted = !quoted;
                }
                if quoted
                    && *c == '-'
                    && chars.get(i + 1) == Some(&'-')
                    && chars.get(i + 2).is_some_and(|c| c.is_ascii_lowercase())
                    && !line.contains("cargo run --release")
                {
                    wrong.push(format!("{rel}:{}: {}", n + 1, line.trim()));
                    break;
                }
            }
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

/// Every key the API and Python take is a flag of the same command (read into the same field),
/// besides the two that only text input needs: a program's name and an insert file's text.
#[test]
fn every_api_key_is_a_flag_of_its_command() {
    use clap::Subcommand;
    let cli = threadcheck::Command::augment_subcommands(clap::Command::new("threadcheck"));
    for name in threadcheck::Command::API {
        let sub = cli.find_subcommand(name).unwrap_or_else(|| panic!("{name} is not a command line command"));
        let ids: Vec<&str> = sub.get_arguments().map(|a| a.get_id().as_str()).collect();
        for key in threadcheck::Command::keys(name).unwrap() {
            if key == "program_name" || key == "insert_toml" {
                continue;
            }
            assert!(ids.contains(&key), "{name}: the API's key {key} is no flag of the command line");
        }
    }
}

/// The module path of each file of `src/` (`analysis/turn/core.rs` → `analysis::turn::core`,
/// `gcode/mod.rs` → `gcode`), with the file.
fn modules() -> Vec<(String, String)> {
    src_code()
        .into_iter()
        .map(|(rel, _)| {
            let m = rel.trim_end_matches(".rs").trim_end_matches("/mod").replace('/', "::");
            (m, rel)
        })
        .collect()
}

/// The files of `src/` each file's code names (by `crate::…`, `super::…` and braced `use` lists,
/// to the deepest module a path names), unit tests left out. A module's own `mod.rs` naming its
/// children by their bare names is not an import: a parent holding its children is no circle.
fn imports() -> std::collections::BTreeMap<String, std::collections::BTreeSet<String>> {
    let mods: std::collections::BTreeSet<String> = modules().into_iter().map(|(m, _)| m).collect();
    let deepest = |parts: &[String]| -> Option<String> {
        (1..=parts.len()).rev().map(|k| parts[..k].join("::")).find(|c| mods.contains(c))
    };
    let ident = |s: &str| {
        s.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_' || *c == ':').collect::<String>()
    };
    let mut out = std::collections::BTreeMap::new();
    for (rel, text) in src_code() {
        let me = rel.trim_end_matches(".rs").trim_end_matches("/mod").replace('/', "::");
        let is_mod = rel.ends_with("mod.rs") || rel == "lib.rs";
        let parent: Vec<String> = if is_mod {
            me.split("::").map(String::from).collect()
        } else {
            let v: Vec<String> = me.split("::").map(String::from).collect();
            v[..v.len() - 1].to_vec()
        };
        let mut deps = std::collections::BTreeSet::new();
        for (prefix, base) in [
            ("crate::", Vec::new()),
            ("super::", parent[..parent.len().saturating_sub(usize::from(is_mod))].to_vec()),
        ] {
            for (i, _) in text.match_indices(prefix) {
                if text[..i].ends_with(|c: char| c.is_ascii_alphanumeric() || c == '_' || c == ':') {
                    continue;
                }
                let rest = &text[i + prefix.len()..];
                let path = ident(rest);
                let path = path.trim_end_matches(':');
                let mut parts: Vec<String> = base.clone();
                parts.extend(path.split("::").filter(|p| !p.is_empty()).map(String::from));
                // `crate::analysis::{verify, tools::Tool}`: each braced item.
                let after = &rest[path.len()..];
                if let Some(list) = after.strip_prefix("::{").and_then(|l| l.split('}').next()) {
                    for item in list.split(',') {
                        let mut p = parts.clone();
                        p.extend(ident(item.trim()).split("::").filter(|s| !s.is_empty()).map(String::from));
                        if let Some(m) = deepest(&p) {
                            deps.insert(m);
                        }
                    }
                }
                if let Some(m) = deepest(&parts) {
                    deps.insert(m);
                }
            }
        }
        deps.remove(&me);
        out.insert(me, deps);
    }
    out
}

/// Issue 60: no import circle between the files of `src/` (the five files of `analysis/` and
/// `commands/args.rs` with `commands/verify.rs` made two): each circle found is named.
#[test]
fn no_file_imports_itself_round_a_circle() {
    let graph = imports();
    assert!(
        graph.get("analysis::turn::core").is_some_and(|d| d.contains("analysis::check")),
        "the imports were not read: {:?}",
        graph.get("analysis::turn::core")
    );
    // Tarjan's strongly connected components: each of more than one file is a circle.
    struct T<'a> {
        g: &'a std::collections::BTreeMap<String, std::collections::BTreeSet<String>>,
        index: std::collections::HashMap<&'a str, usize>,
        low: std::collections::HashMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on: std::collections::HashSet<&'a str>,
        circles: Vec<Vec<&'a str>>,
    }
    fn visit<'a>(t: &mut T<'a>, v: &'a str) {
        let n = t.index.len();
        t.index.insert(v, n);
        t.low.insert(v, n);
        t.stack.push(v);
        t.on.insert(v);
        for w in t.g.get(v).into_iter().flatten() {
            let w = w.as_str();
            if !t.g.contains_key(w) {
                continue;
            }
            if !t.index.contains_key(w) {
                visit(t, w);
                let lw = t.low[w];
                let lv = t.low.get_mut(v).unwrap();
                *lv = (*lv).min(lw);
            } else if t.on.contains(w) {
                let iw = t.index[w];
                let lv = t.low.get_mut(v).unwrap();
                *lv = (*lv).min(iw);
            }
        }
        if t.low[v] == t.index[v] {
            let mut c = Vec::new();
            while let Some(w) = t.stack.pop() {
                t.on.remove(w);
                c.push(w);
                if w == v {
                    break;
                }
            }
            if c.len() > 1 {
                c.sort();
                t.circles.push(c);
            }
        }
    }
    let mut t = T {
        g: &graph,
        index: Default::default(),
        low: Default::default(),
        stack: Vec::new(),
        on: Default::default(),
        circles: Vec::new(),
    };
    for v in graph.keys() {
        if !t.index.contains_key(v.as_str()) {
            visit(&mut t, v);
        }
    }
    let circles: Vec<String> = t.circles.iter().map(|c| c.join(" → ")).collect();
    assert!(circles.is_empty(), "import circles:\n{}", circles.join("\n"));
}

/// Issue 60: no function of `src/` longer than this many lines, from its signature to its closing
/// brace (a closure counts inside the function that holds it). A longer one does several things;
/// each gets a name.
const FUNCTION_LINES: usize = 200;

/// Every function (free, in an `impl` or a trait, nested or in a unit test) of a file: its path
/// and its length in lines, read by `syn` with the spans of `proc-macro2`'s `span-locations`.
fn function_lengths(text: &str) -> Vec<(String, usize)> {
    use syn::visit::Visit;
    struct V(Vec<(String, usize)>);
    impl V {
        fn push(&mut self, sig: &syn::Signature, body: &syn::Block) {
            let (start, end) = (sig.fn_token.span.start().line, body.brace_token.span.close().end().line);
            self.0.push((sig.ident.to_string(), end - start + 1));
        }
    }
    impl<'a> Visit<'a> for V {
        fn visit_item_fn(&mut self, f: &'a syn::ItemFn) {
            self.push(&f.sig, &f.block);
            syn::visit::visit_item_fn(self, f);
        }
        fn visit_impl_item_fn(&mut self, f: &'a syn::ImplItemFn) {
            self.push(&f.sig, &f.block);
            syn::visit::visit_impl_item_fn(self, f);
        }
        fn visit_trait_item_fn(&mut self, f: &'a syn::TraitItemFn) {
            if let Some(body) = &f.default {
                self.push(&f.sig, body);
            }
            syn::visit::visit_trait_item_fn(self, f);
        }
    }
    let file = syn::parse_file(text).expect("src/ parses as Rust");
    let mut v = V(Vec::new());
    v.visit_file(&file);
    v.0
}

/// Issue 60: no function of `src/` over [`FUNCTION_LINES`] lines; each one over is named with
/// its file and length. The reader is checked first on a function of known length.
#[test]
fn no_function_is_over_200_lines() {
    let known = "fn a() {\n    let x = 1;\n    let _ = x;\n}\nimpl S { fn b(&self) {} }\n";
    assert_eq!(function_lengths(known), vec![("a".to_string(), 4), ("b".to_string(), 1)]);
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut over = Vec::new();
    let mut seen = 0;
    for f in &files {
        let text = std::fs::read_to_string(f).unwrap();
        for (name, n) in function_lengths(&text) {
            seen += 1;
            if n > FUNCTION_LINES {
                over.push(format!("{} {name}: {n} lines", f.strip_prefix(&src).unwrap().display()));
            }
        }
    }
    assert!(seen > 1000, "only {seen} functions read in src/");
    over.sort();
    assert!(over.is_empty(), "functions over {FUNCTION_LINES} lines:\n{}", over.join("\n"));
}

/// Issue 60: `docs/architecture.md` describes the tree as it is: every folder of `src/` has a
/// row of its layout table (`| `analysis/turn/` | …`), and every file of `analysis/` is named
/// in it, so a folder or a process added without a word there fails here.
#[test]
fn architecture_names_every_folder() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let doc = std::fs::read_to_string(root.join("docs/architecture.md")).unwrap();
    let src = root.join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut folders: Vec<String> = files
        .iter()
        .filter_map(|f| f.parent())
        .filter(|d| *d != src)
        .map(|d| format!("{}/", d.strip_prefix(&src).unwrap().to_string_lossy().replace('\\', "/")))
        .collect();
    folders.sort();
    folders.dedup();
    assert!(folders.len() >= 12, "only {} folders read: {folders:?}", folders.len());
    let missing: Vec<&String> = folders.iter().filter(|d| !doc.contains(&format!("| `{d}` |"))).collect();
    assert!(missing.is_empty(), "folders of src/ without a row in docs/architecture.md: {missing:?}");
    let unnamed: Vec<String> = files
        .iter()
        .filter(|f| f.starts_with(src.join("analysis")))
        .filter_map(|f| f.file_stem().map(|s| s.to_string_lossy().into_owned()))
        .filter(|stem| {
            stem != "mod" && !doc.contains(&format!("`{stem}`")) && !doc.contains(&format!("`{stem}.rs`"))
        })
        .collect();
    assert!(unnamed.is_empty(), "files of analysis/ docs/architecture.md does not name: {unnamed:?}");
}

/// Issue 60, read once: the program-reading flags are declared in one struct of `commands/`
/// (`ReadingArgs`), and every command that reads a program takes each of them, on the command
/// line and through the API; so is the designation-reading flag (`StandardArgs`), taken by every
/// command that reads a thread.
#[test]
fn the_reading_flags_are_declared_once_and_taken_by_every_reader() {
    use clap::Subcommand;
    const READING: [&str; 7] = [
        "dialect",
        "default_units",
        "main",
        "linuxcnc_release",
        "gcode_system",
        "machine_type",
        "block_delete",
    ];
    // Each struct clap reads flags into: its name and its body.
    let flag_structs: Vec<(String, String)> = src_code()
        .into_iter()
        .filter(|(f, _)| f.starts_with("commands/"))
        .flat_map(|(_, code)| {
            code.split("derive(clap::Args))]")
                .skip(1)
                .filter_map(|after| {
                    let at = after.find("pub struct ")? + "pub struct ".len();
                    let name: String = after[at..].chars().take_while(|c| c.is_alphanumeric()).collect();
                    let body = &after[at..];
                    Some((name, body[..body.find("\n}").unwrap_or(body.len())].to_string()))
                })
                .collect::<Vec<_>>()
        })
        .collect();
    assert!(flag_structs.len() > 5, "{flag_structs:?}");
    for key in READING.iter().chain(&["subroutine_path"]) {
        let declared: Vec<&str> = flag_structs
            .iter()
            .filter(|(_, body)| body.contains(&format!("pub {key}:")))
            .map(|(name, _)| name.as_str())
            .collect();
        assert_eq!(declared, vec!["ReadingArgs"], "{key} is declared in {declared:?}");
    }
    let cli = threadcheck::Command::augment_subcommands(clap::Command::new("threadcheck"));
    for name in ["verify", "passes", "compare", "correct", "capability", "tap", "thread-mill", "mill"] {
        let sub = cli.find_subcommand(name).unwrap();
        let ids: Vec<&str> = sub.get_arguments().map(|a| a.get_id().as_str()).collect();
        let keys = threadcheck::Command::keys(name).unwrap();
        for key in READING {
            assert!(ids.contains(&key), "{name} has no --{}", key.replace('_', "-"));
            assert!(keys.contains(&key), "{name}'s API takes no {key}");
        }
        assert!(ids.contains(&"subroutine_path"), "{name} has no --subroutine-path");
    }
    // How a designation is read: declared once, in StandardArgs, and taken by every command that
    // reads one (mill reads none).
    let declared: Vec<&str> = flag_structs
        .iter()
        .filter(|(_, body)| body.contains("pub allow_nonstandard:"))
        .map(|(name, _)| name.as_str())
        .collect();
    assert_eq!(declared, vec!["StandardArgs"], "allow_nonstandard is declared in {declared:?}");
    for name in
        ["verify", "passes", "compare", "correct", "capability", "limits", "fit", "tap", "thread-mill"]
    {
        let sub = cli.find_subcommand(name).unwrap();
        assert!(
            sub.get_arguments().any(|a| a.get_id() == "allow_nonstandard"),
            "{name} has no --allow-nonstandard"
        );
        let keys = threadcheck::Command::keys(name).unwrap();
        assert!(keys.contains(&"allow_nonstandard"), "{name}'s API takes no allow_nonstandard");
    }
}

/// The reading flags do in the other commands that read a program what they do in verify: a
/// system-B G78 (the threading cycle) is refused in system A by `thread-mill` naming its own
/// `--gcode-system` (it named verify's before it took the flag), and read past with
/// `--gcode-system b` (it then says what it lacks: the cutter).
#[test]
fn thread_mill_reads_with_verifys_flags() {
    let prog = crate::data("programs/fanuc-system-b-g78.nc");
    let p = prog.to_str().unwrap();
    let o = crate::run(&["thread-mill", "--program", p]);
    assert_eq!(o.status.code(), Some(2));
    let e = crate::stderr(&o);
    assert!(
        e.contains(":7:1: G78 is not a code of Fanuc G-code system A")
            && e.contains("give --gcode-system b or c"),
        "{e}"
    );
    let o = crate::run(&["thread-mill", "--program", p, "--gcode-system", "b"]);
    let e = crate::stderr(&o);
    assert!(!e.contains("G78") && e.contains("give the cutter"), "{e}");
}

/// Issue 60, read once: a designation is parsed where it enters and carried parsed after that —
/// a flag's, a project file's or a modeline's by its command (`StandardArgs::parse`), a comment's,
/// a CAM tool list's or an inferred size's by `naming`, a tool library's description by
/// `fusion`, a tool table's tap where a hole takes it, the catalogue's sizes by the sweep,
/// `VerifySpec::of`'s for a library caller. A parse anywhere else is a second one.
#[test]
fn a_designation_is_parsed_where_it_enters() {
    const ENTRIES: [&str; 7] = [
        "commands/args.rs",
        "analysis/naming.rs",
        "analysis/fusion.rs",
        "analysis/tap.rs",
        "analysis/study/sweep.rs",
        "analysis/turn/spec.rs",
        "standards/designation.rs",
    ];
    let parsing: Vec<String> = src_code()
        .into_iter()
        .filter(|(f, code)| code.contains("parse_designation(") && !ENTRIES.contains(&f.as_str()))
        .map(|(f, _)| f)
        .collect();
    assert!(parsing.is_empty(), "a designation parsed again in {parsing:?}");
    // And the specs carry it parsed.
    for (file, field) in [
        ("analysis/turn/spec.rs", "pub designation: Option<Designation>,"),
        ("analysis/naming.rs", "pub designation: Designation,"),
        ("analysis/thread_mill.rs", "pub designation: Option<crate::standards::Designation>,"),
        ("analysis/study/fit.rs", "pub thread: Designation,"),
        ("analysis/tap.rs", "pub tap: Option<crate::standards::Designation>,"),
    ] {
        let code = src_code().into_iter().find(|(f, _)| f == file).map(|(_, c)| c).unwrap_or_default();
        assert!(code.contains(field), "{file} carries no parsed designation ({field})");
    }
}

/// Issue 60, one name for one thing: a note carries its argument as data (`‹insert›`), and each
/// reader gets it in its own words — a library caller printing a note (`to_string`) the key the
/// API and Python take, the command line its flag; the marked text is the reports' to render.
#[test]
fn a_library_caller_reads_notes_in_its_own_words() {
    use threadcheck::{verify_program, Dialect, InsertChoice, VerifySpec};
    let text = "(M20X1.5-6G)\nG0 X22 Z5\nG76 P011060 Q100 R0.05\nG76 X18.16 Z-20 P920 Q350 F1.5\n";
    let assumed = |_: &threadcheck::Operation| Some((InsertChoice::Full, "no tool known".to_string(), true));
    let pv = verify_program(&VerifySpec::new(None), text, "m20.nc", Dialect::Fanuc, &[], &assumed).unwrap();
    let threadcheck::OperationResult::Verified(v) = &pv.operations[0].result else { panic!("not cut") };
    let note = v.notes.iter().find(|n| n.message.contains("insert assumed")).expect("the insert's note");
    let library = note.to_string();
    assert!(library.contains("choose with insert or tools") && !library.contains('‹'), "{library}");
    assert!(note.marked().to_string().contains("choose with ‹insert› or ‹tools›"), "{}", note.marked());
    let dir = crate::tempdir("notes");
    let path = dir.join("m20.nc");
    std::fs::write(&path, text).unwrap();
    let o = crate::run(&["verify", "--program", path.to_str().unwrap()]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("choose with --insert or --tools"), "{out}");
}
