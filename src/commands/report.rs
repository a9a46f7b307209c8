//! `threadcheck report`: regenerates a committed report.

use super::{Dest, Document, Job, Outcome, Outputs, Request};
use crate::Error;
use std::path::PathBuf;

/// The committed reports `report` regenerates.
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReportName {
    /// reports/infeed-comparison.md and its SVGs.
    InfeedComparison,
}

/// The arguments of `report` (the command line's alone).
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[derive(Clone, Debug)]
pub struct ReportArgs {
    /// Which report.
    #[cfg_attr(feature = "cli", arg(value_enum))]
    pub name: ReportName,
    /// Folder to write it and its pictures into.
    #[cfg_attr(feature = "cli", arg(long, default_value = "reports"))]
    pub out: PathBuf,
}

impl Job for ReportArgs {
    const NAME: &'static str = "report";
    const DOCUMENTS: &'static [Document] = &[Document::Text];

    /// `infeed-comparison`: every strategy compared on the report's threads with a full- and a
    /// partial-profile insert; the page and its pictures are the run's files.
    fn run(&self, request: &Request) -> Result<Outputs, Error> {
        use crate::analysis::study::compare::{compare, REPORT_THREADS};
        use crate::analysis::tools::InsertChoice;
        use crate::analysis::turn::VerifySpec;
        match self.name {
            ReportName::InfeedComparison => {
                let inserts = [
                    ("full-profile", InsertChoice::Full),
                    ("partial-profile r0.04", InsertChoice::Partial { tip_radius: 0.04 }),
                ];
                let mut runs = Vec::new();
                for d in REPORT_THREADS {
                    for (iname, choice) in &inserts {
                        let spec = VerifySpec { insert: choice.clone(), picture: true, ..VerifySpec::of(d)? };
                        runs.push((d, *iname, compare(&spec, &[29.5, 27.0], &Default::default())?));
                    }
                }
                let sections: Vec<crate::report::compare::InfeedSection<'_>> = runs
                    .iter()
                    .map(|(thread, insert, comparison)| crate::report::compare::InfeedSection {
                        thread,
                        insert,
                        comparison,
                    })
                    .collect();
                let (md, pictures) = crate::report::compare::infeed_comparison_page(&sections);
                let page = self.out.join("infeed-comparison.md");
                let mut o = Outputs::new(
                    Outcome::Pass,
                    [Some((Document::Text, format!("wrote {}\n", page.display())))],
                );
                // The page is the command line's: its words name flags as `request.reader` does.
                let words = |t: String| request.reader.words(&t).into_bytes();
                o.files = pictures.into_iter().map(|(name, svg)| (self.out.join(name), words(svg))).collect();
                o.files.push((page, words(md)));
                Ok(o)
            }
        }
    }

    fn destinations(&self) -> Vec<(Document, Dest)> {
        Vec::new()
    }
}
