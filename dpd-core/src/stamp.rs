//! Validity of the caches tied to the positions (pair table, conservative and full forces).
//!
//! Every change of the positions starts a new [`Generation`]; a cache records the generation
//! it was computed at in a [`Stamp`] and is fresh while the two agree. A new cache needs no
//! code at the places that move particles: they only start a new generation.

/// Counts the changes of the positions of a [`crate::System`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Generation(u64);

impl Generation {
    /// The positions changed.
    pub(crate) fn advance(&mut self) {
        self.0 += 1;
    }
}

/// The generation of the positions a cache was computed at; `None`: never computed.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Stamp(Option<Generation>);

impl Stamp {
    /// Computed at the positions of generation `now`.
    pub(crate) fn at(now: Generation) -> Self {
        Stamp(Some(now))
    }

    /// Whether the cache belongs to the positions of generation `now`.
    pub(crate) fn is_fresh(self, now: Generation) -> bool {
        self.0 == Some(now)
    }
}
