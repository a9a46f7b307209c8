//! # threadcheck
//!
//! Tells a machinist, before any metal is cut, what thread a CNC lathe program will produce and
//! whether that thread meets its standard.
//!
//! The source follows the path the data takes, one private folder per step, and this crate
//! root re-exports what a program needs, flat:
//!
//! 1. standards: a designation (`M10x1.5-6g`, [`parse_designation`]) becomes a
//!    [`BasicThread`] and its classes, and [`limits_for`] their limits of size;
//! 2. toolpaths: a generated plan ([`PlanSpec`]) or a real program read as the control expands
//!    it ([`read_program`]) says where the tip runs, pass after pass ([`Pass`]);
//! 3. geometry: the [`Insert`] is placed once per lead for every pass; the cut surface is the
//!    lower envelope of the imprints, or their polygon union ([`UnionStrategy`]), subtracted from
//!    the blank ([`sweep`]); the as-cut groove is measured as a metrology lab would
//!    ([`measure`]);
//! 4. analysis: the measurements against the limits ([`checks`]) and the verdict, the whole
//!    path as one call ([`verify`], [`verify_program`]), and the studies built on it
//!    ([`compare`], [`fit`], [`mill`], [`run_catalogue`]);
//! 5. report: text, JSON, SVG and HTML of those results;
//! 6. commands: each command's arguments, read by the command line and by the API and Python
//!    ([`Command`], [`VerifyArgs`], …), its job, and the one writer of its documents
//!    ([`deliver`]).
//!
//! ```
//! use threadcheck::Insert;
//! use threadcheck::{measure, MeasureSetup};
//! use threadcheck::{Infeed, PlanSpec};
//! use threadcheck::{sweep, SweepSetup, Window};
//! use threadcheck::{parse_designation, ParseOptions, ThreadKind, UnionStrategy};
//!
//! let m10 = parse_designation("M10x1.5", ParseOptions::default())?.thread;
//! // A 60° partial-profile insert with a 0.04 mm tip, arcs to 0.05 µm.
//! let insert = Insert::partial_for(&m10, 0.04, 5e-5)?;
//! // Its depth for the basic pitch diameter is 7H/8 − r below the crest line.
//! let h = m10.fundamental_height();
//! let final_x = 10.0 - 2.0 * (7.0 * h / 8.0 - 0.04);
//! // Eight constant-area passes, modified flank infeed, one spring pass.
//! let passes = PlanSpec {
//!     infeed: Infeed::Flank { angle: 29.5 }, spring: 1, z_start: 2.0, length: 20.0,
//!     ..PlanSpec::new(ThreadKind::External, 1.5, 9.85, final_x, 8)
//! }.generate()?;
//! let setup = SweepSetup { kind: ThreadKind::External, insert: &insert, blank_diameter: 9.85, pitch: 1.5 };
//! let groove = passes.last().unwrap().z_start - 2.0; // where the last pass's groove sits near z = 0
//! let cut = sweep(&setup, &passes, Window::around(groove, 1.5, 4.0), UnionStrategy::BalancedTree)?;
//! let ms = MeasureSetup { thread: &m10, kind: ThreadKind::External, mmc_pitch_diameter: None, mmc_major_diameter: None, extras: true };
//! let m = measure(&ms, &cut.section.profile(), groove)?;
//! println!("d2 = {:.4} mm", m.pitch_diameter);
//! assert!((m.pitch_diameter - 9.0257).abs() < 1e-4); // basic d2 = d − 0.649519·P
//! # Ok::<(), threadcheck::Error>(())
//! ```
//!
//! All lengths are millimetres (`f64`). Lathe X values are **diameters**; geometry works in the
//! axial half-plane with `(z, r)` where `r` is a radius. Deviations are reported in µm.

// The wings, in the order the data flows; each imports only the wings above it in this list.
mod analysis;
mod commands;
mod gcode;
mod geometry;
mod ground;
mod lsp;
mod report;
mod serve;
mod standards;
mod toolpath;

// Ground: the error, the plane's value types.
pub use ground::cancel::{check as check_cancelled, Cancel};
pub use ground::error::{one_line, Audience, CliFlags, Error, Result};
pub use ground::fmt::{path_name, shown_text};
pub use ground::note::{Marked, Note, NoteKind, Place};
pub use ground::plane::{Arc, Point, DEFAULT_TOLERANCE, MIN_TOLERANCE};

// Standards: designations, forms, classes and their limits of size.
pub use standards::drills::{drill_that_passes, inch_drill, DrillSource, PassingDrill};
pub use standards::tolerance::Resolution;
pub use standards::tolerance::{
    iso_limits, limits_for, AcmeClass, Bs84Class, CoatingLimits, GaugePlane, Iso228Class, IsoClass, Limit,
    TaperClass, ThreadLimits, TrClass, UnifiedClass, UnifiedSeries,
};
pub use standards::torque::{
    material as torque_material, tapping_torque, Material, MaterialGroup, TapKind, MATERIALS,
};
pub use standards::{
    catalog, parse_designation, BasicThread, Catalog, ClassSpec, Designation, DesignationError, Hand,
    ParseOptions, ProfileKind, ThreadForm, ThreadKind, MM_PER_INCH,
};
pub use standards::{Feature, GrooveForm};

