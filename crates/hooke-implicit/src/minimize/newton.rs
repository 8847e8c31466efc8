//! Newton's method ([`Minimizer::Newton`](crate::Minimizer::Newton)) as a
//! [`Descent`]: each direction solves the system the terms assemble,
//! `(M + βh C + β²h² K) δ = −∇Φ(v)`, with the step's linear solver
//! ([`Linear`]), inexactly where that solver iterates. The linearised step
//! ([`Minimizer::Linearized`](crate::Minimizer::Linearized)) is this
//! method stopped after one iteration. [`Implicit`](crate::Implicit)'s
//! docs give the equations.

use hooke_core::{At, CompressedSprings, StepError, StepReport, Vec3};

use crate::linear::cg::PcgWorkspace;
use crate::linear::solver::solve::Solve;
use crate::linear::solver::topology::Topology;
use crate::linear::vector::dot;
use crate::minimize::descent::Descent;
use crate::minimize::objective::{Objective, iterate};
use crate::minimize::terms::Terms;

/// The loosest relative residual an iterative solve of a Newton step may
/// stop at (the forcing term before the first decrement is known).
const MAX_FORCING: f64 = 0.1;

/// The forcing term of an inexact Newton iteration whose last relative
/// decrement was `last`: `η = min(0.1, ½ last)`, so that the linear solves
/// are loose while Newton is far from the answer and tighten with it
/// (Eisenstat & Walker, *Choosing the forcing terms in an inexact Newton
/// method*, 1996).
fn forcing(last: f64) -> f64 {
    if last.is_finite() {
        (0.5 * last).min(MAX_FORCING)
    } else {
        MAX_FORCING
    }
}

/// The step's linear solver: what its solves share, the topology's matrix,
/// filters and factor or hierarchy, PCG's workspace, the right-hand side
/// `b`, and the report that counts the solves.
pub(crate) struct Linear<'a> {
    pub(crate) solve: Solve<'a>,
    pub(crate) topology: &'a mut Topology,
    pub(crate) pcg: &'a mut PcgWorkspace,
    pub(crate) b: &'a mut [Vec3],
    pub(crate) report: &'a mut StepReport,
}

impl Linear<'_> {
    /// Assembles the terms' system at `at` into the topology's matrix and
    /// `b` ([`Terms::assemble`]).
    ///
    /// # Errors
    /// Assembly errors.
    pub(crate) fn assemble(&mut self, terms: &mut Terms, at: &At<'_>) -> Result<(), StepError> {
        self.solve.assemble(terms, self.topology, at, self.b)
    }

    /// Solves the filtered system last assembled at `positions` into `x`
    /// (a warm start on entry), counting the solve in the report.
    ///
    /// # Errors
    /// As [`Solve::solve`].
    pub(crate) fn solve(&mut self, positions: &[Vec3], x: &mut [Vec3]) -> Result<(), StepError> {
        self.solve
            .solve(self.topology, positions, self.b, x, self.pcg, self.report)
    }
}

/// Newton's method on one (sub)step's `Φ`: its linear solver, whether the
/// solves stop at the forcing term, and the Hessians its last direction
/// was solved with.
pub(crate) struct Newton<'a> {
    pub(crate) linear: Linear<'a>,
    /// Whether iterative solves stop at the forcing term
    /// `η = min(0.1, ½ λ_rel)` of the last relative decrement where that is
    /// looser than their own tolerance ([`forcing`]). CG started from zero
    /// gives a descent direction at every iteration, so a loose step still
    /// descends, and the stopping rule is checked on steps solved to a
    /// fraction of the decrement itself.
    pub(crate) inexact: bool,
    /// The stiffness blocks the last Newton step was solved with: once a
    /// step needed compressed springs clamped, its later iterations start
    /// there instead of assembling and factoring the exact blocks first.
    pub(crate) hessian: CompressedSprings,
}

impl Descent for Newton<'_> {
    const EXACT_CURVATURE: bool = true;

    fn iteration(&mut self, last: f64) {
        if self.inexact {
            self.linear.solve.forcing = forcing(last);
        }
    }

    fn slope(&self, d: &[Vec3]) -> f64 {
        -dot(self.linear.b, d)
    }

    /// Newton's step `δ` at `v`: assembles the terms' `(M + βh C + β²h² K)
    /// δ = −∇Φ(v)` with their exact Hessians (unless an earlier iteration
    /// of the same step needed the stand-ins, [`Newton::hessian`]), or —
    /// where that system is not positive definite or its solution does not
    /// descend, and the integrator clamps compressed springs — with their
    /// positive-semidefinite stand-ins (compressed springs clamped, the
    /// elements' and barriers' Hessians projected), and solves it in the
    /// free directions. Returns the slope `∇Φ·δ`.
    fn direction(
        &mut self,
        phi: &mut Objective<'_>,
        v: &[Vec3],
        delta: &mut [Vec3],
    ) -> Result<f64, StepError> {
        phi.positions(v);
        let mut hessian = self.hessian;
        loop {
            let at = iterate(phi.x, v, (phi.v_tilde, phi.beta_h), hessian);
            delta.fill(Vec3::zeros());
            let last = hessian == phi.compressed;
            let solved = self
                .linear
                .assemble(phi.terms, &at)
                .and_then(|()| self.linear.solve(phi.x, delta));
            match solved {
                Err(StepError::NotPositiveDefinite { .. }) if !last => {}
                Err(e) => return Err(e),
                Ok(()) if !last && dot(self.linear.b, delta) <= 0.0 => {}
                Ok(()) => break,
            }
            hessian = CompressedSprings::Clamped;
        }
        self.hessian = hessian;
        Ok(-dot(self.linear.b, delta))
    }
}
