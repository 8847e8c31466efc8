//! Explicit midpoint (second-order Runge–Kutta).

use hooke_core::{
    ForceEvaluator, Integrator, State, StepBuffers, StepError, StepReport, System, Vec3,
};

use crate::ops::combine;

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
    out: StepBuffers,
    a: Vec<Vec3>,
    x_half: Vec<Vec3>,
    v_half: Vec<Vec3>,
}

impl Midpoint {
    /// The name scene files, reports and the command line use.
    pub const NAME: &'static str = "midpoint";

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
        let name = self.name();
        let buffers = [&mut self.a, &mut self.x_half, &mut self.v_half];
        self.out.begin(name, system, state, dt, buffers)?;
        let (x0, v0) = (state.positions(), state.velocities());
        self.forces.accelerations(system, x0, v0, &mut self.a);
        combine(&mut self.x_half, x0, &[(0.5 * dt, v0)]);
        combine(&mut self.v_half, v0, &[(0.5 * dt, &self.a)]);
        self.forces
            .accelerations(system, &self.x_half, &self.v_half, &mut self.a);
        combine(&mut self.out.x, x0, &[(dt, &self.v_half)]);
        combine(&mut self.out.v, v0, &[(dt, &self.a)]);
        self.out
            .finish(system, state, dt, StepReport::fixed_step(2))
    }

    fn name(&self) -> &'static str {
        Self::NAME
    }
}
