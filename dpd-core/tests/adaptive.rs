//! The pairwise adaptive Langevin thermostat (letters Oa and Xi, PAdL): its invariant measure
//! (xi Gaussian around 1 with variance k_B T / mu, k_B T_K = k_B T), its claim (the kinetic
//! temperature held at a step where ABOBA's drifts), and what it needs; the same for the
//! pairwise Nose-Hoover-Langevin thermostat (On and Xi with a thermostat friction, PNHL: xi
//! around 0).
use super::common;

use dpd_core::observe::{block_mean, kinetic_temperature};
use dpd_core::reference::Aboba;
use dpd_core::{AdvanceError, DynScheme, Params, Scheme, System};

/// PAdL in the ordering of BAOAB, xi updated around the adaptive sweep.
const PADL: &str = "B A Xi(1/2) Oa Xi(1/2) A B";

fn compiled(source: &str) -> DynScheme {
    DynScheme::compile(source, source, &Default::default()).unwrap()
}

/// PNHL in the same ordering, the pair sweep without noise.
const PNHL: &str = "B A Xi(1/2) On Xi(1/2) A B";

/// `n` particles at density 3 (a = 25, k_B T = 1) at friction `gamma` with thermostat mass
/// `mu`.
fn adaptive_box(n: usize, gamma: f64, mu: f64, dt: f64, seed: u64) -> System {
    let params = Params::builder().gamma(gamma).thermostat_mass(mu);
    common::system(n, 3.0, params, dt, seed)
}

/// On `sys` run by `scheme` for 200 time units at dt = 0.01 after 20: xi's mean, its variance
/// around `centre` and k_B T_K, each with its standard error (20 blocks).
fn moments(mut sys: System, scheme: &str, centre: f64) -> [(f64, f64); 3] {
    let (xi, tk) = series(&mut sys, &compiled(scheme), 2000, 20_000);
    let squares: Vec<f64> = xi.iter().map(|x| (x - centre) * (x - centre)).collect();
    [&xi, &squares, &tk].map(|v| block_mean(v, 20).unwrap())
}

/// After `skip` steps, per step of the next `steps`: xi and k_B T_K.
fn series(sys: &mut System, scheme: &dyn Scheme, skip: u64, steps: u64) -> (Vec<f64>, Vec<f64>) {
    sys.advance(scheme, skip).unwrap();
    let (mut xi, mut tk) = (Vec::new(), Vec::new());
    for _ in 0..steps {
        sys.advance(scheme, 1).unwrap();
        xi.push(sys.xi());
        tk.push(kinetic_temperature(sys));
    }
    (xi, tk)
}

/// The invariant density `exp(-H / kT) exp(-mu (xi - 1)^2 / (2 kT))` (flow/adaptive.rs): xi has
/// mean 1 and variance kT / mu = 0.04, and k_B T_K = k_B T. N = 250, gamma = 4.5, mu = 25, at
/// dt = 0.01 (short against xi's oscillation, whose frequency grows as sqrt(gamma^2 N / mu):
/// mu = 1 at N = 500 blew up at dt = 0.02), 200 time units after 20. Measured over 300 units:
/// xi 1.0006 +- 0.0032, variance 0.0381 +- 0.0013, k_B T_K 0.9989 +- 0.0013; the bounds below
/// are about 3 standard errors of 200 units (0.02, 12 %, 0.5 %). A factor missing from the
/// feedback (gamma, the weight, the reduced mass 2) changes the variance by that factor, a
/// wrong sign sends xi away.
#[test]
fn xi_and_the_kinetic_temperature_sample_their_invariant_measure() {
    let sys = adaptive_box(250, 4.5, 25.0, 0.01, 3);
    let [(mean, mean_err), (var, var_err), (t, t_err)] = moments(sys, PADL, 1.0);
    assert!((mean - 1.0).abs() < 0.02, "xi {mean} +- {mean_err}");
    assert!((var / 0.04 - 1.0).abs() < 0.12, "var {var} +- {var_err}");
    assert!((t - 1.0).abs() < 0.005, "kT_K {t} +- {t_err}");
}

