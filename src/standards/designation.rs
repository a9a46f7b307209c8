//! The designation parser: `M10x1.25-6g`, `M24xPh6P2-6g`, `BSF 3/8 medium`, `G1/2 A` and kin.
//!
//! Every error names the part of the text that is wrong, by its column.

use super::data::{catalog, find_pitch, SeriesSize};
use super::{BasicThread, Hand, ThreadForm, ThreadKind, MM_PER_INCH};
pub use crate::ground::error::DesignationError;
use crate::standards::tolerance::{
    AcmeClass, Bs84Class, Iso228Class, IsoClass, TaperClass, TrClass, UnifiedClass, UnifiedGrade,
    UnifiedSeries,
};
use std::fmt;

/// A parsed thread designation: the basic thread and the classes it names.
#[derive(Clone, Debug, PartialEq)]
pub struct Designation {
    /// The text as given (trimmed).
    pub text: String,
    /// Basic size.
    pub thread: BasicThread,
    /// Class of the external thread, if named.
    pub external: Option<ClassSpec>,
    /// Class of the internal thread, if named.
    pub internal: Option<ClassSpec>,
    /// True when the size/pitch pair is not in its standard series (`--allow-nonstandard`).
    pub nonstandard: bool,
}

impl Designation {
    /// The designation with an example class of `kind` in its standard's own vocabulary, for a
    /// designation that names none: `M10x1.5-6g`, `BSW 1/2 medium`, `G1/2 A`, `1/2-13 UNC-2A`,
    /// `Tr40x7-7e`, `1/2-10 ACME-2G`.
    pub fn with_example_class(&self, kind: ThreadKind) -> String {
        match (self.thread.form, kind) {
            (ThreadForm::IsoMetric, ThreadKind::External) => format!("{}-6g", self.text),
            (ThreadForm::IsoMetric, ThreadKind::Internal) => format!("{}-6H", self.text),
            (ThreadForm::Whitworth, _) => format!("{} medium", self.text),
            (ThreadForm::BspParallel, ThreadKind::External) => format!("{} A", self.text),
            (ThreadForm::BspParallel, ThreadKind::Internal) => self.text.clone(),
            (ThreadForm::Unified, ThreadKind::External) => format!("{}-2A", self.text),
            (ThreadForm::Unified, ThreadKind::Internal) => format!("{}-2B", self.text),
            (ThreadForm::Trapezoidal, ThreadKind::External) => format!("{}-7e", self.text),
            (ThreadForm::Trapezoidal, ThreadKind::Internal) => format!("{}-7H", self.text),
            (ThreadForm::Acme, ThreadKind::External | ThreadKind::Internal) => format!("{}-2G", self.text),
            (ThreadForm::Npt, ThreadKind::External | ThreadKind::Internal) => self.text.clone(),
            (ThreadForm::Iso7Taper, ThreadKind::External) => self.text.replace("Rc", "R"),
            (ThreadForm::Iso7Taper, ThreadKind::Internal) => {
                format!("Rc{}", self.text.trim_start_matches(['R', 'r']))
            }
        }
    }

    /// The class for `kind`, if the designation names one.
    pub fn class(&self, kind: ThreadKind) -> Option<&ClassSpec> {
        match kind {
            ThreadKind::External => self.external.as_ref(),
            ThreadKind::Internal => self.internal.as_ref(),
        }
    }
}

/// The designation as the parser reads it (`M10x1.5-6g`).
impl fmt::Display for Designation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.text)
    }
}

/// A tolerance class of one of the supported standards.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ClassSpec {
    /// ISO 965-1 (e.g. `6g`, `5g6g`, `6H`).
    Iso(IsoClass),
    /// BS 84 Whitworth class (close, medium, free bolts; close, medium, normal nuts).
    Bs84(Bs84Class),
    /// ISO 228-1 class (A or B external; the one internal class).
    Iso228(Iso228Class),
    /// ASME B1.1 Unified class (1A 2A 3A, 1B 2B 3B) with its series.
    Unified(UnifiedClass),
    /// ISO 2903 trapezoidal class (7e 8e 8c 9c, 7H 8H 9H).
    Trapezoidal(TrClass),
    /// ASME B1.5 general-purpose Acme class (2G 3G 4G), for nut and bolt alike.
    Acme(AcmeClass),
    /// A taper pipe thread's side (NPT; ISO 7-1 R external, Rc internal).
    Taper(TaperClass),
}

impl fmt::Display for ClassSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ClassSpec::Iso(c) => c.fmt(f),
            ClassSpec::Bs84(c) => c.fmt(f),
            ClassSpec::Iso228(c) => c.fmt(f),
            ClassSpec::Unified(c) => c.fmt(f),
            ClassSpec::Trapezoidal(c) => c.fmt(f),
            ClassSpec::Acme(c) => c.fmt(f),
            ClassSpec::Taper(c) => c.fmt(f),
        }
    }
}

/// Parser options.
#[derive(Clone, Copy, Debug, Default)]
pub struct ParseOptions {
    /// Accept a diameter/pitch pair outside the standard series.
    pub allow_nonstandard: bool,
}

struct Cursor<'a> {
    text: &'a str,
    pos: usize,
}

