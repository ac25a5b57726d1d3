//! The interacting pairs of the current positions, with the geometry every sub-flow needs,
//! and the executor that visits them in the sweep order of [`crate::neighbour`].

use crate::avx2::with_avx2;
use crate::boundary::{LeesEdwards, PeriodicBox};
use crate::chunked::{self, Parts};
use crate::neighbour::{Hits, Runs, VerletList};
use crate::params::Params;
use crate::rng::pair_normals;
use crate::walls::FrozenWalls;
use crate::{Tensor, Vec3};
use dpd_ir::SweepOrder;
use rayon::prelude::*;
use std::cell::RefCell;
use std::marker::PhantomData;
use std::ops::Range;

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

thread_local! {
    /// The standard normals of the run a noisy visit is at, one buffer per thread.
    static NORMALS: RefCell<Vec<f64>> = const { RefCell::new(Vec::new()) };
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

    /// Refill with the pairs of `list` that interact at positions `q`, keeping its order: from
    /// the list's candidates, or with skin 0 straight from the scan of its grid (then `q` must
    /// be in the cell order of its last build, as a [`crate::System`] keeps it).
    ///
    /// Coincident particles (`r = 0`) have no defined direction; such a pair is left out, so it
    /// exerts no force rather than a NaN one.
    pub(crate) fn collect(
        &mut self,
        list: &VerletList,
        q: &[Vec3],
        bx: &PeriodicBox,
        shear: Option<&LeesEdwards>,
        walls: Option<&FrozenWalls>,
        params: &Params,
    ) {
        match (shear, walls) {
            (None, None) => self.collect_then(list, q, bx, params, |_: &[Pair]| {}),
            // The scan's separation is the image, but the velocity shift needs the crossing
            // count: both come from the positions.
            (Some(le), _) => {
                let fill = self.start_fill(list, q, bx, shear, params, true);
                let image = |i: u32, j: u32| le.min_image(bx, q[i as usize] - q[j as usize]);
                let from_positions = |i, j, _| Some(image(i, j).0);
                fill.into(self, from_positions, Some(from_positions), |_: &[Pair]| {});
                let shifts = self.pairs.iter().map(|p| image(p.i, p.j).1);
                self.shifts.extend(shifts);
            }
            (None, Some(w)) => {
                let fill = self.start_fill(list, q, bx, None, params, true);
                let mobile = |i: u32, j: u32, d: Vec3| {
                    (!(w.frozen[i as usize] && w.frozen[j as usize])).then_some(d)
                };
                let image = |i, j, d| mobile(i, j, bx.min_image(d));
                fill.into(self, image, Some(mobile), |_: &[Pair]| {});
                let v = &w.velocity_x;
                let shifts = self.pairs.iter().map(|p| v[p.i as usize] - v[p.j as usize]);
                self.shifts.extend(shifts);
            }
        }
    }

    /// [`PairTable::collect`] in a periodic box without walls, calling `after(run)` for every
    /// run of the new table as soon as it is filled, while its pairs are in cache: on the
    /// thread that filled it, colour by colour, so that `after` may update the particles of
    /// the run's pairs as [`PairTable::visit`] would, in the same order. The table's indices
    /// are below `Bound::of(q)`.
    pub(crate) fn collect_then(
        &mut self,
        list: &VerletList,
        q: &[Vec3],
        bx: &PeriodicBox,
        params: &Params,
        after: impl Fn(&[Pair]) + Sync,
    ) {
        let fill = self.start_fill(list, q, bx, None, params, false);
        let image = |_, _, d| Some(bx.min_image(d));
        fill.into(self, image, None::<Separation>, after);
    }

    /// Reset the table for a fill at positions `q`, which records velocity shifts if
    /// `shifted`, and what the fill reads.
    fn start_fill<'a>(
        &mut self,
        list: &'a VerletList,
        q: &'a [Vec3],
        bx: &'a PeriodicBox,
        shear: Option<&'a LeesEdwards>,
        params: &'a Params,
        shifted: bool,
    ) -> Fill<'a> {
        self.shifted = shifted;
        self.shifts.clear();
        self.particles = q.len();
        Fill {
            list,
            q,
            bx,
            shear,
            params,
        }
    }
}

