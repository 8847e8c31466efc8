//! The linear solver of an implicit step: the choice, what it keeps per
//! topology, and the assemble-and-solve path every Newton step takes.

use hooke_core::{StepError, StepReport, System, Vec3};

use crate::assembly::{Assembler, Linearization};
use crate::cg::{self, BlockJacobi, PcgError, PcgSettings, PcgWorkspace};
use crate::cholesky::SparseCholesky;
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
    fn default() -> Self {
        Self::Pcg(PcgSettings::default())
    }
}

/// What depends on the system's topology only.
#[derive(Debug)]
pub(crate) struct Topology {
    system: u64,
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
    /// Assembles the linearisation `lin` into the topology's matrix and `b`,
    /// then solves into `x` (a warm start on entry), recording both in
    /// `report`. With `prescribed = Some((z, scratch))` the constrained
    /// components of the solution are `z` rather than zero: `b` becomes
    /// `b − A z` and `x` the free part `y` of `Δv = y + z`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn linearised(
        self,
        assembler: &mut Assembler,
        topology: &mut Topology,
        lin: &Linearization<'_>,
        b: &mut [Vec3],
        x: &mut [Vec3],
        workspace: &mut PcgWorkspace,
        prescribed: Option<(&[Vec3], &mut [Vec3])>,
        report: &mut StepReport,
    ) -> Result<(), StepError> {
        let Self {
            system,
            solver,
            strict,
            time,
        } = self;
        let Topology {
            matrix,
            jacobi,
            filters,
            cholesky,
            ..
        } = topology;
        assembler.assemble(system, lin, matrix, jacobi, b, time)?;
        if let Some((z, az)) = prescribed {
            matrix.apply(z, az);
            for (bi, azi) in b.iter_mut().zip(az.iter()) {
                *bi -= azi;
            }
        }
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
                factor.solve(matrix, filters, b, x).map_err(|particle| {
                    StepError::NotPositiveDefinite {
                        time,
                        particle: Some(particle),
                    }
                })?;
            }
        }
        Ok(())
    }
}
