//! Bonded forces in dynamics: energy and momentum conservation, the stationary bond-length
//! distribution, the FENE guard and which schemes a bonded system accepts.

use super::common;

use common::{
    assert_energy_error_of_order_dt_squared, blow_up, bond_lengths, bond_quantities, chain_melt,
    integral, same_bits, Steps,
};
use dpd_core::bonded::{AngleStyle, BondStyle};
use dpd_core::observe::block_mean;
use dpd_core::{DynScheme, Params, System};

fn scheme(source: &str) -> DynScheme {
    DynScheme::compile(source, source, &Default::default()).unwrap()
}

const BONDS: [BondStyle; 2] = [
    BondStyle::Harmonic { k: 50.0, r0: 0.7 },
    BondStyle::Fene {
        k: 30.0,
        r_max: 1.5,
    },
];
const ANGLES: [AngleStyle; 2] = [
    AngleStyle::Cosine { k: 2.0 },
    AngleStyle::CosineSquared {
        k: 5.0,
        theta0: 2.5,
    },
];

/// 40 chains of 5 beads at density 3 (a = 25), harmonic and FENE bonds, both angle styles.
fn melt(gamma: f64, dt: f64) -> System {
    let params = Params::builder().gamma(gamma);
    chain_melt(40, 5, params, &BONDS, &ANGLES, 0.7, 11)
        .dt(dt)
        .build()
        .unwrap()
}

/// Velocity Verlet without friction conserves H = K + U (pairs, bonds, angles) up to an error
/// of order dt^2: halving dt divides the rms deviation over the same time by about 4 (measured
/// 4.17 for dt 0.01 -> 0.005, 4.40 for 0.02 -> 0.01; a wrong force, not the gradient of the
/// energy, leaves an error that does not shrink with dt).
#[test]
fn velocity_verlet_conserves_the_energy_of_a_bonded_melt_to_order_dt_squared() {
    assert_energy_error_of_order_dt_squared(melt(4.5, 0.01));
}

/// DPD's forces are pairwise and the bonded forces sum to zero: velocity Verlet with friction
/// and noise keeps the total momentum to rounding.
#[test]
fn a_bonded_melt_conserves_momentum() {
    let mut sys = melt(4.5, 0.01);
    let before = sys.total_momentum();
    let scale: f64 = sys.momenta().iter().map(|p| p.norm()).sum();
    sys.advance(&scheme("F(1/2) A F(1/2)"), 200).unwrap();
    let drift = (sys.total_momentum() - before).norm();
    assert!(drift < 1e-13 * scale, "{drift:e} of {scale}");
    assert!(sys.counters().bonded_force_evaluations >= 200);
}

/// Without pair repulsion (a = 0) but with DPD friction between all beads, trimers without an
/// angle potential have independent bond vectors, each with the Boltzmann density
/// `r^2 exp(-E(r) / k_B T)`. BAOAB (dt = 0.01, 100 time units, 200 trimers: a harmonic and a
/// FENE bond each) samples it: the mean of r, of r^2 and the fraction of bonds in each of 6
/// bins agree with the exact values within 4.5 block standard errors (plus 1e-9 for a bin
/// beyond FENE's reach, empty in both; 20 blocks of 5 time
/// units, far longer than a bond's relaxation time; BAOAB's configurational bias at this dt is
/// of order (omega dt)^2 / 100 ~ 1e-4 relative, below the errors). Forgetting LAMMPS's
/// missing 1/2 (force 2K) or the FENE denominator moves <r^2> by tens of standard errors.
#[test]
fn bond_lengths_follow_the_boltzmann_distribution() {
    let styles = [
        BondStyle::Harmonic { k: 4.0, r0: 0.5 },
        BondStyle::Fene {
            k: 20.0,
            r_max: 1.2,
        },
    ];
    let params = Params::builder().a(0.0);
    let mut sys = chain_melt(200, 3, params, &styles, &[], 0.5, 21)
        .dt(0.01)
        .build()
        .unwrap();
    let baoab = scheme("BAOAB");
    sys.advance(&baoab, 200).unwrap();
    let count = bond_quantities(0.0).len();
    // series[style][quantity]: one mean over the trimers per snapshot.
    let mut series = vec![vec![Vec::new(); count]; 2];
    for _ in 0..1000 {
        sys.advance(&baoab, 10).unwrap();
        let mut sums = vec![vec![0.0; count]; 2];
        for (kind, r) in bond_lengths(&sys) {
            for (s, x) in sums[kind as usize].iter_mut().zip(bond_quantities(r)) {
                *s += x / 200.0;
            }
        }
        for (style, sums) in sums.into_iter().enumerate() {
            for (q, s) in sums.into_iter().enumerate() {
                series[style][q].push(s);
            }
        }
    }
    for (bond, series) in styles.iter().zip(&series) {
        let end = match bond {
            BondStyle::Fene { r_max, .. } => *r_max * (1.0 - 1e-12),
            _ => 4.0,
        };
        let density = |r: f64| r * r * (-bond.energy(r)).exp();
        let norm = integral(end, density);
        for (q, samples) in series.iter().enumerate() {
            let exact = integral(end, |r| bond_quantities(r)[q] * density(r)) / norm;
            let (mean, error) = block_mean(samples, 20).unwrap();
            assert!(
                (mean - exact).abs() < 4.5 * error + 1e-9,
                "{bond:?}, quantity {q}: {mean} +- {error}, exact {exact}"
            );
        }
    }
}

