//! Frames as binary little-endian PLY files, the format Blender, MeshLab and
//! ParaView all import.
//!
//! Positions are stored as `float` (f32), which is what those tools expect;
//! indices as `int`. The `face` element is present when the mesh has
//! triangles, the `edge` element when it has edges.

use std::fs::File;
use std::io::{BufReader, BufWriter, Read, Write};
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

/// Reads back the positions of a frame that [`write_ply`] wrote for `mesh`
/// (as `f32`, the precision stored): the runner renders its pictures from
/// the frames on disk once the run is over and the camera can frame where
/// the bodies came to rest.
///
/// ```
/// use hooke_core::Vec3;
/// use hooke_viz::{Mesh, read_ply, write_ply};
/// let mesh = Mesh::new(2, Vec::new(), vec![[0, 1]])?;
/// let dir = tempfile::tempdir()?;
/// let path = dir.path().join("frame.ply");
/// write_ply(&path, &mesh, &[Vec3::zeros(), Vec3::new(0.5, 1.0, -2.0)])?;
/// assert_eq!(read_ply(&path, &mesh)?[1], Vec3::new(0.5, 1.0, -2.0));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// [`OutputError::Read`] naming `path` when it cannot be read;
/// [`OutputError::NotAFrame`] when its header is not the one `write_ply`
/// writes for `mesh` or it ends before the positions do.
pub fn read_ply(path: &Path, mesh: &Mesh) -> Result<Vec<Vec3>, OutputError> {
    let read_error = |source| OutputError::Read {
        path: path.to_path_buf(),
        source,
    };
    let not_a_frame = |reason| OutputError::NotAFrame {
        path: path.to_path_buf(),
        reason,
    };
    let file = File::open(path).map_err(read_error)?;
    let expected = header(mesh);
    let mut input = BufReader::new(file);
    let mut found = vec![0; expected.len()];
    match input.read_exact(&mut found) {
        Ok(()) if found == expected.as_bytes() => {}
        Ok(()) => return Err(not_a_frame("its header differs")),
        Err(e) if e.kind() == std::io::ErrorKind::UnexpectedEof => {
            return Err(not_a_frame("its header differs"));
        }
        Err(e) => return Err(read_error(e)),
    }
    let mut bytes = vec![0; 12 * mesh.vertex_count()];
    input.read_exact(&mut bytes).map_err(|e| {
        if e.kind() == std::io::ErrorKind::UnexpectedEof {
            not_a_frame("it ends within the positions")
        } else {
            read_error(e)
        }
    })?;
    let coordinate = |c: &[u8]| f64::from(f32::from_le_bytes([c[0], c[1], c[2], c[3]]));
    Ok(bytes
        .chunks_exact(12)
        .map(|p| {
            Vec3::new(
                coordinate(&p[..4]),
                coordinate(&p[4..8]),
                coordinate(&p[8..]),
            )
        })
        .collect())
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
