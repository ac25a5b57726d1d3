//! The `order >= N` and `invariant_order >= N` assertions, checked against the order analysis
//! of `dpd_ir::analysis` (algorithms.md section 4).

use dpd_ir::analysis::{self, Analysis};
use dpd_ir::Program;

use crate::args::{Args, Bound};
use crate::fallback::combine;

/// Every failed assertion of `args` about `program`, as errors at the assertion's tokens.
pub fn check(program: &Program, args: &Args) -> syn::Result<()> {
    if args.order.is_none() && args.invariant_order.is_none() {
        return Ok(());
    }
    // Analyse as deep as the assertions need, and at least as deep as `Program::analysis`.
    let defaults = analysis::Options::default();
    let depth = |bound: &Option<Bound>, default: u32| {
        bound.as_ref().map_or(default, |b| b.min.max(default))
    };
    let options = analysis::Options {
        max_degree: depth(&args.order, defaults.max_degree),
        max_invariant_order: depth(&args.invariant_order, defaults.max_invariant_order),
        ..defaults
    };
    let found = analysis::analyse_with(&program.unmerged_stages, &options);
    let errors = [
        args.order
            .as_ref()
            .and_then(|b| deterministic_order(b, &found)),
        args.invariant_order
            .as_ref()
            .and_then(|b| invariant_order(b, &found)),
    ];
    combine(errors.into_iter().flatten()).map_or(Ok(()), Err)
}

/// `order >= N`: the Hamiltonian part (O dropped) matches `exp(dt (A + B))` through degree N.
fn deterministic_order(bound: &Bound, found: &Analysis) -> Option<syn::Error> {
    let why = if !found.consistent {
        let s = &found.coefficient_sums;
        format!(
            "the scheme is inconsistent (coefficient sums A = {}, B = {}, O = {}), so it has no order",
            s.a, s.b, s.o
        )
    } else if found.deterministic_order < bound.min {
        format!(
            "the analysis finds deterministic order {} for the Hamiltonian part",
            found.deterministic_order
        )
    } else {
        return None;
    };
    Some(failed(bound, "does not hold", &why))
}

/// `invariant_order >= N`: the left-ideal bound on the order of the invariant measure.
fn invariant_order(bound: &Bound, found: &Analysis) -> Option<syn::Error> {
    let why = match found.invariant_measure_order {
        None => {
            return Some(failed(
                bound,
                "cannot be checked",
                "the invariant-measure bound does not apply to schemes with F stages (not a \
                 splitting of exact flows); measure it instead",
            ))
        }
        Some(p) if p < bound.min => {
            let term = found
                .first_nonvanishing
                .as_ref()
                .map_or(String::new(), |t| {
                    format!(" (first non-vanishing term L_{p} rho = {t})")
                });
            format!("the analysis finds invariant-measure order {p}{term}")
        }
        Some(_) => return None,
    };
    Some(failed(bound, "does not hold", &why))
}

/// "`order >= 3` does not hold: why", at the assertion's tokens.
fn failed(bound: &Bound, verdict: &str, why: &str) -> syn::Error {
    syn::Error::new_spanned(
        &bound.tokens,
        format!("`{}` {verdict}: {why}", bound.tokens),
    )
}
