//! Position (Störmer) Verlet.

use hooke_core::{
    ForceEvaluator, Integrator, State, StepBuffers, StepError, StepReport, System, Vec3,
};

use crate::ops::combine;

/// Position (Störmer) Verlet, the two-step recurrence on positions:
///
/// ```text
/// xₙ₊₁ = 2xₙ − xₙ₋₁ + h² aₙ
/// vₙ₊₁ = (xₙ₊₁ − xₙ)/h + (h/2) aₙ₊₁
/// ```
///
/// with `aₙ₊₁` evaluated at the predicted velocity `(xₙ₊₁ − xₙ)/h + (h/2) aₙ`
/// for velocity-dependent forces. It starts itself from one state with the
/// backward Taylor step `x₋₁ = x₀ − h v₀ + (h²/2) a₀`, which makes the first
/// step `x₁ = x₀ + h v₀ + (h²/2) a₀`.
///
/// Second order, one force evaluation per step; on the undamped oscillator the
/// energy error stays bounded for `hω < 2` and the motion grows without bound
/// above. In exact arithmetic its positions are those of
/// [`crate::VelocityVerlet`]; it carries `xₙ₋₁` instead of `vₙ`, the form
/// Störmer and Verlet used.
///
/// The integrator restarts whenever the state, the system or `h` changes
/// between steps.
///
/// Source: Verlet, Phys. Rev. 159 (1967) 98; Hairer, Lubich & Wanner, Acta
/// Numerica 12 (2003), §1.
#[derive(Debug, Clone, Default)]
pub struct PositionVerlet {
    forces: ForceEvaluator,
    out: StepBuffers,
    /// `xₙ₋₁`.
    x_prev: Vec<Vec3>,
    /// `aₙ` at the state's positions.
    a: Vec<Vec3>,
    a_next: Vec<Vec3>,
}

/// `v = (x₁ − x₀)/h + (h/2) a`.
fn velocity(v: &mut [Vec3], x1: &[Vec3], x0: &[Vec3], a: &[Vec3], h: f64) {
    for (((v, x1), x0), a) in v.iter_mut().zip(x1).zip(x0).zip(a) {
        *v = (x1 - x0) / h + 0.5 * h * a;
    }
}

impl PositionVerlet {
    /// The name scene files, reports and the command line use.
    pub const NAME: &'static str = "position-verlet";

    /// A new integrator.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }
}

impl Integrator for PositionVerlet {
    fn step(
        &mut self,
        system: &System,
        state: &mut State,
        dt: f64,
    ) -> Result<StepReport, StepError> {
        let name = self.name();
        let buffers = [&mut self.x_prev, &mut self.a, &mut self.a_next];
        let start = self.out.begin(name, system, state, dt, buffers)?;
        let (x0, v0) = (state.positions(), state.velocities());
        let mut evaluations = 1;
        if !start.continues_same_step() {
            self.forces.accelerations(system, x0, v0, &mut self.a);
            combine(&mut self.x_prev, x0, &[(-dt, v0), (0.5 * dt * dt, &self.a)]);
            evaluations += 1;
        }
        let out = &mut self.out;
        combine(
            &mut out.x,
            x0,
            &[(1.0, x0), (-1.0, &self.x_prev), (dt * dt, &self.a)],
        );
        velocity(&mut out.v, &out.x, x0, &self.a, dt);
        self.forces
            .accelerations(system, &out.x, &out.v, &mut self.a_next);
        velocity(&mut out.v, &out.x, x0, &self.a_next, dt);
        let report = out.finish(system, state, dt, StepReport::fixed_step(evaluations))?;
        // `x` now holds the previous positions xₙ, which become xₙ₋₁.
        std::mem::swap(&mut self.x_prev, &mut out.x);
        std::mem::swap(&mut self.a, &mut self.a_next);
        Ok(report)
    }

    fn name(&self) -> &'static str {
        Self::NAME
    }
}
