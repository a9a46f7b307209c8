//! A program's lead against its designation's: equal at the program's own resolution, and what
//! the remaining difference does to the thread a gauge sees.
//!
//! A control takes a lead in its least input increment (0.001 mm; 0.0001 in), so a metric
//! program cutting 14 tpi writes `F1.814` for 25.4/14 = 1.8142857… mm, an inch program `F.0714`.
//! Such a lead matches: it is the designation's lead rounded to the increment the program wrote
//! (more digits when the program writes more). What is left is not ignored: over the length of
//! engagement the lead error adds up to δP, and a thread with a lead error assembles like one
//! whose pitch diameter is δP·cot(α/2) larger (external) or smaller (internal): its
//! **functional (virtual) pitch diameter**, which the GO gauge sees.

use crate::gcode::ProgramUnits;
use crate::standards::BasicThread;
use serde::Serialize;

/// A lead difference whose functional effect on the pitch diameter is below this (mm, 0.5 µm:
/// half the standards' 1 µm resolution) changes no size and is not reported.
pub const NEGLIGIBLE_FUNCTIONAL_MM: f64 = 5e-4;

/// Written digits are looked for up to this many decimals; a computed lead (`F[25.4/14]`)
/// has more and is compared at this resolution.
const MAX_DIGITS: i32 = 9;

/// The lead a program cuts against its designation's, and the pitch-diameter equivalent of the
/// difference over the length of engagement.
///
/// ```
/// use threadcheck::{lead_deviation, parse_designation, ParseOptions, ProgramUnits};
/// // 1/2-14 NPT cut by a metric control at F1.814: 25.4/14 = 1.8142857 mm rounded to 0.001 mm.
/// let npt = parse_designation("1/2-14 NPT", ParseOptions::default())?.thread;
/// let d = lead_deviation(1.814, ProgramUnits::Mm, &npt, 19.0).expect("it matches").expect("not exact");
/// assert_eq!(d.increment, 0.001);
/// // 0.2857 µm short per turn over 19 mm (10.47 turns): 2.99 µm, times cot 30° = 5.18 µm.
/// assert!((d.cumulative * 1000.0 + 2.992).abs() < 1e-3);
/// assert!((d.pitch_diameter_equivalent * 1000.0 - 5.183).abs() < 1e-3);
/// // F1.81 is not 1.8143 rounded to what it wrote: refused.
/// assert!(lead_deviation(1.81, ProgramUnits::Mm, &npt, 19.0).is_err());
/// # Ok::<(), threadcheck::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct LeadDeviation {
    /// The lead the program cuts, mm.
    pub program_lead: f64,
    /// The designation's lead, mm.
    pub designation_lead: f64,
    /// The program's units.
    pub units: ProgramUnits,
    /// The least increment the lead was compared at, in the program's units.
    pub increment: f64,
    /// The length it adds up over, mm: the thread on the part, capped at the length of
    /// engagement ([`LeadDeviation::engagement`]).
    pub length: f64,
    /// The length the finishing pass threads, run-in in air included, mm.
    pub pass_length: f64,
    /// The length of engagement a gauge feels, mm: the thread's nominal diameter (ASME B1.1's
    /// LE = D, BS 84's L = D), NPT's L1, or the one given.
    pub engagement: f64,
    /// The cumulative lead error over that length, mm (program − designation).
    pub cumulative: f64,
    /// Its pitch-diameter equivalent, |δP|·cot(α/2), mm: what the functional pitch diameter
    /// adds (external) or takes off (internal).
    pub pitch_diameter_equivalent: f64,
}

/// Whether a program's lead (mm, written in `units`) is the designation's at the program's
/// resolution: `Ok(None)` when it is exact (its functional effect negligible), `Ok(Some(_))`
/// with the deviation when it matches after rounding or truncation to the increment,
/// `Err(increment)` when it differs by more than that (the increment in program units, for the message).
pub fn lead_deviation(
    program_lead: f64,
    units: ProgramUnits,
    thread: &BasicThread,
    length: f64,
) -> Result<Option<LeadDeviation>, f64> {
    let designation_lead = thread.lead();
    let written = program_lead / units.mm();
    let wanted = designation_lead / units.mm();
    let increment = units.least_increment().min(written_increment(written));
    // Half an increment either way rounds to the written value; a lead truncated to the
    // increment (F0.0869 in for 11.5 tpi, whose rounding is 0.0870) lies up to one increment
    // short of it; a whisker more absorbs the binary representation of both. The functional
    // size counts the remaining error either way.
    let whisker = 1e-9 * increment + 1e-12;
    let rounded = (written - wanted).abs() <= 0.5 * increment + whisker;
    let truncated = wanted.abs() >= written.abs()
        && wanted.abs() - written.abs() < increment + whisker
        && wanted.signum() == written.signum();
    if !(rounded || truncated) {
        return Err(increment);
    }
    let per_turn = program_lead - designation_lead;
    let cumulative = per_turn * length.abs() / designation_lead;
    let cot = 1.0 / thread.half_angle().tan();
    let equivalent = cumulative.abs() * cot;
    debug_assert!(equivalent.is_finite());
    if equivalent < NEGLIGIBLE_FUNCTIONAL_MM {
        return Ok(None);
    }
    Ok(Some(LeadDeviation {
        program_lead,
        designation_lead,
        units,
        increment,
        length: length.abs(),
        pass_length: length.abs(),
        engagement: length.abs(),
        cumulative,
        pitch_diameter_equivalent: equivalent,
    }))
}

/// The place of the last written digit of `v`: 10^-d for the fewest decimals d that give `v`
/// back (to its binary representation), 10^-9 at most.
fn written_increment(v: f64) -> f64 {
    for d in 0..=MAX_DIGITS {
        let s = 10f64.powi(d);
        if ((v * s).round() / s - v).abs() <= 1e-12 * v.abs().max(1.0) {
            return 1.0 / s;
        }
    }
    10f64.powi(-MAX_DIGITS)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn written_digits_are_read_back() {
        assert_eq!(written_increment(1.5), 0.1);
        assert_eq!(written_increment(1.814), 0.001);
        assert_eq!(written_increment(1.8139999999999998), 0.001);
        assert_eq!(written_increment(0.07692308), 1e-8);
        assert_eq!(written_increment(2.0), 1.0);
        assert_eq!(written_increment(25.4 / 14.0), 1e-9);
    }
}
