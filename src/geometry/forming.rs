//! A thread formed, not cut (issue 64): a form (roll) tap pressing its teeth into a hole's wall,
//! or dies rolling a blank. The metal is displaced, not removed: the volume the tool's teeth push
//! out of the groove flows into the thread's teeth, so the crest forms where the two volumes are
//! equal. Volumes of revolution by Pappus: per pitch, 2π·∫ w(r)·r dr over the radius r, with w the
//! profile's axial width at r (linear between the flat crest and root of a V form, so each
//! integral is exact). The crest forms flat (a form tap's crest is cupped, split where the metal
//! meets: its height is the same to the first order; stated where it is reported).

/// The thread's profile in the axial section for the volume balance: pitch `p`, pitch radius
/// `r2` and half the flank angle's tangent. `groove(r)` is the width at radius r of the
/// internal thread's groove (the form tap's tooth), `p − groove(r)` the nut's tooth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FormProfile {
    /// Pitch, mm.
    pub p: f64,
    /// Pitch radius, mm.
    pub r2: f64,
    /// tan(α/2).
    pub tan_half: f64,
}

impl FormProfile {
    /// The nut's groove width at radius `r`: P/2 at the pitch radius, narrowing outward by
    /// 2·tan(α/2) a unit of radius, within 0 and P.
    fn groove(&self, r: f64) -> f64 {
        (0.5 * self.p - 2.0 * (r - self.r2) * self.tan_half).clamp(0.0, self.p)
    }

    /// ∫ₐᵇ groove(r)·r dr, exact: split where the clamp starts and ends, polynomial between.
    fn groove_moment(&self, a: f64, b: f64) -> f64 {
        if b <= a {
            return 0.0;
        }
        let k = 0.25 * self.p / self.tan_half;
        let (full, empty) = (self.r2 - k, self.r2 + k);
        let mut cuts = vec![a, b];
        cuts.extend([full, empty].into_iter().filter(|&x| x > a && x < b));
        cuts.sort_by(f64::total_cmp);
        cuts.windows(2)
            .map(|w| {
                let (x0, x1) = (w[0], w[1]);
                // Linear on [x0, x1]: w(r) = c0 + c1·r.
                let (g0, g1) = (self.groove(x0), self.groove(x1));
                let c1 = if x1 > x0 { (g1 - g0) / (x1 - x0) } else { 0.0 };
                let c0 = g0 - c1 * x0;
                let f = |r: f64| 0.5 * c0 * r * r + c1 * r * r * r / 3.0;
                f(x1) - f(x0)
            })
            .sum()
    }

    /// ∫ₐᵇ (P − groove(r))·r dr: the nut's tooth.
    fn tooth_moment(&self, a: f64, b: f64) -> f64 {
        if b <= a {
            return 0.0;
        }
        0.5 * self.p * (b * b - a * a) - self.groove_moment(a, b)
    }

    /// The radius where the nut's tooth comes to a point (its width 0).
    fn apex(&self) -> f64 {
        self.r2 - 0.25 * self.p / self.tan_half
    }
}

/// What a form tap leaves in a hole.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Formed {
    /// The crest forms at this minor diameter D1, mm.
    Minor(f64),
    /// The hole holds more metal than the thread's teeth: they close to a point before it is
    /// all placed (the hole is too small: the tap is overloaded).
    Overfilled,
}

