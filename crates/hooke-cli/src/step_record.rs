//! [`StepRecord`]: the observer that times every step of a run for its
//! summary, notes where its steps first fell short, and stops a run that
//! has diverged.

use std::ops::ControlFlow;

use hooke_core::{Observer, State, StepInfo, System};

use crate::frames::beyond_frame_range;

/// Called after every step: records its wall time and contacts, the first
/// step that was accepted unconverged and the first linear solve that
/// stopped at its cap, and stops the run when a position leaves what a
/// frame file holds (the run has diverged), keeping the reason.
#[derive(Debug, Default)]
pub(crate) struct StepRecord {
    /// Wall time of each step, ms.
    pub(crate) step_ms: Vec<f64>,
    /// Most contacts one step resolved.
    pub(crate) contacts_max: usize,
    /// The end time and final Newton residual of the first step accepted
    /// without converging.
    pub(crate) first_unconverged: Option<(f64, f64)>,
    /// The end time and relative residual of the first step with a linear
    /// solve stopped at its iteration cap.
    pub(crate) first_capped_solve: Option<(f64, f64)>,
    /// Why the run diverged, if it did.
    pub(crate) diverged: Option<String>,
}

impl Observer for StepRecord {
    fn observe(&mut self, _system: &System, state: &State, step: &StepInfo) -> ControlFlow<()> {
        self.step_ms.push(step.wall.as_secs_f64() * 1e3);
        self.contacts_max = self.contacts_max.max(step.report.contacts);
        let report = &step.report;
        if report.unconverged_steps > 0 && self.first_unconverged.is_none() {
            self.first_unconverged = Some((state.time(), report.newton_residual));
        }
        if report.unconverged_solves > 0 && self.first_capped_solve.is_none() {
            self.first_capped_solve = Some((state.time(), report.linear_residual));
        }
        match beyond_frame_range(state) {
            Some(particle) => {
                self.diverged = Some(format!(
                    "diverged: particle {particle} is beyond the range of the frame files \
                     (|x| > {:.1e} m) at t = {}",
                    f32::MAX,
                    state.time()
                ));
                ControlFlow::Break(())
            }
            None => ControlFlow::Continue(()),
        }
    }
}
