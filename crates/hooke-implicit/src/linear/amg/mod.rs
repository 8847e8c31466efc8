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
//! [`BlockMatrix::apply`](crate::internals::BlockMatrix::apply) with the filters, `Â x = S A S x + (I − S) x`.
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
//!
//! # Scalar matrices
//!
//! The `scalar` module builds the same hierarchy on a scalar matrix, the
//! constant vector its near-null space: the quasi-Newton step's initial
//! Hessian on meshes whose factor would be large.

mod aggregation;
mod bsr;
pub(crate) mod coarse;
pub(crate) mod csr;
mod fine;
mod hierarchy;
mod level;
mod prolongation;
pub(crate) mod scalar;
mod settings;
mod smoother;

pub use self::hierarchy::{Amg, Cycle};
pub use self::settings::AmgSettings;

/// What a built hierarchy holds ([`Amg::info`]); the solves' iterations and
/// residuals are [`PcgInfo`](crate::linear::cg::PcgInfo)'s, as multigrid
/// preconditions CG.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct AmgInfo {
    /// The unknowns of each level, finest first, the coarsest included;
    /// every aggregate of a coarse level has six.
    pub unknowns: Vec<usize>,
    /// Bytes the hierarchy holds: operators, transfers, smoothers, the
    /// coarsest level's factor and vectors (the fine matrix itself is not
    /// counted).
    pub bytes: usize,
}

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
