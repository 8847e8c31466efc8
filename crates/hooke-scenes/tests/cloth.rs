//! Cloth: spring counts and rest lengths per family against hand counts,
//! masses, pins, surface orientation, placement, and every error.

use approx::assert_relative_eq;
use hooke_core::Vec3;
use hooke_scenes::{Cloth, Corner, Edge, Family, Mass, Plane, SceneError, Springs};

fn full(n: usize, m: usize) -> Cloth {
    Cloth::grid(n, m).stretch(100.0).shear(50.0).bend(10.0)
}

#[test]
fn family_counts_match_the_hand_formulas() {
    for (n, m) in [(2, 2), (3, 3), (4, 7), (10, 5)] {
        let body = full(n, m).build().unwrap();
        let count = |f| body.springs_of(f).count();
        // n columns, m rows.
        assert_eq!(count(Family::Stretch), m * (n - 1) + n * (m - 1), "{n}x{m}");
        assert_eq!(count(Family::Shear), 2 * (n - 1) * (m - 1), "{n}x{m}");
        assert_eq!(count(Family::Bend), m * (n - 2) + n * (m - 2), "{n}x{m}");
        assert_eq!(body.triangles().len(), 2 * (n - 1) * (m - 1));
        assert_eq!(body.particle_count(), n * m);
    }
    // The 3x3 case by hand: 12 stretch, 8 shear, 6 bend.
    assert_eq!(full(3, 3).build().unwrap().springs().len(), 26);
}

#[test]
fn families_not_asked_for_are_absent() {
    let body = Cloth::grid(5, 5).shear(1.0).build().unwrap();
    assert!(body.springs().iter().all(|s| s.family == Family::Shear));
    assert!(Cloth::grid(5, 5).build().unwrap().springs().is_empty());
}

#[test]
fn rest_lengths_are_spacings_diagonals_and_double_spacings() {
    // 5 columns over 2 m: dx = 0.5; 3 rows over 0.6 m: dy = 0.3.
    let body = full(5, 3).size(2.0, 0.6).build().unwrap();
    for s in body.springs() {
        let (di, dj) = ((s.i % 5).abs_diff(s.j % 5), (s.i / 5).abs_diff(s.j / 5));
        let expected = (0.5 * di as f64).hypot(0.3 * dj as f64);
        assert_relative_eq!(s.rest_length, expected, epsilon = 1e-12);
        let family = match (di, dj) {
            (1, 0) | (0, 1) => Family::Stretch,
            (1, 1) => Family::Shear,
            (2, 0) | (0, 2) => Family::Bend,
            other => panic!("unexpected spring span {other:?}"),
        };
        assert_eq!(s.family, family);
    }
}

#[test]
fn each_family_has_its_own_stiffness_and_damping() {
    let body = Cloth::grid(4, 4)
        .size(3.0, 3.0)
        .stretch(Springs::per_spring(100.0).damping(1.0))
        .shear(Springs::modulus(30.0).damping(2.0))
        .bend(Springs::per_spring(5.0))
        .build()
        .unwrap();
    for s in body.springs() {
        let (k, c) = match s.family {
            Family::Stretch => (100.0, 1.0),
            Family::Shear => (30.0 / 2f64.sqrt(), 2.0), // dx = 1, diagonal √2
            Family::Bend => (5.0, 0.0),
            other => panic!("unexpected family {other:?}"),
        };
        assert_relative_eq!(s.stiffness, k, epsilon = 1e-12);
        assert_relative_eq!(s.damping, c);
    }
}

#[test]
fn mass_is_conserved_and_lumped_by_cell() {
    let body = Cloth::grid(6, 4)
        .size(2.0, 1.5)
        .mass(Mass::Density(0.4))
        .build()
        .unwrap();
    assert_relative_eq!(body.total_mass(), 0.4 * 2.0 * 1.5, epsilon = 1e-12);
    let cell = 1.2 / 15.0; // 5 × 3 cells
    assert_relative_eq!(body.masses()[0], cell / 4.0, epsilon = 1e-15);
    assert_relative_eq!(body.masses()[1], cell / 2.0, epsilon = 1e-15);
    assert_relative_eq!(body.masses()[7], cell, epsilon = 1e-15);
    let total = Cloth::grid(7, 3).mass(Mass::Total(2.5)).build().unwrap();
    assert_relative_eq!(total.total_mass(), 2.5, epsilon = 1e-12);
}

