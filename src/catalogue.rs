//! The catalogue sweep: `verify` over every size of ISO 261 (M1 to M68, coarse and fine) in a
//! class, with every insert, infeed and schedule asked for, in parallel.

use crate::passes::{Infeed, Schedule};
use crate::standards::catalog;
use crate::verify::{verify, InsertChoice, Verification, VerifySpec};
use crate::Error;
use rayon::prelude::*;

/// What to sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct CatalogueSpec {
    /// Include coarse pitches.
    pub coarse: bool,
    /// Include fine pitches.
    pub fine: bool,
    /// Smallest and largest nominal diameter, mm.
    pub diameters: (f64, f64),
    /// Tolerance class, e.g. `6g`.
    pub class: String,
    /// Full-profile insert cases.
    pub full: bool,
    /// Partial-profile insert cases (tip radius min(0.04, 0.1·P) mm, so that the finest pitches
    /// get an insert whose tip fits their root).
    pub partial: bool,
    /// Infeeds.
    pub infeeds: Vec<Infeed>,
    /// Schedules.
    pub schedules: Vec<Schedule>,
    /// Leave form checks out of the verdicts.
    pub gauge_only: bool,
}

impl Default for CatalogueSpec {
    /// The whole catalogue of issue 7: M1–M68 coarse and fine in 6g, full and partial inserts,
    /// radial, flank, 29.5° modified-flank and alternating infeed, constant area and depth.
    fn default() -> Self {
        CatalogueSpec {
            coarse: true,
            fine: true,
            diameters: (1.0, 68.0),
            class: "6g".into(),
            full: true,
            partial: true,
            infeeds: vec![
                Infeed::Radial,
                Infeed::Flank { angle: 30.0 },
                Infeed::Flank { angle: 29.5 },
                Infeed::Alternating { angle: 30.0 },
            ],
            schedules: vec![Schedule::ConstantArea, Schedule::ConstantDepth],
            gauge_only: false,
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

/// The cases, in catalogue order.
pub fn cases(spec: &CatalogueSpec) -> Result<Vec<Case>, Error> {
    let cat = catalog()?;
    let mut out = Vec::new();
    for s in &cat.iso.series.sizes {
        if s.d < spec.diameters.0 - 1e-9 || s.d > spec.diameters.1 + 1e-9 {
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
            let designation = format!("M{}x{}-{}", s.d, p, spec.class);
            let mut inserts = Vec::new();
            if spec.full {
                inserts.push(("full".to_string(), InsertChoice::Full));
            }
            if spec.partial {
                let r = (0.1 * p).min(0.04);
                inserts.push((format!("partial r{r}"), InsertChoice::Partial { tip_radius: r }));
            }
            for (iname, insert) in &inserts {
                for infeed in &spec.infeeds {
                    for schedule in &spec.schedules {
                        let mut v = VerifySpec::new(&designation);
                        v.insert = insert.clone();
                        v.infeed = Some(*infeed);
                        v.schedule = schedule.clone();
                        v.gauge_only = spec.gauge_only;
                        v.metrics = false;
                        let label = format!(
                            "{designation} {iname} {} {}",
                            crate::report::infeed_text(infeed),
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
pub fn run(cases: &[Case]) -> Vec<Result<Verification, Error>> {
    cases.par_iter().map(|c| verify(&c.spec)).collect()
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
}