/// PAdL's claim: the feedback holds the pairs' kinetic temperature where a fixed friction
/// cannot. At dt = 0.12, gamma = 4.5 (N = 250, mu = 200, 150 time units after 30), in the same
/// box: measured k_B T_K 1.66 +- 0.01 for ABOBA, 1.36 for PAdL in ABOBA's ordering, 0.79 in
/// BAOAB's. Both adaptive errors must stay below 3/4 of ABOBA's (a loose bound: the feedback
/// sets the mean of sum gamma w_D (u^2 - kT mu_ij) at the Xi stages, not T_K at the step's end).
#[test]
fn the_kinetic_temperature_stays_closer_to_k_b_t_than_abobas() {
    let dt = 0.12;
    let error = |scheme: &dyn Scheme| {
        let mut sys = adaptive_box(250, 4.5, 200.0, dt, 5);
        let (_, tk) = series(&mut sys, scheme, 250, 1250);
        (tk.iter().sum::<f64>() / tk.len() as f64 - 1.0).abs()
    };
    let aboba = error(&Aboba);
    for padl in [PADL, "A(1/2) B(1/2) Xi(1/2) Oa Xi(1/2) B(1/2) A(1/2)"] {
        let e = error(&compiled(padl));
        assert!(e < 0.75 * aboba, "{padl}: |T_K - 1| {e}, ABOBA's {aboba}");
    }
}

/// A scheme with Xi needs the thermostat mass, and says so by name; Oa at xi = 1 with a
/// frozen xi is not a scheme (the language refuses Oa without Xi).
#[test]
fn a_scheme_with_xi_needs_a_thermostat_mass() {
    let mut sys = common::standard_box(4.5, 0.04, 1);
    match sys.advance(&compiled(PADL), 1) {
        Err(AdvanceError::Scheme(e)) => {
            assert_eq!(e.field, "thermostat_mass", "{e}");
            assert!(e.to_string().contains("has Xi"), "{e}");
        }
        other => panic!("{other:?}"),
    }
    let e = DynScheme::compile("BAOaAB", "BAOaAB", &Default::default()).unwrap_err();
    assert!(format!("{e:?}").contains("Oa needs an Xi stage"), "{e:?}");
}

/// PNHL's invariant density `exp(-H / kT) exp(-mu xi^2 / (2 kT))` (flow/adaptive.rs): xi has
/// mean 0 and variance kT / mu = 0.04, and k_B T_K = k_B T, though no pair draws noise: the
/// Langevin part of xi (gamma_xi = 1) is the only noise. Same box, step and length as PAdL's
/// test above, xi starting at 0. Measured: xi -0.0001 +- 0.0009, variance 0.0401 +- 0.0021,
/// k_B T_K 0.9991 +- 0.0020; the bounds are 2.5 to 3 standard errors. A feedback of the wrong sign sends xi away, a missing factor
/// 2 in the noise of xi doubles the variance, an OU centred on 1 (PAdL's) moves the mean by 1.
#[test]
fn pnhl_samples_its_invariant_measure_with_the_noise_on_xi_alone() {
    let params = Params::builder()
        .thermostat_mass(25.0)
        .thermostat_friction(1.0);
    let sys = common::system(250, 3.0, params, 0.01, 3);
    let [(mean, mean_err), (var, var_err), (t, t_err)] = moments(sys, PNHL, 0.0);
    assert!(mean.abs() < 0.02, "xi {mean} +- {mean_err}");
    assert!((var / 0.04 - 1.0).abs() < 0.15, "var {var} +- {var_err}");
    assert!((t - 1.0).abs() < 0.005, "kT_K {t} +- {t_err}");
}

/// PNHL's pair sweep conserves momentum to rounding (500 steps, xi of either sign).
#[test]
fn pnhl_conserves_momentum() {
    let params = Params::builder()
        .thermostat_mass(25.0)
        .thermostat_friction(1.0);
    let mut sys = common::system(250, 3.0, params, 0.01, 7);
    let p0 = sys.total_momentum();
    sys.advance(&compiled(PNHL), 500).unwrap();
    let scale: f64 = sys.momenta().iter().map(|p| p.norm()).sum();
    let drift = (sys.total_momentum() - p0).norm() / scale;
    assert!(drift < 1e-13, "relative momentum change {drift:e}");
}

/// On needs the thermostat friction (its only noise), Oa refuses it (PAdL's xi centres on 1),
/// and each says so by name.
#[test]
fn pnhl_and_padl_name_the_thermostat_friction() {
    let params = Params::builder().thermostat_mass(25.0);
    let mut sys = common::system(250, 3.0, params.clone(), 0.01, 1);
    let mut with = common::system(250, 3.0, params.thermostat_friction(1.0), 0.01, 1);
    for (sys, scheme, says) in [
        (&mut sys, PNHL, "has On"),
        (&mut with, PADL, "has Oa (PAdL), whose xi centres on 1"),
    ] {
        match sys.advance(&compiled(scheme), 1) {
            Err(AdvanceError::Scheme(e)) => {
                assert_eq!(e.field, "thermostat_friction", "{e}");
                assert!(e.to_string().contains(says), "{e}");
            }
            other => panic!("{scheme}: {other:?}"),
        }
    }
}
