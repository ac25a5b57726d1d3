//! Shared set-up of the core's integration tests.
#![allow(dead_code)]

use dpd_core::bonded::{Angle, AngleStyle, Bond, BondStyle, Topology};
use dpd_core::flow::{bbk, drift, full_force, kick, ou, trotter};
use dpd_core::init::{equilibrium_box, maxwell_momenta};
use dpd_core::params::ParamsBuilder;
use dpd_core::{
    AdvanceError, BlowUp, Params, PeriodicBox, Scheme, SweepOrder, System, SystemBuilder, Vec3,
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
    a.ids() == b.ids() && bits(a) == bits(b)
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
