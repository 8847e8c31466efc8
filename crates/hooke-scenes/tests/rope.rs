//! Rope: counts, rest lengths, masses, pins, the refinement invariance of
//! `Stiffness::Modulus`, and every error.

use approx::assert_relative_eq;
use hooke_core::{Spring, Vec3};
use hooke_scenes::{Body, Family, Mass, Rope, SceneError, Springs};

fn rope(segments: usize, stretch: Springs) -> Body {
    Rope::between([0.0, 1.0, 0.0], [3.0, 1.0, 4.0], segments) // 5 m long
        .stretch(stretch)
        .build()
        .unwrap()
}

/// End-to-end stiffness measured through the springs' energy: stretch the
/// whole rope uniformly by `δ` and read `K` off `E = ½ K δ²`.
fn effective_stiffness(body: &Body) -> f64 {
    let (first, last) = (body.positions()[0], *body.positions().last().unwrap());
    let length = (last - first).norm();
    let delta = 1e-3;
    let stretched: Vec<Vec3> = body
        .positions()
        .iter()
        .map(|p| first + (p - first) * (1.0 + delta / length))
        .collect();
    let energy: f64 = body
        .springs()
        .iter()
        .map(|s| {
            let spring = Spring {
                i: s.i,
                j: s.j,
                stiffness: s.stiffness,
                rest_length: s.rest_length,
                damping: 0.0,
            };
            spring.energy(stretched[s.i], stretched[s.j])
        })
        .sum();
    2.0 * energy / (delta * delta)
}

#[test]
fn modulus_keeps_the_end_to_end_stiffness_under_refinement() {
    let coarse = effective_stiffness(&rope(10, Springs::modulus(400.0)));
    let fine = effective_stiffness(&rope(40, Springs::modulus(400.0)));
    assert_relative_eq!(coarse, 400.0 / 5.0, max_relative = 1e-9);
    assert_relative_eq!(fine, 400.0 / 5.0, max_relative = 1e-9);
}

#[test]
fn per_spring_stiffness_softens_under_refinement() {
    let coarse = effective_stiffness(&rope(10, Springs::per_spring(400.0)));
    let fine = effective_stiffness(&rope(40, Springs::per_spring(400.0)));
    assert_relative_eq!(coarse, 40.0, max_relative = 1e-9);
    assert_relative_eq!(fine, 10.0, max_relative = 1e-9);
}

#[test]
fn counts_rest_lengths_and_segments() {
    let body = Rope::between([0.0; 3], [0.0, -2.0, 0.0], 8)
        .stretch(1.0)
        .bend(2.0)
        .build()
        .unwrap();
    assert_eq!(body.particle_count(), 9);
    assert_eq!(body.springs_of(Family::Stretch).count(), 8);
    assert_eq!(body.springs_of(Family::Bend).count(), 7);
    for s in body.springs() {
        let expected = if s.family == Family::Stretch {
            0.25
        } else {
            0.5
        };
        assert_relative_eq!(s.rest_length, expected, epsilon = 1e-12);
        assert_eq!(s.j - s.i, if s.family == Family::Stretch { 1 } else { 2 });
    }
    assert!(body.triangles().is_empty());
    assert_eq!(body.segments().len(), 8);
    assert_eq!(body.segments()[3], [3, 4]);
    assert_eq!(body.positions()[8], Vec3::new(0.0, -2.0, 0.0));
}

#[test]
fn masses_are_lumped_per_segment_and_sum_to_the_total() {
    let body = Rope::between([0.0; 3], [2.0, 0.0, 0.0], 4)
        .mass(Mass::Density(0.3))
        .build()
        .unwrap();
    assert_relative_eq!(body.total_mass(), 0.6, epsilon = 1e-15);
    assert_relative_eq!(body.masses()[0], 0.075, epsilon = 1e-15);
    assert_relative_eq!(body.masses()[2], 0.15, epsilon = 1e-15);
    let one = Rope::between([0.0; 3], [1.0, 0.0, 0.0], 1)
        .mass(Mass::Total(3.0))
        .build()
        .unwrap();
    assert_eq!(one.masses(), [1.5, 1.5]);
}

#[test]
fn pins_at_either_or_both_ends() {
    let r = || Rope::between([0.0; 3], [1.0, 0.0, 0.0], 5);
    assert_eq!(r().pin_start().build().unwrap().pins(), [0]);
    assert_eq!(r().pin_end().build().unwrap().pins(), [5]);
    assert_eq!(r().pin_end().pin_start().build().unwrap().pins(), [0, 5]);
    assert!(r().build().unwrap().pins().is_empty());
}

#[test]
fn bad_parameters_are_errors() {
    let r = |n| Rope::between([0.0; 3], [1.0, 0.0, 0.0], n);
    assert!(matches!(
        r(0).build(),
        Err(SceneError::InvalidCount {
            field: "rope segments",
            value: 0,
            min: 1
        })
    ));
    assert!(matches!(
        Rope::between([1.0; 3], [1.0; 3], 3).build(),
        Err(SceneError::InvalidVector {
            field: "rope end",
            ..
        })
    ));
    assert!(matches!(
        Rope::between([f64::NAN, 0.0, 0.0], [1.0; 3], 3).build(),
        Err(SceneError::InvalidVector {
            field: "rope start",
            ..
        })
    ));
    assert!(matches!(
        r(3).mass(Mass::Density(0.0)).build(),
        Err(SceneError::InvalidValue {
            field: "density",
            ..
        })
    ));
    assert!(matches!(
        r(3).bend(Springs::per_spring(1.0).damping(f64::NAN))
            .build(),
        Err(SceneError::InvalidValue {
            field: "bend damping",
            ..
        })
    ));
}
