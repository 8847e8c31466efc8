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

use hooke_core::{CompressedSprings, Mat3, StepError, System, TET_PAIRS, Tet, TetHessian, Vec3};

use crate::linear::block::SymBlock;
use crate::linear::cg::BlockJacobi;
use crate::linear::matrix::BlockMatrix;
use crate::linear::pattern::Pattern;
use crate::linear::vector::{for_each_row, for_each_row3, spring_chunks, sum2};

/// The incremental potential at a point and its rounding level.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Potential {
    /// `Φ`.
    pub(crate) value: f64,
    /// How far rounding alone may move `Φ`, in J.
    pub(crate) rounding: f64,
}

/// Where and how to linearise.
#[derive(Debug, Clone, Copy)]
pub struct Linearization<'a> {
    /// Positions `X` at which forces and stiffness blocks are evaluated.
    pub positions: &'a [Vec3],
    /// Velocities `V` at which damping forces are evaluated.
    pub velocities: &'a [Vec3],
    /// The displacement `u` multiplied by the stiffness in the right-hand
    /// side, or `None` for zero.
    pub displacement: Option<&'a [Vec3]>,
    /// The inertia term `M(ṽ − V)` of the right-hand side.
    pub inertia: &'a [Vec3],
    /// `βh`.
    pub beta_h: f64,
    /// How compressed springs' stiffness blocks are treated, and with them
    /// the volume elements' Hessians: exact with
    /// [`CompressedSprings::Exact`], positive semidefinite stand-ins with
    /// [`CompressedSprings::Clamped`] ([`Assembler`]'s `volume_terms`).
    pub compressed: CompressedSprings,
    /// Whether to take the damping directions from `positions` (the first
    /// linearisation of a step) or keep those of the previous call.
    pub freeze_directions: bool,
}

/// Assembles linearised steps; keeps the per-spring scratch between calls so
/// that assembly does not allocate.
///
/// ```
/// use hooke_core::{CompressedSprings, Vec3, reference::Sheet};
/// use hooke_implicit::{Assembler, BlockJacobi, BlockMatrix, Linearization, Pattern};
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
    diagonals: Vec<SymBlock>,
    pub(crate) rhs: Vec<Vec3>,
    /// Per chunk: the rows its springs reach.
    pub(crate) touched: Vec<Range<usize>>,
    /// Per slot: the spring's damping direction, frozen at the step's start.
    pub(crate) directions: Vec<Vec3>,
    /// Per element: its blocks and right-hand-side shares.
    element_terms: Vec<ElementTerms>,
    /// Per element of the system identified by the first entry: the
    /// pattern's slot between each pair of its vertices, if a spring joins
    /// them.
    element_slots: (u64, Vec<[Option<usize>; 6]>),
    /// Per particle: the volume elements' diagonal blocks, those plus the
    /// bounds of their blocks outside the pattern, and their right-hand-side
    /// shares.
    volume_rows: Vec<SymBlock>,
    volume_diagonals: Vec<SymBlock>,
    pub(crate) volume_rhs: Vec<Vec3>,
}

/// Element count from which the elements' blocks are evaluated in parallel
/// (with the `parallel` feature): an element's projected Hessian takes
/// about a microsecond, its exact one a tenth of that, against the tens
/// of microseconds of waking the workers.
pub const PARALLEL_MIN_ELEMENTS: usize = 1024;

/// The index in [`TET_PAIRS`] of the pair `(p, q)`, `p < q`.
fn pair_index(p: usize, q: usize) -> usize {
    match (p, q) {
        (0, q) => q - 1,
        (1, q) => q + 1,
        _ => 5,
    }
}

/// One element's share of a linearised step: `β²h²` times its Hessian's
/// diagonal blocks (symmetrised) and blocks between its vertices, and its
/// right-hand-side shares `−βh (∇E + H u)` at its four vertices.
#[derive(Debug, Clone, Copy, Default)]
struct ElementTerms {
    diagonal: [SymBlock; 4],
    pairs: [Mat3; 6],
    rhs: [Vec3; 4],
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
        let volume = self.volume_terms(system, lin, a);

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
        let (volume_diagonals, volume_rhs) = (&self.volume_diagonals, &self.volume_rhs);
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

