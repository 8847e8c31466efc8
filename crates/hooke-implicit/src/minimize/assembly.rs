//! Assembly of the linearised implicit step into a [`BlockMatrix`] and a
//! right-hand side, in two race-free passes.
//!
//! A step of backward Euler (`β = 1`) or BDF2 (`β = 2/3`) solves
//! `v = ṽ + βh M⁻¹ f(x, v)`, `x = x̃ + βh v` for the new velocity `v`.
//! Linearising the forces at a point `(X, V)`,
//! `f(x, v) ≈ f(X, V) − K (x − X) − C (v − V)` with `K = −∂f/∂x` the
//! stiffness and `C = −∂f/∂v` the damping matrix, gives for `Δ = v − V`
//!
//! ```text
//! (M + βh C + β²h² K) Δ = M(ṽ − V) + βh [f(X, V) − K u],   u = x̃ + βh V − X.
//! ```
//!
//! At `(X, V) = (xₙ, vₙ)` this is Baraff & Witkin's step (for backward Euler
//! `u = h vₙ`, `ṽ = vₙ`); at a Newton iterate `V = vᵏ`, `X = x̃ + βh vᵏ`, so
//! `u = 0` and the right-hand side is minus the residual.
//!
//! Each spring `s = (i, j)` contributes `K_s = βh c d dᵀ + β²h² H_s` and the
//! right-hand-side share `βh [f_s − H_s (uᵢ − uⱼ)]`, built as a symmetric
//! block from the factored Hessian `H_s = k_∥ d dᵀ + k_⊥ (I − d dᵀ)` that
//! `hooke-core` returns. The off-diagonal blocks are `−K_s`, so every block
//! row sums to the mass and air-damping term: the diagonal block is
//! `(mᵢ + βhγ) I + Σ K_s` over the springs at `i`.
//!
//! Pass one splits the springs into one contiguous chunk per thread; each
//! chunk writes its springs' blocks and scatters them, with their
//! right-hand-side shares, into accumulators of its own, so no two threads
//! write the same memory. Pass two, per particle, adds the mass term and the
//! chunks' accumulators, and inverting the diagonal block both checks that it
//! is positive definite and gives the block-Jacobi inverse. Damping directions `d` are frozen at the step's
//! start, as Baraff & Witkin's Jacobian leaves out the damping force's
//! dependence on positions.

use std::ops::Range;
use std::sync::atomic::{AtomicUsize, Ordering};

use hooke_core::{CompressedSprings, StepError, System, Vec3};

use crate::linear::block::SymBlock;
use crate::linear::cg::BlockJacobi;
use crate::linear::matrix::BlockMatrix;
use crate::linear::pattern::Pattern;
use crate::linear::solver::solve::Solve;
use crate::linear::solver::topology::Topology;
use crate::linear::vector::{for_each_row, for_each_row3, spring_chunks, sum2};
use crate::minimize::linearization::Linearization;
use crate::minimize::potential::{particles_potential, spring_potential};
use crate::minimize::volume::{VolumeTerms, volume_energy};

/// The incremental potential at a point and its rounding level.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Potential {
    /// `Φ`.
    pub(crate) value: f64,
    /// How far rounding alone may move `Φ`, in J.
    pub(crate) rounding: f64,
}

