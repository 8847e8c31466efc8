//! Volume elements of the volumetric bodies: where their tets come from
//! (lattice splits, tet meshes, layered prisms), that they fill the body
//! exactly, the default modulus against hand computations, and the
//! modulus's errors.

mod common;

use std::collections::HashMap;

use approx::assert_relative_eq;
use common::two_tets;
use hooke_core::{SystemBuilder, Vec3};
use hooke_scenes::{
    Body, Cloth, Lattice, Layered, Rope, SceneError, Shell, Solid, Springs, TetMesh, TetSplit,
    TriangleMesh, Volume,
};

/// `det(b − a, c − a, d − a) / 6`.
fn signed_volume(body: &Body, t: [usize; 4]) -> f64 {
    let [a, b, c, d] = t.map(|v| body.positions()[v]);
    (b - a).cross(&(c - a)).dot(&(d - a)) / 6.0
}

/// How many tets use each face (its three vertices, sorted).
fn face_uses(tets: &[[usize; 4]]) -> HashMap<[usize; 3], usize> {
    let mut uses = HashMap::new();
    for t in tets {
        for skip in 0..4 {
            let mut face = [0; 3];
            let mut k = 0;
            for (corner, &v) in t.iter().enumerate() {
                if corner != skip {
                    face[k] = v;
                    k += 1;
                }
            }
            face.sort_unstable();
            *uses.entry(face).or_insert(0) += 1;
        }
    }
    uses
}

/// The tets are positively oriented, share every inner face between
/// exactly two of them (neighbours cut shared faces alike), and their
/// faces used once are exactly the body's surface triangles.
fn assert_conforming(name: &str, body: &Body) {
    for &t in body.tets() {
        assert!(signed_volume(body, t) > 0.0, "{name}: tet {t:?}");
    }
    let uses = face_uses(body.tets());
    assert!(
        uses.values().all(|&n| n <= 2),
        "{name}: a face in three tets"
    );
    let mut boundary: Vec<[usize; 3]> = uses
        .iter()
        .filter(|&(_, &n)| n == 1)
        .map(|(f, _)| *f)
        .collect();
    let mut surface: Vec<[usize; 3]> = body
        .triangles()
        .iter()
        .map(|t| {
            let mut t = *t;
            t.sort_unstable();
            t
        })
        .collect();
    boundary.sort_unstable();
    surface.sort_unstable();
    assert_eq!(boundary, surface, "{name}: faces used once");
}

#[test]
fn lattices_get_five_or_six_tets_a_cell_filling_the_box() {
    let size = [0.4, 0.3, 0.2];
    for n in 1..=3 {
        let cells = n * n * n;
        for (name, lattice, per_cell) in [
            ("cubes", Lattice::cubes(n, n, n), 6),
            ("tets-5", Lattice::tets(n, n, n, TetSplit::Five), 5),
            ("tets-6", Lattice::tets(n, n, n, TetSplit::Six), 6),
        ] {
            let body = lattice.size(size).edges(100.0).build().unwrap();
            assert_eq!(body.tets().len(), per_cell * cells, "{name}, n = {n}");
            assert_relative_eq!(body.rest_volume(), 0.4 * 0.3 * 0.2, max_relative = 1e-12);
            assert_conforming(name, &body);
        }
    }
}

#[test]
fn a_tet_lattice_has_its_springs_on_its_volume_elements() {
    for split in [TetSplit::Five, TetSplit::Six] {
        let body = Lattice::tets(2, 3, 2, split)
            .edges(1.0)
            .face_diagonals(1.0)
            .body_diagonals(1.0)
            .build()
            .unwrap();
        let springs: std::collections::HashSet<(usize, usize)> = body
            .springs()
            .iter()
            .map(|s| (s.i.min(s.j), s.i.max(s.j)))
            .collect();
        let mut edges = std::collections::HashSet::new();
        for t in body.tets() {
            for a in 0..4 {
                for b in a + 1..4 {
                    edges.insert((t[a].min(t[b]), t[a].max(t[b])));
                }
            }
        }
        assert_eq!(springs, edges, "{split:?}");
    }
}

