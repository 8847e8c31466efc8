//! The surface part of the pair list: its Verlet list, its swept search
//! and its part of the limit.

use hooke_core::collision::barrier::Barrier;
use hooke_core::collision::broad::{BroadPhase, Candidates};
use hooke_core::{Shape, System, SystemBuilder, Vec3};

use super::surface::SurfacePart;
use super::verlet::{MARGIN, drift};
use crate::minimize::contact::KEEP;
use crate::minimize::contact::obstacles::{At, Obstacles};
use crate::minimize::contact::pair::{Geometry, Pair};
use crate::minimize::contact::tests::{sheet, sheets_over, uniform};

/// The gap of a surface pair at `x`.
fn gap(pair: &Pair, x: &[Vec3]) -> f64 {
    pair.distance(x) - pair.thickness
}

/// The surface part's limit on the motion from `x` by `dx`.
fn limit(
    part: &mut SurfacePart,
    geometry: &Geometry,
    (x, dx): (&[Vec3], &[Vec3]),
    keep: (f64, f64),
) -> f64 {
    let end: Vec<Vec3> = x.iter().zip(dx).map(|(x, d)| x + d).collect();
    part.limit(geometry, (x, dx, &end), keep, |_, _| ())
}

/// The barrier per unit stiffness with contact distance `d_hat`.
fn barrier(d_hat: f64) -> Barrier {
    Barrier {
        stiffness: 1.0,
        activation: d_hat,
    }
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
    let mut close: Vec<[usize; 4]> = SurfacePart::pairs(system, candidates)
        .filter(|p| gap(p, x) < reach)
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
    pairs: &SurfacePart,
    x0: &[Vec3],
    dx: &[Vec3],
    points: u32,
) -> usize {
    let d_hat = system.contact_distance();
    let mut everything = Candidates::default();
    BroadPhase::default().proximity(system.surfaces(), x0, 1.0, &mut everything);
    let listed = |particles: [usize; 4]| {
        SurfacePart::pairs(system, &pairs.near).any(|p| p.particles == particles)
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
fn searched_sheets() -> (System, f64, Vec<Vec3>, SurfacePart) {
    let system = sheets();
    let d_hat = system.contact_distance();
    let x0 = system.initial_positions().to_vec();
    let mut pairs = SurfacePart::default();
    pairs.begin(&system);
    pairs.search(&system, &x0, d_hat);
    (system, d_hat, x0, pairs)
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
    assert_eq!(pairs.verlet.reference, x0, "the list was renewed");
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
    assert_eq!(pairs.verlet.reference, x2);
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
    let mut pairs = SurfacePart::default();
    pairs.begin(&system);
    pairs.search(&system, &x0, d_hat);
    assert!(
        (pairs.verlet.margin - d_hat).abs() < 1e-9 * d_hat,
        "margin {} m, d̂ {d_hat} m",
        pairs.verlet.margin
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
fn a_candidate_the_bound_leaves_out_is_beyond_the_contact_distance() {
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
        assert_eq!(pairs.verlet.reference, x0);
        let reachable: Vec<[usize; 4]> = pairs
            .reachable(&system, &x, d_hat)
            .map(|pair| pair.particles)
            .collect();
        let (mut far, mut near) = (0, 0);
        for pair in SurfacePart::pairs(&system, &pairs.near) {
            let gap = gap(&pair, &x);
            if !reachable.contains(&pair.particles) {
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
        let obstacles = Obstacles::default();
        let geometry = Geometry::new(&system, &obstacles, At::End);
        let barrier = barrier(d_hat);
        let all: f64 = SurfacePart::pairs(&system, &pairs.near)
            .map(|pair| pair.energy(&geometry, &x, &barrier))
            .sum();
        let filtered: f64 = pairs
            .reachable(&system, &x, d_hat)
            .map(|pair| pair.energy(&geometry, &x, &barrier))
            .sum();
        assert!(
            (filtered - all).abs() <= f64::EPSILON * all,
            "{filtered} J, {all} J"
        );
    }
}

#[test]
fn the_line_search_limit_skips_only_pairs_that_ccd_clears_and_covers_the_motion() {
    let (system, d_hat, x0, mut pairs) = searched_sheets();
    let obstacles = Obstacles::default();
    let geometry = Geometry::new(&system, &obstacles, At::End);
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
        let tau = limit(&mut pairs, &geometry, (&x0, &dx), (keep, d_hat));
        match kept {
            Some(true) => assert_eq!(pairs.verlet.reference, x0),
            Some(false) => {
                assert!(
                    pairs.verlet.margin > 2.0 * size * d_hat,
                    "margin {}",
                    pairs.verlet.margin
                );
                let end: Vec<Vec3> = x0.iter().zip(&dx).map(|(x, d)| x + d).collect();
                assert!(pairs.covers(&x0) && pairs.covers(&end));
            }
            None => assert!(
                pairs.verlet.margin == 0.0 && !pairs.covers(&x0),
                "motions of {size} d̂"
            ),
        }
        // The bound skipped no pair whose CCD stops the motion.
        let unpruned = SurfacePart::pairs(&system, &pairs.near)
            .map(|pair| pair.ccd(&geometry, &x0, &dx, keep))
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
    let obstacles = Obstacles::default();
    let geometry = Geometry::new(&system, &obstacles, At::End);
    let tau = limit(&mut pairs, &geometry, (&x0, &dx), (0.1, d_hat));
    assert!(
        pairs.verlet.margin == 0.0 && tau < 0.2,
        "margin {}, τ {tau}",
        pairs.verlet.margin
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
    let (system, x0, everything, mut contact) = sheets_over(Shape::Plane {
        point: Vec3::new(0.0, -3e-3, 0.0),
        normal: Vec3::y(),
    });
    let d_hat = system.contact_distance();
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
        let geometry = Geometry::new(&system, &contact.obstacles, At::End);
        let floor = (0..x0.len() as u32)
            .map(|i| Pair::obstacle(&system, &contact.obstacles, (i, 0)))
            .map(|pair| pair.ccd(&geometry, &x0, &dx, KEEP))
            .fold(1.0, f64::min);
        let mut whole = SurfacePart::default();
        whole.begin(&system);
        whole.search(&system, &x0, d_hat);
        let surfaces = limit(&mut whole, &geometry, (&x0, &dx), (KEEP, d_hat));
        let tau = contact.limit(&system, &x0, &dx);
        assert!(
            tau <= floor && tau >= floor.min(surfaces) * (1.0 - 1e-12),
            "drop {drop}: {tau} against floor {floor}, surfaces {surfaces}"
        );
        for pair in SurfacePart::pairs(&system, &everything) {
            let start = gap(&pair, &x0);
            for step in 1..=10 {
                let t = tau * f64::from(step) / 10.0;
                let x: Vec<Vec3> = x0.iter().zip(&dx).map(|(x, d)| x + t * d).collect();
                let gap = gap(&pair, &x);
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

/// A fine flat sheet (as in `a_fine_flat_sheet_lists_no_pair_of_its_own`)
/// swung 8° as a whole about one edge: a motion of more than an edge,
/// which the particles' common translation does not take off, so that
/// every pair of neighbouring primitives is a swept candidate and the
/// common translation alone cannot clear one of them. A pair's own
/// primitives move together, and the swept search lists only the pairs
/// that their motion relative to each other can bring within d̂: none of
/// the swung sheet's. Shaken besides (each particle up to 2 d̂ in its own
/// direction), the sheet brings pairs within d̂, and the list holds every
/// one of them, anywhere along the motion.
#[test]
fn a_swept_search_measures_each_pair_by_its_own_relative_motion() {
    let mut b = SystemBuilder::new();
    let n = 20;
    let spacing = 0.01;
    sheet(&mut b, n, spacing, Vec3::zeros());
    b.contact_distance(0.25 * spacing);
    let system = b.build().unwrap();
    let d_hat = system.contact_distance();
    let x0 = system.initial_positions().to_vec();
    let obstacles = Obstacles::default();
    let geometry = Geometry::new(&system, &obstacles, At::End);
    // Particle (i, j) sits at spacing · (i, 0, j); the swing turns it
    // about the x axis.
    let (sin, cos) = 8.0_f64.to_radians().sin_cos();
    let mut unit = uniform(17);
    for shake in [0.0, 2.0 * d_hat] {
        let dx: Vec<Vec3> = x0
            .iter()
            .map(|x| {
                let swung = Vec3::new(x.x, x.z * sin, x.z * cos);
                let d = Vec3::new(unit(), unit(), unit()).normalize();
                swung - x + shake * (unit() + 0.5) * d
            })
            .collect();
        let end: Vec<Vec3> = x0.iter().zip(&dx).map(|(x, d)| x + d).collect();
        assert!(drift(&x0, &end).1 > spacing);
        let mut pairs = SurfacePart::default();
        pairs.begin(&system);
        pairs.search(&system, &x0, d_hat);
        limit(&mut pairs, &geometry, (&x0, &dx), (KEEP, d_hat));
        assert!(pairs.verlet.margin == 0.0, "shaken {shake} m: not swept");
        let mut boxes = Candidates::default();
        let reach = d_hat + pairs.thickest;
        BroadPhase::default().swept(system.surfaces(), &x0, &end, reach, &mut boxes);
        let count = |c: &Candidates| c.point_triangle.len() + c.edge_edge.len();
        let (listed, found) = (count(&pairs.near), count(&boxes));
        let close = every_close_pair_listed(&system, &pairs, &x0, &dx, 20);
        let expected = if shake == 0.0 {
            close == 0 && listed == 0 && found > 1000
        } else {
            close > 0 && listed < found
        };
        assert!(
            expected,
            "shaken {shake} m: {listed} listed of {found} found, {close} close"
        );
    }
}

/// A search whose candidates fill several blocks of the narrow phase (a
/// 90 × 90 sheet with a contact distance of two spacings, about 90
/// candidates a particle, their distances computed on every core) keeps
/// exactly the pairs a direct filter of the same candidates keeps, in
/// the same order, each with its distance.
#[test]
fn a_search_longer_than_a_block_keeps_what_a_direct_filter_keeps() {
    let mut b = SystemBuilder::new();
    let spacing = 0.01;
    sheet(&mut b, 90, spacing, Vec3::zeros());
    b.contact_distance(2.0 * spacing);
    let system = b.build().unwrap();
    let d_hat = system.contact_distance();
    let mut unit = uniform(23);
    let x: Vec<Vec3> = system
        .initial_positions()
        .iter()
        .map(|x| x + 0.3 * spacing * Vec3::new(unit(), unit(), unit()))
        .collect();
    let mut pairs = SurfacePart::default();
    pairs.begin(&system);
    pairs.search(&system, &x, d_hat);
    let reach = d_hat + pairs.verlet.margin;
    let mut found = Candidates::default();
    BroadPhase::default().proximity(system.surfaces(), &x, reach, &mut found);
    let count = |c: &Candidates| c.point_triangle.len() + c.edge_edge.len();
    assert!(
        count(&found) > 4 * (1 << 16),
        "{} candidates",
        count(&found)
    );
    let direct: Vec<(Pair, f64)> = SurfacePart::pairs(&system, &found)
        .map(|pair| {
            let distance = pair.distance(&x);
            (pair, distance)
        })
        .filter(|(pair, distance)| distance - pair.thickness < reach)
        .collect();
    let listed: Vec<Pair> = SurfacePart::pairs(&system, &pairs.near).collect();
    assert_eq!(listed.len(), direct.len());
    assert!(count(&pairs.near) < count(&found), "every candidate kept");
    for ((pair, searched), (expected, distance)) in listed.iter().zip(&pairs.searched).zip(&direct)
    {
        assert_eq!(pair.particles, expected.particles);
        assert_eq!(searched.to_bits(), distance.to_bits());
    }
}
