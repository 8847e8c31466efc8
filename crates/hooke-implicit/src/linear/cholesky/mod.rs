//! Sparse Cholesky with the symbolic analysis done once per topology (faer).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
    factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};
use hooke_core::{Mat3, StepError, System, Vec3};

use std::cell::RefCell;

mod prediction;
mod routes;
use prediction::particle_order;
pub(crate) use prediction::predicted_factor_entries;
use routes::Carried;
pub use routes::WeakSprings;
pub(crate) use routes::{Routes, SpringRoute};

use crate::linear::amg::fine::Neighbours;

use crate::linear::cg::{self, PcgError, PcgInfo, PcgSettings, PcgWorkspace, Preconditioner};
use crate::linear::filter::Filter;
use crate::linear::matrix::BlockMatrix;

/// Why [`SparseCholesky`] could not factorize a matrix.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CholeskyError {
    /// The filtered matrix is not positive definite: a pivot of the
    /// factorization is not positive, at this particle where the
    /// factorization names one.
    NotPositiveDefinite {
        /// The particle of the first non-positive pivot.
        particle: Option<usize>,
    },
}

impl CholeskyError {
    /// The step error at time `time` that this error makes.
    pub(crate) fn at(self, time: f64) -> StepError {
        match self {
            Self::NotPositiveDefinite { particle } => {
                StepError::NotPositiveDefinite { time, particle }
            }
        }
    }
}

/// How [`SparseCholesky`] orders the unknowns to reduce the factor's fill.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FillOrdering {
    /// Approximate minimum degree on the particle graph, each particle's
    /// three unknowns kept together, and the matrix laid out in that order
    /// once: a factorization reads it as it is. The default.
    #[default]
    Particles,
    /// faer's approximate minimum degree on the scalar matrix, laid out in
    /// the particles' own order, which faer copies into its order at every
    /// factorization (the solver before [`FillOrdering::Particles`], kept
    /// to measure against it).
    Scalar,
}

/// Which of faer's two numeric factorizations [`SparseCholesky`] runs.
/// faer's symbolic analysis takes the supernodal one (dense blocks of
/// columns, matrix–matrix kernels) over the simplicial one (column by
/// column) where the factor averages more flops per entry than a
/// threshold: `Σ (c + c(c + 1)/2) / Σ c` over the factor's column counts
/// `c`, about half the mean column count.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Supernodes {
    /// Supernodal above [`Supernodes::BLOCK_FLOPS_PER_ENTRY`] flops per
    /// entry (the default). Each particle's three unknowns share their
    /// pattern, so every column lies in a dense block at least three wide,
    /// and the supernodal kernels pay on factors far sparser than faer's
    /// rule, made for scalar matrices, expects. Where the two rules differ
    /// (the routed factors of the 30 × 30 and two 25 × 25 cloths of the
    /// contact scenes, the volumetric and shell scenes of 60–84
    /// particles), the first simulated second takes 0.56–0.82 of the
    /// time it takes under faer's rule (`benches/README.md`); the
    /// 21-particle chain, whose factor is a band, stays simplicial.
    #[default]
    Blocks,
    /// faer's own rule: supernodal above 40 flops per entry (the rule
    /// before 2026-11-28, kept to measure against).
    Faer,
}

impl Supernodes {
    /// The flops per factor entry above which [`Supernodes::Blocks`] takes
    /// the supernodal factorization.
    pub const BLOCK_FLOPS_PER_ENTRY: f64 = 10.0;

    /// faer's threshold, as a multiple of its own 40 flops per entry.
    fn threshold(self) -> SupernodalThreshold {
        match self {
            Self::Blocks => SupernodalThreshold(Self::BLOCK_FLOPS_PER_ENTRY / 40.0),
            Self::Faer => SupernodalThreshold::AUTO,
        }
    }
}

impl hooke_core::Named for Supernodes {
    /// `"blocks"` and `"faer"`, as scene files (`supernodes`) and reports
    /// spell them.
    const TABLE: &'static [(Self, &'static str)] =
        &[(Self::Blocks, "blocks"), (Self::Faer, "faer")];
}

