//! The scheme's predictor of an implicit (sub)step: its coefficients
//! ([`Coefficients`]) and the predicted positions and velocities
//! ([`Predictor`]) that `Φ` is written around.

use hooke_core::{StepStart, Vec3};

use crate::step::scheme::Scheme;

/// The coefficients of a step of `h` after one of `previous`:
/// `x = x̃ + βh v` and `v = ṽ + βh M⁻¹ f(x, v)` with
/// `x̃ = a xₙ − b xₙ₋₁`, `ṽ = a vₙ − b vₙ₋₁`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Coefficients {
    /// `β`.
    pub(crate) beta: f64,
    /// `a`.
    pub(crate) current: f64,
    /// `b`: positive for BDF2's two-step steps, zero for backward Euler.
    pub(crate) past: f64,
}

impl Coefficients {
    /// Backward Euler (`β = a = 1`, `b = 0`), or variable-step BDF2 with
    /// step ratio `ω = h/hₙ₋₁ ≤ 2`: `β = (1+ω)/(1+2ω)`,
    /// `a = (1+ω)²/(1+2ω)`, `b = ω²/(1+2ω)` (for `ω = 1` the familiar
    /// `2/3, 4/3, 1/3`). BDF2 (re)starts with a backward-Euler step.
    pub(crate) fn new(scheme: Scheme, h: f64, previous: Option<f64>) -> Self {
        let ratio = previous
            .map(|last| h / last)
            .filter(|&omega| scheme == Scheme::Bdf2 && omega <= 2.0 + 1e-9);
        ratio.map_or(
            Self {
                beta: 1.0,
                current: 1.0,
                past: 0.0,
            },
            |omega| {
                let d = 1.0 + 2.0 * omega;
                Self {
                    beta: (1.0 + omega) / d,
                    current: (1.0 + omega).powi(2) / d,
                    past: omega * omega / d,
                }
            },
        )
    }
}

/// The predictor of a (sub)step, one vector per particle each.
#[derive(Debug, Default)]
pub(crate) struct Predictor {
    /// `x̃ = a xₙ − b xₙ₋₁`.
    pub(crate) x_tilde: Vec<Vec3>,
    /// `ṽ = a vₙ − b vₙ₋₁`.
    pub(crate) v_tilde: Vec<Vec3>,
    /// `u = x̃ − xₙ + βh vₙ`, how far the point `x̃ + βh vₙ` lies from `xₙ`,
    /// where Baraff & Witkin's solve linearises the forces; the buffer is
    /// the minimisation's motion scratch afterwards.
    pub(crate) u: Vec<Vec3>,
}

impl Predictor {
    /// Predicts the step from `step` with coefficients `c`, after the
    /// positions and velocities `past = (xₙ₋₁, vₙ₋₁)`.
    pub(crate) fn predict(&mut self, step: &StepStart<'_>, c: Coefficients, past: [&[Vec3]; 2]) {
        let (x0, v0, beta_h) = (step.x, step.v, step.beta_h);
        let [x_prev, v_prev] = past;
        let Self {
            x_tilde,
            v_tilde,
            u,
        } = self;
        for i in 0..x0.len() {
            x_tilde[i] = c.current * x0[i] - c.past * x_prev[i];
            v_tilde[i] = c.current * v0[i] - c.past * v_prev[i];
            u[i] = x_tilde[i] - x0[i] + beta_h * v0[i];
        }
    }
}
