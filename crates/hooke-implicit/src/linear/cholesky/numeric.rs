//! The numeric factorization of a step's matrix: its filtered blocks copied
//! into the laid-out lower triangle, blocks outside the pattern made up for
//! on the diagonal, routed springs carried on their paths, and faer's
//! `L Lᵀ` into preallocated storage.

use faer::dyn_stack::MemStack;
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Par, Side};
use hooke_core::Mat3;

use super::{CholeskyError, SparseCholesky};
use crate::linear::filter::Filter;
use crate::linear::matrix::BlockMatrix;

/// Particle count from which faer factorizes in parallel. On the issue's
/// cloth (`benches/solvers/`, 2 cores) faer's parallel factorization and
/// solve took 438 ms against 366 ms sequentially at 40 000 particles, and
/// 2.27 s against 2.63 s at 160 000; in converged steps of the falling
/// cloth it took 170 ms against 92 ms at 4 096 particles and 749 ms
/// against 411 ms at 10 000.
#[cfg(feature = "parallel")]
const PARALLEL_MIN_PARTICLES: usize = 100_000;

impl SparseCholesky {
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

/// Sequential for small systems, faer's rayon parallelism for large ones.
#[cfg(feature = "parallel")]
pub(super) fn parallelism(particles: usize) -> Par {
    if particles >= PARALLEL_MIN_PARTICLES {
        Par::rayon(0)
    } else {
        Par::Seq
    }
}

/// Sequential: the `parallel` feature is off.
#[cfg(not(feature = "parallel"))]
pub(super) fn parallelism(_particles: usize) -> Par {
    Par::Seq
}
