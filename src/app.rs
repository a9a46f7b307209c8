//! Validated jobs behind the command line. `main.rs` parses arguments into one of these, runs it
//! and maps the [`Outcome`] to an exit code; everything here is usable without the CLI.

use crate::standards::{parse_designation, Designation, ParseOptions, ThreadKind};
use crate::tolerance::{basic_rounded, limits_for, Limit, ThreadLimits};
use crate::Error;
use serde_json::json;
use std::fmt::Write as _;

/// What a job concluded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// The job did its work; for `verify`, the thread is within every limit (exit 0).
    Pass,
    /// `verify` ran and the thread is out of tolerance (exit 1).
    OutOfTolerance,
}

impl Outcome {
    /// The process exit code: 0 pass, 1 out of tolerance (2, errors, is the caller's).
    pub fn exit_code(self) -> i32 {
        match self {
            Outcome::Pass => 0,
            Outcome::OutOfTolerance => 1,
        }
    }
}

/// `threadcheck limits`: the limits of size of a designation.
#[derive(Clone, Debug)]
pub struct LimitsJob {
    /// The designation text.
    pub designation: String,
    /// Accept sizes outside the standard series.
    pub allow_nonstandard: bool,
    /// The JSON: `-` prints it on stdout instead of the table, a path writes it there.
    pub json: Option<String>,
}

impl LimitsJob {
    /// Runs the job, returning what to print on stdout.
    pub fn run(&self) -> Result<(String, Outcome), Error> {
        let des =
            parse_designation(&self.designation, ParseOptions { allow_nonstandard: self.allow_nonstandard })?;
        let ext = limits_for(&des, ThreadKind::External)?;
        let int = limits_for(&des, ThreadKind::Internal)?;
        let json_text =
            self.json.as_ref().map(|_| pretty(&limits_json(&des, ext.as_ref(), int.as_ref()))).transpose()?;
        let text = limits_table(&des, ext.as_ref(), int.as_ref());
        Ok((route_json(self.json.as_deref(), json_text, text)?, Outcome::Pass))
    }
}

/// The `limits --json` object of the CLI contract.
pub fn limits_json(
    des: &Designation,
    ext: Option<&ThreadLimits>,
    int: Option<&ThreadLimits>,
) -> serde_json::Value {
    let t = &des.thread;
    let (d, d2, d3, d1, h) = basic_rounded(t);
    let side =
        |l: Option<&ThreadLimits>| l.map(|l| serde_json::to_value(l).unwrap_or(serde_json::Value::Null));
    json!({
        "designation": des.text,
        "form": t.form.name(),
        "nominal_diameter": t.nominal_diameter,
        "pitch": t.pitch,
        "lead": t.lead(),
        "starts": t.starts,
        "hand": match t.hand { crate::Hand::Right => "right", crate::Hand::Left => "left" },
        "nonstandard": des.nonstandard,
        "basic": {
            "major_diameter": d,
            "pitch_diameter": d2,
            "minor_diameter_external": d3,
            "minor_diameter_internal": d1,
            "fundamental_triangle_height": h,
        },
        "external": side(ext),
        "internal": side(int),
    })
}

fn fmt_opt(v: Option<f64>) -> String {
    v.map_or_else(|| "—".to_string(), |x| format!("{x:.3}"))
}

