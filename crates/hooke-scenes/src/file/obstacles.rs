//! `[[obstacles]]`: a `shape` — `plane`, `sphere`, `box` or `capsule` —
//! with its geometry, `restitution`, `friction` and an optional motion.

use hooke_core::{Mat3, Obstacle, Shape, Vec3};
use nalgebra::Rotation3;
use serde::Deserialize;
use toml::Spanned;

use super::bodies::At;
use super::error::{SceneFileError, Source};
use super::schema::{Rotation, Vector};
use super::values::{key, non_negative, path, positive, positive_vector, rotation, vector};

/// `shape = "plane"`: the half-space below the plane through `point`
/// (default the origin) with normal `normal` (default +y).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct PlaneTable {
    #[serde(rename = "shape")]
    _shape: String,
    point: Option<Vector>,
    normal: Option<Vector>,
    restitution: Option<Spanned<f64>>,
    friction: Option<Spanned<f64>>,
    velocity: Option<Vector>,
    keyframes: Option<Spanned<Vec<Spanned<[f64; 4]>>>>,
}

/// `shape = "sphere"`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SphereTable {
    #[serde(rename = "shape")]
    _shape: String,
    center: Vector,
    radius: Spanned<f64>,
    restitution: Option<Spanned<f64>>,
    friction: Option<Spanned<f64>>,
    velocity: Option<Vector>,
    keyframes: Option<Spanned<Vec<Spanned<[f64; 4]>>>>,
}

/// `shape = "box"`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct BoxTable {
    #[serde(rename = "shape")]
    _shape: String,
    center: Vector,
    half_extents: Vector,
    rotate: Option<Spanned<Rotation>>,
    restitution: Option<Spanned<f64>>,
    friction: Option<Spanned<f64>>,
    velocity: Option<Vector>,
    keyframes: Option<Spanned<Vec<Spanned<[f64; 4]>>>>,
}

/// `shape = "capsule"`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct CapsuleTable {
    #[serde(rename = "shape")]
    _shape: String,
    a: Vector,
    b: Vector,
    radius: Spanned<f64>,
    restitution: Option<Spanned<f64>>,
    friction: Option<Spanned<f64>>,
    velocity: Option<Vector>,
    keyframes: Option<Spanned<Vec<Spanned<[f64; 4]>>>>,
}

/// What every obstacle has besides its shape.
struct Response<'a> {
    restitution: Option<&'a Spanned<f64>>,
    friction: Option<&'a Spanned<f64>>,
    velocity: Option<&'a Vector>,
    keyframes: Option<&'a Spanned<Vec<Spanned<[f64; 4]>>>>,
}

/// The obstacle of `shape` with restitution (default 0, in [0, 1]),
/// friction (default 0, ≥ 0) and motion.
fn obstacle(
    src: &Source<'_>,
    shape: Shape,
    r: Response<'_>,
    at: &At,
) -> Result<Obstacle, SceneFileError> {
    let mut o = Obstacle::new(shape).moving(path(src, r.velocity, r.keyframes, &at.key)?);
    if let Some(e) = r.restitution {
        let value = *e.get_ref();
        if !(0.0..=1.0).contains(&value) {
            return Err(src.invalid(
                e.span(),
                key(&at.key, "restitution"),
                value,
                "a number in [0, 1]",
            ));
        }
        o = o.restitution(value);
    }
    if let Some(mu) = r.friction {
        o = o.friction(non_negative(
            src,
            mu,
            &key(&at.key, "friction"),
            "a coefficient",
        )?);
    }
    Ok(o)
}

/// A plane obstacle.
pub(crate) fn plane(src: &Source<'_>, t: &PlaneTable, at: &At) -> Result<Obstacle, SceneFileError> {
    let point = t.point.as_ref().map_or(Ok(Vec3::zeros()), |p| {
        vector(src, p, &key(&at.key, "point"))
    })?;
    let normal = match &t.normal {
        Some(n) => {
            let v = vector(src, n, &key(&at.key, "normal"))?;
            if v.norm() > 0.0 && v.norm().is_finite() {
                v
            } else {
                return Err(src.invalid(
                    n.span(),
                    key(&at.key, "normal"),
                    format!("{:?}", n.get_ref()),
                    "a non-zero normal of finite length",
                ));
            }
        }
        None => Vec3::y(),
    };
    let response = Response {
        restitution: t.restitution.as_ref(),
        friction: t.friction.as_ref(),
        velocity: t.velocity.as_ref(),
        keyframes: t.keyframes.as_ref(),
    };
    obstacle(src, Shape::Plane { point, normal }, response, at)
}

/// A sphere obstacle.
pub(crate) fn sphere(
    src: &Source<'_>,
    t: &SphereTable,
    at: &At,
) -> Result<Obstacle, SceneFileError> {
    let center = vector(src, &t.center, &key(&at.key, "center"))?;
    let radius = positive(src, &t.radius, &key(&at.key, "radius"), "m")?;
    let response = Response {
        restitution: t.restitution.as_ref(),
        friction: t.friction.as_ref(),
        velocity: t.velocity.as_ref(),
        keyframes: t.keyframes.as_ref(),
    };
    obstacle(src, Shape::Sphere { center, radius }, response, at)
}

/// A box obstacle.
pub(crate) fn cuboid(src: &Source<'_>, t: &BoxTable, at: &At) -> Result<Obstacle, SceneFileError> {
    let center = vector(src, &t.center, &key(&at.key, "center"))?;
    let half_extents = positive_vector(src, &t.half_extents, &key(&at.key, "half_extents"))?.into();
    let rotation: Mat3 = match &t.rotate {
        Some(r) => {
            let (axis, angle) = rotation(src, r, &key(&at.key, "rotate"))?;
            Rotation3::from_axis_angle(&axis, angle).into_inner()
        }
        None => Mat3::identity(),
    };
    let response = Response {
        restitution: t.restitution.as_ref(),
        friction: t.friction.as_ref(),
        velocity: t.velocity.as_ref(),
        keyframes: t.keyframes.as_ref(),
    };
    obstacle(
        src,
        Shape::Box {
            center,
            half_extents,
            rotation,
        },
        response,
        at,
    )
}

/// A capsule obstacle.
pub(crate) fn capsule(
    src: &Source<'_>,
    t: &CapsuleTable,
    at: &At,
) -> Result<Obstacle, SceneFileError> {
    let a = vector(src, &t.a, &key(&at.key, "a"))?;
    let b = vector(src, &t.b, &key(&at.key, "b"))?;
    let radius = positive(src, &t.radius, &key(&at.key, "radius"), "m")?;
    let response = Response {
        restitution: t.restitution.as_ref(),
        friction: t.friction.as_ref(),
        velocity: t.velocity.as_ref(),
        keyframes: t.keyframes.as_ref(),
    };
    obstacle(src, Shape::Capsule { a, b, radius }, response, at)
}