impl<'a> Cursor<'a> {
    fn rest(&self) -> &'a str {
        &self.text[self.pos..]
    }

    fn err(&self, start: usize, end: usize, message: impl Into<String>) -> DesignationError {
        // Spans come from byte arithmetic; snap them to character boundaries so that any text,
        // however odd, slices cleanly.
        let floor = |mut i: usize| {
            i = i.min(self.text.len());
            while !self.text.is_char_boundary(i) {
                i -= 1;
            }
            i
        };
        let ceil = |mut i: usize| {
            i = i.min(self.text.len());
            while !self.text.is_char_boundary(i) {
                i += 1;
            }
            i
        };
        let start = floor(start);
        let end = ceil(end.max(start));
        DesignationError {
            text: self.text.to_string(),
            column: self.text[..start].chars().count() + 1,
            part: self.text[start..end].to_string(),
            message: message.into(),
        }
    }

    fn eat(&mut self, s: &str) -> bool {
        if self.rest().starts_with(s) {
            self.pos += s.len();
            true
        } else {
            false
        }
    }

    fn skip_spaces(&mut self) {
        while self.rest().starts_with(' ') {
            self.pos += 1;
        }
    }

    /// A decimal number `12`, `1.25`, `.5`; returns it and its byte span.
    fn number(&mut self, what: &str) -> Result<(f64, usize, usize), DesignationError> {
        let start = self.pos;
        let len = self
            .rest()
            .char_indices()
            .find(|&(_, c)| !(c.is_ascii_digit() || c == '.'))
            .map_or(self.rest().len(), |(i, _)| i);
        let s = &self.rest()[..len];
        if s.is_empty() {
            let next = self.rest().chars().next().map_or(0, char::len_utf8);
            return Err(self.err(start, start + next, format!("expected {what} (a number)")));
        }
        let v: f64 =
            s.parse().map_err(|_| self.err(start, start + len, format!("{what} '{s}' is not a number")))?;
        if !(v.is_finite() && v > 0.0) {
            return Err(self.err(start, start + len, format!("{what} must be greater than zero")));
        }
        self.pos += len;
        Ok((v, start, start + len))
    }
}

/// Parses a designation against the embedded catalogues.
///
/// ```
/// use threadcheck::{parse_designation, ParseOptions};
/// let d = parse_designation("M10x1.25-6g", ParseOptions::default()).unwrap();
/// assert_eq!(d.thread.pitch, 1.25);
/// assert!(d.external.is_some() && d.internal.is_none());
/// assert!(parse_designation("M10x1.3", ParseOptions::default()).is_err());
/// ```
pub fn parse_designation(text: &str, opts: ParseOptions) -> Result<Designation, crate::Error> {
    let text = text.trim();
    let mut c = Cursor { text, pos: 0 };
    if text.is_empty() {
        return Err(none_given_at(&c));
    }
    // ISO 965 writes the series letter upper case; a lower-case `m` before a digit can only
    // mean it (the class letters keep their case: 6g and 6H are different sides).
    if let Some(rest) = text.strip_prefix('m') {
        if rest.starts_with(|ch: char| ch.is_ascii_digit()) {
            return parse_designation(&format!("M{rest}"), opts);
        }
    }
    // A decimal comma (`M10x1,5-6g`) is named, not taken for a separator.
    let b = text.as_bytes();
    if let Some(i) = (1..b.len().saturating_sub(1))
        .find(|&i| b[i] == b',' && b[i - 1].is_ascii_digit() && b[i + 1].is_ascii_digit())
    {
        let fixed = format!("{}.{}", &text[..i], &text[i + 1..]);
        return Err(c.err(i, i + 1, format!("a decimal comma: write a decimal point, {fixed}")).into());
    }
    let upper = text.to_ascii_uppercase();
    if upper.contains("NPT") && upper.starts_with(|ch: char| ch.is_ascii_digit()) {
        parse_npt(&mut c, opts).map_err(Into::into)
    } else if upper.starts_with('R')
        && upper[1..].trim_start_matches(['C', 'P']).trim_start().starts_with(|ch: char| ch.is_ascii_digit())
    {
        parse_iso7(&mut c).map_err(Into::into)
    } else if upper.contains("ACME") && upper.starts_with(|ch: char| ch.is_ascii_digit() || ch == '.') {
        parse_acme(&mut c, opts).map_err(Into::into)
    } else if upper.contains("UN")
        && upper.starts_with(|ch: char| ch.is_ascii_digit() || ch == '#' || ch == '.')
    {
        parse_unified(&mut c, opts).map_err(Into::into)
    } else if upper.starts_with("TR") && text[2..].starts_with(|ch: char| ch.is_ascii_digit()) {
        parse_trapezoidal(&mut c, opts).map_err(Into::into)
    } else if upper.starts_with("BSW") || upper.starts_with("BSF") {
        parse_whitworth(&mut c, opts).map_err(Into::into)
    } else if upper.starts_with('G') {
        parse_bsp(&mut c).map_err(Into::into)
    } else if text.starts_with('M') {
        parse_metric(&mut c, opts).map_err(Into::into)
    } else {
        let first = text.chars().next().map_or(0, char::len_utf8);
        Err(c
            .err(
                0,
                first.max(text.find(|ch: char| ch.is_ascii_digit()).unwrap_or(first)),
                "unknown thread series; expected M (ISO metric), Tr (trapezoidal), BSW, BSF (Whitworth), G (BSP pipe), R/Rc (ISO 7-1 taper), or an inch size such as 1/4-20 UNC, 1/2-10 ACME or 1/2-14 NPT",
            )
            .into())
    }
}

/// The refusal of a thread asked for and not given: an empty designation.
pub fn none_given() -> crate::Error {
    none_given_at(&Cursor { text: "", pos: 0 })
}

fn none_given_at(c: &Cursor<'_>) -> crate::Error {
    c.err(0, 0, "empty designation; expected e.g. M10x1.5-6g, BSW 1/2 or G1/2 A").into()
}

fn fmt_pitch(p: f64) -> String {
    format!("{p}")
}

fn series_entry(d: f64) -> Result<Option<SeriesSize>, crate::Error> {
    let cat = catalog()?;
    Ok(cat.iso.series.sizes.iter().find(|s| (s.d - d).abs() < 1e-9).cloned())
}

fn standard_pitches(s: &SeriesSize) -> String {
    let mut parts = Vec::new();
    if let Some(c) = s.coarse {
        parts.push(format!("{} (coarse)", fmt_pitch(c)));
    }
    if !s.fine.is_empty() {
        let f: Vec<String> = s.fine.iter().map(|p| fmt_pitch(*p)).collect();
        parts.push(format!("{} (fine)", f.join(", ")));
    }
    parts.join("; ")
}