fn limits_table(des: &Designation, ext: Option<&ThreadLimits>, int: Option<&ThreadLimits>) -> String {
    let t = &des.thread;
    let (d, d2, d3, d1, h) = basic_rounded(t);
    let mut s = String::new();
    let hand = if t.hand == crate::Hand::Left { "left-hand" } else { "right-hand" };
    let _ = writeln!(
        s,
        "{}  {}, P = {} mm{}, lead {} mm, {} start{}, {}{}",
        des.text,
        t.form.name(),
        crate::tolerance::round_um(t.pitch),
        if t.form.is_inch() {
            format!(" ({} tpi)", crate::tolerance::round_um(25.4 / t.pitch))
        } else {
            String::new()
        },
        crate::tolerance::round_um(t.lead()),
        t.starts,
        if t.starts == 1 { "" } else { "s" },
        hand,
        if des.nonstandard { " (non-standard size)" } else { "" }
    );
    let _ = writeln!(s, "\nbasic (mm)");
    let _ = writeln!(s, "  {:<34}{d:>9.3}", "major diameter d = D");
    let _ = writeln!(s, "  {:<34}{d2:>9.3}", "pitch diameter d2 = D2");
    let _ = writeln!(s, "  {:<34}{d3:>9.3}", "minor diameter of the bolt d3");
    let _ = writeln!(s, "  {:<34}{d1:>9.3}", "minor diameter of the nut D1");
    let _ = writeln!(s, "  {:<34}{h:>9.4}", "fundamental triangle height H");
    for l in [ext, int].into_iter().flatten() {
        let dev_name = if l.kind == ThreadKind::External { "es" } else { "EI" };
        let head = format!(
            "{} {} ({dev_name} = {} µm)",
            l.kind.name(),
            l.class,
            fmt_num((l.fundamental_deviation_um * 10.0).round() / 10.0)
        );
        let _ = writeln!(s, "\n{head:<36}{:>9} {:>9}", "max", "min");
        // Inch tables (ASME B1.1) print inches: show them beside the mm.
        let inch = matches!(t.form, crate::ThreadForm::Unified | crate::ThreadForm::Acme);
        let row = |s: &mut String, name: &str, lim: &Limit| {
            let _ = write!(s, "  {name:<34}{:>9} {:>9}", fmt_opt(lim.max), fmt_opt(lim.min));
            if inch {
                let i = |v: Option<f64>| v.map_or_else(|| "—".to_string(), |x| format!("{:.4}", x / 25.4));
                let _ = write!(s, "   {:>7} {:>7} in", i(lim.max), i(lim.min));
            }
            s.push('\n');
        };
        let (maj, minor) = if l.kind == ThreadKind::External {
            ("major diameter d", "minor: d1+es (max) / d3 min (min)")
        } else {
            ("major diameter D", "minor diameter D1")
        };
        if let Some(gp) = &l.gauge_plane {
            let _ = writeln!(
                s,
                "  {:<34}{:>9.3}   at {:.3} mm {}, ±{} turn (±{:.3} mm); taper 1:{}",
                "gauge plane: pitch diameter",
                gp.pitch_diameter,
                gp.distance,
                if l.kind == ThreadKind::External { "from the small end" } else { "(the face)" },
                gp.tolerance_turns,
                gp.tolerance_turns * t.pitch,
                fmt_num(1.0 / gp.taper)
            );
            for n in &l.notes {
                let _ = writeln!(s, "  note: {n}");
            }
            continue;
        }
        row(&mut s, maj, &l.major_diameter);
        row(
            &mut s,
            if l.kind == ThreadKind::External { "pitch diameter d2" } else { "pitch diameter D2" },
            &l.pitch_diameter,
        );
        row(&mut s, minor, &l.minor_diameter);
        if let Some(r) = l.root_radius_min {
            let _ = writeln!(s, "  {:<34}{:>9} {:>9.3}", "root radius R", "", r);
        }
        for n in &l.notes {
            let _ = writeln!(s, "  note: {n}");
        }
    }
    if ext.is_none() && int.is_none() {
        let _ =
            writeln!(s, "\nno class given: add one for limits, e.g. {}-6g or {}-6H/6g", des.text, des.text);
    }
    s
}

/// Reads `--insert`: `full`, `partial`, `partial:R` (tip radius mm) or a TOML file path.
pub fn parse_insert(s: &str) -> Result<crate::verify::InsertChoice, Error> {
    use crate::verify::InsertChoice;
    match s {
        "full" => Ok(InsertChoice::Full),
        "partial" => Ok(InsertChoice::Partial { tip_radius: 0.04 }),
        _ => {
            if let Some(r) = s.strip_prefix("partial:") {
                let tip_radius = parse_len(r, "--insert partial tip radius")?;
                if tip_radius < 0.0 {
                    return Err(Error::Input(format!("--insert partial:{r}: the tip radius must be ≥ 0")));
                }
                Ok(InsertChoice::Partial { tip_radius })
            } else {
                Ok(InsertChoice::File(std::path::PathBuf::from(s)))
            }
        }
    }
}

