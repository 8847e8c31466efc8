//! The symbolic side of the factorization, computed once per topology: the
//! order of the particles, the lower triangle of the scalar matrix laid out
//! in compressed columns in that order, and faer's symbolic analysis, which
//! also chooses the numeric factorization ([`Supernodes`]).

use faer::Side;
use faer::sparse::SymbolicSparseColMatRef;
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, SymbolicCholesky, SymmetricOrdering, factorize_symbolic_cholesky,
};

use super::Routes;
use crate::linear::neighbours::Neighbours;
use crate::linear::pattern::Pattern;

/// How [`SparseCholesky`](super::SparseCholesky) orders the unknowns to
/// reduce the factor's fill.
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

/// Which of faer's two numeric factorizations
/// [`SparseCholesky`](super::SparseCholesky) runs. faer's symbolic analysis
/// takes the supernodal one (dense blocks of columns, matrix–matrix
/// kernels) over the simplicial one (column by column) where the factor
/// averages more flops per entry than a threshold: `Σ (c + c(c + 1)/2) / Σ c` over the factor's column counts
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

/// The lower triangle of the scalar `3n × 3n` matrix in compressed
/// columns, the particles in the order of the factorization, and where each
/// slot's block goes in it.
pub(super) struct LowerTriangle {
    /// Where each column starts in `row_idx`, and the end.
    pub(super) col_ptr: Vec<u32>,
    /// Each column's rows, in increasing order.
    pub(super) row_idx: Vec<u32>,
    /// Per slot of the pattern, the position of the first entry of each of
    /// the three columns of its spring's block below the diagonal.
    pub(super) slot_columns: Vec<[u32; 3]>,
    /// Per slot, whether the block below the diagonal is the slot's block
    /// `(q, p)` itself (its row particle `q` ordered after its column
    /// particle `p`) rather than its transpose.
    pub(super) slot_upper: Vec<bool>,
}

impl LowerTriangle {
    /// The layout of matrices with the pattern `blocks` less the routed
    /// springs of `routes`, particle `q` in place `order[q]`: column
    /// `3k + c`, for the `k`-th particle `q` of the order, holds rows
    /// `3k + c..3k + 2` of `q`'s diagonal block, then rows `3l..3l + 2` for
    /// every neighbour of `q` whose place `l > k`, in increasing order.
    pub(super) fn new(blocks: &Pattern, order: &[u32], routes: &Routes) -> Self {
        let (n, springs) = (blocks.rows(), blocks.slots());
        let (dofs, nonzeros) = (3 * n, 6 * n + 9 * springs);
        let mut particle_at = vec![0; n];
        for (q, &k) in order.iter().enumerate() {
            particle_at[k as usize] = q;
        }
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
        Self {
            col_ptr,
            row_idx,
            slot_columns,
            slot_upper,
        }
    }
}

/// faer's symbolic factorization of the `dofs × dofs` matrix whose lower
/// triangle has the compressed columns `col_ptr`, `row_idx`, in the
/// particles' order or ordered by faer ([`FillOrdering`]), its numeric
/// factorization chosen by `supernodes`. faer analyses a matrix it does
/// not order from its upper triangle, built here and dropped after.
pub(super) fn analyse(
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
