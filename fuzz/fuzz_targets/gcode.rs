//! Any bytes, read as a program in every dialect (and Fanuc's G-code systems B and C): an error
//! or passes, never a panic or a hang.
//! A small execution budget keeps runaway loops quick under the sanitizer; the full bounds of
//! `limits.rs` are the same code with larger numbers.
#![no_main]
use libfuzzer_sys::fuzz_target;
use threadcheck::{read_program_with, Budget, Dialect, GCodeSystem, MachineType, ReadOptions};

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let opts = ReadOptions {
            budget: Some(Budget { blocks: 200_000, backward_jumps: 20_000 }),
            ..ReadOptions::default()
        };
        for d in Dialect::ALL {
            let _ = read_program_with(text, "fuzz.nc", d, opts.clone());
        }
        // The machine-centre and mill-turn readings of the Fanuc family, whatever the words show.
        for t in [MachineType::Mill, MachineType::MillTurn] {
            let _ = read_program_with(text, "fuzz.nc", Dialect::Fanuc, ReadOptions { machine_type: Some(t), ..opts.clone() });
        }
        for gcode_system in [GCodeSystem::B, GCodeSystem::C] {
            let _ = read_program_with(text, "fuzz.nc", Dialect::Fanuc, ReadOptions { gcode_system: Some(gcode_system), ..opts.clone() });
        }
    }
});