/// Reads `--infeed`: `radial`, `flank[:ANGLE]`, `alternating[:ANGLE]` (degrees from the radial;
/// default half the thread angle).
pub fn parse_infeed(s: &str, half_angle: f64) -> Result<crate::passes::Infeed, Error> {
    use crate::passes::Infeed;
    let (name, angle) = match s.split_once(':') {
        Some((n, a)) => (n, Some(parse_len(a, "--infeed angle")?)),
        None => (s, None),
    };
    let angle = angle.unwrap_or(half_angle);
    if !(0.0..90.0).contains(&angle) {
        return Err(Error::Input(format!("--infeed {s}: the angle must be from 0 to under 90 degrees")));
    }
    match name {
        "radial" if angle == half_angle || s == "radial" => Ok(Infeed::Radial),
        "flank" => Ok(Infeed::Flank { angle }),
        "alternating" => Ok(Infeed::Alternating { angle }),
        _ => Err(Error::Input(format!(
            "--infeed '{s}': expected radial, flank[:ANGLE] or alternating[:ANGLE]"
        ))),
    }
}

/// Reads `--schedule`: `constant-area`, `constant-depth` or `sandvik`.
pub fn parse_schedule(s: &str) -> Result<crate::passes::Schedule, Error> {
    use crate::passes::Schedule;
    match s {
        "constant-area" => Ok(Schedule::ConstantArea),
        "constant-depth" => Ok(Schedule::ConstantDepth),
        "sandvik" => Ok(Schedule::Sandvik),
        _ => {
            Err(Error::Input(format!("--schedule '{s}': expected constant-area, constant-depth or sandvik")))
        }
    }
}

/// A finite number from an option value, or an error naming the option.
pub fn parse_len(s: &str, what: &str) -> Result<f64, Error> {
    let v: f64 = s.trim().parse().map_err(|_| Error::Input(format!("{what} '{s}' is not a number")))?;
    if !v.is_finite() {
        return Err(Error::Input(format!("{what} '{s}' is not a finite number")));
    }
    Ok(v)
}

/// `threadcheck verify`.
#[derive(Clone, Debug)]
pub struct VerifyJob {
    /// What to verify.
    pub spec: crate::verify::VerifySpec,
    /// With a program: one designation for all its operations, or one per operation.
    pub threads: Vec<String>,
    /// The insert was chosen on the command line (else the tool table, else the default).
    pub insert_given: bool,
    /// T numbers → inserts.
    pub tools: Option<crate::tools::ToolTable>,
    /// Write the SVG cross-section here.
    pub svg: Option<std::path::PathBuf>,
    /// Write the JSON report here; `-` prints it on stdout instead of the table.
    pub json: Option<String>,
}

impl VerifyJob {
    /// Runs the job: the report on stdout, files written atomically, pass or out of tolerance.
    pub fn run(&self) -> Result<(String, Outcome), Error> {
        if let Some((source, dialect)) = &self.spec.program {
            return self.run_program(source, *dialect);
        }
        let v = crate::verify::verify(&self.spec)?;
        let outcome = if v.pass { Outcome::Pass } else { Outcome::OutOfTolerance };
        // Render everything before writing anything, so a failure leaves no file half-done.
        let json_text = self.json.as_ref().map(|_| pretty(&crate::report::verify_json(&v))).transpose()?;
        let svg_text = self.svg.as_ref().map(|_| crate::render::verify_svg(&v));
        let text = crate::report::verify_text(&v);
        self.write(json_text, svg_text, text, outcome)
    }

