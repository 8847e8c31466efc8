//! [`Body`]: what every builder produces — particles, springs, pins and
//! the surface to draw — and its [`Placement`] in a system.

use std::ops::Range;

use hooke_core::{System, SystemBuilder, Vec3};

use crate::error::{SceneError, finite_vector};
use crate::spring::{BodySpring, Family};

/// A deformable body described as particles and springs, ready to go into a
/// [`SystemBuilder`] alone or beside other bodies.
///
/// Indices in springs, pins, triangles and segments are local: `0..n` over
/// the body's own particles. Triangles are oriented counter-clockwise seen
/// from outside (their normal `(b − a) × (c − a)` points out), for writing
/// frames and rendering; segments are the polyline of a rope.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    masses: Vec<f64>,
    positions: Vec<Vec3>,
    springs: Vec<BodySpring>,
    pins: Vec<usize>,
    triangles: Vec<[usize; 3]>,
    segments: Vec<[usize; 2]>,
}

/// Where a body's particles went in a system: particles
/// `first..first + count`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Placement {
    /// System index of the body's particle 0.
    pub first: usize,
    /// Number of particles of the body.
    pub count: usize,
}

impl Placement {
    /// The system indices of the body's particles.
    #[must_use]
    pub fn range(&self) -> Range<usize> {
        self.first..self.first + self.count
    }

    /// The body's surface triangles with system indices, for writing the
    /// frames of a system that holds several bodies.
    ///
    /// ```
    /// use hooke_scenes::Cloth;
    /// let cloth = Cloth::grid(2, 2).build()?;
    /// let mut b = hooke_core::SystemBuilder::new();
    /// b.particle(1.0, [0.0, 5.0, 0.0]); // something else first
    /// let placed = cloth.add_to(&mut b);
    /// assert_eq!(placed.first, 1);
    /// for (local, global) in cloth.triangles().iter().zip(placed.triangles(&cloth)) {
    ///     assert_eq!(global, local.map(|i| i + 1));
    /// }
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    #[must_use]
    pub fn triangles(&self, body: &Body) -> Vec<[usize; 3]> {
        body.triangles
            .iter()
            .map(|t| t.map(|i| i + self.first))
            .collect()
    }
}

impl Body {
    /// Assembles a body from parts whose indices the builder has checked.
    pub(crate) fn from_parts(
        masses: Vec<f64>,
        positions: Vec<Vec3>,
        springs: Vec<BodySpring>,
        pins: Vec<usize>,
        triangles: Vec<[usize; 3]>,
        segments: Vec<[usize; 2]>,
    ) -> Result<Self, SceneError> {
        let particles = masses.len();
        if let Some(&particle) = pins.iter().find(|&&p| p >= particles) {
            return Err(SceneError::PinOutOfRange {
                particle,
                particles,
            });
        }
        let mut pins = pins;
        pins.sort_unstable();
        pins.dedup();
        Ok(Self {
            masses,
            positions,
            springs,
            pins,
            triangles,
            segments,
        })
    }

    /// Number of particles.
    #[must_use]
    pub fn particle_count(&self) -> usize {
        self.masses.len()
    }

    /// Particle masses in kg.
    #[must_use]
    pub fn masses(&self) -> &[f64] {
        &self.masses
    }

    /// Sum of the particle masses in kg.
    #[must_use]
    pub fn total_mass(&self) -> f64 {
        self.masses.iter().sum()
    }

    /// Initial particle positions in m.
    #[must_use]
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// All springs, in the order the builder made them.
    #[must_use]
    pub fn springs(&self) -> &[BodySpring] {
        &self.springs
    }

    /// The springs of one family.
    ///
    /// ```
    /// use hooke_scenes::{Cloth, Family};
    /// let cloth = Cloth::grid(3, 3).stretch(1e3).build()?;
    /// assert_eq!(cloth.springs_of(Family::Stretch).count(), 12);
    /// assert_eq!(cloth.springs_of(Family::Shear).count(), 0); // not asked for
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn springs_of(&self, family: Family) -> impl Iterator<Item = &BodySpring> + '_ {
        self.springs.iter().filter(move |s| s.family == family)
    }

    /// Pinned particles, in increasing order without repeats.
    #[must_use]
    pub fn pins(&self) -> &[usize] {
        &self.pins
    }

    /// Surface triangles (empty for a rope).
    #[must_use]
    pub fn triangles(&self) -> &[[usize; 3]] {
        &self.triangles
    }

    /// Polyline segments (a rope's; empty for other bodies).
    #[must_use]
    pub fn segments(&self) -> &[[usize; 2]] {
        &self.segments
    }

    /// Adds the body's particles, springs and pins to `builder`, after
    /// whatever it holds already, and says where they went.
    ///
    /// ```
    /// use hooke_scenes::{Cloth, Rope};
    /// let cloth = Cloth::grid(4, 4).stretch(1e3).build()?;
    /// let rope = Rope::between([0.0, 2.0, 0.0], [1.0, 2.0, 0.0], 5).stretch(1e3).build()?;
    /// let mut b = hooke_core::SystemBuilder::new();
    /// let c = cloth.add_to(&mut b);
    /// let r = rope.add_to(&mut b);
    /// assert_eq!((c.first, r.first, r.count), (0, 16, 6));
    /// assert_eq!(b.build()?.springs().len(), cloth.springs().len() + rope.springs().len());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn add_to(&self, builder: &mut SystemBuilder) -> Placement {
        let mut first = None;
        for (&mass, &position) in self.masses.iter().zip(&self.positions) {
            let index = builder.particle(mass, position);
            first.get_or_insert(index);
        }
        let placement = Placement {
            first: first.unwrap_or(0),
            count: self.masses.len(),
        };
        let at = placement.first;
        for s in &self.springs {
            builder
                .spring(at + s.i, at + s.j, s.stiffness)
                .rest_length(s.rest_length)
                .damping(s.damping);
        }
        for &p in &self.pins {
            builder.pin(at + p);
        }
        placement
    }

    /// A system holding this body alone under gravity `g` (m/s²; pass zeros
    /// for none).
    ///
    /// ```
    /// use hooke_scenes::{Corner, Cloth};
    /// let system = Cloth::grid(5, 5)
    ///     .stretch(2e3)
    ///     .pin_corners([Corner::TopLeft, Corner::TopRight])
    ///     .build()?
    ///     .system([0.0, -9.81, 0.0])?;
    /// assert_eq!(system.pinned().count(), 2);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    ///
    /// # Errors
    /// [`SceneError::InvalidVector`] for a gravity that is not finite;
    /// [`SceneError::Build`] if the system builder rejects the body.
    pub fn system(&self, gravity: [f64; 3]) -> Result<System, SceneError> {
        let g = finite_vector("gravity", gravity)?;
        let mut builder = SystemBuilder::new();
        self.add_to(&mut builder);
        if g.norm() > 0.0 {
            builder.gravity(g);
        }
        Ok(builder.build()?)
    }
}
