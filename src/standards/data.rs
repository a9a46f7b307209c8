//! The embedded catalogues (`profiles/*.toml`), parsed once on first use.
//!
//! The files ship inside the binary with `include_str!`, so threadcheck runs from any folder.

use serde::Deserialize;
use std::sync::OnceLock;

const ISO_METRIC: &str = include_str!("../../profiles/iso-metric.toml");
const WHITWORTH: &str = include_str!("../../profiles/whitworth.toml");
const BSP: &str = include_str!("../../profiles/bsp.toml");
const UNIFIED: &str = include_str!("../../profiles/unified.toml");
const TRAPEZOIDAL: &str = include_str!("../../profiles/trapezoidal.toml");
const PIPE_TAPER: &str = include_str!("../../profiles/pipe-taper.toml");
const DRILLS: &str = include_str!("../../profiles/drills.toml");

/// Everything the standards module knows, from the embedded TOML files.
#[derive(Debug)]
pub struct Catalog {
    /// ISO 965-1 tables and the ISO 261 series.
    pub iso: IsoTables,
    /// BSW (coarse) sizes, BS 84.
    pub bsw: Vec<WhitworthSize>,
    /// BSF (fine) sizes, BS 84.
    pub bsf: Vec<WhitworthSize>,
    /// BSP parallel pipe sizes, ISO 228-1.
    pub bsp: Vec<BspSize>,
    /// Unified inch sizes with their standard series, ASME B1.1.
    pub unified: Vec<UnifiedSize>,
    /// ISO 2902 series and ISO 2903 tables of the trapezoidal thread.
    pub tr: TrapezoidalTables,
    /// NPT (ASME B1.20.1, inches) and ISO 7-1 (mm) taper pipe sizes.
    pub pipe: PipeTables,
    /// Tap drills (ISO 2306) and the inch drill gauge (`profiles/drills.toml`).
    pub drills: DrillTables,
}

/// Drills for tapped holes (`profiles/drills.toml`).
#[derive(Debug, Clone, Deserialize)]
pub struct DrillTables {
    /// ISO 2306's tap drills for the ISO metric coarse series.
    pub iso2306_coarse: Iso2306Coarse,
    /// The number and letter drill gauge, inches.
    pub inch_drills: InchDrills,
}

/// ISO 2306's coarse-series tap drills, mm.
#[derive(Debug, Clone, Deserialize)]
pub struct Iso2306Coarse {
    /// Nominal diameters.
    pub d: Vec<f64>,
    /// Their tap drills.
    pub drill: Vec<f64>,
}

/// The number (#1 first) and letter (A first) drills, inches.
#[derive(Debug, Clone, Deserialize)]
pub struct InchDrills {
    /// #1 to #60.
    pub number: Vec<f64>,
    /// A to Z.
    pub letter: Vec<f64>,
}

/// Taper pipe thread sizes (`profiles/pipe-taper.toml`).
#[derive(Debug, Clone, Deserialize)]
pub struct PipeTables {
    /// NPT, inches.
    pub npt: NptTable,
    /// ISO 7-1, mm.
    pub iso7: Iso7Table,
}

/// NPT sizes, inches.
#[derive(Debug, Clone, Deserialize)]
#[allow(non_snake_case)]
pub struct NptTable {
    /// Sizes as written (`1/2`, `1-1/4`).
    pub sizes: Vec<String>,
    /// Threads per inch.
    pub tpi: Vec<f64>,
    /// Pipe outside diameter.
    pub OD: Vec<f64>,
    /// Pitch diameter at the small end of the external thread.
    pub E0: Vec<f64>,
    /// Pitch diameter at the hand-tight (gauge) plane.
    pub E1: Vec<f64>,
    /// Hand-tight engagement: the gauge plane's distance from the small end.
    pub L1: Vec<f64>,
    /// Effective thread length.
    pub L2: Vec<f64>,
}

