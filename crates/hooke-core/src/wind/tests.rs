use crate::collision::distance::tests::Rng;
use crate::term::Blocks;
use crate::{BuildError, CompressedSprings, SystemBuilder};

use super::*;

/// Five particles, three triangles: two sharing an edge, one sharing a
/// vertex with them, and one of no area (its vertices in a line).
const TRIANGLES: [[usize; 3]; 4] = [[0, 1, 2], [1, 3, 2], [3, 4, 0], [0, 2, 4]];

/// A system of the particles at random positions, with the last
/// triangle's vertices in a line, and its wind.
fn windy(rng: &mut Rng) -> (System, Wind) {
    let mut b = SystemBuilder::new();
    let mut x: Vec<Vec3> = (0..5).map(|_| rng.vec3(1.0)).collect();
    x[4] = x[0] + 0.7 * (x[2] - x[0]);
    for p in &x {
        b.particle(rng.uniform(0.1, 2.0), *p);
    }
    let wind = Wind::new(rng.vec3(3.0), rng.uniform(0.1, 2.0), TRIANGLES.to_vec());
    b.term(wind.clone());
    (b.build().unwrap(), wind)
}

/// A point of a step: velocities `v`, positions `x`, `βh`.
fn at<'a>(x: &'a [Vec3], v: &'a [Vec3], beta_h: f64) -> At<'a> {
    At {
        x,
        v,
        v_tilde: v,
        beta_h,
        displacement: None,
        compressed: CompressedSprings::Exact,
    }
}

/// Starts a step of `h` from `x` with the velocities `v`.
fn begin(wind: &mut Wind, system: &System, x: &[Vec3], v: &[Vec3], h: f64) {
    let step = StepStart {
        x,
        v,
        time: 0.0,
        h,
        beta_h: h,
    };
    wind.begin(system, &step);
}

/// `−∇Φ_wind` at `v`.
fn minus_gradient(wind: &mut Wind, system: &System, x: &[Vec3], v: &[Vec3], bh: f64) -> Vec<Vec3> {
    let mut b = vec![Vec3::zeros(); v.len()];
    wind.gradient(system, &at(x, v, bh), &mut b);
    b
}

/// `Φ_wind = βh R` is a quadratic in `v`, so central differences are exact
/// but for rounding: the gradient matches the value's, the Hessian the
/// gradient's, at random states and winds, with the triangles lagged at
/// the step's start whatever the point's positions.
#[test]
fn the_gradient_and_hessian_are_the_values_derivatives() {
    let mut rng = Rng::new(46);
    for _ in 0..20 {
        let (system, mut wind) = windy(&mut rng);
        let n = system.particle_count();
        let x0: Vec<Vec3> = system.initial_positions().to_vec();
        let v: Vec<Vec3> = (0..n).map(|_| rng.vec3(2.0)).collect();
        let bh = rng.uniform(1e-3, 0.1);
        begin(&mut wind, &system, &x0, &v, bh);
        // The point's positions are not the start's: the lagged triangles
        // are used all the same.
        let x: Vec<Vec3> = x0.iter().map(|p| p + rng.vec3(0.3)).collect();
        let b = minus_gradient(&mut wind, &system, &x, &v, bh);
        let mut hessian = Blocks::new(n);
        let mut b_add = vec![Vec3::zeros(); n];
        wind.add(&system, &at(&x, &v, bh), &mut b_add, &mut hessian);
        assert_eq!(b, b_add);
        let value = wind.value(&system, &at(&x, &v, bh)).value;
        let scale = b.iter().map(Vec3::norm).fold(0.0, f64::max);
        let step = 1e-4;
        for i in 0..n {
            for c in 0..3 {
                let shifted = |by: f64| {
                    let mut u = v.clone();
                    u[i][c] += by;
                    u
                };
                let (up, down) = (shifted(step), shifted(-step));
                let slope = (wind.value(&system, &at(&x, &up, bh)).value
                    - wind.value(&system, &at(&x, &down, bh)).value)
                    / (2.0 * step);
                assert!(
                    (slope + b[i][c]).abs() <= 1e-8 * (scale + value),
                    "∂Φ/∂v[{i}][{c}]: {slope} against {}",
                    -b[i][c]
                );
                let (b_up, b_down) = (
                    minus_gradient(&mut wind, &system, &x, &up, bh),
                    minus_gradient(&mut wind, &system, &x, &down, bh),
                );
                let mut e = vec![Vec3::zeros(); n];
                e[i][c] = 1.0;
                let mut column = vec![Vec3::zeros(); n];
                hessian.apply(&e, &mut column);
                for j in 0..n {
                    let fd = (b_down[j] - b_up[j]) / (2.0 * step);
                    assert!(
                        (fd - column[j]).norm() <= 1e-6 * bh * wind.drag,
                        "∂²Φ/∂v[{j}]∂v[{i}][{c}]: {fd} against {}",
                        column[j]
                    );
                }
            }
        }
    }
}

