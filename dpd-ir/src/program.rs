//! The flattened form of a scheme: the sequence of sub-flow applications of one step.
//!
//! This is the contract between the language front end (`lang`), the order analysis
//! (`analysis`), the proc macro (which turns a [`Program`] into straight-line calls) and the
//! run-time interpreter in `dpd-core` (which walks the same stages). Both back ends call the
//! same core function for each [`Stage`] with the same `f64` coefficient, which is what makes
//! macro-generated and dynamic schemes bitwise identical.

use num_rational::BigRational;
use serde::{Deserialize, Serialize};

/// A sub-flow of the DPD dynamics (algorithms.md section 2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Flow {
    /// Drift `q += h p / m`. Exact; accepts any sign of `h`.
    A,
    /// Conservative kick `p += h F^C(q)`. Exact; accepts any sign of `h`.
    B,
    /// Pairwise Ornstein-Uhlenbeck sweep, exact in distribution per pair. Needs `h > 0`.
    O,
    /// Pairwise Ornstein-Uhlenbeck sweep with Shardlow's BBK update (weakly second order).
    /// Needs `h > 0`.
    Bbk,
    /// Pairwise conservative + OU update, exact per pair (DPD-Trotter piece). Needs `h > 0`.
    T,
    /// Explicit full-force kick `p += h (F^C + F^D + F^R)`; not a splitting of exact flows.
    /// An evaluation is reused while positions do not change (velocity Verlet convention).
    F,
}

impl Flow {
    /// Every flow, in the order of the enum.
    pub const ALL: [Flow; 6] = [Flow::A, Flow::B, Flow::O, Flow::Bbk, Flow::T, Flow::F];

    /// True for the flows that loop over pairs drawing random numbers.
    pub fn is_stochastic(self) -> bool {
        matches!(self, Flow::O | Flow::Bbk | Flow::T | Flow::F)
    }

    /// True for the flows that visit pairs successively, so that their order matters.
    pub fn is_successive_sweep(self) -> bool {
        matches!(self, Flow::O | Flow::Bbk | Flow::T)
    }

    /// True for the flows that change positions.
    pub fn moves_positions(self) -> bool {
        matches!(self, Flow::A)
    }

    /// True for the flows that may not run with a zero or negative step (stochastic ones).
    pub fn needs_positive_step(self) -> bool {
        self.is_successive_sweep()
    }
}

/// The order in which a successive pair sweep visits the pair list.
///
/// `Forward` is the documented base order of `dpd-core` (pairs sorted by `(i, j)`, `i < j`);
/// `Reverse` visits the same pairs last to first.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum SweepOrder {
    #[default]
    Forward,
    Reverse,
}

/// A step-length coefficient: the step length of a stage is `value * dt`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Coeff {
    /// The coefficient as used at run time.
    pub value: f64,
    /// The exact rational value, where the coefficient is rational.
    #[serde(skip)]
    pub exact: Option<BigRational>,
}

/// One sub-flow application inside a step.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Stage {
    pub flow: Flow,
    pub coeff: Coeff,
    /// Random-number stream of this stage within the step (the `sweep` component of the pair
    /// RNG key). Distinct stochastic stages get distinct streams, except where a scheme asks for
    /// frozen noise (PRK tables: all full-force stages of a step share one stream). 0 for
    /// deterministic flows.
    pub stream: u8,
    /// Visiting order of a successive sweep (`Forward` for all other flows).
    pub order: SweepOrder,
}
