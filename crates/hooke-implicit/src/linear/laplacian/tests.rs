//! The routed Laplacian against the whole one.

use super::*;
use hooke_core::Mat3;

use crate::linear::amg::csr::Csr;
use crate::linear::cholesky::tests::stiff_and_weak_grid;
use crate::linear::vector::dot;

/// `H₀` at `h = 0.05` s for the grid with weak springs as `weak` says.
fn matrix(system: &System, weak: WeakSprings) -> Laplacian {
    let weights = (0.05, |s: &Spring| 0.05 * s.damping + 0.0025 * s.stiffness);
    Laplacian::new(system, weights, (0, &[]), (Inverse::Factor, weak), 0.0).unwrap()
}

fn entries(laplacian: &Laplacian) -> usize {
    match &laplacian.solver {
        Solver::Factor(factor) => factor.entries(),
        Solver::Multigrid(..) => unreachable!("a factor was asked for"),
    }
}

/// `A y`, coordinate by coordinate (nothing is pinned).
fn product(a: &Csr, y: &[Vec3]) -> Vec<Vec3> {
    let mut b = vec![Vec3::zeros(); y.len()];
    let (mut column, mut out) = (vec![0.0; y.len()], vec![0.0; y.len()]);
    for c in 0..3 {
        column.iter_mut().zip(y).for_each(|(x, y)| *x = y[c]);
        a.apply(&column, &mut out);
        b.iter_mut().zip(&out).for_each(|(b, o)| b[c] = *o);
    }
    b
}

/// With the grid's bending springs routed, `H₀` becomes a matrix `P` at
/// least the whole one `A` that equals it on affine fields, with a
/// smaller factor: for `b = A y`, `P⁻¹ b` is `y` itself where `y` is
/// affine, and for any `y`, `bᵀP⁻¹b ≤ bᵀA⁻¹b = yᵀA y` — strictly
/// where the field bends. The columns' spacing grows along the rows, so
/// the legs of a route differ in length and each weight must go to its
/// own leg for the affine fields to come back.
#[test]
fn routed_weak_springs_make_a_smaller_majorizer_exact_on_affine_fields() {
    let n = 12;
    let system = stiff_and_weak_grid(n, 0.1);
    let (kept, mut routed) = (
        matrix(&system, WeakSprings::Kept),
        matrix(&system, WeakSprings::Routed),
    );
    let (whole, carried) = (entries(&kept), entries(&routed));
    assert!(4 * carried < 3 * whole, "{carried} against {whole}");
    let gradient = Mat3::new(0.3, -1.2, 0.5, 0.7, 0.2, -0.4, 1.1, 0.6, -0.9);
    let affine: Vec<Vec3> = system
        .initial_positions()
        .iter()
        .map(|x| gradient * x + Vec3::new(0.1, -0.2, 0.3))
        .collect();
    let mut x = product(&kept.layout.a, &affine);
    routed.apply_inverse_in_place(&mut x);
    let size = affine.iter().map(|y| y.norm()).fold(0.0, f64::max);
    for (i, (x, y)) in x.iter().zip(&affine).enumerate() {
        assert!(
            (x - y).norm() < 1e-9 * size,
            "particle {i}: {x:?} against {y:?}"
        );
    }
    let bent: Vec<Vec3> = system
        .initial_positions()
        .iter()
        .map(|p| Vec3::new((3.0 * p.x).sin(), (p.x * p.z).cos(), (2.0 * p.z).sin()))
        .collect();
    let b = product(&kept.layout.a, &bent);
    let mut x = b.clone();
    routed.apply_inverse_in_place(&mut x);
    let (majorized, whole) = (dot(&b, &x), dot(&b, &bent));
    assert!(
        majorized < whole * (1.0 - 1e-9),
        "{majorized} against {whole}"
    );
}