/// The separation of pair `(i, j)` to use, given the one a scan found, or `None` when the pair
/// does not interact.
type Separation = fn(u32, u32, Vec3) -> Option<Vec3>;

/// What [`PairTable::collect`] fills from.
struct Fill<'a> {
    list: &'a VerletList,
    q: &'a [Vec3],
    bx: &'a PeriodicBox,
    shear: Option<&'a LeesEdwards>,
    params: &'a Params,
}

impl Fill<'_> {
    /// Fill `table`: from the candidates with `image(i, j, q_i - q_j)` giving the minimum
    /// image, or `None` for a pair that does not interact (two frozen particles); without skin
    /// from the grid's scan, with `scanned(i, j, d)` doing the same for the scan's
    /// minimum-image separation `d`, or with the scan's hits as they are when `scanned` is
    /// `None`. `after(run)` is called with every run once it is filled, colour by colour, the
    /// runs of one colour on the threads that filled them.
    #[inline(always)]
    fn into(
        self,
        table: &mut PairTable,
        image: impl Fn(u32, u32, Vec3) -> Option<Vec3> + Sync,
        scanned: Option<impl Fn(u32, u32, Vec3) -> Option<Vec3> + Sync>,
        after: impl Fn(&[Pair]) + Sync,
    ) {
        let Fill {
            list,
            q,
            bx,
            shear,
            params,
        } = self;
        let rc = params.rc();
        let rc2 = rc * rc;
        let inv_rc = 1.0 / rc;
        // The pair of `(i, j)` at separation `d`, `r2 = |d|^2`, `r = sqrt(r2)`, `inv = 1 / r`.
        let geometry = |i: u32, j: u32, d: Vec3, r: f64, inv: f64| {
            let w = 1.0 - r * inv_rc;
            Pair {
                i,
                j,
                e: d * inv,
                w,
                wr: params.w_r(w),
            }
        };
        let interacts = |r2: f64| r2 < rc2 && r2 > 0.0;
        let pair = |i: u32, j: u32, d: Vec3| -> Option<Pair> {
            let r2 = d.norm_squared();
            interacts(r2).then(|| {
                let r = r2.sqrt();
                geometry(i, j, d, r, 1.0 / r)
            })
        };
        if list.skin() == 0.0 {
            let grid = list.grid();
            table.groups = match &scanned {
                None => grid.sweep(
                    q,
                    bx,
                    shear,
                    rc,
                    &mut table.pairs,
                    #[inline(always)]
                    |h, out| {
                        out.reserve(h.len());
                        for k in 0..h.len() {
                            if interacts(h.r2[k]) {
                                let (j, d) = h.get(k);
                                out.push(geometry(h.a(), j, d, h.r[k], h.inv_r[k]));
                            }
                        }
                    },
                    after,
                ),
                Some(scanned) => {
                    let emit = |h: &Hits, out: &mut Vec<Pair>| {
                        for k in 0..h.len() {
                            let (j, d) = h.get(k);
                            out.extend(scanned(h.a(), j, d).and_then(|g| pair(h.a(), j, g)))
                        }
                    };
                    grid.sweep(q, bx, shear, rc, &mut table.pairs, emit, after)
                }
            };
            return;
        }
        let from = list.groups();
        let runs: Vec<&[(u32, u32)]> = from
            .runs
            .windows(2)
            .map(|run| list.candidates().slice(run[0] as usize..run[1] as usize))
            .collect();
        let parallel = on_all_threads(list.candidates().len());
        let (groups, split) = (&from.colours, from.independent);
        let kept = chunked::flat_map_ordered(
            &runs,
            groups,
            split,
            &mut table.pairs,
            parallel,
            |run, out| {
                let start = out.len();
                for &(i, j) in *run {
                    let d = q[i as usize] - q[j as usize];
                    out.extend(image(i, j, d).and_then(|g| pair(i, j, g)));
                }
                after(&out[start..]);
            },
        );
        let groups = &mut table.groups;
        groups.runs.clear();
        groups.runs.push(0);
        let mut end = 0;
        for n in kept {
            end += n;
            groups.runs.push(end);
        }
        groups.colours.clone_from(&from.colours);
        groups.independent = from.independent;
    }
}

