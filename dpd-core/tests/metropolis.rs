//! Metropolis-adjusted steps (`{...}`, generalised hybrid Monte Carlo): the Gibbs measure
//! exactly at a step where the unadjusted scheme is far off, the unadjusted trajectory while
//! every proposal is accepted, the same bits on any thread count, and what such a step needs.
use super::common;

use dpd_core::observe::{block_mean, kinetic_temperature, thermo, EnergyBalance};
use dpd_core::{AdvanceError, DynScheme, Params, Scheme, System, Vec3};

/// Velocity Verlet in braces, then the exact O sweep (the registry's `ghmc`).
const GHMC: &str = "{B(1/2) A B(1/2)} O";
/// The same step unadjusted.
const PLAIN: &str = "B(1/2) A B(1/2) O";

fn compiled(source: &str) -> DynScheme {
    DynScheme::compile(source, source, &Default::default()).unwrap()
}

/// `n` particles at density 3 (a = 25, k_B T = 1, gamma = 4.5), relaxed by 500 ABOBA steps at
/// dt = 0.02, then at `dt`.
fn relaxed(n: usize, dt: f64, seed: u64) -> System {
    let mut sys = common::system(n, 3.0, Params::builder().gamma(4.5), 0.02, seed);
    sys.advance(&compiled("ABOBA"), 500).unwrap();
    sys.set_dt(dt).unwrap();
    sys
}

/// Means with block errors (20 blocks) after `skip` steps, over the next `steps`:
/// `[k_B T_K, k_B T_C]`, T_C as the ratio of the mean numerator and denominator.
fn temperatures(sys: &mut System, scheme: &dyn Scheme, skip: u64, steps: u64) -> [(f64, f64); 2] {
    sys.advance(scheme, skip).unwrap();
    let (mut tk, mut num, mut den) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..steps {
        sys.advance(scheme, 1).unwrap();
        let t = thermo(sys);
        tk.push(kinetic_temperature(sys));
        num.push(t.config_numerator);
        den.push(t.config_denominator);
    }
    let mean = |v: &[f64]| block_mean(v, 20).unwrap();
    let ((n, n_err), (d, d_err)) = (mean(&num), mean(&den));
    let tc = n / d;
    [
        mean(&tk),
        (tc, tc * ((n_err / n).powi(2) + (d_err / d).powi(2)).sqrt()),
    ]
}

/// At dt = 0.06 (N = 250, gamma = 4.5), where the unadjusted step's k_B T_C is 1.114 +- 0.004
/// (+11 %), the adjusted step samples the Gibbs measure: measured k_B T_C 1.003 +- 0.007 and
/// k_B T_K 1.002 +- 0.005 over 3000 steps, 40 % of the proposals accepted. The bounds, 0.025
/// and 0.02, are about 3.5 and 4 block errors. The wrong variants, run once each: without the
/// momentum flip on rejection k_B T_C came out 1.042 +- 0.008 (the chain is no longer reversible
/// and its measure not Gibbs), with the sign of Delta H reversed 1.268 +- 0.012; both fail here,
/// as does the unadjusted step.
#[test]
fn the_gibbs_measure_is_sampled_where_the_unadjusted_step_is_off_by_ten_percent() {
    let [(tk, tk_err), (tc, tc_err)] =
        temperatures(&mut relaxed(250, 0.06, 3), &compiled(GHMC), 100, 3000);
    assert!((tc - 1.0).abs() < 0.025, "k_B T_C {tc} +- {tc_err}");
    assert!((tk - 1.0).abs() < 0.02, "k_B T_K {tk} +- {tk_err}");
    let mut plain = relaxed(250, 0.06, 3);
    let [_, (tc, tc_err)] = temperatures(&mut plain, &compiled(PLAIN), 100, 1000);
    assert!(tc - 1.0 > 0.08, "unadjusted k_B T_C {tc} +- {tc_err}");
}

