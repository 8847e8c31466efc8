//! Contact as terms of the incremental potential (Li et al., *Incremental
//! Potential Contact*, SIGGRAPH 2020; Li, Kaufman & Jiang, *Codimensional
//! Incremental Potential Contact*, SIGGRAPH 2021).
//!
//! Every close pair — a particle and an obstacle, a point and a triangle,
//! two edges — adds to the step's potential `Φ` a barrier on its gap `g`
//! (its distance less the thicknesses),
//!
//! ```text
//! κ b(g),   b(g) = −(g − d̂)² ln(g/d̂)  for 0 < g < d̂,   0 for g ≥ d̂,
//! ```
//!
//! smooth (C²) where it switches on, growing without bound as `g → 0`, with
//! `d̂` the system's [contact distance](hooke_core::System::contact_distance)
//! (by default 10⁻³ of the scene's size), and a friction term, the lagged
//! dissipation potential of the `friction` module. Newton's method sees
//! their gradients and Hessians (each pair's projected onto its positive
//! part), and every line search is bounded by continuous collision
//! detection: a step along a direction goes at most as far as keeps every
//! pair at a tenth of its gap ([`KEEP`]), so no iterate ever crosses and
//! `Φ` stays finite — the whole step as far as the first pair allows
//! ([`Contact::limit`]), or each particle as far as its own pairs allow
//! ([`Contact::truncate`], the minimiser's `bounds` module). Contacts never enter or leave the iteration as
//! constraints: `Φ` keeps its shape from one iterate to the next.
//!
//! **One model.** The pairs of every kind come from one list (the `pairs`
//! module), and one type evaluates each (the `pair` module): its gap, its
//! barrier term, its continuous collision detection, its friction. This
//! type holds the step's barrier, friction and obstacles and sums over the
//! list.
//!
//! **Barrier stiffness.** `κ` makes a particle of the mean mass `m̄` rest
//! on an obstacle under gravity at half the contact distance,
//! `κ = m̄ |g| / |b'(d̂/2)|` (with `|g|` = 9.81 m/s² in a system without
//! gravity); heavier loads settle closer, where the barrier is stiffer.
//! When a step ends with a gap below [`CLOSE`]` · d̂`, `κ` doubles for the
//! next step (up to [`MAX_STIFFENING`] times its start), as IPC's adaptive
//! stiffness does, so that a pair pressed hard is held farther apart.
//!
//! **Friction.** A particle on an obstacle has the obstacle's coefficient
//! `μ`; a pair of surfaces the mean of theirs. The normal force `λ = κ|b'(g)|`
//! and the contact's tangent plane are taken at the step's start (the
//! particles' obstacle contacts listed first, then the surfaces', the order
//! the friction terms are summed in). The
//! friction sticks below the speed `ε = d̂ / 1 s` (10⁻³ of the scene's size
//! per second, IPC's choice): a sticking body creeps at most that fast, and
//! over a step of `h` moves at most `ε h`, well below `d̂`.
//!
//! **Moving obstacles.** The barrier acts against each obstacle's place at
//! the end of the step. The step starts from the positions at its start,
//! with every particle within `d̂` of a moving obstacle carried along by its
//! displacement; a particle that starts inside an obstacle (a scene set up
//! that way, or a fast obstacle) is first pushed out along the normal to
//! half the contact distance.
//!
//! **Energy.** The barrier is a potential: the implicit step's energy test
//! counts `κ Σ b` with the springs' energy, and the work of a moving
//! obstacle, `Σ F·Δo` over its barrier and friction forces `F`.

mod friction;
mod obstacles;
mod pair;
mod pairs;
#[cfg(test)]
mod tests;

use hooke_core::collision::barrier::Barrier;
use hooke_core::{State, System, Vec3};

use crate::linear::matrix::HessianBlocks;
use friction::{FrictionModel, Lagged};
use obstacles::{At, Obstacles};
use pair::Geometry;
use pairs::Pairs;

