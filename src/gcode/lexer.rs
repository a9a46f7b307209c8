//! Splits a program into blocks of words, per dialect, keeping line and column of every word and
//! whether each number had a decimal point (Fanuc reads some words in least-input increments).

use super::Dialect;

/// A value as written.
#[derive(Clone, Debug, PartialEq)]
pub enum Val {
    /// A number, and whether it was written with a decimal point.
    Num {
        /// The value.
        v: f64,
        /// Written with a decimal point.
        point: bool,
    },
    /// An expression after `=` (Sinumerik), evaluated when the block runs.
    Expr(String),
    /// Arguments of a call such as `CYCLE97(1.5,,0,…)`: each raw text (None where empty) and
    /// its column.
    Args(Vec<(Option<String>, usize)>),
    /// A bare name (`M17` is `M` with a number; `DIAMON` is a bare name).
    Bare,
}

/// One word: an address (uppercase) and its value, at a column (1-based, characters).
#[derive(Clone, Debug, PartialEq)]
pub struct Word {
    /// Address: `X`, `G`, `R3` (an R-parameter target), `CYCLE97`, `SF`, …
    pub name: String,
    /// The value.
    pub val: Val,
    /// 1-based column of the word's first character.
    pub col: usize,
    /// The word as written (`P1.950`), for messages.
    pub text: String,
}

impl Word {
    /// The number, if it is one.
    pub fn num(&self) -> Option<f64> {
        match self.val {
            Val::Num { v, .. } => Some(v),
            _ => None,
        }
    }
}

/// A block: its words and the 1-based line it stands on.
#[derive(Clone, Debug, PartialEq)]
pub struct Block {
    /// 1-based line.
    pub line: usize,
    /// Column of the first word.
    pub col: usize,
    /// The words in order.
    pub words: Vec<Word>,
    /// A Sinumerik subprogram header (`%_N_L9_SPF`, or a line holding only `L9` after the main
    /// program's end) names the subprogram that starts here.
    pub label: Option<String>,
}

/// A lexing error: line, column, message.
pub type LexError = (usize, usize, String);

/// Splits `text` into blocks. A UTF-8 byte-order mark is skipped; CR LF line ends are accepted.
pub fn lex(text: &str, dialect: Dialect) -> Result<Vec<Block>, LexError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut blocks = Vec::new();
    for (i, raw) in text.split('\n').enumerate() {
        let line = raw.strip_suffix('\r').unwrap_or(raw);
        lex_line(line, i + 1, dialect, &mut blocks)?;
    }
    Ok(blocks)
}

fn is_number_start(c: Option<&char>) -> bool {
    matches!(c, Some(c) if c.is_ascii_digit() || *c == '.' || *c == '-' || *c == '+')
}

