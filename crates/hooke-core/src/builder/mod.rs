//! [`SystemBuilder`]: collects particles, springs, pins and global forces and
//! validates all of them at [`SystemBuilder::build`].

mod entries;
mod resolve;

pub use entries::{SpringEntry, SurfaceEntry};

use crate::error::BuildError;
use crate::system::fresh_system_id;
use crate::{Obstacle, Path, System, Term, Vec3};

/// Builds a [`System`]; every value is checked at [`SystemBuilder::build`],
/// which names the first particle, spring or field that is wrong.
///
/// ```
/// use hooke_core::{SystemBuilder, Vec3};
/// let mut b = SystemBuilder::new();
/// let anchor = b.particle(1.0, [0.0, 0.0, 0.0]);
/// let bob = b.particle(0.5, [0.0, -1.0, 0.0]);
/// b.pin(anchor);
/// b.spring(anchor, bob, 200.0).damping(0.1); // rest length: the initial 1 m
/// b.gravity([0.0, -9.81, 0.0]);
/// let system = b.build()?;
/// assert_eq!(system.particle_count(), 2);
/// assert_eq!(system.springs()[0].rest_length, 1.0);
/// # Ok::<(), hooke_core::BuildError>(())
/// ```
#[derive(Debug, Clone, Default)]
pub struct SystemBuilder {
    masses: Vec<f64>,
    positions: Vec<Vec3>,
    velocities: Vec<Vec3>,
    springs: Vec<SpringEntry>,
    tets: Vec<([usize; 4], f64)>,
    pins: Vec<usize>,
    pin_paths: Vec<(usize, Path)>,
    gravity: Option<Vec3>,
    air_damping: Option<f64>,
    obstacles: Vec<Obstacle>,
    surfaces: Vec<SurfaceEntry>,
    contact_distance: Option<f64>,
    terms: Vec<Box<dyn Term>>,
}

impl SystemBuilder {
    /// An empty builder: no particles, no gravity, no air damping.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a particle of `mass` kg at rest at `position`; returns its index.
    ///
    /// ```
    /// let mut b = hooke_core::SystemBuilder::new();
    /// assert_eq!(b.particle(1.0, [0.0, 2.0, 0.0]), 0);
    /// assert_eq!(b.particle(1.0, [1.0, 2.0, 0.0]), 1);
    /// ```
    pub fn particle(&mut self, mass: f64, position: impl Into<Vec3>) -> usize {
        self.particle_with_velocity(mass, position, Vec3::zeros())
    }

    /// Adds a particle with an initial velocity; returns its index.
    ///
    /// ```
    /// let mut b = hooke_core::SystemBuilder::new();
    /// let p = b.particle_with_velocity(1.0, [0.0; 3], [0.0, 0.0, 3.0]);
    /// assert_eq!(b.build()?.initial_velocities()[p].z, 3.0);
    /// # Ok::<(), hooke_core::BuildError>(())
    /// ```
    pub fn particle_with_velocity(
        &mut self,
        mass: f64,
        position: impl Into<Vec3>,
        velocity: impl Into<Vec3>,
    ) -> usize {
        self.masses.push(mass);
        self.positions.push(position.into());
        self.velocities.push(velocity.into());
        self.masses.len() - 1
    }

    /// Adds a spring of stiffness `k` N/m between particles `i` and `j`;
    /// refine it through the returned [`SpringEntry`].
    ///
    /// ```
    /// # let mut b = hooke_core::SystemBuilder::new();
    /// # let (p, q) = (b.particle(1.0, [0.0; 3]), b.particle(1.0, [1.0, 0.0, 0.0]));
    /// b.spring(p, q, 1e3).rest_length(1.0).damping(0.2);
    /// ```
    pub fn spring(&mut self, i: usize, j: usize, stiffness: f64) -> &mut SpringEntry {
        self.springs.push(SpringEntry {
            i,
            j,
            stiffness,
            rest_length: None,
            damping: 0.0,
        });
        self.springs.last_mut().expect("a spring was just pushed")
    }

    /// Adds a volume element on four particles with modulus `κ` in Pa (see
    /// [`Tet`](crate::Tet)): its rest volume is theirs at their initial
    /// positions, in either orientation; a modulus of 0 adds an element
    /// that only measures its volume ([`System::inversion`]). Returns its
    /// index.
    ///
    /// ```
    /// let mut b = hooke_core::SystemBuilder::new();
    /// let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]].map(|x| b.particle(1.0, x));
    /// b.tet(p, 1e4);
    /// let system = b.build()?;
    /// assert_eq!(system.tets()[0].rest_volume, 1.0 / 6.0);
    /// # Ok::<(), hooke_core::BuildError>(())
    /// ```
    pub fn tet(&mut self, vertices: [usize; 4], modulus: f64) -> usize {
        self.tets.push((vertices, modulus));
        self.tets.len() - 1
    }

