//! A linear (Hookean) spring between two particles: energy, force, and the
//! 3x3 blocks of its Jacobians.
//!
//! With `l = |xᵢ − xⱼ|`, `d = (xᵢ − xⱼ)/l`, stiffness `k`, rest length `L` and
//! axial damping `c`:
//!
//! ```text
//! E   = ½ k (l − L)²
//! fᵢ  = −k (l − L) d − c ((vᵢ − vⱼ)·d) d          fⱼ = −fᵢ
//! H   = k [d dᵀ + (1 − L/l)(I − d dᵀ)]            ∂fᵢ/∂xᵢ = −H,  ∂fᵢ/∂xⱼ = H
//! D   = c d dᵀ                                    ∂fᵢ/∂vᵢ = −D,  ∂fᵢ/∂vⱼ = D
//! ```
//!
//! so a spring contributes `[[H, −H], [−H, H]]` to the stiffness matrix `−∂f/∂x`
//! and likewise `D` to the damping matrix `−∂f/∂v` (Baraff & Witkin, *Large
//! Steps in Cloth Simulation*, SIGGRAPH 1998, §4.2 and §5). As in that paper the
//! dependence of the damping force on the positions (through `d`) is left out
//! of the Jacobians.
//!
//! Under compression (`l < L`) the transverse factor `1 − L/l` is negative and
//! `H` is indefinite; [`CompressedSprings::Clamped`] (the default) clamps the
//! factor at zero so that `H` stays positive semi-definite and an implicit
//! system matrix stays positive definite (Choi & Ko, *Stable but Responsive
//! Cloth*, SIGGRAPH 2002). [`CompressedSprings::Exact`] keeps the true Jacobian.
//!
//! Degenerate geometry never produces NaN:
//! - a spring with `L = 0` is exactly linear, `f = −k (xᵢ − xⱼ)` and `H = k I`,
//!   including when its ends coincide;
//! - a spring with `L > 0` whose ends coincide has no direction: its energy
//!   `½ k L²` is a local maximum there, and its force and both blocks are zero.

use crate::{Mat3, Vec3};

/// How the stiffness block treats the transverse factor `1 − L/l` of a
/// compressed spring (`l < L`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CompressedSprings {
    /// Clamp `1 − L/l` at zero, keeping the block positive semi-definite. This
    /// is what implicit solvers want and the default.
    #[default]
    Clamped,
    /// The exact Jacobian of the force, indefinite under compression.
    Exact,
}

impl crate::Named for CompressedSprings {
    /// `"clamped"` and `"exact"`, as scene files (`compressed_springs`) and
    /// reports spell them.
    const TABLE: &'static [(Self, &'static str)] =
        &[(Self::Clamped, "clamped"), (Self::Exact, "exact")];
}

/// A spring's elastic force on its first end and its stiffness block in
/// factored form, `H = k_∥ d dᵀ + k_⊥ (I − d dᵀ)`: axial stiffness
/// `k_∥ = k`, transverse stiffness `k_⊥ = k (1 − L/l)` (clamped at zero
/// under compression by default).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Linearized {
    /// Elastic force on `i`, `−k (l − L) d`.
    pub force: Vec3,
    /// Unit direction `d` from `xⱼ` to `xᵢ` (zero where it is undefined and
    /// irrelevant).
    pub direction: Vec3,
    /// Stiffness along `d`, `k_∥`.
    pub axial: f64,
    /// Stiffness across `d`, `k_⊥`.
    pub transverse: f64,
}

impl Linearized {
    /// `H v` without forming `H`.
    #[must_use]
    #[inline]
    pub fn apply(&self, v: Vec3) -> Vec3 {
        let along = self.direction.dot(&v) * self.direction;
        self.axial * along + self.transverse * (v - along)
    }

