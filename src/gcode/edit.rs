//! Rewriting words of a program in place: only the words named change, every other byte
//! (comments, blanks, line ends, a BOM) is kept.

use crate::Error;

/// One word to rewrite: at `line:column` (1-based, columns in characters as the lexer counts
/// them) the program has `old` (blanks inside it in the source are allowed, as the lexer allows
/// them); it becomes `new`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct WordEdit {
    /// Line, from 1.
    pub line: usize,
    /// Column of the word's first character, from 1.
    pub column: usize,
    /// The word as the lexer read it (`X19.462`, `K.045`, `1.534`).
    pub old: String,
    /// What replaces it.
    pub new: String,
}

/// The program `text` with `edits` applied; an edit whose word is not where it says is an
/// error naming the place (the program changed since it was read).
///
/// ```
/// use threadcheck::{rewrite_words, WordEdit};
/// let p = "G0 X22 Z5\r\nG92 X 19.46 Z-20 F1.5 (last pass)\r\n";
/// let e = WordEdit { line: 2, column: 5, old: "X19.46".into(), new: "X19.452".into() };
/// assert_eq!(rewrite_words(p, "p.nc", &[e])?, "G0 X22 Z5\r\nG92 X19.452 Z-20 F1.5 (last pass)\r\n");
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn rewrite_words(text: &str, file: &str, edits: &[WordEdit]) -> Result<String, Error> {
    let mut lines: Vec<String> = text.split('\n').map(str::to_string).collect();
    let mut sorted: Vec<&WordEdit> = edits.iter().collect();
    // Right to left within a line, so earlier columns stay where they are.
    sorted.sort_by_key(|e| (e.line, std::cmp::Reverse(e.column)));
    sorted.dedup();
    for e in sorted {
        let misplaced = || Error::Program {
            file: file.to_string(),
            line: e.line,
            column: e.column,
            message: format!("expected the word {} here to rewrite it", e.old),
        };
        let line = lines.get_mut(e.line.wrapping_sub(1)).ok_or_else(misplaced)?;
        let chars: Vec<char> = line.chars().collect();
        let start = e.column.checked_sub(1).ok_or_else(misplaced)?;
        let mut i = start;
        for want in e.old.chars() {
            while i < chars.len() && chars[i].is_whitespace() && !want.is_whitespace() && i > start {
                i += 1;
            }
            match chars.get(i) {
                Some(c) if c.eq_ignore_ascii_case(&want) => i += 1,
                _ => return Err(misplaced()),
            }
        }
        let mut out: String = chars[..start].iter().collect();
        out.push_str(&e.new);
        out.extend(&chars[i..]);
        *line = out;
    }
    Ok(lines.join("\n"))
}
