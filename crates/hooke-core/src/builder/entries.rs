//! The entries a [`SystemBuilder`](crate::SystemBuilder) hands back to
//! refine what was just added: a spring's rest length and damping, a
//! surface's self-collision, thickness and friction.

/// A collision surface being added to a
/// [`SystemBuilder`](crate::SystemBuilder): a body's triangles, whether
/// they collide with each other and how thick the surface is.
#[derive(Debug, Clone)]
pub struct SurfaceEntry {
    pub(super) triangles: Vec<[usize; 3]>,
    pub(super) self_collision: bool,
    pub(super) thickness: f64,
    pub(super) friction: f64,
}

impl SurfaceEntry {
    /// Whether pairs of the surface's own primitives collide (default
    /// `true`); pairs with other surfaces always do.
    ///
    /// ```
    /// # let mut b = hooke_core::SystemBuilder::new();
    /// # let t = [b.particle(1.0, [0.0; 3]), b.particle(1.0, [1.0, 0.0, 0.0]), b.particle(1.0, [0.0, 1.0, 0.0])];
    /// b.surface(&[t]).self_collision(false);
    /// ```
    pub fn self_collision(&mut self, on: bool) -> &mut Self {
        self.self_collision = on;
        self
    }

    /// The surface's thickness `ξ` in m (default 0): two surfaces are kept
    /// `(ξ₁ + ξ₂)/2` apart plus the barrier's gap, an obstacle `ξ/2`.
    ///
    /// ```
    /// # let mut b = hooke_core::SystemBuilder::new();
    /// # let t = [b.particle(1.0, [0.0; 3]), b.particle(1.0, [1.0, 0.0, 0.0]), b.particle(1.0, [0.0, 1.0, 0.0])];
    /// b.surface(&[t]).thickness(1e-3);
    /// ```
    pub fn thickness(&mut self, thickness: f64) -> &mut Self {
        self.thickness = thickness;
        self
    }

    /// The Coulomb friction coefficient `μ ≥ 0` of the surface against
    /// itself and other surfaces (default [`SurfaceEntry::FRICTION`]); a
    /// pair of surfaces takes the mean of theirs.
    ///
    /// ```
    /// # let mut b = hooke_core::SystemBuilder::new();
    /// # let t = [b.particle(1.0, [0.0; 3]), b.particle(1.0, [1.0, 0.0, 0.0]), b.particle(1.0, [0.0, 1.0, 0.0])];
    /// b.surface(&[t]).friction(0.5);
    /// ```
    pub fn friction(&mut self, mu: f64) -> &mut Self {
        self.friction = mu;
        self
    }
}

impl SurfaceEntry {
    /// The default friction coefficient between surfaces, 0.3 (cloth on
    /// cloth).
    pub const FRICTION: f64 = 0.3;
}

/// A spring being added to a [`SystemBuilder`](crate::SystemBuilder); set
/// its rest length and damping here.
#[derive(Debug, Clone, Copy)]
pub struct SpringEntry {
    pub(super) i: usize,
    pub(super) j: usize,
    pub(super) stiffness: f64,
    pub(super) rest_length: Option<f64>,
    pub(super) damping: f64,
}

impl SpringEntry {
    /// Rest length `L` in m. Without it, the rest length is the distance
    /// between the two particles' initial positions.
    ///
    /// ```
    /// # let mut b = hooke_core::SystemBuilder::new();
    /// # let (p, q) = (b.particle(1.0, [0.0; 3]), b.particle(1.0, [1.0, 0.0, 0.0]));
    /// b.spring(p, q, 50.0).rest_length(0.8); // starts stretched by 0.2 m
    /// ```
    pub fn rest_length(&mut self, rest_length: f64) -> &mut Self {
        self.rest_length = Some(rest_length);
        self
    }

    /// Axial damping `c` in N·s/m: force `−c ((vᵢ − vⱼ)·d) d` on `i`
    /// (default 0).
    ///
    /// ```
    /// # let mut b = hooke_core::SystemBuilder::new();
    /// # let (p, q) = (b.particle(1.0, [0.0; 3]), b.particle(1.0, [1.0, 0.0, 0.0]));
    /// b.spring(p, q, 50.0).damping(0.5);
    /// ```
    pub fn damping(&mut self, damping: f64) -> &mut Self {
        self.damping = damping;
        self
    }
}