fn parse_metric(c: &mut Cursor<'_>, opts: ParseOptions) -> Result<Designation, DesignationError> {
    c.pos = 1;
    let (d, ds, de) = c.number("nominal diameter after M")?;
    let entry = series_entry(d).map_err(|e| c.err(ds, de, e.to_string()))?;
    let mut nonstandard = false;
    if entry.is_none() {
        if !opts.allow_nonstandard {
            let cat = catalog().map_err(|e| c.err(ds, de, e.to_string()))?;
            let sizes = &cat.iso.series.sizes;
            let below = sizes.iter().rfind(|s| s.d < d).map(|s| format!("M{}", s.d));
            let above = sizes.iter().find(|s| s.d > d).map(|s| format!("M{}", s.d));
            let near: Vec<String> = [below, above].into_iter().flatten().collect();
            return Err(c.err(
                ds,
                de,
                format!(
                "M{d} is not an ISO 261 diameter (M1 to M68); nearest: {}; non-standard sizes are accepted when allowed (‹allow_nonstandard›)",
                if near.is_empty() { "none".into() } else { near.join(", ") }
            ),
            ));
        }
        nonstandard = true;
    }
    let mut starts = 1u32;
    let pitch;
    let (ps, pe);
    if c.eat("x") || c.eat("X") || c.eat("×") {
        if c.eat("Ph") || c.eat("PH") {
            let (lead, ls, le) = c.number("lead after Ph")?;
            if !c.eat("P") {
                let p = c.pos;
                return Err(c.err(
                    p,
                    p + c.rest().chars().next().map_or(0, char::len_utf8),
                    "expected P and the pitch after the lead (e.g. M24xPh6P2)",
                ));
            }
            let (p, s, e) = c.number("pitch after P")?;
            let n = lead / p;
            if (n - n.round()).abs() > 1e-9 || n.round() < 1.0 {
                return Err(c.err(ls, e, format!("lead {lead} is not a whole multiple of the pitch {p}")));
            }
            if n.round() > 64.0 {
                return Err(c.err(
                    ls,
                    le,
                    format!("{} starts is more than the 64 threadcheck accepts", n.round()),
                ));
            }
            starts = n.round() as u32;
            pitch = p;
            (ps, pe) = (s, e);
        } else {
            let (p, s, e) = c.number("pitch after x")?;
            pitch = p;
            (ps, pe) = (s, e);
        }
        if let Some(s) = &entry {
            let ok =
                s.coarse.is_some_and(|cp| (cp - pitch).abs() < 1e-9) || find_pitch(&s.fine, pitch).is_some();
            if !ok {
                if !opts.allow_nonstandard {
                    return Err(c.err(
                        ps,
                        pe,
                        format!(
                            "{} mm is not an ISO 261 pitch for M{d}; standard pitches: {}; non-standard sizes are accepted when allowed (‹allow_nonstandard›)",
                            fmt_pitch(pitch),
                            standard_pitches(s)
                        ),
                    ));
                }
                nonstandard = true;
            }
        }
    } else {
        match &entry {
            Some(SeriesSize { coarse: Some(p), .. }) => pitch = *p,
            Some(s) => {
                return Err(c.err(
                    ds,
                    de,
                    format!("M{d} has no coarse pitch in ISO 261; give one: {}", standard_pitches(s)),
                ));
            }
            None => {
                return Err(c.err(ds, de, format!("give the pitch of the non-standard size, e.g. M{d}x1.5")))
            }
        }
    }
    if pitch >= d {
        return Err(c.err(
            ds,
            c.pos,
            format!("pitch {} mm is not smaller than the diameter {d} mm", fmt_pitch(pitch)),
        ));
    }
    let thread =
        BasicThread { form: ThreadForm::IsoMetric, nominal_diameter: d, pitch, starts, hand: Hand::Right };
    let mut des =
        Designation { text: c.text.to_string(), thread, external: None, internal: None, nonstandard };
    // Suffixes: -LH, -6g, -6H/6g, -5g6g, in any order, each once.
    while !c.rest().is_empty() {
        let seg_start = c.pos;
        if !c.eat("-") {
            let end = c.pos + c.rest().chars().next().map_or(0, char::len_utf8);
            return Err(c.err(seg_start, end, "expected '-' before a class or LH"));
        }
        let start = c.pos;
        let len = c.rest().find('-').unwrap_or(c.rest().len());
        let seg = &c.rest()[..len];
        if seg.eq_ignore_ascii_case("LH") {
            des.thread.hand = Hand::Left;
        } else if seg.eq_ignore_ascii_case("RH") {
            des.thread.hand = Hand::Right;
        } else {
            if des.external.is_some() || des.internal.is_some() {
                return Err(c.err(start, start + len, "a second tolerance class; write a fit as 6H/6g"));
            }
            parse_iso_classes(c, start, seg, &mut des)?;
        }
        c.pos = start + len;
    }
    Ok(des)
}

fn parse_iso_classes(
    c: &Cursor<'_>,
    start: usize,
    seg: &str,
    des: &mut Designation,
) -> Result<(), DesignationError> {
    if seg.is_empty() {
        return Err(c.err(start, start, "expected a tolerance class such as 6g, 6H or 6H/6g"));
    }
    let mut offset = 0;
    for part in seg.split('/') {
        let s = start + offset;
        let cls = IsoClass::parse(part).map_err(|m| c.err(s, s + part.len(), m))?;
        let slot = if cls.internal { &mut des.internal } else { &mut des.external };
        if slot.is_some() {
            return Err(c.err(
                s,
                s + part.len(),
                format!("two {} classes in one fit", if cls.internal { "internal" } else { "external" }),
            ));
        }
        cls.check_pitch(des.thread.pitch).map_err(|m| c.err(s, s + part.len(), m))?;
        *slot = Some(ClassSpec::Iso(cls));
        offset += part.len() + 1;
    }
    Ok(())
}

