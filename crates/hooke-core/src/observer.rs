//! [`Observer`]: watches a [`Simulation`](crate::Simulation) instead of
//! printing from inside it, and may stop it.

use std::ops::ControlFlow;
use std::time::Duration;

use crate::{Run, State, StepReport, System};

/// What an observer is shown of the steps since its previous call.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepInfo {
    /// Steps taken since the start of the run, this one included.
    pub index: usize,
    /// The reports of the steps since the previous call, summed.
    pub report: StepReport,
    /// Wall time spent inside [`Integrator::step`](crate::Integrator::step)
    /// for those steps (what observers did between them is not counted).
    pub wall: Duration,
}

/// Watches a [`Simulation`](crate::Simulation). Every hook does nothing by
/// default; implement the ones you need.
///
/// [`Observer::observe`] returns whether the run goes on:
/// [`ControlFlow::Break`] stops it after the current step (the other
/// observers due at that step are still called).
///
/// ```
/// use std::ops::ControlFlow;
/// use hooke_core::{Observer, State, StepInfo, System};
/// /// Stops the run once a particle falls below the floor.
/// struct Floor(f64);
/// impl Observer for Floor {
///     fn observe(&mut self, _: &System, state: &State, _: &StepInfo) -> ControlFlow<()> {
///         if state.positions().iter().any(|x| x.y < self.0) {
///             ControlFlow::Break(())
///         } else {
///             ControlFlow::Continue(())
///         }
///     }
/// }
/// ```
pub trait Observer {
    /// Called once with the initial state, before the first step.
    fn start(&mut self, _system: &System, _state: &State) {}

    /// Called after every `n`-th step (see
    /// [`Simulation::observe`](crate::Simulation::observe)) with the state
    /// after it and what the steps since the previous call did.
    fn observe(&mut self, _system: &System, _state: &State, _step: &StepInfo) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }

    /// Called once when the run ends — completed, stopped by an observer or
    /// failed — with the last state reached and how the run went.
    fn finish(&mut self, _system: &System, _state: &State, _run: &Run) {}
}

/// The observer that watches nothing.
impl Observer for () {}

impl<O: Observer + ?Sized> Observer for &mut O {
    fn start(&mut self, system: &System, state: &State) {
        (**self).start(system, state);
    }

    fn observe(&mut self, system: &System, state: &State, step: &StepInfo) -> ControlFlow<()> {
        (**self).observe(system, state, step)
    }

    fn finish(&mut self, system: &System, state: &State, run: &Run) {
        (**self).finish(system, state, run);
    }
}

/// An observer made of a closure called at every observed step, for the
/// cases where a type of its own would be ceremony.
///
/// ```
/// use std::ops::ControlFlow;
/// use hooke_core::{ObserveFn, Simulation, State, StepInfo, System};
/// # use hooke_core::{Integrator, StepError, StepReport};
/// # use hooke_core::reference::Oscillator;
/// # struct Still;
/// # impl Integrator for Still {
/// #     fn step(&mut self, _: &System, s: &mut State, dt: f64) -> Result<StepReport, StepError> {
/// #         let t = s.time() + dt;
/// #         s.set_time(t);
/// #         Ok(StepReport::fixed_step(0))
/// #     }
/// # }
/// let system = Oscillator::undamped(1.0, 1.0).system()?;
/// let mut state = system.initial_state();
/// let mut heights = Vec::new();
/// let mut record = ObserveFn(|_: &System, state: &State, _: &StepInfo| {
///     heights.push(state.positions()[Oscillator::BOB].y);
///     ControlFlow::Continue(())
/// });
/// Simulation::new(&system, &mut Still) // any Integrator
///     .observe(5, &mut record)
///     .run(&mut state, 0.01, 20)?;
/// assert_eq!(heights.len(), 4);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct ObserveFn<F>(pub F);

impl<F: FnMut(&System, &State, &StepInfo) -> ControlFlow<()>> Observer for ObserveFn<F> {
    fn observe(&mut self, system: &System, state: &State, step: &StepInfo) -> ControlFlow<()> {
        (self.0)(system, state, step)
    }
}
