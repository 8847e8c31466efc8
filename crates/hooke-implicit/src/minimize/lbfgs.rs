//! The quasi-Newton step ([`Minimizer::QuasiNewton`](crate::Minimizer::QuasiNewton))
//! as a [`Descent`]: L-BFGS's directions from the [`QuasiNewton`] state
//! (its prefactored `H₀` and curvature pairs, which the integrator keeps
//! across steps), on a gradient taken without any matrix. The
//! `quasi_newton` module gives the equations.

use hooke_core::{Potential, StepError, StepReport, Vec3};

use crate::linear::matrix::DiagonalBlocks;
use crate::linear::vector::dot;
use crate::minimize::descent::Descent;
use crate::minimize::objective::{Objective, iterate};
use crate::minimize::quasi_newton::QuasiNewton;
use crate::minimize::terms::check_finite;

/// L-BFGS on one (sub)step's `Φ`: the quasi-Newton state, begun for this
/// step ([`QuasiNewton::begin`]), the residual `b = −∇Φ`, the report that
/// counts the directions as linear solves, and the step's time.
pub(crate) struct Lbfgs<'a> {
    pub(crate) quasi: &'a mut QuasiNewton,
    pub(crate) b: &'a mut [Vec3],
    pub(crate) report: &'a mut StepReport,
    pub(crate) time: f64,
    /// Whether `b` holds `−∇Φ`, without the barriers' terms, at the point
    /// [`Descent::value`] evaluated last, whose next direction reuses it
    /// where that point becomes the iterate.
    pub(crate) evaluated: bool,
}

impl Descent for Lbfgs<'_> {
    const EXACT_CURVATURE: bool = false;

    /// `Φ(v)`, with `−∇Φ(v)` without the barriers' terms left in `b` from
    /// the same passes ([`Objective::gradient`]).
    fn value(&mut self, phi: &mut Objective<'_>, v: &[Vec3]) -> Potential {
        self.evaluated = true;
        phi.gradient(v, self.b)
    }

    fn discard(&mut self) {
        self.evaluated = false;
    }

    fn slope(&self, d: &[Vec3]) -> f64 {
        -dot(self.b, d)
    }

    /// The quasi-Newton step at `v`: the residual `−∇Φ(v)`, the barriers'
    /// gradients included, without any matrix, then L-BFGS's two-loop
    /// recursion ([`QuasiNewton::direction`]). Returns the slope `∇Φ·δ`.
    fn direction(
        &mut self,
        phi: &mut Objective<'_>,
        v: &[Vec3],
        delta: &mut [Vec3],
    ) -> Result<f64, StepError> {
        phi.positions(v);
        let system = phi.system;
        let at = iterate(phi.x, v, (phi.v_tilde, phi.beta_h), phi.compressed);
        if !std::mem::take(&mut self.evaluated) {
            phi.terms.gradient(system, &at, self.b);
        }
        check_finite(system, self.b, self.time)?;
        // The barriers' gradients join the residual. At the step's first
        // iterate their diagonal Hessian blocks give the stand-in on H₀;
        // later iterations keep no blocks.
        if self.quasi.pending() {
            let mut diagonal = DiagonalBlocks::default();
            phi.terms.add_barriers(system, &at, self.b, &mut diagonal);
            self.quasi.add_stand_in(system, &diagonal.0, self.time)?;
        } else {
            phi.terms.add_barriers(system, &at, self.b, &mut ());
        }
        self.report.linear_solves += 1;
        let slope = self.quasi.direction(system, self.b, v, delta);
        self.report.linear_solver = self.quasi.solver_name();
        Ok(slope)
    }
}
