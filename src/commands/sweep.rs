//! `threadcheck sweep`: the catalogue verified in parallel.

use super::args::JsonArg;
use super::{Dest, Document, Job, Outcome, Outputs, Request};
use crate::analysis::study::sweep::CatalogueSpec;
use crate::standards::ThreadForm;
use crate::toolpath::passes::{InfeedChoice, Schedule};
use crate::Error;
use std::fmt::Write as _;
use std::path::PathBuf;

/// A form of `sweep --form`.
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FormSet {
    /// ISO metric, ISO 261.
    #[cfg_attr(feature = "cli", value(alias = "metric"))]
    IsoMetric,
    /// Unified inch, ASME B1.1.
    Unified,
    /// ISO metric trapezoidal.
    Trapezoidal,
    /// General-purpose Acme.
    Acme,
    /// BS 84 Whitworth.
    Whitworth,
    /// ISO 228-1 parallel pipe.
    #[cfg_attr(feature = "cli", value(alias = "bsp"))]
    BspParallel,
    /// ASME B1.20.1 NPT.
    Npt,
    /// ISO 7-1 taper pipe.
    #[cfg_attr(feature = "cli", value(alias = "iso7"))]
    Iso7Taper,
    /// Every form.
    All,
}

impl FormSet {
    fn forms(self) -> Vec<ThreadForm> {
        match self {
            FormSet::IsoMetric => vec![ThreadForm::IsoMetric],
            FormSet::Unified => vec![ThreadForm::Unified],
            FormSet::Trapezoidal => vec![ThreadForm::Trapezoidal],
            FormSet::Acme => vec![ThreadForm::Acme],
            FormSet::Whitworth => vec![ThreadForm::Whitworth],
            FormSet::BspParallel => vec![ThreadForm::BspParallel],
            FormSet::Npt => vec![ThreadForm::Npt],
            FormSet::Iso7Taper => vec![ThreadForm::Iso7Taper],
            FormSet::All => CatalogueSpec::all_forms().forms,
        }
    }
}

/// The pitch series of `sweep --series`.
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SeriesSet {
    /// The coarse series.
    Coarse,
    /// The fine series.
    Fine,
    /// Both.
    All,
}

/// The inserts of `sweep --insert`.
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InsertSet {
    /// Full-profile inserts.
    Full,
    /// Partial-profile inserts.
    Partial,
    /// Both.
    Both,
}

/// The arguments of `sweep` (the command line's alone).
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[derive(Clone, Debug)]
pub struct SweepArgs {
    /// Forms (comma-separated).
    #[cfg_attr(feature = "cli", arg(long, value_delimiter = ',', default_value = "iso-metric"))]
    pub form: Vec<FormSet>,
    /// Also the internal threads, in each form's medium internal class.
    #[cfg_attr(feature = "cli", arg(long))]
    pub internal: bool,
    /// Pitch series.
    #[cfg_attr(feature = "cli", arg(long, value_enum, default_value = "all"))]
    pub series: SeriesSet,
    /// Smallest nominal diameter, mm.
    #[cfg_attr(feature = "cli", arg(long, default_value = "1", value_parser = crate::commands::args::finite))]
    pub min_d: f64,
    /// Largest nominal diameter, mm.
    #[cfg_attr(feature = "cli", arg(long, default_value = "68", value_parser = crate::commands::args::finite))]
    pub max_d: f64,
    /// Tolerance class of the external thread.
    #[cfg_attr(feature = "cli", arg(long, default_value = "6g"))]
    pub class: String,
    /// Inserts.
    #[cfg_attr(feature = "cli", arg(long, value_enum, default_value = "both"))]
    pub insert: InsertSet,
    /// Comma-separated infeeds, as verify takes them: radial, flank[:ANGLE], modified,
    /// alternating[:ANGLE].
    #[cfg_attr(
        feature = "cli",
        arg(long, value_delimiter = ',', default_value = "radial,flank,modified,alternating")
    )]
    pub infeed: Vec<InfeedChoice>,
    /// Comma-separated schedules: constant-area, constant-depth, sandvik.
    #[cfg_attr(
        feature = "cli",
        arg(long, value_delimiter = ',', default_value = "constant-area,constant-depth")
    )]
    pub schedule: Vec<Schedule>,
    /// Leave form checks out of the verdicts.
    #[cfg_attr(feature = "cli", arg(long))]
    pub gauge_only: bool,
    /// One verify report per line (JSON Lines): on stdout (`--json` or `--json -`, the
    /// summary then goes to stderr), or written to FILE.
    #[cfg_attr(feature = "cli", command(flatten))]
    pub out: JsonArg,
    /// Write each case's blank, placements and measured d2 here (JSON Lines).
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE"))]
    pub export_placements: Option<PathBuf>,
}

impl SweepArgs {
    fn spec(&self) -> Result<CatalogueSpec, Error> {
        if self.min_d > self.max_d {
            return Err(Error::Input("‹min_d› must not be above ‹max_d›".into()));
        }
        let mut spec = CatalogueSpec::default();
        (spec.coarse, spec.fine) = match self.series {
            SeriesSet::Coarse => (true, false),
            SeriesSet::Fine => (false, true),
            SeriesSet::All => (true, true),
        };
        (spec.full, spec.partial) = match self.insert {
            InsertSet::Full => (true, false),
            InsertSet::Partial => (false, true),
            InsertSet::Both => (true, true),
        };
        spec.diameters = (self.min_d, self.max_d);
        spec.class = self.class.clone();
        spec.forms = self.form.iter().flat_map(|f| f.forms()).collect();
        spec.forms.dedup();
        spec.internal = self.internal;
        spec.infeeds = self.infeed.clone();
        spec.schedules = self.schedule.clone();
        spec.gauge_only = self.gauge_only;
        Ok(spec)
    }
}

