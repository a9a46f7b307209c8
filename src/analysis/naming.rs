//! The thread a program names: a designation in a comment near the operation (as shops write
//! them: `(M10X1.5 THREAD)`, `; THREAD M24x2`, `(1/2-13 UNC-2A)`, `(TAP M8)`, `(1/2" BSP)`),
//! else the standard size whose lead and diameter the operation cuts.
//!
//! A comment is read by the designation parser itself: the longest run of one to three of its
//! words that parses, at the first word where one does, after the spellings shops use and the
//! parser does not (a decimal comma, an inch mark, `×`, `BSP 1/2`, `LH` without its hyphen,
//! a class in capitals) are put into its form. A bare `M8` counts only in a comment that also
//! says thread or tap (in one of the words listed in [`THREAD_WORDS`]): `(COOLANT M8)` names
//! no thread.

use crate::gcode::{Comment, ProgramUnits};
use crate::standards::designation::{parse_designation, Designation, ParseOptions};
use crate::standards::{ThreadForm, ThreadKind, MM_PER_INCH};
use crate::Error;
use serde::Serialize;

/// Where an operation's designation came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum DesignationFrom {
    /// Given by the user (`--thread`).
    Given,
    /// A comment of the program.
    Comment,
    /// The tool table (a tap's designation).
    Tool,
    /// The standard size of the lead and diameter the operation cuts.
    Inferred,
}

impl DesignationFrom {
    /// The word the reports and the JSON use.
    pub fn name(self) -> &'static str {
        match self {
            DesignationFrom::Given => "given",
            DesignationFrom::Comment => "comment",
            DesignationFrom::Tool => "tool",
            DesignationFrom::Inferred => "inferred",
        }
    }
}

/// An operation's designation (with the class it is checked against) and where it came from.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Named {
    /// The designation with its class, parsed (its text in the parser's form).
    #[serde(serialize_with = "text_of")]
    pub designation: Designation,
    /// Where it came from.
    pub from: DesignationFrom,
    /// The line of the comment (or of the operation, for an inferred one); `None` when given.
    pub line: Option<usize>,
    /// How it was read, for the notes (empty when given).
    #[serde(skip)]
    pub why: String,
}

/// A designation written as its text.
fn text_of<S: serde::Serializer>(d: &Designation, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(&d.text)
}

impl Named {
    /// A designation the user gave.
    pub fn given(designation: Designation) -> Named {
        Named { designation, from: DesignationFrom::Given, line: None, why: String::new() }
    }
}

/// Words that make a bare metric size (`M8`) in a comment a thread: English, German, French,
/// Spanish, Italian, Portuguese and Russian shop words for thread and tap.
pub const THREAD_WORDS: &[&str] = &[
    "THREAD",
    "THREADING",
    "THD",
    "THRD",
    "THR",
    "TAP",
    "TAPPING",
    "TAPPED",
    "GEWINDE",
    "GEW",
    "GEWINDEBOHRER",
    "GEWINDEFORMER",
    "GEWINDEFURCHER",
    "FILETAGE",
    "FILET",
    "TARAUD",
    "TARAUDAGE",
    "ROSCA",
    "ROSCADO",
    "MACHO",
    "FILETTO",
    "FILETTATURA",
    "MASCHIO",
    "РЕЗЬБА",
    "МЕТЧИК",
];

/// A designation found in a comment: in the parser's form, and the (0-based, in characters)
/// offset of its first word in the comment.
#[derive(Clone, Debug, PartialEq)]
pub struct Found {
    /// The designation as the parser reads it.
    pub text: String,
    /// Its parse.
    pub designation: Designation,
    /// Where its first word starts in the comment, characters.
    pub offset: usize,
}

/// The first designation a comment names, if any.
///
/// ```
/// use threadcheck::{designation_in_comment, ParseOptions};
/// let find = |c: &str| designation_in_comment(c, ParseOptions::default());
/// assert_eq!(find("M10X1.5 THREAD").map(|f| f.text), Some("M10X1.5".to_string()));
/// assert_eq!(find(" THREAD M24x2").map(|f| f.offset), Some(8));
/// assert_eq!(find("1/2\"-13 UNC-2A").map(|f| f.text), Some("1/2-13 UNC-2A".to_string()));
/// assert_eq!(find("TAP M8").map(|f| f.text), Some("M8".to_string()));
/// assert_eq!(find("COOLANT M8"), None);
/// // A shop's inch tap: the Unified series whose standard size it is.
/// assert_eq!(find("3/8-16 TAP").map(|f| f.text), Some("3/8-16 UNC".to_string()));
/// assert_eq!(find("#10-32 TAP").map(|f| f.text), Some("#10-32 UNF".to_string()));
/// ```
pub fn designation_in_comment(comment: &str, opts: ParseOptions) -> Option<Found> {
    // Words with their character offsets; edge punctuation is not part of a word.
    let mut words: Vec<(usize, String)> = Vec::new();
    let mut start = None;
    let chars: Vec<char> = comment.chars().collect();
    for (i, &c) in chars.iter().chain(std::iter::once(&' ')).enumerate() {
        let sep = c.is_whitespace() || matches!(c, ',' | ';' | ':' | '=' | '(' | ')' | '[' | ']' | '\'');
        // A comma between digits is a decimal comma, part of the word.
        let decimal_comma = c == ','
            && i > 0
            && chars.get(i - 1).is_some_and(char::is_ascii_digit)
            && chars.get(i + 1).is_some_and(char::is_ascii_digit);
        match (sep && !decimal_comma, start) {
            (true, Some(s)) => {
                words.push((s, chars[s..i].iter().collect()));
                start = None;
            }
            (false, None) => start = Some(i),
            _ => {}
        }
    }
    let upper = comment.to_uppercase();
    let says_thread = upper.split(|c: char| !c.is_alphanumeric()).any(|w| THREAD_WORDS.contains(&w));
    let capitals = !comment.chars().any(|c| c.is_lowercase());
    for i in 0..words.len() {
        for len in (1..=3).rev() {
            let Some(run) = words.get(i..i + len) else { continue };
            let joined: Vec<&str> = run.iter().map(|(_, w)| w.as_str()).collect();
            for text in spellings(&joined, capitals) {
                let Ok(d) = parse_designation(&text, opts) else { continue };
                // A series added to a bare inch size (`3/8-16` read as 3/8-16 UNC) needs a word
                // for a thread or tap in the comment.
                if !says_thread && text.len() > joined.join(" ").len() && d.thread.form == ThreadForm::Unified
                {
                    continue;
                }
                let bare = d.thread.form == ThreadForm::IsoMetric
                    && d.external.is_none()
                    && d.internal.is_none()
                    && !text.to_ascii_uppercase().contains('X');
                if bare && !says_thread {
                    continue;
                }
                return Some(Found { text, designation: d, offset: words[i].0 });
            }
        }
    }
    None
}

