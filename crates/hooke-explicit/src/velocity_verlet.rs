//! Velocity Verlet.

use hooke_core::{
    ForceEvaluator, Integrator, State, StepBuffers, StepError, StepReport, System, Vec3,
};

use crate::ops::combine;

/// Velocity Verlet:
///
/// ```text
/// xₙ₊₁ = xₙ + h vₙ + (h²/2) aₙ
/// aₙ₊₁ = a(xₙ₊₁, vₙ + h aₙ)
/// vₙ₊₁ = vₙ + (h/2)(aₙ + aₙ₊₁)
/// ```
///
/// Second order, one force evaluation per step (`aₙ₊₁` is kept for the next
/// step), time-reversible and symplectic for conservative forces: on the
/// undamped oscillator the energy error stays bounded for `hω < 2` and the
/// motion grows without bound above. Velocity-dependent forces are evaluated
/// at the predicted velocity `vₙ + h aₙ`, whose `O(h²)` error keeps second
/// order.
///
/// The cached acceleration is recomputed whenever the state, the system or `h`
/// changes between steps.
///
/// Source: Swope, Andersen, Berens & Wilson, J. Chem. Phys. 76 (1982) 637;
/// Hairer, Lubich & Wanner, Acta Numerica 12 (2003), §1.
#[derive(Debug, Clone, Default)]
pub struct VelocityVerlet {
    forces: ForceEvaluator,
    out: StepBuffers,
    /// `aₙ` at the state's positions.
    a: Vec<Vec3>,
    a_next: Vec<Vec3>,
}

impl VelocityVerlet {
    /// The name scene files, reports and the command line use.
    pub const NAME: &'static str = "velocity-verlet";

    /// A new integrator.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }
}

impl Integrator for VelocityVerlet {
    fn step(
        &mut self,
        system: &System,
        state: &mut State,
        dt: f64,
    ) -> Result<StepReport, StepError> {
        let name = self.name();
        let start = self
            .out
            .begin(name, system, state, dt, [&mut self.a, &mut self.a_next])?;
        let (x0, v0) = (state.positions(), state.velocities());
        let mut evaluations = 1;
        if !start.continues_same_step() {
            self.forces.accelerations(system, x0, v0, &mut self.a);
            evaluations += 1;
        }
        let out = &mut self.out;
        combine(&mut out.x, x0, &[(dt, v0), (0.5 * dt * dt, &self.a)]);
        combine(&mut out.v, v0, &[(dt, &self.a)]);
        self.forces
            .accelerations(system, &out.x, &out.v, &mut self.a_next);
        combine(
            &mut out.v,
            v0,
            &[(0.5 * dt, &self.a), (0.5 * dt, &self.a_next)],
        );
        let report = out.finish(system, state, dt, StepReport::fixed_step(evaluations))?;
        std::mem::swap(&mut self.a, &mut self.a_next);
        Ok(report)
    }

    fn name(&self) -> &'static str {
        Self::NAME
    }
}
