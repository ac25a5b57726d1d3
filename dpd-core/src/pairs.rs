//! The interacting pairs of the current positions, with the geometry every sub-flow needs,
//! and the executor that visits them in the sweep order of [`crate::neighbour`].

use crate::avx2::with_avx2;
use crate::boundary::{LeesEdwards, PeriodicBox};
use crate::chunked::{self, Parts};
use crate::disjoint::Disjoint;
use crate::neighbour::{Hits, Runs, VerletList};
use crate::params::Params;
use crate::rng::pair_normals;
use crate::walls::FrozenWalls;
use crate::{Tensor, Vec3};
use dpd_ir::SweepOrder;
use rayon::prelude::*;
use std::cell::RefCell;
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
            (None, None) => {
                let nothing = &mut vec![(); q.len()];
                self.collect_then(list, q, bx, params, nothing, |_: Run<()>| {})
            }
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
    /// the run's pairs in `out` (one entry per particle) as [`PairTable::for_each_pair`] would,
    /// in the same order. The table's indices are below `Bound::of(q)`.
    pub(crate) fn collect_then<W: Send>(
        &mut self,
        list: &VerletList,
        q: &[Vec3],
        bx: &PeriodicBox,
        params: &Params,
        out: &mut [W],
        after: impl Fn(Run<W>) + Sync,
    ) {
        let out = Bound::of(q).write(out);
        let fill = self.start_fill(list, q, bx, None, params, false);
        let image = |_, _, d| Some(bx.min_image(d));
        // A fill hands `after` its runs as they are filled: pairs of distinct particles below
        // `q.len()`, and runs on different threads at the same time only from one colour,
        // whose runs touch disjoint particles; `out` has an entry for each (`Bound::write`).
        let run = move |pairs: &[Pair]| after(Run { pairs, out });
        fill.into(self, image, None::<Separation>, run);
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

/// The engine: every pair visit of the crate goes through the methods below, which hand each
/// call of the visiting closure one pair of the table with its two particles' entries of a
/// per-particle array `out`: `(&mut out[i], &mut out[j])`, or a [`Two`] that gives them where
/// the closure writes (the sweeps; the full forces' loop took 1 % more instructions when the
/// references were made before the visit, the conservative forces' plain loop 1.6 % more
/// with a `Two`). The engine owns the aliasing: the table's pairs join distinct particles
/// below its bound, `out` is checked once to have an entry for each, and runs visited at the
/// same time touch disjoint particles; so the closures need no unsafe code to write and cannot
/// write to any other particle.
impl PairTable {
    /// Call `visit(pair, out_i, out_j)` for every pair once, in the sweep order (`Forward`) or
    /// in exactly the reverse order (`Reverse`). Runs of one colour go to different threads
    /// when the grid is coloured and the table is large; they touch disjoint particles, so the
    /// result is the same as the sequential visit on any number of threads.
    pub(crate) fn for_each_pair<W: Send>(
        &self,
        order: SweepOrder,
        out: &mut [W],
        visit: impl Fn(&Pair, &mut W, &mut W) + Sync + Copy,
    ) {
        let each = move |p: &Pair, two: Two<W>, _, _| {
            let (wi, wj) = two.split();
            visit(p, wi, wj)
        };
        self.sweep_noisy(order, None, out, each)
    }

    /// [`PairTable::for_each_pair`] handing each pair also its standard normal of `noise` (0
    /// with `None`) and its velocity shift (0 without, see [`PairTable::shifts`]), and summing
    /// what `visit` returns: within a run in visiting order, then run by run, then colour by
    /// colour, so the sum is the same on any number of threads (with `T = ()` at no cost). The
    /// normals of a run are drawn just before it is visited, while its pairs are in cache
    /// ([`crate::rng::pair_normals`]); they are the numbers [`crate::rng::pair_normal`]
    /// gives.
    pub(crate) fn sweep_noisy<T: Virial, W: Send>(
        &self,
        order: SweepOrder,
        noise: Option<Noise>,
        out: &mut [W],
        visit: impl Fn(&Pair, Two<W>, f64, f64) -> T + Sync + Copy,
    ) -> T {
        let shifts = self.shifts();
        let noise = noise.map(|noise| noise.of(self.bound()));
        let out = self.bound().write(out);
        self.fold_groups::<1, T>(order, |runs| {
            let (range, pairs) = runs[0].clone();
            let dvx = shifts.map(|s| &s[range][..pairs.len()]);
            // SAFETY: a run of this table, `out` made for its bound, and other threads only at
            // runs of the same colour (`fold_groups`).
            [unsafe { sweep_run(pairs, out, dvx, order, noise, visit) }]
        })
    }

    /// [`PairTable::sweep_noisy`] with a preparation: before a run is visited,
    /// `prepare(pairs, z, prepared)` pushes onto `prepared` one value per pair of the run, in
    /// table order, computed from the pairs and their normals `z` (all 0 without noise) alone;
    /// then `visit(pair, out_i, out_j, p, dvx)` gets each pair's value `p`, in `order`.
    /// `prepare` must not read what the visits change. The preparation runs as a loop of its
    /// own, so that it may be vectorised and does not compete with the visits' chain of
    /// momentum updates, and up to [`INTERLEAVED`] runs of a colour are visited alternately,
    /// pair by pair.
    pub(crate) fn sweep_prepared<P: Copy, T: Virial, W: Send>(
        &self,
        order: SweepOrder,
        noise: Option<Noise>,
        out: &mut [W],
        prepare: impl Fn(&[Pair], &[f64], &mut Vec<P>) + Sync + Copy,
        visit: impl Fn(&Pair, Two<W>, P, f64) -> T + Sync + Copy,
    ) -> T {
        let shifts = self.shifts();
        let noise = noise.map(|noise| noise.of(self.bound()));
        let out = self.bound().write(out);
        self.fold_groups::<INTERLEAVED, T>(order, |runs| {
            // SAFETY: runs of this table that touch disjoint particles, `out` made for its
            // bound, and other threads only at other runs of the same colour (`fold_groups`).
            unsafe { sweep_group_prepared(runs, out, shifts, order, noise, prepare, visit) }
        })
    }

    /// Fold every run of the table: `group(runs)` visits up to `K` runs of one colour that
    /// touch disjoint particles, consecutive in visiting order (each as the items `range` of
    /// the table and its pairs), each in `order`, and returns each run's result. The results
    /// are summed run by run, then colour by colour, in `order`: the same sum for any grouping
    /// and on any number of threads. Runs of a colour that are not independent go one by one.
    fn fold_groups<const K: usize, T: Virial>(
        &self,
        order: SweepOrder,
        group: impl Fn(&[(Range<usize>, &[Pair])]) -> [T; K] + Sync,
    ) -> T {
        let g = &self.groups;
        let run = |k: usize| {
            let range = g.runs[k] as usize..g.runs[k + 1] as usize;
            (range.clone(), self.pairs.slice(range))
        };
        let add =
            |total: T, (sums, n): ([T; K], usize)| sums.into_iter().take(n).fold(total, T::add);
        let parallel = g.independent > 0 && on_all_threads(self.pairs.len());
        let colours = g.colours.len().saturating_sub(1);
        let colour = |c: usize| -> T {
            let (first, n) = (
                g.colours[c] as usize,
                (g.colours[c + 1] - g.colours[c]) as usize,
            );
            // The run at position `m` of the colour in visiting order.
            let at = |m: usize| match order {
                SweepOrder::Forward => first + m,
                SweepOrder::Reverse => first + n - 1 - m,
            };
            let independent = c < g.independent;
            let threads = match parallel && independent {
                true => rayon::current_num_threads(),
                false => 1,
            };
            // As few groups of at most `K` runs as the threads can share evenly, of sizes
            // that differ by at most one, so that each thread gets as many runs.
            let groups = match independent {
                true => n.div_ceil(K).next_multiple_of(threads).min(n),
                false => n,
            };
            // Each result of group `k` with the number of runs it had.
            let group = |k: usize| {
                let positions = k * n / groups..(k + 1) * n / groups;
                let mut runs: [_; K] = std::array::from_fn(|_| (0..0, &[][..]));
                for (slot, m) in runs.iter_mut().zip(positions.clone()) {
                    *slot = run(at(m));
                }
                (group(&runs[..positions.len()]), positions.len())
            };
            if threads > 1 {
                let sums: Vec<_> = (0..groups).into_par_iter().map(group).collect();
                sums.into_iter().fold(T::default(), add)
            } else {
                (0..groups).map(group).fold(T::default(), add)
            }
        };
        match order {
            SweepOrder::Forward => (0..colours).map(colour).fold(T::default(), T::add),
            SweepOrder::Reverse => (0..colours).rev().map(colour).fold(T::default(), T::add),
        }
    }
}

/// Runs a prepared sweep visits together ([`PairTable::sweep_prepared`]). Runs of one
/// colour touch disjoint particles, so their visits may alternate, pair by pair, with the
/// results of one run after the other. Each run's visits are a chain of momentum updates
/// (consecutive pairs mostly share a particle) that leaves the CPU idle for much of each
/// visit; the CPU overlaps the chains of runs that alternate. ABOBA's O sweep at N = 24 000
/// (one thread): 2 alternating runs 1.66 ms, 3 runs 1.60 ms, 4 runs 1.50 ms (medians of 12).
const INTERLEAVED: usize = 4;

/// A run of pairs just filled ([`PairTable::collect_then`]), with the entries of its particles
/// in a per-particle array: made only by the engine, for a run no other thread touches.
pub(crate) struct Run<'a, W> {
    pairs: &'a [Pair],
    out: Disjoint<'a, W>,
}