/// Whether `w` is an inch size with its threads per inch and nothing else: `3/8-16`, `1/4-20`,
/// `#10-32`, `0-80`.
fn is_inch_size_and_tpi(w: &str) -> bool {
    let Some((size, tpi)) = w.rsplit_once('-') else { return false };
    let size = size.strip_prefix('#').unwrap_or(size);
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    let size_ok = match size.split_once('/') {
        Some((a, b)) => digits(a) && digits(b),
        None => digits(size) && size.len() <= 2,
    };
    size_ok && digits(tpi)
}

/// The spellings of a run of words to try, the most literal first.
fn spellings(words: &[&str], capitals: bool) -> Vec<String> {
    let clean = |w: &str| -> String {
        let mut s: String = w.chars().filter(|&c| c != '"').map(|c| if c == '×' { 'x' } else { c }).collect();
        // A decimal comma.
        let b: Vec<char> = s.chars().collect();
        if let Some(k) = (1..b.len().saturating_sub(1))
            .find(|&k| b[k] == ',' && b[k - 1].is_ascii_digit() && b[k + 1].is_ascii_digit())
        {
            s = b[..k].iter().chain(std::iter::once(&'.')).chain(&b[k + 1..]).collect();
        }
        s
    };
    let w: Vec<String> = words.iter().map(|w| clean(w)).collect();
    let first = w[0].to_ascii_uppercase();
    // Words that never begin a designation are not tried (the parser would only refuse them).
    let begins = first
        .starts_with(|c: char| c.is_ascii_digit() || matches!(c, 'M' | 'T' | 'G' | 'B' | 'R' | '#' | '.'));
    if !begins {
        return Vec::new();
    }
    let mut out = vec![w.join(" ")];
    // `3/8-16`, `#10-32` (a shop's tap comment): the Unified series whose standard size it is.
    if w.len() == 1 && is_inch_size_and_tpi(&w[0]) {
        for series in ["UNC", "UNF", "UNEF"] {
            out.push(format!("{} {series}", w[0]));
        }
    }
    // `M10X1.5 6H`: the class as its own word.
    if w.len() == 2 {
        out.push(w.join("-"));
    }
    // `1/2 BSP`, `BSPP 1/2` (ISO 228-1, written G), `1/2 BSPT` (ISO 7-1, written R).
    if w.len() == 2 {
        let (a, b) = (w[0].to_ascii_uppercase(), w[1].to_ascii_uppercase());
        for (size, series) in [(&w[0], &b), (&w[1], &a)] {
            match series.as_str() {
                "BSP" | "BSPP" => out.push(format!("G{size}")),
                "BSPT" => out.push(format!("R{size}")),
                _ => {}
            }
        }
    }
    let mut more = Vec::new();
    for s in &out {
        // `M10x1.5LH`: LH without its hyphen.
        let up = s.to_ascii_uppercase();
        if up.ends_with("LH") && !up.ends_with("-LH") && s.len() > 2 {
            more.push(format!("{}-LH", &s[..s.len() - 2]));
        }
        // A class in capitals (`TR40X7-7E`): the letters as the standard writes the external
        // class; the side is settled against the operation afterwards.
        if capitals {
            if let Some(k) = s.rfind('-') {
                more.push(format!("{}-{}", &s[..k], s[k + 1..].to_ascii_lowercase()));
            }
        }
    }
    out.extend(more);
    out
}

