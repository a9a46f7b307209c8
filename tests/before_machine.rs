//! Issue 63: what the control will refuse and what a post got wrong, each at its line. Every
//! program is written here and shows one construct; what the control does with it is derived
//! from its manual (the reasoning beside each case) and, for LinuxCNC, from its interpreter
//! itself: `rs274` runs every LinuxCNC program of the table, and a finding that carries
//! LinuxCNC's words is one `rs274` refuses with those words, at that line, while every program
//! it accepts carries none (a post's mistake the control runs).

use crate::*;

/// One program and the findings it must give: (rule, line), in the report's order.
struct Case {
    name: &'static str,
    dialect: &'static str,
    args: &'static [&'static str],
    text: &'static str,
    want: &'static [(&'static str, usize)],
}

/// A tapping program's lines for a machining centre: the tap named by a comment, so the
/// tapping check runs.
const CASES: &[Case] = &[
    // ---- LinuxCNC, machining centre: G33.1 and G84 (interp_convert.cc; the G33.1 page:
    // "preposition X and Y, give only Z"; rs274 accepts the sideways move and draws it as one
    // RIGID_TAP to X5 — the tap is dragged).
    Case {
        name: "lc-g33.1-x-move",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G17 G90 G94\n(M8x1.25 tap)\nM3 S500\nG0 X0 Y0 Z5\nG33.1 X5 Z-10 K1.25\nM2\n",
        want: &[("post.tap_moves_sideways", 5)],
    },
    Case {
        name: "lc-g33.1-y-move",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G17 G90 G94\n(M8x1.25 tap)\nM3 S500\nG0 X10 Y10 Z5\nG33.1 Y12 Z-10 K1.25\nM2\n",
        want: &[("post.tap_moves_sideways", 5)],
    },
    Case {
        name: "lc-g33.1-x-written-where-it-stands",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G17 G90 G94\n(M8x1.25 tap)\nM3 S500\nG0 X10 Y10 Z5\nG33.1 X10 Y10 Z-10 K1.25\nM2\n",
        want: &[],
    },
    Case {
        name: "lc-g33.1-k0",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G17 G90 G94\n(M8x1.25 tap)\nM3 S500\nG0 X0 Y0 Z5\nG33.1 Z-10 K0\nM2\n",
        want: &[("post.feed_zero", 5)],
    },
    Case {
        name: "lc-g33.1-s0",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G17 G90 G94\n(M8x1.25 tap)\nM3 S0\nG0 X0 Y0 Z5\nG33.1 Z-10 K1.25\nM2\n",
        want: &[("control.spindle_speed_zero", 5)],
    },
    Case {
        name: "lc-g84-f0",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G17 G90 G94\n(M8x1.25 tap)\nM3 S500\nG0 X0 Y0 Z5\nG84 Z-10 R2 F0\nG80\nM2\n",
        want: &[("post.feed_zero", 5)],
    },
    Case {
        name: "lc-g84-right",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G17 G90 G94\n(M8x1.25 tap)\nM3 S500\nG0 X0 Y0 Z5\nG84 Z-10 R2 F625\nG80\nM2\n",
        want: &[],
    },
    Case {
        // G94 in force: F is per minute, S × P = 500 × 1.25 = 625; F1.25 is the pitch.
        name: "lc-g84-pitch-under-g94",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G17 G90 G94\n(M8x1.25 tap)\nM3 S500\nG0 X0 Y0 Z5\nG84 Z-10 R2 F1.25\nG80\nM2\n",
        want: &[("post.tap_feed_convention", 5)],
    },
    Case {
        // G95 in force: F is per revolution and must be 1.25; F625 is S × P.
        name: "lc-g84-s-times-p-under-g95",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G17 G90 G95\n(M8x1.25 tap)\nM3 S500\nG0 X0 Y0 Z5\nG84 Z-10 R2 F625\nG80\nM2\n",
        want: &[("post.tap_feed_convention", 5)],
    },
    Case {
        name: "lc-g84-s0",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G17 G90 G94\n(M8x1.25 tap)\nM3 S0\nG0 X0 Y0 Z5\nG84 Z-10 R2 F625\nG80\nM2\n",
        want: &[("control.spindle_speed_zero", 5)],
    },
    // ---- LinuxCNC, lathe: threading under cutter compensation (rs274 refuses G76 there, and
    // G33 when the tool has a radius: its compensation code takes G0 and G1 only; T1 has a
    // 0.4 mm nose radius in the table rs274 reads here).
    Case {
        name: "lc-g76-under-g41",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G18 G90 G7\n(M20x1.5)\nM3 S500\nG0 X22 Z5\nG41\nG76 P1.5 Z-20 I-2 J0.2 K1.8\nM2\n",
        want: &[("control.sync_under_compensation", 6)],
    },
    Case {
        name: "lc-g33-under-g42",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G18 G90 G7\n(M20x1.5)\nT1 M6\nM3 S500\nG0 X19.2 Z5\nG42 D1\nG33 Z-20 K1.5\nM2\n",
        want: &[("control.sync_under_compensation", 7)],
    },
    Case {
        name: "lc-g76-after-g40",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G18 G90 G7\n(M20x1.5)\nM3 S500\nG0 X22 Z5\nG41\nG40\nG76 P1.5 Z-20 I-2 J0.2 K1.8\nM2\n",
        want: &[],
    },
    Case {
        name: "lc-g76-plain",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G18 G90 G7\n(M20x1.5)\nM3 S500\nG0 X22 Z5\nG76 P1.5 Z-20 I-2 J0.2 K1.8\nM2\n",
        want: &[],
    },
    Case {
        name: "lc-g76-s0",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G18 G90 G7\n(M20x1.5)\nM3 S0\nG0 X22 Z5\nG76 P1.5 Z-20 I-2 J0.2 K1.8\nM2\n",
        want: &[("control.spindle_speed_zero", 5)],
    },
    // ---- Fanuc lathe: a threading cycle waits for the spindle's one-revolution signal
    // (the thread-cutting pages: the feed is synchronised with the position coder).
    Case {
        name: "fanuc-g76-m5",
        dialect: "fanuc",
        args: &[],
        text: "(M20X1.5-6G)\nG97 S800 M5\nG0 X22 Z5\nG76 P010060 Q100 R0.05\nG76 X18.16 Z-20 P920 Q300 F1.5\nM30\n",
        want: &[("control.spindle_stopped", 5)],
    },
    Case {
        name: "fanuc-g76-s0",
        dialect: "fanuc",
        args: &[],
        text: "(M20X1.5-6G)\nG97 S0 M3\nG0 X22 Z5\nG76 P010060 Q100 R0.05\nG76 X18.16 Z-20 P920 Q300 F1.5\nM30\n",
        want: &[("control.spindle_speed_zero", 5)],
    },
    Case {
        name: "fanuc-g76-m3",
        dialect: "fanuc",
        args: &[],
        text: "(M20X1.5-6G)\nG97 S800 M3\nG0 X22 Z5\nG76 P010060 Q100 R0.05\nG76 X18.16 Z-20 P920 Q300 F1.5\nM30\n",
        want: &[],
    },
    Case {
        name: "fanuc-g92-m5",
        dialect: "fanuc",
        args: &[],
        text: "(M20X1.5-6G)\nG97 S800 M3\nM5\nG0 X22 Z5\nG92 X19.4 Z-20 F1.5\nX18.9\nX18.5\nX18.16\nG0 X30\nM30\n",
        want: &[("control.spindle_stopped", 5)],
    },
    Case {
        name: "fanuc-g32-m5",
        dialect: "fanuc",
        args: &[],
        text: "(M20X1.5-6G)\nG97 S800 M5\nG0 X22 Z5\nX18.16\nG32 Z-20 F1.5\nG0 X22\nZ5\nM30\n",
        want: &[("control.spindle_stopped", 5)],
    },
    Case {
        name: "fanuc-g76-m5-then-m3",
        dialect: "fanuc",
        args: &[],
        text: "(M20X1.5-6G)\nG97 S800 M5\nM3\nG0 X22 Z5\nG76 P010060 Q100 R0.05\nG76 X18.16 Z-20 P920 Q300 F1.5\nM30\n",
        want: &[],
    },
    // The run-in (Fanuc's thread-cutting page: δ1 = t1·V·(−1 − ln a), V = S·L/60). Faced at
    // Z0, turned to Ø20, the passes start at Z1 less the first pass's flank shift 0.3·tan 30°
    // = 0.173: 0.827 mm of run-in. At S2500 and L1.5, V = 62.5 mm/s; with t1 = 0.033 s and
    // a = 0.01 the axis needs 0.033·62.5·3.6052 = 7.436 mm.
    Case {
        name: "fanuc-run-in-short",
        dialect: "fanuc",
        args: &[],
        text: "(M20X1.5-6G)\nG97 S2500 M3\nG0 X22 Z0\nG1 X-1 F0.2\nG0 X20 Z1\nG1 Z-25\nG0 X22 Z1\nG76 P010060 Q100 R0.05\nG76 X18.16 Z-20 P920 Q300 F1.5\nM30\n",
        want: &[("control.run_in_short", 9)],
    },
    // The same at S800 from Z5: V = 20 mm/s needs 2.380 mm; 4.827 mm are there.
    Case {
        name: "fanuc-run-in-enough",
        dialect: "fanuc",
        args: &[],
        text: "(M20X1.5-6G)\nG97 S800 M3\nG0 X22 Z0\nG1 X-1 F0.2\nG0 X20 Z1\nG1 Z-25\nG0 X22 Z5\nG76 P010060 Q100 R0.05\nG76 X18.16 Z-20 P920 Q300 F1.5\nM30\n",
        want: &[],
    },
    // No contour before the thread: where the part ends is not known, and nothing is said.
    Case {
        name: "fanuc-run-in-no-contour",
        dialect: "fanuc",
        args: &[],
        text: "(M20X1.5-6G)\nG97 S2500 M3\nG0 X22 Z1\nG76 P010060 Q100 R0.05\nG76 X18.16 Z-20 P920 Q300 F1.5\nM30\n",
        want: &[],
    },
    // ---- Fanuc machining centre: G84 (the tapping page: F is the feed in the feed mode in
    // force; in G94, S × lead; in G95, the lead).
    Case {
        name: "fanuc-mc-g84-pitch-under-g94",
        dialect: "fanuc",
        args: &[],
        text: "G17 G21 G90 G94\nT5 M6 (TAP M8X1.25)\nS600 M3\nG0 X0 Y0 Z5\nG84 Z-10 R2 F1.25\nG80\nM30\n",
        want: &[("post.tap_feed_convention", 5)],
    },
    Case {
        name: "fanuc-mc-g84-s-times-p-under-g95",
        dialect: "fanuc",
        args: &[],
        text: "G17 G21 G90 G95\nT5 M6 (TAP M8X1.25)\nS600 M3\nG0 X0 Y0 Z5\nG84 Z-10 R2 F750\nG80\nM30\n",
        want: &[("post.tap_feed_convention", 5)],
    },
    Case {
        name: "fanuc-mc-g84-right",
        dialect: "fanuc",
        args: &[],
        text: "G17 G21 G90 G94\nT5 M6 (TAP M8X1.25)\nS600 M3\nG0 X0 Y0 Z5\nG84 Z-10 R2 F750\nG80\nM30\n",
        want: &[],
    },
    // A feed that is neither the lead nor S × lead: the tapping check's feed fails, and no
    // convention is named.
    Case {
        name: "fanuc-mc-g84-feed-just-wrong",
        dialect: "fanuc",
        args: &[],
        text: "G17 G21 G90 G94\nT5 M6 (TAP M8X1.25)\nS600 M3\nG0 X0 Y0 Z5\nG84 Z-10 R2 F700\nG80\nM30\n",
        want: &[],
    },
    Case {
        name: "fanuc-mc-g84-f0",
        dialect: "fanuc",
        args: &[],
        text: "G17 G21 G90 G94\nT5 M6 (TAP M8X1.25)\nS600 M3\nG0 X0 Y0 Z5\nG84 Z-10 R2 F0\nG80\nM30\n",
        want: &[("post.feed_zero", 5)],
    },
    // A floating-holder G84 with M5: Fanuc's G84 page asks for the spindle turned by an M
    // code before the cycle.
    Case {
        name: "fanuc-mc-g84-m5",
        dialect: "fanuc",
        args: &[],
        text: "G17 G21 G90 G94\nT5 M6 (TAP M8X1.25)\nS600 M5\nG0 X0 Y0 Z5\nG84 Z-10 R2 F750\nG80\nM30\n",
        want: &[("control.spindle_stopped", 5)],
    },
    // Rigid tapping (M29 S): the cycle turns the spindle itself.
    Case {
        name: "fanuc-mc-rigid-m5",
        dialect: "fanuc",
        args: &[],
        text: "G17 G21 G90 G94\nT5 M6 (TAP M8X1.25)\nM5\nG0 X0 Y0 Z5\nM29 S600\nG84 Z-10 R2 F750\nG80\nM30\n",
        want: &[],
    },
    Case {
        name: "fanuc-mc-g84-s0",
        dialect: "fanuc",
        args: &[],
        text: "G17 G21 G90 G94\nT5 M6 (TAP M8X1.25)\nS0 M3\nG0 X0 Y0 Z5\nG84 Z-10 R2 F750\nG80\nM30\n",
        want: &[("control.spindle_speed_zero", 5)],
    },
    // ---- Haas machining centre: G84 starts the spindle itself ("it is not necessary to start
    // the spindle CW before this canned cycle").
    Case {
        name: "haas-g84-m5",
        dialect: "haas",
        args: &[],
        text: "G17 G20 G90 G94\nT5 M6 (TAP 5/16-18 UNC)\nS600 M5\nG0 X0 Y0 Z0.2\nG84 Z-0.5 R0.1 F33.3333\nG80\nM30\n",
        want: &[],
    },
    // 5/16-18: lead 1/18 in; under G94 F must be 600/18 = 33.3333 in/min; F0.0556 is the lead.
    Case {
        name: "haas-g84-lead-under-g94",
        dialect: "haas",
        args: &[],
        text: "G17 G20 G90 G94\nT5 M6 (TAP 5/16-18 UNC)\nS600 M3\nG0 X0 Y0 Z0.2\nG84 Z-0.5 R0.1 F0.05556\nG80\nM30\n",
        want: &[("post.tap_feed_convention", 5)],
    },
    // ---- Mitsubishi and Mazak lathes read G76 as Fanuc does.
    Case {
        name: "mitsubishi-g76-m5",
        dialect: "mitsubishi",
        args: &[],
        text: "(M20X1.5-6G)\nG97 S800 M5\nG0 X22 Z5\nG76 P010060 Q100 R0.05\nG76 X18.16 Z-20 P920 Q300 F1.5\nM30\n",
        want: &[("control.spindle_stopped", 5)],
    },
    Case {
        name: "mazak-g76-s0",
        dialect: "mazak",
        args: &[],
        text: "(M20X1.5-6G)\nG97 S0 M3\nG0 X22 Z5\nG76 P010060 Q100 R0.05\nG76 X18.16 Z-20 P920 Q300 F1.5\nM30\n",
        want: &[("control.spindle_speed_zero", 5)],
    },
    // ---- Sinumerik: CYCLE97 and G33 follow the spindle too.
    Case {
        name: "sinumerik-cycle97-m5",
        dialect: "sinumerik",
        args: &[],
        text: "; M20x2.5\nG97 S600 M5\nG0 X25 Z10\nCYCLE97(2.5,,0,-30,20,20,3,2,1.534,0.05,0,0,,1,1,)\nM30\n",
        want: &[("control.spindle_stopped", 4)],
    },
    Case {
        name: "sinumerik-cycle97-m3",
        dialect: "sinumerik",
        args: &[],
        text: "; M20x2.5\nG97 S600 M3\nG0 X25 Z10\nCYCLE97(2.5,,0,-30,20,20,3,2,1.534,0.05,0,0,,1,1,)\nM30\n",
        want: &[],
    },
    Case {
        name: "sinumerik-g33-s0",
        dialect: "sinumerik",
        args: &[],
        text: "; M20x1.5\nG97 S0 M3\nG0 X18.16 Z5\nG33 Z-20 K1.5\nG0 X22\nM30\n",
        want: &[("control.spindle_speed_zero", 4)],
    },
    // LinuxCNC has no peck tapping: a Q on G84 or G33.1 is refused (rs274: "Q word with no
    // G5, G10, … that uses it"); an F on G33.1 too ("F word used with a g33/g33.1").
    Case {
        name: "lc-g84-peck-q",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G17 G90 G94\n(M8x1.25 tap)\nM3 S500\nG0 X0 Y0 Z5\nG84 Z-10 R2 F625 Q2\nG80\nM2\n",
        want: &[("control.tap_peck_q", 5)],
    },
    Case {
        name: "lc-g33.1-peck-q",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G17 G90 G94\n(M8x1.25 tap)\nM3 S500\nG0 X0 Y0 Z5\nG33.1 Z-10 K1.25 Q2\nM2\n",
        want: &[("control.tap_peck_q", 5)],
    },
    Case {
        name: "lc-g33.1-f-word",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G17 G90 G94\n(M8x1.25 tap)\nM3 S500\nG0 X0 Y0 Z5\nG33.1 Z-10 K1.25 F100\nM2\n",
        want: &[("control.feed_word_in_sync", 5)],
    },
    Case {
        name: "lc-g84-dwell-p",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G17 G90 G94\n(M8x1.25 tap)\nM3 S500\nG0 X0 Y0 Z5\nG84 Z-10 R2 F625 P0.5\nG80\nM2\n",
        want: &[],
    },
    // ---- A thread mill's moves after its last helix (line 15). An M20x1.5-6H milled with a
    // Ø8 cutter on a radius 6 helix: its teeth reach 6 + 4 = 10 mm from the axis; the bore is
    // D1's middle, (18.376 + 18.676) / 2 = 18.526, its crest 9.263: 0.737 mm past it. A straight
    // retract along Z from there drags the teeth through the flanks (FreeCAD #7855); a circle in
    // the plane at the helix's radius cuts across the grooves; leaving toward the axis first is
    // safe.
    Case {
        name: "mill-retract-along-z",
        dialect: "fanuc",
        args: &[],
        text: "(M20X1.5-6H)\nG17 G21 G90 G40 G94\nT12 M6 (THREAD MILL D8)\nS3000 M3\nG0 X0 Y0 Z5\nG0 Z-16\nG1 X6 Y0 F100\nG3 X6 Y0 Z-14.5 I-6 J0\nG3 X6 Y0 Z-13 I-6 J0\nG3 X6 Y0 Z-11.5 I-6 J0\nG3 X6 Y0 Z-10 I-6 J0\nG3 X6 Y0 Z-8.5 I-6 J0\nG3 X6 Y0 Z-7 I-6 J0\nG3 X6 Y0 Z-5.5 I-6 J0\nG3 X6 Y0 Z-4 I-6 J0\nG0 Z5\nM30\n",
        want: &[("post.mill_gouge", 16)],
    },
    Case {
        name: "mill-return-circle",
        dialect: "fanuc",
        args: &[],
        text: "(M20X1.5-6H)\nG17 G21 G90 G40 G94\nT12 M6 (THREAD MILL D8)\nS3000 M3\nG0 X0 Y0 Z5\nG0 Z-16\nG1 X6 Y0 F100\nG3 X6 Y0 Z-14.5 I-6 J0\nG3 X6 Y0 Z-13 I-6 J0\nG3 X6 Y0 Z-11.5 I-6 J0\nG3 X6 Y0 Z-10 I-6 J0\nG3 X6 Y0 Z-8.5 I-6 J0\nG3 X6 Y0 Z-7 I-6 J0\nG3 X6 Y0 Z-5.5 I-6 J0\nG3 X6 Y0 Z-4 I-6 J0\nG2 X6 Y0 I-6 J0\nG1 X0 Y0\nG0 Z5\nM30\n",
        want: &[("post.mill_gouge", 16)],
    },
    Case {
        name: "mill-out-to-the-axis",
        dialect: "fanuc",
        args: &[],
        text: "(M20X1.5-6H)\nG17 G21 G90 G40 G94\nT12 M6 (THREAD MILL D8)\nS3000 M3\nG0 X0 Y0 Z5\nG0 Z-16\nG1 X6 Y0 F100\nG3 X6 Y0 Z-14.5 I-6 J0\nG3 X6 Y0 Z-13 I-6 J0\nG3 X6 Y0 Z-11.5 I-6 J0\nG3 X6 Y0 Z-10 I-6 J0\nG3 X6 Y0 Z-8.5 I-6 J0\nG3 X6 Y0 Z-7 I-6 J0\nG3 X6 Y0 Z-5.5 I-6 J0\nG3 X6 Y0 Z-4 I-6 J0\nG1 X0 Y0\nG0 Z5\nM30\n",
        want: &[],
    },
    // ---- A thread mill's return helix (line 16) on the same M20x1.5-6H, its teeth 0.737 mm
    // past the crest at radius 6. Back down along the thread's own helix (G2 falling, a right
    // hand, 1.5 mm a turn) it follows the groove; written with the other hand (G3 falling) it
    // drifts 2 × 1.5 = 3 mm off the groove in its turn; at 12 mm a turn (one G2 turn from Z-4 to
    // Z-16) it drifts 12 − 1.5 = 10.5 mm: both cut through the flanks (FreeCAD #7855).
    Case {
        name: "mill-return-helix-along-the-thread",
        dialect: "fanuc",
        args: &[],
        text: "(M20X1.5-6H)\nG17 G21 G90 G40 G94\nT12 M6 (THREAD MILL D8)\nS3000 M3\nG0 X0 Y0 Z5\nG0 Z-16\nG1 X6 Y0 F100\nG3 X6 Y0 Z-14.5 I-6 J0\nG3 X6 Y0 Z-13 I-6 J0\nG3 X6 Y0 Z-11.5 I-6 J0\nG3 X6 Y0 Z-10 I-6 J0\nG3 X6 Y0 Z-8.5 I-6 J0\nG3 X6 Y0 Z-7 I-6 J0\nG3 X6 Y0 Z-5.5 I-6 J0\nG3 X6 Y0 Z-4 I-6 J0\nG2 X6 Y0 Z-5.5 I-6 J0\nG1 X0 Y0\nG0 Z5\nM30\n",
        want: &[],
    },
    Case {
        name: "mill-return-helix-other-hand",
        dialect: "fanuc",
        args: &[],
        text: "(M20X1.5-6H)\nG17 G21 G90 G40 G94\nT12 M6 (THREAD MILL D8)\nS3000 M3\nG0 X0 Y0 Z5\nG0 Z-16\nG1 X6 Y0 F100\nG3 X6 Y0 Z-14.5 I-6 J0\nG3 X6 Y0 Z-13 I-6 J0\nG3 X6 Y0 Z-11.5 I-6 J0\nG3 X6 Y0 Z-10 I-6 J0\nG3 X6 Y0 Z-8.5 I-6 J0\nG3 X6 Y0 Z-7 I-6 J0\nG3 X6 Y0 Z-5.5 I-6 J0\nG3 X6 Y0 Z-4 I-6 J0\nG3 X6 Y0 Z-5.5 I-6 J0\nG1 X0 Y0\nG0 Z5\nM30\n",
        want: &[("post.mill_return_helix", 16)],
    },
    Case {
        name: "mill-return-helix-fast",
        dialect: "fanuc",
        args: &[],
        text: "(M20X1.5-6H)\nG17 G21 G90 G40 G94\nT12 M6 (THREAD MILL D8)\nS3000 M3\nG0 X0 Y0 Z5\nG0 Z-16\nG1 X6 Y0 F100\nG3 X6 Y0 Z-14.5 I-6 J0\nG3 X6 Y0 Z-13 I-6 J0\nG3 X6 Y0 Z-11.5 I-6 J0\nG3 X6 Y0 Z-10 I-6 J0\nG3 X6 Y0 Z-8.5 I-6 J0\nG3 X6 Y0 Z-7 I-6 J0\nG3 X6 Y0 Z-5.5 I-6 J0\nG3 X6 Y0 Z-4 I-6 J0\nG2 X6 Y0 Z-16 I-6 J0\nG1 X0 Y0\nG0 Z5\nM30\n",
        want: &[("post.mill_return_helix", 16)],
    },
    // ---- A tap a post wrote as a drilling cycle: the CAM tool list names T6 a tap. G81 leaves
    // the hole at rapid and G83 between its pecks, neither reversing the spindle (Fanuc's and
    // LinuxCNC's drilling cycles: the tap is torn out); G85 feeds out turning forward, which
    // only a self-reversing tapping head survives (a warning). LinuxCNC runs all of them: a
    // post's mistake, not a refusal (rs274 below). The drill T5 in G83 is no finding.
    Case {
        name: "fanuc-mc-tap-in-g81",
        dialect: "fanuc",
        args: &[],
        text: "G21 G17 G90 G94\n(T6 | M8X1.25 TAP | D=8.)\nT6 M6\nM3 S500\nG0 X0 Y0 Z5\nG81 Z-10 R2 F625\nG80\nM30\n",
        want: &[("post.tap_in_drill_cycle", 6)],
    },
    Case {
        name: "fanuc-mc-tap-in-g83-pecks",
        dialect: "fanuc",
        args: &[],
        text: "G21 G17 G90 G94\n(T5 | 6.8 DRILL | D=6.8)\n(T6 | M8X1.25 TAP | D=8.)\nT5 M6\nM3 S1500\nG0 X0 Y0 Z5\nG83 Z-15 R2 Q4 F150\nG80\nT6 M6\nM3 S500\nG0 X0 Y0 Z5\nG83 Z-10 R2 Q3 F625\nG80\nM30\n",
        want: &[("post.tap_in_drill_cycle", 12)],
    },
    Case {
        name: "fanuc-mc-tap-in-g85",
        dialect: "fanuc",
        args: &[],
        text: "G21 G17 G90 G94\n(T6 | M8X1.25 TAP | D=8.)\nT6 M6\nM3 S500\nG0 X0 Y0 Z5\nG85 Z-10 R2 F625\nG80\nM30\n",
        want: &[("post.tap_in_boring_cycle", 6)],
    },
    Case {
        name: "fanuc-mc-drill-then-tap",
        dialect: "fanuc",
        args: &[],
        text: "G21 G17 G90 G94\n(T5 | 6.8 DRILL | D=6.8)\n(T6 | M8X1.25 TAP | D=8.)\nT5 M6\nM3 S1500\nG0 X0 Y0 Z5\nG83 Z-15 R2 Q4 F150\nG80\nT6 M6\nM3 S500\nG0 X0 Y0 Z5\nG84 Z-10 R2 F625\nG80\nM30\n",
        want: &[],
    },
    Case {
        name: "lc-tap-in-g81",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G17 G90 G94\n(T6 | M8X1.25 TAP | D=8.)\nT6 M6\nM3 S500\nG0 X0 Y0 Z5\nG81 Z-10 R2 F625\nG80\nM2\n",
        want: &[("post.tap_in_drill_cycle", 6)],
    },
    Case {
        name: "lc-tap-in-g83-pecks",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G17 G90 G94\n(T6 | M8X1.25 TAP | D=8.)\nT6 M6\nM3 S500\nG0 X0 Y0 Z5\nG83 Z-10 R2 Q3 F625\nG80\nM2\n",
        want: &[("post.tap_in_drill_cycle", 6)],
    },
    // ---- A tapping cycle under G96: its S is a surface speed (150 m/min), and on the centre
    // line the spindle runs to its clamp (G50 S2000, LinuxCNC's D2000). LinuxCNC runs it
    // (rs274 below); Beckhoff's controls refuse it (20636); after G97 S500 it is the program's.
    Case {
        name: "fanuc-lathe-g84-under-g96",
        dialect: "fanuc",
        args: &[],
        text: "G21 G18 G90 G99\n(M8X1.25 TAP)\nT0606\nG50 S2000\nG96 S150 M3\nG0 X0 Z5\nG84 Z-10 R2 F1.25\nG80\nM30\n",
        want: &[("control.css_at_tap", 7)],
    },
    Case {
        name: "fanuc-lathe-g84-after-g97",
        dialect: "fanuc",
        args: &[],
        text: "G21 G18 G90 G99\n(M8X1.25 TAP)\nT0606\nG50 S2000\nG96 S150 M3\nG97 S500\nG0 X0 Z5\nG84 Z-10 R2 F1.25\nG80\nM30\n",
        want: &[],
    },
    Case {
        name: "lc-g33.1-under-g96",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G17 G90 G94\n(M8x1.25 tap)\nG96 S150 D2000 M3\nG0 X0 Y0 Z5\nG33.1 Z-10 K1.25\nM2\n",
        want: &[("control.css_at_tap", 5)],
    },
    Case {
        name: "lc-g84-under-g96-per-minute",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G17 G90 G94\n(M8x1.25 tap)\nG96 S150 D2000 M3\nG0 X0 Y0 Z5\nG84 Z-10 R2 F625\nG80\nM2\n",
        want: &[("control.css_at_tap", 5)],
    },
    // ---- Two findings in one program, in the report's order: the reader's (the tap moved
    // sideways) first, then the tapping cycles'.
    Case {
        name: "lc-two-taps-two-findings",
        dialect: "linuxcnc",
        args: &[],
        text: "G21 G17 G90 G94\n(M8x1.25 tap)\nM3 S500\nG0 X0 Y0 Z5\nG84 Z-10 R2 F0\nG80\nG0 X20 Y0 Z5\n(M8x1.25 tap)\nG33.1 X25 Z-10 K1.25\nM2\n",
        want: &[("post.tap_moves_sideways", 9), ("post.feed_zero", 5)],
    },
];

