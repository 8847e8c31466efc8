//! Tests of the list of terms: the passes agree with each other to the
//! bit, and the generic sinks take what the block matrix holds.

use hooke_core::term::Blocks;
use hooke_core::{CompressedSprings, ForceEvaluator, Parallelism};

use super::volume::tests::Fixture;
use super::*;

/// Whether two fields of vectors are equal to the bit.
fn same_bits(a: &[Vec3], b: &[Vec3]) -> bool {
    a.len() == b.len()
        && a.iter().zip(b).all(|(p, q)| {
            p.iter()
                .zip(q.iter())
                .all(|(x, y)| x.to_bits() == y.to_bits())
        })
}

/// The quasi-Newton step's gradient is Newton's right-hand side at the same
/// iterate to the bit, with damped springs, volume elements (one
/// inverted), gravity and air damping: both add each term in the same
/// order and grouping.
#[test]
fn the_gradient_is_the_assembled_right_hand_side_to_the_bit() {
    let f = Fixture::new();
    let (system, v) = (&f.system, &f.v);
    let n = system.particle_count();
    let x = f.positions(v);
    for compressed in [CompressedSprings::Exact, CompressedSprings::Clamped] {
        let at = f.at(&x, v, compressed);
        let mut terms = f.terms();
        let mut gradient = vec![Vec3::repeat(7.0); n];
        terms.gradient(system, &at, &mut gradient);
        let (_, b) = assembled(&mut terms, system, &at);
        assert!(same_bits(&gradient, &b), "{compressed:?}");
    }
}

/// Every term's blocks and right-hand side, written spring by spring and
/// element by element into a sink the terms do not know, make the matrix
/// and right-hand side of the assembly into the block matrix, at an
/// iterate and at Baraff & Witkin's linearisation.
#[test]
fn a_generic_sink_takes_the_block_matrix_terms() {
    let f = Fixture::new();
    let (system, v) = (&f.system, &f.v);
    let n = system.particle_count();
    let x = f.positions(v);
    let u: Vec<Vec3> = (0..n)
        .map(|i| Vec3::new(0.01, -0.02 * i as f64, 0.005))
        .collect();
    let w: Vec<Vec3> = (0..n)
        .map(|i| Vec3::new(1.0, -0.5 * i as f64, 0.25 + i as f64))
        .collect();
    for displacement in [None, Some(&u[..])] {
        let at = At {
            displacement,
            ..f.at(&x, v, CompressedSprings::Clamped)
        };
        let (a, b) = assembled(&mut f.terms(), system, &at);
        let mut expected = vec![Vec3::zeros(); n];
        a.apply(&w, &mut expected);

        let mut terms = f.terms();
        let mut blocks = Blocks::new(n);
        let mut rhs = vec![Vec3::zeros(); n];
        for t in &mut terms.list {
            t.add(system, &at, &mut rhs, &mut blocks);
        }
        let mut product = vec![Vec3::zeros(); n];
        blocks.apply(&w, &mut product);
        for i in 0..n {
            let scale = expected[i].norm().max(b[i].norm()).max(1.0);
            assert!(
                (product[i] - expected[i]).norm() < 1e-12 * scale,
                "A w at {i}"
            );
            assert!((rhs[i] - b[i]).norm() < 1e-12 * scale, "b at {i}");
        }
    }
}

/// The terms' forces sum to the force evaluator's to the bit: the same
/// operations in the same order.
#[test]
fn the_terms_forces_are_the_force_evaluators() {
    let f = Fixture::new();
    let (system, v) = (&f.system, &f.v);
    let n = system.particle_count();
    let terms = f.terms();
    let mut sum = vec![Vec3::zeros(); n];
    for t in terms.iter() {
        t.force(system, &f.x_tilde, v, &mut sum);
    }
    let mut evaluated = vec![Vec3::zeros(); n];
    ForceEvaluator::new(Parallelism::Sequential).forces(system, &f.x_tilde, v, &mut evaluated);
    assert!(same_bits(&sum, &evaluated));
}
