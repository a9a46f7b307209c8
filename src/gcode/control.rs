//! What the control will refuse and what a post is known to get wrong, as a program shows it
//! (issue 63): the rules, their levels, and each control's own message for a rule where the
//! control publishes one — a dialect's facts, in one table ([`alarm`]), as rs274ngc keeps its
//! errors. The reader records what only it sees ([`ControlEvent`]: cutter compensation in force
//! at a synchronised cut, a tap that moves sideways) and reads on; `analysis::control` adds what
//! the operations show (the spindle, the feed) and turns both into findings.

use super::Dialect;
use serde::Serialize;

/// How much a finding weighs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Level {
    /// The control refuses the block, or the cut breaks the tool or scraps the part: the
    /// program fails.
    Error,
    /// The control runs it and the thread suffers: said, and the program's verdict is its
    /// checks'.
    Warning,
}

/// A rule: something a control refuses or a post is known to get wrong.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ControlRule {
    /// A threading move (G33, G76) under cutter radius compensation (G41/G42).
    SyncUnderCompensation,
    /// A synchronised tap (LinuxCNC's G33.1) that moves in X or Y as it feeds.
    TapMovesSideways,
    /// A threading operation or a tapping cycle that needs the spindle turning, with M5 in force.
    SpindleStopped,
    /// S0 in force at a threading operation or a tapping cycle.
    SpindleSpeedZero,
    /// F0 (or K0) at a tapping cycle.
    FeedZero,
    /// A tap's feed written in the other feed mode's convention: the lead under a per-minute
    /// mode, or S × lead under a per-revolution mode.
    TapFeedConvention,
    /// A threading pass that starts too close to the part for the axis to reach the
    /// synchronised feed: the first threads' lead is short.
    RunInShort,
    /// A peck depth Q on a tapping cycle of a control that has no peck tapping.
    TapPeckQ,
    /// An F word on a spindle-synchronised move (LinuxCNC's G33.1), whose feed is its K.
    FeedWordInSync,
    /// A thread mill's move after its last helix that cuts the finished thread.
    MillGouge,
    /// A tap's synchronised feed, S × lead, beyond the fastest feed the machine's axes follow.
    SyncFeedLimit,
    /// A thread mill's helix that crosses the thread's grooves instead of following them: a
    /// return helix of the other hand or another lead, its teeth in the thread.
    MillReturnHelix,
    /// A tapping cycle under G96 (constant surface speed): its S is a surface speed, and the
    /// spindle runs at whatever the diameter makes of it (at the centre, the clamp).
    CssAtTap,
    /// A tap in a drilling cycle that retracts at rapid or with the spindle stopped (G73,
    /// G81–G83, G86–G88): the tap is pulled out without reversing.
    TapInDrillCycle,
    /// A tap in a boring cycle that feeds out with the spindle still turning forward (G85,
    /// G89): only a self-reversing tapping head survives it.
    TapInBoringCycle,
}

impl ControlRule {
    /// Every rule, in the order the reports list them.
    pub const ALL: [ControlRule; 15] = [
        ControlRule::SpindleStopped,
        ControlRule::SpindleSpeedZero,
        ControlRule::FeedZero,
        ControlRule::CssAtTap,
        ControlRule::SyncUnderCompensation,
        ControlRule::TapPeckQ,
        ControlRule::FeedWordInSync,
        ControlRule::TapMovesSideways,
        ControlRule::TapFeedConvention,
        ControlRule::TapInDrillCycle,
        ControlRule::TapInBoringCycle,
        ControlRule::MillGouge,
        ControlRule::MillReturnHelix,
        ControlRule::SyncFeedLimit,
        ControlRule::RunInShort,
    ];

