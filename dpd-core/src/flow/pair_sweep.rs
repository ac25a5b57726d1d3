use super::expm1::expm1;
#[cfg(target_arch = "x86_64")]
use super::expm1::expm1_within;
#[cfg(target_arch = "x86_64")]
use crate::avx2::Avx2;
use crate::force::{ByType, Friction, Uniform};
use crate::lanes::Lanes;
#[cfg(target_arch = "x86_64")]
use crate::lanes::{F64x4, F64x4x2, Vector};
use crate::pairs::{Ends, Noise, Particles, Span, Two, Virial};
use crate::rng::PairRng;
use crate::system::{PairState, System};
use crate::{Tensor, Vec3};
use dpd_ir::SweepOrder;
use rand_core::RngCore;

/// The change of one pair's relative normal velocity `u = e . v_ij`, `du = slope u + offset`,
/// with `slope` and `offset` divided by `mu` ([`per_mass`]), so that `slope u + offset` is the
/// pair's impulse (momentum, added to `p_i` along `e_ij` and taken from `p_j`); and the impulse
/// `conservative` of the conservative force that it includes (0 unless the update applies that
/// force, as T does).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Change {
    pub slope: f64,
    pub offset: f64,
    pub conservative: f64,
}

/// Visit the interacting pairs successively in `order`, each run of the table after
/// `changes(span, z, out)` has pushed the [`Change`] of each pair of the run's `span` (normals
/// `z`) onto `out`, for `u` with the image velocity across a sliding boundary, applied as
/// `p_i += du/mu e`, `p_j -= du/mu e`. Slope and offset come from the pair's geometry and
/// noise alone, so that they are computed in a loop of their own (vectorised where the flow
/// does it) and the chain from one update of a particle to the next (read `u`, write momenta)
/// is a few multiply-adds.
///
/// When the system records pair impulses for the stress, the dissipative and random part of
/// each pair's impulse, `du/mu` less the conservative impulse, is added as a virial. The shear
/// and recording switches are resolved here, once per sweep, not per pair.
#[inline(always)]
pub(super) fn sweep(sys: &mut System, stream: u8, order: SweepOrder, changes: impl Changes) {
    sweep_with_draws(sys, stream, order, Draws::Normals, changes);
}

/// [`sweep`] of a flow without noise: `changes` is given zeros, no normal is drawn.
#[inline(always)]
pub(super) fn sweep_noiseless(
    sys: &mut System,
    stream: u8,
    order: SweepOrder,
    changes: impl Changes,
) {
    sweep_with_draws(sys, stream, order, Draws::Keyed, changes);
}

/// [`sweep`] with the engine's normals if `draws` asks for them.
#[inline(always)]
fn sweep_with_draws(
    sys: &mut System,
    stream: u8,
    order: SweepOrder,
    draws: Draws,
    changes: impl Changes,
) {
    sweep_drawing(
        sys,
        stream,
        order,
        draws,
        // Inlined, as every closure between the engine and the lanes: the engine's AVX2
        // context reaches the O sweep's vector code only through inlined calls.
        #[inline(always)]
        move |_: Noise, span: Span, z: &[f64], out: &mut Vec<Change>| changes(span, z, out),
    );
}

/// Where the random numbers of a sweep's pairs come from.
#[derive(Clone, Copy, PartialEq)]
enum Draws {
    /// The engine draws one standard normal per pair (when the friction is not zero).
    Normals,
    /// The flow draws its own from each pair's [`PairRng`], keyed by the [`Noise`].
    Keyed,
}

/// [`sweep`] with `changes` also given the sweep's [`Noise`] (its key and the particle ids),
/// and with the engine's normals only if `draws` asks for them (else `z` is all zeros).
#[inline(always)]
fn sweep_drawing(
    sys: &mut System,
    stream: u8,
    order: SweepOrder,
    draws: Draws,
    changes: impl KeyedChanges,
) {
    let (shifted, recording) = (sys.shifted_pairs(), sys.recording_impulses());
    let state = sys.pair_state(stream);
    let recorded = match (shifted, recording) {
        (false, false) => {
            sweep_with::<false, ()>(state, order, draws, changes);
            None
        }
        (true, false) => {
            sweep_with::<true, ()>(state, order, draws, changes);
            None
        }
        (false, true) => Some(sweep_with::<false, Tensor>(state, order, draws, changes)),
        (true, true) => Some(sweep_with::<true, Tensor>(state, order, draws, changes)),
    };
    if let Some(virial) = recorded {
        sys.record_impulses(virial);
    }
}

