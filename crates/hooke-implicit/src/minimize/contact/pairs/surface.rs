//! The surface part of the pair list: the point–triangle and edge–edge
//! pairs of the system's collision surfaces, within a body
//! (self-collision) and between bodies, found by the broad phase.

use hooke_core::collision::broad::{BroadPhase, Candidates};
use hooke_core::{System, Vec3};

use super::verlet::{MARGIN, Verlet, below, drift, motion_margin};
use crate::linear::vector::for_each_row;
use crate::minimize::contact::pair::{Geometry, Pair};

/// The widest margin of a search, in units of the surfaces' mean edge
/// length at rest. A fine mesh's contact distance is a quarter of that
/// edge (by default, at most), so its margin stays at `d̂` and the reach
/// `d̂ + s` within half an edge: the closest pairs of a flat triangulated
/// grid that share no particle — a vertex and the diagonal across from it,
/// 0.71 of a spacing or 0.62 of the mean edge apart — stay out of the
/// list, which on a million-particle cloth would otherwise hold tens of
/// pairs a particle.
const WIDEST: f64 = 0.25;

/// The widest margin, in units of the contact distance, of a proximity
/// search that [`SurfacePart::limit`] makes for a motion; a longer motion
/// gets a swept search.
const MAX_MARGIN: f64 = 16.0;

/// Candidates a block whose distances [`SurfacePart::retain`] computes
/// together (a 512 KiB scratch).
const RETAIN_BLOCK: usize = 1 << 16;

/// The pairs of a system's surfaces, with the broad phase's buffers.
///
/// A proximity search at `x_s` with reach `d̂ + ξ + s` (`ξ` the largest
/// thickness, `s` the margin) finds every pair closer than that; the list
/// keeps those whose distance, less their own thickness, is below `d̂ + s`.
/// A pair left out stays farther than `d̂` plus its thickness apart as long
/// as every particle keeps within `s/2` of `x_s` moved by one common
/// translation `t` — distances do not change when every particle is moved
/// by `t` ([`Verlet`]'s rule with the translation taken off). The list
/// then serves the iterations of a step, and the steps after it, until a
/// particle leaves its ball: a cloth falling or carried as a whole keeps
/// its list. The translation taken is the centre of the box of the
/// particles' displacements from `x_s` ([`drift`]).
///
/// Each candidate's distance `D` at `x_s` is kept with the list. A point
/// of a segment or triangle moves no farther than its farthest corner, so
/// at positions `x` the pair is at least `D − δ₁ − δ₂` apart, `δ₁` and `δ₂`
/// the farthest either primitive's corners have moved from `x_s` (the
/// common translation taken off); a pair for which that exceeds `d̂` plus
/// its thickness has no barrier term and no friction, and its exact
/// distance is not computed.
#[derive(Debug, Default)]
pub(super) struct SurfacePart {
    broad: BroadPhase,
    /// The candidates of the last search: the pairs within reach of its
    /// positions (with the margin, by their distance there), or whose
    /// boxes meet anywhere along a checked motion.
    pub(super) near: Candidates,
    /// The positions and margin of the last search.
    pub(super) verlet: Verlet,
    /// Each candidate's distance at the search's positions, in the order
    /// of [`SurfacePart::pairs`].
    pub(super) searched: Vec<f64>,
    /// The largest thickness of a pair.
    pub(super) thickest: f64,
    /// The widest margin of a search ([`WIDEST`] mean edges).
    widest: f64,
    /// Scratch for each particle's distance from the search's positions at
    /// the start of a motion, and the farthest it gets along the motion.
    moved: Vec<(f64, f64)>,
    /// Scratch for the candidates' distances in a search.
    distances: Vec<f64>,
    /// The searches (proximity or swept) since the count was last taken.
    pub(super) queries: usize,
}

