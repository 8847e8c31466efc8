//! The linear solver of an implicit step: the choice, what it keeps per
//! topology, and the assemble-and-solve path every Newton step takes.

use std::time::{Duration, Instant};

use hooke_core::{StepError, StepReport, System, Vec3};

use crate::linear::amg::{Amg, AmgError, AmgSettings};
use crate::minimize::assembly::{Assembler, Linearization};
use crate::linear::cg::{self, BlockJacobi, PcgError, PcgInfo, PcgSettings, PcgWorkspace};
use crate::linear::cholesky::{SparseCholesky, predicted_factor_entries};
use crate::step::conditioning::Rates;
use crate::linear::filter::Filter;
use crate::linear::matrix::BlockMatrix;
use crate::linear::pattern::Pattern;

/// How the linear system of each Newton step is solved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LinearSolver {
    /// Baraff–Witkin's constraint-filtered PCG with a block-Jacobi
    /// preconditioner, warm-started from the previous step's velocity change.
    Pcg(PcgSettings),
    /// Sparse Cholesky (`L Lᵀ`, AMD ordering) of the filtered matrix; the
    /// symbolic factorization is computed once per topology.
    Cholesky,
    /// The filtered PCG preconditioned by one V-cycle of smoothed-aggregation
    /// multigrid ([`Amg`], default [`AmgSettings`]) on the filtered matrix
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
    /// Chooses by measured cost. Below [`LinearSolver::AUTO_TRIAL_PARTICLES`]
    /// particles it takes [`LinearSolver::Cholesky`] without a trial: there
    /// a step costs milliseconds whatever the solver, and the factorization
    /// cost less than multigrid on every scene measured (cloth, tetrahedral
    /// lattices, ropes; block-Jacobi PCG stepped a tetrahedral cube of 729
    /// particles at `h = 1/240 s` in 1.9 ms against its 5.0 ms). From there
    /// on the first solve starts with a trial: each candidate solves the
    /// step's matrix for the same pseudo-random right-hand side twice, the
    /// second run timed (the first touches fresh memory, as later solves do
    /// not), and the fastest is kept for the rest of the run —
    /// [`LinearSolver::Cholesky`] (refill, numeric factorization and solve;
    /// skipped when the factor, predicted from the fill of an
    /// approximate-minimum-degree ordering of the particle graph, would take
    /// more than [`LinearSolver::AUTO_FACTOR_BYTES`]), [`LinearSolver::Amg`]
    /// (the hierarchy's build is not timed, as it is kept across steps; the
    /// smoother's refresh and the PCG solve are) and [`LinearSolver::Pcg`]
    /// with block-Jacobi (capped at
    /// [`LinearSolver::AUTO_TRIAL_PCG_ITERATIONS`] iterations, beyond which
    /// it loses), each to the default [`PcgSettings`] tolerance; an
    /// iterative candidate is kept only if it takes at most
    /// [`LinearSolver::AUTO_ITERATIVE_MARGIN`] of the factorization's time.
    /// An iterative choice made over an affordable factor falls back to
    /// it: a solve that stops at its iteration cap is solved again by the
    /// factorization, which then serves the rest of the run, so that `auto`
    /// never leaves a capped solve where a factor fits.
    ///
    /// One solve does not tell everything: a step's iterative solves are
    /// inexact ([`Implicit::with_inexact_newton`](crate::Implicit::with_inexact_newton))
    /// and their right-hand sides are not the trial's, and a solver changes
    /// Newton's path. So when the factorization and the fastest iterative
    /// candidate solved the trial within [`LinearSolver::AUTO_PROBE_RATIO`]
    /// of each other, both are kept and measured on whole steps: the step
    /// after the trial's with the trial's choice, the next with the other,
    /// each timed per second simulated, and the faster serves the rest of
    /// the run (the other's factor or hierarchy is dropped).
    /// The choice is reported in [`StepReport::linear_solver`]. As it rests
    /// on timings it can differ between machines, and between runs where
    /// two candidates cost about the same: a run that must be reproducible
    /// to the last bit names its solver.
    ///
    /// Measured per converged step (`cargo bench --bench solvers --
    /// scene-step`, `benches/README.md`): a rope of 10 001 particles steps
    /// in 15 ms with the factor and 101 ms with multigrid; a tetrahedral
    /// lattice of 4 913 particles at `h = 1/240 s` in 27 ms with
    /// block-Jacobi PCG, 226 ms with the factor and 1.04 s with multigrid;
    /// a rule by size alone cannot tell these apart, and `auto` keeps the
    /// fastest on both. Where two candidates' solves cost about the same
    /// the trial alone can keep the one that is slower per step: on the
    /// issue's 200×200 cloth swinging from its pins multigrid's trial solve
    /// took 1.3–1.8 times the factorization's, while its inexact solves
    /// made a converged step 1.6 times faster than the factorization's
    /// (4.9 s against 7.9 s); the comparison on whole steps keeps
    /// multigrid there, and `auto` steps in 5.1 s.
    /// [`LinearSolver::LaggedCholesky`] is not a candidate: its worth shows
    /// only over a run of changing matrices.
    Auto,
}

