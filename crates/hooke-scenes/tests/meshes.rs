//! Bodies from meshes built in code: `Solid` (tets), `Shell` (triangles)
//! and `Layered`, with hand-counted springs and every mesh error.

mod common;

use approx::assert_relative_eq;
use common::two_tets;
use hooke_core::Vec3;
use hooke_scenes::{
    Element, Family, Layered, Mass, SceneError, Shell, Solid, Springs, TetMesh, TriangleMesh,
};

#[test]
fn solid_springs_on_unique_edges_and_mass_from_volumes() {
    let body = Solid::new(two_tets())
        .edges(Springs::modulus(2.0))
        .mass(Mass::Density(6.0))
        .build()
        .unwrap();
    // 6 + 6 edges, 3 of them (the shared face's) counted once.
    assert_eq!(body.springs().len(), 9);
    for s in body.springs() {
        assert_relative_eq!(s.stiffness * s.rest_length, 2.0, epsilon = 1e-12);
    }
    // Volumes 1/6 and |(1,1,1)·((0,-1,1)×(-1,1,0))|/6 = 2/6.
    assert_relative_eq!(body.total_mass(), 6.0 * 0.5, epsilon = 1e-12);
    assert_relative_eq!(body.masses()[0], 0.25, epsilon = 1e-12);
    assert_relative_eq!(body.masses()[4], 0.5, epsilon = 1e-12);
    assert_relative_eq!(body.masses()[1], 0.75, epsilon = 1e-12);
    // Boundary: 4 + 4 faces minus the shared one twice.
    assert_eq!(body.triangles().len(), 6);
    let p = body.positions();
    let centroid = p.iter().sum::<Vec3>() / 5.0;
    for &[a, b, c] in body.triangles() {
        let outward = (p[b] - p[a]).cross(&(p[c] - p[a]));
        assert!(
            outward.dot(&(p[a] - centroid)) > 0.0,
            "face {a} {b} {c} points in"
        );
    }
}

#[test]
fn solid_accepts_either_global_orientation() {
    let mut mesh = two_tets();
    for t in &mut mesh.tets {
        t.swap(0, 1);
    }
    let body = Solid::new(mesh).build().unwrap();
    let p = body.positions();
    let volume: f64 = body
        .triangles()
        .iter()
        .map(|&[a, b, c]| p[a].dot(&p[b].cross(&p[c])) / 6.0)
        .sum();
    assert_relative_eq!(volume, 0.5, epsilon = 1e-12);
}

#[test]
fn solid_mesh_errors_name_the_tet_or_vertex() {
    let mut inverted = two_tets();
    inverted.tets[1].swap(2, 3);
    assert!(matches!(
        Solid::new(inverted).build(),
        Err(SceneError::InvertedTet { tet: 1, .. })
    ));
    let mut flat = two_tets();
    flat.vertices[3] = Vec3::new(0.2, 0.2, 0.0); // tet 0 now lies in z = 0
    assert!(matches!(
        Solid::new(flat).build(),
        Err(SceneError::DegenerateElement {
            element: Element::Tet(0),
            ..
        })
    ));
    let mut repeated = two_tets();
    repeated.tets[1] = [4, 1, 1, 2];
    assert!(matches!(
        Solid::new(repeated).build(),
        Err(SceneError::DegenerateElement {
            element: Element::Tet(1),
            ..
        })
    ));
    let mut out = two_tets();
    out.tets[1][3] = 7;
    assert!(matches!(
        Solid::new(out).build(),
        Err(SceneError::VertexOutOfRange {
            element: Element::Tet(1),
            vertex: 7,
            vertices: 5
        })
    ));
    let mut unused = two_tets();
    unused.vertices.push(Vec3::new(5.0, 5.0, 5.0));
    assert!(matches!(
        Solid::new(unused).build(),
        Err(SceneError::UnusedVertex { vertex: 5 })
    ));
    let mut nan = two_tets();
    nan.vertices[2].y = f64::NAN;
    assert!(matches!(
        Solid::new(nan).build(),
        Err(SceneError::NonFiniteVertex { vertex: 2, .. })
    ));
    assert!(matches!(
        Solid::new(TetMesh::default()).build(),
        Err(SceneError::InvalidCount {
            field: "mesh tets",
            ..
        })
    ));
    assert!(matches!(
        Solid::new(two_tets()).pin(5).build(),
        Err(SceneError::PinOutOfRange {
            particle: 5,
            particles: 5
        })
    ));
}

