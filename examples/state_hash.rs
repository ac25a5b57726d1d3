//! A hash of the state (positions and momenta, bit by bit, in particle-id order) after a run on
//! the equilibrium box (density 3, a = 25, gamma = 4.5, k_B T = 1, dt = 0.04): two builds that
//! print the same hash ran the same trajectory. Used to check that a change to the pair loops
//! leaves trajectories bitwise unchanged (docs/performance.md).
//!
//! Usage: `cargo run --release -p dpd --example state_hash -- N STEPS THREADS SKIN SCHEME
//! [SYSTEM]`, SCHEME a registry name, SYSTEM one of
//! - `periodic` (the default): the box as described;
//! - `sheared`: Lees-Edwards boundaries at shear rate 0.2;
//! - `walled`: walls across z at 1 and L - 1 moving at -1 and +1 along x (Couette flow), the
//!   particles outside them frozen, and a body force of 0.1 along x;
//! - `two-types`: every third particle of type 1, `a = [[25, 40], [40, 25]]`, masses 1 and 2;
//! - `melt`: chains of 10 consecutive ids bonded by harmonic springs `K = 100`, `r0 = 0.7` (the
//!   bonds of scenes/melt-stiff.toml), laid as random walks of step 0.7 from uniform starts.

use dpd::bonded::{Bond, BondStyle, Topology};
use dpd::init::{equilibrium_box, freeze_outside, maxwell_momenta};
use dpd::{Params, SystemBuilder, Vec3};
use dpd_core::Walls;
use std::hash::{DefaultHasher, Hash, Hasher};

const USAGE: &str = "usage: N STEPS THREADS SKIN SCHEME [periodic|sheared|walled|two-types|melt]";

fn arg<T: std::str::FromStr>(k: usize, what: &str) -> Result<T, String> {
    let s = std::env::args()
        .nth(k)
        .ok_or_else(|| format!("argument {k} ({what}) missing; {USAGE}"))?;
    s.parse()
        .map_err(|_| format!("argument {k} ({what}) = {s:?} is not valid; {USAGE}"))
}

/// The equilibrium box of `n` particles turned into the system `kind` (see the usage).
fn system(kind: &str, n: usize) -> Result<SystemBuilder, Box<dyn std::error::Error>> {
    let params = Params::builder().a(25.0).gamma(4.5).kbt(1.0);
    let standard = equilibrium_box(params.clone().build()?, n, 3.0, 1)?;
    let built = standard.clone().build()?;
    Ok(match kind {
        "periodic" => standard,
        "sheared" => standard.shear_rate(0.2),
        "walled" => {
            let length = built.boundary().lengths().z;
            let walls = Walls::new(1.0, length - 1.0, [-1.0, 1.0])?;
            let mut p = built.momenta().to_vec();
            let frozen = freeze_outside(&walls, built.positions(), &mut p);
            standard
                .momenta(p)
                .walls(walls)
                .frozen(frozen)
                .body_force(Vec3::new(0.1, 0.0, 0.0))
        }
        "two-types" => {
            let params = params.a_matrix(vec![vec![25.0, 40.0], vec![40.0, 25.0]]);
            let kinds: Vec<u16> = (0..n).map(|k| u16::from(k % 3 == 0)).collect();
            let masses = kinds.iter().map(|&t| 1.0 + f64::from(t)).collect();
            equilibrium_box(params.build()?, n, 3.0, 1)?
                .kinds(kinds)
                .masses(masses)
        }
        "melt" => melt(params.build()?, &built)?,
        other => return Err(format!("SYSTEM = {other:?} is not valid; {USAGE}").into()),
    })
}

/// The particles of `built` (box, momenta, the first bead of each chain) in chains of 10
/// consecutive ids (a shorter last chain if 10 does not divide N): each bead 0.7 from the one
/// before, along a direction drawn from a Gaussian (isotropic).
fn melt(params: Params, built: &dpd::System) -> Result<SystemBuilder, Box<dyn std::error::Error>> {
    const LENGTH: usize = 10;
    let n = built.len();
    let steps = maxwell_momenta(&vec![1.0; n], 1.0, 2);
    let mut q = built.positions().to_vec();
    let mut bonds = Vec::new();
    for k in 1..n {
        if k % LENGTH != 0 {
            q[k] = built.boundary().wrap(q[k - 1] + 0.7 * steps[k].normalize());
            bonds.push(Bond {
                i: k as u32 - 1,
                j: k as u32,
                kind: 0,
            });
        }
    }
    let mut topology = Topology::builder(n);
    topology.bond_types = vec![BondStyle::Harmonic { k: 100.0, r0: 0.7 }];
    topology.bonds = bonds;
    Ok(dpd::System::builder(params, *built.boundary(), q)
        .momenta(built.momenta().to_vec())
        .seed(1)
        .topology(topology.build()?))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let n: usize = arg(1, "N")?;
    let steps: u64 = arg(2, "STEPS")?;
    let threads: usize = arg(3, "THREADS")?;
    let skin: f64 = arg(4, "SKIN")?;
    let name: String = arg(5, "SCHEME")?;
    let kind: String = arg(6, "SYSTEM").unwrap_or_else(|_| String::from("periodic"));
    let scheme = dpd::schemes::lookup(&name)?.scheme();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?;
    let mut sys = system(&kind, n)?.dt(0.04).skin(skin).build()?;
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
        "{name} {kind} n={n} steps={steps} threads={threads} skin={skin} hash={:016x}",
        hash.finish()
    );
    Ok(())
}
