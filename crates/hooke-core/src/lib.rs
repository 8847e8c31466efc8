//! The mass-spring model of hooke.
//!
//! Particles `i = 0..n` with mass `mᵢ`, position `xᵢ` and velocity `vᵢ` obey
//! Newton's law `M x'' = f(x, v)` with a diagonal mass matrix `M`. The forces
//! are those a [`System`] declares and no others:
//!
//! - springs (`i`, `j`, stiffness `k`, rest length `L`, axial damping `c`) —
//!   see [`Spring`] for the force and its Jacobian blocks;
//! - gravity `mᵢ g` and air damping `−γ vᵢ`, if declared;
//! - the scene's own [`Term`]s ([`SystemBuilder::term`]): any force with a
//!   potential or dissipation potential, seen by every integrator (the
//!   [`term`] module gives the interface and its equations), such as the
//!   drag of a [`Wind`] on a system's surfaces;
//! - pins: a pinned particle has zero acceleration, or follows a scripted
//!   [`Path`] ([`SystemBuilder::pin_moving`]);
//! - kinematic [`Obstacle`]s (plane, sphere, box, capsule, optionally moving
//!   along a [`Path`]) that particles cannot enter, with restitution and
//!   Coulomb friction. Every integrator ends its step with
//!   [`System::end_step`] (the explicit ones through
//!   [`StepBuffers::finish`]), which places the scripted pins and resolves
//!   contacts (push out along the normal, then the normal and friction
//!   impulses: [`respond_to_contact`]); the implicit integrators also keep
//!   particles off the obstacles inside their step, by barrier terms of the
//!   potential it minimises (`hooke-implicit`'s `contact` module). A system
//!   with neither runs none of this code.
//!
//! The pieces:
//!
//! - [`SystemBuilder`] validates a description and builds an immutable
//!   [`System`]; [`State`] holds `x`, `v` and `t`, the only thing a step
//!   changes.
//! - [`ForceEvaluator`] computes `a = M⁻¹ f(x, v)`, in parallel on large
//!   systems when the `parallel` feature is on.
//! - [`Integrator`] is the trait every time integrator implements;
//!   [`StepBuffers`] holds what every step does around its formula (check
//!   the arguments, take the history, size the buffers; commit, record the
//!   history, end the step).
//! - [`Simulation`] is the one loop that steps an integrator, for programs,
//!   the lab and the command line alike: it times every step and shows its
//!   [`StepReport`] and wall time ([`StepInfo`]) to [`Observer`]s such as
//!   [`EnergyLog`] and [`StrainLog`], any of which can stop the run
//!   (`ControlFlow::Break`); it returns the [`Run`].
//! - [`System::energy`] and [`System::dissipation_power`] support
//!   energy-balance checks.
//! - [`reference`](mod@reference) holds problems with known answers.
//!
//! ```
//! use hooke_core::{SystemBuilder, Vec3};
//! let mut b = SystemBuilder::new();
//! let top = b.particle(0.1, [0.0, 0.0, 0.0]);
//! let bottom = b.particle(0.1, [0.0, -0.5, 0.0]);
//! b.pin(top);
//! b.spring(top, bottom, 40.0);
//! b.gravity([0.0, -9.81, 0.0]);
//! let system = b.build()?;
//! let state = system.initial_state();
//! assert_eq!(state.positions()[bottom], Vec3::new(0.0, -0.5, 0.0));
//! # Ok::<(), hooke_core::BuildError>(())
//! ```

mod builder;
pub mod collision;
mod contact;
mod energy;
mod error;
mod forces;
mod integrator;
mod logs;
mod named;
mod observer;
mod obstacle;
pub mod reference;
mod simulation;
mod spring;
mod state;
mod step;
mod sym_block;
mod system;
pub mod term;
mod volume;
mod wind;

pub use builder::{SpringEntry, SurfaceEntry, SystemBuilder};
pub use contact::respond_to_contact;
pub use energy::Energy;
pub use error::{BuildError, Parameter, ParameterError, Quantity, SpringParameter, StepError};
pub use forces::{ForceEvaluator, PARALLEL_MIN_SPRINGS, Parallelism};
pub use integrator::{Integrator, StepReport, check_step};
pub use logs::{EnergyLog, EnergySample, StrainLog};
pub use named::{Named, quoted_list};
pub use observer::{ObserveFn, Observer, StepInfo};
pub use obstacle::{Obstacle, Path, Shape};
pub use simulation::{End, Run, Simulation};
pub use spring::{CompressedSprings, Linearized, Spring};
pub use state::{History, State};
pub use step::{Start, StepBuffers};
pub use sym_block::SymBlock;
pub use system::{Inversion, System};
pub use term::{At, Hessian, Potential, StepStart, Term, When};
pub use volume::{TET_PAIRS, Tet, TetBlocks, TetDerivatives, TetHessian};
pub use wind::Wind;

/// A 3-vector of `f64`: positions, velocities, forces.
pub type Vec3 = nalgebra::Vector3<f64>;
/// A 3x3 matrix of `f64`: the Jacobian blocks of a spring.
pub type Mat3 = nalgebra::Matrix3<f64>;
/// A 12-vector of `f64`: the coordinates of four particles stacked, particle
/// `k`'s at `3k..3k + 3` (a volume element's vertices, a contact pair's
/// points).
pub type Vec12 = nalgebra::SVector<f64, 12>;
/// A 12 × 12 matrix of `f64`: a Hessian in the coordinates of a [`Vec12`],
/// particle `a`'s rows and columns at `3a..3a + 3` (of a volume element, of
/// a contact pair).
pub type Mat12 = nalgebra::SMatrix<f64, 12, 12>;