    /// Pins particle `i`: its acceleration is zero, so it keeps its initial
    /// velocity. Pinning twice is harmless.
    ///
    /// ```
    /// let mut b = hooke_core::SystemBuilder::new();
    /// let p = b.particle(1.0, [0.0; 3]);
    /// b.pin(p);
    /// assert!(b.build()?.is_pinned(p));
    /// # Ok::<(), hooke_core::BuildError>(())
    /// ```
    pub fn pin(&mut self, i: usize) -> &mut Self {
        self.pins.push(i);
        self
    }

    /// Pins particle `i` and moves it along `path`: at time `t` it is at its
    /// initial position plus `path.offset(t)` with velocity
    /// `path.velocity(t)` (a scripted handle).
    ///
    /// ```
    /// use hooke_core::{Path, Vec3};
    /// let mut b = hooke_core::SystemBuilder::new();
    /// let handle = b.particle(1.0, [0.0; 3]);
    /// b.pin_moving(handle, Path::Linear { velocity: Vec3::new(0.0, 0.0, 0.5) });
    /// let system = b.build()?;
    /// assert_eq!(system.initial_velocities()[handle], Vec3::new(0.0, 0.0, 0.5));
    /// # Ok::<(), hooke_core::BuildError>(())
    /// ```
    pub fn pin_moving(&mut self, i: usize, path: Path) -> &mut Self {
        self.pins.push(i);
        self.pin_paths.push((i, path));
        self
    }

    /// Uniform gravitational acceleration `g` in m/s²: force `mᵢ g` on every
    /// particle.
    ///
    /// ```
    /// let mut b = hooke_core::SystemBuilder::new();
    /// b.gravity([0.0, -9.81, 0.0]);
    /// ```
    pub fn gravity(&mut self, g: impl Into<Vec3>) -> &mut Self {
        self.gravity = Some(g.into());
        self
    }

    /// Air damping `γ` in N·s/m: force `−γ vᵢ` on every particle.
    ///
    /// ```
    /// let mut b = hooke_core::SystemBuilder::new();
    /// b.air_damping(0.01);
    /// ```
    pub fn air_damping(&mut self, gamma: f64) -> &mut Self {
        self.air_damping = Some(gamma);
        self
    }

    /// Adds a kinematic obstacle that particles cannot enter; every
    /// integrator resolves contacts with it at the end of each step.
    ///
    /// ```
    /// use hooke_core::{Obstacle, Shape, Vec3};
    /// let mut b = hooke_core::SystemBuilder::new();
    /// b.obstacle(Obstacle::new(Shape::Plane { point: Vec3::zeros(), normal: Vec3::y() }));
    /// assert_eq!(b.build()?.obstacles().len(), 1);
    /// # Ok::<(), hooke_core::BuildError>(())
    /// ```
    pub fn obstacle(&mut self, obstacle: Obstacle) -> &mut Self {
        self.obstacles.push(obstacle);
        self
    }

    /// Adds a collision surface: a body's triangles (particle indices), which
    /// collide with every other surface and, unless turned off, with
    /// themselves; refine it through the returned [`SurfaceEntry`]. Only an
    /// implicit step that minimises the incremental potential can keep
    /// surfaces apart (see `hooke-implicit`).
    ///
    /// ```
    /// let mut b = hooke_core::SystemBuilder::new();
    /// let t = [b.particle(1.0, [0.0; 3]), b.particle(1.0, [1.0, 0.0, 0.0]), b.particle(1.0, [0.0, 1.0, 0.0])];
    /// b.surface(&[t]).thickness(1e-3);
    /// assert_eq!(b.build()?.surfaces().triangles().len(), 1);
    /// # Ok::<(), hooke_core::BuildError>(())
    /// ```
    pub fn surface(&mut self, triangles: &[[usize; 3]]) -> &mut SurfaceEntry {
        self.surfaces.push(SurfaceEntry {
            triangles: triangles.to_vec(),
            self_collision: true,
            thickness: 0.0,
            friction: SurfaceEntry::FRICTION,
        });
        self.surfaces.last_mut().expect("pushed above")
    }

    /// The distance `d̂` in m below which contact acts (the barrier's
    /// activation distance, for obstacles and surfaces). Default: 10⁻³ of
    /// the diagonal of the box around the initial positions and the
    /// obstacles' reference points, and at most a quarter of the surfaces'
    /// mean edge length, so that no two primitives of a surface at rest are
    /// within it ([`System::contact_distance`]).
    ///
    /// ```
    /// # let mut b = hooke_core::SystemBuilder::new();
    /// b.contact_distance(5e-4);
    /// ```
    pub fn contact_distance(&mut self, distance: f64) -> &mut Self {
        self.contact_distance = Some(distance);
        self
    }