    /// The rule's id (SARIF's `ruleId`, the JSON's `rule`): `control.` what the control
    /// refuses or runs badly, `post.` what a post wrote wrong.
    pub fn id(self) -> &'static str {
        match self {
            ControlRule::SyncUnderCompensation => "control.sync_under_compensation",
            ControlRule::TapMovesSideways => "post.tap_moves_sideways",
            ControlRule::SpindleStopped => "control.spindle_stopped",
            ControlRule::SpindleSpeedZero => "control.spindle_speed_zero",
            ControlRule::FeedZero => "post.feed_zero",
            ControlRule::TapFeedConvention => "post.tap_feed_convention",
            ControlRule::RunInShort => "control.run_in_short",
            ControlRule::TapPeckQ => "control.tap_peck_q",
            ControlRule::FeedWordInSync => "control.feed_word_in_sync",
            ControlRule::MillGouge => "post.mill_gouge",
            ControlRule::SyncFeedLimit => "control.sync_feed_limit",
            ControlRule::MillReturnHelix => "post.mill_return_helix",
            ControlRule::CssAtTap => "control.css_at_tap",
            ControlRule::TapInDrillCycle => "post.tap_in_drill_cycle",
            ControlRule::TapInBoringCycle => "post.tap_in_boring_cycle",
        }
    }

    /// Its level.
    pub fn level(self) -> Level {
        match self {
            ControlRule::RunInShort | ControlRule::TapInBoringCycle => Level::Warning,
            _ => Level::Error,
        }
    }

    /// What the rule checks, in one sentence (SARIF's rule description).
    pub fn what(self) -> &'static str {
        match self {
            ControlRule::SyncUnderCompensation => {
                "A threading move under cutter radius compensation (G41/G42): LinuxCNC refuses it."
            }
            ControlRule::TapMovesSideways => {
                "A synchronised tap that moves in X or Y as it feeds: the tap is dragged sideways and breaks (preposition X and Y, give only Z)."
            }
            ControlRule::SpindleStopped => {
                "A threading operation or tapping cycle with the spindle stopped (M5): the synchronised feed waits for a spindle that does not turn, or the tap is pushed in without turning."
            }
            ControlRule::SpindleSpeedZero => {
                "S0 in force at a threading operation or tapping cycle: the spindle does not turn."
            }
            ControlRule::FeedZero => {
                "F0 (or K0) at a tapping cycle: the control refuses a zero feed, or the tap does not advance."
            }
            ControlRule::TapFeedConvention => {
                "A tap's feed written in the other feed mode's convention (the lead under G94, S × lead under G95): the tap is fed hundreds of times too slow or too fast."
            }
            ControlRule::RunInShort => {
                "A threading pass that starts closer to the part than the axis needs to reach the synchronised feed: the first threads' lead is short."
            }
            ControlRule::TapPeckQ => {
                "A peck depth Q on a tapping cycle of a control that has no peck tapping (LinuxCNC's G84, G74 and G33.1): the control refuses the word."
            }
            ControlRule::FeedWordInSync => {
                "An F word on a spindle-synchronised move (LinuxCNC's G33.1, whose feed is K): the control refuses it."
            }
            ControlRule::SyncFeedLimit => {
                "A tap's synchronised feed, S × lead, beyond the fastest feed the machine's axes follow (its machine file's max_feed_mm_min): the axis lags the spindle and the tap strips its thread or breaks."
            }
            ControlRule::MillGouge => {
                "A thread mill's move after its last helix (a retract along Z, a return circle, a move across the grooves) whose teeth reach past the finished thread's crest: it cuts the thread just made."
            }
            ControlRule::MillReturnHelix => {
                "A thread mill's helix that crosses the thread's grooves instead of following them (a return helix written with the other hand, or at another lead) with its teeth in the thread: it cuts through the flanks."
            }
            ControlRule::CssAtTap => {
                "A tapping cycle under G96 (constant surface speed): its S is a surface speed, so the tap turns at what the diameter makes of it (on the centre line, the spindle's clamp) and a feed per minute no longer matches it; Beckhoff's controls refuse it (20636)."
            }
            ControlRule::TapInDrillCycle => {
                "A tap (the tool table's, or a CAM tool list's) in a drilling cycle that leaves the hole at rapid or with the spindle stopped (G73, G81, G82, G83, G86, G87, G88): the tap is pulled out without reversing and strips the thread or breaks; tap with G84 (G74 left-hand)."
            }
            ControlRule::TapInBoringCycle => {
                "A tap in a boring cycle that feeds out of the hole with the spindle still turning forward (G85, G89): only a self-reversing tapping head survives it; a plain tap strips the thread."
            }
        }
    }
}

/// A control's own message for a rule: its control, number (where it has one) and words, with
/// where they are published.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Alarm {
    /// The control (`LinuxCNC`).
    pub control: &'static str,
    /// Its number, where the control numbers its messages.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub number: Option<&'static str>,
    /// Its words, as the control prints them.
    pub text: &'static str,
    /// Where they are published.
    pub source: &'static str,
}

/// LinuxCNC's interpreter, `rs274` (linuxcnc-uspace 2.9): its messages, checked by running it
/// (tests/control.rs runs every LinuxCNC program of the rules through it).
const RS274: &str = "LinuxCNC's interpreter rs274 (2.9), its interp_convert.cc";

/// The control's own message for `rule` at the cycle `code` (`G84`, `G76`), where the control
/// of `dialect` publishes one; `None` where it publishes none (the finding then names no
/// number) or runs the block.
pub fn alarm(dialect: Dialect, rule: ControlRule, code: &str) -> Option<Alarm> {
    let linuxcnc =
        |text: &'static str| Some(Alarm { control: "LinuxCNC", number: None, text, source: RS274 });
    match (dialect, rule, code) {
        // G76 checks for compensation first (its interp_check); a G33 meets the compensation
        // code, which takes G0 and G1 only, when the tool has a radius (with none, it runs).
        (Dialect::LinuxCnc, ControlRule::SyncUnderCompensation, "G76") => {
            linuxcnc("Cannot use G76 threading cycle with cutter radius compensation on")
        }
        (Dialect::LinuxCnc, ControlRule::SyncUnderCompensation, _) => linuxcnc("Bug code not g0 or g1"),
        (Dialect::LinuxCnc, ControlRule::FeedZero, "G84" | "G74") => {
            linuxcnc("Cannot feed with zero feed rate")
        }
        (Dialect::LinuxCnc, ControlRule::TapPeckQ, _) => linuxcnc(
            "Q word with no G5, G10, G64, G73, G76, G83, M19, M66, M67, M68 or user M code that uses it",
        ),
        (Dialect::LinuxCnc, ControlRule::FeedWordInSync, _) => linuxcnc("F word used with a g33/g33.1"),
        _ => None,
    }
}

/// What the reader saw of a rule at a block, reading on.
#[derive(Clone, Debug, PartialEq)]
pub struct ControlEvent {
    /// The rule.
    pub rule: ControlRule,
    /// The code of the block (`G76`, `G33.1`).
    pub code: String,
    /// Its line and column.
    pub line: usize,
    /// Its column.
    pub column: usize,
    /// The subprogram file it stands in, when not the program's own.
    pub file: Option<String>,
    /// What exactly, in words (`the tap moves from X0 Y0 to X5 Y0`).
    pub detail: String,
}
