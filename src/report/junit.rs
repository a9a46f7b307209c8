//! A run of many programs as JUnit XML (every CI server's test view): a test suite per program,
//! a test case per thread-making operation (failed with its findings), and an error case for a
//! program that could not be read. The elements and attributes are those of the JUnit schema CI
//! servers validate against (Jenkins xUnit's `junit-10.xsd`, in `tests/data/schemas/`). A view of
//! the run's [`BatchProgram`]s; nothing is computed here.

use super::batch::BatchProgram;
use crate::analysis::check::Verdict;
use quick_xml::events::{BytesDecl, BytesText, Event};
use quick_xml::Writer;

/// The JUnit XML of a run.
pub fn junit_xml(programs: &[BatchProgram]) -> Result<String, crate::Error> {
    let cases = |p: &BatchProgram| p.operations.len() + usize::from(p.error.is_some());
    let failures = |p: &BatchProgram| p.operations.iter().filter(|o| o.verdict != Verdict::Pass).count();
    let errors = |p: &BatchProgram| usize::from(p.error.is_some());
    let total = |f: &dyn Fn(&BatchProgram) -> usize| programs.iter().map(f).sum::<usize>().to_string();
    let mut w = Writer::new_with_indent(Vec::new(), b' ', 2);
    let xml = w.write_event(Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None))).and_then(|()| {
        w.create_element("testsuites")
            .with_attributes([
                ("name", "threadcheck"),
                ("tests", total(&cases).as_str()),
                ("failures", total(&failures).as_str()),
                ("errors", total(&errors).as_str()),
            ])
            .write_inner_content(|w| {
                for p in programs {
                    suite(w, p, cases(p), failures(p), errors(p))?;
                }
                Ok(())
            })
            .map(|_| ())
    });
    xml.map_err(|e| crate::Error::Data(format!("JUnit XML: {e}")))?;
    let mut xml =
        String::from_utf8(w.into_inner()).map_err(|e| crate::Error::Data(format!("JUnit XML: {e}")))?;
    xml.push('\n');
    Ok(xml)
}

/// One program's test suite.
fn suite(
    w: &mut Writer<Vec<u8>>,
    p: &BatchProgram,
    cases: usize,
    failures: usize,
    errors: usize,
) -> std::io::Result<()> {
    w.create_element("testsuite")
        .with_attributes([
            ("name", p.file.as_str()),
            ("tests", cases.to_string().as_str()),
            ("failures", failures.to_string().as_str()),
            ("errors", errors.to_string().as_str()),
            ("skipped", "0"),
            ("file", p.file.as_str()),
        ])
        .write_inner_content(|w| {
            if let Some(e) = &p.error {
                w.create_element("testcase")
                    .with_attributes([("name", "read the program"), ("classname", p.file.as_str())])
                    .write_inner_content(|w| {
                        w.create_element("error")
                            .with_attributes([("type", "unreadable"), ("message", e.as_str())])
                            .write_empty()
                            .map(|_| ())
                    })?;
            }
            for o in &p.operations {
                let name = format!(
                    "line {}: {} {}",
                    o.line,
                    o.made.name(),
                    if o.designation.is_empty() { "thread" } else { &o.designation }
                );
                let case = w
                    .create_element("testcase")
                    .with_attributes([("name", name.as_str()), ("classname", p.file.as_str())]);
                if o.verdict == Verdict::Pass {
                    case.write_empty()?;
                    continue;
                }
                let text: Vec<String> = o
                    .findings
                    .iter()
                    .map(|f| format!("{}:{}:{}: {}", p.file, o.line, o.column, f.message))
                    .collect();
                let failed = o.failed.join(", ");
                case.write_inner_content(|w| {
                    w.create_element("failure")
                        .with_attributes([
                            ("type", o.findings.first().map_or("fail", |f| f.rule.as_str())),
                            ("message", failed.as_str()),
                        ])
                        .write_text_content(BytesText::new(&text.join("\n")))
                        .map(|_| ())
                })?;
            }
            Ok(())
        })
        .map(|_| ())
}
