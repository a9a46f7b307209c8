//! `threadcheck passes`: the expanded pass plan of a program or a generated plan.

use super::args::{JsonArg, PlanArgs};
use super::{pretty, Dest, Document, Job, Outcome, Outputs, Request};
use crate::report::passes::PassesSource;
use crate::Error;
use serde::Deserialize;

/// The arguments of `passes`.
///
/// ```
/// use threadcheck::{Command, Document, Files, Request};
/// // A G92 box cycle: one pass per X word.
/// let args = r#"{"program": "G0 X12 Z3\nG92 X9.4 Z-15 F1.5\nX9.0\nX8.6\nX8.2\nG0 X50\nM30\n", "program_name": "box.nc"}"#;
/// let out = Command::from_api("passes", args)?.run(&Request::api(Document::Json, Files::Refused))?;
/// let v: serde_json::Value = serde_json::from_str(out.document(Document::Json).unwrap_or("")).expect("JSON");
/// let xs: Vec<f64> = v["passes"].as_array().expect("passes").iter().map(|p| p["x_end"].as_f64().unwrap_or(0.0)).collect();
/// assert_eq!(xs, [9.4, 9.0, 8.6, 8.2]);
/// # Ok::<(), threadcheck::Error>(())
/// ```
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PassesArgs {
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    #[allow(missing_docs)]
    pub plan: PlanArgs,
    #[cfg_attr(feature = "cli", command(flatten))]
    #[serde(skip)]
    #[allow(missing_docs)]
    pub out: JsonArg,
}

super::args::api_args!(PassesArgs, shares plan: PlanArgs, reads thread at plan.standard);

impl Job for PassesArgs {
    const NAME: &'static str = "passes";
    const DOCUMENTS: &'static [Document] = &[Document::Json, Document::Text];

    /// A program is read and expanded; a generated plan is laid out as `verify` would (solving
    /// the final X when it is not given).
    fn run(&self, request: &Request) -> Result<Outputs, Error> {
        if self.plan.thread.is_empty() && self.plan.program.is_none() {
            return Err(Error::Input("passes needs ‹thread› (e.g. M10x1.5-6g) or ‹program›".into()));
        }
        if self.plan.thread.len() > 1 && self.plan.program.is_none() {
            self.plan.need_thread("passes")?;
        }
        let spec = self.plan.spec(request.files)?;
        let thread_of = |spec: &crate::analysis::turn::VerifySpec| -> Result<_, Error> {
            let r = crate::analysis::turn::resolve(spec)?;
            Ok((r.designation, r.kind, r.limits.class))
        };
        let json =
            |thread: Option<&(crate::standards::Designation, crate::standards::ThreadKind, String)>,
             passes: &[crate::toolpath::passes::Pass],
             program: Option<&crate::gcode::Program>| {
                request.render(Document::Json, || {
                    let thread = thread.map(|(d, k, c)| crate::report::ThreadReport::new(d, *k, c));
                    pretty(&crate::report::PassesReport::new(
                        thread,
                        passes,
                        program.map(|p| p.operations.as_slice()),
                        program.map(|p| (p.notes.as_slice(), p.read_past_blocks, &p.machine)),
                    ))
                })
            };
        let (json, text) = match &spec.program {
            Some((source, dialect)) => {
                let (shown, text) = source.load()?;
                let prog = crate::gcode::read_program_with(&text, &shown, *dialect, spec.reading.clone())?;
                let thread = if spec.designation.is_none() { None } else { Some(thread_of(&spec)?) };
                let source = PassesSource::Program { shown: &shown, dialect: *dialect, program: &prog };
                (
                    json(thread.as_ref(), &prog.passes, Some(&prog))?,
                    crate::report::passes::text(source, &prog.passes),
                )
            }
            None => {
                // With the final X given, the plan is laid out without cutting it.
                let (thread, passes, blank, final_x) = match spec.final_x {
                    Some(x) => {
                        let r = crate::analysis::turn::resolve(&spec)?;
                        let passes = r.plan(x).generate()?;
                        ((r.designation, r.kind, r.limits.class), passes, r.blank, x)
                    }
                    None => {
                        let v = crate::analysis::turn::verify(&spec)?;
                        ((v.designation, v.kind, v.limits.class), v.passes, v.blank_diameter, v.final_x)
                    }
                };
                let source =
                    PassesSource::Plan { designation: &thread.0.text, kind: thread.1, blank, final_x };
                (json(Some(&thread), &passes, None)?, crate::report::passes::text(source, &passes))
            }
        };
        Ok(Outputs::new(Outcome::Pass, [json, Some((Document::Text, text))]).reading(self.plan.inputs()))
    }

    fn destinations(&self) -> Vec<(Document, Dest)> {
        Dest::list([(Document::Json, &self.out.json)], [])
    }
}
