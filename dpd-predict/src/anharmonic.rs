//! The leading anharmonic correction of the configurational temperature.
//!
//! ABOBA, BAOAB and the other schemes whose configurational marginal is exact on every
//! harmonic mode still err in the fluid, because its modes' stiffness changes with the
//! configuration: a pair inside the cut-off is a stiff spring, one outside is none. A scheme
//! that weights a mode of squared frequency `lambda` wrongly biases how often configurations
//! with many stiff modes are visited: it samples `exp(-U / k_B T) w(q)`, `ln w = sum_k
//! g(lambda_k(q))`. Two limits give `g`:
//!
//! - Weak friction: the step nearly conserves a shadow energy, and a mode's weight is the
//!   phase-space volume of its stationary Gaussian over the exact one,
//!   `g = (1/2) ln(omega2 det C_xp / (k_B T)^2)` (ABOBA `-(1/2) ln(1 - (omega dt / 2)^2)`,
//!   BAOAB the opposite).
//! - Strong friction: the other coordinates feel the mode's mean force where the force is
//!   evaluated, `-(1/2) <x^2>` per unit of `omega2`, so `lambda g' = -s / 2` with `s` the
//!   relative error of `omega2 <x^2>` at the force evaluations, weighted by their kicks. This
//!   is exact at first order in the coupling of a slow coordinate; for ABOBA it gives
//!   `-(dt^2 / 8) lap U` at small dt, for BAOAB zero (Leimkuhler and Matthews' overdamped
//!   limit of BAOAB has no `dt^2` term).
//!
//! Between them each mode is weighted by `theta = zeta / (1 + zeta)`, `zeta = gamma / (2
//! omega)` its damping ratio: an interpolation, not derived (docs/design.md measures it).
//! A pair entering the cut-off adds a spring along a mass-weighted direction `u`, which moves
//! `lambda_k` by `phi'' (u.v_k)^2` at first order; averaged over the network's own pair
//! directions (`sum_pairs phi'' (u.v_k)^2 = lambda_k`) it moves `ln w` by `eps` per unit of
//! the network's trace `X`, `eps = sum_k lambda_k g'(lambda_k) / sum_k lambda_k`. So `ln w ~
//! eps X(q)`, and to first order T_C moves by `eps R`, the response `R = Cov(|F|^2, X) /
//! <|F|^2> - Cov(lap U, X) / <lap U>` measured on equilibrium configurations ([`response`]).

use crate::network::{pairs, NetworkError, PairModel};
use crate::spectrum::Mode;
use crate::stationary::{stationary_covariance, Stationary};
use crate::step_map::{ForcePoint, StepMap, StepMapError};
use dpd_ir::Program;
use nalgebra::Matrix3;
use serde::{Deserialize, Serialize};

/// Relative step of the one-sided difference of the phase-space weight in `omega2` (its
/// truncation error is this fraction of the second derivative's term).
const DIFF: f64 = 1e-5;

/// `lambda g'(lambda)` of a mode under `program` at `dt`, given the step's stationary
/// covariance `c` and force evaluations `points` at the mode; `None` when the mode stiffened
/// by [`DIFF`] has no stationary state.
pub fn weight_slope(
    program: &Program,
    mode: Mode,
    dt: f64,
    kbt: f64,
    c: &Matrix3<f64>,
    points: &[ForcePoint],
) -> Result<Option<f64>, StepMapError> {
    if mode.omega2 <= 0.0 {
        // No stiffness: nothing for the pairs inside the cut-off to change.
        return Ok(Some(0.0));
    }
    let up = Mode {
        omega2: mode.omega2 * (1.0 + DIFF),
        ..mode
    };
    let c_up = match stationary_covariance(&StepMap::new(program, up, dt, kbt)?) {
        Stationary::Covariance(c) => c,
        Stationary::Unstable { .. } => return Ok(None),
    };
    let phase_slope =
        (phase_space(up.omega2, &c_up, kbt) - phase_space(mode.omega2, c, kbt)) / DIFF;
    let (kicks, weighted) = points.iter().fold((0.0, 0.0), |(k, w), p| {
        let x2 = p.covariance(c)[(0, 0)];
        (k + p.kick, w + p.kick * mode.omega2 * x2 / kbt)
    });
    let s = if kicks > 0.0 {
        weighted / kicks - 1.0
    } else {
        0.0
    };
    // zeta / (1 + zeta), zeta = gamma / (2 omega).
    let theta = if mode.gamma > 0.0 {
        mode.gamma / (mode.gamma + 2.0 * mode.omega2.sqrt())
    } else {
        0.0
    };
    Ok(Some((1.0 - theta) * phase_slope - theta * s / 2.0))
}