impl SurfacePart {
    /// Sets up the pairs of `system`: the largest thickness, and the widest
    /// margin from the surfaces' edges at rest.
    pub(super) fn begin(&mut self, system: &System) {
        self.thickest = (0..system.surface_count())
            .map(|g| system.surface_thickness(g))
            .fold(0.0, f64::max);
        let rest = system.initial_positions();
        let edges = system.surfaces().edges();
        let total: f64 = edges.iter().map(|&[a, b]| (rest[a] - rest[b]).norm()).sum();
        self.widest = WIDEST * total / edges.len().max(1) as f64;
    }

    /// The pairs among `candidates`: the point–triangle pairs, then the
    /// edge–edge pairs.
    pub(super) fn pairs<'a>(
        system: &'a System,
        candidates: &'a Candidates,
    ) -> impl Iterator<Item = Pair> + 'a {
        let point_triangle = candidates
            .point_triangle
            .iter()
            .map(|&vt| Pair::point_triangle(system, vt));
        let edge_edge = candidates
            .edge_edge
            .iter()
            .map(|&ef| Pair::edge_edge(system, ef));
        point_triangle.chain(edge_edge)
    }

    /// Makes the candidates cover `x`: every pair within the contact
    /// distance `d̂` (plus its thickness) there is among them. Keeps the
    /// list while `x` lies within its margin, otherwise searches anew.
    pub(super) fn search(&mut self, system: &System, x: &[Vec3], activation: f64) {
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
        self.verlet.within(y, drift(&self.verlet.reference, y).1)
    }

    /// A proximity search at `x` with the margin `margin`, keeping the
    /// pairs within `d̂` plus their thickness plus the margin.
    fn refresh(&mut self, system: &System, x: &[Vec3], activation: f64, margin: f64) {
        self.queries += 1;
        self.verlet.searched(x, margin);
        self.broad.proximity(
            system.surfaces(),
            x,
            activation + self.thickest + margin,
            &mut self.near,
        );
        Self::retain(
            system,
            x,
            (&mut self.near, &mut self.searched, &mut self.distances),
            |pair, distance| below(distance - pair.thickness, activation + margin),
        );
    }

    /// Keeps the candidates `near` for which `close(pair, D)` holds, `D`
    /// the pair's distance at `x`, and their distances in `searched`, in
    /// the order of [`SurfacePart::pairs`]. The distances, most of the
    /// narrow phase's time, are computed a block of [`RETAIN_BLOCK`]
    /// candidates at a time into `scratch` (a dropped candidate marked
    /// there by a negative distance), on every core ([`for_each_row`]),
    /// and each block's kept candidates moved down in order.
    fn retain(
        system: &System,
        x: &[Vec3],
        (near, searched, scratch): (&mut Candidates, &mut Vec<f64>, &mut Vec<f64>),
        close: impl Fn(&Pair, f64) -> bool + Sync,
    ) {
        searched.clear();
        let within = |pair: Pair| {
            let distance = pair.distance(x);
            if close(&pair, distance) {
                distance
            } else {
                -1.0
            }
        };
        let point_triangle = |vt| Pair::point_triangle(system, vt);
        Self::retain_list(
            &mut near.point_triangle,
            point_triangle,
            &within,
            (searched, scratch),
        );
        let edge_edge = |ef| Pair::edge_edge(system, ef);
        Self::retain_list(&mut near.edge_edge, edge_edge, &within, (searched, scratch));
    }

    /// [`SurfacePart::retain`] over one list of candidates, each made a
    /// pair by `pair`; `within` gives a pair's distance, or −1 to drop it.
    fn retain_list(
        list: &mut Vec<(u32, u32)>,
        pair: impl Fn((u32, u32)) -> Pair + Sync,
        within: &(impl Fn(Pair) -> f64 + Sync),
        (searched, scratch): (&mut Vec<f64>, &mut Vec<f64>),
    ) {
        let mut kept = 0;
        for start in (0..list.len()).step_by(RETAIN_BLOCK) {
            let block = start..list.len().min(start + RETAIN_BLOCK);
            scratch.resize(block.len(), 0.0);
            let candidates = &list[block.clone()];
            for_each_row(scratch, |k, slot| *slot = within(pair(candidates[k])));
            for (k, &distance) in block.zip(scratch.iter()) {
                // A distance that is not a number (a position that is not
                // one) was kept by `close` and stays.
                if distance >= 0.0 || distance.is_nan() {
                    list[kept] = list[k];
                    searched.push(distance);
                    kept += 1;
                }
            }
        }
        list.truncate(kept);
    }

    /// A swept search over the motion from `x` to `end`:
    /// the pairs whose boxes, swept over the motion and grown by `d̂` and
    /// the thickness, meet, less those the motion cannot bring within `d̂`
    /// of their thickness. Their distances at `x` are kept and `x` becomes
    /// the list's positions; with no margin, the list covers no other
    /// positions.
    ///
    /// A pair at distance `D` at `x` stays at least `D − M₁ − M₂` apart
    /// along the motion, `M₁` and `M₂` the farthest either primitive's
    /// corners move relative to the pair's first particle (distances do
    /// not change when the pair is moved back by one translation, and a
    /// point of a segment or triangle moves no farther than its farthest
    /// corner); a pair for which that leaves more than `d̂` beyond its
    /// thickness has no barrier term anywhere on the motion and cannot
    /// collide, so it is dropped. On a flat cloth the swept boxes of
    /// neighbouring primitives always meet, and without this the list
    /// kept all of them (about nine a particle). The primitives of a
    /// close pair move nearly together, while one translation for the
    /// whole motion ([`drift`]) leaves a turning or bending sheet's far
    /// parts moving by more than a pair's distance: on the 400 × 400 cloth
    /// of the `million_cloth` example a bound by that translation keeps
    /// 1.27–1.42 million of a swept search's 1.43 million candidates,
    /// this one none.
    fn swept(&mut self, system: &System, (x, end): (&[Vec3], &[Vec3]), activation: f64) {
        self.queries += 1;
        self.verlet.searched(x, 0.0);
        self.broad.swept(
            system.surfaces(),
            x,
            end,
            activation + self.thickest,
            &mut self.near,
        );
        Self::retain(
            system,
            x,
            (&mut self.near, &mut self.searched, &mut self.distances),
            |pair, distance| {
                let (first, second) = Self::relative(pair, x, end);
                below(distance - first - second - pair.thickness, activation)
            },
        );
    }

    /// The candidates that may lie within `activation` beyond their
    /// thickness at `x`: those whose distance at the search's positions,
    /// less how far the corners of each of their two primitives have moved
    /// since (every particle moved back by the common translation), does
    /// not put them beyond it (the type's docs).
    pub(super) fn reachable<'a>(
        &'a self,
        system: &'a System,
        x: &'a [Vec3],
        activation: f64,
    ) -> impl Iterator<Item = Pair> + 'a {
        let reference = &self.verlet.reference;
        let shift = drift(reference, x).0;
        Self::pairs(system, &self.near)
            .zip(&self.searched)
            .filter(move |(pair, searched)| {
                let moved = |p: usize| (x[p] - reference[p] - shift).norm_squared();
                let (first, second) = pair.largest(moved);
                below(
                    *searched - first.sqrt() - second.sqrt() - pair.thickness,
                    activation,
                )
            })
            .map(|(pair, _)| pair)
    }

    /// The farthest the corners of each of `pair`'s two primitives move
    /// from `x` to `y` relative to the pair's first particle: the pair's
    /// distance changes by no more than their sum, as a translation of
    /// the whole pair leaves it unchanged.
    fn relative(pair: &Pair, x: &[Vec3], y: &[Vec3]) -> (f64, f64) {
        let q = pair.particles[0];
        let common = y[q] - x[q];
        pair.largest(|p| (y[p] - x[p] - common).norm())
    }

    /// The largest `τ ∈ [0, 1]` such that the motion from `x` to `x + τ dx`
    /// (`end = x + dx`) keeps every pair at least `keep` of its gap
    /// (additive CCD), over
    /// candidates that then hold every pair within reach at any point of
    /// the motion, and serve the points of the motion:
    ///
    /// - the Verlet list, while both ends of the motion lie within its
    ///   margin (each moved by its particles' common translation);
    /// - otherwise, if the widest margin a search may take — [`MAX_MARGIN`]
    ///   `d̂` or the widest margin of a search, whichever is less — covers
    ///   the motion (its common translation taken off) with
    ///   [`motion_margin`]'s slack, a new proximity search at `x` with that
    ///   margin. The iterations after it, whose motions the line search and
    ///   the obstacles keep short, then keep its list as long as they can;
    ///   on a flat cloth the wider reach lists no more pairs (it stays below
    ///   the grid's closest pair), and on the default scene the main job
    ///   ran in 0.95 of the time of a margin of the slack times the motion
    ///   (farm-bench, 4 pairs; cloth-pile and two-cloths 1.00);
    /// - otherwise (a long motion) the pairs whose boxes, swept over the
    ///   motion and inflated by the contact distance `d̂` and the
    ///   thickness, overlap and which the motion can bring within `d̂`
    ///   ([`SurfacePart::swept`]), with their distances at `x`.
    ///
    /// A pair whose distance `D` at the list's positions (`x` after a
    /// swept search) bounds its gap along the whole motion from below by
    /// more than `keep` times the bound of its gap at `x` from above is
    /// skipped without CCD: along a straight motion a particle is farthest
    /// from its place in the list at one of the motion's ends (distance
    /// from a point is convex, and the common translations `t₀` at `x` and
    /// `t₁` at `x + dx` taken off move straight between them), and a
    /// pair's gap moves by at most the farthest move of each primitive's
    /// corners, so with `m` each particle's distance from its place in the
    /// list at `x` (less `t₀`) and `M` the farther of it at `x` and at
    /// `x + dx` (less `t₁`),
    ///
    /// ```text
    /// g(τ) ≥ D − max₁ M − max₂ M − ξ,   g(0) ≤ D + max₁ m + max₂ m − ξ,
    /// ```
    ///
    /// and the pair keeps more than `keep g(0)` throughout, where CCD would
    /// return 1.
    ///
    /// `limited` is told each pair whose CCD returned less than 1, with
    /// that fraction (the per-particle truncation of the `truncate` module).
    pub(super) fn limit(
        &mut self,
        geometry: &Geometry,
        (x, dx, end): (&[Vec3], &[Vec3], &[Vec3]),
        (keep, activation): (f64, f64),
        mut limited: impl FnMut(&Pair, f64),
    ) -> f64 {
        let system = geometry.system;
        // The common translations of `x` and of the motion's end from the
        // list's positions, and the farthest moves less them.
        let reference = &self.verlet.reference;
        let (mut now, mut then) = (drift(reference, x), drift(reference, end));
        if !(self.verlet.within(x, now.1) && self.verlet.within(end, then.1)) {
            let motion = drift(x, end);
            let widest = (MAX_MARGIN * activation).min(self.widest);
            if motion_margin(self.default_margin(activation), motion.1) <= widest {
                self.refresh(system, x, activation, widest);
            } else {
                self.swept(system, (x, end), activation);
            }
            // The list's positions are now `x`.
            (now, then) = ((Vec3::zeros(), 0.0), motion);
        }
        let (reference, now, then) = (&self.verlet.reference, now.0, then.0);
        self.moved.clear();
        self.moved
            .extend(reference.iter().zip(x).zip(end).map(|((r, x), e)| {
                let start = (x - r - now).norm_squared();
                (
                    start.sqrt(),
                    start.max((e - r - then).norm_squared()).sqrt(),
                )
            }));
        let mut tau: f64 = 1.0;
        for (pair, &searched) in Self::pairs(system, &self.near).zip(&self.searched) {
            let now = pair.largest(|p| self.moved[p].0);
            let along = pair.largest(|p| self.moved[p].1);
            let lowest = searched - along.0 - along.1 - pair.thickness;
            let highest = searched + now.0 + now.1 - pair.thickness;
            if lowest > keep * highest {
                continue;
            }
            let fraction = pair.ccd(geometry, x, dx, keep);
            if fraction < 1.0 {
                limited(&pair, fraction);
            }
            tau = tau.min(fraction);
        }
        tau
    }
}
