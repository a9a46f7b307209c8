//! The catalogue sweep: `verify` over every size of every form's standard series (ISO 261, the
//! ASME B1.1 and B1.5 series, ISO 2902, BS 84, ISO 228-1), external and internal, with every
//! insert, infeed and schedule asked for, in parallel.

use crate::analysis::tools::InsertChoice;
use crate::analysis::turn::{verify, Verification, VerifySpec};
use crate::standards::{catalog, ThreadForm};
use crate::toolpath::passes::{InfeedChoice, Schedule};
use crate::Error;
use rayon::prelude::*;

/// What to sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct CatalogueSpec {
    /// The forms, each over its standard series.
    pub forms: Vec<ThreadForm>,
    /// Include coarse pitches (ISO 261; UNC for Unified).
    pub coarse: bool,
    /// Include fine pitches (ISO 261; UNF and UNEF for Unified).
    pub fine: bool,
    /// Smallest and largest nominal diameter, mm.
    pub diameters: (f64, f64),
    /// ISO metric tolerance class, e.g. `6g` (the other forms take their medium classes: 2A/2B,
    /// 7e/7H, 2G, medium, A / internal).
    pub class: String,
    /// Also the internal threads, in each form's medium internal class (metric: 6H).
    pub internal: bool,
    /// Full-profile insert cases.
    pub full: bool,
    /// Partial-profile insert cases (tip radius min(0.04, 0.1·P) mm, so that the finest pitches
    /// get an insert whose tip fits their root); not for the trapezoid forms, whose partial V
    /// is no tool for a flat root.
    pub partial: bool,
    /// Infeeds.
    pub infeeds: Vec<InfeedChoice>,
    /// Schedules.
    pub schedules: Vec<Schedule>,
    /// Leave form checks out of the verdicts.
    pub gauge_only: bool,
}

impl Default for CatalogueSpec {
    /// The catalogue of issue 7: M1–M68 coarse and fine in 6g, full and partial inserts, radial,
    /// flank, modified-flank and alternating infeed, constant area and depth.
    fn default() -> Self {
        CatalogueSpec {
            forms: vec![ThreadForm::IsoMetric],
            coarse: true,
            fine: true,
            diameters: (1.0, 68.0),
            class: "6g".into(),
            internal: false,
            full: true,
            partial: true,
            infeeds: vec![
                InfeedChoice::Radial,
                InfeedChoice::Flank { angle: None },
                InfeedChoice::Modified,
                InfeedChoice::Alternating { angle: None },
            ],
            schedules: vec![Schedule::ConstantArea, Schedule::ConstantDepth],
            gauge_only: false,
        }
    }
}

impl CatalogueSpec {
    /// Every form, external and internal, every diameter of the series: the catalogue of the
    /// forms issue.
    pub fn all_forms() -> Self {
        CatalogueSpec {
            forms: vec![
                ThreadForm::IsoMetric,
                ThreadForm::Unified,
                ThreadForm::Trapezoidal,
                ThreadForm::Acme,
                ThreadForm::Whitworth,
                ThreadForm::BspParallel,
                ThreadForm::Npt,
                ThreadForm::Iso7Taper,
            ],
            internal: true,
            diameters: (0.0, 1000.0),
            ..CatalogueSpec::default()
        }
    }
}

/// One case of the catalogue.
#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    /// The verify spec of the case.
    pub spec: VerifySpec,
    /// A short label: designation, insert, infeed, schedule.
    pub label: String,
}

/// An inch size as the designations write it: `1/4`, `1 1/4`, `2`.
fn inch_name(d: f64) -> String {
    let whole = d.trunc();
    let frac = d - whole;
    let frac_text = [2u32, 4, 8, 16, 32, 64].iter().find_map(|&den| {
        let num = frac * f64::from(den);
        ((num - num.round()).abs() < 1e-9 && num.round() > 0.0).then(|| format!("{}/{den}", num.round()))
    });
    match (whole > 0.0, frac_text) {
        (true, Some(f)) => format!("{whole} {f}"),
        (false, Some(f)) => f,
        (_, None) => format!("{whole}"),
    }
}