/// The fraction of its gap a pair keeps in any one line-search step.
pub(crate) const KEEP: f64 = 0.1;

/// The fraction of the contact distance below which a gap at the end of a
/// step doubles the barrier stiffness for the next.
pub(crate) const CLOSE: f64 = 1e-2;

/// The most the barrier stiffness grows over its start.
pub(crate) const MAX_STIFFENING: f64 = 1e4;

/// The contact terms of a system's implicit step.
#[derive(Debug, Default)]
pub(crate) struct Contact {
    /// The system they were set up for.
    system: u64,
    obstacles: Obstacles,
    /// The pairs of every kind.
    pairs: Pairs,
    /// The barrier: its stiffness `κ` and the contact distance `d̂`.
    barrier: Barrier,
    /// The barrier stiffness at the start.
    kappa_start: f64,
    /// The friction's sticking speed `ε`.
    sticking: f64,
    /// The step's length `h`.
    step: f64,
    friction: Vec<Lagged>,
    /// The friction's Hessian in Newton's model for the rest of the step.
    friction_model: FrictionModel,
    /// The feasible positions the step starts from.
    start: Vec<Vec3>,
    /// The barriers' energy at the step's start ([`Contact::start_energy`]).
    start_energy: f64,
    /// The smallest gap seen at the end of an accepted step so far.
    pub(crate) smallest_gap: f64,
    /// Each particle's fraction of the last truncated motion.
    scale: Vec<f64>,
}

impl Contact {
    /// Whether `system` has contact terms: obstacles or colliding surfaces.
    pub(crate) fn present(system: &System) -> bool {
        !system.obstacles().is_empty() || system.has_surface_contact()
    }

    /// Sets up the terms for `system` if they were set up for another;
    /// returns whether it did.
    fn setup(&mut self, system: &System) -> bool {
        let fresh = self.system != system.id();
        if fresh {
            self.system = system.id();
            let masses = system.masses();
            let mean = masses.iter().sum::<f64>() / masses.len().max(1) as f64;
            let g = system.gravity().map_or(0.0, |g| g.norm());
            let g = if g > 0.0 { g } else { 9.81 };
            self.barrier = Barrier::resting(mean * g, system.contact_distance());
            self.kappa_start = self.barrier.stiffness;
            self.sticking = self.barrier.activation;
            self.smallest_gap = f64::INFINITY;
            self.pairs = Pairs::new(system);
            self.obstacles.begin(system, 0.0, 0.0, true);
        }
        fresh
    }

    /// Moves every free particle of `state` that lies inside an obstacle,
    /// or within its surface's half thickness of one, out along the normal
    /// to half the contact distance — a scene set up touching an obstacle —
    /// before a step; returns how many it moved.
    ///
    /// A state with nothing to move is left untouched, so that BDF2's and
    /// error control's history, which any write to the positions clears,
    /// carries over to the next step.
    pub(crate) fn push_out(&mut self, system: &System, state: &mut State) -> usize {
        self.setup(system);
        self.obstacles
            .push_out(system, state, self.barrier.activation)
    }

    /// Sets up a step of `h` from `x0` at `time`: the obstacles at the
    /// step's start and end, the lagged friction, and the feasible
    /// positions the step starts from ([`Contact::start`]).
    pub(crate) fn begin(&mut self, system: &System, x0: &[Vec3], time: f64, h: f64) {
        let fresh = self.setup(system);
        self.obstacles.begin(system, time, h, fresh);
        self.step = h;
        self.friction_model = FrictionModel::Exact;
        let d_hat = self.barrier.activation;
        self.obstacles
            .feasible_start(system, (x0, time), d_hat, &mut self.start);
        let geometry = Geometry::new(system, &self.obstacles, At::Start);
        self.pairs.search(&geometry, x0, d_hat);
        let lagged = self
            .pairs
            .obstacle_pairs(&geometry)
            .chain(self.pairs.surface_pairs(system, x0, d_hat))
            .filter_map(|pair| pair.lag(&geometry, x0, &self.barrier, h));
        self.friction.clear();
        self.friction.extend(lagged);
        let barrier = &self.barrier;
        let mut sum = 0.0;
        for pair in self.pairs.iter(&geometry, x0, d_hat) {
            let energy = pair.energy(&geometry, x0, barrier);
            if energy.is_finite() {
                sum += energy;
            }
        }
        self.start_energy = barrier.stiffness * sum;
    }

