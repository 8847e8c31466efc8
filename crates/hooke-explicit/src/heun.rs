//! Heun's method (explicit trapezoidal rule).

use hooke_core::{
    ForceEvaluator, Integrator, State, StepError, StepReport, System, Vec3, check_step,
};

use crate::ops::{combine, fit};

/// Heun's method: an Euler predictor corrected with the trapezoidal rule,
///
/// ```text
/// x̃ = xₙ + h vₙ,                  ṽ = vₙ + h aₙ,      aₙ = a(xₙ, vₙ)
/// xₙ₊₁ = xₙ + (h/2)(vₙ + ṽ),      vₙ₊₁ = vₙ + (h/2)(aₙ + a(x̃, ṽ))
/// ```
///
/// Second order, two force evaluations per step. It has the same stability
/// function as the midpoint method, `R(z) = 1 + z + z²/2`: on the undamped
/// oscillator every step multiplies the energy by `1 + (hω)⁴/4`, so it gains
/// energy at every step size.
///
/// Source: Heun, Z. Math. Phys. 45 (1900) 23; Hairer, Nørsett & Wanner,
/// *Solving Ordinary Differential Equations I*, §II.1.
#[derive(Debug, Clone, Default)]
pub struct Heun {
    forces: ForceEvaluator,
    a: Vec<Vec3>,
    a_predicted: Vec<Vec3>,
    x: Vec<Vec3>,
    v: Vec<Vec3>,
}

impl Heun {
    /// A new integrator.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }
}

impl Integrator for Heun {
    fn step(
        &mut self,
        system: &System,
        state: &mut State,
        dt: f64,
    ) -> Result<StepReport, StepError> {
        check_step(system, state, dt)?;
        fit(
            state.len(),
            [&mut self.a, &mut self.a_predicted, &mut self.x, &mut self.v],
        );
        let (x0, v0) = (state.positions(), state.velocities());
        self.forces.accelerations(system, x0, v0, &mut self.a);
        combine(&mut self.x, x0, &[(dt, v0)]);
        combine(&mut self.v, v0, &[(dt, &self.a)]);
        self.forces
            .accelerations(system, &self.x, &self.v, &mut self.a_predicted);
        // x̃ − xₙ = h vₙ, so xₙ₊₁ = xₙ + (h/2) vₙ + (h/2) ṽ.
        combine(&mut self.x, x0, &[(0.5 * dt, v0), (0.5 * dt, &self.v)]);
        combine(
            &mut self.v,
            v0,
            &[(0.5 * dt, &self.a), (0.5 * dt, &self.a_predicted)],
        );
        state.commit(&mut self.x, &mut self.v, state.time() + dt)?;
        Ok(StepReport {
            contacts: system.end_step(state),
            ..StepReport::fixed_step(2)
        })
    }

    fn name(&self) -> &'static str {
        "heun"
    }
}
