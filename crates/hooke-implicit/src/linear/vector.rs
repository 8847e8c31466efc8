//! Per-particle vector operations, data-parallel for large systems.

use hooke_core::Vec3;

/// Particle count from which loops run in parallel (with the `parallel`
/// feature). A PCG iteration opens about nine parallel regions, and waking a
/// worker costs tens of microseconds on the machine measured — as much as a
/// whole product at 4 096 particles (154 µs, `benches/README.md`) — so
/// smaller systems stay sequential.
pub const PARALLEL_MIN_PARTICLES: usize = 16_384;

/// Rows handed to one rayon task at least.
#[cfg(feature = "parallel")]
pub(crate) const MIN_CHUNK: usize = 2048;

/// Calls `f(i, &mut out[i])` for every `i`, in parallel when `out` is long.
#[inline]
pub(crate) fn for_each_row<T: Send>(out: &mut [T], f: impl Fn(usize, &mut T) + Sync + Send) {
    #[cfg(feature = "parallel")]
    if out.len() >= PARALLEL_MIN_PARTICLES {
        use rayon::prelude::*;
        out.par_iter_mut()
            .enumerate()
            .with_min_len(MIN_CHUNK)
            .for_each(|(i, o)| f(i, o));
        return;
    }
    for (i, o) in out.iter_mut().enumerate() {
        f(i, o);
    }
}

/// Calls `f(i, &mut a[i], &mut b[i])` for every `i`, in parallel when long.
#[inline]
pub(crate) fn for_each_row2<A: Send, B: Send>(
    a: &mut [A],
    b: &mut [B],
    f: impl Fn(usize, &mut A, &mut B) + Sync + Send,
) {
    debug_assert_eq!(a.len(), b.len());
    #[cfg(feature = "parallel")]
    if a.len() >= PARALLEL_MIN_PARTICLES {
        use rayon::prelude::*;
        a.par_iter_mut()
            .zip(b.par_iter_mut())
            .enumerate()
            .with_min_len(MIN_CHUNK)
            .for_each(|(i, (ai, bi))| f(i, ai, bi));
        return;
    }
    for (i, (ai, bi)) in a.iter_mut().zip(b.iter_mut()).enumerate() {
        f(i, ai, bi);
    }
}

/// Calls `f(i, &mut a[i], &mut b[i], &mut c[i])` for every `i`, in parallel
/// when long.
#[inline]
pub(crate) fn for_each_row3<A: Send, B: Send, C: Send>(
    a: &mut [A],
    b: &mut [B],
    c: &mut [C],
    f: impl Fn(usize, &mut A, &mut B, &mut C) + Sync + Send,
) {
    debug_assert!(a.len() == b.len() && b.len() == c.len());
    #[cfg(feature = "parallel")]
    if a.len() >= PARALLEL_MIN_PARTICLES {
        use rayon::prelude::*;
        a.par_iter_mut()
            .zip(b.par_iter_mut())
            .zip(c.par_iter_mut())
            .enumerate()
            .with_min_len(MIN_CHUNK)
            .for_each(|(i, ((ai, bi), ci))| f(i, ai, bi, ci));
        return;
    }
    for (i, ((ai, bi), ci)) in a.iter_mut().zip(b.iter_mut()).zip(c.iter_mut()).enumerate() {
        f(i, ai, bi, ci);
    }
}

/// Into how many chunks to split `springs` springs for a parallel pass: one
/// per thread for large systems, else one.
#[cfg(feature = "parallel")]
pub(crate) fn spring_chunks(springs: usize) -> usize {
    if springs >= PARALLEL_MIN_PARTICLES {
        rayon::current_num_threads().max(1)
    } else {
        1
    }
}

/// One chunk: the `parallel` feature is off.
#[cfg(not(feature = "parallel"))]
pub(crate) fn spring_chunks(_springs: usize) -> usize {
    1
}

/// `Σᵢ f(i)`, in parallel when `n` is large.
#[inline]
pub(crate) fn sum(n: usize, f: impl Fn(usize) -> f64 + Sync + Send) -> f64 {
    #[cfg(feature = "parallel")]
    if n >= PARALLEL_MIN_PARTICLES {
        use rayon::prelude::*;
        return (0..n).into_par_iter().with_min_len(MIN_CHUNK).map(f).sum();
    }
    (0..n).map(f).sum()
}

/// `(Σᵢ f(i).0, Σᵢ f(i).1)`, in parallel when `n` is large.
#[inline]
pub(crate) fn sum2(n: usize, f: impl Fn(usize) -> (f64, f64) + Sync + Send) -> (f64, f64) {
    let add = |a: (f64, f64), b: (f64, f64)| (a.0 + b.0, a.1 + b.1);
    #[cfg(feature = "parallel")]
    if n >= PARALLEL_MIN_PARTICLES {
        use rayon::prelude::*;
        return (0..n)
            .into_par_iter()
            .with_min_len(MIN_CHUNK)
            .map(f)
            .reduce(|| (0.0, 0.0), add);
    }
    (0..n).map(f).fold((0.0, 0.0), add)
}

/// `(Σᵢ f(i, &mut out[i]).0, Σᵢ f(i, &mut out[i]).1)`: a pass that updates
/// every row and sums over them, in parallel when `out` is long (summed in
/// the order of [`sum2`]).
#[inline]
pub(crate) fn sum2_rows<T: Send>(
    out: &mut [T],
    f: impl Fn(usize, &mut T) -> (f64, f64) + Sync + Send,
) -> (f64, f64) {
    let add = |a: (f64, f64), b: (f64, f64)| (a.0 + b.0, a.1 + b.1);
    #[cfg(feature = "parallel")]
    if out.len() >= PARALLEL_MIN_PARTICLES {
        use rayon::prelude::*;
        return out
            .par_iter_mut()
            .enumerate()
            .with_min_len(MIN_CHUNK)
            .map(|(i, o)| f(i, o))
            .reduce(|| (0.0, 0.0), add);
    }
    out.iter_mut()
        .enumerate()
        .map(|(i, o)| f(i, o))
        .fold((0.0, 0.0), add)
}

/// `Σᵢ aᵢ·bᵢ`.
pub(crate) fn dot(a: &[Vec3], b: &[Vec3]) -> f64 {
    sum(a.len(), |i| a[i].dot(&b[i]))
}
