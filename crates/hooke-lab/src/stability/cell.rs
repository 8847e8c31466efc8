//! One cell of a stability sweep: a method on the scaled system at one
//! step, watched by its [`EnergyBudget`].

use hooke_core::{Simulation, System};

use crate::budget::EnergyBudget;
use crate::{LabError, Method, Settings};

/// The number of steps a cell at `dt` takes.
pub(super) fn cell_steps(duration: f64, min_steps: usize, dt: f64) -> usize {
    ((duration / dt).ceil() as usize).max(min_steps)
}

/// One cell's run, before it is placed in the sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct CellRun {
    /// Whether every step succeeded and the energy ratio stayed within
    /// the bound.
    pub stable: bool,
    /// The largest energy ratio seen, `1 + G(t) / A(t)` (see
    /// [`EnergyBudget`]).
    pub max_energy_ratio: f64,
    /// The largest energy gain `G(t) = E(t) − E(0) − W(t)` seen, J.
    pub max_energy_gain: f64,
    /// Wall time inside the integrator's steps, s.
    pub wall_s: f64,
    /// Steps taken.
    pub steps: usize,
    /// Why the run stopped early, if it did.
    pub stopped: Option<String>,
}

/// Runs `method` on `system` at `dt` for `steps` steps and classifies it.
///
/// # Errors
/// [`LabError::Parameter`] if the method's parameters are out of range.
pub fn run_cell(
    system: &System,
    method: Method,
    settings: &Settings,
    dt: f64,
    steps: usize,
    energy_bound: f64,
) -> Result<CellRun, LabError> {
    let mut integrator = settings.build(method, None)?;
    let mut budget = EnergyBudget::new(system).with_bound(energy_bound);
    let mut state = system.initial_state();
    let run = Simulation::new(system, &mut integrator)
        .observe(1, &mut budget)
        .run_to_end(&mut state, dt, steps);
    let stopped = match (run.failure(), budget.exceeded()) {
        (Some(error), _) => Some(error.to_string()),
        (None, true) => Some(format!(
            "energy ratio {:.3e} above the bound {energy_bound} (a gain of {:.3e} J) at t = {:.6e} s",
            budget.max_ratio(),
            budget.max_gain().0,
            state.time()
        )),
        (None, false) => None,
    };
    Ok(CellRun {
        stable: stopped.is_none(),
        max_energy_ratio: budget.max_ratio(),
        max_energy_gain: budget.max_gain().0,
        wall_s: run.wall.as_secs_f64(),
        steps: run.steps,
        stopped,
    })
}
