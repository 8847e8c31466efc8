//! The obstacle part of the pair list: each free particle against each
//! obstacle it may come within reach of, found by a direct loop over the
//! particles and the obstacles.
//!
//! The part follows [`Verlet`]'s rule with two differences from the
//! surface part. An obstacle does not move with the body, so no common
//! translation is taken off a particle's move; and an obstacle that moves
//! along its path counts as a primitive that has moved by its displacement
//! since the search. A search at `x_s` lists the pairs whose gap is below
//! `d̂ + s`; at positions `y`, the obstacles where they are then, every
//! pair left out keeps a gap above `d̂` while
//! `maxᵢ |yᵢ − x_s,ᵢ| + maxₖ |oₖ − o_s,ₖ| < s/2` (`oₖ` an obstacle's offset
//! along its path), as a signed distance is 1-Lipschitz.
//!
//! That also makes a pair left out irrelevant to a line search's limit,
//! which keeps a particle at least a tenth of its gap from every obstacle,
//! however far: along a motion whose ends both satisfy the rule an
//! unlisted pair's gap `g(τ) ≥ G − s/2` (`G ≥ d̂ + s` its gap at the
//! search) stays above a tenth of `g(0) ≤ G + s/2` by at least a quarter
//! of the room it had, so its CCD returns 1 at once or after a few steps,
//! as if it had been checked.

use hooke_core::{System, Vec3};

use super::verlet::{MARGIN, Verlet, below, motion_margin};
use crate::minimize::contact::obstacles::{At, Obstacles};
use crate::minimize::contact::pair::{Geometry, Pair};

/// The particle–obstacle candidates of the last search.
#[derive(Debug, Default)]
pub(super) struct ObstaclePart {
    /// The pairs `(particle, obstacle)`, by particle, then obstacle.
    pub(super) touching: Vec<(u32, u32)>,
    /// The positions and margin of the last search.
    pub(super) verlet: Verlet,
    /// Each obstacle's offset along its path at the last search.
    placed: Vec<Vec3>,
    /// The searches since the count was last taken.
    pub(super) queries: usize,
}

impl ObstaclePart {
    /// The pairs of the last search.
    pub(super) fn pairs<'a>(
        &'a self,
        system: &'a System,
        obstacles: &'a Obstacles,
    ) -> impl Iterator<Item = Pair> + 'a {
        self.touching
            .iter()
            .map(move |&ik| Pair::obstacle(system, obstacles, ik))
    }

    /// Makes the candidates cover `y`, the obstacles where `geometry`
    /// places them: every pair within the contact distance `d̂` there is
    /// among them. Keeps the list while `y` lies within its margin,
    /// otherwise searches anew.
    pub(super) fn search(&mut self, geometry: &Geometry, y: &[Vec3], activation: f64) {
        if !geometry.obstacles.is_empty() && !self.covers(geometry, y) {
            self.refresh(geometry, y, activation, MARGIN * activation);
        }
    }

    /// Makes the candidates cover both `a` and `b` and the straight motion
    /// between them (the obstacles moving straight from where `at_a` to
    /// where `at_b` places them): the list, while it covers both ends,
    /// otherwise a new search at `a` whose margin covers the motion.
    pub(super) fn cover(
        &mut self,
        geometry: &Geometry,
        (a, b, at_b): (&[Vec3], &[Vec3], At),
        activation: f64,
    ) {
        let obstacles = geometry.obstacles;
        let other = Geometry {
            at: at_b,
            ..*geometry
        };
        if obstacles.is_empty() || (self.covers(geometry, a) && self.covers(&other, b)) {
            return;
        }
        let moved = farthest(geometry.system, a, b);
        let shifted = (0..obstacles.len())
            .map(|k| (obstacles.placed(k, at_b) - obstacles.placed(k, geometry.at)).norm())
            .fold(0.0, f64::max);
        let margin = motion_margin(MARGIN * activation, moved + shifted);
        self.refresh(geometry, a, activation, margin);
    }

    /// Whether every free particle at `y` and every obstacle where
    /// `geometry` places it have moved less than half the margin since the
    /// last search, together (the module docs).
    fn covers(&self, geometry: &Geometry, y: &[Vec3]) -> bool {
        let obstacles = geometry.obstacles;
        if self.verlet.reference.len() != y.len() {
            return false;
        }
        let shifted = self
            .placed
            .iter()
            .enumerate()
            .map(|(k, o)| (obstacles.placed(k, geometry.at) - o).norm())
            .fold(0.0, f64::max);
        let moved = farthest(geometry.system, &self.verlet.reference, y);
        self.verlet.within(y, moved + shifted)
    }

    /// A search at `x`, the obstacles where `geometry` places them, with
    /// the margin `margin`: the pairs whose gap is below `d̂` plus the
    /// margin.
    fn refresh(&mut self, geometry: &Geometry, x: &[Vec3], activation: f64, margin: f64) {
        self.queries += 1;
        let (system, obstacles) = (geometry.system, geometry.obstacles);
        self.verlet.searched(x, margin);
        self.placed.clear();
        self.placed
            .extend((0..obstacles.len()).map(|k| obstacles.placed(k, geometry.at)));
        self.touching.clear();
        for (i, &xi) in x.iter().enumerate() {
            if system.is_pinned(i) {
                continue;
            }
            for k in 0..obstacles.len() {
                let gap = obstacles.gap(k, i, xi, geometry.at).0;
                if below(gap, activation + margin) {
                    self.touching.push((i as u32, k as u32));
                }
            }
        }
    }
}

/// The farthest any free particle is at `b` from where it is at `a` (not a
/// number if a position is not).
fn farthest(system: &System, a: &[Vec3], b: &[Vec3]) -> f64 {
    a.iter()
        .zip(b)
        .enumerate()
        .filter(|&(i, _)| !system.is_pinned(i))
        .map(|(_, (a, b))| (b - a).norm_squared())
        .fold(0.0, |m: f64, d| if d > m || d.is_nan() { d } else { m })
        .sqrt()
}
