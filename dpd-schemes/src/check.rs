//! The check of a registry name or a scheme string: what `dpd check --json` prints and what the
//! Python module's `dpd.check` returns. Inconsistent schemes are analysed and reported, not
//! refused.

use crate::registry::{lookup, ResolveError, Row};
use dpd_ir::analysis::CoefficientSums;
use dpd_ir::lang::{compile_family, compile_with, Options};
use dpd_ir::{Analysis, Program};
use serde::Serialize;
use std::collections::BTreeMap;
use thiserror::Error;

/// The analysis of one scheme. For a hand-written registry scheme (no program) the orders and
/// costs are the registry's documented claims and `coefficient_sums` is null.
#[derive(Clone, Debug, Serialize)]
pub struct Check {
    pub scheme: String,
    /// The merged stages of one step, or the step in words.
    pub program: String,
    pub hand_written: bool,
    pub consistent: bool,
    pub coefficient_sums: Option<CoefficientSums>,
    /// 0 when inconsistent.
    pub deterministic_order: u32,
    pub deterministic_order_capped: bool,
    /// Left-ideal bound; null where the criterion does not apply (F stages, hand-written).
    pub invariant_measure_order: Option<u32>,
    pub invariant_measure_order_capped: bool,
    pub first_nonvanishing: Option<String>,
    /// Euclidean norm of the leading Hamiltonian error in the Lyndon basis (see
    /// [`Analysis::deterministic_error_norm`]); null when not analysed or inconsistent.
    pub deterministic_error_norm: Option<f64>,
    /// The leading Hamiltonian error term in the Lyndon basis.
    pub deterministic_leading_term: Option<String>,
    /// Euclidean norm of `first_nonvanishing` over its words (see
    /// [`Analysis::invariant_measure_error_norm`]).
    pub invariant_measure_error_norm: Option<f64>,
    /// The step has a Metropolis-adjusted part (`{...}`): its invariant measure is the Gibbs
    /// measure exactly, and the orders are the unadjusted word's.
    pub metropolis_adjusted: bool,
    pub symmetric: bool,
    /// Pair-force evaluations per step.
    pub force_evaluations_per_step: usize,
    pub pair_distance_evaluations_per_step: usize,
    /// Bonded-force evaluations per step on a system with bonded forces, counted apart from
    /// the pair evaluations, which cost far more; null for hand-written schemes.
    pub bonded_force_evaluations_per_step: Option<usize>,
    /// For a scheme with free parameters (`param`): the point analysed, name -> value (a
    /// generic point of the box unless given). Null for a scheme without parameters.
    pub parameters: Option<BTreeMap<String, f64>>,
    /// The full analysis, for the text report.
    #[serde(skip)]
    pub analysis: Option<Analysis>,
}

/// A text that is neither a registered scheme nor a valid scheme string.
#[derive(Clone, Debug, PartialEq, Error)]
#[error("invalid scheme: {reason}")]
pub struct CheckError {
    /// The text as given.
    pub scheme: String,
    pub reason: ResolveError,
}

impl Check {
    fn of_program(scheme: String, program: &Program) -> Check {
        let a = program.analysis();
        let cost = program.evaluations_per_step();
        Check {
            scheme,
            program: program.to_string(),
            hand_written: false,
            consistent: a.consistent,
            coefficient_sums: Some(a.coefficient_sums.clone()),
            deterministic_order: a.deterministic_order,
            deterministic_order_capped: a.deterministic_order_capped,
            invariant_measure_order: a.invariant_measure_order,
            invariant_measure_order_capped: a.invariant_measure_order_capped,
            first_nonvanishing: a.first_nonvanishing.clone(),
            deterministic_error_norm: a.deterministic_error_norm,
            deterministic_leading_term: a.deterministic_leading_term.clone(),
            invariant_measure_error_norm: a.invariant_measure_error_norm,
            metropolis_adjusted: a.metropolis_adjusted,
            symmetric: program.is_symmetric(),
            force_evaluations_per_step: cost.force,
            pair_distance_evaluations_per_step: cost.pair_distance,
            bonded_force_evaluations_per_step: Some(cost.bonded_force),
            parameters: None,
            analysis: Some(a),
        }
    }

