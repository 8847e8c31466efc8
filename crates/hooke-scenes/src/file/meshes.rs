//! `[[bodies]]` made from mesh files — `tet-mesh` (TetGen), `obj` (a
//! shell) and `layered` — with mesh paths relative to the scene file.

use std::path::Path;

use hooke_core::Vec3;
use serde::Deserialize;
use toml::Spanned;

use super::bodies::{At, Built, PinNames, family, finish, scale, shared};
use super::error::{SceneFileError, Source};
use super::schema::{MovingPin, PinRef, SpringsTable, Vector, VolumeSetting};
use super::values::{key, positive, vector};
use crate::{Layered, SceneError, Shell, Solid, TetMesh, TriangleMesh, obj, tetgen};

/// Where a scene's mesh files come from.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Meshes<'a> {
    /// Files, with paths relative to this directory.
    Dir(&'a Path),
    /// Texts embedded in the program, by path relative to the scene.
    Embedded(&'a [(&'a str, &'a str)]),
}

impl Meshes<'_> {
    /// The text of `name`.
    fn text(&self, name: &Path) -> Result<String, SceneError> {
        let io = |source| SceneError::Io {
            path: name.to_owned(),
            source,
        };
        match self {
            Self::Dir(dir) => std::fs::read_to_string(dir.join(name)).map_err(io),
            Self::Embedded(files) => files
                .iter()
                .find(|(n, _)| Path::new(n) == name)
                .map(|(_, text)| (*text).to_owned())
                .ok_or_else(|| io(std::io::ErrorKind::NotFound.into())),
        }
    }

    /// TetGen's `<base>.node` and `<base>.ele`.
    fn tets(&self, base: &str) -> Result<TetMesh, SceneError> {
        match self {
            Self::Dir(dir) => tetgen::load(dir.join(base)),
            Self::Embedded(_) => {
                let (node, ele) = (format!("{base}.node"), format!("{base}.ele"));
                tetgen::parse(&self.text(Path::new(&node))?, &self.text(Path::new(&ele))?)
            }
        }
    }

    /// An OBJ surface.
    fn surface(&self, name: &str) -> Result<TriangleMesh, SceneError> {
        match self {
            Self::Dir(dir) => obj::load(dir.join(name)),
            Self::Embedded(_) => obj::parse(&self.text(Path::new(name))?),
        }
    }
}

/// `scale` then `offset` applied to mesh vertices.
fn placed(
    src: &Source<'_>,
    vertices: &mut [Vec3],
    scale_value: Option<&Spanned<f64>>,
    offset: Option<&Vector>,
    at: &At,
) -> Result<(), SceneFileError> {
    let factor = scale(src, scale_value, at)?;
    let shift = offset.map_or(Ok(Vec3::zeros()), |o| {
        vector(src, o, &key(&at.key, "offset"))
    })?;
    for v in vertices {
        *v = *v * factor + shift;
    }
    Ok(())
}

/// `type = "tet-mesh"`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct TetMeshTable {
    #[serde(rename = "type")]
    _kind: String,
    name: Option<String>,
    mesh: Spanned<String>,
    scale: Option<Spanned<f64>>,
    offset: Option<Vector>,
    edges: Option<Spanned<SpringsTable>>,
    mass: Option<Spanned<f64>>,
    density: Option<Spanned<f64>>,
    #[serde(default)]
    pins: Vec<Spanned<PinRef>>,
    #[serde(default)]
    moving_pins: Vec<Spanned<MovingPin>>,
    self_collision: Option<Spanned<bool>>,
    volume: Option<Spanned<VolumeSetting>>,
    thickness: Option<Spanned<f64>>,
}

/// Builds a solid from TetGen's `<mesh>.node` and `<mesh>.ele` (a `mesh`
/// ending in `.node` or `.ele` names the pair as well).
pub(crate) fn tet_mesh(
    src: &Source<'_>,
    meshes: Meshes<'_>,
    t: TetMeshTable,
    at: &At,
) -> Result<Built, SceneFileError> {
    let mesh_at = mesh_at(at, &t.mesh);
    let name = t.mesh.get_ref();
    let base = [".node", ".ele"]
        .iter()
        .find_map(|ext| name.strip_suffix(ext))
        .unwrap_or(name);
    let mut mesh = meshes
        .tets(base)
        .map_err(|e| src.scene(e, mesh_at.span.clone(), &mesh_at.key))?;
    placed(
        src,
        &mut mesh.vertices,
        t.scale.as_ref(),
        t.offset.as_ref(),
        at,
    )?;
    let mut solid = Solid::new(mesh);
    if let Some(s) = family(src, t.edges.as_ref(), &at.key, "edges")? {
        solid = solid.edges(s);
    }
    finish(
        src,
        at,
        &mesh_at,
        solid,
        shared!(t),
        ("kg/m³", PinNames::None),
    )
}