impl<W> Run<'_, W> {
    /// `visit(pair, out_i, out_j)` for each pair in table order, in a plain loop.
    #[inline(always)]
    pub(crate) fn for_each(self, visit: impl Fn(&Pair, &mut W, &mut W)) {
        for pair in self.pairs {
            // SAFETY: a run of the engine (see `Run`).
            let (wi, wj) = unsafe { both(self.out, pair) }.split();
            visit(pair, wi, wj);
        }
    }

    /// The run visited as [`PairTable::sweep_noisy`] visits a run in the `Forward` order,
    /// without velocity shifts, with the normals of `noise`.
    #[inline(always)]
    pub(crate) fn sweep<T: Virial>(
        self,
        noise: Option<Drawn>,
        visit: impl Fn(&Pair, Two<W>, f64, f64) -> T + Copy,
    ) -> T {
        // SAFETY: a run of the engine (see `Run`).
        unsafe {
            sweep_run(
                self.pairs,
                self.out,
                None,
                SweepOrder::Forward,
                noise,
                visit,
            )
        }
    }
}

/// The entries `(out[i], out[j])` of the two particles of one pair, handed to a visit by the
/// engine, which alone makes them ([`both`]); [`Two::split`] turns them into references where
/// the visit writes.
pub(crate) struct Two<'a, W> {
    out: Disjoint<'a, W>,
    i: u32,
    j: u32,
}

