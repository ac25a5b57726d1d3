//! `dpd design FAMILY`: solve a family's order conditions for its highest orders, then
//! minimise the error norm with the freedom left (see `dpd_ir::design`).

use super::{bad_input, print_json};
use dpd::design::{design, Member};
use dpd::lang::compile_family;
use std::process::ExitCode;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// A scheme with free parameters, e.g. "param l in 0..1/2; B(l) A(1/2) B(1 - 2*l) A(1/2) B(l) O"
    family: String,
    /// Further points to report, one value per parameter separated by commas; repeatable,
    /// e.g. --at 0.1932
    #[arg(long, allow_negative_numbers = true)]
    at: Vec<String>,
    /// Print one JSON object on stdout
    #[arg(long)]
    json: bool,
}

pub fn main(args: Args) -> ExitCode {
    let family = match compile_family(args.family.trim()) {
        Ok(f) => f,
        Err(e) => {
            let why: Vec<String> = e.iter().map(ToString::to_string).collect();
            return bad_input(format!(
                "invalid family = {:?}: {}",
                args.family,
                why.join("; ")
            ));
        }
    };
    let mut extra = Vec::new();
    for text in &args.at {
        let values: Result<Vec<f64>, _> = text.split(',').map(|v| v.trim().parse()).collect();
        match values {
            Ok(v) if v.len() == family.parameters.len() && v.iter().all(|x| x.is_finite()) => {
                extra.push(v)
            }
            _ => {
                return bad_input(format!(
                    "invalid --at = {text:?}: expected {} finite numbers separated by commas ({})",
                    family.parameters.len(),
                    family.names().join(", ")
                ))
            }
        }
    }
    let Some(d) = design(&family, &extra) else {
        return bad_input(format!(
            "invalid family = {:?}: it cannot be built at a generic point of its box",
            args.family
        ));
    };
    if args.json {
        return print_json(&d);
    }
    let inv = |p: Option<u32>| p.map_or("-".to_string(), |p| p.to_string());
    println!(
        "family: {}\ngeneric orders: deterministic {}, invariant measure {}; minimising the {:?} norm",
        d.family,
        d.generic_orders.0,
        inv(d.generic_orders.1),
        d.objective
    );
    println!("solutions (highest orders, best first):");
    print_members(&d.solutions);
    println!("notable points:");
    print_members(&d.notable);
    ExitCode::SUCCESS
}

fn print_members(members: &[Member]) {
    let norm = |x: Option<f64>| x.map_or("-".to_string(), |v| format!("{v:.6}"));
    for m in members {
        let point: Vec<String> = m
            .parameters
            .iter()
            .map(|(n, v)| format!("{n} = {v:.10}"))
            .collect();
        println!(
            "  {}: det {} (norm {}), inv {} (norm {}), freedom {}, {} force / {} pair-distance evaluations",
            point.join(", "),
            m.deterministic_order,
            norm(m.deterministic_error_norm),
            m.invariant_measure_order.map_or("-".to_string(), |p| p.to_string()),
            norm(m.invariant_measure_error_norm),
            m.freedom,
            m.force_evaluations_per_step,
            m.pair_distance_evaluations_per_step
        );
    }
}
