//! How [`LinearSolver::Amg`](super::LinearSolver::Amg) renews its
//! multigrid hierarchy from one solve to the next.

use crate::linear::amg::Amg;

/// How [`LinearSolver::Amg`](super::LinearSolver::Amg) renews its hierarchy from one solve to the
/// next ([`Implicit::with_amg_renewal`](crate::Implicit::with_amg_renewal)).
/// Its baseline is the iteration count of the first solve after the last
/// build.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub enum AmgRenewal {
    /// Every solve refreshes every level's values ([`Amg::refresh`]: the
    /// block inverses, the smoothers' intervals and the Galerkin coarse
    /// operators), and a solve that took more than twice the baseline has
    /// the next rebuild the hierarchy ([`Amg::build`]). The default: on a
    /// 200² cloth the refresh costs about four PCG iterations (21 ms), and
    /// it keeps the coarse operators those of the matrix being solved.
    #[default]
    EverySolve,
    /// Every solve refreshes only the finest level's smoother
    /// ([`Amg::refresh_smoother`]); a solve that took more than 1.5 times
    /// the baseline has the next refresh every level's values, and one that
    /// took more than twice it right after such a refresh has the next
    /// rebuild. Cheaper per solve, but coarse operators one step old cost
    /// a falling 200² cloth 2–8 times the iterations of fresh ones.
    SmootherOnly,
}

impl hooke_core::Named for AmgRenewal {
    /// `"every-solve"` and `"smoother-only"`, as scene files
    /// (`amg_renewal`) and reports spell them.
    const TABLE: &'static [(Self, &'static str)] = &[
        (Self::EverySolve, "every-solve"),
        (Self::SmootherOnly, "smoother-only"),
    ];
}

impl AmgRenewal {
    /// The renewal of a solve that renews no more than the policy asks.
    fn routine(self) -> Renewal {
        match self {
            Self::EverySolve => Renewal::Values,
            Self::SmootherOnly => Renewal::Smoother,
        }
    }
}

/// The multigrid hierarchy of [`LinearSolver::Amg`](super::LinearSolver::Amg) and how much of it the
/// next solve renews.
#[derive(Debug)]
pub(crate) struct AmgState {
    pub(crate) amg: Option<Amg>,
    policy: AmgRenewal,
    /// Iterations of the first solve after the last build (0: none yet).
    baseline: usize,
    pub(crate) next: Renewal,
}

/// How much of the hierarchy a solve renews.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Renewal {
    /// The finest level's smoother ([`Amg::refresh_smoother`]).
    Smoother,
    /// Every level's values ([`Amg::refresh`]).
    Values,
    /// Everything ([`Amg::build`]).
    Hierarchy,
}

impl AmgState {
    pub(crate) fn new(policy: AmgRenewal) -> Self {
        Self {
            amg: None,
            policy,
            baseline: 0,
            next: policy.routine(),
        }
    }

    /// Drops the hierarchy and its history.
    pub(crate) fn clear(&mut self) {
        *self = Self::new(self.policy);
    }

    /// The renewal after a solve of `iterations` that followed `renewal`
    /// (see [`AmgRenewal`]).
    pub(crate) fn after(&mut self, renewal: Renewal, iterations: usize) {
        let routine = self.policy.routine();
        self.next = if renewal == Renewal::Hierarchy || self.baseline == 0 {
            self.baseline = iterations.max(1);
            routine
        } else if renewal == Renewal::Values && iterations > 2 * self.baseline {
            Renewal::Hierarchy
        } else if 2 * iterations > 3 * self.baseline {
            Renewal::Values
        } else {
            routine
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The renewals each policy asks after a sequence of solves (their
    /// iteration counts), from a hierarchy just built whose first solve
    /// took 20: [`AmgRenewal::EverySolve`] refreshes every level until a
    /// solve takes more than 40, then rebuilds and takes its next solve as
    /// the baseline; [`AmgRenewal::SmootherOnly`] refreshes the smoother
    /// until a solve takes more than 30, then every level, and rebuilds
    /// only when a solve right after that takes more than 40.
    #[test]
    fn multigrid_renews_what_its_policy_asks_after_each_solve() {
        use Renewal::{Hierarchy, Smoother, Values};
        let cases = [
            (
                AmgRenewal::EverySolve,
                vec![
                    (20, Values),
                    (35, Values),
                    (41, Hierarchy),
                    (30, Values),
                    (61, Hierarchy),
                ],
            ),
            (
                AmgRenewal::SmootherOnly,
                vec![
                    (20, Smoother),
                    (30, Smoother),
                    (31, Values),
                    (35, Values),
                    (41, Hierarchy),
                    (30, Smoother),
                    (46, Values),
                ],
            ),
        ];
        for (policy, solves) in cases {
            let mut state = AmgState::new(policy);
            let mut renewal = Hierarchy;
            for (iterations, expected) in solves {
                state.after(renewal, iterations);
                assert_eq!(state.next, expected, "{policy:?} after {iterations}");
                renewal = state.next;
            }
        }
    }
}
