//! Box lattices: unique springs per family against hand counts, masses,
//! surfaces, and errors.

use approx::assert_relative_eq;
use hooke_scenes::{Body, Family, Lattice, Mass, SceneError, TetSplit};

const CELLS: [usize; 3] = [2, 3, 4];

fn all_families(lattice: Lattice) -> Body {
    lattice
        .size([2.0, 1.5, 1.0])
        .edges(10.0)
        .face_diagonals(20.0)
        .body_diagonals(30.0)
        .build()
        .unwrap()
}

fn counts(body: &Body) -> [usize; 3] {
    [Family::Edge, Family::FaceDiagonal, Family::BodyDiagonal].map(|f| body.springs_of(f).count())
}

// For a × b × c = 2 × 3 × 4 cells: 3·4·5 = 60 points; cube edges
// a(b+1)(c+1) + (a+1)b(c+1) + (a+1)(b+1)c = 40 + 45 + 48 = 133; cell faces
// (a+1)bc + a(b+1)c + ab(c+1) = 36 + 32 + 30 = 98; cubes abc = 24.
const EDGES: usize = 133;
const FACES: usize = 98;
const CUBES: usize = 24;

#[test]
fn cube_lattice_has_every_edge_face_diagonal_and_body_diagonal_once() {
    let body = all_families(Lattice::cubes(CELLS[0], CELLS[1], CELLS[2]));
    assert_eq!(body.particle_count(), 60);
    assert_eq!(counts(&body), [EDGES, 2 * FACES, 4 * CUBES]);
}

#[test]
fn tet_splits_have_one_diagonal_per_face() {
    let [a, b, c] = CELLS;
    let six = all_families(Lattice::tets(a, b, c, TetSplit::Six));
    assert_eq!(counts(&six), [EDGES, FACES, CUBES]);
    // With five tets the split alternates, so neighbours agree on the
    // diagonal of the face they share: exactly one per face, none inside.
    let five = all_families(Lattice::tets(a, b, c, TetSplit::Five));
    assert_eq!(counts(&five), [EDGES, FACES, 0]);
}

#[test]
fn rest_lengths_and_stiffness_follow_the_cell_spacing() {
    let body = all_families(Lattice::cubes(CELLS[0], CELLS[1], CELLS[2]));
    // Spacing 1.0 × 0.5 × 0.25.
    let (dx, dy, dz) = (1.0f64, 0.5f64, 0.25f64);
    for s in body.springs() {
        let expected: &[f64] = match s.family {
            Family::Edge => &[dx, dy, dz],
            Family::FaceDiagonal => &[dx.hypot(dy), dy.hypot(dz), dz.hypot(dx)],
            _ => &[(dx * dx + dy * dy + dz * dz).sqrt()],
        };
        assert!(
            expected.iter().any(|e| (e - s.rest_length).abs() < 1e-12),
            "{s:?}"
        );
    }
}

/// `Σ a·(b × c)/6` over the surface: the enclosed volume when the
/// triangles are closed and face outward.
fn enclosed_volume(body: &Body) -> f64 {
    let p = body.positions();
    body.triangles()
        .iter()
        .map(|&[a, b, c]| p[a].dot(&p[b].cross(&p[c])) / 6.0)
        .sum()
}

#[test]
fn surfaces_close_the_box_and_face_outward() {
    let [a, b, c] = CELLS;
    for lattice in [
        Lattice::cubes(a, b, c),
        Lattice::tets(a, b, c, TetSplit::Five),
        Lattice::tets(a, b, c, TetSplit::Six),
    ] {
        let body = lattice
            .size([2.0, 1.5, 1.0])
            .origin([1.0, -2.0, 0.5])
            .build()
            .unwrap();
        assert_eq!(body.triangles().len(), 4 * (a * b + b * c + c * a));
        assert_relative_eq!(enclosed_volume(&body), 3.0, epsilon = 1e-12);
    }
}

#[test]
fn mass_is_conserved_and_cube_corners_get_an_eighth() {
    let cubes = Lattice::cubes(2, 2, 2)
        .mass(Mass::Density(8.0))
        .build()
        .unwrap();
    assert_relative_eq!(cubes.total_mass(), 8.0, epsilon = 1e-12);
    assert_relative_eq!(cubes.masses()[0], 1.0 / 8.0, epsilon = 1e-15); // 1 kg cells
    assert_relative_eq!(cubes.masses()[13], 1.0, epsilon = 1e-15); // centre: 8 cells
    for split in [TetSplit::Five, TetSplit::Six] {
        let tets = Lattice::tets(3, 1, 2, split)
            .size([3.0, 1.0, 2.0])
            .mass(Mass::Density(5.0))
            .build()
            .unwrap();
        assert_relative_eq!(tets.total_mass(), 30.0, epsilon = 1e-12);
    }
}

#[test]
fn a_single_kuhn_cube_builds_into_a_system() {
    let body = Lattice::tets(1, 1, 1, TetSplit::Six)
        .edges(1.0)
        .face_diagonals(1.0)
        .body_diagonals(1.0)
        .pin(0)
        .build()
        .unwrap();
    assert_eq!(body.springs().len(), 12 + 6 + 1);
    let system = body.system([0.0; 3]).unwrap();
    assert_eq!(system.particle_count(), 8);
    assert_eq!(system.springs().len(), 19);
    assert!(system.is_pinned(0));
    assert_eq!(system.gravity(), None);
}

#[test]
fn bad_parameters_are_errors() {
    assert!(matches!(
        Lattice::cubes(2, 0, 2).build(),
        Err(SceneError::InvalidCount {
            field: "lattice cells along y",
            ..
        })
    ));
    assert!(matches!(
        Lattice::cubes(1, 1, 1).size([1.0, 1.0, -1.0]).build(),
        Err(SceneError::InvalidValue {
            field: "lattice size along z",
            ..
        })
    ));
    assert!(matches!(
        Lattice::cubes(1, 1, 1)
            .origin([f64::INFINITY, 0.0, 0.0])
            .build(),
        Err(SceneError::InvalidVector {
            field: "lattice origin",
            ..
        })
    ));
    assert!(matches!(
        Lattice::tets(1, 1, 1, TetSplit::Five)
            .face_diagonals(-3.0)
            .build(),
        Err(SceneError::InvalidValue {
            field: "face-diagonal stiffness",
            ..
        })
    ));
    assert!(matches!(
        Lattice::cubes(1, 1, 1).pin(8).build(),
        Err(SceneError::PinOutOfRange {
            particle: 8,
            particles: 8
        })
    ));
}