/// A direct solver for the filtered system
///
/// ```text
/// (S A S + I − S) x = S b
/// ```
///
/// whose solution is the one the filtered PCG converges to: `x` lies in the
/// free subspace (`x = S x`, so constrained components are zero) and solves
/// `A x = b` there. For a pinned particle `S = 0` and its rows become the
/// identity, so the matrix stays positive definite whenever `A` is.
///
/// The fill-reducing ordering ([`FillOrdering`]) and the symbolic
/// factorization are computed once, the lower triangle of the scalar
/// `3n × 3n` matrix is laid out in compressed columns once, and every solve
/// only copies the filtered blocks into place, factorizes numerically
/// (`L Lᵀ`) into preallocated storage and solves, without allocating.
///
/// By default the particles are ordered by approximate minimum degree on
/// their graph (one node per particle, an edge per spring), and the matrix
/// is laid out in that order: particle `q` in place `k` owns the unknowns
/// `3k..3k + 2`. AMD on the `3n` scalar unknowns finds each particle's three
/// as one supervariable and orders them alike (on the cloths of
/// `benches/solvers` the two factors have the same size), but faer then
/// copies the matrix into its order at every factorization, a fifth of the
/// factorization's time on the default scene; laid out in its order once,
/// the matrix is factorized as it is.
///
/// Built with routes (`SparseCholesky::for_system` with
/// [`WeakSprings::Routed`]), the pattern leaves out the weak springs that
/// stiff ones carry (the `routes` module) and the factor is of the matrix
/// `P ⪰ A` with their blocks moved onto their paths: half the entries on a
/// cloth. It then preconditions CG on `A` ([`SparseCholesky::is_complete`]
/// is false).
pub struct SparseCholesky {
    col_ptr: Vec<u32>,
    row_idx: Vec<u32>,
    values: Vec<f64>,
    /// Per slot of the pattern, the position of the first entry of each of
    /// the three columns of its spring's block below the diagonal.
    slot_columns: Vec<[u32; 3]>,
    /// Per slot, whether the block below the diagonal is the slot's block
    /// `(q, p)` itself (its row particle `q` ordered after its column
    /// particle `p`) rather than its transpose.
    slot_upper: Vec<bool>,
    /// Each particle's place in the order of the factorization.
    order: Vec<u32>,
    symbolic: SymbolicCholesky<u32>,
    factor: Vec<f64>,
    factor_memory: MemBuffer,
    solve_memory: MemBuffer,
    rhs: Vec<f64>,
    par: Par,
    /// Whether every block of the matrix last filled lay in the pattern.
    complete: bool,
    /// Per particle, the diagonal added for the blocks left out
    /// ([`SparseCholesky::is_complete`]).
    compensation: Vec<f64>,
    /// The weak springs whose blocks the factor carries on their paths.
    routes: Routes,
    /// What the routes add to the diagonal blocks and the legs' slots.
    carried: Carried,
}

/// The sizes of a [`SparseCholesky`] ([`SparseCholesky::info`]): it has no
/// settings to take and no iterations to count, and what it costs is the
/// size of its factor.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CholeskyInfo {
    /// Scalar unknowns, three per particle.
    pub unknowns: usize,
    /// Entries of the matrix's lower triangle.
    pub nonzeros: usize,
    /// Entries of the factor `L`.
    pub factor_nonzeros: usize,
    /// Bytes the solver holds: the matrix's and the factor's indices and
    /// values, and the factorization's and solve's scratch.
    pub bytes: usize,
    /// Whether the numeric factorization is supernodal ([`Supernodes`]).
    pub supernodal: bool,
}

impl std::fmt::Debug for SparseCholesky {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SparseCholesky")
            .field("info", &self.info())
            .finish_non_exhaustive()
    }
}

/// Particle count from which faer factorizes in parallel. On the issue's
/// cloth (`benches/solvers/`, 2 cores) faer's parallel factorization and
/// solve took 438 ms against 366 ms sequentially at 40 000 particles, and
/// 2.27 s against 2.63 s at 160 000; in converged steps of the falling
/// cloth it took 170 ms against 92 ms at 4 096 particles and 749 ms
/// against 411 ms at 10 000.
#[cfg(feature = "parallel")]
const PARALLEL_MIN_PARTICLES: usize = 100_000;

impl SparseCholesky {
    /// The layout and symbolic factorization for matrices with the pattern of
    /// `a`.
    ///
    /// # Errors
    /// [`StepError::SystemTooLarge`] if the scalar matrix does not fit 32-bit
    /// indices.
    pub fn new(a: &BlockMatrix) -> Result<Self, StepError> {
        Self::with_ordering(a, FillOrdering::default())
    }

