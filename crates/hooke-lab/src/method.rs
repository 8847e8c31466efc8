//! [`Method`]: the integrators the lab compares, with what theory says
//! about each.

use std::f64::consts::SQRT_2;
use std::fmt;

use hooke_core::{Integrator, ParameterError};
use hooke_implicit::{Implicit, Scheme};
use hooke_scenes::{ExplicitMethod, IntegratorSpec, SolverSpec};

/// An integrator the lab can run: one of the ten fixed-step explicit
/// methods, adaptive Dormand–Prince, backward Euler or BDF2.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// A fixed-step explicit method.
    Explicit(ExplicitMethod),
    /// Dormand–Prince 5(4) with error control (its step is chosen for a
    /// tolerance; the lab's `dt` is how far each call advances).
    DormandPrince,
    /// Backward Euler on the assembled system.
    BackwardEuler,
    /// Second-order backward differentiation on the assembled system.
    Bdf2,
}

/// How a method behaves on the undamped oscillator `x'' = −ω² x` at
/// `θ = hω`: where its amplification factor has modulus at most one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum OscillatorStability {
    /// The amplitude grows at every step size (the factor's modulus exceeds
    /// one for every `θ > 0`): explicit Euler (`|R|² = 1 + θ²`), midpoint
    /// and Heun (`|R|² = 1 + θ⁴/4`), Gear's predictor–corrector.
    GainsEnergy,
    /// Bounded motion for `θ` up to the limit, geometric growth above it.
    BoundedUpTo(f64),
    /// Bounded (and damped) at every step size: the implicit methods.
    Unconditional,
}

impl Method {
    /// Every method, explicit ones in the order of the `hooke-explicit`
    /// table, then Dormand–Prince, backward Euler and BDF2.
    pub const ALL: [Self; 13] = [
        Self::Explicit(ExplicitMethod::ExplicitEuler),
        Self::Explicit(ExplicitMethod::SymplecticEuler),
        Self::Explicit(ExplicitMethod::Leapfrog),
        Self::Explicit(ExplicitMethod::VelocityVerlet),
        Self::Explicit(ExplicitMethod::PositionVerlet),
        Self::Explicit(ExplicitMethod::Midpoint),
        Self::Explicit(ExplicitMethod::Heun),
        Self::Explicit(ExplicitMethod::Rk4),
        Self::Explicit(ExplicitMethod::Beeman),
        Self::Explicit(ExplicitMethod::Gear),
        Self::DormandPrince,
        Self::BackwardEuler,
        Self::Bdf2,
    ];