/// Assembles linearised steps; keeps the per-spring scratch between calls so
/// that assembly does not allocate.
///
/// ```
/// use hooke_core::{CompressedSprings, Vec3, reference::Sheet};
/// use hooke_implicit::internals::{Assembler, BlockJacobi, BlockMatrix, Linearization, Pattern};
///
/// let system = Sheet::new(4).system()?;
/// let state = system.initial_state();
/// let n = system.particle_count();
/// let mut a = BlockMatrix::zeros(Pattern::new(&system)?);
/// let (mut jacobi, mut b) = (BlockJacobi::default(), vec![Vec3::zeros(); n]);
/// let h = 0.01;
/// let u: Vec<Vec3> = state.velocities().iter().map(|v| h * v).collect();
/// let lin = Linearization {
///     positions: state.positions(),
///     velocities: state.velocities(),
///     displacement: Some(&u),
///     inertia: &vec![Vec3::zeros(); n],
///     beta_h: h,
///     compressed: CompressedSprings::Clamped,
///     freeze_directions: true,
/// };
/// Assembler::default().assemble(&system, &lin, &mut a, &mut jacobi, &mut b, 0.0)?;
/// // At rest under gravity the right-hand side is h·m·g.
/// assert!((b[5] - h * system.masses()[5] * Vec3::new(0.0, -9.81, 0.0)).norm() < 1e-15);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Default)]
pub struct Assembler {
    /// Per chunk of springs: its sums into each particle's diagonal block
    /// and right-hand side.
    pub(super) diagonals: Vec<SymBlock>,
    pub(crate) rhs: Vec<Vec3>,
    /// Per chunk: the rows its springs reach.
    pub(crate) touched: Vec<Range<usize>>,
    /// Per slot: the spring's damping direction, frozen at the step's start.
    pub(crate) directions: Vec<Vec3>,
    /// The volume elements' blocks.
    volume: VolumeTerms,
    /// Per particle: the volume elements' right-hand-side shares.
    pub(crate) volume_rhs: Vec<Vec3>,
}

