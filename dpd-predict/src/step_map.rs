//! The one-step map of a program on one harmonic mode.
//!
//! A mode is a coordinate `x` with unit mass (mass-weighted), potential `omega2 x^2 / 2`, and a
//! friction `gamma` (the projection of the pairs' dissipative couplings on the mode), at
//! temperature `k_B T`. Its state is `z = (x, p, f)`, `f` the full-force cache of F stages:
//! like `dpd-core`, F evaluates `f = -omega2 x - gamma p + sqrt(2 gamma k_B T / dt) zeta` at
//! the first F after positions change and reuses it until they change again (velocity
//! Verlet's first half-kick uses the evaluation of the previous step's end). Each stage is
//! `z <- S z + g xi` with `xi` the standard normal of the stage's random stream (stages of one
//! stream share it: the frozen noise of the PRK schemes), so a step is `z <- M z + G xi`.

use crate::spectrum::Mode;
use dpd_ir::{Flow, ForceGroup, Program};
use nalgebra::{Matrix3, Vector3};

/// The linear step `z <- M z + G xi` of one mode, `xi` standard normals, one per random
/// stream of the step.
#[derive(Clone, Debug, PartialEq)]
pub struct StepMap {
    /// Deterministic part.
    pub m: Matrix3<f64>,
    /// Noise loadings, one column per random stream.
    pub g: Vec<Vector3<f64>>,
}

/// A point of the step where the conservative force is evaluated: the state there is
/// `m z + g xi` (`z` the state at the step's start), and the kicks that use the evaluation
/// move momenta by `kick` times the force (B: its step, T: its relaxation time, F: its step).
#[derive(Clone, Debug, PartialEq)]
pub struct ForcePoint {
    pub kick: f64,
    pub m: Matrix3<f64>,
    pub g: Vec<Vector3<f64>>,
}

impl ForcePoint {
    /// The covariance of the state at this point when the step starts from covariance `c`.
    pub fn covariance(&self, c: &Matrix3<f64>) -> Matrix3<f64> {
        self.m * c * self.m.transpose()
            + self
                .g
                .iter()
                .map(|col| col * col.transpose())
                .sum::<Matrix3<f64>>()
    }
}

/// Why a program has no linear step map.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum StepMapError {
    #[error("invalid dt = {0}: must be finite and positive")]
    Dt(f64),
    #[error("invalid mode: omega2 = {omega2} and gamma = {gamma} must be finite, gamma >= 0")]
    Mode { omega2: f64, gamma: f64 },
    #[error("invalid kbt = {0}: must be finite and positive")]
    Kbt(f64),
    /// An L stage: a pair collides or not, so the step is a mixture of two linear maps, whose
    /// covariance `(1 - p) S C S^T + p (...)` no single `M C M^T + G G^T` reproduces.
    #[error(
        "{0} has L (Lowe-Andersen collisions), which the predictor does not cover: a collision \
         happens or not, so the step is a random choice of linear maps, not one linear map \
         with Gaussian noise"
    )]
    Collisions(String),
    /// Oa or On and Xi: the friction factor xi is a state variable that multiplies the momenta
    /// in Oa and On and is driven by their squares in Xi, so the step is not linear.
    #[error(
        "{0} has Oa or On and Xi (the adaptive thermostats, PAdL and PNHL), which the predictor \
         does not cover: the friction factor xi multiplies the momenta and is driven by their \
         squares, so the step is not a linear map with Gaussian noise"
    )]
    Adaptive(String),
    /// Braces: the accept/reject chooses between two states on the energy difference of the
    /// whole system, so the step is not linear.
    #[error(
        "{0} is Metropolis-adjusted ({{...}}), which the predictor does not cover: its \
         accept/reject keeps the proposal or restores the state with negated momenta on the \
         energy difference of the whole system, so the step is not a linear map with Gaussian \
         noise (its invariant measure is exact: there is no bias to predict)"
    )]
    Adjusted(String),
}

impl StepMap {
    /// The step of `program` at `dt` on `mode` at temperature `kbt` (algorithms.md section
    /// 2, each pair update read as the mode's own update).
    pub fn new(program: &Program, mode: Mode, dt: f64, kbt: f64) -> Result<Self, StepMapError> {
        Self::traced(program, mode, dt, kbt).map(|(map, _)| map)
    }

