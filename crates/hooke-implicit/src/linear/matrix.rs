//! [`BlockMatrix`]: the assembled system matrix in 3x3 blocks, one per spring.

use std::any::Any;
use std::ops::Range;
use std::sync::Arc;

use hooke_core::{Hessian, Mat3, SymBlock, Vec3};

use crate::linear::pattern::Pattern;
use crate::linear::vector::for_each_row2;
#[cfg(feature = "parallel")]
use crate::linear::vector::{MIN_CHUNK, PARALLEL_MIN_PARTICLES};

/// A symmetric `3n × 3n` matrix with the sparsity of a spring system:
///
/// ```text
/// A = M̃ + Σ_s (eᵢ − eⱼ)(eᵢ − eⱼ)ᵀ ⊗ K_s,
/// ```
///
/// a diagonal block `m̃ᵢ I + Σ K_s` per particle (over the springs at it) and,
/// for each spring `s = (i, j)`, the off-diagonal blocks `A_ij = A_ji = −K_s`
/// with `K_s` symmetric. `m̃ᵢ` is the mass plus the air-damping term.
///
/// Each `K_s` is stored once, as the six entries of a symmetric block, in
/// the [`Pattern`]'s slot order. The product evaluates the sum above spring
/// by spring,
///
/// ```text
/// yᵢ = m̃ᵢ xᵢ + Σ_s ±K_s (xᵢ − xⱼ),
/// ```
///
/// reading each block once, with nine multiply-adds, and scattering `±` the
/// result to both ends. Per spring it reads 48 bytes of block and a 4-byte
/// column index; per particle `m̃ᵢ`, `xᵢ` and `yᵢ` — against `2·(72 + 4)`
/// bytes per spring for a 3x3 block-row format and `18·(8 + 8)` for a scalar
/// compressed-column one, and half the multiply-adds of a row-by-row
/// product. The diagonal blocks are kept for the preconditioner and the
/// Cholesky factorization; the product does not read them.
///
/// In parallel, the rows are cut into chunks at least [`Pattern::bandwidth`]
/// long, so a chunk's springs reach only into itself and the next chunk: the
/// even chunks run at once, each owning itself and its successor, then the
/// odd ones.
///
/// Contact and volume elements add terms beyond the springs' pattern: a
/// block on the diagonal of a particle near an obstacle or in an element
/// (kept in its diagonal block too), and a block between two particles of
/// a close pair of surface primitives or of an element (a general 3 × 3
/// block: an element's Hessian couples its vertices' coordinates
/// unsymmetrically). Blocks between particles a spring joins are summed
/// per slot and multiplied with the spring's; the product adds the others
/// after the springs' terms. A matrix of springs alone holds none. The
/// diagonal blocks the preconditioners read also carry, for each element
/// block between particles no spring joins, a bound that keeps them
/// positive definite without it
/// ([`Terms::assemble`](crate::Terms::assemble)).
///
/// The terms of the step's potential write into it as a [`Hessian`]: the
/// mass and air-damping terms into `m̃ᵢ`, the springs into their slots,
/// every other block as above.
#[derive(Debug, Clone)]
pub struct BlockMatrix {
    /// The pattern, shared with the springs' term that fills its slots.
    pub(crate) pattern: Arc<Pattern>,
    pub(crate) diagonal: Vec<SymBlock>,
    pub(crate) mass: Vec<f64>,
    pub(crate) springs: Vec<SymBlock>,
    /// Contact and element blocks on the diagonal, `(i, B)`: `yᵢ += B xᵢ`.
    pub(crate) extra_rows: Vec<(u32, SymBlock)>,
    /// Contact and element blocks between particles no spring joins,
    /// `(i, j, B)` with `i ≠ j`: `yᵢ += B xⱼ`, `yⱼ += Bᵀ xᵢ`.
    pub(crate) extra_pairs: Vec<(u32, u32, Mat3)>,
    /// Per slot (empty until a block between particles a spring joins is
    /// added): the sum of those blocks at `(r, c)`, `r < c` the slot's row
    /// and column, which the product, the preconditioners and the Cholesky
    /// factor read slot by slot with the springs' blocks.
    pub(crate) extra_at_slots: Vec<Mat3>,
}

/// The contact module's name for the sink its terms write into.
pub(crate) use hooke_core::Hessian as HessianBlocks;

/// The matrix as a term's sink: a diagonal block goes to its particle's
/// diagonal and the extra rows, a block between particles to its slot or
/// the extra pairs, a scaled identity to `m̃ᵢ` and the diagonal; the
/// springs' and volume elements' terms fill their slots through
/// [`Hessian::as_any_mut`].
impl Hessian for BlockMatrix {
    fn add_row(&mut self, i: usize, block: SymBlock) {
        self.add_extra_row(i, block);
    }