impl LinearSolver {
    /// Iterations of a [`LinearSolver::LaggedCholesky`] solve beyond which
    /// the next solve factorizes again.
    pub const LAGGED_REFACTOR_ITERATIONS: usize = 10;

    /// The particle count from which [`LinearSolver::Auto`] decides by a
    /// trial.
    pub const AUTO_TRIAL_PARTICLES: usize = 2048;

    /// The largest predicted Cholesky factor, in bytes, that the trial of
    /// [`LinearSolver::Auto`] factorizes: 1 GiB. The cloth
    /// (`benches/solvers.rs`) has a predicted factor of 0.24 GB at 200×200
    /// particles, 1.16 GB at 400×400 (where multigrid solves about as fast)
    /// and 9.3 GB at 1000×1000.
    pub const AUTO_FACTOR_BYTES: usize = 1 << 30;

    /// The iterations a block-Jacobi PCG solve may take in the trial of
    /// [`LinearSolver::Auto`].
    pub const AUTO_TRIAL_PCG_ITERATIONS: usize = 300;

    /// The fraction of the factorization's time within which an iterative
    /// candidate must solve the trial's system for [`LinearSolver::Auto`]
    /// to keep it: 0.8. A direct solve costs the same whatever the matrix's
    /// conditioning, which changes during a run; an iterative solve's cost
    /// grows with it.
    /// On a 50×50 sheet at `k = 10⁴ N/m`, `h = 0.1 s` the trial timed
    /// multigrid at 6.2 ms against the factor's 6.5 ms, and two of the
    /// run's 136 multigrid solves then stopped at their iteration cap. The
    /// margin alone cannot rule that out — once multigrid's solves became
    /// faster the same sheet chose it again, under load — so such a solve
    /// now falls back to the factorization (see [`LinearSolver::Auto`]).
    pub const AUTO_ITERATIVE_MARGIN: f64 = 0.8;

    /// How far apart, as a ratio of times, the trial's factorization and its
    /// fastest iterative candidate may be for [`LinearSolver::Auto`] to
    /// compare them on whole steps: 3. Measuring the slower one costs one
    /// step at its speed, so candidates far apart are not measured: on the
    /// tetrahedral lattice of `benches/solvers.rs` the factorization takes
    /// 8.6 times block-Jacobi's time, on the rope multigrid 6.7 times the
    /// factorization's. On the 200×200 cloth swinging from its pins the
    /// trial's ratio was 1.3–1.8 where multigrid's steps were faster.
    pub const AUTO_PROBE_RATIO: f64 = 3.0;

    /// The solver's name as the scene files and reports spell it: `"pcg"`,
    /// `"cholesky"`, `"amg"`, `"lagged-cholesky"` or `"auto"`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Pcg(_) => "pcg",
            Self::Cholesky => "cholesky",
            Self::Amg(_) => "amg",
            Self::LaggedCholesky(_) => "lagged-cholesky",
            Self::Auto => "auto",
        }
    }
}

/// A solver as used: [`LinearSolver::Auto`] resolved, or to be resolved by
/// the trial at the first solve.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Choice {
    Pcg(PcgSettings),
    Cholesky,
    Amg(PcgSettings),
    Lagged(PcgSettings),
    Trial,
}

impl Choice {
    /// `solver` for `system`: `Auto` by its size, then by the trial.
    fn new(solver: LinearSolver, system: &System) -> Self {
        match solver {
            LinearSolver::Pcg(settings) => Self::Pcg(settings),
            LinearSolver::Cholesky => Self::Cholesky,
            LinearSolver::Amg(settings) => Self::Amg(settings),
            LinearSolver::LaggedCholesky(settings) => Self::Lagged(settings),
            LinearSolver::Auto if system.particle_count() >= LinearSolver::AUTO_TRIAL_PARTICLES => {
                Self::Trial
            }
            LinearSolver::Auto => Self::Cholesky,
        }
    }

    /// The name of the solver (see [`LinearSolver::name`]).
    fn name(self) -> &'static str {
        match self {
            Self::Pcg(_) => "pcg",
            Self::Cholesky => "cholesky",
            Self::Amg(_) => "amg",
            Self::Lagged(_) => "lagged-cholesky",
            Self::Trial => "auto",
        }
    }
}

impl Default for LinearSolver {
    /// [`LinearSolver::Auto`].
    fn default() -> Self {
        Self::Auto
    }
}

