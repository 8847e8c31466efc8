//! Where a [`Term`](super::Term) is evaluated: a point of a step's
//! minimisation ([`At`]) and the start of the step ([`StepStart`]).

use crate::{CompressedSprings, Vec3};

/// A point at which a step evaluates its incremental potential `Φ`: the
/// velocities `v`, the positions `x` they give, the predictor's `ṽ`, `βh`,
/// and what a linearisation needs.
///
/// At an iterate of the minimisation `x = x̃ + βh v`. Baraff & Witkin's
/// linearised step evaluates instead at the step's start `(X, V) = (xₙ,
/// vₙ)` with the `displacement` `u = x̃ + βh V − X` (for backward Euler
/// `u = h vₙ`), whose stiffness term `−βh K u` joins the right-hand side.
#[derive(Debug, Clone, Copy)]
pub struct At<'a> {
    /// Positions `x`, m.
    pub x: &'a [Vec3],
    /// Velocities `v`, m/s.
    pub v: &'a [Vec3],
    /// The predictor's velocities `ṽ`, m/s.
    pub v_tilde: &'a [Vec3],
    /// `βh`, s: `β = 1` for backward Euler, `2/3` for BDF2 at a constant
    /// step.
    pub beta_h: f64,
    /// The displacement `u` of a linearisation away from `x = x̃ + βh v`,
    /// or `None` at an iterate.
    pub displacement: Option<&'a [Vec3]>,
    /// Which Hessians to write: with [`CompressedSprings::Exact`] each
    /// term's exact Hessian, with [`CompressedSprings::Clamped`] its
    /// positive-semidefinite stand-in (compressed springs clamped, volume
    /// elements projected onto their positive part, or their Gauss–Newton
    /// Hessian for the linearised step).
    pub compressed: CompressedSprings,
}

/// The start of an implicit (sub)step, which [`Term::begin`](super::Term::begin)
/// receives: what a term lags over the step (the dampers' directions,
/// contact normals and friction, a wind's triangle normals) is taken here.
#[derive(Debug, Clone, Copy)]
pub struct StepStart<'a> {
    /// Positions `xₙ` at the step's start, m.
    pub x: &'a [Vec3],
    /// Velocities `vₙ` at the step's start, m/s.
    pub v: &'a [Vec3],
    /// The time `tₙ` at the step's start, s.
    pub time: f64,
    /// The step's length `h`, s.
    pub h: f64,
    /// `βh`, s.
    pub beta_h: f64,
}

/// Which end of a step an energy is taken at
/// ([`Term::energy`](super::Term::energy)): the obstacles' and scripted
/// pins' places differ.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum When {
    /// The state the step started from, at [`StepStart::time`].
    Start,
    /// A state at the step's end; also any state outside a step.
    End,
}