impl Job for SweepArgs {
    const NAME: &'static str = "sweep";
    const DOCUMENTS: &'static [Document] = &[Document::Json, Document::Text];

    /// Out of tolerance when any case fails; with the JSON on standard output the summary line
    /// goes to standard error.
    fn run(&self, request: &Request) -> Result<Outputs, Error> {
        let spec = self.spec()?;
        let json = request.wants(Document::Json);
        let export_wanted = self.export_placements.is_some();
        let start = std::time::Instant::now();
        let cases = crate::analysis::study::sweep::cases(&spec)?;
        if cases.is_empty() {
            return Err(Error::Input("the catalogue selection is empty".into()));
        }
        // Each case becomes its lines as soon as it is verified, in parallel: no verification is
        // kept, so memory stays at one case per thread.
        let lines =
            crate::analysis::study::sweep::run_map(&cases, |c, r| -> Result<(bool, String, String), Error> {
                let mut out = String::new();
                let mut export = String::new();
                let ok = match r {
                    Ok(v) => {
                        if json {
                            out.push_str(&crate::report::to_json_line(&crate::report::VerifyReport::of(&v))?);
                        } else if !v.pass {
                            let failed: Vec<String> = v
                                .checks
                                .iter()
                                .filter(|k| k.fails(v.gauge_only))
                                .map(|k| {
                                    if k.deviation_um != 0.0 {
                                        format!("{} {:+.1} µm", k.feature, k.deviation_um)
                                    } else {
                                        k.feature.to_string()
                                    }
                                })
                                .collect();
                            let _ = writeln!(out, "FAIL {}: {}", c.label, failed.join(", "));
                        }
                        if export_wanted {
                            export.push_str(&placements_line(&c.label, &c.spec, &v)?);
                        }
                        v.pass
                    }
                    Err(e) => {
                        if json {
                            out.push_str(&crate::report::to_json_line(&crate::report::CaseError {
                                case: &c.label,
                                error: e.to_string(),
                            })?);
                        } else {
                            let _ = writeln!(out, "ERROR {}: {e}", c.label);
                        }
                        false
                    }
                };
                Ok((ok, out, export))
            });
        let (mut pass, mut fail) = (0usize, 0usize);
        let mut out = String::new();
        let mut export = String::new();
        for l in lines {
            let (ok, o, e) = l?;
            if ok {
                pass += 1;
            } else {
                fail += 1;
            }
            out.push_str(&o);
            export.push_str(&e);
        }
        let summary = format!(
            "{} cases, {pass} pass, {fail} fail, {:.3} s\n",
            cases.len(),
            start.elapsed().as_secs_f64()
        );
        // Exit 1 when any case fails, as verify does.
        let mut o = Outputs::new(
            Outcome::of(fail == 0),
            if json {
                [Some((Document::Json, out)), Some((Document::Text, summary.clone()))]
            } else {
                [None, Some((Document::Text, out + &summary))]
            },
        );
        o.aside = Some(summary);
        if let Some(p) = &self.export_placements {
            o.files.push((p.clone(), export.into_bytes()));
        }
        Ok(o)
    }

    fn destinations(&self) -> Vec<(Document, Dest)> {
        Dest::list([(Document::Json, &self.out.json)], [])
    }
}

fn placements_line(
    label: &str,
    spec: &crate::analysis::turn::VerifySpec,
    v: &crate::analysis::turn::Verification,
) -> Result<String, Error> {
    let t = &v.designation.thread;
    let setup = crate::geometry::sweep::SweepSetup {
        kind: v.kind,
        insert: &v.insert,
        blank_diameter: v.blank_diameter,
        pitch: t.pitch,
    };
    let window = crate::geometry::sweep::Window::around(v.z_ref, t.pitch, 4.0);
    let (blank, rings) = crate::geometry::sweep::placements(&setup, &v.passes, window)?;
    // threadcheck's own time for the same work on the same placements (sweep + pitch
    // diameter), best of five, so the baseline can state a ratio measured in one run.
    let ms = crate::geometry::measure::MeasureSetup {
        thread: t,
        kind: v.kind,
        mmc_pitch_diameter: None,
        mmc_major_diameter: None,
        extras: false,
    };
    let mut best = f64::INFINITY;
    for _ in 0..5 {
        let start = std::time::Instant::now();
        let s = crate::geometry::sweep::sweep(
            &setup,
            &v.passes,
            window,
            crate::geometry::boolean::UnionStrategy::Envelope,
        )?;
        let m = crate::geometry::measure::measure(&ms, &s.section.profile(), v.z_ref)?;
        std::hint::black_box(m.pitch_diameter);
        best = best.min(start.elapsed().as_secs_f64());
    }
    // And the whole verify of the case (designation, limits, plan, sweep, measure with the
    // three-wire M and the GO clearance, checks), best of five.
    let mut whole = f64::INFINITY;
    for _ in 0..5 {
        let start = std::time::Instant::now();
        std::hint::black_box(crate::analysis::turn::verify(spec)?.pass);
        whole = whole.min(start.elapsed().as_secs_f64());
    }
    let ring = |r: &[crate::Point]| r.iter().map(|p| [p.z, p.r]).collect::<Vec<_>>();
    crate::report::to_json_line(&crate::report::PlacementsLine {
        verify_seconds: whole,
        case: label,
        kind: v.kind.name(),
        pitch: t.pitch,
        z_ref: v.z_ref,
        blank: ring(&blank),
        placements: rings.iter().map(|r| ring(r)).collect(),
        pitch_diameter: v.measurement.pitch_diameter,
        threadcheck_seconds: best,
    })
}
