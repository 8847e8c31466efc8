//! A square cloth pinned at two corners falls and swings under gravity,
//! integrated with velocity Verlet; prints what happened.
//!
//! `cargo run --release --example hanging_cloth`
#![allow(clippy::print_stdout)] // printing the summary is this program's job

use std::time::Instant;

use hooke::prelude::*;

/// An `n`×`n` grid of side `size` m and total `mass` kg in the horizontal
/// plane, with structural, shear and bending (skip-one) springs of stiffness
/// `k` and light damping, pinned at the two corners of its first row.
fn cloth(n: usize, size: f64, mass: f64, k: f64) -> Result<System, BuildError> {
    let spacing = size / (n - 1) as f64;
    let mut b = SystemBuilder::new();
    for row in 0..n {
        for col in 0..n {
            b.particle(
                mass / (n * n) as f64,
                [col as f64 * spacing, 0.0, row as f64 * spacing],
            );
        }
    }
    let id = |row: usize, col: usize| row * n + col;
    for row in 0..n {
        for col in 0..n {
            // (row step, col step): stretch, shear, and bending over two cells.
            for (dr, dc) in [(0, 1), (1, 0), (1, 1), (1, -1), (0, 2), (2, 0)] {
                let (r, c) = (row + dr, col as isize + dc);
                if r < n && (0..n as isize).contains(&c) {
                    b.spring(id(row, col), id(r, c as usize), k).damping(0.01);
                }
            }
        }
    }
    b.pin(id(0, 0)).pin(id(0, n - 1));
    b.gravity([0.0, -9.81, 0.0]).air_damping(1e-4);
    b.build()
}

fn main() -> Result<(), Error> {
    let system = cloth(32, 1.0, 0.3, 2000.0)?;
    let mut state = system.initial_state();
    let (dt, steps) = (2e-4, 10_000);
    let mut energy = EnergyLog::default();
    let mut strain = StrainLog::default();

    let start = Instant::now();
    let report = Simulation::new(&system, &mut VelocityVerlet::new())
        .observe(500, &mut energy)
        .observe(500, &mut strain)
        .run(&mut state, dt, steps)?;
    let wall = start.elapsed();

    let samples = energy.samples();
    let (first, last) = (samples[0], samples[samples.len() - 1]);
    let lowest = state
        .positions()
        .iter()
        .map(|x| x.y)
        .fold(f64::INFINITY, f64::min);
    println!(
        "hanging cloth: {} particles, {} springs",
        system.particle_count(),
        system.springs().len()
    );
    println!(
        "integrator    velocity Verlet, dt = {dt} s, {steps} steps, {} force evaluations",
        report.force_evaluations
    );
    println!(
        "simulated     {:.2} s in {:.3} s wall ({:.1} µs per step)",
        state.time(),
        wall.as_secs_f64(),
        wall.as_secs_f64() * 1e6 / steps as f64
    );
    println!(
        "energy        {:.4} J -> {:.4} J (kinetic {:.4} J at the end)",
        first.energy.total(),
        last.energy.total(),
        last.energy.kinetic
    );
    println!("max strain    {:.2} %", 100.0 * strain.max());
    println!("lowest point  {:.3} m below the pins", -lowest);
    for s in samples.iter().step_by(4) {
        println!(
            "  t = {:5.2} s  E = {:9.4} J  P_dissipated = {:8.4} W",
            s.time,
            s.energy.total(),
            s.dissipation_power
        );
    }
    Ok(())
}