fn lex_line(line: &str, ln: usize, dialect: Dialect, out: &mut Vec<Block>) -> Result<(), LexError> {
    let chars: Vec<char> = line.chars().collect();
    let trimmed = line.trim();
    if dialect == Dialect::Sinumerik {
        // `%_N_L9_SPF` starts subprogram L9 (file headers of a listing).
        if let Some(rest) = trimmed.strip_prefix("%_N_") {
            let name = rest.trim_end_matches("_SPF").trim_end_matches("_MPF").to_ascii_uppercase();
            let label = rest.ends_with("_SPF").then_some(name);
            out.push(Block { line: ln, col: 1, words: Vec::new(), label });
            return Ok(());
        }
    }
    let mut block = Block { line: ln, col: 1, words: Vec::new(), label: None };
    let mut i = 0;
    let push = |b: &mut Block, out: &mut Vec<Block>| {
        if !b.words.is_empty() {
            out.push(std::mem::replace(b, Block { line: ln, col: 1, words: Vec::new(), label: None }));
        }
    };
    while i < chars.len() {
        let c = chars[i];
        let col = i + 1;
        match c {
            ' ' | '\t' => i += 1,
            '(' => {
                let close = chars[i..].iter().position(|&x| x == ')').ok_or((
                    ln,
                    col,
                    "comment '(' is not closed on this line".to_string(),
                ))?;
                i += close + 1;
            }
            ';' => {
                if dialect == Dialect::Fanuc {
                    // End of block (EOB) as Fanuc listings write it.
                    push(&mut block, out);
                    i += 1;
                } else {
                    break;
                }
            }
            '%' => {
                if block.words.is_empty() {
                    break;
                }
                return Err((ln, col, "'%' inside a block".into()));
            }
            '/' if block.words.is_empty() => i += 1,
            '#' | '[' => {
                return Err((
                    ln,
                    col,
                    format!(
                        "'{c}': parameters and expressions are not supported in the {} dialect",
                        dialect.name()
                    ),
                ));
            }
            c if c.is_ascii_alphabetic() || c == '_' => {
                let start = i;
                while i < chars.len() && (chars[i].is_ascii_alphabetic() || chars[i] == '_') {
                    i += 1;
                }
                let letters: String = chars[start..i].iter().collect::<String>().to_ascii_uppercase();
                if block.words.is_empty() {
                    block.col = col;
                }
                // Sinumerik `LF` written at the end of a listing line is the block end.
                if dialect == Dialect::Sinumerik
                    && letters == "LF"
                    && chars[i..].iter().all(|c| c.is_whitespace())
                {
                    break;
                }
                let word = if dialect == Dialect::Sinumerik {
                    let mut w = sinumerik_word(&chars, &mut i, letters, col, ln)?;
                    w.text = chars[start..i].iter().collect();
                    w
                } else {
                    if letters.len() > 1 {
                        return Err((
                            ln,
                            col,
                            format!("'{letters}' is not a word of the {} dialect", dialect.name()),
                        ));
                    }
                    let (v, point) = number(&chars, &mut i, ln, &letters)?;
                    Word {
                        name: letters,
                        val: Val::Num { v, point },
                        col,
                        text: chars[start..i].iter().collect(),
                    }
                };
                block.words.push(word);
            }
            _ => return Err((ln, col, format!("unexpected character '{c}'"))),
        }
    }
    // A Sinumerik subprogram in the same listing starts with a line holding only its name.
    if dialect == Dialect::Sinumerik
        && block.words.len() == 1
        && line.split(';').next().is_some_and(|s| {
            let t = s.trim().trim_end_matches("LF").trim();
            t.len() > 1 && t.starts_with(['L', 'l']) && t[1..].chars().all(|c| c.is_ascii_digit())
        })
    {
        if let Some(w) = block.words.first() {
            if w.name == "L" {
                block.label = Some(format!("L{}", w.num().unwrap_or(0.0) as i64));
            }
        }
    }
    push(&mut block, out);
    Ok(())
}

