//! Checks on single values of a scene file — numbers, vectors, spring
//! families, masses, rotations and paths — each failing with the value's
//! line and key.

use hooke_core::{Path, Vec3};
use nalgebra::Unit;
use toml::Spanned;

use super::error::{SceneFileError, Source};
use super::schema::{Rotation, SpringsTable, Vector, VolumeSetting};
use crate::{Mass, Springs, Stiffness, Volume};

/// `prefix.field`, or `field` at the top level.
pub(crate) fn key(prefix: &str, field: &str) -> String {
    if prefix.is_empty() {
        field.to_owned()
    } else {
        format!("{prefix}.{field}")
    }
}

/// A number that must be finite and positive.
pub(crate) fn positive(
    src: &Source<'_>,
    value: &Spanned<f64>,
    key: &str,
    unit: &str,
) -> Result<f64, SceneFileError> {
    let v = *value.get_ref();
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(src.invalid(
            value.span(),
            key,
            v,
            format!("a finite number > 0 ({unit})"),
        ))
    }
}

/// A number that must be finite and not negative.
pub(crate) fn non_negative(
    src: &Source<'_>,
    value: &Spanned<f64>,
    key: &str,
    unit: &str,
) -> Result<f64, SceneFileError> {
    let v = *value.get_ref();
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        Err(src.invalid(
            value.span(),
            key,
            v,
            format!("a finite number ≥ 0 ({unit})"),
        ))
    }
}

/// A count that must be at least `min`.
pub(crate) fn count(
    src: &Source<'_>,
    value: &Spanned<usize>,
    key: &str,
    min: usize,
) -> Result<usize, SceneFileError> {
    let n = *value.get_ref();
    if n >= min {
        Ok(n)
    } else {
        Err(src.invalid(value.span(), key, n, format!("an integer ≥ {min}")))
    }
}

/// A vector whose components must be finite.
pub(crate) fn vector(src: &Source<'_>, value: &Vector, key: &str) -> Result<Vec3, SceneFileError> {
    let v = *value.get_ref();
    if v.iter().all(|c| c.is_finite()) {
        Ok(v.into())
    } else {
        Err(src.invalid(value.span(), key, format!("{v:?}"), "three finite numbers"))
    }
}

/// A vector whose components must be finite and positive (sizes).
pub(crate) fn positive_vector(
    src: &Source<'_>,
    value: &Vector,
    key: &str,
) -> Result<[f64; 3], SceneFileError> {
    let v = *value.get_ref();
    if v.iter().all(|c| c.is_finite() && *c > 0.0) {
        Ok(v)
    } else {
        Err(src.invalid(
            value.span(),
            key,
            format!("{v:?}"),
            "three finite numbers > 0 (m)",
        ))
    }
}

/// A spring family: exactly one of `stiffness` (N/m) and `modulus` (N),
/// and a `damping` (N·s/m, default 0).
pub(crate) fn springs(
    src: &Source<'_>,
    table: &Spanned<SpringsTable>,
    key: &str,
) -> Result<Springs, SceneFileError> {
    let t = table.get_ref();
    let stiffness = match (&t.stiffness, &t.modulus) {
        (Some(k), None) => {
            Stiffness::PerSpring(non_negative(src, k, &self::key(key, "stiffness"), "N/m")?)
        }
        (None, Some(e)) => {
            Stiffness::Modulus(non_negative(src, e, &self::key(key, "modulus"), "N")?)
        }
        (Some(_), Some(e)) => {
            return Err(src.invalid(
                e.span(),
                self::key(key, "modulus"),
                "both `stiffness` and `modulus`",
                "one of them",
            ));
        }
        (None, None) => {
            return Err(src.invalid(
                table.span(),
                key,
                "neither `stiffness` nor `modulus`",
                "`stiffness = k` (N/m) or `modulus = E` (N)",
            ));
        }
    };
    let damping = match &t.damping {
        Some(c) => non_negative(src, c, &self::key(key, "damping"), "N·s/m")?,
        None => 0.0,
    };
    Ok(Springs { stiffness, damping })
}

