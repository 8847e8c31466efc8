//! [`Simulation`]: the one loop that steps an integrator and calls the
//! [`Observer`]s, and the [`Run`] it returns.

use std::ops::ControlFlow;
use std::time::{Duration, Instant};

use crate::error::StepError;
use crate::{Integrator, Observer, State, StepInfo, StepReport, System, check_step};

/// Why a run ended.
#[derive(Debug, Clone, PartialEq)]
pub enum End {
    /// Every planned step was taken.
    Completed,
    /// An observer returned [`ControlFlow::Break`].
    Stopped,
    /// A step failed; the state is the one before it.
    Failed(StepError),
}

/// What a run did.
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    /// Steps taken (the failed one not counted).
    pub steps: usize,
    /// The reports of the steps taken, summed.
    pub report: StepReport,
    /// Wall time spent inside [`Integrator::step`], failed step included.
    pub wall: Duration,
    /// Why the run ended.
    pub end: End,
}

impl Run {
    /// The step that failed, if one did.
    #[must_use]
    pub fn failure(&self) -> Option<&StepError> {
        match &self.end {
            End::Failed(error) => Some(error),
            End::Completed | End::Stopped => None,
        }
    }
}

/// Runs an integrator for a number of fixed steps, calling observers along
/// the way: the one stepping loop of hooke, used by programs, the lab and
/// the command line alike.
///
/// ```
/// use hooke_core::{EnergyLog, Integrator, Simulation, State, StepError, StepReport, System};
/// # use hooke_core::reference::Oscillator;
/// # struct Still;
/// # impl Integrator for Still {
/// #     fn step(&mut self, _: &System, s: &mut State, dt: f64) -> Result<StepReport, StepError> {
/// #         let t = s.time() + dt;
/// #         s.set_time(t);
/// #         Ok(StepReport { accepted_steps: 1, ..StepReport::default() })
/// #     }
/// # }
/// let system = Oscillator::undamped(1.0, 4.0).system()?;
/// let mut state = system.initial_state();
/// let mut energy = EnergyLog::default();
/// let mut integrator = Still; // any Integrator, e.g. hooke_explicit::Rk4
/// let run = Simulation::new(&system, &mut integrator)
///     .observe(10, &mut energy)
///     .run(&mut state, 0.01, 100)?;
/// assert_eq!(run.report.accepted_steps, 100);
/// assert_eq!(energy.samples().len(), 11); // the start and every 10th step
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct Simulation<'a, I: ?Sized> {
    system: &'a System,
    integrator: &'a mut I,
    observers: Vec<Watch<'a>>,
}

/// An observer with its period and what it has not been shown yet.
struct Watch<'a> {
    every: usize,
    observer: &'a mut dyn Observer,
    pending: StepInfo,
}

impl<'a, I: Integrator + ?Sized> Simulation<'a, I> {
    /// A simulation of `system` stepped by `integrator`, with no observers.
    #[must_use]
    pub fn new(system: &'a System, integrator: &'a mut I) -> Self {
        Self {
            system,
            integrator,
            observers: Vec::new(),
        }
    }

    /// Adds an observer called after every `every`-th step (`0` is taken as
    /// `1`). Observers are called in the order they were added.
    #[must_use]
    pub fn observe(mut self, every: usize, observer: &'a mut dyn Observer) -> Self {
        self.observers.push(Watch {
            every: every.max(1),
            observer,
            pending: StepInfo::default(),
        });
        self
    }

    /// Takes up to `steps` steps of size `dt` from `state`, each timed on
    /// its own, until they are done, an observer stops the run or a step
    /// fails. Every observer's [`Observer::finish`] is called in each case.
    ///
    /// # Errors
    /// The first [`StepError`]: invalid arguments before any observer is
    /// called, or a failed step, after which `state` is the state before
    /// it. [`Simulation::run_to_end`] returns the [`Run`] in that case too.
    pub fn run(&mut self, state: &mut State, dt: f64, steps: usize) -> Result<Run, StepError> {
        check_step(self.system, state, dt)?;
        let run = self.run_to_end(state, dt, steps);
        match run.end {
            End::Failed(error) => Err(error),
            End::Completed | End::Stopped => Ok(run),
        }
    }

    /// Like [`Simulation::run`], with a failed step (or invalid arguments,
    /// then with no step taken and no observer called) reported in
    /// [`Run::end`] rather than as an error.
    pub fn run_to_end(&mut self, state: &mut State, dt: f64, steps: usize) -> Run {
        let mut run = Run {
            steps: 0,
            report: StepReport::default(),
            wall: Duration::ZERO,
            end: End::Completed,
        };
        if let Err(error) = check_step(self.system, state, dt) {
            run.end = End::Failed(error);
            return run;
        }
        for watch in &mut self.observers {
            watch.observer.start(self.system, state);
            watch.pending = StepInfo::default();
        }
        for index in 1..=steps {
            let started = Instant::now();
            let result = self.integrator.step(self.system, state, dt);
            let wall = started.elapsed();
            run.wall += wall;
            let report = match result {
                Ok(report) => report,
                Err(error) => {
                    run.end = End::Failed(error);
                    break;
                }
            };
            run.steps = index;
            run.report += report;
            if self.show(state, index, report, wall).is_break() {
                run.end = End::Stopped;
                break;
            }
        }
        for watch in &mut self.observers {
            watch.observer.finish(self.system, state, &run);
        }
        run
    }

    /// Shows step `index` to every observer due, and whether one of them
    /// stopped the run.
    fn show(
        &mut self,
        state: &State,
        index: usize,
        report: StepReport,
        wall: Duration,
    ) -> ControlFlow<()> {
        let mut flow = ControlFlow::Continue(());
        for watch in &mut self.observers {
            watch.pending.index = index;
            watch.pending.report += report;
            watch.pending.wall += wall;
            if index % watch.every == 0 {
                let step = std::mem::take(&mut watch.pending);
                if watch.observer.observe(self.system, state, &step).is_break() {
                    flow = ControlFlow::Break(());
                }
            }
        }
        flow
    }
}
