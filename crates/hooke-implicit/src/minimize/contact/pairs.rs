//! Contact between surface primitives as terms of the incremental
//! potential: point–triangle and edge–edge pairs of the system's collision
//! surfaces, within a body (self-collision) and between bodies.
//!
//! A pair of the 12 coordinates `q` (its four particles) at distance `d(q)`
//! has the gap `g = d − ξ`, with `ξ` the mean of its two surfaces'
//! thicknesses, and the term `κ b(g)` — for two edges `κ m(q) b(g)`, with
//! the mollifier `m` that fades the term out as the edges turn parallel,
//! where the edge–edge distance stops being smooth (Li et al. 2020, §4.3).
//! Its gradient and Hessian in `q` come from `hooke_core::collision`, the
//! Hessian projected onto its positive part; the Hessian's 3x3 blocks join
//! the step's matrix on the four particles' diagonals and between them.
//! The broad phase finds the pairs whose boxes come within reach; the
//! line search is bounded by additive continuous collision detection on
//! every pair whose boxes, swept over the motion, overlap.

use hooke_core::collision::barrier::barrier;
use hooke_core::collision::barrier::{mollified_pair_barrier, pair_barrier};
use hooke_core::collision::broad::{BroadPhase, Candidates};
use hooke_core::collision::ccd::{edge_edge_ccd, point_triangle_ccd};
use hooke_core::collision::distance::{
    Derivatives, edge_edge_closest, edge_edge_mollifier, edge_edge_squared,
    edge_edge_squared_distance, mollifier_threshold, point_triangle_closest,
    point_triangle_squared, point_triangle_squared_distance,
};
use hooke_core::{Mat3, System, Vec3};

use super::friction::Lagged;
use crate::linear::block::SymBlock;
use crate::linear::matrix::HessianBlocks;

/// How far beyond the contact distance `d̂` (plus thickness) a proximity
/// search reaches, in units of `d̂`: its candidates stay valid, at any
/// positions and along any motion, while no particle is more than half
/// that margin from where they were found once the particles' common
/// translation is taken off (a Verlet list; see [`Pairs`]).
pub(super) const MARGIN: f64 = 4.0;

/// The widest margin of a search, in units of the surfaces' mean edge
/// length at rest. A fine mesh's contact distance is a quarter of that
/// edge (by default, at most), so its margin stays at `d̂` and the reach
/// `d̂ + s` within half an edge: the closest pairs of a flat triangulated
/// grid that share no particle — a vertex and the diagonal across from it,
/// 0.71 of a spacing or 0.62 of the mean edge apart — stay out of the
/// list, which on a million-particle cloth would otherwise hold tens of
/// pairs a particle.
const WIDEST: f64 = 0.25;

/// The pairs of a system's surfaces, with the broad phase's buffers.
///
/// A proximity search at `x_s` with reach `d̂ + ξ + s` (`ξ` the largest
/// thickness, `s` the margin) finds every pair closer than that; the list
/// keeps those whose distance, less their own thickness, is below `d̂ + s`.
/// A pair left out stays farther than `d̂` plus its thickness apart as long
/// as every particle keeps within `s/2` of `x_s` moved by one common
/// translation `t` — distances do not change when every particle is moved
/// by `t`, and a ball is convex, so along a straight motion between two
/// such configurations too (with `t` moving straight along with them).
/// The list then holds every pair with a barrier term and every pair that
/// can collide, and serves the iterations of a step, and the steps after
/// it, until a particle leaves its ball: a cloth falling or carried as a
/// whole keeps its list. A motion that would leave it gets a new search.
/// The translation taken is the centre of the box of the particles'
/// displacements from `x_s` ([`drift`]).
///
/// Each candidate's distance `D` at `x_s` is kept with the list. A point
/// of a segment or triangle moves no farther than its farthest corner, so
/// at positions `x` the pair is at least `D − δ₁ − δ₂` apart, `δ₁` and `δ₂`
/// the farthest either primitive's corners have moved from `x_s` (the
/// common translation taken off); a pair for which that exceeds `d̂` plus
/// its thickness has no barrier term and no friction, and its exact
/// distance is not computed.
#[derive(Debug, Default)]
pub(crate) struct Pairs {
    pub(super) broad: BroadPhase,
    /// The candidates of the last search: the pairs within reach of its
    /// positions (with the margin, by their distance there), or whose
    /// boxes meet anywhere along a checked motion.
    pub(super) near: Candidates,
    /// The positions of the last search (the start of the motion of a
    /// swept one); empty before the first.
    pub(super) reference: Vec<Vec3>,
    /// Each candidate's distance at `reference`, in the order of
    /// [`Pairs::pairs`].
    pub(super) searched: Vec<f64>,
    /// The margin `s` of the last proximity search; zero after a swept
    /// search, whose list is no Verlet list.
    pub(super) margin: f64,
    /// The largest thickness of a pair.
    pub(super) thickest: f64,
    /// The widest margin of a search ([`WIDEST`] mean edges).
    pub(super) widest: f64,
    /// Scratch for the end of a motion.
    pub(super) end: Vec<Vec3>,
    /// Scratch for each particle's distance from [`Pairs::reference`] at
    /// the start of a motion, and the farthest it gets along the motion.
    pub(super) moved: Vec<(f64, f64)>,
}

