//! Lathe or machining centre: the machine a program is read for, given or found in the
//! program's own evidence (../shared/notes/machining-centres.md §6), before any code whose
//! meaning flips between the two is read (G90/G91, G94/G95, G98/G99, G73, G74, G76).

use super::lexer::{Block, WVal};
use super::Dialect;
use serde::Serialize;

/// The kind of machine a program runs on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MachineType {
    /// A lathe: X a diameter, G18; on Fanuc's G-code system A, G90 the box cycle, G98/G99 feed
    /// per minute/revolution, G76 threading.
    Lathe,
    /// A machining centre: X is X, G17; G90/G91 absolute/incremental, G94/G95 feed modes,
    /// G98/G99 the canned cycles' return level, G73/G74/G76 drilling, left-hand tapping and
    /// fine boring.
    Mill,
    /// A lathe with live tools (or a machining centre that turns): each section read as the
    /// machine its plane names, G18 a lathe's, G17 and G19 a machining centre's (X and Y in the
    /// plane, X not a diameter).
    MillTurn,
}

impl MachineType {
    /// `lathe` or `mill`.
    pub fn name(self) -> &'static str {
        match self {
            MachineType::Lathe => "lathe",
            MachineType::Mill => "mill",
            MachineType::MillTurn => "mill-turn",
        }
    }
}

impl std::str::FromStr for MachineType {
    type Err = crate::Error;

    fn from_str(s: &str) -> Result<MachineType, crate::Error> {
        match s {
            "lathe" => Ok(MachineType::Lathe),
            "mill" | "machining-centre" | "machining-center" => Ok(MachineType::Mill),
            "mill-turn" => Ok(MachineType::MillTurn),
            _ => Err(crate::Error::Input(format!("machine type '{s}': expected lathe, mill or mill-turn"))),
        }
    }
}

/// The machine a program was read for, and why.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MachineReading {
    /// Lathe or mill.
    pub machine_type: MachineType,
    /// Why: given, the block that shows it, or the dialect's default.
    pub reason: String,
}

/// Why a program is read as a mill-turn: the first block of each machine.
fn mill_turn_reason(l0: usize, what0: &str, l1: usize, what1: &str) -> String {
    format!(
        "read as a mill-turn: line {l0} writes {what0} and line {l1} writes {what1}; each section is read by its plane, G18 as a lathe's, G17 and G19 as a machining centre's (‹machine_type› chooses otherwise)"
    )
}