impl Assembler {
    /// Fills `a`, its block-Jacobi inverse and `b` for the linearisation
    /// `lin` of `system`'s step at time `time`. `a` must have `system`'s
    /// pattern and every slice one entry per particle.
    ///
    /// # Errors
    /// [`StepError::NonFiniteSystem`] naming the first particle whose row or
    /// right-hand side is not finite, or [`StepError::NotPositiveDefinite`]
    /// naming the first free particle whose diagonal block is not positive
    /// definite (then neither is the matrix).
    ///
    /// # Panics
    /// If `a` or a slice does not match `system`'s size.
    pub fn assemble(
        &mut self,
        system: &System,
        lin: &Linearization<'_>,
        a: &mut BlockMatrix,
        jacobi: &mut BlockJacobi,
        b: &mut [Vec3],
        time: f64,
    ) -> Result<(), StepError> {
        let n = system.particle_count();
        let m = system.springs().len();
        a.clear_extra();
        self.directions.resize(m, Vec3::zeros());
        jacobi.inverses.resize(n, SymBlock::default());
        if n == 0 {
            return Ok(());
        }
        let (bh, bh2) = (lin.beta_h, lin.beta_h * lin.beta_h);
        let (x, v) = (lin.positions, lin.velocities);
        let volume = self.volume.add(&mut self.volume_rhs, system, lin, a);

        // Pass one: each chunk of slots writes its springs' blocks and
        // scatters them, with their right-hand-side shares, into its own
        // accumulators.
        let pattern = &a.pattern;
        let chunk = self.chunks(pattern, n);
        self.diagonals
            .resize(self.touched.len() * n, SymBlock::default());
        let springs = system.springs();
        let touched = &self.touched;
        let work = |p: usize,
                    blocks: &mut [SymBlock],
                    frozen: &mut [Vec3],
                    diagonal: &mut [SymBlock],
                    rhs: &mut [Vec3]| {
            diagonal[touched[p].clone()].fill(SymBlock::default());
            rhs[touched[p].clone()].fill(Vec3::zeros());
            for (k, (block, frozen)) in blocks.iter_mut().zip(frozen).enumerate() {
                let s = &springs[pattern.spring(p * chunk + k)];
                let h = s.linearize(x[s.i], x[s.j], lin.compressed);
                let mut shared = h.force;
                if let Some(u) = lin.displacement {
                    shared -= h.apply(u[s.i] - u[s.j]);
                }
                // β²h² H = β²h² [(k_∥ − k_⊥) d dᵀ + k_⊥ I], plus βh c e eᵀ
                // along the damping direction e, which is d unless frozen.
                let mut along = bh2 * (h.axial - h.transverse);
                let mut damping = None;
                if s.damping > 0.0 {
                    if lin.freeze_directions {
                        *frozen = h.direction;
                        along += bh * s.damping;
                    } else {
                        damping = Some(*frozen);
                    }
                    let e = *frozen;
                    shared -= s.damping * e.dot(&(v[s.i] - v[s.j])) * e;
                }
                *block = SymBlock::rank_one_plus_identity(along, h.direction, bh2 * h.transverse);
                if let Some(e) = damping {
                    block.add_assign(&SymBlock::rank_one_plus_identity(bh * s.damping, e, 0.0));
                }
                diagonal[s.i].add_assign(block);
                diagonal[s.j].add_assign(block);
                rhs[s.i] += bh * shared;
                rhs[s.j] -= bh * shared;
            }
        };
        let (blocks, directions) = (&mut a.springs, &mut self.directions);
        if cfg!(feature = "parallel") && self.touched.len() > 1 {
            #[cfg(feature = "parallel")]
            {
                use rayon::prelude::*;
                blocks
                    .par_chunks_mut(chunk)
                    .zip(directions.par_chunks_mut(chunk))
                    .zip(
                        self.diagonals
                            .par_chunks_mut(n)
                            .zip(self.rhs.par_chunks_mut(n)),
                    )
                    .enumerate()
                    .for_each(|(p, ((blocks, frozen), (diagonal, rhs)))| {
                        work(p, blocks, frozen, diagonal, rhs);
                    });
            }
        } else {
            let chunks = blocks
                .chunks_mut(chunk)
                .zip(directions.chunks_mut(chunk))
                .zip(self.diagonals.chunks_mut(n).zip(self.rhs.chunks_mut(n)));
            for (p, ((blocks, frozen), (diagonal, rhs))) in chunks.enumerate() {
                work(p, blocks, frozen, diagonal, rhs);
            }
        }

        // Pass two, per particle: the mass and air-damping terms plus the
        // accumulated springs and volume elements.
        let (masses, gravity, gamma) = (system.masses(), system.gravity(), system.air_damping());
        let air = bh * gamma.unwrap_or(0.0);
        let (diagonals, accumulated) = (&self.diagonals, &self.rhs);
        let (volume_diagonals, volume_rhs) = (&self.volume.diagonals, &self.volume_rhs);
        let non_finite = AtomicUsize::new(usize::MAX);
        let not_definite = AtomicUsize::new(usize::MAX);
        for_each_row3(
            &mut a.diagonal,
            &mut jacobi.inverses,
            b,
            |i, diagonal, inverse, bi| {
                let m = masses[i];
                let mut block = SymBlock::scaled_identity(m + air);
                let mut rhs = lin.inertia[i];
                if let Some(g) = gravity {
                    rhs += bh * m * g;
                }
                if let Some(gamma) = gamma {
                    rhs -= bh * gamma * v[i];
                }
                for (p, rows) in touched.iter().enumerate() {
                    if rows.contains(&i) {
                        block.add_assign(&diagonals[p * n + i]);
                        rhs += accumulated[p * n + i];
                    }
                }
                if volume {
                    block.add_assign(&volume_diagonals[i]);
                    rhs += volume_rhs[i];
                }
                *diagonal = block;
                *bi = rhs;
                if !(block.is_finite() && rhs.iter().all(|c| c.is_finite())) {
                    non_finite.fetch_min(i, Ordering::Relaxed);
                }
                // A principal block of a positive-definite matrix is positive
                // definite; for a free particle the check also yields the
                // block-Jacobi inverse. A pinned particle's row is filtered out.
                match block.inverse_if_positive_definite() {
                    Some(inv) => *inverse = inv,
                    None if system.is_pinned(i) => *inverse = SymBlock::default(),
                    None => {
                        not_definite.fetch_min(i, Ordering::Relaxed);
                    }
                }
            },
        );
        for_each_row(&mut a.mass, |i, mass| *mass = masses[i] + air);
        match (non_finite.into_inner(), not_definite.into_inner()) {
            (usize::MAX, usize::MAX) => Ok(()),
            (usize::MAX, particle) => Err(StepError::NotPositiveDefinite {
                time,
                particle: Some(particle),
            }),
            (particle, _) => Err(StepError::NonFiniteSystem { time, particle }),
        }
    }

