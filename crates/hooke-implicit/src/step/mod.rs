//! The step's control: [`Implicit`](crate::Implicit)'s settings, the
//! caller's step delivered in substeps that shrink on rejection and grow
//! back, the energy test, local error control and the conditioning limit.

pub(crate) mod attempt;
pub(crate) mod builders;
pub(crate) mod comparison;
pub(crate) mod conditioning;
pub(crate) mod energy;
pub mod error_control;
pub(crate) mod implicit;
pub(crate) mod pins;
pub(crate) mod scheme;
pub(crate) mod settings;
pub(crate) mod substeps;
pub(crate) mod work;
