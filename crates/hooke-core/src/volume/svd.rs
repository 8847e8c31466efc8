//! The signed SVD of a volume element's deformation gradient, which its
//! projected Hessian is built on.

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
    let eigen = (f.transpose() * f).symmetric_eigen();
    let (values, mut v) = (eigen.eigenvalues, eigen.eigenvectors);
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
