//! A bead on a string without pretension: a stiffness that changes with
//! amplitude.

use crate::{BuildError, System, SystemBuilder};

/// A bead of mass `m` between two pinned anchors at `(±a, 0, 0)`, joined to
/// each by a spring of stiffness `k` and rest length `a` (no pretension),
/// released from rest at `(0, y₀, 0)`. By symmetry it moves along y:
///
/// ```text
/// m y'' = −2k (1 − a/√(a² + y²)) y − γ y'
/// ```
///
/// For `|y| ≫ a` the restoring force is nearly linear, `−2k y`, with angular
/// frequency `√(2k/m)`; for `|y| ≪ a` it is cubic, `≈ −k y³/a²`, and soft.
/// With air damping `γ` the amplitude decays and the problem's stiffness with
/// it, so a fixed step sized for the start is far too small for the end —
/// the situation adaptive step control is for. There is no closed-form
/// motion; tests compare against a converged reference run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeadOnString {
    /// Mass of the bead `m` in kg.
    pub mass: f64,
    /// Stiffness `k` of each spring in N/m.
    pub stiffness: f64,
    /// Half the distance between the anchors, and each spring's rest length,
    /// `a` in m.
    pub half_span: f64,
    /// Initial transverse displacement `y₀` in m.
    pub amplitude: f64,
    /// Air damping `γ` in N·s/m.
    pub air_damping: f64,
}

impl BeadOnString {
    /// Index of the bead in [`BeadOnString::system`]; the anchors are 0 and 1.
    pub const BEAD: usize = 2;

    /// The system: anchors 0 and 1 pinned, the bead at index [`Self::BEAD`].
    ///
    /// # Errors
    /// A [`BuildError`] for invalid parameters.
    pub fn system(&self) -> Result<System, BuildError> {
        let mut b = SystemBuilder::new();
        let left = b.particle(self.mass, [-self.half_span, 0.0, 0.0]);
        let right = b.particle(self.mass, [self.half_span, 0.0, 0.0]);
        let bead = b.particle(self.mass, [0.0, self.amplitude, 0.0]);
        b.pin(left).pin(right);
        for anchor in [left, right] {
            b.spring(anchor, bead, self.stiffness)
                .rest_length(self.half_span);
        }
        if self.air_damping > 0.0 {
            b.air_damping(self.air_damping);
        }
        b.build()
    }
}