    /// The layout and symbolic factorization for matrices with the pattern of
    /// `a`, with the fill-reducing ordering `ordering`.
    ///
    /// # Errors
    /// As [`SparseCholesky::new`].
    pub fn with_ordering(a: &BlockMatrix, ordering: FillOrdering) -> Result<Self, StepError> {
        Self::with_routes(a, (ordering, Supernodes::default()), Routes::default())
    }

    /// The factorization of matrices with the pattern of `a`, the springs
    /// of `system`, which treats its weak springs as `weak` says and runs
    /// the numeric factorization `supernodes` chooses.
    ///
    /// # Errors
    /// As [`SparseCholesky::new`].
    pub(crate) fn for_system(
        a: &BlockMatrix,
        system: &System,
        (weak, supernodes): (WeakSprings, Supernodes),
    ) -> Result<Self, StepError> {
        Self::with_routes(
            a,
            (FillOrdering::default(), supernodes),
            Routes::of(system, a.pattern(), weak),
        )
    }

    /// The layout and symbolic factorization for matrices with the pattern
    /// of `a` less the routed springs of `routes`.
    ///
    /// # Errors
    /// As [`SparseCholesky::new`].
    pub(crate) fn with_routes(
        a: &BlockMatrix,
        (ordering, supernodes): (FillOrdering, Supernodes),
        routes: Routes,
    ) -> Result<Self, StepError> {
        let (n, springs) = (a.rows(), a.pattern().slots());
        let dofs = 3 * n;
        let too_large = || StepError::SystemTooLarge {
            particles: n,
            springs,
        };
        let nonzeros = 6 * n + 9 * springs;
        let index = |k: usize| u32::try_from(k).map_err(|_| too_large());
        index(nonzeros)?;
        // The particles in the fill-reducing order of their graph; each
        // particle's three unknowns stay together, so the factor is made of
        // 3x3 blocks and a solve permutes whole particles.
        let blocks = a.pattern();
        let order = match ordering {
            FillOrdering::Particles => particle_order(blocks, &routes).ok_or_else(too_large)?.0,
            FillOrdering::Scalar => (0..n as u32).collect(),
        };
        let mut particle_at = vec![0; n];
        for (q, &k) in order.iter().enumerate() {
            particle_at[k as usize] = q;
        }
        // Column 3k + c, for the k-th particle q of the order, holds rows
        // 3k + c..3k + 2 of q's diagonal block, then rows 3l..3l + 2 for
        // every neighbour of q whose place l > k, in increasing order.
        let neighbours = Neighbours::new(blocks);
        let mut col_ptr = Vec::with_capacity(dofs + 1);
        let mut row_idx = Vec::with_capacity(nonzeros);
        let mut slot_columns = vec![[0; 3]; springs];
        let mut slot_upper = vec![false; springs];
        let mut later = Vec::new();
        col_ptr.push(0);
        for (k, &q) in particle_at.iter().enumerate() {
            later.clear();
            later.extend(
                routes
                    .kept(neighbours.of(q))
                    .map(|&(p, t)| (order[p as usize], t))
                    .filter(|&(l, _)| l as usize > k),
            );
            later.sort_unstable();
            for &(_, t) in &later {
                slot_upper[t as usize] = blocks.row_of(t as usize) != q;
            }
            #[allow(clippy::needless_range_loop)] // `c` is a column within the block
            for c in 0..3 {
                row_idx.extend((c..3).map(|r| (3 * k + r) as u32));
                for &(l, t) in &later {
                    slot_columns[t as usize][c] = row_idx.len() as u32;
                    row_idx.extend((0..3).map(|r| 3 * l + r));
                }
                col_ptr.push(row_idx.len() as u32);
            }
        }
        drop(neighbours);
        let symbolic =
            analyse(dofs, (&col_ptr, &row_idx), (ordering, supernodes)).map_err(|_| too_large())?;
        let par = parallelism(n);
        let factor_memory =
            MemBuffer::new(symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()));
        let solve_memory = MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(1, par));
        Ok(Self {
            factor: vec![0.0; symbolic.len_val()],
            values: vec![0.0; row_idx.len()],
            col_ptr,
            row_idx,
            slot_columns,
            slot_upper,
            order,
            symbolic,
            factor_memory,
            solve_memory,
            rhs: vec![0.0; dofs],
            par,
            complete: true,
            compensation: vec![0.0; n],
            carried: Carried::new(&routes, n, springs),
            routes,
        })
    }

    /// Solves `(S A S + I − S) x = S b`, the filtered system, into `x`.
    ///
    /// # Errors
    /// [`CholeskyError::NotPositiveDefinite`] if the filtered matrix is not
    /// positive definite.
    pub fn solve(
        &mut self,
        a: &BlockMatrix,
        filters: &[Filter],
        b: &[Vec3],
        x: &mut [Vec3],
    ) -> Result<(), CholeskyError> {
        self.factorize(a, filters)?;
        self.solve_factored(filters, b, x);
        Ok(())
    }

    /// Factorizes `S A S + I − S` numerically, keeping the factor for
    /// [`SparseCholesky::solve_factored`].
    ///
    /// # Errors
    /// As [`SparseCholesky::solve`].
    pub fn factorize(&mut self, a: &BlockMatrix, filters: &[Filter]) -> Result<(), CholeskyError> {
        self.fill(a, filters);
        let dofs = self.rhs.len();
        let pattern =
            SymbolicSparseColMatRef::new_checked(dofs, dofs, &self.col_ptr, None, &self.row_idx);
        let matrix = SparseColMatRef::new(pattern, &self.values);
        self.symbolic
            .factorize_numeric_llt(
                &mut self.factor,
                matrix,
                Side::Lower,
                LltRegularization::default(),
                self.par,
                MemStack::new(&mut self.factor_memory),
                Default::default(),
            )
            .map_err(
                |faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { index }| {
                    // The pivot's unknown in the layout, then its particle.
                    let unknown = match self.symbolic.perm() {
                        Some(p) => p.arrays().0.get(index).map(|&d| d as usize),
                        None => Some(index),
                    };
                    let place = unknown.filter(|&d| d < dofs).map(|d| d / 3);
                    CholeskyError::NotPositiveDefinite {
                        particle: place
                            .and_then(|k| self.order.iter().position(|&l| l as usize == k)),
                    }
                },
            )?;
        Ok(())
    }

    /// `x = S L⁻ᵀ L⁻¹ S b` with the factor `L Lᵀ` of the last
    /// [`SparseCholesky::factorize`] (zero before the first): the solution
    /// of the filtered system that was factorized, and for a later matrix
    /// of the same pattern (a later Newton iteration, a later step) a
    /// preconditioner ([`SparseCholesky::preconditioner`]).
    pub fn solve_factored(&mut self, filters: &[Filter], b: &[Vec3], x: &mut [Vec3]) {
        let dofs = self.rhs.len();
        for (i, (bi, f)) in b.iter().zip(filters).enumerate() {
            let k = 3 * self.order[i] as usize;
            self.rhs[k..k + 3].copy_from_slice(f.apply(*bi).as_slice());
        }
        LltRef::new(&self.symbolic, &self.factor).solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(&mut self.rhs, dofs, 1),
            self.par,
            MemStack::new(&mut self.solve_memory),
        );
        for (i, (xi, f)) in x.iter_mut().zip(filters).enumerate() {
            let k = 3 * self.order[i] as usize;
            *xi = f.apply(Vec3::from_column_slice(&self.rhs[k..k + 3]));
        }
    }

    /// Solves the filtered system of `a` with the last factor: directly
    /// where it is of the whole matrix ([`SparseCholesky::is_complete`],
    /// `None`), otherwise by PCG on `a` from zero, preconditioned by it, to
    /// `settings` (PCG's outcome).
    pub(crate) fn solve_filtered(
        &mut self,
        (a, filters): (&BlockMatrix, &[Filter]),
        b: &[Vec3],
        x: &mut [Vec3],
        settings: PcgSettings,
        workspace: &mut PcgWorkspace,
    ) -> Option<Result<PcgInfo, PcgError>> {
        if self.is_complete() {
            self.solve_factored(filters, b, x);
            return None;
        }
        x.fill(Vec3::zeros());
        let preconditioner = self.preconditioner(filters);
        Some(cg::solve(
            a,
            &preconditioner,
            filters,
            b,
            x,
            settings,
            workspace,
        ))
    }

    /// The last factor as a PCG preconditioner for the filters `filters`:
    /// `P⁻¹ r = S L⁻ᵀ L⁻¹ S r`, symmetric positive definite whatever matrix
    /// was factorized, and exact for that one.
    pub fn preconditioner<'a>(&'a mut self, filters: &'a [Filter]) -> FactorPreconditioner<'a> {
        FactorPreconditioner {
            cholesky: RefCell::new(self),
            filters,
        }
    }

    /// The solver's sizes.
    #[must_use]
    pub fn info(&self) -> CholeskyInfo {
        let (symbolic, supernodal) = match self.symbolic.raw() {
            SymbolicCholeskyRaw::Simplicial(s) => {
                (4 * (s.col_ptr().len() + s.row_idx().len()), false)
            }
            SymbolicCholeskyRaw::Supernodal(s) => (
                4 * (s.col_ptr_for_row_idx().len() + s.row_idx().len() + s.col_ptr_for_val().len()),
                true,
            ),
        };
        CholeskyInfo {
            unknowns: self.rhs.len(),
            nonzeros: self.values.len(),
            factor_nonzeros: self.factor.len(),
            bytes: 4
                * (self.col_ptr.len()
                    + self.row_idx.len()
                    + 3 * self.slot_columns.len()
                    + self.order.len())
                + self.slot_upper.len()
                + 8 * (self.values.len() + self.factor.len() + self.rhs.len())
                + 8 * self.compensation.len()
                + symbolic
                + self.factor_memory.len()
                + self.solve_memory.len(),
            supernodal,
        }
    }

    /// Whether the factor carries weak springs on their paths
    /// ([`WeakSprings::Routed`]).
    pub(crate) fn is_routed(&self) -> bool {
        !self.routes.is_empty()
    }

    /// Whether the last [`SparseCholesky::factorize`] factored the whole
    /// matrix: no weak spring is routed, and every block beside the
    /// springs' (of a contact or a volume element) joined two particles a
    /// spring joins too. Otherwise it factored a matrix above the whole
    /// one — routed springs' blocks on their paths, and the blocks `B` at
    /// `(i, j)` that lie outside its pattern each replaced by `‖B‖_F I`
    /// added to the diagonal blocks of `i` and `j` — and
    /// [`SparseCholesky::solve_factored`] solves that one.
    ///
    /// Leaving a block out alone could make a positive definite matrix
    /// indefinite: a contact pair's Hessian joins four particles, of which
    /// springs join some (a bending spring two apart, a shear spring across
    /// a cell) and not others, and what remains of a positive semidefinite
    /// 12 × 12 block is not. Removing the pair `E = [0 B; Bᵀ 0]` lowers the
    /// matrix by at most `σ_max(B) ≤ ‖B‖_F` in each of the two particles'
    /// directions, as `[σI −B; −Bᵀ σI] ⪰ 0` for `σ ≥ σ_max(B)`; the
    /// compensation adds that back, so the factored matrix is at least the
    /// whole one and positive definite whenever it is.
    #[must_use]
    pub fn is_complete(&self) -> bool {
        self.complete && !self.is_routed()
    }

    /// Copies the lower triangle of `S A S + I − S` into `values`: the
    /// blocks outside the springs' pattern left out and made up for on the
    /// diagonal, and the routed springs' blocks carried on their paths
    /// (`Routes::carry`; [`SparseCholesky::is_complete`]).
    fn fill(&mut self, a: &BlockMatrix, filters: &[Filter]) {
        let sandwich = |block: Mat3, left: Filter, right: Filter| match (left, right) {
            (Filter::Free, Filter::Free) => block,
            _ => left.matrix() * block * right.matrix(),
        };
        self.compensation.fill(0.0);
        self.complete = a.extra_within_pattern();
        // Contact and element blocks at a routed spring's slot leave the
        // pattern with it.
        let at_routed = self.routes.iter().filter_map(|route| {
            let [i, j] = route.ends.map(|e| e as usize);
            a.extra_at_slots
                .get(route.slot as usize)
                .map(|&block| (i, j, block))
        });
        for (i, j, block) in a.extra_outside_pattern().chain(at_routed) {
            let norm = sandwich(block, filters[i], filters[j]).norm();
            self.compensation[i] += norm;
            self.compensation[j] += norm;
        }
        self.routes.carry(a, &mut self.carried);
        for (q, &filter) in filters.iter().enumerate() {
            let s = filter.matrix();
            let mut diagonal = a.diagonal(q);
            if let Some(carried) = self.carried.diagonal(q) {
                diagonal += carried;
            }
            let block = sandwich(diagonal, filter, filter) + Mat3::identity() - s
                + self.compensation[q] * s;
            let k = 3 * self.order[q] as usize;
            for c in 0..3 {
                let start = self.col_ptr[k + c] as usize;
                for r in c..3 {
                    self.values[start + r - c] = block[(r, c)];
                }
            }
        }
        let pattern = a.pattern();
        for q in 0..pattern.rows() {
            for t in pattern.upper(q) {
                if self.routes.is_routed(t) {
                    continue;
                }
                let p = pattern.column(t);
                // The slot's block at (q, p), or its transpose at (p, q),
                // whichever lies below the diagonal in the order.
                let mut block = a.slot_block(t);
                if let Some(carried) = self.carried.slot(t) {
                    block += carried;
                }
                let block = if self.slot_upper[t] {
                    sandwich(block, filters[q], filters[p])
                } else {
                    sandwich(block.transpose(), filters[p], filters[q])
                };
                for (c, &start) in self.slot_columns[t].iter().enumerate() {
                    for r in 0..3 {
                        self.values[start as usize + r] = block[(r, c)];
                    }
                }
            }
        }
    }
}