/// At a small step (dt = 0.002, |Delta H| ~ 1e-4) every proposal is accepted, and the adjusted
/// step is the unadjusted one bit for bit: the braces change nothing but what they test (the
/// accept/reject draws from a stream of its own, O keeps its noise). At dt = 0.06 some
/// proposals are rejected (the acceptance count says how many) and the trajectories part.
#[test]
fn while_every_proposal_is_accepted_the_trajectory_is_the_unadjusted_one() {
    let (mut adjusted, mut plain) = (relaxed(250, 0.002, 5), relaxed(250, 0.002, 5));
    adjusted.advance(&compiled(GHMC), 200).unwrap();
    plain.advance(&compiled(PLAIN), 200).unwrap();
    let a = adjusted.acceptance();
    assert_eq!((a.proposed, a.accepted), (200, 200));
    assert!(common::same_bits(&adjusted, &plain));
    let (mut adjusted, mut plain) = (relaxed(250, 0.06, 5), relaxed(250, 0.06, 5));
    adjusted.advance(&compiled(GHMC), 20).unwrap();
    plain.advance(&compiled(PLAIN), 20).unwrap();
    let a = adjusted.acceptance();
    assert!(a.accepted < a.proposed && a.proposed == 20, "{a:?}");
    assert!(!common::same_bits(&adjusted, &plain));
    assert_eq!(a.rate(), Some(a.accepted as f64 / 20.0));
}

/// The accept/reject is keyed by seed, step and part, and the energy summed in the pair
/// table's fixed order: the same bits and the same acceptance on 1, 2, 3 and 5 threads (N =
/// 3000, relaxed, dt = 0.04, where some proposals are rejected), with one or two adjusted
/// parts.
#[test]
fn the_same_bits_on_any_thread_count() {
    for source in [
        GHMC,
        "{A(1/4) B(1/2) A(1/4)} O(1/2) {A(1/4) B(1/2) A(1/4)} O(1/2)",
    ] {
        let scheme = compiled(source);
        let runs: Vec<System> = [1, 2, 3, 5]
            .into_iter()
            .map(|t| {
                common::with_threads(t, || {
                    let mut sys = relaxed(3000, 0.04, 17);
                    sys.advance(&scheme, 40).unwrap();
                    sys
                })
            })
            .collect();
        let a = runs[0].acceptance();
        assert!(0 < a.accepted && a.accepted < a.proposed, "{source}: {a:?}");
        for run in &runs[1..] {
            assert!(common::same_bits(&runs[0], run), "{source}");
            assert_eq!(run.acceptance(), a, "{source}");
        }
    }
}

/// A checkpoint carries the acceptance counts, and a restarted run continues bit for bit.
#[test]
fn a_restart_continues_bit_for_bit_with_its_counts() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("ghmc.chk");
    let scheme = compiled(GHMC);
    let mut sys = relaxed(250, 0.06, 7);
    sys.advance(&scheme, 15).unwrap();
    sys.save_checkpoint(&path, GHMC).unwrap();
    let (mut back, name) = System::load_checkpoint(&path).unwrap();
    assert_eq!((name.as_str(), back.acceptance()), (GHMC, sys.acceptance()));
    sys.advance(&scheme, 15).unwrap();
    back.advance(&scheme, 15).unwrap();
    assert!(common::same_bits(&sys, &back));
    assert_eq!(back.acceptance(), sys.acceptance());
}

/// The accept/reject needs the energy of an equilibrium system: a body force is refused by
/// name before the first step, and so is the energy balance (heat and shadow work) of an
/// adjusted scheme.
#[test]
fn what_an_adjusted_step_needs_is_named() {
    let scheme = compiled(GHMC);
    let params = Params::builder().gamma(4.5).build().unwrap();
    let mut pushed = dpd_core::init::equilibrium_box(params, 250, 3.0, 3)
        .unwrap()
        .body_force(Vec3::new(0.1, 0.0, 0.0))
        .build()
        .unwrap();
    match pushed.advance(&scheme, 1) {
        Err(AdvanceError::Scheme(e)) => {
            let text = e.to_string();
            assert!(
                text.contains("body_force") && text.contains("Metropolis-adjusted"),
                "{text}"
            );
        }
        other => panic!("{other:?}"),
    }
    let mut sys = relaxed(250, 0.02, 3);
    let Err(e) = EnergyBalance::start(&mut sys, &scheme) else {
        panic!("the energy balance of {GHMC} was accepted");
    };
    assert!(e.to_string().contains("Metropolis-adjusted"), "{e}");
}
