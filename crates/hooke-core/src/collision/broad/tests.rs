use super::*;
use crate::collision::distance::tests::Rng;

/// A flat `n × n` grid cloth of the given spacing in the plane `z = 0`,
/// two triangles per square.
pub(crate) fn cloth(n: usize, spacing: f64) -> (Vec<Vec3>, Vec<[usize; 3]>) {
    let x = (0..n * n)
        .map(|p| Vec3::new((p % n) as f64, (p / n) as f64, 0.0) * spacing)
        .collect();
    let triangles = (0..n - 1)
        .flat_map(|j| (0..n - 1).map(move |i| j * n + i))
        .flat_map(|p| [[p, p + 1, p + n + 1], [p, p + n + 1, p + n]])
        .collect();
    (x, triangles)
}

/// Folds a cloth of `cloth` about the line `x = at` over a half cylinder
/// of `radius`; beyond the fold the sheet comes back at height `2 r`,
/// sinking by `dip` per unit length (through the lower sheet if
/// `dip > 0`).
pub(crate) fn fold(x: &mut [Vec3], at: f64, radius: f64, dip: f64) {
    for p in x {
        let s = p.x - at;
        if s <= 0.0 {
            continue;
        }
        let arc = std::f64::consts::PI * radius;
        let (u, z) = if s < arc {
            (
                radius * (s / radius).sin(),
                radius * (1.0 - (s / radius).cos()),
            )
        } else {
            (-(s - arc), 2.0 * radius - dip * (s - arc))
        };
        *p = Vec3::new(at + u, p.y, z);
    }
}

/// A random triangle soup: `count` triangles of particles `first..`, on
/// a random walk of steps `step` in the cube `[0, 1]³`, each triangle of
/// a particle and two of the next few (so triangles share particles).
pub(crate) fn soup(
    rng: &mut Rng,
    first: usize,
    count: usize,
    step: f64,
) -> (Vec<Vec3>, Vec<[usize; 3]>) {
    let particles = count + 8;
    let mut at = Vec3::new(
        rng.uniform(0.0, 1.0),
        rng.uniform(0.0, 1.0),
        rng.uniform(0.0, 1.0),
    );
    let x: Vec<Vec3> = (0..particles)
        .map(|_| {
            at = (at + rng.vec3(1.0) * step).map(|c| c.clamp(0.0, 1.0));
            at
        })
        .collect();
    let triangles = (0..count)
        .map(|i| {
            let j = i + 1 + rng.below(3);
            let k = j + 1 + rng.below(3);
            [i, j, k].map(|p| p + first)
        })
        .collect();
    (x, triangles)
}

fn box_of(points: &[usize], x0: &[Vec3], x1: &[Vec3], distance: f64) -> [Vec3; 2] {
    let lo = points.iter().fold(Vec3::repeat(f64::INFINITY), |m, &p| {
        m.inf(&x0[p]).inf(&x1[p])
    });
    let hi = points
        .iter()
        .fold(Vec3::repeat(f64::NEG_INFINITY), |m, &p| {
            m.sup(&x0[p]).sup(&x1[p])
        });
    [
        lo.add_scalar(-0.5 * distance),
        hi.add_scalar(0.5 * distance),
    ]
}

fn boxes_overlap(a: &[Vec3; 2], b: &[Vec3; 2]) -> bool {
    (0..3).all(|k| a[0][k] <= b[1][k] && b[0][k] <= a[1][k])
}

fn shares(p: &[usize], q: &[usize]) -> bool {
    p.iter().any(|i| q.contains(i))
}

