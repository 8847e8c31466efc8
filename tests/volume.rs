//! Volume elements turn an inverted body back out: a spring tetrahedron
//! whose apex was pushed through its base to its mirror image is at rest for
//! its springs (the mirror image has the same edge lengths), and only the
//! volume element's energy `½ κ V₀ (J − 1)²` can tell it from the original.

use hooke::explicit::SymplecticEuler;
use hooke::implicit::{FastMassSpring, Implicit, LinearSolver};
use hooke::prelude::*;

/// The rest shape: a base triangle in the plane y = 0 and an apex above.
const REST: [[f64; 3]; 4] = [
    [0.0, 0.0, 0.0],
    [0.1, 0.0, 0.0],
    [0.03, 0.0, 0.09],
    [0.04, 0.08, 0.03],
];

const EDGES: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];

/// The tetrahedron at rest: 0.25 kg particles, springs of 100 N/m with
/// damping 0.5 N·s/m on its six edges, and a volume element of modulus
/// `kappa` (Pa).
fn tet(kappa: f64) -> System {
    let mut b = SystemBuilder::new();
    let p = REST.map(|x| b.particle(0.25, x));
    for (i, j) in EDGES {
        b.spring(p[i], p[j], 100.0).damping(0.5);
    }
    b.tet(p, kappa);
    b.build().unwrap()
}

/// The rest state with the apex mirrored through the base (`y → −y`):
/// every spring at its rest length, the element's volume ratio −1.
fn inverted(system: &System) -> State {
    let mut state = system.initial_state();
    state.positions_mut()[3].y *= -1.0;
    state
}

/// Runs `integrator` for `duration` at steps of `dt` from the inverted
/// state and returns the volume ratio and the largest relative error of an
/// edge length at the end.
fn recover(integrator: &mut dyn Integrator, kappa: f64, dt: f64, duration: f64) -> (f64, f64) {
    let system = tet(kappa);
    let mut state = inverted(&system);
    let start = system.inversion(state.positions()).unwrap();
    assert_eq!(start.inverted, 1);
    assert!((start.smallest_ratio + 1.0).abs() < 1e-12);
    let steps = (duration / dt).round() as usize;
    for _ in 0..steps {
        integrator.step(&system, &mut state, dt).unwrap();
    }
    let x = state.positions();
    let ratio = system.tets()[0].volume_ratio(x);
    let shape = system
        .springs()
        .iter()
        .map(|s| ((x[s.i] - x[s.j]).norm() / s.rest_length - 1.0).abs())
        .fold(0.0, f64::max);
    (ratio, shape)
}

/// The modulus the springs give the tetrahedron under uniform dilation,
/// `Σ k L² / (9 V₀)`: the volume term as stiff as the springs.
fn matched_modulus() -> f64 {
    let system = tet(0.0);
    let sum: f64 = system
        .springs()
        .iter()
        .map(|s| s.stiffness * s.rest_length * s.rest_length)
        .sum();
    sum / (9.0 * system.tets()[0].rest_volume)
}

#[test]
fn springs_alone_leave_the_mirrored_tet_inverted() {
    let mut integrator = Implicit::backward_euler();
    let (ratio, shape) = recover(&mut integrator, 0.0, 0.01, 2.0);
    assert!((ratio + 1.0).abs() < 1e-9, "J = {ratio}");
    assert!(shape < 1e-9);
}

#[test]
fn every_integrator_turns_the_tet_back_to_its_rest_shape() {
    let kappa = matched_modulus();
    let mut integrators: Vec<(&str, Box<dyn Integrator>, f64)> = vec![
        ("backward Euler", Box::new(Implicit::backward_euler()), 0.01),
        (
            "backward Euler, Cholesky, exact Newton",
            Box::new(
                Implicit::backward_euler()
                    .with_solver(LinearSolver::Cholesky)
                    .with_inexact_newton(false),
            ),
            0.01,
        ),
        ("BDF2", Box::new(Implicit::bdf2()), 0.01),
        (
            "linearised backward Euler",
            Box::new(Implicit::backward_euler().linearized()),
            0.01,
        ),
        (
            "fast mass-spring",
            Box::new(FastMassSpring::new(20).unwrap()),
            0.01,
        ),
        ("symplectic Euler", Box::new(SymplecticEuler::new()), 1e-3),
    ];
    for (name, integrator, dt) in &mut integrators {
        let (ratio, shape) = recover(integrator.as_mut(), kappa, *dt, 4.0);
        assert!(
            (ratio - 1.0).abs() < 1e-3 && shape < 1e-3,
            "{name}: J = {ratio}, largest edge strain {shape}"
        );
    }
}

/// The built-in jelly cube (6 × 6 × 6 cells of 5 cm) with its moduli
/// divided by ten, its corner at height `drop`, with `connectivity`; the
/// scene's own integrator: backward Euler at the library's defaults.
fn soft_cube(connectivity: &str, drop: f64) -> Scene {
    let text = include_str!("../scenes/jelly-cube.toml")
        .replace("modulus = 300.0", "modulus = 30.0")
        .replace("modulus = 150.0", "modulus = 15.0")
        .replace("modulus = 100.0", "modulus = 10.0")
        .replace(
            "origin = [-0.15, 0.4, -0.15]",
            &format!("origin = [-0.15, {drop}, -0.15]"),
        )
        .replace(
            "connectivity = \"cubes\"",
            &format!("connectivity = \"{connectivity}\""),
        );
    assert!(text.contains("modulus = 30.0") && text.contains(&format!("{drop}, -0.15")));
    hooke::scenes::file::parse(&text, std::path::Path::new("soft-cube.toml")).unwrap()
}

