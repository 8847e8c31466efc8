//! Adaptive-step Dormand–Prince 5(4).

use hooke_core::{
    ForceEvaluator, Integrator, Parameter, ParameterError, State, StepBuffers, StepError,
    StepReport, System, Vec3,
};

use crate::ops::combine;

/// Stage nodes are implied by `A`; the rows of the Butcher matrix, stage 2..7.
const A: [&[f64]; 6] = [
    &[1.0 / 5.0],
    &[3.0 / 40.0, 9.0 / 40.0],
    &[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
    &[
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
    ],
    &[
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
    ],
    // The fifth-order weights: stage 7 is the new solution (first same as last).
    &[
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
/// Fifth-order minus embedded fourth-order weights, for the error estimate.
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];
/// Safety factor and bounds on the step-size change, and the PI-controller
/// exponents (Hairer's `dopri5`: β = 0.04, α = 1/5 − 0.75 β).
const SAFETY: f64 = 0.9;
const MIN_FACTOR: f64 = 0.2;
const MAX_FACTOR: f64 = 10.0;
const BETA: f64 = 0.04;
const ALPHA: f64 = 0.2 - 0.75 * BETA;

/// `maxᵢ |eᵢ| / (atol + rtol · max(|aᵢ|, |bᵢ|))` over the components of
/// positions (part 0) and velocities (part 1), with `eᵢ` given per part and
/// particle by `error`; infinite if any `eᵢ` is NaN.
fn scaled_max(
    rtol: f64,
    atol: f64,
    pairs: [(&[Vec3], &[Vec3]); 2],
    error: impl Fn(usize, usize) -> Vec3,
) -> f64 {
    let mut max: f64 = 0.0;
    for (part, (a, b)) in pairs.into_iter().enumerate() {
        for (i, (ai, bi)) in a.iter().zip(b).enumerate() {
            let e = error(part, i);
            for c in 0..3 {
                let ratio = e[c].abs() / (atol + rtol * ai[c].abs().max(bi[c].abs()));
                if ratio.is_nan() {
                    return f64::INFINITY;
                }
                max = max.max(ratio);
            }
        }
    }
    max
}

/// The Dormand–Prince 5(4) embedded Runge–Kutta pair with adaptive step-size
/// control, on `y = (x, v)`, `y' = (v, a(x, v))`.
///
/// Seven stages, six force evaluations per accepted substep (the last stage is
/// the first of the next substep). The fifth-order solution is propagated; the
/// difference from the embedded fourth-order one estimates the local error
/// `e`, which is compared with the tolerance component by component over all
/// positions and velocities:
///
/// ```text
/// err = maxᵢ |eᵢ| / (atol + rtol · max(|yₙ,ᵢ|, |yₙ₊₁,ᵢ|))
/// ```
///
/// A substep with `err ≤ 1` is accepted. The next step size comes from
/// Hairer's PI controller, `h ← h · clamp(0.9 · err^(−0.17) · errₚᵣₑᵥ^0.04,
/// 0.2, 10)`, never growing right after a rejection. [`Integrator::step`]
/// covers the requested `dt` exactly with as many substeps as needed and
/// reports accepted and rejected substeps; the step size it ends with carries
/// over to the next call. The local error is controlled, not the global one;
/// on smooth non-stiff problems the global error is typically of the order of
/// the tolerance.
///
/// Explicit, so stiff springs still limit the step. Its stability function
/// `R(z) = Σ_{k≤5} zᵏ/k! + z⁶/600` satisfies `|R(iθ)| ≤ 1` on the imaginary axis
/// only up to `θ = hω ≈ 0.997`; beyond, undamped oscillations grow unless the
/// error control keeps the step small, which it does at any useful tolerance.
///
/// Source: Dormand & Prince, J. Comput. Appl. Math. 6 (1980) 19; Hairer,
/// Nørsett & Wanner, *Solving Ordinary Differential Equations I*, §II.4–II.5
/// (coefficients, error norm, initial step and controller of `dopri5`).
#[derive(Debug, Clone)]
pub struct DormandPrince {
    rtol: f64,
    atol: f64,
    max_substeps: usize,
    forces: ForceEvaluator,
    /// The solution as substeps advance it, and the history.
    out: StepBuffers,
    /// The controller's proposal for the next substep.
    proposal: Option<f64>,
    previous_error: f64,
    /// Stage derivatives `kₛ = (Vₛ, Aₛ)`: the stage velocity is the position
    /// derivative.
    stage_v: [Vec<Vec3>; 7],
    stage_a: [Vec<Vec3>; 7],
    stage_x: Vec<Vec3>,
}

impl Default for DormandPrince {
    /// [`DormandPrince::RTOL`], [`DormandPrince::ATOL`], at most
    /// [`DormandPrince::MAX_SUBSTEPS`] substeps per step.
    fn default() -> Self {
        Self {
            rtol: Self::RTOL,
            atol: Self::ATOL,
            max_substeps: Self::MAX_SUBSTEPS,
            forces: ForceEvaluator::default(),
            out: StepBuffers::default(),
            proposal: None,
            previous_error: 1e-4,
            stage_v: Default::default(),
            stage_a: Default::default(),
            stage_x: Vec::new(),
        }
    }
}

impl DormandPrince {
    /// The name scene files, reports and the command line use.
    pub const NAME: &'static str = "dormand-prince";
    /// The default relative tolerance.
    pub const RTOL: f64 = 1e-6;
    /// The default absolute tolerance, m and m/s.
    pub const ATOL: f64 = 1e-9;
    /// The default cap on substeps per call to [`Integrator::step`].
    pub const MAX_SUBSTEPS: usize = 100_000;

    /// An integrator with relative tolerance `rtol` and absolute tolerance
    /// `atol` (in m for positions and m/s for velocities).
    ///
    /// # Errors
    /// [`ParameterError`] if a tolerance is negative or not finite, or both
    /// are zero.
    pub fn new(rtol: f64, atol: f64) -> Result<Self, ParameterError> {
        for (name, value) in [(Parameter::Rtol, rtol), (Parameter::Atol, atol)] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(ParameterError::new(
                    Self::NAME,
                    name,
                    value,
                    "finite and non-negative",
                ));
            }
        }
        if rtol == 0.0 && atol == 0.0 {
            return Err(ParameterError::new(
                Self::NAME,
                Parameter::Atol,
                atol,
                "positive when rtol is zero",
            ));
        }
        Ok(Self {
            rtol,
            atol,
            ..Self::default()
        })
    }

    /// Caps the substeps one call to [`Integrator::step`] may take (at least
    /// one); beyond it the step fails with [`StepError::TooManySubsteps`]
    /// instead of running on.
    #[must_use]
    pub fn max_substeps(self, max_substeps: usize) -> Self {
        Self {
            max_substeps: max_substeps.max(1),
            ..self
        }
    }

    /// Relative and absolute tolerance.
    #[must_use]
    pub fn tolerances(&self) -> (f64, f64) {
        (self.rtol, self.atol)
    }

    /// Hairer's starting step from `y₀`, `f(y₀)` (in stage 0) and one more
    /// force evaluation.
    fn initial_step(&mut self, system: &System) -> f64 {
        let (x, v) = (&self.out.x[..], &self.out.v[..]);
        let (first_v, rest_v) = self.stage_v.split_at_mut(1);
        let (first_a, rest_a) = self.stage_a.split_at_mut(1);
        let (v0, a0, v1, a1) = (&first_v[0], &first_a[0], &mut rest_v[0], &mut rest_a[0]);
        let (rtol, atol) = (self.rtol, self.atol);
        let norm = |f: &dyn Fn(usize, usize) -> Vec3| scaled_max(rtol, atol, [(x, x), (v, v)], f);
        let d0 = norm(&|part, i| if part == 0 { x[i] } else { v[i] });
        let d1 = norm(&|part, i| if part == 0 { v0[i] } else { a0[i] });
        let h0 = if d0 < 1e-5 || d1 < 1e-5 {
            1e-6
        } else {
            0.01 * d0 / d1
        };
        combine(&mut self.stage_x, x, &[(h0, v0)]);
        combine(v1, v, &[(h0, a0)]);
        self.forces.accelerations(system, &self.stage_x, v1, a1);
        let d2 = norm(&|part, i| {
            (if part == 0 {
                v1[i] - v0[i]
            } else {
                a1[i] - a0[i]
            }) / h0
        });
        let h1 = if d1.max(d2) <= 1e-15 {
            (h0 * 1e-3).max(1e-6)
        } else {
            (0.01 / d1.max(d2)).powf(0.2)
        };
        (100.0 * h0).min(h1)
    }

    /// One trial substep of size `h` from `(x, v)` with `k₁` in stage 0; the
    /// candidate is left in `stage_x` / `stage_v[6]` with `k₇` in stage 6.
    /// Returns the scaled error.
    fn trial(&mut self, system: &System, h: f64) -> f64 {
        for (s, row) in A.iter().enumerate() {
            let stage = s + 1;
            let (done_v, rest_v) = self.stage_v.split_at_mut(stage);
            let (done_a, rest_a) = self.stage_a.split_at_mut(stage);
            for i in 0..self.out.x.len() {
                let (mut xs, mut vs) = (self.out.x[i], self.out.v[i]);
                for (j, &c) in row.iter().enumerate() {
                    xs += h * c * done_v[j][i];
                    vs += h * c * done_a[j][i];
                }
                self.stage_x[i] = xs;
                rest_v[0][i] = vs;
            }
            self.forces
                .accelerations(system, &self.stage_x, &rest_v[0], &mut rest_a[0]);
        }
        let (sv, sa) = (&self.stage_v, &self.stage_a);
        let (x, v) = (&self.out.x[..], &self.out.v[..]);
        let pairs = [(x, &self.stage_x[..]), (v, &sv[6][..])];
        scaled_max(self.rtol, self.atol, pairs, |part, i| {
            let k = if part == 0 { sv } else { sa };
            h * E
                .iter()
                .zip(k)
                .fold(Vec3::zeros(), |acc, (e, ks)| acc + *e * ks[i])
        })
    }
}

