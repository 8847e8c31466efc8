//! A square cloth pinned at two corners falls and swings under gravity,
//! integrated with velocity Verlet; prints what happened.
//!
//! `cargo run --release --example hanging_cloth`
#![allow(clippy::print_stdout)] // printing the summary is this program's job

use std::time::Instant;

use hooke::prelude::*;

fn main() -> Result<(), Error> {
    // 32×32 particles, 1 m, 0.3 kg, 2000 N/m stretch, shear and bending springs.
    let system = Sheet::new(32).system()?;
    let mut state = system.initial_state();
    // The stiffest mode has ω ≈ 2√(Σk/m) ≈ 6600 rad/s: Verlet needs h < 2/ω ≈ 3e-4 s.
    let (dt, steps) = (2e-4, 10_000);
    let mut energy = EnergyLog::default();
    let mut strain = StrainLog::default();

    let start = Instant::now();
    let run = Simulation::new(&system, &mut VelocityVerlet::new())
        .observe(500, &mut energy)
        .observe(500, &mut strain)
        .run(&mut state, dt, steps)?;
    let wall = start.elapsed().as_secs_f64();

    let samples = energy.samples();
    let (first, last) = (samples[0], samples[samples.len() - 1]);
    let lowest = state
        .positions()
        .iter()
        .map(|x| x.y)
        .fold(f64::INFINITY, f64::min);
    println!(
        "hanging cloth: {} particles, {} springs, 2 pinned",
        system.particle_count(),
        system.springs().len()
    );
    println!(
        "integrator    velocity Verlet, dt = {dt} s, {steps} steps, {} force evaluations",
        run.report.force_evaluations
    );
    println!(
        "simulated     {:.2} s in {wall:.3} s wall ({:.1} µs per step)",
        state.time(),
        wall * 1e6 / steps as f64
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