/// How many of the lattice's 6 × 6 × 6 cells have a corner whose three
/// edges into the cell, each pointing away from the corner, are left-handed
/// (the cell turned inside out there).
fn inverted_cells(x: &[Vec3]) -> usize {
    let n = 6;
    let at = |i: usize, j: usize, k: usize| x[(k * (n + 1) + j) * (n + 1) + i];
    let mut inverted = 0;
    for (i, j, k) in (0..n).flat_map(|i| (0..n).flat_map(move |j| (0..n).map(move |k| (i, j, k)))) {
        let corner_inverted = (0..8).any(|c| {
            let (a, b, d) = (c & 1, (c >> 1) & 1, (c >> 2) & 1);
            let p = at(i + a, j + b, k + d);
            let sign = |s: usize| if s == 0 { 1.0 } else { -1.0 };
            let ex = sign(a) * (at(i + 1 - a, j + b, k + d) - p);
            let ey = sign(b) * (at(i + a, j + 1 - b, k + d) - p);
            let ez = sign(d) * (at(i + a, j + b, k + 1 - d) - p);
            ex.cross(&ey).dot(&ez) <= 0.0
        });
        inverted += usize::from(corner_inverted);
    }
    inverted
}

/// Runs `scene` for its duration; returns the final state and the largest
/// number of inverted elements in any step, asserting at every step that
/// the energy stays at or below its start (gravity's work is part of the
/// energy as its potential).
fn run(scene: &Scene) -> (State, usize) {
    let system = &scene.system;
    let mut integrator = scene.integrator.build().unwrap();
    let mut state = system.initial_state();
    let start = system.energy(&state).unwrap().total();
    let dt = scene.timing.dt;
    let mut worst = 0;
    for step in 0..scene.timing.steps() {
        integrator.step(system, &mut state, dt).unwrap();
        let energy = system.energy(&state).unwrap().total();
        assert!(
            energy <= start + 1e-9 * start.abs(),
            "step {step}: energy {energy} J above its start {start} J"
        );
        worst = worst.max(system.inversion(state.positions()).unwrap().inverted);
    }
    (state, worst)
}

fn height(x: &[Vec3]) -> f64 {
    let (low, high) = x
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.y), hi.max(p.y))
        });
    high - low
}

#[test]
fn a_soft_cube_dropped_hard_recovers_its_shape() {
    let scene = soft_cube("cubes", 1.5);
    let (state, _) = run(&scene);
    let x = state.positions();
    let inversion = scene.system.inversion(x).unwrap();
    assert!(height(x) >= 0.28, "height at 3 s {} m", height(x));
    assert_eq!(
        inversion.inverted, 0,
        "smallest J {}",
        inversion.smallest_ratio
    );
    assert_eq!(inverted_cells(x), 0);
}

#[test]
fn a_soft_tet_lattice_placed_gently_never_inverts() {
    let scene = soft_cube("tets-6", 0.001);
    let (state, worst) = run(&scene);
    assert_eq!(worst, 0);
    assert_eq!(inverted_cells(state.positions()), 0);
    assert!(
        height(state.positions()) >= 0.28,
        "height {}",
        height(state.positions())
    );
}

/// The built-in jelly cube falls 0.4 m onto a floor with `μ = 0.5`. At
/// the impact its underside spreads and friction stops it under a normal
/// force many times its weight; Newton's exact model of the friction,
/// constant while a contact slides, carries the contacts through rest and
/// back (the landing step took 264 iterations in three substeps, most of
/// them halving the step length). Once a full step fails, the majorizing
/// model takes over and no step takes more than 30 iterations.
#[test]
fn a_lattice_cube_lands_on_a_floor_with_friction_in_few_newton_iterations() {
    let scene = builtin::load("jelly-cube").unwrap();
    let system = &scene.system;
    let mut integrator = scene.integrator.build().unwrap();
    let mut state = system.initial_state();
    let dt = scene.timing.dt;
    let mut landed = false;
    for step in 0..(0.5 / dt).round() as usize {
        let report = integrator.step(system, &mut state, dt).unwrap();
        landed |= report.contacts > 0;
        assert!(
            report.newton_iterations_max <= 30,
            "step {step}: {} Newton iterations",
            report.newton_iterations_max
        );
    }
    assert!(landed);
}

/// The built-in layered ball, dropped straight onto the floor, lands and
/// bounces in place. Its mesh and springs are symmetric, and so are its
/// volume elements, the six cuts of each prism averaged: its centre of
/// mass stays on the vertical through its start (each prism cut one way
/// alone, the ball landed turning, 9 mm off that line at 1 s and rolling
/// away, and its energy gains along the rolling steps' chords cost it 21
/// rejected substeps). No substep is rejected, and its energy never rises
/// above its start.
#[test]
fn a_layered_ball_dropped_straight_bounces_in_place() {
    let scene = builtin::load("layered-ball").unwrap();
    let system = &scene.system;
    let mut integrator = scene.integrator.build().unwrap();
    let mut state = system.initial_state();
    let start = system.energy(&state).unwrap().total();
    let mass: f64 = system.masses().iter().sum();
    let mut report = StepReport::default();
    let mut landed = false;
    while state.time() < 1.75 {
        let step = integrator
            .step(system, &mut state, scene.timing.dt)
            .unwrap();
        landed |= step.contacts > 0;
        report += step;
        let energy = system.energy(&state).unwrap().total();
        assert!(energy <= start, "{energy} J above its start {start} J");
        let centre = system
            .masses()
            .iter()
            .zip(state.positions())
            .map(|(&m, x)| m * x)
            .sum::<Vec3>()
            / mass;
        assert!(
            centre.x.hypot(centre.z) < 1e-9,
            "t = {} s: centre {centre:?}",
            state.time()
        );
    }
    assert!(landed);
    assert_eq!(report.rejected_steps, 0, "{report:?}");
}
