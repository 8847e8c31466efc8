//! The factorization of a matrix with blocks outside its pattern.

use hooke_core::{Mat3, System, SystemBuilder, Vec3};

use super::*;
use crate::linear::filter::{Filter, pin_filters};
use crate::linear::pattern::Pattern;
use hooke_core::SymBlock;

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

/// The backward-Euler matrix `M + h c + h² K` of a 12 × 12 sheet, its
/// particles moving, with the filters that fix the sheet's pinned
/// particles, and a right-hand side.
fn sheet_system() -> (BlockMatrix, Vec<Filter>, Vec<Vec3>) {
    use hooke_core::reference::Sheet;

    let system = Sheet::new(12).system().unwrap();
    let mut state = system.initial_state();
    for (i, x) in state.positions_mut().iter_mut().enumerate() {
        x.y = 0.05 * (0.7 * i as f64).sin();
    }
    for (i, v) in state.velocities_mut().iter_mut().enumerate() {
        *v = Vec3::new((i as f64).sin(), (3.0 * i as f64).cos(), 0.0);
    }
    let (a, b) = crate::minimize::terms::linearised_step(&system, &state, 0.01);
    (a, pin_filters(&system), b)
}

/// Both fill-reducing orderings solve the filtered system: the residual of
/// the free particles is at rounding level and the pinned ones stay at
/// zero, and the two solutions agree.
#[test]
fn both_orderings_solve_the_filtered_system() {
    let (a, filters, b) = sheet_system();
    let n = b.len();
    let scale = b.iter().map(|bi| bi.norm()).fold(0.0, f64::max);
    let mut solutions = Vec::new();
    for ordering in [FillOrdering::Particles, FillOrdering::Scalar] {
        let mut cholesky = SparseCholesky::with_ordering(&a, ordering).unwrap();
        let mut x = vec![Vec3::zeros(); n];
        cholesky.solve(&a, &filters, &b, &mut x).unwrap();
        let mut ax = vec![Vec3::zeros(); n];
        a.apply(&x, &mut ax);
        for i in 0..n {
            let residual = filters[i].apply(ax[i] - b[i]).norm();
            assert!(residual < 1e-10 * scale, "{ordering:?}: particle {i}");
            if filters[i] == Filter::Fixed {
                assert_eq!(x[i], Vec3::zeros(), "{ordering:?}: pinned {i}");
            }
        }
        solutions.push(x);
    }
    let size = solutions[1].iter().map(|x| x.norm()).fold(0.0, f64::max);
    for (p, s) in solutions[0].iter().zip(&solutions[1]) {
        assert!((p - s).norm() <= 1e-10 * size);
    }
}

/// A particle whose diagonal block is negative definite makes the
/// factorization fail at that particle, whatever the ordering: the pivots
/// eliminated before it do not see it, and its own first pivot is negative.
#[test]
fn a_negative_pivot_names_its_particle() {
    let (a, filters, _) = sheet_system();
    for bad in [0, 17, 70, 143] {
        let mut broken = a.clone();
        let diagonal = broken.diagonal(bad).norm();
        broken.add_extra_row(
            bad,
            SymBlock::rank_one_plus_identity(0.0, Vec3::x(), -10.0 * diagonal),
        );
        let filters: Vec<Filter> = filters.iter().map(|_| Filter::Free).collect();
        for ordering in [FillOrdering::Particles, FillOrdering::Scalar] {
            let mut cholesky = SparseCholesky::with_ordering(&broken, ordering).unwrap();
            assert_eq!(
                cholesky.factorize(&broken, &filters),
                Err(CholeskyError::NotPositiveDefinite {
                    particle: Some(bad)
                }),
                "{ordering:?}"
            );
        }
    }
}

