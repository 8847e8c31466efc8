//! Helpers shared by the integration tests and the benches (which include
//! this file by its path).

use hooke::core::{At, CompressedSprings};
use hooke::implicit::Terms;
use hooke::implicit::internals::{BlockJacobi, BlockMatrix, Pattern};
use hooke::prelude::*;
use hooke::scenes::{Mass, Springs, TetSplit, Volume};

/// Largest error of the bob against the exact solution over `[0, t_end]`,
/// checked after every step: `max(|u − u*|, |u' − u*'|/ω)`.
#[allow(dead_code)] // not every test binary runs the oscillator
pub fn oscillator_error(
    integrator: &mut dyn Integrator,
    oscillator: &Oscillator,
    dt: f64,
    t_end: f64,
) -> f64 {
    let system = oscillator.system().expect("valid oscillator");
    let mut state = system.initial_state();
    let steps = (t_end / dt).round() as usize;
    let mut worst: f64 = 0.0;
    for _ in 0..steps {
        integrator
            .step(&system, &mut state, dt)
            .expect("stable step");
        let (u, v) = oscillator.solution(state.time());
        let bob = Oscillator::BOB;
        let position = (state.positions()[bob].x - u).abs();
        let velocity = (state.velocities()[bob].x - v).abs() / oscillator.omega();
        worst = worst.max(position).max(velocity);
    }
    worst
}

/// Least-squares slope of `log y` against `log x`.
#[allow(dead_code)] // not every test binary fits orders
pub fn log_log_slope(xs: &[f64], ys: &[f64]) -> f64 {
    let (lx, ly): (Vec<f64>, Vec<f64>) = xs.iter().zip(ys).map(|(x, y)| (x.ln(), y.ln())).unzip();
    let n = lx.len() as f64;
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let cov: f64 = lx.iter().zip(&ly).map(|(x, y)| (x - mx) * (y - my)).sum();
    let var: f64 = lx.iter().map(|x| (x - mx) * (x - mx)).sum();
    cov / var
}

/// The backward-Euler system `(A, b)` of one linearised step of `h` from
/// `state` (compressed springs clamped, directions frozen), with its
/// block-Jacobi preconditioner.
#[allow(dead_code)] // only the linear-solver tests assemble systems
pub fn linearised_step(
    system: &System,
    state: &State,
    h: f64,
) -> (BlockMatrix, Vec<Vec3>, BlockJacobi) {
    let n = system.particle_count();
    let mut a = BlockMatrix::zeros(Pattern::new(system).unwrap());
    let mut b = vec![Vec3::zeros(); n];
    let mut jacobi = BlockJacobi::default();
    let u: Vec<Vec3> = state.velocities().iter().map(|v| h * v).collect();
    let at = At {
        x: state.positions(),
        v: state.velocities(),
        v_tilde: state.velocities(),
        beta_h: h,
        displacement: Some(&u),
        compressed: CompressedSprings::Clamped,
    };
    Terms::new(system)
        .unwrap()
        .assemble(system, &at, &mut a, &mut jacobi, &mut b, 0.0)
        .unwrap();
    (a, b, jacobi)
}

/// The constraint filters of `system`'s pins: `Fixed` for a pinned
/// particle, `Free` otherwise (the library's own, which its solvers use).
#[allow(unused_imports)] // only the linear-solver tests and benches filter
pub use hooke::implicit::internals::pin_filters;

/// A rope of `segments + 1` particles, 10 m, 1 kg, stretch / bend springs of
/// 10 000 / 100 N/m (stretch damped by 0.05 N·s/m), its start pinned.
#[allow(dead_code)] // used by the multigrid tests and the solvers bench
pub fn long_rope(segments: usize) -> System {
    Rope::between([0.0, 0.0, 0.0], [10.0, 0.0, 0.0], segments)
        .mass(Mass::Total(1.0))
        .stretch(Springs::per_spring(1e4).damping(0.05))
        .bend(Springs::per_spring(100.0))
        .pin_start()
        .build()
        .unwrap()
        .system([0.0, -9.81, 0.0])
        .unwrap()
}

/// A 0.2 m cube of `cells`³ cubes split into six tetrahedra each
/// (`(cells + 1)³` particles), 1 000 kg/m³, springs of modulus 2·10⁴ N on
/// the edges (damped by 0.5 N·s/m), one corner pinned, springs only: the
/// solver comparisons measure the springs' matrix.
#[allow(dead_code)] // used by the multigrid tests and the solvers bench
pub fn tet_cube(cells: usize) -> System {
    tet_cube_with(cells, Volume::Off)
}

/// [`tet_cube`] with the volume elements `volume`.
#[allow(dead_code)] // used by the quasi-Newton tests and through tet_cube
pub fn tet_cube_with(cells: usize, volume: Volume) -> System {
    Lattice::tets(cells, cells, cells, TetSplit::Six)
        .size([0.2, 0.2, 0.2])
        .mass(Mass::Density(1000.0))
        .edges(Springs::modulus(2e4).damping(0.5))
        .volume(volume)
        .pin(0)
        .build()
        .unwrap()
        .system([0.0, -9.81, 0.0])
        .unwrap()
}
