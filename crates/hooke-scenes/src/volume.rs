//! [`Volume`]: how stiff a volumetric body's volume elements are, and the
//! bulk modulus its springs give by default.

use hooke_core::Vec3;

use crate::error::{SceneError, non_negative};
use crate::mesh::signed_volume;
use crate::spring::BodySpring;

/// The modulus `κ` of a volumetric body's volume elements: each of its tets
/// adds the energy `½ κ V₀ (J − 1)²`, `J = V/V₀` its signed volume ratio
/// (see [`hooke_core::Tet`]), which springs alone lack: a spring body and
/// its mirror image have the same spring lengths, so a body of springs
/// turned inside out stays so, while this energy pushes an inverted tet
/// (`J ≤ 0`) back out.
///
/// [`Lattice`](crate::Lattice), [`Solid`](crate::Solid) and
/// [`Layered`](crate::Layered) bodies have volume elements ([`Body::tets`](crate::Body::tets)
/// lists them); cloth, shells and ropes have none.
///
/// **The default, [`Volume::Auto`]**, is the bulk modulus the body's own
/// springs give under a uniform dilation,
///
/// ```text
/// κ = Σₛ kₛ Lₛ² / (9 V),
/// ```
///
/// over the body's springs `s` (stiffness `kₛ` in N/m, rest length `Lₛ`),
/// with `V` the body's rest volume, the sum of its tets' rest volumes:
/// stretching everything by a factor `1 + ε` stretches each spring by
/// `ε Lₛ` and stores `Σ ½ kₛ Lₛ² ε²` in the springs, while a continuum of
/// bulk modulus `K` stores `½ K (3ε)² V` (the volume grows by `3ε` to first
/// order), so the springs behave in bulk like `K = Σ kₛ Lₛ² / (9 V)`. The
/// volume term then doubles the body's resistance to a uniform
/// compression, and makes every flat or inverted element cost energy.
///
/// ```
/// use hooke_scenes::{Lattice, Volume};
/// let cube = Lattice::cubes(1, 1, 1).edges(100.0).build()?;
/// // 12 edges of k = 100 N/m and L = 1 m around V = 1 m³.
/// assert!((cube.volume_modulus() - 12.0 * 100.0 / 9.0).abs() < 1e-9);
/// let firm = Lattice::cubes(1, 1, 1).edges(100.0).volume(Volume::Modulus(500.0)).build()?;
/// assert_eq!(firm.volume_modulus(), 500.0);
/// let measured = Lattice::cubes(1, 1, 1).edges(100.0).volume(Volume::Off).build()?;
/// assert_eq!((measured.volume_modulus(), measured.tets().len()), (0.0, 6));
/// # Ok::<(), hooke_scenes::SceneError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Volume {
    /// `κ = Σ k L² / (9 V)`, the bulk modulus of the body's springs.
    #[default]
    Auto,
    /// `κ` in Pa; finite and not negative.
    Modulus(f64),
    /// No volume energy: the elements stay, with modulus 0, so that
    /// [`hooke_core::System::inversion`] (and `hooke run`'s report) still
    /// counts inverted elements and the smallest volume ratio.
    Off,
}

impl Volume {
    /// The modulus, Pa, for a body with `springs` whose tets have the
    /// summed rest volume `rest_volume`.
    ///
    /// # Errors
    /// [`SceneError::InvalidValue`] for a [`Volume::Modulus`] that is
    /// negative or not finite.
    pub(crate) fn modulus(
        self,
        springs: &[BodySpring],
        rest_volume: f64,
    ) -> Result<f64, SceneError> {
        match self {
            Self::Auto => Ok(spring_bulk_modulus(springs, rest_volume)),
            Self::Modulus(kappa) => non_negative("volume modulus", kappa),
            Self::Off => Ok(0.0),
        }
    }
}

/// `Σ k L² / (9 V)` over `springs`, 0 for no volume.
pub(crate) fn spring_bulk_modulus(springs: &[BodySpring], volume: f64) -> f64 {
    if volume > 0.0 {
        springs
            .iter()
            .map(|s| s.stiffness * s.rest_length * s.rest_length)
            .sum::<f64>()
            / (9.0 * volume)
    } else {
        0.0
    }
}

/// The summed unsigned volume of `tets` at `positions`, each times its
/// weight, m³.
pub(crate) fn rest_volume(tets: &[[usize; 4]], weights: &[f64], positions: &[Vec3]) -> f64 {
    tets.iter()
        .zip(weights)
        .map(|(t, w)| w * signed_volume(t.map(|v| positions[v])).abs())
        .sum()
}

/// `tet` with its last two corners swapped if its signed volume at
/// `positions` is negative.
pub(crate) fn positively_oriented(tet: [usize; 4], positions: &[Vec3]) -> [usize; 4] {
    let mut tet = tet;
    if signed_volume(tet.map(|v| positions[v])) < 0.0 {
        tet.swap(2, 3);
    }
    tet
}
