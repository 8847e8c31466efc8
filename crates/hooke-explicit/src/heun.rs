//! Heun's method (explicit trapezoidal rule).

use hooke_core::{
    ForceEvaluator, Integrator, State, StepBuffers, StepError, StepReport, System, Vec3,
};

use crate::ops::combine;

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
    out: StepBuffers,
    a: Vec<Vec3>,
    a_predicted: Vec<Vec3>,
}

impl Heun {
    /// The name scene files, reports and the command line use.
    pub const NAME: &'static str = "heun";

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
        let name = self.name();
        let buffers = [&mut self.a, &mut self.a_predicted];
        self.out.begin(name, system, state, dt, buffers)?;
        let (x0, v0) = (state.positions(), state.velocities());
        self.forces.accelerations(system, x0, v0, &mut self.a);
        let out = &mut self.out;
        combine(&mut out.x, x0, &[(dt, v0)]);
        combine(&mut out.v, v0, &[(dt, &self.a)]);
        self.forces
            .accelerations(system, &out.x, &out.v, &mut self.a_predicted);
        // x̃ − xₙ = h vₙ, so xₙ₊₁ = xₙ + (h/2) vₙ + (h/2) ṽ.
        combine(&mut out.x, x0, &[(0.5 * dt, v0), (0.5 * dt, &out.v)]);
        combine(
            &mut out.v,
            v0,
            &[(0.5 * dt, &self.a), (0.5 * dt, &self.a_predicted)],
        );
        self.out
            .finish(system, state, dt, StepReport::fixed_step(2))
    }

    fn name(&self) -> &'static str {
        Self::NAME
    }
}
