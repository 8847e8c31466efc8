//! What the linear solver keeps per topology: the matrix, the filters and
//! the solver in use with its factor or hierarchy.

use std::sync::Arc;

use hooke_core::{StepError, System};

use super::LinearSolver;
use super::auto_settings::AutoSettings;
use super::renewal::{AmgRenewal, AmgState};
use crate::linear::cg::BlockJacobi;
use crate::linear::cg::PcgSettings;
use crate::linear::cholesky::{SparseCholesky, Supernodes, WeakSprings};
use crate::linear::filter::{Filter, pin_filters};
use crate::linear::matrix::BlockMatrix;
use crate::linear::pattern::Pattern;

/// What depends on the system's topology only.
#[derive(Debug)]
pub(crate) struct Topology {
    system: u64,
    pub(super) matrix: BlockMatrix,
    pub(super) jacobi: BlockJacobi,
    pub(super) filters: Vec<Filter>,
    /// The solver in use: the one asked for, or the one
    /// [`LinearSolver::Auto`] chose; `Auto` itself while its trial is to
    /// come at the next solve.
    pub(super) solver: LinearSolver,
    pub(super) cholesky: Option<SparseCholesky>,
    /// Whether the next [`LinearSolver::LaggedCholesky`] solve factorizes.
    pub(super) refactor: bool,
    pub(super) amg: AmgState,
    /// What a Cholesky factor built for [`LinearSolver::Cholesky`] does
    /// with weak springs, and which numeric factorization it runs.
    pub(super) factoring: (WeakSprings, Supernodes),
    /// Whether an iterative solve that stops at its cap falls back to the
    /// factorization: when [`LinearSolver::Auto`] chose the iterative
    /// solver over an affordable factor.
    pub(super) fallback: bool,
    /// The candidate not in use while [`LinearSolver::Auto`] compares two
    /// on whole steps (the factorization and the fastest iterative one).
    pub(super) runner_up: Option<LinearSolver>,
}

impl Topology {
    /// The id of the system the topology is of.
    pub(crate) fn system(&self) -> u64 {
        self.system
    }

    /// The matrix last assembled.
    pub(crate) fn matrix(&self) -> &BlockMatrix {
        &self.matrix
    }

    /// The matrix and its block-Jacobi preconditioner, for the assembly.
    pub(crate) fn system_mut(&mut self) -> (&mut BlockMatrix, &mut BlockJacobi) {
        (&mut self.matrix, &mut self.jacobi)
    }

    /// Whether [`LinearSolver::Auto`] is comparing two candidates on whole
    /// steps.
    pub(crate) fn comparing(&self) -> bool {
        self.runner_up.is_some()
    }

    /// Swaps the solver in use for the runner-up of the comparison.
    pub(crate) fn swap_candidates(&mut self) {
        if let Some(other) = &mut self.runner_up {
            std::mem::swap(&mut self.solver, other);
        }
        // The factor is affordable whenever the two are compared.
        self.fallback = self.solver != LinearSolver::Cholesky;
    }

    /// The solver in use, whether it falls back to the factorization and
    /// whether a factor is kept.
    #[cfg(test)]
    pub(crate) fn choice(&self) -> (LinearSolver, bool, bool) {
        (self.solver, self.fallback, self.cholesky.is_some())
    }

    /// Starts [`LinearSolver::Auto`]'s comparison with `other` as the
    /// runner-up, as the trial does.
    #[cfg(test)]
    pub(crate) fn compare_with(&mut self, other: LinearSolver) {
        self.runner_up = Some(other);
    }

    /// Ends the comparison with the solver in use, dropping the runner-up's
    /// factor or hierarchy.
    pub(crate) fn settle(&mut self) {
        self.runner_up = None;
        if self.solver == LinearSolver::Cholesky {
            self.amg.clear();
        } else {
            self.cholesky = None;
        }
        self.fallback = self.solver != LinearSolver::Cholesky;
    }
}

/// The topology-dependent parts for `system`, whose springs' `pattern`
/// the matrix shares, rebuilt when the system changes or none were built
/// yet (the step's history is keyed on the system too, so it restarts
/// then). [`LinearSolver::Auto`] is resolved here by
/// the system's size, or left to the trial. A factor for
/// [`LinearSolver::Cholesky`] treats weak springs and picks its numeric
/// factorization as `factoring` says;
/// one for [`LinearSolver::LaggedCholesky`], a preconditioner across
/// matrices already, keeps them. Without `solver` (a step that
/// assembles no matrix), the matrix is its pattern alone
/// ([`BlockMatrix::unassembled`]).
pub(crate) fn topology<'a>(
    cached: &'a mut Option<Topology>,
    solver: Option<LinearSolver>,
    (renewal, factoring): (AmgRenewal, (WeakSprings, Supernodes)),
    (system, pattern): (&System, &Arc<Pattern>),
) -> Result<&'a mut Topology, StepError> {
    if cached.as_ref().is_some_and(|t| t.system != system.id()) {
        *cached = None;
    }
    if cached.is_none() {
        let pattern = Arc::clone(pattern);
        let (matrix, solver) = match solver {
            Some(solver) => (BlockMatrix::zeros(pattern), solver),
            None => (
                BlockMatrix::unassembled(pattern),
                LinearSolver::Pcg(PcgSettings::default()),
            ),
        };
        let solver = match solver {
            LinearSolver::Auto
                if system.particle_count() < AutoSettings::DEFAULT.trial_particles =>
            {
                LinearSolver::Cholesky
            }
            solver => solver,
        };
        let cholesky = match solver {
            LinearSolver::Cholesky => Some(SparseCholesky::for_system(&matrix, system, factoring)?),
            LinearSolver::LaggedCholesky(_) => Some(SparseCholesky::new(&matrix)?),
            _ => None,
        };
        let filters = pin_filters(system);
        *cached = Some(Topology {
            system: system.id(),
            matrix,
            jacobi: BlockJacobi::default(),
            filters,
            solver,
            cholesky,
            refactor: true,
            amg: AmgState::new(renewal),
            factoring,
            fallback: false,
            runner_up: None,
        });
    }
    Ok(cached.as_mut().expect("built above"))
}
