//! Explicit midpoint (second-order Runge–Kutta).

use hooke_core::{
    ForceEvaluator, Integrator, State, StepError, StepReport, System, Vec3, check_step,
};

use crate::ops::{combine, fit};

/// Explicit midpoint method, the second-order Runge–Kutta method with the
/// derivative taken at the half step:
///
/// ```text
/// x½ = xₙ + (h/2) vₙ,     v½ = vₙ + (h/2) a(xₙ, vₙ)
/// xₙ₊₁ = xₙ + h v½,       vₙ₊₁ = vₙ + h a(x½, v½)
/// ```
///
/// Second order, two force evaluations per step. Its stability function is
/// `R(z) = 1 + z + z²/2`; on the undamped oscillator `|R(iθ)|² = 1 + θ⁴/4`
/// with `θ = hω`, so every step gains energy and no step size is stable for
/// undamped oscillations (the gain is small at small `θ`).
///
/// Source: Runge, Math. Ann. 46 (1895) 167; Hairer, Nørsett & Wanner, *Solving
/// Ordinary Differential Equations I*, §II.1.
#[derive(Debug, Clone, Default)]
pub struct Midpoint {
    forces: ForceEvaluator,
    a: Vec<Vec3>,
    x: Vec<Vec3>,
    v: Vec<Vec3>,
    x_half: Vec<Vec3>,
    v_half: Vec<Vec3>,
}

impl Midpoint {
    /// A new integrator.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }
}

impl Integrator for Midpoint {
    fn step(
        &mut self,
        system: &System,
        state: &mut State,
        dt: f64,
    ) -> Result<StepReport, StepError> {
        check_step(system, state, dt)?;
        let buffers = [
            &mut self.a,
            &mut self.x,
            &mut self.v,
            &mut self.x_half,
            &mut self.v_half,
        ];
        fit(state.len(), buffers);
        let (x0, v0) = (state.positions(), state.velocities());
        self.forces.accelerations(system, x0, v0, &mut self.a);
        combine(&mut self.x_half, x0, &[(0.5 * dt, v0)]);
        combine(&mut self.v_half, v0, &[(0.5 * dt, &self.a)]);
        self.forces
            .accelerations(system, &self.x_half, &self.v_half, &mut self.a);
        combine(&mut self.x, x0, &[(dt, &self.v_half)]);
        combine(&mut self.v, v0, &[(dt, &self.a)]);
        state.commit(&mut self.x, &mut self.v, state.time() + dt)?;
        Ok(StepReport {
            contacts: system.end_step(state),
            ..StepReport::fixed_step(2)
        })
    }

    fn name(&self) -> &'static str {
        "midpoint"
    }
}
