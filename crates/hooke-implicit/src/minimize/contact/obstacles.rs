//! Contact with obstacles as terms of the incremental potential: a barrier
//! on each particle's gap to each obstacle, the exact continuous collision
//! detection that bounds a line search, and the lagged friction.
//!
//! A particle on a surface of thickness `ξ` has the gap `g = φ(x) − ξ/2` to
//! an obstacle whose signed distance is `φ` (exact for planes, spheres,
//! boxes and capsules); other particles have `g = φ`. The barrier term is
//! `κ b(g)` (see the `contact` module), its gradient `κ b'(g) n` and its
//! Hessian `κ [b''(g) n nᵀ + b'(g) ∇²φ]` projected onto its positive part:
//! `b' < 0` and the distance to a convex shape is convex (`∇²φ ⪰ 0`), so
//! the projection is `κ b''(g) n nᵀ`.

use hooke_core::{Obstacle, Shape, System, Vec3, collision::barrier::barrier};

use super::friction::Lagged;

/// Iterations of conservative advancement before it settles for the
/// fraction reached.
const ADVANCEMENT_ITERATIONS: usize = 64;

/// The largest `τ ∈ [0, 1]` such that a particle moving from `x` to
/// `x + τ dx` keeps its signed distance from `shape` at least
/// `target < φ(x)`: exact for a plane and a sphere; conservative
/// advancement for the others, whose signed distance is 1-Lipschitz, so
/// that `φ(x + τ dx) ≥ target` for `τ ≤ (φ(x) − target)/|dx|` and each
/// advance is safe.
pub(crate) fn advance(shape: &Shape, x: Vec3, dx: Vec3, target: f64) -> f64 {
    let length = dx.norm();
    if length == 0.0 {
        return 1.0;
    }
    match *shape {
        Shape::Plane { normal, .. } => {
            let rate = normal.normalize().dot(&dx);
            let phi = shape.distance(x).0;
            if rate >= 0.0 {
                1.0
            } else {
                ((phi - target) / -rate).clamp(0.0, 1.0)
            }
        }
        Shape::Sphere { center, radius } => {
            // |r + τ dx| = R with r = x − c, R = radius + target.
            let r = x - center;
            let reach = radius + target;
            let (a, b, c) = (
                length * length,
                2.0 * r.dot(&dx),
                r.norm_squared() - reach * reach,
            );
            let discriminant = b * b - 4.0 * a * c;
            if b >= 0.0 || discriminant < 0.0 {
                return 1.0;
            }
            // The smaller root, written to avoid cancellation.
            let q = -0.5 * (b - discriminant.sqrt());
            (c / q).clamp(0.0, 1.0)
        }
        Shape::Box { .. } | Shape::Capsule { .. } => {
            let mut tau = 0.0;
            let start = shape.distance(x).0 - target;
            for _ in 0..ADVANCEMENT_ITERATIONS {
                let room = shape.distance(x + tau * dx).0 - target;
                if room <= 1e-3 * start {
                    break;
                }
                tau += room / length;
                if tau >= 1.0 {
                    return 1.0;
                }
            }
            tau
        }
    }
}

/// The obstacles during one step, at the step's end.
#[derive(Debug, Clone, Default)]
pub(crate) struct Obstacles {
    /// Each obstacle's shape at the end of the step.
    shapes: Vec<Shape>,
    /// Each obstacle's displacement over the step.
    moved: Vec<Vec3>,
    /// Each particle's offset `ξ/2` from obstacles (half its surface's
    /// thickness).
    offset: Vec<f64>,
}

impl Obstacles {
    /// Places the obstacles of `system` at the end of a step from `time`
    /// to `time + h`; `fresh` for a system not seen before.
    pub(crate) fn begin(&mut self, system: &System, time: f64, h: f64, fresh: bool) {
        self.shapes.clear();
        self.moved.clear();
        for o in system.obstacles() {
            let offset = o.path.offset(time + h);
            self.shapes.push(o.shape.translated(offset));
            self.moved.push(offset - o.path.offset(time));
        }
        if fresh {
            self.offset = vec![0.0; system.particle_count()];
            let mesh = system.surfaces();
            for (k, &p) in mesh.vertices().iter().enumerate() {
                self.offset[p] = 0.5 * system.surface_thickness(mesh.vertex_group(k));
            }
        }
    }

    /// Each obstacle's displacement over the step.
    pub(crate) fn moved(&self) -> &[Vec3] {
        &self.moved
    }