    /// Adds the volume elements' blocks between their vertices to `a` and
    /// gathers their diagonal blocks and right-hand-side shares per
    /// particle; returns whether the system has elements with a modulus.
    ///
    /// Each element's Hessian ([`TetHessian`]) is the exact one with
    /// [`CompressedSprings::Exact`]; with [`CompressedSprings::Clamped`] the
    /// projected one at a Newton iterate, and the Gauss–Newton one for
    /// Baraff & Witkin's step (a `displacement`): that step is a starting
    /// point for Newton's method, which corrects it, or the whole step of
    /// the linearised integrator, and the Gauss–Newton Hessian, exact at
    /// rest, costs a tenth of the projection. The elements' blocks are
    /// evaluated independently — in parallel from [`PARALLEL_MIN_ELEMENTS`]
    /// elements on — and then added to the matrix in element order, so both
    /// paths give the same sums.
    fn volume_terms(
        &mut self,
        system: &System,
        lin: &Linearization<'_>,
        a: &mut BlockMatrix,
    ) -> bool {
        let tets = system.tets();
        if tets.iter().all(|t| t.modulus <= 0.0) {
            return false;
        }
        let n = system.particle_count();
        let (bh, bh2) = (lin.beta_h, lin.beta_h * lin.beta_h);
        let kind = match (lin.compressed, lin.displacement) {
            (CompressedSprings::Exact, _) => TetHessian::Exact,
            (CompressedSprings::Clamped, None) => TetHessian::Projected,
            (CompressedSprings::Clamped, Some(_)) => TetHessian::GaussNewton,
        };
        let evaluate = |t: &Tet, terms: &mut ElementTerms| {
            if t.modulus <= 0.0 {
                return;
            }
            let d = t.blocks(lin.positions, kind);
            let block = |p: usize, q: usize| match p.cmp(&q) {
                std::cmp::Ordering::Equal => d.diagonal[p],
                std::cmp::Ordering::Less => d.pairs[pair_index(p, q)],
                std::cmp::Ordering::Greater => d.pairs[pair_index(q, p)].transpose(),
            };
            for p in 0..4 {
                let mut share = -d.gradient[p];
                if let Some(u) = lin.displacement {
                    for (q, &j) in t.vertices.iter().enumerate() {
                        share -= block(p, q) * u[j];
                    }
                }
                terms.rhs[p] = bh * share;
                terms.diagonal[p] = SymBlock::symmetric_part(&(bh2 * d.diagonal[p]));
            }
            for (pair, block) in terms.pairs.iter_mut().zip(&d.pairs) {
                *pair = bh2 * block;
            }
        };
        self.element_terms
            .resize(tets.len(), ElementTerms::default());
        let terms = &mut self.element_terms;
        if cfg!(feature = "parallel") && tets.len() >= PARALLEL_MIN_ELEMENTS {
            #[cfg(feature = "parallel")]
            {
                use rayon::prelude::*;
                terms
                    .par_iter_mut()
                    .zip(tets.par_iter())
                    .with_min_len(PARALLEL_MIN_ELEMENTS / 4)
                    .for_each(|(terms, t)| evaluate(t, terms));
            }
        } else {
            for (terms, t) in terms.iter_mut().zip(tets) {
                evaluate(t, terms);
            }
        }

        if self.element_slots.0 != system.id() || self.element_slots.1.len() != tets.len() {
            self.element_slots.0 = system.id();
            self.element_slots.1.clear();
            self.element_slots.1.extend(tets.iter().map(|t| {
                TET_PAIRS.map(|(p, q)| a.pattern.slot_between(t.vertices[p], t.vertices[q]))
            }));
        }
        // The elements' diagonal blocks are summed per particle into one
        // row block for the product; the diagonal the preconditioners see
        // also gets the bounds of the blocks outside the springs' pattern.
        self.volume_rows.clear();
        self.volume_rows.resize(n, SymBlock::default());
        self.volume_diagonals.clear();
        self.volume_diagonals.resize(n, SymBlock::default());
        self.volume_rhs.clear();
        self.volume_rhs.resize(n, Vec3::zeros());
        let elements = tets
            .iter()
            .zip(&self.element_terms)
            .zip(&self.element_slots.1);
        for ((t, terms), slots) in elements {
            if t.modulus <= 0.0 {
                continue;
            }
            for (p, &i) in t.vertices.iter().enumerate() {
                self.volume_rhs[i] += terms.rhs[p];
                self.volume_rows[i].add_assign(&terms.diagonal[p]);
            }
            for ((&(p, q), &pair), &slot) in TET_PAIRS.iter().zip(&terms.pairs).zip(slots) {
                let (i, j) = (t.vertices[p], t.vertices[q]);
                if slot.is_none() {
                    let bound = SymBlock::scaled_identity(pair.norm());
                    self.volume_diagonals[i].add_assign(&bound);
                    self.volume_diagonals[j].add_assign(&bound);
                }
                a.add_extra_pair_at(i, j, pair, slot);
            }
        }
        for (i, (row, diagonal)) in self
            .volume_rows
            .iter()
            .zip(&mut self.volume_diagonals)
            .enumerate()
        {
            if *row != SymBlock::default() {
                diagonal.add_assign(row);
                a.extra_rows.push((i as u32, *row));
            }
        }
        true
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
        let masses = system.masses();
        let g = system.gravity().unwrap_or_else(Vec3::zeros);
        let gamma = system.air_damping().unwrap_or(0.0);
        let (particles, particles_magnitude) = sum2(x.len(), |i| {
            let m = masses[i];
            let inertia = 0.5 * m * (v[i] - v_tilde[i]).norm_squared();
            let gravitational = -m * g.dot(&x[i]);
            let air = 0.5 * beta_h * gamma * v[i].norm_squared();
            (
                inertia + gravitational + air,
                inertia + gravitational.abs() + air,
            )
        });
        let (springs, springs_rounding) = sum2(pattern.slots(), |t| {
            let s = &system.springs()[pattern.spring(t)];
            let (xi, xj) = (x[s.i], x[s.j]);
            // ½k(l − L)² with its length computed once for the rounding too.
            let stretch = (xi - xj).norm() - s.rest_length;
            let mut e = 0.5 * s.stiffness * stretch * stretch;
            let rounding = s.stiffness * stretch.abs() * (xi.amax() + xj.amax());
            if s.damping > 0.0 {
                let rate = self.directions[t].dot(&(v[s.i] - v[s.j]));
                e += 0.5 * beta_h * s.damping * rate * rate;
            }
            (e, e + rounding)
        });
        let (volume, volume_rounding) = volume_energy(system, x);
        Potential {
            value: particles + springs + volume,
            rounding: f64::EPSILON * (particles_magnitude + springs_rounding + volume_rounding),
        }
    }
}

