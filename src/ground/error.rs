//! The one error type. Every message is one line that names the bad input and states the domain
//! fact it breaks; the CLI prints it and exits with code 2.

/// Everything that can go wrong before a verdict.
///
/// A message names the argument it concerns by its key (`‹min_depth›`, see [`Audience`]):
/// shown (`Display`, `to_string`) as a library caller passes it, `min_depth`; the command line,
/// the API and the page name it their own way with [`one_line_for`](Error::one_line_for).
///
/// ```
/// use threadcheck::{Audience, Error};
/// let e = Error::Input("‹min_depth› must not exceed the thread's depth".into());
/// assert_eq!(e.to_string(), "min_depth must not exceed the thread's depth");
/// assert_eq!(e.one_line_for(Audience::Cli), "--min-depth must not exceed the thread's depth");
/// let e = Error::Program { file: "a.nc".into(), line: 3, column: 1, message: "give ‹gcode_system› b".into() };
/// assert_eq!(e.to_string(), "a.nc:3:1: give gcode_system b");
/// assert_eq!(e.one_line_for(Audience::Cli), "a.nc:3:1: give --gcode-system b");
/// ```
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A thread designation that cannot be read.
    #[error(transparent)]
    Designation(#[from] DesignationError),
    /// A G-code program that cannot be read or expanded, with its place.
    #[error("{file}:{line}:{column}: {}", Audience::Api.words(message))]
    Program {
        /// File name as given.
        file: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What is wrong.
        message: String,
    },
    /// A TOML file (insert, plan) that cannot be read, with its place.
    #[error("{file}: {}", Audience::Api.words(message))]
    File {
        /// File name as given.
        file: String,
        /// What is wrong (with line and column where known).
        message: String,
    },
    /// Geometry that cannot exist or cannot be cut (a tip radius too large, no crest left, …).
    #[error("{}", Audience::Api.words(.0))]
    Geometry(String),
    /// An option value or combination that makes no sense.
    #[error("{}", Audience::Api.words(.0))]
    Input(String),
    /// The embedded data is broken (a build defect, never the user's input).
    #[error("embedded data: {0}")]
    Data(String),
    /// The computation was stopped before it ended (the server's time budget ran out, or the
    /// server is stopping): see [`Cancel`](crate::Cancel).
    #[error(
        "the computation was stopped before it ended (its time budget ran out, or the server is stopping)"
    )]
    Cancelled,
    /// Reading or writing a file failed.
    #[error("{path}: {source}")]
    Io {
        /// The path.
        path: String,
        /// The operating system's error.
        #[source]
        source: std::io::Error,
    },
}

impl Error {
    /// An [`Error::Io`] for `path`.
    pub fn io(path: impl std::fmt::Display, source: std::io::Error) -> Error {
        Error::Io { path: path.to_string(), source }
    }

    /// The message as the one line the CLI prints and Python raises: see [`one_line`].
    ///
    /// ```
    /// let e = threadcheck::Error::Input("a\nb \u{1b}[31m".into());
    /// assert_eq!(e.one_line(), "a b \\u{1b}[31m");
    /// ```
    ///
    /// The place (`file:line:column:`, `file:`, `path:`) is kept whole, escaped only, so that
    /// an editor or CI can jump to it however deep the folder; the untrusted text after it is
    /// shortened as [`one_line`] does.
    pub fn one_line(&self) -> String {
        let mut out = String::new();
        match self {
            Error::Program { file, line, column, message } => {
                escape_into(&mut out, file.chars());
                out.push_str(&format!(":{line}:{column}: "));
                out.push_str(&one_line(message));
            }
            Error::File { file, message } => {
                escape_into(&mut out, file.chars());
                out.push_str(": ");
                out.push_str(&one_line(message));
            }
            Error::Io { path, source } => {
                escape_into(&mut out, path.chars());
                out.push_str(": ");
                out.push_str(&one_line(&source.to_string()));
            }
            // The message as written, its keys for the reader to name (one_line_for).
            Error::Geometry(message) | Error::Input(message) => out = one_line(message),
            _ => out = one_line(&self.to_string()),
        }
        out
    }

    /// [`one_line`](Error::one_line) with its arguments named for `reader` (see [`Audience`]).
    pub fn one_line_for(&self, reader: Audience) -> String {
        reader.words(&self.one_line())
    }
}

