//! [`Method`]: every integrator of hooke, by name — the one list that scene
//! files, the lab, the command line and the tests read — with what theory
//! says about each.

use std::f64::consts::SQRT_2;
use std::fmt;

use hooke_core::Named;
use hooke_explicit::{DormandPrince, ExplicitMethod};
use hooke_implicit::Scheme;
use serde::{Deserialize, Deserializer, Serialize, Serializer, de};

/// An integrator of hooke: one of the ten fixed-step explicit methods,
/// adaptive Dormand–Prince, backward Euler, BDF2 or Liu et al.'s fast
/// mass-spring method. Its parameters come
/// from an [`IntegratorSpec`](crate::IntegratorSpec), which builds it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// A fixed-step explicit method.
    Explicit(ExplicitMethod),
    /// Dormand–Prince 5(4) with error control (its step is chosen for a
    /// tolerance; a run's `dt` is how far each call advances).
    DormandPrince,
    /// Backward Euler on the assembled system.
    BackwardEuler,
    /// Second-order backward differentiation on the assembled system.
    Bdf2,
    /// Liu et al.'s fast mass-spring method: backward Euler by a fixed
    /// number of local/global iterations on a prefactored constant matrix.
    FastMassSpring,
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
    /// Every method: the explicit ones in the order of
    /// [`ExplicitMethod::ALL`], then Dormand–Prince, backward Euler, BDF2
    /// and the fast mass-spring method.
    pub const ALL: [Self; 14] = {
        let mut all = [Self::DormandPrince; 14];
        let mut i = 0;
        while i < ExplicitMethod::ALL.len() {
            all[i] = Self::Explicit(ExplicitMethod::ALL[i]);
            i += 1;
        }
        all[11] = Self::BackwardEuler;
        all[12] = Self::Bdf2;
        all[13] = Self::FastMassSpring;
        all
    };

    /// The name scene files, reports and the command line use, which the
    /// integrator's `name()` returns too, e.g. `"rk4"`, `"dormand-prince"`,
    /// `"backward-euler"` (the implicit schemes by their table,
    /// [`Scheme`]'s [`Named::TABLE`]).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Explicit(method) => method.name(),
            Self::DormandPrince => DormandPrince::NAME,
            Self::BackwardEuler => Scheme::BackwardEuler.name(),
            Self::Bdf2 => Scheme::Bdf2.name(),
            Self::FastMassSpring => hooke_implicit::FastMassSpring::NAME,
        }
    }

    /// The method called `name` (see [`Method::name`]).
    ///
    /// ```
    /// use hooke_scenes::Method;
    /// assert_eq!(Method::from_name("bdf2"), Some(Method::Bdf2));
    /// assert_eq!(Method::from_name("dopri5"), None);
    /// ```
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }

    /// Every name, quoted and separated by commas, for error messages.
    #[must_use]
    pub fn names() -> String {
        Self::ALL.map(|m| format!("\"{m}\"")).join(", ")
    }

    /// Whether the method takes steps of exactly the `dt` it is given.
    #[must_use]
    pub fn is_fixed_step(self) -> bool {
        self != Self::DormandPrince
    }

    /// Whether the method solves a linear system per step.
    #[must_use]
    pub fn is_implicit(self) -> bool {
        matches!(
            self,
            Self::BackwardEuler | Self::Bdf2 | Self::FastMassSpring
        )
    }

    /// The global order of accuracy of the positions.
    #[must_use]
    pub fn expected_order(self) -> f64 {
        use ExplicitMethod as E;
        match self {
            Self::Explicit(E::ExplicitEuler | E::SymplecticEuler)
            | Self::BackwardEuler
            | Self::FastMassSpring => 1.0,
            Self::Explicit(
                E::Leapfrog
                | E::VelocityVerlet
                | E::PositionVerlet
                | E::Midpoint
                | E::Heun
                | E::Beeman,
            )
            | Self::Bdf2 => 2.0,
            Self::Explicit(E::Rk4 | E::Gear) => 4.0,
            Self::DormandPrince => 5.0,
        }
    }

    /// Whether the method keeps colliding surfaces apart: the implicit
    /// methods, whose steps minimise an incremental potential with barrier
    /// terms. The others (explicit, Dormand–Prince, fast mass-spring)
    /// refuse a system with surface contact
    /// ([`hooke_core::System::has_surface_contact`]) with
    /// [`hooke_core::StepError::SurfaceContactUnsupported`].
    ///
    /// ```
    /// use hooke_scenes::Method;
    /// assert!(Method::Bdf2.resolves_surface_contact());
    /// assert!(!Method::FastMassSpring.resolves_surface_contact());
    /// assert!(!Method::from_name("rk4").unwrap().resolves_surface_contact());
    /// ```
    #[must_use]
    pub fn resolves_surface_contact(self) -> bool {
        matches!(self, Self::BackwardEuler | Self::Bdf2)
    }

    /// The method's stability on the undamped oscillator (the stability
    /// interval of its amplification factor on the imaginary axis).
    /// Dormand–Prince adapts its step to its tolerance, so it is
    /// [`OscillatorStability::Unconditional`] in the sense that no `dt`
    /// given to it makes it blow up.
    #[must_use]
    pub fn oscillator_stability(self) -> OscillatorStability {
        use ExplicitMethod as E;
        match self {
            Self::Explicit(E::ExplicitEuler | E::Midpoint | E::Heun | E::Gear) => {
                OscillatorStability::GainsEnergy
            }
            Self::Explicit(
                E::SymplecticEuler
                | E::Leapfrog
                | E::VelocityVerlet
                | E::PositionVerlet
                | E::Beeman,
            ) => OscillatorStability::BoundedUpTo(2.0),
            Self::Explicit(E::Rk4) => OscillatorStability::BoundedUpTo(2.0 * SQRT_2),
            Self::DormandPrince | Self::BackwardEuler | Self::Bdf2 | Self::FastMassSpring => {
                OscillatorStability::Unconditional
            }
        }
    }
}

/// A method is written as its name, e.g. `"rk4"`, in reports.
impl Serialize for Method {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for Method {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let name = String::deserialize(deserializer)?;
        Self::from_name(&name).ok_or_else(|| {
            de::Error::custom(format!(
                "no integrator \"{name}\"; one of {}",
                Self::names()
            ))
        })
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
