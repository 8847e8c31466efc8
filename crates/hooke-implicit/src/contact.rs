//! Contacts with obstacles and scripted pins as constraints of the implicit
//! step, after Baraff & Witkin (1998), §5.
//!
//! A scripted pin is a fixed constraint (`Sᵢ = 0`) whose velocity change is
//! prescribed, `zᵢ = pᵢ'(t + h) − vᵢ`, so it ends the step at its path's
//! velocity.
//!
//! At the start of a step of `h` s, a free particle that would be within
//! `margin` of an obstacle at the step's end at its present velocity —
//! `φ + h v_n ≤ margin`, with `φ` the signed distance, `n` the normal and
//! `v_n = (vᵢ − u)·n` its normal velocity relative to the obstacle's `u` —
//! is constrained along `n`: its filter becomes `Sᵢ = I − n nᵀ` and its
//! velocity change in that direction is prescribed,
//! `zᵢ = (u·n + w − vᵢ·n) n`, with the relative normal velocity
//!
//! ```text
//! w = −φ/h       arriving (φ > margin): it lands on the surface at the step's end;
//! w = e·|v_n|    at the surface after landing, or touching it first: the rebound;
//! w = 0          resting on it, sliding over it, or pressed into it by its own body.
//! ```
//!
//! So a contact never leaves a particle inside an obstacle (pushing it out
//! afterwards would store energy in its springs). A particle sliding over a
//! curved obstacle ends each step slightly outside it, moving away; it stays
//! constrained while it stays within the margin (rather than taking a free
//! step into the obstacle and being pushed out, which pumped a resting cloth
//! into a two-step cycle). The step solves for `Δv = y + z` with `S y = y`
//! from `S A y = S (b − A z)`. The constraint's normal impulse is then
//! `λᵢ = n·(A Δv − b)ᵢ`. Negative, the constraint holds the particle down:
//! it is released, for the step's remaining Newton iterations and the next
//! step. Leftover penetration (a particle that arrived during the step) is
//! resolved afterwards by `System::resolve_contacts`.
//!
//! # Friction
//!
//! Coulomb friction is part of every solve. With the tangential relative
//! velocity `v_t = (I − n nᵀ)(vᵢ − u)`, a constrained particle on an
//! obstacle of friction coefficient `μ` receives the friction impulse
//!
//! ```text
//! F(v) = −μλ f₁(|v_t|) v_t/|v_t|,     f₁(s) = min(s/ε, 1),
//! ```
//!
//! Coulomb's law with sticking smoothed into viscous damping below the
//! speed `ε` = 10⁻⁵ m/s (Li et al., *Incremental Potential Contact*,
//! SIGGRAPH 2020, §5): a particle whose tangential load stays below `μλ`
//! creeps at most at `ε`, and one that slides is braked by `μλ` per step.
//! `F` is minus the gradient of the dissipation potential
//!
//! ```text
//! D(v) = μλ f₀(|v_t|),    f₀(s) = s²/2ε (s < ε),  s − ε/2 (s ≥ ε),
//! ```
//!
//! convex in `v`, which joins the step's incremental potential. The normal
//! impulse `λ` is lagged: that of the solve before (the previous step's
//! last solve's for a step's first solve, zero for a particle that was not
//! constrained then). Each solve linearises the friction at its
//! linearisation point `V` as the damping `c = μλ f₁(s)/s`, `s = |v_t(V)|`:
//! in the particle's row
//!
//! ```text
//! (A + c I) Δ = b − c v_t(V),
//! ```
//!
//! so the friction impulse after the solve is `−c v_t(V + Δ)` and acts on
//! the springs within the solve. Below `ε` that is `D`'s exact Hessian;
//! above it, the quadratic that touches `D` at `V` and lies above it, so a
//! Newton step stays a descent direction of `Φ + D` and the line search
//! applies unchanged, and iterating it converges to Coulomb's law. The
//! `c I` term is added to the particle's mass term and diagonal block after
//! `b − A z` is formed; its normal part is filtered out, so it changes
//! neither the solution's normal component nor `λ`.

use hooke_core::{System, Vec3};

use crate::filter::Filter;
use crate::matrix::BlockMatrix;
use crate::solver::Topology;

/// Tangential relative speed below which friction acts as viscous damping
/// (the particle sticks, creeping at most this fast), m/s.
const STICKING: f64 = 1e-5;

/// One constrained particle.
#[derive(Debug, Clone, Copy)]
struct Active {
    normal: Vec3,
    /// The obstacle's velocity `u` during the step.
    velocity: Vec3,
    /// The obstacle's friction coefficient `μ`.
    friction: f64,
}

