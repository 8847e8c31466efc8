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
