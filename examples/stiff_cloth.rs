//! A stiff cloth (k h²/m = 10⁶) pinned at two corners falls under gravity
//! for 10 s at 30 steps per second with backward Euler — a step explicit
//! methods cannot take — and prints what happened.
//!
//! `cargo run --release --example stiff_cloth`
#![allow(clippy::print_stdout)] // printing the summary is this program's job

use std::time::Instant;

use hooke::prelude::*;

fn main() -> Result<(), Error> {
    let (side, dt, steps) = (32, 1.0 / 30.0, 300);
    let sheet = Sheet::new(side).with_stiffness_ratio(1e6, dt);
    let particle_mass = sheet.mass / (side * side) as f64;
    let stiffness = sheet.stiffness;
    let system = sheet.system()?;

    // Two particles moving apart along one spring have Rayleigh quotient at
    // least 2k/m, so ω_max ≥ √(2k/m) and every explicit method's stable step,
    // at most 2√2/ω_max (RK4), is below 2√2·√(m/2k) = 2√(m/k).
    let explicit_limit = 2.0 * (particle_mass / stiffness).sqrt();
    let mut integrator = Implicit::backward_euler();
    let mut state = system.initial_state();
    let mut energy = EnergyLog::default();
    let mut strain = StrainLog::default();
    let start = Instant::now();
    let run = Simulation::new(&system, &mut integrator)
        .observe(30, &mut energy)
        .observe(1, &mut strain)
        .run(&mut state, dt, steps)?;
    let wall = start.elapsed().as_secs_f64();

    let samples = energy.samples();
    let highest = samples
        .iter()
        .map(|s| s.energy.total())
        .fold(f64::NEG_INFINITY, f64::max);
    println!(
        "stiff cloth: {} particles, {} springs of k = {stiffness:.3e} N/m (k h²/m = 1e6), 2 pinned",
        system.particle_count(),
        system.springs().len()
    );
    println!(
        "backward Euler, Newton ≤ 5, sparse Cholesky: dt = 1/30 s, {steps} steps, {} linear solves",
        run.report.linear_solves
    );
    println!(
        "explicit methods need dt < {explicit_limit:.1e} s, {:.0}× smaller",
        dt / explicit_limit
    );
    println!(
        "simulated     {:.1} s in {wall:.2} s wall ({:.1} ms per step)",
        state.time(),
        1e3 * wall / steps as f64
    );
    println!(
        "energy        {:.4} J -> {:.4} J, never above {highest:.4} J",
        samples[0].energy.total(),
        samples[samples.len() - 1].energy.total()
    );
    println!("max strain    {:.3} %", 100.0 * strain.max());
    Ok(())
}
