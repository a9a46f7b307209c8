//! Random but valid thread + insert + pass plans, swept and measured: an error or a measurement,
//! never a panic; a measurement is finite.
#![no_main]
use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use threadcheck::{verify, InsertChoice, VerifySpec};
use threadcheck::{Infeed, Schedule};

#[derive(Arbitrary, Debug)]
struct Case {
    size: u8,
    internal: bool,
    insert: u8,
    tip: u8,
    infeed: u8,
    angle: u8,
    schedule: u8,
    passes: u8,
    spring: u8,
    final_offset: i16,
    blank_offset: i8,
}

const SIZES: [&str; 8] = [
    "M3-6H/6g",
    "M6x0.75-6H/6g",
    "M10x1.5-6H/6g",
    "M16x1.5-6H/6g",
    "M24xPh6P2-6H/6g",
    "M36x4-6H/6g",
    "BSW 1/2 medium",
    "G1/2 A",
];

fuzz_target!(|c: Case| {
    let size = SIZES[c.size as usize % SIZES.len()];
    let mut s = VerifySpec::of(size).expect("a standard size");
    s.internal = c.internal && !size.starts_with("G") && !size.starts_with("BSW");
    s.insert = match c.insert % 3 {
        0 => InsertChoice::Full,
        _ => InsertChoice::Partial { tip_radius: f64::from(c.tip % 100) * 0.002 },
    };
    let angle = f64::from(c.angle % 61);
    s.infeed = Some(
        match c.infeed % 3 {
            0 => Infeed::Radial,
            1 => Infeed::Flank { angle },
            _ => Infeed::Alternating { angle },
        }
        .into(),
    );
    s.schedule =
        [Schedule::ConstantArea, Schedule::ConstantDepth, Schedule::Sandvik][c.schedule as usize % 3].clone();
    s.passes = Some(1 + (c.passes % 40) as usize);
    s.spring = (c.spring % 4) as usize;
    s.tolerance = 1e-3;
    if c.final_offset != 0 {
        // Around the basic root: ±0.33 mm on the diameter in 10 µm steps.
        let base = s.designation.as_ref().map_or(8.0, |d| d.thread.minor_diameter_external());
        s.final_x = Some(base + f64::from(c.final_offset % 33) * 0.01);
    }
    if c.blank_offset != 0 {
        s.blank_diameter = Some(10.0 + f64::from(c.blank_offset) * 0.1);
    }
    if let Ok(v) = verify(&s) {
        let m = v.measurement;
        assert!(m.pitch_diameter.is_finite() && m.major_diameter.is_finite() && m.minor_diameter.is_finite());
    }
});
