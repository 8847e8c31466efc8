//! `summary.json`'s `implicit_settings`: the [`ImplicitSettings`] of a run
//! as the map of their keys ([`ImplicitSettings::keys`]: the keys of a
//! scene file's `[integrator]` table, each enum by its table's name), read
//! back by [`ImplicitSettings::from_keys`].

use hooke_implicit::{ImplicitSettings, KeyValue};
use serde::de::Error as _;
use serde::ser::SerializeMap;
use serde::{Deserialize, Deserializer, Serializer};
use serde_json::{Map, Value};

/// Writes `settings` as the map of their keys, or `null`.
pub(crate) fn serialize<S: Serializer>(
    settings: &Option<ImplicitSettings>,
    serializer: S,
) -> Result<S::Ok, S::Error> {
    let Some(settings) = settings else {
        return serializer.serialize_none();
    };
    let keys = settings.keys();
    let mut map = serializer.serialize_map(Some(keys.len()))?;
    for (key, value) in keys {
        match value {
            KeyValue::Name(name) => map.serialize_entry(key, name)?,
            KeyValue::Count(n) => map.serialize_entry(key, &n)?,
            KeyValue::Number(x) => map.serialize_entry(key, &x)?,
            KeyValue::Switch(b) => map.serialize_entry(key, &b)?,
        }
    }
    map.end()
}

/// Reads a map of keys as settings ([`ImplicitSettings::from_keys`]), or
/// `null` as none; a key or value the settings do not take is an error
/// naming it.
pub(crate) fn deserialize<'de, D: Deserializer<'de>>(
    deserializer: D,
) -> Result<Option<ImplicitSettings>, D::Error> {
    let Some(map) = Option::<Map<String, Value>>::deserialize(deserializer)? else {
        return Ok(None);
    };
    let mut keys = Vec::with_capacity(map.len());
    for (key, value) in &map {
        let value = match value {
            Value::String(name) => KeyValue::Name(name),
            Value::Bool(b) => KeyValue::Switch(*b),
            Value::Number(n) => match (n.as_u64(), n.as_f64()) {
                (Some(count), _) => KeyValue::Count(count),
                (None, Some(x)) => KeyValue::Number(x),
                (None, None) => return Err(D::Error::custom(format!("{key}: got {n}"))),
            },
            other => {
                return Err(D::Error::custom(format!(
                    "{key}: got {other}, expected a name, a number, true or false"
                )));
            }
        };
        keys.push((key.as_str(), value));
    }
    ImplicitSettings::from_keys(keys)
        .map(Some)
        .map_err(D::Error::custom)
}
