//! The springs of a body: [`BodySpring`], its [`Family`], and the set that
//! builders add springs to without duplicates.

use std::collections::HashSet;

use hooke_core::Vec3;

use crate::error::SceneError;
use crate::material::Springs;

/// The role a spring plays in its body; each family has its own
/// [`Springs`] parameters in the builder that makes it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Family {
    /// Cloth and rope structural springs: neighbours along a row, column or
    /// the rope.
    Stretch,
    /// Cloth shear springs: both diagonals of each grid cell.
    Shear,
    /// Bending springs: two apart along a row, column or rope, or across a
    /// shared edge of a triangle surface.
    Bend,
    /// Mesh edges: lattice cube edges, tet edges, surface triangle edges.
    Edge,
    /// Lattice face diagonals.
    FaceDiagonal,
    /// Lattice body (space) diagonals.
    BodyDiagonal,
    /// Layered model: a surface vertex to its copy on the inner layer.
    Link,
    /// Layered model: a surface vertex to the inner copies of its neighbours.
    Cross,
}

impl Family {
    /// The stiffness field name used in errors.
    pub(crate) fn stiffness_field(self) -> &'static str {
        match self {
            Self::Stretch => "stretch stiffness",
            Self::Shear => "shear stiffness",
            Self::Bend => "bend stiffness",
            Self::Edge => "edge stiffness",
            Self::FaceDiagonal => "face-diagonal stiffness",
            Self::BodyDiagonal => "body-diagonal stiffness",
            Self::Link => "link stiffness",
            Self::Cross => "cross stiffness",
        }
    }

    /// The damping field name used in errors.
    pub(crate) fn damping_field(self) -> &'static str {
        match self {
            Self::Stretch => "stretch damping",
            Self::Shear => "shear damping",
            Self::Bend => "bend damping",
            Self::Edge => "edge damping",
            Self::FaceDiagonal => "face-diagonal damping",
            Self::BodyDiagonal => "body-diagonal damping",
            Self::Link => "link damping",
            Self::Cross => "cross damping",
        }
    }
}

/// One spring of a [`crate::Body`], between its local particles `i` and
/// `j`, with its stiffness already resolved from the family's
/// [`crate::Stiffness`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodySpring {
    /// First particle.
    pub i: usize,
    /// Second particle.
    pub j: usize,
    /// Stiffness `k` in N/m.
    pub stiffness: f64,
    /// Rest length `L` in m: the distance in the body's initial shape.
    pub rest_length: f64,
    /// Axial damping `c` in N·s/m.
    pub damping: f64,
    /// The family the spring belongs to.
    pub family: Family,
}

/// Springs being collected for a body: at most one per pair of particles,
/// rest lengths from the initial positions.
pub(crate) struct SpringSet<'a> {
    positions: &'a [Vec3],
    seen: HashSet<(usize, usize)>,
    springs: Vec<BodySpring>,
}

impl<'a> SpringSet<'a> {
    pub(crate) fn new(positions: &'a [Vec3]) -> Self {
        Self {
            positions,
            seen: HashSet::new(),
            springs: Vec::new(),
        }
    }

    /// Adds a spring of `family` between `i` and `j` unless one is there;
    /// with `params` `None` the family is absent and nothing is added.
    /// Returns whether a spring was added. Indices must be in range.
    ///
    /// # Errors
    /// [`SceneError::InvalidValue`] for a zero-length spring, which
    /// [`crate::Stiffness::Modulus`] cannot give a stiffness.
    pub(crate) fn add(
        &mut self,
        i: usize,
        j: usize,
        family: Family,
        params: Option<Springs>,
    ) -> Result<bool, SceneError> {
        let Some(params) = params else {
            return Ok(false);
        };
        if i == j || !self.seen.insert((i.min(j), i.max(j))) {
            return Ok(false);
        }
        let rest_length = (self.positions[i] - self.positions[j]).norm();
        if !(rest_length.is_finite() && rest_length > 0.0) {
            return Err(SceneError::InvalidValue {
                field: "spring rest length",
                value: rest_length,
                requirement: "positive (the two particles coincide)",
            });
        }
        self.springs.push(BodySpring {
            i,
            j,
            stiffness: params.stiffness.for_length(rest_length),
            rest_length,
            damping: params.damping,
            family,
        });
        Ok(true)
    }

    pub(crate) fn into_springs(self) -> Vec<BodySpring> {
        self.springs
    }
}

/// Checks every family's parameters that is present.
pub(crate) fn validate_families(families: &[(Family, Option<Springs>)]) -> Result<(), SceneError> {
    for &(family, params) in families {
        if let Some(p) = params {
            p.validated(family.stiffness_field(), family.damping_field())?;
        }
    }
    Ok(())
}
