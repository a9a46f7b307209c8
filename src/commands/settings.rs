//! How a folder of programs says how its programs are read (issue 65): a project file,
//! `.threadcheck.toml`, found from the program's folder upwards, and a modeline, a comment in
//! a program's first lines (`(threadcheck: dialect=linuxcnc machine-type=mill)`, or after `;`).
//! A flag given wins over both, the modeline over the project file; every value taken from
//! either is stated in the notes with where it came from.
//!
//! ```toml
//! # .threadcheck.toml
//! dialect = "linuxcnc"
//! machine-type = "mill"
//! machine = "machines/vf2.toml"    # beside the project file
//! tools = "tools.toml"
//! default-units = "inch"
//! [[threads]]
//! files = "bolts/**/*.ngc"         # beside the project file; `*` stops at `/`, `**` crosses it
//! thread = "1/2-13 UNC-2A"         # or a list, one per operation
//! ```

use crate::gcode::{Dialect, MachineType, ProgramUnits};
use crate::Error;
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// The project file's name.
pub const PROJECT_FILE: &str = ".threadcheck.toml";

/// How many of a program's first lines a modeline may stand in (a Fanuc program's `%` and
/// `O1000` come first).
pub const MODELINE_LINES: usize = 5;

/// The most folders looked at above a program's own for a project file.
const MAX_LEVELS: usize = 64;

/// Where a setting came from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SetBy {
    /// The project file at this path (as shown).
    ProjectFile(String),
    /// The program's modeline at this line.
    Modeline(usize),
}

impl SetBy {
    /// The words that name it: `the project file x/.threadcheck.toml`.
    pub fn phrase(&self) -> String {
        match self {
            SetBy::ProjectFile(p) => format!("the project file {p}"),
            SetBy::Modeline(line) => format!("the program's modeline (line {line})"),
        }
    }
}

/// A value and where it came from.
pub type Set<T> = Option<(T, SetBy)>;

/// What a project file and a modeline set for one program.
#[derive(Clone, Debug, Default)]
pub struct Settings {
    /// The dialect.
    pub dialect: Set<Dialect>,
    /// The machine type.
    pub machine_type: Set<MachineType>,
    /// The units of a program that sets none.
    pub default_units: Set<ProgramUnits>,
    /// The machine file (a path beside the project file).
    pub machine: Set<PathBuf>,
    /// The tool table (a path beside the project file).
    pub tools: Set<PathBuf>,
    /// The threads, one for all operations or one per operation (a `[[threads]]` rule's, or the
    /// modeline's `thread=`).
    pub thread: Set<Vec<String>>,
    /// The program is a file but not a regular one (a pipe, a device): its modeline is not
    /// looked for (its text is read once, by the program's reader), and the notes say so.
    pub modeline_unread: bool,
}

/// The project file as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields, rename_all = "kebab-case")]
struct ProjectFile {
    dialect: Option<String>,
    machine_type: Option<String>,
    default_units: Option<String>,
    machine: Option<PathBuf>,
    tools: Option<PathBuf>,
    #[serde(default)]
    threads: Vec<ThreadRule>,
}

/// A `[[threads]]` rule: the programs a glob names cut these threads.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ThreadRule {
    files: String,
    thread: OneOrMany,
}

/// A rule's thread: one designation, or a list of them.
#[derive(Deserialize)]
#[serde(untagged, expecting = "a designation or a list of them")]
enum OneOrMany {
    One(String),
    Many(Vec<String>),
}

impl OneOrMany {
    fn list(&self) -> Vec<String> {
        match self {
            OneOrMany::One(t) => vec![t.clone()],
            OneOrMany::Many(v) => v.clone(),
        }
    }
}

