//! Reference problems, shared by tests, benchmarks and examples:
//!
//! - [`Oscillator`]: one particle on a spring to a pinned anchor, undamped or
//!   damped, with its closed-form motion;
//! - [`HangingChain`]: a chain under gravity, with its closed-form rest
//!   configuration;
//! - [`BeadOnString`]: a bead on a string without pretension, whose stiffness
//!   grows with amplitude — under damping its time scale changes by orders of
//!   magnitude during one run. Its motion has no closed form.
//! - [`Sheet`]: a square cloth with stretch, shear and bending springs, the
//!   common workload of the examples and benchmarks.

mod bead;
mod chain;
mod oscillator;
mod sheet;

pub use bead::BeadOnString;
pub use chain::HangingChain;
pub use oscillator::Oscillator;
pub use sheet::Sheet;