/// How [`LinearSolver::Amg`] renews its hierarchy from one solve to the
/// next ([`Implicit::with_amg_renewal`](crate::Implicit::with_amg_renewal)).
/// Its baseline is the iteration count of the first solve after the last
/// build.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub enum AmgRenewal {
    /// Every solve refreshes every level's values ([`Amg::refresh`]: the
    /// block inverses, the smoothers' intervals and the Galerkin coarse
    /// operators), and a solve that took more than twice the baseline has
    /// the next rebuild the hierarchy ([`Amg::build`]). The default: on a
    /// 200² cloth the refresh costs about four PCG iterations (21 ms), and
    /// it keeps the coarse operators those of the matrix being solved.
    #[default]
    EverySolve,
    /// Every solve refreshes only the finest level's smoother
    /// ([`Amg::refresh_smoother`]); a solve that took more than 1.5 times
    /// the baseline has the next refresh every level's values, and one that
    /// took more than twice it right after such a refresh has the next
    /// rebuild. Cheaper per solve, but coarse operators one step old cost
    /// a falling 200² cloth 2–8 times the iterations of fresh ones.
    SmootherOnly,
}

impl AmgRenewal {
    /// The renewal of a solve that renews no more than the policy asks.
    fn routine(self) -> Renewal {
        match self {
            Self::EverySolve => Renewal::Values,
            Self::SmootherOnly => Renewal::Smoother,
        }
    }
}

/// The multigrid hierarchy of [`LinearSolver::Amg`] and how much of it the
/// next solve renews.
#[derive(Debug)]
struct AmgState {
    amg: Option<Amg>,
    policy: AmgRenewal,
    /// Iterations of the first solve after the last build (0: none yet).
    baseline: usize,
    next: Renewal,
}

/// How much of the hierarchy a solve renews.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Renewal {
    /// The finest level's smoother ([`Amg::refresh_smoother`]).
    Smoother,
    /// Every level's values ([`Amg::refresh`]).
    Values,
    /// Everything ([`Amg::build`]).
    Hierarchy,
}

impl AmgState {
    fn new(policy: AmgRenewal) -> Self {
        Self {
            amg: None,
            policy,
            baseline: 0,
            next: policy.routine(),
        }
    }

    /// Drops the hierarchy and its history.
    fn clear(&mut self) {
        *self = Self::new(self.policy);
    }

    /// The renewal after a solve of `iterations` that followed `renewal`
    /// (see [`AmgRenewal`]).
    fn after(&mut self, renewal: Renewal, iterations: usize) {
        let routine = self.policy.routine();
        self.next = if renewal == Renewal::Hierarchy || self.baseline == 0 {
            self.baseline = iterations.max(1);
            routine
        } else if renewal == Renewal::Values && iterations > 2 * self.baseline {
            Renewal::Hierarchy
        } else if 2 * iterations > 3 * self.baseline {
            Renewal::Values
        } else {
            routine
        };
    }
}

/// The settings of the PCG solve that a Cholesky factor preconditions when
/// contact couples particles outside the factor's pattern: to a relative
/// residual of 10⁻¹⁰ (about a direct solve's), at most 200 iterations.
const CONTACT_PCG: PcgSettings = PcgSettings {
    tolerance: 1e-10,
    max_iterations: 200,
};

/// What depends on the system's topology only.
#[derive(Debug)]
pub(crate) struct Topology {
    system: u64,
    /// The bounds that limit a substep's length.
    pub(crate) rates: Rates,
    matrix: BlockMatrix,
    jacobi: BlockJacobi,
    filters: Vec<Filter>,
    /// The solver in use: the one asked for, or the one `Auto` chose.
    solver: Choice,
    cholesky: Option<SparseCholesky>,
    /// Whether the next [`LinearSolver::LaggedCholesky`] solve factorizes.
    refactor: bool,
    amg: AmgState,
    /// Whether an iterative solve that stops at its cap falls back to the
    /// factorization: when [`LinearSolver::Auto`] chose the iterative
    /// solver over an affordable factor.
    fallback: bool,
    /// [`LinearSolver::Auto`]'s comparison of two candidates on whole
    /// steps, while it lasts.
    probe: Option<Probe>,
}

/// [`LinearSolver::Auto`]'s comparison of the trial's choice and its
/// runner-up (the factorization or the fastest iterative candidate) on
/// whole steps.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Probe {
    /// The candidate not in use.
    other: Choice,
    /// Steps ended since the trial (the trial's own is not measured).
    steps: usize,
    /// The wall time per second simulated of the first measured step.
    first: f64,
}

impl Probe {
    fn new(other: Choice) -> Self {
        Self {
            other,
            steps: 0,
            first: 0.0,
        }
    }
}

