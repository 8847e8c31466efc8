//! Newton's method on the incremental potential `Φ` of one implicit
//! (sub)step: its iteration state, `Φ` at a point, the decrement, and the
//! directions (Newton's, or L-BFGS's through the quasi-Newton state); the
//! `line_search` module iterates them. [`Implicit`](crate::Implicit)'s docs
//! give the equations.

use hooke_core::{At, CompressedSprings, Potential, StepError, StepReport, System, Vec3};

use crate::linear::matrix::DiagonalBlocks;
use crate::linear::solver::solve::Solve;
use crate::linear::solver::topology::Topology;
use crate::linear::vector::{dot, for_each_row};
use crate::minimize::quasi_newton::QuasiNewton;
use crate::minimize::terms::{Terms, check_finite};

/// How Newton's method ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Outcome {
    /// Whether the iterate meets the stopping rule.
    pub(crate) converged: bool,
    /// Linear solves taken (look-ahead steps included).
    pub(crate) iterations: usize,
    /// The last relative Newton decrement ([`Newton::decrement`]).
    pub(crate) residual: f64,
}

/// The iteration buffers: the iterate, its Newton step, a trial point, and
/// the look-ahead step and point of the watchdog.
pub(crate) struct Iterates<'a> {
    pub(crate) v: &'a mut Vec<Vec3>,
    pub(crate) delta: &'a mut Vec<Vec3>,
    pub(crate) trial: &'a mut Vec<Vec3>,
    pub(crate) ahead: &'a mut Vec<Vec3>,
    pub(crate) look: &'a mut Vec<Vec3>,
}

/// What one (sub)step's Newton iterations share: the step's predictor
/// `x = x̃ + βh v` and `ṽ`, the linear solver and its topology, the terms
/// of `Φ`, and scratch for positions, the right-hand side and a motion.
pub(crate) struct Newton<'a> {
    pub(crate) system: &'a System,
    pub(crate) solve: Solve<'a>,
    pub(crate) topology: &'a mut Topology,
    pub(crate) terms: &'a mut Terms,
    pub(crate) compressed: CompressedSprings,
    pub(crate) x_tilde: &'a [Vec3],
    pub(crate) v_tilde: &'a [Vec3],
    pub(crate) beta_h: f64,
    pub(crate) x: &'a mut [Vec3],
    pub(crate) b: &'a mut [Vec3],
    /// Scratch for the motion `βh α δ` that collision detection checks.
    pub(crate) motion: &'a mut [Vec3],
    pub(crate) pcg: &'a mut crate::linear::cg::PcgWorkspace,
    pub(crate) report: &'a mut StepReport,
    /// Whether iterative solves stop at the forcing term (see
    /// [`Newton::minimize`]).
    pub(crate) inexact: bool,
    /// The stiffness blocks the last Newton step was solved with: once a
    /// step needed compressed springs clamped, its later iterations start
    /// there instead of assembling and factoring the exact blocks first.
    pub(crate) hessian: CompressedSprings,
    /// The quasi-Newton state, when the directions are L-BFGS's instead of
    /// Newton's.
    pub(crate) quasi: Option<&'a mut QuasiNewton>,
    /// Whether `b` holds `−∇Φ`, without the barriers' terms, at the point
    /// [`Newton::potential`] evaluated last (the quasi-Newton step's, whose
    /// next direction reuses it where that point becomes the iterate).
    pub(crate) evaluated_residual: bool,
}

