//! The closest features of a pair: which region (point, line or plane
//! pair) holds the closest points, their weights and the offset `r`.

use super::Closest;
use crate::Vec3;

/// `sin²θ` below which two edges (or a triangle's two edges at `a`) count as
/// parallel.
const PARALLEL: f64 = 1e-12;

/// The free parameters of a region: `∂w/∂tⱼ` for each.
#[derive(Debug, Clone, Copy)]
pub(super) enum Region {
    Point,
    Line([f64; 4]),
    Plane([[f64; 4]; 2]),
}

/// The closest points with `r` and their region.
#[derive(Debug, Clone, Copy)]
pub(super) struct Nearest {
    pub(super) closest: Closest,
    pub(super) r: Vec3,
    pub(super) region: Region,
}

/// Point `p` against segment `(j, k)`: the parameter `t` of the line's
/// point nearest `p`, and `p − q` for the segment's nearest point `q` (that
/// point if `t ∈ (0, 1)`, otherwise `j` for `t ≤ 0` and `k` else).
pub(super) fn segment_offset(p: Vec3, j: Vec3, k: Vec3) -> (f64, Vec3) {
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
pub(super) fn face_offset(p: Vec3, a: Vec3, b: Vec3, c: Vec3) -> Option<([f64; 3], Vec3)> {
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
pub(super) fn edges_offset(a0: Vec3, a1: Vec3, b0: Vec3, b1: Vec3) -> Option<([f64; 2], Vec3)> {
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
pub(super) fn point_segment(x: &[Vec3; 4], i: usize, j: usize, k: usize, sign: f64) -> Nearest {
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
pub(super) fn nearest_of<const N: usize>(candidates: [Nearest; N]) -> Nearest {
    let mut best = candidates[0];
    for c in &candidates[1..] {
        if c.closest.squared < best.closest.squared {
            best = *c;
        }
    }
    best
}

pub(super) fn point_triangle_nearest(x: &[Vec3; 4]) -> Nearest {
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

pub(super) fn edge_edge_nearest(x: &[Vec3; 4]) -> Nearest {
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

/// `|r|²` of [`point_segment`] for point `p` and segment `(j, k)`, without
/// the weights and the region (the sign of `r` does not change its square).
pub(super) fn point_segment_squared(p: Vec3, j: Vec3, k: Vec3) -> f64 {
    segment_offset(p, j, k).1.norm_squared()
}

/// The smallest of `squared` as [`nearest_of`] picks it: the first, then
/// each later one that is smaller.
pub(super) fn least<const N: usize>(squared: [f64; N]) -> f64 {
    let mut best = squared[0];
    for &s in &squared[1..] {
        if s < best {
            best = s;
        }
    }
    best
}
