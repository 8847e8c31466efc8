//! One contact pair of any kind — a particle and an obstacle, a point and a
//! triangle, two edges — and everything a step evaluates on it: its gap,
//! its barrier term's value, gradient and Hessian, how far along a motion
//! it stays apart (continuous collision detection), and its lagged
//! friction. The rest of the contact code handles pairs only through these.
//!
//! A pair's gap is its distance less its thickness: `g = d − ξ` with `ξ`
//! the mean of two surfaces' thicknesses, or `g = φ(x) − ξ/2` for a
//! particle on a surface of thickness `ξ` against an obstacle whose signed
//! distance is `φ` (`ξ = 0` for a particle on no surface). Its term is
//! `κ b(g)` ([`Barrier`]) — for two edges `κ m b(g)`, with the mollifier
//! `m` that fades the term out as the edges turn parallel, where the
//! edge–edge distance stops being smooth (Li et al. 2020, §4.3). A surface
//! pair's gradient and Hessian in its 12 coordinates come from
//! `hooke_core::collision`, the Hessian projected onto its positive part,
//! and its 3×3 blocks join the step's matrix on the four particles'
//! diagonals and between them; a particle's against an obstacle are
//! `κ b'(g) n` and the positive part `κ b''(g) n nᵀ` (see
//! [`Barrier`]'s module).

use hooke_core::collision::barrier::Barrier;
use hooke_core::collision::ccd::{edge_edge_ccd, point_triangle_ccd};
use hooke_core::collision::distance::{
    Derivatives, edge_edge_closest, edge_edge_mollifier, edge_edge_squared,
    edge_edge_squared_distance, mollifier_threshold, point_triangle_closest,
    point_triangle_squared, point_triangle_squared_distance,
};
use hooke_core::{Mat3, System, Vec3};

use super::friction::Lagged;
use super::obstacles::{At, Obstacles};
use crate::linear::matrix::HessianBlocks;
use hooke_core::SymBlock;

/// What a pair's particles meet.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Kind {
    /// The point `particles[0]` and the triangle `particles[1..4]`.
    PointTriangle,
    /// The edges `particles[0..2]` and `particles[2..4]`.
    EdgeEdge,
    /// The particle `particles[0]` (repeated) and the obstacle of this
    /// index.
    Obstacle(usize),
}

/// One pair: its kind, particles, thickness and friction coefficient.
#[derive(Debug, Clone, Copy)]
pub(super) struct Pair {
    pub(super) kind: Kind,
    pub(super) particles: [usize; 4],
    /// `ξ` of a surface pair, `ξ/2` of a particle against an obstacle.
    pub(super) thickness: f64,
    /// The mean of the two surfaces' friction coefficients, or the
    /// obstacle's.
    pub(super) friction: f64,
}

/// What the pairs are evaluated against: the system (the rest positions
/// for the edge–edge mollifier) and the obstacles where they are at one
/// moment of the step.
#[derive(Debug, Clone, Copy)]
pub(super) struct Geometry<'a> {
    pub(super) system: &'a System,
    pub(super) obstacles: &'a Obstacles,
    pub(super) at: At,
}

impl<'a> Geometry<'a> {
    /// The pairs' geometry for `system`, the obstacles where they are `at`.
    pub(super) fn new(system: &'a System, obstacles: &'a Obstacles, at: At) -> Self {
        Self {
            system,
            obstacles,
            at,
        }
    }
}

impl Pair {
    /// The pair of vertex `v` and triangle `t` of the collision mesh.
    pub(super) fn point_triangle(system: &System, (v, t): (u32, u32)) -> Self {
        let mesh = system.surfaces();
        let (v, t) = (v as usize, t as usize);
        let [a, b, c] = mesh.triangles()[t];
        let (thickness, friction) =
            Self::between(system, mesh.vertex_group(v), mesh.triangle_group(t));
        Self {
            kind: Kind::PointTriangle,
            particles: [mesh.vertices()[v], a, b, c],
            thickness,
            friction,
        }
    }

