//! Per-particle forces summed over the interacting pairs in sweep order.

use crate::boundary::PeriodicBox;
use crate::neighbour::VerletList;
use crate::pairs::{Bound, ByPair, Noise, Pair, PairTable, Run, Two, Virial};
use crate::params::Params;
use crate::params::Repulsion;
use crate::Vec3;
use dpd_ir::SweepOrder;

/// `out_i = F^C_i = sum_j a_ij (1 - r_ij/r_c) e_ij`.
/// `out` is resized to one entry per particle (it is allocated on first use, so a scheme that
/// never kicks with B holds no conservative-force array).
pub(crate) fn conservative(pairs: &PairTable, params: &Params, kind: &[u16], out: &mut Vec<Vec3>) {
    let add = Conservative::new(pairs.bound(), params, kind);
    let out = zeroed(out, kind.len());
    // SAFETY: the pairs of the table whose bound made `add`.
    let each = move |pair: &Pair, fi: &mut _, fj: &mut _| unsafe { add.pair(pair, fi, fj) };
    pairs.for_each_pair(SweepOrder::Forward, out, each);
}

/// `out` as `n` zero vectors.
pub(crate) fn zeroed(out: &mut Vec<Vec3>, n: usize) -> &mut [Vec3] {
    out.clear();
    out.resize(n, Vec3::zeros());
    out
}

/// The sum of the conservative forces into per-particle totals, pair by pair: what
/// [`conservative`] does over a table, and what a fill does run by run
/// ([`PairTable::collect_then`]), so that both give the same numbers.
#[derive(Clone, Copy)]
pub(crate) struct Conservative<'a> {
    kind: ByPair<'a, u16>,
    a: Repulsion<'a>,
}

impl<'a> Conservative<'a> {
    /// The forces of the pairs of a table with index bound `bound`.
    pub(crate) fn new(bound: Bound, params: &'a Params, kind: &'a [u16]) -> Self {
        Conservative {
            kind: bound.read(kind),
            a: params.repulsion(),
        }
    }

    /// Add the force of `pair`, `f = a_ij w e`, to the total `fi` of particle i and `-f` to
    /// `fj`.
    ///
    /// # Safety
    /// `pair` is a pair of the table (or fill) whose bound made this.
    #[inline(always)]
    pub(crate) unsafe fn pair(&self, pair: &Pair, fi: &mut Vec3, fj: &mut Vec3) {
        // SAFETY: the caller's contract.
        let soft = self.a.soft(|| unsafe { self.kind.get_two(pair.i, pair.j) });
        let f = soft.force(pair.w) * pair.e;
        *fi += f;
        *fj -= f;
    }
}

/// Full DPD forces at the current momenta into `s.full`, from the pair table:
/// `sum_j [a w - gamma w_R^2 (e . v_ij) + sigma w_R zeta_ij / sqrt(dt)] e_ij`,
/// with `zeta_ij` the pair normal of the noise and `v_ij` including the pair's velocity shift
/// (image velocity across a sliding boundary, wall velocity of frozen particles) when
/// `SHIFTED`. Multiplied by a step `h` this is the F kick of algorithms.md section 2. Returns
/// the pair virial of the dissipative and random parts when `V` is [`crate::Tensor`].
#[inline(always)]
pub(crate) fn full<const SHIFTED: bool, V: Virial>(s: FullInputs) -> V {
    let add = s.add;
    let out = zeroed(s.full, s.q.len());
    s.pairs.sweep_noisy(
        SweepOrder::Forward,
        s.noise,
        out,
        move |pair, two, z, dvx| {
            // SAFETY: the pairs of the table whose bound made `add`.
            unsafe { add.pair::<SHIFTED, V>(pair, two, z, dvx) }
        },
    )
}

/// [`full`] while the pair table is filled ([`PairTable::collect_then`]): each run's normals
/// and forces while it is in cache, in the order of a pass over the table, so the same
/// numbers. For a periodic box without walls, not recording impulses, with the list built for
/// the current positions and `s.add` made with the bound of the positions; leaves the table
/// filled.
pub(crate) fn full_while_filling(s: FullInputs) {
    let noise = s.noise.map(|noise| noise.of(Bound::of(s.q)));
    let add = s.add;
    // SAFETY: the pairs of the fill, whose bound (`Bound::of(q)`) made `add`.
    let forces =
        move |pair: &Pair, two: Two<_>, z, _| unsafe { add.pair::<false, ()>(pair, two, z, 0.0) };
    let each = |run: Run<Vec3>| run.sweep(noise, forces);
    let out = zeroed(s.full, s.q.len());
    s.pairs.collect_then(s.list, s.q, s.bx, s.params, out, each);
}

