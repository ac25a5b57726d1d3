//! The weak order of ABOBA's temperature errors on the standard box (gamma = 4.5), measured as
//! the slope of log |error| against log dt between dt = 0.04 and 0.08.
use super::common;

use dpd_schemes::registry::lookup;
use rayon::prelude::*;

/// Mean and standard error over seeds of `T_K - 1` and `T_C - 1` of ABOBA at `dt`: `seeds`
/// runs of 400 time units, the first 5 % discarded (the fluid equilibrates in about one time
/// unit from its uniform start), sampled every 0.2 time units.
fn errors(dt: f64, seeds: u64) -> [(f64, f64); 2] {
    let scheme = lookup("aboba").unwrap().scheme();
    let steps = (400.0 / dt).round() as u64;
    let every = (0.2 / dt).round() as u64;
    let runs: Vec<[f64; 2]> = (0..seeds)
        .into_par_iter()
        .map(|seed| {
            let mut sys = common::standard_box(&*scheme, dt, 100 + seed);
            let s = common::averages(&mut sys, &*scheme, steps, every, 0.95)
                .unwrap_or_else(|e| panic!("ABOBA blew up at dt = {dt}: {e}"));
            [
                s.kinetic_temperature - 1.0,
                s.configurational_temperature - 1.0,
            ]
        })
        .collect();
    [0, 1].map(|k| {
        let n = runs.len() as f64;
        let mean = runs.iter().map(|r| r[k]).sum::<f64>() / n;
        let var = runs.iter().map(|r| (r[k] - mean).powi(2)).sum::<f64>() / (n - 1.0);
        (mean, (var / n).sqrt())
    })
}

/// `d log|e| / d log dt` between two errors of one sign at dt and 2 dt, with its standard
/// error from theirs.
fn slope((e1, s1): (f64, f64), (e2, s2): (f64, f64)) -> (f64, f64) {
    assert!(
        e1 * e2 > 0.0,
        "errors of opposite signs: {e1:+.5}, {e2:+.5}"
    );
    let ln2 = std::f64::consts::LN_2;
    let se = ((s1 / e1).powi(2) + (s2 / e2).powi(2)).sqrt() / ln2;
    ((e2 / e1).ln() / ln2, se)
}

/// Measured with ten seeds of 400 time units per dt (`dpd run --scheme aboba --gamma 4.5
/// --time 400 --runs 10`, 2026-12-04): T_K - 1 = +2.46 +- 0.08 % and +12.63 +- 0.08 % at
/// dt = 0.04 and 0.08, slope 2.36 +- 0.05; T_C - 1 = -0.80 +- 0.08 % and -2.58 +- 0.07 %,
/// slope 1.69 +- 0.15. T_K follows dt^2 (plus a small positive dt^4 term). T_C's error is
/// negative and small, and a positive higher-order term, which turns it positive at
/// dt ~ 0.11 (-0.79 % at 0.1076, +3.6 % at 0.116), already bends it in this range, so its slope
/// is below 2; below dt = 0.04 its error (< 0.5 %) is not resolved at a test's cost. The bands
/// are about three standard errors of the eight-seed estimate around those values (this test
/// measured 2.31 +- 0.05 and 1.78 +- 0.13). The first-order splitting `A B O` fails it: its
/// T_C error is +9.2 % and +34 % at the same dt (measured with `dpd run`, 8 seeds), of the
/// other sign and ten times larger.
#[test]
fn abobas_temperature_errors_shrink_at_second_order() {
    let seeds = 8;
    let [tk1, tc1] = errors(0.04, seeds);
    let [tk2, tc2] = errors(0.08, seeds);
    let (k, k_se) = slope(tk1, tk2);
    let (c, c_se) = slope(tc1, tc2);
    println!(
        "T_K - 1: {:+.4} +- {:.4}, {:+.4} +- {:.4}: slope {k:.2} +- {k_se:.2}",
        tk1.0, tk1.1, tk2.0, tk2.1
    );
    println!(
        "T_C - 1: {:+.4} +- {:.4}, {:+.4} +- {:.4}: slope {c:.2} +- {c_se:.2}",
        tc1.0, tc1.1, tc2.0, tc2.1
    );
    assert!(
        tc1.0 < 0.0 && tc2.0 < 0.0,
        "T_C errors should be negative here"
    );
    assert!((2.0..=2.7).contains(&k), "T_K slope {k:.2} +- {k_se:.2}");
    assert!((1.2..=2.2).contains(&c), "T_C slope {c:.2} +- {c_se:.2}");
}
