//! [`ImplicitSettings`]: everything that configures an implicit step, as
//! plain data, with each default written once; and (the [`keys`] module)
//! the keys scene files, reports and keyword arguments give the settings
//! by.

pub(crate) mod keys;
mod read;
#[cfg(test)]
mod tests;

use hooke_core::{CompressedSprings, Named, Parameter, ParameterError};

use crate::linear::cholesky::{Supernodes, WeakSprings};
use crate::linear::solver::{AmgRenewal, LinearSolver};
use crate::minimize::bounds::ContactLimit;
use crate::minimize::minimizer::Minimizer;
use crate::step::error_control::ErrorControl;
use crate::step::scheme::Scheme;

/// The settings of an [`Implicit`](crate::Implicit) integrator: the scheme, the minimiser
/// and its stopping rule, the linear solver and how it factors or renews
/// what it keeps, the substeps' limits and the error control. Plain data:
/// every field is public, [`ImplicitSettings::default`] gives the
/// library's defaults, and [`ImplicitSettings::validate`] checks the
/// ranges [`Implicit::with_settings`](crate::Implicit::with_settings) needs.
///
/// Scene files set these fields by the keys of their `[integrator]` table,
/// and `summary.json` reports them by the same keys
/// ([`ImplicitSettings::from_keys`], [`ImplicitSettings::keys`]); each
/// enum is written by the names of its one table
/// ([`Named`](hooke_core::Named)).
///
/// ```
/// use hooke_core::Integrator;
/// use hooke_implicit::{Implicit, ImplicitSettings, LinearSolver, Scheme};
/// let settings = ImplicitSettings {
///     scheme: Scheme::Bdf2,
///     solver: LinearSolver::Cholesky,
///     newton_tolerance: 1e-6,
///     ..ImplicitSettings::default()
/// };
/// let integrator = Implicit::with_settings(settings)?;
/// assert_eq!(integrator.name(), "bdf2");
/// assert_eq!(*integrator.settings(), settings);
/// # Ok::<(), hooke_core::ParameterError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImplicitSettings {
    /// The time discretisation ([`Scheme`]). Default
    /// [`Scheme::BackwardEuler`]; either.
    pub scheme: Scheme,
    /// How the linear system of each Newton step is solved, with the PCG
    /// iteration's tolerance and cap where it iterates ([`LinearSolver`];
    /// with [`Minimizer::QuasiNewton`], how `H₀⁻¹` is applied). Default
    /// [`LinearSolver::Auto`]; any (a [`PcgSettings`](crate::PcgSettings)
    /// is checked when it is made).
    pub solver: LinearSolver,
    /// How each step minimises its incremental potential `Φ`: Newton's
    /// method, L-BFGS with its history, or Baraff & Witkin's linearised
    /// step ([`Minimizer`]). Default [`Minimizer::Newton`]; any (a
    /// quasi-Newton step carries at most `history` pairs, whatever
    /// `carried` says).
    pub minimizer: Minimizer,
    /// The cap on linear solves (Newton or L-BFGS iterations) per
    /// (sub)step; a (sub)step that does not converge within it is rejected
    /// and retried in halves. Default [`ImplicitSettings::NEWTON_ITERATIONS`]
    /// (100); at least 1.
    pub newton_iterations: usize,
    /// The relative tolerance `ε` on the Newton decrement that stops the
    /// iteration (the stopping rule of [`Implicit`](crate::Implicit)). Default
    /// [`ImplicitSettings::NEWTON_TOLERANCE`] (`5·10⁻³`); positive and finite.
    pub newton_tolerance: f64,
    /// Whether an iterative linear solver may stop a Newton step's solve at
    /// the forcing term `η = min(0.1, ½ λ_rel)` of the last relative
    /// decrement where that is looser than its own tolerance (an inexact
    /// Newton iteration, Eisenstat & Walker 1996), or always solves to its
    /// own tolerance. The first, linearised solve of a step and direct
    /// solves are exact either way. Default `true`.
    pub inexact_newton: bool,
    /// How much of its hierarchy [`LinearSolver::Amg`] (or
    /// [`LinearSolver::Auto`]'s choice of it) renews from one solve to the
    /// next ([`AmgRenewal`]). Default [`AmgRenewal::EverySolve`]; either.
    pub amg_renewal: AmgRenewal,
    /// Where weak springs go in the matrix a step factorizes
    /// ([`WeakSprings`]): Newton's sparse Cholesky factor
    /// ([`LinearSolver::Cholesky`] or [`LinearSolver::Auto`]'s choice of
    /// it) or the quasi-Newton step's `H₀`. Default `None`: each
    /// minimiser's own ([`ImplicitSettings::weak_springs_used`]).
    pub weak_springs: Option<WeakSprings>,
    /// Which numeric factorization a sparse Cholesky factor of Newton's
    /// matrix runs ([`Supernodes`]); the factor is the same either way up
    /// to rounding. Default [`Supernodes::Blocks`]; either.
    pub supernodes: Supernodes,
    /// How often a rejected (sub)step may be cut in half: the floor is
    /// `h / 2^max_halvings`, where a step is accepted as it is and counted
    /// as unconverged. Default [`ImplicitSettings::MAX_HALVINGS`] (10); any, 0
    /// accepting every step as it comes.
    pub max_halvings: u32,
    /// Whether a linear solve stopped at its iteration cap, or a step
    /// accepted at the floor without converging, fails the step with
    /// [`StepError::NoConvergence`](hooke_core::StepError::NoConvergence)
    /// (`true`) or is used and counted in the
    /// [`StepReport`](hooke_core::StepReport) (`false`). Default `false`.
    pub strict: bool,
    /// How compressed springs' stiffness blocks enter the linearised solve
    /// and the Newton steps whose exact Hessian does not descend
    /// ([`CompressedSprings`]): clamped, which keeps the matrix positive
    /// definite, or exact. Default [`CompressedSprings::Clamped`]; either.
    pub compressed: CompressedSprings,
    /// Substeps chosen by their estimated local error within these
    /// tolerances ([`ErrorControl`], the
    /// [`error_control`](crate::step::error_control) module), or fixed
    /// substeps that shrink only on rejection (`None`). Default `None`; any
    /// (an [`ErrorControl`] is checked when it is made).
    pub error_control: Option<ErrorControl>,
    /// How contact bounds each iterate's motion in a system with barriers
    /// ([`ContactLimit`]): each particle as far as its own contacts allow,
    /// or the whole step as far as the first pair to touch allows. Default
    /// [`ContactLimit::Global`]; either.
    pub contact_limit: ContactLimit,
}

