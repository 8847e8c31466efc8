//! [`Body`]: what every builder produces — particles, springs, volume
//! elements, pins, the surface to draw and how it collides — and its
//! [`Placement`] in a system.

use std::ops::Range;

use hooke_core::{System, SystemBuilder, Vec3};

use crate::error::{SceneError, finite_vector};
use crate::spring::{BodySpring, Family};
use crate::volume::{self, Volume};

/// A deformable body described as particles and springs, ready to go into a
/// [`SystemBuilder`] alone or beside other bodies.
///
/// Indices in springs, pins, triangles and segments are local: `0..n` over
/// the body's own particles. Triangles are oriented counter-clockwise seen
/// from outside (their normal `(b − a) × (c − a)` points out), for writing
/// frames and rendering; segments are the polyline of a rope.
///
/// A body with triangles is a collision surface of the systems it goes
/// into ([`Collision`]): with self-collision for a [`Cloth`](crate::Cloth)
/// or a [`Shell`](crate::Shell), without for the volumetric
/// [`Lattice`](crate::Lattice), [`Solid`](crate::Solid) and
/// [`Layered`](crate::Layered) bodies, thickness 0; a rope has no surface.
///
/// The volumetric bodies also have volume elements, tets on four of their
/// particles whose energy keeps each tet's signed volume near its rest
/// volume, with the modulus [`Volume`] sets (by default the bulk modulus
/// of the body's springs); cloth, shells and ropes have none.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    masses: Vec<f64>,
    positions: Vec<Vec3>,
    springs: Vec<BodySpring>,
    tets: Vec<[usize; 4]>,
    tet_weights: Vec<f64>,
    volume_modulus: f64,
    pins: Vec<usize>,
    triangles: Vec<[usize; 3]>,
    segments: Vec<[usize; 2]>,
    collision: Collision,
}

