//! The stiff melt (scenes/melt-stiff.toml: 10-bead chains, harmonic K = 100, r0 = 0.7) runs
//! with ABOBA and with a multiple-time-stepping scheme, and its chains are the reference's:
//! velocity Verlet at a small step. 300 beads (30 chains), 100 time units, seeds 1 and 2.

use dpd_measure::result::Job;
use dpd_measure::runner::{run, Control};
use dpd_measure::{Keys, RunResult, Scene};
use std::path::Path;
use std::sync::atomic::AtomicBool;

/// Bonds on an inner step of a quarter of dt, pair forces and O on the outer one.
const MTS: &str = "B[pair](1/2) (B[bond](1/8) A(1/4) B[bond](1/8))^4 O B[pair](1/2)";

/// Means over seeds 1 and 2 of `scheme` at `dt`: mean bond length, <R_g^2>, k_B T_K.
fn melt(scheme: &str, dt: f64) -> [f64; 3] {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/melt-stiff.toml");
    let keys: Keys = toml::from_str("n = 300\ntime = 100.0\nruns = 1\nthreads = 1").unwrap();
    let scene = Scene::resolve(Some(&file), &keys).unwrap();
    let compiled = dpd_schemes::registry::resolve(scheme).unwrap();
    let stop = AtomicBool::new(false);
    let control = Control {
        stop: &stop,
        progress: &|_| {},
    };
    let runs: Vec<RunResult> = (1..=2)
        .map(|seed| {
            let job = Job {
                scheme: scheme.into(),
                dt,
                seed,
            };
            run(&scene, &job, compiled.as_ref(), control).unwrap()
        })
        .collect();
    let mean = |f: &dyn Fn(&RunResult) -> f64| runs.iter().map(f).sum::<f64>() / 2.0;
    assert!(runs
        .iter()
        .all(|r| r.stable && r.chains.as_ref().unwrap().chains == 30));
    [
        mean(&|r| r.chains.as_ref().unwrap().bond_length),
        mean(&|r| r.chains.as_ref().unwrap().gyration_squared.unwrap()),
        mean(&|r| r.kinetic_temperature.unwrap()),
    ]
}

/// Tolerances, from 4 seeds of each run at these settings (docs/systems-measured.md): the mean bond
/// length varies by 1e-4 between seeds and is biased by -7e-4 with ABOBA at dt = 0.05 and
/// -3e-4 with the MTS scheme: within 2e-3 of the reference (a bond 0.3 % longer or shorter
/// fails). <R_g^2> (about 1.05) varies by 0.02 between seeds, 0.014 for a mean of two, 0.02
/// for a difference of such means: within 0.1 (5 of those). The MTS scheme's k_B T_K is within
/// 0.03 of 1 (measured +1.3 %); ABOBA's, whose outer step also moves the bonds, is +18 % at
/// this dt, so the bonds on an inner step are what keeps the MTS scheme's temperature.
#[test]
fn a_stiff_melt_runs_with_aboba_and_mts_and_keeps_the_reference_chains() {
    let reference = melt("vv", 0.02);
    for (scheme, dt) in [("aboba", 0.05), (MTS, 0.05)] {
        let [bond, rg2, t_k] = melt(scheme, dt);
        assert!(
            (bond - reference[0]).abs() < 2e-3,
            "{scheme}: bond length {bond}, reference {}",
            reference[0]
        );
        assert!(
            (rg2 - reference[1]).abs() < 0.1,
            "{scheme}: <R_g^2> {rg2}, reference {}",
            reference[1]
        );
        if scheme == MTS {
            assert!((t_k - 1.0).abs() < 0.03, "{scheme}: k_B T_K {t_k}");
        }
    }
}
