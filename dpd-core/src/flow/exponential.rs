use crate::pairs::Noise;
use crate::pairs::PairTable;
use crate::params::Params;
use crate::rng::pair_normal;
use crate::system::{PairState, System};
use crate::{Tensor, Vec3};

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
/// `g = (F^C_i + F^D_i + F^ext)_alpha / m_i` is the whole deterministic acceleration at the
/// start of the step (`F^ext`: the body force on a mobile particle, if any), and
/// `b xi = (1/m_i) sum_j sigma w_R e_ij,alpha xi_ij`. Its solution over `h` simplifies exactly
/// (`exp(-x) u + (a/c)(1 - exp(-x)) = u + h phi1(x) g`, `x = c h`) to
///
/// ```text
/// SETD  (EtdNoise::Exact):  u_new = u + h phi1(c h) g + sqrt(h phi1(2 c h)) b xi
/// MSETD (EtdNoise::Frozen): u_new = u + h phi1(c h) g + sqrt(h) phi1(c h)   b xi
/// ```
///
/// which never divides by `c` and reduces to Euler-Maruyama `u + g h + sqrt(h) b xi` for
/// `c -> 0` (a particle without neighbours, or `gamma = 0`).
///
/// The body force is part of `a`, like every force the equation freezes: in a steady flow the
/// mean of `phi1 (F^D + F^ext)` vanishes, so the friction balances the body force; a separate
/// kick `h F^ext` after the update would instead need a friction `F^ext / phi1(c h)`. In the
/// Poiseuille channel of `dpd-schemes/tests/exponential_flows.rs` (`c dt ~ 1.9`) the mean flow
/// of SETD was 22 % below ABOBA's with the force inside and 33 % above it with a separate kick.
///
/// `xi_ij = xi_ji` is one standard normal per pair, keyed by `(seed, step, stream, i, j)`, and
/// enters both particles with opposite signs; the pair forces are antisymmetric as well. The
/// factors `phi1(c h)` differ between particles, though, so total momentum is conserved only
/// on average, not exactly (it is exactly for `c h -> 0`). A uniform translation of all
/// velocities is left unchanged (Galilean invariance).
///
/// While the system records pair impulses for the stress, each pair adds the virial
/// `q_ij (x) (Delta p_ij - h F^C_ij)` (the conservative part at the start of the step left
/// out, as in the T sweep). The update is not pairwise: particle `i` receives
/// `h phi1(c_i h) F_ij + s_i sigma w_R xi_ij e_ij` from pair `(i, j)` per component (`s_i` the
/// noise factor above) and `j` the opposite with its own factors. The recorded pair impulse
/// `Delta p_ij` uses the mean of the two particles' factors per component, which is exact when
/// their rates agree and for `c h -> 0`; the momentum the two updates do not balance is not
/// counted.
///
/// Costs one pair-geometry evaluation (cached) and one force evaluation: the conservative,
/// dissipative and random pair forces and the rates `c` are summed in one pass over the pairs
/// (recording adds a second pass). For `h <= 0` the noise is dropped (there is no
/// backward-in-time stochastic update).
pub fn exponential_velocity(sys: &mut System, h: f64, stream: u8, noise: EtdNoise) {
    sys.count_force_evaluation();
    // Pairs across a Lees-Edwards boundary or with a moving wall particle carry a velocity
    // shift (`PairTable::shifts`).
    let shifted = sys.shifted_pairs();
    let recording = sys.recording_impulses();
    let PairState {
        pairs,
        p,
        inv_mass,
        kind,
        params,
        noise: Noise { seed, step, id, .. },
        body_force,
    } = sys.pair_state(stream);
    let n = p.len();
    // force: F^C + F^D (+ F^ext); rate: sum gamma w_D e_alpha^2 (divided by m_i below);
    // kick: sum sigma w_R e xi; per pair, while recording: the dissipative and random scalars.
    let mut force = vec![Vec3::zeros(); n];
    let mut rate = vec![Vec3::zeros(); n];
    let mut kick = vec![Vec3::zeros(); n];
    let mut pair_forces = Vec::with_capacity(if recording { pairs.len() } else { 0 });
    let shifts = pairs.shifts();
    for (k, pair) in pairs.iter().enumerate() {
        let dvx = shifts.map_or(0.0, |s| s[k]);
        let (i, j) = (pair.i as usize, pair.j as usize);
        let (gamma, sigma) = params.friction(kind[i], kind[j]);
        let wd = pair.wr * pair.wr;
        let (vi, vj) = (p[i] * inv_mass[i], p[j] * inv_mass[j]);
        let u = if shifted {
            pair.normal_velocity::<true>(vi, vj, dvx)
        } else {
            pair.normal_velocity::<false>(vi, vj, dvx)
        };
        let dissipative = -gamma * wd * u;
        let f = (params.soft(kind[i], kind[j]).force(pair.w) + dissipative) * pair.e;
        force[i] += f;
        force[j] -= f;
        let r = (gamma * wd) * pair.e.component_mul(&pair.e);
        rate[i] += r;
        rate[j] += r;
        let random = if sigma > 0.0 {
            let random = sigma * pair.wr * pair_normal(seed, step, stream, id[i], id[j]);
            let k = random * pair.e;
            kick[i] += k;
            kick[j] -= k;
            random
        } else {
            0.0
        };
        if recording {
            pair_forces.push([dissipative, random]);
        }
    }
    if let Some(g) = body_force {
        for (f, &im) in force.iter_mut().zip(inv_mass.iter()) {
            if im > 0.0 {
                *f += g;
            }
        }
    }
    let factors = |i: usize| Factors::new(rate[i] * inv_mass[i], h, noise);
    let virial = recording.then(|| pair_virial(pairs, &pair_forces, params, kind, h, factors));
    for (i, p) in p.iter_mut().enumerate() {
        let c = factors(i);
        // Momentum form: p = m u, so the 1/m_i of g and b cancels.
        *p += c.drift.component_mul(&force[i]) + c.spread.component_mul(&kick[i]);
    }
    if let Some(virial) = virial {
        sys.record_impulses(virial);
    }
}

