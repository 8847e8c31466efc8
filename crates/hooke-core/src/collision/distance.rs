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

use crate::Vec3;
use nalgebra::{SMatrix, SVector};

/// A pair's 12 coordinates (or a gradient with respect to them).
pub type Vector12 = SVector<f64, 12>;
/// A 12×12 matrix, the Hessian of a function of a pair's coordinates.
pub type Matrix12 = SMatrix<f64, 12, 12>;

/// `sin²θ` below which two edges (or a triangle's two edges at `a`) count as
/// parallel.
const PARALLEL: f64 = 1e-12;

/// A function `f` of the 12 coordinates with its gradient `∇f` and Hessian
/// `∇²f`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Derivatives {
    /// `f(x)`.
    pub value: f64,
    /// `∇f(x)`, point `k`'s components at `3k..3k+3`.
    pub gradient: Vector12,
    /// `∇²f(x)`.
    pub hessian: Matrix12,
}

impl Derivatives {
    /// A constant: `value` with zero gradient and Hessian.
    pub(crate) fn constant(value: f64) -> Self {
        Self {
            value,
            gradient: Vector12::zeros(),
            hessian: Matrix12::zeros(),
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

/// The free parameters of a region: `∂w/∂tⱼ` for each.
#[derive(Debug, Clone, Copy)]
enum Region {
    Point,
    Line([f64; 4]),
    Plane([[f64; 4]; 2]),
}

/// The closest points with `r` and their region.
#[derive(Debug, Clone, Copy)]
struct Nearest {
    closest: Closest,
    r: Vec3,
    region: Region,
}

/// Point `p` against segment `(j, k)`: the parameter `t` of the line's
/// point nearest `p`, and `p − q` for the segment's nearest point `q` (that
/// point if `t ∈ (0, 1)`, otherwise `j` for `t ≤ 0` and `k` else).
fn segment_offset(p: Vec3, j: Vec3, k: Vec3) -> (f64, Vec3) {
    let e = k - j;
    let v = p - j;
    let ee = e.norm_squared();
    let t = if ee > 0.0 { v.dot(&e) / ee } else { 0.0 };
    let r = if t > 0.0 && t < 1.0 {
        v - e * t
    } else if t <= 0.0 {
        p - j
    } else {
        p - k
    };
    (t, r)
}

/// The barycentric coordinates `(α, β, γ)` of the projection of `p` onto
/// the plane of triangle `(a, b, c)`, and `r = p − (α a + β b + γ c)`, if
/// the triangle is not flat and the projection lies inside it.
fn face_offset(p: Vec3, a: Vec3, b: Vec3, c: Vec3) -> Option<([f64; 3], Vec3)> {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let n = ab.cross(&ac);
    let nn = n.norm_squared();
    if nn > PARALLEL * ab.norm_squared() * ac.norm_squared() {
        let beta = ap.cross(&ac).dot(&n) / nn;
        let gamma = ab.cross(&ap).dot(&n) / nn;
        let alpha = 1.0 - beta - gamma;
        if alpha >= 0.0 && beta >= 0.0 && gamma >= 0.0 {
            return Some(([alpha, beta, gamma], n * (n.dot(&ap) / nn)));
        }
    }
    None
}

/// The parameters `(s, t)` of the closest points of the lines through
/// `(a₀, a₁)` and `(b₀, b₁)`, and `r = a₀ + s e₀ − (b₀ + t e₁)`, if the edges
/// are not (nearly) parallel and both lie inside `(0, 1)`.
fn edges_offset(a0: Vec3, a1: Vec3, b0: Vec3, b1: Vec3) -> Option<([f64; 2], Vec3)> {
    let (e0, e1) = (a1 - a0, b1 - b0);
    let n = e0.cross(&e1);
    let nn = n.norm_squared();
    if nn > PARALLEL * e0.norm_squared() * e1.norm_squared() {
        // a₀ + s e₀ − (b₀ + t e₁) = r ∥ n: cross with e₁, e₀ and dot with n.
        let w = b0 - a0;
        let s = w.cross(&e1).dot(&n) / nn;
        let t = w.cross(&e0).dot(&n) / nn;
        if s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0 {
            return Some(([s, t], n * (-n.dot(&w) / nn)));
        }
    }
    None
}

/// Point `i` against segment `(j, k)`, `r = σ (xᵢ − q)`.
fn point_segment(x: &[Vec3; 4], i: usize, j: usize, k: usize, sign: f64) -> Nearest {
    let (t, offset) = segment_offset(x[i], x[j], x[k]);
    let mut weights = [0.0; 4];
    weights[i] = sign;
    let region = if t > 0.0 && t < 1.0 {
        weights[j] = -sign * (1.0 - t);
        weights[k] = -sign * t;
        let mut d = [0.0; 4];
        d[j] = sign;
        d[k] = -sign;
        Region::Line(d)
    } else {
        weights[if t <= 0.0 { j } else { k }] = -sign;
        Region::Point
    };
    let r = sign * offset;
    let squared = r.norm_squared();
    Nearest {
        closest: Closest { weights, squared },
        r,
        region,
    }
}

/// The nearest of several candidates (the first on ties).
fn nearest_of<const N: usize>(candidates: [Nearest; N]) -> Nearest {
    let mut best = candidates[0];
    for c in &candidates[1..] {
        if c.closest.squared < best.closest.squared {
            best = *c;
        }
    }
    best
}

fn point_triangle_nearest(x: &[Vec3; 4]) -> Nearest {
    let [p, a, b, c] = *x;
    if let Some(([alpha, beta, gamma], r)) = face_offset(p, a, b, c) {
        return Nearest {
            closest: Closest {
                weights: [1.0, -alpha, -beta, -gamma],
                squared: r.norm_squared(),
            },
            r,
            region: Region::Plane([[0.0, 1.0, -1.0, 0.0], [0.0, 1.0, 0.0, -1.0]]),
        };
    }
    // Outside the face (or a flat triangle): the minimum is on the boundary.
    nearest_of([
        point_segment(x, 0, 1, 2, 1.0),
        point_segment(x, 0, 2, 3, 1.0),
        point_segment(x, 0, 3, 1, 1.0),
    ])
}

fn edge_edge_nearest(x: &[Vec3; 4]) -> Nearest {
    let [a0, a1, b0, b1] = *x;
    if let Some(([s, t], r)) = edges_offset(a0, a1, b0, b1) {
        return Nearest {
            closest: Closest {
                weights: [1.0 - s, s, -(1.0 - t), -t],
                squared: r.norm_squared(),
            },
            r,
            region: Region::Plane([[-1.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, -1.0]]),
        };
    }
    // The minimum over the square [0, 1]² is on its boundary: an endpoint of
    // one segment against the other segment.
    nearest_of([
        point_segment(x, 0, 2, 3, 1.0),
        point_segment(x, 1, 2, 3, 1.0),
        point_segment(x, 2, 0, 1, -1.0),
        point_segment(x, 3, 0, 1, -1.0),
    ])
}

/// Column `j` of `F_xt` and `Jⱼ`, for `Dⱼ = d`.
fn mixed_column(x: &[Vec3; 4], w: &[f64; 4], r: &Vec3, d: &[f64; 4]) -> (Vector12, Vec3) {
    let j = x[0] * d[0] + x[1] * d[1] + x[2] * d[2] + x[3] * d[3];
    let mut b = Vector12::zeros();
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
    let mut gradient = Vector12::zeros();
    let mut hessian = Matrix12::zeros();
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

/// `|r|²` of [`point_segment`] for point `p` and segment `(j, k)`, without
/// the weights and the region (the sign of `r` does not change its square).
fn point_segment_squared(p: Vec3, j: Vec3, k: Vec3) -> f64 {
    segment_offset(p, j, k).1.norm_squared()
}

/// The smallest of `squared` as [`nearest_of`] picks it: the first, then
/// each later one that is smaller.
fn least<const N: usize>(squared: [f64; N]) -> f64 {
    let mut best = squared[0];
    for &s in &squared[1..] {
        if s < best {
            best = s;
        }
    }
    best
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
    let mut grad_c = Vector12::zeros();
    let mut hessian = Matrix12::zeros();
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

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// SplitMix64: a small deterministic generator for the tests.
    pub(crate) struct Rng(u64);

    impl Rng {
        pub(crate) fn new(seed: u64) -> Self {
            Self(seed)
        }

        fn next_u64(&mut self) -> u64 {
            self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^ (z >> 31)
        }

        /// Uniform on `0..n`.
        pub(crate) fn below(&mut self, n: usize) -> usize {
            (self.next_u64() % n as u64) as usize
        }

        /// Uniform on `[lo, hi)`.
        pub(crate) fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
            let u = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
            lo + (hi - lo) * u
        }

        /// Uniform in the cube `[−scale, scale)³`.
        pub(crate) fn vec3(&mut self, scale: f64) -> Vec3 {
            Vec3::new(
                self.uniform(-scale, scale),
                self.uniform(-scale, scale),
                self.uniform(-scale, scale),
            )
        }

        /// A random unit vector.
        pub(crate) fn unit(&mut self) -> Vec3 {
            loop {
                let v = self.vec3(1.0);
                let n = v.norm();
                if n > 0.1 && n < 1.0 {
                    return v / n;
                }
            }
        }

        pub(crate) fn sign(&mut self) -> f64 {
            if self.next_u64() & 1 == 0 { 1.0 } else { -1.0 }
        }
    }

    pub(crate) fn stack(x: &[Vec3; 4]) -> Vector12 {
        Vector12::from_fn(|i, _| x[i / 3][i % 3])
    }

    pub(crate) fn unstack(x: &Vector12) -> [Vec3; 4] {
        std::array::from_fn(|k| x.fixed_rows::<3>(3 * k).into())
    }

    /// Checks `f`'s gradient against central differences of its value and its
    /// Hessian against central differences of its gradient, relative to the
    /// largest entry (at least `floor`).
    pub(crate) fn check_derivatives(
        f: impl Fn(&Vector12) -> Derivatives,
        x: &Vector12,
        h: f64,
        tol: f64,
        floor: f64,
    ) {
        let d = f(x);
        let mut grad = Vector12::zeros();
        let mut hess = Matrix12::zeros();
        for i in 0..12 {
            let mut xp = *x;
            xp[i] += h;
            let mut xm = *x;
            xm[i] -= h;
            let (fp, fm) = (f(&xp), f(&xm));
            grad[i] = (fp.value - fm.value) / (2.0 * h);
            hess.set_column(i, &((fp.gradient - fm.gradient) / (2.0 * h)));
        }
        let gs = d.gradient.amax().max(floor);
        let hs = d.hessian.amax().max(floor);
        let ge = (grad - d.gradient).amax();
        let he = (hess - d.hessian).amax();
        assert!(
            ge <= tol * gs,
            "gradient error {ge:e} (scale {gs:e}) at {x}"
        );
        assert!(he <= tol * hs, "Hessian error {he:e} (scale {hs:e}) at {x}");
        let asym = (d.hessian - d.hessian.transpose()).amax();
        assert!(asym <= 1e-12 * hs, "asymmetric Hessian");
    }

    fn pt(x: &Vector12) -> Derivatives {
        let [p, a, b, c] = unstack(x);
        point_triangle_squared(p, a, b, c)
    }

    fn ee(x: &Vector12) -> Derivatives {
        let [a0, a1, b0, b1] = unstack(x);
        edge_edge_squared(a0, a1, b0, b1)
    }

    /// A triangle with no angle below ~10°.
    pub(crate) fn triangle(rng: &mut Rng) -> [Vec3; 3] {
        loop {
            let t = [rng.vec3(1.0), rng.vec3(1.0), rng.vec3(1.0)];
            let ok = (0..3).all(|i| {
                let (u, v) = (t[(i + 1) % 3] - t[i], t[(i + 2) % 3] - t[i]);
                u.cross(&v).norm() > 0.2 * u.norm() * v.norm()
            });
            if ok {
                return t;
            }
        }
    }

    /// A point in the face, an edge or a vertex region (`kind` 0, 1, 2).
    pub(crate) fn point_triangle_config(rng: &mut Rng, kind: usize) -> [Vec3; 4] {
        let [a, b, c] = triangle(rng);
        let n = (b - a).cross(&(c - a)).normalize();
        let h = rng.uniform(-1.0, 1.0);
        let p = match kind {
            0 => {
                let beta = rng.uniform(0.1, 0.8);
                let gamma = rng.uniform(0.05, 0.9 - beta);
                a + beta * (b - a) + gamma * (c - a) + h * n
            }
            1 => {
                let q = a + rng.uniform(0.1, 0.9) * (b - a);
                let mut out = (b - a).cross(&n).normalize();
                if out.dot(&(c - q)) > 0.0 {
                    out = -out;
                }
                q + rng.uniform(0.05, 1.0) * out + h * n
            }
            _ => {
                let out = -((b - a).normalize() + (c - a).normalize()).normalize();
                a + rng.uniform(0.05, 1.0) * out + h * n
            }
        };
        [p, a, b, c]
    }

    /// Skew edges whose closest points are interior.
    pub(crate) fn skew_edges(rng: &mut Rng, min_sin: f64) -> [Vec3; 4] {
        loop {
            let (e0, e1) = (rng.vec3(1.0), rng.vec3(1.0));
            let n = e0.cross(&e1);
            if e0.norm() < 0.3 || e1.norm() < 0.3 || n.norm() < min_sin * e0.norm() * e1.norm() {
                continue;
            }
            let qa = rng.vec3(1.0);
            let qb = qa - rng.sign() * rng.uniform(0.01, 1.0) * n.normalize();
            let a0 = qa - rng.uniform(0.1, 0.9) * e0;
            let b0 = qb - rng.uniform(0.1, 0.9) * e1;
            return [a0, a0 + e0, b0, b0 + e1];
        }
    }

    /// An endpoint against an edge interior (`interior`) or against an
    /// endpoint, shuffled by the pair's symmetries.
    pub(crate) fn endpoint_edges(rng: &mut Rng, interior: bool) -> [Vec3; 4] {
        loop {
            let (b0, e1) = (rng.vec3(1.0), rng.vec3(1.0));
            let mut u = rng.vec3(1.0);
            let e0 = rng.vec3(1.0);
            if interior {
                u -= e1 * (u.dot(&e1) / e1.norm_squared());
            }
            let margin = 0.2 * u.norm();
            if e1.norm() < 0.3 || u.norm() < 0.05 || e0.dot(&u) < margin * e0.norm() {
                continue;
            }
            if !interior && e1.dot(&u) > -margin * e1.norm() {
                continue;
            }
            let base = if interior {
                b0 + rng.uniform(0.1, 0.9) * e1
            } else {
                b0
            };
            let a0 = base + u;
            let mut x = [a0, a0 + e0, b0, b0 + e1];
            if rng.sign() > 0.0 {
                x.swap(0, 1);
            }
            if rng.sign() > 0.0 {
                x.swap(2, 3);
            }
            if rng.sign() > 0.0 {
                x = [x[2], x[3], x[0], x[1]];
            }
            return x;
        }
    }

    /// Edges at angle `θ ≈ angle` (`0` for parallel); `overlap` puts them side
    /// by side, otherwise end to end.
    pub(crate) fn near_parallel_edges(rng: &mut Rng, angle: f64, overlap: bool) -> [Vec3; 4] {
        let e0 = rng.unit() * rng.uniform(0.5, 1.5);
        let mut v = rng.unit();
        v -= e0 * (v.dot(&e0) / e0.norm_squared());
        let v = v.normalize();
        let e1 = (e0.normalize() + angle * v).normalize() * rng.uniform(0.5, 1.5) * rng.sign();
        let a0 = rng.vec3(1.0);
        let side = rng.uniform(0.05, 0.5) * v.cross(&e0).normalize();
        let along = if overlap {
            0.5 * e0
        } else {
            (1.2 + 0.5 * e1.norm() / e0.norm()) * e0
        };
        let mid = a0 + along + side;
        [a0, a0 + e0, mid - 0.5 * e1, mid + 0.5 * e1]
    }

    #[test]
    fn point_triangle_derivatives_match_finite_differences_in_every_region() {
        let mut rng = Rng::new(1);
        for kind in 0..3 {
            for _ in 0..30 {
                let x = point_triangle_config(&mut rng, kind);
                check_derivatives(pt, &stack(&x), 1e-6, 1e-6, 1.0);
            }
        }
    }

    #[test]
    fn edge_edge_derivatives_match_finite_differences_for_skew_edges() {
        let mut rng = Rng::new(2);
        for _ in 0..50 {
            let x = skew_edges(&mut rng, 0.2);
            check_derivatives(ee, &stack(&x), 1e-6, 1e-6, 1.0);
        }
    }

    #[test]
    fn edge_edge_derivatives_match_finite_differences_at_endpoints() {
        let mut rng = Rng::new(3);
        for interior in [true, false] {
            for _ in 0..40 {
                let x = endpoint_edges(&mut rng, interior);
                check_derivatives(ee, &stack(&x), 1e-6, 1e-6, 1.0);
            }
        }
    }

    #[test]
    fn edge_edge_derivatives_match_finite_differences_for_nearly_parallel_edges() {
        let mut rng = Rng::new(4);
        for _ in 0..30 {
            // Line–line type, derivatives of order 1/θ.
            let x = near_parallel_edges(&mut rng, 1e-2, true);
            check_derivatives(ee, &stack(&x), 1e-7, 1e-5, 1.0);
            // Parallel and nearly parallel end to end: endpoint–endpoint.
            for angle in [0.0, 1e-9] {
                let x = near_parallel_edges(&mut rng, angle, false);
                check_derivatives(ee, &stack(&x), 1e-6, 1e-6, 1.0);
            }
        }
    }

    #[test]
    fn parallel_edges_side_by_side_take_an_endpoint_type_with_finite_derivatives() {
        let mut rng = Rng::new(5);
        for angle in [0.0, 1e-9, 1e-7] {
            for _ in 0..20 {
                let x = near_parallel_edges(&mut rng, angle, true);
                let d = ee(&stack(&x));
                assert!(
                    d.gradient
                        .iter()
                        .chain(d.hessian.iter())
                        .all(|v| v.is_finite())
                );
                assert!(d.hessian.amax() < 1e3, "{}", d.hessian.amax());
                let w = edge_edge_closest(x[0], x[1], x[2], x[3]).weights;
                let endpoint = w.iter().any(|&v| v.abs() >= 1.0);
                assert!(endpoint, "{w:?}");
            }
        }
    }

    fn brute_force(x: &[Vec3; 4], triangle: bool) -> (f64, Vec3) {
        const N: usize = 300;
        let mut best = (f64::INFINITY, Vec3::zeros());
        for i in 0..=N {
            for j in 0..=N {
                let (u, v) = (i as f64 / N as f64, j as f64 / N as f64);
                let r = if triangle {
                    if i + j > N {
                        continue;
                    }
                    x[0] - (x[1] + u * (x[2] - x[1]) + v * (x[3] - x[1]))
                } else {
                    x[0] + u * (x[1] - x[0]) - (x[2] + v * (x[3] - x[2]))
                };
                if r.norm_squared() < best.0 {
                    best = (r.norm_squared(), r);
                }
            }
        }
        best
    }

    fn check_against_brute_force(x: &[Vec3; 4], triangle: bool) {
        let closest = if triangle {
            point_triangle_closest(x[0], x[1], x[2], x[3])
        } else {
            edge_edge_closest(x[0], x[1], x[2], x[3])
        };
        let w = closest.weights;
        let r: Vec3 = (0..4).map(|k| w[k] * x[k]).sum();
        assert!((r.norm_squared() - closest.squared).abs() <= 1e-12);
        let (sq, rb) = brute_force(x, triangle);
        // The grid is within δ of any point of the primitives; |r − r*|² ≤
        // d²(r) − d*² for the projection of 0 onto a convex set.
        let spacing = (0..4).map(|k| x[k].norm()).sum::<f64>() * 2.0 / 300.0;
        let d = closest.squared.sqrt();
        assert!(closest.squared <= sq + 1e-12, "{} > {sq}", closest.squared);
        assert!(sq <= closest.squared + 2.0 * d * spacing + spacing * spacing);
        assert!((r - rb).norm() <= (2.0 * d * spacing + spacing * spacing).sqrt() + 1e-9);
        if triangle {
            assert!((w[0] - 1.0).abs() < 1e-15 && (w[1] + w[2] + w[3] + 1.0).abs() < 1e-12);
            assert!(w[1..].iter().all(|&v| (-1.0..=0.0).contains(&v)));
        } else {
            assert!((w[0] + w[1] - 1.0).abs() < 1e-12 && (w[2] + w[3] + 1.0).abs() < 1e-12);
            assert!(w[..2].iter().all(|&v| (0.0..=1.0).contains(&v)));
            assert!(w[2..].iter().all(|&v| (-1.0..=0.0).contains(&v)));
        }
    }

    #[test]
    fn closest_points_match_brute_force_minimisation() {
        let mut rng = Rng::new(6);
        for i in 0..60 {
            let pt = if i < 15 {
                [rng.vec3(1.0), rng.vec3(1.0), rng.vec3(1.0), rng.vec3(1.0)]
            } else {
                point_triangle_config(&mut rng, i % 3)
            };
            check_against_brute_force(&pt, true);
            let ee = match i % 5 {
                0 => [rng.vec3(1.0), rng.vec3(1.0), rng.vec3(1.0), rng.vec3(1.0)],
                1 => skew_edges(&mut rng, 0.2),
                2 => endpoint_edges(&mut rng, i % 2 == 0),
                3 => near_parallel_edges(&mut rng, 0.0, true),
                _ => near_parallel_edges(&mut rng, 1e-9, i % 2 == 0),
            };
            check_against_brute_force(&ee, false);
        }
    }

    #[test]
    fn squared_distance_value_equals_closest_squared() {
        let mut rng = Rng::new(7);
        for _ in 0..200 {
            let x = [rng.vec3(1.0), rng.vec3(1.0), rng.vec3(1.0), rng.vec3(1.0)];
            let c = point_triangle_closest(x[0], x[1], x[2], x[3]);
            assert!((pt(&stack(&x)).value - c.squared).abs() <= 1e-15 * c.squared);
            let c = edge_edge_closest(x[0], x[1], x[2], x[3]);
            assert!((ee(&stack(&x)).value - c.squared).abs() <= 1e-15 * c.squared);
        }
    }

    /// The value-only distances are the closest points' squared distances
    /// bit for bit, on general configurations and on the ones that take
    /// each branch: every region of a triangle, skew, touching and
    /// (nearly) parallel edges, and degenerate primitives.
    #[test]
    fn value_only_squared_distances_are_the_closest_points_bit_for_bit() {
        let mut rng = Rng::new(9);
        let same = |x: &[Vec3; 4]| {
            let [p, a, b, c] = *x;
            assert_eq!(
                point_triangle_squared_distance(p, a, b, c).to_bits(),
                point_triangle_closest(p, a, b, c).squared.to_bits(),
                "{x:?}"
            );
            assert_eq!(
                edge_edge_squared_distance(p, a, b, c).to_bits(),
                edge_edge_closest(p, a, b, c).squared.to_bits(),
                "{x:?}"
            );
        };
        for i in 0..600 {
            same(&[rng.vec3(1.0), rng.vec3(1.0), rng.vec3(1.0), rng.vec3(1.0)]);
            same(&point_triangle_config(&mut rng, i % 3));
            same(&skew_edges(&mut rng, 0.2));
            same(&endpoint_edges(&mut rng, i % 2 == 0));
            same(&near_parallel_edges(&mut rng, 0.0, true));
            same(&near_parallel_edges(&mut rng, 1e-9, i % 2 == 0));
            let [p, a, b] = [rng.vec3(1.0), rng.vec3(1.0), rng.vec3(1.0)];
            let t = rng.uniform(-0.5, 1.5);
            for x in [
                [p, a, b, a + t * (b - a)],
                [p, a, a, a],
                [p, p, a, b],
                [p, a, b, b],
                [p, p, a, a],
            ] {
                same(&x);
            }
        }
    }

    #[test]
    fn degenerate_primitives_give_finite_derivatives_and_true_distances() {
        let mut rng = Rng::new(8);
        for _ in 0..20 {
            let [p, a, b] = [rng.vec3(1.0), rng.vec3(1.0), rng.vec3(1.0)];
            let t = rng.uniform(-0.5, 1.5);
            let cases = [
                [p, a, b, a + t * (b - a)], // flat triangle
                [p, a, a, a],               // triangle collapsed to a point
                [p, p, a, b],               // zero-length first edge
                [p, a, b, b],               // zero-length second edge
                [p, p, a, a],               // both
            ];
            for (i, x) in cases.iter().enumerate() {
                let tri = i < 2;
                let d = if tri { pt(&stack(x)) } else { ee(&stack(x)) };
                assert!(d.value.is_finite());
                assert!(
                    d.gradient
                        .iter()
                        .chain(d.hessian.iter())
                        .all(|v| v.is_finite())
                );
                check_against_brute_force(x, tri);
            }
        }
    }

    #[test]
    fn mollifier_derivatives_match_finite_differences() {
        let mut rng = Rng::new(9);
        let mollifier = |x: &Vector12, eps: f64| {
            let [a0, a1, b0, b1] = unstack(x);
            edge_edge_mollifier(a0, a1, b0, b1, eps)
        };
        for _ in 0..40 {
            let (angle, overlap) = (rng.uniform(0.005, 0.03), rng.sign() > 0.0);
            let x = near_parallel_edges(&mut rng, angle, overlap);
            let eps = mollifier_threshold(x[0], x[1], x[2], x[3]);
            let m = mollifier(&stack(&x), eps);
            assert!(m.value > 0.0 && m.value < 1.0, "{}", m.value);
            let scale = 1.0 / eps;
            check_derivatives(|y| mollifier(y, eps), &stack(&x), 1e-7, 1e-5, scale);
        }
    }

    #[test]
    fn mollifier_is_one_with_zero_derivatives_above_its_threshold() {
        let mut rng = Rng::new(10);
        let x = skew_edges(&mut rng, 0.5);
        let eps = mollifier_threshold(x[0], x[1], x[2], x[3]);
        let m = edge_edge_mollifier(x[0], x[1], x[2], x[3], eps);
        assert_eq!(m, Derivatives::constant(1.0));
        // C¹ at c = ε: m → 1 and m' → 0 from below.
        let (a0, a1, b0) = (Vec3::zeros(), Vec3::x(), Vec3::new(0.0, 0.0, 1.0));
        let b1 = b0 + Vec3::new(1.0, 1e-3, 0.0);
        let c = (a1 - a0).cross(&(b1 - b0)).norm_squared();
        let below = edge_edge_mollifier(a0, a1, b0, b1, c * (1.0 + 1e-9));
        let half = edge_edge_mollifier(a0, a1, b0, b1, 2.0 * c);
        assert!((below.value - 1.0).abs() < 1e-12);
        assert!(below.gradient.amax() <= 1e-8 * half.gradient.amax());
    }
}
