//! Tolerance classes and limits of size: ISO 965-1 (metric), BS 84 (Whitworth), ISO 228-1 (BSP).
//!
//! ISO 965-1 limits come from the standard's **tables** (shipped in `profiles/iso-metric.toml`),
//! not from its formulas, which only approximate the tables. Grades other than 6 are the
//! tabulated grade-6 value times the grade factor, rounded to the nearest R40 preferred number.
//! Limits are rounded to 0.001 mm after the basic diameters have been rounded to 0.001 mm, as the
//! tables print them.

use crate::ground::fmt::fmt_num;
use crate::standards::data::{catalog, find_pitch, IsoTables};
use crate::standards::{BasicThread, ClassSpec, Designation, ThreadForm, ThreadKind};
use crate::Error;
use serde::Serialize;
use std::fmt;

/// An ISO 965-1 tolerance position: `e f g h` for bolts, `G H` for nuts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IsoPosition {
    /// e (bolts only).
    E,
    /// f (bolts only).
    F,
    /// g (bolts) or G (nuts).
    G,
    /// h (bolts) or H (nuts): zero fundamental deviation.
    H,
}

impl IsoPosition {
    /// Reads a position letter of either case.
    fn from_letter(c: char) -> Option<IsoPosition> {
        match c.to_ascii_lowercase() {
            'e' => Some(IsoPosition::E),
            'f' => Some(IsoPosition::F),
            'g' => Some(IsoPosition::G),
            'h' => Some(IsoPosition::H),
            _ => None,
        }
    }

    /// The letter, upper case for nuts.
    pub fn letter(self, internal: bool) -> char {
        let c = match self {
            IsoPosition::E => 'e',
            IsoPosition::F => 'f',
            IsoPosition::G => 'g',
            IsoPosition::H => 'h',
        };
        if internal {
            c.to_ascii_uppercase()
        } else {
            c
        }
    }

    /// Whether ISO 965-1 defines the position for nuts (`internal`) or bolts.
    fn exists(self, internal: bool) -> bool {
        match self {
            IsoPosition::E | IsoPosition::F => !internal,
            IsoPosition::G | IsoPosition::H => true,
        }
    }
}

/// An ISO 965-1 tolerance grade, 3 to 9 (which of them a diameter has is the standard's table).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IsoGrade {
    /// Grade 3.
    G3,
    /// Grade 4.
    G4,
    /// Grade 5.
    G5,
    /// Grade 6.
    G6,
    /// Grade 7.
    G7,
    /// Grade 8.
    G8,
    /// Grade 9.
    G9,
}

impl IsoGrade {
    /// Reads a grade digit.
    fn from_digit(d: u32) -> Option<IsoGrade> {
        Some(match d {
            3 => IsoGrade::G3,
            4 => IsoGrade::G4,
            5 => IsoGrade::G5,
            6 => IsoGrade::G6,
            7 => IsoGrade::G7,
            8 => IsoGrade::G8,
            9 => IsoGrade::G9,
            _ => return None,
        })
    }

    /// The grade's number.
    pub fn number(self) -> u8 {
        match self {
            IsoGrade::G3 => 3,
            IsoGrade::G4 => 4,
            IsoGrade::G5 => 5,
            IsoGrade::G6 => 6,
            IsoGrade::G7 => 7,
            IsoGrade::G8 => 8,
            IsoGrade::G9 => 9,
        }
    }
}

impl fmt::Display for IsoGrade {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.number())
    }
}

/// An ISO 965-1 class: pitch-diameter grade and position, crest-diameter grade and position.
/// `5g6g` is pitch 5g, crest 6g; `6g` is both. Lower-case positions are external, upper-case
/// internal.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct IsoClass {
    /// True for an internal (nut) class.
    pub internal: bool,
    /// Tolerance grade of the pitch diameter (3–9 external, 4–8 internal).
    pub pitch_grade: IsoGrade,
    /// Position of the pitch diameter (`e f g h`; `G H` for nuts).
    pub pitch_position: IsoPosition,
    /// Tolerance grade of the crest diameter (major d: 4, 6, 8; minor D1: 4–8).
    pub crest_grade: IsoGrade,
    /// Position of the crest diameter.
    pub crest_position: IsoPosition,
}

impl IsoClass {
    /// Parses `6g`, `5g6g`, `6H`, `4H5H`.
    pub fn parse(s: &str) -> Result<IsoClass, String> {
        let b: Vec<char> = s.chars().collect();
        let pair = |g: char, p: char| -> Result<(IsoGrade, IsoPosition, bool), String> {
            let digit = g.to_digit(10).ok_or_else(|| format!("'{g}' is not a tolerance grade (a digit)"))?;
            if !p.is_ascii_alphabetic() {
                return Err(format!("'{p}' is not a tolerance position letter"));
            }
            let internal = p.is_ascii_uppercase();
            let side = if internal { "internal" } else { "external" };
            let positions = if internal { "G, H" } else { "e, f, g, h" };
            let position = IsoPosition::from_letter(p)
                .filter(|q| q.exists(internal))
                .ok_or_else(|| format!("position {p} is not an ISO 965-1 {side} position ({positions})"))?;
            let grade = IsoGrade::from_digit(digit).ok_or_else(|| {
                format!(
                    "grade {digit} has no pitch-diameter tolerance (grades {})",
                    if internal { "4..8" } else { "3..9" }
                )
            })?;
            Ok((grade, position, internal))
        };
        let ((pg, pp, pi), (cg, cp, ci)) = match b.as_slice() {
            [g, p] => {
                let a = pair(*g, *p)?;
                (a, a)
            }
            [g1, p1, g2, p2] => (pair(*g1, *p1)?, pair(*g2, *p2)?),
            _ => return Err("expected a tolerance class such as 6g, 5g6g, 6H or 6H/6g".into()),
        };
        if pi != ci {
            return Err("mixes an internal (upper-case) and an external (lower-case) position".into());
        }
        let c = IsoClass {
            internal: pi,
            pitch_grade: pg,
            pitch_position: pp,
            crest_grade: cg,
            crest_position: cp,
        };
        c.validate()?;
        Ok(c)
    }

    fn validate(&self) -> Result<(), String> {
        use IsoGrade::{G3, G4, G5, G6, G7, G8, G9};
        let (pitch_ok, crest_ok, pitch_range, crest_name) = if self.internal {
            (
                matches!(self.pitch_grade, G4 | G5 | G6 | G7 | G8),
                matches!(self.crest_grade, G4 | G5 | G6 | G7 | G8),
                "4..8",
                "minor-diameter (TD1) grades are 4 to 8",
            )
        } else {
            (
                matches!(self.pitch_grade, G3 | G4 | G5 | G6 | G7 | G8 | G9),
                matches!(self.crest_grade, G4 | G6 | G8),
                "3..9",
                "major-diameter (Td) grades are 4, 6 and 8",
            )
        };
        if !pitch_ok {
            return Err(format!(
                "grade {} has no pitch-diameter tolerance (grades {pitch_range})",
                self.pitch_grade
            ));
        }
        if !crest_ok {
            return Err(format!(
                "grade {} has no crest tolerance: {crest_name}; write both grades, e.g. {}{}6{}",
                self.crest_grade,
                self.pitch_grade,
                self.pitch_position.letter(self.internal),
                self.crest_position.letter(self.internal)
            ));
        }
        Ok(())
    }

    /// Checks that the positions are defined at this pitch (e is tabulated from 0.5 mm, f from
    /// 0.35 mm).
    pub fn check_pitch(&self, pitch: f64) -> Result<(), String> {
        let Ok(cat) = catalog() else { return Ok(()) };
        let fd = &cat.iso.fundamental_deviations;
        for p in [self.pitch_position, self.crest_position] {
            let list = match p {
                IsoPosition::E => &fd.pitches_e,
                IsoPosition::F => &fd.pitches_f,
                IsoPosition::G | IsoPosition::H => &fd.pitches,
            };
            if find_pitch(list, pitch).is_none() {
                let shown = p.letter(self.internal);
                return Err(format!("ISO 965-1 tabulates no deviation of position {shown} for P = {pitch} mm (it does for P = {}..{} mm)", list[0], list[list.len() - 1]));
            }
        }
        Ok(())
    }
}

