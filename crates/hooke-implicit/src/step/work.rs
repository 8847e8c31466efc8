//! The per-particle buffers of [`Implicit`](crate::Implicit)'s steps.

use hooke_core::Vec3;

use crate::linear::cg::PcgWorkspace;
use crate::minimize::line_search::Iterates;

/// Per-particle buffers, kept so that a step does not allocate.
#[derive(Debug, Default)]
pub(crate) struct Work {
    pub(crate) b: Vec<Vec3>,
    /// The linearised step's `Δv`, kept as the next step's warm start.
    pub(crate) dv: Vec<Vec3>,
    /// The minimisation's iterate, step, trial and look-ahead points.
    pub(crate) iterates: Iterates,
    pub(crate) x: Vec<Vec3>,
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

impl Work {
    /// Sizes every buffer for `n` particles (a no-op once sized).
    pub(crate) fn resize(&mut self, n: usize) {
        let Iterates {
            v,
            delta,
            trial,
            ahead,
            look,
        } = &mut self.iterates;
        for buffer in [
            &mut self.b,
            &mut self.dv,
            delta,
            v,
            &mut self.x,
            trial,
            ahead,
            look,
            &mut self.x_tilde,
            &mut self.v_tilde,
            &mut self.u,
            &mut self.x_prev,
            &mut self.v_prev,
            &mut self.x_earlier,
            &mut self.x_start,
            &mut self.v_start,
        ] {
            buffer.resize(n, Vec3::zeros());
        }
    }
}
