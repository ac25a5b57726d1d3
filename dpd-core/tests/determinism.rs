//! Trajectories depend neither on the number of threads nor on whether observables are
//! measured along the way.
use super::common;

use dpd_core::observe::thermo;
use dpd_core::reference::{Aboba, DpdS1, VelocityVerlet};
use dpd_core::{DynScheme, Params, Scheme, System};

/// `scheme` run for `steps` from `start()` once for each thread count, and every run against
/// the first: the same bits.
fn same_on_any_thread_count(
    scheme: &(dyn Scheme + Sync),
    threads: &[usize],
    start: impl Fn() -> System + Sync,
    steps: u64,
) {
    let runs: Vec<System> = threads
        .iter()
        .map(|&t| {
            common::with_threads(t, || {
                let mut sys = start();
                sys.advance(scheme, steps).unwrap();
                sys
            })
        })
        .collect();
    for (run, t) in runs.iter().zip(threads).skip(1) {
        assert!(
            common::same_bits(&runs[0], run),
            "{}: {} vs {t} threads",
            scheme.name(),
            threads[0]
        );
    }
}

#[test]
fn trajectory_is_identical_for_any_thread_count() {
    // About 20 000 interacting pairs: the sweeps run in parallel, and their runs are grouped
    // differently for each thread count. BAOOAB sweeps the second time in reverse; TAT has
    // the T sweep; B A B O is Peters' scheme (the registry's peters).
    let big_box = || common::system(3000, 3.0, Params::builder(), 0.04, 17);
    let compiled = |source: &str| DynScheme::compile(source, source, &Default::default()).unwrap();
    let (baooab, tat, peters) = (compiled("BAOOAB"), compiled("TAT"), compiled("B A B O"));
    for scheme in [
        &Aboba as &(dyn Scheme + Sync),
        &DpdS1,
        &VelocityVerlet,
        &baooab,
        &tat,
        &peters,
    ] {
        same_on_any_thread_count(scheme, &[1, 2, 3, 5], big_box, 40);
    }
    // Lowe-Andersen collisions (L) draw their own numbers from each pair's key.
    let colliding = || common::system(3000, 3.0, Params::builder().collision_rate(5.0), 0.04, 17);
    let lowe = compiled("A(1/2) B(1/2) L B(1/2) A(1/2)");
    same_on_any_thread_count(&lowe, &[1, 2, 3, 5], colliding, 40);
    // PAdL: xi's feedback is a sum over the pairs, added in the engine's fixed order.
    // mu grows with N: at mu = 5 this box blew up (xi's oscillation outran the step).
    let adaptive = || {
        common::system(
            3000,
            3.0,
            Params::builder().thermostat_mass(200.0),
            0.04,
            17,
        )
    };
    let padl = compiled("B A Xi(1/2) Oa Xi(1/2) A B");
    same_on_any_thread_count(&padl, &[1, 2, 3, 5], adaptive, 40);
    // PNHL: the same sum, and xi's own normal keyed by the step and the Xi stage.
    let pnhl_box = || {
        let params = Params::builder().thermostat_mass(200.0);
        common::system(3000, 3.0, params.thermostat_friction(1.0), 0.04, 17)
    };
    let pnhl = compiled("B A Xi(1/2) On Xi(1/2) A B");
    same_on_any_thread_count(&pnhl, &[1, 2, 3, 5], pnhl_box, 40);
}

/// Above 16 384 particles the per-particle loops (binning, permutation, drifts, kicks, the
/// scan's position columns, the blow-up guard) split across threads too.
#[test]
fn large_systems_are_identical_for_any_thread_count() {
    let large = || common::system(20_000, 3.0, Params::builder(), 0.04, 5);
    for scheme in [&Aboba as &(dyn Scheme + Sync), &VelocityVerlet] {
        same_on_any_thread_count(scheme, &[1, 2], large, 10);
    }
}

#[test]
fn measuring_does_not_change_the_trajectory() {
    for scheme in [&Aboba as &dyn Scheme, &DpdS1, &VelocityVerlet] {
        let mut plain = common::standard_box(4.5, 0.04, 3);
        plain.advance(scheme, 200).unwrap();
        let mut measured = common::standard_box(4.5, 0.04, 3);
        for _ in 0..200 {
            measured.advance(scheme, 1).unwrap();
            thermo(&mut measured);
        }
        assert!(common::same_bits(&plain, &measured), "{}", scheme.name());
    }
}
