use super::*;

/// Two surfaces of a 5 × 5 grid's triangles each, every particle at a
/// pseudo-random point of the unit cube: crumpled through each other and
/// through themselves.
fn crumpled() -> (CollisionMesh, Vec<Vec3>) {
    let side = 5;
    let grid = |offset: usize| {
        let mut triangles = Vec::new();
        for r in 0..side - 1 {
            for c in 0..side - 1 {
                let p = offset + r * side + c;
                triangles.push([p, p + 1, p + side]);
                triangles.push([p + 1, p + side + 1, p + side]);
            }
        }
        triangles
    };
    let mut mesh = CollisionMesh::new();
    mesh.add_surface(&grid(0), true);
    mesh.add_surface(&grid(side * side), false);
    // xorshift64, mapped to [0, 1).
    let mut seed = 0x2545_F491_4F6C_DD1D_u64;
    let mut uniform = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let x = (0..2 * side * side)
        .map(|_| Vec3::new(uniform(), uniform(), uniform()))
        .collect();
    (mesh, x)
}

/// Two triangles of a lattice's flat face, 0.2 m apart, whose diagonals
/// lie on one line, at the coordinates a falling lattice gave them (so
/// that the orientations of their collinear corners are rounding noise):
/// they were reported intersecting.
#[test]
fn coplanar_triangles_with_collinear_sides_far_apart_do_not_intersect() {
    let y = 1.499_318_75;
    let a = [
        Vec3::new(-0.45, y, -0.15),
        Vec3::new(-0.4, y, -0.15),
        Vec3::new(-0.4, y, -0.1),
    ];
    let b = [
        Vec3::new(-0.25, y, 0.049_999_999_999_999_99),
        Vec3::new(-0.2, y, 0.049_999_999_999_999_99),
        Vec3::new(-0.2, y, 0.099_999_999_999_999_98),
    ];
    assert!(!triangles_intersect(a, b));
    assert!(!triangles_intersect(b, a));
    // The same pair moved onto each other's diagonal line does meet:
    // b's corner on a's far corner.
    let shift = a[0] - b[2];
    assert!(triangles_intersect(a, b.map(|p| p + shift)));
}

/// A flat 8 × 8 grid of triangles, moved rigidly to many places in each
/// coordinate plane as a falling body is (coordinates that are not
/// round), each particle's coordinate across the plane then moved by
/// up to one ulp either way as a step's rounding leaves it: a
/// conforming flat triangulation has no two triangles sharing no
/// particle that meet, so none may be reported, by the count or by a
/// test of every pair.
#[test]
fn a_flat_grid_moved_anywhere_has_no_intersecting_pairs() {
    let side = 8;
    let mut triangles = Vec::new();
    for r in 0..side - 1 {
        for c in 0..side - 1 {
            let p = r * side + c;
            triangles.push([p, p + 1, p + side]);
            triangles.push([p + 1, p + side + 1, p + side]);
        }
    }
    let mut mesh = CollisionMesh::new();
    mesh.add_surface(&triangles, true);
    // xorshift64: -1, 0 or 1 ulp.
    let mut seed = 0x9E37_79B9_7F4A_7C15_u64;
    let mut ulps = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed % 3) as i64 - 1
    };
    for axis in 0..3 {
        for k in 0..50 {
            let t = 0.013 * f64::from(k);
            let offset = Vec3::new(-0.47 + 0.31 * t, 1.5 - 4.905 * t * t, -0.15 + 0.7 * t);
            let x: Vec<Vec3> = (0..side * side)
                .map(|p| {
                    let (u, v) = (0.05 * (p % side) as f64, 0.05 * (p / side) as f64);
                    let mut point = Vec3::zeros();
                    point[(axis + 1) % 3] = u;
                    point[(axis + 2) % 3] = v;
                    point += offset;
                    let across = point[axis].to_bits().cast_signed() + ulps();
                    point[axis] = f64::from_bits(across.cast_unsigned());
                    point
                })
                .collect();
            assert_eq!(
                intersecting_triangle_pairs(&mesh, &x),
                0,
                "axis {axis}, t {t}"
            );
            for (s, a) in triangles.iter().enumerate() {
                for b in &triangles[s + 1..] {
                    if a.iter().any(|p| b.contains(p)) {
                        continue;
                    }
                    assert!(
                        !triangles_intersect(a.map(|p| x[p]), b.map(|p| x[p])),
                        "axis {axis}, t {t}: {a:?} {b:?}"
                    );
                }
            }
        }
    }
}

/// A triangle collapsed onto a line (as a crushed body's can be) and a
/// triangle one of whose sides passes 0.1 above that line, their boxes
/// overlapping and their projections crossing: they do not meet (the
/// line crosses the other triangle's plane outside it); moved down by
/// 0.1, that side runs through the line and they do.
#[test]
fn a_degenerate_triangle_meets_only_what_its_line_meets() {
    let line = [Vec3::zeros(), Vec3::x(), Vec3::new(0.5, 0.0, 0.0)];
    let passing = [
        Vec3::new(0.3, -1.0, 0.5),
        Vec3::new(0.7, 1.0, -0.3),
        Vec3::new(2.0, 0.0, 2.0),
    ];
    assert!(!triangles_intersect(line, passing));
    assert!(!triangles_intersect(passing, line));
    let through = passing.map(|p| p - Vec3::new(0.0, 0.0, 0.1));
    assert!(triangles_intersect(line, through));
    assert!(triangles_intersect(through, line));
}

#[test]
fn counts_by_surface_match_every_pair_tested_directly() {
    let (mesh, x) = crumpled();
    let triangles = mesh.triangles();
    let mut expected: Vec<((usize, usize), usize)> = Vec::new();
    for s in 0..triangles.len() {
        for t in s + 1..triangles.len() {
            let (a, b) = (triangles[s], triangles[t]);
            if a.iter().any(|p| b.contains(p)) {
                continue;
            }
            if triangles_intersect(a.map(|p| x[p]), b.map(|p| x[p])) {
                let (g, h) = (mesh.triangle_group(s), mesh.triangle_group(t));
                let key = (g.min(h), g.max(h));
                match expected.iter_mut().find(|(k, _)| *k == key) {
                    Some((_, count)) => *count += 1,
                    None => expected.push((key, 1)),
                }
            }
        }
    }
    expected.sort_unstable();
    // Both surfaces pass through themselves and through each other.
    assert_eq!(expected.len(), 3, "{expected:?}");
    assert_eq!(intersecting_triangle_pairs_by_surface(&mesh, &x), expected);
    let total: usize = expected.iter().map(|(_, count)| count).sum();
    assert_eq!(intersecting_triangle_pairs(&mesh, &x), total);
}
