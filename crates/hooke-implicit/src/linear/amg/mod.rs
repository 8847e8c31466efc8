//! Smoothed-aggregation algebraic multigrid on the 3x3-block system, as a
//! preconditioner for the filtered PCG (Vaněk, Mandel & Brezina 1996;
//! Tamstorf, Jones & McCormick, *Smoothed aggregation multigrid for cloth
//! simulation*, SIGGRAPH Asia 2015).
//!
//! # The hierarchy
//!
//! Constraints enter through the filtered matrix `Â = S A S + I − S`: it
//! has `A`'s pattern, is positive definite whenever `A` is, and on the free
//! subspace its solution is the constrained one (`Δv = y + z` with
//! `Â y = S(b − A z)`). On `Â`, level by level:
//!
//! 1. **Aggregates** of the particles (then of coarse nodes) by strength of
//!    connection on the blocks, `‖Â_ij‖_F ≥ θ √(‖Â_ii‖_F ‖Â_jj‖_F)`
//!    (`aggregation` module). A particle without strong neighbours — a
//!    pinned one, whose row of `Â` is the identity — is left to the smoother.
//! 2. **Near-null space** `B`: the six rigid-body modes of the current
//!    positions, `[I | e_k × (xᵢ − c)]`, filtered, `Sᵢ Bᵢ`: the motions the
//!    springs do not resist (and no constrained direction). Per aggregate,
//!    `B|_a = Q_a R_a`; the tentative prolongator is `T = diag(Q_a)` and the
//!    coarse near-null space `R`.
//! 3. **Smoothed prolongator** `P = (I − ω D⁻¹Â_F) T`, `D = diag(Â_F)`,
//!    `ω = 4/(3 λ_max(D⁻¹Â))`, with `Â_F` the filtered matrix whose
//!    couplings weaker than [`AmgSettings::filter`] are lumped into the
//!    diagonal blocks (on coarse levels `Â_F = Â`), and the **Galerkin**
//!    coarse operator
//!    `A_c = Pᵀ Â P`, in a pattern computed once and refilled.
//!
//! down to a level of at most [`AmgSettings::coarse_unknowns`] unknowns,
//! factorized by faer's sparse Cholesky.
//!
//! Every aggregate is a coarse node of six unknowns — an aggregate whose
//! modes span fewer (at a pin, or too small) pads `T` with zero columns,
//! which the Galerkin operator leaves uncoupled and gets a unit diagonal —
//! so that the transfers and coarse operators are stored in dense blocks,
//! 3x6 and 6x3 from the particles, 6x6 on coarse levels, one column index
//! per block (`bsr` module).
//!
//! # The cycle
//!
//! One V-cycle per preconditioner application: on every level a Chebyshev
//! sweep (of degree [`AmgSettings::fine_degree`] on the particles,
//! [`AmgSettings::coarse_degree`] on the coarse levels) preconditioned by the
//! inverses of the diagonal node blocks (3x3 per particle; on coarse levels
//! the 6x6 blocks of an aggregate's unknowns), on the interval
//! `[1.1 λ̂/30, 1.1 λ̂]` of `D⁻¹Â` (`λ̂` a power-iteration estimate),
//! restriction by `Pᵀ`, the coarse correction, prolongation by `P` and the
//! same sweep again. The pre- and post-sweeps are the same polynomial, so the
//! cycle is a symmetric positive-definite operator and PCG converges with it.
//! The finest level never copies `A`: its products go through
//! [`BlockMatrix::apply`] with the filters, `Â x = S A S x + (I − S) x`.
//!
//! # Reuse
//!
//! Aggregates, `T` and `P` are built once ([`Amg::build`]) and kept across
//! Newton iterations and steps; [`Amg::refresh`] refills only what depends on
//! the matrix's values: the diagonal-block inverses, the eigenvalue bounds,
//! the Galerkin operators `A_c = Pᵀ Â P` level by level and the coarse
//! factor; [`Amg::refresh_smoother`] only the finest level's smoother. The
//! linear solver ([`LinearSolver::Amg`](crate::LinearSolver::Amg)) refreshes
//! every level at every solve and rebuilds the hierarchy when a solve took
//! more than twice the iterations of the first solve after the last build;
//! [`AmgRenewal`](crate::AmgRenewal) has the lazier alternative and the
//! measurements behind the choice.

