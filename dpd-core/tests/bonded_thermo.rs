//! Thermodynamic observables with bonded terms: the configurational temperature of exactly
//! sampled molecules and the virial pressure against the volume derivative of the energy.

use super::common;

use dpd_core::bonded::{Angle, AngleStyle, Bond, BondStyle, Topology};
use dpd_core::observe::{block_ratio_error, potential_energy, thermo};
use dpd_core::{Params, PeriodicBox, System, Vec3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::TAU;

/// Draws from the density `f` on `[lo, hi]` by inverting its cumulative sum on 100 000 cells
/// (linear within a cell: a bias of order the cell width squared, ~1e-10 here).
fn sampler(lo: f64, hi: f64, f: impl Fn(f64) -> f64) -> impl Fn(f64) -> f64 {
    let n = 100_000;
    let h = (hi - lo) / n as f64;
    let mut cdf = vec![0.0];
    for k in 0..n {
        let (a, b) = (lo + k as f64 * h, lo + (k + 1) as f64 * h);
        cdf.push(cdf[k] + 0.5 * (f(a) + f(b)) * h);
    }
    let total = cdf[n];
    move |u: f64| {
        let target = u * total;
        let k = cdf.partition_point(|&c| c < target).clamp(1, n);
        let (c0, c1) = (cdf[k - 1], cdf[k]);
        lo + ((k - 1) as f64 + (target - c0) / (c1 - c0)) * h
    }
}

/// A unit vector at angle `acos(c)` from the unit vector `e`, azimuth `phi`.
fn at_angle(e: Vec3, c: f64, phi: f64) -> Vec3 {
    let helper = if e.x.abs() < 0.9 {
        Vec3::x()
    } else {
        Vec3::y()
    };
    let u = e.cross(&helper).normalize();
    let v = e.cross(&u);
    let s = (1.0 - c * c).max(0.0).sqrt();
    c * e + s * (phi.cos() * u + phi.sin() * v)
}

/// Without pair repulsion, molecules can be drawn exactly from the Boltzmann density:
/// trimers `i - j - k` (harmonic bonds K = 20, r0 = 0.8 and K = 10, r0 = 1, a cosine/squared
/// angle at j) with the two bond lengths from `r^2 exp(-E(r))`, the cosine of the angle from
/// `exp(-E(c))` on [-1, 1] about the first bond and the azimuth uniform; FENE dimers (K = 20,
/// R0 = 1.2) with the length from `r^2 exp(-E(r))`. On 100 such configurations of 1000 of
/// each, k_B T_C = sum |grad U|^2 / sum lap U with the bonded gradients and Laplacians is 1
/// within 4 standard errors (from 20 blocks' ratios; the configurations are independent, so
/// the blocks are too). The angle's terms grow as 1 / r^2 for short arms, an estimator of
/// infinite variance if arms could be short: the stiff bonds with r0 > 0 keep them away from 0.
#[test]
fn configurational_temperature_of_exactly_sampled_molecules_is_one() {
    let first = BondStyle::Harmonic { k: 20.0, r0: 0.8 };
    let second = BondStyle::Harmonic { k: 10.0, r0: 1.0 };
    let fene = BondStyle::Fene {
        k: 20.0,
        r_max: 1.2,
    };
    let angle = AngleStyle::CosineSquared {
        k: 3.0,
        theta0: 2.0,
    };
    let length =
        |style: BondStyle, end: f64| sampler(0.0, end, move |r| r * r * (-style.energy(r)).exp());
    let (first_length, second_length) = (length(first, 4.0), length(second, 4.0));
    let fene_length = length(fene, 1.2 * (1.0 - 1e-12));
    let cosine = sampler(-1.0, 1.0, |c| (-angle.energy(c)).exp());
    let molecules = 1000;
    let n = 5 * molecules;
    let bx = PeriodicBox::cubic((n as f64 / 3.0).cbrt()).unwrap();
    let mut t = Topology::builder(n);
    t.bond_types = vec![first, second, fene];
    t.angle_types = vec![angle];
    for m in 0..molecules as u32 {
        let (i, j, k) = (5 * m, 5 * m + 1, 5 * m + 2);
        t.bonds.push(Bond { i, j, kind: 0 });
        t.bonds.push(Bond {
            i: j,
            j: k,
            kind: 1,
        });
        t.angles.push(Angle { i, j, k, kind: 0 });
        t.bonds.push(Bond {
            i: 5 * m + 3,
            j: 5 * m + 4,
            kind: 2,
        });
    }
    let topology = t.build().unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(17);
    let direction = |rng: &mut ChaCha8Rng| {
        at_angle(
            Vec3::z(),
            2.0 * rng.random::<f64>() - 1.0,
            TAU * rng.random::<f64>(),
        )
    };
    let (mut numerators, mut denominators) = (Vec::new(), Vec::new());
    for _ in 0..100 {
        let mut q = Vec::with_capacity(n);
        for _ in 0..molecules {
            let mut uniform = || {
                bx.lengths()
                    .component_mul(&Vec3::new(rng.random(), rng.random(), rng.random()))
            };
            let (vertex, end) = (uniform(), uniform());
            let e = direction(&mut rng);
            let a = first_length(rng.random()) * e;
            let b = second_length(rng.random())
                * at_angle(e, cosine(rng.random()), TAU * rng.random::<f64>());
            let d = fene_length(rng.random()) * direction(&mut rng);
            q.extend([vertex + a, vertex, vertex + b, end, end + d]);
        }
        let mut sys = System::builder(Params::builder().a(0.0).build().unwrap(), bx, q)
            .topology(topology.clone())
            .build()
            .unwrap();
        let t = thermo(&mut sys);
        numerators.push(t.config_numerator);
        denominators.push(t.config_denominator);
    }
    let tc = numerators.iter().sum::<f64>() / denominators.iter().sum::<f64>();
    let error = block_ratio_error(&numerators, &denominators, 20).unwrap();
    eprintln!("k_B T_C = {tc} +- {error}");
    assert!((tc - 1.0).abs() < 4.0 * error, "k_B T_C = {tc} +- {error}");
}

/// The configurational part of the virial pressure is `-dU/dV`: with every length scaled by
/// `1 + e` (box and positions, so bond vectors scale too), `P - N k_B T_K / V = -(dU/de) / (3
/// V)`, by central differences with step 1e-6, to 1e-6 relative, on a melt of chains (a = 25,
/// harmonic and FENE bonds, both angle styles) after 50 steps.
#[test]
fn virial_pressure_is_the_volume_derivative_of_the_energy() {
    let mut sys = common::melt(60, 5, Params::builder(), 4)
        .dt(0.01)
        .build()
        .unwrap();
    let aboba = dpd_core::DynScheme::compile("ABOBA", "ABOBA", &Default::default()).unwrap();
    sys.advance(&aboba, 50).unwrap();
    let t = thermo(&mut sys);
    let volume = sys.boundary().volume();
    let configurational = t.pressure - sys.len() as f64 * t.kinetic_temperature / volume;
    let scaled = |s: f64| {
        let f = 1.0 + s * 1e-6;
        let bx = PeriodicBox::new((f * sys.boundary().lengths()).into()).unwrap();
        let q = sys.positions().iter().map(|x| f * x).collect();
        let mut scaled = System::builder(sys.params().clone(), bx, q)
            .ids(sys.ids().to_vec())
            .topology(sys.topology().unwrap().clone())
            .build()
            .unwrap();
        potential_energy(&mut scaled)
    };
    let derivative = -(scaled(1.0) - scaled(-1.0)) / (2e-6 * 3.0 * volume);
    assert!(
        (derivative - configurational).abs() < 1e-6 * configurational.abs(),
        "{derivative} vs {configurational}"
    );
}