/// Reads an inch size `1/2`, `1`, `1 1/4`, `1-1/4`; returns the canonical text (`1 1/4`) and inches.
fn inch_size(c: &mut Cursor<'_>) -> Result<(String, f64, usize, usize), DesignationError> {
    let start = c.pos;
    let len = c
        .rest()
        .char_indices()
        .find(|&(i, ch)| {
            !(ch.is_ascii_digit()
                || ch == '/'
                || ((ch == ' ' || ch == '-') && {
                    // A space or dash is part of the size only between a whole number and a fraction.
                    let after = &c.rest()[i + 1..];
                    let frac = after.split(|x: char| !(x.is_ascii_digit() || x == '/')).next().unwrap_or("");
                    frac.contains('/') && c.rest()[..i].chars().all(|x| x.is_ascii_digit())
                }))
        })
        .map_or(c.rest().len(), |(i, _)| i);
    let raw = &c.rest()[..len];
    let bad =
        |c: &Cursor<'_>| c.err(start, start + len.max(1), "expected an inch size such as 1/2, 1 or 1 1/4");
    if raw.is_empty() {
        return Err(bad(c));
    }
    let norm = raw.replace('-', " ");
    let mut inches = 0.0;
    for tok in norm.split(' ') {
        if let Some((a, b)) = tok.split_once('/') {
            let (a, b): (f64, f64) = (a.parse().map_err(|_| bad(c))?, b.parse().map_err(|_| bad(c))?);
            if b == 0.0 {
                return Err(bad(c));
            }
            inches += a / b;
        } else {
            inches += tok.parse::<f64>().map_err(|_| bad(c))?;
        }
    }
    c.pos += len;
    Ok((norm, inches, start, start + len))
}

/// The general-purpose Acme series of ASME B1.5: size (inches) and threads per inch. Rows to
/// 1 1/8-5 are confirmed by the reference's tables; the larger ones are the standard's series as
/// commonly reprinted (not cross-checked here).
const ACME_SERIES: [(f64, f64); 23] = [
    (0.25, 16.0),
    (0.3125, 14.0),
    (0.375, 12.0),
    (0.4375, 12.0),
    (0.5, 10.0),
    (0.625, 8.0),
    (0.75, 6.0),
    (0.875, 6.0),
    (1.0, 5.0),
    (1.125, 5.0),
    (1.25, 5.0),
    (1.375, 4.0),
    (1.5, 4.0),
    (1.75, 4.0),
    (2.0, 4.0),
    (2.25, 3.0),
    (2.5, 3.0),
    (2.75, 3.0),
    (3.0, 2.0),
    (3.5, 2.0),
    (4.0, 2.0),
    (4.5, 2.0),
    (5.0, 2.0),
];

/// NPT: `1/2-14 NPT`, `1/2 NPT`, `1-1/4-11.5 NPT`; the same designation for pipe and fitting
/// (`--internal` chooses the fitting).
fn parse_npt(c: &mut Cursor<'_>, opts: ParseOptions) -> Result<Designation, DesignationError> {
    let _ = opts;
    let upper = c.text.to_ascii_uppercase();
    let at = upper.find("NPT").unwrap_or(upper.len());
    let head = c.text[..at].trim();
    let cat = catalog().map_err(|e| c.err(0, at, e.to_string()))?;
    let n = &cat.pipe.npt;
    // SIZE[-TPI]: the size may itself hold a dash (1-1/4); try the longest size first.
    let norm = |x: &str| x.replace(' ', "-");
    let found = (0..n.sizes.len())
        .filter(|&i| {
            let h = norm(head);
            let size = norm(&n.sizes[i]);
            h == size
                || h.strip_prefix(&size)
                    .and_then(|r| r.strip_prefix('-'))
                    .is_some_and(|t| t.parse::<f64>().is_ok_and(|t| (t - n.tpi[i]).abs() < 1e-9))
        })
        .max_by_key(|&i| n.sizes[i].len());
    let Some(i) = found else {
        return Err(c.err(
            0,
            at,
            format!(
                "'{head}' is not an NPT size with its tpi; sizes: {}",
                n.sizes.iter().zip(&n.tpi).map(|(s, t)| format!("{s}-{t}")).collect::<Vec<_>>().join(", ")
            ),
        ));
    };
    let mut des = Designation {
        text: c.text.to_string(),
        thread: BasicThread {
            form: ThreadForm::Npt,
            nominal_diameter: (n.E1[i] + 0.8 / n.tpi[i]) * MM_PER_INCH,
            pitch: MM_PER_INCH / n.tpi[i],
            starts: 1,
            hand: Hand::Right,
        },
        external: Some(ClassSpec::Taper(TaperClass { internal: false })),
        internal: Some(ClassSpec::Taper(TaperClass { internal: true })),
        nonstandard: false,
    };
    let rest = c.text[at + 3..].trim().trim_start_matches('-').trim();
    if rest.eq_ignore_ascii_case("LH") {
        des.thread.hand = Hand::Left;
    } else if !rest.is_empty() {
        return Err(c.err(
            at + 3,
            c.text.len(),
            "NPT takes no class (the gauge decides); only LH may follow",
        ));
    }
    c.pos = c.text.len();
    Ok(des)
}

