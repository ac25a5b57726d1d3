//! `dpd check`: the order analysis of a registry name or a scheme string. Inconsistent schemes
//! are analysed and reported, not refused.

use super::{bad_input, print_json};
use dpd::analysis::CoefficientSums;
use dpd::lang::Options;
use dpd::schemes::registry::{lookup, ResolveError, Row};
use dpd::{Analysis, Program};
use serde::Serialize;
use std::process::ExitCode;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// Registry name (`dpd schemes` lists them) or scheme string, e.g. "BAOOAB"
    scheme: String,
    /// Print one JSON object on stdout
    #[arg(long)]
    json: bool,
}

/// What `dpd check --json` prints. For a hand-written registry scheme (no program) the orders
/// and costs are the registry's documented claims and `coefficient_sums` is null.
#[derive(Debug, Serialize)]
struct Check {
    scheme: String,
    /// The merged stages of one step, or the step in words.
    program: String,
    hand_written: bool,
    consistent: bool,
    coefficient_sums: Option<CoefficientSums>,
    /// 0 when inconsistent.
    deterministic_order: u32,
    deterministic_order_capped: bool,
    /// Left-ideal bound; null where the criterion does not apply (F stages, hand-written).
    invariant_measure_order: Option<u32>,
    invariant_measure_order_capped: bool,
    first_nonvanishing: Option<String>,
    symmetric: bool,
    force_evaluations_per_step: usize,
    pair_distance_evaluations_per_step: usize,
    /// The full analysis, for the text report.
    #[serde(skip)]
    analysis: Option<Analysis>,
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
fn check(name_or_source: &str) -> Result<Check, ResolveError> {
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
    match dpd::lang::compile_with(name_or_source.trim(), &options) {
        Ok(p) => Ok(Check::of_program(name_or_source.trim().to_string(), &p)),
        Err(diagnostics) => Err(ResolveError {
            unknown,
            diagnostics,
        }),
    }
}

pub fn main(args: Args) -> ExitCode {
    let c = match check(&args.scheme) {
        Ok(c) => c,
        Err(e) => return bad_input(format!("invalid SCHEME = {:?}: {e}", args.scheme)),
    };
    if args.json {
        return print_json(&c);
    }
    let yes = |b: bool| if b { "yes" } else { "no" };
    println!("{} = {}", c.scheme, c.program);
    match &c.analysis {
        Some(a) => print!("{a}"),
        None => println!(
            "hand-written, documented claims: consistent: {}, deterministic order: {}, \
             invariant-measure order: not applicable (measure it)",
            yes(c.consistent),
            c.deterministic_order
        ),
    }
    println!("symmetric: {}", yes(c.symmetric));
    println!(
        "evaluations per step: {} force, {} pair-distance",
        c.force_evaluations_per_step, c.pair_distance_evaluations_per_step
    );
    ExitCode::SUCCESS
}