    fn add_pair(&mut self, i: usize, j: usize, block: Mat3) {
        self.add_extra_pair(i, j, block);
    }

    fn add_identity(&mut self, n: usize, scale: &(dyn Fn(usize) -> f64 + Sync)) {
        debug_assert_eq!(n, self.rows());
        for_each_row2(&mut self.diagonal, &mut self.mass, |i, diagonal, mass| {
            let s = scale(i);
            diagonal.add_assign(&SymBlock::scaled_identity(s));
            *mass += s;
        });
    }

    fn as_any_mut(&mut self) -> Option<&mut dyn Any> {
        Some(self)
    }
}

/// The diagonal blocks `(particle, block)` of the terms added, in order;
/// the blocks between particles are dropped.
#[derive(Debug, Default)]
pub(crate) struct DiagonalBlocks(pub(crate) Vec<(u32, SymBlock)>);

impl Hessian for DiagonalBlocks {
    fn add_row(&mut self, i: usize, block: SymBlock) {
        self.0.push((i as u32, block));
    }

    fn add_pair(&mut self, _: usize, _: usize, _: Mat3) {}
}

impl BlockMatrix {
    /// A zero matrix with the given pattern.
    #[must_use]
    pub fn zeros(pattern: impl Into<Arc<Pattern>>) -> Self {
        let pattern = pattern.into();
        let rows = pattern.rows();
        let slots = pattern.slots();
        Self {
            pattern,
            diagonal: vec![SymBlock::default(); rows],
            mass: vec![0.0; rows],
            springs: vec![SymBlock::default(); slots],
            extra_rows: Vec::new(),
            extra_pairs: Vec::new(),
            extra_at_slots: Vec::new(),
        }
    }

    /// The pattern alone, without values, for a step that assembles no
    /// matrix: the quasi-Newton step reads the springs' slots only, and on
    /// a million particles the values would cost 344 bytes a particle.
    pub(crate) fn unassembled(pattern: Arc<Pattern>) -> Self {
        Self {
            pattern,
            diagonal: Vec::new(),
            mass: Vec::new(),
            springs: Vec::new(),
            extra_rows: Vec::new(),
            extra_pairs: Vec::new(),
            extra_at_slots: Vec::new(),
        }
    }

    /// Zeroes the diagonal blocks and `m̃`, and forgets the contact and
    /// element blocks, for the terms to add themselves afresh (the
    /// springs' blocks are overwritten).
    pub(crate) fn clear(&mut self) {
        self.diagonal.fill(SymBlock::default());
        self.mass.fill(0.0);
        self.clear_extra();
    }

    /// Forgets the contact and element blocks.
    pub(crate) fn clear_extra(&mut self) {
        self.extra_rows.clear();
        self.extra_pairs.clear();
        self.extra_at_slots.fill(Mat3::zeros());
    }

    /// Adds the block `B` (symmetric) to particle `i`'s diagonal.
    pub(crate) fn add_extra_row(&mut self, i: usize, block: SymBlock) {
        self.diagonal[i].add_assign(&block);
        self.extra_rows.push((i as u32, block));
    }

    /// Adds the block `B` at `(i, j)` and `Bᵀ` at `(j, i)`, `i ≠ j`.
    pub(crate) fn add_extra_pair(&mut self, i: usize, j: usize, block: Mat3) {
        self.add_extra_pair_at(i, j, block, self.pattern.slot_between(i, j));
    }

    /// [`Self::add_extra_pair`] with the slot between `i` and `j` known
    /// (`None`: no spring joins them).
    #[inline(always)]
    pub(crate) fn add_extra_pair_at(
        &mut self,
        i: usize,
        j: usize,
        block: Mat3,
        slot: Option<usize>,
    ) {
        match slot {
            Some(t) => {
                if self.extra_at_slots.is_empty() {
                    self.extra_at_slots = vec![Mat3::zeros(); self.pattern.slots()];
                }
                self.extra_at_slots[t] += if i < j { block } else { block.transpose() };
            }
            None => self.extra_pairs.push((i as u32, j as u32, block)),
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
        self.pattern.rows()
    }

    /// The diagonal block of particle `i`.
    #[must_use]
    pub fn diagonal(&self, i: usize) -> Mat3 {
        self.diagonal[i].to_mat3()
    }

    /// The block at `(r, c)`, `r < c`, of the slot `t` joining particles
    /// `r` and `c`: `−K_s` of its spring plus the contact and element
    /// blocks between the two.
    pub(crate) fn slot_block(&self, t: usize) -> Mat3 {
        let spring = -self.springs[t].to_mat3();
        match self.extra_at_slots.get(t) {
            Some(extra) => spring + extra,
            None => spring,
        }
    }

    /// Whether every contact and element block between particles lies in
    /// the springs' pattern.
    pub(crate) fn extra_within_pattern(&self) -> bool {
        self.extra_pairs.is_empty()
    }

    /// The contact and element blocks `(i, j, B)` between particles no
    /// spring joins, which lie outside the pattern.
    pub(crate) fn extra_outside_pattern(&self) -> impl Iterator<Item = (usize, usize, Mat3)> + '_ {
        self.extra_pairs
            .iter()
            .map(|&(i, j, block)| (i as usize, j as usize, block))
    }

