//! Contact between surfaces as barrier terms of the implicit step: cloth
//! resting on cloth never passes through it — counted in every step by a
//! brute-force triangle–triangle test written here, independent of the
//! library's — rests without jitter and never gains energy.

use hooke::core::Mat3;
use hooke::implicit::ContactLimit;
use hooke::prelude::*;
use hooke::scenes::{Body, Cloth, Edge, Mass, Plane, Springs};

/// `(a − d)·((b − d) × (c − d))`: six times the signed volume of the
/// tetrahedron `abcd`.
fn orient(a: Vec3, b: Vec3, c: Vec3, d: Vec3) -> f64 {
    (a - d).dot(&(b - d).cross(&(c - d)))
}

/// Whether the segment `pq` crosses the triangle `abc` (strictly: the ends
/// on opposite sides of its plane and the crossing point inside it). Signed
/// volumes within `tolerance` of zero count as zero, so that two nearly
/// coplanar triangles of a flat cloth, whose volumes are rounding noise,
/// are not taken for crossing.
fn segment_crosses(p: Vec3, q: Vec3, [a, b, c]: [Vec3; 3], tolerance: f64) -> bool {
    let sign = |volume: f64| {
        if volume.abs() <= tolerance {
            0.0
        } else {
            volume.signum()
        }
    };
    let (sp, sq) = (sign(orient(a, b, c, p)), sign(orient(a, b, c, q)));
    if sp * sq >= 0.0 {
        return false;
    }
    let (u, v, w) = (
        sign(orient(p, q, a, b)),
        sign(orient(p, q, b, c)),
        sign(orient(p, q, c, a)),
    );
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
            // 10⁻¹⁰ of the cube of the longest edge: far above the
            // rounding of a volume, far below that of a real crossing.
            let longest = (0..3)
                .flat_map(|e| {
                    [
                        (a[e] - a[(e + 1) % 3]).norm(),
                        (b[e] - b[(e + 1) % 3]).norm(),
                    ]
                })
                .fold(0.0, f64::max);
            let tolerance = 1e-10 * longest.powi(3);
            let crosses = (0..3).any(|e| segment_crosses(a[e], a[(e + 1) % 3], b, tolerance))
                || (0..3).any(|e| segment_crosses(b[e], b[(e + 1) % 3], a, tolerance));
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

/// The default scene's world in `b`: gravity, air damping of 10⁻⁵ N·s/m,
/// and a sphere of `radius` resting on the floor at the origin, both with
/// friction 0.5.
fn sphere_on_floor(b: &mut SystemBuilder, radius: f64) {
    b.gravity([0.0, -9.81, 0.0]);
    b.air_damping(1e-5);
    b.obstacle(
        Obstacle::new(Shape::Sphere {
            center: Vec3::new(0.0, radius, 0.0),
            radius,
        })
        .friction(0.5),
    );
    b.obstacle(floor(0.5));
}

/// Steps `system` for `duration` s with the library's default implicit step,
/// and again with per-particle contact bounds, checking every step's
/// positions for intersecting triangles and the energy (springs, kinetic,
/// gravity) against its start; returns the default step's state.
fn run_without_intersections(system: &System, dt: f64, duration: f64) -> State {
    run_from(system, system.initial_state(), dt, duration)
}

/// [`run_without_intersections`] from `state`.
fn run_from(system: &System, state: State, dt: f64, duration: f64) -> State {
    let particles = Implicit::backward_euler().with_contact_limit(ContactLimit::Particles);
    run_with(particles, system, state.clone(), dt, duration);
    run_with(Implicit::backward_euler(), system, state, dt, duration)
}

/// [`run_from`] with `integrator`.
fn run_with(
    mut integrator: Implicit,
    system: &System,
    mut state: State,
    dt: f64,
    duration: f64,
) -> State {
    let triangles = system.surfaces().triangles().to_vec();
    assert!(!triangles.is_empty());
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

/// A free, horizontal `n × n` cloth of side `size` of the default scene's
/// stiff cloth, smaller: 0.2 kg/m², stretch and shear springs of 10⁴ and
/// 10³ N/m.
fn stiff_cloth(n: usize, size: f64) -> Cloth {
    Cloth::grid(n, n)
        .size(size, size)
        .mass(Mass::Total(0.2 * size * size))
        .stretch(Springs::per_spring(1e4).damping(0.02))
        .shear(Springs::per_spring(1e3).damping(0.01))
        .bend(1.0)
}

/// A [`stiff_cloth`] standing on a corner: in a vertical plane turned 30°
/// within it and leaning 3° out of it (the `cloth-pile` scene's pose), its
/// lowest corner `height` above the origin.
fn standing_cloth(n: usize, size: f64, height: f64) -> Body {
    let cloth = |offset: [f64; 3]| {
        stiff_cloth(n, size)
            .plane(Plane::Vertical)
            .rotate([0.0972, 0.0261, 0.9949], 30.15_f64.to_radians())
            .offset(offset)
            .build()
            .unwrap()
    };
    let lowest = cloth([0.0; 3])
        .positions()
        .iter()
        .map(|p| p.y)
        .fold(f64::INFINITY, f64::min);
    cloth([-0.5 * size, height - lowest, 0.0])
}

/// The `cloth-pile` scene at a size the test suite can afford (12 × 12
/// particles, 0.4 m, dropped from 10 cm): it lands on its corner, folds
/// over onto itself and settles, and no two of its triangles ever
/// intersect.
#[test]
fn a_cloth_dropped_on_its_corner_folds_onto_itself_without_passing_through() {
    let mut b = SystemBuilder::new();
    standing_cloth(12, 0.4, 0.3).add_to(&mut b);
    b.gravity([0.0, -9.81, 0.0]);
    b.air_damping(1e-5);
    b.obstacle(floor(0.5));
    let system = b.build().unwrap();
    assert!(system.has_surface_contact());
    let state = run_without_intersections(&system, 1.0 / 60.0, 2.0);
    // It has fallen over: every particle within 10 cm of the floor.
    let x = state.positions();
    let highest = x.iter().map(|p| p.y).fold(0.0, f64::max);
    assert!(highest < 0.1, "the highest particle is {highest} m up");
    // And folded onto itself: particles at least three grid spacings apart
    // in the cloth lie within half a spacing of each other.
    let spacing = 0.4 / 11.0;
    let rest = system.initial_positions();
    let folded = (0..x.len())
        .flat_map(|i| (i + 1..x.len()).map(move |j| (i, j)))
        .filter(|&(i, j)| {
            (rest[i] - rest[j]).norm() > 3.0 * spacing && (x[i] - x[j]).norm() < 0.5 * spacing
        })
        .count();
    assert!(folded > 0, "no layer lies on another");
}

/// The particles of `upper` within `reach` of a particle of `lower`.
fn close_to(
    x: &[Vec3],
    upper: std::ops::Range<usize>,
    lower: std::ops::Range<usize>,
    reach: f64,
) -> usize {
    upper
        .filter(|&i| lower.clone().any(|j| (x[i] - x[j]).norm() < reach))
        .count()
}

/// Two cloths, the upper turned 45°, dropped onto each other and over a
/// sphere (the `two-cloths` scene with 10 × 10 particles each): no triangle
/// of either ever intersects another.
#[test]
fn two_cloths_falling_onto_each_other_over_a_sphere_never_intersect() {
    let mut b = SystemBuilder::new();
    for (height, degrees) in [(0.3, 0.0), (0.36, 45.0)] {
        stiff_cloth(10, 0.5)
            .bend(20.0)
            .rotate([0.0, 1.0, 0.0], f64::to_radians(degrees))
            .offset([-0.25, height, -0.25])
            .build()
            .unwrap()
            .add_to(&mut b);
    }
    sphere_on_floor(&mut b, 0.12);
    let system = b.build().unwrap();
    // 6 cm apart at the start; at the end the upper lies on the lower, its
    // particles within ¾ of a grid spacing (5.6 cm) of the lower's.
    let reach = 0.75 * 0.5 / 9.0;
    assert_eq!(
        close_to(system.initial_positions(), 100..200, 0..100, reach),
        0
    );
    let state = run_without_intersections(&system, 1.0 / 60.0, 1.0);
    let resting = close_to(state.positions(), 100..200, 0..100, reach);
    assert!(
        resting >= 20,
        "{resting} particles of the upper cloth rest on the lower"
    );
}

/// A small cloth shot at 30 m/s at a larger one held by its border, 2 cm
/// below, without gravity: it covers 25 times that gap in one step, so
/// only continuous collision detection stands between the two; it never
/// passes through, and stays above the lowest point of the other (the
/// lowest point of a triangle mesh is a vertex).
#[test]
fn a_cloth_shot_at_another_does_not_tunnel_through_it() {
    let mut b = SystemBuilder::new();
    Cloth::grid(9, 9)
        .size(0.3, 0.3)
        .mass(Mass::Total(0.02))
        .stretch(1e4)
        .shear(1e3)
        .bend(1.0)
        .pin_edge(Edge::Top)
        .pin_edge(Edge::Bottom)
        .pin_edge(Edge::Left)
        .pin_edge(Edge::Right)
        .offset([-0.15, 0.0, -0.15])
        .build()
        .unwrap()
        .add_to(&mut b);
    Cloth::grid(4, 4)
        .size(0.06, 0.06)
        .mass(Mass::Total(0.002))
        .stretch(1e3)
        .shear(1e2)
        .bend(1.0)
        .offset([-0.027, 0.02, -0.033])
        .build()
        .unwrap()
        .add_to(&mut b);
    let system = b.build().unwrap();
    let mut state = system.initial_state();
    for v in &mut state.velocities_mut()[81..] {
        *v = Vec3::new(0.0, -30.0, 0.0);
    }
    let state = run_from(&system, state, 1.0 / 60.0, 0.1);
    let lowest = |range: std::ops::Range<usize>| {
        state.positions()[range]
            .iter()
            .map(|p| p.y)
            .fold(f64::INFINITY, f64::min)
    };
    assert!(
        lowest(81..97) > lowest(0..81),
        "the small cloth went through: {} m against {} m",
        lowest(81..97),
        lowest(0..81)
    );
}

/// A 20 cm cloth thrown at 20 m/s at a box 1 cm thick, 3 cm below it: it
/// covers 33 cm a step, through the box and out of it, so only the bounds
/// on each iterate's motion keep it out. Under either contact limit it
/// ends on the box's top face, no particle below it and no two triangles
/// ever intersecting.
#[test]
fn a_cloth_thrown_fast_at_a_thin_box_lands_on_it() {
    let mut b = SystemBuilder::new();
    stiff_cloth(8, 0.2)
        .offset([-0.1, 0.035, -0.1])
        .build()
        .unwrap()
        .add_to(&mut b);
    b.gravity([0.0, -9.81, 0.0]);
    let top = 0.005;
    b.obstacle(
        Obstacle::new(Shape::Box {
            center: Vec3::zeros(),
            half_extents: Vec3::new(0.3, top, 0.3),
            rotation: Mat3::identity(),
        })
        .friction(0.5),
    );
    let system = b.build().unwrap();
    let mut state = system.initial_state();
    for v in state.velocities_mut() {
        *v = Vec3::new(0.0, -20.0, 0.0);
    }
    let state = run_from(&system, state, 1.0 / 60.0, 0.25);
    let lowest = state
        .positions()
        .iter()
        .map(|p| p.y)
        .fold(f64::INFINITY, f64::min);
    assert!(
        lowest > top && lowest < top + 0.01,
        "the lowest particle is at {lowest} m"
    );
}

/// A 12 × 12 cloth, 0.5 m wide, dropped 5 cm onto a sphere of 8 cm
/// radius on the floor: it drapes over the sphere, folding under it, and
/// no two of its triangles ever intersect.
#[test]
fn a_cloth_folding_under_a_sphere_never_intersects() {
    let mut b = SystemBuilder::new();
    stiff_cloth(12, 0.5)
        .offset([-0.23, 0.21, -0.26])
        .build()
        .unwrap()
        .add_to(&mut b);
    sphere_on_floor(&mut b, 0.08);
    let system = b.build().unwrap();
    let state = run_without_intersections(&system, 1.0 / 60.0, 1.0);
    // Draped: its corners on the floor, its middle on the sphere's top.
    let x = state.positions();
    let highest = x.iter().map(|p| p.y).fold(0.0, f64::max);
    assert!(highest < 0.18, "the highest particle is {highest} m up");
}
