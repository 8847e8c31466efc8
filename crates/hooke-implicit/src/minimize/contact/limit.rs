//! The bound that contact puts on a motion: the pairs within the contact
//! distance, and the step along a motion that no pair crosses (additive
//! continuous collision detection).

use hooke_core::collision::ccd::{edge_edge_ccd, point_triangle_ccd};
use hooke_core::{System, Vec3};

use super::pairs::{MARGIN, Pairs};

impl Pairs {
    /// The pairs within the contact distance at `x` and the smallest gap
    /// among them.
    pub(crate) fn closest(&self, system: &System, x: &[Vec3], activation: f64) -> (usize, f64) {
        let (mut count, mut smallest) = (0, f64::INFINITY);
        for (k, pair) in Self::pairs(system, &self.near).enumerate() {
            if self.far(k, &pair, x, activation) {
                continue;
            }
            let gap = Self::gap(&pair, Self::squared(&pair, x));
            if gap < activation {
                count += 1;
                smallest = smallest.min(gap);
            }
        }
        (count, smallest)
    }

    /// The largest `τ ∈ [0, 1]` such that the motion from `x` to `x + τ dx`
    /// keeps every pair at least `keep` of its gap (additive CCD on the
    /// pairs whose boxes, swept over the motion and inflated by the contact
    /// distance `d̂` and the thickness, overlap — or on the Verlet list, when
    /// the motion stays within its margin). Those pairs become the
    /// candidates of [`Pairs::energy`] and [`Pairs::add`]: every pair within
    /// reach at any point of the motion is among them.
    pub(crate) fn limit(
        &mut self,
        system: &System,
        x: &[Vec3],
        dx: &[Vec3],
        (keep, activation): (f64, f64),
    ) -> f64 {
        self.end.clear();
        self.end.extend(x.iter().zip(dx).map(|(x, d)| x + d));
        if !(self.covers(x) && self.covers(&self.end)) {
            let reach = (0.5 * MARGIN * activation).powi(2);
            if dx.iter().all(|d| d.norm_squared() < reach) {
                self.refresh(system, x, activation);
            } else {
                self.reference = None;
                self.searched.clear();
                self.broad.swept(
                    system.surfaces(),
                    x,
                    &self.end,
                    activation + self.thickest,
                    &mut self.near,
                );
            }
        }
        let mut tau: f64 = 1.0;
        for pair in Self::pairs(system, &self.near) {
            let (q, d) = (pair.positions(x), pair.particles.map(|p| dx[p]));
            let t = if pair.edges {
                edge_edge_ccd(q, d, pair.thickness, keep)
            } else {
                point_triangle_ccd(q, d, pair.thickness, keep)
            };
            tau = tau.min(t);
        }
        tau
    }
}
