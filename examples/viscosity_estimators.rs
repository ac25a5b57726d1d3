//! Shear viscosity at gamma = 450, kappa = 0.2 (N = 500, density 3, a = 25) by two estimators of
//! the dissipative and random stress: the impulses the scheme applied (`observe::stress`, what
//! `dpd sweep` reports) and the dissipative force of the sampled state
//! (`observe::state_dissipative_stress`, the random force left out). The kinetic and
//! conservative parts are the same in both. For docs/papers.md, 003 Table 6.
//!
//! Usage: `cargo run --release -p dpd --example viscosity_estimators -- SCHEME DT TIME SEEDS`;
//! prints one line per seed and the mean with its standard error over seeds.

use dpd::init::{cubic_box, maxwell_momenta, uniform_positions};
use dpd::observe::{state_dissipative_stress, stress};
use dpd::{Params, System};
use rayon::prelude::*;

fn arg<T: std::str::FromStr>(k: usize, what: &str) -> Result<T, String> {
    let s = std::env::args()
        .nth(k)
        .ok_or_else(|| format!("argument {k} ({what}) missing; usage: SCHEME DT TIME SEEDS"))?;
    s.parse()
        .map_err(|_| format!("argument {k} ({what}) = {s:?} is not valid"))
}

/// `(eta by impulses, eta by state)` of one run of `time` after 5 time units of relaxation,
/// sampled every 0.05 time units.
fn run(
    name: &str,
    dt: f64,
    time: f64,
    seed: u64,
) -> Result<(f64, f64), Box<dyn std::error::Error + Send + Sync>> {
    let (n, rate) = (500, 0.2);
    let scheme = dpd::schemes::lookup(name)?.scheme();
    let params = Params::builder().gamma(450.0).build()?;
    let bx = cubic_box(n, 3.0)?;
    let mut sys = System::builder(params, bx, uniform_positions(&bx, n, seed))
        .momenta(maxwell_momenta(&vec![1.0; n], 1.0, seed))
        .dt(dt)
        .seed(seed)
        .shear_rate(rate)
        .build()?;
    sys.advance(&*scheme, (5.0 / dt).round() as u64)?;
    let every = ((0.05 / dt).round() as u64).max(1);
    let samples = (time / (every as f64 * dt)).round() as u64;
    stress(&mut sys);
    let (mut by_impulses, mut by_state) = (0.0, 0.0);
    for _ in 0..samples {
        sys.advance(&*scheme, every)?;
        let s = stress(&mut sys).ok_or("no stress sample")?;
        let common = s.kinetic[(0, 1)] + s.conservative[(0, 1)];
        by_impulses += common + s.dissipative_random[(0, 1)];
        by_state += common + state_dissipative_stress(&mut sys)[(0, 1)];
    }
    let scale = 1.0 / (samples as f64 * rate);
    Ok((by_impulses * scale, by_state * scale))
}

fn main() -> Result<(), Box<dyn std::error::Error + Send + Sync>> {
    let name: String = arg(1, "SCHEME")?;
    let dt: f64 = arg(2, "DT")?;
    let time: f64 = arg(3, "TIME")?;
    let seeds: u64 = arg(4, "SEEDS")?;
    let runs: Vec<(f64, f64)> = (1..=seeds)
        .into_par_iter()
        .map(|seed| run(&name, dt, time, seed))
        .collect::<Result<_, _>>()?;
    for (seed, (a, b)) in runs.iter().enumerate() {
        println!(
            "{name} dt={dt} seed={} eta_impulses={a:.4} eta_state={b:.4}",
            seed + 1
        );
    }
    let stats = |f: fn(&(f64, f64)) -> f64| {
        let n = runs.len() as f64;
        let mean = runs.iter().map(f).sum::<f64>() / n;
        let var = runs.iter().map(|r| (f(r) - mean).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
        (mean, (var / n).sqrt())
    };
    let (a, sa) = stats(|r| r.0);
    let (b, sb) = stats(|r| r.1);
    println!("{name} dt={dt} mean eta_impulses={a:.4} +- {sa:.4} eta_state={b:.4} +- {sb:.4}");
    Ok(())
}
