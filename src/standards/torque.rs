//! A cutting tap's torque (issue 64), by the tap maker's published equation and tables (Yamawa,
//! general catalogue, technical information "Tapping torque equation for cutting taps", tables
//! 1 and 2; the same in its 2016–2017 and 2021 editions):
//!
//! Tc = tan θ · kc · K · (D − Do)² · (D + 2·Do) / 24 000  N·m,
//!
//! θ the thread's half angle, kc the material's specific cutting resistance (N/mm², table 1), K
//! the correction for the tap's kind, the material group and a coarse or fine pitch (table 2), D
//! the tap's nominal diameter and Do the hole's, mm. The maker adds that a form tap's torque is
//! "twice or three times" a cutting tap's and not calculable by it: no figure is given for one.
//! Power at the spindle P = Tc · 2π·n / 60 000 kW (Tc · n / 9 549).

use serde::Serialize;

/// A workpiece material of the maker's table 1: its name there, the names it is also known by,
/// its hardness as printed, kc in N/mm² and its group for table 2.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Material {
    /// The table's name (`Ck 45`).
    pub name: &'static str,
    /// Names accepted for it (lower case, without spaces): `ck45`, `c45`, `c45e`.
    #[serde(skip)]
    pub ids: &'static [&'static str],
    /// Hardness as the table prints it.
    pub hardness: &'static str,
    /// Specific cutting resistance kc, N/mm².
    pub kc: f64,
    /// The group whose K applies.
    pub group: MaterialGroup,
}

/// Table 2's material groups.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum MaterialGroup {
    /// Steel.
    Steel,
    /// Cast iron and aluminium alloys.
    CastIronAluminium,
    /// Brass.
    Brass,
}

/// Table 1.
pub const MATERIALS: &[Material] = &[
    Material {
        name: "St 44-2",
        ids: &["st44-2", "st44", "s275jr"],
        hardness: "133 HB",
        kc: 3700.0,
        group: MaterialGroup::Steel,
    },
    Material {
        name: "Ck 15",
        ids: &["ck15", "c15", "c15e"],
        hardness: "141 HB",
        kc: 3600.0,
        group: MaterialGroup::Steel,
    },
    Material {
        name: "Ck 35",
        ids: &["ck35", "c35", "c35e"],
        hardness: "162 HB",
        kc: 3700.0,
        group: MaterialGroup::Steel,
    },
    Material {
        name: "Ck 45",
        ids: &["ck45", "c45", "c45e"],
        hardness: "188 HB",
        kc: 3900.0,
        group: MaterialGroup::Steel,
    },
    Material {
        name: "Ck 60",
        ids: &["ck60", "c60", "c60e"],
        hardness: "188 HB",
        kc: 4000.0,
        group: MaterialGroup::Steel,
    },
    Material {
        name: "42 CrMo 4",
        ids: &["42crmo4"],
        hardness: "193 HB",
        kc: 3600.0,
        group: MaterialGroup::Steel,
    },
    Material {
        name: "42 CrMo 4, 30 HRC",
        ids: &["42crmo4-30hrc"],
        hardness: "30 HRC",
        kc: 4900.0,
        group: MaterialGroup::Steel,
    },
    Material {
        name: "42 CrMo 4, 40 HRC",
        ids: &["42crmo4-40hrc"],
        hardness: "40 HRC",
        kc: 5500.0,
        group: MaterialGroup::Steel,
    },
    Material {
        name: "X 6 CrNi 18 10",
        ids: &["x6crni18-10", "x6crni1810"],
        hardness: "209 HB",
        kc: 4200.0,
        group: MaterialGroup::Steel,
    },
    Material {
        name: "C 105 W2",
        ids: &["c105w2"],
        hardness: "175 HB",
        kc: 5300.0,
        group: MaterialGroup::Steel,
    },
    Material { name: "CuZn40", ids: &["cuzn40"], hardness: "—", kc: 2300.0, group: MaterialGroup::Brass },
    Material {
        name: "G-AlSi8Cu3",
        ids: &["g-alsi8cu3", "alsi8cu3"],
        hardness: "—",
        kc: 1300.0,
        group: MaterialGroup::CastIronAluminium,
    },
    Material {
        name: "GG-25",
        ids: &["gg-25", "gg25", "en-gjl-250"],
        hardness: "193 HB",
        kc: 2900.0,
        group: MaterialGroup::CastIronAluminium,
    },
];

