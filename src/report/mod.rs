//! The `verify` report: JSON as the CLI contract specifies, and the human table.

pub mod batch;
pub mod capability;
pub mod compare;
pub mod correct;
pub mod fit;
pub(crate) mod kit;
pub mod limits;
pub mod lsp;
pub mod mill;
pub(crate) mod output;
pub mod passes;
pub mod sweep;
pub mod tap;
pub mod thread_mill;
pub mod verify;

pub use limits::LimitsReport;
pub use passes::PassesReport;
pub use sweep::{CaseError, PlacementsLine};
pub use verify::{
    program_text, read_past_text, verify_text, CorrectionReport, ProgramReport, ThreadReport, VerifyReport,
};

pub(crate) use crate::ground::fmt::fmt_num;
use crate::toolpath::passes::Schedule;
use serde::Serialize;

fn schedule_text(s: &Schedule) -> &'static str {
    s.name()
}

/// The `measured` object: the as-cut tooth.
#[derive(Clone, Debug, Serialize)]
pub struct MeasuredReport {
    /// mm.
    pub major_diameter: f64,
    /// mm.
    pub pitch_diameter: f64,
    /// mm.
    pub minor_diameter: f64,
    /// Smallest root radius, mm.
    pub root_radius: Option<f64>,
    /// Half angles of the low-z and high-z flank, degrees.
    pub flank_angles: [f64; 2],
    /// Crest to root, mm.
    pub thread_depth: f64,
    /// Radial overlap with the basic mating part, mm.
    pub engagement_depth: f64,
    /// Crest flat, mm.
    pub crest_width: f64,
    /// The highest fin or notch inside the groove, mm (0: the profile falls cleanly from each
    /// crest to the root).
    pub fin_height: f64,
    /// Best wire and the measurement over three wires, mm.
    pub three_wire: Option<crate::geometry::measure::ThreeWire>,
    /// Signed clearance to the maximum-material profile, mm.
    pub max_material_clearance: Option<f64>,
    /// The functional (virtual) pitch diameter, where the program's lead deviates, mm.
    pub functional_pitch_diameter: Option<f64>,
}

impl MeasuredReport {
    /// The `measured` object of a measurement (and the functional d2 where a lead deviates).
    pub fn of(m: &crate::geometry::measure::Measurement, functional_pitch_diameter: Option<f64>) -> Self {
        MeasuredReport {
            major_diameter: m.major_diameter,
            pitch_diameter: m.pitch_diameter,
            minor_diameter: m.minor_diameter,
            root_radius: m.root_radius,
            flank_angles: m.flank_angles,
            thread_depth: m.thread_depth,
            engagement_depth: m.engagement_depth,
            crest_width: m.crest_width,
            fin_height: m.fin_height,
            three_wire: m.three_wire,
            max_material_clearance: m.max_material_clearance,
            functional_pitch_diameter,
        }
    }
}

/// How a report writes a length: in the reader's unit, and in inch with the mm beside it where
/// a reader might check it against a drawing in mm. Inches at the inch standards' resolution
/// (0.0001 in: four decimals), millimetres at four decimals (0.1 µm).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Lengths(pub crate::analysis::turn::Units);

impl Lengths {
    /// Whether lengths are in inches.
    pub(crate) fn inch(self) -> bool {
        self.0 == crate::analysis::turn::Units::Inch
    }

    /// A length's number in the reader's unit, four decimals: `12.6994`, `0.5000`.
    pub(crate) fn number(self, mm: f64) -> String {
        if self.inch() {
            format!("{:.4}", mm / 25.4)
        } else {
            format!("{mm:.4}")
        }
    }

    /// A length with its unit, the mm beside the inches: `12.6994 mm`, `0.5000 in (12.6994 mm)`.
    pub(crate) fn both(self, mm: f64) -> String {
        if self.inch() {
            format!("{:.4} in ({mm:.4} mm)", mm / 25.4)
        } else {
            format!("{mm:.4} mm")
        }
    }

    /// A diameter word or value as the program writes it (`X12.6994`, `X0.5000 (12.6994 mm)`):
    /// `prefix` and the number, the mm beside in inch.
    pub(crate) fn word(self, prefix: &str, mm: f64) -> String {
        if self.inch() {
            format!("{prefix}{:.4} ({mm:.4} mm)", mm / 25.4)
        } else {
            format!("{prefix}{mm:.4}")
        }
    }