impl fmt::Display for IsoClass {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let c = |p: IsoPosition| p.letter(self.internal);
        if self.pitch_grade == self.crest_grade && self.pitch_position == self.crest_position {
            write!(f, "{}{}", self.pitch_grade, c(self.pitch_position))
        } else {
            write!(
                f,
                "{}{}{}{}",
                self.pitch_grade,
                c(self.pitch_position),
                self.crest_grade,
                c(self.crest_position)
            )
        }
    }
}

/// BS 84 classes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bs84Class {
    /// Close (bolts and nuts): 2/3·T.
    Close,
    /// Medium (bolts and nuts): T.
    Medium,
    /// Free (bolts): 3/2·T.
    Free,
    /// Normal (nuts): 3/2·T.
    Normal,
}

impl Bs84Class {
    /// Reads a class word; returns the (external, internal) classes it names. `medium` and
    /// `close` exist for bolts and nuts, `free` only for bolts, `normal` only for nuts.
    pub fn parse(word: &str) -> Option<(Option<Bs84Class>, Option<Bs84Class>)> {
        match word.to_ascii_lowercase().as_str() {
            "close" => Some((Some(Bs84Class::Close), Some(Bs84Class::Close))),
            "medium" => Some((Some(Bs84Class::Medium), Some(Bs84Class::Medium))),
            "free" => Some((Some(Bs84Class::Free), None)),
            "normal" => Some((None, Some(Bs84Class::Normal))),
            _ => None,
        }
    }

    fn factor(self) -> f64 {
        match self {
            Bs84Class::Close => 2.0 / 3.0,
            Bs84Class::Medium => 1.0,
            Bs84Class::Free | Bs84Class::Normal => 1.5,
        }
    }
}

impl fmt::Display for Bs84Class {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Bs84Class::Close => "close",
            Bs84Class::Medium => "medium",
            Bs84Class::Free => "free",
            Bs84Class::Normal => "normal",
        })
    }
}

/// ISO 228-1 classes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Iso228Class {
    /// External class A (the finer).
    A,
    /// External class B.
    B,
    /// The single internal class.
    Internal,
}

impl fmt::Display for Iso228Class {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Iso228Class::A => "A",
            Iso228Class::B => "B",
            Iso228Class::Internal => "internal",
        })
    }
}

/// A limit pair in mm; a missing side is unbounded.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Default)]
pub struct Limit {
    /// Largest allowed value, mm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max: Option<f64>,
    /// Smallest allowed value, mm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min: Option<f64>,
}

impl Limit {
    /// Both sides.
    pub fn new(min: f64, max: f64) -> Limit {
        Limit { min: Some(min), max: Some(max) }
    }

    /// Middle of the zone, if both sides exist.
    pub fn mid(&self) -> Option<f64> {
        Some(0.5 * (self.min? + self.max?))
    }

    /// Distance outside the zone in mm (0 inside).
    pub fn deviation(&self, v: f64) -> f64 {
        if let Some(mx) = self.max {
            if v > mx {
                return v - mx;
            }
        }
        if let Some(mn) = self.min {
            if v < mn {
                return v - mn;
            }
        }
        0.0
    }
}

/// Limits of size of one thread (external or internal) in one class, mm.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ThreadLimits {
    /// External or internal.
    #[serde(skip)]
    pub kind: ThreadKind,
    /// The class as written (`6g`, `medium`, `A`).
    pub class: String,
    /// Major diameter d (external: max and min) or D (internal: min only).
    pub major_diameter: Limit,
    /// Pitch diameter d2 / D2.
    pub pitch_diameter: Limit,
    /// Minor diameter. External metric: max = d1 + es (flat-form limit), min = d3 min =
    /// d2 min − H + P/4 (lowest root contour). Internal: D1 min and max.
    pub minor_diameter: Limit,
    /// Smallest root radius of the bolt, mm (ISO 965-1: 0.125·P), if the standard sets one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub root_radius_min: Option<f64>,
    /// Fundamental deviation of the pitch diameter, µm (es ≤ 0 for bolts, EI ≥ 0 for nuts).
    pub fundamental_deviation_um: f64,
    /// Fundamental deviation of the crest diameter, µm.
    #[serde(skip)]
    pub crest_deviation_um: f64,
    /// Assumptions behind values that the sources do not settle.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
    /// Taper threads: where the gauge plane must lie, instead of pitch-diameter limits.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gauge_plane: Option<GaugePlane>,
    /// The resolution the standard's tables print limits to (1 µm for ISO 965-1, BS 84, ISO
    /// 228-1, ISO 2903 and the pipe tapers; 0.0001 in for ASME B1.1 and B1.5): sizes are
    /// compared at it. In JSON, `resolution_mm`.
    #[serde(rename = "resolution_mm")]
    pub resolution: Resolution,
}

/// Which limits a coated thread's class applies to.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum CoatingLimits {
    /// The standards' default: the class's limits apply to the part before coating (ISO 965-1
    /// §8.5 and ISO 965-3 §4: "unless otherwise stated"; ASME B1.1 §7: the limits of 1A and 2A
    /// apply before coating, the allowance taking the coat), and after coating the thread shall
    /// not pass the maximum-material limits of position h/H (a basic GO gauge accepts it): the
    /// maximum-material side is capped at the basic size less the coat's growth (d2 ≤ basic −
    /// 4t on a 60° bolt, D2 ≥ basic + 4t in a nut), rounded inward to the standard's resolution.
    #[default]
    Before,
    /// The drawing says the class applies after coating: every limit moves by the coat's growth,
    /// away from the coating.
    After,
}

impl std::str::FromStr for CoatingLimits {
    type Err = crate::Error;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.to_ascii_lowercase().as_str() {
            "before" => Ok(CoatingLimits::Before),
            "after" => Ok(CoatingLimits::After),
            _ => Err(crate::Error::Input(format!(
                "coating limits '{s}': before (the standards' default: the class applies before coating) or after (the drawing says after)"
            ))),
        }
    }
}