/// How a body's surface takes part in contact between surfaces (the
/// implicit step's barrier terms, see `hooke-implicit`): what
/// [`Body::add_to`] gives [`SystemBuilder::surface`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Collision {
    /// Whether the body's triangles are a collision surface, colliding
    /// with every other surface: `true` for a body with triangles unless
    /// turned off ([`Body::surface_collision`]), always `false` for a rope.
    pub surface: bool,
    /// Whether pairs of the surface's own points, edges and triangles
    /// collide (self-collision): by default `true` for cloth and shells,
    /// `false` for volumetric bodies, whose surface cannot fold onto
    /// itself.
    pub self_collision: bool,
    /// The surface's thickness `ξ`, m (default 0): two surfaces are kept
    /// `(ξ₁ + ξ₂)/2` apart, an obstacle `ξ/2`, besides the barrier's gap.
    pub thickness: f64,
}

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
    /// Assembles a body from parts whose indices the builder has checked;
    /// its triangles, if any, collide, with themselves if `self_collision`.
    pub(crate) fn from_parts(
        masses: Vec<f64>,
        positions: Vec<Vec3>,
        springs: Vec<BodySpring>,
        pins: Vec<usize>,
        (triangles, self_collision): (Vec<[usize; 3]>, bool),
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
        let collision = Collision {
            surface: !triangles.is_empty(),
            self_collision,
            thickness: 0.0,
        };
        Ok(Self {
            masses,
            positions,
            springs,
            tets: Vec::new(),
            tet_weights: Vec::new(),
            volume_modulus: 0.0,
            pins,
            triangles,
            segments,
            collision,
        })
    }

    /// The body with volume elements `tets` (local indices, each oriented
    /// with a positive volume at rest, none degenerate) of the modulus
    /// `volume` gives.
    pub(crate) fn with_tets(
        self,
        tets: Vec<[usize; 4]>,
        volume: Volume,
    ) -> Result<Self, SceneError> {
        let weights = vec![1.0; tets.len()];
        self.with_weighted_tets(tets, weights, volume)
    }

    /// The body with volume elements `tets` as in
    /// [`with_tets`](Self::with_tets), each with its share `weights[t]` of
    /// the modulus (see [`tet_weights`](Self::tet_weights)).
    pub(crate) fn with_weighted_tets(
        mut self,
        tets: Vec<[usize; 4]>,
        weights: Vec<f64>,
        volume: Volume,
    ) -> Result<Self, SceneError> {
        debug_assert_eq!(tets.len(), weights.len());
        self.tets = tets;
        self.tet_weights = weights;
        self.volume(volume)
    }

    /// The body with its volume elements' modulus set by `volume` (see
    /// [`Volume`]); a body without volume elements (cloth, shell, rope)
    /// has none whatever this says.
    ///
    /// ```
    /// use hooke_scenes::{Lattice, Volume};
    /// let cube = Lattice::cubes(2, 2, 2).edges(1e3).build()?;
    /// assert!(cube.volume_modulus() > 0.0); // the springs' bulk modulus
    /// let soft = cube.volume(Volume::Modulus(50.0))?;
    /// assert_eq!(soft.volume_modulus(), 50.0);
    /// assert_eq!(soft.system([0.0; 3])?.tets()[0].modulus, 50.0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    /// [`SceneError::InvalidValue`] for a [`Volume::Modulus`] that is
    /// negative or not finite.
    pub fn volume(mut self, volume: Volume) -> Result<Self, SceneError> {
        let modulus = volume.modulus(&self.springs, self.rest_volume())?;
        self.volume_modulus = if self.tets.is_empty() { 0.0 } else { modulus };
        Ok(self)
    }

    /// The body with its surface colliding or not (see
    /// [`Collision::surface`]); a body without triangles has no surface
    /// whatever this says.
    ///
    /// ```
    /// use hooke_scenes::Cloth;
    /// let cloth = Cloth::grid(3, 3).stretch(1e3).build()?;
    /// assert!(cloth.collision().surface);
    /// let ghost = cloth.surface_collision(false);
    /// assert_eq!(ghost.system([0.0; 3])?.surface_count(), 0);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    #[must_use]
    pub fn surface_collision(mut self, on: bool) -> Self {
        self.collision.surface = on && !self.triangles.is_empty();
        self
    }

    /// The body with its surface colliding with itself or not (see
    /// [`Collision::self_collision`]).
    ///
    /// ```
    /// use hooke_scenes::Cloth;
    /// let cloth = Cloth::grid(3, 3).stretch(1e3).build()?;
    /// assert!(cloth.collision().self_collision); // cloth folds onto itself
    /// let flat = cloth.self_collision(false).system([0.0, -9.81, 0.0])?;
    /// assert!(!flat.has_surface_contact()); // nothing else to collide with
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    #[must_use]
    pub fn self_collision(mut self, on: bool) -> Self {
        self.collision.self_collision = on;
        self
    }

    /// The body with surface thickness `ξ` in m (see
    /// [`Collision::thickness`]); the system builder rejects one that is
    /// negative or not finite.
    ///
    /// ```
    /// use hooke_scenes::Cloth;
    /// let cloth = Cloth::grid(3, 3).stretch(1e3).build()?.thickness(1e-3);
    /// assert_eq!(cloth.collision().thickness, 1e-3);
    /// assert_eq!(cloth.system([0.0; 3])?.surface_thickness(0), 1e-3);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    #[must_use]
    pub fn thickness(mut self, thickness: f64) -> Self {
        self.collision.thickness = thickness;
        self
    }

    /// How the body's surface collides.
    ///
    /// ```
    /// use hooke_scenes::{Lattice, Rope};
    /// let cube = Lattice::cubes(2, 2, 2).edges(1e3).build()?;
    /// assert!(cube.collision().surface && !cube.collision().self_collision);
    /// let rope = Rope::between([0.0; 3], [1.0, 0.0, 0.0], 4).stretch(1e3).build()?;
    /// assert!(!rope.collision().surface); // no triangles
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    #[must_use]
    pub fn collision(&self) -> Collision {
        self.collision
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

    /// The volume elements: tets on four local particles each, oriented so
    /// that their signed volume at rest is positive (empty for cloth,
    /// shells and ropes).
    ///
    /// ```
    /// use hooke_scenes::{Cloth, Lattice, TetSplit};
    /// assert_eq!(Lattice::cubes(2, 1, 1).build()?.tets().len(), 2 * 6);
    /// assert_eq!(Lattice::tets(2, 1, 1, TetSplit::Five).build()?.tets().len(), 2 * 5);
    /// assert!(Cloth::grid(3, 3).build()?.tets().is_empty());
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    #[must_use]
    pub fn tets(&self) -> &[[usize; 4]] {
        &self.tets
    }

    /// Each volume element's share `w` of the modulus: its energy is
    /// `½ w κ V₀ (J − 1)²`. 1 for the tets of lattices and tet meshes,
    /// which fill the body once; a [`Layered`](crate::Layered) body's
    /// prisms average their six cuts into three tets, each cut weighted
    /// `1/6`, so that a tet two cuts share has `1/3`.
    ///
    /// ```
    /// use hooke_scenes::{Lattice, Layered, TriangleMesh};
    /// assert!(Lattice::cubes(2, 1, 1).build()?.tet_weights().iter().all(|&w| w == 1.0));
    /// let tri = TriangleMesh::new([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], [[0, 1, 2]]);
    /// let prism = Layered::new(tri, 0.1).surface(1e3).build()?;
    /// let total: f64 = prism.tet_weights().iter().sum();
    /// assert!((total - 3.0).abs() < 1e-12); // one cut's worth
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    #[must_use]
    pub fn tet_weights(&self) -> &[f64] {
        &self.tet_weights
    }

    /// The modulus `κ` of the volume elements, Pa (0 without any, or with
    /// [`Volume::Off`]).
    #[must_use]
    pub fn volume_modulus(&self) -> f64 {
        self.volume_modulus
    }

    /// The rest volume `V` of the body, m³: the sum of its volume
    /// elements' volumes in the initial shape, each times its
    /// [weight](Self::tet_weights) (0 without any).
    ///
    /// ```
    /// let cube = hooke_scenes::Lattice::cubes(3, 2, 1).size([0.3, 0.2, 0.1]).build()?;
    /// assert!((cube.rest_volume() - 0.3 * 0.2 * 0.1).abs() < 1e-15);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    #[must_use]
    pub fn rest_volume(&self) -> f64 {
        volume::rest_volume(&self.tets, &self.tet_weights, &self.positions)
    }

    /// The bulk modulus of the body's springs under a uniform dilation,
    /// `Σ k L² / (9 V)` in Pa over its springs (stiffness `k`, rest length
    /// `L`), `V` its [`rest_volume`](Self::rest_volume): the modulus of
    /// [`Volume::Auto`], which explains it; 0 without volume elements.
    ///
    /// ```
    /// // One unit cube cell: 12 edges of 1 m, 12 face diagonals of √2 m.
    /// let cell = hooke_scenes::Lattice::cubes(1, 1, 1).edges(90.0).face_diagonals(45.0).build()?;
    /// let expected = (12.0 * 90.0 * 1.0 + 12.0 * 45.0 * 2.0) / 9.0;
    /// assert!((cell.spring_bulk_modulus() - expected).abs() < 1e-9);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    #[must_use]
    pub fn spring_bulk_modulus(&self) -> f64 {
        volume::spring_bulk_modulus(&self.springs, self.rest_volume())
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

    /// Adds the body's particles, springs, volume elements
    /// ([`SystemBuilder::tet`], with its [`volume_modulus`](Self::volume_modulus)
    /// times each one's [weight](Self::tet_weights))
    /// and pins to `builder`, after whatever it holds already, and its
    /// triangles as a collision surface ([`SystemBuilder::surface`], with
    /// its [`Collision`] settings) unless it has none or its surface
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
