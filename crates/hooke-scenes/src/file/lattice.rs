//! `type = "lattice"`: a box of cubes or tetrahedra.

use serde::Deserialize;
use toml::Spanned;

use super::bodies::{At, Built, PinNames, family, finish, shared, within_limit};
use super::error::{SceneFileError, Source};
use super::schema::{MovingPin, PinRef, SpringsTable, Vector, VolumeSetting};
use super::values::{key, positive_vector, vector};
use crate::{Lattice, TetSplit};

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
    self_collision: Option<Spanned<bool>>,
    volume: Option<Spanned<VolumeSetting>>,
    thickness: Option<Spanned<f64>>,
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
        lattice = lattice.size(positive_vector(src, size, &key(&at.key, "size"))?);
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
    finish(src, at, at, lattice, shared!(t), ("kg/m³", PinNames::None))
}
