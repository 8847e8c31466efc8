//! [`IntegratorSpec`]: which [`Method`] a scene runs, with its parameters.

use hooke_core::{Integrator, ParameterError};
use hooke_explicit::{DormandPrince, ExplicitMethod};
use hooke_implicit::{FastMassSpring, Implicit, ImplicitSettings, Scheme};

use crate::Method;

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
    /// Backward Euler or BDF2 (the settings' scheme), with every setting
    /// of the implicit step.
    Implicit(ImplicitSettings),
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
            Self::Implicit(settings) => match settings.scheme {
                Scheme::BackwardEuler => Method::BackwardEuler,
                Scheme::Bdf2 => Method::Bdf2,
            },
            Self::FastMassSpring { .. } => Method::FastMassSpring,
        }
    }

    /// `scheme` with the default [`ImplicitSettings`]: the automatic
    /// solver choice and converged Newton steps.
    #[must_use]
    pub fn implicit(scheme: Scheme) -> Self {
        Self::Implicit(ImplicitSettings {
            scheme,
            ..ImplicitSettings::default()
        })
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
            Self::Implicit(settings) => Box::new(Implicit::with_settings(settings)?),
            Self::FastMassSpring { iterations } => Box::new(FastMassSpring::new(iterations)?),
        })
    }
}