/// What decides the machine: `given` (the caller's choice, or the machine file's `type`, named
/// by `by`), a milling toolpath (`moves`), the program's own evidence (a block whose words only
/// one kind of machine writes: both kinds make it a mill-turn program), else the dialect's
/// default. A block that contradicts a given lathe or mill is an error at its line (line,
/// column, message).
pub(crate) fn decide(
    blocks: &[Block],
    dialect: Dialect,
    given: Option<MachineType>,
    by: Option<&str>,
    moves: bool,
) -> Result<MachineReading, (usize, usize, String)> {
    let read = |machine_type, reason: String| Ok(MachineReading { machine_type, reason });
    // The machine a dialect's controls are, whatever a program writes; `None`: its evidence
    // decides.
    let fixed = match dialect {
        // Okuma OSP lathes and Heidenhain's DIN lathe controls are the dialects read here.
        Dialect::Okuma | Dialect::Heidenhain => Some((
            MachineType::Lathe,
            format!("read as a lathe: the {} dialect is its lathe control's", dialect.name()),
        )),
        // Read by its own reader, which says so; here for completeness.
        Dialect::Klartext => {
            Some((MachineType::Mill, "read as a machining centre: Klartext is a TNC's".into()))
        }
        Dialect::Dyna => {
            Some((MachineType::Mill, "read as a machining centre: Dyna controls are mills".into()))
        }
        Dialect::Fanuc
        | Dialect::Haas
        | Dialect::Mitsubishi
        | Dialect::Mazak
        | Dialect::Sinumerik
        | Dialect::LinuxCnc => None,
    };
    // The program's evidence: the first block that shows a machine, and the first that shows
    // the other (both: a mill-turn program).
    let shown = || {
        let first = first_showing(blocks, dialect, |_| true)?;
        let other = first_showing(blocks, dialect, |m| m != first.1);
        Some((first, other))
    };
    // A milling toolpath is a machining centre's unless the program turns too (a mill-turn
    // program's turning sections are read as a lathe's, so a lathe cycle is not taken for a
    // mill's drilling cycle).
    if moves && given.is_none() && fixed.is_none() {
        if let Some(((b0, _, what0), Some((b1, _, what1)))) = shown() {
            return read(MachineType::MillTurn, mill_turn_reason(b0.line, &what0, b1.line, &what1));
        }
    }
    if moves && given != Some(MachineType::MillTurn) {
        return read(MachineType::Mill, "read as a milling toolpath (G17, X and Y in the plane)".into());
    }
    if let Some(t) = given {
        let source = by.map_or("‹machine_type›".to_string(), str::to_string);
        // The user's word wins: obeyed, with what in the program disagrees named.
        if t != MachineType::MillTurn {
            if let Some((b, _, what)) = first_showing(blocks, dialect, |m| m != t) {
                return read(
                    t,
                    format!(
                        "read as a {}, as {source} says, though line {} writes {what}, which a {} does not write as a rule (a program that turns and mills is read with machine type mill-turn)",
                        t.name(),
                        b.line,
                        if t == MachineType::Lathe { "lathe" } else { "machining centre" },
                    ),
                );
            }
        }
        return read(t, format!("read as a {}, as {source} says", t.name()));
    }
    if let Some((t, why)) = fixed {
        return read(t, why);
    }
    let Some(((b0, t0, what0), other)) = shown() else {
        return read(
            MachineType::Lathe,
            "read as a lathe, the default: no block shows the machine (G17 or G18, a tool change, a drilling cycle's return level, …; ‹machine_type› chooses)".into(),
        );
    };
    if let Some((b1, _, what1)) = other {
        return read(MachineType::MillTurn, mill_turn_reason(b0.line, &what0, b1.line, &what1));
    }
    read(
        t0,
        format!(
            "read as a {}: line {} writes {what0} (‹machine_type› chooses otherwise)",
            match t0 {
                MachineType::Lathe => "lathe",
                MachineType::Mill => "machining centre",
                MachineType::MillTurn => "mill-turn",
            },
            b0.line
        ),
    )
}

/// The first block whose words show a machine `wanted` accepts, the machine and the words that
/// show it.
fn first_showing(
    blocks: &[Block],
    dialect: Dialect,
    wanted: impl Fn(MachineType) -> bool,
) -> Option<(&Block, MachineType, String)> {
    blocks.iter().find_map(|b| evidence(b, dialect).filter(|e| wanted(e.0)).map(|e| (b, e.0, e.1)))
}

/// Whether a mill-turn program starts as a machining centre's: its first block that shows a
/// machine shows one (else it starts as a lathe's).
pub(crate) fn starts_as_mill(blocks: &[Block], dialect: Dialect) -> bool {
    first_showing(blocks, dialect, |_| true).is_some_and(|e| e.1 == MachineType::Mill)
}

