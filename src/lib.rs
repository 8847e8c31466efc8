//! hooke simulates mass-spring systems — cloth, ropes, volumetric bodies —
//! and measures, on your own scene, how accurate, stable and fast each time
//! integrator is.
//!
//! This crate is the facade: it re-exports the model ([`core`]), the explicit
//! integrators ([`explicit`]) and the implicit ones ([`implicit`]), the scene
//! builders and files ([`scenes`]) and the lab's measurements ([`lab`]), and
//! offers a [`prelude`] and one [`Error`] for all of them. It does not
//! depend on the command line: the `hooke` binary lives in the `hooke-cli`
//! package, which `cargo run` from the workspace root builds and runs.
//!
//! ```
//! use hooke::prelude::*;
//!
//! // A pendulum-like spring under gravity, integrated with velocity Verlet.
//! let mut b = SystemBuilder::new();
//! let anchor = b.particle(1.0, [0.0, 0.0, 0.0]);
//! let bob = b.particle(0.2, [0.5, 0.0, 0.0]);
//! b.pin(anchor);
//! b.spring(anchor, bob, 500.0).damping(0.05);
//! b.gravity([0.0, -9.81, 0.0]);
//! let system = b.build()?;
//!
//! let mut state = system.initial_state();
//! let mut energy = EnergyLog::default();
//! Simulation::new(&system, &mut VelocityVerlet::new())
//!     .observe(100, &mut energy)
//!     .run(&mut state, 1e-3, 2000)?;
//! let first = energy.samples()[0].energy.total();
//! let last = energy.samples().last().unwrap().energy.total();
//! assert!(last <= first); // the damper only removes energy
//! # Ok::<(), hooke::Error>(())
//! ```

pub use hooke_core as core;
pub use hooke_explicit as explicit;
pub use hooke_implicit as implicit;
pub use hooke_lab as lab;
pub use hooke_scenes as scenes;

/// The README's example, compiled (not run: it takes seconds) as a doc test.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;

/// Any error hooke returns.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The system description is invalid.
    #[error(transparent)]
    Build(#[from] hooke_core::BuildError),
    /// A step could not be taken.
    #[error(transparent)]
    Step(#[from] hooke_core::StepError),
    /// An integrator or solver parameter is out of range.
    #[error(transparent)]
    Parameter(#[from] hooke_core::ParameterError),
    /// A scene builder was given a description it cannot build.
    #[error(transparent)]
    Scene(#[from] hooke_scenes::SceneError),
    /// A scene file cannot be read or is invalid (the error names its file,
    /// line and key).
    #[error(transparent)]
    SceneFile(#[from] hooke_scenes::file::SceneFileError),
    /// A lab measurement cannot be made.
    #[error(transparent)]
    Lab(#[from] hooke_lab::LabError),
}

/// The types most programs need.
pub mod prelude {
    pub use crate::Error;
    pub use hooke_core::reference::{BeadOnString, HangingChain, Oscillator, Sheet};
    pub use hooke_core::{
        BuildError, EnergyLog, Integrator, Named, ObserveFn, Observer, Obstacle, Path, Run, Shape,
        Simulation, State, StepError, StepInfo, StepReport, StrainLog, System, SystemBuilder, Vec3,
    };
    pub use hooke_explicit::{
        Beeman, DormandPrince, ExplicitEuler, Gear, Heun, Leapfrog, Midpoint, PositionVerlet, Rk4,
        SymplecticEuler, VelocityVerlet,
    };
    pub use hooke_implicit::{
        Implicit, ImplicitSettings, LinearSolver, Minimizer, PcgSettings, Scheme,
    };
    pub use hooke_lab::{AccuracyOptions, StabilityOptions, accuracy, stability};
    pub use hooke_scenes::{
        Cloth, IntegratorSpec, Lattice, Layered, Method, Rope, Scene, Shell, Solid, TetMesh,
        TriangleMesh, builtin,
    };
}
