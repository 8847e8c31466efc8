//! Explicit (forward) Euler.

use hooke_core::{
    ForceEvaluator, Integrator, State, StepBuffers, StepError, StepReport, System, Vec3,
};

use crate::ops::combine;

/// Explicit (forward) Euler:
///
/// ```text
/// xₙ₊₁ = xₙ + h vₙ
/// vₙ₊₁ = vₙ + h a(xₙ, vₙ)
/// ```
///
/// First order; one force evaluation per step. On the undamped oscillator
/// `x'' = −ω² x` one step multiplies the energy by exactly `1 + (hω)²`, so it
/// gains energy at every step size: there is no stable step for undamped
/// oscillations. Shown for comparison; do not simulate with it.
///
/// Source: Euler, *Institutionum calculi integralis* (1768); Hairer, Nørsett
/// & Wanner, *Solving Ordinary Differential Equations I*, §I.7.
#[derive(Debug, Clone, Default)]
pub struct ExplicitEuler {
    forces: ForceEvaluator,
    out: StepBuffers,
    a: Vec<Vec3>,
}

impl ExplicitEuler {
    /// The name scene files, reports and the command line use.
    pub const NAME: &'static str = "explicit-euler";

    /// A new integrator.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }
}

impl Integrator for ExplicitEuler {
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
        combine(&mut self.out.x, x0, &[(dt, v0)]);
        combine(&mut self.out.v, v0, &[(dt, &self.a)]);
        self.out
            .finish(system, state, dt, StepReport::fixed_step(1))
    }

    fn name(&self) -> &'static str {
        Self::NAME
    }
}