/// On a 40 × 40 cloth, ordering the particles gives a factor no larger
/// than ordering the scalar unknowns (AMD finds each particle's unknowns
/// as one supervariable there), and one that holds at least the entries
/// the particle graph's factor predicts (faer stores each supernode's
/// columns whole, zeros among them).
#[test]
fn ordering_the_particles_fills_no_more() {
    let system = hooke_core::reference::Sheet::new(40).system().unwrap();
    let a = BlockMatrix::zeros(Pattern::new(&system).unwrap());
    let particles = SparseCholesky::with_ordering(&a, FillOrdering::Particles).unwrap();
    let scalar = SparseCholesky::with_ordering(&a, FillOrdering::Scalar).unwrap();
    let (p, s) = (
        particles.info().factor_nonzeros,
        scalar.info().factor_nonzeros,
    );
    assert!(p <= s, "{p} against {s}");
    let predicted = predicted_factor_entries(a.pattern(), &Routes::default()).unwrap();
    assert!(predicted <= p, "{predicted} predicted, {p} held");
}

/// A flat `n × n` grid with stiff stretch springs (1000 N/m) along rows
/// and columns, shear springs (100 N/m) across cells and weak bending
/// springs (1 N/m) two apart, nothing pinned: rows a unit apart, the
/// columns' spacing growing by `growth` from one to the next (the particle
/// of column `c` at `x = c (1 + growth c)`).
pub(crate) fn stiff_and_weak_grid(n: usize, growth: f64) -> System {
    let mut builder = SystemBuilder::new();
    for row in 0..n {
        for col in 0..n {
            let c = col as f64;
            builder.particle(0.01, [c * (1.0 + growth * c), 0.0, row as f64]);
        }
    }
    let at = |row: usize, col: usize| row * n + col;
    for row in 0..n {
        for col in 0..n {
            for (down, across, k) in [
                (0, 1, 1000.0),
                (1, 0, 1000.0),
                (1, 1, 100.0),
                (0, 2, 1.0),
                (2, 0, 1.0),
            ] {
                if row + down < n && col + across < n {
                    builder.spring(at(row, col), at(row + down, col + across), k);
                }
            }
            if row + 1 < n && col >= 1 {
                builder.spring(at(row, col), at(row + 1, col - 1), 100.0);
            }
        }
    }
    builder.build().unwrap()
}

/// [`stiff_and_weak_grid`] of unit spacing, its backward-Euler matrix at rest for
/// `h = 0.05` s, and the routes of its weak springs.
fn routed_grid(n: usize) -> (System, BlockMatrix, Routes) {
    let system = stiff_and_weak_grid(n, 0.0);
    let (a, _) = crate::minimize::terms::linearised_step(&system, &system.initial_state(), 0.05);
    let routes = Routes::new(&system, a.pattern());
    (system, a, routes)
}

/// Every bending spring of the grid, and nothing else, is routed through
/// the particle between its ends, with equal weights.
#[test]
fn the_bending_springs_are_routed_through_their_middle_particles() {
    let n = 6;
    let (system, a, routes) = routed_grid(n);
    let weak = |s: &hooke_core::Spring| s.stiffness < 10.0;
    let bending = system.springs().iter().filter(|s| weak(s)).count();
    assert_eq!(bending, 2 * n * (n - 2));
    assert_eq!(routes.iter().count(), bending);
    for route in routes.iter() {
        let spring = &system.springs()[a.pattern().spring(route.slot as usize)];
        assert!(weak(spring));
        let [i, j] = route.ends.map(|e| e as usize);
        assert_eq!(route.middle as usize, (i + j) / 2, "route {i}–{j}");
        assert!(route.weights.iter().all(|w| (w - 2.0).abs() < 1e-12));
    }
}

