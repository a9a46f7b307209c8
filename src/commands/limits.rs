//! `threadcheck limits`: the limits of size of a designation.

use super::{pretty, Dest, Document, Job, Outcome, Outputs, Request};
use crate::standards::tolerance::{limits_for, CoatingLimits, ThreadLimits};
use crate::standards::ThreadKind;
use crate::Error;
use serde::Deserialize;
use serde_with::{serde_as, DisplayFromStr};

/// The arguments of `limits`.
///
/// ```
/// use threadcheck::{Command, Document, Files, Request};
/// let c = Command::from_api("limits", r#"{"thread": "1/4-20 UNC-2A"}"#)?;
/// let out = c.run(&Request::api(Document::Text, Files::Refused))?;
/// assert!(out.document(Document::Text).unwrap_or("").contains("(20 tpi)"));
/// # Ok::<(), threadcheck::Error>(())
/// ```
#[serde_as]
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LimitsArgs {
    /// Designation, e.g. M10x1.5-6g, M10-6H/6g, "BSF 3/8 medium", "G1/2 A", "1/4-20 UNC-2A".
    #[cfg_attr(feature = "cli", arg(conflicts_with = "thread"))]
    pub designation: Option<String>,
    /// The designation as an option, as the other commands take it.
    #[cfg_attr(feature = "cli", arg(long))]
    pub thread: Option<String>,
    /// How the designation is read.
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    pub standard: super::StandardArgs,
    /// The limits to cut to before a coating of this thickness, mm (plating, anodizing;
    /// default 0).
    #[cfg_attr(feature = "cli", arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = super::args::finite))]
    pub coating: Option<f64>,
    /// Under a coating, the class applies before it (the standards' default) or after it
    /// (when the drawing says so): before | after
    #[cfg_attr(feature = "cli", arg(long, value_name = "before|after"))]
    #[serde_as(as = "Option<DisplayFromStr>")]
    pub coating_limits: Option<CoatingLimits>,
    /// A rolled external thread: the blank that fills its crest, by volume constancy (the dies
    /// set d2 at the class's middle; stated).
    #[cfg_attr(feature = "cli", arg(long))]
    pub rolled: bool,
    /// A rolled thread's blank, in the designation's units (inches for Unified, mm for metric):
    /// the major diameter it forms, checked against the class (implies ‹rolled›).
    #[cfg_attr(feature = "cli", arg(long, value_name = "DIAMETER", value_parser = super::args::finite))]
    pub blank: Option<f64>,
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    #[allow(missing_docs)]
    pub out: super::args::JsonArg,
}

impl Job for LimitsArgs {
    const NAME: &'static str = "limits";
    const DOCUMENTS: &'static [Document] = &[Document::Json, Document::Text];

    fn run(&self, request: &Request) -> Result<Outputs, Error> {
        let designation = match (&self.designation, &self.thread) {
            (Some(d), None) | (None, Some(d)) => d,
            (Some(_), Some(_)) => {
                return Err(Error::Input("give the designation once: ‹designation› or ‹thread›".into()))
            }
            (None, None) => {
                return Err(Error::Input(match self.out.json.as_deref() {
                    Some(v) if v != "-" => format!(
                        "limits needs a designation: ‹json› took '{v}' as its file; write `limits {v} --json`"
                    ),
                    _ => "limits needs a designation, e.g. limits M10x1.5-6g".into(),
                }))
            }
        };
        let des = self.standard.parse(designation)?;
        let t = &des.thread;
        let coat = |l: Option<ThreadLimits>| {
            l.map(|l| {
                crate::analysis::turn::coated(
                    l,
                    t,
                    self.coating.unwrap_or(0.0),
                    self.coating_limits.unwrap_or_default(),
                )
            })
            .transpose()
        };
        let ext = coat(limits_for(&des, ThreadKind::External)?)?;
        let int = coat(limits_for(&des, ThreadKind::Internal)?)?;
        let rolled = if self.rolled || self.blank.is_some() {
            let ext = ext.as_ref().ok_or_else(|| {
                Error::Input(format!(
                    "{}: a rolled thread is external: give its external class ({})",
                    des.text,
                    match t.form {
                        crate::standards::ThreadForm::IsoMetric => "6g, 6h, 4h …",
                        crate::standards::ThreadForm::Unified => "1A, 2A, 3A",
                        _ => "the designation's external class",
                    }
                ))
            })?;
            let unit = if t.form.is_inch() { crate::MM_PER_INCH } else { 1.0 };
            Some(crate::analysis::rolled::rolled_thread(&des, ext, self.blank.map(|b| b * unit))?)
        } else {
            None
        };
        let outcome = match rolled.as_ref().and_then(|r| r.major_ok) {
            Some(false) => Outcome::OutOfTolerance,
            _ => Outcome::Pass,
        };
        let mut text = crate::report::limits::text(&des, ext.as_ref(), int.as_ref());
        if let Some(r) = &rolled {
            text.push_str(&crate::report::limits::rolled_text(&des, r));
        }
        Ok(Outputs::new(
            outcome,
            [
                request.render(Document::Json, || {
                    pretty(
                        &crate::report::LimitsReport::new(&des, ext.as_ref(), int.as_ref())
                            .with_rolled(rolled.as_ref()),
                    )
                })?,
                Some((Document::Text, text)),
            ],
        ))
    }

    fn destinations(&self) -> Vec<(Document, Dest)> {
        Dest::list([(Document::Json, &self.out.json)], [])
    }
}

super::args::api_args!(LimitsArgs, shares nothing, reads thread at standard);
