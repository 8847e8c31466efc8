//! Contacts with obstacles and scripted pins as constraints of the implicit
//! step, after Baraff & Witkin (1998), §5.
//!
//! A scripted pin is a fixed constraint (`Sᵢ = 0`) whose velocity change is
//! prescribed, `zᵢ = pᵢ'(t + h) − vᵢ`, so it ends the step at its path's
//! velocity.
//!
//! At the start of a step of `h` s, a free particle that would reach an
//! obstacle within the step at its present velocity — `φ + h min(v_n, 0) ≤
//! margin`, with `φ` the signed distance, `n` the normal and
//! `v_n = (vᵢ − u)·n` its normal velocity relative to the obstacle's `u` —
//! is constrained along `n`: its filter becomes `Sᵢ = I − n nᵀ` and its
//! velocity change in that direction is prescribed,
//! `zᵢ = (u·n + w − vᵢ·n) n`, with the relative normal velocity
//!
//! ```text
//! w = −φ/h       arriving (φ > margin): it lands on the surface at the step's end;
//! w = e·|v_n|    at the surface after landing, or touching it first: the rebound;
//! w = 0          resting on it, or pressed into it by its own body.
//! ```
//!
//! So a contact never leaves a particle inside an obstacle (pushing it out
//! afterwards would store energy in its springs), and the particle slides
//! freely in the tangent plane. The step solves for `Δv = y + z` with `S y = y` from
//! `S A y = S (b − A z)`. The constraint's normal impulse is then
//! `λᵢ = n·(A Δv − b)ᵢ`. Negative, the constraint holds the particle down:
//! it is released, for the step's remaining Newton iterations and the next
//! step. Positive, the obstacle pushes, and after the last iteration Coulomb
//! friction takes up to `μ λᵢ / mᵢ` of the particle's tangential relative
//! speed. Leftover penetration (a particle that arrived during the step) is
//! resolved afterwards by `System::resolve_contacts`.

use hooke_core::{System, Vec3};

use crate::filter::Filter;
use crate::matrix::BlockMatrix;

/// Relative normal speed below which a particle counts as resting, m/s.
const RESTING: f64 = 1e-9;

/// One constrained particle.
#[derive(Debug, Clone, Copy)]
struct Active {
    obstacle: usize,
    normal: Vec3,
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
    /// The prescribed velocity changes `z`.
    pub(crate) prescribed: Vec<Vec3>,
    /// Scratch for `A z` before the solve and `A y` after it.
    pub(crate) product: Vec<Vec3>,
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
        self.prescribed.resize(n, Vec3::zeros());
        self.product.resize(n, Vec3::zeros());
        let mut any = false;
        for i in 0..n {
            if system.is_pinned(i) {
                continue;
            }
            filters[i] = Filter::Free;
            self.prescribed[i] = Vec3::zeros();
            let was_free = self.active[i].take().is_none() && !touching[i];
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
                .filter(|&(_, phi, _, approach)| {
                    approach <= RESTING && phi + h * approach.min(0.0) <= margin
                })
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
                obstacle: k,
                normal,
            });
            any = true;
        }
        for (i, path) in system.pin_paths() {
            self.prescribed[*i] = path.velocity(time + h) - v[*i];
            any = true;
        }
        any
    }

    /// After a solve of a step, `S A x = S b` (the first with `x = y` and
    /// `b = b − A z`, a Newton iteration with its correction): frees the
    /// particles whose constraint pulls them towards the obstacle
    /// (`λ = n·(A x − b) < 0`) for the rest of this step (further Newton
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
            if let Some(Active { normal, .. }) = *active
                && normal.dot(&(self.product[i] - b[i])) < 0.0
            {
                *active = None;
                filters[i] = Filter::Free;
                self.released[i] = true;
            }
        }
    }

    /// After the last solve of a step, `S A x = S b`: Coulomb friction on
    /// the new velocities `v` of the constrained particles, with the normal
    /// impulses `λ = n·(A x − b)` of that solve.
    pub(crate) fn friction(
        &mut self,
        system: &System,
        a: &BlockMatrix,
        x: &[Vec3],
        b: &[Vec3],
        time: f64,
        v: &mut [Vec3],
    ) {
        a.apply(x, &mut self.product);
        let masses = system.masses();
        for (i, active) in self.active.iter().enumerate() {
            let Some(Active { obstacle, normal }) = *active else {
                continue;
            };
            let impulse = normal.dot(&(self.product[i] - b[i])).max(0.0);
            let obstacle = &system.obstacles()[obstacle];
            let relative = v[i] - obstacle.velocity(time);
            let tangential = relative - relative.dot(&normal) * normal;
            let speed = tangential.norm();
            if speed > 0.0 {
                let kept = (1.0 - obstacle.friction * impulse / (masses[i] * speed)).max(0.0);
                v[i] -= (1.0 - kept) * tangential;
            }
        }
    }
}