impl PairTable {
    /// Visit every pair once in the sweep order (`Forward`), or in exactly the reverse order
    /// (`Reverse`). Runs of one colour go to different threads when the grid is coloured and
    /// the table is large; they touch disjoint particles, so the result is the same as the
    /// sequential visit on any number of threads.
    pub(crate) fn visit(&self, order: SweepOrder, visit: impl Fn(&Pair) + Sync + Copy) {
        self.visit_sum(order, visit)
    }

    /// [`PairTable::visit`], summing what `visit` returns: within a run in visiting order,
    /// then run by run, then colour by colour, so the sum is the same on any number of threads.
    /// With `T = ()` this is the plain visit at no cost.
    pub(crate) fn visit_sum<T: Virial>(
        &self,
        order: SweepOrder,
        visit: impl Fn(&Pair) -> T + Sync + Copy,
    ) -> T {
        self.visit_sum_noisy(order, None, move |p, _, _| visit(p))
    }

    /// [`PairTable::visit_sum`] handing each pair its standard normal of `noise` (0 with
    /// `None`) and its velocity shift (0 without, see [`PairTable::shifts`]). The normals of a
    /// run are drawn just before it is visited, while its pairs are in cache
    /// ([`crate::rng::pair_normals`]); they are the numbers [`crate::rng::pair_normal`]
    /// gives. `visit` is called from one place only (a block of one pair), so that the compiler
    /// inlines it into the loop over a run.
    pub(crate) fn visit_sum_noisy<T: Virial>(
        &self,
        order: SweepOrder,
        noise: Option<Noise>,
        visit: impl Fn(&Pair, f64, f64) -> T + Sync + Copy,
    ) -> T {
        self.visit_sum_prepared::<1, f64, T>(order, noise, |_, z| z, visit)
    }

    /// [`PairTable::visit_sum_noisy`] with a preparation: `prepare(pairs, z)` computes what the
    /// visits of `B` consecutive pairs (in visiting order) need from the pairs and their
    /// normals alone, all `B` at once so that it may be vectorised, and `visit(pair, p, dvx)`
    /// gets each pair's result `p`. A run's last block is padded with its last pair, whose
    /// extra results are dropped. `prepare` must not read what the visits change.
    pub(crate) fn visit_sum_prepared<const B: usize, P: Copy, T: Virial>(
        &self,
        order: SweepOrder,
        noise: Option<Noise>,
        prepare: impl Fn([&Pair; B], [f64; B]) -> [P; B] + Sync + Copy,
        visit: impl Fn(&Pair, P, f64) -> T + Sync + Copy,
    ) -> T {
        let shifts = self.shifts();
        let noise = noise.map(|noise| noise.of(self.bound()));
        self.visit_runs(order, |range, pairs| {
            let dvx = shifts.map(|s| &s[range][..pairs.len()]);
            visit_run_prepared(pairs, dvx, order, noise, prepare, visit)
        })
    }

    /// Fold every run of the table with `run(range, pairs)` (`pairs` the run's pairs, items
    /// `range` of the table; `run` visits them in `order`) and sum the results run by run,
    /// then colour by colour, in `order`.
    fn visit_runs<T: Virial>(
        &self,
        order: SweepOrder,
        run: impl Fn(Range<usize>, &[Pair]) -> T + Sync,
    ) -> T {
        let g = &self.groups;
        let total = |items: &mut dyn Iterator<Item = T>| items.fold(T::default(), T::add);
        let run = |k: u32| -> T {
            let range = g.runs[k as usize] as usize..g.runs[k as usize + 1] as usize;
            run(range.clone(), self.pairs.slice(range))
        };
        let parallel = g.independent > 0 && on_all_threads(self.pairs.len());
        let colours = g.colours.len().saturating_sub(1);
        let colour = |c: usize| -> T {
            let runs = g.colours[c]..g.colours[c + 1];
            if parallel && c < g.independent {
                let sums: Vec<T> = runs.into_par_iter().map(run).collect();
                match order {
                    SweepOrder::Forward => total(&mut sums.into_iter()),
                    SweepOrder::Reverse => total(&mut sums.into_iter().rev()),
                }
            } else {
                match order {
                    SweepOrder::Forward => total(&mut runs.map(run)),
                    SweepOrder::Reverse => total(&mut runs.rev().map(run)),
                }
            }
        };
        match order {
            SweepOrder::Forward => total(&mut (0..colours).map(colour)),
            SweepOrder::Reverse => total(&mut (0..colours).rev().map(colour)),
        }
    }
}

