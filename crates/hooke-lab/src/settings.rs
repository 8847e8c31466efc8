//! [`Settings`]: the parameters the lab gives the [`Method`]s that have
//! any.

use hooke_core::{Integrator, ParameterError};
use hooke_explicit::DormandPrince;
use hooke_implicit::{Implicit, LinearSolver, Minimizer};
use hooke_scenes::{IntegratorSpec, Method};

/// The parameters the lab gives the methods that have any: the implicit
/// methods' solver and Newton iterations, Dormand–Prince's tolerance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// The implicit methods' linear solver, with its settings.
    pub solver: LinearSolver,
    /// How the implicit steps minimise their incremental potential.
    pub minimizer: Minimizer,
    /// Cap on Newton iterations per implicit (sub)step.
    pub newton_iterations: usize,
    /// Relative Newton tolerance (see `hooke_implicit::Implicit`).
    pub newton_tolerance: f64,
    /// Dormand–Prince's relative and absolute tolerance.
    pub tolerance: f64,
}

impl Default for Settings {
    /// Sparse Cholesky with converged Newton steps (the integrator's default
    /// cap and tolerance) and Dormand–Prince's default relative tolerance
    /// (10⁻⁶) as both of its tolerances.
    fn default() -> Self {
        Self {
            solver: LinearSolver::Cholesky,
            minimizer: Minimizer::Newton,
            newton_iterations: Implicit::NEWTON_ITERATIONS,
            newton_tolerance: Implicit::NEWTON_TOLERANCE,
            tolerance: DormandPrince::RTOL,
        }
    }
}

impl Settings {
    /// A new integrator of `method` with these settings; `tolerance`
    /// overrides [`Settings::tolerance`] for Dormand–Prince and is ignored
    /// by the others.
    ///
    /// # Errors
    /// [`ParameterError`] for a tolerance or solver setting out of range.
    pub fn build(
        &self,
        method: Method,
        tolerance: Option<f64>,
    ) -> Result<Box<dyn Integrator + Send>, ParameterError> {
        let spec = match IntegratorSpec::new(method) {
            IntegratorSpec::Adaptive { .. } => {
                let tolerance = tolerance.unwrap_or(self.tolerance);
                IntegratorSpec::Adaptive {
                    rtol: tolerance,
                    atol: tolerance,
                }
            }
            IntegratorSpec::Implicit {
                scheme,
                weak_springs,
                max_halvings,
                strict,
                error_control,
                ..
            } => IntegratorSpec::Implicit {
                scheme,
                solver: self.solver,
                weak_springs,
                minimizer: self.minimizer,
                newton_iterations: self.newton_iterations,
                newton_tolerance: self.newton_tolerance,
                max_halvings,
                strict,
                error_control,
            },
            fixed @ (IntegratorSpec::Explicit(_) | IntegratorSpec::FastMassSpring { .. }) => fixed,
        };
        spec.build()
    }

    /// The defaults, with the scene's own implicit or adaptive parameters
    /// where it names an implicit or adaptive integrator.
    #[must_use]
    pub fn from_scene(spec: &IntegratorSpec) -> Self {
        let defaults = Self::default();
        match *spec {
            IntegratorSpec::Explicit(_) | IntegratorSpec::FastMassSpring { .. } => defaults,
            IntegratorSpec::Adaptive { rtol, .. } => Self {
                tolerance: rtol,
                ..defaults
            },
            IntegratorSpec::Implicit {
                solver,
                minimizer,
                newton_iterations,
                newton_tolerance,
                ..
            } => Self {
                solver,
                minimizer,
                newton_iterations,
                newton_tolerance,
                ..defaults
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_method_builds_the_integrator_of_its_name() {
        let settings = Settings::default();
        for method in Method::ALL {
            let integrator = settings.build(method, None).unwrap();
            assert_eq!(integrator.name(), method.name());
            assert_eq!(Method::from_name(method.name()), Some(method));
        }
    }

    #[test]
    fn a_bad_tolerance_is_an_error_naming_it() {
        let error = Settings::default()
            .build(Method::DormandPrince, Some(-1.0))
            .err()
            .unwrap();
        assert_eq!(error.parameter, hooke_core::Parameter::Rtol);
    }
}
