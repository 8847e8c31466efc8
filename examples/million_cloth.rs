//! Memory and time of converged steps on a large cloth: the N×N cloth (1 m,
//! 1 kg, stretch / shear / bend springs of 5 000 / 500 / 50 N/m, two
//! corners pinned) takes converged backward-Euler steps of 1/60 s with the
//! default solver (`auto`, which at a million particles skips the factor by
//! its predicted size and times multigrid against block-Jacobi PCG), then prints
//! per step the solver, Newton and linear iterations, wall time and the
//! share of it that collision detection took, and the process's peak resident memory (`VmHWM` of `/proc/self/status`) per
//! particle.
//!
//! `cargo run --release --example million_cloth -- [N] [STEPS] [STEP] [TOLERANCE] [SELF] [SOLVER] [WEAK] [LIMIT]`
//!
//! `N` = 1000 (a million particles) and `STEPS` = 2 by default; `STEP` is
//! `newton` (the default) or `quasi-newton`, `TOLERANCE` the relative
//! Newton tolerance (the integrator's default if not given), `SELF` `on`
//! (the default) or `off` for the cloth's self-collision, `SOLVER` the
//! linear solver's name (`auto` by default; for the quasi-Newton step,
//! `cholesky` factors `H₀` and `amg` applies it by multigrid), `WEAK`
//! `kept` or `routed` for where the bending springs go in the matrix a
//! step factorizes (each step's default if not given), `LIMIT` `global`
//! (the default) or `particles` for how contact bounds each iterate's
//! motion.
#![allow(clippy::print_stdout)] // printing the measurements is this program's job

use std::time::Instant;

use hooke::implicit::{ContactLimit, Implicit, LinearSolver, Minimizer, WeakSprings};
use hooke::prelude::*;
use hooke::scenes::{Corner, Mass, Springs};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let side: usize = args.next().map_or(Ok(1000), |a| a.parse())?;
    let steps: usize = args.next().map_or(Ok(2), |a| a.parse())?;
    let minimizer = match args.next().as_deref() {
        None | Some("newton") => Minimizer::Newton,
        Some("quasi-newton") => Minimizer::quasi_newton(),
        Some(other) => return Err(format!("unknown step {other:?}").into()),
    };
    let tolerance: f64 = args
        .next()
        .map_or(Ok(ImplicitSettings::NEWTON_TOLERANCE), |a| a.parse())?;
    let self_collision = match args.next().as_deref() {
        None | Some("on") => true,
        Some("off") => false,
        Some(other) => return Err(format!("SELF is on or off, not {other:?}").into()),
    };
    let solver = match args.next() {
        None => LinearSolver::Auto,
        Some(name) => {
            LinearSolver::from_name(&name).ok_or_else(|| format!("unknown solver {name:?}"))?
        }
    };
    let weak = match args.next() {
        None => None,
        Some(name) => Some(
            WeakSprings::from_name(&name)
                .ok_or_else(|| format!("WEAK is kept or routed, not {name:?}"))?,
        ),
    };
    let limit = match args.next() {
        None => ContactLimit::default(),
        Some(name) => ContactLimit::from_name(&name)
            .ok_or_else(|| format!("LIMIT is global or particles, not {name:?}"))?,
    };
    let system = Cloth::grid(side, side)
        .mass(Mass::Total(1.0))
        .stretch(Springs::per_spring(5000.0).damping(0.05))
        .shear(Springs::per_spring(500.0).damping(0.05))
        .bend(Springs::per_spring(50.0))
        .pin_corners([Corner::TopLeft, Corner::TopRight])
        .build()?
        .self_collision(self_collision)
        .system([0.0, -9.81, 0.0])?;
    let particles = system.particle_count();
    let mut state = system.initial_state();
    let mut integrator = Implicit::backward_euler()
        .with_minimizer(minimizer)
        .with_solver(solver)
        .with_weak_springs(weak)
        .with_contact_limit(limit)
        .with_newton(ImplicitSettings::NEWTON_ITERATIONS, tolerance)?;
    for step in 0..steps {
        let started = Instant::now();
        let report = integrator.step(&system, &mut state, 1.0 / 60.0)?;
        let seconds = started.elapsed().as_secs_f64();
        println!(
            "step {step}: {} solver, {} Newton iterations, {} linear iterations, {} unconverged, {seconds:.2} s, detection {:.2} s ({:.0} %, {} proximity queries)",
            report.linear_solver,
            report.newton_iterations,
            report.linear_iterations,
            report.unconverged_steps,
            report.detection_seconds,
            100.0 * report.detection_seconds / seconds,
            report.proximity_queries,
        );
    }
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let peak_kib: Option<f64> = status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok());
    match peak_kib {
        Some(kib) => println!(
            "{particles} particles: peak resident memory {:.0} MiB, {:.0} bytes per particle",
            kib / 1024.0,
            kib * 1024.0 / particles as f64
        ),
        None => {
            println!("{particles} particles: no /proc/self/status to read the peak memory from")
        }
    }
    Ok(())
}
