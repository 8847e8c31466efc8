//! The solve every Newton step takes: the solver in use, renewing what it
//! keeps, and [`LinearSolver::Auto`]'s fallback.

use hooke_core::{Named, StepError, StepReport, System, Vec3};

use super::LinearSolver;
use super::auto::trial;
use super::renewal::Renewal;
use super::topology::Topology;
use crate::linear::amg::{Amg, AmgError, AmgSettings};
use crate::linear::cg::{self, PcgError, PcgInfo, PcgSettings, PcgWorkspace};
use crate::linear::cholesky::SparseCholesky;

/// The settings of the PCG solve that a Cholesky factor preconditions when
/// it is of a matrix above the step's (weak springs routed, or contact
/// coupling particles outside the factor's pattern): to a relative
/// residual of 10⁻¹⁰ (about a direct solve's), or Newton's forcing term
/// where that is looser (at most [`FACTOR_FORCING`] with weak springs
/// routed), at most 200 iterations.
const FACTOR_PCG: PcgSettings = PcgSettings {
    tolerance: 1e-10,
    max_iterations: 200,
};

/// The loosest relative residual PCG preconditioned by a factor with weak
/// springs routed stops at: the factor stands in for a direct solve, whose
/// Newton steps are exact. Measured on the default scene with weak springs routed
/// (`benches/README.md`): Newton's forcing term alone (up to 0.1) took
/// 5.2 iterations a step and up to 83, a cap of `10⁻²` 4.98 and 40.
const FACTOR_FORCING: f64 = 1e-2;

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

impl<'a> Solve<'a> {
    /// The solves of a step of `system` at `time`, `strict` as the
    /// integrator is, with no forcing term yet.
    pub(crate) fn new(system: &'a System, strict: bool, time: f64) -> Self {
        Self {
            system,
            strict,
            time,
            forcing: 0.0,
        }
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
        if topology.solver == LinearSolver::Auto {
            (topology.solver, topology.fallback, topology.runner_up) =
                trial(topology, self.system, positions, workspace, time)?;
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
            runner_up,
            factoring,
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
            LinearSolver::Pcg(settings) => {
                let settings = settings.loosened(forcing);
                let solved = cg::solve(matrix, jacobi, filters, b, x, settings, workspace);
                match solved {
                    Err(PcgError::NoConvergence(info)) if *fallback => capped = Some(info),
                    solved => {
                        pcg(solved, report)?;
                    }
                }
            }
            LinearSolver::Amg(settings) => {
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
            LinearSolver::LaggedCholesky(settings) => {
                let factor = cholesky
                    .as_mut()
                    .expect("built with the topology for this solver");
                if *refactor {
                    factor.factorize(matrix, filters).map_err(|e| e.at(time))?;
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
            LinearSolver::Auto => unreachable!("the trial resolved the choice above"),
            LinearSolver::Cholesky => {}
        }
        if let Some(info) = capped {
            // Auto's iterative choice stopped at its cap where a factor is
            // affordable: the factorization solves this system and the
            // rest of the run.
            report.linear_iterations += info.iterations;
            report.linear_solver = LinearSolver::Cholesky.name();
            *solver = LinearSolver::Cholesky;
            *fallback = false;
            *runner_up = None;
            amg.clear();
            *cholesky = Some(SparseCholesky::for_system(matrix, self.system, *factoring)?);
        }
        if *solver == LinearSolver::Cholesky {
            let factor = cholesky
                .as_mut()
                .expect("built with the topology for this solver");
            factor.factorize(matrix, filters).map_err(|e| e.at(time))?;
            // A factor of a matrix above the whole one — weak springs
            // carried on their paths, or blocks between particles in
            // contact or in a volume element that no spring joins left out
            // of its pattern and made up for on the diagonal —
            // preconditions PCG on the whole matrix.
            let forcing = if factor.is_routed() {
                forcing.min(FACTOR_FORCING)
            } else {
                forcing
            };
            let settings = FACTOR_PCG.loosened(forcing);
            if let Some(solved) =
                factor.solve_filtered((matrix, filters), b, x, settings, workspace)
            {
                pcg(solved, report)?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use hooke_core::reference::Sheet;

    use super::*;
    use crate::linear::solver::renewal::AmgRenewal;
    use crate::linear::solver::topology::topology;
    use crate::minimize::terms::{Terms, step_from};

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
        let mut terms = Terms::new(&system).unwrap();
        let topology = topology(
            &mut cached,
            Some(LinearSolver::Pcg(capped)),
            (AmgRenewal::default(), Default::default()),
            (&system, terms.pattern()),
        )
        .unwrap();
        topology.fallback = true;
        let mut u = Vec::new();
        let at = step_from(&state, 0.01, &mut u);
        let solve = Solve {
            system: &system,
            strict: true,
            time: 0.0,
            forcing: 0.0,
        };
        let mut b = vec![Vec3::zeros(); n];
        solve.assemble(&mut terms, topology, &at, &mut b).unwrap();
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
        assert_eq!(topology.solver, LinearSolver::Cholesky);
        assert!(!topology.fallback);
        let mut ax = vec![Vec3::zeros(); n];
        topology.matrix().apply(&x, &mut ax);
        let scale = b.iter().map(|bi| bi.norm()).fold(0.0, f64::max);
        for i in (0..n).filter(|&i| !system.is_pinned(i)) {
            assert!((ax[i] - b[i]).norm() < 1e-10 * scale, "particle {i}");
        }
    }
}
