//! A run of many programs as SARIF 2.1.0 (code scanning shows each finding at its line): one
//! result per failing check of an operation, and one per program that could not be read. A view of
//! the run's [`BatchProgram`]s; nothing is computed here.

use super::batch::BatchProgram;
use serde_sarif::sarif;

/// The characters a SARIF `uri` keeps as they are (RFC 3986's unreserved ones and the path's
/// `/`); every other byte is percent-encoded.
const URI_PATH: &percent_encoding::AsciiSet =
    &percent_encoding::NON_ALPHANUMERIC.remove(b'-').remove(b'.').remove(b'_').remove(b'~').remove(b'/');

/// A program's path as a SARIF artifact `uri`: relative paths stay relative (code scanning
/// places them from the repository's root), absolute ones become `file://` URIs.
pub fn artifact_uri(file: &str) -> String {
    let slashed = file.replace('\\', "/");
    let encoded = percent_encoding::utf8_percent_encode(&slashed, URI_PATH).to_string();
    if slashed.starts_with('/') {
        format!("file://{encoded}")
    } else {
        encoded.trim_start_matches("./").to_string()
    }
}

/// What a rule checks, for the SARIF rule's short description.
fn rule_words(rule: &str) -> String {
    let (made, check) = rule.split_once('.').unwrap_or(("", rule));
    let made = match made {
        "turned" => "turned thread",
        "tapped" => "tapped hole",
        "milled" => "thread-milled hole",
        _ => "program",
    };
    format!("{made}: {}", check.replace('_', " "))
}

/// The SARIF log of a run: `version` is threadcheck's.
pub fn sarif_log(programs: &[BatchProgram], version: &str, exit_code: i32) -> Result<String, crate::Error> {
    let mut rules: Vec<String> = Vec::new();
    let mut results = Vec::new();
    let mut rule_index = |rule: &str| -> i64 {
        match rules.iter().position(|r| r == rule) {
            Some(i) => i as i64,
            None => {
                rules.push(rule.to_string());
                rules.len() as i64 - 1
            }
        }
    };
    let location = |file: &str, at: Option<(usize, usize)>| {
        let artifact = sarif::ArtifactLocation::builder().uri(artifact_uri(file)).build();
        let physical = match at {
            Some((line, column)) => sarif::PhysicalLocation::builder()
                .artifact_location(artifact)
                .region(
                    sarif::Region::builder()
                        .start_line(line.max(1) as i64)
                        .start_column(column.max(1) as i64)
                        .build(),
                )
                .build(),
            None => sarif::PhysicalLocation::builder().artifact_location(artifact).build(),
        };
        sarif::Location::builder().physical_location(physical).build()
    };
    for p in programs {
        if let Some(e) = &p.error {
            let i = rule_index("program.unreadable");
            results.push(
                sarif::Result::builder()
                    .rule_id("program.unreadable")
                    .rule_index(i)
                    .level(sarif::ResultLevel::Error)
                    .message(sarif::Message::builder().text(e.clone()).build())
                    .locations(vec![location(&p.file, p.error_at)])
                    .build(),
            );
            continue;
        }
        for o in &p.operations {
            let what = format!(
                "{} {}",
                o.made.name(),
                if o.designation.is_empty() { "thread" } else { &o.designation }
            );
            for f in &o.findings {
                let i = rule_index(&f.rule);
                results.push(
                    sarif::Result::builder()
                        .rule_id(f.rule.clone())
                        .rule_index(i)
                        .level(sarif::ResultLevel::Error)
                        .message(sarif::Message::builder().text(format!("{what}: {}", f.message)).build())
                        .locations(vec![location(&p.file, Some((o.line, o.column)))])
                        .build(),
                );
            }
        }
    }
    let descriptors: Vec<sarif::ReportingDescriptor> = rules
        .iter()
        .map(|r| {
            sarif::ReportingDescriptor::builder()
                .id(r.clone())
                .short_description(sarif::MultiformatMessageString::builder().text(rule_words(r)).build())
                .build()
        })
        .collect();
    let driver = sarif::ToolComponent::builder()
        .name("threadcheck")
        .version(version.to_string())
        .rules(descriptors)
        .build();
    let invocation =
        sarif::Invocation::builder().execution_successful(true).exit_code(i64::from(exit_code)).build();
    let run = sarif::Run::builder()
        .tool(sarif::Tool::builder().driver(driver).build())
        .invocations(vec![invocation])
        .results(results)
        .build();
    let log = sarif::Sarif::builder()
        .schema("https://json.schemastore.org/sarif-2.1.0.json")
        .version(serde_json::json!("2.1.0"))
        .runs(vec![run])
        .build();
    super::to_json_pretty(&log)
}