/// ISO 7-1: `R 1/8`, `R1/8` (external taper), `Rc 1/4` (internal taper); `Rp` (internal parallel)
/// is refused: its tolerances are not sourced.
fn parse_iso7(c: &mut Cursor<'_>) -> Result<Designation, DesignationError> {
    let upper = c.text.to_ascii_uppercase();
    let (internal, skip) = if upper.starts_with("RC") {
        (true, 2)
    } else if upper.starts_with("RP") {
        return Err(c.err(0, 2, "Rp (the parallel internal thread of ISO 7-1) is not supported: its tolerances are not in the sources; G (ISO 228-1) is"));
    } else {
        (false, 1)
    };
    c.pos = skip;
    c.skip_spaces();
    let (size, _, ss, se) = inch_size(c)?;
    let cat = catalog().map_err(|e| c.err(ss, se, e.to_string()))?;
    let n = &cat.pipe.iso7;
    let i = n.sizes.iter().position(|x| *x == size).ok_or_else(|| {
        c.err(ss, se, format!("ISO 7-1 has no size {size}\"; sizes: {}", n.sizes.join(", ")))
    })?;
    let mut des = Designation {
        text: c.text.to_string(),
        thread: BasicThread {
            form: ThreadForm::Iso7Taper,
            nominal_diameter: n.d[i],
            pitch: MM_PER_INCH / n.tpi[i],
            starts: 1,
            hand: Hand::Right,
        },
        external: None,
        internal: None,
        nonstandard: false,
    };
    let cls = ClassSpec::Taper(TaperClass { internal });
    if internal {
        des.internal = Some(cls);
    } else {
        des.external = Some(cls);
    }
    let rest = c.rest().trim().trim_start_matches('-').trim();
    if rest.eq_ignore_ascii_case("LH") {
        des.thread.hand = Hand::Left;
    } else if !rest.is_empty() {
        let p = c.pos;
        return Err(c.err(p, c.text.len(), "ISO 7-1 takes no class; only LH may follow the size"));
    }
    c.pos = c.text.len();
    Ok(des)
}

/// The Acme series as (size in inches, threads per inch).
pub fn acme_series() -> impl Iterator<Item = (f64, f64)> {
    ACME_SERIES.into_iter()
}

/// An inch size written `1/2`, `1`, `1 1/4` as inches.
pub fn inch_value(s: &str) -> Option<f64> {
    let mut v = 0.0;
    for tok in s.split([' ', '-']).filter(|t| !t.is_empty()) {
        v += match tok.split_once('/') {
            Some((a, b)) => {
                a.parse::<f64>().ok().zip(b.parse::<f64>().ok()).filter(|x| x.1 > 0.0).map(|(a, b)| a / b)?
            }
            None => tok.parse::<f64>().ok()?,
        };
    }
    Some(v)
}

/// The inch forms' `SIZE-TPI` before the series word `word` (found case-insensitively): the
/// last `-` before it splits them. Returns where the word starts, the dash, the size and the
/// tpi text.
fn size_and_tpi<'t>(
    c: &Cursor<'t>,
    word: &str,
    missing: &str,
) -> Result<(usize, usize, &'t str, &'t str), DesignationError> {
    let upper = c.text.to_ascii_uppercase();
    let at = upper.find(word).unwrap_or(upper.len());
    // `1/2-13-UNC-2A`: a hyphen written where the standard has a blank is read as the blank.
    let head = c.text[..at].trim_end();
    let head = head.strip_suffix('-').unwrap_or(head).trim_end();
    let dash = head.rfind('-').ok_or_else(|| c.err(0, at, missing))?;
    Ok((at, dash, head[..dash].trim(), head[dash + 1..].trim()))
}

/// Acme: `1/2-10 ACME-2G`, `1-5 ACME-3G`, `1 1/4-5 ACME-2G-LH`. The G class is the same for nut
/// and bolt; `--internal` chooses the nut.
fn parse_acme(c: &mut Cursor<'_>, opts: ParseOptions) -> Result<Designation, DesignationError> {
    let (at, _, size_text, tpi_text) =
        size_and_tpi(c, "ACME", "expected SIZE-TPI before ACME, e.g. 1/2-10 ACME-2G")?;
    let bad = |m: &str| c.err(0, at, m.to_string());
    let d = inch_value(size_text)
        .ok_or_else(|| bad("expected an inch size such as 1/2, 1 or 1 1/4 before the tpi"))?;
    let tpi: f64 =
        tpi_text.parse().map_err(|_| bad("expected the threads per inch after the size, e.g. 1/2-10"))?;
    if !(d > 0.0 && tpi > 0.0) {
        return Err(bad("size and threads per inch must be greater than zero"));
    }
    let mut nonstandard = false;
    if !ACME_SERIES.iter().any(|(sd, st)| (sd - d).abs() < 1e-9 && (st - tpi).abs() < 1e-9) {
        if !opts.allow_nonstandard {
            let std_tpi = ACME_SERIES.iter().find(|(sd, _)| (sd - d).abs() < 1e-9).map(|x| x.1);
            let msg = match std_tpi {
                Some(t) => format!("{size_text}-{tpi_text} is not a standard Acme thread: the series has {t} tpi for this size; non-standard sizes are accepted when allowed (‹allow_nonstandard›)"),
                None => format!("{size_text} is not a size of the Acme series (1/4 to 5 in); non-standard sizes are accepted when allowed (‹allow_nonstandard›)"),
            };
            return Err(c.err(0, at, msg));
        }
        nonstandard = true;
    }
    let pitch = MM_PER_INCH / tpi;
    let thread = BasicThread {
        form: ThreadForm::Acme,
        nominal_diameter: d * MM_PER_INCH,
        pitch,
        starts: 1,
        hand: Hand::Right,
    };
    let mut des =
        Designation { text: c.text.to_string(), thread, external: None, internal: None, nonstandard };
    let mut pos = at + 4;
    for part in c.text[at + 4..].split(['-', ' ']) {
        let start = pos;
        pos += part.len() + 1;
        if part.is_empty() {
            continue;
        }
        if part.eq_ignore_ascii_case("LH") {
            des.thread.hand = Hand::Left;
            continue;
        }
        let b = part.as_bytes();
        let grade = match b {
            [g, b'G' | b'g'] => AcmeClass::from_digit(g.wrapping_sub(b'0')),
            _ => None,
        };
        let Some(grade) = grade else {
            return Err(c.err(
                start,
                start + part.len(),
                "expected a general-purpose Acme class 2G, 3G or 4G, or LH",
            ));
        };
        let cls = ClassSpec::Acme(grade);
        des.external = Some(cls);
        des.internal = Some(cls);
    }
    c.pos = c.text.len();
    Ok(des)
}

