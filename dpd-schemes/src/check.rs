//! The check of a registry name or a scheme string: what `dpd check --json` prints and what the
//! Python module's `dpd.check` returns. Inconsistent schemes are analysed and reported, not
//! refused.

use crate::registry::{lookup, ResolveError, Row};
use dpd_ir::analysis::CoefficientSums;
use dpd_ir::lang::{compile_with, Options};
use dpd_ir::{Analysis, Program};
use serde::Serialize;
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
    pub symmetric: bool,
    pub force_evaluations_per_step: usize,
    pub pair_distance_evaluations_per_step: usize,
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
            symmetric: program.is_symmetric(),
            force_evaluations_per_step: cost.force,
            pair_distance_evaluations_per_step: cost.pair_distance,
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
            symmetric: row.symmetric,
            force_evaluations_per_step: row.force_evaluations_per_step,
            pair_distance_evaluations_per_step: row.pair_distance_evaluations_per_step,
            analysis: None,
        }
    }
}

/// The check of a registry entry, else of the text compiled with inconsistency allowed.
pub fn check(name_or_source: &str) -> Result<Check, CheckError> {
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
    match compile_with(source, &options) {
        Ok(p) => Ok(Check::of_program(source.to_string(), &p)),
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