/// How a flow computes the [`Change`]s of a run ([`sweep`]).
pub(super) trait Changes: Fn(Span, &[f64], &mut Vec<Change>) + Sync + Copy {}
impl<F: Fn(Span, &[f64], &mut Vec<Change>) + Sync + Copy> Changes for F {}

/// [`Changes`] that read the sweep's [`Noise`] ([`sweep_drawing`]).
trait KeyedChanges: Fn(Noise, Span, &[f64], &mut Vec<Change>) + Sync + Copy {}
impl<F: Fn(Noise, Span, &[f64], &mut Vec<Change>) + Sync + Copy> KeyedChanges for F {}

#[inline(always)]
fn sweep_with<const SHIFTED: bool, V: Virial>(
    state: PairState,
    order: SweepOrder,
    draws: Draws,
    changes: impl KeyedChanges,
) -> V {
    let PairState {
        pairs,
        p,
        inv_mass,
        kind,
        params,
        noise,
        ..
    } = state;
    let key = noise;
    let noise = (draws == Draws::Normals && params.sigma() > 0.0).then_some(noise);
    let particles = Particles::new(inv_mass, kind, params.coefficients());
    pairs.sweep_prepared(
        order,
        noise,
        particles,
        p,
        #[inline(always)]
        move |span: Span, z: &[f64], out: &mut Vec<Change>| changes(key, span, z, out),
        // Inlined into both loops that visit (pairs of alternating runs, and the rest).
        #[inline(always)]
        move |ends: Ends, two: Two<Vec3>, change: Change, dvx| {
            let pair = ends.pair();
            let (pi, pj) = two.split();
            let (mi, mj) = ends.inv_masses();
            let u = pair.normal_velocity::<SHIFTED>(*pi * mi, *pj * mj, dvx);
            let impulse = change.slope * u + change.offset;
            let dp = impulse * pair.e;
            *pi += dp;
            *pj -= dp;
            V::of(pair, || ends.rc(), impulse - change.conservative)
        },
    )
}

/// `(slope, offset) / mu` as a [`Change`] holds them.
#[inline(always)]
pub(super) fn per_mass<L: Lanes>(slope: L, offset: L, mu: L) -> (L, L) {
    let reduced = mu.splat(1.0) / mu;
    (slope * reduced, offset * reduced)
}

/// Standard deviation of the exact OU noise over a step with `x = tau h`, given
/// `em1 = exp(-x) - 1`: `s_n sqrt((1 - exp(-2 tau h)) / (2 tau))`, which with
/// `sigma^2 = 2 gamma kbt` simplifies to `sqrt(kbt mu (1 - exp(-2x)))` and never divides by
/// `tau`; `1 - exp(-2x) = -em1 (2 + em1)` has no cancellation. Zero for `x <= 0`.
#[inline(always)]
fn ou_std<L: Lanes>(kbt: f64, mu: L, em1: L) -> L {
    (mu.splat(kbt) * mu * -em1 * (mu.splat(2.0) + em1))
        .max_zero()
        .sqrt()
}

/// The exponent `-tau h = -gamma w_R^2 mu h` of the O update.
#[inline(always)]
fn ou_exponent<L: Lanes>(gamma: f64, h: f64, wr: L, mu: L) -> L {
    wr.splat(-gamma) * wr * wr * mu * wr.splat(h)
}

/// Slope and offset per mass of the O update with `em1 = exp(-tau h) - 1` and normal `r`.
#[inline(always)]
fn ou_change<L: Lanes>(kbt: f64, mu: L, em1: L, r: L) -> (L, L) {
    per_mass(em1, ou_std(kbt, mu, em1) * r, mu)
}

/// Push the [`ou_change`] of every pair of a run's `span` (normals `z`) onto `out`: several
/// pairs at once in AVX2 registers when the CPU has them and all their exponents lie in
/// `[-40, 0]` (so with `gamma mu h <= 40`), else pair by pair; the same numbers either way. The
/// vectorised loop takes eight pairs at a time in two registers ([`F64x4x2`]): their two chains
/// of dependent operations are independent, and the CPU overlaps them (with four pairs at a time
/// in one register this loop took 9.5 instead of 6.8 timestamp-counter cycles per pair, at
/// N = 24 000 on the development VM).
#[inline(always)]
fn ou_changes(ou: (f64, f64, f64), span: Span, z: &[f64], out: &mut Vec<Change>) {
    let each = pair_by_pair(move |ends, r| ou_pair(ou, ends, r));
    #[cfg(target_arch = "x86_64")]
    let (span, z) = match Avx2::detect() {
        Some(avx2) => {
            let (span, z) = ou_groups::<8, F64x4x2>(avx2, ou, span, z, out, each);
            ou_groups::<4, F64x4>(avx2, ou, span, z, out, each)
        }
        None => (span, z),
    };
    each(span, z, out)
}

