//! The correction in the program's own words: the change of the word that sets an operation's
//! final depth (the last X of a G76, G92 run or G32 chain; LinuxCNC G76 K; CYCLE97 and CYCLE99 TDEP; L97
//! R24; L96 R15) that moves the pitch diameter by a given amount, in the program's units and X
//! mode, rounded to its least increment.

use crate::gcode::{DepthWord, PassXWord, ProgramUnits, WordForm, WordMeans};
use crate::standards::ThreadKind;
use serde::Serialize;

/// A word to change and its new value.
///
/// ```
/// use threadcheck::{correction, DepthWord, ProgramUnits, ThreadKind, WordForm, WordMeans};
/// // A G20 program's last pass at X.2953 (diameter, inches) leaves d2 12.7 µm over mid: the
/// // tip goes 0.0127 mm = 0.0005 in deeper.
/// let w = DepthWord { word: "X".into(), value: 0.2953, line: 9, column: 1, written: "X.2953".into(),
///     form: WordForm::Number, means: WordMeans::Diameter };
/// let c = correction(&w, ProgramUnits::Inch, ThreadKind::External, -0.0127);
/// assert_eq!(c.word, "X");
/// assert!((c.value - 0.2948).abs() < 1e-12);
/// // LinuxCNC G76 K (radial depth, radius mode): d2 down by 20 µm is K 0.010 mm deeper.
/// let k = DepthWord { word: "K".into(), value: 0.92, line: 3, column: 30, written: "K0.92".into(),
///     form: WordForm::Number, means: WordMeans::Depth { per_radial: 1.0 } };
/// assert!((correction(&k, ProgramUnits::Mm, ThreadKind::External, -0.020).value - 0.930).abs() < 1e-12);
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Correction {
    /// The word's address (`X`, `K`, `TDEP`, `R24`, `R15`).
    pub word: String,
    /// Its new value, program units, rounded to the program's least increment.
    pub value: f64,
    /// Its value now, program units.
    pub was: f64,
    /// The program's units.
    pub units: ProgramUnits,
    /// Where the word is written (for an R-parameter: the cycle call that reads it).
    pub line: usize,
    /// Its column.
    pub column: usize,
    /// How the word is written (in the JSON: `editable`, whether `--fix` rewrites it).
    #[serde(rename = "editable", serialize_with = "editable")]
    pub form: WordForm,
    /// The word as written now.
    pub written: String,
    /// What the word measures.
    pub means: WordMeans,
    /// The same word in the cycles of the thread's other starts (one cycle per start): changed
    /// the same way. Empty for one cycle.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub also: Vec<Place>,
    /// Earlier passes' X words that cut deeper than the new value (a correction that makes the
    /// thread shallower): each set to the new value too, or the thread stays as they cut it.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub deeper: Vec<Deeper>,
}

/// An earlier pass's X word that cuts deeper than a correction's new value.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Deeper {
    /// Line, from 1.
    pub line: usize,
    /// Column, from 1.
    pub column: usize,
    /// The word as written now.
    pub written: String,
    /// Whether `--fix` rewrites it (a plain number in place).
    #[serde(rename = "editable", serialize_with = "editable")]
    pub form: WordForm,
}

