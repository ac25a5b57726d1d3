//! The engine that visits the table's pairs in the sweep order, owning the aliasing of the
//! per-particle arrays the visits update and the checks of those they read.

use crate::avx2::with_avx2;
use crate::disjoint::Disjoint;
use crate::parallel::map_in_parallel;
use dpd_ir::SweepOrder;
use std::cell::RefCell;
use std::ops::Range;

use super::{
    on_all_threads, Drawn, Ends, Momenta, Noise, Pair, PairTable, Particles, Span, Virial,
};

thread_local! {
    /// The standard normals of the run a noisy visit is at, one buffer per thread.
    static NORMALS: RefCell<Vec<f64>> = const { RefCell::new(Vec::new()) };
}

/// The engine: every pair visit of the crate goes through the methods below, which hand each
/// call of the visiting closure one pair of the table as [`Ends`] (the pair with what its
/// update reads of its two particles, from the [`Particles`] the method was given) and its two
/// particles' entries of a per-particle array `out`: `(&mut out[i], &mut out[j])`, or a [`Two`]
/// that gives them where the closure writes (the sweeps; the full forces' loop took 1 % more
/// instructions when the references were made before the visit, the conservative forces' plain
/// loop 1.6 % more with a `Two`). The engine owns the aliasing and the bounds: the table's pairs
/// join distinct particles below its bound, `out` and the particles' arrays are checked once to
/// have an entry for each, and runs visited at the same time touch disjoint particles; so the
/// closures need no unsafe code to read or write and cannot write to any other particle.
impl PairTable {
    /// Call `visit(ends, out_i, out_j)` for every pair once, in the sweep order (`Forward`) or
    /// in exactly the reverse order (`Reverse`). Runs of one colour go to different threads
    /// when the grid is coloured and the table is large; they touch disjoint particles, so the
    /// result is the same as the sequential visit on any number of threads.
    pub(crate) fn for_each_pair<M: Momenta, W: Send>(
        &self,
        order: SweepOrder,
        particles: Particles<M>,
        out: &mut [W],
        visit: impl Fn(Ends<M>, &mut W, &mut W) + Sync + Copy,
    ) {
        let each = move |ends: Ends<M>, two: Two<W>, _, _| {
            let (wi, wj) = two.split();
            visit(ends, wi, wj)
        };
        self.sweep_noisy(order, None, particles, out, each)
    }

    /// [`PairTable::for_each_pair`] handing each pair also its standard normal of `noise` (0
    /// with `None`) and its velocity shift (0 without, see [`PairTable::shifts`]), and summing
    /// what `visit` returns: within a run in visiting order, then run by run, then colour by
    /// colour, so the sum is the same on any number of threads (with `T = ()` at no cost). The
    /// normals of a run are drawn just before it is visited, while its pairs are in cache
    /// ([`crate::rng::pair_normals`]); they are the numbers [`crate::rng::pair_normal`]
    /// gives.
    pub(crate) fn sweep_noisy<M: Momenta, T: Virial, W: Send>(
        &self,
        order: SweepOrder,
        noise: Option<Noise>,
        particles: Particles<M>,
        out: &mut [W],
        visit: impl Fn(Ends<M>, Two<W>, f64, f64) -> T + Sync + Copy,
    ) -> T {
        let shifts = self.shifts();
        let noise = noise.map(|noise| noise.of(self.bound()));
        particles.check(self.bound());
        let out = self.bound().write(out);
        self.fold_groups::<1, T>(order, |runs| {
            let (range, pairs) = runs[0].clone();
            let dvx = shifts.map(|s| &s[range][..pairs.len()]);
            // SAFETY: a run of this table, `particles` checked and `out` made for its bound,
            // and other threads only at runs of the same colour (`fold_groups`).
            [unsafe { sweep_run(pairs, particles, out, dvx, order, noise, visit) }]
        })
    }