/// `verify --program --json` of a case: its exit code and report.
fn verify(c: &Case, extra: &[&str]) -> (i32, serde_json::Value) {
    let dir = tempdir("before-machine");
    let ext = if c.dialect == "linuxcnc" { "ngc" } else { "nc" };
    let file = dir.join(format!("{}.{ext}", c.name));
    std::fs::write(&file, c.text).unwrap();
    let mut args = vec!["verify", "--program", file.to_str().unwrap(), "--dialect", c.dialect, "--json", "-"];
    args.extend(c.args);
    args.extend(extra);
    let o = run_in(&dir, &args);
    assert!(matches!(o.status.code(), Some(0 | 1)), "{}: {}", c.name, stderr(&o));
    (o.status.code().unwrap(), serde_json::from_slice(&o.stdout).unwrap())
}

fn found(v: &serde_json::Value) -> Vec<(String, usize)> {
    v["control"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| (f["rule"].as_str().unwrap().to_string(), f["line"].as_u64().unwrap() as usize))
        .collect()
}

#[test]
fn each_program_gets_its_findings_at_their_lines() {
    assert!(CASES.len() >= 40, "{} programs", CASES.len());
    for c in CASES {
        let (code, v) = verify(c, &[]);
        let want: Vec<(String, usize)> = c.want.iter().map(|(r, l)| (r.to_string(), *l)).collect();
        assert_eq!(found(&v), want, "{}", c.name);
        let errors = v["control"].as_array().unwrap().iter().any(|f| f["level"] == "error");
        if errors {
            assert_eq!(v["verdict"], "fail", "{}: an error fails the program", c.name);
            assert_eq!(code, 1, "{}", c.name);
        }
    }
}

