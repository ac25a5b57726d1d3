//! Per-particle forces summed over the interacting pairs in sweep order: the pair forces, each
//! computed from what the pair engine hands it ([`Ends`]), and the passes that sum them.

use crate::boundary::PeriodicBox;
use crate::neighbour::VerletList;
use crate::pairs::{Ends, Excluding, Noise, PairTable, Particles, Run, Two, Virial};
use crate::params::Params;
use crate::Vec3;
use dpd_ir::SweepOrder;

/// `out_i = F^C_i = sum_j a_ij (1 - r_ij/r_c) e_ij`.
/// `out` is resized to one entry per particle (it is allocated on first use, so a scheme that
/// never kicks with B holds no conservative-force array).
pub(crate) fn conservative(pairs: &PairTable, particles: Particles, out: &mut Vec<Vec3>) {
    let out = zeroed(out, particles.len());
    pairs.for_each_pair(SweepOrder::Forward, particles, out, add_conservative);
}

/// `out` as `n` zero vectors.
pub(crate) fn zeroed(out: &mut Vec<Vec3>, n: usize) -> &mut [Vec3] {
    out.clear();
    out.resize(n, Vec3::zeros());
    out
}

/// Add the conservative force of a pair, `f = a_ij w e`, to the total `fi` of particle i and
/// `-f` to `fj`: what [`conservative`] does over a table, and what a fill does run by run
/// ([`PairTable::collect_then`]), so that both give the same numbers.
#[inline(always)]
pub(crate) fn add_conservative(ends: Ends, fi: &mut Vec3, fj: &mut Vec3) {
    let pair = ends.pair();
    let f = ends.soft().force(pair.w) * pair.e;
    *fi += f;
    *fj -= f;
}

/// Full DPD forces at the current momenta into `s.full`, from the pair table:
/// `sum_j [a w - gamma w_R^2 (e . v_ij) + sigma w_R zeta_ij / sqrt(dt)] e_ij`,
/// with `zeta_ij` the pair normal of the noise and `v_ij` including the pair's velocity shift
/// (image velocity across a sliding boundary, wall velocity of frozen particles) when
/// `SHIFTED`. Multiplied by a step `h` this is the F kick of algorithms.md section 2. Returns
/// the pair virial of the dissipative and random parts when `V` is [`crate::Tensor`].
#[inline(always)]
pub(crate) fn full<const SHIFTED: bool, V: Virial>(s: FullInputs) -> V {
    match (s.add.uniform, s.add.by_type()) {
        (uniform, None) => full_with::<SHIFTED, V, _>(s, uniform),
        (_, Some(by_type)) => full_with::<SHIFTED, V, _>(s, by_type),
    }
}

/// [`full`] with the pairs' friction and noise amplitude from `friction`.
#[inline(always)]
fn full_with<const SHIFTED: bool, V: Virial, F: Friction>(s: FullInputs, friction: F) -> V {
    let out = zeroed(s.full, s.q.len());
    s.pairs.sweep_noisy(
        SweepOrder::Forward,
        s.noise,
        s.particles,
        out,
        move |ends, two, z, dvx| Full::pair::<SHIFTED, V>(friction.of(ends), ends, two, z, dvx),
    )
}

/// [`full`] while the pair table is filled ([`PairTable::collect_then`]): each run's normals
/// and forces while it is in cache, in the order of a pass over the table, so the same
/// numbers. For a periodic box without walls, not recording impulses, with the list built for
/// the current positions; leaves the table filled.
pub(crate) fn full_while_filling(s: FullInputs) {
    match (s.add.uniform, s.add.by_type()) {
        (uniform, None) => full_while_filling_with(s, uniform),
        (_, Some(by_type)) => full_while_filling_with(s, by_type),
    }
}

/// [`full_while_filling`] with the pairs' friction and noise amplitude from `friction`.
fn full_while_filling_with<F: Friction>(s: FullInputs, friction: F) {
    let forces = move |ends: Ends<&[Vec3]>, two: Two<Vec3>, z, _| {
        Full::pair::<false, ()>(friction.of(ends), ends, two, z, 0.0)
    };
    let each = |run: Run<Vec3, _>| run.sweep(forces);
    let out = zeroed(s.full, s.q.len());
    let (list, q, bx, params, excluding) = (s.list, s.q, s.bx, s.params, s.excluding);
    s.pairs.collect_then(
        list,
        q,
        bx,
        params,
        excluding,
        s.noise,
        s.particles,
        out,
        each,
    );
}

