//! [`IntegratorSpec`]: which [`Method`] a scene runs, with its parameters.

use hooke_core::{Integrator, ParameterError};
use hooke_explicit::{DormandPrince, ExplicitMethod};
use hooke_implicit::{
    ErrorControl, FastMassSpring, Implicit, LinearSolver, Minimizer, Scheme, WeakSprings,
};

use crate::Method;

/// `names` quoted and listed for a message: `"a", "b" or "c"`.
pub(crate) fn quoted_list<'a>(names: impl IntoIterator<Item = &'a str>) -> String {
    let quoted: Vec<String> = names.into_iter().map(|n| format!("\"{n}\"")).collect();
    match quoted.split_last() {
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
        None => String::new(),
    }
}

/// Which integrator a scene runs, with its parameters: a [`Method`] of
/// the one list and what it needs to be built.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum IntegratorSpec {
    /// A fixed-step explicit method.
    Explicit(ExplicitMethod),
    /// Adaptive Dormand–Prince 5(4) with relative and absolute tolerances.
    Adaptive {
        /// Relative tolerance.
        rtol: f64,
        /// Absolute tolerance.
        atol: f64,
    },
    /// Backward Euler or BDF2.
    Implicit {
        /// The scheme.
        scheme: Scheme,
        /// The linear solver, with its settings.
        solver: LinearSolver,
        /// Where weak springs go in the matrix a step factorizes (`None`:
        /// each minimiser's default, see `Implicit::with_weak_springs`).
        weak_springs: Option<WeakSprings>,
        /// How each step's incremental potential is minimised: Newton's
        /// method, L-BFGS, or Baraff & Witkin's linearised step.
        minimizer: Minimizer,
        /// Cap on Newton iterations per (sub)step.
        newton_iterations: usize,
        /// Relative Newton tolerance `ε` (see `hooke_implicit::Implicit`).
        newton_tolerance: f64,
        /// Halvings a rejected step may take: its floor is `dt / 2^max_halvings`.
        max_halvings: u32,
        /// Whether a step accepted unconverged at the floor, or a linear
        /// solve stopped at its cap, is an error instead of a warning.
        strict: bool,
        /// Error-controlled variable substeps, or fixed ones (`None`).
        error_control: Option<ErrorControl>,
    },
    /// Liu et al.'s fast mass-spring method (`hooke_implicit::FastMassSpring`).
    FastMassSpring {
        /// Local/global iterations per step.
        iterations: usize,
    },
}

impl IntegratorSpec {
    /// `method` with the default parameters: Dormand–Prince at
    /// [`DormandPrince::RTOL`] and [`DormandPrince::ATOL`], backward Euler
    /// and BDF2 as [`IntegratorSpec::implicit`], the fast mass-spring
    /// method with [`FastMassSpring::ITERATIONS`] iterations.
    ///
    /// ```
    /// use hooke_scenes::{IntegratorSpec, Method};
    /// for method in Method::ALL {
    ///     assert_eq!(IntegratorSpec::new(method).method(), method);
    /// }
    /// ```
    #[must_use]
    pub fn new(method: Method) -> Self {
        match method {
            Method::Explicit(explicit) => Self::Explicit(explicit),
            Method::DormandPrince => Self::Adaptive {
                rtol: DormandPrince::RTOL,
                atol: DormandPrince::ATOL,
            },
            Method::BackwardEuler => Self::implicit(Scheme::BackwardEuler),
            Method::Bdf2 => Self::implicit(Scheme::Bdf2),
            Method::FastMassSpring => Self::FastMassSpring {
                iterations: FastMassSpring::ITERATIONS,
            },
        }
    }

    /// The method this spec builds.
    #[must_use]
    pub fn method(&self) -> Method {
        match *self {
            Self::Explicit(explicit) => Method::Explicit(explicit),
            Self::Adaptive { .. } => Method::DormandPrince,
            Self::Implicit {
                scheme: Scheme::BackwardEuler,
                ..
            } => Method::BackwardEuler,
            Self::Implicit {
                scheme: Scheme::Bdf2,
                ..
            } => Method::Bdf2,
            Self::FastMassSpring { .. } => Method::FastMassSpring,
        }
    }

    /// `scheme` with the automatic solver choice and converged Newton steps
    /// at the integrator's default cap and tolerance
    /// ([`Implicit::NEWTON_ITERATIONS`], [`Implicit::NEWTON_TOLERANCE`]),
    /// rejected steps halved at most [`Implicit::MAX_HALVINGS`] times,
    /// not strict, fixed substeps.
    #[must_use]
    pub fn implicit(scheme: Scheme) -> Self {
        Self::Implicit {
            scheme,
            solver: LinearSolver::Auto,
            weak_springs: None,
            minimizer: Minimizer::Newton,
            newton_iterations: Implicit::NEWTON_ITERATIONS,
            newton_tolerance: Implicit::NEWTON_TOLERANCE,
            max_halvings: Implicit::MAX_HALVINGS,
            strict: false,
            error_control: None,
        }
    }

    /// Backward Euler with the automatic solver choice and converged Newton
    /// steps at the integrator's default cap and tolerance: the default of
    /// scenes.
    #[must_use]
    pub fn backward_euler() -> Self {
        Self::implicit(Scheme::BackwardEuler)
    }

    /// A new integrator with these parameters.
    ///
    /// ```
    /// use hooke_scenes::IntegratorSpec;
    /// let integrator = IntegratorSpec::backward_euler().build()?;
    /// assert_eq!(integrator.name(), "backward-euler");
    /// # Ok::<(), hooke_core::ParameterError>(())
    /// ```
    ///
    /// # Errors
    /// [`ParameterError`] naming the parameter that is out of range.
    pub fn build(&self) -> Result<Box<dyn Integrator + Send>, ParameterError> {
        Ok(match *self {
            Self::Explicit(explicit) => explicit.build(),
            Self::Adaptive { rtol, atol } => Box::new(DormandPrince::new(rtol, atol)?),
            Self::Implicit {
                scheme,
                solver,
                weak_springs,
                minimizer,
                newton_iterations,
                newton_tolerance,
                max_halvings,
                strict,
                error_control,
            } => {
                let implicit = Implicit::new(scheme)
                    .with_solver(solver)
                    .with_weak_springs(weak_springs)
                    .with_newton(newton_iterations, newton_tolerance)?
                    .with_max_halvings(max_halvings)
                    .strict(strict);
                let implicit = match error_control {
                    Some(control) => implicit.with_error_control(control),
                    None => implicit,
                };
                Box::new(implicit.with_minimizer(minimizer))
            }
            Self::FastMassSpring { iterations } => Box::new(FastMassSpring::new(iterations)?),
        })
    }
}
