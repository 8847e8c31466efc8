//! How large a sparse Cholesky factor will be, predicted from the springs'
//! graph without factorizing (the `auto` choice skips a factor that would
//! not fit).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::SymbolicSparseColMatRef;
use faer::sparse::linalg::amd;

use crate::linear::neighbours::Neighbours;
use crate::linear::pattern::Pattern;

use super::Routes;

/// The approximate minimum degree ordering of the particle graph of
/// `pattern` (one node per particle, an edge per pair of particles a
/// spring joins, the springs `routes` carries on their paths left out):
/// each particle's place in the order, and the number of
/// off-diagonal entries of that graph's Cholesky factor, which AMD counts
/// as it orders. `None` if the graph does not fit 32-bit indices.
pub(crate) fn particle_order(pattern: &Pattern, routes: &Routes) -> Option<(Vec<u32>, usize)> {
    let n = pattern.rows();
    // Both triangles of the graph in compressed columns, each column's rows
    // in increasing order.
    let neighbours = Neighbours::new(pattern);
    let mut col_ptr = Vec::with_capacity(n + 1);
    let mut row_idx = Vec::new();
    col_ptr.push(0u32);
    for q in 0..n {
        row_idx.extend(routes.kept(neighbours.of(q)).map(|&(p, _)| p));
        col_ptr.push(u32::try_from(row_idx.len()).ok()?);
    }
    drop(neighbours);
    let graph = SymbolicSparseColMatRef::new_checked(n, n, &col_ptr, None, &row_idx);
    let (mut perm, mut perm_inv) = (vec![0u32; n], vec![0u32; n]);
    let mut memory = MemBuffer::new(amd::order_scratch::<u32>(n, row_idx.len()));
    let count = amd::order(
        &mut perm,
        &mut perm_inv,
        graph,
        amd::Control::default(),
        MemStack::new(&mut memory),
    )
    .ok()?;
    // AMD's division count is the factor's off-diagonal entry count.
    Some((perm_inv, count.n_div as usize))
}

/// The number of scalar entries of the Cholesky factor of a matrix with
/// `pattern`'s blocks less those `routes` carries on their paths, predicted without factorizing: the factor of the
/// particle graph in its [`particle_order`] has `f` off-diagonal entries,
/// and the block factor a 3x3 block for each (`9 f`) and the lower
/// triangle of one per particle (`6 n`) —
/// [`SparseCholesky`](super::SparseCholesky) factorizes in that order, so
/// its factor has this size. `None` if the graph does not fit 32-bit
/// indices.
pub(crate) fn predicted_factor_entries(pattern: &Pattern, routes: &Routes) -> Option<usize> {
    particle_order(pattern, routes).map(|(_, off_diagonal)| 9 * off_diagonal + 6 * pattern.rows())
}

#[cfg(test)]
mod tests {
    use hooke_core::SystemBuilder;
    use hooke_core::reference::{Chain, Sheet};

    use super::*;
    use crate::linear::cholesky::SparseCholesky;
    use crate::linear::matrix::BlockMatrix;

    /// Graphs whose fill is known: a chain and a star (its centre ordered
    /// last) fill nothing, so their factors have the graph's `n − 1` edges.
    #[test]
    fn predicted_factor_of_graphs_without_fill() {
        let n = 100;
        let chain = Pattern::new(&Chain::pendulum(n, 1.0, 1.0, 1.0).system().unwrap()).unwrap();
        let mut b = SystemBuilder::new();
        b.particle(1.0, [0.0, 0.0, 0.0]);
        for i in 1..n {
            let angle = i as f64;
            b.particle(1.0, [angle.cos(), angle.sin(), 0.0]);
            b.spring(0, i, 1.0);
        }
        let star = Pattern::new(&b.build().unwrap()).unwrap();
        for p in [chain, star] {
            let routes = Routes::default();
            assert_eq!(
                predicted_factor_entries(&p, &routes),
                Some(9 * (n - 1) + 6 * n)
            );
        }
    }

    /// On a cloth the prediction from the particle graph is within a factor
    /// of two of the factor faer allocates, whose supernodes hold zeros
    /// too.
    #[test]
    fn predicted_factor_of_a_cloth_is_about_faers() {
        let system = Sheet::new(24).system().unwrap();
        let a = BlockMatrix::zeros(Pattern::new(&system).unwrap());
        let predicted = predicted_factor_entries(a.pattern(), &Routes::default()).unwrap() as f64;
        let actual = SparseCholesky::new(&a).unwrap().info().factor_nonzeros as f64;
        let ratio = predicted / actual;
        assert!((0.5..=2.0).contains(&ratio), "{predicted} against {actual}");
    }
}
