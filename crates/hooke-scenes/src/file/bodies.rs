//! What every `[[bodies]]` table shares — name, pins, scripted pins,
//! spring families — and what reading one produces.

use std::ops::Range;

use toml::Spanned;

use super::MAX_PARTICLES;
use super::error::{SceneFileError, Source};
use super::schema::{MovingPin, PinRef, SpringsTable, VolumeSetting};
use super::values::{key, mass, non_negative, positive, springs, volume};
use crate::{Body, Cloth, Lattice, Layered, Mass, Rope, SceneError, Shell, Solid, Springs};

/// Where a table is: its dotted key and its span in the file.
pub(crate) struct At {
    /// The dotted key, e.g. `bodies[2]`.
    pub(crate) key: String,
    /// The table's span (its header, for `[[bodies]]`).
    pub(crate) span: Range<usize>,
}

/// The keys every body table has besides its geometry and springs, as
/// read; [`shared!`] takes them out of a table.
pub(crate) struct Shared {
    /// `name`.
    pub(crate) name: Option<String>,
    /// `mass`, kg.
    pub(crate) mass: Option<Spanned<f64>>,
    /// `density`, in the body's unit.
    pub(crate) density: Option<Spanned<f64>>,
    /// `pins`.
    pub(crate) pins: Vec<Spanned<PinRef>>,
    /// `moving_pins`.
    pub(crate) moving_pins: Vec<Spanned<MovingPin>>,
    /// `self_collision`.
    pub(crate) self_collision: Option<Spanned<bool>>,
    /// `volume`.
    pub(crate) volume: Option<Spanned<VolumeSetting>>,
    /// The surface's thickness, m, and its key: `thickness`, or
    /// `contact_thickness` where `thickness` means something else.
    pub(crate) thickness: (Option<Spanned<f64>>, &'static str),
}

/// The [`Shared`] keys of a body table `t`, moved out of it; the surface
/// thickness is `t.thickness` unless another field is named.
macro_rules! shared {
    ($t:expr) => {
        $crate::file::bodies::shared!($t, thickness)
    };
    ($t:expr, $thickness:ident) => {
        $crate::file::bodies::Shared {
            name: $t.name,
            mass: $t.mass,
            density: $t.density,
            pins: $t.pins,
            moving_pins: $t.moving_pins,
            self_collision: $t.self_collision,
            volume: $t.volume,
            thickness: ($t.$thickness, stringify!($thickness)),
        }
    };
}
pub(crate) use shared;

/// A scene builder that a body table configures: all of them take a mass
/// and build a [`Body`].
pub(crate) trait BodyBuilder: Sized {
    /// The builder with this mass.
    fn with_mass(self, mass: Mass) -> Self;
    /// The body.
    fn build_body(self) -> Result<Body, SceneError>;
}

macro_rules! body_builders {
    ($($builder:ty),*) => {$(
        impl BodyBuilder for $builder {
            fn with_mass(self, mass: Mass) -> Self {
                self.mass(mass)
            }
            fn build_body(self) -> Result<Body, SceneError> {
                self.build()
            }
        }
    )*};
}
body_builders!(Cloth, Rope, Lattice, Solid, Shell, Layered);

/// Ends reading the body table at `at`: gives `builder` the table's `mass`
/// or `density` (in `density_unit`), builds the body (an error pointing at
/// `built_at`), gives it the table's collision and volume settings and
/// keeps its name and pins.
pub(crate) fn finish(
    src: &Source<'_>,
    at: &At,
    built_at: &At,
    builder: impl BodyBuilder,
    shared: Shared,
    (density_unit, names): (&str, PinNames),
) -> Result<Built, SceneFileError> {
    let given = mass(
        src,
        shared.mass.as_ref(),
        shared.density.as_ref(),
        &at.key,
        density_unit,
    )?;
    let builder = match given {
        Some(m) => builder.with_mass(m),
        None => builder,
    };
    let body = builder
        .build_body()
        .map_err(|e| src.scene(e, built_at.span.clone(), &built_at.key))?;
    let body = collision(src, at, body, &shared)?;
    let body = volume_elements(src, at, body, shared.volume.as_ref())?;
    Ok(Built {
        body,
        names,
        common: Common {
            name: shared.name,
            pins: shared.pins,
            moving_pins: shared.moving_pins,
        },
    })
}

/// `body` with the table's `self_collision` and surface thickness; either
/// key on a body without triangles (a rope) is an error.
fn collision(
    src: &Source<'_>,
    at: &At,
    body: Body,
    shared: &Shared,
) -> Result<Body, SceneFileError> {
    let (thickness, thickness_key) = (&shared.thickness.0, shared.thickness.1);
    if body.triangles().is_empty() {
        let given = [
            shared
                .self_collision
                .as_ref()
                .map(|s| ("self_collision", s.span())),
            thickness.as_ref().map(|t| (thickness_key, t.span())),
        ];
        if let Some((name, span)) = given.into_iter().flatten().next() {
            return Err(src.invalid(
                span,
                key(&at.key, name),
                format!("`{name}` on a body without triangles"),
                format!(
                    "no `{name}`: only bodies with surface triangles collide with surfaces (a rope has none)"
                ),
            ));
        }
        return Ok(body);
    }
    let mut body = body;
    if let Some(on) = &shared.self_collision {
        body = body.self_collision(*on.get_ref());
    }
    if let Some(t) = thickness {
        body = body.thickness(non_negative(src, t, &key(&at.key, thickness_key), "m")?);
    }
    Ok(body)
}

/// `body` with the modulus of the table's `volume`; the key on a body
/// without volume elements (cloth, rope, obj shell) is an error.
fn volume_elements(
    src: &Source<'_>,
    at: &At,
    body: Body,
    setting: Option<&Spanned<VolumeSetting>>,
) -> Result<Body, SceneFileError> {
    let Some(setting) = setting else {
        return Ok(body);
    };
    let volume_key = key(&at.key, "volume");
    if body.tets().is_empty() {
        return Err(src.invalid(
            setting.span(),
            volume_key,
            "`volume` on a body without volume elements",
            "no `volume`: only `lattice`, `tet-mesh` and `layered` bodies have volume elements (cloth, ropes and obj shells have none)",
        ));
    }
    let volume = volume(src, setting, &volume_key)?;
    body.volume(volume)
        .map_err(|e| src.scene(e, setting.span(), &volume_key))
}

/// What every body table has besides its geometry and material.
pub(crate) struct Common {
    /// `name`.
    pub(crate) name: Option<String>,
    /// `pins`.
    pub(crate) pins: Vec<Spanned<PinRef>>,
    /// `moving_pins`.
    pub(crate) moving_pins: Vec<Spanned<MovingPin>>,
}

/// The names a body's pins may use besides indices.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum PinNames {
    /// Corners and edges of a cloth of `columns × rows` particles.
    Cloth {
        /// Particles per row.
        columns: usize,
        /// Rows.
        rows: usize,
    },
    /// `start` and `end` of a rope with `segments` segments.
    Rope {
        /// Segments.
        segments: usize,
    },
    /// Indices only.
    None,
}

