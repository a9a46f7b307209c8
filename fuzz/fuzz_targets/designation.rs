//! Any text as a designation, then its limits for both kinds: never a panic.
#![no_main]
use libfuzzer_sys::fuzz_target;
use threadcheck::limits_for;
use threadcheck::{parse_designation, ParseOptions, ThreadKind};

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        for allow_nonstandard in [false, true] {
            if let Ok(d) = parse_designation(text, ParseOptions { allow_nonstandard }) {
                let _ = limits_for(&d, ThreadKind::External);
                let _ = limits_for(&d, ThreadKind::Internal);
            }
        }
    }
});
