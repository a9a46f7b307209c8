//! `threadcheck fit`: a bolt and a nut, each cut in the computer from a program or a generated
//! plan, assembled in the axial section: the signed clearance at the best axial position, the
//! real engagement depth, the flank overlap, and whether the pair screws together.

use crate::analysis::program::verify_program;
use crate::analysis::tools::InsertChoice;
use crate::analysis::turn::{verify, OperationResult, Verification, VerifySpec};
use crate::ground::plane::Point;
use crate::standards::Designation;
use crate::Error;

/// How one part of the pair is cut.
#[derive(Clone, Debug, PartialEq)]
pub struct FitSide {
    /// The insert.
    pub insert: InsertChoice,
    /// The last pass's tip diameter of a generated plan; `None` solves for mid-tolerance.
    pub final_x: Option<f64>,
    /// A program instead of a plan: its text, its name and dialect. It must cut one thread.
    pub program: Option<(String, String, crate::gcode::Dialect)>,
}

/// What `fit` needs.
#[derive(Clone, Debug, PartialEq)]
pub struct FitSpec {
    /// A fit designation, e.g. `M10x1.5-6H/6g`, parsed (sizes outside the standard series
    /// are the parser's to accept).
    pub thread: Designation,
    /// The bolt.
    pub bolt: FitSide,
    /// The nut.
    pub nut: FitSide,
}

/// What `fit` found.
#[derive(Clone, Debug)]
pub struct FitReport {
    /// The bolt as cut and checked.
    pub bolt: Verification,
    /// The nut as cut and checked.
    pub nut: Verification,
    /// Smallest signed distance between the two profiles at the best axial position, µm:
    /// negative where they interfere.
    pub clearance_um: f64,
    /// The axial shift that puts the nut's profile where it fits best on the bolt's, mm.
    pub nut_shift: f64,
    /// Where the fit is tightest: the bolt's point and the nut's facing it (after the shift).
    pub tightest: (Point, Point),
    /// Real depth of engagement, mm: (bolt major − nut minor)/2, as cut.
    pub engagement_depth: f64,
    /// Length of flank in engagement, mm: the engagement depth along a flank.
    pub flank_overlap: f64,
    /// The pair screws together.
    pub fits: bool,
}

fn side(spec: &FitSpec, s: &FitSide, internal: bool) -> Result<Verification, Error> {
    let v = VerifySpec {
        internal,
        allow_nonstandard: spec.thread.nonstandard,
        insert: s.insert.clone(),
        final_x: s.final_x,
        metrics: false,
        ..VerifySpec::new(Some(spec.thread.clone()))
    };
    match &s.program {
        None => verify(&v),
        Some((text, name, dialect)) => {
            let pv = verify_program(&v, text, name, *dialect, std::slice::from_ref(&spec.thread), &|_| None)?;
            if pv.operations.len() != 1 {
                return Err(Error::Input(format!(
                    "{name} cuts {} threads; fit takes a program with one",
                    pv.operations.len()
                )));
            }
            match pv.operations.into_iter().next().map(|o| o.result) {
                Some(OperationResult::Verified(v)) => Ok(*v),
                Some(OperationResult::NoCut { reason, .. }) => {
                    Err(Error::Geometry(format!("{name}: {reason}")))
                }
                None => Err(Error::Input(format!("{name} cuts no thread"))),
            }
        }
    }
}

/// Cuts both parts and assembles them.
///
/// ```
/// use threadcheck::{fit, FitSide, FitSpec};
/// use threadcheck::InsertChoice;
/// let side = FitSide { insert: InsertChoice::Full, final_x: None, program: None };
/// let thread = threadcheck::parse_designation("M10x1.5-6H/6g", Default::default())?;
/// let r = fit(&FitSpec { thread, bolt: side.clone(), nut: side })?;
/// assert!(r.fits && r.clearance_um > 0.0);
/// # Ok::<(), threadcheck::Error>(())
/// ```
pub fn fit(spec: &FitSpec) -> Result<FitReport, Error> {
    let des = &spec.thread;
    if des.external.is_none() || des.internal.is_none() {
        return Err(Error::Input(format!(
            "'{}' names no fit: give the nut's and the bolt's classes, e.g. M10x1.5-6H/6g",
            spec.thread
        )));
    }
    if des.thread.form.taper() != 0.0 {
        return Err(Error::Input(
            "fit assembles parallel threads; a taper pipe thread is judged by its gauge plane".into(),
        ));
    }
    let bolt = side(spec, &spec.bolt, false)?;
    let nut = side(spec, &spec.nut, true)?;
    let p = des.thread.pitch;
    // The bolt's tooth: from its measured groove's centre one pitch on. The nut's groove goes on
    // it: the nut's profile is moved so its groove centre lies on the tooth's centre.
    let cb = bolt.measurement.groove_center;
    let tooth: Vec<Point> =
        bolt.section.profile().into_iter().filter(|q| q.z >= cb - 1e-9 && q.z <= cb + p + 1e-9).collect();
    let shift = cb + 0.5 * p - nut.measurement.groove_center;
    let nut_side: Vec<Point> = nut
        .section
        .profile()
        .into_iter()
        .map(|q| Point::new(q.z + shift, q.r))
        .filter(|q| q.z >= cb - p && q.z <= cb + 2.0 * p)
        .collect();
    if tooth.len() < 2 || nut_side.len() < 2 {
        return Err(Error::Geometry("the cut sections hold no whole tooth to assemble".into()));
    }
    let contact = crate::geometry::measure::fit_contact(tooth, nut_side, 0.25 * p);
    let clearance = contact.clearance;
    let engagement_depth = 0.5 * (bolt.measurement.major_diameter - nut.measurement.minor_diameter);
    let half = 0.5 * des.thread.form.flank_angle().to_radians();
    Ok(FitReport {
        bolt,
        nut,
        clearance_um: clearance * 1000.0,
        nut_shift: shift + contact.shift,
        tightest: (contact.bolt, contact.nut),
        engagement_depth,
        flank_overlap: engagement_depth.max(0.0) / half.cos(),
        // The geometry's own accuracy: a pair at exactly basic size fits.
        fits: clearance >= -crate::analysis::check::MMC_SLACK,
    })
}

/// Whether the bolt goes into the nut.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum FitVerdict {
    /// Clearance at the best axial position.
    Fits,
    /// Interference.
    Interferes,
}
