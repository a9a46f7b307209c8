//! Any bytes, read as a program in every dialect: an error or passes, never a panic or a hang.
#![no_main]
use libfuzzer_sys::fuzz_target;
use threadcheck::gcode::{read_program, Dialect};

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        for d in Dialect::ALL {
            let _ = read_program(text, "fuzz.nc", d);
        }
    }
});
