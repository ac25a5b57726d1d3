//! Subcommands of the `dpd` program, one module each.

use clap::{Parser, Subcommand};
use std::process::ExitCode;

#[derive(Debug, Parser)]
#[command(name = "dpd", version, about = "Compose, check and run DPD splitting integrators")]
pub struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Debug, Subcommand)]
enum Command {}

/// Run the parsed command line; the exit code is non-zero for bad input.
pub fn main(cli: Cli) -> ExitCode {
    match cli.command {
        None => {
            eprintln!("dpd: the main job is under construction");
            ExitCode::SUCCESS
        }
    }
}