/// Visit the pairs of one run in `order` as [`PairTable::visit_sum_noisy`] does, `dvx` their
/// velocity shifts (all 0 with `None`), and sum what `visit` returns in visiting order. Runs in
/// code compiled with AVX2 where the CPU has it.
#[inline(always)]
pub(crate) fn visit_run<T: Virial>(
    pairs: &[Pair],
    dvx: Option<&[f64]>,
    order: SweepOrder,
    noise: Option<Drawn>,
    visit: impl Fn(&Pair, f64, f64) -> T + Copy,
) -> T {
    visit_run_prepared::<1, f64, T>(pairs, dvx, order, noise, |_, z| z, visit)
}

/// [`visit_run`] with the preparation of [`PairTable::visit_sum_prepared`].
#[inline(always)]
fn visit_run_prepared<const B: usize, P: Copy, T: Virial>(
    pairs: &[Pair],
    dvx: Option<&[f64]>,
    order: SweepOrder,
    noise: Option<Drawn>,
    prepare: impl Fn([&Pair; B], [f64; B]) -> [P; B] + Copy,
    visit: impl Fn(&Pair, P, f64) -> T + Copy,
) -> T {
    NORMALS.with_borrow_mut(|normals| {
        // Everything the loop reads is moved in, so that the compiler sees that the updates
        // (stores through raw pointers) do not change it and keeps it in registers: behind
        // references it was loaded again for every pair.
        with_avx2(
            #[inline(always)]
            move || {
                let n = pairs.len();
                let z = noise.map(|Drawn { noise, id }| {
                    normals.resize(n, 0.0);
                    let key = |k: usize| (id.get(pairs[k].i), id.get(pairs[k].j));
                    pair_normals(noise.seed, noise.step, noise.stream, key, &mut normals[..n]);
                    &normals[..n]
                });
                let dvx = dvx.map(|s| &s[..n]);
                let run = Run {
                    pairs,
                    z,
                    dvx,
                    reverse: order == SweepOrder::Reverse,
                };
                let mut t = T::default();
                // Blocks of one pair are visited as they are prepared: in the force passes
                // the preparation is nothing, and carrying the next pair made VV's step 3 %
                // more instructions (cachegrind).
                if B == 1 {
                    for start in 0..n {
                        t = run.visit(t, start, run.prepare(start, prepare), visit);
                    }
                    return t;
                }
                if n == 0 {
                    return t;
                }
                // Each block is prepared one block ahead of its visits, so that the
                // preparation (independent of the visits) runs while the previous block's
                // chain of momentum updates does, instead of after it.
                let mut next = run.prepare(0, prepare);
                for start in (0..n).step_by(B) {
                    let current = next;
                    if start + B < n {
                        next = run.prepare(start + B, prepare);
                    }
                    t = run.visit(t, start, current, visit);
                }
                t
            },
        )
    })
}

/// One run of pairs being visited: its pairs, their normals and velocity shifts (if any), and
/// whether it is visited last to first.
#[derive(Clone, Copy)]
struct Run<'a> {
    pairs: &'a [Pair],
    z: Option<&'a [f64]>,
    dvx: Option<&'a [f64]>,
    reverse: bool,
}

