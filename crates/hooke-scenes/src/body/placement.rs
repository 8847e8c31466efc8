//! Putting a body into a system: [`Body::add_to`] a builder beside other
//! bodies, or [`Body::system`] alone, and the [`Placement`] that says where
//! its particles and volume elements went.

use std::ops::Range;

use hooke_core::{System, SystemBuilder};

use super::Body;
use crate::error::{SceneError, finite_vector};

/// Where a body's particles went in a system: particles
/// `first..first + count`, and volume elements (the system's
/// [`tets`](hooke_core::System::tets)) `first_tet..first_tet + tet_count`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Placement {
    /// System index of the body's particle 0.
    pub first: usize,
    /// Number of particles of the body.
    pub count: usize,
    /// System index of the body's first volume element (0 for a body
    /// without any).
    pub first_tet: usize,
    /// Number of volume elements of the body.
    pub tet_count: usize,
}

impl Placement {
    /// The system indices of the body's particles.
    #[must_use]
    pub fn range(&self) -> Range<usize> {
        self.first..self.first + self.count
    }

    /// The system indices of the body's volume elements.
    ///
    /// ```
    /// use hooke_scenes::{Cloth, Lattice};
    /// let cloth = Cloth::grid(2, 2).build()?;
    /// let cube = Lattice::cubes(1, 1, 2).edges(1e3).build()?;
    /// let mut b = hooke_core::SystemBuilder::new();
    /// let (c, l) = (cloth.add_to(&mut b), cube.add_to(&mut b));
    /// assert_eq!((c.tet_range(), l.tet_range()), (0..0, 0..12));
    /// let system = b.build()?;
    /// assert_eq!(system.tets()[l.tet_range()].len(), cube.tets().len());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub fn tet_range(&self) -> Range<usize> {
        self.first_tet..self.first_tet + self.tet_count
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
    /// Adds the body's particles, springs, volume elements
    /// ([`SystemBuilder::tet`], with its [`volume_modulus`](Self::volume_modulus)
    /// times each one's [weight](Self::tet_weights))
    /// and pins to `builder`, after whatever it holds already, and its
    /// triangles as a collision surface ([`SystemBuilder::surface`], with
    /// its [`Collision`](super::Collision) settings) unless it has none or its surface
    /// collision is off; says where they went.
    ///
    /// ```
    /// use hooke_scenes::{Cloth, Rope};
    /// let cloth = Cloth::grid(4, 4).stretch(1e3).build()?;
    /// let rope = Rope::between([0.0, 2.0, 0.0], [1.0, 2.0, 0.0], 5).stretch(1e3).build()?;
    /// let mut b = hooke_core::SystemBuilder::new();
    /// let c = cloth.add_to(&mut b);
    /// let r = rope.add_to(&mut b);
    /// assert_eq!((c.first, r.first, r.count), (0, 16, 6));
    /// let system = b.build()?;
    /// assert_eq!(system.springs().len(), cloth.springs().len() + rope.springs().len());
    /// assert_eq!(system.surface_count(), 1); // the cloth's; a rope has none
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn add_to(&self, builder: &mut SystemBuilder) -> Placement {
        let mut first = None;
        for (&mass, &position) in self.masses.iter().zip(&self.positions) {
            let index = builder.particle(mass, position);
            first.get_or_insert(index);
        }
        let at = first.unwrap_or(0);
        for s in &self.springs {
            builder
                .spring(at + s.i, at + s.j, s.stiffness)
                .rest_length(s.rest_length)
                .damping(s.damping);
        }
        let mut first_tet = None;
        for (t, w) in self.tets.iter().zip(&self.tet_weights) {
            let index = builder.tet(t.map(|i| at + i), w * self.volume_modulus);
            first_tet.get_or_insert(index);
        }
        let placement = Placement {
            first: at,
            count: self.masses.len(),
            first_tet: first_tet.unwrap_or(0),
            tet_count: self.tets.len(),
        };
        for &p in &self.pins {
            builder.pin(at + p);
        }
        if self.collision.surface && !self.triangles.is_empty() {
            builder
                .surface(&placement.triangles(self))
                .self_collision(self.collision.self_collision)
                .thickness(self.collision.thickness);
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
