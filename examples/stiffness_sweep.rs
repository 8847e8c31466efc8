//! A stiffness sweep: a 16×16 cloth hanging from two corners, with every
//! spring's stiffness stepped through six decades, run for one second with
//! velocity Verlet (h = 1 ms) and with backward Euler (h = 1/60 s). Velocity
//! Verlet is stable while `h ω_max < 2`, with `ω_max` the cloth's highest
//! natural frequency, which grows like `√k`; backward Euler at any
//! stiffness.
//!
//! `cargo run --release --example stiffness_sweep`
#![allow(clippy::print_stdout)] // printing the table is this program's job

use hooke::prelude::*;
use hooke::scenes::{Cloth, Corner, Mass};

/// Runs `duration` s; returns the largest spring strain, or `None` if the
/// state stopped being finite.
fn run(system: &System, integrator: &mut dyn Integrator, dt: f64, duration: f64) -> Option<f64> {
    let mut state = system.initial_state();
    let mut strain: f64 = 0.0;
    for _ in 0..(duration / dt).round() as usize {
        integrator.step(system, &mut state, dt).ok()?;
        strain = strain.max(system.max_strain(&state).ok()?);
    }
    Some(strain)
}

fn describe(outcome: Option<f64>) -> String {
    match outcome {
        Some(strain) if strain < 10.0 => format!("stable, strain {:6.2} %", 100.0 * strain),
        Some(strain) => format!("blew up, strain {strain:.0e}"),
        None => "blew up (not finite)".to_owned(),
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (explicit_dt, implicit_dt) = (1e-3, 1.0 / 60.0);
    println!("  k (N/m)   velocity Verlet             backward Euler");
    for k in [1e2, 1e3, 1e4, 1e5, 1e6, 1e7] {
        let system = Cloth::grid(16, 16)
            .size(0.5, 0.5)
            .mass(Mass::Total(0.1))
            .stretch(k)
            .shear(k)
            .bend(0.1 * k)
            .pin_corners([Corner::TopLeft, Corner::TopRight])
            .build()?
            .system([0.0, -9.81, 0.0])?;
        let verlet = run(&system, &mut VelocityVerlet::new(), explicit_dt, 1.0);
        let mut implicit = Implicit::backward_euler();
        let backward = run(&system, &mut implicit, implicit_dt, 1.0);
        println!("{k:9.0e}   {:27} {}", describe(verlet), describe(backward));
    }
    Ok(())
}