/// The designation of `found` with the class `kind` is checked against: its own, the same
/// letters in the side's case when the comment is in capitals (`6G` on a bar is 6g), else the
/// standard's default class.
fn with_class(found: &Found, kind: ThreadKind, opts: ParseOptions) -> (Designation, String) {
    let d = &found.designation;
    if d.class(kind).is_some() {
        return (d.clone(), String::new());
    }
    // A comment is read without regard to case (a shop writes `M24X2-6G deburr after` for a
    // bolt): the class takes the case the standard writes for the side the operation cuts.
    let flip = matches!(d.thread.form, ThreadForm::IsoMetric | ThreadForm::Trapezoidal);
    if flip && (d.external.is_some() || d.internal.is_some()) {
        if let Some(k) = found.text.rfind('-') {
            let class = &found.text[k + 1..];
            let cased = match kind {
                ThreadKind::External => class.to_ascii_lowercase(),
                ThreadKind::Internal => class.to_ascii_uppercase(),
            };
            let text = format!("{}-{cased}", &found.text[..k]);
            if let Some(cased_one) = parse_designation(&text, opts).ok().filter(|e| e.class(kind).is_some()) {
                let why = format!(
                    "comments are read without regard to case: its class {class} is read as {cased}, the {} class (the operation's side decides)",
                    kind.name()
                );
                return (cased_one, why);
            }
        }
    }
    if d.external.is_none() && d.internal.is_none() {
        let text = d.with_example_class(kind);
        // The example class is the standard's own: it parses whenever the size did.
        if let Some(classed) = (text != found.text).then(|| parse_designation(&text, opts).ok()).flatten() {
            return (
                classed,
                format!("the comment names no class: the standard's default for an {} thread", kind.name()),
            );
        }
    }
    // A class of the other side: kept, and refused where the operation's side is checked.
    (d.clone(), String::new())
}

/// The nearest comment at or above `upto` (and below `after`, exclusive) that names a thread.
pub fn from_comments(
    comments: &[Comment],
    after: usize,
    upto: usize,
    kind: ThreadKind,
    opts: ParseOptions,
) -> Option<Named> {
    comments.iter().rev().filter(|c| c.line > after && c.line <= upto).find_map(|c| {
        let found = designation_in_comment(&c.text, opts)?;
        let (designation, class_why) = with_class(&found, kind, opts);
        let mut why =
            format!("{designation}: named by the comment at line {} (\"{}\")", c.line, c.text.trim());
        if !class_why.is_empty() {
            why.push_str(&format!("; {class_why}"));
        }
        Some(Named { designation, from: DesignationFrom::Comment, line: Some(c.line), why })
    })
}

/// The standard thread whose lead and diameter an operation cuts. The series is chosen by the
/// diameters first: every size of ISO 261 (metric coarse and fine), ASME B1.1 (UNC, UNF, UNEF),
/// BS 84 (BSW, BSF), ISO 228-1 (BSP) and ISO 2902 (Tr) whose pitch is the lead over the starts
/// (to the program's least increment) and whose major diameter lies within one thread depth of
/// `major` fits; the nearest size of the one series that fits is named, with the standard's
/// default class for `kind`. When sizes of two series fit (1-8 UNC and BSW 1, both Ø25.4 at
/// 8 tpi: the passes cannot tell 60° from 55°), or none does, it is refused naming what was
/// looked at, never guessed across series. A multi-start thread is inferred in ISO 261 alone.
///
/// ```
/// use threadcheck::{infer_designation, ProgramUnits, ThreadKind};
/// let n = infer_designation(2.0, 1, 23.9, ThreadKind::External, ProgramUnits::Mm, 12)?;
/// assert_eq!(n.designation.text, "M24x2-6g");
/// let two = infer_designation(3.0, 2, 24.1, ThreadKind::External, ProgramUnits::Mm, 12)?;
/// assert_eq!(two.designation.text, "M24xPh3P1.5-6g");
/// let u = infer_designation(25.4 / 13.0, 1, 12.7, ThreadKind::Internal, ProgramUnits::Inch, 12)?;
/// assert_eq!(u.designation.text, "1/2-13 UNC-2B");
/// // 12 tpi on Ø12.67: BSW 1/2, not 9/16-12 UNC (Ø14.29, beyond a thread depth).
/// let w = infer_designation(25.4 / 12.0, 1, 12.67, ThreadKind::External, ProgramUnits::Inch, 12)?;
/// assert_eq!(w.designation.text, "BSW 1/2 medium");
/// // 8 tpi on Ø25.4 is 1-8 UNC and BSW 1 alike: refused, naming both.
/// let e = infer_designation(25.4 / 8.0, 1, 25.3, ThreadKind::External, ProgramUnits::Inch, 12).unwrap_err();
/// assert!(e.to_string().contains("1-8 UNC") && e.to_string().contains("BSW 1"));
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn infer_designation(
    lead: f64,
    starts: u32,
    major: f64,
    kind: ThreadKind,
    units: ProgramUnits,
    line: usize,
) -> Result<Named, Error> {
    infer_designation_with(lead, starts, major, kind, units, line, None)
}

