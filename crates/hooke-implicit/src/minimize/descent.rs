//! The one interface of the minimisers of `Φ` ([`Descent`]): a minimiser
//! is its descent directions; the line search, the stopping rule and
//! contact's limit on every motion (the `line_search` module) are shared.

use hooke_core::{Potential, StepError, Vec3};

use crate::minimize::objective::Objective;

/// A minimiser of a (sub)step's `Φ`: at an iterate `v`, a direction `δ`
/// along which `Φ` descends, `∇Φ·δ < 0`, from the model
/// `Φ(v + δ) ≈ Φ(v) + ∇Φ·δ + ½ δᵀ H δ` it minimises —
/// `δ = −H⁻¹ ∇Φ`, `H` the assembled Hessian for Newton's method, L-BFGS's
/// approximation for the quasi-Newton step. The line search
/// (`line_search::minimize`) iterates the directions to the stopping rule,
/// every iterate accepted through the Armijo condition and within the
/// limit contact sets on the motion; each implementation holds what it
/// needs beyond [`Objective`] (the linear solver, its own state) and is
/// built for one (sub)step, so the loop is monomorphised over it and its
/// calls inline.
pub(crate) trait Descent {
    /// Whether `H` has `Φ`'s own curvature along the directions (Newton's
    /// Hessian) or only bounds it from above (L-BFGS's `H₀`, stiffer than
    /// `Φ` along the soft modes). Then the decrement `λ = √|∇Φ·δ|`,
    /// measured in `H`'s norm, is scaled by the curvature `Φ` shows along
    /// `δ` before it stops the iteration, the precision floor needs the
    /// last iterate to have lowered `Φ` by no more than rounding too, and a
    /// full step that undershoots is extended to the model's minimum at
    /// once (`line_search::minimize`).
    const EXACT_CURVATURE: bool;

    /// `Φ(v)` and its magnitude, infinite where a barrier's gap is not
    /// positive. A minimiser whose next direction needs the gradient may
    /// take it from the same passes and keep it for the direction at `v`
    /// ([`Descent::discard`] drops it).
    fn value(&mut self, phi: &mut Objective<'_>, v: &[Vec3]) -> Potential {
        phi.value(v)
    }

    /// Forgets what [`Descent::value`] kept: its point did not become the
    /// iterate.
    fn discard(&mut self) {}

    /// Starts an iteration whose last relative decrement was `last`
    /// (infinite at the first): Newton's inexact solves take their forcing
    /// term from it.
    fn iteration(&mut self, last: f64) {
        let _ = last;
    }

    /// The slope `∇Φ·d` along `d` at the iterate of the last direction.
    fn slope(&self, d: &[Vec3]) -> f64;

    /// The direction `δ` at the iterate `v`; returns the slope `∇Φ·δ`.
    ///
    /// # Errors
    /// Assembly and solver errors, [`StepError::NonFiniteSystem`] for a
    /// gradient that is not finite.
    fn direction(
        &mut self,
        phi: &mut Objective<'_>,
        v: &[Vec3],
        delta: &mut [Vec3],
    ) -> Result<f64, StepError>;
}
