//! PLY frames parse back with an independent reader and with `read_ply`,
//! exactly the one documented.

use std::path::Path;

use hooke_core::Vec3;
use hooke_viz::{Mesh, OutputError, frame_file_name, read_ply, write_frame, write_ply};
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{DefaultElement, Ply, Property};

/// Positions with values that f32 does not hold exactly.
fn positions() -> Vec<Vec3> {
    vec![
        Vec3::new(0.1, -0.2, 0.3),
        Vec3::new(1.0 / 3.0, 2.0, -1e-7),
        Vec3::new(-5.25, 1e3 + 0.123_456_789, 0.0),
        Vec3::new(0.7, 0.8, 0.9),
    ]
}

fn read(path: &Path) -> Ply<DefaultElement> {
    let mut file = std::fs::File::open(path).unwrap();
    Parser::<DefaultElement>::new().read_ply(&mut file).unwrap()
}

fn assert_vertices(ply: &Ply<DefaultElement>, expected: &[Vec3]) {
    let vertices = &ply.payload["vertex"];
    assert_eq!(vertices.len(), expected.len());
    for (vertex, p) in vertices.iter().zip(expected) {
        for (name, &c) in ["x", "y", "z"].iter().zip(p.iter()) {
            let Property::Float(stored) = vertex[*name] else {
                panic!("{name} is not a float: {:?}", vertex[*name]);
            };
            // Exactly the f32 rounding of the f64 value.
            assert_eq!(stored.to_bits(), (c as f32).to_bits(), "{name} of {p:?}");
        }
    }
}

#[test]
fn surface_round_trips_through_a_ply_reader() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = Mesh::new(4, vec![[0, 1, 2], [2, 1, 3]], Vec::new()).unwrap();
    let path = write_frame(dir.path(), 7, &mesh, &positions()).unwrap();
    assert_eq!(path, dir.path().join("frame_00007.ply"));

    let ply = read(&path);
    assert_vertices(&ply, &positions());
    let faces = &ply.payload["face"];
    assert_eq!(faces.len(), 2);
    assert_eq!(faces[0]["vertex_indices"], Property::ListInt(vec![0, 1, 2]));
    assert_eq!(faces[1]["vertex_indices"], Property::ListInt(vec![2, 1, 3]));
    assert!(!ply.header.elements.contains_key("edge"));
}

#[test]
fn rope_round_trips_with_an_edge_element() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("rope.ply");
    let mesh = Mesh::new(4, Vec::new(), vec![[0, 1], [1, 2], [2, 3]]).unwrap();
    write_ply(&path, &mesh, &positions()).unwrap();

    let ply = read(&path);
    assert_vertices(&ply, &positions());
    assert!(!ply.header.elements.contains_key("face"));
    let edges = &ply.payload["edge"];
    assert_eq!(edges.len(), 3);
    for (edge, [a, b]) in edges.iter().zip([[0, 1], [1, 2], [2, 3]]) {
        assert_eq!(edge["vertex1"], Property::Int(a));
        assert_eq!(edge["vertex2"], Property::Int(b));
    }
}

#[test]
fn header_and_payload_bytes_are_as_documented() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("both.ply");
    let mesh = Mesh::new(4, vec![[0, 1, 2]], vec![[2, 3]]).unwrap();
    write_ply(&path, &mesh, &positions()).unwrap();

    let bytes = std::fs::read(&path).unwrap();
    let header = "ply\n\
                  format binary_little_endian 1.0\n\
                  comment written by hooke\n\
                  element vertex 4\n\
                  property float x\n\
                  property float y\n\
                  property float z\n\
                  element face 1\n\
                  property list uchar int vertex_indices\n\
                  element edge 1\n\
                  property int vertex1\n\
                  property int vertex2\n\
                  end_header\n";
    assert_eq!(std::str::from_utf8(&bytes[..header.len()]).unwrap(), header);
    let body = &bytes[header.len()..];
    assert_eq!(body.len(), 4 * 12 + 13 + 8);
    assert_eq!(body[..4], 0.1f32.to_le_bytes());
    assert_eq!(body[48..61], [3, 0, 0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0]);
    assert_eq!(body[61..], [2, 0, 0, 0, 3, 0, 0, 0]);
}

#[test]
fn frame_names_are_zero_padded_and_sort_in_order() {
    assert_eq!(frame_file_name(0), "frame_00000.ply");
    assert_eq!(frame_file_name(42), "frame_00042.ply");
    assert!(frame_file_name(999) < frame_file_name(1000));
}

#[test]
fn unwritable_path_is_a_create_error_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("missing").join("frame.ply");
    let mesh = Mesh::new(4, Vec::new(), Vec::new()).unwrap();
    let err = write_ply(&path, &mesh, &positions()).unwrap_err();
    assert!(matches!(&err, OutputError::Create { path: p, .. } if *p == path));
    assert!(err.to_string().contains(&*path.to_string_lossy()));
}

#[test]
fn a_bad_frame_is_rejected_before_the_file_is_created() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.ply");
    let mesh = Mesh::new(4, Vec::new(), Vec::new()).unwrap();
    let mut bad = positions();
    bad[3].z = f64::INFINITY;
    assert!(matches!(
        write_ply(&path, &mesh, &bad),
        Err(OutputError::NonFinitePosition { vertex: 3, .. })
    ));
    assert!(matches!(
        write_ply(&path, &mesh, &bad[..3]),
        Err(OutputError::PositionCount {
            expected: 4,
            found: 3
        })
    ));
    assert!(!path.exists());
}

#[test]
fn frames_read_back_as_their_single_precision_positions() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = Mesh::new(3, vec![[0, 1, 2]], Vec::new()).unwrap();
    let exact = [
        Vec3::new(0.1, -2.0, 1e-3),
        Vec3::new(1.0 / 3.0, 5.0, -7.25),
        Vec3::new(1e6, 0.0, 2.5),
    ];
    let path = write_frame(dir.path(), 7, &mesh, &exact).unwrap();
    let read = read_ply(&path, &mesh).unwrap();
    for (r, e) in read.iter().zip(&exact) {
        for (a, b) in r.iter().zip(e.iter()) {
            assert_eq!(a.to_bits(), f64::from(*b as f32).to_bits());
        }
    }

    // Another mesh's frame, a truncated file and a missing one.
    let rope = Mesh::new(3, Vec::new(), vec![[0, 1]]).unwrap();
    assert!(matches!(
        read_ply(&path, &rope),
        Err(OutputError::NotAFrame { .. })
    ));
    let bytes = std::fs::read(&path).unwrap();
    let cut = dir.path().join("cut.ply");
    std::fs::write(&cut, &bytes[..bytes.len() - 40]).unwrap();
    let err = read_ply(&cut, &mesh).unwrap_err();
    assert!(matches!(err, OutputError::NotAFrame { .. }));
    assert!(err.to_string().contains("cut.ply"), "{err}");
    assert!(matches!(
        read_ply(&dir.path().join("none.ply"), &mesh),
        Err(OutputError::Read { .. })
    ));
}