impl ThreadLimits {
    /// The limits to cut to before a coating of `thickness` mm (plating, anodizing) on thread
    /// `t`, by `rule`. A coat of thickness t grows a bolt's major and minor diameters by 2t and
    /// its pitch diameter by 2t / sin β (4t for a 60° thread, as ASME B1.1 states for coated
    /// threads); a nut's shrink by as much.
    ///
    /// ```
    /// use threadcheck::{limits_for, parse_designation, CoatingLimits, ParseOptions, ThreadKind};
    /// let d = parse_designation("M10x1.5-6g", ParseOptions::default())?;
    /// let l = limits_for(&d, ThreadKind::External)?.unwrap();
    /// // A 10 µm coat on a 60° bolt. The standards' rule: d2 8.862–8.994 of 6g, its maximum capped
    /// // at basic 9.026 − 4t = 8.986 so that the coated bolt stays within h.
    /// let pre = l.for_coating(0.010, &d.thread, CoatingLimits::Before);
    /// assert_eq!((pre.pitch_diameter.min, pre.pitch_diameter.max), (Some(8.862), Some(8.986)));
    /// // The class after coating (a drawing that says so): 8.822–8.954.
    /// let after = l.for_coating(0.010, &d.thread, CoatingLimits::After);
    /// assert!((after.pitch_diameter.max.unwrap() - 8.954).abs() < 1e-12);
    /// # Ok::<(), threadcheck::Error>(())
    /// ```
    pub fn for_coating(
        &self,
        thickness: f64,
        t: &crate::standards::BasicThread,
        rule: CoatingLimits,
    ) -> ThreadLimits {
        let half_angle_rad = t.half_angle();
        debug_assert!(thickness >= 0.0 && half_angle_rad > 0.0);
        let away = match self.kind {
            ThreadKind::External => -1.0,
            ThreadKind::Internal => 1.0,
        };
        let (pitch, size) = (away * coat_pitch_growth(thickness, half_angle_rad), away * 2.0 * thickness);
        // To 1e-9 mm: the limits are µm (or 0.1 mil) values, the shift is no reason for float noise.
        let nm = |v: f64| (v * 1e9).round() / 1e9;
        let mut notes = self.notes.clone();
        let um = |v: f64| fmt_num((v.abs() * 1e4).round() / 10.0);
        match rule {
            CoatingLimits::After => {
                let shift = |l: Limit, by: f64| Limit {
                    max: l.max.map(|v| nm(v + by)),
                    min: l.min.map(|v| nm(v + by)),
                };
                notes.push(format!(
                    "limits before a coating of {} mm, the class applying after coating (‹coating_limits› after, as the drawing says): the class's moved {} µm {} on the pitch diameter (2t / sin {}°) and {} µm on the major and minor diameters (2t)",
                    fmt_num(thickness),
                    um(pitch),
                    if away < 0.0 { "down" } else { "up" },
                    fmt_num((half_angle_rad.to_degrees() * 1e4).round() / 1e4),
                    um(size),
                ));
                ThreadLimits {
                    notes,
                    major_diameter: shift(self.major_diameter, size),
                    pitch_diameter: shift(self.pitch_diameter, pitch),
                    minor_diameter: shift(self.minor_diameter, size),
                    gauge_plane: self
                        .gauge_plane
                        .map(|g| GaugePlane { pitch_diameter: nm(g.pitch_diameter + pitch), ..g }),
                    ..self.clone()
                }
            }
            CoatingLimits::Before => {
                // The maximum-material side capped at the basic size less the growth, rounded
                // inward to the standard's step.
                let step = self.resolution.mm();
                let inward = |v: f64| match self.kind {
                    ThreadKind::External => nm(((v / step) + 1e-9).floor() * step),
                    ThreadKind::Internal => nm(((v / step) - 1e-9).ceil() * step),
                };
                // A size as the standard prints it: mm to 1 µm, or inches to 0.0001 in.
                let shown = |v: f64| match self.resolution {
                    Resolution::Micrometre => format!("{v:.3}"),
                    Resolution::TenThousandthInch => format!("{:.4} in", v / crate::standards::MM_PER_INCH),
                };
                let mut capped = Vec::new();
                let mut cap = |l: Limit, basic: f64, growth: f64, name: &str| -> Limit {
                    // The basic size as the tables print it (9.026 for M10x1.5's d2).
                    let basic = self.resolution.round(basic);
                    let bound = inward(basic + growth);
                    match self.kind {
                        ThreadKind::External => match l.max {
                            Some(m) if m > bound + 1e-9 => {
                                capped.push(format!(
                                    "{name} max {} → {} (basic {} − {} µm)",
                                    shown(m),
                                    shown(bound),
                                    shown(basic),
                                    um(growth)
                                ));
                                Limit { max: Some(bound), ..l }
                            }
                            _ => l,
                        },
                        ThreadKind::Internal => match l.min {
                            Some(m) if m < bound - 1e-9 => {
                                capped.push(format!(
                                    "{name} min {} → {} (basic {} + {} µm)",
                                    shown(m),
                                    shown(bound),
                                    shown(basic),
                                    um(growth)
                                ));
                                Limit { min: Some(bound), ..l }
                            }
                            _ => l,
                        },
                    }
                };
                // The bolt's major and pitch diameters, the nut's every diameter (its major, the
                // root the coat fills, included).
                let (major_diameter, pitch_diameter, minor_diameter) = match self.kind {
                    ThreadKind::External => (
                        cap(self.major_diameter, t.nominal_diameter, size, "d"),
                        cap(self.pitch_diameter, t.pitch_diameter(), pitch, "d2"),
                        self.minor_diameter,
                    ),
                    ThreadKind::Internal => (
                        cap(self.major_diameter, t.nominal_diameter, size, "D"),
                        cap(self.pitch_diameter, t.pitch_diameter(), pitch, "D2"),
                        cap(self.minor_diameter, t.minor_diameter_internal(), size, "D1"),
                    ),
                };
                notes.push(format!(
                    "limits before a coating of {} mm: the class's own, which the standards apply before coating (ISO 965-1 §8.5, ASME B1.1 §7; ‹coating_limits› after when the drawing says otherwise); after coating the thread must stay within the basic profile (h/H): {}",
                    fmt_num(thickness),
                    if capped.is_empty() { "no limit needs moving".to_string() } else { capped.join(", ") }
                ));
                ThreadLimits { notes, major_diameter, pitch_diameter, minor_diameter, ..self.clone() }
            }
        }
    }
}

/// How much a coat of `thickness` mm grows a bolt's pitch diameter on flanks `half_angle_rad`
/// from the radial: 2t / sin β (4t on a 60° thread); a nut's shrinks as much.
pub fn coat_pitch_growth(thickness: f64, half_angle_rad: f64) -> f64 {
    2.0 * thickness / half_angle_rad.sin()
}

/// The resolution a standard prints its limits to, and so the one sizes are compared at: a limit
/// exactly met passes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Resolution {
    /// 0.001 mm (the metric tables).
    Micrometre,
    /// 0.0001 in (the inch tables).
    TenThousandthInch,
}

impl Resolution {
    /// The step, mm.
    pub fn mm(self) -> f64 {
        match self {
            Resolution::Micrometre => 0.001,
            Resolution::TenThousandthInch => 0.0001 * crate::standards::MM_PER_INCH,
        }
    }

    /// `mm` rounded to this resolution, the way the limits themselves were rounded (in inches,
    /// then converted, for the inch tables), so that a value on a limit compares equal to it.
    pub fn round(self, mm: f64) -> f64 {
        match self {
            Resolution::Micrometre => round_um(mm),
            Resolution::TenThousandthInch => {
                let inch = crate::standards::MM_PER_INCH;
                ((mm / inch) * 10_000.0).round() / 10_000.0 * inch
            }
        }
    }
}

impl Serialize for Resolution {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_f64(self.mm())
    }
}

/// A taper thread's gauge plane: the pitch diameter the gauge checks, where it must lie and how
/// far off it may lie.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct GaugePlane {
    /// The basic pitch diameter at the gauge plane (NPT E1, ISO 7-1 d2), mm.
    pub pitch_diameter: f64,
    /// Its basic distance from the reference end, mm: from the small end for an external thread
    /// (NPT L1, ISO 7-1 gauge length), 0 (the face) for an internal one.
    pub distance: f64,
    /// The gauging tolerance, turns either way (±1: ASME B1.20.1 for NPT; applied to ISO 7-1 too).
    pub tolerance_turns: f64,
    /// Taper on the diameter per mm.
    pub taper: f64,
}

/// A taper pipe thread's designation side: the pipe (external) or the fitting (internal); its
/// class is written `taper` (the gauge decides, there is no class letter).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TaperClass {
    /// The fitting (NPT internal, Rc).
    pub internal: bool,
}

impl fmt::Display for TaperClass {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("taper")
    }
}

/// The diameter a thread's designation names, mm: the nominal diameter d, but for NPT the pipe's
/// outside diameter (ASME B1.20.1's D, from which E0 is reckoned: 0.840 in for 1/2 NPT), where
/// the thread's own major diameter at the gauge plane (E1 + 0.8·P) is not the size's name.
/// ISO 7-1 names its sizes by the gauge plane's major diameter, the nominal diameter itself.
pub fn named_diameter(t: &BasicThread) -> f64 {
    match t.form {
        ThreadForm::Npt => catalog()
            .ok()
            .and_then(|cat| {
                let n = &cat.pipe.npt;
                (0..n.sizes.len())
                    .find(|&i| {
                        ((n.E1[i] + 0.8 / n.tpi[i]) * crate::standards::MM_PER_INCH - t.nominal_diameter)
                            .abs()
                            < 1e-6
                    })
                    .map(|i| n.OD[i] * crate::standards::MM_PER_INCH)
            })
            .unwrap_or(t.nominal_diameter),
        ThreadForm::IsoMetric
        | ThreadForm::Whitworth
        | ThreadForm::BspParallel
        | ThreadForm::Unified
        | ThreadForm::Trapezoidal
        | ThreadForm::Acme
        | ThreadForm::Iso7Taper => t.nominal_diameter,
    }
}

