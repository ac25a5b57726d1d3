//! The `dpd` command-line program. Without a subcommand it runs the main job: the standard
//! gamma = 4.5 comparison of velocity Verlet, DPD-S1 and ABOBA.

mod cli;
mod export;

use clap::Parser;

fn main() -> std::process::ExitCode {
    cli::main(cli::Cli::parse())
}
