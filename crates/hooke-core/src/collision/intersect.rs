//! Exact triangle–triangle intersection, for reports: how many pairs of a
//! mesh's triangles pass through (or touch) each other.
//!
//! The test uses only the signs of orientation determinants,
//!
//! ```text
//! orient(a, b, c, d) = (a − d) · ((b − d) × (c − d)),
//! ```
//!
//! six times the signed volume of the tetrahedron `abcd` (positive when `d`
//! lies below the plane of `abc` seen counter-clockwise), and their planar
//! counterparts `orient₂(a, b, c) = (a − c) ⨯ (b − c)` for coplanar points
//! projected onto a coordinate plane. The decisions are exact for the
//! computed signs: the answer is wrong only where a determinant's rounding
//! flips its sign, i.e. within a few ulps of touching. No divisions, no
//! tolerances, no intersection points.
//!
//! Two closed triangles share a point exactly when a side of one meets the
//! other: if they are not coplanar, their intersection is a segment of the
//! line where their planes meet whose ends lie on sides of one or the other
//! triangle; if they are coplanar, either sides cross or one triangle holds
//! the other, sides included. So [`triangles_intersect`] runs six closed
//! segment–triangle tests.

use crate::Vec3;

use super::broad::BroadPhase;
use super::surface::CollisionMesh;

/// `(a − d)·((b − d) × (c − d))`, six times the signed volume of `abcd`.
fn orient(a: Vec3, b: Vec3, c: Vec3, d: Vec3) -> f64 {
    (a - d).dot(&(b - d).cross(&(c - d)))
}

/// Whether the closed segment `pq` meets the closed triangle `abc`.
///
/// With `s_p = orient(a, b, c, p)` and `s_q` likewise: ends strictly on one
/// side of the plane miss it. Otherwise, if one of them is not zero, the
/// line `pq` crosses the plane at one point, which is in the triangle when
/// `orient(p, q, a, b)`, `orient(p, q, b, c)`, `orient(p, q, c, a)` do not
/// have opposite signs (the line passes on the same side of all three sides,
/// or on one of them). If both are zero the segment lies in the plane of the
/// triangle (or the triangle is degenerate) and the test is planar.
fn segment_meets_triangle(p: Vec3, q: Vec3, [a, b, c]: [Vec3; 3]) -> bool {
    let (sp, sq) = (orient(a, b, c, p), orient(a, b, c, q));
    if (sp > 0.0 && sq > 0.0) || (sp < 0.0 && sq < 0.0) {
        return false;
    }
    if sp != 0.0 || sq != 0.0 {
        let (u, v, w) = (orient(p, q, a, b), orient(p, q, b, c), orient(p, q, c, a));
        return (u >= 0.0 && v >= 0.0 && w >= 0.0) || (u <= 0.0 && v <= 0.0 && w <= 0.0);
    }
    coplanar_segment_triangle(p, q, [a, b, c])
}

/// Whether the segment `pq` meets the triangle `abc`, all five points in
/// one plane (or on one line). They are projected onto the coordinate plane
/// across the largest component of a normal of their plane (the largest of
/// the cross products of their spans), which keeps every orientation's
/// sign; if all are on one line, onto a coordinate plane not across that
/// line.
fn coplanar_segment_triangle(p: Vec3, q: Vec3, [a, b, c]: [Vec3; 3]) -> bool {
    let spans = [b - a, c - a, c - b, q - p, p - a, q - a];
    let mut normal = Vec3::zeros();
    for (i, s) in spans.iter().enumerate() {
        for t in &spans[i + 1..] {
            let n = s.cross(t);
            if n.amax() > normal.amax() {
                normal = n;
            }
        }
    }
    let drop = if normal.amax() > 0.0 {
        normal.iamax()
    } else {
        // All on one line: drop an axis across which the line does not run.
        let along = spans.iter().fold(
            Vec3::zeros(),
            |m, s| if s.amax() > m.amax() { *s } else { m },
        );
        (along.iamax() + 1) % 3
    };
    let (i, j) = ((drop + 1) % 3, (drop + 2) % 3);
    let flat = |v: Vec3| [v[i], v[j]];
    let ([p, q], [a, b, c]) = ([p, q].map(flat), [a, b, c].map(flat));
    point_in_triangle(p, [a, b, c])
        || point_in_triangle(q, [a, b, c])
        || segments_meet(p, q, a, b)
        || segments_meet(p, q, b, c)
        || segments_meet(p, q, c, a)
}