/// The force at the positions the step started from is `−∇Φ_wind / βh`,
/// and with other positions it takes their triangles: a wind lagged at
/// `x'` gives the force the explicit integrators feel at `x'`.
#[test]
fn the_force_is_the_drag_at_the_current_triangles() {
    let mut rng = Rng::new(7);
    let (system, mut wind) = windy(&mut rng);
    let n = system.particle_count();
    let v: Vec<Vec3> = (0..n).map(|_| rng.vec3(2.0)).collect();
    let bh = 0.01;
    for x in [
        system.initial_positions().to_vec(),
        system
            .initial_positions()
            .iter()
            .map(|p| p + rng.vec3(0.3))
            .collect(),
    ] {
        begin(&mut wind, &system, &x, &v, bh);
        let b = minus_gradient(&mut wind, &system, &x, &v, bh);
        let mut f = vec![Vec3::zeros(); n];
        wind.force(&system, &x, &v, &mut f);
        for (fi, bi) in f.iter().zip(&b) {
            assert!(
                (fi - bi / bh).norm() <= 1e-13 * (1.0 + fi.norm()),
                "{fi} against {}",
                bi / bh
            );
        }
    }
}

/// The force on one triangle at rest, by hand: `c A (w·n) n` on the
/// triangle, a third on each vertex, whichever way its normal points.
#[test]
fn a_triangle_at_rest_feels_the_winds_pressure() {
    let mut b = SystemBuilder::new();
    let t = [
        b.particle(1.0, [0.0, 0.0, 0.0]),
        b.particle(1.0, [2.0, 0.0, 0.0]),
        b.particle(1.0, [0.0, 0.0, 3.0]),
    ];
    let (w, c) = (Vec3::new(1.0, -4.0, 2.0), 0.5);
    let system = {
        b.term(Wind::new(w, c, vec![t]));
        b.build().unwrap()
    };
    // Area 3 m², normal ±y: the pressure c (w·n) = −2 Pa along +y.
    let expected = Vec3::new(0.0, c * 3.0 * -4.0 / 3.0, 0.0);
    let mut f = vec![Vec3::zeros(); 3];
    let state = system.initial_state();
    system.terms()[0].force(&system, state.positions(), state.velocities(), &mut f);
    for fi in &f {
        assert!((fi - expected).norm() < 1e-15, "{fi} against {expected}");
    }
}

/// The wind's work over a step is `h (2R(v) + f·v)`: the power the
/// particles receive, `f·v`, plus the power drag dissipates, `2R ≥ 0`.
#[test]
fn the_work_is_the_power_received_plus_the_power_dissipated() {
    let mut rng = Rng::new(11);
    for _ in 0..10 {
        let (system, mut wind) = windy(&mut rng);
        let n = system.particle_count();
        let x0 = system.initial_positions().to_vec();
        let v0: Vec<Vec3> = (0..n).map(|_| rng.vec3(2.0)).collect();
        let h = rng.uniform(1e-3, 0.1);
        begin(&mut wind, &system, &x0, &v0, h);
        let v1: Vec<Vec3> = (0..n).map(|_| rng.vec3(2.0)).collect();
        let x1: Vec<Vec3> = x0.iter().zip(&v1).map(|(x, v)| x + h * v).collect();
        let step = StepStart {
            x: &x0,
            v: &v0,
            time: 0.0,
            h,
            beta_h: h,
        };
        let work = wind.work(&system, &step, &x1, &v1);
        // R at v₁ with the triangles of the start, and its force there.
        let dissipation = 2.0 * wind.value(&system, &at(&x1, &v1, 1.0)).value;
        let mut f = vec![Vec3::zeros(); n];
        wind.force(&system, &x0, &v1, &mut f);
        let received: f64 = f.iter().zip(&v1).map(|(f, v)| f.dot(v)).sum();
        let expected = h * (dissipation + received);
        assert!(
            (work - expected).abs() <= 1e-12 * h * (dissipation + received.abs()),
            "{work} against {expected}"
        );
    }
}

