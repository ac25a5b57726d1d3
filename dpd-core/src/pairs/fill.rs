//! Filling the table from the neighbour list or its grid's scan.

use crate::boundary::{LeesEdwards, PeriodicBox};
use crate::chunked;
use crate::neighbour::{Hits, VerletList};
use crate::params::Params;
use crate::walls::FrozenWalls;
use crate::Vec3;

use super::{
    on_all_threads, All, Bound, Excluding, Keep, Momenta, Noise, Pair, PairTable, Particles, Run,
};

impl PairTable {
    /// Refill with the pairs of `list` that interact at positions `q`, keeping its order: from
    /// the list's candidates, or with skin 0 straight from the scan of its grid (then `q` must
    /// be in the cell order of its last build, as a [`crate::System`] keeps it).
    ///
    /// A pair interacts within the cut-off of its types (`kind`, one per particle, read only
    /// when the cut-offs differ).
    ///
    /// Coincident particles (`r = 0`) have no defined direction; such a pair is left out, so it
    /// exerts no force rather than a NaN one; so is a pair `excluding` names.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn collect(
        &mut self,
        list: &VerletList,
        q: &[Vec3],
        bx: &PeriodicBox,
        shear: Option<&LeesEdwards>,
        walls: Option<&FrozenWalls>,
        params: &Params,
        kind: &[u16],
        excluding: Option<Excluding>,
    ) {
        let cell = (list, q, bx, shear, walls, params, kind);
        match excluding {
            None => self.collect_keeping(cell, All),
            Some(x) => self.collect_keeping(cell, x),
        }
    }

    /// [`PairTable::collect`] keeping the in-range pairs `keep` keeps.
    #[allow(clippy::type_complexity)]
    fn collect_keeping(
        &mut self,
        (list, q, bx, shear, walls, params, kind): (
            &VerletList,
            &[Vec3],
            &PeriodicBox,
            Option<&LeesEdwards>,
            Option<&FrozenWalls>,
            &Params,
            &[u16],
        ),
        keep: impl Keep,
    ) {
        match (shear, walls) {
            (None, None) => self.fill_plainly(list, q, bx, params, kind, keep, |_: &[Pair]| {}),
            // The scan's separation is the image, but the velocity shift needs the crossing
            // count: both come from the positions.
            (Some(le), _) => {
                let fill = self.start_fill(list, q, bx, shear, (params, kind), true);
                // `image` and the scan's closure are inlined by force: left to the optimiser,
                // they became a call per hit that cost 4.5 % of a sheared step.
                #[inline(always)]
                fn image(
                    le: &LeesEdwards,
                    bx: &PeriodicBox,
                    q: &[Vec3],
                    i: u32,
                    j: u32,
                ) -> (Vec3, f64) {
                    le.min_image(bx, q[i as usize] - q[j as usize])
                }
                let from_positions = |i, j, _| Some(image(le, bx, q, i, j).0);
                let scanned = Some(
                    #[inline(always)]
                    |i, j, _| Some(image(le, bx, q, i, j).0),
                );
                fill.into(self, from_positions, scanned, keep, |_: &[Pair]| {});
                let shifts = self.pairs.iter().map(|p| image(le, bx, q, p.i, p.j).1);
                self.shifts.extend(shifts);
            }
            (None, Some(w)) => {
                let fill = self.start_fill(list, q, bx, None, (params, kind), true);
                let mobile = |i: u32, j: u32, d: Vec3| {
                    (!(w.frozen[i as usize] && w.frozen[j as usize])).then_some(d)
                };
                let image = |i, j, d| mobile(i, j, bx.min_image(d));
                fill.into(self, image, Some(mobile), keep, |_: &[Pair]| {});
                let v = &w.velocity_x;
                let shifts = self.pairs.iter().map(|p| v[p.i as usize] - v[p.j as usize]);
                self.shifts.extend(shifts);
            }
        }
    }

    /// [`PairTable::collect`] in a periodic box without walls, calling `after(run)` for every
    /// run of the new table as soon as it is filled, while its pairs are in cache: on the
    /// thread that filled it, colour by colour, so that `after` may read what the run's pairs
    /// read of `particles`, draw their normals of `noise` and update their particles' entries
    /// in `out` (one per particle) as [`PairTable::sweep_noisy`] would, in the same order.
    /// Pairs `excluding` names are left out, as [`PairTable::collect`] leaves them.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn collect_then<M: Momenta, W: Send>(
        &mut self,
        list: &VerletList,
        q: &[Vec3],
        bx: &PeriodicBox,
        params: &Params,
        excluding: Option<Excluding>,
        noise: Option<Noise>,
        particles: Particles<M>,
        out: &mut [W],
        after: impl Fn(Run<W, M>) + Sync,
    ) {
        let bound = Bound::of(q);
        let kind = particles.kinds();
        let noise = noise.map(|noise| noise.of(bound));
        particles.check(bound);
        let out = bound.write(out);
        // A fill hands `after` its runs as they are filled: pairs of distinct particles below
        // `q.len()`, and runs on different threads at the same time only from one colour,
        // whose runs touch disjoint particles; the noise's ids, `particles` and `out` have an
        // entry for each.
        let run = move |pairs: &[Pair]| {
            after(Run {
                pairs,
                particles,
                noise,
                out,
            })
        };
        match excluding {
            None => self.fill_plainly(list, q, bx, params, kind, All, run),
            Some(x) => self.fill_plainly(list, q, bx, params, kind, x, run),
        }
    }

    /// Refill in a periodic box without walls, calling `after` with the pairs of every run once
    /// it is filled ([`Fill::into`]), keeping the in-range pairs `keep` keeps; the
    /// table's indices are below `Bound::of(q)`.
    #[allow(clippy::too_many_arguments)]
    fn fill_plainly(
        &mut self,
        list: &VerletList,
        q: &[Vec3],
        bx: &PeriodicBox,
        params: &Params,
        kind: &[u16],
        keep: impl Keep,
        after: impl Fn(&[Pair]) + Sync,
    ) {
        let fill = self.start_fill(list, q, bx, None, (params, kind), false);
        // Two positions in the box are less than a box length apart on every axis, where one
        // shift per axis is the minimum image to the bit; the general path cost about 50
        // instructions a candidate pair (a melt with skin 0.3: 16 M of a step's 86 M).
        let image = |_, _, d| Some(bx.near_image(d));
        fill.into(self, image, None::<Separation>, keep, after);
    }

    /// Reset the table for a fill at positions `q` of particles of types `kind`, which records
    /// velocity shifts if `shifted`, and what the fill reads.
    fn start_fill<'a>(
        &mut self,
        list: &'a VerletList,
        q: &'a [Vec3],
        bx: &'a PeriodicBox,
        shear: Option<&'a LeesEdwards>,
        (params, kind): (&'a Params, &'a [u16]),
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
            kind,
        }
    }
}

