//! The small decompositions a volume element's projected Hessian needs: the
//! signed SVD of its deformation gradient and a 3 × 3 symmetric eigensolve.

use crate::{Mat3, Vec3};

/// `F = U diag(σ) Vᵀ` with `U` and `V` rotations and `σ₀ ≥ σ₁ ≥ |σ₂|`:
/// where a reflection is needed, the last singular value carries the sign
/// (negative for `det F < 0`).
///
/// `V` and `σ²` are the eigenpairs of `FᵀF`; `uₖ = F vₖ / σₖ` for the two
/// largest, `u₂ = u₀ × u₁` (so `U` is a rotation) and `σ₂ = u₂ᵀ F v₂`, which
/// keeps its sign and its accuracy for a nearly flat element, where
/// `√(σ₂²)` would not. A degenerate `F` (an element collapsed onto a line
/// or a point) gets any orthonormal completion.
pub(super) fn signed_svd(f: &Mat3) -> (Mat3, Vec3, Mat3) {
    let (values, mut v) = symmetric_eigen(f.transpose() * f);
    let mut order = [0, 1, 2];
    order.sort_by(|&a, &b| values[b].total_cmp(&values[a]));
    v = Mat3::from_columns(&order.map(|k| v.column(k).into_owned()));
    if v.determinant() < 0.0 {
        v.column_mut(2).neg_mut();
    }
    let (v0, v1, v2): (Vec3, Vec3, Vec3) =
        (v.column(0).into(), v.column(1).into(), v.column(2).into());
    let u0 = (f * v0).try_normalize(0.0).unwrap_or_else(Vec3::x);
    let mut u1 = f * v1 - (f * v1).dot(&u0) * u0;
    if u1.norm() <= 1e-300 {
        u1 = orthogonal(u0);
    }
    let u1 = u1.normalize();
    let u2 = u0.cross(&u1);
    let sigma = Vec3::new((f * v0).dot(&u0), (f * v1).dot(&u1), (f * v2).dot(&u2));
    (Mat3::from_columns(&[u0, u1, u2]), sigma, v)
}

/// A unit vector orthogonal to the unit vector `u`.
fn orthogonal(u: Vec3) -> Vec3 {
    let helper = if u.x.abs() < 0.9 {
        Vec3::x()
    } else {
        Vec3::y()
    };
    u.cross(&helper).normalize()
}

/// The eigenvalues and eigenvectors (columns) of the symmetric `m`, by
/// cyclic Jacobi rotations: each zeroes one off-diagonal entry, and the
/// sweeps stop when the off-diagonal part is below 10⁻¹⁵ of the norm,
/// after a few sweeps for a 3 × 3 matrix.
pub(super) fn symmetric_eigen(m: Mat3) -> (Vec3, Mat3) {
    let mut a = m;
    let mut v = Mat3::identity();
    let scale = m.norm();
    for _ in 0..20 {
        let off = a[(0, 1)].powi(2) + a[(0, 2)].powi(2) + a[(1, 2)].powi(2);
        if off.sqrt() <= 1e-15 * scale {
            break;
        }
        for (p, q, r) in [(0, 1, 2), (0, 2, 1), (1, 2, 0)] {
            let apq = a[(p, q)];
            if apq == 0.0 {
                continue;
            }
            // The rotation by θ with cot 2θ = (a_qq − a_pp) / 2a_pq,
            // t = tan θ the smaller root, applied as `a ← Pᵀ a P`,
            // `v ← v P` (Numerical Recipes, §11.1).
            let theta = (a[(q, q)] - a[(p, p)]) / (2.0 * apq);
            let t = if theta == 0.0 {
                1.0
            } else {
                theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt())
            };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            a[(p, p)] -= t * apq;
            a[(q, q)] += t * apq;
            a[(p, q)] = 0.0;
            a[(q, p)] = 0.0;
            let (arp, arq) = (a[(r, p)], a[(r, q)]);
            a[(r, p)] = c * arp - s * arq;
            a[(p, r)] = a[(r, p)];
            a[(r, q)] = s * arp + c * arq;
            a[(q, r)] = a[(r, q)];
            for k in 0..3 {
                let (vkp, vkq) = (v[(k, p)], v[(k, q)]);
                v[(k, p)] = c * vkp - s * vkq;
                v[(k, q)] = s * vkp + c * vkq;
            }
        }
    }
    (a.diagonal(), v)
}
