//! `[[bodies]]` of the generated kinds — `cloth`, `rope`, `lattice` — and
//! what every body table shares: name, pins and scripted pins.

use std::ops::Range;

use serde::Deserialize;
use toml::Spanned;

use super::MAX_PARTICLES;
use super::error::{SceneFileError, Source};
use super::schema::{MovingPin, PinRef, Rotation, SpringsTable, Vector};
use super::values::{count, key, mass, positive, rotation, springs, vector};
use crate::{Body, Cloth, Lattice, Plane, Rope, Springs, TetSplit};

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
fn within_limit(
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
    if let Some(m) = mass(src, t.mass.as_ref(), t.density.as_ref(), &at.key, "kg/m²")? {
        cloth = cloth.mass(m);
    }
    Ok(Built {
        body: cloth
            .build()
            .map_err(|e| src.scene(e, at.span.clone(), &at.key))?,
        names: PinNames::Cloth { columns, rows },
        common: Common {
            name: t.name,
            pins: t.pins,
            moving_pins: t.moving_pins,
        },
    })
}

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
    #[serde(default)]
    pins: Vec<Spanned<PinRef>>,
    #[serde(default)]
    moving_pins: Vec<Spanned<MovingPin>>,
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
    if let Some(m) = mass(src, t.mass.as_ref(), t.density.as_ref(), &at.key, "kg/m")? {
        rope = rope.mass(m);
    }
    Ok(Built {
        body: rope
            .build()
            .map_err(|e| src.scene(e, at.span.clone(), &at.key))?,
        names: PinNames::Rope { segments },
        common: Common {
            name: t.name,
            pins: t.pins,
            moving_pins: t.moving_pins,
        },
    })
}

/// `type = "lattice"`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct LatticeTable {
    #[serde(rename = "type")]
    _kind: String,
    name: Option<String>,
    cells: Spanned<[usize; 3]>,
    connectivity: Option<Spanned<String>>,
    size: Option<Vector>,
    origin: Option<Vector>,
    edges: Option<Spanned<SpringsTable>>,
    face_diagonals: Option<Spanned<SpringsTable>>,
    body_diagonals: Option<Spanned<SpringsTable>>,
    mass: Option<Spanned<f64>>,
    density: Option<Spanned<f64>>,
    #[serde(default)]
    pins: Vec<Spanned<PinRef>>,
    #[serde(default)]
    moving_pins: Vec<Spanned<MovingPin>>,
}

/// Builds a box lattice.
pub(crate) fn lattice(src: &Source<'_>, t: LatticeTable, at: &At) -> Result<Built, SceneFileError> {
    let cells = *t.cells.get_ref();
    if cells.contains(&0) {
        return Err(src.invalid(
            t.cells.span(),
            key(&at.key, "cells"),
            format!("{cells:?}"),
            "three cell counts ≥ 1",
        ));
    }
    let points = cells
        .iter()
        .try_fold(1usize, |n, &c| n.checked_mul(c.checked_add(1)?));
    within_limit(src, points, t.cells.span(), &key(&at.key, "cells"))?;
    let [nx, ny, nz] = cells;
    let mut lattice = match t
        .connectivity
        .as_ref()
        .map(|c| (c.get_ref().as_str(), c.span()))
    {
        None | Some(("cubes", _)) => Lattice::cubes(nx, ny, nz),
        Some(("tets-5", _)) => Lattice::tets(nx, ny, nz, TetSplit::Five),
        Some(("tets-6", _)) => Lattice::tets(nx, ny, nz, TetSplit::Six),
        Some((other, span)) => {
            return Err(src.invalid(
                span,
                key(&at.key, "connectivity"),
                format!("\"{other}\""),
                "\"cubes\", \"tets-5\" or \"tets-6\"",
            ));
        }
    };
    if let Some(size) = &t.size {
        lattice = lattice.size(super::values::positive_vector(
            src,
            size,
            &key(&at.key, "size"),
        )?);
    }
    if let Some(origin) = &t.origin {
        lattice = lattice.origin(vector(src, origin, &key(&at.key, "origin"))?.into());
    }
    if let Some(s) = family(src, t.edges.as_ref(), &at.key, "edges")? {
        lattice = lattice.edges(s);
    }
    if let Some(s) = family(src, t.face_diagonals.as_ref(), &at.key, "face_diagonals")? {
        lattice = lattice.face_diagonals(s);
    }
    if let Some(s) = family(src, t.body_diagonals.as_ref(), &at.key, "body_diagonals")? {
        lattice = lattice.body_diagonals(s);
    }
    if let Some(m) = mass(src, t.mass.as_ref(), t.density.as_ref(), &at.key, "kg/m³")? {
        lattice = lattice.mass(m);
    }
    Ok(Built {
        body: lattice
            .build()
            .map_err(|e| src.scene(e, at.span.clone(), &at.key))?,
        names: PinNames::None,
        common: Common {
            name: t.name,
            pins: t.pins,
            moving_pins: t.moving_pins,
        },
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