/// `(1/2) ln(omega2 det C_xp / (k_B T)^2)`: the log of the phase-space volume of a mode's
/// stationary Gaussian over the exact one.
fn phase_space(omega2: f64, c: &Matrix3<f64>, kbt: f64) -> f64 {
    let det = c[(0, 0)] * c[(1, 1)] - c[(0, 1)] * c[(1, 0)];
    0.5 * (omega2 * det / (kbt * kbt)).ln()
}

/// How the configurational temperature responds to weighting configurations by `exp(eps X)`,
/// `X` the pair network's trace: `d ln T_C / d eps` at `eps = 0`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Response {
    /// `R = Cov(|F|^2, X) / <|F|^2> - Cov(lap U, X) / <lap U>`, in units of `1 / omega2`'s
    /// inverse (X is a sum of squared frequencies).
    pub r: f64,
    /// Its standard error from batch means (`BATCHES` batches of consecutive samples).
    pub std_error: f64,
    /// Configurations it was measured on.
    pub samples: usize,
}

/// Batches of the standard error of [`Response`].
const BATCHES: usize = 8;

/// Per configuration: `sum_i |F_i|^2`, `sum_i lap_i U` and the network's trace.
fn observables(q: &[[f64; 3]], masses: &[f64], edges: [f64; 3], model: PairModel) -> [f64; 3] {
    let n = q.len();
    let (a, rc) = (model.a, model.rc);
    let mut force = vec![[0.0; 3]; n];
    let (mut lap, mut trace) = (0.0, 0.0);
    for (i, j, e, r) in pairs(q, edges, rc) {
        // phi = a rc (1 - r/rc)^2 / 2: phi' = -a (1 - r/rc), phi'' = a / rc.
        let f = a * (1.0 - r / rc);
        for c in 0..3 {
            force[i][c] += f * e[c];
            force[j][c] -= f * e[c];
        }
        lap += 2.0 * (a / rc - 2.0 * f / r);
        trace += a / rc * (1.0 / masses[i] + 1.0 / masses[j]);
    }
    let f2 = force.iter().flatten().map(|x| x * x).sum();
    [f2, lap, trace]
}

/// The response of T_C on equilibrium configurations `configs` (positions in a periodic box
/// of edges `edges`, masses `masses`); at least `2 BATCHES` configurations.
pub fn response(
    configs: &[Vec<[f64; 3]>],
    masses: &[f64],
    edges: [f64; 3],
    model: PairModel,
) -> Result<Response, NetworkError> {
    if configs.len() < 2 * BATCHES {
        return Err(NetworkError::Invalid {
            field: "configurations",
            value: configs.len().to_string(),
            allowed: "need at least 16",
        });
    }
    for q in configs {
        crate::network::check(q, masses, edges, model)?;
    }
    let obs: Vec<[f64; 3]> = configs
        .iter()
        .map(|q| observables(q, masses, edges, model))
        .collect();
    let r = response_of(&obs);
    let per = obs.len() / BATCHES;
    let batches: Vec<f64> = obs
        .chunks_exact(per)
        .take(BATCHES)
        .map(response_of)
        .collect();
    let mean = batches.iter().sum::<f64>() / BATCHES as f64;
    let var = batches.iter().map(|b| (b - mean).powi(2)).sum::<f64>() / (BATCHES - 1) as f64;
    Ok(Response {
        r,
        std_error: (var / BATCHES as f64).sqrt(),
        samples: obs.len(),
    })
}