    /// Splits the pattern's slots into one contiguous chunk per thread,
    /// records the rows each chunk touches and sizes the chunks'
    /// right-hand-side accumulators; returns the chunk length. The slots are
    /// ordered by their lower row, so a chunk touches only the rows from its
    /// first slot's row to its last slot's row plus the pattern's bandwidth.
    pub(crate) fn chunks(&mut self, pattern: &Pattern, n: usize) -> usize {
        let m = pattern.slots();
        let chunk = m.div_ceil(spring_chunks(m)).max(1);
        let parts = m.div_ceil(chunk);
        self.rhs.resize(parts * n, Vec3::zeros());
        self.touched.clear();
        self.touched.extend((0..parts).map(|p| {
            let (first, last) = (p * chunk, ((p + 1) * chunk).min(m) - 1);
            pattern.row_of(first)..(pattern.row_of(last) + pattern.bandwidth() + 1).min(n)
        }));
        chunk
    }

    /// Freezes the dampers' directions `d = (xᵢ − xⱼ)/|xᵢ − xⱼ|` at the
    /// positions `x`, as a linearisation with `freeze_directions` does,
    /// without assembling.
    pub(crate) fn freeze_directions(&mut self, system: &System, pattern: &Pattern, x: &[Vec3]) {
        let springs = system.springs();
        self.directions.resize(springs.len(), Vec3::zeros());
        for_each_row(&mut self.directions, |t, d| {
            let s = &springs[pattern.spring(t)];
            if s.damping > 0.0 {
                *d = s
                    .linearize(x[s.i], x[s.j], CompressedSprings::Clamped)
                    .direction;
            }
        });
    }

    /// The incremental potential whose gradient in `v` is minus the
    /// residual of the step,
    ///
    /// ```text
    /// Φ(v) = ½ Σ mᵢ|vᵢ − ṽᵢ|² + V(x̃ + βh v) + ½βh [Σ_s c_s (d_s·(vᵢ − vⱼ))² + γ Σ |vᵢ|²]
    /// ```
    ///
    /// with `V` the spring, volume-element and gravitational potential and
    /// `d_s` the frozen
    /// damping directions; `x` must hold `x̃ + βh v`. Also returns the
    /// rounding level of `Φ`: `ε` times the sum of its terms' magnitudes,
    /// plus each spring's `k |l − L| ε (|xᵢ| + |xⱼ|)` — the energy that the
    /// rounding of its ends' coordinates alone puts into `½k(l − L)²`, which
    /// dominates for stiff springs.
    pub(crate) fn potential(
        &self,
        system: &System,
        pattern: &Pattern,
        x: &[Vec3],
        v: &[Vec3],
        v_tilde: &[Vec3],
        beta_h: f64,
    ) -> Potential {
        let (particles, particles_magnitude) = particles_potential(system, x, v, v_tilde, beta_h);
        let (springs, springs_rounding) = sum2(pattern.slots(), |t| {
            let s = &system.springs()[pattern.spring(t)];
            let (xi, xj) = (x[s.i], x[s.j]);
            let stretch = (xi - xj).norm() - s.rest_length;
            let rate = if s.damping > 0.0 {
                self.directions[t].dot(&(v[s.i] - v[s.j]))
            } else {
                0.0
            };
            spring_potential(s, (xi, xj), stretch, rate, beta_h)
        });
        let (volume, volume_rounding) = volume_energy(system, x);
        Potential {
            value: particles + springs + volume,
            rounding: f64::EPSILON * (particles_magnitude + springs_rounding + volume_rounding),
        }
    }
}

impl Solve<'_> {
    /// Assembles the linearisation `lin` into the topology's matrix and `b`.
    ///
    /// # Errors
    /// As [`Assembler::assemble`].
    pub(crate) fn assemble(
        self,
        assembler: &mut Assembler,
        topology: &mut Topology,
        lin: &Linearization<'_>,
        b: &mut [Vec3],
    ) -> Result<(), StepError> {
        let (matrix, jacobi) = topology.system_mut();
        assembler.assemble(self.system, lin, matrix, jacobi, b, self.time)
    }
}
