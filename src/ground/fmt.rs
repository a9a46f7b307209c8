//! Numbers as text, for the messages of every wing: no float noise, no trailing zeros.

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

/// A number as a message shows it: plainly, or in exponent form when it is huge or tiny
/// (`1e308`, not 309 digits).
pub fn fmt_shown(v: f64) -> String {
    if v != 0.0 && v.is_finite() && !(1e-6..1e9).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}
