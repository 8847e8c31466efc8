//! The minimisers of a step's `Φ` by name ([`Minimizer`], a setting with
//! its one table of names) and the one place that builds the
//! implementation each name stands for ([`Minimizer::minimize`]): Newton's
//! method, L-BFGS and the linearised step, each a
//! [`Descent`](crate::minimize::descent::Descent) that the shared line
//! search iterates.

use hooke_core::{CompressedSprings, Named, StepError, Vec3};

use crate::linear::cholesky::WeakSprings;
use crate::linear::solver::LinearSolver;
use crate::minimize::lbfgs::Lbfgs;
use crate::minimize::line_search::{Iterates, Outcome, minimize};
use crate::minimize::newton::{Linear, Newton};
use crate::minimize::objective::Objective;
use crate::minimize::quasi_newton::QuasiNewton;

/// How a step minimises its incremental potential `Φ` (see [`Implicit`](crate::Implicit)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Minimizer {
    /// Newton's method on the assembled 3×3-block system, the exact spring
    /// Hessian where it is positive definite (the default).
    #[default]
    Newton,
    /// L-BFGS with the last `history` curvature pairs and the constant
    /// initial Hessian `H₀ = M + βh (γI + C₀) + β²h² L` (the springs'
    /// stiffness and damping Laplacians; Liu, Bouaziz & Kavan 2017),
    /// prefactored: an iteration costs one gradient and three pairs of
    /// triangular solves, no matrix is assembled. By default a cloth's
    /// bending springs in a factored `H₀` are carried on the stiff springs
    /// between their ends, which halves the factor
    /// ([`WeakSprings::Routed`](crate::WeakSprings); `WeakSprings::Kept`
    /// keeps fast mass-spring's matrix). The integrator's
    /// [`LinearSolver`] says how `H₀⁻¹` is applied:
    /// [`Amg`](crate::LinearSolver::Amg) by one V-cycle of
    /// smoothed-aggregation multigrid on `H₀` instead of a factor (memory
    /// and time linear in the particles), [`Auto`](crate::LinearSolver::Auto)
    /// by the factor unless it holds more than 96 entries per particle
    /// (the bench cloth from about 200 × 200 particles), every other by
    /// the factor. The same line search, stopping rule,
    /// energy test and substeps as Newton's method; it converges linearly
    /// where Newton converges quadratically, so it wins at loose
    /// tolerances and on large meshes. It loses where contacts come and
    /// go within a step and stiff springs fold: on the default scene (a
    /// stiff cloth landing on a sphere and a floor, default tolerance) it
    /// took 112 iterations a step against Newton's 4.9, rejected 21
    /// substeps, and stepped in 2.2 times Newton's time (2026-11-28). The
    /// `quasi_newton` module gives the equations.
    QuasiNewton {
        /// The curvature pairs kept.
        history: usize,
        /// The newest pairs of a (sub)step that the next one starts its
        /// history with, at most `history` ([`Minimizer::CARRIED`] by
        /// default; 0 starts every step afresh, as Liu et al. do). Carried
        /// only while `H₀` stays the same (the same `βh`, no contact terms).
        carried: usize,
    },
    /// Baraff & Witkin's linearised step: Newton's method stopped after
    /// one iteration and taken as it comes — one linear solve, no line
    /// search, no rejection (with contact, one Newton step from the
    /// feasible start, bounded by collision detection).
    Linearized,
}

impl Minimizer {
    /// The default L-BFGS history (Liu et al.'s).
    pub const HISTORY: usize = 5;

    /// The curvature pairs a quasi-Newton (sub)step hands to the next by
    /// default: its newest. On the `work_precision` bench's cloth it halves
    /// the error of five iterations a step (0.26 → 0.12 m at 50 × 50
    /// particles, 0.25 → 0.11 m at 100 × 100) and leaves that of ten or
    /// more as it was; carrying all five helps five iterations as much but
    /// doubles the error of ten and thirty (`benches/README.md`).
    pub const CARRIED: usize = 1;

    /// L-BFGS with the default history and carried pairs.
    #[must_use]
    pub const fn quasi_newton() -> Self {
        Self::QuasiNewton {
            history: Self::HISTORY,
            carried: Self::CARRIED,
        }
    }
}

impl Named for Minimizer {
    /// `"newton"`, `"quasi-newton"` (with the default history and carried
    /// pairs) and `"linearized"`, as scene files (`step`) and reports spell
    /// them.
    const TABLE: &'static [(Self, &'static str)] = &[
        (Self::Newton, "newton"),
        (Self::quasi_newton(), "quasi-newton"),
        (Self::Linearized, "linearized"),
    ];
}

impl Minimizer {
    /// Whether the step assembles Newton's matrix: it then builds the
    /// linear solver's topology, and without barriers starts from the
    /// better of Baraff & Witkin's linearised step and `vₙ` ([`Start`]).
    /// The quasi-Newton step reads the springs' pattern only.
    pub(crate) const fn assembles(self) -> bool {
        match self {
            Self::Newton | Self::Linearized => true,
            Self::QuasiNewton { .. } => false,
        }
    }

