//! Material parameters shared by every builder: how stiff a family of
//! springs is ([`Stiffness`], [`Springs`]) and how heavy a body is
//! ([`Mass`]).

use crate::error::{SceneError, non_negative, positive};

/// How the stiffness `k` of each spring in a family is chosen.
///
/// - [`Stiffness::PerSpring`]`(k)`: every spring gets the same `k` in N/m,
///   whatever its rest length. Refining a mesh then makes the body softer: a
///   chain of `n` such springs in series has end-to-end stiffness `k/n`.
/// - [`Stiffness::Modulus`]`(E)`: each spring gets `k = E/L` with `L` its
///   rest length, `E` in N (a Young's modulus times a cross-section). A chain
///   of `n` springs of length `ℓ = ℓ_total/n` in series has stiffness
///   `1/Σ(ℓ/E) = E/ℓ_total`, independent of `n`: refining keeps the material.
///
/// A bare number converts to `PerSpring`.
///
/// ```
/// use hooke_scenes::Stiffness;
/// assert_eq!(Stiffness::PerSpring(100.0).for_length(0.5), 100.0);
/// assert_eq!(Stiffness::Modulus(100.0).for_length(0.5), 200.0);
/// assert_eq!(Stiffness::from(7.0), Stiffness::PerSpring(7.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Stiffness {
    /// The same stiffness `k` (N/m) for every spring.
    PerSpring(f64),
    /// `k = E/L` for a spring of rest length `L`; `E` in N.
    Modulus(f64),
}

impl Stiffness {
    /// The stiffness `k` in N/m of a spring of rest length `L` in m.
    #[must_use]
    pub fn for_length(self, rest_length: f64) -> f64 {
        match self {
            Self::PerSpring(k) => k,
            Self::Modulus(e) => e / rest_length,
        }
    }

    fn value(self) -> f64 {
        match self {
            Self::PerSpring(v) | Self::Modulus(v) => v,
        }
    }
}

impl From<f64> for Stiffness {
    fn from(k: f64) -> Self {
        Self::PerSpring(k)
    }
}

/// The parameters of one family of springs (stretch, shear, bend, …): its
/// [`Stiffness`] and the axial damping `c` in N·s/m of each spring (force
/// `−c ((vᵢ − vⱼ)·d) d`, default 0).
///
/// A bare number or a [`Stiffness`] converts to an undamped family.
///
/// ```
/// use hooke_scenes::{Springs, Stiffness};
/// let stretch = Springs::modulus(500.0).damping(0.02);
/// assert_eq!(stretch.stiffness, Stiffness::Modulus(500.0));
/// assert_eq!(Springs::from(5e3), Springs::per_spring(5e3));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Springs {
    /// How each spring's stiffness is chosen.
    pub stiffness: Stiffness,
    /// Axial damping `c` of each spring in N·s/m.
    pub damping: f64,
}

impl Springs {
    /// Undamped springs of stiffness `k` N/m each.
    ///
    /// ```
    /// let s = hooke_scenes::Springs::per_spring(2e3);
    /// assert_eq!(s.damping, 0.0);
    /// ```
    #[must_use]
    pub fn per_spring(k: f64) -> Self {
        Stiffness::PerSpring(k).into()
    }

    /// Undamped springs of stiffness `E/L` each (see [`Stiffness::Modulus`]).
    ///
    /// ```
    /// let s = hooke_scenes::Springs::modulus(40.0);
    /// assert_eq!(s.stiffness.for_length(2.0), 20.0);
    /// ```
    #[must_use]
    pub fn modulus(e: f64) -> Self {
        Stiffness::Modulus(e).into()
    }

    /// Sets the axial damping `c` of each spring in N·s/m.
    ///
    /// ```
    /// let s = hooke_scenes::Springs::per_spring(2e3).damping(0.5);
    /// assert_eq!(s.damping, 0.5);
    /// ```
    #[must_use]
    pub fn damping(mut self, c: f64) -> Self {
        self.damping = c;
        self
    }

    /// Checks the stiffness and damping, naming the field in the error.
    pub(crate) fn validated(
        self,
        stiffness_field: &'static str,
        damping_field: &'static str,
    ) -> Result<Self, SceneError> {
        non_negative(stiffness_field, self.stiffness.value())?;
        non_negative(damping_field, self.damping)?;
        Ok(self)
    }
}

impl From<Stiffness> for Springs {
    fn from(stiffness: Stiffness) -> Self {
        Self {
            stiffness,
            damping: 0.0,
        }
    }
}

impl From<f64> for Springs {
    fn from(k: f64) -> Self {
        Stiffness::PerSpring(k).into()
    }
}

/// How heavy a body is: a total mass in kg, or a density whose unit is that
/// of the body's measure — kg/m for a rope, kg/m² for cloth and shells,
/// kg/m³ for volumes. Either way the mass is lumped onto the particles from
/// the elements (segments, cells, triangles, tets), so the particles' masses
/// always add up to the total.
///
/// ```
/// use hooke_scenes::Mass;
/// assert_eq!(Mass::Density(0.5).total(4.0)?, 2.0); // 0.5 kg/m² over 4 m²
/// assert_eq!(Mass::Total(2.0).total(3.0)?, 2.0);
/// # Ok::<(), hooke_scenes::SceneError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Mass {
    /// Total mass in kg.
    Total(f64),
    /// Mass per unit length, area or volume.
    Density(f64),
}

impl Mass {
    /// The total mass of a body of `measure` (length, area or volume).
    ///
    /// # Errors
    /// [`SceneError::InvalidValue`] for a mass or density that is not finite
    /// and positive.
    pub fn total(self, measure: f64) -> Result<f64, SceneError> {
        match self {
            Self::Total(m) => positive("total mass", m),
            Self::Density(rho) => Ok(positive("density", rho)? * measure),
        }
    }
}
