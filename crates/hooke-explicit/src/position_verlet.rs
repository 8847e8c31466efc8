//! Position (Störmer) Verlet.

use hooke_core::{
    ForceEvaluator, History, Integrator, State, StepError, StepReport, System, Vec3, check_step,
};

use crate::ops::{combine, fit};

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
    history: History,
    /// `xₙ₋₁`.
    x_prev: Vec<Vec3>,
    /// `aₙ` at the state's positions.
    a: Vec<Vec3>,
    a_next: Vec<Vec3>,
    x: Vec<Vec3>,
    v: Vec<Vec3>,
}

/// `v = (x₁ − x₀)/h + (h/2) a`.
fn velocity(v: &mut [Vec3], x1: &[Vec3], x0: &[Vec3], a: &[Vec3], h: f64) {
    for (((v, x1), x0), a) in v.iter_mut().zip(x1).zip(x0).zip(a) {
        *v = (x1 - x0) / h + 0.5 * h * a;
    }
}

impl PositionVerlet {
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
        check_step(system, state, dt)?;
        let continues = self.history.take_same_step(system, state, dt);
        fit(
            state.len(),
            [
                &mut self.x_prev,
                &mut self.a,
                &mut self.a_next,
                &mut self.x,
                &mut self.v,
            ],
        );
        let (x0, v0) = (state.positions(), state.velocities());
        let mut evaluations = 1;
        if !continues {
            self.forces.accelerations(system, x0, v0, &mut self.a);
            combine(&mut self.x_prev, x0, &[(-dt, v0), (0.5 * dt * dt, &self.a)]);
            evaluations += 1;
        }
        combine(
            &mut self.x,
            x0,
            &[(1.0, x0), (-1.0, &self.x_prev), (dt * dt, &self.a)],
        );
        velocity(&mut self.v, &self.x, x0, &self.a, dt);
        self.forces
            .accelerations(system, &self.x, &self.v, &mut self.a_next);
        velocity(&mut self.v, &self.x, x0, &self.a_next, dt);
        state.commit(&mut self.x, &mut self.v, state.time() + dt)?;
        // `x` now holds the previous positions xₙ, which become xₙ₋₁.
        std::mem::swap(&mut self.x_prev, &mut self.x);
        std::mem::swap(&mut self.a, &mut self.a_next);
        self.history.record(system, state, dt);
        Ok(StepReport {
            contacts: system.end_step(state),
            ..StepReport::fixed_step(evaluations)
        })
    }

    fn name(&self) -> &'static str {
        "position-verlet"
    }
}
