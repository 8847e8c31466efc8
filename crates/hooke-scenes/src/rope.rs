//! [`Rope`]: a chain of particles between two points.

use crate::body::Body;
use crate::error::{SceneError, count, finite_vector, grid_points};
use crate::material::{Mass, Springs};
use crate::spring::{Family, SpringSet, validate_families};

/// A straight rope of `segments` equal segments from `start` to `end`:
/// particles `0..=segments`, particle 0 at `start`.
///
/// ```
/// use hooke_scenes::{Family, Mass, Rope, Springs};
/// let rope = Rope::between([0.0, 0.0, 0.0], [2.0, 0.0, 0.0], 20)
///     .mass(Mass::Density(0.05))
///     .stretch(Springs::modulus(800.0).damping(0.01))
///     .bend(1.0)
///     .pin_start()
///     .build()?;
/// assert_eq!(rope.particle_count(), 21);
/// assert_eq!(rope.springs_of(Family::Bend).count(), 19);
/// # Ok::<(), hooke_scenes::SceneError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
#[must_use]
pub struct Rope {
    start: [f64; 3],
    end: [f64; 3],
    segments: usize,
    mass: Mass,
    stretch: Option<Springs>,
    bend: Option<Springs>,
    pin_start: bool,
    pin_end: bool,
    rest_length_fraction: f64,
}

impl Rope {
    /// A rope of `segments` segments (at least 1) from `start` to `end`,
    /// 0.1 kg/m, unpinned, with no springs until a family is set.
    pub fn between(start: [f64; 3], end: [f64; 3], segments: usize) -> Self {
        Self {
            start,
            end,
            segments,
            mass: Mass::Density(0.1),
            stretch: None,
            bend: None,
            pin_start: false,
            pin_end: false,
            rest_length_fraction: 1.0,
        }
    }

    /// Total mass, or linear density in kg/m; lumped half of each segment's
    /// mass to each of its ends.
    ///
    /// ```
    /// use hooke_scenes::{Mass, Rope};
    /// let rope = Rope::between([0.0; 3], [1.0, 0.0, 0.0], 2).mass(Mass::Total(1.0)).build()?;
    /// assert_eq!(rope.masses(), [0.25, 0.5, 0.25]);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn mass(mut self, mass: Mass) -> Self {
        self.mass = mass;
        self
    }

    /// Springs between neighbours along the rope, one per segment.
    ///
    /// ```
    /// let rope = hooke_scenes::Rope::between([0.0; 3], [1.0, 0.0, 0.0], 4).stretch(1e3).build()?;
    /// assert_eq!(rope.springs().len(), 4);
    /// assert_eq!(rope.springs()[0].rest_length, 0.25);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn stretch(mut self, springs: impl Into<Springs>) -> Self {
        self.stretch = Some(springs.into());
        self
    }

    /// Bending springs between particles two apart, `segments − 1` of them.
    ///
    /// ```
    /// let rope = hooke_scenes::Rope::between([0.0; 3], [1.0, 0.0, 0.0], 4).bend(5.0).build()?;
    /// assert_eq!(rope.springs().len(), 3);
    /// assert_eq!(rope.springs()[0].rest_length, 0.5);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn bend(mut self, springs: impl Into<Springs>) -> Self {
        self.bend = Some(springs.into());
        self
    }

    /// Every spring's rest length as a fraction of its length in the
    /// initial shape (default 1: the rope starts unstretched). Below 1 the
    /// rope starts stretched; at 0 its springs have zero rest length and
    /// are exactly linear, `f = −k (xᵢ − xⱼ)`, at any extension — the
    /// textbook linear spring. A stiffness given as a modulus is still
    /// divided by the segment's initial length.
    ///
    /// ```
    /// let rope = hooke_scenes::Rope::between([0.0; 3], [0.0, -1.0, 0.0], 1)
    ///     .stretch(1.0)
    ///     .rest_length_fraction(0.0)
    ///     .build()?;
    /// assert_eq!(rope.springs()[0].rest_length, 0.0);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn rest_length_fraction(mut self, fraction: f64) -> Self {
        self.rest_length_fraction = fraction;
        self
    }

    /// Pins particle 0, at `start`.
    ///
    /// ```
    /// let rope = hooke_scenes::Rope::between([0.0; 3], [1.0, 0.0, 0.0], 3).pin_start().build()?;
    /// assert_eq!(rope.pins(), [0]);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn pin_start(mut self) -> Self {
        self.pin_start = true;
        self
    }

    /// Pins the last particle, at `end`.
    ///
    /// ```
    /// let rope = hooke_scenes::Rope::between([0.0; 3], [1.0, 0.0, 0.0], 3).pin_end().build()?;
    /// assert_eq!(rope.pins(), [3]);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn pin_end(mut self) -> Self {
        self.pin_end = true;
        self
    }

    /// Validates the description and builds the body, whose segment list
    /// is the polyline `[k, k + 1]`; a rope has no surface triangles.
    ///
    /// # Errors
    /// [`SceneError`] naming the first bad field: no segments, an end point
    /// that is not finite, coinciding end points, a rest-length fraction
    /// that is negative or not finite, or a mass or spring parameter out
    /// of range.
    pub fn build(self) -> Result<Body, SceneError> {
        let n = count("rope segments", self.segments, 1)?;
        grid_points("rope segments", &[n], 1)?;
        let start = finite_vector("rope start", self.start)?;
        let end = finite_vector("rope end", self.end)?;
        let length = (end - start).norm();
        if length <= 0.0 {
            return Err(SceneError::InvalidVector {
                field: "rope end",
                value: self.end,
                requirement: "different from the start",
            });
        }
        let fraction = self.rest_length_fraction;
        if !(fraction.is_finite() && fraction >= 0.0) {
            return Err(SceneError::InvalidValue {
                field: "rope rest-length fraction",
                value: fraction,
                requirement: "finite and non-negative",
            });
        }
        let segment_mass = self.mass.total(length)? / n as f64;
        validate_families(&[(Family::Stretch, self.stretch), (Family::Bend, self.bend)])?;
        let positions: Vec<_> = (0..=n)
            .map(|k| start + (end - start) * (k as f64 / n as f64))
            .collect();
        let masses = (0..=n)
            .map(|k| {
                if k == 0 || k == n {
                    segment_mass / 2.0
                } else {
                    segment_mass
                }
            })
            .collect();
        let mut springs = SpringSet::new(&positions);
        for k in 0..n {
            springs.add(k, k + 1, Family::Stretch, self.stretch)?;
        }
        for k in 1..n {
            springs.add(k - 1, k + 1, Family::Bend, self.bend)?;
        }
        let pins = [(self.pin_start, 0), (self.pin_end, n)]
            .into_iter()
            .filter_map(|(pinned, p)| pinned.then_some(p))
            .collect();
        let segments = (0..n).map(|k| [k, k + 1]).collect();
        let mut springs = springs.into_springs();
        for spring in &mut springs {
            spring.rest_length *= fraction;
        }
        Body::from_parts(
            masses,
            positions,
            springs,
            pins,
            (Vec::new(), false),
            segments,
        )
    }
}
