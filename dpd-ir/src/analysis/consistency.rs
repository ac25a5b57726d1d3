//! Consistency: the coefficients of each generator sum to one (algorithms.md section 4.1).

use serde::Serialize;

use super::scalar::Scalar;
use crate::forces::{kicks, ForceGroup, Kick};
use crate::program::{Flow, Stage};

/// Tolerance of the `f64` consistency test `|sum - 1| <= CONSISTENCY_TOLERANCE`.
pub const CONSISTENCY_TOLERANCE: f64 = 1e-12;

/// Sum of the coefficients carried by each generator: A by A stages; B by B, T and F stages;
/// O by O, Bbk, T and F stages. In a step that names force groups (module
/// [`crate::forces`]) B is the pair forces' generator (B, B[pair], T, F and F[pair] stages)
/// and the bonded forces have their own.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CoefficientSums {
    pub a: f64,
    pub b: f64,
    pub o: f64,
    /// The sum of the bonded forces' generator (B, B[bond] and F stages), in a step that
    /// names force groups and applies bonded forces; `None` otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bond: Option<f64>,
    /// The sums were computed in exact rational arithmetic (every coefficient was exact).
    pub exact: bool,
    /// Some stage carries O. A scheme without one is purely Hamiltonian, and its O sum is not
    /// required to be one.
    pub thermostat: bool,
}

/// The coefficient sums of `stages` (with coefficients `coeffs`, one per stage) and whether
/// the scheme is consistent: the A sum, every kick generator's sum and, if any stage carries
/// O, the O sum equal one (exactly in exact arithmetic, else to [`CONSISTENCY_TOLERANCE`]).
pub(crate) fn coefficient_sums<S: Scalar>(
    stages: &[Stage],
    coeffs: &[S],
) -> (CoefficientSums, bool) {
    let sum = |carries: &dyn Fn(&Stage) -> bool| {
        stages
            .iter()
            .zip(coeffs)
            .filter(|(s, _)| carries(s))
            .fold(S::zero(), |acc, (_, c)| acc.plus(c))
    };
    let kicks: Vec<(Kick, S)> = kicks(stages.iter().map(|s| (s.flow, s.group)))
        .into_iter()
        .map(|k| (k, sum(&|s: &Stage| k.advanced_by(s.flow, s.group))))
        .collect();
    let a = sum(&|s: &Stage| s.flow == Flow::A);
    let o = sum(&|s: &Stage| s.flow.is_stochastic());
    let thermostat = stages.iter().any(|s| s.flow.is_stochastic());
    let is_one = |s: &S| {
        let d = s.minus(&S::ratio(1, 1));
        if S::EXACT {
            d.is_zero()
        } else {
            d.to_f64().abs() <= CONSISTENCY_TOLERANCE
        }
    };
    let consistent =
        is_one(&a) && kicks.iter().all(|(_, s)| is_one(s)) && (!thermostat || is_one(&o));
    let of = |k: Kick| kicks.iter().find(|(x, _)| *x == k).map(|(_, s)| s.to_f64());
    let sums = CoefficientSums {
        a: a.to_f64(),
        b: of(Kick::All)
            .or(of(Kick::Group(ForceGroup::Pair)))
            .unwrap_or(0.0),
        o: o.to_f64(),
        bond: of(Kick::Group(ForceGroup::Bond)),
        exact: S::EXACT,
        thermostat,
    };
    (sums, consistent)
}
