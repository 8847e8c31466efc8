//! The TOML scene file: [`parse`] and [`load`] turn a file into a
//! [`Scene`].
//!
//! A scene file states how long to run and at what step (`[simulation]`),
//! the integrator (`[integrator]`), gravity, air damping and wind
//! (`[world]`), any
//! number of bodies (`[[bodies]]`, each with a `type`: `cloth`, `rope`,
//! `lattice`, `tet-mesh`, `layered` or `obj`), their pins, scripted pin
//! motion, collision settings and volume energy (`volume`), and obstacles
//! (`[[obstacles]]`, each with a `shape`). Every key,
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
mod cloth;
mod error;
mod integrator;
mod lattice;
mod meshes;
mod obstacles;
mod pins;
mod rope;
mod schema;
mod tables;
mod values;

use std::ops::Range;
use std::path::Path;

use hooke_core::{BuildError, SystemBuilder, Vec3, Wind};
use toml::de::DeTable;

use crate::{Scene, SceneBody};
use bodies::At;
use error::Source;
pub use error::{ErrorKind, SceneFileError};
pub(crate) use meshes::Meshes;
use schema::{Header, World};
use values::{non_negative, positive, vector};

/// The most particles a scene file may declare, over all its bodies.
/// Larger systems can still be built in code.
pub const MAX_PARTICLES: usize = 1_000_000;

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
    let contact_distance = world(&src, header.world.as_ref(), &mut builder)?;
    let wind = wind(&src, header.world.as_ref())?;

    let mut scene_bodies = Vec::new();
    let mut placed = Vec::new();
    // The body of each collision surface, in the order they were added.
    let mut surfaces = Vec::new();
    let body_values = tables::tables(&src, body_values, "bodies")?;
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
        let (kind, built) = tables::body(&src, meshes, value, &at)?;
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
        if built.body.collision().surface {
            surfaces.push(i);
        }
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
        placed.push(Placed {
            at,
            particles: placement.range(),
            springs: springs_before..springs_before + built.body.springs().len(),
            tets: placement.tet_range(),
        });
    }
    if let Some((velocity, drag)) = wind {
        let triangles = scene_bodies
            .iter()
            .flat_map(|b| b.triangles.iter().copied())
            .collect();
        builder.term(Wind::new(velocity, drag, triangles));
    }
    let mut obstacle_places = Vec::new();
    for (k, value) in tables::tables(&src, obstacle_values, "obstacles")?
        .into_iter()
        .enumerate()
    {
        let at = At {
            key: format!("obstacles[{k}]"),
            span: value.span(),
        };
        builder.obstacle(tables::obstacle(&src, value, &at)?);
        obstacle_places.push(at);
    }
    let system = builder.build().map_err(|e| {
        let places = Places {
            bodies: &placed,
            surfaces: &surfaces,
            obstacles: &obstacle_places,
            contact_distance: contact_distance.as_ref(),
        };
        build_error(&src, e, &places)
    })?;
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

/// A body and where its parts are in the system.
struct Placed {
    /// The body's table.
    at: At,
    /// Its particles.
    particles: Range<usize>,
    /// Its springs.
    springs: Range<usize>,
    /// Its volume elements.
    tets: Range<usize>,
}

fn builder_springs(placed: &[Placed]) -> usize {
    placed.last().map_or(0, |p| p.springs.end)
}

/// `[world]`: gravity (default `[0, -9.81, 0]` m/s²), air damping
/// (default none) and the contact distance (default the system builder's);
/// returns where the contact distance was given.
fn world(
    src: &Source<'_>,
    world: Option<&World>,
    builder: &mut SystemBuilder,
) -> Result<Option<At>, SceneFileError> {
    let gravity = match world.and_then(|w| w.gravity.as_ref()) {
        Some(g) => vector(src, g, "world.gravity")?,
        None => Vec3::new(0.0, -9.81, 0.0),
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
    let Some(d) = world.and_then(|w| w.contact_distance.as_ref()) else {
        return Ok(None);
    };
    let key = "world.contact_distance";
    builder.contact_distance(positive(src, d, key, "m")?);
    Ok(Some(At {
        key: key.to_owned(),
        span: d.span(),
    }))
}

/// `[world] wind`: its velocity (m/s) and drag coefficient (N·s/m³), or
/// none without it or with no drag. It acts on the surface triangles of
/// every body, whether or not they collide: what the air meets.
fn wind(src: &Source<'_>, world: Option<&World>) -> Result<Option<(Vec3, f64)>, SceneFileError> {
    let Some(wind) = world.and_then(|w| w.wind.as_ref()) else {
        return Ok(None);
    };
    let velocity = vector(src, &wind.velocity, "world.wind.velocity")?;
    let drag = non_negative(src, &wind.drag, "world.wind.drag", "N·s/m³")?;
    Ok((drag > 0.0).then_some((velocity, drag)))
}

/// Where the parts of a system came from in the file, for its build
/// errors.
struct Places<'a> {
    /// The bodies.
    bodies: &'a [Placed],
    /// The body (an index into `bodies`) of each collision surface.
    surfaces: &'a [usize],
    /// The obstacles.
    obstacles: &'a [At],
    /// `world.contact_distance`, if given.
    contact_distance: Option<&'a At>,
}

/// A [`BuildError`] pointed at the body, obstacle or key it came from.
fn build_error(src: &Source<'_>, error: BuildError, places: &Places<'_>) -> SceneFileError {
    let placed = places.bodies;
    let by_particle = |p: usize| placed.iter().find(|b| b.particles.contains(&p));
    let by_spring = |s: usize| placed.iter().find(|b| b.springs.contains(&s));
    let by_tet = |t: usize| placed.iter().find(|b| b.tets.contains(&t));
    let at = match &error {
        BuildError::InvalidMass { particle, .. }
        | BuildError::NonFiniteParticle { particle, .. }
        | BuildError::PinOutOfRange { particle, .. }
        | BuildError::InvalidPinPath { particle, .. } => by_particle(*particle).map(|b| &b.at),
        BuildError::SpringEndpointOutOfRange { spring, .. }
        | BuildError::SelfSpring { spring, .. }
        | BuildError::DuplicateSpring { spring, .. }
        | BuildError::InvalidSpringParameter { spring, .. } => by_spring(*spring).map(|b| &b.at),
        BuildError::InvalidTet { tet, .. } => by_tet(*tet).map(|b| &b.at),
        BuildError::InvalidObstacle { obstacle, .. } => places.obstacles.get(*obstacle),
        BuildError::InvalidSurface { surface, .. } => places
            .surfaces
            .get(*surface)
            .and_then(|&body| placed.get(body))
            .map(|b| &b.at),
        BuildError::InvalidContactDistance { .. } => places.contact_distance,
        BuildError::NonFiniteGravity { .. }
        | BuildError::InvalidAirDamping { .. }
        | BuildError::InvalidTerm { .. } => None,
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