/// A factor of an earlier matrix preconditioning PCG:
/// [`SparseCholesky::preconditioner`].
#[derive(Debug)]
pub struct FactorPreconditioner<'a> {
    cholesky: RefCell<&'a mut SparseCholesky>,
    filters: &'a [Filter],
}

impl Preconditioner for FactorPreconditioner<'_> {
    fn apply(&self, r: &[Vec3], z: &mut [Vec3]) {
        self.cholesky
            .borrow_mut()
            .solve_factored(self.filters, r, z);
    }
}

/// faer's symbolic factorization of the `dofs × dofs` matrix whose lower
/// triangle has the compressed columns `col_ptr`, `row_idx`, in the
/// particles' order or ordered by faer ([`FillOrdering`]), its numeric
/// factorization chosen by `supernodes`. faer analyses a matrix it does
/// not order from its upper triangle, built here and dropped after.
fn analyse(
    dofs: usize,
    (col_ptr, row_idx): (&[u32], &[u32]),
    (ordering, supernodes): (FillOrdering, Supernodes),
) -> Result<SymbolicCholesky<u32>, faer::sparse::FaerError> {
    let upper;
    let (pattern, side, fill_ordering) = match ordering {
        FillOrdering::Particles => {
            upper = transpose(dofs, col_ptr, row_idx);
            let (upper_ptr, upper_idx) = &upper;
            (
                SymbolicSparseColMatRef::new_checked(dofs, dofs, upper_ptr, None, upper_idx),
                Side::Upper,
                SymmetricOrdering::Identity,
            )
        }
        FillOrdering::Scalar => (
            SymbolicSparseColMatRef::new_checked(dofs, dofs, col_ptr, None, row_idx),
            Side::Lower,
            SymmetricOrdering::Amd,
        ),
    };
    factorize_symbolic_cholesky(
        pattern,
        side,
        fill_ordering,
        CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: supernodes.threshold(),
            ..CholeskySymbolicParams::default()
        },
    )
}