impl Settings {
    /// The settings of a program: `path` its file, or the path a program given as `text` is
    /// called by (an editor's or the API's; its folder is looked in when `files` allows);
    /// `files` whether files may be read (the server reads none: the modeline alone).
    pub fn of(path: Option<&Path>, text: Option<&str>, files: super::Files) -> Result<Settings, Error> {
        let mut s = Settings::default();
        if files == super::Files::Allowed {
            if let Some(p) = path {
                if let Some(found) = project_file_of(p) {
                    s.read_project_file(&found, p)?;
                }
            }
        }
        let head = match (text, path) {
            (Some(t), _) => t.chars().take(4096).collect(),
            (None, Some(p)) => {
                s.modeline_unread = std::fs::metadata(p).is_ok_and(|m| !m.is_file() && !m.is_dir());
                head_of_file(p)
            }
            (None, None) => String::new(),
        };
        let shown = path.map_or_else(|| "<program>".to_string(), crate::ground::fmt::path_name);
        s.read_modeline(&head, &shown)?;
        Ok(s)
    }

    /// The units of a program that sets none: the flag's (`given`), else the ones set here,
    /// with where they came from (`None` for the flag's: nothing to say).
    pub fn default_units(&self, given: Option<ProgramUnits>) -> (Option<ProgramUnits>, Option<String>) {
        match (given, &self.default_units) {
            (Some(u), _) => (Some(u), None),
            (None, Some((u, by))) => (Some(*u), Some(by.phrase())),
            (None, None) => (None, None),
        }
    }

    /// Nothing set.
    pub fn is_empty(&self) -> bool {
        self.dialect.is_none()
            && self.machine_type.is_none()
            && self.default_units.is_none()
            && self.machine.is_none()
            && self.tools.is_none()
            && self.thread.is_none()
            && !self.modeline_unread
    }

    /// Reads the project file `file` for the program at `program`.
    fn read_project_file(&mut self, file: &Path, program: &Path) -> Result<(), Error> {
        let shown = crate::ground::fmt::path_name(file);
        let text = crate::ground::input::read_text_bounded(
            file,
            crate::ground::bounds::MAX_DATA_FILE_BYTES,
            "a project file",
        )?;
        let f: ProjectFile =
            toml::from_str(&text).map_err(|e| crate::ground::error::toml_error(&e, &text, &shown))?;
        let by = || SetBy::ProjectFile(shown.clone());
        let bad = |key: &str, e: String| Error::File { file: shown.clone(), message: format!("{key}: {e}") };
        let dir = folder_of(file);
        if let Some(d) = f.dialect {
            self.dialect = Some((d.parse().map_err(|e: Error| bad("dialect", e.to_string()))?, by()));
        }
        if let Some(m) = f.machine_type {
            self.machine_type =
                Some((m.parse().map_err(|e: Error| bad("machine-type", e.to_string()))?, by()));
        }
        if let Some(u) = f.default_units {
            self.default_units =
                Some((u.parse().map_err(|e: Error| bad("default-units", e.to_string()))?, by()));
        }
        // Paths beside the project file (an absolute one as written).
        let beside = |p: PathBuf| if dir == Path::new(".") { p } else { dir.join(p) };
        self.machine = f.machine.map(|m| (beside(m), by()));
        self.tools = f.tools.map(|t| (beside(t), by()));
        // The first rule whose glob names the program, relative to the project file's folder.
        let abs_dir = std::path::absolute(dir).unwrap_or_else(|_| dir.to_path_buf());
        let abs_program = std::path::absolute(program).unwrap_or_else(|_| program.to_path_buf());
        let relative = abs_program.strip_prefix(&abs_dir).unwrap_or(&abs_program);
        for (i, rule) in f.threads.iter().enumerate() {
            let glob = globset::GlobBuilder::new(&rule.files)
                .literal_separator(true)
                .build()
                .map_err(|e| bad(&format!("threads[{}].files", i + 1), e.kind().to_string()))?
                .compile_matcher();
            let thread = rule.thread.list();
            if thread.is_empty() {
                return Err(bad(&format!("threads[{}].thread", i + 1), "names no thread".into()));
            }
            if glob.is_match(relative) {
                self.thread = Some((thread, SetBy::ProjectFile(format!("{shown} ('{}')", rule.files))));
                break;
            }
        }
        Ok(())
    }

