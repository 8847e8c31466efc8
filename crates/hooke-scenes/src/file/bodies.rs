//! What every `[[bodies]]` table shares — name, pins, scripted pins,
//! spring families — and what reading one produces.

use std::ops::Range;

use toml::Spanned;

use super::MAX_PARTICLES;
use super::error::{SceneFileError, Source};
use super::schema::{MovingPin, PinRef, SpringsTable};
use super::values::{key, positive, springs};
use crate::{Body, Springs};

/// Where a table is: its dotted key and its span in the file.
pub(crate) struct At {
    /// The dotted key, e.g. `bodies[2]`.
    pub(crate) key: String,
    /// The table's span (its header, for `[[bodies]]`).
    pub(crate) span: Range<usize>,
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
