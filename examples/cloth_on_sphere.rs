//! A 30×30 cloth falls onto a sphere and drapes over it, integrated with
//! backward Euler at 60 steps per second; each contact is a barrier term of
//! the step's incremental potential. Prints how the drop went.
//!
//! `cargo run --release --example cloth_on_sphere`
#![allow(clippy::print_stdout)] // printing the summary is this program's job

use hooke::prelude::*;
use hooke::scenes::{Cloth, Mass};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let cloth = Cloth::grid(30, 30)
        .size(1.0, 1.0)
        .mass(Mass::Total(0.2))
        .stretch(2e3)
        .shear(2e3)
        .bend(50.0)
        .offset([-0.5, 0.4, -0.5])
        .build()?;
    let ball = Obstacle::new(Shape::Sphere {
        center: Vec3::zeros(),
        radius: 0.25,
    })
    .friction(0.3);
    let mut b = SystemBuilder::new();
    cloth.add_to(&mut b);
    b.gravity([0.0, -9.81, 0.0])
        .air_damping(1e-3)
        .obstacle(ball.clone());
    let system = b.build()?;

    let mut integrator = Implicit::backward_euler();
    let mut state = system.initial_state();
    let dt = 1.0 / 60.0;
    println!("  t (s)   kinetic (J)   lowest (m)   deepest (m)   contacts");
    for step in 1..=240 {
        let report = integrator.step(&system, &mut state, dt)?;
        if step % 30 == 0 {
            let energy = system.energy(&state)?;
            let lowest = state
                .positions()
                .iter()
                .map(|x| x.y)
                .fold(f64::MAX, f64::min);
            let deepest = state
                .positions()
                .iter()
                .map(|x| -ball.distance(*x, state.time()).0)
                .fold(f64::MIN, f64::max);
            println!(
                "{:7.2} {:13.3e} {:12.4} {:13.2e} {:10}",
                state.time(),
                energy.kinetic,
                lowest,
                deepest.max(0.0),
                report.contacts
            );
        }
    }
    println!("max strain {:.2} %", 100.0 * system.max_strain(&state)?);
    Ok(())
}