#[test]
fn a_tet_mesh_passes_its_tets_through_positively_oriented() {
    let body = Solid::new(two_tets()).edges(1.0).build().unwrap();
    assert_eq!(body.tets(), two_tets().tets.as_slice());
    assert_relative_eq!(body.rest_volume(), 0.5, epsilon = 1e-15);
    assert_conforming("two tets", &body);
    // The mirrored mesh (every tet negative) gives the same elements,
    // reordered to a positive volume.
    let mut mirrored = two_tets();
    for t in &mut mirrored.tets {
        t.swap(0, 1);
    }
    let body = Solid::new(mirrored.clone()).edges(1.0).build().unwrap();
    for (element, given) in body.tets().iter().zip(&mirrored.tets) {
        let (mut a, mut b) = (*element, *given);
        a.sort_unstable();
        b.sort_unstable();
        assert_eq!(a, b);
    }
    assert_conforming("mirrored", &body);
}

/// An octahedron with vertices at different distances from its centre,
/// faces outward: no two of its side faces' quads are planar.
fn lopsided_octahedron() -> TriangleMesh {
    TriangleMesh::new(
        [
            [1.2, 0.0, 0.05],
            [-0.9, 0.1, 0.0],
            [0.1, 1.1, 0.1],
            [0.05, -1.0, -0.1],
            [0.0, 0.2, 1.3],
            [-0.1, 0.0, -0.8],
        ],
        [
            [0, 2, 4],
            [0, 5, 2],
            [0, 4, 3],
            [0, 3, 5],
            [1, 4, 2],
            [1, 2, 5],
            [1, 3, 4],
            [1, 5, 3],
        ],
    )
}

/// The weighted tets fill the body as a chain: each positively oriented
/// tet's four faces, turned outward and times its weight, cancel inside
/// the body, and what remains is each surface triangle once, in its own
/// orientation.
fn assert_weighted_boundary(name: &str, body: &Body) {
    let mut chain: HashMap<[usize; 3], f64> = HashMap::new();
    for (&t, &w) in body.tets().iter().zip(body.tet_weights()) {
        assert!(signed_volume(body, t) > 0.0, "{name}: tet {t:?}");
        let [a, b, c, d] = t;
        for face in [[a, c, b], [a, b, d], [a, d, c], [b, c, d]] {
            let (key, sign) = sorted_with_sign(face);
            *chain.entry(key).or_insert(0.0) += sign * w;
        }
    }
    for &triangle in body.triangles() {
        let (key, sign) = sorted_with_sign(triangle);
        *chain.entry(key).or_insert(0.0) -= sign;
    }
    for (face, w) in chain {
        assert!(w.abs() < 1e-12, "{name}: face {face:?} left with {w}");
    }
}

/// The face's vertices sorted, and the sign of the permutation that sorts
/// them (its orientation against the sorted order).
fn sorted_with_sign(mut face: [usize; 3]) -> ([usize; 3], f64) {
    let mut sign = 1.0;
    for (i, j) in [(0, 1), (1, 2), (0, 1)] {
        if face[i] > face[j] {
            face.swap(i, j);
            sign = -sign;
        }
    }
    (face, sign)
}

#[test]
fn layered_prisms_average_their_six_cuts_into_three_tets_filling_the_shell() {
    let body = Layered::new(lopsided_octahedron(), 0.15)
        .surface(10.0)
        .links(10.0)
        .build()
        .unwrap();
    assert_eq!(body.tets().len(), 12 * 8);
    assert_relative_eq!(body.tet_weights().iter().sum::<f64>(), 3.0 * 8.0);
    // Σ a·(b × c)/6 over the outer triangles and the inner ones reversed:
    // the volume between the layers.
    let p = body.positions();
    let shell: f64 = body
        .triangles()
        .iter()
        .map(|&[a, b, c]| p[a].dot(&p[b].cross(&p[c])) / 6.0)
        .sum();
    assert!(shell > 0.1, "{shell}");
    assert_relative_eq!(body.rest_volume(), shell, max_relative = 1e-12);
    assert_weighted_boundary("layered octahedron", &body);
}

