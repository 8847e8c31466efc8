//! Observers watch a run instead of printing from inside it, and
//! [`Simulation`] drives an integrator and calls them every `n` steps.

use crate::energy::Energy;
use crate::error::StepError;
use crate::{Integrator, State, StepReport, System};

/// Watches a [`Simulation`]. Both hooks do nothing by default; implement the
/// ones you need.
///
/// ```
/// use hooke_core::{Observer, State, StepReport, System};
/// /// Counts how often it is called.
/// #[derive(Default)]
/// struct Counter(usize);
/// impl Observer for Counter {
///     fn observe(&mut self, _: &System, _: &State, _: &StepReport) {
///         self.0 += 1;
///     }
/// }
/// ```
pub trait Observer {
    /// Called once with the initial state, before the first step.
    fn start(&mut self, _system: &System, _state: &State) {}

    /// Called after every `n`-th step with the state after it and the report
    /// of the steps since the previous call.
    fn observe(&mut self, _system: &System, _state: &State, _report: &StepReport) {}
}

impl<O: Observer + ?Sized> Observer for &mut O {
    fn start(&mut self, system: &System, state: &State) {
        (**self).start(system, state);
    }

    fn observe(&mut self, system: &System, state: &State, report: &StepReport) {
        (**self).observe(system, state, report);
    }
}

/// Runs an integrator for a number of fixed steps, calling observers along
/// the way.
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
/// let report = Simulation::new(&system, &mut integrator)
///     .observe(10, &mut energy)
///     .run(&mut state, 0.01, 100)?;
/// assert_eq!(report.accepted_steps, 100);
/// assert_eq!(energy.samples().len(), 11); // the start and every 10th step
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct Simulation<'a, I: ?Sized> {
    system: &'a System,
    integrator: &'a mut I,
    observers: Vec<(usize, &'a mut dyn Observer)>,
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
    /// `1`).
    #[must_use]
    pub fn observe(mut self, every: usize, observer: &'a mut dyn Observer) -> Self {
        self.observers.push((every.max(1), observer));
        self
    }

    /// Takes `steps` steps of size `dt` from `state`, returning the sum of the
    /// step reports.
    ///
    /// # Errors
    /// The first [`StepError`]; `state` is then the state before the failed
    /// step.
    pub fn run(
        &mut self,
        state: &mut State,
        dt: f64,
        steps: usize,
    ) -> Result<StepReport, StepError> {
        crate::check_step(self.system, state, dt)?;
        for (_, observer) in &mut self.observers {
            observer.start(self.system, state);
        }
        let mut total = StepReport::default();
        let mut since: Vec<StepReport> = vec![StepReport::default(); self.observers.len()];
        for step in 1..=steps {
            let report = self.integrator.step(self.system, state, dt)?;
            total += report;
            for ((every, observer), pending) in self.observers.iter_mut().zip(&mut since) {
                *pending += report;
                if step % *every == 0 {
                    observer.observe(self.system, state, pending);
                    *pending = StepReport::default();
                }
            }
        }
        Ok(total)
    }
}

/// One sample of an [`EnergyLog`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnergySample {
    /// Simulated time.
    pub time: f64,
    /// The energy at that time.
    pub energy: Energy,
    /// The dissipated power at that time.
    pub dissipation_power: f64,
}

/// Records energy and dissipated power at the start and at every observed
/// step.
#[derive(Debug, Clone, Default)]
pub struct EnergyLog {
    samples: Vec<EnergySample>,
}

impl EnergyLog {
    /// The samples, in time order.
    #[must_use]
    pub fn samples(&self) -> &[EnergySample] {
        &self.samples
    }

    fn record(&mut self, system: &System, state: &State) {
        // Simulation checks the state against the system before any hook.
        if let (Ok(energy), Ok(dissipation_power)) =
            (system.energy(state), system.dissipation_power(state))
        {
            self.samples.push(EnergySample {
                time: state.time(),
                energy,
                dissipation_power,
            });
        }
    }
}

impl Observer for EnergyLog {
    fn start(&mut self, system: &System, state: &State) {
        self.record(system, state);
    }

    fn observe(&mut self, system: &System, state: &State, _report: &StepReport) {
        self.record(system, state);
    }
}

/// Records the largest spring strain `|l − L|/L` at the start and at every
/// observed step.
#[derive(Debug, Clone, Default)]
pub struct StrainLog {
    samples: Vec<(f64, f64)>,
}

impl StrainLog {
    /// `(time, max strain)` pairs, in time order.
    #[must_use]
    pub fn samples(&self) -> &[(f64, f64)] {
        &self.samples
    }

    /// The largest strain seen (0 before any sample).
    #[must_use]
    pub fn max(&self) -> f64 {
        self.samples.iter().fold(0.0, |m, &(_, e)| m.max(e))
    }
}

impl Observer for StrainLog {
    fn start(&mut self, system: &System, state: &State) {
        // Simulation checks the state against the system before any hook.
        if let Ok(strain) = system.max_strain(state) {
            self.samples.push((state.time(), strain));
        }
    }

    fn observe(&mut self, system: &System, state: &State, _report: &StepReport) {
        self.start(system, state);
    }
}
