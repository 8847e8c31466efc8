//! Mesh files: OBJ surfaces and TetGen tetrahedral meshes, the bodies
//! made from them, and the errors for files that are missing or malformed.

use std::path::{Path, PathBuf};

use approx::assert_relative_eq;
use hooke_scenes::{Family, Mass, SceneError, Shell, Solid, obj, tetgen};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

#[test]
fn obj_cube_has_18_edges_and_9_bends() {
    let mesh = obj::load(data("cube.obj")).unwrap();
    assert_eq!((mesh.vertices.len(), mesh.triangles.len()), (8, 12));
    let body = Shell::new(mesh)
        .edges(1.0)
        .bend(1.0)
        .mass(Mass::Total(8.0))
        .build()
        .unwrap();
    // 12 cube edges + one diagonal per face.
    assert_eq!(body.springs_of(Family::Edge).count(), 18);
    // Of the 18 opposite-corner pairs, 3 are face diagonals already and 6
    // repeat: what is left is the other diagonal of each face (6) and three
    // body diagonals (worked out edge by edge for this file's fans).
    let bends: Vec<_> = body.springs_of(Family::Bend).collect();
    assert_eq!(bends.len(), 9);
    let face = bends
        .iter()
        .filter(|s| (s.rest_length - 2f64.sqrt()).abs() < 1e-12)
        .count();
    let body_diagonal = bends
        .iter()
        .filter(|s| (s.rest_length - 3f64.sqrt()).abs() < 1e-12)
        .count();
    assert_eq!((face, body_diagonal), (6, 3));
    assert_relative_eq!(body.total_mass(), 8.0, epsilon = 1e-12);
}

#[test]
fn obj_octahedron_has_12_edges_and_3_bends() {
    let body = Shell::new(obj::load(data("octahedron.obj")).unwrap())
        .edges(1.0)
        .bend(1.0)
        .build()
        .unwrap();
    assert_eq!(body.springs_of(Family::Edge).count(), 12);
    assert_eq!(body.springs_of(Family::Bend).count(), 3);
}

#[test]
fn obj_groups_sharing_vertices_are_welded() {
    let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\no a\nf 1 2 3\no b\nf 1 3 4\n";
    let mesh = obj::parse(text).unwrap();
    assert_eq!(mesh.vertices.len(), 4);
    let body = Shell::new(mesh).bend(1.0).build().unwrap();
    assert_eq!(body.springs().len(), 1); // across the shared diagonal
}

#[test]
fn obj_errors() {
    assert!(matches!(
        obj::load(data("missing.obj")),
        Err(SceneError::Io { .. })
    ));
    assert!(matches!(
        obj::parse("v 0 0 0\nv 1 0 0\nf 1 2 9\n"),
        Err(SceneError::Obj { .. })
    ));
    assert!(matches!(
        obj::parse("v 0 zero 0\n"),
        Err(SceneError::Obj { .. })
    ));
}

#[test]
fn tetgen_cube_of_five_tets() {
    let mesh = tetgen::load(data("cube.1")).unwrap();
    assert_eq!((mesh.vertices.len(), mesh.tets.len()), (8, 5));
    assert_eq!(mesh.vertices[6], hooke_core::Vec3::new(1.0, 1.0, 1.0));
    let body = Solid::new(mesh)
        .edges(1.0)
        .mass(Mass::Density(3.0))
        .build()
        .unwrap();
    // 12 cube edges and the 6 face diagonals the central tet's edges make.
    assert_eq!(body.springs().len(), 18);
    assert_eq!(
        body.springs()
            .iter()
            .filter(|s| (s.rest_length - 1.0).abs() < 1e-12)
            .count(),
        12
    );
    assert_relative_eq!(body.total_mass(), 3.0, epsilon = 1e-12);
    assert_eq!(body.triangles().len(), 12);
}

fn parse_error(node: &str, ele: &str) -> (String, usize, String) {
    match tetgen::parse(node, ele) {
        Err(SceneError::Parse {
            file,
            line,
            message,
        }) => (file.display().to_string(), line, message),
        other => panic!("expected a parse error, got {other:?}"),
    }
}

#[test]
fn tetgen_errors_name_file_and_line() {
    let node = "# comment\n4 3 0 0\n0 0 0 0\n1 1 0 0 # trailing comment\n\n2 0 1 0\n3 0 0 1\n";
    let ele = "1 4 0\n0 0 1 2 3\n";
    assert_eq!(tetgen::parse(node, ele).unwrap().tets, [[0, 1, 2, 3]]);

    let (file, line, message) = parse_error("4 2 0 0\n", ele);
    assert_eq!((file.as_str(), line), ("<node>", 1));
    assert!(message.contains("dimension"), "{message}");
    let (_, line, message) = parse_error(&node.replace("1 1 0 0", "1 1 0"), ele);
    assert_eq!(line, 4);
    assert!(message.contains("expected 4 fields"), "{message}");
    let (_, line, message) = parse_error(&node.replace("2 0 1 0", "5 0 1 0"), ele);
    assert_eq!(line, 6);
    assert!(message.contains("expected 2"), "{message}");
    let (_, line, message) = parse_error(&node.replace("3 0 0 1", "3 0 0 nan"), ele);
    assert_eq!(line, 7);
    assert!(message.contains("finite"), "{message}");
    let (_, line, message) = parse_error("5 3 0 0\n0 0 0 0\n", ele);
    assert_eq!(line, 2);
    assert!(message.contains("ends"), "{message}");
    let (_, line, message) = parse_error(&format!("{node}4 1 1 1\n"), ele);
    assert_eq!(line, 8);
    assert!(message.contains("more entries"), "{message}");
    let (file, line, message) = parse_error(node, "1 4 0\n0 0 1 2 4\n");
    assert_eq!((file.as_str(), line), ("<ele>", 2));
    assert!(message.contains("point 4"), "{message}");
    let (_, line, message) = parse_error(node, "1 8 0\n");
    assert_eq!(line, 1);
    assert!(message.contains("4 or 10"), "{message}");
    let (_, _, message) = parse_error(node, "1 4 0\n0 0 1 -2 3\n");
    assert!(message.contains("`-2`"), "{message}");
    assert!(matches!(
        tetgen::load(data("missing")),
        Err(SceneError::Io { .. })
    ));
}

#[test]
fn tetgen_ten_node_tets_keep_their_corners() {
    let node = "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n";
    let ele = "1 10 1\n1 1 2 3 4 1 1 1 1 1 1 7\n";
    assert_eq!(tetgen::parse(node, ele).unwrap().tets, [[0, 1, 2, 3]]);
}
