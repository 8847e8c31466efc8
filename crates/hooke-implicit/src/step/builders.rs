//! [`Implicit`]'s builders and accessors: each sets or reads fields of its
//! [`ImplicitSettings`].

use hooke_core::{CompressedSprings, ParameterError};

use crate::linear::cholesky::{Supernodes, WeakSprings};
use crate::linear::solver::{AmgRenewal, LinearSolver};
use crate::minimize::bounds::ContactLimit;
use crate::minimize::minimizer::Minimizer;
use crate::step::comparison::Comparison;
use crate::step::error_control::ErrorControl;
use crate::step::implicit::Implicit;
use crate::step::scheme::Scheme;
use crate::step::settings::ImplicitSettings;

impl Implicit {
    /// Uses `solver` for the linear systems.
    ///
    /// ```
    /// use hooke_implicit::{Implicit, LinearSolver};
    /// let integrator = Implicit::backward_euler().with_solver(LinearSolver::Cholesky);
    /// ```
    #[must_use]
    pub fn with_solver(mut self, solver: LinearSolver) -> Self {
        self.settings.solver = solver;
        self.rebuilt()
    }

    /// Whether an iterative linear solver (PCG, multigrid, lagged
    /// Cholesky) may stop a Newton step's solve at the forcing term
    /// `η = min(0.1, ½ λ_rel)` of the last relative Newton decrement `λ_rel`
    /// when that is looser than its own tolerance (the default, `true`: an
    /// inexact Newton iteration, Eisenstat & Walker 1996), or always solves
    /// to its own tolerance (`false`). The first, linearised solve of a step
    /// and direct solves are exact either way.
    ///
    /// ```
    /// let exact = hooke_implicit::Implicit::backward_euler().with_inexact_newton(false);
    /// ```
    #[must_use]
    pub fn with_inexact_newton(mut self, inexact: bool) -> Self {
        self.settings.inexact_newton = inexact;
        self
    }

    /// How much of its hierarchy [`LinearSolver::Amg`] renews from one
    /// solve to the next (default [`AmgRenewal::EverySolve`]).
    ///
    /// ```
    /// use hooke_implicit::{AmgRenewal, Implicit};
    /// let lazy = Implicit::backward_euler().with_amg_renewal(AmgRenewal::SmootherOnly);
    /// ```
    #[must_use]
    pub fn with_amg_renewal(mut self, renewal: AmgRenewal) -> Self {
        self.settings.amg_renewal = renewal;
        self.rebuilt()
    }

    /// Where weak springs go in the matrix a step factorizes: in Newton's
    /// sparse Cholesky factorization ([`LinearSolver::Cholesky`], or
    /// [`LinearSolver::Auto`]'s choice of it) by default
    /// [`WeakSprings::Kept`], while [`WeakSprings::Routed`] carries them on
    /// their paths in a sparser factor that preconditions CG; in the
    /// quasi-Newton step's initial Hessian `H₀`, where it is factored, by
    /// default [`WeakSprings::Routed`], a sparser `H₀` at least the whole
    /// one (0.5–0.9 of the time a step at the same tolerance on the bench
    /// cloth, `benches/README.md`), while [`WeakSprings::Kept`] is the fast
    /// mass-spring matrix itself; multigrid on `H₀` keeps every spring.
    /// `None` keeps each step's default.
    ///
    /// ```
    /// use hooke_implicit::{Implicit, WeakSprings};
    /// let routed = Implicit::backward_euler().with_weak_springs(WeakSprings::Routed);
    /// let by_step = Implicit::backward_euler().with_weak_springs(None);
    /// ```
    #[must_use]
    pub fn with_weak_springs(mut self, weak: impl Into<Option<WeakSprings>>) -> Self {
        self.settings.weak_springs = weak.into();
        self.rebuilt()
    }

    /// Which of faer's numeric factorizations a sparse Cholesky factor of
    /// the step's matrix runs: by default [`Supernodes::Blocks`], the
    /// supernodal one wherever the factor averages more than 10 flops per
    /// entry; [`Supernodes::Faer`] is faer's own rule (40), kept to measure
    /// against. The factor, and so every step, is the same either way up
    /// to rounding.
    ///
    /// ```
    /// use hooke_implicit::{Implicit, Supernodes};
    /// let faer_rule = Implicit::backward_euler().with_supernodes(Supernodes::Faer);
    /// ```
    #[must_use]
    pub fn with_supernodes(mut self, supernodes: Supernodes) -> Self {
        self.settings.supernodes = supernodes;
        self.rebuilt()
    }

    /// How contact bounds each iterate's motion: by default
    /// [`ContactLimit::Global`], the whole step as far as the first pair to
    /// touch allows; [`ContactLimit::Particles`] moves each particle as far
    /// as its own contacts allow.
    ///
    /// ```
    /// use hooke_implicit::{ContactLimit, Implicit};
    /// let per_particle = Implicit::backward_euler().with_contact_limit(ContactLimit::Particles);
    /// ```
    #[must_use]
    pub fn with_contact_limit(mut self, limit: ContactLimit) -> Self {
        self.settings.contact_limit = limit;
        self.rebuilt()
    }