/// The minor diameter a form tap whose crest reaches `major` (mm, the nut's major diameter D)
/// leaves in a hole of `hole` mm, for `profile`: the nut's tooth grown inward from the hole's
/// wall until its volume is the volume the tap's teeth displace between the wall and D.
///
/// ```
/// use threadcheck::{formed_minor, FormProfile, Formed};
/// // M10x1.5 (60°) in a Ø9.3 hole. By hand: the tap's teeth displace, between r 4.65 and 5, a
/// // groove 0.5917 → 0.1875 mm wide: 0.1363 mm² at its centroid r ≈ 4.81; the nut's tooth,
/// // 0.9083 mm wide at the wall and narrowing 2·tan 30° a mm inward, holds it at r ≈ 4.55 in
/// // 0.1441 mm² = 0.9083·h − 0.5774·h², h ≈ 0.1785: D1 ≈ 9.3 − 0.357 = 8.943.
/// let p = FormProfile { p: 1.5, r2: 0.5 * 9.025_722, tan_half: 30f64.to_radians().tan() };
/// match formed_minor(&p, 10.0, 9.3) {
///     Formed::Minor(d1) => assert!((d1 - 8.943).abs() < 0.003, "{d1}"),
///     Formed::Overfilled => panic!(),
/// }
/// // A hole at or under the pitch diameter holds more metal than the teeth.
/// assert_eq!(formed_minor(&p, 10.0, 9.0), Formed::Overfilled);
/// ```
pub fn formed_minor(profile: &FormProfile, major: f64, hole: f64) -> Formed {
    let (rh, big) = (0.5 * hole, 0.5 * major);
    let displaced = profile.groove_moment(rh, big);
    if displaced <= 0.0 {
        return Formed::Minor(hole);
    }
    let apex = profile.apex();
    if apex >= rh || profile.tooth_moment(apex, rh) < displaced {
        return Formed::Overfilled;
    }
    // The tooth's volume grows as its crest moves inward: bisect to the radius where it is
    // the displaced volume.
    Formed::Minor(2.0 * bisect(apex, rh, |r| profile.tooth_moment(r, rh) > displaced))
}

/// The point of [lo, hi] where `below` turns false, to 1e-13 mm: `below` holds under it.
fn bisect(mut lo: f64, mut hi: f64, below: impl Fn(f64) -> bool) -> f64 {
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if below(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo < 1e-13 {
            break;
        }
    }
    0.5 * (lo + hi)
}

/// What rolling dies leave on a blank.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Rolled {
    /// The crest forms at this major diameter, mm.
    Major(f64),
    /// The blank holds more metal than the thread's teeth: they close to a point (the dies
    /// are overloaded; the crest laps over).
    Overfilled,
}

/// The major diameter dies whose crests form the root at `root` (mm, a diameter) leave on a
/// blank of `blank` mm, for `profile` (the bolt's tooth is the nut's groove of
/// [`FormProfile`]): the tooth grown outward from the blank's surface until its volume is the
/// volume the dies' teeth displace between the root and the surface.
pub fn rolled_major(profile: &FormProfile, root: f64, blank: f64) -> Rolled {
    let (rr, rb) = (0.5 * root, 0.5 * blank);
    // The bolt's groove is the nut's tooth, its tooth the nut's groove.
    let displaced = profile.tooth_moment(rr, rb);
    if displaced <= 0.0 {
        return Rolled::Major(blank);
    }
    let apex = profile.r2 + 0.25 * profile.p / profile.tan_half;
    if apex <= rb || profile.groove_moment(rb, apex) < displaced {
        return Rolled::Overfilled;
    }
    Rolled::Major(2.0 * bisect(rb, apex, |r| profile.groove_moment(rb, r) < displaced))
}

/// The blank, mm, on which the same dies form the crest at `crest` (mm): the blank whose
/// displaced metal just fills the tooth to it.
pub fn blank_for_crest(profile: &FormProfile, root: f64, crest: f64) -> f64 {
    bisect(root, crest, |b| matches!(rolled_major(profile, root, b), Rolled::Major(m) if m < crest))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The exact moments against a fine midpoint sum of the same widths.
    #[test]
    fn the_moments_are_the_integrals() {
        let p = FormProfile { p: 1.5, r2: 4.512_861, tan_half: 30f64.to_radians().tan() };
        let (a, b) = (3.9, 5.1);
        let n = 200_000;
        let h = (b - a) / n as f64;
        let sum: f64 = (0..n)
            .map(|i| {
                let r = a + (i as f64 + 0.5) * h;
                p.groove(r) * r
            })
            .sum::<f64>()
            * h;
        assert!((sum - p.groove_moment(a, b)).abs() < 1e-9, "{sum}");
    }
}
