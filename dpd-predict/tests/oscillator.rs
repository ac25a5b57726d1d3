//! Known answers on one harmonic oscillator (unit mass, k_B T = 1): the exact stationary
//! variances of the Langevin splittings (Leimkuhler and Matthews, Appl. Math. Res. Express
//! 2013, 34; Molecular Dynamics, Springer 2015, section 7.4) and the Verlet stability limit.

use approx::assert_relative_eq;
use dpd_ir::{Coeff, Flow, Program, Stage, SweepOrder};
use dpd_predict::{stationary_covariance, Mode, Predictor, Spectrum, Stationary, StepMap};

fn program(scheme: &str) -> Program {
    dpd_ir::compile(scheme).expect("scheme compiles")
}

fn covariance(scheme: &str, omega2: f64, gamma: f64, dt: f64) -> nalgebra::Matrix3<f64> {
    let map = StepMap::new(&program(scheme), Mode { omega2, gamma }, dt, 1.0).unwrap();
    match stationary_covariance(&map) {
        Stationary::Covariance(c) => c,
        Stationary::Unstable { radius } => panic!("{scheme} unstable, radius {radius}"),
    }
}

/// BAOAB and ABOBA, observed at the end of their steps, sample x exactly for any friction;
/// with x = (omega h / 2)^2, p has variance 1 - x (BAOAB, BAOOAB) or 1 / (1 - x) (ABOBA).
#[test]
fn baoab_and_aboba_sample_positions_exactly() {
    let p_baoab: fn(f64) -> f64 = |x| 1.0 - x;
    let p_aboba: fn(f64) -> f64 = |x| 1.0 / (1.0 - x);
    for (scheme, p_variance) in [("BAOAB", p_baoab), ("BAOOAB", p_baoab), ("ABOBA", p_aboba)] {
        for (omega2, gamma, dt) in [(100.0, 4.5, 0.08), (100.0, 200.0, 0.15), (1.0, 0.3, 1.5)] {
            let c = covariance(scheme, omega2, gamma, dt);
            let x = omega2 * dt * dt / 4.0;
            assert_relative_eq!(c[(0, 0)], 1.0 / omega2, max_relative = 1e-10);
            assert_relative_eq!(c[(1, 1)], p_variance(x), max_relative = 1e-10);
        }
    }
}

/// Lowe-Andersen collisions have no linear step map: the predictor refuses them by name.
#[test]
fn collisions_are_refused_by_name() {
    let mode = Mode {
        omega2: 100.0,
        gamma: 4.5,
    };
    let e = StepMap::new(&program("B A B L"), mode, 0.05, 1.0).unwrap_err();
    assert!(
        e.to_string().contains("L (Lowe-Andersen collisions)"),
        "{e}"
    );
}

/// The adaptive thermostat's step is not linear: the predictor refuses it by name.
#[test]
fn the_adaptive_thermostat_is_refused_by_name() {
    let mode = Mode {
        omega2: 100.0,
        gamma: 4.5,
    };
    for scheme in ["B A Xi(1/2) Oa Xi(1/2) A B", "B A Xi(1/2) On Xi(1/2) A B"] {
        let e = StepMap::new(&program(scheme), mode, 0.05, 1.0).unwrap_err();
        assert!(
            e.to_string().contains("Oa or On and Xi (the adaptive"),
            "{e}"
        );
    }
}

/// A Metropolis-adjusted step is not linear: the predictor refuses it by name.
#[test]
fn a_metropolis_adjusted_step_is_refused_by_name() {
    let mode = Mode {
        omega2: 100.0,
        gamma: 4.5,
    };
    let e = StepMap::new(&program("{B(1/2) A B(1/2)} O"), mode, 0.05, 1.0).unwrap_err();
    assert!(e.to_string().contains("is Metropolis-adjusted"), "{e}");
}

