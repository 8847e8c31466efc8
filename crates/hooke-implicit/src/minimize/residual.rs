//! The gradient of the incremental potential alone, without the matrix:
//! what a quasi-Newton iteration needs of the system at each iterate.

use hooke_core::{StepError, System, Vec3};

use crate::linear::pattern::Pattern;
use crate::linear::vector::for_each_row;
use crate::minimize::assembly::Assembler;

/// Where to evaluate the residual: positions `x = x̃ + βh v`, velocities
/// `v` and the inertia term `M(ṽ − v)`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Point<'a> {
    pub(crate) x: &'a [Vec3],
    pub(crate) v: &'a [Vec3],
    pub(crate) inertia: &'a [Vec3],
    pub(crate) beta_h: f64,
}

impl Assembler {
    /// `b = −∇Φ(v) = M(ṽ − v) + βh f(x, v)` with the springs' elastic forces,
    /// their dampers' along the frozen directions, gravity, air damping and
    /// the volume elements' forces (the right-hand side [`Assembler::assemble`]
    /// gives at a Newton iterate), in the same two race-free passes.
    ///
    /// # Errors
    /// [`StepError::NonFiniteSystem`] naming the first free particle whose
    /// residual is not finite.
    pub(crate) fn residual(
        &mut self,
        system: &System,
        pattern: &Pattern,
        point: Point<'_>,
        b: &mut [Vec3],
        time: f64,
    ) -> Result<(), StepError> {
        let n = system.particle_count();
        if n == 0 {
            return Ok(());
        }
        let Point {
            x,
            v,
            inertia,
            beta_h,
        } = point;
        let chunk = self.chunks(pattern, n);
        let (springs, directions, touched) = (system.springs(), &self.directions, &self.touched);
        let work = |p: usize, rhs: &mut [Vec3]| {
            rhs[touched[p].clone()].fill(Vec3::zeros());
            let slots = p * chunk..((p + 1) * chunk).min(pattern.slots());
            for t in slots {
                let s = &springs[pattern.spring(t)];
                let mut force = s.elastic_force(x[s.i], x[s.j]);
                if s.damping > 0.0 {
                    let e = directions[t];
                    force -= s.damping * e.dot(&(v[s.i] - v[s.j])) * e;
                }
                rhs[s.i] += force;
                rhs[s.j] -= force;
            }
        };
        #[cfg(feature = "parallel")]
        if self.touched.len() > 1 {
            use rayon::prelude::*;
            self.rhs
                .par_chunks_mut(n)
                .enumerate()
                .for_each(|(p, rhs)| work(p, rhs));
        } else {
            work(0, &mut self.rhs);
        }
        #[cfg(not(feature = "parallel"))]
        for (p, rhs) in self.rhs.chunks_mut(n).enumerate() {
            work(p, rhs);
        }

        let (masses, gravity) = (system.masses(), system.gravity());
        let gamma = system.air_damping().unwrap_or(0.0);
        let (accumulated, touched) = (&self.rhs, &self.touched);
        for_each_row(b, |i, bi| {
            let mut force = gravity.map_or_else(Vec3::zeros, |g| masses[i] * g) - gamma * v[i];
            for (p, rows) in touched.iter().enumerate() {
                if rows.contains(&i) {
                    force += accumulated[p * n + i];
                }
            }
            *bi = inertia[i] + beta_h * force;
        });
        if !system.tets().is_empty() {
            self.volume_rhs.clear();
            self.volume_rhs.resize(n, Vec3::zeros());
            system.add_volume_forces(x, &mut self.volume_rhs);
            let volume = &self.volume_rhs;
            for_each_row(b, |i, bi| *bi += beta_h * volume[i]);
        }
        match (0..n).find(|&i| !system.is_pinned(i) && !b[i].iter().all(|c| c.is_finite())) {
            None => Ok(()),
            Some(particle) => Err(StepError::NonFiniteSystem { time, particle }),
        }
    }
}