/// [`infer_designation`] with the tool's included angle when the program or the tool says it (a
/// G76's angle word, a thread mill's tooth): of series that fit alike, those whose flank angle
/// is not within 5° of it are set aside (M24x3 and Tr24x3 are both Ø24 at 3 mm; a 60° tool cuts
/// the metric one), and the name says so.
pub fn infer_designation_with(
    lead: f64,
    starts: u32,
    major: f64,
    kind: ThreadKind,
    units: ProgramUnits,
    line: usize,
    tool_angle: Option<f64>,
) -> Result<Named, Error> {
    let cat = crate::standards::data::catalog()?;
    let starts = starts.max(1);
    let pitch = lead / f64::from(starts);
    // The lead as the program writes it: to its least increment (0.001 mm, 0.0001 in).
    let increment = units.least_increment() * units.mm();
    let near = |p: f64| (p - pitch).abs() <= increment + 1e-9;
    // (series, major diameter mm, size as the parser reads it)
    let mut candidates: Vec<(&str, f64, String)> = Vec::new();
    for s in &cat.iso.series.sizes {
        for &p in s.coarse.iter().chain(&s.fine).filter(|&&p| near(p)) {
            let name = if starts == 1 {
                format!("M{}x{}", s.d, p)
            } else {
                format!("M{}xPh{}P{}", s.d, p * f64::from(starts), p)
            };
            candidates.push(("ISO 261 metric", s.d, name));
        }
    }
    if starts == 1 {
        for s in &cat.unified {
            for (name, tpi) in [("UNC", s.unc), ("UNF", s.unf), ("UNEF", s.unef)] {
                let Some(tpi) = tpi.filter(|&t| near(MM_PER_INCH / t)) else { continue };
                let size = if s.name.contains(['/', ' ']) || s.d >= 0.25 {
                    s.name.clone()
                } else {
                    format!("#{}", s.name)
                };
                candidates.push(("ASME B1.1 unified", s.d * MM_PER_INCH, format!("{size}-{tpi} {name}")));
            }
        }
        for (series, sizes) in [("BS 84 BSW", &cat.bsw), ("BS 84 BSF", &cat.bsf)] {
            for s in sizes.iter().filter(|s| near(MM_PER_INCH / s.tpi)) {
                let name = format!("{} {}", &series[6..], s.size);
                if let Ok(d) = parse_designation(&name, ParseOptions::default()) {
                    candidates.push((series, d.thread.nominal_diameter, name));
                }
            }
        }
        for s in cat.bsp.iter().filter(|s| near(MM_PER_INCH / s.tpi)) {
            candidates.push(("ISO 228-1 BSP", s.d, format!("G{}", s.size)));
        }
        for (d, pitches) in cat.tr.series_d.iter().zip(&cat.tr.series_pitches) {
            for &p in pitches.iter().filter(|&&p| near(p)) {
                candidates.push(("ISO 2902 trapezoidal", *d, format!("Tr{d}x{p}")));
            }
        }
    }
    // Of each series, its nearest size within one thread depth of the major diameter.
    let mut fits: Vec<(&str, f64, String)> = Vec::new();
    for (series, d, name) in candidates {
        let Ok(des) = parse_designation(&name, ParseOptions::default()) else { continue };
        if (d - major).abs() > des.thread.thread_depth() + 1e-9 {
            continue;
        }
        match fits.iter_mut().find(|f| f.0 == series) {
            Some(f) if (d - major).abs() < (f.1 - major).abs() => *f = (series, d, name),
            Some(_) => {}
            None => fits.push((series, d, name)),
        }
    }
    // Series that fit alike told apart by the tool's angle.
    let mut by_angle = String::new();
    if let (Some(angle), true) = (tool_angle, fits.len() > 1) {
        let agree: Vec<(&str, f64, String)> = fits
            .iter()
            .filter(|f| {
                parse_designation(&f.2, ParseOptions::default())
                    .is_ok_and(|d| (d.thread.form.flank_angle() - angle).abs() <= 5.0)
            })
            .cloned()
            .collect();
        if agree.len() == 1 {
            let set_aside: Vec<&str> =
                fits.iter().filter(|f| f.2 != agree[0].2).map(|f| f.2.as_str()).collect();
            by_angle = format!(
                "; {} set aside: the tool's {}° is not its flank angle",
                set_aside.join(", "),
                crate::ground::fmt::fmt_num(angle)
            );
            fits = agree;
        }
    }
    let of_starts = if starts == 1 { String::new() } else { format!(" over {starts} starts") };
    let size = match fits.as_slice() {
        [] => {
            return Err(Error::Input(format!(
                "cannot name the thread: no size of ISO 261, ASME B1.1, BS 84, ISO 228-1 or ISO 2902 has a lead of {lead:.4} mm{of_starts} and a major diameter within a thread depth of Ø{major:.3}: name it (‹thread›, or a comment such as (M20X1.5) above the operation)"
            )))
        }
        [(_, _, name)] => name.clone(),
        several => {
            let named: Vec<String> =
                several.iter().map(|(series, d, name)| format!("{name} (Ø{d:.3}, {series})")).collect();
            return Err(Error::Input(format!(
                "cannot name the thread: Ø{major:.3} at a lead of {lead:.4} mm fits {}, which the passes cannot tell apart: name it (‹thread›, or a comment above the operation)",
                named.join(" and ")
            )));
        }
    };
    let series = fits[0].0;
    let d = parse_designation(&size, ParseOptions::default())?;
    let designation = parse_designation(&d.with_example_class(kind), ParseOptions::default())?;
    let why = format!(
        "{designation}: inferred from the operation at line {line} (lead {lead:.4} mm{of_starts}, major diameter about Ø{major:.3}: the nearest {series} size of that pitch, no other series within a thread depth{by_angle}; the class is its standard's default for an {} thread; name the thread in a comment or with ‹thread› to check another)",
        kind.name()
    );
    Ok(Named { designation, from: DesignationFrom::Inferred, line: Some(line), why })
}

