//! The classical fourth-order Runge–Kutta method.

use hooke_core::{
    ForceEvaluator, Integrator, State, StepBuffers, StepError, StepReport, System, Vec3,
};

use crate::ops::combine;

/// Classical Runge–Kutta method on `y = (x, v)`, `y' = (v, a(x, v))`:
///
/// ```text
/// k₁ = f(yₙ)              k₂ = f(yₙ + (h/2) k₁)
/// k₃ = f(yₙ + (h/2) k₂)   k₄ = f(yₙ + h k₃)
/// yₙ₊₁ = yₙ + (h/6)(k₁ + 2k₂ + 2k₃ + k₄)
/// ```
///
/// Fourth order, four force evaluations per step. Its stability function is
/// `R(z) = 1 + z + z²/2 + z³/6 + z⁴/24`; on the undamped oscillator
/// `|R(iθ)|² = 1 − θ⁶/72 + θ⁸/576`, which is at most 1 exactly for
/// `θ = hω ≤ 2√2`: below that the energy decays slowly (numerical
/// dissipation), above it the motion grows without bound.
///
/// Source: Kutta, Z. Math. Phys. 46 (1901) 435; Hairer, Nørsett & Wanner,
/// *Solving Ordinary Differential Equations I*, §II.1 and §IV.2.
#[derive(Debug, Clone, Default)]
pub struct Rk4 {
    forces: ForceEvaluator,
    /// Stage acceleration.
    a: Vec<Vec3>,
    /// Stage position and velocity, then the result.
    out: StepBuffers,
    /// `k₁ + 2k₂ + 2k₃ + k₄`, split into its position and velocity parts.
    sum_x: Vec<Vec3>,
    sum_v: Vec<Vec3>,
}

impl Rk4 {
    /// The name scene files, reports and the command line use.
    pub const NAME: &'static str = "rk4";

    /// A new integrator.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }
}

impl Integrator for Rk4 {
    fn step(
        &mut self,
        system: &System,
        state: &mut State,
        dt: f64,
    ) -> Result<StepReport, StepError> {
        let name = self.name();
        let buffers = [&mut self.a, &mut self.sum_x, &mut self.sum_v];
        self.out.begin(name, system, state, dt, buffers)?;
        let StepBuffers { x, v, .. } = &mut self.out;
        let (x0, v0) = (state.positions(), state.velocities());
        self.forces.accelerations(system, x0, v0, &mut self.a);
        self.sum_x.copy_from_slice(v0);
        self.sum_v.copy_from_slice(&self.a);
        combine(x, x0, &[(0.5 * dt, v0)]);
        combine(v, v0, &[(0.5 * dt, &self.a)]);
        for (weight, next) in [(2.0, 0.5 * dt), (2.0, dt), (1.0, 0.0)] {
            self.forces.accelerations(system, x, v, &mut self.a);
            for i in 0..self.a.len() {
                self.sum_x[i] += weight * v[i];
                self.sum_v[i] += weight * self.a[i];
                // The next stage: yₙ + next · (this stage's derivative).
                x[i] = x0[i] + next * v[i];
                v[i] = v0[i] + next * self.a[i];
            }
        }
        combine(x, x0, &[(dt / 6.0, &self.sum_x)]);
        combine(v, v0, &[(dt / 6.0, &self.sum_v)]);
        self.out
            .finish(system, state, dt, StepReport::fixed_step(4))
    }

    fn name(&self) -> &'static str {
        Self::NAME
    }
}
