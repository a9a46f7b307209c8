//! The tapping check's text (its JSON is the report itself, `TapReport` derives `Serialize`).

use crate::analysis::tapping::{TapFeature, TapReport};
use crate::ground::fmt::fmt_num;
use crate::standards::drills::{DrillSource, PassingDrill};
use std::fmt::Write as _;

pub(crate) fn feature_name(f: TapFeature) -> &'static str {
    match f {
        TapFeature::DrillDiameter => "drill diameter",
        TapFeature::Feed => "feed",
        TapFeature::Depth => "depth below",
        TapFeature::Spindle => "spindle",
    }
}

/// Where a suggested drill comes from, in words.
pub(crate) fn drill_source_words(s: DrillSource) -> &'static str {
    match s {
        DrillSource::Iso2306Coarse => "ISO 2306's tap drill",
        DrillSource::Iso2306Fine => "ISO 2306's fine-series tap drill",
        DrillSource::MetricSeries => "the 0.1 mm drill nearest D1's middle",
        DrillSource::InchGauge => "the inch drill nearest D1's middle",
    }
}

/// The drill that would pass, in words: `Ø8.5 mm (ISO 2306's tap drill); D1's middle 8.526 mm`.
pub(crate) fn passing_drill_words(d: &PassingDrill) -> String {
    match (&d.name, d.diameter, d.source) {
        (Some(name), Some(dia), Some(src)) => {
            let inch = src == DrillSource::InchGauge;
            format!(
                "{} ({}{}); D1's middle {:.3} mm",
                if inch {
                    format!("{name}, {:.4} in", dia / crate::MM_PER_INCH)
                } else {
                    format!("Ø{name} mm")
                },
                drill_source_words(src),
                if inch { format!(", {:.3} mm", dia) } else { String::new() },
                d.middle
            )
        }
        _ => format!("Ø{:.3} mm, D1's middle (no stocked drill lies within D1)", d.middle),
    }
}

/// `a drill that passes: …` for a hole whose drill fails D1 or is not known; `None` when the
/// drill passes (or the tap is a taper pipe tap).
pub(crate) fn passing_drill_line(h: &crate::analysis::tapping::TappedHole) -> Option<String> {
    let drill_bad = h.checks.iter().any(|k| k.feature == TapFeature::DrillDiameter && !k.ok);
    let drill_unknown = h.drill.as_ref().is_none_or(|d| d.diameter.is_none());
    let pd = h.drill_that_passes.as_ref().filter(|_| drill_bad || drill_unknown)?;
    Some(format!("a drill that passes: {}", passing_drill_words(pd)))
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
        if let Some(line) = passing_drill_line(h) {
            let _ = writeln!(s, "{line}");
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
