//! Contact response between particles and a system's obstacles, applied by
//! every integrator at the end of a step.

use crate::collision::surface::CollisionMesh;
use crate::{Obstacle, State, StepError, System, Vec3};

/// Pushes a particle at `x` with velocity `v` out of `obstacle` at time `t`
/// and applies Coulomb friction, and restitution if the contact is `new`;
/// returns whether it was in contact (`φ(x) < 0`).
///
/// With `φ` the signed distance, `n` the outward normal and `u` the
/// obstacle's velocity, the particle moves to the surface, `x ← x − φ n`, and
/// if it approaches the obstacle (`v_n = (v − u)·n < 0`) its relative
/// velocity changes by the normal impulse per unit mass `j = (1 + e)|v_n|`
/// (`e` = 0 unless the contact is new):
///
/// ```text
/// v ← u − e v_n n + max(0, 1 − μ j / |v_t|) v_t,    v_t = (v − u) − v_n n,
/// ```
///
/// so a particle sticks when friction can absorb its tangential speed and
/// otherwise loses `μ j` of it — over a step of a particle resting on an
/// incline, exactly Coulomb's law: it stays put while `tan θ ≤ μ` and slides
/// with acceleration `g (sin θ − μ cos θ)` otherwise.
///
/// ```
/// use hooke_core::{Obstacle, Shape, Vec3, respond_to_contact};
/// let floor = Obstacle::new(Shape::Plane { point: Vec3::zeros(), normal: Vec3::y() });
/// let (mut x, mut v) = (Vec3::new(0.0, -0.01, 0.0), Vec3::new(1.0, -2.0, 0.0));
/// assert!(respond_to_contact(&floor, &mut x, &mut v, 0.0, true));
/// assert_eq!((x, v), (Vec3::zeros(), Vec3::new(1.0, 0.0, 0.0)));
/// ```
pub fn respond_to_contact(
    obstacle: &Obstacle,
    x: &mut Vec3,
    v: &mut Vec3,
    t: f64,
    new: bool,
) -> bool {
    let (phi, n) = obstacle.distance(*x, t);
    let restitution = if new { obstacle.restitution } else { 0.0 };
    if phi >= 0.0 {
        return false;
    }
    *x -= phi * n;
    let u = obstacle.velocity(t);
    let relative = *v - u;
    let normal = relative.dot(&n);
    if normal < 0.0 {
        let tangential = relative - normal * n;
        let impulse = -(1.0 + restitution) * normal;
        let speed = tangential.norm();
        let kept = if speed > 0.0 {
            (1.0 - obstacle.friction * impulse / speed).max(0.0)
        } else {
            0.0
        };
        *v = u - restitution * normal * n + kept * tangential;
    }
    true
}

impl System {
    /// The collision surfaces: the triangles of the bodies that collide, by
    /// body ([`crate::SystemBuilder::surface`]).
    #[must_use]
    pub fn surfaces(&self) -> &CollisionMesh {
        &self.surfaces
    }

    /// The number of collision surfaces.
    #[must_use]
    pub fn surface_count(&self) -> usize {
        self.surface_properties.len()
    }

    /// The thickness `ξ` of surface `group` of [`System::surfaces`], m.
    ///
    /// # Panics
    /// If there is no such surface.
    #[must_use]
    pub fn surface_thickness(&self, group: usize) -> f64 {
        self.surface_properties[group][0]
    }

    /// The friction coefficient `μ` of surface `group` of
    /// [`System::surfaces`] against surfaces.
    ///
    /// # Panics
    /// If there is no such surface.
    #[must_use]
    pub fn surface_friction(&self, group: usize) -> f64 {
        self.surface_properties[group][1]
    }

    /// Whether some pair of surface primitives can collide (a surface with
    /// self-collision, or two surfaces).
    #[must_use]
    pub fn has_surface_contact(&self) -> bool {
        self.surfaces.has_pairs()
    }

    /// The distance `d̂` below which contact acts, m.
    #[must_use]
    pub fn contact_distance(&self) -> f64 {
        self.contact_distance
    }

    /// This system without self-collision: the same surfaces, none of which
    /// collides with itself (different surfaces still do), as a new system.
    #[must_use]
    pub fn without_self_collision(&self) -> Self {
        let mut system = self.clone();
        system.id = crate::system::fresh_system_id();
        let mut mesh = CollisionMesh::new();
        for group in 0..self.surface_properties.len() {
            let triangles: Vec<[usize; 3]> = (0..self.surfaces.triangles().len())
                .filter(|&t| self.surfaces.triangle_group(t) == group)
                .map(|t| self.surfaces.triangles()[t])
                .collect();
            mesh.add_surface(&triangles, false);
        }
        system.surfaces = mesh;
        system
    }

    /// Checks that an integrator that only resolves contacts with obstacles
    /// after its step (every explicit one, and the fast mass-spring step)
    /// can run this system: that no surfaces collide.
    ///
    /// # Errors
    /// [`StepError::SurfaceContactUnsupported`] naming `integrator`.
    pub fn check_no_surface_contact(&self, integrator: &'static str) -> Result<(), StepError> {
        if self.has_surface_contact() {
            Err(StepError::SurfaceContactUnsupported { integrator })
        } else {
            Ok(())
        }
    }

    /// The obstacles particles cannot enter.
    #[must_use]
    pub fn obstacles(&self) -> &[Obstacle] {
        &self.obstacles
    }

    /// Resolves the contacts of the state's free particles with the
    /// obstacles at the state's time, one obstacle after another with
    /// [`respond_to_contact`], and records which particles it touched
    /// ([`State::touching`]; restitution applies only to new contacts);
    /// returns the number of contacts.
    ///
    /// A state with contacts counts as edited (integrators with history
    /// restart, as their history assumes smooth motion); a system without
    /// obstacles does nothing here.
    pub fn resolve_contacts(&self, state: &mut State) -> usize {
        if self.obstacles.is_empty() {
            return 0;
        }
        let t = state.time();
        let touching = |i: usize, x: &Vec3| {
            !self.pinned[i] && self.obstacles.iter().any(|o| o.distance(*x, t).0 < 0.0)
        };
        // Only a state with contacts is edited; the particles before the
        // first contact are not looked at twice.
        let Some(first) = state
            .positions()
            .iter()
            .enumerate()
            .position(|(i, x)| touching(i, x))
        else {
            state.touching_mut().fill(false);
            return 0;
        };
        let (positions, velocities, flags) = state.contact_mut();
        flags[..first].fill(false);
        let mut contacts = 0;
        let particles = positions.iter_mut().zip(velocities.iter_mut());
        for (i, (x, v)) in particles.enumerate().skip(first) {
            if self.pinned[i] {
                continue;
            }
            let new = !flags[i];
            let mut touched = false;
            for obstacle in &self.obstacles {
                let hit = respond_to_contact(obstacle, x, v, t, new);
                touched |= hit;
                contacts += usize::from(hit);
            }
            flags[i] = touched;
        }
        contacts
    }
}