    /// The feasible positions of the step's start.
    pub(crate) fn start(&self) -> &[Vec3] {
        &self.start
    }

    /// The contact terms of `Φ` at positions `x` and velocities `v`:
    /// `κ Σ b(g) + βh Σ D(v)`; infinite if a gap is not positive.
    /// `x` must lie on the motion last checked by [`Contact::limit`], whose
    /// pair candidates it reuses.
    pub(crate) fn value(&mut self, system: &System, x: &[Vec3], v: &[Vec3], beta_h: f64) -> f64 {
        let barrier = self.barrier_at(system, x);
        let friction: f64 = self
            .friction
            .iter()
            .map(|f| f.value(v, self.sticking))
            .sum();
        barrier + beta_h * friction
    }

    /// `κ Σ b(g)` at positions `x`, the obstacles at the step's end;
    /// infinite if a gap is not positive.
    pub(crate) fn barrier_energy(&mut self, system: &System, x: &[Vec3]) -> f64 {
        let geometry = Geometry::new(system, &self.obstacles, At::End);
        self.pairs.search(&geometry, x, self.barrier.activation);
        self.barrier_at(system, x)
    }

    /// `κ Σ b(g)` at positions `x` over the pairs of the last search or
    /// checked motion, the obstacles at the step's end.
    fn barrier_at(&self, system: &System, x: &[Vec3]) -> f64 {
        let geometry = Geometry::new(system, &self.obstacles, At::End);
        let barrier = &self.barrier;
        let mut sum = 0.0;
        for pair in self.pairs.iter(&geometry, x, barrier.activation) {
            sum += pair.energy(&geometry, x, barrier);
        }
        barrier.stiffness * sum
    }

    /// `κ Σ b(g)` at the positions `x0` of the step's start, the obstacles
    /// there (infinite terms, of pairs that started crossed or inside an
    /// obstacle, left out), as [`Contact::begin`] measured it over the
    /// pairs it searched at `x0`: measured again after the minimisation,
    /// whose iterates moved the list away from `x0`, it would cost a
    /// proximity search at `x0` and another back at the step's end.
    pub(crate) fn start_energy(&self) -> f64 {
        self.start_energy
    }

    /// The work the moving obstacles did on the particles over a step of
    /// `h` from `x0` at `time` to `x`, `v`: the barrier forces at both ends
    /// by the trapezoid rule, and the friction force at the end, times the
    /// obstacles' displacements.
    pub(crate) fn obstacle_work(
        &mut self,
        system: &System,
        (x0, time): (&[Vec3], f64),
        x: &[Vec3],
        v: &[Vec3],
    ) -> f64 {
        if self.obstacles.moved().iter().all(|m| *m == Vec3::zeros()) {
            return 0.0;
        }
        self.obstacles.place_start(system, time);
        let (start, end) = (
            Geometry::new(system, &self.obstacles, At::Start),
            Geometry::new(system, &self.obstacles, At::End),
        );
        self.pairs
            .cover_obstacles(&end, (x, x0, At::Start), self.barrier.activation);
        let mut work = 0.0;
        for pair in self.pairs.obstacle_pairs(&end) {
            work += pair.obstacle_work((&start, x0), (&end, x), &self.barrier);
        }
        for f in &self.friction {
            work += self.step * f.force(v, self.sticking).dot(&f.velocity);
        }
        work
    }

