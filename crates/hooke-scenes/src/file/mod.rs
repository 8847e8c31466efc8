//! The TOML scene file: [`parse`] and [`load`] turn a file into a
//! [`Scene`].
//!
//! A scene file states how long to run and at what step (`[simulation]`),
//! the integrator (`[integrator]`), gravity and air damping (`[world]`), any
//! number of bodies (`[[bodies]]`, each with a `type`: `cloth`, `rope`,
//! `lattice`, `tet-mesh`, `layered` or `obj`), their pins and scripted pin
//! motion, and obstacles (`[[obstacles]]`, each with a `shape`). Every key,
//! its unit, default and constraints are documented in
//! `docs/scene-format.md`; the shipped scenes in `scenes/` are complete
//! examples.
//!
//! ```
//! use std::path::Path;
//! let scene = hooke_scenes::file::parse(
//!     r#"
//!     [simulation]
//!     duration = 2.0
//!     dt = 0.01
//!
//!     [[bodies]]
//!     type = "cloth"
//!     columns = 10
//!     rows = 10
//!     stretch = { stiffness = 2e3, damping = 0.01 }
//!     pins = ["top-left", "top-right"]
//!     "#,
//!     Path::new("cloth.toml"),
//! )?;
//! assert_eq!(scene.system.particle_count(), 100);
//! assert_eq!(scene.timing.steps(), 200);
//! # Ok::<(), hooke_scenes::file::SceneFileError>(())
//! ```
//!
//! Nothing here panics on any input: unknown keys, values of the wrong
//! type, missing keys, values out of range, unknown names, pins out of
//! range, missing or malformed mesh files, and bodies or systems the
//! builders reject are all a [`SceneFileError`] naming the file, the line
//! and the dotted key.

mod bodies;
mod error;
mod integrator;
mod meshes;
mod obstacles;
mod pins;
mod schema;
mod values;

use std::ops::Range;
use std::path::Path;

use hooke_core::{BuildError, SystemBuilder};
use serde::de::DeserializeOwned;
use toml::Spanned;
use toml::de::{DeTable, DeValue, ValueDeserializer};

use crate::{Scene, SceneBody};
use bodies::{At, Built};
use error::Source;
pub use error::{ErrorKind, SceneFileError};
pub(crate) use meshes::Meshes;
use schema::{Header, World};
use values::{non_negative, vector};

/// The most particles a scene file may declare, over all its bodies.
/// Larger systems can still be built in code.
pub const MAX_PARTICLES: usize = 1_000_000;

/// The body types, the values of a body's `type`.
const BODY_TYPES: [&str; 6] = ["cloth", "rope", "lattice", "tet-mesh", "layered", "obj"];

/// The obstacle shapes, the values of an obstacle's `shape`.
const SHAPES: [&str; 4] = ["plane", "sphere", "box", "capsule"];

/// Reads and parses the scene file at `path`; mesh paths in it are
/// relative to its directory.
///
/// # Errors
/// A [`SceneFileError`] if the file cannot be read or [`parse`] fails.
pub fn load(path: &Path) -> Result<Scene, SceneFileError> {
    let text = std::fs::read_to_string(path).map_err(|e| SceneFileError {
        file: path.to_owned(),
        line: None,
        key: String::new(),
        kind: Box::new(ErrorKind::Io(e)),
    })?;
    parse(&text, path)
}

/// Parses scene-file `text`; `file` names it in errors, its directory is
/// where mesh paths are looked up, and its stem is the scene's name unless
/// the file sets `name`.
///
/// # Errors
/// A [`SceneFileError`] naming the file, the line and the key of the first
/// problem found.
pub fn parse(text: &str, file: &Path) -> Result<Scene, SceneFileError> {
    parse_with(
        text,
        file,
        Meshes::Dir(file.parent().unwrap_or(Path::new(""))),
    )
}