/// Every admissible pair whose boxes overlap, by testing all pairs.
fn brute(mesh: &CollisionMesh, x0: &[Vec3], x1: &[Vec3], distance: f64) -> Candidates {
    let vb: Vec<_> = mesh
        .vertices()
        .iter()
        .map(|&p| box_of(&[p], x0, x1, distance))
        .collect();
    let eb: Vec<_> = mesh
        .edges()
        .iter()
        .map(|e| box_of(e, x0, x1, distance))
        .collect();
    let tb: Vec<_> = mesh
        .triangles()
        .iter()
        .map(|t| box_of(t, x0, x1, distance))
        .collect();
    let mut out = Candidates::default();
    for (v, &p) in mesh.vertices().iter().enumerate() {
        for (t, tri) in mesh.triangles().iter().enumerate() {
            if !tri.contains(&p)
                && mesh.collides(mesh.vertex_group(v), mesh.triangle_group(t))
                && boxes_overlap(&vb[v], &tb[t])
            {
                out.point_triangle.push((v as u32, t as u32));
            }
        }
    }
    for (e, a) in mesh.edges().iter().enumerate() {
        for (f, b) in mesh.edges().iter().enumerate().skip(e + 1) {
            if !shares(a, b)
                && mesh.collides(mesh.edge_group(e), mesh.edge_group(f))
                && boxes_overlap(&eb[e], &eb[f])
            {
                out.edge_edge.push((e as u32, f as u32));
            }
        }
    }
    out
}

/// The squared distance from `p` to the triangle `abc` (Ericson,
/// *Real-Time Collision Detection*, §5.1.5).
fn point_triangle(p: Vec3, [a, b, c]: [Vec3; 3]) -> f64 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(&ap), ac.dot(&ap));
    let closest = if d1 <= 0.0 && d2 <= 0.0 {
        a
    } else {
        let bp = p - b;
        let (d3, d4) = (ab.dot(&bp), ac.dot(&bp));
        let cp = p - c;
        let (d5, d6) = (ab.dot(&cp), ac.dot(&cp));
        let (va, vb, vc) = (d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2);
        if d3 >= 0.0 && d4 <= d3 {
            b
        } else if d6 >= 0.0 && d5 <= d6 {
            c
        } else if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
            a + ab * (d1 / (d1 - d3))
        } else if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
            a + ac * (d2 / (d2 - d6))
        } else if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
            b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))
        } else {
            let s = 1.0 / (va + vb + vc);
            a + ab * (vb * s) + ac * (vc * s)
        }
    };
    (p - closest).norm_squared()
}

