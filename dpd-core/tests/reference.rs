//! The run-time stage interpreter reproduces the hand-written reference steps bit for bit, and
//! the evaluation counters match the costs the scheme language promises.
use super::common;

use dpd_core::reference::{Aboba, DpdS1, VelocityVerlet};
use dpd_core::{DynScheme, Scheme};

fn compiled(source: &str) -> DynScheme {
    DynScheme::compile(source, source, &Default::default()).unwrap()
}

fn run(scheme: &dyn Scheme, steps: u64) -> dpd_core::System {
    let mut sys = common::standard_box(4.5, 0.05, 4);
    sys.advance(scheme, steps).unwrap();
    sys
}

#[test]
fn interpreter_matches_reference_steps_bitwise() {
    let cases: [(&dyn Scheme, &str); 3] = [
        (&VelocityVerlet, "F(1/2) A F(1/2)"),
        (&DpdS1, "ObBAB"),
        (&Aboba, "ABOBA"),
    ];
    for (reference, source) in cases {
        let dynamic = compiled(source);
        let a = run(reference, 1000);
        let b = run(&dynamic, 1000);
        assert!(common::same_bits(&a, &b), "{}", reference.name());
        // The counters of the run agree with the costs the language promises.
        let mut sys = common::standard_box(4.5, 0.05, 4);
        sys.advance(&dynamic, 1).unwrap();
        let before = sys.counters();
        sys.advance(&dynamic, 10).unwrap();
        let program = dynamic.program().unwrap();
        let after = sys.counters();
        assert_eq!(
            after.force_evaluations - before.force_evaluations,
            10 * program.force_evaluations_per_step() as u64,
            "{source}"
        );
        assert_eq!(
            after.pair_distance_evaluations - before.pair_distance_evaluations,
            10 * program.pair_distance_evaluations_per_step() as u64,
            "{source}"
        );
    }
}

#[test]
fn reference_steps_cost_one_evaluation_per_step() {
    for scheme in [&VelocityVerlet as &dyn Scheme, &DpdS1, &Aboba] {
        let mut sys = common::standard_box(4.5, 0.05, 4);
        sys.advance(scheme, 1).unwrap();
        let before = sys.counters();
        sys.advance(scheme, 100).unwrap();
        let after = sys.counters();
        assert_eq!(
            after.force_evaluations - before.force_evaluations,
            100,
            "{}",
            scheme.name()
        );
        assert_eq!(
            after.pair_distance_evaluations - before.pair_distance_evaluations,
            100,
            "{}",
            scheme.name()
        );
    }
}
