//! Friction as a lagged dissipation potential (Li et al., *Incremental
//! Potential Contact*, 2020, §5).
//!
//! A contact's relative velocity is a weighted sum of its particles'
//! velocities less the obstacle's, `u = Σₖ wₖ v_{pₖ} − u_o` (one particle
//! of weight 1 against an obstacle; a point and a triangle's corners, or two
//! edges' ends, against each other). Its tangential part in the contact
//! plane, `s = Tᵀu ∈ ℝ²`, is braked by the force of Coulomb's law with
//! sticking smoothed below the speed `ε`:
//!
//! ```text
//! F = −μλ f₁(|s|) T s/|s|,   f₁(s) = 2s/ε − s²/ε² (s < ε),  1 (s ≥ ε),
//! ```
//!
//! minus the gradient of the convex dissipation potential
//! `D(v) = μλ f₀(|s|)` with `f₀' = f₁`:
//! `f₀(s) = s²/ε − s³/(3ε²) + ε/3` below `ε`, `s` above. The normal force
//! `λ` and the basis `T` are lagged: taken at the start of the step, so
//! that `D` is a fixed, convex term of the step's incremental potential and
//! Newton's method converges on it. Its Hessian in `s`,
//!
//! ```text
//! μλ [f₁'(|s|) ŝŝᵀ + f₁(|s|)/|s| (I − ŝŝᵀ)],
//! ```
//!
//! is positive semidefinite (`f₁' ≥ 0`), tends to `2μλ/ε I` at `s = 0`,
//! and enters the step's matrix as the blocks `wₖ wₗ T H Tᵀ`.
//!
//! **The majorizing model.** Along a sliding contact's direction `ŝ` that
//! Hessian is zero (`f₁' = 0` above `ε`): Newton's model takes the friction
//! force as constant there, so a step that should bring the contact to
//! rest carries it through `s = 0` to slide the other way, where the force
//! has turned, and the next step carries it back. With many contacts
//! reversing at once — a soft body landing, its underside spreading and
//! stopping under a normal force many times its weight — one step length
//! for them all has to be halved until each lands within `ε` of rest, and
//! Newton crawls. [`FrictionModel::Majorizing`] replaces `f₁'` by `f₁/|s|`,
//! the Hessian `μλ f₁(|s|)/|s| I`. As `f₀(√t)` is concave in `t = |s|²`
//! (`f₁(s)/s` falls with `s`), the quadratic with that Hessian lies above
//! `D` everywhere and touches it at `s` — the lagged-diffusivity (Weiszfeld)
//! model of a norm — so a full step never overshoots the friction's
//! minimum. It is slower where a contact slides on slowly (its curvature
//! `μλ/|s|` holds it back), so Newton's step starts each step with the
//! exact Hessian and turns to this one when the exact model fails.

use hooke_core::{Mat3, Vec3};
use nalgebra::{Matrix2, Vector2};

use crate::linear::matrix::HessianBlocks;
use hooke_core::SymBlock;

/// The friction's Hessian in Newton's model of `Φ`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum FrictionModel {
    /// The exact Hessian, `μλ [f₁'(|s|) ŝŝᵀ + f₁(|s|)/|s| (I − ŝŝᵀ)]`.
    #[default]
    Exact,
    /// `μλ f₁(|s|)/|s| I`, whose quadratic lies above `D` (see the module
    /// docs).
    Majorizing,
}

impl FrictionModel {
    /// `f₁(|s|)/|s|` (the gradient of `f₀(|s|)` is that times `s`) and this
    /// model's Hessian of `f₀(|s|)` in `s`.
    fn hessian(self, s: Vector2<f64>, eps: f64) -> (f64, Matrix2<f64>) {
        let speed = s.norm();
        let (ratio, slope) = slopes(speed, eps);
        let along = match self {
            Self::Exact => slope,
            Self::Majorizing => ratio,
        };
        let unit = if speed > 0.0 {
            s / speed
        } else {
            Vector2::zeros()
        };
        let outer = unit * unit.transpose();
        (ratio, along * outer + ratio * (Matrix2::identity() - outer))
    }
}

/// `f₀(s)`: the dissipation potential per unit bound.
fn f0(s: f64, eps: f64) -> f64 {
    if s >= eps {
        s
    } else {
        s * s / eps - s * s * s / (3.0 * eps * eps) + eps / 3.0
    }
}

/// `f₁(s)/s` and `f₁'(s)`, finite at `s = 0`.
fn slopes(s: f64, eps: f64) -> (f64, f64) {
    if s >= eps {
        (1.0 / s, 0.0)
    } else {
        (
            2.0 / eps - s / (eps * eps),
            2.0 / eps - 2.0 * s / (eps * eps),
        )
    }
}

/// One contact's friction, lagged at the start of the step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Lagged {
    /// The particles of the contact (`count` of them).
    pub(crate) particles: [u32; 4],
    /// Their weights `wₖ` in the relative velocity.
    pub(crate) weights: [f64; 4],
    pub(crate) count: usize,
    /// The tangent basis `T` (two orthonormal vectors normal to the contact
    /// normal).
    pub(crate) basis: [Vec3; 2],
    /// The obstacle's velocity `u_o` (zero between particles).
    pub(crate) velocity: Vec3,
    /// The bound `μλ`, N.
    pub(crate) bound: f64,
}

impl Lagged {
    /// A contact along `normal` (unit) with the given particles and weights.
    pub(crate) fn new(
        particles: &[usize],
        weights: &[f64],
        normal: Vec3,
        velocity: Vec3,
        bound: f64,
    ) -> Self {
        let mut p = [0; 4];
        let mut w = [0.0; 4];
        for (k, (&i, &wk)) in particles.iter().zip(weights).enumerate() {
            p[k] = i as u32;
            w[k] = wk;
        }
        Self {
            particles: p,
            weights: w,
            count: particles.len(),
            basis: tangent_basis(normal),
            velocity,
            bound,
        }
    }