/// A signed decimal number at `chars[*i]`; a decimal comma is an error that says how to write it.
fn number(chars: &[char], i: &mut usize, ln: usize, name: &str) -> Result<(f64, bool), LexError> {
    let start = *i;
    let col = start + 1;
    if !is_number_start(chars.get(*i)) {
        return Err((ln, col.max(1), format!("word {name} has no number")));
    }
    if matches!(chars[*i], '-' | '+') {
        *i += 1;
    }
    let mut point = false;
    let mut digits = 0;
    while *i < chars.len() && (chars[*i].is_ascii_digit() || (chars[*i] == '.' && !point)) {
        if chars[*i] == '.' {
            point = true;
        } else {
            digits += 1;
        }
        *i += 1;
    }
    let text: String = chars[start..*i].iter().collect();
    if *i + 1 < chars.len() && chars[*i] == ',' && chars[*i + 1].is_ascii_digit() {
        let mut j = *i + 1;
        while j < chars.len() && chars[j].is_ascii_digit() {
            j += 1;
        }
        let frac: String = chars[*i + 1..j].iter().collect();
        return Err((
            ln,
            col - name.len(),
            format!("decimal comma in {name}{text},{frac}: write {name}{text}.{frac}"),
        ));
    }
    if digits == 0 {
        return Err((ln, col, format!("word {name} has no number")));
    }
    // `X1e309` would otherwise read as X1 and an E word: G-code has no exponents.
    if *i + 1 < chars.len()
        && matches!(chars[*i], 'e' | 'E')
        && (chars[*i + 1].is_ascii_digit()
            || (matches!(chars[*i + 1], '+' | '-') && chars.get(*i + 2).is_some_and(|c| c.is_ascii_digit())))
    {
        let mut j = *i + 1;
        while j < chars.len() && (chars[j].is_ascii_alphanumeric() || matches!(chars[j], '+' | '-' | '.')) {
            j += 1;
        }
        let all: String = chars[start..j].iter().collect();
        return Err((
            ln,
            col - name.len(),
            format!("{name}{all}: G-code numbers have no exponent; write the value in full"),
        ));
    }
    let v: f64 = text.parse().map_err(|_| (ln, col, format!("'{name}{text}' is not a number")))?;
    if !v.is_finite() {
        return Err((ln, col, format!("'{name}{text}' is not a finite number")));
    }
    Ok((v, point))
}

fn skip_spaces(chars: &[char], i: &mut usize) {
    while *i < chars.len() && (chars[*i] == ' ' || chars[*i] == '\t') {
        *i += 1;
    }
}

/// A Sinumerik word: `X-20`, `G33`, `R3=R3-0.05`, `X=R3`, `SF=90`, `CYCLE97(…)`, `DIAMON`, `L9`.
fn sinumerik_word(
    chars: &[char],
    i: &mut usize,
    letters: String,
    col: usize,
    ln: usize,
) -> Result<Word, LexError> {
    // Digits right after the letters: the value of a one-letter address (G33, L9, R3), part of
    // the name of a longer one (CYCLE97).
    let dstart = *i;
    while *i < chars.len() && chars[*i].is_ascii_digit() {
        *i += 1;
    }
    let digits: String = chars[dstart..*i].iter().collect();
    let mut name = letters.clone();
    let mut after = *i;
    skip_spaces(chars, &mut after);
    let next = chars.get(after).copied();
    if letters.len() == 1 && !digits.is_empty() && next != Some('=') {
        // `G33`, `L9`, `M17`, `X10` (a one-letter address and a whole number), maybe with a
        // fraction: `X10.5`.
        *i = dstart;
        let (v, point) = number(chars, i, ln, &letters)?;
        return Ok(Word { name, val: Val::Num { v, point }, col, text: String::new() });
    }
    name.push_str(&digits);
    match next {
        Some('=') => {
            *i = after + 1;
            skip_spaces(chars, i);
            let start = *i;
            expression_end(chars, i);
            let expr: String = chars[start..*i].iter().collect::<String>().trim().to_string();
            if expr.is_empty() {
                return Err((ln, start + 1, format!("{name}= has no value")));
            }
            Ok(Word { name, val: Val::Expr(expr), col, text: String::new() })
        }
        Some('(') => {
            let close = chars[after..].iter().position(|&c| c == ')').ok_or((
                ln,
                after + 1,
                format!("{name}( is not closed"),
            ))?;
            let inner: String = chars[after + 1..after + close].iter().collect();
            let mut args = Vec::new();
            let mut c0 = after + 2;
            for part in inner.split(',') {
                let t = part.trim();
                args.push(((!t.is_empty()).then(|| t.to_string()), c0));
                c0 += part.chars().count() + 1;
            }
            *i = after + close + 1;
            Ok(Word { name, val: Val::Args(args), col, text: String::new() })
        }
        _ if letters.len() == 1 && digits.is_empty() && is_number_start(chars.get(*i)) => {
            let (v, point) = number(chars, i, ln, &letters)?;
            Ok(Word { name, val: Val::Num { v, point }, col, text: String::new() })
        }
        _ => Ok(Word { name, val: Val::Bare, col, text: String::new() }),
    }
}