/// Every LinuxCNC program of the table, run by LinuxCNC's own interpreter: a finding with
/// LinuxCNC's words is a block `rs274` refuses with them, at its line; a program `rs274` runs
/// to its end carries no LinuxCNC words.
#[test]
fn linuxcnc_findings_agree_with_rs274() {
    let exe = crate::linuxcnc::rs274();
    let dir = crate::linuxcnc::rs274_dir("before-machine-rs274");
    // Tool 1 a turning tool with a 0.4 mm nose radius (diameter 0.8).
    let table: String =
        (1..=99).map(|i| format!("T{i} P{i} D{} ;\n", if i == 1 { "0.8" } else { "0" })).collect();
    std::fs::write(dir.join("tool.tbl"), table).unwrap();
    for c in CASES.iter().filter(|c| c.dialect == "linuxcnc") {
        let out = crate::linuxcnc::rs274_text(&exe, c.text, &dir);
        let (_, errors) = crate::linuxcnc::canon_calls(&out);
        let (_, v) = verify(c, &[]);
        let alarms: Vec<(String, usize)> = v["control"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|f| f["alarm"]["control"] == "LinuxCNC")
            .map(|f| (f["alarm"]["text"].as_str().unwrap().to_string(), f["line"].as_u64().unwrap() as usize))
            .collect();
        // rs274 prints its message, then the block it refused.
        let refused: Option<(String, String)> = errors
            .iter()
            .position(|e| !e.starts_with("executing"))
            .map(|i| (errors[i].clone(), errors.get(i + 1).cloned().unwrap_or_default()));
        match (alarms.first(), refused) {
            (None, None) => {}
            (Some((text, line)), Some((message, block))) => {
                assert_eq!(text, &message, "{}", c.name);
                let written = c.text.lines().nth(line - 1).unwrap();
                assert_eq!(block.trim(), written.trim(), "{}: rs274 refused another block", c.name);
            }
            (a, r) => panic!("{}: threadcheck's LinuxCNC words {a:?}, rs274's refusal {r:?}\n{out}", c.name),
        }
    }
}

