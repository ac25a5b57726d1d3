//! The pairwise adaptive Langevin thermostat (PAdL; Leimkuhler and Shang, J. Comput. Phys. 324,
//! 174 (2016)) as two sub-flows: Oa, the O sweep with every pair's friction `xi gamma_ij`
//! scaled by the system's adaptive friction factor `xi` ([`System::xi`]) and its noise
//! amplitude `sigma_ij` kept, and Xi, the update of `xi`,
//!
//! `d xi = (1/mu) sum over pairs gamma_ij w_D(r_ij) (u_ij^2 - kbt (1/m_i + 1/m_j)) dt`,
//!
//! `u_ij = e_ij . v_ij`, `mu` the thermostat mass ([`crate::Params::thermostat_mass`], an
//! energy). With `sigma_ij^2 = 2 gamma_ij kbt` the density
//! `exp(-H/kbt) exp(-mu (xi - 1)^2 / (2 kbt))` is invariant: the extra friction
//! `(xi - 1) gamma_ij` changes it at the rate `(xi - 1) rho sum gamma_ij w_D (mu_ij - u^2/kbt)`
//! (`mu_ij = 1/m_i + 1/m_j`) and the flow of `xi` at exactly the opposite rate. So `xi` is
//! Gaussian around 1 with variance `kbt / mu`, and a discretisation that heats or cools the
//! pairs' relative motion drives `xi` up or down until the kinetic temperature is restored.
//!
//! The pairwise Nose-Hoover-Langevin thermostat (PNHL; Leimkuhler and Shang, J. Comput. Phys.
//! 280, 72 (2015)) drops the pair noise: On is Oa with `sigma_ij = 0`, and Xi, given a
//! thermostat friction `gamma_xi` ([`crate::Params::thermostat_friction`]), adds Langevin
//! dynamics to `xi`, `d xi = (G / mu - gamma_xi xi) dt + sqrt(2 gamma_xi kbt / mu) dW`. Then
//! `exp(-H/kbt) exp(-mu xi^2 / (2 kbt))` is invariant: the whole friction `xi gamma_ij` changes
//! the density at the rate `xi rho sum gamma_ij w_D (mu_ij - u^2/kbt)`, the drift `G / mu`
//! at the opposite rate, and the Ornstein-Uhlenbeck part keeps the Gaussian of `xi` around 0 of
//! variance `kbt / mu`; its noise makes the dynamics ergodic.

use super::adjusted::APART_STREAM;
use super::expm1::expm1;
use super::pair_sweep::{pair_by_pair, per_mass, sweep, sweep_noiseless, Change};
use crate::force::{ByType, Friction, Uniform};
use crate::pairs::{Ends, Pair, Particles, Two, Virial};
use crate::rng::pair_normal;
use crate::system::System;
use crate::Vec3;
use dpd_ir::SweepOrder;

/// Oa: the exact pairwise OU sweep at friction `xi gamma_ij` and noise `sigma_ij`,
/// `u_new = u exp(-x) + sigma_ij w_R mu_ij sqrt(h phi(2x)) R` with
/// `x = xi gamma_ij w_D mu_ij h` and `phi(y) = (1 - exp(-y)) / y` (`phi(0) = 1`), visiting the
/// pairs in `order` as O does. At `xi = 1` it is O (to rounding); at `xi <= 0` the pairs
/// are heated, as the dynamics says. Without `noise` (On, PNHL) `sigma_ij = 0` and no normal is
/// drawn: `u_new = u exp(-x)`. A system without friction is left alone.
#[inline]
pub fn adaptive_ou(sys: &mut System, h: f64, stream: u8, order: SweepOrder, noise: bool) {
    let (gamma, sigma, xi) = (sys.params().gamma(), sys.params().sigma(), sys.xi());
    if gamma == 0.0 {
        return;
    }
    let mark = sys.heat_mark();
    match sys.params().friction_by_type() {
        false => adaptive_with(sys, Uniform(gamma, sigma), xi, h, stream, order, noise),
        true => adaptive_with(sys, ByType(1.0), xi, h, stream, order, noise),
    }
    sys.record_heat(mark);
}

/// [`adaptive_ou`] with the pairs' friction and noise amplitude from `friction`.
#[inline(always)]
fn adaptive_with(
    sys: &mut System,
    friction: impl Friction,
    xi: f64,
    h: f64,
    stream: u8,
    order: SweepOrder,
    noise: bool,
) {
    let change = move |ends: Ends, r: f64| {
        let (gamma, sigma) = friction.of(ends);
        let sigma = if noise { sigma } else { 0.0 };
        adaptive_ou_update(xi * gamma, sigma, h, ends.pair().wr, ends.mu(), r)
    };
    match noise {
        true => sweep(sys, stream, order, pair_by_pair(change)),
        false => sweep_noiseless(sys, stream, order, pair_by_pair(change)),
    }
}

/// The Oa update of one pair (see [`adaptive_ou`]) with friction `friction = xi gamma_ij`
/// (any sign), noise amplitude `sigma`, random weight `wr`, inverse reduced mass `mu` and
/// standard normal `r`.
#[inline(always)]
pub fn adaptive_ou_update(friction: f64, sigma: f64, h: f64, wr: f64, mu: f64, r: f64) -> Change {
    let x = friction * wr * wr * mu * h;
    let phi = match x == 0.0 {
        true => 1.0,
        false => -expm1(-2.0 * x) / (2.0 * x),
    };
    let std = sigma * wr * mu * (h * phi).sqrt();
    let (slope, offset) = per_mass(expm1(-x), std * r, mu);
    Change {
        slope,
        offset,
        conservative: 0.0,
    }
}

