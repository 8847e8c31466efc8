//! The broad phase's loops and sorts, on rayon's pool when asked (and the
//! `parallel` feature is on), sequential otherwise.

#[cfg(feature = "parallel")]
use super::GRAIN;

/// Calls `f(i, &mut items[i])` for every item, on rayon's pool if
/// `parallel`.
#[cfg_attr(not(feature = "parallel"), allow(unused_variables))]
pub(super) fn for_each<T: Send>(
    parallel: bool,
    items: &mut [T],
    f: impl Fn(usize, &mut T) + Sync + Send,
) {
    #[cfg(feature = "parallel")]
    if parallel {
        use rayon::prelude::*;
        let grain = if items.len() > GRAIN { 1024 } else { 1 };
        items
            .par_iter_mut()
            .enumerate()
            .with_min_len(grain)
            .for_each(|(i, item)| f(i, item));
        return;
    }
    for (i, item) in items.iter_mut().enumerate() {
        f(i, item);
    }
}

/// Sorts, on rayon's pool if `parallel`.
#[cfg_attr(not(feature = "parallel"), allow(unused_variables))]
pub(super) fn sort<T: Ord + Send>(parallel: bool, items: &mut [T]) {
    #[cfg(feature = "parallel")]
    if parallel {
        use rayon::prelude::*;
        items.par_sort_unstable();
        return;
    }
    items.sort_unstable();
}

/// The threads of rayon's pool (1 without the `parallel` feature).
pub(super) fn threads() -> usize {
    #[cfg(feature = "parallel")]
    return rayon::current_num_threads().max(1);
    #[cfg(not(feature = "parallel"))]
    1
}