    /// Whether each (sub)step iterates to the stopping rule and is held to
    /// it — rejected and retried in halves where it does not converge or
    /// gains energy, in substeps the conditioning allows — or is taken as
    /// it comes (the linearised step).
    pub(crate) const fn converges(self) -> bool {
        match self {
            Self::Newton | Self::QuasiNewton { .. } => true,
            Self::Linearized => false,
        }
    }

    /// The L-BFGS history and the pairs carried into the next step, for
    /// the step that keeps them.
    pub(crate) const fn history(self) -> Option<(usize, usize)> {
        match self {
            Self::QuasiNewton { history, carried } => Some((history, carried)),
            Self::Newton | Self::Linearized => None,
        }
    }

    /// Where weak springs go in the matrix the step factorizes unless the
    /// settings say: [`WeakSprings::Routed`] in the quasi-Newton step's
    /// `H₀` (a sparser factor that is still an initial Hessian at least the
    /// whole one), [`WeakSprings::Kept`] in Newton's factor (which then
    /// solves each Newton system directly).
    pub(crate) const fn weak_springs(self) -> WeakSprings {
        match self {
            Self::QuasiNewton { .. } => WeakSprings::Routed,
            Self::Newton | Self::Linearized => WeakSprings::Kept,
        }
    }

    /// Minimises the (sub)step's `phi` from its starting candidates
    /// (`start`, in `it.v` and `it.trial`) by the implementation this
    /// minimiser names, with the step's linear solver and what `kept`
    /// holds from earlier steps, following `rules`; `v0` is the step's
    /// initial velocity.
    ///
    /// The linearised step is Newton's method stopped after one iteration
    /// and taken as it comes (converged whatever its decrement). Without
    /// barriers that iteration is Baraff & Witkin's linearised solve,
    /// which the step took already as its first candidate ([`Start::Linearized`]);
    /// with barriers, one Newton step from the feasible start, bounded by
    /// collision detection.
    ///
    /// # Errors
    /// Assembly, factorization and solver errors.
    pub(crate) fn minimize(
        self,
        rules: Rules,
        kept: &mut Kept,
        phi: &mut Objective<'_>,
        linear: Linear<'_>,
        it: &mut Iterates,
        (v0, start): (&[Vec3], Start),
    ) -> Result<Outcome, StepError> {
        let second = start != Start::Current;
        let stopping = (rules.iterations, rules.tolerance);
        let newton = |linear| Newton {
            linear,
            inexact: rules.inexact,
            hessian: CompressedSprings::Exact,
        };
        match self {
            Self::Newton => minimize(&mut newton(linear), phi, it, (v0, second), stopping),
            Self::QuasiNewton { history, carried } => {
                let time = linear.solve.time;
                let inverse = (rules.solver.initial_hessian_inverse(), rules.weak_springs);
                let contact = phi.terms.has_barrier();
                let quasi = &mut kept.quasi;
                quasi.begin(
                    phi.system,
                    (phi.beta_h, contact),
                    (history, carried, inverse),
                    time,
                )?;
                let mut lbfgs = Lbfgs {
                    quasi,
                    b: linear.b,
                    report: linear.report,
                    time,
                    evaluated: false,
                };
                minimize(&mut lbfgs, phi, it, (v0, second), stopping)
            }
            Self::Linearized if start == Start::Linearized => Ok(Outcome {
                converged: true,
                iterations: 1,
                residual: 0.0,
            }),
            Self::Linearized => {
                let one = (1, f64::INFINITY);
                let outcome = minimize(&mut newton(linear), phi, it, (v0, second), one)?;
                Ok(Outcome {
                    converged: true,
                    ..outcome
                })
            }
        }
    }
}

/// What the integrator's settings say to every minimiser besides its name.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Rules {
    /// The cap on directions per (sub)step.
    pub(crate) iterations: usize,
    /// The relative tolerance on the Newton decrement.
    pub(crate) tolerance: f64,
    /// Whether Newton's iterative solves stop at the forcing term.
    pub(crate) inexact: bool,
    /// The linear solver, which says how the quasi-Newton step applies
    /// `H₀⁻¹` ([`LinearSolver::initial_hessian_inverse`]).
    pub(crate) solver: LinearSolver,
    /// Where weak springs go in a factored `H₀`.
    pub(crate) weak_springs: WeakSprings,
}

/// The starting candidates of a (sub)step's minimisation: the first in the
/// iterate, a second (where there is one) in the trial point; the
/// minimisation starts from the one lower in `Φ`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Start {
    /// With barriers: the feasible positions of the step's start, and the
    /// inertial predictor `vₙ + z` (`z` the pins' prescribed velocity
    /// changes) as far towards it as no pair comes closer than a tenth of
    /// its gap.
    Feasible,
    /// Baraff & Witkin's linearised step, one solve of the system
    /// linearised at the step's start, and `vₙ + z`.
    Linearized,
    /// `vₙ + z` alone: no barriers, and a minimiser that assembles no
    /// matrix.
    Current,
}

/// What the minimisers keep from one (sub)step to the next: the
/// quasi-Newton step's factored `H₀` and curvature pairs.
#[derive(Debug, Default)]
pub(crate) struct Kept {
    pub(crate) quasi: QuasiNewton,
}
