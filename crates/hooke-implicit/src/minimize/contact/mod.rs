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
//! `Φ` stays finite. Contacts never enter or leave the iteration as
//! constraints: `Φ` keeps its shape from one iterate to the next.
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
//! and the contact's tangent plane are taken at the step's start. The
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
mod limit;
mod obstacles;
mod pairs;

use hooke_core::{State, System, Vec3, collision::barrier::barrier};

use crate::linear::matrix::HessianBlocks;
use friction::{FrictionModel, Lagged};
use obstacles::{Obstacles, lag_friction};
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
    /// The pairs of colliding surfaces, in a system that has them.
    pairs: Option<Pairs>,
    /// The barrier stiffness `κ` and its starting value.
    kappa: f64,
    kappa_start: f64,
    /// The contact distance `d̂`.
    activation: f64,
    /// The friction's sticking speed `ε`.
    sticking: f64,
    /// The step's length `h`.
    step: f64,
    friction: Vec<Lagged>,
    /// The friction's Hessian in Newton's model for the rest of the step.
    friction_model: FrictionModel,
    /// The feasible positions the step starts from.
    start: Vec<Vec3>,
    /// The part of a motion the obstacles allow, for the pairs' check
    /// ([`Contact::limit`]).
    shortened: Vec<Vec3>,
    /// The smallest gap seen at the end of an accepted step so far.
    pub(crate) smallest_gap: f64,
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
            self.activation = system.contact_distance();
            let masses = system.masses();
            let mean = masses.iter().sum::<f64>() / masses.len().max(1) as f64;
            let g = system.gravity().map_or(0.0, |g| g.norm());
            let g = if g > 0.0 { g } else { 9.81 };
            self.kappa_start = mean * g / barrier(0.5 * self.activation, self.activation).1.abs();
            self.kappa = self.kappa_start;
            self.sticking = self.activation;
            self.smallest_gap = f64::INFINITY;
            self.pairs = system.has_surface_contact().then(|| {
                let mut pairs = Pairs::default();
                pairs.begin(system);
                pairs
            });
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
        let time = state.time();
        let inside = |i: usize, x: &Vec3| {
            !system.is_pinned(i)
                && system
                    .obstacles()
                    .iter()
                    .any(|o| self.obstacles.gap_at(o, i, *x, time).0 <= 0.0)
        };
        let Some(first) = state
            .positions()
            .iter()
            .enumerate()
            .position(|(i, x)| inside(i, x))
        else {
            return 0;
        };
        let d_hat = self.activation;
        let mut moved = 0;
        for (i, x) in state.positions_mut().iter_mut().enumerate().skip(first) {
            if system.is_pinned(i) {
                continue;
            }
            for o in system.obstacles() {
                let (gap, normal) = self.obstacles.gap_at(o, i, *x, time);
                if gap <= 0.0 {
                    *x += (0.5 * d_hat - gap) * normal;
                    moved += 1;
                }
            }
        }
        moved
    }

    /// Sets up a step of `h` from `x0` at `time`: the obstacles at the
    /// step's end, the lagged friction, and the feasible positions the step
    /// starts from ([`Contact::start`]).
    pub(crate) fn begin(&mut self, system: &System, x0: &[Vec3], time: f64, h: f64) {
        let fresh = self.setup(system);
        self.obstacles.begin(system, time, h, fresh);
        self.step = h;
        self.friction.clear();
        self.friction_model = FrictionModel::Exact;
        self.start.clear();
        self.start.extend_from_slice(x0);
        let d_hat = self.activation;
        for (i, x) in self.start.iter_mut().enumerate() {
            if system.is_pinned(i) {
                continue;
            }
            for (k, o) in system.obstacles().iter().enumerate() {
                let moved = self.obstacles.moved()[k];
                if moved != Vec3::zeros() && self.obstacles.gap_at(o, i, x0[i], time).0 < d_hat {
                    *x += moved;
                    break;
                }
            }
            for k in 0..self.obstacles.len() {
                let (gap, normal) = self.obstacles.gap(k, i, *x);
                if gap <= 0.0 {
                    *x += (0.5 * d_hat - gap) * normal;
                }
            }
            lag_friction(
                &self.obstacles,
                system,
                i,
                x0[i],
                time,
                h,
                (self.kappa, d_hat),
                &mut self.friction,
            );
        }
        if let Some(pairs) = &mut self.pairs {
            pairs.search(system, x0, d_hat);
            pairs.lag_friction(system, x0, (self.kappa, d_hat), &mut self.friction);
        }
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
        let barrier = self.barrier(system, x);
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
        if let Some(pairs) = &mut self.pairs {
            pairs.search(system, x, self.activation);
        }
        self.barrier(system, x)
    }

    /// `κ Σ b(g)` at positions `x` over the pair candidates of the last
    /// search or checked motion.
    fn barrier(&self, system: &System, x: &[Vec3]) -> f64 {
        let d_hat = self.activation;
        let mut sum = 0.0;
        if let Some(pairs) = &self.pairs {
            sum += pairs.energy(system, x, d_hat);
        }
        self.close_gaps(system, x, |_, gap, _| sum += barrier(gap, d_hat).0);
        self.kappa * sum
    }

    /// Calls `f(i, g, n)` for every free particle `i` within the contact
    /// distance of an obstacle at its place at the step's end, with its gap
    /// `g` and the obstacle's normal `n` there.
    fn close_gaps(&self, system: &System, x: &[Vec3], mut f: impl FnMut(usize, f64, Vec3)) {
        for (i, &xi) in x.iter().enumerate() {
            if system.is_pinned(i) {
                continue;
            }
            for k in 0..self.obstacles.len() {
                let (gap, normal) = self.obstacles.gap(k, i, xi);
                if gap < self.activation {
                    f(i, gap, normal);
                }
            }
        }
    }

    /// `κ Σ b(g)` at the positions `x0` of the step's start, the obstacles
    /// at `time` (infinite terms, of particles that started inside an
    /// obstacle, left out).
    pub(crate) fn start_energy(&mut self, system: &System, x0: &[Vec3], time: f64) -> f64 {
        let d_hat = self.activation;
        let mut sum = 0.0;
        if let Some(pairs) = &mut self.pairs {
            pairs.search(system, x0, d_hat);
            let energy = pairs.energy(system, x0, d_hat);
            if energy.is_finite() {
                sum += energy;
            }
        }
        for (i, &xi) in x0.iter().enumerate() {
            if system.is_pinned(i) {
                continue;
            }
            for o in system.obstacles() {
                let gap = self.obstacles.gap_at(o, i, xi, time).0;
                if gap > 0.0 && gap < d_hat {
                    sum += barrier(gap, d_hat).0;
                }
            }
        }
        self.kappa * sum
    }

    /// The work the moving obstacles did on the particles over a step of
    /// `h` from `x0` at `time` to `x`, `v`: the barrier forces at both ends
    /// by the trapezoid rule, and the friction force at the end, times the
    /// obstacles' displacements.
    pub(crate) fn obstacle_work(
        &self,
        system: &System,
        (x0, time): (&[Vec3], f64),
        x: &[Vec3],
        v: &[Vec3],
    ) -> f64 {
        let moved = self.obstacles.moved();
        if moved.iter().all(|m| *m == Vec3::zeros()) {
            return 0.0;
        }
        let d_hat = self.activation;
        let force = |gap: f64, n: Vec3| {
            if gap > 0.0 && gap < d_hat {
                -self.kappa * barrier(gap, d_hat).1 * n
            } else {
                Vec3::zeros()
            }
        };
        let mut work = 0.0;
        for i in 0..x.len() {
            if system.is_pinned(i) {
                continue;
            }
            for (k, o) in system.obstacles().iter().enumerate() {
                if moved[k] == Vec3::zeros() {
                    continue;
                }
                let (g0, n0) = self.obstacles.gap_at(o, i, x0[i], time);
                let (g1, n1) = self.obstacles.gap(k, i, x[i]);
                work += 0.5 * (force(g0, n0) + force(g1, n1)).dot(&moved[k]);
            }
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
        let d_hat = self.activation;
        if let Some(pairs) = &self.pairs {
            pairs.add(system, x, (self.kappa, beta_h, d_hat), b, a);
        }
        let (kb, kbb) = (self.kappa * beta_h, self.kappa * beta_h * beta_h);
        self.close_gaps(system, x, |i, gap, n| {
            let (_, slope, curvature) = barrier(gap, d_hat);
            b[i] -= kb * slope * n;
            a.add_row(
                i,
                crate::linear::block::SymBlock::rank_one_plus_identity(kbb * curvature, n, 0.0),
            );
        });
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
    /// and [`Contact::add`] then hold for the points of this motion: its
    /// swept broad phase found every pair that comes within reach along
    /// it, so a line search needs one broad phase, not one a trial point.
    ///
    /// The obstacles come first, particle by particle: where they stop the
    /// motion at `τ₀ < 1`, the surfaces' pairs are checked along `τ₀ dx`
    /// only, the part of the motion a line search can still take. A
    /// landing body, whose obstacles cut most of its Newton steps short,
    /// then has its surfaces searched along motions a fraction as long:
    /// the pair list covers more of them, and the swept searches it still
    /// needs test smaller boxes. The result is as safe and no shorter than
    /// checking the pairs along the whole motion: a pair's CCD bound is
    /// conservative by an amount that shrinks with the motion.
    pub(crate) fn limit(&mut self, system: &System, x: &[Vec3], dx: &[Vec3]) -> f64 {
        let mut tau: f64 = 1.0;
        for (i, (&xi, &di)) in x.iter().zip(dx).enumerate() {
            if system.is_pinned(i) || di == Vec3::zeros() {
                continue;
            }
            tau = tau.min(self.obstacles.limit(i, xi, di, KEEP));
        }
        let Some(pairs) = &mut self.pairs else {
            return tau;
        };
        if tau <= 0.0 {
            return 0.0;
        }
        let motion = if tau < 1.0 {
            self.shortened.clear();
            self.shortened.extend(dx.iter().map(|d| tau * d));
            &self.shortened
        } else {
            dx
        };
        tau * pairs.limit(system, x, motion, (KEEP, self.activation))
    }

    /// The number of pairs closer than the contact distance at positions
    /// `x` and the smallest gap among them (infinite for none); a gap below
    /// [`CLOSE`]` · d̂` doubles the barrier stiffness for the next step.
    pub(crate) fn end_step(&mut self, system: &System, x: &[Vec3]) -> usize {
        let d_hat = self.activation;
        let (mut count, mut smallest) = (0, f64::INFINITY);
        if let Some(pairs) = &mut self.pairs {
            pairs.search(system, x, d_hat);
            (count, smallest) = pairs.closest(system, x, d_hat);
        }
        self.close_gaps(system, x, |_, gap, _| {
            count += 1;
            smallest = smallest.min(gap);
        });
        self.smallest_gap = self.smallest_gap.min(smallest);
        if smallest < CLOSE * d_hat && self.kappa < MAX_STIFFENING * self.kappa_start {
            self.kappa *= 2.0;
        }
        count
    }
}
