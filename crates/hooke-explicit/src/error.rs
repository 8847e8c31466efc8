//! The error for an integrator parameter out of range.

use thiserror::Error;

/// An integrator parameter outside its valid range.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{integrator}: {parameter} must be {requirement}, got {value}")]
pub struct ParameterError {
    /// The integrator's name.
    pub integrator: &'static str,
    /// The parameter's name.
    pub parameter: &'static str,
    /// The value given.
    pub value: f64,
    /// What the value must be.
    pub requirement: &'static str,
}

impl ParameterError {
    pub(crate) fn new(
        integrator: &'static str,
        parameter: &'static str,
        value: f64,
        requirement: &'static str,
    ) -> Self {
        Self {
            integrator,
            parameter,
            value,
            requirement,
        }
    }
}
