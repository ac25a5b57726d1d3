//! Pairs without pair forces: the bonded pairs of a system that excludes them (LAMMPS's
//! `special_bonds lj 0 1 1` with `pair_style dpd`), taken out of the table after each fill, so
//! that no sweep, force or observable sees them. A system that excludes nothing never calls
//! this and fills as before.

use super::PairTable;

/// The pairs left out, as each particle's partners by particle id: those of id `a` are
/// `partners[start[a]..start[a + 1]]`.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Exclusions {
    start: Vec<u32>,
    partners: Vec<u32>,
}

impl Exclusions {
    /// The pairs `(i, j)` of `pairs`, ids below `particles`, each left out both ways.
    pub(crate) fn of_pairs(
        particles: usize,
        pairs: impl Iterator<Item = (u32, u32)> + Clone,
    ) -> Self {
        let mut start = vec![0u32; particles + 1];
        for (i, j) in pairs.clone() {
            start[i as usize + 1] += 1;
            start[j as usize + 1] += 1;
        }
        for k in 0..particles {
            start[k + 1] += start[k];
        }
        let mut next = start.clone();
        let mut partners = vec![0; start[particles] as usize];
        for (i, j) in pairs {
            for (a, b) in [(i, j), (j, i)] {
                partners[next[a as usize] as usize] = b;
                next[a as usize] += 1;
            }
        }
        Exclusions { start, partners }
    }

    /// Whether the pair of ids `a` and `b` is left out.
    #[inline(always)]
    fn excludes(&self, a: u32, b: u32) -> bool {
        let (s, e) = (self.start[a as usize], self.start[a as usize + 1]);
        self.partners[s as usize..e as usize].contains(&b)
    }
}

impl PairTable {
    /// Take the pairs `exclusions` names out of the table, particles stored in the order of
    /// `ids` (their ids); the runs, colours and velocity shifts stay those of the pairs kept.
    pub(crate) fn exclude(&mut self, exclusions: &Exclusions, ids: &[u32]) {
        let mut dropped = Vec::new();
        self.pairs.retain(&mut self.groups.runs, |k, p| {
            let kept = !exclusions.excludes(ids[p.i as usize], ids[p.j as usize]);
            if !kept {
                dropped.push(k);
            }
            kept
        });
        if self.shifted && !dropped.is_empty() {
            let mut k = 0;
            self.shifts.retain(|_| {
                k += 1;
                dropped.binary_search(&(k - 1)).is_err()
            });
        }
    }
}
