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

/// A path as messages and reports name it: its text, each byte that is not UTF-8 written as
/// `\xNN` (two names that differ only there stay apart; `display()` made both `�`) and each
/// control character as `\u{a}` (a newline in a file name forged a line of a run's report).
///
/// ```
/// # #[cfg(unix)] {
/// use std::os::unix::ffi::OsStrExt;
/// let p = std::path::Path::new(std::ffi::OsStr::from_bytes(b"lib/a\xff.nc"));
/// assert_eq!(threadcheck::path_name(p), "lib/a\\xff.nc");
/// assert_eq!(threadcheck::path_name(std::path::Path::new("nl\nPASS.nc")), "nl\\u{a}PASS.nc");
/// # }
/// ```
pub fn path_name(path: &std::path::Path) -> String {
    let controls = |s: &str, out: &mut String| {
        for c in s.chars() {
            if c.is_control() {
                out.push_str(&format!("\\u{{{:x}}}", c as u32));
            } else {
                out.push(c);
            }
        }
    };
    let mut out = String::new();
    if let Some(s) = path.to_str() {
        controls(s, &mut out);
        return out;
    }
    #[cfg(unix)]
    {
        use std::os::unix::ffi::OsStrExt;
        for chunk in path.as_os_str().as_bytes().utf8_chunks() {
            controls(chunk.valid(), &mut out);
            for b in chunk.invalid() {
                out.push_str(&format!("\\x{b:02x}"));
            }
        }
    }
    #[cfg(not(unix))]
    controls(&path.to_string_lossy(), &mut out);
    out
}
