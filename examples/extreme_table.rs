//! Backward Euler and BDF2 at their defaults on a 24×24 cloth (1 m, 0.1 kg,
//! two pinned corners, no damping, every spring of stiffness `k`) across
//! stiffness 10⁻² … 10¹² N/m and steps 10⁻⁴ … 1 s: the peak of the total
//! energy `T + V_springs + V_gravity` (which may only fall), Newton
//! iterations per substep, substeps, rejected steps and time per step. Pass
//! `linearized` to take Baraff & Witkin's linearised step instead.
//!
//! `cargo run --release --example extreme_table [linearized] [STEPS]`
#![allow(clippy::print_stdout)] // printing the table is this program's job

use std::time::Instant;

use hooke::implicit::Implicit;
use hooke::prelude::*;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let linearized = args.iter().any(|a| a == "linearized");
    let steps: usize = args.iter().find_map(|a| a.parse().ok()).unwrap_or(10);
    let only: Option<(f64, f64)> = std::env::var("CELL").ok().map(|c| {
        let v: Vec<f64> = c.split(",").map(|x| x.parse().unwrap()).collect();
        (v[0], v[1])
    });
    println!(
        "method          k (N/m)  dt (s)   E0 (J)   peak E (J)  Newton mean/max  substeps  rejected  unconverged  corrected  ms/step"
    );
    for scheme in [Implicit::backward_euler as fn() -> Implicit, Implicit::bdf2] {
        for k in only.map_or(vec![1e-2, 1.0, 1e4, 1e8, 1e12], |c| vec![c.0]) {
            let system = Sheet {
                mass: 0.1,
                stiffness: k,
                damping: 0.0,
                air_damping: 0.0,
                ..Sheet::new(24)
            }
            .system()?;
            for dt in only.map_or(vec![1e-4, 1e-2, 0.1, 1.0], |c| vec![c.1]) {
                if only.is_some_and(|(ok, odt)| ok != k || odt != dt) {
                    continue;
                }
                let mut integrator = scheme();
                if linearized {
                    integrator = integrator.linearized();
                }
                let mut state = system.initial_state();
                let initial = system.energy(&state)?.total();
                let (mut peak, mut total) = (initial, StepReport::default());
                let start = Instant::now();
                for _ in 0..steps {
                    total += integrator.step(&system, &mut state, dt)?;
                    peak = peak.max(system.energy(&state)?.total());
                }
                let ms = 1e3 * start.elapsed().as_secs_f64() / steps as f64;
                println!(
                    "{:<14} {k:8.0e} {dt:7.0e} {initial:8.4} {peak:12.6e} {:8.2} / {:<4} {:9} {:9} {:12} {:10} {ms:8.2}",
                    integrator.name(),
                    total.newton_iterations as f64 / total.accepted_steps.max(1) as f64,
                    total.newton_iterations_max,
                    total.accepted_steps,
                    total.rejected_steps,
                    total.unconverged_steps,
                    total.energy_corrections,
                );
            }
        }
    }
    Ok(())
}