    /// The tangential relative velocity `s = Tᵀ(Σ wₖ v_{pₖ} − u_o)`.
    fn tangential(&self, v: &[Vec3]) -> Vector2<f64> {
        let mut u = -self.velocity;
        for k in 0..self.count {
            u += self.weights[k] * v[self.particles[k] as usize];
        }
        Vector2::new(self.basis[0].dot(&u), self.basis[1].dot(&u))
    }

    /// `D(v) = μλ f₀(|s|)`.
    pub(crate) fn value(&self, v: &[Vec3], eps: f64) -> f64 {
        self.bound * f0(self.tangential(v).norm(), eps)
    }

    /// The friction force `−μλ f₁(|s|) T ŝ` at `v` (on a particle of weight
    /// 1).
    pub(crate) fn force(&self, v: &[Vec3], eps: f64) -> Vec3 {
        let s = self.tangential(v);
        let (ratio, _) = slopes(s.norm(), eps);
        -self.bound * ratio * (self.basis[0] * s.x + self.basis[1] * s.y)
    }

    /// Adds `scale · D` at `v` to a Newton system `A δ = −∇Φ`: subtracts
    /// `scale ∇D` from `b` and adds `scale` times `model`'s Hessian of `D`
    /// to `a` (see [`HessianBlocks`]).
    pub(crate) fn add(
        &self,
        v: &[Vec3],
        (eps, model): (f64, FrictionModel),
        scale: f64,
        b: &mut [Vec3],
        a: &mut impl HessianBlocks,
    ) {
        let s = self.tangential(v);
        let (ratio, hessian) = model.hessian(s, eps);
        let hessian = self.bound * hessian;
        let t = Mat3::from_columns(&[self.basis[0], self.basis[1], Vec3::zeros()]);
        let gradient = self.bound * ratio * (self.basis[0] * s.x + self.basis[1] * s.y);
        let mut h2 = Mat3::zeros();
        h2.fixed_view_mut::<2, 2>(0, 0).copy_from(&hessian);
        let block = t * h2 * t.transpose();
        for k in 0..self.count {
            let (pk, wk) = (self.particles[k] as usize, self.weights[k]);
            b[pk] -= scale * wk * gradient;
            a.add_row(pk, SymBlock::symmetric_part(&(scale * wk * wk * block)));
            for l in k + 1..self.count {
                let pl = self.particles[l] as usize;
                a.add_pair(pk, pl, scale * wk * self.weights[l] * block);
            }
        }
    }
}

/// Two orthonormal vectors normal to the unit vector `n`.
pub(crate) fn tangent_basis(n: Vec3) -> [Vec3; 2] {
    let helper = if n.x.abs() < 0.9 {
        Vec3::x()
    } else {
        Vec3::y()
    };
    let t0 = n.cross(&helper).normalize();
    [t0, n.cross(&t0)]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_dissipation_potential_is_smooth_and_its_slope_is_coulombs_law() {
        let eps = 1e-3;
        for s in [1e-5, 3e-4, 9.99e-4, 1e-3, 2e-3, 1.0] {
            let h = 1e-9;
            let derivative = (f0(s + h, eps) - f0(s - h, eps)) / (2.0 * h);
            let (ratio, slope) = slopes(s, eps);
            assert!((derivative - ratio * s).abs() < 1e-6, "f₀' at {s}");
            let second =
                (slopes(s + h, eps).0 * (s + h) - slopes(s - h, eps).0 * (s - h)) / (2.0 * h);
            assert!((second - slope).abs() < 1e-3 / eps, "f₁' at {s}");
        }
        assert!((f0(eps, eps) - eps).abs() < 1e-18);
    }

    /// `D` and the quadratic model of a friction Hessian around `s₀`:
    /// `q(s) = D(s₀) + ∇D(s₀)·(s − s₀) + ½ (s − s₀)ᵀ H (s − s₀)`.
    fn model_gap(s0: Vector2<f64>, s: Vector2<f64>, eps: f64, model: FrictionModel) -> f64 {
        let (ratio, hessian) = model.hessian(s0, eps);
        let d = s - s0;
        let q = f0(s0.norm(), eps) + (ratio * s0).dot(&d) + 0.5 * d.dot(&(hessian * d));
        q - f0(s.norm(), eps)
    }

    /// The majorizing model lies above `D` everywhere and touches it at
    /// `s₀`, sliding or sticking; the exact one falls below `D` where a
    /// sliding contact's step carries it through rest.
    #[test]
    fn the_majorizing_model_lies_above_the_dissipation_potential() {
        let eps = 1e-3;
        let mut seed = 12_345_u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for scale in [0.3 * eps, 3.0 * eps, 300.0 * eps] {
            for _ in 0..200 {
                let s0 = scale * Vector2::new(next(), next());
                assert!(model_gap(s0, s0, eps, FrictionModel::Majorizing).abs() < 1e-15);
                for spread in [0.1 * eps, eps, 10.0 * eps, 1000.0 * eps] {
                    let s = s0 + spread * Vector2::new(next(), next());
                    let gap = model_gap(s0, s, eps, FrictionModel::Majorizing);
                    assert!(gap >= -1e-15, "q − D = {gap} at s₀ = {s0:?}, s = {s:?}");
                }
            }
        }
        let s0 = Vector2::new(10.0 * eps, 0.0);
        assert!(model_gap(s0, -s0, eps, FrictionModel::Exact) < -eps);
    }
}
