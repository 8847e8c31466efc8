//! What every minimiser minimises: the incremental potential `Φ(v)` of one
//! implicit (sub)step ([`Objective`]) over the new velocities `v`, at the
//! positions `x = x̃ + βh v` of the scheme's predictor, through the list of
//! terms; with the Newton decrement that the stopping rule measures and
//! the longest step along a direction that contact allows.
//! [`Implicit`](crate::Implicit)'s docs give the equations.

use hooke_core::{At, CompressedSprings, Potential, System, Vec3};

use crate::linear::vector::for_each_row;
use crate::minimize::bounds::Bounds;
use crate::minimize::terms::Terms;

/// `Φ` of one (sub)step: the system and its terms, the predictor
/// `x = x̃ + βh v` and `ṽ`, how compressed springs enter `Φ`'s Hessian, and
/// scratch for positions and for a motion.
pub(crate) struct Objective<'a> {
    pub(crate) system: &'a System,
    pub(crate) terms: &'a mut Terms,
    pub(crate) x_tilde: &'a [Vec3],
    pub(crate) v_tilde: &'a [Vec3],
    pub(crate) beta_h: f64,
    /// How compressed springs' stiffness blocks enter a Hessian, the
    /// integrator's setting, which every point evaluated carries.
    pub(crate) compressed: CompressedSprings,
    /// Scratch for the positions `x̃ + βh v` of the point last evaluated.
    pub(crate) x: &'a mut [Vec3],
    /// Scratch for the motion `βh α δ` that collision detection checks.
    pub(crate) motion: &'a mut [Vec3],
    /// How contact bounds each motion, and what the bounds did.
    pub(crate) bounds: Bounds,
}

impl Objective<'_> {
    /// Fills the position scratch with `x = x̃ + βh v`.
    pub(crate) fn positions(&mut self, v: &[Vec3]) {
        let (x_tilde, beta_h) = (self.x_tilde, self.beta_h);
        for_each_row(self.x, |i, x| *x = x_tilde[i] + beta_h * v[i]);
    }

    /// `Φ(v)` and its magnitude, infinite where a barrier's gap is not
    /// positive ([`Terms::value`]).
    pub(crate) fn value(&mut self, v: &[Vec3]) -> Potential {
        self.positions(v);
        let at = iterate(self.x, v, (self.v_tilde, self.beta_h), self.compressed);
        self.terms.value(self.system, &at)
    }

    /// `Φ(v)`, as [`Objective::value`], and `b = −∇Φ(v)` without the
    /// barriers' terms from the same passes ([`Terms::gradient`]).
    pub(crate) fn gradient(&mut self, v: &[Vec3], b: &mut [Vec3]) -> Potential {
        self.positions(v);
        let at = iterate(self.x, v, (self.v_tilde, self.beta_h), self.compressed);
        self.terms.gradient(self.system, &at, b)
    }

    /// The Newton decrement `λ = √|∇Φ·δ|` relative to the step's velocity
    /// scale in the mass norm `‖u‖_M = √(Σ mᵢ|uᵢ|²)`,
    ///
    /// ```text
    /// λ / max(‖v + δ − v₀‖_M, ‖v + δ‖_M, βh‖g‖ √(Σ mᵢ)),
    /// ```
    ///
    /// the last term the velocity gravity gives in one step, so that a body
    /// at rest has a scale too.
    ///
    /// zero for `δ = 0`. As `λ² = δᵀ A δ ≥ ‖δ‖²_M`, it bounds the relative
    /// error of the velocities in the mass norm, and `λ²/2` estimates how
    /// far `Φ` is above its minimum.
    pub(crate) fn decrement(&self, slope: f64, v: &[Vec3], delta: &[Vec3], v0: &[Vec3]) -> f64 {
        if slope == 0.0 {
            return 0.0;
        }
        let next = v.iter().zip(delta).map(|(v, d)| v + d);
        slope.abs().sqrt() / velocity_scale(self.system, next, v0, self.beta_h)
    }

    /// The longest multiple `α ≤ longest` of the step `δ` from `v` that
    /// the barriers allow: `longest` without barriers, otherwise
    /// `longest · τ` with `τ` the fraction of the motion `βh longest δ` that
    /// keeps every contact pair at a tenth of its gap ([`Terms::limit`]).
    pub(crate) fn limit(&mut self, v: &[Vec3], delta: &[Vec3], longest: f64) -> f64 {
        if !self.terms.has_barrier() {
            return longest;
        }
        self.positions(v);
        let scale = self.beta_h * longest;
        for_each_row(self.motion, |i, m| *m = scale * delta[i]);
        longest * self.terms.limit(self.system, self.x, self.motion)
    }
}

/// The iterate `v` at its positions `x = x̃ + βh v` for the predictor's `ṽ`
/// and `βh`, with the Hessians `compressed` says.
pub(crate) fn iterate<'a>(
    x: &'a [Vec3],
    v: &'a [Vec3],
    (v_tilde, beta_h): (&'a [Vec3], f64),
    compressed: CompressedSprings,
) -> At<'a> {
    At {
        x,
        v,
        v_tilde,
        beta_h,
        displacement: None,
        compressed,
    }
}

/// The step's velocity scale that the stopping rule measures the Newton
/// decrement against, `max(‖v − v₀‖_M, ‖v‖_M, βh‖g‖ √(Σ mᵢ))` for the
/// velocities `v` ([`Objective::decrement`]).
pub(crate) fn velocity_scale(
    system: &System,
    v: impl Iterator<Item = Vec3>,
    v0: &[Vec3],
    beta_h: f64,
) -> f64 {
    let masses = system.masses();
    let (mut change, mut speed, mut total) = (0.0, 0.0, 0.0);
    for (i, (v, v0)) in v.zip(v0).enumerate() {
        change += masses[i] * (v - v0).norm_squared();
        speed += masses[i] * v.norm_squared();
        total += masses[i];
    }
    let gravity = system.gravity().map_or(0.0, |g| g.norm());
    change
        .max(speed)
        .max(total * (beta_h * gravity).powi(2))
        .sqrt()
}
