//! Every explicit bound on input size in one place, so that no input can make threadcheck run
//! for ever or exhaust memory. Each limit is far above what a real program needs.

/// Most passes a plan or program may expand to (all starts together): a real thread takes 5 to
/// a few hundred; a verify of 1 000 passes with its pictures takes 0.7 s (100 000 took
/// 61 s and 1 GB).
pub const MAX_PASSES: usize = 1_000;

/// Most imprints one sweep may place (passes × crossings of the window).
pub const MAX_IMPRINTS: usize = 2_000_000;

/// Most drilling and tapping cycles one program may make (holes, repeats included): a plate of
/// a few hundred tapped holes is large; past the bound the program is refused at the cycle that
/// crosses it (the first 1 000 were once kept without a word, and a failing 1 001st tap passed).
pub const MAX_HOLES: usize = 10_000;

/// Deepest nesting of subprogram calls in a G-code program.
pub const MAX_CALL_DEPTH: usize = 16;

/// Most repetitions of one subprogram call (`L9 P33`).
pub const MAX_REPEATS: usize = 10_000;

/// Most blocks a program may execute, counting repetitions, before it is taken for a loop. The
/// seed paraboloid program runs about 8 million (800 layers of 1440 steps of 7 blocks); the
/// bound trips in 0.65 s (macro B) to 0.8 s (LinuxCNC, whose position parameters are refreshed
/// before every block) on the 2-core machine of reports/performance.md.
pub const MAX_EXECUTED_BLOCKS: usize = 10_000_000;

/// Most loop iterations and backward jumps (WHILE, GOTO back, o-word loops, M73/M74) one
/// program may make: a runaway loop stops here, well within a second.
pub const MAX_BACKWARD_JUMPS: usize = 2_000_000;

/// Largest program file read, bytes: 2 MiB, some 600 times the largest threading program met
/// (3 kB); its worst case, a million one-word blocks, reads in under a second in 250 MB (8 MiB
/// took 2.8 s and 1.5 GB).
pub const MAX_PROGRAM_BYTES: usize = 2 << 20;

/// Largest insert, tool table, machine profile or target file read (TOML), bytes.
pub const MAX_DATA_FILE_BYTES: usize = 1 << 20;

/// Most points a custom insert outline may have, arcs tessellated included.
pub const MAX_OUTLINE_POINTS: usize = 10_000;

/// Farthest an insert outline point may lie from the tip, mm: an insert is a few millimetres
/// across (found by fuzzing: a bulge arc with a 10⁸ mm chord took 19 s to check).
pub const MAX_INSERT_REACH: f64 = 100.0;

/// Most Z levels a milling program may cut for `mill` to check (the source documents' dome has
/// 799).
pub const MAX_MILL_LEVELS: usize = 5_000;

/// Most straight pieces (moves, arcs as chords) `mill` checks over all levels (the source
/// documents' dome has 1 153 603): about 40 bytes each while the levels are held.
pub const MAX_MILL_SEGMENTS: usize = 2_000_000;

/// Most terms (numbers, variables and functions) one target formula of `mill` may hold: the
/// check evaluates it some hundred thousand times per level, so 500 terms take about a second
/// (3 000 took 6 s; the source documents' curves have under 20).
pub const MAX_FORMULA_TERMS: usize = 500;

/// Most target-formula terms `mill` evaluates in one run (samples of every level and the
/// nearest-point searches, each evaluation counting its formulas' terms): about a second on
/// the 2-core machine of reports/bounds.md (about 12 ns a term).
pub const MAX_FORMULA_WORK: u64 = 80_000_000;

/// Most helical turns one thread-milling operation may make (all its helices, a LinuxCNC P
/// or Sinumerik TURN counted in full): a thread mill makes a few to a few hundred; 10 000 turns
/// in one window measure in about half a second (1.9 million took 14 s).
pub const MAX_HELIX_TURNS: usize = 10_000;

/// Most evaluations of the cutter's reach one thread-milling section may take (its 1 601
/// heights, each searching every helix piece whose teeth reach it, 800 samples a radian and a
/// 60-step refinement), estimated from 33 of the heights before the section is cut: about
/// 25 ns each on the 2-core machine of reports/bounds.md, so the largest allowed takes about
/// a second. A single-form cutter's ten helices take 6·10⁶, a comb of 8 rows cutting three
/// turns in quarter arcs 2.6·10⁷; 10 000 one-turn helices stacked 0.0006 mm apart took 372 s.
pub const MAX_SECTION_EVALS: u64 = 40_000_000;

/// Largest cutter `mill` checks, mm (a face mill is at most a few hundred; a 10⁹ mm cutter took
/// 13 s).
pub const MAX_TOOL_DIAMETER: f64 = 1000.0;

/// Farthest from the origin a threading pass may lie, mm (X as a diameter, Z, the phase): a
/// lathe's travel is a few metres. Beyond 10⁶ mm an f64's spacing nears 10⁻¹⁰ mm; at 10¹⁴ mm
/// it is 0.016 mm and the helix's phase is lost (found reading a G92 to Z−10¹⁴, which gave a
/// d2 1.2 mm off, and a CYCLE97 whose start offset NSP of 10²¹ degrees left no section window).
pub const MAX_COORDINATE: f64 = 1.0e6;

/// Programs one `verify` run of many reads (files named and found in folders together).
pub const MAX_BATCH_PROGRAMS: usize = 100_000;