impl Topology {
    /// The sparsity pattern.
    pub(crate) fn pattern(&self) -> &Pattern {
        self.matrix.pattern()
    }

    /// The matrix last assembled.
    pub(crate) fn matrix(&self) -> &BlockMatrix {
        &self.matrix
    }

    /// The matrix last assembled, for the contact terms.
    pub(crate) fn matrix_mut(&mut self) -> &mut BlockMatrix {
        &mut self.matrix
    }

    /// Renews the block-Jacobi inverses of the rows that contact terms
    /// added to after the assembly, whose own diagonal blocks (the volume
    /// elements' among them) end at `assembled` in the list.
    pub(crate) fn contacts_added(&mut self, assembled: usize) {
        for &(i, _) in &self.matrix.extra_rows[assembled..] {
            let i = i as usize;
            if let Some(inverse) = self.matrix.diagonal[i].inverse_if_positive_definite() {
                self.jacobi.inverses[i] = inverse;
            }
        }
    }

    /// Ends a step of `dt` that took `elapsed` of wall time, for
    /// [`LinearSolver::Auto`]'s comparison on whole steps: the step after
    /// the trial's is measured with the trial's choice, the next with the
    /// other candidate, and the faster per second simulated is kept (see
    /// [`LinearSolver::Auto`]).
    pub(crate) fn step_ended(&mut self, elapsed: Duration, dt: f64) {
        let Some(probe) = &mut self.probe else {
            return;
        };
        let cost = elapsed.as_secs_f64() / dt;
        probe.steps += 1;
        match probe.steps {
            1 => return,
            2 => {
                probe.first = cost;
                std::mem::swap(&mut self.solver, &mut probe.other);
            }
            _ => {
                if cost > probe.first {
                    std::mem::swap(&mut self.solver, &mut probe.other);
                }
                self.probe = None;
                if self.solver == Choice::Cholesky {
                    self.amg.clear();
                } else {
                    self.cholesky = None;
                }
            }
        }
        // The factor is affordable whenever the two are compared.
        self.fallback = self.solver != Choice::Cholesky;
    }
}

/// The topology-dependent parts for `system`, rebuilt when the system
/// changes or none were built yet (the step's history is keyed on the system
/// too, so it restarts then).
pub(crate) fn topology<'a>(
    cached: &'a mut Option<Topology>,
    solver: LinearSolver,
    renewal: AmgRenewal,
    system: &System,
) -> Result<&'a mut Topology, StepError> {
    if cached.as_ref().is_some_and(|t| t.system != system.id()) {
        *cached = None;
    }
    if cached.is_none() {
        let matrix = BlockMatrix::zeros(Pattern::new(system)?);
        let solver = Choice::new(solver, system);
        let cholesky = match solver {
            Choice::Cholesky | Choice::Lagged(_) => Some(SparseCholesky::new(&matrix)?),
            _ => None,
        };
        let filters = (0..system.particle_count())
            .map(|i| {
                if system.is_pinned(i) {
                    Filter::Fixed
                } else {
                    Filter::Free
                }
            })
            .collect();
        *cached = Some(Topology {
            system: system.id(),
            rates: Rates::new(system),
            matrix,
            jacobi: BlockJacobi::default(),
            filters,
            solver,
            cholesky,
            refactor: true,
            amg: AmgState::new(renewal),
            fallback: false,
            probe: None,
        });
    }
    Ok(cached.as_mut().expect("built above"))
}

/// What every linear solve of a step shares.
#[derive(Clone, Copy)]
pub(crate) struct Solve<'a> {
    pub(crate) system: &'a System,
    pub(crate) strict: bool,
    pub(crate) time: f64,
    /// The relative residual an iterative solve may stop at when that is
    /// looser than its settings' (Newton's forcing term; `0` for none).
    pub(crate) forcing: f64,
}