/// The gauge-plane limits of a taper pipe thread (`profiles/pipe-taper.toml`): the basic pitch
/// diameter at the gauge plane (NPT E1; ISO 7-1 d2), its distance (external: L1 or the gauge
/// length from the small end; internal: at the face), and ±1 turn of gauging tolerance, stated as
/// an assumption. The diameters at the gauge plane are given for reference, not checked.
pub fn taper_limits(t: &BasicThread, c: TaperClass) -> Result<ThreadLimits, Error> {
    let cat = catalog()?;
    let inch = crate::standards::MM_PER_INCH;
    let (e1, l1, label, gauging) = match t.form {
        ThreadForm::Npt => {
            let n = &cat.pipe.npt;
            let i = (0..n.sizes.len())
                .find(|&i| ((n.E1[i] + 0.8 / n.tpi[i]) * inch - t.nominal_diameter).abs() < 1e-6)
                .ok_or_else(|| Error::Input("not an NPT size".into()))?;
            (n.E1[i] * inch, n.L1[i] * inch, "ASME B1.20.1 E1 and L1", "ASME B1.20.1 §4.1.2 and §7: the L1 gauge may stand one turn large or small of its basic notch")
        }
        ThreadForm::Iso7Taper => {
            let n = &cat.pipe.iso7;
            let i = (0..n.sizes.len())
                .find(|&i| (n.d[i] - t.nominal_diameter).abs() < 1e-6)
                .ok_or_else(|| Error::Input("not an ISO 7-1 size".into()))?;
            (
                n.d2[i],
                n.gauge_length_basic[i],
                "ISO 7-1 gauge-plane d2 and gauge length",
                "one turn applied as for NPT: ISO 7-1's own tolerances on the gauge plane's position (±T1/2, ±T2/2, larger than a turn for the large sizes) are not checked: no public copy of its table was found (looked at: JIS B 0203's published size table, ISO 7-2's front matter, shop pages on ISO 7-1)",
            )
        }
        ThreadForm::IsoMetric
        | ThreadForm::Whitworth
        | ThreadForm::BspParallel
        | ThreadForm::Unified
        | ThreadForm::Trapezoidal
        | ThreadForm::Acme => {
            return Err(Error::Input(format!("the {} form is not a taper thread", t.form.name())))
        }
    };
    let d = t.nominal_diameter;
    let d1 = t.minor_diameter_internal();
    Ok(ThreadLimits {
        kind: if c.internal { ThreadKind::Internal } else { ThreadKind::External },
        class: c.to_string(),
        major_diameter: Limit { min: Some(round_um(d)), max: Some(round_um(d)) },
        pitch_diameter: Limit::new(e1, e1),
        minor_diameter: Limit { min: Some(round_um(d1)), max: Some(round_um(d1)) },
        root_radius_min: None,
        fundamental_deviation_um: 0.0,
        crest_deviation_um: 0.0,
        notes: vec![format!(
            "taper 1:16; the gauge plane ({label}) may lie ±1 turn from its basic position ({gauging}); diameters are at the gauge plane, for reference"
        )],
        gauge_plane: Some(GaugePlane {
            pitch_diameter: e1,
            distance: if c.internal { 0.0 } else { l1 },
            tolerance_turns: 1.0,
            taper: 1.0 / 16.0,
        }),
        resolution: Resolution::Micrometre,
    })
}

/// Rounds mm to the micrometre, as the tables print.
pub fn round_um(mm: f64) -> f64 {
    (mm * 1000.0).round() / 1000.0
}

/// Rounds a tolerance (µm) to the nearest R40 preferred number in the logarithmic sense, with
/// the R′40 integer forms below 100 µm (23.6 → 24, 26.5 → 26, …), as ISO 965-1 prints them.
pub fn r40(x_um: f64, r40_table: &[f64]) -> f64 {
    // R'40 rounded forms for the decade 10..100, index-aligned with the R40 mantissae.
    const R40_ROUNDED: [f64; 40] = [
        10.0, 10.5, 11.0, 12.0, 12.5, 13.0, 14.0, 15.0, 16.0, 17.0, 18.0, 19.0, 20.0, 21.0, 22.0, 24.0, 25.0,
        26.0, 28.0, 30.0, 32.0, 34.0, 36.0, 38.0, 40.0, 42.0, 45.0, 48.0, 50.0, 53.0, 56.0, 60.0, 63.0, 67.0,
        71.0, 75.0, 80.0, 85.0, 90.0, 95.0,
    ];
    let k = (40.0 * x_um.log10()).round() as i64;
    let idx = k.rem_euclid(40) as usize;
    let decade = k.div_euclid(40);
    if decade == 1 {
        return R40_ROUNDED[idx];
    }
    let v = r40_table.get(idx).copied().unwrap_or(1.0) * 10f64.powi(decade as i32);
    // Values are whole micrometres from 100 µm up; strip the float noise of powi.
    (v * 100.0).round() / 100.0
}

fn iso_tables() -> Result<&'static IsoTables, Error> {
    Ok(&catalog()?.iso)
}

fn deviation_um(t: &IsoTables, position: IsoPosition, internal: bool, pitch: f64) -> Result<f64, Error> {
    let fd = &t.fundamental_deviations;
    let (list, vals): (&[f64], &[i32]) = match (position, internal) {
        (IsoPosition::E, false) => (&fd.pitches_e, &fd.es_e),
        (IsoPosition::F, false) => (&fd.pitches_f, &fd.es_f),
        (IsoPosition::G, false) => (&fd.pitches, &fd.es_g),
        (IsoPosition::H, false) => (&fd.pitches, &fd.es_h),
        (IsoPosition::G, true) => (&fd.pitches, &fd.ei_g),
        (IsoPosition::H, true) => (&fd.pitches, &fd.ei_h),
        (IsoPosition::E | IsoPosition::F, true) => {
            return Err(Error::Input(format!("ISO 965-1 has no internal position {}", position.letter(true))))
        }
    };
    let i = find_pitch(list, pitch).ok_or_else(|| {
        Error::Input(format!("ISO 965-1 tabulates no fundamental deviation for P = {pitch} mm"))
    })?;
    Ok(f64::from(vals[i]))
}

/// Td2(6) external and TD2(6) internal (µm) for the diameter range of `d`, tabulated where the
/// pitch is listed for that range, else the ISO 965-1 formula on the range's geometric mean
/// diameter (noted).
fn td2_grade6(t: &IsoTables, d: f64, pitch: f64, notes: &mut Vec<String>) -> Result<(f64, f64), Error> {
    let range = t.td2_grade6.ranges.iter().find(|r| r.over < d && d <= r.up_to).ok_or_else(|| {
        Error::Input(format!("ISO 965-1 tables cover diameters over 0.99 up to 355 mm, not {d} mm"))
    })?;
    if let Some(i) = find_pitch(&range.pitches, pitch) {
        return Ok((range.td2_external[i], range.td2_internal[i]));
    }
    let dm = (range.over * range.up_to).sqrt();
    let ext = r40(90.0 * pitch.powf(0.4) * dm.powf(0.1), &t.rounding.r40);
    let int = r40(1.32 * ext, &t.rounding.r40);
    notes.push(format!(
        "Td2(6) for P = {pitch} mm in the range {}..{} mm is not tabulated; ISO 965-1 formula 90·P^0.4·d^0.1 used ({ext} µm)",
        range.over, range.up_to
    ));
    Ok((ext, int))
}

fn pitch_table(pitches: &[f64], vals: &[f64], pitch: f64, what: &str) -> Result<f64, Error> {
    find_pitch(pitches, pitch)
        .map(|i| vals[i])
        .ok_or_else(|| Error::Input(format!("ISO 965-1 tabulates no {what} for P = {pitch} mm")))
}

fn graded(t: &IsoTables, base: f64, factor: Option<f64>, grade: IsoGrade, what: &str) -> Result<f64, Error> {
    let f = factor.ok_or_else(|| Error::Input(format!("ISO 965-1 has no grade {grade} for {what}")))?;
    if f == 1.0 {
        return Ok(base);
    }
    Ok(r40(f * base, &t.rounding.r40))
}

