//! [`Linearization`]: where and how a step's system is linearised.

use hooke_core::{CompressedSprings, Vec3};

/// Where and how to linearise.
#[derive(Debug, Clone, Copy)]
pub struct Linearization<'a> {
    /// Positions `X` at which forces and stiffness blocks are evaluated.
    pub positions: &'a [Vec3],
    /// Velocities `V` at which damping forces are evaluated.
    pub velocities: &'a [Vec3],
    /// The displacement `u` multiplied by the stiffness in the right-hand
    /// side, or `None` for zero.
    pub displacement: Option<&'a [Vec3]>,
    /// The inertia term `M(ṽ − V)` of the right-hand side.
    pub inertia: &'a [Vec3],
    /// `βh`.
    pub beta_h: f64,
    /// How compressed springs' stiffness blocks are treated, and with them
    /// the volume elements' Hessians: exact with
    /// [`CompressedSprings::Exact`], positive semidefinite stand-ins with
    /// [`CompressedSprings::Clamped`].
    pub compressed: CompressedSprings,
    /// Whether to take the damping directions from `positions` (the first
    /// linearisation of a step) or keep those of the previous call.
    pub freeze_directions: bool,
}

#[cfg(test)]
impl<'a> Linearization<'a> {
    /// Baraff & Witkin's linearised step of `h` from `state` without a
    /// predictor, for tests: the system at the state's positions and
    /// velocities, the displacement `h v` and no inertia term, compressed
    /// springs clamped; `work` holds the displacement and the zero inertia.
    pub(crate) fn step_from(
        state: &'a hooke_core::State,
        h: f64,
        work: &'a mut [Vec<Vec3>; 2],
    ) -> Self {
        let [u, inertia] = work;
        *u = state.velocities().iter().map(|v| h * v).collect();
        *inertia = vec![Vec3::zeros(); u.len()];
        Self {
            positions: state.positions(),
            velocities: state.velocities(),
            displacement: Some(u),
            inertia,
            beta_h: h,
            compressed: CompressedSprings::Clamped,
            freeze_directions: true,
        }
    }
}