impl Solve<'_> {
    /// Assembles the linearisation `lin` into the topology's matrix and `b`.
    ///
    /// # Errors
    /// As [`Assembler::assemble`].
    pub(crate) fn assemble(
        self,
        assembler: &mut Assembler,
        topology: &mut Topology,
        lin: &Linearization<'_>,
        b: &mut [Vec3],
    ) -> Result<(), StepError> {
        let Topology { matrix, jacobi, .. } = topology;
        assembler.assemble(self.system, lin, matrix, jacobi, b, self.time)
    }

    /// Solves the filtered system `S A x = S b` last assembled (and amended)
    /// at `positions` into `x` (a warm start on entry), recording the solve
    /// and the force evaluation of its assembly in `report`.
    ///
    /// # Errors
    /// [`StepError::NoConvergence`] in strict mode when PCG stops at its
    /// cap, [`StepError::NotPositiveDefinite`] when the filtered matrix is
    /// not positive definite.
    pub(crate) fn solve(
        self,
        topology: &mut Topology,
        positions: &[Vec3],
        b: &[Vec3],
        x: &mut [Vec3],
        workspace: &mut PcgWorkspace,
        report: &mut StepReport,
    ) -> Result<(), StepError> {
        let Self {
            strict,
            time,
            forcing,
            ..
        } = self;
        if topology.solver == Choice::Trial {
            (topology.solver, topology.fallback, topology.probe) =
                trial(topology, positions, workspace, time)?;
        }
        let Topology {
            matrix,
            jacobi,
            filters,
            solver,
            cholesky,
            refactor,
            amg,
            fallback,
            probe,
            ..
        } = topology;
        report.force_evaluations += 1;
        report.linear_solves += 1;
        report.linear_solver = solver.name();
        let pcg = |result: Result<PcgInfo, PcgError>, report: &mut StepReport| {
            let info = match result {
                Ok(info) => info,
                Err(PcgError::NoConvergence(info)) if !strict => {
                    report.unconverged_solves += 1;
                    info
                }
                Err(PcgError::NoConvergence(info)) => {
                    return Err(StepError::NoConvergence {
                        time,
                        iterations: info.iterations,
                        residual: info.residual,
                    });
                }
                Err(PcgError::NotPositiveDefinite(_)) => {
                    return Err(StepError::NotPositiveDefinite {
                        time,
                        particle: None,
                    });
                }
            };
            report.linear_iterations += info.iterations;
            report.linear_residual = report.linear_residual.max(info.residual);
            Ok(info)
        };
        // The stopped solve of an iterative choice that falls back.
        let mut capped = None;
        match *solver {
            Choice::Pcg(settings) => {
                let settings = settings.loosened(forcing);
                let solved = cg::solve(matrix, jacobi, filters, b, x, settings, workspace);
                match solved {
                    Err(PcgError::NoConvergence(info)) if *fallback => capped = Some(info),
                    solved => {
                        pcg(solved, report)?;
                    }
                }
            }
            Choice::Amg(settings) => {
                let not_positive_definite = |e: AmgError| match e {
                    AmgError::NotPositiveDefinite(particle) => StepError::NotPositiveDefinite {
                        time,
                        particle: Some(particle),
                    },
                    AmgError::CoarseNotPositiveDefinite => StepError::NotPositiveDefinite {
                        time,
                        particle: None,
                    },
                    AmgError::TooLarge => StepError::SystemTooLarge {
                        particles: matrix.rows(),
                        springs: matrix.pattern().slots(),
                    },
                };
                let renewal = if amg.amg.is_some() {
                    amg.next
                } else {
                    Renewal::Hierarchy
                };
                let hierarchy = match (&mut amg.amg, renewal) {
                    (Some(hierarchy), Renewal::Smoother) => {
                        hierarchy
                            .refresh_smoother(matrix, filters)
                            .map_err(not_positive_definite)?;
                        hierarchy
                    }
                    (Some(hierarchy), Renewal::Values) => {
                        hierarchy
                            .refresh(matrix, filters)
                            .map_err(not_positive_definite)?;
                        hierarchy
                    }
                    (slot, _) => {
                        // The old hierarchy goes first: two at once would
                        // double the solver's peak memory.
                        *slot = None;
                        slot.insert(
                            Amg::build(matrix, filters, positions, AmgSettings::default())
                                .map_err(not_positive_definite)?,
                        )
                    }
                };
                let cycle = hierarchy.cycle(matrix, filters);
                let loosened = settings.loosened(forcing);
                match cg::solve(matrix, &cycle, filters, b, x, loosened, workspace) {
                    Err(PcgError::NoConvergence(info)) if *fallback => capped = Some(info),
                    solved => {
                        let info = pcg(solved, report)?;
                        // CG's iterations grow like the logarithm of the
                        // tolerance: a loosened solve's count is scaled to
                        // the settings' one.
                        let scale = settings.tolerance().ln() / loosened.tolerance().ln();
                        amg.after(renewal, (info.iterations as f64 * scale).ceil() as usize);
                    }
                }
            }
            Choice::Lagged(settings) => {
                let factor = cholesky
                    .as_mut()
                    .expect("built with the topology for this solver");
                if *refactor {
                    factor
                        .factorize(matrix, filters)
                        .map_err(|particle| StepError::NotPositiveDefinite { time, particle })?;
                    *refactor = false;
                }
                let solved = pcg(
                    cg::solve(
                        matrix,
                        &factor.preconditioner(filters),
                        filters,
                        b,
                        x,
                        settings.loosened(forcing),
                        workspace,
                    ),
                    report,
                );
                *refactor = solved.as_ref().map_or(true, |info| {
                    info.iterations > LinearSolver::LAGGED_REFACTOR_ITERATIONS
                });
                solved?;
            }
            Choice::Trial => unreachable!("the trial resolved the choice above"),
            Choice::Cholesky => {}
        }
        if let Some(info) = capped {
            // Auto's iterative choice stopped at its cap where a factor is
            // affordable: the factorization solves this system and the
            // rest of the run.
            report.linear_iterations += info.iterations;
            report.linear_solver = Choice::Cholesky.name();
            *solver = Choice::Cholesky;
            *fallback = false;
            *probe = None;
            amg.clear();
            *cholesky = Some(SparseCholesky::new(matrix)?);
        }
        if *solver == Choice::Cholesky {
            let factor = cholesky
                .as_mut()
                .expect("built with the topology for this solver");
            factor
                .factorize(matrix, filters)
                .map_err(|particle| StepError::NotPositiveDefinite { time, particle })?;
            if factor.is_complete() {
                factor.solve_factored(filters, b, x);
            } else {
                // Blocks between particles in contact or in a volume
                // element that no spring joins lie outside the factor's
                // pattern: the factor of everything else (their diagonal
                // blocks included) preconditions PCG on the whole matrix.
                x.fill(Vec3::zeros());
                let settings = CONTACT_PCG.loosened(forcing);
                let preconditioner = factor.preconditioner(filters);
                pcg(
                    cg::solve(matrix, &preconditioner, filters, b, x, settings, workspace),
                    report,
                )?;
            }
        }
        Ok(())
    }
}

