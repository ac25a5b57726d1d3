//! When a per-particle loop is split across the rayon pool.

/// Below this many particles the per-particle loops (permutations, binning, drifts, kicks, the
/// blow-up guard) run on one thread: splitting them costs more than it saves.
const PARALLEL_MIN_PARTICLES: usize = 16_384;

/// Whether a per-particle loop over `n` particles runs on all threads: only for large systems,
/// and only when the pool has more than one.
pub(crate) fn on_all_threads(n: usize) -> bool {
    n >= PARALLEL_MIN_PARTICLES && rayon::current_num_threads() > 1
}
