//! Shared set-up of the core's integration tests.
// Also included by path in the root crate's tests/macro_equivalence.rs and
// benches/generated_vs_handwritten.rs, which use part of it.
#![allow(dead_code)]

use dpd_core::bonded::{Angle, AngleStyle, Bond, BondStyle, Topology};
use dpd_core::flow::{bbk, drift, full_force, kick, ou, trotter};
use dpd_core::init::{equilibrium_box, maxwell_momenta};
use dpd_core::observe::hamiltonian;
use dpd_core::params::ParamsBuilder;
use dpd_core::{
    AdvanceError, BlowUp, DynScheme, Params, PeriodicBox, Scheme, SweepOrder, System,
    SystemBuilder, Vec3,
};

/// `pairs` isolated pairs at separation 0.5 on a cubic lattice of spacing 3 r_c (pairs do not
/// interact with each other), particles `2k` and `2k + 1`, the pair direction cycling through
/// x, y and z: the box and the positions.
pub fn isolated_pairs(pairs: usize) -> (PeriodicBox, Vec<Vec3>) {
    let side = (pairs as f64).cbrt().ceil() as usize;
    let bx = PeriodicBox::cubic(3.0 * side as f64).unwrap();
    let mut q = Vec::new();
    for k in 0..pairs {
        let c = Vec3::new(
            (k % side) as f64,
            ((k / side) % side) as f64,
            (k / side / side) as f64,
        ) * 3.0;
        let dir = [Vec3::x(), Vec3::y(), Vec3::z()][k % 3];
        q.extend([c, c + 0.5 * dir]);
    }
    (bx, q)
}

/// A system of `n` unit-mass particles at `density` with the given parameters, Maxwell
/// momenta and uniform positions.
pub fn system(n: usize, density: f64, params: ParamsBuilder, dt: f64, seed: u64) -> System {
    equilibrium_box(params.build().unwrap(), n, density, seed)
        .unwrap()
        .dt(dt)
        .build()
        .unwrap()
}

/// The standard equilibrium box of algorithms.md section 8 (N = 500, density 3, a = 25,
/// k_B T = 1) with friction `gamma`.
pub fn standard_box(gamma: f64, dt: f64, seed: u64) -> System {
    system(500, 3.0, Params::builder().gamma(gamma), dt, seed)
}

/// `chains` linear chains of `length` unit-mass beads at density 3 with pair parameters
/// `params`: bead `c length + k` of chain `c`, bonds between neighbours with the styles of
/// `bonds` in turn along the chain, an angle at each inner bead with the styles of `angles` in
/// turn (none if empty). Each chain starts at a uniform position and walks steps of length
/// `step` in random directions; Maxwell momenta.
pub fn chain_melt(
    chains: usize,
    length: usize,
    params: ParamsBuilder,
    bonds: &[BondStyle],
    angles: &[AngleStyle],
    step: f64,
    seed: u64,
) -> SystemBuilder {
    let n = chains * length;
    let base = equilibrium_box(params.build().unwrap(), n, 3.0, seed)
        .unwrap()
        .build()
        .unwrap();
    let start = base.positions();
    let directions = maxwell_momenta(&vec![1.0; n], 1.0, seed + 1);
    let mut q = Vec::with_capacity(n);
    let mut t = Topology::builder(n);
    t.bond_types = bonds.to_vec();
    t.angle_types = angles.to_vec();
    for (c, &first) in start.iter().enumerate().take(chains) {
        for k in 0..length {
            let id = c * length + k;
            if k == 0 {
                q.push(first);
                continue;
            }
            q.push(q[id - 1] + step * directions[id].normalize());
            let kind = ((k - 1) % bonds.len()) as u16;
            t.bonds.push(Bond {
                i: id as u32 - 1,
                j: id as u32,
                kind,
            });
            if k >= 2 && !angles.is_empty() {
                let kind = ((k - 2) % angles.len()) as u16;
                let (i, j, k) = (id as u32 - 2, id as u32 - 1, id as u32);
                t.angles.push(Angle { i, j, k, kind });
            }
        }
    }
    System::builder(base.params().clone(), *base.boundary(), q)
        .momenta(base.momenta().to_vec())
        .seed(seed)
        .topology(t.build().unwrap())
}

