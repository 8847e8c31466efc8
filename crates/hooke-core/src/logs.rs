//! Observers that record what a run did: [`EnergyLog`] and [`StrainLog`].

use std::ops::ControlFlow;

use crate::energy::Energy;
use crate::{Observer, Run, State, StepInfo, System};

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

/// Records energy and dissipated power at the start, at every observed
/// step and at the end of the run.
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
        if self
            .samples
            .last()
            .is_some_and(|s| s.time.to_bits() == state.time().to_bits())
        {
            return;
        }
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

/// Records the largest spring strain `|l − L|/L` at the start, at every
/// observed step and at the end of the run.
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

impl StrainLog {
    fn record(&mut self, system: &System, state: &State) {
        if self
            .samples
            .last()
            .is_some_and(|&(t, _)| t.to_bits() == state.time().to_bits())
        {
            return;
        }
        // Simulation checks the state against the system before any hook.
        if let Ok(strain) = system.max_strain(state) {
            self.samples.push((state.time(), strain));
        }
    }
}

/// A log records the state at the start, at every observed step and at the
/// end.
macro_rules! sampling_observer {
    ($($log:ty),*) => {$(
        impl Observer for $log {
            fn start(&mut self, system: &System, state: &State) {
                self.record(system, state);
            }

            fn observe(&mut self, system: &System, state: &State, _: &StepInfo) -> ControlFlow<()> {
                self.record(system, state);
                ControlFlow::Continue(())
            }

            fn finish(&mut self, system: &System, state: &State, _run: &Run) {
                self.record(system, state);
            }
        }
    )*};
}
sampling_observer!(EnergyLog, StrainLog);
