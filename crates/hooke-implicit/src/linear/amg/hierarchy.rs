//! [`Amg`]: the hierarchy's build and refreshes, and the V-cycle as a
//! preconditioner.

use std::cell::RefCell;

use hooke_core::Vec3;

use super::aggregation::{aggregate, strong_mask};
use super::bsr::{Bsr, for_each_block, zero};
use super::coarse::ScalarCholesky;
use super::fine;
use super::level::{Coarsest, Level, Transfer, coarse_graph, smoothing_weight};
use super::prolongation::{MODES, smooth, tentative};
use super::{AmgError, AmgInfo, AmgSettings};
use crate::linear::cg::Preconditioner;
use crate::linear::filter::Filter;
use crate::linear::matrix::BlockMatrix;
use crate::linear::neighbours::Neighbours;
use crate::linear::vector::{PARALLEL_MIN_PARTICLES, for_each_row};

/// A smoothed-aggregation multigrid hierarchy for the filtered matrix
/// `Â = S A S + I − S` of a [`BlockMatrix`] (see the module docs).
#[derive(Debug)]
pub struct Amg {
    settings: AmgSettings,
    neighbours: Neighbours,
    fine: Level<3>,
    /// The coarse levels above the coarsest, finest first.
    levels: Vec<Level<MODES>>,
    coarsest: Coarsest,
    /// Scratch of the finest level's products.
    xs: Vec<Vec3>,
    ys: Vec<Vec3>,
}

impl Amg {
    /// Builds the hierarchy for `a` with `filters`, the near-null space
    /// taken from `positions` (one per particle).
    ///
    /// # Errors
    /// [`AmgError`] if a diagonal block or a coarse operator is not
    /// positive definite, or the coarsest level is too large.
    ///
    /// # Panics
    /// If `filters` or `positions` does not have one entry per row of `a`.
    pub fn build(
        a: &BlockMatrix,
        filters: &[Filter],
        positions: &[Vec3],
        settings: AmgSettings,
    ) -> Result<Self, AmgError> {
        let n = a.rows();
        assert!(
            filters.len() == n && positions.len() == n,
            "one filter and one position per particle"
        );
        let neighbours = Neighbours::new(a.pattern());
        let mut xs = vec![Vec3::zeros(); n];
        let mut ys = vec![Vec3::zeros(); n];
        // The finest level.
        let graph = fine::graph(a, filters, &neighbours);
        let (agg, count) = aggregate(&graph, settings.strength());
        let tent = tentative(&fine::rigid_modes(positions, filters), &agg, count);
        let strong = strong_mask(&graph, settings.filter());
        let mut at = fine::product_pattern(&neighbours, &tent.t, Some(&strong));
        fine::multiply_into(a, filters, &neighbours, &tent.t, Some(&strong), &mut at);
        let diagonal = fine::filtered_diagonal(a, filters, &neighbours, &strong);
        let omega = smoothing_weight(
            &mut |x, y| fine::apply(a, filters, x, y, &mut xs, &mut ys),
            &diagonal,
        );
        let p = smooth(&tent.t, &at, &diagonal, omega);
        let ap = fine::product_pattern(&neighbours, &p, None);
        let mut finest = Level::new(Bsr::default(), p, ap);
        finest.refresh_fine(a, filters, &neighbours, &mut xs, &mut ys, settings)?;
        let mut next = finest.r.product_pattern(&finest.ap);
        finest.restrict_operator(&mut next);
        let mut coarse_modes = tent.modes;
        // Coarse levels, while the level is large and coarsening shrinks it.
        let mut levels: Vec<Level<MODES>> = Vec::new();
        let mut previous = finest.b.len();
        loop {
            let unknowns = MODES * next.rows();
            if unknowns <= settings.coarse_unknowns()
                || 5 * unknowns > 4 * previous
                || levels.len() >= 9
            {
                break;
            }
            let graph = coarse_graph(&next);
            let (agg, count) = aggregate(&graph, settings.strength());
            if count == 0 {
                break;
            }
            let tent = tentative(&coarse_modes, &agg, count);
            let mut at = next.product_pattern(&tent.t);
            next.multiply_into(&tent.t, &mut at);
            let diagonal: Vec<f64> = (0..next.rows())
                .flat_map(|i| {
                    let block = next.position(i, i).map_or(zero(), |k| next.values[k]);
                    (0..MODES).map(move |r| block[r][r])
                })
                .collect();
            let omega = smoothing_weight(&mut |x, y| next.apply(x, y), &diagonal);
            let p = smooth(&tent.t, &at, &diagonal, omega);
            let ap = next.product_pattern(&p);
            let mut level = Level::new(std::mem::take(&mut next), p, ap);
            level.refresh_coarse(settings)?;
            next = level.r.product_pattern(&level.ap);
            level.restrict_operator(&mut next);
            previous = unknowns;
            levels.push(level);
            coarse_modes = tent.modes;
        }
        let scalar = next.to_scalar();
        let mut coarsest = Coarsest {
            cholesky: if next.rows() == 0 {
                None
            } else {
                Some(ScalarCholesky::new(&scalar).ok_or(AmgError::TooLarge)?)
            },
            x: vec![0.0; MODES * next.rows()],
            scalar,
            a: next,
        };
        coarsest.factorize()?;
        Ok(Self {
            settings,
            neighbours,
            fine: finest,
            levels,
            coarsest,
            xs,
            ys,
        })
    }