/// One pair's particles, its thickness, and whether it is an edge–edge
/// pair.
#[derive(Debug, Clone, Copy)]
pub(super) struct Pair {
    pub(super) particles: [usize; 4],
    pub(super) thickness: f64,
    /// The mean of the two surfaces' friction coefficients.
    pub(super) friction: f64,
    pub(super) edges: bool,
}

impl Pair {
    pub(super) fn positions(&self, x: &[Vec3]) -> [Vec3; 4] {
        self.particles.map(|p| x[p])
    }

    /// The largest of `value(p)` over the particles `p` of the pair's first
    /// primitive (the point, or the first edge), and over its second's.
    pub(super) fn largest(&self, value: impl Fn(usize) -> f64) -> (f64, f64) {
        let split = if self.edges { 2 } else { 1 };
        let (first, second) = self.particles.split_at(split);
        let largest = |ps: &[usize]| ps.iter().map(|&p| value(p)).fold(0.0, f64::max);
        (largest(first), largest(second))
    }

    /// The largest `τ ∈ [0, 1]` that additive CCD allows the pair along
    /// the motion from `x` to `x + τ dx`, keeping at least `keep` of its gap.
    pub(super) fn ccd(&self, x: &[Vec3], dx: &[Vec3], keep: f64) -> f64 {
        let (q, d) = (self.positions(x), self.particles.map(|p| dx[p]));
        if self.edges {
            edge_edge_ccd(q, d, self.thickness, keep)
        } else {
            point_triangle_ccd(q, d, self.thickness, keep)
        }
    }
}

impl Pairs {
    /// Sets up the pairs of `system`: the largest thickness, and the widest
    /// margin from the surfaces' edges at rest.
    pub(crate) fn begin(&mut self, system: &System) {
        self.thickest = (0..system.surface_count())
            .map(|g| system.surface_thickness(g))
            .fold(0.0, f64::max);
        let rest = system.initial_positions();
        let edges = system.surfaces().edges();
        let total: f64 = edges.iter().map(|&[a, b]| (rest[a] - rest[b]).norm()).sum();
        self.widest = WIDEST * total / edges.len().max(1) as f64;
    }

