//! What a dialect is to the interpreter: the [`Rules`] a dialect module implements, the
//! [`Flow`] it answers after a block and the [`Ctx`] it may ask. The interpreter knows this
//! trait, never a dialect; the dialect table in `mod.rs` hands it the rules of the dialect read.

use super::lexer::Block;
use super::motion::{Motion, RBlock};
use super::Dialect;
use crate::Error;
use std::collections::HashSet;

/// What the interpreter needs to know of a dialect's macro language, in one table: a new dialect
/// fails to compile until [`Language::of`] says each of these for it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Language {
    /// Numbered locals `#1 ..= #n` in each call frame (Fanuc macro B: 33; LinuxCNC: 30).
    pub local_range: i64,
    /// `#0` is the always-null variable and #1000–#4999 are system variables (Fanuc macro B).
    pub fanuc_macro: bool,
    /// Numbered variables are written `R n` (Sinumerik's R-parameters).
    pub r_parameters: bool,
    /// What an unset variable reads as, in words.
    pub unset_reads: &'static str,
    /// Reading an undefined named parameter is an error (LinuxCNC).
    pub named_must_exist: bool,
    /// The numbered parameters the control keeps in its parameter file, not the program (LinuxCNC's
    /// homes, G92 and work offsets, #5161–#5390): an unset one reads as a fresh file's 0, said.
    pub stored_numbered: Option<(i64, i64)>,
    /// Predefined parameters the control has and threadcheck does not model, with what they
    /// hold (a name ending in `[` stands for a family, `_ini[`): reading one is refused by name.
    pub unmodelled_names: &'static [(&'static str, &'static str)],
    /// The block's words are evaluated before its assignments, which all take effect after the
    /// block, an unset value as 0 (LinuxCNC); otherwise assignments run first, in order.
    pub deferred_assignments: bool,
    /// A word whose value is an unset variable is left out with its address (Fanuc macro B's
    /// null words); otherwise it reads 0.
    pub null_word_omitted: bool,
    /// Programs in one file start at a header (`O1234`, Sinumerik's `%_N_…`): the file is cut
    /// into subprograms there.
    pub headers_split_programs: bool,
    /// A leading header names the main program (Fanuc, Haas).
    pub leading_header_is_main: bool,
    /// The deepest WHILE nesting the control allows, when it sets one (Fanuc: 3).
    pub max_while_nesting: Option<usize>,
    /// G70/G71/G72 call the profile subroutine named by Q (LinuxCNC).
    pub lathe_cycles_call_q: bool,
    /// How a subprogram is called in the dialect's words (`subprogram 1001`, `o100 sub`).
    pub sub_word: fn(&str) -> String,
    /// Predefined named parameters, read-only to a program (LinuxCNC's `#<_x>`, `#<_metric>` …).
    pub read_only_names: &'static [&'static str],
    /// How comparisons and MOD behave (LinuxCNC's tolerance of 1e-6).
    pub arithmetic: super::expr::Arithmetic,
}

/// LinuxCNC's predefined named parameters (its manual, "Predefined Named Parameters"): a program
/// reads them and cannot set them.
const LINUXCNC_PREDEFINED: &[&str] = &[
    "_vmajor",
    "_vminor",
    "_line",
    "_motion_mode",
    "_plane",
    "_ccomp",
    "_metric",
    "_imperial",
    "_absolute",
    "_incremental",
    "_inverse_time",
    "_units_per_minute",
    "_units_per_rev",
    "_coord_system",
    "_tool_offset",
    "_retract_r_plane",
    "_retract_old_z",
    "_spindle_rpm_mode",
    "_spindle_css_mode",
    "_ijk_absolute_mode",
    "_lathe_diameter_mode",
    "_lathe_radius_mode",
    "_spindle_on",
    "_spindle_cw",
    "_mist",
    "_flood",
    "_speed_override",
    "_feed_override",
    "_adaptive_feed",
    "_feed_hold",
    "_feed",
    "_rpm",
    "_x",
    "_y",
    "_z",
    "_a",
    "_b",
    "_c",
    "_u",
    "_v",
    "_w",
    "_abs_x",
    "_abs_y",
    "_abs_z",
    "_abs_a",
    "_abs_b",
    "_abs_c",
    "_abs_u",
    "_abs_v",
    "_abs_w",
    "_current_tool",
    "_current_pocket",
    "_selected_tool",
    "_selected_pocket",
    "_value",
    "_value_returned",
    "_task",
    "_call_level",
    "_remap_level",
];