#[test]
fn pins_by_corner_edge_and_index() {
    let body = Cloth::grid(4, 3)
        .pin_corners([
            Corner::TopLeft,
            Corner::TopRight,
            Corner::BottomLeft,
            Corner::BottomRight,
        ])
        .build()
        .unwrap();
    assert_eq!(body.pins(), [0, 3, 8, 11]);
    let edges = |e| {
        Cloth::grid(4, 3)
            .pin_edge(e)
            .build()
            .unwrap()
            .pins()
            .to_vec()
    };
    assert_eq!(edges(Edge::Top), [0, 1, 2, 3]);
    assert_eq!(edges(Edge::Bottom), [8, 9, 10, 11]);
    assert_eq!(edges(Edge::Left), [0, 4, 8]);
    assert_eq!(edges(Edge::Right), [3, 7, 11]);
    let mixed = Cloth::grid(4, 3)
        .pin_edge(Edge::Top)
        .pin_corners([Corner::TopLeft])
        .pin(5);
    assert_eq!(mixed.build().unwrap().pins(), [0, 1, 2, 3, 5]);
}

fn normal(body: &hooke_scenes::Body, [a, b, c]: [usize; 3]) -> Vec3 {
    let p = body.positions();
    (p[b] - p[a]).cross(&(p[c] - p[a]))
}

#[test]
fn surface_faces_up_or_forward_and_covers_the_area() {
    let flat = Cloth::grid(3, 4).size(2.0, 3.0).build().unwrap();
    let area: f64 = flat
        .triangles()
        .iter()
        .map(|&t| 0.5 * normal(&flat, t).norm())
        .sum();
    assert_relative_eq!(area, 6.0, epsilon = 1e-12);
    assert!(flat.triangles().iter().all(|&t| normal(&flat, t).y > 0.0));
    let curtain = Cloth::grid(3, 4).plane(Plane::Vertical).build().unwrap();
    assert!(
        curtain
            .triangles()
            .iter()
            .all(|&t| normal(&curtain, t).z > 0.0)
    );
    assert!(curtain.positions().iter().all(|p| p.y <= 0.0 && p.z == 0.0));
}

#[test]
fn rotation_and_offset_move_the_cloth_rigidly() {
    let plain = full(4, 4).build().unwrap();
    let turned = full(4, 4)
        .rotate([1.0, 0.0, 0.0], std::f64::consts::FRAC_PI_2)
        .offset([0.0, 2.0, 0.0])
        .build()
        .unwrap();
    // A quarter turn about +x (right-hand rule) takes +z to −y.
    for (p, q) in plain.positions().iter().zip(turned.positions()) {
        assert_relative_eq!(*q, Vec3::new(p.x, 2.0 - p.z, 0.0), epsilon = 1e-12);
    }
    for (s, t) in plain.springs().iter().zip(turned.springs()) {
        assert_relative_eq!(s.rest_length, t.rest_length, epsilon = 1e-12);
    }
}

#[test]
fn bad_parameters_are_errors_naming_the_field() {
    let field = |cloth: Cloth| match cloth.build() {
        Err(SceneError::InvalidCount { field, .. }) => field,
        Err(SceneError::InvalidValue { field, .. }) => field,
        Err(SceneError::InvalidVector { field, .. }) => field,
        other => panic!("expected a field error, got {other:?}"),
    };
    assert_eq!(field(Cloth::grid(1, 5)), "cloth columns");
    assert_eq!(field(Cloth::grid(5, 0)), "cloth rows");
    assert_eq!(field(Cloth::grid(3, 3).size(0.0, 1.0)), "cloth width");
    assert_eq!(field(Cloth::grid(3, 3).size(1.0, f64::NAN)), "cloth height");
    assert_eq!(
        field(Cloth::grid(3, 3).mass(Mass::Total(-1.0))),
        "total mass"
    );
    assert_eq!(
        field(Cloth::grid(3, 3).mass(Mass::Density(f64::INFINITY))),
        "density"
    );
    assert_eq!(field(Cloth::grid(3, 3).stretch(-1.0)), "stretch stiffness");
    assert_eq!(
        field(Cloth::grid(3, 3).shear(Springs::per_spring(1.0).damping(-0.1))),
        "shear damping"
    );
    assert_eq!(
        field(Cloth::grid(3, 3).bend(Springs::modulus(f64::NAN))),
        "bend stiffness"
    );
    assert_eq!(
        field(Cloth::grid(3, 3).rotate([0.0; 3], 1.0)),
        "rotation axis"
    );
    assert_eq!(
        field(Cloth::grid(3, 3).rotate([0.0, 1.0, 0.0], f64::NAN)),
        "rotation angle"
    );
    assert_eq!(
        field(Cloth::grid(3, 3).offset([0.0, f64::NAN, 0.0])),
        "cloth offset"
    );
    assert!(matches!(
        Cloth::grid(3, 3).pin(9).build(),
        Err(SceneError::PinOutOfRange {
            particle: 9,
            particles: 9
        })
    ));
}
