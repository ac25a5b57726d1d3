use super::expm1::expm1;
#[cfg(target_arch = "x86_64")]
use super::expm1::expm1_within;
#[cfg(target_arch = "x86_64")]
use crate::lanes::F64x4;
use crate::lanes::Lanes;
use crate::pairs::{ByPair, Noise, Pair, Virial};
use crate::params::Repulsion;
use crate::system::System;
use crate::Tensor;
use dpd_ir::SweepOrder;

/// What a pair update sees: inverse reduced mass `mu = 1/m_i + 1/m_j`, the pair, one standard
/// normal `r`, and on request its repulsion `a_ij` ([`PairState::a`]).
#[derive(Clone, Copy)]
struct PairState<'a> {
    mu: f64,
    pair: &'a Pair,
    r: f64,
    repulsion: Repulsion<'a>,
    kind: ByPair<'a, u16>,
}

impl PairState<'_> {
    /// The repulsion `a_ij` of the pair's types.
    #[inline(always)]
    fn a(&self) -> f64 {
        self.repulsion.of_pair(self.kind, self.pair.i, self.pair.j)
    }
}

/// The change of one pair's relative normal velocity `u = e . v_ij`, `du = slope u + offset`,
/// with `slope` and `offset` divided by `mu` ([`per_mass`]), so that `slope u + offset` is the
/// pair's impulse; and the impulse `conservative` of the conservative force that it includes
/// (0 unless the update applies that force, as T does).
#[derive(Clone, Copy)]
struct Change {
    slope: f64,
    offset: f64,
    conservative: f64,
}

/// Visit the interacting pairs successively in `order`; `update` returns the [`Change`] of
/// each of `B` consecutive pairs at once (so that it may be vectorised), for `u` with the
/// image velocity across a sliding boundary, applied as `p_i += du/mu e`, `p_j -= du/mu e`.
/// Slope and offset come from the pair's geometry and noise alone, so that the chain from one
/// update of a particle to the next (read `u`, write momenta) is a few multiply-adds, and the
/// updates of a block are computed before its pairs are visited. The flows below mark
/// `update` `#[inline(always)]`: left to itself the compiler made it a function called per
/// pair (ABOBA about 2-3 % dearer per step).
///
/// When the system records pair impulses for the stress, the dissipative and random part of
/// each pair's impulse, `du/mu` less the conservative impulse, is added as a virial. The shear
/// and recording switches are resolved here, once per sweep, not per pair.
#[inline(always)]
fn sweep<const B: usize>(
    sys: &mut System,
    stream: u8,
    order: SweepOrder,
    update: impl Fn([PairState; B]) -> [Change; B] + Sync + Copy,
) {
    sys.ensure_pairs();
    let recorded = match (sys.shifted_pairs(), sys.impulses.is_some()) {
        (false, false) => {
            sweep_with::<false, (), B>(sys, stream, order, update);
            None
        }
        (true, false) => {
            sweep_with::<true, (), B>(sys, stream, order, update);
            None
        }
        (false, true) => Some(sweep_with::<false, Tensor, B>(sys, stream, order, update)),
        (true, true) => Some(sweep_with::<true, Tensor, B>(sys, stream, order, update)),
    };
    if let (Some(impulses), Some(virial)) = (&mut sys.impulses, recorded) {
        impulses.add(virial);
    }
}

