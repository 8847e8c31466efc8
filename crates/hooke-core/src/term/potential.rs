//! [`Potential`]: a value of `Φ` or of the energy with the scale of its
//! rounding.

use std::ops::{Add, AddAssign};

/// A sum — a term's part of `Φ`, or of the energy `E` — and its
/// magnitude: `ε · magnitude` (`ε` the machine epsilon) bounds how far
/// rounding alone moves the value. The magnitude is at least the sum of its
/// parts' absolute values, and more where rounding the inputs moves a part
/// by more than `ε` times itself (a stiff spring's `½k(l − L)²`, whose
/// length carries the rounding of its ends' coordinates).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Potential {
    /// The value, J.
    pub value: f64,
    /// Its magnitude for rounding, J.
    pub magnitude: f64,
}

impl Potential {
    /// Zero, of magnitude zero.
    pub const ZERO: Self = Self {
        value: 0.0,
        magnitude: 0.0,
    };

    /// A sum of non-negative parts: its own magnitude.
    #[must_use]
    pub fn non_negative(value: f64) -> Self {
        Self {
            value,
            magnitude: value,
        }
    }

    /// How far rounding alone may move the value, `ε · magnitude`, J.
    #[must_use]
    pub fn rounding(&self) -> f64 {
        f64::EPSILON * self.magnitude
    }
}

impl Add for Potential {
    type Output = Self;

    fn add(self, other: Self) -> Self {
        Self {
            value: self.value + other.value,
            magnitude: self.magnitude + other.magnitude,
        }
    }
}

impl AddAssign for Potential {
    fn add_assign(&mut self, other: Self) {
        *self = *self + other;
    }
}
