//! Velocity Verlet and ABOBA at dt = 0.01 sample k_B T = 1 on the standard box.
use super::common;

use dpd_core::observe::{thermo, ThermoAverages};
use dpd_core::reference::{Aboba, VelocityVerlet};
use dpd_core::Scheme;

fn averages<S: Scheme>(scheme: &S, seed: u64) -> dpd_core::observe::ThermoSummary {
    let dt = 0.01;
    let mut sys = common::standard_box(4.5, dt, seed);
    // 10 time units of equilibration (the soft fluid relaxes in ~1), then 100 sampled every
    // 10 steps, measured at the end of full steps.
    let steps = 11_000;
    let mut avg = ThermoAverages::new(steps, 10.0 / 11.0).unwrap();
    for _ in 0..steps / 10 {
        sys.advance(scheme, 10).unwrap();
        if avg.wants(sys.step()) {
            avg.record(&thermo(&mut sys));
        }
    }
    avg.summary()
}

#[test]
fn vv_and_aboba_sample_the_target_temperature() {
    // T_K of one sample of N = 500 fluctuates by sqrt(2/1497) = 3.7 %; 1000 samples, of which
    // ~200 are independent (correlation time ~0.5), give a standard error ~0.3 %, so the 1 %
    // tolerance is three standard errors beyond the small dt = 0.01 bias of either scheme.
    for (name, s) in [
        ("vv", averages(&VelocityVerlet, 2)),
        ("aboba", averages(&Aboba, 1)),
    ] {
        println!("{name}: {s:?}");
        assert!(
            (s.kinetic_temperature - 1.0).abs() < 0.01,
            "{name} T_K {s:?}"
        );
        assert!(
            (s.configurational_temperature - 1.0).abs() < 0.01,
            "{name} T_C {s:?}"
        );
    }
}
