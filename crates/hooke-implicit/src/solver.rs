//! The linear solver of an implicit step: the choice, what it keeps per
//! topology, and the assemble-and-solve path every Newton step takes.

use hooke_core::{StepError, StepReport, System, Vec3};

use crate::amg::{Amg, AmgError, AmgSettings};
use crate::assembly::{Assembler, Linearization};
use crate::block::SymBlock;
use crate::cg::{self, BlockJacobi, PcgError, PcgInfo, PcgSettings, PcgWorkspace};
use crate::cholesky::SparseCholesky;
use crate::conditioning::Rates;
use crate::filter::Filter;
use crate::matrix::BlockMatrix;
use crate::pattern::Pattern;

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
    /// across Newton iterations and steps: every solve refreshes the finest
    /// level's smoother, a solve that took more than 1.5 times the
    /// iterations of the first one after the build has the next refresh
    /// every level's values, and one that took more than twice as many
    /// right after such a refresh has the next rebuild the hierarchy (see
    /// the [`amg`](crate::amg) module).
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
    /// Chooses by the system's size: [`LinearSolver::Cholesky`] below
    /// [`LinearSolver::AUTO_AMG_PARTICLES`] particles, where a factorization
    /// costs less than building and cycling a hierarchy, and
    /// [`LinearSolver::Amg`] with the default [`PcgSettings`] from there on,
    /// where the factor's fill and time grow faster than the multigrid's
    /// linear cost (and a million-particle factor would not fit in memory).
    /// The choice is reported in [`StepReport::linear_solver`].
    Auto,
}

impl LinearSolver {
    /// Iterations of a [`LinearSolver::LaggedCholesky`] solve beyond which
    /// the next solve factorizes again.
    pub const LAGGED_REFACTOR_ITERATIONS: usize = 10;

    /// The particle count from which [`LinearSolver::Auto`] takes multigrid.
    pub const AUTO_AMG_PARTICLES: usize = 4096;

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

/// A solver as used: [`LinearSolver::Auto`] resolved.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Choice {
    Pcg(PcgSettings),
    Cholesky,
    Amg(PcgSettings),
    Lagged(PcgSettings),
}

impl Choice {
    /// `solver` for `system`: `Auto` by the system's size.
    fn new(solver: LinearSolver, system: &System) -> Self {
        match solver {
            LinearSolver::Pcg(settings) => Self::Pcg(settings),
            LinearSolver::Cholesky => Self::Cholesky,
            LinearSolver::Amg(settings) => Self::Amg(settings),
            LinearSolver::LaggedCholesky(settings) => Self::Lagged(settings),
            LinearSolver::Auto if system.particle_count() >= LinearSolver::AUTO_AMG_PARTICLES => {
                Self::Amg(PcgSettings::default())
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
        }
    }
}

impl Default for LinearSolver {
    /// [`LinearSolver::Auto`].
    fn default() -> Self {
        Self::Auto
    }
}

/// The multigrid hierarchy of [`LinearSolver::Amg`] and how much of it the
/// next solve renews.
#[derive(Debug, Default)]
struct AmgState {
    amg: Option<Amg>,
    /// Iterations of the first solve after the last build (0: none yet).
    baseline: usize,
    next: Renewal,
}

/// How much of the hierarchy a solve renews.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
enum Renewal {
    /// The finest level's smoother ([`Amg::refresh_smoother`]).
    #[default]
    Smoother,
    /// Every level's values ([`Amg::refresh`]).
    Values,
    /// Everything ([`Amg::build`]).
    Hierarchy,
}

impl AmgState {
    /// The renewal after a solve of `iterations` that followed `renewal`:
    /// values after 1.5 times the baseline, the hierarchy after twice it
    /// right after the values were renewed.
    fn after(&mut self, renewal: Renewal, iterations: usize) {
        if renewal == Renewal::Hierarchy || self.baseline == 0 {
            self.baseline = iterations.max(1);
            self.next = Renewal::Smoother;
        } else if renewal == Renewal::Values && iterations > 2 * self.baseline {
            self.next = Renewal::Hierarchy;
        } else if 2 * iterations > 3 * self.baseline {
            self.next = Renewal::Values;
        } else {
            self.next = Renewal::Smoother;
        }
    }
}

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

    /// The matrix last assembled and the per-particle filters (pins are
    /// `Fixed` from the start).
    pub(crate) fn matrix_and_filters_mut(&mut self) -> (&BlockMatrix, &mut [Filter]) {
        (&self.matrix, &mut self.filters)
    }

    /// Adds `c I` to the diagonal block of particle `i` of the matrix last
    /// assembled (to its mass term `m̃ᵢ`, which the product reads, to the
    /// block the Cholesky factorization reads, and to the block-Jacobi
    /// inverse); `c ≥ 0` keeps a positive-definite block so.
    pub(crate) fn add_to_diagonal(&mut self, i: usize, c: f64) {
        self.matrix.mass[i] += c;
        let block = &mut self.matrix.diagonal[i];
        block.add_assign(&SymBlock::scaled_identity(c));
        if let Some(inverse) = block.inverse_if_positive_definite() {
            self.jacobi.inverses[i] = inverse;
        }
    }
}

/// The topology-dependent parts for `system`, rebuilt when the system
/// changes or none were built yet (the step's history is keyed on the system
/// too, so it restarts then).
pub(crate) fn topology<'a>(
    cached: &'a mut Option<Topology>,
    solver: LinearSolver,
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
            amg: AmgState::default(),
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
        let Topology {
            matrix,
            jacobi,
            filters,
            solver,
            cholesky,
            refactor,
            amg,
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
        match *solver {
            Choice::Pcg(settings) => {
                let settings = settings.loosened(forcing);
                pcg(
                    cg::solve(matrix, jacobi, filters, b, x, settings, workspace),
                    report,
                )?;
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
                    (slot, _) => slot.insert(
                        Amg::build(matrix, filters, positions, AmgSettings::default())
                            .map_err(not_positive_definite)?,
                    ),
                };
                let cycle = hierarchy.cycle(matrix, filters);
                let loosened = settings.loosened(forcing);
                let info = pcg(
                    cg::solve(matrix, &cycle, filters, b, x, loosened, workspace),
                    report,
                )?;
                // CG's iterations grow like the logarithm of the tolerance:
                // a loosened solve's count is scaled to the settings' one.
                let scale = settings.tolerance().ln() / loosened.tolerance().ln();
                amg.after(renewal, (info.iterations as f64 * scale).ceil() as usize);
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
            Choice::Cholesky => {
                let factor = cholesky
                    .as_mut()
                    .expect("built with the topology for this solver");
                factor
                    .solve(matrix, filters, b, x)
                    .map_err(|particle| StepError::NotPositiveDefinite { time, particle })?;
            }
        }
        Ok(())
    }
}
