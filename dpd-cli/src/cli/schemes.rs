//! `dpd schemes`: the registry of named schemes, with cost and analysed orders.

use super::print_json;
use dpd::schemes::registry::{entries, Row};
use std::process::ExitCode;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// Print a JSON list of objects on stdout
    #[arg(long)]
    json: bool,
}

pub fn main(args: Args) -> ExitCode {
    let rows: Vec<&Row> = entries().iter().map(|e| e.row()).collect();
    if args.json {
        return print_json(&rows);
    }
    outln!(
        "{:<14} {:>5} {:>5} {:>4} {:>4} {:>4}  sequence",
        "name",
        "force",
        "pairs",
        "det",
        "inv",
        "sym"
    );
    for r in &rows {
        let invariant = r
            .invariant_measure_order
            .map_or("-".to_string(), |p| p.to_string());
        let mut sequence = r.sequence.clone();
        if !r.consistent {
            sequence.push_str("   [INCONSISTENT]");
        }
        if r.hand_written {
            sequence.push_str("   [hand-written]");
        }
        outln!(
            "{:<14} {:>5} {:>5} {:>4} {:>4} {:>4}  {sequence}",
            r.name,
            r.force_evaluations_per_step,
            r.pair_distance_evaluations_per_step,
            r.deterministic_order,
            invariant,
            if r.symmetric { "yes" } else { "no" },
        );
    }
    outln!();
    outln!("force, pairs: force and pair-distance evaluations per step; det: deterministic order");
    outln!("of the Hamiltonian part; inv: invariant-measure order bound (- where the criterion");
    outln!("does not apply: F stages, hand-written schemes). Aliases and sources: --json.");
    ExitCode::SUCCESS
}
