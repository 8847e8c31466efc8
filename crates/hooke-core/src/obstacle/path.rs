//! [`Path`]: a scripted motion of an obstacle or a pinned particle.

use crate::Vec3;

/// A scripted motion: the offset of an obstacle (or a pinned particle) from
/// its rest placement as a function of time.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Path {
    /// No motion.
    #[default]
    Fixed,
    /// Offset `u t`: constant velocity `u` in m/s.
    Linear {
        /// The velocity, m/s.
        velocity: Vec3,
    },
    /// Piecewise-linear offsets through `(time, offset)` keyframes with
    /// increasing times; constant before the first and after the last.
    Keyframes(Vec<(f64, Vec3)>),
}

impl Path {
    /// The offset at time `t`, m.
    ///
    /// ```
    /// use hooke_core::{Path, Vec3};
    /// let path = Path::Keyframes(vec![(0.0, Vec3::zeros()), (2.0, Vec3::new(0.0, 1.0, 0.0))]);
    /// assert_eq!(path.offset(1.0), Vec3::new(0.0, 0.5, 0.0));
    /// assert_eq!(path.offset(5.0), Vec3::new(0.0, 1.0, 0.0));
    /// ```
    #[must_use]
    pub fn offset(&self, t: f64) -> Vec3 {
        match self {
            Self::Fixed => Vec3::zeros(),
            Self::Linear { velocity } => t * velocity,
            Self::Keyframes(keys) => match Self::segment(keys, t) {
                Some((k, s)) => keys[k].1 + s * (keys[k + 1].1 - keys[k].1),
                None if keys.first().is_some_and(|(t0, _)| t < *t0) => keys[0].1,
                None => keys.last().map_or_else(Vec3::zeros, |(_, x)| *x),
            },
        }
    }

    /// The velocity at time `t` (on a keyframe, that of the segment after
    /// it), m/s.
    #[must_use]
    pub fn velocity(&self, t: f64) -> Vec3 {
        match self {
            Self::Fixed => Vec3::zeros(),
            Self::Linear { velocity } => *velocity,
            Self::Keyframes(keys) => Self::segment(keys, t).map_or_else(Vec3::zeros, |(k, _)| {
                (keys[k + 1].1 - keys[k].1) / (keys[k + 1].0 - keys[k].0)
            }),
        }
    }

    /// The keyframe segment `k` with `tₖ ≤ t < tₖ₊₁` and the fraction of it
    /// covered at `t`.
    fn segment(keys: &[(f64, Vec3)], t: f64) -> Option<(usize, f64)> {
        let k = keys.partition_point(|(tk, _)| *tk <= t).checked_sub(1)?;
        let (t0, t1) = (keys[k].0, keys.get(k + 1)?.0);
        Some((k, (t - t0) / (t1 - t0)))
    }

    /// The first thing wrong with the path, if any.
    pub(crate) fn problem(&self) -> Option<&'static str> {
        match self {
            Self::Fixed => None,
            Self::Linear { velocity } => {
                (!velocity.iter().all(|c| c.is_finite())).then_some("path velocity must be finite")
            }
            Self::Keyframes(keys) => {
                if keys.is_empty() {
                    Some("path keyframes must not be empty")
                } else if !keys
                    .iter()
                    .all(|(t, x)| t.is_finite() && x.iter().all(|c| c.is_finite()))
                {
                    Some("path keyframes must be finite")
                } else if !keys.windows(2).all(|w| w[0].0 < w[1].0) {
                    Some("path keyframe times must increase")
                } else {
                    None
                }
            }
        }
    }
}
