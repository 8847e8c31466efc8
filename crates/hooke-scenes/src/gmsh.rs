//! Tetrahedral meshes from Gmsh `.msh` files (format 4.1, ASCII or
//! binary), read with the `mshio` crate (feature `gmsh`, on by default).
//!
//! The linear tetrahedra (element type 4) of every element block are kept,
//! and the corners of quadratic ones (type 11); other elements (the
//! triangles and lines Gmsh writes for the boundary) are skipped. Vertices
//! are the file's nodes in file order; nodes no tet uses are dropped.
//! `mshio` reads only format 4.1 (Gmsh's default since 4.0; older files can
//! be converted with `gmsh -save -format msh41`), and it takes dense node
//! tags to run in file order. It is an older crate that can panic on some
//! malformed files; such a panic is caught and reported as
//! [`SceneError::Gmsh`].

use std::collections::HashMap;
use std::panic;
use std::path::{Path, PathBuf};

use hooke_core::Vec3;
use mshio::mshfile::ElementType;

use crate::error::SceneError;
use crate::mesh::TetMesh;

/// Reads the tetrahedra of the Gmsh file at `path`.
///
/// ```
/// let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
/// let cube = hooke_scenes::gmsh::load(dir.join("tests/data/cube.msh"))?;
/// assert_eq!((cube.vertices.len(), cube.tets.len()), (8, 6));
/// # Ok::<(), hooke_scenes::SceneError>(())
/// ```
///
/// # Errors
/// [`SceneError::Io`] if the file cannot be read; [`SceneError::Gmsh`] if
/// it is not an MSH 4.1 file, has no tetrahedra, or names nodes it does not
/// define.
pub fn load(path: impl AsRef<Path>) -> Result<TetMesh, SceneError> {
    let path = path.as_ref();
    let bytes = std::fs::read(path).map_err(|source| SceneError::Io {
        path: path.to_owned(),
        source,
    })?;
    read(&bytes, path)
}

/// Reads the tetrahedra of MSH 4.1 file contents (named `<memory>` in
/// errors).
///
/// ```
/// let result = hooke_scenes::gmsh::parse(b"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n");
/// assert!(result.is_err()); // format 2.2 is not read
/// ```
///
/// # Errors
/// As [`load`], but never [`SceneError::Io`].
pub fn parse(bytes: &[u8]) -> Result<TetMesh, SceneError> {
    read(bytes, Path::new("<memory>"))
}

fn read(bytes: &[u8], path: &Path) -> Result<TetMesh, SceneError> {
    let error = |message: String| SceneError::Gmsh {
        path: PathBuf::from(path),
        message,
    };
    let file = panic::catch_unwind(|| mshio::parse_msh_bytes(bytes).map_err(|e| describe(&e)))
        .map_err(|_| error("the MSH reader failed on malformed input".into()))?
        .map_err(error)?;
    let mut positions = Vec::new();
    let mut index_of: HashMap<u64, usize> = HashMap::new();
    if let Some(nodes) = &file.data.nodes {
        let mut next_tag = nodes.min_node_tag;
        for block in &nodes.node_blocks {
            let mut tags: Vec<(u64, usize)> = match &block.node_tags {
                Some(map) => map.iter().map(|(&tag, &local)| (tag, local)).collect(),
                None => (0..block.nodes.len())
                    .map(|k| (next_tag.saturating_add(k as u64), k))
                    .collect(),
            };
            tags.sort_unstable_by_key(|&(_, local)| local);
            next_tag = next_tag.saturating_add(block.nodes.len() as u64);
            for (tag, local) in tags {
                let n = &block.nodes[local];
                index_of.insert(tag, positions.len());
                positions.push(Vec3::new(n.x, n.y, n.z));
            }
        }
    }
    let mut tets = Vec::new();
    let blocks = file.data.elements.iter().flat_map(|e| &e.element_blocks);
    for block in blocks.filter(|b| matches!(b.element_type, ElementType::Tet4 | ElementType::Tet10))
    {
        for element in &block.elements {
            let mut tet = [0; 4];
            for (corner, tag) in tet.iter_mut().zip(&element.nodes) {
                *corner = *index_of.get(tag).ok_or_else(|| {
                    error(format!(
                        "tetrahedron {} names node {tag}, which the file does not define",
                        element.element_tag
                    ))
                })?;
            }
            tets.push(tet);
        }
    }
    if tets.is_empty() {
        return Err(error("the file has no tetrahedra".into()));
    }
    let mut used = vec![false; positions.len()];
    for &node in tets.iter().flatten() {
        used[node] = true;
    }
    let mut mesh = TetMesh::default();
    let mut new_index = vec![0; positions.len()];
    for (node, &used) in used.iter().enumerate() {
        if used {
            new_index[node] = mesh.vertices.len();
            mesh.vertices.push(positions[node]);
        }
    }
    mesh.tets = tets.iter().map(|t| t.map(|node| new_index[node])).collect();
    Ok(mesh)
}

/// The reader's error as its contexts, outermost first. (`mshio` does not
/// say reliably where in the file it stopped, so no line is given.)
fn describe(error: &mshio::MshParserError<&[u8]>) -> String {
    let mut kinds: Vec<String> = error
        .filter_msh_errors()
        .map(|(_, kind)| kind.to_string())
        .collect();
    if kinds.is_empty() {
        kinds = error
            .backtrace
            .iter()
            .map(|(_, kind)| kind.to_string())
            .collect();
    }
    kinds.reverse();
    format!("malformed MSH 4.1 data: {}", kinds.join(": "))
}
