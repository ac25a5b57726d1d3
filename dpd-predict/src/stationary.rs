//! The exact stationary covariance of a linear step: the discrete Lyapunov equation
//! `C = M C M^T + Q`.
//!
//! nalgebra has no Lyapunov or Sylvester solver; a mode's state has three coordinates, so the
//! equation is solved in its Kronecker form `(I - M (x) M) vec C = vec Q`, a 9 x 9 LU solve,
//! exact up to rounding and cheap next to anything iterative.

use crate::step_map::StepMap;
use nalgebra::{Matrix3, SMatrix, SVector};

/// Spectral radius at or above which a step has no stationary state (one minus the
/// rounding of a 9 x 9 solve: closer to one the covariance is all rounding).
pub const STABLE_RADIUS: f64 = 1.0 - 1e-12;

/// The stationary statistics of one mode under a step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stationary {
    /// The covariance of `(x, p, f)`.
    Covariance(Matrix3<f64>),
    /// The step's spectral radius is at least [`STABLE_RADIUS`]: the mode grows (above one) or
    /// keeps an undamped part (one), and has no stationary distribution.
    Unstable { radius: f64 },
}

/// Spectral radius of the step's deterministic part.
pub fn spectral_radius(map: &StepMap) -> f64 {
    map.m
        .complex_eigenvalues()
        .iter()
        .map(|l| l.norm())
        .fold(0.0, f64::max)
}

/// The stationary covariance of `map`, or why there is none.
pub fn stationary_covariance(map: &StepMap) -> Stationary {
    let radius = spectral_radius(map);
    if radius.is_nan() || radius >= STABLE_RADIUS {
        return Stationary::Unstable { radius };
    }
    let m = &map.m;
    let kron: SMatrix<f64, 9, 9> = m.kronecker(m);
    let a = SMatrix::<f64, 9, 9>::identity() - kron;
    let q = map.noise_covariance();
    let vq = SVector::<f64, 9>::from_iterator(q.iter().copied());
    match a.lu().solve(&vq) {
        Some(v) => {
            let c = Matrix3::from_iterator(v.iter().copied());
            // Symmetric up to rounding; keep it exactly so.
            Stationary::Covariance((c + c.transpose()) / 2.0)
        }
        None => Stationary::Unstable { radius },
    }
}
