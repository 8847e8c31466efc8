//! `type = "rope"`: a chain of particles between two points.

use serde::Deserialize;
use toml::Spanned;

use super::bodies::{At, Built, PinNames, family, finish, shared, within_limit};
use super::error::{SceneFileError, Source};
use super::schema::{MovingPin, PinRef, SpringsTable, Vector, VolumeSetting};
use super::values::{count, key, non_negative, vector};
use crate::Rope;

/// `type = "rope"`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RopeTable {
    #[serde(rename = "type")]
    _kind: String,
    name: Option<String>,
    start: Vector,
    end: Vector,
    segments: Spanned<usize>,
    stretch: Option<Spanned<SpringsTable>>,
    bend: Option<Spanned<SpringsTable>>,
    mass: Option<Spanned<f64>>,
    density: Option<Spanned<f64>>,
    rest_length_fraction: Option<Spanned<f64>>,
    #[serde(default)]
    pins: Vec<Spanned<PinRef>>,
    #[serde(default)]
    moving_pins: Vec<Spanned<MovingPin>>,
    self_collision: Option<Spanned<bool>>,
    volume: Option<Spanned<VolumeSetting>>,
    thickness: Option<Spanned<f64>>,
}

/// Builds a rope.
pub(crate) fn rope(src: &Source<'_>, t: RopeTable, at: &At) -> Result<Built, SceneFileError> {
    let segments = count(src, &t.segments, &key(&at.key, "segments"), 1)?;
    within_limit(
        src,
        segments.checked_add(1),
        t.segments.span(),
        &key(&at.key, "segments"),
    )?;
    let start = vector(src, &t.start, &key(&at.key, "start"))?;
    let end = vector(src, &t.end, &key(&at.key, "end"))?;
    if start == end {
        return Err(src.invalid(
            t.end.span(),
            key(&at.key, "end"),
            format!("{:?}", t.end.get_ref()),
            "a point different from `start`",
        ));
    }
    let mut rope = Rope::between(start.into(), end.into(), segments);
    if let Some(s) = family(src, t.stretch.as_ref(), &at.key, "stretch")? {
        rope = rope.stretch(s);
    }
    if let Some(s) = family(src, t.bend.as_ref(), &at.key, "bend")? {
        rope = rope.bend(s);
    }
    if let Some(fraction) = &t.rest_length_fraction {
        let key = key(&at.key, "rest_length_fraction");
        rope =
            rope.rest_length_fraction(non_negative(src, fraction, &key, "of the initial length")?);
    }
    finish(
        src,
        at,
        at,
        rope,
        shared!(t),
        ("kg/m", PinNames::Rope { segments }),
    )
}
