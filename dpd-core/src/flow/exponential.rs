use crate::rng::pair_normal;
use crate::system::System;
use crate::Vec3;

/// How [`exponential_velocity`] integrates the random force over the step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EtdNoise {
    /// SETD: the exact Ornstein-Uhlenbeck variance of the frozen linear equation,
    /// `(1 - exp(-2 c h)) / (2 c)` per unit `b^2`.
    Exact,
    /// MSETD: the random force treated like the deterministic one, a constant over the step:
    /// variance `(1 - exp(-c h))^2 / (c^2 h)`.
    Frozen,
}

/// `phi1(x) = (1 - exp(-x)) / x`, `phi1(0) = 1`, without cancellation for small `x`.
#[inline(always)]
fn phi1(x: f64) -> f64 {
    if x == 0.0 {
        1.0
    } else {
        -(-x).exp_m1() / x
    }
}

/// Per-particle exponential-time-differencing velocity update of SETD / MSETD
/// (algorithms.md section 5); positions are not moved.
///
/// For particle `i` and Cartesian component `alpha`, with `u = v_i,alpha`, the frozen linear
/// equation `du/dt + c u = a + b xi` has
/// `c = (1/m_i) sum_j gamma w_D e_ij,alpha^2`, `a = g + c u` where
/// `g = (F^C_i + F^D_i)_alpha / m_i` is the whole deterministic acceleration at the start of the
/// step, and `b xi = (1/m_i) sum_j sigma w_R e_ij,alpha xi_ij`. Its solution over `h` simplifies
/// exactly (`exp(-x) u + (a/c)(1 - exp(-x)) = u + h phi1(x) g`, `x = c h`) to
///
/// ```text
/// SETD  (EtdNoise::Exact):  u_new = u + h phi1(c h) g + sqrt(h phi1(2 c h)) b xi
/// MSETD (EtdNoise::Frozen): u_new = u + h phi1(c h) g + sqrt(h) phi1(c h)   b xi
/// ```
///
/// which never divides by `c` and reduces to Euler-Maruyama `u + g h + sqrt(h) b xi` for
/// `c -> 0` (a particle without neighbours, or `gamma = 0`).
///
/// `xi_ij = xi_ji` is one standard normal per pair, keyed by `(seed, step, stream, i, j)`, and
/// enters both particles with opposite signs; the pair forces are antisymmetric as well. The
/// factors `phi1(c h)` differ between particles, though, so total momentum is conserved only
/// on average, not exactly (it is exactly for `c h -> 0`). A uniform translation of all
/// velocities is left unchanged (Galilean invariance).
///
/// Costs one pair-geometry evaluation (cached) and one force evaluation: the conservative,
/// dissipative and random pair forces and the rates `c` are summed in one pass over the pairs.
/// For `h <= 0` the noise is dropped (there is no backward-in-time stochastic update).
pub fn exponential_velocity(sys: &mut System, h: f64, stream: u8, noise: EtdNoise) {
    sys.ensure_pairs();
    sys.counters.force_evaluations += 1;
    // Pairs across a Lees-Edwards boundary or with a moving wall particle carry a velocity
    // shift (`Pair::dvx`).
    let shifted = sys.shifted_pairs();
    let System {
        ref pairs,
        ref mut p,
        ref inv_mass,
        ref kind,
        ref params,
        seed,
        step,
        ..
    } = *sys;
    let n = p.len();
    let (gamma, sigma) = (params.gamma(), params.sigma());
    // force: F^C + F^D; rate: sum gamma w_D e_alpha^2 (divided by m_i below); kick: sum sigma w_R e xi.
    let mut force = vec![Vec3::zeros(); n];
    let mut rate = vec![Vec3::zeros(); n];
    let mut kick = vec![Vec3::zeros(); n];
    for pair in pairs {
        let (i, j) = (pair.i as usize, pair.j as usize);
        let wd = pair.wr * pair.wr;
        let (vi, vj) = (p[i] * inv_mass[i], p[j] * inv_mass[j]);
        let u = if shifted {
            pair.normal_velocity::<true>(vi, vj)
        } else {
            pair.normal_velocity::<false>(vi, vj)
        };
        let f = (params.a(kind[i], kind[j]) * pair.w - gamma * wd * u) * pair.e;
        force[i] += f;
        force[j] -= f;
        let r = (gamma * wd) * pair.e.component_mul(&pair.e);
        rate[i] += r;
        rate[j] += r;
        if sigma > 0.0 {
            let k = (sigma * pair.wr * pair_normal(seed, step, stream, pair.i, pair.j)) * pair.e;
            kick[i] += k;
            kick[j] -= k;
        }
    }
    let root_h = h.max(0.0).sqrt();
    for i in 0..n {
        let im = inv_mass[i];
        for alpha in 0..3 {
            let x = rate[i][alpha] * im * h;
            let drift = h * phi1(x) * force[i][alpha];
            let spread = match noise {
                EtdNoise::Exact => (h * phi1(2.0 * x)).max(0.0).sqrt(),
                EtdNoise::Frozen => root_h * phi1(x),
            };
            // Momentum form: p = m u, so the 1/m_i of g and b cancels.
            p[i][alpha] += drift + spread * kick[i][alpha];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::flow::kick;
    use crate::init::{cubic_box, maxwell_momenta, uniform_positions};
    use crate::Params;

    fn system(gamma: f64) -> System {
        let params = Params::builder().gamma(gamma).build().unwrap();
        let bx = cubic_box(200, 3.0).unwrap();
        let q = uniform_positions(&bx, 200, 3);
        System::builder(params, bx, q)
            .momenta(maxwell_momenta(&[1.0; 200], 1.0, 3))
            .seed(3)
            .build()
            .unwrap()
    }

    #[test]
    fn without_friction_it_is_the_conservative_kick_bitwise() {
        // gamma = 0: c = 0, phi1(0) = 1, no noise, and the pair forces are summed in the
        // order of the conservative-force evaluation.
        let (mut a, mut b) = (system(0.0), system(0.0));
        exponential_velocity(&mut a, 0.01, 0, EtdNoise::Exact);
        kick(&mut b, 0.01);
        assert_eq!(a.momenta(), b.momenta());
    }

    #[test]
    fn a_uniform_velocity_is_carried_along_unchanged() {
        // Galilean invariance: the relative velocities, hence every force, are unchanged, and
        // the c u part of a cancels the c u of the decay exactly (in exact arithmetic).
        let shift = Vec3::new(0.3, -1.1, 2.0);
        for noise in [EtdNoise::Exact, EtdNoise::Frozen] {
            let (mut a, mut b) = (system(4.5), system(4.5));
            b.momenta_mut().iter_mut().for_each(|p| *p += shift);
            exponential_velocity(&mut a, 0.05, 1, noise);
            exponential_velocity(&mut b, 0.05, 1, noise);
            for (pa, pb) in a.momenta().iter().zip(b.momenta()) {
                assert!((pb - pa - shift).norm() < 1e-12, "{noise:?}: {pa} vs {pb}");
            }
        }
    }
}