mod aggregation;
mod bsr;
pub(crate) mod coarse;
pub(crate) mod csr;
pub(crate) mod fine;
mod prolongation;
mod smoother;

use std::cell::RefCell;

use hooke_core::{ParameterError, Vec3};

use self::aggregation::{Graph, aggregate, strong_mask};
use self::bsr::{Bsr, for_each_block, zero};
use self::coarse::ScalarCholesky;
use self::csr::Csr;
use self::fine::Neighbours;
use self::prolongation::{MODES, smooth, tentative};
use self::smoother::{BlockInverse, Chebyshev, Sweep, largest_eigenvalue};
use crate::linear::cg::Preconditioner;
use crate::linear::filter::Filter;
use crate::linear::matrix::BlockMatrix;
use crate::linear::vector::{PARALLEL_MIN_PARTICLES, for_each_row};

/// Parameters of the multigrid hierarchy and cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AmgSettings {
    strength: f64,
    filter: f64,
    fine_degree: usize,
    coarse_degree: usize,
    coarse_unknowns: usize,
}

impl AmgSettings {
    /// Strength threshold `θ` in `[0, 1)` of the aggregation, threshold
    /// `θ_F` in `[0, 1)` of the filtered matrix that smooths the finest
    /// prolongator, Chebyshev degree of each smoothing sweep on every level
    /// (at least 1; [`AmgSettings::with_fine_degree`] sets the finest
    /// level's apart) and the size of the coarsest level (at least 6
    /// unknowns).
    ///
    /// # Errors
    /// [`ParameterError`] for a value outside those ranges.
    pub fn new(
        strength: f64,
        filter: f64,
        smoother_degree: usize,
        coarse_unknowns: usize,
    ) -> Result<Self, ParameterError> {
        for (name, value) in [("strength", strength), ("filter", filter)] {
            if !(0.0..1.0).contains(&value) {
                return Err(ParameterError::new("amg", name, value, "in [0, 1)"));
            }
        }
        check_degree("smoother_degree", smoother_degree)?;
        if coarse_unknowns < MODES {
            return Err(ParameterError::new(
                "amg",
                "coarse_unknowns",
                coarse_unknowns as f64,
                "at least 6",
            ));
        }
        Ok(Self {
            strength,
            filter,
            fine_degree: smoother_degree,
            coarse_degree: smoother_degree,
            coarse_unknowns,
        })
    }

    /// The same settings with Chebyshev sweeps of `degree` on the finest
    /// level.
    ///
    /// # Errors
    /// [`ParameterError`] if `degree` is 0.
    pub fn with_fine_degree(self, degree: usize) -> Result<Self, ParameterError> {
        check_degree("fine_degree", degree)?;
        Ok(Self {
            fine_degree: degree,
            ..self
        })
    }

    /// The strength-of-connection threshold `θ` of the aggregation.
    #[must_use]
    pub fn strength(&self) -> f64 {
        self.strength
    }

    /// The threshold `θ_F` below which a particle's coupling is lumped into
    /// its diagonal block in the matrix `Â_F` that smooths the finest
    /// prolongator, `P = (I − ω D_F⁻¹ Â_F) T`.
    #[must_use]
    pub fn filter(&self) -> f64 {
        self.filter
    }

    /// The Chebyshev degree of each pre- and post-smoothing sweep on the
    /// finest level, the particles.
    #[must_use]
    pub fn fine_degree(&self) -> usize {
        self.fine_degree
    }

    /// The Chebyshev degree of each pre- and post-smoothing sweep on the
    /// coarse levels.
    #[must_use]
    pub fn coarse_degree(&self) -> usize {
        self.coarse_degree
    }

    /// The largest number of unknowns solved directly on the coarsest level.
    #[must_use]
    pub fn coarse_unknowns(&self) -> usize {
        self.coarse_unknowns
    }
}

/// A Chebyshev degree, at least 1.
fn check_degree(name: &'static str, degree: usize) -> Result<(), ParameterError> {
    if degree == 0 {
        return Err(ParameterError::new("amg", name, 0.0, "at least 1"));
    }
    Ok(())
}

