//! `dpd stability`: every registered scheme (or the ones named) over a matrix of friction,
//! mass and time step; which runs complete with sane temperatures, which blow up.

use super::{bad_input, print_json};
use dpd::schemes::registry::{entries, lookup, Entry};
use dpd::schemes::stability::{run, Matrix, Outcome, Record};
use serde::Serialize;
use std::process::ExitCode;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// Print the matrix and every outcome as one JSON object on stdout
    #[arg(long)]
    json: bool,
    /// Run the reduced matrix (gamma 0, 4.5, 1e4; mass 1e-3, 1, 1e3; dt 1e-4, 1e-2, 0.5;
    /// 40 steps of N = 100) instead of the full one
    #[arg(long)]
    reduced: bool,
    /// Registry names to run, comma-separated (default: all)
    #[arg(long, value_delimiter = ',')]
    schemes: Vec<String>,
    /// Steps per run (default: 400 full, 40 reduced)
    #[arg(long, allow_negative_numbers = true)]
    steps: Option<u64>,
    /// Particles in the box (density 3; at least 53 for the box edge 2 (r_c + skin))
    #[arg(long, allow_negative_numbers = true)]
    particles: Option<usize>,
    /// Frictions, comma-separated (replaces the matrix's list)
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    gamma: Vec<f64>,
    /// Masses, comma-separated (replaces the matrix's list)
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    mass: Vec<f64>,
    /// Time steps, comma-separated (replaces the matrix's list)
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    dt: Vec<f64>,
    /// Random seed of the start and of the noise
    #[arg(long, allow_negative_numbers = true)]
    seed: Option<u64>,
}

#[derive(Serialize)]
struct Report<'a> {
    matrix: &'a Matrix,
    records: &'a [Record],
}

pub fn main(args: Args) -> ExitCode {
    let mut matrix = if args.reduced {
        Matrix::reduced()
    } else {
        Matrix::full()
    };
    for (list, given) in [
        (&mut matrix.gammas, args.gamma),
        (&mut matrix.masses, args.mass),
        (&mut matrix.dts, args.dt),
    ] {
        if !given.is_empty() {
            *list = given;
        }
    }
    matrix.steps = args.steps.unwrap_or(matrix.steps);
    matrix.particles = args.particles.unwrap_or(matrix.particles);
    matrix.seed = args.seed.unwrap_or(matrix.seed);
    let schemes: Vec<&'static Entry> = if args.schemes.is_empty() {
        entries().iter().collect()
    } else {
        match args.schemes.iter().map(|n| lookup(n)).collect() {
            Ok(s) => s,
            Err(unknown) => return bad_input(unknown),
        }
    };
    let records = match run(&matrix, &schemes) {
        Ok(r) => r,
        Err(e) => return bad_input(e),
    };
    if args.json {
        return print_json(&Report {
            matrix: &matrix,
            records: &records,
        });
    }
    print_tables(&matrix, &schemes, &records);
    ExitCode::SUCCESS
}

/// One block per scheme: a row per (gamma, mass), a column per dt. A cell is
/// `T_K error / T_C error` in per cent, `blow-up@step`, or `insane`.
fn print_tables(matrix: &Matrix, schemes: &[&Entry], records: &[Record]) {
    outln!(
        "{} steps, N = {}, density {}; cells: T_K/T_C error in %, blow-up@step, or insane \
         (a mean temperature off by more than a factor {})",
        matrix.steps,
        matrix.particles,
        matrix.density,
        dpd::schemes::stability::SANE_FACTOR
    );
    let cases = matrix.cases().len();
    let mut totals = Vec::new();
    for (entry, block) in schemes.iter().zip(records.chunks(cases)) {
        outln!("\n{}", entry.name);
        out!("  {:>8} {:>8} |", "gamma", "mass");
        for dt in &matrix.dts {
            out!(" {:>15}", format!("dt={dt}"));
        }
        outln!();
        let (mut completed, mut blow_ups, mut insane) = (0, 0, 0);
        for row in block.chunks(matrix.dts.len()) {
            out!("  {:>8} {:>8} |", row[0].gamma, row[0].mass);
            for r in row {
                let cell = match &r.outcome {
                    Outcome::Completed {
                        kinetic_error,
                        configurational_error,
                        ..
                    } => {
                        completed += 1;
                        format!(
                            "{:+.1}/{:+.1}",
                            100.0 * kinetic_error,
                            100.0 * configurational_error
                        )
                    }
                    Outcome::BlowUp { step, .. } => {
                        blow_ups += 1;
                        format!("blow-up@{step}")
                    }
                    Outcome::Insane { .. } => {
                        insane += 1;
                        "insane".to_string()
                    }
                };
                out!(" {cell:>15}");
            }
            outln!();
        }
        totals.push((entry.name, completed, blow_ups, insane));
    }
    outln!(
        "\n{:<14} {:>9} {:>8} {:>7}",
        "scheme",
        "completed",
        "blow-up",
        "insane"
    );
    for (name, completed, blow_ups, insane) in totals {
        outln!("{name:<14} {completed:>9} {blow_ups:>8} {insane:>7}");
    }
}
