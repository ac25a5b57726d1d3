//! What the engine hands a pair update to read: its pair with the per-particle data of the
//! pair's two particles ([`Ends`]), or, for a preparation, consecutive pairs of a run with it
//! ([`Span`]). The engine checks the data once against the table it visits
//! ([`Particles::check`]), so an update reads its particles without a bounds check per pair
//! and without unsafe code.

use super::{Bound, Pair};
use crate::params::Coefficients;
use crate::potential::Soft;
use crate::Vec3;

/// The particles as pair updates read them: inverse masses (0 for frozen particles), types
/// and the coefficients of each pair of types, and, where an update reads the momenta without
/// writing them (the full forces), the momenta: `M` is `&[Vec3]` then, `()` otherwise.
#[derive(Clone, Copy)]
pub(crate) struct Particles<'a, M = ()> {
    inv_mass: &'a [f64],
    kind: &'a [u16],
    coefficients: Coefficients<'a>,
    momenta: M,
}

impl<'a> Particles<'a> {
    /// Particles with inverse masses `inv_mass` and types `kind`, one entry per particle in
    /// each, and the `coefficients` of each pair of types.
    pub(crate) fn new(
        inv_mass: &'a [f64],
        kind: &'a [u16],
        coefficients: Coefficients<'a>,
    ) -> Self {
        Particles {
            inv_mass,
            kind,
            coefficients,
            momenta: (),
        }
    }

    /// These particles with their momenta `p`.
    pub(crate) fn with_momenta(self, p: &'a [Vec3]) -> Particles<'a, &'a [Vec3]> {
        let Particles {
            inv_mass,
            kind,
            coefficients,
            ..
        } = self;
        Particles {
            inv_mass,
            kind,
            coefficients,
            momenta: p,
        }
    }
}

impl<'a, M: Momenta> Particles<'a, M> {
    /// The number of particles.
    pub(crate) fn len(&self) -> usize {
        self.kind.len()
    }

    /// The types, one per particle.
    pub(super) fn kinds(self) -> &'a [u16] {
        self.kind
    }

    /// Panics unless every per-particle array has an entry for each index below `bound`:
    /// then every pair of a table with that bound may read its two particles unchecked.
    pub(super) fn check(&self, bound: Bound) {
        bound.check(self.inv_mass.len());
        bound.check(self.kind.len());
        if let Some(n) = self.momenta.len() {
            bound.check(n);
        }
    }
}

/// What [`Particles`] may hold as momenta: nothing, or one entry per particle.
pub(crate) trait Momenta: Copy + Send + Sync {
    /// The number of entries, `None` for no momenta.
    fn len(self) -> Option<usize>;
}

impl Momenta for () {
    fn len(self) -> Option<usize> {
        None
    }
}

impl Momenta for &[Vec3] {
    fn len(self) -> Option<usize> {
        Some(<[Vec3]>::len(self))
    }
}

/// One pair as the engine hands it to an update: the pair's geometry, and what the update reads
/// of its two particles. Made only by the engine, for a pair of a table that its particles were
/// checked against, so each read is in bounds without a check.
#[derive(Clone, Copy)]
pub(crate) struct Ends<'a, M = ()> {
    pair: &'a Pair,
    particles: Particles<'a, M>,
}

impl<'a, M: Copy> Ends<'a, M> {
    /// # Safety
    /// The indices of `pair` are below a bound `particles` was checked against
    /// ([`Particles::check`]).
    #[inline(always)]
    pub(super) unsafe fn new(pair: &'a Pair, particles: Particles<'a, M>) -> Self {
        Ends { pair, particles }
    }

