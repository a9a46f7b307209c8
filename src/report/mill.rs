//! The milling report for a reader.

use crate::analysis::check::Verdict;
use crate::analysis::mill::{LevelReport, Material, MillReport, Spot};

/// The text report.
pub fn text(r: &MillReport) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{} ({}): Ø{} mm cutter, {} levels checked against x = {}, y = {} (material {})",
        r.program,
        r.dialect.name(),
        crate::ground::fmt::fmt_num(r.tool_diameter),
        r.levels.len(),
        r.target.x,
        r.target.y,
        match r.target.material {
            Material::Inside => "inside",
            Material::Outside => "outside",
        }
    );
    let spot = |p: &Option<Spot>| {
        p.map_or(String::new(), |p| {
            format!(
                " at X{:.4} Y{:.4} Z{} (t = {:.2}°{})",
                p.x,
                p.y,
                crate::ground::fmt::fmt_num(p.z),
                p.t,
                if p.line > 0 { format!(", line {}", p.line) } else { String::new() }
            )
        })
    };
    let _ = writeln!(s, "\n  gouge     {:.4} mm{}", r.gouge_max, spot(&r.gouge_at));
    let _ = writeln!(s, "  leftover  {:.4} mm{}", r.leftover_max, spot(&r.leftover_at));
    let _ = writeln!(s, "  tolerance {:.4} mm", r.tolerance);
    if r.levels.len() > 1 {
        let _ = writeln!(s, "\n  level Z     moves     gouge mm   leftover mm");
        let show: Vec<&LevelReport> = if r.levels.len() <= 12 {
            r.levels.iter().collect()
        } else {
            // The first and last few, and the worst.
            let mut v: Vec<&LevelReport> =
                r.levels.iter().take(4).chain(r.levels.iter().rev().take(4).rev()).collect();
            if let Some(w) = r.levels.iter().max_by(|a, b| a.gouge.total_cmp(&b.gouge)) {
                if !v.iter().any(|l| l.z == w.z) {
                    v.push(w);
                }
            }
            v.sort_by(|a, b| b.z.total_cmp(&a.z));
            v
        };
        let mut last_z = None;
        for l in show {
            if let Some(prev) = last_z {
                let gap = r.levels.iter().filter(|m| m.z < prev && m.z > l.z).count();
                if gap > 0 {
                    let _ = writeln!(s, "  … {gap} more");
                }
            }
            let _ = writeln!(
                s,
                "  {:>8}  {:>7}  {:>10.4}  {:>12.4}",
                crate::ground::fmt::fmt_num(l.z),
                l.moves,
                l.gouge,
                l.leftover
            );
            last_z = Some(l.z);
        }
    }
    let _ = writeln!(
        s,
        "\nverdict: {}",
        match r.verdict {
            Verdict::Pass => "PASS".to_string(),
            Verdict::Fail => {
                let mut why = Vec::new();
                if r.gouge_out {
                    why.push("gouge");
                }
                if r.leftover_out {
                    why.push("material left");
                }
                format!("FAIL ({} beyond {} mm)", why.join(", "), crate::ground::fmt::fmt_num(r.tolerance))
            }
        }
    );
    for n in &r.notes {
        let _ = writeln!(s, "note: {n}");
    }
    s
}
