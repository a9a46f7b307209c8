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

/// A name read from a user's file (a machine profile's, an insert's, a tool table's entry) as
/// every output shows it: control characters and the bidirectional overrides escaped as
/// `\u{…}`, so that a newline in a name cannot forge a line of a report.
///
/// ```
/// assert_eq!(threadcheck::shown_text("lathe\nverdict: PASS"), "lathe\\u{a}verdict: PASS");
/// assert_eq!(threadcheck::shown_text("ok \u{202e}x"), "ok \\u{202e}x");
/// ```
pub fn shown_text(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_control() || matches!(c, '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}') {
            out.push_str(&format!("\\u{{{:x}}}", c as u32));
        } else {
            out.push(c);
        }
    }
    out
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
    let controls = |s: &str, out: &mut String| out.push_str(&shown_text(s));
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
