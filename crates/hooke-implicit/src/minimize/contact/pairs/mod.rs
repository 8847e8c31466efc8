//! The pair list: every contact pair a step can see — point–triangle and
//! edge–edge pairs of the collision surfaces, each free particle against
//! each obstacle — as one sequence of [`Pair`]s, and the one limit that
//! contact puts on a motion.
//!
//! Each source of pairs is a part of the list with the same rule for when
//! it is searched again ([`verlet`]): the surfaces' pairs come from the
//! broad phase, the obstacles' from a direct loop over the particles and
//! the obstacles. The parts are searched each when its own rule says so —
//! a body carried as a whole keeps its surface pairs, not its distances to
//! the obstacles. Between searches the list covers every pair within the
//! contact distance at the positions asked for, and, after
//! [`Pairs::limit`], at every point of the motion it checked.
//!
//! The list is iterated in one order: the surface pairs (point–triangle,
//! then edge–edge), then the particles' obstacle pairs, particle by
//! particle. Sums over the pairs are taken in that order.

mod obstacle;
mod surface;
#[cfg(test)]
mod tests;
mod truncate;
mod verlet;

use std::time::Instant;

use hooke_core::{System, Vec3};

use super::obstacles::At;
use super::pair::{Geometry, Pair};
use obstacle::ObstaclePart;
use surface::SurfacePart;

/// The contact pairs of a system.
#[derive(Debug, Default)]
pub(crate) struct Pairs {
    surface: SurfacePart,
    obstacle: ObstaclePart,
    /// Whether the system's surfaces collide (whether the surface part is
    /// searched at all).
    surfaces: bool,
    /// Scratch for the end of a motion, and for the part of a motion the
    /// obstacles allow.
    end: Vec<Vec3>,
    shortened: Vec<Vec3>,
    /// Scratch for each particle's cut in a round of [`Pairs::truncate`].
    cut: Vec<f64>,
    /// The time the searches and checks took since
    /// [`Pairs::take_detection`] last asked, in seconds.
    seconds: f64,
}

impl Pairs {
    /// The pairs of `system`, before any search.
    pub(super) fn new(system: &System) -> Self {
        let mut pairs = Self {
            surfaces: system.has_surface_contact(),
            ..Self::default()
        };
        if pairs.surfaces {
            pairs.surface.begin(system);
        }
        pairs
    }

    /// Makes the list cover `x`, the obstacles where `geometry` places
    /// them: every pair within the contact distance `d̂` there is in it.
    pub(super) fn search(&mut self, geometry: &Geometry, x: &[Vec3], activation: f64) {
        self.timed(|pairs| {
            if pairs.surfaces {
                pairs.surface.search(geometry.system, x, activation);
            }
            pairs.obstacle.search(geometry, x, activation);
        });
    }

    /// Runs `detect` and adds its time to the detection time.
    fn timed<R>(&mut self, detect: impl FnOnce(&mut Self) -> R) -> R {
        let started = Instant::now();
        let result = detect(self);
        self.seconds += started.elapsed().as_secs_f64();
        result
    }

    /// The proximity queries (searches of either part's list, proximity or
    /// swept) since the last call, and the time the searches and the
    /// checks of motions took, in seconds.
    pub(super) fn take_detection(&mut self) -> (usize, f64) {
        let queries =
            std::mem::take(&mut self.surface.queries) + std::mem::take(&mut self.obstacle.queries);
        (queries, std::mem::take(&mut self.seconds))
    }

    /// Makes the obstacle pairs cover `a`, the obstacles where `geometry`
    /// places them, and `b`, the obstacles `at_b`.
    pub(super) fn cover_obstacles(
        &mut self,
        geometry: &Geometry,
        (a, b, at_b): (&[Vec3], &[Vec3], At),
        activation: f64,
    ) {
        self.timed(|pairs| pairs.obstacle.cover(geometry, (a, b, at_b), activation));
    }

    /// The pairs of the list that may lie within `activation` at `x`, in
    /// the list's order (the module docs).
    pub(super) fn iter<'a>(
        &'a self,
        geometry: &Geometry<'a>,
        x: &'a [Vec3],
        activation: f64,
    ) -> impl Iterator<Item = Pair> + 'a {
        self.surface_pairs(geometry.system, x, activation)
            .chain(self.obstacle_pairs(geometry))
    }

    /// The surface pairs of the list that may lie within `activation` at
    /// `x`.
    pub(super) fn surface_pairs<'a>(
        &'a self,
        system: &'a System,
        x: &'a [Vec3],
        activation: f64,
    ) -> impl Iterator<Item = Pair> + 'a {
        self.surface.reachable(system, x, activation)
    }

    /// The obstacle pairs of the list, particle by particle.
    pub(super) fn obstacle_pairs<'a>(
        &'a self,
        geometry: &Geometry<'a>,
    ) -> impl Iterator<Item = Pair> + 'a {
        self.obstacle.pairs(geometry.system, geometry.obstacles)
    }

    /// The largest `τ ∈ [0, 1]` such that the motion from `x` to `x + τ dx`
    /// keeps every pair at least `keep` of its gap, the obstacles where
    /// they are at the step's end. The list then holds every pair within
    /// the contact distance `d̂` at every point of that motion.
    ///
    /// The obstacle pairs come first: where they stop the motion at
    /// `τ₀ < 1`, the surfaces' pairs are checked along `τ₀ dx` only, the
    /// part of the motion a line search can still take. A landing body,
    /// whose obstacles cut most of its Newton steps short, then has its
    /// surfaces searched along motions a fraction as long: the list covers
    /// more of them, and the swept searches it still needs test smaller
    /// boxes. The result is as safe and no shorter than checking the pairs
    /// along the whole motion: a pair's CCD bound is conservative by an
    /// amount that shrinks with the motion.
    pub(super) fn limit(
        &mut self,
        geometry: &Geometry,
        x: &[Vec3],
        dx: &[Vec3],
        reach: (f64, f64),
    ) -> f64 {
        self.timed(|pairs| pairs.limit_untimed(geometry, x, dx, reach))
    }

    /// [`Pairs::limit`], its time not counted.
    fn limit_untimed(
        &mut self,
        geometry: &Geometry,
        x: &[Vec3],
        dx: &[Vec3],
        (keep, activation): (f64, f64),
    ) -> f64 {
        self.end.clear();
        self.end.extend(x.iter().zip(dx).map(|(x, d)| x + d));
        self.obstacle
            .cover(geometry, (x, &self.end, At::End), activation);
        let mut tau: f64 = 1.0;
        for pair in self.obstacle.pairs(geometry.system, geometry.obstacles) {
            tau = tau.min(pair.ccd(geometry, x, dx, keep));
        }
        if !self.surfaces {
            return tau;
        }
        if tau <= 0.0 {
            return 0.0;
        }
        let motion = if tau < 1.0 {
            self.shortened.clear();
            self.shortened.extend(dx.iter().map(|d| tau * d));
            self.end.clear();
            self.end
                .extend(x.iter().zip(&self.shortened).map(|(x, d)| x + d));
            &self.shortened
        } else {
            dx
        };
        tau * self.surface.limit(
            geometry,
            (x, motion, &self.end),
            (keep, activation),
            |_, _| (),
        )
    }
}