/// Per-component factors of one particle's update: `h phi1(c h)` on the deterministic force
/// and the noise factor on the random one.
struct Factors {
    drift: Vec3,
    spread: Vec3,
}

impl Factors {
    /// From the rates `c` (per unit time, already divided by the mass) over a step `h`.
    #[inline(always)]
    fn new(c: Vec3, h: f64, noise: EtdNoise) -> Self {
        let root_h = h.max(0.0).sqrt();
        let x = c * h;
        Factors {
            drift: x.map(|x| h * phi1(x)),
            spread: x.map(|x| match noise {
                EtdNoise::Exact => (h * phi1(2.0 * x)).max(0.0).sqrt(),
                EtdNoise::Frozen => root_h * phi1(x),
            }),
        }
    }
}

/// `sum_pairs q_ij (x) (Delta p_ij - h F^C_ij)` with the pair impulse `Delta p_ij` taken with
/// the mean of the two particles' factors (see [`exponential_velocity`]); `pair_forces` holds
/// each pair's dissipative and random scalars along `e_ij`.
fn pair_virial(
    pairs: &PairTable,
    pair_forces: &[[f64; 2]],
    params: &Params,
    kind: &[u16],
    h: f64,
    factors: impl Fn(usize) -> Factors,
) -> Tensor {
    pairs
        .iter()
        .zip(pair_forces)
        .map(|(pair, &[dissipative, random])| {
            let (ci, cj) = (factors(pair.i as usize), factors(pair.j as usize));
            let (ti, tj) = (kind[pair.i as usize], kind[pair.j as usize]);
            let soft = params.soft(ti, tj);
            let conservative = soft.force(pair.w);
            let drift = 0.5 * (ci.drift + cj.drift);
            let spread = 0.5 * (ci.spread + cj.spread);
            let impulse = ((conservative + dissipative) * drift + random * spread
                - Vec3::repeat(h * conservative))
            .component_mul(&pair.e);
            (pair.r(params.rc_of(ti, tj)) * pair.e) * impulse.transpose()
        })
        .sum()
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
    fn without_friction_the_body_force_is_a_plain_kick() {
        // c = 0: the update is `p += h (F^C + g)`, the B kick with its body force, to rounding.
        let g = Vec3::new(0.5, -0.25, 0.125);
        let with_force = |sys: System| {
            let q = sys.positions().to_vec();
            System::builder(sys.params().clone(), *sys.boundary(), q)
                .momenta(sys.momenta().to_vec())
                .body_force(g)
                .build()
                .unwrap()
        };
        let (mut a, mut b) = (with_force(system(0.0)), with_force(system(0.0)));
        exponential_velocity(&mut a, 0.01, 0, EtdNoise::Frozen);
        kick(&mut b, 0.01);
        for (pa, pb) in a.momenta().iter().zip(b.momenta()) {
            assert!((pa - pb).norm() < 1e-13, "{pa} vs {pb}");
        }
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
