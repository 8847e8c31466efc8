//! Point–triangle and edge–edge distances with their exact gradients and
//! Hessians, and the edge–edge mollifier of Li et al. (*Incremental Potential
//! Contact*, SIGGRAPH 2020, §4 and Appendix).
//!
//! A pair is four points `x = (x₀, x₁, x₂, x₃)` stacked into a 12-vector
//! (point `k`'s coordinates at `3k..3k+3`): `(p, a, b, c)` for point–triangle,
//! `(a₀, a₁, b₀, b₁)` for edge–edge. The closest points are an affine
//! combination `r = Σₖ wₖ xₖ`, the vector from the second primitive's closest
//! point to the first's, and `d² = |r|²`.
//!
//! **Regions.** The closest points lie in the interior of a pair of features
//! (IPC's distance types): point–point `|p − q|²`, point–line
//! `|(p − a) × (b − a)|² / |b − a|²`, point–plane `((p − a)·n)² / |n|²` with
//! `n = (b − a) × (c − a)`, or line–line `((a₀ − b₀)·n)² / |n|²` with
//! `n = e₀ × e₁`. Inside a region `d²` is smooth, and every region is a
//! partial minimisation `d²(x) = min_t F(x, t)`, `F = |Σₖ wₖ(t) xₖ|²`, over the
//! `m ≤ 2` free parameters `t` of the features (with `w` affine in `t`). By
//! the envelope theorem, at the minimiser `t*`:
//!
//! ```text
//! ∇d²  = F_x = 2 w ⊗ r
//! ∇²d² = F_xx − F_xt F_tt⁻¹ F_tx,   F_xx = 2 (w wᵀ) ⊗ I₃,   F_tt = 2 JᵀJ,
//! (F_xt)_{3k+c, j} = 2 Dⱼₖ r_c + 2 wₖ (Jⱼ)_c,   Jⱼ = ∂r/∂tⱼ = Σₖ Dⱼₖ xₖ,
//! ```
//!
//! with `Dⱼ = ∂w/∂tⱼ`. This one formula gives every region's exact Hessian.
//!
//! **Degenerate geometry.** Edges closer to parallel than
//! `|e₀ × e₁|² ≤ 10⁻¹² |e₀|² |e₁|²` (and triangles that flat) are never given
//! the line–line (point–plane) type, whose derivatives grow like `1/sin θ`; the
//! closest pair is then found among the endpoint–segment pairs, which
//! overestimates `d` by at most `~10⁻⁶` of the edge length. Zero-length edges
//! reduce to points. Nothing here divides by zero.

mod mollifier;
mod regions;

pub use mollifier::{edge_edge_mollifier, mollifier_threshold};

use crate::{Mat12, Vec3, Vec12};
use regions::{Nearest, Region, edge_edge_nearest, point_triangle_nearest};
use regions::{edges_offset, face_offset, least, point_segment_squared};

/// A function `f` of the 12 coordinates with its gradient `∇f` and Hessian
/// `∇²f`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Derivatives {
    /// `f(x)`.
    pub value: f64,
    /// `∇f(x)`, point `k`'s components at `3k..3k+3`.
    pub gradient: Vec12,
    /// `∇²f(x)`.
    pub hessian: Mat12,
}

impl Derivatives {
    /// A constant: `value` with zero gradient and Hessian.
    pub(crate) fn constant(value: f64) -> Self {
        Self {
            value,
            gradient: Vec12::zeros(),
            hessian: Mat12::zeros(),
        }
    }
}

/// The closest points of a pair: weights `w` with `Σₖ wₖ xₖ = r`, the vector
/// from the second primitive's closest point to the first's, and `d² = |r|²`.
///
/// Point–triangle: `w = [1, −α, −β, −γ]`, `α + β + γ = 1` the barycentric
/// coordinates of the closest point on the triangle. Edge–edge:
/// `w = [1 − s, s, −(1 − t), −t]` with `s, t ∈ [0, 1]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Closest {
    /// The weights `wₖ` of the four points.
    pub weights: [f64; 4],
    /// The squared distance `|Σₖ wₖ xₖ|²`.
    pub squared: f64,
}

/// The squared distance of point `p` and triangle `(a, b, c)`: bit for bit
/// [`point_triangle_closest`]`(p, a, b, c).squared`, without the closest
/// points' weights (the cheap path of a search that discards most pairs).
#[must_use]
pub fn point_triangle_squared_distance(p: Vec3, a: Vec3, b: Vec3, c: Vec3) -> f64 {
    if let Some((_, r)) = face_offset(p, a, b, c) {
        return r.norm_squared();
    }
    least([
        point_segment_squared(p, a, b),
        point_segment_squared(p, b, c),
        point_segment_squared(p, c, a),
    ])
}

/// The squared distance of segments `(a₀, a₁)` and `(b₀, b₁)`: bit for bit
/// [`edge_edge_closest`]`(a₀, a₁, b₀, b₁).squared`, without the closest
/// points' weights.
#[must_use]
pub fn edge_edge_squared_distance(a0: Vec3, a1: Vec3, b0: Vec3, b1: Vec3) -> f64 {
    if let Some((_, r)) = edges_offset(a0, a1, b0, b1) {
        return r.norm_squared();
    }
    least([
        point_segment_squared(a0, b0, b1),
        point_segment_squared(a1, b0, b1),
        point_segment_squared(b0, a0, a1),
        point_segment_squared(b1, a0, a1),
    ])
}