/// ISO 7-1 sizes, mm.
#[derive(Debug, Clone, Deserialize)]
pub struct Iso7Table {
    /// Sizes as written (`1/2`, `1 1/4`).
    pub sizes: Vec<String>,
    /// Threads per inch.
    pub tpi: Vec<f64>,
    /// Major diameter at the gauge plane.
    pub d: Vec<f64>,
    /// Pitch diameter at the gauge plane.
    pub d2: Vec<f64>,
    /// Minor diameter at the gauge plane.
    pub d1: Vec<f64>,
    /// Basic gauge length: the gauge plane's distance from the small end of the external thread.
    pub gauge_length_basic: Vec<f64>,
}

/// ISO 2901–2903 data (`profiles/trapezoidal.toml`); deviations and tolerances in µm.
#[derive(Debug, Clone, Deserialize)]
pub struct TrapezoidalTables {
    /// Crest clearance ac: pitch upper bounds and values, mm.
    pub ac_pitch_up_to: Vec<f64>,
    /// ac, mm.
    pub ac: Vec<f64>,
    /// ISO 2902 diameters, mm.
    pub series_d: Vec<f64>,
    /// Their pitches, mm.
    pub series_pitches: Vec<Vec<f64>>,
    /// Pitches of the es tables.
    pub es_pitches: Vec<f64>,
    /// es(e), µm.
    pub es_e: Vec<f64>,
    /// Pitches of es(c).
    pub es_c_pitches: Vec<f64>,
    /// es(c), µm.
    pub es_c: Vec<f64>,
    /// Pitches of Td(4) and TD1(4).
    pub td_pitches: Vec<f64>,
    /// Td(4), µm.
    pub td4: Vec<f64>,
    /// TD1(4), µm.
    pub td1_4: Vec<f64>,
    /// Td2(7)/TD2(7) by range.
    pub td2_7: Vec<TrTd2Range>,
}

/// One diameter range of Td2(7)/TD2(7).
#[derive(Debug, Clone, Deserialize)]
pub struct TrTd2Range {
    /// Over this diameter, mm.
    pub over: f64,
    /// Up to this diameter, mm.
    pub up_to: f64,
    /// Pitches, mm.
    pub pitches: Vec<f64>,
    /// Td2(7), µm.
    pub external: Vec<f64>,
    /// TD2(7), µm.
    pub internal: Vec<f64>,
}

/// One Unified size: its name, basic major diameter (inches) and the threads per inch of the
/// coarse, fine and extra-fine series where the size has them.
#[derive(Debug, Clone, Deserialize)]
pub struct UnifiedSize {
    /// Size as written (`1/4`, `1 1/4`, `10` for #10).
    pub name: String,
    /// Basic major diameter, inches.
    pub d: f64,
    /// UNC threads per inch.
    pub unc: Option<f64>,
    /// UNF threads per inch.
    pub unf: Option<f64>,
    /// UNEF threads per inch.
    pub unef: Option<f64>,
}

/// One BSW or BSF size.
#[derive(Debug, Clone, Deserialize)]
pub struct WhitworthSize {
    /// Nominal size in inches as written (`1/2`, `1 1/4`).
    pub size: String,
    /// Threads per inch.
    pub tpi: f64,
}

/// One ISO 228-1 size; lengths and tolerances in mm.
#[derive(Debug, Clone, Deserialize)]
pub struct BspSize {
    /// Size as written after `G` (`1/2`, `1 1/4`).
    pub size: String,
    /// Threads per inch.
    pub tpi: f64,
    /// Basic major diameter d = D, mm.
    pub d: f64,
    /// Internal pitch-diameter tolerance TD2, mm.
    pub td2_int: f64,
    /// External pitch-diameter tolerance, class A, mm.
    pub td2_a: f64,
    /// External pitch-diameter tolerance, class B, mm.
    pub td2_b: f64,
    /// Internal minor-diameter tolerance TD1, mm.
    pub td1_int: f64,
    /// External major-diameter tolerance Td (classes A and B), mm.
    pub td: f64,
}