/// A single cut of each prism depends on the order of its corners; the
/// average over all six does not. Relabelling the mesh's vertices (and
/// so every triangle's corners) gives the same weighted elements.
#[test]
fn layered_volume_elements_do_not_depend_on_the_vertex_order() {
    let mesh = lopsided_octahedron();
    let order = [3, 5, 0, 4, 1, 2]; // new vertex k is old vertex order[k]
    let mut new_of = [0; 6];
    for (new, &old) in order.iter().enumerate() {
        new_of[old] = new;
    }
    let relabelled = TriangleMesh::new(
        order.map(|old| {
            let v = mesh.vertices[old];
            [v.x, v.y, v.z]
        }),
        mesh.triangles
            .iter()
            .map(|t| [t[1], t[2], t[0]].map(|v| new_of[v]))
            .collect::<Vec<_>>(),
    );
    // Particles are the vertices and then their copies, in the same order.
    let back = |p: usize| if p < 6 { order[p] } else { 6 + order[p - 6] };
    let elements = |body: &Body, label: &dyn Fn(usize) -> usize| {
        let mut e: Vec<([usize; 4], u64)> = body
            .tets()
            .iter()
            .zip(body.tet_weights())
            .map(|(t, &w)| {
                let mut t = t.map(label);
                t.sort_unstable();
                (t, (6.0 * w).round() as u64)
            })
            .collect();
        e.sort_unstable();
        e
    };
    let build = |mesh: TriangleMesh| Layered::new(mesh, 0.15).surface(10.0).build().unwrap();
    let original = build(mesh.clone());
    let other = build(relabelled);
    assert_eq!(elements(&original, &|p| p), elements(&other, &back));
}

#[test]
fn a_flat_layered_sheet_has_prisms_of_area_times_thickness() {
    // A 2 × 1 m rectangle of 2 × 2 squares, four triangles each way round.
    let mut vertices = Vec::new();
    for j in 0..3 {
        for i in 0..3 {
            vertices.push([i as f64, 0.0, 0.5 * j as f64]);
        }
    }
    let at = |i: usize, j: usize| 3 * j + i;
    let mut triangles = Vec::new();
    for j in 0..2 {
        for i in 0..2 {
            triangles.push([at(i, j), at(i, j + 1), at(i + 1, j)]);
            triangles.push([at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)]);
        }
    }
    let sheet = TriangleMesh::new(vertices, triangles);
    let body = Layered::new(sheet, 0.1).surface(1.0).build().unwrap();
    assert_eq!(body.tets().len(), 12 * 8);
    assert_relative_eq!(body.rest_volume(), 2.0 * 1.0 * 0.1, max_relative = 1e-12);
}

#[test]
fn the_default_modulus_of_one_cube_cell_by_hand() {
    // One a × b × c cell: 4 edges along each axis (Σ L² = 4(a² + b² + c²)),
    // 2 diagonals on each of 6 faces (Σ L² = 8(a² + b² + c²)) and 4 body
    // diagonals (Σ L² = 4(a² + b² + c²)), around V = abc.
    let (a, b, c) = (0.2, 0.3, 0.5);
    let (ke, kf, kb) = (600.0, 300.0, 200.0);
    let body = Lattice::cubes(1, 1, 1)
        .size([a, b, c])
        .edges(ke)
        .face_diagonals(kf)
        .body_diagonals(kb)
        .build()
        .unwrap();
    let squares = a * a + b * b + c * c;
    let expected = (4.0 * ke + 8.0 * kf + 4.0 * kb) * squares / (9.0 * a * b * c);
    assert_relative_eq!(body.spring_bulk_modulus(), expected, max_relative = 1e-12);
    assert_relative_eq!(body.volume_modulus(), expected, max_relative = 1e-12);
    let system = body.system([0.0; 3]).unwrap();
    assert_eq!(system.tets().len(), 6);
    for t in system.tets() {
        assert_relative_eq!(t.modulus, expected, max_relative = 1e-12);
    }
    // With `modulus` springs, k L² = E L: a unit cube of edges only.
    let unit = Lattice::cubes(1, 1, 1)
        .edges(Springs::modulus(90.0))
        .build()
        .unwrap();
    assert_relative_eq!(
        unit.volume_modulus(),
        12.0 * 90.0 / 9.0,
        max_relative = 1e-12
    );
}

/// A uniform dilation by `1 + ε` stores `½ K (3ε)² V` in a continuum of
/// bulk modulus `K`: the springs' energy at that dilation, to first order
/// in `ε`, is that of `K` = the default modulus.
#[test]
fn the_default_modulus_is_the_springs_bulk_modulus_under_dilation() {
    let body = Lattice::tets(2, 2, 3, TetSplit::Five)
        .size([0.3, 0.2, 0.4])
        .edges(Springs::modulus(50.0))
        .face_diagonals(Springs::modulus(20.0))
        .build()
        .unwrap();
    let epsilon = 1e-6;
    let stretched: f64 = body
        .springs()
        .iter()
        .map(|s| 0.5 * s.stiffness * (epsilon * s.rest_length).powi(2))
        .sum();
    let bulk = stretched / (0.5 * (3.0 * epsilon).powi(2) * body.rest_volume());
    assert_relative_eq!(body.volume_modulus(), bulk, max_relative = 1e-9);
}