/// A thread mill a comment names: its tool number when the comment lists tools (`T5 …`), its
/// diameter in mm and, when written, its tooth's angle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MillInComment {
    /// The tool the comment begins with (`T5  D=8. CR=0. - thread mill`, as a CAM system's
    /// tool list writes it), else `None` (a comment at the tool change).
    pub tool: Option<u32>,
    /// The diameter over the tooth's tip, mm.
    pub diameter: f64,
    /// The tooth's included angle, degrees, when the comment writes one (`60 DEG`, `60°`).
    pub angle_deg: Option<f64>,
}

/// The thread mill a comment names: a comment with the words THREAD MILL (THREADMILL,
/// THREAD-MILL; GEWINDEFRÄSER) and a diameter written as one (`D=8.`, `D8`, `DIA 8`, `Ø8`), in the
/// program's units unless it ends in `MM`. Autodesk's posts list every tool at the program's
/// top as `(T5  D=8. CR=0. - ZMIN=-15. - thread mill)`, Mastercam's before each tool change as
/// `( 8. THREAD MILL TOOL - 5 DIA. OFF. - 5 LEN. - 5 DIA. - 8. )`.
///
/// ```
/// use threadcheck::{thread_mill_in_comment, ProgramUnits};
/// let m = thread_mill_in_comment("T5  D=8. CR=0. - ZMIN=-15. - thread mill", ProgramUnits::Mm).unwrap();
/// assert_eq!((m.tool, m.diameter, m.angle_deg), (Some(5), 8.0, None));
/// let m = thread_mill_in_comment("THREAD MILL D10 60 DEG", ProgramUnits::Mm).unwrap();
/// assert_eq!((m.tool, m.diameter, m.angle_deg), (None, 10.0, Some(60.0)));
/// // Mastercam's form: the description, then the tool, its offsets and its diameter.
/// let m = thread_mill_in_comment(" 8. THREAD MILL TOOL - 5 DIA. OFF. - 5 LEN. - 5 DIA. - 8. ", ProgramUnits::Mm).unwrap();
/// assert_eq!((m.tool, m.diameter), (Some(5), 8.0));
/// let m = thread_mill_in_comment("T12 D=0.375 CR=0. - thread mill", ProgramUnits::Inch).unwrap();
/// assert!((m.diameter - 9.525).abs() < 1e-12);
/// // A drill's or an end mill's line names no thread mill.
/// assert_eq!(thread_mill_in_comment("T2  D=8.5 CR=0. TAPER=118deg - drill", ProgramUnits::Mm), None);
/// assert_eq!(thread_mill_in_comment("THREAD M12X1.75", ProgramUnits::Mm), None);
/// ```
pub fn thread_mill_in_comment(comment: &str, units: ProgramUnits) -> Option<MillInComment> {
    let upper = comment.to_uppercase().replace('-', " ");
    let words: Vec<&str> = upper.split_whitespace().collect();
    let names_mill = words.windows(2).any(|w| w[0] == "THREAD" && (w[1] == "MILL" || w[1] == "MILLING"))
        || words.iter().any(|w| w.starts_with("THREADMILL") || w.starts_with("GEWINDEFR"));
    if !names_mill {
        return None;
    }
    // `T5 …` (Autodesk's list), `TOOL 5 …` (SolidCAM's), or `… TOOL - 5 …` (Mastercam's).
    let tool = listed_number(comment)
        .map(|(n, _)| n)
        .or_else(|| words.windows(2).find(|w| w[0] == "TOOL").and_then(|w| w[1].parse::<u32>().ok()));
    let length = |w: &str| length_in_comment(w.trim_end_matches([',', ';', ')']), units);
    let diameter = words.iter().enumerate().find_map(|(i, w)| {
        for mark in ["DIA.", "DIAM", "DIA", "D=", "Ø", "⌀", "D"] {
            if let Some(rest) = w.strip_prefix(mark) {
                let rest = rest.trim_start_matches('=');
                return if rest.is_empty() {
                    // `DIA 8`, `Ø 8`: the number is the next word (a bare `D` is no mark).
                    (mark != "D").then(|| words.get(i + 1).and_then(|n| length(n))).flatten()
                } else {
                    length(rest)
                };
            }
        }
        None
    })?;
    let angle_deg = words.iter().enumerate().find_map(|(i, w)| {
        let (num, marked) = match w.strip_suffix('°') {
            Some(n) => (n, true),
            None => (*w, words.get(i + 1).is_some_and(|n| n.starts_with("DEG") || n.starts_with('°'))),
        };
        let v: f64 = num.strip_suffix("DEG").unwrap_or(num).parse().ok()?;
        (marked || num.ends_with("DEG")).then_some(v).filter(|v| *v > 0.0 && *v < 180.0)
    });
    Some(MillInComment { tool, diameter, angle_deg })
}

/// Words that make a tool list's line a tap's: English, German (cutting and forming taps),
/// French, Spanish, Italian and Russian.
pub const TAP_WORDS: &[&str] = &[
    "TAP",
    "TAPPING",
    "GEWINDEBOHRER",
    "GEWINDEFORMER",
    "GEWINDEFURCHER",
    "TARAUD",
    "MACHO",
    "MASCHIO",
    "МЕТЧИК",
];

/// Words that make a number in a comment a drill's diameter.
pub const DRILL_WORDS: &[&str] =
    &["DRILL", "DRILLING", "BOHRER", "BOHREN", "FORET", "PERCAGE", "BROCA", "PUNTA", "СВЕРЛО"];

