//! [`Range`]: log-spaced values, as the command line writes them
//! (`1e-5:1e-1:13`).

use std::str::FromStr;

use crate::LabError;

/// `count` values from `first` to `last`, evenly spaced in `log`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// The first value.
    pub first: f64,
    /// The last value.
    pub last: f64,
    /// How many values (one gives `first` alone).
    pub count: usize,
}

impl Range {
    /// The range from `first` to `last` in `count` values.
    #[must_use]
    pub fn new(first: f64, last: f64, count: usize) -> Self {
        Self { first, last, count }
    }

    /// The values `10^(a + (b − a)·k/(count − 1))`, `k = 0..count`, with
    /// `a = log₁₀ first`, `b = log₁₀ last` and the ends exact, so decades
    /// fall on powers of ten.
    ///
    /// ```
    /// let dts = hooke_lab::Range::new(1e-3, 1e-1, 3).values();
    /// assert_eq!(dts, [1e-3, 1e-2, 1e-1]);
    /// ```
    #[must_use]
    pub fn values(&self) -> Vec<f64> {
        if self.count == 1 {
            return vec![self.first];
        }
        let (a, b) = (self.first.log10(), self.last.log10());
        let last = self.count.saturating_sub(1);
        (0..self.count)
            .map(|k| match k {
                0 => self.first,
                k if k == last => self.last,
                k => 10f64.powf(a + (b - a) * k as f64 / last as f64),
            })
            .collect()
    }
}

impl FromStr for Range {
    type Err = LabError;

    /// `FIRST:LAST:COUNT` (both ends positive, COUNT ≥ 2), or a single
    /// positive `VALUE`.
    fn from_str(text: &str) -> Result<Self, LabError> {
        let invalid = || LabError::Invalid {
            name: "range",
            value: text.to_owned(),
            expected: "FIRST:LAST:COUNT with positive ends and COUNT ≥ 2, or one positive value",
        };
        let number = |s: &str| {
            s.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite() && *v > 0.0)
                .ok_or_else(invalid)
        };
        let parts: Vec<&str> = text.split(':').collect();
        match parts[..] {
            [value] => Ok(Self::new(number(value)?, number(value)?, 1)),
            [first, last, count] => {
                let count = count
                    .trim()
                    .parse::<usize>()
                    .ok()
                    .filter(|&c| c >= 2)
                    .ok_or_else(invalid)?;
                Ok(Self::new(number(first)?, number(last)?, count))
            }
            _ => Err(invalid()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_ranges_and_single_values() {
        let r: Range = "1e-5:1e-1:13".parse().unwrap();
        let v = r.values();
        assert_eq!(v.len(), 13);
        assert!((v[3] / v[0] - 10.0).abs() < 1e-12);
        assert!((v[12] - 0.1).abs() < 1e-15);
        assert_eq!("2".parse::<Range>().unwrap().values().len(), 1);
    }

    #[test]
    fn rejects_what_is_not_a_range() {
        for bad in [
            "", "0:1:3", "1:-1:3", "1:10:1", "1:10", "a:b:c", "1:10:3:4", "inf",
        ] {
            let error = bad.parse::<Range>().unwrap_err();
            assert!(
                error.to_string().contains("FIRST:LAST:COUNT"),
                "{bad}: {error}"
            );
        }
    }
}
