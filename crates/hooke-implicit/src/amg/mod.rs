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
//! # The cycle
//!
//! One V-cycle per preconditioner application: on every level a Chebyshev
//! sweep of degree [`AmgSettings::smoother_degree`] preconditioned by the
//! inverses of the diagonal node blocks (3x3 per particle; on coarse levels
//! the up-to-6x6 blocks of an aggregate's unknowns), on the interval
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
//! the smoother at every solve, the whole hierarchy when a solve took more
//! than 1.5 times the iterations of the first solve after the last build, and
//! rebuilds it when a solve right after a full refresh took more than twice
//! as many.

mod aggregation;
pub(crate) mod coarse;
pub(crate) mod csr;
pub(crate) mod fine;
mod prolongation;
mod smoother;

use std::cell::RefCell;

use hooke_core::{ParameterError, Vec3};

use self::aggregation::{Graph, aggregate, strong_mask};
use self::coarse::ScalarCholesky;
use self::csr::Csr;
use self::fine::Neighbours;
use self::prolongation::{MODES, Tentative, smooth, tentative};
use self::smoother::{BlockInverse, Chebyshev, Sweep, largest_eigenvalue};
use crate::cg::Preconditioner;
use crate::filter::Filter;
use crate::matrix::BlockMatrix;

/// Parameters of the multigrid hierarchy and cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AmgSettings {
    strength: f64,
    filter: f64,
    smoother_degree: usize,
    coarse_unknowns: usize,
}

impl AmgSettings {
    /// Strength threshold `θ` in `[0, 1)` of the aggregation, threshold
    /// `θ_F` in `[0, 1)` of the filtered matrix that smooths the finest
    /// prolongator, Chebyshev degree of each smoothing sweep (at least 1)
    /// and the size of the coarsest level (at least 6 unknowns).
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
        if smoother_degree == 0 {
            return Err(ParameterError::new(
                "amg",
                "smoother_degree",
                0.0,
                "at least 1",
            ));
        }
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
            smoother_degree,
            coarse_unknowns,
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

    /// The Chebyshev degree of each pre- and post-smoothing sweep.
    #[must_use]
    pub fn smoother_degree(&self) -> usize {
        self.smoother_degree
    }

    /// The largest number of unknowns solved directly on the coarsest level.
    #[must_use]
    pub fn coarse_unknowns(&self) -> usize {
        self.coarse_unknowns
    }
}

