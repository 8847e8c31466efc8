//! The projection of a symmetric matrix onto the positive semi-definite
//! cone, and its shortcut for a contact pair's Hessian.

use nalgebra::{Const, DefaultAllocator, DimDiff, DimSub, SMatrix, U1, allocator::Allocator};

use crate::Mat12;

/// Projects a symmetric matrix onto the positive semi-definite cone, the
/// nearest PSD matrix in the Frobenius norm: with `M = Q Λ Qᵀ`,
/// `M₊ = Q max(Λ, 0) Qᵀ` (Teran et al., *Robust Quasistatic Finite Elements
/// and Flesh Simulation*, SCA 2005; used per pair by IPC, §5). Only the lower
/// triangle of `m` is read; the result is exactly symmetric.
#[must_use]
pub fn project_positive<const N: usize>(m: &SMatrix<f64, N, N>) -> SMatrix<f64, N, N>
where
    Const<N>: DimSub<U1>,
    DefaultAllocator: Allocator<DimDiff<Const<N>, U1>>,
{
    let mut eigen = m.symmetric_eigen();
    eigen.eigenvalues.iter_mut().for_each(|l| *l = l.max(0.0));
    let p = eigen.recompose();
    (p + p.transpose()) * 0.5
}

/// An orthonormal basis `U = V ⊗ I₃` (12×9) of the complement of the rigid
/// translations `1 ⊗ e_c`, with `V` the 4×3 Helmert basis orthogonal to
/// `(1, 1, 1, 1)`.
pub(super) fn translation_complement() -> SMatrix<f64, 12, 9> {
    const S2: f64 = std::f64::consts::FRAC_1_SQRT_2;
    const S6: f64 = 0.408_248_290_463_863_1; // 1/√6
    const S12: f64 = 0.288_675_134_594_812_9; // 1/√12
    const V: [[f64; 3]; 4] = [
        [S2, S6, S12],
        [-S2, S6, S12],
        [0.0, -2.0 * S6, S12],
        [0.0, 0.0, -3.0 * S12],
    ];
    let mut u = SMatrix::<f64, 12, 9>::zeros();
    for (k, row) in V.iter().enumerate() {
        for (i, v) in row.iter().enumerate() {
            for c in 0..3 {
                u[(3 * k + c, 3 * i + c)] = *v;
            }
        }
    }
    u
}

/// [`project_positive`] for a pair's Hessian. A function of the pair's
/// relative positions (every distance, barrier and mollifier) has
/// `H (1 ⊗ e_c) = 0`; then `H = U (UᵀHU) Uᵀ` and `H₊ = U (UᵀHU)₊ Uᵀ` exactly,
/// a 9×9 eigenproblem instead of 12×12 (about 1.4 times faster in all).
/// Other matrices take the full projection.
pub(super) fn project_pair(h: &Mat12) -> Mat12 {
    let tol = 1e-10 * h.amax();
    let invariant = (0..12).all(|i| {
        (0..3).all(|c| (h[(i, c)] + h[(i, 3 + c)] + h[(i, 6 + c)] + h[(i, 9 + c)]).abs() <= tol)
    });
    if !invariant {
        return project_positive(h);
    }
    let u = translation_complement();
    let p = u * project_positive(&(u.transpose() * h * u)) * u.transpose();
    (p + p.transpose()) * 0.5
}
