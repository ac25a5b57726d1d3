//! Wall time of each sub-flow of an ABOBA step on the equilibrium box (density 3, a = 25,
//! gamma = 4.5, k_B T = 1, dt = 0.04, skin 0), to see which part of a step scales across
//! threads and which does not. The flows are called one by one, as `reference::Aboba` calls
//! them, without `advance`'s blow-up guard; the step counter does not advance, so every timed
//! step draws the noise of the same step number (at the same cost). The first kick includes
//! the neighbour-list rebuild (binning, re-sorting) and the pair-table fill with the
//! conservative forces; the second reuses them. With `--only-o` the timed steps run the O
//! sweep alone, on the table of the last relaxation step, so that its instructions can be
//! counted apart (cachegrind of `--steps 21` less that of `--steps 1` is 20 sweeps).
//!
//! Usage: `cargo run --release -p dpd --example phase_timing -- --n 192000 --steps 20 --threads 2`

use clap::Parser;
use dpd::flow::{drift, kick, ou, SweepOrder};
use dpd::init::equilibrium_box;
use dpd::reference::Aboba;
use dpd::{Params, System};
use std::time::Instant;

#[derive(Parser)]
struct Args {
    /// Particles.
    #[arg(long, default_value_t = 192_000)]
    n: usize,
    /// Timed steps (after 30 steps of relaxation), at least 1.
    #[arg(long, default_value_t = 20, value_parser = clap::value_parser!(u32).range(1..))]
    steps: u32,
    /// Threads of the rayon pool.
    #[arg(long, default_value_t = 1)]
    threads: usize,
    /// Time the O sweep alone: the other sub-flows are not run in the timed steps.
    #[arg(long)]
    only_o: bool,
}

/// The name of the O sweep in [`PHASES`].
const O: &str = "O h";

/// A sub-flow of the step, given the step size `dt`.
type Phase = fn(&mut System, f64);

/// The sub-flows of one ABOBA step, in order.
const PHASES: [(&str, Phase); 5] = [
    ("A h/2", |s, dt| drift(s, 0.5 * dt)),
    ("B h/2, rebuild, fill", |s, dt| kick(s, 0.5 * dt)),
    (O, |s, dt| ou(s, dt, 0, SweepOrder::Forward)),
    ("B h/2", |s, dt| kick(s, 0.5 * dt)),
    ("A h/2 again", |s, dt| drift(s, 0.5 * dt)),
];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = Args::parse();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads)
        .build()?;
    let params = Params::builder().a(25.0).gamma(4.5).kbt(1.0).build()?;
    let mut sys = equilibrium_box(params, args.n, 3.0, 1)?
        .dt(0.04)
        .skin(0.0)
        .build()?;
    let dt = sys.dt();
    let timed = |name: &str| !args.only_o || name == O;
    let seconds = pool.install(|| -> Result<[f64; 5], dpd::AdvanceError> {
        sys.advance(&Aboba, 30)?;
        let mut seconds = [0.0; 5];
        for _ in 0..args.steps {
            for ((name, phase), total) in PHASES.iter().zip(&mut seconds) {
                if !timed(name) {
                    continue;
                }
                let start = Instant::now();
                phase(&mut sys, dt);
                *total += start.elapsed().as_secs_f64();
            }
        }
        Ok(seconds)
    })?;
    let ms = |s: f64| s / f64::from(args.steps) * 1e3;
    for ((name, _), s) in PHASES
        .iter()
        .zip(seconds)
        .filter(|((name, _), _)| timed(name))
    {
        println!(
            "{{\"threads\": {}, \"n\": {}, \"phase\": \"{name}\", \"ms_per_step\": {:.2}}}",
            args.threads,
            args.n,
            ms(s)
        );
    }
    println!(
        "{{\"threads\": {}, \"n\": {}, \"phase\": \"step\", \"ms_per_step\": {:.2}}}",
        args.threads,
        args.n,
        ms(seconds.iter().sum())
    );
    Ok(())
}
