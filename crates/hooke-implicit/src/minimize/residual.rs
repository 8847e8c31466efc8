//! The incremental potential and its gradient together, without the
//! matrix: what a quasi-Newton iteration needs of the system at each
//! iterate and at the line search's extrapolated points.

use hooke_core::{StepError, System, Vec3};

use crate::linear::pattern::Pattern;
use crate::linear::vector::for_each_row;
use crate::minimize::assembly::{Assembler, Potential};
use crate::minimize::potential::{particles_potential, spring_potential};
use crate::minimize::volume::volume_energy_and_forces;

/// Where to evaluate: positions `x = x̃ + βh v`, velocities `v` and the
/// predictor's `ṽ`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Point<'a> {
    pub(crate) x: &'a [Vec3],
    pub(crate) v: &'a [Vec3],
    pub(crate) v_tilde: &'a [Vec3],
    pub(crate) beta_h: f64,
}

impl Assembler {
    /// `Φ(v)` and its rounding level, as [`Assembler::potential`] gives
    /// them, and `b = −∇Φ(v) = M(ṽ − v) + βh f(x, v)` with the springs'
    /// elastic forces, their dampers' along the frozen directions, gravity,
    /// air damping and the volume elements' forces (the right-hand side
    /// [`Assembler::assemble`] gives at a Newton iterate): one pass over
    /// the springs for both, each spring's length computed once, in the
    /// race-free chunks of assembly, and one over the particles.
    pub(crate) fn evaluate(
        &mut self,
        system: &System,
        pattern: &Pattern,
        point: Point<'_>,
        b: &mut [Vec3],
    ) -> Potential {
        let n = system.particle_count();
        if n == 0 {
            return Potential {
                value: 0.0,
                rounding: 0.0,
            };
        }
        let Point {
            x,
            v,
            v_tilde,
            beta_h,
        } = point;
        let chunk = self.chunks(pattern, n);
        let (springs, directions, touched) = (system.springs(), &self.directions, &self.touched);
        // Per chunk: the forces into its accumulator, and the springs'
        // energy and its rounding level (as in `Assembler::potential`).
        let work = |p: usize, rhs: &mut [Vec3]| {
            rhs[touched[p].clone()].fill(Vec3::zeros());
            let (mut energy, mut rounding) = (0.0, 0.0);
            let slots = p * chunk..((p + 1) * chunk).min(pattern.slots());
            for t in slots {
                let s = &springs[pattern.spring(t)];
                let (xi, xj) = (x[s.i], x[s.j]);
                let (stretch, mut force) = s.stretch_and_force(xi, xj);
                let mut rate = 0.0;
                if s.damping > 0.0 {
                    let d = directions[t];
                    rate = d.dot(&(v[s.i] - v[s.j]));
                    force -= s.damping * rate * d;
                }
                let (e, r) = spring_potential(s, (xi, xj), stretch, rate, beta_h);
                energy += e;
                rounding += r;
                rhs[s.i] += force;
                rhs[s.j] -= force;
            }
            (energy, rounding)
        };
        let add = |a: (f64, f64), b: (f64, f64)| (a.0 + b.0, a.1 + b.1);
        #[cfg(feature = "parallel")]
        let (springs_energy, springs_rounding) = if self.touched.len() > 1 {
            use rayon::prelude::*;
            self.rhs
                .par_chunks_mut(n)
                .enumerate()
                .map(|(p, rhs)| work(p, rhs))
                .reduce(|| (0.0, 0.0), add)
        } else {
            work(0, &mut self.rhs)
        };
        #[cfg(not(feature = "parallel"))]
        let (springs_energy, springs_rounding) = self
            .rhs
            .chunks_mut(n)
            .enumerate()
            .map(|(p, rhs)| work(p, rhs))
            .fold((0.0, 0.0), add);

        let (masses, gravity) = (system.masses(), system.gravity());
        let g = gravity.unwrap_or_else(Vec3::zeros);
        let gamma = system.air_damping().unwrap_or(0.0);
        let (accumulated, touched) = (&self.rhs, &self.touched);
        for_each_row(b, |i, bi| {
            let mut force = masses[i] * g - gamma * v[i];
            for (p, rows) in touched.iter().enumerate() {
                if rows.contains(&i) {
                    force += accumulated[p * n + i];
                }
            }
            *bi = masses[i] * (v_tilde[i] - v[i]) + beta_h * force;
        });
        let (particles, particles_magnitude) = particles_potential(system, x, v, v_tilde, beta_h);
        let (volume, volume_rounding) = if system.tets().is_empty() {
            (0.0, 0.0)
        } else {
            self.volume_rhs.clear();
            self.volume_rhs.resize(n, Vec3::zeros());
            let terms = volume_energy_and_forces(system, x, &mut self.volume_rhs);
            let forces = &self.volume_rhs;
            for_each_row(b, |i, bi| *bi += beta_h * forces[i]);
            terms
        };
        Potential {
            value: particles + springs_energy + volume,
            rounding: f64::EPSILON * (particles_magnitude + springs_rounding + volume_rounding),
        }
    }
}

/// Checks a residual `b`.
///
/// # Errors
/// [`StepError::NonFiniteSystem`] at `time` naming the first free particle
/// whose residual is not finite.
pub(crate) fn check_finite(system: &System, b: &[Vec3], time: f64) -> Result<(), StepError> {
    let bad = (0..b.len()).find(|&i| !system.is_pinned(i) && !b[i].iter().all(|c| c.is_finite()));
    match bad {
        None => Ok(()),
        Some(particle) => Err(StepError::NonFiniteSystem { time, particle }),
    }
}