impl<'a, W> Two<'a, W> {
    /// `(&mut out[i], &mut out[j])`.
    #[inline(always)]
    pub(crate) fn split(self) -> (&'a mut W, &'a mut W) {
        // SAFETY: made by `both`, whose caller guaranteed the pair's indices below the bound
        // of `out` and no other thread at them; `i != j` for every pair of a table (coincident
        // particles are left out), so the two references are to distinct entries.
        unsafe { (self.out.get_paired(self.i), self.out.get_paired(self.j)) }
    }
}

/// The entries of the two particles of `pair` in `out`.
///
/// # Safety
/// `pair` is a pair of the table (or fill) whose bound `out` was made with (`Bound::write`),
/// and no other thread is at a pair of `i` or `j` while the [`Two`] lives.
#[inline(always)]
unsafe fn both<'a, W>(out: Disjoint<'a, W>, pair: &Pair) -> Two<'a, W> {
    Two {
        out,
        i: pair.i,
        j: pair.j,
    }
}

/// Visit the pairs of one run in `order` as [`PairTable::sweep_noisy`] does, `dvx` their
/// velocity shifts (all 0 with `None`), and sum what `visit` returns in visiting order. Runs in
/// code compiled with AVX2 where the CPU has it.
///
/// # Safety
/// As for [`both`], for every pair of `pairs`.
#[inline(always)]
unsafe fn sweep_run<T: Virial, W>(
    pairs: &[Pair],
    out: Disjoint<W>,
    dvx: Option<&[f64]>,
    order: SweepOrder,
    noise: Option<Drawn>,
    visit: impl Fn(&Pair, Two<W>, f64, f64) -> T + Copy,
) -> T {
    NORMALS.with_borrow_mut(|normals| {
        // Everything the loop reads is moved in, so that the compiler sees that the updates
        // (stores through raw pointers) do not change it and keeps it in registers: behind
        // references it was loaded again for every pair.
        with_avx2(
            #[inline(always)]
            move || {
                let n = pairs.len();
                let z = noise.map(|noise| {
                    normals.resize(n, 0.0);
                    // SAFETY: the caller's contract.
                    unsafe { noise.draw(pairs, &mut normals[..n]) };
                    &normals[..n]
                });
                // One call of `visit`, so that the compiler inlines it.
                let z = move |k: usize| z.map_or(0.0, |z| z[k]);
                // SAFETY: the caller's contract.
                unsafe { sweep_in_order(T::default(), pairs, out, z, dvx, order, visit) }
            },
        )
    })
}

