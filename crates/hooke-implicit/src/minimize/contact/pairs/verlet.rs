//! The rule of a Verlet list, which each part of the pair list follows: a
//! proximity search at positions `x_s` with margin `s` lists every pair
//! whose gap is below `d̂ + s` there, and the list serves every
//! configuration whose primitives each stay within `s/2` of their place at
//! the search — then no pair left out can have come within `d̂`, as a gap
//! changes by no more than its two primitives move. A motion whose ends
//! both qualify stays within the list throughout (a ball is convex); one
//! that does not gets a new search whose margin covers it.

use hooke_core::Vec3;

/// How far beyond the contact distance `d̂` (plus thickness) a proximity
/// search reaches, in units of `d̂`, when it needs to cover no motion.
pub(super) const MARGIN: f64 = 4.0;

/// How many times over a new proximity search's margin must cover the
/// motion that outgrew the last one.
pub(super) const MOTION_SLACK: f64 = 1.5;

/// The positions and margin of a part's last search.
#[derive(Debug, Default)]
pub(super) struct Verlet {
    /// The positions of the last search (the start of the motion of a
    /// swept one); empty before the first.
    pub(super) reference: Vec<Vec3>,
    /// The margin `s` of the last proximity search; zero after a swept
    /// search, whose list is no Verlet list.
    pub(super) margin: f64,
}

impl Verlet {
    /// Records a search at `x` with margin `margin`.
    pub(super) fn searched(&mut self, x: &[Vec3], margin: f64) {
        self.margin = margin;
        self.reference.clear();
        self.reference.extend_from_slice(x);
    }

    /// Whether positions `y` whose primitives have moved at most
    /// `farthest` from their place at the search lie within half its
    /// margin.
    pub(super) fn within(&self, y: &[Vec3], farthest: f64) -> bool {
        self.reference.len() == y.len() && farthest < 0.5 * self.margin
    }
}

/// The margin of a new search that covers a motion whose primitives move
/// at most `motion`, [`MOTION_SLACK`] times over, and at least `default`.
pub(super) fn motion_margin(default: f64, motion: f64) -> f64 {
    default.max(2.0 * MOTION_SLACK * motion)
}

/// Whether a pair's lower bound on its gap, `bound`, is below `reach`: the
/// pair may come within it, and stays listed. A bound that is not a number
/// (a position that is not one) keeps the pair too.
pub(super) fn below(bound: f64, reach: f64) -> bool {
    bound.is_nan() || bound < reach
}

/// The common translation `t` of the particles from `reference` to `y`
/// that the surface part takes off their moves — the centre of the box of
/// their displacements — and the farthest any particle then is from its
/// reference position, `max |yᵢ − rᵢ − t|` (not a number if a position is
/// not).
pub(super) fn drift(reference: &[Vec3], y: &[Vec3]) -> (Vec3, f64) {
    let (mut lo, mut hi) = (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY));
    for (r, y) in reference.iter().zip(y) {
        let d = y - r;
        lo = lo.inf(&d);
        hi = hi.sup(&d);
    }
    if reference.is_empty() {
        return (Vec3::zeros(), 0.0);
    }
    let shift = 0.5 * (lo + hi);
    let farthest = reference
        .iter()
        .zip(y)
        .map(|(r, y)| (y - r - shift).norm_squared())
        .fold(0.0, |m: f64, d| if d > m || d.is_nan() { d } else { m });
    (shift, farthest.sqrt())
}