impl Integrator for DormandPrince {
    fn step(
        &mut self,
        system: &System,
        state: &mut State,
        dt: f64,
    ) -> Result<StepReport, StepError> {
        let name = self.name();
        let stages = self.stage_v.iter_mut().chain(&mut self.stage_a);
        let start = self
            .out
            .begin(name, system, state, dt, stages.chain([&mut self.stage_x]))?;
        self.out.x.copy_from_slice(state.positions());
        self.out.v.copy_from_slice(state.velocities());
        let mut report = StepReport::default();
        if start.previous_dt().is_none() {
            self.stage_v[0].copy_from_slice(&self.out.v);
            self.forces
                .accelerations(system, &self.out.x, &self.out.v, &mut self.stage_a[0]);
            self.proposal = Some(self.initial_step(system));
            self.previous_error = 1e-4;
            report.force_evaluations += 2;
        }
        let (start, end) = (state.time(), state.time() + dt);
        let mut t = start;
        let mut h = self.proposal.unwrap_or(dt);
        let mut rejected_last = false;
        loop {
            if report.accepted_steps + report.rejected_steps >= self.max_substeps {
                let substeps = report.accepted_steps + report.rejected_steps;
                return Err(StepError::TooManySubsteps { time: t, substeps });
            }
            let last = t + 1.01 * h >= end;
            let h_try = if last { end - t } else { h };
            if h_try <= 16.0 * f64::EPSILON * t.abs().max(dt) {
                return Err(StepError::StepSizeUnderflow {
                    time: t,
                    step: h_try,
                });
            }
            let err = self.trial(system, h_try);
            report.force_evaluations += 6;
            if err <= 1.0 {
                let growth = err.max(1e-10).powf(-ALPHA) * self.previous_error.powf(BETA);
                let mut factor = (SAFETY * growth).clamp(MIN_FACTOR, MAX_FACTOR);
                if rejected_last {
                    factor = factor.min(1.0);
                }
                self.previous_error = err.max(1e-4);
                std::mem::swap(&mut self.out.x, &mut self.stage_x);
                self.out.v.copy_from_slice(&self.stage_v[6]);
                self.stage_v.swap(0, 6);
                self.stage_a.swap(0, 6);
                report.accepted_steps += 1;
                rejected_last = false;
                // A step clipped to land on `end` does not shrink the proposal.
                h = if last {
                    h.max(h_try * factor)
                } else {
                    h_try * factor
                };
                if last {
                    break;
                }
                t += h_try;
            } else {
                let shrink = if err.is_finite() {
                    SAFETY * err.powf(-0.2)
                } else {
                    MIN_FACTOR
                };
                h = h_try * shrink.max(MIN_FACTOR);
                report.rejected_steps += 1;
                rejected_last = true;
            }
        }
        self.proposal = Some(h);
        self.out.finish(system, state, dt, report)
    }

    fn name(&self) -> &'static str {
        Self::NAME
    }
}