    /// The gap `g` of particle `i` at `x` to obstacle `k` (at the step's
    /// end) and the outward normal.
    pub(crate) fn gap(&self, k: usize, i: usize, x: Vec3) -> (f64, Vec3) {
        let (phi, n) = self.shapes[k].distance(x);
        (phi - self.offset[i], n)
    }

    /// The gap of particle `i` at `x` to obstacle `o` at time `t`.
    pub(crate) fn gap_at(&self, o: &Obstacle, i: usize, x: Vec3, t: f64) -> (f64, Vec3) {
        let (phi, n) = o.distance(x, t);
        (phi - self.offset[i], n)
    }

    /// The number of obstacles.
    pub(crate) fn len(&self) -> usize {
        self.shapes.len()
    }

    /// The largest `τ ∈ [0, 1]` such that particle `i` moving from `x` to
    /// `x + τ dx` keeps at least `keep` of its gap to every obstacle within
    /// `reach` (farther ones are ignored while the motion is shorter than
    /// their gap's margin).
    pub(crate) fn limit(&self, i: usize, x: Vec3, dx: Vec3, keep: f64) -> f64 {
        let mut tau: f64 = 1.0;
        for (k, shape) in self.shapes.iter().enumerate() {
            let (gap, _) = self.gap(k, i, x);
            if gap <= 0.0 {
                return 0.0;
            }
            if (1.0 - keep) * gap > dx.norm() {
                continue;
            }
            tau = tau.min(advance(shape, x, dx, self.offset[i] + keep * gap));
        }
        tau
    }
}

/// The lagged friction of particle `i` at `x` (the step's start, at
/// `time`) against every obstacle of `system` within the activation
/// distance, with barrier stiffness `kappa`, into `out`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn lag_friction(
    obstacles: &Obstacles,
    system: &System,
    i: usize,
    x: Vec3,
    time: f64,
    h: f64,
    (kappa, activation): (f64, f64),
    out: &mut Vec<Lagged>,
) {
    for (k, o) in system.obstacles().iter().enumerate() {
        if o.friction <= 0.0 {
            continue;
        }
        let (gap, normal) = obstacles.gap_at(o, i, x, time);
        if gap <= 0.0 || gap >= activation {
            continue;
        }
        let force = -kappa * barrier(gap, activation).1;
        let velocity = obstacles.moved()[k] / h;
        out.push(Lagged::new(
            &[i],
            &[1.0],
            normal,
            velocity,
            o.friction * force,
        ));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shapes() -> Vec<Shape> {
        vec![
            Shape::Plane {
                point: Vec3::new(0.0, 0.2, 0.0),
                normal: Vec3::new(0.3, 2.0, -0.1),
            },
            Shape::Sphere {
                center: Vec3::new(0.1, -0.2, 0.3),
                radius: 0.7,
            },
            Shape::Box {
                center: Vec3::new(-0.1, 0.0, 0.2),
                half_extents: Vec3::new(0.5, 0.3, 0.8),
                rotation: *nalgebra::Rotation3::from_euler_angles(0.3, -0.5, 1.1).matrix(),
            },
            Shape::Capsule {
                a: Vec3::new(-0.4, 0.0, 0.0),
                b: Vec3::new(0.5, 0.3, -0.2),
                radius: 0.35,
            },
        ]
    }

    #[test]
    fn advancement_stops_a_fast_particle_at_the_kept_gap_and_never_crosses() {
        for shape in shapes() {
            for k in 0..200 {
                let f = |a: f64| 2.0 * (a * k as f64 + 0.3).sin();
                let x = Vec3::new(f(0.71), f(1.37), f(2.11));
                let phi = shape.distance(x).0;
                if phi <= 0.01 {
                    continue;
                }
                // Through the shape's centre region and far beyond it.
                let dx = 10.0 * (Vec3::new(0.05, -0.1, 0.2) - x);
                let target = 0.1 * phi;
                let tau = advance(&shape, x, dx, target);
                for j in 0..=1000 {
                    let s = tau * f64::from(j) / 1000.0;
                    assert!(
                        shape.distance(x + s * dx).0 >= target - 1e-9,
                        "{shape:?} from {x:?}: crossed at {s} < τ = {tau}"
                    );
                }
                if tau < 1.0 {
                    // Not absurdly conservative: within 1 % of the gap kept.
                    let reached = shape.distance(x + tau * dx).0;
                    assert!(
                        reached - target <= 0.01 * (phi - target) + 1e-12,
                        "{shape:?}: stopped at φ = {reached}, target {target}"
                    );
                }
            }
        }
    }
}
