//! [`IntegratorSpec`]: which [`Method`] a scene runs, with its parameters,
//! and the [`SolverSpec`] of the implicit ones.

use hooke_core::{Integrator, ParameterError};
use hooke_explicit::{DormandPrince, ExplicitMethod};
use hooke_implicit::{
    ErrorControl, FastMassSpring, Implicit, LinearSolver, Minimizer, PcgSettings, Scheme,
};

use crate::Method;

/// The linear solver of an implicit integrator.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SolverSpec {
    /// Filtered PCG to a relative residual `tolerance`, at most
    /// `max_iterations` iterations.
    Pcg {
        /// Relative residual to stop at.
        tolerance: f64,
        /// Iteration cap.
        max_iterations: usize,
    },
    /// Sparse Cholesky.
    Cholesky,
    /// Filtered PCG preconditioned by smoothed-aggregation multigrid, to a
    /// relative residual `tolerance`, at most `max_iterations` iterations.
    Amg {
        /// Relative residual to stop at.
        tolerance: f64,
        /// Iteration cap.
        max_iterations: usize,
    },
    /// Filtered PCG preconditioned by a lagged Cholesky factor, to a
    /// relative residual `tolerance`, at most `max_iterations` iterations.
    LaggedCholesky {
        /// Relative residual to stop at.
        tolerance: f64,
        /// Iteration cap.
        max_iterations: usize,
    },
    /// Chosen by measured cost ([`LinearSolver::Auto`]): sparse Cholesky
    /// below [`AutoSettings::trial_particles`](hooke_implicit::AutoSettings::trial_particles) particles; from there
    /// on the first solve times the factorization (unless its predicted
    /// factor is too large), multigrid PCG and block-Jacobi PCG on the
    /// step's matrix, and keeps the fastest, an iterative one only if it
    /// clearly beats the factorization. When the two come close, the next
    /// two steps run one each and the faster per second simulated serves
    /// the rest of the run. An iterative choice whose solve stops at its
    /// iteration cap where a factor fits falls back to the factorization.
    Auto,
}

impl SolverSpec {
    /// Every solver of the scene file's `solver` key, the iterative ones
    /// (see [`SolverSpec::is_iterative`]) with this relative residual
    /// `tolerance` and iteration cap: with [`SolverSpec::name`], the one
    /// table of the solvers' names that scene files, reports and the
    /// command line read.
    #[must_use]
    pub fn all(tolerance: f64, max_iterations: usize) -> [Self; 5] {
        [
            Self::Auto,
            Self::Cholesky,
            Self::Pcg {
                tolerance,
                max_iterations,
            },
            Self::Amg {
                tolerance,
                max_iterations,
            },
            Self::LaggedCholesky {
                tolerance,
                max_iterations,
            },
        ]
    }

    /// The solver's name, the `solver` key's value that reads as it:
    /// `"auto"`, `"cholesky"`, `"pcg"`, `"amg"` or `"lagged-cholesky"`.
    #[must_use]
    pub const fn name(&self) -> &'static str {
        match self {
            Self::Auto => "auto",
            Self::Cholesky => "cholesky",
            Self::Pcg { .. } => "pcg",
            Self::Amg { .. } => "amg",
            Self::LaggedCholesky { .. } => "lagged-cholesky",
        }
    }

    /// The solver called `name` (see [`SolverSpec::name`]), an iterative
    /// one with this `tolerance` and iteration cap.
    ///
    /// ```
    /// use hooke_scenes::SolverSpec;
    /// let amg = SolverSpec::from_name("amg", 1e-8, 50);
    /// assert_eq!(amg, Some(SolverSpec::Amg { tolerance: 1e-8, max_iterations: 50 }));
    /// assert_eq!(SolverSpec::from_name("multigrid", 1e-8, 50), None);
    /// ```
    #[must_use]
    pub fn from_name(name: &str, tolerance: f64, max_iterations: usize) -> Option<Self> {
        Self::all(tolerance, max_iterations)
            .into_iter()
            .find(|s| s.name() == name)
    }

    /// Every solver's name (see [`SolverSpec::all`]).
    #[must_use]
    pub fn names() -> [&'static str; 5] {
        let defaults = PcgSettings::default();
        Self::all(defaults.tolerance(), defaults.max_iterations()).map(|s| s.name())
    }

    /// The names of the iterative solvers (see [`SolverSpec::is_iterative`]).
    #[must_use]
    pub fn iterative_names() -> Vec<&'static str> {
        let defaults = PcgSettings::default();
        Self::all(defaults.tolerance(), defaults.max_iterations())
            .iter()
            .filter(|s| s.is_iterative())
            .map(Self::name)
            .collect()
    }

    /// The same solver, an iterative one (see [`SolverSpec::is_iterative`])
    /// with this relative residual `tolerance` and iteration cap; `auto`
    /// and `cholesky` take neither.
    ///
    /// ```
    /// use hooke_scenes::SolverSpec;
    /// let pcg = SolverSpec::Pcg { tolerance: 1e-6, max_iterations: 1000 };
    /// assert_eq!(pcg.with_pcg(1e-2, 50), SolverSpec::Pcg { tolerance: 1e-2, max_iterations: 50 });
    /// assert_eq!(SolverSpec::Cholesky.with_pcg(1e-2, 50), SolverSpec::Cholesky);
    /// ```
    #[must_use]
    pub const fn with_pcg(self, tolerance: f64, max_iterations: usize) -> Self {
        match self {
            Self::Pcg { .. } => Self::Pcg {
                tolerance,
                max_iterations,
            },
            Self::Amg { .. } => Self::Amg {
                tolerance,
                max_iterations,
            },
            Self::LaggedCholesky { .. } => Self::LaggedCholesky {
                tolerance,
                max_iterations,
            },
            direct @ (Self::Auto | Self::Cholesky) => direct,
        }
    }

    /// Whether the solver is a PCG iteration, which takes a relative
    /// residual `tolerance` and an iteration cap: `pcg`, `amg` and
    /// `lagged-cholesky`.
    #[must_use]
    pub const fn is_iterative(&self) -> bool {
        matches!(
            self,
            Self::Pcg { .. } | Self::Amg { .. } | Self::LaggedCholesky { .. }
        )
    }
}

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
        /// The linear solver.
        solver: SolverSpec,
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
            solver: SolverSpec::Auto,
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
                minimizer,
                newton_iterations,
                newton_tolerance,
                max_halvings,
                strict,
                error_control,
            } => {
                let solver = match solver {
                    SolverSpec::Pcg {
                        tolerance,
                        max_iterations,
                    } => LinearSolver::Pcg(PcgSettings::new(tolerance, max_iterations)?),
                    SolverSpec::Cholesky => LinearSolver::Cholesky,
                    SolverSpec::Amg {
                        tolerance,
                        max_iterations,
                    } => LinearSolver::Amg(PcgSettings::new(tolerance, max_iterations)?),
                    SolverSpec::LaggedCholesky {
                        tolerance,
                        max_iterations,
                    } => LinearSolver::LaggedCholesky(PcgSettings::new(tolerance, max_iterations)?),
                    SolverSpec::Auto => LinearSolver::Auto,
                };
                let implicit = Implicit::new(scheme)
                    .with_solver(solver)
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
