//! [`Settings`]: the parameters the lab gives the [`Method`]s that have
//! any.

use hooke_core::{Integrator, ParameterError};
use hooke_explicit::DormandPrince;
use hooke_implicit::ImplicitSettings;
use hooke_scenes::{IntegratorSpec, Method};

/// The parameters the lab gives the methods that have any: the implicit
/// methods' settings, Dormand–Prince's tolerance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// The settings of backward Euler and BDF2, each measured with its own
    /// scheme ([`ImplicitSettings::scheme`] is the method's, whatever this
    /// says).
    pub implicit: ImplicitSettings,
    /// Dormand–Prince's relative and absolute tolerance.
    pub tolerance: f64,
}

impl Default for Settings {
    /// The library's implicit settings ([`ImplicitSettings::default`]: the
    /// automatic solver choice, which factorizes every system below
    /// [`AutoSettings::trial_particles`](hooke_implicit::AutoSettings::trial_particles)
    /// and measures the rest as a run would) and Dormand–Prince's default
    /// relative tolerance (10⁻⁶) as both of its tolerances.
    fn default() -> Self {
        Self {
            implicit: ImplicitSettings::default(),
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
    /// [`ParameterError`] for a tolerance or implicit setting out of range.
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
            IntegratorSpec::Implicit(ImplicitSettings { scheme, .. }) => {
                IntegratorSpec::Implicit(ImplicitSettings {
                    scheme,
                    ..self.implicit
                })
            }
            fixed @ (IntegratorSpec::Explicit(_) | IntegratorSpec::FastMassSpring { .. }) => fixed,
        };
        spec.build()
    }

    /// The defaults, with the scene's own implicit settings or adaptive
    /// tolerance where it names an implicit or adaptive integrator.
    #[must_use]
    pub fn from_scene(spec: &IntegratorSpec) -> Self {
        let defaults = Self::default();
        match *spec {
            IntegratorSpec::Explicit(_) | IntegratorSpec::FastMassSpring { .. } => defaults,
            IntegratorSpec::Adaptive { rtol, .. } => Self {
                tolerance: rtol,
                ..defaults
            },
            IntegratorSpec::Implicit(implicit) => Self {
                implicit,
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
