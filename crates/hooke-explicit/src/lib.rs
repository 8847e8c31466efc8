//! Explicit time integrators for mass-spring systems, each an
//! [`Integrator`](hooke_core::Integrator) over `x'' = a(x, v) = M⁻¹ f(x, v)`.
//!
//! | integrator | order | forces / step | undamped oscillator, `θ = hω` |
//! |---|---|---|---|
//! | [`ExplicitEuler`] | 1 | 1 | gains energy at every `θ` |
//! | [`SymplecticEuler`] | 1 | 1 | bounded for `θ < 2` |
//! | [`Leapfrog`] (kick-drift-kick) | 2 | 1 | bounded for `θ < 2` |
//! | [`VelocityVerlet`] | 2 | 1 | bounded for `θ < 2` |
//! | [`PositionVerlet`] (Störmer) | 2 | 1 | bounded for `θ < 2` |
//! | [`Midpoint`] (RK2) | 2 | 2 | gains energy at every `θ` |
//! | [`Heun`] | 2 | 2 | gains energy at every `θ` |
//! | [`Rk4`] | 4 | 4 | bounded for `θ ≤ 2√2` |
//! | [`Beeman`] | 2 | 1 | bounded for `θ < 2` |
//! | [`Gear`] (5-value Nordsieck) | 4 | 1 | gains energy slowly at every `θ` |
//! | [`DormandPrince`] 5(4), adaptive | 5 | 6 per substep | step chosen for the tolerance |
//!
//! "Bounded" means the energy error stays bounded for all time; above the
//! limit the motion grows geometrically. These limits are the stability
//! intervals on the imaginary axis, and they bind every explicit method: a
//! stiff spring of stiffness `k` between masses `m` has `ω ≈ 2√(k/m)`, so the
//! step must shrink like `1/√k`. That is what the implicit integrators are
//! for.
//!
//! Every integrator owns its buffers (a steady-state step allocates nothing),
//! validates `dt` and the state, and leaves the state untouched when a step
//! fails: each brackets its formula with `hooke_core::StepBuffers`'s
//! `begin` and `finish`. [`ExplicitMethod`] names the fixed-step ones, by
//! their `NAME` constants, and builds them. Those that carry history between steps (leapfrog, the Verlets,
//! Beeman, Gear, and Dormand–Prince's first-same-as-last stage) start
//! themselves from a single state and restart whenever they are handed a state
//! they did not produce.
//!
//! ```
//! use hooke_core::{Integrator, reference::Oscillator};
//! use hooke_explicit::Rk4;
//!
//! let oscillator = Oscillator::undamped(1.0, 1.0); // ω = 1 rad/s
//! let system = oscillator.system()?;
//! let mut state = system.initial_state();
//! let mut rk4 = Rk4::new();
//! for _ in 0..100 {
//!     rk4.step(&system, &mut state, 0.01)?;
//! }
//! let exact = oscillator.displacement(1.0);
//! assert!((state.positions()[Oscillator::BOB].x - exact).abs() < 1e-9);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod beeman;
mod dormand_prince;
mod euler;
mod gear;
mod heun;
mod leapfrog;
mod method;
mod midpoint;
mod ops;
mod position_verlet;
mod rk4;
mod symplectic_euler;
mod velocity_verlet;

pub use beeman::Beeman;
pub use dormand_prince::DormandPrince;
pub use euler::ExplicitEuler;
pub use gear::Gear;
pub use heun::Heun;
pub use leapfrog::Leapfrog;
pub use method::{ExplicitMethod, fixed_step_integrators};
pub use midpoint::Midpoint;
pub use position_verlet::PositionVerlet;
pub use rk4::Rk4;
pub use symplectic_euler::SymplecticEuler;
pub use velocity_verlet::VelocityVerlet;
