//! Macro programs: the first byte picks the dialect, the rest is the program, run with moves
//! recorded and in both block orders. An error or a result, never a panic or a hang (loops and
//! calls are bounded; a small budget keeps runaway loops quick under the sanitizer).
#![no_main]
use libfuzzer_sys::fuzz_target;
use threadcheck::{read_program_with, Budget, Dialect, ProgramUnits, ReadOptions};

fuzz_target!(|data: &[u8]| {
    let Some((&first, rest)) = data.split_first() else { return };
    if let Ok(text) = std::str::from_utf8(rest) {
        let d = Dialect::ALL[first as usize % Dialect::ALL.len()];
        let opts = ReadOptions {
            moves: true,
            allow_no_threading: true,
            n_order: first & 0x80 != 0,
            budget: Some(Budget { blocks: 200_000, backward_jumps: 20_000 }),
            default_units: (first & 0x40 != 0).then_some(ProgramUnits::Inch),
            ..ReadOptions::default()
        };
        let _ = read_program_with(text, "fuzz.nc", d, opts);
    }
});
