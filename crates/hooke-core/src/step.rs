//! [`StepBuffers`]: what every step does around its own formula — check
//! the arguments, ask its [`History`] whether it continues, size its
//! buffers; then commit the new state, record the history and end the
//! step ([`System::end_step`]).

use crate::error::StepError;
use crate::{History, State, StepReport, System, Vec3, check_step};

/// The new positions and velocities a step computes, and the [`History`]
/// of the step before. An integrator keeps one and brackets its formula
/// with [`StepBuffers::begin`] and [`StepBuffers::finish`]:
///
/// ```
/// use hooke_core::{Integrator, State, StepBuffers, StepError, StepReport, System};
/// # use hooke_core::reference::Oscillator;
/// /// Moves every particle along its velocity, forces ignored.
/// #[derive(Default)]
/// struct Drift(StepBuffers);
/// impl Integrator for Drift {
///     fn step(&mut self, sys: &System, s: &mut State, dt: f64) -> Result<StepReport, StepError> {
///         self.0.begin("drift", sys, s, dt, [])?;
///         for (i, (x, v)) in s.positions().iter().zip(s.velocities()).enumerate() {
///             (self.0.x[i], self.0.v[i]) = (x + dt * v, *v);
///         }
///         self.0.finish(sys, s, dt, StepReport::fixed_step(0))
///     }
/// }
/// let system = Oscillator::undamped(1.0, 1.0).system()?;
/// let mut state = system.initial_state();
/// Drift::default().step(&system, &mut state, 0.5)?;
/// assert!((state.time() - 0.5).abs() < 1e-15);
/// assert!(Drift::default().step(&system, &mut state, -1.0).is_err());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Default)]
pub struct StepBuffers {
    /// The new positions `xₙ₊₁`, filled by the step; after
    /// [`StepBuffers::finish`] they hold the previous positions `xₙ` (the
    /// state's buffers are swapped in, not copied).
    pub x: Vec<Vec3>,
    /// The new velocities `vₙ₊₁`; after [`StepBuffers::finish`] the
    /// previous ones.
    pub v: Vec<Vec3>,
    history: History,
}

/// What [`StepBuffers::begin`] found about the step before.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Start {
    previous_dt: Option<f64>,
    dt: f64,
}

impl Start {
    /// The previous step's size if the state handed in is exactly the one
    /// the previous step on the same system produced (see [`History`]).
    #[must_use]
    pub fn previous_dt(self) -> Option<f64> {
        self.previous_dt
    }

    /// Whether the previous step produced this state, on this system, with
    /// this same step size: history that holds for one step size only is
    /// valid.
    #[must_use]
    pub fn continues_same_step(self) -> bool {
        self.previous_dt
            .is_some_and(|h| h.to_bits() == self.dt.to_bits())
    }
}

impl StepBuffers {
    /// Starts a step of `dt` from `state`: checks the arguments
    /// ([`check_step`]), takes the history (forgotten until
    /// [`StepBuffers::finish`] records the new one, so a failed step leaves
    /// none), checks that `integrator` (its name) can run the system — no
    /// surfaces collide ([`System::check_no_surface_contact`]) — and sizes [`Self::x`], [`Self::v`] and every buffer of
    /// `scratch` to the state's particle count (allocating only when one
    /// grows).
    ///
    /// # Errors
    /// [`StepError::InvalidTimestep`], [`StepError::StateMismatch`] or
    /// [`StepError::SurfaceContactUnsupported`]; the state is untouched.
    pub fn begin<'a>(
        &mut self,
        integrator: &'static str,
        system: &System,
        state: &State,
        dt: f64,
        scratch: impl IntoIterator<Item = &'a mut Vec<Vec3>>,
    ) -> Result<Start, StepError> {
        check_step(system, state, dt)?;
        system.check_no_surface_contact(integrator)?;
        let previous_dt = self.history.take(system, state);
        let n = state.len();
        self.x.resize(n, Vec3::zeros());
        self.v.resize(n, Vec3::zeros());
        for buffer in scratch {
            buffer.resize(n, Vec3::zeros());
        }
        Ok(Start { previous_dt, dt })
    }

    /// Ends a step of `dt`: commits [`Self::x`] and [`Self::v`] as the state
    /// at `t + dt` ([`State::commit`]), records the history, then places the
    /// scripted pins and resolves contacts ([`System::end_step`]), whose
    /// count goes into the returned `report`. A contact response changes the
    /// state after the history was recorded, so integrators with history
    /// restart after it.
    ///
    /// # Errors
    /// [`StepError::NonFinite`] naming the first bad particle; the state is
    /// untouched.
    pub fn finish(
        &mut self,
        system: &System,
        state: &mut State,
        dt: f64,
        report: StepReport,
    ) -> Result<StepReport, StepError> {
        state.commit(&mut self.x, &mut self.v, state.time() + dt)?;
        self.history.record(system, state, dt);
        Ok(StepReport {
            contacts: system.end_step(state),
            ..report
        })
    }
}
