//! The factorization of a matrix with blocks outside its pattern.

use hooke_core::SystemBuilder;

use super::*;
use crate::linear::block::SymBlock;
use crate::linear::pattern::Pattern;

/// A chain of four unit masses, springs joining 0–1, 1–2 and 2–3 only,
/// with a contact-like term `c g gᵀ`, `g = (n, n, n, n)`, joining all
/// four: the whole matrix `F = I + c g gᵀ` is positive definite, but
/// without its blocks 0–2, 0–3 and 1–3 what remains is indefinite
/// (in the direction `n` it is `I + c T`, `T` the 4 × 4 tridiagonal
/// matrix of ones, whose eigenvalues `1 + 2 cos(kπ/5)` include
/// `−0.618`). With those blocks' compensation the factorization
/// succeeds, and the factored `K` is at least `F`:
/// `bᵀK⁻¹b ≤ bᵀF⁻¹b` for every `b`, with `F⁻¹` from Sherman–Morrison.
#[test]
fn blocks_outside_the_pattern_leave_the_factored_matrix_above_the_whole_one() {
    let mut builder = SystemBuilder::new();
    for i in 0..4 {
        builder.particle(1.0, [i as f64, 0.0, 0.0]);
    }
    for i in 1..4 {
        builder.spring(i - 1, i, 1.0);
    }
    let system = builder.build().unwrap();
    let mut a = BlockMatrix::zeros(Pattern::new(&system).unwrap());
    let (c, n) = (1e6, Vec3::new(1.0, 2.0, -2.0) / 3.0);
    for i in 0..4 {
        a.add_extra_row(i, SymBlock::rank_one_plus_identity(c, n, 1.0));
        for j in i + 1..4 {
            a.add_extra_pair(i, j, c * n * n.transpose());
        }
    }
    assert!(!a.extra_within_pattern());
    let filters = vec![Filter::Free; 4];
    let mut cholesky = SparseCholesky::new(&a).unwrap();
    cholesky.factorize(&a, &filters).unwrap();
    assert!(!cholesky.is_complete());
    for k in 0..20 {
        let b: Vec<Vec3> = (0..4)
            .map(|i| {
                let t = (7 * k + 3 * i) as f64;
                Vec3::new(t.sin(), (1.3 * t).cos(), (0.7 * t + 1.0).sin())
            })
            .collect();
        let mut x = vec![Vec3::zeros(); 4];
        cholesky.solve_factored(&filters, &b, &mut x);
        let factored: f64 = b.iter().zip(&x).map(|(b, x)| b.dot(x)).sum();
        let along: f64 = b.iter().map(|b| b.dot(&n)).sum();
        let norm: f64 = b.iter().map(|b| b.norm_squared()).sum();
        let whole = norm - c * along * along / (1.0 + 4.0 * c);
        assert!(
            factored > 0.0 && factored <= whole * (1.0 + 1e-9),
            "b {k}: bᵀK⁻¹b = {factored:e}, bᵀF⁻¹b = {whole:e}"
        );
    }
}
