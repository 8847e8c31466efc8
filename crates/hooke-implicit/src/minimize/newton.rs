//! Newton's method on the incremental potential `Φ` of one implicit
//! (sub)step, with its line search; [`Implicit`](crate::Implicit)'s docs give
//! the equations.

use hooke_core::{CompressedSprings, StepError, StepReport, System, Vec3};

use crate::linear::solver::LinearSolver;
use crate::linear::solver::solve::Solve;
use crate::linear::solver::topology::Topology;
use crate::linear::vector::{dot, for_each_row, for_each_row2};
use crate::minimize::assembly::{Assembler, Potential};
use crate::minimize::contact::Contact;
use crate::minimize::linearization::Linearization;
use crate::minimize::quasi_newton::QuasiNewton;
use crate::minimize::residual::{Point, check_finite};

/// The sufficient-decrease constant `c` of the Armijo condition
/// `Φ(v + αδ) ≤ Φ(v) + c α ∇Φ·δ`.
const ARMIJO: f64 = 1e-4;

/// The longest multiple of a Newton step the line search tries.
const MAX_EXTRAPOLATION: f64 = 64.0;

/// The shortest fraction of a Newton step the line search tries.
const MIN_STEP: f64 = 1e-6;

/// The loosest relative residual an iterative solve of a Newton step may
/// stop at (the forcing term before the first decrement is known).
const MAX_FORCING: f64 = 0.1;

