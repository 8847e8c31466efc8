//! [`VolumeRecord`]: the observer that measures, after every step, how
//! many of a run's volume elements are inverted, for its summary.

use std::ops::ControlFlow;

use hooke_core::{Inversion, Observer, State, StepInfo, System};

/// Measures the volume elements ([`System::inversion`]) in the initial
/// state and after every step: the most elements inverted at once (volume
/// ratio `J = V/V₀ ≤ 0`) and the smallest `J` reached. Both stay `None`
/// for a system without volume elements.
#[derive(Debug, Default)]
pub(crate) struct VolumeRecord {
    /// The most elements inverted in one state.
    pub(crate) inverted_max: Option<usize>,
    /// The smallest volume ratio of an element in any state.
    pub(crate) smallest_ratio: Option<f64>,
}

impl VolumeRecord {
    /// Measures the state of `system`.
    fn measure(&mut self, system: &System, state: &State) {
        let Some(Inversion {
            inverted,
            smallest_ratio,
        }) = system.inversion(state.positions())
        else {
            return;
        };
        self.inverted_max = Some(self.inverted_max.map_or(inverted, |n| n.max(inverted)));
        self.smallest_ratio = Some(
            self.smallest_ratio
                .map_or(smallest_ratio, |j| j.min(smallest_ratio)),
        );
    }
}

impl Observer for VolumeRecord {
    fn start(&mut self, system: &System, state: &State) {
        self.measure(system, state);
    }

    fn observe(&mut self, system: &System, state: &State, _step: &StepInfo) -> ControlFlow<()> {
        self.measure(system, state);
        ControlFlow::Continue(())
    }
}

#[cfg(test)]
mod tests {
    use hooke_core::{SystemBuilder, Vec3};

    use super::*;

    /// A unit tet whose apex moves from `y = 1` through the base by `depth`.
    #[test]
    fn the_most_inverted_and_the_smallest_ratio_over_the_states() {
        let mut b = SystemBuilder::new();
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 1.0, 0.0],
        ]
        .map(|x| b.particle(1.0, x));
        b.tet(p, 0.0);
        let system = b.build().unwrap();
        let mut state = system.initial_state();
        let mut record = VolumeRecord::default();
        record.start(&system, &state);
        assert_eq!(record.inverted_max, Some(0));
        assert!((record.smallest_ratio.unwrap() - 1.0).abs() < 1e-12);
        for y in [0.5, -0.5, 0.25] {
            state.positions_mut()[3] = Vec3::new(0.0, y, 0.0);
            let _ = record.observe(&system, &state, &StepInfo::default());
        }
        assert_eq!(record.inverted_max, Some(1));
        assert!((record.smallest_ratio.unwrap() + 0.5).abs() < 1e-12);
    }

    #[test]
    fn a_system_without_volume_elements_records_nothing() {
        let mut b = SystemBuilder::new();
        b.particle(1.0, [0.0; 3]);
        let system = b.build().unwrap();
        let mut record = VolumeRecord::default();
        record.start(&system, &system.initial_state());
        assert_eq!((record.inverted_max, record.smallest_ratio), (None, None));
    }
}