    /// The pair of edges `e` and `f` of the collision mesh.
    pub(super) fn edge_edge(system: &System, (e, f): (u32, u32)) -> Self {
        let mesh = system.surfaces();
        let (e, f) = (e as usize, f as usize);
        let ([a0, a1], [b0, b1]) = (mesh.edges()[e], mesh.edges()[f]);
        let (thickness, friction) = Self::between(system, mesh.edge_group(e), mesh.edge_group(f));
        Self {
            kind: Kind::EdgeEdge,
            particles: [a0, a1, b0, b1],
            thickness,
            friction,
        }
    }

    /// The pair of particle `i` and obstacle `k`.
    pub(super) fn obstacle(system: &System, obstacles: &Obstacles, (i, k): (u32, u32)) -> Self {
        let (i, k) = (i as usize, k as usize);
        Self {
            kind: Kind::Obstacle(k),
            particles: [i; 4],
            thickness: obstacles.offset(i),
            friction: system.obstacles()[k].friction,
        }
    }

    /// The thickness and friction coefficient of a pair between surfaces
    /// `g` and `h`: the means of theirs.
    fn between(system: &System, g: usize, h: usize) -> (f64, f64) {
        (
            0.5 * (system.surface_thickness(g) + system.surface_thickness(h)),
            0.5 * (system.surface_friction(g) + system.surface_friction(h)),
        )
    }

    fn positions(&self, x: &[Vec3]) -> [Vec3; 4] {
        self.particles.map(|p| x[p])
    }

    /// The largest of `value(p)` over the particles `p` of a surface pair's
    /// first primitive (the point, or the first edge), and over its
    /// second's.
    pub(super) fn largest(&self, value: impl Fn(usize) -> f64) -> (f64, f64) {
        let split = if self.kind == Kind::EdgeEdge { 2 } else { 1 };
        let (first, second) = self.particles.split_at(split);
        let largest = |ps: &[usize]| ps.iter().map(|&p| value(p)).fold(0.0, f64::max);
        (largest(first), largest(second))
    }

    /// The squared distance of a surface pair at `x`, without derivatives.
    pub(super) fn squared(&self, x: &[Vec3]) -> f64 {
        let [p0, p1, p2, p3] = self.positions(x);
        if self.kind == Kind::EdgeEdge {
            edge_edge_squared_distance(p0, p1, p2, p3)
        } else {
            point_triangle_squared_distance(p0, p1, p2, p3)
        }
    }

    /// The distance of a surface pair at `x`, without derivatives.
    pub(super) fn distance(&self, x: &[Vec3]) -> f64 {
        self.squared(x).max(0.0).sqrt()
    }

    /// The gap of a surface pair whose squared distance is `squared`.
    fn surface_gap(&self, squared: f64) -> f64 {
        squared.max(0.0).sqrt() - self.thickness
    }

    /// The gap `g` at `x`, and the outward normal of an obstacle pair's
    /// obstacle (zero for a surface pair).
    pub(super) fn gap(&self, geometry: &Geometry, x: &[Vec3]) -> (f64, Vec3) {
        match self.kind {
            Kind::Obstacle(k) => {
                let i = self.particles[0];
                geometry.obstacles.gap(k, i, x[i], geometry.at)
            }
            _ => (self.surface_gap(self.squared(x)), Vec3::zeros()),
        }
    }

    /// The edge–edge mollifier threshold of a pair, from its rest positions.
    fn threshold(&self, system: &System) -> f64 {
        let rest = system.initial_positions();
        let [r0, r1, r2, r3] = self.particles.map(|p| rest[p]);
        mollifier_threshold(r0, r1, r2, r3)
    }