/// `(a − c) ⨯ (b − c)`, twice the signed area of `abc`.
fn orient2(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (a[0] - c[0]) * (b[1] - c[1]) - (a[1] - c[1]) * (b[0] - c[0])
}

/// Whether `p` lies in the closed planar triangle `abc`: on no strict
/// outside of a side, for a triangle of non-zero area (a degenerate one is
/// left to the side tests of the caller).
fn point_in_triangle(p: [f64; 2], [a, b, c]: [[f64; 2]; 3]) -> bool {
    if orient2(a, b, c) == 0.0 {
        return false;
    }
    let (u, v, w) = (orient2(a, b, p), orient2(b, c, p), orient2(c, a, p));
    (u >= 0.0 && v >= 0.0 && w >= 0.0) || (u <= 0.0 && v <= 0.0 && w <= 0.0)
}

/// Whether the closed planar segments `pq` and `rs` meet: each one's ends
/// not strictly on one side of the other's line, and if all four points are
/// on one line, their extents overlapping.
fn segments_meet(p: [f64; 2], q: [f64; 2], r: [f64; 2], s: [f64; 2]) -> bool {
    let (o1, o2) = (orient2(p, q, r), orient2(p, q, s));
    let (o3, o4) = (orient2(r, s, p), orient2(r, s, q));
    let apart = |x: f64, y: f64| (x > 0.0 && y > 0.0) || (x < 0.0 && y < 0.0);
    if apart(o1, o2) || apart(o3, o4) {
        return false;
    }
    if o1 != 0.0 || o2 != 0.0 || o3 != 0.0 || o4 != 0.0 {
        return true;
    }
    // Collinear: the boxes must overlap.
    (0..2).all(|k| p[k].min(q[k]) <= r[k].max(s[k]) && r[k].min(s[k]) <= p[k].max(q[k]))
}

/// Whether two closed triangles intersect (share a point), exactly where
/// floating point allows: true when a side of one meets the other triangle
/// (segment–triangle tests with orientation determinants, see the
/// [module documentation](self)); coplanar overlaps, and triangles that
/// only touch, count. Degenerate triangles (collinear corners) are their
/// longest side. Triangles that share a vertex are the caller's to exclude.
///
/// ```
/// use hooke_core::{Vec3, collision::intersect::triangles_intersect};
/// let flat = [Vec3::zeros(), Vec3::x(), Vec3::z()];
/// let piercing = [Vec3::new(0.2, -1.0, 0.2), Vec3::new(0.2, 1.0, 0.2), Vec3::new(0.3, 1.0, 0.25)];
/// assert!(triangles_intersect(flat, piercing));
/// let above = piercing.map(|p| p + Vec3::new(0.0, 0.0, 1.0));
/// assert!(!triangles_intersect(flat, above));
/// ```
#[must_use]
pub fn triangles_intersect(a: [Vec3; 3], b: [Vec3; 3]) -> bool {
    (0..3).any(|e| segment_meets_triangle(a[e], a[(e + 1) % 3], b))
        || (0..3).any(|e| segment_meets_triangle(b[e], b[(e + 1) % 3], a))
}

/// The number of pairs of the mesh's triangles at the positions `x` that
/// intersect ([`triangles_intersect`]), over all pairs not sharing a
/// particle — within a surface as well as between surfaces, whatever the
/// self-collision setting: a report of interpenetration.
///
/// The candidates are the pairs whose boxes touch
/// ([`BroadPhase::triangle_pairs`] at distance 0); a pair that shares a
/// point has touching boxes.
///
/// # Panics
/// If a particle of the mesh has no position in `x`.
#[must_use]
pub fn intersecting_triangle_pairs(mesh: &CollisionMesh, x: &[Vec3]) -> usize {
    let mut pairs = Vec::new();
    BroadPhase::default().triangle_pairs(mesh, x, 0.0, &mut pairs);
    let corners = |t: u32| mesh.triangles()[t as usize].map(|p| x[p]);
    pairs
        .iter()
        .filter(|&&(s, t)| triangles_intersect(corners(s), corners(t)))
        .count()
}
