//! Sparse Cholesky with the symbolic analysis done once per topology (faer):
//! the solver and its sizes here, the ordering, layout and symbolic
//! analysis in `symbolic`, the numeric factorization of a step's matrix in
//! `numeric`, the solves and the preconditioner in `solve`, the routes of
//! weak springs in `routes` and the factor's predicted size in
//! `prediction`.

use faer::Par;
use faer::dyn_stack::MemBuffer;
use faer::sparse::linalg::cholesky::{SymbolicCholesky, SymbolicCholeskyRaw};
use hooke_core::{StepError, System};

mod numeric;
mod prediction;
mod routes;
mod solve;
mod symbolic;
use numeric::parallelism;
use prediction::particle_order;
pub(crate) use prediction::predicted_factor_entries;
use routes::Carried;
pub use routes::WeakSprings;
pub(crate) use routes::{Routes, SpringRoute};
pub use solve::FactorPreconditioner;
pub use symbolic::{FillOrdering, Supernodes};
use symbolic::{LowerTriangle, analyse};

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
        let LowerTriangle {
            col_ptr,
            row_idx,
            slot_columns,
            slot_upper,
        } = LowerTriangle::new(blocks, &order, &routes);
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
}

#[cfg(test)]
pub(crate) mod tests;