/// `sys` rebuilt without friction at time step `dt`, with its positions, momenta, ids,
/// topology and exclusion.
fn frictionless(sys: &System, dt: f64) -> System {
    System::builder(
        Params::builder().gamma(0.0).build().unwrap(),
        *sys.boundary(),
        sys.positions().to_vec(),
    )
    .momenta(sys.momenta().to_vec())
    .ids(sys.ids().to_vec())
    .topology(sys.topology().unwrap().clone())
    .exclude_bonded(sys.excludes_bonded())
    .dt(dt)
    .build()
    .unwrap()
}

/// Velocity Verlet without friction from `sys` after 500 steps of ABOBA at its own friction and
/// dt (0.01): asserts that halving dt from 0.01 to 0.005 divides the rms energy error over 2
/// time units by 3.5 to 4.5 (order dt^2), and returns both errors.
pub fn assert_energy_error_of_order_dt_squared(mut sys: System) -> (f64, f64) {
    let aboba = DynScheme::compile("ABOBA", "ABOBA", &Default::default()).unwrap();
    sys.advance(&aboba, 500).unwrap();
    let (coarse, fine) = (
        energy_error(frictionless(&sys, 0.01)),
        energy_error(frictionless(&sys, 0.005)),
    );
    let ratio = coarse / fine;
    assert!(
        (3.5..4.5).contains(&ratio),
        "rms {coarse:.3e} / {fine:.3e} = {ratio}"
    );
    (coarse, fine)
}

/// The root mean square of H(t) - H(0) over 2 time units of velocity Verlet on `sys`.
fn energy_error(mut sys: System) -> f64 {
    let vv = DynScheme::compile("VV", "B(1/2) A B(1/2)", &Default::default()).unwrap();
    let h0 = hamiltonian(&mut sys);
    let steps = (2.0 / sys.dt()).round() as u64;
    let mut sum = 0.0;
    for _ in 0..steps {
        sys.advance(&vv, 1).unwrap();
        sum += (hamiltonian(&mut sys) - h0).powi(2);
    }
    (sum / steps as f64).sqrt()
}

/// What the bond-length sampling tests average per bond of length `r`: r, r^2 and whether r
/// is in each bin of edges 0, 0.3, 0.5, 0.7, 0.9, 1.1, 4.
pub fn bond_quantities(r: f64) -> Vec<f64> {
    let edges = [0.0, 0.3, 0.5, 0.7, 0.9, 1.1, 4.0];
    let bins = edges
        .windows(2)
        .map(move |w| f64::from(w[0] <= r && r < w[1]));
    [r, r * r].into_iter().chain(bins).collect()
}

/// The type and length (minimum image) of every bond of `sys`, in the topology's order.
pub fn bond_lengths(sys: &System) -> Vec<(u16, f64)> {
    let mut at = vec![0; sys.len()];
    for (k, &id) in sys.ids().iter().enumerate() {
        at[id as usize] = k;
    }
    let q = sys.positions();
    let bonds = sys.topology().unwrap().bonds().iter();
    bonds
        .map(|b| {
            let d = q[at[b.i as usize]] - q[at[b.j as usize]];
            (b.kind, sys.boundary().min_image(d).norm())
        })
        .collect()
}

/// `int_0^end f(r) dr` by Simpson's rule on 20 000 intervals.
pub fn integral(end: f64, f: impl Fn(f64) -> f64) -> f64 {
    let n = 20_000;
    let h = end / n as f64;
    let sum: f64 = (0..=n)
        .map(|k| {
            let weight = if k == 0 || k == n {
                1.0
            } else {
                [2.0, 4.0][k % 2]
            };
            weight * f(k as f64 * h)
        })
        .sum();
    sum * h / 3.0
}