// Programs read as a control would.
pub use gcode::{
    alarm, comments, read_program, read_program_streaming, read_program_with, rewrite_words, Budget, Comment,
    DepthWord, Dialect, DialectFrom, GCodeSystem, HoleCycle, HoleKind, LinuxCncRelease, MachineReading,
    MachineType, Operation, PassXWord, Program, ProgramUnits, RadialPlace, ReadOptions, Spindle, SpindleDir,
    SubFinder, WordEdit, WordForm, WordMeans, XWords,
};
pub use gcode::{Alarm, ControlEvent, ControlRule, Facts, Level, PROGRAM_EXTENSIONS};

// Toolpaths: passes, generated plans, infeeds and depth schedules.
pub use toolpath::passes::{Infeed, InfeedChoice, Pass, PlanSpec, Schedule};

// Geometry: the insert, the sweep, the measurement.
pub use geometry::boolean::UnionStrategy;
pub use geometry::forming::{blank_for_crest, formed_minor, rolled_major, FormProfile, Formed, Rolled};
pub use geometry::helix::{Cutter, Helix};
pub use geometry::insert::{Insert, InsertKind};
pub use geometry::measure::{
    measure, over_wires, DeviationSample, MeasureSetup, Measurement, ProfileRegion, ThreeWire,
};
pub use geometry::parry::Placement;
pub use geometry::sweep::{pass_metrics, sweep, PassMetrics, Section, Sweep, SweepSetup, Window};
pub use geometry::wire::{classical_wire_helix_term, wire_helix_term};

// The computations.
pub use analysis::check::{checks, Check, CheckFeature, CheckKind, CheckUnit, Verdict};
pub use analysis::control::{before_machine, ControlFinding};
pub use analysis::fusion::tool_table as fusion_tool_table;
pub use analysis::mill::{mill, MillReport, MillSpec, Target};
pub use analysis::naming::{
    designation_in_comment, drill_in_comment, infer_designation, listed_tool, thread_mill_in_comment,
    DesignationFrom, Found, ListedKind, ListedTool, MillInComment, Named,
};
pub use analysis::percent::{thread_percent, ThreadPercent, THREAD_PERCENT_BAND};
pub use analysis::picture::{Cut, Deviation, Picture};
pub use analysis::process::MachineProfile;
pub use analysis::program::{verify_program, verify_whole, Milled, Process, ProgramVerification};
pub use analysis::rolled::{rolled_thread, RolledThread};
pub use analysis::study::capability::{
    capability, CapabilityReport, CapabilitySpec, Histogram, SizeCapability,
};
pub use analysis::study::compare::{compare, CompareChoice, Comparison, Ground, Recommendation};
pub use analysis::study::correct::{
    correct, CorrectReport, CorrectSpec, GaugeResult, Measured, MeasuredState, Pickup, WearOffset,
    WireReading,
};
pub use analysis::study::fit::{fit, FitReport, FitSide, FitSpec, FitVerdict};
pub use analysis::study::sweep::{cases as catalogue_cases, run as run_catalogue, Case, CatalogueSpec};
pub use analysis::tap::{tap, TapCheck, TapFeature, TapReport, TapSpec, TappedHole};
pub use analysis::thread_mill::{thread_mill, ThreadMillReport, ThreadMillSpec};
pub use analysis::tools::{InsertChoice, Tool, ToolTable};
pub use analysis::turn::correction::{correction, deeper_words, Correction, Deeper};
pub use analysis::turn::lead::{lead_deviation, LeadDeviation};
pub use analysis::turn::{
    default_blank, default_pass_count, program_passes, read_program_text, reference_groove, text_of, verify,
    OperationResult, OperationVerdict, ProgramLabel, ProgramSource, Units, Verification, VerifySpec,
};

pub use lsp::{lsp, run as lsp_run, LspArgs, MAX_OPEN_DOCUMENTS};
pub use serve::{router, serve, ServeArgs, ServeOptions};

// The one output writer of the command line and the Python package.
pub use ground::input::forget_reads;
pub use report::output::write_files;

// The commands: each one's arguments (the command line's flags, the API's keys, Python's
// keywords), its job and the one writer of its documents.
pub use commands::{
    deliver, filter, run_request, ApiArgs, CapabilityArgs, Command, CompareArgs, CorrectArgs, Dest, Document,
    Files, FilterArgs, Filtered, FitArgs, FormSet, InsertSet, Job, JsonArg, LimitsArgs, MillArgs, NoShared,
    ONumber, Outcome, Outputs, PassesArgs, PlanArgs, ProgramArgs, ReadingArgs, ReportArgs, ReportName,
    Request, SeriesSet, SharedArgs, Shown, Source, StandardArgs, SweepArgs, TapArgs, ThreadMillArgs,
    VerifyArgs, CAPABLE_CPK,
};
