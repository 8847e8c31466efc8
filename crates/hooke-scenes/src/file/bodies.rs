//! What every `[[bodies]]` table shares — name, pins, scripted pins,
//! spring families — and what reading one produces.

use std::ops::Range;

use toml::Spanned;

use super::MAX_PARTICLES;
use super::error::{SceneFileError, Source};
use super::schema::{MovingPin, PinRef, SpringsTable};
use super::values::{key, mass, positive, springs};
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
}

/// The [`Shared`] keys of a body table `t`, moved out of it.
macro_rules! shared {
    ($t:expr) => {
        $crate::file::bodies::Shared {
            name: $t.name,
            mass: $t.mass,
            density: $t.density,
            pins: $t.pins,
            moving_pins: $t.moving_pins,
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
/// `built_at`) and keeps its name and pins.
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