impl Newton<'_> {
    /// Fills the position scratch with `x = x̃ + βh v`.
    pub(crate) fn positions(&mut self, v: &[Vec3]) {
        let (x_tilde, beta_h) = (self.x_tilde, self.beta_h);
        for_each_row(self.x, |i, x| *x = x_tilde[i] + beta_h * v[i]);
    }

    /// `Φ(v)` (infinite where a barrier's gap is not positive) and its
    /// magnitude. For the quasi-Newton step, the same passes leave `−∇Φ(v)`
    /// without the barriers' terms in `b` ([`Newton::evaluated_residual`]).
    pub(crate) fn potential(&mut self, v: &[Vec3]) -> Potential {
        self.positions(v);
        self.evaluated_residual = self.quasi.is_some();
        let at = iterate(self.x, v, (self.v_tilde, self.beta_h), self.compressed);
        if self.evaluated_residual {
            self.terms.gradient(self.system, &at, self.b)
        } else {
            self.terms.value(self.system, &at)
        }
    }

    /// The starting point of the iteration: `v`, or `trial` (swapped into
    /// `v`) if given and lower in `Φ`; returns `Φ` there.
    pub(crate) fn start(&mut self, v: &mut Vec<Vec3>, trial: Option<&mut Vec<Vec3>>) -> Potential {
        let first = self.potential(v);
        let Some(trial) = trial else {
            return first;
        };
        let second = self.potential(trial);
        if second.value < first.value {
            std::mem::swap(v, trial);
            second
        } else {
            self.evaluated_residual = false;
            first
        }
    }

    /// The Newton decrement `λ = √|∇Φ·δ|` relative to the step's velocity
    /// scale in the mass norm `‖u‖_M = √(Σ mᵢ|uᵢ|²)`,
    ///
    /// ```text
    /// λ / max(‖v + δ − v₀‖_M, ‖v + δ‖_M, βh‖g‖ √(Σ mᵢ)),
    /// ```
    ///
    /// the last term the velocity gravity gives in one step, so that a body
    /// at rest has a scale too.
    ///
    /// zero for `δ = 0`. As `λ² = δᵀ A δ ≥ ‖δ‖²_M`, it bounds the relative
    /// error of the velocities in the mass norm, and `λ²/2` estimates how
    /// far `Φ` is above its minimum.
    pub(crate) fn decrement(&self, slope: f64, v: &[Vec3], delta: &[Vec3], v0: &[Vec3]) -> f64 {
        if slope == 0.0 {
            return 0.0;
        }
        let next = v.iter().zip(delta).map(|(v, d)| v + d);
        slope.abs().sqrt() / velocity_scale(self.system, next, v0, self.beta_h)
    }

    /// Newton's step `δ` at `v`: assembles the terms' `(M + βh C + β²h² K)
    /// δ = −∇Φ(v)` with their exact Hessians (unless an earlier iteration
    /// of the same step needed the stand-ins, [`Newton::hessian`]), or —
    /// where that system is not positive definite or its solution does not
    /// descend, and the integrator clamps compressed springs — with their
    /// positive-semidefinite stand-ins (compressed springs clamped, the
    /// elements' and barriers' Hessians projected), and solves it in the
    /// free directions. Returns the slope `∇Φ·δ`.
    ///
    /// # Errors
    /// Assembly and solver errors.
    pub(crate) fn direction(&mut self, v: &[Vec3], delta: &mut [Vec3]) -> Result<f64, StepError> {
        self.positions(v);
        if let Some(quasi) = self.quasi.take() {
            let slope = self.quasi_direction(quasi, v, delta);
            self.quasi = Some(quasi);
            return slope;
        }
        let mut hessian = self.hessian;
        loop {
            let at = iterate(self.x, v, (self.v_tilde, self.beta_h), hessian);
            delta.fill(Vec3::zeros());
            let last = hessian == self.compressed;
            let solved = self
                .solve
                .assemble(self.terms, self.topology, &at, self.b)
                .and_then(|()| {
                    self.solve
                        .solve(self.topology, self.x, self.b, delta, self.pcg, self.report)
                });
            match solved {
                Err(StepError::NotPositiveDefinite { .. }) if !last => {}
                Err(e) => return Err(e),
                Ok(()) if !last && dot(self.b, delta) <= 0.0 => {}
                Ok(()) => break,
            }
            hessian = CompressedSprings::Clamped;
        }
        self.hessian = hessian;
        Ok(-dot(self.b, delta))
    }

    /// The quasi-Newton step at `v` (see the `quasi_newton` module), whose
    /// positions [`Newton::direction`] filled: the residual `−∇Φ(v)`, the
    /// barriers' gradients included, without any matrix, then L-BFGS's
    /// two-loop recursion. Returns the slope `∇Φ·δ`.
    ///
    /// # Errors
    /// [`StepError::NonFiniteSystem`] for a residual that is not finite.
    fn quasi_direction(
        &mut self,
        quasi: &mut QuasiNewton,
        v: &[Vec3],
        delta: &mut [Vec3],
    ) -> Result<f64, StepError> {
        let system = self.system;
        let at = iterate(self.x, v, (self.v_tilde, self.beta_h), self.compressed);
        if !std::mem::take(&mut self.evaluated_residual) {
            self.terms.gradient(system, &at, self.b);
        }
        check_finite(system, self.b, self.solve.time)?;
        // The barriers' gradients join the residual. At the step's first
        // iterate their diagonal Hessian blocks give the stand-in on H₀;
        // later iterations keep no blocks.
        if quasi.pending() {
            let mut diagonal = DiagonalBlocks::default();
            self.terms.add_barriers(system, &at, self.b, &mut diagonal);
            quasi.add_stand_in(system, &diagonal.0, self.solve.time)?;
        } else {
            self.terms.add_barriers(system, &at, self.b, &mut ());
        }
        self.report.linear_solves += 1;
        let slope = quasi.direction(system, self.b, v, delta);
        self.report.linear_solver = quasi.solver_name();
        Ok(slope)
    }
}

/// The iterate `v` at its positions `x = x̃ + βh v` for the predictor's `ṽ`
/// and `βh`, with the Hessians `compressed` says.
fn iterate<'a>(
    x: &'a [Vec3],
    v: &'a [Vec3],
    (v_tilde, beta_h): (&'a [Vec3], f64),
    compressed: CompressedSprings,
) -> At<'a> {
    At {
        x,
        v,
        v_tilde,
        beta_h,
        displacement: None,
        compressed,
    }
}

/// The step's velocity scale that the stopping rule measures the Newton
/// decrement against, `max(‖v − v₀‖_M, ‖v‖_M, βh‖g‖ √(Σ mᵢ))` for the
/// velocities `v` ([`Newton::decrement`]).
pub(crate) fn velocity_scale(
    system: &System,
    v: impl Iterator<Item = Vec3>,
    v0: &[Vec3],
    beta_h: f64,
) -> f64 {
    let masses = system.masses();
    let (mut change, mut speed, mut total) = (0.0, 0.0, 0.0);
    for (i, (v, v0)) in v.zip(v0).enumerate() {
        change += masses[i] * (v - v0).norm_squared();
        speed += masses[i] * v.norm_squared();
        total += masses[i];
    }
    let gravity = system.gravity().map_or(0.0, |g| g.norm());
    change
        .max(speed)
        .max(total * (beta_h * gravity).powi(2))
        .sqrt()
}