    fn run_program(
        &self,
        source: &crate::verify::ProgramSource,
        dialect: crate::gcode::Dialect,
    ) -> Result<(String, Outcome), Error> {
        if self.spec.final_x.is_some() {
            return Err(Error::Input(
                "--final-x and --program exclude each other: the program sets the passes".into(),
            ));
        }
        let (shown, text) = source.load()?;
        let default = self.spec.insert.clone();
        let insert_for = |op: &crate::gcode::Operation| -> Option<(crate::verify::InsertChoice, String)> {
            if self.insert_given {
                return None;
            }
            if let (Some(tt), Some(t)) = (&self.tools, op.tool) {
                if let Some((choice, written)) = tt.insert(t) {
                    return Some((
                        choice.clone(),
                        format!("insert of tool T{t} from {}: {written}", tt.source),
                    ));
                }
            }
            let why = match (op.tool, &self.tools) {
                (Some(t), Some(tt)) => format!("tool T{t} is not in {}", tt.source),
                (Some(t), None) => {
                    format!("the program names tool T{t} but no tool table was given (--tools)")
                }
                (None, _) => "the program names no tool".to_string(),
            };
            let what = match &default {
                crate::verify::InsertChoice::Full => "a full-profile insert".to_string(),
                crate::verify::InsertChoice::Partial { tip_radius } => {
                    format!("a partial-profile insert with a {} mm tip", fmt_num(*tip_radius))
                }
                crate::verify::InsertChoice::File(p) => format!("the insert {}", p.display()),
            };
            Some((
                default.clone(),
                format!("insert assumed: {what} ({why}; choose with --insert or --tools)"),
            ))
        };
        let pv =
            crate::verify::verify_program(&self.spec, &text, &shown, dialect, &self.threads, &insert_for)?;
        let outcome = if pv.pass() { Outcome::Pass } else { Outcome::OutOfTolerance };
        let json_text = self.json.as_ref().map(|_| pretty(&crate::report::program_json(&pv))).transpose()?;
        let svg_text = self.svg.as_ref().map(|_| crate::render::program_svg(&pv));
        let text = crate::report::program_text(&pv);
        self.write(json_text, svg_text, text, outcome)
    }

    fn write(
        &self,
        json_text: Option<String>,
        svg_text: Option<String>,
        text: String,
        outcome: Outcome,
    ) -> Result<(String, Outcome), Error> {
        if let (Some(path), Some(t)) = (&self.svg, &svg_text) {
            crate::output::write_atomic(path, t.as_bytes())?;
        }
        Ok((route_json(self.json.as_deref(), json_text, text)?, outcome))
    }
}

/// Where `--json` sends the JSON: `-` prints it on stdout instead of the text; a path writes it
/// there (atomically) and the text goes to stdout; without `--json`, the text.
pub fn route_json(json: Option<&str>, json_text: Option<String>, text: String) -> Result<String, Error> {
    match (json, json_text) {
        (Some("-"), Some(t)) => Ok(t),
        (Some(p), Some(t)) => {
            crate::output::write_atomic(std::path::Path::new(p), t.as_bytes())?;
            Ok(text)
        }
        _ => Ok(text),
    }
}

/// A number without float noise: at most six decimals, trailing zeros dropped.
pub fn fmt_num(v: f64) -> String {
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.to_string()
    }
}

fn pretty(v: &serde_json::Value) -> Result<String, Error> {
    let mut s = serde_json::to_string_pretty(v).map_err(|e| Error::Data(e.to_string()))?;
    s.push('\n');
    Ok(s)
}

/// `threadcheck fit`: a bolt and a nut assembled.
#[derive(Clone, Debug)]
pub struct FitJob {
    /// The pair.
    pub spec: crate::fit::FitSpec,
    /// Write the SVG of the pair here.
    pub svg: Option<std::path::PathBuf>,
    /// Write the JSON here; `-` prints it on stdout instead of the text.
    pub json: Option<String>,
}