impl Default for ImplicitSettings {
    /// Backward Euler, the automatic solver choice, converged inexact
    /// Newton steps at [`ImplicitSettings::NEWTON_ITERATIONS`] and
    /// [`ImplicitSettings::NEWTON_TOLERANCE`], rejected steps halved at most
    /// [`ImplicitSettings::MAX_HALVINGS`] times, not strict, clamped compressed
    /// springs, fixed substeps, the global contact limit; every enum at its
    /// own default.
    fn default() -> Self {
        Self {
            scheme: Scheme::default(),
            solver: LinearSolver::default(),
            minimizer: Minimizer::default(),
            newton_iterations: Self::NEWTON_ITERATIONS,
            newton_tolerance: Self::NEWTON_TOLERANCE,
            inexact_newton: true,
            amg_renewal: AmgRenewal::default(),
            weak_springs: None,
            supernodes: Supernodes::default(),
            max_halvings: Self::MAX_HALVINGS,
            strict: false,
            compressed: CompressedSprings::default(),
            error_control: None,
            contact_limit: ContactLimit::default(),
        }
    }
}

impl ImplicitSettings {
    /// The default cap on Newton's linear solves per (sub)step
    /// ([`ImplicitSettings::newton_iterations`]). Stiff
    /// cloth swinging through large angles needs tens of them: at 10⁸ N/m
    /// and 0.1 s steps a 24×24 cloth takes 50–100.
    pub const NEWTON_ITERATIONS: usize = 100;
    /// The default relative Newton tolerance `ε`
    /// ([`ImplicitSettings::newton_tolerance`]; a relative error of the
    /// velocities in the mass norm; `Φ` then lies about `ε²` times twice the
    /// kinetic-energy scale above its minimum), chosen from the
    /// `work_precision` bench (`benches/README.md`): the loosest Newton
    /// tolerance whose error on its 50 × 50 cloth stays within 1 cm. There,
    /// 30 steps at 1/60 s end 4.5–6.9 mm from the converged run at
    /// `5·10⁻³` (3.1 iterations a step), 7–12 mm at `10⁻²`, 1.3 mm at `10⁻⁴`
    /// (6.6 iterations, twice the time). Tighter does not buy
    /// proportionally more: the cloth buckles, and a run converged to
    /// `10⁻⁶` lies up to 2.3 mm (50 × 50) and 12 mm (100 × 100) from one
    /// converged to `10⁻⁹` during the 30 steps, as far as `5·10⁻³` does
    /// on the larger cloth.
    /// On the default scene at 1/60 s a step then takes 14 iterations on
    /// average instead of 25. Every step still passes the energy test (a
    /// gain is absorbed only by moving the velocities less than `ε` of
    /// their scale), and the extreme-stiffness guarantees of
    /// `tests/implicit_robust.rs` hold at this default. Where buckling
    /// cloth makes the exact Hessian indefinite, Newton with clamped
    /// compressed springs converges only linearly, so much tighter
    /// tolerances cost many iterations: a step of a 100×100 cloth swinging
    /// from two pins took 118 Newton iterations to reach `10⁻⁶` against 8
    /// to reach `10⁻⁴`.
    pub const NEWTON_TOLERANCE: f64 = 5e-3;
    /// The default number of halvings a step may be cut by
    /// ([`ImplicitSettings::max_halvings`]).
    pub const MAX_HALVINGS: u32 = 10;