/// The [`ou_change`] of one pair with normal `r`.
#[inline(always)]
fn ou_pair((gamma, kbt, h): (f64, f64, f64), ends: Ends, r: f64) -> Change {
    ou_update(gamma, kbt, h, ends.pair().wr, ends.mu(), r)
}

/// The O update of one pair (see [`ou`]) with random weight `wr`, inverse reduced mass
/// `mu = 1/m_i + 1/m_j` and standard normal `r`: the pair loop of an engine that owns its
/// pairs (the LAMMPS plugin's kernels) applies `impulse = slope u + offset` along `e_ij`.
#[inline(always)]
pub fn ou_update(gamma: f64, kbt: f64, h: f64, wr: f64, mu: f64, r: f64) -> Change {
    let em1 = expm1(ou_exponent(gamma, h, wr, mu));
    let (slope, offset) = ou_change(kbt, mu, em1, r);
    Change {
        slope,
        offset,
        conservative: 0.0,
    }
}

/// The O updates of the pairs `0..z.len()` of an engine that owns its pairs (the LAMMPS
/// plugin's kernels), pushed onto `out` in order: pair `k` with random weight `wr(k)`, inverse
/// reduced mass `mu(k)` and standard normal `z[k]`. Bitwise [`ou_update`] of each pair; eight
/// or four pairs at a time in AVX2 registers where the CPU has them and their exponents lie in
/// `[-40, 0]`, as the O sweep computes them.
pub fn ou_updates(
    (gamma, kbt, h): (f64, f64, f64),
    wr: impl Fn(usize) -> f64 + Copy,
    mu: impl Fn(usize) -> f64 + Copy,
    z: &[f64],
    out: &mut Vec<Change>,
) {
    let each = move |k: usize| ou_update(gamma, kbt, h, wr(k), mu(k), z[k]);
    crate::avx2::with_avx2(
        #[inline(always)]
        move || {
            #[cfg(target_arch = "x86_64")]
            let done = match Avx2::detect() {
                Some(avx2) => {
                    let ou = (gamma, kbt, h);
                    let done = ou_indexed::<8, F64x4x2>(avx2, ou, (wr, mu), (0, z), out, each);
                    ou_indexed::<4, F64x4>(avx2, ou, (wr, mu), (done, z), out, each)
                }
                None => 0,
            };
            #[cfg(not(target_arch = "x86_64"))]
            let done = 0;
            out.extend((done..z.len()).map(each));
        },
    )
}

/// [`ou_updates`] of the pairs `from..`, `N` at a time in lanes `V` ([`ou_lanes`]), or by
/// `each` where an exponent is out of range; returns where the fewer than `N` left over start.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn ou_indexed<const N: usize, V: Vector<N>>(
    avx2: Avx2,
    ou: (f64, f64, f64),
    (wr, mu): (impl Fn(usize) -> f64 + Copy, impl Fn(usize) -> f64 + Copy),
    (from, z): (usize, &[f64]),
    out: &mut Vec<Change>,
    each: impl Fn(usize) -> Change + Copy,
) -> usize {
    let mut k = from;
    while k + N <= z.len() {
        let lanes = (move |l| wr(k + l), move |l| mu(k + l));
        match ou_lanes::<N, V>(avx2, ou, lanes, &z[k..k + N]) {
            Some(changes) => out.extend(changes),
            None => out.extend((k..k + N).map(each)),
        }
        k += N;
    }
    k
}

/// Push the [`ou_change`]s of the pairs of `span` (normals `z`) onto `out`, `N` at a time in
/// lanes `V` ([`ou_lanes`]), or by `each` (pair by pair) where an exponent is out of range;
/// return the fewer than `N` pairs left over, with their normals.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn ou_groups<'a, const N: usize, V: Vector<N>>(
    avx2: Avx2,
    ou: (f64, f64, f64),
    span: Span<'a>,
    z: &'a [f64],
    out: &mut Vec<Change>,
    each: impl Changes,
) -> (Span<'a>, &'a [f64]) {
    let ((groups, rest), groups_z) = (span.chunks_exact(N), z.chunks_exact(N));
    let rest = (rest, groups_z.remainder());
    for (span, z) in groups.zip(groups_z) {
        let (wr, mu) = (|l| span.get(l).pair().wr, |l| span.get(l).mu());
        match ou_lanes::<N, V>(avx2, ou, (wr, mu), z) {
            Some(changes) => out.extend(changes),
            None => each(span, z, out),
        }
    }
    rest
}