    /// The block `K_s` of spring `s`; the matrix holds `−K_s` at `(i, j)` and
    /// `(j, i)`.
    #[must_use]
    pub fn spring_block(&self, s: usize) -> Mat3 {
        self.springs[self.pattern.slot(s)].to_mat3()
    }

    /// The same matrix as a scalar compressed-column matrix with both
    /// triangles, for outside solvers and comparisons.
    #[must_use]
    pub fn to_scalar(&self) -> faer::sparse::SparseColMat<usize, f64> {
        let mut triplets = Vec::with_capacity(9 * (self.rows() + 2 * self.pattern.slots()));
        let mut push = |row: usize, col: usize, block: Mat3| {
            for r in 0..3 {
                for c in 0..3 {
                    triplets.push(faer::sparse::Triplet::new(
                        3 * row + r,
                        3 * col + c,
                        block[(r, c)],
                    ));
                }
            }
        };
        for i in 0..self.rows() {
            push(i, i, self.diagonal(i));
            for t in self.pattern.upper(i) {
                let (j, block) = (self.pattern.column(t), self.slot_block(t));
                push(i, j, block);
                push(j, i, block.transpose());
            }
        }
        for &(i, j, block) in &self.extra_pairs {
            push(i as usize, j as usize, block);
            push(j as usize, i as usize, block.transpose());
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
        let n = self.rows();
        assert!(
            x.len() == n && y.len() == n,
            "vector lengths must match the matrix"
        );
        #[cfg(feature = "parallel")]
        {
            let chunk = self.pattern.bandwidth().max(MIN_CHUNK);
            if n >= PARALLEL_MIN_PARTICLES && n >= 4 * chunk {
                use rayon::prelude::*;
                y.par_chunks_mut(2 * chunk)
                    .enumerate()
                    .for_each(|(k, pair)| {
                        pair.fill(Vec3::zeros());
                        let start = 2 * k * chunk;
                        self.product(start..(start + chunk).min(n), start, x, pair);
                    });
                y[chunk..]
                    .par_chunks_mut(2 * chunk)
                    .enumerate()
                    .for_each(|(k, pair)| {
                        let start = (2 * k + 1) * chunk;
                        self.product(start..(start + chunk).min(n), start, x, pair);
                    });
                self.extra_product(x, y);
                return;
            }
        }
        y.fill(Vec3::zeros());
        self.product(0..n, 0, x, y);
        self.extra_product(x, y);
    }

    /// Adds the terms of the contact and element blocks on the diagonal and
    /// outside the pattern to `y`.
    fn extra_product(&self, x: &[Vec3], y: &mut [Vec3]) {
        for (i, block) in &self.extra_rows {
            let i = *i as usize;
            y[i] += block.mul(x[i]);
        }
        for &(i, j, block) in &self.extra_pairs {
            let (i, j) = (i as usize, j as usize);
            y[i] += block * x[j];
            y[j] += block.tr_mul(&x[i]);
        }
    }

    /// Adds the terms of `rows` and their upper slots (springs, and the
    /// contact and element blocks between the same particles) to `y`, which
    /// holds the rows from `offset` on.
    #[inline]
    fn product(&self, rows: Range<usize>, offset: usize, x: &[Vec3], y: &mut [Vec3]) {
        for i in rows {
            let xi = x[i];
            let mut yi = self.mass[i] * xi;
            let slots = self.pattern.upper(i);
            for (t, (&j, block)) in slots.clone().zip(
                self.pattern.column[slots.clone()]
                    .iter()
                    .zip(&self.springs[slots]),
            ) {
                let xj = x[j as usize];
                let f = block.mul(xi - xj);
                yi += f;
                y[j as usize - offset] -= f;
                if let Some(extra) = self.extra_at_slots.get(t) {
                    yi += extra * xj;
                    y[j as usize - offset] += extra.tr_mul(&xi);
                }
            }
            y[i - offset] += yi;
        }
    }
}
