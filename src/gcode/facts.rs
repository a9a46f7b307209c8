//! A dialect's facts in one table (issue 60, after rs274ngc's tables): what the reader, the
//! lexer, the comment reader and the messages ask of a dialect family, one row each. A new
//! dialect is a row here (the compiler asks for it in [`Dialect::facts`]), its line in the rules
//! table of `mod.rs` and its module; nothing else names every dialect.

use super::expr::Syntax;
use super::Dialect;

/// The comment forms of a dialect: `(…)` on the line, `;` to the line's end, `[…]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct CommentForms {
    /// `(…)`.
    pub parentheses: bool,
    /// `;` to the line's end.
    pub semicolon: bool,
    /// `[…]`.
    pub brackets: bool,
}

/// What threadcheck knows of a dialect family.
#[derive(Clone, Copy, Debug)]
pub struct Facts {
    /// The command-line name (`--dialect`).
    pub name: &'static str,
    /// The file extensions that name it (lower case, without the dot).
    pub extensions: &'static [&'static str],
    /// The G codes that set inch and mm units (`None`: the unit is the program header's or a
    /// machine setting).
    pub unit_codes: Option<(u32, u32)>,
    /// Read as the Fanuc model with its G-code systems A, B and C (`--gcode-system`).
    pub fanuc_family: bool,
    /// Read with Fanuc's codes (G-code system A on a lathe, the M-series' on a machining
    /// centre: U and W incremental on a lathe, the wear offset an X on the diameter): the Fanuc
    /// family and Haas.
    pub fanuc_codes: bool,
    /// What threading it reads, for messages.
    pub threading_words: &'static str,
    /// Its comment forms.
    pub(crate) comments: CommentForms,
    /// Its expressions' syntax.
    pub(crate) syntax: Syntax,
    /// `;` ends the line's code (LinuxCNC's comment), else it ends a block.
    pub(crate) semicolon_ends_line: bool,
    /// O-words are flow control (LinuxCNC's `o100 sub`), else program numbers.
    pub(crate) o_words_are_flow: bool,
    /// Fanuc custom macro B's `GOTO n` and `IF [..] GOTO/THEN` keywords.
    pub(crate) macro_b_keywords: bool,
}

/// `(…)` only: `;` ends a block there.
const PARENTHESES: CommentForms = CommentForms { parentheses: true, semicolon: false, brackets: false };
/// `;` to the line's end only.
const SEMICOLON: CommentForms = CommentForms { parentheses: false, semicolon: true, brackets: false };

/// The Fanuc model's row: Fanuc, and the controls read as it.
const FANUC_MODEL: Facts = Facts {
    name: "fanuc",
    extensions: &[],
    unit_codes: Some((20, 21)),
    fanuc_family: true,
    fanuc_codes: true,
    threading_words: "G32, G92 and G76",
    comments: PARENTHESES,
    syntax: Syntax::MacroB,
    semicolon_ends_line: false,
    o_words_are_flow: false,
    macro_b_keywords: true,
};

