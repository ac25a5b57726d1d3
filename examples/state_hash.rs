//! A hash of the state (positions and momenta, bit by bit, in particle-id order) after a run on
//! the equilibrium box (density 3, a = 25, gamma = 4.5, k_B T = 1, dt = 0.04): two builds that
//! print the same hash ran the same trajectory. Used to check that a change to the pair loops
//! leaves trajectories bitwise unchanged (docs/performance.md).
//!
//! Usage: `cargo run --release -p dpd --example state_hash -- N STEPS THREADS SKIN SCHEME`, SCHEME a
//! registry name.

use dpd::init::equilibrium_box;
use dpd::Params;
use std::hash::{DefaultHasher, Hash, Hasher};

fn arg<T: std::str::FromStr>(k: usize, what: &str) -> Result<T, String> {
    let s = std::env::args().nth(k).ok_or_else(|| {
        format!("argument {k} ({what}) missing; usage: N STEPS THREADS SKIN SCHEME")
    })?;
    s.parse()
        .map_err(|_| format!("argument {k} ({what}) = {s:?} is not valid"))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let n: usize = arg(1, "N")?;
    let steps: u64 = arg(2, "STEPS")?;
    let threads: usize = arg(3, "THREADS")?;
    let skin: f64 = arg(4, "SKIN")?;
    let name: String = arg(5, "SCHEME")?;
    let scheme = dpd::schemes::lookup(&name)?.scheme();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?;
    let params = Params::builder().a(25.0).gamma(4.5).kbt(1.0).build()?;
    let mut sys = equilibrium_box(params, n, 3.0, 1)?
        .dt(0.04)
        .skin(skin)
        .build()?;
    pool.install(|| sys.advance(&*scheme, steps))?;
    let mut by_id: Vec<usize> = (0..sys.len()).collect();
    by_id.sort_by_key(|&k| sys.ids()[k]);
    let mut hash = DefaultHasher::new();
    for k in by_id {
        for x in sys.positions()[k].iter().chain(sys.momenta()[k].iter()) {
            x.to_bits().hash(&mut hash);
        }
    }
    println!(
        "{name} n={n} steps={steps} threads={threads} skin={skin} hash={:016x}",
        hash.finish()
    );
    Ok(())
}