/// Trapezoidal: `Tr40x7`, `Tr40x7-7e`, `Tr40x7-7H/7e`, `Tr40x14(P7)-8e` (two starts), `Tr40x7LH`
/// or `Tr40x7-LH-7e`.
fn parse_trapezoidal(c: &mut Cursor<'_>, opts: ParseOptions) -> Result<Designation, DesignationError> {
    c.pos = 2;
    let (d, ds, de) = c.number("nominal diameter after Tr")?;
    if !(c.eat("x") || c.eat("X") || c.eat("×")) {
        let p = c.pos;
        return Err(c.err(
            p,
            p + c.rest().chars().next().map_or(0, char::len_utf8),
            "expected x and the pitch (or lead), e.g. Tr40x7",
        ));
    }
    let (first, fs, fe) = c.number("pitch after x")?;
    let (mut pitch, mut starts) = (first, 1u32);
    if c.eat("(P") || c.eat("(p") {
        let (p, _, pe) = c.number("pitch after (P")?;
        if !c.eat(")") {
            return Err(c.err(pe, pe + 1, "expected ')' after the pitch, e.g. Tr40x14(P7)"));
        }
        let n = first / p;
        if (n - n.round()).abs() > 1e-9 || !(1.0..=64.0).contains(&n.round()) {
            return Err(c.err(
                fs,
                c.pos,
                format!("lead {first} is not a whole multiple (1 to 64) of the pitch {p}"),
            ));
        }
        pitch = p;
        starts = n.round() as u32;
    }
    let cat = catalog().map_err(|e| c.err(ds, de, e.to_string()))?;
    let tr = &cat.tr;
    let mut nonstandard = false;
    let listed = tr.series_d.iter().position(|x| (x - d).abs() < 1e-9).map(|i| &tr.series_pitches[i]);
    if !listed.is_some_and(|ps| ps.iter().any(|x| (x - pitch).abs() < 1e-9)) {
        if !opts.allow_nonstandard {
            let msg = match listed {
                Some(ps) => format!(
                    "{pitch} mm is not an ISO 2902 pitch for Tr{d}; standard pitches: {}; non-standard sizes are accepted when allowed (‹allow_nonstandard›)",
                    ps.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(", ")
                ),
                None => format!("Tr{d} is not an ISO 2902 diameter (Tr8 to Tr300); non-standard sizes are accepted when allowed (‹allow_nonstandard›)"),
            };
            return Err(c.err(ds, fe, msg));
        }
        nonstandard = true;
    }
    let thread =
        BasicThread { form: ThreadForm::Trapezoidal, nominal_diameter: d, pitch, starts, hand: Hand::Right };
    let mut des =
        Designation { text: c.text.to_string(), thread, external: None, internal: None, nonstandard };
    if c.eat("LH") || c.eat("lh") {
        des.thread.hand = Hand::Left;
    }
    while !c.rest().is_empty() {
        let seg_start = c.pos;
        if !c.eat("-") {
            let end = c.pos + c.rest().chars().next().map_or(0, char::len_utf8);
            return Err(c.err(seg_start, end, "expected '-' before a class or LH"));
        }
        let start = c.pos;
        let len = c.rest().find('-').unwrap_or(c.rest().len());
        let seg = &c.rest()[..len];
        if seg.eq_ignore_ascii_case("LH") {
            des.thread.hand = Hand::Left;
        } else {
            let mut off = start;
            for part in seg.split('/') {
                let cls = TrClass::parse(part).map_err(|m| c.err(off, off + part.len(), m))?;
                let slot = if cls.internal() { &mut des.internal } else { &mut des.external };
                if slot.is_some() {
                    return Err(c.err(off, off + part.len(), "a second class for the same side"));
                }
                *slot = Some(ClassSpec::Trapezoidal(cls));
                off += part.len() + 1;
            }
        }
        c.pos = start + len;
    }
    Ok(des)
}

