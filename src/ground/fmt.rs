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