#[test]
fn the_run_in_states_its_assumption_and_takes_the_machines_figure() {
    let c = CASES.iter().find(|c| c.name == "fanuc-run-in-short").unwrap();
    let (_, v) = verify(c, &[]);
    let f = &v["control"][0];
    assert_eq!(f["level"], "warning");
    // 0.033 · 2500 · 1.5 / 60 · (−1 − ln 0.01) = 7.436; the run-in 1 − 0.3·tan 30° = 0.827.
    let m = f["message"].as_str().unwrap();
    assert!(
        m.contains("starts at Z0.827, 0.83 mm before the part's end at Z0.000")
            && m.contains("needs 7.44 mm"),
        "{m}"
    );
    assert!(f["assumed"].as_str().unwrap().contains("0.033 s"), "{f}");
    // A warning leaves the verdict to the checks.
    assert_eq!(v["operations"][0]["verdict"], v["verdict"]);
    // A machine whose Z axis follows in 10 ms needs 0.01 · 62.5 · 3.6052 = 2.253 mm: a start
    // at Z3 (2.827 mm of run-in) is enough for it, not for the default.
    let dir = tempdir("servo");
    let machine = dir.join("lathe.toml");
    std::fs::write(&machine, "name = \"quick lathe\"\nservo_time_constant_s = 0.01\n").unwrap();
    let at_z3 = Case { text: c.text.replace("G0 X22 Z1\nG76", "G0 X22 Z3\nG76").leak(), ..*c };
    assert_eq!(found(&verify(&at_z3, &[]).1), vec![("control.run_in_short".to_string(), 9)]);
    let (_, quick) = verify(&at_z3, &["--machine", machine.to_str().unwrap()]);
    assert_eq!(found(&quick), vec![], "{}", quick["control"]);
}