/// Who reads a message, and so how it names an argument.
///
/// Below the commands a message names an argument by its key between single guillemets,
/// `‹min_depth›`, the fact it sets rather than a flag; the command line shows it as the flag its
/// user typed (`--min-depth`), the API and Python as the key their user passed (`min_depth`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Audience {
    /// The command line: `--min-depth`.
    Cli,
    /// The JSON API and Python: `min_depth`.
    Api,
    /// The shop's page (`serve`): its fields by their labels (`the Thread field`); a key the page
    /// has no field for by the modeline that sets it, else by the command line's flag.
    Page,
}

/// What the page calls a key: its field's label, or where the page's reader sets it instead.
fn page_words(key: &str) -> String {
    match key {
        "program" => "the Program field".into(),
        "thread" => "the Thread field".into(),
        "dialect" => "the Dialect field".into(),
        "insert" => "the Insert field".into(),
        "tools" => "the Tool table field".into(),
        "final_x" => "the Final X field".into(),
        "coating" => "the Coating field".into(),
        "coating_limits" => "'The class applies'".into(),
        "gauge_only" => "the 'gauge only' box".into(),
        "allow_nonstandard" => "the 'non-standard size' box".into(),
        "internal" => "the 'internal' box".into(),
        // The page reads a pasted program's modeline.
        "machine_type" | "default_units" => {
            format!("a modeline in the program's first lines, (threadcheck: {}=…),", key.replace('_', "-"))
        }
        // No field on the page: the command line's flag (a value may follow it).
        k => format!("the command line's --{}", k.replace('_', "-")),
    }
}

impl Audience {
    /// `text` with every `‹key›` (a lower-case key of letters, digits and `_`) named for this
    /// reader; anything else between guillemets is left as it is.
    ///
    /// ```
    /// use threadcheck::Audience;
    /// let m = "‹min_depth› must not exceed the depth ‹x›";
    /// assert_eq!(Audience::Cli.words(m), "--min-depth must not exceed the depth --x");
    /// assert_eq!(Audience::Api.words(m), "min_depth must not exceed the depth x");
    /// assert_eq!(Audience::Api.words("‹Not a key›"), "‹Not a key›");
    /// assert_eq!(Audience::Page.words("‹min_depth› or ‹thread›"), "the command line's --min-depth or the Thread field");
    /// assert_eq!(Audience::Page.words("use ‹insert› full"), "use Insert: full profile");
    /// ```
    pub fn words(self, text: &str) -> String {
        let text = if self == Audience::Page { Audience::page_phrases(text) } else { text.to_string() };
        name_keys(&text, |key| match self {
            Audience::Cli => format!("--{}", key.replace('_', "-")),
            Audience::Api => key.to_string(),
            Audience::Page => page_words(key),
        })
    }

    /// The page's words for a key with the value it takes (`‹insert› full`, the Insert
    /// field's choice), before the keys alone.
    fn page_phrases(text: &str) -> String {
        const PHRASES: [(&str, &str); 7] = [
            ("‹insert› full", "Insert: full profile"),
            ("give ‹insert› or ‹tools›", "choose the Insert or give a tool table"),
            ("‹insert› or ‹tools›", "the Insert or a tool table"),
            ("‹insert› partial:R", "Insert: partial, tip radius R"),
            ("‹coating_limits› after", "'The class applies: after coating'"),
            ("(‹allow_nonstandard›)", "(tick 'non-standard size')"),
            ("‹allow_nonstandard›", "the 'non-standard size' box"),
        ];
        PHRASES.iter().fold(text.to_string(), |t, (from, to)| t.replace(from, to))
    }
}