/// [`LinearSolver::Auto`]'s trial: solves the filtered system last
/// assembled, `S A y = S r`, for a right-hand side `r` of pseudo-random
/// components in `[−1, 1]` with each candidate ([`second_run`] timing
/// it), keeps what the chosen one built (the factor or the hierarchy) and
/// returns it — the fastest, but an iterative candidate only within
/// [`LinearSolver::AUTO_ITERATIVE_MARGIN`] of the factorization's time —,
/// whether it falls back to the factorization (an iterative choice
/// where the factor is affordable) and, when the factorization and the
/// fastest iterative candidate are within
/// [`LinearSolver::AUTO_PROBE_RATIO`], the comparison of the two on whole
/// steps, for which it keeps what both built. A
/// right-hand side of every frequency tries each preconditioner as
/// the later Newton systems will, where the step's own one may be smooth
/// (a cloth at rest under gravity) and flatter a preconditioner that only
/// damps smooth errors.
///
/// # Errors
/// [`StepError::NotPositiveDefinite`] when the factorization, or multigrid
/// where the factor is not tried, finds the matrix not positive definite;
/// the next solve tries again.
fn trial(
    topology: &mut Topology,
    positions: &[Vec3],
    workspace: &mut PcgWorkspace,
    time: f64,
) -> Result<(Choice, bool, Option<Probe>), StepError> {
    let Topology {
        matrix,
        jacobi,
        filters,
        cholesky,
        amg,
        ..
    } = topology;
    // xorshift64*, mapped to [−1, 1].
    let mut seed = 0x9E37_79B9_7F4A_7C15_u64;
    let mut uniform = || {
        seed ^= seed >> 12;
        seed ^= seed << 25;
        seed ^= seed >> 27;
        (seed.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    };
    let r: Vec<Vec3> = filters
        .iter()
        .map(|f| f.apply(Vec3::new(uniform(), uniform(), uniform())))
        .collect();
    let mut y = vec![Vec3::zeros(); r.len()];
    // The factorization's time, and the iterative candidates' times.
    let mut direct = None;
    let mut iterative: Vec<(Choice, Duration)> = Vec::with_capacity(2);
    let affordable = predicted_factor_entries(matrix.pattern()).is_some_and(|entries| {
        entries.saturating_mul(size_of::<f64>()) <= LinearSolver::AUTO_FACTOR_BYTES
    });
    if affordable {
        // Kept for a retry when this matrix is not positive definite.
        let factor = match cholesky {
            Some(factor) => factor,
            None => cholesky.insert(SparseCholesky::new(matrix)?),
        };
        let ((), elapsed) = second_run(|| factor.solve(matrix, filters, &r, &mut y))
            .map_err(|particle| StepError::NotPositiveDefinite { time, particle })?;
        direct = Some(elapsed);
    }
    let settings = PcgSettings::default();
    match Amg::build(matrix, filters, positions, AmgSettings::default()) {
        Ok(mut hierarchy) => {
            let solved = second_run(|| {
                hierarchy
                    .refresh_smoother(matrix, filters)
                    .map_err(|_| ())?;
                y.fill(Vec3::zeros());
                let cycle = hierarchy.cycle(matrix, filters);
                cg::solve(matrix, &cycle, filters, &r, &mut y, settings, workspace).map_err(|_| ())
            });
            if let Ok((_, elapsed)) = solved {
                iterative.push((Choice::Amg(settings), elapsed));
                // The first solve of the step's own systems sets the
                // baseline of the renewals: the pseudo-random right-hand
                // side takes more iterations than they do.
                amg.clear();
                amg.amg = Some(hierarchy);
            }
        }
        Err(AmgError::NotPositiveDefinite(particle)) if !affordable => {
            return Err(StepError::NotPositiveDefinite {
                time,
                particle: Some(particle),
            });
        }
        Err(_) => {}
    }
    let capped = PcgSettings::new(
        settings.tolerance(),
        LinearSolver::AUTO_TRIAL_PCG_ITERATIONS,
    )
    .expect("a tolerance in (0, 1) and a positive cap");
    let solved = second_run(|| {
        y.fill(Vec3::zeros());
        cg::solve(matrix, jacobi, filters, &r, &mut y, capped, workspace)
    });
    if let Ok((_, elapsed)) = solved {
        iterative.push((Choice::Pcg(settings), elapsed));
    }
    // An iterative candidate must beat the factorization by the margin;
    // with nothing solved, multigrid — the candidate for systems too large
    // to factorize — reports why at the solve that follows.
    let fastest = iterative
        .iter()
        .min_by_key(|&&(_, elapsed)| elapsed)
        .copied();
    let best = match (fastest, direct) {
        (Some((choice, elapsed)), Some(direct))
            if elapsed.as_secs_f64()
                <= LinearSolver::AUTO_ITERATIVE_MARGIN * direct.as_secs_f64() =>
        {
            choice
        }
        (_, Some(_)) => Choice::Cholesky,
        (Some((choice, _)), None) => choice,
        (None, None) => Choice::Amg(settings),
    };
    // The factorization and the fastest iterative candidate close enough
    // to compare on whole steps.
    let probe = match (fastest, direct) {
        (Some((choice, elapsed)), Some(direct)) => {
            let (iterative, direct) = (elapsed.as_secs_f64(), direct.as_secs_f64());
            (iterative.max(direct) <= LinearSolver::AUTO_PROBE_RATIO * iterative.min(direct)).then(
                || {
                    Probe::new(if best == Choice::Cholesky {
                        choice
                    } else {
                        Choice::Cholesky
                    })
                },
            )
        }
        _ => None,
    };
    // Multigrid as the other candidate is built at its first solve, as in
    // a run that starts with it: the trial's hierarchy, kept idle through
    // the factorization's step, set off other refreshes and rebuilds, and
    // steps of the 200² swinging cloth took 4.3–8.2 s against 4.7 s.
    if best != Choice::Cholesky && probe.is_none() {
        *cholesky = None;
    }
    if !matches!(best, Choice::Amg(_)) {
        amg.clear();
    }
    Ok((best, affordable && best != Choice::Cholesky, probe))
}

/// Runs `solve` twice and times the second run, which finds in place the
/// memory the first touched (a fresh factor, a fresh hierarchy), as the
/// solves of a run do; a failing first run is returned as is.
fn second_run<T, E>(mut solve: impl FnMut() -> Result<T, E>) -> Result<(T, Duration), E> {
    solve()?;
    let clock = Instant::now();
    let out = solve()?;
    Ok((out, clock.elapsed()))
}

#[cfg(test)]
mod tests {
    use hooke_core::CompressedSprings;
    use hooke_core::reference::Sheet;

    use super::*;

    /// The renewals each policy asks after a sequence of solves (their
    /// iteration counts), from a hierarchy just built whose first solve
    /// took 20: [`AmgRenewal::EverySolve`] refreshes every level until a
    /// solve takes more than 40, then rebuilds and takes its next solve as
    /// the baseline; [`AmgRenewal::SmootherOnly`] refreshes the smoother
    /// until a solve takes more than 30, then every level, and rebuilds
    /// only when a solve right after that takes more than 40.
    #[test]
    fn multigrid_renews_what_its_policy_asks_after_each_solve() {
        use Renewal::{Hierarchy, Smoother, Values};
        let cases = [
            (
                AmgRenewal::EverySolve,
                vec![
                    (20, Values),
                    (35, Values),
                    (41, Hierarchy),
                    (30, Values),
                    (61, Hierarchy),
                ],
            ),
            (
                AmgRenewal::SmootherOnly,
                vec![
                    (20, Smoother),
                    (30, Smoother),
                    (31, Values),
                    (35, Values),
                    (41, Hierarchy),
                    (30, Smoother),
                    (46, Values),
                ],
            ),
        ];
        for (policy, solves) in cases {
            let mut state = AmgState::new(policy);
            let mut renewal = Hierarchy;
            for (iterations, expected) in solves {
                state.after(renewal, iterations);
                assert_eq!(state.next, expected, "{policy:?} after {iterations}");
                renewal = state.next;
            }
        }
    }

    /// [`LinearSolver::Auto`]'s comparison on whole steps: the trial's own
    /// step is not measured, the next one runs the trial's choice (here the
    /// factorization), the one after the other candidate (block-Jacobi
    /// PCG), and the faster per second simulated serves the rest of the
    /// run, the other's factor dropped. The second case's step is twice as
    /// long: slower in wall time, faster per second simulated.
    #[test]
    fn auto_keeps_the_candidate_faster_per_second_simulated_on_whole_steps() {
        let system = Sheet::new(12).system().unwrap();
        let jacobi = Choice::Pcg(PcgSettings::default());
        let ms = |t: f64| Duration::from_secs_f64(1e-3 * t);
        for ((elapsed, dt), kept) in [((20.0, 0.01), Choice::Cholesky), ((15.0, 0.02), jacobi)] {
            let mut cached = None;
            let topology = topology(
                &mut cached,
                LinearSolver::Cholesky,
                AmgRenewal::default(),
                &system,
            )
            .unwrap();
            topology.probe = Some(Probe::new(jacobi));
            topology.step_ended(ms(50.0), 0.01);
            assert_eq!(topology.solver, Choice::Cholesky);
            topology.step_ended(ms(10.0), 0.01);
            assert_eq!(topology.solver, jacobi);
            assert!(topology.fallback && topology.cholesky.is_some());
            topology.step_ended(ms(elapsed), dt);
            assert_eq!(topology.solver, kept);
            assert!(topology.probe.is_none());
            assert_eq!(topology.cholesky.is_some(), kept == Choice::Cholesky);
            assert_eq!(topology.fallback, kept != Choice::Cholesky);
            topology.step_ended(ms(1000.0), 0.01);
            assert_eq!(topology.solver, kept);
        }
    }

    /// The trial leaves an iterative choice with the fallback on when the
    /// factor is affordable; here block-Jacobi PCG capped at one iteration
    /// stands for a choice that stops at its cap later in a run. In strict
    /// mode a capped solve is an error, so only the fallback lets the
    /// solve succeed: with the factorization, to the factorization's
    /// accuracy, and for the rest of the run.
    #[test]
    fn an_iterative_choice_that_stops_at_its_cap_falls_back_to_the_factorization() {
        let system = Sheet::new(12).system().unwrap();
        let mut state = system.initial_state();
        for (i, v) in state.velocities_mut().iter_mut().enumerate() {
            *v = Vec3::new((i as f64).sin(), (3.0 * i as f64).cos(), 0.0);
        }
        let n = system.particle_count();
        let capped = PcgSettings::new(1e-10, 1).unwrap();
        let mut cached = None;
        let topology = topology(
            &mut cached,
            LinearSolver::Pcg(capped),
            AmgRenewal::default(),
            &system,
        )
        .unwrap();
        topology.fallback = true;
        let h = 0.01;
        let u: Vec<Vec3> = state.velocities().iter().map(|v| h * v).collect();
        let lin = Linearization {
            positions: state.positions(),
            velocities: state.velocities(),
            displacement: Some(&u),
            inertia: &vec![Vec3::zeros(); n],
            beta_h: h,
            compressed: CompressedSprings::Clamped,
            freeze_directions: true,
        };
        let solve = Solve {
            system: &system,
            strict: true,
            time: 0.0,
            forcing: 0.0,
        };
        let mut b = vec![Vec3::zeros(); n];
        solve
            .assemble(&mut Assembler::default(), topology, &lin, &mut b)
            .unwrap();
        let mut x = vec![Vec3::zeros(); n];
        let mut report = StepReport::default();
        solve
            .solve(
                topology,
                state.positions(),
                &b,
                &mut x,
                &mut PcgWorkspace::default(),
                &mut report,
            )
            .unwrap();
        assert_eq!(report.linear_solver, "cholesky");
        assert_eq!((report.linear_solves, report.linear_iterations), (1, 1));
        assert_eq!(report.unconverged_solves, 0);
        assert_eq!(topology.solver, Choice::Cholesky);
        assert!(!topology.fallback);
        let mut ax = vec![Vec3::zeros(); n];
        topology.matrix().apply(&x, &mut ax);
        let scale = b.iter().map(|bi| bi.norm()).fold(0.0, f64::max);
        for i in (0..n).filter(|&i| !system.is_pinned(i)) {
            assert!((ax[i] - b[i]).norm() < 1e-10 * scale, "particle {i}");
        }
    }
}