#[test]
fn a_gouge_says_how_deep() {
    let c = CASES.iter().find(|c| c.name == "mill-retract-along-z").unwrap();
    let (_, v) = verify(c, &[]);
    let f = &v["control"][0];
    assert_eq!(f["made"], "milled");
    assert_eq!(f["code"], "G0");
    // 6 + 4 − 18.526 / 2 = 0.737 mm.
    assert!(
        f["message"].as_str().unwrap().contains("0.737 mm past the finished thread's crest"),
        "{}",
        f["message"]
    );
}

#[test]
fn the_feed_convention_names_the_factor() {
    let c = CASES.iter().find(|c| c.name == "fanuc-mc-g84-pitch-under-g94").unwrap();
    let (_, v) = verify(c, &[]);
    let m = v["control"][0]["message"].as_str().unwrap();
    // S × lead = 600 × 1.25 = 750 mm/min; F1.25 is 600 times too slow.
    assert!(m.contains("600 × 1.25 = 750 mm/min") && m.contains("600 times too slowly"), "{m}");
}

#[test]
fn findings_reach_sarif_with_their_levels_and_text_with_their_lines() {
    let dir = tempdir("before-machine-sarif");
    for name in ["lc-g33.1-x-move", "fanuc-run-in-short", "fanuc-mc-tap-in-g85", "fanuc-lathe-g84-under-g96"]
    {
        let c = CASES.iter().find(|c| c.name == name).unwrap();
        std::fs::write(
            dir.join(format!("{name}.{}", if c.dialect == "linuxcnc" { "ngc" } else { "nc" })),
            c.text,
        )
        .unwrap();
    }
    let o = run_in(&dir, &["verify", ".", "--format", "sarif", "--dialect", "fanuc"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let results = v["runs"][0]["results"].as_array().unwrap();
    let run_in = results.iter().find(|r| r["ruleId"] == "control.run_in_short").expect("the run-in warning");
    assert_eq!(run_in["level"], "warning");
    assert_eq!(run_in["locations"][0]["physicalLocation"]["region"]["startLine"], 9);
    // Each rule at its own level and line: the tap in G85 a warning at line 6, the tap under
    // G96 an error at line 7.
    for (rule, level, line) in
        [("post.tap_in_boring_cycle", "warning", 6), ("control.css_at_tap", "error", 7)]
    {
        let r = results.iter().find(|r| r["ruleId"] == rule).unwrap_or_else(|| panic!("no {rule}"));
        assert_eq!(r["level"], level, "{r}");
        assert_eq!(r["locations"][0]["physicalLocation"]["region"]["startLine"], line, "{r}");
    }
    let rules = v["runs"][0]["tool"]["driver"]["rules"].as_array().unwrap();
    let rule = rules.iter().find(|r| r["id"] == "control.run_in_short").unwrap();
    assert!(rule["shortDescription"]["text"].as_str().unwrap().contains("synchronised feed"), "{rule}");
    // The text report: a section of its own, the verdict naming it.
    let c = CASES.iter().find(|c| c.name == "lc-g33.1-x-move").unwrap();
    let file = dir.join("side.ngc");
    std::fs::write(&file, c.text).unwrap();
    let o = run(&["verify", "--program", file.to_str().unwrap(), "--dialect", "linuxcnc"]);
    let text = stdout(&o);
    assert!(text.contains("== before the machine: 1 error, 0 warnings"), "{text}");
    assert!(text.contains("✗ line 5 (G33.1): the tap moves X from 0 to 5"), "{text}");
    assert!(text.contains("program verdict: FAIL (before the machine: 1 error)"), "{text}");
    assert_eq!(o.status.code(), Some(1));
}

/// The schema's list of rules is the code's.
#[test]
fn the_schema_lists_every_rule() {
    let schema: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/json-schema.json"),
        )
        .unwrap(),
    )
    .unwrap();
    let listed: Vec<&str> = schema["$defs"]["control_finding"]["properties"]["rule"]["enum"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r.as_str().unwrap())
        .collect();
    let code: Vec<&str> = threadcheck::ControlRule::ALL.iter().map(|r| r.id()).collect();
    assert_eq!(listed, code);
    // And the guide names each.
    let guide = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/guide/before-the-machine.md"),
    )
    .unwrap();
    for id in code {
        assert!(guide.contains(&format!("`{id}`")), "docs/guide/before-the-machine.md does not name {id}");
    }
}

