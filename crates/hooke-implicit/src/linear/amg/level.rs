//! The levels of the hierarchy: their operators, smoothers and transfers,
//! and one visit of the V-cycle to each.

use hooke_core::Vec3;

use super::aggregation::Graph;
use super::bsr::{Bsr, zero};
use super::coarse::ScalarCholesky;
use super::csr::Csr;
use super::fine;
use super::prolongation::MODES;
use super::smoother::{BlockInverse, Chebyshev, Sweep, largest_eigenvalue};
use super::{AmgError, AmgSettings};
use crate::linear::filter::Filter;
use crate::linear::matrix::BlockMatrix;
use crate::linear::neighbours::Neighbours;

/// Iterations of the power method estimating `λ_max(D⁻¹Â)` from a
/// pseudo-random start, when a hierarchy is built.
const EIGEN_ITERATIONS: usize = 12;
/// Iterations of the power method at a refresh, warm-started from the last
/// estimate's eigenvector.
const REFRESH_ITERATIONS: usize = 3;
/// The safety factor on the estimate (which lies below the true value).
const EIGEN_SAFETY: f64 = 1.1;
/// The Chebyshev interval is `[λ/RATIO, λ]`.
const CHEBYSHEV_RATIO: f64 = 30.0;

/// A coarse level's operator: 6x6 blocks, one block row per aggregate.
pub(super) type Coarse = Bsr<MODES, MODES>;

/// One level above the coarsest, of nodes of `N` unknowns (3 on the
/// particles, [`MODES`] on the aggregates): its operator (on coarse
/// levels), smoother, the transfer to the next level and its vectors.
#[derive(Debug)]
pub(super) struct Level<const N: usize> {
    /// The operator; empty on the finest level, which reads the
    /// [`BlockMatrix`].
    pub(super) a: Bsr<N, N>,
    pub(super) inverse: BlockInverse<N>,
    pub(super) chebyshev: Chebyshev,
    pub(super) p: Bsr<N, MODES>,
    /// `Pᵀ`: `P` is fixed once built, and so is its transpose.
    pub(super) r: Bsr<MODES, N>,
    /// `A P`, refilled before `A_next = R (A P)`.
    pub(super) ap: Bsr<N, MODES>,
    /// The power method's last iterate (see [`Level::iterations`]).
    pub(super) eigenvector: Vec<f64>,
    pub(super) b: Vec<f64>,
    pub(super) x: Vec<f64>,
    pub(super) residual: Vec<f64>,
    pub(super) sweep: Sweep,
}

/// The coarsest level.
#[derive(Debug)]
pub(super) struct Coarsest {
    pub(super) a: Coarse,
    /// `a` in scalar compressed rows, the factorization's input.
    pub(super) scalar: Csr,
    /// `None` when the level has no unknowns.
    pub(super) cholesky: Option<ScalarCholesky>,
    pub(super) x: Vec<f64>,
}

/// A product `y = A x` on a level.
type Apply<'a> = &'a mut dyn FnMut(&[f64], &mut [f64]);

impl<const N: usize> Level<N> {
    /// A level with operator `a` (empty on the finest level), prolongator
    /// `p` (a block row per node) and the pattern `ap` of `A P`.
    pub(super) fn new(a: Bsr<N, N>, p: Bsr<N, MODES>, ap: Bsr<N, MODES>) -> Self {
        let n = N * p.rows();
        let r = p.transpose();
        let zeros = || vec![0.0; n];
        Self {
            a,
            inverse: BlockInverse::new(p.rows()),
            chebyshev: Chebyshev {
                low: 0.0,
                high: 1.0,
                degree: 1,
            },
            p,
            r,
            ap,
            eigenvector: Vec::new(),
            b: zeros(),
            x: zeros(),
            residual: zeros(),
            sweep: Sweep {
                r: zeros(),
                d: zeros(),
                z: zeros(),
                q: zeros(),
            },
        }
    }

    /// Bytes held by the level's matrices and vectors.
    pub(super) fn bytes(&self) -> usize {
        self.a.bytes()
            + self.p.bytes()
            + self.r.bytes()
            + self.ap.bytes()
            + self.inverse.bytes()
            + 8 * (self.b.len() + self.x.len() + self.residual.len() + self.eigenvector.len())
            + 8 * (self.sweep.r.len()
                + self.sweep.d.len()
                + self.sweep.z.len()
                + self.sweep.q.len())
    }