    /// The pair's geometry.
    #[inline(always)]
    pub(crate) fn pair(self) -> &'a Pair {
        self.pair
    }

    /// The inverse masses `(1/m_i, 1/m_j)`.
    #[inline(always)]
    pub(crate) fn inv_masses(self) -> (f64, f64) {
        self.both(self.particles.inv_mass)
    }

    /// The inverse reduced mass `mu = 1/m_i + 1/m_j`.
    #[inline(always)]
    pub(crate) fn mu(self) -> f64 {
        let (mi, mj) = self.inv_masses();
        mi + mj
    }

    /// The soft repulsion of the pair's types. With one type the types are not read: the pair
    /// loops then load two values fewer per pair.
    #[inline(always)]
    pub(crate) fn soft(self) -> Soft {
        self.particles
            .coefficients
            .soft(|| self.both(self.particles.kind))
    }

    /// The friction and noise amplitude `(gamma_ij, sigma_ij)` of the pair's types (read only
    /// where the pairs' frictions differ).
    #[inline(always)]
    pub(crate) fn friction(self) -> (f64, f64) {
        self.particles
            .coefficients
            .friction(|| self.both(self.particles.kind))
    }

    /// The cut-off `r_c,ij` of the pair's types (read only where the pairs' cut-offs differ).
    #[inline(always)]
    pub(crate) fn rc(self) -> f64 {
        self.particles
            .coefficients
            .rc(|| self.both(self.particles.kind))
    }

    /// `(column[i], column[j])` for a per-particle array of [`Particles`].
    #[inline(always)]
    fn both<T: Copy>(self, column: &[T]) -> (T, T) {
        let (i, j) = (self.pair.i as usize, self.pair.j as usize);
        debug_assert!(i < column.len() && j < column.len());
        // SAFETY: `i` and `j` are below a bound that every array of `particles` was checked to
        // have entries for (`Ends::new`).
        unsafe { (*column.get_unchecked(i), *column.get_unchecked(j)) }
    }
}

impl<'a> Ends<'a, &'a [Vec3]> {
    /// The momenta `(p_i, p_j)`.
    #[inline(always)]
    pub(crate) fn momenta(self) -> (Vec3, Vec3) {
        self.both(self.particles.momenta)
    }
}

/// Consecutive pairs of a run as the engine hands them to a preparation: each with what its
/// update reads of its particles ([`Ends`]).
#[derive(Clone, Copy)]
pub(crate) struct Span<'a, M = ()> {
    pairs: &'a [Pair],
    particles: Particles<'a, M>,
}

impl<'a, M: Copy> Span<'a, M> {
    /// # Safety
    /// As for [`Ends::new`], for every pair of `pairs`.
    #[inline(always)]
    pub(super) unsafe fn new(pairs: &'a [Pair], particles: Particles<'a, M>) -> Self {
        Span { pairs, particles }
    }

    /// `pairs` with `particles`, every index checked (for tests, which have no table).
    #[cfg(test)]
    pub(crate) fn checked(pairs: &'a [Pair], particles: Particles<'a, M>) -> Self
    where
        M: Momenta,
    {
        let largest = pairs.iter().map(|p| p.i.max(p.j) as usize + 1).max();
        particles.check(Bound(largest.unwrap_or(0)));
        // SAFETY: every index is below a bound `particles` was checked against.
        unsafe { Span::new(pairs, particles) }
    }

    /// Pair `k` of the span (panics unless `k < len`).
    #[inline(always)]
    pub(crate) fn get(self, k: usize) -> Ends<'a, M> {
        // SAFETY: a pair of the span (`Span::new`).
        unsafe { Ends::new(&self.pairs[k], self.particles) }
    }

    /// The pairs in order.
    #[inline(always)]
    pub(crate) fn iter(self) -> impl Iterator<Item = Ends<'a, M>> {
        // SAFETY: pairs of the span (`Span::new`).
        self.pairs
            .iter()
            .map(move |pair| unsafe { Ends::new(pair, self.particles) })
    }

    /// The span in consecutive spans of `n` pairs, and the fewer than `n` left over.
    #[inline(always)]
    pub(crate) fn chunks_exact(self, n: usize) -> (impl Iterator<Item = Self>, Self) {
        let chunks = self.pairs.chunks_exact(n);
        let rest = chunks.remainder();
        // SAFETY (both): parts of the span (`Span::new`).
        let each = move |pairs| unsafe { Span::new(pairs, self.particles) };
        (chunks.map(each), each(rest))
    }
}
