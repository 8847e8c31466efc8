//! [`StepRecord`]: the observer that times every step of a run for its
//! summary and stops a run that has diverged.

use std::ops::ControlFlow;

use hooke_core::{Observer, State, StepInfo, System};

use crate::frames::beyond_frame_range;

/// Called after every step: records its wall time and contacts, and stops
/// the run when a position leaves what a frame file holds (the run has
/// diverged), keeping the reason.
#[derive(Debug, Default)]
pub(crate) struct StepRecord {
    /// Wall time of each step, ms.
    pub(crate) step_ms: Vec<f64>,
    /// Most contacts one step resolved.
    pub(crate) contacts_max: usize,
    /// Why the run diverged, if it did.
    pub(crate) diverged: Option<String>,
}

impl Observer for StepRecord {
    fn observe(&mut self, _system: &System, state: &State, step: &StepInfo) -> ControlFlow<()> {
        self.step_ms.push(step.wall.as_secs_f64() * 1e3);
        self.contacts_max = self.contacts_max.max(step.report.contacts);
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
