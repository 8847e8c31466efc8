//! Reference problems, shared by tests, benchmarks and examples:
//!
//! - [`Oscillator`]: one particle on a spring to a pinned anchor, undamped or
//!   damped, with its closed-form motion;
//! - [`HangingChain`]: a chain under gravity, with its closed-form rest
//!   configuration;
//! - [`Chain`]: a chain laid out in a row, a pendulum with one end pinned,
//!   with closed-form axial frequencies with both;
//! - [`BeadOnString`]: a bead on a string without pretension, whose stiffness
//!   grows with amplitude — under damping its time scale changes by orders of
//!   magnitude during one run. Its motion has no closed form.
//! - [`Sheet`]: a square cloth with stretch, shear and bending springs, the
//!   common workload of the tests, examples and benchmarks, among them the
//!   solver benchmarks' cloth ([`Sheet::cloth`]).

mod bead;
mod chain;
mod hanging_chain;
mod oscillator;
mod sheet;

pub use bead::BeadOnString;
pub use chain::Chain;
pub use hanging_chain::HangingChain;
pub use oscillator::Oscillator;
pub use sheet::{Sheet, SpringFamily};