/// [`parse`] with mesh files from `meshes`.
pub(crate) fn parse_with(
    text: &str,
    file: &Path,
    meshes: Meshes<'_>,
) -> Result<Scene, SceneFileError> {
    let src = Source { text, file };
    let root = DeTable::parse(text)
        .map_err(|e| src.error(e.span(), "", ErrorKind::Syntax(e.message().to_owned())))?;
    let body_values = root.get_ref().get("bodies").cloned();
    let obstacle_values = root.get_ref().get("obstacles").cloned();
    let header: Header = serde_path_to_error::deserialize(toml::de::Deserializer::from(root))
        .map_err(|e| src.serde("", e))?;
    let timing = integrator::timing(&src, header.simulation.as_ref())?;
    let integrator = integrator::integrator(&src, header.integrator.as_ref())?;
    let mut builder = SystemBuilder::new();
    world(&src, header.world.as_ref(), &mut builder)?;

    let mut scene_bodies = Vec::new();
    let mut placed = Vec::new();
    let body_values = tables(&src, body_values, "bodies")?;
    if body_values.is_empty() {
        return Err(src.error(
            None,
            "bodies",
            ErrorKind::Schema("a scene needs at least one `[[bodies]]` table".into()),
        ));
    }
    for (i, value) in body_values.into_iter().enumerate() {
        let at = At {
            key: format!("bodies[{i}]"),
            span: value.span(),
        };
        let (kind, built) = body(&src, meshes, value, &at)?;
        let springs_before = builder_springs(&placed);
        let placement = built.body.add_to(&mut builder);
        if placement.range().end > MAX_PARTICLES {
            return Err(src.invalid(
                at.span.clone(),
                &at.key,
                format!("{} particles in all", placement.range().end),
                format!("at most {MAX_PARTICLES} particles in a scene file"),
            ));
        }
        pins::add_pins(&src, &built, placement, &mut builder, &at)?;
        scene_bodies.push(SceneBody {
            name: built.common.name.clone().unwrap_or_else(|| kind.clone()),
            placement,
            triangles: placement.triangles(&built.body),
            segments: built
                .body
                .segments()
                .iter()
                .map(|s| s.map(|p| p + placement.first))
                .collect(),
        });
        placed.push((
            at,
            placement.range(),
            springs_before..springs_before + built.body.springs().len(),
        ));
    }
    let mut obstacle_places = Vec::new();
    for (k, value) in tables(&src, obstacle_values, "obstacles")?
        .into_iter()
        .enumerate()
    {
        let at = At {
            key: format!("obstacles[{k}]"),
            span: value.span(),
        };
        builder.obstacle(obstacle(&src, value, &at)?);
        obstacle_places.push(at);
    }
    let system = builder
        .build()
        .map_err(|e| build_error(&src, e, &placed, &obstacle_places))?;
    let name = header.name.unwrap_or_else(|| {
        file.file_stem()
            .map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned())
    });
    Ok(Scene {
        name,
        system,
        bodies: scene_bodies,
        integrator,
        timing,
    })
}

/// A body, its particle range and its spring range in the system.
type Placed = (At, Range<usize>, Range<usize>);

fn builder_springs(placed: &[Placed]) -> usize {
    placed.last().map_or(0, |(_, _, springs)| springs.end)
}

/// `[world]`: gravity (default `[0, -9.81, 0]` m/s²) and air damping
/// (default none).
fn world(
    src: &Source<'_>,
    world: Option<&World>,
    builder: &mut SystemBuilder,
) -> Result<(), SceneFileError> {
    let gravity = match world.and_then(|w| w.gravity.as_ref()) {
        Some(g) => vector(src, g, "world.gravity")?,
        None => hooke_core::Vec3::new(0.0, -9.81, 0.0),
    };
    if gravity.norm() > 0.0 {
        builder.gravity(gravity);
    }
    if let Some(gamma) = world.and_then(|w| w.air_damping.as_ref()) {
        let gamma = non_negative(src, gamma, "world.air_damping", "N·s/m")?;
        if gamma > 0.0 {
            builder.air_damping(gamma);
        }
    }
    Ok(())
}

/// The tables of an array of tables (`[[bodies]]`), none if absent.
fn tables<'i>(
    src: &Source<'_>,
    value: Option<Spanned<DeValue<'i>>>,
    key: &str,
) -> Result<Vec<Spanned<DeValue<'i>>>, SceneFileError> {
    let Some(value) = value else {
        return Ok(Vec::new());
    };
    let span = value.span();
    match value.into_inner() {
        DeValue::Array(items) => Ok(items.into_iter().collect()),
        other => Err(src.invalid(
            span,
            key,
            format!("a {}", other.type_str()),
            format!("an array of tables (`[[{key}]]`)"),
        )),
    }
}