/// The bond styles of the test melts: a stiff harmonic bond and a FENE bond, in turn.
pub const MELT_BONDS: [BondStyle; 2] = [
    BondStyle::Harmonic { k: 50.0, r0: 0.7 },
    BondStyle::Fene {
        k: 30.0,
        r_max: 1.5,
    },
];

/// The angle styles of the test melts: cosine and cosine/squared, in turn.
pub const MELT_ANGLES: [AngleStyle; 2] = [
    AngleStyle::Cosine { k: 2.0 },
    AngleStyle::CosineSquared {
        k: 5.0,
        theta0: 2.5,
    },
];

/// A melt of `chains` chains of `length` beads with [`MELT_BONDS`] and [`MELT_ANGLES`], steps
/// of 0.7 (see [`chain_melt`]).
pub fn melt(chains: usize, length: usize, params: ParamsBuilder, seed: u64) -> SystemBuilder {
    chain_melt(chains, length, params, &MELT_BONDS, &MELT_ANGLES, 0.7, seed)
}

/// The standard box (gamma = 4.5, seed 3) with every particle at rest but the first, which
/// moves at `edges_per_time` times the shortest box edge per unit time, and a neighbour-list
/// skin of `skin_edges` times that edge: drifts of a known largest length for the blow-up
/// guard.
pub fn one_moving(edges_per_time: Vec3, skin_edges: f64) -> System {
    let base = standard_box(4.5, 0.01, 3);
    let mut p = vec![Vec3::zeros(); base.len()];
    let edge = base.boundary().min_length();
    p[0] = edges_per_time * edge;
    System::builder(
        base.params().clone(),
        *base.boundary(),
        base.positions().to_vec(),
    )
    .momenta(p)
    .skin(skin_edges * edge)
    .build()
    .unwrap()
}

/// Bitwise equality of two systems' positions and momenta, particle order included.
pub fn same_bits(a: &System, b: &System) -> bool {
    let bits = |s: &System| -> Vec<u64> {
        s.positions()
            .iter()
            .chain(s.momenta())
            .flat_map(|v| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>())
            .collect()
    };
    a.ids() == b.ids() && bits(a) == bits(b) && a.xi().to_bits() == b.xi().to_bits()
}

/// The blow-up `outcome` of an advance reports; panics on anything else.
pub fn blow_up(outcome: Result<(), AdvanceError>) -> BlowUp {
    match outcome {
        Err(AdvanceError::BlowUp(e)) => e,
        other => panic!("expected a blow-up, found {other:?}"),
    }
}

/// A step made of plain sub-flow calls, named for messages.
pub struct Steps(pub &'static str, pub fn(&mut System));

impl Scheme for Steps {
    fn name(&self) -> &str {
        self.0
    }
    fn step(&self, sys: &mut System) {
        (self.1)(sys)
    }
}

/// Each pairwise sub-flow (B, O, O-BBK, T, F) followed by a drift, each with step `dt`.
pub fn pairwise_flows() -> [Steps; 5] {
    [
        Steps("B", |s| {
            let h = s.dt();
            kick(s, h);
            drift(s, h)
        }),
        Steps("O", |s| {
            let h = s.dt();
            ou(s, h, 0, SweepOrder::Forward);
            drift(s, h)
        }),
        Steps("O-BBK", |s| {
            let h = s.dt();
            bbk(s, h, 0, SweepOrder::Reverse);
            drift(s, h)
        }),
        Steps("T", |s| {
            let h = s.dt();
            trotter(s, h, 0, SweepOrder::Forward);
            drift(s, h)
        }),
        Steps("F", |s| {
            let h = s.dt();
            full_force(s, h, 0);
            drift(s, h)
        }),
    ]
}

/// `f()` run on a pool of `threads` worker threads.
pub fn with_threads<R: Send>(threads: usize, f: impl FnOnce() -> R + Send) -> R {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(f)
}