    /// Power iterations for the smoother's interval: from a pseudo-random
    /// start the first time, warm-started from the last eigenvector after.
    fn iterations(&self) -> usize {
        if self.eigenvector.is_empty() {
            EIGEN_ITERATIONS
        } else {
            REFRESH_ITERATIONS
        }
    }

    /// The next level's Galerkin operator `R (A P)`; an unknown it does
    /// not couple — an aggregate's padding, whose column of `P` is zero
    /// (see [`tentative`](super::prolongation::tentative)) — gets a unit diagonal, so that the operator
    /// stays positive definite and the padding's correction zero.
    pub(super) fn restrict_operator(&self, next: &mut Coarse) {
        self.r.multiply_into(&self.ap, next);
        for i in 0..next.rows() {
            if let Some(k) = next.position(i, i) {
                let block = &mut next.values[k];
                for (r, row) in block.iter_mut().enumerate() {
                    if row[r] == 0.0 {
                        row[r] = 1.0;
                    }
                }
            }
        }
    }

    /// One visit of the V-cycle to the level, with `fine` the product on
    /// the finest level (`a` on the others): on the way down, pre-smooths
    /// from zero towards `A x = b` and restricts the residual into the next
    /// level's right-hand side; on the way up, adds the prolongated
    /// correction of the next level's solution and post-smooths.
    pub(super) fn visit(&mut self, fine: Option<Apply<'_>>, transfer: Transfer<'_>) {
        let Self {
            a: matrix,
            inverse,
            chebyshev,
            p,
            r,
            b,
            x,
            residual,
            sweep,
            ..
        } = self;
        let mut own = |u: &[f64], v: &mut [f64]| matrix.apply(u, v);
        let apply: Apply<'_> = match fine {
            Some(fine) => fine,
            None => &mut own,
        };
        let inverse = |r: &[f64], z: &mut [f64]| inverse.apply(r, z);
        match transfer {
            Transfer::Down(next_b) => {
                x.fill(0.0);
                chebyshev.smooth(apply, &inverse, b, x, true, sweep);
                apply(x, residual);
                residual
                    .iter_mut()
                    .zip(b.iter())
                    .for_each(|(ri, bi)| *ri = bi - *ri);
                r.apply(residual, next_b);
            }
            Transfer::Up(next_x) => {
                p.apply(next_x, residual);
                x.iter_mut()
                    .zip(residual.iter())
                    .for_each(|(xi, ci)| *xi += ci);
                chebyshev.smooth(apply, &inverse, b, x, false, sweep);
            }
        }
    }
}