/// The forcing term of an inexact Newton iteration whose last relative
/// decrement was `last`: `η = min(0.1, ½ last)`, so that the linear solves
/// are loose while Newton is far from the answer and tighten with it
/// (Eisenstat & Walker, *Choosing the forcing terms in an inexact Newton
/// method*, 1996).
fn forcing(last: f64) -> f64 {
    if last.is_finite() {
        (0.5 * last).min(MAX_FORCING)
    } else {
        MAX_FORCING
    }
}

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
/// `x = x̃ + βh v` and `ṽ`, the linear solver and its topology, the
/// contact terms, and scratch for positions, the inertia term, the
/// right-hand side and a motion.
pub(crate) struct Newton<'a> {
    pub(crate) system: &'a System,
    pub(crate) solve: Solve<'a>,
    pub(crate) topology: &'a mut Topology,
    pub(crate) assembler: &'a mut Assembler,
    /// The contact terms of `Φ`, in a system with obstacles or colliding
    /// surfaces.
    pub(crate) contact: Option<&'a mut Contact>,
    pub(crate) compressed: CompressedSprings,
    pub(crate) x_tilde: &'a [Vec3],
    pub(crate) v_tilde: &'a [Vec3],
    pub(crate) beta_h: f64,
    pub(crate) x: &'a mut [Vec3],
    pub(crate) inertia: &'a mut [Vec3],
    pub(crate) b: &'a mut [Vec3],
    /// Scratch for the motion `βh α δ` that collision detection checks.
    pub(crate) motion: &'a mut [Vec3],
    pub(crate) pcg: &'a mut crate::linear::cg::PcgWorkspace,
    pub(crate) report: &'a mut StepReport,
    /// Whether iterative solves stop at the forcing term ([`forcing`]).
    pub(crate) inexact: bool,
    /// The stiffness blocks the last Newton step was solved with: once a
    /// step needed compressed springs clamped, its later iterations start
    /// there instead of assembling and factoring the exact blocks first.
    pub(crate) hessian: CompressedSprings,
    /// The quasi-Newton state, when the directions are L-BFGS's instead of
    /// Newton's.
    pub(crate) quasi: Option<&'a mut QuasiNewton>,
    /// Whether `b` holds `−∇Φ`, without the contact terms, at the point
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

    /// `Φ(v)`, its contact terms included (infinite where a gap is not
    /// positive), and its rounding level. For the quasi-Newton step, the
    /// same pass over the springs leaves `−∇Φ(v)` without the contact terms
    /// in `b` ([`Newton::evaluated_residual`]).
    pub(crate) fn potential(&mut self, v: &[Vec3]) -> Potential {
        self.positions(v);
        let (system, pattern, beta_h) = (self.system, self.topology.pattern(), self.beta_h);
        self.evaluated_residual = self.quasi.is_some();
        let mut potential = if self.evaluated_residual {
            let point = Point {
                x: self.x,
                v,
                v_tilde: self.v_tilde,
                beta_h,
            };
            self.assembler.evaluate(system, pattern, point, self.b)
        } else {
            self.assembler
                .potential(system, pattern, self.x, v, self.v_tilde, beta_h)
        };
        if let Some(contact) = self.contact.as_deref_mut() {
            let terms = contact.value(system, self.x, v, beta_h);
            potential.value += terms;
            potential.rounding += f64::EPSILON * terms.abs();
        }
        potential
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
    fn decrement(&self, slope: f64, v: &[Vec3], delta: &[Vec3], v0: &[Vec3]) -> f64 {
        if slope == 0.0 {
            return 0.0;
        }
        let next = v.iter().zip(delta).map(|(v, d)| v + d);
        slope.abs().sqrt() / velocity_scale(self.system, next, v0, self.beta_h)
    }

    /// Newton's step `δ` at `v`: assembles `(M + βh C + β²h² K) δ = −∇Φ(v)`
    /// with the exact stiffness blocks of springs and volume elements
    /// (unless an earlier iteration of the same step needed the clamp,
    /// [`Newton::hessian`]), or — where that system is not
    /// positive definite or its solution does not descend, and the
    /// integrator clamps compressed springs — with compressed springs
    /// clamped and the elements' Hessians projected, adds the contact
    /// terms' gradients and projected Hessians,
    /// and solves it in the free directions. Returns the slope `∇Φ·δ`.
    ///
    /// # Errors
    /// Assembly and solver errors.
    fn direction(&mut self, v: &[Vec3], delta: &mut [Vec3]) -> Result<f64, StepError> {
        let (system, x_tilde, v_tilde, beta_h) =
            (self.system, self.x_tilde, self.v_tilde, self.beta_h);
        let masses = system.masses();
        for_each_row2(self.x, self.inertia, |i, x, inertia| {
            *x = x_tilde[i] + beta_h * v[i];
            *inertia = -masses[i] * (v[i] - v_tilde[i]);
        });
        if let Some(quasi) = self.quasi.take() {
            let slope = self.quasi_direction(quasi, v, delta);
            self.quasi = Some(quasi);
            return slope;
        }
        let mut hessian = self.hessian;
        loop {
            let lin = Linearization {
                positions: self.x,
                velocities: v,
                displacement: None,
                inertia: self.inertia,
                beta_h,
                compressed: hessian,
                freeze_directions: false,
            };
            delta.fill(Vec3::zeros());
            let last = hessian == self.compressed;
            let solved = self
                .solve
                .assemble(self.assembler, self.topology, &lin, self.b)
                .and_then(|()| {
                    if let Some(contact) = self.contact.as_deref_mut() {
                        let a = self.topology.matrix_mut();
                        let assembled = a.extra_rows.len();
                        contact.add(system, self.x, v, beta_h, self.b, a);
                        self.topology.contacts_added(assembled);
                    }
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
    /// positions and inertia term [`Newton::direction`] filled: the
    /// residual `−∇Φ(v)` with the contact terms' gradients, without any
    /// matrix, then L-BFGS's two-loop recursion. Returns the slope `∇Φ·δ`.
    ///
    /// # Errors
    /// [`StepError::NonFiniteSystem`] for a residual that is not finite.
    fn quasi_direction(
        &mut self,
        quasi: &mut QuasiNewton,
        v: &[Vec3],
        delta: &mut [Vec3],
    ) -> Result<f64, StepError> {
        let (system, beta_h) = (self.system, self.beta_h);
        if !std::mem::take(&mut self.evaluated_residual) {
            let point = Point {
                x: self.x,
                v,
                v_tilde: self.v_tilde,
                beta_h,
            };
            let pattern = self.topology.pattern();
            self.assembler.evaluate(system, pattern, point, self.b);
        }
        check_finite(system, self.b, self.solve.time)?;
        if let Some(contact) = self.contact.as_deref_mut() {
            // The contact terms' Hessian blocks land in the matrix's extra
            // blocks: their diagonal ones give the stand-in on H₀ at the
            // step's first iterate, and are dropped.
            let a = self.topology.matrix_mut();
            contact.add(system, self.x, v, beta_h, self.b, a);
            if quasi.pending() {
                quasi.add_stand_in(system, &a.extra_rows, self.solve.time)?;
            }
            a.clear_extra();
        }
        self.report.linear_solves += 1;
        self.report.linear_solver = LinearSolver::Cholesky.name();
        Ok(quasi.direction(system, self.b, v, delta))
    }

    /// Minimises `Φ` from the iterate in `it.v` (where `Φ` is `start`) in at
    /// most `max_iterations` linear solves, `v0` being the step's initial
    /// velocity. The iteration stops when the relative Newton decrement
    /// ([`Newton::decrement`]) is at most `tolerance`, or when a full Newton
    /// step would lower `Φ` by no more than the rounding of `Φ` itself,
    /// `½|∇Φ·δ| ≤ rounding(Φ)` (stiff springs, whose forces carry the
    /// rounding of their ends' coordinates times `k`, reach that floor
    /// first).
    ///
    /// Every iterate is accepted through the Armijo condition
    /// `Φ(v + αδ) ≤ Φ(v) + 10⁻⁴ α ∇Φ·δ`:
    ///
    /// - a full step that meets it is extended where the model is stiffer
    ///   than `Φ` and the step undershoots (a clamped compressed spring,
    ///   the quartic energy of a flat sheet bending, the quasi-Newton
    ///   step's initial Hessian `kI` per spring, stiff across a spring
    ///   where `Φ` is soft), if the quadratic through `Φ(v)`, the slope and
    ///   `Φ(v + δ)` has its minimum `α*` beyond 1.5 or is not convex.
    ///   Newton's step doubles `α` (up to 64) while `Φ` keeps falling.
    ///   L-BFGS's undershoots at almost every iteration, by far more (on
    ///   the 50 × 50 cloth of the `work_precision` bench, `α*` has a median
    ///   of 3.5 and reaches 9): it tries `α = min(α*, 64)` once and keeps
    ///   it if `Φ` is lower there, one evaluation where doubling took
    ///   three, and doubles below `α*` only if not. Collision detection
    ///   checks each extension's motion from the last point only, which
    ///   keeps its cost, growing with the motion, to the step that is
    ///   tried;
    /// - a full step that fails it gets the watchdog: one more Newton step
    ///   from the full step's end, accepted if that point meets the Armijo
    ///   condition relative to the iterate (Chamberlain, Powell, Lemaréchal &
    ///   Pedersen, *The watchdog technique*, 1982; Nocedal & Wright,
    ///   *Numerical Optimization*, §15.6). A stiff spring rotated along a
    ///   straight line is stretched by `δ²/2L`, which the second step
    ///   removes, so a rotating stiff body is not held to the steps its
    ///   stretch allows;
    /// - otherwise the step backtracks by halves. A line search that finds
    ///   no decrease down to `α = 10⁻⁶` ends the iteration unconverged.
    ///
    /// With `inexact`, an iterative linear solver stops each Newton step at
    /// the relative residual `η = min(0.1, ½ λ_rel)` of the last relative
    /// decrement ([`forcing`]) when that is looser than its own tolerance.
    /// CG started from zero gives a descent direction at every iteration,
    /// so a loose step still descends, and the stopping rule is checked on
    /// steps solved to a fraction of the decrement itself.
    ///
    /// # Errors
    /// Assembly and solver errors.
    pub(crate) fn minimize(
        &mut self,
        it: &mut Iterates<'_>,
        v0: &[Vec3],
        start: Potential,
        max_iterations: usize,
        tolerance: f64,
    ) -> Result<Outcome, StepError> {
        let mut current = start;
        // Φ before the last accepted iterate (for the quasi-Newton floor).
        let mut previous = f64::INFINITY;
        let mut outcome = Outcome {
            converged: false,
            iterations: 0,
            residual: f64::INFINITY,
        };
        while outcome.iterations < max_iterations {
            if self.inexact {
                self.solve.forcing = forcing(outcome.residual);
            }
            let slope = self.direction(it.v, it.delta)?;
            outcome.iterations += 1;
            outcome.residual = self.decrement(slope, it.v, it.delta, v0);
            // The longest fraction of δ collision detection allows.
            let limit = self.limit(it.v, it.delta, 1.0);
            // A quasi-Newton step's model overestimates the curvature of
            // soft modes and so its predicted decrease; it is at the floor
            // only once the last iterate lowered Φ by no more than rounding.
            let floor = 0.5 * slope.abs() <= current.rounding
                && (self.quasi.is_none() || previous - current.value <= current.rounding);
            if limit >= 1.0 && (outcome.residual <= tolerance || floor) {
                add(it.v, it.delta);
                outcome.converged = true;
                break;
            }
            previous = current.value;
            let sufficient = |value: Potential, alpha: f64| {
                value.value <= current.value + ARMIJO * alpha * slope
            };
            if limit >= 1.0 {
                combine(it.trial, it.v, 1.0, it.delta);
                let full = self.potential(it.trial);
                if sufficient(full, 1.0) {
                    current = self.extend(it, current.value, slope, full);
                    std::mem::swap(it.v, it.trial);
                    continue;
                }
                if outcome.iterations < max_iterations {
                    self.direction(it.trial, it.ahead)?;
                    outcome.iterations += 1;
                    if self.limit(it.trial, it.ahead, 1.0) >= 1.0 {
                        combine(it.look, it.trial, 1.0, it.ahead);
                        let ahead = self.potential(it.look);
                        if sufficient(ahead, 1.0) {
                            current = ahead;
                            std::mem::swap(it.v, it.look);
                            continue;
                        }
                    }
                    // The contact candidates are the look-ahead's: check
                    // the step's own motion again for the backtracking.
                    self.limit(it.v, it.delta, 1.0);
                }
            }
            let mut alpha = if limit >= 1.0 { 0.5 } else { limit };
            loop {
                combine(it.trial, it.v, alpha, it.delta);
                let value = self.potential(it.trial);
                if sufficient(value, alpha) {
                    current = value;
                    break;
                }
                alpha *= 0.5;
                if alpha < MIN_STEP {
                    return Ok(outcome);
                }
            }
            std::mem::swap(it.v, it.trial);
        }
        Ok(outcome)
    }

    /// Extends an accepted full step `it.trial = v + δ`, where `Φ` fell
    /// from `start` (with slope `∇Φ·δ`) to `full`, as [`Newton::minimize`]
    /// describes: if the minimum `α*` of the quadratic model lies beyond
    /// 1.5 (or the model is not convex), Newton's step by doublings up to
    /// 64, the quasi-Newton step to `α*` (at most 64) and, if `Φ` is not
    /// lower there, by doublings below it. Leaves the lowest point tried in
    /// `it.trial` and returns `Φ` there.
    fn extend(
        &mut self,
        it: &mut Iterates<'_>,
        start: f64,
        slope: f64,
        full: Potential,
    ) -> Potential {
        let mut current = full;
        let minimum = model_minimum(start, slope, full.value).map(|m| m.min(MAX_EXTRAPOLATION));
        let mut doubling_below = match minimum {
            Some(alpha) if alpha <= 1.5 => return current,
            Some(alpha) if self.quasi.is_some() => alpha,
            _ => f64::INFINITY,
        };
        let reach = doubling_below - 1.0;
        if doubling_below.is_finite() && self.limit(it.trial, it.delta, reach) >= reach {
            combine(it.look, it.v, doubling_below, it.delta);
            let further = self.potential(it.look);
            if further.value < current.value {
                std::mem::swap(it.trial, it.look);
                return further;
            }
            self.evaluated_residual = false;
        }
        // Each doubling checks the motion from the last point, `α/2 δ`.
        let mut alpha = 2.0;
        doubling_below = doubling_below.min(2.0 * MAX_EXTRAPOLATION);
        while alpha < doubling_below && self.limit(it.trial, it.delta, 0.5 * alpha) >= 0.5 * alpha {
            combine(it.look, it.v, alpha, it.delta);
            let further = self.potential(it.look);
            if further.value >= current.value {
                self.evaluated_residual = false;
                break;
            }
            current = further;
            std::mem::swap(it.trial, it.look);
            alpha *= 2.0;
        }
        current
    }

    /// The longest multiple `α ≤ longest` of the step `δ` from `v` that
    /// collision detection allows: `longest` without contact terms,
    /// otherwise `longest · τ` with `τ` the fraction of the motion
    /// `βh longest δ` that keeps every pair at a tenth of its gap.
    fn limit(&mut self, v: &[Vec3], delta: &[Vec3], longest: f64) -> f64 {
        if self.contact.is_none() {
            return longest;
        }
        self.positions(v);
        let scale = self.beta_h * longest;
        for_each_row(self.motion, |i, m| *m = scale * delta[i]);
        let contact = self.contact.as_deref_mut().expect("checked above");
        longest * contact.limit(self.system, self.x, self.motion)
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

/// Where the quadratic through `Φ(0) = start`, its slope `∇Φ·δ` and
/// `Φ(1) = end` along a step has its minimum, `−slope / 2(end − start −
/// slope)`; `None` where that quadratic is not convex.
fn model_minimum(start: f64, slope: f64, end: f64) -> Option<f64> {
    let curvature = end - start - slope;
    (curvature > 0.0).then(|| -slope / (2.0 * curvature))
}

/// `v += δ`.
fn add(v: &mut [Vec3], delta: &[Vec3]) {
    for_each_row(v, |i, v| *v += delta[i]);
}

/// `out = v + α δ`.
fn combine(out: &mut [Vec3], v: &[Vec3], alpha: f64, delta: &[Vec3]) {
    for_each_row(out, |i, o| *o = v[i] + alpha * delta[i]);
}