/// The guide's example is what the binary prints: its text block, line for line, in the output
/// of its command (run from the repository's root, as the guide says).
#[test]
fn the_guide_shows_what_the_binary_prints() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let guide = std::fs::read_to_string(root.join("docs/guide/before-the-machine.md")).unwrap();
    let block = |fence: &str| -> String {
        let start = guide.find(fence).unwrap() + fence.len();
        guide[start..].split("```").next().unwrap().trim().to_string()
    };
    let command = block("```sh\n");
    let args: Vec<&str> = command.split_whitespace().skip(1).collect();
    let o = run_in(root, &args);
    let out = stdout(&o);
    for line in block("```text\n").lines() {
        assert!(out.contains(line), "the guide shows {line:?}; threadcheck {command} prints:\n{out}");
    }
}

/// A tap's S × lead against the machine's fastest feed: M8x1.25 at S600 is 750 mm/min, over
/// the 500 the slow machine's axes follow (at most S400 for this lead); at S400, 500 mm/min,
/// a limit exactly met passes. Without the machine file nothing is said.
#[test]
fn a_tap_faster_than_the_axes_follow() {
    let machine = data("programs/control/slow-axes.toml");
    let m = machine.to_str().unwrap();
    let c = CASES.iter().find(|c| c.name == "fanuc-mc-g84-right").unwrap();
    let (code, v) = verify(c, &["--machine", m]);
    assert_eq!(found(&v), vec![("control.sync_feed_limit".to_string(), 5)]);
    assert_eq!(code, 1);
    let msg = v["control"][0]["message"].as_str().unwrap();
    assert!(
        msg.contains(
            "S600 × lead 1.25 = 750 mm/min, beyond the fastest feed the axes follow, 500 mm/min (slow axes"
        ),
        "{msg}"
    );
    assert!(msg.contains("at most S400"), "{msg}");
    let at_400 = Case { text: c.text.replace("S600", "S400").replace("F750", "F500").leak(), ..*c };
    assert_eq!(found(&verify(&at_400, &["--machine", m]).1), vec![]);
    assert_eq!(found(&verify(c, &[]).1), vec![]);
}