/// The closest points of point `p` and triangle `(a, b, c)`:
/// `r = p − (α a + β b + γ c)`, `w = [1, −α, −β, −γ]`, `d² = |r|²`.
///
/// The face projection is used when its barycentric coordinates are all
/// non-negative; otherwise the nearest of the three edges (clamped segments).
#[must_use]
pub fn point_triangle_closest(p: Vec3, a: Vec3, b: Vec3, c: Vec3) -> Closest {
    point_triangle_nearest(&[p, a, b, c]).closest
}

/// The closest points of segments `(a₀, a₁)` and `(b₀, b₁)`:
/// `r = (1 − s) a₀ + s a₁ − ((1 − t) b₀ + t b₁)`, `s, t ∈ [0, 1]`,
/// `w = [1 − s, s, −(1 − t), −t]`, `d² = |r|²`.
///
/// The interior line–line solution `s = ((b₀ − a₀) × e₁)·n / |n|²`,
/// `t = ((b₀ − a₀) × e₀)·n / |n|²` (`n = e₀ × e₁`) when it lies in `(0, 1)²`
/// and the edges are not (nearly) parallel; otherwise the nearest
/// endpoint–segment pair. Robust for parallel and zero-length edges.
#[must_use]
pub fn edge_edge_closest(a0: Vec3, a1: Vec3, b0: Vec3, b1: Vec3) -> Closest {
    edge_edge_nearest(&[a0, a1, b0, b1]).closest
}

/// The squared distance `d²` of point `p` and triangle `(a, b, c)` with its
/// exact gradient and Hessian in the closest-feature region (vertex: `|p − a|²`,
/// edge: `|(p − a) × (b − a)|² / |b − a|²`, face:
/// `((p − a)·n)² / |n|²`; see the module docs). Its value equals
/// [`point_triangle_closest`]'s `squared`.
#[must_use]
pub fn point_triangle_squared(p: Vec3, a: Vec3, b: Vec3, c: Vec3) -> Derivatives {
    let x = [p, a, b, c];
    envelope(&x, &point_triangle_nearest(&x))
}

/// The squared distance `d²` of segments `(a₀, a₁)` and `(b₀, b₁)` with its
/// exact gradient and Hessian in the closest-feature region
/// (endpoint–endpoint, endpoint–edge, or line–line
/// `((a₀ − b₀)·n)² / |n|²`, `n = e₀ × e₁`). (Nearly) parallel edges take an
/// endpoint type, so the derivatives stay finite. Its value equals
/// [`edge_edge_closest`]'s `squared`.
#[must_use]
pub fn edge_edge_squared(a0: Vec3, a1: Vec3, b0: Vec3, b1: Vec3) -> Derivatives {
    let x = [a0, a1, b0, b1];
    envelope(&x, &edge_edge_nearest(&x))
}

/// Column `j` of `F_xt` and `Jⱼ`, for `Dⱼ = d`.
fn mixed_column(x: &[Vec3; 4], w: &[f64; 4], r: &Vec3, d: &[f64; 4]) -> (Vec12, Vec3) {
    let j = x[0] * d[0] + x[1] * d[1] + x[2] * d[2] + x[3] * d[3];
    let mut b = Vec12::zeros();
    for k in 0..4 {
        b.fixed_rows_mut::<3>(3 * k)
            .copy_from(&(2.0 * d[k] * r + 2.0 * w[k] * j));
    }
    (b, j)
}

/// `d²` with its gradient and Hessian by the envelope formula (module docs).
fn envelope(x: &[Vec3; 4], near: &Nearest) -> Derivatives {
    let w = &near.closest.weights;
    let r = &near.r;
    let mut gradient = Vec12::zeros();
    let mut hessian = Mat12::zeros();
    for k in 0..4 {
        gradient
            .fixed_rows_mut::<3>(3 * k)
            .copy_from(&(2.0 * w[k] * r));
        for l in 0..4 {
            let v = 2.0 * w[k] * w[l];
            for c in 0..3 {
                hessian[(3 * k + c, 3 * l + c)] = v;
            }
        }
    }
    match near.region {
        Region::Point => {}
        Region::Line(d) => {
            let (b, j) = mixed_column(x, w, r, &d);
            hessian.ger(-0.5 / j.norm_squared(), &b, &b, 1.0);
        }
        Region::Plane([d0, d1]) => {
            let (b0, j0) = mixed_column(x, w, r, &d0);
            let (b1, j1) = mixed_column(x, w, r, &d1);
            // (JᵀJ)⁻¹ = [[j₁·j₁, −j₀·j₁], [−j₀·j₁, j₀·j₀]] / |j₀ × j₁|².
            let f = -0.5 / j0.cross(&j1).norm_squared();
            let g01 = j0.dot(&j1);
            hessian.ger(f * j1.norm_squared(), &b0, &b0, 1.0);
            hessian.ger(-f * g01, &b0, &b1, 1.0);
            hessian.ger(-f * g01, &b1, &b0, 1.0);
            hessian.ger(f * j0.norm_squared(), &b1, &b1, 1.0);
        }
    }
    Derivatives {
        value: near.closest.squared,
        gradient,
        hessian,
    }
}

#[cfg(test)]
pub(crate) mod tests;
