//! [`SymBlock`]: a symmetric 3x3 block stored as its six distinct entries.

use crate::{Mat3, Vec3};

/// A symmetric 3x3 matrix `[[a, b, c], [b, d, e], [c, e, f]]`, stored as
/// `[a, b, c, d, e, f]` (48 bytes instead of 72): a particle's diagonal
/// block of a Hessian ([`Hessian::add_row`](crate::Hessian::add_row)), and
/// every spring's block of an implicit step's matrix, whose products then
/// read a third less memory.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SymBlock(pub [f64; 6]);

impl SymBlock {
    /// `s I`.
    #[inline]
    #[must_use]
    pub fn scaled_identity(s: f64) -> Self {
        Self([s, 0.0, 0.0, s, 0.0, s])
    }

    /// `α d dᵀ + β I`.
    #[inline]
    #[must_use]
    pub fn rank_one_plus_identity(alpha: f64, d: Vec3, beta: f64) -> Self {
        let ad = alpha * d;
        Self([
            ad.x * d.x + beta,
            ad.x * d.y,
            ad.x * d.z,
            ad.y * d.y + beta,
            ad.y * d.z,
            ad.z * d.z + beta,
        ])
    }

    /// The symmetric part `½(m + mᵀ)` of `m`.
    #[inline]
    #[must_use]
    pub fn symmetric_part(m: &Mat3) -> Self {
        let s = 0.5 * (m + m.transpose());
        Self([
            s[(0, 0)],
            s[(0, 1)],
            s[(0, 2)],
            s[(1, 1)],
            s[(1, 2)],
            s[(2, 2)],
        ])
    }

    /// `M v`.
    #[inline]
    #[must_use]
    pub fn mul(&self, v: Vec3) -> Vec3 {
        let [a, b, c, d, e, f] = self.0;
        Vec3::new(
            a * v.x + b * v.y + c * v.z,
            b * v.x + d * v.y + e * v.z,
            c * v.x + e * v.y + f * v.z,
        )
    }

    /// `self += other`.
    #[inline]
    pub fn add_assign(&mut self, other: &Self) {
        for (s, o) in self.0.iter_mut().zip(&other.0) {
            *s += o;
        }
    }

    /// Whether every entry is finite.
    #[inline]
    #[must_use]
    pub fn is_finite(&self) -> bool {
        self.0.iter().all(|c| c.is_finite())
    }

    /// The inverse if the block is positive definite (all leading principal
    /// minors positive, by Sylvester's criterion), else `None`.
    #[inline]
    #[must_use]
    pub fn inverse_if_positive_definite(&self) -> Option<Self> {
        let [a, b, c, d, e, f] = self.0;
        let (cofactor_a, cofactor_b, cofactor_c) = (d * f - e * e, c * e - b * f, b * e - c * d);
        let det = a * cofactor_a + b * cofactor_b + c * cofactor_c;
        if !(a > 0.0 && a * d - b * b > 0.0 && det > 0.0 && det.is_finite()) {
            return None;
        }
        let inv = 1.0 / det;
        Some(Self([
            cofactor_a * inv,
            cofactor_b * inv,
            cofactor_c * inv,
            (a * f - c * c) * inv,
            (b * c - a * e) * inv,
            (a * d - b * b) * inv,
        ]))
    }

    /// The full matrix.
    #[inline]
    #[must_use]
    pub fn to_mat3(&self) -> Mat3 {
        let [a, b, c, d, e, f] = self.0;
        Mat3::new(a, b, c, b, d, e, c, e, f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn products_and_inverse_match_the_full_matrix() {
        let d = Vec3::new(1.0, -2.0, 2.0) / 3.0;
        let m = SymBlock::rank_one_plus_identity(5.0, d, 0.5);
        let full = 5.0 * d * d.transpose() + 0.5 * Mat3::identity();
        assert!((m.to_mat3() - full).norm() < 1e-15);
        let v = Vec3::new(0.3, 1.1, -0.7);
        assert!((m.mul(v) - full * v).norm() < 1e-15);
        let inverse = m.inverse_if_positive_definite().unwrap().to_mat3();
        assert!((inverse * full - Mat3::identity()).norm() < 1e-14);
        assert!(
            SymBlock::rank_one_plus_identity(-5.0, d, 0.5)
                .inverse_if_positive_definite()
                .is_none()
        );
        assert!(
            SymBlock::scaled_identity(f64::NAN)
                .inverse_if_positive_definite()
                .is_none()
        );
    }
}