    /// The step, with the points where it evaluates the conservative force.
    pub fn traced(
        program: &Program,
        mode: Mode,
        dt: f64,
        kbt: f64,
    ) -> Result<(Self, Vec<ForcePoint>), StepMapError> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(StepMapError::Dt(dt));
        }
        if !(mode.omega2.is_finite() && mode.gamma.is_finite() && mode.gamma >= 0.0) {
            return Err(StepMapError::Mode {
                omega2: mode.omega2,
                gamma: mode.gamma,
            });
        }
        if !(kbt.is_finite() && kbt > 0.0) {
            return Err(StepMapError::Kbt(kbt));
        }

        let streams = program
            .stages
            .iter()
            .map(|s| usize::from(s.stream) + 1)
            .max()
            .unwrap_or(1);
        let (w2, gamma) = (mode.omega2, mode.gamma);
        // The cache is carried into the step when no drift follows the step's last
        // evaluation (the cyclic steady state, as `Program::evaluations_per_step` counts).
        let mut valid = carries_cache(program);
        let mut m = if valid {
            Matrix3::identity()
        } else {
            Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, 0.0))
        };
        let mut g = vec![Vector3::zeros(); streams];
        let mut points = Vec::new();
        // Where the cache was evaluated: a cache carried into the step was evaluated at the
        // step's starting positions (no drift since).
        let mut cache_at = ForcePoint {
            kick: 0.0,
            m,
            g: g.clone(),
        };
        for stage in &program.stages {
            let h = stage.coeff.value * dt;
            let k = usize::from(stage.stream);
            // Row operations on (m | g): the stage's S applied on the left, then its noise.
            let (s, noise) = match stage.flow {
                Flow::A => {
                    valid = false;
                    (
                        Matrix3::new(1.0, h, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0),
                        None,
                    )
                }
                // The modes are the pair forces': a kick of the bonded forces alone
                // (`B[bond]`) leaves them as they are.
                Flow::B if !stage.applies(ForceGroup::Pair) => (Matrix3::identity(), None),
                Flow::B => {
                    points.push(ForcePoint {
                        kick: h,
                        m,
                        g: g.clone(),
                    });
                    (
                        Matrix3::new(1.0, 0.0, 0.0, -h * w2, 1.0, 0.0, 0.0, 0.0, 1.0),
                        None,
                    )
                }
                Flow::O => {
                    let (c, d) = ou(gamma, h, kbt);
                    (
                        Matrix3::new(1.0, 0.0, 0.0, 0.0, c, 0.0, 0.0, 0.0, 1.0),
                        Some(d),
                    )
                }
                Flow::Bbk => {
                    let x = gamma * h / 2.0;
                    let c = (1.0 - x) / (1.0 + x);
                    let d = (2.0 * gamma * kbt * h).sqrt() / (1.0 + x);
                    (
                        Matrix3::new(1.0, 0.0, 0.0, 0.0, c, 0.0, 0.0, 0.0, 1.0),
                        Some(d),
                    )
                }
                Flow::T => {
                    // Relaxation towards the force: p <- c p - omega2 x (1 - c) / gamma.
                    let (c, d) = ou(gamma, h, kbt);
                    let lag = relaxed_time(gamma, h);
                    points.push(ForcePoint {
                        kick: lag,
                        m,
                        g: g.clone(),
                    });
                    (
                        Matrix3::new(1.0, 0.0, 0.0, -w2 * lag, c, 0.0, 0.0, 0.0, 1.0),
                        Some(d),
                    )
                }
                Flow::L => return Err(StepMapError::Collisions(program.source.clone())),
                Flow::Oa | Flow::On | Flow::Xi => {
                    return Err(StepMapError::Adaptive(program.source.clone()))
                }
                Flow::Propose | Flow::Accept => {
                    return Err(StepMapError::Adjusted(program.source.clone()))
                }
                Flow::F => {
                    if !valid {
                        cache_at = ForcePoint {
                            kick: 0.0,
                            m,
                            g: g.clone(),
                        };
                        // Evaluate: f <- -omega2 x - gamma p + sqrt(2 gamma kbt / dt) zeta.
                        let eval = Matrix3::new(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, -w2, -gamma, 0.0);
                        m = eval * m;
                        g.iter_mut().for_each(|col| *col = eval * *col);
                        g[k].z += (2.0 * gamma * kbt / dt).sqrt();
                        valid = true;
                    }
                    points.push(ForcePoint {
                        kick: h,
                        ..cache_at.clone()
                    });
                    (
                        Matrix3::new(1.0, 0.0, 0.0, 0.0, 1.0, h, 0.0, 0.0, 1.0),
                        None,
                    )
                }
            };
            m = s * m;
            g.iter_mut().for_each(|col| *col = s * *col);
            if let Some(d) = noise {
                g[k].y += d;
            }
        }
        Ok((StepMap { m, g }, points))
    }

    /// Covariance of the step's noise, `G G^T`.
    pub fn noise_covariance(&self) -> Matrix3<f64> {
        self.g.iter().map(|col| col * col.transpose()).sum()
    }
}

/// Whether the full-force cache is fresh at the start of a step in the cyclic steady state:
/// some F stage evaluates after the step's last drift.
fn carries_cache(program: &Program) -> bool {
    program
        .stages
        .iter()
        .rev()
        .take_while(|s| s.flow != Flow::A)
        .any(|s| s.flow == Flow::F)
}

/// The exact OU update of a momentum over `h`: `p <- c p + d xi` with `c = exp(-gamma h)`,
/// `d^2 = k_B T (1 - c^2)`, through `expm1` as in `dpd-core` (tau h near 0 keeps precision).
fn ou(gamma: f64, h: f64, kbt: f64) -> (f64, f64) {
    let c = (-gamma * h).exp();
    let d = (kbt * -(-2.0 * gamma * h).exp_m1()).sqrt();
    (c, d)
}

/// `(1 - exp(-gamma h)) / gamma`, with its limit `h` at `gamma = 0`.
fn relaxed_time(gamma: f64, h: f64) -> f64 {
    if gamma == 0.0 {
        h
    } else {
        -(-gamma * h).exp_m1() / gamma
    }
}
