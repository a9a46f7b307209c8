//! A tool library in Autodesk Fusion's JSON (its tool library export, `.json`, or a `.tools`
//! file that holds the same JSON) read as a tool table (issue 65 item 3).
//!
//! The fields read, as public tool libraries and the programs that read them write them: the
//! document's `data` (a list of tools); each tool's `type` (`"tap right hand"`, `"tap left
//! hand"`, `"drill"`, `"thread mill"`), `unit` (`"millimeters"` or `"inches"`, every length in
//! it), `description`, `geometry` (`DC` the cutting diameter, `TP` the thread pitch, `SIG` a
//! drill's point angle, `thread-profile-angle` a thread mill's tooth angle) and
//! `post-process.number` (the T number the program calls). What is read, by named defaults:
//! - a tap's thread is the standard size of its `DC` and `TP` of its `thread-profile-angle`
//!   (else 60°) with the standard's default class for a nut (6H, 2B, …), left-hand for `"tap
//!   left hand"`; where two series fit that size alike (1/4-20 UNC and BSW 1/4), the one its
//!   description names, else the tap is passed by; a form tap when its description
//!   says so (FORM, ROLL, as a program's comments);
//! - a thread mill is single-form, its tooth's tip sharp (`thread-profile-angle`, else 60°);
//! - a tool of another type (end mills, turning tools) is not a thread's and is passed by; a
//!   tap or thread mill without what it needs is passed by too, and the T the program calls
//!   then says that no table names it.

use crate::analysis::tools::{Tool, ToolTable, DEFAULT_TAP_CHAMFER_PITCHES};
use crate::Error;

/// Whether `text` is a JSON document (a Fusion library) rather than a TOML tool table.
pub fn is_json(text: &str) -> bool {
    text.trim_start().starts_with('{')
}

/// Reads a Fusion tool library's JSON; `source` names it in messages.
///
/// ```
/// let lib = r#"{"data": [{"type": "tap right hand", "unit": "millimeters", "description": "M10 tap",
///   "geometry": {"DC": 10, "TP": 1.5}, "post-process": {"number": 6}}]}"#;
/// let t = threadcheck::fusion_tool_table(lib, "lib.json")?;
/// assert!(matches!(t.tool(6), Some((threadcheck::Tool::Tap { designation, .. }, _)) if designation == "M10x1.5-6H"));
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn tool_table(text: &str, source: &str) -> Result<ToolTable, Error> {
    let ferr = |m: String| Error::File { file: source.to_string(), message: m };
    let doc: serde_json::Value = serde_json::from_str(text).map_err(|e| Error::Program {
        file: source.to_string(),
        line: e.line(),
        column: e.column(),
        message: format!("not JSON: {e}"),
    })?;
    let data = doc.get("data").and_then(|d| d.as_array()).ok_or_else(|| {
        ferr("a Fusion tool library holds its tools in \"data\", a list: it is not there".into())
    })?;
    let mut entries = Vec::new();
    for tool in data {
        let Some(kind) = tool.get("type").and_then(|t| t.as_str()) else { continue };
        let Some(t) = tool.pointer("/post-process/number").and_then(serde_json::Value::as_u64) else {
            continue;
        };
        let Ok(t) = u32::try_from(t) else { continue };
        let scale = match tool.get("unit").and_then(|u| u.as_str()) {
            Some("inches") => 25.4,
            _ => 1.0,
        };
        let geo =
            |key: &str| tool.get("geometry").and_then(|g| g.get(key)).and_then(serde_json::Value::as_f64);
        let description = tool.get("description").and_then(|d| d.as_str()).unwrap_or("");
        let written = format!("{kind} T{t}: {description}");
        let entry = match kind {
            "tap right hand" | "tap left hand" => {
                let (Some(d), Some(p)) = (geo("DC"), geo("TP")) else { continue };
                let (d, p) = (d * scale, p * scale);
                if !(d > 0.0 && p > 0.0 && d.is_finite() && p.is_finite()) {
                    continue;
                }
                let units = if scale == 1.0 {
                    crate::gcode::ProgramUnits::Mm
                } else {
                    crate::gcode::ProgramUnits::Inch
                };
                // The tap's profile angle tells ISO metric from trapezoidal and Whitworth.
                let angle = geo("thread-profile-angle").filter(|a| *a > 0.0 && *a < 180.0).unwrap_or(60.0);
                // Where two series fit alike (1/4-20 UNC and BSW 1/4: Ø6.35 at 20 tpi, 60° and 55°
                // within the angle's 5°), the thread the description names, if it is that size.
                let named = match crate::analysis::naming::infer_designation_with(
                    p,
                    1,
                    d,
                    crate::standards::ThreadKind::Internal,
                    units,
                    0,
                    Some(angle),
                ) {
                    Ok(n) => n.designation.text,
                    Err(_) => match described(description, d, p) {
                        Some(n) => n,
                        None => continue,
                    },
                };
                let upper = description.to_ascii_uppercase();
                let forming = ["FORM", "ROLL"]
                    .iter()
                    .any(|w| upper.split(|c: char| !c.is_ascii_alphanumeric()).any(|x| x == *w));
                let left = crate::standards::designation::parse_designation(&named, Default::default())
                    .is_ok_and(|d| d.thread.hand == crate::standards::Hand::Left);
                let designation =
                    if kind == "tap left hand" && !left { format!("{named}-LH") } else { named };
                Tool::Tap {
                    designation,
                    chamfer_pitches: DEFAULT_TAP_CHAMFER_PITCHES,
                    chamfer_given: false,
                    forming,
                }
            }
            "drill" => {
                let Some(d) = geo("DC").map(|d| d * scale).filter(|d| *d > 0.0 && *d < 1000.0) else {
                    continue;
                };
                Tool::Drill { diameter: d, point_angle: geo("SIG").filter(|a| *a > 0.0 && *a < 180.0) }
            }
            "thread mill" => {
                let Some(d) = geo("DC").map(|d| d * scale).filter(|d| *d > 0.0 && *d < 1000.0) else {
                    continue;
                };
                let angle = geo("thread-profile-angle").filter(|a| *a > 0.0 && *a < 180.0).unwrap_or(60.0);
                Tool::Insert(crate::analysis::tools::InsertChoice::Toml {
                    name: format!("{source} T{t}"),
                    text: format!("kind = \"thread-mill\"\ndiameter = {d}\nangle = {angle}\ntip_radius = 0.0\nrows = 1\n"),
                })
            }
            _ => continue,
        };
        entries.push((t, entry, written));
    }
    Ok(ToolTable::from_entries(source, entries))
}

/// The nut's designation a tool's description names, when it is the size `d` × `p` (mm): with
/// its class, the standard's default for a nut where the description names none.
fn described(description: &str, d: f64, p: f64) -> Option<String> {
    let opts = crate::standards::designation::ParseOptions::default();
    let found = crate::analysis::naming::designation_in_comment(description, opts)?;
    let t = &found.designation.thread;
    if (t.nominal_diameter - d).abs() > 1e-3 || (t.pitch - p).abs() > 1e-4 {
        return None;
    }
    Some(match found.designation.internal {
        Some(_) => found.text,
        None => found.designation.with_example_class(crate::standards::ThreadKind::Internal),
    })
}