/// (designation, pitch, internal) of every thread of `form` in the selection.
fn threads(spec: &CatalogueSpec, form: ThreadForm) -> Result<Vec<(String, f64, bool)>, Error> {
    let cat = catalog()?;
    let inch = crate::standards::MM_PER_INCH;
    let within = |d_mm: f64| d_mm >= spec.diameters.0 - 1e-9 && d_mm <= spec.diameters.1 + 1e-9;
    let mut out = Vec::new();
    let mut both = |ext: String, int: Option<String>, p: f64| {
        out.push((ext, p, false));
        if spec.internal {
            if let Some(i) = int {
                out.push((i, p, true));
            }
        }
    };
    match form {
        ThreadForm::IsoMetric => {
            for s in &cat.iso.series.sizes {
                if !within(s.d) {
                    continue;
                }
                let mut pitches: Vec<f64> = Vec::new();
                if spec.coarse {
                    pitches.extend(s.coarse);
                }
                if spec.fine {
                    pitches.extend(s.fine.iter().copied());
                }
                for p in pitches {
                    both(format!("M{}x{}-{}", s.d, p, spec.class), Some(format!("M{}x{}-6H", s.d, p)), p);
                }
            }
        }
        ThreadForm::Unified => {
            for s in &cat.unified {
                if !within(s.d * inch) {
                    continue;
                }
                let name = if s.d < 0.25 - 1e-9 { format!("#{}", s.name) } else { s.name.clone() };
                let series =
                    [("UNC", s.unc, spec.coarse), ("UNF", s.unf, spec.fine), ("UNEF", s.unef, spec.fine)];
                for (sname, tpi, on) in series {
                    if let (Some(t), true) = (tpi, on) {
                        let base = format!("{name}-{} {sname}", crate::ground::fmt::fmt_num(t));
                        both(format!("{base}-2A"), Some(format!("{base}-2B")), inch / t);
                    }
                }
            }
        }
        ThreadForm::Trapezoidal => {
            for (d, ps) in cat.tr.series_d.iter().zip(&cat.tr.series_pitches) {
                if !within(*d) {
                    continue;
                }
                for p in ps {
                    both(format!("Tr{d}x{p}-7e"), Some(format!("Tr{d}x{p}-7H")), *p);
                }
            }
        }
        ThreadForm::Acme => {
            for (d, tpi) in crate::standards::designation::acme_series() {
                if within(d * inch) {
                    let des = format!("{}-{} ACME-2G", inch_name(d), crate::ground::fmt::fmt_num(tpi));
                    both(des.clone(), Some(des), inch / tpi);
                }
            }
        }
        ThreadForm::Whitworth => {
            for (series, list) in [("BSW", &cat.bsw), ("BSF", &cat.bsf)] {
                for s in list {
                    let d = crate::standards::designation::inch_value(&s.size).unwrap_or(0.0) * inch;
                    if within(d) {
                        both(
                            format!("{series} {} medium", s.size),
                            Some(format!("{series} {} medium", s.size)),
                            inch / s.tpi,
                        );
                    }
                }
            }
        }
        ThreadForm::Npt => {
            let n = &cat.pipe.npt;
            for i in 0..n.sizes.len() {
                if within(n.OD[i] * inch) {
                    let des = format!("{}-{} NPT", n.sizes[i], crate::ground::fmt::fmt_num(n.tpi[i]));
                    both(des.clone(), Some(des), inch / n.tpi[i]);
                }
            }
        }
        ThreadForm::Iso7Taper => {
            let n = &cat.pipe.iso7;
            for i in 0..n.sizes.len() {
                if within(n.d[i]) {
                    both(format!("R {}", n.sizes[i]), Some(format!("Rc {}", n.sizes[i])), inch / n.tpi[i]);
                }
            }
        }
        ThreadForm::BspParallel => {
            for s in &cat.bsp {
                if within(s.d) {
                    both(format!("G{} A", s.size), Some(format!("G{}", s.size)), inch / s.tpi);
                }
            }
        }
    }
    Ok(out)
}

