//! The interacting pairs of the current positions, with the geometry every sub-flow needs:
//! the table (this module), its fill (`fill.rs`), the engine that visits it in the sweep order
//! of [`crate::neighbour`] (`engine.rs`) and what the engine hands each pair update to read
//! (`ends.rs`), and the pairs a system leaves out of it (`exclude.rs`).

mod ends;
mod engine;
mod exclude;
mod fill;

use ends::Momenta;
pub(crate) use ends::{Ends, Particles, Span};
pub(crate) use engine::{Run, Two};
use exclude::{All, Keep};
pub(crate) use exclude::{Excluding, Exclusions};

use crate::chunked::Parts;
use crate::disjoint::Disjoint;
use crate::neighbour::Runs;
use crate::params::Params;
use crate::potential::Soft;
use crate::rng::pair_normals;
use crate::{Tensor, Vec3};

/// One interacting pair with `r_ij < r_c`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pair {
    pub i: u32,
    pub j: u32,
    /// Unit vector from j to i (minimum image).
    pub e: Vec3,
    /// `w = 1 - r_ij / r_c`, the conservative-force weight.
    pub w: f64,
    /// Random weight `w_R = w^(s/2)`; the dissipative weight is `w_R^2`.
    pub wr: f64,
}

impl Pair {
    /// Distance `r_ij = r_c (1 - w)` for cutoff `rc` (not stored: the pair loops stream the
    /// table, and 8 bytes fewer per pair is 12 % less traffic).
    #[inline(always)]
    pub fn r(&self, rc: f64) -> f64 {
        rc * (1.0 - self.w)
    }

    /// The pair's relative velocity along `e`, `e . (v_i - v_j + (dvx, 0, 0))` for its velocity
    /// shift `dvx` ([`PairTable::shifts`]), added only when `SHIFTED` (a compile-time switch,
    /// so that periodic sweeps do not pay).
    #[inline(always)]
    pub fn normal_velocity<const SHIFTED: bool>(&self, vi: Vec3, vj: Vec3, dvx: f64) -> f64 {
        let u = self.e.dot(&(vi - vj));
        if SHIFTED {
            u + self.e.x * dvx
        } else {
            u
        }
    }
}

/// Below this many pairs a sweep is not worth splitting across threads.
const PARALLEL_MIN_PAIRS: usize = 8192;

/// Whether a pass over `n` pairs runs on all threads.
fn on_all_threads(n: usize) -> bool {
    n >= PARALLEL_MIN_PAIRS && rayon::current_num_threads() > 1
}

/// The interacting pairs in sweep order, grouped into runs and colours.
#[derive(Clone, Debug, Default)]
pub struct PairTable {
    pairs: Parts<Pair>,
    /// Velocity shift of each pair, in table order, when `shifted`; else empty. Kept apart
    /// from [`Pair`] because only sheared boxes and walls have shifts, and every pair loop
    /// streams the pairs.
    shifts: Vec<f64>,
    /// Whether the last fill was under shear or with walls (see [`PairTable::shifts`]).
    shifted: bool,
    groups: Runs,
    /// The particle count of the last fill: every pair's `i` and `j` are below it (the fill
    /// takes them from cell ranges of, or bounds-checked lookups in, that many positions).
    particles: usize,
}

impl PairTable {
    /// Number of pairs.
    pub fn len(&self) -> usize {
        self.pairs.len()
    }

    pub fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }

    /// The pairs in sweep order.
    pub fn iter(&self) -> impl DoubleEndedIterator<Item = &Pair> + '_ {
        self.pairs.iter()
    }

    /// The x-velocity `dvx` each pair adds to `v_i - v_j`, in sweep order, or `None` when there
    /// is none (no shear, no walls). Across a sliding Lees-Edwards boundary the partner of i is
    /// an image of j moving at `v_j - dvx` along x, and a frozen wall particle moves with its
    /// wall (`v_i - v_j` sees it at rest), so the dissipative and random forces see
    /// `v_ij = v_i - v_j + (dvx, 0, 0)`. Zero for every other pair.
    pub fn shifts(&self) -> Option<&[f64]> {
        self.shifted.then_some(&self.shifts)
    }

    /// `sum_pairs term(soft_ij, pair)` in table order (the same on any thread count), with
    /// each pair's repulsion from `params` for the particle kinds `kind` (storage order).
    pub(crate) fn sum_soft<T: std::iter::Sum>(
        &self,
        params: &Params,
        kind: &[u16],
        term: impl Fn(Soft, &Pair) -> T,
    ) -> T {
        self.iter()
            .map(|pair| {
                term(
                    params.soft(kind[pair.i as usize], kind[pair.j as usize]),
                    pair,
                )
            })
            .sum()
    }
}

