//! Triangle–triangle intersection, for reports: how many pairs of a mesh's
//! triangles pass through (or touch) each other.
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
//! projected onto a coordinate plane. A determinant within its rounding
//! error bound of zero counts as zero (the sign is then not known), so
//! every sign the tests use is the exact one of the inputs, and the
//! degenerate cases — an end on a plane, points on one line — are decided
//! by planar tests and extents instead of by signs that rounding chose:
//! on a flat face a few ulps out of plane, as a falling body's is, those
//! signs made triangles that do not touch look crossed. The answer can
//! then only be wrong for points within rounding of touching. No
//! divisions, no intersection points.
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

/// `(a − d)·((b − d) × (c − d))`, six times the signed volume of `abcd`,
/// or 0 where rounding could have given it its sign: where it is at most
/// `8ε ‖a − d‖₁ ‖b − d‖₁ ‖c − d‖₁`, above Shewchuk's bound `(7ε + 56ε²)`
/// times the sum of its terms' magnitudes (*Adaptive precision
/// floating-point arithmetic and fast robust geometric predicates*, 1997;
/// his `ε` is half of `f64::EPSILON`).
fn orient(a: Vec3, b: Vec3, c: Vec3, d: Vec3) -> f64 {
    let (x, y, z) = (a - d, b - d, c - d);
    let det = x.dot(&y.cross(&z));
    let bound = 8.0 * f64::EPSILON * x.lp_norm(1) * y.lp_norm(1) * z.lp_norm(1);
    if det.abs() <= bound { 0.0 } else { det }
}

/// Whether the closed segment `pq` meets the closed triangle `abc`.
///
/// A segment whose box does not touch the triangle's misses it. A triangle
/// whose corners lie on one line has no plane: the segment meets it only
/// if the two lie in one plane, and then where they meet in it. Otherwise,
/// with `s_p = orient(a, b, c, p)` and `s_q` likewise (0 where rounding
/// could have given the sign, see [`orient`]): ends strictly on one side
/// of the plane miss it; an end on the plane meets the triangle where it
/// lies in it (a planar test), and a segment in the plane where it meets
/// it in the plane. Otherwise the segment crosses the plane at one point,
/// which is in the triangle when `orient(p, q, a, b)`, `orient(p, q, b, c)`
/// and `orient(p, q, c, a)` do not have opposite signs (the line passes on
/// the same side of all three sides, or on one of them; all three 0 only
/// where rounding hides the triangle's area, tested in its plane).
///
/// Nearly coplanar points are why the zeros are certified and the ends on
/// the plane tested in it: an end a few ulps off the plane of a flat
/// body's face made the line's orientations with the sides rounding noise,
/// and triangles of a falling lattice's face that do not touch were
/// reported intersecting.
fn segment_meets_triangle(p: Vec3, q: Vec3, [a, b, c]: [Vec3; 3]) -> bool {
    let (lo, hi) = (p.inf(&q), p.sup(&q));
    let (low, high) = (a.inf(&b).inf(&c), a.sup(&b).sup(&c));
    if (0..3).any(|k| hi[k] < low[k] || high[k] < lo[k]) {
        return false;
    }
    let triangle = [a, b, c];
    if collinear(a, b, c) {
        // A triangle on a line has no plane: the segment meets it only in
        // a plane with that line (skew lines never meet).
        let [e0, e1] = longest_side(triangle);
        return orient(p, q, e0, e1) == 0.0 && coplanar_segment_triangle(p, q, triangle);
    }
    let (sp, sq) = (orient(a, b, c, p), orient(a, b, c, q));
    match (sp == 0.0, sq == 0.0) {
        _ if (sp > 0.0 && sq > 0.0) || (sp < 0.0 && sq < 0.0) => false,
        (true, true) => coplanar_segment_triangle(p, q, triangle),
        (true, false) => coplanar_segment_triangle(p, p, triangle),
        (false, true) => coplanar_segment_triangle(q, q, triangle),
        (false, false) => {
            let (u, v, w) = (orient(p, q, a, b), orient(p, q, b, c), orient(p, q, c, a));
            if u == 0.0 && v == 0.0 && w == 0.0 {
                return coplanar_segment_triangle(p, q, triangle);
            }
            (u >= 0.0 && v >= 0.0 && w >= 0.0) || (u <= 0.0 && v <= 0.0 && w <= 0.0)
        }
    }
}

/// Whether `a`, `b` and `c` lie on one line as far as rounding tells: every
/// component of `(b − a) × (c − a)` within the rounding bound of
/// [`orient2`], whose coordinate-plane determinants they are.
fn collinear(a: Vec3, b: Vec3, c: Vec3) -> bool {
    let (u, v) = (b - a, c - a);
    u.cross(&v).amax() <= 4.0 * f64::EPSILON * u.lp_norm(1) * v.lp_norm(1)
}

