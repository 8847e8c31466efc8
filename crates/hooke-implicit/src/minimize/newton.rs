//! Newton's method on the incremental potential `Φ` of one implicit
//! (sub)step: its iteration state, `Φ` at a point, the decrement, and the
//! directions (Newton's, or L-BFGS's through the quasi-Newton state); the
//! `line_search` module iterates them. [`Implicit`](crate::Implicit)'s docs
//! give the equations.

use hooke_core::{CompressedSprings, StepError, StepReport, System, Vec3};

use crate::linear::matrix::DiagonalBlocks;
use crate::linear::solver::solve::Solve;
use crate::linear::solver::topology::Topology;
use crate::linear::vector::{dot, for_each_row, for_each_row2};
use crate::minimize::assembly::{Assembler, Potential};
use crate::minimize::contact::Contact;
use crate::minimize::linearization::Linearization;
use crate::minimize::quasi_newton::QuasiNewton;
use crate::minimize::residual::{Point, check_finite};

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
    pub(crate) fn decrement(&self, slope: f64, v: &[Vec3], delta: &[Vec3], v0: &[Vec3]) -> f64 {
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
    pub(crate) fn direction(&mut self, v: &[Vec3], delta: &mut [Vec3]) -> Result<f64, StepError> {
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
            // The contact terms' gradients join the residual. At the step's
            // first iterate their diagonal Hessian blocks give the stand-in
            // on H₀; later iterations keep no blocks.
            if quasi.pending() {
                let mut diagonal = DiagonalBlocks::default();
                contact.add(system, self.x, v, beta_h, self.b, &mut diagonal);
                quasi.add_stand_in(system, &diagonal.0, self.solve.time)?;
            } else {
                contact.add(system, self.x, v, beta_h, self.b, &mut ());
            }
        }
        self.report.linear_solves += 1;
        let slope = quasi.direction(system, self.b, v, delta);
        self.report.linear_solver = quasi.solver_name();
        Ok(slope)
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