/// The ISO 965-1 base tables (µm) and the ISO 261 series.
#[derive(Debug, Deserialize)]
pub struct IsoTables {
    /// Fundamental deviations.
    pub fundamental_deviations: FundamentalDeviations,
    /// Td2(6) and TD2(6) by diameter range and pitch.
    pub td2_grade6: RangeTable,
    /// Td(6) by pitch.
    pub td_grade6: TdTable,
    /// TD1(6) by pitch.
    pub td1_grade6: Td1Table,
    /// Grade factors.
    pub grade_factors: GradeFactors,
    /// R40 rounding data.
    pub rounding: Rounding,
    /// ISO 261 diameter/pitch series.
    pub series: Series,
}

/// ISO 965-1 Table 1, µm.
#[derive(Debug, Deserialize)]
#[allow(missing_docs)]
pub struct FundamentalDeviations {
    pub pitches: Vec<f64>,
    pub es_h: Vec<i32>,
    pub es_g: Vec<i32>,
    #[serde(rename = "EI_H")]
    pub ei_h: Vec<i32>,
    #[serde(rename = "EI_G")]
    pub ei_g: Vec<i32>,
    pub pitches_f: Vec<f64>,
    pub es_f: Vec<i32>,
    pub pitches_e: Vec<f64>,
    pub es_e: Vec<i32>,
}

/// Pitch-diameter tolerances by diameter range.
#[derive(Debug, Deserialize)]
pub struct RangeTable {
    /// One entry per diameter range (over < d <= up_to).
    pub ranges: Vec<Td2Range>,
}

/// Td2(6) and TD2(6) of one diameter range, µm.
#[derive(Debug, Deserialize)]
#[allow(missing_docs)]
pub struct Td2Range {
    pub over: f64,
    pub up_to: f64,
    pub pitches: Vec<f64>,
    pub td2_external: Vec<f64>,
    pub td2_internal: Vec<f64>,
}

/// Td(6) by pitch, µm.
#[derive(Debug, Deserialize)]
#[allow(missing_docs)]
pub struct TdTable {
    pub pitches: Vec<f64>,
    pub td: Vec<f64>,
}

/// TD1(6) by pitch, µm.
#[derive(Debug, Deserialize)]
#[allow(missing_docs)]
pub struct Td1Table {
    pub pitches: Vec<f64>,
    pub td1: Vec<f64>,
}

/// Grade factors relative to grade 6.
#[derive(Debug, Deserialize)]
#[allow(missing_docs)]
pub struct GradeFactors {
    pub td2: Factors,
    pub td2_internal: Factors,
    pub td: Factors,
    pub td1: Factors,
}

/// Grades and their factors.
#[derive(Debug, Deserialize)]
#[allow(missing_docs)]
pub struct Factors {
    pub grades: Vec<u8>,
    pub factors: Vec<f64>,
}

impl Factors {
    /// The factor for `grade`, if the grade exists for this tolerance.
    pub fn get(&self, grade: u8) -> Option<f64> {
        self.grades.iter().position(|&g| g == grade).map(|i| self.factors[i])
    }
}

/// R40 rounding data and the published test vectors.
#[derive(Debug, Deserialize)]
#[allow(missing_docs)]
pub struct Rounding {
    pub r40: Vec<f64>,
    pub examples_base: Vec<f64>,
    pub examples_factor: Vec<f64>,
    pub examples_expected: Vec<f64>,
}

/// ISO 261.
#[derive(Debug, Deserialize)]
#[allow(missing_docs)]
pub struct Series {
    pub sizes: Vec<SeriesSize>,
}

/// One nominal diameter of ISO 261 with its pitches.
#[derive(Debug, Clone, Deserialize)]
#[allow(missing_docs)]
pub struct SeriesSize {
    pub d: f64,
    pub choice: u8,
    pub coarse: Option<f64>,
    pub fine: Vec<f64>,
}