/// The cases, in catalogue order.
pub fn cases(spec: &CatalogueSpec) -> Result<Vec<Case>, Error> {
    // The metric class is checked once, as a usage error, not once per case.
    crate::standards::tolerance::IsoClass::parse(&spec.class)
        .map_err(|m| Error::Input(format!("‹class› {}: {m}", spec.class)))?;
    let mut out = Vec::new();
    for &form in &spec.forms {
        for (designation, p, internal) in threads(spec, form)? {
            // Parsed once for every case of the thread.
            let parsed = crate::parse_designation(&designation, crate::ParseOptions::default())?;
            let mut inserts = Vec::new();
            if spec.full {
                inserts.push(("full".to_string(), InsertChoice::Full));
            }
            if spec.partial && form.full_insert_tops_crest() {
                // A tip that fits the form's root: NPT's truncation holds an arc of 0.033·P.
                let fits = crate::BasicThread {
                    form,
                    nominal_diameter: 100.0,
                    pitch: p,
                    starts: 1,
                    hand: crate::Hand::Right,
                }
                .root_radius();
                let r = (0.1 * p).min(0.04).min(fits);
                inserts.push((
                    format!("partial r{}", crate::ground::fmt::fmt_num(r)),
                    InsertChoice::Partial { tip_radius: r },
                ));
            }
            for (iname, insert) in &inserts {
                for kind in &spec.infeeds {
                    let infeed = kind.resolve(form.flank_angle());
                    for schedule in &spec.schedules {
                        let mut v = VerifySpec::new(Some(parsed.clone()));
                        v.internal = internal;
                        v.insert = insert.clone();
                        v.infeed = Some(*kind);
                        v.schedule = schedule.clone();
                        v.gauge_only = spec.gauge_only;
                        v.metrics = false;
                        let label = format!(
                            "{designation}{} {iname} {} {}",
                            if internal { " internal" } else { "" },
                            infeed,
                            match schedule {
                                Schedule::ConstantArea => "constant-area",
                                Schedule::ConstantDepth => "constant-depth",
                                Schedule::Sandvik => "sandvik",
                                Schedule::Explicit(_) => "explicit",
                            }
                        );
                        out.push(Case { spec: v, label });
                    }
                }
            }
        }
    }
    Ok(out)
}

/// Runs every case in parallel (rayon), keeping catalogue order in the results.
///
/// ```
/// use threadcheck::{catalogue_cases, run_catalogue, CatalogueSpec};
/// use threadcheck::{InfeedChoice, Schedule};
/// // M10 coarse (ISO 261: P 1.5), full-profile insert, radial, constant area: one case.
/// let spec = CatalogueSpec {
///     diameters: (10.0, 10.0), fine: false, partial: false,
///     infeeds: vec![InfeedChoice::Radial], schedules: vec![Schedule::ConstantArea],
///     ..CatalogueSpec::default()
/// };
/// let cs = catalogue_cases(&spec)?;
/// assert_eq!(cs.len(), 1);
/// let v = run_catalogue(&cs).remove(0)?;
/// assert_eq!(v.designation.thread.pitch, 1.5);
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn run(cases: &[Case]) -> Vec<Result<Verification, Error>> {
    cases.par_iter().map(|c| verify(&c.spec)).collect()
}

/// Runs every case in parallel and keeps only what `f` makes of each (in catalogue order): a
/// sweep that reports each case in a line needs no verification kept.
pub fn run_map<T: Send>(
    cases: &[Case],
    f: impl Fn(&Case, Result<Verification, Error>) -> T + Sync,
) -> Vec<T> {
    cases.par_iter().map(|c| f(c, verify(&c.spec))).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The default catalogue: 4 infeeds × 2 schedules × 2 inserts = 16 cases per ISO 261
    /// diameter/pitch pair from M1 to M68.
    #[test]
    fn default_catalogue_counts_sixteen_cases_per_pair() {
        let cat = catalog().unwrap();
        let pairs: usize =
            cat.iso.series.sizes.iter().map(|s| usize::from(s.coarse.is_some()) + s.fine.len()).sum();
        let c = cases(&CatalogueSpec::default()).unwrap();
        assert_eq!(c.len(), 16 * pairs);
        assert!(c[0].label.starts_with("M1x0.25-6g full radial"), "{}", c[0].label);
    }

    /// Every form, external and internal: more than 10 000 cases, and each designation parses.
    #[test]
    fn all_forms_catalogue_has_over_ten_thousand_cases() {
        let spec = CatalogueSpec::all_forms();
        let c = cases(&spec).unwrap();
        assert!(c.len() >= 10_000, "{}", c.len());
        for form in &spec.forms {
            for (d, _, _) in threads(&spec, *form).unwrap() {
                let parsed = crate::parse_designation(&d, crate::ParseOptions::default());
                assert!(parsed.is_ok(), "{d}: {parsed:?}");
            }
        }
        assert_eq!(inch_name(1.25), "1 1/4");
        assert_eq!(inch_name(0.3125), "5/16");
    }
}
