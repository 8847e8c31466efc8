//! The per-particle buffers of [`Implicit`](crate::Implicit)'s steps.

use hooke_core::Vec3;

use crate::linear::cg::PcgWorkspace;

/// Per-particle buffers, kept so that a step does not allocate.
#[derive(Debug, Default)]
pub(crate) struct Work {
    pub(crate) b: Vec<Vec3>,
    /// The linearised step's `Δv`, kept as the next step's warm start.
    pub(crate) dv: Vec<Vec3>,
    /// A Newton correction.
    pub(crate) delta: Vec<Vec3>,
    pub(crate) v: Vec<Vec3>,
    pub(crate) x: Vec<Vec3>,
    pub(crate) trial: Vec<Vec3>,
    /// The watchdog's look-ahead step and the point it reaches.
    pub(crate) ahead: Vec<Vec3>,
    pub(crate) look: Vec<Vec3>,
    pub(crate) x_tilde: Vec<Vec3>,
    pub(crate) v_tilde: Vec<Vec3>,
    pub(crate) u: Vec<Vec3>,
    /// BDF2's `xₙ₋₁`, `vₙ₋₁`, and `xₙ₋₂` for the error estimates.
    pub(crate) x_prev: Vec<Vec3>,
    pub(crate) v_prev: Vec<Vec3>,
    pub(crate) x_earlier: Vec<Vec3>,
    /// The state at the start of the caller's step, restored on an error.
    pub(crate) x_start: Vec<Vec3>,
    pub(crate) v_start: Vec<Vec3>,
    pub(crate) pcg: PcgWorkspace,
}
