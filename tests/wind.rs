//! The wind term ([`Wind`], a scene file's `[world] wind`) against theory:
//! a cloth hung in a steady wind comes to rest at the angle the balance of
//! drag and gravity gives, gaining no energy beyond the wind's work on the
//! way; an explicit integrator feels the same drag.

use std::path::Path;

use hooke::core::Wind;
use hooke::prelude::*;
use hooke::scenes::file;

/// The cloth's mass per area ρ, kg/m².
const DENSITY: f64 = 0.2;
/// The drag coefficient c, N·s/m³.
const DRAG: f64 = 0.5;
/// The wind's speed W along +z, m/s.
const SPEED: f64 = 2.0;
/// Standard gravity, m/s².
const G: f64 = 9.81;

/// A 1 m × 1 m curtain of `n × n` particles in the x–y plane, hung from
/// its top edge at y = 0, facing a wind along +z; stiff enough in stretch
/// that its area barely grows under its weight.
fn curtain(n: usize) -> Scene {
    let text = format!(
        r#"
        [simulation]
        duration = 10.0
        dt = 0.016666666666666666

        [integrator]
        method = "backward-euler"

        [world]
        wind = {{ velocity = [0.0, 0.0, {SPEED}], drag = {DRAG} }}

        [[bodies]]
        type = "cloth"
        columns = {n}
        rows = {n}
        size = [1.0, 1.0]
        plane = "vertical"
        density = {DENSITY}
        stretch = {{ stiffness = 1e4 }}
        shear = {{ stiffness = 1e3 }}
        bend = {{ stiffness = 1.0 }}
        self_collision = false
        pins = ["top"]
        "#
    );
    file::parse(&text, Path::new("curtain.toml")).unwrap()
}

/// The angle from the vertical of the sheet between rows `r1 < r2` over
/// the columns `columns`, of an `n`-column grid at positions `x`: the mean
/// of each column's `atan(Δz / −Δy)`.
fn angle(x: &[Vec3], n: usize, (r1, r2): (usize, usize), columns: std::ops::Range<usize>) -> f64 {
    let count = columns.len() as f64;
    columns
        .map(|c| {
            let (a, b) = (x[r1 * n + c], x[r2 * n + c]);
            (b.z - a.z).atan2(a.y - b.y)
        })
        .sum::<f64>()
        / count
}

/// For a flat sheet at the angle θ from the vertical at rest in the wind,
/// the loads normal to it per unit area balance: the drag `c W cos θ`
/// against gravity's `ρ g sin θ`, so `tan θ = c W / (ρ g)` (here 0.510,
/// θ = 27.0°), tension carrying the rest. That holds exactly for a
/// membrane away from its edges. The cloth's edge particles carry half an
/// interior one's mass and half its triangles' area, so they balance too,
/// but its corners do not (a corner's mass is a quarter of an interior
/// particle's, its share of the triangles' area a third or a sixth); and
/// the stretch under the sheet's weight grows the triangles, and the drag
/// with them, by the strain, at most `ρ g L / k ≈ 2·10⁻⁴` here, which
/// moves `tan θ` by as much and θ by less. So the angle is measured over
/// the middle rows and columns, away from the pinned edge and the corners,
/// and held to 5·10⁻⁴ of θ: above the strain's part, and far below what a
/// drag off by a factor (a wrong share per vertex, an area not halved)
/// would give. It lies 4·10⁻⁵ below.
///
/// Backward Euler at its defaults (Newton to a relative decrement of
/// 5·10⁻³) at 1/60 s brings the curtain to rest, every step passing the
/// energy test without any excess: the wind's work is counted (without
/// it, the first step, which the wind sets moving, is rejected until its
/// length reaches the floor).
#[test]
fn a_curtain_in_a_steady_wind_comes_to_rest_at_the_balance_angle() {
    let n = 13;
    let scene = curtain(n);
    let system = &scene.system;
    let mut integrator = scene.integrator.build().unwrap();
    let mut state = system.initial_state();
    let h = scene.timing.dt;
    let mut steps = 0;
    let mut excess: f64 = 0.0;
    loop {
        let report = integrator.step(system, &mut state, h).unwrap();
        assert_eq!(report.rejected_steps, 0, "step {steps}");
        assert_eq!(report.energy_corrections, 0, "step {steps}");
        excess = excess.max(report.energy_excess);
        steps += 1;
        let speed = state
            .velocities()
            .iter()
            .map(|v| v.norm())
            .fold(0.0, f64::max);
        if speed < 1e-6 || steps == 3000 {
            break;
        }
    }
    assert!(steps < 3000, "not at rest after {steps} steps");
    assert!(
        excess <= 0.0,
        "a step gained {excess} J beyond the wind's work"
    );
    let theory = (DRAG * SPEED / (DENSITY * G)).atan();
    let middle = angle(
        state.positions(),
        n,
        (n / 4, 3 * n / 4),
        n / 4..3 * n / 4 + 1,
    );
    assert!(
        (middle - theory).abs() <= 5e-4 * theory,
        "{}° against {}°",
        middle.to_degrees(),
        theory.to_degrees()
    );
}