    /// [`PairTable::sweep_noisy`] with a preparation: before a run is visited,
    /// `prepare(span, z, prepared)` pushes onto `prepared` one value per pair of the run's
    /// `span`, in table order, computed from the pairs, what they read of their particles and
    /// their normals `z` (all 0 without noise) alone; then `visit(ends, two, p, dvx)` gets each
    /// pair's value `p`, in `order`. `prepare` must not read what the visits change. The
    /// preparation runs as a loop of its own, so that it may be vectorised and does not compete
    /// with the visits' chain of momentum updates, and up to [`INTERLEAVED`] runs of a colour
    /// are visited alternately, pair by pair.
    pub(crate) fn sweep_prepared<M: Momenta, P: Copy, T: Virial, W: Send>(
        &self,
        order: SweepOrder,
        noise: Option<Noise>,
        particles: Particles<M>,
        out: &mut [W],
        prepare: impl Fn(Span<M>, &[f64], &mut Vec<P>) + Sync + Copy,
        visit: impl Fn(Ends<M>, Two<W>, P, f64) -> T + Sync + Copy,
    ) -> T {
        let shifts = self.shifts();
        let noise = noise.map(|noise| noise.of(self.bound()));
        particles.check(self.bound());
        let out = self.bound().write(out);
        self.fold_groups::<INTERLEAVED, T>(order, |runs| {
            // SAFETY: runs of this table that touch disjoint particles, `particles` checked and
            // `out` made for its bound, and other threads only at other runs of the same colour
            // (`fold_groups`).
            unsafe {
                sweep_group_prepared(runs, particles, out, shifts, order, noise, prepare, visit)
            }
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
                let sums = map_in_parallel(groups, &group);
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

/// A run of pairs just filled ([`PairTable::collect_then`]), with what its pairs read of their
/// particles, their noise and the entries of its particles in a per-particle array: made only
/// by the engine, for a run no other thread touches, with particles, noise and entries checked
/// against the fill's bound.
pub(crate) struct Run<'a, W, M> {
    pub(super) pairs: &'a [Pair],
    pub(super) particles: Particles<'a, M>,
    pub(super) noise: Option<Drawn<'a>>,
    pub(super) out: Disjoint<'a, W>,
}

impl<W, M: Momenta> Run<'_, W, M> {
    /// `visit(ends, out_i, out_j)` for each pair in table order, in a plain loop.
    #[inline(always)]
    pub(crate) fn for_each(self, visit: impl Fn(Ends<M>, &mut W, &mut W)) {
        for pair in self.pairs {
            // SAFETY (both): a run of the engine (see `Run`).
            let (wi, wj) = unsafe { both(self.out, pair) }.split();
            visit(unsafe { Ends::new(pair, self.particles) }, wi, wj);
        }
    }

    /// The run visited as [`PairTable::sweep_noisy`] visits a run in the `Forward` order,
    /// without velocity shifts.
    #[inline(always)]
    pub(crate) fn sweep<T: Virial>(
        self,
        visit: impl Fn(Ends<M>, Two<W>, f64, f64) -> T + Copy,
    ) -> T {
        // SAFETY: a run of the engine (see `Run`).
        unsafe {
            sweep_run(
                self.pairs,
                self.particles,
                self.out,
                None,
                SweepOrder::Forward,
                self.noise,
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
///
/// The engine's functions below share this contract for every pair they visit, and for the
/// [`Particles`] they hand with them ([`Ends::new`]): checked against the same bound.
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
unsafe fn sweep_run<M: Copy, T: Virial, W>(
    pairs: &[Pair],
    particles: Particles<M>,
    out: Disjoint<W>,
    dvx: Option<&[f64]>,
    order: SweepOrder,
    noise: Option<Drawn>,
    visit: impl Fn(Ends<M>, Two<W>, f64, f64) -> T + Copy,
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
                unsafe { sweep_in_order(T::default(), pairs, particles, out, z, dvx, order, visit) }
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
unsafe fn sweep_group_prepared<const K: usize, M: Copy, P: Copy, T: Virial, W>(
    runs: &[(Range<usize>, &[Pair])],
    particles: Particles<M>,
    out: Disjoint<W>,
    shifts: Option<&[f64]>,
    order: SweepOrder,
    noise: Option<Drawn>,
    prepare: impl Fn(Span<M>, &[f64], &mut Vec<P>) + Copy,
    visit: impl Fn(Ends<M>, Two<W>, P, f64) -> T + Copy,
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
                    // SAFETY: the caller's contract.
                    prepare(unsafe { Span::new(pairs, particles) }, z, &mut prepared);
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
                    unsafe { alternate_runs(each, particles, out, order, visit, &mut sums) };
                } else {
                    for ((&(pairs, prepared), (range, _)), sum) in
                        each.iter().zip(runs).zip(&mut sums)
                    {
                        let dvx = shifts.map(|s| &s[range.clone()]);
                        let prepared = move |k: usize| prepared[k];
                        *sum = unsafe {
                            sweep_in_order(
                                T::default(),
                                pairs,
                                particles,
                                out,
                                prepared,
                                dvx,
                                order,
                                visit,
                            )
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
unsafe fn alternate_runs<const K: usize, M: Copy, P: Copy, T: Virial, W>(
    runs: &[(&[Pair], &[P])],
    particles: Particles<M>,
    out: Disjoint<W>,
    order: SweepOrder,
    visit: impl Fn(Ends<M>, Two<W>, P, f64) -> T + Copy,
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
            // SAFETY (both): the caller's contract.
            let (ends, two) = unsafe { (Ends::new(pair, particles), both(out, pair)) };
            *sum = std::mem::take(sum).add(visit(ends, two, values[k], 0.0));
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
        *sum = unsafe {
            let sum = std::mem::take(sum);
            sweep_in_order(sum, pairs, particles, out, values, None, order, visit)
        };
    }
}

/// Add to `sum` `visit(ends, two, q(k), dvx)` over the pairs of a run in `order`, `k`
/// the pair's position in the run and `dvx` its velocity shift (0 with `None`). `visit` is
/// called from one place, so that the compiler inlines it into the loop (from four loops, one
/// for each order and shift, it made `visit` a function called per pair: VV's step took 5 %
/// more instructions).
///
/// # Safety
/// As for [`both`], for every pair of `pairs`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
unsafe fn sweep_in_order<M: Copy, Q, T: Virial, W>(
    mut sum: T,
    pairs: &[Pair],
    particles: Particles<M>,
    out: Disjoint<W>,
    q: impl Fn(usize) -> Q + Copy,
    dvx: Option<&[f64]>,
    order: SweepOrder,
    visit: impl Fn(Ends<M>, Two<W>, Q, f64) -> T + Copy,
) -> T {
    let (n, reverse) = (pairs.len(), order == SweepOrder::Reverse);
    let dvx = dvx.map(|dvx| &dvx[..n]);
    for m in 0..n {
        let k = if reverse { n - 1 - m } else { m };
        let shift = dvx.map_or(0.0, |dvx| dvx[k]);
        let pair = &pairs[k];
        // SAFETY (both): the caller's contract.
        let (ends, two) = unsafe { (Ends::new(pair, particles), both(out, pair)) };
        sum = sum.add(visit(ends, two, q(k), shift));
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Tensor, Vec3};

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
        // Each visit counts itself at its two particles, whose inverse masses are their
        // indices.
        let mut visits = vec![0u32; 100 * lengths.len()];
        let inv_mass: Vec<f64> = (0..visits.len()).map(|i| i as f64).collect();
        let kind = vec![0; visits.len()];
        let params = crate::Params::builder().build().unwrap();
        let particles = Particles::new(&inv_mass, &kind, params.coefficients());
        let out = Disjoint::new(&mut visits);
        // SAFETY: the runs join distinct particles below `100 * runs`, disjoint between runs,
        // and one thread visits them.
        let sums = unsafe {
            sweep_group_prepared::<K, (), u32, Tensor, u32>(
                &runs,
                particles,
                out,
                shifted.then_some(&shifts),
                order,
                None,
                |run: Span, z: &[f64], out: &mut Vec<u32>| {
                    assert_eq!(z, vec![0.0; run.iter().count()], "no noise: normals 0");
                    out.extend(run.iter().map(|ends| 10 * ends.pair().i))
                },
                move |ends: Ends, two: Two<u32>, prepared, dvx| {
                    let pair = ends.pair();
                    let (mi, mj) = ends.inv_masses();
                    assert_eq!((mi, mj), (f64::from(pair.i), f64::from(pair.j)));
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
