//! [`BlockMatrix`]: the assembled system matrix in 3x3 blocks, one per spring.

use hooke_core::{Mat3, Vec3};

use crate::block::SymBlock;
use crate::pattern::Pattern;
use crate::vector::for_each_row;

/// A symmetric `3n × 3n` matrix with the sparsity of a spring system: a
/// diagonal block per particle and, for each spring `s = (i, j)`, the
/// off-diagonal blocks `A_ij = A_ji = −K_s` with `K_s` symmetric.
///
/// Each `K_s` is stored once, as the six entries of a symmetric block, and
/// both of its off-diagonal positions refer to it through the [`Pattern`], so
/// a product reads `48 + 2·8` bytes per spring instead of the `2·(72 + 4)` of
/// a 3x3 block-row format or the `18·(8 + 8)` of a scalar compressed-column
/// one. The product gathers row by row, so it runs in parallel without
/// races.
#[derive(Debug, Clone)]
pub struct BlockMatrix {
    pub(crate) pattern: Pattern,
    pub(crate) diagonal: Vec<SymBlock>,
    pub(crate) springs: Vec<SymBlock>,
}

impl BlockMatrix {
    /// A zero matrix with the given pattern and `springs` spring blocks.
    #[must_use]
    pub fn zeros(pattern: Pattern, springs: usize) -> Self {
        let rows = pattern.rows();
        Self {
            pattern,
            diagonal: vec![SymBlock::default(); rows],
            springs: vec![SymBlock::default(); springs],
        }
    }

    /// The sparsity pattern.
    #[must_use]
    pub fn pattern(&self) -> &Pattern {
        &self.pattern
    }

    /// Number of block rows (particles).
    #[must_use]
    pub fn rows(&self) -> usize {
        self.diagonal.len()
    }

    /// The diagonal block of particle `i`.
    #[must_use]
    pub fn diagonal(&self, i: usize) -> Mat3 {
        self.diagonal[i].to_mat3()
    }

    /// The block `K_s` of spring `s`; the matrix holds `−K_s` at `(i, j)` and
    /// `(j, i)`.
    #[must_use]
    pub fn spring_block(&self, s: usize) -> Mat3 {
        self.springs[s].to_mat3()
    }

    /// The same matrix as a scalar compressed-column matrix with both
    /// triangles, for outside solvers and comparisons.
    #[must_use]
    pub fn to_scalar(&self) -> faer::sparse::SparseColMat<usize, f64> {
        let mut triplets = Vec::with_capacity(9 * (self.rows() + self.pattern.entry_count()));
        let mut push = |row: usize, col: usize, block: Mat3, sign: f64| {
            for r in 0..3 {
                for c in 0..3 {
                    triplets.push(faer::sparse::Triplet::new(
                        3 * row + r,
                        3 * col + c,
                        sign * block[(r, c)],
                    ));
                }
            }
        };
        for i in 0..self.rows() {
            push(i, i, self.diagonal(i), 1.0);
            for e in self.pattern.row(i) {
                push(i, e.column(), self.spring_block(e.spring()), -1.0);
            }
        }
        let dofs = 3 * self.rows();
        faer::sparse::SparseColMat::try_new_from_triplets(dofs, dofs, &triplets)
            .expect("block entries are in range and distinct")
    }

    /// `y = A x`.
    ///
    /// # Panics
    /// If `x` or `y` does not have one entry per row.
    pub fn apply(&self, x: &[Vec3], y: &mut [Vec3]) {
        assert!(
            x.len() == self.rows() && y.len() == self.rows(),
            "vector lengths must match the matrix"
        );
        for_each_row(y, |i, yi| *yi = self.row_product(i, x));
    }

    /// Row `i` of `A x`.
    #[inline]
    pub(crate) fn row_product(&self, i: usize, x: &[Vec3]) -> Vec3 {
        let mut off = Vec3::zeros();
        for e in self.pattern.row(i) {
            off += self.springs[e.spring()].mul(x[e.column()]);
        }
        self.diagonal[i].mul(x[i]) - off
    }
}