/// The string under `tag` in `value`, which must be a table, checked
/// against `allowed`.
fn tag(
    src: &Source<'_>,
    value: &Spanned<DeValue<'_>>,
    tag: &str,
    allowed: &[&str],
    at: &At,
) -> Result<String, SceneFileError> {
    let Some(table) = value.get_ref().as_table() else {
        return Err(src.invalid(
            value.span(),
            &at.key,
            format!("a {}", value.get_ref().type_str()),
            "a table",
        ));
    };
    let key = values::key(&at.key, tag);
    let Some(tagged) = table.get(tag) else {
        return Err(src.error(
            Some(value.span()),
            key,
            ErrorKind::Schema(format!("missing field `{tag}`")),
        ));
    };
    let options = allowed
        .iter()
        .map(|n| format!("\"{n}\""))
        .collect::<Vec<_>>()
        .join(", ");
    match tagged.get_ref().as_str() {
        Some(name) if allowed.contains(&name) => Ok(name.to_owned()),
        Some(name) => Err(src.invalid(
            tagged.span(),
            key,
            format!("\"{name}\""),
            format!("one of {options}"),
        )),
        None => Err(src.invalid(
            tagged.span(),
            key,
            format!("a {}", tagged.get_ref().type_str()),
            format!("a string, one of {options}"),
        )),
    }
}

/// Deserializes the table `value` at `at` as a `T`.
fn read<T: DeserializeOwned>(
    src: &Source<'_>,
    value: Spanned<DeValue<'_>>,
    at: &At,
) -> Result<T, SceneFileError> {
    serde_path_to_error::deserialize(ValueDeserializer::from(value))
        .map_err(|e| src.serde(&at.key, e))
}

/// One `[[bodies]]` table: its type and the body it describes.
fn body(
    src: &Source<'_>,
    meshes: Meshes<'_>,
    value: Spanned<DeValue<'_>>,
    at: &At,
) -> Result<(String, Built), SceneFileError> {
    let kind = tag(src, &value, "type", &BODY_TYPES, at)?;
    let built = match kind.as_str() {
        "cloth" => bodies::cloth(src, read(src, value, at)?, at),
        "rope" => bodies::rope(src, read(src, value, at)?, at),
        "lattice" => bodies::lattice(src, read(src, value, at)?, at),
        "tet-mesh" => meshes::tet_mesh(src, meshes, read(src, value, at)?, at),
        "layered" => meshes::layered(src, meshes, read(src, value, at)?, at),
        _ => meshes::obj_shell(src, meshes, read(src, value, at)?, at),
    }?;
    Ok((kind, built))
}

/// One `[[obstacles]]` table.
fn obstacle(
    src: &Source<'_>,
    value: Spanned<DeValue<'_>>,
    at: &At,
) -> Result<hooke_core::Obstacle, SceneFileError> {
    match tag(src, &value, "shape", &SHAPES, at)?.as_str() {
        "plane" => obstacles::plane(src, &read(src, value, at)?, at),
        "sphere" => obstacles::sphere(src, &read(src, value, at)?, at),
        "box" => obstacles::cuboid(src, &read(src, value, at)?, at),
        _ => obstacles::capsule(src, &read(src, value, at)?, at),
    }
}

/// A [`BuildError`] pointed at the body or obstacle it came from.
fn build_error(
    src: &Source<'_>,
    error: BuildError,
    placed: &[Placed],
    obstacles: &[At],
) -> SceneFileError {
    let by_particle = |p: usize| {
        placed
            .iter()
            .find(|(_, particles, _)| particles.contains(&p))
            .map(|(at, _, _)| at)
    };
    let by_spring = |s: usize| {
        placed
            .iter()
            .find(|(_, _, springs)| springs.contains(&s))
            .map(|(at, _, _)| at)
    };
    let at = match &error {
        BuildError::InvalidMass { particle, .. }
        | BuildError::NonFiniteParticle { particle, .. }
        | BuildError::PinOutOfRange { particle, .. }
        | BuildError::InvalidPinPath { particle, .. } => by_particle(*particle),
        BuildError::SpringEndpointOutOfRange { spring, .. }
        | BuildError::SelfSpring { spring, .. }
        | BuildError::DuplicateSpring { spring, .. }
        | BuildError::InvalidSpringParameter { spring, .. } => by_spring(*spring),
        BuildError::InvalidObstacle { obstacle, .. } => obstacles.get(*obstacle),
        BuildError::NonFiniteGravity { .. } | BuildError::InvalidAirDamping { .. } => None,
    };
    match at {
        Some(at) => src.error(
            Some(at.span.clone()),
            at.key.clone(),
            ErrorKind::Build(error),
        ),
        None => src.error(None, "world", ErrorKind::Build(error)),
    }
}