/// Table 2's kinds of cutting tap.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum TapKind {
    /// A straight-fluted hand tap, plug chamfer (5 threads).
    HandPlug,
    /// A straight-fluted hand tap, bottoming chamfer (1.5 threads).
    HandBottoming,
    /// A spiral-fluted tap (the usual machine tap for blind holes; threadcheck's named default).
    SpiralFluted,
    /// A spiral-pointed (gun) tap.
    SpiralPointed,
}

impl TapKind {
    /// The names accepted (`--tap-kind`).
    pub const NAMES: &'static [&'static str] =
        &["hand-plug", "hand-bottoming", "spiral-fluted", "spiral-pointed"];

    /// Table 2's K for `group` and a coarse (else fine) pitch; `None` where the table has no
    /// figure (brass, fine pitch, bottoming and spiral-fluted taps).
    pub fn k(self, group: MaterialGroup, coarse: bool) -> Option<f64> {
        use MaterialGroup::*;
        use TapKind::*;
        let row: [Option<f64>; 6] = match self {
            HandPlug => [Some(1.35), Some(1.15), Some(1.25), Some(1.08), Some(1.60), Some(1.12)],
            HandBottoming => [Some(1.43), Some(1.50), Some(1.30), Some(1.25), Some(1.68), None],
            SpiralFluted => [Some(1.15), Some(1.25), Some(1.05), Some(1.10), Some(0.85), None],
            SpiralPointed => [Some(0.95), Some(1.00), Some(0.80), Some(1.00), Some(0.75), Some(1.00)],
        };
        let col = match group {
            Steel => 0,
            CastIronAluminium => 2,
            Brass => 4,
        } + usize::from(!coarse);
        row[col]
    }

    /// The kind's name as `--tap-kind` takes it.
    pub fn name(self) -> &'static str {
        match self {
            TapKind::HandPlug => "hand-plug",
            TapKind::HandBottoming => "hand-bottoming",
            TapKind::SpiralFluted => "spiral-fluted",
            TapKind::SpiralPointed => "spiral-pointed",
        }
    }
}

impl std::str::FromStr for TapKind {
    type Err = crate::Error;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Ok(match s.trim().to_ascii_lowercase().as_str() {
            "hand-plug" => TapKind::HandPlug,
            "hand-bottoming" => TapKind::HandBottoming,
            "spiral-fluted" => TapKind::SpiralFluted,
            "spiral-pointed" => TapKind::SpiralPointed,
            other => {
                return Err(crate::Error::Input(format!(
                    "unknown tap kind '{other}': expected {}",
                    TapKind::NAMES.join(", ")
                )))
            }
        })
    }
}

/// The material of table 1 named `name` (its name or an accepted id, case and spaces ignored).
pub fn material(name: &str) -> Result<&'static Material, crate::Error> {
    let key: String = name.chars().filter(|c| !c.is_whitespace()).collect::<String>().to_ascii_lowercase();
    MATERIALS
        .iter()
        .find(|m| m.ids.contains(&key.as_str()) || m.name.replace(' ', "").eq_ignore_ascii_case(&key))
        .ok_or_else(|| {
            let names: Vec<&str> = MATERIALS.iter().map(|m| m.ids[0]).collect();
            crate::Error::Input(format!(
                "unknown material '{name}': the tap maker's table has {}",
                names.join(", ")
            ))
        })
}

/// The equation: Tc in N·m for half angle `half` (radians), kc (N/mm²), K, the tap's nominal
/// diameter `d` and the hole's `d0`, mm; 0 when the hole is no smaller than the tap.
///
/// ```
/// use threadcheck::tapping_torque;
/// // M10x1.5, a plug hand tap in Ck 45 (kc 3900, K 1.35) after an Ø8.5 drill:
/// // tan 30° · 3900 · 1.35 · 1.5² · 27 / 24 000 = 7.69 N·m (issue 64's "≈ 7.7").
/// let t = tapping_torque(30f64.to_radians(), 3900.0, 1.35, 10.0, 8.5);
/// assert!((t - 7.6944).abs() < 1e-4, "{t}");
/// ```
pub fn tapping_torque(half: f64, kc: f64, k: f64, d: f64, d0: f64) -> f64 {
    let cut = (d - d0).max(0.0);
    half.tan() * kc * k * cut * cut * (d + 2.0 * d0) / 24_000.0
}