    /// A lead to six decimals with its unit: `1.500000 mm`, `0.076923 in (1.953846 mm)`.
    pub(crate) fn lead(self, mm: f64) -> String {
        if self.inch() {
            format!("{:.6} in ({mm:.6} mm)", mm / 25.4)
        } else {
            format!("{mm:.6} mm")
        }
    }

    /// A deviation's size, unsigned or `signed`: `38.4 µm`, `0.0015 in (38.4 µm)`; an inch
    /// deviation under the inch resolution gets a fifth decimal rather than reading 0.0000.
    pub(crate) fn deviation(self, um: f64, signed: bool) -> String {
        let sign = |v: f64, d: usize| if signed { format!("{v:+.d$}") } else { format!("{:.d$}", v.abs()) };
        if self.inch() {
            let inch = um / 25_400.0;
            format!("{} in ({} µm)", sign(inch, inch_places(inch)), sign(um, 1))
        } else {
            format!("{} µm", sign(um, 1))
        }
    }

    /// A deviation in a table's cell, the reader's unit alone: `+38.4 µm`, `+0.0015 in`.
    pub(crate) fn deviation_cell(self, um: f64) -> String {
        if self.inch() {
            let inch = um / 25_400.0;
            let d = inch_places(inch);
            format!("{inch:+.d$} in")
        } else {
            format!("{um:+.1} µm")
        }
    }
}

/// A correction's new value at the program's increment: `0.2948` (inch), `0.930` (mm).
fn correction_number(c: &crate::analysis::turn::correction::Correction) -> String {
    match c.units {
        crate::gcode::ProgramUnits::Mm => format!("{:.3}", c.value),
        crate::gcode::ProgramUnits::Inch => format!("{:.4}", c.value),
    }
}

/// A correction's new word as the program would write it: `X0.2948`, `K0.930`, `TDEP=0.930`,
/// `R24=0.930`.
pub fn correction_word(c: &crate::analysis::turn::correction::Correction) -> String {
    use crate::gcode::WordForm;
    match c.form {
        WordForm::Number | WordForm::Expression => format!("{}{}", c.word, correction_number(c)),
        WordForm::Argument | WordForm::ArgumentExpression | WordForm::Parameter => {
            format!("{}={}", c.word, correction_number(c))
        }
    }
}

/// What replaces the word in place to apply a correction: the whole word (`X19.452`), or a
/// call's argument alone (`1.597`); `None` where it cannot be rewritten in place.
pub fn correction_replacement(c: &crate::analysis::turn::correction::Correction) -> Option<String> {
    use crate::gcode::WordForm;
    match c.form {
        WordForm::Number => Some(correction_word(c)),
        WordForm::Argument => Some(correction_number(c)),
        WordForm::Expression | WordForm::ArgumentExpression | WordForm::Parameter => None,
    }
}

/// A form failure's hint as a sentence: what to change, since no final X fixes it.
pub fn hint_text(h: &crate::analysis::check::Hint) -> String {
    use crate::analysis::check::Hint;
    match *h {
        Hint::TipRadius { tip_radius, root_radius_min } => format!(
            "the insert's tip radius {} mm is under the standard's root radius {} mm, which no final X changes: use a full-profile insert (‹insert› full) or a tip of {} mm or more; ‹gauge_only› judges the sizes and the GO gauge alone",
            fmt_num(tip_radius),
            fmt_num(root_radius_min),
            fmt_num(root_radius_min)
        ),
        Hint::FlankAngle { half_angle } => format!(
            "a flank stands steeper than {}°: the infeed angle (or the insert's angle) is over the flank's; infeed at {}° or a little less",
            fmt_num(half_angle),
            fmt_num(half_angle)
        ),
        Hint::Groove => "the passes do not follow one groove (a fin, a notch or a second pocket): check the infeed angle against the flank and every pass's start phase".into(),
    }
}