/// The direction of a visit: the next level's right-hand side to restrict
/// into, or its solution to prolongate.
pub(super) enum Transfer<'a> {
    Down(&'a mut [f64]),
    Up(&'a [f64]),
}

impl Level<3> {
    /// The finest level's block inverses, smoother interval and `Â P`.
    pub(super) fn refresh_fine(
        &mut self,
        a: &BlockMatrix,
        filters: &[Filter],
        neighbours: &Neighbours,
        xs: &mut [Vec3],
        ys: &mut [Vec3],
        settings: AmgSettings,
    ) -> Result<(), AmgError> {
        self.refresh_fine_smoother(a, filters, xs, ys, settings)?;
        fine::multiply_into(a, filters, neighbours, &self.p, None, &mut self.ap);
        Ok(())
    }

    /// The finest level's block inverses and smoother interval.
    pub(super) fn refresh_fine_smoother(
        &mut self,
        a: &BlockMatrix,
        filters: &[Filter],
        xs: &mut [Vec3],
        ys: &mut [Vec3],
        settings: AmgSettings,
    ) -> Result<(), AmgError> {
        self.inverse
            .refill(|i, out| {
                let d = fine::diagonal_block(a, filters, i);
                *out = std::array::from_fn(|r| std::array::from_fn(|c| d[(r, c)]));
            })
            .map_err(AmgError::NotPositiveDefinite)?;
        let inverse = &self.inverse;
        let iterations = self.iterations();
        let lambda = largest_eigenvalue(
            &mut |x, y| fine::apply(a, filters, x, y, xs, ys),
            &|r, z| inverse.apply(r, z),
            &mut self.eigenvector,
            self.b.len(),
            iterations,
        );
        self.chebyshev = chebyshev(lambda, settings.fine_degree());
        Ok(())
    }
}

impl Level<MODES> {
    /// A coarse level's block inverses, smoother interval and `A P`.
    pub(super) fn refresh_coarse(&mut self, settings: AmgSettings) -> Result<(), AmgError> {
        let a = &self.a;
        self.inverse
            .refill(|node, out| *out = a.position(node, node).map_or(zero(), |k| a.values[k]))
            .map_err(|_| AmgError::CoarseNotPositiveDefinite)?;
        let inverse = &self.inverse;
        let iterations = self.iterations();
        let lambda = largest_eigenvalue(
            &mut |x, y| self.a.apply(x, y),
            &|r, z| inverse.apply(r, z),
            &mut self.eigenvector,
            self.b.len(),
            iterations,
        );
        self.chebyshev = chebyshev(lambda, settings.coarse_degree());
        self.a.multiply_into(&self.p, &mut self.ap);
        Ok(())
    }
}

impl Coarsest {
    /// Factorizes the coarsest operator.
    pub(super) fn factorize(&mut self) -> Result<(), AmgError> {
        match &mut self.cholesky {
            Some(c) => {
                self.a.scalar_values(&mut self.scalar.values);
                c.factorize(&self.scalar)
                    .map_err(|()| AmgError::CoarseNotPositiveDefinite)
            }
            None => Ok(()),
        }
    }
}

/// The smoother of `degree` on `[1.1 λ̂/30, 1.1 λ̂]`.
pub(super) fn chebyshev(lambda: f64, degree: usize) -> Chebyshev {
    let high = EIGEN_SAFETY * lambda.max(f64::MIN_POSITIVE);
    Chebyshev {
        low: high / CHEBYSHEV_RATIO,
        high,
        degree,
    }
}

/// `λ̂`, the power method's estimate of `λ_max(D⁻¹A)` from a pseudo-random
/// start (`A` applied by `apply`, `D⁻¹` by `inverse`, `n` unknowns).
pub(super) fn estimate_largest(
    apply: &mut dyn FnMut(&[f64], &mut [f64]),
    inverse: &dyn Fn(&[f64], &mut [f64]),
    n: usize,
) -> f64 {
    largest_eigenvalue(apply, inverse, &mut Vec::new(), n, EIGEN_ITERATIONS)
}

/// The prolongator smoothing weight `ω = 4/(3 · 1.1 λ̂)` for the estimate
/// `λ̂` of `λ_max(D⁻¹A)`.
pub(super) fn smoothing_weight_for(lambda: f64) -> f64 {
    4.0 / (3.0 * EIGEN_SAFETY * lambda.max(f64::MIN_POSITIVE))
}

/// `ω = 4/(3 λ_max(D⁻¹A))` for `D = diag(A)`.
pub(super) fn smoothing_weight(apply: &mut dyn FnMut(&[f64], &mut [f64]), diagonal: &[f64]) -> f64 {
    let inverse = |r: &[f64], z: &mut [f64]| {
        z.iter_mut()
            .zip(r.iter().zip(diagonal))
            .for_each(|(zi, (ri, di))| *zi = ri / di);
    };
    smoothing_weight_for(estimate_largest(apply, &inverse, diagonal.len()))
}

/// The node graph of a coarse level's operator: the Frobenius norms of its
/// blocks.
pub(super) fn coarse_graph(a: &Coarse) -> Graph {
    let norm =
        |block: &[[f64; MODES]; MODES]| block.iter().flatten().map(|v| v * v).sum::<f64>().sqrt();
    let mut g = Graph {
        ptr: vec![0],
        ..Graph::default()
    };
    for node in 0..a.rows() {
        let mut diagonal = 0.0;
        let (cols, blocks) = a.row(node);
        for (&other, block) in cols.iter().zip(blocks) {
            if other as usize == node {
                diagonal = norm(block);
            } else {
                g.adj.push(other);
                g.weight.push(norm(block));
            }
        }
        g.diagonal.push(diagonal);
        g.ptr.push(g.adj.len());
    }
    g
}