/// The ends of the triangle's longest side.
fn longest_side([a, b, c]: [Vec3; 3]) -> [Vec3; 2] {
    [[a, b], [b, c], [c, a]]
        .into_iter()
        .max_by(|[p, q], [r, s]| (q - p).norm_squared().total_cmp(&(s - r).norm_squared()))
        .expect("three sides")
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

/// `(a − c) ⨯ (b − c)`, twice the signed area of `abc`, or 0 where
/// rounding could have given it its sign: at most
/// `4ε ‖a − c‖₁ ‖b − c‖₁`, above Shewchuk's bound `(3ε + 16ε²)` times the
/// sum of its terms' magnitudes (see [`orient`]).
fn orient2(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    let (x, y) = ([a[0] - c[0], a[1] - c[1]], [b[0] - c[0], b[1] - c[1]]);
    let det = x[0] * y[1] - x[1] * y[0];
    let bound = 4.0 * f64::EPSILON * (x[0].abs() + x[1].abs()) * (y[0].abs() + y[1].abs());
    if det.abs() <= bound { 0.0 } else { det }
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

/// Whether the closed planar segments `pq` and `rs` meet: their boxes
/// overlap, and either each one's ends lie strictly on both sides of the
/// other's line, or an end lies on the other's line within the other's
/// extent (Cormen et al., *Introduction to Algorithms*, §33.1). An end on
/// the other's line is not enough by itself: two collinear segments far
/// apart have it, and rounding then gives the other ends' orientations
/// any sign.
fn segments_meet(p: [f64; 2], q: [f64; 2], r: [f64; 2], s: [f64; 2]) -> bool {
    let within = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
        (0..2).all(|k| a[k].min(b[k]) <= c[k] && c[k] <= a[k].max(b[k]))
    };
    let overlap =
        (0..2).all(|k| p[k].min(q[k]) <= r[k].max(s[k]) && r[k].min(s[k]) <= p[k].max(q[k]));
    if !overlap {
        return false;
    }
    let (o1, o2) = (orient2(p, q, r), orient2(p, q, s));
    let (o3, o4) = (orient2(r, s, p), orient2(r, s, q));
    let across = |x: f64, y: f64| (x > 0.0 && y < 0.0) || (x < 0.0 && y > 0.0);
    (across(o1, o2) && across(o3, o4))
        || (o1 == 0.0 && within(p, q, r))
        || (o2 == 0.0 && within(p, q, s))
        || (o3 == 0.0 && within(r, s, p))
        || (o4 == 0.0 && within(r, s, q))
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
    intersecting(mesh, x).len()
}

/// The intersecting pairs of [`intersecting_triangle_pairs`] counted by the
/// surfaces their triangles belong to: `((g, h), count)` for every pair of
/// surfaces `g ≤ h` that has any (`g = h`: a surface passing through
/// itself), in increasing order of `(g, h)`.
///
/// ```
/// use hooke_core::Vec3;
/// use hooke_core::collision::{intersect::intersecting_triangle_pairs_by_surface, surface::CollisionMesh};
/// let flat = [Vec3::zeros(), Vec3::x(), Vec3::z()];
/// let piercing = [Vec3::new(0.2, -1.0, 0.2), Vec3::new(0.2, 1.0, 0.2), Vec3::new(0.3, 1.0, 0.25)];
/// let far = Vec3::new(5.0, 0.0, 0.0);
/// // Surfaces 0 and 1 pass through each other; surface 2, far off, through itself.
/// let mut mesh = CollisionMesh::new();
/// mesh.add_surface(&[[0, 1, 2]], true);
/// mesh.add_surface(&[[3, 4, 5]], true);
/// mesh.add_surface(&[[6, 7, 8], [9, 10, 11]], false);
/// let x: Vec<Vec3> = [flat, piercing, flat.map(|p| p + far), piercing.map(|p| p + far)]
///     .concat();
/// assert_eq!(
///     intersecting_triangle_pairs_by_surface(&mesh, &x),
///     vec![((0, 1), 1), ((2, 2), 1)]
/// );
/// ```
///
/// # Panics
/// If a particle of the mesh has no position in `x`.
#[must_use]
pub fn intersecting_triangle_pairs_by_surface(
    mesh: &CollisionMesh,
    x: &[Vec3],
) -> Vec<((usize, usize), usize)> {
    let mut counts: Vec<((usize, usize), usize)> = Vec::new();
    let mut surfaces: Vec<(usize, usize)> = intersecting(mesh, x)
        .into_iter()
        .map(|(s, t)| {
            let (g, h) = (
                mesh.triangle_group(s as usize),
                mesh.triangle_group(t as usize),
            );
            (g.min(h), g.max(h))
        })
        .collect();
    surfaces.sort_unstable();
    for pair in surfaces {
        match counts.last_mut() {
            Some((last, count)) if *last == pair => *count += 1,
            _ => counts.push((pair, 1)),
        }
    }
    counts
}

/// The pairs of the mesh's triangles at `x` that intersect, as triangle
/// indices (see [`intersecting_triangle_pairs`]).
fn intersecting(mesh: &CollisionMesh, x: &[Vec3]) -> Vec<(u32, u32)> {
    let mut pairs = Vec::new();
    BroadPhase::default().triangle_pairs(mesh, x, 0.0, &mut pairs);
    let corners = |t: u32| mesh.triangles()[t as usize].map(|p| x[p]);
    pairs.retain(|&(s, t)| triangles_intersect(corners(s), corners(t)));
    pairs
}

#[cfg(test)]
mod tests;