/// The drill's diameter a comment names (`(DRILL 8.5)`, `(8.5 DRILL)`, `(DRILL D8.5)`,
/// `(Ø6.8 BOHRER)`), in mm: the first number of the comment, bare or after `Ø`, `⌀`, `D` or `DIA`,
/// in a comment that has a word for drill; in the program's units unless it ends in `MM`.
///
/// ```
/// use threadcheck::{drill_in_comment, ProgramUnits};
/// assert_eq!(drill_in_comment("T5 DRILL D8.5", ProgramUnits::Mm), Some(8.5));
/// assert_eq!(drill_in_comment("6,8 BOHRER", ProgramUnits::Mm), Some(6.8));
/// assert_eq!(drill_in_comment("DRILL .339", ProgramUnits::Inch), Some(0.339 * 25.4));
/// assert_eq!(drill_in_comment("SPOT DRILL 90 DEG", ProgramUnits::Mm), None);
/// assert_eq!(drill_in_comment("TAP M10", ProgramUnits::Mm), None);
/// // Inch drills by their gauges, whatever the program's units.
/// assert_eq!(drill_in_comment("5/16 DRILL", ProgramUnits::Mm), Some(0.3125 * 25.4));
/// assert!((drill_in_comment("T4 | NO. 29 DRILL | H4", ProgramUnits::Inch).unwrap() - 3.4544).abs() < 1e-9);
/// assert!((drill_in_comment("LETTER F DRILL", ProgramUnits::Inch).unwrap() - 6.5278).abs() < 1e-9);
/// assert!((drill_in_comment("F DRILL", ProgramUnits::Inch).unwrap() - 6.5278).abs() < 1e-9);
/// ```
pub fn drill_in_comment(comment: &str, units: ProgramUnits) -> Option<f64> {
    let upper = comment.to_uppercase();
    if !upper.split(|c: char| !c.is_alphanumeric()).any(|w| DRILL_WORDS.contains(&w)) {
        return None;
    }
    let words: Vec<&str> = upper.split_whitespace().collect();
    let bare =
        |w: &str| w.trim_matches(|c: char| matches!(c, ',' | ';' | ':' | '=' | '(' | ')' | '"')).to_string();
    words.iter().enumerate().find_map(|(i, w)| {
        // An inch drill by its gauge: `5/16`, `#29`, `NO. 29`, `LETTER F`, `F DRILL`.
        let w0 = bare(w);
        let next = words.get(i + 1).map(|n| bare(n));
        let gauge = match w0.as_str() {
            "NO." | "NO" | "NR." => {
                next.as_deref().and_then(|n| crate::standards::drills::inch_drill(&format!("#{n}")))
            }
            "LETTER" => next.as_deref().and_then(crate::standards::drills::inch_drill),
            l if l.len() == 1 => next
                .as_deref()
                .filter(|n| DRILL_WORDS.contains(n))
                .and_then(|_| crate::standards::drills::inch_drill(l)),
            f if f.contains('/') || f.starts_with('#') => crate::standards::drills::inch_drill(f),
            _ => None,
        };
        if gauge.is_some() {
            return gauge;
        }
        // An angle (`90 DEG`, `118°`) is not a diameter.
        if w.ends_with('°') || words.get(i + 1).is_some_and(|n| n.starts_with("DEG") || n.starts_with('°'))
        {
            return None;
        }
        let w = w.trim_matches(|c: char| matches!(c, ',' | ';' | ':' | '=' | '(' | ')'));
        let w = w.trim_start_matches('Ø').trim_start_matches('⌀');
        let w = w.strip_prefix("DIA").or_else(|| w.strip_prefix('D')).unwrap_or(w);
        length_in_comment(w.trim_start_matches('='), units)
    })
}

/// A tool as a CAM system's tool list names it: its number, and what it is.
#[derive(Clone, Debug, PartialEq)]
pub struct ListedTool {
    /// The tool's number.
    pub tool: u32,
    /// What the list says it is.
    pub kind: ListedKind,
}

/// What a tool list's line says a tool is.
#[derive(Clone, Debug, PartialEq)]
pub enum ListedKind {
    /// A drill.
    Drill {
        /// Its diameter, mm.
        diameter: f64,
    },
    /// A tap.
    Tap {
        /// Its designation where the line writes one (`NO. 8-32 TAPRH`), parsed.
        designation: Option<Designation>,
        /// Its diameter, mm (`D=8`), for the cycle's pitch to complete.
        diameter: Option<f64>,
        /// Its hand where the line says it.
        hand: Option<crate::standards::Hand>,
    },
}

