//! Pairs without pair forces: the bonded pairs of a system that excludes them (LAMMPS's
//! `special_bonds lj 0 1 1` with `pair_style dpd`), never put in the table (the fill asks
//! [`Excluding::keeps`] of each pair within the cut-off), so that no sweep, force or
//! observable sees them. A system that excludes nothing fills with a check that compiles away.

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

    /// The ids whose pairs with id `a` are left out.
    #[inline(always)]
    fn partners_of(&self, a: u32) -> &[u32] {
        let (s, e) = (self.start[a as usize], self.start[a as usize + 1]);
        &self.partners[s as usize..e as usize]
    }
}

/// Which of the pairs within the cut-off a fill keeps, by storage indices: asked per pair, or
/// for the hits of one particle once for the particle and then per partner.
pub(crate) trait Keep: Copy + Sync {
    /// Whether the pair `(i, j)` is kept.
    fn keeps(self, i: u32, j: u32) -> bool;
    /// Whether the pair `(a, j)` is kept, as a test of `j`.
    fn with(self, a: u32) -> impl Fn(u32) -> bool;
}

/// Every pair is kept: a fill without exclusions, whose checks compile away.
#[derive(Clone, Copy)]
pub(crate) struct All;

impl Keep for All {
    #[inline(always)]
    fn keeps(self, _: u32, _: u32) -> bool {
        true
    }
    #[inline(always)]
    fn with(self, _: u32) -> impl Fn(u32) -> bool {
        |_| true
    }
}

/// A system's exclusions read through its particles' ids, for a fill that works in storage
/// indices.
#[derive(Clone, Copy)]
pub(crate) struct Excluding<'a> {
    exclusions: &'a Exclusions,
    /// The particle id of each storage index.
    ids: &'a [u32],
}

impl<'a> Excluding<'a> {
    /// `exclusions`, if a system has any, for particles whose ids are `ids` in storage order.
    pub(crate) fn of(exclusions: Option<&'a Exclusions>, ids: &'a [u32]) -> Option<Self> {
        exclusions.map(|exclusions| Excluding { exclusions, ids })
    }
}

impl Keep for Excluding<'_> {
    #[inline(always)]
    fn keeps(self, i: u32, j: u32) -> bool {
        self.with(i)(j)
    }
    #[inline(always)]
    fn with(self, a: u32) -> impl Fn(u32) -> bool {
        let (left_out, ids) = (self.exclusions.partners_of(self.ids[a as usize]), self.ids);
        move |j| !left_out.contains(&ids[j as usize])
    }
}
