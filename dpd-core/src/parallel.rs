//! When a per-particle loop is split across the rayon pool, and the pool's loops behind trait
//! objects: rayon's machinery is compiled once per item type, not once for each generic caller
//! (the engine's pair sweeps and fills, monomorphised for every flow, made half of dpd-core's
//! LLVM IR that way); a dynamic call per chunk of work costs nothing next to the chunk.

use rayon::prelude::*;

/// Below this many particles the per-particle loops (permutations, binning, drifts, kicks, the
/// blow-up guard) run on one thread: splitting them costs more than it saves.
const PARALLEL_MIN_PARTICLES: usize = 16_384;

/// Whether a per-particle loop over `n` particles runs on all threads: only for large systems,
/// and only when the pool has more than one.
pub(crate) fn on_all_threads(n: usize) -> bool {
    n >= PARALLEL_MIN_PARTICLES && rayon::current_num_threads() > 1
}

/// `f(k, &mut a[k], &mut b[k])` for every `k` on all threads.
pub(crate) fn each_in_parallel<A: Send, B: Send>(
    a: &mut [A],
    b: &mut [B],
    f: &(dyn Fn(usize, &mut A, &mut B) + Sync),
) {
    a.par_iter_mut()
        .zip(b.par_iter_mut())
        .enumerate()
        .for_each(|(k, (a, b))| f(k, a, b));
}

/// `[f(0), ..., f(n - 1)]`, computed on all threads.
pub(crate) fn map_in_parallel<R: Send>(n: usize, f: &(dyn Fn(usize) -> R + Sync)) -> Vec<R> {
    (0..n).into_par_iter().map(f).collect()
}
