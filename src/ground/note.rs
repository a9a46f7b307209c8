//! Notes: what a reading or a verification says beside its result (an assumption it made, a
//! warning), with its place in the program when it has one. Typed, never re-parsed from text;
//! written as `file:line:column: message` (or the message alone) in the text and the JSON.

use serde::Serialize;
use std::fmt;

/// A place in a program: file (as the messages name it), line and column, from 1.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Place {
    /// The file's name.
    pub file: String,
    /// Line, from 1.
    pub line: usize,
    /// Column, from 1.
    pub column: usize,
}

/// What a note is about, where the code that reads notes decides on it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum NoteKind {
    /// An assumption or a warning for the reader.
    Remark,
    /// A variable is read before it is set.
    UnsetVariable,
    /// A subprogram is defined and never called.
    NeverCalled,
    /// A block (or part of one) threadcheck does not model, read past.
    ReadPast,
}

/// One note.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Note {
    /// Where in the program, when it is about a place.
    pub place: Option<Place>,
    /// What it is about.
    pub kind: NoteKind,
    /// The words.
    pub message: String,
}

impl Note {
    /// A remark about a place.
    pub fn at(file: &str, line: usize, column: usize, message: impl Into<String>) -> Note {
        Note {
            place: Some(Place { file: file.to_string(), line, column }),
            kind: NoteKind::Remark,
            message: message.into(),
        }
    }

    /// The same note of another kind.
    pub fn of_kind(self, kind: NoteKind) -> Note {
        Note { kind, ..self }
    }
}

impl From<String> for Note {
    /// A remark about no place.
    fn from(message: String) -> Note {
        Note { place: None, kind: NoteKind::Remark, message }
    }
}

impl From<&str> for Note {
    fn from(message: &str) -> Note {
        Note::from(message.to_string())
    }
}

/// A note as a library caller reads it: an argument named by its key (`blank_diameter`), as
/// the API and Python name it.
///
/// ```
/// use threadcheck::Note;
/// let n = Note::at("part.nc", 12, 1, "the blank is the stock the program declares (‹blank_diameter› overrides)");
/// assert_eq!(n.to_string(), "part.nc:12:1: the blank is the stock the program declares (blank_diameter overrides)");
/// assert_eq!(n.marked().to_string(), "part.nc:12:1: the blank is the stock the program declares (‹blank_diameter› overrides)");
/// ```
impl fmt::Display for Note {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let message = crate::ground::error::Audience::Api.words(&self.message);
        match &self.place {
            Some(p) => write!(f, "{}:{}:{}: {message}", p.file, p.line, p.column),
            None => f.write_str(&message),
        }
    }
}

/// A note with its arguments still marked (`‹blank_diameter›`), for the layer that renders
/// them for its reader: the command line's flag, the page's field, the API's key.
#[derive(Clone, Copy, Debug)]
pub struct Marked<'a>(&'a Note);

impl Note {
    /// This note with its arguments still marked, for the reports ([`Marked`]).
    pub fn marked(&self) -> Marked<'_> {
        Marked(self)
    }
}

impl fmt::Display for Marked<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.0.place {
            Some(p) => write!(f, "{}:{}:{}: {}", p.file, p.line, p.column, self.0.message),
            None => f.write_str(&self.0.message),
        }
    }
}

/// A report's document is rendered for its reader after it is written: the JSON carries the
/// marks.
impl Serialize for Note {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(&self.marked())
    }
}

/// Notes in the order they were first given, each once: a set beside the list keeps adding
/// linear in their number.
#[derive(Clone, Debug, Default)]
pub struct Notes {
    list: Vec<Note>,
    seen: std::collections::HashSet<Note>,
}

impl Notes {
    /// Adds `n` unless the same note was given before.
    pub fn push(&mut self, n: Note) {
        if !self.seen.contains(&n) {
            self.seen.insert(n.clone());
            self.list.push(n);
        }
    }

    /// The first note of `kind`.
    pub fn find(&self, kind: NoteKind) -> Option<&Note> {
        self.list.iter().find(|n| n.kind == kind)
    }

    /// The notes in order.
    pub fn into_vec(self) -> Vec<Note> {
        self.list
    }
}
