//! Per-particle vector arithmetic shared by the integrators.

use hooke_core::Vec3;

/// Sizes every buffer to `n` particles; allocates only when a buffer grows.
pub(crate) fn fit<const N: usize>(n: usize, buffers: [&mut Vec<Vec3>; N]) {
    for buffer in buffers {
        buffer.resize(n, Vec3::zeros());
    }
}

/// `out = base + Σⱼ cⱼ termsⱼ`, particle by particle.
pub(crate) fn combine(out: &mut [Vec3], base: &[Vec3], terms: &[(f64, &[Vec3])]) {
    for (i, (o, b)) in out.iter_mut().zip(base).enumerate() {
        *o = terms.iter().fold(*b, |acc, &(c, t)| acc + c * t[i]);
    }
}