impl Default for AmgSettings {
    /// `θ = 0` (aggregates of every coupled neighbour: on a cloth with
    /// bending springs, a particle's neighbours two apart), `θ_F = 0.1`
    /// (on the cloth, stretch springs only), Chebyshev degree 1 on
    /// the particles and 2 on the coarse levels, a coarsest level of at
    /// most 2 000 unknowns. Measured on cloth of 100² … 1000² particles
    /// (`benches/README.md`): against `θ = θ_F ∈ {0.02, 0.08}`, a third
    /// fewer coarse unknowns and half the coarse operators' entries for a
    /// few more iterations and faster solves; against degree 1 everywhere,
    /// iterations that grow 1.3× instead of 1.8× from 100² to 1000²;
    /// against degree 2 everywhere, on the nearly flat cloth as many
    /// iterations within four, each with three products of the fine matrix
    /// instead of five, so solves 1.1–1.6× faster (more at larger sizes).
    /// On a curved, swinging cloth degree 2 on the particles saves more
    /// iterations (35 against 53 at 100²) and is as fast at 200², 1.2×
    /// slower at 400²; on a tetrahedral lattice it halves them.
    fn default() -> Self {
        Self {
            strength: 0.0,
            filter: 0.1,
            fine_degree: 1,
            coarse_degree: 2,
            coarse_unknowns: 2000,
        }
    }
}

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

/// Why a hierarchy could not be built or refreshed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AmgError {
    /// A particle's filtered diagonal block is not positive definite.
    NotPositiveDefinite(usize),
    /// A coarse operator is not positive definite (or not finite).
    CoarseNotPositiveDefinite,
    /// The coarsest level does not fit 32-bit indices.
    TooLarge,
}

/// A coarse level's operator: 6x6 blocks, one block row per aggregate.
type Coarse = Bsr<MODES, MODES>;

/// One level above the coarsest, of nodes of `N` unknowns (3 on the
/// particles, [`MODES`] on the aggregates): its operator (on coarse
/// levels), smoother, the transfer to the next level and its vectors.
#[derive(Debug)]
struct Level<const N: usize> {
    /// The operator; empty on the finest level, which reads the
    /// [`BlockMatrix`].
    a: Bsr<N, N>,
    inverse: BlockInverse<N>,
    chebyshev: Chebyshev,
    p: Bsr<N, MODES>,
    /// `Pᵀ`: `P` is fixed once built, and so is its transpose.
    r: Bsr<MODES, N>,
    /// `A P`, refilled before `A_next = R (A P)`.
    ap: Bsr<N, MODES>,
    /// The power method's last iterate (see [`Level::iterations`]).
    eigenvector: Vec<f64>,
    b: Vec<f64>,
    x: Vec<f64>,
    residual: Vec<f64>,
    sweep: Sweep,
}

