//! The bound that contact puts on a motion: the pairs within the contact
//! distance, and the step along a motion that no pair crosses (additive
//! continuous collision detection).

use hooke_core::{System, Vec3};

use super::pairs::{Pairs, drift};

/// How many times over a new proximity search's margin must cover the
/// motion that outgrew the last one.
const MOTION_SLACK: f64 = 1.5;

/// The widest margin, in units of the contact distance, of a proximity
/// search that [`Pairs::limit`] makes for a motion; a longer motion gets a
/// swept search.
const MAX_MARGIN: f64 = 16.0;

impl Pairs {
    /// The pairs within the contact distance at `x` and the smallest gap
    /// among them.
    pub(crate) fn closest(&self, system: &System, x: &[Vec3], activation: f64) -> (usize, f64) {
        let (mut count, mut smallest) = (0, f64::INFINITY);
        for pair in self.reachable(system, x, activation) {
            let gap = Self::gap(&pair, Self::squared(&pair, x));
            if gap < activation {
                count += 1;
                smallest = smallest.min(gap);
            }
        }
        (count, smallest)
    }

    /// The largest `τ ∈ [0, 1]` such that the motion from `x` to `x + τ dx`
    /// keeps every pair at least `keep` of its gap (additive CCD), over
    /// candidates that then hold every pair within reach at any point of
    /// the motion, and become those of [`Pairs::energy`] and [`Pairs::add`]:
    ///
    /// - the Verlet list, while both ends of the motion lie within its
    ///   margin (each moved by its particles' common translation);
    /// - otherwise, if the widest margin a search may take — [`MAX_MARGIN`]
    ///   `d̂` or the widest margin of a search, whichever is less — covers
    ///   the motion (its common translation taken off) `MOTION_SLACK`
    ///   times over, a new proximity search at `x` with that margin. The
    ///   iterations after it, whose motions the line search and the
    ///   obstacles keep short, then keep its list as long as they can; on
    ///   a flat cloth the wider reach lists no more pairs (it stays below
    ///   the grid's closest pair), and on the default scene the main job
    ///   ran in 0.95 of the time of a margin of `MOTION_SLACK` times the
    ///   motion (farm-bench, 4 pairs; cloth-pile and two-cloths 1.00);
    /// - otherwise (a long motion) the pairs whose boxes, swept over the
    ///   motion and inflated by the contact distance `d̂` and the
    ///   thickness, overlap and which the motion can bring within `d̂`
    ///   ([`Pairs::swept`]), with their distances at `x`.
    ///
    /// A pair whose distance `D` at the list's positions (`x` after a
    /// swept search) bounds its gap along the whole motion from below by
    /// more than `keep` times the bound of its gap at `x` from above is
    /// skipped without CCD: along a straight motion a particle is farthest from
    /// its place in the list at one of the motion's ends (distance from a
    /// point is convex, and the common translations `t₀` at `x` and `t₁` at
    /// `x + dx` taken off move straight between them), and a pair's gap
    /// moves by at most the farthest move of each primitive's corners, so
    /// with `m` each particle's distance from its place in the list at `x`
    /// (less `t₀`) and `M` the farther of it at `x` and at `x + dx` (less
    /// `t₁`),
    ///
    /// ```text
    /// g(τ) ≥ D − max₁ M − max₂ M − ξ,   g(0) ≤ D + max₁ m + max₂ m − ξ,
    /// ```
    ///
    /// and the pair keeps more than `keep g(0)` throughout, where CCD would
    /// return 1.
    pub(crate) fn limit(
        &mut self,
        system: &System,
        x: &[Vec3],
        dx: &[Vec3],
        (keep, activation): (f64, f64),
    ) -> f64 {
        self.end.clear();
        self.end.extend(x.iter().zip(dx).map(|(x, d)| x + d));
        // The common translations of `x` and of the motion's end from the
        // list's positions, and the farthest moves less them.
        let (mut start, mut end) = (drift(&self.reference, x), drift(&self.reference, &self.end));
        if !(self.within_margin(x, start.1) && self.within_margin(&self.end, end.1)) {
            let motion = drift(x, &self.end);
            let widest = (MAX_MARGIN * activation).min(self.widest);
            let needed = self
                .default_margin(activation)
                .max(2.0 * MOTION_SLACK * motion.1);
            if needed <= widest {
                self.refresh(system, x, activation, widest);
            } else {
                self.swept(system, x, activation);
            }
            // The list's positions are now `x`.
            (start, end) = ((Vec3::zeros(), 0.0), motion);
        }
        let (reference, start, end) = (&self.reference, start.0, end.0);
        self.moved.clear();
        self.moved
            .extend(reference.iter().zip(x).zip(&self.end).map(|((r, x), e)| {
                let now = (x - r - start).norm_squared();
                (now.sqrt(), now.max((e - r - end).norm_squared()).sqrt())
            }));
        let mut tau: f64 = 1.0;
        for (k, pair) in Self::pairs(system, &self.near).enumerate() {
            let searched = self.searched[k];
            let now = pair.largest(|p| self.moved[p].0);
            let along = pair.largest(|p| self.moved[p].1);
            let lowest = searched - along.0 - along.1 - pair.thickness;
            let highest = searched + now.0 + now.1 - pair.thickness;
            if lowest > keep * highest {
                continue;
            }
            tau = tau.min(pair.ccd(x, dx, keep));
        }
        tau
    }
}
