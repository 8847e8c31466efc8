//! Reading `[[bodies]]` and `[[obstacles]]`: each table is deserialized as
//! the kind its `type` or `shape` names, so unknown keys are reported
//! against that kind's keys.

use hooke_core::Obstacle;
use serde::de::DeserializeOwned;
use toml::Spanned;
use toml::de::{DeValue, ValueDeserializer};

use super::bodies::{At, Built};
use super::error::{ErrorKind, SceneFileError, Source};
use super::meshes::{self, Meshes};
use super::{cloth, lattice, obstacles, rope, values};

/// The body types, the values of a body's `type`.
const BODY_TYPES: [&str; 6] = ["cloth", "rope", "lattice", "tet-mesh", "layered", "obj"];

/// The obstacle shapes, the values of an obstacle's `shape`.
const SHAPES: [&str; 4] = ["plane", "sphere", "box", "capsule"];

/// The tables of an array of tables (`[[bodies]]`), none if absent.
pub(crate) fn tables<'i>(
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
            format!("a value of type {}", other.type_str()),
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
            format!("a value of type {}", value.get_ref().type_str()),
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
            format!("a value of type {}", tagged.get_ref().type_str()),
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
pub(crate) fn body(
    src: &Source<'_>,
    meshes: Meshes<'_>,
    value: Spanned<DeValue<'_>>,
    at: &At,
) -> Result<(String, Built), SceneFileError> {
    let kind = tag(src, &value, "type", &BODY_TYPES, at)?;
    let built = match kind.as_str() {
        "cloth" => cloth::cloth(src, read(src, value, at)?, at),
        "rope" => rope::rope(src, read(src, value, at)?, at),
        "lattice" => lattice::lattice(src, read(src, value, at)?, at),
        "tet-mesh" => meshes::tet_mesh(src, meshes, read(src, value, at)?, at),
        "layered" => meshes::layered(src, meshes, read(src, value, at)?, at),
        _ => meshes::obj_shell(src, meshes, read(src, value, at)?, at),
    }?;
    Ok((kind, built))
}

/// One `[[obstacles]]` table.
pub(crate) fn obstacle(
    src: &Source<'_>,
    value: Spanned<DeValue<'_>>,
    at: &At,
) -> Result<Obstacle, SceneFileError> {
    match tag(src, &value, "shape", &SHAPES, at)?.as_str() {
        "plane" => obstacles::plane(src, &read(src, value, at)?, at),
        "sphere" => obstacles::sphere(src, &read(src, value, at)?, at),
        "box" => obstacles::cuboid(src, &read(src, value, at)?, at),
        _ => obstacles::capsule(src, &read(src, value, at)?, at),
    }
}
