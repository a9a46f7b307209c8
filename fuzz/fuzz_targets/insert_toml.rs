//! Any text as an insert TOML file: an insert or an error, never a panic.
#![no_main]
use libfuzzer_sys::fuzz_target;
use threadcheck::Insert;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = Insert::from_toml(text, "fuzz.toml", 1e-3);
    }
});
