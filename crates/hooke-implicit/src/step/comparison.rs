//! [`LinearSolver::Auto`](crate::LinearSolver::Auto)'s comparison of two
//! candidates on whole steps, timed per second simulated: the step after
//! the trial's is measured with the trial's choice, the next with the
//! runner-up, and the faster serves the rest of the run.

use std::time::Duration;

use crate::linear::solver::topology::Topology;

/// The comparison's progress: steps ended since the trial and the cost of
/// the first one measured.
#[derive(Debug, Default, Clone, Copy, PartialEq)]
pub(crate) struct Comparison {
    /// The id of the system whose topology compares.
    system: u64,
    /// Steps ended since the trial (the trial's own is not measured).
    steps: usize,
    /// The wall time per second simulated of the first measured step.
    first: f64,
}

impl Comparison {
    /// Ends a step of `dt` that took `elapsed` of wall time with
    /// `topology`'s solver: nothing while the topology compares no
    /// candidates; otherwise the trial's own step passes, the next one's
    /// cost is kept and the runner-up takes over, and after the one
    /// following it the faster of the two is kept.
    pub(crate) fn step_ended(
        &mut self,
        topology: Option<&mut Topology>,
        elapsed: Duration,
        dt: f64,
    ) {
        let Some(topology) = topology.filter(|t| t.comparing()) else {
            *self = Self::default();
            return;
        };
        if topology.system() != self.system {
            *self = Self {
                system: topology.system(),
                ..Self::default()
            };
        }
        let cost = elapsed.as_secs_f64() / dt;
        self.steps += 1;
        match self.steps {
            1 => {}
            2 => {
                self.first = cost;
                topology.swap_candidates();
            }
            _ => {
                if cost > self.first {
                    topology.swap_candidates();
                }
                topology.settle();
                *self = Self::default();
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use hooke_core::reference::Sheet;

    use super::*;
    use crate::linear::cg::PcgSettings;
    use crate::linear::pattern::Pattern;
    use crate::linear::solver::topology::topology;
    use crate::linear::solver::{AmgRenewal, LinearSolver};

    /// The trial's own step is not measured, the next one runs the trial's
    /// choice (here the factorization), the one after the runner-up
    /// (block-Jacobi PCG), and the faster per second simulated serves the
    /// rest of the run, the other's factor dropped. The second case's step
    /// is twice as long: slower in wall time, faster per second simulated.
    #[test]
    fn auto_keeps_the_candidate_faster_per_second_simulated_on_whole_steps() {
        let system = Sheet::new(12).system().unwrap();
        let jacobi = LinearSolver::Pcg(PcgSettings::default());
        let cholesky = LinearSolver::Cholesky;
        let ms = |t: f64| Duration::from_secs_f64(1e-3 * t);
        for ((elapsed, dt), kept) in [((20.0, 0.01), cholesky), ((15.0, 0.02), jacobi)] {
            let mut cached = None;
            let pattern = std::sync::Arc::new(Pattern::new(&system).unwrap());
            let topology = topology(
                &mut cached,
                Some(cholesky),
                (AmgRenewal::default(), Default::default()),
                (&system, &pattern),
            )
            .unwrap();
            topology.compare_with(jacobi);
            let mut comparison = Comparison::default();
            comparison.step_ended(Some(topology), ms(50.0), 0.01);
            assert_eq!(topology.choice().0, cholesky);
            comparison.step_ended(Some(topology), ms(10.0), 0.01);
            assert_eq!(topology.choice(), (jacobi, true, true));
            comparison.step_ended(Some(topology), ms(elapsed), dt);
            let cholesky_kept = kept == cholesky;
            assert_eq!(topology.choice(), (kept, !cholesky_kept, cholesky_kept));
            assert!(!topology.comparing());
            comparison.step_ended(Some(topology), ms(1000.0), 0.01);
            assert_eq!(topology.choice().0, kept);
        }
    }
}
