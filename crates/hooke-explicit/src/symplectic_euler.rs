//! Symplectic (semi-implicit) Euler.

use hooke_core::{
    ForceEvaluator, Integrator, State, StepBuffers, StepError, StepReport, System, Vec3,
};

use crate::ops::combine;

/// Symplectic (semi-implicit, Euler–Cromer) Euler:
///
/// ```text
/// vₙ₊₁ = vₙ + h a(xₙ, vₙ)
/// xₙ₊₁ = xₙ + h vₙ₊₁
/// ```
///
/// First order; one force evaluation per step. Symplectic for conservative
/// forces, so on the undamped oscillator it keeps a modified energy exactly
/// and the energy error stays bounded for `hω < 2`; above that one eigenvalue
/// of the step exceeds 1 in modulus and the motion grows without bound.
///
/// Source: Hairer, Lubich & Wanner, *Geometric Numerical Integration*,
/// §I.1.2 and Theorem VI.3.3.
#[derive(Debug, Clone, Default)]
pub struct SymplecticEuler {
    forces: ForceEvaluator,
    out: StepBuffers,
    a: Vec<Vec3>,
}

impl SymplecticEuler {
    /// The name scene files, reports and the command line use.
    pub const NAME: &'static str = "symplectic-euler";

    /// A new integrator.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }
}

impl Integrator for SymplecticEuler {
    fn step(
        &mut self,
        system: &System,
        state: &mut State,
        dt: f64,
    ) -> Result<StepReport, StepError> {
        let name = self.name();
        self.out.begin(name, system, state, dt, [&mut self.a])?;
        let (x0, v0) = (state.positions(), state.velocities());
        self.forces.accelerations(system, x0, v0, &mut self.a);
        combine(&mut self.out.v, v0, &[(dt, &self.a)]);
        combine(&mut self.out.x, x0, &[(dt, &self.out.v)]);
        self.out
            .finish(system, state, dt, StepReport::fixed_step(1))
    }

    fn name(&self) -> &'static str {
        Self::NAME
    }
}