/// What a full-force evaluation reads and writes: the pair table and what fills it, the
/// particles with their momenta, the force totals, the pair forces and the noise.
pub(crate) struct FullInputs<'a> {
    pub(crate) pairs: &'a mut PairTable,
    pub(crate) list: &'a VerletList,
    pub(crate) q: &'a [Vec3],
    pub(crate) bx: &'a PeriodicBox,
    pub(crate) params: &'a Params,
    /// The pairs the system leaves out, if any.
    pub(crate) excluding: Option<Excluding<'a>>,
    pub(crate) particles: Particles<'a, &'a [Vec3]>,
    pub(crate) full: &'a mut Vec<Vec3>,
    pub(crate) add: Full,
    pub(crate) noise: Option<Noise<'a>>,
}

/// The friction `gamma` and the scaled noise amplitude `c sigma` of a pair, `c` fixed by the
/// flow (1 for the pairwise sweeps, `1 / sqrt(dt)` for the full forces): one pair of values
/// for every pair ([`Uniform`]), or each pair's by its types ([`ByType`]). A flow is compiled
/// for each, so that a system whose pairs share one friction reads no types for it.
pub(crate) trait Friction: Copy + Send + Sync {
    fn of<M: Copy>(self, ends: Ends<M>) -> (f64, f64);
}

/// The same `(gamma, c sigma)` for every pair.
#[derive(Clone, Copy)]
pub(crate) struct Uniform(pub(crate) f64, pub(crate) f64);

impl Friction for Uniform {
    #[inline(always)]
    fn of<M: Copy>(self, _: Ends<M>) -> (f64, f64) {
        (self.0, self.1)
    }
}

/// `(gamma_ij, c sigma_ij)` of each pair's types, `c` the field.
#[derive(Clone, Copy)]
pub(crate) struct ByType(pub(crate) f64);

impl Friction for ByType {
    #[inline(always)]
    fn of<M: Copy>(self, ends: Ends<M>) -> (f64, f64) {
        let (gamma, sigma) = ends.friction();
        (gamma, self.0 * sigma)
    }
}

/// The full DPD force of one pair added to the totals of its particles: what [`full`] does
/// over a table, and what a fill does run by run ([`PairTable::collect_then`]), so that both
/// give the same numbers.
#[derive(Clone, Copy)]
pub(crate) struct Full {
    /// `(gamma, sigma / sqrt(dt))` of every pair, the largest ones when they differ.
    uniform: Uniform,
    /// Whether the pairs' frictions differ.
    by_type: bool,
    /// `1 / sqrt(dt)`.
    noise_scale: f64,
}

impl Full {
    /// The forces of `params` at time step `dt` (which scales the random force).
    pub(crate) fn new(params: &Params, dt: f64) -> Self {
        Full {
            uniform: Uniform(params.gamma(), params.sigma() / dt.sqrt()),
            by_type: params.friction_by_type(),
            noise_scale: 1.0 / dt.sqrt(),
        }
    }

    /// The friction of each pair, when the pairs' frictions differ.
    fn by_type(self) -> Option<ByType> {
        self.by_type.then_some(ByType(self.noise_scale))
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
        (self.uniform.1 > 0.0).then_some(Noise {
            seed,
            step,
            stream,
            id,
        })
    }

    /// Add the force of the pair of `ends`, with friction `gamma`, scaled noise amplitude
    /// `noise = sigma / sqrt(dt)`, standard normal `z` and velocity shift `dvx` (used only when
    /// `SHIFTED`) to the total of particle i and its opposite to that of j, and return its
    /// dissipative and random part as `V`.
    #[inline(always)]
    fn pair<const SHIFTED: bool, V: Virial>(
        (gamma, noise): (f64, f64),
        ends: Ends<&[Vec3]>,
        two: Two<Vec3>,
        z: f64,
        dvx: f64,
    ) -> V {
        let pair = ends.pair();
        let ((pi, pj), (mi, mj)) = (ends.momenta(), ends.inv_masses());
        let u = pair.normal_velocity::<SHIFTED>(pi * mi, pj * mj, dvx);
        let conservative = ends.soft().force(pair.w);
        let f = full_pair_force(conservative, gamma, noise, pair.wr, u, z);
        let fe = f * pair.e;
        let (fi, fj) = two.split();
        *fi += fe;
        *fj -= fe;
        V::of(pair, || ends.rc(), f - conservative)
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