/// The separation of pair `(i, j)` to use, given the one a scan found, or `None` when the pair
/// does not interact.
type Separation = fn(u32, u32, Vec3) -> Option<Vec3>;

/// What [`PairTable::collect`] fills from.
#[derive(Clone, Copy)]
struct Fill<'a> {
    list: &'a VerletList,
    q: &'a [Vec3],
    bx: &'a PeriodicBox,
    shear: Option<&'a LeesEdwards>,
    params: &'a Params,
    /// The particles' types, read for each pair when the cut-offs differ.
    kind: &'a [u16],
}

impl Fill<'_> {
    /// Fill `table`: from the candidates with `image(i, j, q_i - q_j)` giving the minimum
    /// image, or `None` for a pair that does not interact (two frozen particles); without skin
    /// from the grid's scan, with `scanned(i, j, d)` doing the same for the scan's
    /// minimum-image separation `d`, or with the scan's hits as they are when `scanned` is
    /// `None`. Of the pairs within the cut-off, those `keep` keeps are kept. `after(run)` is
    /// called with every run once it is filled, colour by colour, the runs of one colour on the
    /// threads that filled them.
    #[inline(always)]
    fn into(
        self,
        table: &mut PairTable,
        image: impl Fn(u32, u32, Vec3) -> Option<Vec3> + Sync,
        scanned: Option<impl Fn(u32, u32, Vec3) -> Option<Vec3> + Sync>,
        keep: impl Keep,
        after: impl Fn(&[Pair]) + Sync,
    ) {
        if self.params.cutoff_by_type() {
            let (params, kind) = (self.params, self.kind);
            let pair = move |i: u32, j: u32, d: Vec3| -> Option<Pair> {
                let r2 = d.norm_squared();
                let rc = params.rc_of(kind[i as usize], kind[j as usize]);
                (r2 < rc * rc && r2 > 0.0).then(|| {
                    let r = r2.sqrt();
                    let w = 1.0 - r * (1.0 / rc);
                    let (e, wr) = (d * (1.0 / r), params.w_r(w));
                    Pair { i, j, e, w, wr }
                })
            };
            return self.each(table, image, scanned, pair, keep, after);
        }
        let Fill {
            list,
            q,
            bx,
            shear,
            params,
            ..
        } = self;
        let rc = params.rc();
        // Captured by value (`move`), as every closure below: behind references the pair loops
        // loaded these again for every hit (the pushes store through pointers the compiler
        // cannot tell apart from them).
        let (rc2, inv_rc, w_r) = (rc * rc, 1.0 / rc, params.random_weight());
        // The pair of `(i, j)` at separation `d`, `r2 = |d|^2`, `r = sqrt(r2)`, `inv = 1 / r`.
        let geometry = move |i: u32, j: u32, d: Vec3, r: f64, inv: f64| {
            let w = 1.0 - r * inv_rc;
            Pair {
                i,
                j,
                e: d * inv,
                w,
                wr: w_r(w),
            }
        };
        let pair = move |i: u32, j: u32, d: Vec3| -> Option<Pair> {
            let r2 = d.norm_squared();
            (r2 < rc2 && r2 > 0.0).then(|| {
                let r = r2.sqrt();
                geometry(i, j, d, r, 1.0 / r)
            })
        };
        // Without skin and with the scan's hits as they are, the pairs reuse the distances the
        // scan computed; every other fill goes pair by pair.
        if list.skin() == 0.0 && scanned.is_none() {
            table.groups = list.grid().sweep(
                q,
                bx,
                shear,
                rc,
                &mut table.pairs,
                #[inline(always)]
                move |h, out| {
                    out.reserve(h.len());
                    let kept = keep.with(h.a());
                    // Over a slice of `r2`, so that `k` is known to be in bounds of every array.
                    for (k, &r2) in h.r2[..h.len()].iter().enumerate() {
                        // The scan's hits are closer than `rc` (the same test of the same
                        // `r2`): only coincident particles are left out here.
                        if r2 > 0.0 {
                            let (j, d) = h.get(k);
                            if kept(j) {
                                out.push(geometry(h.a(), j, d, h.r[k], h.inv_r[k]));
                            }
                        }
                    }
                },
                after,
            );
            return;
        }
        self.each(table, image, scanned, pair, keep, after);
    }

    /// [`Fill::into`] with `pair(i, j, d)` making the pair at separation `d`, or `None` when it
    /// does not interact, for every candidate or hit, and the pairs `keep` keeps kept.
    #[inline(always)]
    fn each(
        self,
        table: &mut PairTable,
        image: impl Fn(u32, u32, Vec3) -> Option<Vec3> + Sync,
        scanned: Option<impl Fn(u32, u32, Vec3) -> Option<Vec3> + Sync>,
        pair: impl Fn(u32, u32, Vec3) -> Option<Pair> + Sync,
        keep: impl Keep,
        after: impl Fn(&[Pair]) + Sync,
    ) {
        let Fill {
            list,
            q,
            bx,
            shear,
            params,
            ..
        } = self;
        let rc = params.rc();
        if list.skin() == 0.0 {
            let grid = list.grid();
            table.groups = match &scanned {
                Some(scanned) => {
                    let emit = |h: &Hits, out: &mut Vec<Pair>| emit(scanned, &pair, keep, h, out);
                    grid.sweep(q, bx, shear, rc, &mut table.pairs, emit, after)
                }
                None => {
                    let emit = |h: &Hits, out: &mut Vec<Pair>| {
                        emit(&|_, _, d| Some(d), &pair, keep, h, out)
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
                    let made = image(i, j, d).and_then(|g| pair(i, j, g));
                    out.extend(made.filter(|_| keep.keeps(i, j)));
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

/// Push onto `out` the pairs of the scan's hits `h`: for each, `pair` at the separation
/// `seen(i, j, d)` gives for the scan's minimum-image separation `d`, if both give one and
/// `keep` keeps the pair.
#[inline(always)]
fn emit(
    seen: &impl Fn(u32, u32, Vec3) -> Option<Vec3>,
    pair: &impl Fn(u32, u32, Vec3) -> Option<Pair>,
    keep: impl Keep,
    h: &Hits,
    out: &mut Vec<Pair>,
) {
    let kept = keep.with(h.a());
    for k in 0..h.len() {
        let (j, d) = h.get(k);
        let made = seen(h.a(), j, d).and_then(|g| pair(h.a(), j, g));
        out.extend(made.filter(|_| kept(j)))
    }
}