/// The [`ou_change`]s of `N` pairs at once in lanes `V`, pair `l` with random weight `wr(l)`,
/// inverse reduced mass `mu(l)` and normal `z[l]`; `None` unless all their exponents lie in
/// `[-40, 0]`.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn ou_lanes<const N: usize, V: Vector<N>>(
    avx2: Avx2,
    (gamma, kbt, h): (f64, f64, f64),
    (wr, mu): (impl Fn(usize) -> f64, impl Fn(usize) -> f64),
    z: &[f64],
) -> Option<[Change; N]> {
    let wr = V::from_fn(avx2, wr);
    let mu = V::from_fn(avx2, mu);
    let r = V::from_fn(avx2, |l| z[l]);
    let x = ou_exponent(gamma, h, wr, mu);
    // No closure around the lane operations: it would not be compiled with AVX2.
    if !x.within(-40.0, 0.0) {
        return None;
    }
    let (slope, offset) = ou_change(kbt, mu, expm1_within(x), r);
    let (slope, offset) = (slope.to_array(), offset.to_array());
    Some(std::array::from_fn(|l| Change {
        slope: slope[l],
        offset: offset[l],
        conservative: 0.0,
    }))
}

/// O: exact pairwise Ornstein-Uhlenbeck sweep,
/// `u_new = u exp(-tau h) + sqrt(kbt mu (1 - exp(-2 tau h))) R`, `tau = gamma w_D mu`.
/// Evaluated with `expm1`, so `tau h -> 0` and `tau h -> infinity` are both accurate.
#[inline]
pub fn ou(sys: &mut System, h: f64, stream: u8, order: SweepOrder) {
    let (gamma, kbt) = (sys.params().gamma(), sys.params().kbt());
    if gamma == 0.0 {
        return;
    }
    let mark = sys.heat_mark();
    if sys.params().friction_by_type() {
        let change = move |ends: Ends, r| ou_pair((ByType(1.0).of(ends).0, kbt, h), ends, r);
        sweep(sys, stream, order, pair_by_pair(change));
    } else {
        sweep(
            sys,
            stream,
            order,
            #[inline(always)]
            move |span: Span, z: &[f64], out: &mut Vec<Change>| {
                ou_changes((gamma, kbt, h), span, z, out)
            },
        );
    }
    sys.record_heat(mark);
}

/// O with BBK (Shardlow's update), using the same normal `R` twice:
/// `u_half = u - (tau h/2) u + (s_n sqrt(h)/2) R`, `u_new = (u_half + (s_n sqrt(h)/2) R) / (1 + tau h/2)`,
/// `s_n = sigma w_R mu`; that is `u_new - u = (-tau h u + s_n sqrt(h) R) / (1 + tau h/2)`.
#[inline]
pub fn bbk(sys: &mut System, h: f64, stream: u8, order: SweepOrder) {
    let (gamma, sigma) = (sys.params().gamma(), sys.params().sigma());
    if gamma == 0.0 {
        return;
    }
    let mark = sys.heat_mark();
    match sys.params().friction_by_type() {
        false => bbk_with(sys, Uniform(gamma, sigma), h, stream, order),
        true => bbk_with(sys, ByType(1.0), h, stream, order),
    }
    sys.record_heat(mark);
}

/// [`bbk`] with the pairs' friction and noise amplitude from `friction`.
#[inline(always)]
fn bbk_with(sys: &mut System, friction: impl Friction, h: f64, stream: u8, order: SweepOrder) {
    let root_h = h.max(0.0).sqrt();
    let change = move |ends: Ends, r: f64| {
        let (gamma, sigma) = friction.of(ends);
        bbk_update(gamma, sigma, h, root_h, ends.pair().wr, ends.mu(), r)
    };
    sweep(sys, stream, order, pair_by_pair(change));
}

