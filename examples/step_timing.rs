//! Time per step of velocity Verlet and ABOBA on the equilibrium box (density 3, a = 25,
//! gamma = 4.5, k_B T = 1), for side-by-side comparisons with other engines
//! (`bench/side_by_side.sh`). Prints one JSON object per scheme.
//!
//! Usage: `cargo run --release -p dpd --example step_timing -- N STEPS THREADS SKIN [SCHEME]`, SCHEME
//! `vv` or `aboba` to time one of them (default both). Besides the mean it prints the fastest
//! block of 10 steps, steadier on a shared machine for comparing two builds.

use dpd::init::equilibrium_box;
use dpd::reference::{Aboba, VelocityVerlet};
use dpd::{Params, Scheme};
use std::time::Instant;

fn arg<T: std::str::FromStr>(k: usize, default: T) -> T {
    match std::env::args().nth(k) {
        None => default,
        Some(s) => s.parse().unwrap_or_else(|_| {
            eprintln!(
                "step_timing: argument {k} = {s:?} is not valid; usage: N STEPS THREADS SKIN [vv|aboba]"
            );
            std::process::exit(2)
        }),
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let n: usize = arg(1, 24_000);
    let steps: u64 = arg(2, 100);
    let threads: usize = arg(3, 1);
    let skin: f64 = arg(4, 0.0);
    let only: String = arg(5, String::from("both"));
    let schemes: Vec<&(dyn Scheme + Sync)> = match only.as_str() {
        "vv" => vec![&VelocityVerlet],
        "aboba" => vec![&Aboba],
        "both" => vec![&VelocityVerlet, &Aboba],
        other => {
            eprintln!("step_timing: SCHEME = {other:?} is not one of vv, aboba, both");
            std::process::exit(2)
        }
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?;
    for scheme in schemes {
        let params = Params::builder().a(25.0).gamma(4.5).kbt(1.0).build()?;
        let mut sys = equilibrium_box(params, n, 3.0, 1)?
            .dt(0.04)
            .skin(skin)
            .build()?;
        let (seconds, fastest) = pool.install(|| -> Result<(f64, f64), dpd::AdvanceError> {
            // Relax the random start, then time in blocks of 10 steps.
            sys.advance(scheme, 50)?;
            let (mut total, mut fastest) = (0.0, f64::INFINITY);
            let mut left = steps;
            while left > 0 {
                let block = left.min(10);
                let start = Instant::now();
                sys.advance(scheme, block)?;
                let t = start.elapsed().as_secs_f64();
                total += t;
                fastest = fastest.min(t / block as f64);
                left -= block;
            }
            Ok((total, fastest))
        })?;
        let per_particle = 1e9 / n as f64;
        println!(
            "{{\"engine\": \"dpd\", \"scheme\": \"{}\", \"n\": {n}, \"threads\": {threads}, \"skin\": {skin}, \"us_per_step\": {:.1}, \"ns_per_particle_step\": {:.1}, \"fastest_block_ns_per_particle_step\": {:.1}}}",
            scheme.name(),
            seconds / steps as f64 * 1e6,
            seconds / steps as f64 * per_particle,
            fastest * per_particle
        );
    }
    Ok(())
}