/// The squared distance between the segments `p0p1` and `q0q1`: the
/// least over a fine sampling of one segment of the distance to the
/// other (the closest point on a segment by projection), refined.
fn segment_segment(p0: Vec3, p1: Vec3, q0: Vec3, q1: Vec3) -> f64 {
    let to_q = |p: Vec3| {
        let d = q1 - q0;
        let t = if d.norm_squared() > 0.0 {
            ((p - q0).dot(&d) / d.norm_squared()).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (p - (q0 + d * t)).norm_squared()
    };
    // The distance to a segment is convex along the other segment:
    // ternary search.
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..100 {
        let (a, b) = (lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0);
        if to_q(p0 + (p1 - p0) * a) < to_q(p0 + (p1 - p0) * b) {
            hi = b;
        } else {
            lo = a;
        }
    }
    to_q(p0 + (p1 - p0) * (0.5 * (lo + hi)))
}

#[test]
fn test_distances_agree_with_sampling() {
    let mut rng = Rng::new(11);
    for _ in 0..200 {
        let [p, a, b, c] = [(); 4].map(|()| rng.vec3(1.0));
        let mut sampled = f64::INFINITY;
        let mut segments = f64::INFINITY;
        for i in 0..=60 {
            for j in 0..=60 - i {
                let (u, v) = (f64::from(i) / 60.0, f64::from(j) / 60.0);
                sampled = sampled.min((a + (b - a) * u + (c - a) * v - p).norm_squared());
            }
            for j in 0..=60 {
                let (u, v) = (f64::from(i) / 60.0, f64::from(j) / 60.0);
                segments = segments.min((p + (a - p) * u - b - (c - b) * v).norm_squared());
            }
        }
        let exact = point_triangle(p, [a, b, c]);
        assert!(
            exact <= sampled + 1e-12 && sampled.sqrt() - exact.sqrt() < 0.05,
            "{exact} {sampled}"
        );
        let exact = segment_segment(p, a, b, c);
        assert!(
            exact <= segments + 1e-12 && segments.sqrt() - exact.sqrt() < 0.05,
            "{exact} {segments}"
        );
    }
}

fn check(mesh: &CollisionMesh, found: &Candidates, expected: &Candidates) {
    for list in [&found.point_triangle, &found.edge_edge] {
        assert!(
            list.windows(2).all(|w| w[0] < w[1]),
            "sorted, no duplicates"
        );
    }
    for &(e, f) in &found.edge_edge {
        assert!(e < f);
        let (a, b) = (mesh.edges()[e as usize], mesh.edges()[f as usize]);
        assert!(!shares(&a, &b));
        assert!(mesh.collides(mesh.edge_group(e as usize), mesh.edge_group(f as usize)));
    }
    for &(v, t) in &found.point_triangle {
        assert!(!mesh.triangles()[t as usize].contains(&mesh.vertices()[v as usize]));
        assert!(mesh.collides(
            mesh.vertex_group(v as usize),
            mesh.triangle_group(t as usize)
        ));
    }
    assert_eq!(
        found.point_triangle, expected.point_triangle,
        "point–triangle pairs"
    );
    assert_eq!(found.edge_edge, expected.edge_edge, "edge–edge pairs");
}

/// Every pair closer than `distance` is a candidate. (Pairs whose
/// points are `distance` apart along an axis are skipped: they are at
/// least that far apart.)
fn check_distances(mesh: &CollisionMesh, x: &[Vec3], distance: f64, found: &Candidates) -> usize {
    let apart = |p: &[usize], q: &[usize]| {
        (0..3).any(|k| {
            let range = |s: &[usize]| {
                s.iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &i| {
                        (lo.min(x[i][k]), hi.max(x[i][k]))
                    })
            };
            let ((a, b), (c, d)) = (range(p), range(q));
            c - b >= distance || a - d >= distance
        })
    };
    let mut close = 0;
    for (v, &p) in mesh.vertices().iter().enumerate() {
        for (t, tri) in mesh.triangles().iter().enumerate() {
            if !tri.contains(&p)
                && mesh.collides(mesh.vertex_group(v), mesh.triangle_group(t))
                && !apart(&[p], tri)
                && point_triangle(x[p], tri.map(|q| x[q])) < distance * distance
            {
                close += 1;
                assert!(
                    found
                        .point_triangle
                        .binary_search(&(v as u32, t as u32))
                        .is_ok()
                );
            }
        }
    }
    for (e, &[a, b]) in mesh.edges().iter().enumerate() {
        for (f, &[c, d]) in mesh.edges().iter().enumerate().skip(e + 1) {
            if !shares(&[a, b], &[c, d])
                && mesh.collides(mesh.edge_group(e), mesh.edge_group(f))
                && !apart(&[a, b], &[c, d])
                && segment_segment(x[a], x[b], x[c], x[d]) < distance * distance
            {
                close += 1;
                assert!(found.edge_edge.binary_search(&(e as u32, f as u32)).is_ok());
            }
        }
    }
    close
}

/// Two random soups (one self-colliding by `seed`) and a folded cloth.
fn scene(seed: u64, size: usize) -> (CollisionMesh, Vec<Vec3>) {
    let mut rng = Rng::new(seed);
    let mut mesh = CollisionMesh::new();
    let mut x = Vec::new();
    for own in [seed % 2 == 0, seed % 3 == 0] {
        let (y, triangles) = soup(&mut rng, x.len(), size, 0.08);
        mesh.add_surface(&triangles, own);
        x.extend(y);
    }
    let (mut y, triangles) = cloth(12, 0.05);
    fold(&mut y, 0.3, 0.02, 0.0);
    let first = x.len();
    mesh.add_surface(
        &triangles
            .iter()
            .map(|t| t.map(|p| p + first))
            .collect::<Vec<_>>(),
        true,
    );
    x.extend(y.iter().map(|p| p + Vec3::new(0.2, 0.2, 0.4)));
    (mesh, x)
}