/// Unified: `1/4-20 UNC-2A`, `#10-32 UNF-2B/2A`, `0-80 UNF`, `1-8 UNC`, `1 1/4-7 UNC-2A-LH`,
/// `.250-20 UNC`, `2.500-28 UNS-2A`, UNR/UNRC/UNRF/UNREF for the rounded-root external form.
fn parse_unified(c: &mut Cursor<'_>, opts: ParseOptions) -> Result<Designation, DesignationError> {
    let (un_at, dash, size_text, tpi_text) =
        size_and_tpi(c, "UN", "expected SIZE-TPI before the series, e.g. 1/4-20 UNC")?;
    let upper = c.text.to_ascii_uppercase();
    let (ss, se) = (0, dash);
    let (ts, te) = (dash + 1, un_at);
    let number_size = size_text.starts_with('#');
    let st = size_text.trim_start_matches('#');
    // TPI: 20, 4.5 or 4 1/2.
    let tpi = inch_value(tpi_text).filter(|v| *v > 0.0 && v.is_finite()).ok_or_else(|| {
        c.err(ts, te, format!("threads per inch '{tpi_text}' is not a number, e.g. 1/4-20"))
    })?;
    let cat = catalog().map_err(|e| c.err(ss, se, e.to_string()))?;
    let in_series = |row: &super::UnifiedSize| {
        [row.unc, row.unf, row.unef].iter().flatten().any(|t| (t - tpi).abs() < 1e-9)
    };
    let bad_size = || {
        c.err(ss, se, format!("'{size_text}' is not an inch size (1/4, 1 1/4, 0.25) or a number size (#10)"))
    };
    // The basic major diameter, inches: a number size (#N, or N when N-TPI is a number size of
    // the standard series), a fraction, a decimal or a whole number of inches.
    let (d, row) = if st.contains('/') || st.contains(' ') {
        (inch_value(st).ok_or_else(bad_size)?, None)
    } else if st.contains('.') {
        (st.parse::<f64>().map_err(|_| bad_size())?, None)
    } else {
        let n: u32 = st.parse().map_err(|_| bad_size())?;
        let numbered = cat.unified.iter().find(|r| r.name == n.to_string() && r.d < 0.25 - 1e-9);
        match numbered {
            Some(r) if number_size || in_series(r) => (r.d, Some(r)),
            _ if number_size => {
                return Err(c.err(ss, se, format!("#{n} is not a Unified number size (#0 to #12)")))
            }
            _ => (f64::from(n), None),
        }
    };
    if !(d > 0.0) {
        return Err(bad_size());
    }
    let row = row.or_else(|| cat.unified.iter().find(|r| (r.d - d).abs() < 1e-6 && r.d >= 0.25 - 1e-9));
    // The series.
    let rest = &upper[un_at..];
    let sl = rest.find(|ch: char| !ch.is_ascii_alphabetic()).unwrap_or(rest.len());
    let word = &rest[..sl];
    let (series, unr) = match word {
        "UNC" => (UnifiedSeries::Unc, false),
        "UNF" => (UnifiedSeries::Unf, false),
        "UNEF" => (UnifiedSeries::Unef, false),
        "UN" => (UnifiedSeries::Un, false),
        "UNS" => (UnifiedSeries::Uns, false),
        "UNRC" => (UnifiedSeries::Unc, true),
        "UNRF" => (UnifiedSeries::Unf, true),
        "UNREF" => (UnifiedSeries::Unef, true),
        "UNR" => (UnifiedSeries::Un, true),
        _ => {
            return Err(c.err(
                un_at,
                un_at + sl,
                format!(
                    "'{word}' is not a Unified series: UNC, UNF, UNEF, UN, UNS (UNR… for the rounded root)"
                ),
            ))
        }
    };
    let mut nonstandard = false;
    let standard = match series {
        UnifiedSeries::Unc => row.and_then(|r| r.unc),
        UnifiedSeries::Unf => row.and_then(|r| r.unf),
        UnifiedSeries::Unef => row.and_then(|r| r.unef),
        UnifiedSeries::Un => {
            [4.0, 6.0, 8.0, 12.0, 16.0, 20.0, 28.0, 32.0].into_iter().find(|t| (t - tpi).abs() < 1e-9)
        }
        UnifiedSeries::Uns => Some(tpi),
    };
    if standard.is_none_or(|t| (t - tpi).abs() > 1e-9) {
        if !opts.allow_nonstandard {
            let what = match standard {
                Some(t) => format!("the {} thread of this size has {t} tpi", series.name(false)),
                None if series == UnifiedSeries::Un => {
                    "the constant-pitch UN series has 4, 6, 8, 12, 16, 20, 28 and 32 tpi".into()
                }
                None => format!("the {} series has no size {size_text}", series.name(false)),
            };
            return Err(c.err(ss, te, format!("{size_text}-{tpi_text} is not a standard {} thread: {what}; write UNS for a special thread, or non-standard sizes are accepted when allowed (‹allow_nonstandard›)", series.name(false))));
        }
        nonstandard = true;
    }
    let pitch = MM_PER_INCH / tpi;
    let thread = BasicThread {
        form: ThreadForm::Unified,
        nominal_diameter: d * MM_PER_INCH,
        pitch,
        starts: 1,
        hand: Hand::Right,
    };
    if pitch >= thread.nominal_diameter {
        return Err(c.err(ss, te, "the pitch is not smaller than the diameter"));
    }
    let mut des =
        Designation { text: c.text.to_string(), thread, external: None, internal: None, nonstandard };
    // Classes and hand: -2A, -2B, -2B/2A, -LH, separated by '-' or blanks.
    let mut pos = un_at + sl;
    for part in c.text[pos..].split(['-', ' ']) {
        let start = pos;
        pos += part.len() + 1;
        if part.is_empty() {
            continue;
        }
        if part.eq_ignore_ascii_case("LH") {
            des.thread.hand = Hand::Left;
            continue;
        }
        if part.eq_ignore_ascii_case("RH") {
            continue;
        }
        let mut off = start;
        for cls in part.split('/') {
            let b = cls.as_bytes();
            let parsed = match b {
                [g, side @ (b'A' | b'a' | b'B' | b'b')] => UnifiedGrade::from_digit(g.wrapping_sub(b'0'))
                    .map(|grade| (grade, matches!(side, b'B' | b'b'))),
                _ => None,
            };
            let Some((grade, internal)) = parsed else {
                return Err(c.err(off, off + cls.len(), "expected a Unified class 1A, 2A, 3A (external), 1B, 2B, 3B (internal), a fit 2B/2A, or LH"));
            };
            let uc = UnifiedClass { grade, internal, series, unr: unr && !internal };
            let slot = if internal { &mut des.internal } else { &mut des.external };
            if slot.is_some() {
                return Err(c.err(off, off + cls.len(), "a second class for the same side"));
            }
            *slot = Some(ClassSpec::Unified(uc));
            off += cls.len() + 1;
        }
    }
    c.pos = c.text.len();
    Ok(des)
}

fn parse_whitworth(c: &mut Cursor<'_>, opts: ParseOptions) -> Result<Designation, DesignationError> {
    let fine = c.text[..3].eq_ignore_ascii_case("BSF");
    c.pos = 3;
    c.skip_spaces();
    let (size, inches, ss, se) = inch_size(c)?;
    let cat = catalog().map_err(|e| c.err(ss, se, e.to_string()))?;
    let list = if fine { &cat.bsf } else { &cat.bsw };
    let series = if fine { "BSF" } else { "BSW" };
    let tpi = match list.iter().find(|s| s.size == size) {
        Some(s) => s.tpi,
        None => {
            let sizes: Vec<&str> = list.iter().map(|s| s.size.as_str()).collect();
            return Err(c.err(ss, se, format!("{series} has no size {size}\"; sizes: {}", sizes.join(", "))));
        }
    };
    let _ = opts;
    let thread = BasicThread {
        form: ThreadForm::Whitworth,
        nominal_diameter: inches * MM_PER_INCH,
        pitch: MM_PER_INCH / tpi,
        starts: 1,
        hand: Hand::Right,
    };
    let mut des =
        Designation { text: c.text.to_string(), thread, external: None, internal: None, nonstandard: false };
    loop {
        c.skip_spaces();
        if c.rest().is_empty() {
            break;
        }
        let start = c.pos;
        let len = c.rest().find(' ').unwrap_or(c.rest().len());
        let word = &c.rest()[..len];
        if word.eq_ignore_ascii_case("LH") {
            des.thread.hand = Hand::Left;
        } else {
            let (ext, int) = Bs84Class::parse(word).ok_or_else(|| {
                c.err(
                    start,
                    start + len,
                    "unknown BS 84 class; bolts: close, medium, free; nuts: close, medium, normal",
                )
            })?;
            if des.external.is_some() || des.internal.is_some() {
                return Err(c.err(start, start + len, "a second class"));
            }
            des.external = ext.map(ClassSpec::Bs84);
            des.internal = int.map(ClassSpec::Bs84);
        }
        c.pos = start + len;
    }
    Ok(des)
}