impl Active {
    /// The tangential part `v_t` of the relative velocity `v − u`.
    fn tangential(&self, v: Vec3) -> Vec3 {
        let relative = v - self.velocity;
        relative - relative.dot(&self.normal) * self.normal
    }
}

/// Which particles are constrained by obstacles, across steps.
#[derive(Debug, Clone, Default)]
pub(crate) struct Contacts {
    active: Vec<Option<Active>>,
    /// Particles whose constraint pulled in the last step: free for one step.
    released: Vec<bool>,
    /// Particles that landed on an obstacle in the last step: the normal
    /// speed they hit it with, for their rebound.
    impact: Vec<f64>,
    /// The normal impulse `λ` of each constrained particle's constraint in
    /// the last solve; zero for the others.
    impulse: Vec<f64>,
    /// The friction bound `μλ` each particle's friction term was built with
    /// for the present solve; zero for particles without friction.
    bound: Vec<f64>,
    /// The prescribed velocity changes `z`.
    pub(crate) prescribed: Vec<Vec3>,
    /// Scratch for `A z` before the solve and `A y` after it.
    product: Vec<Vec3>,
}

impl Contacts {
    /// Chooses the constrained particles at the start of a step of `h` s
    /// from `x`, `v` at `time` (with `touching` from the last step's contact
    /// response), and sets their filters and prescribed velocity changes,
    /// and those of the scripted pins, which end the step at their path's
    /// velocity at `time + h`; returns whether any velocity change is
    /// prescribed.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn begin(
        &mut self,
        system: &System,
        x: &[Vec3],
        v: &[Vec3],
        touching: &[bool],
        time: f64,
        h: f64,
        margin: f64,
        filters: &mut [Filter],
    ) -> bool {
        let n = x.len();
        self.active.resize(n, None);
        self.released.resize(n, false);
        self.impact.resize(n, 0.0);
        self.impulse.resize(n, 0.0);
        self.bound.resize(n, 0.0);
        self.prescribed.resize(n, Vec3::zeros());
        self.product.resize(n, Vec3::zeros());
        let mut any = false;
        for i in 0..n {
            if system.is_pinned(i) {
                continue;
            }
            filters[i] = Filter::Free;
            self.prescribed[i] = Vec3::zeros();
            let was_active = self.active[i].take().is_some();
            let was_free = !was_active && !touching[i];
            let impulse = std::mem::take(&mut self.impulse[i]);
            let impact = std::mem::take(&mut self.impact[i]);
            if std::mem::take(&mut self.released[i]) {
                continue;
            }
            // The obstacle reached deepest within the step, moving as now.
            let reached = system
                .obstacles()
                .iter()
                .enumerate()
                .map(|(k, o)| {
                    let (phi, normal) = o.distance(x[i], time);
                    (k, phi, normal, (v[i] - o.velocity(time)).dot(&normal))
                })
                .filter(|&(_, phi, _, approach)| phi + h * approach <= margin)
                .min_by(|a, b| (a.1 + h * a.3).total_cmp(&(b.1 + h * b.3)));
            let Some((k, phi, normal, approach)) = reached else {
                continue;
            };
            let obstacle = &system.obstacles()[k];
            let relative = if phi > margin {
                // Arriving: land on the surface at the end of the step, and
                // rebound in the next.
                self.impact[i] = -approach;
                -phi / h
            } else if was_free {
                -obstacle.restitution * approach.min(0.0)
            } else {
                obstacle.restitution * impact
            };
            let target = obstacle.velocity(time).dot(&normal) + relative;
            self.prescribed[i] = (target - v[i].dot(&normal)) * normal;
            filters[i] = Filter::Plane(normal);
            self.active[i] = Some(Active {
                normal,
                velocity: obstacle.velocity(time),
                friction: obstacle.friction,
            });
            if was_active {
                self.impulse[i] = impulse;
            }
            any = true;
        }
        for (i, path) in system.pin_paths() {
            self.prescribed[*i] = path.velocity(time + h) - v[*i];
            any = true;
        }
        any
    }

    /// After Newton's iteration on a step of `h` from `x0`, `v0` at `time`
    /// ended at velocities `v` and positions `x`: holds every free particle
    /// that ends the step inside an obstacle as [`Contacts::begin`] holds an
    /// arriving one — its normal velocity, in `v` too, set so that it lands
    /// on the surface (or stays where it is, if it started inside) — and
    /// returns how many it held. The step's iteration then goes on.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn hold_penetrating(
        &mut self,
        system: &System,
        (x0, v0): (&[Vec3], &[Vec3]),
        x: &[Vec3],
        v: &mut [Vec3],
        time: f64,
        h: f64,
        filters: &mut [Filter],
    ) -> usize {
        let mut held = 0;
        for i in 0..x.len() {
            if system.is_pinned(i) || self.active[i].is_some() {
                continue;
            }
            let deepest = system
                .obstacles()
                .iter()
                .map(|o| o.distance(x[i], time + h).0)
                .enumerate()
                .filter(|&(_, depth)| depth < 0.0)
                .min_by(|a, b| a.1.total_cmp(&b.1));
            let Some((k, _)) = deepest else {
                continue;
            };
            let obstacle = &system.obstacles()[k];
            let (phi, normal) = obstacle.distance(x0[i], time);
            let velocity = obstacle.velocity(time);
            let relative = if phi > 0.0 {
                self.impact[i] = -(v0[i] - velocity).dot(&normal);
                -phi / h
            } else {
                0.0
            };
            let target = velocity.dot(&normal) + relative;
            self.prescribed[i] = (target - v0[i].dot(&normal)) * normal;
            v[i] += (target - v[i].dot(&normal)) * normal;
            filters[i] = Filter::Plane(normal);
            self.active[i] = Some(Active {
                normal,
                velocity,
                friction: obstacle.friction,
            });
            self.released[i] = false;
            held += 1;
        }
        held
    }

    /// The particles held by obstacles in the present step, with the
    /// obstacles' velocities.
    pub(crate) fn held(&self) -> impl Iterator<Item = (usize, Vec3)> + Clone + '_ {
        self.active
            .iter()
            .enumerate()
            .filter_map(|(i, a)| a.map(|a| (i, a.velocity)))
    }

    /// Makes the solve's unknown the free part `y` of `Δv = y + z`: `b ← b −
    /// A z`.
    pub(crate) fn prescribe(&mut self, a: &BlockMatrix, b: &mut [Vec3]) {
        a.apply(&self.prescribed, &mut self.product);
        for (bi, azi) in b.iter_mut().zip(&self.product) {
            *bi -= azi;
        }
    }

    /// Adds the linearised friction of the constrained particles at the
    /// velocities `v` to the system last assembled, `A ← A + c I` and `b ←
    /// b − c v_t` in each one's row, with `c = μλ f₁(|v_t|)/|v_t|` and `λ` the
    /// last solve's normal impulse; see the module docs.
    pub(crate) fn add_friction(&mut self, topology: &mut Topology, v: &[Vec3], b: &mut [Vec3]) {
        for (i, active) in self.active.iter().enumerate() {
            self.bound[i] = 0.0;
            let Some(active) = active else {
                continue;
            };
            let bound = active.friction * self.impulse[i];
            if bound > 0.0 {
                let tangential = active.tangential(v[i]);
                let c = bound / tangential.norm().max(STICKING);
                topology.add_to_diagonal(i, c);
                b[i] -= c * tangential;
                self.bound[i] = bound;
            }
        }
    }

    /// The friction's dissipation potential `D(v) = Σ μλ f₀(|v_t|)` at the
    /// velocities `v`, with the bounds `μλ` of the last friction terms
    /// added: the term of the step's incremental potential whose gradient
    /// is the friction impulse.
    pub(crate) fn dissipation(&self, v: &[Vec3]) -> f64 {
        self.active
            .iter()
            .zip(&self.bound)
            .zip(v)
            .filter_map(|((active, &bound), &v)| {
                let speed = active.as_ref()?.tangential(v).norm();
                Some(
                    bound
                        * if speed < STICKING {
                            0.5 * speed * speed / STICKING
                        } else {
                            speed - 0.5 * STICKING
                        },
                )
            })
            .sum()
    }

    /// After a solve of a step, `S A x = S b` (the first with `x = y` and
    /// `b = b − A z`, a Newton iteration with its correction): records the
    /// constraints' normal impulses `λ = n·(A x − b)` for the next solve's
    /// friction, and frees the particles whose constraint pulls them towards
    /// the obstacle (`λ < 0`) for the rest of this step (further Newton
    /// iterations let them go) and the next.
    pub(crate) fn release(
        &mut self,
        a: &BlockMatrix,
        y: &[Vec3],
        b: &[Vec3],
        filters: &mut [Filter],
    ) {
        a.apply(y, &mut self.product);
        for (i, active) in self.active.iter_mut().enumerate() {
            let Some(Active { normal, .. }) = *active else {
                continue;
            };
            let impulse = normal.dot(&(self.product[i] - b[i]));
            self.impulse[i] = impulse.max(0.0);
            if impulse < 0.0 {
                *active = None;
                filters[i] = Filter::Free;
                self.released[i] = true;
            }
        }
    }
}