    /// The block `H = k_∥ d dᵀ + k_⊥ (I − d dᵀ)`.
    #[must_use]
    pub fn block(&self) -> Mat3 {
        let ddt = self.direction * self.direction.transpose();
        self.axial * ddt + self.transverse * (Mat3::identity() - ddt)
    }
}

/// A spring between particles `i` and `j`.
///
/// The physics methods take the end positions (and velocities) directly, so
/// they can be called on any configuration, not only on a [`crate::State`].
///
/// ```
/// use hooke_core::{Spring, Vec3};
/// let s = Spring { i: 0, j: 1, stiffness: 100.0, rest_length: 1.0, damping: 0.0 };
/// let f = s.elastic_force(Vec3::new(1.5, 0.0, 0.0), Vec3::zeros());
/// // stretched by 0.5 m: pulled back toward j with k·0.5 = 50 N
/// assert!((f - Vec3::new(-50.0, 0.0, 0.0)).norm() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spring {
    /// First particle.
    pub i: usize,
    /// Second particle.
    pub j: usize,
    /// Stiffness `k` in N/m.
    pub stiffness: f64,
    /// Rest length `L` in m.
    pub rest_length: f64,
    /// Axial damping coefficient `c` in N·s/m.
    pub damping: f64,
}

/// The unit direction `d` from `xⱼ` to `xᵢ` and the length `l`, or `None` when
/// the ends coincide (or are so close that `d` is not finite).
#[inline]
fn direction(xi: Vec3, xj: Vec3) -> Option<(Vec3, f64)> {
    let delta = xi - xj;
    let l = delta.norm();
    // 1/l is finite exactly when l is positive and not subnormal; then every
    // component of d = δ/l lies in [−1, 1].
    let inverse = l.recip();
    inverse.is_finite().then(|| (delta * inverse, l))
}

impl Spring {
    /// Current length `l = |xᵢ − xⱼ|`.
    #[must_use]
    #[inline]
    pub fn length(&self, xi: Vec3, xj: Vec3) -> f64 {
        (xi - xj).norm()
    }

    /// Engineering strain `(l − L)/L`, or `None` for a zero-rest-length spring.
    #[must_use]
    pub fn strain(&self, xi: Vec3, xj: Vec3) -> Option<f64> {
        (self.rest_length > 0.0)
            .then(|| (self.length(xi, xj) - self.rest_length) / self.rest_length)
    }

    /// Elastic energy `½ k (l − L)²`.
    #[must_use]
    #[inline]
    pub fn energy(&self, xi: Vec3, xj: Vec3) -> f64 {
        let stretch = self.length(xi, xj) - self.rest_length;
        0.5 * self.stiffness * stretch * stretch
    }

    /// The stretch `l − L` and the elastic force on particle `i`,
    /// `−k (l − L) d` (as [`Spring::elastic_force`]), the length computed
    /// once: what the energy `½ k (l − L)²` and the force need together.
    #[must_use]
    #[inline]
    pub fn stretch_and_force(&self, xi: Vec3, xj: Vec3) -> (f64, Vec3) {
        if self.rest_length == 0.0 {
            return (self.length(xi, xj), -self.stiffness * (xi - xj));
        }
        match direction(xi, xj) {
            Some((d, l)) => {
                let stretch = l - self.rest_length;
                (stretch, -self.stiffness * stretch * d)
            }
            None => (-self.rest_length, Vec3::zeros()),
        }
    }

    /// Elastic force on particle `i`, `−k (l − L) d`; the force on `j` is its
    /// negative.
    #[must_use]
    #[inline]
    pub fn elastic_force(&self, xi: Vec3, xj: Vec3) -> Vec3 {
        self.stretch_and_force(xi, xj).1
    }

    /// Damping force on particle `i`, `−c ((vᵢ − vⱼ)·d) d`; the force on `j` is
    /// its negative. Zero when the ends coincide.
    #[must_use]
    #[inline]
    pub fn damping_force(&self, xi: Vec3, xj: Vec3, vi: Vec3, vj: Vec3) -> Vec3 {
        if self.damping == 0.0 {
            return Vec3::zeros();
        }
        match direction(xi, xj) {
            Some((d, _)) => -self.damping * (vi - vj).dot(&d) * d,
            None => Vec3::zeros(),
        }
    }