/// [`Noise`] with its ids checked against a table's bound, as the sweeps draw from it.
#[derive(Clone, Copy)]
pub(crate) struct Drawn<'a> {
    noise: Noise<'a>,
    id: ByPair<'a, u32>,
}

impl Drawn<'_> {
    /// The standard normals of `pairs`, one per pair, into `z`.
    ///
    /// # Safety
    /// `pairs` are pairs of the table (or fill) whose bound made this ([`Noise::of`]).
    #[inline(always)]
    unsafe fn draw(self, pairs: &[Pair], z: &mut [f64]) {
        let Drawn { noise, id } = self;
        // SAFETY: the caller's contract.
        let key = |k: usize| unsafe { id.get_two(pairs[k].i, pairs[k].j) };
        pair_normals(noise.seed, noise.step, noise.stream, key, z);
    }
}

impl<'a> Noise<'a> {
    /// This noise for the pairs of a table with index bound `bound`.
    fn of(self, bound: Bound) -> Drawn<'a> {
        Drawn {
            noise: self,
            id: bound.read(self.id),
        }
    }
}

/// The noise of one pairwise sweep: pair `(i, j)` gets the standard normal
/// `pair_normal(seed, step, stream, id[i], id[j])` ([`crate::rng`]).
#[derive(Clone, Copy)]
pub(crate) struct Noise<'a> {
    pub seed: u64,
    pub step: u64,
    pub stream: u8,
    pub id: &'a [u32],
}

/// What a pairwise update records per pair and [`PairTable::sweep_noisy`] adds up: `()` (nothing,
/// at no cost) or the pair virial tensor `r_ij f e_ij (x) e_ij = q_ij (x) (f e_ij)` of a force
/// or impulse `f` along `e_ij`, with the pair's cut-off `rc()` (called only for the tensor, so
/// that a sweep that records nothing does not look it up).
pub(crate) trait Virial: Send + Default {
    fn of(pair: &Pair, rc: impl FnOnce() -> f64, f: f64) -> Self;
    fn add(self, other: Self) -> Self;
}

impl Virial for () {
    #[inline(always)]
    fn of(_: &Pair, _: impl FnOnce() -> f64, _: f64) {}
    #[inline(always)]
    fn add(self, _: ()) {}
}

impl Virial for Tensor {
    #[inline(always)]
    fn of(pair: &Pair, rc: impl FnOnce() -> f64, f: f64) -> Self {
        (pair.r(rc()) * f) * pair.e * pair.e.transpose()
    }
    #[inline(always)]
    fn add(self, other: Self) -> Self {
        self + other
    }
}

impl PairTable {
    /// The bound on the pairs' indices, for indexing per-particle arrays by them.
    fn bound(&self) -> Bound {
        Bound(self.particles)
    }
}

/// A bound on the particle indices of a pair table: the particle count of its fill.
#[derive(Clone, Copy, Debug)]
struct Bound(usize);

impl Bound {
    /// The bound of a table filled from positions `q` (its indices are below `q.len()`).
    fn of(q: &[Vec3]) -> Self {
        Bound(q.len())
    }

    /// `data`, one entry per particle, for reading by the pairs' indices without a bounds
    /// check per pair. Panics unless it has an entry for every index below the bound.
    fn read<T: Copy>(self, data: &[T]) -> ByPair<'_, T> {
        self.check(data.len());
        ByPair(data)
    }

    /// [`Disjoint`] over `data`, for the engine's writes by the pairs' indices without a
    /// bounds check per pair ([`both`]). Panics unless it has an entry for every index below
    /// the bound.
    fn write<T>(self, data: &mut [T]) -> Disjoint<'_, T> {
        self.check(data.len());
        Disjoint::new(data)
    }

    fn check(self, len: usize) {
        assert!(
            len >= self.0,
            "{len} entries for a pair table of {} particles",
            self.0
        );
    }
}

/// A per-particle slice with an entry for every index of a pair table ([`Bound::read`]): the
/// ids by which the engine draws the pairs' noise.
#[derive(Clone, Copy)]
struct ByPair<'a, T>(&'a [T]);

impl<T: Copy> ByPair<'_, T> {
    /// The entries of particles `i` and `j`, without bounds checks.
    ///
    /// # Safety
    /// `i` and `j` are the indices of a pair of the table (or fill) whose bound made this
    /// ([`Bound::read`]): such indices are below the bound, and the slice has an entry for
    /// each.
    #[inline(always)]
    unsafe fn get_two(self, i: u32, j: u32) -> (T, T) {
        let (i, j) = (i as usize, j as usize);
        debug_assert!(i < self.0.len() && j < self.0.len());
        // SAFETY: in bounds, the caller's contract.
        unsafe { (*self.0.get_unchecked(i), *self.0.get_unchecked(j)) }
    }
}
