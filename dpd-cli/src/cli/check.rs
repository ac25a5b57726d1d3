//! `dpd check`: the order analysis of a registry name or a scheme string, as text or as the
//! JSON of [`dpd::schemes::check::Check`].

use super::{bad_input, print_json};
use dpd::schemes::check::check_at;
use std::process::ExitCode;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// Registry name (`dpd schemes` lists them) or scheme string, e.g. "BAOOAB"
    scheme: String,
    /// Values of the free parameters (`param`) to analyse at, in declaration order, e.g.
    /// --at 0.25 or --at 0.25,0.1 (default: a generic point of the box)
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    at: Option<Vec<f64>>,
    /// Print one JSON object on stdout
    #[arg(long)]
    json: bool,
}

pub fn main(args: Args) -> ExitCode {
    let c = match check_at(&args.scheme, args.at.as_deref()) {
        Ok(c) => c,
        Err(e) => return bad_input(e),
    };
    if args.json {
        return print_json(&c);
    }
    let yes = |b: bool| if b { "yes" } else { "no" };
    outln!("{} = {}", c.scheme, c.program);
    if let Some(point) = &c.parameters {
        let at: Vec<String> = point.iter().map(|(n, v)| format!("{n} = {v}")).collect();
        outln!("analysed at {}", at.join(", "));
    }
    match &c.analysis {
        Some(a) => {
            out!("{a}");
            outln!(
                "note: the deterministic order is that of the pure Hamiltonian splitting, a lower \
                 bound for DPD: with quadratic kinetic energy [B,[B,[B,A]]] = 0, so some schemes \
                 (RKN methods) are an order higher"
            );
        }
        None => outln!(
            "hand-written, documented claims: consistent: {}, deterministic order: {}, \
             invariant-measure order: not applicable (measure it)",
            yes(c.consistent),
            c.deterministic_order
        ),
    }
    outln!("symmetric: {}", yes(c.symmetric));
    out!(
        "evaluations per step: {} force, {} pair-distance",
        c.force_evaluations_per_step,
        c.pair_distance_evaluations_per_step
    );
    match c.bonded_force_evaluations_per_step {
        Some(b) => outln!(", {b} bonded-force (on a system with bonds)"),
        None => outln!(),
    }
    ExitCode::SUCCESS
}
