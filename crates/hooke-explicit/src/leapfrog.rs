//! Leapfrog, kick-drift-kick, with staggered velocities.

use hooke_core::{
    ForceEvaluator, Integrator, State, StepBuffers, StepError, StepReport, System, Vec3,
};

use crate::ops::combine;

/// Leapfrog in kick-drift-kick form. Its own variable is the staggered
/// velocity `vₙ₊½`; it starts with the half kick `v½ = v₀ + (h/2) a₀` and then
/// each step drifts and kicks:
///
/// ```text
/// xₙ₊₁   = xₙ + h vₙ₊½
/// aₙ₊₁   = a(xₙ₊₁, vₙ₊½ + (h/2) aₙ)
/// vₙ₊₃⁄₂ = vₙ₊½ + h aₙ₊₁
/// ```
///
/// reporting the synchronised velocity `vₙ₊₁ = vₙ₊½ + (h/2) aₙ₊₁` in the
/// state. Second order, one force evaluation per step, time-reversible and
/// symplectic for conservative forces: on the undamped oscillator the energy
/// error stays bounded for `hω < 2` and the motion grows without bound above.
///
/// In exact arithmetic the positions are those of [`crate::VelocityVerlet`]
/// and [`crate::PositionVerlet`]; the three differ in what they carry from step
/// to step (here `vₙ₊½` and `aₙ`), hence in rounding and in restarts.
/// Velocity-dependent forces (damping) are evaluated at the predicted
/// velocity `vₙ₊½ + (h/2) aₙ = vₙ + h aₙ`, whose `O(h²)` error keeps the
/// method second order.
///
/// The integrator restarts with a fresh half kick whenever the state, the
/// system or `h` changes between steps.
///
/// Source: Hairer, Lubich & Wanner, *Geometric Numerical Integration Illustrated
/// by the Störmer–Verlet Method*, Acta Numerica 12 (2003), §1.
#[derive(Debug, Clone, Default)]
pub struct Leapfrog {
    forces: ForceEvaluator,
    out: StepBuffers,
    /// `aₙ` at the state's positions.
    a: Vec<Vec3>,
    /// The staggered velocity `vₙ₊½`.
    v_half: Vec<Vec3>,
}

impl Leapfrog {
    /// The name scene files, reports and the command line use.
    pub const NAME: &'static str = "leapfrog";

    /// A new integrator.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }
}

impl Integrator for Leapfrog {
    fn step(
        &mut self,
        system: &System,
        state: &mut State,
        dt: f64,
    ) -> Result<StepReport, StepError> {
        let name = self.name();
        let start = self
            .out
            .begin(name, system, state, dt, [&mut self.a, &mut self.v_half])?;
        let (x0, v0) = (state.positions(), state.velocities());
        let mut evaluations = 1;
        if !start.continues_same_step() {
            self.forces.accelerations(system, x0, v0, &mut self.a);
            combine(&mut self.v_half, v0, &[(0.5 * dt, &self.a)]);
            evaluations += 1;
        }
        let out = &mut self.out;
        combine(&mut out.x, x0, &[(dt, &self.v_half)]);
        combine(&mut out.v, &self.v_half, &[(0.5 * dt, &self.a)]);
        self.forces
            .accelerations(system, &out.x, &out.v, &mut self.a);
        combine(&mut out.v, &self.v_half, &[(0.5 * dt, &self.a)]);
        let report = out.finish(system, state, dt, StepReport::fixed_step(evaluations))?;
        for (vh, a) in self.v_half.iter_mut().zip(&self.a) {
            *vh += dt * a;
        }
        Ok(report)
    }

    fn name(&self) -> &'static str {
        Self::NAME
    }
}