    /// The name reports and the command line use: the integrator's
    /// [`Integrator::name`], e.g. `"rk4"`, `"dormand-prince"`, `"backward-euler"`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Explicit(method) => method.name(),
            Self::DormandPrince => hooke_explicit::DormandPrince::NAME,
            Self::BackwardEuler => "backward-euler",
            Self::Bdf2 => "bdf2",
        }
    }

    /// The method called `name` (see [`Method::name`]).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }

    /// Whether the method takes steps of exactly the `dt` it is given.
    #[must_use]
    pub fn is_fixed_step(self) -> bool {
        self != Self::DormandPrince
    }

    /// Whether the method solves a linear system per step.
    #[must_use]
    pub fn is_implicit(self) -> bool {
        matches!(self, Self::BackwardEuler | Self::Bdf2)
    }

    /// The global order of accuracy of the positions.
    #[must_use]
    pub fn expected_order(self) -> f64 {
        match self {
            Self::Explicit(ExplicitMethod::ExplicitEuler | ExplicitMethod::SymplecticEuler)
            | Self::BackwardEuler => 1.0,
            Self::Explicit(
                ExplicitMethod::Leapfrog
                | ExplicitMethod::VelocityVerlet
                | ExplicitMethod::PositionVerlet
                | ExplicitMethod::Midpoint
                | ExplicitMethod::Heun
                | ExplicitMethod::Beeman,
            )
            | Self::Bdf2 => 2.0,
            Self::Explicit(ExplicitMethod::Rk4 | ExplicitMethod::Gear) => 4.0,
            Self::DormandPrince => 5.0,
        }
    }

    /// The method's stability on the undamped oscillator (the stability
    /// interval of its amplification factor on the imaginary axis).
    /// Dormand–Prince adapts its step to its tolerance, so it is
    /// [`OscillatorStability::Unconditional`] in the sense that no `dt`
    /// given to it makes it blow up.
    #[must_use]
    pub fn oscillator_stability(self) -> OscillatorStability {
        match self {
            Self::Explicit(
                ExplicitMethod::ExplicitEuler
                | ExplicitMethod::Midpoint
                | ExplicitMethod::Heun
                | ExplicitMethod::Gear,
            ) => OscillatorStability::GainsEnergy,
            Self::Explicit(
                ExplicitMethod::SymplecticEuler
                | ExplicitMethod::Leapfrog
                | ExplicitMethod::VelocityVerlet
                | ExplicitMethod::PositionVerlet
                | ExplicitMethod::Beeman,
            ) => OscillatorStability::BoundedUpTo(2.0),
            Self::Explicit(ExplicitMethod::Rk4) => OscillatorStability::BoundedUpTo(2.0 * SQRT_2),
            Self::DormandPrince | Self::BackwardEuler | Self::Bdf2 => {
                OscillatorStability::Unconditional
            }
        }
    }

    /// A new integrator of this method with `settings`; `tolerance`
    /// overrides [`Settings::tolerance`] for Dormand–Prince and is ignored
    /// by the others.
    ///
    /// # Errors
    /// [`ParameterError`] for a tolerance or solver setting out of range.
    pub fn build(
        self,
        settings: &Settings,
        tolerance: Option<f64>,
    ) -> Result<Box<dyn Integrator + Send>, ParameterError> {
        let spec = match self {
            Self::Explicit(method) => IntegratorSpec::Explicit(method),
            Self::DormandPrince => {
                let tolerance = tolerance.unwrap_or(settings.tolerance);
                IntegratorSpec::Adaptive {
                    rtol: tolerance,
                    atol: tolerance,
                }
            }
            Self::BackwardEuler | Self::Bdf2 => IntegratorSpec::Implicit {
                scheme: if self == Self::Bdf2 {
                    Scheme::Bdf2
                } else {
                    Scheme::BackwardEuler
                },
                solver: settings.solver,
                linearized: settings.linearized,
                newton_iterations: settings.newton_iterations,
                newton_tolerance: settings.newton_tolerance,
            },
        };
        spec.build()
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The parameters the lab gives the methods that have any: the implicit
/// methods' solver and Newton iterations, Dormand–Prince's tolerance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// The implicit methods' linear solver.
    pub solver: SolverSpec,
    /// Baraff & Witkin's linearised implicit step instead of the converged
    /// one.
    pub linearized: bool,
    /// Cap on Newton iterations per implicit (sub)step.
    pub newton_iterations: usize,
    /// Relative Newton tolerance (see `hooke_implicit::Implicit`).
    pub newton_tolerance: f64,
    /// Dormand–Prince's relative and absolute tolerance.
    pub tolerance: f64,
}

impl Default for Settings {
    /// Sparse Cholesky with converged Newton steps (the integrator's default
    /// cap and tolerance) and a Dormand–Prince tolerance of 10⁻⁶.
    fn default() -> Self {
        Self {
            solver: SolverSpec::Cholesky,
            linearized: false,
            newton_iterations: Implicit::NEWTON_ITERATIONS,
            newton_tolerance: Implicit::NEWTON_TOLERANCE,
            tolerance: 1e-6,
        }
    }
}

impl Settings {
    /// The defaults, with the scene's own implicit or adaptive parameters
    /// where it names an implicit or adaptive integrator.
    #[must_use]
    pub fn from_scene(spec: &IntegratorSpec) -> Self {
        let defaults = Self::default();
        match *spec {
            IntegratorSpec::Explicit(_) => defaults,
            IntegratorSpec::Adaptive { rtol, .. } => Self {
                tolerance: rtol,
                ..defaults
            },
            IntegratorSpec::Implicit {
                solver,
                linearized,
                newton_iterations,
                newton_tolerance,
                ..
            } => Self {
                solver,
                linearized,
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
    fn names_round_trip_and_match_the_integrators() {
        let settings = Settings::default();
        for method in Method::ALL {
            assert_eq!(Method::from_name(method.name()), Some(method));
            let integrator = method.build(&settings, None).unwrap();
            assert_eq!(integrator.name(), method.name());
        }
        assert_eq!(Method::from_name("rk5"), None);
    }

    #[test]
    fn a_bad_tolerance_is_an_error_naming_it() {
        let error = Method::DormandPrince
            .build(&Settings::default(), Some(-1.0))
            .err()
            .unwrap();
        assert_eq!(error.parameter, "rtol");
    }
}
