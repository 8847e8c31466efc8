//! [`LabError`]: a measurement that cannot be made, naming why.

use hooke_core::{BuildError, ParameterError};
use thiserror::Error;

/// A measurement that cannot be made.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum LabError {
    /// An option out of range.
    #[error("{name}: got {value}, expected {expected}")]
    Invalid {
        /// The option.
        name: &'static str,
        /// The value given.
        value: String,
        /// What it must be.
        expected: &'static str,
    },
    /// A stiffness scale that the scene's springs cannot take.
    #[error("scaling the stiffness: {0}")]
    Scale(#[from] BuildError),
    /// A method parameter out of range.
    #[error(transparent)]
    Parameter(#[from] ParameterError),
    /// Partial reports that are not the parts of one sharded sweep.
    #[error("cannot merge: {reason}")]
    Merge {
        /// What does not fit.
        reason: String,
    },
    /// An accuracy measurement on a scene where surfaces of different
    /// bodies collide: its reference cannot keep them apart, and turning
    /// self-collision off does not remove that contact.
    #[error(
        "surfaces of different bodies collide in this scene: the accuracy reference ({reference}) cannot keep surfaces apart, and without self-collision they still collide; measure a scene whose surfaces collide only with themselves"
    )]
    SurfaceContact {
        /// The reference's method.
        reference: &'static str,
    },
    /// The numerical reference run failed.
    #[error("the reference run ({method} at dt = {dt} s) failed: {reason}")]
    Reference {
        /// The reference's method.
        method: &'static str,
        /// Its step, s.
        dt: f64,
        /// Why it failed.
        reason: String,
    },
}

impl LabError {
    /// `Ok` if `value` (the option `name`) is positive and finite.
    pub(crate) fn positive(name: &'static str, value: f64) -> Result<(), Self> {
        if value.is_finite() && value > 0.0 {
            Ok(())
        } else {
            Err(Self::Invalid {
                name,
                value: value.to_string(),
                expected: "a positive, finite number",
            })
        }
    }

    /// `Ok` if there is at least one of `name`.
    pub(crate) fn at_least_one(name: &'static str, count: usize) -> Result<(), Self> {
        if count == 0 {
            Err(Self::Invalid {
                name,
                value: "0".into(),
                expected: "at least one",
            })
        } else {
            Ok(())
        }
    }
}