/// A regular octahedron, vertices ±x, ±y, ±z, faces outward.
fn octahedron() -> TriangleMesh {
    TriangleMesh::new(
        [
            [1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
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

#[test]
fn shell_bends_join_the_corners_opposite_each_shared_edge() {
    let body = Shell::new(octahedron())
        .edges(1.0)
        .bend(0.5)
        .build()
        .unwrap();
    assert_eq!(body.springs_of(Family::Edge).count(), 12);
    // Each edge's two opposite corners are an antipodal pair: 3 unique.
    let bends: Vec<_> = body.springs_of(Family::Bend).collect();
    assert_eq!(bends.len(), 3);
    assert!(
        bends
            .iter()
            .all(|s| (s.rest_length - 2.0).abs() < 1e-12 && s.i / 2 == s.j / 2)
    );
    // Eight faces of area √3/2, a third to each corner: all vertices equal.
    let body = Shell::new(octahedron())
        .mass(Mass::Density(2.0))
        .build()
        .unwrap();
    assert_relative_eq!(body.total_mass(), 2.0 * 4.0 * 3f64.sqrt(), epsilon = 1e-12);
    assert_relative_eq!(body.masses()[3], body.total_mass() / 6.0, epsilon = 1e-12);
}

#[test]
fn shell_errors() {
    let mut fan = octahedron();
    fan.triangles.push([0, 2, 3]); // a third triangle on edge (0, 2)
    assert!(matches!(
        Shell::new(fan).build(),
        Err(SceneError::NonManifoldEdge {
            a: 0,
            b: 2,
            triangles: 3
        })
    ));
    let mut sliver = octahedron();
    sliver.vertices.push(Vec3::new(2.0, 0.0, 0.0));
    sliver.triangles.push([0, 1, 6]); // collinear corners
    assert!(matches!(
        Shell::new(sliver).build(),
        Err(SceneError::DegenerateElement {
            element: Element::Triangle(8),
            ..
        })
    ));
    let mut out = octahedron();
    out.triangles[2][1] = 6;
    assert!(matches!(
        Shell::new(out).build(),
        Err(SceneError::VertexOutOfRange {
            element: Element::Triangle(2),
            vertex: 6,
            vertices: 6
        })
    ));
    assert!(matches!(
        Shell::new(TriangleMesh::default()).build(),
        Err(SceneError::InvalidCount {
            field: "mesh triangles",
            ..
        })
    ));
}

#[test]
fn layered_octahedron_counts_positions_and_mass() {
    let body = Layered::new(octahedron(), 0.25)
        .surface(1.0)
        .links(2.0)
        .cross(3.0)
        .mass(Mass::Total(12.0))
        .build()
        .unwrap();
    assert_eq!(body.particle_count(), 12);
    assert_eq!(body.springs_of(Family::Edge).count(), 2 * 12);
    assert_eq!(body.springs_of(Family::Link).count(), 6);
    assert_eq!(body.springs_of(Family::Cross).count(), 2 * 12);
    // The octahedron's vertex normals point along the vertices themselves.
    for v in 0..6 {
        let outer = body.positions()[v];
        assert_relative_eq!(body.positions()[6 + v], outer * 0.75, epsilon = 1e-12);
    }
    for s in body.springs_of(Family::Link) {
        assert_eq!(s.j, s.i + 6);
        assert_relative_eq!(s.rest_length, 0.25, epsilon = 1e-12);
    }
    // Cross springs join an outer vertex to the copy of a neighbour.
    let inner_edge = 0.75 * 2f64.sqrt();
    for s in body.springs_of(Family::Cross) {
        assert!(s.i < 6 && s.j >= 6 && s.j - 6 != s.i);
        let expected = (Vec3::new(1.0, 0.0, 0.0) - Vec3::new(0.0, 0.75, 0.0)).norm();
        assert_relative_eq!(s.rest_length, expected, epsilon = 1e-12);
    }
    assert!(
        body.springs_of(Family::Edge)
            .skip(12)
            .all(|s| (s.rest_length - inner_edge).abs() < 1e-12)
    );
    assert_relative_eq!(body.total_mass(), 12.0, epsilon = 1e-12);
    assert!(body.masses().iter().all(|&m| (m - 1.0).abs() < 1e-12));
    assert_eq!(body.triangles().len(), 16);
}

#[test]
fn layered_errors() {
    // A two-sided triangle: the normals of its two faces cancel.
    let double = TriangleMesh::new(
        [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        [[0, 1, 2], [0, 2, 1]],
    );
    assert!(matches!(
        Layered::new(double, 0.1).build(),
        Err(SceneError::ZeroNormal { vertex: 0 })
    ));
    assert!(matches!(
        Layered::new(octahedron(), 0.0).build(),
        Err(SceneError::InvalidValue {
            field: "layer thickness",
            ..
        })
    ));
    assert!(matches!(
        Layered::new(octahedron(), 0.1)
            .cross(Springs::per_spring(1.0).damping(-1.0))
            .build(),
        Err(SceneError::InvalidValue {
            field: "cross damping",
            ..
        })
    ));
}