/// The machine a block shows, if any, and the words that show it.
fn evidence(b: &Block, dialect: Dialect) -> Option<(MachineType, String)> {
    let num = |name: &'static str| {
        b.words.iter().filter(move |w| w.name == name).filter_map(|w| match w.val {
            WVal::Num { v, .. } => Some(v),
            _ => None,
        })
    };
    let has = |name: &str| b.words.iter().any(|w| w.name == name);
    let gs: Vec<f64> = num("G").collect();
    let g = |c: f64| gs.contains(&c);
    let fanuc = dialect.fanuc_family();
    if g(17.0) {
        return Some((MachineType::Mill, "G17, the milling plane".into()));
    }
    if g(18.0) {
        return Some((MachineType::Lathe, "G18, the turning plane".into()));
    }
    if g(43.0) && has("H") {
        return Some((MachineType::Mill, "G43 H, a tool length offset".into()));
    }
    if dialect == Dialect::LinuxCnc && g(7.0) {
        return Some((MachineType::Lathe, "G7, diameter mode".into()));
    }
    if fanuc {
        // A lathe's live tool milling the face (F0i-TF: G12.1, also written G112): a lathe's
        // code, but a milling section of it.
        if let Some(c) = gs.iter().find(|&&c| c == 12.1 || c == 112.0) {
            return Some((MachineType::Mill, format!("G{c}, a live tool's polar coordinate interpolation")));
        }
        let drilling = gs.iter().any(|c| matches!(*c as u32, 73 | 74 | 76 | 81..=89) && c.fract() == 0.0);
        if drilling && (g(98.0) || g(99.0)) && has("R") {
            return Some((
                MachineType::Mill,
                "a drilling cycle with its return level (G98/G99) and R in one block".into(),
            ));
        }
        let tool_change = num("M").any(|m| m == 6.0);
        // The T word as written (`T0707`), and whether it is a lathe's four digits: the turret
        // station and its offset. A turret lathe (Denford's Fanuc-style controls among them)
        // may index with M6 too: the four digits decide, not the M6.
        let t_word = b.words.iter().find(|w| w.name == "T" && matches!(w.val, WVal::Num { .. }));
        let m_word =
            b.words.iter().find(|w| w.name == "M" && matches!(w.val, WVal::Num { v, .. } if v == 6.0));
        if let (Some(t), Some(tv)) = (t_word, num("T").next()) {
            let digits = t.text.trim_start_matches(['T', 't']);
            let station_and_offset = digits.len() == 4 && digits.bytes().all(|c| c.is_ascii_digit());
            if station_and_offset {
                let with = m_word.map_or(String::new(), |m| format!(" {}", m.text));
                return Some((
                    MachineType::Lathe,
                    format!("{}{with}, a turret station and its offset", t.text),
                ));
            }
            if tool_change {
                let m = m_word.map_or("M6".to_string(), |m| m.text.clone());
                return Some((MachineType::Mill, format!("{} {m}, a tool change", t.text)));
            }
            if tv >= 100.0 {
                return Some((MachineType::Lathe, format!("{}, a tool and its offset", t.text)));
            }
        }
        if has("U") || has("W") {
            return Some((MachineType::Lathe, "U or W, incremental X and Z".into()));
        }
    }
    // A Y move: a lathe has no Y axis (one with live tools and a Y axis mills in G17 or G19,
    // which says so first). Not a Y that sets an offset, a reference point or a macro's argument.
    // Nor a Y in a threading block: a lathe's word that does not belong there, refused there.
    let sets_not_moves = gs
        .iter()
        .any(|&c| [10.0, 28.0, 30.0, 32.0, 33.0, 34.0, 52.0, 65.0, 66.0, 76.0, 78.0, 92.0].contains(&c));
    if (fanuc || dialect == Dialect::LinuxCnc) && !sets_not_moves {
        if let Some(y) = b.words.iter().find(|w| w.name == "Y" && matches!(w.val, WVal::Num { .. })) {
            return Some((MachineType::Mill, format!("{}, a Y move (a lathe has no Y axis)", y.text)));
        }
    }
    None
}

