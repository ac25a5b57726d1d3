//! The run-time stage interpreter reproduces the hand-written reference steps bit for bit, and
//! the evaluation counters match the costs the scheme language promises.
mod common;

use dpd_core::reference::{Aboba, DpdS1, VelocityVerlet};
use dpd_core::{DynScheme, Flow, Scheme, Stage, SweepOrder};
use dpd_ir::Coeff;

fn stages(seq: &[(Flow, f64, u8)]) -> Vec<Stage> {
    seq.iter()
        .map(|&(flow, c, stream)| Stage {
            flow,
            coeff: Coeff {
                value: c,
                exact: None,
            },
            stream,
            order: SweepOrder::Forward,
        })
        .collect()
}

fn run(scheme: &dyn Scheme, steps: u64) -> dpd_core::System {
    let mut sys = common::standard_box(4.5, 0.05, 4);
    sys.advance(scheme, steps).unwrap();
    sys
}

#[test]
fn interpreter_matches_reference_steps_bitwise() {
    let cases: [(&dyn Scheme, Vec<Stage>); 3] = [
        (
            &VelocityVerlet,
            stages(&[(Flow::F, 0.5, 0), (Flow::A, 1.0, 0), (Flow::F, 0.5, 1)]),
        ),
        (
            &DpdS1,
            stages(&[
                (Flow::Bbk, 1.0, 0),
                (Flow::B, 0.5, 0),
                (Flow::A, 1.0, 0),
                (Flow::B, 0.5, 0),
            ]),
        ),
        (
            &Aboba,
            stages(&[
                (Flow::A, 0.5, 0),
                (Flow::B, 0.5, 0),
                (Flow::O, 1.0, 0),
                (Flow::B, 0.5, 0),
                (Flow::A, 0.5, 0),
            ]),
        ),
    ];
    for (reference, seq) in cases {
        let a = run(reference, 300);
        let b = run(&DynScheme::from_stages("dyn", seq), 300);
        assert!(common::same_bits(&a, &b), "{}", reference.name());
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
