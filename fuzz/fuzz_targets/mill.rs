//! `mill` on any program and any target TOML: a report or an error, never a panic, a hang or
//! unbounded memory. The input is split at the first NUL: the target's TOML, then the program.
#![no_main]
use libfuzzer_sys::fuzz_target;
use threadcheck::{mill, Dialect, MillSpec, Target};

const TARGET: &str = "x = \"20*cos(t)\"\ny = \"20*sin(t)\"\nt = [0, 360]\nz = [-5, 0]\nmaterial = \"inside\"\n";

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let (target_text, program) = match text.split_once('\0') {
        Some((t, p)) => (t, p),
        None => (TARGET, text),
    };
    let Ok(target) = Target::from_toml(target_text, "fuzz-target.toml") else { return };
    for dialect in [Dialect::Fanuc, Dialect::Dyna] {
        let spec = MillSpec {
            program: (program.to_string(), "fuzz.nc".to_string()),
            dialect,
            n_order: false,
            tool_diameter: 6.0,
            target: target.clone(),
            tolerance: 0.05,
            reading: Default::default(),
        };
        let _ = mill(&spec);
    }
});