/// The BBK update of one pair (see [`bbk`]) with `root_h = sqrt(max(h, 0))`, random weight
/// `wr`, inverse reduced mass `mu` and standard normal `r` (as [`ou_update`]).
#[inline(always)]
pub fn bbk_update(gamma: f64, sigma: f64, h: f64, root_h: f64, wr: f64, mu: f64, r: f64) -> Change {
    let half_tau_h = 0.5 * gamma * wr * wr * mu * h;
    let kick = 0.5 * sigma * wr * mu * root_h * r;
    let scale = 1.0 / (1.0 + half_tau_h);
    let (slope, offset) = per_mass(-2.0 * half_tau_h * scale, 2.0 * kick * scale, mu);
    Change {
        slope,
        offset,
        conservative: 0.0,
    }
}

/// T: pairwise conservative + OU, exact per pair (DPD-Trotter):
/// `u_new = u exp(-tau h) + f mu h phi1(tau h) + sqrt(kbt mu (1 - exp(-2 tau h))) R` with
/// `f = a_ij (1 - r/r_c)` and `phi1(x) = (1 - exp(-x)) / x`, `phi1(0) = 1`.
#[inline]
pub fn trotter(sys: &mut System, h: f64, stream: u8, order: SweepOrder) {
    let (gamma, sigma) = (sys.params().gamma(), sys.params().sigma());
    sys.count_force_evaluation();
    match sys.params().friction_by_type() {
        false => trotter_with(sys, Uniform(gamma, sigma), h, stream, order),
        true => trotter_with(sys, ByType(1.0), h, stream, order),
    }
    sys.apply_body_force(h);
}

/// [`trotter`] with the pairs' friction from `friction`.
#[inline(always)]
fn trotter_with(sys: &mut System, friction: impl Friction, h: f64, stream: u8, order: SweepOrder) {
    let kbt = sys.params().kbt();
    let change = move |ends: Ends, r: f64| {
        let pair = ends.pair();
        let f = ends.soft().force(pair.w);
        let (gamma, _) = friction.of(ends);
        trotter_update(gamma, kbt, h, f, pair.wr, ends.mu(), r)
    };
    sweep(sys, stream, order, pair_by_pair(change));
}

/// The T update of one pair (see [`trotter`]) with conservative pair force `f` along `e_ij`
/// ([`crate::potential::Soft::force`]), random weight `wr`, inverse reduced mass `mu` and
/// standard normal `r` (as [`ou_update`]).
#[inline(always)]
pub fn trotter_update(gamma: f64, kbt: f64, h: f64, f: f64, wr: f64, mu: f64, r: f64) -> Change {
    let x = gamma * wr * wr * mu * h;
    let em1 = expm1(-x);
    let phi1 = if x == 0.0 { 1.0 } else { -em1 / x };
    let offset = f * mu * h * phi1 + ou_std(kbt, mu, em1) * r;
    let (slope, offset) = per_mass(em1, offset, mu);
    Change {
        slope,
        offset,
        conservative: f * h,
    }
}

/// L: Lowe-Andersen collisions at rate Gamma (`collision_rate`) over `h`. Each pair within
/// the cut-off, visited successively in `order` (as O), collides with probability
/// `p = 1 - exp(-Gamma h)`: its relative normal velocity `u = e . v_ij` is replaced by
/// `sqrt(kbt mu) R`, a draw from the Maxwellian of its reduced mass (`mu = 1/m_i + 1/m_j`),
/// by equal and opposite impulses, so momentum is conserved. Pair `(i, j)`'s [`PairRng`] in
/// `stream` gives a uniform `U` (53 bits of its first 64) and, when `U < p`, the normal `R`
/// (its next draws). Without a collision rate (which [`System::check_scheme`] refuses for a
/// scheme with L) no pair collides.
#[inline]
pub fn collide(sys: &mut System, h: f64, stream: u8, order: SweepOrder) {
    let Some(rate) = sys.params().collision_rate() else {
        return;
    };
    let (p, kbt) = (-expm1(-rate * h), sys.params().kbt());
    let mark = sys.heat_mark();
    let change = move |key: Noise, span: Span, _: &[f64], out: &mut Vec<Change>| {
        out.extend(span.iter().map(|ends| {
            let pair = ends.pair();
            let (i, j) = (key.id[pair.i as usize], key.id[pair.j as usize]);
            let mut rng = PairRng::new(key.seed, key.step, key.stream, i, j);
            collision_update(p, kbt, ends.mu(), &mut rng)
        }))
    };
    sweep_drawing(sys, stream, order, Draws::Keyed, change);
    sys.record_heat(mark);
}