impl Dialect {
    /// Its facts: the one table every wing reads.
    ///
    /// ```
    /// use threadcheck::Dialect;
    /// assert_eq!(Dialect::Okuma.facts().extensions, &["min", "ssb", "sub"]);
    /// assert!(Dialect::Mazak.facts().fanuc_family);
    /// ```
    pub fn facts(self) -> &'static Facts {
        match self {
            Dialect::Fanuc => &FANUC_MODEL,
            Dialect::Haas => {
                &Facts { name: "haas", fanuc_family: false, threading_words: "G32, G92 and G76", ..FANUC_MODEL }
            }
            // Sinumerik: `;` to the line's end (parentheses are expressions and calls).
            Dialect::Sinumerik => &Facts {
                name: "sinumerik",
                extensions: &["mpf", "spf"],
                unit_codes: Some((70, 71)),
                fanuc_family: false,
                fanuc_codes: false,
                threading_words: "G33, CYCLE97, L96 and L97",
                comments: SEMICOLON,
                syntax: Syntax::Sinumerik,
                semicolon_ends_line: false,
                o_words_are_flow: false,
                macro_b_keywords: false,
            },
            // LinuxCNC: `(…)` and `;` to the line's end.
            Dialect::LinuxCnc => &Facts {
                name: "linuxcnc",
                extensions: &["ngc"],
                unit_codes: Some((20, 21)),
                fanuc_family: false,
                fanuc_codes: false,
                threading_words: "G33 and G76",
                comments: CommentForms { parentheses: true, semicolon: true, brackets: false },
                syntax: Syntax::LinuxCnc,
                semicolon_ends_line: true,
                o_words_are_flow: true,
                macro_b_keywords: false,
            },
            Dialect::Dyna => &Facts {
                name: "dyna",
                fanuc_family: false,
                fanuc_codes: false,
                threading_words: "none: the Dyna THREAD cycle is not supported",
                syntax: Syntax::Dyna,
                ..FANUC_MODEL
            },
            // OSP main programs and subprograms.
            Dialect::Okuma => &Facts {
                name: "okuma",
                extensions: &["min", "ssb", "sub"],
                fanuc_family: false,
                fanuc_codes: false,
                threading_words: "G33 and the compound cycles G71 and G72",
                ..FANUC_MODEL
            },
            // Reported Fanuc-compatible: the Fanuc model, its rules and G-code systems.
            Dialect::Mitsubishi => {
                &Facts { name: "mitsubishi", threading_words: "G32, G92 and G76 (the Fanuc model)", ..FANUC_MODEL }
            }
            Dialect::Mazak => {
                &Facts { name: "mazak", threading_words: "G32, G92 and G76 (the Fanuc model)", ..FANUC_MODEL }
            }
            // Heidenhain DIN: `[…]`, and `(…)` as its Fanuc-like blocks read them; no unit codes
            // (G20 and G21 define the blank there).
            Dialect::Heidenhain => &Facts {
                name: "heidenhain",
                unit_codes: None,
                fanuc_family: false,
                fanuc_codes: false,
                threading_words: "G31 and G33",
                comments: CommentForms { parentheses: true, semicolon: false, brackets: true },
                ..FANUC_MODEL
            },
            // TNC conversational programs: `;` to the line's end (the cycles' parameter names are
            // read too, and name no thread); the unit is BEGIN PGM's.
            Dialect::Klartext => &Facts {
                name: "klartext",
                extensions: &["h"],
                unit_codes: None,
                fanuc_family: false,
                fanuc_codes: false,
                threading_words: "turned threads: a Klartext program taps (cycles 206, 207, 209) and mills threads (262 to 265, 267, CP helices) instead",
                comments: SEMICOLON,
                ..FANUC_MODEL
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The table holds what the matches it replaced said (each row checked by hand against the
    /// old `name`, `by_extension`, `unit_codes`, `fanuc_family`, comment forms, syntax and
    /// lexer rules), and no two dialects share a name or an extension.
    #[test]
    fn every_dialect_has_one_row_and_its_own_name_and_extensions() {
        let mut names = std::collections::HashSet::new();
        let mut exts = std::collections::HashSet::new();
        for d in Dialect::ALL {
            let f = d.facts();
            assert!(names.insert(f.name), "{} twice", f.name);
            for e in f.extensions {
                assert!(exts.insert(*e), "extension {e} twice");
                // A folder's programs: every dialect's own extension, but Klartext's `.h`, a
                // C header's too, taken only where it opens a Klartext program.
                assert!(
                    super::super::PROGRAM_EXTENSIONS.contains(e) || *e == "h",
                    "{e} is not among the extensions a folder's programs have"
                );
            }
        }
        let f = Dialect::LinuxCnc.facts();
        assert!(f.semicolon_ends_line && f.o_words_are_flow && !f.macro_b_keywords);
        assert_eq!(Dialect::Dyna.facts().syntax, Syntax::Dyna);
        assert!(Dialect::Dyna.facts().macro_b_keywords);
        assert_eq!(Dialect::Sinumerik.facts().unit_codes, Some((70, 71)));
        assert_eq!(Dialect::Klartext.facts().syntax, Syntax::MacroB);
        assert!(Dialect::Heidenhain.facts().comments.brackets);
        assert!(!Dialect::Haas.facts().fanuc_family && Dialect::Mitsubishi.facts().fanuc_family);
        let codes: Vec<Dialect> = Dialect::ALL.into_iter().filter(|d| d.facts().fanuc_codes).collect();
        assert_eq!(codes, [Dialect::Fanuc, Dialect::Haas, Dialect::Mitsubishi, Dialect::Mazak]);
    }
}