/// The routed factor holds half the grid's fill, and solves a matrix `P`
/// at least the whole one `A` that equals it on affine velocity fields:
/// for `b = A y`, the factor returns `y` itself where `y` is affine
/// (`P y = A y`: every route's legs strain alike), and for any `y`,
/// `bᵀP⁻¹b ≤ bᵀA⁻¹b = yᵀA y`.
#[test]
fn the_routed_factor_solves_a_majorizer_exact_on_affine_fields() {
    let n = 12;
    let (_, a, routes) = routed_grid(n);
    let filters = vec![Filter::Free; n * n];
    let whole = SparseCholesky::new(&a).unwrap();
    let mut routed =
        SparseCholesky::with_routes(&a, (FillOrdering::Particles, Supernodes::default()), routes)
            .unwrap();
    let (kept, carried) = (whole.info().factor_nonzeros, routed.info().factor_nonzeros);
    assert!(2 * carried < 3 * kept / 2, "{carried} against {kept}");
    routed.factorize(&a, &filters).unwrap();
    let positions: Vec<Vec3> = (0..n * n)
        .map(|i| Vec3::new((i % n) as f64, 0.0, (i / n) as f64))
        .collect();
    let gradient = Mat3::new(0.3, -1.2, 0.5, 0.7, 0.2, -0.4, 1.1, 0.6, -0.9);
    let affine: Vec<Vec3> = positions
        .iter()
        .map(|x| gradient * x + Vec3::new(0.1, -0.2, 0.3))
        .collect();
    let mut b = vec![Vec3::zeros(); n * n];
    a.apply(&affine, &mut b);
    let mut x = vec![Vec3::zeros(); n * n];
    routed.solve_factored(&filters, &b, &mut x);
    let size = affine.iter().map(|y| y.norm()).fold(0.0, f64::max);
    for (i, (x, y)) in x.iter().zip(&affine).enumerate() {
        assert!(
            (x - y).norm() <= 1e-9 * size,
            "particle {i}: {x:?} against {y:?}"
        );
    }
    for k in 0..20 {
        let y: Vec<Vec3> = (0..n * n)
            .map(|i| {
                let t = (7 * k + 3 * i) as f64;
                Vec3::new(t.sin(), (1.3 * t).cos(), (0.7 * t + 1.0).sin())
            })
            .collect();
        a.apply(&y, &mut b);
        routed.solve_factored(&filters, &b, &mut x);
        let factored: f64 = b.iter().zip(&x).map(|(b, x)| b.dot(x)).sum();
        let exact: f64 = b.iter().zip(&y).map(|(b, y)| b.dot(y)).sum();
        assert!(
            factored > 0.0 && factored <= exact * (1.0 + 1e-12),
            "y {k}: bᵀP⁻¹b = {factored:e}, bᵀA⁻¹b = {exact:e}"
        );
    }
}

/// On the routed factor of a 30 × 30 grid (the contact scenes' cloths are
/// 25 × 25 and 30 × 30), faer's own rule takes the simplicial
/// factorization and [`Supernodes::Blocks`] the supernodal one; the two
/// factor the same matrix, so they solve it alike, to rounding.
#[test]
fn both_supernode_rules_factor_the_same_matrix_and_blocks_takes_supernodes_sooner() {
    let n = 30;
    let (_, a, routes) = routed_grid(n);
    let filters = vec![Filter::Free; n * n];
    let b: Vec<Vec3> = (0..n * n)
        .map(|i| {
            let t = i as f64;
            Vec3::new(t.sin(), (1.3 * t).cos(), (0.7 * t + 1.0).sin())
        })
        .collect();
    let solve = |supernodes| {
        let mut factor =
            SparseCholesky::with_routes(&a, (FillOrdering::Particles, supernodes), routes.clone())
                .unwrap();
        factor.factorize(&a, &filters).unwrap();
        let mut x = vec![Vec3::zeros(); n * n];
        factor.solve_factored(&filters, &b, &mut x);
        (factor.info().supernodal, x)
    };
    let (blocks, by_blocks) = solve(Supernodes::Blocks);
    let (faer, by_faer) = solve(Supernodes::Faer);
    assert!(blocks && !faer, "supernodal: blocks {blocks}, faer {faer}");
    let size = by_faer.iter().map(|x| x.norm()).fold(0.0, f64::max);
    for (i, (x, y)) in by_blocks.iter().zip(&by_faer).enumerate() {
        assert!(
            (x - y).norm() <= 1e-10 * size,
            "particle {i}: {x:?} against {y:?}"
        );
    }
}