/// The tap's holder from the machine file: M8x1.25 at S600 wants F750 (S × lead). F727.5 is
/// 3 % under it: a rigid holder (the default, said) takes up nothing and fails it; a floating
/// (tension-compression) holder takes up to 5 %, down to 750 × 0.95 = 712.5, and passes it,
/// said; F705 (6 % under) fails either way, and F751 (over) too.
#[test]
fn a_floating_holder_takes_up_a_small_under_feed() {
    let dir = tempdir("holder");
    let floating = dir.join("floating.toml");
    std::fs::write(&floating, "name = \"vmc\"\ntype = \"mill\"\ntap_holder = \"floating\"\n").unwrap();
    let rigid = dir.join("rigid.toml");
    std::fs::write(&rigid, "name = \"vmc\"\ntype = \"mill\"\ntap_holder = \"rigid\"\n").unwrap();
    let base = CASES.iter().find(|c| c.name == "fanuc-mc-g84-right").unwrap();
    let feed = |f: &str, machine: Option<&std::path::Path>| {
        let c = Case { text: base.text.replace("F750", f).leak(), ..*base };
        let extra: Vec<&str> = machine.map_or(vec![], |m| vec!["--machine", m.to_str().unwrap()]);
        let (_, v) = verify(&c, &extra);
        let op = &v["operations"][0];
        let check = op["checks"].as_array().unwrap().iter().find(|k| k["feature"] == "feed").unwrap().clone();
        let notes: Vec<String> =
            op["notes"].as_array().unwrap().iter().map(|n| n.as_str().unwrap().to_string()).collect();
        (check, notes)
    };
    let (k, notes) = feed("F727.5", None);
    assert_eq!(k["ok"], false);
    assert!(notes.iter().any(|n| n.contains("3.0 % under the lead: a rigid holder is assumed")), "{notes:?}");
    let (k, _) = feed("F727.5", Some(&rigid));
    assert_eq!((k["ok"].clone(), k["deviation"].clone()), (false.into(), (-22.5).into()));
    let (k, notes) = feed("F727.5", Some(&floating));
    assert_eq!(
        (k["ok"].clone(), k["min"].clone(), k["max"].clone()),
        (true.into(), 712.5.into(), 750.0.into())
    );
    assert!(notes.iter().any(|n| n.contains("3.0 % under the lead: the floating")), "{notes:?}");
    // 705 − 712.5 = −7.5 mm/min past the floating holder's limit.
    let (k, _) = feed("F705", Some(&floating));
    assert_eq!((k["ok"].clone(), k["deviation"].clone()), (false.into(), (-7.5).into()));
    let (k, _) = feed("F751", Some(&floating));
    assert_eq!((k["ok"].clone(), k["deviation"].clone()), (false.into(), 1.0.into()));
    // The limit exactly met passes.
    let (k, _) = feed("F712.5", Some(&floating));
    assert_eq!(k["ok"], true);
}

