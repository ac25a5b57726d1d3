//! Trajectories depend neither on the number of threads nor on whether observables are
//! measured along the way.
mod common;

use dpd_core::observe::thermo;
use dpd_core::reference::{Aboba, DpdS1, VelocityVerlet};
use dpd_core::{Params, Scheme, System};

/// A box large enough (about 20 000 interacting pairs) for the sweeps to run in parallel.
fn big_box() -> System {
    common::system(3000, 3.0, Params::builder(), 0.04, 17)
}

#[test]
fn trajectory_is_identical_for_any_thread_count() {
    for scheme in [&Aboba as &(dyn Scheme + Sync), &DpdS1, &VelocityVerlet] {
        let runs: Vec<System> = [1, 2, 3]
            .iter()
            .map(|&threads| {
                common::with_threads(threads, || {
                    let mut sys = big_box();
                    sys.advance(scheme, 40).unwrap();
                    sys
                })
            })
            .collect();
        assert!(
            common::same_bits(&runs[0], &runs[1]),
            "{}: 1 vs 2 threads",
            scheme.name()
        );
        assert!(
            common::same_bits(&runs[0], &runs[2]),
            "{}: 1 vs 3 threads",
            scheme.name()
        );
    }
}

/// Above 16 384 particles the per-particle loops (binning, permutation, drifts, kicks, the
/// scan's position columns, the blow-up guard) split across threads too.
#[test]
fn large_systems_are_identical_for_any_thread_count() {
    for scheme in [&Aboba as &(dyn Scheme + Sync), &VelocityVerlet] {
        let runs: Vec<System> = [1, 2]
            .iter()
            .map(|&threads| {
                common::with_threads(threads, || {
                    let mut sys = common::system(20_000, 3.0, Params::builder(), 0.04, 5);
                    sys.advance(scheme, 10).unwrap();
                    sys
                })
            })
            .collect();
        assert!(
            common::same_bits(&runs[0], &runs[1]),
            "{}: 1 vs 2 threads",
            scheme.name()
        );
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