    /// Takes up to `max_iterations` Newton solves per (sub)step, stopping
    /// once the relative Newton decrement is at most `tolerance` (see the
    /// type's docs); a (sub)step that does not converge within the cap is
    /// rejected and retried in halves.
    ///
    /// ```
    /// let integrator = hooke_implicit::Implicit::backward_euler().with_newton(8, 1e-6)?;
    /// # Ok::<(), hooke_core::ParameterError>(())
    /// ```
    ///
    /// # Errors
    /// [`ParameterError`] for zero iterations or a tolerance that is not
    /// positive and finite ([`ImplicitSettings::validate`]).
    pub fn with_newton(
        mut self,
        max_iterations: usize,
        tolerance: f64,
    ) -> Result<Self, ParameterError> {
        let settings = ImplicitSettings {
            newton_iterations: max_iterations,
            newton_tolerance: tolerance,
            ..self.settings
        };
        settings.validate()?;
        self.settings = settings;
        Ok(self)
    }

    /// Takes Baraff & Witkin's linearised step (one solve, no line search,
    /// no rejection) instead of the converged one; see the type's docs for
    /// what it risks.
    ///
    /// ```
    /// let integrator = hooke_implicit::Implicit::backward_euler().linearized();
    /// ```
    #[must_use]
    pub fn linearized(self) -> Self {
        self.with_minimizer(Minimizer::Linearized)
    }

    /// Whether the step is the linearised one.
    #[must_use]
    pub fn is_linearized(&self) -> bool {
        self.settings.minimizer == Minimizer::Linearized
    }

    /// Minimises each step's `Φ` with `minimizer` (default
    /// [`Minimizer::Newton`]); the iteration cap and tolerance of
    /// [`Implicit::with_newton`] apply to each.
    ///
    /// ```
    /// use hooke_implicit::{Implicit, Minimizer};
    /// let lbfgs = Implicit::backward_euler().with_minimizer(Minimizer::quasi_newton());
    /// ```
    #[must_use]
    pub fn with_minimizer(mut self, minimizer: Minimizer) -> Self {
        self.settings.minimizer = minimizer;
        self.rebuilt()
    }

    /// Drops what the integrator built for its former settings — the
    /// topology (matrix, filters, factor or hierarchy) and the solver
    /// comparison — so that the next step builds them for the new ones.
    fn rebuilt(mut self) -> Self {
        self.topology = None;
        self.comparison = Comparison::default();
        self
    }

    /// How each step's `Φ` is minimised.
    #[must_use]
    pub fn minimizer(&self) -> Minimizer {
        self.settings.minimizer
    }

    /// Lets a rejected step be cut in half at most `halvings` times (the
    /// floor is `h / 2^halvings`); 0 accepts every step as it comes.
    ///
    /// ```
    /// let integrator = hooke_implicit::Implicit::backward_euler().with_max_halvings(4);
    /// ```
    #[must_use]
    pub fn with_max_halvings(mut self, halvings: u32) -> Self {
        self.settings.max_halvings = halvings;
        self
    }

    /// In strict mode a linear solve that stops at its iteration cap, or a
    /// step accepted at the substep floor without converging, fails the step
    /// with [`StepError::NoConvergence`](hooke_core::StepError::NoConvergence) naming the time and the residual;
    /// otherwise (the default) the approximate solution is used and counted
    /// in [`StepReport::unconverged_solves`](hooke_core::StepReport::unconverged_solves) and
    /// [`StepReport::unconverged_steps`](hooke_core::StepReport::unconverged_steps).
    #[must_use]
    pub fn strict(mut self, strict: bool) -> Self {
        self.settings.strict = strict;
        self
    }

    /// How compressed springs' stiffness blocks are treated (clamped by
    /// default, which keeps the matrix positive definite).
    #[must_use]
    pub fn with_compressed_springs(mut self, compressed: CompressedSprings) -> Self {
        self.settings.compressed = compressed;
        self
    }

    /// Chooses the substeps by their estimated local error (see
    /// [`ErrorControl`] and the [`error_control`](crate::step::error_control)
    /// module): each step the caller asks for is delivered whole, in as
    /// many substeps as the tolerances need.
    ///
    /// ```
    /// use hooke_implicit::{ErrorControl, Implicit};
    /// let integrator = Implicit::bdf2().with_error_control(ErrorControl::new(1e-3, 1e-6)?);
    /// # Ok::<(), hooke_core::ParameterError>(())
    /// ```
    #[must_use]
    pub fn with_error_control(mut self, control: ErrorControl) -> Self {
        self.settings.error_control = Some(control);
        self
    }

    /// The scheme.
    #[must_use]
    pub fn scheme(&self) -> Scheme {
        self.settings.scheme
    }

    /// The settings the integrator steps with.
    #[must_use]
    pub fn settings(&self) -> &ImplicitSettings {
        &self.settings
    }
}