impl FitJob {
    /// Runs the job: exit 0 when the pair screws together, 1 when it does not.
    pub fn run(&self) -> Result<(String, Outcome), Error> {
        let r = crate::fit::fit(&self.spec)?;
        let outcome = if r.fits { Outcome::Pass } else { Outcome::OutOfTolerance };
        let json_text = self.json.as_ref().map(|_| pretty(&crate::fit::json(&r))).transpose()?;
        let svg_text = self.svg.as_ref().map(|_| crate::fit::svg(&r));
        if let (Some(path), Some(t)) = (&self.svg, &svg_text) {
            crate::output::write_atomic(path, t.as_bytes())?;
        }
        let text = crate::fit::text(&r);
        Ok((route_json(self.json.as_deref(), json_text, text)?, outcome))
    }
}

/// `threadcheck passes`: the expanded pass plan.
#[derive(Clone, Debug)]
pub struct PassesJob {
    /// The plan, as for verify (the final X is solved the same way when not given).
    pub spec: crate::verify::VerifySpec,
    /// The JSON: `-` prints it on stdout instead of the table, a path writes it there.
    pub json: Option<String>,
}

impl PassesJob {
    /// Runs the job: a program is read and expanded; a generated plan is laid out as `verify`
    /// would (solving the final X when it is not given).
    pub fn run(&self) -> Result<(String, Outcome), Error> {
        let mut operations = None;
        let (thread, passes, header) = match (&self.spec.program, self.spec.designation.is_empty()) {
            (Some((source, dialect)), no_thread) => {
                let (shown, text) = source.load()?;
                let prog = crate::gcode::read_program(&text, &shown, *dialect)?;
                let thread = if no_thread {
                    serde_json::Value::Null
                } else {
                    let d = parse_designation(
                        &self.spec.designation,
                        ParseOptions { allow_nonstandard: self.spec.allow_nonstandard },
                    )?;
                    json!({"designation": d.text, "form": d.thread.form.name(), "pitch": d.thread.pitch, "lead": d.thread.lead()})
                };
                let leads: Vec<String> = prog.operations.iter().map(|o| fmt_num(o.lead())).collect();
                let mut header = format!(
                    "{shown} ({}): {} operation{}, {} passes, lead {} mm, {} other blocks read for position\n",
                    dialect.name(),
                    prog.operations.len(),
                    if prog.operations.len() == 1 { "" } else { "s" },
                    prog.passes.len(),
                    leads.join(" / "),
                    prog.skipped_blocks
                );
                for n in &prog.notes {
                    header.push_str(&format!("note: {n}\n"));
                }
                operations = Some(prog.operations.clone());
                (thread, prog.passes, header)
            }
            (None, _) if self.spec.final_x.is_some() => {
                // With the final X given, the plan is laid out without cutting it.
                let r = crate::verify::resolve(&self.spec)?;
                let x = self.spec.final_x.unwrap_or_default();
                let passes = r.plan(x).generate()?;
                let header = format!(
                    "{} {}: {} passes, blank X{:.4}, final X{x:.4}\n",
                    r.designation.text,
                    r.kind.name(),
                    passes.len(),
                    r.blank
                );
                let t = &r.designation.thread;
                let thread = json!({"designation": r.designation.text, "form": t.form.name(), "kind": r.kind.name(),
                    "pitch": t.pitch, "lead": t.lead(), "starts": t.starts, "class": r.limits.class});
                (thread, passes, header)
            }
            (None, _) => {
                let v = crate::verify::verify(&self.spec)?;
                let header = format!(
                    "{} {}: {} passes, blank X{:.4}, final X{:.4}\n",
                    v.designation.text,
                    v.kind.name(),
                    v.passes.len(),
                    v.blank_diameter,
                    v.final_x
                );
                (crate::report::thread_json(&v), v.passes, header)
            }
        };
        let pass_json = |p: &crate::passes::Pass| {
            json!({
                "index": p.index, "x_start": p.x_start, "x_end": p.x_end, "z_start": p.z_start,
                "z_end": p.z_end, "z_phase": p.z_phase, "lead": p.lead, "start": p.start, "source_line": p.source_line,
                "taper_in": p.taper_in, "taper_out": p.taper_out, "x_taper": p.x_taper,
            })
        };
        let json_text = if self.json.is_some() {
            let list: Vec<serde_json::Value> = passes.iter().map(pass_json).collect();
            let (start, end) = passes.iter().fold((f64::NEG_INFINITY, f64::INFINITY), |(a, b), p| {
                (a.max(p.z_start.max(p.z_end)), b.min(p.z_start.min(p.z_end)))
            });
            let mut obj = json!({"thread": thread, "thread_start": start, "thread_end": end, "passes": list});
            if let (Some(ops), Some(o)) = (&operations, obj.as_object_mut()) {
                let ops: Vec<serde_json::Value> = ops
                    .iter()
                    .map(|op| {
                        json!({"index": op.index, "cycle": op.cycle, "source_line": op.source_line, "tool": op.tool,
                            "spindle": op.spindle, "lead": op.lead(), "notes": op.notes,
                            "passes": op.passes.iter().map(pass_json).collect::<Vec<_>>()})
                    })
                    .collect();
                o.insert("operations".into(), json!(ops));
            }
            Some(pretty(&obj)?)
        } else {
            None
        };
        let text = {
            let mut s = header;
            let row = |s: &mut String, p: &crate::passes::Pass| {
                let _ = writeln!(
                    s,
                    "  {:>4}  {:>5}  {:>9.4}  {:>9.4}  {:>9.4}  {:>9.4}  {:>5}",
                    p.index,
                    p.start + 1,
                    p.x_start,
                    p.x_end,
                    p.z_start,
                    p.z_end,
                    p.source_line.map_or("—".to_string(), |l| l.to_string())
                );
            };
            let head = "  pass  start    X start      X end    Z start      Z end   line\n";
            match &operations {
                Some(ops) => {
                    for op in ops {
                        let _ = writeln!(
                            s,
                            "\noperation {}: {} at line {}{}, lead {} mm, {} passes",
                            op.index,
                            op.cycle,
                            op.source_line,
                            op.tool.map_or(String::new(), |t| format!(", tool T{t}")),
                            fmt_num(op.lead()),
                            op.passes.len()
                        );
                        for n in &op.notes {
                            let _ = writeln!(s, "  note: {n}");
                        }
                        s.push_str(head);
                        for p in &op.passes {
                            row(&mut s, p);
                        }
                    }
                }
                None => {
                    s.push('\n');
                    s.push_str(head);
                    for p in &passes {
                        row(&mut s, p);
                    }
                }
            }
            s
        };
        Ok((route_json(self.json.as_deref(), json_text, text)?, Outcome::Pass))
    }
}

