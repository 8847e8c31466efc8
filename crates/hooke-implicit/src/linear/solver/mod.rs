//! The linear solver of an implicit step: the choice ([`LinearSolver`],
//! [`auto`]'s trial), what it keeps per topology ([`topology`]), how
//! multigrid renews its hierarchy ([`renewal`]) and the solve every Newton
//! step takes ([`solve`]).

pub(crate) mod auto;
pub(crate) mod auto_settings;
pub(crate) mod renewal;
pub(crate) mod solve;
pub(crate) mod topology;

use hooke_core::Named;

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
    /// symbolic factorization is computed once per topology. With
    /// [`WeakSprings::Routed`](crate::WeakSprings) the factor is of a
    /// sparser matrix at least the step's, its weak springs (a cloth's
    /// bending springs) carried by the stiff springs between their ends,
    /// and preconditions CG on the step's matrix, which reaches Newton's
    /// forcing term or `10⁻²` (whichever is tighter) in two or three
    /// iterations.
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

    /// The settings of a PCG iteration (`pcg`, `amg` and
    /// `lagged-cholesky`): its relative residual tolerance and iteration
    /// cap; `None` for `auto` and `cholesky`, which take neither.
    #[must_use]
    pub const fn pcg(self) -> Option<PcgSettings> {
        match self {
            Self::Pcg(settings) | Self::Amg(settings) | Self::LaggedCholesky(settings) => {
                Some(settings)
            }
            Self::Auto | Self::Cholesky => None,
        }
    }

    /// The same solver, a PCG iteration (see [`LinearSolver::pcg`]) with
    /// `settings`; `auto` and `cholesky` take none and stay as they are.
    ///
    /// ```
    /// use hooke_implicit::{LinearSolver, PcgSettings};
    /// let loose = PcgSettings::new(1e-2, 50)?;
    /// assert_eq!(
    ///     LinearSolver::Pcg(PcgSettings::default()).with_pcg(loose),
    ///     LinearSolver::Pcg(loose)
    /// );
    /// assert_eq!(LinearSolver::Cholesky.with_pcg(loose), LinearSolver::Cholesky);
    /// # Ok::<(), hooke_core::ParameterError>(())
    /// ```
    #[must_use]
    pub const fn with_pcg(self, settings: PcgSettings) -> Self {
        match self {
            Self::Pcg(_) => Self::Pcg(settings),
            Self::Amg(_) => Self::Amg(settings),
            Self::LaggedCholesky(_) => Self::LaggedCholesky(settings),
            direct @ (Self::Auto | Self::Cholesky) => direct,
        }
    }

    /// The names of the PCG iterations (see [`LinearSolver::pcg`]), in the
    /// order of the table ([`Named::TABLE`]).
    pub fn iterative_names() -> impl Iterator<Item = &'static str> {
        Self::TABLE
            .iter()
            .filter(|(solver, _)| solver.pcg().is_some())
            .map(|&(_, name)| name)
    }
}

impl Named for LinearSolver {
    /// `"auto"`, `"cholesky"`, `"pcg"`, `"amg"` and `"lagged-cholesky"`, the
    /// iterative ones at [`PcgSettings::DEFAULT`]: the names scene files
    /// (`solver`), the command line (`--solver`), reports
    /// ([`StepReport::linear_solver`](hooke_core::StepReport::linear_solver))
    /// and messages use.
    ///
    /// ```
    /// use hooke_core::Named;
    /// use hooke_implicit::{LinearSolver, PcgSettings};
    /// let amg = LinearSolver::from_name("amg");
    /// assert_eq!(amg, Some(LinearSolver::Amg(PcgSettings::default())));
    /// assert_eq!(LinearSolver::from_name("multigrid"), None);
    /// ```
    const TABLE: &'static [(Self, &'static str)] = &[
        (Self::Auto, "auto"),
        (Self::Cholesky, "cholesky"),
        (Self::Pcg(PcgSettings::DEFAULT), "pcg"),
        (Self::Amg(PcgSettings::DEFAULT), "amg"),
        (
            Self::LaggedCholesky(PcgSettings::DEFAULT),
            "lagged-cholesky",
        ),
    ];
}