impl Default for AmgSettings {
    /// `θ = 0` (aggregates of every coupled neighbour: on a cloth with
    /// bending springs, a particle's neighbours two apart), `θ_F = 0.1`
    /// (on the cloth, stretch springs only), Chebyshev degree 2, a
    /// coarsest level of at most 2 000 unknowns. Measured on cloth of
    /// 100² … 1000² particles (`benches/README.md`): against
    /// `θ = θ_F ∈ {0.02, 0.08}`, a third fewer coarse unknowns and half the
    /// coarse operators' entries for a few more iterations and faster
    /// solves; against degree 1, iterations that grow 1.4× instead of 1.8×
    /// from 100² to 1000² (21 → 30 against 24 → 43).
    fn default() -> Self {
        Self {
            strength: 0.0,
            filter: 0.1,
            smoother_degree: 2,
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

/// One level above the coarsest: its operator (on coarse levels), smoother,
/// the transfer to the next level and its vectors.
#[derive(Debug)]
struct Level {
    /// The operator; empty on the finest level, which reads the
    /// [`BlockMatrix`].
    a: Csr,
    inverse: BlockInverse,
    chebyshev: Chebyshev,
    p: Csr,
    /// `Pᵀ`: `P` is fixed once built, and so is its transpose.
    r: Csr,
    /// `A P`, refilled before `A_next = R (A P)`.
    ap: Csr,
    /// The power method's last iterate (see [`Level::eigenvalue`]).
    eigenvector: Vec<f64>,
    b: Vec<f64>,
    x: Vec<f64>,
    residual: Vec<f64>,
    sweep: Sweep,
}

/// The coarsest level.
#[derive(Debug)]
struct Coarsest {
    a: Csr,
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
    levels: Vec<Level>,
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
        let mut levels = Vec::new();
        // The finest level.
        let node_ptr: Vec<usize> = (0..=n).map(|i| 3 * i).collect();
        let graph = fine::graph(a, filters, &neighbours);
        let (agg, count) = aggregate(&graph, settings.strength);
        let tent = tentative(
            &fine::rigid_modes(positions, filters),
            &node_ptr,
            &agg,
            count,
        );
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
        let mut level = Level::new(Csr::default(), node_ptr, p, ap);
        let mut next = level.r.product_pattern(&level.ap);
        let Tentative {
            node_ptr: mut coarse_nodes,
            modes: mut coarse_modes,
            ..
        } = tent;
        level.refresh_fine(a, filters, &neighbours, &mut xs, &mut ys, settings)?;
        level.r.multiply_into(&level.ap, &mut next);
        levels.push(level);
        // Coarse levels, while the level is large and coarsening shrinks it.
        loop {
            let unknowns = next.rows();
            let previous = levels.last().expect("the finest level").b.len();
            if unknowns <= settings.coarse_unknowns
                || 5 * unknowns > 4 * previous
                || levels.len() >= 10
            {
                break;
            }
            let graph = csr_graph(&next, &coarse_nodes);
            let (agg, count) = aggregate(&graph, settings.strength);
            let tent = tentative(&coarse_modes, &coarse_nodes, &agg, count);
            if tent.t.cols == 0 {
                break;
            }
            let mut at = next.product_pattern(&tent.t);
            next.multiply_into(&tent.t, &mut at);
            let diagonal: Vec<f64> = (0..unknowns)
                .map(|i| next.position(i, i).map_or(1.0, |k| next.values[k]))
                .collect();
            let omega = smoothing_weight(&mut |x, y| next.apply(x, y), &diagonal);
            let p = smooth(&tent.t, &at, &diagonal, omega);
            let ap = next.product_pattern(&p);
            let a_next = std::mem::take(&mut next);
            let mut level = Level::new(a_next, coarse_nodes, p, ap);
            level.refresh_coarse(settings)?;
            next = level.r.product_pattern(&level.ap);
            level.r.multiply_into(&level.ap, &mut next);
            levels.push(level);
            coarse_nodes = tent.node_ptr;
            coarse_modes = tent.modes;
        }
        let mut coarsest = Coarsest {
            cholesky: if next.rows() == 0 {
                None
            } else {
                Some(ScalarCholesky::new(&next).ok_or(AmgError::TooLarge)?)
            },
            x: vec![0.0; next.rows()],
            a: next,
        };
        coarsest.factorize()?;
        Ok(Self {
            settings,
            neighbours,
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
            levels,
            coarsest,
            xs,
            ys,
        } = self;
        let count = levels.len();
        levels[0].refresh_fine(a, filters, neighbours, xs, ys, *settings)?;
        for l in 0..count {
            let (head, tail) = levels.split_at_mut(l + 1);
            let level = &mut head[l];
            if l > 0 {
                level.refresh_coarse(*settings)?;
            }
            let next = tail.first_mut().map_or(&mut coarsest.a, |next| &mut next.a);
            level.r.multiply_into(&level.ap, next);
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
        self.levels[0].refresh_fine_smoother(a, filters, &mut self.xs, &mut self.ys, settings)
    }

    /// The number of levels, the coarsest included.
    #[must_use]
    pub fn level_count(&self) -> usize {
        self.levels.len() + 1
    }

    /// The unknowns of each level, finest first.
    #[must_use]
    pub fn unknowns(&self) -> Vec<usize> {
        self.levels
            .iter()
            .map(|l| l.b.len())
            .chain(std::iter::once(self.coarsest.x.len()))
            .collect()
    }

    /// Bytes the hierarchy holds (operators, transfers, smoothers, factor
    /// and vectors; the fine matrix itself is not counted).
    #[must_use]
    pub fn bytes(&self) -> usize {
        let vectors = |l: &Level| {
            8 * (l.b.len() + l.x.len() + l.residual.len())
                + 8 * (l.sweep.r.len() + l.sweep.d.len() + l.sweep.z.len() + l.sweep.q.len())
        };
        self.levels
            .iter()
            .map(|l| {
                l.a.bytes()
                    + l.p.bytes()
                    + l.r.bytes()
                    + l.ap.bytes()
                    + l.inverse.bytes()
                    + vectors(l)
            })
            .sum::<usize>()
            + self.coarsest.a.bytes()
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

    /// One V-cycle from `levels[0].b` into `levels[0].x`.
    fn v_cycle(&mut self, a: &BlockMatrix, filters: &[Filter]) {
        let Self {
            levels,
            coarsest,
            xs,
            ys,
            ..
        } = self;
        let count = levels.len();
        for l in 0..count {
            let (head, tail) = levels.split_at_mut(l + 1);
            let level = &mut head[l];
            level.x.fill(0.0);
            let next_b = tail.first_mut().map_or(&mut coarsest.x, |next| &mut next.b);
            let Level {
                a: matrix,
                inverse,
                chebyshev,
                r,
                b,
                x,
                residual,
                sweep,
                ..
            } = level;
            let mut apply = |u: &[f64], v: &mut [f64]| {
                if l == 0 {
                    fine::apply(a, filters, u, v, xs, ys);
                } else {
                    matrix.apply(u, v);
                }
            };
            chebyshev.smooth(&mut apply, inverse, b, x, true, sweep);
            apply(x, residual);
            residual
                .iter_mut()
                .zip(b.iter())
                .for_each(|(ri, bi)| *ri = bi - *ri);
            r.apply(residual, next_b);
        }
        if let Some(cholesky) = &mut coarsest.cholesky {
            cholesky.solve(&mut coarsest.x);
        }
        for l in (0..count).rev() {
            let (head, tail) = levels.split_at_mut(l + 1);
            let level = &mut head[l];
            let next_x = tail.first().map_or(&coarsest.x, |next| &next.x);
            let Level {
                a: matrix,
                inverse,
                chebyshev,
                p,
                b,
                x,
                residual,
                sweep,
                ..
            } = level;
            p.apply(next_x, residual);
            x.iter_mut()
                .zip(residual.iter())
                .for_each(|(xi, ci)| *xi += ci);
            let mut apply = |u: &[f64], v: &mut [f64]| {
                if l == 0 {
                    fine::apply(a, filters, u, v, xs, ys);
                } else {
                    matrix.apply(u, v);
                }
            };
            chebyshev.smooth(&mut apply, inverse, b, x, false, sweep);
        }
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
        let fine = &mut amg.levels[0];
        for (i, ri) in r.iter().enumerate() {
            fine.b[3 * i..3 * i + 3].copy_from_slice(ri.as_slice());
        }
        amg.v_cycle(self.a, self.filters);
        let x = &amg.levels[0].x;
        for (i, zi) in z.iter_mut().enumerate() {
            *zi = Vec3::new(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
        }
    }
}

impl Level {
    /// A level with operator `a` (empty on the finest level), nodes
    /// `node_ptr`, prolongator `p` and the pattern `ap` of `A P`.
    fn new(a: Csr, node_ptr: Vec<usize>, p: Csr, ap: Csr) -> Self {
        let n = p.rows();
        let r = p.transpose();
        let zeros = || vec![0.0; n];
        Self {
            a,
            inverse: BlockInverse::new(node_ptr),
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

    /// Power iterations for the smoother's interval: from a pseudo-random
    /// start the first time, warm-started from the last eigenvector after.
    fn iterations(&self) -> usize {
        if self.eigenvector.is_empty() {
            EIGEN_ITERATIONS
        } else {
            REFRESH_ITERATIONS
        }
    }

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
            .refill(|i, _, out| {
                let d = fine::diagonal_block(a, filters, i);
                out.copy_from_slice(d.as_slice());
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
        self.chebyshev = chebyshev(lambda, settings);
        Ok(())
    }

    /// A coarse level's block inverses, smoother interval and `A P`.
    fn refresh_coarse(&mut self, settings: AmgSettings) -> Result<(), AmgError> {
        let a = &self.a;
        self.inverse
            .refill(|_, unknowns, out| {
                let (lo, k) = (unknowns.start, unknowns.len());
                for r in unknowns.clone() {
                    for c in unknowns.clone() {
                        out[(r - lo) * k + c - lo] = a.position(r, c).map_or(0.0, |p| a.values[p]);
                    }
                }
            })
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
        self.chebyshev = chebyshev(lambda, settings);
        self.a.multiply_into(&self.p, &mut self.ap);
        Ok(())
    }
}

impl Coarsest {
    /// Factorizes the coarsest operator.
    fn factorize(&mut self) -> Result<(), AmgError> {
        match &mut self.cholesky {
            Some(c) => c
                .factorize(&self.a)
                .map_err(|()| AmgError::CoarseNotPositiveDefinite),
            None => Ok(()),
        }
    }
}

/// The smoother on `[1.1 λ̂/30, 1.1 λ̂]`.
fn chebyshev(lambda: f64, settings: AmgSettings) -> Chebyshev {
    let high = EIGEN_SAFETY * lambda.max(f64::MIN_POSITIVE);
    Chebyshev {
        low: high / CHEBYSHEV_RATIO,
        high,
        degree: settings.smoother_degree,
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

/// The node graph of a coarse level's matrix, nodes owning the unknowns
/// `node_ptr[I]..node_ptr[I + 1]`.
fn csr_graph(a: &Csr, node_ptr: &[usize]) -> Graph {
    let nodes = node_ptr.len() - 1;
    let mut node_of = vec![0u32; a.rows()];
    for node in 0..nodes {
        node_of[node_ptr[node]..node_ptr[node + 1]].fill(node as u32);
    }
    let mut sums = vec![0.0; nodes];
    let mut seen = vec![usize::MAX; nodes];
    let mut g = Graph {
        ptr: vec![0],
        ..Graph::default()
    };
    let mut touched = Vec::new();
    for node in 0..nodes {
        touched.clear();
        for row in node_ptr[node]..node_ptr[node + 1] {
            let (cols, vals) = a.row(row);
            for (&c, &v) in cols.iter().zip(vals) {
                let other = node_of[c as usize] as usize;
                if seen[other] != node {
                    seen[other] = node;
                    sums[other] = 0.0;
                    touched.push(other);
                }
                sums[other] += v * v;
            }
        }
        touched.sort_unstable();
        let mut diagonal = 0.0;
        for &other in &touched {
            if other == node {
                diagonal = sums[other].sqrt();
            } else {
                g.adj.push(other as u32);
                g.weight.push(sums[other].sqrt());
            }
        }
        g.diagonal.push(diagonal);
        g.ptr.push(g.adj.len());
    }
    g
}