    /// Checks the fields whose range is narrower than their type's:
    /// [`ImplicitSettings::newton_iterations`] at least 1 and
    /// [`ImplicitSettings::newton_tolerance`] positive and finite. (The
    /// solver's PCG settings and the error control's tolerances are checked
    /// when they are made.)
    ///
    /// ```
    /// use hooke_core::Parameter;
    /// use hooke_implicit::ImplicitSettings;
    /// let settings = ImplicitSettings { newton_iterations: 0, ..ImplicitSettings::default() };
    /// let error = settings.validate().unwrap_err();
    /// assert_eq!(error.parameter, Parameter::NewtonIterations);
    /// assert_eq!(
    ///     error.to_string(),
    ///     "backward-euler: newton_iterations must be at least 1, got 0"
    /// );
    /// ```
    ///
    /// # Errors
    /// [`ParameterError`] naming the first field out of range, the
    /// integrator by its scheme's name.
    pub fn validate(&self) -> Result<(), ParameterError> {
        let integrator = self.scheme.name();
        if self.newton_iterations == 0 {
            return Err(ParameterError::new(
                integrator,
                Parameter::NewtonIterations,
                0.0,
                "at least 1",
            ));
        }
        if !(self.newton_tolerance.is_finite() && self.newton_tolerance > 0.0) {
            return Err(ParameterError::new(
                integrator,
                Parameter::NewtonTolerance,
                self.newton_tolerance,
                "positive and finite",
            ));
        }
        Ok(())
    }

    /// Where weak springs go in the matrix the step factorizes:
    /// [`ImplicitSettings::weak_springs`] if set, otherwise the
    /// minimiser's own — [`WeakSprings::Routed`] in the quasi-Newton
    /// step's `H₀` (a sparser factor that is still an initial Hessian at
    /// least the whole one), [`WeakSprings::Kept`] in Newton's factor (which
    /// then solves each Newton system directly).
    ///
    /// ```
    /// use hooke_implicit::{ImplicitSettings, Minimizer, WeakSprings};
    /// let newton = ImplicitSettings::default();
    /// assert_eq!(newton.weak_springs_used(), WeakSprings::Kept);
    /// let lbfgs = ImplicitSettings { minimizer: Minimizer::quasi_newton(), ..newton };
    /// assert_eq!(lbfgs.weak_springs_used(), WeakSprings::Routed);
    /// ```
    #[must_use]
    pub fn weak_springs_used(&self) -> WeakSprings {
        self.weak_springs
            .unwrap_or_else(|| self.minimizer.weak_springs())
    }
}
