//! [`OutputError`]: everything that can go wrong while writing frames,
//! pictures and animations, naming the file or the input at fault.

use std::path::PathBuf;

use thiserror::Error;

/// Which kind of topology entry an [`OutputError::VertexOutOfRange`] is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Primitive {
    /// A triangle of a surface.
    Triangle,
    /// An edge of a face-less body.
    Edge,
}

impl std::fmt::Display for Primitive {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::Triangle => "triangle",
            Self::Edge => "edge",
        })
    }
}

/// A file that could not be written or an input that cannot be drawn or
/// stored. I/O variants carry the path of the file concerned.
#[derive(Debug, Error)]
pub enum OutputError {
    /// The file could not be created (missing directory, no permission, ...).
    #[error("cannot create {}: {source}", path.display())]
    Create {
        /// The file that was to be created.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// Writing to an open file failed (disk full, ...).
    #[error("cannot write {}: {source}", path.display())]
    Write {
        /// The file being written.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// A frame file could not be read back.
    #[error("cannot read {}: {source}", path.display())]
    Read {
        /// The file being read.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// A file read back as a frame is not one of the mesh's frames.
    #[error("{} is not a frame of this mesh: {reason}", path.display())]
    NotAFrame {
        /// The file read.
        path: PathBuf,
        /// What does not match.
        reason: &'static str,
    },
    /// An image encoder rejected its input.
    #[error("cannot encode {format} image {}: {source}", path.display())]
    Encode {
        /// The file being written.
        path: PathBuf,
        /// The image format, `"PNG"` or `"GIF"`.
        format: &'static str,
        /// The encoder's own error.
        source: Box<dyn std::error::Error + Send + Sync>,
    },
    /// An animation was finished before any frame was written.
    #[error("animation {} has no frames", path.display())]
    EmptyAnimation {
        /// The animation file.
        path: PathBuf,
    },
    /// A triangle or edge names a vertex the mesh does not have.
    #[error(
        "{primitive} {index}: vertex {vertex} is out of range (the mesh has {vertices} vertices)"
    )]
    VertexOutOfRange {
        /// Triangle or edge.
        primitive: Primitive,
        /// Index of the triangle or edge.
        index: usize,
        /// The offending vertex index.
        vertex: u32,
        /// Number of vertices in the mesh.
        vertices: usize,
    },
    /// More vertices than a PLY `int` index can address.
    #[error("{vertices} vertices exceed the PLY index limit of {}", i32::MAX)]
    TooManyVertices {
        /// Number of vertices asked for.
        vertices: usize,
    },
    /// A frame whose number of positions differs from the mesh's vertex count.
    #[error("frame has {found} positions but the mesh has {expected} vertices")]
    PositionCount {
        /// Vertices in the mesh.
        expected: usize,
        /// Positions in the frame.
        found: usize,
    },
    /// A position with a NaN or infinite component.
    #[error("vertex {vertex}: position is not finite: {value:?}")]
    NonFinitePosition {
        /// Index of the vertex.
        vertex: usize,
        /// The offending position.
        value: [f64; 3],
    },
    /// An obstacle that cannot be drawn (non-finite data, non-positive
    /// radius or extent, zero plane normal).
    #[error("obstacle {index}: {reason}")]
    InvalidShape {
        /// Index of the obstacle in the slice passed in.
        index: usize,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// A view whose angles or fill fraction are out of range.
    #[error("invalid view: {reason}")]
    InvalidView {
        /// What is wrong with it.
        reason: &'static str,
    },
    /// An image size that is zero or too large for the format.
    #[error("image size {width}x{height} is not supported (at most {limit} on a side)")]
    ImageSize {
        /// Requested width in pixels.
        width: u32,
        /// Requested height in pixels.
        height: u32,
        /// Largest side the target allows.
        limit: u32,
    },
    /// A frame rate that is zero, negative or not finite.
    #[error("frame rate must be positive and finite, got {fps}")]
    FrameRate {
        /// The offending frames per second.
        fps: f64,
    },
    /// A picture pushed to an animation with a size other than the one declared.
    #[error("frame is {found_width}x{found_height}, the animation expects {width}x{height}")]
    FrameSize {
        /// Declared width.
        width: u32,
        /// Declared height.
        height: u32,
        /// Width of the pushed picture.
        found_width: u32,
        /// Height of the pushed picture.
        found_height: u32,
    },
}
