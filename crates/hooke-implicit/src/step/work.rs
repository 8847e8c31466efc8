//! The per-particle buffers of [`Implicit`](crate::Implicit)'s steps.

use hooke_core::{StepStart, Vec3};

use crate::linear::cg::PcgWorkspace;
use crate::minimize::line_search::Iterates;
use crate::step::predictor::{Coefficients, Predictor};

/// Per-particle buffers, kept so that a step does not allocate.
#[derive(Debug, Default)]
pub(crate) struct Work {
    /// The scheme's predictor and the linearised solve's displacement.
    pub(crate) predictor: Predictor,
    /// The minimisation's iterate, step, trial and look-ahead points.
    pub(crate) iterates: Iterates,
    /// A right-hand side `−∇Φ`.
    pub(crate) b: Vec<Vec3>,
    /// The linearised step's `Δv`, kept as the next step's warm start.
    pub(crate) dv: Vec<Vec3>,
    /// Positions `x̃ + βh v`: scratch while minimising, then the step's end.
    pub(crate) x: Vec<Vec3>,
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
    /// Predicts the (sub)step from `step` with coefficients `c` after the
    /// one recorded, if `continues` (the linearised step's warm start
    /// starts at zero otherwise).
    pub(crate) fn predict(&mut self, step: &StepStart<'_>, c: Coefficients, continues: bool) {
        self.predictor
            .predict(step, c, [&self.x_prev, &self.v_prev]);
        if !continues {
            self.dv.fill(Vec3::zeros());
        }
    }

    /// Sizes every buffer for `n` particles (a no-op once sized).
    pub(crate) fn resize(&mut self, n: usize) {
        let Predictor {
            x_tilde,
            v_tilde,
            u,
        } = &mut self.predictor;
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
            x_tilde,
            v_tilde,
            u,
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