/// The volume elements' energy `Σ ½ κ V₀ (J − 1)²` at positions `x`, and the
/// sum of the energies plus the energy the rounding of the vertices'
/// coordinates puts into them, `κ V₀ |J − 1| |∇J| max|x|` per element
/// (divided by ε), with `|∇J| ≈ V₀^(−1/3)`.
pub(crate) fn volume_energy(system: &System, x: &[Vec3]) -> (f64, f64) {
    let (mut energy, mut rounding) = (0.0, 0.0);
    for t in system.tets().iter().filter(|t| t.modulus > 0.0) {
        let (stiffness, change) = (t.modulus * t.rest_volume, t.volume_ratio(x) - 1.0);
        let e = 0.5 * stiffness * change * change;
        let reach = t.vertices.iter().map(|&i| x[i].amax()).fold(0.0, f64::max);
        energy += e;
        rounding += e + stiffness * change.abs() * t.gradient_scale() * reach;
    }
    (energy, rounding)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linear::cholesky::SparseCholesky;
    use crate::linear::filter::Filter;
    use hooke_core::SystemBuilder;

    /// Two tetrahedra sharing a face, of moduli `moduli`, on five
    /// particles of 0.5 kg, with springs of 50 N/m and damping `damping`
    /// between the pairs `springs`; then `finish` (gravity, damping) and
    /// the build. Also returns positions where the first element is
    /// inverted (its apex through the shared face).
    fn two_tets(
        springs: impl IntoIterator<Item = (usize, usize)>,
        damping: f64,
        moduli: [f64; 2],
        finish: impl FnOnce(&mut SystemBuilder),
    ) -> (System, Vec<Vec3>) {
        let mut b = SystemBuilder::new();
        let rest = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.2, 0.0, 0.9],
            [0.3, 0.8, 0.2],
            [0.4, -0.9, 0.3],
        ];
        let p: Vec<usize> = rest.iter().map(|&x| b.particle(0.5, x)).collect();
        for (i, j) in springs {
            b.spring(p[i], p[j], 50.0).damping(damping);
        }
        b.tet([p[0], p[1], p[2], p[3]], moduli[0]);
        b.tet([p[0], p[1], p[2], p[4]], moduli[1]);
        finish(&mut b);
        let system = b.build().unwrap();
        let mut x = system.initial_positions().to_vec();
        x[3] = Vec3::new(0.35, -0.3, 0.25);
        (system, x)
    }

    /// [`two_tets`] with springs on some of their edges, gravity and air
    /// damping, and a second vertex moved too.
    fn system() -> (System, Vec<Vec3>) {
        let springs = [(0, 1), (1, 2), (2, 3), (3, 4)];
        let (system, mut x) = two_tets(springs, 0.3, [2e3, 5e2], |b| {
            b.gravity([0.0, -9.81, 0.0]).air_damping(0.1);
        });
        x[1] += Vec3::new(0.2, 0.1, -0.1);
        (system, x)
    }

    /// The assembled right-hand side at a Newton iterate is minus the
    /// gradient of `Φ` in the velocities (central differences of
    /// [`Assembler::potential`]), and the matrix holds `β²h²` times each
    /// element's Hessian between its vertices: the exact one with exact
    /// springs, the projected one with clamped springs, and the
    /// Gauss–Newton one for Baraff & Witkin's step (one element inverted,
    /// where the three differ).
    #[test]
    fn volume_terms_are_the_potentials_derivatives() {
        let (system, x_tilde) = system();
        let n = system.particle_count();
        let beta_h = 0.02;
        let pattern = Pattern::new(&system).unwrap();
        let v: Vec<Vec3> = (0..n)
            .map(|i| Vec3::new(0.3 * i as f64, -0.2, 0.1 * (i as f64).sin()))
            .collect();
        let v_tilde: Vec<Vec3> = (0..n)
            .map(|i| Vec3::new(0.1, 0.2 * i as f64, 0.0))
            .collect();
        let positions = |v: &[Vec3]| -> Vec<Vec3> {
            x_tilde.iter().zip(v).map(|(x, v)| x + beta_h * v).collect()
        };
        let x = positions(&v);
        let inertia: Vec<Vec3> = (0..n)
            .map(|i| -system.masses()[i] * (v[i] - v_tilde[i]))
            .collect();
        let mut assembler = Assembler::default();
        let (mut a, mut jacobi) = (BlockMatrix::zeros(pattern.clone()), BlockJacobi::default());
        let mut b = vec![Vec3::zeros(); n];
        // The first linearisation freezes the damping directions at x.
        let lin = Linearization {
            positions: &x,
            velocities: &v,
            displacement: None,
            inertia: &inertia,
            beta_h,
            compressed: CompressedSprings::Exact,
            freeze_directions: true,
        };
        assembler
            .assemble(&system, &lin, &mut a, &mut jacobi, &mut b, 0.0)
            .unwrap();
        let phi = |v: &[Vec3]| {
            assembler
                .potential(&system, &pattern, &positions(v), v, &v_tilde, beta_h)
                .value
        };
        let h = 1e-6;
        for i in 0..n {
            for c in 0..3 {
                let (mut plus, mut minus) = (v.clone(), v.clone());
                plus[i][c] += h;
                minus[i][c] -= h;
                let numeric = (phi(&plus) - phi(&minus)) / (2.0 * h);
                assert!(
                    (numeric + b[i][c]).abs() < 1e-6 * (1.0 + numeric.abs()),
                    "∂Φ/∂v[{i}][{c}] = {numeric}, assembled −b = {}",
                    -b[i][c]
                );
            }
        }
        let w: Vec<Vec3> = (0..n)
            .map(|i| Vec3::new(1.0, -0.5 * i as f64, 0.25 + i as f64))
            .collect();
        let zero = vec![Vec3::zeros(); n];
        for (compressed, displacement, kind) in [
            (CompressedSprings::Exact, None, TetHessian::Exact),
            (CompressedSprings::Clamped, None, TetHessian::Projected),
            (
                CompressedSprings::Clamped,
                Some(&zero[..]),
                TetHessian::GaussNewton,
            ),
        ] {
            let lin = Linearization {
                positions: &x,
                velocities: &v,
                displacement,
                inertia: &inertia,
                beta_h,
                compressed,
                freeze_directions: false,
            };
            assembler
                .assemble(&system, &lin, &mut a, &mut jacobi, &mut b, 0.0)
                .unwrap();
            let mut with = vec![Vec3::zeros(); n];
            a.apply(&w, &mut with);
            let mut springs_only = a.clone();
            springs_only.clear_extra();
            let mut without = vec![Vec3::zeros(); n];
            springs_only.apply(&w, &mut without);
            let mut expected = vec![Vec3::zeros(); n];
            for t in system.tets() {
                let hessian = t.derivatives(&x, kind).hessian;
                for (p, &i) in t.vertices.iter().enumerate() {
                    for (q, &j) in t.vertices.iter().enumerate() {
                        expected[i] +=
                            beta_h * beta_h * hessian.fixed_view::<3, 3>(3 * p, 3 * q) * w[j];
                    }
                }
            }
            for i in 0..n {
                let error = (with[i] - without[i] - expected[i]).norm();
                assert!(
                    error < 1e-9 * expected[i].norm().max(1.0),
                    "{kind:?}: row {i} off by {error}"
                );
            }
        }
    }

    /// Where every pair of an element's vertices is joined by a spring,
    /// the Cholesky factor holds the elements' blocks and solves the
    /// assembled system exactly.
    #[test]
    fn the_factor_solves_a_system_with_elements_on_springs() {
        let every_pair_but_3_4 = (0..5)
            .flat_map(|i| (i + 1..5).map(move |j| (i, j)))
            .filter(|&pair| pair != (3, 4));
        let (system, x) = two_tets(every_pair_but_3_4, 0.0, [2e4, 5e3], |_| {});
        let n = system.particle_count();
        let v = vec![Vec3::zeros(); n];
        let lin = Linearization {
            positions: &x,
            velocities: &v,
            displacement: None,
            inertia: &v,
            beta_h: 0.1,
            compressed: CompressedSprings::Clamped,
            freeze_directions: true,
        };
        let mut a = BlockMatrix::zeros(Pattern::new(&system).unwrap());
        let (mut jacobi, mut rhs) = (BlockJacobi::default(), vec![Vec3::zeros(); n]);
        Assembler::default()
            .assemble(&system, &lin, &mut a, &mut jacobi, &mut rhs, 0.0)
            .unwrap();
        let filters = vec![Filter::Free; n];
        let mut factor = SparseCholesky::new(&a).unwrap();
        let mut solution = vec![Vec3::zeros(); n];
        factor.solve(&a, &filters, &rhs, &mut solution).unwrap();
        assert!(factor.is_complete());
        let mut product = vec![Vec3::zeros(); n];
        a.apply(&solution, &mut product);
        let scale = rhs.iter().map(|r| r.norm()).fold(0.0, f64::max);
        for (ax, r) in product.iter().zip(&rhs) {
            assert!((ax - r).norm() < 1e-10 * scale, "{ax} against {r}");
        }
    }
}
