//! Order analysis of a flattened scheme (algorithms.md section 4).
//!
//! [`analyse`] reports consistency, the deterministic order of the Hamiltonian part and a bound
//! on the order of the invariant measure, from the stages of one step (application order, left
//! first). Both orders come from one hand-written truncated free associative algebra
//! (module `algebra`; no crate provides non-commutative power series), over exact rationals when
//! every coefficient is exact and over `f64` otherwise (module `scalar`).
//!
//! Which way products are written: the deterministic order multiplies the stage exponentials
//! with the first applied leftmost (module `hamiltonian`; the order does not depend on it);
//! the invariant-measure criterion works with Fokker-Planck adjoints acting on `rho` from the
//! right, so there the sub-flow applied last stands leftmost (module `invariant`), and so do
//! the words of [`Analysis::first_nonvanishing`].

mod algebra;
mod consistency;
mod hamiltonian;
mod invariant;
mod lyndon;
mod prk;
mod report;
mod scalar;

pub use consistency::{CoefficientSums, CONSISTENCY_TOLERANCE};
pub use prk::{analyse_prk, prk3_conditions, prk_stages};
pub use report::Analysis;
pub use scalar::FLOAT_TOLERANCE;

/// Highest invariant-measure order [`order_residuals`] can impose.
pub const MAX_INVARIANT_ORDER: u32 = 5;

use crate::program::Stage;
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::One;
use scalar::{Rational, Scalar};

/// Limits of an analysis. Values are clamped to the documented ranges, which keep the work
/// bounded for any input.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Options {
    /// Highest word length compared for the deterministic order (1..=12, default 8).
    pub max_degree: u32,
    /// Highest `n` for which `L_n` is checked by the invariant-measure criterion (1..=5,
    /// default 4).
    pub max_invariant_order: u32,
    /// Number `K` of non-commuting pair generators modelling a pair sweep (2..=3, default 2).
    pub pairs: usize,
    /// Use `f64` even when every coefficient is exact (faster, for bulk enumeration).
    pub force_float: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            max_degree: 8,
            max_invariant_order: 4,
            pairs: 2,
            force_float: false,
        }
    }
}

/// Analyses one step with the default [`Options`].
pub fn analyse(stages: &[Stage]) -> Analysis {
    analyse_with(stages, &Options::default())
}

/// Analyses one step (stages in application order, left first).
pub fn analyse_with(stages: &[Stage], options: &Options) -> Analysis {
    let options = Options {
        max_degree: options.max_degree.clamp(1, 12),
        max_invariant_order: options.max_invariant_order.clamp(1, 5),
        pairs: options.pairs.clamp(2, 3),
        force_float: options.force_float,
    };
    match exact_coefficients(stages).filter(|_| !options.force_float) {
        Some(coeffs) => analyse_in(stages, &coeffs, &options),
        None => {
            let coeffs: Vec<f64> = stages.iter().map(|s| s.coeff.value).collect();
            analyse_in(stages, &coeffs, &options)
        }
    }
}

/// Largest size, in bits, of the exact coefficients analysed exactly: the bits of the least
/// common multiple of their denominators plus those of the largest numerator. Word
/// coefficients of degree `n` carry about `n` times that many bits, so beyond it exact
/// arithmetic grows slow (a 200-pair string with distinct prime denominators took minutes) and
/// the analysis works in `f64` instead, as for irrational coefficients.
pub const MAX_EXACT_BITS: u64 = 256;

/// The exact coefficients, if every stage has one and they are at most [`MAX_EXACT_BITS`] big.
fn exact_coefficients(stages: &[Stage]) -> Option<Vec<Rational>> {
    let exact: Vec<&BigRational> = stages
        .iter()
        .map(|s| s.coeff.exact.as_ref())
        .collect::<Option<_>>()?;
    let mut lcm = BigInt::one();
    let mut numerator_bits = 0;
    for r in &exact {
        lcm = lcm.lcm(r.denom());
        numerator_bits = numerator_bits.max(r.numer().bits());
        if lcm.bits() + numerator_bits > MAX_EXACT_BITS {
            return None;
        }
    }
    exact.into_iter().map(Rational::from_big).collect()
}

/// Residuals of the order conditions of one step, in `f64`: the coefficient sums minus one
/// (the O sum only with a thermostat), the deterministic conditions up to order `det` and the
/// invariant-measure conditions `L_0 ... L_(inv-1)` (K = `pairs` pair generators). All are zero
/// iff the step is consistent with deterministic order >= `det` and invariant-measure bound
/// >= `inv`. `None` when `inv > 0` and the criterion does not apply (F stages).
pub fn order_residuals(stages: &[Stage], det: u32, inv: u32, pairs: usize) -> Option<Vec<f64>> {
    let coeffs: Vec<f64> = stages.iter().map(|s| s.coeff.value).collect();
    let (sums, _) = consistency::coefficient_sums(stages, &coeffs);
    let mut out = vec![sums.a - 1.0, sums.b - 1.0];
    out.extend(sums.bond.map(|b| b - 1.0));
    if sums.thermostat {
        out.push(sums.o - 1.0);
    }
    let factors = hamiltonian::hamiltonian_factors(stages, &coeffs);
    out.extend(hamiltonian::deterministic_residuals(&factors, det.min(12)));
    if inv > 0 {
        out.extend(invariant::invariant_residuals(
            stages,
            &coeffs,
            pairs.clamp(2, 3),
            inv.min(5),
        )?);
    }
    Some(out)
}

fn analyse_in<S: Scalar>(stages: &[Stage], coeffs: &[S], options: &Options) -> Analysis {
    let (coefficient_sums, consistent) = consistency::coefficient_sums(stages, coeffs);
    let factors = hamiltonian::hamiltonian_factors(stages, coeffs);
    let det = hamiltonian::deterministic_order(&factors, options.max_degree);
    let inv = invariant::invariant_measure_bound(
        stages,
        coeffs,
        options.pairs,
        options.max_invariant_order,
    );
    let leading = (consistent && !det.capped)
        .then(|| hamiltonian::leading_error(&factors, det.order))
        .flatten();
    Analysis {
        metropolis_adjusted: stages
            .iter()
            .any(|s| s.flow == crate::program::Flow::Propose),
        consistent,
        coefficient_sums,
        exact: S::EXACT,
        deterministic_order: if consistent { det.order } else { 0 },
        deterministic_order_capped: consistent && det.capped,
        invariant_measure_order: inv.as_ref().map(|b| b.order),
        invariant_measure_order_capped: inv.as_ref().is_some_and(|b| b.capped),
        invariant_measure_error_norm: inv.as_ref().and_then(|b| b.leading_norm),
        first_nonvanishing: inv.and_then(|b| b.leading_term),
        deterministic_error_norm: leading.as_ref().map(|e| e.norm),
        deterministic_leading_term: leading.map(|e| lyndon::spell_terms(&e.terms, &factors.names)),
    }
}