/// `type = "obj"`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ObjTable {
    #[serde(rename = "type")]
    _kind: String,
    name: Option<String>,
    mesh: Spanned<String>,
    scale: Option<Spanned<f64>>,
    offset: Option<Vector>,
    edges: Option<Spanned<SpringsTable>>,
    bend: Option<Spanned<SpringsTable>>,
    mass: Option<Spanned<f64>>,
    density: Option<Spanned<f64>>,
    #[serde(default)]
    pins: Vec<Spanned<PinRef>>,
    #[serde(default)]
    moving_pins: Vec<Spanned<MovingPin>>,
    self_collision: Option<Spanned<bool>>,
    volume: Option<Spanned<VolumeSetting>>,
    thickness: Option<Spanned<f64>>,
}

/// Builds a shell from an OBJ surface.
pub(crate) fn obj_shell(
    src: &Source<'_>,
    meshes: Meshes<'_>,
    t: ObjTable,
    at: &At,
) -> Result<Built, SceneFileError> {
    let mesh_at = mesh_at(at, &t.mesh);
    let mut mesh = meshes
        .surface(t.mesh.get_ref())
        .map_err(|e| src.scene(e, mesh_at.span.clone(), &mesh_at.key))?;
    placed(
        src,
        &mut mesh.vertices,
        t.scale.as_ref(),
        t.offset.as_ref(),
        at,
    )?;
    let mut shell = Shell::new(mesh);
    if let Some(s) = family(src, t.edges.as_ref(), &at.key, "edges")? {
        shell = shell.edges(s);
    }
    if let Some(s) = family(src, t.bend.as_ref(), &at.key, "bend")? {
        shell = shell.bend(s);
    }
    finish(
        src,
        at,
        &mesh_at,
        shell,
        shared!(t),
        ("kg/m²", PinNames::None),
    )
}

/// `type = "layered"`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct LayeredTable {
    #[serde(rename = "type")]
    _kind: String,
    name: Option<String>,
    mesh: Spanned<String>,
    thickness: Spanned<f64>,
    scale: Option<Spanned<f64>>,
    offset: Option<Vector>,
    surface: Option<Spanned<SpringsTable>>,
    links: Option<Spanned<SpringsTable>>,
    cross: Option<Spanned<SpringsTable>>,
    mass: Option<Spanned<f64>>,
    density: Option<Spanned<f64>>,
    #[serde(default)]
    pins: Vec<Spanned<PinRef>>,
    #[serde(default)]
    moving_pins: Vec<Spanned<MovingPin>>,
    self_collision: Option<Spanned<bool>>,
    volume: Option<Spanned<VolumeSetting>>,
    contact_thickness: Option<Spanned<f64>>,
}

/// Builds a layered body from an OBJ surface.
pub(crate) fn layered(
    src: &Source<'_>,
    meshes: Meshes<'_>,
    t: LayeredTable,
    at: &At,
) -> Result<Built, SceneFileError> {
    let mesh_at = mesh_at(at, &t.mesh);
    let thickness = positive(src, &t.thickness, &key(&at.key, "thickness"), "m")?;
    let mut mesh = meshes
        .surface(t.mesh.get_ref())
        .map_err(|e| src.scene(e, mesh_at.span.clone(), &mesh_at.key))?;
    placed(
        src,
        &mut mesh.vertices,
        t.scale.as_ref(),
        t.offset.as_ref(),
        at,
    )?;
    let mut body = Layered::new(mesh, thickness);
    if let Some(s) = family(src, t.surface.as_ref(), &at.key, "surface")? {
        body = body.surface(s);
    }
    if let Some(s) = family(src, t.links.as_ref(), &at.key, "links")? {
        body = body.links(s);
    }
    if let Some(s) = family(src, t.cross.as_ref(), &at.key, "cross")? {
        body = body.cross(s);
    }
    finish(
        src,
        at,
        &mesh_at,
        body,
        shared!(t, contact_thickness),
        ("kg/m³", PinNames::None),
    )
}

/// Where the `mesh` key of the body table at `at` is: what a body built
/// from a mesh file points at when it cannot be built.
fn mesh_at(at: &At, mesh: &Spanned<String>) -> At {
    At {
        key: key(&at.key, "mesh"),
        span: mesh.span(),
    }
}