/// One triangle of three equal masses `m`, at rest, released in a wind
/// without gravity, translates without turning: its normal velocity
/// relative to the air `u = (v − w)·n` obeys `m u' = −(c A / 3) u`, so
/// `v(t) = (w·n)(1 − e^{−λt}) n`, `λ = c A / (3m)`. Symplectic Euler, which
/// evaluates the force at its current state, follows it: its first step
/// gives exactly the acceleration `λ (w·n) n`, and at `λ dt = 10⁻⁴` its
/// velocity after `t = 2/λ` lies within its first-order error `λ² t dt |w·n|`
/// of the closed form.
#[test]
fn an_explicit_integrator_feels_the_drag() {
    let LoneTriangle {
        system,
        normal,
        lambda,
        wn,
    } = LoneTriangle::new();
    let dt = 1e-4 / lambda;
    let mut integrator = SymplecticEuler::new();
    let mut state = system.initial_state();
    integrator.step(&system, &mut state, dt).unwrap();
    let first = lambda * wn * normal;
    for v in state.velocities() {
        assert!(
            (v / dt - first).norm() <= 1e-12 * first.norm(),
            "{} against {first}",
            v / dt
        );
    }
    let steps = 20_000;
    for _ in 1..steps {
        integrator.step(&system, &mut state, dt).unwrap();
    }
    let time = steps as f64 * dt;
    let exact = wn * (1.0 - (-lambda * time).exp()) * normal;
    let tolerance = lambda * lambda * time * dt * wn.abs();
    for v in state.velocities() {
        assert!((v - exact).norm() <= tolerance, "{v} against {exact}");
    }
}

/// The same triangle stepped by backward Euler, whose matrix
/// `M + h C` couples vertices that no spring joins (the blocks outside the
/// springs' pattern, which the solvers take as they take contact's): the
/// potential `Φ` is quadratic in `v`, so Newton's first step, with the
/// exact Hessian, lands on the minimum, and each step takes
/// `u ← u / (1 + hλ)`, so `v_k = (w·n)(1 − (1 + hλ)^(−k)) n`: with the
/// sparse Cholesky factor (incomplete without those blocks, so
/// preconditioning CG), with PCG and with multigrid.
#[test]
fn the_implicit_step_couples_the_vertices_no_spring_joins() {
    let LoneTriangle {
        system,
        normal,
        lambda,
        wn,
    } = LoneTriangle::new();
    let h = 0.5 / lambda;
    for solver in [
        LinearSolver::Cholesky,
        LinearSolver::Pcg(PcgSettings::DEFAULT),
        LinearSolver::Amg(PcgSettings::DEFAULT),
    ] {
        let mut integrator = Implicit::backward_euler().with_solver(solver);
        let mut state = system.initial_state();
        for k in 1..=10 {
            let report = integrator.step(&system, &mut state, h).unwrap();
            assert_eq!(report.newton_iterations, 1, "{solver:?}, step {k}");
            let exact = wn * (1.0 - (1.0 + h * lambda).powi(-k)) * normal;
            for v in state.velocities() {
                assert!(
                    (v - exact).norm() <= 1e-12 * wn.abs(),
                    "{solver:?}, step {k}: {v} against {exact}"
                );
            }
        }
    }
}

/// A free triangle of three 0.05 kg particles, no springs, in a wind
/// `w = (1.5, −0.5, 2)` m/s of drag `c = 0.8`: its normal `n`, the rate
/// `λ = cA/(3m)` at which each vertex's normal velocity relaxes, and `w·n`.
struct LoneTriangle {
    system: System,
    normal: Vec3,
    lambda: f64,
    wn: f64,
}

impl LoneTriangle {
    fn new() -> Self {
        let m = 0.05;
        let p = [
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.4, 1.1, 0.2),
            Vec3::new(0.1, 1.5, -0.3),
        ];
        let (w, c) = (Vec3::new(1.5, -0.5, 2.0), 0.8);
        let mut b = SystemBuilder::new();
        let t = p.map(|p| b.particle(m, p));
        b.term(Wind::new(w, c, vec![t]));
        let system = b.build().unwrap();
        let cross = (p[1] - p[0]).cross(&(p[2] - p[0]));
        let (area, normal) = (0.5 * cross.norm(), cross.normalize());
        let lambda = c * area / (3.0 * m);
        let wn = w.dot(&normal);
        Self {
            system,
            normal,
            lambda,
            wn,
        }
    }
}
