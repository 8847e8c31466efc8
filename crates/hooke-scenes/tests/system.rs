//! Bodies in systems: several bodies in one builder, their placements and
//! offset triangles, and gravity.

use hooke_core::{SystemBuilder, Vec3};
use hooke_scenes::{Cloth, Corner, Lattice, Rope, SceneError, TetSplit, tetgen};

#[test]
fn bodies_share_a_system_at_their_placements() {
    let cloth = Cloth::grid(3, 3)
        .stretch(10.0)
        .pin_corners([Corner::TopRight])
        .build()
        .unwrap();
    let rope = Rope::between([0.0, 1.0, 0.0], [0.0, 2.0, 0.0], 4)
        .stretch(5.0)
        .pin_end()
        .build()
        .unwrap();
    let block = Lattice::tets(1, 1, 1, TetSplit::Five)
        .edges(1.0)
        .face_diagonals(1.0)
        .build()
        .unwrap();
    let mut builder = SystemBuilder::new();
    let c = cloth.add_to(&mut builder);
    let r = rope.add_to(&mut builder);
    let b = block.add_to(&mut builder);
    assert_eq!((c.first, c.count), (0, 9));
    assert_eq!((r.first, r.count), (9, 5));
    assert_eq!((b.first, b.count), (14, 8));
    assert_eq!(b.range(), 14..22);
    let system = builder.build().unwrap();
    assert_eq!(system.particle_count(), 22);
    assert_eq!(
        system.springs().len(),
        cloth.springs().len() + rope.springs().len() + 18
    );
    assert_eq!(system.pinned().collect::<Vec<_>>(), [2, 13]);
    // The rope's springs moved with it, rest lengths kept.
    let first_rope_spring = system.springs()[cloth.springs().len()];
    assert_eq!((first_rope_spring.i, first_rope_spring.j), (9, 10));
    assert!((first_rope_spring.rest_length - 0.25).abs() < 1e-12);
    // Offset triangles name the same points in the system as locally.
    let positions = system.initial_positions();
    for (local, global) in block.triangles().iter().zip(b.triangles(&block)) {
        for (&l, g) in local.iter().zip(global) {
            assert_eq!(block.positions()[l], positions[g]);
        }
    }
    let masses: f64 = system.masses().iter().sum();
    let expected = cloth.total_mass() + rope.total_mass() + block.total_mass();
    assert!((masses - expected).abs() < 1e-9);
}

#[test]
fn system_applies_gravity_only_when_asked() {
    let cloth = Cloth::grid(2, 2).build().unwrap();
    assert_eq!(cloth.system([0.0; 3]).unwrap().gravity(), None);
    let g = cloth.system([0.0, -9.81, 0.0]).unwrap().gravity();
    assert_eq!(g, Some(Vec3::new(0.0, -9.81, 0.0)));
    assert!(matches!(
        cloth.system([0.0, f64::NAN, 0.0]),
        Err(SceneError::InvalidVector {
            field: "gravity",
            ..
        })
    ));
}

#[test]
fn counts_too_large_to_index_are_errors_not_panics() {
    let too_large =
        |r: Result<hooke_scenes::Body, SceneError>| matches!(r, Err(SceneError::TooLarge { .. }));
    assert!(too_large(Cloth::grid(usize::MAX, 2).build()));
    assert!(too_large(
        Rope::between([0.0; 3], [1.0; 3], usize::MAX).build()
    ));
    assert!(too_large(Lattice::cubes(usize::MAX, 1, 1).build()));
    assert!(too_large(Lattice::cubes(1 << 22, 1 << 22, 1 << 22).build()));
    // A header promising more points than the file holds.
    let huge = format!("{} 3 {} 0\n1 0 0 0\n", usize::MAX, usize::MAX);
    assert!(matches!(
        tetgen::parse(&huge, "0 4 0\n"),
        Err(SceneError::Parse { line: 2, .. })
    ));
}
