//! Error-controlled variable steps: local error estimates for backward
//! Euler and variable-step BDF2 from the positions of the last steps, and
//! the step-size rule.
//!
//! With `hₙ₊₁ = h`, `hₙ = h/ω` and `hₙ₋₁` the sizes of the step taken and
//! of the two before it, the divided differences of the positions give
//!
//! ```text
//! D₂ = xₙ₊₁ − [xₙ + h (xₙ − xₙ₋₁)/hₙ]                         (linear extrapolation)
//! D₃ = xₙ₊₁ − P(tₙ₊₁),  P the quadratic through xₙ₋₂, xₙ₋₁, xₙ    (quadratic extrapolation)
//! ```
//!
//! with `D₂ ≈ ½ x'' h (h + hₙ)` and `D₃ ≈ ⅙ x''' h (h + hₙ)(h + hₙ + hₙ₋₁)`.
//! Backward Euler's local error is `½ h² x''`, so `e = D₂ ω/(1 + ω)`;
//! variable-step BDF2's is `(1+ω)² h³ x''' / (6ω(1+2ω))` (from its
//! coefficients, [`crate::Scheme::Bdf2`]), so
//!
//! ```text
//! e = (1+ω)² / (ω(1+2ω)) · h² / ((h + hₙ)(h + hₙ + hₙ₋₁)) · D₃,
//! ```
//!
//! `−(2/9) D₃`'s magnitude at constant steps. (A BDF2 step with only two
//! past positions uses the first-order estimate, which is larger.) The
//! error is measured against a tolerance relative to the step's largest
//! displacement,
//!
//! ```text
//! err = maxᵢ ‖eᵢ‖∞ / (atol + rtol · maxᵢ ‖xₙ₊₁,ᵢ − xₙ,ᵢ‖∞),
//! ```
//!
//! so that it does not depend on where the origin is. A step with
//! `err > 1` is rejected; the next step is `h · min(2, max(0.2, 0.9 err^(−1/(p+1))))`
//! (`p` the order; at most `0.9 h` after a rejection), as in Hairer,
//! Nørsett & Wanner, *Solving Ordinary Differential Equations I*, §II.4.

use hooke_core::{Parameter, ParameterError, Vec3};

/// The tolerances of error-controlled steps: a step's estimated local
/// position error must not exceed `absolute + relative · (its largest
/// displacement)`. See [`Implicit::with_error_control`](crate::Implicit::with_error_control).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ErrorControl {
    relative: f64,
    absolute: f64,
}

impl ErrorControl {
    /// A default relative tolerance: a local error of 0.1 % of a step's
    /// largest displacement.
    pub const RELATIVE: f64 = 1e-3;
    /// A default absolute tolerance, m: a micrometre.
    pub const ABSOLUTE: f64 = 1e-6;

    /// A relative tolerance in `(0, 1)` and an absolute one in m, `≥ 0`.
    ///
    /// # Errors
    /// [`ParameterError`] naming the tolerance out of range.
    pub fn new(relative: f64, absolute: f64) -> Result<Self, ParameterError> {
        if !(relative > 0.0 && relative < 1.0) {
            return Err(ParameterError::new(
                "error control",
                Parameter::RelativeTolerance,
                relative,
                "in (0, 1)",
            ));
        }
        if !(absolute.is_finite() && absolute >= 0.0) {
            return Err(ParameterError::new(
                "error control",
                Parameter::AbsoluteTolerance,
                absolute,
                "finite and non-negative",
            ));
        }
        Ok(Self { relative, absolute })
    }

    /// The relative tolerance.
    #[must_use]
    pub fn relative(&self) -> f64 {
        self.relative
    }

    /// The absolute tolerance, m.
    #[must_use]
    pub fn absolute(&self) -> f64 {
        self.absolute
    }

    /// The error `err` of a step of size `h` from `x0` to `x1` and the order
    /// of the estimate (2 for BDF2's `two_step` steps, 1 otherwise), from
    /// the positions `xₙ₋₁`, `xₙ₋₂` and sizes `hₙ`, `hₙ₋₁` of the steps
    /// before, as far as they are known ([`ErrorControl::error`]); `None`
    /// without the step before.
    pub(crate) fn estimate(
        &self,
        two_step: bool,
        h: f64,
        (x0, x1): (&[Vec3], &[Vec3]),
        past: [(&[Vec3], Option<f64>); 2],
    ) -> Option<(f64, u32)> {
        let [(x_prev, previous), (x_earlier, earlier)] = past;
        let known = [
            (x_prev, previous?),
            (x_earlier, earlier.unwrap_or(f64::NAN)),
        ];
        let count = if earlier.is_some() { 2 } else { 1 };
        let order = if two_step { 2 } else { 1 };
        self.error(two_step, h, (x0, x1), &known[..count])
            .map(|err| (err, order))
    }