    /// Total force on particle `i` (elastic plus damping), computing the
    /// direction once.
    #[must_use]
    #[inline]
    pub fn force(&self, xi: Vec3, xj: Vec3, vi: Vec3, vj: Vec3) -> Vec3 {
        let Some((d, l)) = direction(xi, xj) else {
            return self.elastic_force(xi, xj);
        };
        let elastic = if self.rest_length == 0.0 {
            -self.stiffness * l
        } else {
            -self.stiffness * (l - self.rest_length)
        };
        let damping = -self.damping * (vi - vj).dot(&d);
        (elastic + damping) * d
    }

    /// Rate at which the damper turns kinetic energy into heat,
    /// `c ((vᵢ − vⱼ)·d)² ≥ 0`.
    #[must_use]
    pub fn dissipation_power(&self, xi: Vec3, xj: Vec3, vi: Vec3, vj: Vec3) -> f64 {
        if self.damping == 0.0 {
            return 0.0;
        }
        direction(xi, xj).map_or(0.0, |(d, _)| {
            let rate = (vi - vj).dot(&d);
            self.damping * rate * rate
        })
    }

    /// Stiffness block `H = k [d dᵀ + (1 − L/l)(I − d dᵀ)]`, so that
    /// `∂fᵢ/∂xᵢ = −H`; see [`CompressedSprings`] for the compressed case.
    #[must_use]
    pub fn stiffness_block(&self, xi: Vec3, xj: Vec3, compressed: CompressedSprings) -> Mat3 {
        self.linearize(xi, xj, compressed).block()
    }

    /// Elastic force on `i` and the stiffness block in factored form,
    /// computing the direction once: what an implicit solver needs per
    /// spring.
    ///
    /// ```
    /// use hooke_core::{CompressedSprings, Spring, Vec3};
    /// let s = Spring { i: 0, j: 1, stiffness: 10.0, rest_length: 1.0, damping: 0.0 };
    /// let (xi, xj) = (Vec3::new(2.0, 0.0, 0.0), Vec3::zeros());
    /// let lin = s.linearize(xi, xj, CompressedSprings::Clamped);
    /// assert_eq!((lin.axial, lin.transverse), (10.0, 5.0)); // k and k(1 − L/l)
    /// assert_eq!(lin.block(), s.stiffness_block(xi, xj, CompressedSprings::Clamped));
    /// ```
    #[must_use]
    #[inline]
    pub fn linearize(&self, xi: Vec3, xj: Vec3, compressed: CompressedSprings) -> Linearized {
        let k = self.stiffness;
        if self.rest_length == 0.0 {
            let direction = direction(xi, xj).map_or_else(Vec3::zeros, |(d, _)| d);
            return Linearized {
                force: -k * (xi - xj),
                direction,
                axial: k,
                transverse: k,
            };
        }
        let Some((d, l)) = direction(xi, xj) else {
            return Linearized::default();
        };
        let mut transverse = 1.0 - self.rest_length / l;
        if compressed == CompressedSprings::Clamped {
            transverse = transverse.max(0.0);
        }
        Linearized {
            force: -k * (l - self.rest_length) * d,
            direction: d,
            axial: k,
            // Beyond rounding (ends closer than 1e-308 L) the factor is unbounded.
            transverse: if transverse.is_finite() {
                k * transverse
            } else {
                0.0
            },
        }
    }