/// Limits of an ISO metric thread in an ISO 965-1 class.
///
/// ```
/// use threadcheck::{iso_limits, BasicThread, IsoClass};
/// let l = iso_limits(&BasicThread::metric(10.0, 1.5), &IsoClass::parse("6H").expect("a class"))?;
/// // ISO 965-2, M10x1.5-6H: D2 9.026 to 9.206, D1 8.376 to 8.676.
/// assert_eq!((l.pitch_diameter.min, l.pitch_diameter.max), (Some(9.026), Some(9.206)));
/// assert_eq!((l.minor_diameter.min, l.minor_diameter.max), (Some(8.376), Some(8.676)));
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn iso_limits(thread: &BasicThread, class: &IsoClass) -> Result<ThreadLimits, Error> {
    let t = iso_tables()?;
    let p = thread.pitch;
    let d = thread.nominal_diameter;
    let h = thread.fundamental_height();
    let mut notes = Vec::new();
    let d_b = round_um(d);
    let d2_b = round_um(thread.pitch_diameter());
    let d1_b = round_um(thread.minor_diameter_internal());
    let dev = deviation_um(t, class.pitch_position, class.internal, p)?;
    let dev_crest = deviation_um(t, class.crest_position, class.internal, p)?;
    let (td2_6, _td2_int_6) = td2_grade6(t, d, p, &mut notes)?;
    let gf = &t.grade_factors;
    let mm = |um: f64| um / 1000.0;
    if !class.internal {
        let td2 = graded(t, td2_6, gf.td2.get(class.pitch_grade.number()), class.pitch_grade, "Td2")?;
        let td6 = pitch_table(&t.td_grade6.pitches, &t.td_grade6.td, p, "major-diameter tolerance Td")?;
        let td = graded(t, td6, gf.td.get(class.crest_grade.number()), class.crest_grade, "Td")?;
        let dmax = round_um(d_b + mm(dev_crest));
        let d2max = round_um(d2_b + mm(dev));
        let d2min = round_um(d2max - mm(td2));
        Ok(ThreadLimits {
            kind: ThreadKind::External,
            class: class.to_string(),
            major_diameter: Limit::new(round_um(dmax - mm(td)), dmax),
            pitch_diameter: Limit::new(d2min, d2max),
            minor_diameter: Limit::new(round_um(d2min - h + p / 4.0), round_um(d1_b + mm(dev))),
            root_radius_min: thread.min_root_radius(),
            fundamental_deviation_um: dev,
            crest_deviation_um: dev_crest,
            notes,
            gauge_plane: None,
            resolution: Resolution::Micrometre,
        })
    } else {
        // TD2 of every grade is a factor times the EXTERNAL tabulated Td2(6).
        let td2 =
            graded(t, td2_6, gf.td2_internal.get(class.pitch_grade.number()), class.pitch_grade, "TD2")?;
        let td1 = match find_pitch(&t.td1_grade6.pitches, p) {
            Some(i) => graded(
                t,
                t.td1_grade6.td1[i],
                gf.td1.get(class.crest_grade.number()),
                class.crest_grade,
                "TD1",
            )?,
            None => {
                // P 0.2 and 0.25 carry only fine grades (ISO 965-1 Table 3).
                let fine = match (class.crest_grade, (p * 100.0).round() as i64) {
                    (IsoGrade::G4, 20) => Some(38.0),
                    (IsoGrade::G4, 25) => Some(45.0),
                    (IsoGrade::G5, 25) => Some(56.0),
                    _ => None,
                };
                fine.ok_or_else(|| {
                    Error::Input(format!(
                        "ISO 965-1 has no TD1 of grade {} for P = {p} mm",
                        class.crest_grade
                    ))
                })?
            }
        };
        let d2min = round_um(d2_b + mm(dev));
        let d1min = round_um(d1_b + mm(dev_crest));
        Ok(ThreadLimits {
            kind: ThreadKind::Internal,
            class: class.to_string(),
            major_diameter: Limit { min: Some(round_um(d_b + mm(dev))), max: None },
            pitch_diameter: Limit::new(d2min, round_um(d2min + mm(td2))),
            minor_diameter: Limit::new(d1min, round_um(d1min + mm(td1))),
            root_radius_min: None,
            fundamental_deviation_um: dev,
            crest_deviation_um: dev_crest,
            notes,
            gauge_plane: None,
            resolution: Resolution::Micrometre,
        })
    }
}

/// Limits of a BSW/BSF thread in a BS 84 class. Computed in inches from the BS 84 formula with
/// the length of engagement L = D and no allowance (both stated in `notes`), rounded to
/// 0.0001 in as BS 84 prints, then converted to mm and rounded to 0.001 mm.
pub fn bs84_limits(thread: &BasicThread, class: Bs84Class, kind: ThreadKind) -> ThreadLimits {
    let inch = |mm: f64| mm / 25.4;
    let big_d = inch(thread.nominal_diameter);
    let p = inch(thread.pitch);
    let l = big_d;
    let t = 0.002 * big_d.cbrt() + 0.003 * l.sqrt() + 0.005 * p.sqrt();
    let k = class.factor();
    let h = 0.640327 * p;
    let r4 = |x: f64| (x * 10_000.0).round() / 10_000.0;
    let mm = |x: f64| round_um(r4(x) * 25.4);
    let e = big_d - h;
    let d1 = big_d - 2.0 * h;
    let tpi = 1.0 / p;
    let notes = vec![
        "BS 84 tolerance formula with length of engagement L = D and no allowance (assumed; the sources do not settle them)".to_string(),
    ];
    match kind {
        ThreadKind::External => {
            let minor_extra = if class == Bs84Class::Close { 0.013 } else { 0.02 } * p.sqrt();
            ThreadLimits {
                kind,
                class: class.to_string(),
                major_diameter: Limit::new(mm(big_d - (k * t + 0.01 * p.sqrt())), mm(big_d)),
                pitch_diameter: Limit::new(mm(e - k * t), mm(e)),
                minor_diameter: Limit::new(mm(d1 - (k * t + minor_extra)), mm(d1)),
                root_radius_min: None,
                fundamental_deviation_um: 0.0,
                crest_deviation_um: 0.0,
                notes,
                gauge_plane: None,
                resolution: Resolution::Micrometre,
            }
        }
        ThreadKind::Internal => {
            let c = if tpi >= 26.0 - 1e-9 {
                0.004
            } else if tpi >= 22.0 - 1e-9 {
                0.005
            } else {
                0.007
            };
            ThreadLimits {
                kind,
                class: class.to_string(),
                major_diameter: Limit { min: Some(mm(big_d)), max: None },
                pitch_diameter: Limit::new(mm(e), mm(e + k * t)),
                minor_diameter: Limit::new(mm(d1), mm(d1 + 0.2 * p + c)),
                root_radius_min: None,
                fundamental_deviation_um: 0.0,
                crest_deviation_um: 0.0,
                notes,
                gauge_plane: None,
                resolution: Resolution::Micrometre,
            }
        }
    }
}

/// Basic diameters of an ISO 228-1 thread as the standard prints them (mm):
/// h = 0.640327·P rounded to 0.001 mm, then d2 = d − h and d1 = d − 2h.
pub fn bsp_basic(thread: &BasicThread) -> (f64, f64, f64) {
    let h = round_um(0.640327 * thread.pitch);
    let d = round_um(thread.nominal_diameter);
    (d, round_um(d - h), round_um(d - 2.0 * h))
}

/// Limits of an ISO 228-1 thread. Zero fundamental deviation in every class.
pub fn iso228_limits(thread: &BasicThread, class: Iso228Class) -> Result<ThreadLimits, Error> {
    let cat = catalog()?;
    let size =
        cat.bsp.iter().find(|s| (s.d - thread.nominal_diameter).abs() < 1e-9).ok_or_else(|| {
            Error::Input(format!("no ISO 228-1 size has d = {} mm", thread.nominal_diameter))
        })?;
    let (d, d2, d1) = bsp_basic(thread);
    Ok(match class {
        Iso228Class::A | Iso228Class::B => {
            let td2 = if class == Iso228Class::A { size.td2_a } else { size.td2_b };
            ThreadLimits {
                kind: ThreadKind::External,
                class: class.to_string(),
                major_diameter: Limit::new(round_um(d - size.td), d),
                pitch_diameter: Limit::new(round_um(d2 - td2), d2),
                minor_diameter: Limit { max: Some(d1), min: None },
                root_radius_min: None,
                fundamental_deviation_um: 0.0,
                crest_deviation_um: 0.0,
                notes: Vec::new(),
                gauge_plane: None,
                resolution: Resolution::Micrometre,
            }
        }
        Iso228Class::Internal => ThreadLimits {
            kind: ThreadKind::Internal,
            class: class.to_string(),
            major_diameter: Limit { min: Some(d), max: None },
            pitch_diameter: Limit::new(d2, round_um(d2 + size.td2_int)),
            minor_diameter: Limit::new(d1, round_um(d1 + size.td1_int)),
            root_radius_min: None,
            fundamental_deviation_um: 0.0,
            crest_deviation_um: 0.0,
            notes: Vec::new(),
            gauge_plane: None,
            resolution: Resolution::Micrometre,
        },
    })
}