/// The coarsest level.
#[derive(Debug)]
struct Coarsest {
    a: Coarse,
    /// `a` in scalar compressed rows, the factorization's input.
    scalar: Csr,
    /// `None` when the level has no unknowns.
    cholesky: Option<ScalarCholesky>,
    x: Vec<f64>,
}

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
        let (agg, count) = aggregate(&graph, settings.strength);
        let tent = tentative(&fine::rigid_modes(positions, filters), &agg, count);
        let strong = strong_mask(&graph, settings.filter);
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
            if unknowns <= settings.coarse_unknowns
                || 5 * unknowns > 4 * previous
                || levels.len() >= 9
            {
                break;
            }
            let graph = coarse_graph(&next);
            let (agg, count) = aggregate(&graph, settings.strength);
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

    /// The number of levels, the finest and the coarsest included.
    #[must_use]
    pub fn level_count(&self) -> usize {
        self.levels.len() + 2
    }

    /// The unknowns of each level, finest first; every aggregate of a
    /// coarse level has six.
    #[must_use]
    pub fn unknowns(&self) -> Vec<usize> {
        std::iter::once(self.fine.b.len())
            .chain(self.levels.iter().map(|l| l.b.len()))
            .chain(std::iter::once(self.coarsest.x.len()))
            .collect()
    }

    /// Bytes the hierarchy holds (operators, transfers, smoothers, factor
    /// and vectors; the fine matrix itself is not counted).
    #[must_use]
    pub fn bytes(&self) -> usize {
        self.fine.bytes()
            + self.levels.iter().map(Level::bytes).sum::<usize>()
            + self.coarsest.a.bytes()
            + self.coarsest.scalar.bytes()
            + self
                .coarsest
                .cholesky
                .as_ref()
                .map_or(0, ScalarCholesky::bytes)
            + self.neighbours.bytes()
            + 48 * self.xs.len()
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

/// A product `y = A x` on a level.
type Apply<'a> = &'a mut dyn FnMut(&[f64], &mut [f64]);

impl<const N: usize> Level<N> {
    /// A level with operator `a` (empty on the finest level), prolongator
    /// `p` (a block row per node) and the pattern `ap` of `A P`.
    fn new(a: Bsr<N, N>, p: Bsr<N, MODES>, ap: Bsr<N, MODES>) -> Self {
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
    fn bytes(&self) -> usize {
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
    /// (see [`tentative`]) — gets a unit diagonal, so that the operator
    /// stays positive definite and the padding's correction zero.
    fn restrict_operator(&self, next: &mut Coarse) {
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
    fn visit(&mut self, fine: Option<Apply<'_>>, transfer: Transfer<'_>) {
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
enum Transfer<'a> {
    Down(&'a mut [f64]),
    Up(&'a [f64]),
}

impl Level<3> {
    /// The finest level's block inverses, smoother interval and `Â P`.
    fn refresh_fine(
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
    fn refresh_fine_smoother(
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
        self.chebyshev = chebyshev(lambda, settings.fine_degree);
        Ok(())
    }
}

impl Level<MODES> {
    /// A coarse level's block inverses, smoother interval and `A P`.
    fn refresh_coarse(&mut self, settings: AmgSettings) -> Result<(), AmgError> {
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
        self.chebyshev = chebyshev(lambda, settings.coarse_degree);
        self.a.multiply_into(&self.p, &mut self.ap);
        Ok(())
    }
}

impl Coarsest {
    /// Factorizes the coarsest operator.
    fn factorize(&mut self) -> Result<(), AmgError> {
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
fn chebyshev(lambda: f64, degree: usize) -> Chebyshev {
    let high = EIGEN_SAFETY * lambda.max(f64::MIN_POSITIVE);
    Chebyshev {
        low: high / CHEBYSHEV_RATIO,
        high,
        degree,
    }
}

/// `ω = 4/(3 λ_max(D⁻¹A))` for `D = diag(A)`.
fn smoothing_weight(apply: &mut dyn FnMut(&[f64], &mut [f64]), diagonal: &[f64]) -> f64 {
    let inverse = |r: &[f64], z: &mut [f64]| {
        z.iter_mut()
            .zip(r.iter().zip(diagonal))
            .for_each(|(zi, (ri, di))| *zi = ri / di);
    };
    let lambda = largest_eigenvalue(
        apply,
        &inverse,
        &mut Vec::new(),
        diagonal.len(),
        EIGEN_ITERATIONS,
    );
    4.0 / (3.0 * EIGEN_SAFETY * lambda.max(f64::MIN_POSITIVE))
}

/// The node graph of a coarse level's operator: the Frobenius norms of its
/// blocks.
fn coarse_graph(a: &Coarse) -> Graph {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settings_name_the_parameter_out_of_range_and_set_the_finest_degree_apart() {
        let settings = AmgSettings::new(0.0, 0.1, 3, 100).unwrap();
        assert_eq!((settings.fine_degree(), settings.coarse_degree()), (3, 3));
        let settings = settings.with_fine_degree(1).unwrap();
        assert_eq!((settings.fine_degree(), settings.coarse_degree()), (1, 3));
        let defaults = AmgSettings::default();
        assert_eq!((defaults.fine_degree(), defaults.coarse_degree()), (1, 2));
        for (error, parameter) in [
            (settings.with_fine_degree(0), "fine_degree"),
            (AmgSettings::new(0.0, 0.1, 0, 100), "smoother_degree"),
            (AmgSettings::new(1.0, 0.1, 2, 100), "strength"),
            (AmgSettings::new(0.0, -0.1, 2, 100), "filter"),
            (AmgSettings::new(0.0, 0.1, 2, 5), "coarse_unknowns"),
        ] {
            assert_eq!(error.unwrap_err().parameter, parameter);
        }
    }
}
