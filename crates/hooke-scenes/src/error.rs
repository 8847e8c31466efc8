//! [`SceneError`]: a scene description or mesh file that cannot become a
//! body, naming the field, element, vertex, file or line at fault.

use std::fmt;
use std::path::PathBuf;

use hooke_core::BuildError;
use thiserror::Error;

/// A mesh element named by an error: its kind and its index in the mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Element {
    /// Triangle number `n` of a surface mesh.
    Triangle(usize),
    /// Tetrahedron number `n` of a volume mesh.
    Tet(usize),
    /// The prism of a [`crate::Layered`] body between triangle number `n`
    /// of its surface mesh and the triangle's inner copy.
    Prism(usize),
}

impl fmt::Display for Element {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Triangle(n) => write!(f, "triangle {n}"),
            Self::Tet(n) => write!(f, "tet {n}"),
            Self::Prism(n) => write!(f, "the prism between triangle {n} and its inner copy"),
        }
    }
}

/// Why a scene or mesh could not be turned into a [`crate::Body`].
#[derive(Debug, Error)]
pub enum SceneError {
    /// A count (grid cells, segments, …) below its minimum.
    #[error("{field} must be at least {min}, got {value}")]
    InvalidCount {
        /// The parameter, e.g. `"cloth columns"`.
        field: &'static str,
        /// The value given.
        value: usize,
        /// The smallest value allowed.
        min: usize,
    },
    /// Counts whose product of particles overflows the index type.
    #[error("{field} ask for more particles than can be indexed")]
    TooLarge {
        /// The parameters, e.g. `"lattice cells"`.
        field: &'static str,
    },
    /// A number that is NaN, infinite, or outside its range.
    #[error("{field} must be {requirement}, got {value}")]
    InvalidValue {
        /// The parameter, e.g. `"stretch stiffness"`.
        field: &'static str,
        /// The value given.
        value: f64,
        /// What the value must be, e.g. `"finite and positive"`.
        requirement: &'static str,
    },
    /// A vector parameter with a NaN or infinite component, or a zero
    /// rotation axis.
    #[error("{field} must be {requirement}, got {value:?}")]
    InvalidVector {
        /// The parameter, e.g. `"rope start"`.
        field: &'static str,
        /// The value given.
        value: [f64; 3],
        /// What the vector must be.
        requirement: &'static str,
    },
    /// A pin on a particle the body does not have.
    #[error("pin on particle {particle} is out of range (the body has {particles} particles)")]
    PinOutOfRange {
        /// The requested particle.
        particle: usize,
        /// Number of particles in the body.
        particles: usize,
    },
    /// A mesh vertex with a NaN or infinite coordinate.
    #[error("vertex {vertex} is not finite: {value:?}")]
    NonFiniteVertex {
        /// Index of the vertex.
        vertex: usize,
        /// Its position.
        value: [f64; 3],
    },
    /// An element naming a vertex the mesh does not have.
    #[error("{element} names vertex {vertex}, but the mesh has {vertices} vertices")]
    VertexOutOfRange {
        /// The element.
        element: Element,
        /// The vertex index it names.
        vertex: usize,
        /// Number of vertices in the mesh.
        vertices: usize,
    },
    /// An element with zero area or volume (repeated or collinear/coplanar
    /// corners; for a prism, all of its tets flat).
    #[error("{element} is degenerate (its {} is {measure:e})", match element { Element::Triangle(_) => "area", Element::Tet(_) => "volume", Element::Prism(_) => "largest tet's volume" })]
    DegenerateElement {
        /// The element.
        element: Element,
        /// Its area or unsigned volume (for a prism, the largest of its
        /// tets').
        measure: f64,
    },
    /// A tetrahedron whose orientation is opposite to that of tet 0.
    #[error("tet {tet} is inverted: signed volume {volume:e} has the opposite sign of tet 0's")]
    InvertedTet {
        /// Index of the tetrahedron.
        tet: usize,
        /// Its signed volume `det(b − a, c − a, d − a)/6`.
        volume: f64,
    },
    /// A vertex no element uses: it would get no mass.
    #[error("vertex {vertex} belongs to no element")]
    UnusedVertex {
        /// Index of the vertex.
        vertex: usize,
    },
    /// A surface edge shared by more than two triangles.
    #[error("edge ({a}, {b}) is shared by {triangles} triangles; at most 2 are allowed")]
    NonManifoldEdge {
        /// One end.
        a: usize,
        /// The other end.
        b: usize,
        /// Number of triangles sharing it.
        triangles: usize,
    },
    /// A vertex whose area-weighted normal vanishes, so it cannot be offset
    /// into an inner layer.
    #[error("vertex {vertex} has no normal: the areas around it cancel")]
    ZeroNormal {
        /// Index of the vertex.
        vertex: usize,
    },
    /// A malformed line in a text mesh file.
    #[error("{}:{line}: {message}", file.display())]
    Parse {
        /// The file (or a name for in-memory text).
        file: PathBuf,
        /// Line number, from 1.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A file that could not be read.
    #[error("cannot read {}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// An OBJ file the `tobj` reader rejected.
    #[error("cannot load OBJ {}: {source}", path.display())]
    Obj {
        /// The file.
        path: PathBuf,
        /// The reader's error.
        source: tobj::LoadError,
    },
    /// The body was valid but the system builder rejected the scene it went
    /// into (for example a gravity vector that is not finite).
    #[error(transparent)]
    Build(#[from] BuildError),
}

/// `value` if it is finite and positive.
pub(crate) fn positive(field: &'static str, value: f64) -> Result<f64, SceneError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(SceneError::InvalidValue {
            field,
            value,
            requirement: "finite and positive",
        })
    }
}

/// `value` if it is finite and not negative.
pub(crate) fn non_negative(field: &'static str, value: f64) -> Result<f64, SceneError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(SceneError::InvalidValue {
            field,
            value,
            requirement: "finite and non-negative",
        })
    }
}

/// `value` if it is finite.
pub(crate) fn finite(field: &'static str, value: f64) -> Result<f64, SceneError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(SceneError::InvalidValue {
            field,
            value,
            requirement: "finite",
        })
    }
}

/// `value` if it is at least `min`.
pub(crate) fn count(field: &'static str, value: usize, min: usize) -> Result<usize, SceneError> {
    if value >= min {
        Ok(value)
    } else {
        Err(SceneError::InvalidCount { field, value, min })
    }
}

/// The number of grid points, `Π (cᵢ + extra)`, unless it overflows.
pub(crate) fn grid_points(
    field: &'static str,
    counts: &[usize],
    extra: usize,
) -> Result<usize, SceneError> {
    counts
        .iter()
        .try_fold(1usize, |n, &c| n.checked_mul(c.checked_add(extra)?))
        .ok_or(SceneError::TooLarge { field })
}

/// `value` if every component is finite.
pub(crate) fn finite_vector(
    field: &'static str,
    value: [f64; 3],
) -> Result<hooke_core::Vec3, SceneError> {
    if value.iter().all(|c| c.is_finite()) {
        Ok(value.into())
    } else {
        Err(SceneError::InvalidVector {
            field,
            value,
            requirement: "finite",
        })
    }
}
