//! Backward Euler and BDF2 at their defaults on a 24×24 cloth (1 m, 0.1 kg,
//! two pinned corners, 1 m up, no damping, every spring of stiffness `k`)
//! across stiffness 10⁻² … 10¹² N/m and steps 10⁻⁴ … 1 s: the initial and
//! peak total energy `T + V_springs + V_gravity` (which may only fall),
//! Newton's linear solves per step (mean and largest per substep), substeps,
//! rejected substeps, unconverged steps, energy corrections and wall time
//! per step.
//!
//! `cargo run --release --example extreme_table -- [STEPS] [linearized | quasi-newton] [k=K] [dt=DT]`
//!
//! `STEPS` steps per cell (default 3); `linearized` takes Baraff & Witkin's
//! step instead of the converged one, `quasi-newton` converges it by L-BFGS
//! instead of Newton's method; `k=` and `dt=` run one row or column.
#![allow(clippy::print_stdout)] // printing the table is this program's job

use std::time::Instant;

use hooke::implicit::{Implicit, Minimizer};
use hooke::prelude::*;

/// The table's stiffnesses, N/m, and steps, s.
const STIFFNESS: [f64; 5] = [1e-2, 1.0, 1e4, 1e8, 1e12];
const STEPS: [f64; 4] = [1e-4, 1e-2, 0.1, 1.0];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut steps = 3;
    let mut minimizer = Minimizer::Newton;
    let (mut only_k, mut only_dt) = (None, None);
    for arg in std::env::args().skip(1) {
        if arg == "linearized" {
            minimizer = Minimizer::Linearized;
        } else if arg == "quasi-newton" {
            minimizer = Minimizer::quasi_newton();
        } else if let Some(k) = arg.strip_prefix("k=") {
            only_k = Some(k.parse::<f64>()?);
        } else if let Some(dt) = arg.strip_prefix("dt=") {
            only_dt = Some(dt.parse::<f64>()?);
        } else {
            steps = arg.parse()?;
        }
    }
    println!(
        "method          k (N/m)  dt (s)   E0 (J)   peak E (J)   solves/step  max  substeps  rejected  unconverged  corrected   ms/step"
    );
    for scheme in [Implicit::backward_euler as fn() -> Implicit, Implicit::bdf2] {
        for k in only_k.map_or(STIFFNESS.to_vec(), |k| vec![k]) {
            let system = Sheet::conservative(k).system()?;
            for dt in only_dt.map_or(STEPS.to_vec(), |dt| vec![dt]) {
                let mut integrator = scheme().with_minimizer(minimizer);
                let mut state = system.initial_state();
                let initial = system.energy(&state)?.total();
                let (mut peak, mut total) = (f64::NEG_INFINITY, StepReport::default());
                let start = Instant::now();
                for _ in 0..steps {
                    total += integrator.step(&system, &mut state, dt)?;
                    peak = peak.max(system.energy(&state)?.total());
                }
                let ms = 1e3 * start.elapsed().as_secs_f64() / steps as f64;
                println!(
                    "{:<14} {k:8.0e} {dt:7.0e} {initial:8.4} {peak:12.6e} {:12.1} {:4} {:9} {:9} {:12} {:10} {ms:9.1}",
                    integrator.name(),
                    total.linear_solves as f64 / steps as f64,
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