/// A body's `volume`: `true` is [`Volume::Auto`], `false`
/// [`Volume::Off`], `{ modulus = κ }` a modulus, finite and ≥ 0 (Pa).
pub(crate) fn volume(
    src: &Source<'_>,
    value: &Spanned<VolumeSetting>,
    key: &str,
) -> Result<Volume, SceneFileError> {
    Ok(match value.get_ref() {
        VolumeSetting::Switch(true) => Volume::Auto,
        VolumeSetting::Switch(false) => Volume::Off,
        VolumeSetting::Modulus(kappa) => {
            Volume::Modulus(non_negative(src, kappa, &self::key(key, "modulus"), "Pa")?)
        }
    })
}

/// `mass` (kg) or `density`, at most one; `None` for the builder's default.
pub(crate) fn mass(
    src: &Source<'_>,
    mass: Option<&Spanned<f64>>,
    density: Option<&Spanned<f64>>,
    prefix: &str,
    density_unit: &str,
) -> Result<Option<Mass>, SceneFileError> {
    match (mass, density) {
        (Some(_), Some(d)) => Err(src.invalid(
            d.span(),
            key(prefix, "density"),
            "both `mass` and `density`",
            "one of them",
        )),
        (Some(m), None) => Ok(Some(Mass::Total(positive(
            src,
            m,
            &key(prefix, "mass"),
            "kg",
        )?))),
        (None, Some(d)) => Ok(Some(Mass::Density(positive(
            src,
            d,
            &key(prefix, "density"),
            density_unit,
        )?))),
        (None, None) => Ok(None),
    }
}

/// A rotation by `degrees` about a non-zero `axis`: the unit axis and the
/// angle in radians.
pub(crate) fn rotation(
    src: &Source<'_>,
    rotation: &Spanned<Rotation>,
    key: &str,
) -> Result<(Unit<Vec3>, f64), SceneFileError> {
    let r = rotation.get_ref();
    let axis_key = self::key(key, "axis");
    let axis = vector(src, &r.axis, &axis_key)?;
    let axis = Unit::try_new(axis, f64::MIN_POSITIVE).ok_or_else(|| {
        src.invalid(
            r.axis.span(),
            &axis_key,
            format!("{:?}", r.axis.get_ref()),
            "a non-zero axis",
        )
    })?;
    let degrees = *r.degrees.get_ref();
    if !degrees.is_finite() {
        return Err(src.invalid(
            r.degrees.span(),
            self::key(key, "degrees"),
            degrees,
            "a finite angle (°)",
        ));
    }
    Ok((axis, degrees.to_radians()))
}

/// A scripted motion: `velocity` (m/s) or `keyframes` `[[t, x, y, z], …]`
/// with increasing times, at most one; [`Path::Fixed`] with neither.
pub(crate) fn path(
    src: &Source<'_>,
    velocity: Option<&Vector>,
    keyframes: Option<&Spanned<Vec<Spanned<[f64; 4]>>>>,
    prefix: &str,
) -> Result<Path, SceneFileError> {
    match (velocity, keyframes) {
        (Some(_), Some(k)) => Err(src.invalid(
            k.span(),
            key(prefix, "keyframes"),
            "both `velocity` and `keyframes`",
            "one of them",
        )),
        (Some(v), None) => Ok(Path::Linear {
            velocity: vector(src, v, &key(prefix, "velocity"))?,
        }),
        (None, Some(keys)) => {
            let list_key = key(prefix, "keyframes");
            if keys.get_ref().is_empty() {
                return Err(src.invalid(
                    keys.span(),
                    list_key,
                    "[]",
                    "at least one keyframe [t, x, y, z]",
                ));
            }
            let mut frames: Vec<(f64, Vec3)> = Vec::with_capacity(keys.get_ref().len());
            for (n, frame) in keys.get_ref().iter().enumerate() {
                let [t, x, y, z] = *frame.get_ref();
                let frame_key = format!("{list_key}[{n}]");
                if ![t, x, y, z].iter().all(|c| c.is_finite()) {
                    return Err(src.invalid(
                        frame.span(),
                        frame_key,
                        format!("{:?}", [t, x, y, z]),
                        "four finite numbers [t (s), x, y, z (m)]",
                    ));
                }
                if let Some(&(before, _)) = frames.last() {
                    if t <= before {
                        return Err(src.invalid(
                            frame.span(),
                            frame_key,
                            format!("time {t}"),
                            format!("a time after the previous keyframe's {before} s"),
                        ));
                    }
                }
                frames.push((t, Vec3::new(x, y, z)));
            }
            Ok(Path::Keyframes(frames))
        }
        (None, None) => Ok(Path::Fixed),
    }
}