/// The sentence of a correction: `change X19.462 at line 12 to X19.452 (mm, diameter)`.
pub fn correction_text(c: &crate::analysis::turn::correction::Correction) -> String {
    let what = match c.means {
        crate::gcode::WordMeans::Diameter => "diameter",
        crate::gcode::WordMeans::Radius => "radius",
        crate::gcode::WordMeans::Depth { .. } => "thread depth",
    };
    let mut at = format!("line {}:{}", c.line, c.column);
    if !c.also.is_empty() {
        let more: Vec<String> = c.also.iter().map(|p| format!("{}:{}", p.line, p.column)).collect();
        at = format!("lines {}:{} and {} (one cycle per start)", c.line, c.column, more.join(", "));
    }
    let word = &c.word;
    let place = match c.form {
        crate::gcode::WordForm::Number => format!("change {} at {at} to {}", c.written, correction_word(c)),
        // A call's argument: `change TDEP 1.400 at line 3:34 to 1.597`.
        crate::gcode::WordForm::Argument => {
            format!("change {word} {} at {at} to {}", c.written, correction_number(c))
        }
        crate::gcode::WordForm::Expression | crate::gcode::WordForm::ArgumentExpression => {
            format!("make {word} (written {} at {at}) {}", c.written, correction_word(c))
        }
        crate::gcode::WordForm::Parameter => {
            format!("set {word} (read by the call at line {}) to {}", c.line, correction_word(c))
        }
    };
    let mut text = format!("{place} ({}, {what})", c.units.name());
    if !c.deeper.is_empty() {
        let words: Vec<String> =
            c.deeper.iter().map(|d| format!("{} at line {}:{}", d.written, d.line, d.column)).collect();
        let (verb, them) = if words.len() == 1 { ("cuts", "it") } else { ("cut", "them") };
        text.push_str(&format!(
            "; {} {verb} deeper than that: set {them} to {} too",
            words.join(" and "),
            correction_word(c)
        ));
    }
    text
}

/// A value with `prec` decimals, or a dash when there is none.
pub(crate) fn opt(v: Option<f64>, prec: usize) -> String {
    v.map_or_else(|| "—".to_string(), |x| format!("{x:.prec$}"))
}

/// A check's value, limits and deviation as the tables show them, each in the check's own
/// unit: lengths to 0.1 µm with the deviation in µm, angles to 0.001°, speeds and feeds whole,
/// yes/no checks in words; the deviation is empty inside the limits.
#[derive(Clone, Debug, Serialize)]
pub(crate) struct CheckCells {
    pub value: String,
    pub min: String,
    pub max: String,
    pub deviation: String,
    /// The value's and limits' unit (`mm`, `°`, `turn`, `rpm`, `mm/min`; empty for counts,
    /// tapers and yes/no).
    pub unit: &'static str,
}

/// A check as the JSON gives it: its numbers, and (`shown`) its cells as every table shows
/// them, so that the page reads like the SVG's table (yes/no in words, signed deviations in the
/// check's unit).
#[derive(Clone, Debug, Serialize)]
pub struct CheckReport<'a> {
    #[serde(flatten)]
    check: &'a crate::analysis::check::Check,
    shown: CheckCells,
}

pub(crate) fn check_cells(c: &crate::Check, lengths: Lengths) -> CheckCells {
    use crate::CheckUnit as U;
    let unit = c.feature.unit();
    // In inch, lengths and feeds in inches (a length at the inch standards' 0.0001 in).
    if lengths.inch() && matches!(unit, U::Mm | U::MmPerMin) {
        return inch_cells(c, unit == U::MmPerMin);
    }
    let prec = match unit {
        U::Mm => 4,
        U::Degree | U::Turn => 3,
        U::DiameterPerLength => 5,
        U::Count | U::Rpm | U::MmPerMin | U::YesNo => 0,
    };
    let lim = |v: Option<f64>| if unit == U::YesNo { String::new() } else { opt(v, prec) };
    let value = match unit {
        U::YesNo => (if c.value != 0.0 { "yes" } else { "no" }).to_string(),
        _ => format!("{:.prec$}", c.value),
    };
    let over = past_limit(c);
    let deviation = deviation_words(c, || match unit {
        U::Mm => format!("{:+.1} µm", c.deviation_um),
        U::Degree => format!("{over:+.3}°"),
        U::Turn => format!("{over:+.3} turn"),
        U::DiameterPerLength => format!("{over:+.5}"),
        U::Count => format!("{over:+.0}"),
        U::Rpm => format!("{over:+.0} rpm"),
        U::MmPerMin => format!("{over:+.0} mm/min"),
        U::YesNo => String::new(),
    });
    let unit = match unit {
        U::Mm => "mm",
        U::Degree => "°",
        U::Turn => "turn",
        U::Rpm => "rpm",
        U::MmPerMin => "mm/min",
        U::Count | U::DiameterPerLength | U::YesNo => "",
    };
    CheckCells { value, min: lim(c.min), max: lim(c.max), deviation, unit }
}