/// The L update of one pair (see [`collide`]) with collision probability `p`, inverse reduced
/// mass `mu` and the pair's stream `rng`: no change, or `u -> sqrt(kbt mu) R`.
#[inline(always)]
pub fn collision_update(p: f64, kbt: f64, mu: f64, rng: &mut PairRng) -> Change {
    let uniform = (rng.next_u64() >> 11) as f64 * f64::EPSILON / 2.0;
    let (slope, offset) = match uniform < p {
        true => per_mass(-1.0, (kbt * mu).sqrt() * rng.normal(), mu),
        false => (0.0, 0.0),
    };
    Change {
        slope,
        offset,
        conservative: 0.0,
    }
}

/// The [`Changes`] of a flow that computes the change of each pair on its own,
/// `change(ends, r)` for normal `r`.
#[inline(always)]
pub(super) fn pair_by_pair(change: impl Fn(Ends, f64) -> Change + Sync + Copy) -> impl Changes {
    #[inline(always)]
    move |span: Span, z: &[f64], out: &mut Vec<Change>| {
        out.extend(span.iter().zip(z).map(|(ends, &r)| change(ends, r)));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pairs::Pair;
    use crate::Params;

    /// `ou_updates` is `ou_update` pair by pair, bitwise: runs of every length from 0 to 30
    /// (groups of eight and four and a rest), exponents inside and beyond `[-40, 0]` (where
    /// the lanes fall back to the scalar path), zero weights and normals of both signs.
    #[test]
    fn ou_updates_are_ou_update_of_each_pair() {
        let kbt = 1.3;
        for (n, big) in (0..31).zip([1.0, 1.0, 500.0].into_iter().cycle()) {
            let (gamma, h) = (4.5 * big, 0.04);
            let wr = move |k: usize| (k as f64 * 0.37 + n as f64 * 0.11) % 1.0;
            let mu = move |k: usize| 0.2 + (k as f64 * 0.7) % 2.0;
            let z: Vec<f64> = (0..n).map(|k| (k as f64 * 1.3 + 0.4).sin() * 3.0).collect();
            let mut out = Vec::new();
            ou_updates((gamma, kbt, h), wr, mu, &z, &mut out);
            let each: Vec<Change> = (0..n)
                .map(|k| ou_update(gamma, kbt, h, wr(k), mu(k), z[k]))
                .collect();
            let bits = |c: &[Change]| -> Vec<[u64; 3]> {
                c.iter()
                    .map(|c| [c.slope, c.offset, c.conservative].map(f64::to_bits))
                    .collect()
            };
            assert_eq!(bits(&out), bits(&each), "n = {n}, gamma = {gamma}");
        }
    }

    #[test]
    fn pairs_in_lanes_are_pairs_one_by_one() {
        // Exponents inside [-40, 0] (the vectorised path where the CPU has AVX2) and beyond
        // it, zero weights, normals of both signs, and runs whose length is not a multiple of
        // four.
        let (gamma, kbt, h) = (4.5, 1.0, 0.04);
        let params = Params::builder().build().unwrap();
        let inv_mass: Vec<f64> = (0..64).map(|k| 0.1 + (k as f64 * 0.11) % 5.0).collect();
        let kind = vec![0; inv_mass.len()];
        let particles = Particles::new(&inv_mass, &kind, params.coefficients());
        for (k, big) in (0..1000).zip([1.0, 1.0, 1.0, 300.0].into_iter().cycle()) {
            let t = k as f64;
            let n = 4 + k % 13;
            let pairs: Vec<Pair> = (0..n)
                .map(|l| Pair {
                    i: ((k + l) % 32) as u32,
                    j: (32 + (k * 7 + l) % 32) as u32,
                    e: Vec3::x(),
                    w: 0.5,
                    wr: (t * 0.37 + l as f64 * 0.21) % 1.0,
                })
                .collect();
            let z: Vec<f64> = (0..n).map(|l| (t * 0.7 + l as f64).sin() * 3.0).collect();
            let mut changes = Vec::new();
            let span = Span::checked(&pairs, particles);
            ou_changes((gamma * big, kbt, h), span, &z, &mut changes);
            assert_eq!(changes.len(), n);
            for ((pair, &r), c) in pairs.iter().zip(&z).zip(&changes) {
                let mu = inv_mass[pair.i as usize] + inv_mass[pair.j as usize];
                let em1 = expm1(ou_exponent(gamma * big, h, pair.wr, mu));
                let (s, o) = ou_change(kbt, mu, em1, r);
                assert_eq!(
                    (c.slope.to_bits(), c.offset.to_bits(), c.conservative),
                    (s.to_bits(), o.to_bits(), 0.0)
                );
            }
        }
    }
}