/// OBABO (velocity Verlet between two half OU steps) samples p exactly and x with variance
/// 1 / (omega^2 (1 - (omega h / 2)^2)).
#[test]
fn obabo_samples_momenta_exactly() {
    for (omega2, gamma, dt) in [(100.0, 4.5, 0.08), (25.0, 40.0, 0.3)] {
        let c = covariance("OBABO", omega2, gamma, dt);
        let x = omega2 * dt * dt / 4.0;
        assert_relative_eq!(c[(1, 1)], 1.0, max_relative = 1e-10);
        assert_relative_eq!(c[(0, 0)], 1.0 / (omega2 * (1.0 - x)), max_relative = 1e-10);
    }
}

/// The exact OU sweep alone keeps p's Maxwellian whatever the step; Shardlow's BBK sweep
/// too (its midpoint rule is exact for the variance, algorithms.md section 6), and over-
/// relaxes (a negative factor) beyond gamma h = 2.
#[test]
fn sweeps_keep_the_maxwellian() {
    for (flow, h, negative) in [
        (Flow::O, 0.7, false),
        (Flow::Bbk, 0.1, false),
        (Flow::Bbk, 0.7, true),
    ] {
        let stage = Stage {
            flow,
            coeff: Coeff {
                value: 1.0,
                exact: None,
            },
            stream: 0,
            order: SweepOrder::Forward,
            group: None,
        };
        let sweep = Program {
            source: "sweep".into(),
            stages: vec![stage.clone()],
            unmerged_stages: vec![stage],
        };
        let map = StepMap::new(
            &sweep,
            Mode {
                omega2: 0.0,
                gamma: 3.0,
            },
            h,
            2.0,
        )
        .unwrap();
        let c = map.m[(1, 1)];
        assert_eq!(c < 0.0, negative, "{flow:?} factor {c}");
        let q = map.noise_covariance();
        assert_relative_eq!(q[(1, 1)] / (1.0 - c * c), 2.0, max_relative = 1e-12);
    }
}

/// Velocity Verlet (F(1/2) A F(1/2), the force of a step's end reused) is stable up to
/// omega dt = 2 as friction vanishes; BAOAB up to exactly 2 at any friction.
#[test]
fn stability_limits() {
    let omega = 10.0;
    let vv = Spectrum::oscillator(omega * omega, 1e-6, 1.0);
    let limit = Predictor::new(&vv)
        .stability_limit(&program("F(1/2) A F(1/2)"))
        .unwrap()
        .unwrap();
    assert_relative_eq!(limit, 2.0 / omega, max_relative = 1e-4);
    for gamma in [0.1, 4.5, 200.0] {
        let s = Spectrum::oscillator(omega * omega, gamma, 1.0);
        let limit = Predictor::new(&s)
            .stability_limit(&program("BAOAB"))
            .unwrap()
            .unwrap();
        assert_relative_eq!(limit, 2.0 / omega, max_relative = 1e-5);
    }
}

/// The configurational temperature of BAOAB is exact up to its stability limit, so its
/// critical step is that limit; OBABO's error is x / (1 - x), x = (omega dt / 2)^2, which
/// reaches 10 % at omega dt = 2 sqrt(1/11).
#[test]
fn critical_steps() {
    let omega = 10.0;
    let s = Spectrum::oscillator(omega * omega, 4.5, 1.0);
    let p = Predictor::new(&s);
    let baoab = p.critical_dt(&program("BAOAB"), 0.1).unwrap();
    assert!(
        matches!(baoab, dpd_predict::Critical::StabilityLimit { .. }),
        "{baoab:?}"
    );
    assert_relative_eq!(baoab.dt().unwrap(), 0.2, max_relative = 1e-5);
    let obabo = p.critical_dt(&program("OBABO"), 0.1).unwrap();
    assert!(
        matches!(obabo, dpd_predict::Critical::At { .. }),
        "{obabo:?}"
    );
    assert_relative_eq!(
        obabo.dt().unwrap(),
        2.0 * (1.0f64 / 11.0).sqrt() / omega,
        max_relative = 1e-5
    );
}

