//! Force and acceleration evaluation, `a = M⁻¹ f(x, v)`, sequential or
//! data-parallel.
//!
//! The sequential path makes one pass over the springs and scatters each
//! spring force to its two ends. Scattering in parallel would race, so the
//! parallel path (feature `parallel`) makes two passes instead: every spring
//! force is computed once into a buffer, then every particle gathers the forces
//! of its incident springs through a precomputed incidence list. Both passes
//! are free of races and of atomics, and the result differs from the
//! sequential one only by the order of floating-point additions.

use crate::{System, Vec3};

/// Which evaluation path a [`ForceEvaluator`] takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Parallelism {
    /// Parallel for systems with at least [`PARALLEL_MIN_SPRINGS`] springs
    /// when the `parallel` feature is on, sequential otherwise.
    #[default]
    Auto,
    /// Always the sequential scatter.
    Sequential,
    /// Always the parallel compute-then-gather (sequential when the
    /// `parallel` feature is off).
    Parallel,
}

/// Spring count from which [`Parallelism::Auto`] evaluates in parallel. Below
/// it the two-pass gather costs more than it gains on two cores (see
/// `benches/explicit.rs`).
pub const PARALLEL_MIN_SPRINGS: usize = 20_000;

/// Evaluates forces and accelerations of a [`System`], owning the scratch the
/// parallel path needs so that evaluation allocates nothing once warm.
#[derive(Debug, Clone, Default)]
pub struct ForceEvaluator {
    parallelism: Parallelism,
    #[cfg(feature = "parallel")]
    spring_forces: Vec<Vec3>,
}

impl ForceEvaluator {
    /// An evaluator that takes the given path.
    #[must_use]
    pub fn new(parallelism: Parallelism) -> Self {
        Self {
            parallelism,
            #[cfg(feature = "parallel")]
            spring_forces: Vec::new(),
        }
    }

    /// The path this evaluator takes.
    #[must_use]
    pub fn parallelism(&self) -> Parallelism {
        self.parallelism
    }

    /// Total force `fᵢ` on every particle, pinned ones included (for those it
    /// is the force the pin resists).
    ///
    /// # Panics
    /// If `x`, `v` or `f` does not have one entry per particle of `system`:
    /// these are an integrator's own buffers, sized from a checked state.
    pub fn forces(&mut self, system: &System, x: &[Vec3], v: &[Vec3], f: &mut [Vec3]) {
        let n = system.particle_count();
        assert!(
            x.len() == n && v.len() == n && f.len() == n,
            "force buffers must have one entry per particle ({n}): x {}, v {}, f {}",
            x.len(),
            v.len(),
            f.len()
        );
        #[cfg(feature = "parallel")]
        if self.use_parallel(system) {
            return self.parallel_forces(system, x, v, f);
        }
        sequential_forces(system, x, v, f);
    }

    /// Accelerations `aᵢ = fᵢ/mᵢ`, zero for pinned particles.
    ///
    /// # Panics
    /// As [`ForceEvaluator::forces`].
    pub fn accelerations(&mut self, system: &System, x: &[Vec3], v: &[Vec3], a: &mut [Vec3]) {
        self.forces(system, x, v, a);
        for (ai, &w) in a.iter_mut().zip(system.inverse_masses()) {
            // Pinned (w = 0) exactly, even where the force overflowed.
            *ai = if w == 0.0 { Vec3::zeros() } else { *ai * w };
        }
    }

    #[cfg(feature = "parallel")]
    fn use_parallel(&self, system: &System) -> bool {
        match self.parallelism {
            Parallelism::Auto => system.springs().len() >= PARALLEL_MIN_SPRINGS,
            Parallelism::Sequential => false,
            Parallelism::Parallel => true,
        }
    }

    #[cfg(feature = "parallel")]
    fn parallel_forces(&mut self, system: &System, x: &[Vec3], v: &[Vec3], f: &mut [Vec3]) {
        use rayon::prelude::*;
        const MIN_CHUNK: usize = 1024;
        self.spring_forces
            .resize(system.springs().len(), Vec3::zeros());
        self.spring_forces
            .par_iter_mut()
            .zip(system.springs().par_iter())
            .with_min_len(MIN_CHUNK)
            .for_each(|(fs, s)| *fs = s.force(x[s.i], x[s.j], v[s.i], v[s.j]));
        let spring_forces = &self.spring_forces;
        f.par_iter_mut()
            .enumerate()
            .with_min_len(MIN_CHUNK)
            .for_each(|(i, fi)| {
                *fi = external_force(system, i, v[i]);
                for &(spring, sign) in system.incidence.of(i) {
                    *fi += sign * spring_forces[spring];
                }
            });
    }
}

/// Gravity and air damping on particle `i`.
#[inline]
fn external_force(system: &System, i: usize, vi: Vec3) -> Vec3 {
    let mut f = system
        .gravity
        .map_or_else(Vec3::zeros, |g| system.masses[i] * g);
    if let Some(gamma) = system.air_damping {
        f -= gamma * vi;
    }
    f
}

fn sequential_forces(system: &System, x: &[Vec3], v: &[Vec3], f: &mut [Vec3]) {
    for (i, fi) in f.iter_mut().enumerate() {
        *fi = external_force(system, i, v[i]);
    }
    for s in system.springs() {
        let fs = s.force(x[s.i], x[s.j], v[s.i], v[s.j]);
        f[s.i] += fs;
        f[s.j] -= fs;
    }
}

/// For every particle, the springs it ends, with the sign of the spring force
/// on it (`+1` at end `i`, `−1` at end `j`), in compressed-row form.
#[cfg(feature = "parallel")]
#[derive(Debug, Clone, Default)]
pub(crate) struct Incidence {
    offsets: Vec<usize>,
    entries: Vec<(usize, f64)>,
}

#[cfg(feature = "parallel")]
impl Incidence {
    pub(crate) fn new(particles: usize, springs: &[crate::Spring]) -> Self {
        let mut offsets = vec![0; particles + 1];
        for s in springs {
            offsets[s.i + 1] += 1;
            offsets[s.j + 1] += 1;
        }
        for p in 0..particles {
            offsets[p + 1] += offsets[p];
        }
        let mut next = offsets.clone();
        let mut entries = vec![(0, 0.0); 2 * springs.len()];
        for (k, s) in springs.iter().enumerate() {
            for (p, sign) in [(s.i, 1.0), (s.j, -1.0)] {
                entries[next[p]] = (k, sign);
                next[p] += 1;
            }
        }
        Self { offsets, entries }
    }

    fn of(&self, particle: usize) -> &[(usize, f64)] {
        &self.entries[self.offsets[particle]..self.offsets[particle + 1]]
    }
}
