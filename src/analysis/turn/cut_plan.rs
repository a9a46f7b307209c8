//! What a program's passes did, read back from them: the infeed (straight in, along one flank,
//! alternating) and the depth law, for the plan a report shows beside the passes (a program's
//! plan is what it cut, not the options' defaults).

use crate::toolpath::passes::{Infeed, Pass};
use serde::Serialize;

/// The depth law a program's passes follow from their second pass on (the first's depth is
/// measured from an origin the passes do not show: the cycle's, not the blank's).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum DepthLaw {
    /// The depth after pass n is √n times the first's (Fanuc G76, Okuma M75): constant chip area.
    ConstantArea,
    /// Every pass as deep as the one before it.
    ConstantDepth,
    /// Neither: the depths as the program writes them.
    Programmed,
}

impl DepthLaw {
    /// The name a plan's `schedule` gives it.
    pub fn name(self) -> &'static str {
        match self {
            DepthLaw::ConstantArea => "constant-area",
            DepthLaw::ConstantDepth => "constant-depth",
            DepthLaw::Programmed => "programmed",
        }
    }
}

/// The plan a program's passes follow.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct CutPlan {
    /// The infeed every pass after the first follows; `None` when they follow no single one.
    pub infeed: Option<Infeed>,
    /// The depth law of the leading passes.
    pub law: DepthLaw,
    /// How many leading passes follow it (the rest run to the final depth: a minimum step, a
    /// finishing allowance, spring passes).
    pub law_passes: usize,
    /// The law's first depth, mm radial (√n times it after pass n; or each pass's depth).
    pub first_depth: Option<f64>,
}

/// Radial steps this close are one (a program writes X to 1 µm on the diameter: 0.5 µm a side).
const STEP_TOL: f64 = 6e-4;
/// Infeed angles this close are one, degrees.
const ANGLE_TOL: f64 = 0.5;

/// The plan of a program's passes (the first start's, each chain's head).
pub fn cut_plan(passes: &[Pass]) -> CutPlan {
    let heads: Vec<&Pass> =
        passes.iter().filter(|p| p.start == 0 && (p.z_phase - p.z_start).abs() < 1e-12).collect();
    let external = heads.first().zip(heads.last()).is_none_or(|(f, l)| l.x_end.abs() <= f.x_end.abs());
    // Each pass's radial step and axial shift from the one before it; spring passes (no step)
    // left out.
    let steps: Vec<(f64, f64)> = heads
        .windows(2)
        .map(|w| {
            let dr = 0.5 * (w[0].x_end.abs() - w[1].x_end.abs());
            (if external { dr } else { -dr }, w[1].z_phase - w[0].z_phase)
        })
        .filter(|(dr, _)| *dr > STEP_TOL)
        .collect();
    CutPlan { infeed: infeed(&steps), ..law(&steps) }
}

fn infeed(steps: &[(f64, f64)]) -> Option<Infeed> {
    if steps.is_empty() {
        return None;
    }
    if steps.iter().all(|(_, dz)| dz.abs() < 1e-4) {
        return Some(Infeed::Radial);
    }
    let angles: Vec<f64> = steps.iter().map(|(dr, dz)| (dz.abs() / dr).atan().to_degrees()).collect();
    let mean = angles.iter().sum::<f64>() / angles.len() as f64;
    if angles.iter().any(|a| (a - mean).abs() > ANGLE_TOL) {
        return None;
    }
    let angle = (mean * 100.0).round() / 100.0;
    let signs: Vec<bool> = steps.iter().map(|(_, dz)| *dz > 0.0).collect();
    if signs.iter().all(|&s| s == signs[0]) {
        Some(Infeed::Flank { angle })
    } else if signs.windows(2).all(|w| w[0] != w[1]) {
        Some(Infeed::Alternating { angle })
    } else {
        None
    }
}

/// The law the steps from the second pass on follow: step n (n ≥ 2) is a·(√n − √(n−1)) for
/// constant area, a for constant depth; the longest leading run decides, at least two steps.
fn law(steps: &[(f64, f64)]) -> CutPlan {
    let run = |factor: &dyn Fn(f64) -> f64| -> (usize, f64) {
        let Some(&(d2, _)) = steps.first() else { return (0, 0.0) };
        let a = d2 / factor(2.0);
        let n = steps
            .iter()
            .enumerate()
            .take_while(|(i, (dr, _))| (dr - a * factor(*i as f64 + 2.0)).abs() <= STEP_TOL)
            .count();
        (n, a)
    };
    let (area, a) = run(&|n: f64| n.sqrt() - (n - 1.0).sqrt());
    let (depth, d) = run(&|_| 1.0);
    let plan = |law, steps: usize, first| CutPlan {
        infeed: None,
        law,
        law_passes: steps + 1,
        first_depth: Some(first),
    };
    if area >= 2 && area >= depth {
        plan(DepthLaw::ConstantArea, area, a)
    } else if depth >= 2 {
        plan(DepthLaw::ConstantDepth, depth, d)
    } else {
        CutPlan { infeed: None, law: DepthLaw::Programmed, law_passes: 0, first_depth: None }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn passes(depths: &[f64], shift: impl Fn(usize, f64) -> f64) -> Vec<Pass> {
        depths
            .iter()
            .enumerate()
            .map(|(i, d)| {
                let z = shift(i, *d);
                Pass { z_phase: z, ..Pass::parallel(i, 20.0 - 2.0 * d, z, -20.0, 1.5) }
            })
            .collect()
    }

    /// Fanuc G76's law: the nth pass at Δd·√n; flank infeed at 30°: z shifts by depth·tan 30°.
    #[test]
    fn constant_area_along_a_flank() {
        let depths: Vec<f64> = (1..=6).map(|n| 0.25 * f64::from(n).sqrt()).collect();
        let p = cut_plan(&passes(&depths, |_, d| -d * 30f64.to_radians().tan()));
        assert_eq!(p.law, DepthLaw::ConstantArea);
        assert_eq!(p.law_passes, 6);
        assert!((p.first_depth.unwrap() - 0.25).abs() < 1e-12);
        assert_eq!(p.infeed, Some(Infeed::Flank { angle: 30.0 }));
    }

    /// Equal steps straight in.
    #[test]
    fn constant_depth_radial() {
        let depths: Vec<f64> = (1..=5).map(|n| 0.2 * f64::from(n)).collect();
        let p = cut_plan(&passes(&depths, |_, _| 0.0));
        assert_eq!((p.law, p.law_passes, p.infeed), (DepthLaw::ConstantDepth, 5, Some(Infeed::Radial)));
    }
}