/// What in a block's code (comments cut off) only a DDCS controller's macros write, and its
/// column: its Modbus and byte commands (`MSETDATA[…]`, DDCS Expert's manual); in a program
/// read as Fanuc-family or LinuxCNC (which compare with EQ and NE), a comparison written `!=` or
/// `==`, or a `//` comment after a block's words (those dialects read `/` as block delete or
/// division, never twice).
fn ddcs_word(code: &str, dialect: Dialect) -> Option<(usize, String)> {
    let col = |at: usize| code[..at].chars().count() + 1;
    for w in ["MSETDATA", "MGETDATA", "MDATA2BYTE", "MBYTE2DATA"] {
        if let Some(at) = code.find(w) {
            return Some((col(at), format!("{w} is a DDCS controller's data command")));
        }
    }
    // The dialects whose comparison words are known here (EQ, NE: Fanuc macro B, LinuxCNC).
    let words_compare = match dialect {
        Dialect::Fanuc | Dialect::Haas | Dialect::Mitsubishi | Dialect::Mazak | Dialect::LinuxCnc => true,
        // Sinumerik writes `==` itself; the others' comparison words were not read here.
        Dialect::Sinumerik | Dialect::Dyna | Dialect::Okuma | Dialect::Heidenhain | Dialect::Klartext => {
            false
        }
    };
    if words_compare {
        if let Some(at) = code.find("!=") {
            return Some((
                col(at),
                "`!=` compares as a DDCS controller's macros do (Fanuc macro B writes NE)".into(),
            ));
        }
        if let Some(at) = code.find("==") {
            return Some((
                col(at),
                "`==` compares as a DDCS controller's macros do (Fanuc macro B writes EQ)".into(),
            ));
        }
        if let Some(at) = code.find("//").filter(|&at| !code[..at].trim().is_empty()) {
            return Some((col(at), "`//` opens a comment as a DDCS controller's programs write it".into()));
        }
    }
    None
}

/// A control whose programs threadcheck does not read, named at the first line that shows it:
/// (line, column, message). Heidenhain's Klartext (`BEGIN PGM`), Beckhoff TwinCAT's `#`
/// commands and cycle calls (`#TURN[…]`, `L CYCLE [NAME=…]`); a Fanuc macro's `#100=`, a
/// LinuxCNC `#<name>` and a Sinumerik `L100` call are their own dialects' and pass.
pub(crate) fn foreign_control(text: &str, dialect: Dialect) -> Option<(usize, usize, String)> {
    for (i, line) in text.lines().enumerate().take(200_000) {
        let code = line.split(['(', ';']).next().unwrap_or("");
        if let Some((col, what)) = ddcs_word(code, dialect) {
            return Some((
                i + 1,
                col,
                format!("{what}: a DDCS (Digital Dream) controller's macro program, which threadcheck does not read (its C-style comparisons, // comments and M…DATA commands are not Fanuc macro B's); give the threading blocks as a Fanuc-family control reads them (EQ, NE, GT, LT in IF and WHILE), or check it on the control"),
            ));
        }
        let trimmed = code.trim_start();
        let col = code.len() - trimmed.len() + 1;
        // A block number before the words (Klartext numbers every block: `0 BEGIN PGM`).
        let words = trimmed.trim_start_matches(|c: char| c.is_ascii_digit() || c == 'N').trim_start();
        let wcol = col + (trimmed.len() - words.len());
        if words.starts_with("BEGIN PGM") {
            return Some((
                i + 1,
                wcol,
                "BEGIN PGM opens a Heidenhain Klartext (conversational) program: read it with ‹dialect› klartext (a .h file is read so by its extension; ‹dialect› heidenhain reads the DIN programs of Heidenhain's lathe controls)".into(),
            ));
        }
        let hash_word = words.strip_prefix('#').is_some_and(|r| {
            let name: String = r.chars().take_while(|c| c.is_ascii_uppercase()).collect();
            name.len() >= 2 && r[name.len()..].trim_start().starts_with(['[', '('])
        });
        let cycle_call = words.starts_with("L CYCLE") && words.contains("NAME=");
        if hash_word || cycle_call {
            let what = if cycle_call {
                "L CYCLE [NAME=…] is a Beckhoff TwinCAT CNC cycle call".to_string()
            } else {
                let name: String = words.chars().skip(1).take_while(|c| c.is_ascii_uppercase()).collect();
                format!("#{name} is a Beckhoff TwinCAT CNC command")
            };
            return Some((
                i + 1,
                wcol,
                format!("{what}, which threadcheck does not read: TwinCAT's cycles and # commands are not modelled (write the threading as G-code blocks, or check it on the control)"),
            ));
        }
    }
    None
}