/// `threadcheck compare`: the same thread with every infeed strategy.
#[derive(Clone, Debug)]
pub struct CompareJob {
    /// Thread, insert and plan (infeed and schedule are varied).
    pub spec: crate::verify::VerifySpec,
    /// Modified-flank angles, degrees.
    pub modified: Vec<f64>,
    /// The JSON: `-` prints it on stdout instead of the table, a path writes it there.
    pub json: Option<String>,
    /// Write the table as Markdown here.
    pub markdown: Option<std::path::PathBuf>,
}

impl CompareJob {
    /// Runs the job.
    pub fn run(&self) -> Result<(String, Outcome), Error> {
        let c = crate::compare::compare(&self.spec, &self.modified)?;
        let md = crate::compare::markdown(&c);
        let json_text = self.json.as_ref().map(|_| pretty(&crate::compare::to_json(&c))).transpose()?;
        if let Some(p) = &self.markdown {
            crate::output::write_atomic(p, md.as_bytes())?;
        }
        Ok((route_json(self.json.as_deref(), json_text, crate::compare::text(&c))?, Outcome::Pass))
    }
}

/// `threadcheck sweep`: the catalogue in parallel.
#[derive(Clone, Debug)]
pub struct SweepJob {
    /// What to sweep.
    pub spec: crate::catalogue::CatalogueSpec,
    /// JSON Lines: one verify report per case.
    pub json: bool,
    /// Write every case's blank, insert placements and measured d2 here (JSON Lines), for an
    /// outside baseline to redo the cut.
    pub export_placements: Option<std::path::PathBuf>,
}