/// Xi: `xi += h G / mu` with `G = sum over pairs gamma_ij w_D (u_ij^2 - kbt mu_ij)` at the
/// current positions and momenta (which it does not change), exact for its own flow. The sum
/// runs in the sweep order, run by run and colour by colour, so it is the same on any number
/// of threads. With a thermostat friction `gamma_xi` (PNHL) the exact Ornstein-Uhlenbeck flow
/// under that drift, `xi exp(-gamma_xi h) + G (1 - exp(-gamma_xi h)) / (mu gamma_xi)
/// + sqrt(kbt (1 - exp(-2 gamma_xi h)) / mu) R`, with the standard normal `R` drawn under the
/// system's seed from a stream apart from the sweeps', keyed by the stage's `number` in the
/// step. Without a thermostat mass (which [`System::check_scheme`] refuses for a scheme with
/// Xi) or a friction, `xi` stays.
#[inline]
pub fn xi_update(sys: &mut System, h: f64, number: u8) {
    let (Some(mass), kbt) = (sys.params().thermostat_mass(), sys.params().kbt()) else {
        return;
    };
    if sys.params().gamma() == 0.0 {
        return;
    }
    let g = match sys.params().friction_by_type() {
        false => feedback(sys, Uniform(sys.params().gamma(), 0.0), kbt),
        true => feedback(sys, ByType(1.0), kbt),
    };
    let xi = match sys.params().thermostat_friction() {
        None => sys.xi() + h * g / mass,
        Some(gamma_xi) => {
            // Keyed as the pair (MAX - number, MAX - number), which neither a pair of
            // particles nor an accept/reject test (part, part) is.
            let key = u32::MAX - u32::from(number);
            let r = pair_normal(sys.seed(), sys.step(), APART_STREAM, key, key);
            let decay = expm1(-gamma_xi * h);
            let std = (-kbt * expm1(-2.0 * gamma_xi * h) / mass).sqrt();
            sys.xi() * (1.0 + decay) - decay * g / (mass * gamma_xi) + std * r
        }
    };
    // Non-finite only when the momenta are: the guarded step reports that as a blow-up.
    let _ = sys.set_xi(xi);
}

/// The sum `G` of [`xi_update`], per pair `gamma_ij w_D (u_ij^2 - kbt mu_ij)`.
#[inline(always)]
fn feedback(sys: &mut System, friction: impl Friction, kbt: f64) -> f64 {
    let shifted = sys.shifted_pairs();
    let state = sys.pair_state(0);
    let particles = Particles::new(state.inv_mass, state.kind, state.params.coefficients());
    let visit = move |ends: Ends, two: Two<Vec3>, _: f64, dvx: f64| {
        let (pi, pj) = two.split();
        let (pair, (mi, mj)) = (ends.pair(), ends.inv_masses());
        let u = match shifted {
            true => pair.normal_velocity::<true>(*pi * mi, *pj * mj, dvx),
            false => pair.normal_velocity::<false>(*pi * mi, *pj * mj, dvx),
        };
        let gamma = friction.of(ends).0;
        Sum(gamma * pair.wr * pair.wr * (u * u - kbt * (mi + mj)))
    };
    let order = SweepOrder::Forward;
    let sum: Sum = state
        .pairs
        .sweep_noisy(order, None, particles, state.p, visit);
    sum.0
}

/// A sum over pairs, added in the engine's fixed order (its [`Virial`] fold).
#[derive(Clone, Copy, Default)]
struct Sum(f64);

impl Virial for Sum {
    #[inline(always)]
    fn of(_: &Pair, _: impl FnOnce() -> f64, f: f64) -> Self {
        Sum(f)
    }
    #[inline(always)]
    fn add(self, other: Self) -> Self {
        Sum(self.0 + other.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::flow::ou_update;

    /// At `xi = 1` the adaptive update is O's (to rounding); at `xi = 0` it is the pure noise
    /// kick `sigma w_R mu sqrt(h) R`; at `xi < 0` it amplifies `u`.
    #[test]
    fn the_update_at_known_frictions() {
        let (gamma, kbt, h, wr, mu, r): (f64, f64, f64, f64, f64, f64) =
            (4.5, 1.0, 0.05, 0.7, 2.0, 0.3);
        let sigma = (2.0 * gamma * kbt).sqrt();
        let (a, o) = (
            adaptive_ou_update(gamma, sigma, h, wr, mu, r),
            ou_update(gamma, kbt, h, wr, mu, r),
        );
        assert!((a.slope - o.slope).abs() < 1e-15, "{a:?} {o:?}");
        assert!(
            (a.offset - o.offset).abs() < 1e-14 * o.offset.abs(),
            "{a:?} {o:?}"
        );
        let frozen = adaptive_ou_update(0.0, sigma, h, wr, mu, r);
        assert_eq!(frozen.slope, 0.0);
        let kick = sigma * wr * mu * h.sqrt() * r / mu;
        assert!((frozen.offset - kick).abs() < 1e-15, "{frozen:?} {kick}");
        assert!(adaptive_ou_update(-gamma, sigma, h, wr, mu, r).slope > 0.0);
    }
}