/// The Unified series of a designation: it sets the length of engagement behind the tabulated
/// tolerances (ASME B1.1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnifiedSeries {
    /// Coarse (UNC, UNRC).
    Unc,
    /// Fine (UNF, UNRF).
    Unf,
    /// Extra fine (UNEF, UNREF).
    Unef,
    /// Constant pitch (UN, UNR: 4UN … 32UN).
    Un,
    /// Special (UNS).
    Uns,
}

impl UnifiedSeries {
    /// The series as written (`UNC`), with R for the rounded-root external form.
    pub fn name(self, unr: bool) -> &'static str {
        match (self, unr) {
            (UnifiedSeries::Unc, false) => "UNC",
            (UnifiedSeries::Unc, true) => "UNRC",
            (UnifiedSeries::Unf, false) => "UNF",
            (UnifiedSeries::Unf, true) => "UNRF",
            (UnifiedSeries::Unef, false) => "UNEF",
            (UnifiedSeries::Unef, true) => "UNREF",
            (UnifiedSeries::Un, false) => "UN",
            (UnifiedSeries::Un, true) => "UNR",
            (UnifiedSeries::Uns, false) => "UNS",
            (UnifiedSeries::Uns, true) => "UNRS",
        }
    }
}

/// A Unified class number: 1 (loosest), 2, 3 (tightest).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnifiedGrade {
    /// 1A / 1B.
    G1,
    /// 2A / 2B.
    G2,
    /// 3A / 3B.
    G3,
}

impl UnifiedGrade {
    /// Reads the class digit.
    pub fn from_digit(d: u8) -> Option<UnifiedGrade> {
        match d {
            1 => Some(UnifiedGrade::G1),
            2 => Some(UnifiedGrade::G2),
            3 => Some(UnifiedGrade::G3),
            _ => None,
        }
    }

    /// The class number.
    pub fn number(self) -> u8 {
        match self {
            UnifiedGrade::G1 => 1,
            UnifiedGrade::G2 => 2,
            UnifiedGrade::G3 => 3,
        }
    }
}

/// A Unified class (1A 2A 3A external, 1B 2B 3B internal) with its series.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UnifiedClass {
    /// 1, 2 or 3.
    pub grade: UnifiedGrade,
    /// B (internal) or A (external).
    pub internal: bool,
    /// The series (for the length of engagement).
    pub series: UnifiedSeries,
    /// UNR: the external thread's root is rounded, radius at least 0.108·P.
    pub unr: bool,
}

impl fmt::Display for UnifiedClass {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}{}", self.grade.number(), if self.internal { 'B' } else { 'A' })
    }
}

/// Limits of a Unified thread from ASME B1.1's formulas (shared reference
/// `unified-asme-b1_1.toml`, sections tolerances, length_of_engagement and rounding), in inches, then
/// converted to mm. Td2(2A) = 0.0015·D^(1/3) + 0.0015·√LE + 0.015·P^(2/3) with LE = D for UNC, UNF
/// and 4/6/8UN, 9P for UNEF, 12UN and finer and UNS; classes 1A/2A/3A × 1.5/1/0.75, 1B/2B/3B ×
/// 1.95/1.3/0.975; allowance es = 0.3·Td2(2A) for 1A and 2A, rounded to 0.0001 in; major Td =
/// 0.060·P^(2/3) (0.090 for 1A); internal minor tolerance by the 1B/2B and 3B rules. Limits are
/// rounded to 0.0001 in (the 1B/2B minor of sizes from 1/4 in to 0.001 in).
pub fn unified_limits(t: &BasicThread, c: UnifiedClass) -> ThreadLimits {
    let inch = crate::standards::MM_PER_INCH;
    let (d, p) = (t.nominal_diameter / inch, t.pitch / inch);
    let tpi = 1.0 / p;
    let le = match c.series {
        UnifiedSeries::Unc | UnifiedSeries::Unf => d,
        UnifiedSeries::Un if tpi <= 8.0 + 1e-9 => d,
        UnifiedSeries::Un | UnifiedSeries::Unef | UnifiedSeries::Uns => 9.0 * p,
    };
    let p23 = p.powf(2.0 / 3.0);
    let td2_2a = 0.0015 * d.cbrt() + 0.0015 * le.sqrt() + 0.015 * p23;
    let r4 = |x: f64| (x * 10_000.0).round() / 10_000.0;
    let r3 = |x: f64| (x * 1000.0).round() / 1000.0;
    let h = 0.866_025_403_784_438_6 * p;
    let (d2, d1) = (d - 0.75 * h, d - 1.25 * h);
    let mm = |x: f64| x * inch;
    // The class factors on Td2(2A): external 1A/2A/3A, internal 1B/2B/3B (ASME B1.1).
    let (td2_ext, td2_int) = match c.grade {
        UnifiedGrade::G1 => (1.5, 1.95),
        UnifiedGrade::G2 => (1.0, 1.3),
        UnifiedGrade::G3 => (0.75, 0.975),
    };
    let mut notes = vec![format!(
        "ASME B1.1 limits from its formulas with LE = {:.4} in ({}), rounded to 0.0001 in; the published tables differ from these by 0.0001 in in about one value of five",
        le,
        if (le - d).abs() < 1e-12 { "D" } else { "9P" }
    )];
    if c.internal {
        let td2 = td2_int * td2_2a;
        let a = 0.05 * p23 + 0.03 * p / d - 0.002;
        let td1 = if matches!(c.grade, UnifiedGrade::G1 | UnifiedGrade::G2) {
            let lo = 0.25 * p - 0.4 * p * p;
            if d >= 0.25 {
                lo
            } else {
                a.min(0.394 * p).max(lo)
            }
        } else {
            let lo = if tpi >= 13.0 - 1e-9 { 0.23 * p - 1.5 * p * p } else { 0.12 * p };
            a.min(0.394 * p).max(lo)
        };
        let rd1 = |x: f64| {
            if matches!(c.grade, UnifiedGrade::G1 | UnifiedGrade::G2) && d >= 0.25 {
                r3(x)
            } else {
                r4(x)
            }
        };
        ThreadLimits {
            kind: ThreadKind::Internal,
            class: c.to_string(),
            major_diameter: Limit { min: Some(mm(r4(d))), max: None },
            pitch_diameter: Limit::new(mm(r4(d2)), mm(r4(d2 + td2))),
            minor_diameter: Limit::new(mm(rd1(d1)), mm(rd1(d1 + td1))),
            root_radius_min: None,
            fundamental_deviation_um: 0.0,
            crest_deviation_um: 0.0,
            notes,
            gauge_plane: None,
            resolution: Resolution::TenThousandthInch,
        }
    } else {
        let es = match c.grade {
            UnifiedGrade::G3 => 0.0,
            UnifiedGrade::G1 | UnifiedGrade::G2 => r4(0.3 * td2_2a),
        };
        let td2 = td2_ext * td2_2a;
        let td = match c.grade {
            UnifiedGrade::G1 => 0.090,
            UnifiedGrade::G2 | UnifiedGrade::G3 => 0.060,
        } * p23;
        let (dmax, d2max) = (d - es, d2 - es);
        let (dmin, d2min) = (dmax - td, d2max - td2);
        // UNR: the rounded root's minor diameter at most d max − 1.190784·P; UN: the flat-form
        // limit D1 − es. The lowest root: d2 min − 0.649519·P (reference).
        let minor_max = if c.unr { dmax - 1.190_784 * p } else { d1 - es };
        let minor_min = d2min - 0.649_519 * p;
        if c.unr {
            notes.push("UNR: the root radius is at least 0.108·P".into());
        }
        ThreadLimits {
            kind: ThreadKind::External,
            class: c.to_string(),
            major_diameter: Limit::new(mm(r4(dmin)), mm(r4(dmax))),
            pitch_diameter: Limit::new(mm(r4(d2min)), mm(r4(d2max))),
            minor_diameter: Limit::new(mm(r4(minor_min)), mm(r4(minor_max))),
            root_radius_min: c.unr.then_some(0.108 * t.pitch),
            fundamental_deviation_um: -es * inch * 1000.0,
            crest_deviation_um: -es * inch * 1000.0,
            notes,
            gauge_plane: None,
            resolution: Resolution::TenThousandthInch,
        }
    }
}

