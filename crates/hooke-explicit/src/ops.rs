//! Per-particle vector arithmetic shared by the integrators.

use hooke_core::Vec3;

/// `out = base + Σⱼ cⱼ termsⱼ`, particle by particle.
pub(crate) fn combine(out: &mut [Vec3], base: &[Vec3], terms: &[(f64, &[Vec3])]) {
    for (i, (o, b)) in out.iter_mut().zip(base).enumerate() {
        *o = terms.iter().fold(*b, |acc, &(c, t)| acc + c * t[i]);
    }
}
