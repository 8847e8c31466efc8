//! [`Implicit`]'s step: the caller's step delivered whole, in substeps that
//! shrink on rejection and grow back, within the conditioning limit.

use std::time::Instant;

use hooke_core::{Integrator, Named, State, StepError, StepReport, System, check_step};

use crate::minimize::terms::Terms;
use crate::step::attempt::Outcome;
use crate::step::error_control::step_factor;
use crate::step::implicit::Implicit;

impl Integrator for Implicit {
    fn step(
        &mut self,
        system: &System,
        state: &mut State,
        dt: f64,
    ) -> Result<StepReport, StepError> {
        check_step(system, state, dt)?;
        let converges = self.settings.minimizer.converges();
        let terms = Terms::of(&mut self.terms, system)?;
        terms.push_out(system, state);
        let clock = Instant::now();
        let n = state.len();
        let w = &mut self.work;
        w.resize(n);
        w.x_start.copy_from_slice(state.positions());
        w.v_start.copy_from_slice(state.velocities());
        let (start, end) = (state.time(), state.time() + dt);
        let longest = if converges {
            self.longest.get(system, terms, Self::MAX_CONDITION)
        } else {
            f64::INFINITY
        };
        let floor = (dt / f64::from(self.settings.max_halvings).exp2()).min(longest);
        let mut h = self.substep.min(dt).min(longest);
        // Error control starts afresh at the floor: the first substep has
        // no past to estimate its error from.
        if self.settings.error_control.is_some() && !self.history.continues(system, state) {
            h = floor;
        }
        let mut report = StepReport::default();
        loop {
            let remaining = end - state.time();
            // The last substep ends exactly at the caller's time. It spans
            // the time left only where that is shorter than `h` by more
            // than rounding (`t + dt − t` is not `dt`): steps of one size
            // stay bit for bit the same size, and what is kept per step
            // size (the quasi-Newton step's factored `H₀` and its carried
            // curvature pair) is kept.
            let last = h >= remaining * (1.0 - 1e-12);
            let size = if last && remaining < h * (1.0 - 1e-12) {
                remaining
            } else {
                h
            };
            let at_floor = !converges || size <= floor * (1.0 + 1e-12);
            let outcome = self.attempt(
                system,
                state,
                size,
                last.then_some(end),
                at_floor,
                &mut report,
            );
            match outcome {
                Ok(Outcome::Accepted { easy, error }) => {
                    let factor = match error {
                        Some((err, order)) => {
                            let factor = step_factor(err, order, true);
                            if easy { factor } else { factor.min(1.0) }
                        }
                        None if easy => 2.0,
                        None => 1.0,
                    };
                    h = (factor * size.max(h.min(remaining))).clamp(floor, dt.min(longest));
                    self.substep = h;
                    if last {
                        break;
                    }
                }
                Ok(Outcome::Rejected { error }) => {
                    report.rejected_steps += 1;
                    let factor = error.map_or(0.5, |(err, order)| step_factor(err, order, false));
                    h = (factor * size).max(floor);
                }
                Err(error) => {
                    let (x, v) = (state.positions_mut(), &self.work.v_start);
                    x.copy_from_slice(&self.work.x_start);
                    state.velocities_mut().copy_from_slice(v);
                    state.set_time(start);
                    return Err(error);
                }
            }
        }
        if let Some(terms) = self.terms.as_mut() {
            let (queries, seconds) = terms.take_detection();
            report.proximity_queries += queries;
            report.detection_seconds += seconds;
        }
        self.comparison
            .step_ended(self.topology.as_mut(), clock.elapsed(), dt);
        Ok(report)
    }

    fn name(&self) -> &'static str {
        self.settings.scheme.name()
    }
}
