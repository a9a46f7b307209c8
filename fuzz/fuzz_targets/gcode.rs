//! Any bytes, read as a program in every dialect: an error or passes, never a panic or a hang.
//! A small execution budget keeps runaway loops quick under the sanitizer; the full bounds of
//! `limits.rs` are the same code with larger numbers.
#![no_main]
use libfuzzer_sys::fuzz_target;
use threadcheck::{read_program_with, Budget, Dialect, ReadOptions};

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let opts = ReadOptions {
            budget: Some(Budget { blocks: 200_000, backward_jumps: 20_000 }),
            ..ReadOptions::default()
        };
        for d in Dialect::ALL {
            let _ = read_program_with(text, "fuzz.nc", d, opts);
        }
    }
});
