//! The time discretisation ([`Scheme`]).

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