#[test]
fn a_modulus_can_be_set_or_turned_off_keeping_the_elements() {
    let lattice = || Lattice::cubes(2, 2, 2).edges(1e3);
    let set = lattice().volume(Volume::Modulus(750.0)).build().unwrap();
    assert_relative_eq!(set.volume_modulus(), 750.0);
    let off = lattice().volume(Volume::Off).build().unwrap();
    assert_eq!((off.tets().len(), off.volume_modulus()), (48, 0.0));
    let system = off.system([0.0; 3]).unwrap();
    assert!(system.tets().iter().all(|t| t.modulus == 0.0));
    let inversion = system
        .inversion(system.initial_state().positions())
        .unwrap();
    assert_eq!(inversion.inverted, 0);
    assert_relative_eq!(inversion.smallest_ratio, 1.0, epsilon = 1e-12);
    // The same on a built body, back to the default.
    let auto = off.volume(Volume::Auto).unwrap();
    assert_relative_eq!(
        auto.volume_modulus(),
        lattice().build().unwrap().volume_modulus(),
        max_relative = 1e-15
    );
}

#[test]
fn a_negative_or_non_finite_modulus_is_an_error() {
    let tet = || {
        TetMesh::new(
            [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            [[0, 1, 2, 3]],
        )
    };
    let square = || {
        TriangleMesh::new(
            [[0.0; 3], [1.0, 0.0, 0.0], [1.0, 0.0, 1.0], [0.0, 0.0, 1.0]],
            [[0, 2, 1], [0, 3, 2]],
        )
    };
    for bad in [-1.0, f64::NAN, f64::INFINITY] {
        let volume = Volume::Modulus(bad);
        for result in [
            Lattice::cubes(1, 1, 1).volume(volume).build(),
            Solid::new(tet()).volume(volume).build(),
            Layered::new(square(), 0.1).volume(volume).build(),
            Lattice::cubes(1, 1, 1).build().unwrap().volume(volume),
        ] {
            assert!(
                matches!(
                    result,
                    Err(SceneError::InvalidValue {
                        field: "volume modulus",
                        ..
                    })
                ),
                "{bad}: {result:?}"
            );
        }
    }
}

#[test]
fn surfaces_and_ropes_have_no_volume_elements() {
    let cloth = Cloth::grid(3, 3).stretch(1.0).build().unwrap();
    let rope = Rope::between([0.0; 3], [1.0, 0.0, 0.0], 3)
        .stretch(1.0)
        .build()
        .unwrap();
    let shell = Shell::new(TriangleMesh::new(
        [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        [[0, 1, 2]],
    ))
    .edges(1.0)
    .build()
    .unwrap();
    for body in [cloth, rope, shell] {
        assert!(body.tets().is_empty());
        let body = body.volume(Volume::Modulus(1e3)).unwrap();
        assert_eq!((body.volume_modulus(), body.rest_volume()), (0.0, 0.0));
        assert!(body.system([0.0; 3]).unwrap().tets().is_empty());
    }
}

#[test]
fn bodies_add_their_elements_after_the_others_with_system_indices() {
    let cube = Lattice::cubes(1, 1, 1).edges(1.0).build().unwrap();
    let cloth = Cloth::grid(2, 2).stretch(1.0).build().unwrap();
    let mut b = SystemBuilder::new();
    let first = cube.add_to(&mut b);
    let between = cloth.add_to(&mut b);
    let second = cube.add_to(&mut b);
    assert_eq!(
        (first.tet_range(), between.tet_count, second.tet_range()),
        (0..6, 0, 6..12)
    );
    let system = b.build().unwrap();
    for t in &system.tets()[second.tet_range()] {
        assert!(t.vertices.iter().all(|v| second.range().contains(v)));
    }
    let x: Vec<Vec3> = system.initial_state().positions().to_vec();
    let inversion = system.inversion(&x).unwrap();
    assert_eq!(inversion.inverted, 0);
}