/// Whatever the cell side, from boxes eight cells wide to a few in a
/// cell.
#[test]
fn proximity_finds_exactly_the_overlapping_boxes_on_soups_and_a_folded_cloth() {
    for factor in [0.25, 1.5, CELL_FACTOR, 8.0] {
        let mut broad = BroadPhase::new(Parallelism::Sequential)
            .with_cell_factor(factor)
            .unwrap();
        let mut found = Candidates::default();
        for seed in 0..6 {
            let (mesh, x) = scene(seed, 150);
            for distance in [0.0, 0.01, 0.05] {
                broad.proximity(&mesh, &x, distance, &mut found);
                check(&mesh, &found, &brute(&mesh, &x, &x, distance));
                if distance > 0.0 {
                    let close = check_distances(&mesh, &x, distance, &found);
                    let listed = found.point_triangle.len() + found.edge_edge.len();
                    assert!(close > 0 && close <= listed, "factor {factor}");
                }
            }
        }
    }
}

#[test]
fn folded_cloth_pairs_across_the_fold_and_not_within_a_surface_without_self_collision() {
    let (mut x, triangles) = cloth(20, 0.1);
    fold(&mut x, 1.0, 0.04, 0.0);
    let (mut broad, mut found) = (BroadPhase::default(), Candidates::default());
    for own in [true, false] {
        let mut mesh = CollisionMesh::new();
        mesh.add_surface(&triangles, own);
        broad.proximity(&mesh, &x, 0.1, &mut found);
        check(&mesh, &found, &brute(&mesh, &x, &x, 0.1));
        if own {
            // The sheets are 8 cm apart across the fold.
            let close = check_distances(&mesh, &x, 0.1, &found);
            assert!(close > 100, "{close}");
        } else {
            assert!(found.point_triangle.is_empty() && found.edge_edge.is_empty());
        }
    }
}

#[test]
fn swept_boxes_with_fast_and_huge_motions_match_brute_force() {
    // Cells small enough that the fast motions go to coarser levels.
    let mut broad = BroadPhase::new(Parallelism::Sequential)
        .with_cell_factor(1.5)
        .unwrap();
    let mut found = Candidates::default();
    for seed in 0..4 {
        let (mesh, x0) = scene(seed, 120);
        let mut rng = Rng::new(100 + seed);
        let x1: Vec<Vec3> = x0
            .iter()
            .map(|p| {
                let r = rng.uniform(0.0, 1.0);
                // Most move a little, some across the scene, a few far.
                let reach = if r < 0.8 {
                    0.01
                } else if r < 0.97 {
                    0.5
                } else {
                    50.0
                };
                p + rng.vec3(1.0) * reach
            })
            .collect();
        broad.swept(&mesh, &x0, &x1, 0.01, &mut found);
        assert!(broad.levels.iter().any(|&l| l > 0), "coarser levels in use");
        check(&mesh, &found, &brute(&mesh, &x0, &x1, 0.01));
    }
}

#[test]
fn non_finite_positions_are_tested_against_every_box() {
    let (mesh, mut x) = scene(3, 100);
    x[5] = Vec3::new(f64::NAN, 0.0, 0.0);
    x[40] = Vec3::new(f64::INFINITY, 0.5, 0.5);
    x[41] = Vec3::new(0.5, f64::NEG_INFINITY, 0.5);
    let (mut broad, mut found) = (BroadPhase::default(), Candidates::default());
    broad.proximity(&mesh, &x, 0.02, &mut found);
    assert!(broad.levels.contains(&WILD));
    check(&mesh, &found, &brute(&mesh, &x, &x, 0.02));
}

