//! Consistency: the coefficients of each generator sum to one (algorithms.md section 4.1).

use serde::Serialize;

use super::scalar::Scalar;
use crate::program::{Flow, Stage};

/// Tolerance of the `f64` consistency test `|sum - 1| <= CONSISTENCY_TOLERANCE`.
pub const CONSISTENCY_TOLERANCE: f64 = 1e-12;

/// Sum of the coefficients carried by each generator: A by A stages; B by B, T and F stages;
/// O by O, Bbk, T and F stages.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CoefficientSums {
    pub a: f64,
    pub b: f64,
    pub o: f64,
    /// The sums were computed in exact rational arithmetic (every coefficient was exact).
    pub exact: bool,
    /// Some stage carries O. A scheme without one is purely Hamiltonian, and its O sum is not
    /// required to be one.
    pub thermostat: bool,
}

/// The generators a flow carries, as (A, B, O).
fn carries(flow: Flow) -> (bool, bool, bool) {
    match flow {
        Flow::A => (true, false, false),
        Flow::B => (false, true, false),
        Flow::O | Flow::Bbk => (false, false, true),
        Flow::T | Flow::F => (false, true, true),
    }
}

/// The coefficient sums of `stages` (with coefficients `coeffs`, one per stage) and whether
/// the scheme is consistent: A and B sums equal one and, if any stage carries O, so does the
/// O sum (exactly in exact arithmetic, else to [`CONSISTENCY_TOLERANCE`]).
pub(crate) fn coefficient_sums<S: Scalar>(
    stages: &[Stage],
    coeffs: &[S],
) -> (CoefficientSums, bool) {
    let (mut a, mut b, mut o) = (S::zero(), S::zero(), S::zero());
    let mut thermostat = false;
    for (stage, c) in stages.iter().zip(coeffs) {
        let (ca, cb, co) = carries(stage.flow);
        if ca {
            a = a.plus(c);
        }
        if cb {
            b = b.plus(c);
        }
        if co {
            o = o.plus(c);
            thermostat = true;
        }
    }
    let is_one = |s: &S| {
        let d = s.minus(&S::ratio(1, 1));
        if S::EXACT {
            d.is_zero()
        } else {
            d.to_f64().abs() <= CONSISTENCY_TOLERANCE
        }
    };
    let consistent = is_one(&a) && is_one(&b) && (!thermostat || is_one(&o));
    let sums = CoefficientSums {
        a: a.to_f64(),
        b: b.to_f64(),
        o: o.to_f64(),
        exact: S::EXACT,
        thermostat,
    };
    (sums, consistent)
}
