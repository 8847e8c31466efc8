//! [`AutoSettings`]: the constants of [`LinearSolver::Auto`](super::LinearSolver::Auto)'s rule.

/// The constants of [`LinearSolver::Auto`](super::LinearSolver::Auto)'s rule, with the measurements
/// behind them.
///
/// Below [`AutoSettings::trial_particles`] a step costs milliseconds
/// whatever the solver, and the factorization cost less than multigrid on
/// every scene measured (cloth, tetrahedral lattices, ropes; block-Jacobi
/// PCG stepped a tetrahedral cube of 729 particles at `h = 1/240 s` in
/// 1.9 ms against its 5.0 ms). From there on the trial solves the step's
/// matrix for the same pseudo-random right-hand side twice with each
/// candidate, the second run timed (the first touches fresh memory, as
/// later solves do not): the factorization (refill, numeric factorization
/// and solve), multigrid (the hierarchy's build is not timed, as it is kept
/// across steps; the smoother's refresh and the PCG solve are) and
/// block-Jacobi PCG, each to the default [`PcgSettings`](crate::PcgSettings) tolerance. The
/// factor is predicted from the fill of an approximate-minimum-degree
/// ordering of the particle graph.
///
/// One solve does not tell everything: a step's iterative solves are
/// inexact ([`Implicit::with_inexact_newton`](crate::Implicit::with_inexact_newton))
/// and their right-hand sides are not the trial's, and a solver changes
/// Newton's path; hence the comparison on whole steps, after which the
/// other's factor or hierarchy is dropped. Measured per converged step
/// (`cargo bench --bench solvers -- scene-step`, `benches/README.md`): a
/// rope of 10 001 particles steps in 15 ms with the factor and 101 ms with
/// multigrid; a tetrahedral lattice of 4 913 particles at `h = 1/240 s` in
/// 27 ms with block-Jacobi PCG, 226 ms with the factor and 1.04 s with
/// multigrid; a rule by size alone cannot tell these apart, and `auto`
/// keeps the fastest on both. Where two candidates' solves cost about the
/// same the trial alone can keep the one that is slower per step: on the
/// issue's 200×200 cloth swinging from its pins multigrid's trial solve
/// took 1.3–1.8 times the factorization's, while its inexact solves made a
/// converged step 1.6 times faster than the factorization's (4.9 s against
/// 7.9 s); the comparison on whole steps keeps multigrid there, and `auto`
/// steps in 5.1 s. [`LinearSolver::LaggedCholesky`](super::LinearSolver::LaggedCholesky) is not a candidate: its
/// worth shows only over a run of changing matrices.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AutoSettings {
    /// The particle count from which [`LinearSolver::Auto`](super::LinearSolver::Auto) decides by a
    /// trial: 2048.
    pub trial_particles: usize,
    /// The largest predicted Cholesky factor, in bytes, that the trial
    /// factorizes: 1 GiB. The cloth (`benches/solvers/`) has a
    /// predicted factor of 0.24 GB at 200×200 particles, 1.16 GB at
    /// 400×400 (where multigrid solves about as fast) and 9.3 GB at
    /// 1000×1000.
    pub factor_bytes: usize,
    /// The iterations a block-Jacobi PCG solve may take in the trial
    /// (beyond which it loses): 300.
    pub trial_pcg_iterations: usize,
    /// The fraction of the factorization's time within which an iterative
    /// candidate must solve the trial's system to be kept: 0.8. A direct
    /// solve costs the same whatever the matrix's conditioning, which
    /// changes during a run; an iterative solve's cost grows with it. On a
    /// 50×50 sheet at `k = 10⁴ N/m`, `h = 0.1 s` the trial timed multigrid
    /// at 6.2 ms against the factor's 6.5 ms, and two of the run's 136
    /// multigrid solves then stopped at their iteration cap. The margin
    /// alone cannot rule that out — once multigrid's solves became faster
    /// the same sheet chose it again, under load — so such a solve falls
    /// back to the factorization.
    pub iterative_margin: f64,
    /// How far apart, as a ratio of times, the trial's factorization and
    /// its fastest iterative candidate may be to be compared on whole
    /// steps: 3. Measuring the slower one costs one step at its speed, so
    /// candidates far apart are not measured: on the tetrahedral lattice of
    /// `benches/solvers/` the factorization takes 8.6 times
    /// block-Jacobi's time, on the rope multigrid 6.7 times the
    /// factorization's. On the 200×200 cloth swinging from its pins the
    /// trial's ratio was 1.3–1.8 where multigrid's steps were faster.
    pub probe_ratio: f64,
}

impl AutoSettings {
    /// The settings [`LinearSolver::Auto`](super::LinearSolver::Auto) uses.
    pub const DEFAULT: Self = Self {
        trial_particles: 2048,
        factor_bytes: 1 << 30,
        trial_pcg_iterations: 300,
        iterative_margin: 0.8,
        probe_ratio: 3.0,
    };
}

impl Default for AutoSettings {
    /// [`AutoSettings::DEFAULT`].
    fn default() -> Self {
        Self::DEFAULT
    }
}