#[test]
fn a_scene_too_wide_for_exact_keys_hashes_its_cells() {
    let (mut mesh, mut x) = scene(1, 100);
    // A lone triangle, and a second one touching it, 10¹² m away.
    let n = x.len();
    mesh.add_surface(&[[n, n + 1, n + 2]], false);
    mesh.add_surface(&[[n + 3, n + 4, n + 5]], false);
    for k in 0..6 {
        x.push(
            Vec3::repeat(1e12)
                + Vec3::new(
                    0.01 * f64::from(k % 3),
                    0.005 * f64::from(k / 3),
                    0.01 * f64::from(k),
                ),
        );
    }
    let (mut broad, mut found) = (BroadPhase::default(), Candidates::default());
    broad.proximity(&mesh, &x, 0.02, &mut found);
    assert!(broad.grids[0].exact.is_none());
    check(&mesh, &found, &brute(&mesh, &x, &x, 0.02));
    let far = mesh.triangles().len() as u32 - 2;
    assert!(found.point_triangle.iter().any(|&(_, t)| t >= far));
}

#[test]
fn triangle_pairs_match_brute_force_whatever_the_groups() {
    let (mesh, x) = scene(4, 150);
    let (mut broad, mut pairs) = (BroadPhase::default(), Vec::new());
    broad.triangle_pairs(&mesh, &x, 0.01, &mut pairs);
    let boxes: Vec<_> = mesh
        .triangles()
        .iter()
        .map(|t| box_of(t, &x, &x, 0.01))
        .collect();
    let mut expected = Vec::new();
    for (s, a) in mesh.triangles().iter().enumerate() {
        for (t, b) in mesh.triangles().iter().enumerate().skip(s + 1) {
            if !shares(a, b) && boxes_overlap(&boxes[s], &boxes[t]) {
                expected.push((s as u32, t as u32));
            }
        }
    }
    assert_eq!(pairs, expected);
}

#[test]
fn an_empty_mesh_has_no_pairs() {
    let (mut broad, mut found) = (BroadPhase::default(), Candidates::default());
    found.edge_edge.push((0, 1));
    broad.proximity(&CollisionMesh::new(), &[], 0.1, &mut found);
    assert!(found.point_triangle.is_empty() && found.edge_edge.is_empty());
}

#[cfg(feature = "parallel")]
#[test]
fn parallel_and_sequential_searches_agree() {
    let (mut x0, triangles) = cloth(90, 0.01);
    fold(&mut x0, 0.45, 0.004, 0.0);
    let mut rng = Rng::new(7);
    let x1: Vec<Vec3> = x0
        .iter()
        .map(|p| {
            p + rng.vec3(1.0)
                * if rng.uniform(0.0, 1.0) < 0.99 {
                    0.005
                } else {
                    0.3
                }
        })
        .collect();
    let mut mesh = CollisionMesh::new();
    mesh.add_surface(&triangles, true);
    assert!(
        mesh.vertices().len() + mesh.edges().len() + mesh.triangles().len()
            >= PARALLEL_MIN_PRIMITIVES
    );
    let mut results = Vec::new();
    for parallelism in [
        Parallelism::Sequential,
        Parallelism::Parallel,
        Parallelism::Auto,
    ] {
        let (mut broad, mut near, mut swept, mut pairs) = (
            BroadPhase::new(parallelism),
            Candidates::default(),
            Candidates::default(),
            Vec::new(),
        );
        broad.proximity(&mesh, &x0, 0.01, &mut near);
        broad.swept(&mesh, &x0, &x1, 0.001, &mut swept);
        broad.triangle_pairs(&mesh, &x0, 0.0, &mut pairs);
        assert!(!near.edge_edge.is_empty() && !swept.point_triangle.is_empty());
        results.push((
            near.point_triangle,
            near.edge_edge,
            swept.point_triangle,
            swept.edge_edge,
            pairs,
        ));
    }
    assert!(results[0] == results[1] && results[1] == results[2]);
}
