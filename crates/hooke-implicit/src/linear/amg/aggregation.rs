//! Aggregates of a level's nodes by strength of connection (Vaněk, Mandel &
//! Brezina, *Algebraic multigrid by smoothed aggregation for second and
//! fourth order elliptic problems*, Computing 56, 1996).

/// The node graph of a level: node `I`'s neighbours `adj[ptr[I]..ptr[I+1]]`
/// with the Frobenius norms `‖A_IJ‖_F` of the coupling blocks, and the
/// norms `‖A_II‖_F` of the diagonal blocks.
#[derive(Debug, Default)]
pub(crate) struct Graph {
    pub(crate) ptr: Vec<usize>,
    pub(crate) adj: Vec<u32>,
    pub(crate) weight: Vec<f64>,
    pub(crate) diagonal: Vec<f64>,
}

/// Marks a node left out of every aggregate (it has no strong neighbour:
/// the smoother alone handles it).
pub(crate) const ISOLATED: u32 = u32::MAX;

/// Per entry of the graph, whether the neighbour is strong:
/// `‖A_IJ‖_F ≥ θ √(‖A_II‖_F ‖A_JJ‖_F)` and `A_IJ ≠ 0`.
pub(crate) fn strong_mask(graph: &Graph, theta: f64) -> Vec<bool> {
    let mut mask = Vec::with_capacity(graph.adj.len());
    for i in 0..graph.diagonal.len() {
        for k in graph.ptr[i]..graph.ptr[i + 1] {
            let j = graph.adj[k] as usize;
            let w = graph.weight[k];
            mask.push(
                j != i && w > 0.0 && w >= theta * (graph.diagonal[i] * graph.diagonal[j]).sqrt(),
            );
        }
    }
    mask
}

/// Groups the nodes into aggregates, returning each node's aggregate (or
/// [`ISOLATED`]) and the number of aggregates.
///
/// `J` is a strong neighbour of `I` when `‖A_IJ‖_F ≥ θ √(‖A_II‖_F ‖A_JJ‖_F)`.
/// Three passes: (1) a node none of whose strong neighbours is aggregated
/// starts an aggregate with all of them; (2) every node left joins the
/// aggregate it is most strongly connected to; (3) nodes still left (their
/// strong neighbours all unaggregated in pass 1 and 2, which cannot happen
/// for a node with any aggregated strong neighbour) start aggregates with
/// their unaggregated strong neighbours.
pub(crate) fn aggregate(graph: &Graph, theta: f64) -> (Vec<u32>, usize) {
    let n = graph.diagonal.len();
    let mask = strong_mask(graph, theta);
    let strong = |i: usize| {
        let range = graph.ptr[i]..graph.ptr[i + 1];
        graph.adj[range.clone()]
            .iter()
            .zip(&mask[range])
            .filter(|&(_, &s)| s)
            .map(|(&j, _)| j as usize)
    };
    let unassigned = u32::MAX - 1;
    let mut agg: Vec<u32> = (0..n)
        .map(|i| {
            if strong(i).next().is_none() {
                ISOLATED
            } else {
                unassigned
            }
        })
        .collect();
    let mut count = 0u32;
    for i in 0..n {
        if agg[i] != unassigned || strong(i).any(|j| agg[j] != unassigned) {
            continue;
        }
        agg[i] = count;
        for j in strong(i) {
            agg[j] = count;
        }
        count += 1;
    }
    let first_pass = agg.clone();
    for (i, a) in agg.iter_mut().enumerate() {
        if *a != unassigned {
            continue;
        }
        let range = graph.ptr[i]..graph.ptr[i + 1];
        let strongest = graph.adj[range.clone()]
            .iter()
            .zip(&graph.weight[range.clone()])
            .zip(&mask[range])
            .filter(|&((&j, _), &s)| s && first_pass[j as usize] < unassigned)
            .max_by(|a, b| a.0.1.total_cmp(b.0.1));
        if let Some(((&j, _), _)) = strongest {
            *a = first_pass[j as usize];
        }
    }
    for i in 0..n {
        if agg[i] != unassigned {
            continue;
        }
        agg[i] = count;
        for j in strong(i) {
            if agg[j] == unassigned {
                agg[j] = count;
            }
        }
        count += 1;
    }
    (agg, count as usize)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A path of `n` nodes with unit couplings.
    fn path(n: usize) -> Graph {
        let mut g = Graph {
            ptr: vec![0],
            diagonal: vec![2.0; n],
            ..Graph::default()
        };
        for i in 0..n {
            for j in [i.wrapping_sub(1), i + 1] {
                if j < n {
                    g.adj.push(j as u32);
                    g.weight.push(1.0);
                }
            }
            g.ptr.push(g.adj.len());
        }
        g
    }

    #[test]
    fn a_path_is_cut_into_neighbourhoods_and_a_loose_node_is_isolated() {
        let (agg, count) = aggregate(&path(9), 0.1);
        assert_eq!(agg, [0, 0, 1, 1, 1, 2, 2, 2, 2]);
        assert_eq!(count, 3);
        let mut loose = path(3);
        loose.weight.fill(0.0);
        let (agg, count) = aggregate(&loose, 0.1);
        assert_eq!(agg, [ISOLATED; 3]);
        assert_eq!(count, 0);
    }
}