fn response_of(obs: &[[f64; 3]]) -> f64 {
    let n = obs.len() as f64;
    let mean = |k: usize| obs.iter().map(|o| o[k]).sum::<f64>() / n;
    let (f2, lap, x) = (mean(0), mean(1), mean(2));
    let cov =
        |k: usize, m: f64| obs.iter().map(|o| (o[k] - m) * (o[2] - x)).sum::<f64>() / (n - 1.0);
    cov(0, f2) / f2 - cov(1, lap) / lap
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn program(s: &str) -> Program {
        dpd_ir::compile(s).unwrap()
    }

    /// One pair at distance r: |F|^2 = 2 (a (1 - r))^2, lap U = 2 (a - 2 a (1 - r) / r), and
    /// the network's trace 2 a (unit masses); a pair beyond the cut-off counts nothing.
    #[test]
    fn a_pair_s_observables() {
        let (a, r) = (25.0, 0.4);
        let o = observables(
            &[[0.5; 3], [0.5 + r, 0.5, 0.5]],
            &[1.0; 2],
            [3.0; 3],
            PairModel::standard(),
        );
        assert_relative_eq!(o[0], 2.0 * (a * (1.0 - r)).powi(2), max_relative = 1e-12);
        assert_relative_eq!(
            o[1],
            2.0 * (a - 2.0 * a * (1.0 - r) / r),
            max_relative = 1e-12
        );
        assert_relative_eq!(o[2], 2.0 * a, max_relative = 1e-12);
        let far = observables(
            &[[0.5; 3], [1.6, 0.5, 0.5]],
            &[1.0; 2],
            [3.0; 3],
            PairModel::standard(),
        );
        assert_eq!(far, [0.0; 3]);
    }

    /// With |F|^2 = 2 X and lap U = 3 + X, R = Var X (2 / <2 X> - 1 / <3 + X>).
    #[test]
    fn the_response_is_the_two_relative_covariances() {
        let obs: Vec<[f64; 3]> = [1.0, 2.0, 4.0, 5.0]
            .iter()
            .map(|&x| [2.0 * x, 3.0 + x, x])
            .collect();
        let var = 10.0 / 3.0;
        assert_relative_eq!(
            response_of(&obs),
            var * (2.0 / 6.0 - 1.0 / 6.0),
            max_relative = 1e-12
        );
        let few = vec![vec![[0.5; 3], [0.9, 0.5, 0.5]]; 15];
        assert!(response(&few, &[1.0; 2], [3.0; 3], PairModel::standard()).is_err());
    }

    /// ABOBA and BAOAB: the phase-space slopes `lambda g'` are `x / (1 - x) / 2` and
    /// `-x / (1 - x) / 2` (x = omega2 dt^2 / 4); the mean-force slopes are `-x / (1 - x) / 2`
    /// (ABOBA's kicks see the midpoint, whose variance is that of BOBA) and 0 (BAOAB's kicks
    /// see the exact end points). Without friction only the first counts, at high friction
    /// almost only the second.
    #[test]
    fn aboba_and_baoab_limits() {
        let (omega2, dt) = (100.0, 0.08);
        let x = omega2 * dt * dt / 4.0;
        let half = x / (1.0 - x) / 2.0;
        let slope = |s: &str, gamma: f64| {
            let (program, mode) = (program(s), Mode { omega2, gamma });
            let (map, points) = StepMap::traced(&program, mode, dt, 1.0).unwrap();
            let Stationary::Covariance(c) = stationary_covariance(&map) else {
                panic!("{s} unstable");
            };
            weight_slope(&program, mode, dt, 1.0, &c, &points)
                .unwrap()
                .unwrap()
        };
        // theta = 5e-5 at gamma 1e-3.
        assert_relative_eq!(slope("ABOBA", 1e-3), half, max_relative = 1e-3);
        assert_relative_eq!(slope("BAOAB", 1e-3), -half, max_relative = 1e-3);
        let gamma = 1e6;
        assert_relative_eq!(slope("ABOBA", gamma), -half, max_relative = 1e-2);
        assert!(slope("BAOAB", gamma).abs() < 1e-2 * half);
    }
}
