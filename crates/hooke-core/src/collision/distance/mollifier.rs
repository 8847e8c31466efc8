//! The edge–edge mollifier of Li et al. (*Incremental Potential Contact*,
//! 2020, §4.3), which fades the edge–edge barrier out as two edges turn
//! parallel.

use nalgebra::{SMatrix, SVector};

use super::Derivatives;
use crate::{Mat12, Vec3, Vec12};

/// The mollifier threshold of an edge–edge pair from its *rest* positions,
/// `ε_× = 10⁻³ |a₁ − a₀|² |b₁ − b₀|²` (Li et al. 2020, §4.3).
#[must_use]
pub fn mollifier_threshold(a0: Vec3, a1: Vec3, b0: Vec3, b1: Vec3) -> f64 {
    1e-3 * (a1 - a0).norm_squared() * (b1 - b0).norm_squared()
}

/// The edge–edge mollifier of Li et al. (2020, §4.3) with its gradient and
/// Hessian: with `c = |e₀ × e₁|²`, `e₀ = a₁ − a₀`, `e₁ = b₁ − b₀`,
///
/// ```text
/// m(c) = −c²/ε² + 2c/ε   for c < ε,        m = 1 otherwise,
/// ∇m = m'(c) ∇c,   ∇²m = m''(c) ∇c ∇cᵀ + m'(c) ∇²c,
/// ∂c/∂e₀ = 2 e₁ × n,   ∂c/∂e₁ = 2 n × e₀,   n = e₀ × e₁,
/// ∇²_(e₀,e₁) c = 2 KᵀK + [[0, −2[n]×], [2[n]×, 0]],   K = [−[e₁]×, [e₀]×].
/// ```
///
/// `m` is C¹ at `c = ε`, vanishes for parallel edges, and multiplies the
/// edge–edge barrier so that it goes smoothly to zero where the edge–edge
/// distance is not smooth. `threshold` is `ε`, from [`mollifier_threshold`].
#[must_use]
pub fn edge_edge_mollifier(a0: Vec3, a1: Vec3, b0: Vec3, b1: Vec3, threshold: f64) -> Derivatives {
    let (e0, e1) = (a1 - a0, b1 - b0);
    let n = e0.cross(&e1);
    let c = n.norm_squared();
    if c.is_nan() || c >= threshold {
        return Derivatives::constant(1.0);
    }
    let q = c / threshold;
    let m = q * (2.0 - q);
    let dm = 2.0 * (1.0 - q) / threshold;
    let ddm = -2.0 / (threshold * threshold);
    // c's gradient and Hessian with respect to (e₀, e₁).
    let mut ge = SVector::<f64, 6>::zeros();
    ge.fixed_rows_mut::<3>(0).copy_from(&(2.0 * e1.cross(&n)));
    ge.fixed_rows_mut::<3>(3).copy_from(&(2.0 * n.cross(&e0)));
    let mut k = SMatrix::<f64, 3, 6>::zeros();
    k.fixed_columns_mut::<3>(0).copy_from(&(-e1.cross_matrix()));
    k.fixed_columns_mut::<3>(3).copy_from(&e0.cross_matrix());
    let mut he = 2.0 * k.transpose() * k;
    let nx = 2.0 * n.cross_matrix();
    for r in 0..3 {
        for c in 0..3 {
            he[(r, 3 + c)] -= nx[(r, c)];
            he[(3 + r, c)] += nx[(r, c)];
        }
    }
    // Back to the points: e₀ = a₁ − a₀, e₁ = b₁ − b₀.
    const EDGE: [usize; 4] = [0, 0, 1, 1];
    const SIGN: [f64; 4] = [-1.0, 1.0, -1.0, 1.0];
    let mut grad_c = Vec12::zeros();
    let mut hessian = Mat12::zeros();
    for i in 0..4 {
        grad_c
            .fixed_rows_mut::<3>(3 * i)
            .copy_from(&(SIGN[i] * ge.fixed_rows::<3>(3 * EDGE[i])));
        for j in 0..4 {
            hessian
                .fixed_view_mut::<3, 3>(3 * i, 3 * j)
                .copy_from(&(SIGN[i] * SIGN[j] * he.fixed_view::<3, 3>(3 * EDGE[i], 3 * EDGE[j])));
        }
    }
    hessian *= dm;
    hessian.ger(ddm, &grad_c, &grad_c, 1.0);
    Derivatives {
        value: m,
        gradient: dm * grad_c,
        hessian,
    }
}