    /// Adds the contact terms at positions `x` and velocities `v` to a
    /// Newton system `A δ = −∇Φ` in the velocities, `x = x̃ + βh v`:
    /// `b −= βh κ ∇b + βh ∇D` and `A += β²h² κ ∇²b + βh ∇²D`, `A`'s blocks
    /// going where `a` keeps them ([`HessianBlocks`]). Like
    /// [`Contact::value`], at a point of the motion last checked.
    pub(crate) fn add(
        &mut self,
        system: &System,
        x: &[Vec3],
        v: &[Vec3],
        beta_h: f64,
        b: &mut [Vec3],
        a: &mut impl HessianBlocks,
    ) {
        let geometry = Geometry::new(system, &self.obstacles, At::End);
        let barrier = &self.barrier;
        let kappa = barrier.stiffness;
        let scale = (kappa * beta_h, kappa * beta_h * beta_h);
        for pair in self.pairs.iter(&geometry, x, barrier.activation) {
            pair.add(&geometry, x, (barrier, scale), b, a);
        }
        for f in &self.friction {
            f.add(v, (self.sticking, self.friction_model), beta_h, b, a);
        }
    }

    /// Turns Newton's model of the friction to the majorizing one of the
    /// `friction` module for the rest of the step, once a full step of the
    /// exact model has failed.
    pub(crate) fn majorize_friction(&mut self) {
        self.friction_model = FrictionModel::Majorizing;
    }

    /// The largest `τ ∈ [0, 1]` such that the motion from `x` to `x + τ dx`
    /// keeps every pair at least [`KEEP`] of its gap. [`Contact::value`]
    /// and [`Contact::add`] then hold for the points of this motion: the
    /// pair list covers every pair that comes within reach along it, so a
    /// line search needs one search, not one a trial point. The obstacle
    /// pairs are checked first, the surface pairs along the part of the
    /// motion they allow (the `pairs` module's `Pairs::limit`).
    pub(crate) fn limit(&mut self, system: &System, x: &[Vec3], dx: &[Vec3]) -> f64 {
        let geometry = Geometry::new(system, &self.obstacles, At::End);
        self.pairs
            .limit(&geometry, x, dx, (KEEP, self.barrier.activation))
    }

    /// Each particle's fraction `sᵢ ∈ [0, 1]` of the motion from `x` by
    /// `dx` such that the motion from `x` to `x + s∘dx` keeps every pair at
    /// least [`KEEP`] of its gap (the `pairs` module's `truncate`):
    /// [`Contact::value`] and [`Contact::add`] then hold for the points of
    /// that motion, as after [`Contact::limit`].
    pub(crate) fn truncate(&mut self, system: &System, x: &[Vec3], dx: &[Vec3]) -> &[f64] {
        let geometry = Geometry::new(system, &self.obstacles, At::End);
        self.pairs.truncate(
            &geometry,
            (x, dx),
            (KEEP, self.barrier.activation),
            &mut self.scale,
        );
        &self.scale
    }

    /// The proximity queries the pair list ran since the last call, and the
    /// time its collision detection took, in seconds.
    pub(crate) fn take_detection(&mut self) -> (usize, f64) {
        self.pairs.take_detection()
    }

    /// The number of pairs closer than the contact distance at positions
    /// `x` and the smallest gap among them (infinite for none); a gap below
    /// [`CLOSE`]` · d̂` doubles the barrier stiffness for the next step.
    pub(crate) fn end_step(&mut self, system: &System, x: &[Vec3]) -> usize {
        let d_hat = self.barrier.activation;
        let geometry = Geometry::new(system, &self.obstacles, At::End);
        self.pairs.search(&geometry, x, d_hat);
        let (mut count, mut smallest) = (0, f64::INFINITY);
        for pair in self.pairs.iter(&geometry, x, d_hat) {
            let gap = pair.gap(&geometry, x).0;
            if gap < d_hat {
                count += 1;
                smallest = smallest.min(gap);
            }
        }
        self.smallest_gap = self.smallest_gap.min(smallest);
        let kappa = &mut self.barrier.stiffness;
        if smallest < CLOSE * d_hat && *kappa < MAX_STIFFENING * self.kappa_start {
            *kappa *= 2.0;
        }
        count
    }
}
