//! Measurements of mass-spring integrators on a user's scene: which stay
//! stable at which stiffness and timestep ([`mod@stability`]), and what
//! accuracy each buys per second of run time ([`mod@accuracy`]). Their
//! figures are drawn by `hooke-viz`; this crate draws nothing.
//!
//! Every measurement runs the scene's [`System`](hooke_core::System) with
//! the integrators of `hooke-explicit` and `hooke-implicit`
//! ([`Method::ALL`]) through [`Simulation`](hooke_core::Simulation), which
//! times the steps alone; a stability run watches its [`EnergyBudget`].
//!
//! On a scene whose surfaces collide, the methods that cannot keep them
//! apart ([`Method::resolves_surface_contact`]) run on the scene without
//! self-collision when only bodies colliding with themselves made the
//! contact, and are otherwise not applicable; the reports' `note` says
//! which (see [`mod@stability`] and [`mod@accuracy`]).
//!
//! A sweep runs on many machines in parts: with a [`Shard`] in its options
//! each part runs its share of the jobs, dealt by their number, and
//! [`StabilityReport::merge`] or [`AccuracyReport::merge`] combines the
//! parts' reports into the unsharded one ([`mod@merge`]).

pub mod accuracy;
mod budget;
mod error;
mod json;
pub mod merge;
mod range;
mod settings;
mod shard;
mod spectrum;
pub mod stability;
mod surfaces;

pub use accuracy::{AccuracyOptions, AccuracyReport, accuracy};
pub use budget::EnergyBudget;
pub use error::LabError;
pub use hooke_scenes::{Method, OscillatorStability};
pub use range::Range;
pub use settings::Settings;
pub use shard::{Shard, interleave};
pub use spectrum::{MAX_ITERATIONS, Spectrum, omega_max};
pub use stability::{StabilityOptions, StabilityReport, stability};