/// `text` with every `‹key›` replaced by `name(key)`; anything else between guillemets is left.
fn name_keys(text: &str, name: impl Fn(&str) -> String) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(open) = rest.find('‹') {
        out.push_str(&rest[..open]);
        let after = &rest[open + '‹'.len_utf8()..];
        match after.find('›').filter(|&n| n > 0 && is_key(&after[..n])) {
            Some(n) => {
                out.push_str(&name(&after[..n]));
                rest = &after[n + '›'.len_utf8()..];
            }
            None => {
                out.push('‹');
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}

/// What the command line in use accepts, for naming a `‹key›` in an error line: its own keys and
/// each other command's (key, command).
#[derive(Clone, Debug, Default)]
pub struct CliFlags {
    own: Vec<String>,
    elsewhere: Vec<(String, String)>,
}

impl CliFlags {
    /// The flags of `command` among every command's (their keys, `_` for `-`).
    pub fn of(command: &str, accepts: &[(String, Vec<String>)]) -> CliFlags {
        let own = accepts.iter().find(|(c, _)| c == command).map(|(_, k)| k.clone()).unwrap_or_default();
        let elsewhere = accepts
            .iter()
            .filter(|(c, _)| c != command)
            .flat_map(|(c, keys)| keys.iter().map(move |k| (k.clone(), c.clone())))
            .collect();
        CliFlags { own, elsewhere }
    }

    /// `key` as the command line in use names it: its flag, or another command's flag with that
    /// command's name when this one lacks it (`threadcheck tap --tap`), so that an error never
    /// tells the user to give a flag the command refuses.
    fn flag(&self, key: &str) -> String {
        let flag = format!("--{}", key.replace('_', "-"));
        if self.own.iter().any(|k| k == key) {
            return flag;
        }
        match self.elsewhere.iter().find(|(k, _)| k == key) {
            Some((_, other)) => format!("`threadcheck {other} {flag}`"),
            None => flag,
        }
    }
}

impl Error {
    /// The one line the command line prints for this error, each `‹key›` named as the command in
    /// use takes it ([`CliFlags`]).
    pub fn one_line_for_command(&self, flags: &CliFlags) -> String {
        name_keys(&self.one_line(), |key| flags.flag(key))
    }
}

/// A `‹key›`'s inside: a lower-case letter, then lower-case letters, digits and `_`.
fn is_key(k: &str) -> bool {
    k.starts_with(|c: char| c.is_ascii_lowercase())
        && k.chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
}

/// Longest run of text without a space that an error line shows whole; a longer one (a
/// megabyte-long number) is shortened to its first [`TOKEN_HEAD`] and last [`TOKEN_TAIL`]
/// characters around an ellipsis.
pub const MAX_TOKEN: usize = 80;
/// Characters kept from the start of a shortened token.
pub const TOKEN_HEAD: usize = 40;
/// Characters kept from the end of a shortened token.
pub const TOKEN_TAIL: usize = 12;

/// `text` as one line a terminal shows as it is: line breaks become spaces; other control
/// characters and the bidirectional overrides (U+202A–U+202E, U+2066–U+2069), which could
/// disguise a file name or a message, are written `\u{…}`; a run of more than 80
/// characters without a space is shortened around an ellipsis.
pub fn one_line(text: &str) -> String {
    let mut out = String::with_capacity(text.len().min(4096));
    for token in text.split(' ') {
        if !out.is_empty() {
            out.push(' ');
        }
        let n = token.chars().count();
        if n > MAX_TOKEN {
            escape_into(&mut out, token.chars().take(TOKEN_HEAD));
            out.push('…');
            escape_into(&mut out, token.chars().skip(n - TOKEN_TAIL));
        } else {
            escape_into(&mut out, token.chars());
        }
    }
    out
}

fn escape_into(out: &mut String, chars: impl Iterator<Item = char>) {
    for c in chars {
        match c {
            '\n' | '\r' if out.ends_with(' ') => {}
            '\n' | '\r' => out.push(' '),
            '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}' => {
                out.push_str(&format!("\\u{{{:x}}}", c as u32))
            }
            c if c.is_control() => out.push_str(&format!("\\u{{{:x}}}", c as u32)),
            c => out.push(c),
        }
    }
}

/// A user's TOML file that cannot be read (a tool table, insert, thread mill, machine profile,
/// target), located at `file:line:column` with the reader's message alone: never the file's
/// text, which may be a file that is no table at all (a system file named by mistake).
pub fn toml_error(e: &toml::de::Error, text: &str, file: &str) -> Error {
    let message = one_line(e.message());
    match e.span() {
        Some(span) => {
            let before = text.get(..span.start.min(text.len())).unwrap_or("");
            let line = before.matches('\n').count() + 1;
            let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
            Error::Program { file: file.to_string(), line, column, message }
        }
        None => Error::File { file: file.to_string(), message },
    }
}

/// Shorthand for results in this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// A designation that cannot be read, with the offending part of the text.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("designation '{text}', column {column}{}: {message}", if part.is_empty() { String::new() } else { format!(" ('{part}')") })]
pub struct DesignationError {
    /// The whole designation.
    pub text: String,
    /// 1-based column (in characters) where the bad part starts.
    pub column: usize,
    /// The bad part of the text (may be empty at the end of the text).
    pub part: String,
    /// What is wrong, in domain terms.
    pub message: String,
}