/// Grouping similar modes (`Spectrum::grouped`) moves a T_C error by under 1 % of itself:
/// 765 modes spread like the standard box's network (omega2 from 2 to 250, frictions varying
/// independently), against the sum over every mode.
#[test]
fn grouped_modes_predict_what_all_modes_do() {
    let modes: Vec<Mode> = (0..765)
        .map(|k| {
            let u = (k as f64 + 0.5) / 765.0;
            Mode {
                omega2: 2.0 + 248.0 * u.powf(0.7),
                gamma: 1.0 + 0.8 * ((k * 7919) % 765) as f64 / 765.0,
            }
        })
        .collect();
    let spectrum = Spectrum {
        modes: modes.clone(),
        particles: 256,
        volume: 256.0 / 3.0,
        kbt: 1.0,
        response: None,
    };
    let grouped = Predictor::new(&spectrum);
    assert!(grouped.groups() < 60, "{} groups", grouped.groups());
    for scheme in ["OBAB", "OABA", "ABOBAO", "OBAOAB"] {
        let p = program(scheme);
        let (mut num, mut den) = (0.0, 0.0);
        for &m in &modes {
            let c = match stationary_covariance(&StepMap::new(&p, m, 0.08, 1.0).unwrap()) {
                Stationary::Covariance(c) => c,
                Stationary::Unstable { .. } => panic!("{scheme} unstable"),
            };
            num += m.omega2 * (m.omega2 * c[(0, 0)] - 1.0);
            den += m.omega2;
        }
        let all = num / den;
        let tc = grouped.errors(&p, 0.08).unwrap().unwrap();
        assert_relative_eq!(tc.configurational_temperature, all, max_relative = 0.01);
    }
}

/// Observables read at the processed positions `x + c dt^2 F`: ABOBA's exact `<x^2>` scaled by
/// `(1 - c omega2 dt^2)^2`, and OBABO's `1 / (omega2 (1 - y))`, `y = (omega dt / 2)^2`, with c
/// = 1/8 becomes `(1 - y/2)^2 / (omega2 (1 - y))`: its T_C error drops from `y / (1 - y)` to
/// `y^2 / (4 (1 - y))`, fourth order (the processor cancels Verlet's `dt^2` term on every
/// mode).
#[test]
fn processing_scales_the_sampled_positions() {
    for (omega2, gamma, dt) in [(100.0, 4.5, 0.08), (100.0, 200.0, 0.15), (1.0, 0.3, 1.5)] {
        let p = Predictor::new(&Spectrum::oscillator(omega2, gamma, 1.0));
        let tc = |scheme: &str, c: f64| {
            let e = p.clone().processed(c).errors(&program(scheme), dt);
            e.unwrap().unwrap().configurational_temperature
        };
        let h2 = omega2 * dt * dt;
        for c in [0.0, 0.1, -0.3] {
            let s = 1.0 - c * h2;
            assert_relative_eq!(tc("ABOBA", c), s * s - 1.0, epsilon = 1e-10);
        }
        let y = h2 / 4.0;
        assert_relative_eq!(tc("OBABO", 0.0), y / (1.0 - y), max_relative = 1e-9);
        assert_relative_eq!(
            tc("OBABO", 0.125),
            y * y / (4.0 * (1.0 - y)),
            max_relative = 1e-9,
            epsilon = 1e-12
        );
    }
}

/// The processing that cancels the leading error: none for BAOAB (exact on a harmonic
/// mode), Verlet's 1/8 for OBABO, up to its `dt^2` correction at `PROCESSING_DT` (the root of
/// `(1 - c omega2 dt^2)^2 = 1 - (omega dt / 2)^2`).
#[test]
fn the_leading_processing_cancels_the_dt2_term() {
    let p = Predictor::new(&Spectrum::oscillator(100.0, 4.5, 1.0));
    let c = p.leading_processing(&program("BAOAB")).unwrap().unwrap();
    assert!(c.abs() < 1e-9, "{c}");
    let h2 = 100.0 * dpd_predict::predict::PROCESSING_DT.powi(2);
    let exact = (1.0 - (1.0 - h2 / 4.0).sqrt()) / h2;
    let c = p.leading_processing(&program("OBABO")).unwrap().unwrap();
    assert_relative_eq!(c, exact, max_relative = 1e-7);
    assert_relative_eq!(c, 0.125, max_relative = 2e-3);
}
