//! Reading back the numbers of a report: JSON has no infinity, so
//! `serde_json` writes a number that is not finite as `null`.

use serde::{Deserialize, Deserializer};

/// A number written by a report, `null` read as infinity (what a ratio or
/// an error that overflowed was).
pub(crate) fn number<'de, D: Deserializer<'de>>(deserializer: D) -> Result<f64, D::Error> {
    Ok(Option::<f64>::deserialize(deserializer)?.unwrap_or(f64::INFINITY))
}
