//! [`Blocks`]: a Hessian written out block by block.

use crate::{Hessian, Mat3, SymBlock, Vec3};

/// A Hessian written out: each particle's diagonal block, summed, and the
/// blocks between particles as added. A sink for evaluating terms outside
/// a step (the lab's spectrum, tests), where no matrix is assembled.
///
/// ```
/// use hooke_core::term::{Blocks, Hessian};
/// use hooke_core::{Mat3, SymBlock, Vec3};
///
/// let mut k = Blocks::new(2);
/// k.add_row(0, SymBlock::scaled_identity(2.0));
/// k.add_row(1, SymBlock::scaled_identity(2.0));
/// k.add_pair(0, 1, -2.0 * Mat3::identity());
/// let mut y = vec![Vec3::zeros(); 2];
/// k.apply(&[Vec3::x(), Vec3::x()], &mut y);
/// assert_eq!(y, [Vec3::zeros(), Vec3::zeros()]);
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Blocks {
    /// Per particle, the sum of its diagonal blocks.
    pub rows: Vec<SymBlock>,
    /// The blocks `(i, j, B)` between particles: `B` at `(i, j)`, `Bᵀ` at
    /// `(j, i)`.
    pub pairs: Vec<(usize, usize, Mat3)>,
}

impl Blocks {
    /// No blocks yet, for `n` particles.
    #[must_use]
    pub fn new(n: usize) -> Self {
        Self {
            rows: vec![SymBlock::default(); n],
            pairs: Vec::new(),
        }
    }

    /// `y = H x`.
    ///
    /// # Panics
    /// If `x` or `y` has fewer entries than the particles, or a block names
    /// a particle beyond them.
    pub fn apply(&self, x: &[Vec3], y: &mut [Vec3]) {
        for ((yi, row), xi) in y.iter_mut().zip(&self.rows).zip(x) {
            *yi = row.mul(*xi);
        }
        for &(i, j, block) in &self.pairs {
            y[i] += block * x[j];
            y[j] += block.tr_mul(&x[i]);
        }
    }
}

impl Hessian for Blocks {
    fn add_row(&mut self, i: usize, block: SymBlock) {
        self.rows[i].add_assign(&block);
    }

    fn add_pair(&mut self, i: usize, j: usize, block: Mat3) {
        self.pairs.push((i, j, block));
    }
}
