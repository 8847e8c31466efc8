//! What a [`Scene`] looks like to the output layer: one [`Mesh`] for all of
//! its bodies, and its obstacles as drawable [`Shape`]s at a given time.

use hooke_core::{Shape, System};
use hooke_scenes::Scene;

use crate::error::OutputError;
use crate::mesh::Mesh;

/// One mesh for every body of `scene`, in system particle indices.
///
/// Its vertices are all the particles of the system, so every frame is the
/// whole state, including particles that no body draws (a lone oscillator
/// bob is still a vertex of the PLY files). Triangles and edges are the
/// bodies' surface triangles and segments, concatenated. Particles of no
/// body that has triangles or segments would otherwise be invisible in
/// pictures, so the springs joining two such particles become edges too.
///
/// ```
/// use hooke_core::SystemBuilder;
/// use hooke_scenes::{IntegratorSpec, Scene, Timing};
/// let mut b = SystemBuilder::new();
/// let anchor = b.particle(1.0, [0.0, 0.0, 0.0]);
/// let bob = b.particle(1.0, [0.0, -1.0, 0.0]);
/// b.pin(anchor);
/// b.spring(anchor, bob, 100.0);
/// let scene = Scene {
///     name: "oscillator".into(),
///     system: b.build()?,
///     bodies: Vec::new(),
///     integrator: IntegratorSpec::backward_euler(),
///     timing: Timing { duration: 1.0, dt: 0.01, frame_rate: 30.0 },
/// };
/// let mesh = hooke_viz::scene_mesh(&scene)?;
/// assert_eq!((mesh.vertex_count(), mesh.edges()), (2, &[[0, 1]][..]));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// [`OutputError::VertexOutOfRange`] for a body triangle or segment naming
/// a particle the system does not have; [`OutputError::TooManyVertices`]
/// for a system too large for PLY indices.
pub fn scene_mesh(scene: &Scene) -> Result<Mesh, OutputError> {
    let particles = scene.system.particle_count();
    let mut drawn = vec![false; particles];
    let mut triangles = Vec::new();
    let mut edges = Vec::new();
    for body in &scene.bodies {
        triangles.extend(body.triangles.iter().map(|t| t.map(vertex)));
        edges.extend(body.segments.iter().map(|s| s.map(vertex)));
        if !(body.triangles.is_empty() && body.segments.is_empty()) {
            for i in body.placement.range() {
                if let Some(d) = drawn.get_mut(i) {
                    *d = true;
                }
            }
        }
    }
    edges.extend(
        scene
            .system
            .springs()
            .iter()
            .filter(|s| !drawn[s.i] && !drawn[s.j])
            .map(|s| [s.i, s.j].map(vertex)),
    );
    Mesh::new(particles, triangles, edges)
}

/// A particle index as a mesh vertex; an index beyond `u32` becomes
/// `u32::MAX`, which [`Mesh::new`] then reports as out of range.
fn vertex(i: usize) -> u32 {
    u32::try_from(i).unwrap_or(u32::MAX)
}

/// The obstacles of `system` as drawn at time `t`: each shape moved by its
/// path's offset at `t`.
#[must_use]
pub fn obstacles_at(system: &System, t: f64) -> Vec<Shape> {
    system
        .obstacles()
        .iter()
        .map(|obstacle| obstacle.shape.translated(obstacle.path.offset(t)))
        .collect()
}
