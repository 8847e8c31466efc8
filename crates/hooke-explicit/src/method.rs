//! [`ExplicitMethod`]: the fixed-step explicit integrators by name.

use hooke_core::Integrator;

use crate::{
    Beeman, ExplicitEuler, Gear, Heun, Leapfrog, Midpoint, PositionVerlet, Rk4, SymplecticEuler,
    VelocityVerlet,
};

/// A fixed-step explicit integrator of this crate, by name: the list that
/// `hooke_scenes::Method` (every integrator of hooke) extends with the
/// adaptive and implicit ones.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ExplicitMethod {
    /// [`ExplicitEuler`].
    ExplicitEuler,
    /// [`SymplecticEuler`].
    SymplecticEuler,
    /// [`Leapfrog`].
    Leapfrog,
    /// [`VelocityVerlet`].
    VelocityVerlet,
    /// [`PositionVerlet`].
    PositionVerlet,
    /// [`Midpoint`].
    Midpoint,
    /// [`Heun`].
    Heun,
    /// [`Rk4`].
    Rk4,
    /// [`Beeman`].
    Beeman,
    /// [`Gear`].
    Gear,
}

impl ExplicitMethod {
    /// Every method, in the order of the crate's table.
    pub const ALL: [Self; 10] = [
        Self::ExplicitEuler,
        Self::SymplecticEuler,
        Self::Leapfrog,
        Self::VelocityVerlet,
        Self::PositionVerlet,
        Self::Midpoint,
        Self::Heun,
        Self::Rk4,
        Self::Beeman,
        Self::Gear,
    ];

    /// The integrator's name, e.g. `"velocity-verlet"`: its `NAME` constant,
    /// which its [`Integrator::name`] returns too.
    ///
    /// ```
    /// use hooke_explicit::{ExplicitMethod, Rk4};
    /// assert_eq!(ExplicitMethod::Rk4.name(), Rk4::NAME);
    /// ```
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::ExplicitEuler => ExplicitEuler::NAME,
            Self::SymplecticEuler => SymplecticEuler::NAME,
            Self::Leapfrog => Leapfrog::NAME,
            Self::VelocityVerlet => VelocityVerlet::NAME,
            Self::PositionVerlet => PositionVerlet::NAME,
            Self::Midpoint => Midpoint::NAME,
            Self::Heun => Heun::NAME,
            Self::Rk4 => Rk4::NAME,
            Self::Beeman => Beeman::NAME,
            Self::Gear => Gear::NAME,
        }
    }

    /// The method called `name`.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }

    /// A new integrator.
    #[must_use]
    pub fn build(self) -> Box<dyn Integrator + Send> {
        match self {
            Self::ExplicitEuler => Box::new(ExplicitEuler::new()),
            Self::SymplecticEuler => Box::new(SymplecticEuler::new()),
            Self::Leapfrog => Box::new(Leapfrog::new()),
            Self::VelocityVerlet => Box::new(VelocityVerlet::new()),
            Self::PositionVerlet => Box::new(PositionVerlet::new()),
            Self::Midpoint => Box::new(Midpoint::new()),
            Self::Heun => Box::new(Heun::new()),
            Self::Rk4 => Box::new(Rk4::new()),
            Self::Beeman => Box::new(Beeman::new()),
            Self::Gear => Box::new(Gear::new()),
        }
    }
}

/// One of each fixed-step integrator, boxed, in the order of
/// [`ExplicitMethod::ALL`].
#[must_use]
pub fn fixed_step_integrators() -> Vec<Box<dyn Integrator + Send>> {
    ExplicitMethod::ALL.map(ExplicitMethod::build).into()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_is_the_integrators_and_leads_back_to_its_method() {
        for method in ExplicitMethod::ALL {
            assert_eq!(method.build().name(), method.name());
            assert_eq!(ExplicitMethod::from_name(method.name()), Some(method));
        }
        assert_eq!(ExplicitMethod::from_name("rk5"), None);
    }
}
