//! SETD and MSETD in non-equilibrium scenes: a body force drives the same Poiseuille flow as
//! the pairwise ABOBA, and the shear-viscosity path records their pair impulses.

use dpd_core::init::{cubic_box, freeze_outside, maxwell_momenta, uniform_positions};
use dpd_core::observe::{Profile, ShearViscosity, ViscositySummary};
use dpd_core::reference::Aboba;
use dpd_core::{Params, PeriodicBox, Scheme, System, Vec3, Walls};
use dpd_schemes::exponential::{Msetd, Setd};

/// A 5 x 5 x 10 box at density 3 with gamma = 450 and unit mass, walls at rest at z = 1 and
/// z = 9 (frozen slabs 1 thick), body force 0.5 per particle along x, dt = 0.01: the
/// relaxation rate is `c dt ~ 450 * 0.42 * 0.01 ~ 1.9`, where `phi1(c dt) ~ 0.45`.
fn channel(seed: u64) -> System {
    let bx = PeriodicBox::new([5.0, 5.0, 10.0]).unwrap();
    let walls = Walls::new(1.0, 9.0, [0.0, 0.0]).unwrap();
    let q = uniform_positions(&bx, 750, seed);
    let mut p = maxwell_momenta(&vec![1.0; q.len()], 1.0, seed);
    let frozen = freeze_outside(&walls, &q, &mut p);
    System::builder(Params::builder().gamma(450.0).build().unwrap(), bx, q)
        .momenta(p)
        .walls(walls)
        .frozen(frozen)
        .body_force(Vec3::new(0.5, 0.0, 0.0))
        .dt(0.01)
        .seed(seed)
        .build()
        .unwrap()
}

/// Mean x-velocity of the fluid over 20 time units after 12 from rest (several
/// momentum-diffusion times across the channel), sampled every 0.1.
fn mean_flow(scheme: &dyn Scheme) -> f64 {
    let mut sys = channel(3);
    sys.advance(scheme, 1200).unwrap();
    let mut profile = Profile::new(&sys, 2, 1).unwrap();
    for _ in 0..200 {
        sys.advance(scheme, 10).unwrap();
        profile.record(&sys);
    }
    profile.rows()[0].velocity[0]
}

/// The body force is balanced by the friction as in a pairwise scheme: the mean flow of SETD
/// and MSETD lies within 30 % of ABOBA's (converged in dt at gamma = 450, dt = 0.01). Measured:
/// SETD -22 %, MSETD -17 % (their own error at `c dt ~ 1.9`); the statistical error of a mean
/// flow of ~1.1 over 200 samples of ~600 particles is ~1 %. The body force applied as a
/// separate kick after the exponential update instead gave +33 %, outside the upper bound.
#[test]
fn body_force_drives_the_pairwise_poiseuille_flow() {
    let reference = mean_flow(&Aboba);
    assert!(reference > 0.5, "ABOBA mean flow {reference}");
    for scheme in [&Setd as &dyn Scheme, &Msetd] {
        let ratio = mean_flow(scheme) / reference;
        assert!(ratio > 0.7 && ratio < 1.1, "{}: {ratio}", scheme.name());
    }
}

/// The gamma = 450 box (N = 500, density 3) sheared at kappa = 0.5, dt = 0.005.
fn viscosity(scheme: &dyn Scheme) -> ViscositySummary {
    let params = Params::builder().gamma(450.0).build().unwrap();
    let bx = cubic_box(500, 3.0).unwrap();
    let mut sys = System::builder(params, bx, uniform_positions(&bx, 500, 4))
        .momenta(maxwell_momenta(&[1.0; 500], 1.0, 4))
        .shear_rate(0.5)
        .dt(0.005)
        .seed(4)
        .build()
        .unwrap();
    // 1 time unit to reach the steady shear, then 101 calls 0.05 apart (the first starts
    // recording): 100 samples over 5 time units.
    sys.advance(scheme, 200).unwrap();
    let mut eta = ShearViscosity::new(&sys).unwrap();
    eta.record(&mut sys);
    for _ in 0..100 {
        sys.advance(scheme, 10).unwrap();
        eta.record(&mut sys);
    }
    eta.summary().unwrap()
}

/// The viscosity path records the exponential update's pair impulses: both give a finite,
/// positive viscosity with a finite error bar under 15 % (ABOBA's is ~5 % here). MSETD agrees
/// with ABOBA within four combined standard errors (measured: 7.45 +- 0.35 vs 7.93 +- 0.36);
/// SETD does not (measured 23.9 +- 2.1 at `c dt ~ 0.95`), so only its finiteness is checked.
#[test]
fn shear_viscosity_is_recorded() {
    let reference = viscosity(&Aboba);
    let msetd = viscosity(&Msetd);
    for (name, s) in [("setd", viscosity(&Setd)), ("msetd", msetd)] {
        assert!(
            s.shear_viscosity.is_finite()
                && s.shear_viscosity > 0.0
                && s.shear_viscosity_error > 0.0
                && s.shear_viscosity_error < 0.15 * s.shear_viscosity,
            "{name}: {s:?}"
        );
    }
    let combined = msetd
        .shear_viscosity_error
        .hypot(reference.shear_viscosity_error);
    assert!(
        (msetd.shear_viscosity - reference.shear_viscosity).abs() < 4.0 * combined,
        "MSETD {msetd:?} vs ABOBA {reference:?}"
    );
}