/// The tool a CAM system's tool-list line names, in the forms the posts write: Autodesk's
/// `T9  D=8. CR=0. - ZMIN=-14. - right hand tap` (Fusion 360, HSMWorks, Inventor CAM; `#9` on
/// some posts), Mastercam's `T5 | NO. 8-32 TAPRH | H5` and `T4 | NO. 29 DRILL | H4`: a tap or a
/// drill, with its number first. Lengths in the program's units unless they end in `MM`.
///
/// ```
/// use threadcheck::{listed_tool, ListedKind, ListedTool, ParseOptions, ProgramUnits, Hand};
/// let mm = ProgramUnits::Mm;
/// let l = listed_tool("T9  D=8. CR=0. - ZMIN=-14. - right hand tap", mm, ParseOptions::default());
/// assert_eq!(l, Some(ListedTool { tool: 9, kind: ListedKind::Tap { designation: None, diameter: Some(8.0), hand: Some(Hand::Right) } }));
/// let l = listed_tool("#7 D=6.8 - ZMIN=-16 - drill", mm, ParseOptions::default());
/// assert_eq!(l, Some(ListedTool { tool: 7, kind: ListedKind::Drill { diameter: 6.8 } }));
/// let l = listed_tool(" T5 | NO. 8-32 TAPRH | H5 ", ProgramUnits::Inch, ParseOptions::default()).unwrap();
/// assert!(matches!(&l.kind, ListedKind::Tap { designation: Some(d), diameter: None, hand: Some(Hand::Right) } if d.text == "#8-32 UNC-2B"));
/// let l = listed_tool(" T4 | NO. 29 DRILL | H4 ", ProgramUnits::Inch, ParseOptions::default()).unwrap();
/// assert_eq!(l.tool, 4);
/// assert!(matches!(l.kind, ListedKind::Drill { diameter } if (diameter - 3.4544).abs() < 1e-9));
/// // SolidCAM's and hyperMILL's headers: the tool's number after TOOL.
/// let l = listed_tool("TOOL 3 - TAP M8X1.25 - DIA 8.", mm, ParseOptions::default()).unwrap();
/// assert!(matches!(&l.kind, ListedKind::Tap { designation: Some(d), diameter: None, hand: None } if d.text == "M8X1.25-6H"));
/// assert_eq!(l.tool, 3);
/// let l = listed_tool("TOOL NUMBER: 4  DRILL D6.8", mm, ParseOptions::default()).unwrap();
/// assert_eq!((l.tool, l.kind), (4, ListedKind::Drill { diameter: 6.8 }));
/// let l = listed_tool("T12: GEWINDEBOHRER M10", mm, ParseOptions::default()).unwrap();
/// assert!(matches!(&l.kind, ListedKind::Tap { designation: Some(d), diameter: None, hand: None } if d.text == "M10-6H"));
/// assert_eq!(l.tool, 12);
/// assert_eq!(listed_tool("TOOLING CHECK - TAP M8", mm, ParseOptions::default()), None);
/// // A thread mill's or an end mill's line, or a comment with no tool first, is none.
/// assert_eq!(listed_tool("T5 D=8. CR=0. - thread mill", mm, ParseOptions::default()), None);
/// assert_eq!(listed_tool("DRILL 6.8", mm, ParseOptions::default()), None);
/// ```
pub fn listed_tool(comment: &str, units: ProgramUnits, opts: ParseOptions) -> Option<ListedTool> {
    let (tool, rest) = listed_number(comment)?;
    let rest = rest.replace('|', " ");
    let upper = rest.to_uppercase();
    // Mastercam's `TAPRH`, `NO. 8-32`: as the comment reader reads them.
    let spaced =
        upper.replace("TAPRH", "TAP RH").replace("TAPLH", "TAP LH").replace("NO. ", "#").replace("NO.", "#");
    let words: Vec<&str> = spaced.split_whitespace().collect();
    let plain: Vec<&str> = spaced.split(|c: char| !c.is_alphanumeric()).filter(|w| !w.is_empty()).collect();
    let has = |w: &str| plain.contains(&w);
    if has("MILL") || spaced.contains("THREADMILL") {
        return None;
    }
    if TAP_WORDS.iter().any(|w| has(w)) {
        let hand = if has("LH") || spaced.contains("LEFT HAND") {
            Some(crate::standards::Hand::Left)
        } else if has("RH") || spaced.contains("RIGHT HAND") {
            Some(crate::standards::Hand::Right)
        } else {
            None
        };
        let designation =
            designation_in_comment(&spaced, opts).map(|f| with_class(&f, ThreadKind::Internal, opts).0);
        let diameter = words.iter().find_map(|w| {
            let v = w.strip_prefix("D=").or_else(|| w.strip_prefix("DIA="))?;
            length_in_comment(v.trim_end_matches(','), units)
        });
        if designation.is_none() && diameter.is_none() {
            return None;
        }
        return Some(ListedTool { tool, kind: ListedKind::Tap { designation, diameter, hand } });
    }
    let diameter = drill_in_comment(&spaced.replace('#', "NO. "), units)?;
    Some(ListedTool { tool, kind: ListedKind::Drill { diameter } })
}

