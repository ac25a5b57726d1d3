//! Subcommands of the `dpd` program, one module each.

#[macro_use]
mod output;

mod check;
mod design;
mod export;
mod kl;
mod orderings;
mod predict;
mod progress;
mod reproduce;
mod run;
mod scene_flags;
mod schemes;
mod stability;
mod sweep;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

#[derive(Debug, Parser)]
#[command(
    name = "dpd",
    version,
    about = "Compose, check and run DPD splitting integrators"
)]
pub struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Run one scene with one scheme and print the averaged observables
    Run(run::Args),
    /// Run schemes over a geometric range of dt: errors, critical dt, stability, efficiency
    Sweep(sweep::Args),
    /// Order analysis of a registry name or a scheme string
    Check(check::Args),
    /// Solve a family's order conditions, then minimise its error norm
    Design(design::Args),
    /// Estimate the KL divergence of a scheme's configurations from shadow work
    Kl(kl::Args),
    /// Enumerate the distinct consistent splitting strings up to a length
    Orderings(orderings::Args),
    /// Predict a scheme's errors, critical steps and stability from the fluid's harmonic modes
    Predict(predict::Args),
    /// List the named schemes with their cost and analysed orders
    Schemes(schemes::Args),
    /// Reproduce the tables and figures of the source papers: published against measured
    Reproduce(reproduce::Args),
    /// Run every named scheme over a matrix of gamma, mass and dt: completed, blow-up, insane
    Stability(stability::Args),
    /// Generate code that runs schemes in another engine (a LAMMPS plugin)
    Export(export::Args),
}

/// Run the parsed command line; the exit code is non-zero for bad input.
pub fn main(cli: Cli) -> ExitCode {
    output::finish(match cli.command {
        None => sweep::main_job(),
        Some(Command::Run(args)) => run::main(args),
        Some(Command::Sweep(args)) => sweep::main(args),
        Some(Command::Check(args)) => check::main(args),
        Some(Command::Orderings(args)) => orderings::main(args),
        Some(Command::Predict(args)) => predict::main(args),
        Some(Command::Design(args)) => design::main(args),
        Some(Command::Kl(args)) => kl::main(args),
        Some(Command::Schemes(args)) => schemes::main(args),
        Some(Command::Stability(args)) => stability::main(args),
        Some(Command::Reproduce(args)) => reproduce::main(args),
        Some(Command::Export(args)) => export::main(args),
    })
}

/// Exit code of invalid input (the same as clap's usage errors).
const BAD_INPUT: u8 = 2;
/// Exit code of a run stopped by Ctrl-C (128 + SIGINT).
const INTERRUPTED: u8 = 130;

/// Print `message` as an error of the program and return the bad-input exit code.
fn bad_input(message: impl std::fmt::Display) -> ExitCode {
    errln!("dpd: error: {message}");
    ExitCode::from(BAD_INPUT)
}

/// Print a JSON value on stdout.
fn print_json(value: &impl serde::Serialize) -> ExitCode {
    match serde_json::to_string_pretty(value) {
        Ok(text) => {
            outln!("{text}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            errln!("dpd: error: cannot write JSON: {e}");
            ExitCode::FAILURE
        }
    }
}
