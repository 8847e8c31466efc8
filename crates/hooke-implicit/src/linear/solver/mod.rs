//! The linear solver of an implicit step: the choice ([`LinearSolver`],
//! [`auto`]'s trial), what it keeps per topology ([`topology`]), how
//! multigrid renews its hierarchy ([`renewal`]) and the solve every Newton
//! step takes ([`solve`]).

pub(crate) mod auto;
pub(crate) mod auto_settings;
pub(crate) mod renewal;
pub(crate) mod solve;
pub(crate) mod topology;

use crate::linear::cg::PcgSettings;

pub use self::auto_settings::AutoSettings;
pub use self::renewal::AmgRenewal;

/// How the linear system of each Newton step is solved.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum LinearSolver {
    /// Baraff–Witkin's constraint-filtered PCG with a block-Jacobi
    /// preconditioner, warm-started from the previous step's velocity change.
    Pcg(PcgSettings),
    /// Sparse Cholesky (`L Lᵀ`, AMD ordering) of the filtered matrix; the
    /// symbolic factorization is computed once per topology.
    Cholesky,
    /// The filtered PCG preconditioned by one V-cycle of smoothed-aggregation
    /// multigrid ([`Amg`](crate::internals::Amg), default
    /// [`AmgSettings`](crate::internals::AmgSettings)) on the filtered matrix
    /// `S A S + I − S`. The hierarchy is built at the first solve and kept
    /// across Newton iterations and steps; how much of it each solve renews
    /// is the integrator's [`AmgRenewal`] (by default every level's values,
    /// and the whole hierarchy once a solve takes twice the iterations of
    /// the first one after the build).
    Amg(PcgSettings),
    /// The filtered PCG preconditioned by a lagged sparse Cholesky factor:
    /// the factor `L Lᵀ` of an earlier matrix of the same topology (an
    /// earlier Newton iteration or step), `P⁻¹ r = S L⁻ᵀ L⁻¹ S r`. The
    /// first solve factorizes (and converges at once); a solve that takes
    /// more than [`LinearSolver::LAGGED_REFACTOR_ITERATIONS`] iterations has
    /// the next one factorize afresh. Each iteration costs two triangular
    /// solves, a tenth to a thirtieth of a factorization on cloth — but the
    /// factor is only as good as the matrix is unchanged: on a 20×20 sheet
    /// falling from rest (`tests/lagged_cholesky.rs`) the factor of one
    /// step takes 159 iterations to 10⁻¹² on the next step's matrix, where
    /// block-Jacobi takes 123, as springs turn and enter or leave the
    /// compressed clamp. [`LinearSolver::Auto`] does not choose it.
    LaggedCholesky(PcgSettings),
    /// Chooses by measured cost (the default; its constants and the
    /// measurements behind them are [`AutoSettings`]): below
    /// [`AutoSettings::trial_particles`] it takes
    /// [`LinearSolver::Cholesky`], otherwise the first solve times each
    /// candidate on the step's matrix — the factorization (if its predicted
    /// factor fits [`AutoSettings::factor_bytes`]), multigrid and
    /// block-Jacobi PCG — and keeps the fastest, an iterative one only
    /// within [`AutoSettings::iterative_margin`] of the factorization's
    /// time. An iterative choice made over an affordable factor falls back
    /// to the factorization for the rest of the run once a solve stops at
    /// its iteration cap. When the factorization and the fastest iterative
    /// candidate solved the trial within [`AutoSettings::probe_ratio`] of
    /// each other, the next two steps run one each and the faster per
    /// second simulated serves the rest of the run. The choice is reported
    /// in [`StepReport::linear_solver`](hooke_core::StepReport::linear_solver)
    /// and rests on timings, so a run that must be reproducible to the last
    /// bit names its solver.
    #[default]
    Auto,
}

impl LinearSolver {
    /// Iterations of a [`LinearSolver::LaggedCholesky`] solve beyond which
    /// the next solve factorizes again.
    pub const LAGGED_REFACTOR_ITERATIONS: usize = 10;

    /// Every solver's name as the scene files and reports spell it, in the
    /// order of the variants.
    pub const NAMES: [&'static str; 5] = ["pcg", "cholesky", "amg", "lagged-cholesky", "auto"];

    /// The solver's name as the scene files and reports spell it: `"pcg"`,
    /// `"cholesky"`, `"amg"`, `"lagged-cholesky"` or `"auto"`
    /// ([`LinearSolver::NAMES`]).
    #[must_use]
    pub fn name(self) -> &'static str {
        Self::NAMES[match self {
            Self::Pcg(_) => 0,
            Self::Cholesky => 1,
            Self::Amg(_) => 2,
            Self::LaggedCholesky(_) => 3,
            Self::Auto => 4,
        }]
    }
}