/// Advances over an expression: operands (numbers, names such as R3, calls) joined by binary
/// operators; stops at the first operand not followed by an operator.
fn expression_end(chars: &[char], i: &mut usize) {
    loop {
        skip_spaces(chars, i);
        // Unary signs.
        while *i < chars.len() && matches!(chars[*i], '-' | '+') {
            *i += 1;
            skip_spaces(chars, i);
        }
        if *i >= chars.len() {
            return;
        }
        if chars[*i] == '(' {
            let mut depth = 0;
            while *i < chars.len() {
                match chars[*i] {
                    '(' => depth += 1,
                    ')' => {
                        depth -= 1;
                        if depth == 0 {
                            *i += 1;
                            break;
                        }
                    }
                    _ => {}
                }
                *i += 1;
            }
        } else if chars[*i].is_ascii_alphanumeric() || chars[*i] == '.' {
            while *i < chars.len()
                && (chars[*i].is_ascii_alphanumeric() || chars[*i] == '.' || chars[*i] == '_')
            {
                *i += 1;
            }
            if *i < chars.len() && chars[*i] == '(' {
                continue;
            }
        } else {
            return;
        }
        let mut j = *i;
        skip_spaces(chars, &mut j);
        if j < chars.len() && matches!(chars[j], '+' | '-' | '*' | '/') {
            *i = j + 1;
        } else {
            return;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fanuc_blocks_words_and_points() {
        let b = lex(
            "%\nO1000 (THREAD)\nN10 G76 P011060 Q100 R0.05;\nN20 G76 X8.16 Z-20. P920 Q350 F1.5;\n%",
            Dialect::Fanuc,
        )
        .unwrap();
        assert_eq!(b.len(), 3);
        assert_eq!(b[1].line, 3);
        // Sequence numbers stay in the block as N words.
        let p = &b[1].words[2];
        assert_eq!((p.name.as_str(), p.val.clone()), ("P", Val::Num { v: 11060.0, point: false }));
        assert_eq!(b[2].words[2].val, Val::Num { v: 8.16, point: true });
        assert_eq!(b[2].words[2].col, 9);
    }

    #[test]
    fn decimal_comma_says_how_to_write_it() {
        let e = lex("G32 Z-39,65 F1.5", Dialect::Fanuc).unwrap_err();
        assert_eq!((e.0, e.1), (1, 5));
        assert!(e.2.contains("write Z-39.65"), "{}", e.2);
    }

    #[test]
    fn sinumerik_assignments_calls_and_lf() {
        let b = lex(
            "N10 R3 = R3 - 0.05 LF\nN20 G0 X=R3 Z2 ; comment\nL9 P33\nCYCLE97(1.5,,0,-30,20,20,3,2,0.92)",
            Dialect::Sinumerik,
        )
        .unwrap();
        assert_eq!(b[0].words[1].val, Val::Expr("R3 - 0.05".into()));
        assert_eq!(b[1].words[2].name, "X");
        assert_eq!(b[1].words[2].val, Val::Expr("R3".into()));
        assert_eq!(b[1].words[3].num(), Some(2.0));
        assert_eq!(b[2].words[0].name, "L");
        match &b[3].words[0].val {
            Val::Args(a) => assert_eq!((a.len(), a[1].0.clone()), (9, None)),
            v => panic!("{v:?}"),
        }
    }

    #[test]
    fn crlf_and_bom_keep_positions() {
        let b = lex("\u{feff}G0 X10\r\nG32 Z-5 F1\r\n", Dialect::Fanuc).unwrap();
        assert_eq!(b[1].line, 2);
        assert_eq!(b[1].words[1].col, 5);
        let e = lex("\u{feff}G0 X10\r\nG32 Z-5,5 F1\r\n", Dialect::Fanuc).unwrap_err();
        assert_eq!((e.0, e.1), (2, 5));
    }
}
