//! Per-particle bounds on a motion: each particle's own fraction of it
//! that contact allows, instead of one fraction for every particle.
//!
//! [`Pairs::limit`] returns the largest `τ` such that the motion from `x`
//! to `x + τ dx` keeps every pair at least `keep` of its gap: the first
//! pair that would touch sets the step length of the whole body, and a
//! body landing on an obstacle finds its contacts one row per Newton
//! iteration (on the default scene, 19 iterations of its worst step cut
//! to `τ = 0.045–0.86`). [`Pairs::truncate`] gives each particle `i` a
//! fraction `sᵢ ∈ [0, 1]` of its own motion instead, such that the motion
//! from `x` to `x + s∘dx` (`(s∘dx)ᵢ = sᵢ dxᵢ`) keeps every pair at least
//! `keep` of its gap, and a particle whose pairs do not stop it moves all
//! the way:
//!
//! - **a particle and an obstacle**: only the particle moves (the obstacles
//!   stand where they are at the step's end), so the pair's own CCD along
//!   the particle's motion bounds that particle alone: `sᵢ ≤ τ_ik` for
//!   every obstacle `k` of its list. A particle that moves less than
//!   `1 − keep` of its gap is not even checked (the signed distance is
//!   1-Lipschitz, so it keeps `keep` of its gap whatever its direction);
//! - **a point and a triangle, two edges**: a pair's four particles move
//!   together, and a pair that CCD stops at `τ_p < 1` has each of its
//!   particles' fractions multiplied by `τ_p` (the smallest over its
//!   pairs, for a particle in several). The new motion is checked again:
//!   a pair none of whose particles was cut keeps its motion and its
//!   clearance, and a pair that was cut at `τ_p` — all four of its
//!   particles by at least `τ_p` — may still need a shorter one, since its
//!   particles were cut by different fractions. The rounds end when CCD
//!   stops no pair along the motion they check, which is then as safe as
//!   any motion [`Pairs::limit`] allows; after [`ROUNDS`] rounds, the last
//!   round's motion is cut as a whole to the fraction CCD allows along it
//!   (a prefix of a checked motion).
//!
//! A motion cut this way is not a multiple of the direction it came from;
//! the minimiser's line search then runs along the cut motion, which
//! [`Pairs::iter`] covers at every point, as it does after
//! [`Pairs::limit`].

use hooke_core::Vec3;

use super::Pairs;
use crate::minimize::contact::obstacles::At;
use crate::minimize::contact::pair::Geometry;

#[cfg(test)]
mod tests;

/// The most rounds of the surface pairs' CCD one truncation takes before
/// it cuts the last round's motion as a whole. A pair cut at `τ_p` has its
/// four particles cut by `τ_p` at once, so the second round finds only
/// pairs whose particles were cut by different pairs; on the contact
/// scenes two rounds end almost every truncation.
pub(crate) const ROUNDS: usize = 4;

impl Pairs {
    /// Each particle's fraction `sᵢ ∈ [0, 1]` of the motion `dx` from `x`
    /// (in `scale`) such that the motion from `x` to `x + s∘dx` keeps every
    /// pair at least `keep` of its gap, the obstacles where they are at the
    /// step's end (the module docs). The list then holds every pair within
    /// the contact distance `d̂` at every point of that motion, as after
    /// [`Pairs::limit`].
    pub(in crate::minimize::contact) fn truncate(
        &mut self,
        geometry: &Geometry,
        motion: (&[Vec3], &[Vec3]),
        reach: (f64, f64),
        scale: &mut Vec<f64>,
    ) {
        self.timed(|pairs| pairs.truncate_untimed(geometry, motion, reach, scale));
    }

    /// [`Pairs::truncate`], its time not counted.
    fn truncate_untimed(
        &mut self,
        geometry: &Geometry,
        (x, dx): (&[Vec3], &[Vec3]),
        (keep, activation): (f64, f64),
        scale: &mut Vec<f64>,
    ) {
        scale.clear();
        scale.resize(x.len(), 1.0);
        self.end.clear();
        self.end.extend(x.iter().zip(dx).map(|(x, d)| x + d));
        self.obstacle
            .cover(geometry, (x, &self.end, At::End), activation);
        for pair in self.obstacle.pairs(geometry.system, geometry.obstacles) {
            let i = pair.particles[0];
            scale[i] = scale[i].min(pair.ccd(geometry, x, dx, keep));
        }
        if !self.surfaces {
            return;
        }
        for round in 0..ROUNDS {
            self.shortened.clear();
            self.shortened
                .extend(dx.iter().zip(scale.iter()).map(|(d, s)| *s * d));
            self.end.clear();
            self.end
                .extend(x.iter().zip(&self.shortened).map(|(x, d)| x + d));
            let cut = &mut self.cut;
            cut.clear();
            cut.resize(x.len(), 1.0);
            let tau = self.surface.limit(
                geometry,
                (x, &self.shortened, &self.end),
                (keep, activation),
                |pair, fraction| {
                    for &p in &pair.particles {
                        cut[p] = cut[p].min(fraction);
                    }
                },
            );
            if tau >= 1.0 {
                return;
            }
            if round + 1 == ROUNDS {
                scale.iter_mut().for_each(|s| *s *= tau);
                return;
            }
            scale.iter_mut().zip(cut.iter()).for_each(|(s, c)| *s *= c);
        }
    }
}