/// A body read from its table, before it goes into the system.
pub(crate) struct Built {
    /// The body, without its pins.
    pub(crate) body: Body,
    /// The names its pins may use.
    pub(crate) names: PinNames,
    /// Name and pins.
    pub(crate) common: Common,
}

/// The spring family `field` of the body at `prefix`, if given.
pub(crate) fn family(
    src: &Source<'_>,
    table: Option<&Spanned<SpringsTable>>,
    prefix: &str,
    field: &str,
) -> Result<Option<Springs>, SceneFileError> {
    table
        .map(|t| springs(src, t, &key(prefix, field)))
        .transpose()
}

/// `n` if it is at most [`MAX_PARTICLES`].
pub(crate) fn within_limit(
    src: &Source<'_>,
    n: Option<usize>,
    span: Range<usize>,
    key: &str,
) -> Result<usize, SceneFileError> {
    n.filter(|&n| n <= MAX_PARTICLES).ok_or_else(|| {
        src.invalid(
            span,
            key,
            "more particles than a scene file may hold",
            format!("at most {MAX_PARTICLES} particles"),
        )
    })
}

/// A mesh's `scale` (default 1), checked.
pub(crate) fn scale(
    src: &Source<'_>,
    s: Option<&Spanned<f64>>,
    at: &At,
) -> Result<f64, SceneFileError> {
    s.map_or(Ok(1.0), |s| {
        positive(src, s, &key(&at.key, "scale"), "a factor")
    })
}
