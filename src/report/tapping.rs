//! The tapping check's text (its JSON is the report itself, `TapReport` derives `Serialize`).

use crate::analysis::tapping::{TapFeature, TapReport};
use crate::ground::fmt::fmt_num;
use std::fmt::Write as _;

pub(crate) fn feature_name(f: TapFeature) -> &'static str {
    match f {
        TapFeature::DrillDiameter => "drill diameter",
        TapFeature::Feed => "feed",
        TapFeature::Depth => "depth below",
        TapFeature::Spindle => "spindle",
    }
}

/// The text `threadcheck tap` prints.
pub fn text(r: &TapReport) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{} ({}): {} tapping cycle{}, {} drilling cycle{}",
        r.program,
        r.dialect.name(),
        r.holes.len(),
        if r.holes.len() == 1 { "" } else { "s" },
        r.drills,
        if r.drills == 1 { "" } else { "s" }
    );
    for h in &r.holes {
        let c = &h.cycle;
        let _ = writeln!(
            s,
            "\n== {} at line {}{}, tap {} (chamfer {} P{}){}",
            c.code,
            c.line,
            c.tool.map_or(String::new(), |t| format!(", tool T{t}")),
            h.tap.designation,
            fmt_num(h.tap.chamfer_pitches),
            if h.tap.chamfer_given { "" } else { ", default" },
            if c.rigid { ", rigid" } else { "" }
        );
        match &h.drill {
            Some(d) => {
                let _ = writeln!(
                    s,
                    "drilled by {} at line {}{}{}{}",
                    d.cycle.code,
                    d.cycle.line,
                    d.cycle.tool.map_or(String::new(), |t| format!(", tool T{t}")),
                    d.diameter.map_or(String::new(), |v| format!(", Ø{}", fmt_num(v))),
                    d.cycle.bottom.map_or(String::new(), |z| format!(", bottom Z{}", fmt_num(z)))
                );
            }
            None => {
                let _ = writeln!(s, "no drilling cycle at this position before it");
            }
        }
        let _ = writeln!(s, "    check                value        min        max   off");
        for k in &h.checks {
            let num = |v: Option<f64>| v.map_or("—".to_string(), |v| format!("{v:.4}"));
            let off = if k.ok {
                String::new()
            } else if k.unit == "mm/min" {
                format!("{:+.1} mm/min", k.deviation)
            } else if k.feature == TapFeature::Spindle {
                "wrong".to_string()
            } else {
                format!("{:+.1} µm", k.deviation)
            };
            let _ = writeln!(
                s,
                "  {} {:<16} {:>10} {:>10} {:>10}   {off}  {}{}",
                if k.ok { "✓" } else { "✗" },
                feature_name(k.feature),
                num(k.value),
                num(k.min),
                num(k.max),
                if k.unit.is_empty() { String::new() } else { format!("{}; ", k.unit) },
                k.note
            );
        }
        let _ = writeln!(
            s,
            "verdict: {}",
            if h.pass {
                "PASS".to_string()
            } else {
                let failed: Vec<&str> =
                    h.checks.iter().filter(|k| !k.ok).map(|k| feature_name(k.feature)).collect();
                format!("FAIL ({})", failed.join(", "))
            }
        );
        for n in &h.notes {
            let _ = writeln!(s, "note: {n}");
        }
    }
    if r.holes.len() > 1 {
        let _ = writeln!(s, "\nprogram verdict: {}", if r.pass { "PASS" } else { "FAIL" });
    }
    for n in &r.notes {
        let _ = writeln!(s, "note: {n}");
    }
    s
}
