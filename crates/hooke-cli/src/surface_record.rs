//! [`SurfaceRecord`]: the observer that measures, after every step, how
//! close a run's collision surfaces came to each other, for its summary.

use std::ops::ControlFlow;

use hooke_core::collision::broad::{BroadPhase, Candidates};
use hooke_core::collision::distance::{edge_edge_closest, point_triangle_closest};
use hooke_core::collision::surface::CollisionMesh;
use hooke_core::{Observer, State, StepInfo, System, Vec3};

/// Measures the pairs of surface primitives that may collide — a point
/// against a triangle, an edge against an edge, of two surfaces or of one
/// that collides with itself — in the initial state and after every step:
/// the most pairs within the contact distance `d̂` at once (a pair is
/// within it when its distance `d` less the pair's thickness
/// `ξ = (ξ₁ + ξ₂)/2` is below `d̂`, where the implicit step's barrier
/// acts) and the smallest distance `d` of such a pair. The candidates come
/// from the broad phase at `d̂ + max ξ`, their distances from
/// [`point_triangle_closest`] and [`edge_edge_closest`].
#[derive(Debug, Default)]
pub(crate) struct SurfaceRecord {
    broad: BroadPhase,
    candidates: Candidates,
    /// The most pairs within the contact distance in one state.
    pub(crate) close_pairs_max: usize,
    /// The smallest distance of a pair within the contact distance, m;
    /// `None` while none has come within it.
    pub(crate) smallest_distance: Option<f64>,
}

impl SurfaceRecord {
    /// Measures the positions `x` of `system`.
    fn measure(&mut self, system: &System, x: &[Vec3]) {
        let mesh = system.surfaces();
        if !mesh.has_pairs() || !x.iter().all(|p| p.iter().all(|c| c.is_finite())) {
            return;
        }
        let d_hat = system.contact_distance();
        let thickest = (0..system.surface_count())
            .map(|g| system.surface_thickness(g))
            .fold(0.0, f64::max);
        self.broad
            .proximity(mesh, x, d_hat + thickest, &mut self.candidates);
        let thickness =
            |g: usize, h: usize| 0.5 * (system.surface_thickness(g) + system.surface_thickness(h));
        let mut close = 0;
        let mut count = |distance: f64, thickness: f64| {
            if distance - thickness < d_hat {
                close += 1;
                self.smallest_distance = Some(
                    self.smallest_distance
                        .map_or(distance, |d: f64| d.min(distance)),
                );
            }
        };
        for &(v, t) in &self.candidates.point_triangle {
            let (v, t) = (v as usize, t as usize);
            let [a, b, c] = mesh.triangles()[t].map(|i| x[i]);
            let closest = point_triangle_closest(x[mesh.vertices()[v]], a, b, c);
            count(
                closest.squared.max(0.0).sqrt(),
                thickness(mesh.vertex_group(v), mesh.triangle_group(t)),
            );
        }
        for &(e, f) in &self.candidates.edge_edge {
            let (e, f) = (e as usize, f as usize);
            let ([a0, a1], [b0, b1]) = (edge(mesh, x, e), edge(mesh, x, f));
            let closest = edge_edge_closest(a0, a1, b0, b1);
            count(
                closest.squared.max(0.0).sqrt(),
                thickness(mesh.edge_group(e), mesh.edge_group(f)),
            );
        }
        self.close_pairs_max = self.close_pairs_max.max(close);
    }
}

/// The ends of edge `e` of `mesh` at the positions `x`.
fn edge(mesh: &CollisionMesh, x: &[Vec3], e: usize) -> [Vec3; 2] {
    mesh.edges()[e].map(|i| x[i])
}

impl Observer for SurfaceRecord {
    fn start(&mut self, system: &System, state: &State) {
        self.measure(system, state.positions());
    }

    fn observe(&mut self, system: &System, state: &State, _step: &StepInfo) -> ControlFlow<()> {
        self.measure(system, state.positions());
        ControlFlow::Continue(())
    }
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;
    use hooke_core::SystemBuilder;

    use super::*;

    /// Two triangles of two surfaces, parallel, `gap` apart.
    fn two_triangles(gap: f64, thickness: f64) -> System {
        let mut b = SystemBuilder::new();
        let mut triangle = |y: f64| {
            let [p, q, r] =
                [[0.0, y, 0.0], [1.0, y, 0.0], [0.0, y, 1.0]].map(|x| b.particle(1.0, x));
            [p, q, r]
        };
        let (lower, upper) = (triangle(0.0), triangle(gap));
        b.surface(&[lower]).thickness(thickness);
        b.surface(&[upper]).thickness(thickness);
        b.contact_distance(1e-2);
        b.build().unwrap()
    }

    #[test]
    fn pairs_within_the_contact_distance_are_counted_with_their_distance() {
        let system = two_triangles(4e-3, 0.0);
        let mut record = SurfaceRecord::default();
        record.start(&system, &system.initial_state());
        // Each of the six corners over the other triangle (the three of
        // each triangle: two of them over the other's edges or corners),
        // and the edges above each other.
        assert!(record.close_pairs_max >= 6, "{}", record.close_pairs_max);
        assert_relative_eq!(record.smallest_distance.unwrap(), 4e-3, epsilon = 1e-15);
    }

    #[test]
    fn pairs_beyond_the_contact_distance_and_thickness_are_not() {
        let mut record = SurfaceRecord::default();
        let far = two_triangles(2e-2, 0.0);
        record.start(&far, &far.initial_state());
        assert_eq!(record.close_pairs_max, 0);
        assert_eq!(record.smallest_distance, None);
        // A thickness of 1.5 cm brings the same gap within reach.
        let thick = two_triangles(2e-2, 1.5e-2);
        record.start(&thick, &thick.initial_state());
        assert!(record.close_pairs_max > 0);
        assert_relative_eq!(record.smallest_distance.unwrap(), 2e-2, epsilon = 1e-15);
    }
}