/// The runs of a group of [`PairTable::fold_groups`] visited with the preparation of
/// [`PairTable::sweep_prepared`], `shifts` the table's velocity shifts if it has them:
/// each run's result. Runs of a group of more than one without shifts alternate.
///
/// # Safety
/// As for [`both`], for every pair of the runs; and the runs touch disjoint particles.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
unsafe fn sweep_group_prepared<const K: usize, P: Copy, T: Virial, W>(
    runs: &[(Range<usize>, &[Pair])],
    out: Disjoint<W>,
    shifts: Option<&[f64]>,
    order: SweepOrder,
    noise: Option<Drawn>,
    prepare: impl Fn(&[Pair], &[f64], &mut Vec<P>) + Copy,
    visit: impl Fn(&Pair, Two<W>, P, f64) -> T + Copy,
) -> [T; K] {
    NORMALS.with_borrow_mut(|normals| {
        with_avx2(
            #[inline(always)]
            move || {
                assert!(runs.len() <= K, "at most {K} runs in a group");
                // The normals and then the prepared values of every run, one after the other.
                let total = runs.iter().map(|(_, pairs)| pairs.len()).sum();
                if noise.is_none() {
                    normals.clear();
                }
                normals.resize(total, 0.0);
                let mut prepared = Vec::with_capacity(total);
                let mut start = 0;
                for (_, pairs) in runs {
                    let z = &mut normals[start..start + pairs.len()];
                    if let Some(noise) = noise {
                        // SAFETY: the caller's contract.
                        unsafe { noise.draw(pairs, z) };
                    }
                    prepare(pairs, z, &mut prepared);
                    assert_eq!(prepared.len(), start + pairs.len(), "one value per pair");
                    start += pairs.len();
                }
                // Each run's pairs with its prepared values.
                let mut each: [(&[Pair], &[P]); K] = [(&[], &[]); K];
                let mut rest = prepared.as_slice();
                for (run, &(_, pairs)) in each.iter_mut().zip(runs) {
                    let (mine, others) = rest.split_at(pairs.len());
                    (*run, rest) = ((pairs, mine), others);
                }
                let each = &each[..runs.len()];
                let mut sums = std::array::from_fn(|_| T::default());
                // SAFETY (both calls): the caller's contract.
                if runs.len() > 1 && shifts.is_none() {
                    unsafe { alternate_runs(each, out, order, visit, &mut sums) };
                } else {
                    for ((&(pairs, prepared), (range, _)), sum) in
                        each.iter().zip(runs).zip(&mut sums)
                    {
                        let dvx = shifts.map(|s| &s[range.clone()]);
                        let prepared = move |k: usize| prepared[k];
                        *sum = unsafe {
                            sweep_in_order(T::default(), pairs, out, prepared, dvx, order, visit)
                        };
                    }
                }
                sums
            },
        )
    })
}