#[inline(always)]
fn sweep_with<const SHIFTED: bool, V: Virial, const B: usize>(
    sys: &mut System,
    stream: u8,
    order: SweepOrder,
    update: impl Fn([PairState; B]) -> [Change; B] + Sync + Copy,
) -> V {
    let System {
        ref mut pairs,
        ref mut p,
        ref inv_mass,
        ref kind,
        ref id,
        ref params,
        seed,
        step,
        ..
    } = *sys;
    let noise = (params.sigma() > 0.0).then_some(Noise {
        seed,
        step,
        stream,
        id,
    });
    let p = pairs.write(p);
    let (inv_mass, kind) = (pairs.read(inv_mass), pairs.read(kind));
    let (repulsion, rc) = (params.repulsion(), params.rc());
    let visit = move |pair: &Pair, change: Change, dvx| {
        let (i, j) = (pair.i, pair.j);
        // SAFETY: `visit` never hands two pairs sharing a particle to different threads, `p`
        // was made for this table, and the two references are to distinct particles (i != j).
        let (pi, pj) = unsafe { (p.get_paired(i), p.get_paired(j)) };
        let (mi, mj) = (inv_mass.get(i), inv_mass.get(j));
        let u = pair.normal_velocity::<SHIFTED>(*pi * mi, *pj * mj, dvx);
        let impulse = change.slope * u + change.offset;
        let dp = impulse * pair.e;
        *pi += dp;
        *pj -= dp;
        V::of(pair, rc, impulse - change.conservative)
    };
    pairs.visit_sum_prepared(
        order,
        noise,
        #[inline(always)]
        move |pairs: [&Pair; B], r: [f64; B]| {
            let states: [PairState; B] = std::array::from_fn(|l| PairState {
                mu: inv_mass.get(pairs[l].i) + inv_mass.get(pairs[l].j),
                pair: pairs[l],
                r: r[l],
                repulsion,
                kind,
            });
            update(states)
        },
        visit,
    )
}

/// `(slope, offset) / mu` as a [`Change`] holds them.
#[inline(always)]
fn per_mass<L: Lanes>(slope: L, offset: L, mu: L) -> (L, L) {
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

/// Pairs whose O updates are computed together (four `f64` lanes: one AVX2 register).
const OU_LANES: usize = 4;

/// [`ou_change`] of `OU_LANES` pairs with random weights `wr`, inverse reduced masses `mu` and
/// normals `r`: in AVX2 registers when the CPU has them and every exponent lies in `[-40, 0]`
/// (so with `gamma mu h <= 40`), else pair by pair; the same numbers either way.
#[inline(always)]
fn ou_changes(
    (gamma, kbt, h): (f64, f64, f64),
    wr: [f64; OU_LANES],
    mu: [f64; OU_LANES],
    r: [f64; OU_LANES],
) -> ([f64; OU_LANES], [f64; OU_LANES]) {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the feature was detected.
        let (wr, mu, r) = unsafe { (F64x4::new(wr), F64x4::new(mu), F64x4::new(r)) };
        let x = ou_exponent(gamma, h, wr, mu);
        if x.within(-40.0, 0.0) {
            let (slope, offset) = ou_change(kbt, mu, expm1_within(x), r);
            return (slope.to_array(), offset.to_array());
        }
    }
    let changes: [(f64, f64); OU_LANES] = std::array::from_fn(|l| {
        let em1 = expm1(ou_exponent(gamma, h, wr[l], mu[l]));
        ou_change(kbt, mu[l], em1, r[l])
    });
    (changes.map(|c| c.0), changes.map(|c| c.1))
}

/// O: exact pairwise Ornstein-Uhlenbeck sweep,
/// `u_new = u exp(-tau h) + sqrt(kbt mu (1 - exp(-2 tau h))) R`, `tau = gamma w_D mu`.
/// Evaluated with `expm1`, so `tau h -> 0` and `tau h -> infinity` are both accurate.
#[inline]
pub fn ou(sys: &mut System, h: f64, stream: u8, order: SweepOrder) {
    let (gamma, kbt) = (sys.params.gamma(), sys.params.kbt());
    if gamma == 0.0 {
        return;
    }
    sweep(
        sys,
        stream,
        order,
        #[inline(always)]
        move |s: [PairState; OU_LANES]| {
            let (wr, mu, r) = (s.map(|s| s.pair.wr), s.map(|s| s.mu), s.map(|s| s.r));
            let (slope, offset) = ou_changes((gamma, kbt, h), wr, mu, r);
            std::array::from_fn(|l| Change {
                slope: slope[l],
                offset: offset[l],
                conservative: 0.0,
            })
        },
    );
}