    /// Refills everything that depends on the values of `a` and the
    /// filters (whose pattern and aggregates are the ones built with): the
    /// smoothers' block inverses and eigenvalue bounds, the Galerkin
    /// operators `A_c = Pᵀ Â P` and the coarse factor.
    ///
    /// # Errors
    /// [`AmgError`] if a diagonal block or a coarse operator is not
    /// positive definite.
    pub fn refresh(&mut self, a: &BlockMatrix, filters: &[Filter]) -> Result<(), AmgError> {
        let Self {
            settings,
            neighbours,
            fine: finest,
            levels,
            coarsest,
            xs,
            ys,
        } = self;
        finest.refresh_fine(a, filters, neighbours, xs, ys, *settings)?;
        finest.restrict_operator(
            levels
                .first_mut()
                .map_or(&mut coarsest.a, |next| &mut next.a),
        );
        for l in 0..levels.len() {
            let (head, tail) = levels.split_at_mut(l + 1);
            let level = &mut head[l];
            level.refresh_coarse(*settings)?;
            level.restrict_operator(tail.first_mut().map_or(&mut coarsest.a, |next| &mut next.a));
        }
        coarsest.factorize()
    }

    /// Refills only the finest level's smoother for `a` and `filters`: its
    /// block inverses and eigenvalue bound, keeping the coarse operators of
    /// the last [`Amg::refresh`]. The cycle stays a symmetric
    /// positive-definite preconditioner — the smoother is the current
    /// matrix's and the coarse operators are positive definite — only a
    /// less exact one, for a tenth of a refresh's cost.
    ///
    /// # Errors
    /// [`AmgError::NotPositiveDefinite`] if a diagonal block is not positive
    /// definite.
    pub fn refresh_smoother(
        &mut self,
        a: &BlockMatrix,
        filters: &[Filter],
    ) -> Result<(), AmgError> {
        let settings = self.settings;
        self.fine
            .refresh_fine_smoother(a, filters, &mut self.xs, &mut self.ys, settings)
    }

    /// What the hierarchy holds: each level's unknowns and its bytes.
    #[must_use]
    pub fn info(&self) -> AmgInfo {
        let unknowns = std::iter::once(self.fine.b.len())
            .chain(self.levels.iter().map(|l| l.b.len()))
            .chain(std::iter::once(self.coarsest.x.len()))
            .collect();
        let bytes = self.fine.bytes()
            + self.levels.iter().map(Level::bytes).sum::<usize>()
            + self.coarsest.a.bytes()
            + self.coarsest.scalar.bytes()
            + self
                .coarsest
                .cholesky
                .as_ref()
                .map_or(0, ScalarCholesky::bytes)
            + self.neighbours.bytes()
            + 48 * self.xs.len();
        AmgInfo { unknowns, bytes }
    }

    /// The preconditioner `z = V(r)`, one V-cycle on `Â` of the filtered
    /// matrix `a` (with `filters`) the hierarchy was last refreshed with.
    pub fn cycle<'a>(&'a mut self, a: &'a BlockMatrix, filters: &'a [Filter]) -> Cycle<'a> {
        Cycle {
            amg: RefCell::new(self),
            a,
            filters,
        }
    }

    /// One V-cycle from the finest level's `b` into its `x`.
    fn v_cycle(&mut self, a: &BlockMatrix, filters: &[Filter]) {
        let Self {
            fine: finest,
            levels,
            coarsest,
            xs,
            ys,
            ..
        } = self;
        let mut fine_apply = |u: &[f64], v: &mut [f64]| fine::apply(a, filters, u, v, xs, ys);
        finest.visit(
            Some(&mut fine_apply),
            Transfer::Down(
                levels
                    .first_mut()
                    .map_or(&mut coarsest.x, |next| &mut next.b),
            ),
        );
        for l in 0..levels.len() {
            let (head, tail) = levels.split_at_mut(l + 1);
            let next_b = tail.first_mut().map_or(&mut coarsest.x, |next| &mut next.b);
            head[l].visit(None, Transfer::Down(next_b));
        }
        if let Some(cholesky) = &mut coarsest.cholesky {
            cholesky.solve(&mut coarsest.x);
        }
        for l in (0..levels.len()).rev() {
            let (head, tail) = levels.split_at_mut(l + 1);
            let next_x = tail.first().map_or(&coarsest.x, |next| &next.x);
            head[l].visit(None, Transfer::Up(next_x));
        }
        finest.visit(
            Some(&mut fine_apply),
            Transfer::Up(levels.first().map_or(&coarsest.x, |next| &next.x)),
        );
    }
}

/// The multigrid preconditioner for one solve: [`Amg::cycle`].
#[derive(Debug)]
pub struct Cycle<'a> {
    amg: RefCell<&'a mut Amg>,
    a: &'a BlockMatrix,
    filters: &'a [Filter],
}

impl Preconditioner for Cycle<'_> {
    fn apply(&self, r: &[Vec3], z: &mut [Vec3]) {
        let mut amg = self.amg.borrow_mut();
        for_each_block(&mut amg.fine.b, 3, PARALLEL_MIN_PARTICLES, |i, b| {
            b.copy_from_slice(r[i].as_slice());
        });
        amg.v_cycle(self.a, self.filters);
        let x = &amg.fine.x;
        for_each_row(z, |i, zi| {
            *zi = Vec3::new(x[3 * i], x[3 * i + 1], x[3 * i + 2])
        });
    }
}
