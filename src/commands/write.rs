//! The one writer: a run's documents to where the command line's flags sent them, every file
//! of the run together, all or none, none of them a file the run read.

use super::{Document, Outputs};
use crate::{Audience, Error};
use std::path::PathBuf;

/// Where a document goes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Dest {
    /// Standard output, instead of the text.
    Stdout,
    /// A file, written atomically.
    File(PathBuf),
}

impl Dest {
    /// `-` for standard output, else the path.
    pub fn of(word: &str) -> Dest {
        if word == "-" {
            Dest::Stdout
        } else {
            Dest::File(PathBuf::from(word))
        }
    }

    /// The destinations of a command's documents: `words` are those given as `FILE|-`, `files`
    /// those given as a path.
    pub(crate) fn list<'a>(
        words: impl IntoIterator<Item = (Document, &'a Option<String>)>,
        files: impl IntoIterator<Item = (Document, &'a Option<PathBuf>)>,
    ) -> Vec<(Document, Dest)> {
        let mut v: Vec<(Document, Dest)> =
            words.into_iter().filter_map(|(d, w)| w.as_deref().map(|w| (d, Dest::of(w)))).collect();
        v.extend(files.into_iter().filter_map(|(d, p)| p.clone().map(|p| (d, Dest::File(p)))));
        v
    }
}

/// What the run shows on the terminal.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Shown {
    /// Standard output.
    pub stdout: String,
    /// Standard error.
    pub stderr: String,
}

/// Writes `out`'s documents to `dests`, and its own files, together (all or none, no input
/// replaced), and returns what the terminal shows: the document sent to standard output, else
/// the text. Messages and documents name arguments for `reader`.
pub fn deliver(out: &Outputs, dests: &[(Document, Dest)], reader: Audience) -> Result<Shown, Error> {
    let on_stdout: Vec<Document> =
        dests.iter().filter(|(_, d)| *d == Dest::Stdout).map(|(k, _)| *k).collect();
    if let [a, b, ..] = on_stdout.as_slice() {
        return Err(Error::Input(reader.words(&format!(
            "‹{}› - and ‹{}› - both want standard output: write one to a file",
            a.name(),
            b.name()
        ))));
    }
    let shown = on_stdout.first().copied().unwrap_or(Document::Text);
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    for (d, dest) in dests {
        if let Dest::File(p) = dest {
            let text = out.document(*d).ok_or_else(|| {
                Error::Input(format!("{} made no {} document for this input", p.display(), d.name()))
            })?;
            files.push((p.clone(), reader.words(text).into_bytes()));
        }
    }
    files.extend(out.files.iter().cloned());
    crate::report::output::refuse_inputs(&files, &out.inputs)?;
    crate::report::output::write_all_atomic(&files)?;
    let mut stderr = match (shown, &out.aside) {
        (Document::Json, Some(a)) => a.clone(),
        _ => String::new(),
    };
    stderr.push_str(&written(&files));
    Ok(Shown { stdout: reader.words(out.document(shown).unwrap_or_default()), stderr })
}

/// The files a run wrote, in words for standard error (standard output keeps the document
/// alone): each one with its size, or, past five, how many and the folder that holds them.
fn written(files: &[(PathBuf, Vec<u8>)]) -> String {
    use crate::ground::fmt::path_name;
    if files.len() <= 5 {
        return files.iter().map(|(p, b)| format!("wrote {} ({} bytes)\n", path_name(p), b.len())).collect();
    }
    let bytes: usize = files.iter().map(|(_, b)| b.len()).sum();
    let folder = files[0].0.parent().filter(|d| files.iter().all(|(p, _)| p.parent() == Some(*d)));
    match folder {
        Some(d) if !d.as_os_str().is_empty() => {
            format!("wrote {} files in {} ({bytes} bytes)\n", files.len(), path_name(d))
        }
        _ => format!("wrote {} files ({bytes} bytes)\n", files.len()),
    }
}
