//! The harmonic spectrum of a DPD configuration: its pair network.
//!
//! Every pair within the cut-off is a radial spring of stiffness `phi''(r) = a / r_c` (the
//! soft potential's curvature, the same for every pair inside r_c) and a radial dashpot
//! `gamma w_D(r)`, as the pair's O update acts along `e_ij` only. The mass-weighted stiffness
//! matrix `K` and friction matrix `Gamma` (3N x 3N) give the modes: the eigenvalues of `K` are
//! the squared frequencies, and each mode's friction is its Rayleigh quotient of `Gamma`;
//! one more mode is `Gamma`'s stiffest direction (`stiffest_friction`).
//! The transverse curvature `phi'(r)/r` is left out: it is negative (the repulsion pushes
//! pairs apart), and with it the network has unstable modes with no stationary state.
//!
//! The eigendecomposition is dense, O((3N)^3): a few hundred particles at the fluid's density
//! give the spectrum's shape (it is a per-particle density), in about a second.

use crate::spectrum::{Mode, Spectrum};
use nalgebra::{DMatrix, SymmetricEigen};

/// The pair interactions a network is built with (algorithms.md section 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairModel {
    /// Repulsion `a`.
    pub a: f64,
    /// Cut-off `r_c`.
    pub rc: f64,
    /// Friction `gamma`.
    pub gamma: f64,
    /// Weight exponent `s`: `w_D(r) = (1 - r/r_c)^s`.
    pub weight_exponent: f64,
    /// `k_B T`.
    pub kbt: f64,
}

/// Modes whose squared frequency is below this fraction of the largest are zero modes (the
/// centre of mass, particles without neighbours) and are left out.
const ZERO_MODE: f64 = 1e-9;

#[cfg(test)]
impl PairModel {
    /// The standard box's pair forces (algorithms.md section 8), for tests.
    pub(crate) fn standard() -> Self {
        PairModel {
            a: 25.0,
            rc: 1.0,
            gamma: 4.5,
            weight_exponent: 2.0,
            kbt: 1.0,
        }
    }
}

/// Why a configuration has no network.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum NetworkError {
    #[error("invalid {field} = {value}: {allowed}")]
    Invalid {
        field: &'static str,
        value: String,
        allowed: &'static str,
    },
}

fn invalid(
    field: &'static str,
    value: impl std::fmt::Debug,
    allowed: &'static str,
) -> NetworkError {
    NetworkError::Invalid {
        field,
        value: format!("{value:?}"),
        allowed,
    }
}

/// Refuses a configuration or pair model the network cannot be built from.
pub(crate) fn check(
    q: &[[f64; 3]],
    masses: &[f64],
    edges: [f64; 3],
    model: PairModel,
) -> Result<(), NetworkError> {
    if masses.len() != q.len() {
        return Err(invalid(
            "masses",
            masses.len(),
            "must have one entry per position",
        ));
    }
    if let Some(m) = masses.iter().find(|m| !(m.is_finite() && **m > 0.0)) {
        return Err(invalid("masses", m, "must be finite and positive"));
    }
    if let Some(x) = q.iter().find(|x| x.iter().any(|c| !c.is_finite())) {
        return Err(invalid("positions", x, "must be finite"));
    }
    if edges.iter().any(|l| !(l.is_finite() && *l > 0.0)) {
        return Err(invalid("edges", edges, "must be finite and positive"));
    }
    let finite = [
        model.a,
        model.rc,
        model.gamma,
        model.weight_exponent,
        model.kbt,
    ];
    if finite.iter().any(|x| !x.is_finite())
        || model.rc <= 0.0
        || model.kbt <= 0.0
        || model.gamma < 0.0
    {
        return Err(invalid(
            "pair model",
            model,
            "needs finite values, r_c > 0, k_B T > 0 and gamma >= 0",
        ));
    }
    Ok(())
}

/// The pairs `(i, j, e_ij, r_ij)` of `q` closer than `rc` (minimum image, `i < j`, coincident
/// particles left out), `e_ij` the unit vector from j to i.
pub(crate) fn pairs(
    q: &[[f64; 3]],
    edges: [f64; 3],
    rc: f64,
) -> impl Iterator<Item = (usize, usize, [f64; 3], f64)> + '_ {
    let n = q.len();
    (0..n)
        .flat_map(move |i| (i + 1..n).map(move |j| (i, j)))
        .filter_map(move |(i, j)| {
            let mut d = [0.0; 3];
            for c in 0..3 {
                let x = q[i][c] - q[j][c];
                d[c] = x - edges[c] * (x / edges[c]).round();
            }
            let r = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            (r < rc && r > 0.0).then(|| (i, j, d.map(|x| x / r), r))
        })
}