/// O with BBK (Shardlow's update), using the same normal `R` twice:
/// `u_half = u - (tau h/2) u + (s_n sqrt(h)/2) R`, `u_new = (u_half + (s_n sqrt(h)/2) R) / (1 + tau h/2)`,
/// `s_n = sigma w_R mu`; that is `u_new - u = (-tau h u + s_n sqrt(h) R) / (1 + tau h/2)`.
#[inline]
pub fn bbk(sys: &mut System, h: f64, stream: u8, order: SweepOrder) {
    let (gamma, sigma) = (sys.params.gamma(), sys.params.sigma());
    if gamma == 0.0 {
        return;
    }
    let root_h = h.max(0.0).sqrt();
    sweep(
        sys,
        stream,
        order,
        #[inline(always)]
        move |[s]: [PairState; 1]| {
            let half_tau_h = 0.5 * gamma * s.pair.wr * s.pair.wr * s.mu * h;
            let kick = 0.5 * sigma * s.pair.wr * s.mu * root_h * s.r;
            let scale = 1.0 / (1.0 + half_tau_h);
            let (slope, offset) = per_mass(-2.0 * half_tau_h * scale, 2.0 * kick * scale, s.mu);
            [Change {
                slope,
                offset,
                conservative: 0.0,
            }]
        },
    );
}

/// T: pairwise conservative + OU, exact per pair (DPD-Trotter):
/// `u_new = u exp(-tau h) + f mu h phi1(tau h) + sqrt(kbt mu (1 - exp(-2 tau h))) R` with
/// `f = a_ij (1 - r/r_c)` and `phi1(x) = (1 - exp(-x)) / x`, `phi1(0) = 1`.
#[inline]
pub fn trotter(sys: &mut System, h: f64, stream: u8, order: SweepOrder) {
    let (gamma, kbt) = (sys.params.gamma(), sys.params.kbt());
    sys.counters.force_evaluations += 1;
    sweep(
        sys,
        stream,
        order,
        #[inline(always)]
        move |[s]: [PairState; 1]| {
            let x = gamma * s.pair.wr * s.pair.wr * s.mu * h;
            let em1 = expm1(-x);
            let phi1 = if x == 0.0 { 1.0 } else { -em1 / x };
            let a = s.a();
            let offset = a * s.pair.w * s.mu * h * phi1 + ou_std(kbt, s.mu, em1) * s.r;
            let (slope, offset) = per_mass(em1, offset, s.mu);
            [Change {
                slope,
                offset,
                conservative: a * s.pair.w * h,
            }]
        },
    );
    sys.apply_body_force(h);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn four_pairs_at_once_are_four_pairs_one_by_one() {
        // Exponents inside [-40, 0] (the vectorised path where the CPU has AVX2) and beyond
        // it, zero weights and normals of both signs.
        let (gamma, kbt, h) = (4.5, 1.0, 0.04);
        for (k, big) in (0..4000).zip([1.0, 1.0, 1.0, 300.0].into_iter().cycle()) {
            let t = k as f64;
            let wr: [f64; 4] = std::array::from_fn(|l| (t * 0.37 + l as f64 * 0.21) % 1.0);
            let mu: [f64; 4] = std::array::from_fn(|l| big * (0.1 + (t * 0.11 + l as f64) % 5.0));
            let r: [f64; 4] = std::array::from_fn(|l| (t * 0.7 + l as f64).sin() * 3.0);
            let (slope, offset) = ou_changes((gamma * big, kbt, h), wr, mu, r);
            for l in 0..4 {
                let em1 = expm1(ou_exponent(gamma * big, h, wr[l], mu[l]));
                let (s, o) = ou_change(kbt, mu[l], em1, r[l]);
                assert_eq!(
                    (slope[l].to_bits(), offset[l].to_bits()),
                    (s.to_bits(), o.to_bits())
                );
            }
        }
    }
}
