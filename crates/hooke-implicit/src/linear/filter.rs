//! Per-particle constraint filters (Baraff & Witkin 1998, §5.3).

use hooke_core::{Mat3, System, Vec3};

/// The filter `Sᵢ` of one particle: the projection onto the directions in
/// which its velocity change is free. A constrained direction's velocity
/// change is prescribed as zero, so a pinned particle keeps its velocity and
/// one held on a plane keeps its normal velocity.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Filter {
    /// Unconstrained: `S = I`.
    #[default]
    Free,
    /// Constrained along the unit normal `p` (free in its plane):
    /// `S = I − p pᵀ`.
    Plane(Vec3),
    /// Free only along the unit direction `r` (constrained in two
    /// directions): `S = r rᵀ`.
    Line(Vec3),
    /// Fully constrained: `S = 0`.
    Fixed,
}

impl Filter {
    /// `S v`.
    #[inline]
    #[must_use]
    pub fn apply(self, v: Vec3) -> Vec3 {
        match self {
            Self::Free => v,
            Self::Plane(p) => v - p * p.dot(&v),
            Self::Line(r) => r * r.dot(&v),
            Self::Fixed => Vec3::zeros(),
        }
    }

    /// The matrix `S`.
    #[must_use]
    pub fn matrix(self) -> Mat3 {
        match self {
            Self::Free => Mat3::identity(),
            Self::Plane(p) => Mat3::identity() - p * p.transpose(),
            Self::Line(r) => r * r.transpose(),
            Self::Fixed => Mat3::zeros(),
        }
    }
}

/// Every particle's filter from its pin alone: [`Filter::Fixed`] for a
/// pinned particle, [`Filter::Free`] otherwise.
#[must_use]
pub fn pin_filters(system: &System) -> Vec<Filter> {
    (0..system.particle_count())
        .map(|i| {
            if system.is_pinned(i) {
                Filter::Fixed
            } else {
                Filter::Free
            }
        })
        .collect()
}

/// `Sᵢ vᵢ` for every particle.
pub(crate) fn project(filters: &[Filter], v: &mut [Vec3]) {
    for (vi, f) in v.iter_mut().zip(filters) {
        *vi = f.apply(*vi);
    }
}