/// Add to `sums[k]` the visits of the pairs of run `runs[k]` (its pairs and the value of each),
/// in `order`, the runs taking turns until the shortest ends, then the rest of each run after
/// the other. At most `K` runs.
///
/// # Safety
/// As for [`sweep_group_prepared`].
#[inline(always)]
unsafe fn alternate_runs<const K: usize, P: Copy, T: Virial, W>(
    runs: &[(&[Pair], &[P])],
    out: Disjoint<W>,
    order: SweepOrder,
    visit: impl Fn(&Pair, Two<W>, P, f64) -> T + Copy,
    sums: &mut [T; K],
) {
    let common = runs.iter().map(|(pairs, _)| pairs.len()).min().unwrap_or(0);
    let reverse = order == SweepOrder::Reverse;
    // The first `common` pairs of each run in visiting order.
    let mut firsts: [(&[Pair], &[P]); K] = [(&[], &[]); K];
    for (first, &(pairs, values)) in firsts.iter_mut().zip(runs) {
        let start = if reverse { pairs.len() - common } else { 0 };
        *first = (
            &pairs[start..start + common],
            &values[start..start + common],
        );
    }
    let firsts = &firsts[..runs.len()];
    for m in 0..common {
        let k = if reverse { common - 1 - m } else { m };
        for ((pairs, values), sum) in firsts.iter().zip(sums.iter_mut()) {
            let pair = &pairs[k];
            // SAFETY: the caller's contract.
            let two = unsafe { both(out, pair) };
            *sum = std::mem::take(sum).add(visit(pair, two, values[k], 0.0));
        }
    }
    for (&(pairs, values), sum) in runs.iter().zip(sums) {
        let rest = if reverse {
            0..pairs.len() - common
        } else {
            common..pairs.len()
        };
        let (pairs, values) = (&pairs[rest.clone()], &values[rest]);
        let values = move |k: usize| values[k];
        // SAFETY: the caller's contract.
        *sum =
            unsafe { sweep_in_order(std::mem::take(sum), pairs, out, values, None, order, visit) };
    }
}

/// Add to `sum` `visit(pair, out_i, out_j, q(k), dvx)` over the pairs of a run in `order`, `k`
/// the pair's position in the run and `dvx` its velocity shift (0 with `None`). `visit` is
/// called from one place, so that the compiler inlines it into the loop (from four loops, one
/// for each order and shift, it made `visit` a function called per pair: VV's step took 5 %
/// more instructions).
///
/// # Safety
/// As for [`both`], for every pair of `pairs`.
#[inline(always)]
unsafe fn sweep_in_order<Q, T: Virial, W>(
    mut sum: T,
    pairs: &[Pair],
    out: Disjoint<W>,
    q: impl Fn(usize) -> Q + Copy,
    dvx: Option<&[f64]>,
    order: SweepOrder,
    visit: impl Fn(&Pair, Two<W>, Q, f64) -> T + Copy,
) -> T {
    let (n, reverse) = (pairs.len(), order == SweepOrder::Reverse);
    let dvx = dvx.map(|dvx| &dvx[..n]);
    for m in 0..n {
        let k = if reverse { n - 1 - m } else { m };
        let shift = dvx.map_or(0.0, |dvx| dvx[k]);
        let pair = &pairs[k];
        // SAFETY: the caller's contract.
        let two = unsafe { both(out, pair) };
        sum = sum.add(visit(pair, two, q(k), shift));
    }
    sum
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
        let key = |k: usize| unsafe { (id.get(pairs[k].i), id.get(pairs[k].j)) };
        pair_normals(noise.seed, noise.step, noise.stream, key, z);
    }
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

/// What a pairwise update records per pair and [`PairTable::sweep_noisy`] adds up: `()` (nothing,
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

/// A per-particle slice with an entry for every index of a pair table ([`Bound::read`]).
#[derive(Clone, Copy)]
pub(crate) struct ByPair<'a, T>(&'a [T]);

