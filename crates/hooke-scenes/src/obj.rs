//! Triangle surfaces from Wavefront OBJ files, read with the `tobj` crate.
//!
//! Faces with more than three corners are split into fans; points, lines
//! and materials are ignored. Vertices are numbered in the order faces
//! first use them (as `tobj` numbers them), which is the file's order
//! whenever the faces use vertices in order; unused vertices are dropped.
//! An OBJ file with several objects or groups gives one mesh: vertices at
//! bit-identical positions are merged, so objects that share vertices stay
//! connected.

use std::collections::HashMap;
use std::io::BufReader;
use std::path::{Path, PathBuf};

use hooke_core::Vec3;

use crate::error::SceneError;
use crate::mesh::TriangleMesh;

/// Reads the triangle surface of the OBJ file at `path`.
///
/// ```
/// let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
/// let cube = hooke_scenes::obj::load(dir.join("tests/data/cube.obj"))?;
/// assert_eq!((cube.vertices.len(), cube.triangles.len()), (8, 12));
/// # Ok::<(), hooke_scenes::SceneError>(())
/// ```
///
/// # Errors
/// [`SceneError::Io`] if the file cannot be read, [`SceneError::Obj`] if
/// it is not valid OBJ.
pub fn load(path: impl AsRef<Path>) -> Result<TriangleMesh, SceneError> {
    let path = path.as_ref();
    let bytes = std::fs::read(path).map_err(|source| SceneError::Io {
        path: path.to_owned(),
        source,
    })?;
    read(&bytes, path)
}

/// Reads a triangle surface from OBJ text.
///
/// ```
/// let mesh = hooke_scenes::obj::parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 4 3\n")?;
/// // Vertices are numbered as the face uses them: 1, 2, 4, 3.
/// assert_eq!(mesh.vertices[2], hooke_core::Vec3::new(1.0, 1.0, 0.0));
/// assert_eq!(mesh.triangles, [[0, 1, 2], [0, 2, 3]]);
/// # Ok::<(), hooke_scenes::SceneError>(())
/// ```
///
/// # Errors
/// [`SceneError::Obj`] if the text is not valid OBJ (its path is shown as
/// `<memory>`).
pub fn parse(text: &str) -> Result<TriangleMesh, SceneError> {
    read(text.as_bytes(), Path::new("<memory>"))
}

fn read(bytes: &[u8], path: &Path) -> Result<TriangleMesh, SceneError> {
    let options = tobj::LoadOptions {
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
        ..tobj::LoadOptions::default()
    };
    let obj_error = |source| SceneError::Obj {
        path: PathBuf::from(path),
        source,
    };
    let (models, _materials) = tobj::load_obj_buf(&mut BufReader::new(bytes), &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(obj_error)?;
    let mut mesh = TriangleMesh::default();
    let mut welded: HashMap<[u64; 3], usize> = HashMap::new();
    for model in &models {
        let local: Vec<usize> = model
            .mesh
            .positions
            .chunks_exact(3)
            .map(|p| {
                let key = [p[0].to_bits(), p[1].to_bits(), p[2].to_bits()];
                *welded.entry(key).or_insert_with(|| {
                    mesh.vertices.push(Vec3::new(p[0], p[1], p[2]));
                    mesh.vertices.len() - 1
                })
            })
            .collect();
        for t in model.mesh.indices.chunks_exact(3) {
            let mut triangle = [0; 3];
            for (corner, &i) in triangle.iter_mut().zip(t) {
                *corner = *local
                    .get(i as usize)
                    .ok_or_else(|| obj_error(tobj::LoadError::FaceVertexOutOfBounds))?;
            }
            mesh.triangles.push(triangle);
        }
    }
    Ok(mesh)
}
