//! Any text as each data file threadcheck reads (a tool table, a machine profile, a mill
//! target, an insert): a value or an error, never a panic.
#![no_main]
use libfuzzer_sys::fuzz_target;
use threadcheck::{Insert, MachineProfile, Target, ToolTable};

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        // The tool table's inserts are looked up in an empty directory: names that are not
        // words fail as missing files.
        let _ = ToolTable::from_toml(text, "fuzz-tools.toml", std::path::Path::new("/nonexistent"));
        let _ = MachineProfile::from_toml(text, "fuzz-machine.toml");
        let _ = Target::from_toml(text, "fuzz-target.toml");
        let _ = Insert::from_toml(text, "fuzz-insert.toml", 1e-3);
    }
});