impl<T: Copy> ByPair<'_, T> {
    /// The entry of particle `i`, without a bounds check (checked, these reads made VV's and
    /// ABOBA's steps 3 % more instructions).
    ///
    /// # Safety
    /// `i` is an index of a pair of the table (or fill) whose bound made this
    /// ([`Bound::read`]): such an index is below the bound, and the slice has an entry for each.
    #[inline(always)]
    pub(crate) unsafe fn get(self, i: u32) -> T {
        debug_assert!((i as usize) < self.0.len());
        // SAFETY: in bounds, the caller's contract.
        unsafe { *self.0.get_unchecked(i as usize) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What a run's visits saw: each pair (by `i`) in the order visited, with the value its
    /// preparation made for it and its shift; and the run's sum.
    type Seen = (Vec<(u32, u32, f64)>, Tensor);

    /// Runs of the given lengths on disjoint particles (run `r` has particles from `100 r`),
    /// visited as a group by [`sweep_group_prepared`] in `order`, with velocity shifts
    /// `i + 0.5` when `shifted`: per run, the pairs (by `i`) in the order visited, each with
    /// the value its preparation made for it and its shift, and the run's sum (of
    /// `0.1 i + dvx` in every entry of a tensor: float sums depend on their order).
    fn visited<const K: usize>(lengths: &[u32], order: SweepOrder, shifted: bool) -> Vec<Seen> {
        let pairs: Vec<Pair> = (0..lengths.len() as u32)
            .flat_map(|r| {
                (0..lengths[r as usize]).map(move |k| Pair {
                    i: 100 * r + k,
                    j: 100 * r + 50 + k,
                    e: Vec3::x(),
                    w: 0.5,
                    wr: 0.5,
                })
            })
            .collect();
        let shifts: Vec<f64> = pairs.iter().map(|p| f64::from(p.i) + 0.5).collect();
        let mut runs = Vec::new();
        let mut start = 0;
        for &n in lengths {
            let range = start..start + n as usize;
            runs.push((range.clone(), &pairs[range]));
            start += n as usize;
        }
        let seen = RefCell::new(vec![Vec::new(); lengths.len()]);
        let seen_ref = &seen;
        // Each visit counts itself at its two particles.
        let mut visits = vec![0u32; 100 * lengths.len()];
        let out = Disjoint::new(&mut visits);
        // SAFETY: the runs join distinct particles below `100 * runs`, disjoint between runs,
        // and one thread visits them.
        let sums = unsafe {
            sweep_group_prepared::<K, u32, Tensor, u32>(
                &runs,
                out,
                shifted.then_some(&shifts),
                order,
                None,
                |run: &[Pair], z: &[f64], out: &mut Vec<u32>| {
                    assert_eq!(z, vec![0.0; run.len()], "no noise: normals 0");
                    out.extend(run.iter().map(|p| 10 * p.i))
                },
                move |pair, two: Two<u32>, prepared, dvx| {
                    let (wi, wj) = two.split();
                    (*wi, *wj) = (*wi + 1, *wj + 1);
                    let run = (pair.i / 100) as usize;
                    seen_ref.borrow_mut()[run].push((pair.i, prepared, dvx));
                    Tensor::from_element(0.1 * f64::from(pair.i) + dvx)
                },
            )
        };
        for (r, &n) in lengths.iter().enumerate() {
            for k in 0..100 {
                let hit = k < n || (50..50 + n).contains(&k);
                assert_eq!(
                    visits[100 * r + k as usize],
                    u32::from(hit),
                    "particle {r} {k}"
                );
            }
        }
        seen.into_inner().into_iter().zip(sums).collect()
    }

    #[test]
    fn runs_visit_each_pair_once_in_order_with_its_preparation_and_shift() {
        let cases: [&[u32]; 8] = [
            &[0],
            &[5],
            &[0, 0],
            &[3, 7],
            &[9, 2],
            &[6, 6],
            &[4, 0, 8],
            &[5, 9, 7],
        ];
        for lengths in cases {
            for shifted in [false, true] {
                for order in [SweepOrder::Forward, SweepOrder::Reverse] {
                    let expected: Vec<Seen> = lengths
                        .iter()
                        .enumerate()
                        .map(|(r, &n)| {
                            let mut run: Vec<_> = (0..n)
                                .map(|k| 100 * r as u32 + k)
                                .map(|i| {
                                    (i, 10 * i, if shifted { f64::from(i) + 0.5 } else { 0.0 })
                                })
                                .collect();
                            if order == SweepOrder::Reverse {
                                run.reverse();
                            }
                            let sum = run.iter().fold(Tensor::zeros(), |t, &(i, _, dvx)| {
                                t + Tensor::from_element(0.1 * f64::from(i) + dvx)
                            });
                            (run, sum)
                        })
                        .collect();
                    let case = format!("{lengths:?} {order:?} shifted {shifted}");
                    // Alternating unless shifted or alone, also fewer runs than `K`.
                    assert_eq!(visited::<3>(lengths, order, shifted), expected, "{case}");
                }
            }
        }
    }
}
