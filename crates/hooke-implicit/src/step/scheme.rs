//! The time discretisation ([`Scheme`]) and the minimiser of each step's
//! potential ([`Minimizer`]).

use hooke_core::Named;

/// The time discretisation. Both are implicit, A-stable and L-stable: stiff
/// modes are damped, never amplified, at any step size.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Scheme {
    /// Backward Euler, first order:
    /// `xₙ₊₁ = xₙ + h vₙ₊₁`, `vₙ₊₁ = vₙ + h M⁻¹ f(xₙ₊₁, vₙ₊₁)`.
    /// On the undamped oscillator one step multiplies the amplitude by
    /// `1/√(1 + (hω)²)`. The default.
    #[default]
    BackwardEuler,
    /// The second-order backward differentiation formula:
    /// `xₙ₊₁ = (4xₙ − xₙ₋₁)/3 + (2/3)h vₙ₊₁`,
    /// `vₙ₊₁ = (4vₙ − vₙ₋₁)/3 + (2/3)h M⁻¹ f(xₙ₊₁, vₙ₊₁)`.
    /// Second order; it starts (and restarts, whenever the state, the system
    /// or `h` changes) with one backward-Euler step. Its amplitude error per
    /// step on the undamped oscillator is `O((hω)⁴)` (Choi & Ko, *Stable but
    /// Responsive Cloth*, SIGGRAPH 2002; Hairer & Wanner, *Solving Ordinary
    /// Differential Equations II*, §V.1).
    Bdf2,
}

impl Named for Scheme {
    /// `"backward-euler"` and `"bdf2"`: the integrator's name
    /// ([`Integrator::name`](hooke_core::Integrator::name)), which scene
    /// files give as their `method`.
    const TABLE: &'static [(Self, &'static str)] = &[
        (Self::BackwardEuler, "backward-euler"),
        (Self::Bdf2, "bdf2"),
    ];
}

/// How a step minimises its incremental potential `Φ` (see [`Implicit`](crate::Implicit)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Minimizer {
    /// Newton's method on the assembled 3×3-block system, the exact spring
    /// Hessian where it is positive definite (the default).
    #[default]
    Newton,
    /// L-BFGS with the last `history` curvature pairs and the constant
    /// initial Hessian `H₀ = M + βh (γI + C₀) + β²h² L` (the springs'
    /// stiffness and damping Laplacians; Liu, Bouaziz & Kavan 2017),
    /// prefactored: an iteration costs one gradient and three pairs of
    /// triangular solves, no matrix is assembled. By default a cloth's
    /// bending springs in a factored `H₀` are carried on the stiff springs
    /// between their ends, which halves the factor
    /// ([`WeakSprings::Routed`](crate::WeakSprings); `WeakSprings::Kept`
    /// keeps fast mass-spring's matrix). The integrator's
    /// [`LinearSolver`](crate::LinearSolver) says how `H₀⁻¹` is applied:
    /// [`Amg`](crate::LinearSolver::Amg) by one V-cycle of
    /// smoothed-aggregation multigrid on `H₀` instead of a factor (memory
    /// and time linear in the particles), [`Auto`](crate::LinearSolver::Auto)
    /// by the factor unless it holds more than 96 entries per particle
    /// (the bench cloth from about 200 × 200 particles), every other by
    /// the factor. The same line search, stopping rule,
    /// energy test and substeps as Newton's method; it converges linearly
    /// where Newton converges quadratically, so it wins at loose
    /// tolerances and on large meshes. It loses where contacts come and
    /// go within a step and stiff springs fold: on the default scene (a
    /// stiff cloth landing on a sphere and a floor, default tolerance) it
    /// took 112 iterations a step against Newton's 4.9, rejected 21
    /// substeps, and stepped in 2.2 times Newton's time (2026-11-28). The
    /// `quasi_newton` module gives the equations.
    QuasiNewton {
        /// The curvature pairs kept.
        history: usize,
        /// The newest pairs of a (sub)step that the next one starts its
        /// history with, at most `history` ([`Minimizer::CARRIED`] by
        /// default; 0 starts every step afresh, as Liu et al. do). Carried
        /// only while `H₀` stays the same (the same `βh`, no contact terms).
        carried: usize,
    },
    /// Baraff & Witkin's linearised step: one linear solve, no line
    /// search, no rejection.
    Linearized,
}

impl Minimizer {
    /// The default L-BFGS history (Liu et al.'s).
    pub const HISTORY: usize = 5;

    /// The curvature pairs a quasi-Newton (sub)step hands to the next by
    /// default: its newest. On the `work_precision` bench's cloth it halves
    /// the error of five iterations a step (0.26 → 0.12 m at 50 × 50
    /// particles, 0.25 → 0.11 m at 100 × 100) and leaves that of ten or
    /// more as it was; carrying all five helps five iterations as much but
    /// doubles the error of ten and thirty (`benches/README.md`).
    pub const CARRIED: usize = 1;

    /// L-BFGS with the default history and carried pairs.
    #[must_use]
    pub const fn quasi_newton() -> Self {
        Self::QuasiNewton {
            history: Self::HISTORY,
            carried: Self::CARRIED,
        }
    }
}

impl Named for Minimizer {
    /// `"newton"`, `"quasi-newton"` (with the default history and carried
    /// pairs) and `"linearized"`, as scene files (`step`) and reports spell
    /// them.
    const TABLE: &'static [(Self, &'static str)] = &[
        (Self::Newton, "newton"),
        (Self::quasi_newton(), "quasi-newton"),
        (Self::Linearized, "linearized"),
    ];
}
