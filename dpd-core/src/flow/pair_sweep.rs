use super::expm1::expm1;
use crate::pairs::{Noise, Pair, Virial};
use crate::system::System;
use crate::Tensor;
use dpd_ir::SweepOrder;

/// What a pair update sees: inverse reduced mass `mu = 1/m_i + 1/m_j`, the pair, its
/// repulsion `a_ij` (looked up only by a sweep that applies the conservative force, else 0)
/// and one standard normal `r`.
struct PairState<'a> {
    mu: f64,
    pair: &'a Pair,
    a: f64,
    r: f64,
}

/// Visit the interacting pairs successively in `order`; `update` returns `(slope, offset)`
/// with the change of the pair's relative normal velocity `u = e . v_ij` (with the image
/// velocity across a sliding boundary) `du = slope u + offset`, applied as `p_i += du/mu e`,
/// `p_j -= du/mu e`. Both come from the pair's geometry and noise alone, so that the chain
/// from one update of a particle to the next (read `u`, write momenta) is a few multiply-adds.
/// The flows below mark `update` `#[inline(always)]`: left to itself the compiler made it a
/// function called per pair (ABOBA about 2-3 % dearer per step).
///
/// When the system records pair impulses for the stress, the dissipative and random part of
/// each pair's impulse, `du/mu - a_ij w h_c` (`h_c`: the step over which the update also applies
/// the conservative force, 0 for O and O-BBK, `h` for T), is added as a virial. The shear and
/// recording switches are resolved here, once per sweep, not per pair.
#[inline(always)]
fn sweep(
    sys: &mut System,
    stream: u8,
    order: SweepOrder,
    conservative_h: f64,
    update: impl Fn(&PairState) -> (f64, f64) + Sync + Copy,
) {
    sys.ensure_pairs();
    let recorded = match (sys.shifted_pairs(), sys.impulses.is_some()) {
        (false, false) => {
            sweep_with::<false, ()>(sys, stream, order, conservative_h, update);
            None
        }
        (true, false) => {
            sweep_with::<true, ()>(sys, stream, order, conservative_h, update);
            None
        }
        (false, true) => Some(sweep_with::<false, Tensor>(
            sys,
            stream,
            order,
            conservative_h,
            update,
        )),
        (true, true) => Some(sweep_with::<true, Tensor>(
            sys,
            stream,
            order,
            conservative_h,
            update,
        )),
    };
    if let (Some(impulses), Some(virial)) = (&mut sys.impulses, recorded) {
        impulses.add(virial);
    }
}

#[inline(always)]
fn sweep_with<const SHIFTED: bool, V: Virial>(
    sys: &mut System,
    stream: u8,
    order: SweepOrder,
    conservative_h: f64,
    update: impl Fn(&PairState) -> (f64, f64) + Sync + Copy,
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
    let (a, rc) = (params.repulsion(), params.rc());
    pairs.visit_sum_noisy(order, noise, move |pair, r, dvx| {
        let (i, j) = (pair.i, pair.j);
        // SAFETY: `visit` never hands two pairs sharing a particle to different threads, `p`
        // was made for this table, and the two references are to distinct particles (i != j).
        let (pi, pj) = unsafe { (p.get_paired(i), p.get_paired(j)) };
        let (mi, mj) = (inv_mass.get(i), inv_mass.get(j));
        let mu = mi + mj;
        let state = PairState {
            mu,
            pair,
            a: if conservative_h != 0.0 {
                a.of_pair(kind, i, j)
            } else {
                0.0
            },
            r,
        };
        let (slope, offset) = update(&state);
        let reduced = 1.0 / mu;
        let (slope, offset) = (slope * reduced, offset * reduced);
        let u = pair.normal_velocity::<SHIFTED>(*pi * mi, *pj * mj, dvx);
        let impulse = slope * u + offset;
        let dp = impulse * pair.e;
        *pi += dp;
        *pj -= dp;
        V::of(pair, rc, impulse - state.a * pair.w * conservative_h)
    })
}

/// Standard deviation of the exact OU noise over a step with `x = tau h`, given
/// `em1 = exp(-x) - 1`: `s_n sqrt((1 - exp(-2 tau h)) / (2 tau))`, which with
/// `sigma^2 = 2 gamma kbt` simplifies to `sqrt(kbt mu (1 - exp(-2x)))` and never divides by
/// `tau`; `1 - exp(-2x) = -em1 (2 + em1)` has no cancellation. Zero for `x <= 0`.
#[inline(always)]
fn ou_std(kbt: f64, mu: f64, em1: f64) -> f64 {
    (kbt * mu * -em1 * (2.0 + em1)).max(0.0).sqrt()
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
        0.0,
        #[inline(always)]
        move |s| {
            let em1 = expm1(-gamma * s.pair.wr * s.pair.wr * s.mu * h);
            (em1, ou_std(kbt, s.mu, em1) * s.r)
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
        0.0,
        #[inline(always)]
        move |s| {
            let half_tau_h = 0.5 * gamma * s.pair.wr * s.pair.wr * s.mu * h;
            let kick = 0.5 * sigma * s.pair.wr * s.mu * root_h * s.r;
            let scale = 1.0 / (1.0 + half_tau_h);
            (-2.0 * half_tau_h * scale, 2.0 * kick * scale)
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
        h,
        #[inline(always)]
        move |s| {
            let x = gamma * s.pair.wr * s.pair.wr * s.mu * h;
            let em1 = expm1(-x);
            let phi1 = if x == 0.0 { 1.0 } else { -em1 / x };
            let offset = s.a * s.pair.w * s.mu * h * phi1 + ou_std(kbt, s.mu, em1) * s.r;
            (em1, offset)
        },
    );
    sys.apply_body_force(h);
}
