//! The linear solver of an implicit step: the choice, what it keeps per
//! topology, and the assemble-and-solve path every Newton step takes.

use hooke_core::{StepError, StepReport, System, Vec3};

use crate::assembly::{Assembler, Linearization};
use crate::block::SymBlock;
use crate::cg::{self, BlockJacobi, PcgError, PcgSettings, PcgWorkspace};
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
}

impl Default for LinearSolver {
    /// Sparse Cholesky: exact at any conditioning the step allows, where
    /// PCG's iterations grow with the stiffness.
    fn default() -> Self {
        Self::Cholesky
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
    cholesky: Option<SparseCholesky>,
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
        let cholesky = match solver {
            LinearSolver::Cholesky => Some(SparseCholesky::new(&matrix)?),
            LinearSolver::Pcg(_) => None,
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
            cholesky,
        });
    }
    Ok(cached.as_mut().expect("built above"))
}

/// What every linear solve of a step shares.
#[derive(Clone, Copy)]
pub(crate) struct Solve<'a> {
    pub(crate) system: &'a System,
    pub(crate) solver: LinearSolver,
    pub(crate) strict: bool,
    pub(crate) time: f64,
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
    /// into `x` (a warm start on entry), recording the solve and the force
    /// evaluation of its assembly in `report`.
    ///
    /// # Errors
    /// [`StepError::NoConvergence`] in strict mode when PCG stops at its
    /// cap, [`StepError::NotPositiveDefinite`] when the filtered matrix is
    /// not positive definite.
    pub(crate) fn solve(
        self,
        topology: &mut Topology,
        b: &[Vec3],
        x: &mut [Vec3],
        workspace: &mut PcgWorkspace,
        report: &mut StepReport,
    ) -> Result<(), StepError> {
        let Self {
            solver,
            strict,
            time,
            ..
        } = self;
        let Topology {
            matrix,
            jacobi,
            filters,
            cholesky,
            ..
        } = topology;
        report.force_evaluations += 1;
        report.linear_solves += 1;
        match solver {
            LinearSolver::Pcg(settings) => {
                let info = match cg::solve(matrix, jacobi, filters, b, x, settings, workspace) {
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
            }
            LinearSolver::Cholesky => {
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