/// The spectrum of the pair network of one configuration: positions `q` in a periodic box of
/// edges `edges`, particle masses `masses`.
pub fn spectrum(
    q: &[[f64; 3]],
    masses: &[f64],
    edges: [f64; 3],
    model: PairModel,
) -> Result<Spectrum, NetworkError> {
    check(q, masses, edges, model)?;
    let n = q.len();
    let mut k = DMatrix::<f64>::zeros(3 * n, 3 * n);
    let mut g = DMatrix::<f64>::zeros(3 * n, 3 * n);
    let stiffness = model.a / model.rc;
    for (i, j, e, r) in pairs(q, edges, model.rc) {
        let wd = (1.0 - r / model.rc).powf(model.weight_exponent);
        let scale = 1.0 / (masses[i] * masses[j]).sqrt();
        for a in 0..3 {
            for b in 0..3 {
                let ee = e[a] * e[b];
                for (u, v, sign) in [(i, i, 1.0), (j, j, 1.0), (i, j, -1.0), (j, i, -1.0)] {
                    let mass = if u == v { 1.0 / masses[u] } else { scale };
                    k[(3 * u + a, 3 * v + b)] += sign * mass * stiffness * ee;
                    g[(3 * u + a, 3 * v + b)] += sign * mass * model.gamma * wd * ee;
                }
            }
        }
    }
    let probe = stiffest_friction(&g, &k);
    let eigen = SymmetricEigen::new(k);
    let largest = eigen.eigenvalues.iter().copied().fold(0.0, f64::max);
    let mut modes: Vec<Mode> = eigen
        .eigenvalues
        .iter()
        .enumerate()
        .filter(|&(_, &w2)| w2 > ZERO_MODE * largest)
        .map(|(col, &omega2)| {
            let v = eigen.eigenvectors.column(col);
            let gamma = (v.transpose() * &g * v)[(0, 0)].max(0.0);
            Mode { omega2, gamma }
        })
        .collect();
    modes.extend(probe);
    let volume = edges.iter().product();
    Ok(Spectrum {
        modes,
        particles: n,
        volume,
        kbt: model.kbt,
        response: None,
    })
}

/// Power iterations for the friction matrix's largest eigenvalue, and their tolerance.
const POWER_ITERATIONS: usize = 1000;
const POWER_TOLERANCE: f64 = 1e-9;

/// The friction matrix's stiffest direction `u` as one more mode: friction its largest
/// eigenvalue, squared frequency `u^T K u`. The stiffness eigenvectors average the friction
/// matrix's largest eigenvalue down (the two matrices do not commute), and an explicit
/// friction (F) is stable only while dt times that eigenvalue stays small: this mode keeps
/// the stability limit of velocity Verlet at high friction; among hundreds of modes its
/// weight in the averages is negligible. `None` without friction.
fn stiffest_friction(g: &DMatrix<f64>, k: &DMatrix<f64>) -> Option<Mode> {
    let n = g.nrows();
    // A start with a component along every direction (no symmetry of the box cancels it).
    let mut u = nalgebra::DVector::from_fn(n, |i, _| 1.0 + ((i * 7919) % 13) as f64 / 13.0);
    let mut lambda = 0.0;
    for _ in 0..POWER_ITERATIONS {
        let w = g * &u;
        let norm = w.norm();
        if norm == 0.0 {
            return None;
        }
        let next = norm / u.norm();
        u = w / norm;
        if (next - lambda).abs() <= POWER_TOLERANCE * next {
            lambda = next;
            break;
        }
        lambda = next;
    }
    let omega2 = (u.transpose() * k * &u)[(0, 0)];
    Some(Mode {
        omega2,
        gamma: lambda,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// Two particles at distance r: one mode, the relative coordinate, with stiffness
    /// `a / r_c` over the reduced mass `m / 2` and friction `gamma w_D(r)` over it; the
    /// centre of mass and the two rotations are zero modes.
    #[test]
    fn a_pair_has_one_mode_of_its_reduced_mass() {
        let model = PairModel::standard();
        let (m, r) = (2.0, 0.6);
        let s = spectrum(
            &[[1.0, 1.0, 1.0], [1.0 + r, 1.0, 1.0]],
            &[m, m],
            [5.0; 3],
            model,
        )
        .unwrap();
        // The pair's mode, and the friction matrix's stiffest direction: the same one.
        assert_eq!(s.modes.len(), 2);
        let wd = (1.0 - r) * (1.0 - r);
        for mode in &s.modes {
            assert_relative_eq!(mode.omega2, 2.0 * 25.0 / m, max_relative = 1e-9);
            assert_relative_eq!(mode.gamma, 2.0 * 4.5 * wd / m, max_relative = 1e-9);
        }
    }

    #[test]
    fn bad_configurations_are_refused() {
        let model = PairModel::standard();
        let q = [[0.0; 3], [0.5, 0.0, 0.0]];
        assert!(spectrum(&q, &[1.0], [5.0; 3], model).is_err());
        assert!(spectrum(&q, &[1.0, 0.0], [5.0; 3], model).is_err());
        assert!(spectrum(&q, &[1.0, 1.0], [5.0, 0.0, 5.0], model).is_err());
        let nan = [[f64::NAN, 0.0, 0.0], [0.5, 0.0, 0.0]];
        assert!(spectrum(&nan, &[1.0, 1.0], [5.0; 3], model).is_err());
    }
}
