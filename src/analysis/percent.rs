//! How much thread a hole leaves for a 60° thread (issue 64): the percent of thread tap makers'
//! and shop charts publish, for a drilled hole (tapping), a bored one (a turned nut) and the
//! bore a thread mill cuts into. Shared by the processes.

use serde::Serialize;

/// How much thread a hole leaves for a 60° internal thread, in the tap makers' and shop charts'
/// definition (issue 64): 100 % is 0.6495·P of height a side (¾ of the fundamental triangle
/// H = 0.866·P), so %thread = (D − drill) / (2 · 0.6495·P) · 100 (in inch, 76.98·TPI·(D − drill)
/// alike); beside it the engagement on the basic height, (D − drill) / (D − D1).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ThreadPercent {
    /// Percent of thread, the charts' figure.
    pub percent: f64,
    /// Percent of the basic thread height D − D1 (D1 = D − 1.0825·P) the drill leaves.
    pub of_basic_height: f64,
    /// The band shops use for a cutting tap, percent (a named default: 60–75 %).
    pub band: [f64; 2],
}

/// The band of percent thread shop tap-drill charts recommend for cutting taps in most
/// materials (a named default: 75 % is the charts' usual target; above it the tap's torque
/// rises steeply for little more strength, below 60 % the thread weakens).
pub const THREAD_PERCENT_BAND: [f64; 2] = [60.0, 75.0];

/// The percent thread a drill of `drill` mm leaves for `thread`: for the 60° parallel forms
/// (ISO metric, Unified), else `None`.
///
/// ```
/// use threadcheck::{thread_percent, BasicThread};
/// // M10x1.5 after Ø8.5: (10 − 8.5) / (1.299·1.5) = 77.0 %.
/// let t = thread_percent(&BasicThread::metric(10.0, 1.5), 8.5).unwrap();
/// assert!((t.percent - 76.98).abs() < 0.01);
/// ```
pub fn thread_percent(thread: &crate::standards::BasicThread, drill: f64) -> Option<ThreadPercent> {
    use crate::standards::ThreadForm;
    if !matches!(thread.form, ThreadForm::IsoMetric | ThreadForm::Unified) || !(drill > 0.0) {
        return None;
    }
    let (d, p) = (thread.nominal_diameter, thread.pitch);
    let full = 2.0 * 0.75 * 3f64.sqrt() / 2.0 * p;
    let basic = 1.082_531_754_730_548 * p;
    Some(ThreadPercent {
        percent: (d - drill) / full * 100.0,
        of_basic_height: (d - drill) / basic * 100.0,
        band: THREAD_PERCENT_BAND,
    })
}