    fn of_row(row: &Row) -> Check {
        Check {
            scheme: row.name.to_string(),
            program: row.sequence.clone(),
            hand_written: true,
            consistent: row.consistent,
            coefficient_sums: None,
            deterministic_order: row.deterministic_order,
            deterministic_order_capped: false,
            invariant_measure_order: row.invariant_measure_order,
            invariant_measure_order_capped: false,
            first_nonvanishing: None,
            deterministic_error_norm: None,
            deterministic_leading_term: None,
            invariant_measure_error_norm: None,
            metropolis_adjusted: false,
            symmetric: row.symmetric,
            force_evaluations_per_step: row.force_evaluations_per_step,
            pair_distance_evaluations_per_step: row.pair_distance_evaluations_per_step,
            bonded_force_evaluations_per_step: None,
            parameters: None,
            analysis: None,
        }
    }
}

/// The check of a registry entry, else of the text compiled with inconsistency allowed; a
/// text with free parameters is analysed at a generic point of its box (the orders found
/// there hold for almost every point).
pub fn check(name_or_source: &str) -> Result<Check, CheckError> {
    check_at(name_or_source, None)
}

/// As [`check`], a text with free parameters analysed at `values` (one per parameter, in
/// declaration order) when given.
pub fn check_at(name_or_source: &str, values: Option<&[f64]>) -> Result<Check, CheckError> {
    let unknown = match lookup(name_or_source) {
        Ok(entry) => {
            return Ok(match entry.scheme().program() {
                Some(p) => Check::of_program(entry.name.to_string(), p),
                None => Check::of_row(entry.row()),
            })
        }
        Err(unknown) => unknown,
    };
    let options = Options {
        allow_inconsistent: true,
    };
    let source = name_or_source.trim();
    let compiled = match compile_family(source) {
        Ok(f) if !f.parameters.is_empty() || values.is_some() => {
            let point = values.map_or_else(|| f.generic_point(), <[f64]>::to_vec);
            f.at_with(&point, &options).map(|p| {
                let mut c = Check::of_program(source.to_string(), &p);
                let names = f.parameters.iter().map(|q| q.name.clone());
                c.parameters = Some(names.zip(point).collect());
                c
            })
        }
        Ok(_) => compile_with(source, &options).map(|p| Check::of_program(source.to_string(), &p)),
        Err(e) => Err(e),
    };
    match compiled {
        Ok(c) => Ok(c),
        Err(diagnostics) => Err(CheckError {
            scheme: name_or_source.to_string(),
            reason: ResolveError::new(unknown, source, diagnostics),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_name_and_its_string_get_the_same_analysis() {
        let (by_name, by_text) = (check("ABOBA").unwrap(), check(" A B O B A ").unwrap());
        assert_eq!(
            (by_name.scheme.as_str(), by_text.scheme.as_str()),
            ("aboba", "A B O B A")
        );
        assert_eq!(by_name.program, by_text.program);
        assert_eq!(by_name.deterministic_order, 2);
        assert_eq!(by_text.invariant_measure_order, Some(2));
    }

    #[test]
    fn a_family_is_analysed_at_a_point() {
        let src = "param x in -2..2; S((1 - x)/2) S(x) S((1 - x)/2) O";
        let x0 = -(2f64.cbrt()) / (2.0 - 2f64.cbrt());
        assert_eq!(check(src).unwrap().deterministic_order, 2);
        let at = check_at(src, Some(&[x0])).unwrap();
        assert_eq!(at.deterministic_order, 4);
        assert_eq!(at.parameters.unwrap()["x"], x0);
        assert!(check_at(src, Some(&[1.0, 2.0])).is_err());
    }

    #[test]
    fn hand_written_schemes_report_their_claims_without_sums() {
        let c = check("setd").unwrap();
        assert!(c.hand_written && c.coefficient_sums.is_none() && c.analysis.is_none());
    }

    #[test]
    fn neither_name_nor_string_is_an_error_naming_the_text() {
        let e = check("ABQ").unwrap_err().to_string();
        assert!(
            e.starts_with("invalid scheme: not a valid scheme string: unknown sub-flow 'Q'"),
            "{e}"
        );
        assert_eq!(e.matches("ABQ").count(), 1, "{e}");
    }
}
