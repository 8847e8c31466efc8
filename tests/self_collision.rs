//! Contact between surfaces as barrier terms of the implicit step: cloth
//! resting on cloth never passes through it — counted in every step by a
//! brute-force triangle–triangle test written here, independent of the
//! library's — rests without jitter and never gains energy.

use hooke::prelude::*;
use hooke::scenes::{Cloth, Mass};

/// `(a − d)·((b − d) × (c − d))`: six times the signed volume of the
/// tetrahedron `abcd`.
fn orient(a: Vec3, b: Vec3, c: Vec3, d: Vec3) -> f64 {
    (a - d).dot(&(b - d).cross(&(c - d)))
}

/// Whether the segment `pq` crosses the triangle `abc` (strictly: the ends
/// on opposite sides of its plane and the crossing point inside it).
fn segment_crosses(p: Vec3, q: Vec3, [a, b, c]: [Vec3; 3]) -> bool {
    let (sp, sq) = (orient(a, b, c, p), orient(a, b, c, q));
    if sp * sq >= 0.0 {
        return false;
    }
    let (u, v, w) = (orient(p, q, a, b), orient(p, q, b, c), orient(p, q, c, a));
    (u > 0.0 && v > 0.0 && w > 0.0) || (u < 0.0 && v < 0.0 && w < 0.0)
}

/// The pairs of triangles of `triangles` that share no particle and
/// intersect (an edge of one crosses the other), over every pair.
fn intersecting_pairs(x: &[Vec3], triangles: &[[usize; 3]]) -> usize {
    let corners = |t: [usize; 3]| t.map(|i| x[i]);
    let mut count = 0;
    for (k, &s) in triangles.iter().enumerate() {
        for &t in &triangles[k + 1..] {
            if s.iter().any(|i| t.contains(i)) {
                continue;
            }
            let (a, b) = (corners(s), corners(t));
            let crosses = (0..3).any(|e| segment_crosses(a[e], a[(e + 1) % 3], b))
                || (0..3).any(|e| segment_crosses(b[e], b[(e + 1) % 3], a));
            count += usize::from(crosses);
        }
    }
    count
}

#[test]
fn the_brute_force_test_sees_a_triangle_through_another() {
    let x = [
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(0.2, -0.5, 0.2),
        Vec3::new(0.2, 0.5, 0.2),
        Vec3::new(0.9, 0.5, 0.9),
    ];
    assert_eq!(intersecting_pairs(&x, &[[0, 1, 2], [3, 4, 5]]), 1);
    let apart: Vec<Vec3> = x.iter().map(|p| p + Vec3::new(0.0, 0.6, 0.0)).collect();
    let x2: Vec<Vec3> = x[..3].iter().chain(&apart[3..]).copied().collect();
    assert_eq!(intersecting_pairs(&x2, &[[0, 1, 2], [3, 4, 5]]), 0);
}

fn floor(friction: f64) -> Obstacle {
    Obstacle::new(Shape::Plane {
        point: Vec3::zeros(),
        normal: Vec3::y(),
    })
    .friction(friction)
}

/// Steps `system` for `duration` s with the library's default implicit step,
/// checking every step's positions for intersecting triangles and the
/// energy (springs, kinetic, gravity) against its start; returns the state.
fn run_without_intersections(system: &System, dt: f64, duration: f64) -> State {
    let triangles = system.surfaces().triangles().to_vec();
    assert!(!triangles.is_empty());
    let mut integrator = Implicit::backward_euler();
    let mut state = system.initial_state();
    let start = system.energy(&state).unwrap().total();
    for step in 0..(duration / dt).round() as usize {
        let report = integrator.step(system, &mut state, dt).unwrap();
        assert_eq!(report.unconverged_steps, 0, "step {step}");
        let crossing = intersecting_pairs(state.positions(), &triangles);
        assert_eq!(crossing, 0, "step {step}: {crossing} intersecting pairs");
        let energy = system.energy(&state).unwrap().total();
        assert!(
            energy <= start + 1e-9 * start.abs(),
            "step {step}: energy rose from {start} J to {energy} J"
        );
    }
    state
}

/// Two cloths stacked on the floor, the upper resting on the lower: after
/// they settle no particle moves more than a micrometre a step and the
/// energy never rises.
#[test]
fn cloth_resting_on_cloth_rests_without_jitter() {
    let mut b = SystemBuilder::new();
    for height in [0.002, 0.006] {
        Cloth::grid(8, 8)
            .size(0.3, 0.3)
            .mass(Mass::Total(0.02))
            .stretch(1e3)
            .shear(1e2)
            .bend(1.0)
            .offset([-0.15, height, -0.15])
            .build()
            .unwrap()
            .add_to(&mut b);
    }
    b.gravity([0.0, -9.81, 0.0]);
    b.air_damping(1e-4);
    b.obstacle(floor(0.5));
    let system = b.build().unwrap();
    let dt = 1.0 / 60.0;
    let mut state = run_without_intersections(&system, dt, 1.0);
    let mut integrator = Implicit::backward_euler();
    for _ in 0..30 {
        let before = state.positions().to_vec();
        integrator.step(&system, &mut state, dt).unwrap();
        let moved = before
            .iter()
            .zip(state.positions())
            .map(|(a, b)| (a - b).norm())
            .fold(0.0, f64::max);
        assert!(moved < 1e-6, "a particle moved {moved} m in a step");
    }
}