impl Language {
    /// The table.
    pub fn of(dialect: Dialect) -> Language {
        let fanuc = Language {
            local_range: 33,
            fanuc_macro: true,
            r_parameters: false,
            unset_reads: "it is null (0 in arithmetic)",
            named_must_exist: false,
            stored_numbered: None,
            unmodelled_names: &[],
            deferred_assignments: false,
            null_word_omitted: true,
            headers_split_programs: true,
            leading_header_is_main: true,
            max_while_nesting: Some(3),
            lathe_cycles_call_q: false,
            sub_word: |n| format!("subprogram {n}"),
            read_only_names: &[],
            arithmetic: super::expr::Arithmetic::Exact,
        };
        match dialect {
            // Okuma's own macro language (VC variables) is not read; its programs lex as Fanuc's.
            // Okuma's own macro language (VC variables) and Heidenhain's DIN PLUS variables are
            // not read; their programs lex as Fanuc's (Heidenhain's `[ ]` comments taken out).
            Dialect::Fanuc
            | Dialect::Haas
            | Dialect::Okuma
            | Dialect::Mitsubishi
            | Dialect::Mazak
            | Dialect::Heidenhain
            | Dialect::Klartext => fanuc,
            Dialect::Sinumerik => Language {
                local_range: 0,
                fanuc_macro: false,
                r_parameters: true,
                unset_reads: "a Sinumerik reads it as 0",
                null_word_omitted: false,
                leading_header_is_main: false,
                max_while_nesting: None,
                ..fanuc
            },
            Dialect::LinuxCnc => Language {
                local_range: 30,
                fanuc_macro: false,
                unset_reads: "LinuxCNC reads it as 0",
                named_must_exist: true,
                stored_numbered: Some((5161, 5390)),
                unmodelled_names: &[
                    ("_vmajor", "the version the machine runs"),
                    ("_vminor", "the version the machine runs"),
                    ("_task", "whether the machine runs the program or a preview reads it"),
                    ("_tool_offset", "the tool length offset (G43)"),
                    ("_current_pocket", "the tool table's pockets"),
                    ("_selected_pocket", "the tool table's pockets"),
                    ("_ini[", "the machine's INI file"),
                ],
                deferred_assignments: true,
                null_word_omitted: false,
                headers_split_programs: false,
                leading_header_is_main: false,
                max_while_nesting: None,
                lathe_cycles_call_q: true,
                sub_word: |n| format!("o{n} sub"),
                read_only_names: LINUXCNC_PREDEFINED,
                arithmetic: super::expr::Arithmetic::LinuxCnc,
                ..fanuc
            },
            Dialect::Dyna => Language {
                local_range: 0,
                fanuc_macro: false,
                headers_split_programs: false,
                leading_header_is_main: false,
                max_while_nesting: None,
                ..fanuc
            },
        }
    }
}

/// A dialect's read-only system parameters (LinuxCNC's `_x`, `_z`, …): a fixed table of
/// names the dialect declares, each set by its slot before every block, read by name.
#[derive(Debug, Default)]
pub(crate) struct SysParams {
    names: &'static [&'static str],
    values: Vec<Option<f64>>,
    /// The dialect's numbered parameters the program's state sets (LinuxCNC's #5220, #5400,
    /// #5420–#5428), by number.
    numbered: Vec<(i64, f64)>,
}