/// The decimals an inch length is shown to: the inch standards' four (0.0001 in), five for one
/// under that resolution that would otherwise read 0.0000 (a crest's 0.001 mm, a small deviation).
fn inch_places(inch: f64) -> usize {
    if (inch.abs() * 1e4).round() == 0.0 {
        5
    } else {
        4
    }
}

/// Outside the limits: by how much, in the check's unit (lengths as the analysis measured them,
/// to the true limit); 0 within them.
fn past_limit(c: &crate::Check) -> f64 {
    match (c.min, c.max) {
        (_, Some(max)) if c.value > max => c.value - max,
        (Some(min), _) if c.value < min => c.value - min,
        _ => 0.0,
    }
}

/// A check's deviation cell: empty within its limits, `outside()` past them, and `rounds to the
/// limit` for a value past its limit that is within it at the standard's resolution (1 µm;
/// 0.0001 in), so that a value shown past its shown limit never passes without a word.
fn deviation_words(c: &crate::Check, outside: impl FnOnce() -> String) -> String {
    match (c.ok, past_limit(c) != 0.0) {
        (true, true) => "rounds to the limit".to_string(),
        (true, false) => String::new(),
        (false, _) => outside(),
    }
}

/// The cells of a length (or a feed, `feed`) in inches: four decimals (a feed in in/min, one),
/// the deviation in inches.
fn inch_cells(c: &crate::Check, feed: bool) -> CheckCells {
    let (prec, unit) = if feed { (1, "in/min") } else { (4, "in") };
    // A length under the inch resolution but not nil (a crest's 0.001 mm) gets its fifth decimal.
    let n = |v: f64| {
        let inch = v / 25.4;
        let p = if feed || inch == 0.0 { prec } else { inch_places(inch) };
        format!("{inch:.p$}")
    };
    let deviation = deviation_words(c, || {
        if feed {
            format!("{:+.1} in/min", past_limit(c) / 25.4)
        } else {
            Lengths(crate::analysis::turn::Units::Inch).deviation_cell(c.deviation_um)
        }
    });
    let lim = |v: Option<f64>| v.map_or_else(|| "—".to_string(), n);
    CheckCells { value: n(c.value), min: lim(c.min), max: lim(c.max), deviation, unit }
}

/// The JSON text of a report: pretty, with a final newline.
pub fn to_json_pretty<T: Serialize>(v: &T) -> Result<String, crate::Error> {
    let mut s = serde_json::to_string_pretty(v).map_err(|e| crate::Error::Data(e.to_string()))?;
    s.push('\n');
    Ok(s)
}

/// The JSON text of a report on one line, with a final newline (JSON Lines).
pub fn to_json_line<T: Serialize>(v: &T) -> Result<String, crate::Error> {
    let mut s = serde_json::to_string(v).map_err(|e| crate::Error::Data(e.to_string()))?;
    s.push('\n');
    Ok(s)
}

/// A hole's percent of thread in words (issue 64): `77 % (the charts' percent: 100 % is 0.6495·P
/// a side), 88.7 % of the basic height D − D1`.
pub(crate) fn thread_percent_words(t: &crate::analysis::percent::ThreadPercent) -> String {
    use crate::ground::fmt::fmt_num;
    format!(
        "{} % (the charts' percent: 100 % is 0.6495·P a side), {} % of the basic height D − D1",
        fmt_num((t.percent * 10.0).round() / 10.0),
        fmt_num((t.of_basic_height * 10.0).round() / 10.0)
    )
}