    /// The error `err` of a step from `x0` to `x1` of size `h` (see the
    /// module docs); `past` holds the positions and sizes of the steps
    /// before, most recent first (`xₙ₋₁, hₙ` then `xₙ₋₂, hₙ₋₁`). `None`
    /// without a past step.
    pub(crate) fn error(
        &self,
        second_order: bool,
        h: f64,
        (x0, x1): (&[Vec3], &[Vec3]),
        past: &[(&[Vec3], f64)],
    ) -> Option<f64> {
        let &(xm1, h1) = past.first()?;
        let omega = h / h1;
        let (mut error, mut motion) = (0.0_f64, 0.0_f64);
        for i in 0..x1.len() {
            let slope = (x0[i] - xm1[i]) / h1;
            let linear = x1[i] - (x0[i] + h * slope);
            let e = match past.get(1) {
                Some(&(xm2, h2)) if second_order => {
                    let curvature = (slope - (xm1[i] - xm2[i]) / h2) / (h1 + h2);
                    let cubic = linear - curvature * h * (h + h1);
                    (1.0 + omega).powi(2) / (omega * (1.0 + 2.0 * omega)) * h * h
                        / ((h + h1) * (h + h1 + h2))
                        * cubic
                }
                _ => linear * omega / (1.0 + omega),
            };
            error = error.max(e.amax());
            motion = motion.max((x1[i] - x0[i]).amax());
        }
        Some(error / (self.absolute + self.relative * motion))
    }
}

/// The factor the next step's size is multiplied by after a step of order
/// `order` with error `err` (see the module docs).
pub(crate) fn step_factor(err: f64, order: u32, accepted: bool) -> f64 {
    let proposed = if err > 0.0 {
        0.9 * err.powf(-1.0 / f64::from(order + 1))
    } else {
        2.0
    };
    let factor = proposed.clamp(0.2, 2.0);
    if accepted { factor } else { factor.min(0.9) }
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;

    use super::*;

    fn line(f: impl Fn(f64) -> f64, t: f64) -> Vec<Vec3> {
        vec![Vec3::new(f(t), 0.0, 0.0)]
    }

    #[test]
    fn the_first_order_estimate_is_backward_eulers_error_on_a_parabola() {
        // x = t²: x'' = 2, so backward Euler's local error is ½ h² x'' = h².
        let control = ErrorControl::new(0.5, 1.0).unwrap();
        let f = |t: f64| t * t;
        let (h1, h) = (0.2, 0.1);
        let (xm1, x0, x1) = (line(f, 0.0), line(f, h1), line(f, h1 + h));
        let err = control.error(false, h, (&x0, &x1), &[(&xm1, h1)]).unwrap();
        let motion = f(h1 + h) - f(h1);
        assert_relative_eq!(err * (1.0 + 0.5 * motion), h * h, max_relative = 1e-12);
    }

    #[test]
    fn the_second_order_estimate_is_bdf2s_error_on_a_cubic() {
        // x = t³: x''' = 6, so the error is (1+ω)²/(ω(1+2ω)) h³ at ratio ω.
        let control = ErrorControl::new(0.5, 1.0).unwrap();
        let f = |t: f64| t * t * t;
        let (h2, h1, h) = (0.3, 0.2, 0.1);
        let t0 = h2 + h1;
        let x = |t| line(f, t);
        let (xm2, xm1, x0, x1) = (x(0.0), x(h2), x(t0), x(t0 + h));
        let err = control
            .error(true, h, (&x0, &x1), &[(&xm1, h1), (&xm2, h2)])
            .unwrap();
        let omega = h / h1;
        let expected = (1.0 + omega).powi(2) / (omega * (1.0 + 2.0 * omega)) * h.powi(3);
        let motion = f(t0 + h) - f(t0);
        assert_relative_eq!(err * (1.0 + 0.5 * motion), expected, max_relative = 1e-9);
    }

    #[test]
    fn no_past_step_gives_no_estimate() {
        let control = ErrorControl::new(0.5, 1.0).unwrap();
        let x = line(|t| t, 1.0);
        assert!(control.error(true, 0.1, (&x, &x), &[]).is_none());
    }

    #[test]
    fn tolerances_out_of_range_are_named() {
        let e = ErrorControl::new(0.0, 1.0).unwrap_err();
        assert!(e.to_string().contains("relative tolerance"), "{e}");
        let e = ErrorControl::new(0.1, f64::NAN).unwrap_err();
        assert!(e.to_string().contains("absolute tolerance"), "{e}");
    }

    #[test]
    fn the_step_factor_is_bounded_and_shrinks_after_a_rejection() {
        assert_relative_eq!(step_factor(0.0, 1, true), 2.0);
        assert_relative_eq!(step_factor(1e9, 1, true), 0.2);
        assert!(step_factor(1.01, 2, false) <= 0.9);
        // err = 0.9^(p+1) keeps the size.
        assert_relative_eq!(
            step_factor(0.9_f64.powi(3), 2, true),
            1.0,
            max_relative = 1e-12
        );
    }
}
