//! `type = "cloth"`: a rectangular grid of particles.

use serde::Deserialize;
use toml::Spanned;

use super::bodies::{At, Built, PinNames, family, finish, shared, within_limit};
use super::error::{SceneFileError, Source};
use super::schema::{MovingPin, PinRef, Rotation, SpringsTable, Vector, VolumeSetting};
use super::values::{count, key, rotation, vector};
use crate::{Cloth, Plane};

/// `type = "cloth"`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ClothTable {
    #[serde(rename = "type")]
    _kind: String,
    name: Option<String>,
    columns: Spanned<usize>,
    rows: Spanned<usize>,
    size: Option<Spanned<[f64; 2]>>,
    plane: Option<Spanned<String>>,
    rotate: Option<Spanned<Rotation>>,
    offset: Option<Vector>,
    stretch: Option<Spanned<SpringsTable>>,
    shear: Option<Spanned<SpringsTable>>,
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

/// Builds a cloth.
pub(crate) fn cloth(src: &Source<'_>, t: ClothTable, at: &At) -> Result<Built, SceneFileError> {
    let columns = count(src, &t.columns, &key(&at.key, "columns"), 2)?;
    let rows = count(src, &t.rows, &key(&at.key, "rows"), 2)?;
    within_limit(
        src,
        columns.checked_mul(rows),
        t.rows.span(),
        &key(&at.key, "rows"),
    )?;
    let mut cloth = Cloth::grid(columns, rows);
    if let Some(size) = &t.size {
        let [w, h] = *size.get_ref();
        if !(w.is_finite() && w > 0.0 && h.is_finite() && h > 0.0) {
            return Err(src.invalid(
                size.span(),
                key(&at.key, "size"),
                format!("{:?}", [w, h]),
                "[width, height], finite and > 0 (m)",
            ));
        }
        cloth = cloth.size(w, h);
    }
    if let Some(plane) = &t.plane {
        cloth = cloth.plane(match plane.get_ref().as_str() {
            "horizontal" => Plane::Horizontal,
            "vertical" => Plane::Vertical,
            other => {
                return Err(src.invalid(
                    plane.span(),
                    key(&at.key, "plane"),
                    format!("\"{other}\""),
                    "\"horizontal\" or \"vertical\"",
                ));
            }
        });
    }
    if let Some(r) = &t.rotate {
        let (axis, angle) = rotation(src, r, &key(&at.key, "rotate"))?;
        cloth = cloth.rotate(axis.into_inner().into(), angle);
    }
    if let Some(offset) = &t.offset {
        cloth = cloth.offset(vector(src, offset, &key(&at.key, "offset"))?.into());
    }
    if let Some(s) = family(src, t.stretch.as_ref(), &at.key, "stretch")? {
        cloth = cloth.stretch(s);
    }
    if let Some(s) = family(src, t.shear.as_ref(), &at.key, "shear")? {
        cloth = cloth.shear(s);
    }
    if let Some(s) = family(src, t.bend.as_ref(), &at.key, "bend")? {
        cloth = cloth.bend(s);
    }
    finish(
        src,
        at,
        at,
        cloth,
        shared!(t),
        ("kg/m²", PinNames::Cloth { columns, rows }),
    )
}
