//! The cases of the property test: small random systems at random
//! states, each holding every kind of term and one contact configuration.
//!
//! Every system has a body of two volume elements sharing a face, the
//! first inverted, on damped springs that are stretched and compressed,
//! one vertex pinned; gravity and air damping; the test's own terms
//! ([`own_terms`](super::own_terms)); and one [`Contact`] configuration
//! with one [`Friction`] regime, the body well away from it.

use hooke_core::{System, SystemBuilder, Vec3};

use super::contacts::{self, Contacting};
use super::kinds::{Contact, Curvature, Draws, Friction, Parts};
use super::own_terms;

/// One case: a system, the step's start, and the point of its `Φ` the
/// checks evaluate.
pub(super) struct Case {
    pub(super) contact: Contact,
    pub(super) friction: Friction,
    /// What the case is, for messages.
    pub(super) label: String,
    pub(super) system: System,
    /// `xₙ` and `vₙ`.
    pub(super) x0: Vec<Vec3>,
    pub(super) v0: Vec<Vec3>,
    /// The velocities `v` of the point and the predictor's `ṽ`.
    pub(super) v: Vec<Vec3>,
    pub(super) v_tilde: Vec<Vec3>,
    pub(super) h: f64,
    pub(super) beta: f64,
    /// The shortest length and the lowest speed over which a term
    /// changes (the smallest gap, the sticking speed): the finite
    /// differences' steps are fractions of them.
    pub(super) length: f64,
    pub(super) speed: f64,
    /// The lever through which the rounding of the coordinates moves a
    /// gap, beyond their own size ([`Contacting::lever`]).
    pub(super) lever: f64,
    pub(super) curvature: Curvature,
}

/// The body's rest positions, m, before its scale and rotation: two
/// elements `[0, 1, 2, 3]` and `[0, 1, 2, 4]` sharing a face.
const BODY: [[f64; 3]; 5] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.2, 0.0, 0.9],
    [0.3, 0.8, 0.2],
    [0.4, -0.9, 0.3],
];

/// Where vertex 3 goes to invert the first element: through the shared
/// face.
const INVERTED: [f64; 3] = [0.35, -0.3, 0.25];

/// Every pair of the body's vertices but `(3, 4)`.
const BODY_SPRINGS: [(usize, usize); 9] = [
    (0, 1),
    (0, 2),
    (0, 3),
    (0, 4),
    (1, 2),
    (1, 3),
    (1, 4),
    (2, 3),
    (2, 4),
];

impl Case {
    /// The case `contact` with `friction`, its parameters from `draws`.
    pub(super) fn new(contact: Contact, friction: Friction, draws: &mut Draws) -> Self {
        let d_hat = draws.log_range(2e-4, 1e-3);
        let mut parts = Parts {
            builder: SystemBuilder::new(),
            x: Vec::new(),
            v: Vec::new(),
        };
        let beta = if draws.flip() { 1.0 } else { 2.0 / 3.0 };
        let near = contacts::place((contact, friction), (d_hat, beta), &mut parts, draws);
        let Contacting {
            point,
            up,
            gap,
            relative,
            curvature,
            lever,
            ref detail,
        } = near;
        // The body, well away from the contact.
        let base = point + 0.8 * up + draws.vector(0.1);
        let (scale, rotation) = (0.25, draws.rotation());
        let body: Vec<usize> = (0..BODY.len())
            .map(|k| {
                let rest = base + scale * rotation * Vec3::from(BODY[k]);
                let moved = if k == 3 { INVERTED } else { BODY[k] };
                let x = base + scale * rotation * Vec3::from(moved) + draws.vector(0.01);
                let mass = draws.log_range(1e-2, 1.0);
                parts.particle(mass, rest, x, draws.vector(0.5))
            })
            .collect();
        let springs = BODY_SPRINGS.map(|(i, j)| (body[i], body[j]));
        parts.springs(&springs, draws);
        for vertices in [[0, 1, 2, 3], [0, 1, 2, 4]] {
            let modulus = draws.log_range(1e2, 1e5);
            parts.builder.tet(vertices.map(|k| body[k]), modulus);
        }
        parts.builder.pin(body[4]);
        let anchored = body[0];
        let faces = [[0, 1, 2], [0, 1, 3]].map(|f| f.map(|k| body[k]));
        own_terms::declare(
            &mut parts.builder,
            (anchored, parts.x[anchored]),
            (point - up, &faces),
            draws,
        );
        parts
            .builder
            .gravity(9.81 * draws.direction())
            .air_damping(draws.log_range(1e-3, 0.5))
            .contact_distance(d_hat);
        let system = parts.builder.build().expect("a valid system");
        let n = system.particle_count();
        let v_tilde = (0..n).map(|_| draws.vector(0.5)).collect();
        // A step short enough that the pair's gap changes by a tenth at
        // most.
        let speed = d_hat;
        let h = (0.1 * gap / (beta * relative.max(speed))).min(1e-2);
        let length = if contact == Contact::Far {
            d_hat
        } else {
            0.5 * gap
        };
        let label = format!(
            "{contact:?} with {friction:?} friction{detail}: d̂ = {d_hat:.3e}, \
             gap {gap:.3e}, relative speed {relative:.3e}, h = {h:.3e}, β = {beta:.3}"
        );
        Self {
            contact,
            friction,
            label,
            system,
            x0: parts.x,
            v0: parts.v.clone(),
            v: parts.v,
            v_tilde,
            h,
            beta,
            length,
            speed,
            lever,
            curvature,
        }
    }
}
