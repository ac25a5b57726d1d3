//! The analysis report.

use std::fmt;

use serde::Serialize;

use super::consistency::CoefficientSums;

/// The order analysis of one step.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Analysis {
    /// The step has a Metropolis-adjusted part (`{ ... }`, validated by the language: a
    /// symmetric A/B word inside, only O, Ob and L outside): its invariant measure is the Gibbs
    /// measure exactly, at any dt. The orders below are those of the unadjusted word (the
    /// braces left out), which the adjusted chain follows while it accepts.
    pub metropolis_adjusted: bool,
    /// Each generator's coefficients sum to one (see [`CoefficientSums::thermostat`]).
    pub consistent: bool,
    pub coefficient_sums: CoefficientSums,
    /// Exact rational arithmetic was used throughout (every coefficient was exact).
    pub exact: bool,
    /// Order of the Hamiltonian part; 0 when the scheme is inconsistent.
    pub deterministic_order: u32,
    /// Every degree checked matched: the order is at least `deterministic_order`.
    pub deterministic_order_capped: bool,
    /// Bound `p` of the left-ideal criterion: `f_n = 0` for `0 < n < p`. `None` for schemes
    /// with F stages (not a splitting of exact flows) or with Oa, On and Xi (the adaptive friction
    /// is a variable outside the criterion's generators): measure them.
    pub invariant_measure_order: Option<u32>,
    /// The criterion found nothing up to the maximal order checked: the bound is at least
    /// `invariant_measure_order`.
    pub invariant_measure_order_capped: bool,
    /// The first non-vanishing reduced term `L_p rho`, words in adjoint order (the sub-flow
    /// applied last stands leftmost; the reduction keeps words ending in A, `B_k` or `E_k`).
    pub first_nonvanishing: Option<String>,
    /// Size of the leading error of the Hamiltonian part, the coefficient of `dt^(p+1)` in
    /// `log(step) - dt (A + B)` (p the deterministic order): the Euclidean norm of its
    /// coordinates in the Lyndon basis of the free Lie algebra on A < B, standard bracketing
    /// (`[A,[A,B]]`, `[B,[B,A]]` at degree 3), no relation of the problem assumed. `None` when
    /// inconsistent or when the order reached the highest degree checked.
    pub deterministic_error_norm: Option<f64>,
    /// The leading Hamiltonian error term itself, e.g. `-1/24 [A,[A,B]] + 1/12 [[A,B],B]`.
    pub deterministic_leading_term: Option<String>,
    /// Size of the first non-vanishing term [`Analysis::first_nonvanishing`]: the Euclidean
    /// norm of its coefficients over the words shown (the word basis of the quotient by the
    /// left ideal, K = 2 pair generators per sweep). `None` where that term is `None`.
    pub invariant_measure_error_norm: Option<f64>,
}

impl fmt::Display for Analysis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = &self.coefficient_sums;
        let at_least = |capped: bool| if capped { ">= " } else { "" };
        writeln!(
            f,
            "consistent: {} (coefficient sums A = {}, B = {}, O = {}{}{})",
            if self.consistent { "yes" } else { "no" },
            s.a,
            s.b,
            s.o,
            if s.thermostat { "" } else { ", no thermostat" },
            if self.exact { ", exact" } else { ", f64" },
        )?;
        writeln!(
            f,
            "deterministic order: {}{}",
            at_least(self.deterministic_order_capped),
            self.deterministic_order
        )?;
        if self.metropolis_adjusted {
            writeln!(
                f,
                "invariant measure: exact, the Gibbs measure exp(-H / k_B T) at any dt \
                 (Metropolis-adjusted: the symmetric A/B word in braces is reversible and \
                 volume-preserving, its accept/reject on exp(-Delta H / k_B T) with the momenta \
                 negated on rejection keeps the measure, and O, Ob and L keep it exactly per \
                 pair); the orders below are the unadjusted word's"
            )?;
        }
        match self.invariant_measure_order {
            Some(p) => writeln!(
                f,
                "invariant-measure order (left-ideal bound): {}{p}",
                at_least(self.invariant_measure_order_capped)
            )?,
            None => writeln!(
                f,
                "invariant-measure order: not applicable (F stages are not exact flows, and Oa, On and \
                 Xi move the adaptive friction xi, which the A, B and O generators do not describe; \
                 measure it)"
            )?,
        }
        if let (Some(term), Some(norm)) = (
            &self.deterministic_leading_term,
            self.deterministic_error_norm,
        ) {
            writeln!(
                f,
                "leading deterministic error: dt^{} ({term}), norm {norm:.6} (Lyndon basis)",
                self.deterministic_order + 1
            )?;
        }
        match (&self.first_nonvanishing, self.invariant_measure_order) {
            (Some(term), Some(p)) => writeln!(
                f,
                "first non-vanishing term: L_{p} rho = {term}, norm {:.6}",
                self.invariant_measure_error_norm.unwrap_or(f64::NAN)
            ),
            _ => Ok(()),
        }
    }
}