    /// The barrier term per unit stiffness at `x` (`m b(g)` for two edges,
    /// `b(g)` otherwise): zero beyond the contact distance, infinite if the
    /// gap is not positive. The line search's cheap path: no derivatives.
    pub(super) fn energy(&self, geometry: &Geometry, x: &[Vec3], barrier: &Barrier) -> f64 {
        let gap = self.gap(geometry, x).0;
        if !barrier.active(gap) {
            return 0.0;
        }
        if gap <= 0.0 {
            return f64::INFINITY;
        }
        let b = barrier.unit(gap).0;
        if self.kind == Kind::EdgeEdge {
            let [p0, p1, p2, p3] = self.positions(x);
            b * edge_edge_mollifier(p0, p1, p2, p3, self.threshold(geometry.system)).value
        } else {
            b
        }
    }

    /// The barrier term per unit stiffness of a surface pair at `x`, with
    /// its derivatives in the pair's 12 coordinates; `None` beyond the
    /// contact distance.
    fn surface_term(&self, system: &System, x: &[Vec3], barrier: &Barrier) -> Option<Derivatives> {
        if !barrier.active(self.surface_gap(self.squared(x))) {
            return None;
        }
        let [p0, p1, p2, p3] = self.positions(x);
        if self.kind == Kind::EdgeEdge {
            let threshold = self.threshold(system);
            let squared = edge_edge_squared(p0, p1, p2, p3);
            let mollifier = edge_edge_mollifier(p0, p1, p2, p3, threshold);
            barrier.mollified_pair(&squared, &mollifier, self.thickness)
        } else {
            let squared = point_triangle_squared(p0, p1, p2, p3);
            barrier.pair(&squared, self.thickness)
        }
    }

    /// Adds the pair's barrier term at `x` to a Newton system in the
    /// velocities (`x = x̃ + βh v`) with `scale = (κβh, κβ²h²)`:
    /// `b −= κβh ∇b`, `A += κβ²h² ∇²b` (the Hessian's positive part);
    /// returns whether the pair is within the contact distance.
    pub(super) fn add(
        &self,
        geometry: &Geometry,
        x: &[Vec3],
        (barrier, (kb, kbb)): (&Barrier, (f64, f64)),
        b: &mut [Vec3],
        a: &mut impl HessianBlocks,
    ) -> bool {
        if let Kind::Obstacle(_) = self.kind {
            let (gap, n) = self.gap(geometry, x);
            if !barrier.active(gap) {
                return false;
            }
            let i = self.particles[0];
            let (_, slope, curvature) = barrier.unit(gap);
            b[i] -= kb * slope * n;
            a.add_row(i, SymBlock::rank_one_plus_identity(kbb * curvature, n, 0.0));
            return true;
        }
        let Some(term) = self.surface_term(geometry.system, x, barrier) else {
            return false;
        };
        for (k, &p) in self.particles.iter().enumerate() {
            let g = term.gradient.fixed_rows::<3>(3 * k).into_owned();
            b[p] -= kb * g;
            let block: Mat3 = term.hessian.fixed_view::<3, 3>(3 * k, 3 * k).into_owned();
            a.add_row(p, SymBlock::symmetric_part(&(kbb * block)));
            for (l, &q) in self.particles.iter().enumerate().skip(k + 1) {
                let block: Mat3 = term.hessian.fixed_view::<3, 3>(3 * k, 3 * l).into_owned();
                a.add_pair(p, q, kbb * block);
            }
        }
        true
    }

    /// The largest `τ ∈ [0, 1]` such that the motion from `x` to
    /// `x + τ dx` keeps the pair at least `keep` of its gap at `x`: additive
    /// CCD for a surface pair; for a particle, the CCD of the obstacle's
    /// shape at the step's end ([`hooke_core::Shape::advance`]), skipped
    /// (`τ = 1`) while the particle moves less than the `1 − keep` of its
    /// gap it may lose, and `0` if it starts at a gap `≤ 0` and moves.
    pub(super) fn ccd(&self, geometry: &Geometry, x: &[Vec3], dx: &[Vec3], keep: f64) -> f64 {
        let Kind::Obstacle(k) = self.kind else {
            let (q, d) = (self.positions(x), self.particles.map(|p| dx[p]));
            return if self.kind == Kind::EdgeEdge {
                edge_edge_ccd(q, d, self.thickness, keep)
            } else {
                point_triangle_ccd(q, d, self.thickness, keep)
            };
        };
        let i = self.particles[0];
        if dx[i] == Vec3::zeros() {
            return 1.0;
        }
        let (gap, _) = self.gap(geometry, x);
        if gap <= 0.0 {
            return 0.0;
        }
        if (1.0 - keep) * gap > dx[i].norm() {
            return 1.0;
        }
        let shape = geometry.obstacles.shape(k);
        shape.advance(x[i], dx[i], self.thickness + keep * gap)
    }