    /// The pairs among `candidates`, with their particles and thickness:
    /// the point–triangle pairs, then the edge–edge pairs.
    pub(super) fn pairs<'a>(
        system: &'a System,
        candidates: &'a Candidates,
    ) -> impl Iterator<Item = Pair> + 'a {
        let point_triangle = candidates
            .point_triangle
            .iter()
            .map(|&vt| Self::point_triangle(system, vt));
        let edge_edge = candidates
            .edge_edge
            .iter()
            .map(|&ef| Self::edge_edge(system, ef));
        point_triangle.chain(edge_edge)
    }

    /// The pair of vertex `v` and triangle `t` of the collision mesh.
    fn point_triangle(system: &System, (v, t): (u32, u32)) -> Pair {
        let mesh = system.surfaces();
        let (v, t) = (v as usize, t as usize);
        let [a, b, c] = mesh.triangles()[t];
        let (thickness, friction) =
            Self::between(system, mesh.vertex_group(v), mesh.triangle_group(t));
        Pair {
            particles: [mesh.vertices()[v], a, b, c],
            thickness,
            friction,
            edges: false,
        }
    }

    /// The pair of edges `e` and `f` of the collision mesh.
    fn edge_edge(system: &System, (e, f): (u32, u32)) -> Pair {
        let mesh = system.surfaces();
        let (e, f) = (e as usize, f as usize);
        let ([a0, a1], [b0, b1]) = (mesh.edges()[e], mesh.edges()[f]);
        let (thickness, friction) = Self::between(system, mesh.edge_group(e), mesh.edge_group(f));
        Pair {
            particles: [a0, a1, b0, b1],
            thickness,
            friction,
            edges: true,
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

    /// Makes the candidates cover `x`: every pair within the contact
    /// distance `d̂` (plus its thickness) there is among them. Keeps the
    /// list while `x` lies within its margin, otherwise searches anew.
    pub(crate) fn search(&mut self, system: &System, x: &[Vec3], activation: f64) {
        if !self.covers(x) {
            self.refresh(system, x, activation, self.default_margin(activation));
        }
    }

    /// The margin of a search that needs to cover no motion: [`MARGIN`]
    /// `d̂`, at most the widest.
    pub(super) fn default_margin(&self, activation: f64) -> f64 {
        (MARGIN * activation).min(self.widest)
    }

    /// Whether every particle at `y` lies within half the margin of the
    /// last proximity search's positions, moved by their common
    /// translation ([`drift`]).
    pub(super) fn covers(&self, y: &[Vec3]) -> bool {
        self.within_margin(y, drift(&self.reference, y).1)
    }

    /// Whether positions `y` whose [`drift`] from the list's positions
    /// reaches `farthest` lie within half its margin.
    pub(super) fn within_margin(&self, y: &[Vec3], farthest: f64) -> bool {
        self.reference.len() == y.len() && farthest < 0.5 * self.margin
    }

    /// A proximity search at `x` with the margin `margin` (see the type's
    /// docs), keeping the pairs within `d̂` plus their thickness plus the
    /// margin.
    pub(super) fn refresh(&mut self, system: &System, x: &[Vec3], activation: f64, margin: f64) {
        self.margin = margin;
        self.broad.proximity(
            system.surfaces(),
            x,
            activation + self.thickest + self.margin,
            &mut self.near,
        );
        self.reference.clear();
        self.reference.extend_from_slice(x);
        Self::retain(
            system,
            x,
            &mut self.near,
            &mut self.searched,
            |pair, distance| below(distance - pair.thickness, activation + margin),
        );
    }

    /// Keeps the candidates `near` for which `close(pair, D)` holds, `D`
    /// the pair's distance at `x`, and their distances in `searched`, in
    /// the order of [`Pairs::pairs`].
    fn retain(
        system: &System,
        x: &[Vec3],
        near: &mut Candidates,
        searched: &mut Vec<f64>,
        close: impl Fn(&Pair, f64) -> bool,
    ) {
        searched.clear();
        let mut within = |pair: Pair| {
            let distance = Self::distance(&pair, x);
            let keep = close(&pair, distance);
            if keep {
                searched.push(distance);
            }
            keep
        };
        near.point_triangle
            .retain(|&vt| within(Self::point_triangle(system, vt)));
        near.edge_edge
            .retain(|&ef| within(Self::edge_edge(system, ef)));
    }

    /// A swept search over the motion from `x` to [`Pairs::end`]: the
    /// pairs whose boxes, swept over the motion and grown by `d̂` and the
    /// thickness, meet, less those the motion cannot bring within `d̂` of
    /// their thickness. Their distances at `x` are kept and `x` becomes the
    /// list's positions, so that the bound on a pair's distance serves the
    /// points of the motion; with no margin, the list covers no other
    /// positions.
    ///
    /// A pair at distance `D` at `x` stays at least `D − M₁ − M₂` apart
    /// along the motion, `M₁` and `M₂` the farthest either primitive's
    /// corners move once the motion's common translation ([`drift`]) is
    /// taken off (a point of a primitive moves no farther than its farthest
    /// corner); a pair for which that leaves more than `d̂` beyond its
    /// thickness has no barrier term anywhere on the motion and cannot
    /// collide, so it is dropped. On a flat cloth the swept boxes of
    /// neighbouring primitives always meet, and without this the list
    /// kept all of them (about nine a particle).
    pub(super) fn swept(&mut self, system: &System, x: &[Vec3], activation: f64) {
        self.margin = 0.0;
        self.broad.swept(
            system.surfaces(),
            x,
            &self.end,
            activation + self.thickest,
            &mut self.near,
        );
        self.reference.clear();
        self.reference.extend_from_slice(x);
        let shift = drift(x, &self.end).0;
        self.moved.clear();
        self.moved.extend(x.iter().zip(&self.end).map(|(x, e)| {
            let moved = (e - x - shift).norm();
            (moved, moved)
        }));
        let moved = &self.moved;
        Self::retain(
            system,
            x,
            &mut self.near,
            &mut self.searched,
            |pair, distance| {
                let (first, second) = pair.largest(|p| moved[p].0);
                below(distance - first - second - pair.thickness, activation)
            },
        );
    }

    /// The candidates that may lie within `activation` beyond their
    /// thickness at `x`: those the bound of [`Pairs::far`] does not rule
    /// out.
    pub(super) fn reachable<'a>(
        &'a self,
        system: &'a System,
        x: &'a [Vec3],
        activation: f64,
    ) -> impl Iterator<Item = Pair> + 'a {
        let shift = drift(&self.reference, x).0;
        Self::pairs(system, &self.near)
            .enumerate()
            .filter(move |(k, pair)| !self.far(*k, pair, x, shift, activation))
            .map(|(_, pair)| pair)
    }

    /// Whether the candidate numbered `index`, `pair`, is certainly
    /// farther than `activation` beyond its thickness at `x`: its distance
    /// at the search's positions less how far the corners of each of its
    /// two primitives have moved since, once every particle is moved back
    /// by the translation `shift` (the type's docs).
    pub(super) fn far(
        &self,
        index: usize,
        pair: &Pair,
        x: &[Vec3],
        shift: Vec3,
        activation: f64,
    ) -> bool {
        let reference = &self.reference;
        let (first, second) = pair.largest(|p| (x[p] - reference[p] - shift).norm_squared());
        let searched = self.searched[index];
        searched - first.sqrt() - second.sqrt() - pair.thickness >= activation
    }

    /// The squared distance of a pair at `x`, without derivatives.
    pub(super) fn squared(pair: &Pair, x: &[Vec3]) -> f64 {
        let [p0, p1, p2, p3] = pair.positions(x);
        if pair.edges {
            edge_edge_squared_distance(p0, p1, p2, p3)
        } else {
            point_triangle_squared_distance(p0, p1, p2, p3)
        }
    }

    /// The distance of a pair at `x`, without derivatives.
    fn distance(pair: &Pair, x: &[Vec3]) -> f64 {
        Self::squared(pair, x).max(0.0).sqrt()
    }

    /// The gap of a pair whose squared distance is `squared`.
    pub(super) fn gap(pair: &Pair, squared: f64) -> f64 {
        squared.max(0.0).sqrt() - pair.thickness
    }

    /// The edge–edge mollifier threshold of a pair, from its rest positions.
    fn threshold(system: &System, pair: &Pair) -> f64 {
        let rest = system.initial_positions();
        let [r0, r1, r2, r3] = pair.particles.map(|p| rest[p]);
        mollifier_threshold(r0, r1, r2, r3)
    }

    /// The barrier term's value of a pair at `x` (`m b(g)` for two edges,
    /// `b(g)` otherwise): zero beyond the contact distance, infinite if the
    /// gap is not positive. The line search's cheap path: no derivatives.
    fn value(system: &System, pair: &Pair, x: &[Vec3], activation: f64) -> f64 {
        let gap = Self::gap(pair, Self::squared(pair, x));
        if gap >= activation {
            return 0.0;
        }
        if gap <= 0.0 {
            return f64::INFINITY;
        }
        let b = barrier(gap, activation).0;
        if pair.edges {
            let [p0, p1, p2, p3] = pair.positions(x);
            b * edge_edge_mollifier(p0, p1, p2, p3, Self::threshold(system, pair)).value
        } else {
            b
        }
    }

    /// The barrier term of a pair at `x`, with its derivatives in the
    /// pair's 12 coordinates; `None` beyond the contact distance.
    fn term(system: &System, pair: &Pair, x: &[Vec3], activation: f64) -> Option<Derivatives> {
        if Self::gap(pair, Self::squared(pair, x)) >= activation {
            return None;
        }
        let [p0, p1, p2, p3] = pair.positions(x);
        if pair.edges {
            let threshold = Self::threshold(system, pair);
            let squared = edge_edge_squared(p0, p1, p2, p3);
            let mollifier = edge_edge_mollifier(p0, p1, p2, p3, threshold);
            mollified_pair_barrier(&squared, &mollifier, pair.thickness, activation)
        } else {
            let squared = point_triangle_squared(p0, p1, p2, p3);
            pair_barrier(&squared, pair.thickness, activation)
        }
    }

    /// `Σ b` over the candidates of the last search at `x`, which must be
    /// the configuration it searched or a point of the motion it checked
    /// (`κ` not applied);
    /// infinite if a gap is not positive.
    pub(crate) fn energy(&self, system: &System, x: &[Vec3], activation: f64) -> f64 {
        self.reachable(system, x, activation)
            .map(|pair| Self::value(system, &pair, x, activation))
            .sum()
    }

    /// Adds `κ Σ b` over the candidates of the last search (as in
    /// [`Pairs::energy`]) at `x` to a Newton system in the velocities
    /// (`x = x̃ + βh v`): `b −= βh κ ∇b`, `A += β²h² κ ∇²b`; returns the
    /// number of pairs within the contact distance.
    pub(crate) fn add(
        &self,
        system: &System,
        x: &[Vec3],
        (kappa, beta_h, activation): (f64, f64, f64),
        b: &mut [Vec3],
        a: &mut impl HessianBlocks,
    ) -> usize {
        let (kb, kbb) = (kappa * beta_h, kappa * beta_h * beta_h);
        let mut count = 0;
        for pair in self.reachable(system, x, activation) {
            let Some(term) = Self::term(system, &pair, x, activation) else {
                continue;
            };
            count += 1;
            for (k, &p) in pair.particles.iter().enumerate() {
                let g = term.gradient.fixed_rows::<3>(3 * k).into_owned();
                b[p] -= kb * g;
                let block: Mat3 = term.hessian.fixed_view::<3, 3>(3 * k, 3 * k).into_owned();
                a.add_row(p, SymBlock::symmetric_part(&(kbb * block)));
                for (l, &q) in pair.particles.iter().enumerate().skip(k + 1) {
                    let block: Mat3 = term.hessian.fixed_view::<3, 3>(3 * k, 3 * l).into_owned();
                    a.add_pair(p, q, kbb * block);
                }
            }
        }
        count
    }

    /// The lagged friction of the pairs of the last search within the
    /// contact distance at `x` (the step's start), with barrier stiffness
    /// `kappa`, into `out`: the normal force `λ = κ m |b'(g)|` (`m` the
    /// edge–edge mollifier, 1 otherwise) along the line between the closest
    /// points, whose weights make the relative velocity.
    pub(crate) fn lag_friction(
        &self,
        system: &System,
        x: &[Vec3],
        (kappa, activation): (f64, f64),
        out: &mut Vec<Lagged>,
    ) {
        for pair in self.reachable(system, x, activation) {
            if pair.friction <= 0.0 {
                continue;
            }
            let [p0, p1, p2, p3] = pair.positions(x);
            let (closest, mollifier) = if pair.edges {
                let threshold = Self::threshold(system, &pair);
                (
                    edge_edge_closest(p0, p1, p2, p3),
                    edge_edge_mollifier(p0, p1, p2, p3, threshold).value,
                )
            } else {
                (point_triangle_closest(p0, p1, p2, p3), 1.0)
            };
            let distance = closest.squared.sqrt();
            let gap = distance - pair.thickness;
            if gap <= 0.0 || gap >= activation || distance == 0.0 {
                continue;
            }
            let between: Vec3 = (0..4)
                .map(|k| closest.weights[k] * x[pair.particles[k]])
                .sum();
            let force = kappa * mollifier * barrier(gap, activation).1.abs();
            out.push(Lagged::new(
                &pair.particles,
                &closest.weights,
                between / distance,
                Vec3::zeros(),
                pair.friction * force,
            ));
        }
    }
}

