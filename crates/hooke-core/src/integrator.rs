//! The [`Integrator`] trait and the [`StepReport`] every step returns.

use std::ops::AddAssign;

use crate::error::StepError;
use crate::{State, System};

/// What one call to [`Integrator::step`] did. Adding reports sums the counts
/// and keeps the largest residuals.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepReport {
    /// Evaluations of all forces of the system (for implicit methods: of the
    /// forces with their Jacobian blocks, i.e. assemblies of the system).
    pub force_evaluations: usize,
    /// Steps (or, for adaptive methods, substeps) that were accepted.
    pub accepted_steps: usize,
    /// Substeps an adaptive method rejected and retried smaller.
    pub rejected_steps: usize,
    /// Iterations of an iterative linear solver (zero for explicit methods and
    /// direct solvers).
    pub linear_iterations: usize,
    /// Linear systems solved.
    pub linear_solves: usize,
    /// Linear solves that stopped at their iteration cap before meeting their
    /// tolerance; their approximate solution was used.
    pub unconverged_solves: usize,
    /// Largest relative residual `‖S(b − A x)‖/‖S b‖` a linear solve ended
    /// with.
    pub linear_residual: f64,
    /// Newton iterations of implicit methods (a linearised step counts one).
    pub newton_iterations: usize,
    /// Most Newton iterations one (sub)step took.
    pub newton_iterations_max: usize,
    /// Steps (or substeps) accepted without meeting the method's convergence
    /// test, because their step size had reached its floor.
    pub unconverged_steps: usize,
    /// Steps whose energy gain beyond the work of external forces was
    /// removed by the last resort of an energy-checked method (see
    /// `hooke_implicit::Implicit`).
    pub energy_corrections: usize,
    /// Largest energy, in J, that one step gained beyond the work of external
    /// forces: removed by the last resort where [`Self::energy_corrections`]
    /// counts it, removed within the Newton tolerance by an energy-checked
    /// method's test (see `hooke_implicit::Implicit`), otherwise left in the
    /// state.
    pub energy_excess: f64,
    /// Largest final Newton residual of a step: the last Newton step
    /// `‖δ‖∞` relative to the step's velocity scale (see
    /// `hooke_implicit::Implicit`), zero where only linearised steps were
    /// taken.
    pub newton_residual: f64,
    /// Particle–obstacle contacts of the step: those resolved at its end,
    /// and for implicit methods those held on an obstacle within it.
    pub contacts: usize,
    /// The linear solver of an implicit method's last solve, as its scene
    /// files spell it (`"cholesky"`, `"pcg"`, `"amg"`; what `"auto"` chose);
    /// empty for methods without linear solves.
    pub linear_solver: &'static str,
    /// Proximity queries of an implicit method's contact: searches of its
    /// pair list, by proximity or swept along a motion.
    pub proximity_queries: usize,
    /// Time an implicit method's contact spent on collision detection — its
    /// searches and its checks of motions (CCD) — in seconds.
    pub detection_seconds: f64,
    /// Particles whose motion an implicit method's per-particle contact
    /// bounds cut, summed over its Newton iterations
    /// (`hooke_implicit::ContactLimit::Particles`).
    pub truncated_particles: usize,
    /// Most particles one Newton iteration cut.
    pub truncated_particles_max: usize,
    /// Newton iterations whose cut step did not descend and that fell back
    /// to the global collision limit along the whole step.
    pub bound_fallbacks: usize,
}

impl StepReport {
    /// The report of one accepted fixed step that evaluated the forces
    /// `force_evaluations` times.
    #[must_use]
    pub fn fixed_step(force_evaluations: usize) -> Self {
        Self {
            force_evaluations,
            accepted_steps: 1,
            ..Self::default()
        }
    }
}

impl AddAssign for StepReport {
    fn add_assign(&mut self, other: Self) {
        self.force_evaluations += other.force_evaluations;
        self.accepted_steps += other.accepted_steps;
        self.rejected_steps += other.rejected_steps;
        self.linear_iterations += other.linear_iterations;
        self.linear_solves += other.linear_solves;
        self.unconverged_solves += other.unconverged_solves;
        self.linear_residual = self.linear_residual.max(other.linear_residual);
        self.newton_iterations += other.newton_iterations;
        self.newton_iterations_max = self.newton_iterations_max.max(other.newton_iterations_max);
        self.unconverged_steps += other.unconverged_steps;
        self.energy_corrections += other.energy_corrections;
        self.energy_excess = self.energy_excess.max(other.energy_excess);
        self.contacts += other.contacts;
        self.newton_residual = self.newton_residual.max(other.newton_residual);
        self.proximity_queries += other.proximity_queries;
        self.detection_seconds += other.detection_seconds;
        self.truncated_particles += other.truncated_particles;
        self.truncated_particles_max = self
            .truncated_particles_max
            .max(other.truncated_particles_max);
        self.bound_fallbacks += other.bound_fallbacks;
        if !other.linear_solver.is_empty() {
            self.linear_solver = other.linear_solver;
        }
    }
}

/// A time integrator: advances a [`State`] of a [`System`] by one step.
///
/// Integrators own their scratch buffers, so once they have seen a system a
/// step allocates nothing. Integrators that keep history between steps
/// (staggered velocities, previous accelerations, a Nordsieck vector) restart
/// themselves from the state alone whenever they are handed a state they did
/// not produce, a different system, or (unless they can rescale) a different
/// step size — see [`crate::History`].
pub trait Integrator {
    /// Advances `state` from `t` to `t + dt`.
    ///
    /// # Errors
    /// [`StepError::InvalidTimestep`] for `dt` not positive and finite,
    /// [`StepError::StateMismatch`] for a state of another system, and
    /// [`StepError::NonFinite`] if the step would produce a NaN or infinite
    /// position or velocity; in every case the state is left unchanged.
    fn step(
        &mut self,
        system: &System,
        state: &mut State,
        dt: f64,
    ) -> Result<StepReport, StepError>;

    /// A short lowercase name for reports and plots, e.g. `"rk4"`.
    fn name(&self) -> &'static str {
        std::any::type_name::<Self>()
    }
}

impl<I: Integrator + ?Sized> Integrator for Box<I> {
    fn step(
        &mut self,
        system: &System,
        state: &mut State,
        dt: f64,
    ) -> Result<StepReport, StepError> {
        (**self).step(system, state, dt)
    }

    fn name(&self) -> &'static str {
        (**self).name()
    }
}

/// Checks the arguments every step shares: a positive, finite `dt` and a
/// state with as many particles as the system.
///
/// # Errors
/// [`StepError::InvalidTimestep`] or [`StepError::StateMismatch`].
pub fn check_step(system: &System, state: &State, dt: f64) -> Result<(), StepError> {
    if !(dt.is_finite() && dt > 0.0) {
        return Err(StepError::InvalidTimestep { dt });
    }
    system.check_state(state)
}