    /// Adds a term beyond the springs, volume elements, gravity and air
    /// damping: a force with a potential or a dissipation potential, given
    /// through the [`Term`] interface (its module gives the equations),
    /// which every integrator then includes. The term's constructor checks
    /// its parameters; [`SystemBuilder::build`] checks it against the
    /// system ([`Term::problem`]).
    ///
    /// ```
    /// use hooke_core::term::{At, Hessian, Potential, Term, When};
    /// use hooke_core::{System, SystemBuilder, Vec3};
    ///
    /// /// A uniform force `F` on particle 0: the potential `−F·x₀`.
    /// #[derive(Debug, Clone)]
    /// struct Push(Vec3);
    ///
    /// impl Term for Push {
    ///     fn name(&self) -> &'static str {
    ///         "push"
    ///     }
    ///     fn value(&mut self, _: &System, at: &At<'_>) -> Potential {
    ///         let e = -self.0.dot(&at.x[0]);
    ///         Potential { value: e, magnitude: e.abs() }
    ///     }
    ///     fn add(&mut self, _: &System, at: &At<'_>, b: &mut [Vec3], _: &mut dyn Hessian) {
    ///         b[0] += at.beta_h * self.0;
    ///     }
    ///     fn energy(&mut self, _: &System, x: &[Vec3], _: &[Vec3], _: When) -> Potential {
    ///         let e = -self.0.dot(&x[0]);
    ///         Potential { value: e, magnitude: e.abs() }
    ///     }
    ///     fn force(&self, _: &System, _: &[Vec3], _: &[Vec3], f: &mut [Vec3]) {
    ///         f[0] += self.0;
    ///     }
    /// }
    ///
    /// let mut b = SystemBuilder::new();
    /// b.particle(2.0, [0.0; 3]);
    /// b.term(Push(Vec3::new(1.0, 0.0, 0.0)));
    /// let system = b.build()?;
    /// assert_eq!(system.terms()[0].name(), "push");
    /// # Ok::<(), hooke_core::BuildError>(())
    /// ```
    pub fn term(&mut self, term: impl Term + 'static) -> &mut Self {
        self.terms.push(Box::new(term));
        self
    }

    /// Validates everything and builds the system.
    ///
    /// # Errors
    /// The first problem found, in this order: particles (mass, position,
    /// velocity), springs (endpoints, parameters, duplicates), volume
    /// elements, pins, gravity, air damping, obstacles, surfaces, contact
    /// distance, terms. See [`BuildError`].
    pub fn build(&self) -> Result<System, BuildError> {
        self.check_particles()?;
        let springs = self.resolved_springs()?;
        let tets = self.resolved_tets()?;
        let particles = self.masses.len();
        let mut pinned = vec![false; particles];
        for &particle in &self.pins {
            *pinned.get_mut(particle).ok_or(BuildError::PinOutOfRange {
                particle,
                particles,
            })? = true;
        }
        if let Some(g) = self.gravity.filter(|g| !g.iter().all(|c| c.is_finite())) {
            return Err(BuildError::NonFiniteGravity { value: g.into() });
        }
        if let Some(value) = self.air_damping.filter(|&y| !(y.is_finite() && y >= 0.0)) {
            return Err(BuildError::InvalidAirDamping { value });
        }
        let mut pin_paths = Vec::new();
        let mut velocities = self.velocities.clone();
        for (particle, path) in &self.pin_paths {
            if let Some(problem) = path.problem() {
                return Err(BuildError::InvalidPinPath {
                    particle: *particle,
                    problem,
                });
            }
            pin_paths.retain(|(p, _)| p != particle);
            pin_paths.push((*particle, path.clone()));
            velocities[*particle] = path.velocity(0.0);
        }
        pin_paths.sort_by_key(|(p, _)| *p);
        if let Some((obstacle, problem)) = self
            .obstacles
            .iter()
            .enumerate()
            .find_map(|(k, o)| o.problem().map(|p| (k, p)))
        {
            return Err(BuildError::InvalidObstacle { obstacle, problem });
        }
        let (surfaces, surface_properties) = self.collision_mesh()?;
        let contact_distance = match self.contact_distance {
            Some(d) if d.is_finite() && d > 0.0 => d,
            Some(value) => return Err(BuildError::InvalidContactDistance { value }),
            None => self.default_contact_distance(),
        };
        let inverse_masses = self
            .masses
            .iter()
            .zip(&pinned)
            .map(|(&m, &p)| if p { 0.0 } else { 1.0 / m })
            .collect();
        let system = System {
            id: fresh_system_id(),
            masses: self.masses.clone(),
            inverse_masses,
            pinned,
            initial_positions: self.positions.clone(),
            initial_velocities: velocities,
            pin_paths,
            springs,
            tets,
            gravity: self.gravity,
            air_damping: self.air_damping,
            obstacles: self.obstacles.clone(),
            surfaces,
            surface_properties,
            contact_distance,
            terms: self.terms.clone(),
        };
        for (term, t) in system.terms.iter().enumerate() {
            if let Some(problem) = t.problem(&system) {
                return Err(BuildError::InvalidTerm {
                    term,
                    name: t.name(),
                    problem,
                });
            }
        }
        Ok(system)
    }
}