/// The words of `words` (the X words that set an operation's passes) that cut deeper than the
/// new value of `c`, an X correction of a thread of `kind`, over the stretch of Z the corrected
/// word's passes span: beyond it toward the axis (external) or away from it (internal). A taper
/// segment elsewhere on the thread is not one of them. None for a correction of a depth word
/// (G76 K, TDEP, …): its cycle lays the passes out anew.
///
/// ```
/// use threadcheck::{correction, deeper_words, DepthWord, PassXWord, ProgramUnits, ThreadKind, WordForm, WordMeans};
/// let w = |x: f64, line| PassXWord {
///     word: DepthWord { word: "X".into(), value: x, line, column: 1, written: format!("X{x}"),
///         form: WordForm::Number, means: WordMeans::Diameter },
///     z_min: -20.0, z_max: 4.0 };
/// // A G92 run X9.9, X9.5, X9.32 whose d2 is 0.3486 mm small: the last becomes X9.669, and the
/// // X9.5 before it cuts deeper than that.
/// let c = correction(&w(9.32, 12).word, ProgramUnits::Mm, ThreadKind::External, 0.3486);
/// let d = deeper_words(&c, &[w(9.9, 10), w(9.5, 11), w(9.32, 12)], ThreadKind::External);
/// assert_eq!(d.iter().map(|d| d.line).collect::<Vec<_>>(), [11]);
/// ```
pub fn deeper_words(c: &Correction, words: &[PassXWord], kind: ThreadKind) -> Vec<Deeper> {
    // Distances from the axis: a tool beyond it writes them negative (issue 47).
    let diameter = |v: f64, m: WordMeans| match m {
        WordMeans::Diameter => Some(v.abs()),
        WordMeans::Radius => Some(2.0 * v.abs()),
        WordMeans::Depth { .. } => None,
    };
    let Some(new) = diameter(c.value, c.means) else { return Vec::new() };
    let at = |w: &DepthWord| w.line == c.line && w.column == c.column;
    let Some(own) = words.iter().find(|w| at(&w.word)) else { return Vec::new() };
    // Compared at a tenth of the program's increment: a word equal to the new value is not deeper.
    let tol = 0.1 * c.units.least_increment();
    words
        .iter()
        .filter(|w| w.word.word == c.word && !at(&w.word))
        .filter(|w| w.z_min.max(own.z_min) < w.z_max.min(own.z_max))
        .filter(|w| {
            diameter(w.word.value, w.word.means).is_some_and(|x| match kind {
                ThreadKind::External => x < new - tol,
                ThreadKind::Internal => x > new + tol,
            })
        })
        .map(|w| Deeper {
            line: w.word.line,
            column: w.word.column,
            written: w.word.written.clone(),
            form: w.word.form,
        })
        .collect()
}

/// A word's place: line and column.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Place {
    /// Line, from 1.
    pub line: usize,
    /// Column, from 1.
    pub column: usize,
}

/// The change of `w` that moves the pitch diameter by `delta_d2` mm (+ larger), for a thread of
/// `kind` in a program written in `units`.
pub fn correction(w: &DepthWord, units: ProgramUnits, kind: ThreadKind, delta_d2: f64) -> Correction {
    let per_unit = units.mm();
    // A tool beyond the spindle axis writes X negative (issue 47): its size moves, its sign stays.
    let side = if w.value < 0.0 { -1.0 } else { 1.0 };
    let raw = match w.means {
        WordMeans::Diameter => w.value + side * delta_d2 / per_unit,
        WordMeans::Radius => w.value + side * 0.5 * delta_d2 / per_unit,
        WordMeans::Depth { per_radial } => {
            // Deeper is a smaller bolt and a larger nut.
            let deeper = match kind {
                ThreadKind::External => -0.5 * delta_d2,
                ThreadKind::Internal => 0.5 * delta_d2,
            };
            let size = w.value.abs() + deeper * per_radial / per_unit;
            if w.value < 0.0 {
                -size
            } else {
                size
            }
        }
    };
    let inc = units.least_increment();
    let value = (raw / inc).round() * inc;
    // Rounded to the increment, printed without binary noise.
    let value = format!("{value:.4}").parse::<f64>().unwrap_or(value);
    debug_assert!(value.is_finite());
    Correction {
        word: w.word.clone(),
        value,
        was: w.value,
        units,
        line: w.line,
        column: w.column,
        form: w.form,
        written: w.written.clone(),
        means: w.means,
        also: Vec::new(),
        deeper: Vec::new(),
    }
}

/// A word form as the JSON gives it: whether `--fix` rewrites it.
fn editable<S: serde::Serializer>(form: &WordForm, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_bool(form.editable())
}
