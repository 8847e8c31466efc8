//! [`Body`]: what every builder produces — particles, springs, volume
//! elements, pins, the surface to draw and how it collides — and its
//! [`Placement`] in a system.

use hooke_core::Vec3;

mod collision;
mod placement;

pub use collision::Collision;
pub use placement::Placement;

use crate::error::SceneError;
use crate::spring::{BodySpring, Family};
use crate::volume::{self, Volume};

/// A deformable body described as particles and springs, ready to go into a
/// [`SystemBuilder`](hooke_core::SystemBuilder) alone or beside other bodies.
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
}
