//! The comments of a program, as its dialect writes them: where programs name their threads
//! (`(M10X1.5 THREAD)`, `; THREAD M24x2`, `[1/2-13 UNC-2A]`).
//!
//! The lexer drops comments; this scan reads them from the text alone, line by line, so that a
//! comment the interpreter never reaches (a skipped branch, a subprogram) is still read: it names
//! the thread of the operations below it whether or not its block runs.

use super::Dialect;

/// One comment: its text (without its delimiters) and where it starts.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Comment {
    /// 1-based line.
    pub line: usize,
    /// 1-based column of the first character inside the delimiters.
    pub column: usize,
    /// The text inside the delimiters, as written.
    pub text: String,
}

/// Every comment of `text` in `dialect`, in order. An unclosed `(` or `[` runs to the line's
/// end (the lexer refuses such a line where it is read).
///
/// ```
/// use threadcheck::{comments, Dialect};
/// let c = comments("G0 X30 (M24X2 THREAD)\nG76 P010060 Q100 R0.05 ; not a comment here\n", Dialect::Fanuc);
/// assert_eq!(c.len(), 1);
/// assert_eq!((c[0].line, c[0].column, c[0].text.as_str()), (1, 9, "M24X2 THREAD"));
/// let s = comments("N10 G0 X30 ; THREAD M24x2\n", Dialect::Sinumerik);
/// assert_eq!(s[0].text, " THREAD M24x2");
/// ```
pub fn comments(text: &str, dialect: Dialect) -> Vec<Comment> {
    let f = dialect.facts().comments;
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if dialect == Dialect::Klartext {
            klartext_names(line, i + 1, &mut out);
        }
        let chars: Vec<char> = line.chars().collect();
        let mut k = 0;
        while k < chars.len() {
            let close = match chars[k] {
                '(' if f.parentheses => Some(')'),
                '[' if f.brackets => Some(']'),
                ';' if f.semicolon => None,
                _ => {
                    k += 1;
                    continue;
                }
            };
            let start = k + 1;
            let end = match close {
                Some(c) => chars[start..].iter().position(|&x| x == c).map_or(chars.len(), |p| start + p),
                None => chars.len(),
            };
            out.push(Comment { line: i + 1, column: start + 1, text: chars[start..end].iter().collect() });
            k = end + 1;
        }
    }
    out
}

/// What a Klartext line says in words besides its `;` comment, read as comments are (issue 62:
/// CAM posts name their operations and tools so): a `* - TAP M8` line (a section's title), and
/// the name of a tool called by name, `TOOL CALL "TAP M8X1.25" Z S500`.
///
/// ```
/// use threadcheck::{comments, Dialect};
/// let c = comments("17 * - DRILL 6.8\n18 TOOL CALL \"TAP M8X1.25\" Z S500\n", Dialect::Klartext);
/// let texts: Vec<&str> = c.iter().map(|c| c.text.as_str()).collect();
/// assert_eq!(texts, ["DRILL 6.8", "TAP M8X1.25"]);
/// assert_eq!((c[1].line, c[1].column), (2, 15));
/// ```
fn klartext_names(line: &str, ln: usize, out: &mut Vec<Comment>) {
    let code = line.split(';').next().unwrap_or("");
    let t = code.trim_start();
    let body = t.trim_start_matches(|c: char| c.is_ascii_digit()).trim_start();
    let at = |sub: &str| code.len() - sub.len();
    if let Some(rest) = body.strip_prefix('*') {
        let title = rest.trim_start().trim_start_matches('-').trim_start();
        if !title.is_empty() {
            out.push(Comment {
                line: ln,
                column: code[..at(title)].chars().count() + 1,
                text: title.trim_end().to_string(),
            });
        }
        return;
    }
    if let Some(rest) = body.strip_prefix("TOOL CALL") {
        let r = rest.trim_start();
        if let Some(name) = r.strip_prefix('"') {
            if let Some(end) = name.find('"') {
                out.push(Comment {
                    line: ln,
                    column: code[..at(name)].chars().count() + 1,
                    text: name[..end].to_string(),
                });
            }
        }
    }
}
