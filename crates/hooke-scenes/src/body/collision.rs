//! [`Collision`]: how a body's surface takes part in contact, and the
//! body's setters for it.

use super::Body;

/// How a body's surface takes part in contact between surfaces (the
/// implicit step's barrier terms, see `hooke-implicit`): what
/// [`Body::add_to`] gives [`SystemBuilder::surface`](hooke_core::SystemBuilder::surface).
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

impl Body {
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
}