impl SysParams {
    /// The parameters `names`, none set yet.
    pub fn new(names: &'static [&'static str]) -> SysParams {
        SysParams { names, values: vec![None; names.len()], numbered: Vec::new() }
    }

    /// Sets the parameter in slot `k` (its index in the names) to `v`.
    pub fn set(&mut self, k: usize, v: f64) {
        debug_assert!(k < self.values.len());
        if let Some(x) = self.values.get_mut(k) {
            *x = Some(v);
        }
    }

    /// The value of `name`, if the dialect has one by that name and has set it.
    pub fn get(&self, name: &str) -> Option<f64> {
        self.names.iter().position(|n| *n == name).and_then(|k| self.values[k])
    }

    /// Sets the parameter `name` to `v`, where the dialect has it.
    pub fn set_named(&mut self, name: &str, v: f64) {
        if let Some(k) = self.names.iter().position(|n| *n == name) {
            self.values[k] = Some(v);
        }
    }

    /// Sets the numbered parameter `n` to `v`.
    pub fn set_numbered(&mut self, n: i64, v: f64) {
        match self.numbered.iter_mut().find(|(k, _)| *k == n) {
            Some(p) => p.1 = v,
            None => self.numbered.push((n, v)),
        }
    }

    /// The numbered parameter `n`, if the dialect's state sets it.
    pub fn get_numbered(&self, n: i64) -> Option<f64> {
        self.numbered.iter().find(|(k, _)| *k == n).map(|p| p.1)
    }

    /// Whether the dialect has a parameter by that name.
    pub fn has(&self, name: &str) -> bool {
        self.names.contains(&name)
    }
}

/// A dialect's rules for the blocks it reads: one value per program read, holding the
/// dialect's modal state.
pub(crate) trait Rules {
    /// Runs one resolved block: motion and cycles into `m`, and what the interpreter does next.
    fn block(&mut self, m: &mut Motion, b: &RBlock<'_>, cx: &mut Ctx<'_>) -> Result<Flow, Error>;

    /// The names of the dialect's read-only system parameters, in their slots' order; none for
    /// dialects that have none.
    fn system_names(&self) -> &'static [&'static str] {
        &[]
    }

    /// Refreshes the dialect's read-only system parameters (LinuxCNC's `#<_x>`) before a block;
    /// nothing for dialects that have none.
    fn system_params(&self, _m: &Motion, _sys: &mut SysParams) {}

    /// The block that ends the loop starting at `pc` (Dyna's M73 … M74), for dialects that have
    /// such loops.
    fn loop_end(&self, _blocks: &[Block], _pc: usize) -> Option<usize> {
        None
    }
}

/// What a dialect module asks of the interpreter after a block.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Flow {
    /// Go on with the next block.
    Next,
    /// The program ends here (M30, M2).
    End,
    /// Call a subprogram of this file (`O1002`, `L9`) `repeats` times; with `locals`, in a new
    /// local frame holding them (G65), else sharing the caller's (M98, L).
    Call { name: String, repeats: u32, locals: Option<Vec<(i64, f64)>>, col: usize },
    /// Haas `M97 Pn`: a subroutine at sequence number n of this program.
    LocalCall { n: f64, repeats: u32, col: usize },
    /// Return from a subprogram (M99, M17), optionally to sequence number n of the caller.
    Return { to_n: Option<f64>, col: usize },
    /// Dyna `M73 N k`: the following blocks up to the matching M74 run k times.
    LoopStart { count: f64, col: usize },
    /// Dyna `M74`.
    LoopEnd { col: usize },
}

/// What the interpreter's variable store answers a dialect module.
pub(crate) trait Store {
    /// A numbered variable (Sinumerik R-parameters for L96/L97), with a note when unset.
    fn numbered(&mut self, m: &mut Motion, n: i64, line: usize, col: usize) -> Option<f64>;
}

/// What the dialect modules may ask of the interpreter.
pub(crate) struct Ctx<'a> {
    /// The variables.
    pub store: &'a mut dyn Store,
    /// Subprograms defined in the file.
    pub subs: &'a HashSet<String>,
    /// Sequence numbers in the file.
    pub ns: &'a HashSet<u64>,
}

impl Ctx<'_> {
    /// Whether a block N`n` exists in the file.
    pub fn has_n(&self, n: f64) -> bool {
        self.ns.contains(&n_key(n))
    }

    /// A numbered variable (Sinumerik R-parameters for L96/L97), with a note when unset.
    pub fn get(&mut self, m: &mut Motion, n: i64, line: usize, col: usize) -> Option<f64> {
        self.store.numbered(m, n, line, col)
    }
}

/// A sequence number as a hashable key.
pub(crate) fn n_key(n: f64) -> u64 {
    (n * 1000.0).round().max(0.0) as u64
}
