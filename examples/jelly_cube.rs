//! A soft cube of tetrahedra dropped on a floor bounces, wobbles and settles;
//! backward Euler with contacts as barrier terms of the step's potential. Prints
//! its height and energy.
//!
//! `cargo run --release --example jelly_cube`
#![allow(clippy::print_stdout)] // printing the summary is this program's job

use hooke::prelude::*;
use hooke::scenes::{Lattice, Mass, Springs, TetSplit};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // A 0.2 m cube of 5³ cells split into tetrahedra, 1000 kg/m³, with
    // springs of modulus 2·10⁴ N on every tet edge
    // (k = E / L, so the material does not change with the resolution).
    let cube = Lattice::tets(5, 5, 5, TetSplit::Six)
        .size([0.2, 0.2, 0.2])
        .origin([-0.1, 0.3, -0.1])
        .mass(Mass::Density(1000.0))
        .edges(Springs::modulus(2e4).damping(0.5))
        .face_diagonals(Springs::modulus(2e4).damping(0.5))
        .body_diagonals(Springs::modulus(2e4).damping(0.5))
        .build()?;
    let floor = Obstacle::new(Shape::Plane {
        point: Vec3::zeros(),
        normal: Vec3::y(),
    })
    .restitution(0.3)
    .friction(0.5);
    let mut b = SystemBuilder::new();
    cube.add_to(&mut b);
    b.gravity([0.0, -9.81, 0.0]).obstacle(floor);
    let system = b.build()?;

    let mut integrator = Implicit::backward_euler();
    let mut state = system.initial_state();
    let dt = 1.0 / 240.0;
    println!(
        "{} particles, {} springs",
        system.particle_count(),
        system.springs().len()
    );
    println!("  t (s)   bottom (m)   top (m)   energy (J)");
    for step in 1..=480 {
        integrator.step(&system, &mut state, dt)?;
        if step % 24 == 0 {
            let ys = state.positions().iter().map(|x| x.y);
            let bottom = ys.clone().fold(f64::MAX, f64::min);
            let top = ys.fold(f64::MIN, f64::max);
            let energy = system.energy(&state)?.total();
            println!(
                "{:7.2} {:12.4} {:9.4} {:12.4}",
                state.time(),
                bottom,
                top,
                energy
            );
        }
    }
    Ok(())
}