    /// Reads a modeline in the first [`MODELINE_LINES`] lines of `head`: a comment whose text
    /// begins `threadcheck:`, then `key=value` words. `shown` names the program in errors.
    fn read_modeline(&mut self, head: &str, shown: &str) -> Result<(), Error> {
        for (i, line) in head.lines().take(MODELINE_LINES).enumerate() {
            let Some((col, words)) = modeline_words(line) else { continue };
            let n = i + 1;
            let at = |column: usize, message: String| Error::Program {
                file: shown.to_string(),
                line: n,
                column,
                message: format!("modeline: {message}"),
            };
            for (start, word) in modeline_tokens(words) {
                let column = col + start + 1;
                let Some((key, value)) = word.split_once('=') else {
                    return Err(at(column, format!("'{word}' is not key=value")));
                };
                let value = value.strip_prefix('"').and_then(|v| v.strip_suffix('"')).unwrap_or(value);
                let by = SetBy::Modeline(n);
                let bad = |e: Error| at(column, format!("{key}: {e}"));
                match key.replace('_', "-").to_ascii_lowercase().as_str() {
                    "dialect" => self.dialect = Some((value.parse().map_err(bad)?, by)),
                    "machine-type" => self.machine_type = Some((value.parse().map_err(bad)?, by)),
                    "default-units" => self.default_units = Some((value.parse().map_err(bad)?, by)),
                    "thread" => {
                        self.thread = Some((value.split(',').map(str::to_string).collect(), by));
                    }
                    _ => {
                        return Err(at(
                            column,
                            format!(
                                "unknown key '{key}': a modeline takes dialect, machine-type, default-units and thread (files are the project file's)"
                            ),
                        ))
                    }
                }
            }
            return Ok(());
        }
        Ok(())
    }

    /// The notes that say where each value came from: one per source, and one per value a
    /// flag overrode (`given` names the flags given, with their values' words).
    pub fn notes(&self, given: &Given) -> Vec<String> {
        let mut by_source: Vec<(SetBy, Vec<String>)> = Vec::new();
        let mut overridden = Vec::new();
        let mut add = |by: &SetBy, what: String, flag: Option<&String>, key: &str| match flag {
            Some(f) => {
                overridden.push(format!("‹{key}› {f} is given, over {what} that {} sets", by.phrase()))
            }
            None => match by_source.iter_mut().find(|(b, _)| b == by) {
                Some((_, v)) => v.push(what),
                None => by_source.push((by.clone(), vec![what])),
            },
        };
        if let Some((d, by)) = &self.dialect {
            add(by, format!("dialect {}", d.name()), given.dialect.as_ref(), "dialect");
        }
        if let Some((m, by)) = &self.machine_type {
            add(by, format!("machine type {}", m.name()), given.machine_type.as_ref(), "machine_type");
        }
        if let Some((u, by)) = &self.default_units {
            add(by, format!("default units {}", u.name()), given.default_units.as_ref(), "default_units");
        }
        if let Some((m, by)) = &self.machine {
            add(
                by,
                format!("machine file {}", crate::ground::fmt::path_name(m)),
                given.machine.as_ref(),
                "machine",
            );
        }
        if let Some((t, by)) = &self.tools {
            add(
                by,
                format!("tool table {}", crate::ground::fmt::path_name(t)),
                given.tools.as_ref(),
                "tools",
            );
        }
        if let Some((t, by)) = &self.thread {
            add(by, format!("thread {}", t.join(", ")), given.thread.as_ref(), "thread");
        }
        let unread = self.modeline_unread.then(|| {
            "the program is not a regular file (a pipe or a device): its modeline is not looked for (give its options as flags)".to_string()
        });
        by_source
            .into_iter()
            .map(|(by, what)| format!("read with {}: {}", by.phrase(), what.join(", ")))
            .chain(overridden)
            .chain(unread)
            .collect()
    }
}