impl Run<'_> {
    /// The position in the run of the pair at position `m` in visiting order.
    #[inline(always)]
    fn at(self, m: usize) -> usize {
        if self.reverse {
            self.pairs.len() - 1 - m
        } else {
            m
        }
    }

    /// What `prepare` makes of the `B` pairs from position `start` in visiting order. Past
    /// the end of the run the last pair is repeated.
    #[inline(always)]
    fn prepare<const B: usize, P: Copy>(
        self,
        start: usize,
        prepare: impl Fn([&Pair; B], [f64; B]) -> [P; B],
    ) -> [P; B] {
        let n = self.pairs.len();
        let k: [usize; B] = if start + B <= n {
            std::array::from_fn(|l| self.at(start + l))
        } else {
            std::array::from_fn(|l| self.at((start + l).min(n - 1)))
        };
        let zs = k.map(|k| self.z.map_or(0.0, |z| z[k]));
        prepare(k.map(|k| &self.pairs[k]), zs)
    }

    /// Add to `t` the visits, in order, of the pairs from position `start` in visiting order
    /// that `prepared` was made for ([`Run::prepare`]), up to the end of the run.
    #[inline(always)]
    fn visit<const B: usize, P: Copy, T: Virial>(
        self,
        mut t: T,
        start: usize,
        prepared: [P; B],
        visit: impl Fn(&Pair, P, f64) -> T,
    ) -> T {
        let len = B.min(self.pairs.len() - start);
        for (l, p) in prepared.into_iter().enumerate().take(len) {
            let k = self.at(start + l);
            let dvx = self.dvx.map_or(0.0, |s| s[k]);
            t = t.add(visit(&self.pairs[k], p, dvx));
        }
        t
    }
}

/// [`Noise`] with its ids checked against a table's bound, as [`visit_run`] draws from it.
#[derive(Clone, Copy)]
pub(crate) struct Drawn<'a> {
    noise: Noise<'a>,
    id: ByPair<'a, u32>,
}

impl<'a> Noise<'a> {
    /// This noise for the pairs of a table with index bound `bound`.
    pub(crate) fn of(self, bound: Bound) -> Drawn<'a> {
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

/// What a pairwise update records per pair and [`PairTable::visit_sum`] adds up: `()` (nothing,
/// at no cost) or the pair virial tensor `r_ij f e_ij (x) e_ij = q_ij (x) (f e_ij)` of a force
/// or impulse `f` along `e_ij`.
pub(crate) trait Virial: Send + Default {
    fn of(pair: &Pair, rc: f64, f: f64) -> Self;
    fn add(self, other: Self) -> Self;
}

impl Virial for () {
    #[inline(always)]
    fn of(_: &Pair, _: f64, _: f64) {}
    #[inline(always)]
    fn add(self, _: ()) {}
}

impl Virial for Tensor {
    #[inline(always)]
    fn of(pair: &Pair, rc: f64, f: f64) -> Self {
        (pair.r(rc) * f) * pair.e * pair.e.transpose()
    }
    #[inline(always)]
    fn add(self, other: Self) -> Self {
        self + other
    }
}

impl PairTable {
    /// The bound on the pairs' indices, for indexing per-particle arrays by them.
    pub(crate) fn bound(&self) -> Bound {
        Bound(self.particles)
    }

    /// [`Bound::read`] for this table.
    pub(crate) fn read<'a, T: Copy>(&self, data: &'a [T]) -> ByPair<'a, T> {
        self.bound().read(data)
    }

    /// [`Bound::write`] for this table.
    pub(crate) fn write<'a, T>(&self, data: &'a mut [T]) -> Disjoint<'a, T> {
        self.bound().write(data)
    }
}

/// A bound on the particle indices of a pair table: the particle count of its fill.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Bound(usize);

impl Bound {
    /// The bound of a table filled from positions `q` (its indices are below `q.len()`).
    pub(crate) fn of(q: &[Vec3]) -> Self {
        Bound(q.len())
    }

    /// `data`, one entry per particle, for reading by the pairs' indices without a bounds
    /// check per pair. Panics unless it has an entry for every index below the bound.
    pub(crate) fn read<T: Copy>(self, data: &[T]) -> ByPair<'_, T> {
        self.check(data.len());
        ByPair(data)
    }

    /// [`Disjoint`] over `data`, for writing by the pairs' indices without a bounds check per
    /// pair ([`Disjoint::get_paired`]). Panics unless it has an entry for every index below
    /// the bound.
    pub(crate) fn write<T>(self, data: &mut [T]) -> Disjoint<'_, T> {
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

/// A per-particle slice with an entry for every index of a pair table ([`Bound::read`]).
#[derive(Clone, Copy)]
pub(crate) struct ByPair<'a, T>(&'a [T]);