/// What a full-force evaluation reads and writes: the pair table and what fills it, the force
/// totals, the pair forces and the noise.
pub(crate) struct FullInputs<'a> {
    pub(crate) pairs: &'a mut PairTable,
    pub(crate) list: &'a VerletList,
    pub(crate) q: &'a [Vec3],
    pub(crate) bx: &'a PeriodicBox,
    pub(crate) params: &'a Params,
    pub(crate) full: &'a mut Vec<Vec3>,
    pub(crate) add: Full<'a>,
    pub(crate) noise: Option<Noise<'a>>,
}

/// The sum of the full DPD forces into per-particle totals, pair by pair: what [`full`] does
/// over a table, and what a fill does run by run ([`PairTable::collect_then`]), so that both
/// give the same numbers.
#[derive(Clone, Copy)]
pub(crate) struct Full<'a> {
    p: ByPair<'a, Vec3>,
    inv_mass: ByPair<'a, f64>,
    kind: ByPair<'a, u16>,
    a: Repulsion<'a>,
    rc: f64,
    gamma: f64,
    /// `sigma / sqrt(dt)`.
    noise: f64,
}

impl<'a> Full<'a> {
    /// The forces of the pairs of a table with index bound `bound`, at momenta `p` (with
    /// `inv_mass` and `kind` the particles' inverse masses and types) and time step `dt`
    /// (which scales the random force).
    pub(crate) fn new(
        bound: Bound,
        params: &'a Params,
        dt: f64,
        (p, inv_mass, kind): (&'a [Vec3], &'a [f64], &'a [u16]),
    ) -> Self {
        Full {
            p: bound.read(p),
            inv_mass: bound.read(inv_mass),
            kind: bound.read(kind),
            a: params.repulsion(),
            rc: params.rc(),
            gamma: params.gamma(),
            noise: params.sigma() / dt.sqrt(),
        }
    }

    /// The noise these forces need: stream `stream` of `step` under `seed`, pairs keyed by
    /// `id`; `None` without noise.
    pub(crate) fn noise<'b>(
        &self,
        seed: u64,
        step: u64,
        stream: u8,
        id: &'b [u32],
    ) -> Option<Noise<'b>> {
        (self.noise > 0.0).then_some(Noise {
            seed,
            step,
            stream,
            id,
        })
    }

    /// Add the force of `pair` with standard normal `z` and velocity shift `dvx` (used only
    /// when `SHIFTED`) to the total of particle i and its opposite to that of j, and return its
    /// dissipative and random part as `V`.
    ///
    /// # Safety
    /// `pair` is a pair of the table (or fill) whose bound made this.
    #[inline(always)]
    pub(crate) unsafe fn pair<const SHIFTED: bool, V: Virial>(
        &self,
        pair: &Pair,
        two: Two<Vec3>,
        z: f64,
        dvx: f64,
    ) -> V {
        let (i, j) = (pair.i, pair.j);
        // SAFETY (both): the caller's contract.
        let u = unsafe {
            pair.normal_velocity::<SHIFTED>(
                self.p.get(i) * self.inv_mass.get(i),
                self.p.get(j) * self.inv_mass.get(j),
                dvx,
            )
        };
        // SAFETY: the caller's contract.
        let conservative = self
            .a
            .soft(|| unsafe { self.kind.get_two(i, j) })
            .force(pair.w);
        let f = full_pair_force(conservative, self.gamma, self.noise, pair.wr, u, z);
        let fe = f * pair.e;
        let (fi, fj) = two.split();
        *fi += fe;
        *fj -= fe;
        V::of(pair, self.rc, f - conservative)
    }
}

/// The full DPD pair force along `e_ij` ([`full`]): `conservative - gamma w_R^2 u + noise w_R z`
/// for the conservative pair force `conservative`, random weight `wr`, relative normal
/// velocity `u = e_ij . v_ij`, standard normal `z` and `noise = sigma / sqrt(dt)`; the noise
/// term only when `noise > 0`. Public for engines that own their pair loop (the LAMMPS
/// plugin's kernels, which pass `conservative = 0` and take the conservative forces from the
/// engine).
#[inline(always)]
pub fn full_pair_force(conservative: f64, gamma: f64, noise: f64, wr: f64, u: f64, z: f64) -> f64 {
    let mut f = conservative - gamma * wr * wr * u;
    if noise > 0.0 {
        f += noise * wr * z;
    }
    f
}