/// The Z axis's acceleration from the machine file: at S2500 × lead 1.5 the feed is
/// V = 62.5 mm/s. At 2000 mm/s² the ramp takes 62.5² / 4000 = 0.98 mm, less than the servo's
/// 7.44 mm: the servo's figure stands, and the assumption now names only t1. At 200 mm/s² it
/// takes 62.5² / 400 = 9.77 mm, which the finding then asks for.
#[test]
fn the_run_in_takes_the_axis_acceleration() {
    let c = CASES.iter().find(|c| c.name == "fanuc-run-in-short").unwrap();
    let (_, v) = verify(c, &[]);
    let assumed = v["control"][0]["assumed"].as_str().unwrap();
    assert!(assumed.contains("acceleration not limited"), "{assumed}");
    let dir = tempdir("acceleration");
    let at = |a: &str| {
        let m = dir.join(format!("lathe-{a}.toml"));
        std::fs::write(&m, format!("name = \"lathe\"\nz_acceleration_mm_s2 = {a}\n")).unwrap();
        verify(c, &["--machine", m.to_str().unwrap()]).1["control"][0].clone()
    };
    let f = at("2000");
    assert!(f["message"].as_str().unwrap().contains("needs 7.44 mm to reach"), "{f}");
    assert!(!f["assumed"].as_str().unwrap().contains("acceleration"), "{f}");
    let f = at("200");
    let m = f["message"].as_str().unwrap();
    assert!(m.contains("needs 9.77 mm to accelerate to the threading feed at its 200 mm/s²"), "{m}");
    assert!(m.contains("start the passes 9.77 mm or more"), "{m}");
}

/// A return helix's finding says how far it drifts and how deep its teeth reach: the other
/// hand drifts 1.5 + 1.5 = 3 mm in its turn; the teeth reach 6 + 4 − 18.526 / 2 = 0.737 mm
/// past the crest.
#[test]
fn a_return_helix_says_its_hand_and_drift() {
    let c = CASES.iter().find(|c| c.name == "mill-return-helix-other-hand").unwrap();
    let (code, v) = verify(c, &[]);
    assert_eq!(code, 1);
    let m = v["control"][0]["message"].as_str().unwrap();
    assert!(m.contains("is a left-hand helix on a right-hand thread"), "{m}");
    assert!(
        m.contains("drifts 3.000 mm off the groove") && m.contains("0.737 mm past the thread's crest"),
        "{m}"
    );
    let c = CASES.iter().find(|c| c.name == "mill-return-helix-fast").unwrap();
    let m = verify(c, &[]).1["control"][0]["message"].as_str().unwrap().to_string();
    // Z-4 to Z-16 in one clockwise turn: 12 mm a turn, 12 − 1.5 = 10.5 mm off the groove.
    assert!(m.contains("moves 12 mm per revolution where the thread's lead is 1.5 mm"), "{m}");
    assert!(m.contains("drifts 10.500 mm"), "{m}");
}

/// A program whose only thread is a tap a post wrote as a peck drilling cycle fails a run of
/// many programs too (it was counted as no operation and passed the run): its own line in the
/// text, the JSON Lines and SARIF, at the cycle's line.
#[test]
fn a_tap_in_a_drilling_cycle_fails_a_run_of_many() {
    let dir = tempdir("tap-in-drill-batch");
    std::fs::copy(data("programs/control/tap-in-peck-cycle.nc"), dir.join("flange.nc")).unwrap();
    let o = run_in(&dir, &["verify", "."]);
    assert_eq!(o.status.code(), Some(1), "{}", stdout(&o));
    let text = stdout(&o);
    assert!(
        text.contains("flange.nc:17: FAIL tapped —: before the machine: post.tap_in_drill_cycle"),
        "{text}"
    );
    assert!(text.contains("1 program read, 1 operation: 0 pass, 1 fail"), "{text}");
    let o = run_in(&dir, &["verify", ".", "--format", "sarif"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let r = &v["runs"][0]["results"][0];
    assert_eq!((r["ruleId"].as_str(), r["level"].as_str()), (Some("post.tap_in_drill_cycle"), Some("error")));
    assert_eq!(r["locations"][0]["physicalLocation"]["region"]["startLine"], 17);
}

/// A run of many programs names a warning on its operation's line of text, as its JSON Lines and
/// SARIF do (the text named failures only; a warning does not fail the operation): the run-in
/// 0.827 mm against 7.436 mm needed at S2500 (above), and nothing where 4.827 mm stand against
/// 2.380 mm at S800.
#[test]
fn a_run_of_many_names_each_warning_in_its_text() {
    let dir = tempdir("before-machine-text");
    for (name, file) in [("fanuc-run-in-short", "short.nc"), ("fanuc-run-in-enough", "enough.nc")] {
        let c = CASES.iter().find(|c| c.name == name).unwrap();
        std::fs::write(dir.join(file), c.text).unwrap();
    }
    let o = run_in(&dir, &["verify", "."]);
    let text = stdout(&o);
    let line =
        |file: &str| text.lines().find(|l| l.contains(file)).unwrap_or_else(|| panic!("{text}")).to_string();
    assert!(line("short.nc").ends_with("; warning before the machine: control.run_in_short"), "{text}");
    assert!(!line("enough.nc").contains("warning"), "{text}");
}