/// The flags given, each with its value's words, for the notes that say a flag won.
#[derive(Clone, Debug, Default)]
pub struct Given {
    /// ‹dialect›.
    pub dialect: Option<String>,
    /// ‹machine_type›.
    pub machine_type: Option<String>,
    /// ‹default_units›.
    pub default_units: Option<String>,
    /// ‹machine›.
    pub machine: Option<String>,
    /// ‹tools›.
    pub tools: Option<String>,
    /// ‹thread›.
    pub thread: Option<String>,
}

/// The modeline's words in `line`: the text after `threadcheck:` in a comment, `( … )` or after
/// `;`, and the byte offset it starts at.
fn modeline_words(line: &str) -> Option<(usize, &str)> {
    const KEY: &str = "threadcheck:";
    let open = line.find(['(', ';'])?;
    let inner_start = open + 1;
    let inner = &line[inner_start..];
    let lead = inner.len() - inner.trim_start().len();
    let body = &inner[lead..];
    if !body.get(..KEY.len()).is_some_and(|k| k.eq_ignore_ascii_case(KEY)) {
        return None;
    }
    let start = inner_start + lead + KEY.len();
    let rest = &line[start..];
    let end = if line.as_bytes()[open] == b'(' { rest.find(')').unwrap_or(rest.len()) } else { rest.len() };
    Some((start, &rest[..end]))
}

/// The modeline's `key=value` words and their byte offsets: split at white space outside
/// double quotes (`thread="1/4-20 UNC-2A"`).
fn modeline_tokens(words: &str) -> Vec<(usize, &str)> {
    let mut out = Vec::new();
    let mut start = None;
    let mut quoted = false;
    for (i, c) in words.char_indices() {
        match (start, c) {
            (None, c) if c.is_whitespace() => {}
            (None, c) => {
                start = Some(i);
                quoted = c == '"';
            }
            (Some(_), '"') => quoted = !quoted,
            (Some(s), c) if c.is_whitespace() && !quoted => {
                out.push((s, &words[s..i]));
                start = None;
            }
            _ => {}
        }
    }
    if let Some(s) = start {
        out.push((s, &words[s..]));
    }
    out
}

/// The folder a file stands in (`.` for a bare name).
fn folder_of(p: &Path) -> &Path {
    p.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."))
}

/// The first 4 KiB of a file, as text (empty when it cannot be read: its reading says why).
fn head_of_file(path: &Path) -> String {
    use std::io::Read;
    let mut head = Vec::new();
    // Only a regular file is opened: opening a FIFO with no writer waits for one.
    if std::fs::metadata(path).is_ok_and(|m| m.is_file()) {
        if let Ok(f) = std::fs::File::open(path) {
            let _ = f.take(4096).read_to_end(&mut head);
        }
    }
    String::from_utf8_lossy(&head).into_owned()
}

/// The project file that governs a program at `program`: the nearest [`PROJECT_FILE`] in its
/// folder or one above it.
pub fn project_file_of(program: &Path) -> Option<PathBuf> {
    let folder = folder_of(program);
    let start = std::path::absolute(folder).ok()?;
    let relative = folder.is_relative();
    let here = std::env::current_dir().ok();
    for dir in start.ancestors().take(MAX_LEVELS) {
        let candidate = dir.join(PROJECT_FILE);
        if candidate.is_file() {
            // Named as the program is: relative to the working folder when it lies under it.
            let shown = match (&here, relative) {
                (Some(h), true) => candidate.strip_prefix(h).map_or(candidate.clone(), Path::to_path_buf),
                _ => candidate,
            };
            return Some(shown);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_modeline_is_read_in_either_comment() {
        assert_eq!(modeline_words("(threadcheck: dialect=linuxcnc)"), Some((13, " dialect=linuxcnc")));
        assert_eq!(modeline_words("; threadcheck: machine-type=mill"), Some((14, " machine-type=mill")));
        assert_eq!(modeline_words("%"), None);
        assert_eq!(modeline_words("(TAP M10X1.5)"), None);
        assert_eq!(
            modeline_tokens(" dialect=fanuc thread=\"1/4-20 UNC-2A\" "),
            vec![(1, "dialect=fanuc"), (15, "thread=\"1/4-20 UNC-2A\"")]
        );
    }
}