/// The tool's number a tool-list line begins with, and the rest of the line: `T5`, `#5`, `T=5`
/// (Autodesk's and Mastercam's lists), `TOOL 5`, `TOOL - 5`, `TOOL NO. 5`, `TOOL NUMBER: 5`
/// (SolidCAM's and hyperMILL's headers; threadcheck's default reading of their forms, which
/// differ by post), `WZ 5` (German posts); `T5:` and `T5,` too.
fn listed_number(comment: &str) -> Option<(u32, &str)> {
    let t = comment.trim_start();
    let digits = |s: &str| s.find(|c: char| !c.is_ascii_digit()).unwrap_or(s.len());
    let number = |s: &str| -> Option<(u32, usize)> {
        let n = digits(s);
        let v = s[..n].parse().ok()?;
        // The number ends the word: `T5`, `T5:`, not `T5X`.
        let next = s[n..].chars().next();
        next.is_none_or(|c| c.is_whitespace() || matches!(c, '|' | ':' | ',' | '-' | ')' | ';'))
            .then_some((v, n))
    };
    let upper = t.to_ascii_uppercase();
    // `TOOL …`/`WZ …` then the separators and words a header puts before the number.
    for word in ["TOOL", "WZ"] {
        if let Some(after) = upper.strip_prefix(word) {
            let mut i = t.len() - after.len();
            if !after.starts_with(|c: char| c.is_whitespace() || matches!(c, ':' | '-' | '#' | '=' | '.')) {
                return None;
            }
            loop {
                let rest = &upper[i..];
                let skip = rest.len() - rest.trim_start_matches([' ', '\t', ':', '-', '#', '=', '.']).len();
                i += skip;
                let rest = &upper[i..];
                match ["NUMBER", "NO", "NR", "NUM"].iter().find(|w| {
                    rest.starts_with(**w) && !rest[w.len()..].starts_with(|c: char| c.is_ascii_alphanumeric())
                }) {
                    Some(w) => i += w.len(),
                    None if skip > 0 => break,
                    None => return None,
                }
            }
            let (v, n) = number(&t[i..])?;
            return Some((v, &t[i + n..]));
        }
    }
    let head = t.strip_prefix(['T', 't', '#'])?;
    let head = head.strip_prefix('=').unwrap_or(head);
    let (v, n) = number(head)?;
    Some((v, &head[n..]))
}

/// The tap a CAM tool list names for tool `tool` (the first line of the list that names it, see
/// [`listed_tool`]): its designation with the class a comment gets; else its diameter with the
/// cycle's `lead` (mm), the standard size of both ([`infer_designation`]: an error when none
/// fits, naming both). `None` when no line names the tool as a tap.
pub(crate) fn listed_tap(
    comments: &[Comment],
    tool: u32,
    units: ProgramUnits,
    opts: ParseOptions,
    lead: Option<f64>,
    line: usize,
) -> Option<Result<Named, Error>> {
    let (kind, at) = comments.iter().find_map(|c| {
        listed_tool(&c.text, units, opts).filter(|l| l.tool == tool).map(|l| (l.kind, c.line))
    })?;
    let ListedKind::Tap { designation, diameter, .. } = kind else { return None };
    if let Some(designation) = designation {
        let why = format!("{designation}: T{tool} in the program's tool list at line {at}");
        return Some(Ok(Named { designation, from: DesignationFrom::Comment, line: Some(at), why }));
    }
    let d = diameter?;
    let Some(lead) = lead else {
        return Some(Err(Error::Program {
            file: String::new(),
            line,
            column: 1,
            message: format!(
                "T{tool} is a tap of Ø{} in the program's tool list at line {at}, and the cycle's feed gives no lead to complete its size",
                crate::ground::fmt::fmt_num(d)
            ),
        }));
    };
    let fits = infer_designation(lead, 1, d, ThreadKind::Internal, units, line);
    Some(match fits {
        Ok(mut n) => {
            n.from = DesignationFrom::Comment;
            n.line = Some(at);
            n.why = format!(
                "{}: T{tool}, a tap of Ø{} in the program's tool list at line {at}, at the cycle's lead {} mm",
                n.designation,
                crate::ground::fmt::fmt_num(d),
                crate::ground::fmt::fmt_num((lead * 1e6).round() / 1e6)
            );
            Ok(n)
        }
        Err(_) => {
            // The metric sizes of that diameter and their pitches, named beside the cycle's.
            let sizes: Vec<String> = crate::standards::data::catalog()
                .map(|cat| {
                    cat.iso
                        .series
                        .sizes
                        .iter()
                        .filter(|s| (s.d - d).abs() < 1e-6)
                        .map(|s| {
                            let pitches: Vec<String> = s
                                .coarse
                                .iter()
                                .chain(&s.fine)
                                .map(|p| crate::ground::fmt::fmt_num(*p))
                                .collect();
                            format!("M{} has {}", crate::ground::fmt::fmt_num(s.d), pitches.join(", "))
                        })
                        .collect()
                })
                .unwrap_or_default();
            Err(Error::Program {
                file: String::new(),
                line,
                column: 1,
                message: format!(
                    "T{tool} is a tap of Ø{} in the program's tool list at line {at}, and the cycle's lead {} mm fits no standard thread of that diameter{}: a tap of this pitch does not exist, or the cycle's pitch is wrong",
                    crate::ground::fmt::fmt_num(d),
                    crate::ground::fmt::fmt_num((lead * 1e6).round() / 1e6),
                    if sizes.is_empty() { String::new() } else { format!(" ({})", sizes.join("; ")) }
                ),
            })
        }
    })
}

/// A length a comment writes (`8.5`, `6,8`, `.339`, `8.5MM`), in mm: in the program's units
/// unless it ends in `MM`; `None` unless it is a positive number.
fn length_in_comment(w: &str, units: ProgramUnits) -> Option<f64> {
    let (num, mm) = match w.strip_suffix("MM") {
        Some(n) => (n, true),
        None => (w, false),
    };
    if !num.starts_with(|c: char| c.is_ascii_digit() || c == '.') {
        return None;
    }
    let v: f64 = num.replace(',', ".").parse().ok()?;
    (v.is_finite() && v > 0.0).then(|| if mm { v } else { v * units.mm() })
}