/// An ISO 2903 tolerance grade of the pitch diameter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TrGrade {
    /// Grade 7 (the published tables).
    G7,
    /// Grade 8 (from grade 7 by the ISO 965-1 grade factors, stated).
    G8,
    /// Grade 9 (likewise).
    G9,
}

/// An ISO 2903 tolerance position of the pitch diameter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TrPosition {
    /// e (external).
    E,
    /// c (external, larger allowance).
    C,
    /// H (internal).
    H,
}

/// An ISO 2903 trapezoidal class: grade 7, 8 or 9 and position e or c (external, d2; d and d3
/// are always h) or H (internal).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TrClass {
    /// 7, 8 or 9.
    pub grade: TrGrade,
    /// `e`, `c` or `H`.
    pub position: TrPosition,
}

impl TrClass {
    /// Reads `7e`, `8c`, `7H`.
    pub fn parse(s: &str) -> Result<TrClass, String> {
        let bad =
            || format!("'{s}' is not an ISO 2903 class: 7e, 8e, 8c, 9c (external), 7H, 8H, 9H (internal)");
        let (grade, position) = match s.as_bytes() {
            [g, p] => (
                match g {
                    b'7' => TrGrade::G7,
                    b'8' => TrGrade::G8,
                    b'9' => TrGrade::G9,
                    _ => return Err(bad()),
                },
                match p {
                    b'e' => TrPosition::E,
                    b'c' => TrPosition::C,
                    b'H' => TrPosition::H,
                    _ => return Err(bad()),
                },
            ),
            _ => return Err(bad()),
        };
        Ok(TrClass { grade, position })
    }

    /// Internal (H).
    pub fn internal(self) -> bool {
        match self.position {
            TrPosition::H => true,
            TrPosition::E | TrPosition::C => false,
        }
    }
}

impl TrGrade {
    /// The grade's number.
    pub fn number(self) -> u8 {
        match self {
            TrGrade::G7 => 7,
            TrGrade::G8 => 8,
            TrGrade::G9 => 9,
        }
    }
}

impl fmt::Display for TrClass {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let g = self.grade.number();
        let p = match self.position {
            TrPosition::E => 'e',
            TrPosition::C => 'c',
            TrPosition::H => 'H',
        };
        write!(f, "{g}{p}")
    }
}

/// Limits of a trapezoidal thread, ISO 2903 (`profiles/trapezoidal.toml`): external d max = d,
/// d min = d − Td(4); d2 max = d2 + es(e or c), d2 min = d2 max − Td2; d3 max = d3 (position h),
/// d3 min = d3 − Td3 with Td3 = 1.25·Td2 + |es|; internal D1 from D1 = d − P up by TD1(4), D2 from
/// d2 up by TD2, D4 min = d + 2ac. Grades 8 and 9 are the reference's rule on grade 7, stated in
/// the output.
pub fn tr_limits(t: &BasicThread, c: TrClass) -> Result<ThreadLimits, Error> {
    let tr = &catalog()?.tr;
    let p = t.pitch;
    let d = t.nominal_diameter;
    let r40t = &catalog()?.iso.rounding.r40;
    let at = |list: &[f64], vals: &[f64], what: &str| -> Result<f64, Error> {
        find_pitch(list, p)
            .and_then(|i| vals.get(i).copied())
            .ok_or_else(|| Error::Input(format!("ISO 2903 tabulates no {what} for P = {p} mm")))
    };
    let range = tr
        .td2_7
        .iter()
        .find(|r| d > r.over && d <= r.up_to + 1e-9)
        .ok_or_else(|| Error::Input(format!("ISO 2903 covers Tr5.6 to Tr355, not Tr{d}")))?;
    let i = find_pitch(&range.pitches, p).ok_or_else(|| {
        Error::Input(format!(
            "ISO 2903 tabulates no pitch-diameter tolerance for P = {p} mm over {} up to {} mm",
            range.over, range.up_to
        ))
    })?;
    let (td2_7, tdd2_7) = (range.external[i], range.internal[i]);
    let mut notes = Vec::new();
    // The ISO 965-1 grade factors (bolt Td2, nut TD2) relative to grade 7; None for grade 7
    // itself, which the tables give.
    let grade_factor = |internal: bool| -> Option<f64> {
        match (c.grade, internal) {
            (TrGrade::G7, _) => None,
            (TrGrade::G8, false) => Some(1.6 / 1.25),
            (TrGrade::G9, false) => Some(2.0 / 1.25),
            (TrGrade::G8, true) => Some(2.12 / 1.7),
            (TrGrade::G9, true) => Some(2.65 / 1.7),
        }
    };
    let graded = |td2_7: f64, internal: bool| grade_factor(internal).map_or(td2_7, |f| r40(f * td2_7, r40t));
    if grade_factor(false).is_some() {
        notes.push(format!(
            "grade {} pitch-diameter tolerance from grade 7 by the ISO 965-1 grade factors (not published in the sources; one 8c value, Tr10x2-8c, agrees)",
            c.grade.number()
        ));
    }
    let (d2, d1, d3) = (t.pitch_diameter(), t.minor_diameter_internal(), t.minor_diameter_external());
    let ac = t.crest_clearance();
    let es = match c.position {
        TrPosition::H => None,
        TrPosition::E => Some(at(&tr.es_pitches, &tr.es_e, "es(e)")?),
        TrPosition::C => Some(find_pitch(&tr.es_c_pitches, p).map(|i| tr.es_c[i]).ok_or_else(|| {
            Error::Input(format!(
                "es(c) of ISO 2903 at P = {p} mm is not in the sources (only P = 2 mm, −150 µm, is): use position e"
            ))
        })?),
    };
    let Some(es) = es else {
        let td2 = graded(tdd2_7, true);
        let td1 = at(&tr.td_pitches, &tr.td1_4, "TD1(4)")?;
        return Ok(ThreadLimits {
            kind: ThreadKind::Internal,
            class: c.to_string(),
            major_diameter: Limit { min: Some(round_um(d + 2.0 * ac)), max: None },
            pitch_diameter: Limit::new(round_um(d2), round_um(d2 + td2 / 1000.0)),
            minor_diameter: Limit::new(round_um(d1), round_um(d1 + td1 / 1000.0)),
            root_radius_min: None,
            fundamental_deviation_um: 0.0,
            crest_deviation_um: 0.0,
            notes,
            gauge_plane: None,
            resolution: Resolution::Micrometre,
        });
    };
    if c.position == TrPosition::E && (p - 12.0).abs() < 1e-9 {
        notes.push("es(e) at P = 12 is −170 µm as the table prints it; its d3 rows imply −160 µm (unresolved in the sources)".into());
    }
    let td2 = graded(td2_7, false);
    let td = at(&tr.td_pitches, &tr.td4, "Td(4)")?;
    // Td3 is a whole number of µm, rounded half up: Tr10x2-7e (308.5 → 309) prints 7.191
    // and the other published rows.
    let td3 = (1.25 * td2 + es.abs()).round();
    let d2max = d2 + es / 1000.0;
    Ok(ThreadLimits {
        kind: ThreadKind::External,
        class: c.to_string(),
        major_diameter: Limit::new(round_um(d - td / 1000.0), round_um(d)),
        pitch_diameter: Limit::new(round_um(d2max - td2 / 1000.0), round_um(d2max)),
        minor_diameter: Limit::new(round_um(d3 - td3 / 1000.0), round_um(d3)),
        root_radius_min: None,
        fundamental_deviation_um: es,
        crest_deviation_um: 0.0,
        notes,
        gauge_plane: None,
        resolution: Resolution::Micrometre,
    })
}

/// A general-purpose Acme class, ASME B1.5: 2G, 3G or 4G (the same class for nut and bolt).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AcmeClass {
    /// 2G.
    G2,
    /// 3G.
    G3,
    /// 4G.
    G4,
}

impl AcmeClass {
    /// Reads the grade digit of `2G`, `3G`, `4G`.
    pub fn from_digit(d: u8) -> Option<AcmeClass> {
        match d {
            2 => Some(AcmeClass::G2),
            3 => Some(AcmeClass::G3),
            4 => Some(AcmeClass::G4),
            _ => None,
        }
    }
}

impl fmt::Display for AcmeClass {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            AcmeClass::G2 => "2G",
            AcmeClass::G3 => "3G",
            AcmeClass::G4 => "4G",
        })
    }
}