    /// The pair's friction lagged at `x` (the step's start, the obstacles
    /// there), for a step of `h`: `None` without friction or beyond the
    /// contact distance. The normal force is `λ = κ m |b'(g)|` (`m` the
    /// edge–edge mollifier, 1 otherwise) along the line between the
    /// closest points, whose weights make the relative velocity; against an
    /// obstacle, `λ = −κ b'(g)` along its normal, relative to its velocity
    /// over the step.
    pub(super) fn lag(
        &self,
        geometry: &Geometry,
        x: &[Vec3],
        barrier: &Barrier,
        h: f64,
    ) -> Option<Lagged> {
        if self.friction <= 0.0 {
            return None;
        }
        let activation = barrier.activation;
        if let Kind::Obstacle(k) = self.kind {
            let (gap, normal) = self.gap(geometry, x);
            if gap <= 0.0 || gap >= activation {
                return None;
            }
            let velocity = geometry.obstacles.moved()[k] / h;
            let bound = self.friction * barrier.force(gap);
            return Some(Lagged::new(
                &self.particles[..1],
                &[1.0],
                normal,
                velocity,
                bound,
            ));
        }
        let [p0, p1, p2, p3] = self.positions(x);
        let (closest, mollifier) = if self.kind == Kind::EdgeEdge {
            let threshold = self.threshold(geometry.system);
            (
                edge_edge_closest(p0, p1, p2, p3),
                edge_edge_mollifier(p0, p1, p2, p3, threshold).value,
            )
        } else {
            (point_triangle_closest(p0, p1, p2, p3), 1.0)
        };
        let distance = closest.squared.sqrt();
        let gap = distance - self.thickness;
        if gap <= 0.0 || gap >= activation || distance == 0.0 {
            return None;
        }
        let between: Vec3 = (0..4)
            .map(|k| closest.weights[k] * x[self.particles[k]])
            .sum();
        let force = barrier.stiffness * mollifier * barrier.unit(gap).1.abs();
        Some(Lagged::new(
            &self.particles,
            &closest.weights,
            between / distance,
            Vec3::zeros(),
            self.friction * force,
        ))
    }

    /// The work `½ (F₀ + F₁)·Δo` that an obstacle pair's obstacle, moving
    /// by `Δo` over the step, did on its particle from `x0` (the obstacle at
    /// the start, `start`) to `x` (at the end, `end`), by the trapezoid rule
    /// on the barrier's force `F = −κ b'(g) n` (zero outside `0 < g < d̂`);
    /// zero for a surface pair and a fixed obstacle.
    pub(super) fn obstacle_work(
        &self,
        (start, x0): (&Geometry, &[Vec3]),
        (end, x): (&Geometry, &[Vec3]),
        barrier: &Barrier,
    ) -> f64 {
        let Kind::Obstacle(k) = self.kind else {
            return 0.0;
        };
        let moved = end.obstacles.moved()[k];
        if moved == Vec3::zeros() {
            return 0.0;
        }
        let force = |geometry: &Geometry, x: &[Vec3]| {
            let (gap, n) = self.gap(geometry, x);
            if gap > 0.0 && gap < barrier.activation {
                barrier.force(gap) * n
            } else {
                Vec3::zeros()
            }
        };
        0.5 * (force(start, x0) + force(end, x)).dot(&moved)
    }
}
