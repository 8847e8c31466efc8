//! Beeman's algorithm.

use hooke_core::{
    ForceEvaluator, Integrator, State, StepBuffers, StepError, StepReport, System, Vec3,
};

use crate::ops::combine;

/// Beeman's algorithm in its predictor–corrector form for velocity-dependent
/// forces:
///
/// ```text
/// xₙ₊₁  = xₙ + h vₙ + (h²/6)(4aₙ − aₙ₋₁)
/// vᵖₙ₊₁ = vₙ + (h/2)(3aₙ − aₙ₋₁)                  (predictor)
/// aₙ₊₁  = a(xₙ₊₁, vᵖₙ₊₁)
/// vₙ₊₁  = vₙ + (h/6)(2aₙ₊₁ + 5aₙ − aₙ₋₁)          (corrector)
/// ```
///
/// Second order globally (its velocities are more accurate than Verlet's
/// locally), one force evaluation per step. Its positions satisfy Verlet's
/// recurrence `xₙ₊₁ − 2xₙ + xₙ₋₁ = h² aₙ`, so on the undamped oscillator the
/// energy error stays bounded for `hω < 2` and the motion grows without bound
/// above.
///
/// It starts itself from one state by evaluating `aₙ₋₁` at the backward
/// Taylor step `x₋₁ = x₀ − h v₀ + (h²/2) a₀`, `v₋₁ = v₀ − h a₀`, and restarts
/// that way whenever the state, the system or `h` changes between steps.
///
/// Source: Beeman, J. Comput. Phys. 20 (1976) 130; Sadus, *Molecular
/// Simulation of Fluids* (1999), §5.2.
#[derive(Debug, Clone, Default)]
pub struct Beeman {
    forces: ForceEvaluator,
    out: StepBuffers,
    /// `aₙ₋₁`, `aₙ` and `aₙ₊₁`.
    a_prev: Vec<Vec3>,
    a: Vec<Vec3>,
    a_next: Vec<Vec3>,
}

impl Beeman {
    /// The name scene files, reports and the command line use.
    pub const NAME: &'static str = "beeman";

    /// A new integrator.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }
}

impl Integrator for Beeman {
    fn step(
        &mut self,
        system: &System,
        state: &mut State,
        dt: f64,
    ) -> Result<StepReport, StepError> {
        let name = self.name();
        let buffers = [&mut self.a_prev, &mut self.a, &mut self.a_next];
        let start = self.out.begin(name, system, state, dt, buffers)?;
        let out = &mut self.out;
        let (x0, v0) = (state.positions(), state.velocities());
        let h = dt;
        let mut evaluations = 1;
        if !start.continues_same_step() {
            self.forces.accelerations(system, x0, v0, &mut self.a);
            combine(&mut out.x, x0, &[(-h, v0), (0.5 * h * h, &self.a)]);
            combine(&mut out.v, v0, &[(-h, &self.a)]);
            self.forces
                .accelerations(system, &out.x, &out.v, &mut self.a_prev);
            evaluations += 2;
        }
        let (a, a_prev) = (&self.a, &self.a_prev);
        combine(
            &mut out.x,
            x0,
            &[(h, v0), (4.0 * h * h / 6.0, a), (-h * h / 6.0, a_prev)],
        );
        combine(&mut out.v, v0, &[(1.5 * h, a), (-0.5 * h, a_prev)]);
        self.forces
            .accelerations(system, &out.x, &out.v, &mut self.a_next);
        let corrector = [
            (2.0 * h / 6.0, &*self.a_next),
            (5.0 * h / 6.0, a),
            (-h / 6.0, a_prev),
        ];
        combine(&mut out.v, v0, &corrector);
        let report = out.finish(system, state, dt, StepReport::fixed_step(evaluations))?;
        // aₙ₋₁ ← aₙ ← aₙ₊₁
        std::mem::swap(&mut self.a_prev, &mut self.a);
        std::mem::swap(&mut self.a, &mut self.a_next);
        Ok(report)
    }

    fn name(&self) -> &'static str {
        Self::NAME
    }
}
