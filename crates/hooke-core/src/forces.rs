//! Force and acceleration evaluation, `a = M⁻¹ f(x, v)`, sequential or
//! data-parallel.
//!
//! The springs, volume elements, gravity and air damping are summed in
//! fused passes of their own; the system's own terms
//! ([`System::terms`]) then add theirs through
//! [`Term::force`](crate::Term::force).
//!
//! The sequential path makes one pass over the springs and scatters each
//! spring force to its two ends. Scattering from several threads into one
//! array would race, so the parallel path (feature `parallel`) splits the
//! springs into one contiguous chunk per thread: the first chunk scatters into
//! the output, every other chunk into a private buffer, and the buffers are
//! then added in, particle by particle. No atomics and no locks; the result
//! differs from the sequential one only in the order of floating-point
//! additions.
//!
//! Measured on two cores with `cargo bench --bench explicit -- forces` on
//! [`Sheet`](crate::reference::Sheet) cloths: below about 5·10⁴ springs the
//! parallel path gains nothing (waking a worker thread costs tens of
//! microseconds, as much as evaluating a 32×32 cloth); from 10⁵ springs on it
//! is 1.3–1.7× faster, limited by the extra buffer traffic.
//! [`Parallelism::Auto`] switches at [`PARALLEL_MIN_SPRINGS`].
//!
//! The parallel path allocates nothing once its per-chunk buffers are
//! sized, when it is called from a thread of rayon's pool: its jobs then go
//! to that worker's own deque, whose buffer never grows at this fan-out. A
//! call from a thread outside the pool hands its first job to rayon's
//! global injector, a linked list of blocks that allocates a new block
//! every 63 jobs. A program that needs allocation-free parallel steps
//! makes the stepping thread a worker, e.g. with
//! `rayon::ThreadPoolBuilder::new().use_current_thread().build_global()`
//! before any parallel work (as `tests/no_allocation.rs` does), or steps
//! inside `ThreadPool::install`.

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

/// Spring count from which [`Parallelism::Auto`] evaluates in parallel (see
/// the module documentation for the measurement).
pub const PARALLEL_MIN_SPRINGS: usize = 50_000;

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
        if system.particle_count() == 0 || system.springs().is_empty() {
            return false;
        }
        match self.parallelism {
            Parallelism::Auto => system.springs().len() >= PARALLEL_MIN_SPRINGS,
            Parallelism::Sequential => false,
            Parallelism::Parallel => true,
        }
    }

    #[cfg(feature = "parallel")]
    fn parallel_forces(&mut self, system: &System, x: &[Vec3], v: &[Vec3], f: &mut [Vec3]) {
        use rayon::prelude::*;
        let n = system.particle_count();
        let springs = system.springs();
        let chunk = springs
            .len()
            .div_ceil(rayon::current_num_threads().max(2))
            .max(1);
        let (own, others) = springs.split_at(chunk.min(springs.len()));
        self.spring_forces
            .resize(others.len().div_ceil(chunk) * n, Vec3::zeros());
        let buffers = &mut self.spring_forces;
        rayon::join(
            || {
                external_forces(system, v, f);
                scatter(own, x, v, f);
                system.add_volume_forces(x, f);
            },
            || {
                buffers
                    .par_chunks_mut(n)
                    .zip(others.par_chunks(chunk))
                    .for_each(|(buffer, part)| {
                        buffer.fill(Vec3::zeros());
                        scatter(part, x, v, buffer);
                    });
            },
        );
        let buffers = &self.spring_forces;
        f.par_iter_mut()
            .enumerate()
            .with_min_len(4096)
            .for_each(|(i, fi)| {
                *fi += buffers.iter().skip(i).step_by(n).sum::<Vec3>();
            });
        add_term_forces(system, x, v, f);
    }
}

impl System {
    /// Adds the springs' forces, elastic and damping, at positions `x` and
    /// velocities `v` to `f`, as [`ForceEvaluator`]'s sequential pass does.
    ///
    /// # Panics
    /// If a spring names a particle beyond `x`, `v` or `f`.
    pub fn add_spring_forces(&self, x: &[Vec3], v: &[Vec3], f: &mut [Vec3]) {
        scatter(&self.springs, x, v, f);
    }
}

/// Adds the forces of the system's own terms ([`System::terms`]).
fn add_term_forces(system: &System, x: &[Vec3], v: &[Vec3], f: &mut [Vec3]) {
    for term in system.terms() {
        term.force(system, x, v, f);
    }
}

/// Sets `f` to gravity and air damping on every particle.
fn external_forces(system: &System, v: &[Vec3], f: &mut [Vec3]) {
    let gravity = system.gravity;
    for ((fi, vi), &m) in f.iter_mut().zip(v).zip(&system.masses) {
        *fi = gravity.map_or_else(Vec3::zeros, |g| m * g);
        if let Some(gamma) = system.air_damping {
            *fi -= gamma * vi;
        }
    }
}

/// Adds the forces of `springs` to `f`.
///
/// Springs usually come in runs that share their first particle (a mesh
/// builder adds a particle's springs together): summing a run in a register
/// avoids a chain of dependent read-modify-writes of the same `f[i]`.
fn scatter(springs: &[crate::Spring], x: &[Vec3], v: &[Vec3], f: &mut [Vec3]) {
    let Some(first) = springs.first() else { return };
    let (mut run, mut sum) = (first.i, Vec3::zeros());
    for s in springs {
        if s.i != run {
            f[run] += sum;
            (run, sum) = (s.i, Vec3::zeros());
        }
        let fs = s.force(x[s.i], x[s.j], v[s.i], v[s.j]);
        sum += fs;
        f[s.j] -= fs;
    }
    f[run] += sum;
}

fn sequential_forces(system: &System, x: &[Vec3], v: &[Vec3], f: &mut [Vec3]) {
    external_forces(system, v, f);
    system.add_spring_forces(x, v, f);
    system.add_volume_forces(x, f);
    add_term_forces(system, x, v, f);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::SystemBuilder;

    /// Systems without particles or without springs take the sequential path
    /// whatever is asked.
    #[test]
    fn parallel_request_on_empty_systems_is_safe() {
        let empty = SystemBuilder::new().build().unwrap();
        ForceEvaluator::new(Parallelism::Parallel).forces(&empty, &[], &[], &mut []);
        let mut b = SystemBuilder::new();
        b.particle(2.0, [0.0; 3]);
        b.gravity([0.0, -1.0, 0.0]);
        let lone = b.build().unwrap();
        let mut f = [Vec3::zeros()];
        ForceEvaluator::new(Parallelism::Parallel).forces(
            &lone,
            &[Vec3::zeros()],
            &[Vec3::zeros()],
            &mut f,
        );
        assert_eq!(f[0], Vec3::new(0.0, -2.0, 0.0));
    }
}
