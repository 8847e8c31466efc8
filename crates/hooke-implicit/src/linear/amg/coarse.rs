//! A direct solve of a scalar symmetric compressed-row matrix (the
//! multigrid's coarsest level, the fast mass-spring step's constant
//! matrix): faer's sparse Cholesky, analysed once per pattern.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, SymbolicCholesky, SymmetricOrdering, factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};

use super::csr::Csr;

/// `L Lᵀ = A` for a symmetric positive-definite `A`: its lower triangle in
/// compressed columns (column `j` is the part of row `j` at or right of the
/// diagonal), AMD-ordered, factorized numerically at every refresh.
pub(crate) struct ScalarCholesky {
    col_ptr: Vec<u32>,
    row_idx: Vec<u32>,
    /// Per entry of the lower triangle, its position in the CSR values.
    source: Vec<usize>,
    values: Vec<f64>,
    symbolic: SymbolicCholesky<u32>,
    factor: Vec<f64>,
    factor_memory: MemBuffer,
    solve_memory: MemBuffer,
}

impl std::fmt::Debug for ScalarCholesky {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ScalarCholesky")
            .field("dofs", &(self.col_ptr.len() - 1))
            .field("factor_nonzeros", &self.factor.len())
            .finish_non_exhaustive()
    }
}

impl ScalarCholesky {
    /// The most right-hand sides one [`ScalarCholesky::solve`] takes: the
    /// three coordinates of a per-particle vector.
    pub(crate) const MAX_COLUMNS: usize = 3;

    /// The layout and symbolic factorization for `a`'s pattern; `None` if
    /// it does not fit 32-bit indices.
    pub(crate) fn new(a: &Csr) -> Option<Self> {
        let n = a.rows();
        let mut col_ptr = vec![0u32];
        let mut row_idx = Vec::new();
        let mut source = Vec::new();
        for j in 0..n {
            for k in a.row_ptr[j]..a.row_ptr[j + 1] {
                if a.col_idx[k] as usize >= j {
                    row_idx.push(a.col_idx[k]);
                    source.push(k);
                }
            }
            col_ptr.push(u32::try_from(row_idx.len()).ok()?);
        }
        let pattern = SymbolicSparseColMatRef::new_checked(n, n, &col_ptr, None, &row_idx);
        let symbolic = factorize_symbolic_cholesky(
            pattern,
            Side::Lower,
            SymmetricOrdering::Amd,
            CholeskySymbolicParams::default(),
        )
        .ok()?;
        let factor_memory = MemBuffer::new(
            symbolic.factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default()),
        );
        let solve_memory =
            MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(Self::MAX_COLUMNS, Par::Seq));
        Some(Self {
            factor: vec![0.0; symbolic.len_val()],
            values: vec![0.0; row_idx.len()],
            col_ptr,
            row_idx,
            source,
            symbolic,
            factor_memory,
            solve_memory,
        })
    }

    /// The factor's entries.
    pub(crate) fn entries(&self) -> usize {
        self.factor.len()
    }

    /// Bytes held by the matrix and its factor.
    pub(crate) fn bytes(&self) -> usize {
        4 * (self.col_ptr.len() + self.row_idx.len())
            + 8 * (self.source.len() + self.values.len() + self.factor.len())
    }

    /// Factorizes `a` (the pattern given to [`ScalarCholesky::new`]); `Err`
    /// if it is not positive definite.
    pub(crate) fn factorize(&mut self, a: &Csr) -> Result<(), ()> {
        for (v, &k) in self.values.iter_mut().zip(&self.source) {
            *v = a.values[k];
        }
        let n = self.col_ptr.len() - 1;
        let pattern =
            SymbolicSparseColMatRef::new_checked(n, n, &self.col_ptr, None, &self.row_idx);
        self.symbolic
            .factorize_numeric_llt(
                &mut self.factor,
                SparseColMatRef::new(pattern, &self.values),
                Side::Lower,
                LltRegularization::default(),
                Par::Seq,
                MemStack::new(&mut self.factor_memory),
                Default::default(),
            )
            .map(|_| ())
            .map_err(|_| ())
    }

    /// Solves `A X = B` in place with the last factorization for the
    /// right-hand sides stored one after the other in `x` (at most
    /// [`ScalarCholesky::MAX_COLUMNS`]): one pass over the factor for all
    /// of them.
    pub(crate) fn solve(&mut self, x: &mut [f64]) {
        let n = self.col_ptr.len() - 1;
        let columns = x.len() / n.max(1);
        debug_assert!(columns <= Self::MAX_COLUMNS && columns * n == x.len());
        let llt = faer::sparse::linalg::cholesky::LltRef::new(&self.symbolic, &self.factor);
        llt.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(x, n, columns),
            Par::Seq,
            MemStack::new(&mut self.solve_memory),
        );
    }
}