/// The damping rates bound the absolute row sums of `M^(−1/2) C M^(−1/2)`
/// at the initial positions, `C` the Hessian of `R`.
#[test]
fn the_damping_rates_bound_the_row_sums() {
    let mut rng = Rng::new(5);
    let (system, mut wind) = windy(&mut rng);
    let n = system.particle_count();
    let w: Vec<f64> = system.inverse_masses().iter().map(|m| m.sqrt()).collect();
    let (mut stiffness, mut damping) = (vec![0.0; n], vec![0.0; n]);
    wind.rates(&system, &w, &mut stiffness, &mut damping);
    assert_eq!(stiffness, vec![0.0; n]);
    let x = system.initial_positions().to_vec();
    let zeros = vec![Vec3::zeros(); n];
    let mut c = Blocks::new(n);
    wind.add(
        &system,
        &at(&x, &zeros, 1.0),
        &mut vec![Vec3::zeros(); n],
        &mut c,
    );
    let mut sums: Vec<f64> = (0..n)
        .map(|i| w[i] * w[i] * c.rows[i].to_mat3().norm())
        .collect();
    for &(i, j, block) in &c.pairs {
        let norm = w[i] * w[j] * block.norm();
        sums[i] += norm;
        sums[j] += norm;
    }
    for i in 0..n {
        assert!(
            sums[i] <= damping[i] * (1.0 + 1e-12),
            "particle {i}: {} > {}",
            sums[i],
            damping[i]
        );
        assert!(damping[i] > 0.0);
    }
}

/// A wind that does not fit the system is named at the build: a velocity
/// not finite, a drag negative or not finite, a triangle out of range or
/// repeating a particle.
#[test]
fn a_wind_out_of_its_domain_is_refused() {
    let cases = [
        (
            Wind::new([f64::NAN, 0.0, 0.0], 1.0, vec![[0, 1, 2]]),
            "velocity",
        ),
        (Wind::new([1.0, 0.0, 0.0], -1.0, vec![[0, 1, 2]]), "drag -1"),
        (
            Wind::new([1.0, 0.0, 0.0], f64::INFINITY, vec![[0, 1, 2]]),
            "drag inf",
        ),
        (
            Wind::new([1.0, 0.0, 0.0], 1.0, vec![[0, 1, 2], [0, 3, 1]]),
            "triangle 1 names particle 3",
        ),
        (
            Wind::new([1.0, 0.0, 0.0], 1.0, vec![[0, 1, 1]]),
            "triangle 0 repeats",
        ),
    ];
    for (wind, says) in cases {
        let mut b = SystemBuilder::new();
        for k in 0..3 {
            b.particle(1.0, [k as f64, (k * k) as f64, 0.0]);
        }
        b.term(wind);
        match b.build() {
            Err(BuildError::InvalidTerm { name, problem, .. }) => {
                assert_eq!(name, "wind");
                assert!(problem.contains(says), "{problem:?} should say {says:?}");
            }
            other => panic!("expected the wind refused for {says:?}, got {other:?}"),
        }
    }
}

/// The dissipated power is the drag's power against the air,
/// `−Σᵢ fᵢ·(vᵢ − w)` from the force, non-negative, and the system's
/// dissipation adds it to the air damping's `γ Σ |vᵢ|²`.
#[test]
fn the_dissipation_is_the_drags_power_against_the_air() {
    let mut rng = Rng::new(13);
    for _ in 0..10 {
        let (system, wind) = windy(&mut rng);
        let n = system.particle_count();
        let x: Vec<Vec3> = system
            .initial_positions()
            .iter()
            .map(|p| p + rng.vec3(0.3))
            .collect();
        let v: Vec<Vec3> = (0..n).map(|_| rng.vec3(2.0)).collect();
        let mut f = vec![Vec3::zeros(); n];
        wind.force(&system, &x, &v, &mut f);
        let against: f64 = -f
            .iter()
            .zip(&v)
            .map(|(f, v)| f.dot(&(v - wind.velocity)))
            .sum::<f64>();
        let power = wind.dissipation_power(&system, &x, &v);
        assert!(power >= 0.0);
        assert!(
            (power - against).abs() <= 1e-12 * power,
            "{power} against {against}"
        );
        let gamma = rng.uniform(0.1, 1.0);
        let mut b = SystemBuilder::new();
        for (i, p) in x.iter().enumerate() {
            b.particle_with_velocity(system.masses()[i], *p, v[i]);
        }
        b.air_damping(gamma);
        b.term(wind.clone());
        let damped = b.build().unwrap();
        let air: f64 = gamma * v.iter().map(|v| v.norm_squared()).sum::<f64>();
        let total = damped.dissipation_power(&damped.initial_state()).unwrap();
        assert!(
            (total - (air + power)).abs() <= 1e-12 * (air + power),
            "{total} against {air} + {power}"
        );
    }
}
