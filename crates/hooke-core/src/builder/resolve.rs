//! What [`SystemBuilder::build`] checks and works out from what was
//! collected: particles, springs (their rest lengths), volume elements
//! (oriented at rest), the collision mesh and the default contact distance.

use std::collections::HashMap;

use super::SystemBuilder;
use crate::collision::surface::CollisionMesh;
use crate::error::{BuildError, Quantity, SpringParameter};
use crate::{Spring, Tet, Vec3};

impl SystemBuilder {
    /// The volume elements, checked and oriented.
    pub(super) fn resolved_tets(&self) -> Result<Vec<Tet>, BuildError> {
        let particles = self.masses.len();
        let mut tets = Vec::with_capacity(self.tets.len());
        for (tet, &(vertices, modulus)) in self.tets.iter().enumerate() {
            let problem = |problem: String| BuildError::InvalidTet { tet, problem };
            if let Some(&p) = vertices.iter().find(|&&p| p >= particles) {
                return Err(problem(format!(
                    "names particle {p}, but the system has {particles}"
                )));
            }
            if let Some(p) = (0..4).find_map(|a| {
                vertices[a + 1..]
                    .contains(&vertices[a])
                    .then_some(vertices[a])
            }) {
                return Err(problem(format!("names particle {p} twice")));
            }
            if !(modulus.is_finite() && modulus >= 0.0) {
                return Err(problem(format!(
                    "modulus must be finite and non-negative, got {modulus}"
                )));
            }
            let corners = vertices.map(|p| self.positions[p]);
            tets.push(Tet::at_rest(vertices, modulus, corners).ok_or_else(|| {
                problem(format!(
                    "particles {vertices:?} have no volume at their initial positions"
                ))
            })?);
        }
        Ok(tets)
    }

    /// The collision mesh of the surfaces and their thicknesses and friction
    /// coefficients, checked.
    pub(super) fn collision_mesh(&self) -> Result<(CollisionMesh, Vec<[f64; 2]>), BuildError> {
        let particles = self.masses.len();
        let mut mesh = CollisionMesh::new();
        let mut owner = vec![usize::MAX; particles];
        for (surface, entry) in self.surfaces.iter().enumerate() {
            let problem = |problem: String| BuildError::InvalidSurface { surface, problem };
            if !(entry.thickness.is_finite() && entry.thickness >= 0.0) {
                return Err(problem(format!(
                    "thickness must be finite and non-negative, got {}",
                    entry.thickness
                )));
            }
            if !(entry.friction.is_finite() && entry.friction >= 0.0) {
                return Err(problem(format!(
                    "friction must be finite and non-negative, got {}",
                    entry.friction
                )));
            }
            for (t, triangle) in entry.triangles.iter().enumerate() {
                let [a, b, c] = *triangle;
                if let Some(&p) = triangle.iter().find(|&&p| p >= particles) {
                    return Err(problem(format!(
                        "triangle {t} names particle {p}, but the system has {particles}"
                    )));
                }
                if a == b || b == c || a == c {
                    return Err(problem(format!(
                        "triangle {t} repeats a particle: {triangle:?}"
                    )));
                }
                for &p in triangle {
                    if owner[p] != usize::MAX && owner[p] != surface {
                        return Err(problem(format!(
                            "particle {p} is already on surface {}",
                            owner[p]
                        )));
                    }
                    owner[p] = surface;
                }
            }
            mesh.add_surface(&entry.triangles, entry.self_collision);
        }
        let properties = self
            .surfaces
            .iter()
            .map(|s| [s.thickness, s.friction])
            .collect();
        Ok((mesh, properties))
    }

    /// 10⁻³ of the diagonal of the box around the initial positions and the
    /// obstacles' reference points (1 mm for an empty or point-like
    /// system), at most a quarter of the surfaces' mean edge length.
    pub(super) fn default_contact_distance(&self) -> f64 {
        let (mut total, mut edges) = (0.0, 0usize);
        for surface in &self.surfaces {
            for t in &surface.triangles {
                for k in 0..3 {
                    total += (self.positions[t[k]] - self.positions[t[(k + 1) % 3]]).norm();
                    edges += 1;
                }
            }
        }
        let finest = if edges > 0 {
            0.25 * total / edges as f64
        } else {
            f64::INFINITY
        };
        self.scene_contact_distance().min(finest)
    }

    /// 10⁻³ of the scene's diagonal.
    fn scene_contact_distance(&self) -> f64 {
        let points = self
            .positions
            .iter()
            .copied()
            .chain(self.obstacles.iter().flat_map(|o| {
                let (a, b) = o.shape.reference_points();
                [a, b]
            }));
        let (mut lo, mut hi) = (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY));
        for p in points {
            lo = lo.inf(&p);
            hi = hi.sup(&p);
        }
        let diagonal = (hi - lo).norm();
        if diagonal.is_finite() && diagonal > 0.0 {
            1e-3 * diagonal
        } else {
            1e-3
        }
    }

    /// Every particle's mass positive and finite, its position and velocity
    /// finite.
    pub(super) fn check_particles(&self) -> Result<(), BuildError> {
        for (particle, &mass) in self.masses.iter().enumerate() {
            if !(mass.is_finite() && mass > 0.0) {
                return Err(BuildError::InvalidMass { particle, mass });
            }
            for (quantity, value) in [
                (Quantity::Position, self.positions[particle]),
                (Quantity::Velocity, self.velocities[particle]),
            ] {
                if !value.iter().all(|c| c.is_finite()) {
                    return Err(BuildError::NonFiniteParticle {
                        particle,
                        quantity,
                        value: value.into(),
                    });
                }
            }
        }
        Ok(())
    }

    /// The springs, checked (endpoints, parameters, no two on one pair),
    /// each without a rest length given taking its initial length.
    pub(super) fn resolved_springs(&self) -> Result<Vec<Spring>, BuildError> {
        let particles = self.masses.len();
        let mut seen = HashMap::with_capacity(self.springs.len());
        let mut springs = Vec::with_capacity(self.springs.len());
        for (spring, e) in self.springs.iter().enumerate() {
            if let Some(&endpoint) = [e.i, e.j].iter().find(|&&p| p >= particles) {
                return Err(BuildError::SpringEndpointOutOfRange {
                    spring,
                    endpoint,
                    particles,
                });
            }
            if e.i == e.j {
                return Err(BuildError::SelfSpring {
                    spring,
                    particle: e.i,
                });
            }
            let rest_length = e
                .rest_length
                .unwrap_or_else(|| (self.positions[e.i] - self.positions[e.j]).norm());
            for (parameter, value) in [
                (SpringParameter::Stiffness, e.stiffness),
                (SpringParameter::RestLength, rest_length),
                (SpringParameter::Damping, e.damping),
            ] {
                if !(value.is_finite() && value >= 0.0) {
                    return Err(BuildError::InvalidSpringParameter {
                        spring,
                        parameter,
                        value,
                    });
                }
            }
            if let Some(&first) = seen.get(&(e.i.min(e.j), e.i.max(e.j))) {
                return Err(BuildError::DuplicateSpring {
                    spring,
                    first,
                    i: e.i,
                    j: e.j,
                });
            }
            seen.insert((e.i.min(e.j), e.i.max(e.j)), spring);
            springs.push(Spring {
                i: e.i,
                j: e.j,
                stiffness: e.stiffness,
                rest_length,
                damping: e.damping,
            });
        }
        Ok(springs)
    }
}