impl SweepJob {
    /// Runs the job: the report on stdout, the summary line last (on stderr with `--json`).
    pub fn run(&self) -> Result<(String, String, Outcome), Error> {
        let start = std::time::Instant::now();
        let cases = crate::catalogue::cases(&self.spec)?;
        if cases.is_empty() {
            return Err(Error::Input("the catalogue selection is empty".into()));
        }
        let results = crate::catalogue::run(&cases);
        let (mut pass, mut fail) = (0usize, 0usize);
        let mut out = String::new();
        let mut export = String::new();
        for (c, r) in cases.iter().zip(&results) {
            match r {
                Ok(v) => {
                    if v.pass {
                        pass += 1;
                    } else {
                        fail += 1;
                    }
                    if self.json {
                        out.push_str(
                            &serde_json::to_string(&crate::report::verify_json(v))
                                .map_err(|e| Error::Data(e.to_string()))?,
                        );
                        out.push('\n');
                    } else if !v.pass {
                        let failed: Vec<String> = v
                            .checks
                            .iter()
                            .filter(|k| !k.ok && k.kind.counts(v.gauge_only))
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
                    if self.export_placements.is_some() {
                        export.push_str(&placements_line(&c.label, v)?);
                    }
                }
                Err(e) => {
                    fail += 1;
                    if self.json {
                        let _ = writeln!(out, "{}", json!({"case": c.label, "error": e.to_string()}));
                    } else {
                        let _ = writeln!(out, "ERROR {}: {e}", c.label);
                    }
                }
            }
        }
        if let Some(p) = &self.export_placements {
            crate::output::write_atomic(p, export.as_bytes())?;
        }
        let summary = format!(
            "{} cases, {pass} pass, {fail} fail, {:.3} s\n",
            cases.len(),
            start.elapsed().as_secs_f64()
        );
        // Exit 1 when any case fails, as verify does.
        Ok((out, summary, if fail > 0 { Outcome::OutOfTolerance } else { Outcome::Pass }))
    }
}

fn placements_line(label: &str, v: &crate::verify::Verification) -> Result<String, Error> {
    let t = &v.designation.thread;
    let setup = crate::sweep::SweepSetup {
        kind: v.kind,
        insert: &v.insert,
        blank_diameter: v.blank_diameter,
        pitch: t.pitch,
    };
    let window = crate::sweep::Window::around(v.z_ref, t.pitch, 4.0);
    let (blank, rings) = crate::sweep::placements(&setup, &v.passes, window)?;
    // threadcheck's own time for the same work on the same placements (sweep + pitch
    // diameter), best of five, so the baseline can state a ratio measured in one run.
    let ms = crate::measure::MeasureSetup {
        thread: t,
        kind: v.kind,
        mmc_pitch_diameter: None,
        mmc_major_diameter: None,
        extras: false,
    };
    let mut best = f64::INFINITY;
    for _ in 0..5 {
        let start = std::time::Instant::now();
        let s = crate::sweep::sweep(&setup, &v.passes, window, crate::boolean::UnionStrategy::Envelope)?;
        let m = crate::measure::measure(&ms, &s.section.profile(), v.z_ref)?;
        std::hint::black_box(m.pitch_diameter);
        best = best.min(start.elapsed().as_secs_f64());
    }
    let ring = |r: &[crate::Point]| r.iter().map(|p| [p.z, p.r]).collect::<Vec<_>>();
    let mut s = serde_json::to_string(&json!({
        "case": label,
        "kind": v.kind.name(),
        "pitch": t.pitch,
        "z_ref": v.z_ref,
        "blank": ring(&blank),
        "placements": rings.iter().map(|r| ring(r)).collect::<Vec<_>>(),
        "pitch_diameter": v.measurement.pitch_diameter,
        "threadcheck_seconds": best,
    }))
    .map_err(|e| Error::Data(e.to_string()))?;
    s.push('\n');
    Ok(s)
}
