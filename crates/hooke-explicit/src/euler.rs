//! Explicit (forward) Euler.

use hooke_core::{
    ForceEvaluator, Integrator, State, StepError, StepReport, System, Vec3, check_step,
};

use crate::ops::{combine, fit};

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
    a: Vec<Vec3>,
    x: Vec<Vec3>,
    v: Vec<Vec3>,
}

impl ExplicitEuler {
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
        check_step(system, state, dt)?;
        fit(state.len(), [&mut self.a, &mut self.x, &mut self.v]);
        let (x0, v0) = (state.positions(), state.velocities());
        self.forces.accelerations(system, x0, v0, &mut self.a);
        combine(&mut self.x, x0, &[(dt, v0)]);
        combine(&mut self.v, v0, &[(dt, &self.a)]);
        state.commit(&mut self.x, &mut self.v, state.time() + dt)?;
        Ok(StepReport {
            contacts: system.end_step(state),
            ..StepReport::fixed_step(1)
        })
    }

    fn name(&self) -> &'static str {
        "explicit-euler"
    }
}