#[derive(Deserialize)]
struct WhitworthFile {
    bsw: Vec<WhitworthSize>,
    bsf: Vec<WhitworthSize>,
}

#[derive(Deserialize)]
struct BspFile {
    size: Vec<BspSize>,
}

#[derive(Deserialize)]
struct UnifiedFile {
    size: Vec<UnifiedSize>,
}

fn load() -> Result<Catalog, String> {
    let iso: IsoTables = toml::from_str(ISO_METRIC).map_err(|e| format!("profiles/iso-metric.toml: {e}"))?;
    let w: WhitworthFile = toml::from_str(WHITWORTH).map_err(|e| format!("profiles/whitworth.toml: {e}"))?;
    let b: BspFile = toml::from_str(BSP).map_err(|e| format!("profiles/bsp.toml: {e}"))?;
    let u: UnifiedFile = toml::from_str(UNIFIED).map_err(|e| format!("profiles/unified.toml: {e}"))?;
    let tr: TrapezoidalTables =
        toml::from_str(TRAPEZOIDAL).map_err(|e| format!("profiles/trapezoidal.toml: {e}"))?;
    let pipe: PipeTables =
        toml::from_str(PIPE_TAPER).map_err(|e| format!("profiles/pipe-taper.toml: {e}"))?;
    let drills: DrillTables = toml::from_str(DRILLS).map_err(|e| format!("profiles/drills.toml: {e}"))?;
    Ok(Catalog { iso, bsw: w.bsw, bsf: w.bsf, bsp: b.size, unified: u.size, tr, pipe, drills })
}

/// The embedded catalogue. Parsing happens once; the files are part of the binary, and a unit
/// test proves they parse, so the error branch only guards against a broken build.
///
/// ```
/// let cat = threadcheck::catalog()?;
/// // ISO 228-1: G1/2 is 20.955 mm over the crests, 14 threads per inch.
/// let g12 = cat.bsp.iter().find(|s| s.size == "1/2").expect("G1/2");
/// assert_eq!((g12.d, g12.tpi), (20.955, 14.0));
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn catalog() -> Result<&'static Catalog, crate::Error> {
    static CATALOG: OnceLock<Result<Catalog, String>> = OnceLock::new();
    CATALOG.get_or_init(load).as_ref().map_err(|e| crate::Error::Data(e.clone()))
}

/// Index of `x` in `list` when equal to within 1 nm (pitches are written with few decimals).
pub fn find_pitch(list: &[f64], x: f64) -> Option<usize> {
    list.iter().position(|&p| (p - x).abs() < 1e-6)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn embedded_catalogues_parse_and_are_consistent() {
        let c = catalog().unwrap();
        let fd = &c.iso.fundamental_deviations;
        assert_eq!(fd.pitches.len(), fd.es_g.len());
        assert_eq!(fd.pitches_e.len(), fd.es_e.len());
        assert_eq!(fd.pitches_f.len(), fd.es_f.len());
        for r in &c.iso.td2_grade6.ranges {
            assert_eq!(r.pitches.len(), r.td2_external.len());
            assert_eq!(r.pitches.len(), r.td2_internal.len());
        }
        assert_eq!(c.iso.rounding.r40.len(), 40);
        assert!(c.iso.series.sizes.len() >= 50);
        assert!(c.iso.series.sizes.iter().any(|s| s.d == 68.0));
        assert_eq!(c.bsw.len(), 25);
        assert_eq!(c.bsp.len(), 20);
        assert_eq!(c.drills.iso2306_coarse.d.len(), c.drills.iso2306_coarse.drill.len());
        assert_eq!((c.drills.inch_drills.number.len(), c.drills.inch_drills.letter.len()), (60, 26));
        // Each gauge runs one way: number drills shrink, letters grow.
        assert!(c.drills.inch_drills.number.windows(2).all(|w| w[0] > w[1]));
        assert!(c.drills.inch_drills.letter.windows(2).all(|w| w[0] < w[1]));
    }
}