/// Whether a pair's lower bound on its gap, `bound`, is below `reach`: the
/// pair may come within it, and stays listed. A bound that is not a number
/// (a position that is not one) keeps the pair too.
fn below(bound: f64, reach: f64) -> bool {
    bound.is_nan() || bound < reach
}

/// The common translation `t` of the particles from `reference` to `y`
/// that [`Pairs`] takes off their moves — the centre of the box of their
/// displacements — and the farthest any particle then is from its
/// reference position, `max |yᵢ − rᵢ − t|` (not a number if a position is
/// not).
pub(super) fn drift(reference: &[Vec3], y: &[Vec3]) -> (Vec3, f64) {
    let (mut lo, mut hi) = (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY));
    for (r, y) in reference.iter().zip(y) {
        let d = y - r;
        lo = lo.inf(&d);
        hi = hi.sup(&d);
    }
    if reference.is_empty() {
        return (Vec3::zeros(), 0.0);
    }
    let shift = 0.5 * (lo + hi);
    let farthest = reference
        .iter()
        .zip(y)
        .map(|(r, y)| (y - r - shift).norm_squared())
        .fold(0.0, |m: f64, d| if d > m || d.is_nan() { d } else { m });
    (shift, farthest.sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;
    use hooke_core::SystemBuilder;

    /// Adds to `b` an `n × n` sheet of particles of 1 g, `spacing` apart
    /// along x and z from `corner`, as a surface of two triangles a cell.
    fn sheet(b: &mut SystemBuilder, n: usize, spacing: f64, corner: Vec3) {
        let indices: Vec<usize> = (0..n * n)
            .map(|k| {
                let (i, j) = ((k / n) as f64, (k % n) as f64);
                b.particle(1e-3, corner + spacing * Vec3::new(i, 0.0, j))
            })
            .collect();
        let at = |i: usize, j: usize| indices[i * n + j];
        let mut triangles = Vec::new();
        for i in 0..n - 1 {
            for j in 0..n - 1 {
                triangles.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                triangles.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        b.surface(&triangles);
    }

    /// Two 6 × 6 sheets, 20 cm wide, 2 mm apart, with a contact distance of
    /// 1 mm (the widest margin of a search 11 mm, a quarter of their mean
    /// edge).
    fn sheets() -> System {
        let mut b = SystemBuilder::new();
        for height in [0.0, 2e-3] {
            sheet(&mut b, 6, 0.04, Vec3::new(0.3 * height, height, 0.0));
        }
        b.contact_distance(1e-3);
        b.build().unwrap()
    }

    /// The pairs of `candidates` closer than `reach` at `x`.
    fn within(system: &System, candidates: &Candidates, x: &[Vec3], reach: f64) -> Vec<[usize; 4]> {
        let mut close: Vec<[usize; 4]> = Pairs::pairs(system, candidates)
            .filter(|p| Pairs::gap(p, Pairs::squared(p, x)) < reach)
            .map(|p| p.particles)
            .collect();
        close.sort_unstable();
        close
    }

    /// Asserts that every pair within `d̂` at any of `points + 1` evenly
    /// spaced points of the motion from `x0` by `dx` is among `pairs`'
    /// candidates; returns how many such pairs and points there are.
    fn every_close_pair_listed(
        system: &System,
        pairs: &Pairs,
        x0: &[Vec3],
        dx: &[Vec3],
        points: u32,
    ) -> usize {
        let d_hat = system.contact_distance();
        let mut everything = Candidates::default();
        BroadPhase::default().proximity(system.surfaces(), x0, 1.0, &mut everything);
        let listed = |particles: [usize; 4]| {
            Pairs::pairs(system, &pairs.near).any(|p| p.particles == particles)
        };
        let mut close = 0;
        for step in 0..=points {
            let t = f64::from(step) / f64::from(points);
            let x: Vec<Vec3> = x0.iter().zip(dx).map(|(x, d)| x + t * d).collect();
            for pair in within(system, &everything, &x, d_hat) {
                close += 1;
                assert!(listed(pair), "{pair:?} at τ = {t}");
            }
        }
        close
    }

    /// The sheets, their contact distance and rest positions, and their
    /// pairs searched there.
    fn searched_sheets() -> (System, f64, Vec<Vec3>, Pairs) {
        let system = sheets();
        let d_hat = system.contact_distance();
        let x0 = system.initial_positions().to_vec();
        let mut pairs = Pairs::default();
        pairs.begin(&system);
        pairs.search(&system, &x0, d_hat);
        (system, d_hat, x0, pairs)
    }

    /// Pseudo-random numbers in `[−½, ½)` from `seed`.
    fn uniform(seed: u64) -> impl FnMut() -> f64 {
        let mut seed = seed;
        move || {
            seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            (seed >> 11) as f64 / (1_u64 << 53) as f64 - 0.5
        }
    }

    #[test]
    fn the_verlet_list_holds_every_close_pair_until_a_particle_leaves_its_ball() {
        let (system, d_hat, x0, mut pairs) = searched_sheets();
        // Every particle moved by up to 0.9 of half the margin, in a
        // pseudo-random direction, and then all of them carried 10 cm (25
        // times the margin) as a whole: the list is kept, and still holds
        // every pair a fresh search finds within d̂.
        let mut unit = uniform(7);
        let reach = 0.5 * MARGIN * d_hat;
        let carried = Vec3::new(0.06, -0.08, 0.0);
        let x1: Vec<Vec3> = x0
            .iter()
            .map(|x| {
                let d = Vec3::new(unit(), unit(), unit()).normalize();
                x + 0.9 * reach * d + carried
            })
            .collect();
        pairs.search(&system, &x1, d_hat);
        assert_eq!(pairs.reference, x0, "the list was renewed");
        let mut fresh = Candidates::default();
        BroadPhase::default().proximity(system.surfaces(), &x1, d_hat, &mut fresh);
        let needed = within(&system, &fresh, &x1, d_hat);
        assert!(!needed.is_empty());
        let kept = within(&system, &pairs.near, &x1, d_hat);
        assert_eq!(kept, needed);
        // One particle beyond its ball, whatever translation is taken off
        // (the others are within 0.9 of it, this one 2.5 times it away):
        // the list is renewed at the new positions.
        let mut x2 = x1.clone();
        x2[0] += Vec3::new(0.0, 2.5 * reach, 0.0) + (x0[0] + carried - x1[0]);
        pairs.search(&system, &x2, d_hat);
        assert_eq!(pairs.reference, x2);
    }

    #[test]
    fn the_drift_takes_off_a_common_translation_and_keeps_a_position_that_is_not_a_number() {
        let mut unit = uniform(3);
        let reference: Vec<Vec3> = (0..50).map(|_| Vec3::new(unit(), unit(), unit())).collect();
        let carried = Vec3::new(0.7, -1.3, 2.1);
        let moved: Vec<Vec3> = reference.iter().map(|r| r + carried).collect();
        let (shift, farthest) = drift(&reference, &moved);
        assert!((shift - carried).norm() < 1e-15 && farthest < 1e-15);
        // Two particles moved apart by ±d along x: the centre of the box is
        // the common translation, and each is d from its place.
        let mut apart = moved.clone();
        apart[3].x += 0.25;
        apart[9].x -= 0.25;
        let (shift, farthest) = drift(&reference, &apart);
        assert!((shift - carried).norm() < 1e-15 && (farthest - 0.25).abs() < 1e-15);
        apart[20].y = f64::NAN;
        assert!(drift(&reference, &apart).1.is_nan());
    }

    #[test]
    fn a_fine_flat_sheet_lists_no_pair_of_its_own() {
        // A 20 × 20 sheet, 1 cm spacing, its contact distance a quarter of
        // its mean edge (the default's bound on a fine mesh): the margin
        // stays at d̂, and the sheet, flat, lists none of its pairs, where
        // a margin of 4 d̂ (a whole edge) would list thousands.
        let mut b = SystemBuilder::new();
        let n = 20;
        sheet(&mut b, n, 0.01, Vec3::zeros());
        // The mean of its 2n(n − 1) edges of 1 cm and (n − 1)² diagonals.
        let (sides, diagonals) = ((2 * n * (n - 1)) as f64, ((n - 1) * (n - 1)) as f64);
        let edge = 0.01 * (sides + 2.0_f64.sqrt() * diagonals) / (sides + diagonals);
        b.contact_distance(0.25 * edge);
        let system = b.build().unwrap();
        let d_hat = system.contact_distance();
        let x0 = system.initial_positions().to_vec();
        let mut pairs = Pairs::default();
        pairs.begin(&system);
        pairs.search(&system, &x0, d_hat);
        assert!(
            (pairs.margin - d_hat).abs() < 1e-9 * d_hat,
            "margin {} m, d̂ {d_hat} m",
            pairs.margin
        );
        assert!(
            pairs.near.point_triangle.is_empty() && pairs.near.edge_edge.is_empty(),
            "{} + {} pairs listed",
            pairs.near.point_triangle.len(),
            pairs.near.edge_edge.len()
        );
        let mut wide = Candidates::default();
        BroadPhase::default().proximity(system.surfaces(), &x0, (1.0 + MARGIN) * d_hat, &mut wide);
        assert!(within(&system, &wide, &x0, (1.0 + MARGIN) * d_hat).len() > 1000);
    }

    #[test]
    fn a_candidate_the_bound_calls_far_is_beyond_the_contact_distance() {
        let (system, d_hat, x0, mut pairs) = searched_sheets();
        let mut unit = uniform(11);
        // Moves of up to a tenth of the margin's half and up to 0.9 of it,
        // each particle in its own direction and by its own fraction, and
        // all of them carried 5 cm as a whole.
        let carried = Vec3::new(0.0, 0.03, -0.04);
        for size in [0.1, 0.9] {
            let moved = size * 0.5 * MARGIN * d_hat;
            let x: Vec<Vec3> = x0
                .iter()
                .map(|x| {
                    let d = Vec3::new(unit(), unit(), unit()).normalize();
                    x + moved * (unit() + 0.5) * d + carried
                })
                .collect();
            pairs.search(&system, &x, d_hat);
            assert_eq!(pairs.reference, x0);
            let shift = drift(&x0, &x).0;
            let (mut far, mut near) = (0, 0);
            for (k, pair) in Pairs::pairs(&system, &pairs.near).enumerate() {
                let gap = Pairs::gap(&pair, Pairs::squared(&pair, &x));
                if pairs.far(k, &pair, &x, shift, d_hat) {
                    far += 1;
                    assert!(gap >= d_hat, "pair {:?}: gap {gap}", pair.particles);
                } else if gap < d_hat {
                    near += 1;
                }
            }
            // The sheets are 2 mm apart: small moves leave every candidate
            // far, and the largest bring some within d̂ = 1 mm.
            if size < 0.5 {
                assert!(
                    far > 0 && near == 0,
                    "moves of {moved} m: {far} far, {near} near"
                );
            } else {
                assert!(near > 0, "moves of {moved} m: no pair within d̂");
            }
            let all: f64 = Pairs::pairs(&system, &pairs.near)
                .map(|pair| Pairs::value(&system, &pair, &x, d_hat))
                .sum();
            let filtered = pairs.energy(&system, &x, d_hat);
            assert!(
                (filtered - all).abs() <= f64::EPSILON * all,
                "{filtered} J, {all} J"
            );
        }
    }

    #[test]
    fn the_line_search_limit_skips_only_pairs_that_ccd_clears_and_covers_the_motion() {
        let (system, d_hat, x0, mut pairs) = searched_sheets();
        let keep = 0.1;
        let mut unit = uniform(5);
        // Motions within the Verlet list's margin (alone, and with the
        // sheets carried 40 d̂ as a whole), beyond it (a new list whose
        // margin covers the motion) and far beyond it (a swept search),
        // each particle in its own direction.
        let cases = [
            (1.8, 0.0, Some(true)),
            (1.8, 40.0, Some(true)),
            (3.0, 0.0, Some(false)),
            (12.0, 0.0, None),
        ];
        for (size, carried, kept) in cases {
            let carried = carried * d_hat * Vec3::new(0.6, -0.8, 0.0);
            let dx: Vec<Vec3> = x0
                .iter()
                .map(|_| {
                    let d = Vec3::new(unit(), unit(), unit()).normalize();
                    size * d_hat * (unit() + 0.5) * d + carried
                })
                .collect();
            let tau = pairs.limit(&system, &x0, &dx, (keep, d_hat));
            match kept {
                Some(true) => assert_eq!(pairs.reference, x0),
                Some(false) => {
                    assert!(pairs.margin > 2.0 * size * d_hat, "margin {}", pairs.margin);
                    let end: Vec<Vec3> = x0.iter().zip(&dx).map(|(x, d)| x + d).collect();
                    assert!(pairs.covers(&x0) && pairs.covers(&end));
                }
                None => assert!(
                    pairs.margin == 0.0 && !pairs.covers(&x0),
                    "motions of {size} d̂"
                ),
            }
            // The bound skipped no pair whose CCD stops the motion.
            let unpruned = Pairs::pairs(&system, &pairs.near)
                .map(|pair| pair.ccd(&x0, &dx, keep))
                .fold(1.0, f64::min);
            assert_eq!(
                tau.to_bits(),
                unpruned.to_bits(),
                "motions of {size} d̂: {tau} against {unpruned}"
            );
            // Every pair within d̂ anywhere along the motion is a candidate.
            let close = every_close_pair_listed(&system, &pairs, &x0, &dx, 10);
            assert!(close > 0, "motions of {size} d̂ bring no pair within d̂");
        }
    }

    /// One particle of the lower sheet thrown up through the upper one (a
    /// motion too long for any Verlet list: a swept search), the others
    /// moved 0.2 d̂ each: the swept boxes of the sheets' neighbouring
    /// primitives meet, but only the pairs the motion can bring within d̂
    /// are listed, and every pair that comes within d̂ anywhere along the
    /// motion is among them.
    #[test]
    fn a_swept_search_lists_only_the_pairs_the_motion_can_bring_within_reach() {
        let (system, d_hat, x0, mut pairs) = searched_sheets();
        let mut unit = uniform(13);
        let mut dx: Vec<Vec3> = x0
            .iter()
            .map(|_| 0.2 * d_hat * Vec3::new(unit(), unit(), unit()))
            .collect();
        dx[14] = Vec3::new(0.0, 20.0 * d_hat, 0.0);
        let tau = pairs.limit(&system, &x0, &dx, (0.1, d_hat));
        assert!(
            pairs.margin == 0.0 && tau < 0.2,
            "margin {}, τ {tau}",
            pairs.margin
        );
        let end: Vec<Vec3> = x0.iter().zip(&dx).map(|(x, d)| x + d).collect();
        let mut boxes = Candidates::default();
        let reach = d_hat + pairs.thickest;
        BroadPhase::default().swept(system.surfaces(), &x0, &end, reach, &mut boxes);
        let count = |c: &Candidates| c.point_triangle.len() + c.edge_edge.len();
        let (listed, found) = (count(&pairs.near), count(&boxes));
        assert!(
            listed > 0 && 4 * listed < found,
            "{listed} listed of {found} found"
        );
        let close = every_close_pair_listed(&system, &pairs, &x0, &dx, 20);
        assert!(close > 0, "the motion brings no pair within d̂");
    }

    /// The whole contact limit checks the pairs along the part of a motion
    /// the obstacles allow: the two sheets 3 mm above a floor, moved down
    /// by 2 to 8 mm with each particle in its own direction besides, stop
    /// no later than the floor stops them and no earlier than checking
    /// their pairs along the whole motion would (CCD's bound, conservative,
    /// tightens on the shorter motion), and along the motion to that point
    /// every pair of the two surfaces keeps more than a tenth of its gap.
    #[test]
    fn the_contact_limit_checks_pairs_along_what_the_obstacles_allow() {
        use hooke_core::{Obstacle, Shape};

        use crate::minimize::contact::{Contact, KEEP};

        let mut b = SystemBuilder::new();
        for height in [0.0, 2e-3] {
            sheet(&mut b, 6, 0.04, Vec3::new(0.3 * height, height, 0.0));
        }
        b.contact_distance(1e-3);
        b.obstacle(Obstacle::new(Shape::Plane {
            point: Vec3::new(0.0, -3e-3, 0.0),
            normal: Vec3::y(),
        }));
        let system = b.build().unwrap();
        let d_hat = system.contact_distance();
        let x0 = system.initial_positions().to_vec();
        let mut everything = Candidates::default();
        BroadPhase::default().proximity(system.surfaces(), &x0, 1.0, &mut everything);
        let mut contact = Contact::default();
        contact.begin(&system, &x0, 0.0, 1e-2);
        let mut unit = uniform(11);
        let (mut floor_first, mut pairs_first) = (0, 0);
        for case in 0..24 {
            let drop = 2e-3 + 6e-3 * f64::from(case) / 24.0;
            let dx: Vec<Vec3> = x0
                .iter()
                .map(|_| {
                    let d = Vec3::new(unit(), unit(), unit());
                    4.0 * d_hat * d - drop * Vec3::y()
                })
                .collect();
            let floor = (0..x0.len())
                .map(|i| contact.obstacles.limit(i, x0[i], dx[i], KEEP))
                .fold(1.0, f64::min);
            let mut whole = Pairs::default();
            whole.begin(&system);
            whole.search(&system, &x0, d_hat);
            let surfaces = whole.limit(&system, &x0, &dx, (KEEP, d_hat));
            let tau = contact.limit(&system, &x0, &dx);
            assert!(
                tau <= floor && tau >= floor.min(surfaces) * (1.0 - 1e-12),
                "drop {drop}: {tau} against floor {floor}, surfaces {surfaces}"
            );
            for pair in Pairs::pairs(&system, &everything) {
                let start = Pairs::gap(&pair, Pairs::squared(&pair, &x0));
                for step in 1..=10 {
                    let t = tau * f64::from(step) / 10.0;
                    let x: Vec<Vec3> = x0.iter().zip(&dx).map(|(x, d)| x + t * d).collect();
                    let gap = Pairs::gap(&pair, Pairs::squared(&pair, &x));
                    assert!(
                        gap > KEEP * start,
                        "drop {drop}: {:?} at {t}",
                        pair.particles
                    );
                }
            }
            if floor < surfaces {
                floor_first += 1;
            } else if surfaces < 1.0 {
                pairs_first += 1;
            }
        }
        assert!(
            floor_first > 0 && pairs_first > 0,
            "{floor_first}, {pairs_first}"
        );
    }
}