/// Limits of a general-purpose Acme thread (shared reference `acme-asme-b1_5.toml`, section
/// formulas: inferred from, and reproducing, two public tables), inches then mm: allowance
/// 0.008/0.006/0.004·√D (2G/3G/4G), Td2 = 0.030·√P + 0.006·√D, 0.014·√P + 0.0028·√D,
/// 0.010·√P + 0.002·√D; d min = D − max(0.05·P, 0.005); d3 max = D − P − c (c = 0.020 in for
/// 10 tpi and coarser, else 0.010), d3 min = d3 max − 1.5·Td2; internal D2 from E up by Td2, D1
/// from D − P up by max(0.05·P, 0.005), D4 min = D + c (not sourced, stated). Limits to 0.0001 in.
pub fn acme_limits(t: &BasicThread, c: AcmeClass, kind: ThreadKind) -> ThreadLimits {
    let inch = crate::standards::MM_PER_INCH;
    let (d, p) = (t.nominal_diameter / inch, t.pitch / inch);
    let r4 = |x: f64| (x * 10_000.0).round() / 10_000.0;
    let mm = |x: f64| x * inch;
    let (allow_k, a, b) = match c {
        AcmeClass::G2 => (0.008, 0.030, 0.006),
        AcmeClass::G3 => (0.006, 0.014, 0.0028),
        AcmeClass::G4 => (0.004, 0.010, 0.002),
    };
    let allowance = allow_k * d.sqrt();
    let td2 = a * p.sqrt() + b * d.sqrt();
    let e = d - 0.5 * p;
    let clear = if 1.0 / p <= 10.0 + 1e-9 { 0.020 } else { 0.010 };
    let major_tol = (0.05 * p).max(0.005);
    let mut notes = vec![
        "ASME B1.5 limits from the formulas that reproduce the public tables of the reference set (the standard's own text was not available), rounded to 0.0001 in".to_string(),
    ];
    match kind {
        ThreadKind::External => {
            let d2max = e - allowance;
            // d3 max is rounded before 1.5·Td2 comes off: that reproduces 3/4-6 2G's 0.5371.
            let d3max = r4(d - p - clear);
            ThreadLimits {
                kind,
                class: c.to_string(),
                major_diameter: Limit::new(mm(r4(d - major_tol)), mm(r4(d))),
                pitch_diameter: Limit::new(mm(r4(d2max - td2)), mm(r4(d2max))),
                minor_diameter: Limit::new(mm(r4(d3max - 1.5 * td2)), mm(r4(d3max))),
                root_radius_min: None,
                fundamental_deviation_um: -allowance * inch * 1000.0,
                crest_deviation_um: 0.0,
                notes,
                gauge_plane: None,
                resolution: Resolution::TenThousandthInch,
            }
        }
        ThreadKind::Internal => {
            notes.push(format!("the nut's major diameter minimum D + {clear} in is not sourced"));
            ThreadLimits {
                kind,
                class: c.to_string(),
                major_diameter: Limit { min: Some(mm(r4(d + clear))), max: None },
                pitch_diameter: Limit::new(mm(r4(e)), mm(r4(e + td2))),
                minor_diameter: Limit::new(mm(r4(d - p)), mm(r4(d - p + major_tol))),
                root_radius_min: None,
                fundamental_deviation_um: 0.0,
                crest_deviation_um: 0.0,
                notes,
                gauge_plane: None,
                resolution: Resolution::TenThousandthInch,
            }
        }
    }
}

/// Limits for the class a designation names for `kind`, or `None` when it names none.
///
/// ```
/// use threadcheck::limits_for;
/// use threadcheck::{parse_designation, ParseOptions, ThreadKind};
/// let des = parse_designation("M10x1.5-6g", ParseOptions::default())?;
/// let l = limits_for(&des, ThreadKind::External)?.expect("6g is an external class");
/// // ISO 965-2: d2 8.994/8.862, d 9.968/9.732.
/// assert_eq!((l.pitch_diameter.max, l.pitch_diameter.min), (Some(8.994), Some(8.862)));
/// assert_eq!((l.major_diameter.max, l.major_diameter.min), (Some(9.968), Some(9.732)));
/// assert!(limits_for(&des, ThreadKind::Internal)?.is_none()); // no internal class given
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn limits_for(des: &Designation, kind: ThreadKind) -> Result<Option<ThreadLimits>, Error> {
    let Some(class) = des.class(kind) else { return Ok(None) };
    let t = &des.thread;
    Ok(Some(match (t.form, class) {
        (ThreadForm::IsoMetric, ClassSpec::Iso(c)) => iso_limits(t, c)?,
        (ThreadForm::Whitworth, ClassSpec::Bs84(c)) => bs84_limits(t, *c, kind),
        (ThreadForm::BspParallel, ClassSpec::Iso228(c)) => iso228_limits(t, *c)?,
        (ThreadForm::Unified, ClassSpec::Unified(c)) => unified_limits(t, *c),
        (ThreadForm::Trapezoidal, ClassSpec::Trapezoidal(c)) => tr_limits(t, *c)?,
        (ThreadForm::Acme, ClassSpec::Acme(c)) => acme_limits(t, *c, kind),
        (ThreadForm::Npt | ThreadForm::Iso7Taper, ClassSpec::Taper(c)) => taper_limits(t, *c)?,
        (
            ThreadForm::IsoMetric
            | ThreadForm::Whitworth
            | ThreadForm::BspParallel
            | ThreadForm::Unified
            | ThreadForm::Trapezoidal
            | ThreadForm::Acme
            | ThreadForm::Npt
            | ThreadForm::Iso7Taper,
            ClassSpec::Iso(_)
            | ClassSpec::Bs84(_)
            | ClassSpec::Iso228(_)
            | ClassSpec::Unified(_)
            | ClassSpec::Trapezoidal(_)
            | ClassSpec::Acme(_)
            | ClassSpec::Taper(_),
        ) => {
            return Err(Error::Input(format!("class {class} does not belong to the {} form", t.form.name())))
        }
    }))
}

/// Basic diameters as the limits tables print them (mm, rounded to 0.001):
/// (major, pitch, minor external, minor internal, H).
pub fn basic_rounded(t: &BasicThread) -> (f64, f64, f64, f64, f64) {
    if t.form == ThreadForm::BspParallel {
        let (d, d2, d1) = bsp_basic(t);
        return (d, d2, d1, d1, round_um(t.fundamental_height()));
    }
    (
        round_um(t.nominal_diameter),
        round_um(t.pitch_diameter()),
        round_um(t.minor_diameter_external()),
        round_um(t.minor_diameter_internal()),
        (t.fundamental_height() * 10_000.0).round() / 10_000.0,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The published test vectors of the rounding rule (profiles/iso-metric.toml, [rounding],
    /// each naming the table cell it comes from).
    #[test]
    fn r40_reproduces_published_cells() {
        let t = iso_tables().unwrap();
        let r = &t.rounding;
        for i in 0..r.examples_base.len() {
            let got = r40(r.examples_factor[i] * r.examples_base[i], &r.r40);
            assert_eq!(got, r.examples_expected[i], "vector {i}");
        }
    }

    /// TD2(6) = R40(1.32 × Td2(6)) reproduces the tabulated internal column of every range.
    #[test]
    fn internal_td2_rule_matches_its_column() {
        let t = iso_tables().unwrap();
        for range in &t.td2_grade6.ranges {
            for (i, ext) in range.td2_external.iter().enumerate() {
                assert_eq!(
                    r40(1.32 * ext, &t.rounding.r40),
                    range.td2_internal[i],
                    "{} P{}",
                    range.over,
                    range.pitches[i]
                );
            }
        }
    }

    #[test]
    fn class_parsing_and_display() {
        assert_eq!(IsoClass::parse("6g").unwrap().to_string(), "6g");
        assert_eq!(IsoClass::parse("5g6g").unwrap().to_string(), "5g6g");
        assert_eq!(IsoClass::parse("6H").unwrap().to_string(), "6H");
        assert!(IsoClass::parse("6k").is_err());
        assert!(IsoClass::parse("6E").is_err());
        assert!(IsoClass::parse("2g").is_err());
        assert!(IsoClass::parse("5h").is_err()); // Td has no grade 5
        assert!(IsoClass::parse("5h4h").is_ok());
        assert!(IsoClass::parse("6G6h").is_err());
    }
}