impl<T: Copy> ByPair<'_, T> {
    /// The entry of particle `i`, which must be an index of the table this was made for.
    #[inline(always)]
    pub(crate) fn get(self, i: u32) -> T {
        debug_assert!((i as usize) < self.0.len());
        // SAFETY: `i` is an index of the table, below its particle count (see
        // `PairTable::particles`), and the slice has that many entries (`Bound::read`).
        unsafe { *self.0.get_unchecked(i as usize) }
    }
}

/// A slice written concurrently at disjoint indices.
///
/// Safety contract of [`Disjoint::get`]: no two threads access the same index at the same
/// time. [`PairTable::visit`] guarantees it for the two particles of a pair, because
/// concurrently visited runs own pairs of disjoint particle sets.
pub(crate) struct Disjoint<'a, T> {
    ptr: *mut T,
    len: usize,
    _slice: PhantomData<&'a mut [T]>,
}

unsafe impl<T: Send> Sync for Disjoint<'_, T> {}

// A copy is one more handle to the same slice, as a shared reference to it would be; the
// contract of `get` is the same for every handle.
impl<T> Clone for Disjoint<'_, T> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<T> Copy for Disjoint<'_, T> {}

impl<'a, T> Disjoint<'a, T> {
    pub(crate) fn new(slice: &'a mut [T]) -> Self {
        Disjoint {
            ptr: slice.as_mut_ptr(),
            len: slice.len(),
            _slice: PhantomData,
        }
    }

    /// # Safety
    /// No other reference to element `i` may be alive while the returned one is.
    #[inline(always)]
    #[allow(clippy::mut_from_ref)]
    pub(crate) unsafe fn get(&self, i: usize) -> &mut T {
        assert!(i < self.len, "index {i} out of bounds ({})", self.len);
        // SAFETY: in bounds (checked above); exclusivity is the caller's contract.
        unsafe { &mut *self.ptr.add(i) }
    }

    /// [`Disjoint::get`] for `i` an index of the pair table this was made for
    /// ([`Bound::write`]), without the bounds check.
    ///
    /// # Safety
    /// As for [`Disjoint::get`]; and `self` must come from [`Bound::write`] with the bound of
    /// the table whose pair holds `i`.
    #[inline(always)]
    #[allow(clippy::mut_from_ref)]
    pub(crate) unsafe fn get_paired(&self, i: u32) -> &mut T {
        debug_assert!((i as usize) < self.len);
        // SAFETY: below the table's particle count, which `Bound::write` checked against the
        // length; exclusivity is the caller's contract.
        unsafe { &mut *self.ptr.add(i as usize) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The pairs (by `i`) that [`visit_run_prepared`] visits, in order, each with the value
    /// its preparation made for it.
    fn visited<const B: usize>(n: u32, order: SweepOrder) -> Vec<(u32, u32)> {
        let pairs: Vec<Pair> = (0..n)
            .map(|i| Pair {
                i,
                j: n + i,
                e: Vec3::x(),
                w: 0.5,
                wr: 0.5,
            })
            .collect();
        let seen = RefCell::new(Vec::new());
        let seen_ref = &seen;
        visit_run_prepared::<B, u32, ()>(
            &pairs,
            None,
            order,
            None,
            |block: [&Pair; B], _| block.map(|p| 10 * p.i),
            move |pair, prepared, _| seen_ref.borrow_mut().push((pair.i, prepared)),
        );
        seen.into_inner()
    }

    #[test]
    fn blocks_visit_each_pair_once_in_order_with_its_preparation() {
        for n in 0..10 {
            let forward: Vec<(u32, u32)> = (0..n).map(|i| (i, 10 * i)).collect();
            let reverse: Vec<(u32, u32)> = forward.iter().rev().copied().collect();
            assert_eq!(visited::<1>(n, SweepOrder::Forward), forward, "n = {n}");
            assert_eq!(visited::<4>(n, SweepOrder::Forward), forward, "n = {n}");
            assert_eq!(visited::<1>(n, SweepOrder::Reverse), reverse, "n = {n}");
            assert_eq!(visited::<4>(n, SweepOrder::Reverse), reverse, "n = {n}");
        }
    }
}
