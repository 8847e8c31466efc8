//! The tables of a scene file as the TOML reader sees them: every key
//! optional where the format has a default, every value that is checked
//! afterwards kept with its place in the file.

use std::fmt;

use serde::Deserialize;
use serde::de::value::MapAccessDeserializer;
use serde::de::{self, Deserializer, IgnoredAny, MapAccess, Visitor};
use toml::Spanned;

/// A 3-vector with its place in the file.
pub(crate) type Vector = Spanned<[f64; 3]>;

/// The top level of a scene file. Bodies and obstacles are read one by one
/// afterwards, each by the table its `type` or `shape` names.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct Header {
    pub(crate) name: Option<String>,
    pub(crate) simulation: Option<Simulation>,
    pub(crate) integrator: Option<Spanned<IntegratorTable>>,
    pub(crate) world: Option<World>,
    #[serde(rename = "bodies")]
    pub(crate) _bodies: Option<IgnoredAny>,
    #[serde(rename = "obstacles")]
    pub(crate) _obstacles: Option<IgnoredAny>,
}

/// `[simulation]`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct Simulation {
    pub(crate) duration: Option<Spanned<f64>>,
    pub(crate) dt: Option<Spanned<f64>>,
    pub(crate) frame_rate: Option<Spanned<f64>>,
}

/// `[integrator]`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct IntegratorTable {
    pub(crate) method: Option<Spanned<String>>,
    pub(crate) solver: Option<Spanned<String>>,
    pub(crate) weak_springs: Option<Spanned<String>>,
    pub(crate) supernodes: Option<Spanned<String>>,
    pub(crate) amg_renewal: Option<Spanned<String>>,
    pub(crate) step: Option<Spanned<String>>,
    pub(crate) history: Option<Spanned<usize>>,
    pub(crate) carried_pairs: Option<Spanned<usize>>,
    pub(crate) tolerance: Option<Spanned<f64>>,
    pub(crate) max_iterations: Option<Spanned<usize>>,
    pub(crate) newton_iterations: Option<Spanned<usize>>,
    pub(crate) newton_tolerance: Option<Spanned<f64>>,
    pub(crate) inexact_newton: Option<Spanned<bool>>,
    pub(crate) max_halvings: Option<Spanned<u32>>,
    pub(crate) strict: Option<Spanned<bool>>,
    pub(crate) compressed_springs: Option<Spanned<String>>,
    pub(crate) rtol: Option<Spanned<f64>>,
    pub(crate) atol: Option<Spanned<f64>>,
    pub(crate) contact_limit: Option<Spanned<String>>,
    pub(crate) iterations: Option<Spanned<usize>>,
}

/// `[world]`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct World {
    pub(crate) gravity: Option<Vector>,
    pub(crate) air_damping: Option<Spanned<f64>>,
    pub(crate) contact_distance: Option<Spanned<f64>>,
    pub(crate) wind: Option<WindTable>,
}

/// `[world] wind = { velocity = [x, y, z], drag = c }`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct WindTable {
    pub(crate) velocity: Vector,
    pub(crate) drag: Spanned<f64>,
}

/// A spring family: `{ stiffness = k, damping = c }` or
/// `{ modulus = E, damping = c }`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SpringsTable {
    pub(crate) stiffness: Option<Spanned<f64>>,
    pub(crate) modulus: Option<Spanned<f64>>,
    pub(crate) damping: Option<Spanned<f64>>,
}

/// `{ axis = [x, y, z], degrees = a }`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct Rotation {
    pub(crate) axis: Vector,
    pub(crate) degrees: Spanned<f64>,
}

/// A scripted pin: `particle`, and `velocity` or `keyframes`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct MovingPin {
    pub(crate) particle: Spanned<PinRef>,
    pub(crate) velocity: Option<Vector>,
    pub(crate) keyframes: Option<Spanned<Vec<Spanned<[f64; 4]>>>>,
}

/// A particle named in `pins` or `moving_pins`: an index or, for cloth and
/// ropes, a name.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum PinRef {
    /// A particle index within the body.
    Index(usize),
    /// A corner, edge or end.
    Name(String),
}

impl fmt::Display for PinRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Index(i) => write!(f, "{i}"),
            Self::Name(name) => write!(f, "\"{name}\""),
        }
    }
}

impl<'de> Deserialize<'de> for PinRef {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct PinVisitor;

        impl Visitor<'_> for PinVisitor {
            type Value = PinRef;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a particle index (an integer ≥ 0) or a pin name (a string)")
            }

            fn visit_i64<E: de::Error>(self, v: i64) -> Result<PinRef, E> {
                usize::try_from(v)
                    .map(PinRef::Index)
                    .map_err(|_| E::invalid_value(de::Unexpected::Signed(v), &self))
            }

            fn visit_u64<E: de::Error>(self, v: u64) -> Result<PinRef, E> {
                usize::try_from(v)
                    .map(PinRef::Index)
                    .map_err(|_| E::invalid_value(de::Unexpected::Unsigned(v), &self))
            }

            fn visit_str<E: de::Error>(self, v: &str) -> Result<PinRef, E> {
                Ok(PinRef::Name(v.to_owned()))
            }
        }

        deserializer.deserialize_any(PinVisitor)
    }
}

/// A body's `volume`: `true` (the default modulus, from the springs),
/// `false` (no volume energy) or `{ modulus = κ }`.
pub(crate) enum VolumeSetting {
    /// `true` or `false`.
    Switch(bool),
    /// `{ modulus = κ }`, Pa.
    Modulus(Spanned<f64>),
}

/// `{ modulus = κ }`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct VolumeTable {
    modulus: Spanned<f64>,
}

impl<'de> Deserialize<'de> for VolumeSetting {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct VolumeVisitor;

        impl<'de> Visitor<'de> for VolumeVisitor {
            type Value = VolumeSetting;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("`true`, `false` or a table `{ modulus = κ }` (Pa)")
            }

            fn visit_bool<E: de::Error>(self, v: bool) -> Result<VolumeSetting, E> {
                Ok(VolumeSetting::Switch(v))
            }

            fn visit_map<M: MapAccess<'de>>(self, map: M) -> Result<VolumeSetting, M::Error> {
                let table = VolumeTable::deserialize(MapAccessDeserializer::new(map))?;
                Ok(VolumeSetting::Modulus(table.modulus))
            }
        }

        deserializer.deserialize_any(VolumeVisitor)
    }
}
