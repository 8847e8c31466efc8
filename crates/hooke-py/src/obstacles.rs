//! Obstacles as dicts, under the keys of a scene file's `[[obstacles]]`
//! tables: `shape` and its geometry, `friction`, `restitution`, and a
//! motion, `velocity` or `keyframes`.

use hooke_core::{Mat3, Obstacle, Path, Shape, Vec3};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::Reader;
use crate::errors::scene_error;

/// The keys each shape takes besides the ones every obstacle takes.
const SHAPES: [(&str, &[&str]); 4] = [
    ("plane", &["point", "normal"]),
    ("sphere", &["center", "radius"]),
    ("box", &["center", "half_extents", "rotation"]),
    ("capsule", &["a", "b", "radius"]),
];

/// The keys every obstacle takes.
const COMMON: [&str; 5] = ["shape", "friction", "restitution", "velocity", "keyframes"];

/// The obstacle `dict` describes, the `k`-th in its list (for messages):
/// `{"shape": "sphere", "center": [0, 0.18, 0], "radius": 0.18,
/// "friction": 0.5}`. A plane's `point` defaults to the origin and its
/// `normal` to +y, a box's `rotation` (a 3 × 3 matrix whose columns are
/// the box's axes) to none, `friction` and `restitution` to 0.
pub(crate) fn from_dict(k: usize, dict: &Bound<'_, PyAny>) -> PyResult<Obstacle> {
    let at = format!("obstacles[{k}]");
    let dict = dict
        .cast::<PyDict>()
        .map_err(|_| scene_error(format!("{at}: expected a dict, got {dict}")))?;
    let get = |key: &str| dict.get_item(key);
    let shape: String = match get("shape")? {
        Some(shape) => shape
            .extract()
            .map_err(|_| scene_error(format!("{at}.shape: expected a name, got {shape}")))?,
        None => return Err(scene_error(format!("{at}: missing key `shape`"))),
    };
    let Some((_, keys)) = SHAPES.iter().find(|(name, _)| *name == shape) else {
        let names: Vec<String> = SHAPES.iter().map(|(n, _)| format!("\"{n}\"")).collect();
        return Err(scene_error(format!(
            "{at}.shape: got \"{shape}\", expected one of {}",
            names.join(", ")
        )));
    };
    for key in dict.keys() {
        let key: String = key.extract()?;
        if !(COMMON.contains(&key.as_str()) || keys.contains(&key.as_str())) {
            let allowed: Vec<String> = COMMON
                .iter()
                .chain(keys.iter())
                .map(|k| format!("`{k}`"))
                .collect();
            return Err(scene_error(format!(
                "{at}.{key}: no such key for a {shape}; one of {}",
                allowed.join(", ")
            )));
        }
    }
    let reader = |key: &str| Reader {
        name: format!("{at}.{key}"),
        make: scene_error_from_string,
    };
    let vector = |key: &str, default: Option<Vec3>| -> PyResult<Vec3> {
        match (get(key)?, default) {
            (Some(value), _) => reader(key).vector(&value),
            (None, Some(default)) => Ok(default),
            (None, None) => Err(scene_error(format!("{at}: missing key `{key}`"))),
        }
    };
    let number = |key: &str, default: Option<f64>| -> PyResult<f64> {
        match (get(key)?, default) {
            (Some(value), _) => reader(key).number(&value),
            (None, Some(default)) => Ok(default),
            (None, None) => Err(scene_error(format!("{at}: missing key `{key}`"))),
        }
    };
    let shape = match shape.as_str() {
        "plane" => Shape::Plane {
            point: vector("point", Some(Vec3::zeros()))?,
            normal: vector("normal", Some(Vec3::y()))?,
        },
        "sphere" => Shape::Sphere {
            center: vector("center", None)?,
            radius: number("radius", None)?,
        },
        "box" => Shape::Box {
            center: vector("center", None)?,
            half_extents: vector("half_extents", None)?,
            rotation: match get("rotation")? {
                Some(value) => {
                    let rows = reader("rotation").vectors(&value, Some(3))?;
                    Mat3::from_rows(&[
                        rows[0].transpose(),
                        rows[1].transpose(),
                        rows[2].transpose(),
                    ])
                }
                None => Mat3::identity(),
            },
        },
        _ => Shape::Capsule {
            a: vector("a", None)?,
            b: vector("b", None)?,
            radius: number("radius", None)?,
        },
    };
    let path = match (get("velocity")?, get("keyframes")?) {
        (Some(_), Some(_)) => {
            return Err(scene_error(format!(
                "{at}: `velocity` and `keyframes` both given; a motion takes one"
            )));
        }
        (Some(_), None) => Path::Linear {
            velocity: vector("velocity", None)?,
        },
        (None, Some(value)) => {
            let rows: Vec<[f64; 4]> = value
                .extract()
                .map_err(|_| scene_error(format!("{at}.keyframes: expected rows [t, x, y, z]")))?;
            Path::Keyframes(
                rows.iter()
                    .map(|r| (r[0], Vec3::new(r[1], r[2], r[3])))
                    .collect(),
            )
        }
        (None, None) => Path::Fixed,
    };
    let mut obstacle = Obstacle::new(shape);
    obstacle.path = path;
    obstacle.friction = number("friction", Some(0.0))?;
    obstacle.restitution = number("restitution", Some(0.0))?;
    Ok(obstacle)
}

fn scene_error_from_string(message: String) -> PyErr {
    scene_error(message)
}

/// `obstacle` as the dict [`from_dict`] reads back.
pub(crate) fn to_dict<'py>(py: Python<'py>, obstacle: &Obstacle) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    let v = |x: Vec3| vec![x.x, x.y, x.z];
    match obstacle.shape {
        Shape::Plane { point, normal } => {
            dict.set_item("shape", "plane")?;
            dict.set_item("point", v(point))?;
            dict.set_item("normal", v(normal))?;
        }
        Shape::Sphere { center, radius } => {
            dict.set_item("shape", "sphere")?;
            dict.set_item("center", v(center))?;
            dict.set_item("radius", radius)?;
        }
        Shape::Box {
            center,
            half_extents,
            rotation,
        } => {
            dict.set_item("shape", "box")?;
            dict.set_item("center", v(center))?;
            dict.set_item("half_extents", v(half_extents))?;
            let rows: Vec<Vec<f64>> = (0..3).map(|i| v(rotation.row(i).transpose())).collect();
            dict.set_item("rotation", rows)?;
        }
        Shape::Capsule { a, b, radius } => {
            dict.set_item("shape", "capsule")?;
            dict.set_item("a", v(a))?;
            dict.set_item("b", v(b))?;
            dict.set_item("radius", radius)?;
        }
    }
    dict.set_item("friction", obstacle.friction)?;
    dict.set_item("restitution", obstacle.restitution)?;
    match &obstacle.path {
        Path::Fixed => {}
        Path::Linear { velocity } => dict.set_item("velocity", v(*velocity))?,
        Path::Keyframes(keys) => {
            let rows: Vec<[f64; 4]> = keys.iter().map(|(t, x)| [*t, x.x, x.y, x.z]).collect();
            dict.set_item("keyframes", rows)?;
        }
    }
    Ok(dict)
}