/// A FENE bond pulled to its R0 within a step: the step is undone and the error names the bond
/// and both particles.
#[test]
fn a_fene_bond_reaching_its_reach_is_a_blow_up_naming_it() {
    let fene = [BondStyle::Fene {
        k: 30.0,
        r_max: 1.5,
    }];
    let build = |step| chain_melt(100, 2, Params::builder(), &fene, &[], step, 5).dt(0.01);
    let mut sys = build(1.0).build().unwrap();
    // Storage order is id order until the first neighbour-list build.
    let e = sys
        .boundary()
        .min_image(sys.positions()[0] - sys.positions()[1])
        .normalize();
    let mut p = sys.momenta().to_vec();
    p[0] += 100.0 * e;
    p[1] -= 100.0 * e;
    sys.momenta_mut().copy_from_slice(&p);
    let before = sys.clone();
    let error = blow_up(sys.advance(&scheme("ABOBA"), 5));
    assert_eq!(error.step, 0);
    assert!(
        error.reason.contains("bond 0 between particles 0 and 1")
            && error
                .reason
                .ends_with("of its style fene (K = 30, R0 = 1.5)"),
        "{}",
        error.reason
    );
    assert!(common::same_bits(&before, &sys));
    // Starting beyond R0 is refused.
    let error = build(1.6).build().unwrap_err().to_string();
    assert!(
        error.starts_with("invalid bonds[0] = ids 0, 1 at distance 1.6"),
        "{error}"
    );
}

/// A bonded system runs schemes that apply the bonded forces (B, F, B[bond]) and refuses one
/// that never does; r-RESPA with four inner steps evaluates the bonded forces four times a step.
#[test]
fn a_bonded_system_needs_a_scheme_that_applies_the_bonds() {
    let mut sys = melt(4.5, 0.01);
    let refused = sys.advance(&scheme("B[pair] A B[pair] O"), 1).unwrap_err();
    assert!(
        refused
            .to_string()
            .contains("never applies the bonded forces"),
        "{refused}"
    );
    let respa = scheme("B[pair](1/2) (B[bond](1/8) A(1/4) B[bond](1/8))^4 O B[pair](1/2)");
    sys.advance(&respa, 1).unwrap();
    let before = sys.counters();
    sys.advance(&respa, 10).unwrap();
    let per_step = (sys.counters().bonded_force_evaluations - before.bonded_force_evaluations) / 10;
    assert_eq!(per_step, 4);
    let program = dpd_core::Scheme::program(&respa).unwrap();
    assert_eq!(program.bonded_force_evaluations_per_step(), 4);
}

/// The MTS step's `O B[pair]`: its sweep fills the pair table while summing the conservative
/// forces that the B[pair] after it applies (`System::advance` sees that in the program). The
/// trajectory is bitwise that of the same stages run by a hand-written step, which has no
/// program, so that its sweep fills the table alone and the B[pair] passes over it; both make
/// one pair evaluation per step. Fails if the forces summed while filling, or the table they
/// leave, differ in any bit.
#[test]
fn a_sweep_filling_the_pair_forces_for_the_kick_after_it_changes_no_bit() {
    use dpd_core::flow::{drift, kick_group, ou};
    use dpd_core::{Flow, Scheme};
    const MTS: &str = "B[pair](1/2) (B[bond](1/8) A(1/4) B[bond](1/8))^4 O B[pair](1/2)";
    fn by_stages(sys: &mut System) {
        for stage in &scheme(MTS).program().unwrap().stages {
            let h = stage.coeff.value * sys.dt();
            match (stage.flow, stage.group) {
                (Flow::A, _) => drift(sys, h),
                (Flow::B, Some(group)) => kick_group(sys, h, group),
                (Flow::O, _) => ou(sys, h, stage.stream, stage.order),
                other => panic!("no {other:?} in {MTS}"),
            }
        }
    }
    let mut fused = melt(4.5, 0.02);
    let mut plain = fused.clone();
    fused.advance(&scheme(MTS), 30).unwrap();
    plain
        .advance(&Steps("MTS by stages", by_stages), 30)
        .unwrap();
    assert!(same_bits(&fused, &plain));
    assert_eq!(fused.counters(), plain.counters());
    assert_eq!(fused.counters().pair_distance_evaluations, 31);
}
