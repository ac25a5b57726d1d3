//! The pairs of a state by the types of their particles, for the observables of mixtures.

use dpd_core::neighbour::CellGrid;
use dpd_core::System;

/// A pass over the pairs closer than a cut-off that knows each particle's type; keeps its cell
/// grid between passes.
#[derive(Default)]
pub(super) struct TypedPairs {
    grid: CellGrid,
}

impl TypedPairs {
    /// Call `f(ti, tj, r)` once for every unordered pair of `sys` closer than `cutoff`, with
    /// `ti <= tj` the types of its particles and `r` their distance.
    pub(super) fn visit(
        &mut self,
        sys: &System,
        cutoff: f64,
        mut f: impl FnMut(usize, usize, f64),
    ) {
        let (q, kinds) = (sys.positions(), sys.kinds());
        let order = self.grid.bin(q, sys.boundary(), cutoff).to_vec();
        let pos = self.grid.gather(q);
        let kind = |a: u32| usize::from(kinds[order[a as usize] as usize]);
        self.grid
            .for_each_pair(&pos, sys.boundary(), sys.shear(), cutoff, |a, b, d| {
                let (ti, tj) = (kind(a), kind(b));
                f(ti.min(tj), ti.max(tj), d.norm());
            });
    }
}

/// Particles of each of `types` types in `sys`.
pub(super) fn type_counts(sys: &System, types: usize) -> Vec<usize> {
    let mut counts = vec![0; types];
    for &t in sys.kinds() {
        counts[usize::from(t)] += 1;
    }
    counts
}

/// The key of the type pair `i <= j`, `"A-B"`.
pub(super) fn pair_name(names: &[String], i: usize, j: usize) -> String {
    format!("{}-{}", names[i], names[j])
}
