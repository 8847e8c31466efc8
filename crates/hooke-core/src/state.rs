//! [`State`]: positions, velocities and time — the only thing a step changes —
//! and [`History`], which lets a multistep integrator tell whether the state
//! it is handed is the one it left.

use std::sync::atomic::{AtomicU64, Ordering};

use crate::error::{Quantity, StepError};
use crate::{System, Vec3};

static NEXT_STATE_ID: AtomicU64 = AtomicU64::new(1);

fn fresh_id() -> u64 {
    NEXT_STATE_ID.fetch_add(1, Ordering::Relaxed)
}

/// Positions `x`, velocities `v` and time `t` of every particle of a
/// [`System`]. Create one with [`System::initial_state`].
///
/// Every mutable access bumps an internal version, so an integrator that
/// keeps history between steps (leapfrog, Beeman, Gear, ...) notices when the
/// state was changed behind its back and restarts itself.
#[derive(Debug)]
pub struct State {
    positions: Vec<Vec3>,
    velocities: Vec<Vec3>,
    time: f64,
    /// Per particle: whether the last step's contact response touched it.
    touching: Vec<bool>,
    id: u64,
    version: u64,
}

impl Clone for State {
    /// A copy with a new identity: integrator history does not carry over to
    /// it.
    fn clone(&self) -> Self {
        Self {
            positions: self.positions.clone(),
            velocities: self.velocities.clone(),
            time: self.time,
            touching: self.touching.clone(),
            id: fresh_id(),
            version: 0,
        }
    }
}

impl State {
    pub(crate) fn new(positions: Vec<Vec3>, velocities: Vec<Vec3>) -> Self {
        Self {
            touching: vec![false; positions.len()],
            positions,
            velocities,
            time: 0.0,
            id: fresh_id(),
            version: 0,
        }
    }

    /// Number of particles.
    #[must_use]
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    /// Whether the state has no particles.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }

    /// Positions `x`, one per particle.
    #[must_use]
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// Velocities `v`, one per particle.
    #[must_use]
    pub fn velocities(&self) -> &[Vec3] {
        &self.velocities
    }

    /// Simulated time `t` in seconds.
    #[must_use]
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Mutable positions. Integrators with history restart on the next step.
    pub fn positions_mut(&mut self) -> &mut [Vec3] {
        self.version += 1;
        &mut self.positions
    }

    /// Mutable velocities. Integrators with history restart on the next step.
    pub fn velocities_mut(&mut self) -> &mut [Vec3] {
        self.version += 1;
        &mut self.velocities
    }

    /// Per particle: whether the contact response at the end of the last
    /// step pushed it out of an obstacle. Restitution applies only to
    /// particles that were not touching: a particle resting on an obstacle,
    /// or pressed into it by the body it belongs to, does not bounce.
    #[must_use]
    pub fn touching(&self) -> &[bool] {
        &self.touching
    }

    /// The contact flags, without invalidating the history of integrators.
    pub(crate) fn touching_mut(&mut self) -> &mut [bool] {
        &mut self.touching
    }

    /// Positions, velocities and contact flags for the contact response.
    pub(crate) fn contact_mut(&mut self) -> (&mut [Vec3], &mut [Vec3], &mut [bool]) {
        self.version += 1;
        (
            &mut self.positions,
            &mut self.velocities,
            &mut self.touching,
        )
    }

    /// Positions and velocities for placing pinned particles, which does not
    /// invalidate the history of integrators.
    pub(crate) fn pins_mut(&mut self) -> (&mut [Vec3], &mut [Vec3]) {
        (&mut self.positions, &mut self.velocities)
    }

    /// Sets the time. Integrators with history restart on the next step.
    pub fn set_time(&mut self, time: f64) {
        self.version += 1;
        self.time = time;
    }

    /// Installs the result of a step: checks that every new position and
    /// velocity is finite, then swaps them in (no copy, no allocation) and
    /// sets the time. On a non-finite value the state is left untouched and
    /// the error names the particle; the buffers then hold the rejected step.
    ///
    /// This is how integrators finish a step; the swapped-out buffers hold the
    /// previous step's values afterwards.
    ///
    /// # Errors
    /// [`StepError::NonFinite`] at `time`, naming the first bad particle.
    pub fn commit(
        &mut self,
        positions: &mut Vec<Vec3>,
        velocities: &mut Vec<Vec3>,
        time: f64,
    ) -> Result<(), StepError> {
        debug_assert_eq!(positions.len(), self.positions.len());
        debug_assert_eq!(velocities.len(), self.velocities.len());
        for (quantity, values) in [
            (Quantity::Position, &*positions),
            (Quantity::Velocity, &*velocities),
        ] {
            if let Some(particle) = values.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
                return Err(StepError::NonFinite {
                    time,
                    particle,
                    quantity,
                });
            }
        }
        std::mem::swap(&mut self.positions, positions);
        std::mem::swap(&mut self.velocities, velocities);
        self.time = time;
        self.version += 1;
        Ok(())
    }
}

/// What a multistep integrator remembers about the step it last finished:
/// which system, which state, at which version, with which step size.
///
/// Cached accelerations, staggered velocities or a Nordsieck vector are only
/// valid for the exact state the integrator left; [`History::take`] says
/// whether that is the state it is handed now.
#[derive(Debug, Clone, Copy, Default)]
pub struct History {
    last: Option<Mark>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Mark {
    system: u64,
    state: u64,
    version: u64,
    dt_bits: u64,
}

impl History {
    /// At the start of a step: the previous step's size if `state` is exactly
    /// the state the previous step on `system` produced, `None` if the
    /// integrator must start afresh. Either way the history is forgotten
    /// until the step [records](History::record) its result, so a step that
    /// fails leaves none behind.
    pub fn take(&mut self, system: &System, state: &State) -> Option<f64> {
        let last = self.last.take()?;
        (last.system == system.id() && last.state == state.id && last.version == state.version)
            .then(|| f64::from_bits(last.dt_bits))
    }

    /// Whether the previous step on `system` produced `state` (what
    /// [`History::take`] would find), without forgetting it.
    #[must_use]
    pub fn continues(&self, system: &System, state: &State) -> bool {
        self.last.is_some_and(|last| {
            last.system == system.id() && last.state == state.id && last.version == state.version
        })
    }

    /// Like [`History::take`], for integrators whose history only holds for
    /// the same step size: whether the previous step produced `state` on
    /// `system` with size `dt` too.
    pub fn take_same_step(&mut self, system: &System, state: &State, dt: f64) -> bool {
        self.take(system, state)
            .is_some_and(|last| last.to_bits() == dt.to_bits())
    }

    /// Records that a step of size `dt` on `system` has just produced `state`.
    pub fn record(&mut self, system: &System, state: &State, dt: f64) {
        self.last = Some(Mark {
            system: system.id(),
            state: state.id,
            version: state.version,
            dt_bits: dt.to_bits(),
        });
    }
}