fn parse_bsp(c: &mut Cursor<'_>) -> Result<Designation, DesignationError> {
    c.pos = 1;
    c.skip_spaces();
    let (size, _inches, ss, se) = inch_size(c)?;
    let cat = catalog().map_err(|e| c.err(ss, se, e.to_string()))?;
    let Some(entry) = cat.bsp.iter().find(|s| s.size == size) else {
        let sizes: Vec<&str> = cat.bsp.iter().map(|s| s.size.as_str()).collect();
        return Err(c.err(ss, se, format!("ISO 228-1 has no size G{size}; sizes: {}", sizes.join(", "))));
    };
    let thread = BasicThread {
        form: ThreadForm::BspParallel,
        nominal_diameter: entry.d,
        pitch: MM_PER_INCH / entry.tpi,
        starts: 1,
        hand: Hand::Right,
    };
    let mut des =
        Designation { text: c.text.to_string(), thread, external: None, internal: None, nonstandard: false };
    let mut class_given = false;
    loop {
        c.skip_spaces();
        if c.rest().is_empty() {
            break;
        }
        let start = c.pos;
        let len = c.rest().find(' ').unwrap_or(c.rest().len());
        let word = &c.rest()[..len];
        match word {
            "A" | "a" if !class_given => des.external = Some(ClassSpec::Iso228(Iso228Class::A)),
            "B" | "b" if !class_given => des.external = Some(ClassSpec::Iso228(Iso228Class::B)),
            w if w.eq_ignore_ascii_case("LH") => des.thread.hand = Hand::Left,
            _ => {
                return Err(c.err(start, start + len, "expected the ISO 228-1 class A or B (external) or LH; an internal G thread has no class letter"));
            }
        }
        class_given |= word.eq_ignore_ascii_case("A") || word.eq_ignore_ascii_case("B");
        c.pos = start + len;
    }
    if !class_given {
        // ISO 228-1 designates the internal thread by size alone: G1/2.
        des.internal = Some(ClassSpec::Iso228(Iso228Class::Internal));
    }
    Ok(des)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(s: &str) -> Result<Designation, crate::Error> {
        parse_designation(s, ParseOptions::default())
    }

    #[test]
    fn accepts_the_documented_forms() {
        for s in [
            "M10",
            "M10x1.25",
            "M10x1.25-6g",
            "M10-6H/6g",
            "M10x1-5g6g",
            "M16x1.5-LH-6g",
            "M24xPh6P2-6g",
            "BSW 1/2",
            "BSF 3/8 medium",
            "G1/2",
            "G1/2 A",
            "M10-6H",
            "BSW 1 1/4 close",
            "G1 1/4 B",
        ] {
            assert!(p(s).is_ok(), "{s}: {:?}", p(s));
        }
    }

    #[test]
    fn coarse_pitch_multi_start_and_hand() {
        assert_eq!(p("M10").unwrap().thread.pitch, 1.5);
        let d = p("M24xPh6P2-6g").unwrap();
        // Ph6 / P2: three starts (the issue text says two; Ph/P = 3).
        assert_eq!((d.thread.pitch, d.thread.starts, d.thread.lead()), (2.0, 3, 6.0));
        assert_eq!(p("M16x1.5-LH-6g").unwrap().thread.hand, Hand::Left);
        let fit = p("M10-6H/6g").unwrap();
        assert!(fit.internal.is_some() && fit.external.is_some());
        let g = p("G1/2").unwrap();
        assert!(g.internal.is_some() && g.external.is_none());
        let bsw = p("BSW 1/2").unwrap();
        assert!((bsw.thread.pitch - 25.4 / 12.0).abs() < 1e-12);
        assert!((bsw.thread.nominal_diameter - 12.7).abs() < 1e-12);
    }

    #[test]
    fn nonstandard_pitch_lists_the_standard_ones() {
        let e = p("M10x1.3-6g").unwrap_err().to_string();
        assert!(e.contains("column 5") && e.contains("'1.3'"), "{e}");
        assert!(e.contains("1.5 (coarse); 1.25, 1, 0.75 (fine)"), "{e}");
        let ok = parse_designation("M10x1.3", ParseOptions { allow_nonstandard: true }).unwrap();
        assert!(ok.nonstandard);
    }

    /// Regression: the random-string proptest found a panic slicing inside a multi-byte character.
    #[test]
    fn regression_error_span_inside_a_multibyte_character() {
        for s in ["¡", "M¡", "M10x¡", "BSW ¡", "G¡", "M10-6¡", "Mé10"] {
            assert!(p(s).is_err(), "{s}");
        }
    }

    #[test]
    fn errors_name_the_bad_part() {
        let e = p("Q10").unwrap_err().to_string();
        assert!(e.contains("column 1"), "{e}");
        let e = p("M10x1.5-6q").unwrap_err().to_string();
        assert!(e.contains("'6q'"), "{e}");
        let e = p("BSW 9/13").unwrap_err().to_string();
        assert!(e.contains("'9/13'"), "{e}");
        let e = p("M10x1.5-3h").unwrap_err().to_string();
        assert!(e.contains("major-diameter"), "{e}");
    }
}