/// The pattern of the transpose of the `dofs × dofs` pattern in compressed
/// columns `col_ptr`, `row_idx`: its compressed rows, each row's columns in
/// increasing order.
fn transpose(dofs: usize, col_ptr: &[u32], row_idx: &[u32]) -> (Vec<u32>, Vec<u32>) {
    let mut ptr = vec![0u32; dofs + 1];
    for &r in row_idx {
        ptr[r as usize + 1] += 1;
    }
    for r in 0..dofs {
        ptr[r + 1] += ptr[r];
    }
    let mut next = ptr.clone();
    let mut idx = vec![0u32; row_idx.len()];
    for c in 0..dofs {
        for &r in &row_idx[col_ptr[c] as usize..col_ptr[c + 1] as usize] {
            idx[next[r as usize] as usize] = c as u32;
            next[r as usize] += 1;
        }
    }
    (ptr, idx)
}

/// Sequential for small systems, faer's rayon parallelism for large ones.
#[cfg(feature = "parallel")]
fn parallelism(particles: usize) -> Par {
    if particles >= PARALLEL_MIN_PARTICLES {
        Par::rayon(0)
    } else {
        Par::Seq
    }
}

/// Sequential: the `parallel` feature is off.
#[cfg(not(feature = "parallel"))]
fn parallelism(_particles: usize) -> Par {
    Par::Seq
}

#[cfg(test)]
pub(crate) mod tests;
