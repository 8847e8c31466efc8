//! Frames as binary little-endian PLY files, the format Blender, MeshLab and
//! ParaView all import.
//!
//! Positions are stored as `float` (f32), which is what those tools expect;
//! indices as `int`. The `face` element is present when the mesh has
//! triangles, the `edge` element when it has edges.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use hooke_core::Vec3;

use crate::error::OutputError;
use crate::mesh::Mesh;

/// The file name of frame `index`: `frame_00042.ply` for 42.
///
/// Indices are zero-padded to five digits so that names sort in frame order
/// up to 99 999 frames.
///
/// ```
/// assert_eq!(hooke_viz::frame_file_name(42), "frame_00042.ply");
/// ```
#[must_use]
pub fn frame_file_name(index: usize) -> String {
    format!("frame_{index:05}.ply")
}

/// Writes frame `index` into `dir` under [`frame_file_name`] and returns the
/// path written.
///
/// # Errors
///
/// As [`write_ply`].
pub fn write_frame(
    dir: &Path,
    index: usize,
    mesh: &Mesh,
    positions: &[Vec3],
) -> Result<PathBuf, OutputError> {
    let path = dir.join(frame_file_name(index));
    write_ply(&path, mesh, positions)?;
    Ok(path)
}

/// Writes one frame of `mesh` at `positions` to `path` as binary
/// little-endian PLY.
///
/// # Errors
///
/// [`OutputError::PositionCount`] or [`OutputError::NonFinitePosition`] for
/// positions that do not fit the mesh (checked before the file is created);
/// [`OutputError::Create`] or [`OutputError::Write`] naming `path` when the
/// file cannot be written.
pub fn write_ply(path: &Path, mesh: &Mesh, positions: &[Vec3]) -> Result<(), OutputError> {
    mesh.check_frame(positions)?;
    let file = File::create(path).map_err(|source| OutputError::Create {
        path: path.to_path_buf(),
        source,
    })?;
    let mut out = BufWriter::new(file);
    write_contents(&mut out, mesh, positions)
        .and_then(|()| out.flush())
        .map_err(|source| OutputError::Write {
            path: path.to_path_buf(),
            source,
        })
}

fn header(mesh: &Mesh) -> String {
    let mut header = format!(
        "ply\nformat binary_little_endian 1.0\ncomment written by hooke\n\
         element vertex {}\nproperty float x\nproperty float y\nproperty float z\n",
        mesh.vertex_count()
    );
    if !mesh.triangles().is_empty() {
        header += &format!(
            "element face {}\nproperty list uchar int vertex_indices\n",
            mesh.triangles().len()
        );
    }
    if !mesh.edges().is_empty() {
        header += &format!(
            "element edge {}\nproperty int vertex1\nproperty int vertex2\n",
            mesh.edges().len()
        );
    }
    header + "end_header\n"
}

/// Writes the header and payload. Vertex indices fit an `i32` because
/// [`Mesh::new`] caps the vertex count at `i32::MAX`, so the `u32` bytes are
/// the `int` bytes.
fn write_contents(out: &mut impl Write, mesh: &Mesh, positions: &[Vec3]) -> std::io::Result<()> {
    out.write_all(header(mesh).as_bytes())?;
    for p in positions {
        for &c in p.iter() {
            out.write_all(&(c as f32).to_le_bytes())?;
        }
    }
    for triangle in mesh.triangles() {
        out.write_all(&[3])?;
        for &v in triangle {
            out.write_all(&v.to_le_bytes())?;
        }
    }
    for edge in mesh.edges() {
        for &v in edge {
            out.write_all(&v.to_le_bytes())?;
        }
    }
    Ok(())
}