    /// Damping block `D = c d dᵀ`, so that `∂fᵢ/∂vᵢ = −D`. Zero when the ends
    /// coincide.
    #[must_use]
    pub fn damping_block(&self, xi: Vec3, xj: Vec3) -> Mat3 {
        if self.damping == 0.0 {
            return Mat3::zeros();
        }
        direction(xi, xj).map_or_else(Mat3::zeros, |(d, _)| self.damping * d * d.transpose())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn spring(rest_length: f64) -> Spring {
        Spring {
            i: 0,
            j: 1,
            stiffness: 7.0,
            rest_length,
            damping: 3.0,
        }
    }

    #[test]
    fn coincident_ends_give_finite_zero_force_and_blocks() {
        let s = spring(1.0);
        let x = Vec3::new(0.3, -0.2, 5.0);
        let v = Vec3::new(1.0, 2.0, 3.0);
        assert_eq!(s.force(x, x, v, Vec3::zeros()), Vec3::zeros());
        assert_eq!(
            s.stiffness_block(x, x, CompressedSprings::Exact),
            Mat3::zeros()
        );
        assert_eq!(s.damping_block(x, x), Mat3::zeros());
        assert_relative_eq!(s.energy(x, x), 0.5 * 7.0);
    }

    /// The stretch gives the energy `½k(l − L)²`, and the force is minus
    /// the energy's gradient in `xᵢ` (central differences), stretched,
    /// compressed and at zero rest length.
    #[test]
    fn stretch_and_force_are_the_energy_and_its_slope() {
        let xj = Vec3::new(0.1, -0.4, 0.2);
        for (rest, xi) in [
            (1.0, Vec3::new(1.3, 0.5, -0.2)),
            (1.0, Vec3::new(0.4, -0.1, 0.3)),
            (0.0, Vec3::new(0.7, 0.2, 0.9)),
        ] {
            let s = spring(rest);
            let (stretch, force) = s.stretch_and_force(xi, xj);
            assert_relative_eq!(
                0.5 * 7.0 * stretch * stretch,
                s.energy(xi, xj),
                epsilon = 1e-14
            );
            let h = 1e-6;
            let slope = Vec3::from_fn(|c, _| {
                let e = Vec3::ith(c, h);
                (s.energy(xi + e, xj) - s.energy(xi - e, xj)) / (2.0 * h)
            });
            assert_relative_eq!(force, -slope, epsilon = 1e-8);
        }
    }

    #[test]
    fn zero_rest_length_is_linear_even_at_coincidence() {
        let s = spring(0.0);
        let x = Vec3::new(0.3, -0.2, 5.0);
        assert_eq!(s.elastic_force(x, x), Vec3::zeros());
        assert_eq!(
            s.stiffness_block(x, x, CompressedSprings::Exact),
            Mat3::identity() * 7.0
        );
        let y = x + Vec3::new(1e-3, 2e-3, -1e-3);
        assert_relative_eq!(s.elastic_force(y, x), -7.0 * (y - x), epsilon = 1e-15);
    }

    #[test]
    fn ends_closer_than_underflow_do_not_overflow_the_block() {
        let s = spring(10.0);
        let xj = Vec3::zeros();
        let xi = Vec3::new(1e-310, 0.0, 0.0);
        let h = s.stiffness_block(xi, xj, CompressedSprings::Exact);
        assert!(h.iter().all(|c| c.is_finite()));
        assert!(s.force(xi, xj, xj, xj).iter().all(|c| c.is_finite()));
    }

    #[test]
    fn clamp_only_changes_compressed_springs() {
        let s = spring(1.0);
        let xj = Vec3::zeros();
        let stretched = Vec3::new(1.2, 0.3, 0.0);
        assert_eq!(
            s.stiffness_block(stretched, xj, CompressedSprings::Clamped),
            s.stiffness_block(stretched, xj, CompressedSprings::Exact)
        );
        let compressed = Vec3::new(0.5, 0.1, 0.0);
        let clamped = s.stiffness_block(compressed, xj, CompressedSprings::Clamped);
        let d = compressed.normalize();
        assert_relative_eq!(clamped, 7.0 * d * d.transpose(), epsilon = 1e-12);
    }
}
